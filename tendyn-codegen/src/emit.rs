//! Graph → Rust source: one straight-line function per requested output and one, `all`,
//! that returns every output sharing their common work; formatted with prettyplease.
//!
//! Every live node the results reach becomes at most one `let` (nodes used once are
//! written inline), in index order, so the code computes exactly the graph; the sine and
//! cosine of one angle are computed together with `sin_cos`, and on targets with 256-bit
//! vectors those of every angle linear in `q` (four or more) first, in one call of
//! `Real::sin_cos_array` (vector code in `f64`); a product whose one consumer among the
//! emitted nodes is a sum or difference is written into it as `Real::mul_add` (one rounding
//! where the target has FMA). Nothing else is emitted: no loops, no allocation, no panics, no
//! arithmetic on known zeros (those never became nodes).
//! The code is generic over `tendyn_core::Real` unless a concrete scalar is asked for, and
//! needs neither `std` nor `alloc`.
//!
//! The file is one `syn` syntax tree: the item skeletons (signatures, constants, the
//! `Outputs` struct) through `quote!` and `parse_quote!`, every `let` and result built as
//! a tree ([`emit_file`]). The derive hands the tree's items to the compiler as they are;
//! the command line and the build script print it once with prettyplease ([`emit`]).
//! prettyplease prints a tree as it is, so the tree carries exactly the parentheses a
//! parser would have produced from the written code.

use crate::expr::{Graph, Id, Node};
use crate::outputs::{result_labels, Function, Output, Param, Shape, StatusFrom, Traced};
use proc_macro2::{Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::cell::OnceCell;
use syn::punctuated::Punctuated;
use syn::{parse_quote, BinOp, Expr, Ident, Stmt};
use tendyn_core::Model;

/// The scalar type of the emitted functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    /// Generic over `T: tendyn_core::Real`.
    Generic,
    /// Concrete `f64`.
    F64,
    /// Concrete `f32`.
    F32,
}

impl Scalar {
    /// `generic`, `f64` or `f32`, as `tendyn generate --scalar` takes them; `None`
    /// otherwise.
    pub fn parse(s: &str) -> Option<Scalar> {
        match s {
            "generic" => Some(Scalar::Generic),
            "f64" => Some(Scalar::F64),
            "f32" => Some(Scalar::F32),
            _ => None,
        }
    }
    fn ty(self) -> TokenStream {
        match self {
            Scalar::Generic => quote!(T),
            Scalar::F64 => quote!(f64),
            Scalar::F32 => quote!(f32),
        }
    }
    fn generics(self) -> TokenStream {
        match self {
            Scalar::Generic => quote!(<T: Real>),
            _ => quote!(),
        }
    }
}

/// The generic parameter of a function: `T: Real`, or `T: Numeric` where it calls the
/// tension distribution (which compares and needs the scalar's round-off).
fn bound(scalar: Scalar, compares: bool) -> TokenStream {
    match (scalar, compares) {
        (Scalar::Generic, true) => quote!(<T: Numeric>),
        _ => scalar.generics(),
    }
}

/// Whether `f` decides a distribution's status or distributes (and so compares).
fn compares(f: &Function) -> bool {
    matches!(
        f.shape,
        Shape::Actuation {
            status: StatusFrom::Line | StatusFrom::Solve | StatusFrom::SolveAtState { .. },
            ..
        } | Shape::ActuationJacobians {
            distributed: StatusFrom::Solve | StatusFrom::SolveAtState { .. },
            ..
        }
    )
}

/// Syntax-tree constructors for the expression forms the bodies use.
mod ast {
    use super::*;

    pub fn ident(name: &str) -> Ident {
        Ident::new(name, Span::call_site())
    }

    /// `a::b::c` (or a plain variable).
    pub fn path(segments: &[&str]) -> Expr {
        Expr::Path(syn::ExprPath {
            attrs: Vec::new(),
            qself: None,
            path: syn::Path {
                leading_colon: None,
                segments: segments
                    .iter()
                    .map(|s| syn::PathSegment::from(ident(s)))
                    .collect(),
            },
        })
    }

    pub fn var(name: Ident) -> Expr {
        Expr::Path(syn::ExprPath {
            attrs: Vec::new(),
            qself: None,
            path: name.into(),
        })
    }

    pub fn lit(l: Literal) -> Expr {
        Expr::Lit(syn::ExprLit {
            attrs: Vec::new(),
            lit: syn::Lit::new(l),
        })
    }

    /// `-e`
    pub fn neg(e: Expr) -> Expr {
        Expr::Unary(syn::ExprUnary {
            attrs: Vec::new(),
            op: syn::UnOp::Neg(Default::default()),
            expr: Box::new(e),
        })
    }

    pub fn binary(left: Expr, op: BinOp, right: Expr) -> Expr {
        Expr::Binary(syn::ExprBinary {
            attrs: Vec::new(),
            left: Box::new(left),
            op,
            right: Box::new(right),
        })
    }

    /// `(e)`
    pub fn paren(e: Expr) -> Expr {
        Expr::Paren(syn::ExprParen {
            attrs: Vec::new(),
            paren_token: Default::default(),
            expr: Box::new(e),
        })
    }

    /// `f(args)`
    pub fn call(func: Expr, args: impl IntoIterator<Item = Expr>) -> Expr {
        Expr::Call(syn::ExprCall {
            attrs: Vec::new(),
            func: Box::new(func),
            paren_token: Default::default(),
            args: Punctuated::from_iter(args),
        })
    }

    /// `receiver.method(args)`
    pub fn method(receiver: Expr, method: &str, args: impl IntoIterator<Item = Expr>) -> Expr {
        Expr::MethodCall(syn::ExprMethodCall {
            attrs: Vec::new(),
            receiver: Box::new(receiver),
            dot_token: Default::default(),
            method: ident(method),
            turbofish: None,
            paren_token: Default::default(),
            args: args.into_iter().collect(),
        })
    }

    /// `array[index]`
    pub fn index(array: &str, index: usize) -> Expr {
        Expr::Index(syn::ExprIndex {
            attrs: Vec::new(),
            expr: Box::new(path(&[array])),
            bracket_token: Default::default(),
            index: Box::new(lit(Literal::usize_unsuffixed(index))),
        })
    }

    /// `[a, b, ...]`
    pub fn array(elems: impl IntoIterator<Item = Expr>) -> Expr {
        Expr::Array(syn::ExprArray {
            attrs: Vec::new(),
            bracket_token: Default::default(),
            elems: elems.into_iter().collect(),
        })
    }

    /// `Name { field: value, ... }`
    pub fn struct_literal(name: &str, fields: impl IntoIterator<Item = (Ident, Expr)>) -> Expr {
        Expr::Struct(syn::ExprStruct {
            attrs: Vec::new(),
            qself: None,
            path: ident(name).into(),
            brace_token: Default::default(),
            fields: fields
                .into_iter()
                .map(|(member, expr)| syn::FieldValue {
                    attrs: Vec::new(),
                    member: syn::Member::Named(member),
                    colon_token: Some(Default::default()),
                    expr,
                })
                .collect(),
            dot2_token: None,
            rest: None,
        })
    }

    fn pat(name: Ident) -> syn::Pat {
        syn::Pat::Ident(syn::PatIdent {
            attrs: Vec::new(),
            by_ref: None,
            mutability: None,
            ident: name,
            subpat: None,
        })
    }

    fn local(pat: syn::Pat, value: Expr) -> Stmt {
        Stmt::Local(syn::Local {
            attrs: Vec::new(),
            let_token: Default::default(),
            modifiers: Default::default(),
            pat,
            init: Some(syn::LocalInit {
                eq_token: Default::default(),
                expr: Box::new(value),
                diverge: None,
            }),
            semi_token: Default::default(),
        })
    }

    /// `let name = value;`
    pub fn let_one(name: Ident, value: Expr) -> Stmt {
        local(pat(name), value)
    }

    /// `let [(s₁, c₁), (s₂, c₂), …] = value;`
    pub fn let_pairs(pairs: impl IntoIterator<Item = (Ident, Ident)>, value: Expr) -> Stmt {
        let tuple = |(a, b)| {
            syn::Pat::Tuple(syn::PatTuple {
                attrs: Vec::new(),
                paren_token: Default::default(),
                elems: Punctuated::from_iter([pat(a), pat(b)]),
            })
        };
        let slice = syn::Pat::Slice(syn::PatSlice {
            attrs: Vec::new(),
            bracket_token: Default::default(),
            elems: pairs.into_iter().map(tuple).collect(),
        });
        local(slice, value)
    }

    /// `#[cfg(predicate)]` on a `let`.
    pub fn only_if(stmt: &mut Stmt, predicate: TokenStream) {
        if let Stmt::Local(local) = stmt {
            local.attrs.push(parse_quote!(#[cfg(#predicate)]));
        }
    }

    /// `let (a, b) = value;`
    pub fn let_pair(a: Ident, b: Ident, value: Expr) -> Stmt {
        let pair = syn::Pat::Tuple(syn::PatTuple {
            attrs: Vec::new(),
            paren_token: Default::default(),
            elems: Punctuated::from_iter([pat(a), pat(b)]),
        });
        local(pair, value)
    }
}

/// The expressions of constants and inputs, by node index, shared by every body: the same
/// few recur throughout, and cloning a tree is cheaper than formatting and parsing a literal.
///
/// `proc_macro2::Literal` asserts that a float is finite: every constant written here (and
/// the structure matrix and distribution constants of [`emit`]) has been checked to fit
/// the scalar before emission (`check_constants` in `lib.rs`), which returns an error
/// instead.
struct Atoms<'g> {
    g: &'g Graph,
    scalar: Scalar,
    exprs: Vec<OnceCell<(Expr, u8)>>,
    /// The products that may become a `Real::mul_add` with their one consumer: those with
    /// exactly one among the nodes any emitted function computes. Decided for them all, not
    /// per function, so that every function rounds a shared subexpression alike (`all`
    /// gives, bit for bit, what the functions it gathers give); nodes no function computes
    /// (left behind by the passes over finished functions) are not consumers.
    fusible: Vec<bool>,
}

impl<'g> Atoms<'g> {
    /// The atoms of `g` for functions whose results are `roots`.
    fn new(g: &'g Graph, roots: &[Id], scalar: Scalar) -> Self {
        let mut consumers = vec![0u32; g.nodes.len()];
        for id in g.live(roots) {
            for operand in g.node(id).operands() {
                consumers[operand.0 as usize] += 1;
            }
        }
        let fusible = (g.nodes.iter().zip(&consumers))
            .map(|(node, &n)| matches!(node, Node::Mul(..)) && n == 1)
            .collect();
        Atoms {
            g,
            scalar,
            fusible,
            exprs: vec![OnceCell::new(); g.nodes.len()],
        }
    }

    /// The expression of a constant or input node and its precedence (see
    /// [`Body::expr_prec`]).
    fn get(&self, id: Id) -> (Expr, u8) {
        let atom = || match self.g.node(id) {
            Node::Const(bits) => self.constant(f64::from_bits(bits)),
            Node::Input(i) => self.input(i),
            _ => unreachable!("only constants and inputs are atoms"),
        };
        self.exprs[id.0 as usize].get_or_init(atom).clone()
    }

    fn constant(&self, c: f64) -> (Expr, u8) {
        let signed = |lit: Literal| {
            let lit = ast::lit(lit);
            if c < 0.0 {
                ast::neg(lit)
            } else {
                lit
            }
        };
        // A negative literal is a unary minus, except as the argument of `from_f64`.
        let negated = if c < 0.0 { 3 } else { 4 };
        match self.scalar {
            Scalar::Generic => {
                let value = signed(Literal::f64_unsuffixed(c.abs()));
                (ast::call(ast::path(&["T", "from_f64"]), [value]), 4)
            }
            Scalar::F64 => (signed(Literal::f64_suffixed(c.abs())), negated),
            Scalar::F32 => (signed(Literal::f32_suffixed((c as f32).abs())), negated),
        }
    }

    fn input(&self, i: u32) -> (Expr, u8) {
        let name = &self.g.input_names[i as usize];
        let (array, index) = name.split_once('[').expect("inputs are array elements");
        let index: usize = index.trim_end_matches(']').parse().expect("an index");
        (ast::index(array, index), 4)
    }
}

/// The variable node `id` is bound to: `prefix` (`t`, `s` or `c`) and the node's number.
fn variable(prefix: char, id: Id) -> Ident {
    use std::fmt::Write;
    let mut name = String::with_capacity(12);
    name.push(prefix);
    write!(name, "{}", id.0).expect("writing to a String");
    ast::ident(&name)
}

/// One function body: `let`s for shared nodes, then the result expression.
struct Body<'g> {
    g: &'g Graph,
    atoms: &'g Atoms<'g>,
    /// The variable bound to each node, by node index ([`variable`]).
    vars: Vec<Option<Ident>>,
    /// The `let`s, in order.
    stmts: Vec<Stmt>,
    /// The sines whose angle's sine and cosine also come from the one `sin_cos_array` call
    /// of targets with wide vectors ([`Body::bind_turns`]).
    batched: rustc_hash::FxHashSet<Id>,
}

impl<'g> Body<'g> {
    fn new(atoms: &'g Atoms<'g>) -> Self {
        Body {
            g: atoms.g,
            atoms,
            vars: vec![None; atoms.g.nodes.len()],
            stmts: Vec::new(),
            batched: Default::default(),
        }
    }

    fn var(&self, id: Id) -> Option<&Ident> {
        self.vars[id.0 as usize].as_ref()
    }

    fn expr(&self, id: Id) -> Expr {
        self.expr_prec(id).0
    }

    /// `a ± b` as `Real::mul_add` where one of them is a product that may be fused
    /// ([`Atoms::fusible`]) and is written inline: one rounding where the target has FMA
    /// (measured: generated `Q` 11-26 % faster on the 8- and 12-link chains,
    /// docs/generated-code.md §4), exactly the unfused form elsewhere. `a − x·y` is
    /// `mul_add(−x, y, a)` and `x·y − b` is `mul_add(x, y, −b)`: negation is exact.
    fn multiply_add(&self, a: Id, b: Id, subtract: bool) -> Option<(Expr, u8)> {
        let product = |x: Id| match self.g.node(x) {
            Node::Mul(p, q) if self.atoms.fusible[x.0 as usize] && self.var(x).is_none() => {
                Some((p, q))
            }
            _ => None,
        };
        let signed = |x: Id, negate: bool| {
            if negate {
                self.negated(x)
            } else {
                self.expr(x)
            }
        };
        let (x, y, addend) = match (product(a), product(b)) {
            (_, Some((x, y))) => (signed(x, subtract), self.expr(y), self.expr(a)),
            (Some((x, y)), None) => (self.expr(x), self.expr(y), signed(b, subtract)),
            (None, None) => return None,
        };
        let call = ast::call(ast::path(&["Real", "mul_add"]), [x, y, addend]);
        Some((call, 4))
    }

    /// `−id`, with no double negation: `−(−e)` is written `e` (negation is exact).
    fn negated(&self, id: Id) -> Expr {
        match self.expr_prec(id) {
            (
                Expr::Unary(syn::ExprUnary {
                    op: syn::UnOp::Neg(_),
                    expr,
                    ..
                }),
                _,
            ) => *expr,
            (e, p) if p < 3 => ast::neg(ast::paren(e)),
            (e, _) => ast::neg(e),
        }
    }

    /// The expression of `id` and its precedence (1: `+ -`, 2: `* /`, 3: unary minus,
    /// 4: atoms and method calls). Parentheses are added where the child binds less
    /// tightly, and around a right operand of equal precedence: floating-point addition and
    /// multiplication are not associative, so the emitted grouping must be the graph's.
    fn expr_prec(&self, id: Id) -> (Expr, u8) {
        if let Some(var) = self.var(id) {
            return (ast::var(var.clone()), 4);
        }
        let operand = |x: Id, min: u8| {
            let (e, p) = self.expr_prec(x);
            if p < min {
                ast::paren(e)
            } else {
                e
            }
        };
        let binary = |a: Id, op: BinOp, b: Id, p: u8| {
            // The right operand of equal precedence is parenthesized (see above).
            let (a, b) = (operand(a, p), operand(b, p + 1));
            (ast::binary(a, op, b), p)
        };
        match self.g.node(id) {
            Node::Const(_) | Node::Input(_) => self.atoms.get(id),
            Node::Add(a, b) => self
                .multiply_add(a, b, false)
                .unwrap_or_else(|| binary(a, BinOp::Add(Default::default()), b, 1)),
            Node::Sub(a, b) => self
                .multiply_add(a, b, true)
                .unwrap_or_else(|| binary(a, BinOp::Sub(Default::default()), b, 1)),
            Node::Mul(a, b) => binary(a, BinOp::Mul(Default::default()), b, 2),
            Node::Div(a, b) => binary(a, BinOp::Div(Default::default()), b, 2),
            Node::Neg(a) => (ast::neg(operand(a, 3)), 3),
            Node::Sin(a) => (ast::method(operand(a, 4), "sin", None), 4),
            Node::Cos(a) => (ast::method(operand(a, 4), "cos", None), 4),
            Node::Sqrt(a) => (ast::method(operand(a, 4), "sqrt", None), 4),
            Node::Tanh(a) => (ast::method(operand(a, 4), "tanh", None), 4),
            Node::Exp(a) => (ast::method(operand(a, 4), "exp", None), 4),
            Node::Max(a, b) => (ast::method(operand(a, 4), "max", Some(self.expr(b))), 4),
            Node::SignOutside(a, b, c) if self.g.constant_value(c) == Some(0.0) => (
                ast::method(operand(a, 4), "sign_outside", Some(self.expr(b))),
                4,
            ),
            Node::SignOutside(a, b, c) => {
                let args = [self.expr(b), self.expr(c)];
                (ast::method(operand(a, 4), "sign_outside_or", args), 4)
            }
            Node::SelectOutside([a, b, p, m, o]) => {
                let args = [self.expr(b), self.expr(p), self.expr(m), self.expr(o)];
                (ast::method(operand(a, 4), "select_outside", args), 4)
            }
        }
    }

    /// Emits the `let`s needed by `roots`.
    fn bind(&mut self, roots: &[Id]) {
        let g = self.g;
        // The nodes the roots depend on (as `Graph::live`), and how often each is used.
        let mut is_live = vec![false; g.nodes.len()];
        let mut stack = roots.to_vec();
        while let Some(id) = stack.pop() {
            if !std::mem::replace(&mut is_live[id.0 as usize], true) {
                stack.extend(g.node(id).operands());
            }
        }
        let live = || {
            (0..g.nodes.len() as u32)
                .map(Id)
                .filter(|id| is_live[id.0 as usize])
        };
        let mut uses = vec![0usize; g.nodes.len()];
        for id in live() {
            for c in g.node(id).operands() {
                uses[c.0 as usize] += 1;
            }
        }
        for r in roots {
            uses[r.0 as usize] += 2;
        }
        self.bind_turns(&is_live);
        let mut sizes = vec![0usize; g.nodes.len()];
        for id in live() {
            if self.var(id).is_some() {
                continue;
            }
            let node = g.node(id);
            match node {
                Node::Const(_) | Node::Input(_) => continue,
                Node::Sin(a) | Node::Cos(a) => {
                    let (sin, cos) = (g.lookup(Node::Sin(a)), g.lookup(Node::Cos(a)));
                    if let (Some(s), Some(c)) = (sin, cos) {
                        if is_live[s.0 as usize] && is_live[c.0 as usize] {
                            let (sn, cn) = (variable('s', s), variable('c', c));
                            let (arg, p) = self.expr_prec(a);
                            let arg = if p < 4 { ast::paren(arg) } else { arg };
                            let value = ast::method(arg, "sin_cos", None);
                            let mut stmt = ast::let_pair(sn.clone(), cn.clone(), value);
                            if self.batched.contains(&s) {
                                let wide = wide_vectors();
                                ast::only_if(&mut stmt, quote!(not(#wide)));
                            }
                            self.stmts.push(stmt);
                            self.vars[s.0 as usize] = Some(sn);
                            self.vars[c.0 as usize] = Some(cn);
                            continue;
                        }
                    }
                }
                _ => {}
            }
            // Inline size of this node's expression: a node used once is still bound when
            // its expression grows large, which keeps lines readable and emission linear.
            let size = 1 + node
                .operands()
                .filter(|&c| self.var(c).is_none())
                .map(|c| sizes[c.0 as usize])
                .sum::<usize>();
            sizes[id.0 as usize] = size;
            if uses[id.0 as usize] > 1 || size > 12 {
                let name = variable('t', id);
                let value = self.expr(id);
                self.stmts.push(ast::let_one(name.clone(), value));
                self.vars[id.0 as usize] = Some(name);
            }
        }
    }

    /// The sines and cosines of every live angle whose sine and cosine are both used and that
    /// depends on no other sine or cosine (every joint's and pulley's angle, linear in `q`),
    /// four or more, for targets with wide vectors: the angles bound first, then, only where
    /// [`wide_vectors`] holds, all their sines and cosines in one call of
    /// `Real::sin_cos_array`, which an `f64` computes as vector code there
    /// (`tendyn_core::trigonometry`). Elsewhere each pair is computed where it is first needed,
    /// under the opposite `cfg`: without wide vectors the routine takes the angles one at a
    /// time, no faster than the C library, and the batch at the start measured slower on three
    /// of the four scale mechanisms (by up to 18 %, arm6's `Q`).
    fn bind_turns(&mut self, is_live: &[bool]) {
        let g = self.g;
        let live = |id: Id| is_live[id.0 as usize];
        let mut turns = Vec::new();
        for id in (0..g.nodes.len() as u32).map(Id).filter(|&id| live(id)) {
            let Node::Sin(angle) = g.node(id) else {
                continue;
            };
            let cos = g.lookup(Node::Cos(angle)).filter(|&c| live(c));
            if let Some(cos) = cos.filter(|_| self.var(id).is_none() && !self.turns_inside(angle)) {
                turns.push((angle, id, cos));
            }
        }
        // Fewer than four angles fill no vector: each `sin_cos` stays where it is needed
        // (measured: Example 3's two angles in one call cost its `actuation` 15 %); nor has
        // `f32` a vector form.
        if turns.len() < 4 || self.atoms.scalar == Scalar::F32 {
            return;
        }
        let angles: Vec<Id> = turns.iter().map(|t| t.0).collect();
        self.bind(&angles);
        let scalar = match self.atoms.scalar {
            Scalar::Generic => "T",
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
        };
        let args = ast::array(angles.iter().map(|&a| self.expr(a)));
        let value = ast::call(ast::path(&[scalar, "sin_cos_array"]), [args]);
        let names: Vec<(Ident, Ident)> = turns
            .iter()
            .map(|&(_, s, c)| (variable('s', s), variable('c', c)))
            .collect();
        let mut stmt = ast::let_pairs(names, value);
        ast::only_if(&mut stmt, wide_vectors());
        self.stmts.push(stmt);
        self.batched.extend(turns.iter().map(|t| t.1));
    }

    /// Whether `id` depends on a sine or cosine not yet bound (it cannot join the turns
    /// computed before everything else).
    fn turns_inside(&self, id: Id) -> bool {
        let mut stack = vec![id];
        let mut seen = rustc_hash::FxHashSet::default();
        while let Some(x) = stack.pop() {
            if self.var(x).is_some() || !seen.insert(x) {
                continue;
            }
            if matches!(self.g.node(x), Node::Sin(_) | Node::Cos(_)) {
                return true;
            }
            stack.extend(self.g.node(x).operands());
        }
        false
    }
}

/// The `cfg` predicate of targets on which one call for every angle pays: those with
/// 256-bit vectors, as `tendyn_core::trigonometry` decides for its own routine.
fn wide_vectors() -> TokenStream {
    quote!(target_feature = "avx2")
}

/// The flat results of `f` arranged in its shape.
fn shaped(f: &Function, values: Vec<Expr>, core: &syn::Path) -> Expr {
    let mut values = values.into_iter();
    let mut take = |n: usize| ast::array(values.by_ref().take(n));
    match &f.shape {
        Shape::Vector(n) => take(*n),
        Shape::Matrix(n) => ast::array((0..*n).map(|_| take(*n))),
        Shape::Actuation {
            motors,
            tendons,
            status,
        } => {
            let m = take(*motors);
            let t_ = take(*tendons);
            let actuation = quote!(#core::distribution::Actuation);
            match (status, &f.distribution) {
                (StatusFrom::Line, _) => {
                    let (excess, scale) = (values.next(), values.next());
                    parse_quote!(#actuation::along_line(#m, #t_, #excess, #scale))
                }
                // The many-dimensional distribution of the minimal-norm tensions, by the
                // fixed-size routine of tendyn-core.
                (StatusFrom::Solve, Some(dist)) => {
                    let problem = fixed_problem(dist, core);
                    parse_quote!(#actuation::bounded(#m, #t_, &#problem))
                }
                // The same over the state's null space (guides with capstan friction): the
                // basis, target and normals' lengths are traced values.
                (StatusFrom::SolveAtState { directions }, Some(dist)) => {
                    let k = *tendons;
                    let null = ast::array((0..*directions).map(|_| take(k)));
                    let target = take(*directions);
                    let inverse_length = take(k);
                    let (floor, max) = (f64_array(&dist.floor), f64_array(&dist.max));
                    parse_quote!(#actuation::bounded_at_state(#m, #t_, &#core::distribution::AtState {
                        null: #null,
                        floor: #floor,
                        max: #max,
                        target: #target,
                        inverse_length: #inverse_length,
                    }))
                }
                _ => parse_quote!(#actuation::exact(#m, #t_)),
            }
        }
        Shape::Wrenches(n) => ast::array((0..*n).map(|_| {
            let force = take(3);
            ast::array([force, take(3)])
        })),
        Shape::Regression { n, columns } => {
            let y = ast::array((0..*n).map(|_| take(*columns)));
            let offset = take(*n);
            parse_quote!(#core::mechanism::Regression { y: #y, offset: #offset })
        }
        Shape::ActuationJacobians {
            n,
            actuators,
            distributed: StatusFrom::Solve | StatusFrom::SolveAtState { .. },
        } => {
            let values: Vec<Expr> = values.collect();
            let call = distributed_call(f, &values, *n, *actuators, core);
            jacobians_from(f, &values, *n, *actuators, core, call)
        }
        Shape::ActuationJacobians { n, actuators, .. } => {
            let value = take(*actuators);
            let mut jacobian = || ast::array((0..*actuators).map(|_| take(*n)));
            let (d_q, d_qd, d_qdd) = (jacobian(), jacobian(), jacobian());
            parse_quote!(#core::dual::ActuationJacobians { value: #value, d_q: #d_q, d_qd: #d_qd, d_qdd: #d_qdd })
        }
        Shape::Jacobians { n, actuators } => {
            let value = take(*n);
            let d_q = ast::array((0..*n).map(|_| take(*n)));
            let d_qd = ast::array((0..*n).map(|_| take(*n)));
            match actuators {
                None => {
                    parse_quote!(#core::dual::StateJacobians { value: #value, d_q: #d_q, d_qd: #d_qd })
                }
                Some(m) => {
                    let d_u = ast::array((0..*n).map(|_| take(*m)));
                    parse_quote!(#core::dual::ForwardJacobians { value: #value, d_q: #d_q, d_qd: #d_qd, d_u: #d_u })
                }
            }
        }
    }
}

/// `actuation_derivatives` over several null directions (`values` as
/// [`Shape::ActuationJacobians`] lays them out): the minimal-norm tensions and their
/// derivatives along each coordinate, distributed by `Actuation::bounded_with_tangents`
/// (or `bounded_at_state_with_tangents`, with the state's problem and its derivatives):
/// the runtime's routine, which differentiates its optimum on its active set. This is the
/// call, whose value is `(Actuation, tangents)`; [`jacobians_from`] lays it out.
fn distributed_call(
    f: &Function,
    values: &[Expr],
    n: usize,
    actuators: usize,
    core: &syn::Path,
) -> Expr {
    let dist = (f.distribution.as_ref()).expect("a many-dimensional distribution's constants");
    let tendons = dist.floor.len();
    let motors = actuators - tendons;
    let coordinates = 3 * n;
    // Entry (row r, coordinate c) of the Jacobians, as traced.
    let jacobian =
        |r: usize, c: usize| &values[actuators + (c / n) * actuators * n + r * n + c % n];
    let (floor, max) = (f64_array(&dist.floor), f64_array(&dist.max));
    let actuation = quote!(#core::distribution::Actuation);
    let (m, t0) = (&values[..motors], &values[motors..actuators]);
    let t0_tangents = (0..coordinates).map(|c| {
        let cells = (0..tendons).map(|k| jacobian(motors + k, c));
        quote!([#(#cells),*])
    });
    let call = match f.shape {
        Shape::ActuationJacobians {
            distributed: StatusFrom::SolveAtState { directions },
            ..
        } => {
            // The state's problem (its values, then its derivative along each coordinate),
            // in `actuation`'s layout.
            let size = directions * tendons + directions + tendons;
            let first = actuators + 3 * actuators * n;
            // Block 0 is the problem's values, block `c + 1` its derivative along `c`:
            // the basis, target and lengths, as `AtState` and `AtStateTangent` name them.
            let parts = |block: usize| {
                let entry = |i: usize| &values[first + block * size + i];
                let null = (0..directions).map(|d| {
                    let cells = (0..tendons).map(|k| entry(d * tendons + k));
                    quote!([#(#cells),*])
                });
                let target = (0..directions).map(|d| entry(directions * tendons + d));
                let inverse_length =
                    (0..tendons).map(|k| entry(directions * tendons + directions + k));
                quote!(
                    null: [#(#null),*],
                    target: [#(#target),*],
                    inverse_length: [#(#inverse_length),*],
                )
            };
            let values = parts(0);
            let tangents = (1..=coordinates).map(|c| {
                let parts = parts(c);
                quote!(#core::distribution::AtStateTangent { #parts })
            });
            quote!(#actuation::bounded_at_state_with_tangents(
                [#(#m),*],
                [#(#t0),*],
                &[#(#t0_tangents),*],
                &#core::distribution::AtState { #values floor: #floor, max: #max },
                &[#(#tangents),*]
            ))
        }
        _ => {
            let problem = fixed_problem(dist, core);
            quote!(#actuation::bounded_with_tangents(
                [#(#m),*], [#(#t0),*], &[#(#t0_tangents),*], &#problem
            ))
        }
    };
    parse_quote!(#call)
}

/// The `tendyn_core::distribution::Fixed` problem of a constant null space, its facets a
/// promoted constant (`&[Facet { .. }, ..]`).
fn fixed_problem(dist: &crate::outputs::Distribution, core: &syn::Path) -> TokenStream {
    let rows = dist.null.iter().map(|r| f64_array(r));
    let (floor, max, target, inverse_length) = (
        f64_array(&dist.floor),
        f64_array(&dist.max),
        f64_array(&dist.target),
        f64_array(&dist.inverse_length),
    );
    let facets = dist.facets.iter().map(|(normal, support)| {
        let (normal, support) = (f64_array(normal), f64_literal(*support));
        quote!(#core::distribution::Facet { normal: #normal, support: #support })
    });
    quote!(#core::distribution::Fixed {
        null: [#(#rows),*],
        floor: #floor,
        max: #max,
        target: #target,
        inverse_length: #inverse_length,
        facets: &[#(#facets),*],
    })
}

/// `actuation_derivatives` over several null directions from `pair`, the value of
/// [`distributed_call`] (`(Actuation, tangents)`): the motors' rows as traced, the tendons'
/// from the tangents.
fn jacobians_from(
    f: &Function,
    values: &[Expr],
    n: usize,
    actuators: usize,
    core: &syn::Path,
    pair: Expr,
) -> Expr {
    let dist = (f.distribution.as_ref()).expect("a many-dimensional distribution's constants");
    let tendons = dist.floor.len();
    let motors = actuators - tendons;
    let jacobian =
        |r: usize, c: usize| &values[actuators + (c / n) * actuators * n + r * n + c % n];
    let m = &values[..motors];
    let value = m
        .iter()
        .map(|x| quote!(#x))
        .chain((0..tendons).map(|k| quote!(actuation.tendon_tensions[#k])));
    let rows = |block: usize| {
        let rows = (0..actuators).map(|r| {
            let cells = (block * n..(block + 1) * n).map(|c| {
                if r < motors {
                    let x = jacobian(r, c);
                    quote!(#x)
                } else {
                    let k = r - motors;
                    quote!(tangents[#c][#k])
                }
            });
            quote!([#(#cells),*])
        });
        quote!([#(#rows),*])
    };
    let (d_q, d_qd, d_qdd) = (rows(0), rows(1), rows(2));
    parse_quote!({
        let (actuation, tangents) = #pair;
        #core::dual::ActuationJacobians {
            value: [#(#value),*],
            d_q: #d_q,
            d_qd: #d_qd,
            d_qdd: #d_qdd,
        }
    })
}

/// `actuation` and `actuation_derivatives` in `all`, where one call of the distribution
/// serves both ([`one_distribution`]).
struct OneDistribution {
    /// Index of `actuation` among the functions.
    actuation: usize,
    /// Index of `actuation_derivatives`.
    derivatives: usize,
    /// Joints.
    n: usize,
    /// Motors and tendons.
    actuators: usize,
}

/// In `all`: `actuation` and `actuation_derivatives` where both distribute over several
/// null directions the very same tensions within the same problem (their traced arguments
/// the same expressions), so that one call serves both.
fn one_distribution(functions: &[Function], values: &[Vec<Expr>]) -> Option<OneDistribution> {
    let a = functions.iter().position(|f| {
        matches!(
            f.shape,
            Shape::Actuation {
                status: StatusFrom::Solve | StatusFrom::SolveAtState { .. },
                ..
            }
        )
    })?;
    let j = functions.iter().position(|f| {
        matches!(
            f.shape,
            Shape::ActuationJacobians {
                distributed: StatusFrom::Solve | StatusFrom::SolveAtState { .. },
                ..
            }
        )
    })?;
    let (
        Shape::Actuation {
            motors, tendons, ..
        },
        Shape::ActuationJacobians { n, actuators, .. },
    ) = (&functions[a].shape, &functions[j].shape)
    else {
        return None;
    };
    let (n, actuators) = (*n, *actuators);
    // The actuation's arguments: motors, tendons, then the state's problem (if any); the
    // derivatives': motors and tendons, the Jacobians, then the state's problem.
    let state_problem = values[a].len().checked_sub(actuators)?;
    let first = actuators + 3 * actuators * n;
    let tokens = |x: &[Expr]| quote!(#(#x),*).to_string();
    let same = motors + tendons == actuators
        && functions[a].distribution == functions[j].distribution
        && values[j].len() >= first + state_problem
        && tokens(&values[a][..actuators]) == tokens(&values[j][..actuators])
        && tokens(&values[a][actuators..]) == tokens(&values[j][first..first + state_problem]);
    same.then_some(OneDistribution {
        actuation: a,
        derivatives: j,
        n,
        actuators,
    })
}

/// `[x₀, x₁, …]` of `f64` constants written exactly (`f64::INFINITY` for an absent maximum),
/// as the emitted constants outside the expression graph take them.
fn f64_array(values: &[f64]) -> TokenStream {
    let cells = values.iter().map(|&x| f64_literal(x));
    quote!([#(#cells),*])
}

/// An `f64` constant written exactly, as [`f64_array`] writes each.
fn f64_literal(x: f64) -> TokenStream {
    if x == f64::INFINITY {
        return quote!(f64::INFINITY);
    }
    let l = Literal::f64_suffixed(x.abs());
    if x < 0.0 {
        quote!(-#l)
    } else {
        quote!(#l)
    }
}

/// `[elem; len]`
fn array_type(elem: syn::Type, len: usize) -> syn::Type {
    syn::Type::Array(syn::TypeArray {
        attrs: Vec::new(),
        bracket_token: Default::default(),
        elem: Box::new(elem),
        semi_token: Default::default(),
        len: ast::lit(Literal::usize_unsuffixed(len)),
    })
}

/// The type a function of `f`'s shape returns, over the scalar type `t`.
fn return_type(f: &Function, t: &syn::Type, core: &syn::Path) -> syn::Type {
    match &f.shape {
        Shape::Vector(n) => array_type(t.clone(), *n),
        Shape::Matrix(n) => array_type(array_type(t.clone(), *n), *n),
        Shape::Actuation {
            motors, tendons, ..
        } => {
            let (m, k) = (
                array_type(t.clone(), *motors),
                array_type(t.clone(), *tendons),
            );
            parse_quote!(#core::distribution::Actuation<#m, #k>)
        }
        Shape::Wrenches(n) => array_type(array_type(array_type(t.clone(), 3), 2), *n),
        Shape::Regression { n, columns } => {
            let y = array_type(array_type(t.clone(), *columns), *n);
            let v = array_type(t.clone(), *n);
            parse_quote!(#core::mechanism::Regression<#y, #v>)
        }
        Shape::ActuationJacobians { n, actuators, .. } => {
            let v = array_type(t.clone(), *actuators);
            let j = array_type(array_type(t.clone(), *n), *actuators);
            parse_quote!(#core::dual::ActuationJacobians<#v, #j>)
        }
        Shape::Jacobians { n, actuators } => {
            let (v, j) = (
                array_type(t.clone(), *n),
                array_type(array_type(t.clone(), *n), *n),
            );
            match actuators {
                None => parse_quote!(#core::dual::StateJacobians<#v, #j>),
                Some(m) => {
                    let u = array_type(array_type(t.clone(), *m), *n);
                    parse_quote!(#core::dual::ForwardJacobians<#v, #j, #u>)
                }
            }
        }
    }
}

/// The argument `name: &[t; len]`.
fn array_argument(name: &str, t: &syn::Type, len: usize) -> syn::FnArg {
    syn::FnArg::Typed(syn::PatType {
        attrs: Vec::new(),
        pat: Box::new(syn::Pat::Ident(syn::PatIdent {
            attrs: Vec::new(),
            by_ref: None,
            mutability: None,
            ident: ast::ident(name),
            subpat: None,
        })),
        colon_token: Default::default(),
        ty: Box::new(syn::Type::Reference(syn::TypeReference {
            attrs: Vec::new(),
            and_token: Default::default(),
            lifetime: None,
            mutability: None,
            elem: Box::new(array_type(t.clone(), len)),
        })),
    })
}

/// `#[doc = text]`, which prettyplease prints as `///text`.
fn doc_attribute(text: &str) -> syn::Attribute {
    syn::Attribute {
        pound_token: Default::default(),
        style: syn::AttrStyle::Outer,
        bracket_token: Default::default(),
        meta: syn::Meta::NameValue(syn::MetaNameValue {
            path: ast::ident("doc").into(),
            eq_token: Default::default(),
            value: ast::lit(Literal::string(text)),
        }),
    }
}

fn param_len(model: &Model<f64>, p: Param) -> usize {
    match p {
        Param::Q | Param::Qd | Param::Qdd => model.dof(),
        Param::MotorTorques => model.motors().len(),
        Param::TendonTensions => model.tendons().len(),
        Param::Parameters => model.parameters().len(),
    }
}

fn doc(model: &Model<f64>, f: &Function) -> String {
    let labels = result_labels(model, f.output);
    let what = match f.output {
        Output::GeneralizedForces => {
            let (mut term, mut note) = if model.has_friction() {
                (" − Σ_b c_bᵀ τ_f,b".to_string(), "; the last term the bearings' friction".to_string())
            } else {
                (String::new(), String::new())
            };
            if model.capstan_before_an_idler() {
                term.push_str(" + Σ_i W_i (N_i − τ_f,i)");
                note.push_str("; `Σ_i W_i (N_i − τ_f,i)` what the turning idlers behind guides with friction demand through the guides (docs/outputs.md §3)");
            }
            format!("Generalized forces the actuators must deliver, `Q = M(q) q̈ + h(q, q̇) + g(q) − Q_ext{term}` (N·m, per joint{note})")
        }
        Output::Actuation => "Motor torques (N·m, file order), ground-level tendon tensions (N, file order, each within its floor and `max_tension`, the file's distribution objective least) and whether the bounds could be met (`status`)".to_string(),
        Output::MassMatrix => "Joint-space mass matrix `M(q)` (kg·m², pulley inertias included)".to_string(),
        Output::Bias => "Coriolis and centrifugal generalized forces `h(q, q̇)` (N·m)".to_string(),
        Output::Gravity => "Gravity generalized forces `g(q)` (N·m)".to_string(),
        Output::ForwardDynamics => format!(
            "Joint accelerations `q̈` (rad/s²) from motor torques and tendon tensions (file order){}; `M` is factorized by an unrolled `L D Lᵀ` without checks",
            if model.has_friction() { ", the bearings' friction directed by `q̇` alone (none at rest)" } else { "" }
        ),
        Output::SegmentTensions => "Tension of every tendon segment (N), strands in order, each from its anchored end".to_string(),
        Output::Bearings => "Bearing force (N) and moment (N·m) on every body from its parent, moment about the joint point, motor torque excluded; links in their DH frame, pulleys in their housing frame".to_string(),
        Output::BaseReaction => "Total force (N) and moment about the base origin (N·m) of the base on the mechanism, base frame".to_string(),
        Output::Regressor => "The identification regressor: `y[j][c]`, the generalized force on joint `j` per unit of parameter `c` (`tendyn regressor --json` lists them: each body's `m`, `mx`, `my`, `mz`, `xx`, `xy`, `xz`, `yy`, `yz`, `zz` about its frame origin, then `coulomb`, `viscous` where its bearing has friction), and `offset`, the external wrench's part: `Q = y · π + offset`".to_string(),
        Output::GeneralizedForcesDerivatives => format!(
            "`Q` as `generalized_forces` computes it (`value`) with its exact derivatives `d_q[i][k] = ∂Q_i/∂q_k` and `d_qd[i][k] = ∂Q_i/∂q̇_k` (`∂Q/∂q̈` is `M`{}), by dual numbers through the same recursion",
            if model.capstan_before_an_idler() { " plus `Σ_i W_i ∂N_i/∂q̈ᵀ` of the idlers behind guides with friction" } else { "" }
        ),
        Output::ActuationDerivatives => "The motor torques and tendon tensions `actuation` computes (`value`, in its order) with their exact derivatives `d_q[i][k] = ∂value_i/∂q_k`, `d_qd[i][k] = ∂value_i/∂q̇_k` and `d_qdd[i][k] = ∂value_i/∂q̈_k`, by dual numbers through the same recursion and distribution: where a tendon's floor or maximum becomes active or inactive, those of the bounds active at the state (one-sided)".to_string(),
        Output::ForwardDynamicsDerivatives => "`q̈` as `forward_dynamics` computes it (`value`) with its exact derivatives `d_q[i][k] = ∂q̈_i/∂q_k`, `d_qd[i][k] = ∂q̈_i/∂q̇_k` and `d_u[i][k] = ∂q̈_i/∂u_k` (`u`: motor torques, then tendon tensions, file order), by dual numbers through the same recursion".to_string(),
    };
    let joints = labels.join(", ");
    let entries = match f.output {
        Output::GeneralizedForcesDerivatives | Output::ForwardDynamicsDerivatives => {
            format!(
                "`value` and each Jacobian's rows: {joints}; columns of `d_q`, `d_qd`: {joints}"
            ) + &match f.output {
                Output::ForwardDynamicsDerivatives => format!(
                    "; of `d_u`: {}",
                    result_labels(model, Output::Actuation).join(", ")
                ),
                _ => String::new(),
            }
        }
        Output::ActuationDerivatives => format!(
            "`value` and each Jacobian's rows: {}; columns of `d_q`, `d_qd`, `d_qdd`: {joints}",
            result_labels(model, Output::Actuation).join(", ")
        ),
        Output::Regressor => format!(
            "rows of `y` and `offset`: {joints}; columns of `y`: {}",
            tendyn_core::regressor::parameters(model)
                .iter()
                .map(|p| p.name(model))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        _ => joints,
    };
    format!(
        " {what}.\n\n Entries: {entries}.\n\n Operations ({}): {}.",
        f.form.label(),
        f.ops
    )
}

/// Rust source for every traced function, and `all`: the header comments and
/// [`emit_file`]'s tree as prettyplease prints it. `core` is the path by which the emitted
/// file reaches `tendyn-core` (`tendyn_core` for a crate that depends on it,
/// `::tendyn::core` behind the front crate).
pub fn emit(
    model: &Model<f64>,
    traced: &Traced,
    scalar: Scalar,
    source: &str,
    core: &syn::Path,
) -> String {
    let file = emit_file(model, traced, scalar, core);
    header(model, traced, scalar, source) + &prettyplease::unparse(&file)
}

/// The comments that open an emitted file: what generated it from which mechanism and
/// file (`source`), its outputs and scalar.
pub fn header(model: &Model<f64>, traced: &Traced, scalar: Scalar, source: &str) -> String {
    let outputs: Vec<&str> = traced.functions.iter().map(|f| f.output.name()).collect();
    format!(
        "// @generated by tendyn-codegen {} from `{}` ({source}). Do not edit.\n\
         // Outputs: {}. Scalar: {}.\n\n",
        env!("CARGO_PKG_VERSION"),
        model.name(),
        outputs.join(", "),
        match scalar {
            Scalar::Generic => "generic over tendyn_core::Real",
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
        },
    )
}

/// Every traced function and `all`, as one syntax tree.
pub fn emit_file(
    model: &Model<f64>,
    traced: &Traced,
    scalar: Scalar,
    core: &syn::Path,
) -> syn::File {
    let t = scalar.ty();
    let n = model.dof();
    let (nm, nt) = (model.motors().len(), model.tendons().len());
    let a = model.structure_matrix();
    let a_rows = a.iter().map(|row| f64_array(row));
    let (n, nm, nt) = (
        Literal::usize_unsuffixed(n),
        Literal::usize_unsuffixed(nm),
        Literal::usize_unsuffixed(nt),
    );
    let a_doc = " The structure matrix `A` (m): `Q = A T`, rows per joint, columns per open-ended tendon (Eqs. 33, 35).";
    let mut file: syn::File = parse_quote! {
        #[allow(unused_imports)]
        use #core::real::{Numeric, Real};
        #[doc = #a_doc]
        #[allow(dead_code)]
        pub const STRUCTURE_MATRIX: [[f64; #nt]; #n] = [#(#a_rows),*];
        /// Degrees of freedom (joint coordinates `q`).
        #[allow(dead_code)]
        pub const DOF: usize = #n;
        /// Motors, in file order.
        #[allow(dead_code)]
        pub const MOTORS: usize = #nm;
        /// Open-ended tendons, in file order.
        #[allow(dead_code)]
        pub const TENDONS: usize = #nt;
    };
    // The functions' signatures are built as trees, from a parsed template (parsing each
    // function's signature and attributes was a sixth of emission).
    let scalar_type: syn::Type = syn::parse2(t.clone()).expect("a type");
    let params = |params: &[Param]| -> Punctuated<syn::FnArg, syn::Token![,]> {
        params
            .iter()
            .map(|&p| array_argument(p.name(), &scalar_type, param_len(model, p)))
            .collect()
    };
    let template: syn::ItemFn = parse_quote! {
        #[inline]
        #[allow(unused_variables, unused_parens, dead_code, clippy::all)]
        pub fn f() {}
    };
    let generics = |compares: bool| -> syn::Generics {
        let g = bound(scalar, compares);
        parse_quote!(#g)
    };
    let (plain, comparing) = (generics(false), generics(true));
    let function = |docs: Vec<syn::Attribute>,
                    name: &str,
                    compares: bool,
                    inputs: Punctuated<syn::FnArg, syn::Token![,]>,
                    ret: syn::Type| {
        let mut item = template.clone();
        item.attrs = docs.into_iter().chain(template.attrs.clone()).collect();
        item.sig.ident = ast::ident(name);
        item.sig.generics = if compares { &comparing } else { &plain }.clone();
        item.sig.inputs = inputs;
        item.sig.output = syn::ReturnType::Type(Default::default(), Box::new(ret));
        item
    };
    let emitted: Vec<Id> = (traced.functions.iter())
        .flat_map(|f| f.results.iter().copied())
        .chain(traced.all.iter().copied())
        .collect();
    let atoms = Atoms::new(&traced.graph, &emitted, scalar);
    for f in &traced.functions {
        let mut body = Body::new(&atoms);
        body.bind(&f.results);
        let values = f.results.iter().map(|&r| body.expr(r)).collect();
        let d = doc(model, f);
        let mut item = function(
            d.lines().map(doc_attribute).collect(),
            f.output.name(),
            compares(f),
            params(&traced.params(f.output)),
            return_type(f, &scalar_type, core),
        );
        item.block.stmts = body.stmts;
        item.block
            .stmts
            .push(Stmt::Expr(shaped(f, values, core), None));
        file.items.push(syn::Item::Fn(item));
    }
    // `all`: every output, sharing their work.
    // The union of the functions' inputs, in the canonical order of `Param::ALL`.
    let all_params: Vec<Param> = Param::ALL
        .into_iter()
        .filter(|p| {
            traced
                .functions
                .iter()
                .any(|f| traced.params(f.output).contains(p))
        })
        .collect();
    let roots = &traced.all;
    let mut body = Body::new(&atoms);
    body.bind(roots);
    let fields = traced.functions.iter().map(|f| {
        let name = format_ident!("{}", f.output.name());
        let ty = return_type(f, &scalar_type, core);
        let d = format!(" See [`{}`].", f.output.name());
        quote!(#[doc = #d] pub #name: #ty)
    });
    let mut offset = 0;
    let values: Vec<Vec<Expr>> = traced
        .functions
        .iter()
        .map(|f| {
            let values = roots[offset..offset + f.results.len()]
                .iter()
                .map(|&r| body.expr(r))
                .collect();
            offset += f.results.len();
            values
        })
        .collect();
    let mut inits: Vec<(Ident, Expr)> = traced
        .functions
        .iter()
        .zip(&values)
        .map(|(f, values)| (ast::ident(f.output.name()), shaped(f, values.clone(), core)))
        .collect();
    // `actuation` and `actuation_derivatives` over several null directions: one run of the
    // distribution gives both (the tangents' routine returns the value's `Actuation`).
    if let Some(one) = one_distribution(&traced.functions, &values) {
        let (j, n, actuators) = (one.derivatives, one.n, one.actuators);
        let (f, values) = (&traced.functions[j], &values[j]);
        let call = distributed_call(f, values, n, actuators, core);
        body.stmts
            .push(parse_quote!(let actuation_and_tangents = #call;));
        inits[one.actuation].1 = parse_quote!(actuation_and_tangents.0);
        inits[j].1 = jacobians_from(
            f,
            values,
            n,
            actuators,
            core,
            parse_quote!(actuation_and_tangents),
        );
    }
    let count = traced.all_ops;
    let all_doc =
        format!(" Every generated output at once, sharing their common work. Operations: {count}.");
    let struct_generics = match scalar {
        Scalar::Generic => quote!(<T>),
        _ => quote!(),
    };
    let outputs: syn::Item = parse_quote! {
        /// Every requested output of [`all`].
        #[derive(Clone, Copy, Debug)]
        pub struct Outputs #struct_generics {
            #(#fields),*
        }
    };
    let mut all = function(
        vec![doc_attribute(&all_doc)],
        "all",
        traced.functions.iter().any(compares),
        params(&all_params),
        parse_quote!(Outputs #struct_generics),
    );
    all.block.stmts = body.stmts;
    all.block
        .stmts
        .push(Stmt::Expr(ast::struct_literal("Outputs", inits), None));
    file.items.extend([outputs, syn::Item::Fn(all)]);
    file
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::ToTokens;
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

    /// What the command line writes is what the derive expands to: the printed file parses
    /// back to the very tree (every token, parentheses included), for the paper's examples,
    /// a 7-link chain and random mechanisms (coupled pulleys, endless loops), every scalar.
    #[test]
    fn the_printed_file_parses_back_to_the_tree_the_derive_expands_to() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        let mut models: Vec<Model<f64>> = tendyn_spec::examples::all();
        models
            .push(tendyn_core::load(format!("{root}/tendyn-codegen/benches/chain7.ron")).unwrap());
        for seed in 0..4 {
            let features = Features {
                coupled_pulleys: seed % 2 == 0,
                endless: seed % 4 == 1,
            };
            models.push(valid_random_mechanism(seed, features).1);
        }
        let core: syn::Path = parse_quote!(tendyn_core);
        for model in &models {
            let traced = crate::outputs::trace(model, &crate::available_outputs(model)).unwrap();
            for scalar in [Scalar::Generic, Scalar::F64, Scalar::F32] {
                let tree = emit_file(model, &traced, scalar, &core);
                let printed = emit(model, &traced, scalar, "t.ron", &core);
                let parsed = syn::parse_file(&printed).unwrap();
                let tokens = |f: &syn::File| spelled(f.to_token_stream());
                assert_eq!(
                    tokens(&parsed),
                    tokens(&tree),
                    "{} ({scalar:?})",
                    model.name()
                );
            }
        }
    }

    /// The tokens as text, with two differences of spelling only removed: `///` in a
    /// template is `doc = r"…"`, printed and parsed `doc = "…"`; a list broken over lines
    /// gets a trailing comma.
    fn spelled(tokens: proc_macro2::TokenStream) -> String {
        use proc_macro2::TokenTree;
        let trees: Vec<TokenTree> = tokens.into_iter().collect();
        let mut out = String::new();
        for (k, tree) in trees.iter().enumerate() {
            match tree {
                TokenTree::Group(g) => {
                    let (open, close) = match g.delimiter() {
                        proc_macro2::Delimiter::Parenthesis => ("(", ")"),
                        proc_macro2::Delimiter::Bracket => ("[", "]"),
                        proc_macro2::Delimiter::Brace => ("{", "}"),
                        proc_macro2::Delimiter::None => ("", ""),
                    };
                    out += &format!("{open}{}{close} ", spelled(g.stream()));
                }
                TokenTree::Punct(p) if p.as_char() == ',' && k + 1 == trees.len() => {}
                TokenTree::Literal(l) => {
                    let text = l.to_string();
                    match text.strip_prefix("r\"") {
                        Some(raw) => out += &format!("\"{raw} "),
                        None => out += &format!("{text} "),
                    }
                }
                other => out += &format!("{other} "),
            }
        }
        out
    }
}
