//! The identification regressor: `Q = Y(q, q̇, q̈) π + Q₀` (`tendyn_core::regressor`).
//!
//! `Y` comes from virtual power over the forward recursion's Jacobians; `Q` from the
//! Newton-Euler backward recursion, computed here in double-double. The two share no
//! balance of forces, so their agreement checks both.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tendyn_core::regressor::{parameters, values, Quantity};
use tendyn_core::spatial::{Mat3, Vec3};
use tendyn_core::{Data, DoubleDouble, Model};
use tendyn_spec::measure::random_state;

/// `‖Y π + Q₀ − Q‖∞ / ‖Q‖∞` (Y in f64, Q in double-double), worst over `states` states.
fn worst_error(model: &Model<f64>, states: usize, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let reference = model.cast_numeric::<DoubleDouble>();
    let (mut data, mut dd) = (Data::new(model), Data::new(&reference));
    let pi = values(model);
    assert_eq!(pi.len(), parameters(model).len());
    assert_eq!(tendyn_core::regressor::count(model), pi.len());
    let n = model.dof();
    let mut worst = 0.0f64;
    for _ in 0..states {
        let [q, qd, qdd] = random_state(&mut rng, n);
        let r = data.regressor(model, &q, &qd, &qdd).unwrap().clone();
        assert_eq!(r.columns, pi.len());
        let lift = |v: &[f64]| v.iter().map(|&x| DoubleDouble::from(x)).collect::<Vec<_>>();
        let exact = dd
            .generalized_forces(&reference, &lift(&q), &lift(&qd), &lift(&qdd))
            .unwrap()
            .to_vec();
        let scale = exact.iter().fold(1e-300f64, |m, x| m.max(x.to_f64().abs()));
        let rows = r.y.chunks_exact(r.columns);
        for ((row, known), exact) in rows.zip(&r.known).zip(&exact) {
            let y_pi: f64 = row.iter().zip(&pi).map(|(y, p)| y * p).sum::<f64>() + known;
            worst = worst.max((y_pi - exact.to_f64()).abs() / scale);
        }
    }
    worst
}

fn report(model: &Model<f64>, worst: f64) {
    println!(
        "{}: {} parameters, worst relative error {worst:.2e}",
        model.name(),
        parameters(model).len()
    );
}

const TOL: f64 = 1e-13;

#[test]
fn the_regressor_times_the_parameters_is_the_generalized_force_on_the_paper_examples() {
    for (i, model) in tendyn_spec::examples::all().iter().enumerate() {
        let worst = worst_error(model, 50, i as u64);
        report(model, worst);
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

#[test]
fn the_regressor_holds_on_random_spatial_mechanisms_with_coupled_pulleys() {
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    for seed in 0..16u64 {
        let features = Features {
            coupled_pulleys: seed % 2 == 1,
            endless: seed % 4 == 2,
        };
        let (_, model) = valid_random_mechanism(seed, features);
        let worst = worst_error(&model, 20, 100 + seed);
        report(&model, worst);
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

/// The scale mechanisms: a finger, a spatial arm with tilted gears and an external wrench
/// (the known part `Q₀`), and chains of 8 and 12 links with 20 and 30 pulleys.
#[test]
fn the_regressor_holds_on_the_benchmark_mechanisms_and_the_external_wrench_is_known() {
    for name in ["finger4", "arm6", "chain8", "chain12"] {
        let model = tendyn_core::load(format!("../bench/mechanisms/{name}.ron")).unwrap();
        let worst = worst_error(&model, 10, 7);
        report(&model, worst);
        assert!(worst < TOL, "{name}: {worst:e}");
    }
    let arm = tendyn_core::load("../bench/mechanisms/arm6.ron").unwrap();
    let mut data = Data::new(&arm);
    let r = data
        .regressor(&arm, &[0.3; 6], &[0.0; 6], &[0.0; 6])
        .unwrap();
    assert!(r.known.iter().any(|&x| x != 0.0), "arm6's wrench is in Q₀");
}

/// The pin with a turning idler behind it (`tendyn_spec::guides::pin_then_idler`, μ = 0.3)
/// whose bearing rubs.
fn pin_then_rubbing_idler() -> Model<f64> {
    let text = tendyn_spec::guides::pin_then_idler(0.3).replacen(
        "zz: 0.00002)),",
        "zz: 0.00002), friction: (coulomb: 0.002, viscous: 0.0001)),",
        1,
    );
    let model = tendyn_core::parse(&text).unwrap();
    assert!(model
        .bodies()
        .iter()
        .any(|b| b.name == "idl" && b.friction.is_some()));
    model
}

/// Where a turning idler follows a guide with friction, the idler's demand reaches the
/// joints scaled by the guide's factor (format.md §6a): `Y π + Q₀` is then what the
/// actuators deliver, `Σ c_m τ_m + A(σ, q) T` of inverse dynamics' tensions through the
/// joint rows of the state's `E` (the capstan law carried down the route by the recursion,
/// not the idlers' weights the regressor adds). On the pin with a rubbing idler behind it
/// and on random mechanisms whose first idlers are guides with friction and later ones
/// turn.
#[test]
fn behind_a_guide_with_friction_the_regressor_gives_what_the_actuators_deliver() {
    use tendyn_spec::measure::actuator_force_scale;
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    let mut models = vec![pin_then_rubbing_idler()];
    for seed in 0..96u64 {
        let features = Features {
            coupled_pulleys: false,
            endless: false,
        };
        let (text, _) = valid_random_mechanism(seed, features);
        let text = tendyn_spec::guides::first_idlers_as_capstans(&text, 0.1);
        if let Ok(model) = tendyn_core::parse(&text) {
            if model.capstan_before_an_idler() {
                models.push(model);
            }
        }
    }
    assert!(models.len() >= 4, "{} mechanisms", models.len());
    for (i, model) in models.iter().enumerate() {
        let (mut data, pi) = (Data::new(model), values(model));
        let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
        let (mut worst, mut checked) = (0.0f64, 0);
        for _ in 0..100 {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            let Ok(r) = data.inverse_dynamics(model, &q, &qd, &qdd) else {
                continue; // uncontrollable for the state's directions of sliding
            };
            let (tau, t) = (r.motor_torques.clone(), r.tendon_tensions.clone());
            let delivered = data.actuator_forces(model, &q, &qd, &tau, &t).unwrap();
            let size = actuator_force_scale(model, &q, &qd, &tau, &t);
            let r = data.regressor(model, &q, &qd, &qdd).unwrap();
            let rows = r.y.chunks_exact(r.columns);
            for ((row, known), d) in rows.zip(&r.known).zip(&delivered) {
                let y_pi: f64 = row.iter().zip(&pi).map(|(y, p)| y * p).sum::<f64>() + known;
                worst = worst.max((y_pi - d).abs() / size);
            }
            checked += 1;
        }
        report(model, worst);
        assert!(checked >= 50, "{}: {checked} states", model.name());
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

/// Bearing friction enters as two parameters per bearing that has it, by the exact law and
/// smoothed: Example 2 with friction in every bearing, and random mechanisms with it added.
#[test]
fn bearing_friction_parameters_complete_the_regressor() {
    use tendyn_spec::friction::with_bearing_friction;
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    let mut models =
        vec![tendyn_core::parse(&tendyn_spec::examples::text("example2_friction")).unwrap()];
    for seed in 0..6u64 {
        let features = Features {
            coupled_pulleys: seed % 3 == 2,
            endless: seed % 2 == 1,
        };
        let (text, _) = valid_random_mechanism(seed, features);
        let smoothing = (seed % 2 == 1).then_some(0.2);
        models.push(tendyn_core::parse(&with_bearing_friction(&text, seed, smoothing)).unwrap());
    }
    for (i, model) in models.iter().enumerate() {
        let frictional = parameters(model)
            .iter()
            .filter(|p| p.quantity == Quantity::Coulomb)
            .count();
        assert!(frictional > 0, "{}: the fixture has friction", model.name());
        assert_eq!(
            parameters(model).len(),
            10 * model.bodies().len() + 2 * frictional
        );
        let worst = worst_error(model, 50, 30 + i as u64);
        report(model, worst);
        assert!(worst < TOL, "{}: {worst:e}", model.name());
    }
}

/// The model's values are mass, first moment and the inertia about the body-frame origin,
/// `I_o = I_c + m (|c|² 1 − c cᵀ)`, written here entry by entry for a body of a random
/// mechanism whose centre of mass is off every axis.
#[test]
fn the_inertia_parameters_are_about_the_body_frame_origin() {
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
    let features = Features {
        coupled_pulleys: false,
        endless: false,
    };
    let (_, model) = valid_random_mechanism(3, features);
    let pi = values(&model);
    let names: Vec<String> = parameters(&model).iter().map(|p| p.name(&model)).collect();
    let at = |name: String| pi[names.iter().position(|n| *n == name).unwrap()];
    let body = model
        .bodies()
        .iter()
        .find(|b| b.com.x * b.com.y * b.com.z != 0.0 && b.mass > 0.0)
        .expect("a body with its centre of mass off every axis");
    let (m, [x, y, z], name) = (body.mass, body.com.to_array(), &body.name);
    let i = |r: usize, c: usize| body.inertia.rows[r][c];
    let expected = [
        ("m", m),
        ("mx", m * x),
        ("my", m * y),
        ("mz", m * z),
        ("xx", i(0, 0) + m * (y * y + z * z)),
        ("xy", i(0, 1) - m * x * y),
        ("xz", i(0, 2) - m * x * z),
        ("yy", i(1, 1) + m * (x * x + z * z)),
        ("yz", i(1, 2) - m * y * z),
        ("zz", i(2, 2) + m * (x * x + y * y)),
    ];
    let size = i(0, 0) + i(1, 1) + i(2, 2) + m * (x * x + y * y + z * z);
    for (quantity, want) in expected {
        let got = at(format!("{name}.{quantity}"));
        assert!(
            (got - want).abs() <= 1e-15 * size.max(m),
            "{name}.{quantity}: {got} vs {want}"
        );
    }
}

#[test]
fn a_bad_state_is_an_error_not_a_regressor() {
    let model = tendyn_core::load("../examples/mechanisms/example3_stanford_jpl.ron").unwrap();
    let mut data = Data::new(&model);
    let err = data
        .regressor(&model, &[0.0, f64::NAN, 0.0], &[0.0; 3], &[0.0; 3])
        .unwrap_err();
    assert!(err.to_string().contains("q[1]"), "{err}");
    assert!(data
        .regressor(&model, &[0.0; 2], &[0.0; 3], &[0.0; 3])
        .is_err());
}

mod base {
    use super::*;
    use nalgebra::DMatrix;
    use tendyn_core::base_parameters::BaseParameters;

    /// `‖Y_base π_base + Q₀ − Q‖∞ / ‖Q‖∞` at `states` fresh random states (not those the
    /// base was found from), Q in double-double.
    fn worst_reduced_error(model: &Model<f64>, base: &BaseParameters, states: usize) -> f64 {
        let mut rng = ChaCha8Rng::seed_from_u64(0xba5e);
        let reference = model.cast_numeric::<DoubleDouble>();
        let (mut data, mut dd) = (Data::new(model), Data::new(&reference));
        let values = base.values(&values(model));
        let mut worst = 0.0f64;
        for _ in 0..states {
            let [q, qd, qdd] = random_state(&mut rng, model.dof());
            let r = data.regressor(model, &q, &qd, &qdd).unwrap().clone();
            let reduced = base.reduce(&r.y);
            let lift = |v: &[f64]| v.iter().map(|&x| DoubleDouble::from(x)).collect::<Vec<_>>();
            let exact: Vec<f64> = dd
                .generalized_forces(&reference, &lift(&q), &lift(&qd), &lift(&qdd))
                .unwrap()
                .iter()
                .map(|x| x.to_f64())
                .collect();
            let scale = exact.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
            let rows = reduced.chunks_exact(values.len().max(1));
            for ((row, known), exact) in rows.zip(&r.known).zip(&exact) {
                let q: f64 = row.iter().zip(&values).map(|(y, p)| y * p).sum::<f64>() + known;
                worst = worst.max((q - exact).abs() / scale);
            }
        }
        worst
    }

    /// The singular values of `Y` stacked over `3p` rows of random states, largest first.
    fn stacked_singular_values(model: &Model<f64>, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (n, p) = (model.dof(), parameters(model).len());
        let states = (3 * p).div_ceil(n);
        let mut stack = DMatrix::<f64>::zeros(states * n, p);
        let mut data = Data::new(model);
        for s in 0..states {
            let [q, qd, qdd] = random_state(&mut rng, n);
            let r = data.regressor(model, &q, &qd, &qdd).unwrap();
            for (k, row) in r.y.chunks_exact(p).enumerate() {
                for (c, y) in row.iter().enumerate() {
                    stack[(s * n + k, c)] = *y;
                }
            }
        }
        let mut sv: Vec<f64> = stack.singular_values().iter().copied().collect();
        sv.sort_by(|a, b| b.total_cmp(a));
        sv
    }

    fn mechanisms() -> Vec<Model<f64>> {
        use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
        let mut models = tendyn_spec::examples::all();
        models.push(tendyn_core::parse(&tendyn_spec::examples::text("example2_friction")).unwrap());
        for seed in 0..8u64 {
            let features = Features {
                coupled_pulleys: seed % 2 == 1,
                endless: seed % 4 == 2,
            };
            models.push(valid_random_mechanism(seed, features).1);
        }
        for name in ["finger4", "arm6"] {
            models.push(tendyn_core::load(format!("../bench/mechanisms/{name}.ron")).unwrap());
        }
        models
    }

    #[test]
    fn the_base_parameters_give_the_generalized_force_at_states_they_were_not_found_from() {
        for model in mechanisms() {
            let base = BaseParameters::of(&model).unwrap();
            let worst = worst_reduced_error(&model, &base, 30);
            println!(
                "{}: {} of {} parameters are base, {} act on nothing; worst relative error {worst:.2e}",
                model.name(),
                base.groups.len(),
                base.parameters.len(),
                base.unidentifiable.len()
            );
            assert!(worst < TOL, "{}: {worst:e}", model.name());
        }
    }

    /// The count of base parameters is the numerical rank of the regressor stacked over
    /// random states: a gap of many orders in its singular values right after that count.
    #[test]
    fn there_are_as_many_base_parameters_as_the_stacked_regressor_has_rank() {
        for (i, model) in mechanisms().iter().enumerate() {
            let r = BaseParameters::of(model).unwrap().groups.len();
            let sv = stacked_singular_values(model, 40 + i as u64);
            assert!(
                r > 0 && r < sv.len(),
                "{}: {r} of {}",
                model.name(),
                sv.len()
            );
            let (last, next) = (sv[r - 1] / sv[0], sv[r] / sv[0]);
            println!(
                "{}: rank {r}; σ_r/σ_1 = {last:.1e}, σ_(r+1)/σ_1 = {next:.1e}",
                model.name()
            );
            assert!(next < 1e-12 && last > 1e6 * next, "{}", model.name());
        }
    }

    /// Example 1's planar arm, by hand: link 1's frame origin sits at its tip, `a₁ = 0.3 m`
    /// from joint 1, so about that joint its inertia is `zz₁ + 2 a₁ mx₁ + a₁² m₁`, and the
    /// masses of link 2 and the drum it carries (their origins at that tip, or on joint 2)
    /// add `a₁² m`. The motor pulley on the base turns alone: its `zz` is a base parameter.
    #[test]
    fn example1_groups_by_the_parallel_axis_theorem() {
        let model = tendyn_core::parse(&tendyn_spec::examples::text("example1_endless")).unwrap();
        let base = BaseParameters::of(&model).unwrap();
        let names: Vec<String> = base.parameters.iter().map(|p| p.name(&model)).collect();
        let group = |kept: &str| {
            let g = base
                .groups
                .iter()
                .find(|g| names[g.column] == kept)
                .unwrap_or_else(|| panic!("{kept} is not a base parameter"));
            g.merged
                .iter()
                .map(|&(c, b)| (names[c].clone(), b))
                .collect::<Vec<_>>()
        };
        let link1 = group("link1.zz");
        let expect = [
            ("link1.mx", 0.6),
            ("link1.m", 0.09),
            ("link2.m", 0.09),
            ("drum2.m", 0.09),
        ];
        assert_eq!(link1.len(), expect.len(), "{link1:?}");
        for ((name, b), (want, value)) in link1.iter().zip(expect) {
            assert_eq!(name, want);
            assert!((b - value).abs() < 1e-12, "{name}: {b}");
        }
        assert!(group("pulley3.zz").is_empty());
        assert_eq!(base.groups.len(), 5);
    }
}

mod identification {
    use super::*;
    use rand::Rng;
    use tendyn_core::base_parameters::BaseParameters;
    use tendyn_core::identification::{identify, Sample};
    use tendyn_core::physical_consistency::identify_consistent;

    /// `count` samples of a seeded random excitation: per joint a sum of three harmonics of
    /// 0.5 Hz with random amplitudes and phases (so every joint reverses, and the bearings'
    /// Coulomb friction shows), sampled over 50 s, with the generalized forces of inverse
    /// dynamics and Gaussian noise at `snr_db` on each joint.
    fn synthetic(model: &Model<f64>, count: usize, snr_db: f64, seed: u64) -> Vec<Sample> {
        excitation(model, count, snr_db, seed, 1.0)
    }

    /// [`synthetic`] with every harmonic's amplitude times `amplitude`.
    fn excitation(
        model: &Model<f64>,
        count: usize,
        snr_db: f64,
        seed: u64,
        amplitude: f64,
    ) -> Vec<Sample> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let n = model.dof();
        let w = 2.0 * std::f64::consts::PI * 0.5;
        let harmonics: Vec<[(f64, f64); 3]> = (0..n)
            .map(|_| {
                [1.0, 2.0, 3.0].map(|h: f64| {
                    let a = amplitude * rng.random_range(0.3..1.0) / h;
                    (a, rng.random_range(0.0..6.3))
                })
            })
            .collect();
        let mut data = Data::new(model);
        let mut samples: Vec<Sample> = (0..count)
            .map(|i| {
                let t = 50.0 * i as f64 / count as f64;
                let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                for j in 0..n {
                    for (h, &(a, phase)) in harmonics[j].iter().enumerate() {
                        let f = w * (h + 1) as f64;
                        q[j] += a * (f * t + phase).sin();
                        qd[j] += a * f * (f * t + phase).cos();
                        qdd[j] -= a * f * f * (f * t + phase).sin();
                    }
                }
                let forces = data
                    .generalized_forces(model, &q, &qd, &qdd)
                    .unwrap()
                    .to_vec();
                Sample { q, qd, qdd, forces }
            })
            .collect();
        // White noise of one variance on every joint (the estimator's assumption), of power
        // 10^(−snr/10) of the signal's mean power per joint (Box-Muller).
        let power = samples
            .iter()
            .flat_map(|s| &s.forces)
            .map(|f| f * f)
            .sum::<f64>()
            / (count * n) as f64;
        let sigma = (power * 10f64.powf(-snr_db / 10.0)).sqrt();
        for s in &mut samples {
            for f in &mut s.forces {
                let (u1, u2): (f64, f64) = (rng.random_range(1e-300..1.0), rng.random());
                let normal = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
                *f += sigma * normal;
            }
        }
        samples
    }

    /// At 40 dB (white noise of one variance on every joint) the estimator is unbiased and
    /// says how sure it is: every estimate lies within 4.5 of its standard deviations of
    /// the truth, and over all of them about 95 % within 2 (at least 85 % is asked, for
    /// about 70 estimates). Every base parameter the motion determines to 0.25 % (one
    /// standard deviation) is then recovered within 1 %. A pulley's inertia of 1e-5 kg·m²
    /// moves the torques by far less than the noise: no practical record determines it.
    #[test]
    fn identification_at_40_db_recovers_the_base_parameters_the_motion_determines() {
        let mut models = vec![
            tendyn_core::parse(&tendyn_spec::examples::text("example1_endless")).unwrap(),
            tendyn_core::parse(&tendyn_spec::examples::text("example3_stanford_jpl")).unwrap(),
            tendyn_core::parse(&tendyn_spec::examples::text("example2_friction")).unwrap(),
        ];
        models.push(tendyn_core::load("../bench/mechanisms/finger4.ron").unwrap());
        let (mut estimates, mut within_two) = (0, 0);
        for (i, model) in models.iter().enumerate() {
            let base = BaseParameters::of(model).unwrap();
            let truth = base.values(&values(model));
            let samples = synthetic(model, 20_000, 40.0, 7 + i as u64);
            let id = identify(model, &base, &samples).unwrap();
            let names = base.names(model);
            let mut determined = 0;
            for (k, name) in names.iter().enumerate() {
                let (estimate, sd, t) = (id.estimates[k], id.standard_deviations[k], truth[k]);
                let error = (estimate - t).abs();
                assert!(
                    error <= 4.5 * sd,
                    "{}: {name}: {estimate} ± {sd} for {t}",
                    model.name()
                );
                estimates += 1;
                within_two += usize::from(error <= 2.0 * sd);
                if sd <= 0.0025 * t.abs() {
                    determined += 1;
                    assert!(
                        error <= 0.01 * t.abs(),
                        "{}: {name}: {estimate} for {t}",
                        model.name()
                    );
                }
            }
            println!(
                "{}: {} base parameters from {} samples (condition {:.1e}, relative residual \
                 {:.2e}): {determined} determined to 0.25 % and recovered within 1 %",
                model.name(),
                truth.len(),
                id.samples,
                id.condition,
                id.relative_residual
            );
            assert!(
                determined > 0,
                "{}: the 1 % branch was exercised",
                model.name()
            );
        }
        println!("{within_two} of {estimates} estimates within 2 standard deviations");
        assert!(within_two as f64 >= 0.85 * estimates as f64);
    }

    /// The paper's examples with bearing friction among them.
    const EXAMPLES: [&str; 3] = [
        "example1_endless",
        "example3_stanford_jpl",
        "example2_friction",
    ];

    /// An example, its base parameters and their values in the file (the truth of data the
    /// file's own inverse dynamics makes).
    fn example_with_truth(name: &str) -> (Model<f64>, BaseParameters, Vec<f64>) {
        let model = tendyn_core::parse(&tendyn_spec::examples::text(name)).unwrap();
        let base = BaseParameters::of(&model).unwrap();
        let truth = base.values(&values(&model));
        (model, base, truth)
    }

    /// Without noise, through the actuators: motor torques and tendon tensions of inverse
    /// dynamics, turned back into generalized forces by `Data::actuator_forces`, identify
    /// every base parameter to round-off, each against its own value: the tiny ones
    /// included.
    #[test]
    fn identification_from_actuator_forces_without_noise_is_exact() {
        let behind_a_guide = pin_then_rubbing_idler();
        let models = (EXAMPLES.iter())
            .map(|name| example_with_truth(name))
            .chain([{
                let base = BaseParameters::of(&behind_a_guide).unwrap();
                let truth = base.values(&values(&behind_a_guide));
                (behind_a_guide, base, truth)
            }]);
        for (model, base, truth) in models {
            let name = model.name().to_string();
            let mut data = Data::new(&model);
            let samples: Vec<Sample> = synthetic(&model, 400, f64::INFINITY, 3)
                .into_iter()
                .map(|s| {
                    let r = data
                        .inverse_dynamics(&model, &s.q, &s.qd, &s.qdd)
                        .unwrap()
                        .clone();
                    let forces = data
                        .actuator_forces(&model, &s.q, &s.qd, &r.motor_torques, &r.tendon_tensions)
                        .unwrap();
                    Sample { forces, ..s }
                })
                .collect();
            let id = identify(&model, &base, &samples).unwrap();
            // Each against its own value: within 1e-9 of it, or 1e-13 of the largest for
            // those that are zero in exact arithmetic (whose round-off is that of their column
            // against the others', friction columns in other units than inertias).
            let size = truth.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let mut worst = 0.0f64;
            for (e, t) in id.estimates.iter().zip(&truth) {
                let error = (e - t).abs();
                assert!(
                    error <= 1e-9 * t.abs() + 1e-13 * size,
                    "{name}: {e} for {t}"
                );
                if t.abs() > 1e-13 * size {
                    worst = worst.max(error / t.abs());
                }
            }
            println!("{name}: worst error {worst:.1e} relative to each base parameter");
            assert!(
                id.relative_residual < 1e-12,
                "{name}: {}",
                id.relative_residual
            );
        }
    }

    /// Whether `pi` (regressor order) is a body's mass properties, checked as a textbook
    /// does, not through the pseudo-inertia the estimator uses: a non-negative mass; an
    /// inertia about the origin whose principal moments are non-negative and satisfy the
    /// triangle inequalities; a first moment within Cauchy-Schwarz, `|h|² ≤ m ∫|r|² dm =
    /// m tr(I_o) / 2`; and for a body of more than 1e-9 of the largest mass, the same of the
    /// inertia about its centre of mass. Slack is 1e-9 of the largest mass `m_max` and
    /// inertia entry `i_max` of the mechanism.
    fn physical_body(pi: &[f64], m_max: f64, i_max: f64) -> Result<(), String> {
        let (m, h) = (pi[0], nalgebra::Vector3::new(pi[1], pi[2], pi[3]));
        let origin = nalgebra::Matrix3::new(
            pi[4], pi[5], pi[6], pi[5], pi[7], pi[8], pi[6], pi[8], pi[9],
        );
        let slack = 1e-9 * i_max;
        let triangle = |moments: nalgebra::Vector3<f64>, about: &str| {
            for i in 0..3 {
                let (a, b, d) = (moments[i], moments[(i + 1) % 3], moments[(i + 2) % 3]);
                if a < -slack || a > b + d + slack {
                    return Err(format!("principal moments {moments} about the {about}"));
                }
            }
            Ok(())
        };
        if m < -1e-9 * m_max {
            return Err(format!("mass {m}"));
        }
        triangle(origin.symmetric_eigenvalues(), "origin")?;
        if h.norm_squared() > m * 0.5 * origin.trace() + 1e-9 * m_max * i_max {
            return Err(format!(
                "first moment {h} beyond mass {m} and inertia {origin}"
            ));
        }
        if m > 1e-9 * m_max {
            let c = h / m;
            // Parallel axes back to the centre of mass: I_c = I_o − m (|c|² 1 − c cᵀ).
            let shift = nalgebra::Matrix3::identity() * c.norm_squared() - c * c.transpose();
            triangle(
                (origin - shift * m).symmetric_eigenvalues(),
                "centre of mass",
            )?;
        }
        Ok(())
    }

    /// `½ ‖Y_base β − (Q − Q₀)‖²` over `samples`, from the regressor at each sample.
    fn misfit(model: &Model<f64>, pi: &[f64], samples: &[Sample]) -> f64 {
        let mut data = Data::new(model);
        let mut sum = 0.0;
        for s in samples {
            let r = data.regressor(model, &s.q, &s.qd, &s.qdd).unwrap().clone();
            for (k, row) in r.y.chunks_exact(r.columns).enumerate() {
                let q: f64 = row.iter().zip(pi).map(|(y, p)| y * p).sum::<f64>() + r.known[k];
                sum += 0.5 * (q - s.forces[k]).powi(2);
            }
        }
        sum
    }

    /// Where the file's values explain the data exactly (no noise), the consistent estimate
    /// is the least-squares one and every body is physical. To 1e-12 of the largest base
    /// parameter (measured 4.6e-15 to 1.8e-14): the barrier method's estimate stays strictly
    /// inside the physical set, by about the square root of its gap of 1e-28, and the
    /// file's massless drums and flat idlers lie on its boundary.
    #[test]
    fn the_consistent_estimate_of_physical_noise_free_data_is_the_least_squares_one() {
        let mut models: Vec<Model<f64>> = [
            "example1_endless",
            "example3_stanford_jpl",
            "example2_friction",
        ]
        .iter()
        .map(|name| tendyn_core::parse(&tendyn_spec::examples::text(name)).unwrap())
        .collect();
        // Fourteen drums and idlers, each a flat disk: on the boundary.
        models.push(tendyn_core::load("../bench/mechanisms/finger4.ron").unwrap());
        for model in &models {
            let name = model.name();
            let base = BaseParameters::of(model).unwrap();
            let truth = base.values(&values(model));
            let samples = synthetic(model, 1000, f64::INFINITY, 5);
            let c = identify_consistent(model, &base, &samples).unwrap();
            let size = truth.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let mut worst = 0.0f64;
            for ((e, t), ls) in c
                .estimates
                .iter()
                .zip(&truth)
                .zip(&c.least_squares.estimates)
            {
                assert!((e - t).abs() <= 1e-12 * size, "{name}: {e} for {t}");
                assert!((e - ls).abs() <= 1e-12 * size, "{name}: {e} against {ls}");
                worst = worst.max((e - t).abs() / size);
            }
            check_physical(model, &c.parameters);
            every_body_in_the_file_s_terms_gives_back_its_parameters(model, &c);
            // The file's truth is the optimum, so a body is on the boundary exactly where
            // the file's is: no mass, or mass on a plane or a line (a principal moment
            // about the centre of mass equal to the sum of the other two).
            for (b, e) in model.bodies().iter().zip(&c.bodies) {
                let moments =
                    nalgebra::Matrix3::from_fn(|i, j| b.inertia.rows[i][j]).symmetric_eigenvalues();
                let biggest = moments.max();
                let flat = biggest >= moments.sum() - biggest - 1e-12 * biggest;
                assert_eq!(e.on_boundary, b.mass == 0.0 || flat, "{name}: {}", b.name);
            }
            println!(
                "{name}: worst error {worst:.1e} of the largest base parameter, {} Newton \
                 steps, relative residual {:.1e}",
                c.newton_steps, c.relative_residual
            );
            assert!(
                c.relative_residual < 1e-12,
                "{name}: {}",
                c.relative_residual
            );
        }
    }

    /// Motion that barely excites some base parameters (every joint within a few
    /// milliradians: a stacked regressor of condition number above 1e6) costs the consistent
    /// estimate no more than round-off times that condition: it keeps its misfit as a square
    /// root. Through the normal equations the gap could not fall below about 1e-20, and the
    /// file's massless and flat bodies, held inside the physical set by the barrier, moved
    /// the estimate by 1e-9 to 3e-7 of the largest base parameter (measured 3e-12 to 3e-11).
    #[test]
    fn poorly_exciting_motion_costs_the_consistent_estimate_no_squared_condition() {
        for name in EXAMPLES {
            let (model, base, truth) = example_with_truth(name);
            let size = truth.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let samples = excitation(&model, 1000, f64::INFINITY, 5, 0.003);
            let c = identify_consistent(&model, &base, &samples).unwrap();
            assert!(
                c.least_squares.condition > 1e6,
                "{name}: {}",
                c.least_squares.condition
            );
            let worst = (c.estimates.iter().zip(&truth))
                .fold(0.0f64, |m, (e, t)| m.max((e - t).abs() / size));
            println!(
                "{name}: condition {:.1e}, worst error {worst:.1e} of the largest base \
                 parameter, {} Newton steps, gap {:.0e}",
                c.least_squares.condition, c.newton_steps, c.gap
            );
            assert!(worst <= 1e-10, "{name}: {worst:.1e}");
            check_physical(&model, &c.parameters);
        }
    }

    /// `BodyEstimate` is the file's terms (mass, centre of mass, inertia about it) of the
    /// estimate's parameters: from them, `h = m c` and `I_o = I_c + m (|c|² 1 − c cᵀ)` give
    /// the parameters back.
    fn every_body_in_the_file_s_terms_gives_back_its_parameters(
        model: &Model<f64>,
        c: &tendyn_core::physical_consistency::Consistent,
    ) {
        let parameters = parameters(model);
        for (b, e) in c.bodies.iter().enumerate() {
            let at = parameters
                .iter()
                .position(|p| p.body == b && p.quantity == Quantity::Inertial(0))
                .unwrap();
            let centre = nalgebra::Matrix3::from_fn(|i, j| e.inertia[i][j]);
            let back = regressor_order(e.mass, nalgebra::Vector3::from(e.com), centre);
            let friction = |q: Quantity| {
                let k = parameters
                    .iter()
                    .position(|p| p.body == b && p.quantity == q);
                k.map(|k| c.parameters[k])
            };
            let pair = friction(Quantity::Coulomb).zip(friction(Quantity::Viscous));
            assert_eq!(e.friction, pair, "{}: body {b}", model.name());
            let pi = &c.parameters[at..at + 10];
            let size = pi.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
            for (x, y) in back.iter().zip(pi) {
                assert!(
                    (x - y).abs() <= 1e-9 * size,
                    "{}: {back:?} vs {pi:?}",
                    model.name()
                );
            }
        }
    }

    /// Every body's parameters in `pi` are physical (see [`physical_body`]), and friction
    /// non-negative.
    fn check_physical(model: &Model<f64>, pi: &[f64]) {
        let parameters = parameters(model);
        let firsts: Vec<usize> = (0..parameters.len())
            .filter(|&c| parameters[c].quantity == Quantity::Inertial(0))
            .collect();
        let m_max = firsts.iter().fold(0.0f64, |m, &c| m.max(pi[c]));
        let i_max = firsts
            .iter()
            .flat_map(|&c| &pi[c + 4..c + 10])
            .fold(0.0f64, |m, x| m.max(x.abs()));
        for &c in &firsts {
            if let Err(e) = physical_body(&pi[c..c + 10], m_max, i_max) {
                let body = &model.bodies()[parameters[c].body].name;
                panic!("{}: body {body}: {e}", model.name());
            }
        }
        for (p, v) in parameters.iter().zip(pi) {
            if matches!(p.quantity, Quantity::Coulomb | Quantity::Viscous) {
                assert!(*v >= 0.0, "{}: {} = {v}", model.name(), p.name(model));
            }
        }
    }

    /// A body that turns without spinning is modelled only with a mass axisymmetric about
    /// its axis, so at 40 dB, where the data alone would tilt it, its estimate stays so: the
    /// centre of mass on the axis and the inertia about it of the form `A a aᵀ + B (1 − a aᵀ)`,
    /// here about the twisted first link's axis, which is not the frame's z.
    #[test]
    fn a_body_turning_without_spinning_stays_axisymmetric_about_its_tilted_axis() {
        let file =
            tendyn_core::parse(&tendyn_spec::examples::text("example3_stanford_jpl")).unwrap();
        // The first link alone: a body that turns without spinning carries nothing.
        let mut links = file.bodies()[..1].to_vec();
        let link = &mut links[0];
        link.coupling.truncate(1);
        let a = link.axis;
        assert!(a.z.abs() < 0.5, "the twisted link's axis: {a:?}");
        let axisymmetric = |along: f64, across: f64| {
            let a = a.to_array();
            Mat3 {
                rows: std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        let identity = if i == j { 1.0 } else { 0.0 };
                        along * a[i] * a[j] + across * (identity - a[i] * a[j])
                    })
                }),
            }
        };
        link.spins = false;
        link.com = -link.joint_to_origin + a.scale(0.01);
        link.inertia = axisymmetric(2e-4, 1e-4);
        let tree =
            tendyn_core::Model::rigid_tree("tilted", [0.0, 0.0, -9.81], 1, links, None).unwrap();
        assert!(tree.bodies()[0].axisymmetric());
        let base = BaseParameters::of(&tree).unwrap();
        let samples = synthetic(&tree, 2000, 40.0, 11);
        let c = identify_consistent(&tree, &base, &samples).unwrap();
        let e = &c.bodies[0];
        let com = Vec3::from_array(e.com);
        let from_axis = com + tree.bodies()[0].joint_to_origin;
        let radial = from_axis - a.scale(from_axis.dot(a));
        assert!(radial.dot(radial).sqrt() <= 1e-9 * 0.1, "{:?}", e.com);
        let inertia = Mat3 { rows: e.inertia };
        let along = a.dot(inertia.mul_vec(a));
        let across = (e.inertia[0][0] + e.inertia[1][1] + e.inertia[2][2] - along) / 2.0;
        let want = axisymmetric(along, across);
        for (row, want) in e.inertia.iter().zip(want.rows) {
            for (x, w) in row.iter().zip(want) {
                assert!((x - w).abs() <= 1e-9 * along, "{:?}", e.inertia);
            }
        }
        // And the data moved it: the estimate is not the file's.
        assert!((along - 2e-4).abs() > 1e-12 || (e.mass - tree.bodies()[0].mass).abs() > 1e-9);
    }

    /// Data no mechanism can produce: the generalized forces of the file's parameters with
    /// every sign flipped (a negative mass matrix). Least squares fits them exactly with
    /// unphysical values; the consistent estimate is physical, and no physical parameters do
    /// better: moving from it towards any of a hundred random physical bodies' values, or
    /// the file's, never lowers the misfit (the problem is convex, so this is its optimum).
    #[test]
    fn the_consistent_estimate_of_unphysical_data_is_the_best_physical_fit() {
        let model = tendyn_core::parse(&tendyn_spec::examples::text("example2_friction")).unwrap();
        let base = BaseParameters::of(&model).unwrap();
        let pi = values(&model);
        let mut data = Data::new(&model);
        let samples: Vec<Sample> = synthetic(&model, 300, f64::INFINITY, 11)
            .into_iter()
            .map(|s| {
                let r = data.regressor(&model, &s.q, &s.qd, &s.qdd).unwrap().clone();
                let forces =
                    r.y.chunks_exact(r.columns)
                        .zip(&r.known)
                        .map(|(row, k)| k - row.iter().zip(&pi).map(|(y, p)| y * p).sum::<f64>())
                        .collect();
                Sample { forces, ..s }
            })
            .collect();
        let c = identify_consistent(&model, &base, &samples).unwrap();
        assert!(c.least_squares.relative_residual < 1e-10);
        assert!(c.relative_residual > 0.1, "{}", c.relative_residual);
        check_physical(&model, &c.parameters);
        let best = misfit(&model, &c.parameters, &samples);
        let mut rng = ChaCha8Rng::seed_from_u64(19);
        let mut others = vec![pi.clone()];
        for _ in 0..100 {
            others.push(random_physical(&model, &mut rng));
        }
        for other in &others {
            for s in [1e-3, 1e-2, 0.1, 1.0] {
                let mixed: Vec<f64> = c
                    .parameters
                    .iter()
                    .zip(other)
                    .map(|(a, b)| a + s * (b - a))
                    .collect();
                let m = misfit(&model, &mixed, &samples);
                assert!(m >= best * (1.0 - 1e-9), "step {s}: {m} below {best}");
            }
        }
        println!(
            "{}: relative residual {:.3} (least squares {:.1e}), {} Newton steps, {} bodies \
             on the boundary",
            model.name(),
            c.relative_residual,
            c.least_squares.relative_residual,
            c.newton_steps,
            c.bodies.iter().filter(|b| b.on_boundary).count()
        );
    }

    /// At 40 dB, where the truth is physical: the consistent estimate is the projection of
    /// the least-squares one onto the physical set in the regressor's norm (the file's
    /// penalty acts only where the forces see nothing), and a projection onto a convex set
    /// moves no farther from any point of it. So `‖Y_base (β − β_true)‖` over the samples is
    /// smaller for the consistent estimate than for least squares where least squares is
    /// unphysical (here two estimates below zero whose truth is positive), and every body
    /// is physical.
    #[test]
    fn the_consistent_estimate_is_no_farther_from_a_physical_truth_than_least_squares() {
        let model = tendyn_core::load("../bench/mechanisms/finger4.ron").unwrap();
        let base = BaseParameters::of(&model).unwrap();
        let truth = base.values(&values(&model));
        let samples = synthetic(&model, 4000, 40.0, 23);
        let c = identify_consistent(&model, &base, &samples).unwrap();
        check_physical(&model, &c.parameters);
        let mut data = Data::new(&model);
        let (mut consistent, mut least_squares) = (0.0f64, 0.0f64);
        for s in &samples {
            let r = data.regressor(&model, &s.q, &s.qd, &s.qdd).unwrap().clone();
            let reduced = base.reduce(&r.y);
            for row in reduced.chunks_exact(truth.len()) {
                let off = |beta: &[f64]| -> f64 {
                    row.iter()
                        .zip(beta)
                        .zip(&truth)
                        .map(|((y, b), t)| y * (b - t))
                        .sum()
                };
                consistent += off(&c.estimates).powi(2);
                least_squares += off(&c.least_squares.estimates).powi(2);
            }
        }
        let (consistent, least_squares) = (consistent.sqrt(), least_squares.sqrt());
        let negative = (c.least_squares.estimates.iter().zip(&truth))
            .filter(|(e, t)| **e < 0.0 && **t > 0.0)
            .count();
        println!(
            "finger4 at 40 dB: ‖Y (β − β_true)‖ {consistent:.4e} consistent, {least_squares:.4e} \
             least squares; {negative} least-squares estimates negative where the truth is \
             positive; {} Newton steps",
            c.newton_steps
        );
        assert!(
            negative > 0,
            "least squares stayed physical: the case tests nothing"
        );
        assert!(consistent < least_squares);
    }

    /// A body's ten parameters in the regressor's order from its mass, centre of mass and
    /// inertia about it: `h = m c`, `I_o = I_c + m (|c|² 1 − c cᵀ)`.
    fn regressor_order(
        m: f64,
        c: nalgebra::Vector3<f64>,
        centre: nalgebra::Matrix3<f64>,
    ) -> [f64; 10] {
        let origin =
            centre + (nalgebra::Matrix3::identity() * c.norm_squared() - c * c.transpose()) * m;
        let h = c * m;
        [
            m,
            h.x,
            h.y,
            h.z,
            origin[(0, 0)],
            origin[(0, 1)],
            origin[(0, 2)],
            origin[(1, 1)],
            origin[(1, 2)],
            origin[(2, 2)],
        ]
    }

    /// Random physical parameters for every body: a mass of up to 1 kg at a centre within
    /// 0.2 m, principal moments that satisfy the triangle inequality, turned at random;
    /// friction up to 0.1.
    fn random_physical(model: &Model<f64>, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let mut out = Vec::new();
        for p in parameters(model) {
            if p.quantity == Quantity::Inertial(0) {
                let m: f64 = rng.random_range(0.0..1.0);
                let c = nalgebra::Vector3::from_fn(|_, _| rng.random_range(-0.2..0.2));
                let (a, b): (f64, f64) = (rng.random_range(0.0..1e-2), rng.random_range(0.0..1e-2));
                let d = rng.random_range((a - b).abs()..(a + b).max((a - b).abs() + 1e-12));
                let turn =
                    nalgebra::Rotation3::from_scaled_axis(nalgebra::Vector3::from_fn(|_, _| {
                        rng.random_range(-3.0..3.0)
                    }));
                let centre = turn.matrix()
                    * nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(a, b, d))
                    * turn.matrix().transpose();
                out.extend(regressor_order(m, c, centre));
            } else if matches!(p.quantity, Quantity::Coulomb | Quantity::Viscous) {
                out.push(rng.random_range(0.0..0.1));
            }
        }
        out
    }
}
