//! The edges of the topology as the hull uses them (H-rep paper §3.2): each edge that bounds a
//! region as a side segment along its designer curve, with its one-sided end tangents, and the
//! edges at every node.

use glam::DVec3;
use rayon::prelude::*;

use crate::curve::NurbsCurve;
use crate::network::Network;
use crate::patch::SideSegment;
use crate::tolerance::Tolerance;
use crate::topo::Topology;

/// What the hull needs of one edge of the topology that bounds a region.
#[derive(Clone, Debug)]
pub(crate) struct EdgeInfo {
    /// The edge as a side segment along its curve (`t0 → t1`, snapped onto knots whose
    /// points coincide with the node within the tolerance), named, with its node positions.
    /// Its curve is the designer curve cut to `[t0, t1]` (same parameterisation): at a corner
    /// point of the curve at a node, evaluation and derivatives then belong to this edge's
    /// side of the corner, whichever direction a face runs along it.
    pub(crate) segment: SideSegment,
    /// d/dt at `t0` (the one-sided derivative of this edge).
    pub(crate) start_tangent: DVec3,
    /// d/dt at `t1` (the one-sided derivative of this edge).
    pub(crate) end_tangent: DVec3,
}

impl EdgeInfo {
    /// The tangent (unnormalised) with which the edge leaves its start node (`at_start`) or its
    /// end node, pointing away from the node, into the edge.
    #[inline]
    pub(crate) fn leaving_tangent(&self, at_start: bool) -> DVec3 {
        if at_start {
            self.start_tangent
        } else {
            -self.end_tangent
        }
    }
}

/// The knots of a curve inside its domain with the curve's points there, evaluated once for
/// all the edges along the curve ([`KnotPoints::snap`] looks at every knot of the curve for
/// each end of each edge: a KCS waterline of 60 knots and 20 edges took 2,400 evaluations).
pub(crate) struct KnotPoints(Vec<(f64, DVec3)>);

impl KnotPoints {
    /// The knots of `curve` in its domain, in order (repeated knots once), with their points.
    pub(crate) fn of(curve: &NurbsCurve) -> KnotPoints {
        let (a, b) = curve.domain();
        let mut out: Vec<(f64, DVec3)> = Vec::new();
        for &k in curve.knots() {
            if k >= a && k <= b && out.last().is_none_or(|&(last, _)| last != k) {
                out.push((k, curve.point(k)));
            }
        }
        KnotPoints(out)
    }

    /// `t` moved onto the nearest knot of `curve` (whose knot points these are) other than `t`
    /// whose point lies within the model tolerance of C(t), the lower of two as near; `t`
    /// where there is none. A node found by the junction solver a hair beside a knot (at
    /// `1 + 2e-16` next to a double knot, or 1e-8 beside a polyline's corner once coordinates
    /// went through Blender's float32) would otherwise leave a sliver span at the end of the
    /// edge's curve, where the derivatives describe the wrong side of the corner and the patch
    /// folds. Points that coincide within the tolerance are the same point, so the knot is the
    /// node. The node position itself is kept ([`SideSegment::with_nodes`]).
    pub(crate) fn snap(&self, curve: &NurbsCurve, t: f64, tolerance: Tolerance) -> f64 {
        let at = curve.point(t);
        self.0
            .iter()
            .filter(|&&(k, p)| k != t && (p - at).length() <= tolerance.get())
            .map(|&(k, _)| k)
            .min_by(|x, y| (x - t).abs().total_cmp(&(y - t).abs()))
            .unwrap_or(t)
    }
}

/// The designer curve restricted to `[t0, t1]` (split at interior ends; the parameterisation
/// is kept). Falls back to the whole curve if a split is refused.
pub(crate) fn edge_curve(curve: &NurbsCurve, t0: f64, t1: f64) -> NurbsCurve {
    let (a, b) = curve.domain();
    let mut c = curve.clone();
    if t0 > a && t0 < b {
        if let Ok((_, right)) = c.split(t0) {
            c = right;
        }
    }
    if t1 < b && t1 > c.domain().0 {
        if let Ok((left, _)) = c.split(t1) {
            c = left;
        }
    }
    c
}

/// A non-zero tangent of `curve` at `t` (first derivative, else second, else the chord
/// direction of the whole edge).
fn tangent(curve: &NurbsCurve, t: f64, chord: DVec3) -> DVec3 {
    let d = curve.derivs(t);
    [d.d1, d.d2, chord]
        .into_iter()
        .find(|v| v.is_finite() && v.length() > 0.0)
        .unwrap_or(DVec3::ZERO)
}

/// Edge `k` of the topology as the hull uses it: snapped onto its curve's knots, cut from the
/// designer curve, named, with its node positions and one-sided end tangents.
/// `knots` are the [`KnotPoints`] of the edge's curve.
fn edge_info(
    network: &Network,
    topology: &Topology,
    k: usize,
    tolerance: Tolerance,
    knots: &KnotPoints,
) -> EdgeInfo {
    let e = &topology.brep.edges[k];
    let nc = &network.curves()[e.curve];
    let (t0, t1) = (
        knots.snap(&nc.curve, e.t0, tolerance),
        knots.snap(&nc.curve, e.t1, tolerance),
    );
    let (t0, t1) = if t0 < t1 { (t0, t1) } else { (e.t0, e.t1) };
    let curve = edge_curve(&nc.curve, t0, t1);
    let (p0, p1) = (
        topology.brep.vertices[e.start.index()].position,
        topology.brep.vertices[e.end.index()].position,
    );
    let chord = curve.point(t1) - curve.point(t0);
    let start_tangent = tangent(&curve, t0, chord);
    let end_tangent = tangent(&curve, t1, chord);
    EdgeInfo {
        segment: SideSegment::new(curve, t0, t1)
            .named(nc.name.clone())
            .with_nodes(p0, p1)
            .measured(tolerance),
        start_tangent,
        end_tangent,
    }
}

/// The [`KnotPoints`] of every curve of `network` with an edge flagged in `wanted` (in
/// parallel), `None` for the others.
fn knot_points(network: &Network, topology: &Topology, wanted: &[bool]) -> Vec<Option<KnotPoints>> {
    let mut used = vec![false; network.curves().len()];
    for (e, _) in topology.brep.edges.iter().zip(wanted).filter(|(_, &w)| w) {
        used[e.curve] = true;
    }
    network
        .curves()
        .par_iter()
        .zip(used)
        .map(|(c, used)| used.then(|| KnotPoints::of(&c.curve)))
        .collect()
}

/// One end of an edge at a node: the edge (index into the topology's edges) and whether the
/// node is the edge's start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct EdgeEnd {
    /// Index of the edge.
    pub(crate) edge: usize,
    /// True when the node is the edge's start (`t0`), false for its end (`t1`).
    pub(crate) at_start: bool,
}

/// The region-bounding edges of a topology with the edges at each node.
#[derive(Clone, Debug)]
pub(crate) struct FaceEdges {
    /// Per topology edge: its [`EdgeInfo`], `None` for an edge that bounds no region.
    pub(crate) info: Vec<Option<EdgeInfo>>,
    /// Per node: the ends of the region-bounding edges there, in edge order.
    pub(crate) at_vertex: Vec<Vec<EdgeEnd>>,
}

impl FaceEdges {
    /// The region-bounding edges of `topology` (in parallel) and their ends at the nodes.
    pub(crate) fn new(network: &Network, topology: &Topology, tolerance: Tolerance) -> FaceEdges {
        let brep = &topology.brep;
        let wanted: Vec<bool> = brep.edges.iter().map(|e| e.half_edges.is_some()).collect();
        let knots = knot_points(network, topology, &wanted);
        let info: Vec<Option<EdgeInfo>> = (0..brep.edges.len())
            .into_par_iter()
            .map(|k| {
                let knots = knots[brep.edges[k].curve].as_ref()?;
                wanted[k].then(|| edge_info(network, topology, k, tolerance, knots))
            })
            .collect();
        let mut at_vertex: Vec<Vec<EdgeEnd>> = vec![Vec::new(); brep.vertices.len()];
        for (k, e) in brep.edges.iter().enumerate() {
            if info[k].is_some() {
                at_vertex[e.start.index()].push(EdgeEnd {
                    edge: k,
                    at_start: true,
                });
                at_vertex[e.end.index()].push(EdgeEnd {
                    edge: k,
                    at_start: false,
                });
            }
        }
        FaceEdges { info, at_vertex }
    }

    /// These edges for `topology`, a topology with the same connectivity as the one they were
    /// made for (the live rebuild): the edges flagged in `dirty` made again (in parallel), the
    /// others and the ends at the nodes kept.
    pub(crate) fn updated(
        &self,
        network: &Network,
        topology: &Topology,
        tolerance: Tolerance,
        dirty: &[bool],
    ) -> FaceEdges {
        let wanted: Vec<bool> = self
            .info
            .iter()
            .zip(dirty)
            .map(|(old, &dirty)| dirty && old.is_some())
            .collect();
        let knots = knot_points(network, topology, &wanted);
        let info = self
            .info
            .par_iter()
            .enumerate()
            .map(|(k, old)| match &knots[topology.brep.edges[k].curve] {
                Some(knots) if wanted[k] => Some(edge_info(network, topology, k, tolerance, knots)),
                _ => old.clone(),
            })
            .collect();
        FaceEdges {
            info,
            at_vertex: self.at_vertex.clone(),
        }
    }
}
