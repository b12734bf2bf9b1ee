//! Bearing friction in joints and pulleys (`docs/format.md` §4a), against what shares
//! none of `tendyn_core::friction`: the law written out by hand for one joint and one
//! idler, and on the paper's Example 2 and seeded random mechanisms with friction on every
//! bearing the power balance with dissipation,
//!
//! > `Σ T_k ẋ_k + Σ τ_m θ̇_m + Q_extᵀ q̇ = dE/dt + P_loss`,
//!
//! `E` from the Lagrangian reference, `ẋ_k`, `θ̇_m` the transmission's rates, `P_loss` from
//! the coefficients and the bodies' rates alone (`tendyn_spec::friction`). Agreement is
//! relative to the size of the terms (the sum of their magnitudes), 1e-12 in f64.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::Model;
use tendyn_core::{parse, Data};
use tendyn_spec::friction::{dissipated_power, generalized_force, rate, with_bearing_friction};
use tendyn_spec::lagrangian;
use tendyn_spec::measure::random_state;
use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

const TOL: f64 = 1e-12;

/// One link on a motor-driven joint; `friction` is spliced into the link.
fn one_joint(friction: &str, smoothing: &str) -> Model<f64> {
    parse(&format!(
        r#"(
    name: "one_joint",{smoothing}
    links: [(name: "arm", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0, com: (-0.15, 0.0, 0.0),
             inertia: (xx: 0.001, yy: 0.01, zz: 0.01){friction})],
    motors: [(name: "m", on: Joint("arm"))],
)"#
    ))
    .unwrap()
}

fn motor_torque(model: &Model<f64>, q: f64, qd: f64, qdd: f64) -> (f64, Vec<usize>) {
    let r = Data::new(model)
        .inverse_dynamics(model, &[q], &[qd], &[qdd])
        .unwrap()
        .clone();
    (r.motor_torques[0], r.sticking)
}

#[test]
fn a_joint_bearing_adds_coulomb_times_the_direction_plus_viscous_times_the_rate() {
    let (c, v) = (0.12, 0.03);
    let ideal = one_joint("", "");
    let rough = one_joint(&format!(", friction: (coulomb: {c}, viscous: {v})"), "");
    let smooth = one_joint(
        &format!(", friction: (coulomb: {c}, viscous: {v})"),
        "\n    friction_smoothing: 0.05,",
    );
    // (q̇, q̈, the direction by hand, whether the bearing is at rest)
    for (qd, qdd, s, at_rest) in [
        (0.7, 1.5, 1.0, false),
        (-0.4, 1.5, -1.0, false),
        (0.0, 2.0, 1.0, true),   // at rest: against the impending motion
        (0.0, -2.0, -1.0, true), //
        (0.0, 0.0, 0.0, true),   // at rest and staying: taken as zero
    ] {
        let (t0, _) = motor_torque(&ideal, 0.4, qd, qdd);
        let (t, sticking) = motor_torque(&rough, 0.4, qd, qdd);
        let want = c * s + v * qd;
        assert!(
            ((t - t0) - want).abs() <= TOL * t0.abs().max(1.0),
            "at q̇ = {qd}, q̈ = {qdd} friction adds {} N·m, not {want}",
            t - t0
        );
        assert_eq!(
            sticking == vec![0],
            at_rest,
            "q̇ = {qd}: sticking {sticking:?}"
        );
        // The smoothed law: c·tanh(q̇ / v_s) + v q̇, never at rest.
        let (ts, sticking) = motor_torque(&smooth, 0.4, qd, qdd);
        let want = c * (qd / 0.05f64).tanh() + v * qd;
        assert!(((ts - t0) - want).abs() <= TOL * t0.abs().max(1.0));
        assert!(sticking.is_empty());
    }
}

/// Example 2 with friction on one idler: the tension step across it (paper Eq. 24b)
/// changes by exactly the bearing's torque over the idler's radius.
#[test]
fn an_idler_bearing_changes_the_tension_step_across_it_by_its_torque_over_the_radius() {
    let text = std::fs::read_to_string("../examples/mechanisms/example2_open_ended.ron").unwrap();
    let (c, v, r) = (0.004, 0.0007, 0.03);
    let rough = text.replacen(
        "radius: 0.03,",
        &format!("radius: 0.03,\n            friction: (coulomb: {c}, viscous: {v}),"),
        1,
    );
    let (ideal, rough) = (parse(&text).unwrap(), parse(&rough).unwrap());
    let idler = rough
        .bodies()
        .iter()
        .position(|b| b.name == "idler3")
        .unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..200 {
        let [q, qd, qdd] = random_state(&mut rng, 2);
        let step = |m: &Model<f64>| {
            let r = Data::new(m)
                .inverse_dynamics(m, &q, &qd, &qdd)
                .unwrap()
                .clone();
            let s = &r.segment_tensions.as_ref().unwrap()[0]; // T32: drum2a, idler3, exit
            (s[0] - s[1], r)
        };
        let ((d0, _), (d, r_rough)) = (step(&ideal), step(&rough));
        let w = rate(&rough, idler, &qd);
        let torque = -(c * w.signum() + v * w);
        assert_eq!(
            r_rough.bearing_friction,
            vec![(idler, r_rough.bearing_friction[0].1)]
        );
        let reported = r_rough.bearing_friction[0].1;
        assert!((reported - torque).abs() <= TOL * torque.abs());
        // T_in − T_out = −s (N − τ_f) / r, with s = −1 for idler3 (`Cw` on T32's route).
        let (change, want) = (d - d0, -torque / r);
        assert!(
            (change - want).abs() <= TOL * (d.abs() + d0.abs()).max(1.0),
            "the step changes by {change} N, not −τ_f / r = {want} N"
        );
    }
}

/// The generalized forces, power balance and forward dynamics of one mechanism with
/// friction, at `states` random states (where no bearing is at rest).
fn check_dissipation(model: &Model<f64>, states: usize, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut solver = Data::new(model);
    let mut worst = 0.0f64;
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, model.dof());
        let id = solver
            .inverse_dynamics(model, &q, &qd, &qdd)
            .unwrap()
            .clone();
        // Actuator and environment power, from the solved tensions and torques and the
        // transmission's rates.
        let terms = lagrangian::power_in(model, &q, &qd, &id.tendon_tensions, &id.motor_torques);
        let q_ext = lagrangian::external_generalized_forces(model, &q);
        let power: f64 = terms.iter().sum();
        let de = lagrangian::energy_rate(model, &q, &qd, &qdd);
        let loss = dissipated_power(model, &qd);
        // What the solver reports dissipates the same, P = −Σ τ_f ω, and never less than 0.
        let reported: f64 = id
            .bearing_friction
            .iter()
            .map(|&(b, t)| -t * rate(model, b, &qd))
            .sum();
        assert!(
            reported >= 0.0,
            "{}: the bearings give {reported} W",
            model.name()
        );
        let scale = terms.iter().map(|x| x.abs()).sum::<f64>() + de.abs() + loss;
        let e_p = (power - de - loss).abs() / scale;
        let e_r = (reported - loss).abs() / loss.max(f64::MIN_POSITIVE);
        assert!(
            e_p <= TOL && e_r <= TOL,
            "{}: power balance off by {e_p:.3e}, reported dissipation by {e_r:.3e}",
            model.name()
        );
        // Q = Lagrange − Q_ext − Σ c_bᵀ τ_f,b, the torques by hand; and the same with every
        // joint at rest, where the direction of impending motion decides.
        let rest = vec![0.0; model.dof()];
        let mut e_q = 0.0f64;
        for v in [&qd, &rest] {
            let want = lagrangian::lagrange_generalized_forces(model, &q, v, &qdd)
                - &q_ext
                - nalgebra::DVector::from_vec(generalized_force(model, v, &qdd));
            let got = &solver
                .inverse_dynamics(model, &q, v, &qdd)
                .unwrap()
                .generalized_forces;
            e_q = e_q.max(tendyn_spec::measure::max_rel(got, want.as_slice()));
        }
        assert!(e_q <= TOL, "{}: Q off by {e_q:.3e}", model.name());
        // Forward dynamics of the solved actuation gives the motion back.
        let back = solver
            .forward_dynamics(model, &q, &qd, &id.motor_torques, &id.tendon_tensions)
            .unwrap()
            .to_vec();
        let size = solver
            .forward_dynamics_scale(model, &q, &qd, &id.motor_torques, &id.tendon_tensions)
            .unwrap();
        let e_f = back
            .iter()
            .zip(&qdd)
            .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()))
            / size;
        assert!(
            e_f <= TOL,
            "{}: forward dynamics off by {e_f:.3e}",
            model.name()
        );
        worst = worst.max(e_p).max(e_q).max(e_f);
    }
    worst
}

#[test]
fn example_2_with_friction_on_every_bearing_balances_power_with_dissipation() {
    let text = std::fs::read_to_string("../examples/mechanisms/example2_friction.ron").unwrap();
    let model = parse(&text).unwrap();
    assert_eq!(
        model
            .bodies()
            .iter()
            .filter(|b| b.friction.is_some())
            .count(),
        4,
        "both joints and both idlers"
    );
    let worst = check_dissipation(&model, 500, 11);
    println!("example 2 with friction: worst relative error {worst:.2e}");
}

#[test]
fn random_mechanisms_with_friction_on_every_bearing_balance_power_with_dissipation() {
    for seed in 0..12u64 {
        let features = Features {
            coupled_pulleys: seed % 3 == 2,
            endless: seed % 4 == 1,
        };
        let (text, _) = valid_random_mechanism(seed, features);
        let smoothing = (seed % 2 == 1).then_some(0.2);
        let model = parse(&with_bearing_friction(&text, seed, smoothing)).unwrap();
        assert!(model.bodies().iter().any(|b| b.friction.is_some()));
        let worst = check_dissipation(&model, 100, seed);
        println!(
            "random_{seed}{}: worst relative error {worst:.2e}",
            if smoothing.is_some() {
                " (smoothed)"
            } else {
                ""
            }
        );
    }
}
