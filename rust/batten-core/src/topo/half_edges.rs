//! Step 3 of [`Topology::build`](super::Topology::build): two half-edges for every edge that
//! can bound a region (H-rep paper §3.1: "the two possible orientations of a physical edge"),
//! with the direction in which each leaves its origin.

use glam::DVec3;

use super::brep::{Brep, EdgeId, HalfEdge, HalfEdgeId, LoopId};
use super::rotation::{leaving_direction, EvalCache};
use crate::curve::BezierDecomposition;

/// Give every edge with `core[k]` its two half-edges (the first runs along the edge's curve,
/// from `t0` to `t1`, the second against it), each for now its own `next` and `prev`, in loop
/// 0. Returns, per half-edge, the unit direction in which it leaves its origin.
pub(crate) fn add_half_edges(
    brep: &mut Brep,
    core: &[bool],
    evals: &[BezierDecomposition],
) -> Vec<DVec3> {
    let core_edges = core.iter().filter(|&&c| c).count();
    brep.half_edges.reserve_exact(2 * core_edges);
    let mut dirs: Vec<DVec3> = Vec::with_capacity(2 * core_edges);
    let mut cache = EvalCache::default();
    for (k, e) in brep.edges.iter_mut().enumerate() {
        if !core[k] {
            continue;
        }
        let curve = &evals[e.curve];
        cache.on_curve(e.curve);
        let a = HalfEdgeId::from_index(brep.half_edges.len());
        let b = HalfEdgeId::from_index(brep.half_edges.len() + 1);
        for (h, origin, twin, from, to) in [(a, e.start, b, e.t0, e.t1), (b, e.end, a, e.t1, e.t0)]
        {
            brep.half_edges.push(HalfEdge {
                origin,
                twin,
                next: h,
                prev: h,
                edge: EdgeId::from_index(k),
                loop_id: LoopId(0),
            });
            dirs.push(leaving_direction(curve, from, to, &mut cache));
        }
        e.half_edges = Some([a, b]);
    }
    dirs
}
