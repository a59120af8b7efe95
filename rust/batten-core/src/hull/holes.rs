//! Holes in the surface: free edges (used by one patch only) that are not on the hull's own
//! boundary — the profile in the centreplane, the deck edge, the transom outline — grouped into
//! connected chains, each one warning naming the curves around it and where it is (the
//! real-ships issue: "the report tells the truth about the surface").

use glam::DVec3;

use super::warning::{Warning, WarningKind};
use crate::network::Network;
use crate::tolerance::Tolerance;
use crate::topo::Topology;

/// Samples along an edge (ends included) to decide whether it lies in the centreplane `y = 0`.
const CENTREPLANE_SAMPLES: usize = 8;

/// Whether a free edge is part of the hull's designed boundary: a curve whose role says so
/// (keel, stem, transom, deck) or an edge lying in the centreplane within the near-miss
/// distance (the profile of a half hull, whatever its role).
fn on_hull_boundary(network: &Network, topology: &Topology, edge: usize, near: f64) -> bool {
    let e = &topology.brep.edges[edge];
    let c = &network.curves()[e.curve];
    if c.role.bounds_hull() {
        return true;
    }
    (0..=CENTREPLANE_SAMPLES).all(|j| {
        let t = e.t0 + (e.t1 - e.t0) * j as f64 / CENTREPLANE_SAMPLES as f64;
        c.curve.point(t).y.abs() <= near
    })
}

/// Find `x`'s root in a union–find forest (path halving).
fn root(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// One warning per connected chain of free edges off the hull's boundary. `free` lists the
/// edges used by exactly one patch. The location is the chain's point nearest its centroid
/// (an edge midpoint, so it lies on the surface's rim); the curves are those of the chain's
/// edges, sorted by name.
pub(crate) fn hole_warnings(
    network: &Network,
    topology: &Topology,
    free: &[usize],
    tolerance: Tolerance,
) -> Vec<Warning> {
    let brep = &topology.brep;
    let holes: Vec<usize> = free
        .iter()
        .copied()
        .filter(|&k| !on_hull_boundary(network, topology, k, tolerance.near_miss()))
        .collect();
    let mut parent: Vec<usize> = (0..brep.vertices.len()).collect();
    for &k in &holes {
        let e = &brep.edges[k];
        let (a, b) = (
            root(&mut parent, e.start.index()),
            root(&mut parent, e.end.index()),
        );
        parent[a] = b;
    }
    let mut chains: Vec<(usize, Vec<usize>)> = Vec::new();
    for &k in &holes {
        let r = root(&mut parent, brep.edges[k].start.index());
        match chains.iter_mut().find(|(cr, _)| *cr == r) {
            Some((_, edges)) => edges.push(k),
            None => chains.push((r, vec![k])),
        }
    }
    chains
        .into_iter()
        .map(|(_, edges)| hole_warning(network, topology, &edges))
        .collect()
}

/// The warning for one chain of free edges.
fn hole_warning(network: &Network, topology: &Topology, edges: &[usize]) -> Warning {
    let brep = &topology.brep;
    let mids: Vec<DVec3> = edges
        .iter()
        .map(|&k| {
            let e = &brep.edges[k];
            network.curves()[e.curve].curve.point(0.5 * (e.t0 + e.t1))
        })
        .collect();
    let centroid = mids.iter().copied().sum::<DVec3>() / mids.len() as f64;
    let location = mids
        .iter()
        .copied()
        .min_by(|a, b| a.distance(centroid).total_cmp(&b.distance(centroid)))
        .unwrap_or(centroid);
    let mut curves: Vec<String> = edges
        .iter()
        .map(|&k| topology.curve_names[brep.edges[k].curve].clone())
        .collect();
    curves.sort();
    curves.dedup();
    Warning {
        kind: WarningKind::Hole,
        message: format!(
            "a hole in the surface: {} free edge(s) of curves '{}' near ({:.3}, {:.3}, {:.3}) have a patch on one side only; \
             the curves there do not close a region (check the near misses and dangling ends there, or give the \
             boundary curve its role: keel, stem, transom or deck)",
            edges.len(),
            curves.join("', '"),
            location.x,
            location.y,
            location.z
        ),
        curves,
        location: Some(location),
        error: None,
    }
}
