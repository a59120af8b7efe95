//! What can go wrong computing hydrostatics.

use glam::DVec3;
use thiserror::Error;

/// A hydrostatic calculation that cannot give a true figure.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum HydroError {
    /// An argument that is not a number, out of range, or inconsistent (the message says which).
    #[error("{0}")]
    InvalidInput(String),
    /// The waterplane does not reach the hull's lowest point: nothing floats.
    #[error("draft {draft} m is below the keel (the lowest point of the hull is at z = {keel} m)")]
    DraftBelowKeel {
        /// The draft asked for (at midships).
        draft: f64,
        /// The lowest `z` of the surface.
        keel: f64,
    },
    /// The waterplane is above the top of the surface somewhere: the hull would fill over its
    /// open top (the deck edge) and no volume is bounded.
    #[error("the water at draft {draft} m is over the open top of the surface near ({x:.3}, {y:.3}, {z:.3}) m (its deck edge): the hull floods there")]
    DraftAboveTop {
        /// The draft asked for (at midships).
        draft: f64,
        /// Where the open top dips under the water, `x`.
        x: f64,
        /// `y` of that point.
        y: f64,
        /// `z` of that point.
        z: f64,
    },
    /// The surface is open below the water away from the centreplane: the volume it bounds is
    /// not a hull's. Names where.
    #[error("the surface has a hole below the waterline near ({x:.3}, {y:.3}, {z:.3}) m{curves}: close it (a missing patch, or a free edge off the centreplane) before reading its hydrostatics")]
    HoleBelowWater {
        /// `x` of a point on the hole's edge.
        x: f64,
        /// `y` of that point.
        y: f64,
        /// `z` of that point.
        z: f64,
        /// `", bounded by curves 'a', 'b'"` when the curves are known, else empty.
        curves: String,
    },
    /// The hull, at the flotation asked for, has no displacement or waterplane to divide by.
    #[error("{0}")]
    Degenerate(String),
    /// No flotation within the search gives the displacement and centre asked for.
    #[error("{0}")]
    NoEquilibrium(String),
}

impl HydroError {
    /// A hole error at `p` with the names of the curves around it (may be empty).
    pub(crate) fn hole(p: DVec3, curves: &[String]) -> HydroError {
        HydroError::HoleBelowWater {
            x: p.x,
            y: p.y,
            z: p.z,
            curves: if curves.is_empty() {
                String::new()
            } else {
                format!(", bounded by curves '{}'", curves.join("', '"))
            },
        }
    }

    /// A flooded-top error at `p`.
    pub(crate) fn above_top(draft: f64, p: DVec3) -> HydroError {
        HydroError::DraftAboveTop {
            draft,
            x: p.x,
            y: p.y,
            z: p.z,
        }
    }
}
