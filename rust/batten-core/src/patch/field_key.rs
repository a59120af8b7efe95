//! Where along an edge its normal field turns: the curve's own parameter, kept from crowding
//! ([`FieldKey`]).
//!
//! An edge's normal field ([`EdgeNormal`](super::EdgeNormal)) blends the normals at its nodes
//! along the curve, in the curve's parameter. A fitted curve's parameter runs slowly where its
//! data are dense (Blender's NURBS knots are uniform, one unit per control point, and a fit
//! puts its control points densely where its data are), and data are dense where the section
//! turns: the field then turns where the curve turns, as the surface's normal does (a
//! waterline curling round a forefoot, the profile rising from the keel into the stem). But
//! data are also dense at a seam of the surface they were cut from: KCS's waterline at
//! z = 9 m spends one sixth of its parameter between the profile and station 1 on 3 cm at
//! x = 10.05 m, so its normal field turned 7° there, the faces' cross tangents with it, and the
//! patch above creased along a line from there (mesh faces at 40°).
//!
//! So the field runs in a key `k(t)` with `dk/dt = min(1, K·v(t)/v̄)` (a smooth minimum): the
//! parameter itself, except where the curve's speed `v` falls below `1/K` of its mean `v̄`
//! over the edge ([`MAX_CROWDING`] = `K`); there the key runs at `K` times the arc length's
//! mean rate. Both faces of the edge evaluate the field at the same curve parameter, so they
//! keep one tangent plane (G1).
//!
//! A Bézier spline's pieces meet tangentially but run at their own speeds, so its parameter's
//! rate per unit length jumps at every joint. There `dk/dt` jumps with the speed, and the key
//! runs at one rate per unit length through the joint: a field in the bare parameter turned at
//! one rate on one side and another after it, and every patch along the edge creased there.

use crate::curve::NurbsCurve;

use super::hermite::hermite_basis;
use super::speed::GAUSS;

/// Samples of the map per knot span of the curve inside the interval.
const SAMPLES_PER_SPAN: usize = 4;

/// `K`: how many times its mean rate (per unit of arc length) the key may run.
pub(crate) const MAX_CROWDING: f64 = 4.0;

/// The exponent of the smooth minimum in `dk/dt` (see the module's doc).
const SOFTNESS: i32 = 4;

/// The key `k(t)` of a curve's parameter over an interval (see the module's doc): a cubic
/// Hermite through its values at samples (Gauss–Legendre between them) with `dk/dt` there as
/// slopes, bounded as Fritsch & Carlson (1980) bound them so the map stays monotone; continued
/// past the interval's ends at the end slopes (nodes beyond an edge's ends shape its field's
/// slopes there). At a joint where the curve's derivative jumps (a Bézier spline's knot: the
/// pieces meet tangentially, but at different speeds), `dk/dt` jumps with the speed, so the
/// key, and the field with it, runs smoothly along the curve itself ([`joint_slopes`]).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FieldKey {
    ts: Vec<f64>,
    keys: Vec<f64>,
    /// `dk/dt` at each sample, on the span after it.
    slopes: Vec<f64>,
    /// `dk/dt` at each sample on the span before it: the same as `slopes` except at a joint
    /// where the curve's first derivative jumps ([`joint_slopes`]).
    slopes_before: Vec<f64>,
}

impl FieldKey {
    /// The map over `[lo, hi]` of `curve` (`lo < hi` within its domain); `None` where the
    /// curve has no measurable length there (the field then stays in the curve parameter).
    pub(crate) fn new(curve: &NurbsCurve, lo: f64, hi: f64) -> Option<FieldKey> {
        let (d0, d1) = curve.domain();
        let (lo, hi) = (lo.max(d0), hi.min(d1));
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return None;
        }
        let mut breaks: Vec<f64> = vec![lo];
        breaks.extend(curve.knots().iter().copied().filter(|&k| k > lo && k < hi));
        breaks.push(hi);
        breaks.dedup();
        let mut ts = Vec::with_capacity(breaks.len() * SAMPLES_PER_SPAN);
        for w in breaks.windows(2) {
            for q in 0..SAMPLES_PER_SPAN {
                ts.push(w[0] + (w[1] - w[0]) * q as f64 / SAMPLES_PER_SPAN as f64);
            }
        }
        ts.push(hi);
        // A break within an ulp or two of the next gives samples that round onto each other.
        ts.dedup_by(|b, a| *b <= *a);
        if ts.len() < 2 {
            return None;
        }
        // `derivs(t).d1` bit for bit, without the higher derivatives.
        let speed = |t: f64| curve.point_d1(t).1.length();
        // The curve's speed at the Gauss points of each interval between samples, taken once
        // for both integrals below (the length, then the key).
        let at_gauss: Vec<(f64, [f64; GAUSS.len()])> = ts
            .windows(2)
            .map(|w| {
                let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
                (half, GAUSS.map(|(x, _)| speed(mid + half * x)))
            })
            .collect();
        let integral = |f: &dyn Fn(f64) -> f64, (half, speeds): &(f64, [f64; GAUSS.len()])| {
            GAUSS
                .iter()
                .zip(speeds)
                .map(|(&(_, g), &v)| g * half * f(v))
                .sum::<f64>()
        };
        let length: f64 = at_gauss.iter().map(|i| integral(&|v| v, i)).sum();
        if !(length.is_finite() && length > 0.0) {
            return None;
        }
        let limit = MAX_CROWDING * (hi - lo) / length;
        // `dk/dt` where the curve runs at speed `v`.
        let rate_at = |v: f64| {
            let v = limit * v;
            if !v.is_finite() {
                return 1.0;
            }
            // A smooth min(1, v): 1 where the curve runs at its mean speed or faster.
            let p = SOFTNESS;
            (1.0 + v.powi(-p)).powf(-1.0 / f64::from(p))
        };
        let rate = |t: f64| rate_at(speed(t));
        let mut keys = Vec::with_capacity(ts.len());
        keys.push(0.0);
        for i in &at_gauss {
            keys.push(keys.last().copied().unwrap_or(0.0) + integral(&rate_at, i));
        }
        if !keys.iter().all(|k| k.is_finite()) {
            return None;
        }
        let chord = |i: usize| (keys[i + 1] - keys[i]) / (ts[i + 1] - ts[i]);
        let n = ts.len();
        let capped = |r: f64, cap: f64| {
            if cap.is_finite() {
                r.clamp(0.0, cap.max(0.0))
            } else {
                r
            }
        };
        let degree = curve.degree();
        let mut slopes = Vec::with_capacity(n);
        let mut slopes_before = Vec::with_capacity(n);
        for (i, &t) in ts.iter().enumerate() {
            let (before, after) = match (i, i + 1 == n) {
                (0, _) => (3.0 * chord(0), 3.0 * chord(0)),
                (_, true) => (3.0 * chord(n - 2), 3.0 * chord(n - 2)),
                _ => (3.0 * chord(i - 1), 3.0 * chord(i)),
            };
            let joint = i > 0 && i + 1 < n && degree > 0 && curve.multiplicity(t) >= degree;
            let sides = joint.then(|| {
                // The speed on the piece before the knot (the curve takes the one after it).
                let span = curve.knots().partition_point(|&k| k < t) - 1;
                let before = curve.derivs_in_span(span, t).d1.length();
                joint_slopes(&rate_at, before, speed(t))
            });
            match sides.flatten() {
                Some((left, right)) => {
                    slopes_before.push(capped(left, before));
                    slopes.push(capped(right, after));
                }
                None => {
                    let r = capped(rate(t), before.min(after));
                    slopes_before.push(r);
                    slopes.push(r);
                }
            }
        }
        Some(FieldKey {
            ts,
            keys,
            slopes,
            slopes_before,
        })
    }

    /// The key at curve parameter `t` (from 0 at the interval's start; negative before it).
    pub(crate) fn at(&self, t: f64) -> f64 {
        let n = self.ts.len();
        if t <= self.ts[0] {
            return self.keys[0] + self.slopes[0] * (t - self.ts[0]);
        }
        if t >= self.ts[n - 1] {
            return self.keys[n - 1] + self.slopes_before[n - 1] * (t - self.ts[n - 1]);
        }
        let i = self.ts.partition_point(|&x| x <= t) - 1;
        let h = self.ts[i + 1] - self.ts[i];
        let x = (t - self.ts[i]) / h;
        let [h00, h10, h01, h11] = hermite_basis(x);
        self.keys[i] * h00
            + self.slopes[i] * (h10 * h)
            + self.keys[i + 1] * h01
            + self.slopes_before[i + 1] * (h11 * h)
    }

    /// Whether `other` is this map bit for bit.
    pub(crate) fn same_bits(&self, other: &FieldKey) -> bool {
        same_bits(&self.ts, &other.ts)
            && same_bits(&self.keys, &other.keys)
            && same_bits(&self.slopes, &other.slopes)
            && same_bits(&self.slopes_before, &other.slopes_before)
    }
}

/// `dk/dt` on either side of a joint where the curve's derivative jumps (its speed is `v0`
/// before it and `v1` after it), so that the key runs at one rate per unit of arc length
/// through the joint: `dk/dt = g·v` on each side, `g` the mean of the two sides' own rates per
/// unit length `rate_at(v)/v`. Without this the field, blended in the key, turned at one rate
/// per unit length on one side of the joint and at another after it, and every patch along the
/// edge creased from there across its width: KVLCC2's station 7 (a Bézier spline whose handle
/// lengths double at a joint near the flat of bottom) made the face beside it fold its normal
/// by 4° within 0.2 mm, which no B-spline of the CAD export could follow within 0.1 mm. `None`
/// where either speed is not a positive finite number (the one slope of a smooth point is kept
/// then).
fn joint_slopes(rate_at: &dyn Fn(f64) -> f64, v0: f64, v1: f64) -> Option<(f64, f64)> {
    if !(v0.is_finite() && v1.is_finite() && v0 > 0.0 && v1 > 0.0) {
        return None;
    }
    let g = 0.5 * (rate_at(v0) / v0 + rate_at(v1) / v1);
    Some((g * v0, g * v1))
}

/// Whether `a` and `b` hold the same floats bit for bit (`==` would take −0 for 0 and refuse
/// NaN).
pub(super) fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::curve::KnotLayout;
    use glam::DVec3;

    /// A straight line from x = 0 to 6 whose control points bunch within 4 cm at x = 3 (a seam
    /// in the data), on uniform knots: its parameter spends about a third of itself there.
    pub(crate) fn crowded_line() -> NurbsCurve {
        let xs = [0.0, 1.0, 2.0, 3.0, 3.01, 3.02, 3.03, 3.04, 4.0, 5.0, 6.0];
        let pts: Vec<DVec3> = xs.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect();
        NurbsCurve::from_layout(&pts, None, 4, KnotLayout::Endpoint, false).unwrap()
    }

    /// The curve parameter where `c` (increasing in x) is at `x`.
    pub(crate) fn t_at(c: &NurbsCurve, x: f64) -> f64 {
        let (mut lo, mut hi) = c.domain();
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if c.point(mid).x < x {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn the_key_runs_with_the_parameter_but_never_crowds_more_than_k_times() {
        let c = crowded_line();
        let (lo, hi) = c.domain();
        let map = FieldKey::new(&c, lo, hi).unwrap();
        let (a, b) = (t_at(&c, 2.98), t_at(&c, 3.06));
        let t_share = (b - a) / (hi - lo);
        let key_share = (map.at(b) - map.at(a)) / (map.at(hi) - map.at(lo));
        // Measured: the parameter spends 0.38 of itself there, the key 0.079.
        assert!(t_share > 0.3, "the parameter crowds there: {t_share}");
        let arc_share = 0.08 / 6.0;
        assert!(
            key_share < 2.0 * MAX_CROWDING * arc_share,
            "the key spends {key_share} on 8 cm of 6 m"
        );
        // Away from the crowding the key is the parameter.
        let (p, q) = (t_at(&c, 0.5), t_at(&c, 1.5));
        let slope = (map.at(q) - map.at(p)) / (q - p);
        assert!(
            (slope - 1.0).abs() < 0.02,
            "dk/dt {slope} where the curve runs evenly"
        );
        for j in 0..200 {
            let t = lo + (hi - lo) * j as f64 / 200.0;
            let u = lo + (hi - lo) * (j + 1) as f64 / 200.0;
            assert!(map.at(u) > map.at(t), "monotone at {t}");
        }
        let end = map.at(hi);
        assert!(
            map.at(hi + 0.1) > end && map.at(lo - 0.1) < 0.0,
            "continued past the ends"
        );
    }

    /// A straight cubic Bézier spline from x = 0 to 9 in two pieces that meet tangentially at
    /// x = 3 with handles twice as long after the joint: its speed doubles there.
    fn line_with_a_joint() -> NurbsCurve {
        let xs = [0.0, 1.0, 2.0, 3.0, 5.0, 7.0, 9.0];
        let pts: Vec<DVec3> = xs.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
        NurbsCurve::try_new(3, knots, pts, None).unwrap()
    }

    #[test]
    fn the_key_runs_at_one_rate_per_unit_length_through_a_joint_of_two_speeds() {
        let c = line_with_a_joint();
        let map = FieldKey::new(&c, 0.0, 2.0).unwrap();
        let h = 1e-6;
        // dk/ds on either side of the joint at t = 1 (x = 3): the speed is 3 before, 6 after
        // (with one slope there, as the parameter runs, the ratio was 2).
        let before = (map.at(1.0) - map.at(1.0 - h)) / (3.0 * h);
        let after = (map.at(1.0 + h) - map.at(1.0)) / (6.0 * h);
        assert!(
            (before / after - 1.0).abs() < 1e-4,
            "dk/ds {before} before the joint, {after} after it"
        );
        for j in 0..200 {
            let (t, u) = (j as f64 / 100.0, (j + 1) as f64 / 100.0);
            assert!(map.at(u) > map.at(t), "monotone at {t}");
        }
        // A curve whose derivative is continuous keeps one slope at each sample.
        let smooth = crowded_line();
        let (lo, hi) = smooth.domain();
        let key = FieldKey::new(&smooth, lo, hi).unwrap();
        assert!(same_bits(&key.slopes, &key.slopes_before));
    }

    #[test]
    fn a_knot_an_ulp_inside_the_interval_gives_a_finite_map() {
        // Found by the fuzzer (a hull 1e7 m from the origin): samples an ulp apart made the
        // chord 0/0, and the slopes' clamp panicked on its NaN bound.
        let c = crowded_line();
        let knot = c.knots()[5];
        let lo = f64::from_bits(knot.to_bits() - 1);
        let map = FieldKey::new(&c, lo, c.domain().1).expect("a map");
        for j in 0..=100 {
            let t = lo + (c.domain().1 - lo) * j as f64 / 100.0;
            assert!(map.at(t).is_finite(), "finite at {t}");
        }
    }
}
