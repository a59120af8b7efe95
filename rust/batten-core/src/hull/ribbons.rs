//! Tangent ribbons of the hull's faces (H-rep paper §3.2.2): the cross-boundary tangents of
//! eq. 8 from the curves crossing each edge at its nodes, with the 15° rule, stored as one
//! surface normal field per edge ([`EdgeNormal`]).

use glam::DVec3;

use super::edges::{EdgeInfo, FaceEdges};
use super::knuckles::Knuckle;
use crate::patch::{EdgeNormal, PatchError, RibbonNode, MIN_CROSSING_ANGLE_DEGREES};
use crate::topo::{TopoFace, Topology, VertexId};

/// Two curve tangents at a node closer to opposite than this make the curve run on smoothly
/// through it: the node beyond may then shape the edge's normal field.
const SMOOTH_RUN_DEGREES: f64 = 10.0;

/// The node one edge beyond end `at_start` of edge `k` along the same curve, where the curve
/// runs on smoothly through that end into a smooth edge: the node, that edge, the node's
/// parameter on the curve and the curve's d/dt there. `None` at a free end, at a corner of the
/// curve, where the curve goes on as a knuckle edge, or across the seam of a closed curve.
pub(crate) fn beyond(
    k: usize,
    at_start: bool,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[Option<Knuckle>],
) -> Option<(VertexId, usize, f64, DVec3)> {
    let e = &topology.brep.edges[k];
    let info = edges.info[k].as_ref()?;
    let v = if at_start { e.start } else { e.end };
    let mut on_curve = edges.at_vertex[v.index()]
        .iter()
        .filter(|end| end.edge != k && topology.brep.edges[end.edge].curve == e.curve);
    let end = on_curve.next()?;
    if on_curve.next().is_some() || knuckle[end.edge].is_some() {
        return None;
    }
    let other = edges.info[end.edge].as_ref()?;
    let (here, there) = (
        info.leaving_tangent(at_start),
        other.leaving_tangent(end.at_start),
    );
    let cos = -here.dot(there) / (here.length() * there.length());
    if cos.is_nan() || cos < SMOOTH_RUN_DEGREES.to_radians().cos() {
        return None;
    }
    let oe = &topology.brep.edges[end.edge];
    let (far, t, d) = if end.at_start {
        (oe.end, other.segment.t1, other.end_tangent)
    } else {
        (oe.start, other.segment.t0, other.start_tangent)
    };
    let outward = if at_start {
        t < info.segment.t0
    } else {
        t > info.segment.t1
    };
    outward.then_some((far, end.edge, t, d))
}

/// The tangents, at node `v`, of the curves other than `curve` whose region-bounding edges end
/// there (both sides of the curve), each leaving the node. Where a knuckle runs through the
/// node, only its edges count: the surface on this curve's side of the knuckle has the
/// knuckle's tangent and this curve's, and a curve on the far side (a line on along a shaft
/// boss from its flat end's edge) belongs to the other tangent plane.
fn crossing_tangents(
    v: VertexId,
    curve: usize,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[Option<Knuckle>],
) -> Vec<DVec3> {
    let crossing: Vec<(DVec3, bool)> = edges.at_vertex[v.index()]
        .iter()
        .filter(|end| topology.brep.edges[end.edge].curve != curve)
        .filter_map(|end| {
            edges.info[end.edge]
                .as_ref()
                .map(|o| (o.leaving_tangent(end.at_start), knuckle[end.edge].is_some()))
        })
        .collect();
    let on_knuckle = crossing.iter().any(|&(_, k)| k);
    crossing
        .into_iter()
        .filter(|&(_, k)| k || !on_knuckle)
        .map(|(t, _)| t)
        .collect()
}

/// The ONE normal field of a smooth edge `k`, shared by both its faces (§3.2.2: the same
/// tangent plane on both sides is GC¹): at each end node, the tangents of every other curve's
/// face edge through that node (both sides of the edge), eq. 8 with the 15° rule, averaged.
/// Where the curve runs on smoothly past an end, the node beyond is taken too (see
/// [`beyond`]): it only shapes the blend's slope at the end, which makes the normal field of
/// the curve continuous in its derivative across the node and exact for a tangent plane that
/// turns quadratically along the curve (a Wigley hull's, between stations).
/// `Ok(None)` when no crossing tangent survives (the faces then use their default ribbons).
pub(crate) fn shared_normal(
    k: usize,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[Option<Knuckle>],
) -> Result<Option<EdgeNormal>, PatchError> {
    let Some(info) = &edges.info[k] else {
        return Ok(None);
    };
    let e = &topology.brep.edges[k];
    let mut nodes = Vec::with_capacity(2);
    let (t0, t1) = (info.segment.t0, info.segment.t1);
    for (v, t) in [(e.start, t0), (e.end, t1)] {
        let tangents = crossing_tangents(v, e.curve, topology, edges, knuckle);
        if !tangents.is_empty() {
            nodes.push(RibbonNode { t, tangents });
        }
    }
    let outer: Vec<(RibbonNode, DVec3)> = [true, false]
        .into_iter()
        .filter_map(|at_start| beyond(k, at_start, topology, edges, knuckle))
        .filter_map(|(v, _, t, d)| {
            let tangents = crossing_tangents(v, e.curve, topology, edges, knuckle);
            (!tangents.is_empty()).then_some((RibbonNode { t, tangents }, d))
        })
        .collect();
    EdgeNormal::from_crossings_along(&info.segment, &nodes, &outer, MIN_CROSSING_ANGLE_DEGREES)
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
