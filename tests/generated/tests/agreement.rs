//! Generated code agrees with the runtime solver: for the paper's three examples, a joint with
//! three tendons (a two-dimensional null space), a finger with runtime parameters (set at random between 90 % and 100 % of nominal) and twelve seeded random
//! spatial mechanisms, at 1,000 random states each, every generated output
//! matches the runtime solver's to 1e-12 relative in f64. The norm is the max norm of each
//! output vector, relative: `‖generated − runtime‖∞ / ‖runtime‖∞` — for forward dynamics,
//! relative to the size of the terms it sums (`Data::forward_dynamics_scale`), since balancing tensions
//! make `q̈` a small difference of large numbers. The derivatives (value and Jacobians
//! flattened, against the runtime solver's dual numbers) are measured per block the same
//! way: each Jacobian relative to its own max norm.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::output::{Output, State};
use tendyn_core::{Data, Model, Numeric};
use tendyn_generated_tests::MECHANISMS;

/// What the runtime solver gives for the output named `output`, flattened as generated
/// code returns it.
fn runtime<T: Numeric>(
    (m, s): (&Model<T>, &mut Data<T>),
    output: &str,
    q: &[T],
    qd: &[T],
    qdd: &[T],
    mt: &[T],
    tt: &[T],
) -> Vec<T> {
    let output = Output::parse(output).expect("a generated output");
    let state = State {
        q,
        qd,
        qdd,
        motor_torques: mt,
        tendon_tensions: tt,
    };
    s.output(m, output, &state).unwrap()
}

#[test]
fn generated_code_matches_the_runtime_solver_on_every_output() {
    let mut summary = Vec::new();
    for mech in MECHANISMS {
        let nominal = tendyn_core::parse(mech.ron).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(2024);
        let n = nominal.dof();
        let mut worst: Vec<(&str, f64)> = Vec::new();
        for _ in 0..1000 {
            // Runtime parameters between 90 % and 100 % of their nominal values (a thin disc
            // sits on the triangle-inequality bound), set in the runtime model and in the call.
            let p: Vec<f64> = nominal
                .parameters()
                .iter()
                .map(|p| p.value * rng.random_range(0.9..1.0))
                .collect();
            let model = nominal.with_parameters(&p).unwrap();
            let mut solver = Data::new(&model);
            let mut v = |len: usize, s: f64| {
                (0..len)
                    .map(|_| rng.random_range(-s..s))
                    .collect::<Vec<f64>>()
            };
            let (q, qd, qdd) = (v(n, std::f64::consts::PI), v(n, 3.0), v(n, 10.0));
            // Inputs of forward dynamics: the torques and tensions of inverse dynamics.
            let id = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
            let (mt, tt) = (id.motor_torques.clone(), id.tendon_tensions.clone());
            for (output, got) in (mech.evaluate)(&q, &qd, &qdd, &mt, &tt, &p) {
                let want = runtime((&model, &mut solver), output, &q, &qd, &qdd, &mt, &tt);
                assert_eq!(got.len(), want.len(), "{} {output}", mech.name);
                // Derivatives: the value, then each Jacobian, each measured on its own.
                let blocks = match output {
                    "generalized_forces_derivatives" => vec![n, n * n, n * n],
                    "forward_dynamics_derivatives" => {
                        vec![n, n * n, n * n, n * (mt.len() + tt.len())]
                    }
                    "actuation_derivatives" => {
                        let a = mt.len() + tt.len();
                        vec![a, a * n, a * n, a * n]
                    }
                    _ => vec![want.len()],
                };
                let mut err = 0.0f64;
                let mut at = 0;
                for (b, len) in blocks.into_iter().enumerate() {
                    let (got, want) = (&got[at..at + len], &want[at..at + len]);
                    at += len;
                    let mut scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
                    if output.starts_with("forward_dynamics") && b == 0 {
                        // Tensions that balance each other make q̈ a small difference of
                        // large terms; measure against the size of those terms.
                        scale = scale.max(
                            solver
                                .forward_dynamics_scale(&model, &q, &qd, &mt, &tt)
                                .unwrap(),
                        );
                    }
                    let e = got
                        .iter()
                        .zip(want)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                    err = err.max(e / scale);
                }
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
    let mut s = Data::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..100 {
        let mut v = |x: f64| -> [f64; 3] { std::array::from_fn(|_| rng.random_range(-x..x)) };
        let (q, qd, qdd) = (v(3.0), v(3.0), v(10.0));
        let want = &s
            .inverse_dynamics(&model, &q, &qd, &qdd)
            .unwrap()
            .tendon_tensions;
        let got = finger::actuation::<f64>(&q, &qd, &qdd).tendon_tensions;
        let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in got.iter().zip(want) {
            assert!((a - b).abs() <= 1e-12 * scale, "{got:?} vs {want:?}");
        }
    }
}

/// `‖got − want‖∞ / scale`, in f64.
fn distance<T: Numeric>(got: &[T], want: &[T], scale: f64) -> f64 {
    got.iter()
        .zip(want)
        .fold(0.0f64, |m, (a, b)| m.max((a.to_f64() - b.to_f64()).abs()))
        / scale
}

/// The mechanisms with bearing or capstan friction: generated code run in f32 agrees with the runtime
/// solver in f32 (both round at every step, in different orders: within `2¹⁰ u`, u = 2⁻²⁴,
/// relative as above; measured 109 u on 2026-12-05), and in f64 at states where every joint is at rest
/// (q̇ = 0: the direction of impending motion from q̈, or none), to 1e-12.
#[test]
fn generated_friction_code_matches_the_runtime_solver_in_f32_and_at_rest() {
    let tolerance = 1024.0 * f32::unit_roundoff();
    let mut worst_f32 = 0.0f64;
    let mut checked = 0;
    for mech in MECHANISMS {
        let model = tendyn_core::parse(mech.ron).unwrap();
        if !model.has_friction() && !model.has_capstan() {
            continue;
        }
        let m32 = model.cast_numeric::<f32>();
        let (mut s64, mut s32) = (Data::new(&model), Data::new(&m32));
        let n = model.dof();
        let mut rng = ChaCha8Rng::seed_from_u64(99);
        for i in 0..300 {
            let mut v = |s: f64| {
                (0..n)
                    .map(|_| rng.random_range(-s..s) as f32)
                    .collect::<Vec<f32>>()
            };
            let (q, mut qd, mut qdd) = (v(std::f64::consts::PI), v(3.0), v(10.0));
            let id = s32.inverse_dynamics(&m32, &q, &qd, &qdd).unwrap();
            let (mt, tt) = (id.motor_torques.clone(), id.tendon_tensions.clone());
            for (output, got) in (mech.evaluate_f32)(&q, &qd, &qdd, &mt, &tt, &[]) {
                let want = runtime((&m32, &mut s32), output, &q, &qd, &qdd, &mt, &tt);
                let mut scale = want
                    .iter()
                    .fold(0.0f64, |m, x| m.max(x.abs() as f64))
                    .max(1e-30);
                if output == "forward_dynamics" {
                    scale = scale
                        .max(s32.forward_dynamics_scale(&m32, &q, &qd, &mt, &tt).unwrap() as f64);
                }
                let err = distance(&got, &want, scale);
                assert!(
                    err <= tolerance,
                    "{} {output}: generated f32 is {err:.3e} from the runtime f32 at q={q:?}",
                    mech.name
                );
                worst_f32 = worst_f32.max(err);
            }
            // At rest, in f64: every other state with q̈ = 0 as well.
            qd.iter_mut().for_each(|x| *x = 0.0);
            if i % 2 == 1 {
                qdd.iter_mut().for_each(|x| *x = 0.0);
            }
            let wide = |x: &[f32]| x.iter().map(|&v| v as f64).collect::<Vec<f64>>();
            let (q, qd, qdd) = (wide(&q), wide(&qd), wide(&qdd));
            let id = s64.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
            if model.friction_smoothing().is_none() {
                assert_eq!(
                    id.sticking.len(),
                    id.bearing_friction.len(),
                    "{}: every bearing is at rest",
                    mech.name
                );
            }
            let (mt, tt) = (id.motor_torques.clone(), id.tendon_tensions.clone());
            for (output, got) in (mech.evaluate)(&q, &qd, &qdd, &mt, &tt, &[]) {
                // With q̇ = q̈ = 0 friction is exactly zero and the one-direction
                // distribution sits where two of its `max`'s arguments are equal: a kink,
                // whose derivative is one-sided. The runtime takes the mean of the two
                // sides there (an exact tie), generated code one side, as its round-off of
                // the tie falls (measured: they differ by half the jump). Compared at
                // rest with q̈ ≠ 0.
                if output == "actuation_derivatives" && qdd.iter().all(|&a| a == 0.0) {
                    continue;
                }
                let want = runtime((&model, &mut s64), output, &q, &qd, &qdd, &mt, &tt);
                let mut scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
                if output == "forward_dynamics" {
                    // At rest forward dynamics takes no friction; the torques came with it.
                    scale = scale.max(
                        s64.forward_dynamics_scale(&model, &q, &qd, &mt, &tt)
                            .unwrap(),
                    );
                }
                let err = distance(&got, &want, scale);
                assert!(err <= 1e-12, "{} {output} at rest: {err:.3e}", mech.name);
            }
        }
        checked += 1;
    }
    println!(
        "{checked} mechanisms with friction; worst f32 {worst_f32:.2e} ({:.0} u)",
        worst_f32 / f32::unit_roundoff()
    );
    assert!(checked >= 9, "{checked}");
}
