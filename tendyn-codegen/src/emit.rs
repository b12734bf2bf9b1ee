//! Graph → Rust source: one straight-line function per requested output and one, `all`,
//! that returns every output sharing their common work; formatted with prettyplease.
//!
//! Every live node the results reach becomes at most one `let` (nodes used once are
//! written inline), in index order, so the code computes exactly the graph; the sine and
//! cosine of one angle are computed together with `sin_cos`. Nothing else is emitted: no
//! loops, no allocation, no panics, no arithmetic on known zeros (those never became nodes).
//! The code is generic over `tendyn_core::Real` unless a concrete scalar is asked for, and
//! needs neither `std` nor `alloc`.

use crate::expr::{Graph, Id, Node};
use crate::outputs::{result_labels, Function, Output, Param, Shape, Traced};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::{BTreeMap, BTreeSet};
use tendyn_core::Model;

/// The scalar type of the emitted functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    /// Generic over `T: tendyn_core::Real`.
    Generic,
    F64,
    F32,
}

impl Scalar {
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

/// Writes one function body: `let`s for shared nodes, then the result expression.
struct Body<'g> {
    g: &'g Graph,
    scalar: Scalar,
    names: BTreeMap<Id, TokenStream>,
    stmts: Vec<TokenStream>,
}

impl Body<'_> {
    fn constant(&self, c: f64) -> TokenStream {
        let lit = match self.scalar {
            Scalar::F32 => Literal::f32_unsuffixed((c as f32).abs()),
            _ => Literal::f64_unsuffixed(c.abs()),
        };
        let lit = if c < 0.0 { quote!(-#lit) } else { quote!(#lit) };
        match self.scalar {
            Scalar::Generic => quote!(T::from_f64(#lit)),
            Scalar::F64 => {
                let lit = Literal::f64_suffixed(c.abs());
                if c < 0.0 {
                    quote!(-#lit)
                } else {
                    quote!(#lit)
                }
            }
            Scalar::F32 => {
                let lit = Literal::f32_suffixed((c as f32).abs());
                if c < 0.0 {
                    quote!(-#lit)
                } else {
                    quote!(#lit)
                }
            }
        }
    }

    fn expr(&self, id: Id) -> TokenStream {
        self.expr_prec(id).0
    }

    /// The expression of `id` and its precedence (1: `+ -`, 2: `* /`, 3: unary minus,
    /// 4: atoms and method calls). Parentheses are added where the child binds less
    /// tightly, and around a right operand of equal precedence: floating-point addition and
    /// multiplication are not associative, so the emitted grouping must be the graph's.
    fn expr_prec(&self, id: Id) -> (TokenStream, u8) {
        if let Some(name) = self.names.get(&id) {
            return (name.clone(), 4);
        }
        let operand = |x: Id, min: u8| {
            let (t, p) = self.expr_prec(x);
            if p < min {
                quote!((#t))
            } else {
                t
            }
        };
        match self.g.node(id) {
            Node::Const(bits) => {
                let c = f64::from_bits(bits);
                (
                    self.constant(c),
                    if c < 0.0 && self.scalar != Scalar::Generic {
                        3
                    } else {
                        4
                    },
                )
            }
            Node::Input(i) => {
                let name = &self.g.input_names[i as usize];
                let (array, index) = name.split_once('[').expect("inputs are array elements");
                let array = format_ident!("{array}");
                let index: usize = index.trim_end_matches(']').parse().expect("an index");
                let index = Literal::usize_unsuffixed(index);
                (quote!(#array[#index]), 4)
            }
            Node::Add(a, b) => {
                let (a, b) = (operand(a, 1), operand(b, 2));
                (quote!(#a + #b), 1)
            }
            Node::Sub(a, b) => {
                let (a, b) = (operand(a, 1), operand(b, 2));
                (quote!(#a - #b), 1)
            }
            Node::Mul(a, b) => {
                let (a, b) = (operand(a, 2), operand(b, 3));
                (quote!(#a * #b), 2)
            }
            Node::Div(a, b) => {
                let (a, b) = (operand(a, 2), operand(b, 3));
                (quote!(#a / #b), 2)
            }
            Node::Neg(a) => {
                let a = operand(a, 3);
                (quote!(-#a), 3)
            }
            Node::Sin(a) => {
                let a = operand(a, 4);
                (quote!(#a.sin()), 4)
            }
            Node::Cos(a) => {
                let a = operand(a, 4);
                (quote!(#a.cos()), 4)
            }
            Node::Sqrt(a) => {
                let a = operand(a, 4);
                (quote!(#a.sqrt()), 4)
            }
            Node::Max(a, b) => {
                let (a, b) = (operand(a, 4), self.expr(b));
                (quote!(#a.max(#b)), 4)
            }
        }
    }

    /// Emits the `let`s needed by `roots`.
    fn bind(&mut self, roots: &[Id]) {
        let live = self.g.live(roots);
        let mut uses: BTreeMap<Id, usize> = BTreeMap::new();
        for &id in &live {
            for c in self.g.node(id).children() {
                *uses.entry(c).or_default() += 1;
            }
        }
        for r in roots {
            *uses.entry(*r).or_default() += 2;
        }
        let live_set: BTreeSet<Id> = live.iter().copied().collect();
        let mut sizes: BTreeMap<Id, usize> = BTreeMap::new();
        for &id in &live {
            if self.names.contains_key(&id) {
                continue;
            }
            let node = self.g.node(id);
            match node {
                Node::Const(_) | Node::Input(_) => continue,
                Node::Sin(a) | Node::Cos(a) => {
                    let (sin, cos) = (self.g.lookup(Node::Sin(a)), self.g.lookup(Node::Cos(a)));
                    if let (Some(s), Some(c)) = (sin, cos) {
                        if live_set.contains(&s) && live_set.contains(&c) {
                            let (arg, p) = self.expr_prec(a);
                            let arg = if p < 4 { quote!((#arg)) } else { arg };
                            let (sn, cn) = (format_ident!("s{}", s.0), format_ident!("c{}", c.0));
                            self.stmts.push(quote!(let (#sn, #cn) = #arg.sin_cos();));
                            self.names.insert(s, quote!(#sn));
                            self.names.insert(c, quote!(#cn));
                            continue;
                        }
                    }
                }
                _ => {}
            }
            // Inline size of this node's expression: a node used once is still bound when
            // its expression grows large, which keeps lines readable and emission linear.
            let size = 1 + node
                .children()
                .iter()
                .filter(|c| !self.names.contains_key(c))
                .map(|c| sizes.get(c).copied().unwrap_or(0))
                .sum::<usize>();
            sizes.insert(id, size);
            if uses.get(&id).copied().unwrap_or(0) > 1 || size > 12 {
                let value = self.expr(id);
                let name = format_ident!("t{}", id.0);
                self.stmts.push(quote!(let #name = #value;));
                self.names.insert(id, quote!(#name));
            }
        }
    }
}

fn shaped(f: &Function, values: &[TokenStream]) -> TokenStream {
    match &f.shape {
        Shape::Vector(_) => quote!([#(#values),*]),
        Shape::Matrix(n) => {
            let rows = values.chunks(*n).map(|r| quote!([#(#r),*]));
            quote!([#(#rows),*])
        }
        Shape::Actuation { motors, .. } => {
            let (m, t) = values.split_at(*motors);
            quote!(([#(#m),*], [#(#t),*]))
        }
        Shape::Wrenches(_) => {
            let w = values.chunks(6).map(|c| {
                let (f, n) = c.split_at(3);
                quote!([[#(#f),*], [#(#n),*]])
            });
            quote!([#(#w),*])
        }
    }
}

fn return_type(f: &Function, t: &TokenStream) -> TokenStream {
    match &f.shape {
        Shape::Vector(n) => {
            let n = Literal::usize_unsuffixed(*n);
            quote!([#t; #n])
        }
        Shape::Matrix(n) => {
            let n = Literal::usize_unsuffixed(*n);
            quote!([[#t; #n]; #n])
        }
        Shape::Actuation { motors, tendons } => {
            let (m, k) = (
                Literal::usize_unsuffixed(*motors),
                Literal::usize_unsuffixed(*tendons),
            );
            quote!(([#t; #m], [#t; #k]))
        }
        Shape::Wrenches(n) => {
            let n = Literal::usize_unsuffixed(*n);
            quote!([[[#t; 3]; 2]; #n])
        }
    }
}

fn param_len(model: &Model<f64>, p: Param) -> usize {
    match p {
        Param::Q | Param::Qd | Param::Qdd => model.dof,
        Param::MotorTorques => model.motors.len(),
        Param::TendonTensions => model.tendons.len(),
    }
}

fn doc(model: &Model<f64>, f: &Function, chosen: &str) -> String {
    let labels = result_labels(model, f.output);
    let what = match f.output {
        Output::GeneralizedForces => "Generalized forces the actuators must deliver, `Q = M(q) q̈ + h(q, q̇) + g(q) − Q_ext` (N·m, per joint)".to_string(),
        Output::Actuation => "Motor torques (N·m, file order) and ground-level tendon tensions (N, file order, every one at or above its floor, least norm)".to_string(),
        Output::MassMatrix => "Joint-space mass matrix `M(q)` (kg·m², pulley inertias included)".to_string(),
        Output::Bias => "Coriolis and centrifugal generalized forces `h(q, q̇)` (N·m)".to_string(),
        Output::Gravity => "Gravity generalized forces `g(q)` (N·m)".to_string(),
        Output::ForwardDynamics => "Joint accelerations `q̈` (rad/s²) from motor torques and tendon tensions (file order); `M` is factorized by an unrolled `L D Lᵀ` without checks".to_string(),
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

/// Rust source for every traced function, and `all`.
pub fn emit(model: &Model<f64>, traced: &Traced, scalar: Scalar, source: &str) -> String {
    let t = scalar.ty();
    let generics = scalar.generics();
    let mut items = Vec::new();
    let n = model.dof;
    let (nm, nt) = (model.motors.len(), model.tendons.len());
    let a = model.structure_matrix();
    let a_rows = a.iter().map(|row| {
        let cells = row.iter().map(|&x| {
            let lit = Literal::f64_suffixed(x.abs());
            if x < 0.0 {
                quote!(-#lit)
            } else {
                quote!(#lit)
            }
        });
        quote!([#(#cells),*])
    });
    let (n, nm, nt) = (
        Literal::usize_unsuffixed(n),
        Literal::usize_unsuffixed(nm),
        Literal::usize_unsuffixed(nt),
    );
    let a_doc = " The structure matrix `A` (m): `Q = A T`, rows per joint, columns per open-ended tendon (Eqs. 33, 35).";
    items.push(quote! {
        #[doc = #a_doc]
        pub const STRUCTURE_MATRIX: [[f64; #nt]; #n] = [#(#a_rows),*];
    });
    items.push(quote! {
        /// Degrees of freedom (joint coordinates `q`).
        pub const DOF: usize = #n;
        /// Motors, in file order.
        pub const MOTORS: usize = #nm;
        /// Open-ended tendons, in file order.
        pub const TENDONS: usize = #nt;
    });
    for f in &traced.functions {
        let mut body = Body {
            g: &traced.graph,
            scalar,
            names: BTreeMap::new(),
            stmts: Vec::new(),
        };
        body.bind(&f.results);
        let values: Vec<TokenStream> = f.results.iter().map(|&r| body.expr(r)).collect();
        let ret = return_type(f, &t);
        let result = shaped(f, &values);
        let name = format_ident!("{}", f.output.name());
        let params = f.output.params().iter().map(|&p| {
            let pn = format_ident!("{}", p.name());
            let len = Literal::usize_unsuffixed(param_len(model, p));
            quote!(#pn: &[#t; #len])
        });
        let stmts = &body.stmts;
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
        let d = d.lines().map(|l| quote!(#[doc = #l]));
        items.push(quote! {
            #(#d)*
            #[inline]
            #[allow(unused_variables, unused_parens, clippy::all)]
            pub fn #name #generics (#(#params),*) -> #ret {
                #(#stmts)*
                #result
            }
        });
    }
    // `all`: every output, sharing their work.
    let mut params: Vec<Param> = Vec::new();
    for f in &traced.functions {
        for &p in f.output.params() {
            if !params.contains(&p) {
                params.push(p);
            }
        }
    }
    let roots: Vec<Id> = traced
        .functions
        .iter()
        .flat_map(|f| f.results.iter().copied())
        .collect();
    let mut body = Body {
        g: &traced.graph,
        scalar,
        names: BTreeMap::new(),
        stmts: Vec::new(),
    };
    body.bind(&roots);
    let fields = traced.functions.iter().map(|f| {
        let name = format_ident!("{}", f.output.name());
        let ty = return_type(f, &t);
        let d = format!(" See [`{}`].", f.output.name());
        quote!(#[doc = #d] pub #name: #ty)
    });
    let mut offset = 0;
    let inits = traced.functions.iter().map(|f| {
        let name = format_ident!("{}", f.output.name());
        let values: Vec<TokenStream> = roots[offset..offset + f.results.len()]
            .iter()
            .map(|&r| body.expr(r))
            .collect();
        offset += f.results.len();
        let v = shaped(f, &values);
        quote!(#name: #v)
    });
    let stmts = &body.stmts;
    let param_tokens = params.iter().map(|&p| {
        let pn = format_ident!("{}", p.name());
        let len = Literal::usize_unsuffixed(param_len(model, p));
        quote!(#pn: &[#t; #len])
    });
    let count = traced.graph.count(&roots);
    let all_doc =
        format!(" Every generated output at once, sharing their common work. Operations: {count}.");
    let struct_generics = match scalar {
        Scalar::Generic => quote!(<T>),
        _ => quote!(),
    };
    items.push(quote! {
        /// Every requested output of [`all`].
        #[derive(Clone, Copy, Debug)]
        pub struct Outputs #struct_generics {
            #(#fields),*
        }
        #[doc = #all_doc]
        #[inline]
        #[allow(unused_variables, unused_parens, clippy::all)]
        pub fn all #generics (#(#param_tokens),*) -> Outputs #struct_generics {
            #(#stmts)*
            Outputs { #(#inits),* }
        }
    });
    let file = quote! {
        #[allow(unused_imports)]
        use tendyn_core::real::Real;
        #(#items)*
    };
    let parsed: syn::File = syn::parse2(file).expect("emitted code parses");
    let pretty = prettyplease::unparse(&parsed);
    let outputs: Vec<&str> = traced.functions.iter().map(|f| f.output.name()).collect();
    format!(
        "// @generated by tendyn-codegen {} from `{}` ({source}). Do not edit.\n\
         // Outputs: {}. Scalar: {}.\n\n{}",
        env!("CARGO_PKG_VERSION"),
        model.name,
        outputs.join(", "),
        match scalar {
            Scalar::Generic => "generic over tendyn_core::Real",
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
        },
        pretty
    )
}
