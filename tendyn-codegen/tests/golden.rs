//! The generated code of the paper's examples, and of Example 2 with friction, is kept in
//! `golden/` (the benchmark compiles the former). Generation must reproduce it byte for byte, so any change to what is emitted shows
//! up in review. After an intended change: `TENDYN_BLESS=1 cargo test -p tendyn-codegen --test golden`.

//!
//! The benchmark of the tension distribution compiles `golden/distribution/`: `actuation`
//! of the mechanisms in `benches/distribution/` (and for two of them with its
//! derivatives), kept the same way; the benchmark of the
//! derivatives compiles `golden/derivatives/`: Examples 1 and 3 with `generalized_forces`,
//! `forward_dynamics` and their derivatives.

use tendyn_codegen::{available_outputs, generate, Output, Scalar};

#[test]
fn generated_paper_examples_match_the_golden_files() {
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        example_matches_its_golden_file(name);
    }
}

/// Example 2 with bearing friction and with capstan friction on its guides, kept the same
/// way: what friction adds to the emitted code shows in review, and the `no_std` check
/// (`tests/no-std`) compiles these too.
#[test]
fn generated_friction_examples_match_the_golden_files() {
    for name in ["example2_friction", "example2_capstan"] {
        example_matches_its_golden_file(name);
    }
}

/// `examples/mechanisms/NAME.ron` with every output it provides against `golden/NAME.rs`.
fn example_matches_its_golden_file(name: &str) {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let model = tendyn_core::load(format!("{root}/examples/mechanisms/{name}.ron")).unwrap();
    let outputs = available_outputs(&model);
    compare(
        name,
        &model,
        &outputs,
        &format!("{root}/tendyn-codegen/golden/{name}.rs"),
    );
}

#[test]
fn generated_distribution_benchmarks_match_their_golden_files() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"));
    for name in ["example3_bounded", "bounded_1x3", "bounded_3x6"] {
        let model = tendyn_core::load(format!("{root}/benches/distribution/{name}.ron")).unwrap();
        let path = format!("{root}/golden/distribution/{name}.rs");
        compare(name, &model, &[Output::Actuation], &path);
    }
    // With its derivatives over two and three null directions (`benches/distribution.rs`).
    for name in ["bounded_1x3", "bounded_3x6"] {
        let model = tendyn_core::load(format!("{root}/benches/distribution/{name}.ron")).unwrap();
        let path = format!("{root}/golden/distribution/{name}_derivatives.rs");
        let outputs = [Output::Actuation, Output::ActuationDerivatives];
        compare(name, &model, &outputs, &path);
    }
}

#[test]
fn generated_derivatives_match_their_golden_files() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for name in ["example1_endless", "example3_stanford_jpl"] {
        let model = tendyn_core::load(format!("{root}/examples/mechanisms/{name}.ron")).unwrap();
        let outputs = [
            Output::GeneralizedForces,
            Output::GeneralizedForcesDerivatives,
            Output::ForwardDynamics,
            Output::ForwardDynamicsDerivatives,
        ];
        let path = format!("{root}/tendyn-codegen/golden/derivatives/{name}.rs");
        compare(name, &model, &outputs, &path);
    }
}

fn compare(name: &str, model: &tendyn_core::Model<f64>, outputs: &[Output], path: &str) {
    {
        let source = generate(model, outputs, Scalar::Generic, &format!("{name}.ron"))
            .unwrap()
            .source();
        if std::env::var("TENDYN_BLESS").as_deref() == Ok("1") {
            std::fs::write(path, &source).unwrap();
            return;
        }
        let golden = std::fs::read_to_string(path).unwrap();
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
