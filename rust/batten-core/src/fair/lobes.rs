//! Curvature lobes the data do not demand: finding the stretches of one curvature sign
//! (lobes) of a fitted piece, and refitting with the small ones flattened when a statistical
//! test says the data allow it.
//!
//! A smoothing spline with `E = S` can still carry small lobes of the wrong curvature sign
//! that lie within the noise: at a free end, whose curvature is fixed by the data on one side
//! only (a cubic end span of 25 points with σ = 0.02 m over 2.6 m has an end curvature
//! scattering by about 0.06 /m), and on flat or nearly straight stretches, where the true
//! curvature is zero and any noise bends the fit both ways. A designer reads each of them as
//! an inflection on the curvature comb. The closest fit without such a lobe has zero
//! curvature at its peak (the constrained optimum lies on the boundary of "no opposite
//! sign"), a linear condition `w · C″(t) = 0` on the coefficients (`w` the in-plane normal).
//!
//! The lobes are tried smallest first (by `∫|κ| ds`), at most [`MAX_TRIES`] refits. A
//! condition is kept when the data do not reject it and the refit has fewer inflections; then
//! the lobes of the refit are tried in turn. "Not rejected" is the likelihood-ratio test of
//! the linear model (e.g. Seber & Lee, *Linear Regression Analysis*, 2003, §4.3): on the same
//! knots, the q conditions together raise the least-squares E by at most the 99 % quantile of
//! χ² with q degrees of freedom times the noise variance `S/M`; and the refit must still meet
//! the smoothing target (E ≤ S, or the accepted range above S).
//!
//! Not removed: ringing after a jump in curvature, such as the negative lobe a cubic spline
//! puts on a flat side just past the bilge radius of a midship section (line, arc, line). The
//! data reject zero curvature there on the fit's knots; a fair fit needs knots placed for
//! the jump, which `convex` adds (in noise mode).

use glam::DVec3;

use super::fit::{constrained_fit, Spline, System, Target, ZeroCurvature, CHI2_99};
use super::metrics::{
    bending_energy, curvature_samples, sign_changes, CurvatureSamples, FairnessMetrics,
    INFLECTION_THRESHOLD,
};
use crate::curve::NurbsCurve;

/// Most constrained refits tried per piece (each costs about one fit on fixed knots).
const MAX_TRIES: usize = 8;

/// The share of its peak's |κ| a lobe keeps at the end of its piece to be an end lobe.
pub(crate) const END_LOBE_SHARE: f64 = 0.5;

/// One stretch of the curve where the in-plane curvature keeps its sign (beyond the
/// threshold).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lobe {
    /// Where |κ| peaks (the curve's end for an end lobe growing towards it).
    pub peak: f64,
    /// `∫|κ| ds` over the lobe's samples, its size.
    size: f64,
    /// Whether it grows towards an end of its smooth piece: it runs to the end, and its |κ|
    /// there is at least [`END_LOBE_SHARE`] of its peak's (a lobe that dies away before the
    /// end, its curvature below the threshold from there on, is no end lobe).
    pub at_end: bool,
}

/// The lobes of a curve from its curvature samples: runs of samples between sign changes
/// of the curvature counted with hysteresis `thr` (the rule of the inflection count), within
/// each smooth piece.
pub(crate) fn lobes(samples: &CurvatureSamples, domain: (f64, f64), thr: f64) -> Vec<Lobe> {
    let mut out: Vec<Lobe> = Vec::new();
    for piece in &samples.pieces {
        let from = out.len();
        let mut cuts = sign_changes(piece.iter().map(|s| s.kappa), thr);
        cuts.push(piece.len());
        let mut start = 0;
        for end in cuts {
            let run = &piece[start..end];
            // The first of equal peaks.
            let Some(peak) = run
                .iter()
                .reduce(|a, b| if b.kappa.abs() > a.kappa.abs() { b } else { a })
            else {
                continue;
            };
            out.push(Lobe {
                peak: peak.t,
                size: run.iter().map(|s| s.kappa.abs() * s.ds).sum(),
                at_end: (start == 0 && piece[0].kappa.abs() >= END_LOBE_SHARE * peak.kappa.abs())
                    || (end == piece.len()
                        && piece[end - 1].kappa.abs() >= END_LOBE_SHARE * peak.kappa.abs()),
            });
            start = end;
        }
        // An end lobe whose |κ| peaks at the piece's first (last) sample peaks at the end
        // itself: it is flattened there, where the curvature is least determined.
        let last = out.len().saturating_sub(1);
        if last > from {
            if piece.first().is_some_and(|s| out[from].peak == s.t) {
                out[from].peak = domain.0;
            }
            if piece.last().is_some_and(|s| out[last].peak == s.t) {
                out[last].peak = domain.1;
            }
        }
    }
    out
}

/// The fit on the knots and data of `system` (those of `fit`) with the lobes the data do not
/// demand flattened (see the module note), when there are any (`None` otherwise), and the
/// fairness metrics of the curve that is kept.
pub(crate) fn flatten(
    system: &System,
    target: Target,
    fit: &Spline,
    curve: &NurbsCurve,
) -> (Option<(Spline, NurbsCurve)>, FairnessMetrics) {
    // Energy only once, for the curve that is kept.
    let mut samples = curvature_samples(curve, false);
    let mut kept: Option<(Spline, NurbsCurve)> = None;
    if fit.degree < 2 || samples.metrics.inflections == 0 {
        samples.metrics.fairness_energy = bending_energy(curve);
        return (kept, samples.metrics);
    }
    let k = fit.degree;
    let p = fit.p.is_finite().then_some(fit.p).filter(|&p| p > 0.0);
    let variance = target.s / system.data_count() as f64;
    let mut conditions: Vec<ZeroCurvature> = Vec::new();
    let mut tries = 0;
    'rounds: while conditions.len() < CHI2_99.len() && samples.metrics.inflections > 0 {
        let current = kept.as_ref().map_or(curve, |(_, c)| c);
        let thr = INFLECTION_THRESHOLD * samples.metrics.max_curvature;
        let n = samples.metrics.plane_normal;
        let mut candidates = lobes(&samples, current.domain(), thr);
        candidates.sort_by(|x, y| x.size.total_cmp(&y.size));
        for lobe in candidates {
            if tries == MAX_TRIES {
                break 'rounds;
            }
            tries += 1;
            let w = n.cross(current.derivs(lobe.peak).d1).normalize_or_zero();
            if w == DVec3::ZERO {
                continue;
            }
            conditions.push(ZeroCurvature { t: lobe.peak, w });
            let max_increase = CHI2_99[conditions.len() - 1] * variance;
            let refit =
                constrained_fit(system, target, &conditions, p, max_increase).and_then(|spline| {
                    let c =
                        NurbsCurve::try_new(k, spline.knots.clone(), spline.coefs.clone(), None);
                    c.ok().map(|c| (spline, c))
                });
            if let Some((spline, refit)) = refit {
                let after = curvature_samples(&refit, false);
                if after.metrics.inflections < samples.metrics.inflections {
                    samples = after;
                    kept = Some((spline, refit));
                    continue 'rounds;
                }
            }
            conditions.pop();
        }
        break;
    }
    let mut metrics = samples.metrics;
    metrics.fairness_energy = bending_energy(kept.as_ref().map_or(curve, |(_, c)| c));
    (kept, metrics)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fair::metrics::CurvatureSample;

    fn samples(kappas: &[f64]) -> CurvatureSamples {
        let piece: Vec<CurvatureSample> = kappas
            .iter()
            .enumerate()
            .map(|(i, &kappa)| CurvatureSample {
                t: i as f64 + 0.5,
                kappa,
                ds: 1.0,
            })
            .collect();
        CurvatureSamples {
            pieces: vec![piece],
            metrics: FairnessMetrics {
                inflections: 0,
                curvature_extrema: 0,
                fairness_energy: 0.0,
                max_curvature: 0.0,
                plane_normal: DVec3::Z,
            },
        }
    }

    #[test]
    fn lobes_split_at_sign_changes_and_end_lobes_peak_at_the_ends() {
        // A curl at the start (largest at the first sample), a big positive lobe, a small
        // negative wiggle (peak in its middle), and a positive end lobe peaking inside.
        let mut k = vec![-0.05, -0.03, -0.01, 0.002];
        k.extend([0.2, 0.5, 0.4, 0.1]);
        k.extend([-0.01, -0.03, -0.02]);
        k.extend([0.1, 0.3, 0.2]);
        let found = lobes(&samples(&k), (0.0, 14.0), 0.005);
        assert_eq!(found.len(), 4, "three sign changes");
        assert_eq!(found[0].peak, 0.0, "the curl grows towards the start");
        assert_eq!(found[1].peak, 5.5, "largest |κ| of the big lobe");
        assert_eq!(found[2].peak, 9.5, "the wiggle's peak");
        assert_eq!(found[3].peak, 12.5, "peaks inside, not at the end");
        // Sizes are ∫|κ| ds over each run (the sub-threshold sample joins the run it is in).
        assert!((found[2].size - 0.06).abs() < 1e-12, "{}", found[2].size);
        assert!((found[0].size - 0.092).abs() < 1e-12, "{}", found[0].size);
    }
}
