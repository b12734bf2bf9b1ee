//! Readable equations for `tendyn equations`: the generated functions printed in
//! mathematical notation with the names of the paper and of the file, so that they can be
//! set beside the paper's Eqs. 28-30, 33 and 35.
//!
//! # What is named
//!
//! The equations are the traced (or collected, [`crate::closed_form`]) functions of a copy
//! of the model in which these numbers are parameters, i.e. symbols of the graph:
//!
//! - joint variables `th1, th1d, th1dd`, with `S2 = sin th2`, `C2 = cos th2`; runtime
//!   parameters by their own names;
//! - every non-zero mass, centre-of-mass component, inertia entry and gravity component:
//!   `m2`, `c2x`, `I2zz`, `gy` (pulleys after their names: `m_idler3`, `I_pulley3zz`);
//! - the non-zero DH lengths and offsets of the links, `a1`, `d2` (paper Eqs. 1 and 7): in the
//!   link transform, in `P = (a, d sin α, d cos α)` and, as `−a_j`, in the placement of a
//!   pulley that link `j` carries on its own joint axis;
//! - pulley pitch radii, `r` followed by the pulley's name from its first digit on
//!   (`pulley3` → `r3`, `drum2a` → `r2a`: the paper's numbering in the shipped examples), or
//!   `r_NAME` when the name has no digit or two pulleys would share a name. A radius enters
//!   by name (a) in every tendon contact point, which is exactly `r` times a unit vector
//!   (Eq. 17); (b) in the couplings of pulley angles to the joints (Eqs. 9-10, 26, 31, 34),
//!   re-derived here as products of radius ratios (`r2/r3`) from the routing the model
//!   records, wherever an entry is a single such product; (c) when the tension system
//!   `E x = b` is square (no redundant tendons, as in Example 1), in its exact inverse,
//!   wherever an entry is a single product of radii (`r3/r2`: Eqs. 28-30). The couplings
//!   and the structure matrix `A` (Eqs. 33, 35) are also printed by name.
//!
//! Every name is checked numerically before it is used: a re-derived coupling, entry of `E`
//! or of its inverse must equal the validated model's number (to `1e-12` relative; `E⁻¹` to
//! its conditioning), or that part stays numeric. So the printed equations, evaluated with
//! every name at its file value, are what the runtime solver computes (to rounding; the
//! exact `E⁻¹` differs from the solver's QR-computed `E⁺` by rounding only).
//!
//! # What stays a number
//!
//! Geometry that is not a product or ratio of named quantities: tendon segment directions
//! (common tangents; their angles depend on centre distances and radii together), exit
//! points, pulley heights along joint axes and `Pose` placements, the `(h − d_j)` part of a
//! pulley carried on its own link's joint axis, twist and angle offsets (`sin`/`cos` of
//! them); the pseudo-inverse and null space of a non-square `E` (redundant open-ended
//! routings, Examples 2 and 3) and the positive null vector; coupling entries that are sums of
//! ratios; the idler step `turn / r` of Eq. 24b (kept by `tension::segment_tensions` as a
//! number of the model's `IdlerStep`), and, in `forward_dynamics`, the structure matrix and
//! motor columns (numbers of the model's `Tendon` and `Motor`).

use crate::expr::{Graph, Id, Node};
use crate::outputs::{result_labels, trace, Output, Traced};
use tendyn_core::model::{
    BodyKind, Contact, Model, MotorKind, Place, PulleyRole, Row, Segment, Slot, Unknown, Via,
};
use tendyn_core::spatial::Vec3;
use tendyn_core::transmission::{joint_parent, Frame};

thread_local! {
    /// Names of the runtime parameters of the mechanism being printed.
    static PARAMETERS: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn input_name(g: &Graph, i: u32) -> String {
    let name = &g.input_names[i as usize];
    let (array, index) = name.split_once('[').expect("array input");
    let k: usize = index.trim_end_matches(']').parse::<usize>().expect("index") + 1;
    match array {
        "params" => PARAMETERS.with(|p| p.borrow()[k - 1].clone()),
        "q" => format!("th{k}"),
        "qd" => format!("th{k}d"),
        "qdd" => format!("th{k}dd"),
        "motor_torques" => format!("tau{k}"),
        "tendon_tensions" => format!("T{k}"),
        other => format!("{other}{k}"),
    }
}

fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let s = format!("{x:.6e}");
    // 1.234500e-2 → 1.2345e-2; short numbers in plain form
    if (1e-3..1e4).contains(&x.abs()) {
        let t = format!("{x:.6}");
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// An expression in infix notation with the fewest parentheses; returns text and precedence.
fn show(g: &Graph, id: Id, names: &dyn Fn(Id) -> Option<String>) -> (String, u8) {
    if let Some(n) = names(id) {
        return (n, 4);
    }
    let operand = |x: Id, min: u8| {
        let (t, p) = show(g, x, names);
        if p < min {
            format!("({t})")
        } else {
            t
        }
    };
    match g.node(id) {
        Node::Const(bits) => {
            let x = f64::from_bits(bits);
            (number(x), if x < 0.0 { 3 } else { 4 })
        }
        Node::Input(i) => (input_name(g, i), 4),
        Node::Add(a, b) | Node::Sub(a, b) => {
            // `a + -x·y` reads `a - x·y` (a product or negation with a leading minus).
            let (tb, pb) = show(g, b, names);
            let negated = pb >= 2 && tb.starts_with('-');
            let subtract = matches!(g.node(id), Node::Sub(..)) != negated;
            let tb = if negated { tb[1..].to_string() } else { tb };
            // A sum on the right needs parentheses after a minus only.
            let tb = if pb < 2 && subtract {
                format!("({tb})")
            } else {
                tb
            };
            let op = if subtract { "-" } else { "+" };
            (format!("{} {op} {tb}", operand(a, 1)), 1)
        }
        Node::Mul(a, b) => (format!("{}*{}", operand(a, 2), operand(b, 2)), 2),
        Node::Div(a, b) => (format!("{}/{}", operand(a, 2), operand(b, 3)), 2),
        Node::Neg(a) => (format!("-{}", operand(a, 3)), 3),
        Node::Sin(a) => (trig(g, "S", a, names), 4),
        Node::Cos(a) => (trig(g, "C", a, names), 4),
        Node::Sqrt(a) => (format!("sqrt({})", show(g, a, names).0), 4),
        Node::Tanh(a) => (format!("tanh({})", show(g, a, names).0), 4),
        Node::Exp(a) => (format!("exp({})", show(g, a, names).0), 4),
        Node::Max(a, b) => (
            format!("max({}, {})", show(g, a, names).0, show(g, b, names).0),
            4,
        ),
        Node::SignOutside(a, b, c) => {
            let within = match g.constant_value(c) {
                Some(0.0) => String::new(),
                _ => format!(", else {}", show(g, c, names).0),
            };
            let (a, b) = (show(g, a, names).0, show(g, b, names).0);
            (format!("sgn({a}; ±{b}{within})"), 4)
        }
    }
}

/// A ratio of two named quantities (`r2/r3`, `1/r2`): short enough to print in place
/// rather than as a temporary, which keeps the couplings visible (`th1dd + r2/r3*th2dd`).
fn is_ratio(g: &Graph, id: Id) -> bool {
    let leaf = |x: Id| matches!(g.node(x), Node::Input(_) | Node::Const(_));
    match g.node(id) {
        Node::Div(a, b) => leaf(a) && leaf(b),
        Node::Neg(a) => is_ratio(g, a),
        _ => false,
    }
}

fn trig(g: &Graph, f: &str, a: Id, names: &dyn Fn(Id) -> Option<String>) -> String {
    match g.node(a) {
        Node::Input(i) => format!("{f}{}", input_name(g, i).trim_start_matches("th")),
        _ => format!(
            "{}({})",
            if f == "S" { "sin" } else { "cos" },
            show(g, a, names).0
        ),
    }
}

// ---------------------------------------------------------------------------------------
// Polynomials in the pulley radii: the transmission re-derived by name.
// ---------------------------------------------------------------------------------------

/// `coef · Π r_b^e`: radius powers by pulley body, sorted by body, no zero powers.
#[derive(Clone, Debug, PartialEq)]
struct Term {
    coef: f64,
    powers: Vec<(usize, i32)>,
}

impl Term {
    fn constant(coef: f64) -> Term {
        Term {
            coef,
            powers: Vec::new(),
        }
    }

    /// `sign · r_b^power`.
    fn radius(b: usize, sign: f64, power: i32) -> Term {
        Term {
            coef: sign,
            powers: vec![(b, power)],
        }
    }

    fn times(&self, o: &Term) -> Term {
        let mut powers = self.powers.clone();
        for &(b, e) in &o.powers {
            match powers.iter().position(|&(c, _)| c == b) {
                Some(i) => powers[i].1 += e,
                None => powers.push((b, e)),
            }
        }
        powers.retain(|&(_, e)| e != 0);
        powers.sort_unstable();
        Term {
            coef: self.coef * o.coef,
            powers,
        }
    }

    fn inverse(&self) -> Term {
        Term {
            coef: 1.0 / self.coef,
            powers: self.powers.iter().map(|&(b, e)| (b, -e)).collect(),
        }
    }

    fn eval(&self, radius: &dyn Fn(usize) -> f64) -> f64 {
        self.powers
            .iter()
            .fold(self.coef, |v, &(b, e)| v * radius(b).powi(e))
    }
}

/// A sum of [`Term`]s (like terms merged; terms that cancel to rounding dropped).
#[derive(Clone, Debug, Default, PartialEq)]
struct Poly(Vec<Term>);

impl Poly {
    fn zero() -> Poly {
        Poly(Vec::new())
    }

    fn constant(c: f64) -> Poly {
        Poly::zero().plus_term(&Term::constant(c))
    }

    fn plus_term(mut self, t: &Term) -> Poly {
        if t.coef == 0.0 {
            return self;
        }
        match self.0.iter().position(|u| u.powers == t.powers) {
            Some(i) => {
                let (a, b) = (self.0[i].coef, t.coef);
                let s = a + b;
                if s.abs() <= 8.0 * f64::EPSILON * (a.abs() + b.abs()) {
                    self.0.remove(i);
                } else {
                    self.0[i].coef = s;
                }
            }
            None => self.0.push(t.clone()),
        }
        self
    }

    fn plus(&self, o: &Poly) -> Poly {
        o.0.iter().fold(self.clone(), |p, t| p.plus_term(t))
    }

    fn times_term(&self, t: &Term) -> Poly {
        self.0
            .iter()
            .fold(Poly::zero(), |p, u| p.plus_term(&u.times(t)))
    }

    fn times(&self, o: &Poly) -> Poly {
        o.0.iter()
            .fold(Poly::zero(), |p, t| p.plus(&self.times_term(t)))
    }

    fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    fn single(&self) -> Option<&Term> {
        match self.0.as_slice() {
            [t] => Some(t),
            _ => None,
        }
    }

    fn eval(&self, radius: &dyn Fn(usize) -> f64) -> f64 {
        self.0.iter().map(|t| t.eval(radius)).sum()
    }

    /// In readable notation: `r2/r3`, `-r3`, `0.5/r2`, `r3 - r2`.
    fn text(&self, name: &dyn Fn(usize) -> String) -> String {
        if self.is_zero() {
            return "0".to_string();
        }
        let mut out = String::new();
        for (i, t) in self.0.iter().enumerate() {
            let magnitude = term_text(t, name);
            match (i, t.coef < 0.0) {
                (0, false) => out.push_str(&magnitude),
                (0, true) => out.push_str(&format!("-{magnitude}")),
                (_, false) => out.push_str(&format!(" + {magnitude}")),
                (_, true) => out.push_str(&format!(" - {magnitude}")),
            }
        }
        out
    }
}

/// `|coef| · Π r^e` as text.
fn term_text(t: &Term, name: &dyn Fn(usize) -> String) -> String {
    let factor = |b: usize, e: i32| {
        if e == 1 {
            name(b)
        } else {
            format!("{}^{e}", name(b))
        }
    };
    let num: Vec<String> = t
        .powers
        .iter()
        .filter(|(_, e)| *e > 0)
        .map(|&(b, e)| factor(b, e))
        .collect();
    let den: Vec<String> = t
        .powers
        .iter()
        .filter(|(_, e)| *e < 0)
        .map(|&(b, e)| factor(b, -e))
        .collect();
    let c = t.coef.abs();
    let mut s = match (c == 1.0, num.is_empty()) {
        (true, true) => "1".to_string(),
        (true, false) => num.join("*"),
        (false, true) => number(c),
        (false, false) => format!("{}*{}", number(c), num.join("*")),
    };
    match den.len() {
        0 => {}
        1 => s.push_str(&format!("/{}", den[0])),
        _ => s.push_str(&format!("/({})", den.join("*"))),
    }
    s
}

/// `Σ_j c_j · var(j)` as text, leaving out zero coefficients.
fn linear_text(
    coefficients: &[Poly],
    name: &dyn Fn(usize) -> String,
    var: &dyn Fn(usize) -> String,
) -> String {
    let mut out = String::new();
    for (j, c) in coefficients.iter().enumerate() {
        if c.is_zero() {
            continue;
        }
        let (negative, body) = match c.single() {
            Some(t) => {
                let m = term_text(t, name);
                let body = if m == "1" {
                    var(j)
                } else {
                    format!("{m}*{}", var(j))
                };
                (t.coef < 0.0, body)
            }
            None => (false, format!("({})*{}", c.text(name), var(j))),
        };
        match (out.is_empty(), negative) {
            (true, false) => out.push_str(&body),
            (true, true) => out.push_str(&format!("-{body}")),
            (false, false) => out.push_str(&format!(" + {body}")),
            (false, true) => out.push_str(&format!(" - {body}")),
        }
    }
    if out.is_empty() {
        "0".to_string()
    } else {
        out
    }
}

/// A rate as linear functions of `q̇` (and of driving-pulley angles), by name.
#[derive(Clone, Debug)]
struct Rate {
    joints: Vec<Poly>,
    pulleys: Vec<(usize, Poly)>,
}

impl Rate {
    fn zero(n: usize) -> Rate {
        Rate {
            joints: vec![Poly::zero(); n],
            pulleys: Vec::new(),
        }
    }

    fn add_scaled(&mut self, o: &Rate, by: &Term) {
        for (a, b) in self.joints.iter_mut().zip(&o.joints) {
            *a = a.plus(&b.times_term(by));
        }
        for (p, c) in &o.pulleys {
            self.add_pulley(*p, c.times_term(by));
        }
    }

    fn add_pulley(&mut self, p: usize, c: Poly) {
        match self.pulleys.iter_mut().find(|(q, _)| *q == p) {
            Some((_, v)) => *v = v.plus(&c),
            None => self.pulleys.push((p, c)),
        }
    }

    fn pulley(&self, p: usize) -> Poly {
        self.pulleys
            .iter()
            .find(|(q, _)| *q == p)
            .map_or(Poly::zero(), |(_, c)| c.clone())
    }
}

/// `θ̇` of frame `a` relative to frame `b` when both are bodies of one joint (a pulley's
/// circle on that joint's axis is fixed in both); `None` when they are not.
fn relative_rate(n: usize, a: Frame, b: Frame) -> Option<Rate> {
    let mut r = Rate::zero(n);
    if a == b {
        return Some(r);
    }
    let (j, sign) = match (a, b) {
        (Some(x), _) if joint_parent(x) == b => (x, 1.0),
        (_, Some(y)) if joint_parent(y) == a => (y, -1.0),
        _ => return None,
    };
    *r.joints.get_mut(j)? = Poly::constant(sign);
    Some(r)
}

/// The turn (`+1` counter-clockwise) of a tendon at a pulley contact, read from the
/// segment's geometry: the contact point is `turn · r (dir × z)` (Eq. 17), `z` the pulley's
/// axis in the segment's frame.
fn turn_at(
    model: &Model<f64>,
    segment: &Segment<f64>,
    contact: &Contact<f64>,
) -> Option<(usize, f64)> {
    let b = contact.body?;
    let body = model.bodies().get(b)?;
    let BodyKind::Pulley { radius, .. } = body.kind else {
        return None;
    };
    let axis = match contact.via {
        Via::Carrier => body.pre.rotation.column(2),
        Via::CarrierParent => Vec3::unit_z(),
        Via::CarrierChild(l) => model.bodies().get(l)?.axis,
    };
    let s = segment.dir.cross(axis).dot(contact.rel) / radius;
    ((s.abs() - 1.0).abs() <= 1e-9).then_some((b, s.signum()))
}

/// The transmission by name: what validation derived in numbers, re-derived as polynomials
/// in the radii from the routing the model records, and checked against those numbers.
#[derive(Clone, Debug)]
struct Transmission {
    /// Per body, its coupling (a link's is its unit row).
    couplings: Vec<Vec<Poly>>,
    /// Per tendon, its column of the structure matrix `A`.
    structure: Vec<Vec<Poly>>,
    /// `E⁻¹` (unknowns × rows) when `E` is square with a one-term determinant.
    inverse: Option<Vec<Vec<Poly>>>,
}

/// Mirrors `transmission::Routing::trace` by name: the couplings of the pulleys a strand
/// passes (and ends on), and its pull rate `ẋ` with driving-pulley angles as coordinates.
fn walk(
    model: &Model<f64>,
    stops: &[(usize, f64)],
    frames: &[Frame],
    ends_on_pulley: bool,
    couplings: &mut [Option<Vec<Poly>>],
) -> Option<Rate> {
    let n = model.dof();
    let carrier = |b: usize| model.bodies()[b].parent;
    let (start, s0) = stops[0];
    let start_coupling = Rate {
        joints: couplings[start].clone()?,
        pulleys: Vec::new(),
    };
    let mut pull = Rate::zero(n);
    let mut body_rate = start_coupling.clone();
    body_rate.add_scaled(
        &relative_rate(n, carrier(start), frames[0])?,
        &Term::constant(1.0),
    );
    pull.add_scaled(&body_rate, &Term::radius(start, s0, 1));
    for (i, &(p, s)) in stops.iter().enumerate().skip(1) {
        let incoming = frames[i - 1];
        // The rim moves with the tendon (Eqs. 9-10, 26): this pulley's coupling.
        let mut c = Rate::zero(n);
        c.add_scaled(&pull, &Term::radius(p, s, -1));
        c.add_scaled(
            &relative_rate(n, incoming, carrier(p))?,
            &Term::constant(1.0),
        );
        if couplings[p].is_none() {
            couplings[p] = Some(c.joints);
        }
        if let Some(&out) = frames.get(i) {
            pull.add_scaled(&relative_rate(n, incoming, out)?, &Term::radius(p, s, 1));
        }
    }
    let mut expanded = pull;
    let driving = |b: usize| {
        matches!(
            model.bodies()[b].kind,
            BodyKind::Pulley {
                role: PulleyRole::Driving,
                ..
            }
        )
    };
    if driving(start) {
        expanded.add_scaled(&start_coupling, &Term::radius(start, -s0, 1));
        expanded.add_pulley(start, Poly::zero().plus_term(&Term::radius(start, s0, 1)));
    }
    if ends_on_pulley {
        let &(e, t) = stops.last()?;
        let incoming = *frames.last()?;
        expanded.add_scaled(
            &relative_rate(n, incoming, carrier(e))?,
            &Term::radius(e, t, 1),
        );
        expanded.add_pulley(e, Poly::zero().plus_term(&Term::radius(e, -t, 1)));
    }
    Some(expanded)
}

/// Whether `derived` (evaluated at the file's radii) equals `x` to `tol`.
fn agrees(derived: &Poly, radius: &dyn Fn(usize) -> f64, x: f64, tol: f64) -> bool {
    let v = derived.eval(radius);
    v.is_finite() && (v - x).abs() <= tol
}

fn radius_of(model: &Model<f64>, b: usize) -> f64 {
    match model.bodies()[b].kind {
        BodyKind::Pulley { radius, .. } => radius,
        BodyKind::Link { .. } => f64::NAN,
    }
}

/// The transmission by name, or `None` where the routing is not what this derivation
/// covers or any re-derived number disagrees with validation's.
fn derive(model: &Model<f64>) -> Option<Transmission> {
    let radius = |b: usize| radius_of(model, b);
    let mut couplings: Vec<Option<Vec<Poly>>> = model
        .bodies()
        .iter()
        .map(|b| match b.kind {
            // Links, fixed drums and explicitly coupled pulleys: the model's numbers.
            BodyKind::Link { .. }
            | BodyKind::Pulley {
                role: PulleyRole::Fixed | PulleyRole::Coupled,
                ..
            } => Some(b.coupling.iter().map(|&c| Poly::constant(c)).collect()),
            _ => None,
        })
        .collect();

    // Each strand: the pulleys it touches with their turns, and its segments' frames.
    struct Walk {
        stops: Vec<(usize, f64)>,
        frames: Vec<Frame>,
        ends_on_pulley: bool,
    }
    let mut walks = Vec::new();
    for strand in model.strands() {
        let segments = &strand.segments;
        let first = segments.first()?;
        let mut stops = vec![turn_at(model, first, &first.from)?];
        for (k, seg) in segments.iter().enumerate() {
            match seg.to.body {
                Some(_) => stops.push(turn_at(model, seg, &seg.to)?),
                None if k + 1 == segments.len() => {}
                None => return None,
            }
        }
        let ends_on_pulley = segments.last()?.to.body.is_some();
        if stops.len() != segments.len() + usize::from(ends_on_pulley)
            || strand.idlers.len() + 1 != segments.len()
            || strand
                .idlers
                .iter()
                .zip(&stops[1..])
                .any(|(idler, &(b, s))| idler.body != b || idler.turn != s)
        {
            return None;
        }
        walks.push(Walk {
            stops,
            frames: segments.iter().map(|s| s.frame).collect(),
            ends_on_pulley,
        });
    }
    // Each strand once the coupling of the body it starts from is known.
    let mut rates: Vec<Option<Rate>> = vec![None; walks.len()];
    loop {
        let mut progressed = false;
        for (s, w) in walks.iter().enumerate() {
            if rates[s].is_none() && couplings[w.stops[0].0].is_some() {
                rates[s] = Some(walk(
                    model,
                    &w.stops,
                    &w.frames,
                    w.ends_on_pulley,
                    &mut couplings,
                )?);
                progressed = true;
            }
        }
        if !progressed {
            break;
        }
    }
    let rates: Vec<Rate> = rates.into_iter().collect::<Option<_>>()?;
    let couplings: Vec<Vec<Poly>> = couplings.into_iter().collect::<Option<_>>()?;

    // E, column by column, as validation builds it (`validate::tension_system`).
    let system = model.system();
    let mut e = vec![vec![Poly::zero(); system.unknowns.len()]; system.rows.len()];
    for (col, u) in system.unknowns.iter().enumerate() {
        for (r, row) in system.rows.iter().enumerate() {
            e[r][col] = match (u, row) {
                (Unknown::Strand(s), Row::Joint(j)) => rates.get(*s)?.joints[*j].clone(),
                (Unknown::Strand(s), Row::Pulley(b)) => rates.get(*s)?.pulley(*b),
                (Unknown::Strand(s), Row::Pretension(l)) => {
                    let on_loop = model.loops().get(*l)?.strands.contains(s);
                    Poly::constant(if on_loop { 0.5 } else { 0.0 })
                }
                (Unknown::Explicit(k), Row::Joint(j)) => {
                    Poly::constant(model.tendons().get(*k)?.structure[*j])
                }
                (Unknown::Motor(k), row) => match (model.motors().get(*k)?.kind.clone(), row) {
                    (MotorKind::Joint(j), Row::Joint(i)) => {
                        Poly::constant(if j == *i { 1.0 } else { 0.0 })
                    }
                    (MotorKind::Pulley(b), Row::Pulley(c)) => {
                        Poly::constant(if b == *c { 1.0 } else { 0.0 })
                    }
                    (MotorKind::Pulley(b), Row::Joint(i))
                        if !system.rows.contains(&Row::Pulley(b)) =>
                    {
                        couplings[b][*i].clone()
                    }
                    _ => Poly::zero(),
                },
                _ => Poly::zero(),
            };
        }
    }
    let structure: Vec<Vec<Poly>> = model
        .tendons()
        .iter()
        .map(|t| match t.strand {
            Some(s) => rates[s].joints.clone(),
            None => t.structure.iter().map(|&x| Poly::constant(x)).collect(),
        })
        .collect();

    // Everything must be validation's numbers, by name.
    const TOL: f64 = 1e-12;
    for (b, body) in model.bodies().iter().enumerate() {
        for (c, &x) in couplings[b].iter().zip(&body.coupling) {
            if !agrees(c, &radius, x, TOL * (1.0 + x.abs())) {
                return None;
            }
        }
    }
    let scale = system
        .matrix
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    for (derived, numbers) in e.iter().zip(&system.matrix) {
        for (d, &x) in derived.iter().zip(numbers) {
            if !agrees(d, &radius, x, TOL * scale) {
                return None;
            }
        }
    }
    for (t, column) in model.tendons().iter().zip(&structure) {
        for (d, &x) in column.iter().zip(&t.structure) {
            if !agrees(d, &radius, x, TOL * scale) {
                return None;
            }
        }
    }
    let inverse = exact_inverse(&e).filter(|inv| {
        // The solver's E⁺ is QR-computed: it agrees to the conditioning of E.
        let pinv = &system.pseudo_inverse;
        let scale = pinv.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let tol = 1e-10 * system.condition.max(1.0) * scale;
        inv.iter().zip(pinv).all(|(derived, numbers)| {
            derived
                .iter()
                .zip(numbers)
                .all(|(d, &x)| agrees(d, &radius, x, tol))
        })
    });
    Some(Transmission {
        couplings,
        structure,
        inverse,
    })
}

/// Largest square `E` inverted by name (cofactors by Laplace expansion over column subsets).
const MAX_SYMBOLIC_INVERSE: usize = 8;

/// `E⁻¹ = adj(E) / det(E)` by name when `E` is square, small and its determinant a single
/// term (so that every entry is a polynomial); `None` otherwise.
fn exact_inverse(e: &[Vec<Poly>]) -> Option<Vec<Vec<Poly>>> {
    let m = e.len();
    if m == 0 || m > MAX_SYMBOLIC_INVERSE || e.iter().any(|row| row.len() != m) {
        return None;
    }
    let all = (1u32 << m) - 1;
    let rows: Vec<usize> = (0..m).collect();
    let det = determinant(e, &rows, all, &mut std::collections::HashMap::new());
    let inv_det = det.single()?.inverse();
    let mut inverse = vec![vec![Poly::zero(); m]; m];
    for i in 0..m {
        let minor_rows: Vec<usize> = (0..m).filter(|&r| r != i).collect();
        let mut memo = std::collections::HashMap::new();
        for (j, row) in inverse.iter_mut().enumerate() {
            let sign = if (i + j) % 2 == 0 { 1.0 } else { -1.0 };
            let minor = determinant(e, &minor_rows, all & !(1 << j), &mut memo);
            // (E⁻¹)_ji = (−1)^(i+j) M_ij / det E
            row[i] = minor.times_term(&Term::constant(sign).times(&inv_det));
        }
    }
    Some(inverse)
}

/// Determinant of `e` restricted to `rows` and the columns in the bit set `cols`
/// (`rows.len()` equal to the number of columns at the top call), expanding along rows in
/// order; `memo` is keyed by the remaining columns, for one list of rows.
fn determinant(
    e: &[Vec<Poly>],
    rows: &[usize],
    cols: u32,
    memo: &mut std::collections::HashMap<u32, Poly>,
) -> Poly {
    if cols == 0 {
        return Poly::constant(1.0);
    }
    if let Some(p) = memo.get(&cols) {
        return p.clone();
    }
    let r = rows[rows.len() - cols.count_ones() as usize];
    let mut acc = Poly::zero();
    let mut sign = 1.0;
    for c in (0..32).filter(|c| cols & (1 << c) != 0) {
        if !e[r][c].is_zero() {
            let minor = determinant(e, rows, cols & !(1 << c), memo);
            acc = acc.plus(&e[r][c].times(&minor).times_term(&Term::constant(sign)));
        }
        sign = -sign;
    }
    memo.insert(cols, acc.clone());
    acc
}

// ---------------------------------------------------------------------------------------
// Naming.
// ---------------------------------------------------------------------------------------

/// A mechanism with its quantities named, traced: what `tendyn equations` prints.
pub struct Named {
    /// The model the equations were traced from: the mechanism's, with the named quantities
    /// as parameters (`parameters[k].value` is each one's file value) and, when `E` is square,
    /// the exact `E⁻¹` in place of the QR-computed one.
    pub model: Model<f64>,
    /// The requested outputs, traced from [`Named::model`]: what is printed.
    pub traced: Traced,
    transmission: Option<Transmission>,
    /// Per body: the name of its radius (pulleys).
    radius_names: Vec<Option<String>>,
    /// The lengths and radii that print by name, in the order of the legend.
    pub lengths: Vec<NamedLength>,
}

/// A length or radius that prints by name.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedLength {
    /// Its name in the equations (`a1`, `d2`, `r3`, `r_NAME`).
    pub name: String,
    /// Its value in the file.
    pub value: f64,
    /// Which length or radius it is.
    pub quantity: Quantity,
}

/// Which length or radius a [`NamedLength`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// DH length `a` of link (body) `j`.
    DhA(usize),
    /// DH offset `d` of link (body) `j`.
    DhD(usize),
    /// Pitch radius of pulley body `b`.
    Radius(usize),
}

impl Quantity {
    fn describe(self, model: &Model<f64>) -> String {
        match self {
            Quantity::DhA(j) => format!("DH a of {}", model.bodies()[j].name),
            Quantity::DhD(j) => format!("DH d of {}", model.bodies()[j].name),
            Quantity::Radius(b) => format!("radius of {}", model.bodies()[b].name),
        }
    }
}

/// Names numbers of the model as new parameters, each name unique among all parameters
/// (what [`Model::with_named_numbers`] then adds).
struct Namer<'m> {
    model: &'m Model<f64>,
    /// Slots the file's own runtime parameters already set.
    taken: Vec<Slot>,
    /// The new parameters' names and values; parameter `k` is `added[k − file's count]`.
    added: Vec<(String, f64)>,
    /// Every number named, `(where, index into added)`.
    slots: Vec<(Slot, usize)>,
}

impl Namer<'_> {
    fn unique(&self, name: String) -> String {
        let mut name = name;
        let file = self.model.parameters().iter().map(|p| &p.name);
        while file
            .clone()
            .chain(self.added.iter().map(|(n, _)| n))
            .any(|n| *n == name)
        {
            name.push('\'');
        }
        name
    }

    /// A parameter `name` with file value `value` setting `slots`; `None` (nothing added)
    /// when the value is zero or a runtime parameter already sets one of the slots.
    fn add(&mut self, name: String, value: f64, slots: &[Slot]) -> Option<usize> {
        if value == 0.0 || slots.iter().any(|s| self.taken.contains(s)) {
            return None;
        }
        let name = self.unique(name);
        let i = self.added.len();
        self.added.push((name, value));
        self.slots.extend(slots.iter().map(|&s| (s, i)));
        Some(self.model.parameters().len() + i)
    }

    /// One more number that the added parameter `k` sets.
    fn also(&mut self, k: usize, slot: Slot) {
        self.slots.push((slot, k - self.model.parameters().len()));
    }
}

/// `r` and the pulley's name from its first digit on (`pulley3` → `r3`), or `r_NAME`; the
/// latter also for every pulley whose short name another pulley would share.
fn radius_names(model: &Model<f64>) -> Vec<Option<String>> {
    let short = |name: &str| {
        name.find(|c: char| c.is_ascii_digit())
            .map(|i| format!("r{}", &name[i..]))
            .unwrap_or_else(|| format!("r_{name}"))
    };
    let shorts: Vec<Option<String>> = model
        .bodies()
        .iter()
        .map(|b| matches!(b.kind, BodyKind::Pulley { .. }).then(|| short(&b.name)))
        .collect();
    model
        .bodies()
        .iter()
        .zip(&shorts)
        .map(|(b, s)| {
            let s = s.as_ref()?;
            let shared = shorts.iter().filter(|t| t.as_ref() == Some(s)).count() > 1;
            Some(if shared {
                format!("r_{}", b.name)
            } else {
                s.clone()
            })
        })
        .collect()
}

/// `model` with its quantities named (see the module documentation), traced.
pub fn named(model: &Model<f64>, outputs: &[Output]) -> Result<Named, crate::Error> {
    let mut namer = Namer {
        model,
        taken: model.parameter_slots().iter().map(|(s, _)| *s).collect(),
        added: Vec::new(),
        slots: Vec::new(),
    };
    let axes = ["x", "y", "z"];
    let dof = model.dof();
    // Masses, centres of mass, inertias (Eqs. 6, 21-22) and gravity.
    for (b, body) in model.bodies().iter().enumerate() {
        let tag = if b < dof {
            format!("{}", b + 1)
        } else {
            format!("_{}", body.name)
        };
        namer.add(format!("m{tag}"), body.mass, &[Slot::Mass(b)]);
        for (c, axis) in axes.iter().enumerate() {
            namer.add(
                format!("c{tag}{axis}"),
                body.com.to_array()[c],
                &[Slot::Com(b, c)],
            );
        }
        for (r, c) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)] {
            namer.add(
                format!("I{tag}{}{}", axes[r], axes[c]),
                body.inertia.rows[r][c],
                &[Slot::Inertia(b, r, c)],
            );
        }
    }
    for (c, axis) in axes.iter().enumerate() {
        namer.add(
            format!("g{axis}"),
            model.gravity().to_array()[c],
            &[Slot::Gravity(c)],
        );
    }

    // DH lengths and offsets (Eqs. 1, 7): `post = TransZ(d)·TransX(a)·RotX(α)`, so
    // `post` translates by (a, 0, d) and `P = postᵀ(a, 0, d) = (a, d sin α, d cos α)`.
    let geometry = |place: Place| Slot::Geometry(place, 1);
    let mut legend = Vec::new();
    for j in 0..dof {
        let link = &model.bodies()[j];
        let (a, d) = (link.post.translation.x, link.post.translation.z);
        let mut a_slots = vec![
            geometry(Place::Post(j, 0)),
            geometry(Place::JointToOrigin(j, 0)),
        ];
        // A pulley link j carries on its own joint's axis is placed by
        // `post⁻¹ · TransZ(h)`, whose x translation is exactly −a.
        for (b, body) in model.bodies().iter().enumerate().skip(dof) {
            if body.parent == Some(j)
                && body.pre.rotation == link.post.rotation.transpose()
                && body.pre.translation.x == -a
            {
                a_slots.push(geometry(Place::Pre(b, 0)));
            }
        }
        let d_slots = [
            geometry(Place::Post(j, 2)),
            geometry(Place::JointToOrigin(j, 1)),
            geometry(Place::JointToOrigin(j, 2)),
        ];
        if let Some(k) = namer.add(format!("a{}", j + 1), a, &a_slots) {
            legend.push((k, Quantity::DhA(j)));
        }
        if let Some(k) = namer.add(format!("d{}", j + 1), d, &d_slots) {
            legend.push((k, Quantity::DhD(j)));
        }
    }

    // Pitch radii: contact points (Eq. 17) always; couplings and E⁻¹ where re-derived.
    let transmission = derive(model);
    let names = radius_names(model);
    let mut radius_parameter = vec![None; model.bodies().len()];
    for (b, name) in names.iter().enumerate() {
        let Some(name) = name else { continue };
        let r = radius_of(model, b);
        let mut slots = Vec::new();
        for (s, strand) in model.strands().iter().enumerate() {
            for (k, seg) in strand.segments.iter().enumerate() {
                for (end, c) in [&seg.from, &seg.to].into_iter().enumerate() {
                    let exact = c.rel.dot(c.rel).sqrt();
                    if c.body == Some(b) && (exact - r).abs() <= 1e-12 * r {
                        slots.push(geometry(Place::Contact(s, k, end)));
                    }
                }
            }
        }
        radius_parameter[b] = namer.add(name.clone(), r, &slots);
        if let Some(k) = radius_parameter[b] {
            legend.push((k, Quantity::Radius(b)));
        }
    }
    let monomial = |namer: &mut Namer, place: Place, t: &Term| {
        for &(b, e) in &t.powers {
            let k = radius_parameter[b].expect("every pulley's radius is named");
            namer.also(k, Slot::Geometry(place, e as i8));
        }
    };
    let mut exact_inverse = Vec::new();
    if let Some(t) = &transmission {
        for (b, coupling) in t.couplings.iter().enumerate().skip(dof) {
            for (j, c) in coupling.iter().enumerate() {
                if let Some(term) = c.single().filter(|t| !t.powers.is_empty()) {
                    monomial(&mut namer, Place::Coupling(b, j), term);
                }
            }
        }
        if let Some(inverse) = &t.inverse {
            // The exact E⁻¹ replaces the QR-computed one where it is a single term (rows of
            // pretensions are not used: those enter exactly, `tension::solution`).
            let radius = |b: usize| radius_of(model, b);
            for (u, row) in inverse.iter().enumerate() {
                for (r, entry) in row.iter().enumerate() {
                    if matches!(model.system().rows[r], Row::Pretension(_)) {
                        continue;
                    }
                    match (entry.is_zero(), entry.single()) {
                        (true, _) => exact_inverse.push(((u, r), 0.0)),
                        (false, Some(term)) => {
                            exact_inverse.push(((u, r), term.eval(&radius)));
                            monomial(&mut namer, Place::PseudoInverse(u, r), term);
                        }
                        (false, None) => {}
                    }
                }
            }
        }
    }
    let m = model.with_named_numbers(&namer.added, &namer.slots, &exact_inverse)?;
    let traced = trace(&m, outputs)?;
    let lengths = legend
        .into_iter()
        .map(|(k, quantity)| NamedLength {
            name: m.parameters()[k].name.clone(),
            value: m.parameters()[k].value,
            quantity,
        })
        .collect();
    let radius_names = (0..m.bodies().len())
        .map(|b| radius_parameter[b].map(|k| m.parameters()[k].name.clone()))
        .collect();
    Ok(Named {
        model: m,
        traced,
        transmission,
        radius_names,
        lengths,
    })
}

/// The equations of `outputs`, as text. (Without `--outputs`, `tendyn equations` asks for
/// the generalized forces and, where the mechanism can provide it, the actuation.)
pub fn equations(model: &Model<f64>, outputs: &[Output]) -> Result<String, crate::Error> {
    let named = named(model, outputs)?;
    Ok(render(&named))
}

fn render(named: &Named) -> String {
    let model = &named.model;
    let traced = &named.traced;
    PARAMETERS
        .with(|p| *p.borrow_mut() = model.parameters().iter().map(|p| p.name.clone()).collect());
    let g = &traced.graph;
    let radius_name = |b: usize| {
        named.radius_names[b]
            .clone()
            .unwrap_or_else(|| format!("r_{}", model.bodies()[b].name))
    };
    let mut out = String::new();
    out.push_str(&format!(
        "# {}: closed-form equations (th_k = joint angle q_k, th_kd, th_kdd its rates; S_k = sin th_k, C_k = cos th_k)\n",
        model.name()
    ));
    if !named.lengths.is_empty() {
        out.push_str("\nLengths and radii by name (file values):\n");
        for l in &named.lengths {
            out.push_str(&format!(
                "  {} = {} ({})\n",
                l.name,
                number(l.value),
                l.quantity.describe(model)
            ));
        }
    }
    let pulleys: Vec<usize> = (model.dof()..model.bodies().len())
        .filter(|&b| model.bodies()[b].coupling.iter().any(|&c| c != 0.0))
        .collect();
    if !pulleys.is_empty() {
        out.push_str("\nPulley angles relative to their carriers (Eqs. 9-10, 26, 31, 34):\n");
        for b in pulleys {
            let coupling: Vec<Poly> = match &named.transmission {
                Some(t) => t.couplings[b].clone(),
                None => model.bodies()[b]
                    .coupling
                    .iter()
                    .map(|&c| Poly::constant(c))
                    .collect(),
            };
            out.push_str(&format!(
                "  {:<10} {}\n",
                model.bodies()[b].name,
                linear_text(&coupling, &radius_name, &|j| format!("th{}", j + 1))
            ));
        }
    }
    if !model.tendons().is_empty() {
        out.push_str("\nStructure matrix A (Q = A T; rows per joint, columns per tendon):\n");
        for j in 0..model.dof() {
            let cells: Vec<String> = model
                .tendons()
                .iter()
                .enumerate()
                .map(|(k, t)| match &named.transmission {
                    Some(tr) => tr.structure[k][j].text(&radius_name),
                    None => number(t.structure[j]),
                })
                .collect();
            out.push_str(&format!(
                "  {:<10} [{}]\n",
                model.bodies()[j].name,
                cells.join(", ")
            ));
        }
    }
    for f in &traced.functions {
        out.push_str(&format!(
            "\n{} ({}):\n",
            f.output.name(),
            g.count(&f.results)
        ));
        // Shared subexpressions become named temporaries w1, w2, ...
        let live = g.live(&f.results);
        let mut uses = std::collections::BTreeMap::<Id, usize>::new();
        for &id in &live {
            for c in g.node(id).children() {
                *uses.entry(c).or_default() += 1;
            }
        }
        let shared: Vec<Id> = live
            .iter()
            .copied()
            .filter(|id| {
                uses.get(id).copied().unwrap_or(0) > 1
                    && !matches!(
                        g.node(*id),
                        Node::Const(_) | Node::Input(_) | Node::Sin(_) | Node::Cos(_)
                    )
                    && !is_ratio(g, *id)
            })
            .collect();
        let name_of = |id: Id| {
            shared
                .iter()
                .position(|&s| s == id)
                .map(|k| format!("w{}", k + 1))
        };
        for (k, &id) in shared.iter().enumerate() {
            let body = {
                let inner = |x: Id| if x == id { None } else { name_of(x) };
                show(g, id, &inner).0
            };
            out.push_str(&format!("  w{} = {}\n", k + 1, body));
        }
        let labels = result_labels(model, f.output);
        for (i, &r) in f.results.iter().enumerate() {
            let label = match f.output {
                Output::MassMatrix => {
                    let n = model.dof();
                    format!("M[{}][{}]", labels[i / n], labels[i % n])
                }
                _ => labels.get(i).cloned().unwrap_or_else(|| format!("#{i}")),
            };
            let expr = if shared.contains(&r) {
                name_of(r).expect("named")
            } else {
                show(g, r, &name_of).0
            };
            out.push_str(&format!("  {} {label} = {expr}\n", f.output.name()));
        }
    }
    out
}
