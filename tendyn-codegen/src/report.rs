//! Text and JSON renderings of what `tendyn-core` computes, shared by the CLI commands.
//! Every JSON key is documented in `docs/outputs.md`.

use serde_json::{json, Value};
use tendyn_core::base_parameters::BaseParameters;
use tendyn_core::error::ImpliedSystem;
use tendyn_core::identification::Identification;
use tendyn_core::model::{BodyKind, Model, PulleyRole, Row, SlidingCheck, Unknown};
use tendyn_core::physical_consistency::Consistent;
use tendyn_core::regressor;
use tendyn_core::spatial::Vec3;
use tendyn_core::torque_range::static_torque_ranges;
use tendyn_core::{InverseDynamics, Regressor};

/// The joint-space terms evaluated beside inverse dynamics, at the same state.
pub struct JointSpace {
    /// `M(q)` (kg·m²), `mass[i][j] = M_ij`.
    pub mass: Vec<Vec<f64>>,
    /// `h(q, q̇)` (N·m), per joint.
    pub bias: Vec<f64>,
    /// `g(q)` (N·m), per joint.
    pub gravity: Vec<f64>,
}

fn v3(v: Vec3<f64>) -> Value {
    json!([v.x, v.y, v.z])
}

fn unknown_name(m: &Model<f64>, u: &Unknown) -> String {
    let strands: Vec<&str> = m.strands().iter().map(|s| s.name.as_str()).collect();
    u.label(&strands, m.tendons(), m.motors())
}

fn row_name(m: &Model<f64>, r: &Row) -> String {
    r.label(m.bodies(), m.loops())
}

/// A pulley's role as `check` names it.
fn role_name(m: &Model<f64>, name: &str, role: &PulleyRole) -> String {
    match role {
        PulleyRole::Fixed if m.guides().any(|g| m.bodies()[g.2].name == name) => {
            "fixed guide".to_string()
        }
        PulleyRole::Fixed => "fixed drum".to_string(),
        PulleyRole::Idler { strand } => format!("idler of {}", m.strands()[*strand].name),
        PulleyRole::Driving => "driving pulley".to_string(),
        PulleyRole::Coupled => "explicit coupling".to_string(),
    }
}

/// A JSON number, or `null` where it is not finite (JSON has no infinity).
fn finite_or_null(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// What `tendyn check --json` prints: the same as [`check_text`], one JSON object.
pub fn check_json(m: &Model<f64>) -> Value {
    let names = |it: &mut dyn Iterator<Item = String>| it.collect::<Vec<_>>();
    let pulleys: serde_json::Map<String, Value> = m.bodies()[m.dof()..]
        .iter()
        .filter_map(|b| match &b.kind {
            BodyKind::Pulley { radius, role } => Some((
                b.name.clone(),
                json!({"radius": radius, "role": role_name(m, &b.name, role), "coupling": b.coupling}),
            )),
            BodyKind::Link { .. } => None,
        })
        .collect();
    let ranges: Value = if m.tendons().is_empty() {
        Value::Null
    } else {
        m.bodies()[..m.dof()]
            .iter()
            .zip(static_torque_ranges(m))
            .map(|(b, r)| {
                let range = r.map_or(
                    Value::Null,
                    |r| json!({"min": finite_or_null(r.min), "max": finite_or_null(r.max)}),
                );
                (b.name.clone(), range)
            })
            .collect::<serde_json::Map<_, _>>()
            .into()
    };
    let segments: serde_json::Map<String, Value> = m
        .strands()
        .iter()
        .map(|st| {
            let list: Vec<Value> = st
                .segments
                .iter()
                .map(|g| {
                    json!({
                        "frame": g.frame.map_or("base".to_string(), |f| m.bodies()[f].name.clone()),
                        "dir": v3(g.dir),
                        "length": g.length,
                        "acting_angles": g.acting_angles.map(|a| finite_or_null(a.to_degrees())),
                    })
                })
                .collect();
            (st.name.clone(), json!(list))
        })
        .collect();
    let friction: serde_json::Map<String, Value> = m
        .bodies()
        .iter()
        .filter_map(|b| {
            let f = b.friction?;
            Some((
                b.name.clone(),
                json!({"coulomb": f.coulomb, "viscous": f.viscous}),
            ))
        })
        .collect();
    json!({
        "mechanism": m.name(),
        "joints": names(&mut m.bodies()[..m.dof()].iter().map(|b| b.name.clone())),
        "joint_ranges": (0..m.dof())
            .map(|j| (m.bodies()[j].name.clone(), json!(m.joint_range(j))))
            .collect::<serde_json::Map<_, _>>(),
        "couplings": pulleys,
        "tendons": names(&mut m.tendons().iter().map(|t| t.name.clone())),
        "structure_matrix": if m.tendons().is_empty() { Value::Null } else { json!(m.structure_matrix()) },
        "static_torque_range": ranges,
        "tension_system": {
            "rows": names(&mut m.system().rows.iter().map(|r| row_name(m, r))),
            "unknowns": names(&mut m.system().unknowns.iter().map(|u| unknown_name(m, u))),
            "matrix": m.system().matrix,
            "condition": finite_or_null(m.system().condition),
            "null_space": m.system().null_space,
            "positive_null_vector": m.system().positive_null,
        },
        "segments": segments,
        "bearing_friction": friction,
        "friction_smoothing": m.friction_smoothing(),
        "guides": m.guides().map(|(s, _, b, g)| json!({
            "pulley": m.bodies()[b].name,
            "tendon": m.strands()[s].name,
            "wrap_angle": g.wrap,
            "wrap_angle_rate": g.wrap_rate,
            "wrap_angle_over_ranges": g.wrap_over(&m.range_box()),
            "mu": g.mu,
            "sliding_rate": g.slide,
        })).collect::<Vec<_>>(),
        "sliding_check": sliding_check_json(m.sliding_check()),
    })
}

/// How far validation showed the routing controllable with the guides' friction, for
/// `check`'s text (docs/outputs.md §1).
fn sliding_check_text(check: SlidingCheck) -> String {
    match check {
        SlidingCheck::Constant => {
            "at every state (nothing slides over the guides with friction)".into()
        }
        SlidingCheck::EveryWay { systems } => {
            format!("every way the guides slide and rest, and between ({systems} tension systems)")
        }
        SlidingCheck::EveryWayNotBetween { systems } => format!(
            "every way the guides slide and rest ({systems} tension systems), not every state \
             between (too many choices of free tendons to take one by one, and none of \
             those tried holds; accepted by `accept_sampled_sliding`): inverse and forward \
             dynamics check each state's system and refuse one that fails"
        ),
        SlidingCheck::EveryFactor { boxes } => format!(
            "at every capstan factor the guides can take ({boxes} box{} of factors)",
            if boxes == 1 { "" } else { "es" }
        ),
        SlidingCheck::AllSliding { systems } => format!(
            "only at {systems} ways every guide slides (too many directions to take one by \
             one; accepted by `accept_sampled_sliding`): inverse and forward dynamics check \
             each state's system and refuse one that fails"
        ),
    }
}

/// [`sliding_check_text`] for `check --json`.
fn sliding_check_json(check: SlidingCheck) -> Value {
    match check {
        SlidingCheck::Constant => json!({"covers": "constant"}),
        SlidingCheck::EveryWay { systems } => json!({"covers": "every_way", "systems": systems}),
        SlidingCheck::EveryWayNotBetween { systems } => {
            json!({"covers": "every_way_not_between", "systems": systems})
        }
        SlidingCheck::EveryFactor { boxes } => json!({"covers": "every_factor", "boxes": boxes}),
        SlidingCheck::AllSliding { systems } => {
            json!({"covers": "all_sliding", "systems": systems})
        }
    }
}

/// What `tendyn check` prints: the validated structure and everything derived from the routing.
pub fn check_text(m: &Model<f64>) -> String {
    let mut s = String::new();
    let mut line = |t: String| {
        s.push_str(&t);
        s.push('\n');
    };
    line(format!("mechanism `{}`: valid", m.name()));
    for o in tendyn_core::transmission::overlapping_pulleys(m.bodies()) {
        let (a, b) = (&m.bodies()[o.first], &m.bodies()[o.second]);
        let carrier = b.parent.map_or("base", |c| m.bodies()[c].name.as_str());
        line(format!(
            "  warning: pulleys `{}` and `{}` on `{carrier}` overlap: their centres are {} m \
             apart in one plane, closer than their radii {} + {} m; move one along its axis or \
             apart",
            a.name,
            b.name,
            number(o.distance),
            number(o.radii[0]),
            number(o.radii[1])
        ));
    }
    for c in tendyn_core::transmission::segments_through_pulleys(m) {
        let radius = match m.bodies()[c.pulley].kind {
            BodyKind::Pulley { radius, .. } => radius,
            BodyKind::Link { .. } => f64::NAN,
        };
        line(format!(
            "  warning: segment {}#{} passes through pulley `{}`, {} m from its centre (radius \
             {} m); route the tendon round it or move one of them",
            m.strands()[c.strand].name,
            c.segment,
            m.bodies()[c.pulley].name,
            number(c.distance),
            number(radius)
        ));
    }
    line(format!(
        "  {} degrees of freedom, {} intermediate links, {} open-ended tendons, {} loops, {} motors",
        m.dof(),
        m.bodies().len() - m.dof(),
        m.tendons().len(),
        m.loops().len(),
        m.motors().len()
    ));
    line("couplings (intermediate-link angle relative to its carrier = Σ ratio · q):".into());
    for b in &m.bodies()[m.dof()..] {
        if let BodyKind::Pulley { radius, role } = &b.kind {
            let role = role_name(m, &b.name, role);
            line(format!(
                "  {:<12} r = {:<8} {:<22} {}",
                b.name,
                radius,
                role,
                fmt_row(&b.coupling)
            ));
        }
    }
    let slides: Vec<_> = m.guides().collect();
    if !slides.is_empty() {
        line("guides (fixed pulleys the tendons slide over; wrap angle β, capstan μ):".into());
        for (s, _, b, g) in slides {
            let [low, high] = g.wrap_over(&m.range_box());
            let at = if g.wrap_is_constant() {
                String::new()
            } else if high > low {
                format!(
                    " (at q = 0; {:.3}° to {:.3}° over the joints' ranges)",
                    low.to_degrees(),
                    high.to_degrees()
                )
            } else {
                " (at q = 0)".into()
            };
            let away = if g.wrap < 0.0 {
                " (negative: the tendon bends away from it here; a real one would lift off)"
            } else {
                ""
            };
            line(format!(
                "  {:<12} {:<8} β = {:.3}°{at}, μ = {}, μβ = {}{away}",
                m.bodies()[b].name,
                m.strands()[s].name,
                g.wrap.to_degrees(),
                coefficient(g.mu),
                coefficient(g.mu * g.wrap.max(0.0))
            ));
        }
        if m.has_capstan() {
            line(format!(
                "  controllable with this friction: {}",
                sliding_check_text(m.sliding_check())
            ));
        }
    }
    if m.bodies().iter().any(|b| b.friction.is_some()) {
        let law = match m.friction_smoothing() {
            Some(v) => format!("tanh(ω / {v} rad/s)"),
            None => format!(
                "sign(ω) (within {:e} rad/s of rest: sign(α))",
                tendyn_core::friction::REST
            ),
        };
        line(format!(
            "bearing friction, τ_f = −(coulomb · s + viscous · ω) with s = {law} (format.md §4a):"
        ));
        for b in m.bodies().iter() {
            if let Some(f) = b.friction {
                line(format!(
                    "  {:<12} coulomb {} N·m, viscous {} N·m·s/rad",
                    b.name, f.coulomb, f.viscous
                ));
            }
        }
    }
    let system = implied_system(m);
    if !m.tendons().is_empty() {
        structure_lines(&mut line, &system);
        line(
            "static torque range, tendons alone without motors (tendons within floor and \
             max_tension, every other joint at zero generalized force):"
                .into(),
        );
        for (j, r) in static_torque_ranges(m).iter().enumerate() {
            let range = match r {
                Some(r) => format!("{} N·m", fmt_row(&[r.min, r.max])),
                None => {
                    "none (no tensions within the bounds hold every other joint at zero)".into()
                }
            };
            line(format!("  {:<12} {range}", m.bodies()[j].name));
        }
    }
    tension_system_lines(&mut line, &system);
    line(format!(
        "  condition number of E: {:.4}",
        m.system().condition
    ));
    line(format!(
        "  null space dimension: {}",
        m.system().null_space.len()
    ));
    if let Some(p) = &m.system().positive_null {
        line(format!("  positive null vector: {}", fmt_row(p)));
    }
    line("segments (frame, direction, length, acting angles in degrees):".into());
    for st in m.strands() {
        for (k, g) in st.segments.iter().enumerate() {
            let frame = g
                .frame
                .map_or("base".to_string(), |f| m.bodies()[f].name.clone());
            // The ground exit is a point, not a pulley: it has no acting angle.
            let angle = |a: f64| {
                if a.is_nan() {
                    "exit".to_string()
                } else {
                    format!("{:.3}", a.to_degrees())
                }
            };
            line(format!(
                "  {}#{k}: in {frame}, dir {}, {} m, angles {} / {}",
                st.name,
                fmt_row(&g.dir.to_array()),
                number(g.length),
                angle(g.acting_angles[0]),
                angle(g.acting_angles[1])
            ));
        }
    }
    s
}

/// The model's tension system with its rows and columns named: what [`structure_lines`]
/// and [`tension_system_lines`] print, as for a rejected routing.
fn implied_system(m: &Model<f64>) -> ImpliedSystem {
    ImpliedSystem {
        rows: m.system().rows.iter().map(|r| row_name(m, r)).collect(),
        unknowns: m
            .system()
            .unknowns
            .iter()
            .map(|u| unknown_name(m, u))
            .collect(),
        matrix: m.system().matrix.clone(),
        joints: m.dof(),
        tendons: m
            .tendons()
            .iter()
            .map(|t| (t.name.clone(), t.unknown))
            .collect(),
    }
}

/// The structure matrix `A`: `E`'s joint rows on the open-ended tendons' columns.
fn structure_lines(line: &mut impl FnMut(String), s: &ImpliedSystem) {
    line("structure matrix A (rows: joints; columns: tendons), Q = A T:".into());
    // Each name over its column of `fmt_row`'s cells.
    let names: Vec<String> = s
        .tendons
        .iter()
        .map(|(name, _)| format!("{name:>11}"))
        .collect();
    line(format!("  {:<18}  {}", "", names.join("  ")));
    for (label, row) in s.rows.iter().zip(&s.matrix).take(s.joints) {
        let a: Vec<f64> = s.tendons.iter().map(|&(_, c)| row[c]).collect();
        line(format!("  {label:<18} {}", fmt_row(&a)));
    }
}

/// The tension system `E x = b`: one line per balance row, then the unknowns' names.
fn tension_system_lines(line: &mut impl FnMut(String), s: &ImpliedSystem) {
    line("tension system E x = b (rows: balances; columns: unknowns):".into());
    for (label, row) in s.rows.iter().zip(&s.matrix) {
        line(format!("  {label:<22} {}", fmt_row(row)));
    }
    line(format!("  unknowns: {}", s.unknowns.join(", ")));
}

/// What `tendyn check` prints on stdout for a rejected routing, beside the error on stderr:
/// the structure matrix and the tension system the routing implies, for finding what is
/// wrong with it.
pub fn implied_text(s: &ImpliedSystem) -> String {
    let mut out = String::new();
    let mut line = |t: String| {
        out.push_str(&t);
        out.push('\n');
    };
    line("what the routing implies (the mechanism is not valid):".into());
    if !s.tendons.is_empty() {
        structure_lines(&mut line, s);
    }
    tension_system_lines(&mut line, s);
    out
}

fn fmt_row(r: &[f64]) -> String {
    let cells: Vec<String> = r.iter().map(|&x| format!("{:>11}", number(x))).collect();
    format!("[{}]", cells.join(", "))
}

/// A number as a person reads it: six significant digits, plainly from 1e-4 to 1e6 and
/// with an exponent beyond, never `-0` (round-off below 1e-15 in size prints as `0`), so
/// that a finger's 1e-5 kg·m² mass matrix does not print as `0.000000`.
pub fn number(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x.abs() < 1e-15 {
        return "0".to_string();
    }
    let exponent = x.abs().log10().floor() as i32;
    if (-4..6).contains(&exponent) {
        let decimals = (5 - exponent).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.5e}")
    }
}

/// A coefficient of the file (`mu`, and `μβ` from it) as [`number`] prints it, but never
/// as `0` unless it is: it is input, not round-off.
fn coefficient(x: f64) -> String {
    match x != 0.0 && x.abs() < 1e-4 {
        true => format!("{x:.5e}"),
        false => number(x),
    }
}

/// The JSON object `tendyn eval --json` prints for one state.
pub fn inverse_json(
    m: &Model<f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    r: &InverseDynamics<f64>,
    js: &JointSpace,
) -> Value {
    let (mass, bias, gravity) = (&js.mass, &js.bias, &js.gravity);
    let names = |it: &mut dyn Iterator<Item = String>| it.collect::<Vec<_>>();
    let mut out = json!({
        "mechanism": m.name(),
        "joints": names(&mut m.bodies()[..m.dof()].iter().map(|b| b.name.clone())),
        "joint_ranges": (0..m.dof())
            .map(|j| (m.bodies()[j].name.clone(), json!(m.joint_range(j))))
            .collect::<serde_json::Map<_, _>>(),
        "q": q, "qd": qd, "qdd": qdd,
        "generalized_forces": r.generalized_forces,
        "motor_torques": m.motors().iter().zip(&r.motor_torques).map(|(mo, t)| (mo.name.clone(), json!(t))).collect::<serde_json::Map<_, _>>(),
        "tendon_tensions": m.tendons().iter().zip(&r.tendon_tensions).map(|(t, v)| (t.name.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "minimal_norm_tensions": m.tendons().iter().zip(&r.minimal_norm_tensions).map(|(t, v)| (t.name.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "null_space_tensions": m.tendons().iter().zip(&r.null_space_tensions).map(|(t, v)| (t.name.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "loops": m.loops().iter().zip(&r.loop_sides).zip(r.slack_loops()).map(|((l, s), slack)| (l.name.clone(), json!({"ccw_side": s[0], "cw_side": s[1], "slack": slack}))).collect::<serde_json::Map<_, _>>(),
        "pulley_moments": r.pulley_demands.iter().map(|(b, v)| (m.bodies()[*b].name.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "bearing_friction": r.bearing_friction.iter().map(|(b, v)| (m.bodies()[*b].name.clone(), json!(unsigned_zero(*v)))).collect::<serde_json::Map<_, _>>(),
        "sticking": r.sticking.iter().map(|b| m.bodies()[*b].name.clone()).collect::<Vec<_>>(),
        "guides": tendyn_core::friction::guide_states(m, [q, qd, qdd], r.segment_tensions.as_deref()).into_iter().map(|g| json!({
            "pulley": m.bodies()[g.body].name,
            "tendon": m.strands()[g.strand].name,
            "wrap_angle": g.wrap_angle,
            "sliding_speed": g.sliding_speed,
            "direction": unsigned_zero(g.direction),
            "sticking": g.sticking,
            "dissipated_power": g.dissipated_power.map(unsigned_zero),
        })).collect::<Vec<_>>(),
        "mass_matrix": mass,
        "bias": bias,
        "gravity": gravity,
    });
    let o = out.as_object_mut().expect("object");
    o.insert(
        "segment_tensions".into(),
        match &r.segment_tensions {
            Some(s) => m
                .strands()
                .iter()
                .zip(s)
                .map(|(st, v)| (st.name.clone(), json!(v)))
                .collect::<serde_json::Map<_, _>>()
                .into(),
            None => Value::Null,
        },
    );
    o.insert(
        "bearings".into(),
        match &r.bearings {
            Some(b) => m
                .bodies()
                .iter()
                .zip(b)
                .map(|(body, (f, n))| {
                    (
                        body.name.clone(),
                        json!({"force": v3(*f), "moment": v3(*n)}),
                    )
                })
                .collect::<serde_json::Map<_, _>>()
                .into(),
            None => Value::Null,
        },
    );
    o.insert(
        "base_reaction".into(),
        match &r.base_reaction {
            Some((f, n)) => json!({"force": v3(*f), "moment": v3(*n)}),
            None => Value::Null,
        },
    );
    out
}

/// The header of `tendyn eval --states FILE --csv`: `q_J`, `qd_J`, `qdd_J` and `Q_J` per
/// joint `J`, `tau_M` per motor, `T_K` per open-ended tendon, in joint and file order.
pub fn inverse_csv_header(m: &Model<f64>) -> String {
    let joints: Vec<&str> = m.joint_names().collect();
    let mut columns: Vec<String> = Vec::new();
    for prefix in ["q", "qd", "qdd", "Q"] {
        columns.extend(joints.iter().map(|j| format!("{prefix}_{j}")));
    }
    columns.extend(m.motors().iter().map(|mo| format!("tau_{}", mo.name)));
    columns.extend(m.tendons().iter().map(|t| format!("T_{}", t.name)));
    columns.join(",")
}

/// One row of [`inverse_csv_header`]'s table, every number at full precision (Rust's
/// shortest representation that reads back to the same `f64`).
pub fn inverse_csv_row(q: &[f64], qd: &[f64], qdd: &[f64], r: &InverseDynamics<f64>) -> String {
    q.iter()
        .chain(qd)
        .chain(qdd)
        .chain(&r.generalized_forces)
        .chain(&r.motor_torques)
        .chain(&r.tendon_tensions)
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// The paper's three mechanisms, built into the binary for `tendyn demo`.
pub const BUILT_IN: [(&str, &str); 3] = [
    (
        "example1_endless.ron",
        include_str!("../../examples/mechanisms/example1_endless.ron"),
    ),
    (
        "example2_open_ended.ron",
        include_str!("../../examples/mechanisms/example2_open_ended.ron"),
    ),
    (
        "example3_stanford_jpl.ron",
        include_str!("../../examples/mechanisms/example3_stanford_jpl.ron"),
    ),
];

/// `x` with `-0` as `0`: friction that vanishes (at rest, or frictionless) has no sign
/// to show.
fn unsigned_zero(x: f64) -> f64 {
    x + 0.0
}

/// A readable summary of inverse dynamics at `state` (`[q, q̇, q̈]`: what `tendyn eval`
/// prints without `--json`, and what `tendyn demo` shows).
pub fn inverse_text(
    m: &Model<f64>,
    state: [&[f64]; 3],
    r: &InverseDynamics<f64>,
    js: &JointSpace,
) -> String {
    let (mass, bias, gravity) = (&js.mass, &js.bias, &js.gravity);
    let mut s = String::new();
    let mut line = |t: String| {
        s.push_str(&t);
        s.push('\n');
    };
    let joints: Vec<&str> = m.joint_names().collect();
    line(format!(
        "  generalized forces Q ({}): {} N·m",
        joints.join(", "),
        fmt_row(&r.generalized_forces)
    ));
    for (mo, t) in m.motors().iter().zip(&r.motor_torques) {
        line(format!("  motor {:<12} {:>12} N·m", mo.name, number(*t)));
    }
    for (k, t) in m.tendons().iter().enumerate() {
        line(format!(
            "  tendon {:<11} {:>12} N  (minimal-norm {} + null-space {}, floor {} N)",
            t.name,
            number(r.tendon_tensions[k]),
            number(r.minimal_norm_tensions[k]),
            number(r.null_space_tensions[k]),
            number(t.floor)
        ));
    }
    for ((l, sides), slack) in m.loops().iter().zip(&r.loop_sides).zip(r.slack_loops()) {
        line(format!(
            "  loop {:<13} ccw side {} N, cw side {} N{}",
            l.name,
            number(sides[0]),
            number(sides[1]),
            if slack {
                "  SLACK: raise the pretension"
            } else {
                ""
            }
        ));
    }
    if let Some(segs) = &r.segment_tensions {
        for (st, v) in m.strands().iter().zip(segs) {
            if v.len() > 1 {
                line(format!(
                    "  segments of {:<8} {} N (anchor side first)",
                    st.name,
                    fmt_row(v)
                ));
            }
        }
    }
    for (b, v) in &r.pulley_demands {
        line(format!(
            "  pulley {:<11} needs {:>12} N·m about its axis",
            m.bodies()[*b].name,
            number(*v)
        ));
    }
    for (b, v) in &r.bearing_friction {
        line(format!(
            "  bearing of {:<9} friction {:>12} N·m{}",
            m.bodies()[*b].name,
            number(*v),
            if r.sticking.contains(b) {
                "  (at rest: against the impending motion)"
            } else {
                ""
            }
        ));
    }
    let guides = tendyn_core::friction::guide_states(m, state, r.segment_tensions.as_deref());
    for g in guides {
        let mu = (m.strands()[g.strand].idlers[g.idler].guide.as_ref()).map_or(0.0, |g| g.mu);
        if mu == 0.0 {
            continue;
        }
        line(format!(
            "  guide {:<10} {:<8} wrap {:.3}°, sliding {} m/s, direction {}{}",
            m.bodies()[g.body].name,
            m.strands()[g.strand].name,
            g.wrap_angle.to_degrees(),
            number(g.sliding_speed),
            number(unsigned_zero(g.direction)),
            match (g.sticking, g.dissipated_power) {
                (true, _) => "  (at rest: the impending motion's)".to_string(),
                (false, Some(p)) => format!(", dissipates {} W", number(unsigned_zero(p))),
                (false, None) => String::new(),
            }
        ));
    }
    if let Some((f, n)) = &r.base_reaction {
        line(format!(
            "  base reaction: force {} N, moment {} N·m",
            fmt_row(&f.to_array()),
            fmt_row(&n.to_array())
        ));
    }
    line("  mass matrix M (kg·m²):".into());
    for row in mass {
        line(format!("    {}", fmt_row(row)));
    }
    line(format!("  bias h: {} N·m", fmt_row(bias)));
    line(format!("  gravity g: {} N·m", fmt_row(gravity)));
    s
}

/// The base parameters with the file's values, in the base regressor's column order: each
/// its name, value, the parameter it keeps and the ones merged into it with their
/// coefficients (`docs/outputs.md` §6d).
pub fn base_parameters_json(m: &Model<f64>, base: &BaseParameters) -> Value {
    let values = base.values(&regressor::values(m));
    let names = base.names(m);
    let parameters = &base.parameters;
    let groups = base.groups.iter().zip(names).zip(values);
    Value::Array(
        groups
            .map(|((g, name), value)| {
                json!({
                    "name": name,
                    "value": value,
                    "kept": parameters[g.column].name(m),
                    "merged": g.merged.iter().map(|&(c, b)| json!({
                        "parameter": parameters[c].name(m),
                        "coefficient": b,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect(),
    )
}

/// What `tendyn regressor --json` prints: every parameter of the regressor with the file's
/// value, the base parameters, and the parameters that act on no generalized force.
pub fn regressor_json(m: &Model<f64>, base: &BaseParameters) -> Value {
    let values = regressor::values(m);
    let parameters = &base.parameters;
    json!({
        "mechanism": m.name(),
        "parameters": parameters.iter().zip(&values).map(|(p, v)| json!({
            "name": p.name(m),
            "value": v,
        })).collect::<Vec<_>>(),
        "base_parameters": base_parameters_json(m, base),
        "unidentifiable": base.unidentifiable.iter().map(|&c| parameters[c].name(m)).collect::<Vec<_>>(),
    })
}

/// What `tendyn regressor` prints: the base parameters with the file's values.
pub fn regressor_text(m: &Model<f64>, base: &BaseParameters) -> String {
    let values = base.values(&regressor::values(m));
    let mut s = format!(
        "{}: {} parameters ({} bodies × 10 inertial, {} of bearing friction), {} base \
         parameters, {} act on no generalized force\n\nbase parameters (file values):\n",
        m.name(),
        base.parameters.len(),
        m.bodies().len(),
        base.parameters.len() - 10 * m.bodies().len(),
        base.groups.len(),
        base.unidentifiable.len()
    );
    for (i, (name, v)) in base.names(m).iter().zip(values).enumerate() {
        s.push_str(&format!("  {:>3}  {:>12}  {name}\n", i + 1, number(v)));
    }
    let none: Vec<String> = base
        .unidentifiable
        .iter()
        .map(|&c| base.parameters[c].name(m))
        .collect();
    s.push_str(&format!(
        "\nact on no generalized force: {}\n",
        if none.is_empty() {
            "none".to_string()
        } else {
            none.join(", ")
        }
    ));
    s
}

/// The keys `tendyn eval --regressor` adds at one state: `regressor` (`n` rows of the base
/// parameters' columns), `base_parameters` and `regressor_offset` (`Q₀`), so that
/// `generalized_forces = regressor · values + regressor_offset`.
pub fn regressor_at_json(m: &Model<f64>, base: &BaseParameters, r: &Regressor<f64>) -> Value {
    let columns = base.groups.len();
    let reduced = base.reduce(&r.y);
    let rows = (0..r.known.len()).map(|k| &reduced[k * columns..(k + 1) * columns]);
    json!({
        "regressor": rows.collect::<Vec<_>>(),
        "base_parameters": base_parameters_json(m, base),
        "regressor_offset": r.known,
    })
}

/// What `tendyn identify --json` prints: each base parameter's estimate, standard deviation
/// and the file's value, and how well the model explains the data.
pub fn identification_json(m: &Model<f64>, base: &BaseParameters, id: &Identification) -> Value {
    let file = base.values(&regressor::values(m));
    let names = base.names(m);
    json!({
        "mechanism": m.name(),
        "samples": id.samples,
        "base_parameters": names.iter().enumerate().map(|(k, name)| json!({
            "name": name,
            "estimate": id.estimates[k],
            "standard_deviation": id.standard_deviations[k],
            "file_value": file[k],
        })).collect::<Vec<_>>(),
        "residual_rms": id.residual_rms,
        "relative_residual": id.relative_residual,
        "condition": id.condition,
    })
}

/// What `tendyn identify` prints.
pub fn identification_text(m: &Model<f64>, base: &BaseParameters, id: &Identification) -> String {
    let file = base.values(&regressor::values(m));
    let mut s = format!(
        "{}: {} base parameters from {} samples; residual {} N·m rms ({:.2} % of the \
         forces), condition number {:.1e}\n\n  {:>12}  {:>12}  {:>12}  base parameter\n",
        m.name(),
        id.estimates.len(),
        id.samples,
        number(id.residual_rms),
        100.0 * id.relative_residual,
        id.condition,
        "estimate",
        "std. dev.",
        "file value"
    );
    for (k, name) in base.names(m).iter().enumerate() {
        s.push_str(&format!(
            "  {:>12}  {:>12}  {:>12}  {name}\n",
            number(id.estimates[k]),
            number(id.standard_deviations[k]),
            number(file[k])
        ));
    }
    s
}

/// What `tendyn identify --consistent --json` prints: the physically consistent estimate
/// (every body's mass properties and the base parameters they give) beside least squares.
pub fn consistent_json(m: &Model<f64>, base: &BaseParameters, c: &Consistent) -> Value {
    let file = base.values(&regressor::values(m));
    let ls = &c.least_squares;
    json!({
        "mechanism": m.name(),
        "samples": ls.samples,
        "base_parameters": base.names(m).iter().enumerate().map(|(k, name)| json!({
            "name": name,
            "estimate": c.estimates[k],
            "least_squares": ls.estimates[k],
            "standard_deviation": ls.standard_deviations[k],
            "file_value": file[k],
        })).collect::<Vec<_>>(),
        "bodies": m.bodies().iter().zip(&c.bodies).map(|(b, e)| {
            let i = &e.inertia;
            let mut body = json!({
                "name": b.name,
                "mass": e.mass,
                "com": e.com,
                "inertia": {
                    "xx": i[0][0], "yy": i[1][1], "zz": i[2][2],
                    "xy": i[0][1], "xz": i[0][2], "yz": i[1][2],
                },
                "on_boundary": e.on_boundary,
            });
            if let Some((coulomb, viscous)) = e.friction {
                body["friction"] = json!({ "coulomb": coulomb, "viscous": viscous });
            }
            body
        }).collect::<Vec<_>>(),
        "residual_rms": c.residual_rms,
        "relative_residual": c.relative_residual,
        "least_squares_residual_rms": ls.residual_rms,
        "least_squares_relative_residual": ls.relative_residual,
        "condition": ls.condition,
        "newton_steps": c.newton_steps,
        "gap": c.gap,
    })
}

/// What `tendyn identify --consistent` prints.
pub fn consistent_text(m: &Model<f64>, base: &BaseParameters, c: &Consistent) -> String {
    let file = base.values(&regressor::values(m));
    let ls = &c.least_squares;
    let mut s = format!(
        "{}: physically consistent estimate from {} samples; residual {} N·m rms ({:.2} % of \
         the forces; least squares {} N·m, {:.2} %), condition number {:.1e}\n\n  {:>12}  \
         {:>12}  {:>12}  {:>12}  base parameter\n",
        m.name(),
        ls.samples,
        number(c.residual_rms),
        100.0 * c.relative_residual,
        number(ls.residual_rms),
        100.0 * ls.relative_residual,
        ls.condition,
        "consistent",
        "least sq.",
        "std. dev.",
        "file value"
    );
    for (k, name) in base.names(m).iter().enumerate() {
        s.push_str(&format!(
            "  {:>12}  {:>12}  {:>12}  {:>12}  {name}\n",
            number(c.estimates[k]),
            number(ls.estimates[k]),
            number(ls.standard_deviations[k]),
            number(file[k])
        ));
    }
    s.push_str("\nbodies (own frame; inertia about the centre of mass):\n");
    for (b, e) in m.bodies().iter().zip(&c.bodies) {
        let i = &e.inertia;
        s.push_str(&format!(
            "  {}: mass {}, com ({}, {}, {}), inertia xx {} yy {} zz {} xy {} xz {} yz {}",
            b.name,
            number(e.mass),
            number(e.com[0]),
            number(e.com[1]),
            number(e.com[2]),
            number(i[0][0]),
            number(i[1][1]),
            number(i[2][2]),
            number(i[0][1]),
            number(i[0][2]),
            number(i[1][2])
        ));
        if let Some((coulomb, viscous)) = e.friction {
            s.push_str(&format!(
                ", friction coulomb {} viscous {}",
                number(coulomb),
                number(viscous)
            ));
        }
        if e.on_boundary {
            s.push_str(" (on the boundary of physical consistency)");
        }
        s.push('\n');
    }
    s
}
