//! The base parameters: the combinations of the regressor's parameters
//! ([`crate::regressor`]) that the generalized forces can tell apart, and so the ones an
//! identification can estimate.
//!
//! Many parameters never change `Q` (a link's mass on its own joint axis, the inertia of a
//! pulley about an axis it never turns about), and many change it only together (a
//! pulley's `zz` acts with its coupling's square wherever its carrier's does). A base is
//! found from the structure numerically, as OpenSYMORO's rules would give it symbolically
//! for a rigid chain:
//!
//! 1. `Y` is computed in double-double and stacked over deterministic, well-spread states (a Kronecker sequence over `q`
//!    in `[−π, π]`, `q̇` in `[−3, 3]`, `q̈` in `[−10, 10]`), at least three rows per
//!    parameter.
//! 2. Each column is brought to common units with the mechanism's length `L` (the largest
//!    distance of a body origin from the base at `q = 0`, at least 1 mm): mass columns
//!    divided by `L²`, first moments by `L`, so that every column multiplies a parameter
//!    in the inertia's units (`m L²`, `m c L`) and all have the units of `Q` per kg·m².
//! 3. Columns are taken body by body (every body after its parent), each body's inertia
//!    (`zz` first), then its first moment, mass and friction. A column whose norm is below
//!    [`ZERO`] of the largest is **unidentifiable**: it does not act on `Q`. A column whose
//!    part outside the span of the columns kept so far is below [`DEPENDENT`] of its norm is
//!    **merged**; else it is **kept** as a base parameter. Taking parents first keeps the
//!    parameters nearest the base and folds those further out into them (a child link's
//!    mass into its parent's first moment and inertia, a pulley's `zz` into its carrier's),
//!    the grouping of the rigid-chain literature.
//! 4. The merged columns are written in the kept ones by least squares over the stack:
//!    `Y_merged = Y_base B`. Base parameter `i` is `π_i + Σ_d B_id π_d`.
//!
//! The dependencies are structural (identities of the kinematics, for every state), so
//! `Y_base π_base + Q₀ = Q` holds at every state, not only the sampled ones: the tests check
//! it at fresh states, and check the count of base parameters against the rank of the
//! stack from its singular values.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::regressor::{self, Parameter, Quantity};
use crate::{Data, DoubleDouble};
use nalgebra::DMatrix;

/// A column whose norm (in those common units) is below this fraction of the largest acts on no
/// generalized force: its values are the double-double round-off of an exact zero.
pub const ZERO: f64 = 1e-20;

/// A column whose part outside the kept columns' span is below this fraction of its norm is
/// a combination of them. Round-off leaves about `1e-15` of a dependent column; an
/// independent one keeps far more than this.
pub const DEPENDENT: f64 = 1e-8;

/// A merged column's part along a kept one below this fraction of its norm is round-off
/// of the least-squares fit (about `1e-15` here), not a grouping.
pub const NEGLIGIBLE: f64 = 1e-12;

/// The base parameters of a mechanism.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParameters {
    /// The regressor's parameters (its columns).
    pub parameters: Vec<Parameter>,
    /// One per base parameter, in the order the columns were considered (see `scan_order`).
    pub groups: Vec<Group>,
    /// Columns that act on no generalized force.
    pub unidentifiable: Vec<usize>,
}

/// A base parameter: a kept column, and the merged ones folded into it.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The regressor column it keeps.
    pub column: usize,
    /// `(column, coefficient)`: the base parameter is `π_column + Σ coefficient · π_merged`.
    pub merged: Vec<(usize, f64)>,
}

impl BaseParameters {
    /// The base parameters of `model` (see the module documentation).
    pub fn of(model: &Model<f64>) -> Result<Self> {
        let parameters = regressor::parameters(model);
        let (n, p) = (model.dof(), parameters.len());
        if n == 0 {
            return Err(Error::State(
                "a mechanism without joints has no regressor".into(),
            ));
        }
        let states = (3 * p).div_ceil(n).max(8);
        let rows = states * n;
        let mut stack = DMatrix::<f64>::zeros(rows, p);
        // In double-double, so that a column no motion excites is round-off of 1e-32, far
        // below any column that acts (in f64 a spinning pulley's frame leaves 1e-16 of one
        // in the columns of its first moment, too near the smallest real ones).
        let reference = model.cast_numeric::<DoubleDouble>();
        let mut data = Data::new(&reference);
        let mut sequence = Kronecker::new(3 * n);
        for s in 0..states {
            let x = sequence.next_point();
            let range = |i: usize, half: f64| DoubleDouble::from((2.0 * x[i] - 1.0) * half);
            let q: Vec<_> = (0..n).map(|j| range(j, std::f64::consts::PI)).collect();
            let qd: Vec<_> = (0..n).map(|j| range(n + j, 3.0)).collect();
            let qdd: Vec<_> = (0..n).map(|j| range(2 * n + j, 10.0)).collect();
            let r = data.regressor(&reference, &q, &qd, &qdd)?;
            for k in 0..n {
                for c in 0..p {
                    stack[(s * n + k, c)] = r.y[k * p + c].to_f64();
                }
            }
        }
        let length = characteristic_length(model);
        let scale: Vec<f64> = (parameters.iter())
            .map(|x| 1.0 / dimension(x, length))
            .collect();
        for (c, s) in scale.iter().enumerate() {
            stack.column_mut(c).scale_mut(*s);
        }
        let norms: Vec<f64> = (0..p).map(|c| stack.column(c).norm()).collect();
        let largest = norms.iter().fold(0.0f64, |m, &x| m.max(x));
        // Modified Gram-Schmidt over the kept columns, twice ("twice is enough").
        let mut basis: Vec<nalgebra::DVector<f64>> = Vec::new();
        let (mut kept, mut merged, mut unidentifiable) = (Vec::new(), Vec::new(), Vec::new());
        for c in scan_order(&parameters) {
            if norms[c] <= ZERO * largest {
                unidentifiable.push(c);
                continue;
            }
            let mut v = stack.column(c).into_owned();
            for _ in 0..2 {
                for b in &basis {
                    let along = b.dot(&v);
                    v.axpy(-along, b, 1.0);
                }
            }
            let outside = v.norm();
            if outside <= DEPENDENT * norms[c] {
                merged.push(c);
            } else {
                basis.push(v / outside);
                kept.push(c);
            }
        }
        // Y_merged = Y_base B, least squares over the stack (exact up to round-off).
        // The kept columns at unit norm, so that the fit's conditioning is that of their
        // directions, not of their sizes (a link's `zz` about a tilted axis can be 1e-5 of
        // its `yy`); `B` is scaled back row by row.
        let mut base = stack.select_columns(&kept);
        for (g, &c) in kept.iter().enumerate() {
            base.column_mut(g).scale_mut(1.0 / norms[c]);
        }
        let dependent = stack.select_columns(&merged);
        let mut coefficients = if kept.is_empty() || merged.is_empty() {
            DMatrix::zeros(kept.len(), merged.len())
        } else {
            base.svd(true, true)
                .solve(&dependent, 0.0)
                .map_err(|e| Error::State(format!("base parameters: {e}")))?
        };
        for (g, &c) in kept.iter().enumerate() {
            coefficients.row_mut(g).scale_mut(1.0 / norms[c]);
        }
        let mut groups: Vec<Group> = kept
            .iter()
            .map(|&column| Group {
                column,
                merged: Vec::new(),
            })
            .collect();
        for (d, &column) in merged.iter().enumerate() {
            for (g, group) in groups.iter_mut().enumerate() {
                let scaled = coefficients[(g, d)];
                // A part of round-off size belongs to no grouping rule.
                if scaled.abs() * norms[group.column] > NEGLIGIBLE * norms[column] {
                    // Back to the parameters' own units: `Y_d s_d = Σ_g B_gd Y_g s_g`, so
                    // `π_d` joins group `g` with `B_gd s_g / s_d`.
                    let b = scaled * scale[group.column] / scale[column];
                    group.merged.push((column, b));
                }
            }
        }
        Ok(BaseParameters {
            parameters,
            groups,
            unidentifiable,
        })
    }

    /// The base parameters' values for the regressor's parameters `pi`
    /// ([`regressor::values`] for the model's own).
    pub fn values(&self, pi: &[f64]) -> Vec<f64> {
        self.groups
            .iter()
            .map(|g| pi[g.column] + g.merged.iter().map(|&(c, b)| b * pi[c]).sum::<f64>())
            .collect()
    }

    /// The base regressor: the kept columns of a regressor `y` (`n` rows of
    /// `parameters.len()`), `n` rows of `groups.len()`.
    pub fn reduce(&self, y: &[f64]) -> Vec<f64> {
        let p = self.parameters.len();
        y.chunks_exact(p.max(1))
            .flat_map(|row| self.groups.iter().map(move |g| row[g.column]))
            .collect()
    }

    /// Each base parameter's name: its kept parameter and what is merged into it, e.g.
    /// `link1.zz + 0.0025 link2.m + 4 pulley1.zz`.
    pub fn names(&self, model: &Model<f64>) -> Vec<String> {
        self.groups
            .iter()
            .map(|g| {
                let mut name = self.parameters[g.column].name(model);
                for &(c, b) in &g.merged {
                    let sign = if b < 0.0 { '-' } else { '+' };
                    let other = self.parameters[c].name(model);
                    let factor = match significant(b.abs()) {
                        one if one == "1" => String::new(),
                        other => format!("{other} "),
                    };
                    name.push_str(&format!(" {sign} {factor}{other}"));
                }
                name
            })
            .collect()
    }
}

/// The order columns are considered in: bodies in the model's order (parents first), and
/// within a body the inertia (`zz` first: the moment about a joint axis), then the first
/// moment, then the mass, then friction. What comes first is kept and what follows
/// merges into it, so a group reads as an inertia plus masses times squared lengths, as the
/// rigid-chain literature writes them (`ZZR₁ = ZZ₁ + a₂² M₂`).
fn scan_order(parameters: &[Parameter]) -> Vec<usize> {
    const INERTIAL: [usize; 10] = [9, 4, 7, 5, 6, 8, 1, 2, 3, 0];
    let rank = |x: &Parameter| match x.quantity {
        Quantity::Inertial(i) => INERTIAL.iter().position(|&j| j == i).unwrap_or(i),
        Quantity::Coulomb => 10,
        Quantity::Viscous => 11,
    };
    let mut order: Vec<usize> = (0..parameters.len()).collect();
    order.sort_by_key(|&c| (parameters[c].body, rank(&parameters[c])));
    order
}

/// What a parameter is multiplied by to be in the inertia's units (kg·m²): `L²` for a
/// mass, `L` for a first moment (its column is divided by as much).
pub(crate) fn dimension(parameter: &Parameter, length: f64) -> f64 {
    match parameter.quantity {
        Quantity::Inertial(0) => length * length,
        Quantity::Inertial(1..=3) => length,
        _ => 1.0,
    }
}

/// `x` with six significant digits and no trailing zeros.
fn significant(x: f64) -> String {
    let s = format!("{x:.5e}");
    let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (-4..6).contains(&exponent) {
        let v: f64 = format!("{mantissa}e{exponent}").parse().unwrap_or(x);
        format!("{v}")
    } else {
        format!("{mantissa}e{exponent}")
    }
}

/// The largest distance of a body origin from the base at `q = 0` (at least 1 mm): the
/// length that makes the regressor's columns commensurable.
pub(crate) fn characteristic_length(model: &Model<f64>) -> f64 {
    let bodies = model.bodies();
    let mut origin: Vec<nalgebra::Vector3<f64>> = Vec::with_capacity(bodies.len());
    let mut rotation: Vec<nalgebra::Matrix3<f64>> = Vec::with_capacity(bodies.len());
    let mut longest = 1e-3f64;
    for b in bodies {
        let (p0, r0) = match b.parent {
            Some(p) => (origin[p], rotation[p]),
            None => (nalgebra::Vector3::zeros(), nalgebra::Matrix3::identity()),
        };
        let frame = b.pre.compose(&b.post);
        let t = frame.translation;
        let r = nalgebra::Matrix3::from_fn(|i, j| frame.rotation.rows[i][j]);
        let o = p0 + r0 * nalgebra::Vector3::new(t.x, t.y, t.z);
        longest = longest.max(o.norm());
        origin.push(o);
        rotation.push(r0 * r);
    }
    longest
}

/// The Kronecker (additive recurrence) sequence `x_i = frac(i α)`, `α_j = frac(√prime_j)`:
/// deterministic points spread evenly over the unit cube, so that the stacked regressor
/// sees every joint in every part of its range.
struct Kronecker {
    alpha: Vec<f64>,
    index: u64,
}

impl Kronecker {
    fn new(dimension: usize) -> Self {
        let mut primes = Vec::new();
        let mut candidate = 2u64;
        while primes.len() < dimension {
            if primes.iter().all(|&p| !candidate.is_multiple_of(p)) {
                primes.push(candidate);
            }
            candidate += 1;
        }
        Kronecker {
            alpha: primes.iter().map(|&p| (p as f64).sqrt().fract()).collect(),
            index: 0,
        }
    }

    fn next_point(&mut self) -> Vec<f64> {
        self.index += 1;
        let i = self.index as f64;
        self.alpha.iter().map(|a| (i * a).fract()).collect()
    }
}
