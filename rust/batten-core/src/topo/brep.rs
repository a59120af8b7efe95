//! The half-edge B-rep of a curve network: arenas of vertices, half-edges, edges, loops, faces
//! and shells addressed by typed indices (no reference cycles), after the H-rep paper §3.1
//! ("implemented as a half-edge-based data structure \[Mäntylä\]").

use glam::DVec3;
use smallvec::SmallVec;

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(pub u32);

        impl $name {
            /// The index into its arena (typed handles of the H-rep §3.1 half-edge structure).
            pub fn index(self) -> usize {
                self.0 as usize
            }

            pub(crate) fn from_index(i: usize) -> Self {
                $name(u32::try_from(i).expect("fewer than 2^32 topological entities"))
            }
        }
    };
}

handle!(
    /// A vertex (node) of the topology: an index into [`Brep::vertices`].
    VertexId
);
handle!(
    /// A half-edge: an index into [`Brep::half_edges`].
    HalfEdgeId
);
handle!(
    /// An edge (a parameter interval of one designer curve): an index into [`Brep::edges`].
    EdgeId
);
handle!(
    /// A loop of half-edges: an index into [`Brep::loops`].
    LoopId
);
handle!(
    /// A face: an index into [`Brep::faces`] (and into [`Topology::faces`](crate::Topology::faces)).
    FaceId
);
handle!(
    /// A shell (one connected part of the network): an index into [`Brep::shells`].
    ShellId
);

/// A node of the network: where curves meet, or a free curve end (H-rep paper §3.1 vertex,
/// "the topological counterpart of a metric point").
#[derive(Clone, Debug, PartialEq)]
pub struct Vertex {
    /// The node's position.
    pub position: DVec3,
    /// The designer curves through the node (indices into the network, and into
    /// [`Topology::curve_names`](crate::Topology::curve_names)), sorted, without repeats.
    pub curves: SmallVec<[usize; 4]>,
    /// One half-edge leaving the vertex, `None` when no face edge touches it.
    pub outgoing: Option<HalfEdgeId>,
    /// The oriented unit surface normal estimated from the incident tangents (zero when the
    /// vertex has no face edges).
    pub normal: DVec3,
}

/// One side of an edge, running along its loop (H-rep paper §3.1: "half-edge entities are
/// logical entities indicating the two possible orientations of a physical edge").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HalfEdge {
    /// The vertex it starts at.
    pub origin: VertexId,
    /// The other half of its edge, running the other way.
    pub twin: HalfEdgeId,
    /// The next half-edge along its loop.
    pub next: HalfEdgeId,
    /// The previous half-edge along its loop.
    pub prev: HalfEdgeId,
    /// The edge it is a side of.
    pub edge: EdgeId,
    /// The loop it belongs to.
    pub loop_id: LoopId,
}

/// An edge: the stretch `[t0, t1]` (t0 < t1) of one designer curve between two nodes (H-rep
/// paper §3.1: the polycurve stays the fundamental entity; edges are pieces of it).
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Index of the curve in the network (and into
    /// [`Topology::curve_names`](crate::Topology::curve_names)).
    pub curve: usize,
    /// Start parameter.
    pub t0: f64,
    /// End parameter.
    pub t1: f64,
    /// The vertex at `t0`.
    pub start: VertexId,
    /// The vertex at `t1`.
    pub end: VertexId,
    /// The half-edge running from `start` to `end` and its twin, `None` for edges that bound
    /// no region (dangling branches).
    pub half_edges: Option<[HalfEdgeId; 2]>,
}

/// A closed cycle of half-edges: a face's boundary or a boundary of the network (H-rep paper
/// §3.1 edge-loop).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Loop {
    /// One of its half-edges.
    pub first: HalfEdgeId,
    /// The face it bounds, `None` for a boundary loop.
    pub face: Option<FaceId>,
    /// The shell it belongs to.
    pub shell: ShellId,
}

/// A face: the region bounded by one loop (H-rep paper §3.1 face, the counterpart of one
/// surface patch).
///
/// Implementation note: faces have one loop; the paper's inner loops (holes in a face) are not
/// detected, since a curve network closed into faces never leaves one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Face {
    /// Its boundary loop, counter-clockwise about the surface normal.
    pub outer: LoopId,
    /// The shell it belongs to.
    pub shell: ShellId,
}

/// A connected part of the network: its faces, boundary loops and genus (H-rep paper §3.1:
/// "the boundary of the ship hull is topologically described by a shell entity").
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shell {
    /// Its faces.
    pub faces: Vec<FaceId>,
    /// Its boundary loops (the open edges of a half hull: keel, stem, deck, transom…).
    pub boundaries: Vec<LoopId>,
    /// The genus of the surface the shell traces: 0 for a disk or a sphere.
    pub genus: i64,
}

/// The half-edge B-rep (H-rep paper §3.1, after Mäntylä): index-based arenas, compared by
/// identity (handle), never by coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Brep {
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Half-edges.
    pub half_edges: Vec<HalfEdge>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Loops.
    pub loops: Vec<Loop>,
    /// Faces.
    pub faces: Vec<Face>,
    /// Shells.
    pub shells: Vec<Shell>,
}

impl Brep {
    /// The half-edge `h` (§3.1).
    pub fn half_edge(&self, h: HalfEdgeId) -> &HalfEdge {
        &self.half_edges[h.index()]
    }

    /// The vertex a half-edge ends at (the origin of its twin; §3.1).
    pub fn destination(&self, h: HalfEdgeId) -> VertexId {
        self.half_edge(self.half_edge(h).twin).origin
    }

    /// True when the half-edge runs along its curve (from `t0` to `t1`; §3.1).
    pub fn is_forward(&self, h: HalfEdgeId) -> bool {
        let he = self.half_edge(h);
        self.edges[he.edge.index()]
            .half_edges
            .is_some_and(|[a, _]| a == h)
    }

    /// The half-edges of a loop in order (§3.1), following `next` from its first half-edge (at most
    /// as many steps as there are half-edges, so a broken `next` chain cannot hang).
    pub fn loop_half_edges(&self, l: LoopId) -> Vec<HalfEdgeId> {
        let mut out = Vec::new();
        self.loop_half_edges_into(l, &mut out);
        out
    }

    /// [`Brep::loop_half_edges`] into `out` (cleared first), reusing its storage.
    pub fn loop_half_edges_into(&self, l: LoopId, out: &mut Vec<HalfEdgeId>) {
        let first = self.loops[l.index()].first;
        out.clear();
        out.push(first);
        let mut h = self.half_edge(first).next;
        while h != first && out.len() <= self.half_edges.len() {
            out.push(h);
            h = self.half_edge(h).next;
        }
    }
}
