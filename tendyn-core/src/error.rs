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

impl Error {
    /// The name of the offending item, when the error is about one.
    pub fn item(&self) -> Option<&str> {
        match self {
            Error::Invalid { item, .. } | Error::Routing { item, .. } => Some(item),
            _ => None,
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
