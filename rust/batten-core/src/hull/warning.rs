//! What batten tells the designer about a build, as data: one shape for the topology's findings
//! and the hull's own warnings (H-rep paper §5.2: the system tells the designer what it resolved
//! and where, naming the curves).

use std::fmt;

use glam::DVec3;
use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};

use crate::diagnostic::Diagnostic;
use crate::patch::{PatchError, MAX_SIDES};

/// What a [`Warning`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WarningKind {
    /// A finding of the topology about the network; the tag is the [`Diagnostic::kind`]
    /// (`"dangling_end"`, `"near_miss"`, `"unclosed_region"`, …).
    Network(&'static str),
    /// An edge got no tangent ribbon from its crossing curves (H-rep §3.2.2); its faces use
    /// their default ribbons there.
    NoRibbon,
    /// A face of the topology could not be patched; [`Warning::error`] says why.
    FaceNotPatched,
    /// A patch turned the ribbon at a degenerate corner (sides meeting at nearly 0° or 180°).
    DegenerateCorner,
    /// A face's corner-based patch folded and its side-blended patch is used instead.
    SideBlended,
    /// A curve bounding a face has a corner inside the face's side where the hull has a
    /// knuckle no curve follows, whose ribbon step the patch spreads inside the face
    /// ([`crate::PatchWarning::KnuckleInSide`]).
    KnuckleInFace,
    /// A patch produced non-finite points and was left out of the mesh.
    NonFiniteSurface,
    /// Free edges off the hull's boundary (not profile, deck or transom): the surface has a
    /// hole or an unintended open rim there.
    Hole,
    /// The surface folds: neighbouring mesh faces at a steep angle off the knuckles, or a
    /// patch standing out of its boundary's box.
    Fold,
}

impl WarningKind {
    /// The stable tag of the kind, for the binding and for filtering (`"face_not_patched"`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            WarningKind::Network(tag) => tag,
            WarningKind::NoRibbon => "no_ribbon",
            WarningKind::FaceNotPatched => "face_not_patched",
            WarningKind::DegenerateCorner => "degenerate_corner",
            WarningKind::SideBlended => "side_blended",
            WarningKind::KnuckleInFace => "knuckle_in_face",
            WarningKind::NonFiniteSurface => "non_finite_surface",
            WarningKind::Hole => "hole",
            WarningKind::Fold => "fold",
        }
    }
}

/// One thing the designer should know about a build: what kind of problem, a sentence naming
/// the curves, the names of those curves, where it is (model coordinates, metres; `None` where
/// it has no place) and, for a face or ribbon that failed, the underlying error.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// A sentence for the designer, naming the curves.
    pub message: String,
    /// The designer curves involved, by name.
    pub curves: Vec<String>,
    /// Where it is, if it has a place.
    pub location: Option<DVec3>,
    /// Why the face (or the edge's ribbon) could not be built, for [`WarningKind::FaceNotPatched`]
    /// and [`WarningKind::NoRibbon`].
    pub error: Option<FaceError>,
}

impl From<&Diagnostic> for Warning {
    /// The topology's finding as a warning (same message, curves and place).
    fn from(d: &Diagnostic) -> Warning {
        Warning {
            kind: WarningKind::Network(d.kind()),
            message: d.to_string(),
            curves: d.curves().into_iter().map(str::to_owned).collect(),
            location: d.location(),
            error: None,
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl Serialize for Warning {
    /// A JSON object `{kind, message, curves, location, error}` with the kind as its tag and the
    /// error as `{kind, message}` (or null).
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Warning", 5)?;
        st.serialize_field("kind", self.kind.as_str())?;
        st.serialize_field("message", &self.message)?;
        st.serialize_field("curves", &self.curves)?;
        st.serialize_field("location", &self.location.map(|p| p.to_array()))?;
        let error = self.error.as_ref().map(|e| ErrorTag {
            kind: e.kind(),
            message: e.to_string(),
        });
        st.serialize_field("error", &error)?;
        st.end()
    }
}

/// Why one face of the topology could not become a patch (H-rep §3.2.1), or why an edge got no
/// ribbon (§3.2.2): the face's sides do not fit the patch methods, or the patch module refused
/// the boundary or the ribbon.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FaceError {
    /// The face has fewer than 3 or more than [`MAX_SIDES`] sides.
    #[error("it has {sides} sides; a patch needs 3 to {MAX_SIDES} (H-rep §3.2.1)")]
    SideCount {
        /// Its number of sides.
        sides: usize,
    },
    /// The face's first side has no edges (a defect of the topology, reported, not panicked).
    #[error("its first side has no edges")]
    EmptyFirstSide,
    /// The face's sides do not run along its loop of edges.
    #[error("its sides do not follow its loop")]
    SidesOffLoop,
    /// The face's sides leave edges of its loop out.
    #[error("its sides do not cover its loop")]
    SidesShortOfLoop,
    /// An edge of the face bounds no region of the network.
    #[error("an edge of it bounds no region")]
    EdgeOutsideRegion,
    /// The patch module refused the face's boundary or ribbons.
    #[error(transparent)]
    Patch(#[from] PatchError),
}

impl FaceError {
    /// A short stable tag for the kind of failure (`"side_count"`, or the patch error's tag).
    pub fn kind(&self) -> &'static str {
        match self {
            FaceError::SideCount { .. } => "side_count",
            FaceError::EmptyFirstSide => "empty_first_side",
            FaceError::SidesOffLoop => "sides_off_loop",
            FaceError::SidesShortOfLoop => "sides_short_of_loop",
            FaceError::EdgeOutsideRegion => "edge_outside_region",
            FaceError::Patch(e) => e.kind(),
        }
    }
}

/// The serialised form of a warning's error.
#[derive(Serialize)]
struct ErrorTag {
    kind: &'static str,
    message: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagnostic_becomes_warning_with_curves_and_place() {
        let d = Diagnostic::NearMiss {
            curves: ["a".into(), "b[2]".into()],
            location: DVec3::new(1.0, 2.0, 3.0),
            gap: 1e-3,
        };
        let w = Warning::from(&d);
        assert_eq!(w.kind.as_str(), "near_miss", "kind tag kept");
        assert_eq!(w.curves, vec!["a", "b[2]"], "names kept as they are");
        assert_eq!(w.location, Some(DVec3::new(1.0, 2.0, 3.0)), "place kept");
        assert_eq!(w.message, d.to_string(), "message is the diagnostic's");
        let json = serde_json::to_value(&w).unwrap();
        assert_eq!(json["kind"], "near_miss", "serialised kind");
        assert_eq!(json["location"][2], 3.0, "serialised location");
        assert!(json["error"].is_null(), "no error for a finding");
    }
}
