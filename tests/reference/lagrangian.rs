//! Joint-space dynamics from the Lagrangian `L = T − V`, by exact automatic differentiation.
//!
//! The recursive Newton-Euler method propagates velocities, accelerations and forces body by
//! body. None of that is used here: the only physics is the scalar energies
//!
//! ```text
//! T(q, q̇) = Σ_b ½ m_b |v_b|² + ½ ω_bᵀ (R_b I_b R_bᵀ) ω_b,      V(q) = −Σ_b m_b g·p_b
//! ```
//!
//! (`v_b`, `p_b` of the centre of mass, `ω_b` of the material body, from
//! [`crate::poses::body_motions`]), and the generalized forces are Lagrange's equations
//! `Q = d/dt(∂L/∂q̇) − ∂L/∂q = M q̈ + h(q, q̇) + g(q)`, every derivative taken by nested
//! dual numbers. No finite differences: results are exact up to `f64` rounding.

use crate::poses::{body_motions, mat, vec, world_poses, Ad};
use nalgebra::{DMatrix, DVector, Vector3};
use num_dual::{Dual, Dual64, HyperDual, HyperDual64};
use tendyn_core::model::Model;

/// Kinetic energy `T(q, q̇)` in any AD scalar (so that it can be differentiated further).
pub fn kinetic_energy_ad<S: Ad>(model: &Model<f64>, q: &[S], qd: &[S]) -> S {
    let half = S::from(0.5);
    body_motions(model, q, qd)
        .iter()
        .zip(model.bodies())
        .fold(S::zero(), |acc, (m, b)| {
            let inertia = m.rotation * mat::<S>(&b.inertia) * m.rotation.transpose();
            let w = &m.angular_velocity;
            let v = &m.com_velocity;
            acc + (v.dot(v) * b.mass + w.dot(&(inertia * w))) * half
        })
}

/// Potential energy `V(q) = −Σ_b m_b g·p_b` in any AD scalar (zero at the base origin).
pub fn potential_energy_ad<S: Ad>(model: &Model<f64>, q: &[S]) -> S {
    let g = vec::<S>(model.gravity());
    world_poses(model, q)
        .iter()
        .zip(model.bodies())
        .fold(S::zero(), |acc, ((r, o), b)| {
            let com = o + r * vec::<S>(&b.com);
            acc - g.dot(&com) * b.mass
        })
}

/// Kinetic energy `T(q, q̇)`.
pub fn kinetic_energy(model: &Model<f64>, q: &[f64], qd: &[f64]) -> f64 {
    kinetic_energy_ad(model, q, qd)
}

/// Potential energy `V(q)` of gravity.
pub fn potential_energy(model: &Model<f64>, q: &[f64]) -> f64 {
    potential_energy_ad(model, q)
}

/// Joint-space mass matrix `M(q) = Σ_b J_vᵀ m J_v + J_ωᵀ (R I Rᵀ) J_ω`, with the Jacobian
/// columns `J_v e_j`, `J_ω e_j` the centre-of-mass and angular velocities at `q̇ = e_j`.
pub fn mass_matrix(model: &Model<f64>, q: &[f64]) -> DMatrix<f64> {
    let n = model.dof();
    let columns: Vec<_> = (0..n)
        .map(|j| body_motions(model, q, &unit(n, j)))
        .collect();
    let poses = world_poses::<f64>(model, q);
    let mut m = DMatrix::zeros(n, n);
    for (b, (body, (r, _))) in model.bodies().iter().zip(&poses).enumerate() {
        let inertia = r * mat::<f64>(&body.inertia) * r.transpose();
        for (i, a) in columns.iter().map(|c| &c[b]).enumerate() {
            for (j, c) in columns.iter().map(|c| &c[b]).enumerate() {
                m[(i, j)] += body.mass * a.com_velocity.dot(&c.com_velocity)
                    + a.angular_velocity.dot(&(inertia * c.angular_velocity));
            }
        }
    }
    m
}

/// `Q = d/dt(∂L/∂q̇) − ∂L/∂q = M q̈ + h(q, q̇) + g(q)`: the total non-conservative generalized
/// force the motion `(q, q̇, q̈)` needs. It is the actuation's (tendons, motors) plus the
/// external wrench's, so the actuation supplies `Q − external_generalized_forces`.
pub fn lagrange_generalized_forces(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> DVector<f64> {
    lagrange(model, q, qd, qdd, true)
}

/// Velocity product terms `h(q, q̇)` (Coriolis and centrifugal; no gravity): `Q` at `q̈ = 0`
/// with `V = 0`.
pub fn bias(model: &Model<f64>, q: &[f64], qd: &[f64]) -> DVector<f64> {
    lagrange(model, q, qd, &vec![0.0; model.dof()], false)
}

/// Gravity terms `g(q) = ∂V/∂q`.
pub fn gravity_forces(model: &Model<f64>, q: &[f64]) -> DVector<f64> {
    DVector::from_fn(model.dof(), |i, _| {
        potential_energy_ad(model, &seeded(q, i)).eps
    })
}

/// `dE/dt` of the total energy `E = T + V` along `q(t) = q + q̇ t + q̈ t²/2`. With no
/// friction, power balance says `Qᵀ q̇ = dE/dt` for the actuation's `Q`.
pub fn energy_rate(model: &Model<f64>, q: &[f64], qd: &[f64], qdd: &[f64]) -> f64 {
    let path = dual_path(q, qd);
    let rates = dual_path(qd, qdd);
    (kinetic_energy_ad(model, &path, &rates) + potential_energy_ad(model, &path)).eps
}

/// The power put into the mechanism, term by term: each open-ended tendon's tension times
/// the rate its exit pulls in, `T_k (A_k · q̇)`; each motor's `τ_m (c_m · q̇)`; and the
/// external wrench's `Q_ext · q̇` (last). The rates are kinematics: friction changes none.
pub fn power_in(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    tendon_tensions: &[f64],
    motor_torques: &[f64],
) -> Vec<f64> {
    let rate = |c: &[f64]| c.iter().zip(qd).map(|(a, v)| a * v).sum::<f64>();
    let tendons = model
        .tendons()
        .iter()
        .zip(tendon_tensions)
        .map(|(t, tension)| tension * rate(&t.structure));
    let motors = model
        .motors()
        .iter()
        .zip(motor_torques)
        .map(|(m, tau)| tau * rate(&m.column));
    let external = rate(external_generalized_forces(model, q).as_slice());
    tendons.chain(motors).chain([external]).collect()
}

/// Generalized force `Q_ext = J_pᵀ f + J_ωᵀ m` of the model's external wrench (zero when it
/// has none), read as a follower wrench: `point`, `force` and `moment` fixed in the frame of
/// body `link`. The actuation then supplies `lagrange_generalized_forces − Q_ext`.
pub fn external_generalized_forces(model: &Model<f64>, q: &[f64]) -> DVector<f64> {
    let n = model.dof();
    let Some(w) = &model.external_wrench() else {
        return DVector::zeros(n);
    };
    DVector::from_fn(n, |j, _| {
        let path: Vec<Dual64> = dual_path(q, &unit(n, j));
        let (r, o) = &world_poses(model, &path)[w.link];
        let point = o + r * vec::<Dual64>(&w.point);
        let r = r.map(|x| x.re);
        let omega = body_motions(model, q, &unit(n, j))[w.link].angular_velocity;
        (r * vec::<f64>(&w.force)).dot(&point.map(|x| x.eps))
            + (r * vec::<f64>(&w.moment)).dot(&omega)
    })
}

fn lagrange(model: &Model<f64>, q: &[f64], qd: &[f64], qdd: &[f64], gravity: bool) -> DVector<f64> {
    let n = model.dof();
    assert!(
        q.len() == n && qd.len() == n && qdd.len() == n,
        "wrong lengths"
    );
    DVector::from_fn(n, |i, _| {
        // d/dt ∂T/∂q̇_i: ε1 seeds q̇_i, ε2 moves along (q̇, q̈), the ε1ε2 part is the
        // derivative along the motion of the ε1 part. (V does not depend on q̇.)
        let path: Vec<HyperDual64> = (0..n)
            .map(|j| HyperDual64::new(q[j], 0.0, qd[j], 0.0))
            .collect();
        let rates: Vec<HyperDual64> = (0..n)
            .map(|j| HyperDual64::new(qd[j], delta(i, j), qdd[j], 0.0))
            .collect();
        let d_dt_momentum = kinetic_energy_ad(model, &path, &rates).eps1eps2;
        // ∂T/∂q_i and ∂V/∂q_i.
        let at = seeded(q, i);
        let rates: Vec<Dual64> = qd.iter().map(|&v| Dual::from_re(v)).collect();
        let dt_dq = kinetic_energy_ad(model, &at, &rates).eps;
        let dv_dq = if gravity {
            potential_energy_ad(model, &at).eps
        } else {
            0.0
        };
        d_dt_momentum - dt_dq + dv_dq
    })
}

/// The derivative of Lagrange's `Q` (as [`lagrange_generalized_forces`]) along the seeds
/// `dq`, `dqd`: `(∂Q/∂q) dq + (∂Q/∂q̇) dqd`, exact. The same energies, each evaluated with
/// every number carrying one more dual part (the seed) beneath the hyper-dual parts that
/// give `Q`: third derivatives of `L`, no finite differences and nothing of the recursion.
pub fn lagrange_generalized_forces_derivative(
    model: &Model<f64>,
    [q, qd, qdd]: [&[f64]; 3],
    [dq, dqd]: [&[f64]; 2],
) -> DVector<f64> {
    let n = model.dof();
    let seeded = |x: f64, dx: f64| Dual64::new(x, dx);
    DVector::from_fn(n, |i, _| {
        let path: Vec<HyperDual<Dual64>> = (0..n)
            .map(|j| {
                HyperDual::new(
                    seeded(q[j], dq[j]),
                    Dual64::from(0.0),
                    seeded(qd[j], dqd[j]),
                    Dual64::from(0.0),
                )
            })
            .collect();
        let rates: Vec<HyperDual<Dual64>> = (0..n)
            .map(|j| {
                let unit = Dual64::from(delta(i, j));
                HyperDual::new(
                    seeded(qd[j], dqd[j]),
                    unit,
                    Dual64::from(qdd[j]),
                    Dual64::from(0.0),
                )
            })
            .collect();
        let d_dt_momentum = kinetic_energy_ad(model, &path, &rates).eps1eps2;
        let at: Vec<Dual<Dual64>> = (0..n)
            .map(|j| Dual::new(seeded(q[j], dq[j]), Dual64::from(delta(i, j))))
            .collect();
        let rates: Vec<Dual<Dual64>> = (0..n)
            .map(|j| Dual::from_re(seeded(qd[j], dqd[j])))
            .collect();
        let dt_dq = kinetic_energy_ad(model, &at, &rates).eps;
        let dv_dq = potential_energy_ad(model, &at).eps;
        (d_dt_momentum - dt_dq + dv_dq).eps
    })
}

/// `x` with the derivative seed `e_i`.
fn seeded(x: &[f64], i: usize) -> Vec<Dual64> {
    x.iter()
        .enumerate()
        .map(|(j, &v)| Dual64::new(v, delta(i, j)))
        .collect()
}

/// `x + ε dx`.
pub(crate) fn dual_path(x: &[f64], dx: &[f64]) -> Vec<Dual64> {
    x.iter().zip(dx).map(|(&v, &d)| Dual64::new(v, d)).collect()
}

fn unit(n: usize, j: usize) -> Vec<f64> {
    (0..n).map(|k| delta(j, k)).collect()
}

fn delta(i: usize, j: usize) -> f64 {
    if i == j {
        1.0
    } else {
        0.0
    }
}

/// World-frame gravity as an nalgebra vector.
pub(crate) fn gravity(model: &Model<f64>) -> Vector3<f64> {
    vec(model.gravity())
}
