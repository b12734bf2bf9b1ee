//! Regrouping (`Model::regrouped`, what generated code traces its axial outputs on): each
//! pulley's mass that moves with its carrier whatever the pulley's angle (a mass on its
//! axis, an inertia `A (1 − z zᵀ)`, all of a fixed drum) moved onto the carrier, or dropped
//! on the base, leaves the torque about every body's axis as it was. So every output made
//! of those torques is the same at every state, to round-off; the bearing forces of the
//! pulleys that gave something up are not, which is why those stay on the file's bodies.

use tendyn_core::model::Model;
use tendyn_core::output::{Output, State};
use tendyn_core::Data;

fn geared_arm() -> Model<f64> {
    tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/mechanisms/geared_arm.ron"
    ))
    .unwrap()
}

/// `count` well-spread states (a Kronecker sequence): `q` in `[−π, π]`, `q̇` in `[−2, 2]`,
/// `q̈` in `[−6, 6]`.
fn states(n: usize, count: usize) -> Vec<[Vec<f64>; 3]> {
    let frac = |k: usize, i: usize| ((k + 1) as f64 * (2.0 + i as f64).sqrt()).fract() * 2.0 - 1.0;
    (0..count)
        .map(|k| {
            let v = |offset: usize, scale: f64| -> Vec<f64> {
                (0..n).map(|j| scale * frac(k, offset + j)).collect()
            };
            [v(0, core::f64::consts::PI), v(n, 2.0), v(2 * n, 6.0)]
        })
        .collect()
}

/// `max |a − b| / max |b|`: the error relative to the output's largest entry (max norm).
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let error = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    error / scale.max(f64::MIN_POSITIVE)
}

/// The largest relative error of `output` between `regrouped` and `model` over `states`.
fn worst(
    model: &Model<f64>,
    regrouped: &Model<f64>,
    output: Output,
    states: &[[Vec<f64>; 3]],
) -> f64 {
    let (mut file, mut moved) = (Data::new(model), Data::new(regrouped));
    let motor_torques: Vec<f64> = (0..model.motors().len())
        .map(|k| 0.3 - 0.1 * k as f64)
        .collect();
    let tendon_tensions: Vec<f64> = (0..model.tendons().len())
        .map(|k| 8.0 + 3.0 * k as f64)
        .collect();
    states
        .iter()
        .map(|[q, qd, qdd]| {
            let state = State {
                q,
                qd,
                qdd,
                motor_torques: &motor_torques,
                tendon_tensions: &tendon_tensions,
            };
            let want = file.output(model, output, &state).unwrap();
            let got = moved.output(regrouped, output, &state).unwrap();
            relative(&got, &want)
        })
        .fold(0.0, f64::max)
}

/// Asserts that each of `outputs` of `regrouped` is `model`'s within `1e-13` relative
/// at every one of `states`.
fn agree(model: &Model<f64>, regrouped: &Model<f64>, outputs: &[Output], states: &[[Vec<f64>; 3]]) {
    for &output in outputs {
        let error = worst(model, regrouped, output, states);
        assert!(error <= 1e-13, "{output:?}: {error:.1e} relative");
    }
}

fn body<'a>(model: &'a Model<f64>, name: &str) -> &'a tendyn_core::model::Body<f64> {
    model.bodies().iter().find(|b| b.name == name).unwrap()
}

#[test]
fn what_turns_with_the_carrier_moves_onto_it_and_the_spin_stays() {
    let model = geared_arm();
    let regrouped = model.regrouped().expect("the geared arm has mass to move");
    // gear0: axisymmetric, centre of mass on its axis: only its moment about the axis stays.
    let gear0 = body(&regrouped, "gear0");
    assert_eq!(gear0.mass, 0.0);
    assert_eq!(
        gear0.inertia.rows,
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 6e-4]]
    );
    let gained = body(&regrouped, "l4").mass - body(&model, "l4").mass;
    assert!(
        (gained - body(&model, "gear0").mass).abs() < 1e-15,
        "l4 gains {gained} kg"
    );
    // drum0: a fixed drum turns with nothing: all of it moves onto l1.
    let drum0 = body(&regrouped, "drum0");
    assert_eq!(drum0.mass, 0.0);
    assert_eq!(drum0.inertia.rows, [[0.0; 3]; 3]);
    // idler1_1, on the base: its mass and the axisymmetric part of its inertia are dropped.
    let idler = body(&regrouped, "idler1_1");
    let zz = body(&model, "idler1_1").inertia.rows[2][2];
    assert_eq!(idler.mass, 0.0);
    assert_eq!(
        idler.inertia.rows,
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, zz]]
    );
    // l1 turns about its frame's z (no twist): `A (1 − z zᵀ)` with `A` its `xx` leaves it
    // for the base, after drum0 and idler2_1, on its joint axis, gave it their mass.
    assert_eq!(body(&regrouped, "l1").inertia.rows[0][0], 0.0);
    let gained = body(&regrouped, "l1").mass - body(&model, "l1").mass;
    let given = body(&model, "drum0").mass + body(&model, "idler2_1").mass;
    assert!((gained - given).abs() < 1e-15, "l1 gains {gained} kg");
}

#[test]
fn every_output_made_of_axial_torques_is_the_file_models_to_round_off() {
    let model = geared_arm();
    let regrouped = model.regrouped().expect("the geared arm has mass to move");
    let states = states(model.dof(), 40);
    // Measured: at most 8e-16 (Q, M, h, g, ∂Q), 5e-15 (forward dynamics, through M's
    // factorisation) and 4e-15 (actuation, through the tension system's solution).
    for (output, bound) in [
        (Output::GeneralizedForces, 1e-13),
        (Output::MassMatrix, 1e-13),
        (Output::Bias, 1e-13),
        (Output::Gravity, 1e-13),
        (Output::Actuation, 1e-13),
        (Output::ForwardDynamics, 1e-12),
        (Output::GeneralizedForcesDerivatives, 1e-12),
    ] {
        let error = worst(&model, &regrouped, output, &states);
        eprintln!("{output:?}: {error:.1e}");
        assert!(error <= bound, "{output:?}: {error:.1e} relative");
    }
}

#[test]
fn a_routed_mechanism_keeps_its_tensions_but_not_its_pulleys_bearing_forces() {
    // Example 3: idlers with mass on their carriers' joint axes.
    let model = tendyn_core::parse(&tendyn_spec::examples::text("example3_stanford_jpl")).unwrap();
    let regrouped = model
        .regrouped()
        .expect("Example 3's idlers have mass to move");
    let states = states(model.dof(), 20);
    agree(
        &model,
        &regrouped,
        &[
            Output::Actuation,
            Output::SegmentTensions,
            Output::GeneralizedForces,
        ],
        &states,
    );
    // The moved masses' inertial forces leave the idlers' bearings: far beyond round-off.
    let error = worst(&model, &regrouped, Output::Bearings, &states);
    assert!(error > 1e-6, "bearings: {error:.1e} relative");
}

#[test]
fn a_fixed_drum_moves_to_where_its_post_puts_it() {
    use tendyn_core::model::{Body, BodyKind, PulleyRole};
    use tendyn_core::spatial::{Mat3, Transform, Vec3};
    // A rigid tree's fixed drum whose `post` turns it a right angle about z (allowed: its
    // axis stays z), its centre of mass 5 cm along its own x, which is the link's y.
    let isotropic = |x: f64| Mat3 {
        rows: [[x, 0.0, 0.0], [0.0, x, 0.0], [0.0, 0.0, x]],
    };
    let link = Body {
        name: "l1".into(),
        kind: BodyKind::Link { joint: 0 },
        parent: None,
        pre: Transform::identity(),
        post: Transform::identity(),
        offset: 0.0,
        coupling: vec![1.0],
        spins: true,
        mass: 1.0,
        com: Vec3::new(0.1, 0.0, 0.0),
        inertia: isotropic(1e-3),
        axis: Vec3::unit_z(),
        joint_to_origin: Vec3::zero(),
        friction: None,
    };
    let drum = Body {
        name: "drum".into(),
        kind: BodyKind::Pulley {
            radius: 0.02,
            role: PulleyRole::Fixed,
        },
        parent: Some(0),
        pre: Transform {
            rotation: Mat3::identity(),
            translation: Vec3::new(0.2, 0.0, 0.0),
        },
        post: Transform {
            rotation: Mat3 {
                rows: [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            },
            translation: Vec3::zero(),
        },
        coupling: vec![0.0],
        mass: 0.5,
        com: Vec3::new(0.05, 0.0, 0.0),
        inertia: isotropic(1e-4),
        ..link.clone()
    };
    let tree = Model::rigid_tree(
        "drum turned by its post",
        [9.81, 0.0, 0.0],
        1,
        vec![link, drum],
        None,
    )
    .unwrap();
    let regrouped = tree.regrouped().expect("the drum moves onto l1");
    // All of the drum on l1: 1.5 kg, centred between l1's own (0.1, 0, 0) and the drum's
    // (0.2, 0.05, 0) in l1's frame.
    let l1 = body(&regrouped, "l1");
    assert_eq!(l1.mass, 1.5);
    let want = [0.4 / 3.0, 0.05 / 3.0, 0.0];
    for (x, w) in l1.com.to_array().iter().zip(want) {
        assert!((x - w).abs() <= 1e-16, "{:?}", l1.com);
    }
    let states = states(1, 20);
    agree(
        &tree,
        &regrouped,
        &[
            Output::GeneralizedForces,
            Output::MassMatrix,
            Output::Bias,
            Output::Gravity,
        ],
        &states,
    );
}

#[test]
fn a_regrouped_parametric_model_takes_parameter_values_as_the_file_model_does() {
    // Regrouping leaves parts of bodies that are not physical alone (no mass, an inertia
    // with a zero diagonal entry); the parameters set other bodies, which alone are
    // checked. At values other than the file's, the outputs still agree.
    let file = tendyn_core::parse(&tendyn_spec::parametric::finger()).unwrap();
    let regrouped = file.regrouped().expect("the finger's pulleys regroup");
    // Masses and gravity up; the inertia entries (each a flat part's largest, at the
    // triangle inequality's limit) down.
    let values: Vec<f64> = file
        .parameters()
        .iter()
        .map(|p| match p.name.starts_with('i') {
            true => 0.95 * p.value,
            false => 1.3 * p.value,
        })
        .collect();
    let (file, regrouped) = (
        file.with_parameters(&values).unwrap(),
        regrouped.with_parameters(&values).unwrap(),
    );
    let states = states(file.dof(), 20);
    agree(
        &file,
        &regrouped,
        &[
            Output::GeneralizedForces,
            Output::MassMatrix,
            Output::Gravity,
            Output::Actuation,
        ],
        &states,
    );
    // A value the parametric body cannot take is still refused.
    let mut negative = values.clone();
    negative[0] = -0.02;
    let error = regrouped
        .with_parameters(&negative)
        .unwrap_err()
        .to_string();
    assert!(error.contains("mass"), "{error}");
}
