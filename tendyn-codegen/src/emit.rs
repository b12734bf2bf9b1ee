//! Graph → Rust source: one straight-line function per requested output and one, `all`,
//! that returns every output sharing their common work; formatted with prettyplease.
//!
//! Every live node the results reach becomes at most one `let` (nodes used once are
//! written inline), in index order, so the code computes exactly the graph; the sine and
//! cosine of one angle are computed together with `sin_cos`. Nothing else is emitted: no
//! loops, no allocation, no panics, no arithmetic on known zeros (those never became nodes).
//! The code is generic over `tendyn_core::Real` unless a concrete scalar is asked for, and
//! needs neither `std` nor `alloc`.
//!
//! The file is what prettyplease prints from one syntax tree. The item skeletons
//! (signatures, constants, the `Outputs` struct) go through `quote!` and `parse_quote!`,
//! and the results of each function are built as `syn` trees; the `let`s, nearly all of
//! the output, are written as text in prettyplease's layout (see `Body` and `layout`):
//! building, printing and dropping their trees was most of the generation time.
//! prettyplease prints a tree as it is, so the tree (and the text) carries exactly the
//! parentheses a parser would have produced from the written code.

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

/// Whether `f` decides a distribution's status (and so compares).
fn compares(f: &Function) -> bool {
    matches!(
        f.shape,
        Shape::Actuation {
            status: StatusFrom::Line | StatusFrom::Solve,
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

    /// `f(arg)`
    pub fn call(func: Expr, arg: Expr) -> Expr {
        Expr::Call(syn::ExprCall {
            attrs: Vec::new(),
            func: Box::new(func),
            paren_token: Default::default(),
            args: Punctuated::from_iter([arg]),
        })
    }

    /// `receiver.method(args)`
    pub fn method(receiver: Expr, method: &str, args: Option<Expr>) -> Expr {
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

/// prettyplease's layout of a long `let`, without building its syntax tree: the tokens
/// prettyplease's printer receives for the few expression forms the bodies use (boxes,
/// breaks and words, see `Body::lay_out`), and its printer (Oppen's algorithm after rustc's
/// `pp`, with its margin of 89 columns), which decides where lines break.
mod layout {
    const MARGIN: isize = 89;
    const INDENT: isize = 4;
    /// Every line may use at least this much, however deep its indentation.
    const MIN_SPACE: isize = 60;
    /// The width of a break that must be taken.
    const HARD: isize = 0xffff;

    #[derive(Clone, Copy, Debug)]
    enum Token {
        /// Words, by byte range in [`Tokens::text`].
        Text(usize, usize),
        /// A place to break: `blank` spaces if not taken; if taken, a new line indented by
        /// the enclosing box's indentation plus `offset`, after a comma if `comma`.
        Break {
            blank: isize,
            offset: isize,
            comma: bool,
            never: bool,
        },
        /// A box: breaks directly in a consistent box are all taken if the box does not
        /// fit on the line; in an inconsistent one, each where the text up to the next
        /// break does not fit.
        Begin {
            offset: isize,
            consistent: bool,
        },
        End,
    }

    /// The token stream of one statement, and where its words are (buffers reused from
    /// statement to statement).
    #[derive(Default)]
    pub struct Tokens {
        text: String,
        tokens: Vec<Token>,
        sizes: Vec<isize>,
        open: Vec<usize>,
    }

    impl Tokens {
        pub fn clear(&mut self) {
            self.text.clear();
            self.tokens.clear();
        }

        pub fn word(&mut self, word: &str) {
            self.word_with(|text| text.push_str(word));
        }

        /// A word written by `write` (appending to the text).
        pub fn word_with(&mut self, write: impl FnOnce(&mut String)) {
            let start = self.text.len();
            write(&mut self.text);
            match self.tokens.last_mut() {
                Some(Token::Text(_, end)) => *end = self.text.len(),
                _ => self.tokens.push(Token::Text(start, self.text.len())),
            }
        }

        fn begin(&mut self, offset: isize, consistent: bool) {
            self.tokens.push(Token::Begin { offset, consistent });
        }

        pub fn ibox(&mut self, offset: isize) {
            self.begin(offset, false);
        }

        pub fn cbox(&mut self, offset: isize) {
            self.begin(offset, true);
        }

        /// Ends a box; a box holding only a break vanishes (prettyplease's `scan_end`).
        pub fn end(&mut self) {
            if let [.., Token::Begin { .. }, Token::Break { .. }] = self.tokens[..] {
                self.tokens.truncate(self.tokens.len() - 2);
            } else {
                self.tokens.push(Token::End);
            }
        }

        fn brk(&mut self, blank: isize, comma: bool, never: bool) {
            self.tokens.push(Token::Break {
                blank,
                offset: 0,
                comma,
                never,
            });
        }

        pub fn zerobreak(&mut self) {
            self.brk(0, false, false);
        }

        pub fn space(&mut self) {
            self.brk(1, false, false);
        }

        pub fn neverbreak(&mut self) {
            self.brk(0, false, true);
        }

        pub fn hardbreak(&mut self) {
            self.brk(HARD, false, false);
        }

        /// A break that writes a comma when taken (after the last argument of a call).
        pub fn trailing_comma(&mut self) {
            self.brk(0, true, false);
        }

        /// Shifts the indentation of the last token if it is a break.
        pub fn offset(&mut self, delta: isize) {
            if let Some(Token::Break { offset, .. }) = self.tokens.last_mut() {
                *offset += delta;
            }
        }

        /// Appends the text of the statement, in a function body (one indentation level).
        pub fn print(&mut self, out: &mut String) {
            self.compute_sizes();
            let sizes = &self.sizes;
            #[derive(Clone, Copy)]
            enum Frame {
                Fits,
                Broken { indent: isize, consistent: bool },
            }
            // The statement sits in the function's block, which is broken.
            let mut stack = vec![Frame::Broken {
                indent: 0,
                consistent: true,
            }];
            let mut indent = INDENT;
            let mut space = MARGIN - INDENT;
            let mut pending = INDENT;
            for (&token, &size) in self.tokens.iter().zip(sizes) {
                match token {
                    Token::Text(start, end) => {
                        out.extend(std::iter::repeat_n(' ', pending as usize));
                        pending = 0;
                        out.push_str(&self.text[start..end]);
                        space -= (end - start) as isize;
                    }
                    Token::Begin { offset, consistent } => {
                        if size > space {
                            stack.push(Frame::Broken { indent, consistent });
                            indent += offset;
                        } else {
                            stack.push(Frame::Fits);
                        }
                    }
                    Token::End => {
                        if let Some(Frame::Broken { indent: outer, .. }) = stack.pop() {
                            indent = outer;
                        }
                    }
                    Token::Break {
                        blank,
                        offset,
                        comma,
                        never,
                    } => {
                        let fits = never
                            || match stack.last().expect("the block's frame") {
                                Frame::Fits => true,
                                Frame::Broken {
                                    consistent: true, ..
                                } => false,
                                Frame::Broken {
                                    consistent: false, ..
                                } => size <= space,
                            };
                        if fits {
                            pending += blank;
                            space -= blank;
                        } else {
                            if comma {
                                out.extend(std::iter::repeat_n(' ', pending as usize));
                                out.push(',');
                            }
                            out.push('\n');
                            pending = indent + offset;
                            space = (MARGIN - pending).max(MIN_SPACE);
                        }
                    }
                }
            }
        }

        /// The size of each token as the printer sees it: a word's length; for a box or a
        /// break, the width from it to the next break outside the box or at the break's
        /// level (breaks counted by their blanks).
        fn compute_sizes(&mut self) {
            let sizes = &mut self.sizes;
            sizes.clear();
            sizes.resize(self.tokens.len(), 0);
            // Tokens whose size is not known yet (prettyplease's `scan_stack`).
            let open = &mut self.open;
            open.clear();
            let tokens = &self.tokens;
            let mut total = 0;
            let settle = |open: &mut Vec<usize>, sizes: &mut Vec<isize>, total: isize| {
                let mut depth = 0;
                while let Some(&i) = open.last() {
                    match tokens[i] {
                        Token::Begin { .. } => {
                            if depth == 0 {
                                break;
                            }
                            open.pop();
                            sizes[i] += total;
                            depth -= 1;
                        }
                        Token::End => {
                            open.pop();
                            sizes[i] = 1;
                            depth += 1;
                        }
                        Token::Break { .. } => {
                            open.pop();
                            sizes[i] += total;
                            if depth == 0 {
                                break;
                            }
                        }
                        Token::Text(..) => unreachable!("words are never open"),
                    }
                }
            };
            for (i, token) in tokens.iter().enumerate() {
                match *token {
                    Token::Text(start, end) => {
                        sizes[i] = (end - start) as isize;
                        total += sizes[i];
                    }
                    Token::Begin { .. } => {
                        sizes[i] = -total;
                        open.push(i);
                    }
                    Token::End => open.push(i),
                    Token::Break { blank, .. } => {
                        settle(open, sizes, total);
                        sizes[i] = -total;
                        open.push(i);
                        total += blank;
                    }
                }
            }
            settle(open, sizes, total);
        }
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
    /// The same, as prettyplease prints them.
    texts: Vec<OnceCell<(String, u8)>>,
}

impl<'g> Atoms<'g> {
    fn new(g: &'g Graph, scalar: Scalar) -> Self {
        Atoms {
            g,
            scalar,
            exprs: vec![OnceCell::new(); g.nodes.len()],
            texts: vec![OnceCell::new(); g.nodes.len()],
        }
    }

    /// The text of [`Atoms::get`]'s expression, and its precedence.
    fn text(&self, id: Id) -> &(String, u8) {
        self.texts[id.0 as usize].get_or_init(|| match self.g.node(id) {
            Node::Const(bits) => {
                let c = f64::from_bits(bits);
                let sign = if c < 0.0 { "-" } else { "" };
                match self.scalar {
                    Scalar::Generic => {
                        let lit = Literal::f64_unsuffixed(c.abs());
                        (format!("T::from_f64({sign}{lit})"), 4)
                    }
                    Scalar::F64 => {
                        let lit = Literal::f64_suffixed(c.abs());
                        (format!("{sign}{lit}"), if c < 0.0 { 3 } else { 4 })
                    }
                    Scalar::F32 => {
                        let lit = Literal::f32_suffixed((c as f32).abs());
                        (format!("{sign}{lit}"), if c < 0.0 { 3 } else { 4 })
                    }
                }
            }
            // Input names are written as the emitted code indexes them: `q[0]`.
            Node::Input(i) => (self.g.input_names[i as usize].clone(), 4),
            _ => unreachable!("only constants and inputs are atoms"),
        })
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
                (ast::call(ast::path(&["T", "from_f64"]), value), 4)
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

/// The variable a node is bound to: `t`, `s` or `c` and the node's number.
#[derive(Clone, Copy)]
struct Name {
    prefix: u8,
    id: u32,
}

impl Name {
    /// Appends the name, digit by digit (`format!` per variable showed in profiles).
    fn push_to(self, out: &mut String) {
        out.push(char::from(self.prefix));
        let mut digits = [0u8; 10];
        let (mut i, mut n) = (digits.len(), self.id);
        loop {
            i -= 1;
            digits[i] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        out.push_str(std::str::from_utf8(&digits[i..]).expect("ASCII digits"));
    }

    fn ident(self) -> Ident {
        let mut name = String::new();
        self.push_to(&mut name);
        ast::ident(&name)
    }
}

/// Writes one function body: `let`s for shared nodes, then the result expression.
///
/// The `let`s are most of the file. Building each as a syntax tree for prettyplease, and
/// dropping it afterwards, took most of the emission time, so they are written as text in
/// prettyplease's layout: a statement that fits on one line as it is (one space around
/// binary operators, nothing else); a longer one, which prettyplease breaks over lines, by
/// [`layout`], which runs prettyplease's printing algorithm on the tokens prettyplease
/// would produce. Only a long `let (s, c) = x.sin_cos();` (none in practice) still goes
/// into the tree; each run of text lines then stands in the tree as a marker statement,
/// [`LETS`], replaced by the text after printing. The file is the one prettyplease prints
/// from the whole tree (a test checks this, statement by statement).
struct Body<'g> {
    g: &'g Graph,
    atoms: &'g Atoms<'g>,
    /// The prefix of the variable bound to each node, by node index (0: none; see
    /// [`Name`]).
    names: Vec<u8>,
    style: Style,
    /// The statements for prettyplease: the long `let`s, and a marker for each run of text.
    stmts: Vec<Stmt>,
    /// The text of each marker, in order.
    runs: Vec<String>,
    /// The run being written.
    run: String,
    /// Scratch space for laying out long `let`s.
    tokens: layout::Tokens,
}

impl<'g> Body<'g> {
    fn new(atoms: &'g Atoms<'g>, style: Style) -> Self {
        Body {
            g: atoms.g,
            atoms,
            names: vec![0; atoms.g.nodes.len()],
            style,
            stmts: Vec::new(),
            runs: Vec::new(),
            run: String::new(),
            tokens: layout::Tokens::default(),
        }
    }

    /// Ends the run of text lines, if any, with its marker.
    fn end_run(&mut self) {
        if !self.run.is_empty() {
            self.stmts.push(marker());
            self.runs.push(std::mem::take(&mut self.run));
        }
    }

    fn name(&self, id: Id) -> Option<Name> {
        match self.names[id.0 as usize] {
            0 => None,
            prefix => Some(Name { prefix, id: id.0 }),
        }
    }

    fn expr(&self, id: Id) -> Expr {
        self.expr_prec(id).0
    }

    /// The precedence of [`Body::expr_prec`]'s expression, without building it.
    fn prec(&self, id: Id) -> u8 {
        if self.name(id).is_some() {
            return 4;
        }
        match self.g.node(id) {
            Node::Const(_) | Node::Input(_) => self.atoms.text(id).1,
            Node::Add(..) | Node::Sub(..) => 1,
            Node::Mul(..) | Node::Div(..) => 2,
            Node::Neg(_) => 3,
            Node::Sin(_)
            | Node::Cos(_)
            | Node::Sqrt(_)
            | Node::Tanh(_)
            | Node::Exp(_)
            | Node::Max(..)
            | Node::SignOutside(..) => 4,
        }
    }

    /// Appends [`Body::expr_prec`]'s expression as prettyplease prints it on one line.
    fn write(&self, id: Id, out: &mut String) {
        if let Some(name) = self.name(id) {
            name.push_to(out);
            return;
        }
        let binary = |a: Id, op: &str, b: Id, p: u8, out: &mut String| {
            self.write_operand(a, p, out);
            out.push_str(op);
            self.write_operand(b, p + 1, out);
        };
        let method = |a: Id, call: &str, out: &mut String| {
            self.write_operand(a, 4, out);
            out.push_str(call);
        };
        match self.g.node(id) {
            Node::Const(_) | Node::Input(_) => out.push_str(&self.atoms.text(id).0),
            Node::Add(a, b) => binary(a, " + ", b, 1, out),
            Node::Sub(a, b) => binary(a, " - ", b, 1, out),
            Node::Mul(a, b) => binary(a, " * ", b, 2, out),
            Node::Div(a, b) => binary(a, " / ", b, 2, out),
            Node::Neg(a) => {
                out.push('-');
                self.write_operand(a, 3, out);
            }
            Node::Sin(a) => method(a, ".sin()", out),
            Node::Cos(a) => method(a, ".cos()", out),
            Node::Sqrt(a) => method(a, ".sqrt()", out),
            Node::Tanh(a) => method(a, ".tanh()", out),
            Node::Exp(a) => method(a, ".exp()", out),
            Node::Max(a, b) => {
                method(a, ".max(", out);
                self.write(b, out);
                out.push(')');
            }
            Node::SignOutside(a, b) => {
                method(a, ".sign_outside(", out);
                self.write(b, out);
                out.push(')');
            }
        }
    }

    /// [`Body::write`], in parentheses if `x` binds less tightly than `min`.
    fn write_operand(&self, x: Id, min: u8, out: &mut String) {
        if self.prec(x) < min {
            out.push('(');
            self.write(x, out);
            out.push(')');
        } else {
            self.write(x, out);
        }
    }

    /// Appends `let <pattern> = <value of id><call>;`: written directly if it fits on one
    /// line, else printed by prettyplease from `stmt`.
    fn push_let(
        &mut self,
        pattern: impl Fn(&mut String),
        id: Id,
        call: &str,
        stmt: impl FnOnce(&Self) -> Stmt,
    ) {
        let start = self.run.len();
        let mut line = std::mem::take(&mut self.run);
        line.push_str("    let ");
        pattern(&mut line);
        line.push_str(" = ");
        if call.is_empty() {
            self.write(id, &mut line);
        } else {
            self.write_operand(id, 4, &mut line);
            line.push_str(call);
        }
        line.push_str(";\n");
        // Lengths in bytes are columns: the code is ASCII.
        let long = line.len() - start - 1 > self.style.one_line;
        if long {
            line.truncate(start);
        }
        if long && self.style.layout && call.is_empty() {
            let mut t = std::mem::take(&mut self.tokens);
            t.clear();
            t.ibox(0);
            t.word("let ");
            t.word_with(&pattern);
            t.word(" = ");
            t.neverbreak();
            self.lay_out(id, &mut t);
            t.end();
            t.word(";");
            t.hardbreak();
            t.print(&mut line);
            self.run = line;
            self.tokens = t;
        } else if long {
            // (`let (s, c) = x.sin_cos();` is never long in practice.)
            self.run = line;
            self.end_run();
            let stmt = stmt(self);
            self.stmts.push(stmt);
        } else {
            self.run = line;
        }
    }

    /// Appends the tokens prettyplease's printer receives for [`Body::expr_prec`]'s
    /// expression (from its `expr_binary`, `expr_unary`, `expr_paren`, `expr_call`,
    /// `call_args`, `expr_method_call`, `prefix_subexpr`): what [`Body::write`] writes, with
    /// the boxes and breaks that decide where long lines break.
    fn lay_out(&self, id: Id, t: &mut layout::Tokens) {
        if let Some(name) = self.name(id) {
            t.word_with(|text| name.push_to(text));
            return;
        }
        let binary = |a: Id, op: &str, b: Id, p: u8, t: &mut layout::Tokens| {
            t.ibox(4);
            t.ibox(-4);
            self.lay_out_operand(a, p, t);
            t.end();
            t.space();
            t.word(op);
            t.word(" ");
            self.lay_out_operand(b, p + 1, t);
            t.end();
        };
        match self.g.node(id) {
            Node::Const(_) => self.lay_out_constant(id, false, t),
            Node::Input(_) => t.word(&self.atoms.text(id).0),
            Node::Add(a, b) => binary(a, "+", b, 1, t),
            Node::Sub(a, b) => binary(a, "-", b, 1, t),
            Node::Mul(a, b) => binary(a, "*", b, 2, t),
            Node::Div(a, b) => binary(a, "/", b, 2, t),
            Node::Neg(a) => {
                t.word("-");
                self.lay_out_operand(a, 3, t);
            }
            Node::Sin(_)
            | Node::Cos(_)
            | Node::Sqrt(_)
            | Node::Tanh(_)
            | Node::Exp(_)
            | Node::Max(..)
            | Node::SignOutside(..) => {
                t.cbox(4);
                self.lay_out_method(id, t);
                t.end();
            }
        }
    }

    /// [`Body::lay_out`], in parentheses if `x` binds less tightly than `min`.
    fn lay_out_operand(&self, x: Id, min: u8, t: &mut layout::Tokens) {
        if self.prec(x) < min {
            t.word("(");
            self.lay_out(x, t);
            t.word(")");
        } else {
            self.lay_out(x, t);
        }
    }

    /// A constant; as the receiver of a method call, `T::from_f64` is boxed alone.
    fn lay_out_constant(&self, id: Id, receiver: bool, t: &mut layout::Tokens) {
        // The atom's text, `T::from_f64(-0.5)` or `-0.5f64`, in its parts.
        let text = self.atoms.text(id).0.as_str();
        let value = text
            .strip_prefix("T::from_f64(")
            .and_then(|v| v.strip_suffix(')'))
            .unwrap_or(text);
        let (sign, literal) = match value.strip_prefix('-') {
            Some(literal) => ("-", literal),
            None => ("", value),
        };
        match self.atoms.scalar {
            Scalar::Generic => {
                if receiver {
                    t.cbox(-4);
                    t.word("T::from_f64");
                    t.end();
                    t.word("(");
                } else {
                    t.word("T::from_f64(");
                }
                t.cbox(4);
                t.zerobreak();
                t.word(sign);
                t.word(literal);
                t.trailing_comma();
                t.offset(-4);
                t.end();
                t.word(")");
            }
            Scalar::F64 | Scalar::F32 => {
                t.word(sign);
                t.word(literal);
            }
        }
    }

    /// A method call on a node's operand, without the box around the whole call (as
    /// prettyplease's `prefix_subexpr_method_call`, which chains calls in one box).
    fn lay_out_method(&self, id: Id, t: &mut layout::Tokens) {
        let (receiver, method, argument) = match self.g.node(id) {
            Node::Sin(a) => (a, "sin", None),
            Node::Cos(a) => (a, "cos", None),
            Node::Sqrt(a) => (a, "sqrt", None),
            Node::Tanh(a) => (a, "tanh", None),
            Node::Exp(a) => (a, "exp", None),
            Node::Max(a, b) => (a, "max", Some(b)),
            Node::SignOutside(a, b) => (a, "sign_outside", Some(b)),
            _ => unreachable!("a method call"),
        };
        // The receiver, as `prefix_subexpr` prints it.
        let chained = self.name(receiver).is_none()
            && matches!(
                self.g.node(receiver),
                Node::Sin(_)
                    | Node::Cos(_)
                    | Node::Sqrt(_)
                    | Node::Tanh(_)
                    | Node::Exp(_)
                    | Node::Max(..)
                    | Node::SignOutside(..)
            );
        let input =
            matches!(self.g.node(receiver), Node::Input(_)) && self.name(receiver).is_none();
        if chained {
            self.lay_out_method(receiver, t);
        } else if input {
            // `q[0]`: the array alone is boxed.
            let text = &self.atoms.text(receiver).0;
            let (array, index) = text.split_once('[').expect("an indexed input");
            t.cbox(-4);
            t.word(array);
            t.end();
            t.word("[");
            t.word(index);
        } else if let (Scalar::Generic, Node::Const(_), true) = (
            self.atoms.scalar,
            self.g.node(receiver),
            self.name(receiver).is_none(),
        ) {
            self.lay_out_constant(receiver, true, t);
        } else {
            t.cbox(-4);
            self.lay_out_operand(receiver, 4, t);
            t.end();
        }
        t.zerobreak();
        t.word(".");
        t.word(method);
        t.cbox(0);
        t.word("(");
        t.cbox(4);
        t.zerobreak();
        if let Some(b) = argument {
            self.lay_out(b, t);
            t.trailing_comma();
        }
        t.offset(-4);
        t.end();
        t.word(")");
        t.end();
    }
    /// The expression of `id` and its precedence (1: `+ -`, 2: `* /`, 3: unary minus,
    /// 4: atoms and method calls). Parentheses are added where the child binds less
    /// tightly, and around a right operand of equal precedence: floating-point addition and
    /// multiplication are not associative, so the emitted grouping must be the graph's.
    fn expr_prec(&self, id: Id) -> (Expr, u8) {
        if let Some(name) = self.name(id) {
            return (ast::var(name.ident()), 4);
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
            Node::Add(a, b) => binary(a, BinOp::Add(Default::default()), b, 1),
            Node::Sub(a, b) => binary(a, BinOp::Sub(Default::default()), b, 1),
            Node::Mul(a, b) => binary(a, BinOp::Mul(Default::default()), b, 2),
            Node::Div(a, b) => binary(a, BinOp::Div(Default::default()), b, 2),
            Node::Neg(a) => (ast::neg(operand(a, 3)), 3),
            Node::Sin(a) => (ast::method(operand(a, 4), "sin", None), 4),
            Node::Cos(a) => (ast::method(operand(a, 4), "cos", None), 4),
            Node::Sqrt(a) => (ast::method(operand(a, 4), "sqrt", None), 4),
            Node::Tanh(a) => (ast::method(operand(a, 4), "tanh", None), 4),
            Node::Exp(a) => (ast::method(operand(a, 4), "exp", None), 4),
            Node::Max(a, b) => (ast::method(operand(a, 4), "max", Some(self.expr(b))), 4),
            Node::SignOutside(a, b) => (
                ast::method(operand(a, 4), "sign_outside", Some(self.expr(b))),
                4,
            ),
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
        let mut sizes = vec![0usize; g.nodes.len()];
        for id in live() {
            if self.name(id).is_some() {
                continue;
            }
            let node = g.node(id);
            match node {
                Node::Const(_) | Node::Input(_) => continue,
                Node::Sin(a) | Node::Cos(a) => {
                    let (sin, cos) = (g.lookup(Node::Sin(a)), g.lookup(Node::Cos(a)));
                    if let (Some(s), Some(c)) = (sin, cos) {
                        if is_live[s.0 as usize] && is_live[c.0 as usize] {
                            let sn = Name {
                                prefix: b's',
                                id: s.0,
                            };
                            let cn = Name {
                                prefix: b'c',
                                id: c.0,
                            };
                            let pattern = |out: &mut String| {
                                out.push('(');
                                sn.push_to(out);
                                out.push_str(", ");
                                cn.push_to(out);
                                out.push(')');
                            };
                            self.push_let(pattern, a, ".sin_cos()", |body| {
                                let (arg, p) = body.expr_prec(a);
                                let arg = if p < 4 { ast::paren(arg) } else { arg };
                                let value = ast::method(arg, "sin_cos", None);
                                ast::let_pair(sn.ident(), cn.ident(), value)
                            });
                            self.names[s.0 as usize] = b's';
                            self.names[c.0 as usize] = b'c';
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
                .filter(|&c| self.name(c).is_none())
                .map(|c| sizes[c.0 as usize])
                .sum::<usize>();
            sizes[id.0 as usize] = size;
            if uses[id.0 as usize] > 1 || size > 12 {
                let name = Name {
                    prefix: b't',
                    id: id.0,
                };
                self.push_let(
                    |out| name.push_to(out),
                    id,
                    "",
                    |body| ast::let_one(name.ident(), body.expr(id)),
                );
                self.names[id.0 as usize] = b't';
            }
        }
    }
}

/// The statement that stands for a run of `let` lines written as text (see [`Body`]).
fn marker() -> Stmt {
    Stmt::Expr(ast::path(&[LETS]), Some(Default::default()))
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
                    let rows = dist.null.iter().map(|r| f64_array(r));
                    let (floor, max, target, inverse_length) = (
                        f64_array(&dist.floor),
                        f64_array(&dist.max),
                        f64_array(&dist.target),
                        f64_array(&dist.inverse_length),
                    );
                    parse_quote!(#actuation::bounded(#m, #t_, &#core::distribution::Fixed {
                        null: [#(#rows),*],
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
    }
}

/// `[x₀, x₁, …]` of `f64` constants written exactly (`f64::INFINITY` for an absent maximum),
/// as the emitted constants outside the expression graph take them.
fn f64_array(values: &[f64]) -> TokenStream {
    let cells = values.iter().map(|&x| {
        if x == f64::INFINITY {
            return quote!(f64::INFINITY);
        }
        let l = Literal::f64_suffixed(x.abs());
        if x < 0.0 {
            quote!(-#l)
        } else {
            quote!(#l)
        }
    });
    quote!([#(#cells),*])
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

fn doc(model: &Model<f64>, f: &Function, chosen: &str) -> String {
    let labels = result_labels(model, f.output);
    let what = match f.output {
        Output::GeneralizedForces => {
            let (term, note) = if model.has_friction() {
                (" − Σ_b c_bᵀ τ_f,b", "; the last term the bearings' friction")
            } else {
                ("", "")
            };
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
    };
    format!(
        " {what}.\n\n Entries: {}.\n\n Operations ({chosen}): {}.",
        labels.join(", "),
        if chosen == "closed form" {
            f.closed_ops.expect("closed")
        } else {
            f.traced_ops
        }
    )
}

/// Rust source for every traced function, and `all`. `core` is the path by which the
/// emitted file reaches `tendyn-core` (`tendyn_core` for a crate that depends on it,
/// `::tendyn::core` behind the front crate).
pub fn emit(
    model: &Model<f64>,
    traced: &Traced,
    scalar: Scalar,
    source: &str,
    core: &syn::Path,
) -> String {
    emit_with(model, traced, scalar, source, core, DIRECT)
}

/// How the `let`s are written (see [`Body`]).
#[derive(Clone, Copy, Debug)]
struct Style {
    /// Longest `let` line (indentation included) written as text directly.
    one_line: usize,
    /// Longer `let`s of one variable are laid out by [`layout`] rather than printed by
    /// prettyplease from a tree.
    layout: bool,
}

/// The fast style. Every style gives the same file (a test checks it).
const DIRECT: Style = Style {
    one_line: ONE_LINE,
    layout: true,
};

/// Longest `let` line written without prettyplease. prettyplease keeps a statement on one
/// line when it fits in its margin of 89 columns; the test
/// `direct_lets_are_what_prettyplease_prints` checks this bound on every statement of
/// several mechanisms and scalars.
const ONE_LINE: usize = 89;

/// The marker statement of a run of `let` lines written as text (see [`Body`]).
const LETS: &str = "__tendyn_lets";

/// [`emit`] in a given style: every style gives the same file, byte for byte; with
/// `one_line: 0` and no layout, prettyplease prints everything (the reference in tests).
fn emit_with(
    model: &Model<f64>,
    traced: &Traced,
    scalar: Scalar,
    source: &str,
    core: &syn::Path,
    style: Style,
) -> String {
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
    let atoms = Atoms::new(&traced.graph, scalar);
    // The text of every marker, in file order.
    let mut runs = Vec::new();
    for f in &traced.functions {
        let mut body = Body::new(&atoms, style);
        body.bind(&f.results);
        let values = f.results.iter().map(|&r| body.expr(r)).collect();
        let closed = f
            .closed_ops
            .is_some_and(|c| c.arithmetic() < f.traced_ops.arithmetic());
        let d = doc(
            model,
            f,
            if closed {
                "closed form"
            } else {
                "traced recursion"
            },
        );
        let mut item = function(
            d.lines().map(doc_attribute).collect(),
            f.output.name(),
            compares(f),
            params(&traced.params(f.output)),
            return_type(f, &scalar_type, core),
        );
        body.end_run();
        runs.append(&mut body.runs);
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
    let mut body = Body::new(&atoms, style);
    body.bind(roots);
    let fields = traced.functions.iter().map(|f| {
        let name = format_ident!("{}", f.output.name());
        let ty = return_type(f, &scalar_type, core);
        let d = format!(" See [`{}`].", f.output.name());
        quote!(#[doc = #d] pub #name: #ty)
    });
    let mut offset = 0;
    let inits: Vec<(Ident, Expr)> = traced
        .functions
        .iter()
        .map(|f| {
            let values = roots[offset..offset + f.results.len()]
                .iter()
                .map(|&r| body.expr(r))
                .collect();
            offset += f.results.len();
            (ast::ident(f.output.name()), shaped(f, values, core))
        })
        .collect();
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
    body.end_run();
    runs.append(&mut body.runs);
    all.block.stmts = body.stmts;
    all.block
        .stmts
        .push(Stmt::Expr(ast::struct_literal("Outputs", inits), None));
    file.items.extend([outputs, syn::Item::Fn(all)]);
    let skeleton = prettyplease::unparse(&file);
    let pieces: Vec<&str> = skeleton.split(&format!("    {LETS};\n")).collect();
    assert_eq!(pieces.len(), runs.len() + 1, "one marker per run of text");
    let mut pretty =
        String::with_capacity(skeleton.len() + runs.iter().map(String::len).sum::<usize>());
    pretty.push_str(pieces[0]);
    for (run, piece) in runs.iter().zip(&pieces[1..]) {
        pretty.push_str(run);
        pretty.push_str(piece);
    }
    let outputs: Vec<&str> = traced.functions.iter().map(|f| f.output.name()).collect();
    format!(
        "// @generated by tendyn-codegen {} from `{}` ({source}). Do not edit.\n\
         // Outputs: {}. Scalar: {}.\n\n{}",
        env!("CARGO_PKG_VERSION"),
        model.name(),
        outputs.join(", "),
        match scalar {
            Scalar::Generic => "generic over tendyn_core::Real",
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
        },
        pretty
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};

    /// The direct text of the `let`s is what prettyplease prints from their trees: every
    /// output of the paper's examples, a 7-link chain and random mechanisms (coupled
    /// pulleys, endless loops), in every scalar; statements of all lengths, around the
    /// one-line bound too.
    #[test]
    fn direct_lets_are_what_prettyplease_prints() {
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
        let mut near_bound = 0;
        for model in &models {
            let traced = crate::outputs::trace(model, &crate::available_outputs(model)).unwrap();
            for scalar in [Scalar::Generic, Scalar::F64, Scalar::F32] {
                let emit = |style| emit_with(model, &traced, scalar, "t.ron", &core, style);
                let reference = emit(Style {
                    one_line: 0,
                    layout: false,
                });
                let laid_out = Style {
                    one_line: 0,
                    layout: true,
                };
                let direct = emit(DIRECT);
                for (style, text) in [(DIRECT, &direct), (laid_out, &emit(laid_out))] {
                    if let Some((k, (a, b))) = text
                        .lines()
                        .zip(reference.lines())
                        .enumerate()
                        .find(|(_, (a, b))| a != b)
                    {
                        panic!(
                            "{} ({scalar:?}, {style:?}), line {}:\n  direct:       {a}\n  prettyplease: {b}",
                            model.name(),
                            k + 1
                        );
                    }
                    assert_eq!(text, &reference, "{}", model.name());
                }
                near_bound += direct
                    .lines()
                    .filter(|l| (ONE_LINE - 3..=ONE_LINE + 3).contains(&l.len()))
                    .count();
            }
        }
        assert!(near_bound > 20, "few lines near the bound: {near_bound}");
    }
}
