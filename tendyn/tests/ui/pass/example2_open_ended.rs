//! Paper Example 2 (open-ended tendons, n + 1 routing): the generated tensions agree with
//! the runtime solver and respect the floor.
use tendyn::TendonMechanism;

#[derive(TendonMechanism)]
#[tendyn(
    file = "../examples/mechanisms/example2_open_ended.ron",
    outputs(actuation, forward_dynamics)
)]
struct Arm;

fn main() {
    let model = tendyn::parse(include_str!("../../../../examples/mechanisms/example2_open_ended.ron")).unwrap();
    let mut solver = tendyn::Data::new(&model);
    assert_eq!((Arm::DOF, Arm::TENDONS), (2, 3));
    assert_eq!(Arm::STRUCTURE_MATRIX.len(), 2);
    for k in 0..20 {
        let x = k as f64 * 0.41;
        let (q, qd, qdd) = ([x.cos(), x], [0.2, x.sin()], [x, -0.7]);
        let runtime = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let tensions = Arm.actuation(&q, &qd, &qdd).tendon_tensions;
        for i in 0..3 {
            let scale = 1.0 + runtime.tendon_tensions[i].abs();
            assert!((tensions[i] - runtime.tendon_tensions[i]).abs() <= 1e-12 * scale);
        }
        // Forward dynamics undoes inverse dynamics.
        let back = Arm.forward_dynamics(&q, &qd, &[], &tensions);
        for j in 0..2 {
            assert!((back[j] - qdd[j]).abs() <= 1e-9 * (1.0 + qdd[j].abs()));
        }
    }
}
