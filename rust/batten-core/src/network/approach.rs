//! Closest approach of two curves: Newton's method on `|C1(s) − C2(t)|²`, evaluated on their
//! Bézier pieces.

use glam::DVec3;

use crate::curve::{BezierDecomposition, PointDerivs};

/// A closest approach: parameters on both curves and the distance there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Approach {
    pub s: f64,
    pub t: f64,
    pub gap: f64,
    /// The first curve's point at `s`.
    pub pa: DVec3,
    /// The second curve's point at `t`.
    pub pb: DVec3,
    /// The first curve's derivative at `s`.
    pub ta: DVec3,
    /// The second curve's derivative at `t`.
    pub tb: DVec3,
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
    c1: &BezierDecomposition,
    c2: &BezierDecomposition,
    start: (f64, f64),
    s_range: (f64, f64),
    t_range: (f64, f64),
    accuracy: f64,
) -> Approach {
    let (mut s, mut t) = start;
    // Points with derivatives at the current parameters; a trial point of the line search is
    // evaluated with its derivatives so an accepted one serves the next iteration.
    let (mut e1, mut e2) = (c1.derivs(s), c2.derivs(t));
    let mut f = (e1.point - e2.point).length_squared();
    for _ in 0..60 {
        if f <= accuracy * accuracy {
            break;
        }
        let PointDerivs {
            point: p1,
            d1: a1,
            d2: b1,
        } = e1;
        let PointDerivs {
            point: p2,
            d1: a2,
            d2: b2,
        } = e2;
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
            let (n1, n2) = (c1.derivs(ns), c2.derivs(nt));
            let nf = (n1.point - n2.point).length_squared();
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
        pa: e1.point,
        pb: e2.point,
        ta: e1.d1,
        tb: e2.d1,
    }
}
