//! The topology of a curve network as plain data: the B-rep, its faces with their sides and
//! designer curves, its boundary loops and the findings about the network (H-rep paper §3.1,
//! §5.2). [`Topology::build`](super::Topology::build) makes it.

use std::collections::BTreeMap;

use smallvec::SmallVec;

use super::brep::{Brep, EdgeId};
use super::faces::FaceSide;
use crate::diagnostic::Diagnostic;

/// A face as the patch builder needs it: its edges in loop order, its sides between true
/// corners and the designer curves along them (H-rep paper §5.2).
#[derive(Clone, Debug, PartialEq)]
pub struct TopoFace {
    /// Its edges, counter-clockwise about the surface normal.
    pub edges: SmallVec<[EdgeId; 6]>,
    /// For each edge, true when the loop runs along the curve (from `t0` to `t1`).
    pub forward: SmallVec<[bool; 6]>,
    /// The number of true corners (3 for a triangle, 4 for a quad …).
    pub corners: usize,
    /// The sides between corners.
    pub sides: SmallVec<[FaceSide; 4]>,
    /// The designer curves of its boundary (indices into the network and into
    /// [`Topology::curve_names`]), sorted, without repeats.
    pub curves: SmallVec<[usize; 4]>,
}

/// A boundary loop of the network (the open edge of a half hull: keel, stem, deck, transom …).
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryLoop {
    /// Its edges in order.
    pub edges: Vec<EdgeId>,
    /// The designer curves along it (indices into [`Topology::curve_names`]), sorted, without
    /// repeats.
    pub curves: Vec<usize>,
}

/// The topology of a curve network: the B-rep, its faces and boundary loops as plain data, and
/// everything the designer should know about the network.
#[derive(Clone, Debug, PartialEq)]
pub struct Topology {
    /// The names of the network's curves, by index: every `curves` list of the topology holds
    /// indices into this.
    pub curve_names: Vec<String>,
    /// The half-edge B-rep (vertices are the nodes, edges the curve stretches between them).
    pub brep: Brep,
    /// The faces, indexed like `brep.faces`.
    pub faces: Vec<TopoFace>,
    /// The boundary loops.
    pub boundary_loops: Vec<BoundaryLoop>,
    /// Findings about the network: dangling ends, near misses, unusual faces …
    pub diagnostics: Vec<Diagnostic>,
}

impl Topology {
    /// The names of curves given by index (as in a face's or side's `curves`; the designer's
    /// curves of H-rep §3.1).
    pub fn names(&self, curves: &[usize]) -> Vec<&str> {
        curves
            .iter()
            .map(|&c| self.curve_names[c].as_str())
            .collect()
    }

    /// Number of nodes (vertices, H-rep §3.1).
    pub fn node_count(&self) -> usize {
        self.brep.vertices.len()
    }

    /// Number of edges (curve stretches between nodes, H-rep §3.1), including those bounding no
    /// face.
    pub fn edge_count(&self) -> usize {
        self.brep.edges.len()
    }

    /// Number of faces with each corner count: `{3: …, 4: …, 5: …}` (three-, four- and N-sided
    /// patches, H-rep §3.2.1).
    pub fn faces_by_corners(&self) -> BTreeMap<usize, usize> {
        let mut out = BTreeMap::new();
        for f in &self.faces {
            *out.entry(f.corners).or_insert(0) += 1;
        }
        out
    }

    /// The diagnostics of one kind (see [`Diagnostic::kind`]; H-rep §5.2).
    pub fn diagnostics_of(&self, kind: &str) -> Vec<&Diagnostic> {
        self.diagnostics
            .iter()
            .filter(|d| d.kind() == kind)
            .collect()
    }
}
