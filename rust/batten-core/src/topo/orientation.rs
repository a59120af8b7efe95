//! Consistent orientation of the nodes' surface normals over each connected part of the
//! network (part of the rotation system, [`super::linking`]).
//!
//! Each node's raw normal ([`RawNormal`]) has either sign. Two neighbouring nodes agree when
//! the normal at one, carried along the curve of their edge, points the same way as the
//! normal at the other. Carrying it (a parallel transport along the edge, approximated by the
//! least rotation that takes the edge's direction of travel at its start to its direction of
//! travel at its end) keeps that test sound where the surface bends sharply along the curve:
//! over a shaft boss, a skeg's edge or a bulb, neighbouring normals turn by 90° or more, and
//! the sign of their plain dot product is chance. The signs are then decided along a maximum
//! spanning tree of the agreement |transported · normal| (Prim's algorithm), so each node is
//! reached over the most reliable edge available: Hoppe et al. 1992, "Surface reconstruction
//! from unorganized points", §3.3 (there with the plain dot product, on a Riemannian graph of
//! sample points).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::{DQuat, DVec3};

use super::adjacency::Adjacency;
use super::rotation::RawNormal;

/// An edge of the network seen from one end: the node at its other end, the unit direction in
/// which the edge leaves this node and the unit direction of travel in which it arrives at the
/// other (the opposite of its leaving direction there).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step {
    /// The node at the other end.
    pub to: usize,
    /// Unit direction in which the edge leaves this node.
    pub leaving: DVec3,
    /// Unit direction of travel in which the edge arrives at `to`.
    pub arriving: DVec3,
}

/// Below this sine of the angle between an edge's directions of travel at its two ends, with
/// the edge turning back on itself, the axis of the rotation between them is undetermined
/// (about 0.06° from a full reversal): the normal is then compared untransported.
const REVERSAL_SINE: f64 = 1e-3;

/// `normal` carried along an edge from its start, where it travels along `leaving`, to its
/// end, where it travels along `arriving`: rotated by the least rotation between the two.
/// Unrotated where a direction is missing (zero) or the edge turns back on itself.
fn transport(normal: DVec3, leaving: DVec3, arriving: DVec3) -> DVec3 {
    let (Some(a), Some(b)) = (leaving.try_normalize(), arriving.try_normalize()) else {
        return normal;
    };
    if a.dot(b) < 0.0 && a.cross(b).length() < REVERSAL_SINE {
        return normal;
    }
    DQuat::from_rotation_arc(a, b) * normal
}

/// `normal` carried along step `s` ([`transport`]), and how far it agrees with the raw normal
/// of the node it reaches: |carried · raw|, 1 for a node without a raw normal.
fn carry(normal: DVec3, s: &Step, raw: &[Option<RawNormal>]) -> (DVec3, f64) {
    let c = transport(normal, s.leaving, s.arriving);
    (c, raw[s.to].map_or(1.0, |r| r.normal.dot(c).abs()))
}

/// A node to reach next, as kept in the heap: how far the normal carried to it can be trusted
/// to decide its sign (|carried · raw|, in [0, 1]; 1 for a node without a raw normal, which
/// takes the carried normal and decides nothing) as the bits of that non-negative float (which
/// order as the numbers do), the node (among equals the lower first, so the result does not
/// depend on the heap's internals), and the index of the carried normal in a side list.
type Candidate = (u64, Reverse<usize>, usize);

/// Orient the raw normals consistently over each connected part of the graph `steps` (per
/// node, its edges): each part starts at its most confident normal, taken as it is, and grows
/// by the candidate edge whose far node's raw normal agrees best with the normal carried to it
/// ([`transport`]); that node's normal is flipped when it points against the carried one.
/// Nodes without a raw normal (all tangents parallel) take the carried normal. Returns one
/// unit normal per node (zero for nodes without edges).
pub(crate) fn orient_normals(raw: &[Option<RawNormal>], steps: &Adjacency<Step>) -> Vec<DVec3> {
    let n = raw.len();
    // The raw normal of every step's node carried along it, and how far it agrees with the
    // far node's raw normal: worked out once, in parallel. A node's oriented normal is its raw
    // normal or its opposite, and carrying is linear (exactly so in floating point: negation
    // only flips signs), so what it carries is this or its opposite, and the agreement
    // |carried · raw| is this one's.
    let carried_raw: Adjacency<Option<(DVec3, f64)>> =
        steps.par_map_rows(|u, s| raw[u].map(|r| carry(r.normal, &s, raw)));
    let mut out = vec![DVec3::ZERO; n];
    let mut seen = vec![false; n];
    let mut order: Vec<usize> = (0..n).filter(|&v| !steps.row(v).is_empty()).collect();
    order.sort_by(|&a, &b| {
        let ca = raw[a].map_or(0.0, |r| r.confidence);
        let cb = raw[b].map_or(0.0, |r| r.confidence);
        cb.total_cmp(&ca).then(a.cmp(&b))
    });
    let mut heap: BinaryHeap<Candidate> = BinaryHeap::new();
    let mut carried: Vec<DVec3> = Vec::new();
    // `normal` is `u`'s oriented normal: its raw normal (`flipped` false), the opposite
    // (true), or a carried one where `u` has no raw normal.
    let push_steps = |u: usize,
                      normal: DVec3,
                      flipped: bool,
                      seen: &[bool],
                      heap: &mut BinaryHeap<Candidate>,
                      carried: &mut Vec<DVec3>| {
        for (s, fixed) in steps.row(u).iter().zip(carried_raw.row(u)) {
            if seen[s.to] {
                continue;
            }
            let (c, agreement) = match *fixed {
                Some((c, agreement)) => (if flipped { -c } else { c }, agreement),
                None => carry(normal, s, raw),
            };
            heap.push((agreement.to_bits(), Reverse(s.to), carried.len()));
            carried.push(c);
        }
    };
    for start in order {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        out[start] = raw[start].map_or(DVec3::Z, |r| r.normal);
        push_steps(start, out[start], false, &seen, &mut heap, &mut carried);
        while let Some((_, Reverse(v), k)) = heap.pop() {
            if seen[v] {
                continue;
            }
            seen[v] = true;
            let c = carried[k];
            let (normal, flipped) = match raw[v] {
                Some(RawNormal { normal, .. }) if normal.dot(c) < 0.0 => (-normal, true),
                Some(RawNormal { normal, .. }) => (normal, false),
                None => (c.normalize_or_zero(), false),
            };
            out[v] = normal;
            push_steps(v, normal, flipped, &seen, &mut heap, &mut carried);
        }
        carried.clear();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw(normal: DVec3) -> Option<RawNormal> {
        Some(RawNormal {
            normal: normal.normalize(),
            confidence: 1.0,
        })
    }

    #[test]
    fn a_normal_carried_round_a_right_angle_bend_turns_with_it() {
        // An edge leaving along +x that arrives travelling along -z (bending down round a
        // corner of a box): +z, the normal on top, arrives as +x, the normal on the end.
        let carried = transport(DVec3::Z, DVec3::X, DVec3::NEG_Z);
        assert!((carried - DVec3::X).length() < 1e-12, "got {carried}");
    }

    #[test]
    fn a_sharp_bend_is_oriented_by_the_carried_normal_not_the_plain_one() {
        // Node 0 on top of a rounded edge, normal +z; node 1 down the side, 100° further round:
        // its outward normal has a negative dot product with +z, so the plain test flips it
        // inward. Carried along the curve, +z arrives close to the outward normal.
        let angle = 100f64.to_radians();
        let outward = DVec3::new(angle.sin(), 0.0, angle.cos());
        let arriving = DVec3::new(angle.cos(), 0.0, -angle.sin());
        let steps = Adjacency::from_pairs(
            2,
            [
                (
                    0,
                    Step {
                        to: 1,
                        leaving: DVec3::X,
                        arriving,
                    },
                ),
                (
                    1,
                    Step {
                        to: 0,
                        leaving: -arriving,
                        arriving: DVec3::NEG_X,
                    },
                ),
            ]
            .into_iter(),
        );
        let mut normals = vec![raw(DVec3::Z), raw(-outward)];
        normals[1].as_mut().expect("a normal").confidence = 0.5;
        let out = orient_normals(&normals, &steps);
        assert!(
            (out[0] - DVec3::Z).length() < 1e-12,
            "start kept: {}",
            out[0]
        );
        assert!(
            (out[1] - outward).length() < 1e-12,
            "outward, got {}",
            out[1]
        );
    }
}
