//! Closest approach of two curve pieces: fixed-size Bézier segments for the recursive
//! subdivision of candidate pairs, and Newton's method on `|C1(s) − C2(t)|²`.

use glam::{DVec3, DVec4};

use crate::curve::{Aabb, BezierDecomposition};

/// Control points a segment can hold: the kernel's largest order.
pub(crate) const SEG_ORDER: usize = crate::curve::MAX_DEGREE + 1;

/// A rational Bézier piece `[t0, t1]` of a curve with homogeneous control points in a fixed
/// array, so that subdivision allocates nothing.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Seg {
    pub t0: f64,
    pub t1: f64,
    n: usize,
    cw: [DVec4; SEG_ORDER],
}

impl Seg {
    /// A segment from a piece's homogeneous control points.
    pub fn new(t0: f64, t1: f64, points: &[DVec4]) -> Seg {
        let mut cw = [DVec4::ZERO; SEG_ORDER];
        cw[..points.len()].copy_from_slice(points);
        Seg {
            t0,
            t1,
            n: points.len(),
            cw,
        }
    }

    fn point(&self, i: usize) -> DVec3 {
        self.cw[i].truncate() / self.cw[i].w
    }

    /// Start point and chord vector (end − start).
    pub fn chord(&self) -> (DVec3, DVec3) {
        let a = self.point(0);
        (a, self.point(self.n - 1) - a)
    }

    /// Box of the control points, which holds the segment (positive weights).
    pub fn hull_box(&self) -> Aabb {
        let mut b = Aabb::from_point(self.point(0));
        for i in 1..self.n {
            b = b.including(self.point(i));
        }
        b
    }

    /// The cone of tangent directions: the unit chord and the largest angle (radians) between
    /// it and a direction the segment can take, bounded by the control polygon (the legs of
    /// a polynomial segment; every pair of control points of a rational one). `None` when the
    /// chord has zero length.
    pub fn tangent_cone(&self) -> Option<(DVec3, f64)> {
        let (_, chord) = self.chord();
        let axis = chord.try_normalize()?;
        let rational = self.cw[..self.n].iter().any(|c| c.w != self.cw[0].w);
        // The widest leg has the smallest cosine with the axis: one arccosine per cone.
        let mut cos_half: f64 = 1.0;
        for i in 0..self.n - 1 {
            let js = if rational {
                i + 1..self.n
            } else {
                i + 1..i + 2
            };
            for j in js {
                let leg = self.point(j) - self.point(i);
                let len = leg.length();
                if len > 0.0 {
                    cos_half = cos_half.min(leg.dot(axis) / len);
                }
            }
        }
        Some((axis, cos_half.clamp(-1.0, 1.0).acos()))
    }

    /// De Casteljau subdivision at the parametric middle.
    pub fn halves(&self) -> (Seg, Seg) {
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
}

/// Distance between two boxes (0 when they overlap): a lower bound of the distance between
/// anything inside them.
pub(crate) fn box_gap(a: &Aabb, b: &Aabb) -> f64 {
    (a.min - b.max).max(b.min - a.max).max(DVec3::ZERO).length()
}

/// A closest approach: parameters on both curves and the distance there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Approach {
    pub s: f64,
    pub t: f64,
    pub gap: f64,
    /// The points of the two curves at `s` and `t`.
    pub points: (DVec3, DVec3),
    /// Their first derivatives there.
    pub tangents: (DVec3, DVec3),
}

/// A curve as its Bézier pieces, evaluated with derivatives by homogeneous de Casteljau
/// (`BezierPiece::derivs_at`), for the inner loop of Newton's
/// method.
pub(crate) struct PieceCurve<'a> {
    decomposition: &'a BezierDecomposition,
}

impl<'a> PieceCurve<'a> {
    /// Evaluator of a decomposed curve.
    pub fn new(decomposition: &'a BezierDecomposition) -> Self {
        PieceCurve { decomposition }
    }

    /// C(t), C'(t) and C''(t) (t clamped into the domain); at a knot, of the piece before it.
    pub fn eval(&self, t: f64) -> (DVec3, DVec3, DVec3) {
        self.eval_side(t, false)
    }

    /// C(t), C'(t) and C''(t); at a knot, of the piece after it when `after` is true (the
    /// one-sided derivative a curve leaves the knot with), else of the piece before it.
    pub fn eval_side(&self, t: f64, after: bool) -> (DVec3, DVec3, DVec3) {
        self.eval_in(self.piece_at(t, after), t)
    }

    /// The index of the piece [`PieceCurve::eval_side`] evaluates at `t`.
    pub fn piece_at(&self, t: f64, after: bool) -> usize {
        self.decomposition.piece_at(t, after)
    }

    /// C(t), C'(t) and C''(t) of piece `k` (t clamped into it).
    pub fn eval_in(&self, k: usize, t: f64) -> (DVec3, DVec3, DVec3) {
        self.decomposition.pieces[k].derivs_at(t)
    }

    /// C(t).
    pub fn point(&self, t: f64) -> DVec3 {
        self.eval(t).0
    }
}

/// Local minimum of `f(s, t) = ½|C1(s) − C2(t)|²` from `(s, t)` by Newton's method, kept in
/// the boxes `[s_lo, s_hi] × [t_lo, t_hi]` (H-rep §3.1 node finding; the standard
/// curve–curve closest-point iteration).
///
/// The Hessian is `[[C1'·C1' + C1''·r, −C1'·C2'], [−C1'·C2', C2'·C2' − C2''·r]]` with
/// `r = C1 − C2`; where it is not positive definite the Gauss–Newton part (without the `r`
/// terms) is used. A parameter held at a bound by a step pushing outwards is frozen and the
/// other one is solved alone (this finds T-joints and end-to-end joints). Steps are halved until
/// `f` decreases; the best point seen is returned. The iteration stops once the distance is
/// below `accuracy` (a crossing), or a step moves the parameters by less than `accuracy`
/// relative to the curves' extents (a minimum at a positive distance).
pub(crate) fn closest_approach(
    c1: &PieceCurve,
    c2: &PieceCurve,
    start: (f64, f64),
    s_range: (f64, f64),
    t_range: (f64, f64),
    accuracy: f64,
) -> Approach {
    let (mut s, mut t) = start;
    // Points with derivatives at the current parameters; a trial point of the line search is
    // evaluated with its derivatives so an accepted one serves the next iteration.
    let (mut e1, mut e2) = (c1.eval(s), c2.eval(t));
    let mut f = (e1.0 - e2.0).length_squared();
    for _ in 0..60 {
        if f <= accuracy * accuracy {
            break;
        }
        let ((p1, a1, b1), (p2, a2, b2)) = (e1, e2);
        let r = p1 - p2;
        let g = [a1.dot(r), -a2.dot(r)];
        let gn = [a1.length_squared(), a2.length_squared()];
        let b = -a1.dot(a2);
        let mut h = [gn[0] + b1.dot(r), b, gn[1] - b2.dot(r)];
        if !(h[0] > 0.0 && h[2] > 0.0 && h[0] * h[2] - b * b > 0.0) {
            h = [gn[0], b, gn[1]];
        }
        // A touch of damping keeps the Gauss–Newton system solvable for parallel tangents.
        let damp = 1e-12 * (h[0] + h[2]) + f64::MIN_POSITIVE;
        let (h00, h11) = (h[0] + damp, h[2] + damp);
        let det = h00 * h11 - b * b;
        let mut ds = -(h11 * g[0] - b * g[1]) / det;
        let mut dt = -(h00 * g[1] - b * g[0]) / det;
        let s_stuck = (s <= s_range.0 && ds < 0.0) || (s >= s_range.1 && ds > 0.0);
        let t_stuck = (t <= t_range.0 && dt < 0.0) || (t >= t_range.1 && dt > 0.0);
        match (s_stuck, t_stuck) {
            (true, true) => break,
            (true, false) => {
                ds = 0.0;
                dt = -g[1] / h11;
            }
            (false, true) => {
                dt = 0.0;
                ds = -g[0] / h00;
            }
            (false, false) => {}
        }
        if !(ds.is_finite() && dt.is_finite()) {
            break;
        }
        let mut accepted = false;
        let mut scale = 1.0;
        for _ in 0..12 {
            let ns = (s + scale * ds).clamp(s_range.0, s_range.1);
            let nt = (t + scale * dt).clamp(t_range.0, t_range.1);
            let (n1, n2) = (c1.eval(ns), c2.eval(nt));
            let nf = (n1.0 - n2.0).length_squared();
            if nf < f {
                (e1, e2) = (n1, n2);
                // Parameter change as a length: parameter step × speed, against the extent.
                let moved = ((ns - s) * a1.length())
                    .abs()
                    .max(((nt - t) * a2.length()).abs());
                s = ns;
                t = nt;
                f = nf;
                accepted = moved > accuracy;
                break;
            }
            scale *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    Approach {
        s,
        t,
        gap: f.sqrt(),
        points: (e1.0, e2.0),
        tangents: (e1.1, e2.1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;

    #[test]
    fn piece_evaluation_matches_the_kernel_derivatives() {
        // A rational quadratic quarter circle joined to a cubic-like tail: rational, several
        // pieces, unequal knot spans.
        let pts = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.2),
            DVec3::new(0.0, 1.0, 0.4),
            DVec3::new(-1.0, 2.0, 0.1),
            DVec3::new(-2.0, 0.5, 0.0),
        ];
        let w = vec![1.0, 0.7, 1.0, 1.3, 1.0];
        let knots = vec![0.0, 0.0, 0.0, 0.3, 0.5, 1.5, 1.5, 1.5];
        let c = NurbsCurve::try_new(2, knots, pts.to_vec(), Some(w)).expect("valid");
        let dec = c.bezier_decomposition();
        let e = PieceCurve::new(&dec);
        for i in 0..=40 {
            let t = 1.5 * (i as f64 + 0.5) / 41.0;
            let d = c.derivs(t);
            let (p, d1, d2) = e.eval(t);
            assert!((p - d.point).length() < 1e-12, "point at {t}");
            assert!(
                (d1 - d.d1).length() < 1e-9 * (1.0 + d.d1.length()),
                "C' at {t}"
            );
            assert!(
                (d2 - d.d2).length() < 1e-8 * (1.0 + d.d2.length()),
                "C'' at {t}"
            );
        }
    }
}
