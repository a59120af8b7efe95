//! Typed errors and warnings of the patch module.

use thiserror::Error;

use crate::curve::CurveError;

/// Why a face boundary, a ribbon or a tessellation request was refused.
///
/// Every variant names the side (0-based, in the face's counter-clockwise order) and, where the
/// designer curves are known, their names, so that the add-on can tell the user which curves to
/// look at. Nothing in this module panics or returns NaN instead of one of these.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PatchError {
    /// A face needs at least three sides (H-rep paper §3.2.1: 3-, 4- and N-sided patches).
    #[error("a face needs at least 3 sides, this one has {sides}")]
    TooFewSides {
        /// Sides given.
        sides: usize,
    },
    /// More sides than the fixed-size evaluator supports.
    #[error("a face may have at most {max} sides, this one has {sides}")]
    TooManySides {
        /// Sides given.
        sides: usize,
        /// The largest number supported.
        max: usize,
    },
    /// A side without segments.
    #[error("side {side} has no curve segments")]
    EmptySide {
        /// Index of the side.
        side: usize,
    },
    /// A segment's parameter interval is not finite or leaves its curve's domain.
    #[error("side {side}, segment {segment} (curve '{curve}'): parameter {t} is not finite or outside the curve's domain [{start}, {end}]")]
    BadParameter {
        /// Index of the side.
        side: usize,
        /// Index of the segment within the side.
        segment: usize,
        /// Name of the curve.
        curve: String,
        /// The offending parameter.
        t: f64,
        /// Curve domain start.
        start: f64,
        /// Curve domain end.
        end: f64,
    },
    /// A side (or one segment of it) has (nearly) zero length.
    #[error("side {side} (curves {curves}) has zero length: {length:.3e} m is below the tolerance {tolerance:.3e} m")]
    ZeroLengthSide {
        /// Index of the side.
        side: usize,
        /// Names of the curves of the side, comma separated.
        curves: String,
        /// The measured length.
        length: f64,
        /// The model tolerance.
        tolerance: f64,
    },
    /// Consecutive segments of a composite side do not meet.
    #[error("side {side}: segments {segment} and {next} (curves '{curve}' and '{next_curve}') are {gap:.3e} m apart (more than {limit:.3e} m)")]
    SegmentGap {
        /// Index of the side.
        side: usize,
        /// Index of the first segment.
        segment: usize,
        /// Index of the following segment.
        next: usize,
        /// Name of the first segment's curve.
        curve: String,
        /// Name of the following segment's curve.
        next_curve: String,
        /// The gap.
        gap: f64,
        /// The largest gap accepted.
        limit: f64,
    },
    /// Consecutive sides do not meet at their shared corner.
    #[error("corner {corner}: side {prev} (curves {prev_curves}) ends {gap:.3e} m away from where side {next} (curves {next_curves}) starts (more than {limit:.3e} m)")]
    CornerGap {
        /// Index of the corner (the start of side `next`).
        corner: usize,
        /// The side ending at the corner.
        prev: usize,
        /// The side starting at the corner.
        next: usize,
        /// Names of the curves of side `prev`.
        prev_curves: String,
        /// Names of the curves of side `next`.
        next_curves: String,
        /// The gap.
        gap: f64,
        /// The largest gap accepted.
        limit: f64,
    },
    /// The number of side ribbons differs from the number of sides.
    #[error("{got} side ribbons given for {expected} sides")]
    RibbonCount {
        /// Sides of the face.
        expected: usize,
        /// Ribbons given.
        got: usize,
    },
    /// A side ribbon does not have one entry per segment of its side.
    #[error("side {side}: ribbon has {got} segment entries for {expected} segments")]
    RibbonSegments {
        /// Index of the side.
        side: usize,
        /// Segments of the side.
        expected: usize,
        /// Entries given.
        got: usize,
    },
    /// A ribbon node has a non-finite or out-of-range parameter, or a non-finite vector.
    #[error("ribbon node on curve '{curve}' at t = {t}: {reason}")]
    BadRibbonNode {
        /// Name of the curve carrying the node.
        curve: String,
        /// The node's parameter.
        t: f64,
        /// What is wrong.
        reason: String,
    },
    /// The 4-sided Gregory patch was asked for on a face that does not have 4 sides.
    #[error(
        "the Gregory patch needs 4 sides, this face has {sides}; use the Charrot–Gregory patch"
    )]
    GregoryNeedsFourSides {
        /// Sides of the face.
        sides: usize,
    },
    /// Tessellation needs at least one segment per side.
    #[error("tessellation resolution must be at least 1, got {0}")]
    Resolution(usize),
    /// Tessellation would produce more vertices than a `u32` index can address.
    #[error("tessellation would produce {0} vertices, more than u32 indices can address")]
    MeshTooLarge(usize),
    /// An operation of the curve kernel failed on a named curve.
    #[error("curve '{curve}': {source}")]
    Curve {
        /// Name of the curve.
        curve: String,
        /// What the kernel reported.
        #[source]
        source: CurveError,
    },
}

impl PatchError {
    /// A short stable tag for the kind of error (`"segment_gap"`, `"ribbon_count"`, …), for the
    /// binding and for filtering.
    pub fn kind(&self) -> &'static str {
        match self {
            PatchError::TooFewSides { .. } => "too_few_sides",
            PatchError::TooManySides { .. } => "too_many_sides",
            PatchError::EmptySide { .. } => "empty_side",
            PatchError::BadParameter { .. } => "bad_parameter",
            PatchError::ZeroLengthSide { .. } => "zero_length_side",
            PatchError::SegmentGap { .. } => "segment_gap",
            PatchError::CornerGap { .. } => "corner_gap",
            PatchError::RibbonCount { .. } => "ribbon_count",
            PatchError::RibbonSegments { .. } => "ribbon_segments",
            PatchError::BadRibbonNode { .. } => "bad_ribbon_node",
            PatchError::GregoryNeedsFourSides { .. } => "gregory_needs_four_sides",
            PatchError::Resolution(_) => "resolution",
            PatchError::MeshTooLarge(_) => "mesh_too_large",
            PatchError::Curve { .. } => "curve",
        }
    }
}

/// Something the patch construction repaired with a documented fallback rather than refused.
///
/// Warnings travel with the [`crate::Patch`] (see [`crate::Patch::warnings`]) so the add-on can
/// report them next to the face.
#[derive(Debug, Clone, PartialEq)]
pub enum PatchWarning {
    /// The angle between the two sides meeting at a corner is close to 0° or 180°; the ribbon
    /// at that corner was turned to `used_degrees` (the cross-boundary derivative then no longer
    /// equals the neighbouring side's tangent there, but the patch stays regular and finite).
    CornerAngle {
        /// Index of the corner (start of side `corner`).
        corner: usize,
        /// The corner angle measured in the tangent plane, degrees.
        degrees: f64,
        /// The angle the ribbon uses instead, degrees.
        used_degrees: f64,
    },
    /// The face's corner-based patch (Gregory or Charrot–Gregory) folded in its own mesh, and
    /// the side-blended patch ([`crate::PatchKind::SideBlend`]) of the same boundary and
    /// ribbons, which folds less, is used instead.
    SideBlended {
        /// The corner-based patch that folded.
        replaced: crate::PatchKind,
        /// Its pairs of neighbouring mesh polygons more than the fold angle apart (a polygon
        /// along a smooth edge paired with the tangent plane the face across it takes there).
        replaced_pairs: usize,
        /// Its largest angle between neighbouring mesh polygons, degrees.
        replaced_degrees: f64,
        /// The same figures of the side-blended patch.
        pairs: usize,
        /// Its largest angle between neighbouring mesh polygons, degrees.
        degrees: f64,
    },
    /// The face is flat and its corner-based patch folds within the plane, in strips too thin
    /// for the mesh to show; the side-blended patch, which does not, is used instead.
    FlatSideBlended {
        /// The corner-based patch that folded.
        replaced: crate::PatchKind,
        /// The cells of a fine grid over its domain that turned over.
        cells: usize,
    },
    /// A side has a corner inside it (no node there) whose two tangents leave the tangent
    /// plane the side's normal field gives there: the hull has a knuckle that no curve of the
    /// network follows, and the side's ribbon steps there (by more than the patch spreads along
    /// the side); the patch spreads the step inside the face instead, fading from the corner
    /// (`ribbon::Fan`).
    KnuckleInSide {
        /// Index of the side.
        side: usize,
        /// Where the corner is (model coordinates, m).
        at: [f64; 3],
        /// The ribbon's step (m).
        step: f64,
        /// The step as a share of the ribbon's length.
        share: f64,
    },
    /// Two sides of the face meet at a cusp (a corner angle near 0°: one repaired,
    /// [`PatchWarning::CornerAngle`], or one under `CUSP_DEGREES`), where they span no tangent
    /// plane a corner-based patch can interpolate; the side-blended patch, which has no corner
    /// interpolants, is used instead.
    CuspSideBlended {
        /// The corner-based patch replaced.
        replaced: crate::PatchKind,
        /// Index of the corner (start of side `corner`).
        corner: usize,
        /// The corner angle, degrees.
        degrees: f64,
    },
}

/// The name of the corner-based patch a side-blended one replaced, for its warning.
fn corner_patch_name(kind: crate::PatchKind) -> &'static str {
    match kind {
        crate::PatchKind::Gregory => "Gregory",
        _ => "Charrot–Gregory",
    }
}

impl std::fmt::Display for PatchWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PatchWarning::CornerAngle {
                corner,
                degrees,
                used_degrees,
            } => write!(
                f,
                "corner {corner}: angle {degrees:.2}° is degenerate; ribbon uses {used_degrees:.2}°"
            ),
            PatchWarning::SideBlended {
                replaced,
                replaced_pairs,
                replaced_degrees,
                pairs,
                degrees,
            } => {
                let name = corner_patch_name(*replaced);
                write!(
                    f,
                    "its {name} patch folds ({replaced_pairs} pair(s) of neighbouring mesh faces, \
                     its own or across its smooth edges, at up to {replaced_degrees:.1}°); the \
                     side-blended patch is used \
                     ({pairs} pair(s), up to {degrees:.1}°)"
                )
            }
            PatchWarning::FlatSideBlended { replaced, cells } => {
                let name = corner_patch_name(*replaced);
                write!(
                    f,
                    "the face is flat and its {name} patch folds within its plane ({cells} cell(s) \
                     of a fine grid turned over, too thin for the mesh); the side-blended patch, \
                     which does not, is used"
                )
            }
            PatchWarning::KnuckleInSide {
                side,
                at,
                step,
                share,
            } => write!(
                f,
                "side {side} has a corner at ({:.3}, {:.3}, {:.3}) where the hull has a knuckle \
                 no curve follows: the ribbon steps by {:.1} mm ({:.1} % of its length), and \
                 the patch spreads the step inside the face, fading from the corner; add a \
                 curve along the knuckle, or fair the corner out",
                at[0],
                at[1],
                at[2],
                step * 1e3,
                share * 100.0
            ),
            PatchWarning::CuspSideBlended {
                replaced,
                corner,
                degrees,
            } => {
                let name = corner_patch_name(*replaced);
                write!(
                    f,
                    "corner {corner}: its sides meet at {degrees:.2}°, a cusp where they span \
                     no tangent plane the {name} patch can take; the side-blended patch, which \
                     needs none, is used"
                )
            }
        }
    }
}
