//! Generated code for the paper's examples and seeded random mechanisms (see `build.rs`),
//! compiled here so that `tests/agreement.rs` can check it against the runtime solver.

/// One generated mechanism: its RON text and an adapter that evaluates every generated
/// output at a state (`q`, `q̇`, `q̈`, motor torques, tendon tensions, runtime parameters).
pub struct Mechanism {
    pub name: &'static str,
    pub ron: &'static str,
    #[allow(clippy::type_complexity)]
    pub evaluate:
        fn(&[f64], &[f64], &[f64], &[f64], &[f64], &[f64]) -> Vec<(&'static str, Vec<f64>)>,
    /// The same code run in `f32`.
    #[allow(clippy::type_complexity)]
    pub evaluate_f32:
        fn(&[f32], &[f32], &[f32], &[f32], &[f32], &[f32]) -> Vec<(&'static str, Vec<f32>)>,
}

/// Generated `actuation` of a bounded-distribution system (`BOUNDED`: the seeded random
/// ones and a capstan one, see `build.rs`): ground-level tensions and status, in each
/// scalar, and their derivatives.
pub struct Bounded {
    pub name: &'static str,
    pub ron: &'static str,
    pub actuation_f64: AtState<f64, (Vec<f64>, Status)>,
    pub actuation_f32: AtState<f32, (Vec<f32>, Status)>,
    /// `actuation_derivatives`, flattened: the value, then `∂/∂q`, `∂/∂q̇`, `∂/∂q̈` row by row.
    pub actuation_derivatives_f64: AtState<f64, Vec<f64>>,
    /// The same in `f32`.
    pub actuation_derivatives_f32: AtState<f32, Vec<f32>>,
    /// `all` (`f64`): its `actuation`'s tensions and status, and its
    /// `actuation_derivatives` flattened as above.
    pub all_f64: AtState<f64, (Vec<f64>, Status, Vec<f64>)>,
}

/// A generated function of the state `(q, q̇, q̈)`, adapted to slices.
pub type AtState<T, R> = fn(&[T], &[T], &[T]) -> R;

use tendyn_core::distribution::Status;

include!(concat!(env!("OUT_DIR"), "/mechanisms.rs"));
