//! Tangent ribbons of the hull's faces (H-rep paper §3.2.2): the cross-boundary tangents of
//! eq. 8 from the curves crossing each edge at its nodes, with the 15° rule, stored as one
//! surface normal field per edge ([`EdgeNormal`]).

use glam::DVec3;

use super::edges::{EdgeInfo, FaceEdges};
use crate::patch::{EdgeNormal, PatchError, RibbonNode, MIN_CROSSING_ANGLE_DEGREES};
use crate::topo::{TopoFace, Topology};

/// The ONE normal field of a smooth edge `k`, shared by both its faces (§3.2.2: the same
/// tangent plane on both sides is GC¹): at each end node, the tangents of every other curve's
/// face edge through that node (both sides of the edge), eq. 8 with the 15° rule, averaged.
/// `Ok(None)` when no crossing tangent survives (the faces then use their default ribbons).
pub(crate) fn shared_normal(
    k: usize,
    topology: &Topology,
    edges: &FaceEdges,
) -> Result<Option<EdgeNormal>, PatchError> {
    let Some(info) = &edges.info[k] else {
        return Ok(None);
    };
    let e = &topology.brep.edges[k];
    let mut nodes = Vec::with_capacity(2);
    let (t0, t1) = (info.segment.t0, info.segment.t1);
    for (v, t) in [(e.start, t0), (e.end, t1)] {
        let tangents: Vec<DVec3> = edges.at_vertex[v.index()]
            .iter()
            .filter(|end| topology.brep.edges[end.edge].curve != e.curve)
            .filter_map(|end| {
                edges.info[end.edge]
                    .as_ref()
                    .map(|o| o.leaving_tangent(end.at_start))
            })
            .collect();
        if !tangents.is_empty() {
            nodes.push(RibbonNode { t, tangents });
        }
    }
    EdgeNormal::from_crossings(&info.segment, &nodes, MIN_CROSSING_ANGLE_DEGREES)
}

/// The normal field of knuckle edge `face.edges[pos]` for that face alone (G0 across the
/// edge): at each end node, the one-sided tangent of the face's neighbouring boundary edge at
/// that node, which is the crossing curve on this face's side, leaving the node into the face's
/// boundary. A neighbour on the same curve (a composite side running on through a T-joint)
/// carries no crossing information and is skipped.
pub(crate) fn one_sided_normal(
    face: &TopoFace,
    pos: usize,
    topology: &Topology,
    edges: &[Option<EdgeInfo>],
) -> Result<Option<EdgeNormal>, PatchError> {
    let n = face.edges.len();
    let k = face.edges[pos].index();
    let Some(info) = &edges[k] else {
        return Ok(None);
    };
    let e = &topology.brep.edges[k];
    let fwd = face.forward[pos];
    // Loop order: the previous edge arrives at this edge's origin, the next leaves its end.
    let prev = (pos + n - 1) % n;
    let next = (pos + 1) % n;
    let (t0, t1) = (info.segment.t0, info.segment.t1);
    let (t_origin, t_dest) = if fwd { (t0, t1) } else { (t1, t0) };
    let mut nodes = Vec::with_capacity(2);
    // The previous edge ends at the origin: it leaves the origin from its own end (forward) or
    // start (backward).
    for (idx, t, at_start) in [
        (prev, t_origin, !face.forward[prev]),
        (next, t_dest, face.forward[next]),
    ] {
        let j = face.edges[idx].index();
        if topology.brep.edges[j].curve == e.curve {
            continue;
        }
        if let Some(other) = &edges[j] {
            nodes.push(RibbonNode {
                t,
                tangents: vec![other.leaving_tangent(at_start)],
            });
        }
    }
    EdgeNormal::from_crossings(&info.segment, &nodes, MIN_CROSSING_ANGLE_DEGREES)
}
