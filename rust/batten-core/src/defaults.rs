//! Every default and limit a front end offers, defined once (the binding, the scripting API and
//! the panel read them from here).

/// The model tolerance (m), 0.1 mm: well below drawing accuracy at ship scale and well above the
/// f64 rounding of coordinates of a few hundred metres ([`Tolerance::DEFAULT`](crate::Tolerance::DEFAULT)).
pub const DEFAULT_TOLERANCE: f64 = 1e-4;
/// Tessellation intervals per edge of a hull build.
pub const DEFAULT_RESOLUTION: usize = 8;
/// The largest tessellation resolution accepted (intervals per edge): at 256 a 150-patch hull is
/// about ten million quads, the most a viewport handles.
pub const MAX_RESOLUTION: usize = 256;
/// Largest deviation (m) of a faired curve from the points of a drawn curve: 1 mm.
pub const DEFAULT_FAIR_TOLERANCE: f64 = 1e-3;
/// Largest deviation (m) of an imported section from its offsets: 5 mm, the drawing accuracy of
/// a lines plan at ship scale.
pub const DEFAULT_SECTION_TOLERANCE: f64 = 5e-3;
/// Model tolerance (m) of imported sections: points of a section closer than 1 mm are one point.
pub const DEFAULT_SECTION_MODEL_TOLERANCE: f64 = 1e-3;
/// Imported curves meet where they come within this many times the import tolerance of each
/// other, and are snapped together there: each curve is within the tolerance of the data, so
/// two curves through one data point are within twice it.
pub const SECTION_CAPTURE_FACTOR: f64 = 2.0;
/// Turns sharper than this (degrees) in a polyline are kept as corners when it is faired.
pub const DEFAULT_CORNER_ANGLE_DEGREES: f64 = 45.0;
/// Degree of a faired curve (cubic).
pub const DEFAULT_FAIR_DEGREE: usize = 3;
/// Rounds of parameter correction (foot points) in a fit.
pub const DEFAULT_PARAMETER_ITERATIONS: usize = 20;
