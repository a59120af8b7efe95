//! What the water reaches of a surface's open edges: under water, a chain of free edges that
//! lies in one steep plane — an open transom — is closed by that plane, as section-based
//! hydrostatics close it at its station; any other open edge under water is a hole, and an
//! open edge in a flat plane (the deck's) means the water is over the top.
//!
//! A cap is the polygon of the chain's part under water, closed along the water surface and, at
//! a half hull's centreplane, down the centreplane; its integrals (wet-surface form of
//! [`WetIntegrals`], the cap's normal outward) are exact by the edge-midpoint rule on a fan of
//! triangles (degree-2 integrands on flat triangles). Caps add no wetted area: an open transom
//! is not hull plating.

use glam::DVec3;

use super::error::HydroError;
use super::geometry::{HullGeometry, OpenChain};
use super::integrals::WetIntegrals;
use super::waterplane::Waterplane;

/// How far from its plane (relative to the hull's size) a chain may stray and still be closed
/// by it: a transom drawn flat is flat to its curves' accuracy.
pub const CAP_FLATNESS_RELATIVE: f64 = 1e-4;

/// A cap whose normal is within 45° of the vertical is no transom: a deck (the water is over the
/// hull's top) or an open bottom (a hole).
const STEEP_CAP_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// How one end of a chain's run under water ends.
#[derive(Clone, Copy, Debug, PartialEq)]
enum End {
    /// Where the chain comes up through the water surface.
    Water,
    /// Where the chain itself ends (for a half hull, on the centreplane).
    Chain(DVec3),
}

/// The runs of a chain under water: its points (ends included) and how each end ends.
fn runs(chain: &OpenChain, plane: &Waterplane) -> Vec<(Vec<DVec3>, End, End)> {
    let n = chain.points.len();
    let z: Vec<f64> = chain.points.iter().map(|p| plane.zeta(*p)).collect();
    if chain.closed && z.iter().all(|&v| v < 0.0) {
        let p0 = chain.points[0];
        return vec![(chain.points.clone(), End::Chain(p0), End::Chain(p0))];
    }
    // An open sequence: a loop starts at a point out of the water and comes back to it.
    let order: Vec<usize> = if chain.closed {
        let start = z.iter().position(|&v| v >= 0.0).unwrap_or(0);
        (0..=n).map(|k| (start + k) % n).collect()
    } else {
        (0..n).collect()
    };
    let mut out = Vec::new();
    let mut current: Option<(Vec<DVec3>, End)> = None;
    for w in 0..order.len() {
        let (k, p) = (order[w], chain.points[order[w]]);
        if z[k] < 0.0 {
            let run = current.get_or_insert_with(|| (Vec::new(), End::Chain(p)));
            if w > 0 && z[order[w - 1]] >= 0.0 {
                // Entered the water between the previous point and this one.
                let (a, za) = (chain.points[order[w - 1]], z[order[w - 1]]);
                run.0.push(a + (p - a) * (za / (za - z[k])));
                run.1 = End::Water;
            }
            run.0.push(p);
        } else if let Some((mut pts, start)) = current.take() {
            let (a, za) = (chain.points[order[w - 1]], z[order[w - 1]]);
            pts.push(a + (p - a) * (za / (za - z[k])));
            out.push((pts, start, End::Water));
        }
    }
    if let Some((pts, start)) = current {
        let last = *pts.last().unwrap_or(&DVec3::ZERO);
        out.push((pts, start, End::Chain(last)));
    }
    out
}

/// The unit normal of the polygon `pts` (Newell), or of the plane through the polyline and the
/// transverse direction when the points are collinear.
fn polygon_normal(pts: &[DVec3]) -> Option<DVec3> {
    let n: DVec3 = (0..pts.len())
        .map(|i| pts[i].cross(pts[(i + 1) % pts.len()]))
        .sum();
    let span = (pts[pts.len() - 1] - pts[0]).length();
    if n.length() > 1e-9 * span * span {
        return Some(n.normalize());
    }
    let m = (pts[pts.len() - 1] - pts[0]).cross(DVec3::Y);
    (m.length() > 0.0).then(|| m.normalize())
}

/// Solve `[0 1 0; n; e3]·p = [0; d1; d2]`: the point of the cap plane on the water surface in the
/// centreplane.
fn centreplane_waterline_point(n: DVec3, d1: f64, e3: DVec3, d2: f64) -> Option<DVec3> {
    // With y = 0: n.x x + n.z z = d1, e3.x x + e3.z z = d2.
    let det = n.x * e3.z - n.z * e3.x;
    if det.abs() < 1e-12 {
        return None;
    }
    Some(DVec3::new(
        (d1 * e3.z - n.z * d2) / det,
        0.0,
        (n.x * d2 - d1 * e3.x) / det,
    ))
}

/// The plane of a run's points: its unit normal, their centroid, whether they lie in it (to
/// [`CAP_FLATNESS_RELATIVE`] of the hull's size) and whether it is steep (a transom's, which a
/// cap closes, rather than a deck's or a bottom's).
struct RunPlane {
    n: DVec3,
    c0: DVec3,
    flat: bool,
    steep: bool,
}

fn run_plane(pts: &[DVec3], plane: &Waterplane, size: f64) -> Option<RunPlane> {
    let n = polygon_normal(pts)?;
    let c0 = pts.iter().copied().sum::<DVec3>() / pts.len() as f64;
    Some(RunPlane {
        n,
        c0,
        flat: pts
            .iter()
            .all(|p| n.dot(*p - c0).abs() <= CAP_FLATNESS_RELATIVE * size),
        steep: n.dot(plane.e3).abs() <= STEEP_CAP_COSINE,
    })
}

/// The lowest point of `pts` in `plane`.
fn lowest(pts: &[DVec3], plane: &Waterplane) -> DVec3 {
    pts.iter()
        .copied()
        .min_by(|a, b| plane.zeta(*a).total_cmp(&plane.zeta(*b)))
        .unwrap_or(DVec3::ZERO)
}

/// The integrals of the caps of the chains of `geom` under `plane` (own half only), or the error
/// that an open edge under water means.
fn own_caps(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    draft: f64,
    size: f64,
    near: f64,
) -> Result<WetIntegrals, HydroError> {
    let (lo, hi) = geom.bounds();
    let centre = 0.5 * (lo + hi);
    let slack = 1e-9 * size;
    // The open top: the chain holding the highest free-edge point, when that point is at the
    // top of the hull (a deck edge left open); a run of it under water floods the hull.
    let chain_top = |c: &OpenChain| {
        c.points
            .iter()
            .map(|p| p.z)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let open_top = geom
        .open_chains()
        .iter()
        .enumerate()
        .max_by(|a, b| chain_top(a.1).total_cmp(&chain_top(b.1)))
        .filter(|(_, c)| chain_top(c) >= hi.z - slack)
        .map(|(k, _)| k);
    let mut out = WetIntegrals::default();
    for (k, chain) in geom.open_chains().iter().enumerate() {
        if chain.points.iter().all(|p| plane.zeta(*p) >= -slack) {
            continue;
        }
        for (mut pts, start, end) in runs(chain, plane) {
            if pts.len() < 2 {
                continue;
            }
            let run = run_plane(&pts, plane, size);
            if Some(k) == open_top
                && pts
                    .iter()
                    .any(|p| p.z >= chain_top(chain) - 0.5 * (hi.z - lo.z))
                && !run.as_ref().is_some_and(|r| r.flat && r.steep)
            {
                // The deck edge's own run (not a transom below it): the water is over the top.
                return Err(HydroError::above_top(draft, lowest(&pts, plane)));
            }
            // A chain end off the centreplane of a half hull is a hole's.
            for e in [start, end] {
                if let End::Chain(p) = e {
                    let closed_loop = chain.closed;
                    if !(closed_loop || geom.is_half() && p.y.abs() <= near) {
                        return Err(HydroError::hole(p, &chain.curves));
                    }
                }
            }
            let Some(RunPlane { n, c0, flat, steep }) = run else {
                continue;
            };
            if !flat {
                return Err(HydroError::hole(lowest(&pts, plane), &chain.curves));
            }
            if !steep {
                // A flat opening: the deck's when in the upper half of the hull, else a hole.
                return Err(if c0.z > centre.z {
                    HydroError::above_top(draft, lowest(&pts, plane))
                } else {
                    HydroError::hole(lowest(&pts, plane), &chain.curves)
                });
            }
            // Close along the water and down the centreplane.
            let q = centreplane_waterline_point(n, n.dot(c0), plane.e3, plane.e3.dot(plane.origin));
            match (start, end, q) {
                (End::Chain(_), End::Water, Some(q)) => pts.push(q),
                (End::Water, End::Chain(_), Some(q)) => pts.insert(0, q),
                _ => {}
            }
            let outward = if n.dot(c0 - centre) >= 0.0 { n } else { -n };
            let tri: Vec<f64> = (1..pts.len() - 1)
                .map(|i| 0.5 * (pts[i] - pts[0]).cross(pts[i + 1] - pts[0]).dot(outward))
                .collect();
            let sign = tri.iter().sum::<f64>().signum();
            for (i, s) in tri.iter().enumerate() {
                let (a, b, c) = (pts[0], pts[i + 1], pts[i + 2]);
                let w = plane.e3.dot(outward) * s * sign / 3.0;
                for m in [0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)] {
                    out.add_point(plane.earth(m), w, 0.0);
                }
            }
        }
    }
    Ok(out)
}

/// The integrals of the caps closing `geom`'s open edges under `plane` (both halves of a half
/// hull), or the error an open edge under water means: a hole ([`HydroError::HoleBelowWater`])
/// or the water over the top ([`HydroError::DraftAboveTop`]).
pub(crate) fn cap_integrals(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    draft: f64,
    size: f64,
    near: f64,
) -> Result<WetIntegrals, HydroError> {
    let own = own_caps(geom, plane, draft, size, near)?;
    Ok(if !geom.is_half() {
        own
    } else if plane.is_upright() {
        own.with_mirror_upright()
    } else {
        own + own_caps(geom, &plane.mirrored(), draft, size, near)?
    })
}
