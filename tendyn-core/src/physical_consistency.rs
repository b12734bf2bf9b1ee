//! Physically consistent identification: the least-squares fit of
//! [`crate::identification`], constrained to mass properties that bodies can have.
//!
//! Base parameters are combinations, and least squares may return values that no
//! mechanism has (a negative combined inertia where a light pulley's is drowned in noise).
//! Here every body's ten inertial parameters `π_b = (m, h, I_o)` (the regressor's, about
//! the body-frame origin) are estimated, constrained so that a non-negative mass density
//! realises them: its **pseudo-inertia**
//!
//! ```text
//! J_b = [ Σ   h ]      Σ = ∫ r rᵀ dm = ½ tr(I_o) 1 − I_o
//!       [ hᵀ  m ]
//! ```
//!
//! positive semidefinite (Wensing, Kim & Slotine, IEEE RA-L 2018: necessary and sufficient;
//! it implies `m ≥ 0`, an inertia about the centre of mass with non-negative principal
//! moments, and their triangle inequalities). Bearing friction parameters stay `≥ 0`.
//!
//! The estimate minimises, over `π` in that set,
//!
//! ```text
//! f(π) = ½ ‖Y_base K π − (Q − Q₀)‖²  +  ½ λ ‖P S (π − π_file)‖²
//! ```
//!
//! where `K π` are the base parameters ([`BaseParameters::values`]). The forces say nothing
//! of `π`'s component in the kernel of `K`; the second term takes it from the file (`P` the
//! orthogonal projector onto that kernel, in the units `S` of [`crate::base_parameters`]
//! that make every parameter an inertia). It does not act on the base parameters, so where
//! the least-squares estimate completed by the file's values is physical the two agree;
//! otherwise it moves them by about `λ`, 1e-6 of the data term's mean curvature, so that
//! the data decide and the file only breaks ties. A body that turns but whose frame does
//! not spin (a pulley whose mass the file makes axisymmetric, such a body of a rigid tree)
//! stays axisymmetric about its axis, tilted or not: the model's dynamics of it hold for no
//! other mass.
//!
//! The problem is convex (a quadratic over a product of cones) and is solved by the barrier
//! method (Boyd & Vandenberghe, *Convex Optimization*, §11.3): Newton's method on
//! `t f(π) − Σ_b log det J_b − Σ log(friction)`, `t` growing tenfold per round, until the
//! duality gap `ν / t` (`ν` = 4 per body and 1 per friction parameter) is below
//! `GAP` of `½ ‖Q − Q₀‖²`, or until a round no longer settles in `ROUND_STEPS` Newton
//! steps where the gap is already below `ROUND_OFF_GAP` (round-off of `t f`'s gradient
//! outgrows the barrier's), whichever comes first; a round that does not settle above that
//! gap is an error. The iterates stay strictly inside the set: where the optimum is on its
//! boundary (a flat disk, a massless drum) the estimate is a hair inside, by about the
//! square root of the gap.
//!
//! `f` is kept as a square root, `f = ½ ‖B π − c‖²` with `B` stacking `R K` (`Y_base =
//! Q₁ R`, a thin QR) on `√λ P S`: its gradient `Bᵀ (B π − c)` then has the round-off of
//! the regressor's condition number, where the normal equations (`H = (Y K)ᵀ Y K`) would
//! square it. That is what lets the gap fall to 1e-28: with `H`, rounds stopped settling
//! at gaps of 1e-20 to 1e-24, and since a body the optimum puts on the boundary stays
//! inside by about the square root of the gap (over the data's curvature across it), motion
//! of condition 2e6 cost the estimate 1e-9 to 3e-7 of the largest base parameter (3e-12 to
//! 3e-11 now). Only the Newton system is formed from `H = Bᵀ B`: its round-off slows
//! Newton's method, it does not move the point it converges to. Hand-written: the
//! least-squares crates built on nalgebra
//! (levenberg-marquardt 0.15) pull a second nalgebra, and Clarabel's semidefinite cones
//! need a system BLAS and LAPACK.

use crate::base_parameters::{characteristic_length, dimension, BaseParameters};
use crate::error::{Error, Result};
use crate::identification::{least_squares, stack, Identification, Sample};
use crate::model::Model;
use crate::regressor::{self, Quantity};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix4, Vector3};

/// The barrier method stops when the duality gap is below this fraction of `½ ‖Q − Q₀‖²`.
pub const GAP: f64 = 1e-28;

/// A body is reported on the boundary of physical consistency when its pseudo-inertia's
/// smallest eigenvalue is below this fraction of its largest (a mass on a plane, a line or
/// a point), or its largest below this fraction of the largest of any body's (no mass to
/// speak of), in the units that make every entry an inertia (`J̃ = D J D`).
pub const BOUNDARY: f64 = 1e-6;

/// Newton steps the barrier method may take in all; far more than it needs (about ten per
/// round of `t`).
const NEWTON_STEPS: usize = 2_000;

/// Newton steps in one round of `t` after which the round is taken as settled to round-off
/// (where the gap is below [`ROUND_OFF_GAP`]) or as failing.
const ROUND_STEPS: usize = 60;

/// Below this duality gap (a fraction of `½ ‖Q − Q₀‖²`) a round that does not settle is
/// limited by round-off, not failing. Measured on every test's data (the paper's examples,
/// random and benchmark mechanisms, noise-free and at 40 dB, motion of condition up to 2e6),
/// rounds settle in 6-12 steps all the way to [`GAP`]; this is the guard for data that
/// round-off stops earlier.
const ROUND_OFF_GAP: f64 = 1e-10;

/// The physically consistent estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct Consistent {
    /// Every parameter of the regressor (`regressor::parameters` order): each body's mass,
    /// first moment and inertia about its origin, and bearing friction.
    pub parameters: Vec<f64>,
    /// The base parameters they give (`BaseParameters::values`), in the order of
    /// [`BaseParameters::groups`].
    pub estimates: Vec<f64>,
    /// The unconstrained least-squares fit of the same samples, for comparison.
    pub least_squares: Identification,
    /// `√(‖e‖² / N)` (N·m) of the consistent estimate.
    pub residual_rms: f64,
    /// `‖e‖ / ‖Q − Q₀‖` of the consistent estimate.
    pub relative_residual: f64,
    /// Every body's estimate (model order), as the file gives mass properties.
    pub bodies: Vec<BodyEstimate>,
    /// Newton steps taken.
    pub newton_steps: usize,
    /// The duality gap the barrier method reached, as a fraction of `½ ‖Q − Q₀‖²`: how far
    /// the estimate's misfit may be above the best physical one's.
    pub gap: f64,
}

/// One body's estimate, in its own frame, as the file gives mass properties.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyEstimate {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass (m); zero for a massless body.
    pub com: [f64; 3],
    /// Inertia about the centre of mass (kg·m²).
    pub inertia: [[f64; 3]; 3],
    /// Bearing friction `(coulomb, viscous)` (N·m, N·m·s/rad), where the file gives the
    /// body a `friction`.
    pub friction: Option<(f64, f64)>,
    /// On the boundary of physical consistency ([`BOUNDARY`]): the data, or the file's
    /// values where the data say nothing, ask for a mass on a plane, a line, a point, or
    /// none at all (a flat disk is one: its inertia about its axis is the sum of the
    /// other two).
    pub on_boundary: bool,
}

/// Estimates every body's mass properties (and bearing friction) of `model` from
/// `samples`, constrained to be physically consistent (see the module documentation).
pub fn identify_consistent(
    model: &Model<f64>,
    base: &BaseParameters,
    samples: &[Sample],
) -> Result<Consistent> {
    let (y, target) = stack(model, base, samples)?;
    let fit = least_squares(model, base, y.clone(), &target, samples.len())?;
    let problem = Problem::new(model, base, &y, &target)?;
    let (theta, newton_steps, gap) = problem.solve()?;
    let parameters = problem.parameters(&theta);
    let estimates = base.values(&parameters);
    let residual = &target - &y * DVector::from_column_slice(&estimates);
    let rss = residual.norm_squared();
    let eigenvalues: Vec<_> = (0..model.bodies().len())
        .map(|b| {
            let at = problem.first[b];
            (problem.pseudo_inertia_of(&parameters[at..at + 10])).symmetric_eigenvalues()
        })
        .collect();
    let largest = eigenvalues.iter().fold(0.0f64, |m, e| m.max(e.max()));
    let bodies = (0..model.bodies().len())
        .map(|b| {
            let e = &eigenvalues[b];
            let at = problem.first[b];
            let (m, com, inertia) = about_centre_of_mass(&parameters[at..at + 10]);
            let friction = problem
                .friction
                .iter()
                .find(|&&c| base.parameters[c].body == b)
                .map(|&c| (parameters[c], parameters[c + 1]));
            BodyEstimate {
                mass: m,
                com,
                inertia,
                friction,
                on_boundary: e.min() <= BOUNDARY * e.max() || e.max() <= BOUNDARY * largest,
            }
        })
        .collect();
    Ok(Consistent {
        parameters,
        estimates,
        least_squares: fit,
        residual_rms: (rss / target.len() as f64).sqrt(),
        relative_residual: rss.sqrt() / target.norm().max(f64::MIN_POSITIVE),
        bodies,
        newton_steps,
        gap,
    })
}

/// A body's ten parameters `(m, h, I_o)` as the file gives mass properties: mass, centre of
/// mass `h / m` and inertia about it, `I_c = I_o − (|h|² 1 − h hᵀ) / m` (parallel axes).
///
/// `I_c` is a difference of terms of size `|I_o|` and `|h|²/m`: where the estimate puts
/// the mass on a point or a line (a drum whose own inertia the data cannot see), its
/// principal moments are that difference's round-off, and may then miss positive
/// semi-definiteness or the triangle inequality by it, which the file's validation
/// refuses at a relative `1e-12` of the moments themselves. The estimate is consistent
/// (its pseudo-inertia positive semi-definite), so a miss within that round-off
/// (`64 u` of the terms) is round-off: the moments are then moved to the nearest that
/// meet both (negative ones to zero, then the two smaller raised and the largest lowered by
/// a third of the shortfall each), in the same principal axes. A larger miss is left as
/// it is for the file's validation to report.
fn about_centre_of_mass(x: &[f64]) -> (f64, [f64; 3], [[f64; 3]; 3]) {
    let (m, h) = (x[0], [x[1], x[2], x[3]]);
    let origin = Matrix3::new(x[4], x[5], x[6], x[5], x[7], x[8], x[6], x[8], x[9]);
    if m <= 0.0 {
        return (m, [0.0; 3], origin.into());
    }
    let h = Vector3::from(h);
    let shift = (Matrix3::identity() * h.norm_squared() - h * h.transpose()) / m;
    let inertia = origin - shift;
    let round_off = 64.0 * f64::EPSILON / 2.0 * (origin.amax() + shift.amax());
    let eigen = inertia.symmetric_eigen();
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let [l0, l1, l2] = order.map(|k| eigen.eigenvalues[k].max(0.0));
    let shortfall = (l2 - l0 - l1).max(0.0);
    let miss = shortfall.max(-eigen.eigenvalues[order[0]]);
    let inertia = if miss == 0.0 || miss > round_off {
        inertia
    } else {
        let third = shortfall / 3.0;
        let mut moments = eigen.eigenvalues;
        for (k, l) in order.into_iter().zip([l0 + third, l1 + third, l2 - third]) {
            moments[k] = l;
        }
        let v = eigen.eigenvectors;
        let i = v * Matrix3::from_diagonal(&moments) * v.transpose();
        (i + i.transpose()) / 2.0
    };
    (m, (h / m).into(), inertia.into())
}

/// The problem in the variables `θ`: per body the ten entries of `J̃ = D J D`
/// (`D = diag(1, 1, 1, L)`, so that every entry is an inertia; for a body kept
/// axisymmetric, of `J̃' = G⁻¹ J̃ G⁻ᵀ`, [`axial_frame`]), in the order of
/// [`SYMMETRIC_BASIS`], in the slots of its ten parameters; friction parameters as they
/// are. In `θ` a body near the boundary is near it in its own entries (a planar body's
/// `Σ_zz`), where in `π` it would be the difference `½ (xx + yy − zz)` of entries a
/// thousand times larger, lost to round-off.
struct Problem {
    /// `f(θ) = ½ ‖B θ − c‖² + const`: `B` is `f`'s square root, from which its gradient
    /// `Bᵀ (B θ − c)` and curvatures `‖B v‖²` are computed (with the round-off of `B`'s
    /// condition number, where `H = Bᵀ B` would square it).
    root: DMatrix<f64>,
    c: DVector<f64>,
    /// `H = Bᵀ B`, for the Newton system alone (its round-off only slows Newton's method).
    h: DMatrix<f64>,
    /// `½ ‖Q − Q₀‖²`: the scale of `f`.
    scale: f64,
    /// `π = T θ`.
    to_parameters: DMatrix<f64>,
    /// The file's values, `π_file`.
    prior: Vec<f64>,
    /// Per body, the index of its first slot.
    first: Vec<usize>,
    /// Per body that turns but whose frame does not spin ([`crate::model::Body::axisymmetric`]:
    /// the model counts on a mass axisymmetric about its joint axis), the map `G` of
    /// [`axial_frame`] and its inverse. Its variables are the entries of `J̃' = G⁻¹ J̃ G⁻ᵀ`
    /// (the body seen with its axis along z through the origin), which Newton's steps keep
    /// axisymmetric about z: its estimate stays axisymmetric about its axis, or the model
    /// would no longer describe it.
    axial_frames: Vec<Option<(Matrix4<f64>, Matrix4<f64>)>>,
    /// The slots of the friction parameters.
    friction: Vec<usize>,
    /// `L` of `D`: the mechanism's length ([`crate::base_parameters`]).
    length: f64,
}

impl Problem {
    fn new(
        model: &Model<f64>,
        base: &BaseParameters,
        y: &DMatrix<f64>,
        target: &DVector<f64>,
    ) -> Result<Self> {
        let p = base.parameters.len();
        let r = base.groups.len();
        let mut first = Vec::new();
        let mut friction = Vec::new();
        for (c, x) in base.parameters.iter().enumerate() {
            match x.quantity {
                Quantity::Inertial(0) => first.push(c),
                Quantity::Inertial(_) => {}
                Quantity::Coulomb | Quantity::Viscous => friction.push(c),
            }
        }
        let length = characteristic_length(model);
        let axial_frames = (model.bodies().iter())
            .map(|b| {
                let joint = (-b.joint_to_origin).to_array();
                b.axisymmetric()
                    .then(|| axial_frame(b.axis.to_array(), joint, length))
            })
            .collect();
        // K (r × p): column c is what parameter c adds to each base parameter.
        let mut k = DMatrix::<f64>::zeros(r, p);
        for (i, group) in base.groups.iter().enumerate() {
            k[(i, group.column)] = 1.0;
            for &(c, coefficient) in &group.merged {
                k[(i, c)] += coefficient;
            }
        }
        let units: Vec<f64> = (base.parameters.iter())
            .map(|x| dimension(x, length))
            .collect();
        // Data term in π: ½ ‖Y K π − t‖² = ½ ‖R K π − Q₁ᵀ t‖² + const, `Y = Q₁ R` (thin
        // QR, `Y` has full column rank: least squares checked its condition).
        let qr = y.clone().qr();
        let data_root = qr.r() * &k;
        let data_c = qr.q().transpose() * target;
        // Prior term on the kernel of K, in the units S: P = 1 − K̃ᵀ (K̃ K̃ᵀ)⁻¹ K̃ with
        // K̃ = K S⁻¹; its quadratic form in π is λ S P S. K has the identity on its kept
        // columns, so K̃ K̃ᵀ is invertible.
        let mut k_units = k.clone();
        for (c, u) in units.iter().enumerate() {
            k_units.column_mut(c).scale_mut(1.0 / u);
        }
        let along = (&k_units * k_units.transpose())
            .cholesky()
            .map(|c| c.solve(&k_units))
            .ok_or_else(|| {
                Error::State(
                    "physically consistent identification: the base parameters' grouping is \
                     singular"
                        .into(),
                )
            })?;
        // P S, whose square (P symmetric and idempotent) is the quadratic form S P S.
        let mut projector = DMatrix::<f64>::identity(p, p) - k_units.transpose() * along;
        for (j, u) in units.iter().enumerate() {
            projector.column_mut(j).scale_mut(*u);
        }
        // The data term's mean curvature per parameter in the units S: its diagonal is the
        // squared norms of `R K`'s columns.
        let curvature = (data_root.column_iter().zip(&units))
            .map(|(column, u)| column.norm_squared() / (u * u))
            .sum::<f64>()
            / p as f64;
        let weight = (1e-6 * curvature.max(f64::MIN_POSITIVE)).sqrt();
        let prior = regressor::values(model);
        let prior_c = &projector * DVector::from_column_slice(&prior) * weight;
        let mut root = DMatrix::<f64>::zeros(data_root.nrows() + p, p);
        root.rows_mut(0, data_root.nrows()).copy_from(&data_root);
        root.rows_mut(data_root.nrows(), p)
            .copy_from(&(projector * weight));
        let c = DVector::from_iterator(
            data_c.len() + p,
            data_c.iter().chain(prior_c.iter()).copied(),
        );
        // To θ: π = T θ, so B_θ = B T.
        let mut problem = Problem {
            root: DMatrix::zeros(0, 0),
            c,
            h: DMatrix::zeros(0, 0),
            scale: 0.5 * target.norm_squared(),
            to_parameters: DMatrix::identity(p, p),
            prior,
            first,
            axial_frames,
            friction,
            length,
        };
        for (b, &at) in problem.first.iter().enumerate() {
            for (k, &(row, column)) in SYMMETRIC_BASIS.iter().enumerate() {
                let mut unit = Matrix4::zeros();
                unit[(row, column)] = 1.0;
                unit[(column, row)] = 1.0;
                // A body kept axisymmetric has the entries of `J̃'`, `J̃ = G J̃' Gᵀ`.
                if let Some((g, _)) = &problem.axial_frames[b] {
                    unit = g * unit * g.transpose();
                }
                let column_of_t = problem.parameters_of(&unit);
                for (i, x) in column_of_t.iter().enumerate() {
                    problem.to_parameters[(at + i, at + k)] = *x;
                }
            }
        }
        problem.root = root * &problem.to_parameters;
        problem.h = problem.root.transpose() * &problem.root;
        Ok(problem)
    }

    /// `π = T θ`.
    fn parameters(&self, theta: &DVector<f64>) -> Vec<f64> {
        (&self.to_parameters * theta).as_slice().to_vec()
    }

    /// Body `b`'s `J̃` at `theta`.
    fn pseudo_inertia(&self, b: usize, theta: &DVector<f64>) -> Matrix4<f64> {
        let at = self.first[b];
        let mut j = Matrix4::zeros();
        for (k, &(row, column)) in SYMMETRIC_BASIS.iter().enumerate() {
            j[(row, column)] = theta[at + k];
            j[(column, row)] = theta[at + k];
        }
        j
    }

    /// `J̃` of a body's parameters `(m, h, I_o)` (regressor order).
    fn pseudo_inertia_of(&self, x: &[f64]) -> Matrix4<f64> {
        let l = self.length;
        let inertia = [[x[4], x[5], x[6]], [x[5], x[7], x[8]], [x[6], x[8], x[9]]];
        let half_trace = 0.5 * (x[4] + x[7] + x[9]);
        let mut j = Matrix4::zeros();
        for r in 0..3 {
            for c in 0..3 {
                // Σ = ½ tr(I_o) 1 − I_o.
                j[(r, c)] = if r == c { half_trace } else { 0.0 } - inertia[r][c];
            }
            j[(r, 3)] = l * x[1 + r];
            j[(3, r)] = l * x[1 + r];
        }
        j[(3, 3)] = l * l * x[0];
        j
    }

    /// The parameters `(m, h, I_o)` of a body whose `J̃` is `j` (the inverse of
    /// [`Problem::pseudo_inertia_of`], linear).
    fn parameters_of(&self, j: &Matrix4<f64>) -> [f64; 10] {
        let l = self.length;
        let trace = j[(0, 0)] + j[(1, 1)] + j[(2, 2)];
        // I_o = tr(Σ) 1 − Σ.
        let inertia = |r: usize, c: usize| if r == c { trace } else { 0.0 } - j[(r, c)];
        [
            j[(3, 3)] / (l * l),
            j[(0, 3)] / l,
            j[(1, 3)] / l,
            j[(2, 3)] / l,
            inertia(0, 0),
            inertia(0, 1),
            inertia(0, 2),
            inertia(1, 1),
            inertia(1, 2),
            inertia(2, 2),
        ]
    }

    /// A strictly feasible start: the file's values, each `J̃` lifted by a small multiple of
    /// the identity (a thin uniform shell of mass), friction by a little.
    fn start(&self) -> DVector<f64> {
        let bodies = self.first.len();
        let priors: Vec<Matrix4<f64>> = (0..bodies)
            .map(|b| self.pseudo_inertia_of(&self.prior[self.first[b]..self.first[b] + 10]))
            .collect();
        let typical = priors
            .iter()
            .map(|j| j.trace() / 4.0)
            .fold(0.0f64, f64::max);
        let typical = if typical > 0.0 { typical } else { 1e-6 };
        let mut theta = DVector::from_column_slice(&self.prior);
        for (b, j) in priors.iter().enumerate() {
            // A body kept axisymmetric starts from `J̃' = G⁻¹ J̃ G⁻ᵀ` (its variables).
            let seen = match &self.axial_frames[b] {
                Some((_, inverse)) => inverse * j * inverse.transpose(),
                None => *j,
            };
            let smallest = seen.symmetric_eigenvalues().min();
            let lifted = seen + Matrix4::identity() * ((-smallest).max(0.0) + 1e-3 * typical);
            for (k, &(row, column)) in SYMMETRIC_BASIS.iter().enumerate() {
                theta[self.first[b] + k] = lifted[(row, column)];
            }
        }
        let friction_scale = self
            .friction
            .iter()
            .map(|&c| self.prior[c].abs())
            .fold(0.0f64, f64::max)
            .max((2.0 * self.scale).sqrt() * 1e-6)
            .max(f64::MIN_POSITIVE);
        for &c in &self.friction {
            theta[c] = self.prior[c].max(0.0) + 1e-3 * friction_scale;
        }
        theta
    }

    /// The barrier method; returns `θ`, the Newton steps taken and the duality gap reached
    /// (a fraction of `½ ‖Q − Q₀‖²`).
    fn solve(&self) -> Result<(DVector<f64>, usize, f64)> {
        let nu = (4 * self.first.len() + self.friction.len()) as f64;
        let scale = self.scale.max(f64::MIN_POSITIVE);
        let mut theta = self.start();
        // Start where the gap is 1e-3 of the scale, then ten times tighter each round.
        let mut t = nu / (1e-3 * scale);
        let mut steps = 0;
        loop {
            let mut last = f64::INFINITY;
            let mut round = 0;
            loop {
                if steps == NEWTON_STEPS {
                    return Err(Error::State(format!(
                        "physically consistent identification did not converge in \
                         {NEWTON_STEPS} Newton steps"
                    )));
                }
                steps += 1;
                round += 1;
                let newton = self.newton_step(t, &theta).ok_or_else(|| {
                    Error::State(
                        "physically consistent identification: the Newton system is singular"
                            .into(),
                    )
                })?;
                let decrement = newton.decrement;
                if decrement <= 1e-12 {
                    break;
                }
                // Past the damped phase the decrement falls quadratically; once it stops
                // falling it is round-off, and this `t` is done.
                if decrement < 1e-2 && decrement >= last {
                    break;
                }
                last = decrement;
                theta = self.line_search(t, &theta, &newton)?;
                // A round that cannot settle once the gap is below [`ROUND_OFF_GAP`] has
                // reached what round-off allows (`t f`'s gradient, of size `t`, then cancels
                // the barrier's to a few digits): the estimate is as good as f64 makes it.
                // Before that, it is not converging.
                if round == ROUND_STEPS {
                    if nu / t <= ROUND_OFF_GAP * scale {
                        return Ok((theta, steps, nu / t / scale));
                    }
                    return Err(Error::State(format!(
                        "physically consistent identification did not converge: Newton's \
                         method took {ROUND_STEPS} steps at a duality gap of {:.1e} of the \
                         forces' scale without settling",
                        nu / t / scale
                    )));
                }
            }
            if nu / t <= GAP * scale {
                return Ok((theta, steps, nu / t / scale));
            }
            t *= 10.0;
        }
    }

    /// Newton's step `H⁻¹ ∇` of `t f + barrier` at `theta` (inside the set), the same in
    /// the scaled coordinates `φ`, and the Newton decrement `λ² = ∇ᵀ H⁻¹ ∇` (about twice
    /// the suboptimality of the self-concordant `t f + barrier`).
    ///
    /// Near the boundary the barrier's curvature is `1/σ²` along a body's thin direction
    /// (`σ` the smallest eigenvalue of its `J̃`) and of order one along the others, and in
    /// the entries of `J̃` both mix: the Hessian is singular to round-off. So the step is
    /// computed in scaled coordinates, per body `ΔJ̃ = C Φ Cᵀ` with `C` the Cholesky factor
    /// of `J̃` and `Φ` symmetric (in the orthonormal basis of symmetric matrices), per
    /// friction parameter `Δc = c φ`: there the barrier's Hessian is the identity and its
    /// gradient `−tr Φ`, so the system is `(1 + t Mᵀ H M) φ = −∇_φ`, `M` the map from `φ`
    /// to `Δθ`, whose eigenvalues are at least one.
    fn newton_step(&self, t: f64, theta: &DVector<f64>) -> Option<Newton> {
        let p = theta.len();
        // M is block diagonal: ten by ten per body, one by one per friction parameter.
        let mut blocks: Vec<(usize, DMatrix<f64>)> = Vec::new();
        let mut barrier_gradient = DVector::<f64>::zeros(p);
        let mut units: Vec<(usize, Vec<Matrix4<f64>>)> = Vec::new();
        for b in 0..self.first.len() {
            let at = self.first[b];
            let j = self.pseudo_inertia(b, theta);
            let c = j.cholesky()?.l();
            // A body kept axisymmetric: `J̃'` axisymmetric about z, as every step.
            let basis = if self.axial_frames[b].is_some() {
                axisymmetric_basis()
            } else {
                symmetric_basis()
            };
            let mut block = DMatrix::<f64>::zeros(10, 10);
            for (k, unit) in basis.iter().enumerate() {
                // −log det: gradient −tr U, Hessian the identity (the basis is orthonormal).
                barrier_gradient[at + k] = -unit.trace();
                let change = c * unit * c.transpose();
                for (i, &(r, s)) in SYMMETRIC_BASIS.iter().enumerate() {
                    block[(i, k)] = change[(r, s)];
                }
            }
            blocks.push((at, block));
            units.push((at, basis));
        }
        for &c in &self.friction {
            if theta[c] <= 0.0 {
                return None;
            }
            blocks.push((c, DMatrix::from_element(1, 1, theta[c])));
            barrier_gradient[c] = -1.0;
        }
        // 1 + t Mᵀ H M and the gradient, block by block (O(p²) per block row, not O(p³)).
        let mut hm = DMatrix::<f64>::zeros(p, p);
        for (at, block) in &blocks {
            let k = block.nrows();
            hm.columns_mut(*at, k)
                .copy_from(&(self.h.columns(*at, k) * block));
        }
        let mut system = DMatrix::<f64>::identity(p, p);
        // `f`'s gradient `Bᵀ (B θ − c)`, once: the system's right-hand side and the slope
        // the line search needs.
        let gradient_f = self.root.transpose() * (&self.root * theta - &self.c);
        let slope = &gradient_f * t;
        let mut gradient = barrier_gradient;
        for (at, block) in &blocks {
            let k = block.nrows();
            let rows = block.transpose() * hm.rows(*at, k) * t;
            let mut target = system.rows_mut(*at, k);
            target += rows;
            let mut g = gradient.rows_mut(*at, k);
            g += block.transpose() * slope.rows(*at, k);
        }
        let phi = system.cholesky()?.solve(&gradient);
        let decrement = gradient.dot(&phi);
        let mut step = DVector::<f64>::zeros(p);
        for (at, block) in &blocks {
            let k = block.nrows();
            step.rows_mut(*at, k).copy_from(&(block * phi.rows(*at, k)));
        }
        // The eigenvalues of each `Φ` (and each friction `φ`): what the line search needs.
        let mut mu: Vec<f64> = Vec::new();
        for (at, basis) in &units {
            let scaled: Matrix4<f64> = (basis.iter().enumerate())
                .map(|(k, unit)| unit * phi[at + k])
                .sum();
            mu.extend(scaled.symmetric_eigenvalues().iter());
        }
        mu.extend(self.friction.iter().map(|&c| phi[c]));
        Some(Newton {
            slope: step.dot(&gradient_f),
            step,
            mu,
            decrement,
        })
    }

    /// Backtracking along the Newton direction `−step` (`−φ` in the scaled coordinates of
    /// [`Problem::newton_step`]): the full step when it stays inside the set and decreases
    /// `t f + barrier` enough (Armijo, 1/4 of the predicted), else halves. With a decrement
    /// below 1e-2 the full step stays inside (it is within the Dikin ellipsoid of the
    /// self-concordant `t f + barrier`) and is taken.
    ///
    /// Both changes are computed from their own terms, not as differences of values: `t f`
    /// is large where the gap is small, and `log det J̃` of a body near the boundary has the
    /// round-off of `J̃`'s condition number. Along `ΔJ̃ = −α C Φ Cᵀ` the barrier changes by
    /// `−Σ log(1 − α μ_i)` over the eigenvalues `μ_i` of `Φ` (and of `φ_c` for friction).
    fn line_search(&self, t: f64, theta: &DVector<f64>, newton: &Newton) -> Result<DVector<f64>> {
        let Newton {
            step,
            mu,
            decrement,
            slope,
        } = newton;
        let (decrement, slope) = (*decrement, *slope);
        let curvature = (&self.root * step).norm_squared();
        let mut alpha = 1.0;
        for _ in 0..60 {
            let next = theta - step * alpha;
            if mu.iter().all(|&m| 1.0 - alpha * m > 0.0) && self.inside(&next) {
                let barrier: f64 = mu.iter().map(|&m| -(-alpha * m).ln_1p()).sum();
                let change = t * alpha * (0.5 * alpha * curvature - slope) + barrier;
                if decrement < 1e-2 || change <= -0.25 * alpha * decrement {
                    return Ok(next);
                }
            }
            alpha *= 0.5;
        }
        Err(Error::State(
            "physically consistent identification: no step along Newton's direction \
             decreases the objective"
                .into(),
        ))
    }

    /// Whether `theta` is inside the set: every `J̃` positive definite (its Cholesky factor
    /// exists, as [`Problem::newton_step`] needs), friction positive.
    fn inside(&self, theta: &DVector<f64>) -> bool {
        self.friction.iter().all(|&c| theta[c] > 0.0)
            && (0..self.first.len()).all(|b| self.pseudo_inertia(b, theta).cholesky().is_some())
    }
}

/// Newton's step of `t f + barrier` at a point, with what the line search needs of it.
struct Newton {
    /// `H⁻¹ ∇` in the entries `θ` (the direction is `−step`).
    step: DVector<f64>,
    /// The eigenvalues of each body's `Φ` and each friction parameter's `φ`.
    mu: Vec<f64>,
    /// The Newton decrement `∇ᵀ H⁻¹ ∇`.
    decrement: f64,
    /// `stepᵀ Bᵀ (B θ − c)`: `f`'s slope along `step`.
    slope: f64,
}

/// The orthonormal basis of symmetric 4 × 4 matrices (trace inner product), in the order of
/// [`SYMMETRIC_BASIS`].
fn symmetric_basis() -> Vec<Matrix4<f64>> {
    (SYMMETRIC_BASIS.iter())
        .map(|&(r, c)| {
            let mut unit = Matrix4::zeros();
            let x = if r == c {
                1.0
            } else {
                core::f64::consts::FRAC_1_SQRT_2
            };
            unit[(r, c)] = x;
            unit[(c, r)] = x;
            unit
        })
        .collect()
}

/// The map of pseudo-inertias `J̃ = G J̃' Gᵀ` from a frame whose z axis is the joint axis
/// through the origin to the body's, where the axis is the line through `joint` along the
/// unit vector `axis` (body frame): `r = R r' + joint`, so `G = [[R, joint/L], [0, 1]]` in
/// the units of `J̃ = D J D` ([`Problem`]), `R` a rotation whose third column is `axis`
/// (the identity for z). With its inverse `[[Rᵀ, −Rᵀ joint/L], [0, 1]]`.
fn axial_frame(axis: [f64; 3], joint: [f64; 3], length: f64) -> (Matrix4<f64>, Matrix4<f64>) {
    let a = nalgebra::Vector3::from(axis).normalize();
    let helper = if a.x.abs() < 0.9 {
        nalgebra::Vector3::x()
    } else {
        nalgebra::Vector3::y()
    };
    let e1 = (helper - a * helper.dot(&a)).normalize();
    let e2 = a.cross(&e1);
    let r = nalgebra::Matrix3::from_columns(&[e1, e2, a]);
    let shift = nalgebra::Vector3::from(joint) / length;
    let mut g = Matrix4::identity();
    g.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
    g.fixed_view_mut::<3, 1>(0, 3).copy_from(&shift);
    let mut inverse = Matrix4::identity();
    inverse
        .fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&r.transpose());
    inverse
        .fixed_view_mut::<3, 1>(0, 3)
        .copy_from(&(-(r.transpose() * shift)));
    (g, inverse)
}

/// The orthonormal basis of the pseudo-inertias axisymmetric about z (`Σ_xx = Σ_yy`, no
/// first moment across the axis, no products of inertia): `(e₀e₀ᵀ + e₁e₁ᵀ)/√2`, `e₂e₂ᵀ`,
/// `e₃e₃ᵀ`, `(e₂e₃ᵀ + e₃e₂ᵀ)/√2`. A Cholesky factor of such a matrix has its pattern, so
/// `C Φ Cᵀ` keeps it.
fn axisymmetric_basis() -> Vec<Matrix4<f64>> {
    let half = core::f64::consts::FRAC_1_SQRT_2;
    let mut across = Matrix4::zeros();
    (across[(0, 0)], across[(1, 1)]) = (half, half);
    let mut along = Matrix4::zeros();
    along[(2, 2)] = 1.0;
    let mut mass = Matrix4::zeros();
    mass[(3, 3)] = 1.0;
    let mut moment = Matrix4::zeros();
    (moment[(2, 3)], moment[(3, 2)]) = (half, half);
    vec![across, along, mass, moment]
}

/// The entries `(row, column)`, `row ≤ column`, of a symmetric 4 × 4 matrix, in the order
/// of a body's slots in `θ`, and of the orthonormal basis of symmetric matrices (`e_r e_rᵀ`
/// on the diagonal, `(e_r e_cᵀ + e_c e_rᵀ)/√2` off it).
const SYMMETRIC_BASIS: [(usize, usize); 10] = [
    (0, 0),
    (1, 1),
    (2, 2),
    (3, 3),
    (0, 1),
    (0, 2),
    (0, 3),
    (1, 2),
    (1, 3),
    (2, 3),
];

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// What the file's validation asks of an inertia about the centre of mass
    /// (`validate/bodies.rs`): positive semi-definite and the triangle inequality, each to
    /// a relative `1e-12` of the largest principal moment.
    fn loads(i: &[[f64; 3]; 3]) -> bool {
        let m = Matrix3::from(*i);
        let mut l: Vec<f64> = m.symmetric_eigen().eigenvalues.iter().copied().collect();
        l.sort_by(f64::total_cmp);
        let scale = l[2].abs().max(f64::MIN_POSITIVE);
        l[0] >= -1e-12 * scale && l[0] + l[1] >= l[2] * (1.0 - 1e-12)
    }

    #[test]
    fn a_point_mass_off_the_origin_is_written_as_an_inertia_the_file_accepts() {
        // A point mass at `c`: `I_o = m (|c|² 1 − c cᵀ)`, so `I_c` is zero but for the
        // round-off of the parallel-axis shift, which left alone failed the file's
        // validation at 1,813 of these 2,000 (seeded) positions.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut next = move || rng.random_range(-0.5f64..0.5);
        for _ in 0..2000 {
            let m = 0.01 + next().abs();
            let c = [next() * 0.1, next() * 0.1, next() * 0.1];
            let c2 = c.iter().map(|v| v * v).sum::<f64>();
            let i = |a: usize, b: usize| m * (if a == b { c2 } else { 0.0 } - c[a] * c[b]);
            let x = [
                m,
                m * c[0],
                m * c[1],
                m * c[2],
                i(0, 0),
                i(0, 1),
                i(0, 2),
                i(1, 1),
                i(1, 2),
                i(2, 2),
            ];
            let (mass, com, inertia) = about_centre_of_mass(&x);
            assert_eq!(mass, m);
            for k in 0..3 {
                assert!((com[k] - c[k]).abs() <= 1e-15, "{com:?} {c:?}");
                for l in 0..3 {
                    // Round-off of the shift, nothing more.
                    assert!(
                        inertia[k][l].abs() <= 1e-15 * m * c2.max(1e-30),
                        "{inertia:?}"
                    );
                }
            }
            assert!(loads(&inertia), "{x:?} gives {inertia:?}");
        }
    }

    #[test]
    fn an_inertia_that_misses_by_more_than_round_off_is_left_for_validation_to_refuse() {
        // A rod's inertia about its centre with one moment too small by a tenth: no
        // round-off makes that, so it is passed on as it is.
        let x = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 2.2];
        let (_, _, inertia) = about_centre_of_mass(&x);
        assert_eq!(inertia, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.2]]);
        assert!(!loads(&inertia));
    }
}
