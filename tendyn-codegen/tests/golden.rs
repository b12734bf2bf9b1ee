//! The generated code of the paper's examples is kept in `golden/` (the benchmark compiles
//! it). Generation must reproduce it byte for byte, so any change to what is emitted shows
//! up in review. After an intended change: `TENDYN_BLESS=1 cargo test -p tendyn-codegen --test golden`.

use tendyn_codegen::{available_outputs, generate, Scalar};

#[test]
fn generated_paper_examples_match_the_golden_files() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        let model = tendyn_core::load(format!("{root}/examples/mechanisms/{name}.ron")).unwrap();
        let source = generate(
            &model,
            &available_outputs(&model),
            Scalar::Generic,
            &format!("{name}.ron"),
        )
        .unwrap()
        .source;
        let path = format!("{root}/tendyn-codegen/golden/{name}.rs");
        if std::env::var("TENDYN_BLESS").as_deref() == Ok("1") {
            std::fs::write(&path, &source).unwrap();
            continue;
        }
        let golden = std::fs::read_to_string(&path).unwrap();
        if golden != source {
            let line = golden
                .lines()
                .zip(source.lines())
                .position(|(a, b)| a != b)
                .unwrap_or(0);
            panic!(
                "{name}: generated code differs from {path} from line {} on:\n  golden: {:?}\n  now:    {:?}\n\
                 If the change is intended, run TENDYN_BLESS=1 cargo test -p tendyn-codegen --test golden",
                line + 1,
                golden.lines().nth(line),
                source.lines().nth(line)
            );
        }
    }
}
