//! Surface fairing through families of sections (seed 003): `fair_sections` and the paper's
//! noise test `section_noise`.

use batten_core::{
    HullFairness, Role, SectionFairness, SectionFamily, SectionFilter, SurfaceFairOptions,
    Tolerance, DEFAULT_SURFACE_FAIR_ROUNDS, DEFAULT_SURFACE_FAIR_TOLERANCE, DEFAULT_TOLERANCE,
};
use glam::DVec3;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::{curves_of, network_of, Curve};
use crate::errors::{arg_err, core_err, guard};
use crate::progress::Progress;

/// The options from Python's arguments, each bad value an InvalidArgumentError naming it.
#[allow(clippy::too_many_arguments)]
fn options(
    tolerance: f64,
    families: Vec<String>,
    fixed_roles: Option<Vec<String>>,
    fixed_curves: Vec<String>,
    fixed_points: Vec<[f64; 3]>,
    curve_tolerances: Vec<(String, f64)>,
    filter: &str,
    max_rounds: usize,
    bias_target: Option<f64>,
    smoothing_length: Option<f64>,
    model_tolerance: f64,
) -> PyResult<SurfaceFairOptions> {
    let families = families
        .iter()
        .map(|f| {
            SectionFamily::from_name(f).ok_or_else(|| {
                arg_err(format!(
                    "families: unknown family '{f}' (stations, waterlines or buttocks)"
                ))
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let defaults = SurfaceFairOptions::default();
    let fixed_roles = match fixed_roles {
        None => defaults.fixed_roles,
        Some(roles) => roles
            .iter()
            .map(|r| {
                Role::from_name(r)
                    .ok_or_else(|| arg_err(format!("fixed roles: unknown role '{r}'")))
            })
            .collect::<PyResult<Vec<_>>>()?,
    };
    let filter = match filter {
        "cubic" => SectionFilter::Cubic,
        "equidistant" => SectionFilter::Equidistant,
        other => {
            return Err(arg_err(format!(
                "filter: unknown filter '{other}' (cubic or equidistant)"
            )))
        }
    };
    let model_tolerance = Tolerance::try_new(model_tolerance).map_err(core_err)?;
    Ok(SurfaceFairOptions {
        tolerance,
        curve_tolerances,
        families,
        fixed_roles,
        fixed_curves,
        fixed_points: fixed_points.into_iter().map(DVec3::from_array).collect(),
        filter,
        max_rounds,
        bias_target,
        model_tolerance,
        smoothing_length,
    })
}

fn section_dict<'py>(py: Python<'py>, f: &SectionFairness) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("curvature_variation", f.curvature_variation)?;
    d.set_item("inflections", f.inflections)?;
    d.set_item("max_bias", f.max_bias)?;
    Ok(d)
}

fn hull_dict<'py>(py: Python<'py>, f: &HullFairness) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("curvature_variation", f.curvature_variation)?;
    d.set_item("inflections", f.inflections)?;
    d.set_item("max_bias", f.max_bias)?;
    Ok(d)
}

/// Fair the sections among `curves` (Pla et al. 1998 §4, `batten_core::fair_sections`):
/// each section smoothed along itself first (`smoothing_length` m; None: 200 tolerances, 0:
/// none), then the relaxation's rounds. Returns `([Curve, ...], report)`, curve for curve in
/// order (fixed and unmoved ones as given). The report: `rounds`, `moves`, `converged`,
/// `bias_target`, `smoothing_length`, `smoothed` (sections the smoothing moved), `sections` (per family,
/// its movable sections), `max_deviation` (m), `before` and `after` (the hull's
/// `curvature_variation` Σ∫κ′² ds, `inflections`, `max_bias`), and `curves`, one dict per
/// curve: `curve`, `family` (or None), `offset`, `moves`, `tolerance`, `max_deviation`,
/// `before`, `after`. The GIL is released while it runs; `progress(rounds done, max rounds)`,
/// if given, is called (holding the GIL again) after each round: returning `False` stops the
/// fairing and raises `Cancelled`, an exception it raises stops it and propagates; either way
/// no curve is returned.
#[pyfunction]
#[pyo3(signature = (curves, *, tolerance=DEFAULT_SURFACE_FAIR_TOLERANCE,
    families=vec!["stations".to_owned(), "waterlines".to_owned()], fixed_roles=None,
    fixed_curves=Vec::new(), fixed_points=Vec::new(), curve_tolerances=Vec::new(),
    filter="cubic", max_rounds=DEFAULT_SURFACE_FAIR_ROUNDS, bias_target=None,
    smoothing_length=None, model_tolerance=DEFAULT_TOLERANCE, progress=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fair_sections<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
    families: Vec<String>,
    fixed_roles: Option<Vec<String>>,
    fixed_curves: Vec<String>,
    fixed_points: Vec<[f64; 3]>,
    curve_tolerances: Vec<(String, f64)>,
    filter: &str,
    max_rounds: usize,
    bias_target: Option<f64>,
    smoothing_length: Option<f64>,
    model_tolerance: f64,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Vec<Curve>, Bound<'py, PyDict>)> {
    let opts = options(
        tolerance,
        families,
        fixed_roles,
        fixed_curves,
        fixed_points,
        curve_tolerances,
        filter,
        max_rounds,
        bias_target,
        smoothing_length,
        model_tolerance,
    )?;
    let network = network_of("", &curves)?;
    let progress = Progress::new(progress);
    let faired = py.detach(|| {
        guard("fairing the sections", || {
            let mut round_done = |done: usize, total: usize| progress.goes_on(done, total);
            batten_core::fair_sections_with(&network, &opts, &mut round_done).map_err(core_err)
        })
    })?;
    let Some(faired) = faired else {
        return Err(progress.stopped("surface fairing cancelled"));
    };
    let r = &faired.report;
    let d = PyDict::new(py);
    d.set_item("rounds", r.rounds)?;
    d.set_item("moves", r.moves)?;
    d.set_item("converged", r.converged)?;
    d.set_item("bias_target", r.bias_target)?;
    d.set_item("smoothing_length", r.smoothing_length)?;
    d.set_item("smoothed", r.smoothed)?;
    let sections = PyDict::new(py);
    for (f, n) in &r.sections {
        sections.set_item(f.name(), n)?;
    }
    d.set_item("sections", sections)?;
    d.set_item("max_deviation", r.max_deviation)?;
    d.set_item("before", hull_dict(py, &r.before)?)?;
    d.set_item("after", hull_dict(py, &r.after)?)?;
    let per_curve = r
        .curves
        .iter()
        .map(|c| {
            let cd = PyDict::new(py);
            cd.set_item("curve", &c.curve)?;
            cd.set_item("family", c.family.map(SectionFamily::name))?;
            cd.set_item("offset", c.offset)?;
            cd.set_item("moves", c.moves)?;
            cd.set_item("tolerance", c.tolerance)?;
            cd.set_item("max_deviation", c.max_deviation)?;
            cd.set_item("before", section_dict(py, &c.before)?)?;
            cd.set_item("after", section_dict(py, &c.after)?)?;
            Ok(cd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("curves", per_curve)?;
    Ok((curves_of(&faired.network), d))
}

/// The paper's test input (Pla et al. 1998 §5, `batten_core::section_noise`): every movable
/// section of `families` among `curves` moved along its normal at each control point by a
/// random amount uniform in ±`amplitude` (m) from `seed`, the nodes carried along so the
/// network stays exact. Returns the curves, in order.
#[pyfunction]
#[pyo3(signature = (curves, amplitude, seed, *,
    families=vec!["stations".to_owned(), "waterlines".to_owned()], fixed_roles=None,
    fixed_curves=Vec::new(), model_tolerance=DEFAULT_TOLERANCE))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn section_noise(
    py: Python<'_>,
    curves: Vec<PyRef<'_, Curve>>,
    amplitude: f64,
    seed: u64,
    families: Vec<String>,
    fixed_roles: Option<Vec<String>>,
    fixed_curves: Vec<String>,
    model_tolerance: f64,
) -> PyResult<Vec<Curve>> {
    let opts = options(
        DEFAULT_SURFACE_FAIR_TOLERANCE,
        families,
        fixed_roles,
        fixed_curves,
        Vec::new(),
        Vec::new(),
        "cubic",
        0,
        None,
        None,
        model_tolerance,
    )?;
    let network = network_of("", &curves)?;
    let noisy = py.detach(|| {
        guard("adding noise to the sections", || {
            batten_core::section_noise(&network, amplitude, seed, &opts).map_err(core_err)
        })
    })?;
    Ok(curves_of(&noisy))
}
