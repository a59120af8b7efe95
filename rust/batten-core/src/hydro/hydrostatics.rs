//! The naval architect's figures from the wet-surface integrals and plane sections of any
//! [`HullGeometry`]: volume, displacement, centres, waterplane, coefficients, metacentres, TPC,
//! MTC, sectional areas (ITTC symbols and definitions; SI units, tonnes for masses).

use glam::DVec3;
use serde::Serialize;

use super::error::HydroError;
use super::geometry::{HullGeometry, SectionSegment};
use super::integrals::WetIntegrals;
use super::waterplane::{Datums, Flotation, Waterplane};

/// How closely plane sections follow the surface, relative to the hull's size (the diagonal of
/// its box): section areas are then good to about 1e-8 relative.
pub const SECTION_TOLERANCE_RELATIVE: f64 = 1e-7;

/// How far below the water (relative to the hull's size) a free edge may reach before it counts
/// as under water: its points are exact, so this only absorbs rounding.
const OPEN_EDGE_SLACK_RELATIVE: f64 = 1e-9;

/// How far below the water (relative to the hull's size) the highest wet point must be for a
/// closed hull to count as sunk: a waterline's points are exact, so this only absorbs rounding.
const SUNK_SLACK_RELATIVE: f64 = 1e-9;

/// The foremost part of the waterline, as a fraction of `Lwl`, whose least-squares parabola
/// gives the half angle of entrance at its fore end (leaves out a stem rounding much smaller
/// than that, as the lines of a design are read).
pub const ENTRANCE_FIT_FRACTION: f64 = 0.025;

/// Stations sampled along the submerged length to find the largest section before refining
/// its place by golden-section search.
const MAX_SECTION_SAMPLES: usize = 41;

/// The hydrostatics of a hull at one flotation (all lengths m, areas m², volumes m³, masses t,
/// moments t·m; `x` forward, `z` up from the baseline, in the ship's axes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Hydrostatics {
    /// Displaced volume ∇, m³ (both sides).
    pub volume: f64,
    /// Displacement Δ = ρ∇, t.
    pub displacement: f64,
    /// Water density ρ, t/m³.
    pub density: f64,
    /// Draft at the aft perpendicular, m.
    pub draft_ap: f64,
    /// Draft at the forward perpendicular, m.
    pub draft_fp: f64,
    /// Draft at midships (halfway between the perpendiculars), m.
    pub draft_mid: f64,
    /// Draft at the longitudinal centre of flotation, m.
    pub draft_lcf: f64,
    /// `T_AP − T_FP`, m (by the stern positive).
    pub trim: f64,
    /// Heel, degrees (to starboard positive).
    pub heel: f64,
    /// `x` of the aft perpendicular, m.
    pub x_ap: f64,
    /// `x` of the forward perpendicular, m.
    pub x_fp: f64,
    /// Length between perpendiculars, m: the length basis of Cb, Cp, Cwp and MTC.
    pub lpp: f64,
    /// Length of the waterline, m.
    pub lwl: f64,
    /// Greatest breadth of the waterline, m.
    pub bwl: f64,
    /// Length of the submerged hull (its extent along the water surface), m.
    pub los: f64,
    /// Wetted surface S, m² (the hull below the water, both sides; an immersed transom included).
    pub wetted_area: f64,
    /// Waterplane area Awp, m².
    pub waterplane_area: f64,
    /// Area of the immersed midship section Am (at `x_mid`), m².
    pub midship_area: f64,
    /// Area of the largest immersed section Ax, m².
    pub max_section_area: f64,
    /// `x` of the largest section, m.
    pub max_section_x: f64,
    /// Block coefficient ∇ / (Lpp·Bwl·T_mid).
    pub cb: f64,
    /// Prismatic coefficient ∇ / (Am·Lpp) = Cb / Cm.
    pub cp: f64,
    /// Midship section coefficient Am / (Bwl·T_mid).
    pub cm: f64,
    /// Waterplane coefficient Awp / (Lpp·Bwl).
    pub cwp: f64,
    /// Vertical prismatic coefficient ∇ / (Awp·T_mid).
    pub cvp: f64,
    /// Longitudinal centre of buoyancy, `x` in the ship's axes, m.
    pub lcb: f64,
    /// Transverse centre of buoyancy, `y`, m.
    pub tcb: f64,
    /// Vertical centre of buoyancy above the baseline (KB), m.
    pub vcb: f64,
    /// Longitudinal centre of flotation, `x`, m.
    pub lcf: f64,
    /// Transverse second moment of the waterplane about its centroid, m⁴.
    pub it: f64,
    /// Longitudinal second moment of the waterplane about its centroid, m⁴.
    pub il: f64,
    /// Transverse metacentric radius It/∇, m.
    pub bmt: f64,
    /// Longitudinal metacentric radius Il/∇, m.
    pub bml: f64,
    /// KMt = KB + BMt, m.
    pub kmt: f64,
    /// KMl = KB + BMl, m.
    pub kml: f64,
    /// Tonnes per centimetre immersion ρ·Awp/100, t/cm.
    pub tpc: f64,
    /// Moment to change trim one centimetre Δ·BMl/(100·Lpp), t·m/cm (GMl taken as BMl, length
    /// basis Lpp).
    pub mtc: f64,
    /// Area of the immersed transom (the section at the aft end of the submerged hull), m².
    pub transom_area: f64,
    /// Half angle of entrance of the waterline at its fore end, degrees (from the parabola of
    /// the foremost [`ENTRANCE_FIT_FRACTION`] of the waterline).
    pub entrance_half_angle: f64,
}

/// The scale of a hull: the diagonal of its box.
fn size(geom: &dyn HullGeometry) -> f64 {
    let (lo, hi) = geom.bounds();
    (hi - lo).length().max(f64::MIN_POSITIVE)
}

/// The perpendiculars a hull implies at `draft`: FP at the fore end of the level waterline there
/// (where it meets the stem); AP `lpp` aft of it, or at the waterline's aft end when `lpp` is not
/// given (so Lpp = Lwl).
pub fn default_datums(
    geom: &dyn HullGeometry,
    draft: f64,
    lpp: Option<f64>,
) -> Result<Datums, HydroError> {
    if !draft.is_finite() {
        return Err(HydroError::InvalidInput(format!(
            "draft {draft} must be a finite number"
        )));
    }
    if let Some(l) = lpp {
        if !(l.is_finite() && l > 0.0) {
            return Err(HydroError::InvalidInput(format!(
                "Lpp {l} must be a positive number of metres"
            )));
        }
    }
    let plane = Waterplane::level(draft);
    let tol = SECTION_TOLERANCE_RELATIVE * size(geom);
    let wl = geom.plane_section(DVec3::Z, draft, tol);
    let (lo, hi) = range(&wl, DVec3::X).ok_or_else(|| below_keel(geom, &plane, draft))?;
    let x_fp = hi;
    let x_ap = lpp.map_or(lo, |l| hi - l);
    let d = Datums { x_ap, x_fp };
    d.check()?;
    Ok(d)
}

fn below_keel(geom: &dyn HullGeometry, _plane: &Waterplane, draft: f64) -> HydroError {
    let (lo, hi) = geom.bounds();
    if draft <= lo.z {
        HydroError::DraftBelowKeel { draft, keel: lo.z }
    } else {
        HydroError::DraftAboveTop {
            draft,
            x: 0.5 * (lo.x + hi.x),
            y: 0.0,
            z: hi.z,
        }
    }
}

/// The range of `dir·p` over the ends of `segments`.
fn range(segments: &[SectionSegment], dir: DVec3) -> Option<(f64, f64)> {
    let mut out: Option<(f64, f64)> = None;
    for p in segments.iter().flatten() {
        let v = dir.dot(*p);
        out = Some(out.map_or((v, v), |(a, b)| (a.min(v), b.max(v))));
    }
    out
}

/// The immersed area of the section of `geom` by the plane `m·p = c` (`m` unit), below the
/// water surface `plane`: Green's theorem on the closed section, `A = −∮ ζ da / (e3·b)` with `b`
/// the upward direction in the section plane and `a = b × m` (zero along the waterline, so only
/// the hull's own segments count, each clipped at `ζ = 0`).
pub fn immersed_section_area(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    m: DVec3,
    c: f64,
    tolerance: f64,
) -> f64 {
    let up = plane.e3 - m * plane.e3.dot(m);
    let up_len = up.length();
    if up_len < 1e-12 {
        return 0.0;
    }
    let b = up / up_len;
    let a = b.cross(m);
    let mut sum = 0.0;
    for [p, q] in geom.plane_section(m, c, tolerance) {
        let (zp, zq) = (plane.zeta(p), plane.zeta(q));
        let (ap, aq) = (a.dot(p), a.dot(q));
        let (z0, a0, z1, a1) = if zp <= 0.0 && zq <= 0.0 {
            (zp, ap, zq, aq)
        } else if zp > 0.0 && zq > 0.0 {
            continue;
        } else {
            // Clip at ζ = 0 (ζ is linear along the chord).
            let t = zp / (zp - zq);
            let am = ap + (aq - ap) * t;
            if zp <= 0.0 {
                (zp, ap, 0.0, am)
            } else {
                (0.0, am, zq, aq)
            }
        };
        sum += 0.5 * (z0 + z1) * (a1 - a0);
    }
    -sum / up_len
}

/// The sectional area curve: immersed areas of the stations `x = xs[k]` (planes normal to the
/// ship's `x` axis) at `flotation`.
pub fn sectional_areas(
    geom: &dyn HullGeometry,
    flotation: &Flotation,
    datums: &Datums,
    xs: &[f64],
) -> Result<Vec<f64>, HydroError> {
    flotation.check()?;
    datums.check()?;
    let plane = Waterplane::new(flotation, datums);
    let tol = SECTION_TOLERANCE_RELATIVE * size(geom);
    xs.iter()
        .map(|&x| {
            if !x.is_finite() {
                return Err(HydroError::InvalidInput(format!(
                    "station x = {x} must be a finite number"
                )));
            }
            Ok(immersed_section_area(geom, &plane, DVec3::X, x, tol))
        })
        .collect()
}

/// Check that the water at `plane` stays below the surface's open edges (other than a half
/// hull's centreplane edges, closed by its mirror image).
fn check_open_edges(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    draft: f64,
) -> Result<(), HydroError> {
    let slack = OPEN_EDGE_SLACK_RELATIVE * size(geom);
    let mut worst: Option<(f64, usize)> = None;
    for (k, e) in geom.open_edges().iter().enumerate() {
        let z = plane.zeta(e.point);
        if z < -slack && worst.is_none_or(|(w, _)| z < w) {
            worst = Some((z, k));
        }
    }
    match worst {
        None => Ok(()),
        Some((_, k)) => {
            let e = &geom.open_edges()[k];
            // A hole anywhere under water is named first; only then the flooded top.
            if let Some(h) = geom
                .open_edges()
                .iter()
                .filter(|e| !e.designed && plane.zeta(e.point) < -slack)
                .min_by(|a, b| plane.zeta(a.point).total_cmp(&plane.zeta(b.point)))
            {
                return Err(HydroError::hole(h.point, &h.curves));
            }
            Err(HydroError::above_top(draft, e.point))
        }
    }
}

/// Whether the whole of a closed hull is under the water surface `plane` (no waterplane: the
/// water is over its top), its highest wet point below the water by more than rounding.
fn sunk(geom: &dyn HullGeometry, plane: &Waterplane, scale: f64) -> bool {
    geom.wet_range(plane, plane.e3)
        .is_some_and(|(_, top)| top - plane.e3.dot(plane.origin) < -SUNK_SLACK_RELATIVE * scale)
}

/// The half angle of entrance (degrees): the slope at the fore end of the least-squares parabola
/// `y(x)` through the waterline points (port side, `y ≥ 0`) within the foremost `fraction·Lwl`.
fn entrance_half_angle(waterline: &[SectionSegment], plane: &Waterplane, lwl: f64) -> f64 {
    let Some((_, fore)) = range(waterline, plane.e1) else {
        return 0.0;
    };
    let reach = ENTRANCE_FIT_FRACTION * lwl;
    // Points (s, |η|) with s = distance aft of the fore end.
    let mut pts: Vec<(f64, f64)> = waterline
        .iter()
        .flatten()
        .map(|p| {
            let q = plane.earth(*p);
            (fore - q.x, q.y)
        })
        .filter(|&(s, eta)| s <= reach && eta >= 0.0)
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 * lwl.max(1.0));
    if pts.len() < 3 {
        return 0.0;
    }
    // y = c0 + c1 s + c2 s²: normal equations in scaled s.
    let mut m = [[0.0f64; 3]; 3];
    let mut r = [0.0f64; 3];
    for &(s, y) in &pts {
        let t = s / reach;
        let basis = [1.0, t, t * t];
        for i in 0..3 {
            r[i] += basis[i] * y;
            for j in 0..3 {
                m[i][j] += basis[i] * basis[j];
            }
        }
    }
    let Some(c) = solve3(m, r) else { return 0.0 };
    (c[1] / reach).atan().to_degrees().abs()
}

/// Solve a 3×3 system by Cramer's rule (the normal equations of a parabola).
fn solve3(m: [[f64; 3]; 3], r: [f64; 3]) -> Option<[f64; 3]> {
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let d = det(m);
    if !(d.abs() > 1e-300) {
        return None;
    }
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let mut a = m;
        for i in 0..3 {
            a[i][k] = r[i];
        }
        *o = det(a) / d;
    }
    Some(out)
}

/// The largest immersed section between `lo` and `hi` (stations normal to `x`): sampled, then
/// refined by golden-section search around the largest sample.
fn max_section(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    lo: f64,
    hi: f64,
    tol: f64,
) -> (f64, f64) {
    let area = |x: f64| immersed_section_area(geom, plane, DVec3::X, x, tol);
    let n = MAX_SECTION_SAMPLES;
    let step = (hi - lo) / (n - 1) as f64;
    let (mut best_x, mut best_a) = (lo, f64::NEG_INFINITY);
    for k in 0..n {
        let x = lo + step * k as f64;
        let a = area(x);
        if a > best_a {
            (best_x, best_a) = (x, a);
        }
    }
    let (mut a, mut b) = ((best_x - step).max(lo), (best_x + step).min(hi));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (area(x1), area(x2));
    for _ in 0..40 {
        if (b - a) < 1e-6 * (hi - lo) {
            break;
        }
        if f1 < f2 {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + g * (b - a);
            f2 = area(x2);
        } else {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - g * (b - a);
            f1 = area(x1);
        }
    }
    for (x, f) in [(x1, f1), (x2, f2)] {
        if f > best_a {
            (best_x, best_a) = (x, f);
        }
    }
    (best_x, best_a)
}

/// The hydrostatics of `geom` floating at `flotation`, about the perpendiculars `datums`.
///
/// Errors: invalid flotation or datums ([`HydroError::InvalidInput`]); the water below the keel
/// ([`HydroError::DraftBelowKeel`]) or over the open top ([`HydroError::DraftAboveTop`]); a free
/// edge under water off the centreplane ([`HydroError::HoleBelowWater`], naming where); no volume
/// or waterplane ([`HydroError::Degenerate`]).
pub fn hydrostatics(
    geom: &dyn HullGeometry,
    flotation: &Flotation,
    datums: &Datums,
) -> Result<Hydrostatics, HydroError> {
    flotation.check()?;
    datums.check()?;
    let plane = Waterplane::new(flotation, datums);
    let scale = size(geom);
    let tol = SECTION_TOLERANCE_RELATIVE * scale;
    let draft = flotation.draft;
    let Some((xi_lo, xi_hi)) = geom.wet_range(&plane, plane.e1) else {
        return Err(below_keel(geom, &plane, draft));
    };
    check_open_edges(geom, &plane, draft)?;
    let w: WetIntegrals = geom.wet_integrals(&plane);
    if !w.is_finite() {
        return Err(HydroError::Degenerate(
            "the wet surface's integrals are not finite".into(),
        ));
    }
    let v = w.volume;
    if !(v > 1e-12 * scale.powi(3)) || !(w.wp_area > 1e-12 * scale * scale) {
        if sunk(geom, &plane, scale) {
            let (lo, hi) = geom.bounds();
            return Err(HydroError::above_top(
                draft,
                DVec3::new(0.5 * (lo.x + hi.x), 0.0, hi.z),
            ));
        }
        return Err(HydroError::Degenerate(format!(
            "at draft {draft} m the hull displaces {v:.3e} m³ with a waterplane of {:.3e} m²: nothing floats",
            w.wp_area
        )));
    }
    let centre = plane.ship(DVec3::new(w.v_xi, w.v_eta, w.v_zeta) / v);
    let a = w.wp_area;
    let (xi_f, eta_f) = (w.wp_xi / a, w.wp_eta / a);
    let flotation_centre = plane.ship(DVec3::new(xi_f, eta_f, 0.0));
    let il = w.wp_xixi - a * xi_f * xi_f;
    let it = w.wp_etaeta - a * eta_f * eta_f;

    let waterline = geom.plane_section(plane.e3, plane.e3.dot(plane.origin), tol);
    let (lwl, bwl) = match (range(&waterline, plane.e1), range(&waterline, plane.e2)) {
        (Some((a0, a1)), Some((b0, b1))) => (a1 - a0, b1 - b0),
        _ => (0.0, 0.0),
    };
    let lpp = datums.lpp();
    let tan_trim = flotation.trim / lpp;
    let draft_at = |x: f64| draft + (datums.x_mid() - x) * tan_trim;
    let midship_area = immersed_section_area(geom, &plane, DVec3::X, datums.x_mid(), tol);
    let (x_lo, x_hi) = geom
        .wet_range(&plane, DVec3::X)
        .unwrap_or((datums.x_ap, datums.x_fp));
    let (max_section_x, max_section_area) = max_section(geom, &plane, x_lo, x_hi, tol);
    let transom_area =
        immersed_section_area(geom, &plane, DVec3::X, x_lo + 1e-6 * (x_hi - x_lo), tol);
    let density = flotation.density;
    let displacement = density * v;
    let t = draft;
    let kb = centre.z;
    let bmt = it / v;
    let bml = il / v;
    let ratio = |num: f64, den: f64| if den > 0.0 { num / den } else { 0.0 };
    let out = Hydrostatics {
        volume: v,
        displacement,
        density,
        draft_ap: draft_at(datums.x_ap),
        draft_fp: draft_at(datums.x_fp),
        draft_mid: draft,
        draft_lcf: draft_at(flotation_centre.x),
        trim: flotation.trim,
        heel: flotation.heel_deg,
        x_ap: datums.x_ap,
        x_fp: datums.x_fp,
        lpp,
        lwl,
        bwl,
        los: xi_hi - xi_lo,
        wetted_area: w.wetted,
        waterplane_area: a,
        midship_area,
        max_section_area,
        max_section_x,
        cb: ratio(v, lpp * bwl * t),
        cp: ratio(v, midship_area * lpp),
        cm: ratio(midship_area, bwl * t),
        cwp: ratio(a, lpp * bwl),
        cvp: ratio(v, a * t),
        lcb: centre.x,
        tcb: centre.y,
        vcb: kb,
        lcf: flotation_centre.x,
        it,
        il,
        bmt,
        bml,
        kmt: kb + bmt,
        kml: kb + bml,
        tpc: density * a / 100.0,
        mtc: displacement * bml / (100.0 * lpp),
        transom_area,
        entrance_half_angle: entrance_half_angle(&waterline, &plane, lwl),
    };
    Ok(out)
}
