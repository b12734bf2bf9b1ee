//! Tendon routing → pulley couplings, segment geometry, structure matrix and the tension
//! system (paper Eqs. 9-10, 17-18, 26, 31, 33-35).
//!
//! # The derivation
//! Tendons are inextensible and do not slip on pulleys. A tendon is followed from the body
//! it is fixed to (an anchor drum, or the driven pulley of a loop) towards its ground exit
//! (or the driving pulley of a loop). Every straight segment is fixed in one link's frame:
//! both pitch circles it touches must be fixed in that frame (a pulley's circle is fixed in
//! its carrier and, when it is coaxial with a joint, in both bodies of that joint). The
//! segment is the common tangent of the two circles on the sides the route names, so its
//! direction and contact points are constants of that frame (Eq. 17).
//!
//! Where the tendon goes round a pulley of radius `r` with turn `s` (`+1` counter-clockwise
//! about the pulley axis, followed towards the ground), the length wrapped there grows by
//! `-s r θ̇` when the frame of the incoming segment turns by `θ̇` relative to the frame of
//! the outgoing one about that axis. Summing over the route gives the rate at which the
//! ground end is pulled in, `ẋ = Σ s r θ̇`, whose gradient in `q̇` is the tendon's column
//! of the structure matrix `A` (so that `Q = A T` by virtual work). A free idler's rim
//! moves with the tendon, which fixes its angle relative to its carrier as a linear
//! function of `q` (Eqs. 9-10, 26, 31, 34); a loop's driving pulley follows from the
//! loop's length staying constant.
//!
//! Validation computes all of this once, in `f64`. The rates and contact points are also
//! generic over the scalar (`Routing::geometry_and_rates`): `tendyn equations` traces them
//! again with the pitch radii as symbols ([`crate::Model::symbolic_geometry`]), so that what
//! it prints is this derivation, not a copy of it. Decisions (the frame a segment is fixed in, its
//! tangent direction, which frames turn relative to which) are taken in `f64` both times.

use crate::error::{Error, Location, Result};
use crate::format::Turn;
use crate::model::{Body, Contact, Guide, IdlerStep, Loop, Motor, MotorKind, Row, Segment, Tendon};
use crate::model::{Unknown, Via};
use crate::real::Real;
use crate::spatial::{sin_cos_snapped, Mat3, Transform, Vec3};

/// A frame a segment can be fixed in: `None` is the base, `Some(i)` link body `i`.
pub type Frame = Option<usize>;

/// What validation knows about a pulley before its coupling is derived.
#[derive(Clone, Debug)]
pub struct PulleyInfo {
    /// The pulley's name.
    pub name: String,
    /// Where it is defined in the file.
    pub at: Location,
    /// Its body index in the model.
    pub body: usize,
    /// The body that carries its bearing (or, for a fixed drum, that it is part of).
    pub carrier: Frame,
    /// Joint (0-based) it is coaxial with, and its height along that joint's axis.
    pub coaxial: Option<(usize, f64)>,
    /// Pitch radius (m).
    pub radius: f64,
    /// A drum that is part of its carrier (`fixed: true`).
    pub fixed: bool,
    /// The capstan coefficient of a fixed pulley a tendon slides over (0 without).
    pub mu: f64,
}

impl PulleyInfo {
    /// Joint and height of a pulley on the axis of the joint that moves its own carrier
    /// (placed by `post⁻¹ · TransZ(height)`, `validate::on_own_joint_axis`).
    pub fn on_own_joint_axis(&self) -> Option<(usize, f64)> {
        self.coaxial.filter(|&(j, _)| self.carrier == Some(j))
    }
}

/// A route as validation resolved it: pulley indices (into the `PulleyInfo` list) with
/// turns, and where it ends.
#[derive(Clone, Debug)]
pub struct Route {
    /// The tendon's name, or `LOOP/ccw`, `LOOP/cw` for a side of a loop.
    pub name: String,
    /// Where its tendon or loop is defined in the file.
    pub at: Location,
    /// The pulleys from the anchor (or driven pulley) on, each with the tendon's turn round
    /// it; a loop's side has its driven pulley only.
    pub wraps: Vec<(usize, Turn)>,
    /// Where it leaves the last pulley of `wraps` for.
    pub end: RouteEnd,
}

/// Where a route ends.
#[derive(Clone, Debug)]
pub enum RouteEnd {
    /// Leaves towards an actuator through this point of the base frame.
    Exit([f64; 3]),
    /// Ends fixed on this (driving) pulley, turning this way round it.
    Pulley(usize, Turn),
}

/// A rate `θ̇` as a linear function of `q̇`, plus the rates of named pulley angles that are
/// coordinates of their own in the tension system (driving pulleys).
#[derive(Clone, Debug, PartialEq)]
pub struct Rate<T = f64> {
    /// Coefficient of each `q̇_j`, in joint order (rad/rad for an angle, m/rad for a pull
    /// rate).
    pub joints: Vec<T>,
    /// Coefficients of the angles of driving pulleys relative to their carriers, each with
    /// its pulley index (into the `PulleyInfo` list).
    pub pulleys: Vec<(usize, T)>,
}

impl<T: Real> Rate<T> {
    fn zero(n: usize) -> Self {
        Rate {
            joints: vec![T::zero(); n],
            pulleys: Vec::new(),
        }
    }
    fn add_scaled(&mut self, o: &Rate<T>, s: T) {
        for (a, &b) in self.joints.iter_mut().zip(&o.joints) {
            *a = *a + s * b;
        }
        for &(p, c) in &o.pulleys {
            self.add_pulley(p, s * c);
        }
    }
    /// `self += (s · o) / r`: one rounding per entry where `s` is a sign, and `±x/r` by
    /// name where `r` is a symbol.
    fn add_divided(&mut self, o: &Rate<T>, s: T, r: T) {
        for (a, &b) in self.joints.iter_mut().zip(&o.joints) {
            *a = *a + s * b / r;
        }
        for &(p, c) in &o.pulleys {
            self.add_pulley(p, s * c / r);
        }
    }
    fn add_pulley(&mut self, p: usize, c: T) {
        match self.pulleys.iter_mut().find(|(q, _)| *q == p) {
            Some((_, v)) => *v = *v + c,
            None => self.pulleys.push((p, c)),
        }
    }
}

/// One strand with its geometry and the rates the tension system needs.
#[derive(Clone, Debug)]
pub struct StrandGeometry {
    /// Its straight segments, from the anchored (or driven-pulley) end on.
    pub segments: Vec<Segment<f64>>,
    /// `idlers[k]`: the idler (or guide) between segments `k` and `k + 1`.
    pub idlers: Vec<IdlerStep>,
    /// `ẋ` of the strand: joints, plus the driving-pulley angles at its two ends.
    pub pull_rate: Rate,
    /// `segment_rates[k]`: segment `k`'s share of `pull_rate` (they sum to it), the rate
    /// at which the rims at its two ends pull it in, relative to the frame it is fixed in.
    /// Where the tension differs from segment to segment, `Σ_k T_k (segment_rates[k] · q̇)`
    /// is the tendon's virtual power on the bodies with every turning idler held to its
    /// carrier (an idler's own spin takes the tension step across it, Eq. 24b): with
    /// capstan friction on guides, whose rims are their carriers, the state's `E`.
    pub segment_rates: Vec<Rate>,
}

fn norm(v: Vec3<f64>) -> f64 {
    v.dot(v).sqrt()
}

fn unit(v: Vec3<f64>) -> Vec3<f64> {
    v.scale(1.0 / norm(v))
}

/// Frame of the body on the proximal side of joint `j`.
pub fn joint_parent(j: usize) -> Frame {
    if j == 0 {
        None
    } else {
        Some(j - 1)
    }
}

/// What [`Routing::trace`] derives a route's geometry and rates from: the bodies and
/// pulleys as validation built them (it reads their placements, not their couplings).
pub struct Routing<'a> {
    /// Every body of the model (only their placements are read).
    pub bodies: &'a [Body<f64>],
    /// Every pulley, in file order.
    pub pulleys: &'a [PulleyInfo],
    /// Number of joints `n`.
    pub dof: usize,
}

impl Routing<'_> {
    /// Frames in which pulley `p`'s pitch circle is fixed.
    pub fn frames_of(&self, p: usize) -> Vec<Frame> {
        let info = &self.pulleys[p];
        let mut f = vec![info.carrier];
        if let Some((j, _)) = info.coaxial {
            for other in [joint_parent(j), Some(j)] {
                if other != info.carrier {
                    f.push(other);
                }
            }
        }
        f
    }

    /// Centre and unit axis of pulley `p`'s pitch circle in `frame` (one of `frames_of`).
    fn circle_in(&self, p: usize, frame: Frame) -> (Vec3<f64>, Vec3<f64>) {
        let info = &self.pulleys[p];
        let body = &self.bodies[info.body];
        if frame == info.carrier {
            return (body.pre.translation, body.pre.rotation.column(2));
        }
        let (j, h) = info
            .coaxial
            .expect("only coaxial pulleys have a second frame");
        let on_axis = Vec3::new(0.0, 0.0, h);
        if frame == Some(j) {
            let post = self.bodies[j].post.inverse();
            (post.apply(on_axis), post.rotation.column(2))
        } else {
            (on_axis, Vec3::unit_z())
        }
    }

    /// `θ̇` of frame (or pulley body) `a` relative to frame `b`, about the axis of pulley
    /// `p`; both must be among the frames `p`'s circle is fixed in.
    fn relative_rate<T: Real>(&self, a: Frame, b: Frame, p: usize) -> Rate<T> {
        let mut r = Rate::zero(self.dof);
        if a == b {
            return r;
        }
        let (j, _) = self.pulleys[p]
            .coaxial
            .expect("distinct frames of one circle come from a coaxial joint");
        r.joints[j] = T::from_f64(if a == Some(j) { 1.0 } else { -1.0 });
        r
    }

    /// `θ̇` of pulley `s`'s own body relative to `frame`, given its coupling `c_s`.
    fn body_rate<T: Real>(&self, s: usize, coupling: &Rate<T>, frame: Frame) -> Rate<T> {
        let mut r = coupling.clone();
        r.add_scaled(
            &self.relative_rate(self.pulleys[s].carrier, frame, s),
            T::one(),
        );
        r
    }

    /// The frame two circles (or a circle and the base) share.
    fn common_frame(&self, route: &Route, p: usize, q: Option<usize>) -> Result<Frame> {
        let fp = self.frames_of(p);
        let fq = match q {
            Some(q) => self.frames_of(q),
            None => vec![None],
        };
        let shared: Vec<Frame> = fp.iter().copied().filter(|f| fq.contains(f)).collect();
        let qname = q.map_or("the ground exit".to_string(), |q| {
            format!("pulley `{}`", self.pulleys[q].name)
        });
        match shared.as_slice() {
            [f] => Ok(*f),
            [] => Err(Error::Routing {
                item: route.name.clone(),
                at: route.at,
                problem: format!(
                    "the segment from pulley `{}` to {} is not fixed in any one link: \
                     a pulley's circle is fixed only in its carrier and, when it sits on a \
                     joint axis, in the two bodies of that joint; put both ends on a common \
                     body or add an idler on the joint axis between them",
                    self.pulleys[p].name, qname
                ),
                implied: None,
            }),
            _ => Err(Error::Routing {
                item: route.name.clone(),
                at: route.at,
                problem: format!(
                    "pulley `{}` and {} sit on the same joint axis: a segment cannot run along it",
                    self.pulleys[p].name, qname
                ),
                implied: None,
            }),
        }
    }

    fn via(&self, p: usize, frame: Frame) -> Via {
        let carrier = self.pulleys[p].carrier;
        if frame == carrier {
            Via::Carrier
        } else if carrier.is_some_and(|c| joint_parent(c) == frame) {
            Via::CarrierParent
        } else {
            Via::CarrierChild(frame.expect("a child frame is a link"))
        }
    }

    /// Acting angle (Eq. 17) of a contact: angle of (contact − centre) about the pulley
    /// axis from the pulley frame's x axis, with every joint at zero.
    fn acting_angle(&self, p: usize, frame: Frame, rel: Vec3<f64>) -> f64 {
        let info = &self.pulleys[p];
        let body = &self.bodies[info.body];
        // rotation of `frame` in the carrier frame at q = 0
        let frame_in_carrier = if frame == info.carrier {
            Mat3::identity()
        } else {
            let (j, _) = info.coaxial.expect("coaxial");
            let link = &self.bodies[j];
            let down = crate::spatial::rot_z(link.offset) * link.post.rotation;
            if frame == Some(j) {
                down
            } else {
                down.transpose()
            }
        };
        let v = body.pre.rotation.tr_mul_vec(frame_in_carrier.mul_vec(rel));
        v.y.atan2(v.x)
    }

    /// The segment from pulley `p` (turn `sp`) to pulley `q` (turn `sq`) or to the exit.
    ///
    /// Its direction is decided in `f64`; its contact points are `r` times a unit vector
    /// (Eq. 17), `radius(p)` being pulley `p`'s pitch radius in the scalar `T`.
    fn segment<T: Real>(
        &self,
        route: &Route,
        p: usize,
        sp: Turn,
        to: SegmentEnd,
        radius: &dyn Fn(usize) -> T,
    ) -> Result<Segment<T>> {
        let q = match to {
            SegmentEnd::Pulley(q, _) => Some(q),
            SegmentEnd::Exit(_) => None,
        };
        let frame = self.common_frame(route, p, q)?;
        let (cp, np) = self.circle_in(p, frame);
        let rp = self.pulleys[p].radius;
        let tp = turn_sign(sp);
        let (cq, nq, rq, tq) = match to {
            SegmentEnd::Pulley(q, sq) => {
                let (c, n) = self.circle_in(q, frame);
                (c, n, self.pulleys[q].radius, turn_sign(sq))
            }
            SegmentEnd::Exit(x) => (Vec3::from_array(x), np, 0.0, 1.0),
        };
        let qname = q.map_or("the ground exit".to_string(), |q| {
            format!("pulley `{}`", self.pulleys[q].name)
        });
        let fail = |problem: String| Error::Routing {
            item: route.name.clone(),
            at: route.at,
            problem: format!(
                "segment from pulley `{}` to {}: {problem}",
                self.pulleys[p].name, qname
            ),
            implied: None,
        };
        let scale = 1.0 + norm(cq - cp) + rp + rq;
        // Validation keeps every length within its range (format.md §12), so this only
        // guards the tests below, which an infinite tolerance would pass.
        let too_large = || {
            fail(
                "its geometry is too large to compute with (a distance or direction is not \
                 finite); check the sizes and units of the lengths along it"
                    .to_string(),
            )
        };
        if !scale.is_finite() {
            return Err(too_large());
        }
        let tol = 1e-9 * scale;
        let cross = np.cross(nq);
        let dir = if norm(cross) < 1e-12 {
            // Parallel axes: the tangent lies in the common plane (classical belt tangent).
            let sigma = np.dot(nq).signum();
            let delta = cq - cp;
            if delta.dot(np).abs() > tol {
                return Err(fail(format!(
                    "the two circles are not in one plane (offset {:.3e} m along the axis); \
                     move one of them along its axis so that the tendon runs in their common plane",
                    delta.dot(np)
                )));
            }
            let (ex, ey) = plane_basis(np);
            let (dx, dy) = (delta.dot(ex), delta.dot(ey));
            let dist = (dx * dx + dy * dy).sqrt();
            let rho = tp * rp - sigma * tq * rq;
            if dist <= rho.abs() {
                return Err(fail(format!(
                    "no common tangent on the given sides: the centres are {dist:.4e} m apart \
                     but the tangent needs more than {:.4e} m; move the pulleys apart or change a turn",
                    rho.abs()
                )));
            }
            let psi = dy.atan2(dx);
            // A tangent along an axis of the plane is computed as the f64 nearest a multiple
            // of π/2, whose sine or cosine is a rounding leftover (1.2e-16), not zero.
            let asin = (rho / dist).asin();
            let delta_angle = psi + asin;
            // (Within the rounding of the sum, which may cancel to nearly zero.)
            let within = 4.0 * f64::EPSILON * (psi.abs() + asin.abs());
            let (sin, cos) = sin_cos_snapped(delta_angle, within);
            ex.scale(cos) + ey.scale(sin)
        } else {
            // Non-parallel axes: the tangent is along the intersection of the two planes,
            // and the circles must be placed so that it touches both.
            let u = unit(cross);
            let mut best: Option<(f64, Vec3<f64>)> = None;
            for d in [u, -u] {
                let a = cp + d.cross(np).scale(tp * rp);
                let b = cq + d.cross(nq).scale(tq * rq);
                let v = b - a;
                let along = v.dot(d);
                let resid = norm(v - d.scale(along));
                let bad = if along > 0.0 {
                    resid
                } else {
                    resid + along.abs() + 1.0
                };
                if best.is_none_or(|(r, _)| bad < r) {
                    best = Some((bad, d));
                }
            }
            let (bad, d) = best.expect("two candidates");
            if bad > tol {
                return Err(fail(format!(
                    "the circles' axes are not parallel and no line touches both on the given \
                     sides (misses by {bad:.3e} m); a tendon between non-parallel pulleys runs \
                     along the intersection of their planes, so place each circle tangent to that line"
                )));
            }
            d
        };
        // The contact points, `turn · r (dir × n)` (Eq. 17): a unit vector that the
        // tangent fixes, times the radius.
        let from_unit = dir.cross(np).scale(tp);
        let to_unit = dir.cross(nq).scale(tq);
        let (from_rel, to_rel) = (from_unit.scale(rp), to_unit.scale(rq));
        let length = (cq + to_rel - cp - from_rel).dot(dir);
        let numbers = [dir, from_rel, to_rel].map(Vec3::to_array);
        if !length.is_finite() || numbers.iter().flatten().any(|x| !x.is_finite()) {
            return Err(too_large());
        }
        let scalar = |v: Vec3<f64>| v.map(T::from_f64);
        let from = Contact {
            body: Some(self.pulleys[p].body),
            rel: scalar(from_unit).scale(radius(p)),
            via: self.via(p, frame),
        };
        let (to, to_angle) = match to {
            SegmentEnd::Pulley(q, _) => (
                Contact {
                    body: Some(self.pulleys[q].body),
                    rel: scalar(to_unit).scale(radius(q)),
                    via: self.via(q, frame),
                },
                self.acting_angle(q, frame, to_rel),
            ),
            SegmentEnd::Exit(x) => (
                Contact {
                    body: None,
                    rel: scalar(Vec3::from_array(x)),
                    via: Via::Carrier,
                },
                f64::NAN,
            ),
        };
        Ok(Segment {
            acting_angles: [self.acting_angle(p, frame, from_rel), to_angle],
            from,
            to,
            frame,
            dir: scalar(dir),
            length,
        })
    }

    /// Geometry of a route and the rates it implies, in `f64`: `Routing::geometry_and_rates`
    /// with the file's radii, the guides it passes, and the couplings it derives checked and
    /// stored.
    /// `couplings[p]` must already hold the coupling of the route's first pulley; the
    /// couplings of the idlers it passes and of a driving pulley it ends on are stored.
    ///
    /// `start_is_coordinate`: the first pulley is itself a driving pulley (a multi-stage
    /// drive), whose angle is a coordinate of the tension system.
    pub fn trace(
        &self,
        route: &Route,
        couplings: &mut [Option<Rate>],
        start_is_coordinate: bool,
    ) -> Result<StrandGeometry> {
        let start_coupling = couplings[route.wraps[0].0]
            .clone()
            .expect("start coupling known");
        let RouteGeometry {
            segments,
            rims,
            rim_speeds,
            pull_rate,
            segment_rates,
        } = self.geometry_and_rates(route, &start_coupling, start_is_coordinate, &|p| {
            self.pulleys[p].radius
        })?;
        let mut idlers = Vec::new();
        for (i, (&(p, turn), speed)) in stops(route).iter().zip(&rim_speeds).enumerate().skip(1) {
            let (s, r) = (turn_sign(turn), self.pulleys[p].radius);
            let incoming = segments[i - 1].frame;
            // A fixed pulley here is a guide: it does not turn, so the rim speed the tendon
            // would give it is the tendon's sliding over it, `v = s r c q̇`.
            let outgoing = segments.get(i);
            let guide = outgoing.filter(|_| self.pulleys[p].fixed).map(|outgoing| {
                let arrive = segments[i - 1].acting_angles[1];
                let depart = outgoing.acting_angles[0];
                // In [−π/2, 3π/2): a negative wrap is a tendon that bends away from the guide
                // at this pose (a real one would lift off; `check` warns), not a wrap of
                // almost 2π. Wraps of 3π/2 or more cannot be told from those and are not
                // represented.
                let quarter = std::f64::consts::FRAC_PI_2;
                Guide {
                    slide: speed.joints.clone(),
                    wrap: (s * (depart - arrive) + quarter).rem_euclid(std::f64::consts::TAU)
                        - quarter,
                    // The departure point turns with the outgoing frame, the arrival point
                    // with the incoming one.
                    wrap_rate: self
                        .relative_rate::<f64>(outgoing.frame, incoming, p)
                        .joints
                        .iter()
                        .map(|x| s * x)
                        .collect(),
                    mu: self.pulleys[p].mu,
                }
            });
            if outgoing.is_some() {
                idlers.push(IdlerStep {
                    body: self.pulleys[p].body,
                    turn: s,
                    radius: r,
                    guide,
                });
            }
        }
        for (p, c) in derived_couplings(self.pulleys, route, &rims) {
            store_coupling(self, route, couplings, p, c.clone())?;
        }
        Ok(StrandGeometry {
            segments,
            idlers,
            pull_rate,
            segment_rates,
        })
    }

    /// A route's segments and rates in the scalar `T`, with `radius(p)` the pitch radius of
    /// pulley `p` and `start_coupling` that of its first pulley (see [`Routing::trace`]).
    /// Directions and frames are decided in `f64` from the file's radii.
    pub(crate) fn geometry_and_rates<T: Real>(
        &self,
        route: &Route,
        start_coupling: &Rate<T>,
        start_is_coordinate: bool,
        radius: &dyn Fn(usize) -> T,
    ) -> Result<RouteGeometry<T>> {
        let n = self.dof;
        let stops = stops(route);
        let (start, start_turn) = stops[0];
        let ends_on_pulley = matches!(route.end, RouteEnd::Pulley(..));
        let mut segments = Vec::new();
        for i in 0..stops.len() - usize::from(ends_on_pulley) {
            let to = match stops.get(i + 1) {
                Some(&(q, t)) => SegmentEnd::Pulley(q, t),
                None => match &route.end {
                    RouteEnd::Exit(x) => SegmentEnd::Exit(*x),
                    RouteEnd::Pulley(..) => unreachable!("the last stop has no outgoing segment"),
                },
            };
            segments.push(self.segment(route, stops[i].0, stops[i].1, to, radius)?);
        }

        // ẋ accumulated along the route with every pulley angle expressed through q, and
        // each segment's share of it: a segment of tension `T` fixed in frame `F` takes in
        // power `T (s r ω_rim/F)` at the rim it leaves and gives `T (s r ω_rim/F)` at the
        // rim it reaches. A wrap's rate `θ̇(incoming rel outgoing)` is split at the pulley's
        // carrier, `θ̇(incoming rel carrier) + θ̇(carrier rel outgoing)`: for a guide the
        // rim is the carrier, so each part is its segment's own; across a turning idler
        // the two segments carry one tension (friction sits only on guides), so where the
        // rim's rate is split does not matter.
        let sign = |t: Turn| T::from_f64(turn_sign(t));
        let mut pull = Rate::zero(n);
        let mut segment_rates = vec![Rate::zero(n); segments.len()];
        let s0 = sign(start_turn);
        let r0 = radius(start);
        pull.add_scaled(
            &self.body_rate(start, start_coupling, segments[0].frame),
            s0 * r0,
        );
        segment_rates[0].add_scaled(&pull, T::one());
        let mut rims = vec![start_coupling.clone()];
        let mut rim_speeds = vec![Rate::zero(n)];
        rim_speeds[0].add_scaled(start_coupling, s0 * r0);
        for (i, &(p, turn)) in stops.iter().enumerate().skip(1) {
            let (s, r) = (sign(turn), radius(p));
            let incoming = segments[i - 1].frame;
            let to_carrier = self.relative_rate(incoming, self.pulleys[p].carrier, p);
            // The rim moves with the tendon (Eqs. 9-10): coupling of this pulley.
            let mut c = Rate::zero(n);
            c.add_divided(&pull, s, r);
            c.add_scaled(&to_carrier, T::one());
            rims.push(c);
            // s r c, without the division and the multiplication that cancel.
            let mut speed = pull.clone();
            speed.add_scaled(&to_carrier, s * r);
            rim_speeds.push(speed);
            if let Some(out) = segments.get(i) {
                pull.add_scaled(&self.relative_rate(incoming, out.frame, p), s * r);
                let carrier = self.pulleys[p].carrier;
                segment_rates[i - 1].add_scaled(&self.relative_rate(incoming, carrier, p), s * r);
                segment_rates[i].add_scaled(&self.relative_rate(carrier, out.frame, p), s * r);
            }
        }

        // In the tension system a driving pulley's angle is a coordinate of its own.
        // The terms at the two ends belong to the first and the last segment.
        let mut expanded = pull;
        if start_is_coordinate {
            let mut c = Rate::zero(n);
            c.add_scaled(start_coupling, -s0 * r0);
            c.add_pulley(start, s0 * r0);
            expanded.add_scaled(&c, T::one());
            segment_rates[0].add_scaled(&c, T::one());
        }
        if let RouteEnd::Pulley(e, t) = &route.end {
            let (s, r) = (sign(*t), radius(*e));
            let incoming = segments.last().expect("one segment at least").frame;
            let mut c = self.relative_rate(incoming, self.pulleys[*e].carrier, *e);
            c.joints.iter_mut().for_each(|x| *x = *x * (s * r));
            c.add_pulley(*e, -s * r);
            expanded.add_scaled(&c, T::one());
            segment_rates
                .last_mut()
                .expect("one segment at least")
                .add_scaled(&c, T::one());
        }
        Ok(RouteGeometry {
            segments,
            rims,
            rim_speeds,
            pull_rate: expanded,
            segment_rates,
        })
    }
}

/// The pulleys a route touches, with its turn round each: its wraps, then the driving
/// pulley it ends on.
fn stops(route: &Route) -> Vec<(usize, Turn)> {
    let mut stops: Vec<(usize, Turn)> = route.wraps.clone();
    if let RouteEnd::Pulley(e, t) = &route.end {
        stops.push((*e, *t));
    }
    stops
}

/// The couplings a traced route derives: each turning pulley after its anchor, with its
/// rim's rate (`RouteGeometry::rims`). A guide's rim rate is its sliding, not a coupling.
pub(crate) fn derived_couplings<'a, T>(
    pulleys: &'a [PulleyInfo],
    route: &Route,
    rims: &'a [Rate<T>],
) -> impl Iterator<Item = (usize, &'a Rate<T>)> {
    (stops(route).into_iter().zip(rims).skip(1))
        .filter(move |((p, _), _)| !pulleys[*p].fixed)
        .map(|((p, _), rim)| (p, rim))
}

/// What validation traced the routing from, in the order it traced it: enough to trace it
/// again in another scalar (`Model::symbolic_geometry`).
#[derive(Clone, Debug, Default)]
pub(crate) struct TraceRecord {
    /// Every pulley, in file order.
    pub(crate) pulleys: Vec<PulleyInfo>,
    /// Each route in the order traced.
    pub(crate) routes: Vec<TracedRoute>,
}

/// A route validation traced, and what became of it.
#[derive(Clone, Debug)]
pub(crate) struct TracedRoute {
    pub(crate) route: Route,
    /// The strand it became (index into `Model::strands`).
    pub(crate) strand: usize,
    /// Whether its first pulley's angle is a coordinate of the tension system (see
    /// [`Routing::trace`]).
    pub(crate) start_is_coordinate: bool,
}

impl TraceRecord {
    /// Whether pulley `p` turns as some route derives (an idler or a driving pulley): a
    /// turning pulley that a route reaches after its anchor. Else its coupling is given
    /// (a fixed drum or guide, an explicit coupling of a pulley no route passes).
    pub(crate) fn derives(&self, p: usize) -> bool {
        !self.pulleys[p].fixed
            && (self.routes.iter()).any(|r| stops(&r.route).iter().skip(1).any(|&(q, _)| q == p))
    }
}

/// A route as `Routing::geometry_and_rates` derives it, in a scalar `T`.
#[derive(Clone, Debug)]
pub(crate) struct RouteGeometry<T> {
    /// Its straight segments, from the anchored (or driven-pulley) end on.
    pub segments: Vec<Segment<T>>,
    /// `rims[k]`: the rate of stop `k`'s rim relative to its carrier (its wraps, then the
    /// driving pulley it ends on), per `q̇`: the coupling of an idler or driving pulley, the
    /// sliding of a guide over its pin, over its radius; `rims[0]` is the start coupling.
    pub rims: Vec<Rate<T>>,
    /// `rim_speeds[k] = s r rims[k]`: the tendon's speed over stop `k`'s rim relative to
    /// its carrier (m per rad/s), formed without dividing by `r` and multiplying back, so
    /// that a guide's sliding speed has the radii's own coefficients (exact sums of the
    /// wraps' `± r` before it, as `E`'s are).
    pub rim_speeds: Vec<Rate<T>>,
    /// `ẋ` of the strand (see [`StrandGeometry::pull_rate`]).
    pub pull_rate: Rate<T>,
    /// Each segment's share of it (see [`StrandGeometry::segment_rates`]).
    pub segment_rates: Vec<Rate<T>>,
}

/// A strand's rate (`ẋ` over `q̇` and the driving pulleys' angles) as a column of `E`: its
/// joint coefficients on the joints' rows, a driving pulley's on that pulley's row.
pub(crate) fn column_of<T: Real>(rows: &[Row], rate: &Rate<T>, pulleys: &[PulleyInfo]) -> Vec<T> {
    let mut column = vec![T::zero(); rows.len()];
    for (r, row) in rows.iter().enumerate() {
        if let Row::Joint(j) = row {
            column[r] = rate.joints[*j];
        }
    }
    for &(p, c) in &rate.pulleys {
        let row = rows.iter().position(|r| *r == Row::Pulley(pulleys[p].body));
        column[row.expect("a driving pulley has its row")] = c;
    }
    column
}

/// What the columns of the tension system belong to.
pub(crate) struct Columns<'a, T> {
    /// Each strand's `ẋ` ([`StrandGeometry::pull_rate`]), in strand order.
    pub(crate) pull_rates: &'a [Rate<T>],
    /// Every pulley, in file order.
    pub(crate) pulleys: &'a [PulleyInfo],
    /// The bodies, with their couplings (a pulley motor's column, where its pulley has no
    /// row).
    pub(crate) bodies: &'a [Body<T>],
    /// The open-ended tendons.
    pub(crate) tendons: &'a [Tendon],
    /// The loops.
    pub(crate) loops: &'a [Loop],
    /// The motors.
    pub(crate) motors: &'a [Motor],
}

/// `E` of the tension system `E x = b` (paper Eqs. 33, 35): the balances of the joints,
/// the driving pulleys and the loops' pretensions (`rows`) against the unknowns (columns).
pub(crate) fn tension_matrix<T: Real>(
    rows: &[Row],
    unknowns: &[Unknown],
    of: &Columns<T>,
) -> Vec<Vec<T>> {
    let n = rows.iter().filter(|r| matches!(r, Row::Joint(_))).count();
    let mut e = vec![vec![T::zero(); unknowns.len()]; rows.len()];
    for (col, u) in unknowns.iter().enumerate() {
        let column = match u {
            Unknown::Strand(s) => column_of(rows, &of.pull_rates[*s], of.pulleys),
            Unknown::Explicit(k) => (of.tendons[*k].structure[..n].iter())
                .map(|&x| T::from_f64(x))
                .collect(),
            Unknown::Motor(k) => {
                let mut column = vec![T::zero(); rows.len()];
                match of.motors[*k].kind {
                    MotorKind::Joint(j) => column[j] = T::one(),
                    MotorKind::Pulley(b) => match rows.iter().position(|r| *r == Row::Pulley(b)) {
                        Some(row) => column[row] = T::one(),
                        None => column[..n].copy_from_slice(&of.bodies[b].coupling),
                    },
                }
                column
            }
        };
        for (row, x) in e.iter_mut().zip(column) {
            row[col] = x;
        }
    }
    for (k, l) in of.loops.iter().enumerate() {
        let row = rows.iter().position(|r| *r == Row::Pretension(k));
        for s in l.strands {
            let col = unknowns.iter().position(|u| *u == Unknown::Strand(s));
            e[row.expect("a loop has its row")][col.expect("a loop's strands are unknowns")] =
                T::from_f64(0.5);
        }
    }
    e
}

#[derive(Clone, Debug)]
enum SegmentEnd {
    Pulley(usize, Turn),
    Exit([f64; 3]),
}

fn store_coupling(
    routing: &Routing,
    route: &Route,
    couplings: &mut [Option<Rate>],
    p: usize,
    c: Rate,
) -> Result<()> {
    if let Some(old) = &couplings[p] {
        let same = old.pulleys == c.pulleys
            && old
                .joints
                .iter()
                .zip(&c.joints)
                .all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs()));
        if !same {
            return Err(Error::Routing {
                item: route.name.clone(),
                at: route.at,
                problem: format!(
                    "pulley `{}` would turn as {:?} by this route but as {:?} by another; \
                     a free pulley carries one tendon, and both sides of a loop must agree \
                     (check `crossed` and the radii)",
                    routing.pulleys[p].name, c.joints, old.joints
                ),
                implied: None,
            });
        }
    }
    couplings[p] = Some(c);
    Ok(())
}

/// `+1` for [`Turn::Ccw`], `−1` for [`Turn::Cw`].
pub fn turn_sign(t: Turn) -> f64 {
    match t {
        Turn::Ccw => 1.0,
        Turn::Cw => -1.0,
    }
}

/// Two unit vectors completing `n` to a right-handed orthonormal basis `(ex, ey, n)`.
fn plane_basis(n: Vec3<f64>) -> (Vec3<f64>, Vec3<f64>) {
    let seed = if n.x.abs() < 0.9 {
        Vec3::new(1.0, 0.0, 0.0)
    } else {
        Vec3::new(0.0, 1.0, 0.0)
    };
    let ex = unit(seed - n.scale(seed.dot(n)));
    (ex, n.cross(ex))
}

/// Two pulleys on one carrier whose pitch circles lie in one plane and overlap: their
/// centres are closer than the sum of their radii. The model accepts it (every result is
/// still the dynamics of the file as written), but no real mechanism can hold both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overlap {
    /// The pulley defined first (body index).
    pub first: usize,
    /// The pulley defined later (body index).
    pub second: usize,
    /// Distance of their centres, m.
    pub distance: f64,
    /// Their pitch radii, m, in the order of `first`, `second`.
    pub radii: [f64; 2],
}

/// Every pair of overlapping pulleys ([`Overlap`]): same carrier, parallel axes, centres in
/// one plane to 1e-9 of their size, `distance < (r₁ + r₂)(1 − 1e-9)`.
pub fn overlapping_pulleys(bodies: &[Body<f64>]) -> Vec<Overlap> {
    let pulleys: Vec<(usize, f64)> = bodies
        .iter()
        .enumerate()
        .filter_map(|(i, b)| match b.kind {
            crate::model::BodyKind::Pulley { radius, .. } => Some((i, radius)),
            crate::model::BodyKind::Link { .. } => None,
        })
        .collect();
    // Pulleys on one carrier, by carrier, so that only those are paired.
    let mut by_carrier: std::collections::BTreeMap<Option<usize>, Vec<(usize, f64)>> =
        std::collections::BTreeMap::new();
    for &(i, r) in &pulleys {
        by_carrier.entry(bodies[i].parent).or_default().push((i, r));
    }
    let mut found = Vec::new();
    for group in by_carrier.values() {
        // Sorted by axis (signed so that it points one way) and then by the plane's offset
        // along it, pulleys that can share a plane are neighbours: each is paired only with
        // the run after it that lies in its plane (a file of many pulleys stays linear).
        let mut planes: Vec<(Vec3<f64>, f64, usize, f64)> = group
            .iter()
            .map(|&(i, r)| {
                let n = bodies[i].pre.rotation.column(2);
                let n = if [n.x, n.y, n.z]
                    .into_iter()
                    .find(|v| *v != 0.0)
                    .unwrap_or(1.0)
                    < 0.0
                {
                    -n
                } else {
                    n
                };
                (n, n.dot(bodies[i].pre.translation), i, r)
            })
            .collect();
        planes.sort_by(|a, b| {
            (a.0.x, a.0.y, a.0.z, a.1)
                .partial_cmp(&(b.0.x, b.0.y, b.0.z, b.1))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        for (a, &(ni, di, i, ri)) in planes.iter().enumerate() {
            let ci = bodies[i].pre.translation;
            for &(nj, dj, j, rj) in &planes[a + 1..] {
                let cj = bodies[j].pre.translation;
                let scale = ri + rj + norm(ci) + norm(cj);
                if norm(ni.cross(nj)) >= 1e-9 || (dj - di).abs() > 1e-9 * scale {
                    break; // past this plane
                }
                let distance = norm(cj - ci);
                if distance < (ri + rj) * (1.0 - 1e-9) {
                    let ((first, r1), (second, r2)) = if i < j {
                        ((i, ri), (j, rj))
                    } else {
                        ((j, rj), (i, ri))
                    };
                    found.push(Overlap {
                        first,
                        second,
                        distance,
                        radii: [r1, r2],
                    });
                }
            }
        }
    }
    found.sort_by_key(|o| (o.first, o.second));
    found
}

/// A straight segment of tendon that passes through a pulley it does not wrap: a routing
/// no real mechanism can have (the tendon would cut the pulley), which the model accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The strand (index into [`Model::strands`](crate::model::Model::strands)).
    pub strand: usize,
    /// The segment's index in the strand.
    pub segment: usize,
    /// The pulley (body index) it passes through.
    pub pulley: usize,
    /// Where it passes the pulley's centre, m: the distance within its plane.
    pub distance: f64,
}

/// Where a pulley's centre and axis are in `frame` when both are fixed there: the pulley is
/// carried by `frame`; or it sits on the axis of a joint between its carrier and `frame`
/// (carried by a link whose joint is in `frame`, or by the parent of `frame`'s own joint),
/// where the joint angle does not move it (the `q_j = 0` convention of the acting angles).
fn pulley_in(
    bodies: &[Body<f64>],
    b: usize,
    frame: Option<usize>,
) -> Option<(Vec3<f64>, Vec3<f64>)> {
    let pre = &bodies[b].pre;
    let (centre, axis) = (pre.translation, pre.rotation.column(2));
    let carrier = bodies[b].parent;
    if carrier == frame {
        return Some((centre, axis));
    }
    let is_link = |l: usize| matches!(bodies[l].kind, crate::model::BodyKind::Link { .. });
    // The joint between the carrier and `frame`: its link, and whether `frame` is the link.
    let (link, into_link) = match (carrier, frame) {
        (Some(l), _) if is_link(l) && bodies[l].parent == frame => (l, false),
        (_, Some(l)) if is_link(l) && bodies[l].parent == carrier => (l, true),
        _ => return None,
    };
    // In the joint's parent frame the joint axis is the `z` axis of the link's `pre`.
    let joint = &bodies[link].pre;
    let t = body_transform(&bodies[link], bodies[link].offset);
    let (in_parent, axis_in_parent) = if into_link {
        (centre, axis)
    } else {
        (t.apply(centre), t.rotation.mul_vec(axis))
    };
    let from_axis = (in_parent - joint.translation).cross(joint.rotation.column(2));
    if norm(from_axis) > 1e-9 * (1.0 + norm(in_parent)) {
        return None;
    }
    Some(if into_link {
        let back = t.inverse();
        (back.apply(centre), back.rotation.mul_vec(axis))
    } else {
        (in_parent, axis_in_parent)
    })
}

/// Every segment that passes through the disc of a pulley fixed in the segment's frame
/// ([`Crossing`]): it crosses the pulley's plane, or runs in it, closer to the centre than
/// `r (1 − 1e-9)`. The pulleys a segment leaves and reaches touch it at their rims and are
/// not counted.
pub fn segments_through_pulleys(model: &crate::Model<f64>) -> Vec<Crossing> {
    let bodies = &model.bodies;
    let mut found = Vec::new();
    for (s, strand) in model.strands.iter().enumerate() {
        for (k, g) in strand.segments.iter().enumerate() {
            // The segment's end points in its frame.
            let point = |c: &crate::model::Contact<f64>| match c.body {
                None => Some(c.rel),
                Some(b) => pulley_in(bodies, b, g.frame).map(|(centre, _)| centre + c.rel),
            };
            let (Some(from), Some(to)) = (point(&g.from), point(&g.to)) else {
                continue;
            };
            let d = to - from;
            let length = norm(d);
            for (b, body) in bodies.iter().enumerate() {
                let crate::model::BodyKind::Pulley { radius, .. } = body.kind else {
                    continue;
                };
                if g.from.body == Some(b) || g.to.body == Some(b) {
                    continue;
                }
                let Some((c, n)) = pulley_in(bodies, b, g.frame) else {
                    continue;
                };
                let scale = 1.0 + length + norm(c - from);
                let (h0, h1) = (n.dot(from - c), n.dot(to - c));
                // The point of the segment nearest the centre within the plane: where it
                // crosses the plane, or (lying in the plane) its nearest point.
                let nearest = if (h0 - h1).abs() > 1e-12 * scale {
                    let t = h0 / (h0 - h1);
                    if !(0.0..=1.0).contains(&t) {
                        continue;
                    }
                    from + d.scale(t)
                } else if h0.abs() <= 1e-9 * scale {
                    let t = if length > 0.0 {
                        ((c - from).dot(d) / (length * length)).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    from + d.scale(t)
                } else {
                    continue;
                };
                let distance = norm(nearest - c);
                if distance < radius * (1.0 - 1e-9) {
                    found.push(Crossing {
                        strand: s,
                        segment: k,
                        pulley: b,
                        distance,
                    });
                }
            }
        }
    }
    found
}

/// Transform of a body frame from its parent with the joint angle at `angle`.
pub fn body_transform(b: &Body<f64>, angle: f64) -> Transform<f64> {
    let rz = Transform {
        rotation: crate::spatial::rot_z(angle),
        translation: Vec3::zero(),
    };
    b.pre.compose(&rz).compose(&b.post)
}
