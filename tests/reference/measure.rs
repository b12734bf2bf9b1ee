//! How the specification tests draw states and measure agreement, in one place.

use rand::Rng;
use tendyn_core::Model;

use crate::random_mechanism::{valid_random_mechanism, Features};

/// Max-norm relative error `‖a − b‖∞ / ‖b‖∞` (the norm every agreement figure states).
pub fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// A random state of `n` joints with the ranges of the benchmark protocol: q in [−π, π],
/// q̇ in [−3, 3], q̈ in [−10, 10].
pub fn random_state(rng: &mut impl Rng, n: usize) -> [Vec<f64>; 3] {
    let mut v = |s: f64| {
        (0..n)
            .map(|_| rng.random_range(-s..s))
            .collect::<Vec<f64>>()
    };
    [v(std::f64::consts::PI), v(3.0), v(10.0)]
}

/// Random mechanisms with a complete routing (no explicit couplings, so every segment
/// tension and bearing force is available), every third one driven by an endless loop.
pub fn routed_random_mechanisms(count: u64) -> Vec<Model<f64>> {
    (0..count)
        .map(|seed| {
            let features = Features {
                coupled_pulleys: false,
                endless: seed % 3 == 1,
            };
            valid_random_mechanism(seed, features).1
        })
        .collect()
}

/// The size of the terms forward dynamics sums, from the solver
/// (`Solver::forward_dynamics_scale`): forward dynamics is measured relative to this.
pub fn forward_dynamics_term_scale(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    motor_torques: &[f64],
    tendon_tensions: &[f64],
) -> f64 {
    tendyn_core::Data::new(model)
        .forward_dynamics_scale(model, q, qd, motor_torques, tendon_tensions)
        .expect("a valid state")
}

/// The size of the terms of the generalized forces the actuators deliver,
/// `Σ c_m τ_m + A(σ, q) T`: the largest `|τ_m|` and `|A_jk T_k|` (each tendon's column of
/// the state from `Data::actuator_forces` with that tendon alone at 1 N). Delivered forces
/// are measured relative to this: a redundant routing's tensions cancel in the sum.
pub fn actuator_force_scale(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    motor_torques: &[f64],
    tendon_tensions: &[f64],
) -> f64 {
    let mut data = tendyn_core::Data::new(model);
    let idle = vec![0.0; motor_torques.len()];
    let mut size = motor_torques.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (k, &t) in tendon_tensions.iter().enumerate() {
        let mut alone = vec![0.0; tendon_tensions.len()];
        alone[k] = 1.0;
        let column = (data.actuator_forces(model, q, qd, &idle, &alone)).expect("a valid state");
        size = column.iter().fold(size, |m, a| m.max((a * t).abs()));
    }
    size
}
