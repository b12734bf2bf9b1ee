//! The joint-space mass matrix by the composite-rigid-body algorithm (Walker and Orin
//! 1982; Featherstone, *Rigid Body Dynamics Algorithms*, §6.2), over the expanded tree.
//! Not in the paper, which needs `M` only implicitly; one Newton-Euler pass per joint
//! (what `M` cost before) grows as `n` passes over every body, this as one pass from the
//! tips to the base.
//!
//! Every link and pulley is a body turning about its own axis by `θ_b = c_b · q +
//! offset_b` (Eqs. 9-10). On the expanded tree, with one coordinate `θ_b` per body, the
//! kinetic energy is `½ θ̇ᵀ M_θ θ̇` and `θ̇ = C q̇` (the couplings as rows of `C`), so
//!
//! ```text
//! M = Cᵀ M_θ C,   M_θ[k][i] = s_kᵀ I^C_i s_i   (k = i or an ancestor of i; 0 otherwise)
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
//! `f_i = (a × h, I a)` (force, moment about it). `M_θ[k][i]` is the moment of `f_i`
//! about `k`'s joint point along `k`'s axis, `f_i` carried to `k`'s frame.
//!
//! The sums of `Cᵀ M_θ C` are taken per joint rather than per body: with
//! `S_k[b] = Σ_i c_i[b] f_i` over the strict descendants `i` of `k` (carried to `k`),
//!
//! ```text
//! M[a][b] = Σ_k  c_k[a] c_k[b] M_θ[k][k] + c_k[a] (a_k · S_k[b]) + c_k[b] (a_k · S_k[a])
//! ```
//!
//! so a pulley on a link costs one transfer to its carrier per joint it turns with, where
//! it is summed with the column the links below already carry, instead of a walk of its
//! own to the base. A pulley that turns with joints whose links are not below its carrier
//! (whose columns would be carried for it alone) walks to the base on its own instead,
//! adding `c_k[a] c_i[b] M_θ[k][i]` and its mirror at each ancestor `k`.
//!
//! Everything is arranged for the symbolic scalar, which makes this the generated `M`:
//! frames change by the factors of `pre · RotZ(θ) · post` one at a time (constant
//! rotations, usually signed permutations that fold away, and a turn about z), and
//! inertias move between points by constant offsets only (the joint point to the body
//! origin, `p`; the parent's origin to the joint point, `pre`'s translation, zero for a
//! link).

use crate::kinematics::body_turns;
use crate::model::{Body, BodyPattern, Model};
use crate::real::Real;
use crate::spatial::{Mat3, Vec3};

/// Mass, first moment and rotational inertia of a body and everything it carries.
#[derive(Clone, Copy, Debug)]
struct Composite<T> {
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

/// A force and its moment about a body's joint point, in the body's frame.
type Wrench<T> = (Vec3<T>, Vec3<T>);

/// Work buffers of [`mass_matrix`], sized for one model.
#[derive(Clone, Debug)]
pub struct Work<T> {
    /// Per body.
    composite: Vec<Composite<T>>,
    /// `S_k[b]`, body-major (`k · n + b`).
    columns: Vec<Wrench<T>>,
    /// Whether `S_k[b]` has a term yet.
    present: Vec<bool>,
    /// Per body, whether it walks to the base on its own rather than joining its
    /// carrier's columns (a fact of the model's structure).
    walks: Vec<bool>,
    /// Per body that carries nothing, its transfer to its parent in harmonics of its angle
    /// ([`Turned`]): numbers of the model, kept for the model they were made from.
    turned: Vec<Option<Turned<T>>>,
    /// The [`Model::identity`] `turned` was made for.
    turned_for: Option<usize>,
}

impl<T: Real> Work<T> {
    /// Buffers for `model`.
    pub fn new<U>(model: &Model<U>) -> Self {
        let (bodies, n) = (model.bodies(), model.dof());
        let nb = bodies.len();
        // The joints whose links are in each body's subtree: the columns carried anyway.
        let mut below = vec![false; nb * n];
        for k in (0..nb).rev() {
            if k < n {
                below[k * n + k] = true;
            }
            if let Some(p) = bodies[k].parent {
                for j in 0..n {
                    below[p * n + j] |= below[k * n + j];
                }
            }
        }
        let walks = (0..nb)
            .map(|k| {
                bodies[k].parent.is_some_and(|p| {
                    model.patterns()[k]
                        .joints
                        .iter()
                        .any(|&j| !below[p * n + j])
                })
            })
            .collect();
        let zero = Vec3::zero();
        Work {
            composite: vec![
                Composite {
                    spin: (T::zero(), T::one()),
                    mass: T::zero(),
                    first_moment: zero,
                    inertia: Mat3 {
                        rows: [[T::zero(); 3]; 3],
                    },
                };
                nb
            ],
            columns: vec![(zero, zero); nb * n],
            present: vec![false; nb * n],
            walks,
            turned: vec![None; nb],
            turned_for: None,
        }
    }
}

/// What a body that carries nothing gives its parent, as functions of its own angle `θ`:
/// its first moment in the parent's axes `h₀ + h_c cos θ + h_s sin θ`, its rotational
/// inertia about the parent's origin `I₀ + I_c cos θ + I_s sin θ + I_c2 cos 2θ + I_s2 sin
/// 2θ`, and its own unit-turn wrench `(a × h, I a)` carried to the parent's joint point in
/// the same harmonics of `θ`. A turn about z moves a vector by harmonics of `θ` and a
/// symmetric tensor by those of `θ` and `2θ` only, and everything else here is a constant
/// of the body. So traced code evaluates a few scaled constants per entry, zeros skipped
/// (an axisymmetric, on-axis pulley's harmonics vanish), instead of two congruences and a
/// point shift, and the runtime computes them once per model (kept in [`Work`]).
#[derive(Clone, Copy, Debug)]
struct Turned<T> {
    first_moment: [Vec3<T>; 3],
    inertia: [Mat3<T>; 5],
    /// The unit-turn wrench's force and moment (about the parent's joint point).
    wrench: [Wrench<T>; 3],
    /// Whether the angle turns the body's frame at all (else only the constant terms).
    spins: bool,
}

impl<T: Real> Turned<T> {
    /// Of body `b`, which carries nothing, on a parent whose origin is `parent_origin`
    /// from its joint point: its mass, first moment and inertia about its joint point as
    /// [`mass_matrix`] forms them, then turned.
    fn of(b: &Body<T>, pattern: &BodyPattern, parent_origin: Vec3<T>) -> Self {
        let (m, p, zero) = (b.mass, b.joint_to_origin, T::zero());
        let own = add(&b.inertia, &point_shift(b.com, m, Vec3::zero()));
        let i = add(&own, &point_shift(p, m, b.com.scale(m)));
        let h = b.com.scale(m) + p.scale(m);
        let turned = |v: Vec3<T>| harmonics(b, pattern, v);
        let first_moment = turned(h);
        let (f, moment) = (turned(b.axis.cross(h)), turned(i.mul_vec(b.axis)));
        // The moment about the parent's joint point: `pre`'s translation, then the
        // parent's `p` (as `carry`).
        let arm = b.pre.translation + parent_origin;
        let wrench = core::array::from_fn(|k| (f[k], moment[k] + arm.cross(f[k])));
        // The tensor: `post` first, then the turn's harmonics, each part through `pre`.
        let j = if pattern.plain_post {
            i
        } else {
            congruence(&b.post.rotation, &i)
        }
        .rows;
        let matrix = |rows: [[T; 3]; 3]| Mat3 { rows };
        let parts: [Mat3<T>; 5] = if b.spins {
            let half = T::from_f64(0.5);
            let (mean, diff) = ((j[0][0] + j[1][1]) * half, (j[0][0] - j[1][1]) * half);
            let (xy, xz, yz) = (j[0][1], j[0][2], j[1][2]);
            [
                matrix([
                    [mean, zero, zero],
                    [zero, mean, zero],
                    [zero, zero, j[2][2]],
                ]),
                matrix([[zero, zero, xz], [zero, zero, yz], [xz, yz, zero]]),
                matrix([[zero, zero, -yz], [zero, zero, xz], [-yz, xz, zero]]),
                matrix([[diff, xy, zero], [xy, -diff, zero], [zero, zero, zero]]),
                matrix([[-xy, diff, zero], [diff, xy, zero], [zero, zero, zero]]),
            ]
        } else {
            let z = matrix([[zero; 3]; 3]);
            [matrix(j), z, z, z, z]
        };
        // About the parent's origin: the point shift is affine in the first moment.
        let r = b.pre.translation;
        let inertia = core::array::from_fn(|k| {
            let part = if pattern.plain_pre {
                parts[k]
            } else {
                congruence(&b.pre.rotation, &parts[k])
            };
            match k {
                0 => add(&part, &point_shift(r, m, first_moment[0])),
                1 | 2 => add(&part, &point_shift(r, zero, first_moment[k])),
                _ => part,
            }
        });
        Turned {
            first_moment,
            inertia,
            wrench,
            spins: b.spins,
        }
    }

    /// The first moment and inertia at the angle whose sine and cosine are `spin`.
    fn at(&self, (s, c): (T, T)) -> (Vec3<T>, Mat3<T>) {
        let [h0, hc, hs] = self.first_moment;
        if !self.spins {
            return (h0, self.inertia[0]);
        }
        let h = h0 + hc.scale(c) + hs.scale(s);
        let (c2, s2) = ((c - s) * (c + s), (s + s) * c);
        let [i0, ic, is, ic2, is2] = &self.inertia;
        let inertia = symmetric(|a, b| {
            i0.rows[a][b]
                + ic.rows[a][b] * c
                + is.rows[a][b] * s
                + ic2.rows[a][b] * c2
                + is2.rows[a][b] * s2
        });
        (h, inertia)
    }

    /// The unit-turn wrench carried to the parent, at the angle whose sine and cosine are
    /// `spin` (what [`carry`] gives of `(a × h, I a)`).
    fn wrench_at(&self, (s, c): (T, T)) -> Wrench<T> {
        let [w0, wc, ws] = self.wrench;
        if !self.spins {
            return w0;
        }
        let sum = |v0: Vec3<T>, vc: Vec3<T>, vs: Vec3<T>| v0 + vc.scale(c) + vs.scale(s);
        (sum(w0.0, wc.0, ws.0), sum(w0.1, wc.1, ws.1))
    }
}

/// A vector of body `b`'s frame in its parent's axes as `v₀ + v_c cos θ + v_s sin θ` (see
/// [`to_parent`]): `post`, the turn about z, then `pre`.
fn harmonics<T: Real>(b: &Body<T>, pattern: &BodyPattern, v: Vec3<T>) -> [Vec3<T>; 3] {
    let u = if pattern.plain_post {
        v
    } else {
        b.post.rotation.mul_vec(v)
    };
    let zero = T::zero();
    let parts = if b.spins {
        [
            Vec3::new(zero, zero, u.z),
            Vec3::new(u.x, u.y, zero),
            Vec3::new(-u.y, u.x, zero),
        ]
    } else {
        [u, Vec3::zero(), Vec3::zero()]
    };
    parts.map(|x| {
        if pattern.plain_pre {
            x
        } else {
            b.pre.rotation.mul_vec(x)
        }
    })
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
pub(crate) fn point_shift<T: Real>(r: Vec3<T>, mass: T, h: Vec3<T>) -> Mat3<T> {
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
pub(crate) fn congruence<T: Real>(r: &Mat3<T>, s: &Mat3<T>) -> Mat3<T> {
    let rs = *r * *s;
    symmetric(|i, j| (0..3).fold(T::zero(), |acc, k| acc + rs.rows[i][k] * r.rows[j][k]))
}

/// A vector of body `b`'s frame in its parent's axes: `pre · RotZ(θ) · post` one factor at a
/// time, those its pattern knows to be the identity skipped.
fn to_parent<T: Real>(b: &Body<T>, pattern: &BodyPattern, spin: (T, T), v: Vec3<T>) -> Vec3<T> {
    let mut v = v;
    if !pattern.plain_post {
        v = b.post.rotation.mul_vec(v);
    }
    if b.spins {
        v = Mat3::rot_z(spin.0, spin.1).mul_vec(v);
    }
    if !pattern.plain_pre {
        v = b.pre.rotation.mul_vec(v);
    }
    v
}

/// A symmetric tensor of body `b`'s frame in its parent's axes, factor by factor.
fn tensor_to_parent<T: Real>(
    b: &Body<T>,
    pattern: &BodyPattern,
    spin: (T, T),
    s: &Mat3<T>,
) -> Mat3<T> {
    let mut s = *s;
    if !pattern.plain_post {
        s = congruence(&b.post.rotation, &s);
    }
    if b.spins {
        s = congruence(&Mat3::rot_z(spin.0, spin.1), &s);
    }
    if !pattern.plain_pre {
        s = congruence(&b.pre.rotation, &s);
    }
    s
}

/// A wrench about body `k`'s joint point in its frame, carried to its parent's axes and
/// joint point (the joint point is `pre`'s translation from the parent's origin, which is
/// `p` from the parent's joint point).
fn carry<T: Real>(model: &Model<T>, k: usize, spin: (T, T), (f, m): Wrench<T>) -> Wrench<T> {
    let (bodies, pattern) = (model.bodies(), &model.patterns()[k]);
    let b = &bodies[k];
    let f = to_parent(b, pattern, spin, f);
    let m = to_parent(b, pattern, spin, m) + b.pre.translation.cross(f);
    let parent = b.parent.expect("a body with a parent");
    (f, m + bodies[parent].joint_to_origin.cross(f))
}

/// Adds `w` to column `index` (`k · n + b`), which holds nothing until `present` says so.
fn join<T: Real>(columns: &mut [Wrench<T>], present: &mut [bool], index: usize, w: Wrench<T>) {
    let s = &mut columns[index];
    *s = if present[index] {
        (s.0 + w.0, s.1 + w.1)
    } else {
        w
    };
    present[index] = true;
}

/// Adds `c_k[a] e` for every joint `a` of body `k` to the upper triangle at `(a, j)` (both
/// orders fall on one entry; on the diagonal they are two terms).
fn add_column<T: Real>(out: &mut [T], n: usize, ck: &[T], pattern: &[usize], j: usize, e: T) {
    for &a in pattern {
        let w = if a == j {
            T::from_f64(2.0) * ck[a]
        } else {
            ck[a]
        };
        let (lo, hi) = (a.min(j), a.max(j));
        out[lo * n + hi] = out[lo * n + hi] + w * e;
    }
}

/// The joint-space mass matrix `M(q)` (row-major `n × n` into `out`), every pulley's
/// inertia included through its coupling. Only the upper triangle is summed; the lower
/// one mirrors it.
pub fn mass_matrix<T: Real>(model: &Model<T>, q: &[T], work: &mut Work<T>, out: &mut [T]) {
    let bodies = model.bodies();
    let n = model.dof();
    let patterns = model.patterns();
    if work.turned_for != Some(model.identity) {
        let carries = |k: usize| bodies.iter().any(|c| c.parent == Some(k));
        for (k, (b, pattern)) in bodies.iter().zip(patterns).enumerate() {
            work.turned[k] = match b.parent {
                Some(parent) if !carries(k) => {
                    Some(Turned::of(b, pattern, bodies[parent].joint_to_origin))
                }
                _ => None,
            };
        }
        work.turned_for = Some(model.identity);
    }
    let Work {
        composite,
        columns,
        present,
        walks,
        turned,
        ..
    } = work;
    // The angles as the forward recursion forms them, so that traces share their sines.
    body_turns(model, q, |_| true, |i, turn| composite[i].spin = turn);
    // Each body's own inertia about its origin.
    for (b, c) in bodies.iter().zip(composite.iter_mut()) {
        c.mass = b.mass;
        c.first_moment = b.com.scale(b.mass);
        c.inertia = add(&b.inertia, &point_shift(b.com, b.mass, Vec3::zero()));
    }
    present.fill(false);
    out.fill(T::zero());

    // From the tips to the base (parents come before children): when body k is reached,
    // its composite and its columns hold everything it carries.
    for k in (0..bodies.len()).rev() {
        let b = &bodies[k];
        let (c, ck, pattern) = (&mut composite[k], &b.coupling, &patterns[k].joints);
        // About the joint point, from which the origin is `p`.
        let p = b.joint_to_origin;
        c.inertia = add(&c.inertia, &point_shift(p, c.mass, c.first_moment));
        c.first_moment = c.first_moment + p.scale(c.mass);
        let c = *c;
        let own = (b.axis.cross(c.first_moment), c.inertia.mul_vec(b.axis));
        // c_k[a] c_k[b] M_θ[k][k], then c_k[a] (a_k · S_k[b]) and its mirror.
        let diagonal = b.axis.dot(own.1);
        for (x, &i) in pattern.iter().enumerate() {
            for &j in &pattern[x..] {
                out[i * n + j] = out[i * n + j] + ck[i] * ck[j] * diagonal;
            }
        }
        for j in (0..n).filter(|&j| present[k * n + j]) {
            add_column(out, n, ck, pattern, j, b.axis.dot(columns[k * n + j].1));
        }
        let Some(parent) = b.parent else { continue };
        if walks[k] && !pattern.is_empty() {
            // M_θ[at][k] at each ancestor `at`, weighted by both couplings.
            let (mut wrench, mut at) = (own, k);
            let mut first = turned[k].as_ref().map(|t| t.wrench_at(c.spin));
            while bodies[at].parent.is_some() {
                wrench = match first.take() {
                    Some(w) => w,
                    None => carry(model, at, composite[at].spin, wrench),
                };
                at = bodies[at].parent.expect("checked");
                let e = bodies[at].axis.dot(wrench.1);
                for &j in pattern {
                    add_column(
                        out,
                        n,
                        &bodies[at].coupling,
                        &patterns[at].joints,
                        j,
                        ck[j] * e,
                    );
                }
            }
        } else {
            // k's own turns join its columns.
            for &j in pattern {
                let term = (own.0.scale(ck[j]), own.1.scale(ck[j]));
                join(columns, present, k * n + j, term);
            }
        }
        // A body that carries nothing holds only its own turns, `c_k[j]` times its wrench
        // (carried once, and only if it has a column: a walking body has none).
        let mut turned_wrench = None;
        for j in 0..n {
            if !present[k * n + j] {
                continue;
            }
            let carried = match &turned[k] {
                Some(t) => {
                    let (f, m) = *turned_wrench.get_or_insert_with(|| t.wrench_at(c.spin));
                    (f.scale(ck[j]), m.scale(ck[j]))
                }
                None => carry(model, k, c.spin, columns[k * n + j]),
            };
            join(columns, present, parent * n + j, carried);
        }
        // The composite moves to the parent: its axes, then about its origin.
        let r = b.pre.translation;
        let (h, inertia) = match &turned[k] {
            Some(t) => t.at(c.spin),
            None => {
                let h = to_parent(b, &patterns[k], c.spin, c.first_moment);
                let inertia = add(
                    &tensor_to_parent(b, &patterns[k], c.spin, &c.inertia),
                    &point_shift(r, c.mass, h),
                );
                (h, inertia)
            }
        };
        let to = &mut composite[parent];
        to.mass = to.mass + c.mass;
        to.first_moment = to.first_moment + h + r.scale(c.mass);
        to.inertia = add(&to.inertia, &inertia);
    }
    for a in 0..n {
        for b in 0..a {
            out[a * n + b] = out[b * n + a];
        }
    }
}
