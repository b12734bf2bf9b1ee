//! Inverse dynamics with every tension and bearing force, the joint-space mass matrix,
//! bias and gravity terms, and forward dynamics, all on top of the one recursion in
//! [`crate::kinematics`] and [`crate::newton_euler`].
//!
//! Everything here is generic over [`Real`] — the code generator traces these very
//! functions — except [`Solver`], the runtime front end, which adds what only numbers can
//! do: input checks, the tension distribution for null spaces of any dimension, the
//! positive-definiteness check of forward dynamics, and the slack flags of loops.
//!
//! `M`, `h` and `g` come from the expanded-tree form of the recursion: every body's axial
//! joint moment `τ_b` mapped to the joint coordinates through its coupling,
//! `Q = Σ_b c_bᵀ τ_b` (virtual work), with the tendons left out (their forces are internal
//! once the pulleys' couplings hold).

use crate::affine::Affine;
use crate::error::{Error, Result};
use crate::friction::{self, Side};
use crate::kinematics::{coupled, forward, Motion};
use crate::linalg;
use crate::model::{BodyKind, Model, MotorKind, TensionSystem};
use crate::newton_euler::{backward, Loads};
use crate::real::{Numeric, Real};
use crate::spatial::{Mat3, Vec3};
use crate::tension;

/// Everything inverse dynamics reports at one state. See `docs/outputs.md` for units,
/// frames and signs.
#[derive(Clone, Debug)]
pub struct InverseDynamics<T> {
    /// Generalized forces the actuators deliver, `Q = Σ motor columns · τ + A T` (N·m),
    /// evaluated as the `M q̈ + h + g − Q_ext − Q_friction` it equals (the tension-free
    /// pass and the bearings' friction, [`generalized_forces`]), so that tensions far above
    /// what the motion needs cost it no accuracy.
    pub generalized_forces: Vec<T>,
    /// One torque per motor, in file order (N·m).
    pub motor_torques: Vec<T>,
    /// Ground-level tension of each open-ended tendon, in file order (N).
    pub tendon_tensions: Vec<T>,
    /// The minimal-norm part of the tendon tensions (may be negative).
    pub minimal_norm_tensions: Vec<T>,
    /// The null-space part the distribution added (`tendon_tensions −
    /// minimal_norm_tensions`): what keeps every tendon within its floor and maximum, the
    /// objective least.
    pub null_space_tensions: Vec<T>,
    /// Tension of both sides of each loop at its driving pulley (leaving the driven pulley
    /// counter-clockwise, then clockwise).
    pub loop_sides: Vec<[T; 2]>,
    /// Tension of every segment of every strand, `None` if the routing is incomplete.
    pub segment_tensions: Option<Vec<Vec<T>>>,
    /// Moment each intermediate link needs about its own axis (body index, N·m).
    pub pulley_demands: Vec<(usize, T)>,
    /// Bearing force and moment on every body from its parent, moment about the joint
    /// point, the motor's torque excluded; links in their DH frame, pulleys in their housing
    /// frame (the pulley frame at zero spin). `None` if the routing is incomplete.
    pub bearings: Option<Vec<(Vec3<T>, Vec3<T>)>>,
    /// Total force and moment (about the base origin) of the base on the mechanism, base
    /// frame (N, N·m). `None` if the routing is incomplete.
    pub base_reaction: Option<(Vec3<T>, Vec3<T>)>,
    /// Friction torque `τ_f` of each bearing that has friction, on the body about its axis
    /// (body index, N·m; [`crate::friction`]).
    pub bearing_friction: Vec<(usize, T)>,
    /// The bodies of `bearing_friction` whose bearing is within [`friction::REST`] of rest
    /// (exact law only): their friction is the direction of impending motion, or zero if
    /// `q̈` does not turn them either ([`friction::at_rest`]; filled in by [`Solver`]).
    pub sticking: Vec<usize>,
    /// The solved unknowns of the tension system, in the order of
    /// [`TensionSystem::unknowns`](crate::model::TensionSystem::unknowns).
    pub unknowns: Vec<T>,
}

impl<T: Numeric> InverseDynamics<T> {
    /// Whether each loop has a side below zero tension (it would go slack: raise the
    /// loop's pretension).
    pub fn slack_loops(&self) -> Vec<bool> {
        self.loop_sides
            .iter()
            .map(|s| s.iter().any(|&v| v < T::zero()))
            .collect()
    }
}

/// Work buffers of the recursion for one model; the model itself stays immutable.
#[derive(Clone, Debug)]
pub struct Workspace<T: Real> {
    /// Motion of every body from the last forward recursion.
    pub motion: Vec<Motion<T>>,
    /// Loads affine in the unknowns (inverse dynamics with tensions).
    pub loads: Loads<T>,
    /// Plain loads (the expanded-tree pass: `M`, `h`, `g`, `Q`).
    pub known: Loads<T, Vec3<T>>,
    /// Tension of every segment of every strand, affine in the unknowns
    /// ([`tension::segment_tensions`]).
    pub tensions: Vec<Vec<Affine<T>>>,
    /// Bearing friction torque of every body at the last inverse-dynamics call
    /// ([`friction::bearing_torques`]), which its balance rows carry.
    pub friction: Vec<T>,
    /// Capstan factor of every idler step, `[strand][idler]` (1 but on guides with
    /// friction; [`friction::capstan_factors`]).
    pub capstan: Vec<Vec<T>>,
    zeros: Vec<T>,
}

impl<T: Real> Workspace<T> {
    /// Buffers sized for `model`.
    pub fn new(model: &Model<T>) -> Self {
        let nu = model.system.unknowns.len();
        Workspace {
            motion: vec![Motion::rest(); model.bodies.len()],
            loads: Loads::new(model.bodies.len(), nu),
            known: Loads::new(model.bodies.len(), 0),
            zeros: vec![T::zero(); model.dof],
            friction: vec![T::zero(); model.bodies.len()],
            capstan: model
                .strands
                .iter()
                .map(|s| vec![T::one(); s.idlers.len()])
                .collect(),
            tensions: model
                .strands
                .iter()
                .map(|s| vec![Affine::constant(T::zero(), nu); s.segments.len()])
                .collect(),
        }
    }
}

/// Generalized forces of the expanded tree, `Q = Σ_b c_bᵀ τ_b`, with the tendons left out:
/// `M q̈ + h + g` with `gravity`, minus the external wrench's generalized force with
/// `external`.
#[allow(clippy::too_many_arguments)]
pub fn expanded_generalized_forces<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    gravity: bool,
    external: bool,
    ws: &mut Workspace<T>,
    out: &mut [T],
) {
    forward(model, q, qd, qdd, gravity, &mut ws.motion);
    backward(model, &ws.motion, None, 0, external, &mut ws.known);
    expanded_sum(model, &ws.known, out);
}

/// `Q = Σ_b c_bᵀ τ_b` of a tension-free backward pass, written into `out`.
fn expanded_sum<T: Real>(model: &Model<T>, known: &Loads<T, Vec3<T>>, out: &mut [T]) {
    for o in out.iter_mut() {
        *o = T::zero();
    }
    for (b, t) in model.bodies.iter().zip(&known.axial) {
        for (o, c) in out.iter_mut().zip(&b.coupling) {
            *o = *o + *c * *t;
        }
    }
}

/// The generalized forces the actuators must deliver at a state: the expanded tree's
/// `M q̈ + h + g − Q_ext` less what the bearings' friction does, `Σ_b c_bᵀ τ_f,b`
/// ([`crate::friction`]; the direction at rest from `q̈`).
pub fn generalized_forces<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    ws: &mut Workspace<T>,
    out: &mut [T],
) {
    expanded_generalized_forces(model, q, qd, qdd, true, true, ws, out);
    friction::apply_at(model, qd, Some(qdd), Side::Delivered, out);
}

/// Joint-space mass matrix `M(q)`, pulley inertias included through their couplings: column
/// `j` is the expanded tree's `Q` at `q̈ = e_j` with no velocity and no gravity. Only the
/// upper triangle is computed from the recursion; the lower one mirrors it.
pub fn mass_matrix<T: Real>(model: &Model<T>, q: &[T], ws: &mut Workspace<T>) -> Vec<Vec<T>> {
    let n = model.dof;
    let zeros = vec![T::zero(); n];
    let mut m = vec![vec![T::zero(); n]; n];
    let mut unit = zeros.clone();
    let mut col = zeros.clone();
    for j in 0..n {
        unit[j] = T::one();
        expanded_generalized_forces(model, q, &zeros, &unit, false, false, ws, &mut col);
        for i in 0..=j {
            m[i][j] = col[i];
            m[j][i] = col[i];
        }
        unit[j] = T::zero();
    }
    m
}

/// Bias `h(q, q̇)`: Coriolis and centrifugal generalized forces.
pub fn bias<T: Real>(model: &Model<T>, q: &[T], qd: &[T], ws: &mut Workspace<T>) -> Vec<T> {
    let zeros = vec![T::zero(); model.dof];
    let mut out = zeros.clone();
    expanded_generalized_forces(model, q, qd, &zeros, false, false, ws, &mut out);
    out
}

/// Gravity generalized forces `g(q)`.
pub fn gravity<T: Real>(model: &Model<T>, q: &[T], ws: &mut Workspace<T>) -> Vec<T> {
    let zeros = vec![T::zero(); model.dof];
    let mut out = zeros.clone();
    expanded_generalized_forces(model, q, &zeros, &zeros, true, false, ws, &mut out);
    out
}

/// Each open-ended tendon's column of the structure matrix `A` at `(q, q̇)`, `[tendon][joint]`
/// (generalized force per newton of its ground-level tension): the model's constant column,
/// but where a tendon slides over guides with friction, the column of the state's
/// `E(σ, q)` (its joint rows), `σ` from `q̇` alone (at rest no friction: forward dynamics
/// does not know `q̈`, as for bearings).
pub fn structure<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    ws: &mut Workspace<T>,
) -> Vec<Vec<T>> {
    let mut columns: Vec<Vec<T>> = model
        .tendons
        .iter()
        .map(|k| k.structure.iter().map(|&a| T::from_f64(a)).collect())
        .collect();
    if !model.has_capstan() {
        return columns;
    }
    let zeros = vec![T::zero(); model.dof];
    forward(model, q, qd, &zeros, true, &mut ws.motion);
    friction::capstan_factors(model, q, qd, None, &mut ws.capstan);
    let rows = balance(model, ws);
    for (k, column) in model.tendons.iter().zip(&mut columns) {
        if k.strand.is_some() {
            // The joints' rows come first; E is minus the balance rows' coefficients.
            for (j, a) in column.iter_mut().enumerate() {
                *a = -rows[j].coefficients[k.unknown];
            }
        }
    }
    columns
}

/// The generalized forces the actuators deliver: `Σ motor columns · τ + A T`, `A` the
/// tendons' columns ([`structure`]).
pub fn actuator_forces<T: Real>(
    model: &Model<T>,
    structure: &[Vec<T>],
    motor_torques: &[T],
    tendon_tensions: &[T],
) -> Vec<T> {
    (0..model.dof)
        .map(|j| {
            let mut u = T::zero();
            for (m, t) in model.motors.iter().zip(motor_torques) {
                u = u + T::from_f64(m.column[j]) * *t;
            }
            for (a, t) in structure.iter().zip(tendon_tensions) {
                u = u + a[j] * *t;
            }
            u
        })
        .collect()
}

/// `M q̈ = Σ actuator forces − (h + g − Q_ext) + Q_friction`: the right-hand side of
/// forward dynamics, the bearings' friction directed by `q̇` alone (none at rest).
pub fn forward_dynamics_rhs<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    motor_torques: &[T],
    tendon_tensions: &[T],
    ws: &mut Workspace<T>,
) -> Vec<T> {
    let a = structure(model, q, qd, ws);
    let zeros = vec![T::zero(); model.dof];
    let mut c = zeros.clone();
    expanded_generalized_forces(model, q, qd, &zeros, true, true, ws, &mut c);
    let mut rhs: Vec<T> = actuator_forces(model, &a, motor_torques, tendon_tensions)
        .into_iter()
        .zip(c)
        .map(|(u, c)| u - c)
        .collect();
    friction::apply_at(model, qd, None, Side::Acting, &mut rhs);
    rhs
}

/// The tension system at joint angles `q` with the guides with friction sliding in the
/// directions `sigma` (`±1` each, `[strand][idler]` as [`Workspace::capstan`], ignored
/// elsewhere): `E(σ, q)` by the recursion's statics ([`tension::system_at`]). What
/// validation checks for each direction of sliding the routing can take.
pub fn system_sliding<T: Numeric>(
    model: &Model<T>,
    q: &[T],
    sigma: &[Vec<f64>],
) -> Result<TensionSystem<T>> {
    let mut ws = Workspace::new(model);
    let zeros = vec![T::zero(); model.dof];
    forward(model, q, &zeros, &zeros, true, &mut ws.motion);
    friction::capstan_factors_sliding(model, q, &mut ws.capstan, |s, k, _| {
        T::from_f64(sigma[s][k])
    });
    let rows = balance(model, &mut ws);
    tension::system_at(model, &rows)
}

/// The balance rows of `E x = b` at the motion, bearing friction and capstan factors in
/// `ws`: the segment tensions (Eq. 24b), the backward recursion with them as unknowns
/// (Eqs. 19-24) and the axial balances it leaves (`tension::balance_rows`).
fn balance<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) -> Vec<Affine<T>> {
    let nu = model.system.unknowns.len();
    tension::segment_tensions(
        model,
        &ws.motion,
        &ws.friction,
        &ws.capstan,
        nu,
        &mut ws.tensions,
    );
    backward(
        model,
        &ws.motion,
        Some(&ws.tensions),
        nu,
        true,
        &mut ws.loads,
    );
    tension::balance_rows(model, &ws.loads, &ws.friction)
}

/// Inverse dynamics by the paper's recursion: tensions carried to the base as unknowns,
/// `E x = b` solved there (`distribute` chooses among the solutions of a redundant
/// routing), every segment tension and bearing force by back-substitution.
pub fn inverse_dynamics<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    ws: &mut Workspace<T>,
    at_state: impl FnOnce(&Model<T>, &[Affine<T>]) -> Result<TensionSystem<T>>,
    distribute: impl FnOnce(&Model<T>, &TensionSystem<T>, &mut [T]) -> Result<()>,
) -> Result<InverseDynamics<T>> {
    let nu = model.system.unknowns.len();
    forward(model, q, qd, qdd, true, &mut ws.motion);
    friction::bearing_torques(model, qd, Some(qdd), &mut ws.friction);
    friction::capstan_factors(model, q, qd, Some(qdd), &mut ws.capstan);
    let rows = balance(model, ws);
    let b: Vec<T> = rows.iter().map(|r| r.constant).collect();
    // With friction on guides `E` depends on the state (`at_state`, tension::system_at);
    // otherwise it is the model's own.
    let state_system;
    let system = if model.has_capstan() {
        state_system = at_state(model, &rows)?;
        &state_system
    } else {
        &model.system
    };
    let mut x = vec![T::zero(); nu];
    tension::minimal_norm(model, system, &b, &mut x);
    let x0 = x.clone();
    distribute(model, system, &mut x)?;

    let motor_torques: Vec<T> = model.motors.iter().map(|m| x[m.unknown]).collect();
    let tendon_tensions: Vec<T> = model.tendons.iter().map(|t| x[t.unknown]).collect();
    let minimal_norm_tensions = model.tendons.iter().map(|t| x0[t.unknown]).collect();
    let null_space_tensions = model
        .tendons
        .iter()
        .map(|t| x[t.unknown] - x0[t.unknown])
        .collect();
    // What the actuators deliver, `Σ c_m τ_m + A T`, is `M q̈ + h + g − Q_ext`: take it from
    // the tension-free pass over the same motion rather than from the solved tensions. A
    // redundant routing's null-space part, `A N λ`, vanishes only to rounding, so summing
    // `A T` loses `u·|A||T|`: everything when the floors lift the tensions far above what
    // the motion needs. The base reaction likewise (momentum balance: the tendons are
    // internal between the mechanism and its base, so their pulls cancel in it).
    backward(model, &ws.motion, None, 0, true, &mut ws.known);
    let mut generalized_forces = vec![T::zero(); model.dof];
    expanded_sum(model, &ws.known, &mut generalized_forces);
    friction::apply(
        model,
        &ws.friction,
        Side::Delivered,
        &mut generalized_forces,
    );
    let bearing_friction = model
        .bodies
        .iter()
        .zip(&ws.friction)
        .enumerate()
        .filter(|(_, (b, _))| b.friction.is_some())
        .map(|(i, (_, t))| (i, *t))
        .collect();
    let loop_sides = model
        .loops
        .iter()
        .map(|l| l.strands.map(|s| x[model.strands[s].unknown]))
        .collect();
    let pulley_demands = model
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| matches!(b.kind, BodyKind::Pulley { .. }))
        .map(|(i, _)| (i, tension::axial_demand(model, &ws.motion, i)))
        .collect();
    let (segment_tensions, bearings, base_reaction) = if model.routing_incomplete {
        (None, None, None)
    } else {
        let segs = ws
            .tensions
            .iter()
            .map(|s| s.iter().map(|t| t.eval(&x)).collect())
            .collect();
        let bearings = (0..model.bodies.len())
            .map(|i| bearing(model, ws, q, &x, i))
            .collect();
        let base = (ws.known.base_force, ws.known.base_moment);
        (Some(segs), Some(bearings), Some(base))
    };
    Ok(InverseDynamics {
        generalized_forces,
        motor_torques,
        tendon_tensions,
        minimal_norm_tensions,
        null_space_tensions,
        loop_sides,
        segment_tensions,
        pulley_demands,
        bearings,
        base_reaction,
        bearing_friction,
        sticking: Vec::new(),
        unknowns: x,
    })
}

/// Bearing force and moment of body `i` at the solved unknowns `x`.
fn bearing<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    q: &[T],
    x: &[T],
    i: usize,
) -> (Vec3<T>, Vec3<T>) {
    let b = &model.bodies[i];
    let f = ws.loads.force[i].eval(x);
    let mut n = ws.loads.moment[i].eval(x);
    // The bearing carries what the motor on this joint does not.
    if let Some(m) = model.motors.iter().find(|m| match m.kind {
        MotorKind::Joint(j) => j == i,
        MotorKind::Pulley(p) => p == i,
    }) {
        n = n - b.axis.scale(x[m.unknown]);
    }
    // A spinning pulley's frame turns with it; report it in its housing frame (the
    // pulley frame at zero spin) like every other pulley.
    if b.spins && matches!(b.kind, BodyKind::Pulley { .. }) {
        let (sn, cs) = coupled(&b.coupling, q).sin_cos();
        let spin = Mat3::rot_z(sn, cs);
        (spin.mul_vec(f), spin.mul_vec(n))
    } else {
        (f, n)
    }
}

/// `Err` when a result is not finite although the inputs were: some intermediate value
/// overflowed the scalar (a speed of 1e200 rad/s squares to infinity). The solver returns
/// this error rather than a non-finite number, and names the largest of the `inputs`
/// (each a name and its values), which is almost always the one to blame.
fn finite<'a, T: Numeric>(
    what: &str,
    values: impl IntoIterator<Item = &'a T>,
    inputs: &[(&str, &[T])],
) -> Result<()> {
    let Some(x) = values.into_iter().find(|x| !x.is_finite()) else {
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

/// The runtime solver: the generic functions above with input checks, on numbers.
pub struct Solver<'m, T: Real> {
    /// The model it evaluates.
    pub model: &'m Model<T>,
    ws: Workspace<T>,
}

impl<'m, T: Numeric> Solver<'m, T> {
    /// A solver of `model`, with work buffers sized for it.
    pub fn new(model: &'m Model<T>) -> Self {
        Solver {
            model,
            ws: Workspace::new(model),
        }
    }

    fn check_state(&self, what: &str, v: &[T]) -> Result<()> {
        let n = self.model.dof;
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

    /// Generalized forces the actuators deliver, `Q = M q̈ + h + g − Jᵀ w_ext − Q_friction`
    /// ([`generalized_forces`]).
    pub fn generalized_forces(&mut self, q: &[T], qd: &[T], qdd: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        self.check_state("qdd", qdd)?;
        let mut out = self.ws.zeros.clone();
        generalized_forces(self.model, q, qd, qdd, &mut self.ws, &mut out);
        finite(
            "generalized forces",
            &out,
            &[("q", q), ("qd", qd), ("qdd", qdd)],
        )?;
        Ok(out)
    }

    /// Joint-space mass matrix `M(q)`.
    pub fn mass_matrix(&mut self, q: &[T]) -> Result<Vec<Vec<T>>> {
        self.check_state("q", q)?;
        let m = mass_matrix(self.model, q, &mut self.ws);
        finite("mass matrix", m.iter().flatten(), &[("q", q)])?;
        Ok(m)
    }

    /// Bias `h(q, q̇)`.
    pub fn bias(&mut self, q: &[T], qd: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        let h = bias(self.model, q, qd, &mut self.ws);
        finite("bias", &h, &[("q", q), ("qd", qd)])?;
        Ok(h)
    }

    /// Gravity generalized forces `g(q)`.
    pub fn gravity(&mut self, q: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        let g = gravity(self.model, q, &mut self.ws);
        finite("gravity", &g, &[("q", q)])?;
        Ok(g)
    }

    /// `‖M⁻¹ (|A| |T| + |B| |τ| + |h + g − Q_ext| + Σ_b |c_b τ_f,b|)‖∞`: the size of the
    /// terms forward dynamics sums (`A`, `B` the tendons' and motors' columns, `τ_f,b` the
    /// bearings' friction). Tensions that balance each
    /// other make `q̈` a small difference of large numbers, so the error of a forward
    /// dynamics result is meaningful relative to this, not to `‖q̈‖`.
    ///
    /// Checked as [`Solver::forward_dynamics`] is, with the same errors: the inputs (their
    /// lengths and finiteness), every intermediate result, and the mass matrix (which must
    /// be positive definite); a finite scale or an error, never a non-finite number.
    pub fn forward_dynamics_scale(
        &mut self,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<T> {
        self.check_forward_inputs(q, qd, motor_torques, tendon_tensions)?;
        let inputs = [
            ("q", q),
            ("qd", qd),
            ("motor_torques", motor_torques),
            ("tendon_tensions", tendon_tensions),
        ];
        let zero = T::from_f64(0.0);
        let model = self.model;
        let a = structure(model, q, qd, &mut self.ws);
        let zeros = self.ws.zeros.clone();
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
                motors + tendons + c[j].abs() + friction
            })
            .collect();
        finite("right-hand side of forward dynamics", &rhs, &inputs)?;
        let y = self.solve_mass_matrix(q, &rhs)?;
        // (`max` would pass over a NaN.)
        finite("forward-dynamics term scale", &y, &inputs)?;
        Ok(y.iter().fold(zero, |a, x| a.max(x.abs())))
    }

    /// Forward dynamics: `q̈` from the motor torques (file order) and the ground-level
    /// tensions of the open-ended tendons (file order).
    pub fn forward_dynamics(
        &mut self,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<Vec<T>> {
        self.check_forward_inputs(q, qd, motor_torques, tendon_tensions)?;
        let inputs = [
            ("q", q),
            ("qd", qd),
            ("motor_torques", motor_torques),
            ("tendon_tensions", tendon_tensions),
        ];
        let model = self.model;
        let rhs = forward_dynamics_rhs(model, q, qd, motor_torques, tendon_tensions, &mut self.ws);
        finite("right-hand side of forward dynamics", &rhs, &inputs)?;
        let qdd = self.solve_mass_matrix(q, &rhs)?;
        finite("joint acceleration", &qdd, &inputs)?;
        Ok(qdd)
    }

    /// The input checks of forward dynamics: the state, and as many finite motor torques
    /// and tendon tensions as the mechanism has motors and open-ended tendons.
    fn check_forward_inputs(
        &self,
        q: &[T],
        qd: &[T],
        motor_torques: &[T],
        tendon_tensions: &[T],
    ) -> Result<()> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        let model = self.model;
        if model.capstan_before_an_idler() {
            return Err(Error::NotYet(
                "forward dynamics where a turning idler follows a guide with capstan friction \
                 (`mu > 0`) towards the tendon's exit: the idler's inertia then reaches the \
                 joints scaled by the guide's friction, which the mass matrix does not carry; \
                 inverse dynamics handles it"
                    .into(),
            ));
        }
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
        Ok(())
    }

    /// `M(q)⁻¹ rhs` by the checked Cholesky factorisation of forward dynamics.
    fn solve_mass_matrix(&mut self, q: &[T], rhs: &[T]) -> Result<Vec<T>> {
        let m = mass_matrix(self.model, q, &mut self.ws);
        finite("mass matrix", m.iter().flatten(), &[("q", q)])?;
        let mut factor: Vec<T> = m.into_iter().flatten().collect();
        let mut x = rhs.to_vec();
        if !linalg::cholesky_solve(&mut factor, &mut x) {
            return Err(Error::Singular(
                "the mass matrix is not positive definite at this state (a massless chain, or a \
                 link whose motion nothing resists)"
                    .into(),
            ));
        }
        Ok(x)
    }

    /// Inverse dynamics by the paper's recursion (see [`inverse_dynamics`]), with the
    /// tension distribution for null spaces of any dimension ([`tension::distribute`]:
    /// every tendon within its floor and maximum, the model's objective least).
    pub fn inverse_dynamics(&mut self, q: &[T], qd: &[T], qdd: &[T]) -> Result<InverseDynamics<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        self.check_state("qdd", qdd)?;
        let inputs = [("q", q), ("qd", qd), ("qdd", qdd)];
        // Tensions that overflowed are reported before the distribution sees them, with the
        // input to blame.
        let distribute = |model: &Model<T>, system: &TensionSystem<T>, x: &mut [T]| {
            finite("tension or motor torque", &*x, &inputs)?;
            tension::distribute(model, system, x)
        };
        let mut r = inverse_dynamics(
            self.model,
            q,
            qd,
            qdd,
            &mut self.ws,
            tension::system_at,
            distribute,
        )?;
        r.sticking = friction::at_rest(self.model, qd);
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
            finite(
                "bearing force",
                &b.iter().flat_map(wrench).collect::<Vec<T>>(),
                &inputs,
            )?;
        }
        if let Some(b) = &r.base_reaction {
            finite("base reaction", &wrench(b).collect::<Vec<T>>(), &inputs)?;
        }
        Ok(r)
    }

    /// The balance rows of the last inverse-dynamics call, as affine forms (for checks of
    /// the recursion against the transmission's `E`).
    pub fn last_balance_rows(&self) -> Vec<Affine<T>> {
        tension::balance_rows(self.model, &self.ws.loads, &self.ws.friction)
    }
}
