//! Ranges of magnitude (format.md §12): the largest size of each kind of number a file
//! holds, the smallest pitch radius and `friction_smoothing`, and the message when a number
//! is beyond its range. Invariant: within them every quantity derived from a file stays
//! finite in f64 (why, below).

// Ranges of magnitude (format.md §12, "Ranges of magnitude"). Within them every quantity
// derived from a file stays finite in f64: a length is at most 1e6 m and a radius at least
// 1e-9 m, so couplings (ratios of radii) stay below 1e15, squares of positions (sums of at
// most 12 links) below 1e15 and the structure matrix's pseudo-inverse near 1e9; a mass is at
// most 1e12 kg and an inertia entry at most 1e24 kg·m² (the heaviest body at the largest
// length), so the mass matrix's entries stay near 1e24 · (coupling)², far below f64's
// 1.8e308, and every number of a file fits f32 (3.4e38; products generated code folds may
// not, which code generation reports). An angle is at most 1e3 rad: f64
// computes its distance to the nearest multiple of π/2 to within 1e-13 rad there (the
// rounding of k·π/2 and of π/2 itself), a tenth of the right-angle snapping's 1e-12 rad, so
// snapping decides correctly; at 1e4 rad that error exceeds the tolerance.

/// A kind of number with a range of magnitude.
#[derive(Clone, Copy)]
pub(super) enum Range {
    Length,
    Mass,
    Inertia,
    Angle,
    Torque,
    Damping,
    Force,
    Moment,
    Acceleration,
    Ratio,
}

impl Range {
    pub(super) fn max(self) -> f64 {
        match self {
            Range::Length => MAX_LENGTH,
            Range::Mass => MAX_MASS,
            Range::Inertia => MAX_INERTIA,
            Range::Angle => MAX_ANGLE,
            Range::Torque => MAX_FRICTION_TORQUE,
            Range::Damping => MAX_VISCOUS,
            Range::Force => MAX_FORCE,
            Range::Moment => MAX_MOMENT,
            Range::Acceleration => MAX_ACCELERATION,
            Range::Ratio => MAX_RATIO,
        }
    }

    /// What the number is, its unit, and what would fix it.
    pub(super) fn described(self) -> (&'static str, &'static str, &'static str) {
        match self {
            Range::Length => (
                "a length",
                "m",
                "check its unit (metres) and its exponent; larger numbers overflow the squares \
                 and products derived from them",
            ),
            Range::Mass => (
                "a mass",
                "kg",
                "check its unit (kilograms) and its exponent; larger numbers overflow the \
                 products derived from them",
            ),
            Range::Inertia => (
                "an inertia entry",
                "kg·m²",
                "check its unit (kg·m²) and its exponent; larger numbers overflow the products \
                 derived from them",
            ),
            Range::Angle => (
                "an angle",
                "rad",
                "reduce it modulo 2π (f64 cannot resolve a larger angle to the 1e-12 rad that \
                 right angles are recognised within), or check its unit (radians)",
            ),
            Range::Torque => (
                "a friction torque",
                "N·m",
                "check its unit (N·m) and its exponent",
            ),
            Range::Damping => (
                "a viscous friction coefficient",
                "N·m·s/rad",
                "check its unit (N·m·s/rad) and its exponent",
            ),
            Range::Force => (
                "a force",
                "N",
                "check its unit (newtons) and its exponent; larger tensions overflow the moments \
                 and the tension distribution derived from them",
            ),
            Range::Moment => (
                "a moment",
                "N·m",
                "check its unit (N·m) and its exponent",
            ),
            Range::Acceleration => (
                "an acceleration",
                "m/s²",
                "check its unit (m/s²) and its exponent",
            ),
            Range::Ratio => (
                "a coupling ratio",
                "rad/rad",
                "check the ratio; a pulley turning 1e15 times faster than its joint is beyond what \
                 f64 resolves",
            ),
        }
    }
}

/// What is wrong with the first number of `field` beyond `range`, if one is.
pub(super) fn beyond(field: &str, values: &[f64], range: Range) -> Option<String> {
    let &v = values.iter().find(|v| v.abs() > range.max())?;
    let (what, unit, fix) = range.described();
    Some(format!(
        "`{field}` is {} {unit}, beyond the range of {what} (at most {:e} {unit} in size; \
         format.md §12, ranges of magnitude): {fix}",
        shown(v),
        range.max()
    ))
}

/// A number as a message shows it: plainly, or with an exponent when very large or small.
pub(super) fn shown(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The largest size of a length (DH `a` and `d`, centres of mass, pulley heights and
/// origins, tendon exits, the external wrench's point), m.
pub const MAX_LENGTH: f64 = 1e6;
/// The most links a mechanism may have: a position sums at most this many lengths, so it
/// stays within `3e7` m and its square below `1e15` (format.md §12).
pub const MAX_LINKS: usize = 30;
/// The smallest pitch radius, m (the largest is [`MAX_LENGTH`]).
pub const MIN_RADIUS: f64 = 1e-9;
/// The largest mass, kg.
pub const MAX_MASS: f64 = 1e12;
/// The largest size of an inertia tensor entry, kg·m².
pub const MAX_INERTIA: f64 = 1e24;
/// The largest size of an angle (DH `alpha` and `offset`, a placement's `rpy`), rad.
pub const MAX_ANGLE: f64 = 1e3;
/// The largest Coulomb friction torque of a bearing, N·m: a tenth of the heaviest body's
/// weight at the largest length (`1e12 kg · 9.81 m/s² · 1e6 m ≈ 1e19 N·m`); anything beyond
/// is a mistake of unit or exponent.
pub const MAX_FRICTION_TORQUE: f64 = 1e18;
/// The largest viscous friction coefficient of a bearing, N·m·s/rad: the same torque at
/// 1 rad/s.
pub const MAX_VISCOUS: f64 = 1e18;
/// The largest size of a force: a tendon's `floor`, `max_tension`, the `tension_floor`, a
/// loop's `pretension`, the external wrench's `force`, N. Times the largest length it is a
/// moment of 1e21 N·m, and the distribution's sums of tensions stay far from overflow.
pub const MAX_FORCE: f64 = 1e15;
/// The largest size of the external wrench's `moment`, N·m: the largest force at the
/// largest length.
pub const MAX_MOMENT: f64 = 1e21;
/// The largest size of a `gravity` component, m/s² (10⁵ g; with the largest mass and length
/// its generalized forces stay near 1e24).
pub const MAX_ACCELERATION: f64 = 1e6;
/// The largest size of an explicit `coupling` ratio, the bound derived couplings keep
/// (ratios of radii within their range).
pub const MAX_RATIO: f64 = 1e15;
/// The largest capstan coefficient `mu` of a guide (dry steel on steel is about 0.5, a
/// tendon in a sheath rarely above 1).
pub(super) const MAX_MU: f64 = 10.0;

/// The smallest `friction_smoothing`, rad/s: below it `ω / v` overflows `f32` at ordinary
/// rates.
pub const MIN_SMOOTHING: f64 = 1e-9;
/// The largest `friction_smoothing`, rad/s: above it friction would reach its Coulomb
/// value at no speed a mechanism turns.
pub const MAX_SMOOTHING: f64 = 1e6;
