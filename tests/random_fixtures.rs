//! The seeded random mechanisms that tests in other languages read
//! (`tests/mechanisms/random/`: the Python package's MuJoCo check): each file is exactly
//! what `tendyn_spec::random_mechanism::valid_random_mechanism` draws for its seed and
//! features, so the files stay the generator's. After a change to the generator,
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
    let write = std::env::var_os("TENDYN_WRITE_FIXTURES").is_some();
    for (stem, seed, features) in FIXTURES {
        let (text, _) = valid_random_mechanism(seed, features);
        let path = dir.join(format!("{stem}.ron"));
        if write {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        let stored =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(
            stored,
            text,
            "{} is not what seed {seed} draws: rewrite it (TENDYN_WRITE_FIXTURES=1)",
            path.display()
        );
    }
}
