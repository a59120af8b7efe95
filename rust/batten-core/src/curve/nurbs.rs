//! The NURBS curve type: validated construction and evaluation with derivatives.

use glam::{DVec3, DVec4};

use super::basis::{basis_funs, basis_funs_d1, ders_basis_funs, find_span, MAX_DEGREE, MAX_ORDER};
use super::error::CurveError;

/// A point on a curve with its first three parametric derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveDerivs {
    /// C(t).
    pub point: DVec3,
    /// C'(t).
    pub d1: DVec3,
    /// C''(t).
    pub d2: DVec3,
    /// C'''(t).
    pub d3: DVec3,
}

/// The smallest weight a curve may have: 2^64 above the smallest normal f64. Knot insertion
/// blends neighbouring weights with coefficients that may be 1e-300; their products underflow,
/// and a weight at the normal limit (2.2e-308) came out below it (the Bézier decomposition
/// then failed inside `bounding_box`).
const MIN_WEIGHT: f64 = f64::MIN_POSITIVE * 18_446_744_073_709_551_616.0;

/// A non-uniform rational B-spline curve in 3D; a B-spline when every weight is 1.
///
/// Control points are stored homogeneous (`w·P, w`), so evaluation, knot insertion and
/// subdivision are linear operations. The parameter domain is `[knots[p], knots[n]]` for degree
/// `p` and `n` control points, so unclamped (uniform) knot vectors are represented exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    knots: Vec<f64>,
    cw: Vec<DVec4>,
    rational: bool,
}

impl NurbsCurve {
    /// Validated constructor: a curve of `degree` with `knots` (`points.len() + degree + 1` of
    /// them), `points`, and optional positive `weights` (`None` means all 1).
    ///
    /// Rejects degrees outside `1..=MAX_DEGREE`, fewer points than the order, non-finite
    /// coordinates, knots or weights, decreasing knots, an empty domain, knot spans too short
    /// for f64 to evaluate, and interior knots repeated more than `degree` times (the curve
    /// would fall apart).
    pub fn try_new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<DVec3>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, CurveError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(CurveError::Degree {
                degree,
                max: MAX_DEGREE,
            });
        }
        let n = points.len();
        if n < degree + 1 {
            return Err(CurveError::TooFewPoints {
                count: n,
                order: degree + 1,
            });
        }
        for (index, p) in points.iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|v| !v.is_finite()) {
                return Err(CurveError::NonFinitePoint { index, value });
            }
        }
        if let Some(w) = &weights {
            if w.len() != n {
                return Err(CurveError::WeightCount {
                    expected: n,
                    got: w.len(),
                });
            }
            if let Some((index, &value)) = w
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v > 0.0))
            {
                return Err(CurveError::BadWeight { index, value });
            }
        }
        validate_knots(&knots, degree, n)?;
        let rational = weights
            .as_ref()
            .is_some_and(|w| w.iter().any(|&v| v != 1.0));
        let cw: Vec<DVec4> = match &weights {
            Some(w) => points
                .iter()
                .zip(w)
                .map(|(p, &w)| (*p * w).extend(w))
                .collect(),
            None => points.iter().map(|p| p.extend(1.0)).collect(),
        };
        if let Some(index) = unrepresentable_point(&cw) {
            return Err(CurveError::WeightedPointOverflow { index });
        }
        if let Some((index, value)) = cw
            .iter()
            .map(|c| c.w)
            .enumerate()
            .find(|&(_, w)| w < MIN_WEIGHT)
        {
            return Err(CurveError::TinyWeight {
                index,
                value,
                min: MIN_WEIGHT,
            });
        }
        Ok(NurbsCurve {
            degree,
            knots,
            cw,
            rational,
        })
    }

    /// Constructor from homogeneous control points without validation, for results of
    /// operations that keep the invariants (knot insertion, splitting, reversal).
    ///
    /// Obligations: `knots.len() == cw.len() + degree + 1`, knots non-decreasing with a
    /// non-empty domain, every `w > 0` and finite, every coordinate finite.
    pub(crate) fn new_unchecked(degree: usize, knots: Vec<f64>, cw: Vec<DVec4>) -> Self {
        debug_assert_eq!(knots.len(), cw.len() + degree + 1, "knot count invariant");
        let rational = cw.iter().any(|c| c.w != 1.0);
        NurbsCurve {
            degree,
            knots,
            cw,
            rational,
        }
    }

    /// The polynomial degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The order p + 1.
    pub fn order(&self) -> usize {
        self.degree + 1
    }

    /// The knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of control points.
    pub fn control_point_count(&self) -> usize {
        self.cw.len()
    }

    /// Cartesian control points.
    pub fn control_points(&self) -> Vec<DVec3> {
        self.cw.iter().map(|c| c.truncate() / c.w).collect()
    }

    /// Weights, or `None` for a non-rational curve (all weights 1).
    pub fn weights(&self) -> Option<Vec<f64>> {
        self.rational.then(|| self.cw.iter().map(|c| c.w).collect())
    }

    /// The curve of this degree, knots and weights through other Cartesian control points
    /// (a curve moved, scaled or faired): [`NurbsCurve::try_new`]'s errors, e.g. for another
    /// number of points or a non-finite one.
    pub fn with_control_points(&self, points: Vec<DVec3>) -> Result<NurbsCurve, CurveError> {
        NurbsCurve::try_new(self.degree, self.knots.clone(), points, self.weights())
    }

    /// True when `other` is this curve, bit for bit, wherever either is evaluated on
    /// `[lo, hi]`: the same degree and knot vector, and the same homogeneous control points
    /// over the spans that reach the interval (one span more on each side, for evaluations at
    /// a knot that take the neighbouring span). A drag of one control point changes a curve on
    /// `degree + 1` spans only; the live rebuild keeps what lies outside them.
    pub fn same_on(&self, other: &NurbsCurve, lo: f64, hi: f64) -> bool {
        if self.degree != other.degree
            || self.cw.len() != other.cw.len()
            || self.knots.len() != other.knots.len()
            || self
                .knots
                .iter()
                .zip(&other.knots)
                .any(|(a, b)| a.to_bits() != b.to_bits())
        {
            return false;
        }
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        let n = self.cw.len();
        let p = self.degree;
        let first = find_span(&self.knots, p, n, lo).saturating_sub(p + 1);
        let last = (find_span(&self.knots, p, n, hi) + 1).min(n - 1);
        self.cw[first..=last]
            .iter()
            .zip(&other.cw[first..=last])
            .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits))
    }

    /// Homogeneous control points `(w·P, w)`.
    pub fn homogeneous_points(&self) -> &[DVec4] {
        &self.cw
    }

    /// True when some weight differs from 1.
    pub fn is_rational(&self) -> bool {
        self.rational
    }

    /// `t` clamped into the domain (a parameter outside it evaluates at the nearer end, never
    /// on the extrapolated polynomial).
    #[inline]
    pub(crate) fn clamp(&self, t: f64) -> f64 {
        let (a, b) = self.domain();
        t.clamp(a, b)
    }

    /// The parameter domain `[knots[p], knots[n]]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.cw.len()])
    }

    /// The point C(t); `t` is clamped into the domain.
    #[inline]
    pub fn point(&self, t: f64) -> DVec3 {
        let t = self.clamp(t);
        let p = self.degree;
        let span = find_span(&self.knots, p, self.cw.len(), t);
        let mut b = [0.0; MAX_ORDER];
        basis_funs(&self.knots, span, t, p, &mut b);
        let acc = self.cw[span - p..=span]
            .iter()
            .zip(&b)
            .fold(DVec4::ZERO, |acc, (c, bj)| acc + *c * *bj);
        acc.truncate() / acc.w
    }

    /// Evaluate at many parameters, writing `x, y, z` triples into `out` (`3 * ts.len()` long);
    /// each parameter is clamped into the domain.
    ///
    /// The inner loop allocates nothing; parameters may come in any order.
    pub fn points_into(&self, ts: &[f64], out: &mut [f64]) {
        assert_eq!(
            out.len(),
            3 * ts.len(),
            "output holds three values per parameter"
        );
        let p = self.degree;
        let n = self.cw.len();
        let mut b = [0.0; MAX_ORDER];
        for (t, o) in ts.iter().zip(out.chunks_exact_mut(3)) {
            let t = &self.clamp(*t);
            let span = find_span(&self.knots, p, n, *t);
            basis_funs(&self.knots, span, *t, p, &mut b);
            let cw = &self.cw[span - p..=span];
            let mut acc = DVec4::ZERO;
            for (c, bj) in cw.iter().zip(&b) {
                acc += *c * *bj;
            }
            let v = acc.truncate() / acc.w;
            o.copy_from_slice(&v.to_array());
        }
    }

    /// C(t) and its first three derivatives (A3.2 with A2.3; rational curves by A4.2, eq. 4.8);
    /// `t` is clamped into the domain.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let t = self.clamp(t);
        let span = find_span(&self.knots, self.degree, self.cw.len(), t);
        self.derivs_in_span(span, t)
    }

    /// C(t) and C′(t): the first two of [`NurbsCurve::derivs`], bit for bit (A2.3's first
    /// derivatives do not depend on the higher ones), without the work of the higher ones.
    pub(crate) fn point_d1(&self, t: f64) -> (DVec3, DVec3) {
        let t = self.clamp(t);
        let span = find_span(&self.knots, self.degree, self.cw.len(), t);
        let p = self.degree;
        let (mut n0, mut n1) = ([0.0; MAX_ORDER], [0.0; MAX_ORDER]);
        basis_funs_d1(&self.knots, span, t, p, &mut n0, &mut n1);
        // `homogeneous_derivs::<2>` bit for bit: the same sums in the same order.
        let mut h = [DVec4::ZERO; 2];
        for (hk, nk) in h.iter_mut().zip([&n0, &n1]) {
            for (c, nkj) in self.cw[span - p..=span].iter().zip(nk) {
                *hk += *c * *nkj;
            }
        }
        let c0 = h[0].truncate() / h[0].w;
        let c1 = (h[1].truncate() - h[1].w * c0) / h[0].w;
        (c0, c1)
    }

    /// The homogeneous point and its first `N − 1` derivatives (`N` ≤ 4) at `t` on knot span
    /// `span`: the basis functions' derivatives (A2.3) applied to the weighted control points.
    fn homogeneous_derivs<const N: usize>(&self, span: usize, t: f64) -> [DVec4; N] {
        let p = self.degree;
        let mut d = [[0.0; MAX_ORDER]; 4];
        ders_basis_funs(&self.knots, span, t, p, N - 1, &mut d);
        let mut h = [DVec4::ZERO; N];
        for (hk, dk) in h.iter_mut().zip(&d) {
            for (c, dkj) in self.cw[span - p..=span].iter().zip(dk) {
                *hk += *c * *dkj;
            }
        }
        h
    }

    /// Derivatives at `t` using the polynomial piece of knot span `span` (so that at a knot the
    /// one-sided derivative of either neighbouring piece can be asked for).
    pub(crate) fn derivs_in_span(&self, span: usize, t: f64) -> CurveDerivs {
        let h: [DVec4; 4] = self.homogeneous_derivs(span, t);
        let (a, w) = (h.map(|v| v.truncate()), h.map(|v| v.w));
        let c0 = a[0] / w[0];
        let c1 = (a[1] - w[1] * c0) / w[0];
        let c2 = (a[2] - 2.0 * w[1] * c1 - w[2] * c0) / w[0];
        let c3 = (a[3] - 3.0 * w[1] * c2 - 3.0 * w[2] * c1 - w[3] * c0) / w[0];
        CurveDerivs {
            point: c0,
            d1: c1,
            d2: c2,
            d3: c3,
        }
    }

    /// The curvature vector at `t`: pointing to the centre of curvature, length κ = 1/radius
    /// (`(C′ × C″) × C′ / |C′|⁴`); zero where the curve has no tangent.
    ///
    /// Computed as the part of C″ normal to the unit tangent, divided by the speed twice (the
    /// same vector): `|C′|⁴` under- or overflows for speeds beyond 1e±77 (a knot span of 1e83
    /// gave 0/0 = NaN).
    pub fn curvature_vector(&self, t: f64) -> DVec3 {
        let d = self.derivs(t);
        let speed = d.d1.length();
        if speed == 0.0 {
            return DVec3::ZERO;
        }
        let tangent = d.d1 / speed;
        (d.d2 - tangent * d.d2.dot(tangent)) / speed / speed
    }

    /// The curve traversed the other way: same shape, parameter `t` maps to `a + b - t` on the
    /// knot vector's full range `[a, b]`.
    pub fn reversed(&self) -> NurbsCurve {
        let (a, b) = (self.knots[0], self.knots[self.knots.len() - 1]);
        let knots = self.knots.iter().rev().map(|&u| a + b - u).collect();
        let cw = self.cw.iter().rev().copied().collect();
        NurbsCurve::new_unchecked(self.degree, knots, cw)
    }

    /// [`NurbsCurve::reversed`], checked: near the top of a large knot range, `a + b − u` can
    /// round distinct knots together so that the curve falls apart (knots ending at 1e17);
    /// such a reversal is refused with the knot error instead of evaluating to NaN.
    pub fn try_reversed(&self) -> Result<NurbsCurve, CurveError> {
        let r = self.reversed();
        validate_knots(&r.knots, r.degree, r.cw.len())?;
        Ok(r)
    }

    /// Multiplicity of the knot value `u` (exact comparison).
    pub(crate) fn multiplicity(&self, u: f64) -> usize {
        self.knots.iter().filter(|&&k| k == u).count()
    }
}

/// The first homogeneous control point `(w·P, w)` that f64 cannot carry: non-finite (w·P
/// overflowed) or with a weight below the smallest normal f64 (evaluation would divide by it).
pub(crate) fn unrepresentable_point(cw: &[DVec4]) -> Option<usize> {
    cw.iter()
        .position(|c| !(c.is_finite() && c.w >= f64::MIN_POSITIVE))
}

/// The first non-empty knot span (start index, width) too short for f64 to evaluate: its
/// reciprocal overflows (a span of a few subnormals; Cox–de Boor divides by it).
pub(crate) fn unresolvable_span(knots: &[f64]) -> Option<(usize, f64)> {
    knots
        .windows(2)
        .map(|w| w[1] - w[0])
        .enumerate()
        .find(|&(_, d)| d > 0.0 && !(1.0 / d).is_finite())
}

fn validate_knots(knots: &[f64], degree: usize, n: usize) -> Result<(), CurveError> {
    let expected = n + degree + 1;
    if knots.len() != expected {
        return Err(CurveError::KnotCount {
            expected,
            got: knots.len(),
        });
    }
    if let Some((index, &value)) = knots.iter().enumerate().find(|(_, k)| !k.is_finite()) {
        return Err(CurveError::NonFiniteKnot { index, value });
    }
    for i in 1..knots.len() {
        if knots[i] < knots[i - 1] {
            return Err(CurveError::DecreasingKnots {
                index: i,
                prev: knots[i - 1],
                next: knots[i],
            });
        }
    }
    let (start, end) = (knots[degree], knots[n]);
    if start >= end {
        return Err(CurveError::EmptyDomain { start, end });
    }
    if let Some((index, span)) = unresolvable_span(knots) {
        return Err(CurveError::ShortSpan { index, span });
    }
    let mut i = 0;
    while i < knots.len() {
        let value = knots[i];
        let mut j = i;
        while j < knots.len() && knots[j] == value {
            j += 1;
        }
        let multiplicity = j - i;
        let max = if value > start && value < end {
            degree
        } else {
            degree + 1
        };
        if multiplicity > max {
            return Err(CurveError::KnotMultiplicity {
                value,
                multiplicity,
                max,
            });
        }
        i = j;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::NurbsCurve;

    /// Another curve's control points keep this one's degree, knots and weights; another
    /// number of them is refused as `try_new` refuses it.
    #[test]
    fn other_control_points_keep_degree_knots_and_weights() {
        let knots = vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0];
        let points: Vec<DVec3> = (0..4).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
        let weights = Some(vec![1.0, 0.5, 2.0, 1.0]);
        let curve = NurbsCurve::try_new(2, knots.clone(), points.clone(), weights.clone()).unwrap();
        let lifted: Vec<DVec3> = points.iter().map(|p| *p + DVec3::Z).collect();
        let moved = curve.with_control_points(lifted.clone()).unwrap();
        assert_eq!(
            moved,
            NurbsCurve::try_new(2, knots.clone(), lifted, weights.clone()).unwrap()
        );
        assert_eq!(
            curve.with_control_points(points[..3].to_vec()).unwrap_err(),
            NurbsCurve::try_new(2, knots, points[..3].to_vec(), weights).unwrap_err()
        );
    }

    /// `point_d1` (the first derivatives alone) is `derivs`'s point and first derivative bit
    /// for bit, on a rational curve with uneven and repeated knots, at its knots and between.
    #[test]
    fn point_and_tangent_alone_are_those_of_all_the_derivatives_bit_for_bit() {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.37, 1.1, 1.1, 2.93, 3.3, 3.3, 3.3, 3.3];
        let points = (0..8)
            .map(|i| {
                let x = f64::from(i);
                DVec3::new(x * 1.7, (x * 0.9).sin() * 3.1, 0.3 * x * x)
            })
            .collect();
        let weights = vec![1.0, 0.7, 1.3, 0.95, 2.1, 1.0, 0.6, 1.0];
        let curve = NurbsCurve::try_new(3, knots.clone(), points, Some(weights)).unwrap();
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        let ts = (0..=2000).map(|i| 3.3 * f64::from(i) / 2000.0).chain(knots);
        for t in ts {
            let (p, d1) = curve.point_d1(t);
            let all = curve.derivs(t);
            assert_eq!(bits(p), bits(all.point), "point at t = {t}");
            assert_eq!(bits(d1), bits(all.d1), "first derivative at t = {t}");
        }
    }
}
