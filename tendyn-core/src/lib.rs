//! `tendyn-core`: the mechanism model of a tendon-driven robot and a generic runtime
//! solver of its dynamics by the recursive Newton-Euler method of the paper
//! (*Dynamic analysis of tendon-driven robotic mechanisms*, J. Robotic Systems 2003).
//!
//! The modules follow the data flow, file by file:
//!
//! - [`format`]: the RON file as serde reads it;
//! - [`validate`]: file → [`Model`], every check with a named error ([`Error`]);
//! - [`transmission`]: tendon routing → pulley couplings, segment geometry, structure
//!   matrix `A` and the tension system (paper Eqs. 9-10, 17-18, 26, 31, 33-35);
//! - [`kinematics`]: forward recursion over primary and intermediate links (Eqs. 2-6, 11-16);
//! - [`newton_euler`]: backward recursion with forces affine in the unknown tensions
//!   (Eqs. 19-24);
//! - [`tension`]: `E x = b`, the tension distribution with a floor, segment tensions;
//! - [`dynamics`]: inverse dynamics outputs, `M`, `h`, `g` and forward dynamics.
//!
//! Everything numeric is generic over [`Real`], so `f32`, `f64`, [`DoubleDouble`] and the
//! symbolic scalar of `tendyn-codegen` run the same code.
//!
//! ```
//! # fn main() -> Result<(), tendyn_core::Error> {
//! let model = tendyn_core::load("../examples/mechanisms/example3_stanford_jpl.ron")?;
//! let mut solver = tendyn_core::Solver::new(&model);
//! let r = solver.inverse_dynamics(&[0.1, 0.5, 0.3], &[0.0; 3], &[1.0, 0.0, 0.0])?;
//! // Every tendon stays at or above the 5 N floor of the file.
//! assert!(r.tendon_tensions.iter().all(|&t| t >= 5.0 - 1e-9));
//!
//! // The same model in double-double, for a reference to f64 precision and beyond.
//! let reference = model.cast_numeric::<tendyn_core::DoubleDouble>();
//! let q = [0.1, 0.5, 0.3].map(tendyn_core::DoubleDouble::from);
//! let mut dd = tendyn_core::Solver::new(&reference);
//! let m = dd.mass_matrix(&q)?;
//! assert!(m[0][0].to_f64() > 0.0);
//! # Ok(())
//! # }
//! ```

pub mod affine;
pub mod double_double;
pub mod dynamics;
pub mod error;
pub mod format;
pub mod kinematics;
pub mod model;
pub mod newton_euler;
pub mod real;
pub mod spatial;
pub mod tension;
pub mod transmission;
pub mod validate;

pub use double_double::DoubleDouble;
pub use dynamics::{InverseDynamics, Solver};
pub use error::{Error, Result};
pub use model::Model;
pub use real::{Numeric, Real};
pub use validate::{load, parse};
