//! The planes of the form (Bole, seed 002, §5 surface attributes and §7.2.1): the centreplane,
//! transverse planes (midship sections, transom, stations), waterplanes (a flat deck) and
//! inclined planes (a flat of bottom with rise of floor) that form-topology curves lie in, and
//! the rule that keeps a vertex on the planes it belongs to.

use glam::DVec3;

use crate::curve::NurbsCurve;

/// What a plane of the form is to the hull.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneKind {
    /// y = 0: the centreplane.
    Centreplane,
    /// x = constant: a transverse plane (midship section, transom, station).
    Transverse,
    /// y = constant ≠ 0: a longitudinal vertical plane (a flat of side).
    Longitudinal,
    /// z = constant: a waterplane (a flat deck, a flat of bottom without rise of floor).
    Waterplane,
    /// Any other plane (a flat of bottom with rise of floor, a raked transom).
    Inclined,
}

impl PlaneKind {
    /// The lowercase name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            PlaneKind::Centreplane => "centreplane",
            PlaneKind::Transverse => "transverse",
            PlaneKind::Longitudinal => "longitudinal",
            PlaneKind::Waterplane => "waterplane",
            PlaneKind::Inclined => "inclined",
        }
    }
}

/// A plane some form-topology curves lie in: `normal · p = offset`, with the curves (network
/// indices) that lie in it.
#[derive(Clone, Debug, PartialEq)]
pub struct FormPlane {
    /// What the plane is to the hull.
    pub kind: PlaneKind,
    /// Unit normal.
    pub normal: DVec3,
    /// `normal · p` for every point of the plane.
    pub offset: f64,
    /// The curves lying in it (indices into the network).
    pub curves: Vec<usize>,
}

/// The planes a curve lies in, found from its control points (a NURBS curve lies in the plane
/// of its control points): every axis plane they all lie in within `tol` (a straight keel lies
/// in the centreplane and the base plane), else their best plane when it holds them all.
pub(crate) fn curve_planes(curve: &NurbsCurve, tol: f64) -> Vec<(PlaneKind, DVec3, f64)> {
    let pts = curve.control_points();
    let mut out = Vec::new();
    for (axis, normal) in [(0, DVec3::X), (1, DVec3::Y), (2, DVec3::Z)] {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[axis]), hi.max(p[axis]))
            });
        if hi - lo <= tol {
            let offset = 0.5 * (lo + hi);
            let kind = match axis {
                0 => PlaneKind::Transverse,
                1 if offset.abs() <= tol => PlaneKind::Centreplane,
                1 => PlaneKind::Longitudinal,
                _ => PlaneKind::Waterplane,
            };
            let offset = if kind == PlaneKind::Centreplane {
                0.0
            } else {
                offset
            };
            out.push((kind, normal, offset));
        }
    }
    if out.is_empty() {
        if let Some(normal) = spanning_normal(&pts, tol) {
            let offset = pts.iter().map(|p| normal.dot(*p)).sum::<f64>() / pts.len() as f64;
            if pts.iter().all(|p| (normal.dot(*p) - offset).abs() <= tol) {
                out.push((PlaneKind::Inclined, normal, offset));
            }
        }
    }
    out
}

/// The unit normal of the plane through the first point, the point farthest from it and the
/// point farthest from their line; `None` when the points are collinear within `tol`.
fn spanning_normal(pts: &[DVec3], tol: f64) -> Option<DVec3> {
    let a = *pts.first()?;
    let b = *pts
        .iter()
        .max_by(|p, q| a.distance_squared(**p).total_cmp(&a.distance_squared(**q)))?;
    let axis = (b - a).try_normalize()?;
    let off_line = |p: DVec3| (p - a).reject_from_normalized(axis).length();
    let c = *pts
        .iter()
        .max_by(|p, q| off_line(**p).total_cmp(&off_line(**q)))?;
    if off_line(c) <= tol {
        return None;
    }
    (b - a).cross(c - a).try_normalize()
}

/// The point nearest to `q` on the intersection of `planes` (each `(normal, offset)`), found by
/// least squares with the planes as equality constraints (§7.2.1: one plane — move parallel to
/// it; two — along their line; three or more — fixed at their intersection). Planes whose
/// normal depends on the others (within `PARALLEL`) are dropped.
pub(crate) fn constrain(q: DVec3, planes: &[(DVec3, f64)]) -> DVec3 {
    let mut basis: Vec<(DVec3, f64)> = Vec::new();
    for &(n, d) in planes {
        let mut v = n;
        let mut dd = d;
        for &(b, bd) in &basis {
            let k = v.dot(b);
            v -= b * k;
            dd -= bd * k;
        }
        let len = v.length();
        if len > PARALLEL && basis.len() < 3 {
            basis.push((v / len, dd / len));
        }
    }
    // `basis` is orthonormal: project q onto each constraint in turn.
    basis.iter().fold(q, |p, &(n, d)| p - n * (n.dot(p) - d))
}

/// Below this the normals of two planes count as parallel (sine of their angle).
const PARALLEL: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_two_three_planes() {
        let q = DVec3::new(1.0, 2.0, 3.0);
        let px = (DVec3::X, 0.5);
        let py = (DVec3::Y, -1.0);
        let pz = (DVec3::Z, 4.0);
        assert_eq!(constrain(q, &[px]), DVec3::new(0.5, 2.0, 3.0), "one plane");
        assert_eq!(
            constrain(q, &[px, py]),
            DVec3::new(0.5, -1.0, 3.0),
            "two planes"
        );
        assert_eq!(
            constrain(q, &[px, py, pz, px]),
            DVec3::new(0.5, -1.0, 4.0),
            "three planes fix the point"
        );
    }
}
