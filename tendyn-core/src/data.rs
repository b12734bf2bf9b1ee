//! The runtime front end: [`Data`], the work and result buffers of one mechanism's
//! evaluations (Pinocchio's `Data`), and its evaluators, which are the generic functions
//! of [`crate::dynamics`] with what only numbers can do: input checks, the tension
//! distribution for null spaces of any dimension, the positive-definiteness check of
//! forward dynamics, and a named error instead of any non-finite result.
//!
//! ```
//! # fn main() -> Result<(), tendyn_core::Error> {
//! use tendyn_core::{load, Data};
//! let model = load("../examples/mechanisms/example3_stanford_jpl.ron")?;
//! let mut data = Data::new(&model);
//! let r = data.inverse_dynamics(&model, &[0.1, 0.5, 0.3], &[0.0; 3], &[1.0, 0.0, 0.0])?;
//! assert!(r.tendon_tensions.iter().all(|&t| t >= 5.0 - 1e-9));
//! // The same buffers serve the same mechanism with other parameters, and nothing else.
//! let other = load("../examples/mechanisms/example1_endless.ron")?;
//! assert!(data.gravity(&other, &[0.0; 3]).is_err());
//! # Ok(())
//! # }
//! ```

use crate::affine::{Affine, MAX_UNKNOWNS};
use crate::derivatives::{self, Derivatives};
use crate::dual::Dual;
use crate::dynamics::{
    accelerations, actuator_forces, balance_at, bias, expanded_generalized_forces,
    forward_dynamics_rhs, generalized_forces, gravity, idlers_behind_capstan, inverse_dynamics,
    mass_matrix, structure, IdlerBehindCapstan, InverseDynamics, Workspace,
};
use crate::error::{Error, Result};
use crate::friction;
use crate::linalg;
use crate::model::{Model, TensionSystem};
use crate::output::{Output, State};
use crate::real::{Numeric, Real};
use crate::regressor;
use crate::spatial::Vec3;
use crate::tension;

/// The work and result buffers of the runtime solver for models of one shape (Pinocchio's
/// `Data`): the generic functions of [`crate::dynamics`] with input checks, on numbers.
/// The model is passed to every call, so that a controller can own both without a
/// lifetime; a `Data` made for a model of another shape is an error, never a panic.
///
/// `inverse_dynamics`, `generalized_forces`, `mass_matrix`, `bias`, `gravity`,
/// `forward_dynamics` and `regressor` lend their results out of the buffers until the next
/// call; the derivatives, `actuator_forces`, `forward_dynamics_scale`, `output` and
/// `balance_rows` return theirs as owned values.
///
/// Errors: `Error::Model` for a `Data` made for a model of another shape, `Error::State`
/// for a state (or actuator input) of the wrong length or not finite, or a result that
/// overflowed the scalar; see each evaluator for the others.
#[derive(Clone, Debug)]
pub struct Data<T: Real> {
    shape: Shape,
    ws: Workspace<T>,
    generalized_forces: Vec<T>,
    mass_matrix: Vec<Vec<T>>,
    bias: Vec<T>,
    gravity: Vec<T>,
    joint_accelerations: Vec<T>,
    inverse_dynamics: InverseDynamics<T>,
    regressor_work: regressor::Work<T>,
    regressor: Regressor<T>,
    /// The derivatives' dual-number copy of the model, made on their first call and
    /// again only for another model (copying the model costs about as much as a few
    /// evaluations of `Q`).
    dual: Option<Box<DualCopy<T>>>,
}

/// A model on dual numbers ([`Model::dual`]) and work buffers for it.
#[derive(Clone, Debug)]
struct DualCopy<T: Real> {
    /// The [`Model::identity`] of the model it was copied from.
    identity: usize,
    model: Model<Dual<T>>,
    ws: Workspace<Dual<T>>,
}

/// `slot`'s dual copy of `model`, made anew if it holds none or one of another model.
fn dual_copy<'a, T: Real>(
    slot: &'a mut Option<Box<DualCopy<T>>>,
    model: &Model<T>,
) -> &'a mut DualCopy<T> {
    if slot.as_ref().is_some_and(|d| d.identity != model.identity) {
        *slot = None;
    }
    slot.get_or_insert_with(|| {
        let dual = model.dual();
        let ws = Workspace::new(&dual);
        Box::new(DualCopy {
            identity: model.identity,
            model: dual,
            ws,
        })
    })
}

/// The identification regressor at one state ([`crate::regressor`]): `Q = Y π + Q₀`.
#[derive(Clone, Debug, PartialEq)]
pub struct Regressor<T> {
    /// Columns of `Y`: the count of [`regressor::parameters`].
    pub columns: usize,
    /// `Y`, `n` rows of `columns` entries, row-major.
    pub y: Vec<T>,
    /// `Q₀`, the generalized forces the actuators need whatever `π` (the external
    /// wrench's; zero without one).
    pub known: Vec<T>,
}

/// What the work buffers' sizes depend on: joints, bodies, unknowns and rows of the
/// tension system, and each strand's segments and idler steps.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Shape {
    dof: usize,
    bodies: usize,
    unknowns: usize,
    rows: usize,
    strands: Vec<(usize, usize)>,
}

impl Shape {
    fn of<T>(model: &Model<T>) -> Self {
        Shape {
            dof: model.dof(),
            bodies: model.bodies().len(),
            unknowns: model.system().unknowns.len(),
            rows: model.system().rows.len(),
            strands: model
                .strands()
                .iter()
                .map(|s| (s.segments.len(), s.idlers.len()))
                .collect(),
        }
    }

    /// Whether `model` has this shape (no allocation).
    fn fits<T>(&self, model: &Model<T>) -> bool {
        self.dof == model.dof()
            && self.bodies == model.bodies().len()
            && self.unknowns == model.system().unknowns.len()
            && self.rows == model.system().rows.len()
            && self.strands.len() == model.strands().len()
            && self
                .strands
                .iter()
                .zip(model.strands())
                .all(|(&(segments, idlers), s)| {
                    segments == s.segments.len() && idlers == s.idlers.len()
                })
    }
}

impl<T: Numeric> Data<T> {
    /// Buffers for `model`, and for every model of its shape (the same mechanism with other
    /// parameters, [`Model::with_parameters`]).
    pub fn new(model: &Model<T>) -> Self {
        let n = model.dof();
        Data {
            shape: Shape::of(model),
            ws: Workspace::new(model),
            generalized_forces: vec![T::zero(); n],
            mass_matrix: vec![vec![T::zero(); n]; n],
            bias: vec![T::zero(); n],
            gravity: vec![T::zero(); n],
            joint_accelerations: vec![T::zero(); n],
            inverse_dynamics: InverseDynamics::empty(),
            regressor_work: regressor::Work::new(model),
            regressor: Regressor {
                columns: 0,
                y: Vec::new(),
                known: Vec::new(),
            },
            dual: None,
        }
    }

    /// `Err` unless these buffers fit `model`.
    fn check_model(&self, model: &Model<T>) -> Result<()> {
        if self.shape.fits(model) {
            return Ok(());
        }
        Err(Error::State(format!(
            "this Data was made for a mechanism of another shape than `{}` ({} joints, {} \
             bodies, {} tension unknowns); make one with `Data::new(&model)`",
            model.name(),
            self.shape.dof,
            self.shape.bodies,
            self.shape.unknowns
        )))
    }

    /// `Err` unless these buffers fit `model` and every named state vector has one finite
    /// entry per joint.
    fn check_states(&self, model: &Model<T>, states: &[(&str, &[T])]) -> Result<()> {
        self.check_model(model)?;
        states
            .iter()
            .try_for_each(|(what, v)| model.check_state(what, v))
    }

    /// Generalized forces the actuators deliver, `Q = M q̈ + h + g − Jᵀ w_ext − Q_friction`
    /// (plus `Σ_i W_i (N_i − τ_f,i)` where turning idlers follow guides with friction:
    /// [`generalized_forces`]). Friction at rest (within the band of format.md §4a) takes
    /// the direction of `q̈`, as inverse dynamics does.
    pub fn generalized_forces(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<&[T]> {
        self.check_states(model, &[("q", q), ("qd", qd), ("qdd", qdd)])?;
        let out = &mut self.generalized_forces;
        generalized_forces(model, q, qd, qdd, &mut self.ws, out);
        finite(
            "generalized forces",
            &*out,
            &[("q", q), ("qd", qd), ("qdd", qdd)],
        )?;
        Ok(out)
    }

    /// The identification regressor at a state: `Y` and `Q₀` with
    /// `Q = Y π + Q₀` ([`crate::regressor`]), `π` the parameters of
    /// [`regressor::parameters`] (their model values: [`regressor::values`]).
    pub fn regressor(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<&Regressor<T>> {
        self.check_states(model, &[("q", q), ("qd", qd), ("qdd", qdd)])?;
        let n = model.dof();
        let columns = regressor::count(model);
        let out = &mut self.regressor;
        out.columns = columns;
        out.y.resize(n * columns, T::zero());
        out.known.resize(n, T::zero());
        regressor::regressor(
            model,
            q,
            qd,
            qdd,
            &mut self.regressor_work,
            &mut out.y,
            &mut out.known,
        );
        let inputs = [("q", q), ("qd", qd), ("qdd", qdd)];
        finite("regressor", out.y.iter().chain(&out.known), &inputs)?;
        Ok(&self.regressor)
    }

    /// `Q` and its derivatives `∂Q/∂q`, `∂Q/∂q̇` ([`derivatives::generalized_forces_derivatives`];
    /// `∂Q/∂q̈` is `M`, [`Data::mass_matrix`], plus `Σ_i W_i ∂N_i/∂q̈ᵀ` where turning idlers
    /// follow guides with friction, [`crate::dynamics::idlers_behind_capstan`]).
    pub fn generalized_forces_derivatives(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<Derivatives<T>> {
        self.check_states(model, &[("q", q), ("qd", qd), ("qdd", qdd)])?;
        let dual = dual_copy(&mut self.dual, model);
        let d = derivatives::generalized_forces_derivatives(&dual.model, q, qd, qdd, &mut dual.ws);
        finite_derivatives("generalized forces", &d, &[("q", q), ("qd", qd)])?;
        Ok(d)
    }

    /// `q̈` of forward dynamics and its derivatives `∂q̈/∂q`, `∂q̈/∂q̇` and `∂q̈/∂u`, `u`
    /// the motor torques then the tendon tensions
    /// ([`derivatives::forward_dynamics_derivatives`], after the checked solve of
    /// [`Data::forward_dynamics`] has vouched that `M` is positive definite). Checked as
    /// [`Data::forward_dynamics`] is.
    pub fn forward_dynamics_derivatives(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<Derivatives<T>> {
        let inputs = self.check_forward_inputs(model, q, qd, motor_torques, tendon_tensions)?;
        self.forward_dynamics(model, q, qd, motor_torques, tendon_tensions)?;
        let dual = dual_copy(&mut self.dual, model);
        let d = derivatives::forward_dynamics_derivatives(
            model,
            &dual.model,
            q,
            qd,
            motor_torques,
            tendon_tensions,
            &mut self.ws,
            &mut dual.ws,
        );
        finite_derivatives("joint acceleration", &d, &inputs)?;
        Ok(d)
    }

    /// The motor torques and tendon tensions of inverse dynamics (in that order, as one
    /// vector) and their derivatives with respect to `q`, `q̇`, `q̈`
    /// ([`crate::derivatives`]: where the distribution's active set changes, those of the
    /// active set chosen at the state). Errors as [`Data::inverse_dynamics`].
    pub fn actuation_derivatives(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<Derivatives<T>> {
        self.check_model(model)?;
        solvable(model)?;
        let inputs = [("q", q), ("qd", qd), ("qdd", qdd)];
        self.check_states(model, &inputs)?;
        // As inverse dynamics: tensions that overflowed are reported before the
        // distribution sees them.
        let distribute =
            |model: &Model<Dual<T>>, system: &TensionSystem<Dual<T>>, x: &mut [Dual<T>]| {
                finite(
                    "tension or motor torque",
                    x.iter().map(|d| d.value),
                    &inputs,
                )?;
                tension::distribute(model, system, x)
            };
        let dual = dual_copy(&mut self.dual, model);
        let derivatives = derivatives::actuation_derivatives(
            &dual.model,
            [q, qd, qdd],
            &mut dual.ws,
            tension::system_at,
            distribute,
        )?;
        finite_derivatives("actuation", &derivatives, &inputs)?;
        Ok(derivatives)
    }

    /// Joint-space mass matrix `M(q)`.
    pub fn mass_matrix(&mut self, model: &Model<T>, q: &[T]) -> Result<&[Vec<T>]> {
        self.check_states(model, &[("q", q)])?;
        self.mass_matrix = mass_matrix(model, q, &mut self.ws);
        finite(
            "mass matrix",
            self.mass_matrix.iter().flatten(),
            &[("q", q)],
        )?;
        Ok(&self.mass_matrix)
    }

    /// Bias `h(q, q̇)`.
    pub fn bias(&mut self, model: &Model<T>, q: &[T], qd: &[T]) -> Result<&[T]> {
        self.check_states(model, &[("q", q), ("qd", qd)])?;
        self.bias = bias(model, q, qd, &mut self.ws);
        finite("bias", &self.bias, &[("q", q), ("qd", qd)])?;
        Ok(&self.bias)
    }

    /// Gravity generalized forces `g(q)`.
    pub fn gravity(&mut self, model: &Model<T>, q: &[T]) -> Result<&[T]> {
        self.check_states(model, &[("q", q)])?;
        self.gravity = gravity(model, q, &mut self.ws);
        finite("gravity", &self.gravity, &[("q", q)])?;
        Ok(&self.gravity)
    }

    /// `‖M⁻¹ (|A| |T| + |B| |τ| + |h + g − Q_ext| + Σ_b |c_b τ_f,b|)‖∞`: the size of the
    /// terms forward dynamics sums (`A`, `B` the tendons' and motors' columns, `τ_f,b` the
    /// bearings' friction; with idlers behind guides with friction also `|W_i N_i,0|`, and
    /// `M⁻¹` is then that of `M + W Jᵀ`, [`crate::dynamics::accelerations`]). Tensions that balance each
    /// other make `q̈` a small difference of large numbers, so the error of a forward
    /// dynamics result is meaningful relative to this, not to `‖q̈‖`.
    ///
    /// Checked as [`Data::forward_dynamics`] is, with the same errors: the inputs (their
    /// lengths and finiteness), every intermediate result, and the mass matrix (which must
    /// be positive definite); a finite scale or an error, never a non-finite number.
    pub fn forward_dynamics_scale(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<T> {
        let inputs = self.check_forward_inputs(model, q, qd, motor_torques, tendon_tensions)?;
        let zero = T::from_f64(0.0);
        let mut behind = idlers_behind_capstan(model, q, qd, &mut self.ws);
        let a = structure(model, q, qd, &mut self.ws);
        let zeros = vec![zero; model.dof()];
        let mut c = zeros.clone();
        expanded_generalized_forces(model, q, qd, &zeros, true, true, &mut self.ws, &mut c);
        finite("generalized forces", &c, &inputs)?;
        // The bearings' friction, each body's part on its own: it may cancel gravity.
        let mut torques = vec![zero; model.bodies.len()];
        friction::bearing_torques(model, qd, None, &mut torques);
        let rhs: Vec<T> = (0..model.dof)
            .map(|j| {
                let motors = model
                    .motors
                    .iter()
                    .zip(motor_torques)
                    .fold(zero, |s, (m, &t)| s + (T::from_f64(m.column[j]) * t).abs());
                let tendons = a
                    .iter()
                    .zip(tendon_tensions)
                    .fold(zero, |s, (a, &t)| s + (a[j] * t).abs());
                let friction = model
                    .bodies
                    .iter()
                    .zip(&torques)
                    .fold(zero, |s, (b, &t)| s + (b.coupling[j] * t).abs());
                let idlers = (behind.iter()).fold(zero, |s, i| s + (i.weight[j] * i.demand).abs());
                motors + tendons + c[j].abs() + friction + idlers
            })
            .collect();
        finite("right-hand side of forward dynamics", &rhs, &inputs)?;
        // The magnitudes are the right-hand side: only `(M + W Jᵀ)⁻¹` of the idlers.
        for idler in &mut behind {
            idler.demand = zero;
        }
        let y = self.solve_mass_matrix(model, q, &rhs, &behind)?;
        // (`max` would pass over a NaN.)
        finite("forward-dynamics term scale", &y, &inputs)?;
        Ok(y.iter().fold(zero, |a, x| a.max(x.abs())))
    }

    /// Forward dynamics: `q̈` from the motor torques (file order) and the ground-level
    /// tensions of the open-ended tendons (file order). Friction's directions come from
    /// `q̇` alone (none at rest, or the smoothed law: format.md §4a). `Error::Singular`
    /// where the mass matrix is not positive definite.
    pub fn forward_dynamics(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<&[T]> {
        let inputs = self.check_forward_inputs(model, q, qd, motor_torques, tendon_tensions)?;
        let rhs = forward_dynamics_rhs(model, q, qd, motor_torques, tendon_tensions, &mut self.ws);
        finite("right-hand side of forward dynamics", &rhs, &inputs)?;
        // Idlers whose inertia reaches the joints through a guide's friction (none in most
        // mechanisms) make the system unsymmetric: `dynamics::accelerations`.
        let behind = idlers_behind_capstan(model, q, qd, &mut self.ws);
        self.joint_accelerations = self.solve_mass_matrix(model, q, &rhs, &behind)?;
        finite("joint acceleration", &self.joint_accelerations, &inputs)?;
        Ok(&self.joint_accelerations)
    }

    /// The generalized forces that motor torques and ground-level tendon tensions deliver
    /// at `(q, q̇)`: `Σ motor columns · τ + A(q, q̇) T` ([`actuator_forces`], `A` the state's
    /// where guides have capstan friction). What identification takes as measured `Q`.
    /// It equals [`Data::generalized_forces`] of the motion the torques and tensions produce
    /// (where turning idlers follow guides with friction, that includes their
    /// `Σ_i W_i (N_i − τ_f,i)`) wherever no guide or bearing is within the band of rest:
    /// there `σ` and the bearings' directions come from `q̇` alone here, as in forward
    /// dynamics, and from `q̈` in inverse dynamics.
    pub fn actuator_forces(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<Vec<T>> {
        let inputs = self.check_forward_inputs(model, q, qd, motor_torques, tendon_tensions)?;
        let a = structure(model, q, qd, &mut self.ws);
        let out = actuator_forces(model, &a, motor_torques, tendon_tensions);
        finite("actuator forces", &out, &inputs)?;
        Ok(out)
    }

    /// The input checks of forward dynamics: buffers that fit the model, the state, and as
    /// many finite motor torques and tendon tensions as the mechanism has motors and
    /// open-ended tendons; the inputs by name, for the errors of the results.
    fn check_forward_inputs<'a>(
        &self,
        model: &Model<T>,
        q: &'a [T],
        qd: &'a [T],
        motor_torques: &'a [T],
        tendon_tensions: &'a [T],
    ) -> Result<[(&'static str, &'a [T]); 4]> {
        self.check_states(model, &[("q", q), ("qd", qd)])?;
        if motor_torques.len() != model.motors.len() || tendon_tensions.len() != model.tendons.len()
        {
            return Err(Error::State(format!(
                "expected {} motor torques and {} tendon tensions, got {} and {}",
                model.motors.len(),
                model.tendons.len(),
                motor_torques.len(),
                tendon_tensions.len()
            )));
        }
        for (what, v) in [
            ("motor torque", motor_torques),
            ("tendon tension", tendon_tensions),
        ] {
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(Error::State(format!(
                    "a {what} is {}; inputs must be finite",
                    x.to_f64()
                )));
            }
        }
        Ok([
            ("q", q),
            ("qd", qd),
            ("motor_torques", motor_torques),
            ("tendon_tensions", tendon_tensions),
        ])
    }

    /// `M(q)⁻¹ rhs` by the checked Cholesky factorisation of forward dynamics.
    /// With idlers behind guides with friction, the accelerations of
    /// [`crate::dynamics::accelerations`] over that factor.
    fn solve_mass_matrix(
        &mut self,
        model: &Model<T>,
        q: &[T],
        rhs: &[T],
        behind: &[IdlerBehindCapstan<T>],
    ) -> Result<Vec<T>> {
        let m = mass_matrix(model, q, &mut self.ws);
        finite("mass matrix", m.iter().flatten(), &[("q", q)])?;
        let mut factor: Vec<T> = m.into_iter().flatten().collect();
        if !linalg::cholesky_factor(&mut factor, model.dof()) {
            return Err(Error::Singular(
                "the mass matrix is not positive definite at this state (a massless chain, or a \
                 link whose motion nothing resists)"
                    .into(),
            ));
        }
        let mut x = rhs.to_vec();
        accelerations(behind, |b| linalg::cholesky_substitute(&factor, b), &mut x);
        Ok(x)
    }

    /// Inverse dynamics by the paper's recursion (see [`inverse_dynamics`]), with the
    /// tension distribution for null spaces of any dimension ([`tension::distribute`]:
    /// every tendon within its floor and maximum, the model's objective least).
    ///
    /// Errors besides those of every evaluator: `Error::State` for a model without tendons
    /// or motors (nothing to solve for: use [`Data::generalized_forces`]);
    /// `Error::Tension` where no tensions within the bounds produce the motion, or, with
    /// capstan friction, where the state's tension system cannot be solved (docs/outputs.md
    /// §7).
    pub fn inverse_dynamics(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<&InverseDynamics<T>> {
        self.check_model(model)?;
        solvable(model)?;
        let inputs = [("q", q), ("qd", qd), ("qdd", qdd)];
        self.check_states(model, &inputs)?;
        // Tensions that overflowed are reported before the distribution sees them, with the
        // input to blame.
        let distribute = |model: &Model<T>, system: &TensionSystem<T>, x: &mut [T]| {
            finite("tension or motor torque", &*x, &inputs)?;
            tension::distribute(model, system, x)
        };
        let r = &mut self.inverse_dynamics;
        inverse_dynamics(
            model,
            q,
            qd,
            qdd,
            &mut self.ws,
            tension::system_at,
            distribute,
            r,
        )?;
        r.sticking = friction::at_rest(model, qd);
        finite("generalized forces", &r.generalized_forces, &inputs)?;
        finite("tension or motor torque", &r.unknowns, &inputs)?;
        finite(
            "pulley moment",
            r.pulley_demands.iter().map(|(_, v)| v),
            &inputs,
        )?;
        finite(
            "bearing friction",
            r.bearing_friction.iter().map(|(_, v)| v),
            &inputs,
        )?;
        if let Some(s) = &r.segment_tensions {
            finite("segment tension", s.iter().flatten(), &inputs)?;
        }
        let wrench = |(f, n): &(Vec3<T>, Vec3<T>)| f.to_array().into_iter().chain(n.to_array());
        if let Some(b) = &r.bearings {
            finite("bearing force", b.iter().flat_map(wrench), &inputs)?;
        }
        if let Some(b) = &r.base_reaction {
            finite("base reaction", wrench(b), &inputs)?;
        }
        Ok(r)
    }

    /// `output` at `state` by the evaluator that gives it, flattened as its generated
    /// function returns it ([`crate::output`]): what the report and the checks compare
    /// generated code with. An output the routing cannot attribute (segment tensions,
    /// bearings, base reaction with explicit couplings or structure columns) is an
    /// [`Error::State`] that says so.
    pub fn output(&mut self, model: &Model<T>, output: Output, state: &State<T>) -> Result<Vec<T>> {
        let State {
            q,
            qd,
            qdd,
            motor_torques,
            tendon_tensions,
        } = *state;
        Ok(match output {
            Output::MassMatrix => self.mass_matrix(model, q)?.concat(),
            Output::Bias => self.bias(model, q, qd)?.to_vec(),
            Output::Gravity => self.gravity(model, q)?.to_vec(),
            Output::GeneralizedForces => self.generalized_forces(model, q, qd, qdd)?.to_vec(),
            Output::ForwardDynamics => self
                .forward_dynamics(model, q, qd, motor_torques, tendon_tensions)?
                .to_vec(),
            Output::GeneralizedForcesDerivatives => self
                .generalized_forces_derivatives(model, q, qd, qdd)?
                .flattened(),
            Output::ForwardDynamicsDerivatives => self
                .forward_dynamics_derivatives(model, q, qd, motor_torques, tendon_tensions)?
                .flattened(),
            Output::ActuationDerivatives => {
                self.actuation_derivatives(model, q, qd, qdd)?.flattened()
            }
            Output::Regressor => {
                let r = self.regressor(model, q, qd, qdd)?;
                [&r.y[..], &r.known].concat()
            }
            _ => self
                .inverse_dynamics(model, q, qd, qdd)?
                .flattened(output)
                .ok_or_else(|| {
                    Error::State(format!(
                        "`{}` is not available: the routing of `{}` is incomplete (an explicit \
                         coupling or structure column), so where those transmissions act is \
                         unknown",
                        output.name(),
                        model.name()
                    ))
                })?,
        })
    }

    /// The balance rows of `E x = b` at a state, as affine forms in the unknowns (for
    /// checks of the recursion against the transmission's `E`: their coefficients are
    /// `−E` on the strand columns, their constants `b`). At most [`MAX_UNKNOWNS`] unknowns;
    /// the model and the state are checked as for every evaluator, the rows (a check's
    /// raw material) are not.
    pub fn balance_rows(
        &mut self,
        model: &Model<T>,
        q: &[T],
        qd: &[T],
        qdd: &[T],
    ) -> Result<Vec<Affine<T>>> {
        self.check_model(model)?;
        let nu = model.system().unknowns.len();
        if nu > MAX_UNKNOWNS {
            return Err(Error::State(format!(
                "`{}` has {nu} unknowns; balance rows as affine forms carry at most {MAX_UNKNOWNS}",
                model.name()
            )));
        }
        self.check_states(model, &[("q", q), ("qd", qd), ("qdd", qdd)])?;
        Ok(balance_at(model, q, qd, qdd, &mut self.ws))
    }
}

impl<T: Numeric> Model<T> {
    /// `Err` unless `v` (named `what` in the message: `q`, `qd`, …) has one finite entry
    /// per joint: the check every evaluator of [`Data`] makes of its state.
    pub fn check_state(&self, what: &str, v: &[T]) -> Result<()> {
        let n = self.dof();
        if v.len() != n {
            return Err(Error::State(format!(
                "{what} has {} entries but the mechanism has {n} joints",
                v.len()
            )));
        }
        if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::State(format!(
                "{what}[{i}] is {}; every entry must be finite",
                x.to_f64()
            )));
        }
        Ok(())
    }
}

/// `Err` for a model without tendons or motors, whose inverse dynamics has nothing to
/// solve for.
fn solvable<T: Real>(model: &Model<T>) -> Result<()> {
    if model.system().unknowns.is_empty() {
        return Err(Error::State(format!(
            "`{}` has no tendons or motors to solve for (a rigid tree): its generalized \
             forces are `Data::generalized_forces`",
            model.name()
        )));
    }
    Ok(())
}

/// [`finite`] over a value and every derivative.
fn finite_derivatives<T: Numeric>(
    what: &str,
    d: &Derivatives<T>,
    inputs: &[(&str, &[T])],
) -> Result<()> {
    let all = d.value.iter().chain(&d.d_q).chain(&d.d_qd).chain(&d.d_qdd);
    finite(
        &format!("derivative of the {what}"),
        all.chain(&d.d_u),
        inputs,
    )
}

/// `Err` when a result is not finite although the inputs were: some intermediate value
/// overflowed the scalar (a speed of 1e200 rad/s squares to infinity). The solver returns
/// this error rather than a non-finite number, and names the largest of the `inputs`
/// (each a name and its values), which is almost always the one to blame.
fn finite<T: Numeric>(
    what: &str,
    values: impl IntoIterator<Item = impl core::borrow::Borrow<T>>,
    inputs: &[(&str, &[T])],
) -> Result<()> {
    let Some(x) = values
        .into_iter()
        .map(|x| *x.borrow())
        .find(|x| !x.is_finite())
    else {
        return Ok(());
    };
    let largest = inputs
        .iter()
        .flat_map(|(name, v)| {
            v.iter()
                .enumerate()
                .map(move |(i, x)| (*name, i, x.to_f64()))
        })
        .fold(None, |best: Option<(&str, usize, f64)>, c| match best {
            Some(b) if b.2.abs() >= c.2.abs() => Some(b),
            _ => Some(c),
        });
    let blame = match largest {
        Some((name, i, v)) => format!(
            "; the largest input is {name}[{i}] = {v:e}: make it smaller (a real mechanism's \
             speeds, accelerations and forces are many orders of magnitude below the scalar's \
             range)"
        ),
        None => String::new(),
    };
    Err(Error::State(format!(
        "the {what} came out {} at this state although every input is finite: an intermediate \
         value overflowed the scalar{blame}",
        x.to_f64()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model fits a `Data` only if every size its buffers depend on is the same: the
    /// rows of the tension system included (with a row fewer, `E x = b` would silently
    /// drop a balance and give wrong torques instead of an error).
    #[test]
    fn a_model_differing_in_any_size_of_the_buffers_does_not_fit() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/mechanisms/example1_endless.ron"
        );
        let model = crate::load(path).unwrap();
        assert!(Shape::of(&model).fits(&model));
        let changes: [fn(&mut Shape); 6] = [
            |s| s.dof += 1,
            |s| s.bodies += 1,
            |s| s.unknowns += 1,
            |s| s.rows += 1,
            |s| s.strands.push((1, 0)),
            |s| s.strands[0].0 += 1,
        ];
        for (i, change) in changes.iter().enumerate() {
            let mut shape = Shape::of(&model);
            change(&mut shape);
            assert!(!shape.fits(&model), "change {i}");
        }
    }
}
