//! Generates code for the paper's three examples, twelve seeded random mechanisms, five with
//! bearing friction (Example 2 and four random ones), three with fixed guides, Example 2
//! with capstan friction on its guides (alone and with a fourth tendon), Example 3 with
//! capstan friction on every idler (exact and smoothed law), two with a turning
//! idler after a guide with friction, the five mechanisms of the scale benchmarks, and a
//! few mechanisms of the stress suite into `OUT_DIR`, with every output each mechanism can
//! provide, plus a small adapter per mechanism that the agreement test calls with slices.

use std::fmt::Write;
use tendyn_codegen::outputs::flattened_numbers;
use tendyn_codegen::{available_outputs, generate, Output, Scalar};
use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

fn main() {
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").unwrap());
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/mechanisms");
    let mut mechanisms: Vec<(String, String)> = Vec::new();
    for name in [
        "example1_endless",
        "example2_open_ended",
        "example3_stanford_jpl",
    ] {
        let path = root.join(format!("{name}.ron"));
        println!("cargo:rerun-if-changed={}", path.display());
        mechanisms.push((name.to_string(), std::fs::read_to_string(path).unwrap()));
    }
    mechanisms.push((
        "parametric_finger".to_string(),
        tendyn_spec::parametric::finger(),
    ));
    mechanisms.push((
        "three_on_one".to_string(),
        tendyn_spec::redundant::THREE_ON_ONE.to_string(),
    ));
    for seed in 0..12u64 {
        let features = Features {
            coupled_pulleys: seed % 3 == 1,
            endless: seed % 4 == 2,
        };
        let (text, _) = valid_random_mechanism(seed, features);
        mechanisms.push((format!("random_{seed}"), text));
    }
    // Bearing friction on every link and turning pulley: the exact law and the smoothed one.
    let friction = root.join("example2_friction.ron");
    println!("cargo:rerun-if-changed={}", friction.display());
    mechanisms.push((
        "example2_friction".to_string(),
        std::fs::read_to_string(friction).unwrap(),
    ));
    for seed in 0..4u64 {
        let features = Features {
            coupled_pulleys: seed == 3,
            endless: seed == 1,
        };
        let (text, _) = valid_random_mechanism(seed, features);
        let smoothing = (seed % 2 == 0).then_some(0.2);
        let text = tendyn_spec::friction::with_bearing_friction(&text, seed, smoothing);
        mechanisms.push((format!("friction_{seed}"), text));
    }
    // Fixed frictionless guides in place of the idlers: Example 2 and two random ones.
    let example2 = std::fs::read_to_string(root.join("example2_open_ended.ron")).unwrap();
    mechanisms.push((
        "example2_guides".to_string(),
        tendyn_spec::guides::idlers_as_guides(&example2),
    ));
    // (The first two seeds whose random mechanisms have idlers.)
    let with_idlers = (0..64u64).filter_map(|seed| {
        let features = Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, model) = valid_random_mechanism(seed, features);
        let idlers = model
            .strands()
            .iter()
            .map(|s| s.idlers.len())
            .sum::<usize>();
        (idlers > 0).then_some((seed, text))
    });
    for (seed, text) in with_idlers.take(2) {
        mechanisms.push((
            format!("guides_{seed}"),
            tendyn_spec::guides::idlers_as_guides(&text),
        ));
    }
    // Each strand's first idler a guide with capstan friction, the later ones turning
    // (forward dynamics' unsymmetric case): seeded random mechanism 23 (7 joints; its
    // derivatives, 17,496 operations, are not generated here: see above).
    let (text, _) = valid_random_mechanism(
        23,
        Features {
            coupled_pulleys: false,
            endless: false,
        },
    );
    mechanisms.push((
        "idlers_behind_guides".to_string(),
        tendyn_spec::guides::first_idlers_as_capstans(&text, 0.02),
    ));
    // The same on one joint, small enough for its derivatives: a pin with friction and a
    // turning idler after it.
    mechanisms.push((
        "pin_then_idler_friction".to_string(),
        tendyn_spec::guides::pin_then_idler(0.3),
    ));
    // Capstan friction on both guides of Example 2 (the state's system, traced), and the
    // same with an antagonist on drum 1 (a two-dimensional null space, of the state too).
    let capstan = root.join("example2_capstan.ron");
    println!("cargo:rerun-if-changed={}", capstan.display());
    let capstan = std::fs::read_to_string(capstan).unwrap();
    let antagonist = tendyn_spec::guides::with_antagonist_on_drum1(&capstan);
    mechanisms.push(("example2_capstan_friction".to_string(), capstan));
    mechanisms.push((
        "example2_capstan_friction_antagonist".to_string(),
        antagonist,
    ));
    // Example 3 with every idler a guide with capstan friction (a 3 x 4 `E` with every
    // column scaled, traced), under the exact law and the smoothed one.
    let example3 = std::fs::read_to_string(root.join("example3_stanford_jpl.ron")).unwrap();
    let guides_everywhere = tendyn_spec::guides::idlers_as_capstans(&example3, 0.1);
    let floor = "tension_floor: 5.0,";
    assert!(
        guides_everywhere.contains(floor),
        "example3_stanford_jpl.ron"
    );
    let smoothed =
        guides_everywhere.replacen(floor, &format!("{floor} friction_smoothing: 0.01,"), 1);
    mechanisms.push(("capstan_guides_everywhere".to_string(), guides_everywhere));
    mechanisms.push(("capstan_guides_everywhere_smoothed".to_string(), smoothed));
    // The scale benchmarks' mechanisms (issue 16): a finger, a random arm with gears, and
    // chains of 7, 8 and 12 links (the last with 13 unknowns); and the arm with gears and a
    // drum whose mass regrouping moves.
    let top = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for file in [
        "bench/mechanisms/finger4",
        "bench/mechanisms/arm6",
        "bench/mechanisms/chain8",
        "bench/mechanisms/chain12",
        "tendyn-codegen/benches/chain7",
        // Pulleys whose mass moves onto their carriers in the traced model (regrouping).
        "tests/mechanisms/geared_arm",
    ] {
        let path = top.join(format!("{file}.ron"));
        println!("cargo:rerun-if-changed={}", path.display());
        let name = file.rsplit('/').next().expect("a file name");
        mechanisms.push((
            format!("bench_{name}"),
            std::fs::read_to_string(path).unwrap(),
        ));
    }
    // Representative stress mechanisms, in a registry of their own (`STRESS`):
    // `tests/stress.rs` checks them against the double-double reference under the stress
    // suite's condition rule.
    let first_stress = mechanisms.len();
    println!("cargo:rerun-if-changed=../mechanisms/stress");
    for case in tendyn_spec::stress::generated_cases() {
        let name = format!("stress_{}", tendyn_spec::stress::ident(&case.name));
        mechanisms.push((name, case.text));
    }
    // Statics, not consts: a const's function pointers are instantiated anew in every
    // test binary that reads it, and each then compiled all the generated code again
    // (3.7 min each for `agreement` and `stress` from a cold start); a static's are
    // compiled once, in this library.
    let mut registry = String::from("pub static MECHANISMS: &[Mechanism] = &[\n");
    let mut modules = String::new();
    for (index, (name, text)) in mechanisms.iter().enumerate() {
        if index == first_stress {
            registry.push_str("];\npub static STRESS: &[Mechanism] = &[\n");
        }
        let model = tendyn_core::parse(text).unwrap();
        let mut outputs = available_outputs(&model);
        // The derivatives and the regressor (not generated by default) for a representative set: the paper's
        // examples (with friction, guides and capstan friction), runtime parameters,
        // random mechanisms with coupled pulleys and endless loops, bearing friction
        // exact and smoothed, the scale finger. (Not the largest: a straight-line function
        // of 10,000+ operations overflows rustc's default stack, see docs/generated-code.md.)
        let derived = name.starts_with("example")
            || [
                "parametric_finger",
                "random_1",
                "random_2",
                "friction_1",
                "friction_2",
                "bench_finger4",
                "pin_then_idler_friction",
            ]
            .contains(&name.as_str());
        if derived {
            for o in [
                Output::GeneralizedForcesDerivatives,
                Output::ForwardDynamicsDerivatives,
                Output::ActuationDerivatives,
                Output::Regressor,
            ] {
                if tendyn_codegen::outputs::check(&model, &[o]).is_ok() {
                    outputs.push(o);
                }
            }
        }
        let generated =
            generate(&model, &outputs, Scalar::Generic, &format!("{name}.ron")).unwrap();
        std::fs::write(out.join(format!("{name}.rs")), generated.source()).unwrap();
        std::fs::write(out.join(format!("{name}.ron")), text).unwrap();
        // The adapter: slices in, one vector per output out.
        let (n, nm, nt) = (model.dof(), model.motors().len(), model.tendons().len());
        let mut adapter = String::new();
        let np = model.parameters().len();
        // Vectors flatten through the same iterator expression as matrices and structs.
        writeln!(adapter, "#[allow(clippy::iter_cloned_collect)]").unwrap();
        writeln!(adapter, "pub fn evaluate<T: tendyn_core::Numeric>(q: &[T], qd: &[T], qdd: &[T], mt: &[T], tt: &[T], p: &[T]) -> Vec<(&'static str, Vec<T>)> {{").unwrap();
        writeln!(
            adapter,
            "let p: &[T; {np}] = p.try_into().unwrap(); let _ = p;"
        )
        .unwrap();
        // Generated functions take the parameters last, when the mechanism has any.
        let pa = if np > 0 { ", p" } else { "" };
        writeln!(adapter, "let q: &[T; {n}] = q.try_into().unwrap(); let qd: &[T; {n}] = qd.try_into().unwrap(); let qdd: &[T; {n}] = qdd.try_into().unwrap();").unwrap();
        writeln!(adapter, "let mt: &[T; {nm}] = mt.try_into().unwrap(); let tt: &[T; {nt}] = tt.try_into().unwrap(); let _ = (mt, tt, qdd);").unwrap();
        writeln!(
            adapter,
            "let mut v: Vec<(&'static str, Vec<T>)> = Vec::new();"
        )
        .unwrap();
        for o in &outputs {
            let args = match o {
                Output::MassMatrix | Output::Gravity => "q",
                Output::Bias => "q, qd",
                Output::ForwardDynamics | Output::ForwardDynamicsDerivatives => "q, qd, mt, tt",
                _ => "q, qd, qdd",
            };
            let numbers = flattened_numbers(*o, "r");
            let call = format!(
                "{{ let r = code::{}({args}{pa}); {numbers}.copied().collect() }}",
                o.name()
            );
            writeln!(adapter, "v.push((\"{}\", {call}));", o.name()).unwrap();
        }
        writeln!(adapter, "v }}").unwrap();
        module(&mut modules, name, &adapter);
        writeln!(
            registry,
            "    Mechanism {{ name: \"{name}\", ron: {name}::RON, evaluate: {name}::evaluate::<f64>, evaluate_f32: {name}::evaluate::<f32> }},"
        )
        .unwrap();
    }
    registry.push_str("];\n");
    // Seeded random systems of the bounded tension distribution (structure-only tendons
    // with floors and maxima, null spaces of one to four dimensions), and one with capstan
    // friction: `actuation` with its status, and its derivatives, in f64 and f32
    // (`tests/bounded.rs`).
    registry.push_str("pub static BOUNDED: &[Bounded] = &[\n");
    let mut bounded: Vec<(String, String)> = tendyn_spec::bounded::SIZES
        .iter()
        .map(|&(n, m, gravity, max)| {
            let seed = tendyn_spec::bounded::seed(n, m);
            let text = tendyn_spec::bounded::mechanism_ron_scaled(seed, n, m, gravity, max);
            (format!("bounded_{n}x{m}"), text)
        })
        .collect();
    // Example 2 with capstan friction and an antagonist on drum 1 (two null directions, a
    // function of the state) with maxima that about a third of the states cannot meet:
    // `bounded_at_state` and its derivatives, best efforts included.
    let antagonist = tendyn_spec::guides::with_antagonist_on_drum1(
        &std::fs::read_to_string(root.join("example2_capstan.ron")).unwrap(),
    );
    let maxima = [("T32", 12.0), ("T42", 12.0), ("T11", 25.0), ("T12", 20.0)];
    bounded.push((
        "capstan_antagonist_bounded".to_string(),
        tendyn_spec::guides::with_maxima(&antagonist, &maxima),
    ));
    for (name, text) in bounded {
        let model = tendyn_core::parse(&text).unwrap();
        let generated = generate(
            &model,
            &[Output::Actuation, Output::ActuationDerivatives],
            Scalar::Generic,
            &format!("{name}.ron"),
        )
        .unwrap();
        std::fs::write(out.join(format!("{name}.rs")), generated.source()).unwrap();
        std::fs::write(out.join(format!("{name}.ron")), &text).unwrap();
        let mut adapter = String::new();
        for t in ["f64", "f32"] {
            writeln!(
                adapter,
                "pub fn actuation_{t}(q: &[{t}], qd: &[{t}], qdd: &[{t}]) -> (Vec<{t}>, tendyn_core::distribution::Status) {{ \
                 let a = code::actuation::<{t}>(q.try_into().unwrap(), qd.try_into().unwrap(), qdd.try_into().unwrap()); \
                 (a.tendon_tensions.to_vec(), a.status) }}"
            )
            .unwrap();
            let numbers = flattened_numbers(Output::ActuationDerivatives, "d");
            writeln!(
                adapter,
                "pub fn actuation_derivatives_{t}(q: &[{t}], qd: &[{t}], qdd: &[{t}]) -> Vec<{t}> {{ \
                 let d = code::actuation_derivatives::<{t}>(q.try_into().unwrap(), qd.try_into().unwrap(), qdd.try_into().unwrap()); \
                 {numbers}.copied().collect() }}"
            )
            .unwrap();
        }
        let numbers = flattened_numbers(Output::ActuationDerivatives, "d");
        writeln!(
            adapter,
            "pub fn all_f64(q: &[f64], qd: &[f64], qdd: &[f64]) -> (Vec<f64>, tendyn_core::distribution::Status, Vec<f64>) {{ \
             let o = code::all::<f64>(q.try_into().unwrap(), qd.try_into().unwrap(), qdd.try_into().unwrap()); \
             let d = o.actuation_derivatives; \
             (o.actuation.tendon_tensions.to_vec(), o.actuation.status, {numbers}.copied().collect()) }}"
        )
        .unwrap();
        module(&mut modules, &name, &adapter);
        writeln!(
            registry,
            "    Bounded {{ name: \"{name}\", ron: {name}::RON, actuation_f64: {name}::actuation_f64, actuation_f32: {name}::actuation_f32, \
             actuation_derivatives_f64: {name}::actuation_derivatives_f64, actuation_derivatives_f32: {name}::actuation_derivatives_f32, \
             all_f64: {name}::all_f64 }},"
        )
        .unwrap();
    }
    registry.push_str("];\n");
    std::fs::write(out.join("mechanisms.rs"), format!("{modules}\n{registry}")).unwrap();
}

/// The module of one generated mechanism: its code, its RON text and the adapter.
fn module(modules: &mut String, name: &str, adapter: &str) {
    writeln!(
        modules,
        "pub mod {name} {{\n pub mod code {{ include!(concat!(env!(\"OUT_DIR\"), \"/{name}.rs\")); }}\n pub const RON: &str = include_str!(concat!(env!(\"OUT_DIR\"), \"/{name}.ron\"));\n {adapter}\n}}"
    )
    .unwrap();
}
