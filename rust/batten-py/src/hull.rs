//! The hull surface: network → topology → patches → one welded mesh, as numpy arrays.

use batten_core::{
    build_hull, HullOptions, HullSurface, Network, Warning, DEFAULT_RESOLUTION, DEFAULT_TOLERANCE,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{optional_whole, text};
use crate::curve::{network_of, tangent_planes_of, Curve};
use crate::errors::{core_err, guard, NoSurfaceError};
use crate::hull_model::HullModel;

/// A warning (or a topology diagnostic) as a dict: `kind`, `message`, `curves` (names),
/// `location` ([x, y, z] or None) and `error` (`{"kind", "message"}` of the underlying face or
/// patch error, or None). The one shape of every finding batten reports to Python.
pub(crate) fn warning_dict<'py>(py: Python<'py>, w: &Warning) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", w.kind.as_str())?;
    d.set_item("message", &w.message)?;
    d.set_item("curves", &w.curves)?;
    d.set_item("location", w.location.map(|p| p.to_array()))?;
    let error = match &w.error {
        Some(e) => {
            let ed = PyDict::new(py);
            ed.set_item("kind", e.kind())?;
            ed.set_item("message", e.to_string())?;
            Some(ed)
        }
        None => None,
    };
    d.set_item("error", error)?;
    Ok(d)
}

/// Mesh arrays: positions (n, 3) float64, corner vertex indices (m,) int32, face sizes (k,)
/// int32, the network face of each mesh face (k,) int32.
pub(crate) type MeshArrays<'py> = (
    Bound<'py, numpy::PyArray2<f64>>,
    Bound<'py, PyArray1<i32>>,
    Bound<'py, PyArray1<i32>>,
    Bound<'py, PyArray1<i32>>,
);

/// `u32` mesh indices as the `int32` Blender's mesh arrays take; a mesh whose indices do not fit
/// is refused (`NoSurfaceError`) rather than wrapped to negative indices.
fn int32_indices(indices: &[u32], what: &str) -> PyResult<Vec<i32>> {
    // The largest index checked first, then every index converted: two plain loops the
    // compiler vectorises (a checked conversion per index took most of a live frame's
    // hand-over on a 660k-corner mesh).
    match indices.iter().copied().max() {
        Some(i) if i32::try_from(i).is_err() => Err(NoSurfaceError::new_err(format!(
            "no surface: {what} index {i} is beyond the int32 indices of a Blender mesh"
        ))),
        #[allow(
            clippy::cast_possible_wrap,
            reason = "every index is at most i32::MAX here: the largest was checked"
        )]
        _ => Ok(indices.iter().map(|&i| i as i32).collect()),
    }
}

/// Build the hull surface of `curves` (H-rep pipeline): returns `(arrays, report)` where arrays
/// are `(positions (n,3), corner_vertices (m,), face_sizes (k,), face_patch (k,))` and report
/// is a dict (node/edge/face counts, faces_by_sides, open_edges, max_gap,
/// max_normal_angle_deg with its place and curve (max_normal_angle_at, max_normal_angle_curve),
/// max_neighbour_angle_deg and max_neighbour_angle_at (mesh faces off the knuckles), holes,
/// folds, crease_angles_deg, knuckle_edges, volume, node_positions, node_kinds,
/// warnings — each a dict, see [`warning_dict`]). Each knuckle edge
/// is a dict: `curve`, `source` (`"role"` or `"auto"`), `corner_curves` (the curves whose
/// corners made an automatic knuckle), `crease_deg` (`(min, max)` or None) and `points` (list
/// of [x, y, z] along the edge). `name` (the collection's) names the network in errors. The
/// GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, tolerance=DEFAULT_TOLERANCE, resolution=None, name=None, tangent_planes=None))]
pub(crate) fn build_surface<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
    resolution: Option<&Bound<'py, PyAny>>,
    name: Option<&Bound<'py, PyAny>>,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
    let (arrays, report, _) = build(py, curves, tolerance, resolution, name, tangent_planes)?;
    Ok((arrays, report))
}

/// As [`build_surface`], with a third result: the [`HullModel`] of the surface's patches, for
/// hydrostatics and sections on the exact surface. The GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, tolerance=DEFAULT_TOLERANCE, resolution=None, name=None, tangent_planes=None))]
pub(crate) fn build_hull_model<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
    resolution: Option<&Bound<'py, PyAny>>,
    name: Option<&Bound<'py, PyAny>>,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, HullModel)> {
    let (arrays, report, hull) = build(py, curves, tolerance, resolution, name, tangent_planes)?;
    Ok((arrays, report, HullModel::new(hull)))
}

/// The build behind both: arrays, report and the surface.
fn build<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
    resolution: Option<&Bound<'py, PyAny>>,
    name: Option<&Bound<'py, PyAny>>,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, HullSurface)> {
    let (network, options) =
        network_and_options(&curves, tolerance, resolution, name, tangent_planes)?;
    let hull = py.detach(|| {
        guard("building the hull surface", || {
            build_hull(&network, &options).map_err(core_err)
        })
    })?;
    let (arrays, d) = surface_outputs(py, &hull)?;
    Ok((arrays, d, hull))
}

/// The parse of `build`'s arguments: the options and the network of `curves`, with the
/// planes its surface is tangent to where curves run in them (`tangent_planes`: each
/// `[nx, ny, nz, offset]` for the plane `n · p = offset`).
pub(crate) fn network_and_options(
    curves: &[PyRef<'_, Curve>],
    tolerance: f64,
    resolution: Option<&Bound<'_, PyAny>>,
    name: Option<&Bound<'_, PyAny>>,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<(Network, HullOptions)> {
    let resolution =
        optional_whole(resolution, || "resolution".to_owned())?.unwrap_or(DEFAULT_RESOLUTION);
    let options = HullOptions::try_new(tolerance, resolution).map_err(core_err)?;
    let name = match name {
        Some(n) => text(n, || "the network name".to_owned())?,
        None => String::new(),
    };
    let planes = tangent_planes_of(tangent_planes)?;
    let network = network_of(&name, curves)?.with_tangent_planes(planes);
    Ok((network, options))
}

/// A built surface's mesh arrays and report dict (see [`build_surface`]).
pub(crate) fn surface_outputs<'py>(
    py: Python<'py>,
    hull: &HullSurface,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
    let mesh = &hull.mesh;
    let positions: Vec<f64> = mesh.positions.as_flattened().to_vec();
    let rows = mesh.positions.len();
    let arrays = (
        PyArray1::from_vec(py, positions).reshape([rows, 3])?,
        PyArray1::from_vec(py, int32_indices(&mesh.face_vertices, "vertex")?),
        PyArray1::from_vec(py, mesh.face_sizes.iter().map(|&s| i32::from(s)).collect()),
        PyArray1::from_vec(py, int32_indices(&mesh.face_patch, "patch")?),
    );
    let r = &hull.report;
    let d = PyDict::new(py);
    d.set_item("nodes", r.nodes)?;
    d.set_item("edges", r.edges)?;
    d.set_item("faces", r.faces)?;
    d.set_item("faces_by_sides", r.faces_by_sides.clone())?;
    d.set_item("skipped_faces", r.skipped_faces)?;
    d.set_item("open_edges", r.open_edges)?;
    d.set_item("max_gap", r.max_gap)?;
    d.set_item("max_normal_angle_deg", r.max_normal_angle_deg)?;
    d.set_item(
        "max_normal_angle_at",
        r.max_normal_angle_at.map(|p| p.to_array()),
    )?;
    d.set_item("max_normal_angle_curve", &r.max_normal_angle_curve)?;
    d.set_item("max_neighbour_angle_deg", r.max_neighbour_angle_deg)?;
    d.set_item(
        "max_neighbour_angle_at",
        r.max_neighbour_angle_at.map(|p| p.to_array()),
    )?;
    d.set_item("holes", r.holes)?;
    d.set_item("folds", r.folds)?;
    let creases: Vec<(String, f64, f64)> = r.crease_angles_deg.clone();
    d.set_item("crease_angles_deg", creases)?;
    let knuckles = r
        .knuckle_edges
        .iter()
        .map(|k| {
            let kd = PyDict::new(py);
            kd.set_item("curve", &k.curve)?;
            kd.set_item("source", k.source.name())?;
            kd.set_item("corner_curves", &k.corner_curves)?;
            kd.set_item("crease_deg", k.crease_deg)?;
            kd.set_item("points", &k.points)?;
            Ok(kd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("knuckle_edges", knuckles)?;
    d.set_item("volume", r.volume)?;
    let nodes: Vec<[f64; 3]> = r.node_positions.iter().map(|p| p.to_array()).collect();
    d.set_item("node_positions", nodes)?;
    let kinds: Vec<&str> = r.node_kinds.iter().map(|k| k.as_str()).collect();
    d.set_item("node_kinds", kinds)?;
    let warnings = r
        .warnings
        .iter()
        .map(|w| warning_dict(py, w))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("warnings", warnings)?;
    d.set_item("mesh_vertices", rows)?;
    d.set_item("mesh_faces", mesh.face_sizes.len())?;
    Ok((arrays, d))
}
