//! `tendyn-codegen`: turns a validated mechanism into specialised straight-line Rust.
//!
//! The pipeline, module by module:
//!
//! - [`expr`]: the hash-consed expression graph; [`expr::Sym`] implements
//!   `tendyn_core::Real`, so the solver's generic recursion builds the graph when run on it;
//! - [`outputs`]: which functions can be generated and how each is traced through
//!   `tendyn-core` (the same code the runtime solver runs);
//! - [`closed_form`]: the collected polynomial form in sines, cosines, velocities and
//!   accelerations, kept per function when it has fewer operations;
//! - [`emit`]: graph → Rust source (quote, prettyplease), with operation counts;
//! - [`report`]: the CLI's text and JSON renderings of runtime results;
//! - [`builder`]: [`Builder`], generation from a build script into `OUT_DIR`.
//!
//! [`generate`] runs the whole pipeline.

pub mod builder;
pub mod closed_form;
pub mod emit;
pub mod equations;
pub mod expr;
pub mod outputs;
pub mod report;

pub use builder::Builder;
pub use emit::Scalar;
pub use outputs::Output;

/// The one error type of `tendyn-codegen`.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// The mechanism file is invalid.
    Model(tendyn_core::Error),
    /// A requested output cannot be generated for this mechanism.
    Unavailable { output: Output, reason: String },
    /// The path given for `tendyn-core` is not a Rust path.
    CorePath { path: String },
    /// A mechanism file of a [`Builder`] is unreadable or invalid.
    File {
        path: String,
        error: tendyn_core::Error,
    },
    /// An output name that is not one of [`Output::ALL`].
    UnknownOutput(String),
    /// The build environment is not what [`Builder`] needs (no `OUT_DIR`, an unwritable
    /// file).
    Build(String),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Model(e) => write!(f, "{e}"),
            Error::Unavailable { output, reason } => {
                write!(
                    f,
                    "output `{}` cannot be generated: {reason}",
                    output.name()
                )
            }
            Error::File { path, error } => write!(f, "{path}: {error}"),
            Error::UnknownOutput(name) => write!(
                f,
                "unknown output `{name}`: the outputs are {}",
                Output::ALL.map(|o| o.name()).join(", ")
            ),
            Error::Build(problem) => write!(f, "{problem}"),
            Error::CorePath { path } => write!(
                f,
                "`{path}` is not a Rust path to tendyn-core (write `tendyn_core` or `::tendyn::core`)"
            ),
        }
    }
}

impl std::error::Error for Error {}

impl From<tendyn_core::Error> for Error {
    fn from(e: tendyn_core::Error) -> Self {
        Error::Model(e)
    }
}

impl From<outputs::Unavailable> for Error {
    fn from(u: outputs::Unavailable) -> Self {
        Error::Unavailable {
            output: u.output,
            reason: u.reason,
        }
    }
}

/// Generated source and what it costs.
#[derive(Debug, Clone)]
pub struct Generated {
    pub source: String,
    /// Per function: name, operations of the emitted form, whether it is the closed form.
    pub functions: Vec<(Output, expr::OpCount, bool)>,
    /// Operations of `all`.
    pub all: expr::OpCount,
}

/// How to emit: the scalar, the name of the input for the file's header, and the path by
/// which the emitted code reaches `tendyn-core`.
#[derive(Debug, Clone)]
pub struct Options {
    pub scalar: Scalar,
    /// Names the input in the generated file's header (a file name, say).
    pub source: String,
    /// `tendyn_core` for a crate that depends on `tendyn-core`; `::tendyn::core` behind the
    /// front crate `tendyn`.
    pub core_path: String,
}

impl Options {
    /// Generic code for a crate that depends on `tendyn-core` directly.
    pub fn new(scalar: Scalar, source: &str) -> Options {
        Options {
            scalar,
            source: source.to_string(),
            core_path: "tendyn_core".to_string(),
        }
    }
}

/// Traces, simplifies and emits `outputs` of `model`, for a crate that depends on
/// `tendyn-core`. `source` names the input in the generated file's header.
pub fn generate(
    model: &tendyn_core::Model<f64>,
    outputs: &[Output],
    scalar: Scalar,
    source: &str,
) -> Result<Generated, Error> {
    generate_with(model, outputs, &Options::new(scalar, source))
}

/// [`generate`] with every emission option.
pub fn generate_with(
    model: &tendyn_core::Model<f64>,
    outputs: &[Output],
    options: &Options,
) -> Result<Generated, Error> {
    let core: syn::Path = syn::parse_str(&options.core_path).map_err(|_| Error::CorePath {
        path: options.core_path.clone(),
    })?;
    let traced = outputs::trace(model, outputs)?;
    let functions = traced
        .functions
        .iter()
        .map(|f| {
            let closed = f
                .closed_ops
                .is_some_and(|c| c.arithmetic() < f.traced_ops.arithmetic());
            (f.output, traced.graph.count(&f.results), closed)
        })
        .collect();
    Ok(Generated {
        source: emit::emit(model, &traced, options.scalar, &options.source, &core),
        functions,
        all: traced.all_ops,
    })
}

/// The outputs `model` can provide (every output, less those [`outputs::check`] refuses).
pub fn available_outputs(model: &tendyn_core::Model<f64>) -> Vec<Output> {
    Output::ALL
        .into_iter()
        .filter(|o| outputs::check(model, &[*o]).is_ok())
        .collect()
}
