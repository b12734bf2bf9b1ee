//! Generated code agrees with the runtime solver: for the paper's three examples, a joint with
//! three tendons (a two-dimensional null space), a finger with runtime parameters (set at random between 90 % and 100 % of nominal) and twelve seeded random
//! spatial mechanisms, at 1,000 random states each, every generated output
//! matches the runtime solver's to 1e-12 relative in f64. The norm is the max norm of each
//! output vector, relative: `‖generated − runtime‖∞ / ‖runtime‖∞` — for forward dynamics,
//! relative to the size of the terms it sums (`Solver::forward_dynamics_scale`), since balancing tensions
//! make `q̈` a small difference of large numbers.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::Solver;
use tendyn_generated_tests::MECHANISMS;

fn runtime(
    s: &mut Solver<f64>,
    output: &str,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    mt: &[f64],
    tt: &[f64],
) -> Vec<f64> {
    match output {
        "generalized_forces" => s.generalized_forces(q, qd, qdd).unwrap(),
        "mass_matrix" => s.mass_matrix(q).unwrap().into_iter().flatten().collect(),
        "bias" => s.bias(q, qd).unwrap(),
        "gravity" => s.gravity(q).unwrap(),
        "forward_dynamics" => s.forward_dynamics(q, qd, mt, tt).unwrap(),
        other => {
            let r = s.inverse_dynamics(q, qd, qdd).unwrap();
            match other {
                "actuation" => r
                    .motor_torques
                    .iter()
                    .chain(&r.tendon_tensions)
                    .copied()
                    .collect(),
                "segment_tensions" => r.segment_tensions.unwrap().into_iter().flatten().collect(),
                "bearings" => r
                    .bearings
                    .unwrap()
                    .into_iter()
                    .flat_map(|(f, n)| f.to_array().into_iter().chain(n.to_array()))
                    .collect(),
                "base_reaction" => {
                    let (f, n) = r.base_reaction.unwrap();
                    f.to_array().into_iter().chain(n.to_array()).collect()
                }
                _ => panic!("unknown output {other}"),
            }
        }
    }
}

#[test]
fn generated_code_matches_the_runtime_solver_on_every_output() {
    let mut summary = Vec::new();
    for mech in MECHANISMS {
        let nominal = tendyn_core::parse(mech.ron).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(2024);
        let n = nominal.dof;
        let mut worst: Vec<(&str, f64)> = Vec::new();
        for _ in 0..1000 {
            // Runtime parameters between 90 % and 100 % of their nominal values (a thin disc
            // sits on the triangle-inequality bound), set in the runtime model and in the call.
            let p: Vec<f64> = nominal
                .parameters
                .iter()
                .map(|p| p.value * rng.random_range(0.9..1.0))
                .collect();
            let model = nominal.with_parameters(&p).unwrap();
            let mut solver = Solver::new(&model);
            let mut v = |len: usize, s: f64| {
                (0..len)
                    .map(|_| rng.random_range(-s..s))
                    .collect::<Vec<f64>>()
            };
            let (q, qd, qdd) = (v(n, std::f64::consts::PI), v(n, 3.0), v(n, 10.0));
            // Inputs of forward dynamics: the torques and tensions of inverse dynamics.
            let id = solver.inverse_dynamics(&q, &qd, &qdd).unwrap();
            let (mt, tt) = (id.motor_torques.clone(), id.tendon_tensions.clone());
            for (output, got) in (mech.evaluate)(&q, &qd, &qdd, &mt, &tt, &p) {
                let want = runtime(&mut solver, output, &q, &qd, &qdd, &mt, &tt);
                assert_eq!(got.len(), want.len(), "{} {output}", mech.name);
                let mut scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
                if output == "forward_dynamics" {
                    // Tensions that balance each other make q̈ a small difference of large
                    // terms; measure against the size of those terms.
                    scale = scale.max(solver.forward_dynamics_scale(&q, &qd, &mt, &tt).unwrap());
                }
                let err = got
                    .iter()
                    .zip(&want)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                    / scale;
                assert!(
                    err <= 1e-12,
                    "{} {output}: generated code is {err:.3e} from the runtime solver at q={q:?}",
                    mech.name
                );
                match worst.iter_mut().find(|(o, _)| *o == output) {
                    Some((_, w)) => *w = w.max(err),
                    None => worst.push((output, err)),
                }
            }
        }
        summary.push(format!(
            "{}: {}",
            mech.name,
            worst
                .iter()
                .map(|(o, e)| format!("{o} {e:.1e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    println!("{}", summary.join("\n"));
}

#[test]
fn the_no_std_build_of_the_finger_links_into_a_host_program_and_agrees() {
    use tendyn_no_std_check::finger;
    let model = tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/mechanisms/example3_stanford_jpl.ron"
    ))
    .unwrap();
    let mut s = Solver::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..100 {
        let mut v = |x: f64| -> [f64; 3] { std::array::from_fn(|_| rng.random_range(-x..x)) };
        let (q, qd, qdd) = (v(3.0), v(3.0), v(10.0));
        let want = s.inverse_dynamics(&q, &qd, &qdd).unwrap().tendon_tensions;
        let got = finger::actuation::<f64>(&q, &qd, &qdd).tendon_tensions;
        let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in got.iter().zip(&want) {
            assert!((a - b).abs() <= 1e-12 * scale, "{got:?} vs {want:?}");
        }
    }
}
