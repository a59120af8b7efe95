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
    let mut uses = vec![0usize; brep.edges.len()];
    let mut faces: Vec<Vec<FaceId>> = vec![Vec::new(); brep.edges.len()];
    for he in &brep.half_edges {
        let e = he.edge.index();
        uses[e] += 1;
        if let Some(f) = brep.loops[he.loop_id.index()].face {
            faces[e].push(f);
        }
    }
    let mut out = Vec::new();
    for (i, (n, mut fs)) in uses.into_iter().zip(faces).enumerate() {
        fs.sort();
        let repeated = fs.windows(2).any(|w| w[0] == w[1]);
        if n > 2 || repeated {
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
