//! Invariant (Euler–Poincaré for surfaces with boundary): for every shell,
//! `V − E + F = 2 − 2g − b`, with `b` its boundary loops and `g` its recorded genus.

use thiserror::Error;

use crate::topo::brep::{Brep, ShellId};

/// A shell whose counts break the Euler–Poincaré formula (H-rep paper §3.1 shell; Mäntylä's
/// Euler operators keep it).
#[derive(Clone, Debug, Error, PartialEq)]
#[error("shell {shell:?}: V − E + F = {v} − {e} + {f} ≠ 2 − 2·{genus} − {b}")]
pub struct EulerPoincareError {
    /// The shell.
    pub shell: ShellId,
    /// Vertices on the shell's half-edges.
    pub v: usize,
    /// Edges of the shell's half-edges.
    pub e: usize,
    /// Faces of the shell.
    pub f: usize,
    /// Boundary loops of the shell.
    pub b: usize,
    /// The genus recorded in the shell.
    pub genus: i64,
}

/// One error per shell whose vertex, edge, face and boundary counts (collected from the loops
/// it lists) do not satisfy `V − E + F = 2 − 2g − b`.
pub(crate) fn check(brep: &Brep) -> Vec<EulerPoincareError> {
    let mut out = Vec::new();
    for (i, shell) in brep.shells.iter().enumerate() {
        let mut vertex_seen = vec![false; brep.vertices.len()];
        let mut edge_seen = vec![false; brep.edges.len()];
        let (mut v, mut e) = (0, 0);
        let mut hs = Vec::new();
        let loops = shell
            .faces
            .iter()
            .map(|f| brep.faces[f.index()].outer)
            .chain(shell.boundaries.iter().copied());
        for l in loops {
            brep.loop_half_edges_into(l, &mut hs);
            for &h in &hs {
                let he = brep.half_edge(h);
                if !std::mem::replace(&mut vertex_seen[he.origin.index()], true) {
                    v += 1;
                }
                if !std::mem::replace(&mut edge_seen[he.edge.index()], true) {
                    e += 1;
                }
            }
        }
        let (f, b) = (shell.faces.len(), shell.boundaries.len());
        let lhs = v as i64 - e as i64 + f as i64;
        if lhs != 2 - 2 * shell.genus - b as i64 {
            out.push(EulerPoincareError {
                shell: ShellId::from_index(i),
                v,
                e,
                f,
                b,
                genus: shell.genus,
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
    fn valid_brep_passes_and_a_lost_boundary_fails_once() {
        let mut brep = fixture::grid();
        assert_eq!(
            check(&brep).len(),
            0,
            "valid B-rep satisfies Euler–Poincaré"
        );
        let boundary = brep.shells[0].boundaries.pop();
        assert!(boundary.is_some(), "the grid has a boundary loop");
        assert_eq!(
            check(&brep).len(),
            1,
            "a shell that lost its boundary gives one error"
        );
    }
}
