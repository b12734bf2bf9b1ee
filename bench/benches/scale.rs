//! Generated code against the runtime solver beyond three joints (issue 16): a planar
//! finger (4 joints, 14 pulleys), a random spatial arm (6 joints, 8 pulleys), chains of 8
//! and 12 links (20 and 30 pulleys). The protocol of `docs/references.md`: 1,024 seeded
//! random states (q in [-π, π], q̇ in [-3, 3], q̈ in [-10, 10]); one sample is a pass over
//! all states, and the figure is time per call (criterion's time per iteration / 1,024).
//! Forward dynamics is fed the torques and tensions inverse dynamics gives at each state.
//!
//! `RUSTFLAGS="-C target-cpu=native" taskset -c 0 cargo bench -p tendyn-bench`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use tendyn_core::{Data, Model};

#[path = "../../tendyn-codegen/benches/common/states.rs"]
mod states;
use states::{states, STATES};

#[allow(dead_code)]
mod finger4 {
    tendyn_core::include_mechanism!("finger4");
}
#[allow(dead_code)]
mod arm6 {
    tendyn_core::include_mechanism!("arm6");
}
#[allow(dead_code)]
mod chain8 {
    tendyn_core::include_mechanism!("chain8");
}
#[allow(dead_code)]
mod chain12 {
    tendyn_core::include_mechanism!("chain12");
}

macro_rules! bench_mechanism {
    ($c:expr, $m:ident, $n:literal, $motors:literal, $tendons:literal) => {{
        let model: Model<f64> = tendyn_core::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/mechanisms/",
            stringify!($m),
            ".ron"
        ))
        .unwrap();
        let data = states::<$n>(7, 3.0, 10.0);
        let mut solver = Data::new(&model);
        let drive: Vec<([f64; $motors], [f64; $tendons])> = data
            .iter()
            .map(|(q, qd, qdd)| {
                let r = solver.inverse_dynamics(&model, q, qd, qdd).unwrap();
                (
                    r.motor_torques.clone().try_into().unwrap(),
                    r.tendon_tensions.clone().try_into().unwrap(),
                )
            })
            .collect();
        let mut group = $c.benchmark_group(stringify!($m));
        group.throughput(Throughput::Elements(STATES as u64));
        group.bench_function("generated Q", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($m::generalized_forces(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
        group.bench_function("generated M", |b| {
            b.iter(|| {
                for (q, _, _) in &data {
                    black_box($m::mass_matrix(black_box(q)));
                }
            })
        });
        group.bench_function("generated forward dynamics", |b| {
            b.iter(|| {
                for ((q, qd, _), (mt, tt)) in data.iter().zip(&drive) {
                    black_box($m::forward_dynamics(
                        black_box(q),
                        black_box(qd),
                        black_box(mt),
                        black_box(tt),
                    ));
                }
            })
        });
        group.bench_function("generated actuation", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($m::actuation(black_box(q), black_box(qd), black_box(qdd)));
                }
            })
        });
        group.bench_function("runtime Q", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box(
                        solver
                            .generalized_forces(&model, black_box(q), black_box(qd), black_box(qdd))
                            .unwrap(),
                    );
                }
            })
        });
        group.bench_function("runtime M", |b| {
            b.iter(|| {
                for (q, _, _) in &data {
                    black_box(solver.mass_matrix(&model, black_box(q)).unwrap());
                }
            })
        });
        group.bench_function("runtime forward dynamics", |b| {
            b.iter(|| {
                for ((q, qd, _), (mt, tt)) in data.iter().zip(&drive) {
                    black_box(
                        solver
                            .forward_dynamics(
                                &model,
                                black_box(q),
                                black_box(qd),
                                black_box(mt),
                                black_box(tt),
                            )
                            .unwrap(),
                    );
                }
            })
        });
        group.bench_function("runtime inverse dynamics", |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box(
                        solver
                            .inverse_dynamics(&model, black_box(q), black_box(qd), black_box(qdd))
                            .unwrap(),
                    );
                }
            })
        });
        group.finish();
    }};
}

fn scale(c: &mut Criterion) {
    bench_mechanism!(c, finger4, 4, 0, 5);
    bench_mechanism!(c, arm6, 6, 4, 3);
    bench_mechanism!(c, chain8, 8, 4, 5);
    bench_mechanism!(c, chain12, 12, 8, 5);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(51).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = scale
}
criterion_main!(benches);
