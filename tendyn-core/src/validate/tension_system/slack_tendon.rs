//! Every capstan factor at once, with one null direction, by the tensions of the runs: a
//! linear program per tendon asks whether any factor the guides can take lets that tendon
//! go slack while the others balance. Invariant: `true` only where no program finds such
//! tensions, which (below) leaves the routing controllable at every factor of the box.
//!
//! Take the tension of each run of each strand as an unknown `T_r` ([`Columns`]: a
//! strand's column of `E` is `Σ_r e^{Λ_r} a_r`, so `E x = Σ_r a_r T_r` with `T_r = x e^{Λ_r}`).
//! Across the guides between two consecutive runs the tension changes by their factors,
//! `e^{λ_g}` with `|λ_g| ≤ μ β_g` ([`super::factor_boxes`] takes the same box): for
//! tensions that are not negative that is the pair of linear constraints `e^{−W} T_r ≤
//! T_{r+1} ≤ e^{W} T_r`, `W` the sum of those guides' `μ β_g`. The balances `Σ_r a_r T_r =
//! 0`, one per row of `E`, are linear too, with the model's constant shares. So the
//! tensions some factor of the box balances, with every tendon at least slack, form a
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
use microlp::{ComparisonOp, OptimizationDirection, Problem, Variable};

/// How much each interval of log factors between two runs is widened (absolute, in
/// nepers) against the round-off of `e^{±W}`: a margin far below any `μβ` that matters.
const WIDENED: f64 = 1e-9;

/// Whether no factor of the box of every capstan factor the guides can take
/// lets a tendon of `tendons` go slack or `E` lose rank, by one linear program per tendon;
/// `false` where one finds such tensions (a factor where the routing fails, or one the
/// program's tolerance cannot tell from it), or a column other than a tendon's has runs.
pub(super) fn never_slack(
    model: &Model<f64>,
    sliding: &Sliding,
    columns: &Columns,
    tendons: &[usize],
) -> bool {
    let reach = sliding.reach(model);
    let rows = model.system.matrix.len();
    let count = model.system.matrix.first().map_or(0, Vec::len);
    if (0..count).any(|c| !tendons.contains(&c) && columns.runs(c).len() > 1) {
        return false;
    }
    tendons.iter().all(|&slack| {
        let mut lp = Problem::new(OptimizationDirection::Minimize);
        let mut balances: Vec<Vec<(Variable, f64)>> = vec![Vec::new(); rows];
        let mut total = Vec::new();
        for c in 0..count {
            let runs = columns.runs(c);
            let tendon = tendons.contains(&c);
            let bounds = match (tendon, c == slack) {
                (true, true) => (0.0, 0.0),
                (true, false) => (0.0, f64::INFINITY),
                (false, _) => (f64::NEG_INFINITY, f64::INFINITY),
            };
            let unknowns: Vec<Variable> = runs.iter().map(|_| lp.add_var(0.0, bounds)).collect();
            for (run, &t) in runs.iter().zip(&unknowns) {
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
            for (pair, t) in runs.windows(2).zip(unknowns.windows(2)) {
                let across = (pair[1].guides.iter())
                    .filter(|g| !pair[0].guides.contains(g))
                    .map(|&g| reach[g])
                    .sum::<f64>()
                    + WIDENED;
                lp.add_constraint([(t[1], 1.0), (t[0], -across.exp())], ComparisonOp::Le, 0.0);
                lp.add_constraint(
                    [(t[1], 1.0), (t[0], -(-across).exp())],
                    ComparisonOp::Ge,
                    0.0,
                );
            }
        }
        for balance in balances.iter().filter(|b| !b.is_empty()) {
            lp.add_constraint(balance.as_slice(), ComparisonOp::Eq, 0.0);
        }
        lp.add_constraint(total.as_slice(), ComparisonOp::Eq, 1.0);
        // Anything but a proof that there is no such point leaves it to the boxes.
        matches!(lp.solve(), Err(microlp::Error::Infeasible))
    })
}
