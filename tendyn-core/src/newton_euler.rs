//! Backward recursion: Newton's and Euler's equations of every body from the tip to the
//! base, with the tendon tensions left as unknowns (paper Eqs. 19-24).
//!
//! A primary link always has more unknowns than balance equations (joint force, joint
//! moment and tendon tensions, Section 7), so the unknowns of the tension system are
//! solved at the base ([`crate::tension`]). The recursion is linear in them, so it runs
//! with known tensions ([`Load`] a plain vector: every unknown zero for `b`, then the
//! solved ones for the bearings), or, where capstan friction makes `E` depend on the state,
//! with every force affine in them ([`crate::affine`]), which gives `E` too.
//!
//! For body `b` with parent `p`, in `b`'s frame, with `F = m a_c` and `N = I ω̇ + ω × I ω`
//! (Eqs. 21-22):
//!
//! ```text
//! f_b = F − Σ f_applied − Σ_children f_from_child                      (Eq. 19, 23)
//! n_b = N + c × F − Σ r × f_applied − Σ moments from children − p_J × f_b  (Eq. 20, 24)
//! ```
//!
//! where `f_b`, `n_b` are the force and moment the parent exerts on `b` through its
//! joint, the moment taken about the joint point `p_J`. (For a spinning pulley, the part
//! `m a_J` of `F` due to the joint point's acceleration reaches the parent in the parent's
//! frame directly; see [`backward`].) The moment includes the torque of
//! a motor on that joint, if any; its component along the joint axis, `τ_b`, is what the
//! rows of the tension system balance.

use crate::affine::{Aff3, Affine};
use crate::kinematics::Motion;
use crate::model::{BodyKind, Contact, Model, Via};
use crate::real::Real;
use crate::spatial::{Mat3, Vec3};

/// A tension or moment of the recursion: a number when the unknowns are known (or zero),
/// or affine in them ([`Affine`]: how tests read `E` off the recursion's own statics).
pub trait LoadScalar<T: Real>: Copy + core::fmt::Debug {
    /// The known value `c`, over `unknowns` unknowns (ignored by a number).
    fn known(c: T, unknowns: usize) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `s · self`.
    fn scale(&self, s: T) -> Self;
    /// `self + c` for a known `c`.
    fn add_known(&self, c: T) -> Self;
}

impl<T: Real> LoadScalar<T> for T {
    fn known(c: T, _: usize) -> Self {
        c
    }
    fn add(&self, o: &Self) -> Self {
        *self + *o
    }
    fn scale(&self, s: T) -> Self {
        *self * s
    }
    fn add_known(&self, c: T) -> Self {
        *self + c
    }
}

impl<T: Real> LoadScalar<T> for Affine<T> {
    fn known(c: T, unknowns: usize) -> Self {
        Affine::constant(c, unknowns)
    }
    fn add(&self, o: &Self) -> Self {
        Affine::add(self, o)
    }
    fn scale(&self, s: T) -> Self {
        Affine::scale(self, s)
    }
    fn add_known(&self, c: T) -> Self {
        self.add_constant(c)
    }
}

/// What a force or moment of the recursion is: a plain vector when everything is known
/// (the expanded-tree pass behind `M`, `h`, `g`, and the passes with known tensions behind
/// `b` and the bearings), or affine in the unknown tensions (the state's `E` with capstan
/// friction). The recursion is written once, over this.
pub trait Load<T: Real>: Copy + core::fmt::Debug {
    /// Its components' type (`T`, or [`Affine`]).
    type Scalar: LoadScalar<T>;
    /// The known vector `v`, over `unknowns` unknowns (ignored by a plain vector).
    fn known(v: Vec3<T>, unknowns: usize) -> Self;
    /// `dir · s`: a force of known direction and (possibly unknown) magnitude.
    fn along(dir: Vec3<T>, s: &Self::Scalar) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self − o`.
    fn sub(&self, o: &Self) -> Self;
    /// `−self`.
    fn neg(&self) -> Self;
    /// `self + v` for a known vector `v`.
    fn add_known(&self, v: Vec3<T>) -> Self;
    /// `r × self`.
    fn moment_of(&self, r: Vec3<T>) -> Self;
    /// `R · self`.
    fn rotate(&self, m: &Mat3<T>) -> Self;
    /// `Rᵀ · self`.
    fn rotate_back(&self, m: &Mat3<T>) -> Self;
    /// `u · self`.
    fn dot(&self, u: Vec3<T>) -> Self::Scalar;
}

impl<T: Real> Load<T> for Vec3<T> {
    type Scalar = T;
    fn known(v: Vec3<T>, _: usize) -> Self {
        v
    }
    fn along(dir: Vec3<T>, s: &T) -> Self {
        dir.scale(*s)
    }
    fn add(&self, o: &Self) -> Self {
        *self + *o
    }
    fn sub(&self, o: &Self) -> Self {
        *self - *o
    }
    fn neg(&self) -> Self {
        -*self
    }
    fn add_known(&self, v: Vec3<T>) -> Self {
        *self + v
    }
    fn moment_of(&self, r: Vec3<T>) -> Self {
        r.cross(*self)
    }
    fn rotate(&self, m: &Mat3<T>) -> Self {
        m.mul_vec(*self)
    }
    fn rotate_back(&self, m: &Mat3<T>) -> Self {
        m.tr_mul_vec(*self)
    }
    fn dot(&self, u: Vec3<T>) -> T {
        u.dot(*self)
    }
}

impl<T: Real> Load<T> for Aff3<T> {
    type Scalar = Affine<T>;
    fn known(v: Vec3<T>, unknowns: usize) -> Self {
        Aff3::known(v, unknowns)
    }
    fn along(dir: Vec3<T>, s: &Affine<T>) -> Self {
        Aff3::along(dir, s)
    }
    fn add(&self, o: &Self) -> Self {
        Aff3::add(self, o)
    }
    fn sub(&self, o: &Self) -> Self {
        Aff3::sub(self, o)
    }
    fn neg(&self) -> Self {
        Aff3::neg(self)
    }
    fn add_known(&self, v: Vec3<T>) -> Self {
        Aff3::add_known(self, v)
    }
    fn moment_of(&self, r: Vec3<T>) -> Self {
        Aff3::moment_of(self, r)
    }
    fn rotate(&self, m: &Mat3<T>) -> Self {
        Aff3::rotate(self, m)
    }
    fn rotate_back(&self, m: &Mat3<T>) -> Self {
        Aff3::rotate_back(self, m)
    }
    fn dot(&self, u: Vec3<T>) -> Affine<T> {
        Aff3::dot(self, u)
    }
}

/// Forces and moments of the backward recursion, as [`Load`]s: affine in the unknowns by
/// default.
#[derive(Clone, Debug)]
pub struct Loads<T: Real, L: Load<T> = Aff3<T>> {
    /// Force on each body from its parent, body frame.
    pub force: Vec<L>,
    /// Moment on each body from its parent about the joint point, body frame, motor
    /// torque included.
    pub moment: Vec<L>,
    /// `τ_b`: component of `moment` along the joint axis.
    pub axial: Vec<L::Scalar>,
    /// Total force of the base on the mechanism (bearings, motors, tendon exits), base frame.
    pub base_force: L,
    /// Total moment of the base on the mechanism about the base origin, base frame.
    pub base_moment: L,
}

impl<T: Real, L: Load<T>> Loads<T, L> {
    /// Zero loads on `bodies` bodies and the base, over `unknowns` unknowns.
    pub fn new(bodies: usize, unknowns: usize) -> Self {
        let zero = L::known(Vec3::zero(), unknowns);
        Loads {
            force: vec![zero; bodies],
            moment: vec![zero; bodies],
            axial: vec![zero.dot(Vec3::unit_z()); bodies],
            base_force: zero,
            base_moment: zero,
        }
    }
}

/// `ᵇR_L` for a contact on pulley body `b` whose segment is fixed in frame `L`.
fn contact_rotation<T: Real>(model: &Model<T>, motion: &[Motion<T>], c: &Contact<T>) -> Mat3<T> {
    let b = c.body.expect("a body contact");
    let own = motion[b].rotation;
    match c.via {
        Via::Carrier => own,
        Via::CarrierParent => {
            let carrier = model.bodies[b].parent.expect("a link carrier");
            own * motion[carrier].rotation
        }
        Via::CarrierChild(l) => own * motion[l].rotation.transpose(),
    }
}

/// The backward recursion. `tensions[s][k]` is the tension of segment `k` of strand `s`
/// (affine in the unknowns), or `None` to leave every tendon out (the expanded-tree
/// recursion behind `M`, `h` and `g`, where pulleys act through their couplings).
/// `external` includes the model's external wrench.
pub fn backward<T: Real, L: Load<T>>(
    model: &Model<T>,
    motion: &[Motion<T>],
    tensions: Option<&[Vec<L::Scalar>]>,
    unknowns: usize,
    external: bool,
    out: &mut Loads<T, L>,
) {
    let nb = model.bodies.len();
    // Applied forces accumulate per body: `out.force` and `out.moment` hold, until a body
    // is processed, the sum of forces applied to it and their moment about its origin.
    for i in 0..nb {
        out.force[i] = L::known(Vec3::zero(), unknowns);
        out.moment[i] = L::known(Vec3::zero(), unknowns);
    }
    out.base_force = L::known(Vec3::zero(), unknowns);
    out.base_moment = L::known(Vec3::zero(), unknowns);

    // Tendon forces (Eqs. 17-18): each segment pulls its `from` pulley along +dir and its
    // `to` pulley along −dir, at the contact points.
    if let Some(tensions) = tensions {
        for (strand, ts) in model.strands.iter().zip(tensions) {
            for (seg, t) in strand.segments.iter().zip(ts) {
                let pull = L::along(seg.dir, t);
                for (contact, f) in [(&seg.from, pull), (&seg.to, pull.neg())] {
                    match contact.body {
                        Some(b) => {
                            let r = contact_rotation(model, motion, contact);
                            let f_b = f.rotate(&r);
                            let at = r.mul_vec(contact.rel);
                            out.force[b] = out.force[b].add(&f_b);
                            out.moment[b] = out.moment[b].add(&f_b.moment_of(at));
                        }
                        None => {
                            // The ground exit: the base holds the tendon there and pulls it
                            // on towards the actuator.
                            let on_tendon = f.neg();
                            out.base_force = out.base_force.add(&on_tendon);
                            out.base_moment =
                                out.base_moment.add(&on_tendon.moment_of(contact.rel));
                        }
                    }
                }
            }
        }
    }
    if let Some(w) = model.external_wrench.as_ref().filter(|_| external) {
        let f = L::known(w.force, unknowns);
        out.force[w.link] = out.force[w.link].add(&f);
        out.moment[w.link] = out.moment[w.link]
            .add(&f.moment_of(w.point))
            .add_known(w.moment);
    }

    for i in (0..nb).rev() {
        if tensions.is_none() && model.patterns[i].inert {
            // Nothing loads it without tendons, and it carries nothing: its loads stay the
            // zeros they were reset to.
            out.axial[i] = out.force[i].dot(Vec3::unit_z());
            continue;
        }
        let b = &model.bodies[i];
        let m = &motion[i];
        let pattern = &model.patterns[i];
        let joint_point = -b.joint_to_origin;
        // Eq. 19 / 23: force from the parent.
        let f = L::known(m.inertial_force, unknowns).sub(&out.force[i]);
        // Eq. 20 / 24: moment from the parent about the joint point (the origin, where the
        // pattern knows them to be one).
        let n = L::known(m.inertial_moment, unknowns).sub(&out.moment[i]);
        let n = if pattern.origin_at_joint {
            n
        } else {
            n.sub(&f.moment_of(joint_point))
        };
        out.axial[i] = n.dot(b.axis);
        // The reaction on the parent: −f at the joint point, −n.
        let r = m.rotation;
        let f_parent = if b.spins && matches!(b.kind, BodyKind::Pulley { .. }) {
            // A spinning pulley: its frame turns with it, and `Rᵀ (m R a_J)` is `m a_J` only
            // to rounding, in a direction the spin angle scrambles. For an idler whose mass
            // sits on its carrier's joint axis, that residue (u·m|a_J|) reaches joints its
            // mass does not otherwise load (a centripetal force through an axis has no
            // moment about it) and can swamp them when the pulley is heavy. So the part of
            // its inertial force due to the joint point's acceleration stays in the parent's
            // frame, where `a_J` was computed; only the rest turns.
            let rel = if pattern.origin_at_joint && pattern.com_at_origin {
                Vec3::zero()
            } else {
                let pc = b.joint_to_origin + b.com;
                m.omega_dot.cross(pc) + m.omega.cross(m.omega.cross(pc))
            };
            L::known(rel.scale(b.mass), unknowns)
                .sub(&out.force[i])
                .rotate_back(&r)
                .add_known(m.joint_accel.scale(b.mass))
                .neg()
        } else {
            f.rotate_back(&r).neg()
        };
        let n_parent = n.rotate_back(&r).neg();
        let at = b.pre.translation;
        let moment_parent = if pattern.joint_at_parent_origin {
            n_parent
        } else {
            n_parent.add(&f_parent.moment_of(at))
        };
        match b.parent {
            Some(p) => {
                out.force[p] = out.force[p].add(&f_parent);
                out.moment[p] = out.moment[p].add(&moment_parent);
            }
            None => {
                out.base_force = out.base_force.sub(&f_parent);
                out.base_moment = out.base_moment.sub(&moment_parent);
            }
        }
        out.force[i] = f;
        out.moment[i] = n;
    }
}
