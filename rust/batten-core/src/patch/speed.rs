//! A side segment's own parameter: even along its curve, slower where the curve turns.
//!
//! A patch interpolates its sides at their parameters: the Gregory and Charrot–Gregory
//! patches blend points of different sides that share a parameter (H-rep paper §3.2.1,
//! eqs. 1–6), so a side that runs fast over one stretch and slowly over the next pulls the
//! inside of the patch towards the slow stretch. A designer curve's own parameter can be very
//! uneven: a curve read from a Bézier-segmented spline (Blender's, and the way a faired curve
//! is written) has one unit of parameter per piece whatever the piece's length, and KCS's
//! faired waterline at z = 9 m has pieces from 5 cm to 20 m. Its speed also jumps at every
//! joint (by the ratio of the pieces' handles, up to 12× there), which creases the inside of
//! the patch along the lines from the joints: the jogs in KCS's reflection lines at the stern.
//!
//! So each segment runs through a [`SpeedMap`]: λ ∈ [0, 1] along the segment, mapped to the
//! curve parameter so that λ grows with arc length plus [`TURN_WEIGHT`] × the segment's length
//! per radian the tangent turns, `dλ ∝ (1 + w·L·κ) ds`. Arc length alone would give a tight
//! turn (KCS's waterline at z = 9 m turns 22° within 5 cm) almost no parameter, and the patch
//! then folds across its inside from there; the turning term gives such a turn room, and leaves
//! a side of even curvature (a line, a circular arc) at its arc length.

use crate::curve::BezierDecomposition;

/// `w`: how much of a segment's parameter its tangent's turning takes, as a fraction of the
/// segment's length per radian. With 1/π a side that turns through 180° spends as much
/// parameter on the turn as on its length.
const TURN_WEIGHT: f64 = std::f64::consts::FRAC_1_PI;

/// Nodes of the map per Bézier piece of the curve inside the segment.
const NODES_PER_PIECE: usize = 4;

/// Gauss–Legendre abscissae and weights on [−1, 1] (5 points: exact for degree 9), for the arc
/// length of one interval between nodes.
pub(super) const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Newton steps (each kept inside its bracket) for the map's inverse.
const INVERSE_STEPS: usize = 60;

/// A monotone, C¹ map from a segment's fraction λ ∈ [0, 1] to its curve's fraction
/// τ ∈ [0, 1] of the segment's parameter interval `[lo, hi]` (in increasing curve parameter):
/// a piecewise cubic Hermite interpolant (Fritsch & Carlson 1980) through the fractions of
/// `∫ (1 + w·L·κ) ds` (see the module's doc) at nodes at the curve's knots and between them,
/// with the slopes of that integrand there.
///
/// The curve's speed may jump at a knot (a Bézier-segmented spline is C¹ in shape, not in its
/// per-piece parameter); the map takes one slope on each side of a node, so the curve run
/// through the map has a continuous speed there. `λ = 0` and `λ = 1` map to exactly 0 and 1.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SpeedMap {
    /// λ at the nodes, `0 = λ_0 < … < λ_m = 1`.
    lam: Vec<f64>,
    /// τ at the nodes, `0 = τ_0 < … < τ_m = 1`.
    tau: Vec<f64>,
    /// dτ/dλ at the start of each interval (`m` values).
    start_slope: Vec<f64>,
    /// dτ/dλ at the end of each interval (`m` values).
    end_slope: Vec<f64>,
}

impl SpeedMap {
    /// The identity, τ = λ: for a segment whose arc length cannot be measured.
    pub(crate) fn identity() -> SpeedMap {
        SpeedMap {
            lam: vec![0.0, 1.0],
            tau: vec![0.0, 1.0],
            start_slope: vec![1.0],
            end_slope: vec![1.0],
        }
    }

    /// The map of the curve `fast` on `[lo, hi]` (`lo < hi`, inside its domain): nodes at the
    /// knots inside the interval and [`NODES_PER_PIECE`] per piece, λ at each the integral of
    /// `1 + w·L·κ` over arc length from `lo` (5-point Gauss–Legendre per interval) over the
    /// whole. The identity where the length is zero or not finite.
    pub(crate) fn of_curve(fast: &BezierDecomposition, lo: f64, hi: f64) -> SpeedMap {
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return SpeedMap::identity();
        }
        let first = fast.piece_at(lo, true);
        let last = fast.piece_at(hi, false).max(first);
        // (t at the interval's start, at its end, its piece).
        let mut intervals = Vec::with_capacity((last - first + 1) * NODES_PER_PIECE);
        for k in first..=last {
            let piece = &fast.pieces[k];
            let (a, b) = (piece.t0.max(lo), piece.t1.min(hi));
            if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) {
                continue;
            }
            for q in 0..NODES_PER_PIECE {
                let ta = a + (b - a) * (q as f64 / NODES_PER_PIECE as f64);
                let tb = if q + 1 == NODES_PER_PIECE {
                    b
                } else {
                    a + (b - a) * ((q + 1) as f64 / NODES_PER_PIECE as f64)
                };
                intervals.push((ta, tb, k));
            }
        }
        if intervals.is_empty() {
            return SpeedMap::identity();
        }
        // |C′| and |C′ × C″| / |C′|² (curvature times speed) at `t` on piece `k`.
        let rates = |k: usize, t: f64| {
            let d = fast.derivs_in(k, t);
            let speed = d.d1.length();
            (speed, d.d1.cross(d.d2).length() / (speed * speed))
        };
        // Arc length and turning angle of every interval.
        let parts: Vec<(f64, f64)> = intervals
            .iter()
            .map(|&(ta, tb, k)| {
                let (mid, half) = (0.5 * (ta + tb), 0.5 * (tb - ta));
                GAUSS.iter().fold((0.0, 0.0), |(l, a), &(x, w)| {
                    let (speed, turn) = rates(k, mid + half * x);
                    (l + w * half * speed, a + w * half * turn)
                })
            })
            .collect();
        let length: f64 = parts.iter().map(|p| p.0).sum();
        let weight = TURN_WEIGHT * length;
        let lengths: Vec<f64> = parts
            .iter()
            .map(|&(l, a)| if a.is_finite() { l + weight * a } else { l })
            .collect();
        let total: f64 = lengths.iter().sum();
        if !(total.is_finite() && total > 0.0) {
            return SpeedMap::identity();
        }
        let width = hi - lo;
        let slope = |k: usize, t: f64| {
            let (speed, turn) = rates(k, t);
            let rate = if turn.is_finite() {
                speed + weight * turn
            } else {
                speed
            };
            total / (width * rate)
        };
        let mut map = SpeedMap {
            lam: vec![0.0],
            tau: vec![0.0],
            start_slope: Vec::with_capacity(intervals.len()),
            end_slope: Vec::with_capacity(intervals.len()),
        };
        let mut acc = 0.0;
        let mut start = intervals[0];
        for (i, (&(_, tb, k), &len)) in intervals.iter().zip(&lengths).enumerate() {
            acc += len;
            let end = i + 1 == intervals.len();
            let (lam, tau) = if end {
                (1.0, 1.0)
            } else {
                (acc / total, (tb - lo) / width)
            };
            if lam > map.lam[map.lam.len() - 1] && tau > map.tau[map.tau.len() - 1] {
                map.start_slope.push(slope(start.2, start.0));
            } else if !end {
                // An interval of no length joins the next one.
                continue;
            } else if map.start_slope.is_empty() {
                return SpeedMap::identity();
            } else {
                // The last interval has no length: the one before it runs on to the end.
                map.lam.pop();
                map.tau.pop();
                map.end_slope.pop();
            }
            map.end_slope.push(slope(k, tb));
            map.lam.push(lam);
            map.tau.push(tau);
            if let Some(&next) = intervals.get(i + 1) {
                start = next;
            }
        }
        map.limit_slopes();
        map
    }

    /// Fritsch & Carlson's condition for a monotone cubic: each slope within `[0, 3·δ]`, δ the
    /// interval's secant (a slope that is not finite, where the curve stops, becomes `3·δ`).
    fn limit_slopes(&mut self) {
        for j in 0..self.start_slope.len() {
            let secant = (self.tau[j + 1] - self.tau[j]) / (self.lam[j + 1] - self.lam[j]);
            for s in [&mut self.start_slope[j], &mut self.end_slope[j]] {
                *s = if s.is_finite() {
                    s.clamp(0.0, 3.0 * secant)
                } else {
                    3.0 * secant
                };
            }
        }
    }

    /// The interval holding λ: at a node, the one starting there.
    #[inline]
    fn interval(&self, lam: f64) -> usize {
        self.lam
            .partition_point(|&l| l <= lam)
            .saturating_sub(1)
            .min(self.start_slope.len() - 1)
    }

    /// τ and dτ/dλ at `lam` (clamped to [0, 1]; at a node, the slope of the interval after it).
    #[inline]
    pub(crate) fn tau(&self, lam: f64) -> (f64, f64) {
        let lam = if lam.is_nan() {
            0.0
        } else {
            lam.clamp(0.0, 1.0)
        };
        let j = self.interval(lam);
        self.hermite(j, (lam - self.lam[j]) / (self.lam[j + 1] - self.lam[j]))
    }

    /// dτ/dλ at `lam` on the side of it given by `after` (the interval after it, in λ, or the
    /// one before): the two differ at a node where the curve's speed jumps.
    pub(crate) fn slope(&self, lam: f64, after: bool) -> f64 {
        let lam = if lam.is_nan() {
            0.0
        } else {
            lam.clamp(0.0, 1.0)
        };
        let j = self.interval(lam);
        if !after && j > 0 && lam == self.lam[j] {
            return self.end_slope[j - 1];
        }
        self.tau(lam).1
    }

    /// The Hermite cubic of interval `j` at its local `x ∈ [0, 1]`: τ and dτ/dλ.
    #[inline]
    fn hermite(&self, j: usize, x: f64) -> (f64, f64) {
        let h = self.lam[j + 1] - self.lam[j];
        let (t0, t1) = (self.tau[j], self.tau[j + 1]);
        let (m0, m1) = (self.start_slope[j] * h, self.end_slope[j] * h);
        let (x2, x3) = (x * x, x * x * x);
        let value = (2.0 * x3 - 3.0 * x2 + 1.0) * t0
            + (x3 - 2.0 * x2 + x) * m0
            + (3.0 * x2 - 2.0 * x3) * t1
            + (x3 - x2) * m1;
        let d = (6.0 * x2 - 6.0 * x) * (t0 - t1)
            + (3.0 * x2 - 4.0 * x + 1.0) * m0
            + (3.0 * x2 - 2.0 * x) * m1;
        (value, d / h)
    }

    /// The λ at which the map reaches `tau` (clamped to [0, 1]): exact at the nodes, else by
    /// Newton's method kept inside the node interval's bracket.
    pub(crate) fn lambda(&self, tau: f64) -> f64 {
        let tau = if tau.is_nan() {
            0.0
        } else {
            tau.clamp(0.0, 1.0)
        };
        let j = self
            .tau
            .partition_point(|&t| t <= tau)
            .saturating_sub(1)
            .min(self.start_slope.len() - 1);
        if tau == self.tau[j] {
            return self.lam[j];
        }
        let (t0, t1) = (self.tau[j], self.tau[j + 1]);
        let (mut a, mut b) = (0.0, 1.0);
        let mut x = (tau - t0) / (t1 - t0);
        let h = self.lam[j + 1] - self.lam[j];
        for _ in 0..INVERSE_STEPS {
            let (v, d) = self.hermite(j, x);
            let f = v - tau;
            if f == 0.0 {
                break;
            }
            if f < 0.0 {
                a = x;
            } else {
                b = x;
            }
            let step = f / (d * h);
            let next = x - step;
            x = if step.is_finite() && next > a && next < b {
                next
            } else {
                0.5 * (a + b)
            };
            if b - a <= f64::EPSILON {
                break;
            }
        }
        self.lam[j] + h * x
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::curve::NurbsCurve;

    /// A straight line from the origin to (10, 0, 0) as two Bézier pieces, the first 1 m long
    /// and the second 9 m, one unit of parameter each (as a Bézier spline is read).
    fn uneven_line() -> NurbsCurve {
        let co = [DVec3::ZERO, DVec3::X, DVec3::new(10.0, 0.0, 0.0)];
        let third = |a: DVec3, b: DVec3, f: f64| a + (b - a) * f;
        let left = [
            co[0],
            third(co[0], co[1], 2.0 / 3.0),
            third(co[1], co[2], 2.0 / 3.0),
        ];
        let right = [
            third(co[0], co[1], 1.0 / 3.0),
            third(co[1], co[2], 1.0 / 3.0),
            co[2],
        ];
        NurbsCurve::from_bezier(&co, &left, &right, false).unwrap()
    }

    fn point(c: &NurbsCurve, map: &SpeedMap, lam: f64) -> DVec3 {
        let (lo, hi) = c.domain();
        c.point(lo + map.tau(lam).0 * (hi - lo))
    }

    #[test]
    fn a_line_of_uneven_pieces_is_run_at_its_arc_length() {
        let c = uneven_line();
        let (lo, hi) = c.domain();
        let map = SpeedMap::of_curve(&c.bezier_decomposition(), lo, hi);
        // The curve's own parameter puts x = 1 at its middle; the map puts x = 5 there.
        assert!((c.point(0.5 * (lo + hi)).x - 1.0).abs() < 1e-12);
        for j in 0..=20 {
            let lam = j as f64 / 20.0;
            let x = point(&c, &map, lam).x;
            assert!((x - 10.0 * lam).abs() < 1e-9, "λ {lam}: x {x}");
        }
        assert_eq!(map.tau(0.0).0, 0.0);
        assert_eq!(map.tau(1.0).0, 1.0);
    }

    #[test]
    fn the_speed_of_the_mapped_curve_is_continuous_where_the_pieces_meet() {
        let c = uneven_line();
        let (lo, hi) = c.domain();
        let fast = c.bezier_decomposition();
        let map = SpeedMap::of_curve(&fast, lo, hi);
        let speed = |lam: f64| {
            let (tau, d) = map.tau(lam);
            fast.derivs(lo + tau * (hi - lo)).d1.length() * d * (hi - lo)
        };
        let joint = map.lambda(0.5);
        assert!((joint - 0.1).abs() < 1e-12, "the joint at λ {joint}");
        for lam in [joint - 1e-9, joint + 1e-9, 0.0, 0.5, 1.0] {
            assert!(
                (speed(lam) - 10.0).abs() < 1e-6,
                "speed {} at λ {lam}",
                speed(lam)
            );
        }
    }

    #[test]
    fn a_turn_takes_parameter_in_proportion_to_its_angle() {
        // 9 m straight, then a quarter turn within about 1.4 m, one Bézier piece each.
        let co = [
            DVec3::ZERO,
            DVec3::new(9.0, 0.0, 0.0),
            DVec3::new(10.0, 1.0, 0.0),
        ];
        let left = [
            co[0],
            DVec3::new(6.0, 0.0, 0.0),
            DVec3::new(10.0, 0.45, 0.0),
        ];
        let right = [DVec3::new(3.0, 0.0, 0.0), DVec3::new(9.55, 0.0, 0.0), co[2]];
        let c = NurbsCurve::from_bezier(&co, &left, &right, false).unwrap();
        let map = SpeedMap::of_curve(&c.bezier_decomposition(), 0.0, 2.0);
        let turn = c.arc_length_between(1.0, 2.0, 1e-12).unwrap();
        let length = 9.0 + turn;
        // dλ ∝ (1 + w·L·κ) ds: the straight gets 9 of L + w·L·π/2.
        let expected = 9.0 / (length + TURN_WEIGHT * length * std::f64::consts::FRAC_PI_2);
        let joint = map.lambda(0.5);
        assert!(
            (joint - expected).abs() < 1e-6,
            "joint at λ {joint}, expected {expected}"
        );
        // Arc length alone would put it at 9 / L, well past.
        assert!(9.0 / length - joint > 0.2);
    }

    #[test]
    fn the_inverse_finds_the_lambda_of_every_tau() {
        // A cubic with a slow middle, so the map is far from the identity.
        let pts = [
            DVec3::ZERO,
            DVec3::new(3.0, 1.0, 0.0),
            DVec3::new(3.2, 1.1, 0.0),
            DVec3::new(6.0, -1.0, 0.5),
        ];
        let c = NurbsCurve::try_new(3, vec![0., 0., 0., 0., 1., 1., 1., 1.], pts.to_vec(), None)
            .unwrap();
        let map = SpeedMap::of_curve(&c.bezier_decomposition(), 0.2, 0.9);
        let mut last = -1.0;
        for j in 0..=200 {
            let lam = j as f64 / 200.0;
            let (tau, d) = map.tau(lam);
            assert!(tau > last && d >= 0.0, "monotone at λ {lam}");
            last = tau;
            assert!((map.lambda(tau) - lam).abs() < 1e-12, "λ {lam}");
        }
    }

    #[test]
    fn a_line_at_even_speed_keeps_its_parameter_to_rounding() {
        // (A mistyped Gauss weight showed here as a drift of 1e-11.)
        let (a, b) = (DVec3::new(0.1, 0.2, 0.0), DVec3::new(0.6, -0.3, 0.2));
        let c = NurbsCurve::try_new(1, vec![0., 0., 1., 1.], vec![a, b], None).unwrap();
        let map = SpeedMap::of_curve(&c.bezier_decomposition(), 0.0, 1.0);
        let worst = (0..=1000)
            .map(|j| j as f64 / 1000.0)
            .map(|lam| {
                (map.tau(lam).0 - lam)
                    .abs()
                    .max((map.tau(lam).1 - 1.0).abs())
            })
            .fold(0.0, f64::max);
        assert!(worst < 1e-15, "{worst:e}");
        let weights: f64 = GAUSS.iter().map(|g| g.1).sum();
        let eighth: f64 = GAUSS.iter().map(|&(x, w)| w * x.powi(8)).sum();
        assert!((weights - 2.0).abs() < 1e-15 && (eighth - 2.0 / 9.0).abs() < 1e-15);
    }

    #[test]
    fn a_segment_of_no_length_keeps_the_curves_parameter() {
        let c = uneven_line();
        let map = SpeedMap::of_curve(&c.bezier_decomposition(), 1.0, 1.0);
        assert_eq!(map, SpeedMap::identity());
        assert_eq!(map.tau(0.25), (0.25, 1.0));
    }
}
