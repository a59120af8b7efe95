//! One flat triangle against a plane: its wet part below the water (exact integrals), its
//! section by a plane (an oriented segment), and where its wet part reaches along a direction.

use glam::DVec3;

use crate::hydro::geometry::SectionSegment;
use crate::hydro::integrals::WetIntegrals;
use crate::hydro::waterplane::Waterplane;

/// The point where the edge from `a` to `b` crosses the level `0` of a linear function with
/// values `da` at `a` and `db` at `b` (of opposite sides: the denominator is never zero).
#[inline]
fn crossing(a: DVec3, b: DVec3, da: f64, db: f64) -> DVec3 {
    a + (b - a) * (da / (da - db))
}

/// The crossing of the earth-frame edge `a → b` with the water surface `ζ = 0`, its `ζ` set to
/// exactly `0`.
#[inline]
fn water_crossing(a: DVec3, b: DVec3) -> DVec3 {
    let mut p = crossing(a, b, a.z, b.z);
    p.z = 0.0;
    p
}

/// Add the exact integrals of the flat triangle `(a, b, c)` (earth coordinates, counter-clockwise
/// about the outward normal): every integrand of [`WetIntegrals`] is a polynomial of degree ≤ 2
/// on it, so the edge-midpoint rule (weights area/3, the classical triangle rule exact to degree
/// 2 of finite-element quadrature) is exact;
/// the weighted normal is the area vector `½ (b − a) × (c − a)` over 3.
#[inline]
fn add_flat(w: &mut WetIntegrals, a: DVec3, b: DVec3, c: DVec3) {
    let n = 0.5 * (b - a).cross(c - a);
    let (n_zeta, area) = (n.z / 3.0, n.length() / 3.0);
    w.add_point(0.5 * (a + b), n_zeta, area);
    w.add_point(0.5 * (b + c), n_zeta, area);
    w.add_point(0.5 * (c + a), n_zeta, area);
}

/// Add the part of the ship triangle `p` (outward winding) below the water surface `plane`:
/// the triangle clipped exactly by `ζ = 0` into one or two wet triangles, each integrated
/// exactly ([`add_flat`]). A corner on the water (`ζ = 0`) counts as wet.
#[inline]
pub(super) fn add_wet_triangle(w: &mut WetIntegrals, plane: &Waterplane, p: [DVec3; 3]) {
    // Earth coordinates at once (the dry runs are skipped before, so most triangles here are
    // wet and need them).
    let q = p.map(|v| plane.earth(v));
    let wet = q.map(|v| v.z <= 0.0);
    let n_wet = wet.iter().filter(|&&b| b).count();
    match n_wet {
        0 => {}
        3 => add_flat(w, q[0], q[1], q[2]),
        1 => {
            // The wet corner `a` and the two crossings on its edges: one triangle.
            let i = wet.iter().position(|&b| b).unwrap_or(0);
            let (a, b, c) = (q[i], q[(i + 1) % 3], q[(i + 2) % 3]);
            add_flat(w, a, water_crossing(a, b), water_crossing(a, c));
        }
        _ => {
            // The dry corner `a`: the wet quadrilateral (ab, b, c, ca) as two triangles.
            let i = wet.iter().position(|&b| !b).unwrap_or(0);
            let (a, b, c) = (q[i], q[(i + 1) % 3], q[(i + 2) % 3]);
            let (ab, ca) = (water_crossing(a, b), water_crossing(c, a));
            add_flat(w, ab, b, c);
            add_flat(w, ab, c, ca);
        }
    }
}

/// The section of the ship triangle `p` (outward winding) by the plane `m·x = c`: a segment
/// oriented along `m × n` (`n` the outward normal), or `None` when the plane misses it. A corner
/// on the plane counts as above it when `on_plane_above` (as if the plane were moved an
/// infinitesimal step back along `m`), below it otherwise; either way, the segments of a closed
/// mesh chain into closed loops.
///
/// Orientation: with the lone corner `i` below the plane, `m × n` runs from the crossing on
/// edge `k–i` to the crossing on edge `i–j` (`j`, `k` following `i` counter-clockwise about
/// `n`); with `i` alone above, the other way.
#[inline]
pub(super) fn section_segment(
    m: DVec3,
    c: f64,
    p: [DVec3; 3],
    on_plane_above: bool,
) -> Option<SectionSegment> {
    let d = p.map(|v| m.dot(v) - c);
    let above = d.map(|x| if on_plane_above { x >= 0.0 } else { x > 0.0 });
    let n_above = above.iter().filter(|&&b| b).count();
    let (i, lone_above) = match n_above {
        1 => (above.iter().position(|&b| b)?, true),
        2 => (above.iter().position(|&b| !b)?, false),
        _ => return None,
    };
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    let on_ij = crossing(p[i], p[j], d[i], d[j]);
    let on_ik = crossing(p[i], p[k], d[i], d[k]);
    Some(if lone_above {
        [on_ij, on_ik]
    } else {
        [on_ik, on_ij]
    })
}

/// The area vector of the ship triangle `p` projected on `m` when the triangle lies in the
/// plane `m·x = c` (its three corners exactly on it), else `0`: the sign says on which side of
/// a face in the plane the solid is.
#[inline]
pub(super) fn coplanar_flux(m: DVec3, c: f64, p: [DVec3; 3]) -> f64 {
    if p.iter().all(|v| m.dot(*v) == c) {
        0.5 * m.dot((p[1] - p[0]).cross(p[2] - p[0]))
    } else {
        0.0
    }
}

/// Widen `range` by `dir·x` over the wet part of the ship triangle `p` below `plane`: its wet
/// corners and the crossings of its edges with the water surface.
#[inline]
pub(super) fn widen_wet_range(
    range: &mut (f64, f64),
    plane: &Waterplane,
    dir: DVec3,
    p: [DVec3; 3],
) {
    let zeta = p.map(|v| plane.zeta(v));
    if zeta.iter().all(|&z| z > 0.0) {
        return;
    }
    let mut widen = |x: DVec3| {
        let v = dir.dot(x);
        range.0 = range.0.min(v);
        range.1 = range.1.max(v);
    };
    for i in 0..3 {
        let j = (i + 1) % 3;
        if zeta[i] <= 0.0 {
            widen(p[i]);
        }
        if (zeta[i] <= 0.0) != (zeta[j] <= 0.0) {
            widen(crossing(p[i], p[j], zeta[i], zeta[j]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_section_runs_along_m_cross_n() {
        // Counter-clockwise about +z; the plane y = 0.5 with m = +y: m × n = +x.
        let p = [
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ];
        let [a, b] = section_segment(DVec3::Y, 0.5, p, true).expect("the plane cuts it");
        assert!((b - a).x > 0.0, "along +x: {a} → {b}");
        // The plane y = 0.5 with m = −y: m × n = −x.
        let [a, b] = section_segment(-DVec3::Y, -0.5, p, true).expect("the plane cuts it");
        assert!((b - a).x < 0.0, "along −x: {a} → {b}");
        assert!(
            section_segment(DVec3::Y, 2.0, p, true).is_none(),
            "above it"
        );
    }

    #[test]
    fn a_half_wet_triangle_keeps_its_wet_half() {
        // A vertical triangle in x = 0 facing −x, from z = −1 to z = 1 about the water z = 0.
        let plane = Waterplane::level(0.0);
        let p = [
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.0, -1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let mut w = WetIntegrals::default();
        add_wet_triangle(&mut w, &plane, p);
        // The wet part: the triangle (0,0,−1), (0,∓½,0): area ½.
        assert!((w.wetted - 0.5).abs() < 1e-15, "wet area {}", w.wetted);
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        widen_wet_range(&mut r, &plane, DVec3::Y, p);
        assert!(
            (r.0 + 0.5).abs() < 1e-15 && (r.1 - 0.5).abs() < 1e-15,
            "{r:?}"
        );
    }
}
