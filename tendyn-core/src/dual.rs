//! Dual numbers: a value and its derivative along one direction, carried through the one
//! generic recursion to differentiate it exactly (forward-mode automatic differentiation).
//!
//! `Dual<f64>` gives the runtime solver's derivatives; `Dual<Sym>` runs the same code on the
//! code generator's expressions, so generated derivatives are a trace of the same
//! arithmetic, their values shared with the function's own by the graph's hash-consing.
//!
//! The two value-dependent operations differentiate as the branch they take: `max(a, b)`
//! as `a` where `a > b`, as `b` where `a < b`, and as the mean of both where they are equal
//! (a subgradient: the derivative does not exist there); `sign_outside_or` is the
//! constant ±1 outside its band, with derivative zero, and its `otherwise` within it
//! (where it jumps, it has no derivative). `sqrt` at exactly zero
//! has no derivative: the tangent comes out infinite or NaN there, and the runtime's
//! checked evaluators report it as a non-finite result rather than return it.

use crate::real::{Numeric, Real};
use core::ops::{Add, Div, Mul, Neg, Sub};

/// `value + ε · tangent` with `ε² = 0`.
#[derive(Clone, Copy, Debug)]
pub struct Dual<T> {
    /// The value.
    pub value: T,
    /// The derivative along the seeded direction.
    pub tangent: T,
}

impl<T: Real> Dual<T> {
    /// A constant: zero derivative.
    pub fn constant(value: T) -> Self {
        Dual {
            value,
            tangent: T::zero(),
        }
    }

    /// The seeded variable: derivative one.
    pub fn variable(value: T) -> Self {
        Dual {
            value,
            tangent: T::one(),
        }
    }

    /// `value` with derivative `tangent`.
    pub fn new(value: T, tangent: T) -> Self {
        Dual { value, tangent }
    }
}

impl<T: Real> Add for Dual<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Dual::new(self.value + o.value, self.tangent + o.tangent)
    }
}

impl<T: Real> Sub for Dual<T> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Dual::new(self.value - o.value, self.tangent - o.tangent)
    }
}

impl<T: Real> Mul for Dual<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Dual::new(
            self.value * o.value,
            self.tangent * o.value + self.value * o.tangent,
        )
    }
}

impl<T: Real> Div for Dual<T> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let q = self.value / o.value;
        Dual::new(q, (self.tangent - q * o.tangent) / o.value)
    }
}

impl<T: Real> Neg for Dual<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Dual::new(-self.value, -self.tangent)
    }
}

impl<T: Real> Real for Dual<T> {
    fn from_f64(x: f64) -> Self {
        Dual::constant(T::from_f64(x))
    }
    fn sin(self) -> Self {
        let (s, c) = self.value.sin_cos();
        Dual::new(s, c * self.tangent)
    }
    fn cos(self) -> Self {
        let (s, c) = self.value.sin_cos();
        Dual::new(c, -(s * self.tangent))
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.value.sin_cos();
        (
            Dual::new(s, c * self.tangent),
            Dual::new(c, -(s * self.tangent)),
        )
    }
    fn sin_cos_many(angles: &[Self], out: &mut [(Self, Self)]) {
        // The values as the plain scalar takes several angles (an `f64` by its own routine,
        // `crate::trigonometry`), so that a dual pass's value is the plain pass's to the bit.
        const BLOCK: usize = 8;
        for (a, o) in angles.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
            let n = a.len().min(o.len());
            let mut values = [T::zero(); BLOCK];
            let mut turns = [(T::zero(), T::zero()); BLOCK];
            for (v, x) in values.iter_mut().zip(a) {
                *v = x.value;
            }
            T::sin_cos_many(&values[..n], &mut turns[..n]);
            for ((o, x), &(s, c)) in o.iter_mut().zip(a).zip(&turns[..n]) {
                *o = (Dual::new(s, c * x.tangent), Dual::new(c, -(s * x.tangent)));
            }
        }
    }
    fn sqrt(self) -> Self {
        let r = self.value.sqrt();
        Dual::new(r, self.tangent / (r + r))
    }
    fn max(self, other: Self) -> Self {
        // s = sign(a − b) (0 where equal): the tangent of the branch taken, or the mean.
        let s = (self.value - other.value).sign_outside(T::zero());
        let half = T::from_f64(0.5);
        let mean = (self.tangent + other.tangent) * half;
        let difference = (self.tangent - other.tangent) * half;
        Dual::new(self.value.max(other.value), mean + s * difference)
    }
    fn sign_outside_or(self, band: Self, otherwise: Self) -> Self {
        // ±1 outside the band (a constant), `otherwise` with its derivative within it.
        let moving = self.value.sign_outside(band.value);
        Dual::new(
            self.value.sign_outside_or(band.value, otherwise.value),
            (T::one() - moving * moving) * otherwise.tangent,
        )
    }
    fn select_outside(self, band: Self, above: Self, below: Self, otherwise: Self) -> Self {
        // The value taken, with its derivative: the choice itself is constant almost
        // everywhere (a step in `self`, whose derivative is taken as zero, as a sign's).
        let (b, v) = (band.value, self.value);
        Dual::new(
            v.select_outside(b, above.value, below.value, otherwise.value),
            v.select_outside(b, above.tangent, below.tangent, otherwise.tangent),
        )
    }
    fn tanh(self) -> Self {
        let t = self.value.tanh();
        Dual::new(t, (T::one() - t * t) * self.tangent)
    }
    fn exp(self) -> Self {
        let e = self.value.exp();
        Dual::new(e, e * self.tangent)
    }
}

/// A dual number compares as its value (the derivative does not order it).
impl<T: Numeric> PartialEq for Dual<T> {
    fn eq(&self, o: &Self) -> bool {
        self.value == o.value
    }
}

impl<T: Numeric> PartialOrd for Dual<T> {
    fn partial_cmp(&self, o: &Self) -> Option<core::cmp::Ordering> {
        self.value.partial_cmp(&o.value)
    }
}

impl<T: Numeric> Numeric for Dual<T> {
    fn to_f64(self) -> f64 {
        self.value.to_f64()
    }
    fn abs(self) -> Self {
        if self.value < T::zero() {
            -self
        } else {
            self
        }
    }
    fn is_finite(self) -> bool {
        self.value.is_finite() && self.tangent.is_finite()
    }
    fn unit_roundoff() -> f64 {
        T::unit_roundoff()
    }
}

/// What a generated `generalized_forces_derivatives` returns: `value` (`[T; n]`) and its
/// Jacobians `d_q`, `d_qd` (`[[T; n]; n]`, `d_q[i][k] = ∂value_i/∂q_k`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateJacobians<V, J> {
    /// The function's value.
    pub value: V,
    /// `∂value/∂q`, row by row.
    pub d_q: J,
    /// `∂value/∂q̇`, row by row.
    pub d_qd: J,
}

/// What a generated `forward_dynamics_derivatives` returns: `value` (`q̈`, `[T; n]`),
/// `d_q`, `d_qd` (`[[T; n]; n]`) and `d_u` (`[[T; m]; n]`, `u` the motor torques then the
/// tendon tensions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForwardJacobians<V, J, U> {
    /// `q̈`.
    pub value: V,
    /// `∂q̈/∂q`, row by row.
    pub d_q: J,
    /// `∂q̈/∂q̇`, row by row.
    pub d_qd: J,
    /// `∂q̈/∂u`, row by row.
    pub d_u: U,
}

/// What a generated `actuation_derivatives` returns: `value` (`[T; m]`, the motor torques
/// then the tendon tensions that `actuation` returns) and its Jacobians `d_q`, `d_qd`,
/// `d_qdd` (`[[T; n]; m]`, `d_q[i][k] = ∂value_i/∂q_k`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActuationJacobians<V, J> {
    /// The motor torques, then the tendon tensions.
    pub value: V,
    /// `∂value/∂q`, row by row.
    pub d_q: J,
    /// `∂value/∂q̇`, row by row.
    pub d_qd: J,
    /// `∂value/∂q̈`, row by row.
    pub d_qdd: J,
}
