//! Compatible tangents at the smooth nodes of a network (H-rep paper §3.2.3; Ye & Nowacki
//! 1995, curve compatibility at the nodes): the surface through a node has one tangent plane
//! there, so the tangents of every curve through it must lie in one plane. Curves fitted one by
//! one to measured sections meet at a node, but their tangents there miss a common plane by
//! the data's noise over the span of a section. Where the surface is nearly tangent to the
//! curves' common direction (at a fine stem, where the hull meets the centreplane at a few
//! degrees) a slope error of a few thousandths turns the tangent plane by tenths of a degree,
//! and the patches on either side of a curve then meet at that angle (KCS's stem: 0.44°).
//!
//! At every smooth node this finds the plane that the curves' tangent lines are closest to (the
//! least squares plane through the origin of the unit tangents, both senses), and gives each
//! curve the derivative it has there turned into that plane: the target of a constrained move
//! ([`NurbsCurve::through_with_tangents`]) that keeps the curve through its nodes.

use glam::DVec3;

use crate::curve::NurbsCurve;
use crate::fair::best_fit_normal;
use crate::network::{NetworkCurve, Role};
use crate::patch::MIN_CROSSING_ANGLE_DEGREES;
use crate::topo::Topology;

/// A curve whose tangent direction turns by more than this (degrees) within the capture
/// distance of a node has a corner or a joint there that the constrained move keeps free: the
/// node is left as it is (a knuckle point; the build makes its edges knuckles above
/// [`KNUCKLE_POINT_ANGLE_DEGREES`](crate::KNUCKLE_POINT_ANGLE_DEGREES)).
const JOINT_DEGREES: f64 = 1.0;

/// The most (degrees) a curve's tangent is turned into its node's plane. More than this is not
/// the data's noise but a crease the data show, or curves that meet at a grazing angle: the node
/// is left as it is, and the build reports the normal jump there.
pub const MAX_TANGENT_TURN_DEGREES: f64 = 2.0;

/// Held tangents (unit) farther than this from their plane are not in one ([`held_plane`]).
const HELD_COPLANAR: f64 = 1e-9;

/// What the plane of one smooth node asks of the curves through it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SmoothNode {
    /// The node's position.
    pub(crate) position: DVec3,
    /// Unit normal of the node's tangent plane.
    pub(crate) normal: DVec3,
    /// Per curve through the node: its index, the parameter there, and the derivative it is to
    /// have (its own turned into the plane).
    pub(crate) tangents: Vec<(usize, f64, DVec3)>,
    /// The curves' own derivatives there, in the order of `tangents`.
    pub(crate) given: Vec<DVec3>,
    /// The largest turn (degrees) of a curve's tangent into the plane.
    pub(crate) turn_degrees: f64,
}

/// Whether `curve` turns its tangent by more than [`JOINT_DEGREES`] at a knot within `reach`
/// (m) of `at`: a corner, or a joint the constrained move leaves free.
fn joint_near(curve: &NurbsCurve, at: DVec3, reach: f64) -> bool {
    curve
        .corner_parameters(JOINT_DEGREES.to_radians())
        .into_iter()
        .any(|u| curve.point(u).distance(at) <= reach)
}

/// The smooth nodes of `topology` (found on `network`) with the derivatives the curves `moved`
/// (the network's curves moved through their nodes, in its order, each with the targets it
/// still passes through) are to have there. A node is
/// smooth when at least three curves meet there, each once and through a kept target, none a
/// knuckle (role), rational, or with a corner or joint within `reach` (m, the capture
/// distance) of it, two of them at least [`MIN_CROSSING_ANGLE_DEGREES`] apart, and no curve's
/// tangent more than [`MAX_TANGENT_TURN_DEGREES`] out of their plane.
pub(crate) fn smooth_nodes(
    network: &[NetworkCurve],
    topology: &Topology,
    moved: &[(&NurbsCurve, &[(f64, DVec3)])],
    reach: f64,
) -> Vec<SmoothNode> {
    let brep = &topology.brep;
    let mut at_vertex: Vec<Vec<(usize, f64)>> = vec![Vec::new(); brep.vertices.len()];
    for e in &brep.edges {
        for (v, t) in [(e.start, e.t0), (e.end, e.t1)] {
            let list = &mut at_vertex[v.index()];
            if !list.iter().any(|&(c, u)| c == e.curve && u == t) {
                list.push((e.curve, t));
            }
        }
    }
    let min_sin = MIN_CROSSING_ANGLE_DEGREES.to_radians().sin();
    let max_sin = MAX_TANGENT_TURN_DEGREES.to_radians().sin();
    let mut nodes = Vec::new();
    for (v, curves) in at_vertex.iter().enumerate() {
        let position = brep.vertices[v].position;
        let once = curves
            .iter()
            .enumerate()
            .all(|(i, &(c, _))| curves[..i].iter().all(|&(d, _)| d != c));
        if curves.len() < 3 || !once {
            continue;
        }
        let eligible = curves.iter().all(|&(c, t)| {
            let (curve, kept) = moved[c];
            network[c].role != Role::Knuckle
                && !curve.is_rational()
                && kept.iter().any(|&(u, _)| u == t)
                && !joint_near(curve, position, reach)
        });
        if !eligible {
            continue;
        }
        let derivs: Vec<DVec3> = curves
            .iter()
            .map(|&(c, t)| moved[c].0.derivs(t).d1)
            .collect();
        let units: Vec<DVec3> = derivs.iter().map(|d| d.normalize_or_zero()).collect();
        if units.contains(&DVec3::ZERO) {
            continue;
        }
        let spread = units.iter().enumerate().any(|(i, a)| {
            units[i + 1..]
                .iter()
                .any(|b| a.cross(*b).length() >= min_sin)
        });
        if !spread {
            continue;
        }
        let both: Vec<DVec3> = units.iter().flat_map(|&u| [u, -u]).collect();
        let normal = best_fit_normal(&both);
        let off = units
            .iter()
            .map(|u| u.dot(normal).abs())
            .fold(0.0, f64::max);
        if off > max_sin {
            continue;
        }
        let tangents = curves
            .iter()
            .zip(&derivs)
            .map(|(&(c, t), &d)| (c, t, d - normal * normal.dot(d)))
            .collect();
        nodes.push(SmoothNode {
            position,
            normal,
            tangents,
            given: derivs,
            turn_degrees: off.asin().to_degrees(),
        });
    }
    nodes
}

/// `node` with its plane made to hold, as they are, the tangents of the curves `held` (by
/// network index; curves whose own turn was refused: their data do not allow it): the plane
/// through them closest to the other curves' tangent lines, each other curve's target turned
/// into it. Otherwise the others would turn into a plane the held curve is not in, and the
/// node would still crease (KVLCC2's stem at the top of station 20, with the sections fitted
/// otherwise in an experiment: turning the profile 0.36° took one of its points 6.4 mm from
/// it, so the station and the waterline there turned into a plane the stem missed by that
/// much, and the patches creased 0.70° across the waterline). None where every curve is
/// held, three or more held tangents lie in no one plane ([`HELD_COPLANAR`]), or another
/// curve would turn more than [`MAX_TANGENT_TURN_DEGREES`].
pub(crate) fn held_plane(node: &SmoothNode, held: &[bool]) -> Option<SmoothNode> {
    let max_sin = MAX_TANGENT_TURN_DEGREES.to_radians().sin();
    let units: Vec<DVec3> = node.given.iter().map(|d| d.normalize()).collect();
    let is_held: Vec<bool> = node.tangents.iter().map(|&(c, _, _)| held[c]).collect();
    if is_held.iter().all(|&h| h) {
        return None;
    }
    let (mut fixed, mut free) = (Vec::new(), Vec::new());
    for (&u, &h) in units.iter().zip(&is_held) {
        if h {
            fixed.push(u);
        } else {
            free.push(u);
        }
    }
    let first = *fixed.first()?;
    // Two held tangents that are not parallel fix the plane; otherwise it turns about the one
    // held direction to the plane the others' lines are closest to.
    let spanning = fixed
        .iter()
        .map(|u| first.cross(*u))
        .max_by(|a, b| a.length().total_cmp(&b.length()))
        .filter(|c| c.length() >= MIN_CROSSING_ANGLE_DEGREES.to_radians().sin());
    let normal = match spanning {
        Some(c) => c.normalize(),
        None => {
            // The held direction weighs far more than any other: the least-variance direction
            // of the set is then exactly perpendicular to it.
            let mut lines: Vec<DVec3> = free
                .iter()
                .map(|&u| u - first * first.dot(u))
                .flat_map(|p| [p, -p])
                .collect();
            lines.extend([first * 10.0, -first * 10.0]);
            best_fit_normal(&lines)
        }
    };
    let off = |set: &[DVec3]| set.iter().map(|u| u.dot(normal).abs()).fold(0.0, f64::max);
    // Three held tangents out of one plane leave none to turn the others into.
    if off(&fixed) > HELD_COPLANAR {
        return None;
    }
    let turn = off(&free);
    if turn > max_sin {
        return None;
    }
    let tangents = node
        .tangents
        .iter()
        .zip(&node.given)
        .zip(&is_held)
        .map(|((&(c, t, _), &d), &h)| {
            let target = if h { d } else { d - normal * normal.dot(d) };
            (c, t, target)
        })
        .collect();
    Some(SmoothNode {
        position: node.position,
        normal,
        tangents,
        given: node.given.clone(),
        turn_degrees: turn.asin().to_degrees(),
    })
}
