//! Curves through their nodes: the nodes of a network are found at a capture distance (the
//! topology's clustering, H-rep §3.1, at the data's tolerance rather than the model's), and
//! each curve is changed as little as possible to pass exactly through the node positions
//! ([`NurbsCurve::through`](crate::NurbsCurve::through)), so the network builds at the model
//! tolerance with no near misses where the data meet.

use glam::DVec3;

use crate::error::Error;
use crate::network::{Network, NetworkCurve};
use crate::tolerance::Tolerance;
use crate::topo::Topology;

/// What snapping did to one curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSnap {
    /// The curve's name.
    pub curve: String,
    /// Nodes the curve now passes through.
    pub nodes: usize,
    /// The largest distance (m) between the curve and a node it was moved through, before the
    /// move.
    pub max_move: f64,
}

/// A network whose curves pass through their nodes, and what it took.
#[derive(Clone, Debug, PartialEq)]
pub struct SnappedNetwork {
    /// The network, curve for curve in the input's order (names and roles kept).
    pub network: Network,
    /// One entry per curve, in the same order.
    pub snaps: Vec<CurveSnap>,
}

/// Move every curve of `network` through the nodes the topology finds at the `capture`
/// distance (ends and crossings closer than it are one node, at the cluster's position).
///
/// Errors: the topology's own errors, and a curve that cannot be moved through its nodes
/// (named, with the curve kernel's reason).
pub fn snap_to_nodes(network: &Network, capture: Tolerance) -> Result<SnappedNetwork, Error> {
    let topology = Topology::build(network, capture)?;
    let brep = &topology.brep;
    let mut targets: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); network.curves().len()];
    for e in &brep.edges {
        for (t, v) in [(e.t0, e.start), (e.t1, e.end)] {
            targets[e.curve].push((t, brep.vertices[v.index()].position));
        }
    }
    let mut curves = Vec::with_capacity(network.curves().len());
    let mut snaps = Vec::with_capacity(network.curves().len());
    for (c, mut at) in network.curves().iter().zip(targets) {
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        at.dedup_by(|a, b| a.0 == b.0);
        let max_move = at
            .iter()
            .map(|&(t, q)| c.curve.point(t).distance(q))
            .fold(0.0, f64::max);
        let curve = c.curve.through(&at).map_err(|e| e.named(&c.name))?;
        snaps.push(CurveSnap {
            curve: c.name.clone(),
            nodes: at.len(),
            max_move,
        });
        curves.push(NetworkCurve {
            name: c.name.clone(),
            role: c.role,
            curve,
        });
    }
    Ok(SnappedNetwork {
        network: Network::try_new(network.name.clone(), curves)?,
        snaps,
    })
}
