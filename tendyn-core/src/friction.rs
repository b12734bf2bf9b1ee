//! Friction in the transmission: Coulomb and viscous friction in the bearings between a
//! body (a link at its joint, or a pulley on its carrier) and its parent, and capstan
//! friction where a tendon slides over a fixed guide ([`capstan_factors`]). The paper's §2
//! leaves friction out ("may be added in the modeling where the force control is
//! important"); this is where it is added, once, for every scalar.
//!
//! # The law
//!
//! Body `b` turns relative to its parent at `ω_b = c_b · q̇` (its coupling: a unit row for
//! a link, the routing's ratios for a pulley, Eqs. 9-10, 26, 31, 34), with `α_b = c_b · q̈`.
//! Its bearing exerts on it, about its axis,
//!
//! > `τ_f = −(coulomb · s + viscous · ω_b)`
//!
//! and `−τ_f` on the parent. The direction `s`:
//!
//! - exact law: `sign(ω_b)` beyond [`REST`] of rest; within it (the bearing sticks, or is
//!   about to slip) the direction of impending motion, `sign(α_b)`, beyond [`REST`] too;
//!   else 0 (friction taken as zero). Written as the hook
//!   [`Real::sign_outside_or`]`(ω_b, REST, sign_outside(α_b, REST))`, so that generated
//!   code computes it with two selects and no arithmetic;
//! - smoothed (`friction_smoothing: v` in the file): `s = tanh(ω_b / v)` everywhere, for
//!   optimisation and derivatives.
//!
//! Forward dynamics does not know `α_b` before it solves for it: there the direction is
//! `sign(ω_b)` alone, so a bearing at rest contributes no friction (the result is then
//! exact only where no bearing is at rest; [`at_rest`] says which are).
//!
//! # Where it enters (virtual work)
//!
//! A friction torque is a pair of equal and opposite moments on a body and its parent
//! about their common axis; its virtual work is `τ_f δθ_b = τ_f c_b · δq`. So the
//! actuators must deliver `Q = M q̈ + h + g − Q_ext − Σ_b c_bᵀ τ_f,b` ([`apply`]),
//! and the balance rows of the tension system `E x = b` carry it where the body's axial
//! moment is balanced: a joint's row and a driving pulley's row (`tension::balance_rows`), an
//! idler's tension step (Eq. 24b with the bearing's moment, `tension::segment_tensions`).

use crate::kinematics::coupled;
use crate::model::Model;
use crate::real::{Numeric, Real};

/// The band of rest (rad/s, and rad/s² for the direction of impending motion): a bearing
/// turning slower than this is sticking. Far below any motion a controller commands and
/// far above the round-off of a rate computed from `q̇` of order one in `f32`.
///
/// The band is absolute: where couplings are large (a pulley turning 1e3 times faster than
/// its joint) or the scalar is `f32`, a rate that is zero in exact arithmetic can come out
/// of `c · q̇` as round-off of `u · Σ|c_j q̇_j|`; it stays inside the band while that is
/// below 1e-6 rad/s (in `f32`, for `Σ|c_j q̇_j|` up to about 16 rad/s).
pub const REST: f64 = 1e-6;

/// The direction friction opposes, `s` of the module documentation: from the rate and,
/// when `accel` is given, the acceleration (the direction of impending motion at rest).
pub fn direction<T: Real>(rate: T, accel: Option<T>, smoothing: Option<f64>) -> T {
    if let Some(v) = smoothing {
        return (rate / T::from_f64(v)).tanh();
    }
    by_direction(rate, accel, [T::one(), -T::one(), T::zero()])
}

/// What the exact law makes of three values, `[moving up, moving down, at rest]`: the
/// first where the rate is above the band of rest, the second where it is below, and
/// within it the same choice by `accel` (the impending motion), or the third without it
/// or where that is within the band too. [`direction`] is its choice among `±1` and `0`;
/// a guide of constant wrap angle makes its capstan factor `e^{−σμβ}` one among three
/// numbers with it ([`capstan_factors`]).
fn by_direction<T: Real>(rate: T, accel: Option<T>, [up, down, rest]: [T; 3]) -> T {
    let band = T::from_f64(REST);
    let within = match accel {
        Some(a) => a.select_outside(band, up, down, rest),
        None => rest,
    };
    rate.select_outside(band, up, down, within)
}

/// Body `b`'s bearing rate `ω_b = c_b · q̇` and the direction `s` its friction opposes
/// ([`direction`]; `qdd` as in [`bearing_torques`]).
pub fn rate_and_direction<T: Real>(
    model: &Model<T>,
    b: usize,
    qd: &[T],
    qdd: Option<&[T]>,
) -> (T, T) {
    let (body, joints) = (&model.bodies[b], &model.patterns[b].joints);
    let rate = coupled(&body.coupling, joints, qd);
    let accel = qdd.map(|a| coupled(&body.coupling, joints, a));
    (rate, direction(rate, accel, model.friction_smoothing))
}

/// `τ_f` of every body (0 where its bearing has no friction), written into `out` (one entry
/// per body). `qdd`: the accelerations of inverse dynamics, or `None` in forward dynamics.
pub fn bearing_torques<T: Real>(model: &Model<T>, qd: &[T], qdd: Option<&[T]>, out: &mut [T]) {
    for (b, (o, body)) in out.iter_mut().zip(&model.bodies).enumerate() {
        *o = match body.friction {
            None => T::zero(),
            Some(f) => {
                let (rate, s) = rate_and_direction(model, b, qd, qdd);
                -(T::from_f64(f.coulomb) * s + T::from_f64(f.viscous) * rate)
            }
        };
    }
}

/// The bearings' friction at `(q̇, q̈)` ([`bearing_torques`]) applied to `out` from `side`
/// ([`apply`]); nothing is computed without friction.
pub fn apply_at<T: Real>(model: &Model<T>, qd: &[T], qdd: Option<&[T]>, side: Side, out: &mut [T]) {
    if model.has_friction() {
        let mut torques = vec![T::zero(); model.bodies.len()];
        bearing_torques(model, qd, qdd, &mut torques);
        apply(model, &torques, side, out);
    }
}

/// How [`apply`] combines the generalized force of friction with what it is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// What the actuators must deliver: friction taken away, `Q − Σ_b c_bᵀ τ_f,b`.
    Delivered,
    /// What moves the mechanism: friction added, `rhs + Σ_b c_bᵀ τ_f,b`.
    Acting,
}

/// The generalized force of the bearings' friction, `Σ_b c_bᵀ τ_f,b` (virtual work: what
/// friction does to the joints), applied to `out` from `side`. Without friction `out` is
/// untouched, so a frictionless mechanism's traced code is what it was.
pub fn apply<T: Real>(model: &Model<T>, torques: &[T], side: Side, out: &mut [T]) {
    for (b, t) in model.bodies.iter().zip(torques) {
        if b.friction.is_some() {
            for (o, c) in out.iter_mut().zip(&b.coupling) {
                *o = match side {
                    Side::Delivered => *o - *c * *t,
                    Side::Acting => *o + *c * *t,
                };
            }
        }
    }
}

/// The capstan law of every guide with friction, into `out[s][k]` (strand `s`, idler `k`;
/// left as is where there is none): the ratio `T_k / T_{k+1}` of the tensions on the
/// guide's anchor and ground sides, `e^{−σ μ β(q)}`.
///
/// The tendon slides over the guide at `v = Σ_j slide_j q̇_j`, positive towards the
/// strand's ground end; the side it slides towards pulls, so there the tension is higher
/// by `e^{μβ}` (Euler-Eytelwein). `σ` is [`direction`] of `v` (with `Σ_j slide_j q̈_j`,
/// the direction of impending motion, at rest; `tanh` when the file smooths friction), so
/// `σ = 0` (no friction) where both are within [`REST`]. `β(q) = wrap + Σ_j wrap_rate_j
/// q_j`, taken as 0 where it turns negative: a tendon bending away from a guide does not
/// touch it.
pub fn capstan_factors<T: Real>(
    model: &Model<T>,
    q: &[T],
    qd: &[T],
    qdd: Option<&[T]>,
    out: &mut [Vec<T>],
) {
    for (strand, factors) in model.strands.iter().zip(out.iter_mut()) {
        for (idler, factor) in strand.idlers.iter().zip(factors.iter_mut()) {
            let Some(guide) = idler.capstan() else {
                continue;
            };
            let (slide, accel) = (guide.speed(qd), qdd.map(|a| guide.speed(a)));
            // A constant wrap angle under the exact law: the factor is one of three
            // numbers, `e^{∓μβ}` or 1, chosen by the direction (folded at generation).
            let mu = T::from_f64(guide.mu);
            if model.friction_smoothing.is_none() && guide.wrap_is_constant() {
                let towards_exit = capstan_factor(-mu, T::from_f64(guide.wrap));
                let towards_anchor = T::one() / towards_exit;
                *factor = by_direction(slide, accel, [towards_exit, towards_anchor, T::one()]);
                continue;
            }
            // `−σ μ`: under the exact law chosen among `∓μ` and 0 as the direction is (a
            // select whose numbers carry the law's sign and `μ` from generation).
            let per_radian = match model.friction_smoothing {
                None => by_direction(slide, accel, [-mu, mu, T::zero()]),
                smoothing => -(direction(slide, accel, smoothing) * mu),
            };
            let wrap = guide.wrap_at(q);
            *factor = capstan_factor(per_radian, wrap);
        }
    }
}

/// A guide's capstan law, the ratio `T_k / T_{k+1} = e^{−σ μ β}` of the tensions on its
/// anchor and ground sides (`per_radian` is `−σ μ`, the log of the factor per radian of
/// wrap), with `β` taken as 0 where it turns negative: a tendon bending away from a guide
/// does not touch it.
pub fn capstan_factor<T: Real>(per_radian: T, wrap: T) -> T {
    capstan_log_factor(per_radian, wrap).exp()
}

/// The log of [`capstan_factor`], `−σ μ β` (`β ≥ 0`, `per_radian` is `−σ μ`):
/// validation's boxes of factors are boxes of these.
pub(crate) fn capstan_log_factor<T: Real>(per_radian: T, wrap: T) -> T {
    per_radian * wrap.max(T::zero())
}

/// The bodies whose bearing has friction and turns within [`REST`] of rest: with the exact
/// law, friction there is the direction of impending motion (or zero), not a sliding one.
/// Empty with the smoothed law, which has no such band.
pub fn at_rest<T: Numeric>(model: &Model<T>, qd: &[T]) -> Vec<usize> {
    if model.friction_smoothing.is_some() {
        return Vec::new();
    }
    model
        .bodies
        .iter()
        .enumerate()
        .filter(|&(i, b)| {
            b.friction.is_some()
                && coupled(&b.coupling, &model.patterns[i].joints, qd).abs() <= T::from_f64(REST)
        })
        .map(|(i, _)| i)
        .collect()
}

/// Where forward dynamics, which does not know `q̈`, takes friction as none at `(q, q̇)`
/// though the exact law would give it the direction of the impending motion: the bodies
/// whose bearing has Coulomb friction, and the guides with friction (each as `(strand,
/// place on it)`) that touch their tendon (`β(q) > 0`), within [`REST`] of rest. Its
/// result is exact only where both are empty (docs/outputs.md §5); both are empty with
/// the smoothed law, which has no such band. (Viscous friction vanishes at rest whatever
/// the direction.)
pub fn forward_at_rest(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
) -> (Vec<usize>, Vec<(usize, usize)>) {
    let bearings = (at_rest(model, qd).into_iter())
        .filter(|&b| model.bodies[b].friction.is_some_and(|f| f.coulomb > 0.0))
        .collect();
    let guides = (model.guides())
        .filter(|(_, _, _, g)| sticks(model, g, g.speed(qd)) && g.wrap_at(q) > 0.0)
        .map(|(s, k, _, _)| (s, k))
        .collect();
    (bearings, guides)
}

/// Whether a guide whose tendon slides at `v` (m/s) sticks: it has friction and the exact
/// law finds it within [`REST`] of rest.
fn sticks(model: &Model<f64>, g: &crate::model::Guide, v: f64) -> bool {
    g.mu > 0.0 && model.friction_smoothing.is_none() && v.abs() <= REST
}

/// What a fixed guide does at a state: the `guides` of `tendyn eval --json` and of the
/// Python package's inverse dynamics (docs/outputs.md).
#[derive(Clone, Debug, PartialEq)]
pub struct GuideState {
    /// The strand that passes the guide, and the guide's place on it
    /// (`model.strands()[strand].idlers[idler]`).
    pub strand: usize,
    /// See `strand`.
    pub idler: usize,
    /// The guide's body.
    pub body: usize,
    /// `β(q)` (rad), [`crate::model::Guide::wrap_at`]: negative where the tendon bends away
    /// from it.
    pub wrap_angle: f64,
    /// The tendon's speed over it (m/s), positive towards the strand's ground end.
    pub sliding_speed: f64,
    /// The direction the capstan law takes ([`direction`]): of sliding, or at rest of the
    /// impending motion (`±1` or `0`; in `(−1, 1)` with `friction_smoothing`).
    pub direction: f64,
    /// A guide with friction that the exact law finds within [`REST`] of rest.
    pub sticking: bool,
    /// `(T_{k+1} − T_k) v` (W), the tension gained across it towards the ground end times
    /// the sliding speed: the power friction takes from the tendon there (`0` when
    /// frictionless). `None` without segment tensions (an incomplete routing).
    pub dissipated_power: Option<f64>,
}

/// Every guide of `model` (strand by strand, in route order) at `(q, q̇, q̈)`, its power
/// from the state's `segment_tensions` (`[strand][segment]`, as inverse dynamics gives
/// them).
pub fn guide_states(
    model: &Model<f64>,
    [q, qd, qdd]: [&[f64]; 3],
    segment_tensions: Option<&[Vec<f64>]>,
) -> Vec<GuideState> {
    (model.guides())
        .map(|(s, k, body, g)| {
            let v = g.speed(qd);
            let accel = g.speed(qdd);
            GuideState {
                strand: s,
                idler: k,
                body,
                wrap_angle: g.wrap_at(q),
                sliding_speed: v,
                direction: direction(v, Some(accel), model.friction_smoothing),
                sticking: sticks(model, g, v),
                dissipated_power: segment_tensions.map(|t| (t[s][k + 1] - t[s][k]) * v),
            }
        })
        .collect()
}
