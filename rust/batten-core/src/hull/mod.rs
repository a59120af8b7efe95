//! The H-rep pipeline of the paper end to end: curve network → topology (§3.1, §5.2) → one
//! surface patch per face (§3.2.1) with tangent ribbons from the crossing curves (§3.2.2, eq. 8
//! and the 15° rule) and knuckles (G0 creases) where the designer drew them → one welded mesh,
//! with a report of what was built and how well it fits the curves.
//!
//! - [`ribbons`]: one shared [`EdgeNormal`](crate::EdgeNormal) per smooth edge (G1 across it),
//!   one per face on knuckle edges (G0).
//! - [`knuckles`]: which edges are knuckles (role, or corner points of crossing curves), and
//!   the report's [`KnuckleEdge`]s.
//! - [`build`]: the face boundaries, the patches, the tessellation and its orientation.
//! - [`report`]: gaps, normal jumps, crease angles and volume.

mod build;
mod knuckles;
mod report;
mod ribbons;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::error::Error;
use crate::network::Network;
use crate::patch::SurfaceMesh;
use crate::tolerance::Tolerance;

pub use knuckles::{KnuckleEdge, KnuckleSource, KNUCKLE_EDGE_SAMPLES, KNUCKLE_POINT_ANGLE_DEGREES};

/// Options of [`build_hull`] (H-rep paper §3: the model tolerance of the topology and the
/// patches, and the density of the display mesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullOptions {
    /// The model tolerance: nodes closer than it are one node (§3.1), gaps between a face's
    /// sides up to 10× it are closed by the patches (§3.2.1).
    pub tolerance: Tolerance,
    /// Tessellation intervals per side segment (per topological edge) of every patch; at least 1.
    pub resolution: usize,
}

impl Default for HullOptions {
    /// The default tolerance (0.1 mm) and 8 intervals per edge.
    fn default() -> Self {
        HullOptions {
            tolerance: Tolerance::DEFAULT,
            resolution: 8,
        }
    }
}

/// What [`build_hull`] built and how good it is (H-rep paper §3–§5: counts of the topology,
/// continuity across the network's edges, and the designer's first hydrostatic check).
/// Serialises (serde) as a JSON object with these field names.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HullReport {
    /// Nodes of the topology (§3.1 vertices).
    pub nodes: usize,
    /// Edges of the topology (§3.1: curve stretches between nodes), including those bounding no
    /// face.
    pub edges: usize,
    /// Faces that became patches (§3.2.1).
    pub faces: usize,
    /// Patches by number of sides: `{3: …, 4: …, 5: …}` (§3.2.1 three-, four-, N-sided).
    pub faces_by_sides: BTreeMap<usize, usize>,
    /// Faces of the topology that could not be patched (each is named in `warnings`).
    pub skipped_faces: usize,
    /// Edges used by exactly one patch: the open boundary of the surface (keel, stem, deck …).
    pub open_edges: usize,
    /// Largest distance (m) between a network curve and the patch side that should lie on it,
    /// sampled along every side segment (the patches interpolate the curves, §3.2.1).
    pub max_gap: f64,
    /// Largest angle (degrees) between the two patches' normals across a smooth edge, sampled
    /// along every edge shared by two patches (GC¹ of §3.2.2: ideally 0).
    pub max_normal_angle_deg: f64,
    /// Per knuckle curve: its name and the smallest and largest angle (degrees) between the two
    /// patches' normals along it (the crease the designer drew, §1 "knuckles").
    pub crease_angles_deg: Vec<(String, f64, f64)>,
    /// Every knuckle edge (G0 crease), in the topology's edge order: its curve, whether the
    /// designer's role or batten's corner rule made it a knuckle, its crease angles and a
    /// polyline along it (so a front end can show which creases were found automatically).
    pub knuckle_edges: Vec<KnuckleEdge>,
    /// Volume (m³) between the surface and the centreplane `y = 0`, closed by lids
    /// perpendicular to the centreplane: `|Σ ȳ·n_y·A|` over the mesh triangles (the divergence
    /// theorem with the field `(0, y, 0)`, exact for the mesh); for the drawn half only.
    pub volume: f64,
    /// Every topology diagnostic (its `Display`), every patch warning and every skipped face,
    /// naming the curves involved (§5.2: the system tells the designer what it resolved).
    pub warnings: Vec<String>,
}

/// The hull surface: the welded mesh of all patches and its report (H-rep paper §3).
#[derive(Clone, Debug, PartialEq)]
pub struct HullSurface {
    /// One welded mesh; `face_patch` holds, for every polygon, the index of its face in the
    /// topology (`Topology::faces`, §3.1; a skipped face has no polygons). Consistently
    /// oriented, normals pointing away from the centreplane for a port half.
    pub mesh: SurfaceMesh,
    /// What was built and how well.
    pub report: HullReport,
}

/// Build the hull surface of a curve network (the H-rep paper's pipeline, §3 and §5.2).
///
/// 1. [`Topology::build`](crate::Topology::build): nodes, edges, faces with their true corners.
/// 2. Knuckle edges: curves with role `Knuckle`, and edges whose end node is a
///    corner point (tangent jump above [`KNUCKLE_POINT_ANGLE_DEGREES`]) of a crossing curve —
///    the paper's chines "connecting the knuckles in each cross section" (§5).
/// 3. Ribbons (§3.2.2): every smooth edge gets ONE surface normal field from the tangents of
///    all curves crossing it at its end nodes (eq. 8, crossings within 15° of the edge
///    ignored), given to both its faces, which makes them GC¹ along the whole edge; a knuckle
///    edge gives each face its own field from the crossing tangents on that face's side (the
///    loop neighbours of the edge in that face), so the surface is G0 there.
/// 4. Patches (§3.2.1): each face with 3..=[`MAX_SIDES`](crate::MAX_SIDES) sides becomes a
///    Gregory (4 sides) or Charrot–Gregory patch; sides are the topology's sides, composite
///    where a T-joint splits them; every segment carries the exact node positions, so faces
///    weld bitwise. A face that fails is skipped, named in the warnings and counted.
/// 5. Tessellation (in parallel), a finiteness check (a patch producing a non-finite point is
///    dropped), and orientation: the topology's faces are counter-clockwise about normals
///    propagated over the network, so the shell is consistent; if the mesh's area-weighted
///    mean normal has a negative `y` component the whole mesh is flipped, so a port half
///    (`y ≥ 0`) has outward normals.
///
/// Errors: the topology's own errors (curve kernel), a network without faces or with no face
/// that could be patched ([`Error::NoSurface`], naming the diagnostics), resolution 0.
pub fn build_hull(network: &Network, options: &HullOptions) -> Result<HullSurface, Error> {
    build::build(network, options)
}
