//! The benchmarks' seeded random states: q in [-π, π], q̇ in [-qd, qd], q̈ in [-qdd, qdd].

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// States per sample: one sample is a pass over all of them, and the figure is time per call.
pub const STATES: usize = 1024;

#[allow(clippy::type_complexity)]
pub fn states<const N: usize>(seed: u64, qd: f64, qdd: f64) -> Vec<([f64; N], [f64; N], [f64; N])> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..STATES)
        .map(|_| {
            let mut v = |s: f64| std::array::from_fn(|_| rng.random_range(-s..s));
            (v(std::f64::consts::PI), v(qd), v(qdd))
        })
        .collect()
}
