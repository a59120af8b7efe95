//! The findings of [`Topology::build`](super::Topology::build) that concern the network as a
//! whole (H-rep paper §3.1, §5.2): dangling branches and isolated curves, nodes and edges where
//! the surface branches, faces no patch method takes, and B-rep invariants that fail. Each
//! becomes a [`Diagnostic`] naming the curves and the place.

use std::collections::BTreeMap;

use glam::DVec3;

use super::brep::{Brep, HalfEdgeId};
use super::checks::ValidationError;
use super::topology::TopoFace;
use crate::diagnostic::Diagnostic;
use crate::network::{Junctions, NetworkCurve};

/// Faces with more corners than this are reported ([`Diagnostic::UnusualFace`]): the N-sided
/// patch of §3.2.1 degrades with many sides.
pub const MAX_NORMAL_CORNERS: usize = 8;
/// Faces with fewer corners than this are reported: no patch method of §3.2.1 takes them.
pub const MIN_CORNERS: usize = 3;

/// Dangling ends, isolated curves and edges bounding no face (`core[k]` is false for edge `k`
/// when it was pruned as a dangling branch).
pub(crate) fn loose_ends(
    curves: &[NetworkCurve],
    junctions: &Junctions,
    brep: &Brep,
    core: &[bool],
    diagnostics: &mut Vec<Diagnostic>,
) {
    let mut degree = vec![0usize; brep.vertices.len()];
    for e in &brep.edges {
        degree[e.start.index()] += 1;
        degree[e.end.index()] += 1;
    }
    let mut isolated = vec![false; curves.len()];
    for (ci, splits) in junctions.splits.iter().enumerate() {
        if junctions.excluded[ci] || splits.is_empty() {
            continue;
        }
        let alone = splits
            .iter()
            .all(|&(_, n)| junctions.nodes[n].incidences.iter().all(|i| i.curve == ci));
        if alone {
            isolated[ci] = true;
            diagnostics.push(Diagnostic::IsolatedCurve {
                curve: curves[ci].name.clone(),
                location: brep.vertices[splits[0].1].position,
            });
        }
    }
    for e in &brep.edges {
        if isolated[e.curve] {
            continue;
        }
        for v in [e.start, e.end] {
            if degree[v.index()] == 1 {
                diagnostics.push(Diagnostic::DanglingEnd {
                    curve: curves[e.curve].name.clone(),
                    location: brep.vertices[v.index()].position,
                });
            }
        }
    }
    // By curve, in curve order.
    let mut unused: BTreeMap<usize, UnusedEdges> = BTreeMap::new();
    for (k, e) in brep.edges.iter().enumerate() {
        if !core[k] && !isolated[e.curve] {
            let entry = unused.entry(e.curve).or_insert(UnusedEdges {
                edges: 0,
                location: brep.vertices[e.start.index()].position,
            });
            entry.edges += 1;
        }
    }
    for (c, UnusedEdges { edges, location }) in unused {
        diagnostics.push(Diagnostic::UnusedEdges {
            curve: curves[c].name.clone(),
            edges,
            location,
        });
    }
}

/// The edges of one curve that bound no face.
struct UnusedEdges {
    /// How many.
    edges: usize,
    /// The start of the first of them.
    location: DVec3,
}

/// A [`Diagnostic::NonManifoldNode`] at the origin of each of the `branching` half-edges.
pub(crate) fn non_manifold_nodes(
    curves: &[NetworkCurve],
    brep: &Brep,
    branching: &[HalfEdgeId],
    diagnostics: &mut Vec<Diagnostic>,
) {
    for h in branching {
        let v = brep.half_edges[h.index()].origin.index();
        diagnostics.push(Diagnostic::NonManifoldNode {
            curves: brep.vertices[v]
                .curves
                .iter()
                .map(|&c| curves[c].name.clone())
                .collect(),
            location: brep.vertices[v].position,
        });
    }
}

/// A [`Diagnostic::UnusualFace`] for each face with fewer than [`MIN_CORNERS`] or more than
/// [`MAX_NORMAL_CORNERS`] corners.
pub(crate) fn unusual_faces(
    curves: &[NetworkCurve],
    brep: &Brep,
    faces: &[TopoFace],
    diagnostics: &mut Vec<Diagnostic>,
) {
    for (i, f) in faces.iter().enumerate() {
        if f.corners < MIN_CORNERS || f.corners > MAX_NORMAL_CORNERS {
            let e = &brep.edges[f.edges[0].index()];
            diagnostics.push(Diagnostic::UnusualFace {
                face: i,
                corners: f.corners,
                curves: f.curves.iter().map(|&c| curves[c].name.clone()).collect(),
                location: brep.vertices[e.start.index()].position,
            });
        }
    }
}

/// Validate the B-rep ([`Brep::validate`]): every failure becomes a
/// [`Diagnostic::InvalidTopology`], an edge used by too many faces first also a
/// [`Diagnostic::NonManifoldEdge`] at its middle.
pub(crate) fn invalid_topology(
    curves: &[NetworkCurve],
    brep: &Brep,
    diagnostics: &mut Vec<Diagnostic>,
) {
    for err in brep.validate() {
        if let ValidationError::EdgeFaces(ref e) = err {
            let edge = &brep.edges[e.edge.index()];
            let mid = curves[edge.curve].curve.point(0.5 * (edge.t0 + edge.t1));
            diagnostics.push(Diagnostic::NonManifoldEdge {
                curve: curves[edge.curve].name.clone(),
                location: mid,
            });
        }
        diagnostics.push(Diagnostic::InvalidTopology {
            message: err.to_string(),
        });
    }
}
