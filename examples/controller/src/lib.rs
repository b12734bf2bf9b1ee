//! A computed-torque controller for the Stanford/JPL finger (the paper's Example 3), as it
//! would run on a microcontroller: `#![no_std]`, no `alloc`, no loops over a model, no
//! panics. Its dynamics are generated at build time (`build.rs`) from the mechanism file.
//!
//! One control step: the commanded acceleration
//! `a = q̈_d + K_d (q̇_d − q̇) + K_p (q_d − q)` is turned by the generated inverse dynamics
//! into the four ground-level tendon tensions that produce it, each at or above the
//! tendon floor of the file (the pretension that keeps every tendon taut). The scalar is
//! generic: `f32` on the target, `f64` on a host for testing.
#![no_std]

use tendyn_core::Real;

/// The generated dynamics of the finger (`tendyn_codegen::Builder` in `build.rs`).
pub mod finger {
    tendyn_core::include_mechanism!("example3_stanford_jpl");
}

/// Joints of the finger.
pub const DOF: usize = finger::DOF;
/// Its ground-level tendons.
pub const TENDONS: usize = finger::TENDONS;

/// Where the finger should be at this instant: `q_d`, `q̇_d`, `q̈_d` (rad, rad/s, rad/s²).
#[derive(Clone, Copy, Debug)]
pub struct Desired<T> {
    pub q: [T; DOF],
    pub qd: [T; DOF],
    pub qdd: [T; DOF],
}

/// Proportional and derivative gains per joint (1/s², 1/s).
#[derive(Clone, Copy, Debug)]
pub struct Gains<T> {
    pub kp: [T; DOF],
    pub kd: [T; DOF],
}

/// What one step commands.
#[derive(Clone, Copy, Debug)]
pub struct Command<T> {
    /// The acceleration asked of the dynamics.
    pub acceleration: [T; DOF],
    /// Ground-level tendon tensions (N, file order), each at or above the file's floor.
    pub tensions: [T; TENDONS],
}

/// Computed-torque control of the finger's tendons.
#[derive(Clone, Copy, Debug)]
pub struct ComputedTorque<T> {
    pub gains: Gains<T>,
}

impl<T: Real + PartialOrd> ComputedTorque<T> {
    pub fn new(gains: Gains<T>) -> Self {
        ComputedTorque { gains }
    }

    /// One control step from the measured state `q`, `q̇`.
    #[inline]
    pub fn step(&self, desired: &Desired<T>, q: &[T; DOF], qd: &[T; DOF]) -> Command<T> {
        let g = &self.gains;
        let acceleration = core::array::from_fn(|j| {
            desired.qdd[j] + g.kd[j] * (desired.qd[j] - qd[j]) + g.kp[j] * (desired.q[j] - q[j])
        });
        let tensions = finger::actuation(q, qd, &acceleration).tendon_tensions;
        Command {
            acceleration,
            tensions,
        }
    }
}
