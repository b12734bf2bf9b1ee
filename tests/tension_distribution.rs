//! Tension distribution of redundant routings and the pretension of loops.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::{Error, Solver};

fn example(name: &str) -> String {
    tendyn_spec::examples::text(name)
}

use tendyn_spec::redundant::THREE_ON_ONE;

#[test]
fn open_ended_tensions_keep_their_floors_with_the_least_norm() {
    for (text, d) in [
        (example("example2_open_ended"), 1),
        (example("example3_stanford_jpl"), 1),
        (THREE_ON_ONE.to_string(), 2),
    ] {
        let m = tendyn_core::parse(&text).unwrap();
        assert_eq!(m.system.null_space.len(), d);
        let mut s = Solver::new(&m);
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..200 {
            let mut v = |s: f64| {
                (0..m.dof)
                    .map(|_| rng.random_range(-s..s))
                    .collect::<Vec<f64>>()
            };
            let (q, qd, qdd) = (v(3.0), v(3.0), v(10.0));
            let r = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
            let t = &r.tendon_tensions;
            let floors: Vec<f64> = m.tendons.iter().map(|t| t.floor).collect();
            // Every tendon at or above its floor, and at least one on it (else less would do).
            let slack: Vec<f64> = t.iter().zip(&floors).map(|(t, f)| t - f).collect();
            assert!(
                slack.iter().all(|&x| x >= -1e-12),
                "{}: below a floor: {t:?}",
                m.name
            );
            assert!(
                slack.iter().any(|&x| x.abs() < 1e-10),
                "{}: no tendon at its floor: {t:?}",
                m.name
            );
            // Minimal-norm part plus null-space part; the null-space part is a null vector and
            // the minimal-norm part is orthogonal to the null space.
            let a = m.structure_matrix();
            for (j, row) in a.iter().enumerate() {
                let an: f64 = row
                    .iter()
                    .zip(&r.null_space_tensions)
                    .map(|(x, y)| x * y)
                    .sum();
                assert!(
                    an.abs() < 1e-10 * (1.0 + t.iter().cloned().fold(0.0, f64::max)),
                    "null part moves joint {j}"
                );
            }
            for nv in &m.system.null_space {
                let dot: f64 = m
                    .tendons
                    .iter()
                    .map(|tt| {
                        nv[tt.unknown]
                            * r.minimal_norm_tensions[m
                                .tendons
                                .iter()
                                .position(|x| x.unknown == tt.unknown)
                                .unwrap()]
                    })
                    .sum();
                assert!(
                    dot.abs() < 1e-9,
                    "minimal-norm part not orthogonal to the null space"
                );
            }
            // No feasible move along the null space lowers the norm (the problem is convex,
            // so local optimality is global).
            let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>();
            for _ in 0..50 {
                let mut cand = t.clone();
                let step = 10f64.powf(rng.random_range(-4.0..0.0));
                for nv in &m.system.null_space {
                    let c = rng.random_range(-step..step);
                    for (k, tt) in m.tendons.iter().enumerate() {
                        cand[k] += c * nv[tt.unknown];
                    }
                }
                if cand.iter().zip(&floors).all(|(c, f)| *c >= *f) {
                    assert!(
                        norm(&cand) >= norm(t) * (1.0 - 1e-12),
                        "{}: a feasible {cand:?} beats {t:?}",
                        m.name
                    );
                }
            }
        }
    }
}

#[test]
fn a_floor_that_needs_more_than_an_actuator_can_pull_is_an_error_naming_the_tendon() {
    let text = example("example2_open_ended").replace(
        "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),",
        "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0), max_tension: 200.0),",
    );
    let m = tendyn_core::parse(&text).unwrap();
    let mut s = Solver::new(&m);
    // At rest, holding the arm against gravity needs about 130 N on T11 (r1 = 4 cm): fine.
    assert!(s
        .inverse_dynamics(&[0.3, 0.5], &[0.0, 0.0], &[0.0, 0.0])
        .is_ok());
    // A hard acceleration needs far more.
    match s.inverse_dynamics(&[0.3, 0.5], &[1.0, 0.5], &[40.0, 30.0]) {
        Err(Error::Tension(msg)) => {
            assert!(msg.contains("T11") && msg.contains("max_tension"), "{msg}")
        }
        other => panic!("expected a tension error, got {other:?}"),
    }
}

#[test]
fn an_endless_loop_side_below_zero_is_flagged_slack_and_a_higher_pretension_clears_it() {
    // q̈ = (20, 30) rad/s² needs about 68 N of tension difference: more than twice the 20 N
    // pretension, so one side would have to push.
    let (q, qd, qdd) = ([0.3, 0.5], [1.0, 0.5], [20.0, 30.0]);
    let low = tendyn_core::parse(&example("example1_endless")).unwrap();
    let r = Solver::new(&low).inverse_dynamics(&q, &qd, &qdd).unwrap();
    let [ccw, cw] = r.loop_sides[0];
    let slack = r.slack_loops()[0];
    assert!(
        slack && cw < 0.0 && (ccw + cw - 40.0).abs() < 1e-12,
        "sides {ccw}, {cw}"
    );
    let high = tendyn_core::parse(
        &example("example1_endless").replace("pretension: 20.0", "pretension: 50.0"),
    )
    .unwrap();
    let r2 = Solver::new(&high).inverse_dynamics(&q, &qd, &qdd).unwrap();
    let [ccw2, cw2] = r2.loop_sides[0];
    let slack2 = r2.slack_loops()[0];
    assert!(!slack2 && cw2 > 0.0, "sides {ccw2}, {cw2}");
    // The pretension shifts both sides equally and changes neither motor torque.
    assert!(((ccw2 - cw2) - (ccw - cw)).abs() < 1e-12);
    for (a, b) in r.motor_torques.iter().zip(&r2.motor_torques) {
        assert!((a - b).abs() < 1e-12);
    }
}

#[test]
fn the_fixed_size_distribution_of_generated_code_matches_the_runtime_solver_in_a_2d_null_space() {
    // The runtime solver's distribution (active sets over Vec) and the no_std, fixed-size
    // routine generated code calls must choose the same tensions.
    let m = tendyn_core::parse(THREE_ON_ONE).unwrap();
    assert_eq!(m.system.null_space.len(), 2);
    let cols: Vec<usize> = m.tendons.iter().map(|t| t.unknown).collect();
    let null: [[f64; 3]; 2] =
        std::array::from_fn(|d| std::array::from_fn(|k| m.system.null_space[d][cols[k]]));
    let floor: [f64; 3] = std::array::from_fn(|k| m.tendons[k].floor);
    let mut s = Solver::new(&m);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..500 {
        let (q, qd, qdd) = (
            [rng.random_range(-3.0..3.0)],
            [rng.random_range(-3.0..3.0)],
            [rng.random_range(-10.0..10.0)],
        );
        let r = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let x0: [f64; 3] = std::array::from_fn(|k| r.minimal_norm_tensions[k]);
        let got = tendyn_core::distribution::least_norm_with_floor::<f64, 3, 2>(x0, &null, &floor);
        for (g, w) in got.iter().zip(&r.tendon_tensions) {
            assert!(
                (g - w).abs() <= 1e-12 * w.abs().max(1.0),
                "{got:?} vs {:?}",
                r.tendon_tensions
            );
        }
    }
}
