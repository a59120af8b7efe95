//! Why a CAD export could not be made.

use thiserror::Error;

/// An export that cannot give a faithful file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ExportError {
    /// The build found holes (the report's warnings, joined); export anyway with
    /// `allow_holes`.
    #[error("the surface has holes, so the file would too (export with allow_holes to write what exists): {0}")]
    Holes(String),
    /// The export tolerance is not a positive finite number of metres.
    #[error("export tolerance {0} must be a positive finite number of metres")]
    Tolerance(f64),
    /// A patch could not be approximated within the tolerance.
    #[error("face {face}: its patch could not be approximated by B-splines within the tolerance (reached {deviation:.3e} m); the patch is not smooth enough there")]
    NotConverged {
        /// The patch's face in the topology.
        face: usize,
        /// The deviation reached (m).
        deviation: f64,
    },
    /// A patch's boundary curves could not be represented (f64 could not hold them).
    #[error("face {face}: its boundary curves could not be represented as B-splines")]
    Degenerate {
        /// The patch's face in the topology.
        face: usize,
    },
}
