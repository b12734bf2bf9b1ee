//! The bodies of a mechanism: links from their DH parameters, then pulleys from their
//! placements, each with its mass properties checked. Invariant: links are bodies `0..n`
//! in file order and pulleys follow in file order (the order parameter slots assume).

use super::locate::candidates;
use super::ranges::{shown, Range, MAX_MU, MIN_RADIUS};
use super::Validator;
use crate::error::Result;
use crate::format::{InertiaSpec, LinkSpec, MechanismFile, Num, Placement, PulleySpec};
use crate::model::{Body, BodyKind, PulleyRole};
use crate::real::Real;
use crate::spatial::{sin_cos_snapped, Mat3, Transform, Vec3};
use crate::transmission::{joint_parent, PulleyInfo};
use nalgebra::Matrix3;

/// The nominal values of a body's mass properties.
pub(super) struct MassProperties {
    pub(super) mass: f64,
    pub(super) com: [f64; 3],
    /// xx, yy, zz, xy, xz, yz
    pub(super) inertia: [f64; 6],
}

/// Angles this close to a multiple of π/2 are taken as exactly that multiple, so that a
/// twist written `1.5707963267948966` gives exact zeros and ones (which the code generator
/// then removes).
const RIGHT_ANGLE_SNAP: f64 = 1e-12;

/// `sin` and `cos` of `angle`, exact at multiples of π/2 (within `RIGHT_ANGLE_SNAP`).
fn snapped_sin_cos(angle: f64) -> (f64, f64) {
    sin_cos_snapped(angle, RIGHT_ANGLE_SNAP)
}

/// The rotation by `angle` about the x, y or z axis (`axis` 0, 1, 2), exact at right
/// angles.
fn snapped_rot(axis: usize, angle: f64) -> Mat3<f64> {
    let (s, c) = snapped_sin_cos(angle);
    match axis {
        0 => Mat3::from_rows([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]),
        1 => Mat3::from_rows([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]),
        _ => Mat3::rot_z(s, c),
    }
}

/// `TransZ(d) · TransX(a) · RotX(α)` of a DH link (Eq. 1), `twist` being `RotX(α)`. Generic
/// in the lengths, so that `tendyn equations` builds the link frames with `a` and `d` as
/// symbols ([`crate::Model::symbolic_geometry`]).
pub fn dh_post<T: Real>(a: T, d: T, twist: &Mat3<f64>) -> Transform<T> {
    Transform {
        rotation: twist.map(T::from_f64),
        translation: Vec3::new(a, T::zero(), d),
    }
}

/// A link's joint axis and the vector `P` from its joint point to its frame's origin (Eq. 7),
/// both in the link frame, from its `post` transform: `postᵀ z` and `postᵀ (a, 0, d) = (a,
/// d sin α, d cos α)`.
pub fn axis_and_origin<T: Real>(post: &Transform<T>) -> (Vec3<T>, Vec3<T>) {
    let z = Vec3::new(T::zero(), T::zero(), T::one());
    (
        post.rotation.tr_mul_vec(z),
        post.rotation.tr_mul_vec(post.translation),
    )
}

/// The housing frame of a pulley on the axis of joint `j` at `height`, carried by link `j`
/// itself: `post_j⁻¹ · TransZ(height)` (Eq. 8), whose origin is `−a_j` along x.
pub fn on_own_joint_axis<T: Real>(link_post: &Transform<T>, height: T) -> Transform<T> {
    let lift = Transform {
        rotation: Mat3::identity(),
        translation: Vec3::new(T::zero(), T::zero(), height),
    };
    link_post.inverse().compose(&lift)
}

struct InertiaValues {
    xx: f64,
    yy: f64,
    zz: f64,
    xy: f64,
    xz: f64,
    yz: f64,
}

/// The symmetric inertia tensor of the entries xx, yy, zz, xy, xz, yz.
fn inertia_matrix(i: [f64; 6]) -> Mat3<f64> {
    let [xx, yy, zz, xy, xz, yz] = i;
    Mat3::from_rows([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
}

impl Validator<'_> {
    /// The links, then the pulleys in file order, with what routing needs of each pulley.
    pub(super) fn bodies(&self, f: &MechanismFile) -> Result<(Vec<Body<f64>>, Vec<PulleyInfo>)> {
        let n = f.links.len();
        let mut bodies: Vec<Body<f64>> = f
            .links
            .iter()
            .enumerate()
            .map(|(j, l)| self.link_body(j, l, n))
            .collect::<Result<_>>()?;

        let mut pulleys: Vec<PulleyInfo> = Vec::new();
        for p in &f.pulleys {
            let (body, info) = self.pulley_body(p, f, &bodies, n)?;
            pulleys.push(PulleyInfo {
                body: bodies.len(),
                ..info
            });
            bodies.push(body);
        }
        Ok((bodies, pulleys))
    }

    /// A body's mass properties at the parameters' declared values.
    fn mass_of(&self, mass: &Num, com: &[Num; 3], i: &InertiaSpec) -> MassProperties {
        MassProperties {
            mass: self.num(mass),
            com: self.nums(com),
            inertia: [&i.xx, &i.yy, &i.zz, &i.xy, &i.xz, &i.yz].map(|x| self.num(x)),
        }
    }

    /// Mass, centre of mass and inertia: finite, within their ranges, and of a body that can
    /// exist (no inertia without mass, positive semi-definite, the triangle inequality).
    pub(super) fn mass_properties(&self, item: &str, mp: &MassProperties) -> Result<()> {
        let (mass, com) = (mp.mass, mp.com);
        let [xx, yy, zz, xy, xz, yz] = mp.inertia;
        self.finite(item, "mass", &[mass])?;
        self.finite(item, "com", &com)?;
        self.finite(item, "inertia", &mp.inertia)?;
        let i = InertiaValues {
            xx,
            yy,
            zz,
            xy,
            xz,
            yz,
        };
        let m = Matrix3::new(i.xx, i.xy, i.xz, i.xy, i.yy, i.yz, i.xz, i.yz, i.zz);
        let nonzero_inertia = m.iter().any(|&x| x != 0.0);
        if mass < 0.0 {
            return Err(self.invalid_field(
                item,
                "mass",
                format!(
                    "mass is {} kg; a mass must be positive (or zero for a massless body)",
                    shown(mass)
                ),
            ));
        }
        self.within(item, "mass", &[mass], Range::Mass)?;
        self.within(item, "com", &com, Range::Length)?;
        self.within(item, "inertia", &mp.inertia, Range::Inertia)?;
        if mass == 0.0 && nonzero_inertia {
            return Err(self.invalid_field(
                item,
                "mass",
                "mass is zero but the inertia is not: a body with inertia needs a positive mass; \
                 give it its mass or drop its inertia",
            ));
        }
        if nonzero_inertia {
            let eig = m.symmetric_eigen().eigenvalues;
            let mut l = [eig[0], eig[1], eig[2]];
            l.sort_by(f64::total_cmp);
            let scale = l[2].abs().max(f64::MIN_POSITIVE);
            if l[0] < -1e-12 * scale {
                return Err(self.invalid_field(
                    item,
                    "inertia",
                    format!(
                        "inertia is not positive semi-definite (principal moments {:.6e}, {:.6e}, \
                         {:.6e} kg·m²); off-diagonal entries are tensor entries I_xy = -∫xy dm, \
                         check their signs and sizes",
                        l[0], l[1], l[2]
                    ),
                ));
            }
            if l[0] + l[1] < l[2] * (1.0 - 1e-12) {
                return Err(self.invalid_field(
                    item,
                    "inertia",
                    format!(
                        "principal moments {:.6e}, {:.6e}, {:.6e} kg·m² violate the triangle \
                         inequality (the two smaller must add up to at least the largest): no \
                         mass distribution has this inertia",
                        l[0], l[1], l[2]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A link's `range`: finite angles within their range of magnitude, lower below upper.
    fn joint_range(&self, l: &LinkSpec) -> Result<()> {
        let Some(range) = l.range else {
            return Ok(());
        };
        self.finite(&l.name, "range", &range)?;
        self.within(&l.name, "range", &range, Range::Angle)?;
        if range[0] >= range[1] {
            return Err(self.invalid_field(
                &l.name,
                "range",
                format!(
                    "`range` is ({}, {}); its lower end must be below its upper one",
                    range[0], range[1]
                ),
            ));
        }
        Ok(())
    }

    /// The body of link `j`, turned by joint `j` (its DH parameters checked).
    fn link_body(&self, j: usize, l: &LinkSpec, n: usize) -> Result<Body<f64>> {
        let d = &l.dh;
        self.finite(&l.name, "dh", &[d.a, d.alpha, d.d, d.offset])?;
        self.within(&l.name, "a", &[d.a], Range::Length)?;
        self.within(&l.name, "d", &[d.d], Range::Length)?;
        self.within(&l.name, "alpha", &[d.alpha], Range::Angle)?;
        self.within(&l.name, "offset", &[d.offset], Range::Angle)?;
        let mp = self.mass_of(&l.mass, &l.com, &l.inertia);
        self.mass_properties(&l.name, &mp)?;
        let friction = self.friction(&l.name, l.friction.as_ref())?;
        self.joint_range(l)?;
        let post = dh_post(d.a, d.d, &snapped_rot(0, d.alpha));
        let (axis, joint_to_origin) = axis_and_origin(&post);
        let mut coupling = vec![0.0; n];
        coupling[j] = 1.0;
        Ok(Body {
            name: l.name.clone(),
            kind: BodyKind::Link { joint: j },
            parent: joint_parent(j),
            pre: Transform::identity(),
            post,
            offset: d.offset,
            coupling,
            spins: true,
            mass: mp.mass,
            com: Vec3::from_array(mp.com),
            inertia: inertia_matrix(mp.inertia),
            axis,
            joint_to_origin,
            friction,
        })
    }

    /// The body of a pulley and what routing needs of it (its body index is set by the
    /// caller, which knows it).
    fn pulley_body(
        &self,
        p: &PulleySpec,
        f: &MechanismFile,
        links: &[Body<f64>],
        n: usize,
    ) -> Result<(Body<f64>, PulleyInfo)> {
        let mp = self.mass_of(&p.mass, &p.com, &p.inertia);
        self.mass_properties(&p.name, &mp)?;
        let friction = self.friction(&p.name, p.friction.as_ref())?;
        if p.fixed && friction.is_some() {
            return Err(self.invalid_field(
                &p.name,
                "friction",
                "a `fixed` drum does not turn on its carrier, so its bearing has no friction: \
                 remove `friction`, or drop `fixed: true` if the pulley turns (a tendon sliding \
                 over a fixed guide loses tension by its `mu`)"
                    .to_string(),
            ));
        }
        let mu = p.mu.unwrap_or(0.0);
        self.finite(&p.name, "mu", &[mu])?;
        if !p.fixed && p.mu.is_some() {
            return Err(self.invalid_field(
                &p.name,
                "mu",
                "`mu` is the capstan coefficient of a fixed guide a tendon slides over; this \
                 pulley turns with the tendon, so nothing slides: remove `mu` (its bearing's \
                 losses are `friction`), or add `fixed: true` if it is a pin",
            ));
        }
        if !(0.0..=MAX_MU).contains(&mu) {
            return Err(self.invalid_field(
                &p.name,
                "mu",
                format!(
                    "`mu` is {}; a capstan coefficient is between 0 (frictionless) and \
                     {MAX_MU} (format.md §6a)",
                    shown(mu)
                ),
            ));
        }
        self.finite(&p.name, "radius", &[p.radius])?;
        if p.radius <= 0.0 {
            return Err(self.invalid_field(
                &p.name,
                "radius",
                format!("radius is {} m; a pitch radius must be positive", p.radius),
            ));
        }
        if p.radius < MIN_RADIUS {
            return Err(self.invalid_field(
                &p.name,
                "radius",
                format!(
                    "`radius` is {} m, below the smallest pitch radius of {MIN_RADIUS:e} m \
                     (format.md §12, ranges of magnitude): couplings are ratios of radii and the \
                     tension system is inverted, which smaller radii overflow or leave without \
                     precision; check its unit (metres) and its exponent",
                    shown(p.radius)
                ),
            ));
        }
        self.within(&p.name, "radius", &[p.radius], Range::Length)?;
        let carrier = if p.carrier == "base" {
            None
        } else {
            Some(
                f.links
                    .iter()
                    .position(|l| l.name == p.carrier)
                    .ok_or_else(|| {
                        self.invalid(
                            &p.name,
                            format!(
                                "its carrier `{}` does not exist; a carrier is `base` or a link \
                                 name ({})",
                                p.carrier,
                                candidates("links", f.links.iter().map(|l| l.name.as_str()))
                            ),
                        )
                    })?,
            )
        };
        let (pre, coaxial) = match &p.at {
            Placement::Joint { joint, height } => {
                self.finite(&p.name, "height", &[*height])?;
                self.within(&p.name, "height", &[*height], Range::Length)?;
                let j = f
                    .links
                    .iter()
                    .position(|l| &l.name == joint)
                    .ok_or_else(|| {
                        self.invalid(
                            &p.name,
                            format!(
                                "`at: Joint` names `{joint}`, which is not a link; name the link \
                                 the joint moves ({})",
                                candidates("links", f.links.iter().map(|l| l.name.as_str()))
                            ),
                        )
                    })?;
                let pre = if carrier == joint_parent(j) {
                    Transform {
                        rotation: Mat3::identity(),
                        translation: Vec3::new(0.0, 0.0, *height),
                    }
                } else if carrier == Some(j) {
                    on_own_joint_axis(&links[j].post, *height)
                } else {
                    let proximal = j
                        .checked_sub(1)
                        .map_or("base", |k| f.links[k].name.as_str());
                    return Err(self.invalid(
                        &p.name,
                        format!(
                            "sits on the axis of joint `{joint}` but is carried by `{}`; a pulley \
                             on a joint axis is carried by one of the two bodies that joint connects \
                             (`{proximal}` or `{joint}`)",
                            p.carrier
                        ),
                    ));
                };
                (pre, Some((j, *height)))
            }
            Placement::Pose { origin, rpy } => {
                self.finite(&p.name, "origin", origin)?;
                self.finite(&p.name, "rpy", rpy)?;
                self.within(&p.name, "origin", origin, Range::Length)?;
                self.within(&p.name, "rpy", rpy, Range::Angle)?;
                let r = snapped_rot(2, rpy[2]) * snapped_rot(1, rpy[1]) * snapped_rot(0, rpy[0]);
                (
                    Transform {
                        rotation: r,
                        translation: Vec3::from_array(*origin),
                    },
                    None,
                )
            }
        };
        // An axisymmetric pulley's inertia does not change as it spins, so its frame may
        // stay the housing frame and its angle never needs a sine or cosine. Parameters can
        // take any value at run time, so a pulley with one in its mass properties spins.
        let [xx, yy, _, xy, xz, yz] = mp.inertia;
        let parametric = [
            &p.com[0],
            &p.com[1],
            &p.inertia.xx,
            &p.inertia.yy,
            &p.inertia.xy,
            &p.inertia.xz,
            &p.inertia.yz,
        ]
        .iter()
        .any(|n| matches!(n, Num::Param(_)));
        let axisymmetric = !parametric
            && mp.com[0] == 0.0
            && mp.com[1] == 0.0
            && xx == yy
            && xy == 0.0
            && xz == 0.0
            && yz == 0.0;
        Ok((
            Body {
                name: p.name.clone(),
                kind: BodyKind::Pulley {
                    radius: p.radius,
                    role: PulleyRole::Fixed,
                },
                parent: carrier,
                pre,
                post: Transform::identity(),
                offset: 0.0,
                coupling: vec![0.0; n],
                spins: !(p.fixed || axisymmetric),
                mass: mp.mass,
                com: Vec3::from_array(mp.com),
                inertia: inertia_matrix(mp.inertia),
                axis: Vec3::unit_z(),
                joint_to_origin: Vec3::zero(),
                friction,
            },
            PulleyInfo {
                name: p.name.clone(),
                at: self.locate(&p.name),
                body: 0,
                carrier,
                coaxial,
                radius: p.radius,
                fixed: p.fixed,
                mu,
            },
        ))
    }
}
