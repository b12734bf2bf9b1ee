//! Sine and cosine of `f64` angles, several at once (`Real::sin_cos_many` and
//! `Real::sin_cos_array` for `f64`; one angle alone is the C library's).
//!
//! Every spinning body needs the sine and cosine of its angle, and they are a large part of
//! a dynamics call: the C library's `sincos` took 37 % of the runtime solver's `Q` over the
//! four scale benchmarks (`perf`, `bench/examples/runtime_q_minimum.rs`), about 11 ns an
//! angle. The angles depend on `q` alone, so they can all be computed first and together;
//! this module computes them with arithmetic alone (no table, no branch on the value), so
//! that where the target has 256-bit vectors (AVX2 and beyond) a block of angles becomes
//! vector code: 8 angles in 36 ns against the C library's 89 ns with `-C
//! target-cpu=x86-64-v3`, 44 ns against 90 ns with `-C target-cpu=native` on this AVX-512
//! machine (`bench/examples/sin_cos_minimum.rs`, the minimum over 300 passes of 1,024
//! seeded blocks, one core, 2026-12-04). With the baseline x86-64's 128-bit vectors a block
//! may lose to the library, so there every angle is computed alone (105 ns for 8 in that
//! benchmark against the library's 92, but inlined into the recursion, where the library's
//! calls are not: the runtime `Q` of the chains still gains 19-20 %, as the README's scale
//! section says).
//!
//! The method is fdlibm's (Sun Microsystems, 1993, as in musl and the `libm` crate):
//! `x = n π/2 + y`, `n` the nearest integer to `x · 2/π`, `y` in `[−π/4, π/4]`, then
//! `sin y` and `cos y` by fdlibm's minimax polynomials, which take `y` as a sum of two
//! doubles `y₀ + y₁`, and the quadrant `n mod 4` swaps them and sets their signs. The
//! reduction subtracts `n π/2` in three pieces of π/2 (33, 33 and 53 bits; fdlibm's
//! `pio2_1`, `pio2_2`, `pio2_3` with `pio2_3t`): for `|n| < 2^20` the products with the
//! first two are exact, the first difference is exact (Sterbenz), the second is taken
//! with its rounding error (Knuth's two-sum), and the rest is below `|n| · 2^-120`: the
//! smallest `|y|` over the doubles below 1024 is 6.2e-19 (at x = 45.553093477052, n = 29),
//! where half an ulp of `y` is `2^-114` and the reduction's error about `2^-117`. Beyond
//! `1024` rad (and for infinities and NaN) the library's function is called, whose
//! reduction is exact at any size.
//!
//! Accuracy, against [`crate::DoubleDouble`]: at most 0.77 ulp over the tests' 220,000
//! seeded angles up to 1150 rad in size, 0.50 ulp at the doubles nearest to the multiples
//! of π/2 (the tests assert less than one ulp); a review's scans of 1.8 billion angles
//! below 1024 rad (strided, random, and around every multiple of π/4) found at most 0.805
//! ulp, at `cos(687.2233929791201)`, confirmed with 300-bit arithmetic. The C library's
//! `sincos` is within one ulp too, so the two differ by at most one ulp.

// fdlibm's constants, digit for digit.
#![allow(clippy::excessive_precision, clippy::unreadable_literal)]

/// Beyond this magnitude (rad) the library's function computes the angle.
const REDUCED_BELOW: f64 = 1024.0;
/// The first 33 bits of π/2.
const PIO2_1: f64 = 1.57079632673412561417e+00;
/// The next 33 bits.
const PIO2_2: f64 = 6.07710050630396597660e-11;
/// The next 33 bits, and the rest.
const PIO2_3: f64 = 2.02226624871116645580e-21;
const PIO2_3T: f64 = 8.47842766036889956997e-32;
/// Below this magnitude `sin x = x` and `cos x = 1` to the last bit.
const TINY: f64 = 7.450580596923828125e-9; // 2^-27
/// `1.5 · 2^52`: adding it rounds a double below `2^51` to an integer, in its low bits.
const TO_INTEGER: f64 = 6755399441055744.0;

const S1: f64 = -1.66666666666666324348e-01;
const S2: f64 = 8.33333333332248946124e-03;
const S3: f64 = -1.98412698298579493134e-04;
const S4: f64 = 2.75573137070700676789e-06;
const S5: f64 = -2.50507602534068634195e-08;
const S6: f64 = 1.58969099521155010221e-10;
const C1: f64 = 4.16666666666666019037e-02;
const C2: f64 = -1.38888888888741095749e-03;
const C3: f64 = 2.48015872894767294178e-05;
const C4: f64 = -2.75573143513906633035e-07;
const C5: f64 = 2.08757232129817482790e-09;
const C6: f64 = -1.13596475577881948265e-11;

/// Sine and cosine of `x`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if reducible(x) {
        reduced(x)
    } else {
        library(x)
    }
}

/// Whether the target has 256-bit vectors (AVX2 and beyond): there a block of angles
/// becomes vector code and beats the C library; with the 128-bit vectors of the baseline
/// x86-64 it may not (9 angles in 117 ns against the library's 103, in a scratch crate),
/// so there each angle is computed alone, inlined.
const WIDE: bool = cfg!(target_feature = "avx2");

/// `[(sin angles[i], cos angles[i])]`: where the target has wide vectors (AVX2 and
/// beyond), all at once, which the compiler makes vector code of; elsewhere one at a time.
#[inline]
pub fn sin_cos_array<const N: usize>(angles: [f64; N]) -> [(f64, f64); N] {
    // Fewer than four angles fill no vector: one at a time.
    if WIDE && N >= 4 {
        together(angles)
    } else {
        angles.map(sin_cos)
    }
}

/// [`sin_cos_array`]'s vector form, the same arithmetic as [`sin_cos`] lane by lane.
/// Never inlined: in the one long block of a generated function the compiler's vectoriser
/// gives up on it (arm6's `Q` gained nothing inlined, measured), on its own it does not.
#[inline(never)]
fn together<const N: usize>(angles: [f64; N]) -> [(f64, f64); N] {
    // Sines and cosines in arrays of their own, not pairs: vectors hold one or the other.
    let (mut sines, mut cosines) = ([0.0; N], [0.0; N]);
    for i in 0..N {
        (sines[i], cosines[i]) = reduced(angles[i]);
    }
    if !angles.iter().all(|&a| reducible(a)) {
        for i in 0..N {
            if !reducible(angles[i]) {
                (sines[i], cosines[i]) = library(angles[i]);
            }
        }
    }
    core::array::from_fn(|i| (sines[i], cosines[i]))
}

/// `out[i] = (sin angles[i], cos angles[i])` for every `i` (up to the shorter length):
/// blocks of 8 and then of 4 by [`sin_cos_array`], the last few one at a time.
#[inline]
pub fn sin_cos_many(angles: &[f64], out: &mut [(f64, f64)]) {
    let count = angles.len().min(out.len());
    let (angles, out) = (&angles[..count], &mut out[..count]);
    let mut at = 0;
    while count - at >= 8 {
        let block: [f64; 8] = core::array::from_fn(|i| angles[at + i]);
        out[at..at + 8].copy_from_slice(&sin_cos_array(block));
        at += 8;
    }
    if count - at >= 4 {
        let block: [f64; 4] = core::array::from_fn(|i| angles[at + i]);
        out[at..at + 4].copy_from_slice(&sin_cos_array(block));
        at += 4;
    }
    for (o, &a) in out[at..].iter_mut().zip(&angles[at..]) {
        *o = sin_cos(a);
    }
}

/// Within the range [`reduced`] serves (false for NaN).
#[inline(always)]
fn reducible(x: f64) -> bool {
    x.abs() < REDUCED_BELOW
}

/// The C library's `sincos` (`libm`'s without `std`), whose reduction is exact at any size.
#[inline(never)]
#[cold]
fn library(x: f64) -> (f64, f64) {
    #[cfg(feature = "std")]
    {
        x.sin_cos()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::sincos(x)
    }
}

/// Sine and cosine of `|x| < 1024` (any other `x` gives a finite or NaN pair of no
/// meaning, which the callers replace): branch-free, so that it vectorises.
#[inline(always)]
fn reduced(x: f64) -> (f64, f64) {
    let shifted = x * core::f64::consts::FRAC_2_PI + TO_INTEGER;
    let n = shifted - TO_INTEGER;
    let quadrant = shifted.to_bits();
    // x − n π/2 as y₀ + y₁ (see the module documentation).
    let y = x - n * PIO2_1;
    let b = -(n * PIO2_2);
    let hi = y + b;
    let bb = hi - y;
    let lo = (y - (hi - bb)) + (b - bb);
    let lo = lo - n * PIO2_3 - n * PIO2_3T;
    let y0 = hi + lo;
    let y1 = (hi - y0) + lo;
    let (s, c) = (kernel_sin(y0, y1), kernel_cos(y0, y1));

    // Quadrant 1: (cos, −sin); 2: (−sin, −cos); 3: (−cos, sin). Swapped and signed by
    // masks, not branches.
    let odd = (quadrant & 1).wrapping_neg();
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let (s, c) = ((sb & !odd) | (cb & odd), (cb & !odd) | (sb & odd));
    let sin_sign = (quadrant & 2) << 62;
    let cos_sign = (quadrant.wrapping_add(1) & 2) << 62;
    let (s, c) = (s ^ sin_sign, c ^ cos_sign);
    // Below `2^-27`, `x` and `1` (what the polynomials give, but for the sign of a zero:
    // `y₀` is `+0` for `x = −0`). A mask again: a branch here keeps the compiler from
    // making vectors of the whole.
    let tiny = u64::from(x.abs() < TINY).wrapping_neg();
    let s = (s & !tiny) | (x.to_bits() & tiny);
    let c = (c & !tiny) | (1f64.to_bits() & tiny);
    (f64::from_bits(s), f64::from_bits(c))
}

/// fdlibm's `__kernel_sin(x, y, 1)`: `sin(x + y)` for `|x| ≤ π/4`, `|y|` below half an ulp
/// of `x`.
#[inline(always)]
fn kernel_sin(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// fdlibm's `__kernel_cos(x, y)` (musl's form): `cos(x + y)` for `|x| ≤ π/4`.
#[inline(always)]
fn kernel_cos(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::real::Real;
    use crate::DoubleDouble;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The error of `computed` against `exact`, in ulps of `exact` rounded to f64.
    fn ulps(computed: f64, exact: DoubleDouble) -> f64 {
        let rounded = exact.to_f64();
        let ulp = if rounded == 0.0 {
            f64::MIN_POSITIVE
        } else {
            let next = f64::from_bits(rounded.abs().to_bits() + 1);
            next - rounded.abs()
        };
        ((DoubleDouble::from(computed) - exact).to_f64() / ulp).abs()
    }

    fn worst_over(angles: impl IntoIterator<Item = f64>) -> (f64, f64) {
        let angles: Vec<f64> = angles.into_iter().collect();
        let mut batch = vec![(0.0, 0.0); angles.len()];
        sin_cos_many(&angles, &mut batch);
        // The vector form, whichever form this target's `sin_cos_many` takes.
        let vector: Vec<(f64, f64)> = angles
            .chunks(7)
            .flat_map(|c| together::<7>(core::array::from_fn(|i| *c.get(i).unwrap_or(&0.0))))
            .collect();
        let mut worst = (0.0, 0.0);
        for ((&x, &pair), &lane) in angles.iter().zip(&batch).zip(&vector) {
            let one = sin_cos(x);
            assert_eq!(one.0.to_bits(), pair.0.to_bits(), "batched sine at {x}");
            assert_eq!(one.1.to_bits(), pair.1.to_bits(), "batched cosine at {x}");
            assert_eq!(one.0.to_bits(), lane.0.to_bits(), "vector sine at {x}");
            assert_eq!(one.1.to_bits(), lane.1.to_bits(), "vector cosine at {x}");
            let (s, c) = (DoubleDouble::from(x).sin(), DoubleDouble::from(x).cos());
            let e = ulps(one.0, s).max(ulps(one.1, c));
            if e > worst.0 {
                worst = (e, x);
            }
        }
        worst
    }

    #[test]
    fn every_angle_is_within_one_ulp_of_the_exact_sine_and_cosine() {
        // Seeded angles over the whole reduced range and past it, and small ones.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut angles: Vec<f64> = (0..200_000)
            .map(|_| rng.random_range(-1150.0..1150.0))
            .collect();
        angles.extend((0..20_000).map(|i| rng.random_range(-0.5..0.5) * 10f64.powi(-(i % 30))));
        let worst = worst_over(angles);
        assert!(worst.0 < 1.0, "{} ulp at {}", worst.0, worst.1);
    }

    #[test]
    fn the_doubles_nearest_multiples_of_a_right_angle_keep_their_digits() {
        // Where `x − n π/2` cancels most: the doubles on either side of `n π/2` for every
        // `n` the reduction handles, the sine or cosine there as small as it gets.
        let half_pi = DoubleDouble::FRAC_PI_2;
        let mut angles = Vec::new();
        for n in -652..=652 {
            let x = (half_pi * DoubleDouble::from(n as f64)).to_f64();
            for d in -2i64..=2 {
                let bits = (x.abs().to_bits() as i64 + d) as u64;
                angles.push(f64::from_bits(bits).copysign(x));
            }
        }
        let worst = worst_over(angles);
        assert!(worst.0 < 1.0, "{} ulp at {}", worst.0, worst.1);
    }

    #[test]
    fn zeros_infinities_and_nan_are_the_library_s() {
        for x in [0.0, -0.0, 1e-310, -1e-310, 1023.9, 1024.0, -1e300] {
            let (s, c) = sin_cos(x);
            let (ls, lc) = x.sin_cos();
            assert!((s - ls).abs() <= ls.abs() * 2.3e-16 && (c - lc).abs() <= lc.abs() * 2.3e-16);
            assert_eq!(
                s.is_sign_negative(),
                ls.is_sign_negative(),
                "the sign of sin {x}"
            );
        }
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan());
            let mut out = [(0.0, 0.0); 9];
            let angles = [0.5, x, 0.25, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5];
            sin_cos_many(&angles, &mut out);
            for block in [out, together(angles)] {
                assert!(block[1].0.is_nan() && block[1].1.is_nan());
                assert_eq!(block[0], sin_cos(0.5));
                assert_eq!(block[2], sin_cos(0.25));
            }
        }
    }
}
