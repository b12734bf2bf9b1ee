//! Identification of the base parameters ([`crate::base_parameters`]) from measured motion:
//! ordinary least squares on `Q − Q₀ = Y_base(q, q̇, q̈) π_base`, stacked over the samples.
//!
//! Each sample is a state and the generalized forces the actuators delivered there, which
//! [`crate::Data::actuator_forces`] gives from measured motor torques and tendon tensions
//! (`Σ motor columns · τ + A(q, q̇) T`). With `N` rows (samples × joints), `r` base
//! parameters and residual `e`, the estimates come with the usual standard deviations
//! `σ_i = √(s² [(YᵀY)⁻¹]_ii)`, `s² = ‖e‖² / (N − r)`: the spread of the estimate if the
//! residual is white noise of equal variance on every joint.
//!
//! The columns are scaled to unit norm before the solve (by SVD), so that the conditioning
//! reported is that of the excitation, not of the parameters' units. No constraint of
//! physical consistency (positive masses, inertias that satisfy the triangle inequality) is
//! imposed: base parameters are combinations, and mapping them back to bodies is the
//! caller's choice.

use crate::base_parameters::BaseParameters;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::regressor;
use crate::Data;
use nalgebra::{DMatrix, DVector};

/// One measurement: a state and the generalized forces delivered at it.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Joint angles (rad).
    pub q: Vec<f64>,
    /// Joint velocities (rad/s).
    pub qd: Vec<f64>,
    /// Joint accelerations (rad/s²).
    pub qdd: Vec<f64>,
    /// Generalized forces the actuators delivered (N·m), per joint.
    pub forces: Vec<f64>,
}

/// The least-squares estimate of every base parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Identification {
    /// The estimates, in the order of [`BaseParameters::groups`].
    pub estimates: Vec<f64>,
    /// Their standard deviations (see the module documentation).
    pub standard_deviations: Vec<f64>,
    /// Samples used.
    pub samples: usize,
    /// `√(‖e‖² / N)` (N·m): the residual's root mean square per row.
    pub residual_rms: f64,
    /// `‖e‖ / ‖Q − Q₀‖`: what the model leaves unexplained.
    pub relative_residual: f64,
    /// The condition number of the stacked regressor with unit-norm columns: how well
    /// the motion excites the base parameters (below about 1e3 is good).
    pub condition: f64,
}

/// Estimates `base`'s parameters of `model` from `samples`.
pub fn identify(
    model: &Model<f64>,
    base: &BaseParameters,
    samples: &[Sample],
) -> Result<Identification> {
    let (y, target) = stack(model, base, samples)?;
    least_squares(model, base, y, &target, samples.len())
}

/// The base regressor and `Q − Q₀` of every sample, stacked: `samples × n` rows.
pub(crate) fn stack(
    model: &Model<f64>,
    base: &BaseParameters,
    samples: &[Sample],
) -> Result<(DMatrix<f64>, DVector<f64>)> {
    let (n, r) = (model.dof(), base.groups.len());
    if base.parameters != regressor::parameters(model) {
        return Err(Error::State(format!(
            "these base parameters were found for another mechanism than `{}`: make them with \
             `BaseParameters::of(&model)`",
            model.name()
        )));
    }
    if r == 0 {
        return Err(Error::State(format!(
            "`{}` has no base parameters: no mass property acts on its generalized forces",
            model.name()
        )));
    }
    let rows = samples.len() * n;
    if rows <= r {
        return Err(Error::State(format!(
            "{} samples of {n} joints give {rows} equations for {r} base parameters: \
             record more than {} samples",
            samples.len(),
            r / n.max(1)
        )));
    }
    let mut y = DMatrix::<f64>::zeros(rows, r);
    let mut target = DVector::<f64>::zeros(rows);
    let mut data = Data::new(model);
    for (s, sample) in samples.iter().enumerate() {
        let at = |e: Error| Error::State(format!("sample {}: {e}", s + 1));
        model.check_state("forces", &sample.forces).map_err(at)?;
        let reg = data
            .regressor(model, &sample.q, &sample.qd, &sample.qdd)
            .map_err(at)?;
        let reduced = base.reduce(&reg.y);
        for k in 0..n {
            for c in 0..r {
                y[(s * n + k, c)] = reduced[k * r + c];
            }
            target[s * n + k] = sample.forces[k] - reg.known[k];
        }
    }
    Ok((y, target))
}

/// Least squares on the stack, columns scaled to unit norm; an error when the samples do
/// not excite every base parameter.
pub(crate) fn least_squares(
    model: &Model<f64>,
    base: &BaseParameters,
    mut y: DMatrix<f64>,
    target: &DVector<f64>,
    samples: usize,
) -> Result<Identification> {
    let (rows, r) = y.shape();
    let norms: Vec<f64> = (0..r).map(|c| y.column(c).norm()).collect();
    if let Some(c) = norms.iter().position(|&x| x == 0.0) {
        let names = base.names(model);
        return Err(Error::State(format!(
            "the samples do not excite the base parameter `{}`: record motion that moves it",
            names[c]
        )));
    }
    for (c, norm) in norms.iter().enumerate() {
        y.column_mut(c).scale_mut(1.0 / norm);
    }
    let svd = y.clone().svd(true, true);
    let (largest, smallest) = (svd.singular_values.max(), svd.singular_values.min());
    let condition = largest / smallest;
    if condition.is_nan() || condition >= 1e12 {
        return Err(Error::State(format!(
            "the samples excite the base parameters too unevenly to tell them apart \
             (condition number {condition:.1e}): record richer motion, every joint moving \
             over its range with varied speeds and accelerations"
        )));
    }
    let solution = svd
        .solve(target, 0.0)
        .map_err(|e| Error::State(format!("least squares: {e}")))?;
    let residual = target - &y * &solution;
    let rss = residual.norm_squared();
    let variance = rss / (rows - r) as f64;
    // (SᵀS)⁻¹ = V Σ⁻² Vᵀ for the scaled columns; unscaled, divide by the norms twice.
    let v_t = svd.v_t.as_ref().expect("V was asked for");
    let estimates: Vec<f64> = (0..r).map(|c| solution[c] / norms[c]).collect();
    let standard_deviations = (0..r)
        .map(|c| {
            let diagonal: f64 = (0..r)
                .map(|k| (v_t[(k, c)] / svd.singular_values[k]).powi(2))
                .sum();
            (variance * diagonal).sqrt() / norms[c]
        })
        .collect();
    Ok(Identification {
        estimates,
        standard_deviations,
        samples,
        residual_rms: (rss / rows as f64).sqrt(),
        relative_residual: rss.sqrt() / target.norm().max(f64::MIN_POSITIVE),
        condition,
    })
}
