//! A flat run at an end of a section's points: the flat of bottom of a ship's station is a
//! straight line in the base plane, and the section leaves it tangentially into the bilge.
//!
//! Fitted as one smooth spline, such a section rounds the curvature jump where the flat ends
//! (zero curvature, then the bilge radius): the flat sags or rises by millimetres and the
//! section's tangent there tilts by degrees, and every patch along the flat of bottom inherits
//! the tilt as a cross-derivative that bulges its interior by centimetres (KCS and KVLCC2:
//! 33 and 37 mm). Seed 002 §5 gives the flat of bottom curve a tangent attribute for this:
//! the curves attached to it enter it tangentially. Here the run of points in the plane at the
//! curve's end becomes a straight piece in the plane (its points moved onto the line, within
//! the plane's tolerance), and the rest of the curve is fitted with its end tangent fixed along
//! that line: the two pieces meet G1 (a knot of multiplicity `degree` with collinear control
//! points), so the flat is exactly flat and the section leaves it with the flat's tangent.

use glam::DVec3;

use super::error::FairError;

/// A plane that the points at one end of a curve may run in: the flat of bottom (or of side)
/// of the hull the curve is a section of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatPlane {
    /// Normal of the plane (made unit by the fit, with the offset).
    pub normal: DVec3,
    /// The plane is `normal · p = offset`.
    pub offset: f64,
    /// How far (m) the run's inner end (where the curve leaves the flat) may be from the plane
    /// and still be on the flat.
    pub tolerance: f64,
    /// How far (m) a point inside the run may be from the plane, and from the straight line of
    /// the run, as the data's noise: the run goes on over such points as long as a later one is
    /// back within `tolerance`. Not less than `tolerance` (a smaller value counts as
    /// `tolerance`). Offsets measured to the nearest millimetre or two straddle the base plane
    /// so (KVLCC2's station at x = 312.05 m: −2 mm, then +1 mm), where a bilge leaves it on one
    /// side only.
    pub noise: f64,
}

/// Shortest flat run kept straight (m, from the curve's end to where the run ends): a shorter
/// one is a point of tangency rather than a flat.
pub const MIN_FLAT_RUN: f64 = 0.3;

/// A flat run found at an end of the points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FlatRun {
    /// Whether the run is at the start of the points (else at their end).
    pub at_start: bool,
    /// Index of the run's inner end, where the curve leaves the flat.
    pub inner: usize,
    /// Unit direction of the run's line, along the curve's direction.
    pub direction: DVec3,
}

impl FlatPlane {
    /// The same plane with a unit normal; [`FairError::FlatPlane`] for a zero or non-finite
    /// normal, a non-finite offset or a tolerance that is not positive and finite.
    pub(crate) fn checked(&self) -> Result<FlatPlane, FairError> {
        let length = self.normal.length();
        let normal_ok = self.normal.is_finite() && length > 0.0 && length.is_finite();
        if !(normal_ok
            && self.offset.is_finite()
            && self.tolerance.is_finite()
            && self.tolerance > 0.0
            && self.noise.is_finite())
        {
            return Err(FairError::FlatPlane {
                normal: self.normal.to_array(),
                offset: self.offset,
                tolerance: self.tolerance,
                noise: self.noise,
            });
        }
        Ok(FlatPlane {
            normal: self.normal / length,
            offset: self.offset / length,
            tolerance: self.tolerance,
            noise: self.noise.max(self.tolerance),
        })
    }

    /// `p` moved onto the plane.
    pub(crate) fn project(&self, p: DVec3) -> DVec3 {
        p - self.normal * (self.normal.dot(p) - self.offset)
    }

    fn holds(&self, p: DVec3) -> bool {
        (self.normal.dot(p) - self.offset).abs() <= self.tolerance
    }

    fn within_noise(&self, p: DVec3) -> bool {
        (self.normal.dot(p) - self.offset).abs() <= self.noise
    }

    /// The flat run at the start of `pts` (else at its end): its points within the noise of
    /// the plane and of a straight line, its ends within the tolerance of the plane, at least
    /// [`MIN_FLAT_RUN`] long, and leaving at least `degree + 1` points for the rest of the
    /// curve; None when there is none.
    pub(crate) fn run(&self, pts: &[DVec3], degree: usize) -> Option<FlatRun> {
        let m = pts.len();
        let at = |i: usize, at_start: bool| if at_start { pts[i] } else { pts[m - 1 - i] };
        for at_start in [true, false] {
            // The last point within the tolerance before the first one beyond the noise.
            let mut k = 0;
            let mut i = 0;
            while i + 1 < m && self.within_noise(at(i + 1, at_start)) {
                i += 1;
                if self.holds(at(i, at_start)) {
                    k = i;
                }
            }
            if !self.holds(at(0, at_start)) || k == 0 || m - k < degree + 1 {
                continue;
            }
            let (a, b) = (self.project(at(0, at_start)), self.project(at(k, at_start)));
            let chord = b - a;
            if chord.length() < MIN_FLAT_RUN {
                continue;
            }
            let line = chord.normalize();
            let straight = (0..=k).all(|i| {
                let q = self.project(at(i, at_start)) - a;
                (q - line * q.dot(line)).length() <= self.noise
            });
            if !straight {
                continue;
            }
            return Some(FlatRun {
                at_start,
                inner: if at_start { k } else { m - 1 - k },
                direction: if at_start { line } else { -line },
            });
        }
        None
    }
}

impl FlatRun {
    /// The points with the run's points moved onto its line (in the plane); the others as
    /// they are.
    pub(crate) fn straightened(&self, pts: &[DVec3], plane: &FlatPlane) -> Vec<DVec3> {
        let m = pts.len();
        let outer = if self.at_start { 0 } else { m - 1 };
        let a = plane.project(pts[outer]);
        let line = self.direction;
        let mut out = pts.to_vec();
        let run = if self.at_start {
            0..=self.inner
        } else {
            self.inner..=m - 1
        };
        for i in run {
            let q = plane.project(pts[i]) - a;
            out[i] = a + line * q.dot(line);
        }
        out
    }
}
