//! Fixed guides: a `fixed: true` pulley after a route's anchor, which the tendon slides over
//! instead of turning (format.md §6a). Checked by hand on one joint, one pin.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::{parse, Error, Solver};
use tendyn_spec::measure::random_state;

/// One joint. A drum of radius 0.02 m on the joint axis; `over_pin` leaves its top
/// horizontally to the left, meets the top of a pin (radius 0.01 m, centre (−0.1, 0.01) in
/// the base) tangentially, wraps it a quarter turn counter-clockwise and leaves straight
/// down to its exit; `direct` leaves the drum's bottom to the left. By hand: both tendons
/// have a moment arm of 0.02 m, of opposite signs, so `Q = 0.02 (T_over − T_direct)`; the
/// pin's wrap angle is π/2; turning the drum counter-clockwise pays `over_pin` out towards
/// its exit at `0.02 q̇`, which is its speed over the pin.
const PIN: &str = r#"(
    name: "one_pin",
    gravity: (0.0, -9.81, 0.0),
    tension_floor: 2.0,
    links: [
        (name: "link1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 0.5, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.004, zz: 0.004)),
    ],
    pulleys: [
        (name: "drum", carrier: "link1", at: Joint(joint: "link1", height: 0.0), radius: 0.02, fixed: true),
        (name: "pin", carrier: "base", at: Pose(origin: (-0.1, 0.01, 0.0), rpy: (0.0, 0.0, 0.0)), radius: 0.01, fixed: true, mu: 0.0),
    ],
    tendons: [
        (name: "over_pin", route: [("drum", Ccw), ("pin", Ccw)], exit: (-0.11, -0.2, 0.0)),
        (name: "direct", route: [("drum", Cw)], exit: (-0.2, -0.02, 0.0)),
    ],
)
"#;

#[test]
fn a_tendon_over_a_frictionless_pin_keeps_its_tension_and_slides_at_its_exit_speed() {
    let model = parse(PIN).unwrap();
    let strand = &model.strands[0];
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
    let mut solver = Solver::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..100 {
        let [q, qd, qdd] = random_state(&mut rng, 1);
        let r = solver.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let segments = &r.segment_tensions.as_ref().unwrap()[0];
        assert_eq!(segments[0], segments[1], "the pin passes the tension on");
        let (over, direct) = (r.tendon_tensions[0], r.tendon_tensions[1]);
        let q_hand = 0.02 * (over - direct);
        let q_solver = r.generalized_forces[0];
        assert!((q_hand - q_solver).abs() <= 1e-12 * (over + direct) * 0.02);
        assert!((guide.speed(&qd) - 0.02 * qd[0]).abs() <= 1e-15 * qd[0].abs());
    }
}

/// `PIN` with the pin's line changed.
fn pin_with(from: &str, to: &str) -> String {
    assert_eq!(PIN.matches(from).count(), 1, "{from}");
    PIN.replacen(from, to, 1)
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
    assert!(shown.contains("between 0 (frictionless) and 10"), "{shown}");
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

#[test]
fn capstan_friction_is_not_implemented_yet_and_says_so() {
    let shown = invalid(&pin_with("mu: 0.0", "mu: 0.2"));
    assert!(shown.contains("not implemented yet"), "{shown}");
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
    for (strand, there) in model.strands[..2].iter().zip(&turned.strands) {
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
