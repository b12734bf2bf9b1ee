//! Fixed guides: a `fixed: true` pulley after a route's anchor, which the tendon slides over
//! instead of turning (format.md §6a). Checked by hand on one joint, one pin.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::{Model, SlidingCheck};
use tendyn_core::{parse, Data, Error};
use tendyn_spec::guides::{pin_with, PIN};
use tendyn_spec::lagrangian;
use tendyn_spec::measure::{actuator_force_scale, random_state};

#[test]
fn a_tendon_over_a_frictionless_pin_keeps_its_tension_and_slides_at_its_exit_speed() {
    let model = parse(PIN).unwrap();
    let strand = &model.strands()[0];
    assert_eq!(strand.name, "over_pin");
    let guide = strand.idlers[0].guide.as_ref().expect("the pin is a guide");
    assert!(
        (guide.wrap - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
        "{}",
        guide.wrap
    );
    assert!(
        guide.wrap_is_constant(),
        "both segments are fixed in the base"
    );
    assert_eq!(model.structure_matrix(), vec![vec![0.02, -0.02]]);
    let mut solver = Data::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..100 {
        let [q, qd, qdd] = random_state(&mut rng, 1);
        let r = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let segments = &r.segment_tensions.as_ref().unwrap()[0];
        assert_eq!(segments[0], segments[1], "the pin passes the tension on");
        let (over, direct) = (r.tendon_tensions[0], r.tendon_tensions[1]);
        let q_hand = 0.02 * (over - direct);
        let q_solver = r.generalized_forces[0];
        assert!((q_hand - q_solver).abs() <= 1e-12 * (over + direct) * 0.02);
        assert!((guide.speed(&qd) - 0.02 * qd[0]).abs() <= 1e-15 * qd[0].abs());
    }
}

fn invalid(text: &str) -> String {
    match parse(text) {
        Err(e @ Error::Invalid { .. }) => e.to_string(),
        other => panic!("expected an invalid item, got {other:?}"),
    }
}

#[test]
fn bad_capstan_coefficients_are_rejected_naming_the_pulley() {
    let shown = invalid(&pin_with("mu: 0.0", "mu: -0.1"));
    assert!(
        shown.starts_with("pin (line 11,") && shown.contains("between 0"),
        "{shown}"
    );
    let shown = invalid(&pin_with("mu: 0.0", "mu: 1e300"));
    assert!(
        shown.contains("`mu` is 1e300; a capstan coefficient is between 0 (frictionless) and 10"),
        "{shown}"
    );
    // On a pulley that turns with the tendon, nothing slides.
    let shown = invalid(&pin_with("fixed: true, mu: 0.0", "mu: 0.0"));
    assert!(
        shown.contains("nothing slides") && shown.contains("friction"),
        "{shown}"
    );
    // On a fixed pulley no tendon slides over.
    let text = pin_with(
        "(name: \"over_pin\", route: [(\"drum\", Ccw), (\"pin\", Ccw)], exit: (-0.11, -0.2, 0.0)),",
        "(name: \"over_pin\", route: [(\"drum\", Cw)], exit: (-0.2, 0.02, 0.0)),",
    );
    let text = text.replacen(
        "(name: \"direct\", route: [(\"drum\", Cw)]",
        "(name: \"direct\", route: [(\"drum\", Ccw)]",
        1,
    );
    let shown = invalid(&text);
    assert!(
        shown.starts_with("pin (line 11,") && shown.contains("no tendon slides over it"),
        "{shown}"
    );
    // Friction on a guide is its `mu`, not a bearing's.
    let shown = invalid(&pin_with(
        "mu: 0.0",
        "friction: (coulomb: 0.01, viscous: 0.0)",
    ));
    assert!(shown.contains("loses tension by its `mu`"), "{shown}");
}

/// `PIN` with capstan friction `μ = 0.2` on the pin (wrap π/2). By hand: the tendon slides
/// over the pin towards its exit at `0.02 q̇`; the side it slides towards pulls, so with
/// `σ = sign(q̇)` (the sign of `q̈` at rest, 0 if that is zero too) the drum side carries
/// `T_drum = T_exit e^{−σμπ/2}`, the joint needs `Q = 0.02 (T_drum − T_direct)`, and the
/// least-norm distribution above the 2 N floors puts one tendon on its floor. Within
/// `1e-6` m/s of rest (of the sliding speed, not of `q̇`) the pin is flagged sticking, in
/// inverse dynamics' guides and in what forward dynamics (which does not know `q̈`) takes
/// at rest, and nowhere else: forward dynamics gives the motion back from the tensions
/// except where it is flagged and the impending motion gave friction a direction.
#[test]
fn a_tendon_over_a_pin_with_friction_loses_tension_by_the_capstan_law_towards_where_it_slides() {
    let model = parse(&pin_with("mu: 0.0", "mu: 0.2")).unwrap();
    assert!(model.has_capstan());
    let mut solver = Data::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let mut states: Vec<[Vec<f64>; 3]> = (0..200).map(|_| random_state(&mut rng, 1)).collect();
    // At rest: impending motion either way, and none; and within the sliding speed's band
    // though `q̇` or `q̈` is beyond 1e-6 (the pin's radius 0.02 m scales them).
    states.push([vec![0.3], vec![0.0], vec![2.0]]);
    states.push([vec![0.3], vec![0.0], vec![-2.0]]);
    states.push([vec![0.3], vec![0.0], vec![0.0]]);
    states.push([vec![0.3], vec![1e-5], vec![-2.0]]);
    states.push([vec![0.3], vec![0.0], vec![1e-5]]);
    for [q, qd, qdd] in states {
        let r = solver
            .inverse_dynamics(&model, &q, &qd, &qdd)
            .unwrap()
            .clone();
        // The band of rest is on the sliding speed `0.02 q̇` (m/s) and its rate.
        let sigma = if (0.02 * qd[0]).abs() > 1e-6 {
            qd[0].signum()
        } else if (0.02 * qdd[0]).abs() > 1e-6 {
            qdd[0].signum()
        } else {
            0.0
        };
        let f = (-sigma * 0.2 * std::f64::consts::FRAC_PI_2).exp();
        let segments = &r.segment_tensions.as_ref().unwrap()[0];
        let at_rest = (0.02 * qd[0]).abs() <= 1e-6;
        let [pin] = &tendyn_core::friction::guide_states(&model, [&q, &qd, &qdd], None)[..] else {
            panic!("one guide")
        };
        assert_eq!(
            (pin.direction, pin.sticking),
            (sigma, at_rest),
            "q̇ = {qd:?}"
        );
        let (_, resting) = tendyn_core::friction::forward_at_rest(&model, &q, &qd);
        assert_eq!(resting.len(), usize::from(at_rest), "q̇ = {qd:?}");
        let (mt, tt) = (r.motor_torques.clone(), r.tendon_tensions.clone());
        let back = solver.forward_dynamics(&model, &q, &qd, &mt, &tt).unwrap()[0];
        let gives_back = (back - qdd[0]).abs() <= 1e-9 * qdd[0].abs().max(1.0);
        assert_eq!(gives_back, !at_rest || sigma == 0.0, "q̇ = {qd:?}: q̈ {back}");
        let (over, direct) = (r.tendon_tensions[0], r.tendon_tensions[1]);
        assert_eq!(
            segments[1], over,
            "the exit segment carries the tendon's tension"
        );
        assert!(
            (segments[0] - f * over).abs() <= 1e-14 * over,
            "q̇ = {qd:?}: drum side {} is not e^(-σμβ) = {f} times {over}",
            segments[0]
        );
        // The distribution by hand: one tendon on its floor, the other what Q needs.
        let need = r.generalized_forces[0] / 0.02;
        let (want_over, want_direct) = if (need + 2.0) / f >= 2.0 {
            ((need + 2.0) / f, 2.0)
        } else {
            (2.0, 2.0 * f - need)
        };
        let size = want_over.max(want_direct);
        assert!(
            (over - want_over).abs() <= 1e-12 * size
                && (direct - want_direct).abs() <= 1e-12 * size,
            "q̇ = {qd:?}: ({over}, {direct}) where by hand ({want_over}, {want_direct})"
        );
    }
}

/// The pin's wrap angle does not change with `q`: under the exact law its capstan factor is
/// one of `e^{−μβ}`, `e^{μβ}` and 1, folded into the generated code as numbers chosen by
/// the direction (docs/generated-code.md), with no `exp` at run time. The numbers are the
/// capstan law's by hand (`μ = 0.2`, `β = π/2`); `tests/generated` checks such code
/// (`pin_then_idler_friction`) against the runtime solver.
#[test]
fn a_guide_of_constant_wrap_angle_has_its_capstan_factors_folded_into_generated_code() {
    use tendyn_codegen::{generate, Output, Scalar};
    let model = parse(&pin_with("mu: 0.0", "mu: 0.2")).unwrap();
    let code = generate(&model, &[Output::Actuation], Scalar::Generic, "pin.ron").unwrap();
    let source = code.source();
    let x = 0.2 * std::f64::consts::FRAC_PI_2;
    assert!(!source.contains(".exp()"), "{source}");
    let numbers: Vec<f64> = (source.split("T::from_f64(").skip(1))
        .filter_map(|s| s.split(')').next()?.parse().ok())
        .collect();
    for factor in [(-x).exp(), x.exp()] {
        assert!(
            (numbers.iter()).any(|n| (n - factor).abs() <= 2.0 * f64::EPSILON * factor),
            "{factor:?} not in {numbers:?}"
        );
    }
    assert!(source.contains(".select_outside("), "{source}");
}

/// The direction each guide reports (`eval --json`, Python) is the one its tensions took,
/// even where the sliding speed is within rounding of the rest band: a review found a
/// state of Example 3 (a guide on every idler, μ 0.1) where Ta's speed over idler 4 is
/// `1e-6` to a few ulps, and the report, summing the speed in another order, said
/// "sticking, −1" while the tensions had taken `+1`.
#[test]
fn a_guide_reports_the_direction_its_tensions_took_at_the_edge_of_rest() {
    let example = tendyn_spec::examples::text("example3_stanford_jpl");
    let model = parse(&tendyn_spec::guides::idlers_as_capstans(&example, 0.1)).unwrap();
    let q = [0.0; 3];
    let qd = [-0.8122808264515302, -0.9433050469559874, 0.2163062962478413];
    let qdd = [1.0, 0.0, 0.0];
    let r = Data::new(&model)
        .inverse_dynamics(&model, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let segments = r.segment_tensions.unwrap();
    let guides = tendyn_core::friction::guide_states(&model, [&q, &qd, &qdd], Some(&segments));
    let edge = (guides.iter())
        .map(|g| (g.sliding_speed.abs() - tendyn_core::friction::REST).abs())
        .fold(f64::INFINITY, f64::min);
    assert!(
        edge <= 1e-15,
        "no guide at the edge of rest here ({edge:e})"
    );
    for g in &guides {
        let guide = model.strands()[g.strand].idlers[g.idler]
            .guide
            .as_ref()
            .unwrap();
        let tensions = &segments[g.strand];
        let factor = (-g.direction * guide.mu * g.wrap_angle.max(0.0)).exp();
        let ratio = tensions[g.idler] / tensions[g.idler + 1];
        assert!(
            (ratio - factor).abs() <= 8.0 * f64::EPSILON,
            "{} over {}: tensions in ratio {ratio}, the reported direction {} gives {factor}",
            model.strands()[g.strand].name,
            model.bodies()[g.body].name,
            g.direction
        );
    }
}

/// Issue 10 asks that capstan friction cost generated code at most 1.5 times the operations
/// of the frictionless code, on Example 3 with a guide on every idler (`μ = 0.1` here):
/// `actuation` and `segment_tensions` take 263 and 269 operations against 192 each
/// without friction (1.37 and 1.40 times, docs/generated-code.md). Both the goal and the
/// figures measured are kept.
#[test]
fn capstan_friction_costs_generated_code_at_most_one_and_a_half_times_the_frictionless() {
    use tendyn_codegen::{generate, Output, Scalar};
    let example = tendyn_spec::examples::text("example3_stanford_jpl");
    let outputs = [Output::Actuation, Output::SegmentTensions];
    let counts = |text: &str| -> Vec<usize> {
        let model = parse(text).unwrap();
        let code = generate(&model, &outputs, Scalar::Generic, "example3.ron").unwrap();
        (code.functions.iter())
            .map(|(_, ops, _)| ops.arithmetic())
            .collect()
    };
    let frictionless = counts(&tendyn_spec::guides::idlers_as_guides(&example));
    let capstan = counts(&tendyn_spec::guides::idlers_as_capstans(&example, 0.1));
    let ratios: Vec<f64> = (capstan.iter().zip(&frictionless))
        .map(|(&c, &f)| c as f64 / f as f64)
        .collect();
    println!("frictionless {frictionless:?}, μ = 0.1 {capstan:?}: {ratios:.2?} times");
    // A new frictionless count moves the goal: measure both again and update them here.
    assert_eq!(frictionless, [192, 192]);
    assert!(ratios.iter().all(|&r| r <= 1.5), "{ratios:?}");
    assert!(capstan[0] <= 263 && capstan[1] <= 269, "{capstan:?}");
}

/// Generated code traces the state's system for any null space (the pin, `d = 1`: every
/// output is available; with a second direct tendon, `d = 2`: `actuation`, `base_reaction`
/// and forward dynamics, the segments and bearings refused as for any `d ≥ 2`, friction or
/// none; `tests/generated` checks Example 2 with capstan friction, with and without an
/// antagonist on drum 1, against the runtime solver).
#[test]
fn generated_capstan_friction_is_traced_for_any_null_space_and_segments_refused_for_two() {
    use tendyn_codegen::outputs::{check, Output};
    let all = [
        Output::Actuation,
        Output::SegmentTensions,
        Output::Bearings,
        Output::BaseReaction,
        Output::ForwardDynamics,
        Output::MassMatrix,
    ];
    check(&parse(&pin_with("mu: 0.0", "mu: 0.2")).unwrap(), &all).unwrap();
    let two = pin_with("mu: 0.0", "mu: 0.2").replacen(
        "(name: \"direct\", route: [(\"drum\", Cw)], exit: (-0.2, -0.02, 0.0)),",
        "(name: \"direct\", route: [(\"drum\", Cw)], exit: (-0.2, -0.02, 0.0)),\n        \
         (name: \"direct2\", route: [(\"drum\", Cw)], exit: (-0.3, -0.02, 0.0)),",
        1,
    );
    let model = parse(&two).unwrap();
    assert_eq!(model.system().null_space.len(), 2);
    for output in [Output::SegmentTensions, Output::Bearings] {
        let refused = check(&model, &[output]).unwrap_err();
        assert!(
            refused.reason.contains("2-dimensional null space"),
            "{refused:?}"
        );
    }
    let available = [Output::Actuation, Output::BaseReaction];
    check(&model, &available).unwrap();
    check(&model, &all[4..]).unwrap();
}

/// `PIN` with a turning idler after the pin on `over_pin`'s way to its exit (the review's
/// counter-example, with an idler light enough that the segment between pin and idler stays
/// taut: the capstan law is for a pulling tendon): inverse dynamics balances power with the
/// guide's dissipation, the idler's steps included; forward dynamics, whose symmetric mass
/// matrix cannot carry the idler's inertia scaled by the guide's factor, adds that part
/// (`dynamics::idlers_behind_capstan`) and gives the motion back, at run time and in
/// generated code; `generalized_forces` is what the actuators deliver through the state's
/// columns, the idler's part through the guide included.
#[test]
fn a_turning_idler_after_a_guide_with_friction_balances_power_and_forward_dynamics_gives_the_motion_back(
) {
    let text = tendyn_spec::guides::pin_then_idler(0.3);
    let model = parse(&text).unwrap();
    assert!(model.capstan_before_an_idler());
    let worst = check_capstan_power(&model, 200, 17);
    println!("pin then idler: power balance worst {worst:.2e}");
    let (forward, delivered) = check_after_inverse(&model, 200, 17);
    println!(
        "pin then idler: forward after inverse worst {forward:.2e}, generalized forces \
         against A(σ, q) T worst {delivered:.2e}"
    );
    use tendyn_codegen::outputs::Output;
    let outputs = [Output::ForwardDynamics, Output::ForwardDynamicsDerivatives];
    tendyn_codegen::outputs::check(&model, &outputs).unwrap();
}

/// Random mechanisms whose strands' first idlers are guides with friction and whose later
/// idlers turn: inverse dynamics balances power with the guides' dissipation (and its `E`
/// is the recursion's), and forward dynamics, with the idlers' inertia reaching the joints
/// through the guides' friction, gives back the motion inverse dynamics solved for, whose
/// generalized forces are what its tensions deliver through the state's columns. The same
/// again with friction in every bearing too, the turning idlers' included (whose friction
/// torque reaches the joints through the guides' friction as their inertia does).
#[test]
fn random_mechanisms_with_idlers_behind_guides_with_friction_balance_power_and_give_the_motion_back(
) {
    let mut checked = 0;
    // Most random strands pass one idler or none: 96 seeds give a few with two or more.
    for seed in 0..96u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        let Ok(model) = parse(&tendyn_spec::guides::first_idlers_as_capstans(&text, 0.1)) else {
            continue; // uncontrollable for some direction of sliding: refused, as tested above
        };
        if !model.capstan_before_an_idler() {
            continue;
        }
        let power = check_capstan_power(&model, 60, seed);
        let (forward, delivered) = check_after_inverse(&model, 60, seed);
        let capstan = tendyn_spec::guides::first_idlers_as_capstans(&text, 0.1);
        let both = parse(&tendyn_spec::friction::with_bearing_friction(
            &capstan, seed, None,
        ))
        .unwrap();
        assert!(both.has_friction() && both.has_capstan());
        let power_both = check_capstan_power(&both, 60, seed);
        let (forward_both, delivered_both) = check_after_inverse(&both, 60, seed);
        println!(
            "random_{seed}: power {power:.2e}, forward after inverse {forward:.2e}, \
             delivered {delivered:.2e}; with bearing friction too {power_both:.2e}, \
             {forward_both:.2e}, {delivered_both:.2e}"
        );
        checked += 1;
    }
    assert!(
        checked >= 3,
        "{checked} mechanisms with idlers behind guides"
    );
}

/// What inverse dynamics solved for at random sliding states (forward dynamics then takes
/// the same directions), turned back:
/// - forward dynamics fed its motor torques and tensions: the worst error in `q̈` relative
///   to the largest `|q̈|` and 1, asserted within 1e-11;
/// - its `generalized_forces` and `Data::generalized_forces` (both from the tension-free
///   recursion and, behind guides with friction, the idlers' weights) against what its
///   motor torques and tensions deliver through the state's columns `A(σ, q)`
///   (`Data::actuator_forces`: the joint rows of the state's `E`): the worst difference
///   relative to the largest `|A_jk T_k|` and `|τ|`, asserted within 1e-12.
fn check_after_inverse(model: &Model<f64>, states: usize, seed: u64) -> (f64, f64) {
    let mut solver = Data::new(model);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut forward, mut delivered) = (0.0f64, 0.0f64);
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, model.dof());
        let Ok(r) = solver.inverse_dynamics(model, &q, &qd, &qdd) else {
            continue; // an uncontrollable state, counted by the power check
        };
        let r = r.clone();
        let (tau, t) = (&r.motor_torques, &r.tendon_tensions);
        let back = solver.forward_dynamics(model, &q, &qd, tau, t).unwrap();
        let size = qdd.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let e = back
            .iter()
            .zip(&qdd)
            .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()))
            / size;
        assert!(e <= 1e-11, "{}: q̈ {back:?} for {qdd:?}", model.name());
        forward = forward.max(e);

        let through_columns = solver.actuator_forces(model, &q, &qd, tau, t).unwrap();
        let alone = solver
            .generalized_forces(model, &q, &qd, &qdd)
            .unwrap()
            .to_vec();
        let size = actuator_force_scale(model, &q, &qd, tau, t);
        for ((a, b), c) in (r.generalized_forces.iter())
            .zip(&alone)
            .zip(&through_columns)
        {
            let e = (a - c).abs().max((b - c).abs()) / size;
            assert!(
                e <= 1e-12,
                "{}: Q {:?} and {alone:?} for {through_columns:?}",
                model.name(),
                r.generalized_forces
            );
            delivered = delivered.max(e);
        }
    }
    (forward, delivered)
}

/// Forward dynamics with capstan friction: the tendons act through the state's columns
/// `A(σ, q)`, `σ` from `q̇`. Fed the motor torques and tensions inverse dynamics solved
/// for, it gives `q̈` back (relative to the size of the terms it sums), on the pin and on
/// the capstan example, at random states (sliding, so both take the same direction).
#[test]
fn forward_dynamics_with_capstan_friction_gives_back_the_motion_inverse_dynamics_solved_for() {
    let example = std::fs::read_to_string("../examples/mechanisms/example2_capstan.ron").unwrap();
    for text in [pin_with("mu: 0.0", "mu: 0.2"), example] {
        let model = parse(&text).unwrap();
        let mut solver = Data::new(&model);
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let mut worst = 0.0f64;
        for _ in 0..200 {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            let r = solver
                .inverse_dynamics(&model, &q, &qd, &qdd)
                .unwrap()
                .clone();
            let (tau, t) = (&r.motor_torques, &r.tendon_tensions);
            let back = solver
                .forward_dynamics(&model, &q, &qd, tau, t)
                .unwrap()
                .to_vec();
            let size = solver
                .forward_dynamics_scale(&model, &q, &qd, tau, t)
                .unwrap();
            let e = back
                .iter()
                .zip(&qdd)
                .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()))
                / size;
            worst = worst.max(e);
        }
        println!("{}: forward after inverse, worst {worst:.2e}", model.name());
        assert!(worst <= 1e-12, "{}: {worst:e}", model.name());
    }
}

#[test]
fn a_guide_on_a_joint_axis_wraps_more_as_the_link_its_tendon_arrives_from_turns() {
    // Example 2 with its idlers fixed: each tendon arrives at its guide (on joint 1's axis,
    // carried by the base) along a segment fixed in link 1 and leaves along one fixed in the
    // base. The arrival point turns with link 1 by q1; both turns are clockwise (s = −1), so
    // β = s (departure − arrival) grows by exactly q1.
    let text = std::fs::read_to_string("../examples/mechanisms/example2_open_ended.ron").unwrap();
    let text = tendyn_spec::guides::idlers_as_guides(&text);
    let model = parse(&text).unwrap();
    // The geometry itself at q1 = 0.25: the same file with link 1's DH offset raised by
    // 0.25 rad, whose reference pose (where wrap angles are taken) is that pose.
    let link1 = "dh: (a: 0.30, alpha: 0.0, d: 0.0)";
    assert_eq!(text.matches(link1).count(), 1);
    let turned =
        parse(&text.replacen(link1, "dh: (a: 0.30, alpha: 0.0, d: 0.0, offset: 0.25)", 1)).unwrap();
    for (strand, there) in model.strands()[..2].iter().zip(turned.strands()) {
        let g = strand.idlers[0].guide.as_ref().unwrap();
        assert!(!g.wrap_is_constant());
        assert_eq!(g.wrap_rate, vec![1.0, 0.0], "{}", strand.name);
        let at = there.idlers[0].guide.as_ref().unwrap().wrap;
        assert!(
            (g.wrap_at(&[0.25, -1.0]) - at).abs() < 1e-12,
            "{}: {at}",
            strand.name
        );
    }
}

/// Power balance with dissipation at `states` random states of a mechanism whose guides
/// have capstan friction: the actuators' and the environment's power, `Σ_k T_k (A_k · q̇) +
/// Σ_m τ_m (c_m · q̇) + Q_ext · q̇`, is the rate of the mechanism's energy (Lagrange,
/// `tests/reference`) plus what the guides dissipate, `Σ (T_high − T_low) |v|` from the
/// tensions on their two sides and their sliding speeds (`A`, `c` and `v` are kinematics:
/// friction changes none of them), plus what any bearing friction dissipates
/// (`tendyn_spec::friction::dissipated_power`, from the law and the bodies' rates); a
/// guide's loss is never negative where its tendon pulls on both sides. Returns the worst
/// relative error.
fn check_capstan_power(model: &Model<f64>, states: usize, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut solver = Data::new(model);
    let mut worst = 0.0f64;
    let (mut lossy, mut uncontrollable) = (0, 0);
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, model.dof());
        let r = match solver.inverse_dynamics(model, &q, &qd, &qdd) {
            Ok(r) => r,
            // Wrap angles change with q, so a routing controllable at q = 0 whichever way
            // its tendons slide may not be everywhere: such a state is an error that says so.
            Err(Error::Tension(e)) if e.contains("controllable in this direction") => {
                uncontrollable += 1;
                continue;
            }
            Err(e) => panic!("{}: {e} at {q:?} {qd:?} {qdd:?}", model.name()),
        };
        let r = r.clone();
        check_state_matrix(model, &mut solver, [&q, &qd, &qdd]);
        let terms = lagrangian::power_in(model, &q, &qd, &r.tendon_tensions, &r.motor_torques);
        let power: f64 = terms.iter().sum();
        let de = lagrangian::energy_rate(model, &q, &qd, &qdd);
        let segments = r.segment_tensions.as_ref().unwrap();
        let mut loss = 0.0;
        for (strand, tensions) in model.strands().iter().zip(segments) {
            for (k, idler) in strand.idlers.iter().enumerate() {
                if let Some(g) = &idler.guide {
                    let v = g.speed(&qd);
                    let step = (tensions[k + 1] - tensions[k]) * v;
                    // The capstan law is a pulling tendon's: where a turning idler behind
                    // the guide needs more than the tendon carries (its inertia or bearing
                    // friction), the segments at the guide come out negative and the law
                    // has no physical meaning there (docs/format.md §6a).
                    if tensions[k] > 0.0 && tensions[k + 1] > 0.0 {
                        assert!(step >= 0.0, "{}: a guide gives {step} W", model.name());
                    }
                    loss += step;
                    // The capstan law itself, its wrap angle from the guide's geometry at q
                    // and its direction from the sliding speed (not the solver's factors).
                    if v.abs() > 1e-6 {
                        let f = (-v.signum() * g.mu * g.wrap_at(&q).max(0.0)).exp();
                        let ratio = tensions[k] - f * tensions[k + 1];
                        assert!(
                            ratio.abs() <= 1e-12 * tensions[k + 1].abs().max(1.0),
                            "{}: {} is not e^(-σμβ) = {f} times {}",
                            model.name(),
                            tensions[k],
                            tensions[k + 1]
                        );
                    }
                }
            }
        }
        lossy += usize::from(loss > 0.0);
        let loss = loss + tendyn_spec::friction::dissipated_power(model, &qd);
        let scale = terms.iter().map(|x| x.abs()).sum::<f64>() + de.abs() + loss;
        let e = (power - de - loss).abs() / scale;
        assert!(
            e <= 1e-11,
            "{}: power balance off by {e:.3e} (loss {loss})",
            model.name()
        );
        worst = worst.max(e);
    }
    assert!(
        lossy > states / 2,
        "{}: the guides hardly dissipate",
        model.name()
    );
    assert!(
        uncontrollable <= states / 4,
        "{}: uncontrollable at {uncontrollable} states",
        model.name()
    );
    if uncontrollable > 0 {
        println!(
            "{}: uncontrollable at {uncontrollable} of {states} states",
            model.name()
        );
    }
    worst
}

/// The state's `E(σ, q)`, which the solver takes from each segment's share of the
/// transmission's rates scaled by the capstan factors (`tension::state_matrix`), is what the
/// recursion's own statics give at that state: minus the coefficients of its balance rows
/// on the strand tensions (the pull of each segment on the bodies at its two ends).
///
/// For every size (the recursion's affine rows stop at 12 unknowns): the shares up to a
/// guide, on the joints' rows, are the rate at which the tendon slides over it (the rim
/// rate an idler there would have), `Guide::slide`.
fn check_state_matrix(model: &Model<f64>, solver: &mut Data<f64>, [q, qd, qdd]: [&[f64]; 3]) {
    for (s, k, _, guide) in model.guides() {
        let shares = &model.strands()[s].shares;
        for (j, slide) in guide.slide.iter().enumerate() {
            let sum: f64 = shares[..=k].iter().map(|share| share[j]).sum();
            let size = 1e-3f64.max(slide.abs());
            assert!(
                (sum - slide).abs() <= 1e-12 * size,
                "{}: strand {s}, guide {k}: shares sum to {sum} on joint {j}, slide {slide}",
                model.name()
            );
        }
    }
    if model.system().unknowns.len() > tendyn_core::affine::MAX_UNKNOWNS {
        return;
    }
    let rows = solver.balance_rows(model, q, qd, qdd).unwrap();
    let mut factors: Vec<Vec<f64>> = (model.strands().iter())
        .map(|s| vec![1.0; s.idlers.len()])
        .collect();
    tendyn_core::friction::capstan_factors(model, q, qd, Some(qdd), &mut factors);
    let e = tendyn_core::tension::state_matrix(model, &factors);
    let size = e.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for (r, row) in rows.iter().enumerate() {
        if matches!(
            model.system().rows[r],
            tendyn_core::model::Row::Pretension(_)
        ) {
            continue;
        }
        for strand in model.strands() {
            let k = strand.unknown;
            let recursion = -row.coefficients[k];
            assert!(
                (recursion - e[r][k]).abs() <= 1e-13 * size,
                "{}: E[{r}][{k}] is {} from the transmission but {recursion} from the recursion",
                model.name(),
                e[r][k]
            );
        }
    }
}

#[test]
fn example_2_with_capstan_friction_on_both_guides_balances_power_with_dissipation() {
    // The example file (README) is Example 2 with both idlers made guides at μ = 0.3.
    let text = std::fs::read_to_string("../examples/mechanisms/example2_capstan.ron").unwrap();
    let model = parse(&text).unwrap();
    let guides: Vec<f64> = model
        .strands()
        .iter()
        .flat_map(|s| &s.idlers)
        .filter_map(|i| i.guide.as_ref().map(|g| g.mu))
        .collect();
    assert_eq!(guides, vec![0.3, 0.3]);
    let worst = check_capstan_power(&model, 300, 21);
    println!("example 2 with capstan friction: worst relative error {worst:.2e}");
}

#[test]
fn random_mechanisms_with_capstan_friction_on_every_guide_balance_power_with_dissipation() {
    let (mut checked, mut guides, mut refused) = (0, 0, Vec::new());
    for seed in 0..24u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: seed % 3 == 1,
        };
        let (text, model) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        let idlers = model
            .bodies()
            .iter()
            .filter(|b| {
                matches!(
                    b.kind,
                    tendyn_core::model::BodyKind::Pulley {
                        role: tendyn_core::model::PulleyRole::Idler { .. },
                        ..
                    }
                )
            })
            .count();
        if idlers == 0 {
            continue;
        }
        match parse(&tendyn_spec::guides::idlers_as_capstans(&text, 0.05)) {
            Ok(model) => {
                let worst = check_capstan_power(&model, 100, seed);
                println!("random_{seed}: {idlers} guides, worst relative error {worst:.2e}");
                checked += 1;
                guides += idlers;
            }
            // Validation checks every direction of sliding: a refusal must say which.
            Err(e @ Error::Routing { .. }) if e.to_string().contains("whichever way") => {
                refused.push(seed)
            }
            Err(e) => panic!("random_{seed}: {e}"),
        }
    }
    println!("{checked} mechanisms with {guides} guides checked; refused: {refused:?}");
    assert!(checked >= 4, "{checked} checked, {refused:?} refused");
}

#[test]
fn capstan_friction_puts_no_limit_on_the_unknowns_and_chain12_gives_back_its_motion() {
    // The state's `E` comes from the transmission's rates (`tension::state_matrix`), not
    // from rows affine in the unknowns (at most 12): chain12's 13 unknowns are solved with
    // its idlers made guides with friction.
    let text = std::fs::read_to_string("../bench/mechanisms/chain12.ron").unwrap();
    let model = parse(&tendyn_spec::guides::idlers_as_capstans(&text, 0.2)).unwrap();
    assert_eq!(model.system().unknowns.len(), 13);
    assert!(model.has_capstan());
    // chain12 drives some joints through coupled pulleys, so it reports no segment tensions
    // and the power balance above cannot be taken: its shares are checked against the
    // guides' sliding rates, and forward dynamics gives back the motion.
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut solver = Data::new(&model);
    for _ in 0..20 {
        let [q, qd, qdd] = random_state(&mut rng, 12);
        check_state_matrix(&model, &mut solver, [&q, &qd, &qdd]);
        let r = solver
            .inverse_dynamics(&model, &q, &qd, &qdd)
            .unwrap()
            .clone();
        assert!(r.tendon_tensions.iter().all(|t| t.is_finite() && *t > 0.0));
        let back = solver
            .forward_dynamics(&model, &q, &qd, &r.motor_torques, &r.tendon_tensions)
            .unwrap();
        let size = qdd.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (a, b) in back.iter().zip(&qdd) {
            assert!((a - b).abs() <= 1e-9 * size, "q̈ {a} for {b}");
        }
    }
}

/// A routing controllable without friction but not whichever way its tendons slide (seeded
/// random mechanism 0, its idlers made guides with `μ = 0.5`): a routing error at the first
/// guide's line that names each tendon, guide and direction of the failing pattern.
#[test]
fn a_routing_that_friction_makes_uncontrollable_in_some_direction_of_sliding_is_refused() {
    let features = tendyn_spec::random_mechanism::Features {
        coupled_pulleys: false,
        endless: false,
    };
    let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(0, features);
    let e = parse(&tendyn_spec::guides::idlers_as_capstans(&text, 0.5)).unwrap_err();
    let shown = e.to_string();
    assert!(matches!(e, Error::Routing { .. }), "{shown}");
    assert!(
        shown.starts_with("idler1_1 (line ")
            && shown.contains("whichever way the tendons slide")
            && shown.contains("`t1` over `idler1_1` towards its anchor")
            && shown.contains("`t2` over `idler2_1` towards its anchor")
            && shown.contains("(at q = 0)")
            && shown.contains("no longer lifts every tendon together"),
        "{shown}"
    );
}

/// A 10-joint finger with every idler a guide at `μ = 2` has 54 groups of guides, far too
/// many ways of sliding to take one by one, and no box of factors settles it. Among the
/// ways every guide slides, a descent finds one that leaves a tendon nearly slack, and
/// validation refuses the routing naming it (docs/format.md §6a). Checked without
/// validation's code: the named way, read back from the message, is produced by a `q̇`
/// (found by a perceptron on the guides' sliding rates), and at it the null vector of
/// `E` (an SVD) holds some tendon below `1e-7` of the largest, which an SVD cannot tell
/// from validation's `1e-9` on this matrix (`σ_min/σ_max` near `1e-7`).
#[test]
fn past_the_ways_taken_one_by_one_a_descent_finds_where_sliding_leaves_a_tendon_nearly_slack() {
    let finger = tendyn_spec::stress::Arm::new("finger", 10, 10);
    let e = parse(&tendyn_spec::guides::idlers_as_capstans(&finger.ron(), 2.0)).unwrap_err();
    let shown = e.to_string();
    assert!(matches!(e, Error::Routing { .. }), "{shown}");
    assert!(
        shown.contains("whichever way the tendons slide")
            && shown.contains("within round-off of slack"),
        "{shown}"
    );
    // The way: "`TENDON` over `GUIDE` towards its anchor|exit", one per guide.
    let pieces: Vec<&str> = shown.split('`').collect();
    let mut way = std::collections::HashMap::new();
    for i in 1..pieces.len().saturating_sub(3) {
        if pieces[i + 1] == " over " {
            let towards = pieces[i + 3];
            assert!(towards.starts_with(" towards its "), "{towards}");
            let sigma = if towards.starts_with(" towards its exit") {
                1.0
            } else {
                -1.0
            };
            way.insert((pieces[i].to_string(), pieces[i + 2].to_string()), sigma);
        }
    }
    // The same finger with a μ validation accepts gives the guides, their wrap angles at
    // `q = 0` and sliding rates, and `E` at any capstan factors.
    let model = parse(&tendyn_spec::guides::idlers_as_capstans(&finger.ron(), 0.1)).unwrap();
    let mut capstan: Vec<Vec<f64>> = (model.strands().iter())
        .map(|s| vec![1.0; s.idlers.len()])
        .collect();
    let mut rates = Vec::new();
    for (s, k, body, guide) in model.guides() {
        let key = (
            model.strands()[s].name.clone(),
            model.bodies()[body].name.clone(),
        );
        let sigma = way[&key];
        capstan[s][k] = (-sigma * 2.0 * guide.wrap.max(0.0)).exp();
        rates.push((sigma, guide.slide.clone()));
    }
    assert_eq!(way.len(), rates.len(), "every guide is named");
    // A `q̇` sliding every guide the named way, by a perceptron's corrections.
    let mut qd = vec![0.0; model.dof()];
    let norm = |u: &[f64]| u.iter().map(|x| x * x).sum::<f64>().sqrt();
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    for _ in 0..100_000 {
        let Some((sigma, u)) = (rates.iter()).find(|(s, u)| s * dot(u, &qd) <= 1e-3 * norm(u))
        else {
            break;
        };
        qd.iter_mut()
            .zip(u)
            .for_each(|(q, a)| *q += sigma * a / norm(u));
    }
    assert!(
        rates.iter().all(|(s, u)| s * dot(u, &qd) > 1e-3 * norm(u)),
        "no motion slides the guides so: {qd:?}"
    );
    let e = tendyn_core::tension::state_matrix(&model, &capstan);
    let (rows, columns) = (e.len(), e[0].len());
    let padded = nalgebra::DMatrix::from_fn(
        columns,
        columns,
        |i, j| {
            if i < rows {
                e[i][j]
            } else {
                0.0
            }
        },
    );
    let svd = nalgebra::linalg::SVD::new(padded, false, true);
    let least = svd.singular_values.imin();
    let v_t = svd.v_t.unwrap();
    let null: Vec<f64> = (0..columns).map(|j| v_t[(least, j)]).collect();
    let largest = null.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let sign = null.iter().sum::<f64>().signum();
    let tendons: Vec<usize> = model.tendons().iter().map(|t| t.unknown).collect();
    let slackest = (tendons.iter()).fold(f64::INFINITY, |a, &k| a.min(sign * null[k] / largest));
    assert!(
        slackest < 1e-7,
        "least tendon {slackest:e} of the largest: {null:?}"
    );
}

/// A finger whose every joint has a flexor and an extensor ending on its link stays
/// controllable whatever its friction: at each joint, from the tip, a tendon of each sign
/// enters, and the capstan factors, all positive, change no entry's sign (docs/format.md
/// §6a, `E`'s signs). At 10 joints and `μ = 2` (99 guides, 11 null directions), which
/// boxes of factors did not settle, validation shows it at every capstan factor (checked
/// without its code at the vertices of the box in
/// `where_validation_shows_every_capstan_factor_no_factor_the_guides_can_take_loosens_a_tendon`).
/// At `μ = 4` the capstan factors multiply up to `e^22` along one tendon: where every guide
/// slides some tendon's tension would be more than `1e9` times another's, and validation
/// refuses the routing saying that floating point, not the routing, fails there.
#[test]
fn a_flexor_and_an_extensor_on_every_joint_keep_a_finger_controllable_whatever_its_friction() {
    let mut finger = tendyn_spec::stress::Arm::new("finger", 10, 10);
    finger.antagonists = true;
    let at = |mu: f64| parse(&tendyn_spec::guides::idlers_as_capstans(&finger.ron(), mu));
    let model = at(2.0).unwrap();
    assert_eq!(model.system().null_space.len(), 11);
    assert_eq!(
        model.sliding_check(),
        SlidingCheck::EveryFactor { boxes: 1 }
    );
    let refused = at(4.0).unwrap_err().to_string();
    for said in [
        "E's signs show it is, in exact arithmetic, but sliding",
        "capstan factors up to e^22.1 along one tendon, more than floating point resolves",
        "lower `mu`",
    ] {
        assert!(refused.contains(said), "{refused}");
    }
}

/// Two joints driven by four tendons (a two-dimensional null space), one of which slides over
/// a pin on link 1 with `μ = 0.4` (found by a seeded random search). Without friction the
/// routing is controllable; sliding `t2` over the pin towards its anchor, no tensions lift
/// every tendon together (the runtime solver then refuses such states). With the exact
/// law and fixed wrap angles no state lies between the points, so only the points' own
/// check can see it, which before checked the rank alone with two or more null directions.
const PIN_ON_LINK_1: &str = r#"(
    name: "pin on link 1",
    links: [
        (name: "l1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0),
        (name: "l2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.5),
    ],
    pulleys: [
        (name: "e", carrier: "l1", at: Joint(joint: "l1", height: 0.0), radius: 0.02, fixed: true),
        (name: "d1", carrier: "l2", at: Joint(joint: "l2", height: 0.01), radius: 0.02, fixed: true),
        (name: "g1", carrier: "base", at: Joint(joint: "l1", height: 0.01), radius: 0.018, fixed: true),
        (name: "d2", carrier: "l2", at: Joint(joint: "l2", height: 0.02), radius: 0.02, fixed: true),
        (name: "g2", carrier: "base", at: Joint(joint: "l1", height: 0.02), radius: 0.024, fixed: true),
        (name: "p", carrier: "l1", at: Pose(origin: (-0.23, -0.036, 0.02), rpy: (0.0, 0.0, 0.0)), radius: 0.01, fixed: true, mu: 0.4),
    ],
    tendons: [
        (name: "t0", route: [("e", Cw)], exit: (-0.1, 0.2, 0.0)),
        (name: "t1", route: [("d1", Ccw), ("g1", Cw)], exit: (-0.18, -0.09, 0.01)),
        (name: "t2", route: [("d2", Cw), ("p", Cw), ("g2", Ccw)], exit: (-0.14, 0.2, 0.02)),
        (name: "t3", route: [("e", Cw)], exit: (-0.2, 0.03, 0.0)),
    ],
)"#;

#[test]
fn with_two_null_directions_a_sliding_direction_that_lifts_no_tendon_set_is_refused() {
    // Without friction: controllable.
    parse(&PIN_ON_LINK_1.replace("mu: 0.4", "mu: 0.0")).unwrap();
    let e = parse(PIN_ON_LINK_1).unwrap_err();
    let shown = e.to_string();
    assert!(matches!(e, Error::Routing { .. }), "{shown}");
    assert!(
        shown.starts_with("p (line ")
            && shown.contains("whichever way the tendons slide")
            && shown.contains("sliding `t2` over `p` towards its anchor (at q = 0)")
            && shown.contains("no null vector of the tension system lifts them all"),
        "{shown}"
    );
}

/// With `friction_smoothing`, states lie between rest and each direction of sliding, which
/// validation covers by a fixed basis (docs/format.md §6a): two tendons held in one proportion
/// that keep the others taut at rest and at every point. Here (two joints, four tendons
/// over pins on link 1 and guides on joint 1's axis with `μβ` up to about 3.4, found by a
/// seeded random search) every point alone is controllable, but the columns turn and
/// scale so differently from point to point that no pair holds: validation cannot show the
/// states between controllable and refuses, saying so.
#[test]
fn a_routing_no_fixed_basis_carries_between_rest_and_sliding_is_refused() {
    let text = r#"(
    name: "no fixed basis",
    friction_smoothing: 0.01,
    links: [
        (name: "l1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.0),
        (name: "l2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.5),
    ],
    pulleys: [
        (name: "d0", carrier: "l2", at: Joint(joint: "l2", height: 0.0000), radius: 0.0185, fixed: true),
        (name: "g0", carrier: "base", at: Joint(joint: "l1", height: 0.0000), radius: 0.0179, fixed: true, mu: 8.4172),
        (name: "d1", carrier: "l2", at: Joint(joint: "l2", height: 0.0100), radius: 0.0139, fixed: true),
        (name: "g1", carrier: "base", at: Joint(joint: "l1", height: 0.0100), radius: 0.0103, fixed: true, mu: 2.7661),
        (name: "p1", carrier: "l1", at: Pose(origin: (-0.0446, -0.0027, 0.0100), rpy: (0.0, 0.0, 0.0)), radius: 0.0141, fixed: true, mu: 6.2643),
        (name: "d2", carrier: "l2", at: Joint(joint: "l2", height: 0.0200), radius: 0.0221, fixed: true),
        (name: "g2", carrier: "base", at: Joint(joint: "l1", height: 0.0200), radius: 0.0268, fixed: true),
        (name: "p2", carrier: "l1", at: Pose(origin: (-0.0719, -0.0430, 0.0200), rpy: (0.0, 0.0, 0.0)), radius: 0.0090, fixed: true, mu: 3.2250),
        (name: "d3", carrier: "l2", at: Joint(joint: "l2", height: 0.0300), radius: 0.0165, fixed: true),
        (name: "g3", carrier: "base", at: Joint(joint: "l1", height: 0.0300), radius: 0.0171, fixed: true),
    ],
    tendons: [
        (name: "t0", route: [("d0", Ccw), ("g0", Cw)], exit: (-0.1596, 0.0004, 0.0000)),
        (name: "t1", route: [("d1", Cw), ("p1", Cw), ("g1", Ccw)], exit: (-0.1015, -0.1802, 0.0100)),
        (name: "t2", route: [("d2", Cw), ("p2", Cw), ("g2", Cw)], exit: (-0.1428, 0.0155, 0.0200)),
        (name: "t3", route: [("d3", Ccw), ("g3", Ccw)], exit: (-0.1656, 0.0438, 0.0300)),
    ],
)"#;
    // Without friction: controllable.
    let frictionless = ["8.4172", "2.7661", "6.2643", "3.2250"]
        .iter()
        .fold(text.to_string(), |t, mu| {
            t.replace(&format!("mu: {mu}"), "mu: 0.0")
        });
    parse(&frictionless).unwrap();
    let e = parse(text).unwrap_err();
    let shown = e.to_string();
    assert!(matches!(e, Error::Routing { .. }), "{shown}");
    // Not a point that fails (that message says "whichever way the tendons slide"): the
    // states between rest and the points.
    assert!(
        shown.starts_with("g0 (line ")
            && shown.contains("must stay controllable between rest and every direction of sliding")
            && shown.contains("no 2 tendons do up to sliding")
            && !shown.contains("whichever way"),
        "{shown}"
    );
}

/// The per-state system in every precision: on the capstan example, inverse dynamics in
/// `f64` and `f32` against the double-double solver (a reference of precision: it solves
/// the state's system by the same QR in its own arithmetic; the physics is checked above,
/// by hand and by power balance): tendon and segment tensions within 1e-12 (`f64`) and
/// `2¹⁰ u` of `f32`, `‖T − T_ref‖∞ / ‖T_ref‖∞`, at random states (their sliding speeds far
/// from rest, so every precision slides the same way).
#[test]
fn capstan_tensions_agree_with_double_double_in_f64_and_f32() {
    use tendyn_core::{DoubleDouble, Numeric};
    let text = std::fs::read_to_string("../examples/mechanisms/example2_capstan.ron").unwrap();
    let model = parse(&text).unwrap();
    let (m32, mdd) = (
        model.cast_numeric::<f32>(),
        model.cast_numeric::<DoubleDouble>(),
    );
    let (mut s64, mut s32, mut sdd) = (Data::new(&model), Data::new(&m32), Data::new(&mdd));
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    for _ in 0..300 {
        let [q, qd, qdd] = random_state(&mut rng, model.dof());
        // Exact in f32, so that every precision solves the same state.
        let narrow = |x: &[f64]| x.iter().map(|&v| v as f32).collect::<Vec<f32>>();
        let (q32, qd32, qdd32) = (narrow(&q), narrow(&qd), narrow(&qdd));
        let wide = |x: &[f32]| x.iter().map(|&v| v as f64).collect::<Vec<f64>>();
        let (q, qd, qdd) = (wide(&q32), wide(&qd32), wide(&qdd32));
        let dd = |x: &[f64]| x.iter().map(|&v| DoubleDouble::from(v)).collect::<Vec<_>>();
        let reference = sdd
            .inverse_dynamics(&mdd, &dd(&q), &dd(&qd), &dd(&qdd))
            .unwrap();
        let all = |t: &[DoubleDouble], s: &[Vec<DoubleDouble>]| -> Vec<f64> {
            t.iter()
                .chain(s.iter().flatten())
                .map(|v| v.to_f64())
                .collect()
        };
        let want = all(
            &reference.tendon_tensions,
            reference.segment_tensions.as_ref().unwrap(),
        );
        let r64 = s64.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let got64: Vec<f64> = r64
            .tendon_tensions
            .iter()
            .chain(r64.segment_tensions.as_ref().unwrap().iter().flatten())
            .copied()
            .collect();
        worst64 = worst64.max(tendyn_spec::measure::max_rel(&got64, &want));
        let r32 = s32.inverse_dynamics(&m32, &q32, &qd32, &qdd32).unwrap();
        let got32: Vec<f64> = r32
            .tendon_tensions
            .iter()
            .chain(r32.segment_tensions.as_ref().unwrap().iter().flatten())
            .map(|&v| v as f64)
            .collect();
        worst32 = worst32.max(tendyn_spec::measure::max_rel(&got32, &want));
    }
    let u32 = f32::unit_roundoff();
    println!(
        "capstan example: worst f64 {worst64:.2e}, f32 {worst32:.2e} ({:.0} u)",
        worst32 / u32
    );
    assert!(worst64 <= 1e-12, "f64 {worst64:e}");
    assert!(worst32 <= 1024.0 * u32, "f32 {worst32:e}");
}

/// What validation's check of sliding directions rests on (one null direction,
/// `validate::tension_system::sliding_directions`): each maximal minor of the state's `E`
/// (`tension::state_matrix`) is affine in every guide's capstan factor taken alone, so
/// inside a box of factors it is the multilinear interpolation of its values at the box's
/// corners, and its sign there is settled by theirs. Checked with minors of its own
/// (`nalgebra`'s determinants) on Example 3 with a guide on every idler, Example 2 with
/// capstan friction and the random mechanisms with guides, at random factors in
/// `[1/2, 2]`: within `1e-11` of the largest corner value.
#[test]
fn every_maximal_minor_of_the_state_tension_matrix_is_multilinear_in_the_capstan_factors() {
    let example3 = std::fs::read_to_string("../examples/mechanisms/example3_stanford_jpl.ron");
    let example2 = std::fs::read_to_string("../examples/mechanisms/example2_capstan.ron");
    let mut texts = vec![
        tendyn_spec::guides::idlers_as_capstans(&example3.unwrap(), 0.1),
        example2.unwrap(),
    ];
    for seed in 0..12u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        texts.push(tendyn_spec::guides::idlers_as_capstans(&text, 0.05));
    }
    let minors = |e: &[Vec<f64>]| -> Vec<f64> {
        let (rows, columns) = (e.len(), e[0].len());
        (0..columns)
            .map(|k| {
                let kept: Vec<usize> = (0..columns).filter(|&c| c != k).collect();
                nalgebra::DMatrix::from_fn(rows, rows, |i, j| e[i][kept[j]]).determinant()
            })
            .collect()
    };
    let (mut checked, mut worst) = (0, 0.0f64);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for text in &texts {
        let Ok(model) = parse(text) else { continue };
        let guides: Vec<(usize, usize)> = (model.strands().iter().enumerate())
            .flat_map(|(s, strand)| {
                (strand.idlers.iter().enumerate())
                    .filter(|(_, idler)| idler.capstan().is_some())
                    .map(move |(k, _)| (s, k))
            })
            .collect();
        let square_plus_one = model.system().matrix.len() + 1 == model.system().unknowns.len();
        if guides.is_empty() || guides.len() > 8 || !square_plus_one {
            continue;
        }
        let matrix = |w: &[f64]| {
            let mut capstan: Vec<Vec<f64>> = (model.strands().iter())
                .map(|s| vec![1.0; s.idlers.len()])
                .collect();
            for (&(s, k), &w) in guides.iter().zip(w) {
                capstan[s][k] = w;
            }
            tendyn_core::tension::state_matrix(&model, &capstan)
        };
        let corners: Vec<Vec<f64>> = (0..1usize << guides.len())
            .map(|bits| {
                let w: Vec<f64> = (0..guides.len())
                    .map(|g| if bits >> g & 1 == 1 { 2.0 } else { 0.5 })
                    .collect();
                minors(&matrix(&w))
            })
            .collect();
        let size = corners.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        for _ in 0..20 {
            let w: Vec<f64> = (0..guides.len())
                .map(|_| rng.random_range(0.5..2.0))
                .collect();
            let t: Vec<f64> = w.iter().map(|w| (w - 0.5) / 1.5).collect();
            let mut interpolated = vec![0.0; model.system().unknowns.len()];
            for (bits, corner) in corners.iter().enumerate() {
                let weight: f64 = (t.iter().enumerate())
                    .map(|(g, t)| if bits >> g & 1 == 1 { *t } else { 1.0 - t })
                    .product();
                for (i, c) in interpolated.iter_mut().zip(corner) {
                    *i += weight * c;
                }
            }
            for (got, want) in minors(&matrix(&w)).iter().zip(&interpolated) {
                let err = (got - want).abs() / size;
                assert!(
                    err <= 1e-11,
                    "{}: minor {got} where corners give {want}",
                    model.name()
                );
                worst = worst.max(err);
            }
        }
        checked += 1;
    }
    println!("{checked} mechanisms; worst {worst:.1e} of the largest corner minor");
    assert!(checked >= 4);
}

/// What validation accepts, the runtime solver meets: on seeded random mechanisms with
/// their idlers made guides with friction (`μ` up to 2), at `q = 0` (the wrap angles
/// validation takes) and at joint velocities so small that some guides slide and others
/// are within the `1e-6` m/s band of rest, where they take the way of `q̈`, maybe against
/// the others' (docs/format.md §6a), no state is uncontrollable.
#[test]
fn a_routing_validation_accepts_is_controllable_however_the_exact_law_sets_its_guides() {
    let mut rng = ChaCha8Rng::seed_from_u64(66);
    let (mut accepted, mut mixed, mut states) = (0, 0, 0);
    for seed in 0..80u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: seed % 3 == 1,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        for mu in [0.2, 1.0, 2.0] {
            let Ok(model) = parse(&tendyn_spec::guides::idlers_as_capstans(&text, mu)) else {
                continue;
            };
            if !model.has_capstan() {
                continue;
            }
            accepted += 1;
            let n = model.dof();
            let mut solver = Data::new(&model);
            for _ in 0..200 {
                let [_, dir, acc] = random_state(&mut rng, n);
                let speed = 10f64.powf(rng.random_range(-6.0..-3.0));
                let qd: Vec<f64> = dir.iter().map(|x| x * speed).collect();
                let scale = 10f64.powf(rng.random_range(-5.0..0.0));
                let qdd: Vec<f64> = acc.iter().map(|x| x * scale).collect();
                let q = vec![0.0; n];
                if let Err(e) = solver.inverse_dynamics(&model, &q, &qd, &qdd) {
                    panic!("random_{seed} with mu {mu}: {e} at {qd:?} {qdd:?}");
                }
                let guides = tendyn_core::friction::guide_states(&model, [&q, &qd, &qdd], None);
                let sticking = guides.iter().filter(|g| g.sticking).count();
                if sticking > 0 && sticking < guides.len() {
                    mixed += 1;
                }
                states += 1;
            }
        }
    }
    println!(
        "{accepted} mechanisms, {states} states, {mixed} with guides both sliding and in the band"
    );
    assert!(
        accepted >= 10 && mixed >= 100,
        "{accepted} mechanisms, {mixed} mixed states"
    );
}

/// Two null directions (a second tendon beside `direct`) and the smoothed law: states
/// between rest and sliding occur (`|σ| < 1`), which the points alone do not settle.
/// Validation accepts the routing by a fixed proportion of two free tendons
/// (docs/format.md §6a); at random states, with every `σ` the smoothed law gives, inverse
/// dynamics keeps every tendon at or above its floor.
#[test]
fn with_two_null_directions_validation_covers_the_states_between_rest_and_sliding() {
    let two = pin_with("mu: 0.0", "mu: 0.5")
        .replacen(
            "(name: \"direct\", route: [(\"drum\", Cw)], exit: (-0.2, -0.02, 0.0)),",
            "(name: \"direct\", route: [(\"drum\", Cw)], exit: (-0.2, -0.02, 0.0)),\n        \
             (name: \"direct2\", route: [(\"drum\", Cw)], exit: (-0.3, -0.02, 0.0)),",
            1,
        )
        .replacen(
            "tension_floor: 2.0,",
            "tension_floor: 2.0,\n    friction_smoothing: 0.01,",
            1,
        );
    let model = parse(&two).unwrap();
    assert_eq!(model.system().null_space.len(), 2);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut solver = Data::new(&model);
    for _ in 0..500 {
        let [q, qd, qdd] = random_state(&mut rng, 1);
        let qd = [qd[0] * 10f64.powf(rng.random_range(-4.0..0.0))];
        let r = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        assert!(
            r.tendon_tensions.iter().all(|&t| t >= 2.0 - 1e-9),
            "{:?}",
            r.tendon_tensions
        );
    }
}

/// Seven null directions (a 12-joint finger with a second tendon on every other link, 19
/// tendons) and the smoothed law on three or four guides at `μ = 10`, where no box of
/// factors settles the routing: too many choices of seven free tendons to take one by one
/// (50,388), so validation carries the patterns' systems to the states between them on
/// the choices a pivoted QR picks (docs/format.md §6a). With one guide set one of them
/// holds (`EveryWay`); with another none does: validation refuses it, saying it showed
/// every way but not every state between, and accepts it, saying so, where the file sets
/// `accept_sampled_sliding`. Either way inverse dynamics at `q = 0` (the wrap angles it
/// covers), moving from nearly at rest to fast, with every `σ` the smoothed law gives,
/// keeps every tendon at or above its floor.
#[test]
fn past_the_choices_taken_one_by_one_the_pivoted_free_tendons_cover_the_states_between() {
    let mut finger = tendyn_spec::stress::Arm::new("finger", 12, 12);
    finger.antagonists = true;
    finger.antagonist_every = 2;
    let frictionless = tendyn_spec::guides::idlers_as_guides(&finger.ron());
    let cases: [(&[&str], bool); 2] = [
        (&["idler8_8", "idler10_9", "idler7_3"], true),
        (&["idler10_4", "idler12_9", "idler3_2", "idler4_2"], false),
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (guides, between) in cases {
        let mut text = frictionless.clone();
        for guide in guides {
            let at = format!("name: \"{guide}\", fixed: true,");
            assert_eq!(text.matches(&at).count(), 1, "{at}");
            text = text.replacen(&at, &format!("{at} mu: 10.0,"), 1);
        }
        let text = text.replacen(
            "tension_floor:",
            "friction_smoothing: 0.01,\n  tension_floor:",
            1,
        );
        if !between {
            let refused = parse(&text).unwrap_err().to_string();
            for phrase in [
                "every way the guides slide and rest",
                "not at the states between",
            ] {
                assert!(refused.contains(phrase), "{refused}");
            }
            assert!(
                refused.contains("`accept_sampled_sliding: true`"),
                "{refused}"
            );
        }
        let text = text.replacen(
            "tension_floor:",
            "accept_sampled_sliding: true,\n  tension_floor:",
            1,
        );
        let model = parse(&text).unwrap();
        assert_eq!(model.system().null_space.len(), 7);
        assert_eq!(model.tendons().len(), 19);
        match model.sliding_check() {
            SlidingCheck::EveryWay { .. } => assert!(between, "{guides:?}"),
            SlidingCheck::EveryWayNotBetween { .. } => assert!(!between, "{guides:?}"),
            other => panic!("{guides:?}: {other:?}"),
        }
        floors_kept_at_q_zero(&model, &mut rng, 300);
    }
}

/// A 5-joint finger with a second tendon on every other link (9 tendons, four null
/// directions) and every idler a guide at `μ = 10`: too many ways of sliding to take one
/// by one (14 groups of guides), and neither boxes of factors nor `E`'s signs settle it,
/// so validation can check it only at a sample of the ways every guide slides. That is
/// not a proof, so it refuses the routing, saying so and naming `accept_sampled_sliding`
/// (docs/format.md §6a); with that set it accepts it, `check` saying `only at`. Inverse
/// dynamics at `q = 0`, moving from nearly at rest to fast, then keeps every tendon at or
/// above its floor (to the distribution's tolerance, with tensions up to ~1e13 times it).
#[test]
fn a_routing_shown_only_at_sampled_ways_of_sliding_is_refused_unless_the_file_accepts_it() {
    let mut finger = tendyn_spec::stress::Arm::new("finger", 5, 5);
    finger.antagonists = true;
    finger.antagonist_every = 2;
    let text = tendyn_spec::guides::idlers_as_capstans(&finger.ron(), 10.0);
    let refused = parse(&text).unwrap_err().to_string();
    for phrase in [
        "with 14 groups of guides there are too many ways to take one by one",
        "30 of the ways every guide slides",
        "none of which fails",
        "set the top-level field `accept_sampled_sliding: true` to accept it",
    ] {
        assert!(refused.contains(phrase), "{refused}");
    }
    let accepted = text.replacen(
        "tension_floor:",
        "accept_sampled_sliding: true,\n  tension_floor:",
        1,
    );
    let model = parse(&accepted).unwrap();
    assert_eq!(
        model.sliding_check(),
        SlidingCheck::AllSliding { systems: 30 }
    );
    let text = tendyn_codegen::report::check_text(&model);
    assert!(
        text.contains("only at 30 ways every guide slides (too many directions to take one by one; accepted by `accept_sampled_sliding`)"),
        "{text}"
    );
    let json = tendyn_codegen::report::check_json(&model);
    let covers = &json["sliding_check"];
    assert!(
        covers["covers"] == "all_sliding" && covers["systems"] == 30,
        "{covers}"
    );
    floors_kept_at_q_zero(&model, &mut ChaCha8Rng::seed_from_u64(5), 300);
}

/// Inverse dynamics at `q = 0` (the wrap angles validation covers without ranges), at
/// `states` random states moving from nearly at rest (`q̇` scaled down to 1e-5) to fast,
/// keeps every tendon at or above its floor, to the distribution's tolerance on a bound:
/// `4 (K + d) u` of the largest tension (module `distribution`), which the capstan factors
/// raise by many orders of magnitude.
fn floors_kept_at_q_zero(model: &Model<f64>, rng: &mut ChaCha8Rng, states: usize) {
    let floor = model.tendons()[0].floor;
    let unknowns = (model.tendons().len() + model.system().null_space.len()) as f64;
    let mut solver = Data::new(model);
    for _ in 0..states {
        let [_, qd, qdd] = random_state(rng, model.dof());
        let slow = 10f64.powf(rng.random_range(-5.0..0.0));
        let qd: Vec<f64> = qd.iter().map(|v| v * slow).collect();
        let q = vec![0.0; model.dof()];
        let r = solver.inverse_dynamics(model, &q, &qd, &qdd).unwrap();
        let largest = r.tendon_tensions.iter().fold(floor, |a, &t| a.max(t));
        let tolerance = 4.0 * unknowns * f64::EPSILON / 2.0 * largest;
        assert!(
            r.tendon_tensions.iter().all(|&t| t >= floor - tolerance),
            "{:?}",
            r.tendon_tensions
        );
    }
}

/// With every joint given a `range` of ±1 rad, validation covers the wrap angles the
/// ranges reach, not only those at `q = 0` (docs/format.md §6a), on seeded random
/// mechanisms whose guides wrap more as the joints turn (their idlers made guides with
/// friction). A routing it accepts, the runtime solver finds controllable at random states
/// within the ranges; one it refuses (accepted without ranges: at `q = 0` it holds) names
/// a state within the ranges where the runtime solver finds it uncontrollable for some
/// motion.
#[test]
fn validation_covers_the_wrap_angles_the_joints_ranges_reach() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (mut accepted, mut refused) = (0, 0);
    for seed in 0..40u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        for mu in [0.2, 1.0] {
            let unranged = tendyn_spec::guides::idlers_as_capstans(&text, mu);
            let Ok(model) = parse(&unranged) else {
                continue;
            };
            if model.guides().all(|(.., g)| g.wrap_is_constant()) {
                continue;
            }
            let ranged = unranged.replace("dh: (", "range: (-1.0, 1.0), dh: (");
            let verdict = parse(&ranged);
            let n = model.dof();
            let mut solver = Data::new(&model);
            let mut uncontrollable = 0;
            for _ in 0..2000 {
                let [_, qd, qdd] = random_state(&mut rng, n);
                let q: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
                match solver.inverse_dynamics(&model, &q, &qd, &qdd) {
                    Ok(_) => {}
                    Err(Error::Tension(e)) if e.contains("controllable in this direction") => {
                        uncontrollable += 1
                    }
                    Err(e) => panic!("random_{seed}: {e}"),
                }
            }
            match verdict {
                Ok(ranged) => {
                    assert_eq!(uncontrollable, 0, "random_{seed} with mu {mu}");
                    // What validation accepts, code generation can solve: its fixed order
                    // of elimination holds over the same ranges.
                    let outputs = tendyn_codegen::available_outputs(&ranged);
                    assert!(
                        outputs.contains(&tendyn_codegen::Output::Actuation),
                        "random_{seed} with mu {mu}: {outputs:?}"
                    );
                    accepted += 1;
                }
                Err(e) => {
                    let shown = e.to_string();
                    assert!(shown.contains("whichever way the tendons slide"), "{shown}");
                    // The state it names: at that `q`, some motion leaves the routing
                    // uncontrollable.
                    let named = shown
                        .split("at q = [")
                        .nth(1)
                        .and_then(|r| r.split("] rad").next());
                    let q: Vec<f64> = (named.expect(&shown).split(", "))
                        .map(|x| x.parse().unwrap())
                        .collect();
                    assert!(q.iter().all(|x| x.abs() <= 1.0), "{shown}");
                    let fails_there = (0..4000).any(|_| {
                        let [_, qd, qdd] = random_state(&mut rng, n);
                        matches!(
                            solver.inverse_dynamics(&model, &q, &qd, &qdd),
                            Err(Error::Tension(e)) if e.contains("controllable in this direction")
                        )
                    });
                    assert!(
                        fails_there && uncontrollable > 0,
                        "random_{seed}, mu {mu}: {shown}"
                    );
                    refused += 1;
                }
            }
        }
    }
    println!("{accepted} accepted, {refused} refused with ranges");
    assert!(
        accepted >= 3 && refused >= 1,
        "{accepted} accepted, {refused} refused"
    );
}

/// A routing (random mechanism 563, its idlers made guides with `mu = 0.5`, joints within
/// ±1 rad) where the order of elimination that leaves the lead tendon free meets a zero
/// pivot for some direction of sliding within the ranges: code generation takes the next
/// tendon instead, and the generated `actuation` agrees with the runtime solver (1e-9 of
/// the largest tension) at random states within the ranges.
#[test]
fn where_the_lead_tendon_s_elimination_fails_generated_code_frees_another_tendon() {
    use tendyn_codegen::outputs::{trace, Output};
    use tendyn_core::tension::Elimination;
    let features = tendyn_spec::random_mechanism::Features {
        coupled_pulleys: false,
        endless: false,
    };
    let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(563, features);
    let text = tendyn_spec::guides::idlers_as_capstans(&text, 0.5)
        .replace("dh: (", "range: (-1.0, 1.0), dh: (");
    let model = parse(&text).unwrap();
    let lead = Elimination::of(&model).unwrap();
    assert!(!lead.holds_while_sliding(&model));
    let chosen = Elimination::candidates(&model)
        .into_iter()
        .find(|o| o.holds_while_sliding(&model))
        .unwrap();
    assert_ne!(chosen.free, lead.free);
    let traced = trace(&model, &[Output::Actuation]).unwrap();
    let results = &traced.functions[0].results;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut solver = Data::new(&model);
    let n = model.dof();
    let (mut worst, mut compared) = (0.0f64, 0);
    for _ in 0..200 {
        let [_, qd, qdd] = random_state(&mut rng, n);
        let q: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let Ok(r) = solver.inverse_dynamics(&model, &q, &qd, &qdd) else {
            continue;
        };
        let expected: Vec<f64> = r
            .motor_torques
            .iter()
            .chain(&r.tendon_tensions)
            .copied()
            .collect();
        let inputs: Vec<f64> = (traced.graph.input_names.iter())
            .map(|name| {
                let (array, index) = name.split_once('[').unwrap();
                let k: usize = index.trim_end_matches(']').parse().unwrap();
                match array {
                    "q" => q[k],
                    "qd" => qd[k],
                    "qdd" => qdd[k],
                    // Inputs of other functions, which `actuation` does not read.
                    _ => f64::NAN,
                }
            })
            .collect();
        let generated = traced.graph.eval(results, &inputs);
        let size = expected.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
        let e = (generated.iter().zip(&expected)).fold(0.0f64, |m, (g, x)| m.max((g - x).abs()));
        worst = worst.max(e / size);
        compared += 1;
    }
    println!(
        "lead tendon {:?}, freed {:?}: {compared} states, worst {worst:.1e}",
        lead.free, chosen.free
    );
    assert!(
        compared >= 100 && worst < 1e-9,
        "{compared} states, worst {worst:e}"
    );
}

/// Whether a tension matrix `e` is controllable, by nalgebra's SVD of `e` with its columns
/// scaled to unit length and a linear program, sharing nothing with validation: full row rank (`σ_min > 1e-10 σ_max`), the columns that
/// are not `tendons` (motors, loop sides) zero in every null vector (within `1e-9`), and
/// some null vector `N y`, `|y_i| ≤ 1`, lifting every tendon by more than `1e-9`. `Ok` with
/// that least lift.
fn controllable(e: &[Vec<f64>], tendons: &[usize]) -> Result<f64, String> {
    use microlp::{ComparisonOp, OptimizationDirection, Problem, SolveOutcome};
    let (rows, columns) = (e.len(), e[0].len());
    // Columns scaled to unit length: the null vectors scale by the inverse, which keeps
    // their signs and zeros, and the thresholds hold for any size of factor.
    let length = |c: usize| e.iter().map(|row| row[c] * row[c]).sum::<f64>().sqrt();
    let lengths: Vec<f64> = (0..columns)
        .map(|c| length(c).max(f64::MIN_POSITIVE))
        .collect();
    let scaled: Vec<Vec<f64>> = (e.iter())
        .map(|row| row.iter().zip(&lengths).map(|(x, l)| x / l).collect())
        .collect();
    let e = &scaled;
    // `E` padded with zero rows to a square: its SVD then gives every right singular
    // vector, and those beyond the rank span `null(E)` (no Gram-Schmidt completion, whose
    // round-off grows where a vector nearly lies in the span).
    let padded = nalgebra::DMatrix::from_fn(
        columns,
        columns,
        |i, j| if i < rows { e[i][j] } else { 0.0 },
    );
    let svd = nalgebra::linalg::SVD::new(padded, false, true);
    let sigma = &svd.singular_values;
    let largest = sigma.max();
    let mut order: Vec<usize> = (0..columns).collect();
    order.sort_by(|&a, &b| sigma[b].total_cmp(&sigma[a]));
    if sigma[order[rows - 1]] <= 1e-10 * largest {
        return Err(format!("rank lost: σ {sigma:?}"));
    }
    let v_t = svd.v_t.unwrap();
    let null: Vec<nalgebra::DVector<f64>> = order[rows..]
        .iter()
        .map(|&k| {
            let mut v: nalgebra::DVector<f64> = v_t.row(k).transpose();
            // Round-off left in the components, which the linear program would take as
            // coefficients 1e16 apart.
            v.apply(|x| {
                if x.abs() < 1e-13 {
                    *x = 0.0
                }
            });
            v
        })
        .collect();
    for v in &null {
        let residual = (0..rows)
            .map(|i| (0..columns).map(|c| e[i][c] * v[c]).sum::<f64>().abs())
            .fold(0.0, f64::max);
        assert!(residual <= 1e-9 * largest, "not a null vector: {residual}");
        if let Some(c) = (0..columns).find(|c| !tendons.contains(c) && v[*c].abs() > 1e-9) {
            return Err(format!("column {c} moves with the tendons"));
        }
    }
    let mut lp = Problem::new(OptimizationDirection::Maximize);
    let y: Vec<_> = null.iter().map(|_| lp.add_var(0.0, (-1.0, 1.0))).collect();
    let t = lp.add_var(1.0, (-10.0, 10.0));
    for &k in tendons {
        let mut terms: Vec<_> = y.iter().zip(&null).map(|(&y, v)| (y, v[k])).collect();
        terms.push((t, -1.0));
        lp.add_constraint(terms.as_slice(), ComparisonOp::Ge, 0.0);
    }
    let lift = match lp.solve() {
        Ok(SolveOutcome::Solution(s)) => s.var_value(t),
        other => return Err(format!("{other:?}")),
    };
    if lift > 1e-9 {
        Ok(lift)
    } else {
        Err(format!("no null vector lifts every tendon ({lift:e})"))
    }
}

/// Where validation reports [`SlidingCheck::EveryFactor`] (docs/format.md §6a), every
/// capstan factor the guides can take, `e^{λ_g}` with `|λ_g| ≤ μ β_g` (`β_g` the largest
/// wrap angle over the joints' ranges), leaves the routing controllable: checked by an SVD
/// and a linear program ([`controllable`]) sharing nothing with the boxes' bounds, at
/// every vertex of the box of factors (2000 random ones past 12 guides, where there are
/// too many, and the vertices an adversary reaches flipping one guide at a time while the
/// least lift falls) and at random points inside it. Seeded random mechanisms; and, with
/// too many directions of sliding to take one by one (which validation checked only where
/// every guide slides, before the boxes), fingers of 5 to 7 joints at `μ = 0.2` and 6 at
/// `μ = 1` (one null direction, 14 to 27 guides), 9 and 12 joints at `μ = 0.5` (44 and 77
/// guides, where the slack-tendon programs settle what boxes could not),
/// fingers of 4 to 12 joints with a second tendon on each link (5 to 13 null directions,
/// 15 to 143 guides) at `μ = 0.2` to `2`, which `E`'s signs show past the ways taken one
/// by one, and fingers of 8, 9 and 12 joints with a second tendon on every other link (5
/// to 7 null directions, which the signs do not show: the boxes and the programs with
/// cutting planes do; at 12 joints, past 26,244 choices of free tendons, on those a
/// pivoted QR picks),
/// every idler made a guide with friction. The fingers also run inverse dynamics at
/// `q = 0`, the wrap angles validation covers without ranges, moving at random.
#[test]
fn where_validation_shows_every_capstan_factor_no_factor_the_guides_can_take_loosens_a_tendon() {
    let mut texts = Vec::new();
    for seed in 0..40u64 {
        let features = tendyn_spec::random_mechanism::Features {
            coupled_pulleys: false,
            endless: seed % 3 == 1,
        };
        let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(seed, features);
        for mu in [0.05, 0.5, 2.0] {
            texts.push((tendyn_spec::guides::idlers_as_capstans(&text, mu), false));
        }
    }
    // (joints, a second tendon on every how many links (0: none), μ)
    let fingers = [
        (5, 0, 0.2),
        (6, 0, 0.2),
        (7, 0, 0.2),
        (6, 0, 1.0),
        (9, 0, 0.5),
        (12, 0, 0.5),
        (4, 1, 0.2),
        (5, 1, 0.2),
        (4, 1, 1.0),
        (6, 1, 0.5),
        (8, 1, 0.5),
        (9, 1, 1.0),
        (10, 1, 2.0),
        (12, 1, 2.0),
        (8, 2, 0.5),
        (9, 2, 1.0),
        (12, 2, 0.5),
    ];
    for (joints, every, mu) in fingers {
        let mut finger = tendyn_spec::stress::Arm::new("finger", joints, joints);
        finger.antagonists = every > 0;
        finger.antagonist_every = every;
        texts.push((
            tendyn_spec::guides::idlers_as_capstans(&finger.ron(), mu),
            true,
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let (mut accepted, mut shown, mut vertices) = (0, 0, 0);
    let mut least = f64::INFINITY;
    for (text, finger) in &texts {
        let Ok(model) = parse(text) else {
            assert!(!finger, "the fingers are controllable");
            continue;
        };
        accepted += model.has_capstan() as usize;
        let SlidingCheck::EveryFactor { .. } = model.sliding_check() else {
            assert!(!finger, "{:?}", model.sliding_check());
            continue;
        };
        shown += 1;
        let reach: Vec<(usize, usize, f64)> = (model.guides())
            .filter(|(_, _, _, g)| g.mu > 0.0)
            .map(|(s, k, _, g)| (s, k, g.mu * g.wrap_over(&model.range_box())[1]))
            .collect();
        let tendons: Vec<usize> = model.tendons().iter().map(|t| t.unknown).collect();
        let mut check = |lambda: &[f64]| -> f64 {
            let mut capstan: Vec<Vec<f64>> = (model.strands().iter())
                .map(|s| vec![1.0; s.idlers.len()])
                .collect();
            for (&(s, k, _), l) in reach.iter().zip(lambda) {
                capstan[s][k] = l.exp();
            }
            let e = tendyn_core::tension::state_matrix(&model, &capstan);
            vertices += 1;
            match controllable(&e, &tendons) {
                Ok(lift) => {
                    least = least.min(lift);
                    lift
                }
                Err(why) => panic!("{}: {why} at {lambda:?}", model.name()),
            }
        };
        // The vertex whose guide `g` is at its upper end where `upper(g)`.
        let corner = |upper: &dyn Fn(usize) -> bool| -> Vec<f64> {
            (reach.iter().enumerate())
                .map(|(g, r)| if upper(g) { r.2 } else { -r.2 })
                .collect()
        };
        let mut random_corner = || {
            let bits: Vec<bool> = reach.iter().map(|_| rng.random()).collect();
            corner(&|g| bits[g])
        };
        if reach.len() <= 12 {
            for bits in 0..1u64 << reach.len() {
                check(&corner(&|g| bits >> g & 1 == 1));
            }
        } else {
            for _ in 0..2000 {
                check(&random_corner());
            }
            // An adversary: from random vertices, flip one guide at a time while the least
            // lift falls, down to a vertex no single flip lowers.
            for _ in 0..3 {
                let mut lambda = random_corner();
                let mut lift = check(&lambda);
                let mut lowered = true;
                while lowered {
                    lowered = false;
                    for g in 0..lambda.len() {
                        lambda[g] = -lambda[g];
                        match check(&lambda) {
                            lower if lower < lift => (lift, lowered) = (lower, true),
                            _ => lambda[g] = -lambda[g],
                        }
                    }
                }
            }
        }
        for _ in 0..50 {
            let inside: Vec<f64> = (reach.iter())
                .map(|r| rng.random_range(-1.0..1.0) * r.2)
                .collect();
            check(&inside);
        }
        // Without ranges validation covers the wrap angles at q = 0: there, whichever way
        // the joints move.
        if *finger {
            let mut solver = Data::new(&model);
            for _ in 0..20 {
                let [_, qd, qdd] = random_state(&mut rng, model.dof());
                let q = vec![0.0; model.dof()];
                solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
            }
        }
    }
    println!(
        "{shown} of {accepted} mechanisms with capstan friction shown on boxes, {vertices} \
         factors checked, least lift {least:.1e}"
    );
    assert!(shown >= 20, "{shown}");
}
