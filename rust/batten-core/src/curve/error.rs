//! Typed errors of the curve kernel.

use thiserror::Error;

/// What is wrong with one curve's definition or with an operation on it.
///
/// These carry the evidence (which index, which value) but not the curve's name; [`Error::Curve`]
/// adds the name of the designer curve they belong to.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CurveError {
    /// The degree is zero or larger than the kernel supports.
    #[error("degree {degree} is outside 1..={max}")]
    Degree {
        /// The degree asked for.
        degree: usize,
        /// The largest degree supported.
        max: usize,
    },
    /// The order (degree + 1) of a spline given by its order, as Blender's NURBS splines are,
    /// is outside what the kernel supports.
    #[error("order {order} is outside 2..={max} (degree 1 to {})", max - 1)]
    Order {
        /// The order asked for.
        order: usize,
        /// The largest order supported.
        max: usize,
    },
    /// Not enough control points for the order.
    #[error("{count} control points are fewer than order {order} needs ({order} at least)")]
    TooFewPoints {
        /// Control points given.
        count: usize,
        /// Order (degree + 1).
        order: usize,
    },
    /// A control point has a NaN or infinite coordinate.
    #[error("control point {index} has a non-finite coordinate ({value})")]
    NonFinitePoint {
        /// Index of the control point.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The knot vector has the wrong length.
    #[error("{got} knots given, {expected} expected (control points + order)")]
    KnotCount {
        /// Knots expected.
        expected: usize,
        /// Knots given.
        got: usize,
    },
    /// A knot is NaN or infinite.
    #[error("knot {index} is not finite ({value})")]
    NonFiniteKnot {
        /// Index of the knot.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// Knots must not decrease.
    #[error("knots decrease at index {index} ({prev} > {next})")]
    DecreasingKnots {
        /// Index of the knot that is smaller than its predecessor.
        index: usize,
        /// The predecessor.
        prev: f64,
        /// The smaller knot.
        next: f64,
    },
    /// An interior knot repeated more than the degree would break the curve in two.
    #[error(
        "knot {value} is repeated {multiplicity} times; at most {max} keeps the curve connected"
    )]
    KnotMultiplicity {
        /// The knot value.
        value: f64,
        /// How often it appears.
        multiplicity: usize,
        /// The most allowed at that place.
        max: usize,
    },
    /// A knot span so short that its reciprocal overflows f64: the basis functions on it
    /// evaluate to NaN.
    #[error("knot span {index} is {span:e} wide, too short for f64 to evaluate")]
    ShortSpan {
        /// Index of the knot the span starts at.
        index: usize,
        /// Its width.
        span: f64,
    },
    /// The parameter domain has zero length.
    #[error("the parameter domain [{start}, {end}] is empty")]
    EmptyDomain {
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
    /// A positive weight too small to survive knot insertion: the edits' convex combinations
    /// of it would fall below the smallest normal f64.
    #[error("weight {index} is {value:e}, below the smallest weight batten can edit ({min:e})")]
    TinyWeight {
        /// Index of the weight.
        index: usize,
        /// Its value.
        value: f64,
        /// The smallest weight accepted.
        min: f64,
    },
    /// Weights must be positive and finite.
    #[error("weight {index} is {value}; weights must be positive and finite")]
    BadWeight {
        /// Index of the weight.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A control point times its weight is not representable (overflows, or the weight is
    /// below the smallest normal f64).
    #[error("control point {index} times its weight is not representable in f64 (overflow or a subnormal weight)")]
    WeightedPointOverflow {
        /// Index of the control point.
        index: usize,
    },
    /// The number of weights differs from the number of control points.
    #[error("{got} weights given for {expected} control points")]
    WeightCount {
        /// Weights expected.
        expected: usize,
        /// Weights given.
        got: usize,
    },
    /// The curve collapses to a point.
    #[error("the curve has zero length (length {length:.3e} m is below the tolerance {tolerance:.3e} m)")]
    ZeroLength {
        /// The measured length.
        length: f64,
        /// The model tolerance.
        tolerance: f64,
    },
    /// A parameter lies outside the curve's domain (or on its end, where a split is meaningless).
    #[error("parameter {t} is outside the domain ({start}, {end})")]
    ParameterOutOfDomain {
        /// The parameter.
        t: f64,
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
    /// A knot cannot be inserted that often.
    #[error("knot {t} cannot be inserted {times} more times (multiplicity would exceed the degree {degree})")]
    InsertTooOften {
        /// The knot.
        t: f64,
        /// How many insertions were asked for.
        times: usize,
        /// The curve degree.
        degree: usize,
    },
    /// An accuracy argument must be positive and finite.
    #[error("accuracy {0} must be a positive finite number")]
    Accuracy(f64),
    /// An accuracy finer than f64 can resolve for the quantity measured.
    #[error("accuracy {accuracy:.3e} m is finer than f64 resolves for this curve ({resolvable:.3e} m); ask for a coarser accuracy or tolerance")]
    AccuracyBelowResolution {
        /// The accuracy asked for.
        accuracy: f64,
        /// The finest accuracy f64 resolves here.
        resolvable: f64,
    },
    /// The curve's length overflows f64 (coordinates or derivatives too large).
    #[error("the curve's length is not finite: its derivative overflows f64 (coordinates too large, or a knot span too short)")]
    NonFiniteLength,
    /// The adaptive arc-length quadrature did not settle to the accuracy within its work
    /// limit: the curve's speed is too rough (extreme weights or knot spans).
    #[error("its length does not settle to the accuracy {accuracy:e} m (its speed varies too sharply: extreme weights or knot spans)")]
    ArcLengthUnsettled {
        /// The accuracy asked for.
        accuracy: f64,
    },
    /// An edit at `t` would leave a knot span too short for f64 to evaluate.
    #[error(
        "an edit at parameter {t:e} leaves a knot span of {span:e}, too short for f64 to evaluate"
    )]
    SpanTooShort {
        /// Where the edit was made.
        t: f64,
        /// The span it leaves.
        span: f64,
    },
    /// A parameter to evaluate at is NaN or infinite.
    #[error("parameter {0} is not a finite number")]
    NonFiniteParameter(f64),
    /// The distance from a query point to the curve overflows f64 (the point or the curve lies
    /// too far out).
    #[error("the distance to the query point overflows f64 (coordinates too large)")]
    DistanceOverflow,
    /// The derivatives or the curvature at a parameter overflow f64 (a knot span tiny beside
    /// the coordinates, extreme neighbouring weights, or a speed near zero).
    #[error("its derivatives or curvature at parameter {t:e} overflow f64 (a knot span too short for its size, extreme weights, or a cusp)")]
    DerivativeOverflow {
        /// Where.
        t: f64,
    },
    /// A figure measured on the curve (curvature, its integral) overflows f64.
    #[error("its fairness figures overflow f64 (coordinates too large)")]
    FiguresOverflow,
    /// A query point is not finite.
    #[error("query point has a non-finite coordinate")]
    NonFiniteQuery,
    /// Two targets of [`NurbsCurve::through`] at one parameter ask for different points.
    #[error("two targets at parameter {t} ask for different points")]
    TargetsConflict {
        /// The parameter.
        t: f64,
    },
    /// The control points cannot meet all targets of [`NurbsCurve::through`] at once.
    #[error(
        "the targets cannot all be met by moving the control points (they are not independent)"
    )]
    TargetsDependent,
}
