//! The collected closed form: outputs as polynomials in the sines and cosines of the joint
//! angles, in `q̇` and in `q̈`, with collected numeric coefficients — the shape of the
//! paper's Eqs. 28-30 — rebuilt for evaluation by a multivariate Horner scheme.
//!
//! 1. **Expand** each output of the traced graph into a sparse polynomial. Variables are
//!    inputs, `sin`/`cos` of a joint angle (the sine and cosine of `q + c` are expanded by
//!    the addition formulas), and any node that is not polynomial (a division by a
//!    variable, a square root, a `max`) taken as a whole. Coefficients are accumulated in
//!    double-double and rounded once, so that terms which cancel exactly vanish.
//! 2. **Reduce** with `cos² = 1 − sin²` (one canonical form per angle).
//! 3. **Factor** greedily: the variable of highest rank (accelerations, then velocities,
//!    then the rest) that occurs in most terms is pulled out, `P = v·P₁ + P₀`, recursively.
//!    Accelerations first makes the coefficients of `q̈` the entries of `M(q)`, built once
//!    and shared between outputs by hash-consing.
//!
//! The expansion is bounded ([`MAX_TERMS`]): a long chain whose polynomial would blow up
//! returns `None`, and the caller keeps the traced recursion.

use crate::expr::{Graph, Id, Node};
use std::collections::BTreeMap;
use tendyn_core::DoubleDouble;

/// Largest number of terms one intermediate polynomial may ever have.
pub const MAX_TERMS: usize = 4000;

/// A monomial: sorted `(variable, power)` pairs.
type Monomial = Vec<(Id, u32)>;
type Poly = BTreeMap<Monomial, DoubleDouble>;

/// How variables rank when factoring (higher first).
pub trait Rank {
    fn rank(&self, g: &Graph, v: Id) -> u8;
}

/// Ranks inputs named `qdd…` highest, then `qd…`, then everything else.
pub struct StateRank;

impl Rank for StateRank {
    fn rank(&self, g: &Graph, v: Id) -> u8 {
        match g.node(v) {
            Node::Input(i) => {
                let name = &g.input_names[i as usize];
                if name.starts_with("qdd") {
                    3
                } else if name.starts_with("qd") {
                    2
                } else {
                    1
                }
            }
            _ => 0,
        }
    }
}

struct Expander<'g, 'r> {
    g: &'g mut Graph,
    rank: &'r dyn Rank,
    memo: BTreeMap<Id, Option<Poly>>,
    /// Largest number of terms an intermediate polynomial may have before the expansion
    /// gives up (a form with more terms than the traced one has operations cannot win).
    max_terms: usize,
}

fn constant(c: f64) -> Poly {
    let mut p = Poly::new();
    if c != 0.0 {
        p.insert(Vec::new(), DoubleDouble::from(c));
    }
    p
}

fn variable(v: Id) -> Poly {
    let mut p = Poly::new();
    p.insert(vec![(v, 1)], DoubleDouble::from(1.0));
    p
}

fn add_into(acc: &mut Poly, p: &Poly, scale: DoubleDouble) {
    for (m, c) in p {
        let e = acc.entry(m.clone()).or_insert(DoubleDouble::from(0.0));
        *e += *c * scale;
    }
}

fn mul_monomials(a: &Monomial, b: &Monomial) -> Monomial {
    let mut out: Monomial = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        if j == b.len() || (i < a.len() && a[i].0 < b[j].0) {
            out.push(a[i]);
            i += 1;
        } else if i == a.len() || b[j].0 < a[i].0 {
            out.push(b[j]);
            j += 1;
        } else {
            out.push((a[i].0, a[i].1 + b[j].1));
            i += 1;
            j += 1;
        }
    }
    out
}

fn product(a: &Poly, b: &Poly, max_terms: usize) -> Option<Poly> {
    if a.len().saturating_mul(b.len()) > max_terms * 4 {
        return None;
    }
    let mut out = Poly::new();
    for (ma, ca) in a {
        for (mb, cb) in b {
            let e = out
                .entry(mul_monomials(ma, mb))
                .or_insert(DoubleDouble::from(0.0));
            *e += *ca * *cb;
        }
    }
    (out.len() <= max_terms).then_some(out)
}

impl Expander<'_, '_> {
    fn expand(&mut self, id: Id) -> Option<Poly> {
        if let Some(p) = self.memo.get(&id) {
            return p.clone();
        }
        let p = self.expand_node(id);
        self.memo.insert(id, p.clone());
        p
    }

    fn expand_node(&mut self, id: Id) -> Option<Poly> {
        let one = DoubleDouble::from(1.0);
        Some(match self.g.node(id) {
            Node::Const(bits) => constant(f64::from_bits(bits)),
            Node::Input(_) => variable(id),
            Node::Add(a, b) | Node::Sub(a, b) => {
                let sign = if matches!(self.g.node(id), Node::Sub(..)) {
                    -one
                } else {
                    one
                };
                let mut p = self.expand(a)?;
                add_into(&mut p, &self.expand(b)?, sign);
                if p.len() > self.max_terms {
                    return None;
                }
                p
            }
            Node::Neg(a) => {
                let mut p = Poly::new();
                add_into(&mut p, &self.expand(a)?, -one);
                p
            }
            Node::Mul(a, b) => product(&self.expand(a)?, &self.expand(b)?, self.max_terms)?,
            Node::Div(a, b) => {
                let pb = self.expand(b)?;
                match (pb.len(), pb.get(&Vec::new())) {
                    (1, Some(c)) => {
                        let mut p = Poly::new();
                        add_into(&mut p, &self.expand(a)?, one / *c);
                        p
                    }
                    // Not a polynomial: a new variable, its operands collected themselves.
                    _ => {
                        let (a, b) = (self.collected(a)?, self.rebuild(pb)?);
                        variable(self.g.div(a, b))
                    }
                }
            }
            Node::Sin(a) | Node::Cos(a) => {
                let is_sin = matches!(self.g.node(id), Node::Sin(_));
                match self.g.node(a) {
                    // sin/cos(u ± v) by the addition formulas, when v is a number.
                    Node::Add(u, v) | Node::Sub(u, v)
                        if self.g.constant_value(v).is_some()
                            || self.g.constant_value(u).is_some() =>
                    {
                        let (x, c) = match self.g.constant_value(v) {
                            Some(c) => (u, c),
                            None => (v, self.g.constant_value(u).expect("one is constant")),
                        };
                        let c = if matches!(self.g.node(a), Node::Sub(..))
                            && self.g.constant_value(v).is_some()
                        {
                            -c
                        } else {
                            c
                        };
                        let (sx, cx) = (self.g.sin(x), self.g.cos(x));
                        let (sc, cc) = (DoubleDouble::from(c).sin(), DoubleDouble::from(c).cos());
                        let (ps, pc) = (self.expand(sx)?, self.expand(cx)?);
                        let mut p = Poly::new();
                        if matches!(self.g.node(a), Node::Sub(..))
                            && self.g.constant_value(u).is_some()
                        {
                            // sin(c − x) = sin c cos x − cos c sin x; cos(c − x) = cos c cos x + sin c sin x
                            if is_sin {
                                add_into(&mut p, &pc, sc);
                                add_into(&mut p, &ps, -cc);
                            } else {
                                add_into(&mut p, &pc, cc);
                                add_into(&mut p, &ps, sc);
                            }
                        } else if is_sin {
                            add_into(&mut p, &ps, cc);
                            add_into(&mut p, &pc, sc);
                        } else {
                            add_into(&mut p, &pc, cc);
                            add_into(&mut p, &ps, -sc);
                        }
                        p
                    }
                    _ => variable(id),
                }
            }
            Node::Sqrt(a) => {
                let a = self.collected(a)?;
                variable(self.g.sqrt(a))
            }
            Node::Max(a, b) => {
                let (a, b) = (self.collected(a)?, self.collected(b)?);
                variable(self.g.max(a, b))
            }
        })
    }

    /// The closed form of `id` as a node, for the operand of a non-polynomial node.
    fn collected(&mut self, id: Id) -> Option<Id> {
        let p = self.expand(id)?;
        self.rebuild(p)
    }

    fn rebuild(&mut self, p: Poly) -> Option<Id> {
        let p = clean(reduce_pythagoras(self.g, p))?;
        Some(horner(self.g, self.rank, &p))
    }
}

use tendyn_core::Real;

/// Replaces `cos^k` (k ≥ 2) by `cos^(k−2) (1 − sin²)` for every angle whose sine and cosine
/// both occur, until no such power is left.
fn reduce_pythagoras(g: &Graph, p: Poly) -> Poly {
    let mut pending: Vec<(Monomial, DoubleDouble)> = p.into_iter().collect();
    let mut out = Poly::new();
    while let Some((m, c)) = pending.pop() {
        let hit = m
            .iter()
            .position(|&(v, k)| k >= 2 && matches!(g.node(v), Node::Cos(a) if g_has_sin(g, a)));
        match hit {
            None => {
                let e = out.entry(m).or_insert(DoubleDouble::from(0.0));
                *e += c;
            }
            Some(i) => {
                let (v, k) = m[i];
                let Node::Cos(a) = g.node(v) else {
                    unreachable!()
                };
                let s = sin_id(g, a);
                let mut lowered = m.clone();
                if k == 2 {
                    lowered.remove(i);
                } else {
                    lowered[i].1 -= 2;
                }
                pending.push((lowered.clone(), c));
                pending.push((mul_monomials(&lowered, &vec![(s, 2)]), -c));
            }
        }
    }
    out
}

fn g_has_sin(g: &Graph, a: Id) -> bool {
    g.lookup(Node::Sin(a)).is_some()
}

fn sin_id(g: &Graph, a: Id) -> Id {
    g.lookup(Node::Sin(a)).expect("checked")
}

/// Rounds the coefficients to f64, drops those that are rounding noise next to the largest
/// one of the polynomial, and snaps those within 4 ulp of ±1 to ±1 (so that no
/// multiplication by a one survives). `None` if a coefficient is not finite: a singular
/// step (a division by a zero polynomial) must stay traced and give inf or NaN, not vanish.
fn clean(p: Poly) -> Option<BTreeMap<Monomial, f64>> {
    let rounded: Vec<(Monomial, f64)> = p.into_iter().map(|(m, c)| (m, c.to_f64())).collect();
    if rounded.iter().any(|(_, c)| !c.is_finite()) {
        return None;
    }
    let max = rounded.iter().map(|(_, c)| c.abs()).fold(0.0, f64::max);
    Some(
        rounded
            .into_iter()
            .filter(|(_, c)| c.abs() > 1e-15 * max)
            .map(|(m, c)| {
                let snapped = if (c.abs() - 1.0).abs() <= 4.0 * f64::EPSILON {
                    c.signum()
                } else {
                    c
                };
                (m, snapped)
            })
            .collect(),
    )
}

/// Builds a polynomial back into the graph by greedy multivariate Horner factoring.
fn horner(g: &mut Graph, rank: &dyn Rank, p: &BTreeMap<Monomial, f64>) -> Id {
    if p.is_empty() {
        return g.constant(0.0);
    }
    if p.len() == 1 {
        if let Some(c) = p.get(&Vec::new()) {
            return g.constant(*c);
        }
    }
    // The variable to pull out: highest rank, then most terms, then lowest id.
    let mut counts: BTreeMap<Id, usize> = BTreeMap::new();
    for m in p.keys() {
        for &(v, _) in m {
            *counts.entry(v).or_default() += 1;
        }
    }
    let Some((&v, _)) = counts
        .iter()
        .max_by_key(|(&v, &n)| (rank.rank(g, v), n, std::cmp::Reverse(v)))
    else {
        return g.constant(*p.get(&Vec::new()).expect("a constant polynomial"));
    };
    let mut with = BTreeMap::new();
    let mut without = BTreeMap::new();
    for (m, c) in p {
        match m.iter().position(|&(x, _)| x == v) {
            Some(i) => {
                let mut m2 = m.clone();
                if m2[i].1 == 1 {
                    m2.remove(i);
                } else {
                    m2[i].1 -= 1;
                }
                with.insert(m2, *c);
            }
            None => {
                without.insert(m.clone(), *c);
            }
        }
    }
    let inner = horner(g, rank, &with);
    let term = g.mul(v, inner);
    if without.is_empty() {
        term
    } else {
        let rest = horner(g, rank, &without);
        g.add(term, rest)
    }
}

/// Collects the closed forms of several functions of one graph, sharing the expansions
/// of the subexpressions they have in common (the outputs of inverse dynamics share most).
pub struct Collector {
    memo: BTreeMap<Id, Option<Poly>>,
    /// Largest intermediate polynomial any function may use.
    max_terms: usize,
}

impl Collector {
    /// `max_terms`: the largest budget any function will ask for (at most [`MAX_TERMS`]).
    pub fn new(max_terms: usize) -> Self {
        Collector {
            memo: BTreeMap::new(),
            max_terms: max_terms.min(MAX_TERMS),
        }
    }

    /// The collected closed form of `roots`, built into `g`; `None` if an intermediate
    /// polynomial exceeds the collector's limit or the results together have more than
    /// `budget` terms (every term costs at least a multiply-add, so such a form cannot beat
    /// a trace of about `budget` operations).
    pub fn collect(
        &mut self,
        g: &mut Graph,
        roots: &[Id],
        rank: &dyn Rank,
        budget: usize,
    ) -> Option<Vec<Id>> {
        let mut e = Expander {
            g,
            rank,
            memo: std::mem::take(&mut self.memo),
            max_terms: self.max_terms,
        };
        let mut total = 0;
        let mut polys = Some(Vec::with_capacity(roots.len()));
        for &r in roots {
            match e.expand(r) {
                Some(p) if total + p.len() <= budget => {
                    total += p.len();
                    if let Some(v) = polys.as_mut() {
                        v.push(p);
                    }
                }
                _ => {
                    polys = None;
                    break;
                }
            }
        }
        let result = polys.and_then(|ps| ps.into_iter().map(|p| e.rebuild(p)).collect());
        self.memo = e.memo;
        result
    }
}

/// The collected closed form of `roots`, built into `g` (see [`Collector::collect`]).
pub fn collect(g: &mut Graph, roots: &[Id], rank: &dyn Rank, max_terms: usize) -> Option<Vec<Id>> {
    Collector::new(max_terms).collect(g, roots, rank, max_terms)
}
