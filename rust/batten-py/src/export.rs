//! CAD exports of a built hull: the core's B-spline faces as IGES or STEP text, or as control
//! nets for the add-on's Rhino `.3dm` writer. Arguments first, then the core with the GIL
//! released; errors through [`crate::errors`].

use batten_core::{
    cad_surface, iges_text, step_text, CadHeader, CadSurface, ExportOptions, Timestamp,
};
use numpy::ndarray::Array3;
use numpy::{PyArray1, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{arg_err, export_err, guard};
use crate::hull_model::HullModel;

/// The faces of `model` within `tolerance` (the GIL released by the caller).
fn faces(model: &HullModel, tolerance: f64, allow_holes: bool) -> PyResult<CadSurface> {
    let options = ExportOptions {
        tolerance,
        allow_holes,
    };
    cad_surface(model.surface(), &options).map_err(export_err)
}

/// What an export measured: faces, patches, control_points, max_deviation (m), tolerance (m).
fn stats<'py>(py: Python<'py>, cad: &CadSurface) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("faces", cad.faces.len())?;
    d.set_item("patches", cad.patches)?;
    let points: usize = cad.faces.iter().map(|f| f.surface.control.len()).sum();
    d.set_item("control_points", points)?;
    d.set_item("max_deviation", cad.max_deviation)?;
    d.set_item("tolerance", cad.tolerance)?;
    Ok(d)
}

/// The text of `model`'s surface as `format` (`"iges"` or `"step"`), each patch approximated
/// by bicubic B-spline faces within `tolerance` (m), and what was measured (see `stats`).
/// `timestamp` is `(year, month, day, hour, minute, second)` UTC.
#[pyfunction]
#[pyo3(signature = (model, format, tolerance, allow_holes, name, file_name, author, timestamp))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn cad_text<'py>(
    py: Python<'py>,
    model: &HullModel,
    format: &str,
    tolerance: f64,
    allow_holes: bool,
    name: String,
    file_name: String,
    author: String,
    timestamp: (u16, u8, u8, u8, u8, u8),
) -> PyResult<(String, Bound<'py, PyDict>)> {
    let writer = match format {
        "iges" => iges_text,
        "step" => step_text,
        other => {
            return Err(arg_err(format!(
                "unknown CAD format '{other}' (use 'iges' or 'step')"
            )))
        }
    };
    let (year, month, day, hour, minute, second) = timestamp;
    let header = CadHeader {
        name,
        file_name,
        author,
        timestamp: Timestamp {
            year,
            month,
            day,
            hour,
            minute,
            second,
        },
    };
    let (text, cad) = py.detach(|| {
        guard("exporting the surface", || {
            let cad = faces(model, tolerance, allow_holes)?;
            Ok((writer(&cad, &header), cad))
        })
    })?;
    Ok((text, stats(py, &cad)?))
}

/// One face as numpy arrays for a NURBS writer.
type FaceArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray3<f64>>,
);

/// `model`'s surface as bicubic B-spline faces within `tolerance` (m): a list of
/// `(knots_u, knots_v, control)` per face — clamped knot vectors on `[0, 1]` (all
/// `count + 4` knots) and the control net of shape `(count_u, count_v, 3)` — and what was
/// measured (see `cad_text`).
#[pyfunction]
#[pyo3(signature = (model, tolerance, allow_holes))]
pub(crate) fn cad_faces<'py>(
    py: Python<'py>,
    model: &HullModel,
    tolerance: f64,
    allow_holes: bool,
) -> PyResult<(Vec<FaceArrays<'py>>, Bound<'py, PyDict>)> {
    let cad = py.detach(|| {
        guard("exporting the surface", || {
            faces(model, tolerance, allow_holes)
        })
    })?;
    let mut out = Vec::with_capacity(cad.faces.len());
    for f in &cad.faces {
        let s = &f.surface;
        let flat: Vec<f64> = s.control.iter().flat_map(|p| p.to_array()).collect();
        let net = Array3::from_shape_vec((s.count_u, s.count_v, 3), flat)
            .map_err(|e| arg_err(format!("face of patch {}: {e}", f.patch)))?;
        out.push((
            PyArray1::from_slice(py, &s.knots_u),
            PyArray1::from_slice(py, &s.knots_v),
            PyArray3::from_owned_array(py, net),
        ));
    }
    Ok((out, stats(py, &cad)?))
}
