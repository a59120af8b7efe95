//! Where the sections meet, and how each meeting point may move so that the network stays
//! exact: a node moved on a station moves on its waterline too, so it may only move along the
//! line both planes share (y for a station and a waterline, z for a station and a buttock), and
//! not at all where three families, a fixed curve, a curve's end or a fixed position meet.

use glam::DVec3;

use crate::curve::{CurveError, NurbsCurve};
use crate::network::Junctions;

/// A knot closer to a node than this share of the distance to the next node gives the node
/// the freedom it needs; nearer still, a knot of its own would make a sliver of a span that
/// single-precision control points (Blender's) bend.
const NEAR_KNOT: f64 = 0.25;

/// How a node may move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Freedom {
    /// Not at all.
    Fixed,
    /// Along the coordinate axes marked true (those in every plane of the curves through it).
    Along([bool; 3]),
}

/// The nodes of the network as the fairing sees them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Nodes {
    /// Per node: how it may move.
    pub freedom: Vec<Freedom>,
    /// Per node: the curves through it and their parameters.
    pub incidences: Vec<Vec<(usize, f64)>>,
    /// Per node: where it is (as found; the fairing moves it, but not by more than a
    /// tolerance, which tells nodes apart well enough).
    pub positions: Vec<DVec3>,
    /// Per curve: its nodes as `(parameter, node)`, in order.
    pub on_curve: Vec<Vec<(f64, usize)>>,
}

/// The nodes of `junctions` with their freedom: `axes` holds, per curve, the axis normal to its
/// plane for a movable section and `None` for a fixed curve. A node is fixed where a fixed curve
/// passes, where a curve ends (the ends of sections stay: keel, stem, deck and the DWL's ends),
/// within `near` (m) of one of `fixed_points`, or where the planes of its curves leave no
/// common direction.
pub(crate) fn nodes(
    junctions: &Junctions,
    curves: &[NurbsCurve],
    axes: &[Option<usize>],
    fixed_points: &[DVec3],
    near: f64,
) -> Nodes {
    let count = junctions.nodes.len();
    let mut incidences: Vec<Vec<(usize, f64)>> = vec![Vec::new(); count];
    let mut on_curve: Vec<Vec<(f64, usize)>> = vec![Vec::new(); curves.len()];
    for (c, splits) in junctions.splits.iter().enumerate() {
        if junctions.excluded.get(c).copied().unwrap_or(true) {
            continue;
        }
        for &(t, node) in splits {
            incidences[node].push((c, t));
            on_curve[c].push((t, node));
        }
    }
    let freedom = (0..count)
        .map(|node| {
            let position = junctions.nodes[node].position;
            let pinned = fixed_points.iter().any(|p| p.distance(position) <= near);
            let mut along = [true; 3];
            for &(c, t) in &incidences[node] {
                let (start, end) = curves[c].domain();
                match axes[c] {
                    Some(a) if t > start && t < end => along[a] = false,
                    _ => return Freedom::Fixed,
                }
            }
            if pinned || along == [false; 3] || incidences[node].len() < 2 {
                Freedom::Fixed
            } else {
                Freedom::Along(along)
            }
        })
        .collect();
    Nodes {
        freedom,
        positions: junctions.nodes.iter().map(|n| n.position).collect(),
        incidences,
        on_curve,
    }
}

/// `curve` with a knot at each interior parameter of `at` (sorted) that has no knot within
/// [`NEAR_KNOT`] of its distance to the neighbouring parameters (Boehm insertion: the shape
/// and the parameters stay), so that each node has a control point of its own to move.
pub(crate) fn refined(curve: &NurbsCurve, at: &[f64]) -> Result<NurbsCurve, CurveError> {
    let (start, end) = curve.domain();
    let mut refined = curve.clone();
    for (i, &t) in at.iter().enumerate() {
        if t <= start || t >= end {
            continue;
        }
        let before = if i > 0 { at[i - 1] } else { start };
        let after = at.get(i + 1).copied().unwrap_or(end);
        let near = NEAR_KNOT * (t - before).min(after - t);
        if refined.knots().iter().all(|&u| (u - t).abs() > near) {
            refined = refined.insert_knot(t, 1)?;
        }
    }
    Ok(refined)
}
