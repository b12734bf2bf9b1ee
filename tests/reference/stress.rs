//! The stress suite (issue 6): mechanisms and states at the edges of what the solver is
//! asked to do, and one library function, [`measure_case`], that measures how far the
//! runtime solver in `f64` and `f32` (and, when given, generated code) is from the
//! double-double reference on them. Nothing here prints; `tests/stress.rs` asserts what
//! must hold, and a report can reuse the figures.
//!
//! # Cases
//!
//! Every case is a seeded generator ([`Arm`], [`near_rank_loss`]) or a shipped file (the
//! paper's examples, `tests/mechanisms/stress/*.ron`), with a name, a description and a
//! [`Range`] its states are drawn from ([`StressCase::states`]). [`cases`] lists them all:
//!
//! - the paper's three examples in the benchmark protocol's range (the baseline);
//! - pulley inertia against link inertia from 1e-9 to 1e9 ([`Arm::pulley_ratio`]);
//! - drum against idler radius from 1e-3 to 1e3 ([`Arm::drum_radius`] against
//!   [`Arm::idler_radius`]), and a structure matrix `σ_min/σ_max` from 1e-2 down to 1e-8,
//!   and past the 1e-10 the validator accepts;
//! - joint speeds to 1e3 rad/s, angles to 1e4 rad, accelerations to 1e6 rad/s²;
//! - chains of 2 to 12 links, motor-driven with 2.5 explicitly coupled pulleys per link
//!   (30 at 12 links), and of 2 to 11 links with a tendon-driven proximal block over idlers
//!   (the block is at most four joints; the 12-link chain of `bench/mechanisms`, with 13
//!   unknowns, is checked by `tests/lagrangian_agreement.rs`);
//! - a distal link from 1e-3 of its nominal mass down to zero (near-singular `M`);
//! - a loop whose pretension the dynamics nearly exhausts and exceeds, and a tendon whose
//!   `max_tension` some states need more than.
//!
//! # The error measure
//!
//! Per output vector, the max-norm relative error against the double-double run,
//! `‖x − x_ref‖∞ / max(‖x_ref‖∞, floor)`, as [`crate::measure::max_rel`] with a floor
//! relative to the output's own scale: [`SCALE_FLOOR`] (1 %) of its typical size (the
//! median over the case's states of `‖x_ref‖∞`), so that a state where an output passes
//! near zero — a cancellation in the problem itself — does not read as a large relative
//! error; for forward dynamics also the size of the terms it sums,
//! `‖M⁻¹(|A||T| + |motor columns||τ| + |h + g − Q_ext|)‖∞`, as in the generated-code
//! agreement test (balancing tensions make `q̈` a small difference of large terms).
//! States are drawn in `f64` and rounded to `f32`, so the `f32` run sees the very state the
//! others do; forward dynamics gets the `f64` run's torques and tensions, rounded likewise.
//! The outputs: `actuation` (motor torques, then tendon tensions),
//! `delivered_forces` (inverse dynamics' `Q`), `pulley_moments`, `loop_sides`,
//! `segment_tensions`, `bearings`, `base_reaction`, `generalized_forces` (the expanded
//! tree's `M q̈ + h + g − Q_ext`), `mass_matrix`, `bias`, `gravity`, `forward_dynamics`.
//!
//! # The condition rule
//!
//! Each output's error is bounded by `C · u · κ_o` with `u` the unit round-off and
//!
//! ```text
//! κ_o = κ_θ + κ_T·[o depends on the tensions] + κ_M·[o is forward dynamics]
//! ```
//!
//! - `κ_θ = 1 + max |θ_b|` over the states and every body whose angle enters a rotation
//!   (links, spinning pulleys), `θ_b = c_b·q + offset_b`: forming the angle rounds it by
//!   `u|θ|`, which `sin`/`cos` turn into an error `u|θ|` relative to the output's scale;
//! - `κ_T = cond₂(E) · max_k p_k / min_k p_k`: the tension system's condition number times
//!   the spread of its positive null vector `p` over the tendons (1 without a redundant
//!   routing). `x₀ = E⁺ b`, `E⁺` and `p` are computed in the working precision, and the
//!   floor lifts every tension by `λ p` with `λ` set by the tendon of smallest `p_k`. It
//!   applies to `actuation`, `loop_sides`, `segment_tensions` and `bearings`; not to the
//!   delivered `Q` or the base reaction, which do not depend on the tensions (the
//!   null-space part and the tendons' internal pulls cancel in them);
//! - `κ_M = max cond₂(D^-½ M D^-½)` over the states, `D = diag M`: forward dynamics solves
//!   `M q̈ = rhs` by Cholesky, whose error follows the diagonally scaled condition number
//!   (van der Sluis), not `cond₂(M)`: a very light link makes `M` badly scaled, not hard.
//!
//! `C = ROUNDING_GROWTH · (bodies + unknowns)` ([`CaseFigures::bound`], [`ROUNDING_GROWTH`]
//! = 8): an output is a sum over the bodies on its path of terms each formed by a few
//! three-term products (a rotation, a cross product, an accumulation), each adding a
//! few `u` relative to the terms. A case is **well conditioned** when `C u κ_o ≤ 1e-9` in
//! `f64` for every output ([`CaseFigures::well_conditioned`]); then the issue's target,
//! 1e-9, applies.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write;
use tendyn_core::model::{BodyKind, Model};
use tendyn_core::output::Output;
use tendyn_core::{Data, DoubleDouble, Error, InverseDynamics, Numeric};

/// `q`, `q̇`, `q̈`.
pub type State = [Vec<f64>; 3];

/// Bounds of a case's states: each coordinate uniform in `[−bound, bound]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    pub q: f64,
    pub qd: f64,
    pub qdd: f64,
}

impl Range {
    /// The benchmark protocol's range (`crate::measure::random_state`).
    pub const PROTOCOL: Range = Range {
        q: PI,
        qd: 3.0,
        qdd: 10.0,
    };
}

/// What kind of stress a case applies (for grouping in a report).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    PaperExample,
    PulleyInertia,
    RadiusRatio,
    RankLoss,
    ExtremeState,
    MotorChain,
    TendonChain,
    LightDistal,
    TensionBound,
    BearingFriction,
    CapstanFriction,
}

/// One case of the stress suite.
#[derive(Clone, Debug)]
pub struct StressCase {
    pub name: String,
    pub description: String,
    pub group: Group,
    /// The mechanism, as RON text.
    pub text: String,
    pub range: Range,
    /// Seed of the state draws.
    pub seed: u64,
}

impl StressCase {
    fn new(name: &str, group: Group, description: String, text: String, range: Range) -> Self {
        let seed = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
        });
        StressCase {
            name: name.to_string(),
            description,
            group,
            text,
            range,
            seed,
        }
    }

    /// The validated mechanism, or the validator's error (some cases are meant to fail).
    pub fn model(&self) -> Result<Model<f64>, Error> {
        tendyn_core::parse(&self.text)
    }

    /// `count` states drawn uniformly in the case's range, each number rounded to the
    /// nearest `f32` (so that every precision sees the same state).
    pub fn states(&self, dof: usize, count: usize) -> Vec<State> {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        (0..count)
            .map(|_| {
                let mut v = |s: f64| -> Vec<f64> {
                    (0..dof)
                        .map(|_| f64::from(rng.random_range(-s..s) as f32))
                        .collect()
                };
                [v(self.range.q), v(self.range.qd), v(self.range.qdd)]
            })
            .collect()
    }

    /// The same mechanism over another range of states.
    pub fn with_range(&self, name: &str, range: Range, what: &str) -> StressCase {
        StressCase::new(
            name,
            Group::ExtremeState,
            format!("{}; {what}", self.description),
            self.text.clone(),
            range,
        )
    }
}

// ---------------------------------------------------------------------------------------
// Generators.

/// A deterministic, fully parametric serial arm: links with DH parameters, a tendon-driven
/// proximal block over idlers, motors on the other joints, explicitly coupled pulleys.
///
/// - Links `1..=n`: `a_j = 0.3·0.93^(j−1)` m, offsets `0.1 j` rad, masses
///   `1.0·0.85^(j−1)` kg (the last one times `distal_scale`), slender-rod inertias with a
///   small product term, centre of mass off the axis. Joints `1..tendon_joints` have
///   parallel axes; with `spatial` the other links are twisted (±π/2, 0.6, −1.1).
/// - Tendon block (`p = tendon_joints ≥ 1`): `p + 1` open-ended tendons, tendon `k < p`
///   anchored Ccw on link `k + 1`'s drum, tendon `p` anchored Cw on link `p`'s; each passes
///   an idler on every joint axis below its anchor, all turning Cw (carried by the proximal
///   body of that joint), so that the structure matrix has a positive null vector.
///   Drums have radius `drum_radius`, idlers `idler_radius`; idlers have `pulley_ratio`
///   times link 1's mass and `I_zz`, and are slightly non-axisymmetric (their frames spin).
/// - Motors on joints `p+1..=n`.
/// - `gears` explicitly coupled pulleys, tilted and off-axis, spread over the links.
#[derive(Clone, Debug)]
pub struct Arm {
    pub name: String,
    pub links: usize,
    pub tendon_joints: usize,
    pub spatial: bool,
    pub gears: usize,
    pub pulley_ratio: f64,
    pub drum_radius: f64,
    pub idler_radius: f64,
    pub distal_scale: f64,
    pub floor: f64,
    pub gravity: [f64; 3],
    /// A second tendon ending on each tendon-driven link but the last, routed the other
    /// way round its drum and idlers (in planes of their own): `2p + 1` tendons on `p`
    /// joints, `p + 1` null directions.
    pub antagonists: bool,
    /// With `antagonists`, the second tendon on every `antagonist_every`-th link only (the
    /// first, then every `antagonist_every`-th after it): with 2, every other joint has
    /// no pair of tendons ending on its link.
    pub antagonist_every: usize,
}

impl Arm {
    pub fn new(name: &str, links: usize, tendon_joints: usize) -> Arm {
        Arm {
            name: name.to_string(),
            links,
            tendon_joints,
            spatial: false,
            gears: 0,
            pulley_ratio: 1e-3,
            drum_radius: 0.02,
            idler_radius: 0.015,
            distal_scale: 1.0,
            floor: 5.0,
            gravity: [0.0, -9.81, 0.0],
            antagonists: false,
            antagonist_every: 1,
        }
    }

    fn link_length(j: usize) -> f64 {
        0.3 * 0.93f64.powi(j as i32 - 1)
    }

    fn link_inertia_zz(&self, j: usize) -> (f64, [f64; 4]) {
        let a = Arm::link_length(j);
        let mut m = 0.85f64.powi(j as i32 - 1);
        if j == self.links {
            m *= self.distal_scale;
        }
        let xx = m * 0.02 * 0.02;
        let yy = m * a * a / 12.0;
        let zz = yy + 0.5 * xx;
        (m, [xx, yy, zz, -0.1 * xx])
    }

    /// The mechanism's RON text.
    pub fn ron(&self) -> String {
        let n = self.links;
        let p = self.tendon_joints.min(n);
        let mut s = String::new();
        let g = self.gravity;
        writeln!(
            s,
            "(\n  name: \"{}\",\n  gravity: ({:e}, {:e}, {:e}),\n  tension_floor: {:e},\n  links: [",
            self.name, g[0], g[1], g[2], self.floor
        )
        .unwrap();
        let twists = [FRAC_PI_2, -FRAC_PI_2, 0.6, -1.1];
        for j in 1..=n {
            let a = Arm::link_length(j);
            let planar = j < p.max(1) || !self.spatial;
            let alpha = if planar { 0.0 } else { twists[j % 4] };
            let d = if planar { 0.0 } else { 0.03 };
            let (m, [xx, yy, zz, xy]) = self.link_inertia_zz(j);
            writeln!(
                s,
                "    (name: \"l{j}\", dh: (a: {a:e}, alpha: {alpha:e}, d: {d:e}, offset: {:e}), mass: {m:e}, com: ({:e}, 0.01, 0.005), inertia: (xx: {xx:e}, yy: {yy:e}, zz: {zz:e}, xy: {xy:e})),",
                0.1 * j as f64,
                -a / 2.0
            )
            .unwrap();
        }
        writeln!(s, "  ],\n  pulleys: [").unwrap();
        let mut tendons = String::new();
        // Idler mass and zz inertia: `pulley_ratio` times link 1's; slightly
        // non-axisymmetric.
        let (r_i, r_d) = (self.idler_radius, self.drum_radius);
        let (m1, i1) = self.link_inertia_zz(1);
        let izz = self.pulley_ratio * i1[2];
        let mass = self.pulley_ratio * m1;
        let idler_inertia = format!(
            "mass: {mass:e}, inertia: (xx: {:e}, yy: {:e}, zz: {izz:e})",
            0.55 * izz,
            0.5 * izz
        );
        // Tendon `k`'s drum on link `anchor` and its idlers on the joints below, named with
        // `tag`, at height `zeta`, wound `turns` (drum, idlers): written to `s`, the route
        // returned.
        let routed = |s: &mut String,
                      tag: &str,
                      k: usize,
                      anchor: usize,
                      zeta: f64,
                      turns: [&str; 2]| {
            writeln!(
                s,
                "    (name: \"drum{tag}{k}\", carrier: \"l{anchor}\", at: Joint(joint: \"l{anchor}\", height: {zeta:e}), radius: {r_d:e}, fixed: true),"
            )
            .unwrap();
            let mut route = format!("(\"drum{tag}{k}\", {})", turns[0]);
            for j in (1..anchor).rev() {
                let carrier = if j == 1 {
                    "base".to_string()
                } else {
                    format!("l{}", j - 1)
                };
                writeln!(
                    s,
                    "    (name: \"idler{tag}{k}_{j}\", carrier: \"{carrier}\", at: Joint(joint: \"l{j}\", height: {zeta:e}), radius: {r_i:e}, {idler_inertia}),"
                )
                .unwrap();
                write!(route, ", (\"idler{tag}{k}_{j}\", {})", turns[1]).unwrap();
            }
            route
        };
        if p >= 1 {
            for k in 0..=p {
                let anchor = if k < p { k + 1 } else { p };
                let turn = if k < p { "Ccw" } else { "Cw" };
                let zeta = 0.012 * (k as f64 + 1.0) * if k % 2 == 0 { 1.0 } else { -1.0 };
                let route = routed(&mut s, "", k, anchor, zeta, [turn, "Cw"]);
                let y = 0.06 * (k as f64 - p as f64 / 2.0);
                writeln!(
                    tendons,
                    "    (name: \"t{k}\", route: [{route}], exit: (-0.25, {y:e}, {zeta:e})),"
                )
                .unwrap();
                if self.antagonists && k < p && k % self.antagonist_every.max(1) == 0 {
                    let zeta = zeta + 0.006;
                    let route = routed(&mut s, "u", k, anchor, zeta, ["Cw", "Ccw"]);
                    writeln!(
                        tendons,
                        "    (name: \"u{k}\", route: [{route}], exit: (-0.25, {:e}, {zeta:e})),",
                        y + 0.03
                    )
                    .unwrap();
                }
            }
        }
        for i in 0..self.gears {
            let carrier = 1 + i % n;
            let mut coupling = vec![0.0; n];
            coupling[carrier - 1] = 3.0 + 0.5 * (i % 4) as f64;
            if carrier < n {
                coupling[carrier] = -1.0 - 0.25 * (i % 3) as f64;
            }
            let c: Vec<String> = coupling.iter().map(|x| format!("{x:e}")).collect();
            let gm = 0.05 * self.pulley_ratio / 1e-3;
            let gi = gm * 0.02 * 0.02;
            writeln!(
                s,
                "    (name: \"gear{i}\", carrier: \"l{carrier}\", at: Pose(origin: ({:e}, {:e}, 0.02), rpy: ({:e}, {:e}, {:e})), radius: 0.02, mass: {gm:e}, com: (0.003, -0.002, 0.001), inertia: (xx: {:e}, yy: {:e}, zz: {:e}, xy: {:e}), coupling: [{}]),",
                -0.05 - 0.02 * (i % 3) as f64,
                0.01 * (i % 2) as f64,
                0.3 + 0.1 * i as f64,
                -0.4 + 0.05 * i as f64,
                0.1 * i as f64,
                0.3 * gi,
                0.35 * gi,
                0.5 * gi,
                0.02 * gi,
                c.join(", ")
            )
            .unwrap();
        }
        writeln!(s, "  ],\n  tendons: [\n{tendons}  ],\n  motors: [").unwrap();
        for j in (p + 1)..=n {
            writeln!(s, "    (name: \"m{j}\", on: Joint(\"l{j}\")),").unwrap();
        }
        s.push_str("  ],\n)\n");
        s
    }
}

/// Two links driven by three structure-only tendons whose structure matrix
/// `A = r [v + εw; v − εw]`, `v = (1, −1, 0)`, `w = (1, 1, −2)`, `r = 0.02` m, is `ε`
/// from losing rank (`σ_min/σ_max = √3 ε`) while its null vector stays `(1, 1, 1)`.
pub fn near_rank_loss(eps: f64) -> String {
    let r = 0.02;
    let col = |k: usize| {
        let (v, w) = ([1.0, -1.0, 0.0][k], [1.0, 1.0, -2.0][k]);
        format!("[{:e}, {:e}]", r * (v + eps * w), r * (v - eps * w))
    };
    format!(
        r#"(
    name: "near_rank_loss", gravity: (0.0, -9.81, 0.0), tension_floor: 5.0,
    links: [
        (name: "l1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 1.2, com: (-0.15, 0.0, 0.0), inertia: (xx: 0.0002, yy: 0.009, zz: 0.009)),
        (name: "l2", dh: (a: 0.25, alpha: 0.0, d: 0.0), mass: 0.8, com: (-0.125, 0.0, 0.0), inertia: (xx: 0.0001, yy: 0.0041667, zz: 0.0041667)),
    ],
    tendons: [
        (name: "t0", structure: {}),
        (name: "t1", structure: {}),
        (name: "t2", structure: {}),
    ],
)"#,
        col(0),
        col(1),
        col(2)
    )
}

fn stress_file(name: &str) -> String {
    let path = format!(
        "{}/mechanisms/stress/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn example(name: &str) -> String {
    crate::examples::text(name)
}

/// The paper's examples in the protocol's range.
pub fn paper_cases() -> Vec<StressCase> {
    crate::examples::NAMES
        .iter()
        .map(|n| {
            StressCase::new(
                n,
                Group::PaperExample,
                format!("the paper's {n} in the benchmark protocol's range"),
                example(n),
                Range::PROTOCOL,
            )
        })
        .collect()
}

/// Pulley inertia against link inertia, `ratio` = idler `I_zz` / link 1's `I_zz`.
pub fn pulley_inertia(ratio: f64) -> StressCase {
    let name = format!("pulley_inertia_{ratio:.0e}");
    let mut arm = Arm::new(&name, 3, 3);
    arm.pulley_ratio = ratio;
    StressCase::new(
        &name,
        Group::PulleyInertia,
        format!(
            "three tendon-driven links over five idlers whose inertia is {ratio:.0e} times the \
             links'"
        ),
        arm.ron(),
        Range::PROTOCOL,
    )
}

/// Drum radius over idler radius = `ratio` (the larger of the two is 20 mm).
pub fn radius_ratio(ratio: f64) -> StressCase {
    let name = format!("radius_ratio_{ratio:.0e}");
    let mut arm = Arm::new(&name, 3, 3);
    let big = 0.02;
    (arm.drum_radius, arm.idler_radius) = if ratio >= 1.0 {
        (big, big / ratio)
    } else {
        (big * ratio, big)
    };
    StressCase::new(
        &name,
        Group::RadiusRatio,
        format!(
            "three tendon-driven links, drum radius {:.1e} m over idler radius {:.1e} m",
            arm.drum_radius, arm.idler_radius
        ),
        arm.ron(),
        Range::PROTOCOL,
    )
}

/// The structure matrix `eps` from losing rank ([`near_rank_loss`]).
pub fn rank_loss(eps: f64) -> StressCase {
    StressCase::new(
        &format!("near_rank_loss_{eps:.0e}"),
        Group::RankLoss,
        format!(
            "two links, three structure-only tendons, structure matrix with σ_min/σ_max = \
             {:.1e}",
            3f64.sqrt() * eps
        ),
        near_rank_loss(eps),
        Range::PROTOCOL,
    )
}

/// A motor-driven spatial chain of `n` links with `ceil(2.5 n)` explicitly coupled pulleys.
pub fn motor_chain(n: usize) -> StressCase {
    let name = format!("motor_chain_{n}");
    let mut arm = Arm::new(&name, n, 0);
    arm.spatial = true;
    arm.gears = (5 * n).div_ceil(2);
    StressCase::new(
        &name,
        Group::MotorChain,
        format!(
            "{n} motor-driven spatial links carrying {} explicitly coupled pulleys",
            arm.gears
        ),
        arm.ron(),
        Range::PROTOCOL,
    )
}

/// A spatial chain of `n` links whose first `min(n, 4)` joints are driven by open-ended
/// tendons over idlers, the rest by motors.
pub fn tendon_chain(n: usize) -> StressCase {
    let name = format!("tendon_chain_{n}");
    let p = n.min(4);
    let mut arm = Arm::new(&name, n, p);
    arm.spatial = true;
    let pulleys = (p + 1) + (1..=p).map(|a| a - 1).sum::<usize>() + (p - 1);
    StressCase::new(
        &name,
        Group::TendonChain,
        format!(
            "{n} spatial links, the first {p} driven by {} tendons over {pulleys} pulleys, \
             the rest by motors",
            p + 1
        ),
        arm.ron(),
        Range::PROTOCOL,
    )
}

/// A three-link spatial motor chain whose distal link has `scale` times its mass and
/// inertia (zero: massless).
pub fn light_distal(scale: f64) -> StressCase {
    let name = if scale == 0.0 {
        "massless_distal".to_string()
    } else {
        format!("light_distal_{scale:.0e}")
    };
    let mut arm = Arm::new(&name, 3, 0);
    arm.spatial = true;
    arm.distal_scale = scale;
    StressCase::new(
        &name,
        Group::LightDistal,
        format!("three motor-driven spatial links, the distal one at {scale:.0e} of its mass"),
        arm.ron(),
        Range::PROTOCOL,
    )
}

/// The extreme-state cases on one mechanism: speeds to 1e3 rad/s, angles to 1e4 rad,
/// accelerations to 1e6 rad/s², and all three.
pub fn extreme_states(base: &StressCase) -> Vec<StressCase> {
    let p = Range::PROTOCOL;
    [
        ("fast", Range { qd: 1e3, ..p }, "joint speeds to 1e3 rad/s"),
        (
            "large_angles",
            Range { q: 1e4, ..p },
            "joint angles to 1e4 rad",
        ),
        (
            "large_accel",
            Range { qdd: 1e6, ..p },
            "joint accelerations to 1e6 rad/s²",
        ),
        (
            "extreme",
            Range {
                q: 1e4,
                qd: 1e3,
                qdd: 1e6,
            },
            "angles to 1e4 rad, speeds to 1e3 rad/s, accelerations to 1e6 rad/s²",
        ),
    ]
    .into_iter()
    .map(|(tag, range, what)| base.with_range(&format!("{}_{tag}", base.name), range, what))
    .collect()
}

/// Tension bounds: a loop whose pretension some states' dynamics exceeds (slack, flagged),
/// a loop with no pretension, and a tendon whose `max_tension` some states need more than.
pub fn tension_bounds() -> Vec<StressCase> {
    vec![
        StressCase::new(
            "loop_near_slack",
            Group::TensionBound,
            "Example 1 with a 4 N loop pretension: the states' dynamics needs between nothing \
             and about twice that on one side"
                .into(),
            stress_file("loop_near_slack"),
            Range {
                qdd: 30.0,
                ..Range::PROTOCOL
            },
        ),
        StressCase::new(
            "loop_no_pretension",
            Group::TensionBound,
            "Example 1 with no loop pretension: one side of the loop must push at every \
             state that needs a torque"
                .into(),
            example("example1_endless").replace("pretension: 20.0", "pretension: 0.0"),
            Range::PROTOCOL,
        ),
        StressCase::new(
            "tendon_max_tension",
            Group::TensionBound,
            "Example 2 with a 200 N max_tension on T11: the hardest states need more".into(),
            stress_file("tendon_max_tension"),
            Range {
                qdd: 40.0,
                ..Range::PROTOCOL
            },
        ),
    ]
}

/// Example 2 with friction in every bearing (`example2_friction.ron`), its coefficients
/// scaled by `scale`: from a trace of friction to friction that dominates the dynamics.
pub fn bearing_friction(scale: f64) -> StressCase {
    let name = format!("bearing_friction_{scale:.0e}");
    let mut text = example("example2_friction");
    for (c, v) in [("0.05", "0.01"), ("0.03", "0.005"), ("0.002", "0.0002")] {
        let written = format!("friction: (coulomb: {c}, viscous: {v})");
        assert!(
            text.contains(&written),
            "example2_friction.ron has {written}"
        );
        text = text.replace(
            &written,
            &format!(
                "friction: (coulomb: {:e}, viscous: {:e})",
                c.parse::<f64>().unwrap() * scale,
                v.parse::<f64>().unwrap() * scale
            ),
        );
    }
    StressCase::new(
        &name,
        Group::BearingFriction,
        format!("Example 2 with Coulomb and viscous friction in both joints and idlers, {scale:.0e} times the file's"),
        text,
        Range::PROTOCOL,
    )
}

/// Example 2 with capstan friction on both guides (`example2_capstan.ron`) at `mu`: the
/// tension system solved per state.
pub fn capstan_friction(mu: f64) -> StressCase {
    let name = format!("capstan_friction_{mu}");
    let text = example("example2_capstan");
    assert_eq!(text.matches("mu: 0.3,").count(), 2, "example2_capstan.ron");
    StressCase::new(
        &name,
        Group::CapstanFriction,
        format!("Example 2 with both idlers made guides with capstan friction mu = {mu}"),
        text.replace("mu: 0.3,", &format!("mu: {mu:?},")),
        Range::PROTOCOL,
    )
}

/// Example 3 with every idler made a guide with capstan friction `mu`: four tendons, each
/// over two or three guides whose wrap angles change with the joints, so that the state's
/// `E` (3 × 4) is solved by the traced elimination with all its columns scaled.
pub fn capstan_guides_everywhere(mu: f64) -> StressCase {
    StressCase::new(
        &format!("capstan_guides_everywhere_{mu}"),
        Group::CapstanFriction,
        format!("Example 3 with every idler made a guide with capstan friction mu = {mu}"),
        crate::guides::idlers_as_capstans(&example("example3_stanford_jpl"), mu),
        Range::PROTOCOL,
    )
}

/// Every case of the suite.
pub fn cases() -> Vec<StressCase> {
    let mut all = paper_cases();
    for r in [1e-9, 1e-6, 1e-3, 1e3, 1e6, 1e9] {
        all.push(pulley_inertia(r));
    }
    for r in [1e-3, 1e-2, 1e-1, 1e1, 1e2, 1e3] {
        all.push(radius_ratio(r));
    }
    for e in [1e-2, 1e-4, 1e-6, 1e-8, 1e-11] {
        all.push(rank_loss(e));
    }
    let bases = paper_cases();
    all.extend(extreme_states(&bases[0]));
    all.extend(extreme_states(&bases[2]));
    all.extend(extreme_states(&tendon_chain(6)));
    for n in 2..=12 {
        all.push(motor_chain(n));
    }
    for n in 2..=11 {
        all.push(tendon_chain(n));
    }
    for s in [1e-3, 1e-6, 1e-9, 1e-12, 0.0] {
        all.push(light_distal(s));
    }
    all.extend(tension_bounds());
    for s in [1e-3, 1.0, 1e3] {
        all.push(bearing_friction(s));
    }
    for mu in [0.01, 0.3, 1.0] {
        all.push(capstan_friction(mu));
    }
    for mu in [0.1, 0.5] {
        all.push(capstan_guides_everywhere(mu));
    }
    all
}

/// The cases whose mechanisms `tests/generated` also generates code for: one or two of each
/// group (the extreme-state cases reuse the paper's examples and `tendon_chain_6`).
pub fn generated_cases() -> Vec<StressCase> {
    let mut v = vec![
        pulley_inertia(1e-9),
        pulley_inertia(1e9),
        radius_ratio(1e-2),
        radius_ratio(1e3),
        rank_loss(1e-4),
        motor_chain(2),
        tendon_chain(6),
        light_distal(1e-9),
        bearing_friction(1e3),
        capstan_friction(1.0),
        capstan_guides_everywhere(0.1),
    ];
    v.extend(
        tension_bounds()
            .into_iter()
            .filter(|c| c.name == "loop_near_slack"),
    );
    v
}

/// A Rust identifier for a case name (`radius_ratio_1e-2` → `radius_ratio_1em2`,
/// `capstan_guides_everywhere_0.1` → `capstan_guides_everywhere_0p1`).
pub fn ident(name: &str) -> String {
    name.replace('-', "m").replace('.', "p")
}

/// The case of that name.
pub fn case(name: &str) -> StressCase {
    cases()
        .into_iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no stress case `{name}`"))
}

// ---------------------------------------------------------------------------------------
// Measurement.

/// Growth factor of rounding errors per body and unknown (see the module documentation).
pub const ROUNDING_GROWTH: f64 = 8.0;

/// The floor of each output's error denominator, relative to that output's scale (the
/// median over the case's states of its reference's max norm).
pub const SCALE_FLOOR: f64 = 1e-2;

/// The target of the issue for well-conditioned cases in `f64`.
pub const WELL_CONDITIONED_TARGET: f64 = 1e-9;

/// Largest and median of a set of errors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stat {
    pub max: f64,
    pub median: f64,
    pub count: usize,
}

impl Stat {
    pub fn of(values: &[f64]) -> Stat {
        if values.is_empty() {
            return Stat::default();
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        Stat {
            max: v[v.len() - 1],
            median: v[v.len() / 2],
            count: v.len(),
        }
    }
}

/// Errors of one output.
#[derive(Clone, Debug)]
pub struct OutputFigures {
    pub name: &'static str,
    pub runtime_f64: Stat,
    pub runtime_f32: Stat,
    pub generated_f64: Option<Stat>,
    /// `κ_o` of the condition rule.
    pub kappa: f64,
}

/// What the solver returned, state by state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outcomes {
    pub states: usize,
    /// Inverse dynamics returned numbers in `f64`.
    pub ok: usize,
    /// ... with a slack loop flagged.
    pub flagged: usize,
    /// States where `f64` and the reference disagree on a slack flag.
    pub flag_mismatches: usize,
    /// `Error::Tension` from inverse dynamics in `f64`.
    pub tension_errors: usize,
    /// `Error::Singular` from forward dynamics in `f64`.
    pub singular_errors: usize,
    /// Any other error in `f64`.
    pub other_errors: usize,
    /// States where `f64` and the reference disagree on returning an error.
    pub error_mismatches: usize,
    /// States where an `f64` call returned `Ok` with a number that is not finite.
    pub silent_non_finite: usize,
    /// The first error message met, for a report.
    pub first_error: Option<String>,
    /// States where the `f32` run returned an error and the `f64` run did not (an `f32`
    /// model whose tension system is singular in `f32`, an overflow in `f32`).
    pub f32_only_errors: usize,
    /// States where an `f32` call returned `Ok` with a number that is not finite.
    pub f32_silent_non_finite: usize,
}

/// Everything measured on one case.
#[derive(Clone, Debug)]
pub struct CaseFigures {
    pub name: String,
    pub links: usize,
    pub pulleys: usize,
    pub unknowns: usize,
    /// Per state, the worst output; over states, max and median.
    pub runtime_f64: Stat,
    pub runtime_f32: Stat,
    pub generated_f64: Option<Stat>,
    /// 2-norm condition number of the structure matrix `A`, over the joints tendons act on
    /// (`None` without tendons).
    pub cond_a: Option<f64>,
    /// Of the tension system `E` (`A` extended by motors and loops).
    pub cond_e: f64,
    /// Of the mass matrix over the states.
    pub cond_m: Stat,
    /// Of the mass matrix with its diagonal scaled to one, `D^-½ M D^-½`: what Cholesky's
    /// accuracy depends on (van der Sluis), and so what the condition rule uses.
    pub cond_m_scaled: Stat,
    /// Largest over smallest tendon component of the positive null vector (1 without a
    /// redundant routing): how far the floors lift some tensions above others.
    pub null_spread: f64,
    /// Largest `|angle|` of a body whose angle enters a rotation.
    pub max_angle: f64,
    pub outputs: Vec<OutputFigures>,
    pub outcomes: Outcomes,
}

impl CaseFigures {
    /// `C u κ_o` for output `o` in precision `u`.
    pub fn bound(&self, output: &OutputFigures, u: f64) -> f64 {
        ROUNDING_GROWTH * (self.links + self.pulleys + self.unknowns) as f64 * u * output.kappa
    }

    /// Whether the condition rule puts every output's `f64` bound within the target.
    pub fn well_conditioned(&self) -> bool {
        self.outputs
            .iter()
            .all(|o| self.bound(o, f64::EPSILON / 2.0) <= WELL_CONDITIONED_TARGET)
    }

    /// The output whose `f64` error is largest relative to its bound, with that ratio.
    pub fn worst_against_bound(&self) -> Option<(&OutputFigures, f64)> {
        self.outputs
            .iter()
            .map(|o| (o, o.runtime_f64.max / self.bound(o, f64::EPSILON / 2.0)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// How much of a case to measure.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    pub states: usize,
    /// Also run `f32` (the slowest part after the reference is the `f32` model's cast).
    pub f32: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            states: 40,
            f32: true,
        }
    }
}

/// Generated code of a case's mechanism: at `(q, q̇, q̈, motor torques, tendon tensions)`,
/// every generated output by name (`generalized_forces` is `M q̈ + h + g − Q_ext`,
/// `actuation` the motor torques then the tendon tensions).
pub type Generated<'a> =
    &'a dyn Fn(&[f64], &[f64], &[f64], &[f64], &[f64]) -> Vec<(&'static str, Vec<f64>)>;

/// The outputs of one state in one precision, by name, or the error of the first call that
/// failed. Inverse-dynamics outputs are absent when inverse dynamics failed.
struct Run {
    outputs: Vec<(&'static str, Vec<f64>)>,
    inverse: Result<(), Error>,
    forward: Result<(), Error>,
    slack: Vec<bool>,
}

/// Outputs whose values depend on the solved tensions `x = E⁺ b + N λ`. (The delivered
/// generalized forces and the base reaction do not: the tensions' null-space part and
/// their internal pulls cancel in them.)
const TENSION_OUTPUTS: [&str; 4] = ["actuation", "loop_sides", "segment_tensions", "bearings"];

fn f64s<T: Numeric>(v: &[T]) -> Vec<f64> {
    v.iter().map(|x| x.to_f64()).collect()
}

fn lift<T: Numeric>(v: &[f64]) -> Vec<T> {
    v.iter().map(|&x| T::from_f64(x)).collect()
}

/// Every number inverse dynamics reports, by output (flattened as generated code returns
/// it), plus the pulleys' moments and the loops' sides.
fn inverse_outputs<T: Numeric>(r: &InverseDynamics<T>) -> Vec<(&'static str, Vec<f64>)> {
    let flat = |o: Output| {
        r.flattened(o)
            .filter(|v| !v.is_empty())
            .map(|v| (o.name(), f64s(&v)))
    };
    let mut out: Vec<(&'static str, Vec<f64>)> = flat(Output::Actuation).into_iter().collect();
    out.extend([
        ("delivered_forces", f64s(&r.generalized_forces)),
        (
            "pulley_moments",
            r.pulley_demands.iter().map(|(_, v)| v.to_f64()).collect(),
        ),
    ]);
    if !r.loop_sides.is_empty() {
        out.push((
            "loop_sides",
            r.loop_sides.iter().flatten().map(|v| v.to_f64()).collect(),
        ));
    }
    out.extend(
        [
            Output::SegmentTensions,
            Output::Bearings,
            Output::BaseReaction,
        ]
        .into_iter()
        .filter_map(flat),
    );
    out
}

fn run<T: Numeric>(
    model: &Model<T>,
    s: &mut Data<T>,
    state: &State,
    mt: &[f64],
    tt: &[f64],
) -> Run {
    let [q, qd, qdd] = state;
    let (q, qd, qdd) = (lift::<T>(q), lift::<T>(qd), lift::<T>(qdd));
    let mut outputs = Vec::new();
    let inverse = s.inverse_dynamics(model, &q, &qd, &qdd).map(|r| {
        outputs.extend(inverse_outputs(r));
        r.slack_loops()
    });
    let slack = inverse.clone().unwrap_or_default();
    let inverse = inverse.map(|_| ());
    if let Ok(v) = s.generalized_forces(model, &q, &qd, &qdd) {
        outputs.push(("generalized_forces", f64s(v)));
    }
    if let Ok(m) = s.mass_matrix(model, &q) {
        outputs.push(("mass_matrix", m.iter().flat_map(|r| f64s(r)).collect()));
    }
    if let Ok(v) = s.bias(model, &q, &qd) {
        outputs.push(("bias", f64s(v)));
    }
    if let Ok(v) = s.gravity(model, &q) {
        outputs.push(("gravity", f64s(v)));
    }
    let forward = s
        .forward_dynamics(model, &q, &qd, &lift::<T>(mt), &lift::<T>(tt))
        .map(|v| outputs.push(("forward_dynamics", f64s(v))));
    Run {
        outputs,
        inverse,
        forward,
        slack,
    }
}

fn rel_floored(a: &[f64], b: &[f64], floor: f64) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    let scale = b.iter().fold(floor.max(1e-300), |m, x| m.max(x.abs()));
    let err = a.iter().zip(b).fold(0.0f64, |m, (x, y)| {
        if (x - y).is_nan() {
            f64::INFINITY
        } else {
            m.max((x - y).abs())
        }
    });
    err / scale
}

fn svd_condition(rows: &[Vec<f64>]) -> Option<f64> {
    let (r, c) = (rows.len(), rows.first()?.len());
    if r == 0 || c == 0 {
        return None;
    }
    let m = nalgebra::DMatrix::from_fn(r, c, |i, j| rows[i][j]);
    let sv = m.svd(false, false).singular_values;
    let max = sv.iter().cloned().fold(0.0, f64::max);
    let min = sv.iter().cloned().fold(f64::INFINITY, f64::min);
    Some(max / min)
}

/// Largest `|θ_b|` over the states of bodies whose angle enters a rotation.
fn max_angle(m: &Model<f64>, states: &[State]) -> f64 {
    states
        .iter()
        .flat_map(|[q, _, _]| {
            m.bodies().iter().filter(|b| b.spins).map(move |b| {
                (b.coupling.iter().zip(q).map(|(c, x)| c * x).sum::<f64>() + b.offset).abs()
            })
        })
        .fold(0.0, f64::max)
}

/// Counts what the `f64` run returned at one state against the reference.
fn tally(outcomes: &mut Outcomes, r64: &Run, reference: &Run) {
    match &r64.inverse {
        Ok(()) => {
            outcomes.ok += 1;
            if r64.slack.iter().any(|&s| s) {
                outcomes.flagged += 1;
            }
            if reference.inverse.is_ok() && r64.slack != reference.slack {
                outcomes.flag_mismatches += 1;
            }
        }
        Err(Error::Tension(_)) => outcomes.tension_errors += 1,
        Err(_) => outcomes.other_errors += 1,
    }
    match &r64.forward {
        Ok(()) => {}
        Err(Error::Singular(_)) => outcomes.singular_errors += 1,
        Err(_) => outcomes.other_errors += 1,
    }
    for e in [&r64.inverse, &r64.forward]
        .into_iter()
        .filter_map(|r| r.as_ref().err())
    {
        outcomes.first_error.get_or_insert_with(|| e.to_string());
    }
    if r64.inverse.is_ok() != reference.inverse.is_ok()
        || r64.forward.is_ok() != reference.forward.is_ok()
    {
        outcomes.error_mismatches += 1;
    }
    if r64
        .outputs
        .iter()
        .any(|(_, v)| v.iter().any(|x| !x.is_finite()))
    {
        outcomes.silent_non_finite += 1;
    }
}

/// 2-norm condition numbers of `M` (row-major, `n × n`) and of `D^-½ M D^-½`.
fn conditions(m: &[f64], n: usize) -> (f64, f64) {
    let dm = nalgebra::DMatrix::from_fn(n, n, |i, j| m[i * n + j]);
    let d: Vec<f64> = (0..n).map(|i| dm[(i, i)].abs().sqrt()).collect();
    let scaled = nalgebra::DMatrix::from_fn(n, n, |i, j| {
        if d[i] > 0.0 && d[j] > 0.0 {
            dm[(i, j)] / (d[i] * d[j])
        } else {
            dm[(i, j)]
        }
    });
    let cond = |a: nalgebra::DMatrix<f64>| {
        let e = a.symmetric_eigen().eigenvalues;
        let min = e.min();
        if min <= 0.0 {
            f64::INFINITY
        } else {
            e.max() / min
        }
    };
    (cond(dm), cond(scaled))
}

/// Largest over smallest tendon component of the positive null vector.
pub fn null_spread(model: &Model<f64>) -> f64 {
    match &model.system().positive_null {
        None => 1.0,
        Some(p) => {
            let v: Vec<f64> = model.tendons().iter().map(|t| p[t.unknown]).collect();
            v.iter().cloned().fold(0.0, f64::max) / v.iter().cloned().fold(f64::INFINITY, f64::min)
        }
    }
}

/// Measures one case: `Err` when its mechanism does not validate.
pub fn measure_case(
    case: &StressCase,
    options: Options,
    generated: Option<Generated>,
) -> Result<CaseFigures, Error> {
    let model = case.model()?;
    let m_dd = model.cast_numeric::<DoubleDouble>();
    let m_32 = options.f32.then(|| model.cast_numeric::<f32>());
    let mut s64 = Data::new(&model);
    let mut sdd = Data::new(&m_dd);
    let mut s32 = m_32.as_ref().map(Data::new);
    let states = case.states(model.dof(), options.states);
    let mut outcomes = Outcomes {
        states: states.len(),
        ..Outcomes::default()
    };
    // Per state: the runs, and the forward-dynamics term scale.
    let mut runs = Vec::new();
    let mut conds = Vec::new();
    for state in &states {
        let [q, qd, qdd] = state;
        // The inputs of forward dynamics: this state's torques and tensions in f64 (or
        // zero where inverse dynamics failed), rounded to f32.
        let (mt, tt) = match s64.inverse_dynamics(&model, q, qd, qdd) {
            Ok(r) => (r.motor_torques.clone(), r.tendon_tensions.clone()),
            Err(_) => (
                vec![0.0; model.motors().len()],
                vec![0.0; model.tendons().len()],
            ),
        };
        let round =
            |v: Vec<f64>| -> Vec<f64> { v.into_iter().map(|x| f64::from(x as f32)).collect() };
        let (mt, tt) = (round(mt), round(tt));
        let reference = run(&m_dd, &mut sdd, state, &mt, &tt);
        let r64 = run(&model, &mut s64, state, &mt, &tt);
        let r32 = m_32
            .as_ref()
            .zip(s32.as_mut())
            .map(|(m, s)| run(m, s, state, &mt, &tt));
        let gen = generated.map(|g| g(q, qd, qdd, &mt, &tt));
        tally(&mut outcomes, &r64, &reference);
        if let Some(r32) = &r32 {
            if (r32.inverse.is_err() && r64.inverse.is_ok())
                || (r32.forward.is_err() && r64.forward.is_ok())
            {
                outcomes.f32_only_errors += 1;
            }
            if r32
                .outputs
                .iter()
                .any(|(_, v)| v.iter().any(|x| !x.is_finite()))
            {
                outcomes.f32_silent_non_finite += 1;
            }
        }
        // Condition of M at this state, from the reference.
        if let Some((_, m)) = reference.outputs.iter().find(|(n, _)| *n == "mass_matrix") {
            conds.push(conditions(m, model.dof()));
        }
        let fd_floor = s64
            .forward_dynamics_scale(&model, &state[0], &state[1], &mt, &tt)
            .unwrap_or(0.0);
        runs.push((reference, r64, r32, gen, fd_floor));
    }
    // Each output's scale: the median of its reference's max norm over the states.
    let mut names: Vec<&'static str> = Vec::new();
    for (reference, ..) in &runs {
        for (n, _) in &reference.outputs {
            if !names.contains(n) {
                names.push(n);
            }
        }
    }
    let scale = |name: &str| {
        let norms: Vec<f64> = runs
            .iter()
            .filter_map(|(r, ..)| r.outputs.iter().find(|(n, _)| *n == name))
            .map(|(_, v)| v.iter().fold(0.0f64, |m, x| m.max(x.abs())))
            .collect();
        Stat::of(&norms).median
    };
    let scales: Vec<f64> = names.iter().map(|n| scale(n)).collect();
    // Errors: per output and state, and per state the worst output.
    let mut errs = vec![(Vec::new(), Vec::new(), Vec::new()); names.len()];
    let mut per_state = (Vec::new(), Vec::new(), Vec::new());
    for (reference, r64, r32, gen, fd_floor) in &runs {
        let (mut w64, mut w32, mut wgen) = (0.0f64, 0.0f64, 0.0f64);
        for (name, want) in &reference.outputs {
            let k = names.iter().position(|n| n == name).expect("listed");
            let mut floor = SCALE_FLOOR * scales[k];
            if *name == "forward_dynamics" {
                floor = floor.max(*fd_floor);
            }
            let find = |outs: &[(&'static str, Vec<f64>)]| {
                outs.iter()
                    .find(|(n, _)| n == name)
                    .map(|(_, v)| rel_floored(v, want, floor))
            };
            if let Some(e) = find(&r64.outputs) {
                errs[k].0.push(e);
                w64 = w64.max(e);
            }
            if let Some(e) = r32.as_ref().and_then(|r| find(&r.outputs)) {
                errs[k].1.push(e);
                w32 = w32.max(e);
            }
            if let Some(e) = gen.as_ref().and_then(|g| find(g)) {
                errs[k].2.push(e);
                wgen = wgen.max(e);
            }
        }
        per_state.0.push(w64);
        per_state.1.push(w32);
        per_state.2.push(wgen);
    }
    let cond_e = model.system().condition;
    let cond_m = Stat::of(&conds.iter().map(|c| c.0).collect::<Vec<_>>());
    let cond_m_scaled = Stat::of(&conds.iter().map(|c| c.1).collect::<Vec<_>>());
    let angle = max_angle(&model, &states);
    let outputs = names
        .iter()
        .zip(errs)
        .map(|(&name, (e64, e32, egen))| {
            let mut kappa = 1.0 + angle;
            if TENSION_OUTPUTS.contains(&name) {
                kappa += cond_e * null_spread(&model);
            }
            if name == "forward_dynamics" {
                kappa += cond_m_scaled.max;
            }
            OutputFigures {
                name,
                runtime_f64: Stat::of(&e64),
                runtime_f32: Stat::of(&e32),
                generated_f64: generated.map(|_| Stat::of(&egen)),
                kappa,
            }
        })
        .collect();
    let pulleys = model
        .bodies()
        .iter()
        .filter(|b| matches!(b.kind, BodyKind::Pulley { .. }))
        .count();
    Ok(CaseFigures {
        name: case.name.clone(),
        links: model.dof(),
        pulleys,
        unknowns: model.system().unknowns.len(),
        runtime_f64: Stat::of(&per_state.0),
        runtime_f32: Stat::of(&per_state.1),
        generated_f64: generated.map(|_| Stat::of(&per_state.2)),
        cond_a: svd_condition(
            &model
                .structure_matrix()
                .into_iter()
                .filter(|row| row.iter().any(|&x| x != 0.0))
                .collect::<Vec<_>>(),
        )
        .filter(|_| !model.tendons().is_empty()),
        cond_e,
        cond_m,
        cond_m_scaled,
        null_spread: null_spread(&model),
        max_angle: angle,
        outputs,
        outcomes,
    })
}

// ---------------------------------------------------------------------------------------
// Energy of a passive mechanism under forward dynamics.

/// Energy drift of a passive mechanism (no motor torque, no tendon tension) integrated by
/// classical RK4 of the runtime `f64` forward dynamics.
#[derive(Clone, Debug)]
pub struct EnergyDrift {
    /// `T + V` at the start (J), from [`crate::lagrangian`] (independent of the solver).
    pub initial: f64,
    /// Largest `|E(t) − E(0)|` over the run (J).
    pub max_drift: f64,
    /// Largest kinetic energy met (J): the scale the drift is judged against.
    pub max_kinetic: f64,
    /// Final joint angles.
    pub q: Vec<f64>,
    pub steps: usize,
}

/// Integrates `model` from `(q0, q̇0)` for `duration` s with step `dt` (forward dynamics
/// errors stop the run and are returned).
pub fn energy_drift(
    model: &Model<f64>,
    q0: &[f64],
    qd0: &[f64],
    dt: f64,
    duration: f64,
) -> Result<EnergyDrift, Error> {
    let n = model.dof();
    let mut s = Data::new(model);
    let (mt, tt) = (
        vec![0.0; model.motors().len()],
        vec![0.0; model.tendons().len()],
    );
    let energy = |q: &[f64], qd: &[f64]| {
        let t = crate::lagrangian::kinetic_energy(model, q, qd);
        (t, t + crate::lagrangian::potential_energy(model, q))
    };
    let mut deriv = |q: &[f64], qd: &[f64]| -> Result<(Vec<f64>, Vec<f64>), Error> {
        Ok((
            qd.to_vec(),
            s.forward_dynamics(model, q, qd, &mt, &tt)?.to_vec(),
        ))
    };
    let (mut q, mut qd) = (q0.to_vec(), qd0.to_vec());
    let (t0, e0) = energy(&q, &qd);
    let mut drift = EnergyDrift {
        initial: e0,
        max_drift: 0.0,
        max_kinetic: t0,
        q: Vec::new(),
        steps: 0,
    };
    let steps = (duration / dt).round() as usize;
    let axpy = |x: &[f64], a: f64, y: &[f64]| -> Vec<f64> {
        x.iter().zip(y).map(|(x, y)| x + a * y).collect()
    };
    for _ in 0..steps {
        let (k1q, k1v) = deriv(&q, &qd)?;
        let (k2q, k2v) = deriv(&axpy(&q, dt / 2.0, &k1q), &axpy(&qd, dt / 2.0, &k1v))?;
        let (k3q, k3v) = deriv(&axpy(&q, dt / 2.0, &k2q), &axpy(&qd, dt / 2.0, &k2v))?;
        let (k4q, k4v) = deriv(&axpy(&q, dt, &k3q), &axpy(&qd, dt, &k3v))?;
        for i in 0..n {
            q[i] += dt / 6.0 * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + k4q[i]);
            qd[i] += dt / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
        }
        let (t, e) = energy(&q, &qd);
        drift.max_drift = drift.max_drift.max((e - e0).abs());
        drift.max_kinetic = drift.max_kinetic.max(t);
        drift.steps += 1;
    }
    drift.q = q;
    Ok(drift)
}
