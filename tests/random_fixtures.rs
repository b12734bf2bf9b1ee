//! The seeded random mechanisms that tests in other languages read
//! (`tests/mechanisms/random/`: the Python package's MuJoCo check): each file is
//! what `tendyn_spec::random_mechanism::valid_random_mechanism` draws for its seed and
//! features (up to the last bits of its numbers, which a platform's `sin` and `cos` may
//! round differently), so the files stay the generator's. After a change to the generator,
//! `TENDYN_WRITE_FIXTURES=1 cargo test -p tendyn-spec --test random_fixtures` rewrites them.

use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

/// (file stem, seed, features): pulleys with explicit couplings (tilted, off-axis), with
/// and without an endless loop, and plain open-ended routing.
const FIXTURES: [(&str, u64, Features); 3] = [
    (
        "random_1_coupled",
        1,
        Features {
            coupled_pulleys: true,
            endless: false,
        },
    ),
    (
        "random_2_coupled_endless",
        2,
        Features {
            coupled_pulleys: true,
            endless: true,
        },
    ),
    (
        "random_3",
        3,
        Features {
            coupled_pulleys: false,
            endless: false,
        },
    ),
];

#[test]
fn the_random_mechanism_files_are_what_the_generator_draws_for_their_seeds() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("mechanisms/random");
    let write = std::env::var("TENDYN_WRITE_FIXTURES").is_ok_and(|v| v == "1");
    for (stem, seed, features) in FIXTURES {
        let (text, _) = valid_random_mechanism(seed, features);
        let path = dir.join(format!("{stem}.ron"));
        if write {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        let stored =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            same_up_to_rounding(&stored, &text),
            "{} is not what seed {seed} draws: rewrite it (TENDYN_WRITE_FIXTURES=1)",
            path.display()
        );
    }
    // No file that no seed draws any more.
    let mut stored: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    stored.sort();
    let mut expected: Vec<String> = FIXTURES.iter().map(|f| format!("{}.ron", f.0)).collect();
    expected.sort();
    assert_eq!(stored, expected);
}

/// Whether two texts are the same but for their numbers' last few bits: the generator
/// calls `sin` and `cos`, whose last bit may differ between platforms' maths libraries.
fn same_up_to_rounding(a: &str, b: &str) -> bool {
    let is_number = |c: char| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+');
    let tokens = |s: &str| -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mut last = None;
        for c in s.chars() {
            let kind = is_number(c);
            if last != Some(kind) {
                out.push(String::new());
                last = Some(kind);
            }
            out.last_mut().unwrap().push(c);
        }
        out
    };
    let (a, b) = (tokens(a), tokens(b));
    a.len() == b.len()
        && a.iter()
            .zip(&b)
            .all(|(x, y)| match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => (x - y).abs() <= 1e-13 * x.abs().max(y.abs()),
                _ => x == y,
            })
}
