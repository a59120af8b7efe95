//! Knuckle edges: where the hull keeps a crease (G0) instead of the GC¹ join of the tangent
//! ribbons (H-rep paper §1 "knuckles", §5: chines made "simply by connecting the knuckles in
//! each cross section").

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use serde::Serialize;

use super::edges::FaceEdges;
use crate::network::{Network, NetworkCurve, Role};
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

/// Intervals (equal steps of the curve parameter) of the polyline drawn along each knuckle edge
/// in [`KnuckleEdge::points`]: 17 points, enough to draw a curved chine between two nodes.
pub const KNUCKLE_EDGE_SAMPLES: usize = 16;

/// Why an edge is a knuckle (H-rep paper §1 "knuckles", §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum KnuckleSource {
    /// The designer gave its curve the role [`Role::Knuckle`].
    Role,
    /// Found automatically: a crossing curve has a corner (a tangent jump above
    /// [`KNUCKLE_POINT_ANGLE_DEGREES`]) at one of the edge's nodes.
    Auto,
}

impl KnuckleSource {
    /// The stable tag: `"role"` or `"auto"` (as serialised).
    pub fn name(self) -> &'static str {
        match self {
            KnuckleSource::Role => "role",
            KnuckleSource::Auto => "auto",
        }
    }
}

/// One knuckle edge of the hull: a stretch of a curve between two nodes along which the
/// surface keeps a crease (G0), with why, how sharp, and where (for drawing it).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KnuckleEdge {
    /// The name of the edge's curve.
    pub curve: String,
    /// Role knuckle, or found automatically.
    pub source: KnuckleSource,
    /// For an automatic knuckle, the crossing curves (sorted names) whose corners at the edge's
    /// nodes made it one; empty for a role knuckle.
    pub corner_curves: Vec<String>,
    /// Smallest and largest angle (degrees) between the two patches' normals along the edge,
    /// as in [`HullReport::crease_angles_deg`](super::HullReport::crease_angles_deg); `None`
    /// when fewer than two patches share the edge.
    pub crease_deg: Option<(f64, f64)>,
    /// [`KNUCKLE_EDGE_SAMPLES`] + 1 points along the edge's curve, from its start node to its
    /// end node (equal parameter steps), for drawing.
    pub points: Vec<[f64; 3]>,
}

/// Why an edge of the topology is a knuckle, as found by [`knuckle_edges`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Knuckle {
    /// Its curve has role [`Role::Knuckle`].
    Role,
    /// Corner points of these crossing curves (network indices) lie on its nodes.
    Auto(BTreeSet<usize>),
}

/// The corner points of one curve (positions where the tangent jumps by more than
/// [`KNUCKLE_POINT_ANGLE_DEGREES`]).
pub(crate) fn curve_corner_points(curve: &NetworkCurve) -> Vec<DVec3> {
    let angle = KNUCKLE_POINT_ANGLE_DEGREES.to_radians();
    curve
        .curve
        .corner_parameters(angle)
        .into_iter()
        .map(|t| curve.curve.point(t))
        .collect()
}

/// The corner points of every curve ([`curve_corner_points`]), in network order.
pub(crate) fn corner_points(network: &Network) -> Vec<Vec<DVec3>> {
    network.curves().iter().map(curve_corner_points).collect()
}

/// Which edges are knuckles, and why: every edge of a curve with role [`Role::Knuckle`], and
/// every edge with an end node that lies (within the near-miss distance, 10× the tolerance) on
/// a corner point (`corners`, per curve as [`corner_points`] gives them) of another curve
/// through that node. `None` for the other edges.
pub(crate) fn knuckle_edges(
    network: &Network,
    topology: &Topology,
    edges: &FaceEdges,
    corners: &[Vec<DVec3>],
    near_miss: f64,
) -> Vec<Option<Knuckle>> {
    let curves = network.curves();
    topology
        .brep
        .edges
        .iter()
        .enumerate()
        .map(|(k, e)| {
            edges.info[k].as_ref()?;
            if curves[e.curve].role == Role::Knuckle {
                return Some(Knuckle::Role);
            }
            let mut by: BTreeSet<usize> = BTreeSet::new();
            for v in [e.start, e.end] {
                let p = topology.brep.vertices[v.index()].position;
                for end in &edges.at_vertex[v.index()] {
                    let d = topology.brep.edges[end.edge].curve;
                    if d != e.curve && corners[d].iter().any(|c| (*c - p).length() <= near_miss) {
                        by.insert(d);
                    }
                }
            }
            (!by.is_empty()).then_some(Knuckle::Auto(by))
        })
        .collect()
}

/// The knuckle edges for the report, in the topology's edge order: curve, source, the curves
/// whose corners made it, its crease (`creases[edge]`, min and max degrees) and a polyline.
pub(crate) fn knuckle_report(
    network: &Network,
    topology: &Topology,
    knuckle: &[Option<Knuckle>],
    creases: &BTreeMap<usize, (f64, f64)>,
) -> Vec<KnuckleEdge> {
    let curves = network.curves();
    topology
        .brep
        .edges
        .iter()
        .enumerate()
        .filter_map(|(k, e)| {
            let why = knuckle[k].as_ref()?;
            let (source, corner_curves) = match why {
                Knuckle::Role => (KnuckleSource::Role, Vec::new()),
                Knuckle::Auto(by) => {
                    let mut names: Vec<String> =
                        by.iter().map(|&d| curves[d].name.clone()).collect();
                    names.sort();
                    (KnuckleSource::Auto, names)
                }
            };
            let curve = &curves[e.curve].curve;
            let points = (0..=KNUCKLE_EDGE_SAMPLES)
                .map(|j| {
                    let lam = j as f64 / KNUCKLE_EDGE_SAMPLES as f64;
                    curve.point(e.t0 + lam * (e.t1 - e.t0)).to_array()
                })
                .collect();
            Some(KnuckleEdge {
                curve: curves[e.curve].name.clone(),
                source,
                corner_curves,
                crease_deg: creases.get(&k).copied(),
                points,
            })
        })
        .collect()
}
