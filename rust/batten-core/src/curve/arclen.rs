//! Arc length by adaptive Gauss–Legendre quadrature of |C'(t)| over each knot span.

use glam::DVec3;

use super::error::CurveError;
use super::nurbs::{unrepresentable_point, NurbsCurve};

/// 8-point Gauss–Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun 25.4.30), with
/// the digits as published.
#[allow(clippy::excessive_precision)]
pub(crate) const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

const MAX_DEPTH: u32 = 40;

/// Most halvings one arc-length call may make in all (16 evaluations of C′ each; measured
/// 0.10 s in all on a shared machine (load 3), where 2^16 took 0.34 s and, under load, over the fuzz
/// suite's 2 s per call). A smooth curve needs a few per knot span, so this serves curves of
/// thousands of spans; an integrand whose rounding noise exceeds the budget everywhere
/// (neighbouring weights 1e-200 and 1e200 cancel in the rational derivative, or spans of 1e159
/// beside 1e172) would otherwise halve to `MAX_DEPTH` everywhere: 2^40 halvings.
const MAX_HALVINGS: usize = 1 << 14;

/// Relative rounding noise of one Gauss–Legendre estimate (a sum of 8 terms, each a length
/// from three squared coordinates): 16 ulps. A difference between two estimates below this
/// share of their size is rounding, not quadrature error, so halving further cannot help, and
/// an accuracy finer than this share of the length cannot be reached in f64.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

impl NurbsCurve {
    /// Length of the whole curve, within `accuracy` (metres).
    pub fn arc_length(&self, accuracy: f64) -> Result<f64, CurveError> {
        let (a, b) = self.domain();
        self.arc_length_between(a, b, accuracy)
    }

    /// Length of the curve between parameters `t0 <= t1` (clamped to the domain), within
    /// `accuracy`. Each knot span is integrated separately (the integrand is smooth there);
    /// a span's estimate is accepted when it agrees with the sum over its halves within its
    /// share of the accuracy budget, otherwise both halves recurse with half the budget.
    ///
    /// Errors: an accuracy that is not positive and finite, or finer than f64 resolves for this
    /// length ([`CurveError::AccuracyBelowResolution`]: `ROUNDING` × the length), and a length
    /// that is not finite ([`CurveError::NonFiniteLength`], coordinates too large), and a length
    /// that does not settle within [`MAX_HALVINGS`] halvings ([`CurveError::ArcLengthUnsettled`]:
    /// a speed too rough for the accuracy, as extreme weights make it). A halving that
    /// cannot split its interval any more (spans of a few ulps) ends the recursion there.
    pub fn arc_length_between(&self, t0: f64, t1: f64, accuracy: f64) -> Result<f64, CurveError> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(CurveError::Accuracy(accuracy));
        }
        let (start, end) = self.domain();
        let (lo, hi) = (t0.max(start), t1.min(end));
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Ok(0.0);
        }
        self.about_centre().length_between(lo, hi, accuracy)
    }

    /// This curve moved so that its control points' bounding box is centred on the origin:
    /// the same speed |C′|, computed without the rounding noise of large coordinates. At an
    /// offset of 1e7 m (georeferenced data) the noise of C′ from coordinates of 1e7 exceeded
    /// any millimetre budget and the quadrature halved to its depth limit everywhere.
    fn about_centre(&self) -> NurbsCurve {
        let Some(bbox) = super::bbox::Aabb::from_points(self.control_points()) else {
            return self.clone();
        };
        let centre = 0.5 * (bbox.min + bbox.max);
        if !centre.is_finite() || centre == DVec3::ZERO {
            return self.clone();
        }
        let cw: Vec<_> = self
            .homogeneous_points()
            .iter()
            .map(|c| (c.truncate() - centre * c.w).extend(c.w))
            .collect();
        if unrepresentable_point(&cw).is_some() {
            return self.clone(); // a huge weight times the centre overflows: keep the curve
        }
        NurbsCurve::new_unchecked(self.degree(), self.knots().to_vec(), cw)
    }

    /// [`NurbsCurve::arc_length_between`] on `lo < hi` inside the domain.
    fn length_between(&self, lo: f64, hi: f64, accuracy: f64) -> Result<f64, CurveError> {
        let mut breaks: Vec<f64> = vec![lo];
        breaks.extend(self.knots().iter().copied().filter(|&u| u > lo && u < hi));
        breaks.push(hi);
        breaks.dedup();
        let spans = (breaks.len() - 1) as f64;
        let wholes: Vec<f64> = breaks.windows(2).map(|w| self.gauss(w[0], w[1])).collect();
        let estimate: f64 = wholes.iter().sum();
        if !estimate.is_finite() {
            return Err(CurveError::NonFiniteLength);
        }
        let resolvable = ROUNDING * estimate;
        if accuracy < resolvable {
            return Err(CurveError::AccuracyBelowResolution {
                accuracy,
                resolvable,
            });
        }
        let mut total = 0.0;
        let mut halvings = 0;
        for (w, &whole) in breaks.windows(2).zip(&wholes) {
            total += self
                .adaptive(w[0], w[1], whole, accuracy / spans, 0, &mut halvings)
                .ok_or(CurveError::ArcLengthUnsettled { accuracy })?;
        }
        if total.is_finite() {
            Ok(total)
        } else {
            Err(CurveError::NonFiniteLength)
        }
    }

    fn gauss(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        GL8.iter()
            .map(|&(x, w)| w * self.point_d1(mid + half * x).1.length())
            .sum::<f64>()
            * half
    }

    /// The length over `[a, b]` (whose single Gauss estimate is `whole`) within `budget`, or
    /// `None` once `halvings` (counted over the whole call) passes [`MAX_HALVINGS`].
    fn adaptive(
        &self,
        a: f64,
        b: f64,
        whole: f64,
        budget: f64,
        depth: u32,
        halvings: &mut usize,
    ) -> Option<f64> {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            return Some(whole); // the interval is a few ulps wide: nothing left to halve
        }
        *halvings += 1;
        if *halvings > MAX_HALVINGS {
            return None;
        }
        let (left, right) = (self.gauss(a, m), self.gauss(m, b));
        let diff = (left + right - whole).abs();
        let noise = ROUNDING * (left.abs() + right.abs());
        if diff <= budget || diff <= noise || !diff.is_finite() || depth >= MAX_DEPTH {
            return Some(left + right);
        }
        Some(
            self.adaptive(a, m, left, 0.5 * budget, depth + 1, halvings)?
                + self.adaptive(m, b, right, 0.5 * budget, depth + 1, halvings)?,
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn line(to: f64) -> NurbsCurve {
        NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![DVec3::ZERO, DVec3::X * to],
            None,
        )
        .expect("line")
    }

    #[test]
    fn the_first_derivative_alone_is_bit_for_bit_that_of_all_three() {
        // point_d1 (what the quadrature evaluates) against derivs, on a rational quintic with
        // uneven knots and on a cubic, at knots and between them.
        let quintic = NurbsCurve::try_new(
            5,
            vec![
                0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.35, 1.7, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0,
            ],
            (0..9)
                .map(|i| DVec3::new(i as f64, (i as f64 * 1.3).sin(), (i * i) as f64 * 0.1))
                .collect(),
            Some(vec![1.0, 0.5, 2.0, 1.5, 0.7, 1.1, 3.0, 0.9, 1.0]),
        )
        .expect("quintic");
        let cubic = NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(2.0, 1.0, 0.0),
                DVec3::new(3.0, 0.0, 1.0),
            ],
            None,
        )
        .expect("cubic");
        for c in [quintic, cubic] {
            let (a, b) = c.domain();
            for k in 0..=200 {
                let t = a + (b - a) * k as f64 / 200.0;
                let d = c.derivs(t);
                assert_eq!(c.point_d1(t), (d.point, d.d1), "t = {t}");
            }
            for &t in c.knots() {
                let d = c.derivs(t);
                assert_eq!(c.point_d1(t), (d.point, d.d1), "knot {t}");
            }
        }
    }

    #[test]
    fn a_georeferenced_curve_is_measured_as_at_the_origin() {
        // Found by the fuzz suite: a cubic at x = -1e7 m, z = 1e17 m (where z rounds to 16 m)
        // made C′ noisy, above a 1 cm budget everywhere, and the quadrature halved to depth 40.
        let pts = [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 0.5)];
        let cubic = |at: f64| {
            NurbsCurve::try_new(
                3,
                vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
                pts.iter()
                    .map(|&(x, y)| DVec3::new(x - at, y, at * 1e10))
                    .collect(),
                None,
            )
            .expect("cubic")
        };
        let here = cubic(0.0).arc_length(1e-9).expect("at the origin");
        let started = std::time::Instant::now();
        let there = cubic(1e7).arc_length(1e-2).expect("1e7 m and 1e17 m away");
        assert!((here - there).abs() <= 1e-2, "{here} vs {there}");
        assert!(
            started.elapsed().as_secs_f64() < 0.1,
            "{:?}",
            started.elapsed()
        );
    }

    #[test]
    fn a_speed_rougher_than_the_accuracy_is_an_error_not_a_hang() {
        // Found by the fuzz suite: weights 1e-200 beside 1e200 at 1e17 m. The rational
        // derivative's rounding noise exceeds every budget, and the recursion halved to depth
        // 40 everywhere (it ran for hours).
        let p = |z: f64| DVec3::new(1e17, 1e17, z);
        let c = NurbsCurve::try_new(
            2,
            vec![0.0, 0.0, 0.0, 0.01, 0.02, 0.03, 0.03, 0.03],
            vec![p(0.1), p(0.0033), p(0.1), p(0.015), p(0.0)],
            Some(vec![7.7, 1e-200, 4.85, 1e200, 1e200]),
        )
        .expect("valid, if extreme");
        let started = std::time::Instant::now();
        let got = c.arc_length(1.0);
        assert!(
            matches!(got, Ok(l) if l.is_finite())
                || got == Err(CurveError::ArcLengthUnsettled { accuracy: 1.0 }),
            "{got:?}"
        );
        assert!(
            started.elapsed().as_secs_f64() < 1.0,
            "{:?}",
            started.elapsed()
        );
    }

    #[test]
    fn an_accuracy_f64_cannot_reach_is_refused_not_chased() {
        // 1e150 m: an absolute 1e-9 m is 1e-159 of the length (the recursion used to halve its
        // budget to depth 40, 2^40 evaluations).
        assert!(
            matches!(
                line(1e150).arc_length(1e-9),
                Err(CurveError::AccuracyBelowResolution { resolvable, .. }) if resolvable > 1e130
            ),
            "refused with what f64 resolves"
        );
        // The same relative accuracy a designer asks for is met exactly.
        let l = line(120.0).arc_length(1e-9).expect("120 m to 1 nm");
        assert!((l - 120.0).abs() <= 1e-9, "{l}");
    }

    #[test]
    fn an_overflowing_length_is_an_error() {
        assert_eq!(
            line(1e200).arc_length(1e-3),
            Err(CurveError::NonFiniteLength),
            "|C'| = 1e200 squares past f64"
        );
    }

    #[test]
    fn a_knot_span_of_1e_300_returns_at_once() {
        // |C'| ~ 1e300 over a span of 1e-300: the length is not computable in f64 (its
        // derivative squares past f64) and is refused at once instead of halving to depth 40.
        let c = NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1e-300, 1e-300, 1e-300, 1e-300],
            vec![
                DVec3::ZERO,
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(2.0, -1.0, 0.0),
                DVec3::new(3.0, 0.0, 0.0),
            ],
            None,
        )
        .expect("a valid, if extreme, cubic");
        assert_eq!(
            c.arc_length(1e-9),
            Err(CurveError::NonFiniteLength),
            "refused"
        );
        // Splitting a curve at the first subnormal would leave such a span, and is refused.
        assert!(
            matches!(
                line(5.0).split(f64::from_bits(1)),
                Err(CurveError::SpanTooShort { .. })
            ),
            "split at 5e-324"
        );
        assert!(
            matches!(
                line(5.0).insert_knot(f64::from_bits(1), 1),
                Err(CurveError::SpanTooShort { .. })
            ),
            "knot inserted at 5e-324"
        );
    }
}
