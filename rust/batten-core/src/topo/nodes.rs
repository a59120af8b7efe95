//! Step 1 of [`Topology::build`](super::Topology::build): one B-rep vertex per node of the
//! network (H-rep paper §3.1: where the designer's curves meet, or a free curve end).

use glam::DVec3;
use smallvec::SmallVec;

use super::brep::Vertex;
use crate::network::Junctions;

/// The vertices of the nodes of `junctions`, in node order, each with the designer curves
/// through it (sorted, without repeats); no half-edge and no normal yet.
pub(crate) fn vertices(junctions: &Junctions) -> Vec<Vertex> {
    junctions
        .nodes
        .iter()
        .map(|j| {
            let mut names: SmallVec<[usize; 4]> = j.incidences.iter().map(|i| i.curve).collect();
            names.sort_unstable();
            names.dedup();
            Vertex {
                position: j.position,
                curves: names,
                outgoing: None,
                normal: DVec3::ZERO,
            }
        })
        .collect()
}
