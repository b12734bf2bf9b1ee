//! `tendyn equations` names lengths and radii as the paper does, and what it prints is the
//! mechanism's dynamics:
//!
//! - evaluated with every name at its file value, the printed graph is what the runtime
//!   solver computes, for every output, on the paper's examples and on random spatial
//!   mechanisms;
//! - for Example 1 the names are structural, not numeric coincidences: with other values of
//!   the names the printed equations are the paper's Eqs. 28-30 (corrected,
//!   `docs/paper-errata.md`) with those values, and the runtime solver of a file with those
//!   lengths and radii;
//! - the couplings and structure matrices print as the paper's Eqs. 26, 33 and 35.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;
use tendyn_codegen::equations::{equations, named, Named, Quantity};
use tendyn_codegen::Output;
use tendyn_core::{Data, Model};
use tendyn_spec::measure::{forward_dynamics_term_scale, max_rel, random_state};
use tendyn_spec::paper::Arm;
use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

/// Agreement required of the printed equations (max-norm relative).
const TOL: f64 = 1e-12;

fn example(name: &str) -> String {
    tendyn_spec::examples::text(name)
}

fn parse(text: &str) -> Model<f64> {
    tendyn_core::parse(text).unwrap_or_else(|e| panic!("{e}"))
}

/// Example 1's arm in a vertical plane (gravity along −y), so that gravity terms print too.
fn vertical_example1() -> String {
    let text = example("example1_endless");
    assert!(text.contains("gravity: (0.0, 0.0, -9.81)"));
    text.replace("gravity: (0.0, 0.0, -9.81)", "gravity: (0.0, -9.81, 0.0)")
}

/// One state of the inputs of the printed functions.
struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    motor_torques: Vec<f64>,
    tendon_tensions: Vec<f64>,
}

fn draw(rng: &mut ChaCha8Rng, m: &Model<f64>) -> State {
    let [q, qd, qdd] = random_state(rng, m.dof());
    State {
        q,
        qd,
        qdd,
        motor_torques: (0..m.motors().len())
            .map(|_| rng.random_range(-2.0..2.0))
            .collect(),
        tendon_tensions: (0..m.tendons().len())
            .map(|_| rng.random_range(0.0..50.0))
            .collect(),
    }
}

/// Input values of the printed graph: the state, and every parameter by name (`values`)
/// or else at its file value.
fn inputs(n: &Named, s: &State, values: &HashMap<String, f64>) -> Vec<f64> {
    n.traced
        .graph
        .input_names
        .iter()
        .map(|name| {
            let (array, index) = name.split_once('[').expect("array input");
            let k: usize = index.trim_end_matches(']').parse().expect("index");
            match array {
                "q" => s.q[k],
                "qd" => s.qd[k],
                "qdd" => s.qdd[k],
                "motor_torques" => s.motor_torques[k],
                "tendon_tensions" => s.tendon_tensions[k],
                "params" => {
                    let p = &n.model.parameters()[k];
                    values.get(&p.name).copied().unwrap_or(p.value)
                }
                "lengths" => {
                    let l = &n.lengths[k];
                    values.get(&l.name).copied().unwrap_or(l.value)
                }
                other => panic!("unexpected input {other}"),
            }
        })
        .collect()
}

/// What the runtime solver gives for `o` at `s`, flattened as the printed function's
/// results, and the scale its error is measured against.
fn runtime(m: &Model<f64>, o: Output, s: &State) -> (Vec<f64>, f64) {
    let state = tendyn_core::output::State {
        q: &s.q,
        qd: &s.qd,
        qdd: &s.qdd,
        motor_torques: &s.motor_torques,
        tendon_tensions: &s.tendon_tensions,
    };
    let v = Data::new(m).output(m, o, &state).unwrap();
    let scale = match o {
        Output::ForwardDynamics => {
            forward_dynamics_term_scale(m, &s.q, &s.qd, &s.motor_torques, &s.tendon_tensions)
        }
        _ => v.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300),
    };
    (v, scale)
}

/// Largest error over `states` random states of every printed function of `text`'s
/// mechanism against the runtime solver of `reference` (the same file unless names are
/// given other values), per output.
fn worst_errors(
    text: &str,
    outputs: &[Output],
    reference: &Model<f64>,
    values: &HashMap<String, f64>,
    states: usize,
    seed: u64,
) -> Vec<(Output, f64)> {
    let m = parse(text);
    let n = named(&m, outputs).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut worst: Vec<(Output, f64)> = outputs.iter().map(|&o| (o, 0.0)).collect();
    for _ in 0..states {
        let s = draw(&mut rng, reference);
        let x = inputs(&n, &s, values);
        for (f, (_, w)) in n.traced.functions.iter().zip(worst.iter_mut()) {
            let printed = n.traced.graph.eval(&f.results, &x);
            let (expected, scale) = runtime(reference, f.output, &s);
            let diff = printed
                .iter()
                .zip(&expected)
                .fold(0.0f64, |a, (p, e)| a.max((p - e).abs()));
            assert_eq!(printed.len(), expected.len(), "{}", f.output.name());
            *w = w.max(diff / scale);
        }
    }
    worst
}

fn assert_agree(what: &str, worst: &[(Output, f64)]) {
    for (o, e) in worst {
        eprintln!("{what}: {:<20} {e:.2e}", o.name());
        assert!(
            *e <= TOL,
            "{what}: printed `{}` is off by {e:.3e}",
            o.name()
        );
    }
}

#[test]
fn printed_equations_at_the_file_values_are_what_the_runtime_solver_computes() {
    for name in tendyn_spec::examples::NAMES {
        let text = example(name);
        let m = parse(&text);
        let outputs = tendyn_codegen::available_outputs(&m);
        let worst = worst_errors(&text, &outputs, &m, &HashMap::new(), 300, 1);
        assert_agree(name, &worst);
    }
}

#[test]
fn printed_equations_of_random_spatial_mechanisms_are_what_the_runtime_solver_computes() {
    // General twists, DH offsets d, joint offsets, pulleys on their own link's joint axis,
    // endless loops, explicit couplings: every place a length or radius is named.
    for seed in 0..8 {
        let features = Features {
            coupled_pulleys: seed % 4 == 3,
            endless: seed % 3 == 1,
        };
        let (text, m) = valid_random_mechanism(seed, features);
        let outputs = tendyn_codegen::available_outputs(&m);
        let worst = worst_errors(&text, &outputs, &m, &HashMap::new(), 100, seed);
        assert_agree(m.name(), &worst);
        // The lengths are named: every non-zero DH length and offset has its name.
        let printed = equations(&m, &[Output::GeneralizedForces]).unwrap();
        for (j, link) in m.bodies()[..m.dof()].iter().enumerate() {
            if link.post.translation.x != 0.0 {
                assert!(printed.contains(&format!("  a{} = ", j + 1)), "{printed}");
            }
            if link.post.translation.z != 0.0 {
                assert!(printed.contains(&format!("  d{} = ", j + 1)), "{printed}");
            }
        }
    }
}

#[test]
fn names_that_a_runtime_parameter_already_uses_are_primed() {
    // A runtime parameter called `a1` (link 1's mass) and one called `r3` (a centre of
    // mass): the DH length and the radius get primed names, and the equations still hold.
    let text = vertical_example1()
        .replacen(
            "name: \"example1_endless\",",
            "name: \"example1_endless\",\n    parameters: [(name: \"a1\", value: 1.2), (name: \"r3\", value: -0.125)],",
            1,
        )
        .replacen("mass: 1.2,", "mass: \"a1\",", 1)
        .replacen("com: (-0.125, 0.0, 0.0)", "com: (\"r3\", 0.0, 0.0)", 1);
    let m = parse(&text);
    let printed = equations(&m, &[Output::GeneralizedForces, Output::Actuation]).unwrap();
    assert!(printed.contains("  a1' = 0.3 (DH a of link1)"), "{printed}");
    assert!(
        printed.contains("  r3' = 0.03 (radius of pulley3)"),
        "{printed}"
    );
    assert!(printed.contains("r2/r3'"), "{printed}");
    let outputs = tendyn_codegen::available_outputs(&m);
    let worst = worst_errors(&text, &outputs, &m, &HashMap::new(), 100, 7);
    assert_agree("example1 with colliding parameter names", &worst);
}

/// The block of `function` in the printed text (its temporaries and results).
fn block<'t>(printed: &'t str, function: &str) -> &'t str {
    let start = printed
        .find(&format!("\n{function} ("))
        .unwrap_or_else(|| panic!("no {function} in\n{printed}"));
    let rest = &printed[start + 1..];
    let end = rest.find("\n\n").map_or(rest.len(), |e| e);
    &rest[rest.find('\n').expect("header line")..end]
}

/// The numbers printed in `text` (tokens that start with a digit and are not part of a
/// name such as `th1` or `w3`).
fn numbers(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut previous = ' ';
    let mut current = String::new();
    for c in text.chars().chain([' ']) {
        let in_number = !current.is_empty();
        if in_number
            && (c.is_ascii_digit() || c == '.' || c == 'e' || (c == '-' && current.ends_with('e')))
        {
            current.push(c);
        } else {
            if in_number {
                out.push(std::mem::take(&mut current));
            }
            if c.is_ascii_digit()
                && !(previous.is_ascii_alphanumeric() || previous == '_' || previous == '\'')
            {
                current.push(c);
            }
        }
        previous = c;
    }
    out
}

#[test]
fn example1_forces_and_motor_torques_print_with_names_only() {
    // a1 in the joint-1 terms (the paper's a1, where it used to print 0.3), a2 in link 2's,
    // the radii in the coupling ratio r2/r3 (Eq. 26) and in r3/r2 of Eqs. 28-29: not one
    // number is left in Example 1's generalized forces and motor torques.
    for text in [example("example1_endless"), vertical_example1()] {
        let m = parse(&text);
        let printed = equations(&m, &[Output::GeneralizedForces, Output::Actuation]).unwrap();
        for function in ["generalized_forces", "actuation"] {
            let b = block(&printed, function);
            assert!(numbers(b).is_empty(), "numbers {:?} in\n{b}", numbers(b));
            for name in ["a1", "a2", "r2/r3", "th1dd", "S2", "C2"] {
                assert!(b.contains(name), "no {name} in\n{b}");
            }
        }
        let motors = block(&printed, "actuation");
        assert!(motors.contains("r3/r2*"), "{motors}");
        assert!(
            motors.contains("actuation motor motor3 = I_pulley3zz*(th1dd + r2/r3*th2dd) + "),
            "Eq. 29: n30 = cI3 (θ̈1 + γ23 θ̈2) + r3 (T21 − T22)\n{motors}"
        );
        assert!(
            printed.contains("  pulley3    th1 + r2/r3*th2\n"),
            "Eq. 26\n{printed}"
        );
    }
}

/// Random values for Example 1's names: lengths, radii, masses, centres of mass,
/// inertias and gravity, all different from the file's.
fn other_values(rng: &mut ChaCha8Rng) -> HashMap<String, f64> {
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    [
        ("a1", r(0.2, 0.5)),
        ("a2", r(0.1, 0.4)),
        ("r2", r(0.01, 0.04)),
        ("r3", r(0.02, 0.06)),
        ("m1", r(0.5, 2.0)),
        ("m2", r(0.3, 1.5)),
        ("c1x", r(-0.2, -0.05)),
        ("c2x", r(-0.2, -0.05)),
        ("I1zz", r(0.001, 0.02)),
        ("I2zz", r(0.001, 0.02)),
        ("I_pulley3zz", r(1e-5, 1e-4)),
        ("gy", r(-12.0, -5.0)),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

#[test]
fn example1_printed_equations_are_the_papers_eqs_28_to_30_for_any_values_of_the_names() {
    // Q and the motor torques as printed, evaluated with other lengths, radii and mass
    // properties, against the hand derivations of tests/reference/paper.rs with the same
    // values: Lagrange's torques of the arm plus pulley 3 through its coupling γ23 = r2/r3
    // (Eq. 26); Eq. 29 with Eq. 28 for the motor on pulley 3; corrected Eq. 30 for link 1.
    let m = parse(&vertical_example1());
    let n = named(&m, &[Output::GeneralizedForces, Output::Actuation]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(28);
    let mut worst = 0.0f64;
    for _ in 0..300 {
        let v = other_values(&mut rng);
        let arm = Arm {
            a1: v["a1"],
            s1: -v["c1x"],
            m1: v["m1"],
            i1: v["I1zz"],
            a2: v["a2"],
            s2: -v["c2x"],
            m2: v["m2"],
            i2: v["I2zz"],
        };
        let (r2, r3, i3, g) = (v["r2"], v["r3"], v["I_pulley3zz"], -v["gy"]);
        let s = draw(&mut rng, &m);
        let (q, qd, qdd) = (&s.q, &s.qd, &s.qdd);
        let gamma = r2 / r3;
        let pulley = i3 * (qdd[0] + gamma * qdd[1]);
        let (tau1, tau2) = arm.torques(q, qd, qdd, g);
        let eq28 = arm.eq28(q, qd, qdd, g); // r2 (T21 − T22)
        let motor3 = r3 / r2 * eq28 + pulley; // Eq. 29
        let motor1 = (r3 - r2) * (-eq28 / r2) + arm.eq30(q, qd, qdd, g, 0.0, 0.0); // Eq. 30
        let expected = [
            vec![tau1 + pulley, tau2 + gamma * pulley],
            vec![motor1, motor3],
        ];
        let x = inputs(&n, &s, &v);
        for (f, e) in n.traced.functions.iter().zip(&expected) {
            worst = worst.max(max_rel(&n.traced.graph.eval(&f.results, &x), e));
        }
    }
    eprintln!("example 1 against Eqs. 28-30 with other values of the names: {worst:.2e}");
    assert!(worst <= TOL, "{worst:.3e}");
}

#[test]
fn example1_printed_equations_with_other_lengths_and_radii_are_that_files_dynamics() {
    // The names carry every length and radius these outputs depend on: evaluating the
    // printed equations of the shipped file with the values of another file is that file's
    // runtime dynamics (segment tensions included: 20 ± (1/2r2) · link 2's moment).
    let text = vertical_example1();
    let other = text
        .replacen("a: 0.30,", "a: 0.41,", 1)
        .replacen("a: 0.25,", "a: 0.33,", 1)
        .replacen("radius: 0.03,", "radius: 0.045,", 1)
        .replacen("radius: 0.02,", "radius: 0.025,", 1);
    assert_ne!(text, other);
    let values: HashMap<String, f64> = [("a1", 0.41), ("a2", 0.33), ("r3", 0.045), ("r2", 0.025)]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    let outputs = [
        Output::GeneralizedForces,
        Output::Actuation,
        Output::MassMatrix,
        Output::Bias,
        Output::Gravity,
        Output::SegmentTensions,
    ];
    let worst = worst_errors(&text, &outputs, &parse(&other), &values, 300, 30);
    assert_agree("example 1 with another file's lengths and radii", &worst);
}

#[test]
fn example1_with_equal_radii_every_output_follows_the_names() {
    // With equal radii the belt runs parallel to the line of centres whatever the radius,
    // so no tangent direction changes with it and every output (bearing forces and the base
    // reaction through the contact points `r · unit vector` included) must follow the names.
    let text = vertical_example1().replacen("radius: 0.02,", "radius: 0.03,", 1);
    let other = text
        .replacen("a: 0.30,", "a: 0.41,", 1)
        .replacen("a: 0.25,", "a: 0.33,", 1)
        .replace("radius: 0.03,", "radius: 0.045,");
    let values: HashMap<String, f64> = [("a1", 0.41), ("a2", 0.33), ("r3", 0.045), ("r2", 0.045)]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    let m = parse(&text);
    let outputs = tendyn_codegen::available_outputs(&m);
    assert!(outputs.contains(&Output::Bearings));
    let worst = worst_errors(&text, &outputs, &parse(&other), &values, 300, 31);
    assert_agree(
        "example 1 (equal radii) with other lengths and radii",
        &worst,
    );
}

/// `text` with every number after `key` multiplied by a random factor in [0.75, 1.35].
fn rescaled(text: &str, key: &str, rng: &mut ChaCha8Rng) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find(key) {
        let (head, tail) = rest.split_at(i + key.len());
        out.push_str(head);
        let end = tail
            .find(|c: char| c == ',' || c == ')' || c.is_whitespace())
            .expect("a number ends");
        let x: f64 = tail[..end].parse().expect("a number");
        out.push_str(&format!("{:e}", x * rng.random_range(0.75..1.35)));
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn random_mechanisms_with_other_lengths_and_radii_have_the_same_printed_equations() {
    // The DH lengths and radii of random routed mechanisms changed in the file: the printed
    // joint-space dynamics of the original, with the names at the new values, is the
    // runtime dynamics of the new file. (Outputs through the tendons depend on tangent
    // directions too, which stay numbers, so M, h, g and Q are what can be compared.)
    let outputs = [
        Output::GeneralizedForces,
        Output::MassMatrix,
        Output::Bias,
        Output::Gravity,
    ];
    let mut compared = 0;
    for seed in 0..12 {
        let features = Features {
            coupled_pulleys: false,
            endless: seed % 3 == 1,
        };
        let (text, m) = valid_random_mechanism(seed, features);
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        let other_text = rescaled(&rescaled(&text, "dh: (a: ", &mut rng), "radius: ", &mut rng);
        // A radius may now leave no common tangent: such draws are not mechanisms.
        let Ok(other) = tendyn_core::parse(&other_text) else {
            continue;
        };
        let n = named(&m, &outputs).unwrap();
        assert!(n
            .lengths
            .iter()
            .any(|l| matches!(l.quantity, Quantity::Radius(_))));
        let values: HashMap<String, f64> = n
            .lengths
            .iter()
            .map(|l| {
                let v = match l.quantity {
                    Quantity::DhA(j) => other.bodies()[j].post.translation.x,
                    Quantity::DhD(j) => other.bodies()[j].post.translation.z,
                    Quantity::Radius(b) => match other.bodies()[b].kind {
                        tendyn_core::model::BodyKind::Pulley { radius, .. } => radius,
                        _ => unreachable!("a radius belongs to a pulley"),
                    },
                };
                assert!(v != l.value || matches!(l.quantity, Quantity::DhD(_)));
                (l.name.clone(), v)
            })
            .collect();
        let worst = worst_errors(&text, &outputs, &other, &values, 100, seed);
        assert_agree(&format!("{} rescaled", m.name()), &worst);
        compared += 1;
    }
    assert!(
        compared >= 8,
        "only {compared} rescaled mechanisms were valid"
    );
}

#[test]
fn structure_matrices_print_as_the_papers_eqs_33_and_35() {
    // Eq. 33, rows joint 1, joint 2 (the paper lists joint 2 first; its r2 is our two
    // drums r2a, r2b); Eq. 35, rows knuckle (joint 1) to distal (joint 3), r3 = r3a, r3b.
    let ex2 = equations(
        &parse(&example("example2_open_ended")),
        &[Output::GeneralizedForces],
    )
    .unwrap();
    for line in [
        "  link1      [-r3, -r4, r1]\n",
        "  link2      [r2a, -r2b, 0]\n",
        "  idler3     th1 - r2a/r3*th2\n",
        "  idler4     th1 + r2b/r4*th2\n",
    ] {
        assert!(ex2.contains(line), "no `{}` in\n{ex2}", line.trim_end());
    }
    let ex3 = equations(
        &parse(&example("example3_stanford_jpl")),
        &[Output::GeneralizedForces],
    )
    .unwrap();
    for line in [
        "  knuckle    [-r4, -r5, r6, r7]\n",
        "  proximal   [r8, -r9, r2, -r2]\n",
        "  distal     [r3a, -r3b, 0, 0]\n",
        // Eq. 34: the idler angles in ones and pulley ratios.
        "  idler8     th2 + r3a/r8*th3\n",
        "  idler4     th1 - r8/r4*th2 - r3a/r4*th3\n",
    ] {
        assert!(ex3.contains(line), "no `{}` in\n{ex3}", line.trim_end());
    }
}

#[test]
fn no_dh_length_of_the_examples_is_left_as_a_number() {
    // Every a_i of the three examples prints by name in every output: no printed number
    // equals one (to the six digits printed).
    for name in tendyn_spec::examples::NAMES {
        let m = parse(&example(name));
        let lengths: Vec<String> = m.bodies()[..m.dof()]
            .iter()
            .map(|b| format!("{}", b.post.translation.x))
            .collect();
        let printed = equations(&m, &tendyn_codegen::available_outputs(&m)).unwrap();
        let body = &printed[printed.find("\ngeneralized_forces (").expect("forces")..];
        for x in numbers(body) {
            let v: f64 = x.parse().unwrap_or(f64::NAN);
            assert!(
                !lengths.iter().any(|l| l.parse::<f64>() == Ok(v)),
                "{name}: the DH length {x} prints as a number"
            );
        }
    }
}

/// A mechanism file of the repository, by its path from this crate.
fn file(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn guides_with_friction_bearing_friction_and_many_idlers_print_what_the_solver_computes() {
    // Capstan friction makes `E` depend on the state through each segment's share of its
    // strand's column, traced by name too; finger4 has fourteen drums and idlers, some on
    // their own link's joint axis.
    for path in [
        "../examples/mechanisms/example2_capstan.ron",
        "../examples/mechanisms/example2_friction.ron",
        "../bench/mechanisms/finger4.ron",
    ] {
        let text = file(path);
        let m = parse(&text);
        let outputs = tendyn_codegen::available_outputs(&m);
        let worst = worst_errors(&text, &outputs, &m, &HashMap::new(), 50, 3);
        assert_agree(path, &worst);
    }
}

#[test]
fn a_tendon_along_an_axis_leaves_no_rounding_leftover_in_the_equations() {
    // finger4's tendons run along the links' x axes between idlers: the tangent's angle is
    // the f64 nearest π, whose sine (1.2e-16) printed as `r2_2*1.224647e-16` terms until the
    // direction was taken exactly.
    let m = parse(&file("../bench/mechanisms/finger4.ron"));
    let printed = equations(&m, &[Output::GeneralizedForces, Output::Actuation]).unwrap();
    let tiny: Vec<String> = numbers(&printed)
        .into_iter()
        .filter(|x| x.parse::<f64>().is_ok_and(|v| v != 0.0 && v.abs() < 1e-12))
        .collect();
    assert!(tiny.is_empty(), "{tiny:?} in\n{printed}");
}
