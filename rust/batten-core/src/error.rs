//! The core's error: every module's typed error composes into [`Error`] (`#[from]` or by
//! naming the curve), which the Python binding maps, in one place, to `BattenError` subclasses.

use thiserror::Error;

use crate::curve::CurveError;
use crate::fair::FairError;
use crate::hydro::HydroError;
use crate::patch::PatchError;
use crate::tolerance::InvalidTolerance;

/// Any error of the core, naming the designer curve where there is one.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A problem with one named curve.
    #[error("curve '{curve}': {source}")]
    Curve {
        /// The designer curve's name (the Blender object name, or the name in a network file).
        curve: String,
        /// What is wrong.
        #[source]
        source: CurveError,
    },
    /// Fairing the points of one named curve failed.
    #[error("curve '{curve}': {source}")]
    Fair {
        /// The designer curve's name.
        curve: String,
        /// What is wrong with its points or the fairing options.
        #[source]
        source: FairError,
    },
    /// The model tolerance is not a positive finite number (an invalid argument).
    #[error("tolerance {0} must be a positive finite number of metres")]
    Tolerance(f64),
    /// The tessellation resolution is outside `1..=max` (an invalid argument).
    #[error("resolution {resolution} must be between 1 and {max} intervals per edge")]
    Resolution {
        /// The resolution asked for.
        resolution: usize,
        /// The largest accepted.
        max: usize,
    },
    /// Two curves in one network share a name.
    #[error("two curves are named '{0}'; curve names in a network must be unique")]
    DuplicateName(String),
    /// A curve has no name.
    #[error("curve {0} has an empty name")]
    EmptyName(usize),
    /// An argument that does not fit what it goes with (the message says which and why).
    #[error("{0}")]
    InvalidInput(String),
    /// A network file could not be read.
    #[error("network file: {0}")]
    Format(String),
    /// The network gives no hull surface: it has no faces (the message names the topology's
    /// diagnostics), none of its faces could be patched, or the mesh request is invalid
    /// (H-rep paper §3: a surface needs closed regions of curves).
    #[error("no surface: {0}")]
    NoSurface(String),
    /// The hull's patches could not be tessellated into one mesh (too many vertices for its
    /// indices).
    #[error("no surface: {0}")]
    Mesh(#[from] PatchError),
    /// A hydrostatic calculation that cannot give a true figure (bad flotation, the water
    /// below the keel or over the top, a hole under water).
    #[error("hydrostatics: {0}")]
    Hydro(#[from] HydroError),
}

impl From<InvalidTolerance> for Error {
    /// A refused tolerance as the crate's error.
    fn from(e: InvalidTolerance) -> Error {
        Error::Tolerance(e.0)
    }
}

impl FairError {
    /// Attach the name of the designer curve whose points were being faired.
    pub fn named(self, curve: impl Into<String>) -> Error {
        Error::Fair {
            curve: curve.into(),
            source: self,
        }
    }
}

impl CurveError {
    /// Attach the name of the designer curve this error belongs to.
    pub fn named(self, curve: impl Into<String>) -> Error {
        Error::Curve {
            curve: curve.into(),
            source: self,
        }
    }
}
