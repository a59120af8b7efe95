//! Curve fairing: a smoothing B-spline through a sequence of measured or digitised points, as in
//! the H-rep paper §4 (eqs. 9–12), which follows Dierckx, *Curve and Surface Fitting with
//! Splines* (1993), ch. 5 and 6 (FITPACK curfit/parcur).
//!
//! The fit minimises the fairness functional `J` (sum of squared jumps of the k-th derivative at
//! the interior knots) subject to `E ≤ S` (`E` the sum of squared distances of the points from
//! the curve at their parameters). Knots are added one at a time at the parametric middle of the
//! span with the largest error until the least-squares spline meets `S`; then the smoothing
//! parameter p with `E = S` is found by Dierckx's rational interpolation. Parameters start as
//! chord lengths and are corrected by foot-point projection until they settle. End points are
//! interpolated, end tangents may be fixed, and corners (knuckle points) split the fit into
//! pieces joined with a knot of multiplicity `degree`, so the curve stays sharp there.
//!
//! Two refinements for fairness (both measured in `tests/fair.rs` and
//! `blender_scripts/bench_fairing.py`): once some span's residuals are significantly more
//! than noise explains, knots go where that excess is largest (bias) rather than where the
//! plain sum is (`knots::next_knots`); and small curvature lobes that the data do not demand
//! (a hook at a free end, ripples on a flat) are flattened by refits with zero curvature at
//! their peaks, each accepted by a likelihood-ratio test (`lobes`); in noise mode, the lobes
//! a spline rings with past a jump in curvature (a flat running into a bilge radius) are
//! flattened the same way on knots refined around them (`convex`).

mod clean;
mod convex;
mod error;
mod fit;
mod flat;
mod frame;
mod gaps;
mod knots;
mod lobes;
mod lsq;

// The CAD export fits its B-spline control points with the same banded least squares.
pub(crate) use lsq::BandedQr;
mod metrics;
pub(crate) use metrics::best_fit_normal;
mod param;
mod piece;

use glam::DVec3;

pub use clean::corner_indices;
pub use error::FairError;
pub use flat::{FlatPlane, MIN_FLAT_RUN};
pub use metrics::{
    curvature_variation, fairness_metrics, FairnessMetrics, EXTREMUM_THRESHOLD,
    INFLECTION_THRESHOLD,
};

use crate::curve::NurbsCurve;
use crate::defaults::{
    DEFAULT_CORNER_ANGLE_DEGREES, DEFAULT_FAIR_DEGREE, DEFAULT_FAIR_TOLERANCE,
    DEFAULT_PARAMETER_ITERATIONS,
};
use crate::tolerance::Tolerance;
use clean::ORDER_STEP;
use fit::Target;
use frame::Frame;
use gaps::fit_within_gaps;
use piece::{fit_smooth, join, Directions, PieceFit};

/// Largest coordinate (m) the fitter takes: its squared distances and their sums over the
/// points must stay finite (f64 squares overflow beyond about 1.3e154).
const MAX_COORDINATE: f64 = 1e150;

/// A closeness finer than this many ulps of the points' largest coordinate cannot be measured
/// (every distance the fit compares is a difference of such coordinates).
const RESOLUTION_ULPS: f64 = 16.0;

/// Refuse points beyond [`MAX_COORDINATE`] ([`FairError::CoordinatesTooLarge`]), and a
/// closeness (tolerance, noise or √(S/M)) finer than f64 resolves at the points
/// ([`FairError::BelowResolution`]) or so coarse that its smoothing factor overflows
/// ([`FairError::ClosenessOverflow`]).
fn check_resolution(pts: &[DVec3], smoothing: Smoothing) -> Result<(), FairError> {
    let size = pts
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    if let Some(index) = pts
        .iter()
        .position(|p| p.abs().max_element() > MAX_COORDINATE)
    {
        return Err(FairError::CoordinatesTooLarge {
            index,
            limit: MAX_COORDINATE,
        });
    }
    let resolvable = RESOLUTION_ULPS * f64::EPSILON * size;
    let asked = match smoothing {
        Smoothing::MaxDeviation(t) => t,
        Smoothing::Noise(s) => s,
        Smoothing::Factor(f) => (f / pts.len() as f64).sqrt(),
    };
    if asked < resolvable {
        return Err(FairError::BelowResolution { asked, resolvable });
    }
    // The smoothing factor S = M·closeness² (m²) must be a number too.
    if !(asked * asked * pts.len() as f64).is_finite() {
        return Err(FairError::ClosenessOverflow { asked });
    }
    Ok(())
}

/// Highest degree the fairing accepts (Dierckx's curfit: 1 ≤ k ≤ 5).
pub const MAX_FAIR_DEGREE: usize = 5;

/// How close the faired curve must stay to the points: the smoothing factor S of Dierckx
/// (1993) eq. 5.3 / the H-rep paper eq. 9, given in one of three ways.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Smoothing {
    /// The largest orthogonal distance (metres) of any point from the curve. S is searched
    /// downwards from `M·tol²` (M points) until the fit is within the tolerance.
    MaxDeviation(f64),
    /// The noise level σ (metres): the RMS distance of the points from the true curve. Then
    /// `S = M·σ²`, the H-rep paper's eq. 9 with the mean deviation σ and unit weights, and
    /// Dierckx's advice for data with known standard deviation (1993 §5.2.2).
    ///
    /// Implementation note: the sum of squares of pure noise scatters by about `√(2M)·σ²`
    /// about `M·σ²`, so knots stop being added once the least-squares spline is within
    /// `(M + √(2M))·σ²` (the upper end of Dierckx's range for S); adding more would fit the
    /// noise. If it stops above `M·σ²`, the least-squares spline is the result.
    Noise(f64),
    /// S itself (square metres): the bound on the sum of squared distances.
    Factor(f64),
}

/// How many standard deviations Gaussian noise reaches, for the scale of the data's detail: it
/// lies farther from the mean at about 1 point in 16,000.
pub(crate) const NOISE_REACH: f64 = 4.0;

impl Smoothing {
    /// How far `points` points may stray from the curve (m): the tolerance, or the noise's reach
    /// (σ given, or `√(S/M)` from the smoothing factor). Detail below it is not resolved by the
    /// fit, so corners and order are decided at this scale.
    fn reach(self, points: usize) -> f64 {
        match self {
            Smoothing::MaxDeviation(t) => t,
            Smoothing::Noise(sigma) => NOISE_REACH * sigma,
            Smoothing::Factor(s) => NOISE_REACH * (s / points.max(1) as f64).sqrt(),
        }
    }
}

/// Options of [`fair_points`].
#[derive(Clone, Debug, PartialEq)]
pub struct FairOptions {
    /// Spline degree, 1..=5 (default 3).
    pub degree: usize,
    /// How close to the points (default: within 1 mm).
    pub smoothing: Smoothing,
    /// Indices (into the input points) of knuckle points the curve must keep sharp.
    pub corners: Vec<usize>,
    /// Also treat as corners the points where the polyline turns by more than this angle
    /// (radians) over a length the fit resolves ([`corner_indices`] at the scale of the
    /// tolerance or noise); `None` to detect none (default 45°).
    pub corner_angle: Option<f64>,
    /// Fixed tangent direction at the first point (pointing along the curve); the end
    /// derivative is this unit vector times the fit's mean speed, as Dierckx's concur fixes end
    /// derivatives. Needs degree ≥ 2 (≥ 3 with both tangents).
    pub start_tangent: Option<DVec3>,
    /// Fixed tangent direction at the last point (pointing along the curve, i.e. out of it).
    pub end_tangent: Option<DVec3>,
    /// Points closer than this to the previous kept point are duplicates and are dropped.
    pub model_tolerance: Tolerance,
    /// Most foot-point parameter corrections per fit (default 20; 0 keeps chord lengths).
    pub max_parameter_iterations: usize,
    /// Planes stretches of the points may run in (a section's flat of bottom, the hull's flat
    /// of side): each such run becomes a straight piece in its plane and the curve leaves it
    /// tangentially (see [`FlatPlane`]; default none). Where runs in two planes overlap, the
    /// one that starts first is kept.
    pub flats: Vec<FlatPlane>,
}

impl Default for FairOptions {
    fn default() -> Self {
        FairOptions {
            degree: DEFAULT_FAIR_DEGREE,
            smoothing: Smoothing::MaxDeviation(DEFAULT_FAIR_TOLERANCE),
            corners: Vec::new(),
            corner_angle: Some(DEFAULT_CORNER_ANGLE_DEGREES.to_radians()),
            start_tangent: None,
            end_tangent: None,
            model_tolerance: Tolerance::DEFAULT,
            max_parameter_iterations: DEFAULT_PARAMETER_ITERATIONS,
            flats: Vec::new(),
        }
    }
}

/// What the fit of one smooth piece (between corners or ends) came to.
#[derive(Clone, Debug, PartialEq)]
pub struct PieceReport {
    /// Points in the piece (corner points count in both pieces they end).
    pub points: usize,
    /// Interior knots of the piece.
    pub interior_knots: usize,
    /// The smoothing factor S the piece was fitted to (m²).
    pub smoothing_factor: f64,
    /// E, the sum of squared distances at the final parameters (m²).
    pub residual: f64,
    /// Dierckx's smoothing parameter p: 0 for the least-squares polynomial, ∞ for the
    /// least-squares spline.
    pub p: f64,
    /// Foot-point parameter corrections made.
    pub parameter_iterations: usize,
    /// True when the parameters settled before the iteration limit.
    pub parameters_settled: bool,
}

/// The report of one faired curve: size, closeness and fairness.
#[derive(Clone, Debug, PartialEq)]
pub struct FairReport {
    /// Number of control points.
    pub control_points: usize,
    /// The knot vector.
    pub knots: Vec<f64>,
    /// Largest orthogonal distance of a (kept) point from the curve (m).
    pub max_deviation: f64,
    /// Input index of the point at `max_deviation`.
    pub max_deviation_index: usize,
    /// Root mean square orthogonal distance of the kept points from the curve (m).
    pub rms_deviation: f64,
    /// Inflections, curvature extrema and ∫κ² ds of the faired curve.
    pub metrics: FairnessMetrics,
    /// Sum of the pieces' smoothing factors (m²).
    pub smoothing_factor: f64,
    /// Consecutive duplicate points dropped before fitting.
    pub dropped_duplicates: usize,
    /// Input indices of the corners kept (given and detected).
    pub corners: Vec<usize>,
    /// Curve parameters of those corners (knots of multiplicity `degree`).
    pub corner_parameters: Vec<f64>,
    /// One report per smooth piece.
    pub pieces: Vec<PieceReport>,
    /// Where the curve leaves its straight flat runs ([`FairOptions::flats`]), in order along
    /// it: one for a run at an end of the curve, two for a run between; none where a corner is
    /// (a chine where a flat starts stays a corner, in `corners`).
    pub flats: Vec<FlatEnd>,
}

/// Where a faired curve leaves a flat run: an end of the straight piece that is not an end of
/// the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatEnd {
    /// Index of the run's plane in [`FairOptions::flats`].
    pub plane: usize,
    /// Input index of the point where the curve leaves the run.
    pub index: usize,
    /// Its curve parameter (a knot of multiplicity `degree`; the curve is G1 there).
    pub parameter: f64,
    /// Its position (on the plane).
    pub point: DVec3,
}

/// A faired curve and its report.
#[derive(Clone, Debug, PartialEq)]
pub struct FairedCurve {
    /// The smoothing spline: a clamped non-rational B-spline through the end points whose
    /// parameter runs over the chord length of the points.
    pub curve: NurbsCurve,
    /// How it was made and how good it is.
    pub report: FairReport,
}

/// Fair a sequence of points into a smooth B-spline curve (H-rep paper §4; Dierckx 1993 ch. 5,
/// FITPACK curfit/parcur with single-knot insertion).
///
/// Clean-up first: non-finite coordinates are an error; consecutive points within the model
/// tolerance of the previous kept point are dropped and counted (the last point is kept
/// exactly); points not in order along the curve are an error. Then the curve is split at the
/// corners (given and detected), each piece is fitted (end points interpolated; end tangents
/// fixed where asked), and the pieces are joined with knots of multiplicity `degree`.
pub fn fair_points(points: &[DVec3], options: &FairOptions) -> Result<FairedCurve, FairError> {
    let k = options.degree;
    if !(1..=MAX_FAIR_DEGREE).contains(&k) {
        return Err(FairError::Degree { degree: k });
    }
    match options.smoothing {
        Smoothing::MaxDeviation(t) if !(t.is_finite() && t > 0.0) => {
            return Err(FairError::Tolerance(t))
        }
        Smoothing::Noise(s) if !(s.is_finite() && s > 0.0) => return Err(FairError::Noise(s)),
        Smoothing::Factor(s) if !(s.is_finite() && s > 0.0) => {
            return Err(FairError::SmoothingFactor(s))
        }
        _ => {}
    }
    if let Some(a) = options.corner_angle {
        if !(a > 0.0 && a < std::f64::consts::PI) {
            return Err(FairError::CornerAngle(a));
        }
    }
    let flat_planes = options
        .flats
        .iter()
        .map(FlatPlane::checked)
        .collect::<Result<Vec<_>, _>>()?;
    let start_dir = direction(options.start_tangent, "start")?;
    let end_dir = direction(options.end_tangent, "end")?;
    let tangents = usize::from(start_dir.is_some()) + usize::from(end_dir.is_some());
    if tangents > 0 && k < tangents + 1 {
        return Err(FairError::TangentDegree {
            degree: k,
            tangents,
            needed: tangents + 1,
        });
    }
    for &index in &options.corners {
        if index == 0 || index + 1 >= points.len() {
            return Err(FairError::CornerIndex {
                index,
                count: points.len(),
            });
        }
    }

    let tol = options.model_tolerance.get();
    let cleaned = clean::clean(points, tol)?;
    let pts = &cleaned.points;
    let m = pts.len();
    if m < k + 1 {
        return Err(FairError::TooFewPoints {
            count: m,
            needed: k + 1,
            degree: k,
            dropped: cleaned.dropped,
        });
    }
    check_resolution(pts, options.smoothing)?;
    clean::check_order(pts, options.smoothing.reach(m))?;

    // Corners in cleaned indexing: a given corner that was dropped as a duplicate moves to the
    // kept point it duplicated.
    let mut corners: Vec<usize> = options
        .corners
        .iter()
        .map(|&c| cleaned.index.partition_point(|&i| i <= c) - 1)
        .collect();
    if let Some(angle) = options.corner_angle {
        corners.extend(corner_indices(pts, angle, options.smoothing.reach(m)));
    }
    corners.retain(|&c| c > 0 && c + 1 < m);
    // A flat run is one straight piece: no corner inside it; its ends (but the curve's) are
    // joints, smooth ones (the curve leaves the flat along it) unless a corner is there (a
    // chine where the flat of side starts stays a knuckle).
    let runs = flat::runs_of(&flat_planes, pts, k);
    corners.retain(|&c| !runs.iter().any(|r| r.first < c && c < r.last));
    let smooth_joints: Vec<usize> = runs
        .iter()
        .flat_map(|r| [r.first, r.last])
        .filter(|&j| j > 0 && j + 1 < m && !corners.contains(&j))
        .collect();
    corners.extend(&smooth_joints);
    corners.sort_unstable();
    corners.dedup();
    let mut straight = pts.clone();
    for run in &runs {
        run.straighten(&mut straight, &flat_planes[run.plane]);
    }
    let fit_pts: &[DVec3] = &straight;

    // The fit works in the data's own frame (see `frame`); its results are moved back.
    let frame = Frame::of(pts);
    let local: Vec<DVec3> = pts.iter().map(|&p| frame.to_local(p)).collect();
    let fit_local: Vec<DVec3> = fit_pts.iter().map(|&p| frame.to_local(p)).collect();
    let smoothing = frame.smoothing(options.smoothing);
    let mut bounds = vec![0];
    bounds.extend_from_slice(&corners);
    bounds.push(m - 1);
    let count = bounds.len() - 1;
    // A straight flat's direction in the frame, fixed at both sides of each of its smooth
    // joints.
    let at_straight = |index: usize| {
        runs.iter()
            .filter(|r| r.ends_at(index) && smooth_joints.contains(&index))
            .find_map(|r| r.direction)
            .map(|d| (frame.to_local(d) - frame.to_local(DVec3::ZERO)).normalize())
    };
    // The pieces that are runs curving in their plane are fitted first, so that the pieces
    // beside them take their end tangents.
    let planar_piece = |w: &[usize]| {
        runs.iter()
            .any(|r| r.direction.is_none() && r.first == w[0] && r.last == w[1])
    };
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by_key(|&i| !planar_piece(&bounds[i..=i + 1]));
    let mut local_fits: Vec<Option<PieceFit>> = vec![None; count];
    for i in order {
        let w = &bounds[i..=i + 1];
        let piece = &fit_local[w[0]..=w[1]];
        // At a smooth joint: a straight flat's direction, or the end tangent of the fitted
        // curved flat there (`piece` on the joint's other side).
        let at_flat = |index: usize, other: Option<usize>| {
            at_straight(index).or_else(|| {
                let other = other.filter(|_| smooth_joints.contains(&index))?;
                let fit = local_fits[other].as_ref()?;
                let c = &fit.spline.coefs;
                let d = if other < i {
                    c[c.len() - 1] - c[c.len() - 2]
                } else {
                    c[1] - c[0]
                };
                d.try_normalize()
            })
        };
        let dirs = Directions {
            start: if i == 0 {
                start_dir
            } else {
                at_flat(w[0], Some(i - 1))
            },
            end: if i + 1 == count {
                end_dir
            } else {
                at_flat(w[1], Some(i + 1))
            },
        };
        let iters = options.max_parameter_iterations;
        let fit = match smoothing {
            Smoothing::MaxDeviation(t) => match fit_within_gaps(piece, k, t, dirs, iters)? {
                Ok(fit) => fit,
                Err((achieved, index)) => {
                    return Err(FairError::ToleranceNotReached {
                        tolerance: frame.length(t),
                        achieved: frame.length(achieved),
                        index: cleaned.index[w[0] + index],
                    })
                }
            },
            Smoothing::Noise(sigma) => {
                // S = M·σ²; the knots may stop within one standard deviation of the noise's
                // sum of squares above it, M + √(2M) (Dierckx 1993 §5.2.2's range for S).
                let mp = piece.len() as f64;
                let s = Target {
                    s: mp * sigma * sigma,
                    accept: (mp + (2.0 * mp).sqrt()) * sigma * sigma,
                    noise: true,
                };
                // The parameters start as the arc length of the data at the scale the fit
                // resolves (see `param::resolved_chord_length`); without a noise level they
                // start at the points' chord lengths (tolerance mode: design offsets, taken
                // as they are).
                //
                // Choice: S given (KCS st10, 2,000 points, σ = 5 mm, `bench_fairing.py`)
                // would gain with chord lengths only (252 → 28 knots, 39 → 8 inflections)
                // but lose a little with the parameter correction (6 → 8 inflections,
                // 2.49 → 2.67 mm from the truth): left as it was.
                let resolution = ORDER_STEP * smoothing.reach(m);
                fit_smooth(piece, k, s, dirs, iters, Some(resolution), None)?
            }
            Smoothing::Factor(s) => {
                let share = (piece.len() - 1) as f64 / (m - 1) as f64;
                fit_smooth(piece, k, Target::exact(s * share), dirs, iters, None, None)?
            }
        };
        local_fits[i] = Some(fit);
    }
    let mut pieces: Vec<PieceFit> = Vec::with_capacity(count);
    for (fit, w) in local_fits.into_iter().zip(bounds.windows(2)) {
        let fit = fit.expect("every piece is fitted");
        pieces.push(frame.piece_to_world(fit, (fit_pts[w[0]], fit_pts[w[1]]))?);
    }

    let (knots, coefs, mut corner_parameters) = join(&pieces, k);
    // A flat's smooth joints are no corners; said apart.
    // (`corners` holds them, pushed above, at the same places as their joints.)
    let mut flat_ends = Vec::new();
    let mut at = 0;
    while at < corners.len() {
        let c = corners[at];
        let mut ending = runs
            .iter()
            .filter(|r| r.ends_at(c) && smooth_joints.contains(&c));
        match (ending.next(), ending.next()) {
            // Where a curved run meets a straight one, the curve stays on the flat.
            (Some(_), Some(_)) => {
                corners.remove(at);
                corner_parameters.remove(at);
            }
            (Some(run), None) => {
                corners.remove(at);
                flat_ends.push(FlatEnd {
                    plane: run.plane,
                    index: cleaned.index[c],
                    parameter: corner_parameters.remove(at),
                    point: fit_pts[c],
                });
            }
            (None, _) => at += 1,
        }
    }
    let curve = NurbsCurve::try_new(k, knots.clone(), coefs, None)?;
    // A single piece is the curve itself (its parameters start at 0, so joining leaves knots
    // and control points as they were): what its fit measured holds for the curve.
    let single = match pieces.as_slice() {
        [p] if p.curve.knots() == curve.knots()
            && p.curve.control_points() == curve.control_points() =>
        {
            Some(p)
        }
        _ => None,
    };
    let dev = match single.and_then(|p| p.deviation) {
        Some(dev) => dev,
        None => frame.deviation(&curve, &local)?,
    };
    let fairness = single
        .and_then(|p| p.metrics)
        .unwrap_or_else(|| fairness_metrics(&curve));
    let report = FairReport {
        control_points: curve.control_point_count(),
        knots,
        max_deviation: dev.max,
        max_deviation_index: cleaned.index[dev.max_index],
        rms_deviation: dev.rms,
        metrics: fairness,
        smoothing_factor: pieces.iter().map(|p| p.s).sum(),
        dropped_duplicates: cleaned.dropped,
        corners: corners.iter().map(|&c| cleaned.index[c]).collect(),
        corner_parameters,
        pieces: pieces
            .iter()
            .zip(bounds.windows(2))
            .map(|(p, w)| PieceReport {
                points: w[1] - w[0] + 1,
                interior_knots: p.spline.knots.len() - 2 * (p.spline.degree + 1),
                smoothing_factor: p.s,
                residual: p.spline.fp,
                p: p.spline.p,
                parameter_iterations: p.iterations,
                parameters_settled: p.settled,
            })
            .collect(),
        flats: flat_ends,
    };
    Ok(FairedCurve { curve, report })
}

fn direction(v: Option<DVec3>, end: &'static str) -> Result<Option<DVec3>, FairError> {
    match v {
        None => Ok(None),
        Some(d) if d.is_finite() && d.length_squared() > 0.0 => Ok(Some(d.normalize())),
        Some(d) => Err(FairError::Tangent {
            end,
            value: d.to_array(),
        }),
    }
}
