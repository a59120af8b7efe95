//! Invariant: following `next` round a loop returns to its first half-edge; along the way
//! `prev(next(h)) == h`, each half-edge belongs to the loop, and `next(h)` starts where `h` ends.

use thiserror::Error;

use crate::topo::brep::{Brep, HalfEdgeId, LoopId};

/// A loop whose `next`/`prev` chain is broken (H-rep paper §3.1: "an ordered sequence of edges
/// is mapped to an edge-loop").
#[derive(Clone, Debug, Error, PartialEq)]
#[error("loop {loop_id:?}: at half-edge {half_edge:?}: {problem}")]
pub struct NextPrevError {
    /// The loop.
    pub loop_id: LoopId,
    /// The half-edge where the chain breaks.
    pub half_edge: HalfEdgeId,
    /// What is wrong there.
    pub problem: &'static str,
}

/// One error per loop, at the first place its chain breaks.
pub(crate) fn check(brep: &Brep) -> Vec<NextPrevError> {
    let mut out = Vec::new();
    for (i, l) in brep.loops.iter().enumerate() {
        let loop_id = LoopId::from_index(i);
        let mut h = l.first;
        let mut steps = 0;
        let problem = loop {
            let he = brep.half_edge(h);
            if he.loop_id != loop_id {
                break Some("belongs to another loop");
            }
            let next = he.next;
            if brep.half_edge(next).prev != h {
                break Some("prev(next(h)) is not h");
            }
            if brep.half_edge(next).origin != brep.destination(h) {
                break Some("next(h) does not start where h ends");
            }
            h = next;
            steps += 1;
            if h == l.first {
                break None;
            }
            if steps > brep.half_edges.len() {
                break Some("next chain does not return to the loop's first half-edge");
            }
        };
        if let Some(problem) = problem {
            out.push(NextPrevError {
                loop_id,
                half_edge: h,
                problem,
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
    fn valid_brep_passes_and_one_broken_prev_fails_once() {
        let mut brep = fixture::grid();
        assert_eq!(check(&brep).len(), 0, "valid B-rep has no next/prev errors");
        let h = brep.half_edges[0].next;
        brep.half_edges[h.index()].prev = h;
        assert_eq!(check(&brep).len(), 1, "one broken prev gives one error");
    }
}
