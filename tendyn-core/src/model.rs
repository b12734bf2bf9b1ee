//! The validated, immutable mechanism: every body, every tendon segment and the tension
//! system, in the scalar the solver runs on.
//!
//! A [`Model`] is produced once by [`crate::validate`] in `f64` and never changes (its
//! fields are private); work and result buffers live in a [`crate::Data`]. [`Model::cast`] converts it to another scalar
//! (a symbolic one for code generation); [`Model::cast_numeric`] also recomputes the
//! tension system's pseudo-inverse and null space in the new precision.

pub use crate::format::Objective;
use crate::linalg;
use crate::real::{Numeric, Real, Symbolic};
use crate::spatial::{Mat3, Transform, Vec3};

/// What a body is in the paper's terms.
#[derive(Clone, Debug, PartialEq)]
pub enum BodyKind {
    /// Primary link moved by joint `joint` (0-based: joint 0 is the paper's joint 1).
    Link {
        /// The joint that moves it, 0-based; also the link's body index.
        joint: usize,
    },
    /// Intermediate link (pulley, idler, drum) of pitch radius `radius`.
    Pulley {
        /// Pitch radius (m): where the tendon's centre line runs.
        radius: f64,
        /// How its angle is determined and balanced.
        role: PulleyRole,
    },
}

/// How a pulley's rotation is determined and balanced.
#[derive(Clone, Debug, PartialEq)]
pub enum PulleyRole {
    /// Part of its carrier: does not turn relative to it.
    Fixed,
    /// Turned by the one tendon strand that runs over it; its axial balance fixes the
    /// tension difference across it (paper Eq. 24b).
    Idler {
        /// The strand that runs over it (index into [`Model::strands`]).
        strand: usize,
    },
    /// End of the strands of endless loops: its axial balance is a row of the tension system.
    Driving,
    /// Turned through an explicit coupling (gear, calibrated ratio); the transmission's
    /// reaction is not modelled, so routing-dependent outputs are unavailable.
    Coupled,
}

/// One rigid body of the expanded tree: a primary link or an intermediate link.
///
/// Its frame relative to its parent's is `pre · RotZ(angle) · post` with
/// `angle = coupling · q + offset`.
#[derive(Clone, Debug)]
pub struct Body<T> {
    /// The link's or pulley's name, unique across the file.
    pub name: String,
    /// Primary link or pulley.
    pub kind: BodyKind,
    /// Parent (carrier) body index; `None` is the base.
    pub parent: Option<usize>,
    /// The part of the frame before the joint rotation, in the parent frame; its origin is
    /// the joint point. Identity for a link; for a pulley its housing frame `Pre` in the
    /// carrier frame (format.md §5, Eq. 8).
    pub pre: Transform<T>,
    /// The part after the joint rotation: `TransZ(d) · TransX(a) · RotX(α)` for a link
    /// (Eq. 1, [`crate::validate::dh_post`]), identity for a pulley.
    pub post: Transform<T>,
    /// Constant part of the angle (rad): the DH `offset` of a link, 0 for a pulley.
    pub offset: T,
    /// Joint angle as a linear function of the joint coordinates (Eqs. 9-10, 26, 31, 34).
    pub coupling: Vec<T>,
    /// Whether the angle enters the body's orientation. `false` for fixed drums and for
    /// axisymmetric pulleys, whose frame then stays the non-spinning housing frame.
    pub spins: bool,
    /// Mass (kg).
    pub mass: T,
    /// Centre of mass in the body frame.
    pub com: Vec3<T>,
    /// Inertia tensor about the centre of mass, body-frame axes.
    pub inertia: Mat3<T>,
    /// Joint axis in the body frame (`postᵀ z`).
    pub axis: Vec3<T>,
    /// Vector from the joint point (on the axis) to the body-frame origin, in the body
    /// frame (paper Eq. 7 for links, zero for pulleys).
    pub joint_to_origin: Vec3<T>,
    /// Friction in the bearing between the body and its parent (`crate::friction`).
    pub friction: Option<BearingFriction>,
}

impl Body<f64> {
    /// Whether the model counts on the body's mass being axisymmetric about its axis: a
    /// body that turns relative to its parent (a nonzero coupling) but whose frame does not
    /// spin. Validation allows that only for a mass axisymmetric about the axis (a file's
    /// pulley, a rigid tree's body), and the dynamics are exact only for such a mass, so
    /// whatever changes its mass properties (identification) must keep them so.
    pub fn axisymmetric(&self) -> bool {
        !self.spins && self.coupling.iter().any(|&c| c != 0.0)
    }
}

/// Coulomb and viscous friction of a bearing: on the body, `τ_f = −(coulomb · sign(ω) +
/// viscous · ω)` about its axis, `ω = coupling · q̇` its rate relative to its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingFriction {
    /// N·m, `≥ 0`.
    pub coulomb: f64,
    /// N·m·s/rad, `≥ 0`.
    pub viscous: f64,
}

/// How to rotate a vector given in a segment's frame into a contact body's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Via {
    /// The segment is fixed in the body's carrier.
    Carrier,
    /// The segment is fixed in the carrier's parent (the pulley sits on the carrier's
    /// proximal joint axis).
    CarrierParent,
    /// The segment is fixed in the given link, a child of the carrier across the joint
    /// the pulley is coaxial with.
    CarrierChild(usize),
}

/// Where a segment touches a pulley.
#[derive(Clone, Debug)]
pub struct Contact<T> {
    /// The pulley body; `None` for the ground exit point (base frame).
    pub body: Option<usize>,
    /// Contact point minus pulley centre, in the segment frame (the exit point itself for
    /// the ground end).
    pub rel: Vec3<T>,
    /// How segment-frame vectors reach the pulley's frame.
    pub via: Via,
}

/// A straight piece of tendon between two contacts, fixed in one link's frame.
#[derive(Clone, Debug)]
pub struct Segment<T> {
    /// The contact at the anchor (or driven-pulley) end.
    pub from: Contact<T>,
    /// The contact at the ground end: the next pulley, the exit point or the driving pulley.
    pub to: Contact<T>,
    /// The link (body index) in whose frame the segment is fixed; `None` is the base.
    pub frame: Option<usize>,
    /// Unit direction from `from` towards `to` in the segment frame: the tension pulls the
    /// `from` body along `+dir` and the `to` body along `-dir` (paper Eq. 17).
    pub dir: Vec3<T>,
    /// Distance between the two contacts, tangent point to tangent point (or exit point), m.
    pub length: f64,
    /// Acting angles (Eq. 17, rad) at both ends, about each pulley's axis from the x axis of
    /// its frame at `θ_p = 0`, evaluated with the joint between segment frame and carrier at
    /// `q_j = 0`; `NaN` at a ground exit, which has none.
    pub acting_angles: [f64; 2],
}

/// An idler, or a fixed guide, between segments `k` and `k + 1` of a strand.
#[derive(Clone, Debug)]
pub struct IdlerStep {
    /// The idler or guide (body index).
    pub body: usize,
    /// `+1` when the tendon turns counter-clockwise about the idler's axis.
    pub turn: f64,
    /// Its pitch radius (m).
    pub radius: f64,
    /// `Some` for a fixed guide, which the tendon slides over instead of turning it.
    pub guide: Option<Guide>,
}

impl IdlerStep {
    /// The guide, where this is one with capstan friction (`mu > 0`): where the tension
    /// changes by the capstan law and `E` depends on the state.
    pub fn capstan(&self) -> Option<&Guide> {
        self.guide.as_ref().filter(|g| g.mu > 0.0)
    }
}

/// `Σ_j c_j x_j` of constant coefficients, summed from the last joint down: a route
/// gathers its joints from its anchor, usually the most distal, towards the ground, so a
/// guide's sum then extends the sum of the guide before it on the route, which generated
/// code shares.
fn linear<T: Real>(c: &[f64], x: &[T]) -> T {
    (c.iter().zip(x).rev()).fold(T::zero(), |s, (c, x)| s + T::from_f64(*c) * *x)
}

/// A fixed pulley after a route's anchor: the tendon slides over it (format.md §6a).
#[derive(Clone, Debug, PartialEq)]
pub struct Guide {
    /// The tendon's speed over the guide, `v = Σ_j slide_j q̇_j` (m/s per rad/s), positive
    /// when it moves towards the strand's ground end (in the direction of its turn).
    pub slide: Vec<f64>,
    /// Wrap angle `β` (rad): from the arrival to the departure tangent point in the turn's
    /// direction, in `[−π/2, 3π/2)` (negative: the tendon bends away from it); where the
    /// two segments are fixed in different frames, at the joints between them at `q = 0`
    /// (DH angle = `offset`).
    pub wrap: f64,
    /// `∂β/∂q`: how the wrap angle changes with the joints between the two segments' frames
    /// (all zero when both are fixed in one frame), `β(q) = wrap + Σ_j wrap_rate_j q_j`.
    pub wrap_rate: Vec<f64>,
    /// Capstan coefficient `μ` (0: frictionless).
    pub mu: f64,
}

impl Guide {
    /// The tendon's speed over the guide at joint velocities `qd` (m/s), positive towards
    /// the strand's ground end (with `q̈`, the acceleration of its sliding). The one sum
    /// the solver, generated code and the reports all take, so they agree on the
    /// direction to the last bit.
    pub fn speed<T: Real>(&self, qd: &[T]) -> T {
        linear(&self.slide, qd)
    }

    /// The wrap angle at joint angles `q` (rad), before the clamp at 0 of the capstan law.
    pub fn wrap_at<T: Real>(&self, q: &[T]) -> T {
        T::from_f64(self.wrap) + linear(&self.wrap_rate, q)
    }

    /// The interval of the wrap angle over a box of joint angles (`[lower, upper]` per
    /// joint, as [`Model::range_box`] gives), each end at least 0: a tendon bending away
    /// does not touch the guide.
    pub fn wrap_over(&self, joints: &[[f64; 2]]) -> [f64; 2] {
        let (mut low, mut high) = (self.wrap, self.wrap);
        for (&rate, r) in self.wrap_rate.iter().zip(joints) {
            let (x, y) = (rate * r[0], rate * r[1]);
            low += x.min(y);
            high += x.max(y);
        }
        [low.max(0.0), high.max(0.0)]
    }

    /// Whether the wrap angle is the same at every state.
    pub fn wrap_is_constant(&self) -> bool {
        self.wrap_rate.iter().all(|&k| k == 0.0)
    }
}

/// One continuous run of tendon from a body it is fixed to (anchor drum, driven pulley) to
/// the ground exit or a driving pulley. Its last segment's tension is an unknown of the
/// tension system; the others follow from the idlers' balances.
#[derive(Clone, Debug)]
pub struct Strand<T> {
    /// The tendon's name, or `LOOP/ccw` and `LOOP/cw` for the two sides of a loop.
    pub name: String,
    /// From the anchored (or driven-pulley) end towards the ground exit (or driving pulley).
    pub segments: Vec<Segment<T>>,
    /// `idlers[k]` is the idler (or guide) between segments `k` and `k + 1`.
    pub idlers: Vec<IdlerStep>,
    /// Index of the unknown (tension of the last segment).
    pub unknown: usize,
    /// `shares[k]`: segment `k`'s share of the strand's column of `E` (over the system's
    /// rows, zero on the pretension rows;
    /// [`crate::transmission::StrandGeometry::segment_rates`]), the shares summing to the
    /// column on the joint and driving-pulley rows. Where guides with friction make the tension differ from segment to
    /// segment, the state's column is `Σ_k (T_k / T) shares[k]` ([`crate::tension::state_matrix`]).
    pub shares: Vec<Vec<T>>,
}

/// An open-ended tendon.
#[derive(Clone, Debug)]
pub struct Tendon {
    /// The tendon's name, unique across the file.
    pub name: String,
    /// The strand it runs as, `None` for a tendon given only by an explicit structure column.
    pub strand: Option<usize>,
    /// Index of its ground-level tension among the tension system's unknowns.
    pub unknown: usize,
    /// Lowest ground-level tension it must keep (N): its own `floor`, else the file's
    /// `tension_floor`.
    pub floor: f64,
    /// Highest ground-level tension its actuator can apply (N); `None`: unbounded.
    pub max_tension: Option<f64>,
    /// Its column of the structure matrix `A` (Eqs. 33, 35): generalized force per newton.
    pub structure: Vec<f64>,
}

/// An endless loop between a driven and a driving pulley (format.md §7).
#[derive(Clone, Debug)]
pub struct Loop {
    /// The loop's name; its strands are `name/ccw` and `name/cw`.
    pub name: String,
    /// The pulley the loop drives (body index).
    pub driven: usize,
    /// The pulley that drives the loop (body index).
    pub driving: usize,
    /// `true` for a crossed belt (opposite turns at the two pulleys), `false` for an open one.
    pub crossed: bool,
    /// Mean of the two sides' tensions, `(T_ccw + T_cw)/2` (N), imposed exactly.
    pub pretension: f64,
    /// The two strands (indices into [`Model::strands`]): leaving the driven pulley
    /// counter-clockwise (`LOOP/ccw`), then clockwise (`LOOP/cw`).
    pub strands: [usize; 2],
}

/// Where a motor acts (format.md §8).
#[derive(Clone, Debug, PartialEq)]
pub enum MotorKind {
    /// Between link `j` (0-based joint index, also its body index) and its parent, about the
    /// joint axis.
    Joint(usize),
    /// Between pulley body `b` and its carrier, about the pulley's axis.
    Pulley(usize),
}

/// A torque source (format.md §8); its torque is an unknown of the tension system.
#[derive(Clone, Debug)]
pub struct Motor {
    /// The motor's name, unique across the file.
    pub name: String,
    /// What it acts on.
    pub kind: MotorKind,
    /// Index of its torque among the tension system's unknowns.
    pub unknown: usize,
    /// Generalized force per newton-metre of motor torque: `e_j` for a joint motor, the
    /// pulley's coupling for a pulley motor.
    pub column: Vec<f64>,
}

/// What an unknown of the tension system is.
#[derive(Clone, Debug, PartialEq)]
pub enum Unknown {
    /// Tension of the last segment of strand `s` (index into [`Model::strands`]).
    Strand(usize),
    /// Tension of open-ended tendon `k` (index into [`Model::tendons`]), known only by its
    /// structure column.
    Explicit(usize),
    /// Torque of motor `k` (index into [`Model::motors`]).
    Motor(usize),
}

/// What a row of the tension system balances.
#[derive(Clone, Debug, PartialEq)]
pub enum Row {
    /// Moment about joint `j`'s axis (0-based).
    Joint(usize),
    /// Moment about the axis of driving pulley `b` (body index).
    Pulley(usize),
    /// Mean tension of loop `l` (index into [`Model::loops`]) at its driving pulley.
    Pretension(usize),
}

impl Unknown {
    /// How reports name the unknown: `tension T1`, `tension belt/ccw`, `torque motor1`.
    pub fn label(&self, strand_names: &[&str], tendons: &[Tendon], motors: &[Motor]) -> String {
        match *self {
            Unknown::Strand(s) => format!("tension {}", strand_names[s]),
            Unknown::Explicit(k) => format!("tension {}", tendons[k].name),
            Unknown::Motor(k) => format!("torque {}", motors[k].name),
        }
    }
}

impl Row {
    /// How reports name the balance: `joint link1`, `pulley p3`, `pretension belt`.
    pub fn label<T>(&self, bodies: &[Body<T>], loops: &[Loop]) -> String {
        match *self {
            Row::Joint(j) => format!("joint {}", bodies[j].name),
            Row::Pulley(b) => format!("pulley {}", bodies[b].name),
            Row::Pretension(l) => format!("pretension {}", loops[l].name),
        }
    }
}

/// The linear system `E x = b` the unknown tensions and torques satisfy (the paper's
/// `A T = B`, Eqs. 33 and 35, extended by motors and loops), with what its solution needs.
#[derive(Clone, Debug)]
pub struct TensionSystem<T> {
    /// What each column of `E` is: the strands of routed open-ended tendons (file order), then
    /// both sides of each loop, then structure-only tendons, then motors (outputs.md §2).
    pub unknowns: Vec<Unknown>,
    /// What each row of `E` balances: the joints in order, then the driving pulleys, then
    /// the loops' pretensions.
    pub rows: Vec<Row>,
    /// `E`, row-major, `rows.len() × unknowns.len()`.
    pub matrix: Vec<Vec<T>>,
    /// `Eᵀ (E Eᵀ)⁻¹`: maps `b` to the minimal-norm solution. Empty in a state's system
    /// traced for generated code, which solves by [`TensionSystem::eliminated`] instead.
    pub pseudo_inverse: Vec<Vec<T>>,
    /// Orthonormal basis of the null space of `E` (in a state's system traced for
    /// generated code, as `tension::system_traced` builds it: one direction scaled to its
    /// smallest tendon component, several orthonormal over the tendons' components).
    pub null_space: Vec<Vec<T>>,
    /// A null vector whose open-ended-tendon components are all strictly positive, when
    /// the null space is one-dimensional it spans it.
    pub positive_null: Option<Vec<T>>,
    /// 2-norm condition number of `E` (largest over smallest singular value).
    pub condition: f64,
    /// Only in a state's system traced for generated code (`tension::system_traced`):
    /// the factors `tension::solution` solves with in place of `E⁺`.
    pub eliminated: Option<Eliminated<T>>,
}

/// The `L U` factors of the square part of a state's `E` that an elimination order
/// chooses (`tension::Elimination`, `linalg::lu_factor`), row-major in that order.
#[derive(Clone, Debug)]
pub struct Eliminated<T> {
    /// Which rows and columns of `E`, in which order.
    pub order: crate::tension::Elimination,
    /// The factors.
    pub factors: Vec<T>,
}

/// A constant wrench on one link by its environment (link frame; format.md §9).
#[derive(Clone, Debug)]
pub struct Wrench<T> {
    /// The link it acts on (joint index, also its body index).
    pub link: usize,
    /// Point of application of `force` in the link's frame `i`, relative to `O_i` (m).
    pub point: Vec3<T>,
    /// Force on the link (N), in its frame: it turns with the link.
    pub force: Vec3<T>,
    /// Pure moment on the link (N·m), in its frame.
    pub moment: Vec3<T>,
}

/// A runtime parameter of the mechanism file.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// The parameter's name, as the file's numbers refer to it.
    pub name: String,
    /// Nominal value (what the model holds until [`Model::with_parameters`]).
    pub value: f64,
}

/// A number of the model that a parameter sets.
///
/// Validation creates the mass-property, gravity and wrench slots: the numbers a mechanism
/// file may name as runtime parameters (`docs/format.md` §9a). Lengths and radii are never
/// slots: validation derives the routing from them once, in `f64` (segment directions,
/// couplings, `E`, its pseudo-inverse and null space), and a length or radius changed at run
/// time would leave all of that stale. `tendyn equations` prints them by name by deriving
/// the geometry again with them as symbols ([`Model::symbolic_geometry`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// The mass of a body (body index).
    Mass(usize),
    /// Component `(body, axis)` of a body's centre of mass (axis 0: x, 1: y, 2: z).
    Com(usize, usize),
    /// Inertia entry `(body, row, column)` of a body (and its mirror).
    Inertia(usize, usize, usize),
    /// Component `c` of gravity (0: x, 1: y, 2: z).
    Gravity(usize),
    /// Component `c` of the external wrench's point.
    WrenchPoint(usize),
    /// Component `c` of the external wrench's force.
    WrenchForce(usize),
    /// Component `c` of the external wrench's moment.
    WrenchMoment(usize),
}

impl Slot {
    /// The body whose mass properties the slot sets, if it sets any.
    pub fn body(self) -> Option<usize> {
        match self {
            Slot::Mass(b) | Slot::Com(b, _) | Slot::Inertia(b, _, _) => Some(b),
            _ => None,
        }
    }
}

/// Whether a parameter of `slots` sets body `i`'s mass properties.
pub(crate) fn parametric(slots: &[(Slot, usize)], i: usize) -> bool {
    slots.iter().any(|(slot, _)| slot.body() == Some(i))
}

/// Lengths and radii in another scalar: what [`Model::symbolic_geometry`] derives the
/// geometry from. `None` keeps the file's number.
#[derive(Clone, Debug)]
pub struct Dimensions<U> {
    /// Per link, its DH length `a` (Eq. 1).
    pub a: Vec<Option<U>>,
    /// Per link, its DH offset `d` (Eq. 1).
    pub d: Vec<Option<U>>,
    /// Per body, a pulley's pitch radius (a link's entry is not read).
    pub radius: Vec<Option<U>>,
}

/// A validated mechanism in scalar `T`.
///
/// Immutable: its fields are read through the accessors below, and a changed model is a
/// new one, made by the checked [`Model::with_parameters`] (numbers) or
/// [`Model::symbolic`] (code generation). Nothing outside this crate can break the
/// invariants that indexing relies on (every body index, unknown and coupling in range,
/// `E`'s pseudo-inverse and null space those of its matrix).
#[derive(Clone, Debug)]
pub struct Model<T> {
    /// The mechanism's name (the file's `name`).
    pub(crate) name: String,
    /// Gravitational acceleration in the base frame (m/s²).
    pub(crate) gravity: Vec3<T>,
    /// Runtime parameters, in file order.
    pub(crate) parameters: Vec<Parameter>,
    /// Which numbers each parameter (by index) sets.
    pub(crate) parameter_slots: Vec<(Slot, usize)>,
    /// Number of joint coordinates `n`.
    pub(crate) dof: usize,
    /// Links first (body `j` is moved by joint `j`), then pulleys in file order; parents
    /// come first.
    pub(crate) bodies: Vec<Body<T>>,
    /// Every strand: the routed open-ended tendons in file order, then both sides of each
    /// loop (`LOOP/ccw`, `LOOP/cw`); strand `s` is unknown `s` of the tension system.
    pub(crate) strands: Vec<Strand<T>>,
    /// Open-ended tendons, routed or structure-only, in file order.
    pub(crate) tendons: Vec<Tendon>,
    /// Endless loops, in file order.
    pub(crate) loops: Vec<Loop>,
    /// Motors, in file order.
    pub(crate) motors: Vec<Motor>,
    /// The tension system `E x = b`.
    pub(crate) system: TensionSystem<T>,
    /// What the tension distribution minimises (format.md §3).
    pub(crate) objective: Objective,
    /// `v` of the smoothed friction law, if the file sets it: `tanh(ω / v)` for bearings
    /// (rad/s), `tanh(v_slide / v)` for guides (m/s).
    pub(crate) friction_smoothing: Option<f64>,
    /// Each joint's `range` of `q` (rad), where the file gives one (format.md §4).
    pub(crate) joint_ranges: Vec<Option<[f64; 2]>>,
    /// The file's `external_wrench`, if any.
    pub(crate) external_wrench: Option<Wrench<T>>,
    /// Explicit couplings or structure columns are present: segment tensions and bearing
    /// forces cannot be attributed and are reported as unavailable.
    pub(crate) routing_incomplete: bool,
    /// [`Model::capstan_before_an_idler`], found once at validation: every inverse and
    /// forward dynamics call asks it.
    pub(crate) idler_behind_capstan: bool,
    /// How far validation showed the routing controllable with the guides' friction.
    pub(crate) sliding_check: SlidingCheck,
    /// What the routing was traced from ([`Model::symbolic_geometry`] traces it again).
    pub(crate) trace_record: crate::transmission::TraceRecord,
    /// What the recursions may skip for each body (derived at validation by
    /// [`patterns_of`]).
    pub(crate) patterns: Vec<BodyPattern>,
    /// A number no other model made in this process has ([`new_identity`]), renewed
    /// whenever a copy's numbers change; clones share it, having the same numbers. What
    /// [`crate::Data`] keys the dual-number copy it keeps for derivatives on.
    pub(crate) identity: usize,
}

/// How far validation showed a routing controllable (full row rank, every tendon lifted,
/// motors and loop sides determined) at every state the guides' capstan friction can
/// produce (docs/format.md §6a). Inverse and forward dynamics check each state's system
/// all the same, and refuse one that fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlidingCheck {
    /// Nothing slides over a guide with friction: `E` is the same at every state.
    Constant,
    /// Every way the guides can slide and rest, and every state between.
    EveryWay {
        /// The systems checked: one per pattern of directions and rest.
        systems: usize,
    },
    /// Every way the guides can slide and rest, but not every state between (the smoothed
    /// law's `|σ| < 1`, or wrap angles smaller than the largest): with two or more null
    /// directions, too many choices of free tendons to take one by one, and none of those
    /// tried carries the ways' systems between them (docs/format.md §6a). Only where the
    /// file sets `accept_sampled_sliding`: validation refuses such a routing otherwise.
    EveryWayNotBetween {
        /// The systems checked: one per pattern of directions and rest.
        systems: usize,
    },
    /// Every capstan factor the guides can take, whatever the directions of sliding, with
    /// wrap angles up to their largest over the joints' ranges (at `q = 0` without).
    EveryFactor {
        /// The boxes of factors it was shown on: 1 where the whole box was shown at once,
        /// by one bound, by the slack-tendon programs or by `E`'s signs (docs/format.md
        /// §6a).
        boxes: usize,
    },
    /// Only patterns in which every guide slides: too many directions to take one by one,
    /// and neither the boxes of factors nor `E`'s signs settled it. Every such pattern up
    /// to 12 groups of guides (guides whose speeds are proportional), beyond that the two
    /// uniform ones, those with one group flipped, and, with one null direction, those a
    /// descent on the tendons' least lift passes through (docs/format.md §6a). Only where
    /// the file sets `accept_sampled_sliding`: validation refuses such a routing otherwise.
    AllSliding {
        /// The systems checked: one per pattern.
        systems: usize,
    },
}

/// A fresh [`Model::identity`].
pub(crate) fn new_identity() -> usize {
    static NEXT: core::sync::atomic::AtomicUsize = core::sync::atomic::AtomicUsize::new(0);
    NEXT.fetch_add(1, core::sync::atomic::Ordering::Relaxed)
}

/// What the recursions may skip for one body: facts of the model's structure, derived
/// once from the `f64` model and valid for every parameter value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BodyPattern {
    /// The joints its angle moves with: the nonzero entries of its coupling, increasing
    /// (no parameter sets a coupling; those of `Model::symbolic_geometry` are the same
    /// ratios by name).
    pub joints: Vec<usize>,
    /// A pulley without mass or inertia that carries nothing (and whose mass no parameter
    /// sets): the tension-free recursion (`Q`, `M`, `h`, `g`) neither moves nor loads it.
    pub inert: bool,
    /// Whether `pre`'s rotation is the identity (every link's), and `post`'s (every
    /// pulley's, and a link's without twist): frame changes skip those factors.
    pub plain_pre: bool,
    /// See `plain_pre`.
    pub plain_post: bool,
    /// Whether the joint point is the parent's origin (`pre`'s translation zero, every
    /// link's): its acceleration is the parent origin's.
    pub joint_at_parent_origin: bool,
    /// Whether the body's origin is on its joint point (`joint_to_origin` zero, every
    /// pulley's): the origin moves as the joint point does.
    pub origin_at_joint: bool,
    /// Whether the centre of mass is the body's origin (and no parameter sets it): the
    /// inertial force has no moment about the origin.
    pub com_at_origin: bool,
    /// Whether the joint axis is the body frame's z axis exactly (every pulley's, and a
    /// link's without twist): its own rate adds to the angular velocity's z alone.
    pub axis_along_z: bool,
}

/// Each body's [`BodyPattern`], from the `f64` bodies and the parameter slots (a mass a
/// parameter sets is not zero for good).
pub(crate) fn patterns_of(bodies: &[Body<f64>], slots: &[(Slot, usize)]) -> Vec<BodyPattern> {
    let identity = Mat3::<f64>::identity();
    (0..bodies.len())
        .map(|i| {
            let b = &bodies[i];
            let inert = matches!(b.kind, BodyKind::Pulley { .. })
                && b.mass == 0.0
                && b.inertia.rows.iter().flatten().all(|&x| x == 0.0)
                && !bodies.iter().any(|c| c.parent == Some(i))
                && !parametric(slots, i);
            let zero = |v: Vec3<f64>| v.to_array() == [0.0; 3];
            BodyPattern {
                joints: (0..b.coupling.len())
                    .filter(|&j| b.coupling[j] != 0.0)
                    .collect(),
                inert,
                plain_pre: b.pre.rotation == identity,
                plain_post: b.post.rotation == identity,
                // A pulley's placement becomes symbols in `Model::symbolic_geometry` where
                // it sits on its joint's axis, so only links (whose `pre` it never
                // changes) are told; a zero DH `a` or `d` is never a symbol there.
                joint_at_parent_origin: !matches!(b.kind, BodyKind::Pulley { .. })
                    && zero(b.pre.translation),
                origin_at_joint: zero(b.joint_to_origin),
                com_at_origin: zero(b.com)
                    && !slots
                        .iter()
                        .any(|(slot, _)| matches!(*slot, Slot::Com(s, _) if s == i)),
                axis_along_z: b.axis.to_array() == [0.0, 0.0, 1.0],
            }
        })
        .collect()
}

impl<T> Model<T> {
    /// The mechanism's name (the file's `name`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Gravitational acceleration in the base frame (m/s²).
    pub fn gravity(&self) -> &Vec3<T> {
        &self.gravity
    }

    /// Runtime parameters, in file order, with their nominal values.
    pub fn parameters(&self) -> &[Parameter] {
        &self.parameters
    }

    /// Which numbers each parameter (by index) sets.
    pub fn parameter_slots(&self) -> &[(Slot, usize)] {
        &self.parameter_slots
    }

    /// Number of joint coordinates `n`.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Links first (body `j` is moved by joint `j`), then pulleys in file order; parents
    /// come first.
    pub fn bodies(&self) -> &[Body<T>] {
        &self.bodies
    }

    /// Every strand: the routed open-ended tendons in file order, then both sides of each
    /// loop (`LOOP/ccw`, `LOOP/cw`); strand `s` is unknown `s` of the tension system.
    pub fn strands(&self) -> &[Strand<T>] {
        &self.strands
    }

    /// Open-ended tendons, routed or structure-only, in file order.
    pub fn tendons(&self) -> &[Tendon] {
        &self.tendons
    }

    /// Endless loops, in file order.
    pub fn loops(&self) -> &[Loop] {
        &self.loops
    }

    /// Motors, in file order.
    pub fn motors(&self) -> &[Motor] {
        &self.motors
    }

    /// The tension system `E x = b`.
    pub fn system(&self) -> &TensionSystem<T> {
        &self.system
    }

    /// What the tension distribution minimises (format.md §3).
    pub fn objective(&self) -> Objective {
        self.objective
    }

    /// `v` of the smoothed friction law, if the file sets it: `tanh(ω / v)` for bearings
    /// (rad/s), `tanh(v_slide / v)` for guides (m/s).
    pub fn friction_smoothing(&self) -> Option<f64> {
        self.friction_smoothing
    }

    /// Joint `j`'s range of `q` (rad), `[lower, upper]`, where the file gives one: what
    /// validation covers of the wrap angles that change with it (format.md §6a); not
    /// enforced by the dynamics.
    pub fn joint_range(&self, j: usize) -> Option<[f64; 2]> {
        self.joint_ranges.get(j).copied().flatten()
    }

    /// Every joint's range, `[0, 0]` for a joint without one: the box of joint angles
    /// validation covers where wrap angles change with them (format.md §6a).
    pub fn range_box(&self) -> Vec<[f64; 2]> {
        (0..self.dof)
            .map(|j| self.joint_range(j).unwrap_or([0.0, 0.0]))
            .collect()
    }

    /// The file's `external_wrench`, if any.
    pub fn external_wrench(&self) -> Option<&Wrench<T>> {
        self.external_wrench.as_ref()
    }

    /// Explicit couplings or structure columns are present: segment tensions and bearing
    /// forces cannot be attributed and are reported as unavailable.
    pub fn routing_incomplete(&self) -> bool {
        self.routing_incomplete
    }

    /// What the recursions may skip for each body ([`BodyPattern`]).
    pub fn patterns(&self) -> &[BodyPattern] {
        &self.patterns
    }
}

impl<T: Real> Model<T> {
    /// The links' names in joint order (each names its joint too).
    pub fn joint_names(&self) -> impl Iterator<Item = &str> {
        self.bodies[..self.dof].iter().map(|b| b.name.as_str())
    }

    /// Whether any bearing has friction (`crate::friction`).
    pub fn has_friction(&self) -> bool {
        self.bodies.iter().any(|b| b.friction.is_some())
    }

    /// Whether some guide has capstan friction (`mu > 0`): then the tension system's `E`
    /// depends on the state (`tension::system_at`).
    pub fn has_capstan(&self) -> bool {
        self.strands.iter().any(has_capstan)
    }

    /// Whether a turning idler lies between a guide with capstan friction and its tendon's
    /// ground end: the idler's inertia, gravity and bearing friction then reach the joints
    /// scaled by the guide's factor, beyond what the symmetric mass matrix carries
    /// (forward dynamics adds it: `dynamics::idlers_behind_capstan`).
    pub fn capstan_before_an_idler(&self) -> bool {
        self.idler_behind_capstan
    }

    /// How far validation showed the routing controllable at every state the guides'
    /// friction can produce (docs/format.md §6a).
    pub fn sliding_check(&self) -> SlidingCheck {
        self.sliding_check
    }

    /// Every fixed guide a tendon slides over, strand by strand in route order: strand
    /// index, idler index on it (`strands()[s].idlers[k]`), the guide's body, the guide.
    pub fn guides(&self) -> impl Iterator<Item = (usize, usize, usize, &Guide)> {
        self.strands.iter().enumerate().flat_map(|(s, strand)| {
            (strand.idlers.iter().enumerate())
                .filter_map(move |(k, i)| i.guide.as_ref().map(|g| (s, k, i.body, g)))
        })
    }

    /// Open-ended tendons whose tensions are unknowns (routed or explicit).
    pub fn tendon_count(&self) -> usize {
        self.tendons.len()
    }

    /// The structure matrix `A` (n × tendons): the tendons' constant columns, their part
    /// of `Q = Σ c_m τ_m + A T` without capstan friction (with it, the state's
    /// `A(σ, q)`: `dynamics::structure`).
    pub fn structure_matrix(&self) -> Vec<Vec<f64>> {
        (0..self.dof)
            .map(|j| self.tendons.iter().map(|t| t.structure[j]).collect())
            .collect()
    }

    /// The same model on dual numbers, every number a constant (zero derivative): what
    /// the derivatives of [`crate::derivatives`] run the generic functions on.
    pub fn dual(&self) -> Model<crate::dual::Dual<T>> {
        self.map_scalar(crate::dual::Dual::constant)
    }

    /// The same model with every number converted by [`Real::from_f64`] semantics.
    /// Numbers must come from an `f64` model; see [`Model::cast_numeric`] for a numeric
    /// target whose derived linear algebra should be recomputed in its own precision.
    pub(crate) fn map_scalar<U: Real>(&self, f: impl Fn(T) -> U + Copy) -> Model<U> {
        let v = |x: Vec3<T>| x.map(f);
        Model {
            name: self.name.clone(),
            gravity: v(self.gravity),
            parameters: self.parameters.clone(),
            parameter_slots: self.parameter_slots.clone(),
            dof: self.dof,
            bodies: self
                .bodies
                .iter()
                .map(|b| Body {
                    name: b.name.clone(),
                    kind: b.kind.clone(),
                    parent: b.parent,
                    pre: b.pre.map(f),
                    post: b.post.map(f),
                    offset: f(b.offset),
                    coupling: b.coupling.iter().map(|&c| f(c)).collect(),
                    spins: b.spins,
                    mass: f(b.mass),
                    com: v(b.com),
                    inertia: b.inertia.map(f),
                    axis: v(b.axis),
                    joint_to_origin: v(b.joint_to_origin),
                    friction: b.friction,
                })
                .collect(),
            strands: self
                .strands
                .iter()
                .map(|s| Strand {
                    name: s.name.clone(),
                    segments: s
                        .segments
                        .iter()
                        .map(|g| Segment {
                            from: Contact {
                                body: g.from.body,
                                rel: v(g.from.rel),
                                via: g.from.via,
                            },
                            to: Contact {
                                body: g.to.body,
                                rel: v(g.to.rel),
                                via: g.to.via,
                            },
                            frame: g.frame,
                            dir: v(g.dir),
                            length: g.length,
                            acting_angles: g.acting_angles,
                        })
                        .collect(),
                    idlers: s.idlers.clone(),
                    shares: map2(&s.shares, f),
                    unknown: s.unknown,
                })
                .collect(),
            tendons: self.tendons.clone(),
            loops: self.loops.clone(),
            motors: self.motors.clone(),
            system: TensionSystem {
                unknowns: self.system.unknowns.clone(),
                rows: self.system.rows.clone(),
                matrix: map2(&self.system.matrix, f),
                pseudo_inverse: map2(&self.system.pseudo_inverse, f),
                null_space: map2(&self.system.null_space, f),
                positive_null: self
                    .system
                    .positive_null
                    .as_ref()
                    .map(|p| p.iter().map(|&x| f(x)).collect()),
                condition: self.system.condition,
                eliminated: self.system.eliminated.as_ref().map(|e| Eliminated {
                    order: e.order.clone(),
                    factors: e.factors.iter().map(|&x| f(x)).collect(),
                }),
            },
            objective: self.objective,
            friction_smoothing: self.friction_smoothing,
            joint_ranges: self.joint_ranges.clone(),
            external_wrench: self.external_wrench.as_ref().map(|w| Wrench {
                link: w.link,
                point: v(w.point),
                force: v(w.force),
                moment: v(w.moment),
            }),
            routing_incomplete: self.routing_incomplete,
            idler_behind_capstan: self.idler_behind_capstan,
            sliding_check: self.sliding_check,
            trace_record: self.trace_record.clone(),
            patterns: self.patterns.clone(),
            identity: new_identity(),
        }
    }
}

impl<T: Real> Model<T> {
    /// Sets every number a parameter names to `values[parameter]`, unchecked: callers
    /// check (`with_parameters`) or pass symbols (`symbolic`); both give one value per
    /// parameter.
    fn set_parameters(&mut self, values: &[T]) {
        self.identity = new_identity();
        for &(slot, k) in &self.parameter_slots {
            let v = values[k];
            match slot {
                Slot::Mass(b) => self.bodies[b].mass = v,
                Slot::Com(b, c) => set3(&mut self.bodies[b].com, c, v),
                Slot::Inertia(b, r, c) => {
                    self.bodies[b].inertia.rows[r][c] = v;
                    self.bodies[b].inertia.rows[c][r] = v;
                }
                Slot::Gravity(c) => set3(&mut self.gravity, c, v),
                // Validation creates wrench slots only with a wrench.
                Slot::WrenchPoint(c) => {
                    if let Some(w) = &mut self.external_wrench {
                        set3(&mut w.point, c, v);
                    }
                }
                Slot::WrenchForce(c) => {
                    if let Some(w) = &mut self.external_wrench {
                        set3(&mut w.force, c, v);
                    }
                }
                Slot::WrenchMoment(c) => {
                    if let Some(w) = &mut self.external_wrench {
                        set3(&mut w.moment, c, v);
                    }
                }
            }
        }
    }
}

impl<U: Symbolic> Model<U> {
    /// The model with entries `(unknown, row)` of `E`'s pseudo-inverse replaced by `entries`:
    /// for `tendyn equations`, which gives a square `E`'s exact inverse by name (paper Eqs.
    /// 28-30) where the solver's is computed by QR. An entry out of range is an
    /// [`Error::Invalid`](crate::Error::Invalid) naming it.
    pub fn with_exact_inverse(mut self, entries: &[((usize, usize), U)]) -> crate::Result<Self> {
        for &((u, r), value) in entries {
            let entry = (self.system.pseudo_inverse.get_mut(u)).and_then(|row| row.get_mut(r));
            let Some(x) = entry else {
                return Err(crate::Error::Invalid {
                    item: self.name.clone(),
                    at: crate::error::Location::default(),
                    problem: format!("pseudo-inverse entry ({u}, {r}) is out of range"),
                });
            };
            *x = value;
        }
        self.identity = new_identity();
        Ok(self)
    }
}

fn set3<T>(v: &mut Vec3<T>, c: usize, x: T) {
    match c {
        0 => v.x = x,
        1 => v.y = x,
        _ => v.z = x,
    }
}

fn map2<T: Copy, U>(m: &[Vec<T>], f: impl Fn(T) -> U + Copy) -> Vec<Vec<U>> {
    m.iter()
        .map(|r| r.iter().map(|&x| f(x)).collect())
        .collect()
}

impl Model<f64> {
    /// The same mechanism with its runtime parameters set to `values` (file order), checked
    /// as validation checks the file: finite numbers, non-negative masses, physical inertias
    /// of the bodies the parameters set (the others are as validation left them, or, in a
    /// [`Model::regrouped`] one, parts of bodies that need not be physical alone).
    pub fn with_parameters(&self, values: &[f64]) -> crate::Result<Model<f64>> {
        self.check_parameter_count(values.len())?;
        if let Some((p, v)) = self
            .parameters
            .iter()
            .zip(values)
            .find(|(_, v)| !v.is_finite())
        {
            return Err(crate::Error::State(format!(
                "parameter `{}` is {v}; it must be finite",
                p.name
            )));
        }
        let mut m = self.clone();
        m.set_parameters(values);
        for (i, b) in m.bodies.iter().enumerate() {
            if parametric(&self.parameter_slots, i) {
                crate::validate::check_mass_properties(&b.name, b.mass, b.com, &b.inertia)?;
            }
        }
        crate::validate::check_gravity_and_wrench(&m.name, m.gravity, m.external_wrench.as_ref())?;
        Ok(m)
    }

    /// The model in a symbolic scalar whose runtime parameter `k` (file order) is
    /// `input(k)`: what code generation traces, so that generated code takes the parameters
    /// as inputs. Symbols cannot be checked; numbers go through [`Model::with_parameters`].
    pub fn symbolic<U: Symbolic>(&self, input: impl Fn(usize) -> U) -> Model<U> {
        let inputs: Vec<U> = (0..self.parameters.len()).map(input).collect();
        let mut m = self.cast::<U>();
        m.set_parameters(&inputs);
        m
    }

    /// The model in a symbolic scalar, as [`Model::symbolic`], with its geometry derived
    /// again from `dimensions`: the link frames (Eq. 1, 7), the placements of pulleys on their
    /// own link's joint axis (Eq. 8), and the routing (contact points, couplings and `E`;
    /// Eqs. 9-10, 17, 26, 31, 33-35) by the very functions validation derived them with
    /// (`transmission::Routing::geometry_and_rates`). What validation decides from numbers stays
    /// a number: tangent directions, which frame a segment is fixed in, the pseudo-inverse,
    /// null space, idler steps, and guides' sliding rates and wrap angles. For `tendyn equations`, which prints lengths and radii by
    /// name; never for generated code, whose routing cannot follow other lengths.
    pub fn symbolic_geometry<U: Symbolic>(
        &self,
        input: impl Fn(usize) -> U,
        dimensions: &Dimensions<U>,
    ) -> crate::Result<Model<U>> {
        use crate::transmission::{column_of, derived_couplings, tension_matrix, Columns};
        use crate::transmission::{Rate, Routing};
        use crate::validate::{axis_and_origin, dh_post, on_own_joint_axis};
        let mut m = self.symbolic(input);
        let given = |of: &[Option<U>], i: usize, x: f64| {
            of.get(i)
                .copied()
                .flatten()
                .unwrap_or_else(|| U::from_f64(x))
        };
        for (j, body) in self.bodies[..self.dof].iter().enumerate() {
            let t = body.post.translation;
            let mut post = dh_post(
                given(&dimensions.a, j, t.x),
                given(&dimensions.d, j, t.z),
                &body.post.rotation,
            );
            // Zero for a DH link; a body of `Model::rigid_tree` may have one.
            post.translation.y = U::from_f64(t.y);
            let (axis, joint_to_origin) = axis_and_origin(&post);
            let link = &mut m.bodies[j];
            (link.post, link.axis, link.joint_to_origin) = (post, axis, joint_to_origin);
        }
        let record = &self.trace_record;
        for info in &record.pulleys {
            if let Some((j, height)) = info.on_own_joint_axis() {
                m.bodies[info.body].pre = on_own_joint_axis(&m.bodies[j].post, U::from_f64(height));
            }
        }

        // The routing, traced again in the order validation traced it.
        let routing = Routing {
            bodies: &self.bodies,
            pulleys: &record.pulleys,
            dof: self.dof,
        };
        let radius = |p: usize| {
            let info = &record.pulleys[p];
            given(&dimensions.radius, info.body, info.radius)
        };
        let mut couplings: Vec<Option<Rate<U>>> = (record.pulleys.iter().enumerate())
            .map(|(p, info)| {
                (!record.derives(p)).then(|| Rate {
                    joints: m.bodies[info.body].coupling.clone(),
                    pulleys: Vec::new(),
                })
            })
            .collect();
        let mut pull_rates = vec![None; self.strands.len()];
        for traced in &record.routes {
            let route = &traced.route;
            let start = couplings[route.wraps[0].0]
                .clone()
                .expect("validation traced each route once the coupling of its start was known");
            let g =
                routing.geometry_and_rates(route, &start, traced.start_is_coordinate, &radius)?;
            for (p, rim) in derived_couplings(&record.pulleys, route, &g.rims) {
                couplings[p] = Some(rim.clone());
            }
            let strand = &mut m.strands[traced.strand];
            strand.segments = g.segments;
            strand.shares = (g.segment_rates.iter())
                .map(|rate| column_of(&self.system.rows, rate, &record.pulleys))
                .collect();
            pull_rates[traced.strand] = Some(g.pull_rate);
        }
        for (info, c) in record.pulleys.iter().zip(couplings) {
            if let Some(c) = c {
                m.bodies[info.body].coupling = c.joints;
            }
        }
        let pull_rates: Vec<Rate<U>> = pull_rates
            .into_iter()
            .map(|r| r.expect("every strand is a traced route"))
            .collect();
        let columns = Columns {
            pull_rates: &pull_rates,
            pulleys: &record.pulleys,
            bodies: &m.bodies,
            tendons: &self.tendons,
            loops: &self.loops,
            motors: &self.motors,
        };
        m.system.matrix = tension_matrix(&self.system.rows, &self.system.unknowns, &columns);
        Ok(m)
    }

    /// The same mechanism with more of its numbers named, for `tendyn equations` (crate
    /// `tendyn-codegen`), which prints every mass by name: `named[i]` `(name, value)`
    /// becomes parameter `i` after the file's, and each `(slot, i)` of `slots` makes the
    /// number at `slot` one it sets.
    ///
    /// A name that is taken, a value that is not finite, or a slot out of range is an
    /// [`Error::Invalid`](crate::Error::Invalid) naming it.
    pub fn with_named_numbers(
        &self,
        named: &[(String, f64)],
        slots: &[(Slot, usize)],
    ) -> crate::Result<Model<f64>> {
        let invalid = |item: &str, problem: String| crate::Error::Invalid {
            item: item.to_string(),
            at: crate::error::Location::default(),
            problem,
        };
        let mut m = self.clone();
        m.identity = new_identity();
        for (name, value) in named {
            if !value.is_finite() {
                return Err(invalid(name, format!("value {value} is not finite")));
            }
            if m.parameters.iter().any(|p| &p.name == name) {
                return Err(invalid(name, "another parameter has this name".into()));
            }
            m.parameters.push(Parameter {
                name: name.clone(),
                value: *value,
            });
        }
        for &(slot, i) in slots {
            let Some((name, _)) = named.get(i) else {
                return Err(invalid(
                    &self.name,
                    format!("{slot:?} names parameter {i} of {}", named.len()),
                ));
            };
            if !self.slot_in_range(slot) {
                return Err(invalid(
                    name,
                    format!("{slot:?} is not a number of the model"),
                ));
            }
            m.parameter_slots.push((slot, self.parameters.len() + i));
        }
        // A named mass makes its body no longer inert.
        m.patterns = patterns_of(&m.bodies, &m.parameter_slots);
        Ok(m)
    }

    /// `Err` unless `given` is the number of parameters.
    fn check_parameter_count(&self, given: usize) -> crate::Result<()> {
        if given != self.parameters.len() {
            return Err(crate::Error::State(format!(
                "{given} parameter values given but the mechanism declares {}",
                self.parameters.len()
            )));
        }
        Ok(())
    }

    /// Whether every index of `slot` names a number of this model.
    fn slot_in_range(&self, slot: Slot) -> bool {
        let body = |b: usize| b < self.bodies.len();
        match slot {
            Slot::Mass(b) => body(b),
            Slot::Com(b, c) => body(b) && c < 3,
            Slot::Inertia(b, r, c) => body(b) && r < 3 && c < 3,
            Slot::Gravity(c) => c < 3,
            Slot::WrenchPoint(c) | Slot::WrenchForce(c) | Slot::WrenchMoment(c) => {
                self.external_wrench.is_some() && c < 3
            }
        }
    }

    /// The model in another scalar (a symbolic one for code generation): every number is
    /// converted with [`Real::from_f64`].
    pub fn cast<U: Real>(&self) -> Model<U> {
        self.map_scalar(U::from_f64)
    }

    /// The model in another numeric scalar, with the tension system's pseudo-inverse and
    /// null space recomputed in that precision (the accuracy reference needs this).
    pub fn cast_numeric<U: Numeric>(&self) -> Model<U> {
        let mut m = self.cast::<U>();
        let (pinv, null) = linalg::pseudo_inverse_and_null_space_of_rows(&m.system.matrix);
        m.system.pseudo_inverse = pinv;
        m.system.null_space = null;
        if let Some(p) = &self.system.positive_null {
            // Re-project the positive null vector onto the recomputed null space so that it
            // is a null vector to the new precision.
            let p: Vec<U> = p.iter().map(|&x| U::from_f64(x)).collect();
            let basis: Vec<U> = m.system.null_space.iter().flatten().copied().collect();
            let mut projected = vec![U::zero(); p.len()];
            linalg::project_onto(&p, &basis, &mut projected);
            m.system.positive_null = Some(projected);
        }
        m
    }
}

/// Whether, on some strand, a turning idler lies between a guide with capstan friction and
/// the ground end ([`Model::capstan_before_an_idler`]).
pub(crate) fn capstan_before_an_idler<T>(strands: &[Strand<T>]) -> bool {
    strands.iter().any(|strand| {
        let first = strand.idlers.iter().position(|i| i.capstan().is_some());
        first.is_some_and(|k| strand.idlers[k..].iter().any(|i| i.guide.is_none()))
    })
}

/// Whether one of the strand's guides has capstan friction.
fn has_capstan<T>(strand: &Strand<T>) -> bool {
    strand.idlers.iter().any(|i| i.capstan().is_some())
}
