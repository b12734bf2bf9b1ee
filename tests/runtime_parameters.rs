//! Runtime parameters: a mechanism whose payload, inertia and gravity are parameters, set at
//! run time, is exactly the mechanism with those numbers typed into the file.

use tendyn_core::Solver;

fn example(name: &str) -> String {
    tendyn_spec::examples::text(name)
}

fn parametric_finger() -> String {
    tendyn_spec::parametric::finger()
}

#[test]
fn parameters_set_at_run_time_give_the_mechanism_with_those_numbers_typed_in() {
    let text = parametric_finger();
    assert!(
        text.contains("\"m3\"") && text.contains("\"i3zz\"") && text.contains("\"i8\""),
        "substitutions applied"
    );
    let model = tendyn_core::parse(&text).unwrap();
    assert_eq!(model.parameters.len(), 4);
    // Nominal values: the shipped example.
    let shipped = tendyn_core::parse(&example("example3_stanford_jpl")).unwrap();
    let (q, qd, qdd) = ([0.2, 0.7, -0.4], [1.0, -2.0, 0.5], [3.0, -1.0, 4.0]);
    let nominal = Solver::new(&model).inverse_dynamics(&q, &qd, &qdd).unwrap();
    let want = Solver::new(&shipped)
        .inverse_dynamics(&q, &qd, &qdd)
        .unwrap();
    assert_eq!(nominal.tendon_tensions, want.tendon_tensions);
    // A 50 g payload, a stiffer inertia, weaker gravity, a lighter idler.
    let heavy = model
        .with_parameters(&[0.07, 0.0000035, -3.7, 0.000000045])
        .unwrap();
    let typed = tendyn_core::parse(
        &example("example3_stanford_jpl")
            .replacen("gravity: (0.0, 0.0, -9.81)", "gravity: (0.0, 0.0, -3.7)", 1)
            .replacen("            mass: 0.02,\n            com: (-0.02, 0.0, 0.0),\n            inertia: (xx: 0.0000006, yy: 0.0000030, zz: 0.0000030),", "            mass: 0.07,\n            com: (-0.02, 0.0, 0.0),\n            inertia: (xx: 0.0000006, yy: 0.0000030, zz: 0.0000035),", 1)
            .replacen("yy: 0.0000000245, zz: 0.000000049)", "yy: 0.0000000245, zz: 0.000000045)", 1),
    )
    .unwrap();
    let got = Solver::new(&heavy).inverse_dynamics(&q, &qd, &qdd).unwrap();
    let want = Solver::new(&typed).inverse_dynamics(&q, &qd, &qdd).unwrap();
    assert_eq!(got.generalized_forces, want.generalized_forces);
    assert_eq!(got.tendon_tensions, want.tendon_tensions);
    assert_ne!(
        got.tendon_tensions, nominal.tendon_tensions,
        "the parameters must matter"
    );
}

#[test]
fn parameter_values_are_checked_like_the_file() {
    let model = tendyn_core::parse(&parametric_finger()).unwrap();
    let err = model
        .with_parameters(&[-0.01, 0.000003, -9.81, 0.00000005])
        .unwrap_err();
    assert!(
        err.to_string().contains("distal") && err.to_string().contains("mass"),
        "{err}"
    );
    let err = model
        .with_parameters(&[0.02, 0.00001, -9.81, 0.00000005])
        .unwrap_err();
    assert!(err.to_string().contains("triangle inequality"), "{err}");
    let err = model
        .with_parameters(&[0.02, f64::NAN, -9.81, 0.00000005])
        .unwrap_err();
    assert!(err.to_string().contains("i3zz"), "{err}");
    assert!(model.with_parameters(&[0.02]).is_err());
}
