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
//! pairs per operator; the tests embed a few hundred of them):
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
    fn sign_outside(self, band: Self) -> Self {
        if self > band {
            Self::ONE
        } else if self < -band {
            -Self::ONE
        } else {
            Self::ZERO
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

#[cfg(test)]
mod tests {
    //! The reference tables at the end of this module were computed with mpmath at 50
    //! significant digits and stored exactly as double-doubles: `hi` the double nearest to
    //! the true value, `lo` the double nearest to the remainder (representation error
    //! ≤ 2⁻¹⁰⁷ relative, far below the tolerances tested). Arguments: 80 in [−π, π] and
    //! 80 in [−1e4, 1e4] (half of them with a non-zero low word), tiny ones down to the
    //! smallest subnormal, the double and the double-double nearest to ±kπ/2 (k up to
    //! 6366, i.e. |x| ≤ 1e4) with and without a 1e-20 offset, and the octant boundaries
    //! kπ/2 ± π/4 of the argument reduction.

    use super::*;

    /// Rows of whitespace-separated numbers, an optional leading word kept as a tag.
    fn rows(table: &str) -> Vec<(String, Vec<f64>)> {
        table
            .lines()
            .filter(|line| !line.trim().is_empty())
            .map(|line| {
                let mut words = line.split_whitespace().peekable();
                let tag = match words.peek() {
                    Some(word) if word.parse::<f64>().is_err() => words.next().unwrap_or(""),
                    _ => "",
                };
                let numbers = words
                    .map(|w| w.parse().unwrap_or_else(|_| panic!("bad number {w:?}")))
                    .collect();
                (tag.to_string(), numbers)
            })
            .collect()
    }

    fn dd(hi: f64, lo: f64) -> DoubleDouble {
        DoubleDouble::from_parts(hi, lo)
    }

    /// |computed − reference| / |reference| (0 if both are zero).
    fn relative_error(computed: DoubleDouble, reference: DoubleDouble) -> f64 {
        let error = (computed - reference).hi().abs();
        if reference.hi() == 0.0 {
            if error == 0.0 {
                0.0
            } else {
                f64::INFINITY
            }
        } else {
            error / reference.hi().abs()
        }
    }

    fn assert_close(what: &str, computed: DoubleDouble, reference: DoubleDouble, tol: f64) {
        let error = relative_error(computed, reference);
        assert!(
            error <= tol,
            "{what}: got {computed:?}, reference {reference:?}, relative error {error:e} > {tol:e}"
        );
    }

    /// `(x, tanh x as hi, lo)` from mpmath at 60 digits: tiny, moderate and saturating
    /// arguments, where `expm1`'s halvings and doublings and the cut at |x| = 40 act.
    const TANH_REFERENCE: [(f64, f64, f64); 12] = [
        (1e-20, 1e-20, -3.333333333333333e-61),
        (1e-06, 9.999999999996666e-07, -2.5868588632771325e-23),
        (0.001, 0.0009999996666668, 1.7800613799166557e-20),
        (0.1, 0.09966799462495582, 3.542433877641546e-18),
        (0.5, 0.46211715726000974, 2.1916603238260928e-17),
        (0.7, 0.6043677771171635, -2.7916180015425346e-17),
        (1.0, 0.7615941559557649, 3.7090214482164924e-17),
        (2.5, 0.9866142981514303, -2.4529238788172874e-17),
        (10.0, 0.9999999958776927, 3.693278996616596e-17),
        (-3.3, -0.9972829600991421, -2.0750489070819206e-18),
        (35.0, 1.0, -7.950899471817294e-31),
        (
            0.3333333333333333,
            0.32151273753163434,
            -1.2420265324202129e-17,
        ),
    ];

    #[test]
    fn tanh_agrees_with_a_60_digit_reference_to_1e30() {
        for (x, hi, lo) in TANH_REFERENCE {
            let x = DoubleDouble::from(x);
            assert_close(&format!("tanh {x:?}"), x.tanh(), dd(hi, lo), 1e-30);
            assert_close(&format!("tanh {:?}", -x), (-x).tanh(), -dd(hi, lo), 1e-30);
        }
        assert_eq!(DoubleDouble::from(1e3).tanh(), DoubleDouble::ONE);
        assert!(DoubleDouble::from(f64::NAN).tanh().is_nan());
    }

    #[test]
    fn sin_and_cos_agree_with_50_digit_reference_to_1e30() {
        let table = rows(SIN_COS_REFERENCE);
        assert!(table.len() > 300);
        for (tag, v) in table {
            let x = dd(v[0], v[1]);
            let (sin, cos) = (dd(v[2], v[3]), dd(v[4], v[5]));
            assert_close(&format!("sin {x:?} ({tag})"), x.sin(), sin, 1e-30);
            assert_close(&format!("cos {x:?} ({tag})"), x.cos(), cos, 1e-30);
        }
    }

    #[test]
    fn sin_and_cos_near_multiples_of_half_pi_keep_relative_accuracy() {
        // Rows tagged "zero" are within 1e-20 of ±kπ/2, |x| ≤ 1e4: there sin or cos is as
        // small as 1e-33, and the 265-bit π/2 keeps even the relative error at ~1e-32.
        let mut smallest = f64::INFINITY;
        for (_, v) in rows(SIN_COS_REFERENCE)
            .iter()
            .filter(|(tag, _)| tag == "zero")
        {
            let x = dd(v[0], v[1]);
            let (sin, cos) = (dd(v[2], v[3]), dd(v[4], v[5]));
            smallest = smallest.min(sin.hi().abs().min(cos.hi().abs()));
            for (name, computed, reference) in [("sin", x.sin(), sin), ("cos", x.cos(), cos)] {
                let absolute = (computed - reference).hi().abs();
                assert!(
                    absolute <= 1e-32,
                    "{name} {x:?}: absolute error {absolute:e}"
                );
                assert_close(&format!("{name} {x:?}"), computed, reference, 1e-31);
            }
        }
        assert!(
            smallest < 1e-30,
            "the table must reach the zeros, got {smallest:e}"
        );
    }

    #[test]
    fn sin_cos_is_the_pair_of_sin_and_cos_and_sin_is_odd() {
        for (_, v) in rows(SIN_COS_REFERENCE) {
            let x = dd(v[0], v[1]);
            let (sin, cos) = x.sin_cos();
            assert_eq!((sin.hi(), sin.lo()), (x.sin().hi(), x.sin().lo()));
            assert_eq!((cos.hi(), cos.lo()), (x.cos().hi(), x.cos().lo()));
            assert_eq!(((-x).sin() + sin).hi(), 0.0, "sin(-x) = -sin(x) at {x:?}");
            assert_eq!(((-x).cos() - cos).hi(), 0.0, "cos(-x) = cos(x) at {x:?}");
        }
    }

    #[test]
    fn sin_squared_plus_cos_squared_is_one_to_1e31() {
        // A deterministic sweep of 2000 arguments in [-1e4, 1e4], beyond the table.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..2000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            let x = dd(2e4 * unit - 1e4, 1e-13 * (unit - 0.5));
            let (sin, cos) = x.sin_cos();
            let defect = (sin * sin + cos * cos - 1.0).hi().abs();
            assert!(defect <= 1e-31, "sin²+cos²−1 = {defect:e} at {x:?}");
        }
    }

    #[test]
    fn sqrt_agrees_with_50_digit_reference_to_1e31() {
        let table = rows(SQRT_REFERENCE);
        assert!(table.len() > 50);
        for (_, v) in table {
            let x = dd(v[0], v[1]);
            assert_close(&format!("sqrt {x:?}"), x.sqrt(), dd(v[2], v[3]), 1e-31);
        }
    }

    #[test]
    fn arithmetic_agrees_with_50_digit_reference_to_1e31() {
        let table = rows(ARITHMETIC_REFERENCE);
        assert!(table.len() > 100);
        for (op, v) in table {
            let (a, b, reference) = (dd(v[0], v[1]), dd(v[2], v[3]), dd(v[4], v[5]));
            let computed = match op.as_str() {
                "add" => a + b,
                "sub" => a - b,
                "mul" => a * b,
                "div" => a / b,
                other => panic!("unknown operation {other}"),
            };
            assert_close(&format!("{a:?} {op} {b:?}"), computed, reference, 1e-31);
        }
    }

    #[test]
    fn mixed_and_assigning_operators_agree_with_the_double_double_ones() {
        // Mixed operands may use twofloat's cheaper double-double × double algorithms, so
        // they agree to the last bits, not bit for bit.
        let (a, b) = (DoubleDouble::PI, 0.1);
        assert_close("π + 0.1", a + b, a + DoubleDouble::from(b), 1e-31);
        assert_close("0.1 − π", b - a, DoubleDouble::from(b) - a, 1e-31);
        assert_close("π · 0.1", a * b, a * DoubleDouble::from(b), 1e-31);
        assert_close("0.1 / π", b / a, DoubleDouble::from(b) / a, 1e-31);
        let mut c = a;
        c += b;
        c -= a;
        c *= 3.0;
        c /= DoubleDouble::from(3.0);
        assert_close("(π + 0.1 − π)·3/3", c, DoubleDouble::from(0.1), 1e-31);
        let one_third = DoubleDouble::ONE / 3.0;
        assert_close("1/3 · 3", one_third * 3.0, DoubleDouble::ONE, 1e-31);
        assert!(
            (one_third - 1.0 / 3.0).hi().abs() > 1e-18,
            "1/3 must keep its low word"
        );
        let sum: DoubleDouble = [0.1, 0.2, 0.3].into_iter().map(DoubleDouble::from).sum();
        let product: DoubleDouble = [2.0, 3.0].into_iter().map(DoubleDouble::from).product();
        assert_close("Σ", sum, dd(0.1, 0.0) + dd(0.2, 0.0) + dd(0.3, 0.0), 0.0);
        assert_eq!(product, 6.0);
    }

    #[test]
    fn division_by_zero_and_by_infinity_behave_like_f64() {
        let one = DoubleDouble::ONE;
        assert_eq!((one / 0.0).hi(), f64::INFINITY);
        assert_eq!((-one / 0.0).hi(), f64::NEG_INFINITY);
        assert!((DoubleDouble::ZERO / 0.0).is_nan());
        assert_eq!((one / f64::INFINITY).hi(), 0.0);
        assert!(!(one / 0.0).is_finite());
    }

    #[test]
    fn huge_and_non_finite_arguments_do_not_panic() {
        // Beyond 2^50 sin/cos fall back to f64 accuracy; they stay finite and bounded.
        for x in [1.2e15, -3e16, 1e100, -1e300, f64::MAX] {
            let (sin, cos) = DoubleDouble::from(x).sin_cos();
            assert!((sin.hi() - x.sin()).abs() <= 1e-15, "sin {x:e}");
            assert!((cos.hi() - x.cos()).abs() <= 1e-15, "cos {x:e}");
        }
        // Just below the limit the reduction is still exact.
        let x = DoubleDouble::from(1e15);
        let (sin, cos) = x.sin_cos();
        assert!((sin * sin + cos * cos - 1.0).hi().abs() <= 1e-31);
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let x = DoubleDouble::from(x);
            assert!(x.sin().is_nan() && x.cos().is_nan() && x.sin_cos().0.is_nan());
        }
        assert!(DoubleDouble::from(-1.0).sqrt().is_nan());
        assert!(DoubleDouble::from(f64::NAN).sqrt().is_nan());
        assert_eq!(DoubleDouble::from(f64::INFINITY).sqrt().hi(), f64::INFINITY);
        assert_eq!(DoubleDouble::ZERO.sqrt(), 0.0);
        assert_eq!(Real::sqrt(DoubleDouble::from(-0.0)).hi(), 0.0);
    }

    #[test]
    fn max_is_the_tension_floor() {
        let floor = DoubleDouble::from(0.5);
        let just_above = dd(0.5, 1e-25);
        assert_eq!(DoubleDouble::from(-3.0).max(floor), floor);
        assert_eq!(DoubleDouble::from(2.0).max(floor), 2.0);
        assert_eq!(just_above.max(floor), just_above, "the low word decides");
        assert_eq!(floor.max(just_above), just_above);
        let nan = DoubleDouble::from(f64::NAN);
        assert_eq!(nan.max(floor), floor, "NaN is ignored, as by f64::max");
        assert_eq!(floor.max(nan), floor);
        let minus_infinity = DoubleDouble::from(f64::NEG_INFINITY);
        assert_eq!(minus_infinity.max(floor), floor);
        assert_eq!(floor.max(minus_infinity), floor);
    }

    #[test]
    fn ordering_follows_the_value_including_low_word_and_infinities() {
        let values = [
            DoubleDouble::from(f64::NEG_INFINITY),
            DoubleDouble::from(-1e300),
            dd(-1.0, -1e-20),
            DoubleDouble::from(-1.0),
            DoubleDouble::ZERO,
            dd(1.0, -1e-30),
            DoubleDouble::ONE,
            dd(1.0, 1e-30),
            DoubleDouble::from(f64::INFINITY),
        ];
        for (i, a) in values.iter().enumerate() {
            for (j, b) in values.iter().enumerate() {
                assert_eq!(a.partial_cmp(b), Some(i.cmp(&j)), "{a:?} vs {b:?}");
            }
        }
        let nan = DoubleDouble::from(f64::NAN);
        assert_eq!(nan.partial_cmp(&DoubleDouble::ONE), None);
        assert!(nan != nan);
        assert!(dd(1.0, 1e-30) > 1.0 && DoubleDouble::from(-0.0) == 0.0);
    }

    #[test]
    fn parts_are_normalised_and_round_trip() {
        let x = dd(1.0, 1e-20);
        assert_eq!((x.hi(), x.lo()), (1.0, 1e-20));
        let y = dd(1.0, 1.0);
        assert_eq!((y.hi(), y.lo()), (2.0, 0.0));
        let z = dd(1e-20, 1.0);
        assert_eq!((z.hi(), z.lo()), (1.0, 1e-20));
        assert_eq!(x.to_f64(), 1.0);
        assert_eq!(Numeric::to_f64(dd(0.1, 0.0)), 0.1);
        assert_eq!(f64::from(DoubleDouble::from(2.5)), 2.5);
        assert_eq!(DoubleDouble::from(TwoFloat::from(2.5)), 2.5);
        assert_eq!(<DoubleDouble as Real>::from_f64(0.25), 0.25);
        assert_eq!(<DoubleDouble as Real>::zero(), 0.0);
        assert_eq!(<DoubleDouble as Real>::one(), 1.0);
        assert_eq!(Numeric::abs(dd(-1.0, 1e-20)), dd(1.0, -1e-20));
        assert_eq!(Numeric::abs(dd(1.0, -1e-20)), dd(1.0, -1e-20));
        assert!(Numeric::is_finite(x) && !Numeric::is_finite(DoubleDouble::from(f64::NAN)));
        assert!(!Numeric::is_finite(DoubleDouble::from(f64::INFINITY)));
        let infinite = dd(1e308, 1e308);
        assert_eq!((infinite.hi(), infinite.lo()), (f64::INFINITY, 0.0));
        assert!(!infinite.is_nan() && infinite > DoubleDouble::from(f64::MAX));
    }

    #[test]
    fn constants_agree_with_50_digit_reference() {
        // π = 3.14159265358979323846264338327950288419716939937510…
        let pi = dd(core::f64::consts::PI, 1.2246467991473532e-16);
        assert_eq!(DoubleDouble::PI, pi);
        assert_eq!(DoubleDouble::FRAC_PI_2, pi / 2.0);
    }

    #[test]
    fn unit_roundoff_is_two_to_the_minus_106() {
        let u = <DoubleDouble as Numeric>::unit_roundoff();
        assert_eq!(u, 2f64.powi(-106));
        // Resolved, unlike in f64: 1 + u is not 1.
        assert!(DoubleDouble::ONE + u > DoubleDouble::ONE);
        assert!(u < f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn display_prints_up_to_32_significant_digits() {
        let show = |x: DoubleDouble| format!("{x}");
        assert_eq!(
            show(DoubleDouble::PI),
            "3.1415926535897932384626433832795e0"
        );
        assert_eq!(
            show(DoubleDouble::ONE / 3.0),
            "3.3333333333333333333333333333333e-1"
        );
        // 2/3 as a double-double is 0.66666666666666666666666666666666461…
        assert_eq!(
            show(-DoubleDouble::from(2.0) / 3.0),
            "-6.6666666666666666666666666666666e-1"
        );
        // The double 0.2 is 0.2000000000000000111022302462515654…: rounded up.
        assert_eq!(
            show(DoubleDouble::from(0.2)),
            "2.0000000000000001110223024625157e-1"
        );
        assert_eq!(show(DoubleDouble::ONE), "1e0");
        assert_eq!(
            show(DoubleDouble::from(-2.5e-7)),
            "-2.4999999999999998868702795647156e-7"
        );
        assert_eq!(show(DoubleDouble::ZERO), "0e0");
        assert_eq!(
            show(DoubleDouble::from(1e23)), // the double nearest 1e23
            "9.9999999999999991611392e22"
        );
        assert_eq!(
            show(DoubleDouble::from(f64::MAX)),
            "1.797693134862315708145274237317e308"
        );
        assert_eq!(
            show(DoubleDouble::from(5e-324)),
            "4.9406564584124654417656879286822e-324"
        );
        assert_eq!(format!("{:.3}", DoubleDouble::PI), "3.142e0");
        assert_eq!(format!("{:.2}", DoubleDouble::from(9.999)), "1.00e1");
        assert_eq!(format!("{:>+10.2}", DoubleDouble::ONE), "   +1.00e0");
        assert_eq!(show(DoubleDouble::from(f64::NAN)), "NaN");
        assert_eq!(show(DoubleDouble::from(f64::NEG_INFINITY)), "-inf");
    }

    // Tables (generated; see the module comment). One row per argument.

    /// tag x_hi x_lo sin_hi sin_lo cos_hi cos_lo
    const SIN_COS_REFERENCE: &str = "
unit -0.18792555850219417 0.0 -0.18682137974239746 -4.843171583011145e-18 0.9823938986328992 -1.9117909366719586e-17
unit 1.4342268420240574 0.0 0.9906888734131655 -2.0289127033858328e-17 0.13614534915065238 -8.233558469972566e-18
unit -1.233066581509375 0.0 -0.9435093360167927 4.1781197511865834e-17 0.3313459413500505 1.5341258748131976e-17
unit 2.433466793276982 0.0 0.6504113510145142 1.124899978334915e-17 -0.7595821709805164 3.039086740680943e-17
unit -0.5649300535978945 0.0 -0.5353567387676119 4.2496430384274986e-17 0.8446260487672086 -3.007521426894491e-17
unit 1.3610283750757937 0.0 0.9780792611533853 1.5832870158856912e-17 0.20823294384330238 1.0558829351145683e-18
unit -1.4751590974071882 0.0 -0.9954302448686948 2.6392473742614078e-17 0.09549150538477419 -1.833837039928753e-18
unit -1.6011651655656547 0.0 -0.999538902255404 5.1360032451112254e-17 -0.030364170959571182 6.220823969337219e-19
unit 1.9640082834746657 0.0 0.9236831422527926 2.2952456430764814e-17 -0.38315721671137465 8.785069114462173e-18
unit -0.010672731525650736 0.0 -0.010672528909980472 8.615336731584122e-19 0.9999430469415074 5.584383494529155e-18
unit -0.5285911792707219 0.0 -0.504317299435534 -4.859298675091013e-18 0.8635184198904212 4.368458731329202e-17
unit 1.4310528498919695 0.0 0.9902517596640527 -4.9993733851386393e-17 0.13928909678164833 7.744598455513025e-18
unit 2.9106833803139853 0.0 0.22886275800234251 -1.2540662664975787e-18 -0.9734586986614077 4.0874929476076895e-17
unit -1.1967632585015804 0.0 -0.9308613473865487 4.0945972417644563e-17 0.36537262067880677 -1.8270077400687337e-17
unit 1.2821454247051483 0.0 0.958628780911975 4.51000722217107e-18 0.28465920046121923 2.6368345218930314e-17
unit 0.12158417836456392 0.0 0.1212848423760332 -6.769751582677143e-18 0.9926177446579427 1.2111562791540173e-18
unit 1.4536782781161914 0.0 0.9931495171758544 7.849940337136054e-18 0.11685048794663727 4.1753465556226264e-18
unit 3.139475980457931 0.0 0.002116671551305812 1.204742697789598e-19 -0.9999977598482628 -2.7006776112319075e-17
unit -1.8448573545246933 0.0 -0.962679748364468 4.080869347860041e-17 -0.2706431268089486 1.248531176510143e-18
unit 1.58707416840502 0.0 0.9998675188615699 6.2054220046265885e-18 -0.01627712276811183 -3.810473312460054e-19
unit -0.19771162643768436 0.0 -0.19642605412544223 5.084533615765987e-18 0.980518640955239 -2.1002911828075092e-17
unit 1.3134048944353625 0.0 0.9670573014237254 -1.0981065536548644e-17 0.2545587864581814 -1.918525538272842e-17
unit 2.3367589167452607 0.0 0.7207153941754866 1.584600566911354e-17 -0.6932310730185665 2.5661158379774532e-17
unit -2.209347637963321 0.0 -0.8029600662690792 2.8667806626689427e-17 -0.5960328279358075 -4.754605632370041e-17
unit -1.8057178975341783 0.0 -0.9725326000448011 -5.3542243621874685e-17 -0.23276671121554038 -4.1368719008699634e-18
unit -0.5534829550060429 0.0 -0.5256533571293189 8.381174313681436e-18 0.8506988586677877 2.2654560804107698e-17
unit -2.774120329238288 0.0 -0.3592576581405604 -3.639133846623738e-18 -0.9332384127688702 -4.482467352077893e-17
unit -0.9459654944251508 0.0 -0.8110620874199329 -1.610014836377722e-17 0.584960075859901 4.471229829705051e-18
unit -0.5242020065891007 0.0 -0.5005223223587968 -1.0904260439587405e-17 0.8657236307393698 3.781797790539352e-17
unit -2.3613245939515 0.0 -0.703469961156573 1.0773082624330506e-17 -0.7107249916461146 -2.7219549115477772e-17
unit 1.5299781568994701 0.0 0.9991670541620133 5.427930886546941e-17 0.04080683615773441 -2.8670243660085997e-18
unit 1.6512912911146609 0.0 0.9967620292790329 -2.386779071480436e-18 -0.0804080654383897 -5.319318411880455e-18
unit -0.6892275050342023 0.0 -0.6359412086909606 3.478835733590243e-17 0.7717375065970813 3.2964135314719206e-17
unit -0.9720313631241977 0.0 -0.8260323392518997 2.9124679488664035e-17 0.5636227235571988 5.374952531882676e-17
unit -1.8777451743758649 0.0 -0.9532599159520102 2.710138614076605e-17 -0.30215150610110564 -1.9607239953722502e-17
unit -0.4598859976826972 0.0 -0.4438459520197061 4.905700797560398e-18 0.896103102815586 -4.931640359613303e-19
unit -1.153252656330739 0.0 -0.9140877787648227 1.1153624149885648e-17 0.4055163778601211 -5.434649816028109e-18
unit -1.7966324020818647 0.0 -0.9746072326737439 -5.551760547331315e-18 -0.22392128532148686 -1.0956647626030147e-17
unit 2.3109590224446306 0.0 0.7383588452465968 7.003164164783682e-18 -0.6744080483254274 -3.767930599400196e-17
unit -1.7020957661653369 0.0 -0.9913926049063514 -2.2533112988127465e-17 -0.13092250737363306 4.899852230599854e-18
unit -2.8872050212595126 -1.220269718446031e-16 -0.2516527956586825 7.8402317168835905e-19 -0.9678175811779663 4.0685347136856086e-17
unit -3.0195681066239786 1.6227567800483423e-16 -0.12172194828964575 -3.864603922402534e-18 -0.9925642383768281 -2.8323322102411494e-17
unit 2.161156215746523 -8.02807313200724e-17 0.8307403971074823 1.533575455169986e-17 -0.5566600332462379 5.070353044075084e-17
unit 2.8924392869109647 1.3517247474515798e-16 0.2465835571429172 1.0792426155809769e-17 -0.969121534868948 -1.7606731220350097e-17
unit -0.49606252464490774 -2.15364002588148e-17 -0.4759663713904585 -1.1497429169364272e-18 0.8794634803705041 -2.3285517244383815e-18
unit 2.207542897223422 4.738386275821186e-17 0.8040344427561386 1.83935795923119e-17 -0.5945827233125982 -7.100821577933098e-18
unit -1.6926754148968737 1.099312338046453e-16 -0.9925819334125915 4.27732756357541e-17 -0.12157756973604088 4.1507551547153496e-18
unit -0.8437656391458526 -3.2963367135234127e-17 -0.747151258648482 4.18005790115813e-17 0.6646540428674073 5.0035784501256565e-18
unit -0.04183484147918248 2.3350322604210655e-18 -0.041822639644728 -2.5000584266040803e-19 0.9991250506383809 5.126064854706382e-17
unit -2.2531682966478246 -5.006143513811136e-17 -0.7760790546480703 1.667775353072748e-17 -0.6306356324666071 -2.8953800995189187e-18
unit -1.0225273375312192 9.771107168073417e-17 -0.8534280215615383 -5.074474649417482e-18 0.5212107174776421 2.232769531354393e-17
unit 3.1363470138243006 -1.556043576028163e-17 0.005245615708377853 3.7737905059205226e-19 -0.9999862416632741 5.210390400650167e-18
unit -2.0746108627500846 8.685928728427635e-17 -0.875747395664771 -5.0896203179539635e-17 -0.48276961274128566 -1.8805739328696217e-17
unit 2.269390180646856 -7.468984352629025e-17 0.7657472950645462 -2.1842704896140142e-17 -0.6431415708079605 3.646014856461731e-17
unit -1.8415347332349645 4.142757753893012e-17 -0.9635736774279977 4.015547847019418e-17 -0.2674430185439229 -2.6550154929280488e-17
unit -2.5258985141218906 1.5257003341507542e-16 -0.5775253379278548 4.6539900483058414e-17 -0.8163727604785189 8.442330510323157e-18
unit -3.1144689867531543 -1.5513862240714973e-16 -0.027120341175635217 5.577471627816776e-19 -0.9996321758999743 3.633981397433934e-17
unit 1.2807652682527708 -3.3243299870724355e-17 0.9582349937912924 -4.9777123722646826e-17 0.2859819866246857 -1.2138198037173026e-17
unit -2.629897371868908 1.34563092703917e-16 -0.4896560924793426 1.6109036600776655e-17 -0.871915655954096 4.1004689872530346e-17
unit -1.6381211418534727 -8.62319476302872e-18 -0.9977345405402251 -2.7832415440918183e-17 -0.06727396682956767 6.551944955258518e-18
unit -1.4851825931596965 5.262135737239742e-18 -0.9963373822875423 8.244970243804963e-18 0.08550918463187317 -1.9605651124981556e-18
unit -0.4020166918580137 2.6202081793198767e-17 -0.39127504536600616 3.9454487682274535e-18 0.9202737847368194 -1.426880708151723e-17
unit -1.8790758672601124 -9.529094964153682e-17 -0.9528570012222372 4.149822652171469e-17 -0.30341973439736186 -6.641738298288931e-18
unit -1.2409203179244137 -8.087594729516816e-17 -0.9460825147172539 1.7724643843019163e-17 0.32392572504553735 1.916840633025577e-17
unit 1.0153897516468318 -5.550509043372222e-17 0.8496861279797375 5.321410680252808e-17 0.5272888050383784 2.056189700921095e-18
unit -2.5094316950293694 -1.2492834381193992e-16 -0.5908894949679859 -9.351396410688708e-18 -0.8067525052557807 -5.087784061468897e-17
unit -1.9136040136017634 -2.4736000474616698e-17 -0.9418146235350116 5.2054841501222117e-17 -0.3361327340435688 -4.8545637910323534e-18
unit 0.09593170037815435 -3.840859802702056e-18 0.09578462657047894 -2.1042311073728865e-18 0.9954020822324785 2.9701385084285086e-18
unit -0.9135045303015854 2.2487057063663712e-17 -0.7916497776317682 -3.8926718789908076e-17 0.6109751464467044 -1.718995689533653e-17
unit 1.8835603028163854 1.7510134582606682e-17 0.9514867584989671 4.977738939877081e-17 -0.3076896949868944 2.6238500396032966e-17
unit 2.714546861866147 1.9610766122428912e-17 0.41418371310782925 1.9894476275283593e-17 -0.9101933046316103 -1.3074237898579821e-17
unit 2.740297359524522 9.790494493712115e-17 0.3906110601339075 2.021750653505985e-17 -0.9205558102043921 -1.4411312570920485e-17
unit 0.8383466258793226 -4.23493897969454e-17 0.7435385369157871 -2.417500790131987e-18 0.6686930866407479 -2.6966945089587866e-17
unit -2.791201981147317 -1.663232242680614e-16 -0.3432647683108581 1.5413733656426416e-17 -0.9392386804409691 2.2263828672422853e-17
unit 2.070592865522838 1.8059843126647783e-16 0.877680088255223 2.6283822571667817e-18 -0.4792469746177892 -1.4936951344891557e-17
unit 0.7222289826608241 -4.575523837449571e-17 0.6610587944876475 -6.6415493218359565e-18 0.7503341057359303 2.7788036196176316e-17
unit 0.026013828079973766 -9.150592859378922e-19 0.0260108941695366 -1.4819978241340793e-18 0.9996616594550884 -2.9179297397165205e-17
unit 0.5273860309268832 2.5739459493874558e-17 0.5032762656630634 2.6179090805600446e-17 0.8641255698220263 2.1711033122998276e-17
unit -2.123492952445144 -1.663935654819375e-16 -0.8511119322914436 -2.389108836971975e-17 -0.5249842652033727 6.313942821489492e-18
unit -2.4862730550531014 1.969967739233143e-16 -0.6094126691717034 -2.9023653286009774e-17 -0.7928532011999573 3.0988611789291596e-17
wide 1233.5233110907448 0.0 0.9012309399535006 4.149815162044687e-17 -0.4333391199401801 6.869233471378874e-18
wide 9892.471969772578 0.0 0.3924523896642948 1.3972731566811812e-17 -0.9197723206570115 -3.380939359328426e-17
wide 2630.2169308330576 0.0 -0.6471802493958531 -5.34778407061016e-17 -0.7623370152314011 3.9981119361982686e-17
wide 1907.702402466446 0.0 -0.6857704431273134 -3.495556444836763e-17 -0.727817902591691 7.507727158481154e-18
wide 1200.6631761537574 0.0 0.54365223877135 -2.1981978631495493e-17 0.8393105761748144 3.961239092158856e-17
wide 885.704561817065 0.0 -0.2226837633119956 -5.863901456727237e-18 0.9748907331374154 -5.3658141024465044e-17
wide -3705.208897521439 0.0 0.955443585571135 -3.1622925515689966e-17 -0.2951737704996387 2.7754387619022714e-17
wide -7542.711454486833 0.0 -0.24983203184421354 -2.137026358838233e-18 -0.9682891902033152 -9.220980097995933e-18
wide -9421.605589650908 0.0 -0.03077360563429373 -1.2005145619729308e-18 -0.9995263804403889 2.4696067719560077e-17
wide -8770.359441071972 0.0 0.8233267458793052 5.5362054268625056e-18 0.5675676783607343 2.9824514947929945e-17
wide 2706.9782998187493 0.0 -0.879384349997683 -2.3891749824675095e-17 0.4761125549480422 -1.0058725626695375e-18
wide 2497.938226676868 0.0 -0.36354184670612555 -4.746886068566863e-18 -0.931577868829815 1.9878078703022717e-17
wide 2397.278507682682 0.0 -0.24091935260021552 8.10037095492973e-18 -0.9705451383334487 8.488818075353696e-18
wide -5796.532097583673 0.0 0.28944953997103234 -1.4927594814088902e-17 -0.9571932740103003 3.7373406642922613e-17
wide -5842.891090430149 0.0 0.45399615657731734 -2.0936617929542445e-17 0.891003641862941 -4.047742556758847e-17
wide -6198.08801100024 0.0 -0.27086790966702945 -2.409745926994518e-17 -0.9626165256801973 -1.8767548384051483e-17
wide -6276.839454028315 0.0 0.06262683333966945 -6.647288598833813e-18 0.9980370132143623 5.702244202382809e-18
wide -3726.752508773372 0.0 -0.733611772595682 5.4168368757719144e-17 0.6795688096940746 1.8134905081528352e-17
wide 4651.9596060943095 0.0 0.6736332694424737 -4.657200926725669e-17 -0.7390657740013697 3.6609183380468904e-17
wide 2686.008876430971 0.0 0.05281779960987977 -9.113231113995877e-19 -0.9986041658456921 -1.0541014756127494e-17
wide 6692.428546540446 0.0 0.7420976335009941 3.020310421819284e-17 0.6702918038826255 1.8490632816582558e-17
wide 6116.39884472063 0.0 0.2783269769749822 1.8778393565259533e-17 -0.9604863840200796 3.1917839352566833e-17
wide -5654.382646053511 0.0 0.46543887711954507 -6.084427160472173e-18 0.8850800255715282 4.497674372505566e-18
wide 1726.6046802247365 0.0 -0.9554790911827813 -5.2194922702602054e-17 0.29505881839478415 -2.099948223310155e-18
wide -1025.3425145568126 0.0 -0.925861612223686 1.8557774741303042e-18 0.37786277272385127 -1.0892883984834983e-17
wide -1631.556213739068 0.0 0.8770211291686536 1.8075654040684763e-18 -0.4804518071479592 -2.5191297438221495e-17
wide 4060.6376728082596 0.0 0.9916694005205605 2.445874477667426e-17 -0.128809161441227 1.2621311693033612e-17
wide 7647.71330497762 0.0 0.8804384713249089 4.59084035240928e-17 0.4741604140067551 6.186687480859714e-18
wide -6792.485220484563 0.0 -0.35405500199333734 -9.099693624626879e-18 0.9352246016671599 -3.5802702447602014e-17
wide -2042.000860432434 0.0 0.03435763777517516 -1.8223648956093344e-18 0.999409602078402 -1.13989936150253e-19
wide 5052.555230174343 0.0 0.7670581773107157 -1.6362782973853437e-17 0.641577549966302 -4.995430125614836e-17
wide -2866.3993693398825 0.0 -0.9541685997903767 2.165436109074539e-17 0.29926958277458127 1.0624709187493159e-17
wide 3732.600512339388 0.0 0.3787449790091108 1.9437942052465023e-18 0.9255010755668457 1.1067597288716666e-18
wide -7614.998916484838 0.0 0.21986474124210975 -6.32801455107629e-18 0.9755303662923774 1.6635793551693265e-17
wide 3494.070619780321 0.0 0.5807005980405461 3.9444351646679426e-17 0.8141172000611165 1.86723721471342e-17
wide 5456.54315098227 0.0 0.39244495928873824 -1.428102895613556e-17 -0.9197754910459729 -2.035215834715918e-17
wide 5042.2153632173195 0.0 0.040834437535786694 3.334935649951536e-18 -0.9991659265162799 4.5065606900245047e-17
wide -1615.5913980936712 0.0 -0.7261971559532304 -2.7053969346733915e-17 0.6874865021841807 -2.6131989972572053e-17
wide 9527.011370299999 0.0 0.9913468723212467 3.207436792614281e-17 -0.13126834629445763 5.009864568525258e-18
wide -5716.362653894127 0.0 0.9725560773560389 2.933924594127558e-17 0.2326685977905795 -4.37899296907128e-19
wide -707.6614268793328 -4.079966724597986e-16 0.7194984177334778 -3.898028704346308e-17 -0.6944940798012766 3.2892118555028396e-17
wide 6116.510041050884 -6.224056147290791e-14 0.17002544343343876 9.225935178321898e-18 -0.98543967272749 4.38484881440894e-17
wide -9786.984248487626 -2.91060801314594e-13 0.7974954785704508 -3.891207278480997e-17 -0.6033249221271136 -8.591568189993998e-18
wide 9463.594689967736 7.969642859931222e-13 0.8990598117464665 4.154160436237233e-18 0.4378258271303877 -3.5769034659735783e-19
wide -4886.428018495252 2.1198001143625924e-13 0.9494383786157283 3.211135864563645e-17 -0.31395344433775024 -4.715762820871704e-18
wide -5498.039334346258 4.268257710940817e-13 -0.24952582875070675 2.5612348516951653e-18 0.9683681432111824 -1.4036663241862864e-17
wide 6530.341475521709 3.150120913292321e-13 0.8571194153472195 1.1414315714952972e-17 -0.5151177611331613 -9.542739070936844e-18
wide -8649.76034207601 6.963313949594709e-13 0.81675637809865 -5.3303164045446715e-17 -0.5769826850393132 4.355087556498665e-17
wide -6500.922586726141 3.2861642916736523e-13 0.8234054585345265 8.54212660558278e-18 -0.5674534790232113 -1.1264118909262589e-17
wide -3851.079650633429 1.8936653884925563e-13 0.4907433265790903 -1.793491778929666e-17 0.8713041876509537 -4.735134598191032e-17
wide -99.77904537403992 -1.9483364150377023e-15 0.6830420100266914 5.416213858835893e-17 0.7303790882402762 -2.6418435371374305e-17
wide -674.6064236585589 -7.51975950012306e-15 -0.7419652156538731 2.6143972473725475e-17 -0.6704383780480512 -4.9937483921861934e-17
wide -161.23926441421463 -4.935657985151112e-15 0.8510801061765086 4.729879079742541e-17 -0.5250358586521331 -1.2950254187412721e-17
wide -9254.284833332207 -6.88335021045004e-13 0.7493792840702134 -1.2993869271878704e-17 0.6621409884657605 4.4450780059277475e-17
wide -2731.5782866317795 6.215039860817418e-14 0.9993330120734182 -3.029373569212109e-17 -0.036517543458856765 -3.414427315518532e-18
wide -6386.836840916887 1.8654194464665959e-13 -0.02102228243631783 -7.349535303319215e-19 -0.9997790074017195 -5.022978630369963e-17
wide -8912.408551627917 -1.1709524553620248e-13 -0.2857669014547519 -8.938524294732684e-18 -0.9582991589440899 -9.995215569806446e-18
wide -9475.591956040784 7.48673460599634e-13 -0.5214187888163009 1.6563477361665272e-17 0.8533009121460857 -3.725306894538728e-17
wide 8795.444708082428 -4.894708483249274e-13 -0.8493338242366023 -2.1890612070008358e-17 0.5278560930856329 -2.853497097865702e-18
wide -3648.0725491929534 1.6802970543538247e-13 0.6314939043189209 -3.1071635545289544e-17 -0.7753808411406911 1.1202487265973693e-17
wide -7250.577775782645 6.333539503272052e-14 0.21634446905521978 -4.412291352881267e-18 0.9763170953687204 2.698145330904263e-17
wide -7838.908220621657 -3.6134582099996416e-13 0.5928151036910019 1.085427854111183e-17 -0.8053385951485417 1.4579551225853672e-17
wide 1963.6620142830834 4.509411687975831e-14 -0.16583609874337527 -5.047615833969675e-18 -0.9861533290282893 2.0927255006537218e-18
wide -1319.2563416267221 -7.744778538817755e-14 0.21097556424654532 -2.821007622929587e-18 0.977491335660246 1.8830818298751535e-17
wide -5381.376156293023 -4.5469752153524683e-13 -0.17121160981529393 -1.2694131207342812e-17 -0.9852342790750105 5.4374175297174636e-17
wide -7511.541515764881 -1.1110145236958027e-13 -0.006518922141614233 3.4181705324150094e-19 -0.9999787516013086 -4.836785427465999e-18
wide 1462.976248108007 -1.2350891365334476e-14 -0.8446593418471596 2.619858004657893e-17 0.5353042090534346 -4.704685161246665e-19
wide 5770.393784761365 2.9981721617043114e-13 0.6532885349515837 3.495897343036192e-18 -0.7571090344863238 3.737708956762733e-17
wide 8498.85392893924 9.461035360726936e-14 -0.7485025068997921 2.872922332976089e-18 -0.6631319605966272 3.801358185710806e-17
wide 5303.3715921392195 3.6280709349820306e-13 0.35526063849479494 9.29752294242656e-18 0.9347672858718744 2.0842607038929976e-17
wide -4471.677602611799 -1.3019391439289702e-13 0.9288352447349127 -1.3661619372201426e-17 -0.3704930338592546 -7.942319930184618e-18
wide 2749.1386400732845 -4.345186049710341e-14 -0.24262247033673204 -1.0832700730521681e-17 -0.9701207846900826 -2.6560207990923663e-17
wide 5217.833560952904 -1.6532169173836038e-13 0.34462253617886746 6.885044393620467e-18 -0.9387413422011652 6.760988370425701e-18
wide 441.51726785048595 -1.489077957200431e-14 0.992383560435418 4.78466422980465e-18 -0.12318631814257258 5.653324972954902e-18
wide 5591.48249107381 -1.2909885815736971e-13 -0.5247592897902337 -1.0017961525443462e-17 0.8512506609564833 -5.3456957305914385e-17
wide -1576.5111463042795 -7.410693672914267e-15 0.5382554923427578 -1.1684956161018528e-17 0.8427817184555295 -2.0495604432475684e-17
wide -3827.9278149738084 2.0920106357481192e-13 -0.9947173010296075 2.9593430255257254e-17 0.1026522821586213 -1.928246024510404e-19
wide 3705.988216947564 -1.392068783502986e-13 -0.887141705983611 -3.752997169950799e-17 0.4614971218810452 -4.7345930624464625e-18
wide 2901.7495424999343 -2.029025302124216e-13 -0.8829312926489433 -5.3567560539991766e-17 0.4695022177383893 -1.167220141105948e-18
wide -2388.3661885232123 6.873360052198137e-14 -0.6858505408129115 -1.9976987404605596e-17 0.7277424239843633 -1.2262547280619286e-17
tiny 0.0 0.0 0.0 0.0 1.0 0.0
tiny 1e-08 0.0 1e-08 -1.6666666666666668e-25 1.0 -5e-17
tiny -1e-08 0.0 -1e-08 1.6666666666666668e-25 1.0 -5e-17
tiny 1e-12 0.0 1e-12 -1.6666666666666666e-37 1.0 -5e-25
tiny 1e-20 0.0 1e-20 -1.6666666665965e-61 1.0 -5.000000000043952e-41
tiny 9.313225746154785e-10 0.0 9.313225746154785e-10 -1.3463226115771934e-28 1.0 -4.336808689942018e-19
tiny 1e-100 0.0 1e-100 0.0 1.0 0.0
tiny 1e-300 0.0 1e-300 0.0 1.0 0.0
tiny 5e-324 0.0 5e-324 0.0 1.0 0.0
tiny 0.0001 0.0 9.999999983333334e-05 -5.1001428759619744e-21 0.999999995 -2.622068866855033e-17
tiny 0.1 0.0 0.09983341664682815 3.08001512929492e-18 0.9950041652780258 -5.50210156918377e-17
tiny -0.5 0.0 -0.479425538604203 5.103969860556013e-18 0.8775825618903728 -4.2623149864279997e-17
zero 1.5707963267948966 6.123233995736766e-17 1.0 0.0 -1.4973849048591698e-33 5.562271104316826e-50
zero 1.5707963267948966 0.0 1.0 -1.874699728327322e-33 6.123233995736766e-17 -1.4973849048591698e-33
zero 1.5707963267948966 6.124233995736766e-17 1.0 -5.000000000043952e-41 -1.0000000000000674e-20 -2.7529965190440717e-37
zero -1.5707963267948966 -6.123233995736766e-17 -1.0 0.0 -1.4973849048591698e-33 5.562271104316826e-50
zero -1.5707963267948966 0.0 -1.0 1.874699728327322e-33 6.123233995736766e-17 -1.4973849048591698e-33
zero -1.5707963267948966 -6.122233995736766e-17 -1.0 5.000000000043952e-41 9.99999999999768e-21 -2.7529965190440717e-37
octant 2.356194490192345 9.184850993605148e-17 0.7071067811865476 -4.833646656726456e-17 -0.7071067811865476 4.833646656726457e-17
octant 0.7853981633974483 0.0 0.7071067811865475 4.1036934489363755e-17 0.7071067811865476 -2.6687565161377232e-17
zero 3.141592653589793 1.2246467991473532e-16 -2.9947698097183397e-33 1.1124542208633653e-49 -1.0 0.0
zero 3.141592653589793 0.0 1.2246467991473532e-16 -2.99476980971834e-33 -1.0 7.498798913309288e-33
zero 3.141592653589793 1.2247467991473532e-16 -1.000000000000217e-20 -5.505993038088143e-37 -1.0 5.000000000043952e-41
zero -3.141592653589793 -1.2246467991473532e-16 2.9947698097183397e-33 -1.1124542208633653e-49 -1.0 0.0
zero -3.141592653589793 0.0 -1.2246467991473532e-16 2.99476980971834e-33 -1.0 7.498798913309288e-33
zero -3.141592653589793 -1.2245467991473532e-16 -9.999999999996182e-21 5.505993038088143e-37 -1.0 5.000000000043952e-41
octant 3.9269908169872414 1.5308084989341916e-16 -0.7071067811865476 4.833646656726456e-17 -0.7071067811865476 4.8336466567264573e-17
octant 2.356194490192345 0.0 0.7071067811865476 1.661023765039743e-17 -0.7071067811865475 2.26086832241091e-18
zero 4.71238898038469 1.8369701987210297e-16 -1.0 0.0 -7.8337969295008e-33 5.173596326540973e-49
zero 4.71238898038469 0.0 -1.0 1.6872297554945898e-32 -1.8369701987210297e-16 -7.833796929500799e-33
zero 4.71238898038469 1.8370701987210297e-16 -1.0 5.000000000043952e-41 9.999999999991343e-21 -6.787338133393065e-37
zero -4.71238898038469 -1.8369701987210297e-16 1.0 0.0 -7.8337969295008e-33 5.173596326540973e-49
zero -4.71238898038469 0.0 1.0 -1.6872297554945898e-32 -1.8369701987210297e-16 -7.833796929500799e-33
zero -4.71238898038469 -1.8368701987210297e-16 1.0 -5.000000000043952e-41 -1.000000000000701e-20 -6.787338133393065e-37
octant 5.497787143782138 2.143131898507868e-16 -0.7071067811865476 4.833646656726457e-17 0.7071067811865476 -4.833646656726457e-17
octant 3.9269908169872414 0.0 -0.7071067811865475 4.555867113418558e-17 -0.7071067811865477 5.1114262000343567e-17
zero 6.283185307179586 2.4492935982947064e-16 5.989539619436679e-33 -2.2249084417267306e-49 1.0 0.0
zero 6.283185307179586 0.0 -2.4492935982947064e-16 5.9895396194366814e-33 1.0 -2.999519565323715e-32
zero 6.283185307179586 2.449393598294706e-16 9.999999999980514e-21 -4.034341614348993e-37 1.0 -5.000000000043952e-41
zero -6.283185307179586 -2.4492935982947064e-16 -5.989539619436679e-33 2.2249084417267306e-49 1.0 0.0
zero -6.283185307179586 0.0 2.4492935982947064e-16 -5.9895396194366814e-33 1.0 -2.999519565323715e-32
zero -6.283185307179586 -2.449193598294706e-16 1.0000000000017838e-20 4.034341614348993e-37 1.0 -5.000000000043952e-41
octant 7.0685834705770345 2.755455298081545e-16 0.7071067811865476 -4.8336466567264555e-17 0.7071067811865476 -4.8336466567264573e-17
octant 5.497787143782138 0.0 -0.7071067811865477 7.816459188568912e-18 0.7071067811865474 2.2165828516555403e-17
zero 7.853981633974483 3.061616997868383e-16 1.0 0.0 -1.981287616837416e-32 9.623413209994434e-49
zero 7.853981633974483 0.0 1.0 -4.686749320818305e-32 3.061616997868383e-16 -1.9812876168374162e-32
zero 7.853981633974483 3.061716997868383e-16 1.0 -5.000000000043952e-41 -9.999999999994338e-21 1.2813450953049215e-37
zero -7.853981633974483 -3.061616997868383e-16 -1.0 0.0 -1.981287616837416e-32 9.623413209994434e-49
zero -7.853981633974483 0.0 -1.0 4.686749320818305e-32 3.061616997868383e-16 -1.9812876168374162e-32
zero -7.853981633974483 -3.061516997868383e-16 -1.0 5.000000000043952e-41 1.0000000000004015e-20 1.2813450953049215e-37
octant 8.639379797371932 -5.514005499346031e-16 0.7071067811865476 -4.8336466567264586e-17 -0.7071067811865476 4.833646656726455e-17
octant 7.0685834705770345 0.0 0.7071067811865474 -2.1131974295219273e-17 0.7071067811865477 3.5481343623205743e-17
zero 9.42477796076938 3.6739403974420594e-16 1.56675938590016e-32 -1.0347192653081946e-48 -1.0 0.0
zero 9.42477796076938 0.0 3.6739403974420594e-16 1.5667593859001593e-32 -1.0 6.748919021978359e-32
zero 9.42477796076938 3.6740403974420596e-16 -1.000000000000816e-20 -1.4716514237391502e-37 -1.0 5.000000000043952e-41
zero -9.42477796076938 -3.6739403974420594e-16 -1.56675938590016e-32 1.0347192653081946e-48 -1.0 0.0
zero -9.42477796076938 0.0 -3.6739403974420594e-16 -1.5667593859001593e-32 -1.0 6.748919021978359e-32
zero -9.42477796076938 -3.6738403974420596e-16 -9.999999999990192e-21 1.4716514237391502e-37 -1.0 5.000000000043952e-41
octant 10.210176124166829 -4.901682099772354e-16 -0.7071067811865476 4.8336466567264536e-17 -0.7071067811865476 4.833646656726459e-17
octant 8.639379797371932 0.0 0.7071067811865471 5.853675274048571e-18 -0.7071067811865479 -8.495694053937737e-18
zero 10.995574287564276 4.286263797015736e-16 -1.0 0.0 -1.844257310064121e-33 -4.7245094410376825e-50
zero 10.995574287564276 0.0 -1.0 9.186028668803878e-32 -4.286263797015736e-16 -1.844257310064108e-33
zero 10.995574287564276 4.2863637970157363e-16 -1.0 5.000000000043952e-41 1.0000000000021984e-20 4.224647942783222e-37
zero -10.995574287564276 -4.286263797015736e-16 1.0 0.0 -1.844257310064121e-33 -4.7245094410376825e-50
zero -10.995574287564276 0.0 1.0 -9.186028668803878e-32 -4.286263797015736e-16 -1.844257310064108e-33
zero -10.995574287564276 -4.2861637970157364e-16 1.0 -4.999999999910313e-41 -9.999999999976369e-21 4.224647942783222e-37
octant 11.780972450961725 -4.289358700198678e-16 -0.7071067811865476 4.833646656726457e-17 0.7071067811865476 -4.833646656726456e-17
octant 10.210176124166829 0.0 -0.7071067811865479 3.4802108757836904e-17 -0.7071067811865471 -4.915147808582326e-17
zero 12.566370614359172 4.898587196589413e-16 1.1979079238873359e-32 -4.449816883453461e-49 1.0 0.0
zero 12.566370614359172 0.0 -4.898587196589413e-16 1.1979079238873378e-32 1.0 -1.199807826129486e-31
zero 12.566370614359172 4.898687196589413e-16 9.999999999986503e-21 6.977644461827293e-37 1.0 -5.000000000043952e-41
zero -12.566370614359172 -4.898587196589413e-16 -1.1979079238873359e-32 4.449816883453461e-49 1.0 0.0
zero -12.566370614359172 0.0 4.898587196589413e-16 -1.1979079238873378e-32 1.0 -1.199807826129486e-31
zero -12.566370614359172 -4.898487196589413e-16 9.999999999962546e-21 -6.977644461827293e-37 1.0 -4.999999999910313e-41
octant 13.351768777756622 -3.677035300625001e-16 0.7071067811865476 -4.833646656726455e-17 0.7071067811865476 -4.833646656726458e-17
octant 11.780972450961725 0.0 -0.7071067811865472 1.857302156491771e-17 0.7071067811865478 3.2922390892904104e-17
zero 98.96016858807849 -1.471433100886589e-15 -1.0 0.0 -1.659831579057709e-32 -8.309196680159039e-50
zero 98.96016858807849 0.0 -1.0 1.0825576851923613e-30 1.471433100886589e-15 -1.659831579057762e-32
zero 98.96016858807849 -1.471423100886589e-15 -1.0 4.999999999910313e-41 9.999999999957927e-21 -7.117151586526843e-37
zero -98.96016858807849 1.471433100886589e-15 1.0 0.0 -1.659831579057709e-32 -8.309196680159039e-50
zero -98.96016858807849 0.0 1.0 -1.0825576851923613e-30 1.471433100886589e-15 -1.659831579057762e-32
zero -98.96016858807849 1.4714431008865889e-15 1.0 -5.000000000043952e-41 -9.999999999991122e-21 -7.117151586526843e-37
octant 99.74556675147593 1.2237183281924706e-15 -0.7071067811865476 4.8336466567264524e-17 0.7071067811865476 -4.8336466567264604e-17
octant 98.17477042468104 0.0 -0.7071067811865505 -1.1303844932996011e-17 -0.7071067811865446 -3.0455243949782375e-18
zero 100.53096491487338 3.91886975727153e-15 9.583263391098687e-32 -3.559853506762769e-48 1.0 0.0
zero 100.53096491487338 0.0 -3.91886975727153e-15 9.58326339109969e-32 1.0 -7.678770087228711e-30
zero 100.53096491487338 3.91887975727153e-15 9.999999999873142e-21 -4.3641550674827714e-37 1.0 -4.999999999910313e-41
zero -100.53096491487338 -3.91886975727153e-15 -9.583263391098687e-32 3.559853506762769e-48 1.0 0.0
zero -100.53096491487338 0.0 3.91886975727153e-15 -9.58326339109969e-32 1.0 -7.678770087228711e-30
zero -100.53096491487338 -3.9188597572715305e-15 9.999999999681476e-21 4.3641550674827714e-37 1.0 -4.999999999643037e-41
octant 101.31636307827083 6.61402118635059e-15 0.7071067811865476 -4.833646656726453e-17 0.7071067811865476 -4.8336466567264604e-17
octant 99.74556675147593 0.0 -0.7071067811865483 -3.980694432228642e-17 0.7071067811865467 -2.545757499430095e-17
zero 157.07963267948966 -9.82193361864236e-16 1.8270707569772643e-33 -8.844897804801e-50 1.0 0.0
zero 157.07963267948966 0.0 9.82193361864236e-16 1.8270707569771062e-33 1.0 -4.82351900045085e-31
zero 157.07963267948966 -9.82183361864236e-16 9.999999999976351e-21 4.46575347495213e-37 1.0 -4.999999999910313e-41
zero -157.07963267948966 9.82193361864236e-16 -1.8270707569772643e-33 8.844897804801e-50 1.0 0.0
zero -157.07963267948966 0.0 -9.82193361864236e-16 -1.8270707569771062e-33 1.0 -4.82351900045085e-31
zero -157.07963267948966 9.82203361864236e-16 9.999999999972698e-21 -4.46575347495213e-37 1.0 -4.999999999910313e-41
octant 157.8650308428871 1.7129580672148235e-15 0.7071067811865476 -4.833646656726459e-17 0.7071067811865476 -4.8336466567264536e-17
octant 156.29423451609222 0.0 -0.7071067811865449 -1.592335409607515e-17 0.7071067811865501 -1.5739847680981882e-18
zero 158.65042900628455 4.408109496293883e-15 1.0 0.0 -1.1425802045854122e-31 -1.908611608259628e-48
zero 158.65042900628455 0.0 1.0 -9.715714665658156e-30 4.408109496293883e-15 -1.142580204585555e-31
zero 158.65042900628455 4.408119496293883e-15 1.0 -4.999999999910313e-41 -9.999999999891567e-21 -7.218749993996202e-37
zero -158.65042900628455 -4.408109496293883e-15 -1.0 0.0 -1.1425802045854122e-31 -1.908611608259628e-48
zero -158.65042900628455 0.0 -1.0 9.715714665658156e-30 4.408109496293883e-15 -1.142580204585555e-31
zero -158.65042900628455 -4.4080994962938834e-15 -1.0 4.999999999643037e-41 9.999999999663052e-21 -7.218749993996202e-37
octant 159.435827169682 7.103260925372943e-15 0.7071067811865476 -4.8336466567264617e-17 -0.7071067811865476 4.833646656726451e-17
octant 157.8650308428871 0.0 0.7071067811865464 -3.8335404695397015e-17 0.7071067811865487 5.2684774023381463e-17
zero 1570.7963267948967 -6.666535247945037e-14 3.5681447810643255e-30 2.235422173965414e-46 1.0 0.0
zero 1570.7963267948967 0.0 6.666535247945037e-14 3.568144781014946e-30 1.0 -2.22213461060468e-27
zero 1570.7963267948967 -6.666534247945037e-14 1.0000000001767732e-20 -4.814483220545405e-38 1.0 -5.000000001781249e-41
zero -1570.7963267948967 6.666535247945037e-14 -3.5681447810643255e-30 -2.235422173965414e-46 1.0 0.0
zero -1570.7963267948967 0.0 -6.666535247945037e-14 -3.568144781014946e-30 1.0 -2.22213461060468e-27
zero -1570.7963267948967 6.666536247945037e-14 9.999999994631443e-21 4.814483220545405e-38 1.0 -4.999999994564784e-41
octant 1571.581724958294 7.813834610164872e-14 0.7071067811865476 -4.8336466567266533e-17 0.7071067811865476 -4.8336466567262595e-17
octant 1570.0109286314992 0.0 -0.7071067811865588 1.5321262061669678e-17 0.7071067811865362 2.967063138947733e-17
zero 1572.3671231216915 -4.43163076048424e-15 1.0 0.0 -3.2791688357658956e-31 7.098162383575687e-48
zero 1572.3671231216915 0.0 1.0 -9.819675598635065e-30 -4.43163076048424e-15 -3.2791688357657506e-31
zero 1572.3671231216915 -4.4316207604842406e-15 1.0 -5.000000000043952e-41 -1.0000000000105226e-20 -2.2715481969895313e-37
zero -1572.3671231216915 4.43163076048424e-15 -1.0 0.0 -3.2791688357658956e-31 7.098162383575687e-48
zero -1572.3671231216915 0.0 -1.0 9.819675598635065e-30 -4.43163076048424e-15 -3.2791688357657506e-31
zero -1572.3671231216915 4.431640760484241e-15 -1.0 5.00000000017759e-41 1.0000000000238254e-20 -2.2715481969895313e-37
octant 1573.152521285089 -8.700160762261721e-14 0.7071067811865476 -4.8336466567262533e-17 -0.7071067811865476 4.8336466567266595e-17
octant 1571.581724958294 0.0 0.7071067811864923 -1.1384239413869214e-17 0.7071067811866028 2.5733608737538427e-17
zero 4999.844708188156 4.746492041408047e-14 -1.0 0.0 1.4997989664859855e-30 -6.688641895924466e-47
zero 4999.844708188156 0.0 -1.0 1.1264593349574965e-27 -4.746492041408047e-14 1.4997989665038079e-30
zero 4999.844708188156 4.746493041408047e-14 -1.0 4.999999999643037e-41 9.999999999699386e-21 5.825204231567259e-37
zero -4999.844708188156 -4.746492041408047e-14 1.0 0.0 1.4997989664859855e-30 -6.688641895924466e-47
zero -4999.844708188156 0.0 1.0 -1.1264593349574965e-27 -4.746492041408047e-14 1.4997989665038079e-30
zero -4999.844708188156 -4.7464910414080467e-14 1.0 -5.000000002983993e-41 -1.0000000003010676e-20 5.825204231567259e-37
octant 5000.630106351553 4.196422944384116e-13 -0.7071067811865476 4.833646656724775e-17 0.7071067811865476 -4.8336466567281386e-17
octant 4999.059310024759 0.0 -0.7071067811867772 3.6080075556419186e-17 -0.7071067811863179 -5.042944480984966e-17
zero 9998.118620049518 -6.494249072205013e-13 1.0 0.0 -2.8327931176648036e-29 -1.9798623532981007e-45
zero 9998.118620049518 0.0 1.0 -2.108763550591784e-25 -6.494249072205013e-13 -2.8327931130998586e-29
zero 9998.118620049518 -6.494248972205014e-13 1.0 -5.000000013942328e-41 -1.0000000013905745e-20 6.148915746434833e-37
zero -9998.118620049518 6.494249072205013e-13 -1.0 0.0 -2.8327931176648036e-29 -1.9798623532981007e-45
zero -9998.118620049518 0.0 -1.0 2.108763550591784e-25 -6.494249072205013e-13 -2.8327931130998586e-29
zero -9998.118620049518 6.494249172205013e-13 -1.0 4.999999957279716e-41 9.999999957249881e-21 6.148915746434833e-37
octant 9998.904018212914 6.32247168576758e-13 0.7071067811865476 -4.8336466567253326e-17 -0.7071067811865476 4.83364665672758e-17
octant 9997.33322188612 0.0 0.7071067811866268 -4.623075781457017e-17 0.7071067811864683 -5.044217532884596e-17
zero 9999.689416376312 9.492984082816094e-14 -2.999597932971971e-30 1.3377283791848932e-46 -1.0 0.0
zero 9999.689416376312 0.0 9.492984082816094e-14 -2.9995979331145502e-30 -1.0 4.505837339829986e-27
zero 9999.689416376312 9.492985082816094e-14 -1.0000000001199186e-20 3.395919227390761e-37 -1.0 5.000000001246696e-41
zero -9999.689416376312 -9.492984082816094e-14 2.999597932971971e-30 -1.3377283791848932e-46 -1.0 0.0
zero -9999.689416376312 0.0 -9.492984082816094e-14 2.9995979331145502e-30 -1.0 4.505837339829986e-27
zero -9999.689416376312 -9.492983082816094e-14 -9.999999995199989e-21 -3.395919227390761e-37 -1.0 4.999999995232975e-41
octant 10000.47481453971 -4.4238748692043615e-13 -0.7071067811865476 4.8336466567266934e-17 -0.7071067811865476 4.8336466567262195e-17
octant 9998.904018212914 0.0 0.7071067811869945 4.213410582324376e-17 -0.7071067811861005 2.7784736777913615e-17
zero 1745.1547190691301 2.0067495028828707e-14 -1.0 0.0 4.679773198229416e-31 -2.2795849319294624e-47
zero 1745.1547190691301 0.0 -1.0 2.0135217836603242e-28 -2.0067495028828707e-14 4.6797731982428845e-31
zero 1745.1547190691301 2.0067505028828705e-14 -1.0 4.999999998707569e-41 9.999999998667564e-21 4.174611481331818e-37
zero -1745.1547190691301 -2.0067495028828707e-14 1.0 0.0 4.679773198229416e-31 -2.2795849319294624e-47
zero -1745.1547190691301 0.0 1.0 -2.0135217836603242e-28 -2.0067495028828707e-14 4.6797731982428845e-31
zero -1745.1547190691301 -2.0067485028828706e-14 1.0 -5.000000000845781e-41 -1.0000000000887054e-20 4.174611481331818e-37
octant 1745.9401172325277 -6.250248183330426e-14 -0.7071067811865476 4.833646656726486e-17 0.7071067811865476 -4.8336466567264265e-17
octant 1744.3693209057326 0.0 -0.707106781186475 1.5403034028406526e-17 -0.7071067811866201 -2.9752403348944066e-17
zero 3396.0616585305665 -5.590950598859767e-14 2.8787600590087145e-31 1.2006700289830302e-48 -1.0 0.0
zero 3396.0616585305665 0.0 -5.590950598859767e-14 2.878760059299991e-31 -1.0 1.5629364299445195e-27
zero 3396.0616585305665 -5.590949598859767e-14 -9.999999997911712e-21 6.367291274727866e-37 -1.0 4.99999999790574e-41
zero -3396.0616585305665 5.590950598859767e-14 -2.8787600590087145e-31 -1.2006700289830302e-48 -1.0 0.0
zero -3396.0616585305665 0.0 5.590950598859767e-14 -2.878760059299991e-31 -1.0 1.5629364299445195e-27
zero -3396.0616585305665 5.590951598859767e-14 -9.999999998487463e-21 -6.367291274727866e-37 -1.0 4.999999998440293e-41
octant 3396.847056693964 -1.3847948285073063e-13 -0.7071067811865476 4.83364665672648e-17 -0.7071067811865476 4.833646656726433e-17
octant 3395.276260367169 0.0 0.7071067811865663 4.069416157058185e-17 -0.7071067811865287 2.634479224309792e-17
zero 3678.804997353648 -2.2252336873629654e-13 -3.3836159307393926e-30 4.679260183750063e-47 -1.0 0.0
zero 3678.804997353648 0.0 -2.2252336873629654e-13 -3.383615928902957e-30 -1.0 2.4758324816874898e-26
zero 3678.804997353648 -2.2252335873629655e-13 -9.99999998896143e-21 7.3567316341292e-37 -1.0 4.999999988951978e-41
zero -3678.804997353648 2.2252336873629654e-13 3.3836159307393926e-30 -4.679260183750063e-47 -1.0 0.0
zero -3678.804997353648 0.0 2.2252336873629654e-13 3.383615928902957e-30 -1.0 2.4758324816874898e-26
zero -3678.804997353648 2.2252337873629655e-13 -1.0000000007437745e-20 -7.3567316341292e-37 -1.0 5.000000007394055e-41
octant 3679.590395517045 1.4965400528803463e-13 -0.7071067811865476 4.833646656725774e-17 -0.7071067811865476 4.833646656727139e-17
octant 3678.0195991902506 0.0 0.7071067811864485 2.1564885710451805e-17 -0.7071067811866465 7.215516396315348e-18
zero 4084.0704496667313 -8.238044626927816e-14 -5.8689529494761794e-30 -2.5956931336388264e-46 1.0 0.0
zero 4084.0704496667313 0.0 8.238044626927816e-14 -5.8689529495693595e-30 1.0 -3.393268963762712e-27
zero 4084.0704496667313 -8.238043626927815e-14 1.000000000495241e-20 -4.261031175446861e-37 1.0 -5.000000004988566e-41
zero -4084.0704496667313 8.238044626927816e-14 5.8689529494761794e-30 2.5956931336388264e-46 1.0 0.0
zero -4084.0704496667313 0.0 -8.238044626927816e-14 5.8689529495693595e-30 1.0 -3.393268963762712e-27
zero -4084.0704496667313 8.238045626927815e-14 1.000000000406854e-20 4.261031175446861e-37 1.0 -5.000000004053099e-41
octant 4084.855847830129 -1.6495042313141113e-13 0.7071067811865476 -4.833646656727321e-17 0.7071067811865476 -4.833646656725592e-17
octant 4083.2850515033338 0.0 -0.7071067811865477 2.5340401579835617e-17 0.7071067811865474 3.968977090782211e-17
zero 5334.424325795469 3.429481462896396e-13 1.4995184258740702e-29 -4.5437509982663706e-46 1.0 0.0
zero 5334.424325795469 0.0 -3.429481462896396e-13 1.4995184265463252e-29 1.0 -5.880671552175003e-26
zero 5334.424325795469 3.429481562896396e-13 1.0000000000572997e-20 5.4066828574686115e-37 1.0 -5.000000000578505e-41
zero -5334.424325795469 -3.429481462896396e-13 -1.4995184258740702e-29 4.5437509982663706e-46 1.0 0.0
zero -5334.424325795469 0.0 3.429481462896396e-13 -1.4995184265463252e-29 1.0 -5.880671552175003e-26
zero -5334.424325795469 -3.429481362896396e-13 1.0000000021069727e-20 -5.4066828574686115e-37 1.0 -5.000000021025155e-41
octant 5335.209723958867 -1.9436918145895748e-13 0.7071067811865476 -4.833646656726738e-17 0.7071067811865476 -4.833646656726175e-17
octant 5333.6389276320715 0.0 -0.7071067811865268 -4.464895387655569e-17 0.7071067811865682 -3.0299584549173285e-17
zero 6679.0259815319005 -4.5173466878115795e-14 -7.821713381042296e-31 -3.6713259746739664e-47 1.0 0.0
zero 6679.0259815319005 0.0 4.5173466878115795e-14 -7.821713381195934e-31 1.0 -1.0203210548941123e-27
zero 6679.0259815319005 -4.51734568781158e-14 9.999999997417416e-21 -3.017442532749738e-38 1.0 -4.999999997371187e-41
zero -6679.0259815319005 4.5173466878115795e-14 7.821713381042296e-31 3.6713259746739664e-47 1.0 0.0
zero -6679.0259815319005 0.0 -4.5173466878115795e-14 7.821713381195934e-31 1.0 -1.0203210548941123e-27
zero -6679.0259815319005 4.5173476878115793e-14 9.999999998981759e-21 3.017442532749738e-38 1.0 -4.999999998974846e-41
octant 6679.811379695298 3.2700390714621536e-13 0.7071067811865476 -4.8336466567265147e-17 0.7071067811865476 -4.833646656726398e-17
octant 6678.240583368503 0.0 -0.7071067811862524 -4.835604517211254e-17 0.7071067811868427 -3.400667596729109e-17
zero 8408.472737333082 -8.748168644821805e-13 1.0 0.0 3.7331674702852964e-29 2.0537762383329346e-46
zero 8408.472737333082 0.0 1.0 -3.8265227319121687e-25 -8.748168644821805e-13 3.7331674814436517e-29
zero 8408.472737333082 -8.748168544821804e-13 1.0 -5.000000049222822e-41 -1.0000000049220334e-20 -6.435557418666687e-37
zero -8408.472737333082 8.748168644821805e-13 -1.0 0.0 3.7331674702852964e-29 2.0537762383329346e-46
zero -8408.472737333082 0.0 -1.0 3.8265227319121687e-25 -8.748168644821805e-13 3.7331674814436517e-29
zero -8408.472737333082 8.748168744821805e-13 -1.0 5.00000002289609e-41 1.0000000022909488e-20 -6.435557418666687e-37
octant 8409.258135496479 4.0685521131507893e-13 0.7071067811865476 -4.83364665672783e-17 -0.7071067811865476 4.833646656725083e-17
octant 8407.687339169684 0.0 0.7071067811867862 1.2946613081442212e-17 0.7071067811863089 1.4027561660006504e-18
zero 8868.716061083986 7.613852918189564e-13 -9.354046699471037e-31 -4.859488931558107e-47 -1.0 0.0
zero 8868.716061083986 0.0 7.613852918189564e-13 -9.354047435105725e-31 -1.0 2.898537812991187e-25
zero 8868.716061083986 7.613853018189564e-13 -9.999999986513218e-21 -5.618422102145753e-38 -1.0 4.99999998654649e-41
zero -8868.716061083986 -7.613852918189564e-13 9.354046699471037e-31 4.859488931558107e-47 -1.0 0.0
zero -8868.716061083986 0.0 -7.613852918189564e-13 9.354047435105725e-31 -1.0 2.898537812991187e-25
zero -8868.716061083986 -7.613852818189564e-13 -9.999999984642408e-21 5.618422102145753e-38 -1.0 4.999999984675555e-41
octant 8869.501459247384 2.2406796407035934e-13 -0.7071067811865476 4.833646656725947e-17 -0.7071067811865476 4.833646656726966e-17
octant 8867.93066292059 0.0 0.7071067811861796 -1.8739218684501368e-17 -0.7071067811869154 -3.3088587821075264e-17
";

    /// x_hi x_lo sqrt_hi sqrt_lo
    const SQRT_REFERENCE: &str = "
5.075665547301392e+22 0.0 225292377751.6983 -1.464220045644864e-05
1.3379565781181135e+265 0.0 3.657808877071236e+132 2.4716949379227114e+115
3.277784633030473e+158 0.0 1.8104653084305352e+79 -3.8464936849610385e+62
1353.8325330245736 0.0 36.79446334741918 9.42239575453922e-16
1.3563393434869345e-22 0.0 1.1646198278781513e-11 -7.472658688802866e-28
5.524973616723701e-132 0.0 2.3505262425090473e-66 4.756284733194426e-83
2.733743970728921e-152 0.0 1.6534037530890394e-76 -1.007186692216625e-92
124896645727.45737 0.0 353407.19535326015 -1.9477367595855576e-11
2.160750239079199e+143 0.0 4.648387074114201e+71 2.7751430328652795e+55
3.176633993105147e+272 0.0 1.7823114186654213e+136 7.151384086340113e+119
6.236148393197854e+277 0.0 7.896928765791074e+138 4.460063541055963e+122
4.7519409460456164e+246 0.0 2.1798947098531197e+123 -1.2293018193956535e+107
7.286226499857451e-13 0.0 8.535939608418894e-07 8.764071767222374e-24
7.427825349056706e-82 0.0 2.72540370386787e-41 2.2992225236528526e-57
4.500583290119313e-282 0.0 2.1214578219043888e-141 -5.573300352268037e-158
6.69291569134707e+86 0.0 2.587067005577372e+43 -1.674669070727741e+27
1.5371402868995756e+117 0.0 3.92063806911525e+58 1.2677211019451017e+42
2.788337977313089e+153 0.0 5.280471548368658e+76 1.745372841396551e+60
9.397165863672978e+241 0.0 9.693898010435728e+120 3.2909865126818185e+104
6.574014652351426e-240 0.0 2.5639841365249172e-120 4.096192293786622e-137
2.239259412782568e+67 -9.254695970283939e+50 4.7320813737535917e+33 3.8283408969037544e+16
2.2420914949366136e+160 1.4252501947544231e+144 1.4973615111043204e+80 -1.8585618682654343e+63
1.0706772620954418e+155 -2.92635819564038e+138 3.272120508317873e+77 2.11016660179133e+61
6.058904559137051e+183 2.588427926979563e+167 7.783896555798421e+91 -6.063230234836753e+75
3.371779217767958e+102 1.0216642426258833e+85 1.8362405119613166e+51 -5.977656303361877e+34
9.571502085101653e+264 5.379118773928912e+248 3.093784427703659e+132 -2.6384303497303948e+116
4.5233451588886516e-200 1.241156064059702e-216 2.1268157322364935e-100 -1.0534809654363684e-116
4.908653449296762e+195 -4.467682428242441e+179 7.006178308676395e+97 -4.471490755069969e+81
3.2964593241460678e-226 3.4914448691253065e-243 1.8156154119598312e-113 8.872539103804855e-130
1.5738849397390523e-222 -3.5223211782084114e-239 1.2545457105020337e-111 -8.385720129575775e-128
3.6458912473571264e+287 2.2360946429668e+271 6.038121601423018e+143 -1.7647929131500048e+127
5.3675333964768155e-242 2.1239485119871567e-258 2.3167937751290715e-121 1.7368219399684193e-137
4.5459103497194117e-160 -1.2921806442660037e-176 2.1321140564518145e-80 7.708760547082302e-97
2.2362036132999523e+238 9.169121362396329e+221 1.4953941330966737e+119 8.230033870945523e+102
1.0058613499875857e+258 -2.446949798024005e+241 1.0029263931054889e+129 3.2684180649867546e+112
4.455804745690112e-236 -3.222771212342316e-252 2.1108777192651666e-118 1.3652127504046894e-135
2.631492729423715e-53 6.014547216671847e-70 5.1298077248798666e-27 -2.2761808214095398e-43
1.3956345000063697e-100 8.210688996460325e-117 1.1813697558369987e-50 -9.473400615830658e-67
3.1816991550047196e-159 5.183477915320411e-176 5.640655241197355e-80 3.039110366941364e-96
1.5527435372936213e-71 1.3943133715056848e-88 3.9404866923942545e-36 1.884463880864948e-52
0.8912278163977596 3.318819091210081e-17 0.9440486303140107 4.93794103830162e-17
1.2153623463029026 8.429824240950223e-17 1.1024347356206183 3.29236567313007e-17
2.307849181778257 9.002344391059266e-17 1.5191606833308506 -8.500770943005165e-18
3.0276091697311416 -1.3716100426291215e-16 1.7400026349782178 7.933196200767547e-17
3.29915720030313 7.77455069971627e-17 1.816358224663607 4.1825264093404454e-17
1.1211082931460845 -1.0548627604344954e-16 1.0588240142469778 6.780965005034483e-17
2.5624145533312372 -1.733923692119604e-16 1.6007543700803184 3.396455710693839e-17
1.8389416410912027 -1.7675716397127643e-17 1.3560758242411088 -1.7126259392150814e-18
2.0323130587805514 -9.906089125193327e-17 1.425592178282608 4.0740774518528243e-17
1.5981653796781363 -3.385915062244089e-17 1.2641856587060842 7.644856982216081e-17
0.0 0.0 0.0 0.0
1.0 0.0 1.0 0.0
2.0 0.0 1.4142135623730951 -9.667293313452913e-17
4.0 0.0 2.0 0.0
1.0000000000000002 0.0 1.0 1.1102230246251565e-16
0.9999999999999999 0.0 0.9999999999999999 5.551115123125783e-17
1.7976931348623157e+308 0.0 1.3407807929942596e+154 7.442828536787015e+137
2.2250738585072014e-308 0.0 1.4916681462400413e-154 0.0
5e-324 0.0 2.2227587494850775e-162 0.0
1.0715086071862673e+301 0.0 3.273390607896142e+150 0.0
9.332636185032189e-302 0.0 3.054936363499605e-151 0.0
1e-320 0.0 9.99994433575849e-161 -1.4140498498069067e-177
2.0 1e-25 1.4142135623730951 -9.66729330991738e-17
";

    /// op a_hi a_lo b_hi b_lo result_hi result_lo
    const ARITHMETIC_REFERENCE: &str = "
add -1.0680727672091165e+17 -2.8355671860635 -1.1295620886475643e-11 7.570085675990639e-28 -1.0680727672091165e+17 -2.8355671860747953
sub -1.0680727672091165e+17 -2.8355671860635 -1.1295620886475643e-11 7.570085675990639e-28 -1.0680727672091165e+17 -2.8355671860522045
mul -1.0680727672091165e+17 -2.8355671860635 -1.1295620886475643e-11 7.570085675990639e-28 1206454.5057563134 -1.1166006235364041e-10
div -1.0680727672091165e+17 -2.8355671860635 -1.1295620886475643e-11 7.570085675990639e-28 9.455635754276514e+27 -247733521520.9492
add -22.125809627895435 -1.4118685697380403e-15 23.77994720503628 1.561276490613426e-15 1.6541375771408442 -7.26366840496456e-17
sub -22.125809627895435 -1.4118685697380403e-15 23.77994720503628 1.561276490613426e-15 -45.905756832931715 -2.9731450603514662e-15
mul -22.125809627895435 -1.4118685697380403e-15 23.77994720503628 1.561276490613426e-15 -526.1505848200369 -3.4178372238815524e-14
div -22.125809627895435 -1.4118685697380403e-15 23.77994720503628 1.561276490613426e-15 -0.930439812886106 -1.0715656597565147e-17
add -5.0549002694702585e-11 -3.075007279605429e-27 2.687933484454267e-13 -1.6866394207160142e-30 -5.028020934625716e-11 5.078900342981324e-28
sub -5.0549002694702585e-11 -3.075007279605429e-27 2.687933484454267e-13 -1.6866394207160142e-30 -5.0817796043148015e-11 -1.955560579384621e-28
mul -5.0549002694702585e-11 -3.075007279605429e-27 2.687933484454267e-13 -1.6866394207160142e-30 -1.3587235694886005e-23 -5.2818995814419675e-40
div -5.0549002694702585e-11 -3.075007279605429e-27 2.687933484454267e-13 -1.6866394207160142e-30 -188.05897908952753 -1.1442399472920748e-14
add -119240269882.94327 1.1736346949274222e-06 55623891.436865516 -3.117548735348447e-09 -119184645991.50641 7.555664717755794e-06
sub -119240269882.94327 1.1736346949274222e-06 55623891.436865516 -3.117548735348447e-09 -119295893774.38013 -5.20839532790095e-06
mul -119240269882.94327 1.1736346949274222e-06 55623891.436865516 -3.117548735348447e-09 -6.632607826871381e+18 309.2703905065962
div -119240269882.94327 1.1736346949274222e-06 55623891.436865516 -3.117548735348447e-09 -2143.6880233071056 4.1260516510400296e-14
add 49651778.11563806 3.3104149538448532e-09 -6.550289948656626 1.6575928771024128e-16 49651771.56534812 -1.5319336246009418e-09
sub 49651778.11563806 3.3104149538448532e-09 -6.550289948656626 1.6575928771024128e-16 49651784.66592801 7.021829353668202e-10
mul 49651778.11563806 3.3104149538448532e-09 -6.550289948656626 1.6575928771024128e-16 -325233543.12379307 2.6482372022511082e-09
div 49651778.11563806 3.3104149538448532e-09 -6.550289948656626 1.6575928771024128e-16 -7580088.592234143 -3.924874418205062e-10
add 86794959.28959906 -6.618038264424423e-09 8.23675316538247e-07 -2.7502919866063536e-24 86794959.28959988 -2.5065873877985625e-09
sub 86794959.28959906 -6.618038264424423e-09 8.23675316538247e-07 -2.7502919866063536e-24 86794959.28959823 4.1716720527973716e-09
mul 86794959.28959906 -6.618038264424423e-09 8.23675316538247e-07 -2.7502919866063536e-24 71.49086556678476 -3.3933253179492653e-15
div 86794959.28959906 -6.618038264424423e-09 8.23675316538247e-07 -2.7502919866063536e-24 105375209802792.2 0.003661709950753145
add -4.575384949360676e-17 1.1476209805325506e-33 -1.7395836109983873e-05 -1.20949133255898e-22 -1.7395836110029626e-05 -6.387638517280481e-22
sub -4.575384949360676e-17 1.1476209805325506e-33 -1.7395836109983873e-05 -1.20949133255898e-22 1.739583610993812e-05 -3.9686558521625213e-22
mul -4.575384949360676e-17 1.1476209805325506e-33 -1.7395836109983873e-05 -1.20949133255898e-22 7.959264671916518e-22 3.4535568424325335e-38
div -4.575384949360676e-17 1.1476209805325506e-33 -1.7395836109983873e-05 -1.20949133255898e-22 2.630160988200364e-12 1.8232723773302237e-28
add 705308.1021520164 -5.2013562424498955e-11 7.586427283739465e+17 -23.661255649776592 7.586427283746518e+17 4.440896366534501
sub 705308.1021520164 -5.2013562424498955e-11 7.586427283739465e+17 -23.661255649776592 -7.586427283732412e+17 51.76340766608769
mul 705308.1021520164 -5.2013562424498955e-11 7.586427283739465e+17 -23.661255649776592 5.350768629608558e+23 -13631028.485669006
div 705308.1021520164 -5.2013562424498955e-11 7.586427283739465e+17 -23.661255649776592 9.29697307800938e-13 -3.175257607805372e-29
add 1.1672985834136168e-12 -9.279120645634637e-30 -0.0010739065458323846 3.605243050022e-21 -0.001073906544665086 -9.257245112991378e-20
sub 1.1672985834136168e-12 -9.279120645634637e-30 -0.0010739065458323846 3.605243050022e-21 0.0010739065469996833 -9.978293722995778e-20
mul 1.1672985834136168e-12 -9.279120645634637e-30 -0.0010739065458323846 3.605243050022e-21 -1.2535695896687528e-15 -5.817961266960235e-32
div 1.1672985834136168e-12 -9.279120645634637e-30 -0.0010739065458323846 3.605243050022e-21 -1.0869647716960733e-09 -8.967267023248326e-26
add 1.1979814351593767e-13 -7.572159638381988e-30 -4.911797399758214e+16 0.381376841048362 -4.911797399758214e+16 0.3813768410484818
sub 1.1979814351593767e-13 -7.572159638381988e-30 -4.911797399758214e+16 0.381376841048362 4.911797399758214e+16 -0.3813768410482422
mul 1.1979814351593767e-13 -7.572159638381988e-30 -4.911797399758214e+16 0.381376841048362 -5884.24209817444 4.2606277956153605e-14
div 1.1979814351593767e-13 -7.572159638381988e-30 -4.911797399758214e+16 0.381376841048362 -2.438987885001828e-30 -1.0790587912577807e-46
add -2.3799590724828688e-06 6.668187004246798e-23 -2162405435.77328 -8.269828411634245e-08 -2162405435.7732825 -7.847156558358615e-08
sub -2.3799590724828688e-06 6.668187004246798e-23 -2162405435.77328 -8.269828411634245e-08 2162405435.7732778 8.692500264909875e-08
mul -2.3799590724828688e-06 6.668187004246798e-23 -2162405435.77328 -8.269828411634245e-08 5146.436435254889 3.6466149755491277e-13
div -2.3799590724828688e-06 6.668187004246798e-23 -2162405435.77328 -8.269828411634245e-08 1.100607237250951e-15 4.5830667938928226e-32
add 114489388577524.75 -0.0009065569375552897 -8.928608984263773 -8.794932440205403e-16 114489388577515.83 -0.007640541201329421
sub 114489388577524.75 -0.0009065569375552897 -8.928608984263773 -8.794932440205403e-16 114489388577533.67 0.0058274273262188415
mul 114489388577524.75 -0.0009065569375552897 -8.928608984263773 -8.794932440205403e-16 -1022230983456153.8 -0.04423579628860439
div 114489388577524.75 -0.0009065569375552897 -8.928608984263773 -8.794932440205403e-16 -12822757585118.416 -0.0003820913815356503
add 5.76021416654824e+17 -0.2187059150438344 -146960566555174.94 -0.006215969791845612 5.758744560882688e+17 24.83757811516432
sub 5.76021416654824e+17 -0.2187059150438344 -146960566555174.94 -0.006215969791845612 5.761683772213792e+17 -25.27498994525199
mul 5.76021416654824e+17 -0.2187059150438344 -146960566555174.94 -0.006215969791845612 -8.465243373950742e+31 1946062758580545.2
div 5.76021416654824e+17 -0.2187059150438344 -146960566555174.94 -0.006215969791845612 -3919.564480166605 1.1870631712966915e-13
add 2.4736273434022238e-08 8.442891855568314e-26 -1990342.3266146174 -6.086779885149411e-11 -1990342.3266145927 -4.642592139436581e-12
sub 2.4736273434022238e-08 8.442891855568314e-26 -1990342.3266146174 -6.086779885149411e-11 1990342.3266146423 -1.1573763809031798e-10
mul 2.4736273434022238e-08 8.442891855568314e-26 -1990342.3266146174 -6.086779885149411e-11 -0.04923365201844718 3.1531412923954243e-18
div 2.4736273434022238e-08 8.442891855568314e-26 -1990342.3266146174 -6.086779885149411e-11 -1.2428150224839102e-14 5.353540870226191e-31
add 3.559644249200754e-06 1.4813796594357086e-22 -2127386974188357.5 0.003970774618726025 -2127386974188357.5 0.003974334262975226
sub 3.559644249200754e-06 1.4813796594357086e-22 -2127386974188357.5 0.003970774618726025 2127386974188357.5 -0.003967214974476824
mul 3.559644249200754e-06 1.4813796594357086e-22 -2127386974188357.5 0.003970774618726025 -7572740808.49418 -4.3470020116148327e-07
div 3.559644249200754e-06 1.4813796594357086e-22 -2127386974188357.5 0.003970774618726025 -1.6732471771191664e-21 -3.0472817198449994e-38
add -7329751.368115557 -2.706114911626105e-10 -5.0698258281240504e+16 -2.597455881548351 -5.069825828857026e+16 -1.9655714391766312
sub -7329751.368115557 -2.706114911626105e-10 -5.0698258281240504e+16 -2.597455881548351 5.069825827391075e+16 3.2293403239200704
mul -7329751.368115557 -2.706114911626105e-10 -5.0698258281240504e+16 -2.597455881548351 3.716056279979985e+23 26813808.942612093
div -7329751.368115557 -2.706114911626105e-10 -5.0698258281240504e+16 -2.597455881548351 1.4457599958276537e-10 -1.2603029502514152e-26
add -1.0112202756637395e-12 5.052315817562666e-29 2.6129153746402532e-08 -1.0295457443529526e-24 2.612814252612687e-08 -7.958409319555551e-25
sub -1.0112202756637395e-12 5.052315817562666e-29 2.6129153746402532e-08 -1.0295457443529526e-24 -2.6130164966678196e-08 1.2632505567503501e-24
mul -1.0112202756637395e-12 5.052315817562666e-29 2.6129153746402532e-08 -1.0295457443529526e-24 -2.64223300542974e-20 1.4902820176048066e-36
div -1.0112202756637395e-12 5.052315817562666e-29 2.6129153746402532e-08 -1.0295457443529526e-24 -3.8700842954126076e-05 -3.110426774905701e-21
add 9.876211245143628e-10 -3.428414120932592e-26 8.61575705107913e-13 -2.286415597391851e-29 9.884827002194706e-10 7.79763004402381e-26
sub 9.876211245143628e-10 -3.428414120932592e-26 8.61575705107913e-13 -2.286415597391851e-29 9.867595488092548e-10 6.025057027936698e-26
mul 9.876211245143628e-10 -3.428414120932592e-26 8.61575705107913e-13 -2.286415597391851e-29 8.50910366732932e-22 -6.139463608682915e-38
div 9.876211245143628e-10 -3.428414120932592e-26 8.61575705107913e-13 -2.286415597391851e-29 1146.296394686132 2.296265182466427e-15
add -2.8324083193408256e+17 -10.998883734102392 243.22819215587236 1.3592940656330679e-14 -2.8324083193408234e+17 8.229308421769986
sub -2.8324083193408256e+17 -10.998883734102392 243.22819215587236 1.3592940656330679e-14 -2.832408319340828e+17 1.7729241100252302
mul -2.8324083193408256e+17 -10.998883734102392 243.22819215587236 1.3592940656330679e-14 -6.889215549605219e+19 -1650.7959399878268
div -2.8324083193408256e+17 -10.998883734102392 243.22819215587236 1.3592940656330679e-14 -1164506587100594.8 0.092316562801408
add -5.10418733830891e-09 2.729347298798947e-25 -0.22301941924990895 -8.553846344418367e-18 -0.2230194243540963 3.694753271625978e-18
sub -5.10418733830891e-09 2.729347298798947e-25 -0.22301941924990895 -8.553846344418367e-18 0.22301941414572163 -6.953129655166201e-18
mul -5.10418733830891e-09 2.729347298798947e-25 -0.22301941924990895 -8.553846344418367e-18 1.1383328959323917e-09 3.183791444701483e-26
div -5.10418733830891e-09 2.729347298798947e-25 -0.22301941924990895 -8.553846344418367e-18 2.288673943944455e-08 -5.8280336009234745e-25
add 108788861.37639596 -3.832807095886199e-09 -2.6397272827816128e-08 -8.709807305422064e-25 108788861.37639593 -4.2775753600701517e-10
sub 108788861.37639596 -3.832807095886199e-09 -2.6397272827816128e-08 -8.709807305422064e-25 108788861.37639599 -7.237856655765383e-09
mul 108788861.37639596 -3.832807095886199e-09 -2.6397272827816128e-08 -8.709807305422064e-25 -2.871729254380192 -1.4127384268699585e-16
div 108788861.37639596 -3.832807095886199e-09 -2.6397272827816128e-08 -8.709807305422064e-25 -4121215933403532.5 -0.010718291609823164
add 9.440288386169444e-05 -5.362710351307236e-22 -3.1945814197189895e-16 1.7489665355650835e-32 9.440288386137498e-05 1.4918799198203387e-21
sub 9.440288386169444e-05 -5.362710351307236e-22 -3.1945814197189895e-16 1.7489665355650835e-32 9.44028838620139e-05 -2.564421990081786e-21
mul 9.440288386169444e-05 -5.362710351307236e-22 -3.1945814197189895e-16 1.7489665355650835e-32 -3.0157769875245867e-20 -2.0568385826631974e-36
div 9.440288386169444e-05 -5.362710351307236e-22 -3.1945814197189895e-16 1.7489665355650835e-32 -295509400007.71234 -1.401442740792026e-06
add 1748018927853.2234 -9.221789066977021e-05 3.1050555466960976e+16 -1.0829899310210287 3.1052303485888828e+16 0.14030652296330154
sub 1748018927853.2234 -9.221789066977021e-05 3.1050555466960976e+16 -1.0829899310210287 -3.104880744803312e+16 -1.693713614994641
mul 1748018927853.2234 -9.221789066977021e-05 3.1050555466960976e+16 -1.0829899310210287 5.427695867660417e+28 -1733389182482.1868
div 1748018927853.2234 -9.221789066977021e-05 3.1050555466960976e+16 -1.0829899310210287 5.629589878716292e-05 -3.347981624385492e-21
add 8200363917361474.0 0.12958271404195187 -891991.6804608557 3.129481095185322e-11 8200363916469482.0 0.4491218583592012
sub 8200363917361474.0 0.12958271404195187 -891991.6804608557 3.129481095185322e-11 8200363918253466.0 -0.18995643027529746
mul 8200363917361474.0 0.12958271404195187 -891991.6804608557 3.129481095185322e-11 -7.314656391037827e+21 -158430.47290728605
div 8200363917361474.0 0.12958271404195187 -891991.6804608557 3.129481095185322e-11 -9193318835.804255 2.8056094874833467e-07
add 161.7836516851023 7.684969344378225e-15 161.7836516851023 7.605194346417296e-15 323.5673033702046 1.5290163690795523e-14
sub 161.7836516851023 7.684969344378225e-15 161.7836516851023 7.605194346417296e-15 7.977499796092945e-17 0.0
mul 161.7836516851023 7.684969344378225e-15 161.7836516851023 7.605194346417296e-15 26173.949952566512 -1.2745335487678622e-12
div 161.7836516851023 7.684969344378225e-15 161.7836516851023 7.605194346417296e-15 1.0 4.930967815969718e-19
add 44.41385367871749 2.3002658718900592e-15 44.41420931106665 2.1901454673779904e-15 88.82806298978414 -2.6150160183329523e-15
sub 44.41385367871749 2.3002658718900592e-15 44.41420931106665 2.1901454673779904e-15 -0.0003556323491621392 1.9673896165875548e-20
mul 44.41385367871749 2.3002658718900592e-15 44.41420931106665 2.1901454673779904e-15 1972.606193597646 7.719537816294703e-14
div 44.41385367871749 2.3002658718900592e-15 44.41420931106665 2.1901454673779904e-15 0.9999919928249387 4.869407064627303e-17
add -515.0625055872624 2.7471283572382173e-14 -515.0625055872624 2.7471283561008844e-14 -1030.1250111745248 5.494256713339102e-14
sub -515.0625055872624 2.7471283572382173e-14 -515.0625055872624 2.7471283561008844e-14 1.1373329525820657e-23 0.0
mul -515.0625055872624 2.7471283572382173e-14 -515.0625055872624 2.7471283561008844e-14 265289.3846618287 1.3377834147242938e-11
div -515.0625055872624 2.7471283572382173e-14 -515.0625055872624 2.7471283561008844e-14 1.0 -2.2081454973805653e-26
add 390.5884021712384 2.8260185213253534e-14 390.5884021712384 2.8260185211678312e-14 781.1768043424768 5.6520370424931846e-14
sub 390.5884021712384 2.8260185213253534e-14 390.5884021712384 2.8260185211678312e-14 1.5752226990942834e-24 0.0
mul 390.5884021712384 2.8260185213253534e-14 390.5884021712384 2.8260185211678312e-14 152559.2999106811 -8.524673151900962e-12
div 390.5884021712384 2.8260185213253534e-14 390.5884021712384 2.8260185211678312e-14 1.0 4.032947958356653e-27
add 358.85019468964833 1.9011647826283557e-14 358.85019468493044 2.2742779925793228e-14 717.7003893745788 4.1754427752076785e-14
sub 358.85019468964833 1.9011647826283557e-14 358.85019468493044 2.2742779925793228e-14 4.7178863474772445e-09 -4.054681943963583e-25
mul 358.85019468964833 1.9011647826283557e-14 358.85019468493044 2.2742779925793228e-14 128773.46222710551 -2.5944022951901267e-13
div 358.85019468964833 1.9011647826283557e-14 358.85019468493044 2.2742779925793228e-14 1.0000000000131473 -3.021489263733158e-17
add 658.5398864857029 -3.8912439160400253e-14 658.5398864857029 -3.888941849425168e-14 1317.0797729714059 -7.780185765465193e-14
sub 658.5398864857029 -3.8912439160400253e-14 658.5398864857029 -3.888941849425168e-14 -2.3020666148575962e-17 0.0
mul 658.5398864857029 -3.8912439160400253e-14 658.5398864857029 -3.888941849425168e-14 433674.78209260246 1.7873054019991592e-13
div 658.5398864857029 -3.8912439160400253e-14 658.5398864857029 -3.888941849425168e-14 1.0 -3.4957132621724266e-20
add 455.25740489502664 2.4433416096302164e-15 455.2574048949527 -6.283244410190672e-15 910.5148097899793 5.300351606024756e-14
sub 455.25740489502664 2.4433416096302164e-15 455.2574048949527 -6.283244410190672e-15 7.396201452393105e-11 -2.9716390299675515e-27
mul 455.25740489502664 2.4433416096302164e-15 455.2574048949527 -6.283244410190672e-15 207259.30471172056 -1.5272615173430073e-12
div 455.25740489502664 2.4433416096302164e-15 455.2574048949527 -6.283244410190672e-15 1.0000000000001625 -7.468153523867953e-17
add -764.7925074255548 1.8942228598444368e-14 -764.7925074255548 1.894222859858933e-14 -1529.5850148511097 3.78844571970337e-14
sub -764.7925074255548 1.8942228598444368e-14 -764.7925074255548 1.894222859858933e-14 -1.4496107994341313e-25 0.0
mul -764.7925074255548 1.8942228598444368e-14 -764.7925074255548 1.894222859858933e-14 584907.5794142673 8.306255045708512e-12
div -764.7925074255548 1.8942228598444368e-14 -764.7925074255548 1.894222859858933e-14 1.0 1.895430179244057e-28
add 1.0 0.0 3.0 0.0 4.0 0.0
sub 1.0 0.0 3.0 0.0 -2.0 0.0
mul 1.0 0.0 3.0 0.0 3.0 0.0
div 1.0 0.0 3.0 0.0 0.3333333333333333 1.850371707708594e-17
add 2.0 0.0 3.0 0.0 5.0 0.0
sub 2.0 0.0 3.0 0.0 -1.0 0.0
mul 2.0 0.0 3.0 0.0 6.0 0.0
div 2.0 0.0 3.0 0.0 0.6666666666666666 3.700743415417188e-17
";
}
