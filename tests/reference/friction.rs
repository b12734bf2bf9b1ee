//! Bearing friction for the checks: friction added to the files of seeded random
//! mechanisms ([`crate::random_mechanism`] writes each link and pulley on one line), and
//! the power that friction dissipates, written from the law of `docs/format.md` §4a and
//! the bodies' rates alone (`ω_b = c_b · q̇`, the couplings the transmission derived and
//! other checks hold against the kinematics) — none of `tendyn_core::friction`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::Model;

/// `text` with a bearing of random Coulomb (0.005 to 0.2 N·m on links, a tenth of that on
/// pulleys) and viscous friction (0.001 to 0.05 N·m·s/rad, likewise) on every link and
/// every pulley that turns (not `fixed`), and `friction_smoothing` if given.
pub fn with_bearing_friction(text: &str, seed: u64, smoothing: Option<f64>) -> String {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0xf71c);
    let mut out = String::new();
    let mut section = "";
    for line in text.lines() {
        let trimmed = line.trim_start();
        for s in ["links: [", "pulleys: [", "tendons: ["] {
            if trimmed.starts_with(s) {
                section = s;
            }
        }
        let entry = trimmed.starts_with("(name: \"") && line.trim_end().ends_with("),");
        let turns = match section {
            "links: [" => Some(1.0),
            "pulleys: [" if !line.contains("fixed: true") => Some(0.1),
            _ => None,
        };
        match turns.filter(|_| entry) {
            Some(scale) => {
                let body = line.trim_end().strip_suffix("),").expect("an entry");
                out.push_str(&format!(
                    "{body}, friction: (coulomb: {:e}, viscous: {:e})),\n",
                    scale * rng.random_range(0.005..0.2),
                    scale * rng.random_range(0.001..0.05)
                ));
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
        if let Some(v) = smoothing.filter(|_| trimmed.starts_with("name: \"")) {
            out.push_str(&format!("  friction_smoothing: {v:e},\n"));
        }
    }
    out
}

/// The band of rest of the exact law (`docs/format.md` §4a): rad/s, and rad/s² for the
/// direction of impending motion.
pub const REST: f64 = 1e-6;

/// The direction of a bearing's friction by the file's law: `sign(ω)` away from rest,
/// within [`REST`] of it `sign(α)` (or 0 if `α` is within it too); `tanh(ω / v)` with
/// `friction_smoothing: v`.
pub fn direction(model: &Model<f64>, rate: f64, accel: f64) -> f64 {
    match model.friction_smoothing() {
        Some(v) => (rate / v).tanh(),
        None if rate.abs() > REST => rate.signum(),
        None if accel.abs() > REST => accel.signum(),
        None => 0.0,
    }
}

/// `Σ_b c_bᵀ τ_f,b` with `τ_f,b = −(coulomb · s + viscous · ω_b)` by [`direction`]: what
/// the bearings' friction does to the joints.
pub fn generalized_force(model: &Model<f64>, qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; model.dof()];
    for (b, body) in model.bodies().iter().enumerate() {
        if let Some(f) = body.friction {
            let w = rate(model, b, qd);
            let s = direction(model, w, rate(model, b, qdd));
            let tau = -(f.coulomb * s + f.viscous * w);
            for (o, c) in out.iter_mut().zip(&body.coupling) {
                *o += c * tau;
            }
        }
    }
    out
}

/// The rate of body `b` relative to its parent: `c_b · q̇`.
pub fn rate(model: &Model<f64>, b: usize, qd: &[f64]) -> f64 {
    model.bodies()[b]
        .coupling
        .iter()
        .zip(qd)
        .map(|(c, v)| c * v)
        .sum()
}

/// `P_loss = Σ_b (coulomb_b · s_b · ω_b + viscous_b · ω_b²)`: the power the bearings
/// dissipate while every one of them turns (then `s_b ω_b = |ω_b|` or `tanh` of it, so
/// `≥ 0`).
pub fn dissipated_power(model: &Model<f64>, qd: &[f64]) -> f64 {
    (0..model.bodies().len())
        .filter_map(|b| {
            let f = model.bodies()[b].friction?;
            let w = rate(model, b, qd);
            Some(f.coulomb * direction(model, w, 0.0) * w + f.viscous * w * w)
        })
        .sum()
}
