//! Global closest-point projection: branch and bound over the Bézier decomposition, polished by
//! Newton's method. Robust on S-shaped curves, where Newton alone finds a wrong local minimum.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec3;

use super::bezier::{BezierDecomposition, BezierPiece};
use super::nurbs::NurbsCurve;
use crate::error::CurveError;

/// The closest point of a curve to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Curve parameter of the closest point.
    pub t: f64,
    /// The closest point C(t).
    pub point: DVec3,
    /// Distance from the query point to C(t).
    pub distance: f64,
}

struct Candidate {
    lower: f64,
    piece: BezierPiece,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.lower == other.lower
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Candidate {
    // Smallest lower bound first in a max-heap.
    fn cmp(&self, other: &Self) -> Ordering {
        other.lower.total_cmp(&self.lower)
    }
}

impl BezierDecomposition {
    /// The closest point of the curve to `q`, within `accuracy` of the true minimum distance.
    ///
    /// Branch and bound: every piece's distance is bounded below by the distance to its
    /// control-point box (convex hull property, positive weights) and above by its end points.
    /// Pieces are halved (de Casteljau) best-first until no piece can beat the best point found
    /// by more than `accuracy`; small pieces are finished by Newton's method on
    /// `f(t) = C'(t)·(C(t) − q)`, kept inside the piece.
    pub fn nearest(&self, q: DVec3, accuracy: f64) -> Result<Nearest, CurveError> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(CurveError::Accuracy(accuracy));
        }
        if !q.is_finite() {
            return Err(CurveError::NonFiniteQuery);
        }
        let size = self.hull_box().diagonal();
        // Pieces smaller than this go to Newton; it converges fast on a piece this small.
        let leaf = (size * 1e-3).max(accuracy);
        let mut best = self.endpoint_nearest(q);
        let mut heap: BinaryHeap<Candidate> = self
            .pieces
            .iter()
            .map(|p| Candidate {
                lower: p.hull_box().distance_to(q),
                piece: p.clone(),
            })
            .collect();
        while let Some(Candidate { lower, piece }) = heap.pop() {
            if lower >= best.distance - accuracy {
                break;
            }
            let hull = piece.hull_box();
            if hull.diagonal() <= leaf {
                let start = [piece.t0, 0.5 * (piece.t0 + piece.t1), piece.t1]
                    .map(|t| self.at(q, t))
                    .into_iter()
                    .min_by(|a, b| a.distance.total_cmp(&b.distance))
                    .expect("three samples");
                let polished = self.newton(q, start, piece.t0, piece.t1);
                if polished.distance < best.distance {
                    best = polished;
                }
                continue;
            }
            let (l, r) = piece.halves();
            let mid = l.ends().1;
            let d = (mid - q).length();
            if d < best.distance {
                best = Nearest {
                    t: l.t1,
                    point: mid,
                    distance: d,
                };
            }
            for half in [l, r] {
                let lower = half.hull_box().distance_to(q);
                if lower < best.distance - accuracy {
                    heap.push(Candidate { lower, piece: half });
                }
            }
        }
        // The bound proves `best` is within `accuracy` in distance; polish its parameter too
        // (the distance is flat at a minimum, so a good distance can hide a poor parameter).
        let piece = self
            .pieces
            .iter()
            .find(|p| best.t >= p.t0 && best.t <= p.t1)
            .expect("best lies on a piece");
        Ok(self.newton(q, best, piece.t0, piece.t1))
    }

    fn at(&self, q: DVec3, t: f64) -> Nearest {
        let point = self.curve.point(t);
        Nearest {
            t,
            point,
            distance: (point - q).length(),
        }
    }

    fn endpoint_nearest(&self, q: DVec3) -> Nearest {
        let mut best: Option<Nearest> = None;
        for piece in &self.pieces {
            let (a, b) = piece.ends();
            for (t, p) in [(piece.t0, a), (piece.t1, b)] {
                let distance = (p - q).length();
                if best.is_none_or(|bst| distance < bst.distance) {
                    best = Some(Nearest {
                        t,
                        point: p,
                        distance,
                    });
                }
            }
        }
        best.expect("a curve has at least one piece")
    }

    /// Newton's method on `f(t) = C'(t)·(C(t) − q)` from `start`, kept inside `[lo, hi]`;
    /// returns the best point seen (never worse than `start`).
    fn newton(&self, q: DVec3, start: Nearest, lo: f64, hi: f64) -> Nearest {
        let mut best = start;
        let mut t = best.t;
        for _ in 0..20 {
            let d = self.curve.derivs(t);
            let diff = d.point - q;
            let f = d.d1.dot(diff);
            let df = d.d2.dot(diff) + d.d1.length_squared();
            if df <= 0.0 || !df.is_finite() {
                break;
            }
            let next = (t - f / df).clamp(lo, hi);
            let cand = self.at(q, next);
            // Near the minimum the distance is flat to rounding: accept steps that do not
            // make it measurably worse, so the parameter converges too.
            let slack = 4.0 * f64::EPSILON * (1.0 + best.distance + cand.point.length());
            if cand.distance <= best.distance + slack {
                best = cand;
            } else {
                break;
            }
            if (next - t).abs() <= f64::EPSILON * (hi - lo).max(1.0) * 4.0 {
                break;
            }
            t = next;
        }
        best
    }
}

impl NurbsCurve {
    /// The closest point of the curve to `q` within `accuracy` (global; see
    /// [`BezierDecomposition::nearest`]). For many queries on one curve, decompose once.
    pub fn nearest(&self, q: DVec3, accuracy: f64) -> Result<Nearest, CurveError> {
        self.bezier_decomposition().nearest(q, accuracy)
    }
}
