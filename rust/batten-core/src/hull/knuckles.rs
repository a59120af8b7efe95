//! Knuckle edges: where the hull keeps a crease (G0) instead of the GC¹ join of the tangent
//! ribbons (H-rep paper §1 "knuckles", §5: chines made "simply by connecting the knuckles in
//! each cross section").

use glam::DVec3;

use super::build::EdgeInfo;
use crate::network::{Network, Role};
use crate::topo::Topology;

/// A crossing curve whose tangent direction jumps by more than this (degrees) at a node is
/// drawn with a knuckle point there, and the edges through that node are knuckle edges.
///
/// Choice: 5°. Below it a jump is taken for drawing noise on a curve meant to be smooth (the
/// shared ribbon then averages both sides, tilting the surface normal by at most half the jump);
/// above it the designer clearly drew a corner, and forcing GC¹ through it would bulge the
/// patches on both sides. The paper gives no number for this (its 15° rule, §3.2.2, is about
/// crossing tangents too close to the edge, not about corners).
pub const KNUCKLE_POINT_ANGLE_DEGREES: f64 = 5.0;

/// The corner points of every curve (positions where the tangent jumps by more than
/// [`KNUCKLE_POINT_ANGLE_DEGREES`]).
pub(crate) fn corner_points(network: &Network) -> Vec<Vec<DVec3>> {
    let angle = KNUCKLE_POINT_ANGLE_DEGREES.to_radians();
    network
        .curves()
        .iter()
        .map(|c| {
            c.curve
                .corner_parameters(angle)
                .into_iter()
                .map(|t| c.curve.point(t))
                .collect()
        })
        .collect()
}

/// Which edges are knuckles: every edge of a curve with role [`Role::Knuckle`], and every edge
/// with an end node that lies (within the near-miss distance, 10× the tolerance) on a corner
/// point of another curve through that node.
///
/// `at_vertex[v]` lists the face edges at node `v` as `(edge, node is the edge's start)`.
pub(crate) fn knuckle_edges(
    network: &Network,
    topology: &Topology,
    edges: &[Option<EdgeInfo>],
    at_vertex: &[Vec<(usize, bool)>],
    near_miss: f64,
) -> Vec<bool> {
    let corners = corner_points(network);
    let curves = network.curves();
    topology
        .brep
        .edges
        .iter()
        .enumerate()
        .map(|(k, e)| {
            if edges[k].is_none() {
                return false;
            }
            if curves[e.curve].role == Role::Knuckle {
                return true;
            }
            [e.start, e.end].iter().any(|v| {
                let p = topology.brep.vertices[v.index()].position;
                at_vertex[v.index()].iter().any(|&(j, _)| {
                    let d = topology.brep.edges[j].curve;
                    d != e.curve && corners[d].iter().any(|c| (*c - p).length() <= near_miss)
                })
            })
        })
        .collect()
}
