//! The shape checks every deformed hull must pass (seed 002 §8.3's bracket: a deformation is
//! taken until one fails): it builds with the original's faces and no more warnings (no face
//! lost, no new fold or gap), and no station gains an inflection.

use crate::fair::fairness_metrics;
use crate::form::{curve_planes, PlaneKind};
use crate::hull::HullSurface;
use crate::network::Network;
use crate::tolerance::Tolerance;

/// What the original has that every deformed hull must keep.
pub(super) struct Reference {
    faces: usize,
    warnings: usize,
    /// Per curve: its inflections when it is a station (in a plane x = constant), else None.
    inflections: Vec<Option<usize>>,
}

/// The inflections of each station of `network` (a curve in a transverse plane, as the form
/// topology finds its planes; None for other curves).
fn station_inflections(network: &Network, tolerance: Tolerance) -> Vec<Option<usize>> {
    network
        .curves()
        .iter()
        .map(|c| {
            let transverse = curve_planes(&c.curve, tolerance.get())
                .iter()
                .any(|(kind, _, _)| *kind == PlaneKind::Transverse);
            (transverse && c.curve.degree() >= 2).then(|| fairness_metrics(&c.curve).inflections)
        })
        .collect()
}

impl Reference {
    /// The original `network` and its built `hull`.
    pub(super) fn of(network: &Network, hull: &HullSurface, tolerance: Tolerance) -> Reference {
        Reference {
            faces: hull.report.faces,
            warnings: hull.report.warnings.len(),
            inflections: station_inflections(network, tolerance),
        }
    }

    /// Whether the deformed `network`, built as `hull`, passes; else which check fails.
    pub(super) fn check(
        &self,
        network: &Network,
        hull: &HullSurface,
        tolerance: Tolerance,
    ) -> Result<(), String> {
        if hull.report.faces != self.faces {
            return Err(format!(
                "the hull would build {} faces instead of {}",
                hull.report.faces, self.faces
            ));
        }
        if hull.report.warnings.len() > self.warnings {
            let new = hull
                .report
                .warnings
                .last()
                .map(|w| w.message.clone())
                .unwrap_or_default();
            return Err(format!("the hull would gain a warning ({new})"));
        }
        let now = station_inflections(network, tolerance);
        for ((c, before), after) in network.curves().iter().zip(&self.inflections).zip(now) {
            if let (Some(b), Some(a)) = (before, after) {
                if a > *b {
                    return Err(format!(
                        "station '{}' would gain an inflection ({b} → {a})",
                        c.name
                    ));
                }
            }
        }
        Ok(())
    }
}
