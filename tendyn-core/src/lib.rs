//! `tendyn-core`: the mechanism model of a tendon-driven robot and a generic runtime
//! solver of its dynamics by the recursive Newton-Euler method of the paper
//! (*Dynamic analysis of tendon-driven robotic mechanisms*, J. Robotic Systems 2003).
//!
//! The modules follow the data flow, file by file:
//!
//! - [`format`](mod@format): the RON file as serde reads it;
//! - [`validate`]: file → [`Model`], every check with a named error ([`Error`], `error.rs`);
//! - [`model`]: the validated, immutable [`Model`] (bodies, strands, the tension system)
//!   and what the recursions may skip ([`model::BodyPattern`]);
//! - [`real`]: the scalar traits [`Real`] (what the recursion needs), [`Numeric`]
//!   (ordering and round-off, for what decides) and [`Symbolic`]; [`trigonometry`]: the
//!   sine and cosine of `f64`, several angles at once (the kinematics forms every angle
//!   first and takes them together); [`DoubleDouble`]
//!   (`double_double.rs`) for references beyond f64; [`spatial`]: 3-vectors and 3×3
//!   matrices over any of them;
//! - [`transmission`]: tendon routing → pulley couplings, segment geometry, structure
//!   matrix `A` and the tension system (paper Eqs. 9-10, 17-18, 26, 31, 33-35);
//! - [`kinematics`]: forward recursion over primary and intermediate links (Eqs. 2-6, 11-15);
//! - [`newton_euler`]: backward recursion (Eqs. 19-24), linear in the tensions: run with
//!   them zero and then with the solved ones; with them as unknowns (affine forms,
//!   [`affine`], at most 12) only for the tests that check `E` against its statics;
//! - [`friction`]: Coulomb and viscous friction of the bearings, the torques the backward
//!   recursion's balances and the generalized forces take in (not in the paper, §2 ii);
//! - [`tension`]: `E x = b` and its minimal-norm solution, segment tensions, and the
//!   model's data for the distribution (and the message when its bounds cannot be met);
//! - [`composite`]: the joint-space mass matrix by the composite-rigid-body algorithm over
//!   the expanded tree (pulleys through their couplings);
//! - [`regrouping`]: the model with each body's mass that moves with its carrier moved
//!   onto it ([`model::Model::regrouped`]): the same torque about every body's axis for
//!   less work, which code generation traces its axial outputs on;
//! - [`dual`](mod@dual) and [`derivatives`]: dual numbers (`no_std`), on which the generic
//!   functions give their exact derivatives with respect to the state and the actuators;
//! - [`regressor`]: the identification regressor `Q = Y π + Q₀`, linear in every body's
//!   inertial parameters and the bearings' friction, by virtual power (not the backward
//!   recursion, which it thereby checks);
//! - [`base_parameters`]: the combinations of those parameters that `Q` can tell apart,
//!   with the grouping of each (what identification can estimate);
//! - [`identification`]: least-squares estimates of the base parameters from measured
//!   motion and actuator forces, with standard deviations;
//! - [`physical_consistency`]: the same fit constrained to mass properties bodies can have
//!   (every pseudo-inertia positive semidefinite, friction non-negative), by a barrier
//!   method, which gives every body's mass, centre of mass and inertia;
//! - [`dynamics`]: inverse dynamics outputs, `M`, `h`, `g` and forward dynamics, generic;
//! - [`data`](mod@data): the runtime front end, [`Data`] (work and result buffers) and its
//!   checked evaluators on numbers;
//! - [`output`]: the outputs by name and the one order their numbers are flattened in
//!   (generated functions', the report's and the checks');
//! - [`torque_range`]: the static torque range of each joint, what the tendons within their
//!   floors and maxima can do on it with every other joint at rest (a linear program);
//! - [`distribution`]: the tension distribution within floors and maxima (`no_std`,
//!   allocation-free), one routine that the runtime solver and generated code both call;
//! - [`linalg`]: the small factorisations (Householder QR for `E⁺` and `null(E)`, Cholesky,
//!   `L D Lᵀ`), written once, generic and allocation-free;
//! - [`mechanism`]: the [`TendonMechanism`] trait of generated dynamics and
//!   [`include_mechanism!`] for code a build script generated.
//!
//! Everything numeric is generic over [`Real`], so `f32`, `f64`, [`DoubleDouble`] and the
//! symbolic scalar of `tendyn-codegen` run the same code. Without the default `std`
//! feature only `real` ([`Real`], [`Numeric`], [`Symbolic`]), `dual`, `distribution`,
//! `linalg` and `mechanism` remain (`no_std`, no `alloc`, math from `libm`): what generated
//! code needs.
//!
//! ```
//! # fn main() -> Result<(), tendyn_core::Error> {
//! let model = tendyn_core::load("../examples/mechanisms/example3_stanford_jpl.ron")?;
//! let mut data = tendyn_core::Data::new(&model);
//! let r = data.inverse_dynamics(&model, &[0.1, 0.5, 0.3], &[0.0; 3], &[1.0, 0.0, 0.0])?;
//! // Every tendon stays at or above the 5 N floor of the file.
//! assert!(r.tendon_tensions.iter().all(|&t| t >= 5.0 - 1e-9));
//!
//! // The same model in double-double, for a reference to f64 precision and beyond.
//! let reference = model.cast_numeric::<tendyn_core::DoubleDouble>();
//! let q = [0.1, 0.5, 0.3].map(tendyn_core::DoubleDouble::from);
//! let mut dd = tendyn_core::Data::new(&reference);
//! let m = dd.mass_matrix(&reference, &q)?;
//! assert!(m[0][0].to_f64() > 0.0);
//! # Ok(())
//! # }
//! ```

#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]

pub mod distribution;
pub mod dual;
pub mod linalg;
pub mod mechanism;
pub mod real;
pub mod trigonometry;
pub use mechanism::TendonMechanism;
pub use real::{Numeric, Real, Symbolic};

#[cfg(feature = "std")]
pub mod affine;
#[cfg(feature = "std")]
pub mod base_parameters;
#[cfg(feature = "std")]
pub mod composite;
#[cfg(feature = "std")]
pub mod data;
#[cfg(feature = "std")]
pub mod derivatives;
#[cfg(feature = "std")]
pub mod double_double;
#[cfg(feature = "std")]
pub mod dynamics;
#[cfg(feature = "std")]
pub mod error;
#[cfg(feature = "std")]
pub mod format;
#[cfg(feature = "std")]
pub mod friction;
#[cfg(feature = "std")]
pub mod identification;
#[cfg(feature = "std")]
pub mod kinematics;
#[cfg(feature = "std")]
pub mod model;
#[cfg(feature = "std")]
pub mod newton_euler;
#[cfg(feature = "std")]
pub mod output;
#[cfg(feature = "std")]
pub mod physical_consistency;
#[cfg(feature = "std")]
pub mod regressor;
#[cfg(feature = "std")]
pub mod regrouping;
#[cfg(feature = "std")]
pub mod spatial;
#[cfg(feature = "std")]
pub mod tension;
#[cfg(feature = "std")]
pub mod torque_range;
#[cfg(feature = "std")]
pub mod transmission;
#[cfg(feature = "std")]
pub mod validate;

#[cfg(feature = "std")]
pub use data::{Data, Regressor};
#[cfg(feature = "std")]
pub use double_double::DoubleDouble;
#[cfg(feature = "std")]
pub use dynamics::InverseDynamics;
#[cfg(feature = "std")]
pub use error::{Error, Result};
#[cfg(feature = "std")]
pub use model::Model;
#[cfg(feature = "std")]
pub use validate::{load, parse};
