//! Bézier decomposition of a NURBS curve and rational de Casteljau subdivision: the basis of
//! the global (branch-and-bound) closest-point search and the tight bounding box.

use glam::{DVec3, DVec4};

use super::bbox::Aabb;
use super::nurbs::NurbsCurve;
use crate::error::CurveError;

/// One rational Bézier piece: `degree + 1` homogeneous control points on `[t0, t1]` of the
/// original curve's parameter.
#[derive(Clone, Debug)]
pub(crate) struct BezierPiece {
    pub t0: f64,
    pub t1: f64,
    pub cw: Vec<DVec4>,
}

impl BezierPiece {
    /// Box of the projected control points. Weights are positive, so the piece lies inside
    /// the convex hull of these points and hence inside this box.
    pub fn hull_box(&self) -> Aabb {
        Aabb::from_points(self.cw.iter().map(|c| c.truncate() / c.w)).expect("a piece has points")
    }

    /// A lower bound of the distance from `q` to the piece: the larger of the distance to its
    /// control-point box and the distance to its chord (end to end) less its flatness (the
    /// largest distance of a control point from the chord; the piece lies in the convex hull
    /// of its control points, so within that distance of the chord). The chord bound is exact
    /// to O(width²), which keeps branch and bound from splitting a flat minimum into
    /// thousands of pieces.
    pub fn lower_bound(&self, q: DVec3) -> f64 {
        let (a, b) = self.ends();
        let chord = segment_distance(q, a, b) - self.flatness();
        chord.max(self.hull_box().distance_to(q))
    }

    /// Largest distance of a control point from the chord: how far the piece can stray from
    /// the straight line between its ends.
    pub fn flatness(&self) -> f64 {
        let (a, b) = self.ends();
        self.cw
            .iter()
            .map(|c| segment_distance(c.truncate() / c.w, a, b))
            .fold(0.0, f64::max)
    }

    /// End points, which lie on the curve.
    pub fn ends(&self) -> (DVec3, DVec3) {
        let (a, b) = (self.cw[0], self.cw[self.cw.len() - 1]);
        (a.truncate() / a.w, b.truncate() / b.w)
    }

    /// De Casteljau subdivision at the parametric middle, in homogeneous coordinates.
    pub fn halves(&self) -> (BezierPiece, BezierPiece) {
        let n = self.cw.len();
        let mut work = self.cw.clone();
        let mut left = Vec::with_capacity(n);
        let mut right = vec![DVec4::ZERO; n];
        left.push(work[0]);
        right[n - 1] = work[n - 1];
        for level in 1..n {
            for i in 0..n - level {
                work[i] = (work[i] + work[i + 1]) * 0.5;
            }
            left.push(work[0]);
            right[n - 1 - level] = work[n - 1 - level];
        }
        let tm = 0.5 * (self.t0 + self.t1);
        (
            BezierPiece {
                t0: self.t0,
                t1: tm,
                cw: left,
            },
            BezierPiece {
                t0: tm,
                t1: self.t1,
                cw: right,
            },
        )
    }
}

/// A curve cut into rational Bézier pieces, one per non-empty knot span, kept with the curve
/// for Newton refinement. Build it once and query it many times.
#[derive(Clone, Debug)]
pub struct BezierDecomposition {
    pub(crate) curve: NurbsCurve,
    pub(crate) pieces: Vec<BezierPiece>,
}

impl BezierDecomposition {
    /// Decompose by inserting every knot of the domain to multiplicity `degree` (A5.1 repeated):
    /// each non-empty span's `degree + 1` control points are then its Bézier points.
    pub fn new(curve: &NurbsCurve) -> BezierDecomposition {
        let p = curve.degree();
        let (start, end) = curve.domain();
        let mut values: Vec<f64> = curve
            .knots()
            .iter()
            .copied()
            .filter(|&u| u >= start && u <= end)
            .collect();
        values.dedup();
        let mut full = curve.clone();
        for &u in &values {
            let s = full.multiplicity(u);
            if s < p {
                full = full
                    .insert_knot(u, p - s)
                    .expect("insertion to multiplicity p within the domain is valid");
            }
        }
        let knots = full.knots();
        let cw = full.homogeneous_points();
        let n = cw.len();
        let pieces = (p..n)
            .filter(|&k| knots[k] < knots[k + 1])
            .map(|k| BezierPiece {
                t0: knots[k],
                t1: knots[k + 1],
                cw: cw[k - p..=k].to_vec(),
            })
            .collect();
        BezierDecomposition {
            curve: curve.clone(),
            pieces,
        }
    }

    /// Number of Bézier pieces.
    pub fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    /// Box of all control points: holds the curve, cheap, not tight.
    pub fn hull_box(&self) -> Aabb {
        self.pieces
            .iter()
            .map(BezierPiece::hull_box)
            .reduce(Aabb::union)
            .expect("a curve has at least one piece")
    }

    /// A box that holds the curve and is at most `accuracy` larger than the tightest one on
    /// each side: pieces whose hull box already lies inside the box of known curve points
    /// are done; the others are halved until their hull box is smaller than `accuracy`.
    pub fn bounding_box(&self, accuracy: f64) -> Result<Aabb, CurveError> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(CurveError::Accuracy(accuracy));
        }
        let mut known = Aabb::from_point(self.pieces[0].ends().0);
        for piece in &self.pieces {
            let (a, b) = piece.ends();
            known = known.including(a).including(b);
        }
        let mut stack: Vec<BezierPiece> = self.pieces.clone();
        while let Some(piece) = stack.pop() {
            let hull = piece.hull_box();
            if known.contains_box(&hull) {
                continue;
            }
            if hull.diagonal() <= accuracy {
                known = known.union(hull);
                continue;
            }
            let (l, r) = piece.halves();
            known = known.including(l.ends().1);
            stack.push(l);
            stack.push(r);
        }
        Ok(known)
    }
}

/// Distance from `p` to the segment `[a, b]`.
pub(crate) fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * s - p).length()
}

impl NurbsCurve {
    /// The Bézier decomposition of this curve (see [`BezierDecomposition`]).
    pub fn bezier_decomposition(&self) -> BezierDecomposition {
        BezierDecomposition::new(self)
    }

    /// A box holding the curve, at most `accuracy` larger than the tightest one on each side.
    pub fn bounding_box(&self, accuracy: f64) -> Result<Aabb, CurveError> {
        self.bezier_decomposition().bounding_box(accuracy)
    }
}
