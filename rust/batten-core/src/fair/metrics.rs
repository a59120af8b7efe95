//! Fairness measures of a curve: inflections and curvature extrema in its best-fit plane, and
//! the bending energy ∫κ² ds; and the orthogonal deviation of points from a curve.

use glam::DVec3;

use crate::curve::CurveError;
use crate::curve::{segment_distance, Aabb, BezierDecomposition, NurbsCurve, GL8};

/// Curvature samples per non-empty knot span for counting sign changes and extrema.
const SAMPLES_PER_SPAN: usize = 24;
/// A sign change of the curvature counts as an inflection only when the curvature reaches this
/// fraction of the curve's largest |κ| on both sides (so the rounding wobble of a straight
/// part is not an inflection).
pub const INFLECTION_THRESHOLD: f64 = 0.01;
/// A curvature extremum counts only when κ rises or falls by this fraction of the largest |κ|
/// on both sides of it.
pub const EXTREMUM_THRESHOLD: f64 = 0.02;

/// Fairness of one curve, the figures a designer reads off a curvature comb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FairnessMetrics {
    /// Sign changes of the curvature in the best-fit plane, ignoring changes where |κ| stays
    /// below [`INFLECTION_THRESHOLD`] × max |κ|; counted within each smooth piece (a knuckle
    /// is not an inflection).
    pub inflections: usize,
    /// Interior local extrema of the signed in-plane curvature with a rise or fall of at least
    /// [`EXTREMUM_THRESHOLD`] × max |κ| on either side.
    pub curvature_extrema: usize,
    /// The bending energy ∫κ² ds over the whole curve (1/m), the usual fairness functional.
    pub fairness_energy: f64,
    /// Largest curvature |κ| found (1/m).
    pub max_curvature: f64,
    /// Unit normal of the best-fit plane of the control points (least-squares plane).
    pub plane_normal: DVec3,
}

/// Fairness measures of `curve`: inflections and curvature extrema of the signed curvature
/// `κ = (C′ × C″)·n / |C′|³` in the best-fit plane (normal `n`), sampled densely per knot
/// span, and ∫κ² ds by 8-point Gauss–Legendre per span with the space curvature
/// `|C′ × C″| / |C′|³` (the fairness criteria of the H-rep paper §4 and of Dierckx 1993 §5.1).
pub fn fairness_metrics(curve: &NurbsCurve) -> FairnessMetrics {
    curvature_samples(curve, true).metrics
}

/// One sample of the signed in-plane curvature.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CurvatureSample {
    /// Curve parameter.
    pub t: f64,
    /// Signed curvature in the best-fit plane.
    pub kappa: f64,
    /// Arc length the sample stands for (`|C′|·Δt`).
    pub ds: f64,
}

/// The samples [`fairness_metrics`] counts on, per smooth piece, with the metrics.
pub(crate) struct CurvatureSamples {
    pub pieces: Vec<Vec<CurvatureSample>>,
    pub metrics: FairnessMetrics,
}

/// The curvature samples of `curve` ([`SAMPLES_PER_SPAN`] per knot span, at the middles of
/// equal parameter steps, split into smooth pieces at knots of multiplicity ≥ degree) and its
/// [`FairnessMetrics`]; `fairness_energy` is left 0 unless `energy`.
pub(crate) fn curvature_samples(curve: &NurbsCurve, energy: bool) -> CurvatureSamples {
    let n = best_fit_normal(&curve.control_points());
    let bez = curve.bezier_decomposition();
    let p = curve.degree();
    let knots = curve.knots();
    let (start, end) = curve.domain();
    // Smooth pieces: split where a knot's multiplicity reaches the degree (C0 or worse).
    let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    let mut i = p;
    while i < knots.len() - p - 1 {
        let (t0, t1) = (knots[i], knots[i + 1]);
        if t0 >= start && t1 <= end && t1 > t0 {
            let spans = pieces.last_mut().expect("one piece at least");
            spans.push((t0, t1));
            let mult = knots.iter().filter(|&&u| u == t1).count();
            if t1 < end && mult >= p {
                pieces.push(Vec::new());
            }
        }
        i += 1;
    }
    let mut samples: Vec<Vec<CurvatureSample>> = Vec::with_capacity(pieces.len());
    let mut kmax: f64 = 0.0;
    for spans in &pieces {
        let mut ks = Vec::with_capacity(spans.len() * SAMPLES_PER_SPAN);
        for &(t0, t1) in spans {
            let dt = (t1 - t0) / SAMPLES_PER_SPAN as f64;
            for j in 0..SAMPLES_PER_SPAN {
                let t = t0 + dt * (j as f64 + 0.5);
                let (d1, d2) = piece_derivs(&bez, t);
                let speed = d1.length();
                let kappa = if speed > 0.0 {
                    curvature_vector(d1, d2, speed).dot(n)
                } else {
                    0.0
                };
                kmax = kmax.max(kappa.abs());
                ks.push(CurvatureSample {
                    t,
                    kappa,
                    ds: speed * dt,
                });
            }
        }
        samples.push(ks);
    }
    let infl_thr = INFLECTION_THRESHOLD * kmax;
    let ext_thr = EXTREMUM_THRESHOLD * kmax;
    let kappas = |ks: &Vec<CurvatureSample>| ks.iter().map(|s| s.kappa).collect::<Vec<f64>>();
    let metrics = FairnessMetrics {
        inflections: samples
            .iter()
            .map(|ks| sign_changes(ks.iter().map(|s| s.kappa), infl_thr).len())
            .sum(),
        curvature_extrema: samples
            .iter()
            .map(|ks| count_extrema(&kappas(ks), ext_thr))
            .sum(),
        fairness_energy: if energy { energy_on(&bez, curve) } else { 0.0 },
        max_curvature: kmax,
        plane_normal: n,
    };
    CurvatureSamples {
        pieces: samples,
        metrics,
    }
}

/// The bending energy ∫κ² ds of `curve` alone (the `fairness_energy` of
/// [`fairness_metrics`]).
pub(crate) fn bending_energy(curve: &NurbsCurve) -> f64 {
    energy_on(&curve.bezier_decomposition(), curve)
}

/// The curvature variation ∫κ′² ds of `curve` (1/m³), `κ′ = dκ/ds` of the signed curvature in
/// the best-fit plane: the minimum-variation functional of Moreton & Séquin (1994) that the
/// surface-fairing paper (Pla et al. 1998, §3) names the better fairness measure. Per knot span
/// by two 8-point Gauss–Legendre panels with `dκ/dt = ((C′×C‴)·n − 3κ|C′|(C′·C″))/|C′|³` and
/// `ds = |C′| dt`; a curvature jump at a knot (a knuckle, a C1 joint) is not variation inside a
/// span and is left out.
pub fn curvature_variation(curve: &NurbsCurve) -> f64 {
    let n = best_fit_normal(&curve.control_points());
    let (start, end) = curve.domain();
    let mut total = 0.0;
    for (span, w) in curve.knots().windows(2).enumerate() {
        let (t0, t1) = (w[0], w[1]);
        if !(t0 >= start && t1 <= end && t1 > t0) {
            continue;
        }
        for (a, b) in [(t0, 0.5 * (t0 + t1)), (0.5 * (t0 + t1), t1)] {
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            for &(x, weight) in &GL8 {
                let d = curve.derivs_in_span(span, mid + half * x);
                let speed = d.d1.length();
                if speed > 0.0 {
                    let u = d.d1 / speed;
                    let kappa = curvature_vector(d.d1, d.d2, speed).dot(n);
                    let dk_dt =
                        u.cross(d.d3 / speed).dot(n) / speed - 3.0 * kappa * u.dot(d.d2) / speed;
                    // (dκ/ds)² ds = (dκ/dt)² / |C′| dt.
                    total += weight * half * dk_dt * (dk_dt / speed);
                }
            }
        }
    }
    total
}

/// ∫κ² ds of `curve` span by span, evaluated on its Bézier decomposition `bez`.
fn energy_on(bez: &BezierDecomposition, curve: &NurbsCurve) -> f64 {
    let (start, end) = curve.domain();
    curve
        .knots()
        .windows(2)
        .filter(|w| w[0] >= start && w[1] <= end && w[1] > w[0])
        .map(|w| span_energy(&|t| piece_derivs(bez, t), w[0], w[1]))
        .sum()
}

/// First and second derivative at `t` on the Bézier piece holding it (de Casteljau, no
/// basis-function tables); `t` is inside a span.
fn piece_derivs(bez: &BezierDecomposition, t: f64) -> (DVec3, DVec3) {
    let d = bez.derivs(t);
    (d.d1, d.d2)
}

/// `C′ × C″ / |C′|³` (curvature times the binormal) from the unit tangent, one power of the
/// speed at a time: `|C′|³` and `|C′|⁶` underflow to zero, and the quotient to 0/0, at speeds
/// that f64 still holds (below about 1e-51 and 1e-103).
fn curvature_vector(d1: DVec3, d2: DVec3, speed: f64) -> DVec3 {
    (d1 / speed).cross(d2 / speed) / speed
}

/// `|v|` without squaring `v` itself (its squares overflow beyond about 1.3e154, a curvature
/// f64 holds): the largest component times the length of `v` over it.
fn scaled_length(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        m * (v / m).length()
    } else {
        m
    }
}

fn span_energy(derivs: &impl Fn(f64) -> (DVec3, DVec3), t0: f64, t1: f64) -> f64 {
    // Two Gauss–Legendre panels per span: κ²|C′| is smooth but not polynomial.
    let mut total = 0.0;
    for (a, b) in [(t0, 0.5 * (t0 + t1)), (0.5 * (t0 + t1), t1)] {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        for &(x, w) in &GL8 {
            let (d1, d2) = derivs(mid + half * x);
            let speed = d1.length();
            if speed > 0.0 {
                // κ · (κ ds): κ² alone overflows on tiny curves (radius 1e-152) whose energy,
                // the turning angle over the radius, f64 holds; and so would |κ| taken as √(κ·κ).
                let k = scaled_length(curvature_vector(d1, d2, speed));
                total += k * (w * k * speed * half);
            }
        }
    }
    total
}

/// The indices at which a sign change completes, with hysteresis: a change counts when κ goes
/// from below −thr to above +thr or back (the first sample beyond the threshold on the new
/// side).
pub(crate) fn sign_changes(ks: impl IntoIterator<Item = f64>, thr: f64) -> Vec<usize> {
    let mut state = 0i8;
    let mut at = Vec::new();
    for (i, k) in ks.into_iter().enumerate() {
        let sign = if k > thr {
            1
        } else if k < -thr {
            -1
        } else {
            continue;
        };
        if state != 0 && sign != state {
            at.push(i);
        }
        state = sign;
    }
    at
}

/// Interior extrema with hysteresis `thr`: a maximum counts once κ has fallen `thr` below it,
/// a minimum once κ has risen `thr` above it.
fn count_extrema(ks: &[f64], thr: f64) -> usize {
    let Some(&first) = ks.first() else { return 0 };
    let (mut hi, mut lo) = (first, first);
    // 0: direction unknown, 1: rising (looking for a maximum), -1: falling.
    let mut dir = 0i8;
    let mut count = 0;
    for &k in &ks[1..] {
        match dir {
            0 => {
                hi = hi.max(k);
                lo = lo.min(k);
                if k > lo + thr && k >= hi {
                    dir = 1;
                    hi = k;
                } else if k < hi - thr && k <= lo {
                    dir = -1;
                    lo = k;
                }
            }
            1 => {
                if k > hi {
                    hi = k;
                } else if k < hi - thr {
                    count += 1;
                    dir = -1;
                    lo = k;
                }
            }
            _ => {
                if k < lo {
                    lo = k;
                } else if k > lo + thr {
                    count += 1;
                    dir = 1;
                    hi = k;
                }
            }
        }
    }
    count
}

/// Unit normal of the least-squares plane through `points`: the eigenvector of the smallest
/// eigenvalue of their covariance (cyclic Jacobi). A straight or degenerate set gives some
/// unit vector perpendicular to its main direction.
pub(crate) fn best_fit_normal(points: &[DVec3]) -> DVec3 {
    let m = points.len().max(1) as f64;
    let c = points.iter().copied().sum::<DVec3>() / m;
    let mut a = [[0.0f64; 3]; 3];
    for p in points {
        let d = (*p - c).to_array();
        for (i, row) in a.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v += d[i] * d[j];
            }
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-15 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let cs = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * cs;
            // A ← Jᵀ A J for the rotation in the (p, q) plane.
            for row in a.iter_mut() {
                let (x, y) = (row[p], row[q]);
                row[p] = cs * x - sn * y;
                row[q] = sn * x + cs * y;
            }
            let (rp, rq) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = cs * rp[k] - sn * rq[k];
                a[q][k] = sn * rp[k] + cs * rq[k];
            }
            for row in v.iter_mut() {
                let (x, y) = (row[p], row[q]);
                row[p] = cs * x - sn * y;
                row[q] = sn * x + cs * y;
            }
        }
    }
    let k = (0..3)
        .min_by(|&i, &j| a[i][i].total_cmp(&a[j][j]))
        .expect("three eigenvalues");
    let n = DVec3::new(v[0][k], v[1][k], v[2][k]);
    let n = n.normalize_or_zero();
    if n == DVec3::ZERO {
        DVec3::Z
    } else {
        // A fixed orientation: the largest component positive, so the sign of κ is stable.
        let arr = n.to_array();
        let big = (0..3)
            .max_by(|&i, &j| arr[i].abs().total_cmp(&arr[j].abs()))
            .expect("three components");
        if arr[big] < 0.0 {
            -n
        } else {
            n
        }
    }
}

/// Orthogonal deviations of points from a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Deviation {
    pub max: f64,
    pub max_index: usize,
    pub rms: f64,
}

/// Largest and RMS distance of `points` from `curve`: each the global closest-point distance
/// (branch and bound on the Bézier decomposition, built once).
///
/// Implementation note: the search for each point is run on the pieces that can hold its
/// closest point only: a piece whose lower bound (control-point box, chord less flatness,
/// computed once per piece) exceeds the distance to a known curve point (the nearest piece end
/// or the previous point's foot) cannot, so the answer is the same global minimum as over all
/// pieces, at a fraction of the cost on curves with many knots.
pub(crate) fn deviation(curve: &NurbsCurve, points: &[DVec3]) -> Result<Deviation, CurveError> {
    let mut out = Deviation {
        max: 0.0,
        max_index: 0,
        rms: 0.0,
    };
    let mut sum2 = 0.0;
    for (i, d) in distances(curve, points)?.into_iter().enumerate() {
        sum2 += d * d;
        if d > out.max {
            out.max = d;
            out.max_index = i;
        }
    }
    out.rms = (sum2 / points.len().max(1) as f64).sqrt();
    Ok(out)
}

/// The distance of each of `points` (in order along the curve, for speed) from `curve`: the
/// global closest-point distance, as [`deviation`] measures it.
pub(crate) fn distances(curve: &NurbsCurve, points: &[DVec3]) -> Result<Vec<f64>, CurveError> {
    let bez = curve.bezier_decomposition();
    let size = bez.hull_box().diagonal();
    let accuracy = (size * 1e-10).max(1e-12);
    let bounds: Vec<(Aabb, DVec3, DVec3, f64)> = bez
        .pieces
        .iter()
        .map(|p| {
            let (a, b) = p.ends();
            (p.hull_box(), a, b, p.flatness())
        })
        .collect();
    let mut sub = bez.empty_like();
    let mut out = Vec::with_capacity(points.len());
    let mut last_t: Option<f64> = None;
    let mut step: Option<f64> = None;
    let mut lower = vec![0.0; bez.pieces.len()];
    for q in points {
        for (l, (boxed, a, b, flat)) in lower.iter_mut().zip(&bounds) {
            *l = boxed
                .distance_to(*q)
                .max(segment_distance(*q, *a, *b) - flat);
        }
        // Fast path: the piece of the previous point's foot, when the distance is convex on
        // it (one minimum, found exactly) and no other piece can come closer.
        let k = last_t.map_or(0, |t| bez.piece_at(t, false));
        let piece = &bez.pieces[k];
        let local = piece.distance_convex(*q).then(|| {
            // Newton from the previous foot moved on by the last step along the curve.
            let (t, point) = match (last_t, step) {
                (Some(t), Some(dt)) => piece.convex_foot_near(*q, t + dt),
                _ => piece.convex_foot(*q),
            };
            (t, (point - *q).length())
        });
        let proven = local.filter(|&(_, d)| {
            lower
                .iter()
                .enumerate()
                .all(|(j, &l)| j == k || l >= d - accuracy)
        });
        let (t, d) = match proven {
            Some(found) => found,
            None => {
                // An upper bound of the distance: a curve point near q.
                let mut upper = last_t.map_or(f64::INFINITY, |t| (curve.point(t) - *q).length());
                for (_, a, b, _) in &bounds {
                    upper = upper.min((*a - *q).length()).min((*b - *q).length());
                }
                bez.select_into(&mut sub, |k| lower[k] <= upper);
                let near = sub.nearest(*q, accuracy)?;
                (near.t, near.distance)
            }
        };
        step = last_t.map(|l| t - l);
        last_t = Some(t);
        out.push(d);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_normal_of_a_tilted_planar_set() {
        let n = DVec3::new(1.0, 2.0, 2.0).normalize();
        let u = n.any_orthonormal_vector();
        let w = n.cross(u);
        let pts: Vec<DVec3> = (0..20)
            .map(|i| {
                let a = f64::from(i) * 0.3;
                u * a.cos() * 3.0 + w * a.sin() + DVec3::new(5.0, -1.0, 2.0)
            })
            .collect();
        let got = best_fit_normal(&pts);
        assert!(got.cross(n).length() < 1e-10, "normal {got} vs {n}");
    }

    #[test]
    fn bending_energy_of_a_circular_arc_is_its_angle_over_the_radius() {
        // A quarter circle of radius r (exact rational quadratic), split at a knot: κ = 1/r
        // over length πr/2, so ∫κ² ds = π/(2r). The reported metrics carry the same sum.
        let r = 2.0;
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let quarter = NurbsCurve::try_new(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![
                DVec3::new(r, 0., 0.),
                DVec3::new(r, r, 0.),
                DVec3::new(0., r, 0.),
            ],
            Some(vec![1., w, 1.]),
        )
        .unwrap();
        let arc = quarter.insert_knot(0.4, 1).unwrap();
        assert_eq!(arc.knots().len(), 7, "two spans");
        let e = bending_energy(&arc);
        let exact = std::f64::consts::PI / (2.0 * r);
        assert!((e - exact).abs() < 1e-9 * exact, "{e} vs {exact}");
        assert_eq!(
            fairness_metrics(&arc).fairness_energy,
            e,
            "the metrics' energy"
        );
    }

    #[test]
    fn hysteresis_counts() {
        let ks = [1.0, 0.5, 0.001, -0.001, 0.002, -0.5, -1.0, -0.2, 0.3];
        assert_eq!(
            sign_changes(ks, 0.01),
            [5, 8],
            "two real changes, where they complete"
        );
        let ks = [0.0, 1.0, 2.0, 1.0, 1.01, 0.0, 0.5];
        assert_eq!(count_extrema(&ks, 0.1), 2, "max at 2, min at 0");
    }
}
