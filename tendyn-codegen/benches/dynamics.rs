//! Generated code against the runtime solver on the paper's three examples, with the
//! protocol of `docs/references.md`: 1,024 seeded random states (q in [-π, π],
//! q̇ in [-3, 3], q̈ in [-10, 10]); one sample is a pass over all states, and the figure is
//! time per call (criterion's time per iteration divided by 1,024).
//!
//! `cargo bench -p tendyn-codegen` (pin with `taskset -c 0` and build with
//! `RUSTFLAGS="-C target-cpu=native"` for the protocol's conditions).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use std::hint::black_box;

#[allow(dead_code)]
mod ex1 {
    include!("../golden/example1_endless.rs");
}
#[allow(dead_code)]
mod ex2 {
    include!("../golden/example2_open_ended.rs");
}
#[allow(dead_code)]
mod ex3 {
    include!("../golden/example3_stanford_jpl.rs");
}

#[path = "common/states.rs"]
mod states;
use states::{states, STATES};

macro_rules! bench_example {
    ($c:expr, $name:literal, $module:ident, $n:literal) => {{
        let model = tendyn_core::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/mechanisms/",
            $name,
            ".ron"
        ))
        .unwrap();
        let data = states::<$n>(7, 3.0, 10.0);
        let mut group = $c.benchmark_group($name);
        group.throughput(Throughput::Elements(STATES as u64));
        group.bench_function("generated Q (f64)", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($module::generalized_forces::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
        group.bench_function("generated actuation (f64)", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($module::actuation::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
        group.bench_function("generated Q (f32)", |b| {
            let data32: Vec<([f32; $n], [f32; $n], [f32; $n])> = data
                .iter()
                .map(|(a, b, c)| {
                    (
                        a.map(|x| x as f32),
                        b.map(|x| x as f32),
                        c.map(|x| x as f32),
                    )
                })
                .collect();
            b.iter(|| {
                for (q, qd, qdd) in &data32 {
                    black_box($module::generalized_forces::<f32>(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
        group.bench_function("runtime Q (f64)", |b| {
            let mut s = tendyn_core::Data::new(&model);
            b.iter_batched_ref(
                || (),
                |_| {
                    for (q, qd, qdd) in &data {
                        black_box(
                            s.generalized_forces(
                                &model,
                                black_box(q),
                                black_box(qd),
                                black_box(qdd),
                            )
                            .unwrap(),
                        );
                    }
                },
                BatchSize::SmallInput,
            )
        });
        group.bench_function("runtime inverse dynamics (f64)", |b| {
            let mut s = tendyn_core::Data::new(&model);
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box(
                        s.inverse_dynamics(&model, black_box(q), black_box(qd), black_box(qdd))
                            .unwrap(),
                    );
                }
            })
        });
        group.finish();
    }};
}

fn paper_examples(c: &mut Criterion) {
    bench_example!(c, "example1_endless", ex1, 2);
    bench_example!(c, "example2_open_ended", ex2, 2);
    bench_example!(c, "example3_stanford_jpl", ex3, 3);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(51).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = paper_examples
}
criterion_main!(benches);
