//! Wireframe import (H-rep paper §3.2.3 and the wireframe import of §4): from curves fitted
//! one by one to measured or digitised points, to one consistent network whose curves meet
//! exactly where they cross (Ye & Nowacki 1995: curve compatibility at the nodes).
//!
//! - [`chines`]: knuckle curves joining the knuckles of consecutive sections.
//! - [`snap`]: find the nodes of the network at the data's capture distance and move every
//!   curve, as little as possible, through the nodes its data allow.

mod chines;
mod snap;

pub use chines::chines_from_knuckles;
pub use snap::{snap_to_nodes, CurveSnap, SnapData, SnappedNetwork};
