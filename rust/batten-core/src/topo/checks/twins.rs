//! Invariant: the two half-edges of an edge are each other's twins and run between the edge's
//! end vertices in opposite directions.

use thiserror::Error;

use crate::topo::brep::{Brep, EdgeId, HalfEdgeId, VertexId};

/// The half-edges of an edge are not a twin pair running in opposite directions (H-rep paper
/// §3.1 half-edge structure).
#[derive(Clone, Debug, Error, PartialEq)]
#[error(
    "edge {edge:?}: half-edges {half_edges:?} have twins {twins:?} and origins {origins:?}, \
     expected each other and ({start:?}, {end:?})"
)]
pub struct TwinError {
    /// The edge.
    pub edge: EdgeId,
    /// Its two half-edges.
    pub half_edges: [HalfEdgeId; 2],
    /// Their recorded twins.
    pub twins: [HalfEdgeId; 2],
    /// Their recorded origins.
    pub origins: [VertexId; 2],
    /// The edge's start vertex.
    pub start: VertexId,
    /// The edge's end vertex.
    pub end: VertexId,
}

/// One error per edge whose half-edges are not twins of each other, refer to another edge, or
/// do not start at the edge's two ends.
pub(crate) fn check(brep: &Brep) -> Vec<TwinError> {
    let mut out = Vec::new();
    for (i, e) in brep.edges.iter().enumerate() {
        let Some([a, b]) = e.half_edges else {
            continue;
        };
        let (ha, hb) = (brep.half_edge(a), brep.half_edge(b));
        let id = EdgeId::from_index(i);
        let ok = ha.twin == b
            && hb.twin == a
            && ha.edge == id
            && hb.edge == id
            && ha.origin == e.start
            && hb.origin == e.end;
        if !ok {
            out.push(TwinError {
                edge: id,
                half_edges: [a, b],
                twins: [ha.twin, hb.twin],
                origins: [ha.origin, hb.origin],
                start: e.start,
                end: e.end,
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
    fn valid_brep_passes_and_one_broken_twin_fails_once() {
        let mut brep = fixture::grid();
        assert_eq!(check(&brep).len(), 0, "valid B-rep has no twin errors");
        brep.half_edges[0].twin = HalfEdgeId(0);
        assert_eq!(check(&brep).len(), 1, "one broken twin gives one error");
    }
}
