//! The `no_std` controller linked into a host program: its tensions are the runtime
//! solver's for the commanded acceleration (1e-12 relative in f64, max norm), never below
//! the floor, and in closed loop with the runtime solver's forward dynamics as the plant it
//! brings the finger onto a desired trajectory.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tendyn_core::Data;
use tendyn_finger_controller::{ComputedTorque, Desired, Gains, DOF, TENDONS};

const FLOOR: f64 = 5.0;

fn finger() -> tendyn_core::Model<f64> {
    tendyn_core::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../mechanisms/example3_stanford_jpl.ron"
    ))
    .unwrap()
}

fn gains<T: tendyn_core::Real>(kp: f64, kd: f64) -> Gains<T> {
    Gains {
        kp: [T::from_f64(kp); DOF],
        kd: [T::from_f64(kd); DOF],
    }
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn controller_tensions_are_the_runtime_solvers_for_the_commanded_acceleration_and_stay_taut() {
    let model = finger();
    let mut solver = Data::new(&model);
    let controller = ComputedTorque::new(gains::<f64>(400.0, 40.0));
    let controller32 = ComputedTorque::new(gains::<f32>(400.0, 40.0));
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    for _ in 0..1000 {
        let mut v = |s: f64| -> [f64; DOF] { std::array::from_fn(|_| rng.random_range(-s..s)) };
        let desired = Desired {
            q: v(1.5),
            qd: v(3.0),
            qdd: v(10.0),
        };
        let (q, qd) = (v(1.5), v(3.0));
        let cmd = controller.step(&desired, &q, &qd);
        // The acceleration is the computed-torque law, written out independently here.
        for j in 0..DOF {
            let a = desired.qdd[j] + 40.0 * (desired.qd[j] - qd[j]) + 400.0 * (desired.q[j] - q[j]);
            assert!((cmd.acceleration[j] - a).abs() <= 1e-12 * a.abs().max(1.0));
        }
        let want = &solver
            .inverse_dynamics(&model, &q, &qd, &cmd.acceleration)
            .unwrap()
            .tendon_tensions;
        worst64 = worst64.max(max_rel(&cmd.tensions, want));
        assert!(
            cmd.tensions.iter().all(|&t| t >= FLOOR - 1e-9),
            "{:?}",
            cmd.tensions
        );

        // The same controller in f32, as on the target.
        let f = |x: [f64; DOF]| x.map(|v| v as f32);
        let desired32 = Desired {
            q: f(desired.q),
            qd: f(desired.qd),
            qdd: f(desired.qdd),
        };
        let cmd32 = controller32.step(&desired32, &f(q), &f(qd));
        let want32 = &solver
            .inverse_dynamics(
                &model,
                &q.map(|x| x as f32 as f64),
                &qd.map(|x| x as f32 as f64),
                &cmd32.acceleration.map(f64::from),
            )
            .unwrap()
            .tendon_tensions;
        let got32: Vec<f64> = cmd32.tensions.iter().map(|&t| t as f64).collect();
        worst32 = worst32.max(max_rel(&got32, want32));
        assert!(cmd32
            .tensions
            .iter()
            .all(|&t| t >= FLOOR as f32 * (1.0 - 1e-5)));
    }
    println!(
        "controller vs runtime solver: f64 {worst64:.1e}, f32 {worst32:.1e} (max-norm relative)"
    );
    assert!(worst64 <= 1e-12, "f64: {worst64:.2e}");
    assert!(worst32 <= 1e-5, "f32: {worst32:.2e}");
}

#[test]
fn in_closed_loop_with_the_finger_the_controller_tracks_a_desired_trajectory() {
    // The plant is the runtime solver's forward dynamics driven by the commanded tensions
    // (RK4, 1 ms steps, the tensions held over each step as a controller's would be). The
    // finger starts 0.2 rad off a smooth trajectory; computed torque with ω = 20 rad/s,
    // critically damped, must bring the error under 1e-3 rad within 1 s.
    let model = finger();
    let mut solver = Data::new(&model);
    let (w, dt) = (20.0, 1e-3);
    let controller = ComputedTorque::new(gains::<f64>(w * w, 2.0 * w));
    let desired = |t: f64| {
        // q_d = a sin(f t) per joint, (a, f) below.
        let wave: [(f64, f64); DOF] = [(0.5, 1.0), (0.4, 1.5), (0.3, 2.0)];
        Desired {
            q: wave.map(|(a, f)| a * (f * t).sin()),
            qd: wave.map(|(a, f)| a * f * (f * t).cos()),
            qdd: wave.map(|(a, f)| -a * f * f * (f * t).sin()),
        }
    };
    let mut q = [0.2, -0.2, 0.2];
    let mut qd = [0.0; DOF];
    let mut t = 0.0;
    let mut accel = |q: &[f64; DOF], qd: &[f64; DOF], tensions: &[f64; TENDONS]| -> [f64; DOF] {
        solver
            .forward_dynamics(&model, q, qd, &[], tensions)
            .unwrap()
            .try_into()
            .unwrap()
    };
    let mut worst_late = 0.0f64;
    for step in 0..2000 {
        let cmd = controller.step(&desired(t), &q, &qd);
        assert!(cmd.tensions.iter().all(|&x| x >= FLOOR - 1e-9));
        // RK4 over one step with the tensions held.
        let add = |x: &[f64; DOF], k: &[f64; DOF], h: f64| -> [f64; DOF] {
            std::array::from_fn(|j| x[j] + h * k[j])
        };
        let k1v = accel(&q, &qd, &cmd.tensions);
        let k1q = qd;
        let k2q = add(&qd, &k1v, dt / 2.0);
        let k2v = accel(&add(&q, &k1q, dt / 2.0), &k2q, &cmd.tensions);
        let k3q = add(&qd, &k2v, dt / 2.0);
        let k3v = accel(&add(&q, &k2q, dt / 2.0), &k3q, &cmd.tensions);
        let k4q = add(&qd, &k3v, dt);
        let k4v = accel(&add(&q, &k3q, dt), &k4q, &cmd.tensions);
        for j in 0..DOF {
            q[j] += dt / 6.0 * (k1q[j] + 2.0 * k2q[j] + 2.0 * k3q[j] + k4q[j]);
            qd[j] += dt / 6.0 * (k1v[j] + 2.0 * k2v[j] + 2.0 * k3v[j] + k4v[j]);
        }
        t += dt;
        if step >= 1000 {
            let d = desired(t);
            for (x, want) in q.iter().zip(&d.q) {
                worst_late = worst_late.max((x - want).abs());
            }
        }
    }
    println!("tracking error after 1 s: {worst_late:.2e} rad");
    assert!(worst_late < 1e-3, "{worst_late:.3e} rad");
}
