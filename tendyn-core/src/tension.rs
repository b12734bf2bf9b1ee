//! The unknowns at the base: segment tensions, the system `E x = b` and the tension
//! distribution (paper Eqs. 24b, 33, 35 and the "torque resolver" of its ref. 12).
//!
//! - Every segment tension is the strand's last (ground-level) tension plus what the
//!   idlers between them need to turn (Eq. 24b): across an idler of radius `r` and turn
//!   `s`, `T_in = T_out − s N_axial / r`.
//! - The rows of `E x = b` are the axial balances of each joint, each driving pulley, and
//!   each loop's pretension. `E` is constant (it is the transmission's virtual-work map);
//!   `b` is what the backward recursion leaves over when every unknown is zero.
//! - The solution with least norm is `x₀ = E⁺ b`. Redundant open-ended routings add a
//!   null-space part `N λ` so that every tendon stays at or above its floor; among those,
//!   the one of least norm is chosen. Since `x₀ ⟂ N`, that is the least `|λ|`.

use crate::affine::Affine;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::model::{BodyKind, Model, PulleyRole, Row, Unknown};
use crate::newton_euler::Loads;
use crate::real::{Numeric, Real};

/// Axial moment a pulley needs about its own axis to move as it does (inertia and gravity),
/// taken about its centre: `z · (I ω̇ + ω × I ω + c × m a_c)`.
pub fn axial_demand<T: Real>(model: &Model<T>, motion: &[Motion<T>], body: usize) -> T {
    let b = &model.bodies[body];
    let m = &motion[body];
    let f = m.com_accel.scale(b.mass);
    let n =
        b.inertia.mul_vec(m.omega_dot) + m.omega.cross(b.inertia.mul_vec(m.omega)) + b.com.cross(f);
    b.axis.dot(n)
}

/// Tension of every segment of every strand, affine in the unknowns (Eq. 24b), written
/// into `out[s][k]`.
pub fn segment_tensions<T: Real>(
    model: &Model<T>,
    motion: &[Motion<T>],
    unknowns: usize,
    out: &mut [Vec<Affine<T>>],
) {
    for (s, strand) in model.strands.iter().enumerate() {
        let last = strand.segments.len() - 1;
        let mut t = Affine::unknown(strand.unknown, T::zero(), unknowns);
        out[s][last] = t;
        for k in (0..last).rev() {
            let idler = &strand.idlers[k];
            let step = T::from_f64(idler.turn / idler.radius);
            t = t.add_constant(-(step * axial_demand(model, motion, idler.body)));
            out[s][k] = t;
        }
    }
}

/// `b` of `E x = b`: the constant parts of the balance rows.
pub fn demand<T: Real>(model: &Model<T>, loads: &Loads<T>, out: &mut [T]) {
    let balance = balance_rows(model, loads);
    for (o, r) in out.iter_mut().zip(balance) {
        *o = r.constant;
    }
}

/// The balance rows as affine forms, before motors and explicit tendons are added: for a
/// joint, `τ_j + Σ_coupled c_Pj τ_P`; for a driving pulley, its `τ`; for a loop, its
/// pretension (a constant: the loop's row of `E` carries the strand tensions).
/// Their coefficients are `−E` on the strand columns, which tests check against the
/// transmission's derivation.
pub fn balance_rows<T: Real>(model: &Model<T>, loads: &Loads<T>) -> Vec<Affine<T>> {
    let n_unknowns = model.system.unknowns.len();
    model
        .system
        .rows
        .iter()
        .map(|row| match row {
            Row::Joint(j) => {
                let mut r = loads.axial[*j];
                for (i, b) in model.bodies.iter().enumerate() {
                    if matches!(
                        b.kind,
                        BodyKind::Pulley {
                            role: PulleyRole::Coupled,
                            ..
                        }
                    ) {
                        r = r.add(&loads.axial[i].scale(b.coupling[*j]));
                    }
                }
                r
            }
            Row::Pulley(b) => loads.axial[*b],
            Row::Pretension(l) => {
                Affine::constant(T::from_f64(model.loops[*l].pretension), n_unknowns)
            }
        })
        .collect()
}

/// Minimal-norm solution `x₀ = E⁺ b`.
///
/// A loop's pretension is added exactly rather than through `E⁺`: the two strand columns
/// of a loop are negatives of each other in every row but its pretension row (every term
/// of a strand's rate carries one turn sign, and the two sides turn oppositely everywhere),
/// so both sides at the pretension solve that part of `b` exactly, and that solution is
/// orthogonal to the null space. Passing the pretension through the rounded `E⁺` instead
/// leaves an error of about `u · pretension` in every motor torque.
pub fn minimal_norm<T: Real>(model: &Model<T>, b: &[T], out: &mut [T]) {
    let dynamic = |r: usize| !matches!(model.system.rows[r], Row::Pretension(_));
    for (o, row) in out.iter_mut().zip(&model.system.pseudo_inverse) {
        let mut s = T::zero();
        for (r, (p, v)) in row.iter().zip(b).enumerate() {
            if dynamic(r) {
                s = s + *p * *v;
            }
        }
        *o = s;
    }
    for l in &model.loops {
        for strand in l.strands {
            let k = model.strands[strand].unknown;
            out[k] = out[k] + T::from_f64(l.pretension);
        }
    }
}

/// The floor-respecting distribution for a one-dimensional null space in closed form:
/// `x = x₀ + λ p`, `λ = max(0, max_k (floor_k − x₀_k) / p_k)` over the tendons, `p` the
/// positive null vector. Uses only [`Real::max`], so the code generator can emit it.
/// Returns `λ`.
pub fn lift_to_floor<T: Real>(model: &Model<T>, x: &mut [T]) -> T {
    let p = model
        .system
        .positive_null
        .as_ref()
        .expect("a redundant routing has a positive null vector");
    let mut lambda = T::zero();
    for t in &model.tendons {
        let k = t.unknown;
        let need = (T::from_f64(t.floor) - x[k]) / p[k];
        lambda = lambda.max(need);
    }
    for (xi, pi) in x.iter_mut().zip(p) {
        *xi = *xi + lambda * *pi;
    }
    lambda
}

/// The least-norm solution with every tendon at or above its floor, for a null space of
/// any dimension: minimises `|λ|` subject to `(x₀ + N λ)_k ≥ floor_k` by enumerating
/// active sets (small: a handful of tendons). Writes the result into `x`.
pub fn distribute<T: Numeric>(model: &Model<T>, x: &mut [T]) -> Result<()> {
    let null = &model.system.null_space;
    let d = null.len();
    if d == 0 || model.tendons.is_empty() {
        return Ok(());
    }
    if d == 1 {
        lift_to_floor(model, x);
    } else {
        // g_k = floor_k − x₀_k; constraint rows a_k = N[·][k].
        let cons: Vec<(Vec<T>, T)> = model
            .tendons
            .iter()
            .map(|t| {
                let a: Vec<T> = null.iter().map(|v| v[t.unknown]).collect();
                (a, T::from_f64(t.floor) - x[t.unknown])
            })
            .collect();
        let lambda = least_norm_in_polyhedron(&cons, d).ok_or_else(|| {
            Error::Tension("no distribution keeps every tendon at its floor".into())
        })?;
        for (v, l) in null.iter().zip(&lambda) {
            for (xi, vi) in x.iter_mut().zip(v) {
                *xi = *xi + *l * *vi;
            }
        }
    }
    for t in &model.tendons {
        let v = x[t.unknown];
        if !v.is_finite() {
            return Err(Error::Tension(format!(
                "tension of `{}` is not finite ({})",
                t.name,
                v.to_f64()
            )));
        }
        if let Some(mx) = t.max_tension {
            if v.to_f64() > mx {
                return Err(Error::Tension(format!(
                    "`{}` would need {:.6e} N, above its max_tension {mx} N, to keep every \
                     tendon at or above its floor",
                    t.name,
                    v.to_f64()
                )));
            }
        }
    }
    Ok(())
}

/// Least-norm `λ` with `a_k · λ ≥ g_k` for all constraints, by active-set enumeration.
fn least_norm_in_polyhedron<T: Numeric>(cons: &[(Vec<T>, T)], d: usize) -> Option<Vec<T>> {
    let m = cons.len();
    let feasible = |l: &[T]| {
        cons.iter().all(|(a, g)| {
            let v = a.iter().zip(l).fold(T::zero(), |s, (x, y)| s + *x * *y);
            let scale = g.abs().to_f64().max(1.0);
            (v - *g).to_f64() >= -1e-12 * scale
        })
    };
    let zero = vec![T::zero(); d];
    if feasible(&zero) {
        return Some(zero);
    }
    for size in 1..=d.min(m) {
        let mut idx: Vec<usize> = (0..size).collect();
        loop {
            if let Some(l) = candidate(cons, &idx, d) {
                if feasible(&l) {
                    return Some(l);
                }
            }
            if !next_combination(&mut idx, m) {
                break;
            }
        }
    }
    None
}

/// The least-norm point on the active constraints `idx` (`λ = A_Sᵀ μ` with
/// `(A_S A_Sᵀ) μ = g_S`), if they are independent and their multipliers `μ` are
/// non-negative (otherwise this active set is not the optimum's).
fn candidate<T: Numeric>(cons: &[(Vec<T>, T)], idx: &[usize], d: usize) -> Option<Vec<T>> {
    let dot = |a: &[T], b: &[T]| a.iter().zip(b).fold(T::zero(), |s, (x, y)| s + *x * *y);
    let gram: Vec<Vec<T>> = idx
        .iter()
        .map(|&i| idx.iter().map(|&j| dot(&cons[i].0, &cons[j].0)).collect())
        .collect();
    let rhs: Vec<T> = idx.iter().map(|&i| cons[i].1).collect();
    let mu = crate::transmission::linalg::cholesky_solve(&gram, &rhs)?;
    if mu.iter().any(|&u| u < T::zero()) {
        return None;
    }
    let mut l = vec![T::zero(); d];
    for (k, &i) in idx.iter().enumerate() {
        for (lv, a) in l.iter_mut().zip(&cons[i].0) {
            *lv = *lv + mu[k] * *a;
        }
    }
    Some(l)
}

/// Advances `idx` (strictly increasing indices below `m`) to the next combination in
/// lexicographic order; `false` after the last one.
fn next_combination(idx: &mut [usize], m: usize) -> bool {
    let k = idx.len();
    for i in (0..k).rev() {
        if idx[i] < m - k + i {
            idx[i] += 1;
            for j in i + 1..k {
                idx[j] = idx[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

/// Whether unknown `k` is a tension of an open-ended tendon.
pub fn is_tendon_unknown<T>(model: &Model<T>, k: usize) -> bool {
    matches!(model.system.unknowns[k], Unknown::Explicit(_))
        || model.tendons.iter().any(|t| t.unknown == k)
}
