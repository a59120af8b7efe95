//! Typed errors of the core. The Python binding maps them, in one place, to `BattenError`.

use thiserror::Error;

use crate::fair::FairError;
use crate::patch::PatchError;

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
    /// The parameter domain has zero length.
    #[error("the parameter domain [{start}, {end}] is empty")]
    EmptyDomain {
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
    /// Weights must be positive and finite.
    #[error("weight {index} is {value}; weights must be positive and finite")]
    BadWeight {
        /// Index of the weight.
        index: usize,
        /// The offending value.
        value: f64,
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
    /// A query point is not finite.
    #[error("query point has a non-finite coordinate")]
    NonFiniteQuery,
}

/// Any error of the core, naming the designer curve where there is one.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A problem with one named curve.
    #[error("curve '{curve}': {source}")]
    Curve {
        /// The designer curve's name (the Blender object name, or the name in a network file).
        curve: String,
        /// What is wrong.
        #[source]
        source: CurveError,
    },
    /// Fairing the points of one named curve failed.
    #[error("curve '{curve}': {source}")]
    Fair {
        /// The designer curve's name.
        curve: String,
        /// What is wrong with its points or the fairing options.
        #[source]
        source: FairError,
    },
    /// The model tolerance is not a positive finite number (an invalid argument).
    #[error("tolerance {0} must be a positive finite number of metres")]
    Tolerance(f64),
    /// The tessellation resolution is outside `1..=max` (an invalid argument).
    #[error("resolution {resolution} must be between 1 and {max} intervals per edge")]
    Resolution {
        /// The resolution asked for.
        resolution: usize,
        /// The largest accepted.
        max: usize,
    },
    /// Two curves in one network share a name.
    #[error("two curves are named '{0}'; curve names in a network must be unique")]
    DuplicateName(String),
    /// A curve has no name.
    #[error("curve {0} has an empty name")]
    EmptyName(usize),
    /// A network file could not be read.
    #[error("network file: {0}")]
    Format(String),
    /// The network gives no hull surface: it has no faces (the message names the topology's
    /// diagnostics), none of its faces could be patched, or the mesh request is invalid
    /// (H-rep paper §3: a surface needs closed regions of curves).
    #[error("no surface: {0}")]
    NoSurface(String),
    /// The hull's patches could not be tessellated into one mesh (too many vertices for its
    /// indices).
    #[error("no surface: {0}")]
    Mesh(#[from] PatchError),
}

impl FairError {
    /// Attach the name of the designer curve whose points were being faired.
    pub fn named(self, curve: impl Into<String>) -> Error {
        Error::Fair {
            curve: curve.into(),
            source: self,
        }
    }
}

impl CurveError {
    /// Attach the name of the designer curve this error belongs to.
    pub fn named(self, curve: impl Into<String>) -> Error {
        Error::Curve {
            curve: curve.into(),
            source: self,
        }
    }
}
