//! The frame the fit works in: coordinates relative to the centre of the data's bounding box
//! and scaled by a power of two near their size, so that a fit does not depend on where the
//! points are (georeferenced data 10⁷ m from the origin fit as well as data at it) and every
//! length the fitter compares is of order one.

use glam::DVec3;

use super::error::FairError;
use super::metrics::{deviation, Deviation};
use super::piece::PieceFit;
use super::Smoothing;
use crate::curve::NurbsCurve;

/// Centre and scale of the local frame: `local = (world − centre) / scale`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    centre: DVec3,
    /// A power of two, so that scaling is exact and only the centring rounds.
    scale: f64,
}

impl Frame {
    /// The frame of `points` (finite, not all equal): the centre of their bounding box, and
    /// the power of two nearest below their largest extent.
    pub(crate) fn of(points: &[DVec3]) -> Frame {
        let (lo, hi) = points.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let centre = lo * 0.5 + hi * 0.5;
        let extent = (hi - lo).max_element();
        let scale = if extent > 0.0 && extent.is_finite() {
            2f64.powi(extent.log2().floor() as i32)
        } else {
            1.0
        };
        Frame { centre, scale }
    }

    /// A world point in the frame.
    pub(crate) fn to_local(self, p: DVec3) -> DVec3 {
        (p - self.centre) / self.scale
    }

    /// The smoothing in the frame's units (lengths over the scale, S over its square).
    pub(crate) fn smoothing(self, s: Smoothing) -> Smoothing {
        match s {
            Smoothing::MaxDeviation(t) => Smoothing::MaxDeviation(t / self.scale),
            Smoothing::Noise(sigma) => Smoothing::Noise(sigma / self.scale),
            Smoothing::Factor(f) => Smoothing::Factor(f / (self.scale * self.scale)),
        }
    }

    /// A length in the frame, in metres.
    pub(crate) fn length(self, l: f64) -> f64 {
        l * self.scale
    }

    /// The deviation (m) of the points `local` (in the frame) from the world curve `curve`,
    /// measured in the frame, where the closest-point search works at full precision.
    pub(crate) fn deviation(
        self,
        curve: &NurbsCurve,
        local: &[DVec3],
    ) -> Result<Deviation, FairError> {
        let knots: Vec<f64> = curve.knots().iter().map(|t| t / self.scale).collect();
        let coefs: Vec<DVec3> = curve
            .control_points()
            .iter()
            .map(|&p| self.to_local(p))
            .collect();
        let moved = NurbsCurve::try_new(curve.degree(), knots, coefs, None)?;
        let mut dev = deviation(&moved, local)?;
        dev.max *= self.scale;
        dev.rms *= self.scale;
        Ok(dev)
    }

    /// A piece fitted in the frame, in world coordinates: control points moved back, knots,
    /// sums of squares and fairness figures scaled, and the end control points set to the
    /// world points `ends` it interpolates (exactly, which the centring's rounding would not
    /// give).
    pub(crate) fn piece_to_world(
        self,
        mut fit: PieceFit,
        ends: (DVec3, DVec3),
    ) -> Result<PieceFit, FairError> {
        let s = self.scale;
        let sp = &mut fit.spline;
        for c in &mut sp.coefs {
            *c = self.centre + *c * s;
        }
        let last = sp.coefs.len() - 1;
        sp.coefs[0] = ends.0;
        sp.coefs[last] = ends.1;
        for t in &mut sp.knots {
            *t *= s;
        }
        sp.fp *= s * s;
        fit.s *= s * s;
        fit.curve = NurbsCurve::try_new(sp.degree, sp.knots.clone(), sp.coefs.clone(), None)?;
        if let Some(d) = &mut fit.deviation {
            d.max *= s;
            d.rms *= s;
        }
        if let Some(m) = &mut fit.metrics {
            m.fairness_energy /= s;
            m.max_curvature /= s;
        }
        fit.start = None;
        Ok(fit)
    }
}
