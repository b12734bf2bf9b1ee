//! Runtime parameters are the struct's fields: changing a field changes the dynamics
//! exactly as changing the parameter in the runtime model does.
use tendyn::TendonMechanism;

#[derive(TendonMechanism)]
#[tendyn(
    file = "tests/ui/mechanisms/parametric_finger.ron",
    outputs(generalized_forces, gravity),
    scalar = f64
)]
struct Finger {
    // In any order: they are matched by name.
    g: f64,
    m3: f64,
    i3zz: f64,
    i8: f64,
}

fn main() {
    assert_eq!(Finger::PARAMETER_NAMES, ["m3", "i3zz", "g", "i8"]);
    let file = tendyn::parse(include_str!("../mechanisms/parametric_finger.ron")).unwrap();
    let values = [0.05, 0.0000035, -3.7, 0.000000045];
    let model = file.with_parameters(&values).unwrap();
    let mut solver = tendyn::Data::new(&model);
    let finger = Finger { m3: values[0], i3zz: values[1], g: values[2], i8: values[3] };
    let q = [0.3, -0.2, 0.9];
    let runtime = solver.gravity(&model, &q).unwrap();
    let derived = finger.gravity(&q);
    for j in 0..3 {
        assert!((derived[j] - runtime[j]).abs() <= 1e-12 * (1.0 + runtime[j].abs()));
    }
    // And the payload matters: a different mass gives a different gravity load.
    let lighter = Finger { m3: 0.01, ..finger };
    assert!((lighter.gravity(&q)[1] - derived[1]).abs() > 1e-6);
}
