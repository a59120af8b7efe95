//! What a hull must offer for its hydrostatics: the wet-surface integrals, plane sections and
//! its open boundary. Two kinds implement it: batten's patch surface
//! ([`PatchHydroModel`](super::PatchHydroModel)) and any triangle mesh
//! ([`TriangleHull`](super::TriangleHull)), so both give their figures through the same
//! assembly ([`hydrostatics`](super::hydrostatics)).

use glam::DVec3;

use super::integrals::WetIntegrals;
use super::waterplane::Waterplane;

/// How far to starboard (as a fraction of its greatest `y`) a surface open along the centreplane
/// may reach and still be a port half: a patch folding a little across the centreplane (a
/// forefoot's fit hooking back) is a defect the build report names, not a second side.
pub const HALF_HULL_SLACK: f64 = 0.05;

/// Whether a surface spanning `min_y ..= max_y`, with free edges in the centreplane or not, is a
/// port half answered for both sides.
pub fn is_port_half(min_y: f64, max_y: f64, open_on_centreplane: bool) -> bool {
    open_on_centreplane && max_y > 0.0 && min_y >= -HALF_HULL_SLACK * max_y
}

/// One oriented piece of a plane section of the hull: from `a` to `b` along `m × n` (`m` the
/// plane's normal, `n` the hull's outward normal), so a closed section runs counter-clockwise
/// about `m` round the inside of the hull.
pub type SectionSegment = [DVec3; 2];

/// A plane section's piece as an arc: its start, the section's point halfway along it, and its
/// end (oriented as [`SectionSegment`]); the parabola through them follows the section to
/// fourth order, so areas by Simpson's rule on arcs converge much faster than on chords.
pub type SectionArc = [DVec3; 3];

/// A chain of the surface's free edges that its mirror image does not close (for a half hull,
/// every free edge off the centreplane): the deck edge, an open transom's outline, a hole's rim.
/// Under water, a chain lying in one steep plane is closed by that plane (an open transom, as
/// section-based hydrostatics close it); any other is a hole.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OpenChain {
    /// The chain's points in order along it.
    pub points: Vec<DVec3>,
    /// Whether the last point joins the first (a loop).
    pub closed: bool,
    /// The curves around it, where known.
    pub curves: Vec<String>,
}

/// A hull surface whose hydrostatics can be computed. A half hull (port side, `y ≥ 0`, open
/// along the centreplane) answers for the whole ship: every method includes its mirror image.
pub trait HullGeometry: Sync {
    /// Integrals over the surface below `plane` (the water surface), both halves.
    fn wet_integrals(&self, plane: &Waterplane) -> WetIntegrals;

    /// The oriented pieces of the section of the surface (both halves) by the plane
    /// `{p : m·p = c}`, `m` a unit normal; accurate to within `tolerance` (m) of the surface.
    fn plane_section(&self, m: DVec3, c: f64, tolerance: f64) -> Vec<SectionSegment>;

    /// The pieces of the same section as arcs (the default: each segment with its chord's
    /// middle, exact for a mesh).
    fn section_arcs(&self, m: DVec3, c: f64, tolerance: f64) -> Vec<SectionArc> {
        self.plane_section(m, c, tolerance)
            .into_iter()
            .map(|[a, b]| [a, 0.5 * (a + b), b])
            .collect()
    }

    /// The pieces of the same section that can reach below the water surface `plane`: pieces
    /// wholly above it may be left out, as they add nothing to an immersed area (the default
    /// leaves none out).
    fn section_arcs_below(
        &self,
        m: DVec3,
        c: f64,
        tolerance: f64,
        _plane: &Waterplane,
    ) -> Vec<SectionArc> {
        self.section_arcs(m, c, tolerance)
    }

    /// The smallest box holding the surface, both halves.
    fn bounds(&self) -> (DVec3, DVec3);

    /// The chains of free edges not closed by the mirror image (for a half hull, every free
    /// edge off the centreplane), their points dense enough to follow the edge: the open top
    /// (deck edge), a transom outline, holes.
    fn open_chains(&self) -> &[OpenChain];

    /// Whether this is a half hull answered for both sides.
    fn is_half(&self) -> bool;

    /// The range of `dir·p` over the surface below `plane` (both halves), `dir` a unit vector:
    /// along `e1` its extent is the length of the submerged hull. `waterline` is the section of
    /// the surface by `plane` (from [`HullGeometry::plane_section`]), which bounds the wet part.
    /// `None` when nothing is below.
    fn wet_range(
        &self,
        plane: &Waterplane,
        dir: DVec3,
        waterline: &[SectionSegment],
    ) -> Option<(f64, f64)>;
}
