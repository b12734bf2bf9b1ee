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

use crate::expr::{Graph, Id, Node, NodeMap};
use std::cmp::Ordering;
use std::collections::hash_map::Entry;
use tendyn_core::DoubleDouble;

/// Largest number of terms one intermediate polynomial may ever have.
pub const MAX_TERMS: usize = 4000;

/// A monomial: sorted `(variable, power)` pairs.
type Monomial = Vec<(Id, u32)>;

/// A monomial by its number in [`Monomials`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Mono(u32);

/// The monomial 1 (no variable).
const ONE: Mono = Mono(0);

/// Every monomial met in a collection, stored once, and the products already formed: a
/// term is then a number and a coefficient, and the product of two terms a table lookup
/// (a monomial of its own per term cost an allocation per term).
struct Monomials {
    list: Vec<Monomial>,
    /// The [`sort_key`] of each monomial: most comparisons need not read the monomials.
    keys: Vec<Option<u128>>,
    numbers: NodeMap<Monomial, Mono>,
    /// The product of two monomials, by their numbers (the smaller in the high half).
    products: NodeMap<u64, Mono>,
}

impl Monomials {
    fn new() -> Self {
        let mut m = Monomials {
            list: Vec::new(),
            keys: Vec::new(),
            numbers: NodeMap::default(),
            products: NodeMap::default(),
        };
        assert_eq!(m.intern(Vec::new()), ONE);
        m
    }

    fn intern(&mut self, m: Monomial) -> Mono {
        match self.numbers.entry(m) {
            Entry::Occupied(e) => *e.get(),
            Entry::Vacant(e) => {
                let n = Mono(self.list.len() as u32);
                self.keys.push(sort_key(e.key()));
                self.list.push(e.key().clone());
                e.insert(n);
                n
            }
        }
    }

    fn get(&self, m: Mono) -> &Monomial {
        &self.list[m.0 as usize]
    }

    /// The order polynomials are sorted in: that of the sorted pairs.
    fn cmp(&self, a: Mono, b: Mono) -> Ordering {
        if a == b {
            return Ordering::Equal;
        }
        match (self.keys[a.0 as usize], self.keys[b.0 as usize]) {
            (Some(x), Some(y)) if x != y => x.cmp(&y),
            _ => self.get(a).cmp(self.get(b)),
        }
    }

    fn mul(&mut self, a: Mono, b: Mono) -> Mono {
        if a == ONE {
            return b;
        }
        if b == ONE {
            return a;
        }
        let key = (u64::from(a.0.min(b.0)) << 32) | u64::from(a.0.max(b.0));
        if let Some(&p) = self.products.get(&key) {
            return p;
        }
        let p = self.intern(mul_monomials(self.get(a), self.get(b)));
        self.products.insert(key, p);
        p
    }
}

/// The first four pairs of `m` packed into a number that sorts as the pairs do: each pair
/// in 32 bits as `id · 2⁸ + power`, the first pair highest. A power is at least 1, so a
/// missing pair, 0, sorts first, as a shorter monomial does. `None` if an id or a power is
/// too large to pack.
fn sort_key(m: &Monomial) -> Option<u128> {
    let mut key = 0u128;
    for (k, &(v, p)) in m.iter().take(4).enumerate() {
        if v.0 >= 1 << 24 || !(1..1 << 8).contains(&p) {
            return None;
        }
        key |= u128::from(v.0 << 8 | p) << (96 - 32 * k);
    }
    Some(key)
}

/// A polynomial: its terms sorted by monomial (see [`Monomials::cmp`]), each monomial
/// once. A coefficient that cancelled to zero keeps its term until [`clean`], as it did
/// when this was a map: term counts bound the expansion, so they must not depend on the
/// representation.
///
/// Every coefficient is accumulated from zero in the order the terms are generated
/// (the sorted order of the operands), so the double-double sums, and hence the emitted
/// constants, are independent of how the terms are stored.
type Poly = Vec<Term>;
type Term = (Mono, DoubleDouble);

/// A polynomial kept in a collection's store of terms: `terms[start..start + len]`. Every
/// expansion is kept (a subexpression is expanded once and read by every parent), so one
/// growing store replaces a vector per polynomial.
#[derive(Clone, Copy, Debug)]
struct Span {
    start: u32,
    len: u32,
}

impl Span {
    fn range(self) -> std::ops::Range<usize> {
        self.start as usize..(self.start + self.len) as usize
    }
}

/// How variables rank when factoring (higher first).
pub trait Rank {
    /// The rank of variable `v` of `g`: among the variables of a polynomial, those of
    /// highest rank are pulled out first.
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
    memo: &'g mut NodeMap<Id, Option<Span>>,
    terms: &'g mut Vec<Term>,
    monos: &'g mut Monomials,
    /// Where each monomial of the product being formed is, plus one, by monomial (0: not
    /// yet); reused between products, all 0 between them.
    slots: Vec<u32>,
    /// Buffers for expansions under way (one per level of the recursion), reused.
    buffers: Vec<Poly>,
    /// Largest number of terms an intermediate polynomial may have before the expansion
    /// gives up (a form with more terms than the traced one has operations cannot win).
    max_terms: usize,
}

fn zero() -> DoubleDouble {
    DoubleDouble::from(0.0)
}

/// `0 + x`, as a coefficient's first contribution is accumulated (see [`Poly`]).
fn first(x: DoubleDouble) -> DoubleDouble {
    let mut e = zero();
    e += x;
    e
}

/// `scale · p`, into `out`.
fn scaled(p: &[Term], scale: DoubleDouble, out: &mut Poly) {
    out.extend(p.iter().map(|&(m, c)| (m, first(c * scale))));
}

/// `a + scale · b`, by merging the sorted terms, into `out`.
fn add_scaled(monos: &Monomials, a: &[Term], b: &[Term], scale: DoubleDouble, out: &mut Poly) {
    let (mut i, mut j) = (0, 0);
    loop {
        let order = match (a.get(i), b.get(j)) {
            (None, None) => break,
            (Some(_), None) => Ordering::Less,
            (None, Some(_)) => Ordering::Greater,
            (Some(&(ma, _)), Some(&(mb, _))) => monos.cmp(ma, mb),
        };
        match order {
            Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            Ordering::Greater => {
                let (mb, cb) = b[j];
                out.push((mb, first(cb * scale)));
                j += 1;
            }
            Ordering::Equal => {
                let ((m, mut e), (_, cb)) = (a[i], b[j]);
                e += cb * scale;
                out.push((m, e));
                i += 1;
                j += 1;
            }
        }
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

/// `a · b`, into `out` (empty); `slots` is scratch space (see [`Expander::slots`]). `None`
/// if it has too many terms.
fn product(
    monos: &mut Monomials,
    slots: &mut Vec<u32>,
    a: &[Term],
    b: &[Term],
    max_terms: usize,
    out: &mut Poly,
) -> Option<()> {
    if a.len().saturating_mul(b.len()) > max_terms * 4 {
        return None;
    }
    for &(ma, ca) in a {
        for &(mb, cb) in b {
            let (m, c) = (monos.mul(ma, mb), ca * cb);
            if slots.len() <= m.0 as usize {
                slots.resize(monos.list.len(), 0);
            }
            match slots[m.0 as usize] {
                0 => {
                    out.push((m, first(c)));
                    slots[m.0 as usize] = out.len() as u32;
                }
                slot => out[slot as usize - 1].1 += c,
            }
        }
    }
    for &(m, _) in out.iter() {
        slots[m.0 as usize] = 0;
    }
    if out.len() > max_terms {
        return None;
    }
    out.sort_unstable_by(|x, y| monos.cmp(x.0, y.0));
    Some(())
}

impl Expander<'_, '_> {
    fn expand(&mut self, id: Id) -> Option<Span> {
        if let Some(&p) = self.memo.get(&id) {
            return p;
        }
        let mut out = self.buffers.pop().unwrap_or_default();
        out.clear();
        let p = self.expand_node(id, &mut out).map(|()| {
            let start = self.terms.len() as u32;
            self.terms.extend_from_slice(&out);
            Span {
                start,
                len: out.len() as u32,
            }
        });
        self.buffers.push(out);
        self.memo.insert(id, p);
        p
    }

    fn poly(&self, p: Span) -> &[Term] {
        &self.terms[p.range()]
    }

    /// The expansion of node `id`, into `out` (empty); `None` if it is too large.
    fn expand_node(&mut self, id: Id, out: &mut Poly) -> Option<()> {
        let one = DoubleDouble::from(1.0);
        match self.g.node(id) {
            Node::Const(bits) => {
                let c = f64::from_bits(bits);
                if c != 0.0 {
                    out.push((ONE, DoubleDouble::from(c)));
                }
            }
            Node::Input(_) => self.variable(id, out),
            Node::Add(a, b) | Node::Sub(a, b) => {
                let sign = if matches!(self.g.node(id), Node::Sub(..)) {
                    -one
                } else {
                    one
                };
                let (pa, pb) = (self.expand(a)?, self.expand(b)?);
                let terms = &self.terms;
                add_scaled(
                    self.monos,
                    &terms[pa.range()],
                    &terms[pb.range()],
                    sign,
                    out,
                );
                if out.len() > self.max_terms {
                    return None;
                }
            }
            Node::Neg(a) => {
                let pa = self.expand(a)?;
                scaled(self.poly(pa), -one, out);
            }
            Node::Mul(a, b) => {
                let (pa, pb) = (self.expand(a)?, self.expand(b)?);
                let terms = &self.terms;
                let (a, b) = (&terms[pa.range()], &terms[pb.range()]);
                product(self.monos, &mut self.slots, a, b, self.max_terms, out)?;
            }
            Node::Div(a, b) => {
                let pb = self.expand(b)?;
                match *self.poly(pb) {
                    [(ONE, c)] => {
                        let pa = self.expand(a)?;
                        scaled(self.poly(pa), one / c, out);
                    }
                    // Not a polynomial: a new variable, its operands collected themselves.
                    _ => {
                        let (a, b) = (self.collected(a)?, self.rebuild(pb)?);
                        let v = self.g.div(a, b);
                        self.variable(v, out);
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
                        let (ps, pc) = (self.poly(ps), self.poly(pc));
                        // `first · a + second · b`
                        let monos = &*self.monos;
                        let mut sum = |a: &[Term], first: DoubleDouble, b: &[Term], second| {
                            let mut scaled_a = Vec::with_capacity(a.len());
                            scaled(a, first, &mut scaled_a);
                            add_scaled(monos, &scaled_a, b, second, out);
                        };
                        if matches!(self.g.node(a), Node::Sub(..))
                            && self.g.constant_value(u).is_some()
                        {
                            // sin(c − x) = sin c cos x − cos c sin x; cos(c − x) = cos c cos x + sin c sin x
                            if is_sin {
                                sum(pc, sc, ps, -cc)
                            } else {
                                sum(pc, cc, ps, sc)
                            }
                        } else if is_sin {
                            sum(ps, cc, pc, sc)
                        } else {
                            sum(pc, cc, ps, -sc)
                        }
                    }
                    _ => self.variable(id, out),
                }
            }
            Node::Sqrt(a) => {
                let a = self.collected(a)?;
                let v = self.g.sqrt(a);
                self.variable(v, out);
            }
            Node::Tanh(a) => {
                let a = self.collected(a)?;
                let v = self.g.tanh(a);
                self.variable(v, out);
            }
            Node::Exp(a) => {
                let a = self.collected(a)?;
                let v = self.g.exp(a);
                self.variable(v, out);
            }
            Node::Max(a, b) => {
                let (a, b) = (self.collected(a)?, self.collected(b)?);
                let v = self.g.max(a, b);
                self.variable(v, out);
            }
            Node::SignOutside(a, b, c) => {
                let (a, b, c) = (self.collected(a)?, self.collected(b)?, self.collected(c)?);
                let v = self.g.sign_outside(a, b, c);
                self.variable(v, out);
            }
            Node::SelectOutside(ids) => {
                let mut c = [ids[0]; 5];
                for (to, from) in c.iter_mut().zip(ids) {
                    *to = self.collected(from)?;
                }
                let v = self.g.select_outside(c);
                self.variable(v, out);
            }
        }
        Some(())
    }

    fn variable(&mut self, v: Id, out: &mut Poly) {
        out.push((self.monos.intern(vec![(v, 1)]), DoubleDouble::from(1.0)));
    }

    /// The closed form of `id` as a node, for the operand of a non-polynomial node.
    fn collected(&mut self, id: Id) -> Option<Id> {
        let p = self.expand(id)?;
        self.rebuild(p)
    }

    fn rebuild(&mut self, p: Span) -> Option<Id> {
        let mut p = clean(reduce_pythagoras(
            self.g,
            self.monos,
            &self.terms[p.range()],
            self.max_terms,
        )?)?;
        Some(horner(self.g, self.rank, &mut p))
    }
}

use tendyn_core::Real;

/// Replaces `cos^k` (k ≥ 2) by `cos^(k−2) (1 − sin²)` for every angle whose sine and cosine
/// both occur, until no such power is left. The terms come out in no particular order
/// (what follows does not depend on it). `None` once more than `max_terms` terms result
/// or are pending: a monomial with high powers of several cosines multiplies into many
/// terms, and such a form cannot beat the trace.
fn reduce_pythagoras(
    g: &Graph,
    monos: &Monomials,
    p: &[Term],
    max_terms: usize,
) -> Option<Vec<(Monomial, DoubleDouble)>> {
    let mut pending: Vec<(Monomial, DoubleDouble)> =
        p.iter().map(|&(m, c)| (monos.get(m).clone(), c)).collect();
    let mut out: NodeMap<Monomial, DoubleDouble> = NodeMap::default();
    while let Some((m, c)) = pending.pop() {
        if out.len() + pending.len() > max_terms {
            return None;
        }
        let hit = m
            .iter()
            .position(|&(v, k)| k >= 2 && matches!(g.node(v), Node::Cos(a) if g_has_sin(g, a)));
        match hit {
            None => {
                *out.entry(m).or_insert(zero()) += c;
            }
            Some(i) => {
                let (v, k) = m[i];
                let Node::Cos(a) = g.node(v) else {
                    unreachable!()
                };
                let s = sin_id(g, a);
                let mut lowered = m;
                if k == 2 {
                    lowered.remove(i);
                } else {
                    lowered[i].1 -= 2;
                }
                let with_sine = mul_monomials(&lowered, &vec![(s, 2)]);
                pending.push((lowered, c));
                pending.push((with_sine, -c));
            }
        }
    }
    Some(out.into_iter().collect())
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
fn clean(p: Vec<(Monomial, DoubleDouble)>) -> Option<Vec<(Monomial, f64)>> {
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

/// Builds a polynomial (terms in any order, each monomial once) back into the graph by
/// greedy multivariate Horner factoring. The terms are reordered and their monomials
/// divided in place.
fn horner(g: &mut Graph, rank: &dyn Rank, p: &mut [(Monomial, f64)]) -> Id {
    match p {
        [] => return g.constant(0.0),
        [(m, c)] if m.is_empty() => return g.constant(*c),
        _ => {}
    }
    // The variable to pull out: highest rank, then most terms, then lowest id.
    let mut counts: Vec<(Id, usize)> = Vec::new();
    for (m, _) in p.iter() {
        for &(v, _) in m {
            match counts.iter_mut().find(|(x, _)| *x == v) {
                Some((_, n)) => *n += 1,
                None => counts.push((v, 1)),
            }
        }
    }
    let Some(&(v, _)) = counts
        .iter()
        .max_by_key(|&&(v, n)| (rank.rank(g, v), n, std::cmp::Reverse(v)))
    else {
        unreachable!("a polynomial of several terms has a variable")
    };
    // The terms with `v` first, then divided by it.
    let mut k = 0;
    for i in 0..p.len() {
        if p[i].0.iter().any(|&(x, _)| x == v) {
            p.swap(i, k);
            k += 1;
        }
    }
    let (with, without) = p.split_at_mut(k);
    for (m, _) in with.iter_mut() {
        let i = m.iter().position(|&(x, _)| x == v).expect("partitioned");
        if m[i].1 == 1 {
            m.remove(i);
        } else {
            m[i].1 -= 1;
        }
    }
    let inner = horner(g, rank, with);
    let term = g.mul(v, inner);
    if without.is_empty() {
        term
    } else {
        let rest = horner(g, rank, without);
        g.add(term, rest)
    }
}

/// Collects the closed forms of several functions of one graph, sharing the expansions
/// of the subexpressions they have in common (the outputs of inverse dynamics share most).
pub struct Collector {
    memo: NodeMap<Id, Option<Span>>,
    terms: Vec<Term>,
    monos: Monomials,
    /// Largest intermediate polynomial any function may use.
    max_terms: usize,
}

impl Collector {
    /// `max_terms`: the largest budget any function will ask for (at most [`MAX_TERMS`]).
    pub fn new(max_terms: usize) -> Self {
        Collector {
            memo: NodeMap::default(),
            terms: Vec::new(),
            monos: Monomials::new(),
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
            memo: &mut self.memo,
            terms: &mut self.terms,
            monos: &mut self.monos,
            slots: Vec::new(),
            buffers: Vec::new(),
            max_terms: self.max_terms,
        };
        let mut total = 0;
        let mut polys = Some(Vec::with_capacity(roots.len()));
        for &r in roots {
            match e.expand(r) {
                Some(p) if total + p.len as usize <= budget => {
                    total += p.len as usize;
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
        polys.and_then(|ps| ps.into_iter().map(|p| e.rebuild(p)).collect())
    }
}

/// The collected closed form of `roots`, built into `g` (see [`Collector::collect`]).
pub fn collect(g: &mut Graph, roots: &[Id], rank: &dyn Rank, max_terms: usize) -> Option<Vec<Id>> {
    Collector::new(max_terms).collect(g, roots, rank, max_terms)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Sym;

    /// `cos(x)¹² cos(y)¹²` is one monomial, but `1 − sin²` for each square makes it 49
    /// terms: the expansion stops at its limit instead of building them.
    #[test]
    fn the_pythagorean_reduction_stops_at_the_term_limit() {
        let (mut g, root) = Graph::default().scope(|| {
            let (x, y) = (Sym::input("x"), Sym::input("y"));
            let _ = (x.sin(), y.sin());
            let (cx, cy) = (x.cos(), y.cos());
            let mut r = cx * cy;
            for _ in 0..11 {
                r = r * cx * cy;
            }
            r.0
        });
        assert!(collect(&mut g, &[root], &StateRank, 20).is_none());
        let reduced = collect(&mut g, &[root], &StateRank, 64).expect("within the limit");
        // The reduced form is the product: its 49 terms of alternating sign sum to it up to
        // their own size (at most 2¹² in all, times the rounding of each).
        let at = |ids: &[Id]| g.eval(ids, &[0.3, -1.1])[0];
        let want = (0.3f64.cos() * (-1.1f64).cos()).powi(12);
        assert!(
            (at(&reduced) - want).abs() <= 4096.0 * 1e-15,
            "{} {want}",
            at(&reduced)
        );
    }
}
