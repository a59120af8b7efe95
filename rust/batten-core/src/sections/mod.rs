//! Exact plane sections of the hull's patch surface — stations (`x = c`), waterlines
//! (`z = c`), buttocks (`y = c`) and diagonals (planes through a line parallel to `x`) — for
//! the lines plan, the offsets table and the CAD checks (issue 16).
//!
//! The patches themselves are cut, not the display mesh: the section is found on the cells of
//! the hydrostatics (degree-7 interpolants of each patch, [`trace`]), every point is moved onto
//! the patch's own evaluation ∩ the plane by Newton steps, pieces are halved until each chord
//! is within the tolerance, and the pieces of all patches are joined into ordered polylines
//! ([`chain`]) with corners where the plane crosses a knuckle. [`SectionPolyline::fit`] gives
//! the NURBS curve of a polyline (the Dierckx fairing of [`crate::fair_points`], corners kept).
//! [`knuckle_lines`] joins the hull's knuckle edges into the chine lines drawn beside them.

mod chain;
mod knuckle_lines;
mod trace;

use glam::DVec3;

use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::fair::{fair_points, FairOptions, Smoothing};
use crate::hull::{HullSurface, KNUCKLE_POINT_ANGLE_DEGREES};
use crate::hydro::CellDensity;
use crate::patch::Patch;
use crate::tolerance::Tolerance;

pub use chain::SectionPolyline;
pub use knuckle_lines::{knuckle_lines, KnuckleLine};

use trace::{domain_cells, mend_cell_edges, section_pieces, Cut, DomainCell};

/// The chordal tolerance of a section's polylines and fitted curves by default (m): 1 mm, a
/// line's width on a 1:100 lines plan and well inside what a yard's offsets give.
pub const DEFAULT_CUT_TOLERANCE: f64 = 1e-3;

/// How far (relative to the hull's size) the cells are cut off the plane asked for, so that a
/// plane holding a patch edge (a station where a station was drawn) cuts the patches on one
/// side of it only, and the points are then polished onto the plane itself.
const CUT_NUDGE_RELATIVE: f64 = 1e-10;

/// A point is on the plane when `|m·P − c|` is below this fraction of the hull's size (1e-12
/// of a 230 m ship is 0.2 nm: well inside the 1e-9 m asked of a section's points).
const ON_PLANE_RELATIVE: f64 = 1e-12;

/// Ends of pieces closer than this fraction of the hull's size are one point of the polyline
/// (the pieces' ends are polished to the same curve point to about 1e-12 of the size; patches
/// meet within the model tolerance).
const JOIN_RELATIVE: f64 = 1e-6;

/// Ends further apart, up to this many chordal tolerances, are joined too (nearest pairs
/// first, after the exact ones), by a chord that is within the tolerance of any curve bending
/// less than one such gap across: where the plane weaves across a drawn curve that is not quite
/// plane, or the cell polynomials (about 1 mm from a real ship's patches near their composite
/// sides) and the patch disagree on where the curve leaves a cell, the pieces' ends are polished
/// to nearby but different points.
///
/// Implementation note: measured on KCS (39 stations, 12 waterlines, 6 buttocks), the widest
/// such gap is 1.8 cm (a buttock across the bilge).
const BRIDGE_TOLERANCES: f64 = 50.0;

/// The section plane `{p : normal·p = offset}`, `normal` a unit vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionPlane {
    normal: DVec3,
    offset: f64,
}

impl SectionPlane {
    /// The plane `normal·p = offset`, the normal made unit (the offset scaled with it).
    /// Errors ([`Error::InvalidInput`]): a normal that is zero or not finite, an offset that
    /// is not finite.
    pub fn try_new(normal: DVec3, offset: f64) -> Result<SectionPlane, Error> {
        let len = normal.length();
        if !(normal.is_finite() && len > 0.0 && len.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "section plane normal {:?} must be a finite non-zero vector",
                normal.to_array()
            )));
        }
        if !offset.is_finite() {
            return Err(Error::InvalidInput(format!(
                "section plane offset {offset} must be a finite number of metres"
            )));
        }
        Ok(SectionPlane {
            normal: normal / len,
            offset: offset / len,
        })
    }

    /// The station `x = x`.
    pub fn station(x: f64) -> Result<SectionPlane, Error> {
        SectionPlane::try_new(DVec3::X, x).map_err(|_| named("station", x))
    }

    /// The waterline `z = z`.
    pub fn waterline(z: f64) -> Result<SectionPlane, Error> {
        SectionPlane::try_new(DVec3::Z, z).map_err(|_| named("waterline", z))
    }

    /// The buttock `y = y`.
    pub fn buttock(y: f64) -> Result<SectionPlane, Error> {
        SectionPlane::try_new(DVec3::Y, y).map_err(|_| named("buttock", y))
    }

    /// The diagonal through the line parallel to `x` at `(y0, z0)` in the body plan, its trace
    /// there rising outboard at `angle_deg` above the horizontal (negative: falling outboard,
    /// as diagonals drawn from the centreline down to the bilge do).
    pub fn diagonal(y0: f64, z0: f64, angle_deg: f64) -> Result<SectionPlane, Error> {
        for (what, v) in [("y0", y0), ("z0", z0), ("angle_deg", angle_deg)] {
            if !v.is_finite() {
                return Err(Error::InvalidInput(format!(
                    "diagonal {what} {v} must be a finite number"
                )));
            }
        }
        let a = angle_deg.to_radians();
        let normal = DVec3::new(0.0, -a.sin(), a.cos());
        SectionPlane::try_new(normal, normal.dot(DVec3::new(0.0, y0, z0)))
    }

    /// The unit normal.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The offset along the normal.
    pub fn offset(&self) -> f64 {
        self.offset
    }
}

/// The error of a plane of one family whose offset is not a number.
fn named(family: &str, v: f64) -> Error {
    Error::InvalidInput(format!(
        "{family} offset {v} must be a finite number of metres"
    ))
}

/// A built hull's patches ready for plane sections: the patches, their cells and the hull's
/// knuckle lines. Made once per surface ([`SectionModel::new`]); every section reads it.
pub struct SectionModel {
    patches: Vec<Patch>,
    sign: f64,
    cells: Vec<DomainCell>,
    bounds: (DVec3, DVec3),
    knuckles: Vec<KnuckleLine>,
}

impl std::fmt::Debug for SectionModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SectionModel")
            .field("patches", &self.patches.len())
            .field("cells", &self.cells.len())
            .field("bounds", &self.bounds)
            .finish()
    }
}

impl SectionModel {
    /// The section model of a built hull (its cells at [`CellDensity::DEFAULT`], in parallel).
    pub fn new(hull: &HullSurface) -> SectionModel {
        let patches = hull.patches.clone();
        let cells = domain_cells(&patches, CellDensity::DEFAULT);
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for p in &hull.mesh.positions {
            lo = lo.min(DVec3::from(*p));
            hi = hi.max(DVec3::from(*p));
        }
        let size = if lo.is_finite() && hi.is_finite() {
            (hi - lo).length()
        } else {
            0.0
        };
        let knuckles = knuckle_lines(&hull.report.knuckle_edges, JOIN_RELATIVE * size);
        SectionModel {
            patches,
            sign: if hull.patches_outward { 1.0 } else { -1.0 },
            cells,
            bounds: (lo, hi),
            knuckles,
        }
    }

    /// The smallest box of the surface (of its display mesh's vertices, which lie on it).
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.bounds
    }

    /// The hull's knuckle (chine) lines.
    pub fn knuckle_lines(&self) -> &[KnuckleLine] {
        &self.knuckles
    }

    fn size(&self) -> f64 {
        let (lo, hi) = self.bounds;
        if lo.is_finite() && hi.is_finite() {
            (hi - lo).length()
        } else {
            0.0
        }
    }

    /// The section of the surface (the drawn surface only: a port half stays a half) by
    /// `plane`, as ordered polylines within `tolerance` (m) of the surface between their
    /// points, every point on the patches and the plane to about 1e-12 of the hull's size.
    /// Empty when the plane misses the hull. Errors ([`Error::InvalidInput`]): a tolerance
    /// that is not a positive finite number.
    pub fn section(
        &self,
        plane: &SectionPlane,
        tolerance: f64,
    ) -> Result<Vec<SectionPolyline>, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidInput(format!(
                "section tolerance {tolerance} must be a positive finite number of metres"
            )));
        }
        let size = self.size();
        let cut = Cut {
            m: plane.normal,
            c: plane.offset,
            c_cells: plane.offset + CUT_NUDGE_RELATIVE * size,
            tolerance,
            close: ON_PLANE_RELATIVE * size,
            sign: self.sign,
        };
        let mut pieces = section_pieces(&self.cells, &self.patches, &cut);
        let join = (JOIN_RELATIVE * size).max(BRIDGE_TOLERANCES * tolerance);
        mend_cell_edges(&mut pieces, &self.patches, &cut, join);
        Ok(chain::join_pieces(
            &pieces,
            &self.patches,
            plane.normal,
            join,
            KNUCKLE_POINT_ANGLE_DEGREES.to_radians(),
        ))
    }
}

impl SectionPolyline {
    /// The polyline as a NURBS curve within `tolerance` (m) of its points: the smoothing
    /// spline of [`fair_points`] (cubic, its corners kept as knots of full multiplicity, no
    /// other corners looked for), or, where that cannot meet the tolerance, the polyline
    /// itself as a degree-1 curve. A closed polyline's curve returns to its first point.
    /// Errors ([`Error::InvalidInput`]): fewer than two distinct points, a tolerance that is
    /// not a positive finite number.
    pub fn fit(&self, tolerance: f64) -> Result<NurbsCurve, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidInput(format!(
                "section tolerance {tolerance} must be a positive finite number of metres"
            )));
        }
        // Points closer than a tenth of the tolerance (or the model tolerance) are one.
        let within = Tolerance::try_new((0.1 * tolerance).min(Tolerance::DEFAULT.get()))
            .map_err(|e| Error::InvalidInput(e.to_string()))?;
        let mut points = self.points.clone();
        if self.closed && !points.is_empty() {
            points.push(points[0]);
        }
        let options = FairOptions {
            smoothing: Smoothing::MaxDeviation(tolerance),
            corners: self
                .corners
                .iter()
                .copied()
                .filter(|&c| c > 0 && c + 1 < points.len())
                .collect(),
            corner_angle: None,
            model_tolerance: within,
            ..FairOptions::default()
        };
        match fair_points(&points, &options) {
            Ok(faired) => Ok(faired.curve),
            Err(_) => polyline_curve(&points, within.get()),
        }
    }
}

/// The points (duplicates within `within` dropped) as a degree-1 NURBS curve on their chord
/// lengths.
fn polyline_curve(points: &[DVec3], within: f64) -> Result<NurbsCurve, Error> {
    let mut kept: Vec<DVec3> = Vec::with_capacity(points.len());
    for &p in points {
        if kept.last().is_none_or(|q| (p - *q).length() > within) {
            kept.push(p);
        }
    }
    if kept.len() < 2 {
        return Err(Error::InvalidInput(format!(
            "a section polyline of {} distinct points cannot be a curve",
            kept.len()
        )));
    }
    let mut knots = vec![0.0, 0.0];
    let mut t = 0.0;
    for w in kept.windows(2) {
        t += (w[1] - w[0]).length();
        knots.push(t);
    }
    knots.push(t);
    NurbsCurve::try_new(1, knots, kept, None).map_err(|e| Error::InvalidInput(e.to_string()))
}
