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
//! - [`emit`]: graph → one `syn` tree (the derive's expansion), printed with prettyplease
//!   for files, with operation counts;
//! - [`report`]: the CLI's text and JSON renderings of runtime results;
//! - [`equations`]: the traced functions in mathematical notation (`tendyn equations`);
//! - [`builder`]: [`Builder`], generation from a build script into `OUT_DIR`.
//!
//! [`generate`] runs the whole pipeline.
#![warn(missing_docs)]

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
    Unavailable {
        /// The output refused.
        output: Output,
        /// Why, in words (see [`outputs::check`]).
        reason: String,
    },
    /// The path given for `tendyn-core` is not a Rust path.
    CorePath {
        /// [`Options::core_path`] as given.
        path: String,
    },
    /// A mechanism file of a [`Builder`] is unreadable or invalid.
    File {
        /// The file's path as given to [`Builder::mechanism`].
        path: String,
        /// What reading or validating it reported.
        error: tendyn_core::Error,
    },
    /// Code generation failed for a mechanism file of a [`Builder`] (an output it cannot
    /// provide, a constant its scalar cannot hold).
    Generation {
        /// The file's path as given to [`Builder::mechanism`].
        path: String,
        /// What generation reported.
        error: Box<Error>,
    },
    /// An output name that is not one of [`Output::ALL`].
    UnknownOutput(String),
    /// No output was asked for: a file of no function (and an `Outputs` struct of no
    /// field, which does not compile for a generic scalar) is never what is wanted.
    NoOutputs,
    /// The build environment is not what [`Builder`] needs (no `OUT_DIR`, an unwritable
    /// file).
    Build(String),
    /// A constant the emitted code would hold that its scalar cannot, folded from the
    /// mechanism's numbers (each of which f32 and f64 hold: validation keeps them within
    /// the ranges of format.md §12). `item` names the output whose function holds it.
    Constant {
        /// `` output `NAME` ``.
        item: String,
        /// The number, the scalar's limit and what to do about it.
        problem: String,
    },
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
            Error::Generation { path, error } => write!(f, "{path}: {error}"),
            Error::UnknownOutput(name) => write!(
                f,
                "unknown output `{name}`: the outputs are {}",
                Output::ALL.map(|o| o.name()).join(", ")
            ),
            Error::Build(problem) => write!(f, "{problem}"),
            Error::NoOutputs => write!(
                f,
                "no output asked for: name at least one of {}",
                Output::ALL.map(|o| o.name()).join(", ")
            ),
            Error::Constant { item, problem } => write!(f, "{item}: {problem}"),
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

/// Generated code and what it costs.
#[derive(Clone)]
pub struct Generated {
    /// Every emitted item, as one syntax tree: what the derive expands to.
    pub file: syn::File,
    /// The comments that open the file as text (generator, mechanism, outputs, scalar).
    pub header: String,
    /// Per function: name, operations of the emitted form, and which form it is.
    pub functions: Vec<(Output, expr::OpCount, outputs::Form)>,
    /// Operations of `all`.
    pub all: expr::OpCount,
}

impl std::fmt::Debug for Generated {
    // (`syn::File` is `Debug` only with syn's `extra-traits`, which this crate does not need.)
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Generated")
            .field("file", &format_args!("{} items", self.file.items.len()))
            .field("header", &self.header)
            .field("functions", &self.functions)
            .field("all", &self.all)
            .finish()
    }
}

impl Generated {
    /// The Rust source of the whole file: the header, then the tree as prettyplease prints
    /// it (what the command line writes and build scripts include).
    pub fn source(&self) -> String {
        self.header.clone() + &prettyplease::unparse(&self.file)
    }
}

/// How to emit: the scalar, the name of the input for the file's header, and the path by
/// which the emitted code reaches `tendyn-core`.
#[derive(Debug, Clone)]
pub struct Options {
    /// The scalar type of the emitted functions.
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
    if outputs.is_empty() {
        return Err(Error::NoOutputs);
    }
    let traced = outputs::trace(model, outputs)?;
    check_constants(model, &traced, options.scalar)?;
    let functions = traced
        .functions
        .iter()
        .map(|f| (f.output, f.ops, f.form))
        .collect();
    Ok(Generated {
        file: emit::emit_file(model, &traced, options.scalar, &core),
        header: emit::header(model, &traced, options.scalar, &options.source),
        functions,
        all: traced.all_ops,
    })
}

/// The default outputs `model` can provide ([`Output::DEFAULT`], less those [`outputs::check`]
/// refuses): what is generated when no output is named.
pub fn available_outputs(model: &tendyn_core::Model<f64>) -> Vec<Output> {
    outputs::available(model, Output::DEFAULT)
}

/// The largest number `scalar` holds, and its name.
fn largest(scalar: Scalar) -> (f64, &'static str) {
    match scalar {
        Scalar::F32 => (f64::from(f32::MAX), "f32"),
        // Generic code writes its constants as f64 literals.
        Scalar::F64 | Scalar::Generic => (f64::MAX, "f64"),
    }
}

/// Whether `x` can be written as a literal of `scalar`.
fn fits(x: f64, scalar: Scalar) -> bool {
    x.abs() <= largest(scalar).0
}

/// What to do about a number the scalar cannot hold.
fn fix(scalar: Scalar) -> &'static str {
    match scalar {
        Scalar::F32 => {
            "generate for f64, or write the mechanism in units that keep its numbers smaller"
        }
        Scalar::F64 | Scalar::Generic => {
            "check the sizes and units of the mechanism's numbers (format.md §12 gives the \
             ranges validation keeps them in)"
        }
    }
}

/// The first joint whose pivot `D_j` in the `L D Lᵀ` factors of `M(0)` that forward
/// dynamics divides by ([`tendyn_core::linalg::ldlt_factor`], as generated code traces
/// it) is not positive (below `1e-12` of `M`'s largest diagonal entry): nothing that joint
/// moves beyond what the joints before it move has mass or inertia.
fn unresisted_joint(model: &tendyn_core::Model<f64>) -> Option<String> {
    let n = model.dof();
    let mut ws = tendyn_core::dynamics::Workspace::new(model);
    let rows = tendyn_core::dynamics::mass_matrix(model, &vec![0.0; n], &mut ws);
    let mut m: Vec<f64> = rows.concat();
    let largest = (0..n).fold(0.0f64, |a, j| a.max(m[j * n + j].abs()));
    tendyn_core::linalg::ldlt_factor(&mut m, n);
    let positive = |d: f64| d > 1e-12 * largest; // false for NaN after a zero pivot
    let unresisted = (0..n).find(|&j| !positive(m[j * n + j]))?;
    Some(model.bodies()[unresisted].name.clone())
}

/// Every constant the emitted code writes fits the scalar: those of the traced functions
/// (folded from the mechanism's numbers as the graph is built: an error names the output
/// whose function holds one), the structure matrix and the distribution's constants.
fn check_constants(
    model: &tendyn_core::Model<f64>,
    traced: &outputs::Traced,
    scalar: Scalar,
) -> Result<(), Error> {
    let (max, name) = largest(scalar);
    let g = &traced.graph;
    let bad = |x: f64| !fits(x, scalar);
    let roots: Vec<expr::Id> = traced
        .functions
        .iter()
        .flat_map(|f| f.results.iter().chain(&f.traced))
        .chain(&traced.all)
        .copied()
        .collect();
    let live = g.live_mask(&roots);
    let overflows =
        |id: usize| matches!(g.nodes[id], expr::Node::Const(bits) if bad(f64::from_bits(bits)));
    if (0..g.nodes.len()).any(|id| live[id] && overflows(id)) {
        // Rare: find the function that holds it.
        for f in &traced.functions {
            let live = g.live_mask(
                &f.results
                    .iter()
                    .chain(&f.traced)
                    .copied()
                    .collect::<Vec<_>>(),
            );
            if let Some(id) = (0..g.nodes.len()).find(|&id| live[id] && overflows(id)) {
                let x = g.constant_value(expr::Id(id as u32)).expect("a constant");
                let forward = matches!(
                    f.output,
                    Output::ForwardDynamics | Output::ForwardDynamicsDerivatives
                );
                let why = match forward.then(|| unresisted_joint(model)).flatten() {
                    Some(joint) => format!(
                        "; the mass matrix is singular at q = 0: joint `{joint}` moves nothing \
                         with mass or inertia that the joints before it could not move as \
                         well, and forward dynamics divides by its pivot; give the bodies it \
                         moves mass or inertia, or leave `{}` out of the outputs",
                        f.output.name()
                    ),
                    None => format!("; {}", fix(scalar)),
                };
                return Err(Error::Constant {
                    item: format!("output `{}`", f.output.name()),
                    problem: format!(
                        "a constant folded from the mechanism's numbers is {x:e}, which {name} \
                         cannot hold (its largest number is {max:.1e}){why}"
                    ),
                });
            }
        }
        // (`all` holds only the functions' results, so this is not reached.)
        return Err(Error::Constant {
            item: "output `all`".to_string(),
            problem: format!(
                "a constant folded from the mechanism's numbers is beyond what {name} can hold \
                 (its largest number is {max:.1e}); {}",
                fix(scalar)
            ),
        });
    }
    // Written as f64 literals whatever the scalar.
    let a = model.structure_matrix();
    for (k, t) in model.tendons().iter().enumerate() {
        if let Some(x) = a.iter().map(|row| row[k]).find(|x| !x.is_finite()) {
            return Err(Error::Constant {
                item: t.name.clone(),
                problem: format!(
                    "its structure-matrix column holds {x}; {}",
                    fix(Scalar::F64)
                ),
            });
        }
    }
    for f in &traced.functions {
        let Some(d) = &f.distribution else { continue };
        // A maximum (and so a target) may be infinite: no maximum.
        let finite = d
            .null
            .iter()
            .flatten()
            .chain(&d.floor)
            .all(|x| x.is_finite());
        let bounded = d
            .max
            .iter()
            .chain(&d.target)
            .all(|&x| x.is_finite() || x == f64::INFINITY);
        if !finite || !bounded {
            return Err(Error::Constant {
                item: format!("output `{}`", f.output.name()),
                problem: format!(
                    "a constant of its tension distribution (null space, floors, maxima) is not \
                     finite; {}",
                    fix(Scalar::F64)
                ),
            });
        }
    }
    Ok(())
}
