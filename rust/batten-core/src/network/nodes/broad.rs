//! Broad phase of the node search: sort-and-sweep over the boxes of all Bézier pieces.

use super::Prepared;
use crate::adjacency::Adjacency;
use crate::curve::Aabb;

/// Two pieces whose grown boxes overlap: piece `piece_a` of curve `curve_a` and piece
/// `piece_b` of curve `curve_b` (`(curve_a, piece_a) < (curve_b, piece_b)`). Ordered by curves,
/// then pieces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct CandidatePair {
    pub(super) curve_a: usize,
    pub(super) curve_b: usize,
    pub(super) piece_a: usize,
    pub(super) piece_b: usize,
}

/// One piece in the sweep: its curve, its index on the curve and its grown box.
#[derive(Clone, Copy)]
struct Item {
    curve: usize,
    piece: usize,
    bbox: Aabb,
}

/// Candidate pairs of pieces, sorted (by curves, then pieces): pieces of
/// the curves not `excluded` whose boxes, grown by `margin` on every side,
/// overlap (sort-and-sweep along the axis of largest spread); the same piece and neighbouring
/// pieces of one curve are left out (they share an end point).
pub(super) fn candidate_pairs(
    prepared: &[Prepared],
    excluded: &[bool],
    margin: f64,
) -> Vec<CandidatePair> {
    let mut items: Vec<Item> = Vec::new();
    for (ci, p) in prepared.iter().enumerate() {
        if excluded[ci] {
            continue;
        }
        for (si, s) in p.decomposition.pieces.iter().enumerate() {
            items.push(Item {
                curve: ci,
                piece: si,
                bbox: s.hull_box().expanded(margin),
            });
        }
    }
    let axis = sweep_axis(&items);
    items.sort_by(|a, b| a.bbox.min[axis].total_cmp(&b.bbox.min[axis]));
    let mut pairs: Vec<CandidatePair> = Vec::new();
    for i in 0..items.len() {
        let a = items[i];
        for b in &items[i + 1..] {
            if b.bbox.min[axis] > a.bbox.max[axis] {
                break;
            }
            if !a.bbox.intersects(&b.bbox) {
                continue;
            }
            let (x, y) = if (a.curve, a.piece) < (b.curve, b.piece) {
                (a, *b)
            } else {
                (*b, a)
            };
            if x.curve == y.curve && y.piece <= x.piece + 1 {
                continue; // the same piece or neighbours: they share an end point
            }
            pairs.push(CandidatePair {
                curve_a: x.curve,
                curve_b: y.curve,
                piece_a: x.piece,
                piece_b: y.piece,
            });
        }
    }
    sorted_by_curves(pairs, prepared.len())
}

/// `pairs` sorted as the derived `Ord` sorts them: counted out by their first curve (one row
/// per curve of the network, `curves` of them), then each curve's few pairs sorted on their
/// own — half the time of one comparison sort of them all.
fn sorted_by_curves(pairs: Vec<CandidatePair>, curves: usize) -> Vec<CandidatePair> {
    let mut by_curve = Adjacency::from_pairs(curves, pairs.iter().map(|p| (p.curve_a, *p)));
    for row in by_curve.rows_mut() {
        row.sort_unstable();
    }
    by_curve.into_items()
}

/// The axis (0, 1, 2) along which the boxes spread most.
fn sweep_axis(items: &[Item]) -> usize {
    let all = items.iter().map(|i| i.bbox).reduce(Aabb::union);
    match all {
        Some(b) => {
            let d = b.max - b.min;
            if d.x >= d.y && d.x >= d.z {
                0
            } else if d.y >= d.z {
                1
            } else {
                2
            }
        }
        None => 0,
    }
}
