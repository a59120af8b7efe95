//! Step 4 of [`Topology::build`](super::Topology::build): the rotation system (H-rep paper
//! §5.2, see [`super::rotation`]) — a surface normal at every node, oriented consistently over
//! the network, the half-edges leaving each node sorted counter-clockwise about it — and from
//! it every half-edge's `next` and `prev`: next is the edge immediately clockwise from the
//! twin.

use glam::DVec3;
use rayon::prelude::*;

use super::brep::{Brep, HalfEdgeId};
use super::orientation::{orient_normals, Step};
use super::rotation::{ccw_order, confidence, off_plane, raw_normal, tip_plane, RawNormal};
use crate::adjacency::Adjacency;
use crate::curve::BezierDecomposition;

/// A node whose unit edge tangents have a tip farther than this from the best plane through
/// the tips is a branching of the surface
/// ([`Diagnostic::NonManifoldNode`](crate::Diagnostic::NonManifoldNode), H-rep §3.1: faces
/// form a manifold shell). In one smooth surface the tips lie in the tangent plane (0); at a
/// cone-like corner they lie in a plane across the cone (0); where three sheets branch off one
/// curve the farthest tip is 0.75 from the best plane.
pub const BRANCHING_TIP_DISTANCE: f64 = 0.6;

/// Edges leaving a node with the same tangent are ordered by the direction to their point
/// this fraction of their parameter interval along (a quarter: far enough to bend apart, near
/// enough to stay on the node's side of the edge).
const TIE_BREAK_FRACTION: f64 = 0.25;

/// Nodes per parallel task at least (the per-node work is a few microseconds).
const PAR_MIN_NODES: usize = 256;

/// What the rotation system leaves for the later steps.
pub(crate) struct RotationSystem {
    /// Per vertex: the unoriented normal from its tangents, `None` when they are all
    /// parallel.
    pub raw: Vec<Option<RawNormal>>,
    /// Per vertex: the oriented unit normal (zero for vertices without half-edges).
    pub normals: Vec<DVec3>,
    /// Per vertex: the vertices its half-edges lead to, in the order they were made.
    pub neighbours: Adjacency<usize>,
    /// One half-edge leaving each node where the surface branches
    /// ([`BRANCHING_TIP_DISTANCE`]).
    pub branching: Vec<HalfEdgeId>,
}

/// Estimate and orient the normals, sort every node's half-edges counter-clockwise (setting
/// each vertex's `outgoing` and `normal`) and link the half-edges into loops. `dirs` holds the
/// leaving direction of every half-edge, `evals` the network's curves.
pub(crate) fn link(
    brep: &mut Brep,
    dirs: &[DVec3],
    evals: &[BezierDecomposition],
) -> RotationSystem {
    // The half-edges leaving each vertex, in the order they were made.
    let mut outgoing = Adjacency::from_pairs(
        brep.vertices.len(),
        brep.half_edges
            .iter()
            .enumerate()
            .map(|(i, he)| (he.origin.index(), HalfEdgeId::from_index(i))),
    );

    // Per vertex, in parallel: the raw normal, and whether the surface branches there.
    let per_vertex: Vec<(Option<RawNormal>, bool)> = (0..outgoing.rows())
        .into_par_iter()
        .with_min_len(PAR_MIN_NODES)
        .map_init(Vec::new, |ts: &mut Vec<DVec3>, v| {
            let hs = outgoing.row(v);
            ts.clear();
            ts.extend(hs.iter().map(|h| dirs[h.index()]));
            let plane = tip_plane(ts);
            let branches = off_plane(ts, plane) > BRANCHING_TIP_DISTANCE;
            let raw = raw_normal(ts, plane).map(|normal| RawNormal {
                normal,
                confidence: confidence(ts),
            });
            (raw, branches)
        })
        .collect();
    let branching: Vec<HalfEdgeId> = per_vertex
        .iter()
        .enumerate()
        .filter(|(_, &(_, branches))| branches)
        .map(|(v, _)| outgoing.row(v)[0])
        .collect();
    let raw: Vec<Option<RawNormal>> = per_vertex.into_iter().map(|(raw, _)| raw).collect();
    let neighbours = outgoing.map(|h| brep.destination(h).index());
    let normals = orient_normals(&raw, &outgoing, &neighbours, |h| Step {
        to: brep.destination(h).index(),
        leaving: dirs[h.index()],
        arriving: -dirs[brep.half_edge(h).twin.index()],
    });

    // Each node's half-edges sorted counter-clockwise, the nodes in parallel.
    let brep_ref = &*brep;
    outgoing
        .rows_mut()
        .into_par_iter()
        .zip(normals.par_iter())
        .with_min_len(PAR_MIN_NODES)
        .for_each_init(
            || (Vec::new(), Vec::new(), Vec::new(), Vec::new()),
            |(keys, order, hs, ts), (row, &normal)| {
                if row.is_empty() {
                    return;
                }
                hs.clear();
                hs.extend_from_slice(row);
                ts.clear();
                ts.extend(hs.iter().map(|h: &HalfEdgeId| dirs[h.index()]));
                // Edges leaving with the same tangent are told apart further along the edge.
                let further = |i: usize| {
                    let h: HalfEdgeId = hs[i];
                    let he = &brep_ref.half_edges[h.index()];
                    let e = &brep_ref.edges[he.edge.index()];
                    let (from, to) = if he.origin == e.start {
                        (e.t0, e.t1)
                    } else {
                        (e.t1, e.t0)
                    };
                    let c = &evals[e.curve];
                    (c.point(from + TIE_BREAK_FRACTION * (to - from)) - c.point(from))
                        .normalize_or_zero()
                };
                ccw_order(normal, ts, &further, keys, order);
                for (slot, &k) in row.iter_mut().zip(order.iter()) {
                    *slot = hs[k];
                }
            },
        );
    let mut position_in_rotation = vec![0usize; brep.half_edges.len()];
    for (v, &normal) in normals.iter().enumerate() {
        let row = outgoing.row(v);
        if row.is_empty() {
            continue;
        }
        for (i, h) in row.iter().enumerate() {
            position_in_rotation[h.index()] = i;
        }
        brep.vertices[v].outgoing = Some(row[0]);
        brep.vertices[v].normal = normal;
    }
    for i in 0..brep.half_edges.len() {
        let twin = brep.half_edges[i].twin;
        let v = brep.half_edges[twin.index()].origin.index();
        let rot = outgoing.row(v);
        let next = rot[(position_in_rotation[twin.index()] + rot.len() - 1) % rot.len()];
        brep.half_edges[i].next = next;
        brep.half_edges[next.index()].prev = HalfEdgeId::from_index(i);
    }

    RotationSystem {
        raw,
        normals,
        neighbours,
        branching,
    }
}
