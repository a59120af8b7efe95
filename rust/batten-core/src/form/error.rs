//! Errors of the form-topology transformations: a request the form cannot carry out, named by
//! the parameter, the vertex or the curves concerned.

use thiserror::Error;

use crate::error::Error;

/// Why a form-topology transformation was refused (Bole, seed 002, §7.2.4–§7.2.5).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FormError {
    /// The parameter needs a parallel middle body and the hull has none.
    #[error("{parameter}: the hull has no parallel middle body ({reason})")]
    NoParallelMiddleBody {
        /// The parameter asked for.
        parameter: &'static str,
        /// Why no parallel middle body was found.
        reason: String,
    },
    /// The parameter cannot be measured on this hull (no arc in the midship section, no
    /// draft …).
    #[error("{parameter}: {reason}")]
    NotMeasurable {
        /// The parameter asked for.
        parameter: &'static str,
        /// What is missing.
        reason: String,
    },
    /// A target value that is not a finite positive length, or that the form cannot take.
    #[error("{parameter} = {value}: {reason}")]
    BadTarget {
        /// The parameter asked for.
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// Why it is refused.
        reason: String,
    },
    /// A move names a form-topology vertex that does not exist, or is not finite.
    #[error("move of form-topology vertex {vertex}: {reason}")]
    BadMove {
        /// The vertex index given.
        vertex: usize,
        /// Why it is refused.
        reason: String,
    },
    /// After the transformation some curves no longer meet as they did (§7.2.4): the request
    /// is refused and nothing is changed.
    #[error("the transformation breaks the connection of curves '{}' ({detail})", curves.join("', '"))]
    ConnectionLost {
        /// The curves that lost (or gained) a connection.
        curves: Vec<String>,
        /// What happened to them.
        detail: String,
    },
    /// The network itself could not be analysed (a curve error, naming the curve).
    #[error(transparent)]
    Network(#[from] Error),
}
