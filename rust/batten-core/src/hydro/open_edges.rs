//! The free edges of a polygon mesh walked into chains ([`OpenChain`]): where a surface is open.

use std::collections::HashMap;

use glam::DVec3;

use super::geometry::OpenChain;

/// The edges used by exactly one face, each as `(smaller, larger)` vertex index, sorted.
pub(crate) fn free_edge_list<'a>(faces: impl Iterator<Item = &'a [u32]>) -> Vec<(u32, u32)> {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for f in faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let mut out: Vec<(u32, u32)> = uses
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect();
    out.sort_unstable();
    out
}

/// Walk `edges` into chains of points: from every vertex that is not on exactly two edges (an
/// end, or a branch), then round what is left (loops).
pub(crate) fn chains(positions: &[DVec3], edges: &[(u32, u32)]) -> Vec<OpenChain> {
    let mut adj: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, &(a, b)) in edges.iter().enumerate() {
        adj.entry(a).or_default().push(k);
        adj.entry(b).or_default().push(k);
    }
    let mut used = vec![false; edges.len()];
    let mut out = Vec::new();
    let walk = |start: u32, used: &mut Vec<bool>| -> Option<OpenChain> {
        let mut v = start;
        let mut pts = vec![positions[v as usize]];
        loop {
            let next = adj[&v].iter().copied().find(|&k| !used[k]);
            let Some(k) = next else { break };
            used[k] = true;
            let (a, b) = edges[k];
            v = if a == v { b } else { a };
            pts.push(positions[v as usize]);
            if adj[&v].len() != 2 || v == start {
                break;
            }
        }
        let closed = v == start && pts.len() > 2;
        if closed {
            pts.pop();
        }
        (pts.len() > 1).then(|| OpenChain {
            points: pts,
            closed,
            curves: Vec::new(),
        })
    };
    let mut starts: Vec<u32> = adj
        .iter()
        .filter(|(_, e)| e.len() != 2)
        .map(|(&v, _)| v)
        .collect();
    starts.sort_unstable();
    for s in starts {
        while adj[&s].iter().any(|&k| !used[k]) {
            if let Some(c) = walk(s, &mut used) {
                out.push(c);
            }
        }
    }
    for k in 0..edges.len() {
        if !used[k] {
            if let Some(c) = walk(edges[k].0, &mut used) {
                out.push(c);
            }
        }
    }
    out
}
