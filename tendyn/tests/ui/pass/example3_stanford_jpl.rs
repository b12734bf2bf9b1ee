//! Paper Example 3 (the Stanford/JPL finger, 3 joints and 4 tendons), every output: the
//! derived code agrees with the runtime solver, and generic code sees it through the trait.
use tendyn::TendonMechanism;

#[derive(TendonMechanism)]
#[tendyn(file = "../examples/mechanisms/example3_stanford_jpl.ron")]
struct Finger;

/// Generic over any derived mechanism.
fn taut<M: TendonMechanism<Scalar = f64, Joints = [f64; 3], Tendons = [f64; 4]>>(
    m: &M,
    q: &[f64; 3],
) -> bool {
    let t = m.actuation(q, &[0.0; 3], &[0.0; 3]).unwrap().tendon_tensions;
    t.iter().all(|&t| t >= 5.0 - 1e-9)
}

fn main() {
    let model = tendyn::parse(include_str!("../../../../examples/mechanisms/example3_stanford_jpl.ron")).unwrap();
    let mut solver = tendyn::Data::new(&model);
    assert_eq!(Finger::OUTPUTS.len(), 9);
    assert_eq!(Finger::JOINT_NAMES.len(), 3);
    for k in 0..20 {
        let x = k as f64 * 0.29;
        let (q, qd, qdd) = ([x.sin(), x, -x], [1.0, x.cos(), 0.5], [x, 2.0, -1.0]);
        let runtime = solver.inverse_dynamics(&model, &q, &qd, &qdd).unwrap();
        let all = Finger.all(&q, &qd, &qdd, &[0.0; 0], &[1.0, 2.0, 3.0, 4.0]);
        for j in 0..3 {
            let scale = 1.0 + runtime.generalized_forces[j].abs();
            assert!((all.generalized_forces[j] - runtime.generalized_forces[j]).abs() <= 1e-12 * scale);
        }
        assert!(taut(&Finger, &q));
    }
}
