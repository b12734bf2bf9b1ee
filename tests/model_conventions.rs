//! The file's conventions mean what `docs/format.md` says, checked against computations that
//! use neither the model's internal representation nor the solver: a hand-written DH
//! product, and a body made of point masses whose dynamics is summed particle by particle.

// Matrix arithmetic reads best with index loops.
#![allow(clippy::needless_range_loop)]

use tendyn_core::spatial::Vec3;
use tendyn_core::transmission::body_transform;
use tendyn_core::Data;

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            c[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// `RotZ(θ) · TransZ(d) · TransX(a) · RotX(α)` written out as the textbook matrix.
fn dh(theta: f64, d: f64, a: f64, alpha: f64) -> M4 {
    let (st, ct, sa, ca) = (theta.sin(), theta.cos(), alpha.sin(), alpha.cos());
    [
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [0.0, sa, ca, d],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

#[test]
fn dh_parameters_compose_as_rotz_transz_transx_rotx_from_the_proximal_frame() {
    let text = r#"(
        name: "chain", gravity: (0.0, 0.0, 0.0),
        links: [
            (name: "l1", dh: (a: 0.3, alpha: 0.7, d: 0.05, offset: 0.2), mass: 1.0),
            (name: "l2", dh: (a: -0.1, alpha: -1.2, d: 0.15, offset: -0.4), mass: 1.0),
            (name: "l3", dh: (a: 0.2, alpha: 2.5, d: -0.07), mass: 1.0),
        ],
        motors: [(name: "m1", on: Joint("l1")), (name: "m2", on: Joint("l2")), (name: "m3", on: Joint("l3"))],
    )"#;
    let m = tendyn_core::parse(text).unwrap();
    let params = [
        (0.3, 0.7, 0.05, 0.2),
        (-0.1, -1.2, 0.15, -0.4),
        (0.2, 2.5, -0.07, 0.0),
    ];
    let q = [0.9, -1.3, 2.1];
    let mut want: M4 = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let mut got = tendyn_core::spatial::Transform::<f64>::identity();
    for (j, &(a, alpha, d, offset)) in params.iter().enumerate() {
        want = mul(&want, &dh(q[j] + offset, d, a, alpha));
        got = got.compose(&body_transform(&m.bodies()[j], q[j] + offset));
        for r in 0..3 {
            for c in 0..3 {
                assert!((got.rotation.rows[r][c] - want[r][c]).abs() < 1e-15);
            }
            assert!((got.translation.to_array()[r] - want[r][3]).abs() < 1e-15);
        }
    }
}

#[test]
fn inertia_off_diagonals_are_tensor_entries_as_a_point_mass_body_shows() {
    // A link made of three point masses (positions in the link frame). Its inertia about
    // the centre of mass, written as the tensor I = Σ m (|r|² 1 − r rᵀ), has entries
    // I_xy = −Σ m x y etc. The link spins about joint 1's axis (z0, through O0 = (−a, 0, 0)
    // in frame 1, since alpha = 0). The force and moment the joint must supply are, particle by
    // particle, Σ m a_i and Σ r_i × m a_i; the solver must report them as the bearing force,
    // bearing moment and motor torque.
    let a = 0.1;
    let particles = [
        (0.3, [0.05, 0.02, 0.03]),
        (0.5, [-0.04, 0.06, -0.02]),
        (0.2, [0.01, -0.05, 0.07]),
    ];
    let mass: f64 = particles.iter().map(|p| p.0).sum();
    let mut com = [0.0; 3];
    for (m, p) in &particles {
        for k in 0..3 {
            com[k] += m * p[k] / mass;
        }
    }
    let mut i = [[0.0; 3]; 3];
    for (m, p) in &particles {
        let r = [p[0] - com[0], p[1] - com[1], p[2] - com[2]];
        let rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        for u in 0..3 {
            for v in 0..3 {
                i[u][v] += m * (if u == v { rr } else { 0.0 } - r[u] * r[v]);
            }
        }
    }
    let text = format!(
        "(name: \"points\", gravity: (0.0, 0.0, 0.0),
          links: [(name: \"l1\", dh: (a: {a}, alpha: 0.0, d: 0.0), mass: {mass}, com: ({}, {}, {}),
                   inertia: (xx: {}, yy: {}, zz: {}, xy: {}, xz: {}, yz: {}))],
          motors: [(name: \"m\", on: Joint(\"l1\"))])",
        com[0], com[1], com[2], i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]
    );
    let m = tendyn_core::parse(&text).unwrap();
    let mut s = Data::new(&m);
    let (q, qd, qdd) = (0.4, 2.5, -3.0);
    let r = s.inverse_dynamics(&m, &[q], &[qd], &[qdd]).unwrap();
    let (f, n) = <Option<Vec<(Vec3<f64>, Vec3<f64>)>> as Clone>::clone(&r.bearings).unwrap()[0];
    let tau = r.motor_torques[0];
    // Particle sums in frame 1, about the joint point.
    let mut force = Vec3::<f64>::zero();
    let mut moment = Vec3::<f64>::zero();
    for (mp, p) in &particles {
        let rvec = Vec3::new(p[0] + a, p[1], p[2]);
        let z = Vec3::unit_z();
        let acc = z.scale(qdd).cross(rvec) - Vec3::new(rvec.x, rvec.y, 0.0).scale(qd * qd);
        force = force + acc.scale(*mp);
        moment = moment + rvec.cross(acc.scale(*mp));
    }
    let close = |x: f64, y: f64| (x - y).abs() < 1e-13 * (1.0 + y.abs());
    assert!(
        close(f.x, force.x) && close(f.y, force.y) && close(f.z, force.z),
        "force {f:?} vs {force:?}"
    );
    assert!(
        close(n.x, moment.x) && close(n.y, moment.y),
        "bearing moment {n:?} vs particle moment {moment:?}"
    );
    assert!(
        close(n.z, 0.0) && close(tau, moment.z),
        "motor torque {tau} vs {}",
        moment.z
    );
    // The off-diagonal entries matter here: with their signs flipped (products of inertia
    // typed where tensor entries belong) the bearing moment changes.
    let flipped = text
        .replace(&format!("xy: {}", i[0][1]), &format!("xy: {}", -i[0][1]))
        .replace(&format!("xz: {}", i[0][2]), &format!("xz: {}", -i[0][2]))
        .replace(&format!("yz: {}", i[1][2]), &format!("yz: {}", -i[1][2]));
    // Here the flipped tensor is not even a physical inertia; either way the two readings
    // cannot both hold.
    match tendyn_core::parse(&flipped) {
        Err(e) => assert!(
            e.to_string().contains("triangle inequality")
                || e.to_string().contains("semi-definite")
        ),
        Ok(m2) => {
            let (_, n2) = <Option<Vec<(Vec3<f64>, Vec3<f64>)>> as Clone>::clone(
                &Data::new(&m2)
                    .inverse_dynamics(&m2, &[q], &[qd], &[qdd])
                    .unwrap()
                    .bearings,
            )
            .unwrap()[0];
            assert!(
                !close(n2.x, moment.x) || !close(n2.y, moment.y),
                "the test cannot tell the conventions apart"
            );
        }
    }
}
