//! The joint-space mass matrix by the composite-rigid-body algorithm (Walker and Orin
//! 1982; Featherstone, *Rigid Body Dynamics Algorithms*, §6.2), over the expanded tree.
//! Not in the paper, which needs `M` only implicitly; one Newton-Euler pass per joint
//! (what `M` cost before) grows as `n` passes over every body, this as one pass plus a
//! walk up each body's ancestors.
//!
//! Every link and pulley is a body turning about its own axis by `θ_b = c_b · q +
//! offset_b` (Eqs. 9-10). On the expanded tree, with one coordinate `θ_b` per body, the
//! kinetic energy is `½ θ̇ᵀ M_θ θ̇` and `θ̇ = C q̇` (the couplings as rows of `C`), so
//!
//! ```text
//! M = Cᵀ M_θ C,   M_θ[i][k] = s_kᵀ I^C_i s_i   (k = i or an ancestor of i; 0 otherwise)
//! ```
//!
//! where `I^C_i` is the composite inertia of `i` and everything it carries and `s_i` its
//! unit motion, a turn about its axis through its joint point. A pulley's mass is thereby
//! folded into its carrier's composite inertia and its spin enters through its coupling,
//! exactly as `Q = Σ_b c_bᵀ τ_b` takes it in the recursion.
//!
//! A composite inertia is kept as mass `m`, first moment `h = Σ m c` and rotational
//! inertia `I` about the body's joint point, in body-frame axes. The unit turn of body `i`
//! is a rotation about its axis `a` through that point, so the subtree's momentum is
//! `F = a × h`, `N = I a` about it. `M_θ[i][k]` is the moment of that momentum about
//! `k`'s joint point along `k`'s axis, with `(F, N)` carried to `k`'s frame as a force and
//! its moment.
//!
//! Everything is arranged for the symbolic scalar, which makes this the generated `M`:
//! frames change by the factors of `pre · RotZ(θ) · post` one at a time (constant
//! rotations, usually signed permutations that fold away, and a turn about z), and
//! inertias move between points by constant offsets only (the joint point to the body
//! origin, `p`; the parent's origin to the joint point, `pre`'s translation, zero for a
//! link).

use crate::kinematics::coupled;
use crate::model::{Body, Model};
use crate::real::Real;
use crate::spatial::{Mat3, Vec3};

/// Mass, first moment and rotational inertia of a body and everything it carries.
#[derive(Clone, Copy, Debug)]
pub struct Composite<T> {
    /// Sine and cosine of the body's angle (`(0, 1)` where the frame does not spin).
    spin: (T, T),
    /// Total mass (kg).
    mass: T,
    /// `Σ m c`, body frame (kg·m): about the body-frame origin while the children are
    /// added, then about the joint point.
    first_moment: Vec3<T>,
    /// Rotational inertia, body-frame axes (kg·m²), about the same point as `first_moment`.
    inertia: Mat3<T>,
}

impl<T: Real> Composite<T> {
    /// No mass: what work buffers start as.
    pub fn empty() -> Self {
        Composite {
            spin: (T::zero(), T::one()),
            mass: T::zero(),
            first_moment: Vec3::zero(),
            inertia: Mat3 {
                rows: [[T::zero(); 3]; 3],
            },
        }
    }
}

/// A symmetric matrix from its upper triangle `upper(i, j)`, `i ≤ j`.
fn symmetric<T: Real>(upper: impl Fn(usize, usize) -> T) -> Mat3<T> {
    let (a, b, c) = (upper(0, 0), upper(0, 1), upper(0, 2));
    let (d, e, f) = (upper(1, 1), upper(1, 2), upper(2, 2));
    Mat3 {
        rows: [[a, b, c], [b, d, e], [c, e, f]],
    }
}

fn add<T: Real>(a: &Mat3<T>, b: &Mat3<T>) -> Mat3<T> {
    symmetric(|i, j| a.rows[i][j] + b.rows[i][j])
}

/// What moving the reference point of a mass `m` with first moment `h` by `r` (the old
/// point's position from the new one) adds to its rotational inertia:
/// `−m [r]×² − [r]×[h]× − [h]×[r]×`, whose entries are `δᵢⱼ r·(w + h) − rᵢ wⱼ − hᵢ rⱼ`
/// with `w = m r + h`, the first moment about the new point.
fn point_shift<T: Real>(r: Vec3<T>, mass: T, h: Vec3<T>) -> Mat3<T> {
    let w = r.scale(mass) + h;
    let d = r.dot(w + h);
    let (r, w, h) = (r.to_array(), w.to_array(), h.to_array());
    symmetric(|i, j| {
        let off = r[i] * w[j] + h[i] * r[j];
        if i == j {
            d - off
        } else {
            -off
        }
    })
}

/// `R S Rᵀ` of a symmetric `S`.
fn congruence<T: Real>(r: &Mat3<T>, s: &Mat3<T>) -> Mat3<T> {
    let rs = *r * *s;
    symmetric(|i, j| (0..3).fold(T::zero(), |acc, k| acc + rs.rows[i][k] * r.rows[j][k]))
}

/// A vector of body `b`'s frame in its parent's axes: `pre · RotZ(θ) · post` one factor at a
/// time.
fn to_parent<T: Real>(b: &Body<T>, spin: (T, T), v: Vec3<T>) -> Vec3<T> {
    let v = b.post.rotation.mul_vec(v);
    let v = if b.spins {
        Mat3::rot_z(spin.0, spin.1).mul_vec(v)
    } else {
        v
    };
    b.pre.rotation.mul_vec(v)
}

/// A symmetric tensor of body `b`'s frame in its parent's axes, factor by factor.
fn tensor_to_parent<T: Real>(b: &Body<T>, spin: (T, T), s: &Mat3<T>) -> Mat3<T> {
    let s = congruence(&b.post.rotation, s);
    let s = if b.spins {
        congruence(&Mat3::rot_z(spin.0, spin.1), &s)
    } else {
        s
    };
    congruence(&b.pre.rotation, &s)
}

/// The joint-space mass matrix `M(q)` (row-major `n × n` into `out`), every pulley's
/// inertia included through its coupling. `composite` holds one entry per body. Only the
/// upper triangle is summed; the lower one mirrors it.
pub fn mass_matrix<T: Real>(
    model: &Model<T>,
    q: &[T],
    composite: &mut [Composite<T>],
    out: &mut [T],
) {
    let bodies = model.bodies();
    let n = model.dof();
    let joints = model.coupled_joints();
    // Each body's own inertia about its origin; then, from the tips down (parents come
    // before children), each composite is moved to its joint point and added to its
    // parent's, about the parent's origin.
    for (b, c) in bodies.iter().zip(composite.iter_mut()) {
        // The angle as the forward recursion forms it, so that traces share its sine.
        c.spin = if b.spins {
            (coupled(&b.coupling, q) + b.offset).sin_cos()
        } else {
            (T::zero(), T::one())
        };
        c.mass = b.mass;
        c.first_moment = b.com.scale(b.mass);
        c.inertia = add(&b.inertia, &point_shift(b.com, b.mass, Vec3::zero()));
    }
    for i in (0..bodies.len()).rev() {
        let b = &bodies[i];
        let c = &mut composite[i];
        // The origin is `p` from the joint point.
        let p = b.joint_to_origin;
        c.inertia = add(&c.inertia, &point_shift(p, c.mass, c.first_moment));
        c.first_moment = c.first_moment + p.scale(c.mass);
        let c = *c;
        let Some(parent) = b.parent else { continue };
        // In the parent's axes, then about its origin, from which the joint point is
        // `pre`'s translation.
        let h = to_parent(b, c.spin, c.first_moment);
        let r = b.pre.translation;
        let inertia = add(
            &tensor_to_parent(b, c.spin, &c.inertia),
            &point_shift(r, c.mass, h),
        );
        let to = &mut composite[parent];
        to.mass = to.mass + c.mass;
        to.first_moment = to.first_moment + h + r.scale(c.mass);
        to.inertia = add(&to.inertia, &inertia);
    }

    for x in out.iter_mut() {
        *x = T::zero();
    }
    for i in 0..bodies.len() {
        if joints[i].is_empty() {
            continue;
        }
        let b = &bodies[i];
        let c = &composite[i];
        // The subtree's momentum for a unit turn of body i, about its joint point.
        let mut force = b.axis.cross(c.first_moment);
        let mut moment = c.inertia.mul_vec(b.axis);
        let mut k = i;
        loop {
            let bk = &bodies[k];
            accumulate(model, i, k, bk.axis.dot(moment), n, out);
            let Some(parent) = bk.parent else { break };
            // To the parent's axes, about its origin, then about its joint point.
            let spin = composite[k].spin;
            force = to_parent(bk, spin, force);
            moment = to_parent(bk, spin, moment) + bk.pre.translation.cross(force);
            k = parent;
            moment = moment + bodies[k].joint_to_origin.cross(force);
        }
    }
    for a in 0..n {
        for b in 0..a {
            out[a * n + b] = out[b * n + a];
        }
    }
}

/// Adds `M_θ[i][k]` (`k` = `i` or an ancestor) to the upper triangle of `M = Cᵀ M_θ C`:
/// for `k = i`, `c_i[a] c_i[b]` at `(a, b)`; otherwise `c_k[a] c_i[b]` and its mirror
/// `c_i[a] c_k[b]` (the term of `M_θ[k][i]`), both at `(min, max)`.
fn accumulate<T: Real>(model: &Model<T>, i: usize, k: usize, entry: T, n: usize, out: &mut [T]) {
    let joints = model.coupled_joints();
    let (ci, ck) = (&model.bodies()[i].coupling, &model.bodies()[k].coupling);
    if i == k {
        for (x, &a) in joints[i].iter().enumerate() {
            for &b in &joints[i][x..] {
                out[a * n + b] = out[a * n + b] + ci[a] * ci[b] * entry;
            }
        }
        return;
    }
    for &a in &joints[k] {
        for &b in &joints[i] {
            // On the diagonal the term and its mirror fall on one entry.
            let w = if a == b {
                T::from_f64(2.0) * ck[a] * ci[a]
            } else {
                ck[a] * ci[b]
            };
            let (lo, hi) = (a.min(b), a.max(b));
            out[lo * n + hi] = out[lo * n + hi] + w * entry;
        }
    }
}
