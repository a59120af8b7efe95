//! Data parameters: chord length to start with (Dierckx 1993 §6.1, parcur with `ipar = 0`),
//! then foot-point projection onto the current fit (parameter correction, Hoschek 1988).

use glam::DVec3;

use super::clean::resolved_indices;
use crate::curve::{basis_funs, NurbsCurve, MAX_ORDER};

/// Newton steps per foot point; the start is already close, so a few suffice.
const NEWTON_STEPS: usize = 8;

/// Cumulative chord lengths: `u[0] = 0`, `u[i] = u[i-1] + |q[i] − q[i-1]|`.
pub(crate) fn chord_length(points: &[DVec3]) -> Vec<f64> {
    let mut u = Vec::with_capacity(points.len());
    let mut acc = 0.0;
    u.push(0.0);
    for w in points.windows(2) {
        acc += (w[1] - w[0]).length();
        u.push(acc);
    }
    u
}

/// Chord lengths at the data's resolution `step`: the points are grouped into runs about
/// `step` long (from one point of [`resolved`] to the next), the polyline through the first
/// point, the mean of each run and the last point is the data at that resolution, and each
/// point's parameter is the arc length along it of its foot on a segment next to its run's
/// mean (the nearer foot, clamped to the segment). Returned in the order of `points`, which it
/// may not be sorted in; the last parameter is the polyline's length.
///
/// Where the noise is larger than the point spacing, the plain chord length of the points
/// measures the noise: each step adds about `√2·σ` across the curve, so the parameters run
/// over many times the curve's length and drift along it like a random walk (2 m arc,
/// 100,000 points, σ = 1 mm: over 100 m). Nor do the points of [`resolved`] alone do: the
/// first point `step` away is the one whose noise carried it there, so their polyline is
/// too long as well (the same arc at `step` = 4 mm: 2.9 m at 10,000 points, 4.9 m at
/// 30,000). The mean of a run of `n` points is within `σ/√n` of the curve, so the polyline of
/// the means is as long as the curve to a fraction `σ²/(n·step²)`. With `step` below the
/// point spacing every run is one point and this is [`chord_length`].
pub(crate) fn resolved_chord_length(points: &[DVec3], step: f64) -> Vec<f64> {
    let m = points.len();
    let kept = resolved_indices(points, step);
    // Vertex j: the first point (j = 0), the mean of run j = kept[j]..kept[j + 1] (the last
    // run ending before the last point), the last point.
    let mut vertices = Vec::with_capacity(kept.len());
    vertices.push(points[0]);
    for w in kept[1..].windows(2) {
        let run = &points[w[0]..w[1]];
        vertices.push(run.iter().copied().sum::<DVec3>() / run.len() as f64);
    }
    vertices.push(points[m - 1]);
    let mut at = Vec::with_capacity(vertices.len());
    let mut acc = 0.0;
    at.push(0.0);
    for w in vertices.windows(2) {
        acc += (w[1] - w[0]).length();
        at.push(acc);
    }
    // The arc length of the foot of `q` on segment j (vertices j, j + 1) and its distance².
    let foot = |q: DVec3, j: usize| -> (f64, f64) {
        let (a, b) = (vertices[j], vertices[j + 1]);
        let len = at[j + 1] - at[j];
        let x = (q - a).dot((b - a).normalize_or_zero()).clamp(0.0, len);
        let p = a + (b - a).normalize_or_zero() * x;
        (at[j] + x, (q - p).length_squared())
    };
    let mut u = vec![0.0; m];
    for (run, w) in kept.windows(2).enumerate() {
        let single = w[1] - w[0] == 1;
        for i in w[0]..w[1] {
            if i == 0 {
                continue;
            }
            u[i] = if single {
                at[run]
            } else {
                let after = foot(points[i], run);
                if run == 0 {
                    after.0
                } else {
                    let before = foot(points[i], run - 1);
                    if before.1 < after.1 {
                        before.0
                    } else {
                        after.0
                    }
                }
            };
        }
    }
    u[m - 1] = acc;
    u
}

/// Sort the pairs of interior points and parameters by parameter (stable: points with equal
/// parameters keep their order); the end points stay first and last.
pub(crate) fn sort_by_parameter(points: &mut [DVec3], params: &mut [f64]) {
    let m = points.len();
    if params.windows(2).all(|w| w[0] <= w[1]) {
        return;
    }
    let mut pairs: Vec<(f64, DVec3)> = params.iter().copied().zip(points.iter().copied()).collect();
    pairs[1..m - 1].sort_by(|a, b| a.0.total_cmp(&b.0));
    for (i, (u, q)) in pairs.into_iter().enumerate() {
        params[i] = u;
        points[i] = q;
    }
}

/// The curve in piecewise power form, for the many evaluations of the foot-point search: on
/// each non-empty knot span `[u_s, u_{s+1})`, `C(u_s + x) = Σⱼ a[j]·xʲ`, with the Taylor
/// coefficients `a[j] = C⁽ʲ⁾(u_s)/j!` from the derivative control points (Piegl & Tiller
/// eq. 3.8, repeated). Position, first and second derivative are then one Horner pass, several
/// times cheaper than de Boor's derivative algorithm per evaluation. Non-rational curves only
/// (the fit is a polynomial B-spline).
struct PowerForm {
    starts: Vec<f64>,
    coefs: Vec<[DVec3; MAX_ORDER]>,
    degree: usize,
}

impl PowerForm {
    fn new(curve: &NurbsCurve) -> PowerForm {
        let p = curve.degree();
        let knots = curve.knots();
        // Derivative control points: level j has degree p − j on knots[j..len − j].
        let mut levels: Vec<Vec<DVec3>> = vec![curve.control_points()];
        for j in 1..=p {
            let prev = &levels[j - 1];
            let d = (p - j + 1) as f64;
            let next: Vec<DVec3> = (0..prev.len() - 1)
                .map(|i| {
                    let den = knots[i + p + 1] - knots[i + j];
                    if den > 0.0 {
                        (prev[i + 1] - prev[i]) * (d / den)
                    } else {
                        DVec3::ZERO
                    }
                })
                .collect();
            levels.push(next);
        }
        let n = levels[0].len();
        let mut starts = Vec::new();
        let mut coefs = Vec::new();
        let mut factorial = [1.0; MAX_ORDER];
        for j in 1..=p {
            factorial[j] = factorial[j - 1] * j as f64;
        }
        for s in p..n {
            let u = knots[s];
            if knots[s + 1] <= u {
                continue;
            }
            let mut a = [DVec3::ZERO; MAX_ORDER];
            for (j, level) in levels.iter().enumerate() {
                let mut b = [0.0; MAX_ORDER];
                basis_funs(&knots[j..knots.len() - j], s - j, u, p - j, &mut b);
                let mut v = DVec3::ZERO;
                for (r, &br) in b.iter().enumerate().take(p - j + 1) {
                    v += level[s - p + r] * br;
                }
                a[j] = v / factorial[j];
            }
            starts.push(u);
            coefs.push(a);
        }
        PowerForm {
            starts,
            coefs,
            degree: p,
        }
    }

    /// Position, first and second derivative at `t` (in the domain).
    #[inline]
    fn eval(&self, t: f64) -> (DVec3, DVec3, DVec3) {
        let i = self.starts.partition_point(|&u| u <= t).saturating_sub(1);
        let x = t - self.starts[i];
        let a = &self.coefs[i];
        let p = self.degree;
        let (mut c0, mut c1, mut c2) = (a[p], DVec3::ZERO, DVec3::ZERO);
        for j in (0..p).rev() {
            c2 = c2 * x + c1 * 2.0;
            c1 = c1 * x + c0;
            c0 = c0 * x + a[j];
        }
        (c0, c1, c2)
    }
}

/// The foot point of `q` on the curve near `t0`: Newton's method on `f(t) = C'(t)·(C(t) − q)`
/// kept inside `[lo, hi]`, a step taken only when it brings the curve point closer (a gradient
/// step where the squared distance is not convex). Returns the parameter and squared distance.
fn foot(curve: &PowerForm, q: DVec3, t0: f64, lo: f64, hi: f64, eps: f64) -> (f64, f64) {
    let mut t = t0.clamp(lo, hi);
    let mut d = curve.eval(t);
    let mut dist2 = (d.0 - q).length_squared();
    for _ in 0..NEWTON_STEPS {
        let r = d.0 - q;
        let f = d.1.dot(r);
        let fp = d.2.dot(r) + d.1.length_squared();
        let step = if fp > 0.0 {
            -f / fp
        } else {
            -f / d.1.length_squared().max(f64::MIN_POSITIVE)
        };
        let next = (t + step).clamp(lo, hi);
        if (next - t).abs() <= eps {
            break;
        }
        let dn = curve.eval(next);
        let dist2n = (dn.0 - q).length_squared();
        if dist2n > dist2 {
            break;
        }
        t = next;
        d = dn;
        dist2 = dist2n;
    }
    (t, dist2)
}

/// Move every interior parameter to the foot point of its data point on `curve` (Newton's
/// method on `f(t) = C'(t)·(C(t) − q)` started at the current parameter, kept between the
/// neighbouring points' parameters, a step taken only when it brings the curve point closer),
/// then sort the pairs by parameter.
///
/// With `min_gap` (points taken in their given order), the parameters of neighbouring points
/// stay at least `min_gap` times their distance apart instead, and keep their order. Without
/// it a fit with a kink is its own fixed point: the points on both sides of the kink have
/// their foot points at its tip, so their parameters meet, and the next fit, asked to pass
/// two points at one parameter, keeps the kink (KVLCC2's wl_z0.30: two offsets 3 cm apart at
/// one parameter after 20 corrections, a kink of radius 0.5 mm that folded the surface).
///
/// The end parameters stay put (the ends are interpolated). Returns the largest change and
/// the sum of squared distances at the new parameters. The curve is evaluated in power form
/// (see `PowerForm`), built once per call.
pub(crate) fn reproject(
    curve: &NurbsCurve,
    points: &mut [DVec3],
    params: &mut [f64],
    min_gap: Option<f64>,
) -> (f64, f64) {
    let (lo, hi) = curve.domain();
    let power = PowerForm::new(curve);
    let m = points.len();
    let eps = (hi - lo) * 1e-14;
    let old = params.to_vec();
    let mut dist2 = vec![0.0; m];
    for i in 1..m - 1 {
        // Each foot point stays between its neighbours' parameters before the step: a point
        // that jumped across a span (past a loop the fit made there) would leave the span
        // without data, and the next least-squares fit free to swing there without bound.
        let (a, b) = (old[i - 1].max(lo), old[i + 1].min(hi));
        let (a, b) = if a <= b { (a, b) } else { (lo, hi) };
        (params[i], dist2[i]) = foot(&power, points[i], params[i], a, b, eps);
    }
    if let Some(f) = min_gap {
        // Up from the start, then down from the end: every gap is kept (the end parameter is
        // the data's chord length, more than `f` times the sum of the gaps for `f` < 1).
        let gap = |i: usize| f * (points[i] - points[i - 1]).length();
        for i in 1..m - 1 {
            params[i] = params[i].max(params[i - 1] + gap(i));
        }
        for i in (1..m - 1).rev() {
            params[i] = params[i].min(params[i + 1] - gap(i + 1));
        }
        for i in 1..m - 1 {
            dist2[i] = (power.eval(params[i]).0 - points[i]).length_squared();
        }
    }
    // Each point's own change (before the pairs are sorted).
    let largest = (1..m - 1)
        .map(|i| (params[i] - old[i]).abs())
        .fold(0.0, f64::max);
    if min_gap.is_none() {
        sort_by_parameter(points, params);
    }
    (largest, dist2.iter().sum())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::KnotLayout;

    #[test]
    fn power_form_matches_de_boor() {
        let ctrl: Vec<DVec3> = (0..9)
            .map(|i| {
                let x = f64::from(i);
                DVec3::new(x, (0.7 * x).sin() * 2.0, 0.1 * x * x)
            })
            .collect();
        for order in 2..=6 {
            let curve =
                NurbsCurve::from_layout(&ctrl, None, order, KnotLayout::Endpoint, false).unwrap();
            let power = PowerForm::new(&curve);
            let (lo, hi) = curve.domain();
            for i in 0..=200 {
                let t = lo + (hi - lo) * f64::from(i) / 200.0;
                let d = curve.derivs(t);
                let (p, d1, d2) = power.eval(t);
                let scale = 1.0 + d.d2.length();
                assert!((p - d.point).length() < 1e-12, "order {order} t {t}: point");
                assert!(
                    (d1 - d.d1).length() < 1e-11 * scale,
                    "order {order} t {t}: d1"
                );
                if order > 2 {
                    assert!(
                        (d2 - d.d2).length() < 1e-10 * scale,
                        "order {order} t {t}: d2"
                    );
                }
            }
        }
    }

    #[test]
    fn with_min_gap_points_keep_their_order_and_gaps() {
        // On a straight fit two points the data give in one order have their foot points in
        // the other: without a minimum gap they are swapped, with one they keep their order
        // at least a quarter of their distance apart.
        let pts = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.6, 0.1, 0.0),
            DVec3::new(0.4, -0.1, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
        ];
        let u = chord_length(&pts);
        let line =
            NurbsCurve::try_new(1, vec![0.0, 0.0, u[3], u[3]], vec![pts[0], pts[3]], None).unwrap();
        let (mut p, mut t) = (pts.to_vec(), u.clone());
        reproject(&line, &mut p, &mut t, None);
        assert_eq!((p[1], p[2]), (pts[2], pts[1]), "swapped");
        let (mut p, mut t) = (pts.to_vec(), u.clone());
        let (_, e) = reproject(&line, &mut p, &mut t, Some(0.25));
        assert_eq!(p, pts, "the points keep their order");
        let gap = 0.25 * (pts[2] - pts[1]).length();
        assert!(t[2] - t[1] >= gap * (1.0 - 1e-12), "{t:?}");
        assert!(t[0] < t[1] && t[2] < t[3], "{t:?}");
        // The distances are those where the parameters end up.
        let at = |i: usize| line.point(t[i]).distance_squared(pts[i]);
        assert!((e - at(1) - at(2)).abs() < 1e-12, "{e}");
        assert!(
            at(2) > 0.1 * 0.1 + 1e-3,
            "p2 sits off its foot point: {}",
            at(2)
        );
    }
}
