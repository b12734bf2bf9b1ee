//! The tension distribution (the "torque resolver" of the paper's ref. 12, with maxima):
//! one implementation, `no_std` and allocation-free, for the runtime solver and for
//! generated code alike.
//!
//! # The problem
//!
//! Every solution of `E x = b` is `x = x₀ + N λ`, `x₀ = E⁺ b` the minimal-norm one and `N`
//! an orthonormal basis of the null space. Validation guarantees that the null space
//! holds open-ended tendon directions only (motor torques and loop sides are the same in
//! every solution), so on the tendon tensions `T = T₀ + N λ`, with the columns of `N`
//! (restricted to the tendons) still orthonormal. The distribution is the `T` with
//!
//! > `floor_k ≤ T_k ≤ max_k` for every open-ended tendon, minimising `‖T − c‖²`,
//!
//! `c = 0` for the least-norm objective, `c = (floor + max) / 2` for the centered one.
//! Since `x₀ ⟂ N`, `Nᵀ T₀ = 0` and `‖T − c‖² = ‖T₀ − c‖² + ‖λ − λ*‖²` with
//! `λ* = Nᵀ c` (constant): the distribution is the **projection of `λ*` onto the
//! polytope** `{λ : floor ≤ T₀ + N λ ≤ max}` of dimension `d = dim null(E)`. It is unique
//! (a strictly convex objective) and continuous in `T₀` wherever the polytope is not
//! empty (a projection onto a continuously moving convex set).
//!
//! - `d = 1`, [`along_line`]: along the positive null vector `p` (every tendon component
//!   `> 0`), `T = T₀ + μ p`; each floor bounds `μ` from below and each maximum from
//!   above, so the answer is `μ* = pᵀc / pᵀp` clamped to the intersection of those
//!   intervals. It uses only [`Real::max`], so the code generator traces it.
//! - `d ≥ 2`, [`solve`]: the dual active-set method of Goldfarb and Idnani (1983) for a
//!   unit Hessian. It starts at the unconstrained optimum `λ*`, adds the most violated
//!   bound, and moves in the primal and dual spaces so that every bound in its active set
//!   stays satisfied with a non-negative multiplier, dropping a bound whose multiplier
//!   would turn negative. Each added bound strictly increases the objective of the
//!   current point, which is the optimum of the problem restricted to the active set, so
//!   no active set recurs and the method ends, exactly, after at most one step per active
//!   set of at most `d` independent bounds (and `d` drops per step): the iteration bound
//!   below is that count and can never stop a run that exact arithmetic would finish.
//!   When a violated bound's normal lies in the span of the active normals with no
//!   multiplier able to give way, the polytope is empty: the active bounds and the
//!   violated one form a Farkas certificate, returned to the caller to explain.
//!   It runs in two phases: the floors alone first, then, from their optimum, every
//!   bound (the method only ever adds violated bounds to an optimal point, so widening
//!   the set of candidates is sound, and the objective still increases at every added
//!   bound, so the count above bounds both phases together). The floors' optimum is the
//!   best effort below, so an infeasible state costs no second run.
//!
//! # When the bounds cannot be met
//!
//! Floors alone can always be met (the positive null vector lifts every tendon at once),
//! so an empty polytope is always a matter of maxima. The result is then
//! [`Status::MaxExceeded`] with a best effort that keeps every floor and delivers the
//! motion exactly:
//! - `d = 1`: `μ = max(μ_floor, min(μ_max, μ*)) = μ_floor`, the least lift that meets
//!   every floor (the tensions as low as the floors allow, so the maxima are exceeded as
//!   little as along `p` they can be; continuous across the boundary of feasibility);
//! - `d ≥ 2`: the same problem without the maxima (the distribution tendyn chose before
//!   maxima became constraints): the first phase's optimum.
//!
//! # Tolerances
//!
//! From the scalar's own round-off ([`Numeric::unit_roundoff`]), relative to the size of
//! the tensions and bounds involved: for `d ≥ 2` a bound counts as met when violated by
//! at most `4 (K + d) u · max(|T₀|, |floor|, |max|, |T|)`, and a new bound's normal as
//! independent of the active ones when its part outside their span exceeds `√u` of it;
//! for `d = 1`, see [`Status::of_line`].
//!
//! In a scalar of short precision (`f32`) the optimum found for `d ≥ 2` gets one step of
//! iterative refinement on its active set (`refine`): at vertices where bounds meet at
//! small angles the steps' round-off otherwise reaches a few hundred `u` of the tensions
//! (1.04e-5 measured, against 3.5e-6 with the step). `f64` keeps well within its promise
//! without it, and the test that chooses folds away.

// Index loops read like the algorithm over index sets.
#![allow(clippy::needless_range_loop)]

use crate::dual::Dual;
use crate::linalg::dot;
use crate::real::{Numeric, Real};

/// Whether a distribution meets every bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    /// The optimum: every tendon within its floor and maximum (to the scalar's round-off).
    Feasible,
    /// No tensions within the floors and maxima produce the motion. The tensions returned
    /// are a best effort: the motion exactly, every floor kept, some maximum exceeded (see
    /// the module documentation for which tensions exactly).
    MaxExceeded,
    /// The minimal-norm tensions were not finite, or the work buffers too small, or the
    /// method did not finish within the count of active sets that bounds it (which only
    /// round-off could cause; never seen in the test suite). The tensions returned are
    /// the minimal-norm ones, untouched.
    Unresolved,
}

impl Status {
    /// The status of a one-direction distribution from [`LineResult`]: `MaxExceeded` when
    /// the floors' lower bound on `μ` exceeds the maxima's upper bound by more than
    /// `4 (K + 1) u · scale` (in units of `μ`, the positive null vector scaled to a
    /// smallest component of 1: so a maximum may be exceeded by up to that times `p_k`);
    /// `Unresolved` for a non-finite excess or scale (non-finite inputs).
    pub fn of_line<T: Numeric>(excess: T, scale: T, tendons: usize) -> Status {
        if !(excess.is_finite() && scale.is_finite()) {
            return Status::Unresolved;
        }
        let tolerance = T::from_f64(tolerance_factor::<T>(tendons, 1)) * scale;
        if excess <= tolerance {
            Status::Feasible
        } else {
            Status::MaxExceeded
        }
    }
}

/// What the actuators must do: the result of a generated `actuation` function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Actuation<M, K> {
    /// One torque per motor, in file order (N·m).
    pub motor_torques: M,
    /// Ground-level tension of each open-ended tendon, in file order (N).
    pub tendon_tensions: K,
    /// Whether the tensions meet every floor and maximum.
    pub status: Status,
}

impl<M, K> Actuation<M, K> {
    /// Torques and tensions that are the unique solution, or already distributed without
    /// maxima to meet: [`Status::Feasible`].
    pub const fn exact(motor_torques: M, tendon_tensions: K) -> Self {
        Actuation {
            motor_torques,
            tendon_tensions,
            status: Status::Feasible,
        }
    }
}

impl<T: Numeric, const M: usize, const K: usize> Actuation<[T; M], [T; K]> {
    /// Tensions distributed by [`along_line`], with its excess and scale.
    pub fn along_line(motor_torques: [T; M], tendon_tensions: [T; K], excess: T, scale: T) -> Self {
        Actuation {
            motor_torques,
            tendon_tensions,
            status: Status::of_line(excess, scale, K),
        }
    }

    /// The minimal-norm tensions `t0` distributed by [`solve`] within `problem`'s bounds.
    #[inline(always)]
    pub fn bounded<const D: usize>(
        motor_torques: [T; M],
        t0: [T; K],
        problem: &Fixed<K, D>,
    ) -> Self {
        Self::distributed::<D, _>(motor_torques, t0, problem)
    }

    /// [`Actuation::bounded`] over a null space computed at the state ([`AtState`]: guides
    /// with capstan friction).
    #[inline(always)]
    pub fn bounded_at_state<const D: usize>(
        motor_torques: [T; M],
        t0: [T; K],
        problem: &AtState<T, K, D>,
    ) -> Self {
        Self::distributed::<D, _>(motor_torques, t0, problem)
    }

    /// [`Actuation::bounded`] with the tensions' derivatives along `J` directions, from the
    /// minimal-norm tensions' (`t0_tangents[j]`): `tangents[j][k] = ∂T_k` along direction
    /// `j` (see `Actuation::distributed_with_tangents`).
    #[inline(always)]
    pub fn bounded_with_tangents<const D: usize, const J: usize>(
        motor_torques: [T; M],
        t0: [T; K],
        t0_tangents: &[[T; K]; J],
        problem: &Fixed<K, D>,
    ) -> (Self, [[T; K]; J]) {
        Self::distributed_with_tangents::<D, J, _, _>(
            motor_torques,
            t0,
            t0_tangents,
            problem,
            true,
            |_| problem,
        )
    }

    /// [`Actuation::bounded_at_state`] with the tensions' derivatives along `J`
    /// directions, from the minimal-norm tensions' (`t0_tangents[j]`) and the state's
    /// problem's (`problem_tangents[j]`).
    #[inline(always)]
    pub fn bounded_at_state_with_tangents<const D: usize, const J: usize>(
        motor_torques: [T; M],
        t0: [T; K],
        t0_tangents: &[[T; K]; J],
        problem: &AtState<T, K, D>,
        problem_tangents: &[AtStateTangent<T, K, D>; J],
    ) -> (Self, [[T; K]; J]) {
        Self::distributed_with_tangents::<D, J, _, _>(
            motor_torques,
            t0,
            t0_tangents,
            problem,
            false,
            |j| problem.seeded(&problem_tangents[j]),
        )
    }

    /// `t0` distributed by [`solve`], with the derivatives along `J` directions of what it
    /// returns, `along(j)` the problem over dual numbers seeded along direction `j`; where
    /// its normals are constants (`constant_normals`) the factorisation of the active
    /// normals is the value's, taken as it is, else it is taken afresh over dual numbers
    /// for each direction. At a
    /// feasible optimum the active bounds hold nearby (a change of active set is where the
    /// derivative is one-sided; this takes the side of the set found), and the derivative
    /// is that of the solution on them: [`refine`]'s step over dual numbers, whose result
    /// is that solution whatever point it starts from (`λ = P⊥ λ* + Q R⁻ᵀ rhs`, `Q R` the
    /// active normals, `rhs` their bounds), so it starts from the optimum with no
    /// derivative. A best effort ([`Status::MaxExceeded`]) is the floors' optimum, the
    /// method's first phase: found again over the floors alone ([`FloorsOnly`]) for its
    /// active set, and differentiated the same way. Where the method did not finish
    /// ([`Status::Unresolved`]) it runs again over dual numbers per direction, which gives
    /// what [`Actuation::bounded`] over [`Dual`] would.
    #[inline(always)]
    fn distributed_with_tangents<
        const D: usize,
        const J: usize,
        P: Problem<T>,
        Q: Problem<Dual<T>>,
    >(
        motor_torques: [T; M],
        t0: [T; K],
        t0_tangents: &[[T; K]; J],
        problem: &P,
        constant_normals: bool,
        along: impl Fn(usize) -> Q,
    ) -> (Self, [[T; K]; J]) {
        let mut buffers = Buffers::<T, D>::new();
        let mut work = buffers.work();
        let mut tendon_tensions = [T::zero(); K];
        let (status, mut q) = solve_counted(problem, &t0, &mut work, &mut tendon_tensions, None);
        let differentiable = match status {
            Status::Feasible => true,
            Status::MaxExceeded => {
                let mut floors = [T::zero(); K];
                let floors_only = FloorsOnly(problem);
                let (found, count) = solve_counted(&floors_only, &t0, &mut work, &mut floors, None);
                q = count;
                found == Status::Feasible
            }
            Status::Unresolved => false,
        };
        // (Over the floors' active set no maximum is read.)
        let Buffers {
            lambda,
            basis,
            triangle,
            active,
            ..
        } = buffers;
        let active = &active[..q];
        let zero = Dual::constant(T::zero());
        let lift = |m: [[T; D]; D]| m.map(|row| row.map(Dual::constant));
        let (mut basis, mut triangle) = if constant_normals {
            (lift(basis), lift(triangle))
        } else {
            ([[zero; D]; D], [[zero; D]; D])
        };
        // Each direction's step starts from the optimum, with no derivative.
        let optimum = lambda.map(Dual::constant);
        let mut tangents = [[T::zero(); K]; J];
        for (j, out) in tangents.iter_mut().enumerate() {
            let p = along(j);
            let seeded: [Dual<T>; K] =
                core::array::from_fn(|k| Dual::new(t0[k], t0_tangents[j][k]));
            let mut t = [zero; K];
            if differentiable {
                if !constant_normals {
                    let (b, r) = (basis.as_flattened_mut(), triangle.as_flattened_mut());
                    factorize(&p, b, r, active, D, 0);
                }
                let mut lambda = optimum;
                let (mut y, mut delta) = ([zero; D], [zero; D]);
                refine(
                    &p,
                    &seeded,
                    &mut lambda,
                    basis.as_flattened(),
                    triangle.as_flattened(),
                    active,
                    &mut y,
                    &mut delta,
                );
                tensions_at(&p, &seeded, &lambda, &mut t);
            } else {
                t = Actuation::<[Dual<T>; 0], [Dual<T>; K]>::distributed::<D, _>([], seeded, &p)
                    .tendon_tensions;
            }
            *out = t.map(|x| x.tangent);
        }
        let actuation = Actuation {
            motor_torques,
            tendon_tensions,
            status,
        };
        (actuation, tangents)
    }

    /// `t0` distributed by [`solve`] over `D` directions, with work buffers on the stack.
    #[inline(always)]
    fn distributed<const D: usize, P: Problem<T>>(
        motor_torques: [T; M],
        t0: [T; K],
        problem: &P,
    ) -> Self {
        let mut buffers = Buffers::<T, D>::new();
        let mut tendon_tensions = [T::zero(); K];
        let status = solve(
            problem,
            &t0,
            &mut buffers.work(),
            &mut tendon_tensions,
            None,
        );
        Actuation {
            motor_torques,
            tendon_tensions,
            status,
        }
    }
}

/// [`Work`]'s buffers for `D` directions, on the stack (generated code's sizes are
/// constants, so the compiler sees them).
struct Buffers<T, const D: usize> {
    lambda: [T; D],
    basis: [[T; D]; D],
    triangle: [[T; D]; D],
    multipliers: [T; D],
    scratch: [[T; D]; 4],
    active: [usize; D],
}

impl<T: Real, const D: usize> Buffers<T, D> {
    #[inline(always)]
    fn new() -> Self {
        Buffers {
            lambda: [T::zero(); D],
            basis: [[T::zero(); D]; D],
            triangle: [[T::zero(); D]; D],
            multipliers: [T::zero(); D],
            scratch: [[T::zero(); D]; 4],
            active: [0; D],
        }
    }

    #[inline(always)]
    fn work(&mut self) -> Work<'_, T> {
        Work {
            lambda: &mut self.lambda,
            basis: self.basis.as_flattened_mut(),
            triangle: self.triangle.as_flattened_mut(),
            multipliers: &mut self.multipliers,
            scratch: self.scratch.as_flattened_mut(),
            active: &mut self.active,
        }
    }
}

// ---------------------------------------------------------------------------------------
// One null direction: closed form.

/// The data of a one-direction distribution: the positive null vector's tendon components
/// `p` (all `> 0`), the bounds, and the unconstrained optimum `μ* = pᵀc / pᵀp`.
pub struct Line<'a, T> {
    /// `p_k`: the positive null vector's component on each tendon (all `> 0`).
    pub direction: &'a [T],
    /// Each tendon's floor (N).
    pub floor: &'a [f64],
    /// Each tendon's maximum (N); `f64::INFINITY` where it has none.
    pub max: &'a [f64],
    /// `μ* = pᵀc / pᵀp`: the lift the objective alone would choose (0 for least norm).
    pub target: T,
}

/// What [`along_line`] found besides the tensions.
#[derive(Clone, Copy, Debug)]
pub struct LineResult<T> {
    /// `μ`: how far along `p` the tensions were moved.
    pub lift: T,
    /// `μ_floor − μ_max` (`> 0`: no `μ` meets every bound) and the size it is measured
    /// against (`max(|T₀|, floors, maxima)`), for [`Status::of_line`]; `None` when no
    /// tendon has a maximum (the floors can always be met).
    pub excess: Option<(T, T)>,
}

/// `T = T₀ + μ p` with `μ = max(μ_floor, min(μ_max, μ*))`, written into `t` (which holds
/// `T₀` on entry): `μ_floor = maxₖ (floor_k − T₀ₖ)/p_k`, `μ_max = minₖ (max_k − T₀ₖ)/p_k`.
/// Only [`Real::max`] decides, so a symbolic scalar traces it into straight-line code.
pub fn along_line<T: Real>(line: &Line<'_, T>, t: &mut [T]) -> LineResult<T> {
    // Slices of unequal lengths are cut to the shortest (never a panic).
    let k = [line.direction.len(), line.floor.len(), line.max.len()]
        .into_iter()
        .fold(t.len(), usize::min);
    let t = &mut t[..k];
    if k == 0 {
        return LineResult {
            lift: line.target,
            excess: None,
        };
    }
    let bounded: usize = line.max[..k].iter().filter(|m| m.is_finite()).count();
    let need = |k: usize, t: &[T]| (T::from_f64(line.floor[k]) - t[k]) / line.direction[k];
    let lift = if bounded == 0 {
        // μ = max(μ*, μ_floor), folded from μ* so that the least-norm case (μ* = 0) is
        // the plain chain max(0, need₀, need₁, …).
        (0..t.len()).fold(line.target, |mu, k| mu.max(need(k, t)))
    } else {
        // min(μ_max, μ*) = −max(maxₖ (T₀ₖ − max_k)/p_k, −μ*).
        let over = |k: usize| (t[k] - T::from_f64(line.max[k])) / line.direction[k];
        let mut maxima = (0..t.len()).filter(|&k| line.max[k].is_finite());
        let first = maxima.next().map(over).unwrap_or(line.target);
        let minus_mu_max = maxima.fold(first, |m, k| m.max(over(k)));
        let capped = -minus_mu_max.max(-line.target);
        let mu_floor = (1..t.len()).fold(need(0, t), |m, k| m.max(need(k, t)));
        let constants = line.floor[..k]
            .iter()
            .chain(line.max[..k].iter().filter(|m| m.is_finite()))
            .fold(0.0f64, |m, &x| m.max(x.abs()));
        let scale = t
            .iter()
            .fold(T::from_f64(constants), |m, &x| m.max(x).max(-x));
        let excess = mu_floor + minus_mu_max;
        let lift = capped.max(mu_floor);
        for (tk, pk) in t.iter_mut().zip(line.direction) {
            *tk = *tk + lift * *pk;
        }
        return LineResult {
            lift,
            excess: Some((excess, scale)),
        };
    };
    for (tk, pk) in t.iter_mut().zip(line.direction) {
        *tk = *tk + lift * *pk;
    }
    LineResult { lift, excess: None }
}

// ---------------------------------------------------------------------------------------
// Several null directions: the dual active-set method.

/// The constant data of a distribution over `d ≥ 1` null directions.
pub trait Problem<T> {
    /// `K`, the open-ended tendons.
    fn tendons(&self) -> usize;
    /// `d`, the null directions.
    fn directions(&self) -> usize;
    /// Component on tendon `k` of null direction `d` (orthonormal over the tendons).
    fn null(&self, d: usize, k: usize) -> T;
    /// The floor of tendon `k` (N).
    fn floor(&self, k: usize) -> f64;
    /// The maximum of tendon `k` (N); `f64::INFINITY` where it has none.
    fn max(&self, k: usize) -> f64;
    /// `λ*_d = Σₖ null(d, k) c_k`: the objective's optimum in null-space coordinates.
    fn target(&self, d: usize) -> T;
    /// `1 / |n_k|`, `n_k = (null(0, k), …, null(d − 1, k))` the normal of tendon `k`'s
    /// bounds ([`inverse_length`]): the first step of a run needs it, and it is a constant
    /// of the problem.
    fn inverse_length(&self, k: usize) -> T;
    /// How many facets of the minimal-norm tensions the bounds allow are known ([`Facet`]):
    /// none by default (a null space computed at the state has none at hand).
    fn facets(&self) -> usize {
        0
    }
    /// Facet `i < facets()`: its normal over the tendons (`‖w‖₁ = 1`) and its support.
    fn facet(&self, i: usize) -> (&[f64], f64) {
        let _ = i;
        (&[], f64::INFINITY)
    }
    /// The largest floor or finite maximum: the bounds' part of the size that round-off
    /// is measured against ([`solve`]'s tolerance).
    fn bound_size(&self) -> f64 {
        (0..self.tendons()).fold(0.0f64, |m, j| {
            let max = self.max(j);
            m.max(self.floor(j))
                .max(if max.is_finite() { max } else { 0.0 })
        })
    }
}

/// `1 / |n|` for the components of `n`: [`Problem::inverse_length`], computed the same way
/// wherever a problem is built (at run time or for generated code's constants).
pub fn inverse_length<T: Real>(components: impl IntoIterator<Item = T>) -> T {
    let square = components.into_iter().fold(T::zero(), |s, x| s + x * x);
    T::one() / square.sqrt()
}

impl<T, P: Problem<T>> Problem<T> for &P {
    fn tendons(&self) -> usize {
        (**self).tendons()
    }
    fn directions(&self) -> usize {
        (**self).directions()
    }
    fn null(&self, d: usize, k: usize) -> T {
        (**self).null(d, k)
    }
    fn floor(&self, k: usize) -> f64 {
        (**self).floor(k)
    }
    fn max(&self, k: usize) -> f64 {
        (**self).max(k)
    }
    fn target(&self, d: usize) -> T {
        (**self).target(d)
    }
    fn inverse_length(&self, k: usize) -> T {
        (**self).inverse_length(k)
    }
    fn bound_size(&self) -> f64 {
        (**self).bound_size()
    }
    fn facets(&self) -> usize {
        (**self).facets()
    }
    fn facet(&self, i: usize) -> (&[f64], f64) {
        (**self).facet(i)
    }
}

/// A problem with its maxima taken away: its floors' optimum is [`solve`]'s best effort
/// where the maxima cannot all be met, found by the same steps as the first phase of the
/// run over the whole problem (the size of round-off, which the maxima enter, is kept).
struct FloorsOnly<P>(P);

impl<T, P: Problem<T>> Problem<T> for FloorsOnly<P> {
    fn tendons(&self) -> usize {
        self.0.tendons()
    }
    fn directions(&self) -> usize {
        self.0.directions()
    }
    fn null(&self, d: usize, k: usize) -> T {
        self.0.null(d, k)
    }
    fn floor(&self, k: usize) -> f64 {
        self.0.floor(k)
    }
    fn max(&self, _: usize) -> f64 {
        f64::INFINITY
    }
    fn target(&self, d: usize) -> T {
        self.0.target(d)
    }
    fn inverse_length(&self, k: usize) -> T {
        self.0.inverse_length(k)
    }
    fn bound_size(&self) -> f64 {
        self.0.bound_size()
    }
}

/// A [`Problem`] of constants, as generated code holds it.
#[derive(Clone, Copy, Debug)]
pub struct Fixed<const K: usize, const D: usize> {
    /// `null[d][k]`.
    pub null: [[f64; K]; D],
    /// `floor[k]`, each tendon's floor (N).
    pub floor: [f64; K],
    /// Each tendon's maximum (N); `f64::INFINITY` where it has none.
    pub max: [f64; K],
    /// `λ*`: the objective's optimum in null-space coordinates (0 for least norm).
    pub target: [f64; D],
    /// `1 / |n_k|` of each tendon's normal ([`inverse_length`] of `null[·][k]`).
    pub inverse_length: [f64; K],
    /// Facets of the tensions the bounds allow, as normals over the tendons with `‖w‖₁ =
    /// 1` and their supports `max {wᵀT : floor ≤ T ≤ max}` (see [`Facet`]).
    pub facets: &'static [Facet<K>],
}

/// A facet of the set of minimal-norm tensions the bounds allow: `wᵀT₀ ≤ support` holds
/// wherever some tensions within the bounds produce the motion (`w ⟂ null`, so `wᵀT = wᵀT₀`
/// for every `T = T₀ + N λ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facet<const K: usize> {
    /// `w`, with `‖w‖₁ = 1`.
    pub normal: [f64; K],
    /// `max {wᵀT : floor ≤ T ≤ max}`.
    pub support: f64,
}

impl<T: Real, const K: usize, const D: usize> Problem<T> for Fixed<K, D> {
    fn facets(&self) -> usize {
        self.facets.len()
    }
    fn facet(&self, i: usize) -> (&[f64], f64) {
        (&self.facets[i].normal, self.facets[i].support)
    }
    fn tendons(&self) -> usize {
        K
    }
    fn directions(&self) -> usize {
        D
    }
    fn null(&self, d: usize, k: usize) -> T {
        T::from_f64(self.null[d][k])
    }
    fn floor(&self, k: usize) -> f64 {
        self.floor[k]
    }
    fn max(&self, k: usize) -> f64 {
        self.max[k]
    }
    fn target(&self, d: usize) -> T {
        T::from_f64(self.target[d])
    }
    fn inverse_length(&self, k: usize) -> T {
        T::from_f64(self.inverse_length[k])
    }
}

/// A [`Problem`] whose null space was computed at the state, as generated code holds it
/// where guides with capstan friction make `E` depend on the state: the bounds are
/// constants, the basis, the target and the normals' lengths are values of the state.
#[derive(Clone, Copy, Debug)]
pub struct AtState<T, const K: usize, const D: usize> {
    /// `null[d][k]`, orthonormal over the tendons.
    pub null: [[T; K]; D],
    /// `floor[k]`, each tendon's floor (N).
    pub floor: [f64; K],
    /// Each tendon's maximum (N); `f64::INFINITY` where it has none.
    pub max: [f64; K],
    /// `λ*_d = Σₖ null[d][k] c_k`: the objective's optimum in null-space coordinates.
    pub target: [T; D],
    /// `1 / |n_k|` of each tendon's normal ([`inverse_length`] of `null[·][k]`).
    pub inverse_length: [T; K],
}

/// The derivative of an [`AtState`] problem's state-dependent parts along one direction
/// (its bounds are constants).
#[derive(Clone, Copy, Debug)]
pub struct AtStateTangent<T, const K: usize, const D: usize> {
    /// `∂null[d][k]`.
    pub null: [[T; K]; D],
    /// `∂target[d]`.
    pub target: [T; D],
    /// `∂inverse_length[k]`.
    pub inverse_length: [T; K],
}

impl<T: Real, const K: usize, const D: usize> AtState<T, K, D> {
    /// The problem over dual numbers: these values, with the derivatives of the basis, the
    /// target and the normals' lengths along one direction from `tangent`.
    pub fn seeded(&self, tangent: &AtStateTangent<T, K, D>) -> AtState<Dual<T>, K, D> {
        let pair = |v: T, t: T| Dual::new(v, t);
        AtState {
            null: core::array::from_fn(|d| {
                core::array::from_fn(|k| pair(self.null[d][k], tangent.null[d][k]))
            }),
            floor: self.floor,
            max: self.max,
            target: core::array::from_fn(|d| pair(self.target[d], tangent.target[d])),
            inverse_length: core::array::from_fn(|k| {
                pair(self.inverse_length[k], tangent.inverse_length[k])
            }),
        }
    }
}

impl<T: Real, const K: usize, const D: usize> Problem<T> for AtState<T, K, D> {
    fn tendons(&self) -> usize {
        K
    }
    fn directions(&self) -> usize {
        D
    }
    fn null(&self, d: usize, k: usize) -> T {
        self.null[d][k]
    }
    fn floor(&self, k: usize) -> f64 {
        self.floor[k]
    }
    fn max(&self, k: usize) -> f64 {
        self.max[k]
    }
    fn target(&self, d: usize) -> T {
        self.target[d]
    }
    fn inverse_length(&self, k: usize) -> T {
        self.inverse_length[k]
    }
}

/// Work buffers of [`solve`] for `d` directions, borrowed so that the caller decides where
/// they live (the stack in generated code, the solver's workspace at run time).
pub struct Work<'a, T> {
    /// `d`: the current point.
    pub lambda: &'a mut [T],
    /// `d·d`: orthonormal basis of the active bounds' normals, column `j` at `j·d..`.
    pub basis: &'a mut [T],
    /// `d·d`: `R` of those normals (`normals = basis · R`), row-major, with the reciprocal
    /// of each diagonal entry in its place.
    pub triangle: &'a mut [T],
    /// `d`: multipliers of the active bounds.
    pub multipliers: &'a mut [T],
    /// `4·d`: the primal direction, its coordinates in the basis and in the active normals,
    /// and the floors' optimum (the best effort, should the maxima not be met).
    pub scratch: &'a mut [T],
    /// `d`: indices of the active bounds (`k` the floor of tendon `k`, `K + k` its maximum).
    pub active: &'a mut [usize],
}

impl<'a, T> Work<'a, T> {
    /// How many reals [`Work::split`] needs for `d` directions.
    pub const fn reals(d: usize) -> usize {
        6 * d + 2 * d * d
    }

    /// Work buffers for `d` directions carved from one buffer of reals (at least
    /// [`Work::reals`]`(d)`) and one of `d` indices; `None` if either is too short.
    pub fn split(reals: &'a mut [T], active: &'a mut [usize], d: usize) -> Option<Self> {
        if reals.len() < Self::reals(d) || active.len() < d {
            return None;
        }
        let (lambda, rest) = reals.split_at_mut(d);
        let (basis, rest) = rest.split_at_mut(d * d);
        let (triangle, rest) = rest.split_at_mut(d * d);
        let (multipliers, scratch) = rest.split_at_mut(d);
        Some(Work {
            lambda,
            basis,
            triangle,
            multipliers,
            scratch,
            active,
        })
    }

    fn fits(&self, d: usize) -> bool {
        self.lambda.len() >= d
            && self.basis.len() >= d * d
            && self.triangle.len() >= d * d
            && self.multipliers.len() >= d
            && self.scratch.len() >= 4 * d
            && self.active.len() >= d
    }
}

/// The distribution of the minimal-norm tensions `t0` within `problem`'s bounds, written
/// into `tensions`. On [`Status::MaxExceeded`], `certificate` (if given, `K` entries)
/// receives a vector `w` over the tendons with `max {wᵀT : floor ≤ T ≤ max} < wᵀT₀`:
/// along `w` the motion needs more than the bounded tendons can give. Entries `w_k > 0`
/// belong to tendons whose maximum blocks, `w_k < 0` to tendons whose floor does (in the
/// certificate `w`'s bounds are reached; the best effort returned keeps the floors only).
#[inline(always)]
pub fn solve<T: Numeric, P: Problem<T>>(
    problem: &P,
    t0: &[T],
    work: &mut Work<'_, T>,
    tensions: &mut [T],
    certificate: Option<&mut [T]>,
) -> Status {
    solve_counted(problem, t0, work, tensions, certificate).0
}

/// [`solve`], with the count of active bounds at a feasible optimum (0 otherwise): `work`
/// then holds the optimum `λ` and those bounds, first in `work.active`.
#[inline(always)]
fn solve_counted<T: Numeric, P: Problem<T>>(
    problem: &P,
    t0: &[T],
    work: &mut Work<'_, T>,
    tensions: &mut [T],
    certificate: Option<&mut [T]>,
) -> (Status, usize) {
    let (k, d) = (problem.tendons(), problem.directions());
    // Non-finite tensions (from a non-finite state, which generated code does not check)
    // have no distribution: say so at once rather than search.
    let finite = t0.iter().all(|x| x.is_finite());
    let short = certificate.as_ref().is_some_and(|c| c.len() < k);
    if t0.len() != k || tensions.len() != k || !work.fits(d) || !finite || short {
        // Copies what fits: a mismatch of lengths is reported, never a panic.
        for (t, x) in tensions.iter_mut().zip(t0) {
            *t = *x;
        }
        return (Status::Unresolved, 0);
    }
    let (status, active) = project(problem, t0, work, tensions, certificate);
    if status == Status::Unresolved {
        tensions.copy_from_slice(t0);
    }
    (status, active)
}

/// The normal of the first facet `p` knows ([`Problem::facets`]) that `t0` lies beyond by
/// more than `margin`: `wᵀT₀ − support > margin`, `‖w‖₁ = 1`.
#[inline(always)]
fn beyond_a_facet<'p, T: Numeric, P: Problem<T>>(
    p: &'p P,
    t0: &[T],
    margin: T,
) -> Option<&'p [f64]> {
    if short_precision::<T>() {
        return None;
    }
    (0..p.facets()).find_map(|i| {
        let (w, support) = p.facet(i);
        let along = t0.iter().zip(w).fold(T::from_f64(-support), |s, (t, w)| {
            T::from_f64(*w).mul_add(*t, s)
        });
        (along > margin).then_some(w)
    })
}

/// How many round-off allowances (`4 (K + d) u` times the largest tension or bound at the
/// floors' optimum) beyond a facet a state must lie for the facet to decide it (see
/// [`project`]): `2²⁴`, so that the steps would call it feasible only if their tensions
/// rose to `2²⁴` times everything at that point; in `f64` that leaves the states within
/// about `7e-8` of that size of a facet to the steps. In a scalar of short precision
/// (`f32`) as many allowances would be tens of times the tensions' size, so there no facet
/// decides anything ([`short_precision`]).
const FACET_MARGIN: f64 = (1u64 << 24) as f64;

/// `4 (K + d) u`: the bound violation that round-off allows, per unit of size.
fn tolerance_factor<T: Numeric>(tendons: usize, directions: usize) -> f64 {
    4.0 * (tendons + directions) as f64 * T::unit_roundoff()
}

/// The normal of bound `i` in null-space coordinates: `+null(·, k)` for a floor, `−` for a
/// maximum (bound `i` reads `normal · λ ≥ …`).
fn normal<T: Real, P: Problem<T>>(p: &P, i: usize, d: usize) -> T {
    let k = p.tendons();
    if i < k {
        p.null(d, i)
    } else {
        -p.null(d, i - k)
    }
}

/// Goldfarb-Idnani for `min ½‖λ − λ*‖²`, in two phases: over the floors alone, then over
/// the floors and the maxima, continuing from the first phase's optimum (the method only
/// ever adds violated bounds to an optimal pair, so a widened set of bounds is just more
/// candidates). The first phase's optimum is the best effort of [`Status::MaxExceeded`],
/// so an infeasible state costs no second run. Leaves the tensions in `t`, and where they
/// are feasible the optimum in `work` (`λ`, and its active bounds: how many is returned);
/// the caller has checked every length ([`solve`]).
///
/// Every buffer is cut to its exact length on entry, so that where the sizes are constants
/// (generated code's [`Fixed`]) the compiler sees them: the loops over `d` and `K` unroll
/// and need no bounds checks.
#[inline(always)]
fn project<T: Numeric, P: Problem<T>>(
    p: &P,
    t0: &[T],
    work: &mut Work<'_, T>,
    t: &mut [T],
    certificate: Option<&mut [T]>,
) -> (Status, usize) {
    let (k, d) = (p.tendons(), p.directions());
    let (t0, t) = (&t0[..k], &mut t[..k]);
    let lambda = &mut work.lambda[..d];
    let basis = &mut work.basis[..d * d];
    let triangle = &mut work.triangle[..d * d];
    let multipliers = &mut work.multipliers[..d];
    let active = &mut work.active[..d];
    let (z, rest) = work.scratch[..4 * d].split_at_mut(d);
    let (w, rest) = rest.split_at_mut(d);
    let (r, floors_only) = rest.split_at_mut(d);

    let mut with_max = false;
    // The bounds' part of the size is a constant of the problem (folded where it is one).
    let mut size = T::from_f64(p.bound_size());
    for x in t0.iter() {
        let x = x.abs();
        if x > size {
            size = x;
        }
    }
    let factor = T::from_f64(tolerance_factor::<T>(k, d));
    for i in 0..d {
        lambda[i] = p.target(i);
    }
    tensions_at(p, t0, lambda, t);
    let mut q = 0; // active bounds
                   // The guard of the module documentation, computed only once a run gets long.
    let mut steps = 0usize;
    let mut limit = 4 * (2 * k + 1);
    let mut limit_is_bound = false;
    loop {
        let (floor, threshold) = most_violated_floor(p, t, size, factor);
        // Before every floor is met only the floors compete; the maxima are looked at once
        // they are (to switch phases) and from then on.
        let max = if with_max || floor.is_none() {
            most_violated_max(p, t, threshold)
        } else {
            None
        };
        if !with_max && floor.is_none() && max.is_some() {
            // The floors are met: keep this point, the best effort should the maxima turn
            // out not to be, and go on with every bound.
            floors_only.copy_from_slice(lambda);
            with_max = true;
            // Where the problem knows the facets of the tensions its bounds allow (generated
            // code's constant null space), a state beyond one has none: the floors' optimum
            // is the best effort at once, without the steps that would show the maxima
            // empty (3.6 on average at the 3×6 benchmark's infeasible states). Beyond by
            // more than `FACET_MARGIN` round-off allowances, not one or two: the steps'
            // allowance grows with the largest tension they reach, and a tendon without a
            // maximum can rise far above every tension and bound at this point (a review
            // found 6.6× to 10⁵×); within it of a facet the steps could still call the
            // state feasible, to round-off, and so they decide it there.
            if let Some(w) = beyond_a_facet(p, t0, threshold * T::from_f64(-FACET_MARGIN)) {
                if let Some(c) = certificate {
                    for (c, w) in c.iter_mut().zip(w) {
                        *c = T::from_f64(*w);
                    }
                }
                tensions_at(p, t0, floors_only, t);
                return (Status::MaxExceeded, 0);
            }
        }
        let next = match (floor, max) {
            (Some(f), Some(m)) if with_max && m.1 < f.1 => Some(m),
            (None, m) if with_max => m,
            (f, _) => f,
        };
        let Some((add, mut violation)) = next else {
            if short_precision::<T>() {
                refine(p, t0, lambda, basis, triangle, &active[..q], z, w);
            }
            // The tensions afresh from λ: the steps' updates of `t` round at every step.
            tensions_at(p, t0, lambda, t);
            return (Status::Feasible, q);
        };
        let mut added_multiplier = T::zero();
        loop {
            steps += 1;
            if steps > limit {
                if limit_is_bound {
                    return (Status::Unresolved, 0);
                }
                let bounds = k + (0..k).filter(|&j| p.max(j).is_finite()).count();
                limit = iteration_bound(d, bounds);
                limit_is_bound = true;
            }
            // Dispatched on the count of active bounds, so that each copy of the step
            // knows it: its loops over the active set unroll and keep their values in
            // registers (up to three; beyond, one copy serves every count).
            let (step, z_norm2) = match q {
                0 => direction(p, add, violation, 0, basis, triangle, multipliers, z, w, r),
                1 => direction(p, add, violation, 1, basis, triangle, multipliers, z, w, r),
                2 => direction(p, add, violation, 2, basis, triangle, multipliers, z, w, r),
                3 => direction(p, add, violation, 3, basis, triangle, multipliers, z, w, r),
                _ => direction(p, add, violation, q, basis, triangle, multipliers, z, w, r),
            };
            match step {
                Step::Empty => {
                    // new normal = Σ r_j (active normal j) with every r_j ≤ 0: the bounds
                    // with multipliers μ_new = 1, μ_j = −r_j ≥ 0 cannot all hold (Farkas).
                    if let Some(c) = certificate {
                        for x in c.iter_mut() {
                            *x = T::zero();
                        }
                        // A multiplier on a floor lowers the certificate, on a maximum
                        // raises it.
                        let mut add_to = |i: usize, mu: T| {
                            if i < k {
                                c[i] = c[i] - mu;
                            } else {
                                c[i - k] = c[i - k] + mu;
                            }
                        };
                        add_to(add, T::one());
                        for j in 0..q {
                            add_to(active[j], -r[j]);
                        }
                    }
                    // Floors alone can always be met (the positive null vector lifts
                    // every tendon), so only the maxima can empty the set: the best
                    // effort is the floors' optimum.
                    if !with_max {
                        return (Status::Unresolved, 0);
                    }
                    tensions_at(p, t0, floors_only, t);
                    return (Status::MaxExceeded, 0);
                }
                Step::Full(s) => {
                    advance(p, s, z, lambda, t);
                    for j in 0..q {
                        multipliers[j] = multipliers[j] - s * r[j];
                    }
                    // The new column of the factorisation is already at hand: w and |z|
                    // (with no bound active, z is the new bound's normal, of known length).
                    let reciprocal = if q == 0 {
                        p.inverse_length(tendon_of(add, k))
                    } else {
                        T::one() / z_norm2.sqrt()
                    };
                    for j in 0..q {
                        triangle[j * d + q] = w[j];
                    }
                    triangle[q * d + q] = reciprocal;
                    let column = &mut basis[q * d..(q + 1) * d];
                    for i in 0..d {
                        column[i] = z[i] * reciprocal;
                    }
                    active[q] = add;
                    multipliers[q] = added_multiplier + s;
                    q += 1;
                    break;
                }
                Step::Partial { drop, t: s, primal } => {
                    // Bound `drop` leaves the active set, its multiplier having reached 0;
                    // then the same new bound is tried again.
                    if primal {
                        advance(p, s, z, lambda, t);
                    }
                    for j in 0..q {
                        multipliers[j] = multipliers[j] - s * r[j];
                    }
                    added_multiplier = added_multiplier + s;
                    for j in drop..q - 1 {
                        active[j] = active[j + 1];
                        multipliers[j] = multipliers[j + 1];
                    }
                    q -= 1;
                    // The columns before the dropped bound's are those of the bounds
                    // before it, unchanged: only the later ones are built anew.
                    factorize(p, basis, triangle, &active[..q], d, drop);
                    violation = slack(p, add, t);
                }
            }
        }
    }
}

/// The next step of the method for the violated bound `add` with `q` bounds active: the
/// primal direction `z` (the new normal's part outside the active normals' span), its
/// coordinates `w` in their orthonormal basis, `r = R⁻¹ w` (the dual direction), and which
/// step to take; with `|z|²`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn direction<T: Numeric, P: Problem<T>>(
    p: &P,
    add: usize,
    violation: T,
    q: usize,
    basis: &[T],
    triangle: &[T],
    multipliers: &[T],
    z: &mut [T],
    w: &mut [T],
    r: &mut [T],
) -> (Step<T>, T) {
    let d = z.len();
    // A new normal counts as independent of the active ones when its part outside their
    // span is more than √u of it: nearer to parallel, a full step would be longer than
    // 1/√u times the violation and its round-off would no longer be small against the
    // tensions (the normals themselves carry errors of u·cond(E)). Squared: u.
    let independent = T::from_f64(T::unit_roundoff());
    // z: the part of the new normal outside the active normals' span (the primal
    // direction); w: its coordinates in their orthonormal basis; r = R⁻¹ w, its
    // coordinates in the active normals (the dual direction).
    for i in 0..d {
        z[i] = normal(p, add, i);
    }
    let need = -violation;
    let need = if need > T::zero() { need } else { T::zero() };
    if q == 0 {
        // No bound active: z is the normal itself, whose length the problem holds, so the
        // step needs no dot product and no division. A zero normal (a tendon the null
        // space cannot move, which validation excludes) has no step.
        let inverse = p.inverse_length(tendon_of(add, p.tendons()));
        let step = if inverse.is_finite() {
            Step::Full(need * (inverse * inverse))
        } else {
            Step::Empty
        };
        return (step, T::zero());
    }
    let a_norm2 = dot(z, z);
    for j in 0..q {
        w[j] = T::zero();
    }
    // Gram-Schmidt against the active basis, repeated only when the first pass
    // cancelled more than half of the normal's square (the criterion of Daniel,
    // Gragg, Kaufman and Stewart, 1976): "twice is enough". After the first pass
    // `|z|² = |a|² − Σ c_j²` (the columns are orthonormal), which does not wait for `z`
    // and, short of that cancellation, loses nothing; after a second, it is taken afresh.
    let mut z_norm2 = a_norm2;
    for pass in 0..2 {
        let mut removed = T::zero();
        for (j, column) in basis.chunks_exact(d).take(q).enumerate() {
            let c = dot(column, z);
            w[j] = w[j] + c;
            removed = removed + c * c;
            for i in 0..d {
                z[i] = z[i] - c * column[i];
            }
        }
        if pass == 0 {
            z_norm2 = a_norm2 - removed;
            if z_norm2 + z_norm2 > a_norm2 {
                break;
            }
        } else {
            z_norm2 = dot(z, z);
        }
    }
    for i in (0..q).rev() {
        let row = &triangle[i * d..(i + 1) * d];
        let mut v = w[i];
        for j in i + 1..q {
            v = v - row[j] * r[j];
        }
        // The diagonal holds reciprocals (see `factorize`).
        r[i] = v * row[i];
    }
    // Full step: to where the new bound is met (never backwards, should round-off
    // have met it already). With `d` bounds active the new normal lies in their span.
    let full = (q < d && z_norm2 > independent * a_norm2).then(|| need / z_norm2);
    // Partial step: to where an active bound's multiplier reaches zero, the least
    // u_j / r_j over r_j > 0 (compared as u_j r_b < u_b r_j, one division in all).
    let mut first: Option<usize> = None;
    for j in 0..q {
        if r[j] > T::zero() && first.is_none_or(|b| multipliers[j] * r[b] < multipliers[b] * r[j]) {
            first = Some(j);
        }
    }
    let partial = first.map(|j| (j, multipliers[j] / r[j]));
    let step = match (full, partial) {
        (None, None) => Step::Empty,
        (Some(s), None) => Step::Full(s),
        (Some(s), Some((_, sp))) if s <= sp => Step::Full(s),
        (full, Some((drop, s))) => Step::Partial {
            drop,
            t: s,
            primal: full.is_some(),
        },
    };
    (step, z_norm2)
}

/// Whether `T` is a scalar of short precision (`u > 2⁻³⁰`, that is `f32`), where the
/// routine works differently (the test folds away):
/// - the optimum gets a step of [`refine`]: the steps' round-off at a vertex of nearly
///   parallel bounds reaches a few hundred `u` of the tensions, while in `f64` that
///   error is far below what the distribution promises;
/// - no facet decides a state: `FACET_MARGIN` allowances would exceed the tensions.
#[inline(always)]
fn short_precision<T: Numeric>() -> bool {
    T::unit_roundoff() > 1.0 / (1u64 << 30) as f64
}

/// One step of iterative refinement of the optimum on its active set: `λ` moves by `δ` so
/// that every active bound holds with zero slack (`Rᵀ y = −slack` in the active normals'
/// basis, `normals = basis · R`) and the part of `λ − λ*` outside their span vanishes
/// (stationarity: `λ − λ*` is a combination of the active normals). Slacks are computed
/// afresh from `λ`, not from the tensions the steps updated, so the step removes the
/// round-off the steps accumulated.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn refine<T: Numeric, P: Problem<T>>(
    p: &P,
    t0: &[T],
    lambda: &mut [T],
    basis: &[T],
    triangle: &[T],
    active: &[usize],
    y: &mut [T],
    delta: &mut [T],
) {
    let (k, d, q) = (t0.len(), lambda.len(), active.len());
    for j in 0..q {
        let bound = active[j];
        let tendon = tendon_of(bound, k);
        let t = (0..d).fold(t0[tendon], |s, i| s + p.null(i, tendon) * lambda[i]);
        // −slack: `floor − T` for a floor, `T − max` for a maximum.
        let mut v = if bound < k {
            T::from_f64(p.floor(tendon)) - t
        } else {
            t - T::from_f64(p.max(tendon))
        };
        for i in 0..j {
            v = v - triangle[i * d + j] * y[i];
        }
        // The diagonal holds reciprocals (see `factorize`).
        y[j] = v * triangle[j * d + j];
    }
    for i in 0..d {
        delta[i] = p.target(i) - lambda[i];
    }
    // λ* − λ with its part along each active basis column replaced by y_j.
    for (j, column) in basis.chunks_exact(d).take(q).enumerate() {
        let c = dot(column, delta);
        for i in 0..d {
            delta[i] = delta[i] + (y[j] - c) * column[i];
        }
    }
    for i in 0..d {
        lambda[i] = lambda[i] + delta[i];
    }
}

/// The tendon of bound `i` (`k` tendons): `i` for a floor, `i − k` for a maximum.
fn tendon_of(i: usize, k: usize) -> usize {
    if i < k {
        i
    } else {
        i - k
    }
}

/// The slack of bound `i` at tensions `t` (`≥ 0` when met).
fn slack<T: Real, P: Problem<T>>(p: &P, i: usize, t: &[T]) -> T {
    let k = t.len();
    if i < k {
        t[i] - T::from_f64(p.floor(i))
    } else {
        T::from_f64(p.max(i - k)) - t[i - k]
    }
}

/// The most violated floor at tensions `t` (bound index and slack), if violated by more
/// than round-off, with that round-off threshold (`−factor` times the largest of `size` and
/// every `|t_j|`, for [`most_violated_max`]); of equally violated floors the first.
///
/// One pass finds the least slack and the largest tension together: the least slack is
/// past the threshold exactly when some slack is, so the threshold can wait.
#[inline(always)]
fn most_violated_floor<T: Numeric, P: Problem<T>>(
    p: &P,
    t: &[T],
    size: T,
    factor: T,
) -> (Option<(usize, T)>, T) {
    // Two lanes (even and odd tendons), merged at the end: two independent chains of
    // compare-and-select halve the scan's latency, which every step of the method waits for.
    let mut largest = [size; 2];
    let mut floors = [(usize::MAX, T::zero()); 2];
    for (j, &tj) in t.iter().enumerate() {
        let x = tj.abs();
        if x > largest[j % 2] {
            largest[j % 2] = x;
        }
        let s = tj - T::from_f64(p.floor(j));
        if s < floors[j % 2].1 {
            floors[j % 2] = (j, s);
        }
    }
    let largest = if largest[1] > largest[0] {
        largest[1]
    } else {
        largest[0]
    };
    // Of equal slacks the earlier tendon, as one chain in tendon order would pick.
    let [even, odd] = floors;
    let floor = if odd.1 < even.1 || (odd.1 == even.1 && odd.0 < even.0) {
        odd
    } else {
        even
    };
    let threshold = -(factor * largest);
    ((floor.1 < threshold).then_some(floor), threshold)
}

/// The most violated maximum at tensions `t` (bound index `K + k` and slack), if violated
/// beyond `threshold`; of equally violated maxima the first.
#[inline(always)]
fn most_violated_max<T: Numeric, P: Problem<T>>(
    p: &P,
    t: &[T],
    threshold: T,
) -> Option<(usize, T)> {
    let k = t.len();
    let mut max = (usize::MAX, T::zero());
    for (j, &tj) in t.iter().enumerate() {
        let bound = p.max(j);
        if bound.is_finite() {
            let s = T::from_f64(bound) - tj;
            if s < max.1 {
                max = (k + j, s);
            }
        }
    }
    (max.1 < threshold).then_some(max)
}

/// `T = T₀ + N λ`, a row of `N` at a time (the inner loop runs over contiguous entries).
#[inline(always)]
fn tensions_at<T: Real, P: Problem<T>>(p: &P, t0: &[T], lambda: &[T], t: &mut [T]) {
    t.copy_from_slice(t0);
    for (i, l) in lambda.iter().enumerate() {
        for (j, tj) in t.iter_mut().enumerate() {
            *tj = *tj + p.null(i, j) * *l;
        }
    }
}

/// Moves `λ` by `s z`, and the tensions `t` with it, by `s (N z)`: `N z` does not wait for
/// the step's length `s` (a division), so only one product per tendon does.
#[inline(always)]
fn advance<T: Real, P: Problem<T>>(p: &P, s: T, z: &[T], lambda: &mut [T], t: &mut [T]) {
    for (l, zi) in lambda.iter_mut().zip(z) {
        *l = *l + s * *zi;
    }
    let Some((z0, rest)) = z.split_first() else {
        return;
    };
    for (j, tj) in t.iter_mut().enumerate() {
        let mut nz = p.null(0, j) * *z0;
        for (i, zi) in rest.iter().enumerate() {
            nz = nz + p.null(i + 1, j) * *zi;
        }
        *tj = *tj + s * nz;
    }
}

/// One step of the dual active-set method.
enum Step<T> {
    /// The bounds admit no point.
    Empty,
    /// Move by `t` along the primal direction; the new bound becomes active.
    Full(T),
    /// Move by `t` (in the primal space too if `primal`); bound `drop` leaves.
    Partial { drop: usize, t: T, primal: bool },
}

/// Gram-Schmidt, twice, of the `active` bounds' normals: `basis` (`d × d`, a column of `d`
/// at a time) and `triangle` (`R`, row-major, with the reciprocals of its diagonal on the
/// diagonal), from column `from` on (the columns before it already span the normals
/// before it: Gram-Schmidt builds each column from the earlier ones only).
#[inline(always)]
fn factorize<T: Numeric, P: Problem<T>>(
    p: &P,
    basis: &mut [T],
    triangle: &mut [T],
    active: &[usize],
    d: usize,
    from: usize,
) {
    let q = active.len();
    for j in from..q {
        let (done, rest) = basis.split_at_mut(j * d);
        let v = &mut rest[..d];
        for i in 0..d {
            v[i] = normal(p, active[j], i);
        }
        for i in 0..q {
            triangle[i * d + j] = T::zero();
        }
        for _pass in 0..2 {
            for (m, column) in done.chunks_exact(d).enumerate() {
                let w = dot(column, v);
                triangle[m * d + j] = triangle[m * d + j] + w;
                for i in 0..d {
                    v[i] = v[i] - w * column[i];
                }
            }
        }
        // The reciprocal of R's diagonal entry: back-substitution multiplies by it.
        let reciprocal = T::one() / dot(v, v).sqrt();
        triangle[j * d + j] = reciprocal;
        for x in v.iter_mut() {
            *x = *x * reciprocal;
        }
    }
}

/// `(d + 1) Σ_{s ≤ d} C(m, s)`: a step per active set of at most `d` of the `m` bounds,
/// each after at most `d` drops (saturating).
fn iteration_bound(d: usize, m: usize) -> usize {
    let mut sets: usize = 0;
    let mut choose: usize = 1; // C(m, s)
    for s in 0..=d.min(m) {
        sets = sets.saturating_add(choose);
        choose = if choose == usize::MAX {
            choose
        } else {
            choose.saturating_mul(m - s) / (s + 1)
        };
    }
    sets.saturating_mul(d + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One joint, three tendons: the null space of `A = [1, 1, −1]` (scaled) has the
    /// orthonormal basis below; every tension `(T₀ + N λ)` delivers the same torque.
    fn three_on_one(max: [f64; 3]) -> Fixed<3, 2> {
        let s2 = core::f64::consts::FRAC_1_SQRT_2;
        let s6 = 1.0 / 6.0f64.sqrt();
        Fixed {
            null: [[s2, 0.0, s2], [-s6, 2.0 * s6, s6]],
            floor: [1.0, 1.0, 1.0],
            max,
            target: [0.0, 0.0],
            inverse_length: [
                1.0 / (0.5 + 1.0 / 6.0f64).sqrt(),
                1.0 / (4.0 / 6.0f64).sqrt(),
                1.0 / (0.5 + 1.0 / 6.0f64).sqrt(),
            ],
            facets: &[],
        }
    }

    /// A state a few round-off allowances beyond a facet that the steps call feasible, to
    /// round-off, is left to them (a review's reproducer: tendon 2, which has no maximum,
    /// rises to 2,359 N, and the steps' allowance with it, while the facet's excess is
    /// 2.4e-12 against tensions of 264 N at the floors' optimum).
    #[test]
    fn a_state_within_the_steps_allowance_of_a_facet_is_theirs_to_decide() {
        use core::array::from_fn;
        let null = [
            [
                -0.0972390156742235,
                0.06083589232711231,
                0.9898619533169797,
                -0.0837668276286371,
            ],
            [
                -0.3632418561462206,
                0.9194797812560288,
                -0.08149900830052521,
                0.12637324657871363,
            ],
        ];
        let without = Fixed::<4, 2> {
            null,
            floor: [
                2.4151545549176445,
                4.09854442555112,
                3.3503393386239653,
                1.2163635301299032,
            ],
            max: [
                f64::INFINITY,
                66.27883691099393,
                f64::INFINITY,
                44.00436533405569,
            ],
            target: [-23.407739306292278, -3.4567150011464562],
            inverse_length: from_fn(|k| inverse_length((0..2).map(|d| null[d][k]))),
            facets: &[],
        };
        let facets: Vec<Facet<4>> = crate::tension::facets(&without)
            .into_iter()
            .map(|(w, support)| Facet {
                normal: from_fn(|k| w[k]),
                support,
            })
            .collect();
        let with = Fixed {
            facets: Vec::leak(facets),
            ..without
        };
        let t0 = [
            4639917473877081617u64,
            4629496646545927410,
            4630298538714497643,
            4643326834752384848,
        ]
        .map(f64::from_bits);
        let beyond = with.facets.iter().any(|f| dot(&f.normal, &t0) > f.support);
        assert!(beyond, "the state lies beyond a facet");
        let run = |p: &Fixed<4, 2>| {
            let mut buffers = Buffers::<f64, 2>::new();
            let mut t = [0.0; 4];
            let status = solve(p, &t0, &mut buffers.work(), &mut t, None);
            (status, t.map(f64::to_bits))
        };
        assert_eq!(run(&without).0, Status::Feasible);
        assert_eq!(run(&with), run(&without));
    }

    #[test]
    fn bad_lengths_and_non_finite_tensions_are_unresolved_never_a_panic() {
        let p = three_on_one([f64::INFINITY; 3]);
        let t0 = [f64::NAN, 1.0, 2.0];
        let a = Actuation::<[f64; 0], [f64; 3]>::bounded([], t0, &p);
        assert_eq!(a.status, Status::Unresolved);
        let mut work = Work::<f64> {
            lambda: &mut [],
            basis: &mut [],
            triangle: &mut [],
            multipliers: &mut [],
            scratch: &mut [],
            active: &mut [],
        };
        let mut out = [0.0; 3];
        assert_eq!(
            solve(&p, &[1.0, 2.0, 3.0], &mut work, &mut out, None),
            Status::Unresolved
        );
        assert_eq!(out, [1.0, 2.0, 3.0], "the minimal-norm tensions, untouched");
    }

    #[test]
    fn a_tendon_whose_maximum_equals_its_floor_is_held_there() {
        // T₀ = (1/3)(1, 1, −1)·τ with τ = 3: (1, 1, −1); T₂ fixed at 1 N.
        let p = three_on_one([f64::INFINITY, 1.0, f64::INFINITY]);
        let a = Actuation::<[f64; 0], [f64; 3]>::bounded([], [1.0, 1.0, -1.0], &p);
        assert_eq!(a.status, Status::Feasible);
        let t = a.tendon_tensions;
        assert!((t[1] - 1.0).abs() < 1e-14, "{t:?}");
        // The torque is kept: T₁ + T₂ − T₃ = 3.
        assert!((t[0] + t[1] - t[2] - 3.0).abs() < 1e-13, "{t:?}");
        assert!(t.iter().all(|&x| x >= 1.0 - 1e-14), "{t:?}");
    }

    /// The derivatives `bounded_with_tangents` returns are those of the tensions `bounded`
    /// returns: along the torque `τ` of `T₀ = (τ/3)(1, 1, −1)`, against central differences
    /// of `bounded` for `τ` over ±40 N·m with maxima 15, 30 and 20 N, at feasible optima
    /// (the active set's solution) and at best efforts (`MaxExceeded`: the floors' optimum,
    /// found again over the floors alone for its active set), away from a change of active
    /// set (where the one-sided differences part).
    #[test]
    fn the_tangents_are_the_derivatives_of_the_distribution() {
        let p = three_on_one([15.0, 30.0, 20.0]);
        let dt0 = [1.0 / 3.0, 1.0 / 3.0, -1.0 / 3.0];
        let at = |tau: f64| {
            let t0 = dt0.map(|x| x * tau);
            Actuation::<[f64; 0], [f64; 3]>::bounded_with_tangents([], t0, &[dt0], &p)
        };
        let h = 1e-5;
        let (mut feasible, mut exceeded) = (0, 0);
        for i in 0..800 {
            let tau = -40.0 + 0.1 * i as f64 + 0.0123;
            let (a, [tangent]) = at(tau);
            let (up, down) = (at(tau + h).0, at(tau - h).0);
            if up.status != a.status || down.status != a.status {
                continue;
            }
            let (mut kink, mut error) = (false, 0.0f64);
            for k in 0..3 {
                let forward = (up.tendon_tensions[k] - a.tendon_tensions[k]) / h;
                let backward = (a.tendon_tensions[k] - down.tendon_tensions[k]) / h;
                kink |= (forward - backward).abs() > 1e-6;
                error = error.max((0.5 * (forward + backward) - tangent[k]).abs());
            }
            if kink {
                continue;
            }
            assert!(error < 1e-8, "τ = {tau}: {tangent:?}, {:?}", a.status);
            match a.status {
                Status::Feasible => feasible += 1,
                Status::MaxExceeded => exceeded += 1,
                Status::Unresolved => panic!("τ = {tau}"),
            }
        }
        assert!(feasible > 100 && exceeded > 100, "{feasible}, {exceeded}");
    }

    #[test]
    fn the_iteration_bound_counts_active_sets() {
        // d = 2 of m = 4 bounds: 1 + 4 + 6 = 11 sets, each after at most 2 drops.
        assert_eq!(iteration_bound(2, 4), 33);
        assert_eq!(iteration_bound(40, 80), usize::MAX);
    }
}
