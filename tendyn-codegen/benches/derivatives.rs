//! The derivatives against the function alone, with the protocol of `benches/dynamics.rs`
//! (1,024 seeded random states; the figure is time per call): generated `Q` and generated
//! `(Q, ∂Q/∂q, ∂Q/∂q̇)` (`generalized_forces_derivatives`), generated `q̈` and
//! `(q̈, ∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂u)`, on Examples 1 and 3 (`golden/derivatives/`), and the
//! runtime solver's dual-number derivatives (`Data::generalized_forces_derivatives`) on
//! Example 3 and the scale benchmarks' finger and arm.
//!
//! `cargo bench -p tendyn-codegen --bench derivatives` (pin with `taskset -c 0` and build
//! with `RUSTFLAGS="-C target-cpu=native"` for the protocol's conditions).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

#[allow(dead_code)]
mod ex1 {
    include!("../golden/derivatives/example1_endless.rs");
}
#[allow(dead_code)]
mod ex3 {
    include!("../golden/derivatives/example3_stanford_jpl.rs");
}

#[path = "common/states.rs"]
mod states;
use states::{states, STATES};

macro_rules! bench_generated {
    ($c:expr, $name:literal, $module:ident, $n:literal, $motors:literal, $tendons:literal) => {{
        let data = states::<$n>(7, 3.0, 10.0);
        let mut group = $c.benchmark_group(concat!($name, " generated"));
        group.throughput(Throughput::Elements(STATES as u64));
        group.bench_function("Q", |b| {
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
        group.bench_function("Q, dQ/dq, dQ/dqd", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($module::generalized_forces_derivatives::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
        let motors: [f64; $motors] = std::array::from_fn(|k| 0.5 + k as f64);
        let tendons: [f64; $tendons] = std::array::from_fn(|k| 10.0 + k as f64);
        group.bench_function("qdd", |b| {
            b.iter(|| {
                for (q, qd, _) in &data {
                    black_box($module::forward_dynamics::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(&motors),
                        black_box(&tendons),
                    ));
                }
            })
        });
        group.bench_function("qdd, dqdd/dq, dqdd/dqd, dqdd/du", |b| {
            b.iter(|| {
                for (q, qd, _) in &data {
                    black_box($module::forward_dynamics_derivatives::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(&motors),
                        black_box(&tendons),
                    ));
                }
            })
        });
        group.finish();
    }};
}

/// The runtime solver's `Q` and its derivatives on a mechanism file.
fn bench_runtime(c: &mut Criterion, name: &str, path: &str) {
    let model = tendyn_core::load(format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let n = model.dof();
    let data: Vec<[Vec<f64>; 3]> = states::<12>(7, 3.0, 10.0)
        .into_iter()
        .map(|(q, qd, qdd)| [q[..n].to_vec(), qd[..n].to_vec(), qdd[..n].to_vec()])
        .collect();
    let mut group = c.benchmark_group(format!("{name} runtime"));
    group.throughput(Throughput::Elements(STATES as u64));
    let mut s = tendyn_core::Data::new(&model);
    group.bench_function("Q", |b| {
        b.iter(|| {
            for [q, qd, qdd] in &data {
                black_box(s.generalized_forces(&model, q, qd, qdd).unwrap());
            }
        })
    });
    group.bench_function("Q, dQ/dq, dQ/dqd", |b| {
        b.iter(|| {
            for [q, qd, qdd] in &data {
                black_box(
                    s.generalized_forces_derivatives(&model, q, qd, qdd)
                        .unwrap(),
                );
            }
        })
    });
    group.finish();
}

fn derivatives(c: &mut Criterion) {
    bench_generated!(c, "example1_endless", ex1, 2, 2, 0);
    bench_generated!(c, "example3_stanford_jpl", ex3, 3, 0, 4);
    bench_runtime(
        c,
        "example3_stanford_jpl",
        "examples/mechanisms/example3_stanford_jpl.ron",
    );
    bench_runtime(c, "finger4", "bench/mechanisms/finger4.ron");
    bench_runtime(c, "arm6", "bench/mechanisms/arm6.ron");
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(31).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = derivatives
}
criterion_main!(benches);
