//! Derivatives of the dynamics (`tendyn_core::derivatives`): dual numbers through the
//! generic functions in `f64`, against central differences of the same functions' values
//! in double-double (step 1e-12: truncation error about 1e-24, round-off about 1e-20, both
//! far below `f64`'s), which share no derivative arithmetic with them.
//!
//! Agreement is measured per Jacobian as `‖J − J_ref‖_max / ‖J_ref‖_max`.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::{Data, DoubleDouble, Model};
use tendyn_spec::measure::random_state;

type DD = DoubleDouble;

const STEP: f64 = 1e-12;
const TOL: f64 = 1e-12;

fn lift(v: &[f64]) -> Vec<DD> {
    v.iter().map(|&x| DD::from(x)).collect()
}

/// Central differences of `f` in double-double along every coordinate of input `which`:
/// the row-major Jacobian (`rows × inputs[which].len()`).
fn central(
    inputs: &[Vec<f64>],
    which: usize,
    mut f: impl FnMut(&[Vec<DD>]) -> Vec<DD>,
) -> Vec<f64> {
    let base: Vec<Vec<DD>> = inputs.iter().map(|v| lift(v)).collect();
    let h = DD::from(STEP);
    let mut columns = Vec::new();
    for k in 0..inputs[which].len() {
        let (mut plus, mut minus) = (base.clone(), base.clone());
        plus[which][k] += h;
        minus[which][k] -= h;
        let (a, b) = (f(&plus), f(&minus));
        let column: Vec<f64> = a
            .iter()
            .zip(&b)
            .map(|(a, b)| ((*a - *b) / (h + h)).to_f64())
            .collect();
        columns.push(column);
    }
    let rows = columns.first().map_or(0, |c| c.len());
    (0..rows)
        .flat_map(|r| columns.iter().map(move |c| c[r]))
        .collect()
}

fn max_rel(a: &[f64], reference: &[f64]) -> f64 {
    tendyn_spec::measure::max_rel(a, reference)
}

fn mechanisms() -> Vec<Model<f64>> {
    use tendyn_spec::friction::with_bearing_friction;
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    let mut models = tendyn_spec::examples::all();
    for seed in 0..6u64 {
        let features = Features {
            coupled_pulleys: seed % 2 == 1,
            endless: seed % 3 == 2,
        };
        models.push(valid_random_mechanism(seed, features).1);
    }
    // Smoothed bearing friction (tanh) is differentiable everywhere.
    let (text, _) = valid_random_mechanism(
        11,
        Features {
            coupled_pulleys: false,
            endless: false,
        },
    );
    models.push(tendyn_core::parse(&with_bearing_friction(&text, 11, Some(0.3))).unwrap());
    for name in ["finger4", "arm6"] {
        models.push(tendyn_core::load(format!("../bench/mechanisms/{name}.ron")).unwrap());
    }
    models
}

#[test]
fn generalized_force_derivatives_match_central_differences_in_double_double() {
    for (i, model) in mechanisms().iter().enumerate() {
        let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
        let reference = model.cast_numeric::<DD>();
        let (mut data, mut dd) = (Data::new(model), Data::new(&reference));
        let mut worst = 0.0f64;
        for _ in 0..5 {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            let d = data
                .generalized_forces_derivatives(model, &q, &qd, &qdd)
                .unwrap();
            let exact = data.generalized_forces(model, &q, &qd, &qdd).unwrap();
            assert_eq!(
                d.value, exact,
                "the value is the plain function's, bit for bit"
            );
            let inputs = [q, qd, qdd];
            let mut f = |x: &[Vec<DD>]| {
                dd.generalized_forces(&reference, &x[0], &x[1], &x[2])
                    .unwrap()
                    .to_vec()
            };
            worst = worst.max(max_rel(&d.d_q, &central(&inputs, 0, &mut f)));
            worst = worst.max(max_rel(&d.d_qd, &central(&inputs, 1, &mut f)));
        }
        println!(
            "{}: ∂Q/∂q, ∂Q/∂q̇ worst relative error {worst:.2e}",
            model.name()
        );
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

/// Seeded random mechanism 23 with each strand's first idler a guide with capstan friction
/// and the idlers after it turning: forward dynamics' unsymmetric case.
fn idlers_behind_a_guide() -> Model<f64> {
    let features = tendyn_spec::random_mechanism::Features {
        coupled_pulleys: false,
        endless: false,
    };
    let (text, _) = tendyn_spec::random_mechanism::valid_random_mechanism(23, features);
    let model =
        tendyn_core::parse(&tendyn_spec::guides::first_idlers_as_capstans(&text, 0.1)).unwrap();
    assert!(model.capstan_before_an_idler());
    model
}

#[test]
fn forward_dynamics_derivatives_match_central_differences_in_double_double() {
    let mut models = mechanisms();
    models.push(idlers_behind_a_guide());
    for (i, model) in models.iter().enumerate() {
        let mut rng = ChaCha8Rng::seed_from_u64(50 + i as u64);
        let reference = model.cast_numeric::<DD>();
        let (mut data, mut dd) = (Data::new(model), Data::new(&reference));
        let (motors, tendons) = (model.motors().len(), model.tendons().len());
        let mut worst = 0.0f64;
        for _ in 0..5 {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            // Actuator values that a real motion needs: those of inverse dynamics.
            let r = data.inverse_dynamics(model, &q, &qd, &qdd).unwrap().clone();
            let u: Vec<f64> = r
                .motor_torques
                .iter()
                .chain(&r.tendon_tensions)
                .copied()
                .collect();
            let d = data
                .forward_dynamics_derivatives(model, &q, &qd, &r.motor_torques, &r.tendon_tensions)
                .unwrap();
            assert_eq!(d.d_u.len(), model.dof() * (motors + tendons));
            let inputs = [q, qd, u];
            let mut f = |x: &[Vec<DD>]| {
                let (torques, tensions) = x[2].split_at(motors);
                dd.forward_dynamics(&reference, &x[0], &x[1], torques, tensions)
                    .unwrap()
                    .to_vec()
            };
            worst = worst.max(max_rel(&d.d_q, &central(&inputs, 0, &mut f)));
            worst = worst.max(max_rel(&d.d_qd, &central(&inputs, 1, &mut f)));
            worst = worst.max(max_rel(&d.d_u, &central(&inputs, 2, &mut f)));
        }
        println!(
            "{}: ∂q̈/∂(q, q̇, u) worst relative error {worst:.2e}",
            model.name()
        );
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

/// Where the distribution's active set does not change within the step, the tensions are
/// differentiable and their dual derivative is the difference quotient's limit: on the
/// mechanisms above and on the seeded bounded-distribution systems of one to four null
/// directions with floors and maxima (`tendyn_spec::bounded::SIZES`).
#[test]
fn actuation_derivatives_match_central_differences_where_the_active_set_holds() {
    // Five states each; twenty for the bounded systems, where about a third of the states
    // cannot meet the maxima (no derivative at run time).
    let mut models: Vec<(Model<f64>, usize)> = mechanisms().into_iter().map(|m| (m, 5)).collect();
    for (n, m, gravity, max) in tendyn_spec::bounded::SIZES {
        let seed = tendyn_spec::bounded::seed(n, m);
        let text = tendyn_spec::bounded::mechanism_ron_scaled(seed, n, m, gravity, max);
        models.push((tendyn_core::parse(&text).unwrap(), 20));
    }
    for (i, (model, states)) in models.iter().enumerate() {
        let mut rng = ChaCha8Rng::seed_from_u64(90 + i as u64);
        let reference = model.cast_numeric::<DD>();
        let (mut data, mut dd) = (Data::new(model), Data::new(&reference));
        let mut worst = 0.0f64;
        let mut checked = 0;
        for _ in 0..*states {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            let Ok(d) = data.actuation_derivatives(model, &q, &qd, &qdd) else {
                continue; // a state the bounds cannot meet
            };
            let inputs = [q, qd, qdd];
            let mut f = |x: &[Vec<DD>]| {
                let r = dd
                    .inverse_dynamics(&reference, &x[0], &x[1], &x[2])
                    .unwrap();
                r.motor_torques
                    .iter()
                    .chain(&r.tendon_tensions)
                    .copied()
                    .collect()
            };
            worst = worst.max(max_rel(&d.d_q, &central(&inputs, 0, &mut f)));
            worst = worst.max(max_rel(&d.d_qd, &central(&inputs, 1, &mut f)));
            worst = worst.max(max_rel(&d.d_qdd, &central(&inputs, 2, &mut f)));
            checked += 1;
        }
        println!(
            "{}: ∂(τ, T)/∂(q, q̇, q̈) at {checked} states, worst relative error {worst:.2e}",
            model.name()
        );
        assert!(checked >= 3 && worst < TOL, "{}: {worst:e}", model.name());
    }
}

#[test]
fn derivatives_of_a_bad_state_are_an_error() {
    let model = tendyn_core::load("../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let mut data = Data::new(&model);
    let err = data
        .generalized_forces_derivatives(&model, &[0.0; 3], &[f64::INFINITY, 0.0, 0.0], &[0.0; 3])
        .unwrap_err();
    assert!(err.to_string().contains("qd[0]"), "{err}");
    assert!(data
        .forward_dynamics_derivatives(&model, &[0.0; 3], &[0.0; 3], &[], &[1.0])
        .is_err());
}

/// Against the Lagrangian reference, which shares no code with the recursion: every
/// column of `∂Q/∂q` and `∂Q/∂q̇` is the derivative of Lagrange's `Q = d/dt(∂L/∂q̇) − ∂L/∂q`
/// along that coordinate, taken exactly by one more layer of dual numbers beneath the
/// reference's own (third derivatives of the energies), for mechanisms without friction
/// or external wrench (whose generalized forces the Lagrangian does not hold).
#[test]
fn the_derivatives_are_those_of_lagrange_s_equations_by_nested_dual_numbers() {
    let mut checked = 0;
    for (i, model) in mechanisms().iter().enumerate() {
        if model.has_friction() || model.external_wrench().is_some() {
            continue;
        }
        let mut rng = ChaCha8Rng::seed_from_u64(200 + i as u64);
        let mut data = Data::new(model);
        let n = model.dof();
        let mut worst = 0.0f64;
        for _ in 0..3 {
            let [q, qd, qdd] = random_state(&mut rng, n);
            let d = data
                .generalized_forces_derivatives(model, &q, &qd, &qdd)
                .unwrap();
            // Row-major, as `Derivatives` holds them: column `l` from the seed `e_l`.
            let (mut by_q, mut by_qd) = (vec![0.0; n * n], vec![0.0; n * n]);
            let zero = vec![0.0; n];
            for l in 0..n {
                let unit: Vec<f64> = (0..n).map(|k| if k == l { 1.0 } else { 0.0 }).collect();
                let state = [&q[..], &qd[..], &qdd[..]];
                let lagrange = |seeds| {
                    tendyn_spec::lagrangian::lagrange_generalized_forces_derivative(
                        model, state, seeds,
                    )
                };
                for (r, x) in lagrange([&unit[..], &zero[..]]).iter().enumerate() {
                    by_q[r * n + l] = *x;
                }
                for (r, x) in lagrange([&zero[..], &unit[..]]).iter().enumerate() {
                    by_qd[r * n + l] = *x;
                }
            }
            worst = worst.max(max_rel(&d.d_q, &by_q));
            worst = worst.max(max_rel(&d.d_qd, &by_qd));
        }
        println!(
            "{}: ∂Q/∂q, ∂Q/∂q̇ against Lagrange, worst {worst:.2e}",
            model.name()
        );
        assert!(worst < TOL, "{}: {worst:e}", model.name());
        checked += 1;
    }
    assert!(checked >= 6, "{checked} mechanisms checked");
}
