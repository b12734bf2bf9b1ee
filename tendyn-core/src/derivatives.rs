//! Derivatives of the dynamics with respect to the state and the actuators, for model-
//! predictive control and trajectory optimisation: the generic functions run on
//! [`Dual`] numbers, one input coordinate seeded at a time (forward mode), so every
//! derivative is exact to round-off and follows the very arithmetic of the value.
//!
//! What [`crate::Data`] offers on this:
//!
//! - [`crate::Data::generalized_forces_derivatives`]: `∂Q/∂q`, `∂Q/∂q̇` (`∂Q/∂q̈ = M`, plus
//!   `Σ_i W_i ∂N_i/∂q̈ᵀ` where turning idlers follow guides with friction);
//! - [`crate::Data::forward_dynamics_derivatives`]: `∂q̈/∂q`, `∂q̈/∂q̇`, `∂q̈/∂u`, `u` the
//!   motor torques then the open-ended tendons' tensions;
//! - [`crate::Data::actuation_derivatives`]: the derivatives of the motor torques and
//!   tendon tensions inverse dynamics chooses, `∂(τ, T)/∂(q, q̇, q̈)`. Where the tension
//!   distribution's active set (which tendons sit at a floor or a maximum) does not change
//!   near the state, the distribution is differentiable and this is its derivative; at a
//!   change, it is the derivative of the active set chosen at the state (one-sided).
//!
//! Friction differentiates as its law: the smoothed `tanh` exactly; the exact law's
//! direction (a sign) has derivative zero away from rest, and none at it.

use crate::dual::Dual;
use crate::dynamics::{self, Workspace};
use crate::error::Error;
use crate::linalg;
use crate::model::{Model, TensionSystem};
use crate::real::Real;

/// A function's value at a state and its derivatives with respect to each input, each
/// row-major with one row per entry of `value` and one column per input coordinate:
/// `d_q[i * n + k] = ∂value_i/∂q_k`. Inputs a function does not take are empty.
#[derive(Clone, Debug, PartialEq)]
pub struct Derivatives<T> {
    /// The value.
    pub value: Vec<T>,
    /// `∂value/∂q` (`value.len() × n`).
    pub d_q: Vec<T>,
    /// `∂value/∂q̇` (`value.len() × n`).
    pub d_qd: Vec<T>,
    /// `∂value/∂q̈` (`value.len() × n`), where the function takes `q̈` and it is not
    /// otherwise known (empty for the generalized forces: `∂Q/∂q̈ = M`).
    pub d_qdd: Vec<T>,
    /// `∂value/∂u` (`value.len() × m`), `u` the motor torques then the tendon tensions,
    /// where the function takes them.
    pub d_u: Vec<T>,
}

impl<T: Copy> Derivatives<T> {
    /// The value, then `d_q`, `d_qd`, `d_qdd` and `d_u` (each row-major; absent ones add
    /// nothing): the order of the generated `*_derivatives` functions
    /// ([`crate::output`]).
    pub fn flattened(&self) -> Vec<T> {
        [
            &self.value[..],
            &self.d_q,
            &self.d_qd,
            &self.d_qdd,
            &self.d_u,
        ]
        .concat()
    }

    /// The derivatives from [`jacobians`]' blocks over `q`, `q̇` and, where the function
    /// takes them, `u`, in that order.
    fn of_blocks(value: Vec<T>, blocks: Vec<Vec<T>>) -> Self {
        let mut blocks = blocks.into_iter();
        let mut next = || blocks.next().unwrap_or_default();
        let (d_q, d_qd, d_u) = (next(), next(), next());
        Derivatives {
            value,
            d_q,
            d_qd,
            d_qdd: Vec::new(),
            d_u,
        }
    }
}

/// The Jacobians of `f` at `inputs`: `f` is evaluated once per coordinate of every input
/// on dual numbers with that coordinate's tangent one and every other zero. `f` writes
/// its result into the vector it is given. Returns the value and, per input, the
/// row-major Jacobian (`rows × inputs[i].len()`).
pub fn jacobians<T: Real, E>(
    inputs: &[&[T]],
    mut f: impl FnMut(&[Vec<Dual<T>>], &mut Vec<Dual<T>>) -> Result<(), E>,
) -> Result<(Vec<T>, Vec<Vec<T>>), E> {
    let mut seeded: Vec<Vec<Dual<T>>> = inputs
        .iter()
        .map(|x| x.iter().map(|&v| Dual::constant(v)).collect())
        .collect();
    let mut out = Vec::new();
    let mut value = Vec::new();
    let mut blocks: Vec<Vec<T>> = Vec::with_capacity(inputs.len());
    let mut columns: Vec<Vec<T>> = Vec::new();
    for i in 0..inputs.len() {
        columns.clear();
        for k in 0..inputs[i].len() {
            seeded[i][k].tangent = T::one();
            f(&seeded, &mut out)?;
            seeded[i][k].tangent = T::zero();
            if value.is_empty() {
                value = out.iter().map(|d| d.value).collect();
            }
            columns.push(out.iter().map(|d| d.tangent).collect());
        }
        // Row-major: entry (row r, coordinate k).
        let rows = value.len();
        let mut block = Vec::with_capacity(rows * columns.len());
        for r in 0..rows {
            block.extend(columns.iter().map(|c| c[r]));
        }
        blocks.push(block);
    }
    if value.is_empty() {
        // No input coordinate at all: the value alone.
        f(&seeded, &mut out)?;
        value = out.iter().map(|d| d.value).collect();
    }
    Ok((value, blocks))
}

/// The motor torques and tendon tensions of [`dynamics::inverse_dynamics`] on `dual` (the
/// model on dual numbers), with their derivatives with respect to `q`, `q̇` and `q̈` (`d_u`
/// empty), one coordinate seeded at a time: the runtime and generated code alike, each
/// with its own tension system at the state (`at_state`, for guides with capstan
/// friction) and distribution (`distribute`) as its inverse dynamics has them.
pub fn actuation_derivatives<T: Real>(
    dual: &Model<Dual<T>>,
    [q, qd, qdd]: [&[T]; 3],
    dual_ws: &mut Workspace<Dual<T>>,
    at_state: impl Fn(&Model<Dual<T>>, Vec<Vec<Dual<T>>>) -> Result<TensionSystem<Dual<T>>, Error>,
    distribute: impl Fn(&Model<Dual<T>>, &TensionSystem<Dual<T>>, &mut [Dual<T>]) -> Result<(), Error>,
) -> Result<Derivatives<T>, Error> {
    let mut r = dynamics::InverseDynamics::empty();
    let (value, blocks) = jacobians(&[q, qd, qdd], |x, out| {
        dynamics::inverse_dynamics(
            dual,
            &x[0],
            &x[1],
            &x[2],
            dual_ws,
            &at_state,
            &distribute,
            &mut r,
        )?;
        out.clear();
        out.extend(r.motor_torques.iter().chain(&r.tendon_tensions));
        Ok(())
    })?;
    let mut blocks = blocks.into_iter();
    let mut next = || blocks.next().unwrap_or_default();
    let (d_q, d_qd, d_qdd) = (next(), next(), next());
    Ok(Derivatives {
        value,
        d_q,
        d_qd,
        d_qdd,
        d_u: Vec::new(),
    })
}

/// `Q` with `∂Q/∂q` and `∂Q/∂q̇` (`d_qdd`, `d_u` empty): [`dynamics::generalized_forces`]
/// on `dual` (the model on dual numbers, [`Model::dual`]), one joint coordinate seeded at a
/// time. What the runtime, generated code and [`forward_dynamics_derivatives`] all use.
pub fn generalized_forces_derivatives<T: Real>(
    dual: &Model<Dual<T>>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    dual_ws: &mut Workspace<Dual<T>>,
) -> Derivatives<T> {
    let n = dual.dof();
    let qdd: Vec<Dual<T>> = qdd.iter().map(|&a| Dual::constant(a)).collect();
    let (value, blocks) = jacobians(&[q, qd], |x, out| {
        out.resize(n, Dual::constant(T::zero()));
        dynamics::generalized_forces(dual, &x[0], &x[1], &qdd, dual_ws, out);
        Ok::<(), ()>(())
    })
    .unwrap_or_default();
    Derivatives::of_blocks(value, blocks)
}

/// `q̈` of forward dynamics with `∂q̈/∂q`, `∂q̈/∂q̇` and `∂q̈/∂u` (`u`: motor torques, then
/// tendon tensions), by the unchecked `L D Lᵀ` solve of generated code (the runtime checks
/// that `M` is positive definite before).
///
/// By way of inverse dynamics (the route of Carpentier and Mansard for the derivatives of
/// the articulated-body algorithm): at the solution `q̈*`, `Q(q, q̇, q̈*) = Σ c_m τ_m + A T`,
/// so differentiating, `∂Q/∂x + M ∂q̈*/∂x = 0` for `x = q, q̇` and
/// `M ∂q̈*/∂u = [c_m | A]`. One dual pass of `Q` per joint coordinate and one substitution
/// per column, instead of a dual pass of the whole forward dynamics (mass matrix and
/// factorisation included) per input coordinate. Bearing friction differentiates alike
/// on both sides (its viscous part the same, its Coulomb part piecewise constant).
///
/// Where guides have capstan friction `A` depends on the state, and each input is seeded
/// through forward dynamics itself instead.
#[allow(clippy::too_many_arguments)]
pub fn forward_dynamics_derivatives<T: Real>(
    model: &Model<T>,
    dual: &Model<Dual<T>>,
    q: &[T],
    qd: &[T],
    motor_torques: &[T],
    tendon_tensions: &[T],
    ws: &mut Workspace<T>,
    dual_ws: &mut Workspace<Dual<T>>,
) -> Derivatives<T> {
    if model.has_capstan() {
        return forward_dynamics_seeded(dual, q, qd, motor_torques, tendon_tensions, dual_ws);
    }
    let n = model.dof();
    let mut factors: Vec<T> = dynamics::mass_matrix(model, q, ws).concat();
    linalg::ldlt_factor(&mut factors, n);
    let solve = |b: &mut [T]| linalg::ldlt_substitute(&factors, b);
    let mut qdd = dynamics::forward_dynamics_rhs(model, q, qd, motor_torques, tendon_tensions, ws);
    solve(&mut qdd);
    let at_solution = generalized_forces_derivatives(dual, q, qd, &qdd, dual_ws);
    // The actuators' columns: each motor's, then each tendon's structure column.
    let actuators: Vec<&[f64]> = model
        .motors()
        .iter()
        .map(|m| &m.column[..])
        .chain(model.tendons().iter().map(|k| &k.structure[..]))
        .collect();
    // `M⁻¹` times each column of `sign · block` (row-major, `n` rows), row-major again.
    let solved = |block: &dyn Fn(usize, usize) -> T, columns: usize| {
        let mut out = vec![T::zero(); n * columns];
        for c in 0..columns {
            let mut b: Vec<T> = (0..n).map(|i| block(i, c)).collect();
            solve(&mut b);
            for i in 0..n {
                out[i * columns + c] = b[i];
            }
        }
        out
    };
    let d_q = solved(&|i, c| -at_solution.d_q[i * n + c], n);
    let d_qd = solved(&|i, c| -at_solution.d_qd[i * n + c], n);
    let d_u = solved(&|i, c| T::from_f64(actuators[c][i]), actuators.len());
    Derivatives {
        value: qdd,
        d_q,
        d_qd,
        d_qdd: Vec::new(),
        d_u,
    }
}

/// [`forward_dynamics_derivatives`] with every input seeded through forward dynamics on
/// dual numbers (right-hand side, mass matrix and `L D Lᵀ`, idlers behind guides with
/// friction: [`dynamics::accelerations`]): the route where `A` depends on the state.
fn forward_dynamics_seeded<T: Real>(
    dual: &Model<Dual<T>>,
    q: &[T],
    qd: &[T],
    motor_torques: &[T],
    tendon_tensions: &[T],
    dual_ws: &mut Workspace<Dual<T>>,
) -> Derivatives<T> {
    let motors = motor_torques.len();
    let u: Vec<T> = motor_torques
        .iter()
        .chain(tendon_tensions)
        .copied()
        .collect();
    let (value, blocks) = jacobians(&[q, qd, &u], |x, out| {
        let (torques, tensions) = x[2].split_at(motors);
        *out = dynamics::forward_dynamics_rhs(dual, &x[0], &x[1], torques, tensions, dual_ws);
        let behind = dynamics::idlers_behind_capstan(dual, &x[0], &x[1], dual_ws);
        let mut mass = dynamics::mass_matrix(dual, &x[0], dual_ws).concat();
        linalg::ldlt_factor(&mut mass, out.len());
        dynamics::accelerations(&behind, |b| linalg::ldlt_substitute(&mass, b), out);
        Ok::<(), ()>(())
    })
    .unwrap_or_default();
    Derivatives::of_blocks(value, blocks)
}
