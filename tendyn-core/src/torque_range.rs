//! The static torque range: what the open-ended tendons alone can do on each joint at rest.
//!
//! # Definition
//! Tendon `k` carries a tension `T_k` with `floor_k ≤ T_k ≤ max_tension_k` (no upper bound
//! where `max_tension` is `None`); the structure matrix `A` (n × K) maps the tensions to
//! generalized forces, `Q = A T` (N·m). The static torque range of joint `j` is the
//! interval
//!
//! ```text
//! [ min (A T)_j , max (A T)_j ]   over   floor ≤ T ≤ max_tension,  (A T)_i = 0 for every i ≠ j
//! ```
//!
//! the generalized force the tendons can put on joint `j` while they hold every other joint
//! with zero generalized force ("the others at rest"). It is a property of the transmission
//! only: motors, loops, gravity and inertia are left out, so it says what the tendons alone
//! can do on a mechanism at rest, not what a motion needs. An endpoint is `±∞` when tendons
//! without a maximum can raise it without bound; no interval exists (`None`) when no tension
//! within the bounds holds the other joints at zero.
//!
//! # Why a linear program
//! The tensions allowed form a polytope (a box cut by the `n − 1` equalities), and `(A T)_j`
//! is linear in `T`: each endpoint is the optimum of a linear objective over a polytope, a
//! linear program, solved here by the simplex method of `microlp`. Its answer distinguishes
//! the three cases of an LP: an optimum (at a vertex of the polytope), an unbounded
//! objective (an infinite endpoint) and an empty polytope (`None`).
//!
//! # Numerics
//! Entries of `A` at most `1e-12 · max|A|` are round-off of the geometry and taken as exact
//! zeros; every equality row is scaled by its largest entry (which changes no solution).
//! An endpoint is recomputed in `f64` as `Σ_k A_jk T_k` from the tensions of the optimum,
//! and set to exactly `0` when it is below `1e-9 · Σ_k |A_jk T_k|` (a joint the tendons cannot
//! move while the others are held). Should the solver fail numerically (a model far outside
//! its recommended coefficient range, or a non-finite number in the model), that endpoint is
//! `NaN`; nothing here panics.

use crate::model::Model;
use microlp::{ComparisonOp, Error as LpError, OptimizationDirection, Problem, SolveOutcome};

/// The interval of generalized force on one joint (N·m).
///
/// `min` may be `-f64::INFINITY` and `max` `f64::INFINITY` (unbounded); `NaN` only where
/// the LP solver failed numerically.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorqueRange {
    /// The least generalized force the tendons can put on the joint (N·m).
    pub min: f64,
    /// The greatest generalized force the tendons can put on the joint (N·m).
    pub max: f64,
}

/// The static torque range of every joint, in joint order (see the [module](self)
/// documentation for the definition): `None` for a joint where no tension within the
/// tendons' bounds holds every other joint at zero generalized force.
///
/// Without open-ended tendons every range is `[0, 0]`.
pub fn static_torque_ranges(model: &Model<f64>) -> Vec<Option<TorqueRange>> {
    let n = model.dof;
    let tendons = &model.tendons;
    let entry = |j: usize, k: usize| tendons[k].structure.get(j).copied().unwrap_or(0.0);
    let largest = (0..n)
        .flat_map(|j| (0..tendons.len()).map(move |k| (j, k)))
        .map(|(j, k)| entry(j, k).abs())
        .fold(0.0, f64::max);
    let tiny = 1e-12 * largest;
    let a: Vec<Vec<f64>> = (0..n)
        .map(|j| {
            (0..tendons.len())
                .map(|k| {
                    let x = entry(j, k);
                    if x.abs() <= tiny {
                        0.0
                    } else {
                        x
                    }
                })
                .collect()
        })
        .collect();
    let bounds: Vec<(f64, f64)> = tendons
        .iter()
        .map(|t| (t.floor, t.max_tension.unwrap_or(f64::INFINITY)))
        .collect();
    (0..n).map(|j| joint_range(&a, &bounds, j)).collect()
}

/// One endpoint of one joint's range, as the LP answered.
enum Endpoint {
    Value(f64),
    Unbounded,
    Infeasible,
    Failed,
}

fn joint_range(a: &[Vec<f64>], bounds: &[(f64, f64)], j: usize) -> Option<TorqueRange> {
    if bounds.is_empty() {
        return Some(TorqueRange { min: 0.0, max: 0.0 });
    }
    let max = match endpoint(a, bounds, j, OptimizationDirection::Maximize) {
        Endpoint::Value(v) => v,
        Endpoint::Unbounded => f64::INFINITY,
        Endpoint::Infeasible => return None,
        Endpoint::Failed => f64::NAN,
    };
    let min = match endpoint(a, bounds, j, OptimizationDirection::Minimize) {
        Endpoint::Value(v) => v,
        Endpoint::Unbounded => f64::NEG_INFINITY,
        // The feasible set does not depend on the direction: an infeasible minimum after a
        // feasible maximum is the solver contradicting itself, reported as such.
        Endpoint::Infeasible | Endpoint::Failed => f64::NAN,
    };
    Some(TorqueRange { min, max })
}

/// Optimizes `(A T)_j` over `bounds` with `(A T)_i = 0` for `i ≠ j`.
fn endpoint(
    a: &[Vec<f64>],
    bounds: &[(f64, f64)],
    j: usize,
    direction: OptimizationDirection,
) -> Endpoint {
    let mut lp = Problem::new(direction);
    let vars: Vec<_> = bounds
        .iter()
        .zip(&a[j])
        .map(|(&b, &c)| lp.add_var(c, b))
        .collect();
    for (i, row) in a.iter().enumerate() {
        let scale = row.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        if i == j || scale == 0.0 {
            continue; // a row of zeros holds its joint at zero whatever the tensions
        }
        let terms: Vec<_> = vars
            .iter()
            .zip(row)
            .filter(|(_, &x)| x != 0.0)
            .map(|(&v, &x)| (v, x / scale))
            .collect();
        lp.add_constraint(terms.as_slice(), ComparisonOp::Eq, 0.0);
    }
    match lp.solve() {
        Ok(SolveOutcome::Solution(s)) => {
            let (mut value, mut size) = (0.0, 0.0);
            for (&v, &c) in vars.iter().zip(&a[j]) {
                let term = c * s.var_value(v);
                value += term;
                size += term.abs();
            }
            if value.abs() <= 1e-9 * size {
                value = 0.0; // also turns -0 into 0
            }
            Endpoint::Value(value)
        }
        Ok(SolveOutcome::Interrupted(_)) => Endpoint::Failed, // no limits are set
        Err(LpError::Unbounded) => Endpoint::Unbounded,
        Err(LpError::Infeasible) => Endpoint::Infeasible,
        Err(_) => Endpoint::Failed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_JOINTS: &str = r#"(
        name: "two", gravity: (0.0, 0.0, -9.81), tension_floor: 1.0,
        links: [
            (name: "l1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0, com: (-0.15, 0.0, 0.0), inertia: (xx: 0.001, yy: 0.008, zz: 0.008)),
            (name: "l2", dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: 0.5, com: (-0.1, 0.0, 0.0), inertia: (xx: 0.001, yy: 0.004, zz: 0.004)),
        ],
        tendons: [
            (name: "a", structure: [0.02, 0.01], max_tension: 10.0),
            (name: "b", structure: [-0.02, 0.0]),
            (name: "c", structure: [0.0, -0.01], max_tension: 20.0),
        ],
    )"#;

    #[test]
    fn unbounded_and_bounded_endpoints() {
        let m = crate::parse(TWO_JOINTS).unwrap();
        let r = static_torque_ranges(&m);
        // Joint 1 with joint 2 held: Tc = Ta ∈ [1, 10], Tb ≥ 1: Q1 = 0.02 (Ta − Tb).
        let r1 = r[0].unwrap();
        assert_eq!(r1.min, f64::NEG_INFINITY);
        assert!((r1.max - 0.02 * 9.0).abs() < 1e-12, "{r1:?}");
        // Joint 2 with joint 1 held: Tb = Ta ∈ [1, 10]; Q2 = 0.01 (Ta − Tc), Tc ∈ [1, 20].
        let r2 = r[1].unwrap();
        assert!((r2.min - 0.01 * (1.0 - 20.0)).abs() < 1e-12, "{r2:?}");
        assert!((r2.max - 0.01 * 9.0).abs() < 1e-12, "{r2:?}");
    }

    #[test]
    fn infeasible_and_exactly_zero() {
        let mut m = crate::parse(TWO_JOINTS).unwrap();
        // Tendon c alone pulls joint 2 one way and its floor cannot be balanced once a
        // can no longer pull back: no tension holds joint 2 at zero.
        m.tendons[0].structure = vec![0.02, 0.0];
        assert_eq!(static_torque_ranges(&m)[0], None);
        // Joint 2 driven by nothing: its range is exactly zero.
        m.tendons[2].structure = vec![0.0, 0.0];
        let r = static_torque_ranges(&m);
        assert_eq!(r[1], Some(TorqueRange { min: 0.0, max: 0.0 }));
        m.tendons.clear();
        assert_eq!(
            static_torque_ranges(&m),
            vec![Some(TorqueRange { min: 0.0, max: 0.0 }); 2]
        );
    }

    #[test]
    fn non_finite_input_gives_nan_not_a_panic() {
        let mut m = crate::parse(TWO_JOINTS).unwrap();
        m.tendons[0].floor = f64::NAN;
        m.tendons[1].structure = vec![f64::INFINITY];
        let _ = static_torque_ranges(&m);
    }
}
