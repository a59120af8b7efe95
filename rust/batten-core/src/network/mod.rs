//! Curve networks: the designer's named curves with their roles, and their versioned JSON file
//! format.

mod approach;
mod format;
mod nodes;

use glam::DVec3;
use std::collections::HashSet;

use serde::{Deserialize, Serialize};

use crate::curve::CurveError;
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::tolerance::Tolerance;

pub use format::{NETWORK_FORMAT, NETWORK_VERSION};
pub use nodes::{Incidence, Junction, Junctions};

/// What a curve is to the hull. `Knuckle` makes the surface G0 (a chine) across the curve; the
/// boundary roles (keel, stem, transom, deck, midship, FOS, FOB) mark the form topology that
/// later features use. `Free` is an ordinary curve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// An ordinary curve: the surface is G1 across it.
    #[default]
    Free,
    /// A chine: the surface keeps a crease (G0) across it.
    Knuckle,
    /// The keel line.
    Keel,
    /// The stem profile.
    Stem,
    /// The transom outline.
    Transom,
    /// The deck edge (sheer line).
    Deck,
    /// The midship section.
    Midship,
    /// Flat of side boundary.
    Fos,
    /// Flat of bottom boundary.
    Fob,
}

impl Role {
    /// Every role, in the order the UI lists them.
    pub const ALL: [Role; 9] = [
        Role::Free,
        Role::Knuckle,
        Role::Keel,
        Role::Stem,
        Role::Transom,
        Role::Deck,
        Role::Midship,
        Role::Fos,
        Role::Fob,
    ];

    /// The lowercase name used in files and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Role::Free => "free",
            Role::Knuckle => "knuckle",
            Role::Keel => "keel",
            Role::Stem => "stem",
            Role::Transom => "transom",
            Role::Deck => "deck",
            Role::Midship => "midship",
            Role::Fos => "fos",
            Role::Fob => "fob",
        }
    }

    /// Whether a curve of this role is part of the hull's designed boundary (keel, stem,
    /// transom, deck): the edge of the surface, with faces on one side only.
    pub fn bounds_hull(self) -> bool {
        matches!(self, Role::Keel | Role::Stem | Role::Transom | Role::Deck)
    }

    /// The role of a lowercase name (case-insensitive), `None` if there is no such role.
    pub fn from_name(name: &str) -> Option<Role> {
        let lower = name.to_ascii_lowercase();
        Role::ALL.into_iter().find(|r| r.name() == lower)
    }
}

/// One designer curve: a name (unique in its network), a role and its geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct NetworkCurve {
    /// The curve's name: the Blender object name, and how every message refers to it.
    pub name: String,
    /// What the curve is to the hull.
    pub role: Role,
    /// The geometry.
    pub curve: NurbsCurve,
}

/// A plane the hull surface is tangent to wherever a curve of its network runs in it: the
/// flat of side (the greatest breadth) or the flat of bottom (the base plane). A smooth
/// surface on one side of a plane that touches it along a curve is tangent to it there, so
/// the faces along such a run take the plane as their tangent plane (the seed 002 §5 tangent
/// attribute of the flat of side and bottom curves, given here for the whole plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentPlane {
    /// Unit normal of the plane.
    pub normal: DVec3,
    /// The plane is `normal · p = offset`.
    pub offset: f64,
}

impl TangentPlane {
    /// The plane `normal · p = offset` with its normal made unit; [`Error::InvalidInput`]
    /// for a zero or non-finite normal or a non-finite offset.
    pub fn try_new(normal: DVec3, offset: f64) -> Result<TangentPlane, Error> {
        let length = normal.length();
        if !(normal.is_finite() && length > 0.0 && length.is_finite() && offset.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "a tangent plane needs a non-zero finite normal and a finite offset, not \
                 normal {normal} and offset {offset}"
            )));
        }
        Ok(TangentPlane {
            normal: normal / length,
            offset: offset / length,
        })
    }

    /// The plane as `[nx, ny, nz, offset]` (how files and Python give it).
    pub fn to_array(&self) -> [f64; 4] {
        [self.normal.x, self.normal.y, self.normal.z, self.offset]
    }

    /// Signed distance of `p` from the plane, along its normal.
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}

/// A hull's curve network: named curves with roles, in the order they were given, and the
/// planes the surface is tangent to where curves run in them.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    /// The network's name (the collection or file it came from).
    pub name: String,
    curves: Vec<NetworkCurve>,
    tangent_planes: Vec<TangentPlane>,
}

impl Network {
    /// Validated constructor: names must be non-empty and unique.
    pub fn try_new(name: impl Into<String>, curves: Vec<NetworkCurve>) -> Result<Network, Error> {
        let mut seen = HashSet::new();
        for (i, c) in curves.iter().enumerate() {
            if c.name.is_empty() {
                return Err(Error::EmptyName(i));
            }
            if !seen.insert(c.name.as_str()) {
                return Err(Error::DuplicateName(c.name.clone()));
            }
        }
        Ok(Network {
            name: name.into(),
            curves,
            tangent_planes: Vec::new(),
        })
    }

    /// The same network with `planes` as the planes its surface is tangent to where its
    /// curves run in them (see [`TangentPlane`]; none by default).
    pub fn with_tangent_planes(mut self, planes: Vec<TangentPlane>) -> Network {
        self.tangent_planes = planes;
        self
    }

    /// The curves, in order.
    pub fn curves(&self) -> &[NetworkCurve] {
        &self.curves
    }

    /// The planes the surface is tangent to where curves run in them.
    pub fn tangent_planes(&self) -> &[TangentPlane] {
        &self.tangent_planes
    }

    /// Check every curve is long enough to matter at this tolerance: a curve shorter than the
    /// tolerance is a zero-length curve, reported by name.
    pub fn check_lengths(&self, tolerance: Tolerance) -> Result<(), Error> {
        for c in &self.curves {
            check_length(&c.curve, tolerance).map_err(|e| e.named(&c.name))?;
        }
        Ok(())
    }
}

/// Error when the curve's length is below the model tolerance.
pub(crate) fn check_length(curve: &NurbsCurve, tolerance: Tolerance) -> Result<(), CurveError> {
    let tol = tolerance.get();
    let length = curve.arc_length(tolerance.length_check_accuracy())?;
    if length < tol {
        return Err(CurveError::ZeroLength {
            length,
            tolerance: tol,
        });
    }
    Ok(())
}
