//! What a hull must offer for its hydrostatics: the wet-surface integrals, plane sections and
//! its open boundary. Two kinds implement it: batten's patch surface
//! ([`PatchHydroModel`](super::PatchHydroModel)) and any triangle mesh
//! ([`TriangleHull`](super::TriangleHull)), so both give their figures through the same
//! assembly ([`hydrostatics`](super::hydrostatics)).

use glam::DVec3;

use super::integrals::WetIntegrals;
use super::waterplane::Waterplane;

/// One oriented piece of a plane section of the hull: from `a` to `b` along `m × n` (`m` the
/// plane's normal, `n` the hull's outward normal), so a closed section runs counter-clockwise
/// about `m` round the inside of the hull.
pub type SectionSegment = [DVec3; 2];

/// Where a free edge of the surface (or of its mirror image) lies relative to the water.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenEdgePoint {
    /// A point of the free edge.
    pub point: DVec3,
    /// The curves around it, where known.
    pub curves: Vec<String>,
    /// Whether the edge is the hull's designed open boundary (the deck edge, a transom or top
    /// outline) rather than a hole: under water it means the draft is above the top.
    pub designed: bool,
}

/// A hull surface whose hydrostatics can be computed. A half hull (port side, `y ≥ 0`, open
/// along the centreplane) answers for the whole ship: every method includes its mirror image.
pub trait HullGeometry: Sync {
    /// Integrals over the surface below `plane` (the water surface), both halves.
    fn wet_integrals(&self, plane: &Waterplane) -> WetIntegrals;

    /// The oriented pieces of the section of the surface (both halves) by the plane
    /// `{p : m·p = c}`, `m` a unit normal; accurate to within `tolerance` (m) of the surface.
    fn plane_section(&self, m: DVec3, c: f64, tolerance: f64) -> Vec<SectionSegment>;

    /// The smallest box holding the surface, both halves.
    fn bounds(&self) -> (DVec3, DVec3);

    /// Points of the surface's free edges that are not closed by the mirror image (for a half
    /// hull, every free edge off the centreplane), sampled densely enough to find where they are
    /// below a waterplane: the open top (deck edge), a dry transom outline, holes.
    fn open_edges(&self) -> &[OpenEdgePoint];

    /// Whether this is a half hull answered for both sides.
    fn is_half(&self) -> bool;

    /// The range of `dir·p` over the surface below `plane` (both halves), `dir` a unit vector:
    /// along `e1` its extent is the length of the submerged hull. `None` when nothing is below.
    fn wet_range(&self, plane: &Waterplane, dir: DVec3) -> Option<(f64, f64)>;
}
