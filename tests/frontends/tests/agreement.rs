//! The three ways to get a mechanism's dynamics agree, for each of the paper's examples:
//! the derive and the build script run the same generator, so their results must be
//! identical to the bit (compared through `Debug`, which prints every f64 exactly); both
//! must equal the runtime solver to 1e-12, max-norm relative per output vector
//! (`tendyn_spec::measure::max_rel`; forward dynamics relative to the size of the terms it
//! sums, `forward_dynamics_term_scale`), at 1,000 seeded random states.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::output::{Output, State};
use tendyn_core::{Data, Model};
use tendyn_frontends_tests::{built, derived};
use tendyn_spec::measure::{forward_dynamics_term_scale, max_rel, random_state};

/// Everything the runtime solver says at a state, flattened per output as generated code
/// shapes it (forward dynamics driven by the actuation it solved).
fn runtime(
    model: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Vec<(&'static str, Vec<f64>)> {
    let mut s = Data::new(model);
    let r = s.inverse_dynamics(model, q, qd, qdd).unwrap().clone();
    let state = State {
        q,
        qd,
        qdd,
        motor_torques: &r.motor_torques,
        tendon_tensions: &r.tendon_tensions,
    };
    Output::DEFAULT
        .iter()
        .copied()
        .filter_map(|o| match s.output(model, o, &state) {
            Ok(v) => Some((o.name(), v)),
            // Segment tensions, bearings and the base reaction of an incomplete routing.
            Err(_) if model.routing_incomplete() && r.flattened(o).is_none() => None,
            Err(e) => panic!("{}: {e}", o.name()),
        })
        .collect()
}

/// Checks one example: `$derived` (a value) against `$built` (a module) and the runtime.
macro_rules! agree {
    ($file:literal, $derived:expr, $built:path, $n:literal) => {{
        use $built as built;
        let model = tendyn_core::load(concat!("../../examples/mechanisms/", $file)).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut worst = 0.0f64;
        for _ in 0..1000 {
            let [q, qd, qdd] = random_state(&mut rng, $n);
            let (q, qd, qdd): ([f64; $n], [f64; $n], [f64; $n]) = (
                q.try_into().unwrap(),
                qd.try_into().unwrap(),
                qdd.try_into().unwrap(),
            );
            let want = runtime(&model, &q, &qd, &qdd);
            let a = $derived.actuation(&q, &qd, &qdd);
            let (mt, tt) = (a.motor_torques, a.tendon_tensions);
            let d = $derived.all(&q, &qd, &qdd, &mt, &tt);
            let b = built::all(&q, &qd, &qdd, &mt, &tt);
            assert_eq!(
                format!("{d:?}"),
                format!("{b:?}"),
                "derive and build.rs differ"
            );
            let got: Vec<(&str, Vec<f64>)> = vec![
                ("generalized_forces", d.generalized_forces.to_vec()),
                (
                    "actuation",
                    d.actuation
                        .motor_torques
                        .iter()
                        .chain(&d.actuation.tendon_tensions)
                        .copied()
                        .collect(),
                ),
                ("mass_matrix", d.mass_matrix.concat()),
                ("bias", d.bias.to_vec()),
                ("gravity", d.gravity.to_vec()),
                ("forward_dynamics", d.forward_dynamics.to_vec()),
                ("segment_tensions", d.segment_tensions.to_vec()),
                (
                    "bearings",
                    d.bearings.iter().flatten().flatten().copied().collect(),
                ),
                (
                    "base_reaction",
                    d.base_reaction
                        .iter()
                        .flatten()
                        .flatten()
                        .copied()
                        .collect(),
                ),
            ];
            for (name, want) in &want {
                let (_, got) = got.iter().find(|(g, _)| g == name).unwrap();
                let mut err = max_rel(got, want);
                if *name == "forward_dynamics" {
                    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    let terms = forward_dynamics_term_scale(&model, &q, &qd, &mt, &tt);
                    err *= scale / scale.max(terms);
                }
                assert!(
                    err <= 1e-12,
                    "{} {name}: {err:.2e} from the runtime solver",
                    $file
                );
                worst = worst.max(err);
            }
        }
        println!(
            "{}: derive ≡ build.rs bit for bit; worst against the runtime solver {worst:.1e}",
            $file
        );
    }};
}

#[test]
fn example1_derive_build_script_and_runtime_agree() {
    agree!(
        "example1_endless.ron",
        derived::Example1,
        built::example1,
        2
    );
}

#[test]
fn example2_derive_build_script_and_runtime_agree() {
    agree!(
        "example2_open_ended.ron",
        derived::Example2,
        built::example2,
        2
    );
}

#[test]
fn example3_derive_build_script_and_runtime_agree() {
    agree!(
        "example3_stanford_jpl.ron",
        derived::Example3,
        built::example3,
        3
    );
}

/// The derive's derivatives are the runtime solver's dual numbers (to round-off of the
/// closed form's different grouping).
#[test]
fn example3_derived_derivatives_agree_with_the_runtime_solver() {
    use tendyn_frontends_tests::derived::Example3Derivatives;
    let model = tendyn_core::load("../../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let mut data = tendyn_core::Data::new(&model);
    let (q, qd, qdd) = ([0.3, -0.7, 1.1], [0.5, -1.0, 2.0], [3.0, -2.0, 1.0]);
    let close = |got: &[f64], want: &[f64]| {
        let scale = want.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
        let err = got
            .iter()
            .zip(want)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err <= 1e-13 * scale, "{err:e} of {scale:e}");
    };
    let g = Example3Derivatives.generalized_forces_derivatives(&q, &qd, &qdd);
    let r = data
        .generalized_forces_derivatives(&model, &q, &qd, &qdd)
        .unwrap();
    close(&g.value, &r.value);
    close(g.d_q.as_flattened(), &r.d_q);
    close(g.d_qd.as_flattened(), &r.d_qd);
    let tensions = [12.0, 20.0, 15.0, 30.0];
    let g = Example3Derivatives.forward_dynamics_derivatives(&q, &qd, &[], &tensions);
    let r = data
        .forward_dynamics_derivatives(&model, &q, &qd, &[], &tensions)
        .unwrap();
    close(&g.value, &r.value);
    close(g.d_q.as_flattened(), &r.d_q);
    close(g.d_qd.as_flattened(), &r.d_qd);
    close(g.d_u.as_flattened(), &r.d_u);
    let g = Example3Derivatives.actuation_derivatives(&q, &qd, &qdd);
    let r = data.actuation_derivatives(&model, &q, &qd, &qdd).unwrap();
    close(&g.value, &r.value);
    close(g.d_q.as_flattened(), &r.d_q);
    close(g.d_qd.as_flattened(), &r.d_qd);
    close(g.d_qdd.as_flattened(), &r.d_qdd);
}

/// The derive's regressor times the file's parameters is the generalized force.
#[test]
fn example3_derived_regressor_times_the_parameters_is_q() {
    use tendyn_frontends_tests::derived::Example3Derivatives;
    let model = tendyn_core::load("../../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let pi = tendyn_core::regressor::values(&model);
    let (q, qd, qdd) = ([0.3, -0.7, 1.1], [0.5, -1.0, 2.0], [3.0, -2.0, 1.0]);
    let r = Example3Derivatives.regressor(&q, &qd, &qdd);
    let q_runtime = tendyn_core::Data::new(&model)
        .generalized_forces(&model, &q, &qd, &qdd)
        .unwrap()
        .to_vec();
    for ((row, offset), want) in r.y.iter().zip(&r.offset).zip(&q_runtime) {
        let got: f64 = row.iter().zip(&pi).map(|(y, p)| y * p).sum::<f64>() + offset;
        assert!(
            (got - want).abs() <= 1e-13 * want.abs().max(1.0),
            "{got} {want}"
        );
    }
}
