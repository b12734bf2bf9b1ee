//! Paper Example 1 (motors and an endless loop): the derived functions agree with the
//! runtime solver.
use tendyn::TendonMechanism;

#[derive(TendonMechanism)]
#[tendyn(
    file = "../examples/mechanisms/example1_endless.ron",
    outputs(generalized_forces, actuation, mass_matrix, segment_tensions)
)]
struct Arm;

fn main() {
    let model = tendyn::parse(include_str!("../../../../examples/mechanisms/example1_endless.ron")).unwrap();
    let mut solver = tendyn::Data::new(&model);
    assert_eq!((Arm::DOF, Arm::MOTORS, Arm::TENDONS), (2, 2, 0));
    assert_eq!(Arm::MOTOR_NAMES, ["motor1", "motor3"]);
    for k in 0..20 {
        let x = k as f64 * 0.37;
        let (q, qd, qdd) = ([x.sin(), 0.5 * x], [x.cos(), -1.0], [0.3, x]);
        let runtime = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let motors = Arm.actuation(&q, &qd, &qdd).motor_torques;
        let generic = <Arm as TendonMechanism>::generalized_forces(&Arm, &q, &qd, &qdd).unwrap();
        for j in 0..2 {
            let scale = 1.0 + runtime.motor_torques[j].abs();
            assert!((motors[j] - runtime.motor_torques[j]).abs() <= 1e-12 * scale);
            assert!((generic[j] - runtime.generalized_forces[j]).abs() <= 1e-12 * scale);
        }
        let m = Arm.mass_matrix(&q);
        assert_eq!(m[0][1], m[1][0]);
    }
    // Not requested: the trait says so instead of failing to compile generic code.
    assert!(Arm.gravity(&[0.0; 2]).is_none());
}
