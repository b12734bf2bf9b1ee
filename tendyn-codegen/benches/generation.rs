//! How long generation takes (issue 4: under 10 ms for each paper example, well under a
//! second for a 7-link chain with a dozen pulleys; issue 16: under 100 ms for a 12-link
//! chain with 30 pulleys), every available output, generic scalar.
//!
//! Per mechanism: loading and validation, then `generate` as a whole (which builds the
//! syntax tree but does not print it), then its phases: `outputs::trace` (tracing and the
//! closed forms), `emit::emit_file` (the syntax tree: all the derive needs) and `emit::emit`
//! (the tree printed by prettyplease: what the command line and build scripts write), so
//! that a regression points at its phase.
//!
//! And how long validation takes with capstan friction on many guides
//! ([`capstan_validation`]).
//!
//! `cargo bench -p tendyn-codegen --bench generation` (the CLI's `generate` also prints the
//! time of one run; `-- capstan` for validation alone).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tendyn_codegen::{available_outputs, emit, generate, outputs, Scalar};

/// The paper's examples, a 7-link spatial chain whose four parallel proximal joints are
/// driven by five tendons over 14 drums and idlers (`benches/chain7.ron`), and the 12-link
/// chain with 30 pulleys of the scale benchmarks (`bench/mechanisms/chain12.ron`).
const MECHANISMS: [&str; 5] = [
    "/../examples/mechanisms/example1_endless.ron",
    "/../examples/mechanisms/example2_open_ended.ron",
    "/../examples/mechanisms/example3_stanford_jpl.ron",
    "/benches/chain7.ron",
    "/../bench/mechanisms/chain12.ron",
];

fn generation(c: &mut Criterion) {
    for file in MECHANISMS {
        let path = format!("{}{file}", env!("CARGO_MANIFEST_DIR"));
        let model = tendyn_core::load(&path).unwrap();
        let all = available_outputs(&model);
        let core: syn::Path = syn::parse_quote!(tendyn_core);
        let mut group = c.benchmark_group(model.name());
        group.bench_function("load and validate", |b| {
            b.iter(|| tendyn_core::load(black_box(&path)).unwrap())
        });
        group.bench_function("generate (all outputs)", |b| {
            b.iter(|| generate(black_box(&model), &all, Scalar::Generic, "bench.ron").unwrap())
        });
        group.bench_function("trace and collect", |b| {
            b.iter(|| outputs::trace(black_box(&model), &all).unwrap())
        });
        let traced = outputs::trace(&model, &all).unwrap();
        group.bench_function("emit tree", |b| {
            b.iter(|| emit::emit_file(&model, black_box(&traced), Scalar::Generic, &core))
        });
        group.bench_function("emit", |b| {
            b.iter(|| {
                emit::emit(
                    &model,
                    black_box(&traced),
                    Scalar::Generic,
                    "bench.ron",
                    &core,
                )
            })
        });
        group.finish();
    }
}

/// Validation of fingers whose every idler is a guide with capstan friction, past the
/// 26,244 directions of sliding validation takes one by one (docs/format.md §6a): shown at
/// every factor on one box or a few (6 joints at `μ = 0.2`), by the slack-tendon programs
/// (12 joints at `μ = 1`, one null direction; 9 joints with a second tendon on every other
/// link at `μ = 1`, 6 null directions, with cutting planes), by `E`'s signs (10 joints
/// with a second tendon on each link at `μ = 2`, 11 null directions), and the worst case,
/// where neither they nor 4096 boxes settle it and validation falls back to the patterns
/// where every guide slides, from which a descent finds one that leaves a tendon nearly
/// slack and refuses the routing (10 joints at `μ = 2`).
fn capstan_validation(c: &mut Criterion) {
    let mut group = c.benchmark_group("capstan validation");
    // (joints, a second tendon on every how many links (0: none), μ)
    for (joints, every, mu) in [
        (6, 0, 0.2),
        (12, 0, 1.0),
        (9, 2, 1.0),
        (10, 1, 2.0),
        (10, 0, 2.0),
    ] {
        let mut finger = tendyn_spec::stress::Arm::new("finger", joints, joints);
        finger.antagonists = every > 0;
        finger.antagonist_every = every;
        let text = tendyn_spec::guides::idlers_as_capstans(&finger.ron(), mu);
        let check = match tendyn_core::parse(&text) {
            Ok(model) => format!("{:?}", model.sliding_check()),
            Err(_) => "refused".into(),
        };
        let name = format!(
            "{joints} joints{} mu {mu}: {check}",
            match every {
                0 => "",
                1 => " antagonistic",
                _ => " half antagonistic",
            }
        );
        group.bench_function(name, |b| b.iter(|| tendyn_core::parse(black_box(&text))));
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(3));
    targets = generation, capstan_validation
}
criterion_main!(benches);
