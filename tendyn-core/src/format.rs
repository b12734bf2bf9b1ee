//! The RON mechanism file, exactly as documented in `docs/format.md`.
//!
//! These types are what serde reads; nothing here is checked yet. [`crate::validate`]
//! turns a [`MechanismFile`] into a [`crate::Model`] or a named error. Units are SI
//! (m, kg, kg·m², rad, N, N·m) throughout.

use serde::Deserialize;

/// A number, or the name of a runtime parameter (declared in `parameters`) where the
/// field allows one: masses, centres of mass, inertias, gravity, the external wrench.
#[derive(Clone, Debug, PartialEq)]
pub enum Num {
    /// A number, in the field's unit.
    Value(f64),
    /// The name of a declared parameter.
    Param(String),
}

/// Read by hand rather than as an untagged enum: serde's untagged error names the enum
/// ("did not match any variant of untagged enum Num") and points past the value, where a
/// visitor's error says what the field takes, at the value.
impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = Num;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number or the name of a declared parameter (in quotes)")
            }
            fn visit_f64<E>(self, v: f64) -> Result<Num, E> {
                Ok(Num::Value(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<Num, E> {
                Ok(Num::Value(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<Num, E> {
                Ok(Num::Value(v as f64))
            }
            fn visit_str<E>(self, v: &str) -> Result<Num, E> {
                Ok(Num::Param(v.to_string()))
            }
        }
        d.deserialize_any(Visitor)
    }
}

impl Default for Num {
    fn default() -> Self {
        Num::Value(0.0)
    }
}

impl From<f64> for Num {
    fn from(x: f64) -> Self {
        Num::Value(x)
    }
}

/// A runtime parameter: a number that generated code takes as an input (a payload mass, a
/// calibrated inertia) instead of folding it in. `value` is its nominal value, used for
/// validation and by the runtime solver unless overridden.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSpec {
    /// The parameter's name, unique, written as a string in place of a number where it is
    /// used (`mass: "payload"`).
    pub name: String,
    /// Its nominal value, in the unit of the fields that name it: validation checks it like
    /// any number, and the runtime solver uses it unless [`crate::Model::with_parameters`]
    /// sets another.
    pub value: f64,
}

/// A whole mechanism description.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MechanismFile {
    /// Free-form name, used in messages and generated code.
    pub name: String,
    /// Runtime parameters that numbers elsewhere may name.
    #[serde(default)]
    pub parameters: Vec<ParameterSpec>,
    /// Gravitational acceleration in the base frame (m/s²). Default `(0, 0, -9.81)`.
    #[serde(default = "default_gravity")]
    pub gravity: [Num; 3],
    /// The primary links of the serial chain, from the base outwards (link 1 first).
    pub links: Vec<LinkSpec>,
    /// Intermediate links (pulleys, idlers) and the drums fixed to primary links.
    #[serde(default)]
    pub pulleys: Vec<PulleySpec>,
    /// Open-ended tendons, each anchored on a drum and pulled at ground level.
    #[serde(default)]
    pub tendons: Vec<TendonSpec>,
    /// Endless tendon loops between a driven and a driving pulley.
    #[serde(default)]
    pub loops: Vec<LoopSpec>,
    /// Torque sources between a body and its carrier.
    #[serde(default)]
    pub motors: Vec<MotorSpec>,
    /// Default lowest tension (N) every open-ended tendon must keep (its pretension floor).
    #[serde(default)]
    pub tension_floor: f64,
    /// A constant wrench applied to one link by its environment.
    #[serde(default)]
    pub external_wrench: Option<WrenchSpec>,
    /// What the tension distribution of a redundant routing minimises.
    #[serde(default)]
    pub distribution: Objective,
    /// `v`: replace `sign(ω)` of every bearing's Coulomb friction by `tanh(ω / v)` (rad/s)
    /// and the direction of every guide's capstan law by `tanh(v_slide / v)` (m/s).
    #[serde(default)]
    pub friction_smoothing: Option<f64>,
    /// Accept a routing that validation could show controllable with capstan friction only
    /// at sampled states (some ways of sliding, or every way but not the states between),
    /// leaving the others to the runtime solver's check of each state. Default `false`:
    /// such a routing is refused.
    #[serde(default)]
    pub accept_sampled_sliding: bool,
}

/// Friction in a bearing, opposing the body's angular velocity relative to its carrier:
/// `τ_f = −(coulomb · sign(ω) + viscous · ω)`.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// N·m.
    #[serde(default)]
    pub coulomb: f64,
    /// N·m·s/rad.
    #[serde(default)]
    pub viscous: f64,
}

/// The objective of the tension distribution: among the tensions within every floor and
/// maximum that produce the motion, the ones nearest to a target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Objective {
    /// Least `Σ T_k²`: the lowest tensions (the default).
    #[default]
    LeastNorm,
    /// Least `Σ (T_k − (floor_k + max_k)/2)²`: tensions mid-way between their bounds, for
    /// antagonistic stiffness. Every tendon needs a `max_tension`.
    Centered,
}

fn default_gravity() -> [Num; 3] {
    [Num::Value(0.0), Num::Value(0.0), Num::Value(-9.81)]
}

/// Standard Denavit-Hartenberg parameters of the joint that moves this link:
/// `{}^{i-1}A_i = RotZ(q_i + offset) · TransZ(d) · TransX(a) · RotX(alpha)`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dh {
    /// Length along `x_i` (TransX), m.
    pub a: f64,
    /// Twist about `x_i` (RotX), rad; snapped to a right angle within `1e-12` rad of one
    /// (format.md §2).
    pub alpha: f64,
    /// Offset along `z_{i-1}` (TransZ), m.
    pub d: f64,
    /// Constant added to the joint angle (rad, default 0): the DH angle is `θ_i = q_i + offset`.
    #[serde(default)]
    pub offset: f64,
}

/// Inertia tensor about the centre of mass, axes parallel to the body frame.
/// `xy`, `xz`, `yz` are the tensor's entries (`I_xy = -∫ x y dm`), not products of inertia.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InertiaSpec {
    /// `I_xx` (kg·m²); required once `inertia:` is written.
    pub xx: Num,
    /// `I_yy` (kg·m²); required once `inertia:` is written.
    pub yy: Num,
    /// `I_zz` (kg·m²); required once `inertia:` is written.
    pub zz: Num,
    /// Tensor entry `I_xy = −∫ x y dm` (kg·m²), default 0.
    #[serde(default)]
    pub xy: Num,
    /// Tensor entry `I_xz = −∫ x z dm` (kg·m²), default 0.
    #[serde(default)]
    pub xz: Num,
    /// Tensor entry `I_yz = −∫ y z dm` (kg·m²), default 0.
    #[serde(default)]
    pub yz: Num,
}

/// Primary link `i` of the serial chain and the revolute joint `i` that moves it
/// (format.md §4).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkSpec {
    /// The link's name, unique across the file; it also names its joint in the outputs.
    pub name: String,
    /// DH parameters of joint `i`.
    pub dh: Dh,
    /// Mass of the link (kg, `≥ 0`), without the pulleys and drums listed in `pulleys`,
    /// which are separate bodies.
    pub mass: Num,
    /// Centre of mass in the link frame (the DH frame at the link's distal joint).
    #[serde(default)]
    pub com: [Num; 3],
    /// Inertia tensor about the centre of mass, axes parallel to frame `i`; default all zero.
    #[serde(default)]
    pub inertia: InertiaSpec,
    /// Friction in the joint's bearing.
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
    /// Range of the joint variable `q` (rad), `(lower, upper)`: where a guide's wrap angle
    /// changes with this joint, validation covers the wrap angles it reaches over the range
    /// (format.md §6a). The dynamics does not enforce it.
    #[serde(default)]
    pub range: Option<[f64; 2]>,
}

/// Where a pulley sits on its carrier.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Placement {
    /// Coaxial with the axis of the joint that moves link `joint`, `height` metres along
    /// that axis from the joint's DH origin; spins about the joint axis. The carrier must
    /// be one of the two bodies the joint connects.
    Joint {
        /// The link whose joint it sits on (the joint that moves that link).
        joint: String,
        /// Distance along `z_{j-1}` from `O_{j-1}` (m); may be negative.
        height: f64,
    },
    /// Anywhere on the carrier: origin and roll-pitch-yaw (`RotZ(yaw)·RotY(pitch)·RotX(roll)`)
    /// of the pulley frame in the carrier frame; spins about its own z axis.
    Pose {
        /// Origin of the pulley frame in the carrier frame (m).
        origin: [f64; 3],
        /// Roll, pitch, yaw (rad), snapped to right angles as in format.md §2.
        rpy: [f64; 3],
    },
}

/// A pulley, idler or drum: an intermediate link carried by the base or by a link
/// (format.md §5).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PulleySpec {
    /// The pulley's name, unique across the file.
    pub name: String,
    /// `"base"` or the name of a primary link.
    pub carrier: String,
    /// Where it sits on its carrier.
    pub at: Placement,
    /// Pitch radius (m), where the tendon's centre line runs.
    pub radius: f64,
    /// `true` for a drum that is part of its carrier (it does not turn relative to it).
    #[serde(default)]
    pub fixed: bool,
    /// Capstan coefficient of a fixed pulley that tendons slide over (a guide), `>= 0`.
    #[serde(default)]
    pub mu: Option<f64>,
    /// Mass (kg, `≥ 0`), default 0.
    #[serde(default)]
    pub mass: Num,
    /// Centre of mass in the pulley frame.
    #[serde(default)]
    pub com: [Num; 3],
    /// Inertia tensor about the centre of mass, pulley-frame axes; default all zero.
    #[serde(default)]
    pub inertia: InertiaSpec,
    /// Explicit coupling: angle relative to the carrier = Σ ratio_j · q_j (one ratio per
    /// joint). Needed for a pulley no routing turns (a gear, a calibrated ratio); checked
    /// against the routing when both are given.
    #[serde(default)]
    pub coupling: Option<Vec<f64>>,
    /// Friction in the pulley's bearing (not on a `fixed` drum, which has none).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// The direction in which a tendon goes round a pulley's z axis (right-hand rule) when
/// followed from its anchored (driven) end towards its ground (driving) end.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
pub enum Turn {
    /// Counter-clockwise seen from the pulley's `+z`. At an anchor the tendon leaves along
    /// the counter-clockwise tangent: pulling it turns the drum by `+r T`.
    Ccw,
    /// Clockwise seen from the pulley's `+z`; at an anchor, `−r T`.
    Cw,
}

/// One pulley on a tendon's route, and the way the tendon turns round it.
#[derive(Clone, Debug, Deserialize)]
pub struct Wrap(pub String, pub Turn);

/// An open-ended tendon: fixed on a drum (its anchor), over idlers, and out of the
/// mechanism at a point of the base towards its actuator, which pulls it with the
/// ground-level tension (format.md §6).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TendonSpec {
    /// The tendon's name, unique across the file.
    pub name: String,
    /// From the anchor drum (first, a `fixed` pulley) over idlers towards the actuator.
    #[serde(default)]
    pub route: Vec<Wrap>,
    /// Point in the base frame where the tendon leaves towards its actuator.
    #[serde(default)]
    pub exit: Option<[f64; 3]>,
    /// Lowest tension this tendon must keep (N); default: the file's `tension_floor`.
    #[serde(default)]
    pub floor: Option<f64>,
    /// Highest tension its actuator can apply (N); default: unbounded.
    #[serde(default)]
    pub max_tension: Option<f64>,
    /// Explicit structure-matrix column (one entry per joint, m): generalized force per
    /// newton of tension. Replaces the route, or is checked against it.
    #[serde(default)]
    pub structure: Option<Vec<f64>>,
}

/// An endless tendon between a driven and a driving pulley: two straight strands, no
/// idlers (format.md §7).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoopSpec {
    /// The loop's name, unique across the file; its strands are `name/ccw` and `name/cw`.
    pub name: String,
    /// The pulley the loop drives (usually a drum fixed to a link).
    pub driven: String,
    /// The pulley that drives the loop (turned by a motor or by a previous stage).
    pub driving: String,
    /// `false`: open belt (both pulleys turn the same way); `true`: crossed.
    #[serde(default)]
    pub crossed: bool,
    /// Mean tension of the two sides at the driving pulley (N).
    pub pretension: f64,
}

/// What a motor acts on.
#[derive(Clone, Debug, Deserialize)]
pub enum MotorSite {
    /// Between a primary link and the previous one, about the joint axis.
    Joint(String),
    /// Between a pulley and its carrier, about the pulley axis.
    Pulley(String),
}

/// A torque source (format.md §8); at most one per joint or pulley.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotorSpec {
    /// The motor's name, unique across the file.
    pub name: String,
    /// Where it acts, which sets the sign of its torque: on link `i` about `+z_{i-1}`, or on
    /// the pulley about its `+z`; the reaction acts on the parent or carrier.
    pub on: MotorSite,
}

/// Force and moment applied to `link` by its environment, in the link frame; the force
/// acts at `point` (link frame).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WrenchSpec {
    /// The link it acts on (links only, not pulleys).
    pub link: String,
    /// Point of application of `force` in frame `i` of that link, relative to `O_i` (m);
    /// default zero.
    #[serde(default)]
    pub point: [Num; 3],
    /// Force on the link (N) in its frame: it turns with the link (a follower force);
    /// default zero.
    #[serde(default)]
    pub force: [Num; 3],
    /// Pure moment on the link (N·m) in its frame, turning with it; default zero.
    #[serde(default)]
    pub moment: [Num; 3],
}
