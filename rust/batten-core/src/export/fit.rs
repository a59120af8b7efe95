//! Least-squares B-spline approximation with refinement where the error is over the budget
//! (Piegl & Tiller §9.4.1 for the fixed-end curve fit, §9.4.3 for the tensor-product surface
//! fit, here solved direction by direction; knots halved where the measured deviation is too
//! large, as in their error-bounded approximation §9.4.4).
//!
//! A surface is fitted inside four given boundary curves: its first and last rows and columns
//! are their control points (after exact knot insertion), so two surfaces fitted inside the same
//! curve meet on that curve exactly, and only the interior control points are free.

use glam::DVec3;

use super::bspline::{
    basis, clamped, curve, interior, knot_union, refined_points, BsplineSurface, EXPORT_DEGREE,
};
use crate::curve::NurbsCurve;
use crate::fair::BandedQr;

/// Least-squares samples per knot span, at these fractions of the span (the Gauss-like
/// midpoints of four equal parts): enough to fix the cubic's control points, none on a knot.
const FIT_FRACTIONS: [f64; 4] = [0.125, 0.375, 0.625, 0.875];

/// Where the deviation is measured in each span: at the knot and at the odd sixteenths, twice
/// as dense as the fit samples and never on them (a sparser check let a one-span face reach
/// 1.8× its check deviation between the samples, on Wigley's bow).
const CHECK_FRACTIONS: [f64; 9] = [
    0.0, 0.0625, 0.1875, 0.3125, 0.4375, 0.5625, 0.6875, 0.8125, 0.9375,
];

/// The most knot spans of a fitted curve: an edge needing more (about 1/1024 of it per span)
/// is not smooth enough to export, and refining further would only hide that.
pub const MAX_CURVE_SPANS: usize = 1024;

/// The most knot spans along one direction of a fitted face (a long, curved patch may need
/// many along its length).
pub const MAX_SURFACE_SPANS: usize = 512;

/// The most knot spans of a fitted face in all (spans along u × spans along v): each halving
/// doubles the work in both directions, and a patch not within the tolerance at this many is
/// singular or folded somewhere (a repaired degenerate corner, a fold the build reports),
/// which more spans would only chase into a point.
pub const MAX_SURFACE_CELLS: usize = 8192;

/// Why a fit failed: it did not reach the tolerance within its most spans, or its least-squares
/// system was singular (the deviation reached so far is given).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FitFailed {
    /// The largest deviation of the last fit (m), infinite when no fit was made.
    pub(crate) deviation: f64,
}

/// The distinct knots of a clamped knot vector (span ends, 0 and 1 included).
fn breakpoints(knots: &[f64]) -> Vec<f64> {
    let mut b: Vec<f64> = Vec::new();
    for &k in &knots[EXPORT_DEGREE..knots.len() - EXPORT_DEGREE] {
        if b.last() != Some(&k) {
            b.push(k);
        }
    }
    b
}

/// Parameters at `fractions` of every span between `breaks` (and 1 at the end when `ends`).
fn span_samples(breaks: &[f64], fractions: &[f64], ends: bool) -> Vec<(usize, f64)> {
    let mut out = Vec::new();
    for (k, w) in breaks.windows(2).enumerate() {
        out.extend(fractions.iter().map(|f| (k, w[0] + f * (w[1] - w[0]))));
    }
    if ends {
        out.push((breaks.len() - 2, 1.0));
    }
    out
}

/// `interior` with a knot added in the middle of every span `k` whose flag is set.
fn bisected(interior: &[f64], breaks: &[f64], over: &[bool]) -> Vec<f64> {
    let mut out = interior.to_vec();
    out.extend(
        breaks
            .windows(2)
            .zip(over)
            .filter(|(_, &o)| o)
            .map(|(w, _)| 0.5 * (w[0] + w[1])),
    );
    out.sort_by(f64::total_cmp);
    out
}

/// One least-squares observation of the interior control points `1..count − 1` at a sample
/// whose basis is `(span, n)`: the row's first unknown and its entries (end columns dropped).
fn interior_row(span: usize, n: &[f64], count: usize) -> (usize, Vec<f64>) {
    let p = EXPORT_DEGREE;
    let lo = (span - p).max(1);
    let hi = span.min(count - 2);
    let row = (lo..=hi).map(|c| n[c - (span - p)]).collect();
    (lo - 1, row)
}

/// Solve the least squares of the interior control points for one right-hand side per sample
/// (`rows` from [`interior_row`], in sample order); `None` when singular.
fn solve_interior(rows: &[(usize, Vec<f64>)], rhs: &[DVec3], count: usize) -> Option<Vec<DVec3>> {
    let mut qr = BandedQr::new(count - 2, EXPORT_DEGREE + 1);
    let mut h = Vec::with_capacity(EXPORT_DEGREE + 1);
    for ((first, row), &r) in rows.iter().zip(rhs) {
        if row.is_empty() {
            continue;
        }
        h.clear();
        h.extend_from_slice(row);
        qr.add_row(*first, &mut h, r);
    }
    qr.solve()
}

/// The cubic B-spline on `[0, 1]` through `f(0)` and `f(1)` that approximates `f` within `tol`
/// at every check sample, starting from the interior knots `initial` and halving every span
/// over the tolerance. Returns the curve and its measured deviation.
pub(crate) fn fit_curve(
    f: impl Fn(f64) -> DVec3,
    initial: &[f64],
    tol: f64,
) -> Result<(NurbsCurve, f64), FitFailed> {
    let (start, end) = (f(0.0), f(1.0));
    let mut knots_in = initial.to_vec();
    let mut deviation = f64::INFINITY;
    loop {
        let knots = clamped(&knots_in);
        let count = knots_in.len() + EXPORT_DEGREE + 1;
        let breaks = breakpoints(&knots);
        let samples = span_samples(&breaks, &FIT_FRACTIONS, false);
        let mut rows = Vec::with_capacity(samples.len());
        let mut rhs = Vec::with_capacity(samples.len());
        for &(_, t) in &samples {
            let (span, n) = basis(&knots, count, t);
            let first = span - EXPORT_DEGREE;
            let mut r = f(t);
            for (j, &nj) in n[..=EXPORT_DEGREE].iter().enumerate() {
                if first + j == 0 {
                    r -= start * nj;
                } else if first + j == count - 1 {
                    r -= end * nj;
                }
            }
            rows.push(interior_row(span, &n, count));
            rhs.push(r);
        }
        let inner = solve_interior(&rows, &rhs, count).ok_or(FitFailed { deviation })?;
        let mut points = Vec::with_capacity(count);
        points.push(start);
        points.extend(inner);
        points.push(end);
        let c = curve(knots, points).ok_or(FitFailed { deviation })?;
        let mut over = vec![false; breaks.len() - 1];
        deviation = 0.0;
        for (k, t) in span_samples(&breaks, &CHECK_FRACTIONS, true) {
            let d = (c.point(t) - f(t)).length();
            deviation = deviation.max(d);
            over[k] |= d > tol;
        }
        if !over.contains(&true) {
            return Ok((c, deviation));
        }
        if breaks.len() > MAX_CURVE_SPANS {
            return Err(FitFailed { deviation });
        }
        knots_in = bisected(&knots_in, &breaks, &over);
    }
}

/// The four boundary curves of a quad, each on `[0, 1]`: `bottom` (`v = 0`) and `top`
/// (`v = 1`) along `u`, `left` (`u = 0`) and `right` (`u = 1`) along `v`, meeting at the
/// corners.
#[derive(Clone, Debug)]
pub(crate) struct QuadBoundary {
    /// `S(u, 0)`.
    pub(crate) bottom: NurbsCurve,
    /// `S(u, 1)`.
    pub(crate) top: NurbsCurve,
    /// `S(0, v)`.
    pub(crate) left: NurbsCurve,
    /// `S(1, v)`.
    pub(crate) right: NurbsCurve,
}

/// The basis of every sample along one direction.
fn bases(knots: &[f64], count: usize, ts: &[(usize, f64)]) -> Vec<(usize, [f64; 16])> {
    ts.iter().map(|&(_, t)| basis(knots, count, t)).collect()
}

/// The bicubic surface inside `boundary` that approximates `target` within `tol` at every
/// check sample (or, where refining cannot get there — a singular system near a degenerate
/// corner, or [`MAX_SURFACE_SPANS`] or [`MAX_SURFACE_CELLS`] reached —, the last fit if it is within `limit`): boundary rows and columns from the curves (knot vectors the union of the
/// opposite curves', refined by exact knot insertion), interior control points by least
/// squares on a grid of samples, solved along `u` then along `v` (the tensor-product system
/// separates); spans over the tolerance are halved in both directions and the fit is made
/// again. Returns the surface and its measured deviation.
pub(crate) fn fit_surface(
    target: impl Fn(f64, f64) -> DVec3,
    boundary: &QuadBoundary,
    tol: f64,
    limit: f64,
) -> Result<(BsplineSurface, f64), FitFailed> {
    let mut best: Option<(BsplineSurface, f64)> = None;
    let give_up = |best: Option<(BsplineSurface, f64)>, deviation: f64| match best {
        Some((s, d)) if d <= limit => Ok((s, d)),
        _ => Err(FitFailed { deviation }),
    };
    let mut ku = knot_union(
        interior(boundary.bottom.knots()),
        interior(boundary.top.knots()),
    );
    let mut kv = knot_union(
        interior(boundary.left.knots()),
        interior(boundary.right.knots()),
    );
    let mut deviation = f64::INFINITY;
    loop {
        let (knots_u, knots_v) = (clamped(&ku), clamped(&kv));
        let (nu, nv) = (ku.len() + EXPORT_DEGREE + 1, kv.len() + EXPORT_DEGREE + 1);
        let rows = [
            refined_points(&boundary.bottom, &ku),
            refined_points(&boundary.top, &ku),
            refined_points(&boundary.left, &kv),
            refined_points(&boundary.right, &kv),
        ];
        let [Some(bottom), Some(top), Some(left), Some(right)] = rows else {
            return give_up(best, deviation);
        };
        let mut control = vec![DVec3::ZERO; nu * nv];
        for j in 1..nv - 1 {
            control[j] = left[j];
            control[(nu - 1) * nv + j] = right[j];
        }
        for i in 0..nu {
            control[i * nv] = bottom[i];
            control[i * nv + nv - 1] = top[i];
        }
        let mut surface = BsplineSurface {
            knots_u,
            knots_v,
            count_u: nu,
            count_v: nv,
            control,
        };
        let (bu, bv) = (breakpoints(&surface.knots_u), breakpoints(&surface.knots_v));
        let (us, vs) = (
            span_samples(&bu, &FIT_FRACTIONS, false),
            span_samples(&bv, &FIT_FRACTIONS, false),
        );
        // Right-hand sides: the target less what the fixed boundary contributes.
        let residual: Vec<Vec<DVec3>> = us
            .iter()
            .map(|&(_, u)| {
                vs.iter()
                    .map(|&(_, v)| target(u, v) - surface.eval(u, v))
                    .collect()
            })
            .collect();
        let (basis_u, basis_v) = (
            bases(&surface.knots_u, nu, &us),
            bases(&surface.knots_v, nv, &vs),
        );
        let rows_u: Vec<_> = basis_u
            .iter()
            .map(|(s, n)| interior_row(*s, n, nu))
            .collect();
        let rows_v: Vec<_> = basis_v
            .iter()
            .map(|(s, n)| interior_row(*s, n, nv))
            .collect();
        // Along u for every v sample: y[b][i] for the interior columns i.
        let mut y: Vec<Vec<DVec3>> = Vec::with_capacity(vs.len());
        for b in 0..vs.len() {
            let rhs: Vec<DVec3> = residual.iter().map(|r| r[b]).collect();
            match solve_interior(&rows_u, &rhs, nu) {
                Some(col) => y.push(col),
                None => return give_up(best, deviation),
            }
        }
        // Along v for every interior column.
        for i in 1..nu - 1 {
            let rhs: Vec<DVec3> = y.iter().map(|yb| yb[i - 1]).collect();
            let Some(x) = solve_interior(&rows_v, &rhs, nv) else {
                return give_up(best, deviation);
            };
            for (j, p) in x.into_iter().enumerate() {
                surface.control[i * nv + j + 1] = p;
            }
        }
        if !surface.control.iter().all(|p| p.is_finite()) {
            return give_up(best, deviation);
        }
        let (mut over_u, mut over_v) = (vec![false; bu.len() - 1], vec![false; bv.len() - 1]);
        deviation = 0.0;
        let (cu, cv) = (
            span_samples(&bu, &CHECK_FRACTIONS, true),
            span_samples(&bv, &CHECK_FRACTIONS, true),
        );
        for &(ku_span, u) in &cu {
            for &(kv_span, v) in &cv {
                let d = (surface.eval(u, v) - target(u, v)).length();
                deviation = deviation.max(d);
                if d > tol {
                    over_u[ku_span] = true;
                    over_v[kv_span] = true;
                }
            }
        }
        if !over_u.contains(&true) {
            return Ok((surface, deviation));
        }
        if best.as_ref().is_none_or(|b| deviation < b.1) {
            best = Some((surface, deviation));
        }
        let (su, sv) = (bu.len() - 1, bv.len() - 1);
        let (nu_next, nv_next) = (
            su + over_u.iter().filter(|&&o| o).count(),
            sv + over_v.iter().filter(|&&o| o).count(),
        );
        if nu_next.max(nv_next) > MAX_SURFACE_SPANS || nu_next * nv_next > MAX_SURFACE_CELLS {
            return give_up(best, deviation);
        }
        ku = bisected(&ku, &bu, &over_u);
        kv = bisected(&kv, &bv, &over_v);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_curve_fit_meets_its_tolerance_and_refines() {
        let f = |t: f64| DVec3::new(t, (6.0 * t).sin(), (3.0 * t).cos());
        for tol in [1e-3, 1e-5, 1e-7] {
            let (c, dev) = fit_curve(f, &[], tol).expect("a fit");
            assert!(dev <= tol, "deviation {dev} over {tol}");
            for k in 0..=997 {
                let t = k as f64 / 997.0;
                let d = (c.point(t) - f(t)).length();
                assert!(d <= 2.0 * tol, "dense deviation {d} at {t} for {tol}");
            }
            assert_eq!(c.point(0.0), f(0.0), "start interpolated");
            assert_eq!(c.point(1.0), f(1.0), "end interpolated");
        }
    }

    #[test]
    fn a_surface_fit_keeps_its_boundary_and_meets_its_tolerance() {
        let s = |u: f64, v: f64| DVec3::new(u, v, 0.3 * (2.0 * u).sin() * (1.0 + v * v));
        let tol = 1e-6;
        let fit = |g: &dyn Fn(f64) -> DVec3| fit_curve(g, &[], 0.25 * tol).expect("edge").0;
        let boundary = QuadBoundary {
            bottom: fit(&|t| s(t, 0.0)),
            top: fit(&|t| s(t, 1.0)),
            left: fit(&|t| s(0.0, t)),
            right: fit(&|t| s(1.0, t)),
        };
        let (surf, dev) = fit_surface(s, &boundary, 0.5 * tol, tol).expect("a fit");
        assert!(dev <= 0.5 * tol, "deviation {dev}");
        for a in 0..=41 {
            for b in 0..=37 {
                let (u, v) = (a as f64 / 41.0, b as f64 / 37.0);
                let d = (surf.eval(u, v) - s(u, v)).length();
                assert!(d <= tol, "dense deviation {d} at ({u}, {v})");
            }
        }
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let d = (surf.eval(t, 0.0) - boundary.bottom.point(t)).length()
                + (surf.eval(1.0, t) - boundary.right.point(t)).length();
            assert!(d < 1e-12, "boundary curve kept exactly: off by {d}");
        }
    }
}
