//! End curls: a sign change of the curvature inside the first or last knot span of a fitted
//! piece, and the refit that removes one when the data allow it.
//!
//! The curvature at a free end of a least-squares spline is fixed by the data on one side
//! only, so its scatter is large: for a cubic end span of 25 points with noise σ = 0.02 m
//! over 2.6 m, the standard deviation of the end curvature is about 0.06 /m. Where the true
//! end curvature is smaller than that, a fit can bend the wrong way in the last percent of the
//! curve, a hook that a designer reads as an inflection on the curvature comb and that the
//! data do not support. The closest fit without the hook (a convex least-squares problem
//! under the inequality "the end curvature has the sign of the curvature inside the span")
//! has its optimum on the boundary, zero end curvature, a linear condition on the
//! coefficients. The refit imposes it and is kept only when the data do not reject it and it
//! has fewer inflections: a hook the data demand stays. "Not rejected" is the likelihood-ratio
//! test of the linear model (e.g. Seber & Lee, *Linear Regression Analysis*, 2003, §4.3): on
//! the same knots, the condition raises the least-squares E by at most the 99 % quantile of
//! χ² with one degree of freedom per condition times the noise variance `S/M`; and the refit
//! must still meet the smoothing target (E ≤ S, or the accepted range above S).

use glam::DVec3;

use super::fit::{constrained_fit, EndCurvature, Ends, Spline, Target};
use super::metrics::{fairness_metrics, FairnessMetrics, INFLECTION_THRESHOLD};
use crate::curve::NurbsCurve;

/// Curvature samples across an end span, the end point included.
const SAMPLES: usize = 32;
/// The 99 % quantiles of χ² with 1 and 2 degrees of freedom: the largest rise of E, in units
/// of the noise variance, that one or two end conditions may cause and still be accepted.
const CHI2_99: [f64; 2] = [6.635, 9.210];

/// The signed curvature in the plane with normal `n`, `(C′ × C″)·n / |C′|³`, and `C′`.
fn signed_curvature(curve: &NurbsCurve, t: f64, n: DVec3) -> (f64, DVec3) {
    let d = curve.derivs(t);
    let speed = d.d1.length();
    if speed > 0.0 {
        (d.d1.cross(d.d2).dot(n) / speed.powi(3), d.d1)
    } else {
        (0.0, d.d1)
    }
}

/// True when the samples change sign with hysteresis `thr` (from above `thr` to below `−thr`
/// or back), the rule the inflection count uses.
fn changes_sign(ks: impl Iterator<Item = f64>, thr: f64) -> bool {
    let mut state = 0i8;
    for k in ks {
        let s = if k > thr {
            1
        } else if k < -thr {
            -1
        } else {
            0
        };
        if s != 0 && state != 0 && s != state {
            return true;
        }
        if s != 0 {
            state = s;
        }
    }
    false
}

/// The end conditions that would remove the end curls of `curve`: for each end whose knot
/// span holds a sign change of the in-plane curvature (plane of `normal`; changes below
/// `thr` do not count), the condition that `C″` at that end has no component along the
/// in-plane normal `normal × C′`.
pub(crate) fn end_curls(curve: &NurbsCurve, normal: DVec3, thr: f64) -> Vec<EndCurvature> {
    let k = curve.degree();
    if k < 2 {
        return Vec::new();
    }
    let knots = curve.knots();
    let (a, b) = curve.domain();
    let first = knots[k + 1..].iter().copied().find(|&t| t > a).unwrap_or(b);
    let last = knots[..knots.len() - k - 1]
        .iter()
        .rev()
        .copied()
        .find(|&t| t < b)
        .unwrap_or(a);
    let mut out = Vec::new();
    for (at_start, from, to) in [(true, a, first), (false, b, last)] {
        let ks = (0..=SAMPLES).map(|j| {
            let t = from + (to - from) * j as f64 / SAMPLES as f64;
            signed_curvature(curve, t, normal).0
        });
        if changes_sign(ks, thr) {
            let (_, d1) = signed_curvature(curve, from, normal);
            let w = normal.cross(d1).normalize_or_zero();
            if w != DVec3::ZERO {
                out.push(EndCurvature { at_start, w });
            }
        }
    }
    out
}

/// The fit of `points` at `params` on the knots of `fit`, with its end curls removed, when
/// that is possible within `target` and leaves fewer inflections (`None` otherwise), and the
/// fairness metrics of the curve that is kept.
pub(crate) fn straighten(
    points: &[DVec3],
    params: &[f64],
    target: Target,
    ends: &Ends,
    fit: &Spline,
    curve: &NurbsCurve,
) -> (Option<(Spline, NurbsCurve)>, FairnessMetrics) {
    let before = fairness_metrics(curve);
    match refit(points, params, target, ends, fit, curve, &before) {
        Some((spline, refit, metrics)) => (Some((spline, refit)), metrics),
        None => (None, before),
    }
}

fn refit(
    points: &[DVec3],
    params: &[f64],
    target: Target,
    ends: &Ends,
    fit: &Spline,
    curve: &NurbsCurve,
    before: &FairnessMetrics,
) -> Option<(Spline, NurbsCurve, FairnessMetrics)> {
    let thr = INFLECTION_THRESHOLD * before.max_curvature;
    let cons = end_curls(curve, before.plane_normal, thr);
    if cons.is_empty() {
        return None;
    }
    let k = fit.degree;
    let interior = &fit.knots[k + 1..fit.knots.len() - k - 1];
    let p = fit.p.is_finite().then_some(fit.p).filter(|&p| p > 0.0);
    let variance = target.s / points.len() as f64;
    let max_increase = CHI2_99[cons.len() - 1] * variance;
    let spline = constrained_fit(
        points,
        params,
        k,
        target,
        ends,
        interior,
        &cons,
        p,
        max_increase,
    )?;
    let refit = NurbsCurve::try_new(k, spline.knots.clone(), spline.coefs.clone(), None).ok()?;
    let after = fairness_metrics(&refit);
    (after.inflections < before.inflections).then_some((spline, refit, after))
}
