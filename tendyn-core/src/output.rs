//! The outputs of the dynamics by name, and each one's numbers flattened in one order: the
//! order generated functions return them in (row-major matrices; motor torques, then
//! tendon tensions; segment tensions strand by strand; per body force then moment). The
//! runtime solver ([`Data::output`](crate::Data::output)), the code generator, the
//! error report and the checks all flatten here.

use crate::dynamics::InverseDynamics;
use crate::spatial::Vec3;

/// One output of the dynamics: a runtime evaluator of [`Data`](crate::Data), and one
/// generated function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Output {
    /// `Q = M q̈ + h + g − Q_ext − Σ_b c_bᵀ τ_f,b` (what the actuators deliver, bearing
    /// friction included; plus `Σ_i W_i (N_i − τ_f,i)` of idlers behind guides with
    /// friction, `crate::dynamics::idlers_behind_capstan`).
    GeneralizedForces,
    /// Motor torques and ground-level tendon tensions (the tension distribution included).
    Actuation,
    /// `M(q)` (kg·m², pulley inertias included).
    MassMatrix,
    /// `h(q, q̇)`: Coriolis and centrifugal generalized forces (N·m).
    Bias,
    /// `g(q)`: gravity generalized forces (N·m).
    Gravity,
    /// `q̈` from motor torques and tendon tensions.
    ForwardDynamics,
    /// Every tendon segment's tension (N), strand by strand, each from its anchored end.
    SegmentTensions,
    /// Force (N) and moment (N·m) on every body from its parent, motor torque excluded.
    Bearings,
    /// The base's force (N) and moment about `O_0` (N·m) on the mechanism, base frame.
    BaseReaction,
    /// `Q` with `∂Q/∂q` and `∂Q/∂q̇` (`crate::derivatives`), flattened value first, then
    /// each Jacobian row by row.
    GeneralizedForcesDerivatives,
    /// `q̈` with `∂q̈/∂q`, `∂q̈/∂q̇` and `∂q̈/∂u` (`u`: motor torques, then tendon
    /// tensions), flattened value first, then each Jacobian row by row.
    ForwardDynamicsDerivatives,
    /// The motor torques and tendon tensions of [`Actuation`](Output::Actuation) with
    /// their derivatives `∂/∂q`, `∂/∂q̇`, `∂/∂q̈` (`crate::derivatives`), flattened value
    /// first, then each Jacobian row by row.
    ActuationDerivatives,
    /// The identification regressor `Y(q, q̇, q̈)` (`crate::regressor`, every parameter's
    /// column) and the offset `Q₀`: `Q = Y π + Q₀`; flattened `Y` row by row, then `Q₀`.
    Regressor,
}

impl Output {
    /// Every output: the [`DEFAULT`](Output::DEFAULT) ones, then the derivatives and the
    /// regressor, which are generated only when asked for.
    pub const ALL: [Output; 13] = [
        Output::GeneralizedForces,
        Output::Actuation,
        Output::MassMatrix,
        Output::Bias,
        Output::Gravity,
        Output::ForwardDynamics,
        Output::SegmentTensions,
        Output::Bearings,
        Output::BaseReaction,
        Output::GeneralizedForcesDerivatives,
        Output::ForwardDynamicsDerivatives,
        Output::ActuationDerivatives,
        Output::Regressor,
    ];

    /// What is generated when no output is named, in the default order (that of
    /// `tendyn generate` and of the file): every output but the derivatives and the
    /// regressor, which come last in [`ALL`](Output::ALL).
    pub const DEFAULT: &'static [Output] = Output::ALL.split_at(9).0;

    /// The name of the generated function (and of the output on the command line).
    pub fn name(self) -> &'static str {
        match self {
            Output::GeneralizedForces => "generalized_forces",
            Output::Actuation => "actuation",
            Output::MassMatrix => "mass_matrix",
            Output::Bias => "bias",
            Output::Gravity => "gravity",
            Output::ForwardDynamics => "forward_dynamics",
            Output::SegmentTensions => "segment_tensions",
            Output::Bearings => "bearings",
            Output::BaseReaction => "base_reaction",
            Output::GeneralizedForcesDerivatives => "generalized_forces_derivatives",
            Output::ForwardDynamicsDerivatives => "forward_dynamics_derivatives",
            Output::ActuationDerivatives => "actuation_derivatives",
            Output::Regressor => "regressor",
        }
    }

    /// The output whose [`name`](Output::name) is `name`; `None` for any other name.
    pub fn parse(name: &str) -> Option<Output> {
        Output::ALL.into_iter().find(|o| o.name() == name)
    }

    /// The [`Data`](crate::Data) method that gives it (and that
    /// [`Data::output`](crate::Data::output) calls).
    pub fn evaluator(self) -> &'static str {
        match self {
            Output::GeneralizedForces => "generalized_forces",
            Output::MassMatrix => "mass_matrix",
            Output::Bias => "bias",
            Output::Gravity => "gravity",
            Output::ForwardDynamics => "forward_dynamics",
            Output::GeneralizedForcesDerivatives => "generalized_forces_derivatives",
            Output::ForwardDynamicsDerivatives => "forward_dynamics_derivatives",
            Output::ActuationDerivatives => "actuation_derivatives",
            Output::Regressor => "regressor",
            Output::Actuation
            | Output::SegmentTensions
            | Output::Bearings
            | Output::BaseReaction => "inverse_dynamics",
        }
    }

    /// The inputs the function takes, in order.
    pub fn params(self) -> &'static [Param] {
        match self {
            Output::MassMatrix | Output::Gravity => &[Param::Q],
            Output::Bias => &[Param::Q, Param::Qd],
            Output::ForwardDynamics | Output::ForwardDynamicsDerivatives => &[
                Param::Q,
                Param::Qd,
                Param::MotorTorques,
                Param::TendonTensions,
            ],
            _ => &[Param::Q, Param::Qd, Param::Qdd],
        }
    }
}

/// An array input of an output (and of its generated function).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Param {
    /// `q`: joint angles (rad), in joint order.
    Q,
    /// `qd`: joint rates (rad/s).
    Qd,
    /// `qdd`: joint accelerations (rad/s²).
    Qdd,
    /// `motor_torques` (N·m), in file order of the motors.
    MotorTorques,
    /// `tendon_tensions`: ground-level tensions (N), in file order of the open-ended
    /// tendons.
    TendonTensions,
    /// The mechanism's runtime parameters, in declaration order.
    Parameters,
}

impl Param {
    /// Every input, in the order `all` takes those it needs.
    pub const ALL: [Param; 6] = [
        Param::Q,
        Param::Qd,
        Param::Qdd,
        Param::MotorTorques,
        Param::TendonTensions,
        Param::Parameters,
    ];

    /// The argument's name in the generated signature.
    pub fn name(self) -> &'static str {
        match self {
            Param::Q => "q",
            Param::Qd => "qd",
            Param::Qdd => "qdd",
            Param::MotorTorques => "motor_torques",
            Param::TendonTensions => "tendon_tensions",
            Param::Parameters => "params",
        }
    }
}

/// The inputs of every output at one state; an output reads those its
/// [`params`](Output::params) name (runtime parameters are the model's).
#[derive(Clone, Copy, Debug)]
pub struct State<'a, T> {
    /// Joint angles (rad).
    pub q: &'a [T],
    /// Joint rates (rad/s).
    pub qd: &'a [T],
    /// Joint accelerations (rad/s²).
    pub qdd: &'a [T],
    /// Motor torques (N·m), file order (forward dynamics).
    pub motor_torques: &'a [T],
    /// Ground-level tendon tensions (N), file order (forward dynamics).
    pub tendon_tensions: &'a [T],
}

impl<T: Copy> InverseDynamics<T> {
    /// `output` flattened as its generated function returns it, when inverse dynamics
    /// gives it: `None` for the joint-space outputs (`mass_matrix`, `bias`, `gravity`,
    /// `forward_dynamics`), the derivatives and the regressor, and for segment tensions,
    /// bearings and the base reaction of an incomplete routing.
    pub fn flattened(&self, output: Output) -> Option<Vec<T>> {
        let mut out = Vec::new();
        self.extend_flattened(output, &mut out).then_some(out)
    }

    /// [`InverseDynamics::flattened`] appended to `out`, without a vector of its own (the
    /// Python package appends each state's to a field's values this way); `false`,
    /// appending nothing, where that gives `None`.
    pub fn extend_flattened(&self, output: Output, out: &mut Vec<T>) -> bool {
        let wrench = |(f, n): &(Vec3<T>, Vec3<T>)| [f.x, f.y, f.z, n.x, n.y, n.z];
        match output {
            Output::GeneralizedForces => out.extend(&self.generalized_forces),
            Output::Actuation => out.extend(self.motor_torques.iter().chain(&self.tendon_tensions)),
            // Slice by slice: a flattening iterator appends number by number.
            Output::SegmentTensions => match &self.segment_tensions {
                Some(s) => s.iter().for_each(|strand| out.extend_from_slice(strand)),
                None => return false,
            },
            Output::Bearings => match &self.bearings {
                Some(b) => b.iter().for_each(|w| out.extend_from_slice(&wrench(w))),
                None => return false,
            },
            Output::BaseReaction => match &self.base_reaction {
                Some(b) => out.extend(wrench(b)),
                None => return false,
            },
            Output::MassMatrix
            | Output::Bias
            | Output::Gravity
            | Output::ForwardDynamics
            | Output::GeneralizedForcesDerivatives
            | Output::ForwardDynamicsDerivatives
            | Output::ActuationDerivatives
            | Output::Regressor => return false,
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The order of docs/generated-code.md, written out by hand: torques then tensions;
    /// segments strand by strand; per body force then moment, x y z.
    #[test]
    fn flattened_numbers_are_in_the_documented_order() {
        let v = |x: f64, y: f64, z: f64| Vec3 { x, y, z };
        let r = InverseDynamics {
            generalized_forces: vec![1.0, 2.0],
            motor_torques: vec![3.0],
            tendon_tensions: vec![4.0, 5.0],
            minimal_norm_tensions: vec![],
            null_space_tensions: vec![],
            loop_sides: vec![],
            segment_tensions: Some(vec![vec![6.0, 7.0], vec![8.0]]),
            pulley_demands: vec![],
            bearings: Some(vec![
                (v(9.0, 10.0, 11.0), v(12.0, 13.0, 14.0)),
                (v(15.0, 16.0, 17.0), v(18.0, 19.0, 20.0)),
            ]),
            base_reaction: Some((v(21.0, 22.0, 23.0), v(24.0, 25.0, 26.0))),
            bearing_friction: vec![],
            sticking: vec![],
            unknowns: vec![],
        };
        let run = |a: u32, b: u32| (a..=b).map(f64::from).collect::<Vec<f64>>();
        assert_eq!(r.flattened(Output::GeneralizedForces), Some(run(1, 2)));
        assert_eq!(r.flattened(Output::Actuation), Some(run(3, 5)));
        assert_eq!(r.flattened(Output::SegmentTensions), Some(run(6, 8)));
        assert_eq!(r.flattened(Output::Bearings), Some(run(9, 20)));
        assert_eq!(r.flattened(Output::BaseReaction), Some(run(21, 26)));
        assert_eq!(r.flattened(Output::MassMatrix), None);
        // Appended after what is there; nothing appended where there is no such output.
        let mut out = vec![0.0];
        assert!(r.extend_flattened(Output::BaseReaction, &mut out));
        assert!(!r.extend_flattened(Output::Gravity, &mut out));
        assert_eq!(out, [&[0.0][..], &run(21, 26)].concat());
        let incomplete = InverseDynamics {
            segment_tensions: None,
            bearings: None,
            base_reaction: None,
            ..r
        };
        assert_eq!(incomplete.flattened(Output::Bearings), None);
    }
}
