//! The mechanism inline, in f32: a single pendulum whose gravity torque is m g l sin-like.
use tendyn::TendonMechanism;

#[derive(TendonMechanism)]
#[tendyn(
    ron = r#"(
        name: "pendulum",
        gravity: (0.0, -9.81, 0.0),
        links: [
            (name: "link1", dh: (a: 0.5, alpha: 0.0, d: 0.0), mass: 2.0, com: (0.0, 0.0, 0.0),
                inertia: (xx: 0.0, yy: 0.0, zz: 0.0)),
        ],
        motors: [(name: "motor1", on: Joint("link1"))],
    )"#,
    // A repeated output is generated once.
    outputs(gravity, mass_matrix, gravity),
    scalar = f32
)]
struct Pendulum;

fn main() {
    // A point mass of 2 kg at 0.5 m: M = m l², g(q) = m g l cos q (gravity along −y).
    let m = Pendulum.mass_matrix(&[0.4f32]);
    assert!((m[0][0] - 0.5).abs() < 1e-6);
    let g = Pendulum.gravity(&[0.4f32]);
    assert!((g[0] - 2.0 * 9.81 * 0.5 * 0.4f32.cos()).abs() < 1e-4, "{g:?}");
    let _: <Pendulum as TendonMechanism>::Scalar = 0.0f32;
    assert_eq!(Pendulum::OUTPUTS, ["gravity", "mass_matrix"]);
}
