//! The reference checked against closed forms and against itself by independent routes.
//! Each test prints the worst disagreement it saw (`cargo test -- --nocapture`).

use crate::fixtures::{dh_link, model, pulley, rebuilt, with_inertia, with_wrench};
use crate::lagrangian::*;
use crate::momentum::*;
use crate::poses::*;
use nalgebra::{DMatrix, DVector, Matrix3, Matrix4, Vector3};
use num_dual::HyperDual64;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::model::{Body, Model, Wrench};
use tendyn_core::spatial::{rot_x, rot_y, rot_z, Mat3, Transform, Vec3};

const G0: f64 = 9.81;
/// Agreement asked of every comparison, relative to the size of the expected value.
const TOL: f64 = 1e-12;

/// Worst relative disagreement seen in one test.
struct Worst(&'static str, f64);

impl Worst {
    fn check(&mut self, what: &str, got: &[f64], want: &[f64]) {
        assert_eq!(got.len(), want.len(), "{what}: lengths");
        let scale = want.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        let err = got
            .iter()
            .zip(want)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
            / scale;
        assert!(
            err <= TOL,
            "{what}: relative error {err:e}\n got {got:?}\nwant {want:?}"
        );
        self.1 = self.1.max(err);
    }
}

impl Drop for Worst {
    fn drop(&mut self) {
        println!("{}: worst relative disagreement {:e}", self.0, self.1);
    }
}

fn random_vec(rng: &mut ChaCha8Rng, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-scale..scale)).collect()
}

/// A physically valid inertia tensor: principal moments obeying the triangle inequality,
/// rotated by a random rotation.
fn random_inertia(rng: &mut ChaCha8Rng) -> [[f64; 3]; 3] {
    let [x, y, z] = [0; 3].map(|_| rng.random_range(0.01..0.2));
    let r = mat::<f64>(
        &(rot_z(rng.random_range(-3.0..3.0))
            * rot_y(rng.random_range(-3.0..3.0))
            * rot_x(rng.random_range(-3.0..3.0))),
    );
    let i = r * Matrix3::from_diagonal(&Vector3::new(x + y, y + z, z + x)) * r.transpose();
    [0, 1, 2].map(|a| [0, 1, 2].map(|b| i[(a, b)]))
}

/// Inertia `j a aᵀ + jt (1 − a aᵀ)`, axisymmetric about the unit vector `a`.
fn axisymmetric(a: Vector3<f64>, j: f64, jt: f64) -> [[f64; 3]; 3] {
    let i = a * a.transpose() * j + (Matrix3::identity() - a * a.transpose()) * jt;
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| i[(r, c)]))
}

fn dv(x: &[f64]) -> DVector<f64> {
    DVector::from_column_slice(x)
}

fn flat(m: &DMatrix<f64>) -> Vec<f64> {
    m.as_slice().to_vec()
}

// ---------------------------------------------------------------- poses

/// A DH chain with a body whose `pre` is not the identity, against 4×4 homogeneous
/// matrices `Rz(θ) Tz(d) Tx(a) Rx(α)` multiplied out by hand.
#[test]
fn dh_chain_poses_match_homogeneous_products() {
    let mut worst = Worst("dh_chain_poses", 0.0);
    let dh = [
        [0.3, 0.5, 0.1, 0.2],
        [0.0, -1.2, 0.25, -0.4],
        [0.45, 0.0, -0.1, 0.0],
    ];
    let mut bodies: Vec<Body<f64>> = (0..3)
        .map(|j| dh_link(3, j, j.checked_sub(1), dh[j]))
        .collect();
    let pre_r = rot_y(0.3) * rot_x(-0.7);
    let pre_t = [0.05, -0.02, 0.3];
    bodies[1].pre = Transform {
        rotation: pre_r,
        translation: Vec3::from_array(pre_t),
    };
    let m = model(3, [0.0, 0.0, -G0], bodies);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..20 {
        let q = random_vec(&mut rng, 3, 3.0);
        let poses = world_poses::<f64>(&m, &q);
        let mut x = Matrix4::identity();
        for j in 0..3 {
            let [a, alpha, d, offset] = dh[j];
            let (st, ct) = (q[j] + offset).sin_cos();
            let (sa, ca) = alpha.sin_cos();
            #[rustfmt::skip]
            let a_j = Matrix4::new(
                ct, -st * ca,  st * sa, a * ct,
                st,  ct * ca, -ct * sa, a * st,
                0.0,      sa,       ca,      d,
                0.0,     0.0,      0.0,    1.0,
            );
            if j == 1 {
                let mut p = Matrix4::identity();
                p.fixed_view_mut::<3, 3>(0, 0)
                    .copy_from(&mat::<f64>(&pre_r));
                p.fixed_view_mut::<3, 1>(0, 3)
                    .copy_from(&Vector3::from(pre_t));
                x *= p;
            }
            x *= a_j;
            let (r, o) = &poses[j];
            worst.check(
                "rotation",
                r.as_slice(),
                x.fixed_view::<3, 3>(0, 0).clone_owned().as_slice(),
            );
            worst.check(
                "origin",
                o.as_slice(),
                x.fixed_view::<3, 1>(0, 3).clone_owned().as_slice(),
            );
        }
    }
}

// ---------------------------------------------------------------- closed forms

const L: f64 = 0.7;
const LC: f64 = 0.3;
const MASS: f64 = 2.0;
const IZZ: f64 = 0.05;

/// Pendulum about the base z axis, gravity along −y. The link's inertia has off-diagonal
/// entries and its centre of mass sits off the motion plane: neither may matter.
fn pendulum() -> Model<f64> {
    let link = with_inertia(
        dh_link(1, 0, None, [L, 0.0, 0.0, 0.0]),
        MASS,
        [LC - L, 0.0, 0.02],
        [
            [0.11, 0.01, 0.003],
            [0.01, 0.09, -0.004],
            [0.003, -0.004, IZZ],
        ],
    );
    model(1, [0.0, -G0, 0.0], vec![link])
}

#[test]
fn pendulum_closed_form() {
    let mut worst = Worst("pendulum", 0.0);
    let m = pendulum();
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..20 {
        let [q, qd, qdd]: [f64; 3] = [0; 3].map(|_| rng.random_range(-3.0..3.0));
        let (s, c) = q.sin_cos();
        let inertia = IZZ + MASS * LC * LC;
        let grav = MASS * G0 * LC * c;
        worst.check("M", mass_matrix(&m, &[q]).as_slice(), &[inertia]);
        worst.check("g", gravity_forces(&m, &[q]).as_slice(), &[grav]);
        worst.check("h", bias(&m, &[q], &[qd]).as_slice(), &[0.0]);
        let tau = inertia * qdd + grav;
        worst.check(
            "Q",
            lagrange_generalized_forces(&m, &[q], &[qd], &[qdd]).as_slice(),
            &[tau],
        );
        worst.check(
            "T",
            &[kinetic_energy(&m, &[q], &[qd])],
            &[0.5 * inertia * qd * qd],
        );
        worst.check("V", &[potential_energy(&m, &[q])], &[MASS * G0 * LC * s]);
        worst.check(
            "dE/dt",
            &[energy_rate(&m, &[q], &[qd], &[qdd])],
            &[tau * qd],
        );

        let acc = &body_accelerations(&m, &[q], &[qd], &[qdd])[0];
        let a_c = [
            LC * (-s * qdd - c * qd * qd),
            LC * (c * qdd - s * qd * qd),
            0.0,
        ];
        worst.check("ω", acc.angular_velocity.as_slice(), &[0.0, 0.0, qd]);
        worst.check("ω̇", acc.angular_acceleration.as_slice(), &[0.0, 0.0, qdd]);
        worst.check("a_c", acc.com_acceleration.as_slice(), &a_c);
        worst.check(
            "v_c",
            acc.com_velocity.as_slice(),
            &[-LC * s * qd, LC * c * qd, 0.0],
        );

        let (force, moment) = base_reaction(&m, &[q], &[qd], &[qdd]);
        let want = [MASS * a_c[0], MASS * (a_c[1] + G0), 0.0];
        worst.check("F_base", force.as_slice(), &want);
        worst.check("M_base·z", &[moment.z], &[tau]);
    }
}

const ARM: [[f64; 4]; 2] = [[1.0, 0.45, 3.0, 0.2], [0.8, 0.35, 1.7, 0.09]]; // l, lc, m, Izz
const ARM_OFFSETS: [f64; 2] = [-0.2, 0.4];

/// Planar two-link arm in the base x-y plane, gravity along −y. Link 2 sits at a height
/// `d = 0.1` above link 1; inertias are full tensors with the given `I_zz`.
fn arm(extra: Vec<Body<f64>>) -> Model<f64> {
    let n = 2;
    let mut bodies = vec![];
    for (j, [l, lc, mass, izz]) in ARM.into_iter().enumerate() {
        let d = if j == 1 { 0.1 } else { 0.0 };
        let link = dh_link(n, j, j.checked_sub(1), [l, 0.0, d, ARM_OFFSETS[j]]);
        let inertia = [[0.3, -0.02, 0.01], [-0.02, 0.25, 0.015], [0.01, 0.015, izz]];
        bodies.push(with_inertia(link, mass, [lc - l, 0.0, -0.03], inertia));
    }
    bodies.extend(extra);
    model(n, [0.0, -G0, 0.0], bodies)
}

/// `(M, h, g)` of the planar arm (Spong's closed form, angles including the offsets).
fn arm_closed_form(q: &[f64], qd: &[f64]) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
    let [[l1, lc1, m1, i1], [_, lc2, m2, i2]] = ARM;
    let t1 = q[0] + ARM_OFFSETS[0];
    let t2 = q[1] + ARM_OFFSETS[1];
    let (s2, c2) = t2.sin_cos();
    let m11 = i1 + i2 + m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2.0 * l1 * lc2 * c2);
    let m12 = i2 + m2 * (lc2 * lc2 + l1 * lc2 * c2);
    let m22 = i2 + m2 * lc2 * lc2;
    let k = m2 * l1 * lc2 * s2;
    let h = [
        -k * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]),
        k * qd[0] * qd[0],
    ];
    let c1 = t1.cos();
    let c12 = (t1 + t2).cos();
    let g = [
        (m1 * lc1 + m2 * l1) * G0 * c1 + m2 * lc2 * G0 * c12,
        m2 * lc2 * G0 * c12,
    ];
    (
        DMatrix::from_row_slice(2, 2, &[m11, m12, m12, m22]),
        dv(&h),
        dv(&g),
    )
}

#[test]
fn two_link_arm_closed_form() {
    let mut worst = Worst("two_link_arm", 0.0);
    let m = arm(vec![]);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..20 {
        let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, 2, 3.0));
        let (mm, h, g) = arm_closed_form(&q, &qd);
        worst.check("M", mass_matrix(&m, &q).as_slice(), mm.as_slice());
        worst.check("h", bias(&m, &q, &qd).as_slice(), h.as_slice());
        worst.check("g", gravity_forces(&m, &q).as_slice(), g.as_slice());
        let tau = &mm * dv(&qdd) + &h + &g;
        worst.check(
            "Q",
            lagrange_generalized_forces(&m, &q, &qd, &qdd).as_slice(),
            tau.as_slice(),
        );
        worst.check(
            "dE/dt",
            &[energy_rate(&m, &q, &qd, &qdd)],
            &[tau.dot(&dv(&qd))],
        );
        let (_, moment) = base_reaction(&m, &q, &qd, &qdd);
        worst.check("M_base·z", &[moment.z], &[tau[0]]);
        let joint2 = subtree_moment_about_joint(&m, &q, &qd, &qdd, 1);
        worst.check("joint 2 from subtree momentum", &[joint2], &[tau[1]]);
    }
}

/// A disc of inertia `J` about its axis on the base, turned at `q̇1 + γ q̇2`, adds
/// `J [[1, γ], [γ, γ²]]` to `M` and nothing to `h` or `g`: with a spinning frame, and with
/// a non-spinning frame tilted from its axis (axisymmetric inertia about `postᵀ z`).
#[test]
fn coupled_pulley_on_base_adds_j_gamma() {
    let mut worst = Worst("coupled_pulley", 0.0);
    let (j, jt, gamma) = (0.04, 0.025, -1.7);
    let pre = Transform {
        rotation: rot_x(0.3) * rot_y(-0.2),
        translation: Vec3::new(0.2, -0.1, 0.05),
    };
    let add = DMatrix::from_row_slice(2, 2, &[1.0, gamma, gamma, gamma * gamma]) * j;
    for spins in [true, false] {
        let post = if spins {
            Mat3::identity()
        } else {
            rot_x(0.5) * rot_z(0.8)
        };
        let disc = pulley("disc", None, pre, post, vec![1.0, gamma], spins);
        let axis = spin_axis(&disc);
        let disc = with_inertia(disc, 0.5, (axis * 0.03).into(), axisymmetric(axis, j, jt));
        let m = arm(vec![disc]);
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        for _ in 0..20 {
            let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, 2, 3.0));
            let (mm, h, g) = arm_closed_form(&q, &qd);
            let mm = mm + &add;
            worst.check("M", mass_matrix(&m, &q).as_slice(), mm.as_slice());
            worst.check("h", bias(&m, &q, &qd).as_slice(), h.as_slice());
            worst.check("g", gravity_forces(&m, &q).as_slice(), g.as_slice());
            let tau = &mm * dv(&qdd) + &h + &g;
            let got = lagrange_generalized_forces(&m, &q, &qd, &qdd);
            worst.check("Q", got.as_slice(), tau.as_slice());
            let rate = qdd[0] + gamma * qdd[1];
            let acc = &body_accelerations(&m, &q, &qd, &qdd)[2];
            let world_axis = mat::<f64>(&pre.rotation) * Vector3::z();
            worst.check(
                "ω̇ of disc",
                acc.angular_acceleration.as_slice(),
                (world_axis * rate).as_slice(),
            );
        }
    }
}

// ---------------------------------------------------------------- spatial mechanisms

/// A random spatial four-link chain with pulleys: an axisymmetric one on link 1 turned by
/// joints 2-4 (spinning frame or not, as asked), and a fixed drum (no coupling, off-axis
/// centre of mass) on link 2. Gravity points anywhere.
fn spatial_chain(seed: u64, pulley_spins: bool) -> Model<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = 4;
    let mut bodies = vec![];
    for j in 0..n {
        let dh = [
            rng.random_range(-0.5..0.5),
            rng.random_range(-3.0..3.0),
            rng.random_range(-0.3..0.3),
            rng.random_range(-3.0..3.0),
        ];
        let link = dh_link(n, j, j.checked_sub(1), dh);
        let com: [f64; 3] = random_vec(&mut rng, 3, 0.3).try_into().unwrap();
        let inertia = random_inertia(&mut rng);
        bodies.push(with_inertia(link, rng.random_range(0.5..3.0), com, inertia));
    }
    let pre = Transform {
        rotation: rot_y(0.4) * rot_x(0.2),
        translation: Vec3::new(0.1, 0.05, -0.02),
    };
    let p = pulley(
        "pulley",
        Some(1),
        pre,
        rot_x(0.7) * rot_z(-0.3),
        vec![0.0, 1.0, -0.6, 0.3],
        pulley_spins,
    );
    let axis = spin_axis(&p);
    bodies.push(with_inertia(
        p,
        0.4,
        (axis * -0.02).into(),
        axisymmetric(axis, 0.03, 0.02),
    ));
    let drum_pre = Transform {
        rotation: rot_z(1.1),
        translation: Vec3::new(-0.05, 0.1, 0.0),
    };
    let drum = pulley("drum", Some(2), drum_pre, rot_y(0.9), vec![0.0; n], false);
    let inertia = random_inertia(&mut rng);
    bodies.push(with_inertia(drum, 0.3, [0.02, -0.01, 0.04], inertia));
    let gravity: [f64; 3] = random_vec(&mut rng, 3, 6.0).try_into().unwrap();
    model(n, gravity, bodies)
}

/// Lagrange, Jacobians, energy and momentum agree with each other on spatial chains:
/// `M` from Jacobians is the Hessian of `T` in `q̇` and is symmetric positive definite;
/// `Q = M q̈ + h + g`; `Qᵀ q̇ = dE/dt`; the base's moment about joint 1's axis is `Q_1`.
#[test]
fn spatial_chain_routes_agree() {
    let mut worst = Worst("spatial_chain", 0.0);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for seed in 0..10 {
        let mut m = spatial_chain(100 + seed, true);
        m = with_wrench(
            &m,
            Wrench {
                link: 2,
                point: Vec3::new(0.1, -0.2, 0.05),
                force: Vec3::new(3.0, -1.0, 2.0),
                moment: Vec3::new(0.2, 0.5, -0.3),
            },
        );
        let n = m.dof();
        let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, n, 3.0));
        let mm = mass_matrix(&m, &q);
        worst.check("M symmetric", mm.as_slice(), mm.transpose().as_slice());
        assert!(mm.clone().cholesky().is_some(), "M not positive definite");
        let hessian = DMatrix::from_fn(n, n, |i, j| {
            let path: Vec<HyperDual64> = q.iter().map(|&x| HyperDual64::from(x)).collect();
            let rates: Vec<HyperDual64> = (0..n)
                .map(|k| {
                    let e = |a: usize| if a == k { 1.0 } else { 0.0 };
                    HyperDual64::new(qd[k], e(i), e(j), 0.0)
                })
                .collect();
            kinetic_energy_ad(&m, &path, &rates).eps1eps2
        });
        worst.check("M = ∂²T/∂q̇²", mm.as_slice(), hessian.as_slice());
        let t = 0.5 * dv(&qd).dot(&(&mm * dv(&qd)));
        worst.check("T = ½ q̇ᵀMq̇", &[kinetic_energy(&m, &q, &qd)], &[t]);

        let tau = lagrange_generalized_forces(&m, &q, &qd, &qdd);
        let split = &mm * dv(&qdd) + bias(&m, &q, &qd) + gravity_forces(&m, &q);
        worst.check("Q = Mq̈ + h + g", tau.as_slice(), split.as_slice());
        let zero = vec![0.0; n];
        let g = lagrange_generalized_forces(&m, &q, &zero, &zero);
        worst.check(
            "g = Q(q, 0, 0)",
            gravity_forces(&m, &q).as_slice(),
            g.as_slice(),
        );
        worst.check(
            "Qᵀq̇ = dE/dt",
            &[tau.dot(&dv(&qd))],
            &[energy_rate(&m, &q, &qd, &qdd)],
        );

        // Joint 1 turns everything rigidly about the base z axis (pre = I), so the base's
        // moment about that axis is what the actuation supplies to q1.
        let actuation = &tau - external_generalized_forces(&m, &q);
        let (_, moment) = base_reaction(&m, &q, &qd, &qdd);
        worst.check("M_base·z = Q1 − Q_ext,1", &[moment.z], &[actuation[0]]);
    }
}

/// A plain spatial chain driven by joint torques: every joint's torque from the momentum
/// balance of the subtree it carries (moment about its axis) equals Lagrange's `Q_j`.
#[test]
fn joint_torques_from_subtree_momentum() {
    let mut worst = Worst("subtree_momentum", 0.0);
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    for seed in 0..10 {
        let chain = spatial_chain(200 + seed, true);
        let links = chain.bodies()[..chain.dof()].to_vec();
        let m = rebuilt(&chain, links, chain.gravity().to_array(), None);
        let m = with_wrench(
            &m,
            Wrench {
                link: 3,
                point: Vec3::new(-0.1, 0.2, 0.05),
                force: Vec3::new(-2.0, 1.0, 4.0),
                moment: Vec3::new(0.1, -0.4, 0.3),
            },
        );
        let n = m.dof();
        let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, n, 3.0));
        let actuation =
            lagrange_generalized_forces(&m, &q, &qd, &qdd) - external_generalized_forces(&m, &q);
        for j in 0..n {
            let about_axis = subtree_moment_about_joint(&m, &q, &qd, &qdd, j);
            worst.check("τ_j", &[about_axis], &[actuation[j]]);
        }
    }
}

/// An axisymmetric pulley with its centre of mass on its axis is the same body whether its
/// frame spins or not: every output agrees.
#[test]
fn spinning_and_non_spinning_pulley_frames_agree() {
    let mut worst = Worst("spins_true_vs_false", 0.0);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for seed in 0..10 {
        let a = spatial_chain(300 + seed, true);
        let b = spatial_chain(300 + seed, false);
        let n = a.dof();
        let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, n, 3.0));
        worst.check(
            "M",
            &flat(&mass_matrix(&a, &q)),
            &flat(&mass_matrix(&b, &q)),
        );
        let qa = lagrange_generalized_forces(&a, &q, &qd, &qdd);
        let qb = lagrange_generalized_forces(&b, &q, &qd, &qdd);
        worst.check("Q", qa.as_slice(), qb.as_slice());
        let (pa, ha) = momentum_rates(&a, &q, &qd, &qdd);
        let (pb, hb) = momentum_rates(&b, &q, &qd, &qdd);
        worst.check("dP/dt", pa.as_slice(), pb.as_slice());
        worst.check("dH/dt", ha.as_slice(), hb.as_slice());
        let acc_a = &body_accelerations(&a, &q, &qd, &qdd)[n];
        let acc_b = &body_accelerations(&b, &q, &qd, &qdd)[n];
        worst.check(
            "ω",
            acc_a.angular_velocity.as_slice(),
            acc_b.angular_velocity.as_slice(),
        );
        worst.check(
            "ω̇",
            acc_a.angular_acceleration.as_slice(),
            acc_b.angular_acceleration.as_slice(),
        );
        worst.check(
            "a_c",
            acc_a.com_acceleration.as_slice(),
            acc_b.com_acceleration.as_slice(),
        );
    }
}

/// Moving and turning the base frame (every root's `pre`, and gravity with it) changes
/// no joint-space quantity, and moves the base reaction as a wrench.
#[test]
fn base_frame_change_is_invisible_in_joint_space() {
    let mut worst = Worst("base_frame_change", 0.0);
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let r0 = rot_z(0.7) * rot_x(-1.3) * rot_y(0.4);
    let t0 = Vec3::new(0.3, -0.8, 1.1);
    let shift = Transform {
        rotation: r0,
        translation: t0,
    };
    for seed in 0..10 {
        let a = spatial_chain(400 + seed, seed % 2 == 0);
        let mut bodies = a.bodies().to_vec();
        for body in bodies.iter_mut().filter(|body| body.parent.is_none()) {
            body.pre = shift.compose(&body.pre);
        }
        let b = rebuilt(&a, bodies, r0.mul_vec(*a.gravity()).to_array(), None);
        let n = a.dof();
        let [q, qd, qdd] = [0; 3].map(|_| random_vec(&mut rng, n, 3.0));
        worst.check(
            "M",
            &flat(&mass_matrix(&a, &q)),
            &flat(&mass_matrix(&b, &q)),
        );
        let qa = lagrange_generalized_forces(&a, &q, &qd, &qdd);
        let qb = lagrange_generalized_forces(&b, &q, &qd, &qdd);
        worst.check("Q", qa.as_slice(), qb.as_slice());
        let (fa, ma) = base_reaction(&a, &q, &qd, &qdd);
        let (fb, mb) = base_reaction(&b, &q, &qd, &qdd);
        let (r0, t0) = (mat::<f64>(&r0), vec::<f64>(&t0));
        worst.check("F_base", fb.as_slice(), (r0 * fa).as_slice());
        worst.check(
            "M_base",
            mb.as_slice(),
            (r0 * ma + t0.cross(&(r0 * fa))).as_slice(),
        );
    }
}

/// A model built in code must be one the recursion models: a pulley that turns without
/// spinning its frame must be axisymmetric about its axis, and `axis` must be `postᵀ z`.
#[test]
fn a_rigid_tree_the_recursion_does_not_model_is_refused() {
    let m = spatial_chain(9, false);
    let n = m.dof();
    let refused = |change: &dyn Fn(&mut Vec<Body<f64>>)| {
        let mut bodies = m.bodies().to_vec();
        change(&mut bodies);
        Model::rigid_tree("changed", m.gravity().to_array(), n, bodies, None)
            .unwrap_err()
            .to_string()
    };
    let off_axis = refused(&|b| b[n].com = Vec3::new(0.1, 0.0, 0.0));
    assert!(off_axis.contains("not axisymmetric"), "{off_axis}");
    let axis = refused(&|b| b[0].axis = Vec3::new(1.0, 0.0, 0.0));
    assert!(axis.contains("is not postᵀ z"), "{axis}");
    // NaN anywhere, an asymmetric inertia, a pulley carried by a pulley, a shared name.
    let nan = refused(&|b| b[1].post.rotation.rows[0][0] = f64::NAN);
    assert!(nan.contains("must be finite"), "{nan}");
    let nan = refused(&|b| b[0].joint_to_origin.y = f64::NAN);
    assert!(nan.contains("must be finite"), "{nan}");
    let lopsided = refused(&|b| b[2].inertia.rows[1][0] += 1e-3);
    assert!(lopsided.contains("not symmetric"), "{lopsided}");
    let carried = refused(&|b| b[n + 1].parent = Some(n));
    assert!(
        carried.contains("carried by the base or a link"),
        "{carried}"
    );
    let twin = refused(&|b| b[1].name = b[0].name.clone());
    assert!(twin.contains("a name of its own"), "{twin}");
}
