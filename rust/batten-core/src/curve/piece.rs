//! One rational Bézier piece of a curve in fixed-size storage, and everything computed on it
//! alone: its control-point box, chord and flatness, tangent cone, de Casteljau halving and
//! evaluation with derivatives (rational de Casteljau, Piegl & Tiller §1.4 and eq. 4.8), and
//! the closest point on a piece where the squared distance is convex.

use glam::{DVec3, DVec4};

use super::basis::MAX_ORDER;
use super::bbox::Aabb;

/// Work arrays of this size cover the usual degrees (up to 7) without touching a full
/// [`MAX_ORDER`] array.
const SMALL_ORDER: usize = 8;

/// Point, first and second derivative of a curve at one parameter.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct PointDerivs {
    /// C(t).
    pub point: DVec3,
    /// C′(t).
    pub d1: DVec3,
    /// C″(t).
    pub d2: DVec3,
}

/// The cone of directions a piece's tangent can take: every tangent direction (up to sign for
/// a rational piece) lies within `half_angle` of `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TangentCone {
    /// The unit chord, end minus start.
    pub axis: DVec3,
    /// The largest angle (radians) between the axis and a tangent direction.
    pub half_angle: f64,
}

/// One rational Bézier piece: `degree + 1` homogeneous control points on `[t0, t1]` of the
/// original curve's parameter, in a fixed array so that copying and halving allocate nothing.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BezierPiece {
    /// Curve parameter where the piece starts.
    pub t0: f64,
    /// Curve parameter where the piece ends.
    pub t1: f64,
    /// Number of control points (order).
    n: usize,
    /// Homogeneous control points `(w·P, w)`; the first `n` are used.
    cw: [DVec4; MAX_ORDER],
}

/// One level of de Casteljau's algorithm, in the two roundings the evaluators use: glam's
/// `lerp`, `a·(1 − u) + b·u`, and the monotonic `a + (b − a)·u`.
#[derive(Clone, Copy)]
enum Blend {
    Lerp,
    Monotonic,
}

impl Blend {
    #[inline]
    fn apply(self, a: DVec4, b: DVec4, u: f64) -> DVec4 {
        match self {
            Blend::Lerp => a.lerp(b, u),
            Blend::Monotonic => a + (b - a) * u,
        }
    }
}

/// De Casteljau's algorithm on the points `work[..n]` at `u` until `stop` points are left
/// (they are `work[..stop]`).
#[inline]
fn casteljau_down_to(work: &mut [DVec4], n: usize, stop: usize, u: f64, blend: Blend) {
    for level in 1..=n - stop {
        for i in 0..n - level {
            work[i] = blend.apply(work[i], work[i + 1], u);
        }
    }
}

/// The point at `u` of the quadratic Bézier `q0 q1 q2` (homogeneous), in Bernstein form: the
/// last step of [`casteljau_derivs`].
#[inline]
fn quadratic_point(q0: DVec4, q1: DVec4, q2: DVec4, u: f64) -> DVec4 {
    q0 * ((1.0 - u) * (1.0 - u)) + q1 * (2.0 * u * (1.0 - u)) + q2 * (u * u)
}

/// Homogeneous point, first and second derivative (with respect to the local parameter
/// `u ∈ [0, 1]`) of a rational Bézier piece whose `n` control points fill `work[..n]`, by de
/// Casteljau down to three points (the last step blended as a quadratic).
#[inline]
fn casteljau_derivs(work: &mut [DVec4], n: usize, u: f64) -> [DVec4; 3] {
    let p = (n - 1) as f64;
    let stop = n.min(3);
    casteljau_down_to(work, n, stop, u, Blend::Lerp);
    if stop == 3 {
        let (q0, q1, q2) = (work[0], work[1], work[2]);
        let h = quadratic_point(q0, q1, q2, u);
        let d1 = ((q1 - q0) * (1.0 - u) + (q2 - q1) * u) * p;
        let d2 = (q2 - q1 * 2.0 + q0) * (p * (p - 1.0));
        [h, d1, d2]
    } else {
        let (q0, q1) = (work[0], work[1]);
        [q0.lerp(q1, u), q1 - q0, DVec4::ZERO]
    }
}

/// Point and first derivative from their homogeneous forms (the quotient rule).
#[inline]
fn cartesian_d1(h: DVec4, d1: DVec4) -> (DVec3, DVec3) {
    let c = h.truncate() / h.w;
    (c, (d1.truncate() - d1.w * c) / h.w)
}

/// Point, first and second derivative from their homogeneous forms (the quotient rule,
/// Piegl & Tiller eq. 4.8).
#[inline]
fn cartesian([h, d1, d2]: [DVec4; 3]) -> PointDerivs {
    let (point, c1) = cartesian_d1(h, d1);
    let c2 = (d2.truncate() - 2.0 * d1.w * c1 - d2.w * point) / h.w;
    PointDerivs {
        point,
        d1: c1,
        d2: c2,
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

impl BezierPiece {
    /// The piece on `[t0, t1]` with homogeneous control points `points` (1 to [`MAX_ORDER`]
    /// of them).
    pub(crate) fn new(t0: f64, t1: f64, points: &[DVec4]) -> BezierPiece {
        let mut cw = [DVec4::ZERO; MAX_ORDER];
        cw[..points.len()].copy_from_slice(points);
        BezierPiece {
            t0,
            t1,
            n: points.len(),
            cw,
        }
    }

    /// The homogeneous control points `(w·P, w)`.
    pub(crate) fn points(&self) -> &[DVec4] {
        &self.cw[..self.n]
    }

    /// Control point `i` projected to 3D.
    #[inline]
    fn control_point(&self, i: usize) -> DVec3 {
        self.cw[i].truncate() / self.cw[i].w
    }

    /// Box of the projected control points. Weights are positive, so the piece lies inside
    /// the convex hull of these points and hence inside this box.
    pub(crate) fn hull_box(&self) -> Aabb {
        Aabb::from_points((0..self.n).map(|i| self.control_point(i))).expect("a piece has points")
    }

    /// A lower bound of the distance from `q` to the piece: the larger of the distance to its
    /// control-point box and the distance to its chord (end to end) less its flatness (the
    /// largest distance of a control point from the chord; the piece lies in the convex hull
    /// of its control points, so within that distance of the chord). The chord bound is exact
    /// to O(width²), which keeps branch and bound from splitting a flat minimum into
    /// thousands of pieces.
    pub(crate) fn lower_bound(&self, q: DVec3) -> f64 {
        let (a, b) = self.ends();
        let chord = segment_distance(q, a, b) - self.flatness();
        chord.max(self.hull_box().distance_to(q))
    }

    /// Largest distance of a control point from the chord: how far the piece can stray from
    /// the straight line between its ends.
    pub(crate) fn flatness(&self) -> f64 {
        let (a, b) = self.ends();
        (0..self.n)
            .map(|i| segment_distance(self.control_point(i), a, b))
            .fold(0.0, f64::max)
    }

    /// End points, which lie on the curve.
    pub(crate) fn ends(&self) -> (DVec3, DVec3) {
        (self.control_point(0), self.control_point(self.n - 1))
    }

    /// The cone of tangent directions: the unit chord and the largest angle between it and a
    /// direction the piece can take, bounded by the control polygon (the legs of a polynomial
    /// piece; every pair of control points of a rational one). `None` when the chord has zero
    /// length.
    pub(crate) fn tangent_cone(&self) -> Option<TangentCone> {
        let (a, b) = self.ends();
        let axis = (b - a).try_normalize()?;
        let rational = self.points().iter().any(|c| c.w != self.cw[0].w);
        // The widest leg has the smallest cosine with the axis: one arccosine per cone.
        let mut cos_half: f64 = 1.0;
        for i in 0..self.n - 1 {
            let js = if rational {
                i + 1..self.n
            } else {
                i + 1..i + 2
            };
            for j in js {
                let leg = self.control_point(j) - self.control_point(i);
                let len = leg.length();
                if len > 0.0 {
                    cos_half = cos_half.min(leg.dot(axis) / len);
                }
            }
        }
        Some(TangentCone {
            axis,
            half_angle: cos_half.clamp(-1.0, 1.0).acos(),
        })
    }

    /// De Casteljau subdivision at the parametric middle, in homogeneous coordinates.
    pub(crate) fn halves(&self) -> (BezierPiece, BezierPiece) {
        let n = self.n;
        let mut work = self.cw;
        let mut left = *self;
        let mut right = *self;
        left.cw[0] = work[0];
        right.cw[n - 1] = work[n - 1];
        for level in 1..n {
            for i in 0..n - level {
                work[i] = (work[i] + work[i + 1]) * 0.5;
            }
            left.cw[level] = work[0];
            right.cw[n - 1 - level] = work[n - 1 - level];
        }
        let tm = 0.5 * (self.t0 + self.t1);
        left.t1 = tm;
        right.t0 = tm;
        (left, right)
    }

    /// The local parameter `u ∈ [0, 1]` of the curve parameter `t` (clamped into the piece).
    #[inline]
    fn local(&self, t: f64) -> f64 {
        ((t - self.t0) / (self.t1 - self.t0)).clamp(0.0, 1.0)
    }

    /// `f` applied to a copy of the control points in a work array on the stack (a small one
    /// for the usual degrees).
    #[inline]
    fn with_work<R>(&self, f: impl FnOnce(&mut [DVec4]) -> R) -> R {
        // The leading block of the stored array, copied whole: one copy, no zeroing first.
        if self.n <= SMALL_ORDER {
            let mut work: [DVec4; SMALL_ORDER] = *self
                .cw
                .first_chunk()
                .expect("MAX_ORDER is at least SMALL_ORDER");
            f(&mut work)
        } else {
            let mut work = self.cw;
            f(&mut work)
        }
    }

    /// Homogeneous point, first and second derivative with respect to the local parameter
    /// `u ∈ [0, 1]`.
    #[inline]
    fn homogeneous_derivs(&self, u: f64) -> [DVec4; 3] {
        self.with_work(|work| casteljau_derivs(work, self.n, u))
    }

    /// Point, first and second derivative with respect to the local parameter `u ∈ [0, 1]`.
    #[inline]
    fn local_derivs(&self, u: f64) -> PointDerivs {
        cartesian(self.homogeneous_derivs(u))
    }

    /// Point, first and second derivative at the curve parameter `t` (clamped into the piece),
    /// with respect to `t`, by homogeneous de Casteljau: no allocation and no basis-function
    /// tables.
    #[inline]
    pub(crate) fn derivs_at(&self, t: f64) -> PointDerivs {
        let len = self.t1 - self.t0;
        let [h, d1, d2] = self.homogeneous_derivs(self.local(t));
        cartesian([h, d1 * (1.0 / len), d2 * (1.0 / (len * len))])
    }

    /// The point and first derivative of [`BezierPiece::derivs_at`], bit for bit, without
    /// working out the second derivative.
    #[inline]
    pub(crate) fn point_tangent_at(&self, t: f64) -> (DVec3, DVec3) {
        let len = self.t1 - self.t0;
        let u = self.local(t);
        let n = self.n;
        let [h, d1] = self.with_work(|work| {
            let p = (n - 1) as f64;
            let stop = n.min(3);
            casteljau_down_to(work, n, stop, u, Blend::Lerp);
            if stop == 3 {
                let (q0, q1, q2) = (work[0], work[1], work[2]);
                [
                    quadratic_point(q0, q1, q2, u),
                    ((q1 - q0) * (1.0 - u) + (q2 - q1) * u) * p,
                ]
            } else {
                let (q0, q1) = (work[0], work[1]);
                [q0.lerp(q1, u), q1 - q0]
            }
        });
        cartesian_d1(h, d1 * (1.0 / len))
    }

    /// The point of [`BezierPiece::derivs_at`], bit for bit, without the derivatives.
    #[inline]
    pub(crate) fn point_at(&self, t: f64) -> DVec3 {
        let u = self.local(t);
        let n = self.n;
        let h = self.with_work(|work| {
            let stop = n.min(3);
            casteljau_down_to(work, n, stop, u, Blend::Lerp);
            if stop == 3 {
                quadratic_point(work[0], work[1], work[2], u)
            } else {
                work[0].lerp(work[1], u)
            }
        });
        h.truncate() / h.w
    }

    /// Point and first derivative at the curve parameter `t` (clamped into the piece), with
    /// respect to `t`: de Casteljau down to the last leg, whose direction is the derivative.
    ///
    /// Implementation note: this rounds differently from [`BezierPiece::derivs_at`]
    /// (monotonic blends, the degree folded into the parameter scale); the surface patches
    /// are evaluated with this one and the node finding and fairing with that one, and both
    /// results are kept bit for bit.
    #[inline]
    pub(crate) fn point_d1_at(&self, t: f64) -> (DVec3, DVec3) {
        let x = self.local(t);
        let n = self.n;
        let (q0, q1) = self.with_work(|work| {
            casteljau_down_to(work, n, 2, x, Blend::Monotonic);
            (work[0], work[1])
        });
        let h = Blend::Monotonic.apply(q0, q1, x);
        let dh = (q1 - q0) * ((n - 1) as f64 / (self.t1 - self.t0));
        cartesian_d1(h, dh)
    }

    /// True when the squared distance from `q` is convex along the whole piece, so it has one
    /// minimum there and Newton's method finds it: for a polynomial piece,
    /// `½ d²/du² |C − q|² = |C′|² + C″·(C − q)`, and `|C′| ≥ min_i H_i·e` (hodograph control
    /// points `H_i` along the unit chord `e`), `|C″| ≤ max_i |C″_i|` (second hodograph),
    /// `|C − q| ≤ max_i |P_i − q|` (convex hull). Always false for rational pieces.
    pub(crate) fn distance_convex(&self, q: DVec3) -> bool {
        let w0 = self.cw[0].w;
        if self.points().iter().any(|c| c.w != w0) || self.n < 2 {
            return false;
        }
        let p = |i: usize| self.cw[i].truncate() / w0;
        let n = self.n;
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

    /// [`BezierPiece::convex_foot`] starting from the global parameter `hint` (a nearby
    /// point's foot): plain Newton, which from a close start needs two or three steps and no
    /// end evaluations; where it would leave the piece (the foot may be an end), the
    /// bracketed search of `convex_foot`. The same foot: `g` increases along the piece, so a
    /// root inside it is the only one.
    pub(crate) fn convex_foot_near(&self, q: DVec3, hint: f64) -> (f64, DVec3) {
        let len = self.t1 - self.t0;
        let mut u = (hint - self.t0) / len;
        if u > 0.0 && u < 1.0 {
            for _ in 0..8 {
                let PointDerivs { point, d1, d2 } = self.local_derivs(u);
                let r = point - q;
                let (gu, dg) = (d1.dot(r), d2.dot(r) + d1.length_squared());
                if dg <= 0.0 {
                    break;
                }
                let next = u - gu / dg;
                if !(next > 0.0 && next < 1.0) {
                    break;
                }
                if (next - u).abs() <= 4.0 * f64::EPSILON {
                    return (self.t0 + next * len, self.local_derivs(next).point);
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
    pub(crate) fn convex_foot(&self, q: DVec3) -> (f64, DVec3) {
        let g = |u: f64| {
            let PointDerivs { point, d1, d2 } = self.local_derivs(u);
            let r = point - q;
            (point, d1.dot(r), d2.dot(r) + d1.length_squared())
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
        let cw: Vec<DVec4> = p.iter().map(|q| q.extend(1.0)).collect();
        BezierPiece::new(2.0, 4.0, &cw)
    }

    fn sampled_nearest(piece: &BezierPiece, q: DVec3) -> f64 {
        (0..=100_000)
            .map(|i| {
                let u = f64::from(i) / 100_000.0;
                (piece.local_derivs(u).point - q).length()
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
        let PointDerivs { point: c, d1, .. } = piece.local_derivs((t - 2.0) / 2.0);
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
        let rational = BezierPiece::new(
            piece.t0,
            piece.t1,
            &[
                DVec4::new(0.0, 0.0, 0.0, 1.0),
                DVec4::new(0.4, 1.0, 0.0, 2.0),
                DVec4::new(1.0, 0.0, 0.0, 1.0),
            ],
        );
        assert!(
            !rational.distance_convex(DVec3::new(0.5, 0.6, 0.0)),
            "rational pieces are never taken as convex"
        );
    }

    #[test]
    fn both_evaluators_agree_with_each_other_to_rounding() {
        let piece = arch();
        for i in 0..=20 {
            let t = 2.0 + 2.0 * f64::from(i) / 20.0;
            let d = piece.derivs_at(t);
            let (p, d1) = piece.point_d1_at(t);
            assert!((p - d.point).length() < 1e-15, "point at {t}");
            assert!((d1 - d.d1).length() < 1e-14, "C' at {t}");
        }
    }
}
