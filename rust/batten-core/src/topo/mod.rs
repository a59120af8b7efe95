//! Topology of a curve network (H-rep paper §3.1): nodes where the designer's curves meet,
//! edges as parameter intervals of those curves, a half-edge B-rep, and faces found
//! automatically (§5.2) with their true corners, plus diagnostics that name curves and places.
//!
//! [`Topology::build`] is the pipeline; each step is a module: [`nodes`] → [`edges`] →
//! [`half_edges`] → [`linking`] (the rotation system, its normals oriented by
//! [`orientation`]) → [`shells`] and [`loops`] (faces and boundary loops) → [`findings`] (with
//! the B-rep [`checks`]).

mod brep;
mod checks;
mod edges;
mod faces;
mod findings;
mod half_edges;
mod linking;
mod loops;
mod node_kind;
mod nodes;
mod orientation;
mod rotation;
mod shells;
mod topology;

pub use brep::{
    Brep, Edge, EdgeId, Face, FaceId, HalfEdge, HalfEdgeId, Loop, LoopId, Shell, ShellId, Vertex,
    VertexId,
};
pub use checks::{EdgeFacesError, EulerPoincareError, NextPrevError, TwinError, ValidationError};
pub use faces::{FaceSide, CORNER_ANGLE_DEGREES};
pub use findings::{MAX_NORMAL_CORNERS, MIN_CORNERS};
pub use linking::BRANCHING_TIP_DISTANCE;
pub use node_kind::NodeKind;
pub use topology::{BoundaryLoop, TopoFace, Topology};

use crate::error::Error;
use crate::network::Network;
use crate::tolerance::Tolerance;

impl Topology {
    /// Build the topology of `network` at `tolerance` (H-rep paper §3.1 and §5.2).
    ///
    /// 1. Nodes: [`Network::junctions`] (end to end, T-joints, crossings within tolerance).
    /// 2. Edges: each curve is cut at its nodes into parameter intervals `[t0, t1]`; the
    ///    designer's curve stays the fundamental entity.
    /// 3. Branches that cannot bound a region (dangling ends and the edges leading to them) are
    ///    pruned and reported; the rest gets half-edges.
    /// 4. At each node the edges are sorted counter-clockwise about a surface normal estimated
    ///    from the edge tangents and oriented consistently by propagation over the network.
    /// 5. Loops are traced with "next = the edge immediately clockwise from the twin"; a loop
    ///    that is counter-clockwise about the normals is a face, the others are boundary loops.
    /// 6. Each face's corners are counted: the boundary turning by 15° or more (§3.2.2).
    /// 7. The B-rep is validated; a failure becomes
    ///    [`Diagnostic::InvalidTopology`](crate::Diagnostic::InvalidTopology).
    ///
    /// Bad input (near misses, dangling ends, duplicates, overlaps, self-intersections,
    /// zero-length curves, faces with too few or too many corners) is reported in
    /// [`Topology::diagnostics`], never a panic; the error case is reserved for the curve kernel.
    ///
    /// Implementation note: corners are counted at nodes only, so a kink inside a curve between
    /// two nodes does not make a corner; a self-intersection makes no node; edges on dangling
    /// branches stay in `brep.edges` without half-edges.
    pub fn build(network: &Network, tolerance: Tolerance) -> Result<Topology, Error> {
        rayon::scope(|_| Self::build_in_pool(network, tolerance))
    }

    /// [`Topology::build`] on a thread of rayon's pool (where `build` puts it). Called from
    /// outside the pool, each parallel step would hand its work to the pool's threads and wait,
    /// and between the steps those threads would spin on the cores the calling thread needs:
    /// on two cores the 130 × 66 grid's narrow phase took 3.5 ms so, and 2.1 ms from inside the
    /// pool.
    fn build_in_pool(network: &Network, tolerance: Tolerance) -> Result<Topology, Error> {
        let (junctions, evals) = network.junctions_and_pieces(tolerance)?;
        let curves = network.curves();
        let mut diagnostics = junctions.diagnostics.clone();

        // 1–2. Nodes and edges; 3. the edges that can bound a region get half-edges.
        let mut brep = Brep {
            vertices: nodes::vertices(&junctions),
            ..Brep::default()
        };
        brep.edges = edges::cut_curves(curves, &junctions, &brep.vertices, tolerance);
        let core = edges::prune_branches(&brep);
        findings::loose_ends(curves, &junctions, &brep, &core, &mut diagnostics);
        // The half-edges and their directions, and beside them each edge's share of the vector
        // area of the loops along it (read in step 5).
        let ((new_half_edges, dirs), edge_areas) = rayon::join(
            || half_edges::half_edges(&brep.edges, &core, &evals),
            || faces::edge_areas(&brep, &core, &evals),
        );
        half_edges::attach(&mut brep, new_half_edges);

        // 4. Normals, the rotation system and the next/prev links.
        let mut rotation = linking::link(&mut brep, &dirs, &evals);
        findings::non_manifold_nodes(curves, &brep, &rotation.branching, &dirs, &mut diagnostics);

        // 5–6. Shells (connected parts), loops, faces with their corners, boundary loops.
        let shell_of = shells::components(&rotation.neighbours);
        loops::trace_loops(&mut brep, &shell_of);
        shells::add_shells(&mut brep, &shell_of);
        shells::orient_lone_parts(
            &mut brep,
            &evals,
            &rotation.raw,
            &mut rotation.normals,
            &shell_of,
        );
        let (faces, boundary_loops) = loops::sort_loops(
            &mut brep,
            curves,
            &evals,
            loops::LoopGeometry {
                dirs: &dirs,
                normals: &rotation.normals,
                edge_areas: &edge_areas,
            },
            &mut diagnostics,
        );
        shells::set_genus(&mut brep, &shell_of, &mut diagnostics);

        // 7. What the designer should know about the faces, and the B-rep checks.
        findings::unusual_faces(curves, &brep, &faces, &mut diagnostics);
        findings::invalid_topology(curves, &brep, &mut diagnostics);

        Ok(Topology {
            curve_names: curves.iter().map(|c| c.name.clone()).collect(),
            brep,
            faces,
            boundary_loops,
            diagnostics,
        })
    }
}
