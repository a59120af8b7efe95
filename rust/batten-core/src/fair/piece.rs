//! Fitting one smooth piece (between corners): the parameter-correction loop around the
//! smoothing spline, the search for S that meets a maximum deviation, and joining pieces G0.

use glam::DVec3;

use super::clean::ORDER_STEP;
use super::convex::{keep_convexity, PieceData};
use super::error::FairError;
use super::fit::{fit_with_system, smoothing_spline, Ends, Spline, System, Target};
use super::lobes::flatten;
use super::metrics::{deviation, Deviation, FairnessMetrics};
use super::param::{chord_length, reproject, resolved_chord_length, sort_by_parameter};
use crate::curve::NurbsCurve;

/// The parameters have settled when no parameter moved by more than this fraction of the mean
/// point spacing in one correction step.
const SETTLE: f64 = 1e-3;
/// ... or when projecting the points onto the fit lowers E by less than this fraction of S
/// (the RMS distance by less than 0.25 %): the parameters still drift along the curve
/// (parameter correction converges linearly there, on the KCS benchmark by about 2 % per
/// step), but the fit no longer changes measurably.
const SETTLE_E: f64 = 5e-3;
/// The parameters of neighbouring points stay at least this fraction of their distance apart
/// where the points are taken in their given order (no resolution: tolerance mode, or S
/// given), see [`reproject`]. Points a spacing `h` apart along the curve and scattered `±d`
/// to its sides have foot points `h` apart and are `√(h² + 4d²)` apart: the bound bites only
/// where the scatter is about twice the spacing, never for offsets fitted within a tolerance.
const MIN_GAP: f64 = 0.25;
/// A parameter correction is a descent on the roughness of the fit at a fixed S (its foot
/// points lower E, so the refit to S may be smoother); one that raises the roughness
/// ([`roughness`]) above this factor times the least reached on the same knots is not taken,
/// and the corrections stop at that least. Where the parameters are held apart
/// ([`MIN_GAP`]) they are not foot points, and the correction can run away instead: KCS's
/// wl_z9.00 aft of its flat of side, where eleven offsets lie within 5 cm of each other
/// across a 2 cm step, sharpened each step until a kink of curvature 50,000 /m folded the
/// surface at the stern.
const ROUGHNESS_RISE: f64 = 1.5;
/// Most steps of the search for S in tolerance mode.
const MAX_S_STEPS: usize = 24;
/// Each step lowers S by the squared ratio of tolerance to deviation times this safety factor
/// (E scales with the square of the deviations).
const S_SAFETY: f64 = 0.8;
/// The first parameter corrections fit to S times these factors (least-squares splines only,
/// no search for p), each round keeping the knots of the one before.
///
/// Choice: chord lengths of noisy points drift along the curve like a random walk (each
/// step adds the noise component along the curve), and a fit to S on them needs knots to
/// follow that drift (KCS benchmark, 2,000 points: 254 knots on chord lengths, 32 on
/// corrected parameters). A fit to 16·S (RMS distance 4σ) has too few knots to follow it, so
/// its foot points remove the drift; the fit to 4·S refines them. Later rounds fit to S and
/// keep their knots, adding knots only where the corrected parameters still need them, so
/// the knot search runs about once in all instead of once per correction (2,000 points:
/// 153 ms → 8 ms).
const RELAXED_ROUNDS: [f64; 2] = [16.0, 4.0];
/// The relaxed rounds are used only when the noise level implied by S (`σ ≈ √(S/M)`) is
/// above this fraction of the mean point spacing: below it the chord lengths drift by a
/// small fraction of a spacing per point, and the first fit to S on them already needs no
/// more knots than the corrected parameters (KCS benchmark, 200 points, σ/spacing = 0.03:
/// 9 knots either way, where the relaxed rounds ended with 12).
const RELAX_NOISE_RATIO: f64 = 0.1;

/// A fitted piece with what it took.
#[derive(Clone, Debug)]
pub(crate) struct PieceFit {
    pub spline: Spline,
    pub curve: NurbsCurve,
    pub s: f64,
    pub iterations: usize,
    pub settled: bool,
    /// The deviation of the piece's points from `curve`, when the fit already measured it.
    pub deviation: Option<Deviation>,
    /// The fairness metrics of `curve`, when the fit already measured them.
    pub metrics: Option<FairnessMetrics>,
    /// The points (in parameter order) and data parameters `curve` was fitted on.
    pub start: Option<Start>,
}

/// Data parameters to start a fit from: the points in parameter order and their parameters,
/// corrected by an earlier fit to the same points (the search for S fits the same points
/// again and again; their foot points on the last fit are a better start than chord lengths).
#[derive(Clone, Debug)]
pub(crate) struct Start {
    pub points: Vec<DVec3>,
    pub params: Vec<f64>,
}

/// End directions (unit vectors) of the piece, if fixed.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Directions {
    pub start: Option<DVec3>,
    pub end: Option<DVec3>,
}

/// Smoothing spline of `points` with `E ≤ s.s`, starting from chord-length parameters (at
/// the data's `resolution` when given, see [`resolved_chord_length`]; or those of `start`,
/// corrected before) and correcting them by foot-point projection until
/// they settle or `max_iter` corrections are done (Dierckx parcur, then Hoschek's parameter
/// correction). From plain chord lengths, the first corrections project onto fits to a relaxed
/// target ([`RELAXED_ROUNDS`]); every round starts from the knots of the one before.
pub(crate) fn fit_smooth(
    points: &[DVec3],
    degree: usize,
    s: Target,
    dirs: Directions,
    max_iter: usize,
    resolution: Option<f64>,
    start: Option<Start>,
) -> Result<PieceFit, FairError> {
    let m = points.len();
    if m < degree + 1 {
        return short_piece(points, degree, s.s);
    }
    let warm = start.is_some();
    // The data at the fit's resolution: its length, and (with a resolution given) the
    // parameters to start from.
    let noise = (s.s / m as f64).sqrt();
    let resolved = resolved_chord_length(points, resolution.unwrap_or(ORDER_STEP * noise));
    let data_length = resolved[m - 1];
    let (mut pts, mut u) = match (start, resolution) {
        (Some(st), _) => (st.points, st.params),
        (None, Some(_)) => {
            let mut pts = points.to_vec();
            let mut u = resolved;
            sort_by_parameter(&mut pts, &mut u);
            (pts, u)
        }
        (None, None) => (points.to_vec(), chord_length(points)),
    };
    let domain = u[m - 1];
    let spacing = domain / (m - 1) as f64;
    // The mean |C′| of the fixed end derivatives: the length of the data at the fit's
    // resolution over the parameter domain (the fit's own length would feed back: a fixed
    // tangent the data turn away from makes a loop, the loop a longer curve and a faster end
    // derivative, and so on until the coefficients overflow).
    let speed = data_length / domain;
    let mut last: Option<(Spline, NurbsCurve)> = None;
    let mut iterations = 0;
    let mut settled = false;
    // A warm start's parameters are already corrected, and those at the data's resolution do
    // not drift: no drift to remove.
    let relaxed = if noise > RELAX_NOISE_RATIO * spacing && !warm && resolution.is_none() {
        RELAXED_ROUNDS.len().min(max_iter)
    } else {
        0
    };
    let mut interior: Vec<f64> = Vec::new();
    let mut last_system = None;
    let mut last_round = None;
    // The smoothest exact fit on the current knots, and what it was fitted to.
    let mut best: Option<Best> = None;
    loop {
        let ends = Ends {
            start: pts[0],
            end: pts[m - 1],
            start_derivative: dirs.start.map(|d| d * speed),
            end_derivative: dirs.end.map(|d| d * speed),
        };
        let factor = if iterations < relaxed {
            RELAXED_ROUNDS[RELAXED_ROUNDS.len() - relaxed + iterations]
        } else {
            1.0
        };
        let round = Target {
            s: s.s * factor,
            accept: s.accept * factor,
            // The likelihood-ratio stop for noise knots only where the noise is larger than
            // the spacing (see `Target::noise`).
            noise: s.noise && noise > spacing,
        };
        let exact = iterations >= relaxed;
        // A fit to S searches p, from the p of the fit before (the data barely moved).
        let search_p = exact.then(|| last.as_ref().map(|(sp, _)| sp.p));
        let f_zero = last_system.as_ref().map(|sys: &System| sys.f_zero());
        let Some((spline, system)) =
            fit_with_system(&pts, &u, degree, round, &ends, &interior, search_p, f_zero)
        else {
            break;
        };
        interior = spline.knots[degree + 1..spline.knots.len() - degree - 1].to_vec();
        let fp = spline.fp;
        let curve = NurbsCurve::try_new(degree, spline.knots.clone(), spline.coefs.clone(), None)?;
        if exact {
            let eta = roughness(&spline);
            let knots = spline.knots.len();
            if let Some(b) = best.take_if(|b| b.knots == knots && eta > ROUGHNESS_RISE * b.eta) {
                // Running away: back to the smoothest fit and its parameters.
                last = Some(b.fit);
                last_system = b.system;
                last_round = b.round;
                pts = b.points;
                u = b.params;
                break;
            }
            let smoother = best
                .as_ref()
                .is_none_or(|b| b.knots != knots || eta < b.eta);
            let fit = (spline, curve.clone());
            last_round = Some((round, ends, interior.clone()));
            if smoother {
                best = Some(Best {
                    eta,
                    knots,
                    fit: fit.clone(),
                    system: system.clone(),
                    round: last_round.clone(),
                    points: pts.clone(),
                    params: u.clone(),
                });
            }
            last = Some(fit);
            last_system = system;
            if iterations >= max_iter {
                break;
            }
        }
        iterations += 1;
        let (change, e_proj) = reproject(
            &curve,
            &mut pts,
            &mut u,
            resolution.is_none().then_some(MIN_GAP),
        );
        if exact && (change <= SETTLE * spacing || fp - e_proj <= SETTLE_E * s.s) {
            settled = true;
            break;
        }
    }
    // Curvature lobes the data do not demand are flattened (see `lobes`), on the knots and
    // data parameters of the last fit.
    let mut metrics = None;
    if let (Some((sp, curve)), Some(system)) = (&last, &last_system) {
        let (flat, m) = flatten(system, s, sp, curve);
        if flat.is_some() {
            last = flat;
        }
        metrics = Some(m);
    }
    // In noise mode, the convexity the data show is kept where the spline rings (`convex`).
    if let (true, Some((target, ends, knots)), Some((_, curve)), Some(m)) =
        (s.noise, &last_round, &last, metrics)
    {
        let data = PieceData {
            points: &pts,
            params: &u,
            ends,
            target: *target,
        };
        if let Some((sp, curve, m)) = keep_convexity(&data, knots, curve, m.inflections) {
            last = Some((sp, curve));
            metrics = Some(m);
        }
    }
    let (spline, curve) = match last {
        Some(fit) => fit,
        // Chord-length parameters of distinct points always determine the polynomial; this is
        // reached only if rounding breaks that.
        None => return Err(FairError::Unfittable { points: m }),
    };
    Ok(PieceFit {
        spline,
        curve,
        s: s.s,
        iterations,
        settled,
        deviation: None,
        metrics,
        start: Some(Start {
            points: pts,
            params: u,
        }),
    })
}

/// The smoothest exact fit of a parameter correction so far (see [`ROUGHNESS_RISE`]).
struct Best {
    eta: f64,
    knots: usize,
    fit: (Spline, NurbsCurve),
    system: Option<System>,
    round: Option<(Target, Ends, Vec<f64>)>,
    points: Vec<DVec3>,
    params: Vec<f64>,
}

/// The roughness a smoothing spline of degree k minimises (Dierckx 1993 §5.2: the sum of the
/// squared jumps of its k-th derivative at the interior knots), from its coefficients: k
/// differentiations of the B-spline leave one constant per span.
fn roughness(spline: &Spline) -> f64 {
    let k = spline.degree;
    let t = &spline.knots;
    let mut c = spline.coefs.clone();
    for r in 0..k {
        let p = (k - r) as f64;
        let knots = &t[r..t.len() - r];
        let deg = k - r;
        c = c
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let h = knots[i + deg + 1] - knots[i + 1];
                if h > 0.0 {
                    (w[1] - w[0]) * (p / h)
                } else {
                    DVec3::ZERO
                }
            })
            .collect();
    }
    // Degree 0 on the knots t[k..len−k]: span i is [t[k+i], t[k+i+1]).
    let spans = &t[k..t.len() - k];
    let values: Vec<DVec3> = c
        .iter()
        .enumerate()
        .filter(|&(i, _)| spans[i + 1] > spans[i])
        .map(|(_, &v)| v)
        .collect();
    values
        .windows(2)
        .map(|w| (w[1] - w[0]).length_squared())
        .sum()
}

/// Search S downwards from `M·tol²` until the largest orthogonal deviation of the fit is within
/// `tol` (the designer's tolerance), each step scaling S by `(tol / deviation)²` and starting
/// from the data parameters the step before corrected (see [`Start`]).
/// On failure returns the smallest deviation reached and the index of its worst point.
pub(crate) fn fit_within(
    points: &[DVec3],
    degree: usize,
    tol: f64,
    dirs: Directions,
    max_iter: usize,
) -> Result<Result<PieceFit, (f64, usize)>, FairError> {
    let m = points.len();
    let mut s = m as f64 * tol * tol;
    let mut best: Option<(f64, usize)> = None;
    let mut start: Option<Start> = None;
    for _ in 0..MAX_S_STEPS {
        let mut fit = fit_smooth(
            points,
            degree,
            Target::exact(s),
            dirs,
            max_iter,
            None,
            start.take(),
        )?;
        let dev = deviation(&fit.curve, points)?;
        if dev.max <= tol {
            fit.deviation = Some(dev);
            return Ok(Ok(fit));
        }
        if best.is_none_or(|(d, _)| dev.max < d) {
            best = Some((dev.max, dev.max_index));
        }
        if fit.spline.p.is_infinite() && !fit.spline.reached {
            // Every span that can take a knot has one: a smaller S cannot help.
            break;
        }
        s *= S_SAFETY * (tol / dev.max).powi(2);
        start = fit.start.take();
    }
    Ok(Err(best.unwrap_or((f64::INFINITY, 0))))
}

/// A piece with fewer points than `degree + 1`: a polynomial of degree `m − 1` on
/// chord-length parameters, raised to `degree`: of the blends `L + λ·(I − L)` of the chord `L`
/// (its control points evenly spaced along the chord between the end points) and the
/// interpolating polynomial `I`, the one nearest the chord with `E ≤ s`. At the data
/// parameters `I` is the data, so the blend's residual is `(1 − λ)·(q − L(u))` and
/// `E(λ) = (1 − λ)²·E_chord`: `λ = 1 − √(s / E_chord)`, 0 when the chord is within `s`.
///
/// Choice: the interpolant alone ignores the tolerance, and three points are enough to curl
/// it: KCS's wl_z0.30 ends in a 5 cm hook past a corner (a nose 3.5 cm wide at the stem whose
/// last offset falls 3 cm aft), where the quadratic through the three points turned at 30.6 /m
/// and folded the forefoot's patches; its middle point lies 4.1 mm off the chord, and the
/// blend within the 3.5 mm the import fits it to turns at 10.3 /m (within 5 mm, straight).
fn short_piece(points: &[DVec3], degree: usize, s: f64) -> Result<PieceFit, FairError> {
    let m = points.len();
    let d = m - 1;
    let u = chord_length(points);
    let ends = Ends {
        start: points[0],
        end: points[m - 1],
        start_derivative: None,
        end_derivative: None,
    };
    let mut spline = smoothing_spline(points, &u, d, Target::exact(0.0), &ends).ok_or(
        FairError::TooFewPoints {
            count: m,
            needed: d + 1,
            degree: d,
            dropped: 0,
        },
    )?;
    let (first, last, length) = (points[0], points[m - 1], u[m - 1]);
    let chord = |t: f64| {
        if length > 0.0 {
            first.lerp(last, t / length)
        } else {
            first
        }
    };
    let e_chord: f64 = points
        .iter()
        .zip(&u)
        .map(|(q, &t)| (*q - chord(t)).length_squared())
        .sum();
    if e_chord > s && s > 0.0 {
        let lambda = 1.0 - (s / e_chord).sqrt();
        for (i, c) in spline.coefs.iter_mut().enumerate() {
            let on_chord = first.lerp(last, i as f64 / d as f64);
            *c = on_chord + (*c - on_chord) * lambda;
        }
        spline.fp = s;
    } else if s > 0.0 {
        for (i, c) in spline.coefs.iter_mut().enumerate() {
            *c = first.lerp(last, i as f64 / d as f64);
        }
        spline.fp = e_chord;
    }
    spline.reached = true;
    let curve = NurbsCurve::try_new(d, spline.knots.clone(), spline.coefs.clone(), None)?;
    Ok(elevate_fit(
        PieceFit {
            spline,
            curve,
            s,
            iterations: 0,
            settled: true,
            deviation: None,
            metrics: None,
            start: None,
        },
        degree,
    ))
}

/// Raise a single-span (Bézier) piece to `degree` (Piegl & Tiller eq. 5.36, repeated).
fn elevate_fit(mut fit: PieceFit, degree: usize) -> PieceFit {
    let sp = &mut fit.spline;
    while sp.degree < degree && sp.knots.len() == 2 * (sp.degree + 1) {
        let d = sp.degree;
        let p = &sp.coefs;
        let mut q = Vec::with_capacity(d + 2);
        q.push(p[0]);
        for i in 1..=d {
            let a = i as f64 / (d + 1) as f64;
            q.push(p[i - 1] * a + p[i] * (1.0 - a));
        }
        q.push(p[d]);
        let (a, b) = (sp.knots[0], sp.knots[sp.knots.len() - 1]);
        sp.knots = super::knots::clamped(d + 1, a, b, &[]);
        sp.coefs = q;
        sp.degree = d + 1;
    }
    if let Ok(curve) = NurbsCurve::try_new(sp.degree, sp.knots.clone(), sp.coefs.clone(), None) {
        fit.curve = curve;
    }
    fit
}

/// Join pieces end to start into one clamped B-spline: each inner joint becomes a knot of
/// multiplicity `degree` (C0, so a knuckle stays sharp), and each piece's parameter domain is
/// shifted to follow the previous one. Returns the knots, control points and the joint
/// parameters.
pub(crate) fn join(pieces: &[PieceFit], degree: usize) -> (Vec<f64>, Vec<DVec3>, Vec<f64>) {
    let k = degree;
    let mut knots = Vec::new();
    let mut coefs: Vec<DVec3> = Vec::new();
    let mut joints = Vec::new();
    let mut offset = 0.0;
    for (i, piece) in pieces.iter().enumerate() {
        let t = &piece.spline.knots;
        let (a, b) = (t[0], t[t.len() - 1]);
        let repeat = if i == 0 { k + 1 } else { k };
        if i > 0 {
            joints.push(offset);
        }
        knots.extend(std::iter::repeat_n(offset, repeat));
        knots.extend(t[k + 1..t.len() - k - 1].iter().map(|&u| u - a + offset));
        let skip = usize::from(i > 0);
        coefs.extend_from_slice(&piece.spline.coefs[skip..]);
        offset += b - a;
    }
    knots.extend(std::iter::repeat_n(offset, k + 1));
    (knots, coefs, joints)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_is_the_sum_of_the_squared_jumps_of_the_third_derivative() {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 3.0, 3.0, 3.0];
        let coefs = vec![
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(2.0, -1.0, 0.5),
            DVec3::new(3.0, 4.0, 0.0),
            DVec3::new(4.0, 0.0, -1.0),
            DVec3::new(5.0, 1.0, 0.0),
        ];
        let spline = Spline {
            degree: 3,
            knots: knots.clone(),
            coefs: coefs.clone(),
            p: 1.0,
            fp: 0.0,
            reached: true,
        };
        let curve = NurbsCurve::try_new(3, knots, coefs, None).unwrap();
        let jump =
            |t: f64| (curve.derivs(t + 1e-9).d3 - curve.derivs(t - 1e-9).d3).length_squared();
        let want = jump(1.0) + jump(2.5);
        assert!(want > 1.0);
        assert!(
            (roughness(&spline) - want).abs() < 1e-9 * want,
            "{} vs {want}",
            roughness(&spline)
        );
        // A polynomial has none.
        let cubic = Spline {
            degree: 3,
            knots: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            coefs: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE],
            p: 1.0,
            fp: 0.0,
            reached: true,
        };
        assert_eq!(roughness(&cubic), 0.0);
    }

    /// The greatest curvature of `curve` (the fairness metrics' dense sampling).
    fn max_curvature(curve: &NurbsCurve) -> f64 {
        crate::fair::metrics::fairness_metrics(curve).max_curvature
    }

    #[test]
    fn a_short_piece_keeps_to_its_tolerance_not_to_its_points() {
        // KCS wl_z0.30's last three points, past its corner at the stem: the middle one lies
        // 4.1 mm off the chord between the other two.
        let pts = [
            DVec3::new(228.243, 0.035, 0.3),
            DVec3::new(228.241, 0.027, 0.3),
            DVec3::new(228.209, 0.0, 0.3),
        ];
        let off_chord = {
            let d = (pts[2] - pts[0]).normalize();
            (pts[1] - pts[0]).cross(d).length()
        };
        assert!((off_chord - 0.0041).abs() < 1e-4, "{off_chord}");
        let fit = |tol: f64| {
            fit_within(&pts, 3, tol, Directions::default(), 8)
                .unwrap()
                .unwrap()
        };
        // Exact (S = 0): the interpolating quadratic, which turns at some 30 /m.
        let exact = fit_smooth(
            &pts,
            3,
            Target::exact(0.0),
            Directions::default(),
            8,
            None,
            None,
        )
        .unwrap();
        let d = deviation(&exact.curve, &pts).unwrap();
        assert!(d.max < 1e-9, "{}", d.max);
        let curl = max_curvature(&exact.curve);
        assert!(curl > 25.0, "{curl}");
        // Within 3.5 mm: the blend nearest the chord, under a fifth of the turn (4.8 /m against
        // 27 /m); its ends stay.
        let within = fit(0.0035);
        let d = deviation(&within.curve, &pts).unwrap();
        assert!(d.max <= 0.0035 && d.max > 0.003, "{}", d.max);
        let turn = max_curvature(&within.curve);
        assert!(turn < curl / 5.0, "{turn} vs {curl}");
        let (a, b) = within.curve.domain();
        assert!(within.curve.point(a).distance(pts[0]) < 1e-12);
        assert!(within.curve.point(b).distance(pts[2]) < 1e-12);
        // Within 5 mm the chord is near enough: a straight line.
        let straight = fit(0.005);
        assert!(max_curvature(&straight.curve) < 1e-9);
        assert_eq!(within.curve.degree(), 3);
    }
}
