//! The one error type of `tendyn-core`. Every variant names what is wrong and, where the
//! mistake is in a file, where, and says what would fix it.

use thiserror::Error;

/// Where in a RON file an item is defined (1-based), when it could be located.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Location {
    pub line: usize,
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

#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    #[error("cannot read {path}: {reason}")]
    Io { path: String, reason: String },

    #[error("RON syntax error at line {line}, column {column}: {message}")]
    Syntax {
        line: usize,
        column: usize,
        message: String,
    },

    /// An item's definition is wrong (a bad number, a bad reference, an impossible shape).
    #[error("{item}{at}: {problem}")]
    Invalid {
        item: String,
        at: Location,
        problem: String,
    },

    /// The tendon routing cannot do what a transmission must.
    #[error("{item}{at}: {problem}")]
    Routing {
        item: String,
        at: Location,
        problem: String,
        /// The tension system the routing implies, where it was derived before the routing
        /// failed its checks (rank, controllability): `check` prints it beside the error.
        implied: Option<Box<ImpliedSystem>>,
    },

    /// A state handed to the solver is unusable.
    #[error("state: {0}")]
    State(String),

    /// The requested tension distribution cannot be met.
    #[error("tension distribution: {0}")]
    Tension(String),

    /// The mass matrix cannot be factorized (forward dynamics of a degenerate mechanism).
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

pub type Result<T> = std::result::Result<T, Error>;
