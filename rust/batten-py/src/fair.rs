//! Curve fairing: `fair_points` (Dierckx smoothing spline) and `fairness` metrics.

use batten_core::{
    fair_points as core_fair, fairness_metrics, CurveError, FairOptions, FairnessMetrics,
    FlatPlane, Smoothing, Tolerance, DEFAULT_CORNER_ANGLE_DEGREES, DEFAULT_FAIR_DEGREE,
    DEFAULT_FAIR_TOLERANCE, DEFAULT_PARAMETER_ITERATIONS, DEFAULT_TOLERANCE,
};
use glam::DVec3;
use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{optional_whole, role_or_free, rows, text, whole};
use crate::curve::Curve;
use crate::errors::{arg_err, core_err, curve_err, guard};

fn metrics_into(d: &Bound<'_, PyDict>, m: &FairnessMetrics) -> PyResult<()> {
    d.set_item("inflections", m.inflections)?;
    d.set_item("curvature_extrema", m.curvature_extrema)?;
    d.set_item("fairness_energy", m.fairness_energy)?;
    d.set_item("max_curvature", m.max_curvature)?;
    d.set_item("plane_normal", m.plane_normal.to_array())?;
    Ok(())
}

/// Fair the points (n, 3) into a smooth B-spline named `name` (H-rep paper §4, Dierckx's
/// smoothing spline). Give at most one of `tolerance` (max deviation, m; default 1 mm),
/// `noise` (σ, m: S = M·σ²) or `smoothing_factor` (S, m²). `flat_planes`: a list of
/// `(normal, offset, tolerance)`, planes runs of points may lie in (a section's flat of
/// bottom, a flat of side): each run becomes a straight piece in its plane and the curve leaves
/// it tangentially (the report's `flats` say where, each with its plane's index);
/// `flat_noise` (m, default each plane's tolerance): how far points inside a run may stray
/// from the plane, its ends staying within the tolerance.
/// Returns `(Curve, report dict)`.
#[pyfunction]
#[pyo3(signature = (name, points, *, degree=None, tolerance=None, noise=None,
    smoothing_factor=None, corners=None, corner_angle_deg=Some(DEFAULT_CORNER_ANGLE_DEGREES),
    start_tangent=None, end_tangent=None, model_tolerance=DEFAULT_TOLERANCE,
    max_parameter_iterations=None, role=None, flat_planes=None, flat_noise=None),
    text_signature = "(name, points, *, degree=None, tolerance=None, noise=None, smoothing_factor=None, corners=None, corner_angle_deg=..., start_tangent=None, end_tangent=None, model_tolerance=..., max_parameter_iterations=None, role=\"free\", flat_planes=None, flat_noise=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fair_points<'py>(
    py: Python<'py>,
    name: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    degree: Option<&Bound<'py, PyAny>>,
    tolerance: Option<f64>,
    noise: Option<f64>,
    smoothing_factor: Option<f64>,
    corners: Option<Vec<Bound<'py, PyAny>>>,
    corner_angle_deg: Option<f64>,
    start_tangent: Option<[f64; 3]>,
    end_tangent: Option<[f64; 3]>,
    model_tolerance: f64,
    max_parameter_iterations: Option<&Bound<'py, PyAny>>,
    role: Option<&Bound<'py, PyAny>>,
    flat_planes: Option<Vec<([f64; 3], f64, f64)>>,
    flat_noise: Option<f64>,
) -> PyResult<(Curve, Bound<'py, PyDict>)> {
    let name = &text(name, || "the curve name".to_owned())?;
    let role = &role_or_free(name, role)?;
    let points = rows(points, || format!("curve '{name}': points"))?;
    let degree = optional_whole(degree, || format!("curve '{name}': degree"))?
        .unwrap_or(DEFAULT_FAIR_DEGREE);
    let max_parameter_iterations = optional_whole(max_parameter_iterations, || {
        format!("curve '{name}': max_parameter_iterations")
    })?
    .unwrap_or(DEFAULT_PARAMETER_ITERATIONS);
    let corners = corners
        .unwrap_or_default()
        .iter()
        .map(|c| whole(c, || format!("curve '{name}': corner index")))
        .collect::<PyResult<Vec<usize>>>()?;
    if points.shape()[1] != 3 {
        return Err(arg_err(format!(
            "curve '{name}': points must have shape (n, 3)"
        )));
    }
    let pts: Vec<DVec3> = points
        .as_array()
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect();
    let smoothing = match (tolerance, noise, smoothing_factor) {
        (t, None, None) => Smoothing::MaxDeviation(t.unwrap_or(DEFAULT_FAIR_TOLERANCE)),
        (None, Some(s), None) => Smoothing::Noise(s),
        (None, None, Some(s)) => Smoothing::Factor(s),
        _ => {
            return Err(arg_err(format!(
                "curve '{name}': give only one of tolerance, noise and smoothing_factor"
            )))
        }
    };
    let options = FairOptions {
        degree,
        smoothing,
        corners,
        corner_angle: corner_angle_deg.map(f64::to_radians),
        start_tangent: start_tangent.map(DVec3::from_array),
        end_tangent: end_tangent.map(DVec3::from_array),
        model_tolerance: Tolerance::try_new(model_tolerance).map_err(|_| {
            arg_err(format!(
                "curve '{name}': model_tolerance {model_tolerance} must be a positive finite number of metres"
            ))
        })?,
        max_parameter_iterations,
        flats: flat_planes
            .unwrap_or_default()
            .into_iter()
            .map(|(normal, offset, tolerance)| {
                flat(name, normal, offset, tolerance, flat_noise.unwrap_or(tolerance))
            })
            .collect::<PyResult<_>>()?,
    };
    let faired = py.detach(|| {
        guard(name, || {
            core_fair(&pts, &options).map_err(|e| core_err(e.named(name)))
        })
    })?;
    let curve = Curve::from_parts(name, role, faired.curve)?;
    let r = &faired.report;
    let d = PyDict::new(py);
    d.set_item("control_points", r.control_points)?;
    d.set_item("knots", r.knots.clone())?;
    d.set_item(
        "interior_knots",
        r.pieces.iter().map(|p| p.interior_knots).sum::<usize>(),
    )?;
    d.set_item("max_deviation", r.max_deviation)?;
    d.set_item("max_deviation_index", r.max_deviation_index)?;
    d.set_item("rms_deviation", r.rms_deviation)?;
    metrics_into(&d, &r.metrics)?;
    d.set_item("smoothing_factor", r.smoothing_factor)?;
    d.set_item("dropped_duplicates", r.dropped_duplicates)?;
    d.set_item("corners", r.corners.clone())?;
    d.set_item("corner_parameters", r.corner_parameters.clone())?;
    let pieces = r
        .pieces
        .iter()
        .map(|p| {
            let pd = PyDict::new(py);
            pd.set_item("points", p.points)?;
            pd.set_item("interior_knots", p.interior_knots)?;
            pd.set_item("smoothing_factor", p.smoothing_factor)?;
            pd.set_item("residual", p.residual)?;
            pd.set_item("p", p.p)?;
            pd.set_item("parameter_iterations", p.parameter_iterations)?;
            pd.set_item("parameters_settled", p.parameters_settled)?;
            Ok(pd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("pieces", pieces)?;
    let flats = r
        .flats
        .iter()
        .map(|f| {
            let fd = PyDict::new(py);
            fd.set_item("plane", f.plane)?;
            fd.set_item("index", f.index)?;
            fd.set_item("parameter", f.parameter)?;
            fd.set_item("point", f.point.to_array())?;
            Ok(fd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("flats", flats)?;
    Ok((curve, d))
}

/// The flat plane of `fair_points`, checked: a finite non-zero normal (made unit), a finite
/// offset and a positive finite tolerance.
fn flat(
    name: &str,
    normal: [f64; 3],
    offset: f64,
    tolerance: f64,
    noise: f64,
) -> PyResult<FlatPlane> {
    let n = DVec3::from_array(normal);
    let normal_ok = n.is_finite() && n.length_squared() > 0.0;
    if !(normal_ok && offset.is_finite() && tolerance.is_finite() && tolerance > 0.0) {
        return Err(arg_err(format!(
            "curve '{name}': a flat plane needs a finite non-zero normal, a finite offset and a positive tolerance, got {normal:?}, {offset}, {tolerance}"
        )));
    }
    if !(noise.is_finite() && noise >= 0.0) {
        return Err(arg_err(format!(
            "curve '{name}': flat_noise must be a finite distance of at least 0 m, got {noise}"
        )));
    }
    let length = n.length();
    Ok(FlatPlane {
        normal: n / length,
        offset: offset / length,
        tolerance,
        noise: noise.max(tolerance),
    })
}

/// Fairness figures of a curve: inflections, curvature extrema, ∫κ² ds, max curvature.
#[pyfunction]
pub(crate) fn fairness<'py>(
    py: Python<'py>,
    curve: PyRef<'py, Curve>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = guard(&curve.inner.name, || {
        Ok(fairness_metrics(&curve.inner.curve))
    })?;
    let figures = [m.fairness_energy, m.max_curvature];
    if !figures.iter().all(|f| f.is_finite()) || !m.plane_normal.is_finite() {
        return Err(curve_err(&curve.inner.name, CurveError::FiguresOverflow));
    }
    let d = PyDict::new(py);
    metrics_into(&d, &m)?;
    Ok(d)
}
