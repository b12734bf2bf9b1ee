//! `#[derive(TendonMechanism)]`: the closed-form dynamics of a tendon-driven mechanism,
//! generated from its RON file at compile time. Use it through the front crate `tendyn`.
//!
//! ```ignore
//! #[derive(tendyn::TendonMechanism)]
//! #[tendyn(file = "mechanisms/finger.ron", outputs(generalized_forces, actuation), scalar = f64)]
//! struct Finger { m3: f64, g: f64 } // the runtime parameters of finger.ron
//! ```
//!
//! The attribute:
//! - `file = "path"`: the mechanism, relative to the crate's manifest directory (editing
//!   it rebuilds the crate); or `ron = "..."`: the mechanism inline;
//! - `outputs(...)`: the functions to generate: `generalized_forces`, `actuation`,
//!   `mass_matrix`, `bias`, `gravity`, `forward_dynamics`, `segment_tensions`, `bearings`,
//!   `base_reaction` (by default each of these the mechanism can provide), and only when
//!   named `generalized_forces_derivatives`, `forward_dynamics_derivatives`,
//!   `actuation_derivatives` and `regressor`;
//! - `scalar = f64` (default) or `f32`;
//! - `crate = "path"`: where the front crate is (default `::tendyn`).
//!
//! The struct's fields are the mechanism's runtime parameters, one field per declared
//! parameter, of the scalar type. The expansion is a hidden module with the code
//! `tendyn-codegen` emits, inherent methods (one per output, plus `all`) that pass the
//! fields as the parameters, and an implementation of `tendyn::TendonMechanism`.
//!
//! Every problem becomes a compile error at the attribute: an unreadable file, a RON
//! syntax error or an invalid mechanism (quoting the file, line and column of the item),
//! an output the mechanism cannot provide, an unknown output or scalar, or fields that do
//! not match the declared parameters (naming both sides). Beside the error the expansion
//! still declares the methods and the trait with the shapes the file gives (bodies that
//! never run), so that the located error is the only one: no "no method named …" at every
//! call site.
//!
//! For tests run through `trybuild`, whose crates live in a scratch directory, the
//! environment variable `TENDYN_MANIFEST_DIR` replaces `CARGO_MANIFEST_DIR` as the base of
//! relative paths.
//!
//! The full reference (every key, the fields, the expansion, the errors) is the derive's
//! own documentation, `TendonMechanism`.
#![warn(missing_docs)]

use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote, quote_spanned};
use syn::punctuated::Punctuated;
use syn::spanned::Spanned;
use syn::{parse_macro_input, DeriveInput, Ident, LitStr, Token};
use tendyn_codegen::outputs::Param;
use tendyn_codegen::{Options, Output, Scalar};

/// `#[derive(TendonMechanism)]`: the dynamics of a tendon-driven mechanism, generated from
/// its RON file at compile time as straight-line, allocation-free methods of the struct. Use it through the front crate `tendyn` (it re-exports `tendyn-core` as
/// `tendyn::core` and this derive as `tendyn::TendonMechanism`).
///
/// ```ignore
/// use tendyn::TendonMechanism;
///
/// #[derive(TendonMechanism)]
/// #[tendyn(file = "mechanisms/finger.ron", outputs(generalized_forces, actuation), scalar = f64)]
/// struct Finger { m3: f64, g: f64 } // one field per runtime parameter, by name, any order
///
/// let finger = Finger { m3: 0.02, g: -9.81 };
/// let (q, qd, qdd) = ([0.1, 0.5, 0.3], [0.0; 3], [1.0, 0.0, 0.0]); // rad, rad/s, rad/s²
/// let forces = finger.generalized_forces(&q, &qd, &qdd); // [f64; 3], N·m
/// let actuation = finger.actuation(&q, &qd, &qdd); // motor torques, tendon tensions, status
/// ```
///
/// # The attribute `#[tendyn(...)]`
///
/// Required. Keys, comma-separated:
///
/// | Key | Meaning |
/// |---|---|
/// | `file = "path"` | The mechanism file, relative to the crate's manifest directory. The expansion embeds it with `include_bytes!`, so editing it rebuilds the crate. |
/// | `ron = "..."` | The mechanism inline (a raw string `r#"..."#` is convenient). Exactly one of `file` and `ron`. |
/// | `outputs(a, b, ...)` | The functions to generate, by name: `generalized_forces`, `actuation`, `mass_matrix`, `bias`, `gravity`, `forward_dynamics`, `segment_tensions`, `bearings`, `base_reaction`, the derivatives `generalized_forces_derivatives`, `forward_dynamics_derivatives`, `actuation_derivatives` and the identification `regressor` (these four as inherent methods only; not in the trait). Default: every output the mechanism can provide, less those four. |
/// | `scalar = f64` or `scalar = f32` | The type of every input, output and field. Default `f64`. (The derive always generates concrete code; there is no generic scalar.) |
/// | `crate = "path"` | Where the front crate is, default `::tendyn`: the expansion implements `<path>::TendonMechanism`, and the generated code reaches `<path>::core`. |
///
/// # The struct
///
/// A struct without generic parameters whose fields are the mechanism's runtime
/// parameters (the file's `parameters`): named fields, exactly one per declared
/// parameter, matched by name in any order, each of the scalar type, and no other
/// fields. A mechanism without parameters takes a unit struct (`struct Finger;`). The
/// methods pass the fields to the generated code as its `params`, in the order the file
/// declares them.
///
/// # What the expansion contains
///
/// For `struct Finger`:
/// - a hidden module `__tendyn_finger` with the code `tendyn-codegen` emits for the
///   requested outputs at the chosen scalar (`docs/generated-code.md` §3): its constants,
///   functions, `Outputs` and `all`;
/// - inherent methods, one per requested output plus `all`, e.g.
///   `Finger::generalized_forces(&self, q, qd, qdd) -> [f64; 3]`: the generated
///   functions' signatures and doc comments, without `params` (the fields are passed);
/// - `impl tendyn::TendonMechanism for Finger`: the constants `NAME`, `DOF`, `MOTORS`,
///   `TENDONS`, `JOINT_NAMES`, `MOTOR_NAMES`, `TENDON_NAMES`, `PARAMETER_NAMES`,
///   `OUTPUTS`, `STRUCTURE_MATRIX`; the associated types `Scalar`, `Joints = [S; n]`,
///   `Motors = [S; M]`, `Tendons = [S; K]`, `MassMatrix = [[S; n]; n]`, `Segments`,
///   `Bearings`, `BaseReaction` (`()` when not generated); and the nine output methods,
///   which return `Some` for the requested outputs and `None` for the others.
///
/// The inherent methods take precedence in method-call syntax, so `finger.actuation(..)`
/// needs no `unwrap`; generic code uses the trait.
///
/// # Errors
///
/// Every problem is a compile error spanned at the part of the attribute (or of the
/// struct) at fault:
///
/// | Problem | Message (span) |
/// |---|---|
/// | no `#[tendyn(...)]` | ``missing `#[tendyn(file = "mechanism.ron")]`: ...`` (the struct's name) |
/// | neither `file` nor `ron` | `missing the mechanism: add ...` (the struct's name) |
/// | both, or one twice | `` give the mechanism once: `file = "..."` or `ron = "..."` `` (the second) |
/// | an unknown key | `` unknown key: the keys are `file`, `ron`, `outputs(...)`, `scalar` and `crate` `` (the key) |
/// | an unknown scalar | ``unknown scalar `f16`: write `scalar = f64` or `scalar = f32` `` (the name) |
/// | a scalar written as a string | ``write the scalar as a type, not a string: `scalar = f32` `` (the string) |
/// | an empty `outputs()` | ``` `outputs()` names no output: list at least one, … ``` (the key) |
/// | an unknown output | ``unknown output `x`: the outputs are ...`` (the name) |
/// | an unreadable file | ``cannot read `mechanisms/x.ron` (relative to the crate's manifest directory): no such file`` (the path) |
/// | a RON syntax error | `mechanisms/x.ron:17:13: RON syntax error: ...` (the path) |
/// | an invalid mechanism (unknown name, invalid inertia, uncontrollable routing, ...) | `mechanisms/x.ron:LINE:COLUMN: ITEM: PROBLEM`, as `tendyn check` reports it (the path; `inline RON:LINE:COLUMN` for `ron = ...`) |
/// | an output the mechanism cannot provide | ``mechanism `motor_only` cannot provide `segment_tensions`: ...`` (that output) |
/// | a number the scalar cannot hold | ``output `NAME`: a constant folded from the mechanism's numbers is ..., which f32 cannot hold ...`` (the `file` or `ron` value) |
/// | a field that is not a parameter | ``field `payload` is not a runtime parameter of mechanism `finger`: it declares `m3`, `g` `` (the field) |
/// | a parameter without a field | ``mechanism `finger` declares the runtime parameter `g`, missing from the fields of `Finger` (fields: `m3`); ...`` (the struct's name) |
/// | a field of another type | rustc's `mismatched types` (the field) |
/// | a tuple struct | ``the fields of a `TendonMechanism` are its runtime parameters by name: use named fields (...)`` (the fields) |
/// | an enum or a union | `` `TendonMechanism` is derived for a struct whose fields are the runtime parameters`` (its name) |
/// | generic parameters | `` `TendonMechanism` is derived for a concrete type: ... `` (the parameters) |
///
/// Beside the error the expansion still declares the inherent methods and the trait with
/// the shapes the file gives (with bodies that never run), so that the located error is
/// the only one: no "no method named ..." at every call site.
///
/// Relative paths are relative to `CARGO_MANIFEST_DIR`, or to `TENDYN_MANIFEST_DIR` when
/// it is set (for tests run through `trybuild`, which builds in a scratch directory).
#[proc_macro_derive(TendonMechanism, attributes(tendyn))]
pub fn derive_tendon_mechanism(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    match expand(&input) {
        Ok(tokens) => tokens.into(),
        Err(e) => {
            let mut tokens = e.into_compile_error();
            tokens.extend(stand_in(&input));
            tokens.into()
        }
    }
}

/// Where the mechanism comes from.
enum Source {
    File(LitStr),
    Inline(LitStr),
}

/// The parsed `#[tendyn(...)]` attribute.
struct Attribute {
    source: Source,
    outputs: Option<Vec<Ident>>,
    scalar: (Scalar, Span),
    krate: syn::Path,
}

fn parse_attribute(input: &DeriveInput) -> syn::Result<Attribute> {
    let mut source = None;
    let mut outputs = None;
    let mut scalar = (Scalar::F64, Span::call_site());
    let mut krate: syn::Path = syn::parse_quote!(::tendyn);
    let mut found = false;
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("tendyn")) {
        found = true;
        attr.parse_nested_meta(|meta| {
            let set_source = |source: &mut Option<Source>, s: Source| {
                if source.is_some() {
                    return Err(
                        meta.error("give the mechanism once: `file = \"...\"` or `ron = \"...\"`")
                    );
                }
                *source = Some(s);
                Ok(())
            };
            if meta.path.is_ident("file") {
                set_source(&mut source, Source::File(meta.value()?.parse()?))
            } else if meta.path.is_ident("ron") {
                set_source(&mut source, Source::Inline(meta.value()?.parse()?))
            } else if meta.path.is_ident("outputs") {
                let names;
                syn::parenthesized!(names in meta.input);
                let list = Punctuated::<Ident, Token![,]>::parse_terminated(&names)?;
                if list.is_empty() {
                    return Err(meta.error(
                        "`outputs()` names no output: list at least one, e.g. \
                         `outputs(generalized_forces)`, or leave `outputs` out for every output \
                         the mechanism provides",
                    ));
                }
                outputs = Some(list.into_iter().collect());
                Ok(())
            } else if meta.path.is_ident("scalar") {
                let value = meta.value()?;
                if value.peek(LitStr) {
                    let written: LitStr = value.parse()?;
                    return Err(syn::Error::new(
                        written.span(),
                        format!(
                            "write the scalar as a type, not a string: `scalar = {}`",
                            written.value()
                        ),
                    ));
                }
                let ident: Ident = value.parse()?;
                scalar = match ident.to_string().as_str() {
                    "f64" => (Scalar::F64, ident.span()),
                    "f32" => (Scalar::F32, ident.span()),
                    other => {
                        return Err(syn::Error::new(
                            ident.span(),
                            format!(
                                "unknown scalar `{other}`: write `scalar = f64` or `scalar = f32`"
                            ),
                        ))
                    }
                };
                Ok(())
            } else if meta.path.is_ident("crate") {
                let path: LitStr = meta.value()?.parse()?;
                krate = path.parse()?;
                Ok(())
            } else {
                Err(meta.error(
                    "unknown key: the keys are `file`, `ron`, `outputs(...)`, `scalar` and `crate`",
                ))
            }
        })?;
    }
    if !found {
        return Err(syn::Error::new(
            input.ident.span(),
            "missing `#[tendyn(file = \"mechanism.ron\")]`: say which mechanism to generate",
        ));
    }
    let source = source.ok_or_else(|| {
        syn::Error::new(
            input.ident.span(),
            "missing the mechanism: add `file = \"mechanism.ron\"` (relative to the crate's \
             manifest directory) or `ron = \"...\"` to `#[tendyn(...)]`",
        )
    })?;
    Ok(Attribute {
        source,
        outputs,
        scalar,
        krate,
    })
}

/// The model, and the text to embed so that cargo rebuilds when the file changes.
fn load(source: &Source) -> syn::Result<(tendyn_core::Model<f64>, Option<String>)> {
    match source {
        Source::Inline(lit) => {
            let model = tendyn_core::parse(&lit.value())
                .map_err(|e| syn::Error::new(lit.span(), located("inline RON", &e)))?;
            Ok((model, None))
        }
        Source::File(lit) => {
            let written = lit.value();
            let path = path_of(lit);
            let text = std::fs::read_to_string(&path).map_err(|e| {
                syn::Error::new(
                    lit.span(),
                    format!(
                        "cannot read `{written}` (relative to the crate's manifest directory): {}",
                        io_reason(&e)
                    ),
                )
            })?;
            let model = tendyn_core::parse(&text)
                .map_err(|e| syn::Error::new(lit.span(), located(&written, &e)))?;
            Ok((model, Some(path.to_string_lossy().into_owned())))
        }
    }
}

/// A `file = "..."` path, relative to the crate's manifest directory.
fn path_of(lit: &LitStr) -> std::path::PathBuf {
    let base = std::env::var_os("TENDYN_MANIFEST_DIR")
        .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
        .map(std::path::PathBuf::from)
        .unwrap_or_default();
    base.join(lit.value())
}

fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".to_string(),
        _ => e.to_string(),
    }
}

/// `path:line:column: item: problem`, the way compilers quote a place in a file.
fn located(path: &str, e: &tendyn_core::Error) -> String {
    use tendyn_core::Error as E;
    match e {
        E::Syntax {
            line,
            column,
            message,
        } => format!("{path}:{line}:{column}: RON syntax error: {message}"),
        E::Invalid { item, at, problem }
        | E::Routing {
            item, at, problem, ..
        } if at.line > 0 => {
            format!("{path}:{}:{}: {item}: {problem}", at.line, at.column)
        }
        other => format!("{path}: {other}"),
    }
}

fn expand(input: &DeriveInput) -> syn::Result<TokenStream> {
    let attr = parse_attribute(input)?;
    if !input.generics.params.is_empty() {
        return Err(syn::Error::new(
            input.generics.span(),
            "`TendonMechanism` is derived for a concrete type: remove the generic parameters \
             (choose the scalar with `scalar = f64` or `scalar = f32`)",
        ));
    }
    let (model, tracked) = load(&attr.source)?;
    let source_span = match &attr.source {
        Source::File(l) | Source::Inline(l) => l.span(),
    };

    // The fields are the runtime parameters, one for one.
    let fields = parameter_fields(input, &model)?;

    let outputs: Vec<Output> = match &attr.outputs {
        None => tendyn_codegen::available_outputs(&model),
        Some(list) => list
            .iter()
            .map(|ident| {
                Output::parse(&ident.to_string()).ok_or_else(|| {
                    syn::Error::new(
                        ident.span(),
                        format!(
                            "unknown output `{ident}`: the outputs are {}",
                            Output::ALL.map(|o| o.name()).join(", ")
                        ),
                    )
                })
            })
            .collect::<syn::Result<Vec<_>>>()
            .map(once_each)?,
    };
    if let Err(u) = tendyn_codegen::outputs::check(&model, &outputs) {
        let span = attr
            .outputs
            .iter()
            .flatten()
            .find(|i| *i == u.output.name())
            .map_or(source_span, Ident::span);
        return Err(syn::Error::new(
            span,
            format!(
                "mechanism `{}` cannot provide `{}`: {}",
                model.name(),
                u.output.name(),
                u.reason
            ),
        ));
    }

    let krate = &attr.krate;
    let core_path = quote!(#krate::core).to_string().replace(' ', "");
    let options = Options {
        scalar: attr.scalar.0,
        source: match &attr.source {
            Source::File(l) => l.value(),
            Source::Inline(_) => "inline RON".to_string(),
        },
        core_path,
    };
    let generated = tendyn_codegen::generate_with(&model, &outputs, &options)
        .map_err(|e| syn::Error::new(source_span, e.to_string()))?;
    let file = &generated.file;

    let ident = &input.ident;
    let module = format_ident!("__tendyn_{}", snake(&ident.to_string()));
    let items = &file.items;
    let scalar = match attr.scalar.0 {
        Scalar::F32 => quote_spanned!(attr.scalar.1=> f32),
        _ => quote_spanned!(attr.scalar.1=> f64),
    };

    let params_value = if model.parameters().is_empty() {
        None
    } else {
        let values = fields.iter().map(|f| quote_spanned!(f.span()=> self.#f));
        Some(quote!(&[#(#values),*]))
    };
    let functions: Vec<&syn::ItemFn> = file
        .items
        .iter()
        .filter_map(|i| match i {
            syn::Item::Fn(f) => Some(f),
            _ => None,
        })
        .collect();
    let find = |name: &str| functions.iter().copied().find(|f| f.sig.ident == name);

    // Inherent methods: each generated function with the parameters taken from `self`.
    let inherent = functions.iter().map(|f| {
        let name = &f.sig.ident;
        let inputs: Vec<&syn::PatType> = f
            .sig
            .inputs
            .iter()
            .filter_map(|a| match a {
                syn::FnArg::Typed(t) if !is_params(t) => Some(t),
                _ => None,
            })
            .collect();
        let args = inputs.iter().map(|t| &t.pat);
        let params = params_value.iter();
        let output = match &f.sig.output {
            syn::ReturnType::Type(..) if name == "all" => quote!(#module::Outputs),
            syn::ReturnType::Type(_, ty) => quote!(#ty),
            syn::ReturnType::Default => quote!(()),
        };
        let docs = f.attrs.iter().filter(|a| a.path().is_ident("doc"));
        quote! {
            #(#docs)*
            #[inline]
            pub fn #name(&self, #(#inputs),*) -> #output {
                #module::#name(#(#args,)* #(#params)*)
            }
        }
    });

    // The trait: the associated types are the generated functions' shapes.
    let (n, m, t) = (model.dof(), model.motors().len(), model.tendons().len());
    let return_of = |name: &str| match find(name).map(|f| &f.sig.output) {
        Some(syn::ReturnType::Type(_, ty)) => quote!(#ty),
        _ => quote!(()),
    };
    let segments = return_of("segment_tensions");
    let bearings = return_of("bearings");
    let base_reaction = return_of("base_reaction");
    // The derivatives are inherent methods only: the trait has no method for them.
    let in_trait = outputs.iter().filter(|o| Output::DEFAULT.contains(o));
    let trait_methods = in_trait.map(|o| {
        let name = format_ident!("{}", o.name());
        let params = params_value.iter();
        let unnamed = Unnamed {
            actuated: quote!(()),
            actuators: quote!(()),
            actuation_jacobian: quote!(()),
            regression: quote!(()),
        };
        let (signature, args, ret) = signature(*o, krate, &|t| quote!(Self::#t), &unnamed);
        quote! {
            #[inline]
            fn #name(&self, #signature) -> ::core::option::Option<#ret> {
                ::core::option::Option::Some(#module::#name(#args, #(#params)*))
            }
        }
    });
    let names = |v: Vec<&String>| quote!(&[#(#v),*]);
    let joint_names = names(model.bodies()[..n].iter().map(|b| &b.name).collect());
    let motor_names = names(model.motors().iter().map(|x| &x.name).collect());
    let tendon_names = names(model.tendons().iter().map(|x| &x.name).collect());
    let parameter_names = names(model.parameters().iter().map(|x| &x.name).collect());
    let output_names = outputs.iter().map(|o| o.name());
    let name = model.name();
    let structure_rows = model.structure_matrix().into_iter().map(|row| {
        let cells = row.into_iter().map(|x| {
            let lit = proc_macro2::Literal::f64_suffixed(x.abs());
            if x < 0.0 {
                quote!(-#lit)
            } else {
                quote!(#lit)
            }
        });
        quote!(&[#(#cells),*])
    });
    let trait_impl = trait_impl(
        ident,
        krate,
        &scalar,
        Shapes {
            joints: n,
            motors: m,
            tendons: t,
            segments,
            bearings,
            base_reaction,
        },
        quote! {
            const NAME: &'static str = #name;
            const JOINT_NAMES: &'static [&'static str] = #joint_names;
            const MOTOR_NAMES: &'static [&'static str] = #motor_names;
            const TENDON_NAMES: &'static [&'static str] = #tendon_names;
            const PARAMETER_NAMES: &'static [&'static str] = #parameter_names;
            const OUTPUTS: &'static [&'static str] = &[#(#output_names),*];
            const STRUCTURE_MATRIX: &'static [&'static [f64]] = &[#(#structure_rows),*];
            #(#trait_methods)*
        },
    );
    let track = tracked.map(|path| {
        quote!(
            const _: &[u8] = include_bytes!(#path);
        )
    });
    let doc = format!(
        " Code generated by `#[derive(TendonMechanism)]` for `{ident}` from {}.",
        options.source
    );

    Ok(quote! {
        #[doc = #doc]
        #[doc(hidden)]
        #[allow(clippy::all, unused_imports, dead_code, non_snake_case)]
        pub mod #module {
            #(#items)*
        }

        // Cargo rebuilds the crate when the mechanism file changes.
        #track

        impl #ident {
            #(#inherent)*
        }

        #trait_impl
    })
}

/// An output's parameters as the trait declares them, the arguments that pass them on, and
/// its return type (inside the trait's `Option`). `ty` writes one of the trait's associated
/// types (`Joints`, `Motors`, …) as a path: `Self::Joints` in the trait's impl. `unnamed`
/// holds the types the trait has no name for (those of outputs outside it).
fn signature(
    o: Output,
    krate: &syn::Path,
    ty: &dyn Fn(Ident) -> TokenStream,
    unnamed: &Unnamed,
) -> (TokenStream, TokenStream, TokenStream) {
    let Unnamed {
        actuated,
        actuators,
        actuation_jacobian,
        regression,
    } = unnamed;
    let t = |name: &str| ty(format_ident!("{name}"));
    let (joints, motors, tendons) = (t("Joints"), t("Motors"), t("Tendons"));
    let (signature, args) = match o {
        Output::MassMatrix | Output::Gravity => (quote!(q: &#joints), quote!(q)),
        Output::Bias => (quote!(q: &#joints, qd: &#joints), quote!(q, qd)),
        Output::ForwardDynamics | Output::ForwardDynamicsDerivatives => (
            quote!(q: &#joints, qd: &#joints, motor_torques: &#motors, tendon_tensions: &#tendons),
            quote!(q, qd, motor_torques, tendon_tensions),
        ),
        _ => (
            quote!(q: &#joints, qd: &#joints, qdd: &#joints),
            quote!(q, qd, qdd),
        ),
    };
    let ret = match o {
        Output::GeneralizedForces | Output::Bias | Output::Gravity | Output::ForwardDynamics => {
            joints
        }
        Output::Actuation => quote!(#krate::core::distribution::Actuation<#motors, #tendons>),
        Output::MassMatrix => t("MassMatrix"),
        Output::SegmentTensions => t("Segments"),
        Output::Bearings => t("Bearings"),
        Output::BaseReaction => t("BaseReaction"),
        Output::GeneralizedForcesDerivatives => {
            let mass = t("MassMatrix");
            quote!(#krate::core::dual::StateJacobians<#joints, #mass>)
        }
        Output::ForwardDynamicsDerivatives => {
            let mass = t("MassMatrix");
            quote!(#krate::core::dual::ForwardJacobians<#joints, #mass, #actuated>)
        }
        Output::ActuationDerivatives => {
            quote!(#krate::core::dual::ActuationJacobians<#actuators, #actuation_jacobian>)
        }
        Output::Regressor => quote!(#krate::core::mechanism::Regression<#regression, #joints>),
    };
    (signature, args, ret)
}

/// Types of outputs the trait has no associated type for: `∂q̈/∂u`,
/// `[[T; motors + tendons]; n]`, the actuators' `[T; motors + tendons]` and their
/// Jacobian `[[T; n]; motors + tendons]`, and the regressor's `[[T; parameters]; n]`.
struct Unnamed {
    actuated: TokenStream,
    actuators: TokenStream,
    actuation_jacobian: TokenStream,
    regression: TokenStream,
}

/// What the expansion holds beside a compile error: the inherent methods and the trait with
/// the shapes the file gives, with bodies that never run. Without them every call of a
/// method would add a second, misleading error ("no method named …", E0599, "perhaps you
/// need to implement `TendonMechanism`") to the one that says what is wrong. The shapes
/// come from the file as written, so they are there even when validation fails; without a
/// readable file or a usable attribute (or for a generic struct) there is nothing to give.
fn stand_in(input: &DeriveInput) -> Option<TokenStream> {
    let attr = parse_attribute(input).ok()?;
    if !input.generics.params.is_empty() {
        return None;
    }
    let text = match &attr.source {
        Source::Inline(lit) => lit.value(),
        Source::File(lit) => std::fs::read_to_string(path_of(lit)).ok()?,
    };
    let f = tendyn_core::validate::read(&text).ok()?;
    let (n, m, t) = (f.links.len(), f.motors.len(), f.tendons.len());
    let bodies = f.links.len() + f.pulleys.len();
    // A tendon has a segment after each of its wraps; a loop one on each side.
    let segments = f.tendons.iter().map(|t| t.route.len()).sum::<usize>() + 2 * f.loops.len();
    let outputs: Vec<Output> = match &attr.outputs {
        None => Output::DEFAULT.to_vec(),
        Some(list) => list
            .iter()
            .filter_map(|i| Output::parse(&i.to_string()))
            .collect(),
    };
    let outputs = once_each(outputs);
    let (ident, krate) = (&input.ident, &attr.krate);
    let scalar = match attr.scalar.0 {
        Scalar::F32 => quote!(f32),
        _ => quote!(f64),
    };
    // Every body of the stand-in: it is only ever emitted beside the `compile_error!` of
    // the real error, so the crate never builds and no body can run.
    let never = quote!(::core::unreachable!(
        "emitted only beside the compile error of `#[derive(TendonMechanism)]`"
    ));
    // Ten inertial parameters per body, two more where its bearing has friction.
    let frictional = f.links.iter().filter(|l| l.friction.is_some()).count()
        + f.pulleys.iter().filter(|p| p.friction.is_some()).count();
    let (u, p) = (m + t, 10 * bodies + 2 * frictional);
    let unnamed = Unnamed {
        actuated: quote!([[#scalar; #u]; #n]),
        actuators: quote!([#scalar; #u]),
        actuation_jacobian: quote!([[#scalar; #n]; #u]),
        regression: quote!([[#scalar; #p]; #n]),
    };
    let methods = outputs.iter().map(|o| {
        let name = format_ident!("{}", o.name());
        let (signature, _, ret) = signature(
            *o,
            krate,
            &|t| quote!(<Self as #krate::TendonMechanism>::#t),
            &unnamed,
        );
        quote! {
            #[allow(unused_variables)]
            pub fn #name(&self, #signature) -> #ret {
                #never
            }
        }
    });
    let name = &f.name;
    let trait_impl = trait_impl(
        ident,
        krate,
        &scalar,
        Shapes {
            joints: n,
            motors: m,
            tendons: t,
            segments: quote!([#scalar; #segments]),
            bearings: quote!([[[#scalar; 3]; 2]; #bodies]),
            base_reaction: quote!([[[#scalar; 3]; 2]; 1]),
        },
        quote! {
            const NAME: &'static str = #name;
            const JOINT_NAMES: &'static [&'static str] = &[];
            const MOTOR_NAMES: &'static [&'static str] = &[];
            const TENDON_NAMES: &'static [&'static str] = &[];
            const PARAMETER_NAMES: &'static [&'static str] = &[];
            const OUTPUTS: &'static [&'static str] = &[];
            const STRUCTURE_MATRIX: &'static [&'static [f64]] = &[];
        },
    );
    // `all` and its `Outputs`, one field per output, typed through the trait.
    let module = format_ident!("__tendyn_{}", snake(&ident.to_string()));
    let fields = outputs.iter().map(|o| {
        let name = format_ident!("{}", o.name());
        let (_, _, ret) = signature(
            *o,
            krate,
            &|t| quote!(<super::#ident as #krate::TendonMechanism>::#t),
            &unnamed,
        );
        quote!(pub #name: #ret,)
    });
    let of = |t: &str| {
        let t = format_ident!("{t}");
        quote!(<Self as #krate::TendonMechanism>::#t)
    };
    // The inputs its outputs take, in `all`'s order (the parameters come from the fields).
    let inputs = Param::ALL
        .into_iter()
        .filter(|p| outputs.iter().any(|o| o.params().contains(p)))
        .filter_map(|p| {
            let ty = match p {
                Param::Q | Param::Qd | Param::Qdd => of("Joints"),
                Param::MotorTorques => of("Motors"),
                Param::TendonTensions => of("Tendons"),
                Param::Parameters => return None,
            };
            let name = format_ident!("{}", p.name());
            Some(quote!(#name: &#ty))
        });
    Some(quote! {
        #[doc(hidden)]
        #[allow(dead_code, non_snake_case)]
        pub mod #module {
            pub struct Outputs {
                #(#fields)*
            }
        }

        impl #ident {
            #(#methods)*

            #[allow(unused_variables)]
            pub fn all(&self, #(#inputs),*) -> #module::Outputs {
                #never
            }
        }

        #trait_impl
    })
}

/// `outputs` with each repeated one dropped: a repeated name is generated once
/// (docs/generated-code.md §1).
fn once_each(outputs: Vec<Output>) -> Vec<Output> {
    outputs.into_iter().fold(Vec::new(), |mut seen, o| {
        if !seen.contains(&o) {
            seen.push(o);
        }
        seen
    })
}

/// The sizes and result types of the trait's associated types.
struct Shapes {
    joints: usize,
    motors: usize,
    tendons: usize,
    segments: TokenStream,
    bearings: TokenStream,
    base_reaction: TokenStream,
}

/// `impl TendonMechanism for ident`: the associated types from `shapes`, the counts, and
/// `rest` (the names, the structure matrix and the methods).
fn trait_impl(
    ident: &Ident,
    krate: &syn::Path,
    scalar: &TokenStream,
    shapes: Shapes,
    rest: TokenStream,
) -> TokenStream {
    let Shapes {
        joints: n,
        motors: m,
        tendons: t,
        segments,
        bearings,
        base_reaction,
    } = shapes;
    quote! {
        impl #krate::TendonMechanism for #ident {
            type Scalar = #scalar;
            type Joints = [#scalar; #n];
            type Motors = [#scalar; #m];
            type Tendons = [#scalar; #t];
            type MassMatrix = [[#scalar; #n]; #n];
            type Segments = #segments;
            type Bearings = #bearings;
            type BaseReaction = #base_reaction;
            const DOF: usize = #n;
            const MOTORS: usize = #m;
            const TENDONS: usize = #t;
            #rest
        }
    }
}

fn is_params(t: &syn::PatType) -> bool {
    matches!(&*t.pat, syn::Pat::Ident(i) if i.ident == "params")
}

/// The struct's fields, in the order of the declared parameters; a compile error naming
/// both sides when they differ.
fn parameter_fields(
    input: &DeriveInput,
    model: &tendyn_core::Model<f64>,
) -> syn::Result<Vec<Ident>> {
    let declared: Vec<&str> = model.parameters().iter().map(|p| p.name.as_str()).collect();
    let list = |v: &[&str]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    let fields: Vec<Ident> =
        match &input.data {
            syn::Data::Struct(s) => match &s.fields {
                syn::Fields::Named(named) => {
                    named.named.iter().filter_map(|f| f.ident.clone()).collect()
                }
                syn::Fields::Unit => Vec::new(),
                syn::Fields::Unnamed(u) => {
                    return Err(syn::Error::new(
                        u.span(),
                        format!(
                        "the fields of a `TendonMechanism` are its runtime parameters by name: \
                         use named fields ({})",
                        list(&declared)
                    ),
                    ))
                }
            },
            _ => return Err(syn::Error::new(
                input.ident.span(),
                "`TendonMechanism` is derived for a struct whose fields are the runtime parameters",
            )),
        };
    let have: Vec<String> = fields.iter().map(Ident::to_string).collect();
    let have_refs: Vec<&str> = have.iter().map(String::as_str).collect();
    if let Some(extra) = fields
        .iter()
        .find(|f| !declared.contains(&f.to_string().as_str()))
    {
        return Err(syn::Error::new(
            extra.span(),
            format!(
                "field `{extra}` is not a runtime parameter of mechanism `{}`: it declares {}",
                model.name(),
                list(&declared)
            ),
        ));
    }
    let missing: Vec<&str> = declared
        .iter()
        .copied()
        .filter(|d| !have_refs.contains(d))
        .collect();
    if !missing.is_empty() {
        return Err(syn::Error::new(
            input.ident.span(),
            format!(
                "mechanism `{}` declares the runtime parameter{} {}, missing from the fields of \
                 `{}` (fields: {}); add one field per parameter, of the scalar type",
                model.name(),
                if missing.len() > 1 { "s" } else { "" },
                list(&missing),
                input.ident,
                list(&have_refs)
            ),
        ));
    }
    // Every declared parameter has its field (checked above): in declaration order.
    Ok(declared
        .iter()
        .filter_map(|d| fields.iter().find(|f| *f == d).cloned())
        .collect())
}

/// `StanfordFinger` → `stanford_finger`.
fn snake(name: &str) -> String {
    let mut s = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() {
            if i > 0 {
                s.push('_');
            }
            s.extend(c.to_lowercase());
        } else {
            s.push(c);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expand_str(input: DeriveInput) -> String {
        expand(&input).map_or_else(|e| e.to_string(), |t| t.to_string())
    }

    #[test]
    fn a_file_mechanism_is_embedded_by_its_absolute_path_so_editing_it_rebuilds_the_crate() {
        let out = expand_str(syn::parse_quote! {
            #[tendyn(file = "../examples/mechanisms/example1_endless.ron", outputs(gravity))]
            struct Arm;
        });
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../examples/mechanisms/example1_endless.ron");
        let embedded = format!("include_bytes ! ({:?})", path.to_string_lossy());
        assert!(out.contains(&embedded), "{out}");
    }

    #[test]
    fn an_inline_mechanism_embeds_no_file() {
        let out = expand_str(syn::parse_quote! {
            #[tendyn(ron = r#"(
                name: "pendulum",
                links: [(name: "link1", dh: (a: 0.5, alpha: 0.0, d: 0.0), mass: 2.0,
                    com: (0.0, 0.0, 0.0), inertia: (xx: 0.0, yy: 0.0, zz: 0.0))],
                motors: [(name: "motor1", on: Joint("link1"))],
            )"#, outputs(gravity))]
            struct Pendulum;
        });
        assert!(out.contains("fn gravity"), "{out}");
        assert!(!out.contains("include_bytes"), "{out}");
    }

    #[test]
    fn only_the_requested_outputs_become_methods_and_the_trait_lists_them() {
        let out = expand_str(syn::parse_quote! {
            #[tendyn(file = "../examples/mechanisms/example2_open_ended.ron", outputs(mass_matrix, actuation))]
            struct Arm;
        });
        assert!(out.contains("pub fn mass_matrix"), "{out}");
        assert!(out.contains("pub fn actuation"), "{out}");
        assert!(!out.contains("fn bearings"), "{out}");
        assert!(
            out.contains(
                r#"const OUTPUTS : & 'static [& 'static str] = & ["mass_matrix" , "actuation"]"#
            ),
            "{out}"
        );
    }

    #[test]
    fn struct_names_become_snake_case_module_names() {
        assert_eq!(snake("StanfordFinger"), "stanford_finger");
        assert_eq!(snake("Arm"), "arm");
    }
}
