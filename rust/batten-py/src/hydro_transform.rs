//! Hydrostatic transformations (seed 002 §8) as plain Python data.

use batten_core::{
    transform_hydrostatic as core_transform_hydrostatic, Datums, HullOptions, HydroTargets,
    HydroTransformOptions, PmbHold, Stop, VolumeTarget, DEFAULT_RESOLUTION, DEFAULT_TOLERANCE,
    SEA_WATER_DENSITY,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::{curves_of, network_of, tangent_planes_of, Curve};
use crate::errors::{arg_err, core_err, form_err, guard};
use crate::hydro::hydrostatics_dict;

/// Take the network `curves` to a target volume (one of `volume` m³, `displacement` t, `cb`,
/// `cp`) and/or `lcb` (x, m) through its form topology, floating level at `draft`: by moving
/// the ends of its parallel middle body, or (no PMB, or `keep_pmb` True) by bulging its ends'
/// faces below the waterline; `keep_pmb` `"length"` or `"position"` holds that of the PMB and
/// bulges the ends for the rest (a target not given is held). Perpendiculars: `fp` with `lpp`, else FP at the fore end of the original's waterline at
/// `draft` and AP `lpp` aft of it (or at the waterline's aft end); held for every hull.
/// Returns `(curves, report)`: `before`, `after` (hydrostatics dicts), `target_figure`
/// (`"volume"`, a displacement as its volume, `"cb"` or `"cp"`) and `target_value`,
/// `target_volume` (Cb and Cp on the original's Lpp, Bwl and midship section),
/// `target_lcb`, `mode` (`"pmb"`, `"bulge"`, `"pmb+bulge"`, `"pmb_shift+bulge"`,
/// `"pmb_length+bulge"`), `entrance_length`, `run_length`, `pmb_length`
/// (each `[before, after]`, None without a PMB), `bulge` (None, or `offsets` `[entrance, run]`
/// in m and the form faces `entrance_faces`, `run_faces`),
/// `evaluations`, `stop` (`"converged"`, `"out_of_range"`, `"evaluations_spent"`), `limit`
/// (what stopped it, or None), `explored` (`volume`, `lcb`: `[min, max]` over the hulls evaluated), `x_ap`,
/// `x_fp`. `tangent_planes` (`[nx, ny, nz, offset]` each, as `build_surface` takes them) go
/// with every hull built.
#[pyfunction]
#[pyo3(signature = (curves, draft, *, volume=None, displacement=None, cb=None, cp=None, lcb=None, keep_pmb=None, lpp=None, fp=None, density=SEA_WATER_DENSITY, tolerance=DEFAULT_TOLERANCE, resolution=DEFAULT_RESOLUTION, tangent_planes=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn transform_hydrostatic<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    draft: f64,
    volume: Option<f64>,
    displacement: Option<f64>,
    cb: Option<f64>,
    cp: Option<f64>,
    lcb: Option<f64>,
    keep_pmb: Option<&Bound<'py, PyAny>>,
    lpp: Option<f64>,
    fp: Option<f64>,
    density: f64,
    tolerance: f64,
    resolution: usize,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<(Vec<Curve>, Bound<'py, PyDict>)> {
    let given: Vec<VolumeTarget> = [
        volume.map(VolumeTarget::Volume),
        displacement.map(VolumeTarget::Displacement),
        cb.map(VolumeTarget::Cb),
        cp.map(VolumeTarget::Cp),
    ]
    .into_iter()
    .flatten()
    .collect();
    if given.len() > 1 {
        return Err(arg_err(
            "transform_hydrostatic: give one of volume, displacement, cb and cp, not several",
        ));
    }
    if given.is_empty() && lcb.is_none() {
        return Err(arg_err(
            "transform_hydrostatic: give a volume (or displacement, cb, cp) target, an lcb target, or both",
        ));
    }
    if !(draft.is_finite() && density.is_finite() && density > 0.0) {
        return Err(arg_err(format!(
            "transform_hydrostatic: draft {draft} and density {density} must be finite (density > 0)"
        )));
    }
    let datums = match (fp, lpp) {
        (Some(fp), Some(lpp)) => Some(Datums {
            x_ap: fp - lpp,
            x_fp: fp,
        }),
        (None, _) => None,
        (Some(_), None) => {
            return Err(arg_err(
                "transform_hydrostatic: fp was given without lpp: give the length between perpendiculars too",
            ))
        }
    };
    let hold = match keep_pmb {
        None => PmbHold::Free,
        Some(k) => match (k.extract::<bool>(), k.extract::<String>()) {
            (Ok(false), _) => PmbHold::Free,
            (Ok(true), _) => PmbHold::Whole,
            (_, Ok(s)) if s == "length" => PmbHold::Length,
            (_, Ok(s)) if s == "position" => PmbHold::Position,
            _ => {
                return Err(arg_err(format!(
                    "transform_hydrostatic: keep_pmb must be False, True, 'length' or 'position', not {}",
                    k.repr()?
                )))
            }
        },
    };
    let hull = HullOptions::try_new(tolerance, resolution).map_err(core_err)?;
    let network = network_of("", &curves)?.with_tangent_planes(tangent_planes_of(tangent_planes)?);
    let options = HydroTransformOptions {
        draft,
        datums,
        lpp,
        density,
        hull,
    };
    let targets = HydroTargets {
        volume: given.first().copied(),
        lcb,
        hold,
    };
    let out = py.detach(|| {
        guard("transforming the hull to its hydrostatic targets", || {
            core_transform_hydrostatic(&network, targets, &options).map_err(form_err)
        })
    })?;
    let report = PyDict::new(py);
    report.set_item("before", hydrostatics_dict(py, &out.before)?)?;
    report.set_item("after", hydrostatics_dict(py, &out.after)?)?;
    report.set_item("target_figure", out.target.0)?;
    report.set_item("target_value", out.target.1)?;
    report.set_item("target_volume", out.target_volume)?;
    report.set_item("target_lcb", out.target_lcb)?;
    report.set_item("mode", out.mode)?;
    report.set_item("entrance_length", out.entrance_length.map(|v| v.to_vec()))?;
    report.set_item("run_length", out.run_length.map(|v| v.to_vec()))?;
    report.set_item("pmb_length", out.pmb_length.map(|v| v.to_vec()))?;
    match &out.bulge {
        Some((offsets, [entrance, run])) => {
            let bulge = PyDict::new(py);
            bulge.set_item("offsets", offsets.to_vec())?;
            bulge.set_item("entrance_faces", entrance.clone())?;
            bulge.set_item("run_faces", run.clone())?;
            report.set_item("bulge", bulge)?;
        }
        None => report.set_item("bulge", py.None())?,
    }
    report.set_item("evaluations", out.evaluations)?;
    let (stop, limit) = match &out.stop {
        Stop::Converged => ("converged", None),
        Stop::OutOfRange { limit } => ("out_of_range", Some(limit.clone())),
        Stop::EvaluationsSpent => ("evaluations_spent", None),
    };
    report.set_item("stop", stop)?;
    report.set_item("limit", limit)?;
    let explored = PyDict::new(py);
    explored.set_item("volume", out.explored.volume.to_vec())?;
    explored.set_item("lcb", out.explored.lcb.to_vec())?;
    report.set_item("explored", explored)?;
    report.set_item("x_ap", out.datums.x_ap)?;
    report.set_item("x_fp", out.datums.x_fp)?;
    Ok((curves_of(&out.network), report))
}
