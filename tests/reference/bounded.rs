//! An independent reference for the bounded tension distribution, by exhaustive enumeration
//! of active bound sets in double-double.
//!
//! # The problem
//!
//! Given `A` (r × m, f64: what the m tendon tensions must deliver; rows independent or not),
//! a required right side `b` (r, DoubleDouble), per-tendon bounds `lower_k ≤ T_k ≤ upper_k`
//! (f64; `upper_k = f64::INFINITY` means no maximum; `lower_k ≤ upper_k`), and a target `c`
//! (m, f64; all zeros for the least-norm objective): find T minimising Σ_k (T_k − c_k)²
//! subject to A T = b and the bounds; or report that no T satisfies the constraints.
//!
//! (Also accepted: `lower_k = −∞`, no floor; and `lower_k = upper_k`, a tendon held fixed.)
//!
//! # The method
//!
//! Nothing is shared with `tendyn_core::distribution` or `tendyn_core::tension`: only
//! [`DoubleDouble`] and, for the rank of `A`, nalgebra's `f64` SVD are used. The optimum
//! is found in the full tension space (no null-space basis, no particular solution): for
//! each candidate set `S` of tendons held at a bound, the remaining ("free") tendons `F`
//! take `T_F = c_F + A_Fᵀ y` with `y` from the normal equations `A_F A_Fᵀ y = b − A_S T_S −
//! A_F c_F`, solved by an `LDLᵀ` factorisation with symmetric pivoting in double-double;
//! the first `S` (by increasing size) whose point satisfies `A T = b`, every bound and the
//! sign conditions on the multipliers of `S` is the optimum. [`solve`] documents the
//! derivation, why sets of at most `d = m − rank(A)` tendons suffice, and the tolerances.
//!
//! [`random_problem`] draws controllable systems (with a strictly positive null vector)
//! where the maxima make some draws infeasible, and [`mechanism_ron`] writes the same
//! system as a mechanism file for the real parser, solver and code generator.

// Index loops read like the algebra over index sets.
#![allow(clippy::needless_range_loop)]

use nalgebra::DMatrix;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;
use tendyn_core::{DoubleDouble, Numeric};

/// A bounded least-distance tension problem (see the module documentation).
#[derive(Clone, Debug)]
pub struct Problem {
    /// `A`, r rows of m entries.
    pub a: Vec<Vec<f64>>,
    /// The required right side `b`, r entries.
    pub b: Vec<DoubleDouble>,
    /// Per-tendon lower bounds (floors), m entries.
    pub lower: Vec<f64>,
    /// Per-tendon upper bounds (maxima), m entries; `f64::INFINITY` for none.
    pub upper: Vec<f64>,
    /// The target `c`, m entries (zeros: least norm).
    pub target: Vec<f64>,
}

/// The answer to a [`Problem`].
#[derive(Clone, Debug)]
pub enum Solution {
    /// The unique minimiser.
    Optimal(Vec<DoubleDouble>),
    /// No `T` satisfies `A T = b` and the bounds.
    Infeasible,
}

/// Bounds and sign conditions are checked to this tolerance, relative to the size of the
/// numbers (double-double round-off, u² ≈ 1.2e-32, with ample room for the solve).
const TOL: f64 = 1e-25;
/// `A T = b` is checked to this tolerance, relative to `|b| + |A| |T|`. Looser than [`TOL`]:
/// the normal equations square the conditioning of `A_F`. The check decides anything only
/// when `A` (or `A_F`) has dependent rows and `b` is inconsistent with them, which is never
/// a matter of round-off.
const RESIDUAL_TOL: f64 = 1e-20;
/// Relative tolerance on singular values for the rank of `A` (in `f64`).
const RANK_TOL: f64 = 1e-10;
/// A pivot of `A_F A_Fᵀ` at or below this fraction of its largest diagonal entry ends the
/// factorisation: the square of [`RANK_TOL`], since the pivots scale as squared singular
/// values.
const PIVOT_TOL: f64 = RANK_TOL * RANK_TOL;

/// The numerical rank of `a` (rows of equal length `m`): singular values above
/// `1e-10 ×` the largest, by nalgebra's SVD in `f64`.
pub fn rank(a: &[Vec<f64>], m: usize) -> usize {
    if a.is_empty() || m == 0 {
        return 0;
    }
    let sv = DMatrix::from_fn(a.len(), m, |i, j| a[i][j]).singular_values();
    let largest = sv.iter().fold(0.0_f64, |x, &s| x.max(s));
    if largest == 0.0 {
        return 0;
    }
    sv.iter().filter(|&&s| s > RANK_TOL * largest).count()
}

/// The unique optimum of `p`, or [`Solution::Infeasible`].
///
/// Panics if the dimensions disagree, a bound is NaN, some `lower_k > upper_k`, or a
/// lower bound is `+∞` or an upper bound `−∞`.
///
/// # Derivation
///
/// Write the problem as: minimise `½ Σ (T_k − c_k)²` subject to `A T = b`, `T_k ≥ l_k`,
/// `T_k ≤ u_k`. The objective is strictly convex and the constraints are linear, so a
/// minimiser, if the feasible set is non-empty, exists (the objective is coercive on a
/// closed set) and is unique, and the KKT conditions are necessary (linear constraints need
/// no further qualification) and sufficient. With multipliers `y` (r) for `A T = b`,
/// `λ_k ≥ 0` for `T_k ≥ l_k` and `ν_k ≥ 0` for `T_k ≤ u_k`, stationarity of
/// `½|T − c|² − yᵀ(A T − b) − λᵀ(T − l) + νᵀ(T − u)` reads
///
/// `T − c − Aᵀy = λ − ν`, with `λ_k (T_k − l_k) = 0`, `ν_k (u_k − T_k) = 0`.
///
/// Define `g_k = (T_k − c_k) − (Aᵀy)_k = λ_k − ν_k`. Then:
/// - a tendon strictly between its bounds ("free") has `λ_k = ν_k = 0`, so
///   `T_k = c_k + (Aᵀy)_k`;
/// - a tendon at its lower bound (and `l_k < u_k`) has `ν_k = 0`, so `g_k = λ_k ≥ 0`;
/// - a tendon at its upper bound (and `l_k < u_k`) has `λ_k = 0`, so `g_k = −ν_k ≤ 0`;
/// - a tendon with `l_k = u_k` is held there with `g_k` of either sign.
///
/// Conversely, any `T` satisfying `A T = b` and the bounds, and any `y`, with a set `S` of
/// tendons at a bound such that `T_k = c_k + (Aᵀy)_k` off `S` and `g_k` has the sign above
/// on `S`, is a KKT point, hence *the* optimum. So for a candidate `S` (each member
/// assigned to its lower or its upper bound) the free tendons `F` satisfy
/// `T_F = c_F + A_Fᵀ y` and `A_F T_F = b − A_S T_S`, that is
///
/// `(A_F A_Fᵀ) y = b − A_S T_S − A_F c_F`.
///
/// Whatever solution `y` is taken, `T_F` is the same: it is the point of the affine set
/// `{A_F T_F = b − A_S T_S}` nearest to `c_F` (its difference from `c_F` lies in the row
/// space of `A_F`). If this system is inconsistent (possible only when `A_F` has dependent
/// rows), no `T` with this `S` exists; that is caught by checking `A T = b` afterwards. The
/// first `S` (in order of increasing `|S|`) whose point passes every bound and sign check,
/// to the tolerances below, is returned; if none passes, the problem is infeasible, by the
/// completeness argument that follows.
///
/// # Why sets of at most `d = m − rank(A)` tendons suffice
///
/// Let `N = null(A)` (dimension `d`), `P` the orthogonal projector onto it (so `I − P`
/// projects onto the row space of `A`), and `T*` the optimum with its KKT multipliers
/// `y*`, `g*`; let `B` be the set of bounds active at `T*`, with `σ_k = +1` for a tendon at
/// its lower bound, `−1` at its upper bound (and both signs admitted when `l_k = u_k`). Then
/// `T* − c = Aᵀy* + Σ_{k∈B} g*_k e_k` with `σ_k g*_k ≥ 0`. Applying `P` removes `Aᵀy*`:
///
/// `P (T* − c) = Σ_{k∈B} |g*_k| σ_k P e_k`,
///
/// a point of the convex cone spanned by the vectors `σ_k P e_k` in the `d`-dimensional
/// space `N`. By Carathéodory's theorem for cones it is a non-negative combination
/// `Σ_{k∈S} μ_k σ_k P e_k` of a subset `S ⊆ B` whose vectors `P e_k` are linearly
/// independent, so `|S| ≤ d`. Put `g'_k = μ_k σ_k` on `S`: then `P (T* − c − Σ_S g'_k e_k)
/// = 0`, so `T* − c − Σ_S g'_k e_k = Aᵀy'` for some `y'`; off `S` this says
/// `T*_k = c_k + (Aᵀy')_k` (members of `B \ S` are simply free tendons that happen to sit at
/// a bound), and on `S` the multipliers `g'_k` have the right sign. So this `S`, with its
/// members assigned to the bounds they are at, is one of the enumerated sets and `T*`
/// satisfies its equations. Its check cannot depend on which `y` the solve picks: if
/// `A_Fᵀ z = 0`, then `Aᵀz` is supported on `S` and lies in the row space of `A`, so
/// `Σ_S (Aᵀz)_k P e_k = P Aᵀz = 0`, and independence forces `Aᵀz = 0`. Hence every solution
/// `y` of the normal equations gives the same `Aᵀy` as `y'`, the same `T` (`= T*`) and the
/// same multipliers `g'`. In particular `rank(A_F) = rank(A)` for this `S`.
///
/// Nothing here assumes independent rows of `A` (`d` counts the null space, not `m − r`),
/// a non-degenerate optimum (`B` may be larger than `S`, multipliers may vanish) or finite
/// bounds, so enumerating sets of up to `d` tendons is enough in every case; the tests
/// confirm it against enumerating up to `m` on random systems.
///
/// # Tolerances
///
/// - bounds: `l_k − 1e-25 s ≤ T_k ≤ u_k + 1e-25 s`, `s` the largest of `|T_k|`, `|c_k|`
///   and the finite `|l_k|`, `|u_k|`;
/// - signs: `g_k ≥ −1e-25 s'` at a lower bound, `≤ 1e-25 s'` at an upper bound, `s'` the
///   larger of `s` and the largest `|(Aᵀy)_k|`;
/// - `A T = b`: each row within `1e-20 (|b_j| + Σ_k |A_jk| |T_k|)`. Rows that the `f64`
///   SVD finds dependent (relative `1e-10`) are taken to be exactly so: `b` must satisfy
///   the same dependence to this tolerance, or the problem is infeasible;
/// - the factorisation of `A_F A_Fᵀ` stops after `rank(A)` pivots, or at a pivot at or
///   below `1e-20 ×` its largest diagonal entry (an `A_F` of condition number beyond
///   `1e10` counts as rank deficient, as it does for the rank of `A`).
pub fn solve(p: &Problem) -> Solution {
    solve_enumerating(p, None)
}

/// Which bound a tendon of the candidate set is held at.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Bound {
    Lower,
    Upper,
    /// `lower = upper`: the multiplier may have either sign.
    Fixed,
}

/// [`solve`] with the enumeration limited to sets of at most `max_size` tendons (by default
/// `d = m − rank(A)`).
fn solve_enumerating(p: &Problem, max_size: Option<usize>) -> Solution {
    let (r, m) = (p.a.len(), p.lower.len());
    assert_eq!(p.b.len(), r, "b has one entry per row of A");
    assert!(
        p.a.iter().all(|row| row.len() == m),
        "every row of A has m entries"
    );
    assert_eq!(p.upper.len(), m, "one upper bound per tendon");
    assert_eq!(p.target.len(), m, "one target per tendon");
    for k in 0..m {
        assert!(
            p.lower[k] < f64::INFINITY && p.upper[k] > f64::NEG_INFINITY,
            "tendon {k}: bounds {} ..= {}",
            p.lower[k],
            p.upper[k]
        );
        assert!(
            p.lower[k] <= p.upper[k],
            "tendon {k}: lower {} must not exceed upper {}",
            p.lower[k],
            p.upper[k]
        );
    }
    let rho = rank(&p.a, m);
    let max_size = max_size.unwrap_or(m - rho);
    // The options of each tendon when it is in the set.
    let options: Vec<Vec<Bound>> = (0..m)
        .map(|k| {
            let (l, u) = (p.lower[k], p.upper[k]);
            if l == u {
                vec![Bound::Fixed]
            } else {
                let mut o = Vec::new();
                if l.is_finite() {
                    o.push(Bound::Lower);
                }
                if u.is_finite() {
                    o.push(Bound::Upper);
                }
                o
            }
        })
        .collect();
    let bounds_scale = (0..m).fold(0.0_f64, |s, k| {
        let mut s = s.max(p.target[k].abs());
        for x in [p.lower[k], p.upper[k]] {
            if x.is_finite() {
                s = s.max(x.abs());
            }
        }
        s
    });
    // Precomputed for every set: the products a_ik a_jk of each column (exact in
    // double-double), A Aᵀ, and b − A c.
    let outer: Vec<Vec<DoubleDouble>> = (0..m)
        .map(|k| {
            let mut o = vec![DoubleDouble::ZERO; r * r];
            for i in 0..r {
                for j in 0..r {
                    o[i * r + j] = dd(p.a[i][k]) * p.a[j][k];
                }
            }
            o
        })
        .collect();
    let mut gram = vec![DoubleDouble::ZERO; r * r];
    for o in &outer {
        for (g, x) in gram.iter_mut().zip(o) {
            *g += *x;
        }
    }
    let b_minus_ac = (0..r)
        .map(|j| (0..m).fold(p.b[j], |s, k| s - dd(p.a[j][k]) * p.target[k]))
        .collect();
    let ctx = Context {
        p,
        rho,
        bounds_scale,
        outer,
        gram,
        b_minus_ac,
    };
    let mut set: Vec<(usize, Bound)> = Vec::new();
    for size in 0..=max_size.min(m) {
        // Index sets of this size in lexicographic order.
        let mut idx: Vec<usize> = (0..size).collect();
        loop {
            // Every assignment of the members to their options (mixed radix).
            let mut choice = vec![0usize; size];
            if idx.iter().all(|&k| !options[k].is_empty()) {
                // A_F A_Fᵀ depends only on the index set: factored once for its assignments.
                let factor = ctx.factor(&idx);
                loop {
                    set.clear();
                    set.extend(idx.iter().zip(&choice).map(|(&k, &c)| (k, options[k][c])));
                    if let Some(t) = ctx.try_set(&set, &factor) {
                        return Solution::Optimal(t);
                    }
                    // next assignment
                    let mut pos = 0;
                    while pos < size {
                        choice[pos] += 1;
                        if choice[pos] < options[idx[pos]].len() {
                            break;
                        }
                        choice[pos] = 0;
                        pos += 1;
                    }
                    if pos == size {
                        break;
                    }
                }
            }
            if !next_combination(&mut idx, m) {
                break;
            }
        }
    }
    Solution::Infeasible
}

/// Steps `idx` (strictly increasing indices below `m`) to the next combination of its
/// size in lexicographic order; `false` after the last.
fn next_combination(idx: &mut [usize], m: usize) -> bool {
    let size = idx.len();
    for i in (0..size).rev() {
        if idx[i] < m - size + i {
            idx[i] += 1;
            for j in i + 1..size {
                idx[j] = idx[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

struct Context<'a> {
    p: &'a Problem,
    rho: usize,
    /// Largest `|c_k|` and finite `|l_k|`, `|u_k|`.
    bounds_scale: f64,
    /// `outer[k][i r + j] = A_ik A_jk`.
    outer: Vec<Vec<DoubleDouble>>,
    /// `A Aᵀ`, row-major.
    gram: Vec<DoubleDouble>,
    /// `b − A c`.
    b_minus_ac: Vec<DoubleDouble>,
}

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::from(x)
}

impl Context<'_> {
    /// The factorisation of `A_F A_Fᵀ = A Aᵀ − Σ_S a_k a_kᵀ` for the tendons `held`.
    fn factor(&self, held: &[usize]) -> Ldlt {
        let r = self.p.a.len();
        let mut g: Vec<Vec<DoubleDouble>> = self.gram.chunks(r).map(|row| row.to_vec()).collect();
        for &k in held {
            for j in 0..r {
                for i in 0..r {
                    g[j][i] -= self.outer[k][j * r + i];
                }
            }
        }
        Ldlt::new(g, self.rho)
    }

    /// The KKT point of candidate set `set` (tendon, bound), if it passes every check;
    /// `factor` is [`Context::factor`] of its tendons.
    fn try_set(&self, set: &[(usize, Bound)], factor: &Ldlt) -> Option<Vec<DoubleDouble>> {
        let p = self.p;
        let (r, m) = (p.a.len(), p.lower.len());
        let mut held: Vec<Option<Bound>> = vec![None; m];
        for &(k, bound) in set {
            held[k] = Some(bound);
        }
        // w: the held tendons at their bounds, the free ones at their targets.
        let w: Vec<f64> = (0..m)
            .map(|k| match held[k] {
                Some(Bound::Upper) => p.upper[k],
                Some(_) => p.lower[k],
                None => p.target[k],
            })
            .collect();
        // Normal equations (A_F A_Fᵀ) y = b − A w, with b − A w = (b − A c) − Σ_S a_k
        // (w_k − c_k).
        let mut h = self.b_minus_ac.clone();
        for &(k, _) in set {
            let shift = dd(w[k]) - p.target[k];
            for j in 0..r {
                h[j] -= shift * p.a[j][k];
            }
        }
        let y = factor.solve(&h);
        // T = w + (Aᵀy on F); q = Aᵀy everywhere (for the multipliers).
        let q: Vec<DoubleDouble> = (0..m)
            .map(|k| (0..r).fold(DoubleDouble::ZERO, |s, j| s + y[j] * p.a[j][k]))
            .collect();
        let t: Vec<DoubleDouble> = (0..m)
            .map(|k| match held[k] {
                Some(_) => dd(w[k]),
                None => dd(w[k]) + q[k],
            })
            .collect();
        // Bounds (the held tendons are exactly at theirs).
        let s = t
            .iter()
            .fold(self.bounds_scale, |s, x| s.max(x.abs().to_f64()));
        let tol = dd(TOL * s);
        for k in (0..m).filter(|&k| held[k].is_none()) {
            let (l, u) = (p.lower[k], p.upper[k]);
            if (l > f64::NEG_INFINITY && t[k] < dd(l) - tol)
                || (u < f64::INFINITY && t[k] > dd(u) + tol)
            {
                return None;
            }
        }
        // Signs of the multipliers g_k = (T_k − c_k) − (Aᵀy)_k.
        let s2 = q.iter().fold(s, |s, x| s.max(x.abs().to_f64()));
        let tol2 = dd(TOL * s2);
        for &(k, bound) in set {
            let gk = t[k] - p.target[k] - q[k];
            let ok = match bound {
                Bound::Lower => gk >= -tol2,
                Bound::Upper => gk <= tol2,
                Bound::Fixed => true,
            };
            if !ok {
                return None;
            }
        }
        // A T = b.
        for j in 0..r {
            let mut res = -p.b[j];
            let mut size = p.b[j].abs().to_f64();
            for k in 0..m {
                res += t[k] * p.a[j][k];
                size += (t[k].to_f64() * p.a[j][k]).abs();
            }
            if res.abs() > dd(RESIDUAL_TOL * size) {
                return None;
            }
        }
        Some(t)
    }
}

/// `P g Pᵀ = L D Lᵀ` of a symmetric positive semi-definite `g` (r × r) by symmetric
/// pivoting (largest remaining diagonal first), stopped after `max_rank` pivots or at a
/// pivot `≤ PIVOT_TOL ×` the largest diagonal entry of `g`.
struct Ldlt {
    /// `L` below the diagonal (unit diagonal implied), `D` on it; the rest is scratch.
    g: Vec<Vec<DoubleDouble>>,
    /// Row `i` of the factored matrix is row `perm[i]` of `g`.
    perm: Vec<usize>,
    rank: usize,
}

impl Ldlt {
    fn new(mut g: Vec<Vec<DoubleDouble>>, max_rank: usize) -> Self {
        let r = g.len();
        let mut perm: Vec<usize> = (0..r).collect();
        let largest = (0..r).fold(
            DoubleDouble::ZERO,
            |s, i| if g[i][i] > s { g[i][i] } else { s },
        );
        let floor = largest * PIVOT_TOL;
        let mut rank = 0;
        while rank < r.min(max_rank) {
            let k = rank;
            let piv = (k..r).fold(k, |b, i| if g[i][i] > g[b][b] { i } else { b });
            if g[piv][piv] <= floor || largest == DoubleDouble::ZERO {
                break;
            }
            if piv != k {
                g.swap(k, piv);
                for row in g.iter_mut() {
                    row.swap(k, piv);
                }
                perm.swap(k, piv);
            }
            // Schur complement, kept symmetric (both triangles) for the pivoting; the
            // multipliers l_i go below the diagonal.
            let inv = DoubleDouble::ONE / g[k][k];
            let col: Vec<DoubleDouble> = (0..r).map(|i| g[i][k]).collect();
            for i in k + 1..r {
                let l = col[i] * inv;
                for j in k + 1..=i {
                    let v = g[i][j] - l * col[j];
                    g[i][j] = v;
                    g[j][i] = v;
                }
                g[i][k] = l;
            }
            rank += 1;
        }
        Ldlt { g, perm, rank }
    }

    /// A solution `y` of `g y = h` with the components past the last pivot zero (the
    /// equations past it are not checked: the caller checks `A T = b`).
    fn solve(&self, h: &[DoubleDouble]) -> Vec<DoubleDouble> {
        let (g, rank) = (&self.g, self.rank);
        // L z = P h, z /= D, Lᵀ x = z on the first `rank` components, y = Pᵀ x.
        let mut z: Vec<DoubleDouble> = self.perm[..rank].iter().map(|&i| h[i]).collect();
        for i in 0..rank {
            for j in 0..i {
                let v = z[i] - g[i][j] * z[j];
                z[i] = v;
            }
        }
        for i in 0..rank {
            z[i] /= g[i][i];
        }
        for i in (0..rank).rev() {
            for j in i + 1..rank {
                let v = z[i] - g[j][i] * z[j];
                z[i] = v;
            }
        }
        let mut y = vec![DoubleDouble::ZERO; h.len()];
        for i in 0..rank {
            y[self.perm[i]] = z[i];
        }
        y
    }
}

/// The problem of `seed` and the generator state after it (for [`mechanism_ron`]).
fn draw(seed: u64, n: usize, m: usize) -> (Problem, ChaCha8Rng) {
    // How far the drawn tensions may overshoot the maxima (see random_problem).
    let over = 1.0 + 0.4 * (m - n) as f64 / n as f64;
    assert!(n >= 1 && m > n, "a controllable routing needs m > n ≥ 1");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pos: Vec<f64> = (0..m).map(|_| rng.random_range(0.5..2.0)).collect();
    let pp: f64 = pos.iter().map(|x| x * x).sum();
    let a = loop {
        let a: Vec<Vec<f64>> = (0..n)
            .map(|_| {
                let mut row: Vec<f64> = (0..m).map(|_| rng.random_range(-0.05..0.05)).collect();
                let s = row.iter().zip(&pos).map(|(x, y)| x * y).sum::<f64>() / pp;
                for (x, y) in row.iter_mut().zip(&pos) {
                    *x -= s * y;
                }
                row
            })
            .collect();
        if rank(&a, m) == n {
            break a;
        }
    };
    let lower: Vec<f64> = (0..m).map(|_| rng.random_range(0.0..10.0)).collect();
    let upper: Vec<f64> = lower
        .iter()
        .map(|&l| {
            if rng.random_bool(0.7) {
                l + rng.random_range(10.0..50.0)
            } else {
                f64::INFINITY
            }
        })
        .collect();
    // Required forces: those of random tensions that may overshoot the maxima.
    let t: Vec<f64> = upper
        .iter()
        .map(|&u| {
            if u.is_finite() {
                rng.random_range(0.0..over * u)
            } else {
                rng.random_range(0.0..40.0)
            }
        })
        .collect();
    let b = a
        .iter()
        .map(|row| dd(row.iter().zip(&t).map(|(x, y)| x * y).sum::<f64>()))
        .collect();
    let problem = Problem {
        a,
        b,
        lower,
        upper,
        target: vec![0.0; m],
    };
    (problem, rng)
}

/// The (joints, tendons) of the random systems the tests check the distribution on (null
/// spaces of one to four dimensions), with the gravity and maximum factors of
/// [`mechanism_ron_scaled`] that make about 10–50 % of random states infeasible.
pub const SIZES: [(usize, usize, f64, f64); 7] = [
    (1, 3, 1.0, 1.0),
    (2, 4, 2.5, 1.0),
    (3, 4, 1.0, 1.0),
    (3, 6, 0.5, 4.0),
    (4, 6, 0.5, 4.0),
    (6, 8, 0.1, 4.0),
    (6, 10, 0.5, 4.0),
];

/// The seed of the random system of `n` joints and `m` tendons that the tests check (the
/// factors of [`SIZES`] are set for these seeds).
pub fn seed(n: usize, m: usize) -> u64 {
    100 + 16 * n as u64 + m as u64
}

/// A seeded random system of n joints and m tendons: A (n × m) with rank n, whose null space contains a vector with every component strictly positive (so every floor can be met, as a controllable tendon routing guarantees), floors drawn in [0, 10] N, maxima drawn per tendon (some tendons without maximum), and required generalized forces b such that roughly 10–40 % of draws are infeasible because of the maxima.
///
/// The positive null vector `p` has components in `[0.5, 2]`; each row is drawn in
/// `[-0.05, 0.05]` m and projected onto `p⊥` (redrawn if the rank falls short). Each tendon
/// has a maximum with probability 0.7, `floor + [10, 50]` N. `b = A t` for tensions `t`
/// drawn in `[0, f × max]` (or `[0, 40]` N without a maximum) with
/// `f = 1 + 0.4 (m − n)/n`: the more freedom per joint, the more the redundant tendons can
/// make up for an overshoot, so the overshoot allowed grows with it; this keeps the
/// infeasible fraction between about 15 % and 35 % for the sizes the tests draw (it is
/// printed by `random_systems_infeasible_fraction_and_optimality`). The target is zero
/// (least norm). Requires `1 ≤ n < m`.
pub fn random_problem(seed: u64, n: usize, m: usize) -> Problem {
    draw(seed, n, m).0
}

/// RON text of a planar chain of n revolute links (parallel z axes, DH a = 0.1..0.3 m, alpha 0, d 0, masses ~0.2..1 kg, diagonal inertias, gravity (0,-9.81,0)) driven by m structure-only tendons whose columns are the problem's A (`structure: [..]` per tendon, no route), with each tendon's `floor` and (where finite) `max_tension` from the problem. The name is `format!("bounded_{n}x{m}_{seed}")`.
///
/// The problem is [`random_problem`]`(seed, n, m)`; its `b` is not used (the state decides
/// it). Each link is a slender rod (radius 1 cm) with its centre of mass midway between
/// its joints. Every number is written so that it reads back exactly.
pub fn mechanism_ron(seed: u64, n: usize, m: usize) -> String {
    mechanism_ron_scaled(seed, n, m, 1.0, 1.0)
}

/// [`mechanism_ron`] with gravity scaled by `gravity` and every maximum by `max`: the
/// mechanism's own loads decide how many states the bounds can meet, and these two
/// factors set that fraction per system.
pub fn mechanism_ron_scaled(seed: u64, n: usize, m: usize, gravity: f64, max: f64) -> String {
    let (mut p, mut rng) = draw(seed, n, m);
    for u in p.upper.iter_mut() {
        *u *= max;
    }
    let mut s = String::new();
    writeln!(
        s,
        "(\n    name: \"bounded_{n}x{m}_{seed}\",\n    gravity: (0.0, {:e}, 0.0),\n    links: [",
        -9.81 * gravity
    )
    .unwrap();
    for j in 1..=n {
        let a: f64 = rng.random_range(0.1..0.3);
        let mass: f64 = rng.random_range(0.2..1.0);
        let rod = 0.01_f64;
        let (xx, yy) = (
            mass * rod * rod / 2.0,
            mass * (3.0 * rod * rod + a * a) / 12.0,
        );
        writeln!(
            s,
            "        (name: \"l{j}\", dh: (a: {a:e}, alpha: 0.0, d: 0.0), mass: {mass:e}, com: ({:e}, 0.0, 0.0), inertia: (xx: {xx:e}, yy: {yy:e}, zz: {yy:e})),",
            -a / 2.0
        )
        .unwrap();
    }
    writeln!(s, "    ],\n    tendons: [").unwrap();
    for k in 0..m {
        let column: Vec<String> = p.a.iter().map(|row| format!("{:e}", row[k])).collect();
        write!(
            s,
            "        (name: \"t{}\", structure: [{}], floor: {:e}",
            k + 1,
            column.join(", "),
            p.lower[k]
        )
        .unwrap();
        if p.upper[k].is_finite() {
            write!(s, ", max_tension: {:e}", p.upper[k]).unwrap();
        }
        writeln!(s, "),").unwrap();
    }
    s.push_str("    ],\n)\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};
    use tendyn_core::Real;

    /// Relative disagreement of `got` from `want`.
    fn rel(got: DoubleDouble, want: DoubleDouble) -> f64 {
        ((got - want).abs() / want.abs().max(DoubleDouble::ONE)).to_f64()
    }

    fn optimal(s: Solution) -> Vec<DoubleDouble> {
        match s {
            Solution::Optimal(t) => t,
            Solution::Infeasible => panic!("expected an optimum, got Infeasible"),
        }
    }

    fn one_joint(a: Vec<f64>, b: f64, lower: Vec<f64>, upper: Vec<f64>) -> Problem {
        let m = a.len();
        Problem {
            a: vec![a],
            b: vec![dd(b)],
            lower,
            upper,
            target: vec![0.0; m],
        }
    }

    const INF: f64 = f64::INFINITY;

    /// `A T = b` and the bounds, checked independently of the solver, to `tol` relative.
    fn assert_feasible(p: &Problem, t: &[DoubleDouble], tol: f64) {
        let s = t.iter().fold(1.0_f64, |s, x| s.max(x.abs().to_f64()));
        let slack = dd(tol * s);
        for k in 0..t.len() {
            let (l, u) = (p.lower[k], p.upper[k]);
            assert!(
                l == f64::NEG_INFINITY || t[k] >= dd(l) - slack,
                "T{k} = {:?} below {l}",
                t[k]
            );
            assert!(
                u == f64::INFINITY || t[k] <= dd(u) + slack,
                "T{k} = {:?} above {u}",
                t[k]
            );
        }
        for (row, &bj) in p.a.iter().zip(&p.b) {
            let at = row
                .iter()
                .zip(t)
                .fold(DoubleDouble::ZERO, |s, (&a, &x)| s + x * a);
            let size = row
                .iter()
                .zip(t)
                .map(|(a, x)| (a * x.to_f64()).abs())
                .sum::<f64>()
                + bj.abs().to_f64();
            assert!(
                ((at - bj).abs()).to_f64() <= 1e-20 * size,
                "A T = {at:?}, b = {bj:?}"
            );
        }
    }

    fn objective(p: &Problem, t: &[DoubleDouble]) -> DoubleDouble {
        t.iter()
            .zip(&p.target)
            .fold(DoubleDouble::ZERO, |s, (&x, &c)| s + (x - c) * (x - c))
    }

    #[test]
    fn two_opposite_tendons_by_hand() {
        // A = [r1, −r2] with r1 = 1/32, r2 = 1/16 (exact in binary), floors (1, 2).
        //
        // Least norm, τ = 1/2: the free solution T = Aᵀy = y (r1, −r2) has T2 < 0, so
        // T2 sits at its floor 2 and T1 = (τ + r2·2)/r1 = (1/2 + 1/8)·32 = 20. Check of
        // the multiplier: T1 = r1 y gives y = 640, (Aᵀy)_2 = −r2 y = −40, so
        // g2 = T2 − (Aᵀy)_2 = 42 ≥ 0, as a floor needs.
        let p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            0.5,
            vec![1.0, 2.0],
            vec![INF, INF],
        );
        let t = optimal(solve(&p));
        assert_eq!(t, vec![dd(20.0), dd(2.0)]);

        // Target c = (10, 10), τ = 3/16: T = c + Aᵀy, A T = τ gives
        // (r1² + r2²) y = τ − A c = 3/16 − (10/32 − 10/16) = 1/2, r1² + r2² = 5/1024, so
        // y = 512/5, T1 = 10 + y/32 = 66/5, T2 = 10 − y/16 = 18/5: both above their floors,
        // no bound active.
        let mut p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            3.0 / 16.0,
            vec![1.0, 2.0],
            vec![INF, INF],
        );
        p.target = vec![10.0, 10.0];
        let t = optimal(solve(&p));
        let want = [dd(66.0) / dd(5.0), dd(18.0) / dd(5.0)];
        for k in 0..2 {
            assert!(
                rel(t[k], want[k]) < 1e-30,
                "T{k}: {:?} vs {:?}",
                t[k],
                want[k]
            );
        }

        // Target (10, 10), τ = −1/2: y = (−1/2 + 5/16)·1024/5 = −192/5, T1 = 10 − 6/5 =
        // 44/5, T2 = 10 + 12/5 = 62/5. With a maximum of 12 on T2 that point is out: T2 at
        // 12, T1 = (τ + 12/16)·32 = 8; multiplier g2 = T2 − c2 − (Aᵀy)_2 with y = (T1 − c1)
        // /r1 = −64, (Aᵀy)_2 = 4: g2 = 12 − 10 − 4 = −2 ≤ 0, as a maximum needs.
        let mut p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            -0.5,
            vec![1.0, 2.0],
            vec![INF, 12.0],
        );
        p.target = vec![10.0, 10.0];
        let t = optimal(solve(&p));
        assert_eq!(t, vec![dd(8.0), dd(12.0)]);
    }

    #[test]
    fn infeasible_because_of_a_maximum() {
        // As above, τ = 1/2: every feasible T has T1 = (1/2 + T2/16)·32 ≥ 20 (T2 ≥ 2), so a
        // maximum of 15 on T1 leaves nothing; a maximum of 25 leaves the optimum (20, 2).
        let p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            0.5,
            vec![1.0, 2.0],
            vec![15.0, INF],
        );
        assert!(matches!(solve(&p), Solution::Infeasible));
        let p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            0.5,
            vec![1.0, 2.0],
            vec![25.0, INF],
        );
        assert_eq!(optimal(solve(&p)), vec![dd(20.0), dd(2.0)]);
        // Without any maximum it is feasible whatever τ.
        let p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            -1e3,
            vec![1.0, 2.0],
            vec![INF, INF],
        );
        assert_feasible(&p, &optimal(solve(&p)), 1e-25);
    }

    #[test]
    fn three_tendons_one_maximum_active() {
        // One joint, moment arms (r1, r2, −r3) = (1/16, 1/32, −1/32), floors 1 N, maxima
        // 15 N (T1) and 30 N (T2), τ = 1.21875 N·m.
        //
        // Least norm above the floors: T3 at its floor 1, T1,2 = y (r1, r2) with
        // (r1² + r2²) y = τ + r3 = 1.25, r1² + r2² = 5/1024: y = 256, T = (16, 8, 1), whose
        // T1 exceeds 15. With T1 at 15: T3 free gives y from (r2² + r3²) y = τ − 15 r1 =
        // 0.28125, y = 144, T3 = −4.5 < 1; so T3 also at its floor, and
        // T2 = (τ − 15 r1 + r3)/r2 = (0.28125 + 0.03125)·32 = 10 ≤ 30. Multipliers with
        // y = T2/r2 = 320, Aᵀy = (20, 10, −10): g1 = 15 − 20 = −5 ≤ 0 (at a maximum),
        // g3 = 1 + 10 = 11 ≥ 0 (at a floor). So the optimum is (15, 10, 1).
        let p = one_joint(
            vec![1.0 / 16.0, 1.0 / 32.0, -1.0 / 32.0],
            1.21875,
            vec![1.0; 3],
            vec![15.0, 30.0, INF],
        );
        let mut no_max = p.clone();
        no_max.upper = vec![INF; 3];
        let free = optimal(solve(&no_max));
        assert!(
            rel(free[0], dd(16.0)) < 1e-30 && rel(free[1], dd(8.0)) < 1e-30 && free[2] == dd(1.0)
        );
        let t = optimal(solve(&p));
        assert_feasible(&p, &t, 1e-25);
        assert!(rel(t[0], dd(15.0)) <= 1e-25, "T1 = {:?}", t[0]);
        assert!(rel(t[1], dd(10.0)) <= 1e-25, "T2 = {:?}", t[1]);
        assert!(rel(t[2], dd(1.0)) <= 1e-25, "T3 = {:?}", t[2]);
        // Optimality against other feasible points: a grid over the two-dimensional feasible
        // set, T3 = 1 + s, T1 = 15 − u, T2 from A T = τ.
        let best = objective(&p, &t);
        for i in 0..=20 {
            for j in 0..=20 {
                let (s, u) = (i as f64 * 0.5, j as f64 * 0.7);
                let (t1, t3) = (15.0 - u, 1.0 + s);
                let t2 = (dd(1.21875) - dd(t1) / 16.0 + dd(t3) / 32.0) * 32.0;
                if t1 >= 1.0 && t2 >= dd(1.0) && t2 <= dd(30.0) {
                    assert!(objective(&p, &[dd(t1), t2, dd(t3)]) >= best);
                }
            }
        }
    }

    #[test]
    fn dependent_rows_fixed_tendons_and_square_systems() {
        // The three-tendon case with its row repeated (and doubled): same optimum.
        let row = vec![1.0 / 16.0, 1.0 / 32.0, -1.0 / 32.0];
        let p = Problem {
            a: vec![row.clone(), row.iter().map(|x| 2.0 * x).collect()],
            b: vec![dd(1.21875), dd(2.4375)],
            lower: vec![1.0; 3],
            upper: vec![15.0, 30.0, INF],
            target: vec![0.0; 3],
        };
        assert_eq!(rank(&p.a, 3), 1);
        assert_eq!(optimal(solve(&p)), vec![dd(15.0), dd(10.0), dd(1.0)]);
        // ... and an inconsistent right side.
        let mut q = p.clone();
        q.b[1] = dd(2.5);
        assert!(matches!(solve(&q), Solution::Infeasible));
        // A tendon held fixed (lower = upper = 5/2), target (10, 10), τ = 3/16: T2 = 5/2,
        // T1 = (τ + r2·5/2)/r1 = (3/16 + 5/32)·32 = 11. Its multiplier, with
        // y = (T1 − c1)/r1 = 32 and (Aᵀy)_2 = −2, is g2 = 5/2 − 10 + 2 = −11/2 < 0, which a
        // floor alone would refuse (the free optimum (66/5, 18/5) has T2 above 5/2).
        let mut p = one_joint(
            vec![1.0 / 32.0, -1.0 / 16.0],
            3.0 / 16.0,
            vec![1.0, 2.5],
            vec![INF, 2.5],
        );
        p.target = vec![10.0, 10.0];
        assert_eq!(optimal(solve(&p)), vec![dd(11.0), dd(2.5)]);
        // A square system (d = 0): T = A⁻¹ b, checked against the bounds only.
        let sq = |b1: f64| Problem {
            a: vec![vec![1.0, 1.0], vec![1.0, -1.0]],
            b: vec![dd(b1), dd(1.0)],
            lower: vec![0.0; 2],
            upper: vec![INF; 2],
            target: vec![5.0, 5.0],
        };
        assert_eq!(optimal(solve(&sq(3.0))), vec![dd(2.0), dd(1.0)]);
        assert!(matches!(solve(&sq(-3.0)), Solution::Infeasible));
        // No floor at all (lower = −∞): the plain least-distance point.
        let p = one_joint(vec![1.0, 1.0], 4.0, vec![-INF; 2], vec![INF; 2]);
        assert_eq!(optimal(solve(&p)), vec![dd(2.0), dd(2.0)]);
    }

    const SIZES: [(usize, usize); 7] = [(1, 3), (2, 4), (3, 4), (3, 6), (4, 6), (6, 8), (6, 10)];

    #[test]
    fn random_systems_rank_and_positive_null_vector() {
        for &(n, m) in &SIZES {
            for seed in 0..50 {
                let p = random_problem(seed, n, m);
                assert_eq!(p.a.len(), n);
                assert_eq!(rank(&p.a, m), n, "seed {seed} ({n}, {m})");
                // The generator's positive vector p (its first draws): A p = 0 to f64
                // round-off of the row products.
                let mut rng = ChaCha8Rng::seed_from_u64(seed);
                let pos: Vec<f64> = (0..m).map(|_| rng.random_range(0.5..2.0)).collect();
                assert!(pos.iter().all(|&x| x >= 0.5));
                for row in &p.a {
                    let ap: f64 = row.iter().zip(&pos).map(|(a, x)| a * x).sum();
                    let size: f64 = row.iter().zip(&pos).map(|(a, x)| (a * x).abs()).sum();
                    assert!(
                        ap.abs() <= 1e-14 * size,
                        "seed {seed} ({n}, {m}): (A p)_j = {ap:e}"
                    );
                }
                for k in 0..m {
                    assert!((0.0..10.0).contains(&p.lower[k]));
                    assert!(p.upper[k] >= p.lower[k]);
                }
            }
        }
    }

    #[test]
    fn random_systems_infeasible_fraction_and_optimality() {
        for &(n, m) in &SIZES {
            let draws = 200;
            let mut infeasible = 0;
            let mut some_max_active = 0;
            for seed in 0..draws {
                let p = random_problem(seed, n, m);
                let sol = solve(&p);
                if seed < 40 {
                    // Enumerating up to m (not just d = m − n) never finds anything else.
                    match (&sol, solve_enumerating(&p, Some(m))) {
                        (Solution::Optimal(a), Solution::Optimal(b)) => assert_eq!(a, &b),
                        (Solution::Infeasible, Solution::Infeasible) => {}
                        (a, b) => panic!("seed {seed} ({n}, {m}): {a:?} vs {b:?}"),
                    }
                }
                match sol {
                    Solution::Infeasible => {
                        infeasible += 1;
                        // Only the maxima can make it so.
                        let mut q = p.clone();
                        q.upper = vec![INF; m];
                        assert_feasible(&q, &optimal(solve(&q)), 1e-25);
                    }
                    Solution::Optimal(t) => {
                        assert_feasible(&p, &t, 1e-25);
                        if (0..m)
                            .any(|k| p.upper[k].is_finite() && rel(t[k], dd(p.upper[k])) < 1e-25)
                        {
                            some_max_active += 1;
                        }
                        // Optimality: the optimum for another target is feasible for this
                        // problem, so it cannot be closer to this target.
                        let best = objective(&p, &t);
                        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0xb0b);
                        for _ in 0..3 {
                            let mut q = p.clone();
                            q.target = (0..m).map(|_| rng.random_range(-20.0..60.0)).collect();
                            let other = optimal(solve(&q));
                            assert_feasible(&p, &other, 1e-25);
                            let o = objective(&p, &other);
                            assert!(o >= best - best * 1e-25, "seed {seed}: {o:?} < {best:?}");
                        }
                    }
                }
            }
            let fraction = infeasible as f64 / draws as f64;
            println!(
                "({n}, {m}): {infeasible}/{draws} infeasible ({:.1} %), a maximum active in {some_max_active} of the optima",
                100.0 * fraction
            );
            assert!(
                (0.05..=0.5).contains(&fraction),
                "({n}, {m}): infeasible fraction {fraction}"
            );
        }
    }

    /// Dykstra's alternating projections onto `{A T = b}` and the box converge, in `f64`,
    /// to the point of the intersection nearest to the target (when it is not empty), and
    /// the two iterates stay apart when it is: a wholly different algorithm to compare with.
    #[test]
    fn agrees_with_dykstra_projections() {
        use nalgebra::DVector;
        for &(n, m) in &[(1, 3), (3, 6), (6, 10)] {
            let (mut worst, mut least_gap) = (0.0_f64, f64::INFINITY);
            for seed in 10_000..10_030 {
                let p = random_problem(seed, n, m);
                let a = DMatrix::from_fn(n, m, |i, j| p.a[i][j]);
                let b = DVector::from_fn(n, |i, _| p.b[i].to_f64());
                let aat_inv = (&a * a.transpose()).try_inverse().expect("rank n");
                let onto_plane = |x: &DVector<f64>| x - a.transpose() * (&aat_inv * (&a * x - &b));
                let onto_box = |x: &DVector<f64>| {
                    DVector::from_fn(m, |k, _| x[k].max(p.lower[k]).min(p.upper[k]))
                };
                let mut x = DVector::from_vec(p.target.clone());
                let mut y = x.clone();
                let (mut dp, mut dq) = (DVector::zeros(m), DVector::zeros(m));
                for _ in 0..100_000 {
                    y = onto_plane(&(&x + &dp));
                    dp = &x + &dp - &y;
                    let next = onto_box(&(&y + &dq));
                    dq = &y + &dq - &next;
                    x = next;
                }
                let gap = (&x - &y).norm();
                match solve(&p) {
                    Solution::Optimal(t) => {
                        let t = DVector::from_fn(m, |k, _| t[k].to_f64());
                        let err = (&t - &x).norm() / t.norm();
                        assert!(
                            err < 1e-6 && gap < 1e-6,
                            "seed {seed} ({n}, {m}): {err:e}, gap {gap:e}"
                        );
                        worst = worst.max(err);
                    }
                    Solution::Infeasible => {
                        assert!(
                            gap > 1e-3,
                            "seed {seed} ({n}, {m}): Infeasible, but the gap is {gap:e}"
                        );
                        least_gap = least_gap.min(gap);
                    }
                }
            }
            println!("({n}, {m}): optimum vs Dykstra worst relative {worst:e}; least gap when infeasible {least_gap:e}");
        }
    }

    #[test]
    fn mechanism_file_round_trips() {
        for &(n, m) in &SIZES {
            for seed in [0, 1, 7] {
                let text = mechanism_ron(seed, n, m);
                let model = tendyn_core::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
                let p = random_problem(seed, n, m);
                assert_eq!(model.name(), format!("bounded_{n}x{m}_{seed}"));
                assert_eq!(model.dof(), n);
                assert_eq!(model.structure_matrix(), p.a, "{text}");
                assert_eq!(model.tendons().len(), m);
                for (k, t) in model.tendons().iter().enumerate() {
                    assert_eq!(t.floor, p.lower[k]);
                    assert_eq!(t.max_tension, p.upper[k].is_finite().then_some(p.upper[k]));
                }
            }
        }
    }

    /// A measurement, not a check: how long the enumeration takes at the largest size
    /// (`cargo test -p tendyn-spec --lib bounded -- --ignored --nocapture`).
    #[test]
    #[ignore = "prints timings; asserts nothing"]
    fn solve_time_6x10() {
        let (n, m) = (6, 10);
        let (mut feasible, mut infeasible) = ((0, Duration::ZERO), (0, Duration::ZERO));
        let mut worst = (Duration::ZERO, Duration::ZERO);
        for seed in 0..100 {
            let p = random_problem(1000 + seed, n, m);
            let start = Instant::now();
            let sol = std::hint::black_box(solve(&p));
            let dt = start.elapsed();
            match sol {
                Solution::Optimal(_) => {
                    feasible.0 += 1;
                    feasible.1 += dt;
                    worst.0 = worst.0.max(dt);
                }
                Solution::Infeasible => {
                    infeasible.0 += 1;
                    infeasible.1 += dt;
                    worst.1 = worst.1.max(dt);
                }
            }
        }
        let mean = |(c, d): (u32, Duration)| d.as_secs_f64() / f64::from(c.max(1)) * 1e3;
        println!(
            "solve (6, 10): {} feasible, mean {:.3} ms (worst {:.3} ms); {} infeasible, mean {:.3} ms (worst {:.3} ms)",
            feasible.0,
            mean(feasible),
            worst.0.as_secs_f64() * 1e3,
            infeasible.0,
            mean(infeasible),
            worst.1.as_secs_f64() * 1e3
        );
    }
}
