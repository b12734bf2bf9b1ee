//! Tension distribution of redundant routings and the pretension of loops.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::{Data, Error};

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
        assert_eq!(m.system().null_space.len(), d);
        let mut s = Data::new(&m);
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..200 {
            let mut v = |s: f64| {
                (0..m.dof())
                    .map(|_| rng.random_range(-s..s))
                    .collect::<Vec<f64>>()
            };
            let (q, qd, qdd) = (v(3.0), v(3.0), v(10.0));
            let r = s.inverse_dynamics(&m, &q, &qd, &qdd).unwrap();
            let t = &r.tendon_tensions;
            let floors: Vec<f64> = m.tendons().iter().map(|t| t.floor).collect();
            // Every tendon at or above its floor, and at least one on it (else less would do).
            let slack: Vec<f64> = t.iter().zip(&floors).map(|(t, f)| t - f).collect();
            assert!(
                slack.iter().all(|&x| x >= -1e-12),
                "{}: below a floor: {t:?}",
                m.name()
            );
            assert!(
                slack.iter().any(|&x| x.abs() < 1e-10),
                "{}: no tendon at its floor: {t:?}",
                m.name()
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
            for nv in &m.system().null_space {
                let dot: f64 = m
                    .tendons()
                    .iter()
                    .map(|tt| {
                        nv[tt.unknown]
                            * r.minimal_norm_tensions[m
                                .tendons()
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
                for nv in &m.system().null_space {
                    let c = rng.random_range(-step..step);
                    for (k, tt) in m.tendons().iter().enumerate() {
                        cand[k] += c * nv[tt.unknown];
                    }
                }
                if cand.iter().zip(&floors).all(|(c, f)| *c >= *f) {
                    assert!(
                        norm(&cand) >= norm(t) * (1.0 - 1e-12),
                        "{}: a feasible {cand:?} beats {t:?}",
                        m.name()
                    );
                }
            }
        }
    }
}

#[test]
fn a_motion_that_needs_more_than_an_actuator_can_pull_is_an_error_naming_the_tendon() {
    let text = example("example2_open_ended").replace(
        "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0)),",
        "(name: \"T11\", route: [(\"drum1\", Ccw)], exit: (-0.25, 0.10, 0.0), max_tension: 200.0),",
    );
    let m = tendyn_core::parse(&text).unwrap();
    let mut s = Data::new(&m);
    // At rest, holding the arm against gravity needs about 130 N on T11 (r1 = 4 cm): fine.
    assert!(s
        .inverse_dynamics(&m, &[0.3, 0.5], &[0.0, 0.0], &[0.0, 0.0])
        .is_ok());
    // A hard acceleration needs far more.
    match s.inverse_dynamics(&m, &[0.3, 0.5], &[1.0, 0.5], &[40.0, 30.0]) {
        Err(Error::Tension(msg)) => assert!(
            msg.starts_with("`T11` at its maximum 200 N cannot produce ")
                && msg.contains("the most they can produce with every other tendon at its floor"),
            "{msg}"
        ),
        other => panic!("expected a tension error, got {other:?}"),
    }
}

#[test]
fn an_endless_loop_side_below_zero_is_flagged_slack_and_a_higher_pretension_clears_it() {
    // q̈ = (20, 30) rad/s² needs about 68 N of tension difference: more than twice the 20 N
    // pretension, so one side would have to push.
    let (q, qd, qdd) = ([0.3, 0.5], [1.0, 0.5], [20.0, 30.0]);
    let low = tendyn_core::parse(&example("example1_endless")).unwrap();
    let r = Data::new(&low)
        .inverse_dynamics(&low, &q, &qd, &qdd)
        .unwrap()
        .clone();
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
    let r2 = Data::new(&high)
        .inverse_dynamics(&high, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let [ccw2, cw2] = r2.loop_sides[0];
    let slack2 = r2.slack_loops()[0];
    assert!(!slack2 && cw2 > 0.0, "sides {ccw2}, {cw2}");
    // The pretension shifts both sides equally and changes neither motor torque.
    assert!(((ccw2 - cw2) - (ccw - cw)).abs() < 1e-12);
    for (a, b) in r.motor_torques.iter().zip(&r2.motor_torques) {
        assert!((a - b).abs() < 1e-12);
    }
}

/// One joint driven by three structure-only tendons: `T1` and `T2` pull it positively with
/// moment arms `a₁ = 0.51/26 m` and `a₂ = a₁/2`, `T3` negatively with `a₃ = 0.01 m`; floors
/// 1 N. The link's centre of mass is on the joint axis and gravity is off, so the joint
/// needs `Q = I q̈ = 0.01 kg·m² · q̈`: 0.5 N·m at `q̈ = 50 rad/s²`.
fn one_joint_three_tendons(max1: f64, max2: f64) -> String {
    let a1 = 0.51 / 26.0;
    format!(
        r#"(
    name: "one_joint", gravity: (0.0, 0.0, 0.0), tension_floor: 1.0,
    links: [(name: "arm", dh: (a: 0.1, alpha: 0.0, d: 0.0), mass: 1.0, com: (-0.1, 0.0, 0.0),
             inertia: (xx: 0.001, yy: 0.01, zz: 0.01))],
    tendons: [
        (name: "T1", structure: [{a1:e}], max_tension: {max1:?}),
        (name: "T2", structure: [{:e}], max_tension: {max2:?}),
        (name: "T3", structure: [-0.01]),
    ],
)"#,
        a1 / 2.0
    )
}

#[test]
fn a_maximum_is_a_constraint_of_the_choice_not_a_check_after_it() {
    // Floors alone: T3 on its floor and (T1, T2) ∝ (a₁, a₂) deliver
    // a₁T₁ + a₂T₂ = 0.5 + 0.01·1, so T₁ = a₁·0.51/(a₁² + a₂²) = 20.8 N: above a 15 N maximum.
    // With the maximum as a constraint the optimum is T = (15, 22, 1): T₂ = (0.51 − 15a₁)/a₂
    // = 52·(1 − 15/26) = 22 N, and its KKT multipliers are non-negative (T = Aᵀy − ν₁e₁ + μ₃e₃
    // with y = 22/a₂, ν₁ = a₁y − 15 = 29, μ₃ = 1 + 0.01y ≈ 23.4).
    let m = tendyn_core::parse(&one_joint_three_tendons(15.0, 30.0)).unwrap();
    assert_eq!(m.system().null_space.len(), 2);
    let r = Data::new(&m)
        .inverse_dynamics(&m, &[0.3], &[0.0], &[50.0])
        .unwrap()
        .clone();
    let want = [15.0, 22.0, 1.0];
    for (got, want) in r.tendon_tensions.iter().zip(want) {
        assert!(
            (got - want).abs() <= 1e-13 * 22.0,
            "{:?}",
            r.tendon_tensions
        );
    }
    // Without the maximum the old answer returns, T1 = 20.8 N.
    let free = tendyn_core::parse(&one_joint_three_tendons(1e6, 1e6)).unwrap();
    let r = Data::new(&free)
        .inverse_dynamics(&free, &[0.3], &[0.0], &[50.0])
        .unwrap()
        .clone();
    assert!(
        (r.tendon_tensions[0] - 20.8).abs() < 1e-12,
        "{:?}",
        r.tendon_tensions
    );
}

#[test]
fn a_state_the_bounds_cannot_meet_names_the_tendons_at_their_maxima_and_what_they_can_do() {
    // With T2 ≤ 20 N the most the tendons give is 15a₁ + 20a₂ − 0.01·1 = 0.4804 N·m.
    let m = tendyn_core::parse(&one_joint_three_tendons(15.0, 20.0)).unwrap();
    match Data::new(&m).inverse_dynamics(&m, &[0.3], &[0.0], &[50.0]) {
        Err(Error::Tension(msg)) => assert_eq!(
            msg,
            "`T1` at its maximum 15 N and `T2` at its maximum 20 N cannot produce 0.5000 N·m \
             on `arm`; the most they can produce with every other tendon at its floor is \
             0.4804 N·m"
        ),
        other => panic!("expected a tension error, got {other:?}"),
    }
    // Pulling the other way, T3 has no maximum: every negative torque is feasible.
    assert!(Data::new(&m)
        .inverse_dynamics(&m, &[0.3], &[0.0], &[-5000.0])
        .is_ok());
}

#[test]
fn the_centered_objective_puts_opposing_tendons_mid_way_between_their_bounds() {
    // One joint, two tendons of arm r = 0.02 m pulling opposite ways, floors 1 N, maxima
    // 21 N and 41 N: c = (11, 21). Q = r(T₁ − T₂), so T₁ − T₂ = Q/r and the nearest point
    // to c on that line is c + t(1, −1) with t = (Q/r − (c₁ − c₂))/2: for Q = 0.2 N·m
    // (I = 0.01 kg·m², q̈ = 20 rad/s²) t = 10 and T = (21, 11), flex exactly at its maximum.
    let text = r#"(
    name: "antagonists", gravity: (0.0, 0.0, 0.0), tension_floor: 1.0, distribution: Centered,
    links: [(name: "arm", dh: (a: 0.1, alpha: 0.0, d: 0.0), mass: 1.0, com: (-0.1, 0.0, 0.0),
             inertia: (xx: 0.001, yy: 0.01, zz: 0.01))],
    tendons: [
        (name: "flex", structure: [0.02], max_tension: 21.0),
        (name: "ext", structure: [-0.02], max_tension: 41.0),
    ],
)"#;
    let close = |got: &[f64], want: [f64; 2]| {
        got.iter()
            .zip(want)
            .all(|(g, w)| (g - w).abs() <= 1e-13 * w.abs().max(1.0))
    };
    let m = tendyn_core::parse(text).unwrap();
    let mut s = Data::new(&m);
    let r = s.inverse_dynamics(&m, &[0.0], &[0.0], &[20.0]).unwrap();
    assert!(
        close(&r.tendon_tensions, [21.0, 11.0]),
        "{:?}",
        r.tendon_tensions
    );
    // Q = −0.7 N·m: T₁ − T₂ = −35, t = −12.5, c + t(1, −1) = (−1.5, 33.5) is below flex's
    // floor, so flex rests on it and ext takes the rest: (1, 36).
    let r = s.inverse_dynamics(&m, &[0.0], &[0.0], &[-70.0]).unwrap();
    assert!(
        close(&r.tendon_tensions, [1.0, 36.0]),
        "{:?}",
        r.tendon_tensions
    );
    // In between, nothing binds: Q = −0.2 N·m, t = 0, T = c = (11, 21).
    let r = s.inverse_dynamics(&m, &[0.0], &[0.0], &[-20.0]).unwrap();
    assert!(
        close(&r.tendon_tensions, [11.0, 21.0]),
        "{:?}",
        r.tendon_tensions
    );
    // The least-norm objective keeps the antagonist on its floor instead: (11, 1).
    let least = tendyn_core::parse(&text.replace(" distribution: Centered,", "")).unwrap();
    let r = Data::new(&least)
        .inverse_dynamics(&least, &[0.0], &[0.0], &[20.0])
        .unwrap()
        .clone();
    assert!(
        close(&r.tendon_tensions, [11.0, 1.0]),
        "{:?}",
        r.tendon_tensions
    );
}

#[test]
fn the_centered_objective_needs_every_maximum() {
    let text = one_joint_three_tendons(15.0, 30.0).replace(
        "tension_floor: 1.0,",
        "tension_floor: 1.0, distribution: Centered,",
    );
    match tendyn_core::parse(&text) {
        Err(e) => {
            let msg = e.to_string();
            assert!(
                msg.contains("T3") && msg.contains("max_tension") && msg.contains("Centered"),
                "{msg}"
            );
        }
        Ok(_) => panic!("accepted a centered distribution without every maximum"),
    }
}

/// The distribution in `f32` on null spaces of two dimensions (three tendons on one joint)
/// and three (three joints, six tendons): within the floors to `f32` round-off and at the
/// `f64` tensions to `f32` accuracy, at every one of 2,000 states. (The fixed `1e-12`
/// tolerance of the former routine rejected every candidate in `f32`.)
#[test]
fn the_distribution_is_exact_in_f32_for_two_and_three_null_directions() {
    let mechanisms = [
        THREE_ON_ONE.to_string(),
        tendyn_spec::bounded::mechanism_ron_scaled(3, 3, 6, 0.5, 4.0),
    ];
    let u = f32::EPSILON as f64 / 2.0;
    for text in mechanisms {
        let m = tendyn_core::parse(&text).unwrap();
        let d = m.system().null_space.len();
        let m32 = m.cast_numeric::<f32>();
        let (mut s64, mut s32) = (Data::new(&m), Data::new(&m32));
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (mut compared, mut infeasible) = (0, 0);
        for _ in 0..2000 {
            // States exact in f32, so that both solve the same problem.
            let mut v = |s: f64| {
                (0..m.dof())
                    .map(|_| rng.random_range(-s..s) as f32)
                    .collect::<Vec<f32>>()
            };
            let (q, qd, qdd) = (v(3.0), v(2.0), v(5.0));
            let f = |x: &[f32]| x.iter().map(|&v| v as f64).collect::<Vec<f64>>();
            let r64 = s64.inverse_dynamics(&m, &f(&q), &f(&qd), &f(&qdd));
            let r32 = s32.inverse_dynamics(&m32, &q, &qd, &qdd);
            let (r64, r32) = match (r64, r32) {
                (Ok(a), Ok(b)) => (a, b),
                (Err(_), Err(_)) => {
                    infeasible += 1;
                    continue;
                }
                // Only a state on the boundary of feasibility, to f32 round-off, may differ.
                (a, b) => panic!("{}: f64 {:?} but f32 {:?}", m.name(), a.is_ok(), b.is_ok()),
            };
            let scale = r64
                .tendon_tensions
                .iter()
                .fold(1.0f64, |a, x| a.max(x.abs()));
            for ((t, want), tendon) in r32
                .tendon_tensions
                .iter()
                .zip(&r64.tendon_tensions)
                .zip(m.tendons())
            {
                let t = *t as f64;
                assert!(
                    t >= tendon.floor - 64.0 * u * scale,
                    "{}: {t} below the floor {} (d = {d})",
                    m.name(),
                    tendon.floor
                );
                if let Some(max) = tendon.max_tension {
                    assert!(t <= max + 64.0 * u * scale, "{}: {t} above {max}", m.name());
                }
                // The inputs themselves are rounded to f32, and the tensions follow the
                // state with a condition of a few hundred at most on these mechanisms.
                assert!(
                    (t - want).abs() <= 1e4 * u * scale,
                    "{}: f32 {:?} vs f64 {:?}",
                    m.name(),
                    r32.tendon_tensions,
                    r64.tendon_tensions
                );
            }
            compared += 1;
        }
        println!(
            "{} (d = {d}): {compared} states compared, {infeasible} infeasible in both",
            m.name()
        );
        assert!(
            compared > 1000,
            "{}: only {compared} feasible states",
            m.name()
        );
    }
}

/// Two joints, four tendons whose strictly positive null vectors fill a cone only 9e-7 rad
/// wide (in null-space coordinates): controllable, with a small margin. The perceptron
/// search that validation used before gave up after 100,000 iterations and called this
/// routing uncontrollable; the linear program finds the cone. Checked against the file's
/// own structure numbers: `A p = 0` to round-off and every component of `p` positive.
#[test]
fn a_controllable_routing_with_a_thin_cone_of_positive_null_vectors_is_accepted() {
    let structure = [
        [0.015671206043274277, 0.0],
        [-0.003612010557858738, 0.007565598891127229],
        [0.006654243242714545, -0.013937813961390164],
        [0.00985331049677968, 0.01218601884933106],
    ];
    let tendons: String = structure
        .iter()
        .enumerate()
        .map(|(k, [a, b])| format!("(name: \"t{}\", structure: [{a:e}, {b:e}]),\n", k + 1))
        .collect();
    let text = format!(
        "(name: \"thin_cone\", gravity: (0.0, -9.81, 0.0), links: [
            (name: \"l1\", dh: (a: 0.2, alpha: 0.0, d: 0.0), mass: 0.5, com: (-0.1, 0.0, 0.0),
             inertia: (xx: 2.5e-5, yy: 2.2e-3, zz: 2.2e-3)),
            (name: \"l2\", dh: (a: 0.15, alpha: 0.0, d: 0.0), mass: 0.3, com: (-0.07, 0.0, 0.0),
             inertia: (xx: 1.5e-5, yy: 1.2e-3, zz: 1.2e-3)),
        ], tendons: [{tendons}])"
    );
    let m = tendyn_core::parse(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.system().null_space.len(), 2);
    let p = m
        .system()
        .positive_null
        .as_ref()
        .expect("a positive null vector");
    assert!(p.iter().all(|&x| x >= 1.0 - 1e-12), "{p:?}");
    for joint in 0..2 {
        let moments = structure.iter().zip(p).map(|(row, pk)| row[joint] * pk);
        let moment: f64 = moments.clone().sum();
        let size: f64 = moments.map(f64::abs).sum();
        assert!(
            moment.abs() <= 1e-12 * size,
            "joint {joint}: A p = {moment:e}, {p:?}"
        );
    }
}
