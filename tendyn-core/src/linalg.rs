//! The small dense factorisations the method needs, written once, generic over the scalar
//! and allocation-free (`no_std`, no `alloc`): every matrix is a row-major slice and every
//! result goes into a buffer the caller sized, so they serve the runtime solver in any
//! precision, the symbolic scalar that traces them for generated code, and code without a
//! heap alike.
//!
//! - [`pseudo_inverse_and_null_space`]: Householder QR of `Eᵀ` (the condition number is
//!   not squared), for the tension system `E x = b` (paper Eq. 33): `E⁺ = Eᵀ(EEᵀ)⁻¹` and an
//!   orthonormal basis of `null(E)`;
//! - [`cholesky_solve`]: the checked Cholesky factorisation of the runtime's forward
//!   dynamics (`M q̈ = τ − h`, which fails on a matrix that is not positive definite);
//! - [`ldlt_solve`]: `L D Lᵀ` without pivoting or checks, branch-free, which the code
//!   generator traces for generated forward dynamics.
//!
//! Where `std` is available and the job is diagnosis rather than the method (the rank and
//! singular values of a structure matrix in validation), nalgebra serves instead.

// Index loops read like the textbook algorithms here.
#![allow(clippy::needless_range_loop)]

use crate::real::{Numeric, Real};

/// `Σ aᵢ bᵢ`, in index order.
pub fn dot<T: Real>(a: &[T], b: &[T]) -> T {
    a.iter().zip(b).fold(T::zero(), |s, (x, y)| s + *x * *y)
}

/// Reals of work [`pseudo_inverse_and_null_space`] needs for an `r × m` matrix.
pub const fn qr_work(r: usize, m: usize) -> usize {
    m * r + m * m + m + r
}

/// The pseudo-inverse `Eᵀ(EEᵀ)⁻¹` (`m × r`, into `pinv`) and an orthonormal basis of the
/// null space (`m − r` rows of `m`, into `null`) of a full-row-rank `E` (`r × m`, `r ≤ m`,
/// row-major in `e`), by Householder QR of `Eᵀ = Q R`: `E⁺ = Q₁ R⁻ᵀ`, the null space the
/// last `m − r` columns of `Q`. `work` holds [`qr_work`]`(r, m)` reals. Returns `false`,
/// writing nothing, if a buffer is too short or `r > m`.
pub fn pseudo_inverse_and_null_space<T: Numeric>(
    e: &[T],
    r: usize,
    m: usize,
    work: &mut [T],
    pinv: &mut [T],
    null: &mut [T],
) -> bool {
    if r > m
        || e.len() < r * m
        || work.len() < qr_work(r, m)
        || pinv.len() < m * r
        || null.len() < (m - r) * m
    {
        return false;
    }
    let (a, rest) = work.split_at_mut(m * r);
    let (q, rest) = rest.split_at_mut(m * m);
    let (v, y) = rest.split_at_mut(m);
    // a = Eᵀ (m × r), factorized in place; q accumulates the Householder reflections.
    for i in 0..m {
        for j in 0..r {
            a[i * r + j] = e[j * m + i];
        }
        for k in 0..m {
            q[i * m + k] = if i == k { T::one() } else { T::zero() };
        }
    }
    let two = T::from_f64(2.0);
    for col in 0..r {
        let mut norm2 = T::zero();
        for i in col..m {
            norm2 = norm2 + a[i * r + col] * a[i * r + col];
        }
        let norm = norm2.sqrt();
        if norm == T::zero() {
            continue;
        }
        let alpha = if a[col * r + col] > T::zero() {
            -norm
        } else {
            norm
        };
        for i in 0..m {
            v[i] = if i < col { T::zero() } else { a[i * r + col] };
        }
        v[col] = v[col] - alpha;
        let mut vnorm2 = T::zero();
        for i in col..m {
            vnorm2 = vnorm2 + v[i] * v[i];
        }
        if vnorm2 == T::zero() {
            continue;
        }
        for j in 0..r {
            let mut s = T::zero();
            for i in col..m {
                s = s + v[i] * a[i * r + j];
            }
            let f = two * s / vnorm2;
            for i in col..m {
                a[i * r + j] = a[i * r + j] - f * v[i];
            }
        }
        // q ← q · H (H symmetric), so that Eᵀ = q · R.
        for row in q.chunks_exact_mut(m) {
            let mut s = T::zero();
            for i in col..m {
                s = s + row[i] * v[i];
            }
            let f = two * s / vnorm2;
            for i in col..m {
                row[i] = row[i] - f * v[i];
            }
        }
    }
    // E⁺ = Q₁ R⁻ᵀ: column i solves Rᵀ y = e_i, then Q₁ y.
    for i in 0..r {
        for k in 0..r {
            let mut s = if k == i { T::one() } else { T::zero() };
            for l in 0..k {
                s = s - a[l * r + k] * y[l];
            }
            y[k] = s / a[k * r + k];
        }
        for row in 0..m {
            let mut s = T::zero();
            for k in 0..r {
                s = s + q[row * m + k] * y[k];
            }
            pinv[row * r + i] = s;
        }
    }
    for k in r..m {
        for i in 0..m {
            null[(k - r) * m + i] = q[i * m + k];
        }
    }
    true
}

/// [`pseudo_inverse_and_null_space`] of `E` given as `r` rows of `m` (`r ≤ m`), with the
/// pseudo-inverse as `m` rows of `r` and the null-space basis as `m − r` rows of `m`: the
/// form the model keeps them in.
#[cfg(feature = "std")]
pub fn pseudo_inverse_and_null_space_of_rows<T: Numeric>(
    e: &[Vec<T>],
) -> (Vec<Vec<T>>, Vec<Vec<T>>) {
    let r = e.len();
    let m = e.first().map_or(0, Vec::len);
    let flat: Vec<T> = e.iter().flat_map(|row| row.iter().copied()).collect();
    let mut work = vec![T::zero(); qr_work(r, m)];
    let (mut pinv, mut null) = (
        vec![T::zero(); m * r],
        vec![T::zero(); m.saturating_sub(r) * m],
    );
    if !pseudo_inverse_and_null_space(&flat, r, m, &mut work, &mut pinv, &mut null) {
        return (Vec::new(), Vec::new());
    }
    let rows = |flat: Vec<T>, width: usize| -> Vec<Vec<T>> {
        flat.chunks(width.max(1)).map(<[T]>::to_vec).collect()
    };
    (rows(pinv, r), rows(null, m))
}

/// Solves `M x = b` for a symmetric positive definite `M` (`n × n`, row-major, `n` =
/// `x.len()`) by Cholesky: `m`'s lower triangle is overwritten by `L`, `x` holds `b` on
/// entry and the solution on return. Returns `false` when `M` is not positive definite to
/// working precision (a pivot `≤ 0` or not finite), or `m` is too short.
pub fn cholesky_solve<T: Numeric>(m: &mut [T], x: &mut [T]) -> bool {
    let ok = cholesky_factor(m, x.len());
    if ok {
        cholesky_substitute(m, x);
    }
    ok
}

/// The checked Cholesky factor `L` of [`cholesky_solve`], in `m`'s lower triangle; `false`
/// where `M` is not positive definite to working precision or `m` is too short. Factor
/// once and [`cholesky_substitute`] for each right-hand side.
pub fn cholesky_factor<T: Numeric>(m: &mut [T], n: usize) -> bool {
    if m.len() < n * n {
        return false;
    }
    for i in 0..n {
        for j in 0..=i {
            let mut s = m[i * n + j];
            for k in 0..j {
                s = s - m[i * n + k] * m[j * n + k];
            }
            if i == j {
                if s <= T::zero() || !s.is_finite() {
                    return false;
                }
                m[i * n + i] = s.sqrt();
            } else {
                m[i * n + j] = s / m[j * n + j];
            }
        }
    }
    true
}

/// `x ← M⁻¹ x` from the factor [`cholesky_factor`] left (`n = x.len()`).
pub fn cholesky_substitute<T: Real>(factor: &[T], x: &mut [T]) {
    let n = x.len();
    let m = &factor[..n * n];
    // L y = b, then Lᵀ x = y, in place.
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s = s - m[i * n + k] * x[k];
        }
        x[i] = s / m[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s = s - m[k * n + i] * x[k];
        }
        x[i] = s / m[i * n + i];
    }
}

/// Solves `M x = b` (`n × n`, row-major, `n = x.len()`, overwritten) by Gaussian
/// elimination without pivoting or checks: for matrices whose leading minors stay far from
/// zero, such as the identity plus a small coupling (forward dynamics' idlers behind guides
/// with friction, [`crate::dynamics::accelerations`]). Straight-line, so the code generator
/// can trace it. `m` must hold `n²` reals.
pub fn gauss_solve<T: Real>(m: &mut [T], x: &mut [T]) {
    lu_factor(m, x.len());
    lu_substitute(m, x);
}

/// The `L U` factors of `m` (`n × n`, row-major) in place, by Gaussian elimination without
/// pivoting or checks: `U` on and above the diagonal, the multipliers of the unit lower
/// `L` below it. Factor once and [`lu_substitute`] for each right-hand side. Where the
/// leading minors of `m` itself may vanish, order its rows first (as a pivoting
/// elimination of a nearby matrix would: [`crate::tension::Elimination`]).
pub fn lu_factor<T: Real>(m: &mut [T], n: usize) {
    let m = &mut m[..n * n];
    for j in 0..n {
        for i in j + 1..n {
            let f = m[i * n + j] / m[j * n + j];
            m[i * n + j] = f;
            for k in j + 1..n {
                m[i * n + k] = m[i * n + k] - f * m[j * n + k];
            }
        }
    }
}

/// Solves `L U x = b` with the factors of [`lu_factor`]; `x` holds `b` on entry.
pub fn lu_substitute<T: Real>(factors: &[T], x: &mut [T]) {
    let n = x.len();
    let m = &factors[..n * n];
    for i in 0..n {
        for k in 0..i {
            x[i] = x[i] - m[i * n + k] * x[k];
        }
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s = s - m[i * n + k] * x[k];
        }
        x[i] = s / m[i * n + i];
    }
}

/// Solves `M x = b` by `L D Lᵀ` without pivoting or checks, as generated code does (the
/// code generator traces it; the runtime solver uses [`cholesky_solve`]): `m` (`n × n`,
/// row-major, `n = x.len()`) is overwritten by `L` below its diagonal and `D` on it, `x`
/// holds `b` on entry and the solution on return. `m` must hold `n²` reals.
pub fn ldlt_solve<T: Real>(m: &mut [T], x: &mut [T]) {
    ldlt_factor(m, x.len());
    ldlt_substitute(m, x);
}

/// The `L D Lᵀ` factors of `m` (`n × n`, row-major) in place: `L` below the diagonal, `D`
/// on it; no pivoting, no checks. Factor once and [`ldlt_substitute`] for each right-hand
/// side.
pub fn ldlt_factor<T: Real>(m: &mut [T], n: usize) {
    let m = &mut m[..n * n];
    for j in 0..n {
        let mut dj = m[j * n + j];
        for k in 0..j {
            dj = dj - m[j * n + k] * m[j * n + k] * m[k * n + k];
        }
        m[j * n + j] = dj;
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s = s - m[i * n + k] * m[j * n + k] * m[k * n + k];
            }
            m[i * n + j] = s / dj;
        }
    }
}

/// Solves `L D Lᵀ x = b` with the factors of [`ldlt_factor`]; `x` holds `b` on entry.
pub fn ldlt_substitute<T: Real>(factors: &[T], x: &mut [T]) {
    let n = x.len();
    let m = &factors[..n * n];
    for i in 0..n {
        for k in 0..i {
            x[i] = x[i] - m[i * n + k] * x[k];
        }
    }
    for i in 0..n {
        x[i] = x[i] / m[i * n + i];
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            x[i] = x[i] - m[k * n + i] * x[k];
        }
    }
}

/// The orthogonal projection of `v` onto the span of the orthonormal rows of `basis`
/// (each of `v.len()` reals), into `out`.
pub fn project_onto<T: Real>(v: &[T], basis: &[T], out: &mut [T]) {
    let n = v.len();
    for o in out.iter_mut() {
        *o = T::zero();
    }
    if n == 0 {
        return;
    }
    for b in basis.chunks_exact(n) {
        let c = dot(v, b);
        for (o, y) in out.iter_mut().zip(b) {
            *o = *o + c * *y;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Not symmetric: `[[2, 1, 0], [1, 3, 1], [0, 1, 4]]` with its (1, 2) entry 2 instead
    /// of 1, `x = (1, 2, 1)` gives `b = (4, 9, 6)` (by hand).
    #[test]
    fn gauss_solves_an_unsymmetric_system() {
        let mut m = [2.0, 1.0, 0.0, 1.0, 3.0, 2.0, 0.0, 1.0, 4.0];
        let mut x = [4.0, 9.0, 6.0];
        gauss_solve(&mut m, &mut x);
        for (got, want) in x.iter().zip([1.0, 2.0, 1.0]) {
            assert!((got - want).abs() <= 8.0 * f64::EPSILON, "{x:?}");
        }
    }

    /// `E = [[1, 1, 0], [0, 1, 1]]`: `E E⁺ = I`, the null space `±(1, −1, 1)/√3`, by hand.
    #[test]
    fn the_pseudo_inverse_inverts_and_the_null_space_is_by_hand() {
        let e = [1.0, 1.0, 0.0, 0.0, 1.0, 1.0];
        let (mut work, mut pinv, mut null) = ([0.0; qr_work(2, 3)], [0.0; 6], [0.0; 3]);
        assert!(pseudo_inverse_and_null_space(
            &e, 2, 3, &mut work, &mut pinv, &mut null
        ));
        for i in 0..2 {
            for j in 0..2 {
                let eij: f64 = (0..3).map(|k| e[i * 3 + k] * pinv[k * 2 + j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((eij - want).abs() < 1e-15, "(E E⁺)[{i}][{j}] = {eij}");
            }
        }
        let s = null[0].signum() / 3.0f64.sqrt();
        for (x, want) in null.iter().zip([s, -s, s]) {
            assert!((x - want).abs() < 1e-15, "{null:?}");
        }
    }

    /// `M = [[4, 2], [2, 3]]`, `b = (2, 1)`: `x = (1/2, 0)`, by hand, both ways.
    #[test]
    fn both_solvers_solve_a_small_system_by_hand() {
        let m = [4.0, 2.0, 2.0, 3.0];
        let (mut a, mut x) = (m, [2.0, 1.0]);
        assert!(cholesky_solve(&mut a, &mut x));
        assert_eq!(x, [0.5, 0.0]);
        let (mut a, mut x) = (m, [2.0, 1.0]);
        ldlt_solve(&mut a, &mut x);
        assert_eq!(x, [0.5, 0.0]);
    }

    #[test]
    fn cholesky_refuses_a_matrix_that_is_not_positive_definite() {
        let mut x = [1.0, 1.0];
        assert!(!cholesky_solve(&mut [1.0, 2.0, 2.0, 1.0], &mut x));
        assert!(!cholesky_solve(&mut [1.0, 0.0, 0.0, f64::NAN], &mut x));
        assert!(!cholesky_solve(&mut [1.0], &mut x), "too short");
    }

    #[test]
    fn short_buffers_are_refused_not_a_panic() {
        let e = [1.0, 1.0, 0.0, 0.0, 1.0, 1.0];
        let (mut work, mut pinv, mut null) = ([0.0; 3], [0.0; 6], [0.0; 3]);
        assert!(!pseudo_inverse_and_null_space(
            &e, 2, 3, &mut work, &mut pinv, &mut null
        ));
        assert!(!pseudo_inverse_and_null_space(
            &e, 3, 2, &mut work, &mut pinv, &mut null
        ));
    }
}
