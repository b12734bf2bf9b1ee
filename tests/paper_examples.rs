//! The paper's Examples 1 and 2 against their equations, written out by hand here.
//!
//! The paper leaves gravity out. Each hand formula below carries a gravity term, and each
//! test runs the arm both as shipped (horizontal: gravity normal to its plane, the term
//! vanishes) and in a vertical plane (gravity along −y). Corrections to the printed equations are
//! recorded, with their derivations, in `docs/paper-errata.md`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::{Model, Solver};

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

/// The numbers of Examples 1 and 2 (see the RON files).
struct Arm {
    a1: f64,
    s1: f64,
    m1: f64,
    i1: f64,
    a2: f64,
    s2: f64,
    m2: f64,
    i2: f64,
}

const ARM: Arm = Arm {
    a1: 0.30,
    s1: 0.15,
    m1: 1.2,
    i1: 0.009,
    a2: 0.25,
    s2: 0.125,
    m2: 0.8,
    i2: 0.0041667,
};

impl Arm {
    /// Joint torques of the bare two-link arm (no pulleys), gravity `g` along −y, from the
    /// textbook closed form (Lagrange), with l_c1 = a1 − s1, l_c2 = a2 − s2.
    fn torques(&self, q: &[f64], qd: &[f64], qdd: &[f64], g: f64) -> (f64, f64) {
        let (lc1, lc2) = (self.a1 - self.s1, self.a2 - self.s2);
        let (c2, s2) = (q[1].cos(), q[1].sin());
        let m11 = self.i1
            + self.m1 * lc1 * lc1
            + self.i2
            + self.m2 * (self.a1 * self.a1 + lc2 * lc2 + 2.0 * self.a1 * lc2 * c2);
        let m12 = self.i2 + self.m2 * (lc2 * lc2 + self.a1 * lc2 * c2);
        let m22 = self.i2 + self.m2 * lc2 * lc2;
        let hh = self.m2 * self.a1 * lc2 * s2;
        let g1 = (self.m1 * lc1 + self.m2 * self.a1) * g * q[0].cos()
            + self.m2 * lc2 * g * (q[0] + q[1]).cos();
        let g2 = self.m2 * lc2 * g * (q[0] + q[1]).cos();
        (
            m11 * qdd[0] + m12 * qdd[1] - hh * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1,
            m12 * qdd[0] + m22 * qdd[1] + hh * qd[0] * qd[0] + g2,
        )
    }
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
        let mut s = Solver::new(&m);
        let r2 = 0.02;
        for [q, qd, qdd] in states(1, 500) {
            let id = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
            let [t21, t22] = id.loop_sides[0];
            // Eq. 28 (+ gravity): r2 (T21 − T22) = cI2 (θ̈1 + θ̈2) + m2 (a2 − s2)[a1 (sin θ2 θ̇1² +
            // cos θ2 θ̈1) + (a2 − s2)(θ̈1 + θ̈2)] + m2 g (a2 − s2) cos(θ1 + θ2)
            let lc2 = ARM.a2 - ARM.s2;
            let rhs = ARM.i2 * (qdd[0] + qdd[1])
                + ARM.m2
                    * lc2
                    * (ARM.a1 * (q[1].sin() * qd[0] * qd[0] + q[1].cos() * qdd[0])
                        + lc2 * (qdd[0] + qdd[1]))
                + ARM.m2 * g * lc2 * (q[0] + q[1]).cos();
            close(r2 * (t21 - t22), rhs, 1.0, "Eq. 28");
            // The sides straddle the pretension.
            close(0.5 * (t21 + t22), 20.0, 20.0, "pretension");
        }
    }
}

#[test]
fn example1_motor_torques_satisfy_eq29_and_corrected_eq30() {
    for (m, g) in example("example1_endless") {
        let mut s = Solver::new(&m);
        let (r2, r3, i3) = (0.02, 0.03, 0.000045);
        let gamma = r2 / r3;
        for [q, qd, qdd] in states(2, 500) {
            let id = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
            let [t21, t22] = id.loop_sides[0];
            let (n10, n30) = (id.motor_torques[0], id.motor_torques[1]);
            // Eq. 29: n30 = r3 (T21 − T22) + cI3 (θ̈1 + γ23 θ̈2).
            close(
                n30,
                r3 * (t21 - t22) + i3 * (qdd[0] + gamma * qdd[1]),
                1.0,
                "Eq. 29",
            );
            // Eq. 30, corrected (docs/paper-errata.md): with l_c1 = a1 − s1, l_c2 = a2 − s2,
            // n10 = (r3 − r2)(T22 − T21) + (cI1 + m1 l_c1² + m2 a1²) θ̈1
            //       + m2 a1 l_c2 [cos θ2 (θ̈1 + θ̈2) − sin θ2 (θ̇1 + θ̇2)²]
            //       + (m1 l_c1 + m2 a1) g cos θ1.
            let (lc1, lc2) = (ARM.a1 - ARM.s1, ARM.a2 - ARM.s2);
            let eq30 = (r3 - r2) * (t22 - t21)
                + (ARM.i1 + ARM.m1 * lc1 * lc1 + ARM.m2 * ARM.a1 * ARM.a1) * qdd[0]
                + ARM.m2
                    * ARM.a1
                    * lc2
                    * (q[1].cos() * (qdd[0] + qdd[1]) - q[1].sin() * (qd[0] + qd[1]).powi(2))
                + (ARM.m1 * lc1 + ARM.m2 * ARM.a1) * g * q[0].cos();
            close(n10, eq30, 1.0, "Eq. 30");
            // Substituting Eq. 28 removes the tensions: the motors deliver the arm's torques
            // plus the pulley's inertia (n10 = τ1 − (r3/r2) τ2, n30 = (r3/r2) τ2 + cI3 (θ̈1 + γ θ̈2)).
            let (tau1, tau2) = ARM.torques(&q, &qd, &qdd, g);
            close(n10, tau1 - tau2 / gamma, 1.0, "Eq. 30 without tensions");
            close(
                n30,
                tau2 / gamma + i3 * (qdd[0] + gamma * qdd[1]),
                1.0,
                "Eq. 29 without tensions",
            );
        }
    }
}

#[test]
fn example2_structure_matrix_and_demand_match_eq33() {
    for (m, g) in example("example2_open_ended") {
        let (r1, r2, r3, r4, i3, i4) = (0.04, 0.02, 0.03, 0.03, 0.0000225, 0.0000225);
        // Eq. 33 with T = (T32, T42, T11) and rows (joint 2, joint 1):
        // A = [[r2, −r2, 0], [−r3, −r4, r1]].
        let a = m.structure_matrix();
        let want = [[-r3, -r4, r1], [r2, -r2, 0.0]]; // rows in joint order (joint 1, joint 2)
        for j in 0..2 {
            for k in 0..3 {
                assert!(
                    (a[j][k] - want[j][k]).abs() < 1e-15,
                    "A[{j}][{k}] = {} but Eq. 33 gives {}",
                    a[j][k],
                    want[j][k]
                );
            }
        }
        // B: the arm's torques plus each idler's inertia through its coupling, θ3 = θ1 − (r2/r3) θ2,
        // θ4 = θ1 + (r2/r4) θ2 (the tendon over idler 3 crosses from one side to the other).
        let mut s = Solver::new(&m);
        for [q, qd, qdd] in states(3, 500) {
            let id = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
            let t = &id.tendon_tensions;
            let (tau1, tau2) = ARM.torques(&q, &qd, &qdd, g);
            let (c3, c4) = ([1.0, -r2 / r3], [1.0, r2 / r4]);
            let (a3, a4) = (
                c3[0] * qdd[0] + c3[1] * qdd[1],
                c4[0] * qdd[0] + c4[1] * qdd[1],
            );
            let b1 = tau2 + i3 * c3[1] * a3 + i4 * c4[1] * a4;
            let b2 = tau1 + i3 * c3[0] * a3 + i4 * c4[0] * a4;
            close(r2 * t[0] - r2 * t[1], b1, 1.0, "Eq. 33a");
            close(-r3 * t[0] - r4 * t[1] + r1 * t[2], b2, 1.0, "Eq. 33b");
            // Every tendon taut, the least at its 5 N floor.
            let least = t.iter().cloned().fold(f64::INFINITY, f64::min);
            assert!((least - 5.0).abs() < 1e-12, "least tension {least}");
        }
    }
}
