//! Independent reference derivations of the dynamics of a [`Model`], for the specification
//! tests to check the Newton-Euler solver against.
//!
//! Nothing here shares code with the solver's kinematics or dynamics: from `tendyn-core`
//! only the model's data types are read (and, in [`fixtures`], a few constructors to fill
//! them in). The derivations are different in kind from a recursion over bodies:
//!
//! - [`poses`]: each body's pose as the plain product of its stored transforms in nalgebra,
//!   in a dual-number scalar; velocities are forward-mode derivatives of poses along the
//!   motion, angular velocities read from `Ṙ Rᵀ`.
//! - [`lagrangian`]: `T`, `V`, `M` (from Jacobians), and Lagrange's equations
//!   `Q = d/dt(∂L/∂q̇) − ∂L/∂q = M q̈ + h + g` by nested dual numbers; energy rate.
//! - [`momentum`]: accelerations, total momentum and its rate, and the base (or any
//!   subtree's) reaction from the momentum balance of the whole mechanism.
//! - [`bounded`]: not dynamics but the bounded tension distribution (least distance to a
//!   target subject to `A T = b`, floors and maxima, or infeasibility) by exhaustive
//!   enumeration of active bound sets in double-double, sharing no code with
//!   `tendyn_core::distribution` or `tendyn_core::tension`; seeded random systems and
//!   their mechanism files.
//!
//! - [`friction`]: bearing friction added to random mechanisms' files, and the power it
//!   dissipates, from the law and the bodies' rates alone.
//!
//! Everything is exact to `f64` rounding: no finite differences.
//!
//! [`stress`] is of another kind: the stress suite's cases and [`stress::measure_case`],
//! which runs the solver itself in `f64`, `f32` and double-double to measure its accuracy.
//!
//! [`Model`]: tendyn_core::model::Model

pub mod bounded;
pub mod examples;
pub mod fixtures;
pub mod friction;
pub mod guides;
pub mod lagrangian;
pub mod measure;
pub mod momentum;
pub mod paper;
pub mod parametric;
pub mod poses;
pub mod random_mechanism;
pub mod redundant;
pub mod stress;

#[cfg(test)]
mod tests;
