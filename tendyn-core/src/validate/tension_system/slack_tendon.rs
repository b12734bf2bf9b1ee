//! Every capstan factor at once, by the tensions of the runs: a linear program per tendon
//! asks whether any factor the guides can take lets that tendon go slack while the others
//! balance (with two or more null directions, the others solved from free tendons held in
//! one proportion: [`never_slack`]). Invariant: `Ok` only where no program finds such
//! tensions, which (below) leaves the routing controllable at every factor of the box.
//!
//! Take the tension of each run of each strand as an unknown `T_r` ([`Columns`]: a
//! strand's column of `E` is `Σ_r e^{Λ_r} a_r`, so `E x = Σ_r a_r T_r` with
//! `T_r = x e^{Λ_r}`). Across the guides between two consecutive runs the tension changes
//! by their factors `e^{λ_g}`, `|λ_g| ≤ μ β_g` ([`super::factor_boxes`] takes the same
//! box): for tensions that are not negative, the pair of linear constraints
//! `e^{−W} T_r ≤ T_{r+1} ≤ e^{W} T_r`, `W` the sum of those guides' `μ β_g`. The balances
//! `Σ_r a_r T_r = 0`, one per row of `E`, are linear too, with the model's constant
//! shares. So the tensions some factor of the box balances, none negative, form a
//! polyhedral cone, and a linear program finds in it, for a tendon `k`, a point with `k`'s
//! runs at zero, `Σ T = 1` and the motors' and loop sides' unknowns free, if there is one.
//!
//! Where there is none for any tendon, every factor of the box leaves `E` controllable. At
//! rest (the box's centre) it is, with a strictly positive null vector, and the states
//! where it is form an open set (a full-rank `E` keeps a one-dimensional null space that
//! moves continuously, and the motors' and loop sides' components vanish by `E`'s pattern,
//! [`Columns::always_singular`], checked by the caller). Were some factor to fail, the
//! segment from the centre to it would leave that set at a first factor `λ*`, where the
//! null vectors before it tend to one `x* ≥ 0`: either `x*` has a tendon at zero, or, all
//! taut, `E(λ*)` has lost rank and a second null vector moves `x*` until a first tendon
//! reaches zero. Either way the runs' tensions of that vector are a point the program for
//! that tendon finds. Conversely such a point is a factor of the box where a tendon is
//! slack or `E` has lost rank: the test is exact, up to the program's arithmetic.
//!
//! `microlp` answers `Infeasible` only where no point meets every constraint within its
//! feasibility tolerance (`1e-7`, absolute, on tensions that sum to 1): a point of the
//! exact cone, or one within round-off of it, is found, never missed. The box is widened
//! by [`WIDENED`] all the same.

use super::factor_boxes::Columns;
use super::Sliding;
use crate::model::Model;
use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome, Variable};

/// How much each interval of log factors between two runs is widened (absolute, in
/// nepers) against the round-off of `e^{±W}`: a margin far below any `μβ` that matters.
const WIDENED: f64 = 1e-9;

/// `Ok` where no factor of the box of every capstan factor the guides can take lets a
/// tendon of `tendons` go slack or `E` lose rank, by one linear program per tendon; `Err`
/// with the log factors of the first program's tensions where one finds some (a factor
/// where the routing fails, or one the program's tolerance cannot tell from it), `Err(None)`
/// where a program fails or a column other than a tendon's has runs.
///
/// With `free` tendons `N` held at ground-end tensions `x_N` (a fixed basis, two or more
/// null directions: [`super::every_factor_held`]), the question is whether the other
/// columns `B`, solved from `E_B x_B = −E_N x_N`, keep every tendon taut, and the programs
/// hold `N`'s first runs at `s x_N` (`s ≥ 0`, the tensions summing to 1). The path argument
/// is the same, for `x_B` and `det E_B`: at a first factor where it fails, a tendon of `B`
/// is at zero, or `E_B` is singular, where a null vector of `E_B` moves a bounded `x_B` to
/// a first zero, and an unbounded one tends (scaled) to a null vector of `E_B` with its
/// tendons not negative, which one more program looks for: `N`'s runs at zero, `B`'s
/// tendons summing to 1. There a factor found is one where that proportion fails, not
/// necessarily the routing.
pub(super) fn never_slack(
    model: &Model<f64>,
    sliding: &Sliding,
    columns: &Columns,
    tendons: &[usize],
    free: &[(usize, f64)],
) -> Result<(), Option<Vec<f64>>> {
    let count = model.system.matrix.first().map_or(0, Vec::len);
    if (0..count).any(|c| !tendons.contains(&c) && columns.runs(c).len() > 1) {
        return Err(None);
    }
    let is_free = |c: usize| free.iter().any(|n| n.0 == c);
    let solved = tendons.iter().filter(|&&k| !is_free(k)).map(|&k| Some(k));
    // `Some(k)`: tendon `k` slack; `None`: the free tendons (with a fixed basis).
    let mut programs = solved.chain((!free.is_empty()).then_some(None));
    let reach = sliding.reach(model);
    programs.try_for_each(|slack| slack_point(model, &reach, columns, tendons, free, slack))
}

/// Tensions of the runs with `slack` (a tendon, or with `None` the free tendons) at zero,
/// the other tendons not negative, every row of `E` balanced, consecutive runs within
/// their guides' factors, the free tendons' first runs in their proportion and every
/// tendon's runs summing to 1. `Ok` where the program proves there are none; `Err` with
/// the log factors of the tensions found ([`factors_of`]), or `None` where the program
/// fails.
fn slack_point(
    model: &Model<f64>,
    reach: &[f64],
    columns: &Columns,
    tendons: &[usize],
    free: &[(usize, f64)],
    slack: Option<usize>,
) -> Result<(), Option<Vec<f64>>> {
    let rows = model.system.matrix.len();
    let count = model.system.matrix.first().map_or(0, Vec::len);
    let held = |c: usize| free.iter().find(|n| n.0 == c).map(|n| n.1);
    let mut lp = Problem::new(OptimizationDirection::Minimize);
    // The free tendons' first runs are `s x_N` for a scale `s ≥ 0` (`s = 0` is the
    // program with the free tendons slack, or the limit of tensions unbounded at `s = 1`),
    // so that every program's tensions sum to 1 and none needs large values.
    let scale = lp.add_var(0.0, (0.0, f64::INFINITY));
    let mut balances: Vec<Vec<(Variable, f64)>> = vec![Vec::new(); rows];
    let mut total = Vec::new();
    let mut unknowns: Vec<Vec<Variable>> = Vec::with_capacity(count);
    for c in 0..count {
        let runs = columns.runs(c);
        let tendon = tendons.contains(&c);
        let at_zero = match slack {
            Some(k) => c == k,
            None => held(c).is_some(),
        };
        let bounds = match (tendon, at_zero) {
            (false, _) => (f64::NEG_INFINITY, f64::INFINITY),
            (true, true) => (0.0, 0.0),
            (true, false) => (0.0, f64::INFINITY),
        };
        let column: Vec<Variable> = runs.iter().map(|_| lp.add_var(0.0, bounds)).collect();
        if let (Some(x), false, Some(&first)) = (held(c), at_zero, column.first()) {
            lp.add_constraint([(first, 1.0), (scale, -x)], ComparisonOp::Eq, 0.0);
        }
        for (run, &t) in runs.iter().zip(&column) {
            for (i, &a) in run.share.iter().enumerate() {
                if a != 0.0 {
                    balances[i].push((t, a));
                }
            }
            if tendon {
                total.push((t, 1.0));
            }
        }
        // Consecutive runs: the guides below the second and not the first.
        for (pair, t) in runs.windows(2).zip(column.windows(2)) {
            let across = pair[1]
                .guides_after(&pair[0])
                .map(|g| reach[g])
                .sum::<f64>()
                + WIDENED;
            lp.add_constraint([(t[1], 1.0), (t[0], -across.exp())], ComparisonOp::Le, 0.0);
            lp.add_constraint(
                [(t[1], 1.0), (t[0], -(-across).exp())],
                ComparisonOp::Ge,
                0.0,
            );
        }
        unknowns.push(column);
    }
    for balance in balances.iter().filter(|b| !b.is_empty()) {
        lp.add_constraint(balance.as_slice(), ComparisonOp::Eq, 0.0);
    }
    lp.add_constraint(total.as_slice(), ComparisonOp::Eq, 1.0);
    match lp.solve() {
        Err(microlp::Error::Infeasible) => Ok(()),
        Ok(SolveOutcome::Solution(found)) => {
            let tensions: Vec<Vec<f64>> = (unknowns.iter())
                .map(|column| column.iter().map(|&t| found.var_value(t)).collect())
                .collect();
            Err(Some(factors_of(columns, &tensions, reach)))
        }
        _ => Err(None),
    }
}

/// The log factors `λ_g` a program's run tensions imply: across consecutive runs whose
/// tensions are both positive, the log of their ratio (within the interval's `±Σ μβ_g`)
/// shared among the guides between them in proportion to their `μβ_g`; `0` where no two
/// such runs tell.
fn factors_of(columns: &Columns, tensions: &[Vec<f64>], reach: &[f64]) -> Vec<f64> {
    let mut lambda = vec![0.0; reach.len()];
    for (c, column) in tensions.iter().enumerate() {
        let runs = columns.runs(c);
        for (pair, t) in runs.windows(2).zip(column.windows(2)) {
            let between: Vec<usize> = pair[1].guides_after(&pair[0]).collect();
            let width: f64 = between.iter().map(|&g| reach[g]).sum();
            if t[0] > 0.0 && t[1] > 0.0 && width > 0.0 {
                let log = (t[1] / t[0]).ln().clamp(-width, width);
                for &g in &between {
                    lambda[g] = log * reach[g] / width;
                }
            }
        }
    }
    lambda
}
