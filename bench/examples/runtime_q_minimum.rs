//! The runtime solver's `Q` on the benchmark mechanisms, as the minimum over 200 passes of
//! the 1,024 seeded states of `expanded_tree` (ns per call). For comparing two builds on
//! this noisy VM: criterion's mean moves by ±25 % between runs, the minimum by about 1 %,
//! so alternating two builds' runs tells a few per cent apart.
//!
//! `RUSTFLAGS="-C target-cpu=native" cargo build --release -p tendyn-bench --example
//! runtime_q_minimum`, then `taskset -c 0 target/release/examples/runtime_q_minimum`, copied
//! aside per build and run in turns.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    for name in ["finger4", "arm6", "chain8", "chain12"] {
        let path = format!("{}/mechanisms/{name}.ron", env!("CARGO_MANIFEST_DIR"));
        let model = tendyn_core::load(&path).expect("a benchmark mechanism");
        let n = model.dof();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let states: Vec<[Vec<f64>; 3]> = (0..1024)
            .map(|_| {
                let mut v = |s: f64| (0..n).map(|_| rng.random_range(-s..s)).collect::<Vec<_>>();
                [v(std::f64::consts::PI), v(3.0), v(10.0)]
            })
            .collect();
        let mut data = tendyn_core::Data::new(&model);
        let mut best = f64::INFINITY;
        for _ in 0..200 {
            let start = Instant::now();
            for [q, qd, qdd] in &states {
                let q = black_box(q.as_slice());
                black_box(
                    data.generalized_forces(&model, q, qd, qdd)
                        .expect("a valid state"),
                );
            }
            best = best.min(start.elapsed().as_nanos() as f64 / states.len() as f64);
        }
        print!("{name} {best:.0}  ");
    }
    println!();
}
