//! Data parameters: chord length to start with (Dierckx 1993 §6.1, parcur with `ipar = 0`),
//! then foot-point projection onto the current fit (parameter correction, Hoschek 1988).

use glam::DVec3;

use crate::curve::NurbsCurve;

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

/// The foot point of `q` on `curve` near `t0`: Newton's method on `f(t) = C'(t)·(C(t) − q)`
/// kept inside `[lo, hi]`, a step taken only when it brings the curve point closer (a gradient
/// step where the squared distance is not convex). Returns the parameter and squared distance.
pub(crate) fn foot(
    curve: &NurbsCurve,
    q: DVec3,
    t0: f64,
    lo: f64,
    hi: f64,
    eps: f64,
) -> (f64, f64) {
    let mut t = t0.clamp(lo, hi);
    let mut d = curve.derivs(t);
    let mut dist2 = (d.point - q).length_squared();
    for _ in 0..NEWTON_STEPS {
        let r = d.point - q;
        let f = d.d1.dot(r);
        let fp = d.d2.dot(r) + d.d1.length_squared();
        let step = if fp > 0.0 {
            -f / fp
        } else {
            -f / d.d1.length_squared().max(f64::MIN_POSITIVE)
        };
        let next = (t + step).clamp(lo, hi);
        if (next - t).abs() <= eps {
            break;
        }
        let dn = curve.derivs(next);
        let dist2n = (dn.point - q).length_squared();
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
/// method on `f(t) = C'(t)·(C(t) − q)` started at the current parameter, kept inside the domain,
/// a step taken only when it brings the curve point closer), then sort the pairs by parameter.
/// The end parameters stay put (the ends are interpolated). Returns the largest change and
/// the sum of squared distances at the new parameters.
pub(crate) fn reproject(
    curve: &NurbsCurve,
    points: &mut [DVec3],
    params: &mut [f64],
) -> (f64, f64) {
    let (lo, hi) = curve.domain();
    let m = points.len();
    let mut largest: f64 = 0.0;
    let mut e = 0.0;
    let eps = (hi - lo) * 1e-14;
    for i in 1..m - 1 {
        let (t, dist2) = foot(curve, points[i], params[i], lo, hi, eps);
        largest = largest.max((t - params[i]).abs());
        e += dist2;
        params[i] = t;
    }
    if params.windows(2).any(|w| w[1] < w[0]) {
        let mut pairs: Vec<(f64, DVec3)> =
            params.iter().copied().zip(points.iter().copied()).collect();
        // Stable sort keeps the order of points with equal feet.
        pairs[1..m - 1].sort_by(|a, b| a.0.total_cmp(&b.0));
        for (i, (u, q)) in pairs.into_iter().enumerate() {
            params[i] = u;
            points[i] = q;
        }
    }
    (largest, e)
}
