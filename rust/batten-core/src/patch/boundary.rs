//! The topology-independent face description (sides made of designer-curve segments) and its
//! validated, evaluation-ready form.
//!
//! A face is a loop of N ≥ 3 sides, counter-clockwise seen from outside (the H-rep paper's
//! edge loops, §3.1). A side is one or more [`SideSegment`]s end to end: a composite side arises
//! where a T-joint splits it (paper §5.2). Each side is parameterised by `s ∈ [0, 1]` from its
//! start corner to its end corner; a composite side gives each segment an interval of `s` in
//! proportion to its arc length (or its chord, [`SideParam`]), and within a segment `s` runs
//! through the segment's [`SpeedMap`] onto the curve's own parameter (at nearly uniform speed
//! along the curve, whatever its knots), so the side is exactly the designer curve.

use std::sync::{Arc, OnceLock};

use glam::DVec3;

use super::error::PatchError;
use super::speed::SpeedMap;
use crate::curve::{BezierDecomposition, CurveError, NurbsCurve};
use crate::tolerance::Tolerance;

/// How far a segment's parameter may lie outside its curve's domain, relative to the domain's
/// length (at least 1): rounding in parameters computed from the domain's ends, not a distance
/// on the curve.
const PARAMETER_SLACK: f64 = 1e-12;

/// A parameter interval `[t0, t1]` of one designer curve, traversed from `t0` to `t1`
/// (`t0 > t1` traverses the curve backwards).
///
/// `start` and `end` are optional node positions supplied by the topology (the network node
/// the segment starts/ends at). When given they are the exact corner positions the patch
/// interpolates and the tessellation emits, so every face meeting at a node gets the same,
/// bitwise identical vertex there; when absent the curve's own end points are used (and two
/// segments meeting within tolerance are joined at their midpoint).
#[derive(Clone, Debug, PartialEq)]
pub struct SideSegment {
    /// The designer curve.
    pub curve: NurbsCurve,
    /// Parameter where the segment starts (in the face's traversal direction).
    pub t0: f64,
    /// Parameter where the segment ends.
    pub t1: f64,
    /// The designer curve's name, used in error messages (may be empty).
    pub name: String,
    /// Node position at `t0`, if the topology knows it.
    pub start: Option<DVec3>,
    /// Node position at `t1`, if the topology knows it.
    pub end: Option<DVec3>,
    /// The segment's measure, where it was taken beforehand ([`SideSegment::measured`]).
    pub(crate) measure: Measure,
}

/// What preparing a segment measures of its curve between its ends, in increasing curve
/// parameter (so the same whichever way a face runs along it): the arc length, the curve's
/// Bézier pieces and the segment's [`SpeedMap`], with the curve itself. The hull measures
/// each edge once, and the two faces along it take the measure instead of each measuring it
/// again; the prepared segments of both share it.
#[derive(Debug)]
pub(crate) struct SegmentMeasure {
    /// The curve measured.
    curve: NurbsCurve,
    /// The interval measured, `lo ≤ hi`.
    lo: f64,
    hi: f64,
    /// The arc length's relative accuracy ([`Tolerance::side_length_accuracy`]).
    accuracy: f64,
    length: f64,
    fast: BezierDecomposition,
    speed: SpeedMap,
    /// The curve at [`EVEN_SAMPLES`] + 1 even steps of the segment's fraction, taken by the
    /// first face that asks ([`PreparedSegment::point_d1_even`]) and read by the other.
    even: OnceLock<Vec<EvenSample>>,
}

/// Even steps of a segment's fraction at which [`PreparedSegment::point_d1_even`] keeps the
/// curve's points: the steps at which a patch measures how its side turns (the ribbon's
/// transport). A power of two, so that a step counted from either end is the same number.
pub(crate) const EVEN_SAMPLES: usize = 64;

/// The curve at one even step `u / EVEN_SAMPLES` of a segment's fraction in increasing curve
/// parameter: its point, its derivative d/dt, the slope dτ/dλ of the segment's speed map
/// there and the curve parameter.
#[derive(Clone, Copy, Debug)]
struct EvenSample {
    point: DVec3,
    d1: DVec3,
    slope: f64,
    t: f64,
}

impl SegmentMeasure {
    /// The measure of `curve` on `[lo, hi]` (`lo ≤ hi`) at `accuracy`: the arc length 0 where
    /// the interval is empty; the curve's error where its length cannot be measured.
    fn take(
        curve: &NurbsCurve,
        lo: f64,
        hi: f64,
        accuracy: f64,
    ) -> Result<SegmentMeasure, CurveError> {
        let length = if hi > lo {
            curve.arc_length_between(lo, hi, accuracy)?
        } else {
            0.0
        };
        let fast = curve.bezier_decomposition();
        let speed = SpeedMap::of_curve(&fast, lo, hi);
        Ok(SegmentMeasure {
            curve: curve.clone(),
            lo,
            hi,
            accuracy,
            length,
            fast,
            speed,
            even: OnceLock::new(),
        })
    }

    /// Whether this measures `curve` on `[lo, hi]` at `accuracy`, bit for bit.
    fn is_of(&self, curve: &NurbsCurve, lo: f64, hi: f64, accuracy: f64) -> bool {
        self.lo.to_bits() == lo.to_bits()
            && self.hi.to_bits() == hi.to_bits()
            && self.accuracy.to_bits() == accuracy.to_bits()
            && self.curve == *curve
    }
}

/// A segment's measure taken beforehand, if it was ([`SideSegment::measured`]). Equal to any
/// other: it is what the segment's own fields give, so it leaves the segment's meaning as it
/// is.
#[derive(Clone, Debug, Default)]
pub(crate) struct Measure(Option<Arc<SegmentMeasure>>);

impl PartialEq for Measure {
    fn eq(&self, _: &Measure) -> bool {
        true
    }
}

impl SideSegment {
    /// A segment of `curve` from `t0` to `t1`, unnamed and without node positions.
    pub fn new(curve: NurbsCurve, t0: f64, t1: f64) -> SideSegment {
        SideSegment {
            curve,
            t0,
            t1,
            name: String::new(),
            start: None,
            end: None,
            measure: Measure::default(),
        }
    }

    /// The same segment with its curve measured between its ends at `tol`'s side-length
    /// accuracy (the arc length, the Bézier pieces and the speed map [`prepare_boundary`]
    /// needs), so that every patch with this segment on a side takes the measure instead of
    /// taking it again; a segment whose curve or parameters are changed afterwards is
    /// measured afresh. Where the arc length cannot be measured, nothing is kept (the patch
    /// reports why).
    pub(crate) fn measured(mut self, tol: Tolerance) -> SideSegment {
        let (lo, hi) = (self.t0.min(self.t1), self.t0.max(self.t1));
        let accuracy = tol.side_length_accuracy();
        self.measure = Measure(
            (hi > lo)
                .then(|| SegmentMeasure::take(&self.curve, lo, hi, accuracy).ok())
                .flatten()
                .map(Arc::new),
        );
        self
    }

    /// The measure of this segment at `accuracy`: the one taken beforehand where it is of
    /// this segment, else taken now.
    fn measure_at(&self, accuracy: f64) -> Result<Arc<SegmentMeasure>, PatchError> {
        let (lo, hi) = (self.t0.min(self.t1), self.t0.max(self.t1));
        match &self.measure.0 {
            Some(m) if m.is_of(&self.curve, lo, hi, accuracy) => Ok(Arc::clone(m)),
            _ => SegmentMeasure::take(&self.curve, lo, hi, accuracy)
                .map(Arc::new)
                .map_err(|source| PatchError::Curve {
                    curve: self.label(),
                    source,
                }),
        }
    }

    /// The whole curve, in its own parameter direction.
    pub fn whole(curve: NurbsCurve) -> SideSegment {
        let (a, b) = curve.domain();
        SideSegment::new(curve, a, b)
    }

    /// The same segment with a curve name for error messages.
    pub fn named(mut self, name: impl Into<String>) -> SideSegment {
        self.name = name.into();
        self
    }

    /// The same segment with node positions at its two ends.
    pub fn with_nodes(mut self, start: DVec3, end: DVec3) -> SideSegment {
        self.start = Some(start);
        self.end = Some(end);
        self
    }

    /// The same segment traversed the other way (node positions swapped).
    pub fn reversed(&self) -> SideSegment {
        SideSegment {
            curve: self.curve.clone(),
            t0: self.t1,
            t1: self.t0,
            name: self.name.clone(),
            start: self.end,
            end: self.start,
            measure: self.measure.clone(),
        }
    }

    fn label(&self) -> String {
        if self.name.is_empty() {
            "<unnamed>".to_string()
        } else {
            self.name.clone()
        }
    }
}

/// One side of a face: segments end to end, from the side's start corner to its end corner.
#[derive(Clone, Debug, PartialEq)]
pub struct Side {
    /// The segments in traversal order.
    pub segments: Vec<SideSegment>,
}

impl Side {
    /// A side made of the given segments.
    pub fn new(segments: Vec<SideSegment>) -> Side {
        Side { segments }
    }

    /// A side made of one segment.
    pub fn single(segment: SideSegment) -> Side {
        Side {
            segments: vec![segment],
        }
    }

    /// The same side traversed the other way, as the neighbouring face sees it.
    pub fn reversed(&self) -> Side {
        Side {
            segments: self.segments.iter().rev().map(|s| s.reversed()).collect(),
        }
    }

    fn curve_names(&self) -> String {
        let names: Vec<String> = self.segments.iter().map(|s| s.label()).collect();
        names.join(", ")
    }
}

/// A face's boundary: N ≥ 3 sides, counter-clockwise seen from outside, side `i` ending where
/// side `i + 1` starts (corner `i + 1`; corner `i` is the start of side `i`).
#[derive(Clone, Debug, PartialEq)]
pub struct FaceBoundary {
    /// The sides in counter-clockwise order.
    pub sides: Vec<Side>,
}

impl FaceBoundary {
    /// A boundary from its sides.
    pub fn new(sides: Vec<Side>) -> FaceBoundary {
        FaceBoundary { sides }
    }
}

/// How a composite side divides its parameter `s ∈ [0, 1]` among its segments.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SideParam {
    /// In proportion to the segments' arc lengths (the default: the patch parameter then runs
    /// at roughly uniform speed along the side).
    #[default]
    ArcLength,
    /// In proportion to the segments' chords (cheaper; close to arc length for flat segments).
    Chord,
}

/// One segment ready for evaluation: traversal parameters and the linear end corrections that
/// make consecutive segments and sides meet exactly at the resolved node positions.
#[derive(Clone, Debug)]
pub(crate) struct PreparedSegment {
    /// The curve, its Bézier pieces (for fast point-and-derivative evaluation) and the
    /// segment's fraction λ onto its parameter (in increasing curve parameter): shared with
    /// the other faces along the segment.
    measure: Arc<SegmentMeasure>,
    /// Curve parameter at the segment start (traversal order).
    pub(crate) ta: f64,
    /// Curve parameter at the segment end.
    pub(crate) tb: f64,
    /// Resolved start point minus the curve's start point.
    pub(crate) d0: DVec3,
    /// Resolved end point minus the curve's end point.
    pub(crate) d1: DVec3,
    /// Resolved start point (node position).
    pub(crate) p0: DVec3,
}

impl PreparedSegment {
    /// The designer curve.
    #[inline]
    pub(crate) fn curve(&self) -> &NurbsCurve {
        &self.measure.curve
    }

    /// The curve's Bézier pieces.
    #[inline]
    pub(crate) fn fast(&self) -> &BezierDecomposition {
        &self.measure.fast
    }

    /// The segment's fraction λ onto its curve's parameter.
    #[inline]
    fn speed(&self) -> &SpeedMap {
        &self.measure.speed
    }

    /// The segment's curve parameter interval `(lo, hi)`, `lo ≤ hi`.
    #[inline]
    fn interval(&self) -> (f64, f64) {
        if self.ta <= self.tb {
            (self.ta, self.tb)
        } else {
            (self.tb, self.ta)
        }
    }

    /// The curve parameter at the segment's fraction `lam` (clamped to [0, 1]; exactly `ta`
    /// and `tb` at its ends) and dt/dλ there (at a knot, on the side after it in the curve's
    /// parameter, except at the segment's far end in the curve's parameter: always inside the
    /// segment).
    #[inline]
    pub(crate) fn parameter(&self, lam: f64) -> (f64, f64) {
        let up = self.ta <= self.tb;
        let (tau, d) = self.speed().tau(if up { lam } else { 1.0 - lam });
        (self.at_tau(tau), d * (self.tb - self.ta))
    }

    /// The curve parameter at fraction `tau` of the interval in increasing curve parameter:
    /// exactly its ends at and past 0 and 1.
    #[inline]
    fn at_tau(&self, tau: f64) -> f64 {
        let (lo, hi) = self.interval();
        if tau >= 1.0 {
            hi
        } else if tau <= 0.0 {
            lo
        } else {
            lo + tau * (hi - lo)
        }
    }

    /// C(t) and dC/dλ at the segment's fraction `lam`, with the curve parameter `t` there: at a
    /// knot, of the curve's piece after it (before it at the segment's far end in the curve's
    /// parameter), so a segment that ends on a knot takes its end tangent from its own piece,
    /// as the map takes its slope from its own interval.
    #[inline]
    pub(crate) fn point_d1(&self, lam: f64) -> (DVec3, DVec3, f64) {
        let (t, dt) = self.parameter(lam);
        let (c, d1) = self.curve_d1(t);
        (c, d1 * dt, t)
    }

    /// C(t) and dC/dt at curve parameter `t` of the segment, from the segment's own piece at
    /// a knot (see [`PreparedSegment::point_d1`]).
    #[inline]
    fn curve_d1(&self, t: f64) -> (DVec3, DVec3) {
        let piece = self.fast().piece_at(t, t < self.interval().1);
        self.fast().point_d1_in(piece, t)
    }

    /// [`PreparedSegment::point_d1`] at `lam = j / EVEN_SAMPLES`, bit for bit, from the
    /// curve's points at those steps: taken once per segment measure, so the two faces along
    /// an edge evaluate its curve there once between them.
    #[inline]
    pub(crate) fn point_d1_even(&self, j: usize) -> (DVec3, DVec3, f64) {
        let n = EVEN_SAMPLES;
        let even = self.measure.even.get_or_init(|| {
            (0..=n)
                .map(|u| {
                    let (tau, slope) = self.speed().tau(u as f64 / n as f64);
                    let t = self.at_tau(tau);
                    let (point, d1) = self.curve_d1(t);
                    EvenSample {
                        point,
                        d1,
                        slope,
                        t,
                    }
                })
                .collect()
        });
        // Run down in the curve's parameter, step j is step n − j up: `1 − j/n` is exact.
        let e = even[if self.ta <= self.tb { j } else { n - j }];
        (e.point, e.d1 * (e.slope * (self.tb - self.ta)), e.t)
    }

    /// dt/dλ at curve parameter `t` of the segment, on the side after `t` in the curve's
    /// parameter (`after_in_t`) or before it.
    pub(crate) fn parameter_slope(&self, t: f64, after_in_t: bool) -> f64 {
        let (lo, hi) = self.interval();
        let lam = self.speed().lambda((t - lo) / (hi - lo));
        self.speed().slope(lam, after_in_t) * (self.tb - self.ta)
    }

    /// The segment's fraction λ at curve parameter `t` (the inverse of
    /// [`PreparedSegment::parameter`]).
    pub(crate) fn fraction(&self, t: f64) -> f64 {
        let (lo, hi) = self.interval();
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return 0.0;
        }
        let lam = self.speed().lambda((t - lo) / (hi - lo));
        if self.ta <= self.tb {
            lam
        } else {
            1.0 - lam
        }
    }

    /// The curve parameter of tessellation sample `j` of `r` in the curve's increasing
    /// parameter, ends exact: the one formula every face uses, so a shared segment's samples
    /// are bitwise equal whichever way the faces run along it.
    pub(crate) fn canonical_sample(&self, r: usize, j: usize) -> f64 {
        match j {
            0 => self.at_tau(0.0),
            j if j >= r => self.at_tau(1.0),
            j => self.at_tau(self.speed().tau(j as f64 / r as f64).0),
        }
    }
}

/// A validated side: segments with corrections and the break parameters `U_0 = 0 < … < U_m = 1`.
#[derive(Clone, Debug)]
pub(crate) struct PreparedSide {
    pub(crate) segs: Vec<PreparedSegment>,
    pub(crate) breaks: Vec<f64>,
    /// Resolved end point of the side (start of the next side).
    pub(crate) end: DVec3,
}

impl PreparedSide {
    /// Segment index and local parameter λ ∈ [0, 1] of side parameter `s` (clamped to [0, 1]).
    #[inline]
    pub(crate) fn locate(&self, s: f64) -> (usize, f64) {
        let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
        let m = self.segs.len();
        let mut k = 0;
        while k + 1 < m && s > self.breaks[k + 1] {
            k += 1;
        }
        let (a, b) = (self.breaks[k], self.breaks[k + 1]);
        let lam = ((s - a) / (b - a)).clamp(0.0, 1.0);
        (k, lam)
    }

    /// Position and derivative d/ds of the (corrected) side at `s`.
    #[inline]
    pub(crate) fn eval(&self, s: f64) -> (DVec3, DVec3) {
        let (p, dp, _, _) = self.eval_located(s);
        (p, dp)
    }

    /// Position and derivative d/ds at `s`, with the segment index and curve parameter there.
    ///
    /// At a knot of the curve the derivative is the piece's after it, except at the segment's
    /// end of larger parameter, where it is the piece's before it: always the segment's own
    /// piece, so a side that ends on a knot does not take its end tangent's length from the
    /// next piece of its curve (one unit of parameter per piece, whatever their lengths, in a
    /// Bézier-segmented curve).
    #[inline]
    pub(crate) fn eval_located(&self, s: f64) -> (DVec3, DVec3, usize, f64) {
        let (k, lam) = self.locate(s);
        self.corrected(k, lam, self.segs[k].point_d1(lam))
    }

    /// The side's point and d/ds on segment `k` at its fraction `lam`, from the segment's
    /// curve point, dC/dλ and curve parameter there: with the segment's end corrections, and
    /// the segment's share of the side's parameter.
    #[inline]
    fn corrected(
        &self,
        k: usize,
        lam: f64,
        (c, d1, t): (DVec3, DVec3, f64),
    ) -> (DVec3, DVec3, usize, f64) {
        let seg = &self.segs[k];
        let du = self.breaks[k + 1] - self.breaks[k];
        let p = c + seg.d0 * (1.0 - lam) + seg.d1 * lam;
        let dp = (d1 + (seg.d1 - seg.d0)) / du;
        (p, dp, k, t)
    }

    /// [`PreparedSide::eval_located`] at `s = j / EVEN_SAMPLES`, bit for bit: on a side of one
    /// segment from its curve's points kept at those steps
    /// ([`PreparedSegment::point_d1_even`]).
    #[inline]
    pub(crate) fn eval_located_even(&self, j: usize) -> (DVec3, DVec3, usize, f64) {
        let s = j as f64 / EVEN_SAMPLES as f64;
        if self.segs.len() != 1 || self.breaks[0] != 0.0 || self.breaks[1] != 1.0 {
            return self.eval_located(s);
        }
        // One segment over the whole side: its fraction is `s`.
        self.corrected(0, s, self.segs[0].point_d1_even(j))
    }

    /// Position only.
    #[inline]
    pub(crate) fn point(&self, s: f64) -> DVec3 {
        let (k, lam) = self.locate(s);
        let seg = &self.segs[k];
        let t = seg.parameter(lam).0;
        seg.curve().point(t) + seg.d0 * (1.0 - lam) + seg.d1 * lam
    }

    /// Resolved start point (corner).
    pub(crate) fn start(&self) -> DVec3 {
        self.segs[0].p0
    }
}

/// A segment's curve end points (traversal order), arc length and chord, measured once while
/// its parameters are validated.
#[derive(Clone, Copy, Debug)]
struct MeasuredSegment {
    /// The curve's point at `t0`.
    start: DVec3,
    /// The curve's point at `t1`.
    end: DVec3,
    /// Arc length between `t0` and `t1`.
    length: f64,
    /// Distance from `start` to `end`.
    chord: f64,
}

/// Validate a face boundary and resolve its corners and junctions (see [`SideSegment`]).
pub(crate) fn prepare_boundary(
    boundary: &FaceBoundary,
    param: SideParam,
    tol: Tolerance,
    max_sides: usize,
) -> Result<Vec<PreparedSide>, PatchError> {
    let n = boundary.sides.len();
    if n < 3 {
        return Err(PatchError::TooFewSides { sides: n });
    }
    if n > max_sides {
        return Err(PatchError::TooManySides {
            sides: n,
            max: max_sides,
        });
    }
    let limit = tol.near_miss();
    // Raw end points and lengths, after parameter validation, and each segment's measure.
    let mut raw: Vec<Vec<MeasuredSegment>> = Vec::with_capacity(n);
    let mut measures: Vec<Vec<Arc<SegmentMeasure>>> = Vec::with_capacity(n);
    for (si, side) in boundary.sides.iter().enumerate() {
        if side.segments.is_empty() {
            return Err(PatchError::EmptySide { side: si });
        }
        let mut segs = Vec::with_capacity(side.segments.len());
        let mut side_measures = Vec::with_capacity(side.segments.len());
        let mut total = 0.0;
        for (ki, seg) in side.segments.iter().enumerate() {
            let (a, b) = seg.curve.domain();
            for t in [seg.t0, seg.t1] {
                let slack = PARAMETER_SLACK * (b - a).abs().max(1.0);
                if !t.is_finite() || t < a - slack || t > b + slack {
                    return Err(PatchError::BadParameter {
                        side: si,
                        segment: ki,
                        curve: seg.label(),
                        t,
                        start: a,
                        end: b,
                    });
                }
            }
            for (p, which) in [(seg.start, "start"), (seg.end, "end")] {
                if let Some(p) = p {
                    if !p.is_finite() {
                        return Err(PatchError::BadRibbonNode {
                            curve: seg.label(),
                            t: if which == "start" { seg.t0 } else { seg.t1 },
                            reason: format!("{which} node position is not finite"),
                        });
                    }
                }
            }
            let measure = seg.measure_at(tol.side_length_accuracy())?;
            let length = measure.length;
            if length.is_nan() || length < tol.get() {
                return Err(PatchError::ZeroLengthSide {
                    side: si,
                    curves: seg.label(),
                    length,
                    tolerance: tol.get(),
                });
            }
            total += length;
            let p0 = seg.curve.point(seg.t0);
            let p1 = seg.curve.point(seg.t1);
            segs.push(MeasuredSegment {
                start: p0,
                end: p1,
                length,
                chord: (p1 - p0).length(),
            });
            side_measures.push(measure);
        }
        if total.is_nan() || total < tol.get() {
            return Err(PatchError::ZeroLengthSide {
                side: si,
                curves: side.curve_names(),
                length: total,
                tolerance: tol.get(),
            });
        }
        raw.push(segs);
        measures.push(side_measures);
    }

    // Resolve the junction point between (side, segment) and the next segment (or next side).
    let resolve = |a: &SideSegment, a_end: DVec3, b: &SideSegment, b_start: DVec3| -> DVec3 {
        a.end.or(b.start).unwrap_or(if a_end == b_start {
            a_end
        } else {
            (a_end + b_start) * 0.5
        })
    };

    let mut out = Vec::with_capacity(n);
    for (si, side) in boundary.sides.iter().enumerate() {
        let m = side.segments.len();
        // Start point of each segment and end point of the last.
        let mut starts = Vec::with_capacity(m + 1);
        // Corner at the start of this side: junction with the previous side's last segment.
        let pi = (si + n - 1) % n;
        let prev_side = &boundary.sides[pi];
        let prev_seg = prev_side.segments.last().expect("sides are non-empty");
        let prev_end = raw[pi].last().expect("sides are non-empty").end;
        let first = &side.segments[0];
        let first_start = raw[si][0].start;
        let gap = (prev_end - first_start).length();
        let corner = resolve(prev_seg, prev_end, first, first_start);
        let worst = gap
            .max((corner - prev_end).length())
            .max((corner - first_start).length());
        if worst.is_nan() || worst > limit {
            return Err(PatchError::CornerGap {
                corner: si,
                prev: pi,
                next: si,
                prev_curves: prev_side.curve_names(),
                next_curves: side.curve_names(),
                gap: worst,
                limit,
            });
        }
        starts.push(corner);
        for k in 0..m - 1 {
            let (a, b) = (&side.segments[k], &side.segments[k + 1]);
            let (a_end, b_start) = (raw[si][k].end, raw[si][k + 1].start);
            let j = resolve(a, a_end, b, b_start);
            let worst = (a_end - b_start)
                .length()
                .max((j - a_end).length())
                .max((j - b_start).length());
            if worst.is_nan() || worst > limit {
                return Err(PatchError::SegmentGap {
                    side: si,
                    segment: k,
                    next: k + 1,
                    curve: a.label(),
                    next_curve: b.label(),
                    gap: worst,
                    limit,
                });
            }
            starts.push(j);
        }
        // End corner: resolved as the next side's start (same rule, same inputs).
        let ni = (si + 1) % n;
        let next_first = &boundary.sides[ni].segments[0];
        let last = side.segments.last().expect("sides are non-empty");
        let end = resolve(
            last,
            raw[si].last().expect("sides are non-empty").end,
            next_first,
            raw[ni][0].start,
        );
        starts.push(end);

        // Break parameters.
        let use_chord = param == SideParam::Chord && raw[si].iter().all(|r| r.chord >= tol.get());
        let weights: Vec<f64> = raw[si]
            .iter()
            .map(|r| if use_chord { r.chord } else { r.length })
            .collect();
        let total: f64 = weights.iter().sum();
        let mut breaks = Vec::with_capacity(m + 1);
        let mut acc = 0.0;
        breaks.push(0.0);
        for w in &weights[..m - 1] {
            acc += w;
            breaks.push(acc / total);
        }
        breaks.push(1.0);

        let segs = side
            .segments
            .iter()
            .enumerate()
            .map(|(k, seg)| PreparedSegment {
                measure: Arc::clone(&measures[si][k]),
                ta: seg.t0,
                tb: seg.t1,
                d0: starts[k] - raw[si][k].start,
                d1: starts[k + 1] - raw[si][k].end,
                p0: starts[k],
            })
            .collect();
        out.push(PreparedSide { segs, breaks, end });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A line along x through 0, 1 m and 10 m as two Bézier pieces (handles at thirds), one
    /// unit of parameter each, as a Bézier spline is read: 1 m per unit, then 9 m per unit.
    fn uneven_line() -> NurbsCurve {
        let x = |v: f64| DVec3::new(v, 0.0, 0.0);
        let co = [x(0.0), x(1.0), x(10.0)];
        let left = [co[0], x(2.0 / 3.0), x(7.0)];
        let right = [x(1.0 / 3.0), x(4.0), co[2]];
        NurbsCurve::from_bezier(&co, &left, &right, false).expect("a valid curve")
    }

    /// A triangle whose first side is `first`, closed by straight lines through (0.5, 1, 0).
    fn triangle(first: SideSegment) -> FaceBoundary {
        let (a, b) = (first.curve.point(first.t0), first.curve.point(first.t1));
        let apex = DVec3::new(0.5, 1.0, 0.0);
        let line = |p: DVec3, q: DVec3| {
            NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p, q], None).expect("a line")
        };
        FaceBoundary::new(vec![
            Side::single(first),
            Side::single(SideSegment::whole(line(b, apex))),
            Side::single(SideSegment::whole(line(apex, a))),
        ])
    }

    #[test]
    fn a_measured_segment_prepares_as_one_measured_afresh_and_a_changed_one_is_measured_again() {
        let c = uneven_line();
        let tol = Tolerance::DEFAULT;
        let prepared = |seg: SideSegment| {
            let sides = prepare_boundary(&triangle(seg), SideParam::ArcLength, tol, 8)
                .expect("a valid face");
            (0..=16)
                .map(|j| sides[0].eval(j as f64 / 16.0))
                .map(|(p, d)| [p.to_array(), d.to_array()].map(|v| v.map(f64::to_bits)))
                .collect::<Vec<_>>()
        };
        let plain = SideSegment::new(c.clone(), 0.25, 1.75);
        let measured = plain.clone().measured(tol);
        assert!(measured.measure.0.is_some(), "measured");
        assert_eq!(
            prepared(measured.clone()),
            prepared(plain.clone()),
            "bit for bit"
        );
        assert_eq!(
            prepared(measured.reversed()),
            prepared(plain.reversed()),
            "reversed, bit for bit"
        );
        // Cut short after measuring: the measure is of another interval and is not taken.
        let cut = SideSegment {
            t1: 1.5,
            ..measured.clone()
        };
        assert_eq!(prepared(cut), prepared(SideSegment::new(c, 0.25, 1.5)));
        assert_ne!(
            prepared(measured),
            prepared(SideSegment::new(uneven_line(), 0.25, 1.5))
        );
    }

    /// The even steps a measure keeps are the side's own points there bit for bit, with the
    /// segment run either way round, the measure shared by both (the two faces of an edge) or
    /// not, and on a side of two segments (which evaluates them as usual).
    #[test]
    fn the_even_steps_kept_on_a_measure_are_the_sides_points_either_way_round() {
        let tol = Tolerance::DEFAULT;
        let located = |sides: &[PreparedSide], j: usize| {
            let (p, d, k, t) = sides[0].eval_located(j as f64 / EVEN_SAMPLES as f64);
            (
                p.to_array().map(f64::to_bits),
                d.to_array().map(f64::to_bits),
                k,
                t.to_bits(),
            )
        };
        let even = |sides: &[PreparedSide], j: usize| {
            let (p, d, k, t) = sides[0].eval_located_even(j);
            (
                p.to_array().map(f64::to_bits),
                d.to_array().map(f64::to_bits),
                k,
                t.to_bits(),
            )
        };
        let measured = SideSegment::new(uneven_line(), 0.25, 1.75).measured(tol);
        for seg in [measured.clone(), measured.reversed(), measured] {
            let sides = prepare_boundary(&triangle(seg), SideParam::ArcLength, tol, 8)
                .expect("a valid face");
            for j in 0..=EVEN_SAMPLES {
                assert_eq!(even(&sides, j), located(&sides, j), "step {j}");
            }
        }
        // Two segments on one side: each step is evaluated where the side's breaks put it.
        let c = uneven_line();
        let x = |v: f64| DVec3::new(v, 0.0, 0.0);
        let line = |p: DVec3, q: DVec3| {
            NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p, q], None).expect("a line")
        };
        let apex = DVec3::new(0.5, 1.0, 0.0);
        let face = FaceBoundary::new(vec![
            Side::new(vec![
                SideSegment::new(c.clone(), 0.0, 1.0).measured(tol),
                SideSegment::new(c, 1.0, 2.0).measured(tol),
            ]),
            Side::single(SideSegment::whole(line(x(10.0), apex))),
            Side::single(SideSegment::whole(line(apex, x(0.0)))),
        ]);
        let sides = prepare_boundary(&face, SideParam::ArcLength, tol, 8).expect("a valid face");
        for j in 0..=EVEN_SAMPLES {
            assert_eq!(even(&sides, j), located(&sides, j), "composite, step {j}");
        }
    }

    #[test]
    fn a_side_ending_on_a_knot_takes_its_end_tangent_from_its_own_piece() {
        let c = uneven_line();
        // The first piece, 1 m long: d/ds is 1 m along the whole side, both ways round.
        for (t0, t1) in [(0.0, 1.0), (1.0, 0.0)] {
            let face = triangle(SideSegment::new(c.clone(), t0, t1));
            let sides = prepare_boundary(&face, SideParam::ArcLength, Tolerance::DEFAULT, 8)
                .expect("a valid face");
            for s in [0.0, 0.5, 1.0] {
                let speed = sides[0].eval(s).1.length();
                assert!(
                    (speed - 1.0).abs() < 1e-12,
                    "t {t0} → {t1}, s {s}: |d/ds| {speed} (9 is the next piece's)"
                );
            }
        }
    }
}
