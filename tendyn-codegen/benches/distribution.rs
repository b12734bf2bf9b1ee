//! The generated `actuation` of tendon mechanisms whose tension distribution has one, two
//! and three null directions, with the protocol of `benches/dynamics.rs` (1,024 seeded
//! random states, q in [-π, π], q̇ in [-2, 2], q̈ in [-6, 6]; the figure is time per call):
//!
//! - Example 3 as in the paper (one direction, floors only: the closed form, no status to
//!   decide) and with a 60 N maximum on every tendon (one direction with a status);
//! - `bounded_1x3` (one joint, three tendons: two directions) and `bounded_3x6` (three
//!   joints, six tendons: three directions), floors and maxima drawn per tendon, where the
//!   generated code calls the dual active-set routine of `tendyn_core::distribution`;
//!   and the same two with their derivatives (`actuation_derivatives`: the optimum
//!   differentiated on its active set along each of the `3n` coordinates), on every state.
//!
//! `cargo bench -p tendyn-codegen --bench distribution` (pin with `taskset -c 0` and build
//! with `RUSTFLAGS="-C target-cpu=native"` for the protocol's conditions). The generated
//! files are `golden/distribution/`, kept by `tests/golden.rs`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

#[allow(dead_code)]
mod example3 {
    include!("../golden/example3_stanford_jpl.rs");
}
#[allow(dead_code)]
mod example3_bounded {
    include!("../golden/distribution/example3_bounded.rs");
}
#[allow(dead_code)]
mod bounded_1x3 {
    include!("../golden/distribution/bounded_1x3.rs");
}
#[allow(dead_code)]
mod bounded_3x6 {
    include!("../golden/distribution/bounded_3x6.rs");
}
#[allow(dead_code)]
mod bounded_1x3_derivatives {
    include!("../golden/distribution/bounded_1x3_derivatives.rs");
}
#[allow(dead_code)]
mod bounded_3x6_derivatives {
    include!("../golden/distribution/bounded_3x6_derivatives.rs");
}

#[path = "common/states.rs"]
mod states;
use states::{states, STATES};

macro_rules! bench_actuation {
    ($group:expr, $label:literal, $module:ident, $n:literal) => {{
        let data = states::<$n>(7, 2.0, 6.0);
        let feasible: Vec<_> = data
            .iter()
            .filter(|(q, qd, qdd)| {
                $module::actuation::<f64>(q, qd, qdd).status
                    == tendyn_core::distribution::Status::Feasible
            })
            .copied()
            .collect();
        println!("{}: {} of {STATES} states feasible", $label, feasible.len());
        let mut sets = vec![($label.to_string(), data)];
        // The same on the feasible states alone, repeated to 1,024 calls: a state the
        // bounds cannot meet costs the second phase's steps until the maxima are shown to
        // leave no tensions (about 3.6 of them on the 3×6 system, against 0.3 at a feasible
        // state), after which the floors' optimum is the best effort.
        if feasible.len() < STATES {
            let repeated = feasible.iter().cycle().take(STATES).copied().collect();
            sets.push((format!("{}, feasible states", $label), repeated));
        }
        for (name, set) in &sets {
            $group.bench_function(name.as_str(), |b| {
                b.iter(|| {
                    for (q, qd, qdd) in set {
                        black_box($module::actuation::<f64>(
                            black_box(q),
                            black_box(qd),
                            black_box(qdd),
                        ));
                    }
                })
            });
        }
    }};
}

macro_rules! bench_derivatives {
    ($group:expr, $label:literal, $module:ident, $n:literal) => {{
        let data = states::<$n>(7, 2.0, 6.0);
        $group.bench_function($label, |b| {
            b.iter(|| {
                for (q, qd, qdd) in &data {
                    black_box($module::actuation_derivatives::<f64>(
                        black_box(q),
                        black_box(qd),
                        black_box(qdd),
                    ));
                }
            })
        });
    }};
}

fn distribution(c: &mut Criterion) {
    let mut group = c.benchmark_group("generated actuation (f64)");
    group.throughput(Throughput::Elements(STATES as u64));
    bench_actuation!(group, "example 3, d = 1, floors only", example3, 3);
    bench_actuation!(group, "example 3, d = 1, with maxima", example3_bounded, 3);
    bench_actuation!(group, "1 joint, 3 tendons, d = 2", bounded_1x3, 1);
    bench_actuation!(group, "3 joints, 6 tendons, d = 3", bounded_3x6, 3);
    group.finish();
    // With the derivatives: the optimum's active set differentiated per coordinate.
    let mut group = c.benchmark_group("generated actuation_derivatives (f64)");
    group.throughput(Throughput::Elements(STATES as u64));
    bench_derivatives!(
        group,
        "1 joint, 3 tendons, d = 2",
        bounded_1x3_derivatives,
        1
    );
    bench_derivatives!(
        group,
        "3 joints, 6 tendons, d = 3",
        bounded_3x6_derivatives,
        3
    );
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(51).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = distribution
}
criterion_main!(benches);
