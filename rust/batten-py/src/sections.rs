//! Plane sections of a built hull's exact surface (the core's `SectionModel`): polylines as
//! numpy arrays and their fitted NURBS as `Curve`s, and the hull's knuckle lines.

use batten_core::{SectionModel, SectionPlane, SectionPolyline};
use glam::DVec3;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::curve::{points_array, Curve};
use crate::errors::{arg_err, core_err, guard};

/// One polyline of a section as Python gets it: points (n, 3), closed, corner indices, and the
/// fitted curve.
pub(crate) type PySection<'py> = (Bound<'py, PyArray2<f64>>, bool, Vec<usize>, Curve);

/// The sections of `model` by the planes `normals[k]·p = offsets[k]`, each polyline within
/// `tolerance` (m) and fitted within it, its curve named `names[k]` (with ` (2)`, ` (3)` … for
/// a plane's further pieces). Arguments checked first, the core runs with the GIL released.
pub(crate) fn sections<'py>(
    py: Python<'py>,
    model: impl FnOnce() -> &'py SectionModel + Send,
    normals: Vec<[f64; 3]>,
    offsets: Vec<f64>,
    names: Vec<String>,
    tolerance: f64,
) -> PyResult<Vec<Vec<PySection<'py>>>> {
    if normals.len() != offsets.len() || names.len() != offsets.len() {
        return Err(arg_err(format!(
            "sections: {} normals, {} offsets and {} names must be as many",
            normals.len(),
            offsets.len(),
            names.len()
        )));
    }
    let planes = normals
        .iter()
        .zip(&offsets)
        .zip(&names)
        .map(|((n, c), name)| {
            SectionPlane::try_new(DVec3::from_array(*n), *c)
                .map_err(|e| arg_err(format!("section '{name}': {e}")))
        })
        .collect::<PyResult<Vec<_>>>()?;
    type Cut = Vec<(SectionPolyline, batten_core::NurbsCurve)>;
    let cuts: Vec<Cut> = py.detach(|| {
        guard("cutting sections", || {
            let model = model();
            planes
                .iter()
                .map(|plane| {
                    let lines = model.section(plane, tolerance).map_err(core_err)?;
                    lines
                        .into_iter()
                        .map(|l| {
                            let curve = l.fit(tolerance).map_err(core_err)?;
                            Ok((l, curve))
                        })
                        .collect::<PyResult<Cut>>()
                })
                .collect()
        })
    })?;
    cuts.into_iter()
        .zip(&names)
        .map(|(cut, name)| {
            cut.into_iter()
                .enumerate()
                .map(|(k, (line, curve))| {
                    let label = if k == 0 {
                        name.clone()
                    } else {
                        format!("{name} ({})", k + 1)
                    };
                    Ok((
                        points_array(py, &line.points)?,
                        line.closed,
                        line.corners,
                        Curve::from_parts(&label, "free", curve)?,
                    ))
                })
                .collect()
        })
        .collect()
}

/// The hull's knuckle lines as `(curve name, points (n, 3))`.
pub(crate) fn knuckle_lines<'py>(
    py: Python<'py>,
    model: &SectionModel,
) -> PyResult<Vec<(String, Bound<'py, PyArray2<f64>>)>> {
    model
        .knuckle_lines()
        .iter()
        .map(|k| Ok((k.curve.clone(), points_array(py, &k.points)?)))
        .collect()
}
