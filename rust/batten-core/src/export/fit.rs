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

/// The most knot spans of a fitted face in all (spans along u × spans along v). A smooth
/// patch needs few; one that bends sharply along a line across it needs many, because a
/// tensor-product face refines whole rows and columns: the real ships' faces beside the seams
/// of the surfaces their offsets were cut from (KCS's wl_z9.00 steps 27 mm in 3.5 cm, its
/// face 75 fits in 204 × 152 cells; KVLCC2's wl_z17.00 jogs 11 mm in 3 cm, its face 81 in
/// 245 × 306). A patch that is singular or folded somewhere (a repaired degenerate corner, a
/// fold the build reports) is given up earlier, once refining stops paying
/// ([`STALL_ROUNDS`]).
pub const MAX_SURFACE_CELLS: usize = 131_072;

/// Refinements within which a face's fit must halve its largest deviation while that is over
/// the tolerance, or the fit is given up: where the patch is smooth, each refinement of the
/// cells over the tolerance divides it by 1.5–4 (the real ships' largest faces); where it
/// cracks, folds or has a singular corner, the deviation stays, and refining on to
/// [`MAX_SURFACE_CELLS`] would take minutes to no end. (A fit within the tolerance whose
/// cells still fail only because it turns over between samples refines on: those few cells
/// cost little, and the real ships' faces come out of it.)
const STALL_ROUNDS: usize = 3;

/// Why a fit failed: it did not reach the tolerance within its most spans, or its least-squares
/// system was singular (the deviation reached so far is given).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FitFailed {
    /// The largest deviation of the last fit measured (m), infinite when no fit was made.
    pub(crate) deviation: f64,
    /// Whether the last fit turned over somewhere (a face only; see [`turned_over`]).
    pub(crate) turned: bool,
}

impl FitFailed {
    /// Nothing could be fitted (a boundary curve f64 cannot hold, a singular system at once).
    pub(crate) const NOTHING: FitFailed = FitFailed::short(f64::INFINITY);

    /// A fit that did not get within its tolerance.
    const fn short(deviation: f64) -> FitFailed {
        FitFailed {
            deviation,
            turned: false,
        }
    }

    /// The worse of two failures of one patch's fits: the larger deviation, turned if either
    /// turned.
    pub(crate) fn worse(self, other: FitFailed) -> FitFailed {
        FitFailed {
            deviation: self.deviation.max(other.deviation),
            turned: self.turned || other.turned,
        }
    }
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
        let inner = solve_interior(&rows, &rhs, count).ok_or(FitFailed::short(deviation))?;
        let mut points = Vec::with_capacity(count);
        points.push(start);
        points.extend(inner);
        points.push(end);
        let c = curve(knots, points).ok_or(FitFailed::short(deviation))?;
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
            return Err(FitFailed::short(deviation));
        }
        knots_in = bisected(&knots_in, &breaks, &over);
    }
}

/// Gauss–Newton steps [`deviation_at`] takes towards the foot point: from the sample's own
/// parameters, a few steps reach it to rounding where the surface is within a few tolerances.
const FOOT_STEPS: usize = 6;

/// How a fitted face compares with its target at one check sample.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    /// The distance (m) from the target's point to a point of the face (never less than the
    /// distance to the face).
    distance: f64,
    /// The face's normal `S_u × S_v` at the sample's own parameters (not unit).
    normal: DVec3,
    /// Whether the face's point at the sample's parameters is more than the tolerance from
    /// the target's (the distance is then to another point of the face).
    slid: bool,
}

/// How far the fitted `surface` lies from the target's point `p` at `(u, v)`: `|S(u, v) − p|`
/// where that is within `tol`; else the distance from `p` to the nearest point of the surface
/// found by Gauss–Newton steps from `(u, v)` (Piegl & Tiller §6.1, point inversion), so that a
/// face is judged by its shape, not by how its parameters run. A patch's parameters can run
/// unevenly where its surface is smooth (Kato's side-blended patch near its corners, whose
/// blend is continuous but not smooth in the parameters; a Gregory patch across a T-joint of
/// its side): a cubic follows the shape there but not the parameters. Every distance is from
/// `p` to an actual point of the surface, so never less than the true distance.
///
/// Sliding lets a face fold in its own tangent plane and still lie close to the target, so
/// the fit also checks that the face does not turn over ([`turned_over`]).
///
/// `first` is the face's point and first derivatives at `(u, v)`, where the search starts
/// ([`check`] evaluates them from one basis per row and column of its samples).
fn deviation_at(
    surface: &BsplineSurface,
    p: DVec3,
    (u, v): (f64, f64),
    first: [DVec3; 3],
    tol: f64,
) -> Sample {
    let (mut a, mut b) = (u, v);
    let mut best = f64::INFINITY;
    let mut normal = DVec3::ZERO;
    let mut slid = false;
    for step in 0..=FOOT_STEPS {
        let [s, su, sv] = if step == 0 {
            first
        } else {
            surface.eval_derivs(a, b)
        };
        let r = p - s;
        best = best.min(r.length());
        if step == 0 {
            normal = su.cross(sv);
            slid = best > tol;
        }
        if step == FOOT_STEPS || !slid {
            break;
        }
        let (uu, uv, vv) = (su.dot(su), su.dot(sv), sv.dot(sv));
        let det = uu * vv - uv * uv;
        if det.is_nan() || det <= 0.0 {
            break;
        }
        let (gu, gv) = (su.dot(r), sv.dot(r));
        let next = (
            (a + (vv * gu - uv * gv) / det).clamp(0.0, 1.0),
            (b + (uu * gv - uv * gu) / det).clamp(0.0, 1.0),
        );
        if next == (a, b) {
            break;
        }
        (a, b) = next;
    }
    Sample {
        distance: best,
        normal,
        slid,
    }
}

/// Whether a face turns over between two neighbouring check samples where it has slid along
/// the target: their normals point away from each other, and at least one of them is more
/// than the tolerance from the target's point at its parameters. Check samples lie a
/// sixteenth of a span apart, and a smooth face turns by far less than a right angle over
/// that; one that turns over there has folded (a zero normal, at a singular point, decides
/// nothing). Where the face keeps to the target's parameters, it turns only where the target
/// does (a patch may fold thinly, as at a T-joint of its side), and follows it faithfully.
fn turned_over(a: &Sample, b: &Sample) -> bool {
    (a.slid || b.slid) && a.normal.dot(b.normal) < 0.0
}

/// What [`check`] found of a fitted face.
#[derive(Clone, Debug, PartialEq)]
struct Check {
    /// The largest distance from a target sample to the face (m).
    deviation: f64,
    /// The cells (`i` along `u` times the spans along `v`, plus `j`) over the tolerance or
    /// where the face turns over.
    failing: Vec<bool>,
    /// Whether the face turns over anywhere.
    turned: bool,
}

/// The fitted `surface` against `target` at the check samples of every cell between the
/// breakpoints `bu` × `bv`: each sample's distance ([`deviation_at`]), and whether the face
/// turns over between neighbouring samples ([`turned_over`]; both cells of such a pair fail).
/// `None` once `go_on` (asked before each row of samples) says to stop.
fn check(
    surface: &BsplineSurface,
    target: &impl Fn(f64, f64) -> DVec3,
    bu: &[f64],
    bv: &[f64],
    tol: f64,
    go_on: &dyn Fn() -> bool,
) -> Option<Check> {
    let cells_v = bv.len() - 1;
    let mut out = Check {
        deviation: 0.0,
        failing: vec![false; (bu.len() - 1) * cells_v],
        turned: false,
    };
    let (cu, cv) = (
        span_samples(bu, &CHECK_FRACTIONS, true),
        span_samples(bv, &CHECK_FRACTIONS, true),
    );
    let basis_v: Vec<_> = cv.iter().map(|&(_, v)| surface.basis_v(v)).collect();
    // The row of samples before (along v), to compare with their neighbours.
    let mut previous: Vec<Sample> = Vec::with_capacity(cv.len());
    let mut row: Vec<Sample> = Vec::with_capacity(cv.len());
    for (a, &(i, u)) in cu.iter().enumerate() {
        if !go_on() {
            return None;
        }
        row.clear();
        let basis_u = surface.basis_u(u);
        for (b, &(j, v)) in cv.iter().enumerate() {
            let first = surface.eval_derivs_at(&basis_u, &basis_v[b]);
            let sample = deviation_at(surface, target(u, v), (u, v), first, tol);
            out.deviation = out.deviation.max(sample.distance);
            let fold_u = a > 0 && turned_over(&previous[b], &sample);
            let fold_v = b > 0 && turned_over(&row[b - 1], &sample);
            if sample.distance > tol || fold_u || fold_v {
                out.failing[i * cells_v + j] = true;
            }
            // At a span's start the neighbour before lies in the cell before.
            if fold_u {
                out.failing[cu[a - 1].0 * cells_v + j] = true;
            }
            if fold_v {
                out.failing[i * cells_v + cv[b - 1].0] = true;
            }
            out.turned |= fold_u || fold_v;
            row.push(sample);
        }
        std::mem::swap(&mut previous, &mut row);
    }
    Some(out)
}

/// Which directions of the cell `[u0, u1] × [v0, v1]` of a face over the tolerance to halve:
/// the direction(s) along which the target bends most off its tangent plane across the cell.
/// The error of a cubic span of width `h` grows as `h⁴` times the fourth derivative along it;
/// the fourth difference of five target points across the cell's middle line, taken along
/// the surface normal (the parameters' own unevenness is not an error, see [`deviation_at`]),
/// estimates it in each direction. A direction is halved when its estimate is at least half
/// the other's, so both are where they are alike, and both where neither bends (the cell is
/// over for another reason: a kink, a singular corner).
fn directions_to_refine(
    surface: &BsplineSurface,
    target: &impl Fn(f64, f64) -> DVec3,
    [u0, u1]: [f64; 2],
    [v0, v1]: [f64; 2],
) -> (bool, bool) {
    let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
    let [_, su, sv] = surface.eval_derivs(um, vm);
    let normal = su.cross(sv).normalize_or_zero();
    let fourth = |point: &dyn Fn(f64) -> DVec3| {
        let f: [DVec3; 5] = std::array::from_fn(|k| point(k as f64 / 4.0));
        (f[0] - 4.0 * f[1] + 6.0 * f[2] - 4.0 * f[3] + f[4])
            .dot(normal)
            .abs()
    };
    let along_u = fourth(&|t| target(u0 + t * (u1 - u0), vm));
    let along_v = fourth(&|t| target(um, v0 + t * (v1 - v0)));
    let largest = along_u.max(along_v);
    if largest.is_nan() || largest <= 0.0 || normal == DVec3::ZERO {
        return (true, true);
    }
    (along_u >= 0.5 * largest, along_v >= 0.5 * largest)
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
/// check sample ([`deviation_at`]: the distance from the target's point to the surface; and
/// the surface not turned over where it slid along the target, [`turned_over`]), or — where
/// refining cannot get there: a singular system near a degenerate corner, [`MAX_SURFACE_SPANS`]
/// or [`MAX_SURFACE_CELLS`] reached, a deviation that refining no longer halves
/// ([`STALL_ROUNDS`]) — the best fit that did not turn over, if it is within `limit`.
///
/// Boundary rows and columns come from the curves (knot vectors the union of the opposite
/// curves', refined by exact knot insertion), interior control points from least squares on a
/// grid of samples, solved along `u` then along `v` (the tensor-product system separates).
/// Every cell over the tolerance has its spans halved along the direction(s) it bends in
/// ([`directions_to_refine`]), and the fit is made again. Returns the surface and its measured
/// deviation, or `None` once `go_on` (asked at each fit and each row of its check) says to
/// stop: a face that can be fitted at all takes milliseconds, but one that cannot may take
/// seconds to refine to its most spans, and an export that another face has already failed,
/// or that the designer cancelled, need not wait for it.
pub(crate) fn fit_surface(
    target: impl Fn(f64, f64) -> DVec3,
    boundary: &QuadBoundary,
    tol: f64,
    limit: f64,
    go_on: &dyn Fn() -> bool,
) -> Result<Option<(BsplineSurface, f64)>, FitFailed> {
    let mut best: Option<(BsplineSurface, f64)> = None;
    let give_up = |best: Option<(BsplineSurface, f64)>, last: FitFailed| match best {
        Some((s, d)) if d <= limit => Ok(Some((s, d))),
        _ => Err(last),
    };
    let mut ku = knot_union(
        interior(boundary.bottom.knots()),
        interior(boundary.top.knots()),
    );
    let mut kv = knot_union(
        interior(boundary.left.knots()),
        interior(boundary.right.knots()),
    );
    let mut last = FitFailed::short(f64::INFINITY);
    // The largest deviation of each fit so far.
    let mut reached: Vec<f64> = Vec::new();
    loop {
        if !go_on() {
            return Ok(None);
        }
        let (knots_u, knots_v) = (clamped(&ku), clamped(&kv));
        let (nu, nv) = (ku.len() + EXPORT_DEGREE + 1, kv.len() + EXPORT_DEGREE + 1);
        let rows = [
            refined_points(&boundary.bottom, &ku),
            refined_points(&boundary.top, &ku),
            refined_points(&boundary.left, &kv),
            refined_points(&boundary.right, &kv),
        ];
        let [Some(bottom), Some(top), Some(left), Some(right)] = rows else {
            return give_up(best, last);
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
                None => return give_up(best, last),
            }
        }
        // Along v for every interior column.
        for i in 1..nu - 1 {
            let rhs: Vec<DVec3> = y.iter().map(|yb| yb[i - 1]).collect();
            let Some(x) = solve_interior(&rows_v, &rhs, nv) else {
                return give_up(best, last);
            };
            for (j, p) in x.into_iter().enumerate() {
                surface.control[i * nv + j + 1] = p;
            }
        }
        if !surface.control.iter().all(|p| p.is_finite()) {
            return give_up(best, last);
        }
        let Some(Check {
            deviation,
            failing,
            turned,
        }) = check(&surface, &target, &bu, &bv, tol, go_on)
        else {
            return Ok(None);
        };
        let (mut over_u, mut over_v) = (vec![false; bu.len() - 1], vec![false; bv.len() - 1]);
        if !failing.contains(&true) {
            return Ok(Some((surface, deviation)));
        }
        for (cell, _) in failing.iter().enumerate().filter(|(_, &f)| f) {
            let (i, j) = (cell / over_v.len(), cell % over_v.len());
            let (along_u, along_v) =
                directions_to_refine(&surface, &target, [bu[i], bu[i + 1]], [bv[j], bv[j + 1]]);
            over_u[i] |= along_u;
            over_v[j] |= along_v;
        }
        if !turned && best.as_ref().is_none_or(|b| deviation < b.1) {
            best = Some((surface, deviation));
        }
        last = FitFailed { deviation, turned };
        reached.push(deviation);
        if let Some(&before) = reached.iter().rev().nth(STALL_ROUNDS) {
            if deviation > tol && deviation > 0.5 * before {
                return give_up(best, last);
            }
        }
        let (su, sv) = (bu.len() - 1, bv.len() - 1);
        let (nu_next, nv_next) = (
            su + over_u.iter().filter(|&&o| o).count(),
            sv + over_v.iter().filter(|&&o| o).count(),
        );
        if nu_next.max(nv_next) > MAX_SURFACE_SPANS || nu_next * nv_next > MAX_SURFACE_CELLS {
            return give_up(best, last);
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

    /// The boundary curves of `s` on the unit square, each fitted to a quarter of `tol`.
    fn boundary_of(s: &dyn Fn(f64, f64) -> DVec3, tol: f64) -> QuadBoundary {
        let fit = |g: &dyn Fn(f64) -> DVec3| fit_curve(g, &[], 0.25 * tol).expect("edge").0;
        QuadBoundary {
            bottom: fit(&|t| s(t, 0.0)),
            top: fit(&|t| s(t, 1.0)),
            left: fit(&|t| s(0.0, t)),
            right: fit(&|t| s(1.0, t)),
        }
    }

    #[test]
    fn a_face_is_judged_by_its_shape_not_by_how_its_parameters_run() {
        // A tilted plane whose parameter u runs four times as fast on its first quarter as
        // after it (a kink in the parameters, as at a T-joint), inside straight sides that
        // run evenly: one cubic span lies in the plane but cannot follow the kink.
        let plane = |x: f64, y: f64| DVec3::new(x, y, 0.2 * x + 0.1 * y);
        let kinked = |u: f64| {
            if u < 0.25 {
                2.0 * u
            } else {
                0.5 + (u - 0.25) * 2.0 / 3.0
            }
        };
        let target = |u: f64, v: f64| plane(kinked(u), v);
        let tol = 1e-6;
        let boundary = boundary_of(&|u, v| plane(u, v), tol);
        let (surf, dev) = fit_surface(target, &boundary, 0.5 * tol, tol, &|| true)
            .expect("a fit")
            .expect("not stopped");
        assert!(dev <= 0.5 * tol, "deviation {dev}");
        assert_eq!(
            (surf.count_u, surf.count_v),
            (4, 4),
            "one span each way: the shape needs no more"
        );
        let slide = (0..=40)
            .map(|a| {
                let u = a as f64 / 40.0;
                (surf.eval(u, 0.5) - target(u, 0.5)).length()
            })
            .fold(0.0, f64::max);
        assert!(
            slide > 1e3 * tol,
            "its parameters slide along the plane by {slide}"
        );
        for a in 0..=40 {
            for b in 0..=40 {
                let p = surf.eval(a as f64 / 40.0, b as f64 / 40.0);
                let off = (p.z - 0.2 * p.x - 0.1 * p.y).abs();
                assert!(off < 1e-12, "off the plane by {off}");
                assert!(
                    (-1e-12..=1.0 + 1e-12).contains(&p.x) && (-1e-12..=1.0 + 1e-12).contains(&p.y),
                    "inside the face's sides: {p}"
                );
            }
        }
    }

    /// The face `(x(u), v, 0)` over the unit square as a bicubic of one span in `v` and
    /// `spans` in `u`, its control points' `x` from `x` at the Greville abscissae (exact for a
    /// cubic `x`).
    fn sheet(x: impl Fn(f64) -> f64, spans: usize) -> BsplineSurface {
        let interior: Vec<f64> = (1..spans).map(|k| k as f64 / spans as f64).collect();
        let knots_u = clamped(&interior);
        let count_u = spans + EXPORT_DEGREE;
        let control = (0..count_u)
            .flat_map(|i| {
                let greville = knots_u[i + 1..i + 1 + EXPORT_DEGREE].iter().sum::<f64>() / 3.0;
                let xi = x(greville);
                (0..4).map(move |j| DVec3::new(xi, j as f64 / 3.0, 0.0))
            })
            .collect();
        BsplineSurface {
            knots_u,
            knots_v: clamped(&[]),
            count_u,
            count_v: 4,
            control,
        }
    }

    #[test]
    fn a_face_that_folds_in_its_plane_fails_where_it_slid_and_turned_over() {
        let tol = 1e-6;
        let square = |u: f64, v: f64| DVec3::new(u, v, 0.0);
        let breaks = [0.0, 0.5, 1.0];
        // A sheet in the square's plane, its parameter running back over the middle (a fold
        // in the plane): it turns over twice.
        let folded = sheet(|u| u + 0.3 * (2.0 * std::f64::consts::PI * u).sin(), 8);
        let c = check(&folded, &square, &breaks, &breaks, tol, &|| true).expect("not stopped");
        assert!(c.turned, "turned over: {c:?}");
        assert!(
            c.failing.iter().all(|&f| f),
            "in every cell: {:?}",
            c.failing
        );
        // Running unevenly but the same way all along: only slid, nothing fails.
        let uneven = sheet(|u| u * u * (3.0 - 2.0 * u), 8);
        let c = check(&uneven, &square, &breaks, &breaks, tol, &|| true).expect("not stopped");
        assert!(c.deviation < 1e-12 && !c.turned, "{c:?}");
        assert!(!c.failing.contains(&true), "{c:?}");
        // The target folds, the face does not: the face is kept.
        let target_folds =
            |u: f64, v: f64| square(u + 0.3 * (2.0 * std::f64::consts::PI * u).sin(), v);
        let c = check(
            &sheet(|u| u, 1),
            &target_folds,
            &breaks,
            &breaks,
            tol,
            &|| true,
        )
        .expect("not stopped");
        assert!(c.deviation < 1e-12 && !c.turned, "{c:?}");
        // The face folds where the target does, keeping to its parameters: it follows the
        // target faithfully, and is kept.
        let same = |u: f64, v: f64| folded.eval(u, v);
        let c = check(&folded, &same, &breaks, &breaks, tol, &|| true).expect("not stopped");
        assert!(c.deviation < 1e-12 && !c.turned, "{c:?}");
        // Off the plane: the distance to the face, not between the parameters.
        let lifted = |u: f64, v: f64| DVec3::new(u, v, 3e-3);
        let c = check(&uneven, &lifted, &breaks, &breaks, tol, &|| true).expect("not stopped");
        assert!((c.deviation - 3e-3).abs() < 1e-12, "{c:?}");
    }

    #[test]
    fn a_face_is_refined_only_across_the_direction_it_bends_in() {
        // Quadratic along u (one cubic span holds it exactly), a sine wave along v.
        let s = |u: f64, v: f64| DVec3::new(u, v, 0.4 * u * (1.0 - u) * (9.0 * v).sin());
        let tol = 1e-6;
        let (surf, dev) = fit_surface(s, &boundary_of(&s, tol), 0.5 * tol, tol, &|| true)
            .expect("a fit")
            .expect("not stopped");
        assert!(dev <= 0.5 * tol, "deviation {dev}");
        assert_eq!(surf.count_u, 4, "one span along u");
        assert!(
            surf.count_v > 8,
            "refined along v: {} control points",
            surf.count_v
        );
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
        let (surf, dev) = fit_surface(s, &boundary, 0.5 * tol, tol, &|| true)
            .expect("a fit")
            .expect("not stopped");
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

    #[test]
    fn a_cracked_face_is_given_up_once_refining_stops_paying() {
        // A sheet with a 2 mm crack along a circle inside it (as a patch cracked where a ribbon
        // steps): no bicubic follows the jump, and the fit's deviation stays about half of it
        // however far it refines.
        let crack = 2e-3;
        let s = |u: f64, v: f64| {
            let inside = (u - 0.5).powi(2) + (v - 0.5).powi(2) < 0.09;
            DVec3::new(u, v, 0.1 * u * v + if inside { crack } else { 0.0 })
        };
        let evaluations = std::cell::Cell::new(0usize);
        let target = |u: f64, v: f64| {
            evaluations.set(evaluations.get() + 1);
            s(u, v)
        };
        let tol = 1e-4;
        let boundary = boundary_of(&s, tol);
        let Err(failed) = fit_surface(target, &boundary, 0.5 * tol, tol, &|| true) else {
            panic!("a cracked face cannot be fitted");
        };
        assert!(
            failed.deviation > 0.2 * crack,
            "it reached {} of the crack",
            failed.deviation / crack
        );
        // Refined on to the most cells it took 1.7e7 evaluations (9.3e3 given up).
        assert!(
            evaluations.get() < 2_000_000,
            "{} evaluations before giving up",
            evaluations.get()
        );
    }
}
