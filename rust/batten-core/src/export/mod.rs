//! What leaves batten for CAD: every patch of the hull surface approximated by bicubic
//! B-spline faces within a tolerance (0.1 mm by default), neighbours meeting on the same
//! curves, written as IGES 5.3 (entity 128) or STEP AP214 text; the control nets themselves
//! go to the binding for Rhino's `.3dm`.
//!
//! - [`bspline`]: the B-spline surface type and exact curve operations (split, join, knot
//!   insertion).
//! - [`fit`]: least-squares curve and surface fits refined until within their tolerance.
//! - [`quads`]: the four-sided pieces a patch is exported as.
//! - [`surface`]: the hull's patches as faces ([`cad_surface`]).
//! - [`iges`], [`step`]: the file texts; [`text`]: numbers, names and dates in them.
//! - [`error`]: why an export could not be made.
//!
//! The modules depend on each other one way: `iges`, `step` → `surface` → `fit` → `bspline`,
//! `surface` → `quads`, and `text`, `error` at the bottom.

mod bspline;
mod error;
mod fit;
mod iges;
mod quads;
mod step;
mod surface;
mod text;

pub use bspline::{BsplineSurface, EXPORT_DEGREE, KNOT_MERGE};
pub use error::{ExportError, UnfittedFace, UnfittedFaces};
pub use fit::{MAX_CURVE_SPANS, MAX_SURFACE_CELLS, MAX_SURFACE_SPANS};
pub use iges::iges_text;
pub use step::step_text;
pub use surface::{
    cad_surface, cad_surface_with, CadFace, CadSurface, ExportOptions, BOUNDARY_SHARE,
    DEFAULT_EXPORT_TOLERANCE, FACE_SHARE,
};
pub use text::{CadHeader, Timestamp};
