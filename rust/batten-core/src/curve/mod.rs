//! The curve kernel: B-spline and NURBS curves and the operations hull design needs on them.
//!
//! Algorithms follow Piegl & Tiller, *The NURBS Book* (2nd ed.): span search (A2.1), basis
//! functions (A2.2) and their derivatives (A2.3), rational derivatives (A4.2, eq. 4.8), knot
//! insertion (A5.1). Closest points and bounding boxes work on the Bézier decomposition with
//! branch and bound, so they are global, not local.

mod arclen;
mod basis;
mod bbox;
mod bezier;
mod corners;
mod edit;
mod error;
mod layout;
mod nearest;
mod nurbs;
mod piece;
mod through;
pub(crate) use through::{cholesky_solve, rational_basis, smooth_joint_rows, JOINT_ROW_WIDTH};

pub(crate) use arclen::GL8;
pub use basis::MAX_DEGREE;
// The fairing module builds least-squares rows from the same basis functions.
pub(crate) use basis::{basis_funs, ders_basis_funs, find_span, MAX_ORDER};
pub use bbox::Aabb;
pub use bezier::BezierDecomposition;
pub use error::CurveError;
pub use layout::KnotLayout;
pub use nearest::Nearest;
pub use nurbs::{CurveDerivs, NurbsCurve};
pub(crate) use piece::{segment_distance, BezierPiece, PointDerivs, TangentCone};
