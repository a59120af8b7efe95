//! The free boundary of a triangle mesh (edges used by one triangle): whether the mesh is a
//! half hull open along the centreplane, and the points of its other free edges, the open top
//! marked as designed and every other loop as a hole.

use glam::DVec3;
use rustc_hash::FxHashMap;

use crate::hydro::geometry::{is_port_half, OpenChain};

/// The free boundary of a mesh, as the hydrostatics read it.
#[derive(Clone, Debug)]
pub(in crate::hydro) struct Boundary {
    /// A half hull: no vertex to starboard (beyond the centreplane tolerance) and free edges
    /// along the centreplane, which its mirror image closes.
    pub(in crate::hydro) half: bool,
    /// The chains of free edges off the centreplane (of the mesh as given: a half hull's image
    /// is the caps' business).
    pub(in crate::hydro) open: Vec<OpenChain>,
}

/// Edges used by exactly one triangle, each directed as in its triangle (so a free boundary
/// runs round its opening consistently); an edge of a triangle with a repeated corner is no
/// edge. Edges are grouped by their lower vertex (compressed rows): two passes over the
/// triangles and a sort of each vertex's few edges.
pub(super) fn free_edges(vertices: usize, triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let edges = |t: &[u32; 3]| {
        [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
            .into_iter()
            .filter(|(a, b)| a != b)
    };
    let mut starts = vec![0usize; vertices + 1];
    for t in triangles {
        for (a, b) in edges(t) {
            starts[a.min(b) as usize + 1] += 1;
        }
    }
    for v in 0..vertices {
        starts[v + 1] += starts[v];
    }
    let mut fill = starts.clone();
    // The other end of each edge, and whether the edge runs from the lower vertex.
    let mut others = vec![(0u32, false); starts[vertices]];
    for t in triangles {
        for (a, b) in edges(t) {
            let low = a.min(b) as usize;
            others[fill[low]] = (a.max(b), a < b);
            fill[low] += 1;
        }
    }
    let mut free = Vec::new();
    for v in 0..vertices {
        let row = &mut others[starts[v]..starts[v + 1]];
        row.sort_unstable_by_key(|e| e.0);
        let mut k = 0;
        while k < row.len() {
            let run = row[k..].iter().take_while(|e| e.0 == row[k].0).count();
            if run == 1 {
                let (b, forward) = row[k];
                free.push(if forward {
                    [v as u32, b]
                } else {
                    [b, v as u32]
                });
            }
            k += run;
        }
    }
    free
}

/// A chain of free edges: its vertices in order, and whether it closes on itself.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Chain {
    /// The chain's vertices in order along it.
    pub(super) vertices: Vec<u32>,
    /// Whether the last vertex joins the first.
    pub(super) closed: bool,
}

/// The directed `edges` joined end to start into chains: open ones from their free starts
/// first, then the loops. At a vertex with more than one way on, the first unused is taken.
pub(super) fn chains(edges: &[[u32; 2]]) -> Vec<Chain> {
    let mut outgoing: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
    let mut incoming: FxHashMap<u32, usize> = FxHashMap::default();
    for (k, &[a, b]) in edges.iter().enumerate() {
        outgoing.entry(a).or_default().push(k);
        *incoming.entry(b).or_default() += 1;
    }
    let mut used = vec![false; edges.len()];
    let open_starts = (0..edges.len()).filter(|&k| !incoming.contains_key(&edges[k][0]));
    let order: Vec<usize> = open_starts.chain(0..edges.len()).collect();
    let mut out = Vec::new();
    for k in order {
        if used[k] {
            continue;
        }
        used[k] = true;
        let [first, mut v] = edges[k];
        let mut vertices = vec![first, v];
        while let Some(&e) = outgoing
            .get(&v)
            .and_then(|ks| ks.iter().find(|&&e| !used[e]))
        {
            used[e] = true;
            v = edges[e][1];
            vertices.push(v);
        }
        let closed = vertices.len() > 2 && vertices.last() == vertices.first();
        if closed {
            vertices.pop();
        }
        out.push(Chain { vertices, closed });
    }
    out
}

/// The free boundary of the mesh `positions`, `triangles`; `centre_tol` is how far from `y = 0`
/// a vertex may be and still lie on the centreplane.
pub(in crate::hydro) fn boundary(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    centre_tol: f64,
) -> Boundary {
    let free = free_edges(positions.len(), triangles);
    let on_centre = |v: u32| positions[v as usize].y.abs() <= centre_tol;
    let min_y = positions.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let max_y = positions
        .iter()
        .map(|p| p.y)
        .fold(f64::NEG_INFINITY, f64::max);
    let on_centreplane = free.iter().any(|e| on_centre(e[0]) && on_centre(e[1]));
    let half = is_port_half(min_y, max_y, on_centreplane);
    let open: Vec<[u32; 2]> = free
        .into_iter()
        .filter(|e| !(half && on_centre(e[0]) && on_centre(e[1])))
        .collect();
    let open = chains(&open)
        .into_iter()
        .map(|c| OpenChain {
            points: c.vertices.iter().map(|&v| positions[v as usize]).collect(),
            closed: c.closed,
            curves: Vec::new(),
        })
        .collect();
    Boundary { half, open }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lone_triangle_has_three_free_edges_and_a_closed_tetrahedron_none() {
        assert_eq!(free_edges(3, &[[0, 1, 2]]).len(), 3, "one triangle");
        let tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        assert!(free_edges(4, &tet).is_empty(), "closed");
        let rim = free_edges(4, &tet[1..]);
        assert_eq!(rim.len(), 3, "one face removed");
        // The rim runs opposite to the removed face's winding (0, 2, 1): a loop 0 → 1 → 2.
        let c = chains(&rim);
        assert_eq!(c.len(), 1, "one loop");
        assert!(c[0].closed, "closed");
        let v = &c[0].vertices;
        let k = v.iter().position(|&i| i == 0).expect("vertex 0");
        assert_eq!(v[(k + 1) % 3], 1, "0 → 1 in {v:?}");
    }

    #[test]
    fn an_open_chain_starts_at_its_free_end() {
        let c = chains(&[[2, 3], [1, 2], [5, 6]]);
        assert_eq!(c.len(), 2, "{c:?}");
        assert_eq!(c[0].vertices, vec![1, 2, 3], "in order");
        assert!(!c[0].closed && !c[1].closed, "open");
    }
}
