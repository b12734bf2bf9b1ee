//! `DoubleDouble`: a double-double scalar (an unevaluated sum `hi + lo` of two `f64`,
//! about 106 bits of significand), the *accuracy reference* against which the `f64` and
//! `f32` runs of the recursion are judged.
//!
//! The representation and `+`, `-`, `*` are those of the [`twofloat`] crate (the
//! algorithms of Joldes, Muller and Popescu, 2017, with proven relative error bounds of
//! 3u² for `+`/`-` and 5u² for `*`, u = 2⁻⁵³, u² ≈ 1.2e-32). Everything else that decides
//! accuracy is implemented here, because twofloat 0.8.4 falls short of a reference:
//!
//! - `/`: twofloat's `TwoFloat / TwoFloat` and `f64 / TwoFloat` form `1 − y.hi·(1/y.hi)`
//!   without a fused multiply-add, so they are only `f64`-accurate (`1/3` comes back with a
//!   zero low word; relative error up to 1.1e-16). Here: long division with three
//!   quotient words.
//! - `sin`/`cos`: twofloat's use a degree-15 polynomial and a two-word π/2, good to about
//!   1e-20 relative, 1e-28 absolute at `|x| ~ 1e4`, and with no relative accuracy at all
//!   near the zeros. Here: `k = round(x·2/π)`, `r = x − k·π/2` with π/2 held as five
//!   doubles (≈ 265 bits) and every `k·cᵢ` formed exactly, then the Taylor series through
//!   `r²⁹/29!` (sin) and `r²⁸/28!` (cos) by Horner's rule in double-double on `|r| ≤ π/4`.
//!   This keeps full *relative* accuracy even at the double-double nearest to `kπ`.
//! - `tanh` (the smoothed friction law): twofloat's goes through its `exp`, itself not a
//!   reference. Here: `expm1` by halving to below 2⁻¹⁰, eleven Taylor terms and doubling
//!   back, then `expm1(2|x|) / (expm1(2|x|) + 2)`, with no cancellation near zero.
//! - `sqrt`: twofloat's loses accuracy below about 1e-290 (1e-17 at subnormals). Here: one
//!   Newton step in double-double from the `f64` square root, with exact power-of-two
//!   scaling at both ends of the range.
//! - Comparisons and `max`: twofloat orders every non-finite value, `-inf` included, above
//!   every finite one (`-inf > 1`, `-inf == inf`) and its `max` drops an infinite argument.
//!   Here: the numeric order of `(hi, lo)`, NaN unordered, and `max` ignores only NaN,
//!   like `f64::max`.
//!
//! Measured against mpmath at 50 digits, with the exact value of each computed
//! double-double (about 9 800 arguments for `sin`/`cos`, 2 300 for `sqrt`, 2 500 operand
//! pairs per operator; `tests/double_double.rs` checks a few hundred of them, kept in
//! `tests/data/`):
//!
//! | operation  | arguments                                                   | max rel. error |
//! |------------|-------------------------------------------------------------|----------------|
//! | `sin`      | `\|x\| ≤ 1e4`, `f64` and double-double inputs               | 2.0e-32        |
//! | `cos`      | `\|x\| ≤ 1e4`, `f64` and double-double inputs               | 1.8e-32        |
//! | `sin`, `cos` | within 3e-30 … 1e-10 of `kπ/2`, `k ≤ 6366`; abs. error ≤ 3e-37 | 1.6e-32   |
//! | `sqrt`     | 1e-300 … 1e300, `f64::MAX`, subnormals                      | 2.8e-32        |
//! | `tanh`     | 12 arguments, 1e-20 … 35 and their negatives (60 digits)     | ≤ 1e-30 (tested) |
//! | `+`, `-`   | random pairs 2⁻⁶⁰ … 2⁶⁰, and cancelling pairs               | 1.4e-32        |
//! | `*`        | same                                                        | 3.6e-32        |
//! | `/`        | same                                                        | 1.4e-32        |
//! | mixed with `f64` | `+`, `-`, `*`, `/` with one `f64` operand             | 1.4e-32        |
//!
//! Full accuracy of `sin`/`cos` holds for `|x| < 2⁵⁰ ≈ 1.1e15`; beyond that (no angle of a
//! mechanism lives there) they fall back to `f64` accuracy. Non-finite arguments give NaN
//! and no operation panics. Division by zero gives `±inf` as in `f64`, but an overflowing
//! `+`, `-` or `*` may give NaN rather than `±inf` (twofloat); [`Numeric::is_finite`]
//! reports either.

use core::cmp::Ordering;
use core::f64::consts::FRAC_PI_2;
use core::fmt;
use core::iter::{Product, Sum};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use twofloat::TwoFloat;

use crate::real::{Numeric, Real};

/// A double-double number: the unevaluated sum of two non-overlapping `f64` words,
/// about 106 bits of significand. See the module documentation for its accuracy.
#[derive(Clone, Copy, Debug, Default)]
pub struct DoubleDouble(pub TwoFloat);

impl DoubleDouble {
    /// Zero.
    pub const ZERO: Self = Self(TwoFloat::from_f64(0.0));
    /// One.
    pub const ONE: Self = Self(TwoFloat::from_f64(1.0));
    /// π to double-double precision.
    pub const PI: Self = Self(twofloat::consts::PI);
    /// π/2 to double-double precision.
    pub const FRAC_PI_2: Self = Self(twofloat::consts::FRAC_PI_2);

    /// The value `hi + lo`, renormalised exactly: any two words are accepted, in any
    /// order of magnitude (a non-finite sum gives that sum with a zero low word).
    pub fn from_parts(hi: f64, lo: f64) -> Self {
        let sum = hi + lo;
        if sum.is_finite() {
            Self(TwoFloat::new_add(hi, lo))
        } else {
            Self(TwoFloat::from(sum))
        }
    }

    /// The high word: the `f64` nearest to the value.
    pub fn hi(self) -> f64 {
        self.0.hi()
    }

    /// The low word: the remainder `value − hi`.
    pub fn lo(self) -> f64 {
        self.0.lo()
    }

    /// The `f64` nearest to the value (the high word).
    pub fn to_f64(self) -> f64 {
        self.0.hi()
    }

    /// `true` if the value is NaN: the high word is, or the low word is while the high
    /// word is finite (an infinite high word makes the value infinite).
    pub fn is_nan(self) -> bool {
        let (hi, lo) = (self.0.hi(), self.0.lo());
        hi.is_nan() || (hi.is_finite() && lo.is_nan())
    }
}

impl From<f64> for DoubleDouble {
    fn from(x: f64) -> Self {
        Self(TwoFloat::from(x))
    }
}

impl From<TwoFloat> for DoubleDouble {
    fn from(x: TwoFloat) -> Self {
        Self(x)
    }
}

impl From<DoubleDouble> for f64 {
    fn from(x: DoubleDouble) -> Self {
        x.to_f64()
    }
}

// ---------------------------------------------------------------------------------------
// Arithmetic: forwarded to twofloat.

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

macro_rules! forward_binary_op {
    ($Op:ident, $op:ident, $OpAssign:ident, $op_assign:ident) => {
        impl $Op for DoubleDouble {
            type Output = Self;
            fn $op(self, rhs: Self) -> Self {
                Self($Op::$op(self.0, rhs.0))
            }
        }
        impl $Op<f64> for DoubleDouble {
            type Output = Self;
            fn $op(self, rhs: f64) -> Self {
                Self($Op::$op(self.0, rhs))
            }
        }
        impl $Op<DoubleDouble> for f64 {
            type Output = DoubleDouble;
            fn $op(self, rhs: DoubleDouble) -> DoubleDouble {
                DoubleDouble($Op::$op(self, rhs.0))
            }
        }
        impl $OpAssign for DoubleDouble {
            fn $op_assign(&mut self, rhs: Self) {
                *self = $Op::$op(*self, rhs);
            }
        }
        impl $OpAssign<f64> for DoubleDouble {
            fn $op_assign(&mut self, rhs: f64) {
                *self = $Op::$op(*self, rhs);
            }
        }
    };
}

forward_binary_op!(Add, add, AddAssign, add_assign);
forward_binary_op!(Sub, sub, SubAssign, sub_assign);
forward_binary_op!(Mul, mul, MulAssign, mul_assign);

impl Div for DoubleDouble {
    type Output = Self;
    fn div(self, rhs: Self) -> Self {
        Self(dd_div(self.0, rhs.0))
    }
}
impl Div<f64> for DoubleDouble {
    type Output = Self;
    fn div(self, rhs: f64) -> Self {
        Self(dd_div(self.0, TwoFloat::from(rhs)))
    }
}
impl Div<DoubleDouble> for f64 {
    type Output = DoubleDouble;
    fn div(self, rhs: DoubleDouble) -> DoubleDouble {
        DoubleDouble(dd_div(TwoFloat::from(self), rhs.0))
    }
}
impl DivAssign for DoubleDouble {
    fn div_assign(&mut self, rhs: Self) {
        *self = *self / rhs;
    }
}
impl DivAssign<f64> for DoubleDouble {
    fn div_assign(&mut self, rhs: f64) {
        *self = *self / rhs;
    }
}

/// `x / y` by long division: three quotient words, each remainder formed in
/// double-double (measured ≤ 1.4e-32 relative). Not twofloat's `/`, which computes
/// `1 − y.hi·(1/y.hi)` without a fused multiply-add and so is only `f64`-accurate. Like
/// `f64`, a zero divisor gives `±inf` (NaN for `0/0`) and an infinite one gives `±0`.
fn dd_div(x: TwoFloat, y: TwoFloat) -> TwoFloat {
    let q1 = x.hi() / y.hi();
    if !(q1.is_finite() && y.hi().is_finite()) {
        return TwoFloat::from(q1);
    }
    let r = x - y * q1;
    let q2 = r.hi() / y.hi();
    let r = r - y * q2;
    let q3 = r.hi() / y.hi();
    TwoFloat::new_add(q1, q2) + q3
}

impl Sum for DoubleDouble {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::ZERO, Add::add)
    }
}

impl Product for DoubleDouble {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::ONE, Mul::mul)
    }
}

// ---------------------------------------------------------------------------------------
// Comparison: lexicographic on (hi, lo), which is the numeric order for normalised
// pairs; an infinite high word decides alone; NaN is unordered.

impl PartialOrd for DoubleDouble {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        let (a, b) = (self.0, other.0);
        match a.hi().partial_cmp(&b.hi())? {
            Ordering::Equal if a.hi().is_finite() => a.lo().partial_cmp(&b.lo()),
            ordering => Some(ordering),
        }
    }
}

impl PartialEq for DoubleDouble {
    fn eq(&self, other: &Self) -> bool {
        self.partial_cmp(other) == Some(Ordering::Equal)
    }
}

impl PartialOrd<f64> for DoubleDouble {
    fn partial_cmp(&self, other: &f64) -> Option<Ordering> {
        self.partial_cmp(&Self::from(*other))
    }
}

impl PartialEq<f64> for DoubleDouble {
    fn eq(&self, other: &f64) -> bool {
        *self == Self::from(*other)
    }
}

// ---------------------------------------------------------------------------------------
// Square root.

/// 2^500 and 2^-500, 2^1000 and 2^-1000: exact scale factors for `sqrt`.
const TWO_POW_500: f64 = 3.273390607896142e150;
const TWO_POW_M500: f64 = 3.054936363499605e-151;
const TWO_POW_1000: f64 = 1.0715086071862673e301;
const TWO_POW_M1000: f64 = 9.332636185032189e-302;

fn dd_sqrt(a: TwoFloat) -> TwoFloat {
    let hi = a.hi();
    if !(hi > 0.0 && hi.is_finite()) {
        // ±0 → ±0, negative → NaN, +inf → +inf, NaN → NaN (as f64::sqrt).
        return TwoFloat::from(hi.sqrt());
    }
    // Keep s² and its rounding error representable: scale by an even power of two.
    if hi > TWO_POW_1000 {
        return dd_sqrt(a * TWO_POW_M1000) * TWO_POW_500;
    }
    if hi < TWO_POW_M500 {
        return dd_sqrt(a * TWO_POW_1000) * TWO_POW_M500;
    }
    // One Newton step from s = √hi: √a ≈ s + (a − s²)/(2s), with s² formed exactly.
    let s = hi.sqrt();
    let square = TwoFloat::new_mul(s, s);
    let residual = ((hi - square.hi()) - square.lo()) + a.lo();
    let correction = residual / (2.0 * s);
    TwoFloat::new_add(s, correction)
}

// ---------------------------------------------------------------------------------------
// Sine and cosine.

/// π/2 as five doubles (≈ 265 bits): the leading word is `f64::consts::FRAC_PI_2`, each
/// further word the nearest double to what the previous ones leave out. Four words
/// (212 bits) already give 1e-61 absolute accuracy for `|x| ≤ 1e4`, but that is 2e-29
/// *relative* to `sin x` at the double-double nearest to `kπ`, where `|sin x| ~ 1e-32`.
const PIO2_WORDS: [f64; 5] = [
    FRAC_PI_2,
    6.123233995736766e-17,
    -1.4973849048591698e-33,
    5.562271104316826e-50,
    2.836115989820158e-66,
];

/// Above this `|hi|` the quotient `k` no longer fits comfortably in 53 bits and the
/// Cody-Waite reduction stops being exact; `sin`/`cos` fall back to `f64` accuracy.
const REDUCTION_LIMIT: f64 = 1_125_899_906_842_624.0; // 2^50

/// `(−1)^(j+1) / (2j+3)!` for `j = 0..14`, as (hi, lo): `sin r = r + r·z·S(z)`, `z = r²`.
/// Truncation after `r²⁹/29!` leaves a relative error below 1e-37 on `|r| ≤ π/4`.
const SIN_COEFFS: [(f64, f64); 14] = [
    (-0.16666666666666666, -9.25185853854297e-18),
    (0.008333333333333333, 1.1564823173178714e-19),
    (-0.0001984126984126984, -1.7209558293420705e-22),
    (2.7557319223985893e-06, -1.858393274046472e-22),
    (-2.505210838544172e-08, 1.448814070935912e-24),
    (1.6059043836821613e-10, 1.2585294588752098e-26),
    (-7.647163731819816e-13, -7.03872877733453e-30),
    (2.8114572543455206e-15, 1.6508842730861433e-31),
    (-8.22063524662433e-18, -2.2141894119604265e-34),
    (1.9572941063391263e-20, -1.3643503830087908e-36),
    (-3.868170170630684e-23, 8.843177655482344e-40),
    (6.446950284384474e-26, -1.9330404233703465e-42),
    (-9.183689863795546e-29, -1.4303150396787322e-45),
    (1.1309962886447716e-31, 1.0498015412959506e-47),
];

/// `(−1)^(j+1) / (2j+2)!` for `j = 0..14`, as (hi, lo): `cos r = 1 + z·C(z)`, `z = r²`.
/// Truncation after `r²⁸/28!` leaves an error below 3e-36 on `|r| ≤ π/4`.
const COS_COEFFS: [(f64, f64); 14] = [
    (-0.5, 0.0),
    (0.041666666666666664, 2.3129646346357427e-18),
    (-0.001388888888888889, 5.300543954373577e-20),
    (2.48015873015873e-05, 2.1511947866775882e-23),
    (-2.755731922398589e-07, -2.3767714622250297e-23),
    (2.08767569878681e-09, -1.20734505911326e-25),
    (-1.1470745597729725e-11, -2.0655512752830745e-28),
    (4.779477332387385e-14, 4.399205485834081e-31),
    (-1.5619206968586225e-16, -1.1910679660273754e-32),
    (4.110317623312165e-19, 1.4412973378659527e-36),
    (-8.896791392450574e-22, 7.911402614872376e-38),
    (1.6117375710961184e-24, -3.6846573564509766e-41),
    (-2.4795962632247976e-27, 1.2953730964765229e-43),
    (3.279889237069838e-30, 1.5117542744029879e-46),
];

fn horner(z: TwoFloat, coeffs: &[(f64, f64)]) -> TwoFloat {
    coeffs
        .iter()
        .rev()
        .fold(TwoFloat::from(0.0), |acc, &(hi, lo)| {
            acc * z + TwoFloat::new_add(hi, lo)
        })
}

/// sin r for |r| ≤ π/4 (slightly beyond is harmless).
fn sin_reduced(r: TwoFloat) -> TwoFloat {
    let z = r * r;
    r + r * (z * horner(z, &SIN_COEFFS))
}

/// cos r for |r| ≤ π/4 (slightly beyond is harmless).
fn cos_reduced(r: TwoFloat) -> TwoFloat {
    let z = r * r;
    1.0 + z * horner(z, &COS_COEFFS)
}

/// `x = k·π/2 + r` with `|r| ≲ π/4`; returns `r` and `k mod 4`. Requires finite
/// `|x.hi| < REDUCTION_LIMIT`.
fn reduce(x: TwoFloat) -> (TwoFloat, u8) {
    let k = (x * twofloat::consts::FRAC_2_PI).hi().round();
    // Each k·cᵢ is exact as a double-double product; each subtraction is accurate to 3u²
    // relative to its (small, after the first) result.
    let r = PIO2_WORDS
        .iter()
        .fold(x, |r, &word| r - TwoFloat::new_mul(k, word));
    (r, ((k as i64) & 3) as u8)
}

/// sin(r + q·π/2).
fn sin_quadrant(r: TwoFloat, q: u8) -> TwoFloat {
    match q & 3 {
        0 => sin_reduced(r),
        1 => cos_reduced(r),
        2 => -sin_reduced(r),
        _ => -cos_reduced(r),
    }
}

/// `(sin x, cos x)` to `f64` accuracy, for arguments beyond [`REDUCTION_LIMIT`].
fn sin_cos_f64(x: TwoFloat) -> (TwoFloat, TwoFloat) {
    let (sin_hi, cos_hi) = x.hi().sin_cos();
    let (sin_lo, cos_lo) = x.lo().sin_cos();
    (
        TwoFloat::from(sin_hi * cos_lo + cos_hi * sin_lo),
        TwoFloat::from(cos_hi * cos_lo - sin_hi * sin_lo),
    )
}

enum Reduced {
    Accurate(TwoFloat, u8),
    Huge,
    NotFinite,
}

fn classify_and_reduce(x: TwoFloat) -> Reduced {
    let hi = x.hi();
    if !(hi.is_finite() && x.lo().is_finite()) {
        Reduced::NotFinite
    } else if hi.abs() >= REDUCTION_LIMIT {
        Reduced::Huge
    } else {
        let (r, q) = reduce(x);
        Reduced::Accurate(r, q)
    }
}

fn dd_sin(x: TwoFloat) -> TwoFloat {
    match classify_and_reduce(x) {
        Reduced::Accurate(r, q) => sin_quadrant(r, q),
        Reduced::Huge => sin_cos_f64(x).0,
        Reduced::NotFinite => TwoFloat::NAN,
    }
}

fn dd_cos(x: TwoFloat) -> TwoFloat {
    match classify_and_reduce(x) {
        Reduced::Accurate(r, q) => sin_quadrant(r, q.wrapping_add(1)),
        Reduced::Huge => sin_cos_f64(x).1,
        Reduced::NotFinite => TwoFloat::NAN,
    }
}

fn dd_sin_cos(x: TwoFloat) -> (TwoFloat, TwoFloat) {
    match classify_and_reduce(x) {
        Reduced::Accurate(r, q) => (sin_quadrant(r, q), sin_quadrant(r, q.wrapping_add(1))),
        Reduced::Huge => sin_cos_f64(x),
        Reduced::NotFinite => (TwoFloat::NAN, TwoFloat::NAN),
    }
}

/// `e^y − 1` for `0 ≤ y ≤ 80`: `y` halved `s` times to below 2⁻¹⁰, where the Taylor series
/// through `z¹¹/11!` leaves an error below 2⁻¹¹⁸ relative, then doubled back by
/// `expm1(2z) = expm1(z)·(expm1(z) + 2)` (no cancellation: both factors are positive).
fn dd_expm1(y: TwoFloat) -> TwoFloat {
    let mut z = y;
    let mut halvings = 0;
    while z.hi() > 1.0 / 1024.0 {
        z *= 0.5;
        halvings += 1;
    }
    // z (1 + z/2 (1 + z/3 (1 + … (1 + z/11)))), each `z/k` a correctly rounded division.
    let mut e = TwoFloat::from(1.0);
    for k in (2..=11).rev() {
        e = 1.0 + dd_div(z, TwoFloat::from(k as f64)) * e;
    }
    e = z * e;
    for _ in 0..halvings {
        e = e * (e + 2.0);
    }
    e
}

/// `e^x` from [`dd_expm1`] for `|x| ≤ 80` (a capstan's `μβ` is at most `10 · 3π/2`): for
/// `x ≥ 0` directly, for `x < 0` as `1 / e^{−x}`, so that the series always runs on a
/// positive number. Beyond, `f64::exp` (to `f64` precision, overflowing to infinity as it
/// does).
fn dd_exp(x: TwoFloat) -> TwoFloat {
    let (hi, lo) = (x.hi(), x.lo());
    if hi.is_nan() || lo.is_nan() {
        return TwoFloat::NAN;
    }
    if hi.abs() > 80.0 {
        return TwoFloat::from(hi.exp());
    }
    let negative = hi < 0.0 || (hi == 0.0 && lo < 0.0);
    let a = if negative { -x } else { x };
    let e = dd_expm1(a) + 1.0;
    if negative {
        dd_div(TwoFloat::from(1.0), e)
    } else {
        e
    }
}

/// `tanh x = expm1(2|x|) / (expm1(2|x|) + 2)` with the sign of `x`; `±1` beyond `|x| = 40`,
/// where `1 − tanh` is below 1e-34.
fn dd_tanh(x: TwoFloat) -> TwoFloat {
    let (hi, lo) = (x.hi(), x.lo());
    if hi.is_nan() || lo.is_nan() {
        return TwoFloat::NAN;
    }
    let negative = hi < 0.0 || (hi == 0.0 && lo < 0.0);
    let a = if negative { -x } else { x };
    let t = if a.hi() > 40.0 {
        TwoFloat::from(1.0)
    } else {
        let e = dd_expm1(a * 2.0);
        dd_div(e, e + 2.0)
    };
    if negative {
        -t
    } else {
        t
    }
}

// ---------------------------------------------------------------------------------------
// The scalar traits.

impl Real for DoubleDouble {
    fn from_f64(x: f64) -> Self {
        Self::from(x)
    }
    fn sin(self) -> Self {
        Self(dd_sin(self.0))
    }
    fn cos(self) -> Self {
        Self(dd_cos(self.0))
    }
    fn sin_cos(self) -> (Self, Self) {
        let (sin, cos) = dd_sin_cos(self.0);
        (Self(sin), Self(cos))
    }
    fn sqrt(self) -> Self {
        Self(dd_sqrt(self.0))
    }
    fn tanh(self) -> Self {
        Self(dd_tanh(self.0))
    }
    fn exp(self) -> Self {
        Self(dd_exp(self.0))
    }
    fn sign_outside_or(self, band: Self, otherwise: Self) -> Self {
        self.select_outside(band, Self::ONE, -Self::ONE, otherwise)
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
    /// The larger of the two; like `f64::max`, a NaN argument is ignored.
    fn max(self, other: Self) -> Self {
        if self.is_nan() || other > self {
            other
        } else {
            self
        }
    }
    fn zero() -> Self {
        Self::ZERO
    }
    fn one() -> Self {
        Self::ONE
    }
}

impl Numeric for DoubleDouble {
    fn to_f64(self) -> f64 {
        self.0.hi()
    }
    fn abs(self) -> Self {
        let (hi, lo) = (self.0.hi(), self.0.lo());
        if hi < 0.0 || (hi == 0.0 && lo < 0.0) {
            -self
        } else {
            self
        }
    }
    fn is_finite(self) -> bool {
        self.0.hi().is_finite() && self.0.lo().is_finite()
    }
    /// 2⁻¹⁰⁶ ≈ 1.23e-32, i.e. u² with u = 2⁻⁵³ the unit round-off of `f64`: the relative
    /// spacing a double-double resolves with its 53 + 53 bits. (The format has no fixed
    /// "next number after 1": a low word can be arbitrarily small.) Unlike `f64`
    /// operations, which are accurate to 1 times theirs, the double-double operations are
    /// accurate to a small multiple of this value: proven 3 for `+`/`-` and 5 for `*`,
    /// measured below 3 for everything in this file (see the module documentation), so
    /// error bounds written as `c·n·unit_roundoff` need a slightly larger `c` here.
    fn unit_roundoff() -> f64 {
        UNIT_ROUNDOFF
    }
}

/// 2⁻¹⁰⁶.
const UNIT_ROUNDOFF: f64 = f64::EPSILON * f64::EPSILON * 0.25;

// ---------------------------------------------------------------------------------------
// Display: decimal scientific notation.

/// Digits after the decimal point when the formatter gives no precision: 32 significant
/// digits in all, about what 106 bits resolve.
const DEFAULT_FRACTION_DIGITS: usize = 31;
/// More digits than this would only print noise.
const MAX_FRACTION_DIGITS: usize = 34;

/// `10^n` for `0 ≤ n ≤ 300`, by binary powering in double-double.
fn pow10(n: i32) -> TwoFloat {
    let (mut result, mut base, mut n) = (TwoFloat::from(1.0), TwoFloat::from(10.0), n);
    while n > 0 {
        if n & 1 == 1 {
            result *= base;
        }
        n >>= 1;
        if n > 0 {
            base *= base;
        }
    }
    result
}

/// `v · 10^p` for any `p` that keeps the result finite.
fn mul_pow10(v: TwoFloat, p: i32) -> TwoFloat {
    const STEP: i32 = 300;
    if p > STEP {
        mul_pow10(v * pow10(STEP), p - STEP)
    } else if p < -STEP {
        mul_pow10(dd_div(v, pow10(STEP)), p + STEP)
    } else if p >= 0 {
        v * pow10(p)
    } else {
        dd_div(v, pow10(-p))
    }
}

/// `v ≥ 0`, finite: "d.ddd…e±x" with `fraction_digits` digits after the point, trailing
/// zeros dropped if `trim`.
fn scientific(v: TwoFloat, fraction_digits: usize, trim: bool) -> String {
    let digit_count = fraction_digits + 1;
    let mut exponent = 0i32;
    let mut digits = vec![0u8; digit_count];
    if v.hi() != 0.0 {
        exponent = v.hi().log10().floor() as i32;
        let mut w = mul_pow10(v, -exponent);
        if w.hi() >= 10.0 {
            w = dd_div(w, TwoFloat::from(10.0));
            exponent += 1;
        } else if w.hi() < 1.0 {
            w *= 10.0;
            exponent -= 1;
        }
        for digit in digits.iter_mut() {
            let mut d = w.hi().floor();
            if (w - d).hi() < 0.0 {
                d -= 1.0;
            }
            let d = d.clamp(0.0, 9.0);
            *digit = d as u8;
            w = (w - d) * 10.0;
        }
        // Round half up on the remainder, carrying leftwards.
        if w.hi() >= 5.0 {
            let mut carry = true;
            for digit in digits.iter_mut().rev() {
                if *digit == 9 {
                    *digit = 0;
                } else {
                    *digit += 1;
                    carry = false;
                    break;
                }
            }
            if carry {
                digits.insert(0, 1);
                digits.truncate(digit_count);
                exponent += 1;
            }
        }
    }
    if trim {
        while digits.len() > 1 && digits.last() == Some(&0) {
            digits.pop();
        }
    }
    let mut out = String::with_capacity(digit_count + 8);
    for (i, d) in digits.iter().enumerate() {
        if i == 1 {
            out.push('.');
        }
        out.push(char::from(b'0' + d));
    }
    out.push('e');
    out.push_str(&exponent.to_string());
    out
}

/// Decimal scientific notation, e.g. `3.1415926535897932384626433832795e0` for
/// [`DoubleDouble::PI`] and `5e-1` for one half: by default 32 significant digits with
/// trailing zeros dropped; a precision (`{:.5}`) sets the digits after the point exactly
/// (at most 34). Width, fill and `+` are honoured. The digits are correct to about the
/// 31st significant one.
impl fmt::Display for DoubleDouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let hi = self.0.hi();
        if self.is_nan() {
            return f.pad_integral(true, "", "NaN");
        }
        let nonnegative = !hi.is_sign_negative();
        if hi.is_infinite() {
            return f.pad_integral(nonnegative, "", "inf");
        }
        let fraction_digits = f
            .precision()
            .unwrap_or(DEFAULT_FRACTION_DIGITS)
            .min(MAX_FRACTION_DIGITS);
        let magnitude = if nonnegative { self.0 } else { -self.0 };
        let text = scientific(magnitude, fraction_digits, f.precision().is_none());
        f.pad_integral(nonnegative, "", &text)
    }
}
