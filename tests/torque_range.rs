//! The static torque range (`tendyn_core::torque_range`): for each joint `j`, the interval of
//! `(A T)_j` over `floor ≤ T ≤ max_tension` with `(A T)_i = 0` for every other joint `i`.
//!
//! Checked against hand derivations and, for random systems, against a brute-force
//! enumeration of the vertices of the polytope of allowed tensions, which shares nothing with
//! the linear program.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::Model;
use tendyn_core::torque_range::{static_torque_ranges, TorqueRange};

/// A mechanism of `n` planar links (dynamics irrelevant here) and structure-only tendons
/// `(structure column, floor, max_tension)`, plus `extra` (motors, ...).
fn mechanism(n: usize, tendons: &[(Vec<f64>, f64, Option<f64>)], extra: &str) -> String {
    let links: String = (1..=n)
        .map(|i| {
            format!(
                "(name: \"l{i}\", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0, \
                 com: (-0.15, 0.0, 0.0), inertia: (xx: 0.001, yy: 0.008, zz: 0.008)),\n"
            )
        })
        .collect();
    let tendons: String = tendons
        .iter()
        .enumerate()
        .map(|(k, (col, floor, max))| {
            let col: Vec<String> = col.iter().map(|x| format!("{x:?}")).collect();
            let max = max.map_or(String::new(), |m| format!(", max_tension: {m:?}"));
            format!(
                "(name: \"t{k}\", structure: [{}], floor: {floor:?}{max}),\n",
                col.join(", ")
            )
        })
        .collect();
    format!(
        "(name: \"ranges\", gravity: (0.0, 0.0, -9.81),\n links: [\n{links}],\n \
         tendons: [\n{tendons}],\n{extra})"
    )
}

fn ranges(text: &str) -> Vec<Option<TorqueRange>> {
    static_torque_ranges(&tendyn_core::parse(text).unwrap_or_else(|e| panic!("{e}\n{text}")))
}

fn close(x: f64, y: f64) -> bool {
    x == y || (x - y).abs() <= 1e-12 * (1.0 + y.abs())
}

fn assert_range(r: Option<TorqueRange>, min: f64, max: f64) {
    let r = r.expect("a range");
    assert!(
        close(r.min, min) && close(r.max, max),
        "{r:?}, expected [{min}, {max}]"
    );
}

/// One joint, three tendons. With no other joint to hold, the tensions range over the box
/// `floor ≤ T ≤ max` and `Q = Σ_k A_k T_k` is a sum of independent terms: its extremes are
/// the sums of each term's extremes, `A_k floor_k` or `A_k max_k` whichever is larger
/// (smaller), and `±∞` from a tendon without maximum, upwards when `A_k > 0`, downwards
/// when `A_k < 0`.
///
/// `A = [0.02, 0.03, −0.025]`, floors 2, 4, 2:
/// - maxima 10, 20, 30: `t0 ∈ [0.04, 0.2]`, `t1 ∈ [0.12, 0.6]`, `t2 ∈ [−0.75, −0.05]`:
///   `Q ∈ [0.04 + 0.12 − 0.75, 0.2 + 0.6 − 0.05] = [−0.59, 0.75]`;
/// - `t1` without maximum: `Q ∈ [−0.59, ∞)`;
/// - `t2` without maximum as well: `Q ∈ (−∞, ∞)`.
#[test]
fn one_joint_the_range_is_the_sum_of_each_tendons_extremes() {
    let a = [0.02, 0.03, -0.025];
    let floors = [2.0, 4.0, 2.0];
    let t = |max: [Option<f64>; 3]| -> Vec<(Vec<f64>, f64, Option<f64>)> {
        (0..3).map(|k| (vec![a[k]], floors[k], max[k])).collect()
    };
    let r = ranges(&mechanism(1, &t([Some(10.0), Some(20.0), Some(30.0)]), ""));
    assert_range(r[0], 0.04 + 0.12 - 0.75, 0.2 + 0.6 - 0.05);
    let r = ranges(&mechanism(1, &t([Some(10.0), None, Some(30.0)]), ""));
    assert_range(r[0], 0.04 + 0.12 - 0.75, f64::INFINITY);
    let r = ranges(&mechanism(1, &t([Some(10.0), None, None]), ""));
    assert_range(r[0], f64::NEG_INFINITY, f64::INFINITY);
}

/// The paper's Example 2 structure (rows joint 1, joint 2; tendons T32, T42, T11):
/// `A = [[−0.03, −0.03, 0.04], [0.02, −0.02, 0]]`, every floor 5, T11 at most 100 N, T32 and
/// T42 without maximum.
///
/// Joint 2 alone could take any torque (T32 or T42 without bound). Holding joint 1 at zero
/// ties them to T11: `0.03 (T32 + T42) = 0.04 T11`, so `S = T32 + T42 = (4/3) T11 ≤ 400/3`;
/// `Q2 = 0.02 (T32 − T42)` is largest with T42 at its floor: `0.02 (S − 10) = 0.02 (400/3 −
/// 10) = 2.4667`, and by symmetry the smallest is its negative.
///
/// Joint 1 with joint 2 held: `T32 = T42 = t ≥ 5`, `Q1 = −0.06 t + 0.04 T11`: largest at
/// `t = 5`, `T11 = 100`, `−0.3 + 4 = 3.7`; no smallest (t without bound).
///
/// With T11 at most 7 N instead, holding joint 1 needs `S = (4/3) T11 ≤ 28/3 < 10`: no
/// tension holds joint 1 at zero, joint 2 has no range; joint 1's largest is `−0.3 + 0.28`.
///
/// A third joint driven by a motor only (its row of `A` is zero) has the range `[0, 0]`
/// exactly, and its presence changes nothing else: motors do not count. A third joint
/// whose row is proportional to joint 2's (again with a motor) leaves both with `[0, 0]`.
#[test]
fn two_joints_holding_the_other_at_zero_limits_the_range() {
    let tendons = |t11: f64| {
        vec![
            (vec![-0.03, 0.02], 5.0, None),
            (vec![-0.03, -0.02], 5.0, None),
            (vec![0.04, 0.0], 5.0, Some(t11)),
        ]
    };
    let r = ranges(&mechanism(2, &tendons(100.0), ""));
    let q2 = 0.02 * (0.04 * 100.0 / 0.03 - 10.0);
    assert_range(r[0], f64::NEG_INFINITY, -0.3 + 4.0);
    assert_range(r[1], -q2, q2);
    let r = ranges(&mechanism(2, &tendons(7.0), ""));
    assert_range(r[0], f64::NEG_INFINITY, -0.3 + 0.28);
    assert_eq!(r[1], None);

    let with_third: Vec<_> = tendons(100.0)
        .into_iter()
        .map(|(mut col, f, m)| {
            col.push(0.0);
            (col, f, m)
        })
        .collect();
    let r = ranges(&mechanism(
        3,
        &with_third,
        "motors: [(name: \"m3\", on: Joint(\"l3\"))],",
    ));
    assert_range(r[0], f64::NEG_INFINITY, -0.3 + 4.0);
    assert_range(r[1], -q2, q2);
    assert_eq!(r[2], Some(TorqueRange { min: 0.0, max: 0.0 }));

    // A third joint (with a motor, for the tension system's rank) whose row is 0.7 times
    // joint 2's: holding either at zero holds the other, so both ranges are exactly zero
    // (not round-off), and joint 1's is as before.
    let dependent: Vec<_> = tendons(100.0)
        .into_iter()
        .map(|(mut col, f, m)| {
            col.push(0.7 * col[1]);
            (col, f, m)
        })
        .collect();
    let r = ranges(&mechanism(
        3,
        &dependent,
        "motors: [(name: \"m3\", on: Joint(\"l3\"))],",
    ));
    assert_range(r[0], f64::NEG_INFINITY, -0.3 + 4.0);
    let zero = Some(TorqueRange { min: 0.0, max: 0.0 });
    assert_eq!((r[1], r[2]), (zero, zero));
}

/// Solves the square system `m x = b` by Gaussian elimination with partial pivoting;
/// `None` when a pivot is below `1e-12` of the largest entry (singular to working precision).
fn solve(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    let big = m.iter().flatten().fold(0.0, |a: f64, x| a.max(x.abs()));
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[p][c].abs() <= 1e-12 * big {
            return None;
        }
        m.swap(c, p);
        b.swap(c, p);
        let pivot = m[c].clone();
        for r in c + 1..n {
            let f = m[r][c] / pivot[c];
            for (x, p) in m[r][c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| m[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / m[c][c];
    }
    Some(x)
}

/// The range of joint `j` by enumerating vertices (every maximum finite, so the polytope
/// `P = {lo ≤ T ≤ hi, A_i T = 0 for i ≠ j}` is bounded and, when not empty, the extremes of
/// the linear `(A T)_j` over it are attained at vertices).
///
/// A vertex of `P ⊂ R^K` is a point of `P` where `K` linearly independent constraints are
/// active. The `n − 1` equalities are always active (and independent for these random `A`),
/// so at least `K − (n − 1)` bounds are, and they can be chosen so that with the equalities
/// they are independent: the remaining `n − 1` "free" tendons `F` have a non-singular
/// `A_{−j,F}`. So every vertex is found by choosing `F` (`C(K, n−1)` ways), putting every
/// other tendon at its floor or its maximum (`2^(K−n+1)` ways), solving
/// `A_{−j,F} T_F = −A_{−j,B} T_B` and keeping the solutions within the bounds. The candidates
/// that are not vertices lie in `P` too, so taking the extremes over all kept points is exact.
fn brute_force(a: &[Vec<f64>], lo: &[f64], hi: &[f64], j: usize) -> Option<(f64, f64)> {
    let (n, k) = (a.len(), lo.len());
    let others: Vec<usize> = (0..n).filter(|&i| i != j).collect();
    let mut best: Option<(f64, f64)> = None;
    for free_mask in 0u32..1 << k {
        if free_mask.count_ones() as usize != n - 1 {
            continue;
        }
        let free: Vec<usize> = (0..k).filter(|&c| free_mask >> c & 1 == 1).collect();
        let fixed: Vec<usize> = (0..k).filter(|&c| free_mask >> c & 1 == 0).collect();
        for at_max in 0u32..1 << fixed.len() {
            let mut t = vec![0.0; k];
            for (b, &c) in fixed.iter().enumerate() {
                t[c] = if at_max >> b & 1 == 1 { hi[c] } else { lo[c] };
            }
            let m: Vec<Vec<f64>> = others
                .iter()
                .map(|&i| free.iter().map(|&c| a[i][c]).collect())
                .collect();
            let rhs: Vec<f64> = others
                .iter()
                .map(|&i| -fixed.iter().map(|&c| a[i][c] * t[c]).sum::<f64>())
                .collect();
            let Some(x) = solve(m, rhs) else { continue };
            let within = free.iter().zip(&x).all(|(&c, &v)| {
                let tol = 1e-9 * (1.0 + hi[c]);
                v >= lo[c] - tol && v <= hi[c] + tol
            });
            if !within {
                continue;
            }
            for (&c, &v) in free.iter().zip(&x) {
                t[c] = v;
            }
            let q: f64 = (0..k).map(|c| a[j][c] * t[c]).sum();
            best = Some(best.map_or((q, q), |(lo, hi)| (lo.min(q), hi.max(q))));
        }
    }
    best
}

/// Random systems of 2-3 joints and 4-6 tendons, every maximum finite. `A` has entries up to
/// 5 cm with a strictly positive null vector (rows projected orthogonal to a positive `p`,
/// as validation demands); floors in [0, 5] N, maxima 1-40 N above them, so that some joints
/// cannot be held (no range). The LP agrees with the vertex enumeration to `1e-9` relative
/// to the larger of the endpoint and the joint's torque scale `Σ_k |A_jk| max_k`.
#[test]
fn random_systems_agree_with_vertex_enumeration() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let (mut joints, mut empty, mut worst) = (0, 0, 0.0f64);
    for _ in 0..300 {
        let n = rng.random_range(2..=3);
        let k = rng.random_range(4..=6);
        let p: Vec<f64> = (0..k).map(|_| rng.random_range(0.5..2.0)).collect();
        let pp: f64 = p.iter().map(|x| x * x).sum();
        let a: Vec<Vec<f64>> = (0..n)
            .map(|_| {
                let row: Vec<f64> = (0..k).map(|_| rng.random_range(-0.05..0.05)).collect();
                let d = row.iter().zip(&p).map(|(x, y)| x * y).sum::<f64>() / pp;
                row.iter().zip(&p).map(|(x, y)| x - d * y).collect()
            })
            .collect();
        let tendons: Vec<(Vec<f64>, f64, Option<f64>)> = (0..k)
            .map(|c| {
                let floor = rng.random_range(0.0..5.0);
                let max = floor + rng.random_range(1.0..40.0);
                ((0..n).map(|i| a[i][c]).collect(), floor, Some(max))
            })
            .collect();
        let text = mechanism(n, &tendons, "");
        let model: Model<f64> = tendyn_core::parse(&text).unwrap_or_else(|e| panic!("{e}"));
        // The model's own numbers, as parsed.
        let a = model.structure_matrix();
        let lo: Vec<f64> = model.tendons().iter().map(|t| t.floor).collect();
        let hi: Vec<f64> = model
            .tendons()
            .iter()
            .map(|t| t.max_tension.unwrap())
            .collect();
        let lp = static_torque_ranges(&model);
        assert_eq!(lp.len(), n);
        for j in 0..n {
            joints += 1;
            let scale: f64 = (0..k).map(|c| a[j][c].abs() * hi[c]).sum();
            match (lp[j], brute_force(&a, &lo, &hi, j)) {
                (None, None) => empty += 1,
                (Some(r), Some((min, max))) => {
                    for (x, y) in [(r.min, min), (r.max, max)] {
                        let err = (x - y).abs() / y.abs().max(scale);
                        worst = worst.max(err);
                        assert!(
                            err <= 1e-9,
                            "joint {j}: LP {r:?}, vertices [{min}, {max}]\n{text}"
                        );
                    }
                }
                (x, y) => panic!("joint {j}: LP {x:?}, vertices {y:?}\n{text}"),
            }
        }
    }
    eprintln!("{joints} joints, {empty} without a range, worst relative error {worst:.1e}");
    assert!(
        empty > 10 && empty < joints - 10,
        "{empty} of {joints} empty"
    );
}
