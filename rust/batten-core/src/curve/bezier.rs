//! Bézier decomposition of a NURBS curve and rational de Casteljau subdivision: the basis of
//! the global (branch-and-bound) closest-point search and the tight bounding box.

use glam::{DVec3, DVec4};

use super::basis::MAX_ORDER;
use super::bbox::Aabb;
use super::error::CurveError;
use super::nurbs::NurbsCurve;

/// Work arrays of this size cover the usual degrees (up to 7) without touching a full
/// [`MAX_ORDER`] array.
const SMALL_ORDER: usize = 8;

/// Homogeneous point, first and second derivative (with respect to the local parameter
/// `u ∈ [0, 1]`) of a rational Bézier piece, by de Casteljau down to three points.
fn casteljau_derivs(cw: &[DVec4], work: &mut [DVec4], u: f64) -> (DVec4, DVec4, DVec4) {
    let n = cw.len();
    let p = (n - 1) as f64;
    work[..n].copy_from_slice(cw);
    let stop = n.min(3);
    for level in 1..=n - stop {
        for i in 0..n - level {
            work[i] = work[i].lerp(work[i + 1], u);
        }
    }
    if stop == 3 {
        let (q0, q1, q2) = (work[0], work[1], work[2]);
        let h = q0 * ((1.0 - u) * (1.0 - u)) + q1 * (2.0 * u * (1.0 - u)) + q2 * (u * u);
        let d1 = ((q1 - q0) * (1.0 - u) + (q2 - q1) * u) * p;
        let d2 = (q2 - q1 * 2.0 + q0) * (p * (p - 1.0));
        (h, d1, d2)
    } else {
        let (q0, q1) = (work[0], work[1]);
        (q0.lerp(q1, u), q1 - q0, DVec4::ZERO)
    }
}

/// Point, first and second derivative from their homogeneous forms (the quotient rule).
fn cartesian((h, d1, d2): (DVec4, DVec4, DVec4)) -> (DVec3, DVec3, DVec3) {
    let w = h.w;
    let c = h.truncate() / w;
    let c1 = (d1.truncate() - d1.w * c) / w;
    let c2 = (d2.truncate() - 2.0 * d1.w * c1 - d2.w * c) / w;
    (c, c1, c2)
}

/// One rational Bézier piece: `degree + 1` homogeneous control points on `[t0, t1]` of the
/// original curve's parameter.
#[derive(Clone, Debug)]
pub(crate) struct BezierPiece {
    pub t0: f64,
    pub t1: f64,
    pub cw: Vec<DVec4>,
}

impl BezierPiece {
    /// Box of the projected control points. Weights are positive, so the piece lies inside
    /// the convex hull of these points and hence inside this box.
    pub fn hull_box(&self) -> Aabb {
        Aabb::from_points(self.cw.iter().map(|c| c.truncate() / c.w)).expect("a piece has points")
    }

    /// A lower bound of the distance from `q` to the piece: the larger of the distance to its
    /// control-point box and the distance to its chord (end to end) less its flatness (the
    /// largest distance of a control point from the chord; the piece lies in the convex hull
    /// of its control points, so within that distance of the chord). The chord bound is exact
    /// to O(width²), which keeps branch and bound from splitting a flat minimum into
    /// thousands of pieces.
    pub fn lower_bound(&self, q: DVec3) -> f64 {
        let (a, b) = self.ends();
        let chord = segment_distance(q, a, b) - self.flatness();
        chord.max(self.hull_box().distance_to(q))
    }

    /// Largest distance of a control point from the chord: how far the piece can stray from
    /// the straight line between its ends.
    pub fn flatness(&self) -> f64 {
        let (a, b) = self.ends();
        self.cw
            .iter()
            .map(|c| segment_distance(c.truncate() / c.w, a, b))
            .fold(0.0, f64::max)
    }

    /// End points, which lie on the curve.
    pub fn ends(&self) -> (DVec3, DVec3) {
        let (a, b) = (self.cw[0], self.cw[self.cw.len() - 1]);
        (a.truncate() / a.w, b.truncate() / b.w)
    }

    /// True when the squared distance from `q` is convex along the whole piece, so it has one
    /// minimum there and Newton's method finds it: for a polynomial piece,
    /// `½ d²/du² |C − q|² = |C′|² + C″·(C − q)`, and `|C′| ≥ min_i H_i·e` (hodograph control
    /// points `H_i` along the unit chord `e`), `|C″| ≤ max_i |C″_i|` (second hodograph),
    /// `|C − q| ≤ max_i |P_i − q|` (convex hull). Always false for rational pieces.
    pub fn distance_convex(&self, q: DVec3) -> bool {
        let w0 = self.cw[0].w;
        if self.cw.iter().any(|c| c.w != w0) || self.cw.len() < 2 {
            return false;
        }
        let p = |i: usize| self.cw[i].truncate() / w0;
        let n = self.cw.len();
        let (a, b) = self.ends();
        let Some(e) = (b - a).try_normalize() else {
            return false;
        };
        let deg = (n - 1) as f64;
        let mut speed = f64::INFINITY;
        for i in 0..n - 1 {
            speed = speed.min(deg * (p(i + 1) - p(i)).dot(e));
        }
        if speed <= 0.0 {
            return false;
        }
        let mut accel: f64 = 0.0;
        for i in 0..n.saturating_sub(2) {
            accel = accel.max(deg * (deg - 1.0) * (p(i + 2) - 2.0 * p(i + 1) + p(i)).length());
        }
        let reach = (0..n).map(|i| (p(i) - q).length()).fold(0.0, f64::max);
        speed * speed > accel * reach
    }

    /// Homogeneous point, first and second derivative with respect to the local parameter
    /// `u ∈ [0, 1]`.
    fn homogeneous_derivs(&self, u: f64) -> (DVec4, DVec4, DVec4) {
        if self.cw.len() <= SMALL_ORDER {
            casteljau_derivs(&self.cw, &mut [DVec4::ZERO; SMALL_ORDER], u)
        } else {
            casteljau_derivs(&self.cw, &mut [DVec4::ZERO; MAX_ORDER], u)
        }
    }

    /// Point, first and second derivative with respect to the local parameter `u ∈ [0, 1]`.
    fn local_derivs(&self, u: f64) -> (DVec3, DVec3, DVec3) {
        cartesian(self.homogeneous_derivs(u))
    }

    /// Point, first and second derivative at the curve parameter `t` (clamped into the piece),
    /// with respect to `t`, by homogeneous de Casteljau: no allocation and no basis-function
    /// tables.
    pub fn derivs_at(&self, t: f64) -> (DVec3, DVec3, DVec3) {
        let len = self.t1 - self.t0;
        let u = ((t - self.t0) / len).clamp(0.0, 1.0);
        let (h, d1, d2) = self.homogeneous_derivs(u);
        cartesian((h, d1 * (1.0 / len), d2 * (1.0 / (len * len))))
    }

    /// [`BezierPiece::convex_foot`] starting from the global parameter `hint` (a nearby
    /// point's foot): plain Newton, which from a close start needs two or three steps and no
    /// end evaluations; where it would leave the piece (the foot may be an end), the
    /// bracketed search of `convex_foot`. The same foot: `g` increases along the piece, so a
    /// root inside it is the only one.
    pub fn convex_foot_near(&self, q: DVec3, hint: f64) -> (f64, DVec3) {
        let len = self.t1 - self.t0;
        let mut u = (hint - self.t0) / len;
        if u > 0.0 && u < 1.0 {
            for _ in 0..8 {
                let (c, d1, d2) = self.local_derivs(u);
                let r = c - q;
                let (gu, dg) = (d1.dot(r), d2.dot(r) + d1.length_squared());
                if dg <= 0.0 {
                    break;
                }
                let next = u - gu / dg;
                if !(next > 0.0 && next < 1.0) {
                    break;
                }
                if (next - u).abs() <= 4.0 * f64::EPSILON {
                    return (self.t0 + next * len, self.local_derivs(next).0);
                }
                u = next;
            }
        }
        self.convex_foot(q)
    }

    /// The closest point to `q` on a piece where [`BezierPiece::distance_convex`] holds:
    /// the root of `g(u) = C′(u)·(C(u) − q)`, which increases along the piece, by Newton's
    /// method kept inside a bisection bracket (or an end, where `g` does not change sign).
    /// Returns the global parameter and the point.
    pub fn convex_foot(&self, q: DVec3) -> (f64, DVec3) {
        let g = |u: f64| {
            let (c, d1, d2) = self.local_derivs(u);
            let r = c - q;
            (c, d1.dot(r), d2.dot(r) + d1.length_squared())
        };
        let global = |u: f64| self.t0 + u * (self.t1 - self.t0);
        let (c0, g0, _) = g(0.0);
        if g0 >= 0.0 {
            return (self.t0, c0);
        }
        let (c1, g1, _) = g(1.0);
        if g1 <= 0.0 {
            return (self.t1, c1);
        }
        let (a, b) = self.ends();
        let ab = b - a;
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        let mut u = ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        let (mut c, mut gu, mut dg) = g(u);
        for _ in 0..64 {
            if gu < 0.0 {
                lo = u;
            } else {
                hi = u;
            }
            let newton = u - gu / dg;
            let next = if dg > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - u).abs() <= 4.0 * f64::EPSILON || hi - lo <= 4.0 * f64::EPSILON {
                break;
            }
            u = next;
            (c, gu, dg) = g(u);
        }
        (global(u), c)
    }

    /// De Casteljau subdivision at the parametric middle, in homogeneous coordinates.
    pub fn halves(&self) -> (BezierPiece, BezierPiece) {
        let n = self.cw.len();
        let mut work = self.cw.clone();
        let mut left = Vec::with_capacity(n);
        let mut right = vec![DVec4::ZERO; n];
        left.push(work[0]);
        right[n - 1] = work[n - 1];
        for level in 1..n {
            for i in 0..n - level {
                work[i] = (work[i] + work[i + 1]) * 0.5;
            }
            left.push(work[0]);
            right[n - 1 - level] = work[n - 1 - level];
        }
        let tm = 0.5 * (self.t0 + self.t1);
        (
            BezierPiece {
                t0: self.t0,
                t1: tm,
                cw: left,
            },
            BezierPiece {
                t0: tm,
                t1: self.t1,
                cw: right,
            },
        )
    }
}

/// A curve cut into rational Bézier pieces, one per non-empty knot span, kept with the curve
/// for Newton refinement. Build it once and query it many times.
#[derive(Clone, Debug)]
pub struct BezierDecomposition {
    pub(crate) curve: NurbsCurve,
    pub(crate) pieces: Vec<BezierPiece>,
}

impl BezierDecomposition {
    /// The index of the piece holding `t`; at a piece boundary, the piece after it when
    /// `after` is true (the one a curve leaves the knot on), else the piece before it.
    pub(crate) fn piece_at(&self, t: f64, after: bool) -> usize {
        if after {
            self.pieces.partition_point(|p| p.t1 <= t)
        } else {
            self.pieces.partition_point(|p| p.t1 < t)
        }
        .min(self.pieces.len() - 1)
    }

    /// Decompose by inserting every knot of the domain to multiplicity `degree` (A5.1 repeated):
    /// each non-empty span's `degree + 1` control points are then its Bézier points.
    pub fn new(curve: &NurbsCurve) -> BezierDecomposition {
        let p = curve.degree();
        let (start, end) = curve.domain();
        let mut values: Vec<f64> = curve
            .knots()
            .iter()
            .copied()
            .filter(|&u| u >= start && u <= end)
            .collect();
        values.dedup();
        let mut full = curve.clone();
        for &u in &values {
            let s = full.multiplicity(u);
            if s < p {
                full = full
                    .insert_knot(u, p - s)
                    .expect("insertion to multiplicity p within the domain is valid");
            }
        }
        let knots = full.knots();
        let cw = full.homogeneous_points();
        let n = cw.len();
        let pieces = (p..n)
            .filter(|&k| knots[k] < knots[k + 1])
            .map(|k| BezierPiece {
                t0: knots[k],
                t1: knots[k + 1],
                cw: cw[k - p..=k].to_vec(),
            })
            .collect();
        BezierDecomposition {
            curve: curve.clone(),
            pieces,
        }
    }

    /// Number of Bézier pieces.
    pub fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    /// Box of all control points: holds the curve, cheap, not tight.
    pub fn hull_box(&self) -> Aabb {
        self.pieces
            .iter()
            .map(BezierPiece::hull_box)
            .reduce(Aabb::union)
            .expect("a curve has at least one piece")
    }

    /// A box that holds the curve and is at most `accuracy` larger than the tightest one on
    /// each side: pieces whose hull box already lies inside the box of known curve points
    /// are done; the others are halved until their hull box is smaller than `accuracy`.
    pub fn bounding_box(&self, accuracy: f64) -> Result<Aabb, CurveError> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(CurveError::Accuracy(accuracy));
        }
        let mut known = Aabb::from_point(self.pieces[0].ends().0);
        for piece in &self.pieces {
            let (a, b) = piece.ends();
            known = known.including(a).including(b);
        }
        let mut stack: Vec<BezierPiece> = self.pieces.clone();
        while let Some(piece) = stack.pop() {
            let hull = piece.hull_box();
            if known.contains_box(&hull) {
                continue;
            }
            if hull.diagonal() <= accuracy {
                known = known.union(hull);
                continue;
            }
            let (l, r) = piece.halves();
            known = known.including(l.ends().1);
            stack.push(l);
            stack.push(r);
        }
        Ok(known)
    }
}

/// Distance from `p` to the segment `[a, b]`.
pub(crate) fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * s - p).length()
}

impl NurbsCurve {
    /// The Bézier decomposition of this curve (see [`BezierDecomposition`]).
    pub fn bezier_decomposition(&self) -> BezierDecomposition {
        BezierDecomposition::new(self)
    }

    /// A box holding the curve, at most `accuracy` larger than the tightest one on each side.
    pub fn bounding_box(&self, accuracy: f64) -> Result<Aabb, CurveError> {
        self.bezier_decomposition().bounding_box(accuracy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A shallow cubic arch bulging towards +y: from (0, 0) over (0.5, 0.0375) to (1, 0),
    /// radius of curvature about 3.3 at its middle.
    fn arch() -> BezierPiece {
        let p = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0 / 3.0, 0.05, 0.0),
            DVec3::new(2.0 / 3.0, 0.05, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
        ];
        BezierPiece {
            t0: 2.0,
            t1: 4.0,
            cw: p.iter().map(|q| q.extend(1.0)).collect(),
        }
    }

    fn sampled_nearest(piece: &BezierPiece, q: DVec3) -> f64 {
        (0..=100_000)
            .map(|i| {
                let u = f64::from(i) / 100_000.0;
                (piece.local_derivs(u).0 - q).length()
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn convex_distance_is_recognised_and_its_foot_is_the_nearest_point() {
        let piece = arch();
        // Just above the arch: one minimum, found exactly.
        let q = DVec3::new(0.37, 0.2, 0.0);
        assert!(piece.distance_convex(q), "a point near the arch");
        let (t, point) = piece.convex_foot(q);
        assert!((2.0..=4.0).contains(&t), "global parameter {t}");
        let d = (point - q).length();
        let dense = sampled_nearest(&piece, q);
        assert!(d <= dense + 1e-12, "foot {d} vs sampled {dense}");
        assert!(d >= dense - 1e-9, "foot {d} below sampled {dense}");
        // The foot is perpendicular: C'(u)·(C(u) − q) = 0.
        let (c, d1, _) = piece.local_derivs((t - 2.0) / 2.0);
        assert!(d1.dot(c - q).abs() < 1e-12, "perpendicular foot");
        // Beyond the centre of curvature the middle of the arch is a local maximum of the
        // distance (two minima, towards the ends): not convex, so it is subdivided.
        let below = DVec3::new(0.5, -5.0, 0.0);
        assert!(
            !piece.distance_convex(below),
            "beyond the centre of curvature"
        );
    }

    #[test]
    fn convex_foot_from_a_hint_is_the_same_foot() {
        let piece = arch();
        for (q, hint) in [
            (DVec3::new(0.37, 0.2, 0.0), 2.9),
            (DVec3::new(0.37, 0.2, 0.0), 2.01),
            (DVec3::new(0.9, 0.1, 0.0), 3.5),
            (DVec3::new(-0.3, -0.2, 0.0), 2.5), // foot at the start: Newton leaves the piece
            (DVec3::new(1.3, -0.2, 0.0), 2.5),  // foot at the end
        ] {
            assert!(piece.distance_convex(q), "convex at {q}");
            let (t0, p0) = piece.convex_foot(q);
            let (t1, p1) = piece.convex_foot_near(q, hint);
            assert!((t0 - t1).abs() < 1e-12, "q {q}: {t1} vs {t0}");
            assert!((p0 - p1).length() < 1e-12, "q {q}: point");
        }
    }

    #[test]
    fn convex_foot_at_an_end_when_the_distance_only_grows() {
        let piece = arch();
        let q = DVec3::new(-0.3, -0.2, 0.0);
        assert!(piece.distance_convex(q), "near the start");
        let (t, point) = piece.convex_foot(q);
        assert_eq!(t, 2.0, "the start is nearest");
        assert_eq!(point, DVec3::ZERO, "at the start point");
        let rational = BezierPiece {
            cw: vec![
                DVec4::new(0.0, 0.0, 0.0, 1.0),
                DVec4::new(0.4, 1.0, 0.0, 2.0),
                DVec4::new(1.0, 0.0, 0.0, 1.0),
            ],
            ..piece
        };
        assert!(
            !rational.distance_convex(DVec3::new(0.5, 0.6, 0.0)),
            "rational pieces are never taken as convex"
        );
    }
}
