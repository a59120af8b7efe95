//! Step 2 of [`Topology::build`](super::Topology::build): each designer curve cut at its nodes
//! into edges, parameter intervals `[t0, t1]` of the curve (H-rep paper §3.1: the designer's
//! curve stays the fundamental entity), and the edges that can bound a region.

use super::brep::{Brep, Edge, Vertex, VertexId};
use crate::adjacency::Adjacency;
use crate::network::{Junctions, NetworkCurve};
use crate::tolerance::Tolerance;

/// The curve stretches between consecutive nodes of every curve, curve by curve. Left out:
/// curves the junctions exclude, stretches another curve carries (an overlap), and a stretch
/// from a node back to itself that never leaves the node by more than the tolerance.
pub(crate) fn cut_curves(
    curves: &[NetworkCurve],
    junctions: &Junctions,
    vertices: &[Vertex],
    tolerance: Tolerance,
) -> Vec<Edge> {
    let tol = tolerance.get();
    let mut edges = Vec::with_capacity(
        junctions
            .splits
            .iter()
            .map(|s| s.len().saturating_sub(1))
            .sum(),
    );
    for (ci, splits) in junctions.splits.iter().enumerate() {
        if junctions.excluded[ci] {
            continue;
        }
        let curve = &curves[ci].curve;
        for w in splits.windows(2) {
            let ((t0, n0), (t1, n1)) = (w[0], w[1]);
            if t1 <= t0 {
                continue;
            }
            let tm = 0.5 * (t0 + t1);
            if junctions
                .suppressed
                .iter()
                .any(|&(c, lo, hi)| c == ci && tm > lo && tm < hi)
            {
                continue; // another curve carries this shared stretch
            }
            if n0 == n1 {
                let mid = curve.point(tm);
                if (mid - vertices[n0].position).length() <= tol {
                    continue; // a sub-tolerance wiggle, not a loop
                }
            }
            edges.push(Edge {
                curve: ci,
                t0,
                t1,
                start: VertexId::from_index(n0),
                end: VertexId::from_index(n1),
                half_edges: None,
            });
        }
    }
    edges
}

/// Edges that can bound a region: repeatedly drop edges with an end no other edge touches.
pub(crate) fn prune_branches(brep: &Brep) -> Vec<bool> {
    // Most networks have no dangling end: then every edge stays, and no adjacency is needed.
    let mut ends = vec![0u32; brep.vertices.len()];
    for e in &brep.edges {
        ends[e.start.index()] += 1;
        ends[e.end.index()] += 1;
    }
    if !ends.contains(&1) {
        return vec![true; brep.edges.len()];
    }
    let at = Adjacency::from_pairs(
        brep.vertices.len(),
        brep.edges
            .iter()
            .enumerate()
            .flat_map(|(k, e)| [(e.start.index(), k), (e.end.index(), k)]),
    );
    let mut degree: Vec<usize> = (0..at.rows()).map(|v| at.row(v).len()).collect();
    let mut core = vec![true; brep.edges.len()];
    let mut stack: Vec<usize> = (0..degree.len()).filter(|&v| degree[v] == 1).collect();
    while let Some(v) = stack.pop() {
        if degree[v] != 1 {
            continue;
        }
        let Some(&k) = at.row(v).iter().find(|&&k| core[k]) else {
            continue;
        };
        core[k] = false;
        let e = &brep.edges[k];
        for w in [e.start.index(), e.end.index()] {
            degree[w] -= 1;
            if degree[w] == 1 {
                stack.push(w);
            }
        }
    }
    core
}
