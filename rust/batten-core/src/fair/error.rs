//! Typed errors of curve fairing: every bad input gives one of these, never a panic.

use thiserror::Error;

use crate::curve::CurveError;

/// What is wrong with a point sequence or with the options given to [`fair_points`].
///
/// Each variant carries the evidence (which index, which value) so that the add-on can tell the
/// designer what to change.
///
/// [`fair_points`]: crate::fair_points
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FairError {
    /// The flat plane has a zero or non-finite normal, a non-finite offset, a tolerance
    /// that is not a positive finite distance or a non-finite noise.
    #[error(
        "flat plane: normal {normal:?}, offset {offset}, tolerance {tolerance}, noise {noise}: \
         needs a finite non-zero normal, a finite offset, a positive finite tolerance and a \
         finite noise"
    )]
    FlatPlane {
        /// The normal given.
        normal: [f64; 3],
        /// The offset given.
        offset: f64,
        /// The tolerance given.
        tolerance: f64,
        /// The noise given.
        noise: f64,
    },
    /// The degree is outside the range the fitting supports (Dierckx's curfit allows 1..=5).
    #[error("fairing degree {degree} is outside 1..=5")]
    Degree {
        /// The degree asked for.
        degree: usize,
    },
    /// Too few distinct points for a spline of the asked degree.
    #[error(
        "{count} distinct points are too few for a degree-{degree} fit ({needed} at least; \
         {dropped} duplicate points were dropped)"
    )]
    TooFewPoints {
        /// Distinct points left after dropping duplicates.
        count: usize,
        /// Points needed (degree + 1).
        needed: usize,
        /// The degree asked for.
        degree: usize,
        /// Consecutive duplicates that were dropped.
        dropped: usize,
    },
    /// The asked closeness (tolerance, noise, or √(S/M) for a smoothing factor) is finer than
    /// f64 resolves at the points' coordinates (16 ulps of their largest magnitude): no fit
    /// could be measured to meet it.
    #[error(
        "the asked closeness {asked:.3e} m is finer than f64 resolves at these coordinates \
         ({resolvable:.3e} m); ask for a coarser tolerance or move the points nearer the origin"
    )]
    BelowResolution {
        /// The closeness asked for (m).
        asked: f64,
        /// What f64 resolves at the points (m).
        resolvable: f64,
    },
    /// A point lies so far from the origin that squared distances of the fit would overflow.
    #[error(
        "point {index} is more than {limit:.0e} m from the origin: too far for the fit's squared distances"
    )]
    CoordinatesTooLarge {
        /// Index of the point among the points kept (duplicates dropped).
        index: usize,
        /// The largest coordinate taken (m).
        limit: f64,
    },
    /// The asked closeness is so large that the smoothing factor `M·closeness²` overflows f64.
    #[error("the asked closeness {asked:.3e} m is too large: its smoothing factor overflows f64")]
    ClosenessOverflow {
        /// The closeness asked for (m).
        asked: f64,
    },
    /// Every point lies within the model tolerance of the first: there is no curve to fit.
    #[error("all {count} points coincide within the model tolerance {tolerance:.3e} m")]
    AllPointsIdentical {
        /// Points given.
        count: usize,
        /// The model tolerance used to compare them.
        tolerance: f64,
    },
    /// A point has a NaN or infinite coordinate.
    #[error("point {index} has a non-finite coordinate ({value})")]
    NonFinitePoint {
        /// Index of the point in the input.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The maximum deviation asked for is not a positive finite number of metres.
    #[error("the fairing tolerance {0} must be a positive finite number of metres")]
    Tolerance(f64),
    /// The noise level asked for is not a positive finite number of metres.
    #[error("the noise level σ = {0} must be a positive finite number of metres")]
    Noise(f64),
    /// The smoothing factor asked for is not a positive finite number of square metres.
    #[error("the smoothing factor S = {0} must be a positive finite number of square metres")]
    SmoothingFactor(f64),
    /// The corner-detection angle is not in (0, π).
    #[error("the corner angle {}° must lie strictly between 0° and 180°", .0.to_degrees())]
    CornerAngle(f64),
    /// A corner index given by the caller does not name an interior point.
    #[error("corner index {index} is not an interior point of the {count} points given")]
    CornerIndex {
        /// The index given.
        index: usize,
        /// Points given.
        count: usize,
    },
    /// An end tangent is zero or not finite.
    #[error("the {end} tangent {value:?} must be a non-zero finite vector")]
    Tangent {
        /// "start" or "end".
        end: &'static str,
        /// The vector given.
        value: [f64; 3],
    },
    /// Fixed end tangents need a degree above their number (one tangent: degree 2 or more; both:
    /// 3 or more), so that the polynomial with no interior knot can meet them.
    #[error("{tangents} fixed end tangent(s) need degree {needed} or more, not {degree}")]
    TangentDegree {
        /// The degree asked for.
        degree: usize,
        /// Fixed tangents asked for.
        tangents: usize,
        /// Smallest degree that takes them.
        needed: usize,
    },
    /// The points do not follow the curve in order (shuffled, or far noisier than their
    /// spacing): the polyline through them is much longer than a nearest-neighbour ordering.
    #[error(
        "the points are not in order along the curve: the polyline through them is \
         {path_length:.4} m long, a nearest-neighbour ordering only {ordered_length:.4} m \
         (largest jump after point {jump_index})"
    )]
    OutOfOrder {
        /// Length of the polyline through the points as given, at the data's resolution (its
        /// points the order check's step apart).
        path_length: f64,
        /// Length of a greedy nearest-neighbour ordering from the first point.
        ordered_length: f64,
        /// Index of the point after which the longest jump occurs.
        jump_index: usize,
    },
    /// No smoothing factor brought the maximum deviation under the tolerance.
    #[error(
        "the fit did not come within {tolerance:.3e} m of the points (best {achieved:.3e} m \
         at point {index})"
    )]
    ToleranceNotReached {
        /// The maximum deviation asked for.
        tolerance: f64,
        /// The smallest maximum deviation reached.
        achieved: f64,
        /// Index (in the input) of the point farthest from the best fit.
        index: usize,
    },
    /// The data parameters do not determine a spline (rounding made them coincide).
    #[error(
        "the {points} points of a piece do not determine a spline (their parameters coincide)"
    )]
    Unfittable {
        /// Points in the piece.
        points: usize,
    },
    /// Building the fitted curve failed (a bug if it ever happens: the fit keeps the curve
    /// invariants).
    #[error("building the faired curve: {0}")]
    Curve(#[from] CurveError),
}
