//! Step 3 of [`Topology::build`](super::Topology::build): two half-edges for every edge that
//! can bound a region (H-rep paper §3.1: "the two possible orientations of a physical edge"),
//! with the direction in which each leaves its origin.

use glam::DVec3;
use rayon::prelude::*;

use super::brep::{Brep, Edge, EdgeId, HalfEdge, HalfEdgeId, LoopId};
use super::rotation::{leaving_direction, EvalCache};
use crate::curve::BezierDecomposition;

/// Half-edges per parallel run of direction evaluations.
const PAR_HALF_EDGES: usize = 1024;

/// The half-edges of a B-rep that has none yet: two for every edge with `core[k]` (the first
/// runs along the edge's curve, from `t0` to `t1`, the second against it), each for now its
/// own `next` and `prev`, in loop 0; and, per half-edge, the unit direction in which it leaves
/// its origin. It only reads the edges, so the topology works out the edges' area shares
/// beside it; [`attach`] then puts the half-edges in the B-rep.
pub(crate) fn half_edges(
    edges: &[Edge],
    core: &[bool],
    evals: &[BezierDecomposition],
) -> (Vec<HalfEdge>, Vec<DVec3>) {
    let core_edges = core.iter().filter(|&&c| c).count();
    let mut half_edges: Vec<HalfEdge> = Vec::with_capacity(2 * core_edges);
    // Per half-edge: its curve and the stretch it leaves along, from → to.
    let mut leaving: Vec<(usize, f64, f64)> = Vec::with_capacity(2 * core_edges);
    for (k, e) in edges.iter().enumerate() {
        if !core[k] {
            continue;
        }
        let a = HalfEdgeId::from_index(half_edges.len());
        let b = HalfEdgeId::from_index(half_edges.len() + 1);
        for (h, origin, twin, from, to) in [(a, e.start, b, e.t0, e.t1), (b, e.end, a, e.t1, e.t0)]
        {
            half_edges.push(HalfEdge {
                origin,
                twin,
                next: h,
                prev: h,
                edge: EdgeId::from_index(k),
                loop_id: LoopId(0),
            });
            leaving.push((e.curve, from, to));
        }
    }
    // The directions, in parallel runs of consecutive half-edges (each run with its own cache:
    // consecutive edges of one curve share their node's evaluation).
    let dirs = leaving
        .par_chunks(PAR_HALF_EDGES)
        .flat_map_iter(|run| {
            let mut cache = EvalCache::default();
            run.iter().map(move |&(curve, from, to)| {
                cache.on_curve(curve);
                leaving_direction(&evals[curve], from, to, &mut cache)
            })
        })
        .collect();
    (half_edges, dirs)
}

/// Put the half-edges of [`half_edges`] into `brep` (which has none yet), each edge told its
/// pair.
pub(crate) fn attach(brep: &mut Brep, half_edges: Vec<HalfEdge>) {
    debug_assert!(brep.half_edges.is_empty(), "a B-rep without half-edges");
    for (k, pair) in half_edges.chunks_exact(2).enumerate() {
        let ids = [2 * k, 2 * k + 1].map(HalfEdgeId::from_index);
        brep.edges[pair[0].edge.index()].half_edges = Some(ids);
    }
    brep.half_edges = half_edges;
}
