//! The runtime solver: inverse dynamics with every tension and bearing force, the
//! joint-space mass matrix, bias and gravity terms, and forward dynamics, all on top of
//! the one recursion in [`crate::kinematics`] and [`crate::newton_euler`].
//!
//! `M`, `h` and `g` come from the expanded-tree form of the same recursion: every body's
//! axial joint moment `τ_b` mapped to the joint coordinates through its coupling,
//! `Q = Σ_b c_bᵀ τ_b` (virtual work), with the tendons left out (their forces are internal
//! once the pulleys' couplings hold).

use crate::affine::Affine;
use crate::error::{Error, Result};
use crate::kinematics::{forward, Motion};
use crate::model::{BodyKind, Model, MotorKind};
use crate::newton_euler::{backward, Loads};
use crate::real::{Numeric, Real};
use crate::spatial::Vec3;
use crate::tension;
use crate::transmission::linalg;

/// Everything inverse dynamics reports at one state. See `docs/outputs.md` for units,
/// frames and signs.
#[derive(Clone, Debug)]
pub struct InverseDynamics<T> {
    /// Generalized forces the actuators deliver, `Q = Σ motor columns · τ + A T` (N·m).
    pub generalized_forces: Vec<T>,
    /// One torque per motor, in file order (N·m).
    pub motor_torques: Vec<T>,
    /// Ground-level tension of each open-ended tendon, in file order (N).
    pub tendon_tensions: Vec<T>,
    /// The minimal-norm part of the tendon tensions (may be negative).
    pub minimal_norm_tensions: Vec<T>,
    /// The null-space part added to keep every tendon at its floor.
    pub null_space_tensions: Vec<T>,
    /// Tension of both sides of each loop at its driving pulley (leaving the driven pulley
    /// counter-clockwise, then clockwise), and whether a side would be slack (< 0).
    pub loop_sides: Vec<([T; 2], bool)>,
    /// Tension of every segment of every strand, `None` if the routing is incomplete.
    pub segment_tensions: Option<Vec<Vec<T>>>,
    /// Moment each intermediate link needs about its own axis (body index, N·m).
    pub pulley_demands: Vec<(usize, T)>,
    /// Bearing force and moment on every body from its parent, moment about the joint
    /// point, the motor's torque excluded; links in their DH frame, pulleys in their housing
    /// frame (the pulley frame at zero spin). `None` if the routing is incomplete.
    pub bearings: Option<Vec<(Vec3<T>, Vec3<T>)>>,
    /// Total force and moment (about the base origin) of the base on the mechanism.
    pub base_reaction: Option<(Vec3<T>, Vec3<T>)>,
    /// The solved unknowns of the tension system.
    pub unknowns: Vec<T>,
}

/// Generalized forces of the expanded tree, `Q = Σ_b c_bᵀ τ_b`, with the tendons left out
/// (their forces are internal once the pulleys' couplings hold): `M q̈ + h + g` with
/// `gravity`, minus the external wrench's generalized force with `external`. Generic over
/// [`Real`], so the code generator traces exactly this.
#[allow(clippy::too_many_arguments)]
pub fn expanded_generalized_forces<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    gravity: bool,
    external: bool,
    motion: &mut [Motion<T>],
    loads: &mut Loads<T>,
    out: &mut [T],
) {
    forward(model, q, qd, qdd, gravity, motion);
    backward(model, motion, None, 0, external, loads);
    for o in out.iter_mut() {
        *o = T::zero();
    }
    for (b, t) in model.bodies.iter().zip(&loads.axial) {
        for (o, c) in out.iter_mut().zip(&b.coupling) {
            *o = *o + *c * t.constant;
        }
    }
}

/// Work buffers for one model; the model itself stays immutable.
pub struct Solver<'m, T> {
    pub model: &'m Model<T>,
    motion: Vec<Motion<T>>,
    loads: Loads<T>,
    tensions: Vec<Vec<Affine<T>>>,
    zeros: Vec<T>,
}

impl<'m, T: Numeric> Solver<'m, T> {
    pub fn new(model: &'m Model<T>) -> Self {
        let nu = model.system.unknowns.len();
        Solver {
            model,
            motion: vec![Motion::rest(); model.bodies.len()],
            loads: Loads::new(model.bodies.len(), nu),
            tensions: model
                .strands
                .iter()
                .map(|s| vec![Affine::constant(T::zero(), nu); s.segments.len()])
                .collect(),
            zeros: vec![T::zero(); model.dof],
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

    /// `Σ_b c_bᵀ τ_b` of the expanded tree, tendons left out.
    fn expanded(
        &mut self,
        q: &[T],
        qd: &[T],
        qdd: &[T],
        gravity: bool,
        external: bool,
        out: &mut [T],
    ) {
        expanded_generalized_forces(
            self.model,
            q,
            qd,
            qdd,
            gravity,
            external,
            &mut self.motion,
            &mut self.loads,
            out,
        );
    }

    /// Generalized forces `Q = M q̈ + h + g − Jᵀ w_ext` from the expanded tree.
    pub fn generalized_forces(&mut self, q: &[T], qd: &[T], qdd: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        self.check_state("qdd", qdd)?;
        let mut out = vec![T::zero(); self.model.dof];
        self.expanded(q, qd, qdd, true, true, &mut out);
        Ok(out)
    }

    /// Joint-space mass matrix `M(q)`, pulley inertias included through their couplings.
    pub fn mass_matrix(&mut self, q: &[T]) -> Result<Vec<Vec<T>>> {
        self.check_state("q", q)?;
        let n = self.model.dof;
        let zeros = self.zeros.clone();
        let mut m = vec![vec![T::zero(); n]; n];
        let mut unit = zeros.clone();
        let mut col = zeros.clone();
        for j in 0..n {
            unit[j] = T::one();
            self.expanded(q, &zeros, &unit, false, false, &mut col);
            for i in 0..n {
                m[i][j] = col[i];
            }
            unit[j] = T::zero();
        }
        Ok(m)
    }

    /// Bias `h(q, q̇)`: Coriolis and centrifugal generalized forces.
    pub fn bias(&mut self, q: &[T], qd: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        let zeros = self.zeros.clone();
        let mut out = zeros.clone();
        self.expanded(q, qd, &zeros, false, false, &mut out);
        Ok(out)
    }

    /// Gravity generalized forces `g(q)`.
    pub fn gravity(&mut self, q: &[T]) -> Result<Vec<T>> {
        self.check_state("q", q)?;
        let zeros = self.zeros.clone();
        let mut out = zeros.clone();
        self.expanded(q, &zeros, &zeros, true, false, &mut out);
        Ok(out)
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
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        let model = self.model;
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
        let zeros = self.zeros.clone();
        let mut rhs = zeros.clone();
        self.expanded(q, qd, &zeros, true, true, &mut rhs);
        for (j, r) in rhs.iter_mut().enumerate() {
            let mut u = T::zero();
            for (m, t) in model.motors.iter().zip(motor_torques) {
                u = u + T::from_f64(m.column[j]) * *t;
            }
            for (k, t) in model.tendons.iter().zip(tendon_tensions) {
                u = u + T::from_f64(k.structure[j]) * *t;
            }
            *r = u - *r;
        }
        let m = self.mass_matrix(q)?;
        linalg::cholesky_solve(&m, &rhs).ok_or_else(|| {
            Error::Singular(
                "the mass matrix is not positive definite at this state (a massless chain, or a \
                 link whose motion nothing resists)"
                    .into(),
            )
        })
    }

    /// Inverse dynamics by the paper's recursion: tensions carried to the base, `E x = b`
    /// solved there, and every segment tension and bearing force by back-substitution.
    pub fn inverse_dynamics(&mut self, q: &[T], qd: &[T], qdd: &[T]) -> Result<InverseDynamics<T>> {
        self.check_state("q", q)?;
        self.check_state("qd", qd)?;
        self.check_state("qdd", qdd)?;
        let model = self.model;
        let nu = model.system.unknowns.len();
        forward(model, q, qd, qdd, true, &mut self.motion);
        tension::segment_tensions(model, &self.motion, nu, &mut self.tensions);
        backward(
            model,
            &self.motion,
            Some(&self.tensions),
            nu,
            true,
            &mut self.loads,
        );
        let mut b = vec![T::zero(); model.system.rows.len()];
        tension::demand(model, &self.loads, &mut b);
        let mut x = vec![T::zero(); nu];
        tension::minimal_norm(model, &b, &mut x);
        let x0 = x.clone();
        tension::distribute(model, &mut x)?;

        let motor_torques: Vec<T> = model.motors.iter().map(|m| x[m.unknown]).collect();
        let tendon_tensions: Vec<T> = model.tendons.iter().map(|t| x[t.unknown]).collect();
        let minimal_norm_tensions: Vec<T> = model.tendons.iter().map(|t| x0[t.unknown]).collect();
        let null_space_tensions: Vec<T> = model
            .tendons
            .iter()
            .map(|t| x[t.unknown] - x0[t.unknown])
            .collect();
        let mut generalized_forces = vec![T::zero(); model.dof];
        for (j, g) in generalized_forces.iter_mut().enumerate() {
            for (m, t) in model.motors.iter().zip(&motor_torques) {
                *g = *g + T::from_f64(m.column[j]) * *t;
            }
            for (k, t) in model.tendons.iter().zip(&tendon_tensions) {
                *g = *g + T::from_f64(k.structure[j]) * *t;
            }
        }
        let loop_sides = model
            .loops
            .iter()
            .map(|l| {
                let sides = l.strands.map(|s| x[model.strands[s].unknown]);
                let slack = sides.iter().any(|&v| v < T::zero());
                (sides, slack)
            })
            .collect();
        let pulley_demands = model
            .bodies
            .iter()
            .enumerate()
            .filter(|(_, b)| matches!(b.kind, BodyKind::Pulley { .. }))
            .map(|(i, _)| (i, tension::axial_demand(model, &self.motion, i)))
            .collect();
        let (segment_tensions, bearings, base_reaction) = if model.routing_incomplete {
            (None, None, None)
        } else {
            let segs = self
                .tensions
                .iter()
                .map(|s| s.iter().map(|t| t.eval(&x)).collect())
                .collect();
            let bearings = (0..model.bodies.len())
                .map(|i| {
                    let f = self.loads.force[i].eval(&x);
                    let mut n = self.loads.moment[i].eval(&x);
                    // The bearing carries what the motor on this joint does not.
                    if let Some(m) = model.motors.iter().find(|m| match m.kind {
                        MotorKind::Joint(j) => j == i,
                        MotorKind::Pulley(b) => b == i,
                    }) {
                        n = n - model.bodies[i].axis.scale(x[m.unknown]);
                    }
                    // A spinning pulley's frame turns with it; report it in its housing
                    // frame (the pulley frame at zero spin) like every other pulley.
                    let b = &model.bodies[i];
                    if b.spins && matches!(b.kind, BodyKind::Pulley { .. }) {
                        let (sn, cs) = crate::kinematics::coupled(&b.coupling, q).sin_cos();
                        let spin = crate::spatial::Mat3::rot_z(sn, cs);
                        (spin.mul_vec(f), spin.mul_vec(n))
                    } else {
                        (f, n)
                    }
                })
                .collect();
            let base = (
                self.loads.base_force.eval(&x),
                self.loads.base_moment.eval(&x),
            );
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
            unknowns: x,
        })
    }

    /// The balance rows of the last inverse-dynamics call, as affine forms (for checks of
    /// the recursion against the transmission's `E`).
    pub fn last_balance_rows(&self) -> Vec<Affine<T>> {
        tension::balance_rows(self.model, &self.loads)
    }
}
