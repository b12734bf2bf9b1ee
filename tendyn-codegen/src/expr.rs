//! The hash-consed expression graph and the symbolic scalar [`Sym`].
//!
//! A [`Graph`] is a flat list of [`Node`]s in which children come before parents; a node
//! is stored once (a memo map is consulted before every insertion), so equal
//! subexpressions are shared by construction. The smart constructors fold what is known
//! at generation time as the graph is built — constant arithmetic, `x + 0`, `x · 1`,
//! `x · 0`, `x − x`, `−(−x)`, signs pulled out of products — so the zeros and ones of DH
//! parameters and planar geometry never become nodes.
//!
//! [`Sym`] is a handle into the graph that is current on this thread (see [`Graph::scope`]);
//! it implements [`tendyn_core::Real`], so the solver's generic recursion builds the
//! graph when it runs on `Sym`.

use std::cell::RefCell;
use tendyn_core::{Real, Symbolic};

/// A map keyed by nodes or ids of one graph. Interning hashes every node the recursion
/// builds, so the hash is most of the cost of tracing: rustc's Fx hash (one multiplication
/// per word) rather than std's SipHash, whose resistance to crafted keys nodes numbered by
/// this graph do not need.
pub type NodeMap<K, V> = rustc_hash::FxHashMap<K, V>;

/// Index of a node in its graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

/// One operation of a [`Graph`]; its operands are earlier nodes of the same graph.
///
/// The operands of `Add`, `Mul` and `Max` are stored in id order, so `a + b` and `b + a`
/// are one node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A number, by its bits (`-0.0` is stored as `0.0`).
    Const(u64),
    /// Input `index` of the generated function (see [`Graph::input_names`]).
    Input(u32),
    /// `a + b`.
    Add(Id, Id),
    /// `a − b`.
    Sub(Id, Id),
    /// `a · b`.
    Mul(Id, Id),
    /// `a / b`, `b` not a constant (a division by a number is a multiplication by its
    /// reciprocal).
    Div(Id, Id),
    /// `−a`.
    Neg(Id),
    /// `sin a`.
    Sin(Id),
    /// `cos a`.
    Cos(Id),
    /// `√a`.
    Sqrt(Id),
    /// `tanh a` (the smoothed friction law).
    Tanh(Id),
    /// `e^a` (the capstan law of a guide).
    Exp(Id),
    /// The larger of `a` and `b` ([`Real::max`]; the tension distribution along one null
    /// direction).
    Max(Id, Id),
    /// `a.sign_outside_or(band, otherwise)`: ±1 beyond the band, `otherwise` within it
    /// ([`Real::sign_outside_or`]; `a.sign_outside(band)` where `otherwise` is 0).
    SignOutside(Id, Id, Id),
    /// `a.select_outside(band, above, below, otherwise)` ([`Real::select_outside`]).
    SelectOutside([Id; 5]),
}

impl Node {
    /// The operands of the node, without allocating.
    pub fn operands(self) -> impl Iterator<Item = Id> {
        let (ids, n) = match self {
            Node::Const(_) | Node::Input(_) => ([Id(0); 5], 0),
            Node::Neg(a)
            | Node::Sin(a)
            | Node::Cos(a)
            | Node::Sqrt(a)
            | Node::Tanh(a)
            | Node::Exp(a) => ([a; 5], 1),
            Node::Add(a, b)
            | Node::Sub(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Max(a, b) => ([a, b, b, b, b], 2),
            Node::SignOutside(a, b, c) => ([a, b, c, c, c], 3),
            Node::SelectOutside(ids) => (ids, 5),
        };
        ids.into_iter().take(n)
    }

    /// The operands of the node, collected.
    pub fn children(&self) -> Vec<Id> {
        self.operands().collect()
    }
}

/// A hash-consed expression graph: every node once, children before parents.
#[derive(Default, Debug, Clone)]
pub struct Graph {
    /// The nodes; a node's [`Id`] is its index here.
    pub nodes: Vec<Node>,
    memo: NodeMap<Node, Id>,
    /// The constants, by their bits: kept apart from `memo` because tracing makes most of
    /// its nodes from numbers (the model's, and products of them folded as they are built),
    /// and a bare number hashes and compares faster than a node.
    constants: NodeMap<u64, Id>,
    /// Name of each input, by index (`q[0]`, `qd[1]`, ...).
    pub input_names: Vec<String>,
}

thread_local! {
    static CURRENT: RefCell<Option<Graph>> = const { RefCell::new(None) };
}

fn with<R>(f: impl FnOnce(&mut Graph) -> R) -> R {
    CURRENT.with(|c| {
        f(c.borrow_mut()
            .as_mut()
            .expect("a symbolic scalar is used outside Graph::scope"))
    })
}

impl Graph {
    /// Runs `build` with `self` as the graph that [`Sym`] values on this thread refer to,
    /// and gives the graph back afterwards.
    pub fn scope<R>(self, build: impl FnOnce() -> R) -> (Graph, R) {
        /// Clears the thread's graph when the scope ends, by return or by panic: a panic
        /// inside `build` (caught by a caller) must not leave the next scope on this
        /// thread refused as nested.
        struct Clear;
        impl Drop for Clear {
            fn drop(&mut self) {
                CURRENT.with(|c| c.borrow_mut().take());
            }
        }
        CURRENT.with(|c| {
            let previous = c.borrow_mut().replace(self);
            assert!(previous.is_none(), "Graph::scope does not nest");
        });
        let clear = Clear;
        let r = build();
        let g = CURRENT
            .with(|c| c.borrow_mut().take())
            .expect("graph present");
        drop(clear);
        (g, r)
    }

    /// The node `id`.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.0 as usize]
    }

    /// The number node `id` holds, if it is a constant.
    pub fn constant_value(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// The id of `n` if the graph holds it.
    pub fn lookup(&self, n: Node) -> Option<Id> {
        match n {
            Node::Const(bits) => self.constants.get(&bits).copied(),
            _ => self.memo.get(&n).copied(),
        }
    }

    fn intern(&mut self, n: Node) -> Id {
        let next = Id(self.nodes.len() as u32);
        let nodes = &mut self.nodes;
        *self.memo.entry(n).or_insert_with(|| {
            nodes.push(n);
            next
        })
    }

    /// The node of the number `x` (`-0.0` and `0.0` are one node).
    pub fn constant(&mut self, x: f64) -> Id {
        let bits = if x == 0.0 { 0.0f64 } else { x }.to_bits();
        let next = Id(self.nodes.len() as u32);
        let nodes = &mut self.nodes;
        *self.constants.entry(bits).or_insert_with(|| {
            nodes.push(Node::Const(bits));
            next
        })
    }

    /// A new input named `name` (`q[0]`, ...); every call makes a distinct input.
    pub fn input(&mut self, name: impl Into<String>) -> Id {
        let index = self.input_names.len() as u32;
        self.input_names.push(name.into());
        self.intern(Node::Input(index))
    }

    /// `a + b`, folded: constants summed, `x + 0 = x`, `a + (−c) = a − c`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x + y),
            (Some(0.0), _) => return b,
            (_, Some(0.0)) => return a,
            _ => {}
        }
        match (self.node(a), self.node(b)) {
            (_, Node::Neg(c)) => self.sub(a, c),
            (Node::Neg(c), _) => self.sub(b, c),
            _ => self.intern(Node::Add(a.min(b), a.max(b))),
        }
    }

    /// `a − b`, folded: `x − x = 0`, constants, `x − 0`, `0 − x = −x`, signs moved out.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.constant(0.0);
        }
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x - y),
            (_, Some(0.0)) => return a,
            (Some(0.0), _) => return self.neg(b),
            _ => {}
        }
        match self.node(b) {
            Node::Neg(c) => self.add(a, c),
            _ => match self.node(a) {
                // (−c) − b = −(c + b)
                Node::Neg(c) => {
                    let s = self.add(c, b);
                    self.neg(s)
                }
                _ => self.intern(Node::Sub(a, b)),
            },
        }
    }

    /// `a · b`, folded: constants multiplied, `x · 0 = 0`, `x · (±1) = ±x` (also for a
    /// factor within 4 ulp of ±1), and signs pulled out of the product (`(−a) · b =
    /// −(a · b)`), so that `k x` and `−k x` share one product.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        // A factor within 4 ulp of ±1 is a one that rounding bent (the model's constants
        // are products of f64 numbers, e.g. (s/r)·r): it multiplies by exactly ±1.
        let near_one = |x: Option<f64>| x.filter(|c| (c.abs() - 1.0).abs() <= 4.0 * f64::EPSILON);
        if let Some(c) =
            near_one(self.constant_value(a)).filter(|_| self.constant_value(b).is_none())
        {
            return if c > 0.0 { b } else { self.neg(b) };
        }
        if let Some(c) =
            near_one(self.constant_value(b)).filter(|_| self.constant_value(a).is_none())
        {
            return if c > 0.0 { a } else { self.neg(a) };
        }
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(0.0), _) | (_, Some(0.0)) => return self.constant(0.0),
            (Some(1.0), _) => return b,
            (_, Some(1.0)) => return a,
            (Some(-1.0), _) => return self.neg(b),
            (_, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => self.mul(x, y),
            (Node::Neg(x), _) => {
                let p = self.mul(x, b);
                self.neg(p)
            }
            (_, Node::Neg(y)) => {
                let p = self.mul(a, y);
                self.neg(p)
            }
            // A negative constant factor becomes a negation of the positive one, so that
            // `−k x` and `k x` share their product.
            (Node::Const(bits), _) if f64::from_bits(bits) < 0.0 => {
                let k = self.constant(-f64::from_bits(bits));
                let p = self.mul(k, b);
                self.neg(p)
            }
            (_, Node::Const(bits)) if f64::from_bits(bits) < 0.0 => {
                let k = self.constant(-f64::from_bits(bits));
                let p = self.mul(a, k);
                self.neg(p)
            }
            _ => self.intern(Node::Mul(a.min(b), a.max(b))),
        }
    }

    /// `(k, y)` if node `x` is `k · y` with `k` a number (a product's operands are stored
    /// in id order: the number may be either).
    fn scaled(&self, x: Id) -> Option<(Id, Id)> {
        match self.node(x) {
            Node::Mul(p, y) if self.constant_value(p).is_some() => Some((p, y)),
            Node::Mul(y, p) if self.constant_value(p).is_some() => Some((p, y)),
            _ => None,
        }
    }

    /// `k / l` if `a` is `k x` and `b` is `l x` for one node `x`, each factor a number or
    /// missing (1) and either side possibly negated.
    fn ratio_of_multiples(&self, a: Id, b: Id) -> Option<f64> {
        let multiple = |x: Id| -> (f64, Id) {
            let (sign, x) = match self.node(x) {
                Node::Neg(y) => (-1.0, y),
                _ => (1.0, x),
            };
            match self.scaled(x).map(|(k, y)| (self.constant_value(k), y)) {
                Some((Some(k), y)) => (sign * k, y),
                _ => (sign, x),
            }
        };
        let ((k, x), (l, y)) = (multiple(a), multiple(b));
        (x == y).then_some(k / l)
    }

    /// `a / b`, folded: constants divided, `0 / x = 0`, `x / 1 = x`, `(k x) / (l x) = k / l`
    /// (so `x / x = 1`), a division by a number as a multiplication by its reciprocal, and
    /// a negated dividend's sign moved out.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x / y),
            (Some(0.0), _) => return self.constant(0.0),
            (_, Some(1.0)) => return a,
            // Division by a number becomes multiplication by its reciprocal.
            (_, Some(y)) => {
                let r = self.constant(1.0 / y);
                return self.mul(a, r);
            }
            _ => {}
        }
        // (k x)/(l x) = k/l (with `x / x = 1` the case k = l = 1): multiples of one
        // value, such as two entries of a column of `E` that share its capstan factors.
        if let Some(ratio) = self.ratio_of_multiples(a, b) {
            return self.constant(ratio);
        }
        // (−x)/y = −(x/y) exactly: the sign joins the others outside.
        if let Node::Neg(x) = self.node(a) {
            let q = self.div(x, b);
            return self.neg(q);
        }
        self.intern(Node::Div(a, b))
    }

    /// `−a`, folded: `−c` of a constant, `−(−x) = x`, `−(x − y) = y − x`.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(-x);
        }
        match self.node(a) {
            Node::Neg(x) => x,
            Node::Sub(x, y) => self.sub(y, x),
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `sin a`, folded: of a constant, and `sin(−x) = −sin x`.
    pub fn sin(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.sin());
        }
        match self.node(a) {
            Node::Neg(x) => {
                let s = self.sin(x);
                self.neg(s)
            }
            _ => self.intern(Node::Sin(a)),
        }
    }

    /// `cos a`, folded: of a constant, and `cos(−x) = cos x`.
    pub fn cos(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.cos());
        }
        match self.node(a) {
            Node::Neg(x) => self.cos(x),
            _ => self.intern(Node::Cos(a)),
        }
    }

    /// `√a`, folded for a constant.
    pub fn sqrt(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.sqrt());
        }
        self.intern(Node::Sqrt(a))
    }

    /// The larger of `a` and `b`, folded: `max(x, x) = x`, and of two constants.
    pub fn max(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return a;
        }
        if let (Some(x), Some(y)) = (self.constant_value(a), self.constant_value(b)) {
            return self.constant(x.max(y));
        }
        self.intern(Node::Max(a.min(b), a.max(b)))
    }

    /// `tanh a`, folded: of a constant, and `tanh(−x) = −tanh x`.
    pub fn tanh(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.tanh());
        }
        match self.node(a) {
            Node::Neg(x) => {
                let t = self.tanh(x);
                self.neg(t)
            }
            _ => self.intern(Node::Tanh(a)),
        }
    }

    /// `e^a`, folded of a constant.
    pub fn exp(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.exp());
        }
        self.intern(Node::Exp(a))
    }

    /// `a.sign_outside_or(band, otherwise)` ([`Real::sign_outside_or`]), folded when `a`
    /// and `band` are constants, and with a negation of `a` moved out: `sgn(−x) = −sgn(x)`,
    /// within the band too once `otherwise` is negated, so that a friction direction of a
    /// negated rate carries its sign to the products it enters (where it meets and cancels
    /// the capstan law's own `−` in `e^{−σμβ}`).
    pub fn sign_outside(&mut self, a: Id, band: Id, otherwise: Id) -> Id {
        if let (Some(x), Some(b)) = (self.constant_value(a), self.constant_value(band)) {
            return match x.sign_outside(b) {
                0.0 => otherwise,
                s => self.constant(s),
            };
        }
        if let Node::Neg(x) = self.node(a) {
            let flipped = self.neg(otherwise);
            let s = self.sign_outside(x, band, flipped);
            return self.neg(s);
        }
        self.intern(Node::SignOutside(a, band, otherwise))
    }

    /// `a.select_outside(band, above, below, otherwise)` ([`Real::select_outside`]),
    /// folded when `a` and `band` are constants or the three values are one, and with a
    /// negation of `a` taken into the choice (`above` and `below` swapped).
    pub fn select_outside(&mut self, [a, band, above, below, otherwise]: [Id; 5]) -> Id {
        if let (Some(x), Some(b)) = (self.constant_value(a), self.constant_value(band)) {
            return match x.sign_outside(b) {
                1.0 => above,
                -1.0 => below,
                _ => otherwise,
            };
        }
        if above == below && below == otherwise {
            return above;
        }
        // A choice of signs is a sign.
        if (self.constant_value(above), self.constant_value(below)) == (Some(1.0), Some(-1.0)) {
            return self.sign_outside(a, band, otherwise);
        }
        if let Node::Neg(x) = self.node(a) {
            return self.select_outside([x, band, below, above, otherwise]);
        }
        self.intern(Node::SelectOutside([a, band, above, below, otherwise]))
    }

    /// `roots` rebuilt with their numbers gathered in products: `k · (k' · y) = (k k') · y`,
    /// and `x · (k · y) = k · (x · y)` wherever `k · y` has no other use among the nodes the
    /// roots depend on. Never more multiplications, and products that differ only in
    /// their numbers (`q̇₀ (0.3 q̇₀)` and `q̇₀ (q̇₀ 0.15)`) then share `x · y`. A pass over
    /// finished functions: use counts are not known while the graph is built, and the
    /// closed form must expand the products as traced (a product of two numbers folded
    /// in f64 is rounded where the expansion's double-double one is not, and equal
    /// coefficients of two outputs would then differ in their last bit and not be shared).
    pub fn shared_products(&mut self, roots: &[Id]) -> Vec<Id> {
        let (live, uses) = self.live_with_uses(roots);
        let mut map: Vec<Id> = (0..self.nodes.len() as u32).map(Id).collect();
        for id in live {
            let node = self.node(id);
            let operands: Vec<Id> = node.operands().map(|x| map[x.0 as usize]).collect();
            map[id.0 as usize] = match node {
                Node::Mul(a, b) => self.gathered_product([a, b], &operands, &uses),
                _ => self.apply(node, &operands),
            };
        }
        roots.iter().map(|r| map[r.0 as usize]).collect()
    }

    /// `roots` rebuilt with the like terms of each sum merged: `a y + … + b y = (a + b) y`,
    /// `y − y = 0`. A sum reaches through the sums it alone uses (`x + (b y + z)` is the
    /// sum `x + b y + z`), so terms that the recursion added at different levels meet: the
    /// parallel-axis terms of a body, `m c ẍ` and `−(m c / 2) ẍ`, for one. A group of like
    /// terms is merged only where that saves operations, counting a product as free when
    /// it has other uses, and a sum is rebuilt from its terms only where one of them adds
    /// (see `sum_of`); everything else is rebuilt as it was, so no function gains
    /// an operation (tested on random graphs, root by root). A pass over finished
    /// functions, after [`Graph::shared_products`] (whose gathered numbers make like terms
    /// recognisable), over every function at once so that what they share stays shared.
    /// Numbers in a sum are summed the same way (`(x + 1) + 2 = x + 3`). Merged factors
    /// are summed in f64 and kept only where f32 holds them as normal numbers (or they
    /// cancel).
    pub fn merged_like_terms(&mut self, roots: &[Id]) -> Vec<Id> {
        let (live, uses) = self.live_with_uses(roots);
        let mut map: Vec<Id> = (0..self.nodes.len() as u32).map(Id).collect();
        let one = self.constant(1.0);
        // The terms of each sum with one use, for the sum that uses it to reach through.
        let mut sums: NodeMap<Id, Vec<Term>> = NodeMap::default();
        for id in live {
            let node = self.node(id);
            let operands: Vec<Id> = node.operands().map(|x| map[x.0 as usize]).collect();
            let (a, b, sign) = match node {
                Node::Add(a, b) => (a, b, 1.0),
                Node::Sub(a, b) => (a, b, -1.0),
                _ => {
                    map[id.0 as usize] = self.apply(node, &operands);
                    continue;
                }
            };
            let mut terms = Vec::new();
            for (x, sign) in [(a, 1.0), (b, sign)] {
                match sums.get(&x) {
                    Some(inner) => terms.extend(inner.iter().map(|t| t.times(sign))),
                    None => {
                        let alone = uses[x.0 as usize] == 1;
                        terms.push(self.term(map[x.0 as usize], sign, alone, one));
                    }
                }
            }
            let mut merged = terms.clone();
            let sum = if merge_like(&mut merged) {
                self.sum_of(&merged)
            } else {
                None
            };
            map[id.0 as usize] = match sum {
                Some(sum) => {
                    terms = merged;
                    sum
                }
                None => self.apply(node, &operands),
            };
            if uses[id.0 as usize] == 1 {
                sums.insert(id, terms);
            }
        }
        roots.iter().map(|r| map[r.0 as usize]).collect()
    }

    /// Node `x` as a term of a sum, times `sign`: `k y` as `(k, y)`, a number `c` as `(c,
    /// one)` (`one` the node of 1, so that numbers are summed as factors are, and held to
    /// f32's range as they are), `−z` as `−1` times `z`'s term, anything else as `(1, x)`.
    /// `alone`: `x` has no other use, so a product in it costs a multiplication that
    /// merging would save.
    fn term(&self, x: Id, sign: f64, alone: bool, one: Id) -> Term {
        if let Some(c) = self.constant_value(x) {
            // Numbers merged cost no product (`c · 1` folds): counted as one saved, so
            // that numbers are always summed.
            return Term {
                factor: sign * c,
                of: one,
                product_alone: true,
            };
        }
        match (self.node(x), self.scaled(x)) {
            (_, Some((k, y))) => Term {
                factor: sign * self.constant_value(k).unwrap_or(1.0),
                of: y,
                product_alone: alone,
            },
            // The negation's own product, if any, may be shared: not counted as saved.
            (Node::Neg(z), None) => Term {
                product_alone: false,
                ..self.term(z, -sign, false, one)
            },
            _ => Term {
                factor: sign,
                of: x,
                product_alone: false,
            },
        }
    }

    /// `Σ factor · of` over `terms` (0 for none), from the first term that adds, then the
    /// others in order, each added or subtracted as it stands: a negated term would be a
    /// node of its own (`−(a − b)` is built as `b − a`), and a sum of negative terms alone
    /// the negation of a sum, which its consumers would move outwards (`(−c) − b =
    /// −(c + b)`): operations more, so `None` there.
    fn sum_of(&mut self, terms: &[Term]) -> Option<Id> {
        if terms.is_empty() {
            return Some(self.constant(0.0));
        }
        let first = terms.iter().position(|t| t.factor > 0.0)?;
        let magnitude = |g: &mut Graph, t: &Term| {
            let k = g.constant(t.factor.abs());
            g.mul(k, t.of)
        };
        let mut sum = magnitude(self, &terms[first]);
        for (i, t) in terms.iter().enumerate() {
            if i != first {
                let term = magnitude(self, t);
                sum = if t.factor > 0.0 {
                    self.add(sum, term)
                } else {
                    self.sub(sum, term)
                };
            }
        }
        Some(sum)
    }

    /// The product of `rebuilt` (the new nodes of `original`'s two factors) with its
    /// numbers gathered (see [`Graph::shared_products`]).
    fn gathered_product(&mut self, original: [Id; 2], rebuilt: &[Id], uses: &[u32]) -> Id {
        let (a, b) = (rebuilt[0], rebuilt[1]);
        for (i, (x, s)) in [(a, b), (b, a)].into_iter().enumerate() {
            let Some((k, y)) = self.scaled(s) else {
                continue;
            };
            if let (Some(a), Some(b)) = (self.constant_value(x), self.constant_value(k)) {
                // Not where the product of the numbers would leave f32's normal range
                // (generated code may be asked for in f32, which must hold each number).
                let p = (a * b).abs();
                if (f64::from(f32::MIN_POSITIVE)..=f64::from(f32::MAX)).contains(&p) {
                    let kk = self.mul(x, k);
                    return self.mul(kk, y);
                }
                continue;
            }
            if uses[original[1 - i].0 as usize] == 1 {
                let xy = self.mul(x, y);
                return self.mul(k, xy);
            }
        }
        self.mul(a, b)
    }

    /// The operation of `node` applied to `operands` (as many as it has), folded by the
    /// smart constructors.
    fn apply(&mut self, node: Node, operands: &[Id]) -> Id {
        let x = |i: usize| operands[i];
        match node {
            Node::Const(bits) => self.constant(f64::from_bits(bits)),
            Node::Input(_) => self.intern(node),
            Node::Add(..) => self.add(x(0), x(1)),
            Node::Sub(..) => self.sub(x(0), x(1)),
            Node::Mul(..) => self.mul(x(0), x(1)),
            Node::Div(..) => self.div(x(0), x(1)),
            Node::Neg(_) => self.neg(x(0)),
            Node::Sin(_) => self.sin(x(0)),
            Node::Cos(_) => self.cos(x(0)),
            Node::Sqrt(_) => self.sqrt(x(0)),
            Node::Tanh(_) => self.tanh(x(0)),
            Node::Exp(_) => self.exp(x(0)),
            Node::Max(..) => self.max(x(0), x(1)),
            Node::SignOutside(..) => self.sign_outside(x(0), x(1), x(2)),
            Node::SelectOutside(..) => self.select_outside([x(0), x(1), x(2), x(3), x(4)]),
        }
    }

    /// Values of `roots` at the given inputs (by input index), in f64, node by node as the
    /// emitted code computes them.
    pub fn eval(&self, roots: &[Id], inputs: &[f64]) -> Vec<f64> {
        let live = self.live(roots);
        let mut value = vec![0.0f64; self.nodes.len()];
        for id in live {
            let v = |x: Id| value[x.0 as usize];
            value[id.0 as usize] = match self.node(id) {
                Node::Const(bits) => f64::from_bits(bits),
                Node::Input(i) => inputs[i as usize],
                Node::Add(a, b) => v(a) + v(b),
                Node::Sub(a, b) => v(a) - v(b),
                Node::Mul(a, b) => v(a) * v(b),
                Node::Div(a, b) => v(a) / v(b),
                Node::Neg(a) => -v(a),
                Node::Sin(a) => v(a).sin(),
                Node::Cos(a) => v(a).cos(),
                Node::Sqrt(a) => v(a).sqrt(),
                Node::Tanh(a) => v(a).tanh(),
                Node::Exp(a) => v(a).exp(),
                Node::Max(a, b) => v(a).max(v(b)),
                Node::SignOutside(a, b, c) => v(a).sign_outside_or(v(b), v(c)),
                Node::SelectOutside([a, b, p, m, o]) => v(a).select_outside(v(b), v(p), v(m), v(o)),
            };
        }
        roots.iter().map(|r| value[r.0 as usize]).collect()
    }

    /// Whether each node (by index) is one the given roots depend on.
    pub fn live_mask(&self, roots: &[Id]) -> Vec<bool> {
        let mut mark = vec![false; self.nodes.len()];
        let mut stack: Vec<Id> = roots.to_vec();
        while let Some(id) = stack.pop() {
            if !std::mem::replace(&mut mark[id.0 as usize], true) {
                stack.extend(self.node(id).operands());
            }
        }
        mark
    }

    /// [`Graph::live`], and how many times each node (by index) is used: as an operand of a
    /// live node, or as a root (a root used inside the graph too is used more than once).
    fn live_with_uses(&self, roots: &[Id]) -> (Vec<Id>, Vec<u32>) {
        let live = self.live(roots);
        let mut uses = vec![0u32; self.nodes.len()];
        for &id in &live {
            for a in self.node(id).operands() {
                uses[a.0 as usize] += 1;
            }
        }
        for r in roots {
            uses[r.0 as usize] += 1;
        }
        (live, uses)
    }

    /// Every node the given roots depend on, in index (evaluation) order.
    pub fn live(&self, roots: &[Id]) -> Vec<Id> {
        let mark = self.live_mask(roots);
        (0..self.nodes.len() as u32)
            .map(Id)
            .filter(|id| mark[id.0 as usize])
            .collect()
    }

    /// Operation counts of the nodes the roots depend on.
    pub fn count(&self, roots: &[Id]) -> OpCount {
        let mut c = OpCount::default();
        let mark = self.live_mask(roots);
        let live = (0..self.nodes.len() as u32)
            .map(Id)
            .filter(|id| mark[id.0 as usize]);
        let has = |n: Node| self.memo.get(&n).is_some_and(|id| mark[id.0 as usize]);
        for id in live {
            match self.node(id) {
                Node::Add(..) | Node::Sub(..) => c.add += 1,
                Node::Mul(..) => c.mul += 1,
                Node::Div(..) => c.div += 1,
                Node::Neg(_) => c.neg += 1,
                Node::Sin(a) => {
                    // sin and cos of one angle are computed together, once.
                    if has(Node::Cos(a)) {
                        c.sin_cos += 1;
                    } else {
                        c.sin += 1;
                    }
                }
                Node::Cos(a) => {
                    if !has(Node::Sin(a)) {
                        c.cos += 1;
                    }
                }
                Node::Sqrt(_) => c.sqrt += 1,
                Node::Tanh(_) => c.tanh += 1,
                Node::Exp(_) => c.exp += 1,
                Node::Max(..) => c.max += 1,
                Node::SignOutside(..) | Node::SelectOutside(..) => c.sign += 1,
                Node::Const(_) | Node::Input(_) => {}
            }
        }
        c
    }
}

/// One term `factor · of` of a sum ([`Graph::merged_like_terms`]).
#[derive(Clone, Copy, Debug)]
struct Term {
    factor: f64,
    of: Id,
    /// The term is a product `factor · of` with no other use: merging saves it.
    product_alone: bool,
}

impl Term {
    fn times(self, sign: f64) -> Term {
        Term {
            factor: sign * self.factor,
            ..self
        }
    }
}

/// Merges, in place, each group of `terms` with one `of` into its first, where that saves
/// operations; whether any group was merged. A group of `n` terms, `p` of them products
/// with no other use, costs `n` places in the sum and `p` products; merged, one place (none
/// if the factors cancel) and one product (none for a factor of ±1 or 0).
fn merge_like(terms: &mut Vec<Term>) -> bool {
    let mut merged = false;
    let mut i = 0;
    while i < terms.len() {
        let of = terms[i].of;
        let group: Vec<usize> = (i..terms.len()).filter(|&j| terms[j].of == of).collect();
        if group.len() > 1 {
            let factor: f64 = group.iter().map(|&j| terms[j].factor).sum();
            let alone = group.iter().filter(|&&j| terms[j].product_alone).count();
            let places = usize::from(factor != 0.0);
            let product = usize::from(factor != 0.0 && factor.abs() != 1.0);
            // f32 must hold the merged number (generated code may be asked for in f32).
            let holds = factor == 0.0
                || (f64::from(f32::MIN_POSITIVE)..=f64::from(f32::MAX)).contains(&factor.abs());
            if holds && alone + group.len() > places + product {
                for &j in group[1..].iter().rev() {
                    terms.remove(j);
                }
                if factor == 0.0 {
                    terms.remove(i);
                    merged = true;
                    continue;
                }
                terms[i] = Term {
                    factor,
                    of,
                    product_alone: product == 1,
                };
                merged = true;
            }
        }
        i += 1;
    }
    merged
}

/// Operations of a straight-line function.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions (by a variable: division by a number is a multiplication).
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// Sines of angles whose cosine is not needed.
    pub sin: usize,
    /// Cosines of angles whose sine is not needed.
    pub cos: usize,
    /// Angles whose sine and cosine are both needed (one `sin_cos` call each).
    pub sin_cos: usize,
    /// Square roots.
    pub sqrt: usize,
    /// `max`es (the tension distribution along one null direction).
    pub max: usize,
    /// Sign selects ([`Node::SignOutside`]): friction directions, and the branch a
    /// derivative of `max` follows.
    #[serde(skip_serializing_if = "is_zero")]
    pub sign: usize,
    /// Hyperbolic tangents (the smoothed friction law).
    #[serde(skip_serializing_if = "is_zero")]
    pub tanh: usize,
    /// Exponentials (the capstan law of guides with friction).
    #[serde(skip_serializing_if = "is_zero")]
    pub exp: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl OpCount {
    /// Arithmetic operations (add, sub, mul, div, neg, max, sign selects: friction's
    /// directions and the branch a derivative of `max` follows): what the peers' op counts
    /// count.
    pub fn arithmetic(&self) -> usize {
        self.add + self.mul + self.div + self.neg + self.max + self.sign
    }
}

impl std::fmt::Display for OpCount {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} arithmetic ({} add/sub, {} mul, {} div, {} neg, {} max), {} sin_cos, {} sin, {} cos, {} sqrt",
            self.arithmetic(),
            self.add,
            self.mul,
            self.div,
            self.neg,
            self.max,
            self.sin_cos,
            self.sin,
            self.cos,
            self.sqrt
        )?;
        // Selects and friction's terms only where there are any: a count without them
        // reads as before.
        if self.sign > 0 {
            write!(f, ", {} sign selects", self.sign)?;
        }
        if self.tanh > 0 {
            write!(f, ", {} tanh", self.tanh)?;
        }
        if self.exp > 0 {
            write!(f, ", {} exp", self.exp)?;
        }
        Ok(())
    }
}

/// The symbolic scalar: a node of the current graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sym(pub Id);

impl Sym {
    /// A new input of the current graph, named `name` (see [`Graph::input`]).
    ///
    /// # Panics
    ///
    /// Outside [`Graph::scope`].
    pub fn input(name: impl Into<String>) -> Sym {
        let name = name.into();
        Sym(with(|g| g.input(name)))
    }

    /// `f` of the current graph, read only: what a symbol built so far is.
    ///
    /// # Panics
    ///
    /// Outside [`Graph::scope`].
    pub fn inspect<R>(f: impl FnOnce(&Graph) -> R) -> R {
        with(|g| f(g))
    }
}

macro_rules! binary {
    ($tr:ident, $m:ident, $g:ident) => {
        impl std::ops::$tr for Sym {
            type Output = Sym;
            fn $m(self, o: Sym) -> Sym {
                Sym(with(|g| g.$g(self.0, o.0)))
            }
        }
    };
}
binary!(Add, add, add);
binary!(Sub, sub, sub);
binary!(Mul, mul, mul);
binary!(Div, div, div);

impl std::ops::Neg for Sym {
    type Output = Sym;
    fn neg(self) -> Sym {
        Sym(with(|g| g.neg(self.0)))
    }
}

/// A handle is an expression of the generated code's inputs, never a number.
impl Symbolic for Sym {}

impl Real for Sym {
    fn from_f64(x: f64) -> Self {
        Sym(with(|g| g.constant(x)))
    }
    fn sin(self) -> Self {
        Sym(with(|g| g.sin(self.0)))
    }
    fn cos(self) -> Self {
        Sym(with(|g| g.cos(self.0)))
    }
    fn sqrt(self) -> Self {
        Sym(with(|g| g.sqrt(self.0)))
    }
    fn max(self, other: Self) -> Self {
        Sym(with(|g| g.max(self.0, other.0)))
    }
    fn tanh(self) -> Self {
        Sym(with(|g| g.tanh(self.0)))
    }
    fn exp(self) -> Self {
        Sym(with(|g| g.exp(self.0)))
    }
    fn sign_outside_or(self, band: Self, otherwise: Self) -> Self {
        Sym(with(|g| g.sign_outside(self.0, band.0, otherwise.0)))
    }
    fn select_outside(self, band: Self, above: Self, below: Self, otherwise: Self) -> Self {
        Sym(with(|g| {
            g.select_outside([self.0, band.0, above.0, below.0, otherwise.0])
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_inside_a_scope_leaves_the_thread_free_for_the_next_scope() {
        let caught = std::panic::catch_unwind(|| {
            Graph::default().scope(|| panic!("a trace that fails"));
        });
        assert!(caught.is_err());
        // Without the guard this second scope panicked with "does not nest".
        let (g, _) = Graph::default().scope(|| Sym::input("x"));
        assert_eq!(g.input_names, ["x"]);
    }

    /// Builds `f` of inputs `x`, `y` and gathers its numbers: the operation counts before
    /// and after, and both values at `(x, y) = (0.7, -1.3)`.
    fn gathered(f: impl FnOnce(Sym, Sym) -> Sym) -> (OpCount, OpCount, f64, f64) {
        let (mut g, root) = Graph::default().scope(|| f(Sym::input("x"), Sym::input("y")));
        let before = g.count(&[root.0]);
        let after = g.shared_products(&[root.0])[0];
        let inputs = [0.7, -1.3];
        let values = (g.eval(&[root.0], &inputs)[0], g.eval(&[after], &inputs)[0]);
        (before, g.count(&[after]), values.0, values.1)
    }

    #[test]
    fn products_that_differ_only_in_their_numbers_share_the_product_of_their_variables() {
        let k = Sym::from_f64;
        // x (0.3 x) + x (x 0.15) + y: x·x once, then each number.
        let (before, after, v0, v1) = gathered(|x, y| x * (k(0.3) * x) + x * (x * k(0.15)) + y);
        assert_eq!((before.mul, after.mul), (4, 3));
        assert_eq!(before.add, after.add);
        assert!((v0 - v1).abs() <= 4.0 * f64::EPSILON * v0.abs());
    }

    #[test]
    fn a_number_times_a_scaled_variable_is_one_multiplication() {
        let k = Sym::from_f64;
        // 2 (3 x) + y: 6 x + y.
        let (before, after, v0, v1) = gathered(|x, y| k(2.0) * (k(3.0) * x) + y);
        assert_eq!((before.mul, after.mul), (2, 1));
        assert_eq!(v0, v1);
    }

    #[test]
    fn the_quotient_of_two_multiples_of_one_value_is_the_ratio_of_their_numbers() {
        let k = Sym::from_f64;
        let (g, roots) = Graph::default().scope(|| {
            let (x, y) = (Sym::input("x"), Sym::input("y"));
            let e = x * y;
            [
                (k(0.007) * e) / (-(k(0.008) * e)),
                e / (k(4.0) * e),
                (k(3.0) * e) / e,
                (k(3.0) * x) / (k(2.0) * y),
            ]
        });
        let numbers: Vec<Option<f64>> = roots.iter().map(|r| g.constant_value(r.0)).collect();
        assert_eq!(numbers[..3], [Some(0.007 / -0.008), Some(0.25), Some(3.0)]);
        // Multiples of different values stay a division.
        assert_eq!(numbers[3], None);
        assert_eq!(g.count(&[roots[3].0]).div, 1);
    }

    /// Builds `f` of inputs `x`, `y` and merges its like terms: the operation counts before
    /// and after, and both values at `(x, y) = (0.7, -1.3)`.
    fn merged(f: impl FnOnce(Sym, Sym) -> Sym) -> (OpCount, OpCount, f64, f64) {
        let (mut g, root) = Graph::default().scope(|| f(Sym::input("x"), Sym::input("y")));
        let before = g.count(&[root.0]);
        let after = g.merged_like_terms(&[root.0])[0];
        let inputs = [0.7, -1.3];
        let values = (g.eval(&[root.0], &inputs)[0], g.eval(&[after], &inputs)[0]);
        (before, g.count(&[after]), values.0, values.1)
    }

    #[test]
    fn like_terms_added_at_different_levels_of_a_sum_are_one_product() {
        let k = Sym::from_f64;
        // 0.3 x + (y − 0.1 x): the inner sum has no other use, so the outer one reaches
        // into it and sees 0.3 x and −0.1 x: 0.2 x + y.
        let (before, after, v0, v1) = merged(|x, y| k(0.3) * x + (y - k(0.1) * x));
        assert_eq!((before.mul, before.add), (2, 2));
        assert_eq!((after.mul, after.add), (1, 1));
        assert!((v0 - v1).abs() <= 4.0 * f64::EPSILON * v0.abs());
    }

    #[test]
    fn like_terms_that_cancel_leave_the_sum() {
        let k = Sym::from_f64;
        // (0.5 x + y) − 0.5 x = y, with no operation left; and x + (y − x) likewise.
        let (_, after, v0, v1) = merged(|x, y| (k(0.5) * x + y) - k(0.5) * x);
        assert_eq!(after.arithmetic(), 0);
        assert_eq!(v0, v1);
        let (_, after, v0, v1) = merged(|x, y| x + (y - x));
        assert_eq!(after.arithmetic(), 0);
        assert_eq!(v0, v1);
    }

    #[test]
    fn like_terms_are_left_apart_where_merging_saves_nothing() {
        let k = Sym::from_f64;
        // 0.3 y and 0.2 y are both used elsewhere: (0.3 + 0.2) y would trade an addition
        // for a multiplication.
        let (before, after, ..) = merged(|x, y| {
            let (a, b) = (k(0.3) * y, k(0.2) * y);
            (a + b) * (a * x + b)
        });
        assert_eq!(before, after);
        // A sum with another use is not copied into its consumer: a − 0.3 x keeps `a`.
        let (before, after, ..) = merged(|x, y| {
            let a = k(0.3) * x + y;
            (a - k(0.3) * x) * a
        });
        assert_eq!(before, after);
    }

    #[test]
    fn merging_like_terms_never_adds_an_operation_and_keeps_every_value() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let numbers = [0.5, -0.5, 0.25, 1.0, -1.0, 2.0, 0.3, -0.3];
        let mut fewer = 0;
        for _ in 0..3000 {
            // Random sums, differences, negations and products, scaled and not, over three
            // inputs, whose pieces are used once or more: the last three are the roots.
            let (mut g, roots) = Graph::default().scope(|| {
                let mut pool: Vec<Sym> = (0..3).map(|i| Sym::input(format!("x{i}"))).collect();
                for _ in 0..14 {
                    let mut pick = || pool[rng.random_range(0..pool.len())];
                    let (a, b) = (pick(), pick());
                    let k = Sym::from_f64(numbers[rng.random_range(0..numbers.len())]);
                    pool.push(match rng.random_range(0..7) {
                        0 => a + b,
                        1 => a - b,
                        2 => k * a + b,
                        3 => a - k * b,
                        4 => a * b,
                        5 => a + k,
                        _ => -a,
                    });
                }
                pool[pool.len() - 3..]
                    .iter()
                    .map(|s| s.0)
                    .collect::<Vec<Id>>()
            });
            let before = g.count(&roots).arithmetic();
            let merged = g.merged_like_terms(&roots);
            let after = g.count(&merged).arithmetic();
            assert!(after <= before, "{after} operations against {before}");
            for (r, m) in roots.iter().zip(&merged) {
                let (before, after) = (g.count(&[*r]), g.count(&[*m]));
                assert!(
                    after.arithmetic() <= before.arithmetic(),
                    "one root: {after} against {before}"
                );
            }
            fewer += usize::from(after < before);
            let inputs: Vec<f64> = (0..3).map(|_| rng.random_range(-1.0..1.0)).collect();
            // Round-off relative to the largest value the original computes on the way.
            let live = g.live(&roots);
            let size = g
                .eval(&live, &inputs)
                .iter()
                .fold(1.0f64, |m, v| m.max(v.abs()));
            let (v0, v1) = (g.eval(&roots, &inputs), g.eval(&merged, &inputs));
            for (a, b) in v0.iter().zip(&v1) {
                assert!(
                    (a - b).abs() <= 64.0 * f64::EPSILON * size,
                    "{a} against {b}"
                );
            }
        }
        // The pass does something on such graphs (not a test that cannot fail).
        assert!(fewer > 300, "{fewer} of 3000 graphs lost an operation");
    }

    #[test]
    fn a_scaled_variable_used_elsewhere_keeps_its_number() {
        let k = Sym::from_f64;
        // (0.3 y) is used twice: moving 0.3 out of x (0.3 y) would add a multiplication.
        let (before, after, ..) = gathered(|x, y| {
            let s = k(0.3) * y;
            x * s + s
        });
        assert_eq!(before, after);
    }
}
