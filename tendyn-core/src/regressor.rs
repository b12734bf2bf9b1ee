//! The identification regressor: `Q = Y(q, q̇, q̈) π + Q₀`, the generalized forces of
//! [`crate::dynamics::generalized_forces`] linear in the inertial parameters `π` of every
//! body of the expanded tree (links and pulleys alike) and in the friction parameters of
//! every bearing the file gives a `friction`.
//!
//! # The parameters
//!
//! Per body, in its own frame (the frame of the mass properties in the file), ten inertial
//! parameters in this order ([`INERTIAL`]):
//!
//! > `m`, `mx`, `my`, `mz` (`m c`, the first moment), `xx`, `xy`, `xz`, `yy`, `yz`, `zz`
//! > (the inertia tensor about the **body-frame origin**, `I_o = I_c + m (|c|² 1 − c cᵀ)`),
//!
//! then, where the body's bearing has friction, `coulomb` and `viscous`. Body order is the
//! model's (links, then pulleys); [`parameters`] lists them and [`values`] gives the
//! model's own.
//!
//! # The derivation (virtual power, not the Newton-Euler recursion)
//!
//! With `a` the acceleration of the body-frame origin (gravity included as `−g`), `ω`, `ω̇`
//! the body's angular velocity and acceleration (all from [`crate::kinematics::forward`]),
//! the body's inertial force and moment about its origin are linear in `π`:
//!
//! ```text
//! F = m a + ω̇ × h + ω × (ω × h)            h = m c
//! N = I_o ω̇ + ω × (I_o ω) + h × a
//! ```
//!
//! (Eqs. 21-22 moved to the origin by the parallel-axis theorem). By virtual power, a
//! wrench `(F, N)` at the origin needs the generalized force `J_vᵀ F + J_ωᵀ N` of the
//! actuators, where `J_v`, `J_ω` map `q̇` to the origin's velocity and the body's angular
//! velocity, couplings included. Those Jacobians are read off the forward recursion
//! itself: at `q̇ = 0`, `q̈ = e_k` and no gravity, the origin's acceleration is `J_v e_k`
//! and the angular acceleration `J_ω e_k`. So, per joint `k`, with `u = J_v e_k`,
//! `r = J_ω e_k` and `s = r × ω`:
//!
//! ```text
//! Y[k, m]           = u · a
//! Y[k, (mx,my,mz)]  = u × ω̇ + (u × ω) × ω + a × r
//! Y[k, I_ij]        = r_i ω̇_j + s_i ω_j   (+ the same with i, j swapped when i ≠ j)
//! ```
//!
//! A bearing's friction torque `τ_f = −(coulomb · s + viscous · ω_b)` ([`crate::friction`])
//! needs `−c_bᵀ τ_f` of the actuators: its columns are `c_b s` and `c_b ω_b`. Where a
//! turning idler follows a guide with capstan friction, the actuators deliver
//! `W_i (N_i − τ_f,i)` more ([`crate::dynamics::idlers_behind_capstan`]); its axial demand
//! `N_i = axis · N` is the row above with `u = 0`, `r` the idler's axis, and its friction
//! adds `W_i s` and `W_i ω_b` to its two columns. The external
//! wrench, not a parameter, is the known part `Q₀ = −J_bᵀ (f, n + p × f)` of its link `b`.
//!
//! This shares the forward recursion with [`crate::dynamics`] but not the backward one, so
//! `Y π + Q₀ = Q` checks the Newton-Euler recursion against the principle of virtual power.

use crate::composite::point_shift;
use crate::dynamics;
use crate::friction;
use crate::kinematics::{forward, Motion};
use crate::model::Model;
use crate::real::Real;
use crate::spatial::Vec3;

/// The names of a body's ten inertial parameters, in the regressor's order.
pub const INERTIAL: [&str; 10] = ["m", "mx", "my", "mz", "xx", "xy", "xz", "yy", "yz", "zz"];

/// The index pairs `(i, j)` of the inertia entries `xx, xy, xz, yy, yz, zz`.
const INERTIA_ENTRIES: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// What a parameter of the regressor is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Inertial parameter `INERTIAL[i]` of the body.
    Inertial(usize),
    /// The Coulomb torque of the body's bearing (N·m).
    Coulomb,
    /// The viscous coefficient of the body's bearing (N·m·s/rad).
    Viscous,
}

/// One parameter of the regressor: a quantity of a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The body (index into [`Model::bodies`]).
    pub body: usize,
    /// Which of its quantities.
    pub quantity: Quantity,
}

impl Parameter {
    /// `body.quantity`, e.g. `link2.zz` or `pulley1.coulomb`.
    pub fn name<T>(&self, model: &Model<T>) -> String {
        let body = &model.bodies[self.body].name;
        match self.quantity {
            Quantity::Inertial(i) => format!("{body}.{}", INERTIAL[i]),
            Quantity::Coulomb => format!("{body}.coulomb"),
            Quantity::Viscous => format!("{body}.viscous"),
        }
    }
}

/// The regressor's parameters, in its column order: every body's ten inertial ones, then
/// its bearing's two where the file gives it a `friction`.
pub fn parameters<T>(model: &Model<T>) -> Vec<Parameter> {
    let mut out = Vec::new();
    for (body, b) in model.bodies.iter().enumerate() {
        out.extend((0..10).map(|i| Parameter {
            body,
            quantity: Quantity::Inertial(i),
        }));
        if b.friction.is_some() {
            for quantity in [Quantity::Coulomb, Quantity::Viscous] {
                out.push(Parameter { body, quantity });
            }
        }
    }
    out
}

/// How many parameters [`parameters`] lists (the columns of `Y`).
pub fn count<T>(model: &Model<T>) -> usize {
    model
        .bodies
        .iter()
        .map(|b| 10 + if b.friction.is_some() { 2 } else { 0 })
        .sum()
}

/// The model's own parameter values `π`, in [`parameters`]' order.
pub fn values<T: Real>(model: &Model<T>) -> Vec<T> {
    let mut out = Vec::new();
    for b in &model.bodies {
        let (m, c) = (b.mass, b.com);
        let h = c.scale(m);
        // Parallel axes from the centre of mass to the origin: I_o = I_c + m (|c|² 1 − c cᵀ).
        let shift = point_shift(c, m, Vec3::zero());
        let at = |i: usize, j: usize| b.inertia.rows[i][j] + shift.rows[i][j];
        out.extend([m, h.x, h.y, h.z]);
        out.extend(INERTIA_ENTRIES.iter().map(|&(i, j)| at(i, j)));
        if let Some(f) = b.friction {
            out.extend([T::from_f64(f.coulomb), T::from_f64(f.viscous)]);
        }
    }
    out
}

/// Work buffers of [`regressor`] for one model's shape.
#[derive(Clone, Debug)]
pub struct Work<T> {
    /// The motion at the state.
    state: Vec<Motion<T>>,
    /// The motion of a unit acceleration of one joint (the Jacobians' column).
    unit: Vec<Motion<T>>,
    /// `(J_v e_k, J_ω e_k)` per joint `k` and body: `jacobian[k * bodies + b]`.
    jacobian: Vec<(Vec3<T>, Vec3<T>)>,
    /// `e_k` and zeros, `n` each.
    unit_qdd: Vec<T>,
    zeros: Vec<T>,
    /// Each body's first column in `Y`.
    first_column: Vec<usize>,
    /// The guides' capstan factors ([`friction::capstan_factors`]).
    capstan: Vec<Vec<T>>,
}

impl<T: Real> Work<T> {
    /// Buffers for `model`'s shape.
    pub fn new(model: &Model<T>) -> Self {
        let (n, nb) = (model.dof, model.bodies.len());
        Work {
            state: vec![Motion::rest(); nb],
            unit: vec![Motion::rest(); nb],
            jacobian: vec![(Vec3::zero(), Vec3::zero()); n * nb],
            unit_qdd: vec![T::zero(); n],
            zeros: vec![T::zero(); n],
            first_column: vec![0; nb],
            capstan: (model.strands().iter())
                .map(|s| vec![T::one(); s.idlers.len()])
                .collect(),
        }
    }
}

/// `Y(q, q̇, q̈)` into `y` (`n` rows of [`parameters`]`.len()` entries, row-major) and the
/// known part `Q₀` (the external wrench's) into `known` (`n`): `Q = Y π + Q₀`. The caller
/// sizes the buffers (the checked front end is [`crate::Data::regressor`]).
pub fn regressor<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    work: &mut Work<T>,
    y: &mut [T],
    known: &mut [T],
) {
    let (n, nb) = (model.dof, model.bodies.len());
    forward(model, q, qd, qdd, true, true, &mut work.state);
    for k in 0..n {
        work.unit_qdd[k] = T::one();
        forward(
            model,
            q,
            &work.zeros,
            &work.unit_qdd,
            false,
            true,
            &mut work.unit,
        );
        work.unit_qdd[k] = T::zero();
        for (b, m) in work.unit.iter().enumerate() {
            work.jacobian[k * nb + b] = (m.accel, m.omega_dot);
        }
    }
    let p = y.len() / n.max(1);
    for v in y.iter_mut() {
        *v = T::zero();
    }
    let mut column = 0;
    for (b, (body, pattern)) in model.bodies.iter().zip(&model.patterns).enumerate() {
        let m = &work.state[b];
        let (a, w, wd) = (m.accel, m.omega, m.omega_dot);
        for k in 0..n {
            let (u, r) = work.jacobian[k * nb + b];
            let row = &mut y[k * p + column..k * p + column + 10];
            row.copy_from_slice(&inertial_row(u, r, a, w, wd));
        }
        work.first_column[b] = column;
        column += 10;
        if body.friction.is_some() {
            let joints = &pattern.joints;
            let (rate, direction) = friction::rate_and_direction(model, b, qd, Some(qdd));
            for &k in joints {
                y[k * p + column] = body.coupling[k] * direction;
                y[k * p + column + 1] = body.coupling[k] * rate;
            }
            column += 2;
        }
    }
    add_idler_rows(model, q, qd, qdd, work, y, p);
    for v in known.iter_mut() {
        *v = T::zero();
    }
    if let Some(wrench) = &model.external_wrench {
        // The wrench's moment about the link's origin: its own plus `p × f`.
        let moment = wrench.moment + wrench.point.cross(wrench.force);
        for (k, v) in known.iter_mut().enumerate() {
            let (u, r) = work.jacobian[k * nb + wrench.link];
            *v = -(u.dot(wrench.force) + r.dot(moment));
        }
    }
}

/// The coefficients of `u · F + r · N` in a body's ten inertial parameters, `(F, N)` its
/// inertial wrench about its origin (the module's formulas) at origin acceleration `a`
/// (gravity included), angular velocity `w` and acceleration `wd`, all in its frame.
fn inertial_row<T: Real>(u: Vec3<T>, r: Vec3<T>, a: Vec3<T>, w: Vec3<T>, wd: Vec3<T>) -> [T; 10] {
    let mut row = [T::zero(); 10];
    row[0] = u.dot(a);
    let first = u.cross(wd) + u.cross(w).cross(w) + a.cross(r);
    row[1..4].copy_from_slice(&first.to_array());
    let s = r.cross(w);
    let (r, s, w, wd) = (r.to_array(), s.to_array(), w.to_array(), wd.to_array());
    for (e, &(i, j)) in INERTIA_ENTRIES.iter().enumerate() {
        let mut v = r[i] * wd[j] + s[i] * w[j];
        if i != j {
            v = v + r[j] * wd[i] + s[j] * w[i];
        }
        row[4 + e] = v;
    }
    row
}

/// Adds to `y` (rows of `p` entries) what turning idlers behind guides with friction
/// demand of the actuators beyond their couplings, `Σ_i W_i (N_i − τ_f,i)`
/// ([`crate::dynamics::idlers_behind_capstan`]): idler `i`'s axial demand `N_i = axis · N`
/// is linear in its own parameters (`inertial_row` with `u = 0`, `r` its axis), and
/// `−τ_f,i = coulomb · s + viscous · ω_b`. The guides' directions at rest come from `q̈`,
/// as in inverse dynamics. Nothing is done without such idlers.
fn add_idler_rows<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    work: &mut Work<T>,
    y: &mut [T],
    p: usize,
) {
    if !model.capstan_before_an_idler() {
        return;
    }
    friction::capstan_factors(model, q, qd, Some(qdd), &mut work.capstan);
    let (state, first_column) = (&work.state, &work.first_column);
    dynamics::idler_weights(model, &work.capstan, |strand, idler, weight| {
        let b = model.strands()[strand].idlers[idler].body;
        let (m, body) = (&state[b], &model.bodies[b]);
        let axial = inertial_row(Vec3::zero(), body.axis, m.accel, m.omega, m.omega_dot);
        let bearing = body.friction.map(|_| {
            let (rate, direction) = friction::rate_and_direction(model, b, qd, Some(qdd));
            [direction, rate]
        });
        let column = first_column[b];
        for (k, w) in weight.iter().enumerate() {
            let row = &mut y[k * p + column..];
            for (v, x) in row.iter_mut().zip(&axial) {
                *v = *v + *w * *x;
            }
            for (v, x) in row[10..].iter_mut().zip(bearing.iter().flatten()) {
                *v = *v + *w * *x;
            }
        }
    });
}
