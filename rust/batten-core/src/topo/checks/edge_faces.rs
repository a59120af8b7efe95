//! Invariant: every edge is used by at most two faces, and by one face at most once (an edge
//! with a face on both sides of it is a cut inside that face, not a boundary between faces).

use thiserror::Error;

use crate::topo::brep::{Brep, EdgeId, FaceId};

/// An edge used by more than two faces, or twice by one face (H-rep paper §3.1: faces are
/// "finite and non-self intersecting surface patches", so the shell is a manifold).
#[derive(Clone, Debug, Error, PartialEq)]
#[error("edge {edge:?} is used {uses} times, by faces {faces:?}")]
pub struct EdgeFacesError {
    /// The edge.
    pub edge: EdgeId,
    /// How many half-edges refer to it.
    pub uses: usize,
    /// The faces of those half-edges (boundary loops give none).
    pub faces: Vec<FaceId>,
}

/// One error per edge that is used by more than two half-edges or by one face twice.
pub(crate) fn check(brep: &Brep) -> Vec<EdgeFacesError> {
    // Uses and the first two faces of every edge; the full face list is gathered only for
    // the (rare) edges that fail.
    let mut uses = vec![0usize; brep.edges.len()];
    let mut first: Vec<[Option<FaceId>; 2]> = vec![[None; 2]; brep.edges.len()];
    let face_of = |he: &crate::topo::brep::HalfEdge| brep.loops[he.loop_id.index()].face;
    for he in &brep.half_edges {
        let e = he.edge.index();
        if let Some(f) = face_of(he) {
            let slot = &mut first[e];
            if slot[0].is_none() {
                slot[0] = Some(f);
            } else if slot[1].is_none() {
                slot[1] = Some(f);
            }
        }
        uses[e] += 1;
    }
    let mut out = Vec::new();
    for (i, &n) in uses.iter().enumerate() {
        let repeated = matches!(first[i], [Some(a), Some(b)] if a == b);
        if n > 2 || repeated {
            let mut fs: Vec<FaceId> = brep
                .half_edges
                .iter()
                .filter(|he| he.edge.index() == i)
                .filter_map(face_of)
                .collect();
            fs.sort();
            out.push(EdgeFacesError {
                edge: EdgeId::from_index(i),
                uses: n,
                faces: fs,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topo::checks::fixture;

    #[test]
    fn valid_brep_passes_and_one_edge_on_both_sides_of_a_face_fails_once() {
        let mut brep = fixture::grid();
        assert_eq!(check(&brep).len(), 0, "valid B-rep has no edge-use errors");
        // Put one half-edge of an inner edge into the loop of its twin's face.
        let (i, he) = brep
            .half_edges
            .iter()
            .enumerate()
            .find(|(_, he)| {
                let twin = brep.half_edge(he.twin);
                brep.loops[he.loop_id.index()].face.is_some()
                    && brep.loops[twin.loop_id.index()].face.is_some()
            })
            .expect("an inner edge");
        let twin_loop = brep.half_edge(he.twin).loop_id;
        brep.half_edges[i].loop_id = twin_loop;
        assert_eq!(
            check(&brep).len(),
            1,
            "one doubly used edge gives one error"
        );
    }
}
