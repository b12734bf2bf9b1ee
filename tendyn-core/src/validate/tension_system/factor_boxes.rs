//! Every capstan factor at once: boxes of log capstan factors on which determinants of
//! square parts of `E` are shown to keep their sign, for routings whose directions of
//! sliding are too many to take one by one ([`super::EVERY_WAY_UP_TO`]), and before them
//! for the others. Invariant: `Some` only where the check passes at every box's centre
//! and no determinant asked for can vanish anywhere in the box of every factor the guides
//! can take.
//!
//! A guide's factor is `f_g = e^{λ_g}`, `λ_g = −σ μ β` with `|σ| ≤ 1` (the exact law's
//! `±1` and rest, the smoothed law's `tanh`) and `0 ≤ β ≤ β_g`, its largest wrap angle over
//! the joints' ranges: every state lies in the box `|λ_g| ≤ μ β_g`, whichever way anything
//! slides. A strand's column of `E` is `Σ_r e^{Λ_r} a_r` over its runs
//! ([`crate::tension::for_each_run`]), `Λ_r` the sum of the `λ_g` of the guides `G_r` between the
//! ground end and run `r`; a column of a square part may also be a fixed combination of
//! columns of `E`, whose runs are theirs, scaled.
//!
//! On a box with centre `c` and half-widths `h`, scale a column by `e^{−δ_ρ}` (`δ_r =
//! Λ_r(λ) − Λ_r(c)`, `ρ` one of its runs): no determinant changes sign, and the column
//! becomes `col(c) + Δ`, `Δ = Σ_r e^{Λ_r(c)} (e^{δ_r − δ_ρ} − 1) a_r`, with `|δ_r − δ_ρ|`
//! at most `H(G_r △ G_ρ)`, the sum of `h_g` over the guides below one run and not the other.
//! A square part `M` of `E(c)` becomes `M + Δ_M`, and `det(M + Δ_M) = det M · det(I + M⁻¹
//! Δ_M)`: where the spectral radius of `M⁻¹ Δ_M` stays below 1 the second factor never
//! vanishes on the (connected) box and is `1` at its centre, so it stays positive. Entry by
//! entry `|M⁻¹ Δ_M| ≤ P`, each column `Σ_r e^{Λ_r(c)} (e^{H(G_r △ G_ρ)} − 1) |M⁻¹ a_r|`
//! with the `ρ` of least sum, and `ρ(M⁻¹ Δ_M) ≤ ρ(P) ≤ max_i (P x)_i / x_i` for any `x > 0`
//! (Perron-Frobenius, Collatz-Wielandt), `x` from a few steps of power iteration: where `P`
//! is nearly triangular, as for a finger whose tendons end joint by joint, far below `P`'s
//! norms. Where a box's bound exceeds [`SETTLED_BELOW`], the guide that weighs most on the
//! column that contributes most is fixed at each end of its interval in turn, two boxes
//! with one guide fewer: every determinant asked for is affine in each factor taken alone
//! (a guide's factor multiplies the runs on the anchor side of it, all in its strand's one
//! column, and no column of `E` enters a square twice), so where it keeps its sign at both
//! ends it keeps it in between. At worst that is every vertex of the box, `2^sliders`.
//!
//! The determinants, `M⁻¹ a_r` and the bound are computed in floating point, without an
//! error bound of their own: the margin below 1 ([`SETTLED_BELOW`]) stands for the
//! round-off of a well-conditioned `M`, and the runtime solver checks each state's system
//! all the same.

use super::Sliding;
use crate::model::{Model, Row};
use crate::tension::for_each_run;
use nalgebra::{DMatrix, DVector};

/// The largest bound on `M⁻¹ Δ_M`'s spectral radius a box may have to be settled: below 1
/// by far more than the round-off of `M`'s factorisation.
const SETTLED_BELOW: f64 = 0.9;

/// A square part of `E`: its rows, and its columns, each a combination
/// `Σ coefficient · (column of E)`.
pub(crate) struct Square {
    pub(crate) rows: Vec<usize>,
    pub(crate) columns: Vec<Vec<(usize, f64)>>,
}

impl Square {
    /// The part of `E` in `rows` and `columns`.
    pub(crate) fn of(rows: &[usize], columns: &[usize]) -> Square {
        Square {
            rows: rows.to_vec(),
            columns: columns.iter().map(|&c| vec![(c, 1.0)]).collect(),
        }
    }
}

/// A run of a column of `E`: its share of the column, and the sliders between it and its
/// strand's ground end, in increasing order (none for a column that friction leaves as it
/// is).
#[derive(Clone)]
pub(super) struct Run {
    pub(super) share: Vec<f64>,
    pub(super) guides: Vec<usize>,
}

impl Run {
    /// The sliders between `previous`, the run before it towards the ground end, and this
    /// one: those below this run and not below `previous`.
    pub(super) fn guides_after<'a>(
        &'a self,
        previous: &'a Run,
    ) -> impl Iterator<Item = usize> + 'a {
        (self.guides.iter())
            .filter(|g| !previous.guides.contains(g))
            .copied()
    }
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

    /// `H(a △ b)`: the half-widths of the guides in one of two increasing lists and not
    /// the other.
    fn apart(&self, a: &[usize], b: &[usize]) -> f64 {
        let (mut i, mut j, mut sum) = (0, 0, 0.0);
        loop {
            match (a.get(i), b.get(j)) {
                (None, None) => return sum,
                (Some(x), Some(y)) if x == y => (i, j) = (i + 1, j + 1),
                (Some(&x), Some(&y)) if x < y => (sum, i) = (sum + self.half(x), i + 1),
                (Some(&x), None) => (sum, i) = (sum + self.half(x), i + 1),
                (_, Some(&y)) => (sum, j) = (sum + self.half(y), j + 1),
            }
        }
    }
}

/// The number of boxes on which every capstan factor the guides can take is shown to pass
/// `fails` (at each box's centre) and to keep the sign of each of `squares`' determinants;
/// `Err` with the boxes taken where `budget` boxes do not settle it, or some centre fails
/// or has a singular square (a failure validation then looks for among the directions of
/// sliding).
pub(super) fn every_factor(
    model: &Model<f64>,
    sliding: &Sliding,
    columns: &Columns,
    squares: &[Square],
    fails: &dyn Fn(Vec<Vec<f64>>) -> Option<String>,
    budget: usize,
) -> Result<usize, usize> {
    let squares: Vec<(&Square, Vec<Vec<Run>>)> = (squares.iter())
        .map(|square| (square, columns.of_square(square)))
        .collect();
    let reach = sliding.reach(model);
    let mut boxes = vec![FactorBox {
        low: reach.iter().map(|r| -r).collect(),
        high: reach,
    }];
    let mut explored = 0;
    while let Some(b) = boxes.pop() {
        explored += 1;
        if explored > budget {
            return Err(budget);
        }
        let centre: Vec<f64> = (0..sliding.sliders.len()).map(|g| b.centre(g)).collect();
        let e = sliding.matrix_with_factors(model, &centre);
        let mut worst: Option<(f64, Option<usize>)> = None;
        for (square, runs) in &squares {
            let (bound, guide) = bound(&e, &b, square, runs).ok_or(explored)?;
            if worst.is_none_or(|(w, _)| bound > w) {
                worst = Some((bound, guide));
            }
        }
        if fails(e).is_some() {
            return Err(explored);
        }
        let Some((_, guide)) = worst.filter(|w| w.0 > SETTLED_BELOW) else {
            continue;
        };
        // Fix the guide that weighs most in the worst square at each end (one has some
        // width: without, the bound is zero).
        let guide = guide.ok_or(explored)?;
        let (mut lower, mut upper) = (b.clone(), b);
        lower.high[guide] = lower.low[guide];
        upper.low[guide] = upper.high[guide];
        boxes.push(lower);
        boxes.push(upper);
    }
    Ok(explored)
}

/// A bound on the spectral radius of `M⁻¹ Δ_M` over box `b` for `square` of `e` (`E` at
/// the box's centre), whose columns have `runs`, and the guide to fix where it is too
/// large: on the column that contributes most, the one whose half-width times the runs it
/// sets apart from the reference (`Σ e^{Λ_r(c)} ‖M⁻¹ a_r‖₁` over the runs on its other
/// side) is largest. `None` where `M` is singular.
fn bound(
    e: &[Vec<f64>],
    b: &FactorBox,
    square: &Square,
    runs: &[Vec<Run>],
) -> Option<(f64, Option<usize>)> {
    let k = square.rows.len();
    let m = DMatrix::from_fn(k, k, |i, j| {
        (square.columns[j].iter()).fold(0.0, |sum, &(c, x)| sum + x * e[square.rows[i]][c])
    });
    let lu = m.lu();
    let det = lu.determinant();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    // Every run of every column friction moves, solved at once: `M⁻¹ a_r`.
    let moved: Vec<(usize, &Run)> = (runs.iter().enumerate())
        .filter(|(_, column)| column.iter().any(|r| !r.guides.is_empty()))
        .flat_map(|(j, column)| column.iter().map(move |run| (j, run)))
        .collect();
    let shares = DMatrix::from_fn(k, moved.len(), |i, r| moved[r].1.share[square.rows[i]]);
    let solved = lu.solve(&shares)?;
    // Each run's weight `e^{Λ_r(c)}`, and its `e^{Λ_r(c)} ‖M⁻¹ a_r‖₁` for choosing the
    // reference run of its column (the one of least sum).
    let weights: Vec<f64> = (moved.iter())
        .map(|(_, run)| run.guides.iter().map(|&g| b.centre(g)).sum::<f64>().exp())
        .collect();
    let sizes: Vec<f64> = (0..moved.len())
        .map(|r| weights[r] * solved.column(r).lp_norm(1))
        .collect();
    let mut p = DMatrix::<f64>::zeros(k, k);
    // Each moved column's runs (a range of `moved`) and its reference run.
    let mut references: Vec<(usize, std::ops::Range<usize>, usize)> = Vec::new();
    let mut start = 0;
    while start < moved.len() {
        let j = moved[start].0;
        let end = start + moved[start..].iter().take_while(|m| m.0 == j).count();
        let column = start..end;
        let spread = |r: usize, reference: usize| {
            b.apart(&moved[r].1.guides, &moved[reference].1.guides)
                .exp_m1()
        };
        let reference = (column.clone())
            .min_by(|&x, &y| {
                let sum = |reference| {
                    column
                        .clone()
                        .map(|r| sizes[r] * spread(r, reference))
                        .sum::<f64>()
                };
                sum(x).total_cmp(&sum(y))
            })
            .unwrap_or(start);
        for r in column.clone() {
            let scale = weights[r] * spread(r, reference);
            for i in 0..k {
                p[(i, j)] += scale * solved[(i, r)].abs();
            }
        }
        references.push((j, column, reference));
        start = end;
    }
    let (radius, worst) = match p.iter().all(|x| x.is_finite()) {
        true => spectral_bound(p.clone()),
        false => {
            let column = (0..k).find(|&j| !p.column(j).iter().all(|x| x.is_finite()));
            (f64::INFINITY, column.unwrap_or(0))
        }
    };
    let Some((_, column, reference)) = references.iter().find(|c| c.0 == worst) else {
        return Some((radius, None));
    };
    let guides = &moved[*reference].1.guides;
    let weight = |g: usize| -> f64 {
        let apart = |r: &usize| moved[*r].1.guides.contains(&g) != guides.contains(&g);
        b.half(g) * column.clone().filter(apart).map(|r| sizes[r]).sum::<f64>()
    };
    let guide = (column.clone())
        .flat_map(|r| moved[r].1.guides.iter().copied())
        .filter(|&g| b.half(g) > 0.0)
        .max_by(|&x, &y| weight(x).total_cmp(&weight(y)));
    Some((radius, guide))
}

/// `max_i (P x)_i / x_i ≥ ρ(P)` for nonnegative `P`, `x > 0` from power iteration (the
/// Collatz-Wielandt bound, exact at `P`'s Perron vector), and the column whose share
/// `y_i P_ij x_j` of `yᵀ P x` is largest (`y` from `Pᵀ`'s iteration). Infinite where it
/// overflows.
fn spectral_bound(p: DMatrix<f64>) -> (f64, usize) {
    // On `P` scaled to a largest entry of 1, so that no sum overflows nor any `x_i`
    // underflows (`x_i ≥ 1e-30 / (k + 1)`).
    let k = p.nrows();
    let largest = p.max();
    if largest == 0.0 {
        return (0.0, 0);
    }
    let p = p / largest;
    let (mut x, mut y) = (DVector::from_element(k, 1.0), DVector::from_element(k, 1.0));
    for _ in 0..20 {
        x = (&p * &x).add_scalar(1e-30);
        y = (p.transpose() * &y).add_scalar(1e-30);
        x /= x.max();
        y /= y.max();
    }
    let px = &p * &x;
    let scaled = (0..k).map(|i| px[i] / x[i]).fold(0.0, f64::max);
    let radius = match scaled * largest {
        r if r <= f64::MAX => r,
        _ => f64::INFINITY,
    };
    let yp = p.transpose() * &y;
    let worst = (0..k).max_by(|&a, &b| (yp[a] * x[a]).total_cmp(&(yp[b] * x[b])));
    (radius, worst.unwrap_or(0))
}

/// Each column of `E` as its runs: a strand over guides with friction by
/// [`crate::tension::for_each_run`] (a guide nothing slides over keeps the factor 1, and is
/// left out of the runs' guides; the pretension rows keep the model's entries, in the first
/// run, as `state_matrix` keeps them), every other column one run without guides. Built
/// once per model and its sliders.
pub(super) struct Columns(Vec<Vec<Run>>);

impl Columns {
    pub(super) fn of(model: &Model<f64>, sliding: &Sliding) -> Columns {
        let e = &model.system.matrix;
        let count = e.first().map_or(0, Vec::len);
        let constant = |c: usize| Run {
            share: e.iter().map(|row| row[c]).collect(),
            guides: Vec::new(),
        };
        let mut columns: Vec<Vec<Run>> = (0..count).map(|c| vec![constant(c)]).collect();
        let slider_at = |s: usize, idler: usize| {
            (sliding.sliders.iter()).position(|x| x.strand == s && x.idler == idler)
        };
        for (s, strand) in model.strands.iter().enumerate() {
            if !strand.idlers.iter().any(|idler| idler.capstan().is_some()) {
                continue;
            }
            let mut below = Vec::new();
            let mut column: Vec<Run> = Vec::new();
            for_each_run(strand, e.len(), |share, ends| {
                column.push(Run {
                    share: share.to_vec(),
                    guides: below.clone(),
                });
                below.extend(ends.and_then(|idler| slider_at(s, idler)));
                below.sort_unstable();
            });
            for (r, row) in model.system.rows.iter().enumerate() {
                if matches!(row, Row::Pretension(_)) {
                    column[0].share[r] = e[r][strand.unknown];
                }
            }
            columns[strand.unknown] = column;
        }
        Columns(columns)
    }

    /// Column `c`'s runs, from the ground end.
    pub(super) fn runs(&self, c: usize) -> &[Run] {
        &self.0[c]
    }

    /// The runs of each column of `square`, `Σ coefficient · (column of E)`.
    fn of_square(&self, square: &Square) -> Vec<Vec<Run>> {
        let combined = |combination: &Vec<(usize, f64)>| -> Vec<Run> {
            (combination.iter())
                .flat_map(|&(c, x)| {
                    self.0[c].iter().map(move |run| Run {
                        share: run.share.iter().map(|a| x * a).collect(),
                        guides: run.guides.clone(),
                    })
                })
                .collect()
        };
        square.columns.iter().map(combined).collect()
    }

    /// Whether the determinant of `square` vanishes at every capstan factor, by its
    /// pattern of entries that are not always zero ([`without_transversal`]).
    pub(super) fn always_singular(&self, square: &Square) -> bool {
        let runs = self.of_square(square);
        without_transversal(square.rows.len(), &|i, j| {
            (runs[j].iter()).any(|run| run.share[square.rows[i]] != 0.0)
        })
    }
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
    use super::{spectral_bound, without_transversal};
    use nalgebra::DMatrix;

    /// The bound on the spectral radius is the radius for a triangle to within the power
    /// iteration's 20 steps (far below its norms: the off-diagonal 100 does not count), at
    /// least the radius for a full matrix, zero
    /// for zero, and infinite where the radius is beyond `f64` (`2e308` for `1e308 (J − I)`),
    /// never zero or NaN.
    #[test]
    fn the_spectral_bound_is_the_perron_root_from_above_and_overflows_to_infinity() {
        let triangle = DMatrix::from_row_slice(2, 2, &[0.1, 100.0, 0.0, 0.2]);
        let (radius, _) = spectral_bound(triangle);
        assert!((0.2..=0.2 * (1.0 + 1e-5)).contains(&radius), "{radius}");
        let full = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]);
        let perron = (5.0 + 33f64.sqrt()) / 2.0;
        let (radius, _) = spectral_bound(full);
        assert!(
            radius >= perron && radius <= perron * (1.0 + 1e-9),
            "{radius}"
        );
        assert_eq!(spectral_bound(DMatrix::zeros(3, 3)).0, 0.0);
        let huge = DMatrix::from_fn(3, 3, |i, j| if i == j { 0.0 } else { 1e308 });
        assert_eq!(spectral_bound(huge).0, f64::INFINITY);
    }

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
