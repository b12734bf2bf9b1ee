//! Every capstan factor at once, where the directions of sliding are too many to take one
//! by one ([`super::EVERY_WAY_UP_TO`]): boxes of log capstan factors on which determinants
//! of square parts of `E` are shown to keep their sign. Invariant: `Some` only where the
//! check passes at every box's centre and no determinant asked for can vanish anywhere in
//! the box of every factor the guides can take.
//!
//! A guide's factor is `f_g = e^{λ_g}`, `λ_g = −σ μ β` with `|σ| ≤ 1` (the exact law's
//! `±1` and rest, the smoothed law's `tanh`) and `0 ≤ β ≤ β_g`, its largest wrap angle over
//! the joints' ranges: every state lies in the box `|λ_g| ≤ μ β_g`, whichever way anything
//! slides. A strand's column is `Σ_r e^{Λ_r} a_r` over its runs ([`crate::tension::runs`]),
//! `Λ_r` the sum of the `λ_g` of the guides between the ground end and run `r`.
//!
//! On a box with centre `c` and half-widths `h`, scale each varying column by `e^{−δ_ρ}`
//! (`δ_r = Λ_r(λ) − Λ_r(c)`, `ρ` one of its runs): no determinant changes sign, and the
//! column becomes `col(c) + Δ`, `Δ = Σ_r e^{Λ_r(c)} (e^{δ_r − δ_ρ} − 1) a_r`, where
//! `|δ_r − δ_ρ| ≤ |H_r − H_ρ|`, `H_r` the sum of `h_g` below run `r` (the runs' guides
//! are nested). A square part `M` of `E(c)` then becomes `M + Δ_M`, and
//! `det(M + Δ_M) = det M · det(I + M⁻¹ Δ_M)`: where `‖M⁻¹ Δ_M‖₁ < 1` the second factor never
//! vanishes on the (connected) box and is `1` at its centre, so it stays positive. The
//! 1-norm is the largest column sum, bounded column by column by
//! `min_ρ Σ_r e^{Λ_r(c)} (e^{|H_r − H_ρ|} − 1) ‖M⁻¹ a_r‖₁`; a box whose bound exceeds
//! [`SETTLED_BELOW`] is halved across its widest guide on the worst column.

use super::Sliding;
use crate::model::Model;
use crate::tension::{runs, state_matrix};
use nalgebra::{DMatrix, DVector};

/// The largest bound on `M⁻¹ Δ_M`'s spectral radius a box may have to be settled: below 1 by far more than
/// the round-off of `M`'s factorisation.
const SETTLED_BELOW: f64 = 0.9;

/// A square part of `E`: its rows and columns.
pub(crate) struct Square {
    pub(crate) rows: Vec<usize>,
    pub(crate) columns: Vec<usize>,
}

/// A strand whose column changes with the capstan factors: its unknown, and its runs from
/// the ground end, each as its share of the column and the sliders between the ground end
/// and it (those of the run before, and the one that ends that run).
struct Varying {
    column: usize,
    runs: Vec<(Vec<f64>, Vec<usize>)>,
}

/// A box of log capstan factors, one interval `[low, high]` per slider.
#[derive(Clone)]
struct FactorBox {
    low: Vec<f64>,
    high: Vec<f64>,
}

impl FactorBox {
    fn centre(&self, g: usize) -> f64 {
        0.5 * (self.low[g] + self.high[g])
    }

    fn half(&self, g: usize) -> f64 {
        0.5 * (self.high[g] - self.low[g])
    }
}

/// The number of boxes on which every capstan factor the guides can take is shown to pass
/// `fails` (at each box's centre) and to keep the sign of each of `squares`' determinants;
/// `None` where `budget` boxes do not settle it, or some centre fails or has a singular
/// square (a failure validation then looks for among the directions of sliding).
pub(super) fn every_factor(
    model: &Model<f64>,
    sliding: &Sliding,
    squares: &[Square],
    fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
    budget: usize,
) -> Option<usize> {
    let varying = varying_columns(model, sliding);
    let reach: Vec<f64> = (sliding.sliders.iter())
        .map(|s| sliding.guide(model, s).mu * s.wrap.max(0.0))
        .collect();
    let mut boxes = vec![FactorBox {
        low: reach.iter().map(|r| -r).collect(),
        high: reach,
    }];
    let mut explored = 0;
    while let Some(b) = boxes.pop() {
        explored += 1;
        if explored > budget {
            return None;
        }
        let mut capstan: Vec<Vec<f64>> = (model.strands.iter())
            .map(|s| vec![1.0; s.idlers.len()])
            .collect();
        for (g, slider) in sliding.sliders.iter().enumerate() {
            capstan[slider.strand][slider.idler] = b.centre(g).exp();
        }
        let e = state_matrix(model, &capstan);
        let mut worst: Option<(f64, usize)> = None;
        for square in squares {
            let (bound, column) = bound(&e, &b, square, &varying)?;
            if worst.is_none_or(|(w, _)| bound > w) {
                worst = Some((bound, column));
            }
        }
        if fails(e).is_some() {
            return None;
        }
        let Some((bound, column)) = worst else {
            continue;
        };
        if bound <= SETTLED_BELOW {
            continue;
        }
        // Halve the widest of the guides on the worst column (some has width: with none,
        // every `H_r` is zero and so is the bound).
        let (_, guides) = varying[column].runs.last()?;
        let widest = (guides.iter().copied()).max_by(|&x, &y| b.half(x).total_cmp(&b.half(y)))?;
        let middle = b.centre(widest);
        let (mut lower, mut upper) = (b.clone(), b);
        lower.high[widest] = middle;
        upper.low[widest] = middle;
        boxes.push(lower);
        boxes.push(upper);
    }
    Some(explored)
}

/// A bound on the spectral radius of `M⁻¹ Δ_M` over box `b` for `square` of `e` (`E` at
/// the box's centre), and the varying column that contributes most to it; `None` where `M`
/// is singular. `|M⁻¹ Δ_M|` is bounded entry by entry by `P`, each varying column's
/// `Σ_r e^{Λ_r(c)} (e^{|H_r − H_ρ|} − 1) |M⁻¹ a_r|` with the `ρ` of least sum; then
/// `ρ(M⁻¹ Δ_M) ≤ ρ(P) ≤ max_i (P x)_i / x_i` for any `x > 0` (Perron-Frobenius, Collatz-
/// Wielandt), `x` from a few steps of power iteration. Where `P` is nearly triangular, as
/// for a finger whose tendons end joint by joint, that is far below `P`'s norms.
fn bound(
    e: &[Vec<f64>],
    b: &FactorBox,
    square: &Square,
    varying: &[Varying],
) -> Option<(f64, usize)> {
    let k = square.rows.len();
    let lu = DMatrix::from_fn(k, k, |i, j| e[square.rows[i]][square.columns[j]]).lu();
    let det = lu.determinant();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let mut p = DMatrix::<f64>::zeros(k, k);
    let mut columns = Vec::new();
    for (v, column) in varying.iter().enumerate() {
        let Some(at) = square.columns.iter().position(|&c| c == column.column) else {
            continue;
        };
        // Each run's `e^{Λ_r(c)} |M⁻¹ a_r|` and `H_r`.
        let mut runs = Vec::with_capacity(column.runs.len());
        for (share, guides) in &column.runs {
            let a = DVector::from_fn(k, |i, _| share[square.rows[i]]);
            let centre: f64 = guides.iter().map(|&g| b.centre(g)).sum();
            let half: f64 = guides.iter().map(|&g| b.half(g)).sum();
            runs.push((lu.solve(&a)?.abs() * centre.exp(), half));
        }
        let with_reference = |reference: f64| {
            (runs.iter()).fold(DVector::zeros(k), |sum, (size, half)| {
                sum + size * (half - reference).abs().exp_m1()
            })
        };
        let best = (runs.iter())
            .map(|&(_, reference)| with_reference(reference))
            .min_by(|x, y| x.sum().total_cmp(&y.sum()))?;
        p.set_column(at, &best);
        columns.push((at, v));
    }
    if !p.iter().all(|x| x.is_finite()) {
        return Some((f64::INFINITY, columns.first()?.1));
    }
    // Power iteration from both sides, kept positive.
    let (mut x, mut y) = (DVector::from_element(k, 1.0), DVector::from_element(k, 1.0));
    for _ in 0..20 {
        x = (&p * &x).add_scalar(1e-30);
        y = (p.transpose() * &y).add_scalar(1e-30);
        x /= x.max();
        y /= y.max();
    }
    let px = &p * &x;
    let radius = (0..k).map(|i| px[i] / x[i]).fold(0.0, f64::max);
    // The column whose share `y_i P_ik x_k` of `yᵀ P x` is largest.
    let yp = p.transpose() * &y;
    let worst = (columns.iter()).max_by(|a, b| (yp[a.0] * x[a.0]).total_cmp(&(yp[b.0] * x[b.0])));
    Some((radius, worst.map_or(0, |w| w.1)))
}

/// The strands over guides with friction, their runs ([`crate::tension::runs`]) with the
/// sliders below each (a guide nothing slides over keeps the factor 1, and is left out).
fn varying_columns(model: &Model<f64>, sliding: &Sliding) -> Vec<Varying> {
    let rows = model.system.matrix.len();
    let slider_at = |s: usize, idler: usize| {
        (sliding.sliders.iter()).position(|x| x.strand == s && x.idler == idler)
    };
    let mut varying = Vec::new();
    for (s, strand) in model.strands.iter().enumerate() {
        if !strand.idlers.iter().any(|idler| idler.capstan().is_some()) {
            continue;
        }
        let mut below = Vec::new();
        let mut column = Vec::new();
        for run in runs(strand, rows) {
            column.push((run.share, below.clone()));
            below.extend(run.below.and_then(|idler| slider_at(s, idler)));
        }
        varying.push(Varying {
            column: strand.unknown,
            runs: column,
        });
    }
    varying
}

/// Whether the determinant of `square` vanishes at every capstan factor, by its pattern of
/// entries that are not always zero ([`without_transversal`]).
pub(super) fn always_singular(model: &Model<f64>, sliding: &Sliding, square: &Square) -> bool {
    let varying = varying_columns(model, sliding);
    let entry = |i: usize, c: usize| match varying.iter().find(|v| v.column == c) {
        Some(v) => v.runs.iter().any(|(share, _)| share[i] != 0.0),
        None => model.system.matrix[i][c] != 0.0,
    };
    without_transversal(square.rows.len(), &|i, j| {
        entry(square.rows[i], square.columns[j])
    })
}

/// Whether a `k × k` pattern of possibly nonzero entries has no assignment of its rows to
/// distinct columns through them (a maximum bipartite matching smaller than `k`, by
/// augmenting paths): then every term of the determinant's expansion has a zero factor,
/// whatever the entries' values.
fn without_transversal(k: usize, entry: &dyn Fn(usize, usize) -> bool) -> bool {
    fn augment(
        i: usize,
        seen: &mut [bool],
        matched: &mut [Option<usize>],
        entry: &dyn Fn(usize, usize) -> bool,
    ) -> bool {
        for j in 0..seen.len() {
            if entry(i, j) && !seen[j] {
                seen[j] = true;
                if matched[j].is_none_or(|other| augment(other, seen, matched, entry)) {
                    matched[j] = Some(i);
                    return true;
                }
            }
        }
        false
    }
    let mut matched: Vec<Option<usize>> = vec![None; k];
    let size = (0..k)
        .filter(|&i| augment(i, &mut vec![false; k], &mut matched, entry))
        .count();
    size < k
}

#[cfg(test)]
mod tests {
    use super::without_transversal;

    fn pattern<'a>(rows: &'a [&'a str]) -> impl Fn(usize, usize) -> bool + 'a {
        move |i, j| rows[i].as_bytes()[j] == b'x'
    }

    /// A determinant is zero by its pattern alone exactly where no rows-to-columns
    /// assignment runs through possibly nonzero entries: a zero row, or three rows whose
    /// entries lie in two columns, leave none; a permuted diagonal and a triangle have one,
    /// and so does `[xx, x.]`, found only by moving a match (row 1 takes column 0 from
    /// row 0, which moves on to column 1).
    #[test]
    fn a_pattern_is_singular_only_without_a_transversal() {
        assert!(without_transversal(3, &pattern(&["xx.", "...", "x.x"])));
        assert!(without_transversal(3, &pattern(&["xx.", "x..", ".x."])));
        assert!(!without_transversal(3, &pattern(&["..x", "x..", ".x."])));
        assert!(!without_transversal(3, &pattern(&["x..", "xx.", "xxx"])));
        assert!(!without_transversal(2, &pattern(&["xx", "x."])));
    }
}
