//! The paper's Examples 1 and 2 against their equations, written out by hand here.
//!
//! The paper leaves gravity out. Each hand formula below carries a gravity term, and each
//! test runs the arm both as shipped (horizontal: gravity normal to its plane, the term
//! vanishes) and in a vertical plane (gravity along −y). Corrections to the printed equations are
//! recorded, with their derivations, in `docs/paper-errata.md`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::{Data, Model};
use tendyn_spec::paper::{ARM, EX1};

/// The example as shipped (a horizontal arm: gravity normal to its plane) and the same arm
/// in a vertical plane (gravity along −y), with the gravity each hand formula must use.
fn example(name: &str) -> Vec<(Model<f64>, f64)> {
    let path = format!(
        "{}/../examples/mechanisms/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("gravity: (0.0, 0.0, -9.81)"));
    let vertical = text.replace("gravity: (0.0, 0.0, -9.81)", "gravity: (0.0, -9.81, 0.0)");
    vec![
        (tendyn_core::parse(&text).unwrap(), 0.0),
        (tendyn_core::parse(&vertical).unwrap(), 9.81),
    ]
}

fn states(seed: u64, count: usize) -> Vec<[Vec<f64>; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            let mut v = |s: f64| vec![rng.random_range(-s..s), rng.random_range(-s..s)];
            [v(std::f64::consts::PI), v(3.0), v(10.0)]
        })
        .collect()
}

fn close(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * scale.max(want.abs()),
        "{what}: got {got}, hand derivation gives {want}"
    );
}

#[test]
fn example1_tension_difference_satisfies_eq28_link2_moment_balance() {
    for (m, g) in example("example1_endless") {
        let mut s = Data::new(&m);
        let (r2, _, _) = EX1;
        for [q, qd, qdd] in states(1, 500) {
            let [t21, t22] = s.inverse_dynamics(&m, &q, &qd, &qdd).unwrap().loop_sides[0];
            close(r2 * (t21 - t22), ARM.eq28(&q, &qd, &qdd, g), 1.0, "Eq. 28");
            // The sides straddle the pretension.
            close(0.5 * (t21 + t22), 20.0, 20.0, "pretension");
        }
    }
}

#[test]
fn example1_motor_torques_satisfy_eq29_and_corrected_eq30() {
    for (m, g) in example("example1_endless") {
        let mut s = Data::new(&m);
        let (r2, r3, i3) = EX1;
        let gamma = r2 / r3;
        for [q, qd, qdd] in states(2, 500) {
            let id = s.inverse_dynamics(&m, &q, &qd, &qdd).unwrap();
            let [t21, t22] = id.loop_sides[0];
            let (n10, n30) = (id.motor_torques[0], id.motor_torques[1]);
            close(n30, ARM.eq29(&qdd, t21, t22), 1.0, "Eq. 29");
            close(n10, ARM.eq30(&q, &qd, &qdd, g, t21, t22), 1.0, "Eq. 30");
            // Substituting Eq. 28 removes the tensions: the motors deliver the arm's torques
            // plus the pulley's inertia (n10 = τ1 − (r3/r2) τ2, n30 = (r3/r2) τ2 + cI3 (θ̈1 + γ θ̈2)).
            let (tau1, tau2) = ARM.torques(&q, &qd, &qdd, g);
            close(n10, tau1 - tau2 / gamma, 1.0, "Eq. 30 without tensions");
            let pulley = i3 * (qdd[0] + gamma * qdd[1]);
            close(n30, tau2 / gamma + pulley, 1.0, "Eq. 29 without tensions");
        }
    }
}

#[test]
fn example2_structure_matrix_and_demand_match_eq33() {
    for (m, g) in example("example2_open_ended") {
        // Eq. 33 with T = (T32, T42, T11); rows here in joint order (joint 1, joint 2).
        let a = m.structure_matrix();
        let want = ARM.eq33_a();
        for j in 0..2 {
            for k in 0..3 {
                let (got, w) = (a[j][k], want[j][k]);
                assert!(
                    (got - w).abs() < 1e-15,
                    "A[{j}][{k}] = {got} but Eq. 33 gives {w}"
                );
            }
        }
        let mut s = Data::new(&m);
        for [q, qd, qdd] in states(3, 500) {
            let t = &s
                .inverse_dynamics(&m, &q, &qd, &qdd)
                .unwrap()
                .tendon_tensions;
            let (b1, b2) = ARM.eq33_b(&q, &qd, &qdd, g);
            let at = |j: usize| (0..3).map(|k| want[j][k] * t[k]).sum::<f64>();
            close(at(1), b1, 1.0, "Eq. 33a");
            close(at(0), b2, 1.0, "Eq. 33b");
            // Every tendon taut, the least at its 5 N floor.
            let least = t.iter().cloned().fold(f64::INFINITY, f64::min);
            assert!((least - 5.0).abs() < 1e-12, "least tension {least}");
        }
    }
}
