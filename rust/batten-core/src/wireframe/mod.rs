//! Wireframe import (H-rep paper §3.2.3 and the wireframe import of §4): from curves fitted
//! one by one to measured or digitised points, to one consistent network whose curves meet
//! exactly where they cross (Ye & Nowacki 1995: curve compatibility at the nodes).
//!
//! - [`data_nodes`]: where the point curves meet, found on the data before the fit, one point
//!   per node that every curve through it takes among its points; [`needles`] cuts a section
//!   end that runs into a needle along another curve back to its last node.
//! - [`chines`]: knuckle curves joining the knuckles of consecutive sections; [`transom`]
//!   carries a chain lying in one plane (a transom's edge) on to that plane's other knuckles.
//! - [`snap`]: find the nodes of the network at the data's capture distance and move every
//!   curve, as little as possible, through the nodes its data allow, with its tangent at each
//!   smooth node turned into the plane of every tangent there ([`tangents`]).

mod chines;
mod data_nodes;
mod needles;
mod snap;
mod tangents;
#[cfg(test)]
mod test_curves;
mod transom;

use glam::DVec3;

use crate::error::Error;
use crate::tolerance::Tolerance;

pub use chines::chines_from_knuckles;
pub use data_nodes::{DataNode, NodedPoints};
pub use snap::{snap_to_nodes, CurveSnap, SmoothNodeReport, SnapData, SnappedNetwork};
pub use tangents::MAX_TANGENT_TURN_DEGREES;

/// The point curves `points` with the nodes where they meet among their points, and the
/// nodes (H-rep paper §3.2.3, Ye & Nowacki 1995: found on the polylines before any fit,
/// clustered, one point each), with every section end that runs into a needle beside another
/// curve at a grazing angle cut back to its last node (the `needles` module). `tolerance` (m)
/// is the data's: how far a sample may be from the true curve; `corner_angle` (radians) the
/// turn above which a polyline has a knuckle (None: every turn is curvature); a node within
/// `model_tolerance` of a sample takes the sample's place. A curve with fewer than two points
/// or a non-finite point takes no part (its fit names it).
///
/// Errors: a tolerance that is not positive and finite ([`Error::Tolerance`]).
pub fn nodes_from_data(
    points: &[Vec<DVec3>],
    tolerance: f64,
    corner_angle: Option<f64>,
    model_tolerance: Tolerance,
) -> Result<NodedPoints, Error> {
    let noded = data_nodes::nodes_from_data(points, tolerance, corner_angle, model_tolerance)?;
    Ok(needles::without_needle_ends(noded, 2.0 * tolerance))
}
