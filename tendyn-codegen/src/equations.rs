//! Readable equations for `tendyn equations`: the generated functions printed in
//! mathematical notation with the names of the paper and of the file, so that they can be
//! set beside the paper's Eqs. 28-30, 33 and 35.
//!
//! # What is named
//!
//! - joint variables `th1, th1d, th1dd`, with `S2 = sin th2`, `C2 = cos th2`; runtime
//!   parameters by their own names;
//! - every non-zero mass, centre-of-mass component, inertia entry and gravity component:
//!   `m2`, `c2x`, `I2zz`, `gy` (pulleys after their names: `m_idler3`, `I_pulley3zz`), as
//!   parameters of a copy of the model ([`Model::with_named_numbers`]);
//! - the non-zero DH lengths and offsets of the links, `a1`, `d2` (paper Eqs. 1 and 7), and
//!   pulley pitch radii, `r` followed by the pulley's name from its first digit on
//!   (`pulley3` → `r3`, `drum2a` → `r2a`: the paper's numbering in the shipped examples), or
//!   `r_NAME` when the name has no digit or two pulleys would share a name. These are inputs
//!   `lengths[k]` of their own.
//!
//! The equations are traced from [`Model::symbolic_geometry`]: the model with its geometry
//! derived again from the lengths and radii as symbols, by the functions validation derives
//! it with (link frames, the placements of pulleys on their own link's joint axis, the
//! routing's contact points, couplings and pull rates, and `E`). So a name appears wherever
//! the derivation puts that quantity, and nowhere by a match of numbers: in the link
//! transforms and `P` (Eq. 7), in every tendon contact point (`r` times a unit vector,
//! Eq. 17), in the couplings (Eqs. 9-10, 26, 31, 34) and in `E` (Eqs. 33, 35). The couplings
//! and the structure matrix `A` print in the legend as polynomials in the radii read back
//! from the graph. When `E` is square (no redundant tendons, as in Example 1), its inverse is
//! computed by name from those polynomials, checked against the solver's QR-computed `E⁺` to
//! the conditioning of `E`, and its single-term entries replace the numbers (`r3/r2`: Eqs.
//! 28-30).
//!
//! # What stays a number
//!
//! What validation decides from numbers: tendon segment directions (common tangents; their
//! angles depend on centre distances and radii together), exit points, pulley heights along
//! joint axes and `Pose` placements, twist and angle offsets (`sin`/`cos` of them); the
//! pseudo-inverse and null space of a non-square `E` (redundant open-ended routings,
//! Examples 2 and 3) and the positive null vector; a guide's sliding rate and wrap angle;
//! the idler step `turn / r` of Eq. 24b
//! (kept by `tension::segment_tensions` as a number of the model's `IdlerStep`), and, in
//! `forward_dynamics`, the structure matrix and motor columns (numbers of the model's
//! `Tendon` and `Motor`).

use crate::expr::{Graph, Id, Node, Sym};
use crate::outputs::{self, result_labels, Output, Traced};
use tendyn_core::model::{BodyKind, Dimensions, Model, Row, Slot};
use tendyn_core::Real;

thread_local! {
    /// Names of the runtime parameters of the mechanism being printed.
    static PARAMETERS: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
    /// Names of its lengths and radii.
    static LENGTHS: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn input_name(g: &Graph, i: u32) -> String {
    let name = &g.input_names[i as usize];
    let (array, index) = name.split_once('[').expect("array input");
    let k: usize = index.trim_end_matches(']').parse::<usize>().expect("index") + 1;
    match array {
        "params" => PARAMETERS.with(|p| p.borrow()[k - 1].clone()),
        "lengths" => LENGTHS.with(|l| l.borrow()[k - 1].clone()),
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
        Node::SelectOutside([a, b, p, m, o]) => {
            let [a, b, p, m, o] = [a, b, p, m, o].map(|x| show(g, x, names).0);
            (format!("select({a}; ±{b}: {p}, {m}, else {o})"), 4)
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
// Polynomials in the pulley radii: the transmission read back from the graph by name.
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

/// What the graph holds at `id` as a polynomial in the radii (negative powers allowed):
/// `radius(id)` names the inputs that are radii (by pulley body), numbers are constants;
/// `None` where it is anything else, or divides by a sum.
fn poly_of(g: &Graph, id: Id, radius: &dyn Fn(Id) -> Option<usize>) -> Option<Poly> {
    let of = |x: Id| poly_of(g, x, radius);
    let minus = |p: Poly| p.times_term(&Term::constant(-1.0));
    Some(match g.node(id) {
        Node::Const(bits) => Poly::constant(f64::from_bits(bits)),
        Node::Input(_) => Poly::zero().plus_term(&Term::radius(radius(id)?, 1.0, 1)),
        Node::Add(a, b) => of(a)?.plus(&of(b)?),
        Node::Sub(a, b) => of(a)?.plus(&minus(of(b)?)),
        Node::Mul(a, b) => of(a)?.times(&of(b)?),
        Node::Div(a, b) => of(a)?.times_term(&of(b)?.single()?.inverse()),
        Node::Neg(a) => minus(of(a)?),
        _ => return None,
    })
}

/// `coef · Π r^e` as a symbol: `r2/r3`, `-r3`, `0.5/r2` (the number leads; a divisor
/// divides, so that `1/r` is not a product).
fn term_sym(t: &Term, radius: &dyn Fn(usize) -> Sym) -> Sym {
    let mut numerator: Option<Sym> = None;
    for &(b, e) in t.powers.iter().filter(|(_, e)| *e > 0) {
        for _ in 0..e {
            numerator = Some(numerator.map_or(radius(b), |y| y * radius(b)));
        }
    }
    let divide = |mut y: Sym| {
        for &(b, e) in t.powers.iter().filter(|(_, e)| *e < 0) {
            for _ in 0..-e {
                y = y / radius(b);
            }
        }
        y
    };
    let coef = Sym::from_f64(t.coef);
    match numerator {
        Some(q) => coef * divide(q),
        None => divide(coef),
    }
}

/// The transmission by name: the couplings and `E` as the symbolic model derived them,
/// read back as polynomials in the radii.
#[derive(Clone, Debug)]
struct Transmission {
    /// Per body, its coupling (a link's is its unit row).
    couplings: Vec<Vec<Poly>>,
    /// Per tendon, its column of the structure matrix `A`.
    structure: Vec<Vec<Poly>>,
}

/// The symbolic model `s`'s couplings and `E` read back as polynomials in the radii
/// (`radii`: the inputs that are radii, with their pulley bodies), each entry that does not
/// read as one being the f64 `model`'s number: the transmission to print, and `E`.
fn by_name(
    g: &Graph,
    s: &Model<Sym>,
    model: &Model<f64>,
    radii: &[(Id, usize)],
) -> (Transmission, Vec<Vec<Poly>>) {
    let radius = |id: Id| radii.iter().find(|(r, _)| *r == id).map(|&(_, b)| b);
    let polys = |syms: &[Sym], numbers: &[f64]| -> Vec<Poly> {
        (syms.iter().zip(numbers))
            .map(|(x, &n)| poly_of(g, x.0, &radius).unwrap_or_else(|| Poly::constant(n)))
            .collect()
    };
    let couplings = (s.bodies().iter().zip(model.bodies()))
        .map(|(b, numbers)| polys(&b.coupling, &numbers.coupling))
        .collect();
    let e: Vec<Vec<Poly>> = (s.system().matrix.iter().zip(&model.system().matrix))
        .map(|(row, numbers)| polys(row, numbers))
        .collect();
    let structure = (model.tendons().iter())
        .map(|t| match t.strand {
            Some(_) => (0..model.dof()).map(|j| e[j][t.unknown].clone()).collect(),
            None => t.structure.iter().map(|&x| Poly::constant(x)).collect(),
        })
        .collect();
    let transmission = Transmission {
        couplings,
        structure,
    };
    (transmission, e)
}

/// Where a square `E`'s exact inverse by name is a single term or zero, that entry
/// `(unknown, row)` (rows of pretensions are left out: those enter exactly,
/// `tension::solution`), checked against the solver's QR-computed `E⁺` to the conditioning
/// of `E`.
fn exact_inverse_entries(e: &[Vec<Poly>], model: &Model<f64>) -> Vec<((usize, usize), Term)> {
    let Some(inverse) = exact_inverse(e) else {
        return Vec::new();
    };
    let system = model.system();
    let radius = |b: usize| radius_of(model, b);
    let pinv = &system.pseudo_inverse;
    let scale = pinv.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = 1e-10 * system.condition.max(1.0) * scale;
    let agrees = (inverse.iter().zip(pinv)).all(|(derived, numbers)| {
        (derived.iter().zip(numbers)).all(|(d, &x)| {
            let v = d.eval(&radius);
            v.is_finite() && (v - x).abs() <= tol
        })
    });
    if !agrees {
        return Vec::new();
    }
    let mut entries = Vec::new();
    for (u, row) in inverse.iter().enumerate() {
        for (r, entry) in row.iter().enumerate() {
            if matches!(system.rows[r], Row::Pretension(_)) {
                continue;
            }
            match (entry.is_zero(), entry.single()) {
                (true, _) => entries.push(((u, r), Term::constant(0.0))),
                (false, Some(term)) => entries.push(((u, r), term.clone())),
                (false, None) => {}
            }
        }
    }
    entries
}

fn radius_of(model: &Model<f64>, b: usize) -> f64 {
    match model.bodies()[b].kind {
        BodyKind::Pulley { radius, .. } => radius,
        BodyKind::Link { .. } => f64::NAN,
    }
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
    /// The model the equations were traced from: the mechanism's, with its masses, centres
    /// of mass, inertias and gravity named as parameters (`parameters[k].value` is each
    /// one's file value; graph inputs `params[k]`).
    pub model: Model<f64>,
    /// The requested outputs, traced from [`Named::model`] with its geometry derived again
    /// from [`Named::lengths`] ([`Model::symbolic_geometry`]): what is printed.
    pub traced: Traced,
    transmission: Transmission,
    /// Per body: the name of its radius (pulleys).
    radius_names: Vec<Option<String>>,
    /// The lengths and radii that print by name, in the order of the legend: graph inputs
    /// `lengths[k]`.
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

/// Names numbers of the model, each name unique among all parameters and lengths: masses
/// and the like as new parameters (what [`Model::with_named_numbers`] then adds), lengths
/// and radii as inputs of their own.
struct Namer<'m> {
    model: &'m Model<f64>,
    /// Slots the file's own runtime parameters already set.
    taken: Vec<Slot>,
    /// The new parameters' names and values; parameter `k` is `added[k − file's count]`.
    added: Vec<(String, f64)>,
    /// Every number named, `(where, index into added)`.
    slots: Vec<(Slot, usize)>,
    /// The lengths and radii named.
    lengths: Vec<NamedLength>,
}

impl Namer<'_> {
    fn unique(&self, name: String) -> String {
        let mut name = name;
        let file = self.model.parameters().iter().map(|p| &p.name);
        while file
            .clone()
            .chain(self.added.iter().map(|(n, _)| n))
            .chain(self.lengths.iter().map(|l| &l.name))
            .any(|n| *n == name)
        {
            name.push('\'');
        }
        name
    }

    /// A parameter `name` with file value `value` setting `slot`; nothing when the value is
    /// zero or a runtime parameter already sets the slot.
    fn add(&mut self, name: String, value: f64, slot: Slot) {
        if value == 0.0 || self.taken.contains(&slot) {
            return;
        }
        let name = self.unique(name);
        self.slots.push((slot, self.added.len()));
        self.added.push((name, value));
    }

    /// A length or radius `name` of file value `value`, unless it is zero.
    fn length(&mut self, name: String, value: f64, quantity: Quantity) {
        if value != 0.0 {
            let name = self.unique(name);
            self.lengths.push(NamedLength {
                name,
                value,
                quantity,
            });
        }
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
        lengths: Vec::new(),
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
        namer.add(format!("m{tag}"), body.mass, Slot::Mass(b));
        for (c, axis) in axes.iter().enumerate() {
            namer.add(
                format!("c{tag}{axis}"),
                body.com.to_array()[c],
                Slot::Com(b, c),
            );
        }
        for (r, c) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)] {
            namer.add(
                format!("I{tag}{}{}", axes[r], axes[c]),
                body.inertia.rows[r][c],
                Slot::Inertia(b, r, c),
            );
        }
    }
    for (c, axis) in axes.iter().enumerate() {
        namer.add(
            format!("g{axis}"),
            model.gravity().to_array()[c],
            Slot::Gravity(c),
        );
    }
    // DH lengths and offsets (Eq. 1: `post` translates by (a, 0, d)), then pitch radii.
    for (j, link) in model.bodies()[..dof].iter().enumerate() {
        let (a, d) = (link.post.translation.x, link.post.translation.z);
        namer.length(format!("a{}", j + 1), a, Quantity::DhA(j));
        namer.length(format!("d{}", j + 1), d, Quantity::DhD(j));
    }
    let names = radius_names(model);
    for (b, name) in names.iter().enumerate() {
        if let Some(name) = name {
            namer.length(name.clone(), radius_of(model, b), Quantity::Radius(b));
        }
    }
    let m = model.with_named_numbers(&namer.added, &namer.slots)?;
    let lengths = namer.lengths;

    // Traced with the lengths and radii as symbols; a square E's exact inverse by name.
    let mut transmission = None;
    let traced = outputs::trace_with(&m, outputs, outputs::Regroup::No, |m, params| {
        let symbols = outputs::array("lengths", lengths.len());
        let mut given = Dimensions {
            a: vec![None; dof],
            d: vec![None; dof],
            radius: vec![None; m.bodies().len()],
        };
        let mut radii = Vec::new();
        for (l, &x) in lengths.iter().zip(&symbols) {
            match l.quantity {
                Quantity::DhA(j) => given.a[j] = Some(x),
                Quantity::DhD(j) => given.d[j] = Some(x),
                Quantity::Radius(b) => {
                    given.radius[b] = Some(x);
                    radii.push((x.0, b));
                }
            }
        }
        let s = m.symbolic_geometry(|k| params[k], &given)?;
        let (read, e) = Sym::inspect(|g| by_name(g, &s, m, &radii));
        let entries = exact_inverse_entries(&e, m);
        let radius = |b: usize| given.radius[b].expect("every pulley's radius is named");
        let entries: Vec<((usize, usize), Sym)> = (entries.iter())
            .map(|(at, term)| (*at, term_sym(term, &radius)))
            .collect();
        transmission = Some(read);
        Ok::<_, crate::Error>(s.with_exact_inverse(&entries)?)
    })?;
    let transmission = transmission.expect("traced");
    let radius_names = (0..m.bodies().len())
        .map(|b| {
            let is = |l: &&NamedLength| l.quantity == Quantity::Radius(b);
            lengths.iter().find(is).map(|l| l.name.clone())
        })
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
    LENGTHS.with(|l| *l.borrow_mut() = named.lengths.iter().map(|l| l.name.clone()).collect());
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
            let coupling = &named.transmission.couplings[b];
            out.push_str(&format!(
                "  {:<10} {}\n",
                model.bodies()[b].name,
                linear_text(coupling, &radius_name, &|j| format!("th{}", j + 1))
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
                .map(|(k, _)| named.transmission.structure[k][j].text(&radius_name))
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
