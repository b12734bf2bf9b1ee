//! Double-double arithmetic and functions against 50-digit references. The reference
//! tables (`data/double_double_*.txt`) were computed with mpmath at 50
//! significant digits and stored exactly as double-doubles: `hi` the double nearest to
//! the true value, `lo` the double nearest to the remainder (representation error
//! ≤ 2⁻¹⁰⁷ relative, far below the tolerances tested). Arguments: 80 in [−π, π] and
//! 80 in [−1e4, 1e4] (half of them with a non-zero low word), tiny ones down to the
//! smallest subnormal, the double and the double-double nearest to ±kπ/2 (k up to
//! 6366, i.e. |x| ≤ 1e4) with and without a 1e-20 offset, and the octant boundaries
//! kπ/2 ± π/4 of the argument reduction.

use tendyn_core::double_double::DoubleDouble;
use tendyn_core::{Numeric, Real};
use twofloat::TwoFloat;

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

/// `e^x` of the `f64` arguments below, to 60 digits (Python's `decimal`, which evaluates
/// `exp` of the exact binary value), split into a double-double `(hi, lo)`. The capstan law
/// takes `e^{±μβ}` with `μβ` up to `10 · 3π/2 ≈ 47`.
const EXP_REFERENCE: [(f64, f64, f64); 8] = [
    (0.25, 1.2840254166877414, 8.968972781793724e-17),
    (1.0, std::f64::consts::E, 1.4456468917292502e-16),
    (2.5, 12.182493960703473, 2.0334002173348147e-16),
    (7.0, 1096.6331584284585, 9.869752640434095e-14),
    (31.4, 43335791368684.4, -0.003388689368486366),
    (-0.75, 0.4723665527410147, 1.7984004434373214e-17),
    (-12.5, 3.726653172078671e-06, 5.469656173191849e-23),
    (47.0, 2.5813128861900675e+20, -15192.714199784727),
];

#[test]
fn exp_agrees_with_a_60_digit_reference_to_1e30() {
    for (x, hi, lo) in EXP_REFERENCE {
        let x = DoubleDouble::from(x);
        assert_close(&format!("exp {x:?}"), x.exp(), dd(hi, lo), 1e-30);
    }
    assert_eq!(DoubleDouble::from(0.0).exp(), DoubleDouble::ONE);
    assert!(DoubleDouble::from(f64::NAN).exp().is_nan());
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
const SIN_COS_REFERENCE: &str = include_str!("data/double_double_sin_cos.txt");

/// x_hi x_lo sqrt_hi sqrt_lo
const SQRT_REFERENCE: &str = include_str!("data/double_double_sqrt.txt");

/// op a_hi a_lo b_hi b_lo result_hi result_lo
const ARITHMETIC_REFERENCE: &str = include_str!("data/double_double_arithmetic.txt");
