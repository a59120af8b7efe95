//! Curve networks: the designer's named curves with their roles, and their versioned JSON file
//! format.

mod approach;
mod format;
mod nodes;

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

/// A hull's curve network: named curves with roles, in the order they were given.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    /// The network's name (the collection or file it came from).
    pub name: String,
    curves: Vec<NetworkCurve>,
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
        })
    }

    /// The curves, in order.
    pub fn curves(&self) -> &[NetworkCurve] {
        &self.curves
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
