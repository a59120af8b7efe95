//! Step 5 of [`Topology::build`](super::Topology::build): the loops of the half-edges,
//! traced along `next`, and their sorting into faces and boundary loops (H-rep paper §3.1
//! edge-loops and faces, §5.2): a loop counter-clockwise about the node normals that runs along
//! no edge twice is a face; the others are boundary loops.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::brep::{Brep, Face, FaceId, HalfEdgeId, Loop, LoopId, ShellId};
use super::faces;
use super::topology::{BoundaryLoop, TopoFace};
use crate::curve::BezierDecomposition;
use crate::diagnostic::Diagnostic;
use crate::network::NetworkCurve;

/// Trace every loop of the half-edges along `next`, setting each half-edge's `loop_id`; each
/// loop belongs to the shell of its first half-edge's origin (`shell_of`, per vertex).
pub(crate) fn trace_loops(brep: &mut Brep, shell_of: &[usize]) {
    let mut visited = vec![false; brep.half_edges.len()];
    for i in 0..brep.half_edges.len() {
        if visited[i] {
            continue;
        }
        let l = LoopId::from_index(brep.loops.len());
        let first = HalfEdgeId::from_index(i);
        let mut h = first;
        loop {
            visited[h.index()] = true;
            brep.half_edges[h.index()].loop_id = l;
            h = brep.half_edges[h.index()].next;
            if h == first {
                break;
            }
        }
        let shell = shell_of[brep.half_edges[i].origin.index()];
        brep.loops.push(Loop {
            first,
            face: None,
            shell: ShellId::from_index(shell),
        });
    }
}

/// Loops per parallel task at least in [`sort_loops`].
const PAR_MIN_LOOPS: usize = 128;

/// What [`sort_loops`] reads of the geometry, per half-edge, node and edge.
pub(crate) struct LoopGeometry<'g> {
    /// The unit direction in which each half-edge leaves its origin.
    pub dirs: &'g [DVec3],
    /// The oriented unit normal at each node.
    pub normals: &'g [DVec3],
    /// Each edge's share of the vector area of a loop along it ([`faces::edge_areas`]).
    pub edge_areas: &'g [DVec3],
}

/// Sort the loops into faces (added to the B-rep and their shells, with their corners and
/// sides counted from the leaving directions `dirs`) and boundary loops (added to their
/// shells). A loop on the face side that runs along an edge twice bounds no disk: it becomes
/// a boundary loop and is reported as [`Diagnostic::UnclosedRegion`].
///
/// The loops are told apart in parallel, then the faces are made in parallel straight into
/// their list; the B-rep's face and shell lists are filled in loop order.
pub(crate) fn sort_loops(
    brep: &mut Brep,
    curves: &[NetworkCurve],
    evals: &[BezierDecomposition],
    geometry: LoopGeometry,
    diagnostics: &mut Vec<Diagnostic>,
) -> (Vec<TopoFace>, Vec<BoundaryLoop>) {
    let LoopGeometry {
        dirs,
        normals,
        edge_areas,
    } = geometry;
    let shared = &*brep;
    // Per loop: (on the face side, runs along an edge twice).
    let kinds: Vec<(bool, bool)> = (0..shared.loops.len())
        .into_par_iter()
        .with_min_len(PAR_MIN_LOOPS)
        .map_init(Vec::new, |hs, li| {
            let l = LoopId::from_index(li);
            shared.loop_half_edges_into(l, hs);
            let (area, normal) = faces::loop_orientation(shared, evals, edge_areas, normals, l, hs);
            (area.dot(normal) > 0.0, faces::has_bridge(shared, hs))
        })
        .collect();
    let face_loops: Vec<usize> = (0..kinds.len())
        .filter(|&li| kinds[li].0 && !kinds[li].1)
        .collect();
    let mut topo_faces = Vec::new();
    face_loops
        .par_iter()
        .with_min_len(PAR_MIN_LOOPS)
        .map_init(
            || (Vec::new(), Vec::new()),
            |(hs, corner_flags), &li| {
                shared.loop_half_edges_into(LoopId::from_index(li), hs);
                let (corners, sides) = faces::corners_and_sides(shared, dirs, hs, corner_flags);
                TopoFace {
                    edges: hs.iter().map(|&h| shared.half_edge(h).edge).collect(),
                    forward: hs.iter().map(|&h| shared.is_forward(h)).collect(),
                    corners,
                    sides,
                    curves: sorted_curves(shared, hs),
                }
            },
        )
        .collect_into_vec(&mut topo_faces);
    let mut boundary_loops = Vec::new();
    let mut hs = Vec::new();
    for (li, &(face_side, bridge)) in kinds.iter().enumerate() {
        let l = LoopId::from_index(li);
        let shell = brep.loops[li].shell;
        if face_side && !bridge {
            let f = FaceId::from_index(brep.faces.len());
            brep.faces.push(Face { outer: l, shell });
            brep.loops[li].face = Some(f);
            brep.shells[shell.index()].faces.push(f);
            continue;
        }
        brep.loop_half_edges_into(l, &mut hs);
        let names = sorted_curves(brep, &hs);
        if face_side {
            diagnostics.push(Diagnostic::UnclosedRegion {
                curves: names.iter().map(|&c| curves[c].name.clone()).collect(),
                location: brep.vertices[brep.half_edge(hs[0]).origin.index()].position,
            });
        }
        brep.shells[shell.index()].boundaries.push(l);
        boundary_loops.push(BoundaryLoop {
            edges: hs.iter().map(|&h| brep.half_edge(h).edge).collect(),
            curves: names.to_vec(),
        });
    }
    (topo_faces, boundary_loops)
}

/// The designer curves along a loop, sorted, without repeats.
fn sorted_curves(brep: &Brep, hs: &[HalfEdgeId]) -> SmallVec<[usize; 4]> {
    let mut curves: SmallVec<[usize; 4]> = hs
        .iter()
        .map(|&h| brep.edges[brep.half_edge(h).edge.index()].curve)
        .collect();
    curves.sort_unstable();
    curves.dedup();
    curves
}
