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

use glam::DVec3;

use super::rotation::RawNormal;
use crate::adjacency::Adjacency;

/// Steps per parallel task at least when the steps are worked out.
const PAR_MIN_STEPS: usize = 1024;

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
/// end, where it travels along `arriving` (both unit vectors, or zero where missing): rotated
/// by the least rotation between the two, written out by Rodrigues' formula for the rotation
/// taking unit `a` to unit `b` (axis `k = a × b`, cosine `c = a · b`):
/// `v c + k × v + k (k · v) / (1 + c)`. Unrotated where a direction is missing or the edge
/// turns back on itself (`1 + c` near 0, where the axis is undetermined).
fn transport(normal: DVec3, leaving: DVec3, arriving: DVec3) -> DVec3 {
    if leaving == DVec3::ZERO || arriving == DVec3::ZERO {
        return normal;
    }
    let (k, c) = (leaving.cross(arriving), leaving.dot(arriving));
    if c < 0.0 && k.length_squared() < REVERSAL_SINE * REVERSAL_SINE {
        return normal;
    }
    normal * c + k.cross(normal) + k * (k.dot(normal) / (1.0 + c))
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
/// depend on the heap's internals), and what it is reached with (packed as [`KEEP`] says).
type Candidate = (u64, Reverse<u32>, u32);

/// What a node is reached with, packed into a heap [`Candidate`]: between two nodes with raw
/// normals only whether the far one is to be flipped ([`KEEP`], [`FLIP`]); where either has
/// none, the carried normal itself, by its index in a side list (`CARRIED + index`).
const KEEP: u32 = 0;
/// See [`KEEP`].
const FLIP: u32 = 1;
/// See [`KEEP`].
const CARRIED: u32 = 2;

/// Orient the raw normals consistently over each connected part of the graph `steps` (per
/// node, its edges, each made into a [`Step`] by `step`; `targets` holds, in the same shape,
/// the node each step reaches, `step(x).to`, which the caller has at hand): each part starts
/// at its most confident normal, taken as it is, and grows by the candidate edge whose far
/// node's raw normal agrees best with the normal carried to it ([`transport`]); that node's
/// normal is flipped when it points against the carried one. Nodes without a raw normal (all
/// tangents parallel) take the carried normal. Returns one unit normal per node (zero for
/// nodes without edges).
pub(crate) fn orient_normals<T: Copy + Sync>(
    raw: &[Option<RawNormal>],
    steps: &Adjacency<T>,
    targets: &Adjacency<usize>,
    step: impl Fn(T) -> Step + Sync,
) -> Vec<DVec3> {
    let n = raw.len();
    // Between two nodes with raw normals: the raw normal carried along the step, against the
    // far node's raw normal (worked out once). A node's oriented normal is its raw normal or
    // its opposite, and carrying is linear (exactly so in floating point: negation only flips
    // signs), so what it carries is that or its opposite: the agreement is this figure's size
    // and the far node is flipped when its sign differs from the near node's flip. NaN where
    // either node has no raw normal (carried as the search reaches it).
    let signed: Adjacency<f64> = steps.par_map_rows(PAR_MIN_STEPS, |u, x| {
        let s = step(x);
        match (raw[u], raw[s.to]) {
            (Some(a), Some(b)) => b.normal.dot(transport(a.normal, s.leaving, s.arriving)),
            _ => f64::NAN,
        }
    });
    if let Some(out) = consistent_orientation(raw, targets, &signed) {
        return out;
    }
    let mut out = vec![DVec3::ZERO; n];
    let mut seen = vec![false; n];
    // Parts start at their most confident node: the nodes in order of confidence, highest
    // first, lower index among equals.
    let mut order: Vec<(u64, u32)> = (0..n)
        .filter(|&v| !steps.row(v).is_empty())
        .map(|v| {
            let c = raw[v].map_or(0.0, |r| r.confidence);
            (c.to_bits(), v as u32)
        })
        .collect();
    order.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
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
        for (&x, &sign) in steps.row(u).iter().zip(signed.row(u)) {
            let s = step(x);
            if seen[s.to] {
                continue;
            }
            let (agreement, reached) = if sign.is_nan() {
                let (c, agreement) = carry(normal, &s, raw);
                carried.push(c);
                (agreement, CARRIED + (carried.len() - 1) as u32)
            } else {
                let flip = (sign < 0.0) != flipped;
                (sign.abs(), if flip { FLIP } else { KEEP })
            };
            heap.push((agreement.to_bits(), Reverse(s.to as u32), reached));
        }
    };
    for (_, start) in order {
        let start = start as usize;
        if seen[start] {
            continue;
        }
        seen[start] = true;
        out[start] = raw[start].map_or(DVec3::Z, |r| r.normal);
        push_steps(start, out[start], false, &seen, &mut heap, &mut carried);
        while let Some((_, Reverse(v), reached)) = heap.pop() {
            let v = v as usize;
            if seen[v] {
                continue;
            }
            seen[v] = true;
            let (normal, flipped) = match (raw[v], reached) {
                (Some(r), FLIP) => (-r.normal, true),
                (Some(r), KEEP) => (r.normal, false),
                (Some(r), k) if r.normal.dot(carried[(k - CARRIED) as usize]) < 0.0 => {
                    (-r.normal, true)
                }
                (Some(r), _) => (r.normal, false),
                (None, k) => (carried[(k - CARRIED) as usize].normalize_or_zero(), false),
            };
            out[v] = normal;
            push_steps(v, normal, flipped, &seen, &mut heap, &mut carried);
        }
        carried.clear();
    }
    out
}

/// The orientation of [`orient_normals`] where no edge disagrees: every node has a raw normal
/// and, over each connected part, the signs of all the steps' agreements fit one choice of
/// flips. Then every spanning tree gives the same flips, the maximum one of Prim's algorithm
/// among them, so a breadth-first search from each part's most confident node (the one Prim
/// starts from) gives its result exactly, without sorting the nodes or keeping a heap. None
/// where some node has no raw normal, an agreement is zero or not a number, or two steps
/// disagree (the maximum spanning tree then decides which one wins).
fn consistent_orientation(
    raw: &[Option<RawNormal>],
    targets: &Adjacency<usize>,
    signed: &Adjacency<f64>,
) -> Option<Vec<DVec3>> {
    let n = raw.len();
    let mut flip = vec![false; n];
    let mut part = vec![usize::MAX; n];
    let mut oriented = vec![false; n];
    let mut queue: Vec<usize> = Vec::new();
    let mut members: Vec<usize> = Vec::new();
    for seed in 0..n {
        if part[seed] != usize::MAX || targets.row(seed).is_empty() {
            continue;
        }
        // The part of `seed`, then its most confident node (lowest index among equals).
        members.clear();
        part[seed] = seed;
        queue.clear();
        queue.push(seed);
        while let Some(u) = queue.pop() {
            members.push(u);
            for &v in targets.row(u) {
                if part[v] == usize::MAX {
                    part[v] = seed;
                    queue.push(v);
                }
            }
        }
        let mut start = members[0];
        let mut best = raw[start]?.confidence;
        for &v in &members[1..] {
            let c = raw[v]?.confidence;
            if c > best || (c == best && v < start) {
                (start, best) = (v, c);
            }
        }
        // Flips by breadth-first search from the start; every step is checked on the way (a
        // node's flip is final once it is queued, and the search walks every member's steps).
        queue.clear();
        queue.push(start);
        oriented[start] = true;
        let mut k = 0;
        while k < queue.len() {
            let u = queue[k];
            k += 1;
            for (&v, &sign) in targets.row(u).iter().zip(signed.row(u)) {
                if sign.is_nan() || sign == 0.0 {
                    return None;
                }
                let flip_v = (sign < 0.0) != flip[u];
                if !oriented[v] {
                    oriented[v] = true;
                    flip[v] = flip_v;
                    queue.push(v);
                } else if flip[v] != flip_v {
                    return None;
                }
            }
        }
    }
    Some(
        (0..n)
            .map(|v| match raw[v] {
                Some(r) if part[v] != usize::MAX => {
                    if flip[v] {
                        -r.normal
                    } else {
                        r.normal
                    }
                }
                _ => DVec3::ZERO,
            })
            .collect(),
    )
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
    fn a_cycle_whose_signs_disagree_is_decided_by_the_most_reliable_edges() {
        // Three nodes in a cycle, edges straight (nothing carried: the agreements are the raw
        // normals' dot products): a·b > 0 and b·c > 0 but c·a < 0, so no choice of flips fits
        // all three edges. The weakest edge (c–a, |c·a| 0.2) gives way: c is reached from b
        // and kept as it is. A search that took the edges in any order would flip c from a.
        let (a, b, c) = (
            DVec3::Z,
            DVec3::new(1.0, 0.0, 1.0).normalize(),
            DVec3::new(1.0, 0.0, -0.2).normalize(),
        );
        let straight = |to: usize| Step {
            to,
            leaving: DVec3::X,
            arriving: DVec3::X,
        };
        let steps = Adjacency::from_pairs(
            3,
            [
                (0, straight(2)),
                (0, straight(1)),
                (1, straight(0)),
                (1, straight(2)),
                (2, straight(1)),
                (2, straight(0)),
            ]
            .into_iter(),
        );
        let mut normals = vec![raw(a), raw(b), raw(c)];
        normals[1].as_mut().expect("a normal").confidence = 0.5;
        normals[2].as_mut().expect("a normal").confidence = 0.25;
        let near = |out: &[DVec3]| {
            out.iter()
                .zip([a, b, c])
                .all(|(got, want)| (*got - want).length() < 1e-12)
        };
        let out = orient_normals(&normals, &steps, &steps.map(|s| s.to), |s| s);
        assert!(near(&out), "{out:?}");
        // With b's normal turned round, the cycle still disagrees: b is flipped back.
        normals[1].as_mut().expect("a normal").normal *= -1.0;
        let out = orient_normals(&normals, &steps, &steps.map(|s| s.to), |s| s);
        assert!(near(&out), "{out:?}");
        // Where the signs agree (c's plane tilted the other way) every path gives the same.
        let c2 = DVec3::new(1.0, 0.0, 0.2).normalize();
        normals[2].as_mut().expect("a normal").normal = -c2;
        let out = orient_normals(&normals, &steps, &steps.map(|s| s.to), |s| s);
        assert!((out[2] - c2).length() < 1e-12, "{out:?}");
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
        let out = orient_normals(&normals, &steps, &steps.map(|s| s.to), |s| s);
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
