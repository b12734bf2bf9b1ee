//! The scalar the recursion is written in.
//!
//! [`Real`] asks only for what a symbolic expression can honestly provide as well: field
//! arithmetic, `sin`/`cos`, `sqrt`, `tanh`, `exp`, constants and two value-dependent hooks,
//! [`Real::max`] (the tension floor of a redundant routing) and [`Real::sign_outside_or`]
//! (the direction friction opposes). The code generator runs the very same recursion on
//! its expression type, so nothing here may compare or branch on values.
//!
//! [`Numeric`] adds what only numbers have (ordering, finiteness, conversion back to `f64`);
//! the validation-time linear algebra and the multi-dimensional tension distribution need it.

use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A scalar the generic recursion runs on: `f32`, `f64`, [`crate::DoubleDouble`], or the
/// symbolic expression handle of `tendyn-codegen`.
pub trait Real:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + 'static
{
    /// The nearest value of this scalar to `x` (exact for the types that hold an `f64`).
    fn from_f64(x: f64) -> Self;
    /// The sine of an angle in radians.
    fn sin(self) -> Self;
    /// The cosine of an angle in radians.
    fn cos(self) -> Self;
    /// The non-negative square root.
    fn sqrt(self) -> Self;
    /// The larger of the two. The only value-dependent operation the recursion uses;
    /// a symbolic scalar maps it to a select node.
    fn max(self, other: Self) -> Self;
    /// `+1` where `self > band`, `−1` where `self < −band`, `otherwise` in between (a rate
    /// within `band` of rest): the direction of friction (`crate::friction`), whose
    /// `otherwise` is the direction of impending motion. A symbolic scalar maps it to a
    /// select node.
    fn sign_outside_or(self, band: Self, otherwise: Self) -> Self;
    /// [`Real::sign_outside_or`] with `0` in the band.
    fn sign_outside(self, band: Self) -> Self {
        self.sign_outside_or(band, Self::zero())
    }
    /// `above` where `self > band`, `below` where `self < −band`, `otherwise` in between:
    /// [`Real::sign_outside_or`] choosing among three values, so that a guide's capstan
    /// factor `e^{−σμβ}` of a constant wrap angle is one of three numbers fixed at
    /// generation, not an `exp` at run time (`crate::friction`). A symbolic scalar maps it
    /// to a select node.
    fn select_outside(self, band: Self, above: Self, below: Self, otherwise: Self) -> Self;
    /// The hyperbolic tangent: the smoothed friction law.
    fn tanh(self) -> Self;
    /// `e^self`: the capstan law of a guide, `T_high = T_low e^{μβ}`.
    fn exp(self) -> Self;

    /// `self · a + b`: how generated code writes a product added to a sum. A primitive
    /// float rounds it once (a fused multiply-add instruction) where the target has one
    /// (`target_feature = "fma"`, with `std`); every other scalar, and every other target,
    /// computes `self * a + b` as written, so without FMA generated code rounds exactly as
    /// its unfused form.
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    /// `0`.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// `1`.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// Sine and cosine of one angle; a symbolic scalar computes them together.
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// `out[i] = angles[i].sin_cos()`, over the shorter of the two: every angle of a
    /// recursion at once, which an `f64` computes several at a time
    /// ([`crate::trigonometry`]); a symbolic scalar records them one after another.
    fn sin_cos_many(angles: &[Self], out: &mut [(Self, Self)]) {
        for (o, a) in out.iter_mut().zip(angles) {
            *o = a.sin_cos();
        }
    }
    /// [`Real::sin_cos_many`] of an array: how generated code takes the sines and cosines
    /// of all its angles in one call, on targets with AVX2.
    fn sin_cos_array<const N: usize>(angles: [Self; N]) -> [(Self, Self); N] {
        let mut out = [(Self::zero(), Self::zero()); N];
        Self::sin_cos_many(&angles, &mut out);
        out
    }
}

/// A [`Real`] whose values are expressions of named inputs, not numbers: the expression
/// handle of `tendyn-codegen`. Nothing about such a value can be checked, so a model takes
/// symbols as its parameters only through [`Model::symbolic`](crate::model::Model::symbolic)
/// (numbers go through the checked `with_parameters`).
pub trait Symbolic: Real {}

/// A [`Real`] that is a number: it can be ordered, tested and converted back to `f64`.
pub trait Numeric: Real + PartialOrd {
    /// The value as an `f64`, rounded to it (for a double-double, its high word).
    fn to_f64(self) -> f64;
    /// The absolute value.
    fn abs(self) -> Self;
    /// Neither infinite nor NaN.
    fn is_finite(self) -> bool;
    /// Unit round-off of the type (half the distance from 1 to the next number).
    fn unit_roundoff() -> f64;
}

/// Sine and cosine of a primitive float: the library's (`std`, or `libm` without it), and
/// for `f64` several angles at a time by [`crate::trigonometry`].
macro_rules! primitive_trigonometry {
    (library, $t:ty, $sin:ident, $cos:ident) => {
        #[cfg(feature = "std")]
        fn sin(self) -> Self {
            <$t>::sin(self)
        }
        #[cfg(feature = "std")]
        fn cos(self) -> Self {
            <$t>::cos(self)
        }
        #[cfg(feature = "std")]
        fn sin_cos(self) -> (Self, Self) {
            <$t>::sin_cos(self)
        }
        #[cfg(not(feature = "std"))]
        fn sin(self) -> Self {
            libm::$sin(self)
        }
        #[cfg(not(feature = "std"))]
        fn cos(self) -> Self {
            libm::$cos(self)
        }
    };
    (trigonometry, $t:ty, $sin:ident, $cos:ident) => {
        // One angle: the library's, as fast where called alone (and a call inlines less
        // into long generated functions); several: `trigonometry`'s.
        primitive_trigonometry!(library, $t, $sin, $cos);
        #[cfg(not(feature = "std"))]
        fn sin_cos(self) -> (Self, Self) {
            libm::sincos(self)
        }
        fn sin_cos_many(angles: &[Self], out: &mut [(Self, Self)]) {
            crate::trigonometry::sin_cos_many(angles, out)
        }
        fn sin_cos_array<const N: usize>(angles: [Self; N]) -> [(Self, Self); N] {
            crate::trigonometry::sin_cos_array(angles)
        }
    };
}

macro_rules! primitive_real {
    ($t:ty, $trigonometry:ident, $sin:ident, $cos:ident, $sqrt:ident, $tanh:ident, $exp:ident) => {
        impl Real for $t {
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            primitive_trigonometry!($trigonometry, $t, $sin, $cos);
            #[cfg(feature = "std")]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[cfg(not(feature = "std"))]
            fn sqrt(self) -> Self {
                libm::$sqrt(self)
            }
            #[cfg(feature = "std")]
            fn tanh(self) -> Self {
                <$t>::tanh(self)
            }
            #[cfg(not(feature = "std"))]
            fn tanh(self) -> Self {
                libm::$tanh(self)
            }
            #[cfg(feature = "std")]
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            #[cfg(not(feature = "std"))]
            fn exp(self) -> Self {
                libm::$exp(self)
            }
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            // Without the instruction, `<$t>::mul_add` is a slow software routine: fused
            // only where the target has it (see the trait's documentation).
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                #[cfg(all(feature = "std", target_feature = "fma"))]
                {
                    <$t>::mul_add(self, a, b)
                }
                #[cfg(not(all(feature = "std", target_feature = "fma")))]
                {
                    self * a + b
                }
            }
            fn sign_outside_or(self, band: Self, otherwise: Self) -> Self {
                self.select_outside(band, 1.0, -1.0, otherwise)
            }
            fn select_outside(self, band: Self, above: Self, below: Self, otherwise: Self) -> Self {
                if self > band {
                    above
                } else if self < -band {
                    below
                } else {
                    otherwise
                }
            }
        }
        impl Numeric for $t {
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            fn unit_roundoff() -> f64 {
                (<$t>::EPSILON as f64) / 2.0
            }
        }
    };
}
primitive_real!(f32, library, sinf, cosf, sqrtf, tanhf, expf);
primitive_real!(f64, trigonometry, sin, cos, sqrt, tanh, exp);
