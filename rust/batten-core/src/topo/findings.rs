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
use crate::network::{Junctions, NetworkCurve, Role};

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

/// Sheets meeting along a knuckle curve at a node are told apart by the direction in which
/// they leave it, about the knuckle's tangent: directions closer than this (degrees) are one
/// sheet.
const SHEET_GAP_DEGREES: f64 = 30.0;

/// A [`Diagnostic::NonManifoldNode`] at the origin of each of the `branching` half-edges
/// (leaving directions `dirs`), except where a knuckle curve runs through the node and the
/// other edges leave it in at most two sheets about the knuckle: the two faces of a crease
/// (a boss's flat end meeting its side, where the line across the end and the line along the
/// side meet the edge at one point) are one surface, though their tangents lie in no one plane.
pub(crate) fn non_manifold_nodes(
    curves: &[NetworkCurve],
    brep: &Brep,
    branching: &[HalfEdgeId],
    dirs: &[DVec3],
    diagnostics: &mut Vec<Diagnostic>,
) {
    for h in branching {
        let v = brep.half_edges[h.index()].origin;
        if two_sheets_about_a_knuckle(curves, brep, dirs, v) {
            continue;
        }
        let v = v.index();
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

/// True when a curve of role knuckle runs through vertex `v` (two of its half-edges leave
/// `v` in opposite directions) and the other half-edges leaving `v` point, about its tangent,
/// into at most two sheets ([`SHEET_GAP_DEGREES`] apart or more).
fn two_sheets_about_a_knuckle(
    curves: &[NetworkCurve],
    brep: &Brep,
    dirs: &[DVec3],
    v: crate::topo::VertexId,
) -> bool {
    let leaving: Vec<usize> = (0..brep.half_edges.len())
        .filter(|&i| brep.half_edges[i].origin == v)
        .collect();
    let curve_of = |i: usize| brep.edges[brep.half_edges[i].edge.index()].curve;
    let axis = leaving.iter().find_map(|&a| {
        let c = curve_of(a);
        (curves[c].role == Role::Knuckle)
            .then(|| {
                leaving
                    .iter()
                    .find(|&&b| b != a && curve_of(b) == c && dirs[a].dot(dirs[b]) < -0.5)
                    .map(|_| (c, dirs[a]))
            })
            .flatten()
    });
    let Some((knuckle, axis)) = axis else {
        return false;
    };
    let Some(axis) = axis.try_normalize() else {
        return false;
    };
    let reference = axis.any_orthonormal_vector();
    let other = axis.cross(reference);
    let mut angles: Vec<f64> = leaving
        .iter()
        .filter(|&&i| curve_of(i) != knuckle)
        .filter_map(|&i| {
            let d = dirs[i] - axis * dirs[i].dot(axis);
            (d.length() > 1e-9).then(|| d.dot(other).atan2(d.dot(reference)))
        })
        .collect();
    if angles.len() <= 2 {
        return true;
    }
    angles.sort_by(f64::total_cmp);
    let gap = SHEET_GAP_DEGREES.to_radians();
    let n = angles.len();
    let sheets = (0..n)
        .filter(|&i| {
            let next = if i + 1 < n {
                angles[i + 1]
            } else {
                angles[0] + std::f64::consts::TAU
            };
            next - angles[i] >= gap
        })
        .count();
    sheets <= 2
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
