// A derive that fails still declares its methods and the trait, with the file's shapes, so
// that the one error is the located one at the attribute: no "no method named …" (E0599) at
// each call below.
use tendyn::TendonMechanism;

#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/invalid_inertia.ron")]
struct Arm;

fn through_the_trait<M: TendonMechanism<Joints = [f64; 2]>>(m: &M) -> f64 {
    m.gravity(&[0.0; 2]).map_or(0.0, |g| g[0])
}

fn main() {
    let arm = Arm;
    let (q, qd, qdd) = ([0.1, 0.2], [0.0; 2], [0.0; 2]);
    let tau: [f64; 2] = arm.generalized_forces(&q, &qd, &qdd);
    let m = arm.mass_matrix(&q);
    let qdd = arm.forward_dynamics(&q, &qd, &[0.0; 0], &[0.0; 3]);
    let a = arm.actuation(&q, &qd, &qdd);
    let all = arm.all(&q, &qd, &qdd, &[0.0; 0], &[0.0; 3]);
    println!("{} {} {} {:?}", tau[0], m[1][1], through_the_trait(&arm), a.tendon_tensions);
    println!("{:?} {}", all.segment_tensions, all.gravity[1]);
}
