//! Knot insertion (Boehm's algorithm, Piegl & Tiller A5.1) and splitting a curve in two.

use glam::DVec4;

use super::error::CurveError;
use super::nurbs::{unrepresentable_point, unresolvable_span, NurbsCurve};

impl NurbsCurve {
    /// Insert the knot `t` `times` times without changing the curve's shape (A5.1, applied to
    /// the homogeneous control points so rational curves stay exact).
    ///
    /// `t` must lie in the closed domain and the resulting multiplicity must not exceed the degree.
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<NurbsCurve, CurveError> {
        let (start, end) = self.domain();
        if !(t >= start && t <= end) {
            return Err(CurveError::ParameterOutOfDomain { t, start, end });
        }
        let p = self.degree();
        let s = self.multiplicity(t);
        if times == 0 {
            return Ok(self.clone());
        }
        if s + times > p {
            return Err(CurveError::InsertTooOften {
                t,
                times,
                degree: p,
            });
        }
        let up = self.knots();
        let pw = self.homogeneous_points();
        let np = pw.len() - 1;
        let mp = up.len() - 1;
        // k: last index with up[k] <= t (A5.1 needs u_k <= t < u_{k+1} or t == u_k).
        let k = up.partition_point(|&u| u <= t) - 1;
        let r = times;

        let mut uq = Vec::with_capacity(up.len() + r);
        uq.extend_from_slice(&up[..=k]);
        uq.extend(std::iter::repeat_n(t, r));
        uq.extend_from_slice(&up[k + 1..=mp]);

        let mut qw = vec![DVec4::ZERO; pw.len() + r];
        qw[..=k - p].copy_from_slice(&pw[..=k - p]);
        qw[k - s + r..=np + r].copy_from_slice(&pw[k - s..=np]);
        let mut rw: Vec<DVec4> = (0..=p - s).map(|i| pw[k - p + i]).collect();
        let mut l = 0;
        for j in 1..=r {
            l = k - p + j;
            for i in 0..=p - j - s {
                let alpha = (t - up[l + i]) / (up[i + k + 1] - up[l + i]);
                rw[i] = rw[i + 1] * alpha + rw[i] * (1.0 - alpha);
            }
            qw[l] = rw[0];
            qw[k + r - j - s] = rw[p - j - s];
        }
        if l + 1 < k - s {
            qw[l + 1..k - s].copy_from_slice(&rw[1..k - s - l]);
        }
        NurbsCurve::new_unchecked(p, uq, qw).resolvable(t)
    }

    /// Split the curve at an interior parameter `t` into the pieces on `[start, t]` and
    /// `[t, end]`; both keep the original parameterisation and meet exactly at C(t).
    pub fn split(&self, t: f64) -> Result<(NurbsCurve, NurbsCurve), CurveError> {
        let (start, end) = self.domain();
        if !(t > start && t < end) {
            return Err(CurveError::ParameterOutOfDomain { t, start, end });
        }
        let p = self.degree();
        let s = self.multiplicity(t);
        let full = self.insert_knot(t, p.saturating_sub(s))?;
        let knots = full.knots();
        let cw = full.homogeneous_points();
        // First index of t: the p copies sit at a..a+p and C(t) is control point a-1.
        let a = knots.partition_point(|&u| u < t);
        let mut left_knots = knots[..a + p].to_vec();
        left_knots.push(t);
        // Both pieces' spans and control points are the checked insertion's own.
        let left = NurbsCurve::new_unchecked(p, left_knots, cw[..a].to_vec());
        let mut right_knots = vec![t];
        right_knots.extend_from_slice(&knots[a..]);
        let right = NurbsCurve::new_unchecked(p, right_knots, cw[a - 1..].to_vec());
        Ok((left, right))
    }

    /// This curve, made by an edit at `t`, if f64 can still evaluate it: every homogeneous
    /// control point finite with a positive normal weight, and every non-empty knot span wide
    /// enough that its reciprocal is finite (a span of a few subnormals, as a split or knot
    /// insertion at 5e-324 makes, evaluates to NaN). Else [`CurveError::SpanTooShort`] or
    /// [`CurveError::WeightedPointOverflow`].
    fn resolvable(self, t: f64) -> Result<NurbsCurve, CurveError> {
        if let Some((_, span)) = unresolvable_span(self.knots()) {
            return Err(CurveError::SpanTooShort { t, span });
        }
        if let Some(index) = unrepresentable_point(self.homogeneous_points()) {
            return Err(CurveError::WeightedPointOverflow { index });
        }
        Ok(self)
    }
}
