//! The shells of a topology (H-rep paper §3.1: "the boundary of the ship hull is topologically
//! described by a shell entity"): the connected parts of the network, the normal of a part
//! whose tangents define none, and each shell's genus.

use glam::DVec3;

use super::brep::{Brep, LoopId, Shell};
use super::faces;
use super::rotation::RawNormal;
use crate::adjacency::Adjacency;
use crate::curve::BezierDecomposition;
use crate::diagnostic::Diagnostic;

/// Connected parts of the graph: a part index per vertex (`usize::MAX` for lone vertices).
pub(crate) fn components(neighbours: &Adjacency<usize>) -> Vec<usize> {
    let mut part = vec![usize::MAX; neighbours.rows()];
    let mut count = 0;
    let mut stack = Vec::new();
    for s in 0..neighbours.rows() {
        if part[s] != usize::MAX || neighbours.row(s).is_empty() {
            continue;
        }
        part[s] = count;
        stack.push(s);
        while let Some(u) = stack.pop() {
            for &v in neighbours.row(u) {
                if part[v] == usize::MAX {
                    part[v] = count;
                    stack.push(v);
                }
            }
        }
        count += 1;
    }
    part
}

/// One empty shell per connected part of `shell_of` (the part index of every vertex, as from
/// [`components`]).
pub(crate) fn add_shells(brep: &mut Brep, shell_of: &[usize]) {
    let shell_count = shell_of
        .iter()
        .copied()
        .filter(|&s| s != usize::MAX)
        .max()
        .map_or(0, |m| m + 1);
    brep.shells = vec![
        Shell {
            faces: Vec::new(),
            boundaries: Vec::new(),
            genus: 0,
        };
        shell_count
    ];
}

/// A part whose nodes all have parallel tangents (a lone closed curve: no vertex of it has a
/// `raw` normal) has no normal from its tangents: give all its vertices the direction of its
/// first loop's vector area, in `normals` and in the B-rep.
pub(crate) fn orient_lone_parts(
    brep: &mut Brep,
    evals: &[BezierDecomposition],
    raw: &[Option<RawNormal>],
    normals: &mut [DVec3],
    shell_of: &[usize],
) {
    let mut has_normal = vec![false; brep.shells.len()];
    for (v, r) in raw.iter().enumerate() {
        if r.is_some() && shell_of[v] != usize::MAX {
            has_normal[shell_of[v]] = true;
        }
    }
    for (si, _) in has_normal.iter().enumerate().filter(|(_, &h)| !h) {
        let Some(li) = brep.loops.iter().position(|l| l.shell.index() == si) else {
            continue;
        };
        let (area, _) = faces::orientation(brep, evals, normals, LoopId::from_index(li));
        let n = area.normalize_or_zero();
        for v in 0..normals.len() {
            if shell_of[v] == si {
                normals[v] = n;
                brep.vertices[v].normal = n;
            }
        }
    }
}

/// The genus of every shell from its counts (Euler–Poincaré: `V − E + F + B = 2 − 2g` for a
/// shell with `B` boundary loops); a shell that is not a disk or a sphere is reported as
/// [`Diagnostic::Genus`].
pub(crate) fn set_genus(brep: &mut Brep, shell_of: &[usize], diagnostics: &mut Vec<Diagnostic>) {
    for (si, shell) in brep.shells.iter_mut().enumerate() {
        let v = shell_of.iter().filter(|&&s| s == si).count() as i64;
        let e = brep
            .edges
            .iter()
            .filter(|e| e.half_edges.is_some() && shell_of[e.start.index()] == si)
            .count() as i64;
        let chi = v - e + shell.faces.len() as i64 + shell.boundaries.len() as i64;
        shell.genus = (2 - chi) / 2;
        if shell.genus != 0 || chi % 2 != 0 {
            let location = shell_of
                .iter()
                .position(|&s| s == si)
                .map_or(DVec3::ZERO, |v| brep.vertices[v].position);
            diagnostics.push(Diagnostic::Genus {
                genus: shell.genus,
                location,
            });
        }
    }
}
