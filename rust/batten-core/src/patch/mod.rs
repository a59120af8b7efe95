//! Surface patches on the faces of the curve network (H-rep paper §3.2): tangent ribbons from
//! the crossing curves (§3.2.2, eq. 8 and the 15° rule), the 4-sided Gregory patch and the
//! N-sided Charrot–Gregory patch (§3.2.1, eqs. 1–6), and a tessellation that samples each side
//! from its designer curve so neighbouring patches weld exactly.
//!
//! The module is independent of the topology: a face is a [`FaceBoundary`] (sides made of
//! [`SideSegment`]s of designer curves) plus one [`SideRibbon`] per side. The topology builds
//! those from its half-edge loops: for every edge it calls [`EdgeNormal::from_crossings`] once
//! with the tangents of the curves through the nodes on that edge (on a smooth edge the same
//! [`EdgeNormal`] then goes to both faces, which makes them GC¹ along the whole edge; on a
//! knuckle edge each face gets its own, built from its own side's crossing tangents only), and
//! gives node positions to the segments ([`SideSegment::with_nodes`]) so corners weld.
//!
//! Choices the paper leaves open, made here as a naval architect would expect:
//! - A side runs at arc length plus turning, not at its curves' own parameters (`speed`): a
//!   Bézier-segmented curve has one unit of parameter per piece, whatever its length, and a
//!   patch following that would crowd and crease its inside where the pieces are short.
//! - An edge's normal field turns with its curve's parameter, which crowds where a section
//!   turns, but at most `MAX_CROWDING` times faster than its mean rate along the edge
//!   (`field_key`): a fit crowds its parameter even more at a seam in its data, and a field
//!   turning there creased the faces beside it.
//! - The cross-derivative magnitude follows the neighbouring sides at the corners (linear in
//!   between): a long, narrow patch is not bulged by unit-length ribbons.
//! - A face whose corner-based patch folds can be given Kato's side-blended patch instead
//!   ([`PatchKind::SideBlend`], `side_blend`): the same boundary and ribbon planes, no corner
//!   interpolants, ribbons cut to the face's width. The hull build does so where it folds
//!   clearly less.
//! - Corners whose angle is within [`MIN_CORNER_ANGLE_DEGREES`] of 0° or 180° are repaired
//!   (the ribbon is turned to that angle) and reported as a [`PatchWarning`], not refused.
//! - A side of (nearly) zero length, a gap between sides larger than 10× the model tolerance,
//!   and non-finite input are refused with a [`PatchError`] naming the curves.

mod boundary;
mod charrot_gregory;
mod corner;
mod curvature;
mod domain;
mod error;
mod face_patch;
mod field_key;
mod gregory4;
mod hermite;
mod ribbon;
mod side_blend;
mod speed;
mod tessellate;

pub use boundary::{FaceBoundary, Side, SideParam, SideSegment};
pub use curvature::SurfaceCurvature;
pub(crate) use curvature::{central_differences, stencil_fits};
pub use domain::{Domain, MAX_SIDES};
pub use error::{PatchError, PatchWarning};
pub use face_patch::{Patch, PatchKind, PatchOptions};
pub(crate) use ribbon::CUSP_DEGREES;
pub use ribbon::{
    gram_schmidt_cross_tangent, EdgeNormal, RibbonNode, SideRibbon, MIN_CORNER_ANGLE_DEGREES,
    MIN_CROSSING_ANGLE_DEGREES,
};
pub use tessellate::{tessellate_patches, SurfaceMesh};
pub(crate) use tessellate::{weld_face_meshes_with, FaceMesh, Weld};
