//! The fairing's report: per section and for the hull, the fairness figures before and after
//! (curvature variation ∫κ′² ds, inflections, the largest bias ‖F − C‖) and how far each curve
//! moved from where it started.

use crate::curve::NurbsCurve;
use crate::fair::{curvature_variation, fairness_metrics};
use crate::network::Network;

use super::families::{Family, SectionFamily};
use super::filter::SectionBias;
use super::relax::State;

/// Points per knot span at which a moved curve is compared with where it started.
const DEVIATION_SAMPLES_PER_SPAN: usize = 16;

/// Fairness figures of one section.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionFairness {
    /// ∫κ′² ds (1/m³), the curvature variation.
    pub curvature_variation: f64,
    /// Inflections in the section's plane.
    pub inflections: usize,
    /// The largest bias against the filtered section (m); 0 for a curve in no family.
    pub max_bias: f64,
}

/// What the fairing did to one curve.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionReport {
    /// The curve's name.
    pub curve: String,
    /// Its family, `None` for a fixed curve or one in no faired family.
    pub family: Option<SectionFamily>,
    /// The plane's offset along the family's axis (m).
    pub offset: Option<f64>,
    /// Moves it took part in (as the section moved, or carrying a node along).
    pub moves: usize,
    /// Its tolerance (m); 0 for a curve that may not move.
    pub tolerance: f64,
    /// The largest distance (m) of a point of the curve from where it started (sampled at
    /// equal parameters, so an upper bound of the distance to the original curve).
    pub max_deviation: f64,
    /// Figures before.
    pub before: SectionFairness,
    /// Figures after.
    pub after: SectionFairness,
}

/// The hull's figures: sums over the sections of the faired families, the largest bias.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullFairness {
    /// Σ ∫κ′² ds over the sections (1/m³).
    pub curvature_variation: f64,
    /// Σ inflections over the sections.
    pub inflections: usize,
    /// The largest bias of any section (m).
    pub max_bias: f64,
}

/// The report of [`fair_sections`](super::fair_sections).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceFairReport {
    /// One entry per curve of the network, in its order.
    pub curves: Vec<SectionReport>,
    /// Rounds made (one family each).
    pub rounds: usize,
    /// Sections moved, in all.
    pub moves: usize,
    /// True when every section's RMS bias is within `bias_target`, or nothing could move any
    /// more (every family had a round without a move).
    pub converged: bool,
    /// The RMS bias that counts as fair (m).
    pub bias_target: f64,
    /// The smoothing length along the sections (m; 0: none).
    pub smoothing_length: f64,
    /// Sections the smoothing along the sections moved (before the rounds).
    pub smoothed: usize,
    /// Movable sections per family, in the order they were faired.
    pub sections: Vec<(SectionFamily, usize)>,
    /// The largest distance of any point from where it started (m).
    pub max_deviation: f64,
    /// The hull's figures before.
    pub before: HullFairness,
    /// The hull's figures after.
    pub after: HullFairness,
}

/// The counters of the run.
pub(crate) struct Totals {
    pub rounds: usize,
    pub moves: usize,
    pub converged: bool,
    pub bias_target: f64,
    pub smoothing_length: f64,
    pub smoothed: usize,
}

fn figures(curve: &NurbsCurve, bias: Option<&SectionBias>) -> SectionFairness {
    SectionFairness {
        curvature_variation: curvature_variation(curve),
        inflections: fairness_metrics(curve).inflections,
        max_bias: bias.map_or(0.0, |b| b.max),
    }
}

/// The largest distance between `a` and `b` (same domain) at equal parameters.
fn deviation(a: &NurbsCurve, b: &NurbsCurve) -> f64 {
    let (start, end) = b.domain();
    b.knots()
        .windows(2)
        .filter(|w| w[0] >= start && w[1] <= end && w[1] > w[0])
        .flat_map(|w| {
            (0..=DEVIATION_SAMPLES_PER_SPAN)
                .map(move |i| w[0] + (w[1] - w[0]) * i as f64 / DEVIATION_SAMPLES_PER_SPAN as f64)
        })
        .map(|t| a.point(t).distance(b.point(t)))
        .fold(0.0, f64::max)
}

fn hull(sections: &[&SectionFairness]) -> HullFairness {
    HullFairness {
        curvature_variation: sections.iter().map(|s| s.curvature_variation).sum(),
        inflections: sections.iter().map(|s| s.inflections).sum(),
        max_bias: sections.iter().map(|s| s.max_bias).fold(0.0, f64::max),
    }
}

/// The report of a fairing of `network` that ended in `state`.
pub(crate) fn report(
    network: &Network,
    state: &State,
    place: &[Option<(usize, usize)>],
    families: &[Family],
    before: &[Option<SectionBias>],
    after: &[Option<SectionBias>],
    totals: Totals,
) -> SurfaceFairReport {
    let curves: Vec<SectionReport> = network
        .curves()
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let at = place[i].map(|(f, g)| (families[f].family, families[f].groups[g].offset));
            let moved = state.moves[i] > 0;
            SectionReport {
                curve: c.name.clone(),
                family: at.map(|a| a.0),
                offset: at.map(|a| a.1),
                moves: state.moves[i],
                tolerance: state.tolerance[i],
                max_deviation: if moved {
                    deviation(&c.curve, &state.curves[i])
                } else {
                    0.0
                },
                before: figures(&c.curve, before[i].as_ref()),
                after: if moved {
                    figures(&state.curves[i], after[i].as_ref())
                } else {
                    SectionFairness {
                        max_bias: after[i].as_ref().map_or(0.0, |b| b.max),
                        ..figures(&c.curve, None)
                    }
                },
            }
        })
        .collect();
    let in_family: Vec<&SectionReport> = curves.iter().filter(|c| c.family.is_some()).collect();
    let before_hull = hull(&in_family.iter().map(|c| &c.before).collect::<Vec<_>>());
    let after_hull = hull(&in_family.iter().map(|c| &c.after).collect::<Vec<_>>());
    SurfaceFairReport {
        max_deviation: curves.iter().map(|c| c.max_deviation).fold(0.0, f64::max),
        sections: families
            .iter()
            .enumerate()
            .map(|(f, family)| {
                let moving = place.iter().filter(|p| p.is_some_and(|(pf, _)| pf == f));
                (family.family, moving.count())
            })
            .collect(),
        before: before_hull,
        after: after_hull,
        curves,
        rounds: totals.rounds,
        moves: totals.moves,
        converged: totals.converged,
        bias_target: totals.bias_target,
        smoothing_length: totals.smoothing_length,
        smoothed: totals.smoothed,
    }
}
