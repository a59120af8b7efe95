//! Why a CAD export could not be made.

use std::fmt;

use thiserror::Error;

/// A patch that could not be approximated within the export tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct UnfittedFace {
    /// The patch's face in the topology.
    pub face: usize,
    /// The largest deviation (m) its last fits reached (infinite where its boundary curves
    /// could not be fitted or represented at all).
    pub deviation: f64,
    /// Whether its fits turned over (folded in their own tangent plane) somewhere: they follow
    /// a fold of the patch (one the build's mesh may step over) that no unfolded face smooths
    /// over within the tolerance.
    pub turned: bool,
}

/// The faces of [`ExportError::NotConverged`], each with what its fit reached.
#[derive(Clone, Debug, PartialEq)]
pub struct UnfittedFaces(pub Vec<UnfittedFace>);

impl fmt::Display for UnfittedFaces {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, u) in self.0.iter().enumerate() {
            let sep = if k == 0 { "" } else { ", " };
            if u.deviation.is_finite() {
                let turned = if u.turned {
                    ", turning over where the patch folds in its own tangent plane"
                } else {
                    ""
                };
                write!(
                    f,
                    "{sep}face {} (reached {:.3e} m{turned})",
                    u.face, u.deviation
                )?;
            } else {
                write!(
                    f,
                    "{sep}face {} (its boundary curves could not be fitted)",
                    u.face
                )?;
            }
        }
        Ok(())
    }
}

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
    /// Some patches could not be approximated within the tolerance: every one whose boundary
    /// curves could not be fitted, and the faces found before the first failing face stopped
    /// the rest (fitting each to its limit takes seconds).
    #[error("{} of {patches} patches could not be approximated by B-splines within {tolerance:.1e} m: {faces} (the export stops at the first faces it cannot fit; others may follow). Such a patch folds (see the build's fold warnings) or bends too sharply for the most spans: fair or move the curves around it, or export with a larger tolerance where it reached little more than the tolerance", faces.0.len())]
    NotConverged {
        /// The faces, in patch order.
        faces: UnfittedFaces,
        /// Number of patches of the surface.
        patches: usize,
        /// The export tolerance (m).
        tolerance: f64,
    },
}
