//! The inverse of hydrostatics: the draft and trim at which a hull floats with a given
//! displacement and its centre of buoyancy under the centre of gravity (Newton's method on the
//! two equilibrium conditions, the Jacobian by central differences of the wet-surface integrals).

use glam::DVec3;

use super::caps::cap_integrals;
use super::error::HydroError;
use super::geometry::HullGeometry;
use super::waterplane::{Datums, Flotation, Waterplane};

/// Newton iterations at most.
const MAX_ITERATIONS: usize = 40;
/// Bisection steps for the level draft that starts Newton.
const BISECTION_STEPS: usize = 60;
/// Relative step of the central differences (of the hull's depth for the draft, of Lpp for the
/// trim).
const DIFFERENCE_STEP: f64 = 1e-5;
/// Convergence: the volume to this fraction of itself, the centre to this fraction of Lpp.
const CONVERGED: f64 = 1e-11;

/// The upright flotation at which `geom` displaces `displacement` tonnes in water of `density`
/// with its centre of buoyancy on the vertical through the centre of gravity: `lcg` its `x`, and
/// `vcg` its height above the baseline when given (the vertical then tilts with the trim);
/// without `vcg`, `LCB = LCG` in the ship's axes (the hydrostatic tables' condition).
///
/// Errors: a displacement that is not positive or more than the hull holds, invalid numbers
/// ([`HydroError::InvalidInput`]); no convergence ([`HydroError::NoEquilibrium`]); and any
/// error of the hull's integrals at the flotations tried (a hole under water …).
pub fn float_to(
    geom: &dyn HullGeometry,
    datums: &Datums,
    displacement: f64,
    lcg: f64,
    vcg: Option<f64>,
    density: f64,
) -> Result<Flotation, HydroError> {
    datums.check()?;
    let probe = Flotation {
        draft: 0.0,
        trim: 0.0,
        heel_deg: 0.0,
        density,
    };
    probe.check()?;
    for (what, v) in [("displacement", displacement), ("LCG", lcg)] {
        if !v.is_finite() {
            return Err(HydroError::InvalidInput(format!(
                "{what} {v} must be a finite number"
            )));
        }
    }
    if let Some(v) = vcg {
        if !v.is_finite() {
            return Err(HydroError::InvalidInput(format!(
                "VCG {v} must be a finite number"
            )));
        }
    }
    if displacement <= 0.0 {
        return Err(HydroError::InvalidInput(format!(
            "displacement {displacement} t must be positive"
        )));
    }
    let target = displacement / density;
    let (lo, hi) = geom.bounds();
    let size = (hi - lo).length();
    let near = super::patch_model::CENTREPLANE_RELATIVE * size;
    let depth = hi.z - lo.z;
    let lpp = datums.lpp();
    // Volume and the centre's offset from G along the water, at (draft, trim).
    let state = |draft: f64, trim: f64| -> Result<(f64, f64), HydroError> {
        let f = Flotation {
            draft,
            trim,
            heel_deg: 0.0,
            density,
        };
        let plane = Waterplane::new(&f, datums);
        let w = geom.wet_integrals(&plane) + cap_integrals(geom, &plane, draft, size, near)?;
        if w.volume.is_nan() || w.volume <= 0.0 {
            return Ok((0.0, 0.0));
        }
        let b = plane.ship(DVec3::new(w.v_xi, w.v_eta, w.v_zeta) / w.volume);
        let offset = match vcg {
            Some(z) => plane.e1.dot(b - DVec3::new(lcg, 0.0, z)),
            None => b.x - lcg,
        };
        Ok((w.volume, offset))
    };
    let level = level_draft(geom, displacement, density)?;
    let (mut draft, mut trim) = (level, 0.0);
    let (hd, ht) = (DIFFERENCE_STEP * depth, DIFFERENCE_STEP * lpp);
    for _ in 0..MAX_ITERATIONS {
        let (v, o) = state(draft, trim)?;
        let (r1, r2) = (v - target, o);
        if r1.abs() <= CONVERGED * target && r2.abs() <= CONVERGED * lpp {
            return Ok(Flotation {
                draft,
                trim,
                heel_deg: 0.0,
                density,
            });
        }
        let (vp, op) = state(draft + hd, trim)?;
        let (vm, om) = state(draft - hd, trim)?;
        let (vq, oq) = state(draft, trim + ht)?;
        let (vn, on) = state(draft, trim - ht)?;
        let j = [
            [(vp - vm) / (2.0 * hd), (vq - vn) / (2.0 * ht)],
            [(op - om) / (2.0 * hd), (oq - on) / (2.0 * ht)],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let dd = (r1 * j[1][1] - r2 * j[0][1]) / det;
        let dt = (j[0][0] * r2 - j[1][0] * r1) / det;
        // Damped: never more than a tenth of the depth or of Lpp at a time.
        let scale = (dd.abs() / (0.1 * depth))
            .max(dt.abs() / (0.1 * lpp))
            .max(1.0);
        draft -= dd / scale;
        trim -= dt / scale;
    }
    Err(HydroError::NoEquilibrium(format!(
        "no flotation found for displacement {displacement} t with LCG {lcg} m: the search for draft and trim did not settle (last draft {draft:.4} m, trim {trim:.4} m)"
    )))
}

/// The level, upright draft at which `geom` displaces `displacement` tonnes in water of
/// `density` (bisection between the keel and the top; a draft that floods the open top is too
/// deep). The perpendiculars play no part when level.
///
/// Errors: a displacement that is not positive or finite, or more than the hull holds below its
/// open top ([`HydroError::InvalidInput`]); a hole under water on the way.
pub fn level_draft(
    geom: &dyn HullGeometry,
    displacement: f64,
    density: f64,
) -> Result<f64, HydroError> {
    if !(displacement.is_finite() && displacement > 0.0) {
        return Err(HydroError::InvalidInput(format!(
            "displacement {displacement} t must be a positive number"
        )));
    }
    Flotation {
        draft: 0.0,
        trim: 0.0,
        heel_deg: 0.0,
        density,
    }
    .check()?;
    let target = displacement / density;
    let (lo, hi) = geom.bounds();
    let size = (hi - lo).length();
    let near = super::patch_model::CENTREPLANE_RELATIVE * size;
    let volume = |z: f64| -> Result<f64, HydroError> {
        let plane = Waterplane::level(z);
        Ok((geom.wet_integrals(&plane) + cap_integrals(geom, &plane, z, size, near)?).volume)
    };
    let (mut a, mut b) = (lo.z, hi.z);
    let mut held = 0.0f64;
    for _ in 0..BISECTION_STEPS {
        let m = 0.5 * (a + b);
        match volume(m) {
            Ok(v) if v < target => {
                a = m;
                held = held.max(v);
            }
            Ok(_) | Err(HydroError::DraftAboveTop { .. }) => b = m,
            Err(e) => return Err(e),
        }
    }
    let z = 0.5 * (a + b);
    match volume(z) {
        Ok(v) if (v - target).abs() <= 1e-6 * target => Ok(z),
        Ok(_) | Err(HydroError::DraftAboveTop { .. }) => Err(HydroError::InvalidInput(format!(
            "displacement {displacement:.6} t is more than the hull holds level below its open top ({:.6} t)",
            held * density
        ))),
        Err(e) => Err(e),
    }
}
