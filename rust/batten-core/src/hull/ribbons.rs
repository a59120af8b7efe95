//! Tangent ribbons of the hull's faces (H-rep paper §3.2.2): the cross-boundary tangents of
//! eq. 8 from the curves crossing each edge at its nodes, with the 15° rule, stored as one
//! surface normal field per edge ([`EdgeNormal`]).

use glam::DVec3;

use super::edges::{EdgeInfo, FaceEdges};
use crate::curve::NurbsCurve;
use crate::network::Network;
use crate::patch::{EdgeNormal, PatchError, RibbonNode, SupportNode, MIN_CROSSING_ANGLE_DEGREES};
use crate::topo::{TopoFace, Topology};

/// How many nodes beyond each end of an edge, along the same curve, shape its normal field's
/// slopes: two, so that the three-point stencils at both of the edge's own nodes are centred
/// where the curve runs on.
const SUPPORT_NODES: usize = 2;

/// Knots closer than this to a node's parameter (relative to the curve's parameter span) are
/// at the node, for counting the knot's multiplicity there.
const KNOT_AT_NODE_RELATIVE: f64 = 1e-9;

/// Whether the curve's character changes at parameter `t`: a knot there of multiplicity at
/// least the degree, so the curve is only C0 in its parameter (a corner, or a parabola
/// meeting a straight wall side as on the Wigley stations at the waterline). The normal
/// field's stencils do not reach across such a node.
fn is_break(curve: &NurbsCurve, t: f64) -> bool {
    let (a, b) = curve.domain();
    let near = KNOT_AT_NODE_RELATIVE * (b - a).abs().max(f64::MIN_POSITIVE);
    if (t - a).abs() <= near || (t - b).abs() <= near {
        return true;
    }
    let m = curve
        .knots()
        .iter()
        .filter(|&&k| (k - t).abs() <= near)
        .count();
    m >= curve.degree()
}

/// The tangents, at node `v`, of every region-bounding edge there on another curve than
/// `curve`, leaving the node.
fn crossing_tangents(v: usize, curve: usize, topology: &Topology, edges: &FaceEdges) -> Vec<DVec3> {
    edges.at_vertex[v]
        .iter()
        .filter(|end| topology.brep.edges[end.edge].curve != curve)
        .filter_map(|end| {
            edges.info[end.edge]
                .as_ref()
                .map(|o| o.leaving_tangent(end.at_start))
        })
        .collect()
}

/// Up to [`SUPPORT_NODES`] nodes beyond node `v` of edge `k`, walking along the same curve
/// through its smooth edges: each with its parameter, the curve's d/dt there and the crossing
/// tangents. The walk stops at a break of the curve ([`is_break`]), a knuckle edge, a node
/// where the curve's continuation is not unique, or after looping back to `k`.
fn support_beyond(
    k: usize,
    v: usize,
    t_v: f64,
    network: &Network,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[bool],
) -> Vec<SupportNode> {
    let curve = topology.brep.edges[k].curve;
    let designer = &network.curves()[curve].curve;
    let mut out = Vec::with_capacity(SUPPORT_NODES);
    let (mut at, mut t_at, mut from) = (v, t_v, k);
    while out.len() < SUPPORT_NODES && !is_break(designer, t_at) {
        let mut next = edges.at_vertex[at]
            .iter()
            .filter(|end| end.edge != from && topology.brep.edges[end.edge].curve == curve);
        let (Some(end), None) = (next.next(), next.next()) else {
            break;
        };
        let j = end.edge;
        let Some(info) = edges.info[j].as_ref() else {
            break;
        };
        if j == k || knuckle[j] {
            break;
        }
        let e = &topology.brep.edges[j];
        // The far node of edge j, its parameter and the curve's d/dt there (from j's side).
        let (far, t_far, d_far) = if end.at_start {
            (e.end.index(), info.segment.t1, info.end_tangent)
        } else {
            (e.start.index(), info.segment.t0, info.start_tangent)
        };
        out.push(SupportNode {
            t: t_far,
            curve_tangent: d_far,
            tangents: crossing_tangents(far, curve, topology, edges),
        });
        (at, t_at, from) = (far, t_far, j);
    }
    out
}

/// The ONE normal field of a smooth edge `k`, shared by both its faces (§3.2.2: the same
/// tangent plane on both sides is GC¹): at each end node, the tangents of every other curve's
/// face edge through that node (both sides of the edge), eq. 8 with the 15° rule, averaged;
/// and the same at up to [`SUPPORT_NODES`] nodes beyond each end along the curve's smooth run
/// ([`support_beyond`]), which give the blend its slopes. `Ok(None)` when no crossing tangent
/// survives (the faces then use their default ribbons).
pub(crate) fn shared_normal(
    k: usize,
    network: &Network,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[bool],
) -> Result<Option<EdgeNormal>, PatchError> {
    let Some(info) = &edges.info[k] else {
        return Ok(None);
    };
    let e = &topology.brep.edges[k];
    let mut nodes = Vec::with_capacity(2);
    let mut support = Vec::with_capacity(2 * SUPPORT_NODES);
    let (t0, t1) = (info.segment.t0, info.segment.t1);
    for (v, t) in [(e.start, t0), (e.end, t1)] {
        let tangents = crossing_tangents(v.index(), e.curve, topology, edges);
        if !tangents.is_empty() {
            nodes.push(RibbonNode { t, tangents });
        }
        support.extend(support_beyond(
            k,
            v.index(),
            t,
            network,
            topology,
            edges,
            knuckle,
        ));
    }
    // A closed curve's walk may come round to this edge's own span: keep support outside it.
    let (lo, hi) = (t0.min(t1), t0.max(t1));
    support.retain(|s| s.t < lo || s.t > hi);
    EdgeNormal::from_crossings_along(&info.segment, &nodes, &support, MIN_CROSSING_ANGLE_DEGREES)
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
