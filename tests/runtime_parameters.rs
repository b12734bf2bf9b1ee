//! Runtime parameters: a mechanism whose payload, inertia and gravity are parameters, set at
//! run time, is exactly the mechanism with those numbers typed into the file.

use tendyn_core::Data;

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
    assert_eq!(model.parameters().len(), 4);
    // Nominal values: the shipped example.
    let shipped = tendyn_core::parse(&example("example3_stanford_jpl")).unwrap();
    let (q, qd, qdd) = ([0.2, 0.7, -0.4], [1.0, -2.0, 0.5], [3.0, -1.0, 4.0]);
    let nominal = Data::new(&model)
        .inverse_dynamics(&model, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let want = Data::new(&shipped)
        .inverse_dynamics(&shipped, &q, &qd, &qdd)
        .unwrap()
        .clone();
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
    let got = Data::new(&heavy)
        .inverse_dynamics(&heavy, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let want = Data::new(&typed)
        .inverse_dynamics(&typed, &q, &qd, &qdd)
        .unwrap()
        .clone();
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

/// One `Data` serves a mechanism and every parameter set of it, with results equal to a
/// fresh `Data`'s; a mechanism of another shape gets an error from every evaluator, never
/// a panic or a result computed with the wrong buffers.
#[test]
fn one_data_serves_a_mechanism_at_any_parameters_and_refuses_another_shape() {
    let model = tendyn_core::parse(&parametric_finger()).unwrap();
    let heavy = model
        .with_parameters(&[0.07, 0.0000035, -3.7, 0.000000045])
        .unwrap();
    let (q, qd, qdd) = ([0.2, 0.7, -0.4], [1.0, -2.0, 0.5], [3.0, -1.0, 4.0]);
    let mut data = Data::new(&model);
    data.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
    let reused = data
        .inverse_dynamics(&heavy, &q, &qd, &qdd)
        .unwrap()
        .clone();
    let fresh = Data::new(&heavy)
        .inverse_dynamics(&heavy, &q, &qd, &qdd)
        .unwrap()
        .clone();
    assert_eq!(reused.tendon_tensions, fresh.tendon_tensions);
    assert_eq!(reused.segment_tensions, fresh.segment_tensions);

    let other = tendyn_core::parse(&example("example1_endless")).unwrap();
    let n = other.dof();
    let z = vec![0.0; n];
    let t = vec![0.0; other.tendons().len()];
    let m = vec![0.0; other.motors().len()];
    let refused = |e: tendyn_core::Error| {
        let shown = e.to_string();
        assert!(shown.contains("Data::new(&model)"), "{shown}");
    };
    refused(data.inverse_dynamics(&other, &z, &z, &z).unwrap_err());
    refused(data.generalized_forces(&other, &z, &z, &z).unwrap_err());
    refused(data.mass_matrix(&other, &z).unwrap_err());
    refused(data.bias(&other, &z, &z).unwrap_err());
    refused(data.gravity(&other, &z).unwrap_err());
    refused(data.forward_dynamics(&other, &z, &z, &m, &t).unwrap_err());
    refused(
        data.forward_dynamics_scale(&other, &z, &z, &m, &t)
            .unwrap_err(),
    );
    refused(data.balance_rows(&other, &z, &z, &z).unwrap_err());
}

/// A tree of rigid bodies built in code has no tendons or motors: inverse dynamics says so
/// (its generalized forces are the answer), the joint-space terms are those of the file.
#[test]
fn a_rigid_tree_built_in_code_gives_the_joint_space_terms_of_its_bodies() {
    let file = tendyn_core::parse(&example("example3_stanford_jpl")).unwrap();
    let links = file.bodies()[..file.dof()].to_vec();
    let g = file.gravity().to_array();
    let tree = tendyn_core::Model::rigid_tree("links", g, file.dof(), links, None).unwrap();
    let (q, qd) = ([0.2, 0.7, -0.4], [1.0, -2.0, 0.5]);
    let mut data = Data::new(&tree);
    let err = data.inverse_dynamics(&tree, &q, &qd, &q).unwrap_err();
    assert!(err.to_string().contains("no tendons or motors"), "{err}");
    // The file's pulleys add inertia: the links alone weigh less than the whole finger.
    let whole = Data::new(&file).mass_matrix(&file, &q).unwrap().to_vec();
    let bare = data.mass_matrix(&tree, &q).unwrap().to_vec();
    assert!(
        bare[0][0] > 0.0 && bare[0][0] < whole[0][0],
        "{bare:?} vs {whole:?}"
    );
    let qdd = data.forward_dynamics(&tree, &q, &qd, &[], &[]).unwrap();
    assert!(qdd.iter().all(|x| x.is_finite()));
}

/// `tendyn equations` names more numbers than the file's parameters; what it asks is
/// checked: no clash with a parameter, finite values, every index in range.
#[test]
fn numbers_named_for_printing_are_checked() {
    use tendyn_core::model::Slot;
    let model = tendyn_core::parse(&parametric_finger()).unwrap();
    let mass = model.bodies()[0].mass;
    let named = |names: &[(&str, f64)], slots: &[(Slot, usize)]| {
        let names: Vec<(String, f64)> = names.iter().map(|&(n, v)| (n.to_string(), v)).collect();
        model.with_named_numbers(&names, slots)
    };
    let m = named(&[("m1", mass)], &[(Slot::Mass(0), 0), (Slot::Com(0, 0), 0)]).unwrap();
    assert_eq!(m.parameters().len(), model.parameters().len() + 1);
    assert_eq!(m.parameters().last().unwrap().name, "m1");
    for (names, slots, said) in [
        (
            vec![("m3", mass)],
            vec![],
            "another parameter has this name",
        ),
        (
            vec![("m1", mass), ("m1", mass)],
            vec![],
            "another parameter has this name",
        ),
        (vec![("m1", f64::NAN)], vec![], "not finite"),
        (
            vec![("m9", 1.0)],
            vec![(Slot::Mass(99), 0)],
            "not a number of the model",
        ),
        (
            vec![("w", 1.0)],
            vec![(Slot::WrenchForce(0), 0)],
            "not a number of the model",
        ),
        (
            vec![("m1", mass)],
            vec![(Slot::Mass(0), 1)],
            "names parameter 1 of 1",
        ),
    ] {
        let err = named(&names, &slots).unwrap_err().to_string();
        assert!(err.contains(said), "{err}");
    }
    // Entries of an exact inverse given out of range are named.
    let (_, err) = tendyn_codegen::expr::Graph::default().scope(|| {
        let symbolic = model.symbolic(|_| tendyn_codegen::expr::Sym::input("p"));
        let one = <tendyn_codegen::expr::Sym as tendyn_core::Real>::one();
        let entries = [((99, 0), one)];
        symbolic
            .with_exact_inverse(&entries)
            .unwrap_err()
            .to_string()
    });
    assert!(err.contains("out of range"), "{err}");
}

/// Gravity and the external wrench set at run time are checked as the file's are.
#[test]
fn gravity_set_at_run_time_is_checked_like_the_file() {
    let model = tendyn_core::parse(&parametric_finger()).unwrap();
    let err = model
        .with_parameters(&[0.02, 0.000003, -1e7, 0.000000045])
        .unwrap_err()
        .to_string();
    assert!(err.contains("gravity") && err.contains("range"), "{err}");
}

/// A massless drum whose mass is a parameter is not massless for good: set at run time,
/// its mass reaches `Q`, `h`, `g` and `M` alike, as when typed into the file.
#[test]
fn a_drum_massless_at_its_nominal_value_carries_the_mass_set_at_run_time() {
    let drum = "            radius: 0.02,\n            fixed: true,";
    let text = example("example1_endless");
    assert!(text.contains(drum));
    let with_mass = |mass: &str| {
        text.replacen(
            drum,
            &format!("            radius: 0.02,\n            fixed: true,\n            mass: {mass},\n            com: (0.01, 0.005, 0.0),"),
            1,
        )
    };
    let parametric = with_mass("\"md\"").replacen(
        "(\n    name:",
        "(\n    parameters: [(name: \"md\", value: 0.0)],\n    name:",
        1,
    );
    let model = tendyn_core::parse(&parametric).unwrap();
    let set = model.with_parameters(&[0.3]).unwrap();
    let typed = tendyn_core::parse(&with_mass("0.3")).unwrap();
    let (q, qd, qdd) = ([0.4, -1.1], [1.5, -0.7], [2.0, 3.0]);
    let (mut a, mut b) = (Data::new(&set), Data::new(&typed));
    assert_eq!(
        a.generalized_forces(&set, &q, &qd, &qdd).unwrap(),
        b.generalized_forces(&typed, &q, &qd, &qdd).unwrap()
    );
    assert_eq!(
        a.bias(&set, &q, &qd).unwrap(),
        b.bias(&typed, &q, &qd).unwrap()
    );
    assert_eq!(a.gravity(&set, &q).unwrap(), b.gravity(&typed, &q).unwrap());
    assert_eq!(
        a.mass_matrix(&set, &q).unwrap(),
        b.mass_matrix(&typed, &q).unwrap()
    );
    // The drum carries nothing, so the mass matrix derives its share once per model and
    // keeps it: one Data used with the massless model first must not keep its numbers.
    let mut reused = Data::new(&model);
    reused.mass_matrix(&model, &q).unwrap();
    assert_eq!(
        reused.mass_matrix(&set, &q).unwrap(),
        b.mass_matrix(&typed, &q).unwrap()
    );
    // And the nominal (massless) drum changes nothing.
    let nominal = tendyn_core::parse(&example("example1_endless")).unwrap();
    assert_eq!(
        Data::new(&model)
            .generalized_forces(&model, &q, &qd, &qdd)
            .unwrap(),
        Data::new(&nominal)
            .generalized_forces(&nominal, &q, &qd, &qdd)
            .unwrap()
    );
}

/// A centre of mass at the body's origin at its nominal value, but set by a parameter, is
/// not there for good: the recursions skip the offsets the model knows to be zero, and a
/// parameter's is not one of them.
#[test]
fn a_centre_of_mass_at_the_origin_at_its_nominal_value_moves_with_its_parameter() {
    let text = example("example1_endless");
    let com = "com: (-0.125, 0.0, 0.0),";
    assert!(text.contains(com));
    let parametric = text.replacen(com, "com: (\"cx\", 0.0, 0.0),", 1).replacen(
        "(\n    name:",
        "(\n    parameters: [(name: \"cx\", value: 0.0)],\n    name:",
        1,
    );
    let model = tendyn_core::parse(&parametric).unwrap();
    let set = model.with_parameters(&[-0.125]).unwrap();
    let typed = tendyn_core::parse(&text).unwrap();
    let (q, qd, qdd) = ([0.4, -1.1], [1.5, -0.7], [2.0, 3.0]);
    let (mut a, mut b) = (Data::new(&set), Data::new(&typed));
    assert_eq!(
        a.generalized_forces(&set, &q, &qd, &qdd).unwrap(),
        b.generalized_forces(&typed, &q, &qd, &qdd).unwrap()
    );
    assert_eq!(
        a.inverse_dynamics(&set, &q, &qd, &qdd)
            .unwrap()
            .tendon_tensions,
        b.inverse_dynamics(&typed, &q, &qd, &qdd)
            .unwrap()
            .tendon_tensions
    );
    // At the nominal value the centre of mass is at the origin, and `Q` differs.
    let nominal = Data::new(&model)
        .generalized_forces(&model, &q, &qd, &qdd)
        .unwrap()
        .to_vec();
    assert_ne!(
        nominal,
        b.generalized_forces(&typed, &q, &qd, &qdd).unwrap()
    );
}

/// One `Data` serves a model and the same mechanism with other parameters: its
/// derivatives are each model's own, as fresh buffers give them (the dual-number copy it
/// keeps between calls is that of the model passed, never a stale one).
#[test]
fn derivatives_follow_the_model_passed_not_the_one_before() {
    let model = tendyn_core::parse(&parametric_finger()).unwrap();
    let heavy = model
        .with_parameters(&[0.07, 0.0000035, -3.7, 0.000000045])
        .unwrap();
    let (q, qd, qdd) = ([0.2, 0.7, -0.4], [1.0, -2.0, 0.5], [3.0, -1.0, 4.0]);
    // Every kind of derivative `data` gives for `m`.
    let derivatives = |data: &mut Data<f64>, m: &tendyn_core::Model<f64>| {
        let tensions = [20.0, 15.0, 10.0, 5.0];
        let d = data.generalized_forces_derivatives(m, &q, &qd, &qdd);
        let f = data.forward_dynamics_derivatives(m, &q, &qd, &[], &tensions);
        let a = data.actuation_derivatives(m, &q, &qd, &qdd);
        let (d, f, a) = (d.unwrap(), f.unwrap(), a.unwrap());
        [d.d_q, d.d_qd, f.d_q, f.d_u, a.d_q, a.d_qdd]
    };
    let fresh = |m| derivatives(&mut Data::new(m), m);
    let (mut shared, copy) = (Data::new(&model), model.clone());
    for m in [&model, &heavy, &model, &copy, &heavy] {
        assert_eq!(derivatives(&mut shared, m), fresh(m));
    }
    assert_ne!(fresh(&model), fresh(&heavy), "the parameters must matter");
}
