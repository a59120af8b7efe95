//! What the topology builder tells the designer: every finding names the curves and the place.

use std::fmt;

use glam::DVec3;

/// One finding of [`Topology::build`](crate::Topology::build) about the curve network, naming
/// the designer curves involved and where (model coordinates, metres).
///
/// Follows the H-rep paper (§3.1, "line-induced topological structure"): the designer's curves
/// must start and end on other curves (§5.2); where they do not, or where the network cannot be
/// read as a closed arrangement of faces, the designer is told where, never silently corrected.
#[derive(Clone, Debug, PartialEq)]
pub enum Diagnostic {
    /// A curve end meets no other curve.
    DanglingEnd {
        /// The curve.
        curve: String,
        /// The free end.
        location: DVec3,
    },
    /// A curve meets no other curve anywhere.
    IsolatedCurve {
        /// The curve.
        curve: String,
        /// Its start point.
        location: DVec3,
    },
    /// Two curves pass closer than 10× the tolerance but farther than the tolerance: they are
    /// not joined, and probably should be.
    NearMiss {
        /// The two curves (sorted by name).
        curves: [String; 2],
        /// Midpoint of the closest approach.
        location: DVec3,
        /// The gap between them.
        gap: f64,
    },
    /// Two curves coincide over their whole length; a free one is left out beside one with a
    /// role, else the second by name.
    DuplicateCurve {
        /// The kept and the left-out curve.
        curves: [String; 2],
        /// A point of the curves.
        location: DVec3,
    },
    /// Two curves run together (within tolerance) along a stretch.
    Overlap {
        /// The two curves (sorted by name).
        curves: [String; 2],
        /// One end of the shared stretch.
        from: DVec3,
        /// The other end.
        to: DVec3,
    },
    /// A curve crosses itself; no node is made there.
    SelfIntersection {
        /// The curve.
        curve: String,
        /// Where it crosses itself.
        location: DVec3,
        /// The gap there.
        gap: f64,
    },
    /// A curve is shorter than the model tolerance; it is left out of the topology.
    ZeroLength {
        /// The curve.
        curve: String,
        /// Where it is.
        location: DVec3,
    },
    /// Edges that belong to no closed region (a dangling branch of the network).
    UnusedEdges {
        /// The curve.
        curve: String,
        /// Number of its edges left out of faces.
        edges: usize,
        /// A point of the first such edge.
        location: DVec3,
    },
    /// A loop of edges that does not bound a disk (it runs along some edge on both sides), so
    /// no face could be made of it.
    UnclosedRegion {
        /// Curves along the loop.
        curves: Vec<String>,
        /// A point of the loop.
        location: DVec3,
    },
    /// An edge that is used by more than two faces or twice by one face.
    NonManifoldEdge {
        /// The edge's curve.
        curve: String,
        /// The edge's midpoint.
        location: DVec3,
    },
    /// A node where the edges do not lie in one surface (they leave the best plane of their
    /// tangents steeply): several surface sheets branch there, as along a bulkhead or a
    /// T-shaped appendage, so its edges are not manifold.
    NonManifoldNode {
        /// Curves through the node.
        curves: Vec<String>,
        /// The node.
        location: DVec3,
    },
    /// A face with fewer than 3 or more than 8 corners: the patch methods of §3.2.1 handle it
    /// poorly or not at all.
    UnusualFace {
        /// Index of the face in [`Topology::faces`](crate::Topology::faces).
        face: usize,
        /// Its number of corners.
        corners: usize,
        /// Curves along its boundary.
        curves: Vec<String>,
        /// A point of its boundary.
        location: DVec3,
    },
    /// A connected part of the network traced to a surface with handles (genus > 0), which a
    /// hull network never is: the local normals could not be oriented consistently.
    Genus {
        /// The shell's genus.
        genus: i64,
        /// A point of the shell.
        location: DVec3,
    },
    /// A B-rep invariant failed (a defect of batten, reported rather than panicking).
    InvalidTopology {
        /// What failed.
        message: String,
    },
}

impl Diagnostic {
    /// The names of the curves the finding is about (H-rep §5.2: the designer works with curves).
    pub fn curves(&self) -> Vec<&str> {
        match self {
            Diagnostic::DanglingEnd { curve, .. }
            | Diagnostic::IsolatedCurve { curve, .. }
            | Diagnostic::SelfIntersection { curve, .. }
            | Diagnostic::ZeroLength { curve, .. }
            | Diagnostic::UnusedEdges { curve, .. }
            | Diagnostic::NonManifoldEdge { curve, .. } => vec![curve.as_str()],
            Diagnostic::NearMiss { curves, .. }
            | Diagnostic::DuplicateCurve { curves, .. }
            | Diagnostic::Overlap { curves, .. } => curves.iter().map(String::as_str).collect(),
            Diagnostic::UnclosedRegion { curves, .. }
            | Diagnostic::UnusualFace { curves, .. }
            | Diagnostic::NonManifoldNode { curves, .. } => {
                curves.iter().map(String::as_str).collect()
            }
            Diagnostic::Genus { .. } | Diagnostic::InvalidTopology { .. } => Vec::new(),
        }
    }

    /// A short stable tag (H-rep §5.2 findings) for the kind of finding (`"near_miss"`, `"dangling_end"`, …), for the
    /// binding and for filtering.
    pub fn kind(&self) -> &'static str {
        match self {
            Diagnostic::DanglingEnd { .. } => "dangling_end",
            Diagnostic::IsolatedCurve { .. } => "isolated_curve",
            Diagnostic::NearMiss { .. } => "near_miss",
            Diagnostic::DuplicateCurve { .. } => "duplicate_curve",
            Diagnostic::Overlap { .. } => "overlap",
            Diagnostic::SelfIntersection { .. } => "self_intersection",
            Diagnostic::ZeroLength { .. } => "zero_length",
            Diagnostic::UnusedEdges { .. } => "unused_edges",
            Diagnostic::UnclosedRegion { .. } => "unclosed_region",
            Diagnostic::NonManifoldEdge { .. } => "non_manifold_edge",
            Diagnostic::NonManifoldNode { .. } => "non_manifold_node",
            Diagnostic::UnusualFace { .. } => "unusual_face",
            Diagnostic::Genus { .. } => "genus",
            Diagnostic::InvalidTopology { .. } => "invalid_topology",
        }
    }

    /// Where the finding is, if it has a place (H-rep §5.2).
    pub fn location(&self) -> Option<DVec3> {
        match self {
            Diagnostic::DanglingEnd { location, .. }
            | Diagnostic::IsolatedCurve { location, .. }
            | Diagnostic::NearMiss { location, .. }
            | Diagnostic::DuplicateCurve { location, .. }
            | Diagnostic::SelfIntersection { location, .. }
            | Diagnostic::ZeroLength { location, .. }
            | Diagnostic::UnusedEdges { location, .. }
            | Diagnostic::UnclosedRegion { location, .. }
            | Diagnostic::NonManifoldEdge { location, .. }
            | Diagnostic::NonManifoldNode { location, .. }
            | Diagnostic::UnusualFace { location, .. }
            | Diagnostic::Genus { location, .. } => Some(*location),
            Diagnostic::Overlap { from, .. } => Some(*from),
            Diagnostic::InvalidTopology { .. } => None,
        }
    }
}

fn at(p: &DVec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", p.x, p.y, p.z)
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Diagnostic::DanglingEnd { curve, location } => {
                write!(
                    f,
                    "curve '{curve}' ends at {} on no other curve",
                    at(location)
                )
            }
            Diagnostic::IsolatedCurve { curve, location } => {
                write!(
                    f,
                    "curve '{curve}' (starting at {}) meets no other curve",
                    at(location)
                )
            }
            Diagnostic::NearMiss {
                curves: [a, b],
                location,
                gap,
            } => write!(
                f,
                "curves '{a}' and '{b}' miss each other by {gap:.3e} m at {}",
                at(location)
            ),
            Diagnostic::DuplicateCurve {
                curves: [a, b],
                location,
            } => write!(
                f,
                "curve '{b}' duplicates '{a}' (at {}); '{b}' is left out",
                at(location)
            ),
            Diagnostic::Overlap {
                curves: [a, b],
                from,
                to,
            } => write!(
                f,
                "curves '{a}' and '{b}' overlap from {} to {}",
                at(from),
                at(to)
            ),
            Diagnostic::SelfIntersection {
                curve,
                location,
                gap,
            } => write!(
                f,
                "curve '{curve}' crosses itself at {} (gap {gap:.3e} m)",
                at(location)
            ),
            Diagnostic::ZeroLength { curve, location } => write!(
                f,
                "curve '{curve}' at {} is shorter than the tolerance",
                at(location)
            ),
            Diagnostic::UnusedEdges {
                curve,
                edges,
                location,
            } => write!(
                f,
                "{edges} edge(s) of curve '{curve}' (near {}) bound no face",
                at(location)
            ),
            Diagnostic::UnclosedRegion { curves, location } => write!(
                f,
                "the region bounded by {} (near {}) could not be closed into a face",
                curves.join(", "),
                at(location)
            ),
            Diagnostic::NonManifoldEdge { curve, location } => write!(
                f,
                "an edge of curve '{curve}' at {} is not bounded by exactly two sides",
                at(location)
            ),
            Diagnostic::NonManifoldNode { curves, location } => write!(
                f,
                "at {} the curves {} do not lie in one surface (the surface branches)",
                at(location),
                curves.join(", ")
            ),
            Diagnostic::UnusualFace {
                face,
                corners,
                curves,
                location,
            } => write!(
                f,
                "face {face} (bounded by {}, near {}) has {corners} corners",
                curves.join(", "),
                at(location)
            ),
            Diagnostic::Genus { genus, location } => write!(
                f,
                "the network near {} traces a surface of genus {genus}",
                at(location)
            ),
            Diagnostic::InvalidTopology { message } => write!(f, "invalid topology: {message}"),
        }
    }
}
