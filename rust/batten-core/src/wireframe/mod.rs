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
//!   curve, as little as possible, through the nodes its data allow.

mod chines;
mod data_nodes;
mod needles;
mod snap;
#[cfg(test)]
mod test_curves;
mod transom;

pub use chines::chines_from_knuckles;
pub use data_nodes::{nodes_from_data, DataNode, NodedPoints};
pub use snap::{snap_to_nodes, CurveSnap, SnapData, SnappedNetwork};
