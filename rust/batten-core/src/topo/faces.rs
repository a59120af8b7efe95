//! The geometry of the loops of the rotation system (traced and sorted in [`super::loops`]):
//! a loop's vector area against the node normals, which tells a face from a boundary loop,
//! whether it runs along an edge twice, and each face's true corners and sides (H-rep paper
//! §3.1 loops and faces, §5.2 three-, four- and N-sided patches).

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::brep::{Brep, EdgeId, HalfEdgeId, LoopId};
use crate::curve::BezierDecomposition;

/// The boundary of a face runs on smoothly through a node (no corner) when its direction turns
/// by less than this (15°, the H-rep paper's minimum angle between tangents, §3.2.2).
pub const CORNER_ANGLE_DEGREES: f64 = 15.0;

/// Samples per loop for its vector area, at least (a loop of one or two curved edges needs
/// points inside its edges to have an area at all)…
const AREA_SAMPLES_PER_LOOP: usize = 8;
/// …and per edge.
const AREA_SAMPLES_PER_EDGE: usize = 2;

/// Edges per parallel task in [`edge_areas`] at least (one curve evaluation each).
const PAR_MIN_EDGES: usize = 512;

/// One side of a face: the edges between two true corners, and the designer curves along it
/// (H-rep paper §5.2: the system resolves "the number of edges bounding a patch").
#[derive(Clone, Debug, PartialEq)]
pub struct FaceSide {
    /// The edges of the side, in loop order.
    pub edges: SmallVec<[EdgeId; 2]>,
    /// The designer curves along the side (indices into the network), in order, without
    /// consecutive repeats.
    pub curves: SmallVec<[usize; 2]>,
}

/// The unit direction in which half-edge `h` leaves its origin.
pub(crate) fn leaving(brep: &Brep, dirs: &[DVec3], h: HalfEdgeId) -> DVec3 {
    debug_assert!(h.index() < brep.half_edges.len(), "half-edge in range");
    dirs[h.index()]
}

/// True when a loop turns by [`CORNER_ANGLE_DEGREES`] or more at the vertex between `h_in`
/// and `h_out`: the cosine of the turn, from the unit leaving directions, against the cosine
/// of the limit (no arc cosine per vertex). A missing (zero) direction makes no corner.
pub(crate) fn turns_at_corner(
    brep: &Brep,
    dirs: &[DVec3],
    h_in: HalfEdgeId,
    h_out: HalfEdgeId,
    cos_limit: f64,
) -> bool {
    let arriving = -leaving(brep, dirs, brep.half_edge(h_in).twin);
    let out = leaving(brep, dirs, h_out);
    let cos = arriving.dot(out) / (arriving.length_squared() * out.length_squared()).sqrt();
    cos <= cos_limit
}

/// Corners and sides of a loop: a vertex is a corner when the boundary turns there by at least
/// [`CORNER_ANGLE_DEGREES`]; a T-joint seen from the through-curve's side, or a node where
/// one curve is split, is not a corner, so that side is a composite of several edges.
///
/// `corner` is a work buffer.
pub(crate) fn corners_and_sides(
    brep: &Brep,
    dirs: &[DVec3],
    half_edges: &[HalfEdgeId],
    corner: &mut Vec<bool>,
) -> (usize, SmallVec<[FaceSide; 4]>) {
    let n = half_edges.len();
    let cos_limit = CORNER_ANGLE_DEGREES.to_radians().cos();
    // corner[i]: the vertex where half_edges[i] starts is a corner.
    corner.clear();
    corner.extend((0..n).map(|i| {
        turns_at_corner(
            brep,
            dirs,
            half_edges[(i + n - 1) % n],
            half_edges[i],
            cos_limit,
        )
    }));
    let count = corner.iter().filter(|&&c| c).count();
    let start = corner.iter().position(|&c| c).unwrap_or(0);
    let mut sides: SmallVec<[FaceSide; 4]> = SmallVec::with_capacity(count.max(1));
    for k in 0..n {
        let i = (start + k) % n;
        if k == 0 || corner[i] {
            // The side runs to the next corner: size its edge list once.
            let len = (1..n)
                .position(|j| corner[(i + j) % n])
                .map_or(n - k, |j| j + 1);
            sides.push(FaceSide {
                edges: SmallVec::with_capacity(len),
                curves: SmallVec::new(),
            });
        }
        let side = sides.last_mut().expect("a side was opened");
        let edge = brep.half_edge(half_edges[i]).edge;
        side.edges.push(edge);
        let curve = brep.edges[edge.index()].curve;
        if side.curves.last() != Some(&curve) {
            side.curves.push(curve);
        }
    }
    (count, sides)
}

/// Vector area `½ ∮ p × dp` of a loop, from points sampled along its edges, and the sum of its
/// vertices' normals. Their dot product is positive for a face (counter-clockwise about the
/// normals) and negative for a boundary loop traced round the outside.
pub(crate) fn orientation(
    brep: &Brep,
    curves: &[BezierDecomposition],
    normals: &[DVec3],
    l: LoopId,
) -> (DVec3, DVec3) {
    let hs = brep.loop_half_edges(l);
    let origin = brep.vertices[brep.half_edge(hs[0]).origin.index()].position;
    let mut area = DVec3::ZERO;
    let mut normal = DVec3::ZERO;
    let mut prev: Option<DVec3> = None;
    let samples = AREA_SAMPLES_PER_EDGE.max(AREA_SAMPLES_PER_LOOP.div_ceil(hs.len()));
    for &h in &hs {
        let he = brep.half_edge(h);
        normal += normals[he.origin.index()];
        let e = &brep.edges[he.edge.index()];
        let curve = &curves[e.curve];
        let (a, b) = if brep.is_forward(h) {
            (e.t0, e.t1)
        } else {
            (e.t1, e.t0)
        };
        for k in 0..samples {
            let t = a + (b - a) * k as f64 / samples as f64;
            let p = curve.point(t) - origin;
            if let Some(q) = prev {
                area += 0.5 * q.cross(p);
            }
            prev = Some(p);
        }
    }
    if let Some(q) = prev {
        area += 0.5 * q.cross(DVec3::ZERO);
    }
    (area, normal)
}

/// Each edge's share `½ ∫ p × dp` of the vector area of any loop along it (forward
/// direction), from the polyline through its end vertices and its middle point; zero for edges
/// that bound no region (`core[k]` false: they get no half-edges). Shares of the edges of a
/// loop add up to the loop's vector area, because the polylines of consecutive edges meet at
/// the shared vertex.
pub(crate) fn edge_areas(brep: &Brep, core: &[bool], curves: &[BezierDecomposition]) -> Vec<DVec3> {
    brep.edges
        .par_iter()
        .zip(core.par_iter())
        .with_min_len(PAR_MIN_EDGES)
        .map(|(e, &core)| {
            if !core {
                return DVec3::ZERO;
            }
            let a = brep.vertices[e.start.index()].position;
            let b = brep.vertices[e.end.index()].position;
            let m = curves[e.curve].point(0.5 * (e.t0 + e.t1));
            0.5 * (a.cross(m) + m.cross(b))
        })
        .collect()
}

/// Vector area and normal sum of a loop from the edge shares of [`edge_areas`]; loops of one
/// or two edges (whose three-point polylines may enclose nothing) are sampled more finely.
pub(crate) fn loop_orientation(
    brep: &Brep,
    curves: &[BezierDecomposition],
    areas: &[DVec3],
    normals: &[DVec3],
    l: LoopId,
    half_edges: &[HalfEdgeId],
) -> (DVec3, DVec3) {
    if half_edges.len() <= 2 {
        return orientation(brep, curves, normals, l);
    }
    let mut area = DVec3::ZERO;
    let mut normal = DVec3::ZERO;
    for &h in half_edges {
        let he = brep.half_edge(h);
        normal += normals[he.origin.index()];
        let share = areas[he.edge.index()];
        area += if brep.is_forward(h) { share } else { -share };
    }
    (area, normal)
}

/// Loops up to this many edges are checked for a repeated edge pair by pair; longer ones
/// (boundary loops) through a sorted copy.
const BRIDGE_PAIRWISE: usize = 16;

/// True when a loop runs along some edge on both sides (it then bounds no disk).
pub(crate) fn has_bridge(brep: &Brep, half_edges: &[HalfEdgeId]) -> bool {
    let edge = |h: &HalfEdgeId| brep.half_edge(*h).edge;
    if half_edges.len() <= BRIDGE_PAIRWISE {
        let es: SmallVec<[EdgeId; BRIDGE_PAIRWISE]> = half_edges.iter().map(edge).collect();
        es.iter().enumerate().any(|(i, e)| es[i + 1..].contains(e))
    } else {
        let mut es: Vec<EdgeId> = half_edges.iter().map(edge).collect();
        es.sort_unstable();
        es.windows(2).any(|w| w[0] == w[1])
    }
}
