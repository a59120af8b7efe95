//! The parameters measured from the form topology (Bole, seed 002, §7.2.5): main dimensions,
//! waterline breadth at the design draft, the parallel middle body, the bilge radius and rise
//! of floor of the midship section, entrance and run.
//!
//! Choices the paper leaves open, as a naval architect would expect: length is the overall
//! x extent of the curves, breadth twice their largest y (the network is the port half),
//! depth their z extent; the PMB runs between the aft- and foremost midship sections (at least
//! two, joined by flat of side or flat of bottom curves) and its position is its centre; the
//! entrance runs from the PMB's forward end to the bow, the run from the stern to its aft end;
//! rise of floor is the height of the flat of bottom line above the keel at half breadth.

use glam::DVec3;

use super::error::FormError;
use super::identify::{FormOptions, FormTopology};
use super::parameters::{Bilge, FormParameters, ParallelMiddleBody};
use crate::curve::{Aabb, NurbsCurve};
use crate::network::{Network, Role};

/// Samples per Bézier span when a curve is searched for extremes or plane crossings.
const SAMPLES_PER_SPAN: usize = 64;
/// Bisection / golden-section steps: enough to reach f64 resolution on any span.
const REFINE_STEPS: usize = 80;

/// Measure the parameters of `form` on `network` (§7.2.5).
pub(crate) fn measure(
    network: &Network,
    form: &FormTopology,
    options: &FormOptions,
) -> Result<FormParameters, FormError> {
    let tol = options.tolerance.get();
    let curves = network.curves();
    let acc = options.tolerance.search_accuracy();
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for c in curves {
        let b = c.curve.bounding_box(acc).map_err(|e| e.named(&c.name))?;
        lo = lo.min(b.min);
        hi = hi.max(b.max);
    }
    let mut p = FormParameters {
        length: hi.x - lo.x,
        breadth: 2.0 * max_along(curves.iter().map(|c| &c.curve), DVec3::Y),
        depth: hi.z - lo.z,
        draft: options.draft,
        x_range: [lo.x, hi.x],
        ..FormParameters::default()
    };
    if let Some(t) = options.draft {
        p.waterline_breadth = Some(2.0 * waterline_half_breadth(network, t, tol));
    }
    let sections = midship_sections(network, form, tol);
    match pmb_of(network, form, &sections) {
        Ok(pmb) => {
            p.entrance_length = Some(hi.x - pmb.fwd);
            p.run_length = Some(pmb.aft - lo.x);
            p.pmb = Some(pmb);
        }
        Err(reason) => p.no_pmb_reason = Some(reason),
    }
    p.bilges = sections
        .iter()
        .filter_map(|&s| bilge_of(network, form, s, tol))
        .collect();
    Ok(p)
}

/// The midship-role curves lying in transverse planes, aft first.
fn midship_sections(network: &Network, form: &FormTopology, tol: f64) -> Vec<usize> {
    let curves = network.curves();
    let mut out: Vec<(f64, usize)> = (0..curves.len())
        .filter(|&i| curves[i].role == Role::Midship && form.is_form_curve[i])
        .filter_map(|i| {
            let pts = curves[i].curve.control_points();
            let x0 = pts[0].x;
            pts.iter()
                .all(|q| (q.x - x0).abs() <= tol)
                .then_some((x0, i))
        })
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.into_iter().map(|(_, i)| i).collect()
}

/// The PMB between the aft- and foremost midship sections, or why there is none.
fn pmb_of(
    network: &Network,
    form: &FormTopology,
    sections: &[usize],
) -> Result<ParallelMiddleBody, String> {
    let curves = network.curves();
    let (Some(&aft), Some(&fwd)) = (sections.first(), sections.last()) else {
        return Err(
            "no midship section (a curve with the role 'midship' in a transverse plane)".into(),
        );
    };
    if aft == fwd {
        return Err(format!(
            "one midship section ('{}'); a parallel middle body needs one at each end",
            curves[aft].name
        ));
    }
    let flat = |c: usize| matches!(curves[c].role, Role::Fos | Role::Fob);
    let joined = form.edges.iter().any(|e| {
        flat(e.curve) && {
            let (a, b) = (&form.vertices[e.start].curves, &form.vertices[e.end].curves);
            (a.contains(&aft) && b.contains(&fwd)) || (a.contains(&fwd) && b.contains(&aft))
        }
    });
    if !joined {
        return Err(format!(
            "no flat of side or flat of bottom curve joins the midship sections '{}' and '{}'",
            curves[aft].name, curves[fwd].name
        ));
    }
    let x = |c: usize| curves[c].curve.control_points()[0].x;
    let (xa, xf) = (x(aft), x(fwd));
    Ok(ParallelMiddleBody {
        aft: xa,
        fwd: xf,
        length: xf - xa,
        position: 0.5 * (xa + xf),
        aft_section: aft,
        fwd_section: fwd,
    })
}

/// The form vertex on curve `section` that also lies on a curve of `role`, with its parameter
/// on the section.
fn vertex_with(
    network: &Network,
    form: &FormTopology,
    section: usize,
    role: Role,
) -> Option<(usize, f64)> {
    let curves = network.curves();
    form.edges
        .iter()
        .filter(|e| e.curve == section)
        .flat_map(|e| [(e.start, e.t0), (e.end, e.t1)])
        .find(|&(v, _)| {
            form.vertices[v]
                .curves
                .iter()
                .any(|&c| curves[c].role == role)
        })
}

/// The bilge of midship section `s`: the stretch between its flat-of-bottom and flat-of-side
/// vertices, its circle (through its ends and middle, accepted when every sample is within
/// `tol` of it) and the bottom and side lines either side of it.
fn bilge_of(network: &Network, form: &FormTopology, s: usize, tol: f64) -> Option<Bilge> {
    let curve = &network.curves()[s].curve;
    let (fob_vertex, tb) = vertex_with(network, form, s, Role::Fob)?;
    let (fos_vertex, ts) = vertex_with(network, form, s, Role::Fos)?;
    let (a, b) = curve.domain();
    let (pb, ps) = (curve.point(tb), curve.point(ts));
    // The keel end is the section end nearer the flat of bottom vertex in parameter.
    let (keel_t, deck_t) = if (tb - a).abs() < (tb - b).abs() {
        (a, b)
    } else {
        (b, a)
    };
    let keel = curve.point(keel_t);
    let deck = curve.point(deck_t);
    let bottom = (keel - pb).try_normalize()?;
    let side = (deck - ps).try_normalize()?;
    let corner = line_meeting(pb, bottom, ps, side)?;
    let half_breadth = max_along(std::iter::once(curve), DVec3::Y);
    let slope = (pb.z - keel.z) / (pb.y - keel.y);
    let radius = arc_radius(curve, tb, ts, tol);
    Some(Bilge {
        section: s,
        fob_vertex,
        fos_vertex,
        radius,
        rise_of_floor: slope * (half_breadth - keel.y),
        corner,
        bottom_direction: bottom,
        side_direction: side,
    })
}

/// The point where line `p + s·u` meets line `q + t·v` (the middle of their closest points),
/// `None` for parallel lines.
pub(crate) fn line_meeting(p: DVec3, u: DVec3, q: DVec3, v: DVec3) -> Option<DVec3> {
    let w = p - q;
    let (a, b, c) = (u.dot(u), u.dot(v), v.dot(v));
    let (d, e) = (u.dot(w), v.dot(w));
    let den = a * c - b * b;
    if den.abs() <= PARALLEL_DENOMINATOR * a * c {
        return None;
    }
    let s = (b * e - c * d) / den;
    let t = (a * e - b * d) / den;
    Some(0.5 * ((p + u * s) + (q + v * t)))
}

/// Lines whose direction Gram determinant is below this fraction are parallel.
const PARALLEL_DENOMINATOR: f64 = 1e-12;

/// The radius of the circle through the stretch's ends and middle, when every sample of the
/// stretch lies within `tol` of that circle.
fn arc_radius(curve: &NurbsCurve, t0: f64, t1: f64, tol: f64) -> Option<f64> {
    let (lo, hi) = (t0.min(t1), t0.max(t1));
    let (a, m, b) = (
        curve.point(lo),
        curve.point(0.5 * (lo + hi)),
        curve.point(hi),
    );
    let (ab, am) = (b - a, m - a);
    let n = ab.cross(am);
    let n2 = n.length_squared();
    if n2 <= 0.0 {
        return None;
    }
    let centre =
        a + (n.cross(ab) * am.length_squared() + am.cross(n) * ab.length_squared()) / (2.0 * n2);
    let r = centre.distance(a);
    (0..=SAMPLES_PER_SPAN)
        .map(|j| lo + (hi - lo) * j as f64 / SAMPLES_PER_SPAN as f64)
        .all(|t| (curve.point(t).distance(centre) - r).abs() <= tol)
        .then_some(r)
}

/// The largest `dir · C(t)` over the curves (sampled per span, refined by golden section).
/// A span whose control points (their box: the span lies in their convex hull) cannot reach
/// beyond the largest value found so far is not sampled: it cannot change the result.
fn max_along<'a>(curves: impl Iterator<Item = &'a NurbsCurve>, dir: DVec3) -> f64 {
    let mut best = f64::NEG_INFINITY;
    for c in curves {
        let f = |t: f64| dir.dot(c.point(t));
        // The spans by the most their control points allow, largest first.
        let mut pieces: Vec<(f64, f64, f64)> = c
            .bezier_decomposition()
            .pieces
            .iter()
            .map(|piece| (upper_bound(&piece.hull_box(), dir), piece.t0, piece.t1))
            .collect();
        pieces.sort_by(|a, b| b.0.total_cmp(&a.0));
        for (bound, t0, t1) in pieces {
            if bound <= best {
                break;
            }
            let n = SAMPLES_PER_SPAN;
            let ts: Vec<f64> = (0..=n)
                .map(|j| t0 + (t1 - t0) * j as f64 / n as f64)
                .collect();
            let (j, v) = ts
                .iter()
                .map(|&t| f(t))
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((0, f64::NEG_INFINITY));
            let (a, b) = (ts[j.saturating_sub(1)], ts[(j + 1).min(n)]);
            best = best.max(v).max(golden_max(&f, a, b));
        }
    }
    best
}

/// The largest `dir · p` over the box `b` (at one of its corners).
fn upper_bound(b: &Aabb, dir: DVec3) -> f64 {
    dir.x * if dir.x >= 0.0 { b.max.x } else { b.min.x }
        + dir.y * if dir.y >= 0.0 { b.max.y } else { b.min.y }
        + dir.z * if dir.z >= 0.0 { b.max.z } else { b.min.z }
}

/// Golden-section search for the maximum of `f` on `[a, b]`.
fn golden_max(f: &impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..REFINE_STEPS {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    fc.max(fd)
}

/// The largest y where the curves meet the waterplane `z = draft`: crossings found by sign
/// changes and bisection, and the whole of curves lying in the plane. A span whose control
/// points lie all above or all below the plane, or cannot reach beyond the largest y found so
/// far, is not searched: it cannot change the result.
fn waterline_half_breadth(network: &Network, draft: f64, tol: f64) -> f64 {
    let mut best: f64 = 0.0;
    for nc in network.curves() {
        let c = &nc.curve;
        let pts = c.control_points();
        if pts.iter().all(|p| (p.z - draft).abs() <= tol) {
            best = best.max(max_along(std::iter::once(c), DVec3::Y));
            continue;
        }
        let g = |t: f64| c.point(t).z - draft;
        for piece in &c.bezier_decomposition().pieces {
            let hull = piece.hull_box();
            if draft < hull.min.z || draft > hull.max.z || hull.max.y <= best {
                continue;
            }
            let (t0, t1) = (piece.t0, piece.t1);
            let n = SAMPLES_PER_SPAN;
            for j in 0..n {
                let (mut a, mut b) = (
                    t0 + (t1 - t0) * j as f64 / n as f64,
                    t0 + (t1 - t0) * (j + 1) as f64 / n as f64,
                );
                let (ga, gb) = (g(a), g(b));
                if ga == 0.0 {
                    best = best.max(c.point(a).y);
                }
                if ga * gb >= 0.0 {
                    continue;
                }
                for _ in 0..REFINE_STEPS {
                    let m = 0.5 * (a + b);
                    if g(m) * g(a) <= 0.0 {
                        b = m;
                    } else {
                        a = m;
                    }
                }
                best = best.max(c.point(0.5 * (a + b)).y);
            }
            if g(t1) == 0.0 {
                best = best.max(c.point(t1).y);
            }
        }
    }
    best
}
