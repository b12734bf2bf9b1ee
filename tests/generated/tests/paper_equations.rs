//! The generated code of the paper's examples against their equations written out by hand
//! (`tendyn_spec::paper`, corrections in `docs/paper-errata.md`): Example 1's generated
//! motor torques and loop-side tensions satisfy Eqs. 28, 29 and the corrected Eq. 30;
//! Example 2's generated structure matrix is Eq. 33's `A` and its generated generalized
//! forces are Eq. 33's `B` (= `A T`). Shipped arms are horizontal: gravity terms are zero.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_generated_tests::{example1_endless as ex1, example2_open_ended as ex2};
use tendyn_spec::paper::ARM;

fn states(seed: u64) -> Vec<[[f64; 2]; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..1000)
        .map(|_| {
            let mut v = |s: f64| [rng.random_range(-s..s), rng.random_range(-s..s)];
            [v(std::f64::consts::PI), v(3.0), v(10.0)]
        })
        .collect()
}

fn close(got: f64, want: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(1.0),
        "{what}: generated {got}, hand {want}"
    );
}

#[test]
fn generated_example1_satisfies_eqs_28_29_and_corrected_30() {
    let (r2, _, _) = tendyn_spec::paper::EX1;
    for [q, qd, qdd] in states(1) {
        let [n10, n30] = ex1::code::actuation::<f64>(&q, &qd, &qdd).motor_torques;
        let [t21, t22] = ex1::code::segment_tensions::<f64>(&q, &qd, &qdd);
        close(r2 * (t21 - t22), ARM.eq28(&q, &qd, &qdd, 0.0), "Eq. 28");
        close(n30, ARM.eq29(&qdd, t21, t22), "Eq. 29");
        close(n10, ARM.eq30(&q, &qd, &qdd, 0.0, t21, t22), "Eq. 30");
    }
}

#[test]
fn generated_example2_structure_matrix_and_demand_are_eq33() {
    let a = ARM.eq33_a();
    for (j, row) in ex2::code::STRUCTURE_MATRIX.iter().enumerate() {
        for (k, &x) in row.iter().enumerate() {
            assert!(
                (x - a[j][k]).abs() < 1e-15,
                "A[{j}][{k}] = {x}, Eq. 33 gives {}",
                a[j][k]
            );
        }
    }
    for [q, qd, qdd] in states(2) {
        let [q1, q2] = ex2::code::generalized_forces::<f64>(&q, &qd, &qdd);
        let (b1, b2) = ARM.eq33_b(&q, &qd, &qdd, 0.0);
        close(q2, b1, "Eq. 33 b1");
        close(q1, b2, "Eq. 33 b2");
        // And the generated tensions meet it: A T = B.
        let t = ex2::code::actuation::<f64>(&q, &qd, &qdd).tendon_tensions;
        let at = |j: usize| (0..3).map(|k| a[j][k] * t[k]).sum::<f64>();
        close(at(1), b1, "Eq. 33a with generated tensions");
        close(at(0), b2, "Eq. 33b with generated tensions");
    }
}
