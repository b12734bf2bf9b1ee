//! World poses and velocities of every body, composed from scratch with nalgebra.
//!
//! Nothing here touches the solver's kinematics (`spatial::Transform::compose`, the
//! forward recursion of Eqs. 2-6 and 11-16): each body's pose is the plain product of the
//! transforms the model stores, evaluated in a forward-mode dual-number scalar, and a
//! velocity is the derivative of a pose along the path `q(t) = q + q̇ t`, read off the dual
//! part. Angular velocities come from `Ṙ Rᵀ`, not from summing joint axes.

use nalgebra::{Matrix3, Vector3};
use num_dual::{Dual, DualNumCopy};
use tendyn_core::model::{Body, Model};
use tendyn_core::spatial::{Mat3, Transform, Vec3};

/// A forward-mode dual-number scalar over `f64`: `f64` itself, `Dual64`, `HyperDual64`,
/// `Dual<Dual64>`, ... Every function of this crate that is generic takes one of these.
pub trait Ad: DualNumCopy<Primitive = f64> {}
impl<S: DualNumCopy<Primitive = f64>> Ad for S {}

/// A world-frame pose: rotation (body axes to base axes) and origin of the body frame.
pub type Pose<S> = (Matrix3<S>, Vector3<S>);

/// The model's row-major matrix as an nalgebra matrix in scalar `S`.
pub fn mat<S: Ad>(m: &Mat3<f64>) -> Matrix3<S> {
    Matrix3::from_fn(|i, j| S::from(m.rows[i][j]))
}

/// The model's vector as an nalgebra vector in scalar `S`.
pub fn vec<S: Ad>(v: &Vec3<f64>) -> Vector3<S> {
    Vector3::new(S::from(v.x), S::from(v.y), S::from(v.z))
}

fn transform<S: Ad>(t: &Transform<f64>) -> Pose<S> {
    (mat(&t.rotation), vec(&t.translation))
}

/// `angle_b = Σ_j coupling[j]·x[j] + offset` (pass `x = q` for the angle; an angle rate
/// is `rate(body, q̇)`, the same sum without the offset).
pub fn angle<S: Ad>(body: &Body<f64>, q: &[S]) -> S {
    rate(body, q) + S::from(body.offset)
}

/// `Σ_j coupling[j]·x[j]`: the joint's angle rate when `x = q̇`.
pub fn rate<S: Ad>(body: &Body<f64>, x: &[S]) -> S {
    body.coupling
        .iter()
        .zip(x)
        .fold(S::zero(), |acc, (&c, &xj)| acc + xj * c)
}

/// The joint (spin) axis in the body frame, recomputed from its definition
/// `post.rotationᵀ · z` rather than read from `body.axis`.
pub fn spin_axis(body: &Body<f64>) -> Vector3<f64> {
    mat::<f64>(&body.post.rotation).transpose() * Vector3::z()
}

/// Every body's pose in the base frame: `X_parent · pre · RotZ(angle) · post`, with the
/// rotation left out when `spins == false`. Bodies must come in topological order.
pub fn world_poses<S: Ad>(model: &Model<f64>, q: &[S]) -> Vec<Pose<S>> {
    assert_eq!(q.len(), model.dof(), "q has the wrong length");
    let mut poses: Vec<Pose<S>> = Vec::with_capacity(model.bodies().len());
    for (index, body) in model.bodies().iter().enumerate() {
        let (pre_r, pre_t) = transform::<S>(&body.pre);
        let (post_r, post_t) = transform::<S>(&body.post);
        let joint_r = if body.spins {
            let (s, c) = angle(body, q).sin_cos();
            let (o, z) = (S::one(), S::zero());
            pre_r * Matrix3::new(c, -s, z, s, c, z, z, z, o)
        } else {
            pre_r
        };
        let local_r = joint_r * post_r;
        let local_t = joint_r * post_t + pre_t;
        let pose = match body.parent {
            None => (local_r, local_t),
            Some(p) => {
                assert!(p < index, "body {index} comes before its parent {p}");
                let (r, t) = &poses[p];
                (r * local_r, r * local_t + t)
            }
        };
        poses.push(pose);
    }
    poses
}

/// Where a body is and how it moves, in the base frame.
#[derive(Clone, Debug)]
pub struct BodyMotion<S: Ad> {
    /// Rotation of the body frame.
    pub rotation: Matrix3<S>,
    pub origin: Vector3<S>,
    /// Centre of mass.
    pub com: Vector3<S>,
    pub com_velocity: Vector3<S>,
    /// Angular velocity of the material body: that of its frame, plus
    /// `rate · R · spin_axis` for a body whose frame does not spin (`spins == false`).
    pub angular_velocity: Vector3<S>,
}

/// `vee(W)` of a skew matrix `W = [w]×` (the antisymmetric part of `W`, to be exact).
fn vee<S: Ad>(w: &Matrix3<S>) -> Vector3<S> {
    let half = S::from(0.5);
    Vector3::new(
        (w[(2, 1)] - w[(1, 2)]) * half,
        (w[(0, 2)] - w[(2, 0)]) * half,
        (w[(1, 0)] - w[(0, 1)]) * half,
    )
}

/// Poses and velocities of all bodies at `(q, q̇)`, by forward-mode AD of [`world_poses`]
/// along `q(t) = q + q̇ t`: `v = d/dt (o + R c)` and `[ω]× = Ṙ Rᵀ`.
///
/// `S` may itself be a dual number (then `q` and `q̇` carry further derivatives, e.g. the
/// Lagrangian's partial derivatives or a second time derivative).
pub fn body_motions<S: Ad>(model: &Model<f64>, q: &[S], qd: &[S]) -> Vec<BodyMotion<S>> {
    assert_eq!(qd.len(), model.dof(), "q̇ has the wrong length");
    let path: Vec<Dual<S>> = q.iter().zip(qd).map(|(&x, &v)| Dual::new(x, v)).collect();
    let poses = world_poses(model, &path);
    poses
        .iter()
        .zip(model.bodies())
        .map(|((r, o), body)| {
            let com = o + r * vec::<Dual<S>>(&body.com);
            let rotation = r.map(|x| x.re);
            let r_dot = r.map(|x| x.eps);
            let mut angular_velocity = vee(&(r_dot * rotation.transpose()));
            if !body.spins {
                let axis = spin_axis(body).map(S::from);
                angular_velocity += rotation * axis * rate(body, qd);
            }
            BodyMotion {
                rotation,
                origin: o.map(|x| x.re),
                com: com.map(|x| x.re),
                com_velocity: com.map(|x| x.eps),
                angular_velocity,
            }
        })
        .collect()
}
