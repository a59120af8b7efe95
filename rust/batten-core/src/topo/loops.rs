//! Step 5 of [`Topology::build`](super::Topology::build): the loops of the half-edges,
//! traced along `next`, and their sorting into faces and boundary loops (H-rep paper §3.1
//! edge-loops and faces, §5.2): a loop counter-clockwise about the node normals that runs along
//! no edge twice is a face; the others are boundary loops.

use glam::DVec3;
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

/// Sort the loops into faces (added to the B-rep and their shells, with their corners and
/// sides counted from the leaving directions `dirs`) and boundary loops (added to their
/// shells). A loop on the face side that runs along an edge twice bounds no disk: it becomes
/// a boundary loop and is reported as [`Diagnostic::UnclosedRegion`].
pub(crate) fn sort_loops(
    brep: &mut Brep,
    curves: &[NetworkCurve],
    evals: &[BezierDecomposition],
    dirs: &[DVec3],
    normals: &[DVec3],
    diagnostics: &mut Vec<Diagnostic>,
) -> (Vec<TopoFace>, Vec<BoundaryLoop>) {
    let edge_areas = faces::edge_areas(brep, evals);
    let mut topo_faces = Vec::with_capacity(brep.loops.len());
    let mut boundary_loops = Vec::new();
    let mut edge_stamp = vec![0u32; brep.edges.len()];
    let (mut hs, mut corner_flags) = (Vec::new(), Vec::new());
    for li in 0..brep.loops.len() {
        let l = LoopId::from_index(li);
        brep.loop_half_edges_into(l, &mut hs);
        let (area, normal) = faces::loop_orientation(brep, evals, &edge_areas, normals, l, &hs);
        let is_face_side = area.dot(normal) > 0.0;
        let bridge = faces::has_bridge(brep, &hs, &mut edge_stamp, li as u32 + 1);
        let shell = brep.loops[li].shell;
        let names = sorted_curves(brep, &hs);
        if is_face_side && !bridge {
            let f = FaceId::from_index(brep.faces.len());
            brep.faces.push(Face { outer: l, shell });
            brep.loops[li].face = Some(f);
            brep.shells[shell.index()].faces.push(f);
            let (corners, sides) = faces::corners_and_sides(brep, dirs, &hs, &mut corner_flags);
            topo_faces.push(TopoFace {
                edges: hs.iter().map(|&h| brep.half_edge(h).edge).collect(),
                forward: hs.iter().map(|&h| brep.is_forward(h)).collect(),
                corners,
                sides,
                curves: names,
            });
        } else {
            if is_face_side {
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
