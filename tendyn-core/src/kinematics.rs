//! Forward recursion: velocities and accelerations of every primary and intermediate
//! link, from the base outwards (paper Eqs. 2-6 for primary links, 11-15 for intermediate
//! links).
//!
//! Both kinds are one case here. A body's frame relative to its parent's is
//! `pre · RotZ(angle) · post`: a DH link has `pre = I` and `post = TransZ(d)·TransX(a)·RotX(α)`
//! (Eq. 1), a pulley has its placement as `pre` and `post = I` (Eq. 8). The joint point
//! (on the axis) is the parent's `pre` origin, which the body shares with its parent, so
//! its acceleration is the parent's there (Eq. 5, and Eq. 14 with the carrier's motion).
//! Gravity enters as an upward acceleration of the base (`v̇_0 = −g`).

use crate::model::{Body, BodyPattern, Model};
use crate::real::Real;
use crate::spatial::{Mat3, Vec3};

/// Motion of one body, in its own frame.
#[derive(Clone, Copy, Debug)]
pub struct Motion<T> {
    /// `ᵇR_parent`: rotates parent-frame vectors into this body's frame.
    pub rotation: Mat3<T>,
    /// Angular velocity of the body (rad/s): its parent's plus its own rate about its axis
    /// (Eqs. 2, 11). For a pulley whose frame does not spin it is still the turning pulley's.
    pub omega: Vec3<T>,
    /// Angular acceleration of the body (rad/s², Eqs. 3, 12).
    pub omega_dot: Vec3<T>,
    /// Acceleration of the body-frame origin (m/s², Eqs. 5, 14), gravity included as `−g`.
    pub accel: Vec3<T>,
    /// Acceleration of the joint point (the origin of the body's `pre`, a point of the
    /// parent), gravity included, in the **parent's** frame: what the backward recursion
    /// hands a pulley's inertial force back to its carrier in (see `newton_euler::backward`).
    pub joint_accel: Vec3<T>,
    /// Inertial force `m a_c` (N, Eq. 21), body frame.
    pub inertial_force: Vec3<T>,
    /// Inertial moment about the body-frame origin, `I ω̇ + ω × I ω + c × m a_c` (N·m,
    /// Eq. 22 moved to the origin), body frame: what every backward pass over this motion
    /// takes, computed once.
    pub inertial_moment: Vec3<T>,
    /// Sine and cosine of the body's angle `coupling · q + offset` (`(0, 1)` for a body
    /// whose frame does not spin).
    pub turn: (T, T),
}

impl<T: Real> Motion<T> {
    /// At rest, frame aligned with its parent's, no gravity: what work buffers start as.
    pub fn rest() -> Self {
        Motion {
            rotation: Mat3::identity(),
            omega: Vec3::zero(),
            omega_dot: Vec3::zero(),
            accel: Vec3::zero(),
            joint_accel: Vec3::zero(),
            inertial_force: Vec3::zero(),
            inertial_moment: Vec3::zero(),
            turn: (T::zero(), T::one()),
        }
    }
}

/// `coupling · v` (Eqs. 9-10: a body's angle is linear in the joint coordinates), summed
/// over `joints`, the coupling's nonzero entries ([`BodyPattern::joints`]).
pub fn coupled<T: Real>(coupling: &[T], joints: &[usize], v: &[T]) -> T {
    let mut s = T::zero();
    for &j in joints {
        s = s + coupling[j] * v[j];
    }
    s
}

/// The sine and cosine of the angle `coupling · q + offset` of every body `wanted` selects
/// (`(0, 1)` where its frame does not spin), handed to `put` with the body's index: the
/// angles formed first and their sines and cosines computed together, a block at a time
/// ([`Real::sin_cos_many`]: an `f64` computes several in one vector).
pub fn body_turns<T: Real>(
    model: &Model<T>,
    q: &[T],
    wanted: impl Fn(usize) -> bool,
    mut put: impl FnMut(usize, (T, T)),
) {
    const BLOCK: usize = 8;
    let mut angles = [T::zero(); BLOCK];
    let mut owners = [0; BLOCK];
    let mut turns = [(T::zero(), T::one()); BLOCK];
    let mut filled = 0;
    let bodies = model.bodies.iter().zip(&model.patterns).enumerate();
    for (i, (b, pattern)) in bodies.filter(|(i, _)| wanted(*i)) {
        if !b.spins {
            put(i, (T::zero(), T::one()));
            continue;
        }
        angles[filled] = coupled(&b.coupling, &pattern.joints, q) + b.offset;
        owners[filled] = i;
        filled += 1;
        if filled == BLOCK {
            T::sin_cos_many(&angles, &mut turns);
            for (&i, &turn) in owners.iter().zip(&turns) {
                put(i, turn);
            }
            filled = 0;
        }
    }
    T::sin_cos_many(&angles[..filled], &mut turns[..filled]);
    for (&i, &turn) in owners[..filled].iter().zip(&turns[..filled]) {
        put(i, turn);
    }
}

/// `ᵇR_parent` of a body whose angle has sine and cosine `turn` ([`body_turns`]):
/// `(pre · RotZ(angle) · post)ᵀ`, the factors its pattern knows to be the identity
/// skipped, and the turn applied to its neighbour by mixing two rows or columns (a link's
/// `post`, a pulley's `pre`), not by a full product.
pub fn body_rotation<T: Real>(b: &Body<T>, pattern: &BodyPattern, turn: (T, T)) -> Mat3<T> {
    let turn = b.spins.then_some(turn);
    let down = match (turn, pattern.plain_pre, pattern.plain_post) {
        (None, true, true) => Mat3::identity(),
        (None, true, false) => b.post.rotation,
        (None, false, true) => b.pre.rotation,
        (None, false, false) => b.pre.rotation * b.post.rotation,
        (Some((s, c)), true, true) => Mat3::rot_z(s, c),
        (Some((s, c)), true, false) => b.post.rotation.turned_about_z(s, c),
        (Some((s, c)), false, true) => b.pre.rotation.then_turned_about_z(s, c),
        (Some((s, c)), false, false) => b.pre.rotation * b.post.rotation.turned_about_z(s, c),
    };
    down.transpose()
}

/// Runs the forward recursion and writes one [`Motion`] per body into `out`.
/// With `gravity == false` the base does not accelerate (for `M` and `h`). With
/// `tendons == false` the inert bodies (massless pulleys that carry nothing), which only
/// tendons load, are left as they were.
#[allow(clippy::too_many_arguments)]
pub fn forward<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    gravity: bool,
    tendons: bool,
    out: &mut [Motion<T>],
) {
    let base_accel = if gravity {
        -model.gravity
    } else {
        Vec3::zero()
    };
    // The sines and cosines first: they depend on `q` alone, and computed together the
    // processor overlaps them (and an f64 computes several in one vector), where in the
    // recursion each would wait for the last body's arithmetic.
    let wanted = |i: usize| tendons || !model.patterns[i].inert;
    body_turns(model, q, wanted, |i, turn| out[i].turn = turn);
    for (i, (b, pattern)) in model.bodies.iter().zip(&model.patterns).enumerate() {
        if !tendons && pattern.inert {
            continue;
        }
        let (w_p, wd_p, a_p) = match b.parent {
            None => (Vec3::zero(), Vec3::zero(), base_accel),
            Some(p) => (out[p].omega, out[p].omega_dot, out[p].accel),
        };
        let turn = out[i].turn;
        let r = body_rotation(b, pattern, turn);
        let rate = coupled(&b.coupling, &pattern.joints, qd);
        let rate_dot = coupled(&b.coupling, &pattern.joints, qdd);
        // Eqs. 2-3 (11-12): ω = R(ω_p) + θ̇ z, ω̇ = R ω̇_p + θ̈ z + (R ω_p) × θ̇ z.
        let w_in = r.mul_vec(w_p);
        let (omega, omega_dot) = if pattern.axis_along_z {
            // The same sums with the axis's zero components left out: `θ̇ z` adds to ω_z
            // alone, and `(R ω_p) × θ̇ z = θ̇ (w_y, −w_x, 0)`.
            let wd = r.mul_vec(wd_p);
            (
                Vec3::new(w_in.x, w_in.y, w_in.z + rate),
                Vec3::new(wd.x + w_in.y * rate, wd.y - w_in.x * rate, wd.z + rate_dot),
            )
        } else {
            let spin = b.axis.scale(rate);
            (
                w_in + spin,
                r.mul_vec(wd_p) + b.axis.scale(rate_dot) + w_in.cross(spin),
            )
        };
        // Eq. 5 (14): acceleration of the joint point as a point of the parent, carried
        // into this frame, then out to this body's origin.
        // The terms of offsets the pattern knows to be zero are skipped: they would add
        // exact zeros (and a symbolic scalar folds them away).
        let j = b.pre.translation;
        let a_joint = if pattern.joint_at_parent_origin {
            a_p
        } else {
            a_p + wd_p.cross(j) + w_p.cross(w_p.cross(j))
        };
        let p = b.joint_to_origin;
        let accel = if pattern.origin_at_joint {
            r.mul_vec(a_joint)
        } else {
            r.mul_vec(a_joint) + omega_dot.cross(p) + omega.cross(omega.cross(p))
        };
        // Eq. 6 (15): the centre of mass.
        let c = b.com;
        let com_accel = if pattern.com_at_origin {
            accel
        } else {
            accel + omega_dot.cross(c) + omega.cross(omega.cross(c))
        };
        // Eqs. 21-22.
        let inertial_force = com_accel.scale(b.mass);
        let spin_momentum = b.inertia.mul_vec(omega);
        let inertial_moment = b.inertia.mul_vec(omega_dot) + omega.cross(spin_momentum);
        let inertial_moment = if pattern.com_at_origin {
            inertial_moment
        } else {
            inertial_moment + c.cross(inertial_force)
        };
        out[i] = Motion {
            inertial_force,
            inertial_moment,
            rotation: r,
            omega,
            omega_dot,
            accel,
            joint_accel: a_joint,
            turn,
        };
    }
}
