//! Arc length by adaptive Gauss–Legendre quadrature of |C'(t)| over each knot span.

use super::error::CurveError;
use super::nurbs::NurbsCurve;

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
    pub fn arc_length_between(&self, t0: f64, t1: f64, accuracy: f64) -> Result<f64, CurveError> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(CurveError::Accuracy(accuracy));
        }
        let (start, end) = self.domain();
        let (lo, hi) = (t0.max(start), t1.min(end));
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Ok(0.0);
        }
        let mut breaks: Vec<f64> = vec![lo];
        breaks.extend(self.knots().iter().copied().filter(|&u| u > lo && u < hi));
        breaks.push(hi);
        breaks.dedup();
        let spans = (breaks.len() - 1) as f64;
        let mut total = 0.0;
        for w in breaks.windows(2) {
            let whole = self.gauss(w[0], w[1]);
            total += self.adaptive(w[0], w[1], whole, accuracy / spans, 0);
        }
        Ok(total)
    }

    fn gauss(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        GL8.iter()
            .map(|&(x, w)| w * self.derivs(mid + half * x).d1.length())
            .sum::<f64>()
            * half
    }

    fn adaptive(&self, a: f64, b: f64, whole: f64, budget: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let (left, right) = (self.gauss(a, m), self.gauss(m, b));
        if (left + right - whole).abs() <= budget || depth >= MAX_DEPTH {
            return left + right;
        }
        self.adaptive(a, m, left, 0.5 * budget, depth + 1)
            + self.adaptive(m, b, right, 0.5 * budget, depth + 1)
    }
}
