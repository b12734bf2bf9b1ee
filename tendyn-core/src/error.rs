//! The one error type of `tendyn-core`. Every variant names what is wrong and, where the
//! mistake is in a file, where, and says what would fix it.

use thiserror::Error;

/// Where in a RON file an item is defined (1-based), when it could be located.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Location {
    /// Line, from 1; `0` when the item could not be located (no source text), and then
    /// nothing is printed.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            Ok(())
        } else {
            write!(f, " (line {}, column {})", self.line, self.column)
        }
    }
}

/// Everything that can go wrong in `tendyn-core`: reading and validating a mechanism file
/// (`docs/format.md` §11) and evaluating it at a state (`docs/outputs.md` §7).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The mechanism file cannot be read (missing, unreadable, not UTF-8).
    #[error("cannot read {path}: {reason}")]
    Io {
        /// The path as given to [`crate::load`].
        path: String,
        /// Why, as the I/O error states it.
        reason: String,
    },

    /// The text is not valid RON for [`crate::format::MechanismFile`]: an unknown or
    /// missing field, a wrong type, `[...]` for a 3-vector, an unknown enum variant.
    #[error("RON syntax error at line {line}, column {column}: {message}")]
    Syntax {
        /// Line of the offending token, from 1 (after a byte-order mark).
        line: usize,
        /// Column of the offending token, in characters, from 1.
        column: usize,
        /// ron's message, with a hint where it alone does not say what would fix it (a
        /// missing comma, a missing field).
        message: String,
    },

    /// An item's definition is wrong (a bad number, a bad reference, an impossible shape).
    #[error("{item}{at}: {problem}")]
    Invalid {
        /// The name of the offending link, pulley, tendon, loop, motor or parameter, or
        /// the mechanism's name for a top-level field (`the mechanism` or `an item` when
        /// the name itself is empty).
        item: String,
        /// Where `item` is defined in the file; line `0` when unknown (a file validated
        /// without its text, or a parameter value set at run time).
        at: Location,
        /// What is wrong and what would fix it.
        problem: String,
    },

    /// The tendon routing cannot do what a transmission must.
    #[error("{item}{at}: {problem}")]
    Routing {
        /// The tendon, loop strand (`LOOP/ccw`), loop or pulley at fault, or the
        /// mechanism's name for a fault of the tension system as a whole.
        item: String,
        /// Where `item` is defined in the file (a strand: its loop); line `0` when unknown.
        at: Location,
        /// What is wrong and what would fix it.
        problem: String,
        /// The tension system the routing implies, where it was derived before the routing
        /// failed its checks (rank, controllability): `check` prints it beside the error.
        implied: Option<Box<ImpliedSystem>>,
    },

    /// A state handed to the solver is unusable: a wrong length, a non-finite entry, or a
    /// result that overflowed the scalar (the message names the input to blame); also a
    /// wrong number of parameter values, or a non-finite one
    /// ([`crate::Model::with_parameters`]).
    #[error("state: {0}")]
    State(String),

    /// No tensions within every `floor` and `max_tension` produce the motion (the message
    /// names the tendons whose bounds block and what they can produce), a tension is not
    /// finite, or the distribution did not finish (round-off at a degenerate state).
    #[error("tension distribution: {0}")]
    Tension(String),

    /// The mass matrix cannot be factorized (forward dynamics of a degenerate mechanism,
    /// e.g. a massless chain): it is not positive definite at that state.
    #[error("forward dynamics: {0}")]
    Singular(String),
}

/// The tension system `E x = b` of a rejected routing, named for a person to read.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpliedSystem {
    /// What each row balances (`joint link1`, `pulley p3`, `pretension belt`); the joints
    /// come first.
    pub rows: Vec<String>,
    /// Each column's unknown (`tension T1`, `tension belt/ccw`, `torque motor1`).
    pub unknowns: Vec<String>,
    /// `E`, row-major.
    pub matrix: Vec<Vec<f64>>,
    /// The mechanism's joints: the structure matrix `A` is `E`'s first `joints` rows on the
    /// columns of the `tendons`.
    pub joints: usize,
    /// Each open-ended tendon's name and column, in the file's order.
    pub tendons: Vec<(String, usize)>,
}

impl Error {
    /// The name of the offending item, when the error is about one.
    pub fn item(&self) -> Option<&str> {
        match self {
            Error::Invalid { item, .. } | Error::Routing { item, .. } => Some(item),
            _ => None,
        }
    }

    /// The tension system a rejected routing implies, when it was derived.
    pub fn implied(&self) -> Option<&ImpliedSystem> {
        match self {
            Error::Routing { implied, .. } => implied.as_deref(),
            _ => None,
        }
    }
}

/// `Result` with this crate's [`Error`](enum@Error).
pub type Result<T> = std::result::Result<T, Error>;
