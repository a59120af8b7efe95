//! Global closest-point projection: branch and bound over the Bézier decomposition, polished by
//! Newton's method. Robust on S-shaped curves, where Newton alone finds a wrong local minimum.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec3;

use super::bezier::BezierDecomposition;
use super::error::CurveError;
use super::nurbs::NurbsCurve;
use super::piece::BezierPiece;

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

/// A piece waiting in the branch-and-bound queue: its lower bound and its index in the
/// search's arena of pieces (the queue moves these small entries, not the pieces).
struct Candidate {
    lower: f64,
    piece: usize,
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
        // A piece flat to within the accuracy is a leaf: its chord bound is then within the
        // accuracy of its true distance, so the bound alone proves the answer and Newton only
        // polishes the parameter. (Handing larger pieces to an unguarded Newton failed on
        // curves with very unequal spans: 54 mm off on a 230 m waterline.)
        let leaf = 0.5 * accuracy;
        let mut best = self.endpoint_nearest(q);
        if !best.distance.is_finite() {
            return Err(CurveError::DistanceOverflow);
        }
        // True while `best` is the exact minimum of a convex piece (no polish needed).
        let mut polished = false;
        let mut arena: Vec<BezierPiece> = self.pieces.clone();
        let mut heap: BinaryHeap<Candidate> = arena
            .iter()
            .enumerate()
            .map(|(i, p)| Candidate {
                lower: p.lower_bound(q),
                piece: i,
            })
            .collect();
        while let Some(Candidate { lower, piece }) = heap.pop() {
            if lower >= best.distance - accuracy {
                break;
            }
            let piece = arena[piece];
            if piece.flatness() <= leaf
                || piece.t1 - piece.t0 <= f64::EPSILON * piece.t1.abs().max(1.0)
            {
                let start = self.golden(q, piece.t0, piece.t1);
                let refined = self.newton(q, start, piece.t0, piece.t1);
                if refined.distance < best.distance {
                    best = refined;
                    polished = false;
                }
                continue;
            }
            if piece.distance_convex(q) {
                // One minimum on the piece (the squared distance is convex in the
                // parameter): found to rounding on the piece itself, no subdivision needed.
                let (t, point) = piece.convex_foot(q);
                let distance = (point - q).length();
                if distance < best.distance {
                    best = Nearest { t, point, distance };
                    polished = true;
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
                polished = false;
            }
            for half in [l, r] {
                let lower = half.lower_bound(q);
                if lower < best.distance - accuracy {
                    heap.push(Candidate {
                        lower,
                        piece: arena.len(),
                    });
                    arena.push(half);
                }
            }
        }
        if polished {
            return Ok(best);
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

    /// Golden-section search for the smallest distance on `[lo, hi]`: robust on a leaf,
    /// which is flat to the accuracy, so the distance along it has one minimum whatever the
    /// (rational) parameterisation; ends are candidates too.
    fn golden(&self, q: DVec3, lo: f64, hi: f64) -> Nearest {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let (mut a, mut b) = (lo, hi);
        let mut c = b - INV_PHI * (b - a);
        let mut d = a + INV_PHI * (b - a);
        let (mut fc, mut fd) = (self.at(q, c), self.at(q, d));
        for _ in 0..80 {
            if b - a <= f64::EPSILON * (a.abs() + b.abs()).max(f64::MIN_POSITIVE) {
                break;
            }
            if fc.distance <= fd.distance {
                b = d;
                (d, fd) = (c, fc);
                c = b - INV_PHI * (b - a);
                fc = self.at(q, c);
            } else {
                a = c;
                (c, fc) = (d, fd);
                d = a + INV_PHI * (b - a);
                fd = self.at(q, d);
            }
        }
        [self.at(q, lo), self.at(q, hi), fc, fd]
            .into_iter()
            .min_by(|x, y| x.distance.total_cmp(&y.distance))
            .expect("four candidates")
    }

    /// Newton's method on `f(t) = C'(t)·(C(t) − q)` from `start`, kept inside `[lo, hi]`;
    /// returns the best point seen (never worse than `start`).
    fn newton(&self, q: DVec3, start: Nearest, lo: f64, hi: f64) -> Nearest {
        let mut best = start;
        let mut t = best.t;
        for _ in 0..30 {
            let d = self.curve.derivs(t);
            let diff = d.point - q;
            let f = d.d1.dot(diff);
            let df = d.d2.dot(diff) + d.d1.length_squared();
            let speed2 = d.d1.length_squared();
            if !(df.is_finite() && speed2 > 0.0) {
                break;
            }
            // Newton where the squared distance is convex, a gradient step elsewhere (rational
            // parameterisations bend f′ negative); backtracking halves a step that makes the
            // distance measurably worse.
            let mut step = if df > 0.0 { -f / df } else { -f / speed2 };
            let mut accepted = None;
            for _ in 0..8 {
                let next = (t + step).clamp(lo, hi);
                let cand = self.at(q, next);
                // Near the minimum the distance is flat to rounding: accept steps that do not
                // make it measurably worse, so the parameter converges too.
                let slack = 4.0 * f64::EPSILON * (1.0 + best.distance + cand.point.length());
                if cand.distance <= best.distance + slack {
                    accepted = Some(cand);
                    break;
                }
                step *= 0.5;
            }
            let Some(cand) = accepted else { break };
            let moved = (cand.t - t).abs();
            best = cand;
            t = cand.t;
            if moved <= f64::EPSILON * (hi - lo).max(1.0) * 4.0 {
                break;
            }
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
