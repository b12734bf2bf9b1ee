//! What generated dynamics look like from the outside: the [`TendonMechanism`] trait that
//! `#[derive(TendonMechanism)]` implements, and
//! [`include_mechanism!`](crate::include_mechanism!) for code that a build script generated
//! into `OUT_DIR`.
//!
//! Both live here, without `std`, because firmware that uses generated code depends on this
//! crate alone.

use crate::distribution::Actuation;
use crate::real::Real;

/// What a generated `regressor` returns: `y` (`[[T; p]; n]`, one row per joint, one column
/// per parameter of `tendyn_core::regressor::parameters`) and `offset` (`[T; n]`, the
/// external wrench's part), so that `Q = y · π + offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Regression<Y, V> {
    /// The regressor `Y(q, q̇, q̈)`, row by row.
    pub y: Y,
    /// `Q₀`: what the actuators deliver whatever the parameters.
    pub offset: V,
}

/// A mechanism whose dynamics were generated at compile time, by
/// `#[derive(TendonMechanism)]` (crate `tendyn`).
///
/// The constants describe the mechanism as the RON file declares it. The methods are the
/// generated functions, in the scalar the derive was asked for; each returns `None` when
/// its output was not requested ([`OUTPUTS`](Self::OUTPUTS) lists those that were). The
/// derive also adds inherent methods of the same names that return the arrays directly, so
/// `finger.generalized_forces(&q, &qd, &qdd)` needs no `unwrap`; this trait is for code
/// generic over mechanisms. Runtime parameters are the fields of the implementing type.
///
/// Units are SI throughout: rad, rad/s, rad/s², N·m, N, kg·m². Shapes:
/// - `Joints`: `[Scalar; DOF]`, joint coordinates and generalized forces, per joint;
/// - `Motors`: `[Scalar; MOTORS]`, `Tendons`: `[Scalar; TENDONS]`, in file order;
/// - `MassMatrix`: `[[Scalar; DOF]; DOF]`;
/// - `Segments`, `Bearings`, `BaseReaction`: the return types of
///   [`segment_tensions`](Self::segment_tensions), [`bearings`](Self::bearings) and
///   [`base_reaction`](Self::base_reaction) (see `docs/generated-code.md`), `()` when that
///   output was not generated.
pub trait TendonMechanism {
    /// The scalar of the generated functions (`f64` or `f32`).
    type Scalar: Real;
    /// Per joint, in joint order: `[Scalar; DOF]` (coordinates, rates, accelerations,
    /// generalized forces).
    type Joints;
    /// Per motor, in file order: `[Scalar; MOTORS]` (N·m).
    type Motors;
    /// Per open-ended tendon, in file order: `[Scalar; TENDONS]` (N).
    type Tendons;
    /// The mass matrix, `[[Scalar; DOF]; DOF]` (kg·m²).
    type MassMatrix;
    /// What [`segment_tensions`](Self::segment_tensions) returns: `[Scalar; S]`, every
    /// segment of every strand, or `()` when not generated.
    type Segments;
    /// What [`bearings`](Self::bearings) returns: `[[[Scalar; 3]; 2]; B]`, `[force,
    /// moment]` per body, or `()` when not generated.
    type Bearings;
    /// What [`base_reaction`](Self::base_reaction) returns: `[[[Scalar; 3]; 2]; 1]`, or
    /// `()` when not generated.
    type BaseReaction;

    /// The `name` of the RON file.
    const NAME: &'static str;
    /// Degrees of freedom: joint coordinates `q`.
    const DOF: usize;
    /// Motors, in file order.
    const MOTORS: usize;
    /// Open-ended (ground-level) tendons, in file order.
    const TENDONS: usize;
    /// The links (one per joint), in file order.
    const JOINT_NAMES: &'static [&'static str];
    /// The motors' names, in file order.
    const MOTOR_NAMES: &'static [&'static str];
    /// The open-ended tendons' names, in file order.
    const TENDON_NAMES: &'static [&'static str];
    /// Runtime parameters, in declaration order: the fields of the implementing type.
    const PARAMETER_NAMES: &'static [&'static str];
    /// The generated functions, by name (`generalized_forces`, `actuation`, ...).
    const OUTPUTS: &'static [&'static str];
    /// The structure matrix `A` (m): `Q = A T`, a row per joint and a column per tendon
    /// (paper Eqs. 33, 35).
    const STRUCTURE_MATRIX: &'static [&'static [f64]];

    /// `Q = M(q) q̈ + h(q, q̇) + g(q) − Q_ext − Σ_b c_bᵀ τ_f,b`: what the actuators deliver
    /// (the last term the bearings' friction, `crate::friction`; plus `Σ_i W_i (N_i − τ_f,i)`
    /// where turning idlers follow guides with friction, `crate::dynamics::idlers_behind_capstan`).
    fn generalized_forces(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _qdd: &Self::Joints,
    ) -> Option<Self::Joints> {
        None
    }

    /// Motor torques and ground-level tendon tensions (every tension within its floor and
    /// maximum, the distribution's objective least) and whether the bounds could be met.
    fn actuation(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _qdd: &Self::Joints,
    ) -> Option<Actuation<Self::Motors, Self::Tendons>> {
        None
    }

    /// The joint-space mass matrix `M(q)`, pulley inertias included.
    fn mass_matrix(&self, _q: &Self::Joints) -> Option<Self::MassMatrix> {
        None
    }

    /// Coriolis and centrifugal generalized forces `h(q, q̇)`.
    fn bias(&self, _q: &Self::Joints, _qd: &Self::Joints) -> Option<Self::Joints> {
        None
    }

    /// Gravity generalized forces `g(q)`.
    fn gravity(&self, _q: &Self::Joints) -> Option<Self::Joints> {
        None
    }

    /// `q̈` from the motor torques and tendon tensions.
    fn forward_dynamics(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _motor_torques: &Self::Motors,
        _tendon_tensions: &Self::Tendons,
    ) -> Option<Self::Joints> {
        None
    }

    /// The tension of every tendon segment (N).
    fn segment_tensions(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _qdd: &Self::Joints,
    ) -> Option<Self::Segments> {
        None
    }

    /// Every bearing's force and moment (N, N·m).
    fn bearings(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _qdd: &Self::Joints,
    ) -> Option<Self::Bearings> {
        None
    }

    /// The wrench the base exerts on the mechanism (N, N·m).
    fn base_reaction(
        &self,
        _q: &Self::Joints,
        _qd: &Self::Joints,
        _qdd: &Self::Joints,
    ) -> Option<Self::BaseReaction> {
        None
    }
}

/// Includes the code a build script generated with `tendyn_codegen::Builder` for the
/// mechanism file of this stem: `include_mechanism!("finger")` is
/// `include!(concat!(env!("OUT_DIR"), "/finger.rs"))`. Use it inside a module:
///
/// ```ignore
/// mod finger {
///     tendyn_core::include_mechanism!("finger");
/// }
/// ```
#[macro_export]
macro_rules! include_mechanism {
    ($stem:literal) => {
        include!(concat!(env!("OUT_DIR"), "/", $stem, ".rs"));
    };
}
