//! Bézier decomposition of a NURBS curve (knot insertion, Piegl & Tiller A5.1): the pieces
//! that the global (branch-and-bound) closest-point search, the tight bounding box, the node
//! finding and the fast evaluators work on.

use glam::DVec3;

use super::bbox::Aabb;
use super::error::CurveError;
use super::nurbs::NurbsCurve;
use super::piece::{BezierPiece, PointDerivs};

/// A curve cut into rational Bézier pieces, one per non-empty knot span, kept with the curve
/// for Newton refinement. Build it once and query it many times.
#[derive(Clone, Debug)]
pub struct BezierDecomposition {
    pub(crate) curve: NurbsCurve,
    pub(crate) pieces: Vec<BezierPiece>,
    /// `pieces[k].t1` for every piece, packed: the piece lookup of every evaluation searches
    /// this instead of striding over the (large, fixed-size) pieces.
    ends: Vec<f64>,
}

impl BezierDecomposition {
    /// The index of the piece holding `t`; at a piece boundary, the piece after it when
    /// `after` is true (the one a curve leaves the knot on), else the piece before it.
    #[inline]
    pub(crate) fn piece_at(&self, t: f64, after: bool) -> usize {
        if after {
            self.ends.partition_point(|&t1| t1 <= t)
        } else {
            self.ends.partition_point(|&t1| t1 < t)
        }
        .min(self.pieces.len() - 1)
    }

    /// Point, first and second derivative at `t` (clamped into the domain) by de Casteljau on
    /// the piece holding it; at a knot, of the piece before it.
    #[inline]
    pub(crate) fn derivs(&self, t: f64) -> PointDerivs {
        self.derivs_in(self.piece_at(t, false), t)
    }

    /// Point, first and second derivative at `t` on piece `k` (`t` clamped into it): at a
    /// knot, the one-sided derivatives of the piece chosen by [`BezierDecomposition::piece_at`].
    #[inline]
    pub(crate) fn derivs_in(&self, k: usize, t: f64) -> PointDerivs {
        self.pieces[k].derivs_at(t)
    }

    /// C(t) as [`BezierDecomposition::derivs`] gives it.
    #[inline]
    pub(crate) fn point(&self, t: f64) -> DVec3 {
        self.pieces[self.piece_at(t, false)].point_at(t)
    }

    /// C(t) and C′(t) on piece `k` as [`BezierDecomposition::derivs_in`] gives them, bit for
    /// bit, without C″.
    #[inline]
    pub(crate) fn point_tangent_in(&self, k: usize, t: f64) -> (DVec3, DVec3) {
        self.pieces[k].point_tangent_at(t)
    }

    /// C(t) and C′(t) on piece `k` (`t` clamped into it) by [`BezierPiece::point_d1_at`], as
    /// [`BezierDecomposition::point_d1`] gives them on that piece.
    #[inline]
    pub(crate) fn point_d1_in(&self, k: usize, t: f64) -> (DVec3, DVec3) {
        self.pieces[k].point_d1_at(t)
    }

    /// C(t) and C′(t) (t clamped into the domain; at a knot, of the piece after it) by
    /// [`BezierPiece::point_d1_at`], the evaluator of the surface patches' sides.
    #[inline]
    pub(crate) fn point_d1(&self, t: f64) -> (DVec3, DVec3) {
        self.point_d1_in(self.piece_at(t, true), t)
    }

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
            .map(|k| BezierPiece::new(knots[k], knots[k + 1], &cw[k - p..=k]))
            .collect();
        BezierDecomposition::from_pieces(curve.clone(), pieces)
    }

    /// A decomposition of `curve` from its pieces (in parameter order).
    fn from_pieces(curve: NurbsCurve, pieces: Vec<BezierPiece>) -> BezierDecomposition {
        let ends = pieces.iter().map(|p| p.t1).collect();
        BezierDecomposition {
            curve,
            pieces,
            ends,
        }
    }

    /// The same curve restricted to the pieces of `self` that `keep` selects (by index), for a
    /// search that may skip pieces it has ruled out; `into` is reused to avoid allocation.
    pub(crate) fn select_into(
        &self,
        into: &mut BezierDecomposition,
        mut keep: impl FnMut(usize) -> bool,
    ) {
        into.pieces.clear();
        into.ends.clear();
        for (k, piece) in self.pieces.iter().enumerate() {
            if keep(k) {
                into.pieces.push(*piece);
                into.ends.push(piece.t1);
            }
        }
    }

    /// An empty decomposition of the same curve, to be filled by
    /// [`BezierDecomposition::select_into`].
    pub(crate) fn empty_like(&self) -> BezierDecomposition {
        BezierDecomposition::from_pieces(self.curve.clone(), Vec::new())
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

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::curve::NurbsCurve;

    #[test]
    fn piece_evaluation_matches_the_kernel_derivatives() {
        // A rational quadratic quarter circle joined to a cubic-like tail: rational, several
        // pieces, unequal knot spans.
        let pts = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.2),
            DVec3::new(0.0, 1.0, 0.4),
            DVec3::new(-1.0, 2.0, 0.1),
            DVec3::new(-2.0, 0.5, 0.0),
        ];
        let w = vec![1.0, 0.7, 1.0, 1.3, 1.0];
        let knots = vec![0.0, 0.0, 0.0, 0.3, 0.5, 1.5, 1.5, 1.5];
        let c = NurbsCurve::try_new(2, knots, pts.to_vec(), Some(w)).expect("valid");
        let dec = c.bezier_decomposition();
        for i in 0..=40 {
            let t = 1.5 * (i as f64 + 0.5) / 41.0;
            let d = c.derivs(t);
            let e = dec.derivs(t);
            assert!((e.point - d.point).length() < 1e-12, "point at {t}");
            assert!(
                (e.d1 - d.d1).length() < 1e-9 * (1.0 + d.d1.length()),
                "C' at {t}"
            );
            assert!(
                (e.d2 - d.d2).length() < 1e-8 * (1.0 + d.d2.length()),
                "C'' at {t}"
            );
            let (p, d1) = dec.point_d1(t);
            assert!((p - d.point).length() < 1e-12, "fast point at {t}");
            assert!(
                (d1 - d.d1).length() < 1e-9 * (1.0 + d.d1.length()),
                "fast C' at {t}"
            );
        }
    }
}
