//! The smoothing spline of one smooth piece for fixed data parameters: Dierckx's `fpcurf`
//! (Dierckx 1993 ch. 5, routines curfit/parcur) with the H-rep paper's one-knot-at-a-time rule.
//!
//! Part 1 adds knots until the least-squares spline `s∞` satisfies `F(∞) = E(s∞) ≤ S`; part 2
//! finds `p` with `F(p) = S` for the spline minimising `E + J/p²` (Dierckx's scaling of the
//! paper's `J + p·E`), by Dierckx's rational interpolation (`fprati`). The end points are
//! interpolated by fixing the end control points; fixed end derivatives fix the next control
//! point too (as Dierckx's concur does with end derivatives).
//!
//! Implementation note: where fpcurf refactorises the whole observation matrix after each knot
//! step, the triangle here is updated in place at each insertion (see `System`): only the data
//! of the spans around the new knot are rotated again, and the per-span triangles after it are
//! merged again from a saved state, which is the same least-squares problem solved by the same
//! Givens rotations, grouped by span. Dierckx's fpcurf also adds several knots per step once it
//! can estimate how many are needed (its `nplus`); that changes the knots chosen and gave a less
//! fair curve on the KCS section benchmark (2,000 noisy points: 77 instead of 48 interior knots
//! and 46 instead of 25 inflections), so knots are still added one at a time.

mod p_search;
mod system;

use glam::DVec3;

use super::knots::{clamped, next_knots, schoenberg_whitney};
use p_search::find_p;
use system::initial_interior;
pub(crate) use system::System;

/// Dierckx's relative tolerance on `F(p) = S` (curfit's `tol = 0.001`), shared by the p search,
/// the system's splines and the fit.
const REL_ACC: f64 = 1e-3;

/// Constraints at the ends of a piece: the end points, and optionally the end derivatives
/// `C'(a)`, `C'(b)` (with respect to the fitting parameter).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ends {
    pub start: DVec3,
    pub end: DVec3,
    pub start_derivative: Option<DVec3>,
    pub end_derivative: Option<DVec3>,
}

/// A linear condition on the fit: `w · C″(t) = 0`, which makes the curvature at `t` zero in
/// the plane with in-plane normal `w` (for `w ⊥ C′(t)`). The condition is linear in the
/// coefficients, so the constrained fit is a least-squares problem with equality
/// constraints, solved by a Lagrange correction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ZeroCurvature {
    /// The parameter (inside the piece's domain).
    pub t: f64,
    /// The direction `w` whose component of `C″(t)` is held at zero.
    pub w: DVec3,
}

/// The 99 % quantiles of χ² with 1..=8 degrees of freedom: how far, in units of the noise
/// variance, so many extra conditions or unknowns may move E under noise alone (the lobes'
/// conditions, a knot's coefficient).
pub(crate) const CHI2_99: [f64; 8] = [6.635, 9.210, 11.345, 13.277, 15.086, 16.812, 18.475, 20.090];

/// The smoothing factor S, and the value of `F(∞)` at which knot insertion may stop (`≥ s`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Target {
    pub s: f64,
    pub accept: f64,
    /// S is `M·σ²` for a known noise level σ larger than the point spacing (a scan denser
    /// than its noise): knot insertion also stops, with the
    /// least-squares spline even above `accept`, when the last knot lowered E by no more than
    /// noise explains (the likelihood-ratio test of the linear model with known variance,
    /// Seber & Lee 2003 §4.3: a knot adds one coefficient, three unknowns, so under noise
    /// alone the fall of E is σ²·χ²(3), and a fall below its 99 % quantile is noise).
    ///
    /// Choice: E of the true curve scatters by `√(2M)·σ²` about `M·σ²`, and points dropped as
    /// duplicates (within the model tolerance of the point before) are those whose noise is
    /// like their neighbour's, so the rest scatter more than σ (2 m arc, σ = 1 mm, 100,000
    /// points: 5 % dropped, the rest 2.8 % above `M·σ²`). Insisting on `E ≤ S` then fits that
    /// excess with noise knots: 130–540 control points at 10,000–30,000 points and 390 at
    /// 100,000, where the truth needs 7. Where the points are farther apart than σ, Dierckx's
    /// range is kept as the contract (E within `(M + √(2M))·σ²`; its noise knots are few there).
    pub noise: bool,
}

impl Target {
    /// Knots are added until `F(∞) ≤ s` (Dierckx's rule).
    pub(super) fn exact(s: f64) -> Self {
        Target {
            s,
            accept: s,
            noise: false,
        }
    }
}

/// A fitted piece: a clamped B-spline on `[params[0], params[m-1]]`.
#[derive(Clone, Debug)]
pub(crate) struct Spline {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub coefs: Vec<DVec3>,
    /// The smoothing parameter: 0 for the least-squares polynomial, ∞ for the least-squares
    /// spline, otherwise the root of `F(p) = S` (Dierckx's scaling).
    pub p: f64,
    /// `E`, the sum of squared residuals at the data parameters.
    pub fp: f64,
    /// True when `E ≤ S` within Dierckx's tolerance.
    pub reached: bool,
}

/// The smoothing spline of degree `degree` through `points` at sorted `params` with
/// `E ≤ S` (Dierckx fpcurf with single knot insertion, H-rep paper §4); knot insertion stops
/// at `F(∞) ≤ target.accept`, and when that is above S the least-squares spline is returned.
///
/// Requires at least `degree + 1` points with distinct end parameters; `None` when the
/// parameters cannot determine even the polynomial (Schoenberg–Whitney fails).
pub(crate) fn smoothing_spline(
    points: &[DVec3],
    params: &[f64],
    degree: usize,
    target: Target,
    ends: &Ends,
) -> Option<Spline> {
    fit_with_system(points, params, degree, target, ends, &[], Some(None), None).map(|(sp, _)| sp)
}

/// [`smoothing_spline`] starting from the interior knots `warm` instead of none (they are
/// kept; knots are only added), returning with it the least-squares system of its knots (for
/// a refit under conditions on the same knots and data, [`constrained_fit`]; `None` only when
/// the spline is the last good one before a numerically singular step).
///
/// `search_p`: `None` stops at the least-squares spline once `F(∞)` is within the target
/// (part 1 only); `Some(start)` searches p from `start` (the p of a previous fit to nearly
/// the same data) or, when that is `None`, from fpcurf's first guess. `f_zero`: `F(0)` of a
/// previous fit to nearly the same data, to start that search without fitting the
/// polynomial again.
///
/// `warm` is used only when the Schoenberg–Whitney conditions hold for it at `params`
/// (parameters moved by a correction can leave a span without data); otherwise the search
/// starts from no knots.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_with_system(
    points: &[DVec3],
    params: &[f64],
    degree: usize,
    target: Target,
    ends: &Ends,
    warm: &[f64],
    search_p: Option<Option<f64>>,
    f_zero: Option<f64>,
) -> Option<(Spline, Option<System>)> {
    let k = degree;
    let s = target.s;
    let m = points.len();
    let (a, b) = (params[0], params[m - 1]);
    let acc = REL_ACC * s;
    let cold = initial_interior(k, ends, params);
    let warm_started = warm.len() > cold.len()
        && warm.iter().all(|&t| a < t && t < b)
        && schoenberg_whitney(&clamped(k, a, b, warm), k, params);
    let mut interior = if warm_started {
        warm.to_vec()
    } else {
        cold.clone()
    };

    // Part 1: knots until F(∞) ≤ S, one at a time, each updating the triangle in place.
    let mut fp0: Option<f64> = None;
    let mut previous: Option<Spline> = None;
    // E before the last knot this call added.
    let mut before: Option<f64> = None;
    let mut system = System::new(k, clamped(k, a, b, &interior), points, params, ends);
    let (mut system, ls_coefs, fp_inf) = loop {
        // Knots are only added where Schoenberg–Whitney holds, so this fails only when
        // rounding makes the system numerically singular: keep the last good spline then.
        let Some(coefs) = system.least_squares() else {
            return previous.map(|sp| (sp, None));
        };
        let r2 = system.residuals2(&coefs);
        let fp: f64 = r2.iter().sum();
        if fp0.is_none() {
            fp0 = Some(fp);
            if fp <= s && !warm_started {
                // The least-squares polynomial is smooth enough (fpcurf ier = -2).
                let sp = system.spline(coefs, 0.0, fp, s);
                return Some((sp, Some(system)));
            }
        }
        if (fp - s).abs() < acc || fp < s {
            break (system, coefs, fp);
        }
        let insignificant = before.is_some_and(|e| e - fp < CHI2_99[2] * s / m as f64);
        if fp <= target.accept || (target.noise && insignificant) {
            // Within the accepted range above S, or (noise known) the last knot lowered E by
            // no more than noise would: the least-squares spline.
            let sp = system.spline(coefs, f64::INFINITY, fp, target.accept);
            return Some((sp, Some(system)));
        }
        before = Some(fp);
        // One knot at a time (the paper's rule; see the module note on fpcurf's nplus).
        let ts = next_knots(
            &system.knots,
            k,
            &system.design,
            &r2,
            params,
            1,
            s / m as f64,
        );
        if ts.is_empty() {
            // No span can take a knot: the least-squares spline is the closest we get.
            let sp = system.spline(coefs, f64::INFINITY, fp, s);
            return Some((sp, Some(system)));
        }
        for &t in &ts {
            let pos = interior.partition_point(|&u| u < t);
            interior.insert(pos, t);
        }
        previous = Some(system.spline(coefs, f64::INFINITY, fp, s));
        for &t in &ts {
            system.insert(t);
        }
    };
    let Some(p_start) = search_p else {
        let sp = system.spline(ls_coefs, f64::INFINITY, fp_inf, s);
        return Some((sp, Some(system)));
    };
    if (fp_inf - s).abs() < acc || interior.is_empty() {
        let sp = system.spline(ls_coefs, f64::INFINITY, fp_inf, s);
        return Some((sp, Some(system)));
    }

    // Part 2: p with F(p) = S by rational interpolation (fpcurf, fprati).
    // F(0): the least-squares polynomial's E (the first pass of a cold start).
    let fp0 = match (warm_started, f_zero) {
        (true, Some(f)) if f.is_finite() => f,
        (true, _) => {
            let poly = system.polynomial();
            let c = poly.least_squares()?;
            poly.residuals2(&c).iter().sum()
        }
        (false, _) => fp0.expect("set on the first pass"),
    };
    system.f_zero = fp0;
    let sp = find_p(&system, s, fp0, (ls_coefs, fp_inf), p_start, &[])?;
    Some((sp, Some(system)))
}

/// The smoothing spline of `system` (its knots and data; no knot is added) under the
/// conditions `cons`, with `E ≤ target.s` when the constrained least-squares spline can reach
/// it (p searched from `p_start`), otherwise that least-squares spline when its E is within
/// `target.accept`. `None` when neither is possible, when the conditions cannot be imposed, or
/// when they raise the least-squares E by more than `max_increase` (the data reject them).
pub(crate) fn constrained_fit(
    system: &System,
    target: Target,
    cons: &[ZeroCurvature],
    p_start: Option<f64>,
    max_increase: f64,
) -> Option<Spline> {
    let s = target.s;
    let free = system.least_squares()?;
    let coefs = system.least_squares_with(cons)?;
    let fp_inf: f64 = system.residuals2(&coefs).iter().sum();
    if fp_inf - system.residuals2(&free).iter().sum::<f64>() > max_increase {
        return None;
    }
    let k = system.degree;
    let interior = system.knots.len() - 2 * (k + 1);
    if fp_inf > s * (1.0 + REL_ACC) || (fp_inf - s).abs() < REL_ACC * s || interior == 0 {
        return (fp_inf <= target.accept * (1.0 + REL_ACC))
            .then(|| system.spline(coefs, f64::INFINITY, fp_inf, target.accept));
    }
    // F(0) only starts the bracket on p: the free polynomial's of the fit, if it had one (the
    // constrained polynomial's is no smaller), else the constrained polynomial's (or, if the
    // conditions fix it completely or cannot be imposed on it, the free one's).
    if system.f_zero.is_finite() {
        let f0 = system.f_zero.max(fp_inf);
        return find_p(system, s, f0, (coefs, fp_inf), p_start, cons);
    }
    let poly = system.polynomial();
    let c0 = poly
        .least_squares_with(cons)
        .or_else(|| poly.least_squares())?;
    let fp0: f64 = poly.residuals2(&c0).iter().sum();
    find_p(system, s, fp0.max(fp_inf), (coefs, fp_inf), p_start, cons)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;

    fn ends(points: &[DVec3]) -> Ends {
        Ends {
            start: points[0],
            end: points[points.len() - 1],
            start_derivative: None,
            end_derivative: None,
        }
    }

    #[test]
    fn a_cubic_is_reproduced_by_the_polynomial_stage() {
        let params: Vec<f64> = (0..20).map(|i| f64::from(i) / 19.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .map(|&u| DVec3::new(u, u * u * u - u, 0.5 * u * u))
            .collect();
        let sp = smoothing_spline(&points, &params, 3, Target::exact(1e-12), &ends(&points))
            .expect("fits");
        assert_eq!(sp.knots.len(), 8, "no interior knot for a cubic");
        assert!(sp.fp < 1e-20, "exact: {}", sp.fp);
        assert_eq!(sp.p, 0.0, "polynomial stage");
    }

    #[test]
    fn inserting_knots_updates_the_triangle_exactly() {
        // The in-place update from the checkpoints gives bit for bit the triangle of a rebuild,
        // with and without fixed end derivatives, for knots anywhere (near the ends included).
        let params: Vec<f64> = (0..80).map(|i| (f64::from(i) / 79.0).powf(1.3)).collect();
        let points: Vec<DVec3> = params
            .iter()
            .map(|&u| DVec3::new(u, (5.0 * u).sin(), 0.3 * (3.0 * u).cos()))
            .collect();
        let mut with_tangents = ends(&points);
        with_tangents.start_derivative = Some(DVec3::new(1.0, 5.0, 0.0));
        with_tangents.end_derivative = Some(DVec3::new(1.0, 1.4, -0.4));
        for (e, degrees) in [(ends(&points), [1, 2, 3, 5]), (with_tangents, [3, 4, 5, 5])] {
            for k in degrees {
                let mut interior: Vec<f64> = Vec::new();
                let mut sys = System::new(k, clamped(k, 0.0, 1.0, &interior), &points, &params, &e);
                for t in [0.5, 0.8, 0.9, 0.03, 0.65, 0.97, 0.3, 0.72, 0.77] {
                    sys.insert(t);
                    interior.push(t);
                    interior.sort_by(f64::total_cmp);
                    let fresh =
                        System::new(k, clamped(k, 0.0, 1.0, &interior), &points, &params, &e);
                    assert_eq!(sys.knots, fresh.knots, "knots");
                    assert_eq!(sys.design.span, fresh.design.span, "spans");
                    let n = fresh.ls.unknowns();
                    assert_eq!(sys.ls.unknowns(), n, "unknowns");
                    for i in 0..n {
                        assert_eq!(sys.ls.row(i), fresh.ls.row(i), "k {k} t {t}: row {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn end_curvature_conditions_are_met_by_the_closest_fit() {
        // Noisy data on a bent curve; the fit with zero end curvature along w at both ends must
        // meet the conditions (checked on the curve itself), and every feasible change of its
        // coefficients must raise E (it is the constrained minimiser).
        let params: Vec<f64> = (0..90).map(|i| f64::from(i) / 89.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .enumerate()
            .map(|(i, &u)| {
                let wobble = 0.01 * ((i * 7 % 5) as f64 - 2.0);
                DVec3::new(3.0 * u, (2.5 * u).sin() + wobble, 0.4 * u * u)
            })
            .collect();
        let e = ends(&points);
        let interior = [0.2, 0.45, 0.7, 0.85];
        let sys = System::new(3, clamped(3, 0.0, 1.0, &interior), &points, &params, &e);
        let cons = [
            ZeroCurvature {
                t: 0.0,
                w: DVec3::new(0.0, 1.0, 0.2).normalize(),
            },
            ZeroCurvature {
                t: 1.0,
                w: DVec3::new(-0.3, 1.0, 0.0).normalize(),
            },
        ];
        let energy = |c: &[DVec3]| -> f64 { sys.residuals2(c).iter().sum() };
        for p in [f64::INFINITY, 30.0] {
            let c = if p.is_infinite() {
                sys.least_squares_with(&cons)
            } else {
                sys.smoothing(p, &cons)
            }
            .expect("fits");
            let curve = NurbsCurve::try_new(3, sys.knots.clone(), c.clone(), None).unwrap();
            for (con, t) in cons.iter().zip([0.0, 1.0]) {
                let d2 = curve.derivs(t).d2;
                assert!(
                    d2.dot(con.w).abs() < 1e-9 * d2.length().max(1.0),
                    "p {p}: w·C'' = {} at {t}",
                    d2.dot(con.w)
                );
            }
            if p.is_finite() {
                continue;
            }
            // Feasible perturbations: along a direction orthogonal to both w, or along w on a
            // coefficient the conditions do not involve (the middle ones).
            let base = energy(&c);
            let across = cons[0].w.cross(cons[1].w).normalize();
            for j in 1..c.len() - 1 {
                let mut dirs = vec![across];
                if (3..c.len() - 3).contains(&j) {
                    dirs.extend([cons[0].w, cons[1].w]);
                }
                for d in dirs {
                    for eps in [1e-3, -1e-3] {
                        let mut moved = c.clone();
                        moved[j] += d * eps;
                        assert!(energy(&moved) > base, "coefficient {j} moved lowers E");
                    }
                }
            }
            let free = sys.least_squares().expect("fits");
            assert!(energy(&free) < base, "the conditions cost something here");
        }
    }

    #[test]
    fn smoothing_hits_the_smoothing_factor() {
        let params: Vec<f64> = (0..60).map(|i| f64::from(i) / 59.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .enumerate()
            .map(|(i, &u)| {
                let wobble = if i % 2 == 0 { 0.01 } else { -0.01 };
                DVec3::new(u, (6.0 * u).sin() + wobble, 0.0)
            })
            .collect();
        let s = 60.0 * 0.012f64.powi(2);
        let sp =
            smoothing_spline(&points, &params, 3, Target::exact(s), &ends(&points)).expect("fits");
        assert!(sp.reached, "E {} vs S {s}", sp.fp);
        assert!(
            (sp.fp - s).abs() <= 2.0 * REL_ACC * s || sp.p.is_infinite(),
            "F(p) = S: {} vs {s} (p = {})",
            sp.fp,
            sp.p
        );
    }
}
