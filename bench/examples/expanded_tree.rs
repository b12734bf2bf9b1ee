//! Writes a mechanism's expanded tree (every link and pulley a body on a revolute joint,
//! paper Eq. 8: `pre · RotZ(coupling · q + offset) · post` in its parent's frame), the
//! benchmark's 1,024 seeded states and tendyn's `Q`, `∂Q/∂q` and `∂Q/∂q̇` at each, as
//! whitespace-separated numbers,
//! for the Pinocchio harness of `bench/peers/` (`bench/peers/README.md`).
//!
//! `cargo run --release -p tendyn-bench --example expanded_tree -- bench/mechanisms/arm6.ron > arm6.tree`

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::spatial::{Mat3, Transform, Vec3};
use tendyn_core::{Data, Model};

/// The states of `tendyn-codegen/benches/common/states.rs` (seed 7, q̇ in [-3, 3], q̈ in
/// [-10, 10]), for any number of joints.
fn states(n: usize) -> Vec<[Vec<f64>; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    (0..1024)
        .map(|_| {
            let mut v = |s: f64| (0..n).map(|_| rng.random_range(-s..s)).collect::<Vec<_>>();
            [v(std::f64::consts::PI), v(3.0), v(10.0)]
        })
        .collect()
}

fn numbers(out: &mut String, xs: impl IntoIterator<Item = f64>) {
    for x in xs {
        out.push_str(&format!("{x:e} "));
    }
    out.push('\n');
}

fn matrix(m: &Mat3<f64>) -> impl Iterator<Item = f64> + '_ {
    m.rows.iter().flatten().copied()
}

fn transform(out: &mut String, t: &Transform<f64>) {
    let Vec3 { x, y, z } = t.translation;
    numbers(out, matrix(&t.rotation).chain([x, y, z]));
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: expanded_tree FILE.ron");
    let model: Model<f64> = tendyn_core::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let n = model.dof();
    let mut out = String::new();
    let g = model.gravity();
    numbers(
        &mut out,
        [n as f64, model.bodies().len() as f64, g.x, g.y, g.z],
    );
    // The external wrench on a link (format.md §9): its link, point, force and moment in the
    // link's frame; -1 without one.
    match model.external_wrench() {
        Some(w) => {
            let [p, f, m] = [w.point, w.force, w.moment].map(|v| [v.x, v.y, v.z]);
            numbers(&mut out, [[w.link as f64].as_slice(), &p, &f, &m].concat());
        }
        None => numbers(&mut out, [-1.0]),
    }
    for b in model.bodies() {
        numbers(&mut out, [b.parent.map_or(-1.0, |p| p as f64), b.offset]);
        transform(&mut out, &b.pre);
        transform(&mut out, &b.post);
        numbers(&mut out, b.coupling.iter().copied());
        let c = b.com;
        numbers(&mut out, [b.mass, c.x, c.y, c.z]);
        numbers(&mut out, matrix(&b.inertia));
    }
    let mut data = Data::new(&model);
    for [q, qd, qdd] in states(n) {
        let tau = data
            .generalized_forces(&model, &q, &qd, &qdd)
            .unwrap()
            .to_vec();
        // ∂Q/∂q and ∂Q/∂q̇, row-major n × n.
        let d = data
            .generalized_forces_derivatives(&model, &q, &qd, &qdd)
            .unwrap();
        let state = q.iter().chain(&qd).chain(&qdd).chain(&tau);
        numbers(&mut out, state.chain(&d.d_q).chain(&d.d_qd).copied());
    }
    print!("{out}");
}
