//! Curves through their nodes: the nodes of a network are found at a capture distance (the
//! topology's clustering, H-rep §3.1, at the data's tolerance rather than the model's), and
//! each curve is changed as little as possible to pass exactly through the node positions
//! ([`NurbsCurve::through`](crate::NurbsCurve::through)), so the network builds at the model
//! tolerance with no near misses where the data meet.
//!
//! Given the points each curve was fitted to, a curve moves only through the nodes its data
//! allow: while some point is farther than the tolerance from the moved curve, the node
//! nearest that point (along the curve) is left out, and the curve is moved again. A curve
//! that duplicates another follows it.

use glam::DVec3;
use rayon::prelude::*;

use crate::curve::{CurveError, NurbsCurve};
use crate::diagnostic::Diagnostic;
use crate::error::Error;
use crate::network::{Network, NetworkCurve};
use crate::tolerance::Tolerance;
use crate::topo::Topology;

use super::tangents::{held_plane, smooth_nodes};

/// What snapping did to one curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSnap {
    /// The curve's name.
    pub curve: String,
    /// Nodes the curve now passes through.
    pub nodes: usize,
    /// Nodes left out because moving through them took a data point past the tolerance.
    pub skipped: usize,
    /// The largest distance (m) between the curve and a node it was moved through, before the
    /// move.
    pub max_move: f64,
    /// With data: the largest distance (m) of a data point from the moved curve, and the
    /// point's index; `None` without data.
    pub max_deviation: Option<(f64, usize)>,
    /// Smooth nodes at which the curve's tangent was turned into the node's tangent plane.
    pub tangent_nodes: usize,
    /// The largest of those turns (degrees), 0 at none.
    pub max_tangent_turn: f64,
}

/// One smooth node whose curves' tangents were turned into one plane.
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothNodeReport {
    /// Where the node is.
    pub position: DVec3,
    /// Unit normal of its tangent plane.
    pub normal: DVec3,
    /// The names of the curves through it.
    pub curves: Vec<String>,
    /// The largest turn (degrees) of a curve's tangent into the plane.
    pub turn_degrees: f64,
}

/// A network whose curves pass through their nodes, and what it took.
#[derive(Clone, Debug, PartialEq)]
pub struct SnappedNetwork {
    /// The network, curve for curve in the input's order (names and roles kept).
    pub network: Network,
    /// One entry per curve, in the same order.
    pub snaps: Vec<CurveSnap>,
    /// The smooth nodes whose tangents were made coplanar, with the change at each (module
    /// doc).
    pub smooth_nodes: Vec<SmoothNodeReport>,
}

/// The points each curve was fitted to and how close the moved curve must stay to them.
#[derive(Clone, Copy, Debug)]
pub struct SnapData<'a> {
    /// Per curve of the network, in its order: the points it was fitted to.
    pub points: &'a [Vec<DVec3>],
    /// Largest distance (m) a point may have from its moved curve.
    pub tolerance: f64,
}

/// Move every curve of `network` through the nodes the topology finds at the `capture`
/// distance (ends and crossings closer than it are one node, at the cluster's position). With
/// `data`, a curve leaves out the nodes that would take one of its points farther than the
/// tolerance (module doc). Then, at every smooth node (the `tangents` module), the curves'
/// tangents are turned into one plane, in the same least move from the curve as given (a
/// curve whose data that would take past the tolerance keeps its move through the nodes
/// alone; a curve in the centreplane y = 0, a profile, turns only within it, and the others
/// into a plane through its tangent).
///
/// Errors: the topology's own errors, data for a different number of curves or with a
/// non-finite point ([`Error::InvalidInput`]), a data tolerance that is not positive and finite
/// ([`Error::Tolerance`]), and a curve that cannot be moved
/// through its nodes (named, with the curve kernel's reason).
pub fn snap_to_nodes(
    network: &Network,
    capture: Tolerance,
    data: Option<SnapData<'_>>,
) -> Result<SnappedNetwork, Error> {
    if let Some(d) = data {
        check_data(network, d)?;
    }
    let topology = Topology::build(network, capture)?;
    let brep = &topology.brep;
    // The curves in the centreplane (profiles), whose tangents turn only within it (below).
    let centre: Vec<bool> = network
        .curves()
        .iter()
        .map(|c| in_centreplane(&c.curve, CENTREPLANE_SHARE * capture.get()))
        .collect();
    let mut targets: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); network.curves().len()];
    for e in &brep.edges {
        for (t, v) in [(e.t0, e.start), (e.t1, e.end)] {
            targets[e.curve].push((t, brep.vertices[v.index()].position));
        }
    }
    let points_of = |i: usize| data.map(|d| (d.points[i].as_slice(), d.tolerance));
    let moved: Vec<Snapped> = network
        .curves()
        .par_iter()
        .zip(targets)
        .enumerate()
        .map(|(i, (c, mut at))| {
            at.sort_by(|a, b| a.0.total_cmp(&b.0));
            at.dedup_by(|a, b| a.0 == b.0);
            let (curve, snap, kept) =
                snap_curve(&c.curve, at, points_of(i)).map_err(|e| e.named(&c.name))?;
            let snap = CurveSnap {
                curve: c.name.clone(),
                ..snap
            };
            Ok((curve, snap, kept))
        })
        .collect::<Result<_, Error>>()?;
    let views: Vec<(&NurbsCurve, &[(f64, DVec3)])> =
        moved.iter().map(|(c, _, k)| (c, k.as_slice())).collect();
    let found = smooth_nodes(network.curves(), &topology, &views, capture.get());
    // The turn is an improvement, not a condition of meeting: where the move cannot be made,
    // or takes a data point past the tolerance, the curve keeps its move through the nodes
    // alone, and its tangents are held as they are at its nodes (`held_plane`): the other
    // curves there turn again, into a plane through them.
    let turn = |i: usize, at: &[(f64, DVec3)]| -> Option<Turned> {
        let turned = network.curves()[i]
            .curve
            .through_with_tangents(&moved[i].2, at)
            .ok()?;
        let worst = match points_of(i) {
            Some((points, tol)) => {
                let (d, k, _) = worst_point(&turned, points, tol).ok()?;
                (d <= tol).then_some(Some((d, k)))?
            }
            None => None,
        };
        Some((turned, worst))
    };
    let n = moved.len();
    // A curve in the centreplane (a profile) keeps its tangents in it: turned out of it like
    // the others, it left the plane between its nodes (by 0.63 mm at KCS's stem, where
    // st20 and wl_z10.80 meet it), and the hull's two halves no longer met on it. At a node
    // its tangent goes to its turn into the node's plane taken back into the centreplane,
    // and the other curves turn into a plane through that.
    let mut held = vec![false; n];
    let planes_through_held = |held: &[bool]| -> Vec<_> {
        let fixed: Vec<bool> = held.iter().zip(&centre).map(|(h, c)| *h || *c).collect();
        found
            .iter()
            .filter_map(|node| {
                if !node.tangents.iter().any(|&(c, _, _)| fixed[c]) {
                    return Some(node.clone());
                }
                let mut pinned = node.clone();
                for (k, &(c, _, target)) in node.tangents.iter().enumerate() {
                    let within = DVec3::new(target.x, 0.0, target.z);
                    // (A target across the plane has no direction in it: the tangent is kept.)
                    if centre[c] && !held[c] && within.length() > 0.5 * target.length() {
                        pinned.given[k] = within;
                    }
                }
                held_plane(&pinned, &fixed)
            })
            .collect()
    };
    let mut nodes = planes_through_held(&held);
    let mut targets: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); n];
    let mut results: Vec<Option<Turned>> = vec![None; n];
    for round in 0..HELD_ROUNDS {
        let mut wanted: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); n];
        for node in &nodes {
            for &(c, t, d) in &node.tangents {
                if !held[c] {
                    wanted[c].push((t, d));
                }
            }
        }
        let again: Vec<usize> = (0..n).filter(|&i| wanted[i] != targets[i]).collect();
        let fresh: Vec<Option<Turned>> = again
            .par_iter()
            .map(|&i| {
                (!wanted[i].is_empty())
                    .then(|| turn(i, &wanted[i]))
                    .flatten()
            })
            .collect();
        for (&i, r) in again.iter().zip(fresh) {
            results[i] = r;
        }
        targets = wanted;
        let refused: Vec<usize> = (0..n)
            .filter(|&i| !targets[i].is_empty() && results[i].is_none())
            .collect();
        // The last round's turns are those of `nodes`: a curve refused then keeps its move
        // through the nodes alone, and its nodes are not reported.
        if refused.is_empty() || round + 1 == HELD_ROUNDS {
            break;
        }
        for &i in &refused {
            held[i] = true;
        }
        nodes = planes_through_held(&held);
    }
    // A node is made coplanar where every curve through it was turned into its plane or is
    // held in it.
    let coplanar: Vec<bool> = nodes
        .iter()
        .map(|node| {
            node.tangents
                .iter()
                .all(|&(c, _, _)| held[c] || results[c].is_some())
        })
        .collect();
    let turned: Vec<(NetworkCurve, CurveSnap)> = network
        .curves()
        .iter()
        .zip(moved)
        .zip(results)
        .enumerate()
        .map(|(i, ((c, (curve, snap, _)), result))| {
            let (curve, snap) = match result {
                Some((turned, worst)) => {
                    let most = nodes
                        .iter()
                        .filter(|node| node.tangents.iter().any(|&(d, _, _)| d == i))
                        .map(|node| node.turn_degrees)
                        .fold(0.0, f64::max);
                    let snap = CurveSnap {
                        max_deviation: worst,
                        tangent_nodes: targets[i].len(),
                        max_tangent_turn: most,
                        ..snap
                    };
                    (turned, snap)
                }
                None => (curve, snap),
            };
            let curve = NetworkCurve {
                name: c.name.clone(),
                role: c.role,
                curve,
            };
            (curve, snap)
        })
        .collect();
    let (mut curves, snaps): (Vec<NetworkCurve>, Vec<_>) = turned.into_iter().unzip();
    let smooth_nodes = nodes
        .iter()
        .zip(&coplanar)
        .filter(|(_, &made)| made)
        .map(|(n, _)| SmoothNodeReport {
            position: n.position,
            normal: n.normal,
            curves: n
                .tangents
                .iter()
                .map(|&(c, _, _)| network.curves()[c].name.clone())
                .collect(),
            turn_degrees: n.turn_degrees,
        })
        .collect();
    follow_duplicates(&topology, network, &mut curves)?;
    Ok(SnappedNetwork {
        network: Network::try_new(network.name.clone(), curves)?,
        snaps,
        smooth_nodes,
    })
}

/// A curve the topology left out as a duplicate of another (it has no nodes of its own) takes
/// the moved geometry of the curve it duplicates, run its own way, so the two stay duplicates
/// (and are named so by the build) instead of drifting apart into near misses.
fn follow_duplicates(
    topology: &Topology,
    network: &Network,
    curves: &mut [NetworkCurve],
) -> Result<(), Error> {
    let index = |name: &str| network.curves().iter().position(|c| c.name == name);
    for d in &topology.diagnostics {
        let Diagnostic::DuplicateCurve {
            curves: [kept, out],
            ..
        } = d
        else {
            continue;
        };
        let (Some(k), Some(o)) = (index(kept), index(out)) else {
            continue;
        };
        let original = &network.curves()[o].curve;
        let moved = &curves[k].curve;
        let (a, _) = original.domain();
        let (ka, kb) = moved.domain();
        let start = original.point(a);
        let same_way = moved.point(ka).distance(start) <= moved.point(kb).distance(start);
        let geometry = if same_way {
            moved.clone()
        } else {
            moved.try_reversed().map_err(|e| e.named(out))?
        };
        curves[o].curve = geometry;
    }
    Ok(())
}

/// Data for every curve, finite, with a positive finite tolerance.
fn check_data(network: &Network, d: SnapData<'_>) -> Result<(), Error> {
    if d.points.len() != network.curves().len() {
        return Err(Error::InvalidInput(format!(
            "snapping: data for {} curves, the network has {}",
            d.points.len(),
            network.curves().len()
        )));
    }
    Tolerance::try_new(d.tolerance)?;
    for (c, pts) in network.curves().iter().zip(d.points) {
        if let Some(i) = pts.iter().position(|p| !p.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "snapping: data point {i} of curve '{}' is not finite",
                c.name
            )));
        }
    }
    Ok(())
}

/// A curve moved through its nodes, what that took, and the targets (node parameters and
/// positions) it passes through.
type Snapped = (NurbsCurve, CurveSnap, Vec<(f64, DVec3)>);

/// A curve turned into its nodes' planes, and its worst data point (distance, index) if it
/// has data.
type Turned = (NurbsCurve, Option<(f64, usize)>);

/// A curve whose control points all lie within this share of the capture distance of the
/// centreplane y = 0 lies in it ([`in_centreplane`]).
const CENTREPLANE_SHARE: f64 = 0.05;

/// Whether every control point of `curve` lies within `within` of the centreplane y = 0 (and
/// the curve is not a point).
fn in_centreplane(curve: &NurbsCurve, within: f64) -> bool {
    let pts = curve.control_points();
    pts.iter().all(|p| p.y.abs() <= within) && pts.iter().any(|p| p.distance(pts[0]) > within)
}

/// Rounds of turning at most: the first turns every curve into its nodes' planes; each
/// further one holds the curves whose turn was refused and turns the others at their nodes
/// again ([`held_plane`]).
const HELD_ROUNDS: usize = 3;

/// Accuracy (fraction of the tolerance) of the closest points that measure the data's
/// distance from a moved curve.
const DEVIATION_ACCURACY: f64 = 1e-3;

/// Move `curve` through `targets` (sorted by parameter); with `data`, leave out one target at a
/// time, the nearest along the curve to the worst point, until every point is within the
/// tolerance (or no target is left).
fn snap_curve(
    curve: &NurbsCurve,
    mut targets: Vec<(f64, DVec3)>,
    data: Option<(&[DVec3], f64)>,
) -> Result<Snapped, CurveError> {
    let move_of = |at: &[(f64, DVec3)]| {
        at.iter()
            .map(|&(t, q)| curve.point(t).distance(q))
            .fold(0.0, f64::max)
    };
    let all = targets.len();
    loop {
        let moved = curve.through(&targets)?;
        let worst = match data {
            Some((points, tol)) => Some(worst_point(&moved, points, tol)?),
            None => None,
        };
        let snap = |moved: NurbsCurve, targets: &[(f64, DVec3)]| {
            let snap = CurveSnap {
                curve: String::new(),
                nodes: targets.len(),
                skipped: all - targets.len(),
                max_move: move_of(targets),
                max_deviation: worst.map(|(d, i, _)| (d, i)),
                tangent_nodes: 0,
                max_tangent_turn: 0.0,
            };
            (moved, snap)
        };
        match (worst, data) {
            (Some((d, _, t)), Some((_, tol))) if d > tol && !targets.is_empty() => {
                let k = (0..targets.len())
                    .min_by(|&a, &b| {
                        (targets[a].0 - t)
                            .abs()
                            .total_cmp(&(targets[b].0 - t).abs())
                    })
                    .unwrap_or(0);
                targets.remove(k);
            }
            _ => {
                let (moved, snap) = snap(moved, &targets);
                return Ok((moved, snap, targets));
            }
        }
    }
}

/// The point of `points` farthest from `curve`: its distance, index and the parameter of its
/// closest point.
fn worst_point(
    curve: &NurbsCurve,
    points: &[DVec3],
    tol: f64,
) -> Result<(f64, usize, f64), CurveError> {
    let mut worst = (0.0, 0, curve.domain().0);
    let pieces = curve.bezier_decomposition();
    for (i, p) in points.iter().enumerate() {
        let n = pieces.nearest(*p, DEVIATION_ACCURACY * tol)?;
        if n.distance > worst.0 {
            worst = (n.distance, i, n.t);
        }
    }
    Ok(worst)
}
