//! Curves from the usual ways of laying out knots and control points: uniform, end-point
//! (clamped) and Bézier-segmented NURBS, optionally periodic; Bézier splines with handles; and
//! polylines. These are the spline kinds of Blender and most modellers; the core knows the
//! conventions, not Blender.

use glam::DVec3;

use super::error::CurveError;
use super::nurbs::NurbsCurve;

/// How a NURBS spline's knots are laid out from its control-point count and order.
///
/// Knots are integers counted up from 0: inner knots step by 1 (`Uniform`, `Endpoint`) or are
/// repeated `order − 1` times (`Bezier`, `EndpointBezier`, giving Bézier-like segments);
/// end-point layouts repeat the first and last knot `order` times so the curve starts and ends
/// at its end control points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KnotLayout {
    /// Uniform knots 0, 1, 2, …; the curve does not reach its end control points.
    Uniform,
    /// Clamped: first and last knots repeated `order` times.
    Endpoint,
    /// Inner knots repeated `order − 1` times.
    Bezier,
    /// Clamped and Bézier-segmented.
    EndpointBezier,
}

impl KnotLayout {
    /// The knot vector for `count` control points (before wrapping for a periodic curve) of
    /// `order`: `count + order` knots, or `count + 2·order − 1` when `cyclic`.
    ///
    /// The head knot is repeated `order` times for end-point layouts (`order − 1` times when
    /// cyclic, after one leading knot), twice for Bézier layouts, once otherwise. A cyclic
    /// vector ends with `2·order − 1` knots that repeat the widths of the first ones, so the
    /// wrapped curve closes with the same spacing it starts with.
    pub fn knots(self, count: usize, order: usize, cyclic: bool) -> Vec<f64> {
        let is_bezier = matches!(self, KnotLayout::Bezier | KnotLayout::EndpointBezier);
        let is_endpoint = matches!(self, KnotLayout::Endpoint | KnotLayout::EndpointBezier);
        let len = count + order + if cyclic { order - 1 } else { 0 };
        let repeat_inner = if is_bezier { order - 1 } else { 1 };
        let head = if is_endpoint {
            order - usize::from(cyclic)
        } else if is_bezier {
            repeat_inner.min(2)
        } else {
            1
        };
        let tail = if cyclic {
            2 * order - 1
        } else if is_endpoint {
            order
        } else {
            0
        };
        let mut knots = vec![0.0; len];
        let offset = usize::from(is_endpoint && cyclic);
        let mut current = 0.0;
        if offset == 1 {
            knots[0] = current;
            current += 1.0;
        }
        let mut r = head;
        for k in knots.iter_mut().take(len - tail).skip(offset) {
            *k = current;
            r -= 1;
            if r == 0 {
                current += 1.0;
                r = repeat_inner;
            }
        }
        let first = knots[0];
        for i in 0..tail {
            knots[len - tail + i] = current + (knots[i] - first);
        }
        knots
    }
}

impl NurbsCurve {
    /// A NURBS spline given as control points, optional weights, order and knot layout; a
    /// `cyclic` spline wraps its first `order − 1` control points round to close smoothly.
    pub fn from_layout(
        points: &[DVec3],
        weights: Option<&[f64]>,
        order: usize,
        layout: KnotLayout,
        cyclic: bool,
    ) -> Result<NurbsCurve, CurveError> {
        if !(2..=super::MAX_DEGREE + 1).contains(&order) {
            return Err(CurveError::Order {
                order,
                max: super::MAX_DEGREE + 1,
            });
        }
        if points.len() < order {
            return Err(CurveError::TooFewPoints {
                count: points.len(),
                order,
            });
        }
        let knots = layout.knots(points.len(), order, cyclic);
        let wrap = if cyclic { order - 1 } else { 0 };
        let pts: Vec<DVec3> = points
            .iter()
            .chain(points.iter().take(wrap))
            .copied()
            .collect();
        let w = weights.map(|w| w.iter().chain(w.iter().take(wrap)).copied().collect());
        NurbsCurve::try_new(order - 1, knots, pts, w)
    }

    /// A piecewise cubic Bézier spline (points with left and right handles, as drawn in Blender
    /// and most illustration tools) as a cubic B-spline with triple inner knots: segment `i` runs
    /// from `co[i]` via `right[i]`, `left[i+1]` to `co[i+1]` on parameters `[i, i+1]`. Corners
    /// (non-aligned handles) stay corners: see [`NurbsCurve::corner_parameters`].
    pub fn from_bezier(
        co: &[DVec3],
        left: &[DVec3],
        right: &[DVec3],
        cyclic: bool,
    ) -> Result<NurbsCurve, CurveError> {
        let n = co.len();
        assert!(
            left.len() == n && right.len() == n,
            "one handle pair per point"
        );
        if n < 2 {
            return Err(CurveError::TooFewPoints { count: n, order: 2 });
        }
        let segments = if cyclic { n } else { n - 1 };
        let mut pts = Vec::with_capacity(3 * segments + 1);
        for i in 0..segments {
            let j = (i + 1) % n;
            pts.extend_from_slice(&[co[i], right[i], left[j]]);
        }
        pts.push(co[segments % n]);
        let mut knots = vec![0.0; 4];
        for i in 1..segments {
            knots.extend(std::iter::repeat_n(i as f64, 3));
        }
        knots.extend(std::iter::repeat_n(segments as f64, 4));
        NurbsCurve::try_new(3, knots, pts, None)
    }

    /// A polyline as a degree-1 B-spline with one knot per vertex (`cyclic` closes it).
    pub fn from_polyline(points: &[DVec3], cyclic: bool) -> Result<NurbsCurve, CurveError> {
        let mut pts = points.to_vec();
        if cyclic && !pts.is_empty() {
            pts.push(pts[0]);
        }
        let n = pts.len();
        if n < 2 {
            return Err(CurveError::TooFewPoints { count: n, order: 2 });
        }
        let mut knots = Vec::with_capacity(n + 2);
        knots.push(0.0);
        knots.extend((0..n).map(|i| i as f64));
        knots.push((n - 1) as f64);
        NurbsCurve::try_new(1, knots, pts, None)
    }
}

impl NurbsCurve {
    /// The open (non-cyclic) layout whose knots this curve's knot vector is an affine image of,
    /// checked for `Endpoint` then `Uniform`; `None` for any other knot vector.
    ///
    /// A curve with a matching layout can be handed to a modeller that only knows layouts
    /// (Blender) with its control points unchanged.
    pub fn matching_layout(&self) -> Option<KnotLayout> {
        let k = self.knots();
        let (n, order) = (self.control_point_count(), self.order());
        [KnotLayout::Endpoint, KnotLayout::Uniform]
            .into_iter()
            .find(|layout| {
                let l = layout.knots(n, order, false);
                let scale = (k[k.len() - 1] - k[0]) / (l[l.len() - 1] - l[0]);
                let tol = 1e-12 * (k[k.len() - 1] - k[0]);
                k.iter()
                    .zip(&l)
                    .all(|(&u, &v)| (u - (k[0] + scale * (v - l[0]))).abs() <= tol)
            })
    }

    /// The curve as a modeller that knows only knot layouts (Blender) holds it: itself when a
    /// layout matches ([`NurbsCurve::matching_layout`]), else its Bézier pieces in the
    /// `EndpointBezier` layout ([`NurbsCurve::bezier_control_points`]): the same shape, with
    /// one unit of parameter per piece. What a surface built from the modeller's curves is
    /// built from (its nodes and edges are found at those parameters; its patches run their
    /// sides at arc length and turning, whatever the parameter).
    pub fn as_layouts_hold(&self) -> NurbsCurve {
        if self.matching_layout().is_some() {
            return self.clone();
        }
        let hw = self.bezier_control_points();
        let points: Vec<DVec3> = hw.iter().map(|h| h.truncate() / h.w).collect();
        let weights: Vec<f64> = hw.iter().map(|h| h.w).collect();
        let rational = weights.iter().any(|&w| w != 1.0);
        NurbsCurve::from_layout(
            &points,
            rational.then_some(weights.as_slice()),
            self.order(),
            KnotLayout::EndpointBezier,
            false,
        )
        .unwrap_or_else(|_| self.clone())
    }

    /// Control points of the curve cut into Bézier pieces, consecutive pieces sharing their
    /// joint point (`1 + pieces·degree` homogeneous points). With the `EndpointBezier` layout
    /// and the same order they give back exactly this shape (parameterised per piece).
    pub fn bezier_control_points(&self) -> Vec<glam::DVec4> {
        let dec = self.bezier_decomposition();
        let mut out = Vec::with_capacity(1 + dec.piece_count() * self.degree());
        for (i, piece) in dec.pieces.iter().enumerate() {
            let skip = usize::from(i > 0);
            out.extend_from_slice(&piece.points()[skip..]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knot_layouts_order_4_six_points() {
        assert_eq!(
            KnotLayout::Uniform.knots(6, 4, false),
            (0..10).map(f64::from).collect::<Vec<_>>(),
            "uniform"
        );
        assert_eq!(
            KnotLayout::Endpoint.knots(6, 4, false),
            vec![0., 0., 0., 0., 1., 2., 3., 3., 3., 3.],
            "endpoint"
        );
    }

    #[test]
    fn layouts_are_recognised_and_bezier_points_rebuild_the_shape() {
        let pts: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(i as f64, (i as f64 * 0.9).sin(), 0.2 * i as f64))
            .collect();
        let w = [1.0, 0.5, 2.0, 1.0, 3.0, 0.7, 1.0];
        for layout in [KnotLayout::Endpoint, KnotLayout::Uniform] {
            let c = NurbsCurve::from_layout(&pts, Some(&w), 4, layout, false).unwrap();
            assert_eq!(c.matching_layout(), Some(layout), "{layout:?} recognised");
            let hw = c.bezier_control_points();
            let (bp, bw): (Vec<DVec3>, Vec<f64>) =
                hw.iter().map(|h| (h.truncate() / h.w, h.w)).unzip();
            let b = NurbsCurve::from_layout(&bp, Some(&bw), 4, KnotLayout::EndpointBezier, false)
                .unwrap();
            let (a0, a1) = c.domain();
            let (b0, b1) = b.domain();
            for i in 0..=60 {
                let s = i as f64 / 60.0;
                let (pa, pb) = (c.point(a0 + s * (a1 - a0)), b.point(b0 + s * (b1 - b0)));
                // Same pieces, uniform per-piece parameters on both: pointwise equal.
                assert!(
                    (pa - pb).length() < 1e-12,
                    "{layout:?} at {s}: {pa} vs {pb}"
                );
            }
        }
        let odd = NurbsCurve::try_new(
            2,
            vec![0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0],
            pts[..4].to_vec(),
            None,
        )
        .unwrap();
        assert_eq!(
            odd.matching_layout(),
            None,
            "non-uniform knots match no layout"
        );
    }
}
