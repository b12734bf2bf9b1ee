//! Inverse dynamics with every tension and bearing force, the joint-space mass matrix,
//! bias and gravity terms, and forward dynamics, all on top of the one recursion in
//! [`crate::kinematics`] and [`crate::newton_euler`].
//!
//! Everything here is generic over [`Real`]: the code generator traces these very
//! functions, and the runtime front end ([`crate::data`]) adds to them what only numbers
//! can do: input checks, the tension distribution for null spaces of any dimension, the
//! positive-definiteness check of forward dynamics.
//!
//! The functions here take the model's sizes on trust (`q` of `dof` entries, output
//! slices as long as they write, a [`Workspace`] made for the model): shorter slices
//! panic on indexing. [`crate::Data`] checks every size and returns a named error; call
//! them directly only with sizes from the model.
//!
//! `Q`, `h` and `g` come from the expanded-tree form of the recursion: every body's axial
//! joint moment `τ_b` mapped to the joint coordinates through its coupling,
//! `Q = Σ_b c_bᵀ τ_b` (virtual work), with the tendons left out (their forces are internal
//! once the pulleys' couplings hold); `M` from the composite-rigid-body algorithm over the
//! same expanded tree ([`crate::composite`]).

use crate::affine::Affine;
use crate::composite;
use crate::error::Result;
use crate::friction::{self, Side};
use crate::kinematics::{coupled, forward, Motion};
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
    /// pass and the bearings' friction, [`generalized_forces`]; plus `Σ_i W_i (N_i − τ_f,i)`
    /// where turning idlers follow guides with friction, [`idlers_behind_capstan`]), so
    /// that tensions far above what the motion needs cost it no accuracy.
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
    /// `q̈` does not turn them either ([`friction::at_rest`]; filled in by [`crate::Data`]).
    pub sticking: Vec<usize>,
    /// The solved unknowns of the tension system, in the order of
    /// [`TensionSystem::unknowns`](crate::model::TensionSystem::unknowns).
    pub unknowns: Vec<T>,
}

impl<T> InverseDynamics<T> {
    /// No results yet: the buffers [`inverse_dynamics`] fills.
    pub fn empty() -> Self {
        InverseDynamics {
            generalized_forces: Vec::new(),
            motor_torques: Vec::new(),
            tendon_tensions: Vec::new(),
            minimal_norm_tensions: Vec::new(),
            null_space_tensions: Vec::new(),
            loop_sides: Vec::new(),
            segment_tensions: None,
            pulley_demands: Vec::new(),
            bearings: None,
            base_reaction: None,
            bearing_friction: Vec::new(),
            sticking: Vec::new(),
            unknowns: Vec::new(),
        }
    }
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

/// Work buffers of the recursion, sized by [`Workspace::new`] for one model's shape: the
/// generic functions index them by that model's bodies and strands (the runtime
/// [`crate::Data`] checks the shape; the code generator makes one for its models, which
/// share their shape).
#[derive(Clone, Debug)]
pub struct Workspace<T: Real> {
    /// Motion of every body from the last forward recursion.
    pub(crate) motion: Vec<Motion<T>>,
    /// Loads affine in the unknowns (the state's `E` with capstan friction).
    pub(crate) loads: Loads<T>,
    /// Plain loads (the tension-free expanded-tree pass: `Q`, `h`, `g`).
    pub(crate) known: Loads<T, Vec3<T>>,
    /// Tension of every segment of every strand, affine in the unknowns
    /// ([`tension::segment_tensions`]; with capstan friction).
    pub(crate) tensions: Vec<Vec<Affine<T>>>,
    /// Tension of every segment of every strand at known ground-level tensions.
    pub(crate) segments: Vec<Vec<T>>,
    /// Plain loads of the pass with those tensions (`b`, then the bearings).
    pub(crate) tendon_loads: Loads<T, Vec3<T>>,
    /// `b` of `E x = b`.
    pub(crate) b: Vec<T>,
    /// The minimal-norm solution `x₀ = E⁺ b`.
    pub(crate) minimal: Vec<T>,
    /// Bearing friction torque of every body at the last state a recursion took it at
    /// ([`friction::bearing_torques`]): inverse dynamics' balance rows carry it.
    pub(crate) friction: Vec<T>,
    /// Capstan factor of every idler step, `[strand][idler]` (1 but on guides with
    /// friction; [`friction::capstan_factors`]).
    pub(crate) capstan: Vec<Vec<T>>,
    /// Composite inertias of the mass matrix ([`composite::mass_matrix`]).
    pub(crate) composite: composite::Work<T>,
}

impl<T: Real> Workspace<T> {
    /// Buffers sized for `model`.
    pub fn new(model: &Model<T>) -> Self {
        // The affine buffers are only read after `balance` has filled them, which needs a
        // model within the affine forms' capacity; any size does until then.
        let nu = model.system.unknowns.len().min(crate::affine::MAX_UNKNOWNS);
        Workspace {
            motion: vec![Motion::rest(); model.bodies.len()],
            loads: Loads::new(model.bodies.len(), nu),
            known: Loads::new(model.bodies.len(), 0),
            tendon_loads: Loads::new(model.bodies.len(), 0),
            b: vec![T::zero(); model.system.rows.len()],
            minimal: vec![T::zero(); model.system.unknowns.len()],
            segments: model
                .strands
                .iter()
                .map(|s| vec![T::zero(); s.segments.len()])
                .collect(),
            friction: vec![T::zero(); model.bodies.len()],
            composite: composite::Work::new(model),
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
    forward(model, q, qd, qdd, gravity, false, &mut ws.motion);
    backward(model, &ws.motion, None, 0, external, &mut ws.known);
    expanded_sum(model, &ws.known, out);
}

/// `Q = Σ_b c_bᵀ τ_b` of a tension-free backward pass, written into `out`.
fn expanded_sum<T: Real>(model: &Model<T>, known: &Loads<T, Vec3<T>>, out: &mut [T]) {
    for o in out.iter_mut() {
        *o = T::zero();
    }
    for ((b, pattern), t) in model.bodies.iter().zip(&model.patterns).zip(&known.axial) {
        // Over the coupling's nonzero entries only.
        for &j in &pattern.joints {
            out[j] = out[j] + b.coupling[j] * *t;
        }
    }
}

/// The generalized forces the actuators must deliver at a state: the expanded tree's
/// `M q̈ + h + g − Q_ext` less what the bearings' friction does, `Σ_b c_bᵀ τ_f,b`
/// ([`crate::friction`]; the direction at rest from `q̈`), and where turning idlers sit
/// behind guides with friction, their `Σ_i W_i (N_i − τ_f,i)` ([`idlers_behind_capstan`];
/// the guides' directions at rest from `q̈` too).
pub fn generalized_forces<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    ws: &mut Workspace<T>,
    out: &mut [T],
) {
    expanded_generalized_forces(model, q, qd, qdd, true, true, ws, out);
    if model.has_friction() {
        friction::bearing_torques(model, qd, Some(qdd), &mut ws.friction);
        friction::apply(model, &ws.friction, Side::Delivered, out);
    }
    if model.capstan_before_an_idler() {
        friction::capstan_factors(model, q, qd, Some(qdd), &mut ws.capstan);
        add_idlers_behind_capstan(model, ws, out);
    }
}

/// Joint-space mass matrix `M(q)`, pulley inertias included through their couplings, by
/// the composite-rigid-body algorithm over the expanded tree ([`crate::composite`]).
pub fn mass_matrix<T: Real>(model: &Model<T>, q: &[T], ws: &mut Workspace<T>) -> Vec<Vec<T>> {
    let n = model.dof;
    let mut flat = vec![T::zero(); n * n];
    composite::mass_matrix(model, q, &mut ws.composite, &mut flat);
    flat.chunks_exact(n.max(1)).map(|r| r.to_vec()).collect()
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
    friction::capstan_factors(model, q, qd, None, &mut ws.capstan);
    let matrix = tension::state_matrix(model, &ws.capstan);
    for (k, column) in model.tendons.iter().zip(&mut columns) {
        if k.strand.is_some() {
            // The joints' rows come first.
            for (a, row) in column.iter_mut().zip(&matrix) {
                *a = row[k.unknown];
            }
        }
    }
    columns
}

/// A turning idler between a guide with capstan friction and its tendon's ground end, as
/// forward dynamics needs it ([`idlers_behind_capstan`]).
pub struct IdlerBehindCapstan<T> {
    /// The idler's strand and its place on it (`model.strands()[strand].idlers[idler]`).
    pub strand: usize,
    /// See `strand`.
    pub idler: usize,
    /// `W_i` (one entry per joint): how the idler's net axial moment reaches the joints
    /// beyond what its coupling carries.
    pub weight: Vec<T>,
    /// `N_i − τ_f,i` at `q̈ = 0`: the idler's axial demand (inertia and gravity, about its
    /// axis) less its bearing's friction (`τ_f` from `q̇` alone, as forward dynamics takes
    /// it).
    pub demand: T,
    /// `∂N_i/∂q̈` (one entry per joint).
    pub inertia: Vec<T>,
}

/// The idlers whose axial demand reaches the joints through a guide with capstan friction,
/// at `(q, q̇)` with `σ` from `q̇` alone (forward dynamics' convention; empty without such
/// idlers).
///
/// An idler `i` (between segments `i` and `i + 1` of its strand) needs the tension step
/// `T_i − T_{i+1} = −s_i (N_i − τ_f,i) / r_i` (Eq. 24b), and every segment `k ≤ i` on its
/// anchor side carries that step scaled by `T_k / T_{i+1}` (the capstan factors between
/// them). Weighted by each segment's share of the strand's column (`Strand::shares`), the
/// step delivers `−(N_i − τ_f,i) (s_i / r_i) Σ_{k ≤ i} (T_k / T_{i+1}) shares[k]` to the
/// joints. With every ratio 1 that is `−(N_i − τ_f,i) c_i`, `c_i` the idler's coupling
/// (the shares up to it sum to `(r_i / s_i) c_i`, [`crate::transmission`]): the mass matrix,
/// the bias and the bearings' friction of forward dynamics already carry it. What they do
/// not carry is `W_i = (s_i / r_i) Σ_{k ≤ i} (T_k / T_{i+1} − 1) shares[k]`, nonzero only
/// where a guide with friction lies on the idler's anchor side: forward dynamics is then
/// `(M + Σ_i W_i ∂N_iᵀ/∂q̈) q̈ = rhs − Σ_i (N_i − τ_f,i)|_{q̈=0} W_i`, not symmetric
/// ([`accelerations`]).
pub fn idlers_behind_capstan<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    ws: &mut Workspace<T>,
) -> Vec<IdlerBehindCapstan<T>> {
    if !model.capstan_before_an_idler() {
        return Vec::new();
    }
    let n = model.dof;
    let zeros = vec![T::zero(); n];
    friction::capstan_factors(model, q, qd, None, &mut ws.capstan);
    friction::bearing_torques(model, qd, None, &mut ws.friction);
    forward(model, q, qd, &zeros, true, true, &mut ws.motion);
    let mut out = Vec::new();
    idler_weights(model, &ws.capstan, |strand, idler, weight| {
        out.push(IdlerBehindCapstan {
            strand,
            idler,
            weight,
            demand: idler_demand(model, ws, model.strands[strand].idlers[idler].body),
            inertia: Vec::new(),
        });
    });
    // ∂N_i/∂q̈: the axial demands of a motion from rest with one unit acceleration and no
    // gravity (N is affine in q̈): n more forward passes, only for such mechanisms.
    let mut unit = zeros.clone();
    for l in 0..n {
        unit[l] = T::one();
        forward(model, q, &zeros, &unit, false, true, &mut ws.motion);
        unit[l] = T::zero();
        for term in &mut out {
            let body = model.strands[term.strand].idlers[term.idler].body;
            term.inertia
                .push(tension::axial_demand(model, &ws.motion, body));
        }
    }
    out
}

/// Calls `each(strand, idler, W_i)` for every turning idler behind a guide with capstan
/// friction, `W_i` (one entry per joint) at the guides' factors `capstan`
/// ([`friction::capstan_factors`]): the derivation is [`idlers_behind_capstan`]'s. Nothing
/// is called where no such idler exists.
pub fn idler_weights<T: Real>(
    model: &Model<T>,
    capstan: &[Vec<T>],
    mut each: impl FnMut(usize, usize, Vec<T>),
) {
    if !model.capstan_before_an_idler() {
        return;
    }
    for (s, (strand, factors)) in model.strands.iter().zip(capstan).enumerate() {
        for (i, idler) in strand.idlers.iter().enumerate() {
            if idler.guide.is_some() {
                continue;
            }
            // T_k / T_{i+1} for k = i, i − 1, …, 0, and the weight they give.
            let mut ratio = T::one();
            let mut weight = vec![T::zero(); model.dof];
            let mut behind = false;
            for k in (0..=i).rev() {
                if k < i && strand.idlers[k].capstan().is_some() {
                    ratio = ratio * factors[k];
                    behind = true;
                }
                if behind {
                    let step = T::from_f64(idler.turn / idler.radius);
                    for (w, share) in weight.iter_mut().zip(&strand.shares[k]) {
                        *w = *w + step * (ratio - T::one()) * *share;
                    }
                }
            }
            if behind {
                each(s, i, weight);
            }
        }
    }
}

/// `N_i − τ_f,i` of idler body `body`: its axial demand over `ws.motion` less its bearing's
/// friction in `ws.friction`.
fn idler_demand<T: Real>(model: &Model<T>, ws: &Workspace<T>, body: usize) -> T {
    let demand = tension::axial_demand(model, &ws.motion, body);
    if model.bodies[body].friction.is_some() {
        demand - ws.friction[body]
    } else {
        demand
    }
}

/// Adds `Σ_i W_i (N_i − τ_f,i)` to the generalized forces `out`: what the actuators deliver
/// beyond `M q̈ + h + g − Q_ext − Σ_b c_bᵀ τ_f,b` where turning idlers sit behind guides
/// with friction ([`idlers_behind_capstan`]), over the state's motion, bearing torques and
/// capstan factors in `ws` (`ws.motion` with the tendons' inert bodies: a massless idler
/// demands nothing either way).
fn add_idlers_behind_capstan<T: Real>(model: &Model<T>, ws: &Workspace<T>, out: &mut [T]) {
    idler_weights(model, &ws.capstan, |strand, idler, weight| {
        let demand = idler_demand(model, ws, model.strands[strand].idlers[idler].body);
        for (o, w) in out.iter_mut().zip(&weight) {
            *o = *o + *w * demand;
        }
    });
}

/// Forward dynamics' joint accelerations from its right-hand side `rhs` (replaced by `q̈`),
/// `solve` applying `M⁻¹` in place (a factor of the mass matrix): `M⁻¹ rhs`, or, where
/// idlers sit behind guides with friction ([`idlers_behind_capstan`]), the solution of
/// `(M + W Jᵀ) q̈ = rhs − Σ_i W_i N_i,0` (`W`, `J` with the columns `W_i`, `∂N_i/∂q̈`) by
/// the Woodbury identity on `M`'s factor: `q̈ = x − Y (I + Jᵀ Y)⁻¹ Jᵀ x`, `x = M⁻¹ (rhs −
/// Σ W_i N_i,0)`, `Y = M⁻¹ W`. The small system `I + Jᵀ Y` (one row per idler) is the
/// identity plus the idlers' inertia relative to the mechanism's, scaled by the guides'
/// excess factors, and is solved without pivoting (straight-line, for every scalar).
pub fn accelerations<T: Real>(
    idlers: &[IdlerBehindCapstan<T>],
    mut solve: impl FnMut(&mut [T]),
    rhs: &mut [T],
) {
    for idler in idlers {
        for (r, w) in rhs.iter_mut().zip(&idler.weight) {
            *r = *r - idler.demand * *w;
        }
    }
    solve(rhs);
    if idlers.is_empty() {
        return;
    }
    let y: Vec<Vec<T>> = (idlers.iter())
        .map(|idler| {
            let mut v = idler.weight.clone();
            solve(&mut v);
            v
        })
        .collect();
    let p = idlers.len();
    let mut small = vec![T::zero(); p * p];
    for (a, idler) in idlers.iter().enumerate() {
        for (b, yb) in y.iter().enumerate() {
            let identity = if a == b { T::one() } else { T::zero() };
            small[a * p + b] = identity + crate::linalg::dot(&idler.inertia, yb);
        }
    }
    let mut z: Vec<T> = (idlers.iter())
        .map(|idler| crate::linalg::dot(&idler.inertia, rhs))
        .collect();
    crate::linalg::gauss_solve(&mut small, &mut z);
    for (yk, zk) in y.iter().zip(&z) {
        for (x, v) in rhs.iter_mut().zip(yk) {
            *x = *x - *v * *zk;
        }
    }
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

/// The balance rows of `E x = b` as affine forms, at the motion, bearing friction and
/// capstan factors in `ws`: the segment tensions (Eq. 24b), the backward recursion with
/// them as unknowns (Eqs. 19-24) and the axial balances it leaves (`tension::balance_rows`).
/// The solver takes `E` from the transmission (constant, or [`tension::state_matrix`]);
/// these rows are how tests check it against the recursion's own statics. At most
/// [`crate::affine::MAX_UNKNOWNS`] unknowns.
fn balance<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) -> Vec<Affine<T>> {
    let nu = model.system.unknowns.len();
    tension::segment_tensions(
        model,
        &ws.motion,
        &ws.friction,
        &ws.capstan,
        |k| Affine::unknown(k, T::zero(), nu),
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
    let mut rows = vec![Affine::constant(T::zero(), nu); model.system.rows.len()];
    tension::balance_rows(model, &ws.loads, &ws.friction, &mut rows);
    rows
}

/// The recursion with every strand's ground-level tension known, `ground(unknown)`: the
/// segment tensions into `ws.segments`, the loads into `ws.tendon_loads`. With every
/// unknown zero its balance rows are `b`; with the solved unknowns its loads are the
/// bearings'.
fn with_ground_tensions<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    ground: impl Fn(usize) -> T,
) {
    tension::segment_tensions(
        model,
        &ws.motion,
        &ws.friction,
        &ws.capstan,
        ground,
        &mut ws.segments,
    );
    backward(
        model,
        &ws.motion,
        Some(&ws.segments),
        0,
        true,
        &mut ws.tendon_loads,
    );
}

/// The balance rows as affine forms at a state (`balance` after the forward pass and the
/// friction of that state): what [`crate::Data::balance_rows`] checks `E` with.
pub(crate) fn balance_at<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    ws: &mut Workspace<T>,
) -> Vec<Affine<T>> {
    forward(model, q, qd, qdd, true, true, &mut ws.motion);
    friction::bearing_torques(model, qd, Some(qdd), &mut ws.friction);
    friction::capstan_factors(model, q, qd, Some(qdd), &mut ws.capstan);
    balance(model, ws)
}

/// Inverse dynamics by the paper's recursion, with the unknowns solved apart from it: a
/// pass with every tension zero leaves `b`, `E x = b` is solved (`E` constant, `E⁺`
/// precomputed; `distribute` chooses among the solutions of a redundant routing), and a
/// pass with the solved tensions gives every segment tension and bearing force. This is
/// the paper's carrying of the tensions as unknowns to the base (Section 6), by
/// superposition: the recursion is linear in them. With capstan friction on guides `E`
/// depends on the state: `at_state` solves the state's `E` ([`tension::state_matrix`]).
///
/// The results are written into `out`, whose buffers are reused (no allocation once they
/// have the model's sizes; `sticking` is left to the caller).
#[allow(clippy::too_many_arguments)]
pub fn inverse_dynamics<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    ws: &mut Workspace<T>,
    at_state: impl FnOnce(&Model<T>, Vec<Vec<T>>) -> Result<TensionSystem<T>>,
    distribute: impl FnOnce(&Model<T>, &TensionSystem<T>, &mut [T]) -> Result<()>,
    out: &mut InverseDynamics<T>,
) -> Result<()> {
    forward(model, q, qd, qdd, true, true, &mut ws.motion);
    friction::bearing_torques(model, qd, Some(qdd), &mut ws.friction);
    friction::capstan_factors(model, q, qd, Some(qdd), &mut ws.capstan);
    with_ground_tensions(model, ws, |_| T::zero());
    tension::balance_rows(model, &ws.tendon_loads, &ws.friction, &mut ws.b);
    let state_system;
    let system = if model.has_capstan() {
        state_system = at_state(model, tension::state_matrix(model, &ws.capstan))?;
        &state_system
    } else {
        &model.system
    };
    let x = &mut out.unknowns;
    refill(x, model.system.unknowns.iter().map(|_| T::zero()));
    tension::solution(model, system, &ws.b, x);
    refill(&mut ws.minimal, x.iter().copied());
    tension::minimal_norm(model, system, &mut ws.minimal);
    distribute(model, system, x)?;
    let (x, x0) = (&out.unknowns, &ws.minimal);

    refill(
        &mut out.motor_torques,
        model.motors.iter().map(|m| x[m.unknown]),
    );
    refill(
        &mut out.tendon_tensions,
        model.tendons.iter().map(|t| x[t.unknown]),
    );
    refill(
        &mut out.minimal_norm_tensions,
        model.tendons.iter().map(|t| x0[t.unknown]),
    );
    refill(
        &mut out.null_space_tensions,
        model.tendons.iter().map(|t| x[t.unknown] - x0[t.unknown]),
    );
    // What the actuators deliver, `Σ c_m τ_m + A T`, is `M q̈ + h + g − Q_ext` (less the
    // bearings' friction, plus what idlers behind guides with friction demand): take it
    // from the tension-free pass over the same motion rather than from the solved tensions. A
    // redundant routing's null-space part, `A N λ`, vanishes only to rounding, so summing
    // `A T` loses `u·|A||T|`: everything when the floors lift the tensions far above what
    // the motion needs. The base reaction likewise (momentum balance: the tendons are
    // internal between the mechanism and its base, so their pulls cancel in it).
    backward(model, &ws.motion, None, 0, true, &mut ws.known);
    refill(
        &mut out.generalized_forces,
        (0..model.dof).map(|_| T::zero()),
    );
    expanded_sum(model, &ws.known, &mut out.generalized_forces);
    friction::apply(
        model,
        &ws.friction,
        Side::Delivered,
        &mut out.generalized_forces,
    );
    add_idlers_behind_capstan(model, ws, &mut out.generalized_forces);
    refill(
        &mut out.bearing_friction,
        (model.bodies.iter().zip(&ws.friction).enumerate())
            .filter(|(_, (b, _))| b.friction.is_some())
            .map(|(i, (_, t))| (i, *t)),
    );
    refill(
        &mut out.loop_sides,
        (model.loops.iter()).map(|l| l.strands.map(|s| x[model.strands[s].unknown])),
    );
    refill(
        &mut out.pulley_demands,
        (model.bodies.iter().enumerate())
            .filter(|(_, b)| matches!(b.kind, BodyKind::Pulley { .. }))
            .map(|(i, _)| (i, tension::axial_demand(model, &ws.motion, i))),
    );
    if model.routing_incomplete {
        (out.segment_tensions, out.bearings, out.base_reaction) = (None, None, None);
    } else {
        with_ground_tensions(model, ws, |k| out.unknowns[k]);
        let segments = out.segment_tensions.get_or_insert_with(Vec::new);
        segments.resize_with(ws.segments.len(), Vec::new);
        for (to, from) in segments.iter_mut().zip(&ws.segments) {
            refill(to, from.iter().copied());
        }
        let bearings = out.bearings.get_or_insert_with(Vec::new);
        refill(
            bearings,
            (0..model.bodies.len()).map(|i| bearing(model, ws, q, &out.unknowns, i)),
        );
        out.base_reaction = Some((ws.known.base_force, ws.known.base_moment));
    }
    Ok(())
}

/// `v`'s entries replaced by `values`, in the buffer `v` already has.
fn refill<T>(v: &mut Vec<T>, values: impl IntoIterator<Item = T>) {
    v.clear();
    v.extend(values);
}

/// Bearing force and moment of body `i` from the pass with the solved unknowns `x`
/// ([`with_ground_tensions`]).
fn bearing<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    q: &[T],
    x: &[T],
    i: usize,
) -> (Vec3<T>, Vec3<T>) {
    let b = &model.bodies[i];
    let f = ws.tendon_loads.force[i];
    let mut n = ws.tendon_loads.moment[i];
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
        let (sn, cs) = coupled(&b.coupling, &model.patterns[i].joints, q).sin_cos();
        let spin = Mat3::rot_z(sn, cs);
        (spin.mul_vec(f), spin.mul_vec(n))
    } else {
        (f, n)
    }
}
