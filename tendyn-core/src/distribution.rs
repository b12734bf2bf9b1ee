//! The tension distribution of generated code for null spaces of more than one dimension:
//! fixed-size, allocation-free and `no_std`, so it runs on the controllers the generated
//! code is for. (One-dimensional null spaces are distributed in closed form by the
//! generated code itself.)
//!
//! Given the minimal-norm tensions `x₀` of `K` tendons and an orthonormal basis `N` of the
//! null space restricted to them (`D` vectors), it returns `x₀ + Nᵀλ` with the least `|λ|`
//! such that every tension is at or above its floor. Since `x₀ ⟂ N`, that is the least-norm
//! tension vector meeting the floors — the same choice as the runtime solver's.
//!
//! The optimum has an active set of at most `D` independent floors with non-negative
//! multipliers; the routine enumerates candidate sets by size and returns the first whose
//! point is feasible. `K` is small (a handful of tendons), so this is at most `2^K` tiny
//! solves.

// Index loops read like the algorithm over index sets.
#![allow(clippy::needless_range_loop)]

use crate::real::Real;

/// Least-norm tensions at or above `floor`. `null[d][k]` is component `k` of null-space
/// vector `d`. Returns `x0` unchanged when it already meets every floor. If no active set
/// qualifies (which a controllable routing rules out) the result is `x0` lifted along the
/// first null vector as far as the worst floor needs.
pub fn least_norm_with_floor<T: Real + PartialOrd, const K: usize, const D: usize>(
    x0: [T; K],
    null: &[[f64; K]; D],
    floor: &[f64; K],
) -> [T; K] {
    let n = |d: usize, k: usize| T::from_f64(null[d][k]);
    // g_k = floor_k − x0_k: constraint k reads a_k · λ ≥ g_k with a_k = (null[·][k]).
    let mut g = [T::zero(); K];
    for k in 0..K {
        g[k] = T::from_f64(floor[k]) - x0[k];
    }
    let tolerance = |gk: T| T::from_f64(1e-12) * (gk.max(-gk)).max(T::one());
    let feasible = |lambda: &[T; D]| {
        (0..K).all(|k| {
            let mut v = T::zero();
            for d in 0..D {
                v = v + n(d, k) * lambda[d];
            }
            v - g[k] >= -tolerance(g[k])
        })
    };
    let apply = |lambda: &[T; D]| {
        let mut x = x0;
        for k in 0..K {
            for d in 0..D {
                x[k] = x[k] + n(d, k) * lambda[d];
            }
        }
        x
    };
    let zero = [T::zero(); D];
    if feasible(&zero) {
        return x0;
    }
    for size in 1..=D.min(K) {
        for mask in 1u32..(1u32 << K) {
            if mask.count_ones() as usize != size {
                continue;
            }
            if let Some(lambda) = candidate::<T, K, D>(mask, null, &g) {
                if feasible(&lambda) {
                    return apply(&lambda);
                }
            }
        }
    }
    // Unreachable for a controllable routing; stay taut rather than return nonsense.
    let mut lambda = zero;
    for k in 0..K {
        let a = n(0, k);
        if a > T::zero() {
            lambda[0] = lambda[0].max(g[k] / a);
        }
    }
    apply(&lambda)
}

/// The least-norm point on the floors in `mask`: `λ = A_Sᵀ μ` with `(A_S A_Sᵀ) μ = g_S`, if
/// they are independent and `μ ≥ 0`.
fn candidate<T: Real + PartialOrd, const K: usize, const D: usize>(
    mask: u32,
    null: &[[f64; K]; D],
    g: &[T; K],
) -> Option<[T; D]> {
    let mut idx = [0usize; D];
    let mut s = 0;
    for (k, slot) in (0..K).filter(|k| mask & (1 << k) != 0).zip(0..D) {
        idx[slot] = k;
        s += 1;
    }
    let a = |i: usize, d: usize| T::from_f64(null[d][idx[i]]);
    // Gram matrix and its Cholesky factor, in place (s ≤ D).
    let mut l = [[T::zero(); D]; D];
    for i in 0..s {
        for j in 0..=i {
            let mut v = T::zero();
            for d in 0..D {
                v = v + a(i, d) * a(j, d);
            }
            for m in 0..j {
                v = v - l[i][m] * l[j][m];
            }
            if i == j {
                if v <= T::from_f64(1e-24) {
                    return None;
                }
                l[i][i] = v.sqrt();
            } else {
                l[i][j] = v / l[j][j];
            }
        }
    }
    let mut mu = [T::zero(); D];
    for i in 0..s {
        let mut v = g[idx[i]];
        for m in 0..i {
            v = v - l[i][m] * mu[m];
        }
        mu[i] = v / l[i][i];
    }
    for i in (0..s).rev() {
        let mut v = mu[i];
        for m in i + 1..s {
            v = v - l[m][i] * mu[m];
        }
        mu[i] = v / l[i][i];
    }
    if mu[..s].iter().any(|&m| m < T::zero()) {
        return None;
    }
    let mut lambda = [T::zero(); D];
    for i in 0..s {
        for d in 0..D {
            lambda[d] = lambda[d] + mu[i] * a(i, d);
        }
    }
    Some(lambda)
}
