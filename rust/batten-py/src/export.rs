//! CAD exports of a built hull: the core's B-spline faces as IGES or STEP text, or as control
//! nets for the add-on's Rhino `.3dm` writer. Arguments first, then the core with the GIL
//! released; errors through [`crate::errors`].

use batten_core::{
    cad_surface_with, iges_text, step_text, CadHeader, CadSurface, ExportOptions, Timestamp,
};
use numpy::ndarray::Array3;
use numpy::{PyArray1, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{arg_err, export_err, guard};
use crate::hull_model::HullModel;
use crate::progress::Progress;

/// The faces of `model` within `tolerance`, `progress` told of each face fitted (the GIL
/// released by the caller); None when it stopped the export.
fn faces(
    model: &HullModel,
    tolerance: f64,
    allow_holes: bool,
    progress: &Progress,
) -> PyResult<Option<CadSurface>> {
    let options = ExportOptions {
        tolerance,
        allow_holes,
    };
    let face_done = |done: usize, total: usize| progress.goes_on(done, total);
    cad_surface_with(model.surface(), &options, &face_done).map_err(export_err)
}

/// What a stopped export raises.
const CANCELLED: &str = "exporting the surface cancelled";

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
/// `timestamp` is `(year, month, day, hour, minute, second)` UTC. `progress(faces fitted,
/// faces)`, if given, is called (holding the GIL) as each face is fitted: returning `False`
/// stops the export and raises `Cancelled`, an exception it raises stops it and propagates.
#[pyfunction]
#[pyo3(signature = (model, format, tolerance, allow_holes, name, file_name, author, timestamp,
    *, progress=None))]
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
    progress: Option<Py<PyAny>>,
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
    let progress = Progress::new(progress);
    let written = py.detach(|| {
        guard("exporting the surface", || {
            let cad = faces(model, tolerance, allow_holes, &progress)?;
            Ok(cad.map(|cad| (writer(&cad, &header), cad)))
        })
    })?;
    let Some((text, cad)) = written else {
        return Err(progress.stopped(CANCELLED));
    };
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
/// measured (see `cad_text`); `progress` as there.
#[pyfunction]
#[pyo3(signature = (model, tolerance, allow_holes, *, progress=None))]
pub(crate) fn cad_faces<'py>(
    py: Python<'py>,
    model: &HullModel,
    tolerance: f64,
    allow_holes: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Vec<FaceArrays<'py>>, Bound<'py, PyDict>)> {
    let progress = Progress::new(progress);
    let cad = py.detach(|| {
        guard("exporting the surface", || {
            faces(model, tolerance, allow_holes, &progress)
        })
    })?;
    let Some(cad) = cad else {
        return Err(progress.stopped(CANCELLED));
    };
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
