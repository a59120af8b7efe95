//! What kind of node each vertex of the topology is (H-rep paper §3.1, §5.2): where curves
//! cross, meet end to end, end on another curve (a T-joint when the other curve runs on as one
//! side of a face), or end free. The viewport marks each kind differently.

use std::collections::BTreeMap;

use super::topology::Topology;

/// The kind of a node of the network.
#[derive(serde::Serialize, Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// Curves cross or pass through the node; none ends there.
    Crossing,
    /// Every curve at the node ends there (a corner of the network, or curves joined end to
    /// end).
    EndToEnd,
    /// A curve ends on another curve's interior but not as a T-joint: every face there has a
    /// corner at the node (a station landing on the keel or the deck edge), or the ending
    /// curve is a dangling branch that bounds no face.
    EndOnCurve,
    /// A curve ends on another curve's interior, its edge there bounds a face, and the other
    /// curve runs straight through the node as one side of a face (H-rep paper §3.2.1: that
    /// face's side is composite).
    TJoint,
    /// One curve ends here and meets nothing (a dangling end).
    FreeEnd,
}

impl NodeKind {
    /// A short snake-case name: `crossing`, `end_to_end`, `end_on_curve`, `t_joint`,
    /// `free_end`.
    pub fn as_str(self) -> &'static str {
        match self {
            NodeKind::Crossing => "crossing",
            NodeKind::EndToEnd => "end_to_end",
            NodeKind::EndOnCurve => "end_on_curve",
            NodeKind::TJoint => "t_joint",
            NodeKind::FreeEnd => "free_end",
        }
    }
}

impl Topology {
    /// The kind of every vertex of `self.brep.vertices`, in order.
    ///
    /// A curve ends at a node when exactly one of its edges (face edges or pruned ones) has an
    /// end there, and passes through it when two do. A node lies inside a face side when two
    /// consecutive edges of one [`FaceSide`](super::faces::FaceSide) meet there.
    pub fn node_kinds(&self) -> Vec<NodeKind> {
        node_kinds(self)
    }
}

/// One curve at one node: how many of its edges end there, and whether one of them bounds a
/// face.
#[derive(Clone, Copy, Debug, Default)]
struct CurveAtNode {
    /// Edge ends of the curve at the node: 1 when the curve ends there, 2 when it passes
    /// through.
    edge_ends: usize,
    /// Whether one of those edges bounds a face (has half-edges).
    bounds_face: bool,
}

impl CurveAtNode {
    /// The curve ends at the node (one of its edges ends there, none continues).
    fn ends_here(self) -> bool {
        self.edge_ends == 1
    }
}

fn node_kinds(topo: &Topology) -> Vec<NodeKind> {
    let brep = &topo.brep;
    let n = brep.vertices.len();
    let mut inside_side = vec![false; n];
    for face in &topo.faces {
        for side in &face.sides {
            for w in side.edges.windows(2) {
                let Some(pos) = face.edges.iter().position(|e| *e == w[0]) else {
                    continue;
                };
                let e = &brep.edges[w[0].index()];
                let v = if face.forward[pos] { e.end } else { e.start };
                inside_side[v.index()] = true;
            }
        }
    }
    // Per node: each curve through it.
    let mut ends: Vec<BTreeMap<usize, CurveAtNode>> = vec![BTreeMap::new(); n];
    for e in &brep.edges {
        for v in [e.start, e.end] {
            let at = ends[v.index()].entry(e.curve).or_default();
            at.edge_ends += 1;
            at.bounds_face |= e.half_edges.is_some();
        }
    }
    ends.iter()
        .enumerate()
        .map(|(vi, curves)| {
            let ending = curves.values().filter(|c| c.ends_here()).count();
            let passing = curves.len() - ending;
            let face_end = curves.values().any(|c| c.ends_here() && c.bounds_face);
            match (ending, passing) {
                (0, _) => NodeKind::Crossing,
                (1, 0) => NodeKind::FreeEnd,
                (_, 0) => NodeKind::EndToEnd,
                _ if face_end && inside_side[vi] => NodeKind::TJoint,
                _ => NodeKind::EndOnCurve,
            }
        })
        .collect()
}
