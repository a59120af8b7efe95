//! Flat runs of a section's points: the flat of bottom of a ship's station is a straight line
//! in the base plane, and the section leaves it tangentially into the bilge; a station's top
//! runs straight up the flat of side, and a waterline runs along the flat of side through the
//! parallel middle body and leaves it tangentially at both ends.
//!
//! Fitted as one smooth spline, such a section rounds the curvature jump where the flat ends
//! (zero curvature, then the bilge radius): the flat sags or rises by millimetres and the
//! section's tangent there tilts by degrees, and every patch along the flat of bottom inherits
//! the tilt as a cross-derivative that bulges its interior by centimetres (KCS and KVLCC2:
//! 33 and 37 mm). Seed 002 §5 gives the flat of bottom curve a tangent attribute for this:
//! the curves attached to it enter it tangentially. Here each run of points in a flat plane
//! becomes a straight piece in the plane (its points moved onto the line, within the plane's
//! noise), and the pieces beside it are fitted with their end tangents fixed along that line:
//! they meet G1 (knots of multiplicity `degree` with collinear control points), so the flat is
//! exactly flat and the section leaves it with the flat's tangent.

use glam::DVec3;

use super::error::FairError;

/// A plane that stretches of a curve's points may run in: the flat of bottom or of side of the
/// hull the curve is a section of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatPlane {
    /// Normal of the plane (made unit by the fit, with the offset).
    pub normal: DVec3,
    /// The plane is `normal · p = offset`.
    pub offset: f64,
    /// How far (m) a run's ends (where the curve leaves the flat) may be from the plane and
    /// still be on the flat.
    pub tolerance: f64,
    /// How far (m) a point inside the run may be from the plane, and from the straight line of
    /// the run, as the data's noise: the run goes on over such points as long as a later one is
    /// back within `tolerance`. Not less than `tolerance` (a smaller value counts as
    /// `tolerance`). Offsets measured to the nearest millimetre or two straddle the base plane
    /// so (KVLCC2's station at x = 312.05 m: −2 mm, then +1 mm), where a bilge leaves it on one
    /// side only.
    pub noise: f64,
}

/// Shortest flat run kept straight (m, between the run's ends): a shorter one is a point of
/// tangency rather than a flat.
pub const MIN_FLAT_RUN: f64 = 0.3;

/// Fewest points of a flat run between the ends of a curve: two are a crossing of the plane
/// (KVLCC2's station 15 crosses the flat of side at z = 17 m, a node and a data point there).
const MIN_MIDDLE_RUN_POINTS: usize = 3;

/// A flat run found in the points: a straight stretch in one of the curve's flat planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FlatRun {
    /// Index of the plane (in [`FairOptions::flats`](super::FairOptions::flats)).
    pub plane: usize,
    /// Index of the run's first point.
    pub first: usize,
    /// Index of the run's last point.
    pub last: usize,
    /// Unit direction of the run's line, from its first point to its last; `None` for a run
    /// that curves in the plane (a deck edge rising with the sheer along the flat of side),
    /// whose points are moved onto the plane rather than a line.
    pub direction: Option<DVec3>,
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

    /// Every flat run of `pts` in this plane (`plane` is its index among the curve's planes),
    /// in order: stretches of consecutive points within the noise of the plane and of the
    /// straight line through the stretch's ends, both ends within the tolerance of the plane,
    /// at least [`MIN_FLAT_RUN`] long; of a stretch that curves in the plane, its longer
    /// straight end (`straight_end`). A run may be at either end of the points (a station's
    /// flat of bottom or side) or between them (a waterline along the flat of side).
    pub(crate) fn runs(&self, pts: &[DVec3], plane: usize) -> Vec<FlatRun> {
        let m = pts.len();
        let mut runs = Vec::new();
        let mut i = 0;
        while i < m {
            if !self.holds(pts[i]) {
                i += 1;
                continue;
            }
            // The last point within the tolerance before the first one beyond the noise.
            let (first, mut last, mut j) = (i, i, i);
            while j + 1 < m && self.within_noise(pts[j + 1]) {
                j += 1;
                if self.holds(pts[j]) {
                    last = j;
                }
            }
            match self.run_between(pts, plane, first, last) {
                Some(run) => runs.push(run),
                None => runs.extend(self.curved(pts, plane, first, last)),
            }
            i = j + 1;
        }
        runs
    }

    /// The runs of a stretch from `first` to `last` in the plane that curves in it: its
    /// straight end (`straight_end`) and the rest of it as a run that curves in the plane, or
    /// the whole stretch as one such run, in order along the points. KVLCC2's deck edge from
    /// x = 79 m to 131 m, fitted smooth between a plain piece and its straight end, bowed
    /// 2.3 mm off the flat of side; on the plane its curve stays there.
    fn curved(&self, pts: &[DVec3], plane: usize, first: usize, last: usize) -> Vec<FlatRun> {
        let planar = |a: usize, b: usize| {
            (b > a)
                .then(|| self.long_run(pts, plane, a, b))
                .flatten()
                .map(|r| FlatRun {
                    direction: None,
                    ..r
                })
        };
        match self.straight_end(pts, plane, first, last) {
            Some(s) => [planar(first, s.first), Some(s), planar(s.last, last)]
                .into_iter()
                .flatten()
                .collect(),
            None => planar(first, last).into_iter().collect(),
        }
    }

    /// Of a stretch from `first` to `last` in the plane that curves in it, the longer of its
    /// straight runs from `first` and to `last` (each grown a point at a time while it stays
    /// straight, and ending on a point within the tolerance of the plane), when one is long
    /// enough: KVLCC2's deck edge runs along the flat of side from x = 79 m, rising with the
    /// sheer to z = 26 m at x = 131 m and straight from there to x = 237 m; as no straight run
    /// at all, it bowed 2.4 mm off the flat at x = 231 m. The curved rest is fitted smooth,
    /// leaving the run with its tangent. Growing stops where the run first bends, so the
    /// search costs the run's length squared at most, not the stretch's cubed.
    fn straight_end(
        &self,
        pts: &[DVec3],
        plane: usize,
        first: usize,
        last: usize,
    ) -> Option<FlatRun> {
        // Grown from `from` towards each of `ends` in turn: the run between them while it
        // stays straight, kept where the end is within the tolerance and the run long enough.
        let grow = |from: usize, ends: &mut dyn Iterator<Item = usize>| {
            let mut best = None;
            for end in ends {
                let (a, b) = (from.min(end), from.max(end));
                if !self.straight(pts, a, b) {
                    break;
                }
                if self.holds(pts[end]) {
                    best = self.long_run(pts, plane, a, b).or(best);
                }
            }
            best
        };
        let from_first = grow(first, &mut (first + 1..last));
        let to_last = grow(last, &mut (first + 1..last).rev());
        let length = |r: &FlatRun| pts[r.first].distance(pts[r.last]);
        [from_first, to_last]
            .into_iter()
            .flatten()
            .max_by(|a, b| length(a).total_cmp(&length(b)))
    }

    /// Whether the points `first..=last`, moved onto the plane, lie within the noise of the
    /// straight line through the two ends.
    fn straight(&self, pts: &[DVec3], first: usize, last: usize) -> bool {
        let (a, b) = (self.project(pts[first]), self.project(pts[last]));
        let Some(line) = (b - a).try_normalize() else {
            return true;
        };
        (first..=last).all(|i| {
            let q = self.project(pts[i]) - a;
            (q - line * q.dot(line)).length() <= self.noise
        })
    }

    /// The run from `first` to `last` when it is long and straight enough.
    fn run_between(
        &self,
        pts: &[DVec3],
        plane: usize,
        first: usize,
        last: usize,
    ) -> Option<FlatRun> {
        self.long_run(pts, plane, first, last)
            .filter(|_| self.straight(pts, first, last))
    }

    /// The run from `first` to `last`, straight or not, when it is at least [`MIN_FLAT_RUN`]
    /// long, its direction that of its chord in the plane.
    fn long_run(&self, pts: &[DVec3], plane: usize, first: usize, last: usize) -> Option<FlatRun> {
        let chord = self.project(pts[last]) - self.project(pts[first]);
        (last != first && chord.length() >= MIN_FLAT_RUN).then(|| FlatRun {
            plane,
            first,
            last,
            direction: Some(chord.normalize()),
        })
    }
}

/// The flat runs of `pts` in `planes` that a fit of degree `degree` can keep straight, in
/// order along the points: every run in every plane, but one that overlaps an earlier one, one
/// that would leave fewer than `degree + 1` points for the smooth piece before or after it (it
/// needs them to leave the flat with the flat's tangent), and one between the ends of fewer
/// than [`MIN_MIDDLE_RUN_POINTS`] points. Two runs in one plane keep the wave of the data
/// between them (KCS's wl_z10.80 dips 6 mm off its flat of side at x = 48–52 m): the piece
/// between leaves one flat and enters the next with the flat's tangent. A degree-1 fit is a
/// polyline through its points (no tangent to carry off a flat): none. A degree-2 piece can
/// take one fixed tangent only: one run, at an end of the points. A run that curves in the
/// plane needs `degree + 2` points (its own piece, a tangent fixed at each joint); it may end
/// where a straight run in its plane starts, or start where one ends.
pub(crate) fn runs_of(planes: &[FlatPlane], pts: &[DVec3], degree: usize) -> Vec<FlatRun> {
    let m = pts.len();
    if degree < 2 || m == 0 {
        return Vec::new();
    }
    let mut all: Vec<FlatRun> = planes
        .iter()
        .enumerate()
        .flat_map(|(i, plane)| plane.runs(pts, i))
        .collect();
    all.sort_by_key(|r| (r.first, std::cmp::Reverse(r.last)));
    let mut kept: Vec<FlatRun> = Vec::new();
    for run in all {
        // A run that curves in the plane needs the points of a smooth piece of its own (with
        // a tangent fixed at each joint); it may share a joint with a straight run in its plane.
        if run.direction.is_none() && run.last - run.first < degree + 1 {
            continue;
        }
        let before = match kept.last() {
            Some(prev) if run.first == prev.last => {
                prev.plane == run.plane && (prev.direction.is_none() != run.direction.is_none())
            }
            Some(prev) => run.first > prev.last && run.first - prev.last >= degree,
            None => run.first == 0 || run.first >= degree,
        };
        let after = run.last + 1 == m || m - 1 - run.last >= degree;
        let at_end = run.first == 0 || run.last + 1 == m;
        // Between the ends, two points in the plane are where the curve crosses it.
        let enough = at_end || run.last - run.first + 1 >= MIN_MIDDLE_RUN_POINTS;
        if before && after && enough && (degree >= 3 || (at_end && kept.is_empty())) {
            kept.push(run);
        }
    }
    if degree == 2 {
        kept.truncate(1);
    }
    kept
}

impl FlatRun {
    /// The run's points in `pts` moved onto its line in the plane (onto the plane, for a run
    /// that curves in it), the others as they are.
    pub(crate) fn straighten(&self, pts: &mut [DVec3], plane: &FlatPlane) {
        let a = plane.project(pts[self.first]);
        for p in &mut pts[self.first..=self.last] {
            let q = plane.project(*p);
            *p = match self.direction {
                Some(d) => a + d * (q - a).dot(d),
                None => q,
            };
        }
    }

    /// Whether `index` is one of the run's ends.
    pub(crate) fn ends_at(&self, index: usize) -> bool {
        index == self.first || index == self.last
    }
}
