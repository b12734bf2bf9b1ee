//! What the scene does not need is not emitted, measured by operation counts of the
//! generated functions (the form emitted: traced or closed).

use tendyn_codegen::expr::Node;
use tendyn_codegen::outputs::trace;
use tendyn_codegen::{generate, Output, Scalar};

/// Example 1's arm in a vertical plane (gravity along −y), the base of every variant.
fn vertical_arm() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/mechanisms/example1_endless.ron"
    ))
    .unwrap()
    .replace("gravity: (0.0, 0.0, -9.81)", "gravity: (0.0, -9.81, 0.0)")
}

fn ops(text: &str, output: Output) -> usize {
    ops_among(text, output, &[output])
}

/// The operations (arithmetic and trigonometry) of `output`'s function when `outputs` are
/// generated together.
fn ops_among(text: &str, output: Output, outputs: &[Output]) -> usize {
    let m = tendyn_core::parse(text).unwrap_or_else(|e| panic!("{e}"));
    let g = generate(&m, outputs, Scalar::Generic, "test").unwrap();
    let f = &g.functions.iter().find(|f| f.0 == output).unwrap().1;
    f.arithmetic() + f.sin + f.cos + f.sin_cos
}

fn replace_once(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "`{from}`");
    text.replacen(from, to, 1)
}

#[test]
fn no_node_of_any_generated_function_does_arithmetic_on_a_known_zero_or_one() {
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        let m = tendyn_core::load(format!(
            "{}/../examples/mechanisms/{name}.ron",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let t = trace(&m, &tendyn_codegen::available_outputs(&m)).unwrap();
        let roots = &t.all;
        let is = |id, v: f64| t.graph.constant_value(id) == Some(v);
        for id in t.graph.live(roots) {
            let bad = match t.graph.node(id) {
                Node::Add(a, b) | Node::Sub(a, b) => is(a, 0.0) || is(b, 0.0),
                Node::Mul(a, b) => {
                    is(a, 0.0)
                        || is(b, 0.0)
                        || is(a, 1.0)
                        || is(b, 1.0)
                        || is(a, -1.0)
                        || is(b, -1.0)
                }
                Node::Div(_, b) => is(b, 1.0) || t.graph.constant_value(b).is_some(),
                Node::Neg(a) => t.graph.constant_value(a).is_some(),
                _ => false,
            };
            assert!(
                !bad,
                "{name}: node {:?} works on a known constant",
                t.graph.node(id)
            );
        }
    }
}

#[test]
fn gravity_normal_to_a_planar_mechanism_emits_no_gravity_terms() {
    let horizontal =
        vertical_arm().replace("gravity: (0.0, -9.81, 0.0)", "gravity: (0.0, 0.0, -9.81)");
    assert_eq!(ops(&horizontal, Output::Gravity), 0);
    // Inverse dynamics is exactly as long as with no gravity at all.
    let none = vertical_arm().replace("gravity: (0.0, -9.81, 0.0)", "gravity: (0.0, 0.0, 0.0)");
    assert_eq!(
        ops(&horizontal, Output::GeneralizedForces),
        ops(&none, Output::GeneralizedForces)
    );
    assert!(
        ops(&horizontal, Output::GeneralizedForces)
            < ops(&vertical_arm(), Output::GeneralizedForces)
    );
}

#[test]
fn asking_only_for_motor_torques_emits_no_bearing_force_arithmetic() {
    let arm = vertical_arm();
    let alone = ops(&arm, Output::Actuation);
    let bearings = ops(&arm, Output::Bearings);
    // The actuation function alone costs what it costs inside a full generation, a fraction
    // of the bearing forces that the same recursion would also give.
    let m = tendyn_core::parse(&arm).unwrap();
    let full = generate(
        &m,
        &tendyn_codegen::available_outputs(&m),
        Scalar::Generic,
        "t",
    )
    .unwrap();
    let inside = full
        .functions
        .iter()
        .find(|f| f.0 == Output::Actuation)
        .unwrap()
        .1;
    assert_eq!(
        alone,
        inside.arithmetic() + inside.sin + inside.cos + inside.sin_cos
    );
    assert!(
        3 * alone < bearings,
        "actuation {alone} ops, bearings {bearings}"
    );
}

#[test]
fn a_zero_twist_emits_no_multiplication_by_its_sine() {
    // Link 2 with a twist: its sine and cosine enter the recursion; with zero twist they
    // are exact zeros and ones and vanish as the graph is built.
    let twisted = replace_once(
        &vertical_arm(),
        "dh: (a: 0.25, alpha: 0.0, d: 0.0)",
        "dh: (a: 0.25, alpha: 0.3, d: 0.0)",
    );
    let m = tendyn_core::parse(&twisted).unwrap();
    let t = trace(&m, &[Output::GeneralizedForces]).unwrap();
    let sine = 0.3f64.sin();
    let uses_sine = |t: &tendyn_codegen::outputs::Traced| {
        t.graph.live(&t.functions[0].traced).iter().any(|&id| {
            t.graph
                .constant_value(id)
                .is_some_and(|c| (c.abs() - sine).abs() < 1e-15)
        })
    };
    assert!(
        uses_sine(&t),
        "the twisted chain must multiply by sin(alpha)"
    );
    let straight = tendyn_core::parse(&vertical_arm()).unwrap();
    assert!(!uses_sine(
        &trace(&straight, &[Output::GeneralizedForces]).unwrap()
    ));
    // Link 2 is the last link, so its twist only turns its own frame; give it an
    // off-axis centre of mass so that the twist matters to the dynamics.
    let off = |s: &str| replace_once(s, "com: (-0.125, 0.0, 0.0)", "com: (-0.125, 0.02, 0.01)");
    assert!(
        ops(&off(&vertical_arm()), Output::GeneralizedForces)
            < ops(&off(&twisted), Output::GeneralizedForces)
    );
}

#[test]
fn zero_gravity_massless_bodies_coaxial_pulleys_and_zero_offsets_each_shrink_the_code() {
    let base = replace_once(
        &vertical_arm(),
        "com: (-0.125, 0.0, 0.0)",
        "com: (-0.125, 0.01, 0.0)",
    );
    let base_ops = ops(&base, Output::GeneralizedForces);
    let variants = [
        ("zero gravity", base.replace("gravity: (0.0, -9.81, 0.0)", "gravity: (0.0, 0.0, 0.0)")),
        // A massless body removes the terms only it contributes: without link 2's mass the
        // cos q2 coupling terms go (link 1's mass only changes coefficients that link 2
        // shares, so it leaves the closed form's shape as it is).
        (
            "massless link 2",
            replace_once(&base, "mass: 0.8,\n            com: (-0.125, 0.01, 0.0),\n            inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667),", "mass: 0.0,"),
        ),
        ("zero centre-of-mass offset off the link's axis", replace_once(&base, "com: (-0.125, 0.01, 0.0)", "com: (-0.125, 0.0, 0.0)")),
    ];
    for (what, text) in &variants {
        let o = ops(text, Output::GeneralizedForces);
        assert!(
            o < base_ops,
            "{what}: {o} operations, not fewer than {base_ops}"
        );
    }
    // A pulley riding on link 1, with an explicit coupling: coaxial with joint 1 its centre
    // does not move and its mass adds no force terms; off the axis it swings round.
    let on_link1 = replace_once(&base, "carrier: \"base\",\n            at: Joint(joint: \"link1\", height: 0.02),\n            radius: 0.03,",
        "carrier: \"link1\",\n            at: Joint(joint: \"link1\", height: 0.02),\n            radius: 0.03,\n            coupling: [0.0, 0.5],");
    let on_link1 = on_link1
        .replace("    loops: [\n        (name: \"belt\", driven: \"drum2\", driving: \"pulley3\", crossed: false, pretension: 20.0),\n    ],\n", "")
        .replace("(name: \"motor3\", on: Pulley(\"pulley3\")),", "(name: \"motor2\", on: Joint(\"link2\")),");
    let coaxial = on_link1.clone();
    let offset = replace_once(&on_link1, "at: Joint(joint: \"link1\", height: 0.02),\n            radius: 0.03,\n            coupling", "at: Pose(origin: (-0.1, 0.02, 0.02), rpy: (0.0, 0.0, 0.0)),\n            radius: 0.03,\n            coupling");
    let (o_off, o_co) = (
        ops(&offset, Output::GeneralizedForces),
        ops(&coaxial, Output::GeneralizedForces),
    );
    assert!(
        o_co < o_off,
        "coaxial pulley {o_co} operations, off-axis {o_off}"
    );
}

#[test]
fn actuation_costs_the_same_whatever_is_generated_beside_it() {
    // Example 3 with a 60 N maximum on every tendon: actuation's status needs its
    // distribution's excess. Actuation is traced on the regrouped model and bearings on the
    // file's bodies; whichever comes first, actuation takes its own inverse dynamics' excess
    // and nothing of the other's (each model's trace keeps its own).
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/benches/distribution/example3_bounded.ron"
    ))
    .unwrap();
    let alone = ops(&text, Output::Actuation);
    for order in [
        &[Output::SegmentTensions, Output::Bearings, Output::Actuation][..],
        &[Output::Bearings, Output::Actuation],
        &[Output::Actuation, Output::Bearings],
    ] {
        let inside = ops_among(&text, Output::Actuation, order);
        // Numbers gathered in products and like terms merged over every function at once
        // may move a count by a few: a product another function also uses is not merged
        // away (328 against 325 here); another model's distribution would add its whole
        // recursion.
        assert!(
            alone <= inside && inside <= alone + alone / 50,
            "{order:?}: {inside} against {alone}"
        );
    }
}
