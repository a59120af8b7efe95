//! The naval architect's figures from the wet-surface integrals and plane sections of any
//! [`HullGeometry`]: volume, displacement, centres, waterplane, coefficients, metacentres, TPC,
//! MTC, sectional areas (ITTC symbols and definitions; SI units, tonnes for masses).

use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

use super::caps::cap_integrals;
use super::error::HydroError;
use super::geometry::{HullGeometry, SectionSegment};
use super::integrals::WetIntegrals;
use super::patch_model::CENTREPLANE_RELATIVE;
use super::waterplane::{Datums, Flotation, Waterplane};

/// How closely plane sections follow the surface, relative to the hull's size (the diagonal of
/// its box): the arcs' middles are on the surface, so section areas by Simpson's rule on the
/// arcs are good to far better than this (the error goes as its square).
pub const SECTION_TOLERANCE_RELATIVE: f64 = 1e-4;

/// How far below the water (relative to the hull's size) the highest wet point must be for a
/// closed hull to count as sunk: a waterline's points are exact, so this only absorbs rounding.
const SUNK_SLACK_RELATIVE: f64 = 1e-9;

/// The foremost part of the waterline, as a fraction of `Lwl`, whose least-squares parabola
/// gives the half angle of entrance at its fore end (leaves out a stem rounding much smaller
/// than that, as the lines of a design are read).
pub const ENTRANCE_FIT_FRACTION: f64 = 0.025;

/// At least this many waterline points go into the entrance parabola (where the pieces are
/// long, reaching beyond [`ENTRANCE_FIT_FRACTION`], but never beyond
/// [`ENTRANCE_MAX_FRACTION`] of Lwl).
const ENTRANCE_MIN_POINTS: usize = 4;
/// The farthest aft (as a fraction of Lwl) the entrance parabola reads the waterline.
const ENTRANCE_MAX_FRACTION: f64 = 0.1;

/// Stations sampled along the submerged length to find the largest section before refining
/// its place by successive parabolic interpolation ([`maximise`]).
const MAX_SECTION_SAMPLES: usize = 9;

/// Parabolic steps at most in [`maximise`] (each one more station; the bracket's spacing
/// shrinks superlinearly, and the area is flat at the top: four steps leave it within 1e-7
/// relative on a smooth curve, see the tests — the figure is printed to five digits).
const MAX_SECTION_REFINEMENTS: usize = 4;

/// A parabolic step closer than this (relative to the range) to the best place ends
/// [`maximise`]: the area cannot gain more than rounding.
const MAX_SECTION_PLACE_RELATIVE: f64 = 1e-9;

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
/// the hull's own pieces count). Each piece is an arc; `ζ` and `a` are quadratic along it and
/// `ζ·a'` cubic, so Simpson's rule on the arc — or on its part under water, cut at the root of
/// the quadratic `ζ` — is exact for the parabola.
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
    let sum: f64 = geom
        .section_arcs_below(m, c, tolerance, plane)
        .iter()
        .map(|arc| arc_integral(arc.map(|p| plane.zeta(p)), arc.map(|p| a.dot(p))))
        .sum();
    -sum / up_len
}

/// `∫ min(ζ, 0)·da` along the parabolic arc with values `z`, `a` at its start, middle and end.
fn arc_integral(z: [f64; 3], a: [f64; 3]) -> f64 {
    if z.iter().all(|&v| v >= 0.0) {
        return 0.0;
    }
    // Quadratic coefficients in λ ∈ [0, 1]: f(λ) = f0 + f1 λ + f2 λ².
    let quad = |v: [f64; 3]| {
        [
            v[0],
            -3.0 * v[0] + 4.0 * v[1] - v[2],
            2.0 * v[0] - 4.0 * v[1] + 2.0 * v[2],
        ]
    };
    let (zq, aq) = (quad(z), quad(a));
    let at = |q: [f64; 3], l: f64| q[0] + l * (q[1] + l * q[2]);
    let slope = |q: [f64; 3], l: f64| q[1] + 2.0 * l * q[2];
    let simpson = |l0: f64, l1: f64| {
        let lm = 0.5 * (l0 + l1);
        (l1 - l0) / 6.0
            * (at(zq, l0) * slope(aq, l0)
                + 4.0 * at(zq, lm) * slope(aq, lm)
                + at(zq, l1) * slope(aq, l1))
    };
    // Roots of ζ(λ) in (0, 1) split the arc.
    let mut cuts = vec![0.0];
    let (c0, c1, c2) = (zq[0], zq[1], zq[2]);
    if c2.abs() > 1e-14 * (c0.abs() + c1.abs()) {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc > 0.0 {
            let sq = disc.sqrt();
            let q = -0.5 * (c1 + c1.signum() * sq);
            for r in [q / c2, if q != 0.0 { c0 / q } else { f64::NAN }] {
                if r > 0.0 && r < 1.0 {
                    cuts.push(r);
                }
            }
        }
    } else if c1 != 0.0 {
        let r = -c0 / c1;
        if r > 0.0 && r < 1.0 {
            cuts.push(r);
        }
    }
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2)
        .filter(|w| at(zq, 0.5 * (w[0] + w[1])) < 0.0)
        .map(|w| simpson(w[0], w[1]))
        .sum()
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

/// Whether the whole of a closed hull is under the water surface `plane` (no waterplane: the
/// water is over its top), its highest wet point below the water by more than rounding.
fn sunk(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    scale: f64,
    waterline: &[SectionSegment],
) -> bool {
    geom.wet_range(plane, plane.e3, waterline)
        .is_some_and(|(_, top)| top - plane.e3.dot(plane.origin) < -SUNK_SLACK_RELATIVE * scale)
}

/// The half angle of entrance (degrees): the slope at the fore end of the least-squares parabola
/// `y(x)` through the waterline points (port side, `y ≥ 0`) within the foremost `fraction·Lwl`.
fn entrance_half_angle(waterline: &[SectionSegment], plane: &Waterplane, lwl: f64) -> f64 {
    // The fore end in the earth frame (ξ about the plane's origin, as the points below).
    let Some((_, fore)) = range(waterline, plane.e1) else {
        return 0.0;
    };
    let fore = fore - plane.e1.dot(plane.origin);
    // Points (s, |η|) with s = distance aft of the fore end.
    let mut pts: Vec<(f64, f64)> = waterline
        .iter()
        .flatten()
        .map(|p| {
            let q = plane.earth(*p);
            (fore - q.x, q.y)
        })
        .filter(|&(s, eta)| eta >= 0.0 && s <= ENTRANCE_MAX_FRACTION * lwl)
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 * lwl.max(1.0));
    // The foremost fraction, or (where the waterline's pieces are long) its first points.
    let within = pts
        .iter()
        .filter(|p| p.0 <= ENTRANCE_FIT_FRACTION * lwl)
        .count();
    pts.truncate(within.max(ENTRANCE_MIN_POINTS));
    if pts.len() < 3 {
        return 0.0;
    }
    let reach = pts.last().map_or(1.0, |p| p.0.max(f64::MIN_POSITIVE));
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
    if d.is_nan() || d.abs() <= 1e-300 {
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

/// The largest immersed section between `lo` and `hi` (stations normal to `x`): its place and
/// area ([`maximise`] of the sectional area curve), and the area at `lo` (its first sample).
fn max_section(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    lo: f64,
    hi: f64,
    tol: f64,
) -> ((f64, f64), f64) {
    maximise(
        &|x: f64| immersed_section_area(geom, plane, DVec3::X, x, tol),
        lo,
        hi,
    )
}

/// The maximum of a smooth `f` on `[lo, hi]`, as `(x, f(x))`, with `f(lo)`: `f` sampled at
/// [`MAX_SECTION_SAMPLES`] even places (in parallel, in order, so the result is a serial run's
/// bit for bit), then the best sample's bracket narrowed by successive parabolic
/// interpolation (Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 5: the
/// vertex of the parabola through the bracket's three points replaces one of them), at most
/// [`MAX_SECTION_REFINEMENTS`] more evaluations. A best sample at an end of the range is the
/// result (the curve then rises towards the end).
fn maximise(f: &(dyn Fn(f64) -> f64 + Sync), lo: f64, hi: f64) -> ((f64, f64), f64) {
    let n = MAX_SECTION_SAMPLES;
    let step = (hi - lo) / (n - 1) as f64;
    let samples: Vec<(f64, f64)> = (0..n)
        .into_par_iter()
        .map(|k| {
            let x = if k + 1 == n { hi } else { lo + step * k as f64 };
            (x, f(x))
        })
        .collect();
    // The first of equal maxima: a flat top (parallel middle body) keeps its first station.
    let best = (1..n).fold(0, |b, k| if samples[k].1 > samples[b].1 { k } else { b });
    let first = samples[0].1;
    if best == 0 || best + 1 == n {
        return (samples[best], first);
    }
    let (mut a, mut b, mut c) = (samples[best - 1], samples[best], samples[best + 1]);
    let close = MAX_SECTION_PLACE_RELATIVE * (hi - lo);
    for _ in 0..MAX_SECTION_REFINEMENTS {
        // The vertex of the parabola through a, b, c (b the highest of the three).
        let (h0, h2) = (b.0 - a.0, c.0 - b.0);
        let (d0, d2) = (b.1 - a.1, b.1 - c.1);
        let den = h0 * d2 + h2 * d0;
        if den.is_nan() || den <= 0.0 {
            break;
        }
        let x = b.0 + 0.5 * (h2 * h2 * d0 - h0 * h0 * d2) / den;
        if x.is_nan() || x <= a.0 || x >= c.0 || (x - b.0).abs() <= close {
            break;
        }
        let v = (x, f(x));
        // Keep the highest point and its neighbours on either side as the bracket.
        if x < b.0 {
            if v.1 > b.1 {
                (c, b) = (b, v);
            } else {
                a = v;
            }
        } else if v.1 > b.1 {
            (a, b) = (b, v);
        } else {
            c = v;
        }
    }
    (b, first)
}

/// The immersed areas of the stations the figures need, side by side: at midship, the largest
/// (its place and area) and the transom's (just forward of the wet surface's aft end), with
/// `xi` the wet range along the waterplane's `e1`.
fn stations(
    geom: &dyn HullGeometry,
    plane: &Waterplane,
    datums: &Datums,
    waterline: &[SectionSegment],
    (xi_lo, xi_hi): (f64, f64),
    tol: f64,
) -> (f64, (f64, f64), f64) {
    // Upright and level in x, the range along x is the one along e1.
    let (x_lo, x_hi) = if plane.e1 == DVec3::X {
        (xi_lo, xi_hi)
    } else {
        geom.wet_range(plane, DVec3::X, waterline)
            .unwrap_or((datums.x_ap, datums.x_fp))
    };
    // The transom's station is the first of the sectional area curve's samples.
    let transom_x = x_lo + 1e-6 * (x_hi - x_lo);
    let (midship, (max, transom)) = rayon::join(
        || immersed_section_area(geom, plane, DVec3::X, datums.x_mid(), tol),
        || max_section(geom, plane, transom_x, x_hi, tol),
    );
    (midship, max, transom)
}

/// The hydrostatics of `geom` floating at `flotation`, about the perpendiculars `datums`.
///
/// Errors: invalid flotation or datums ([`HydroError::InvalidInput`]); the water below the keel
/// ([`HydroError::DraftBelowKeel`]) or over the open top ([`HydroError::DraftAboveTop`]); a free
/// edge under water off the centreplane that no steep plane closes
/// ([`HydroError::HoleBelowWater`], naming where — an open transom is closed by its plane, see
/// [`caps`](super::caps)); no volume or waterplane ([`HydroError::Degenerate`]).
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
    let lpp = datums.lpp();
    // The wet surface's integrals, and the waterline with the stations (midship, the largest
    // section, the transom) are independent: computed side by side, then checked in the order
    // the errors are documented (the water below the keel, then a hole, before the sections
    // are used).
    let (wet, (waterline, stations)) = rayon::join(
        || -> Result<WetIntegrals, HydroError> {
            let caps = cap_integrals(geom, &plane, draft, scale, CENTREPLANE_RELATIVE * scale)?;
            Ok(geom.wet_integrals(&plane) + caps)
        },
        || {
            let waterline = geom.plane_section(plane.e3, plane.e3.dot(plane.origin), tol);
            let stations = geom
                .wet_range(&plane, plane.e1, &waterline)
                .map(|xi| (xi, stations(geom, &plane, datums, &waterline, xi, tol)));
            (waterline, stations)
        },
    );
    let Some(((xi_lo, xi_hi), (midship_area, (max_section_x, max_section_area), transom_area))) =
        stations
    else {
        return Err(below_keel(geom, &plane, draft));
    };
    let w: WetIntegrals = wet?;
    if !w.is_finite() {
        return Err(HydroError::Degenerate(
            "the wet surface's integrals are not finite".into(),
        ));
    }
    let v = w.volume;
    let floats = v > 1e-12 * scale.powi(3) && w.wp_area > 1e-12 * scale * scale;
    if !floats {
        if sunk(geom, &plane, scale, &waterline) {
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

    let (lwl, bwl) = match (range(&waterline, plane.e1), range(&waterline, plane.e2)) {
        (Some((a0, a1)), Some((b0, b1))) => (a1 - a0, b1 - b0),
        _ => (0.0, 0.0),
    };
    let tan_trim = flotation.trim / lpp;
    let draft_at = |x: f64| draft + (datums.x_mid() - x) * tan_trim;
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// `maximise` of `f` on `[lo, hi]` with the number of evaluations it made.
    fn counted(f: impl Fn(f64) -> f64 + Sync, lo: f64, hi: f64) -> ((f64, f64), usize) {
        let calls = AtomicUsize::new(0);
        let g = |x: f64| {
            calls.fetch_add(1, Ordering::Relaxed);
            f(x)
        };
        let (out, _) = maximise(&g, lo, hi);
        (out, calls.into_inner())
    }

    #[test]
    fn the_largest_section_of_a_smooth_curve_is_found_to_1e_7_in_a_few_stations() {
        // x²(1 − x): maximum 4/27 at 2/3, between the samples; sin(πx)·eˣ (a fuller aft body):
        // maximum where tan(πx) = −π, x = 1 − atan(π)/π.
        let x_skew = 1.0 - std::f64::consts::PI.atan() / std::f64::consts::PI;
        let skew = |x: f64| (std::f64::consts::PI * x).sin() * x.exp();
        for (f, x_max) in [
            (
                &(|x: f64| x * x * (1.0 - x)) as &(dyn Fn(f64) -> f64 + Sync),
                2.0 / 3.0,
            ),
            (&skew, x_skew),
        ] {
            let ((x, v), calls) = counted(f, 0.0, 1.0);
            let want = f(x_max);
            assert!(
                (v - want).abs() <= 1e-7 * want,
                "maximum {v} vs {want} (at {x} vs {x_max})"
            );
            assert!((x - x_max).abs() < 1e-3, "place {x} vs {x_max}");
            assert!(
                calls <= MAX_SECTION_SAMPLES + MAX_SECTION_REFINEMENTS,
                "{calls} stations"
            );
        }
    }

    #[test]
    fn a_curve_rising_to_an_end_or_flat_has_its_maximum_at_a_sample() {
        let ((x, v), _) = counted(|x| 2.0 * x, 3.0, 5.0);
        assert_eq!((x, v), (5.0, 10.0));
        let ((x, v), calls) = counted(|_| 7.0, -1.0, 1.0);
        assert_eq!((x, v), (-1.0, 7.0), "the first station of a flat top");
        assert_eq!(calls, MAX_SECTION_SAMPLES);
    }
}
