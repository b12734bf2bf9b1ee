//! Body accelerations, total momentum and its rate, and the base reaction from the
//! momentum balance of the whole mechanism.
//!
//! Newton-Euler solvers get the base reaction at the end of their backward force
//! recursion. Here it comes from Newton's and Euler's laws for the mechanism as one system,
//! with no internal forces at all:
//!
//! ```text
//! F_base = dP/dt − Σ m g − F_ext,    M_base = dH_O/dt − Σ p_c × m g − M_ext,
//! P = Σ m v_c,    H_O = Σ (R I Rᵀ ω + p_c × m v_c),
//! ```
//!
//! with the rates taken by forward-mode AD along `q(t) = q + q̇ t + q̈ t²/2` of the
//! velocities of [`crate::poses::body_motions`]. Everything is in the base frame, moments
//! about the base origin; `(F_base, M_base)` is the wrench the base exerts on the mechanism.

use crate::lagrangian::{dual_path, gravity};
use crate::poses::{body_motions, mat, spin_axis, vec, world_poses, Ad};
use nalgebra::{Matrix3, Vector3};
use tendyn_core::model::Model;

/// A body's motion to second order, in the base frame.
#[derive(Clone, Debug)]
pub struct BodyAcceleration {
    pub rotation: Matrix3<f64>,
    pub com: Vector3<f64>,
    pub com_velocity: Vector3<f64>,
    pub com_acceleration: Vector3<f64>,
    /// Of the material body (including the spin of a body whose frame does not spin).
    pub angular_velocity: Vector3<f64>,
    pub angular_acceleration: Vector3<f64>,
}

/// Every body's centre-of-mass and angular velocity and acceleration at `(q, q̇, q̈)`: the
/// velocities of [`body_motions`] differentiated once more along the motion.
pub fn body_accelerations(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Vec<BodyAcceleration> {
    body_motions(model, &dual_path(q, qd), &dual_path(qd, qdd))
        .into_iter()
        .map(|m| BodyAcceleration {
            rotation: m.rotation.map(|x| x.re),
            com: m.com.map(|x| x.re),
            com_velocity: m.com_velocity.map(|x| x.re),
            com_acceleration: m.com_velocity.map(|x| x.eps),
            angular_velocity: m.angular_velocity.map(|x| x.re),
            angular_acceleration: m.angular_velocity.map(|x| x.eps),
        })
        .collect()
}

/// Linear momentum `P` and angular momentum `H_O` about the base origin, in any AD scalar.
pub fn momentum_ad<S: Ad>(model: &Model<f64>, q: &[S], qd: &[S]) -> (Vector3<S>, Vector3<S>) {
    momentum_of(model, q, qd, |_| true)
}

/// `(P, H_O)` summed over the bodies `inside`.
fn momentum_of<S: Ad>(
    model: &Model<f64>,
    q: &[S],
    qd: &[S],
    inside: impl Fn(usize) -> bool,
) -> (Vector3<S>, Vector3<S>) {
    let mut p = Vector3::zeros();
    let mut h = Vector3::zeros();
    let motions = body_motions(model, q, qd);
    for (i, (m, b)) in motions.iter().zip(model.bodies()).enumerate() {
        if !inside(i) {
            continue;
        }
        let inertia = m.rotation * mat::<S>(&b.inertia) * m.rotation.transpose();
        let linear = m.com_velocity * S::from(b.mass);
        h += inertia * m.angular_velocity + m.com.cross(&linear);
        p += linear;
    }
    (p, h)
}

/// Linear momentum `P` and angular momentum `H_O` about the base origin.
pub fn momentum(model: &Model<f64>, q: &[f64], qd: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    momentum_ad(model, q, qd)
}

/// `(dP/dt, dH_O/dt)` at `(q, q̇, q̈)`.
pub fn momentum_rates(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> (Vector3<f64>, Vector3<f64>) {
    rates_of(model, q, qd, qdd, |_| true)
}

fn rates_of(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    inside: impl Fn(usize) -> bool,
) -> (Vector3<f64>, Vector3<f64>) {
    let (p, h) = momentum_of(model, &dual_path(q, qd), &dual_path(qd, qdd), inside);
    (p.map(|x| x.eps), h.map(|x| x.eps))
}

/// Total gravity wrench `(Σ m g, Σ p_c × m g)` about the base origin.
pub fn gravity_wrench(model: &Model<f64>, q: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    gravity_of(model, q, |_| true)
}

fn gravity_of(
    model: &Model<f64>,
    q: &[f64],
    inside: impl Fn(usize) -> bool,
) -> (Vector3<f64>, Vector3<f64>) {
    let g = gravity(model);
    let mut force = Vector3::zeros();
    let mut moment = Vector3::zeros();
    let poses = world_poses::<f64>(model, q);
    for (i, ((r, o), b)) in poses.iter().zip(model.bodies()).enumerate() {
        if !inside(i) {
            continue;
        }
        let weight = g * b.mass;
        moment += (o + r * vec::<f64>(&b.com)).cross(&weight);
        force += weight;
    }
    (force, moment)
}

/// The model's external wrench as force and moment about the base origin, in the base
/// frame (zeros when it has none); `point`, `force` and `moment` are fixed in the link.
pub fn external_wrench_world(model: &Model<f64>, q: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    let Some(w) = &model.external_wrench() else {
        return (Vector3::zeros(), Vector3::zeros());
    };
    let (r, o) = &world_poses::<f64>(model, q)[w.link];
    let force = r * vec::<f64>(&w.force);
    let point = o + r * vec::<f64>(&w.point);
    (force, r * vec::<f64>(&w.moment) + point.cross(&force))
}

/// The wrench `(F_base, M_base)` the base exerts on the mechanism (moment about the base
/// origin, base frame), from the momentum balance of the whole mechanism.
pub fn base_reaction(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> (Vector3<f64>, Vector3<f64>) {
    balance(model, q, qd, qdd, |_| true)
}

/// The wrench `(F, M_O)` that everything outside the subtree rooted at body `root` exerts
/// on it (moment about the base origin, base frame): the same momentum balance over the
/// subtree's bodies only. For a chain driven by joint torques alone, the moment of this
/// wrench about the root's joint axis is that joint's torque.
pub fn subtree_reaction(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    root: usize,
) -> (Vector3<f64>, Vector3<f64>) {
    let mut inside = vec![false; model.bodies().len()];
    for (b, body) in model.bodies().iter().enumerate() {
        inside[b] = b == root || body.parent.is_some_and(|p| inside[p]);
    }
    balance(model, q, qd, qdd, |b| inside[b])
}

/// `(dP/dt − Σ m g − F_ext, dH_O/dt − Σ p × m g − M_ext)` over the bodies `inside`.
fn balance(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    inside: impl Fn(usize) -> bool + Copy,
) -> (Vector3<f64>, Vector3<f64>) {
    let (dp, dh) = rates_of(model, q, qd, qdd, inside);
    let (gf, gm) = gravity_of(model, q, inside);
    let (ef, em) = match &model.external_wrench() {
        Some(w) if inside(w.link) => external_wrench_world(model, q),
        _ => (Vector3::zeros(), Vector3::zeros()),
    };
    (dp - gf - ef, dh - gm - em)
}

/// Moment about body `j`'s joint axis (the line through its joint point along its spin
/// axis) of [`subtree_reaction`]`(.., j)`: for a chain driven by joint torques alone and
/// whose couplings do not turn bodies outside the subtree, joint `j`'s torque.
pub fn subtree_moment_about_joint(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    j: usize,
) -> f64 {
    let body = &model.bodies()[j];
    let (r, o) = &world_poses::<f64>(model, q)[j];
    // The joint point is at −postᵀ post.t in the body frame (whether the frame spins or not).
    let post_r = mat::<f64>(&body.post.rotation);
    let joint_point = o - r * post_r.transpose() * vec::<f64>(&body.post.translation);
    let axis = r * spin_axis(body);
    let (force, moment) = subtree_reaction(model, q, qd, qdd, j);
    (moment - joint_point.cross(&force)).dot(&axis)
}
