//! Hydrostatics: the figures of any triangle mesh (`mesh_hydrostatics`,
//! `mesh_sectional_areas`), and the pieces every hydrostatics call shares — the flotation, the
//! perpendiculars and the figures as a dict.

use batten_core::{
    default_datums, hydrostatics, sectional_areas, Datums, Flotation, HullGeometry, Hydrostatics,
    TriangleHull, SEA_WATER_DENSITY,
};
use glam::DVec3;
use numpy::{
    AllowTypeChange, PyArray1, PyArrayDescrMethods, PyArrayLike2, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{rows, whole};
use crate::errors::{arg_err, core_err, guard, InternalError};

/// A record of figures (any `Serialize` struct of numbers, such as [`Hydrostatics`]) as a dict
/// keyed by its serde field names in field order. The numbers go through serde_json's
/// shortest round-trip decimals, so every float arrives exactly.
pub(crate) fn figures_dict<'py>(
    py: Python<'py>,
    figures: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyDict>> {
    let text = serde_json::to_string(figures)
        .map_err(|e| InternalError::new_err(format!("the figures as JSON: {e}")))?;
    py.import("json")?
        .call_method1("loads", (text,))?
        .cast_into::<PyDict>()
        .map_err(|e| InternalError::new_err(format!("the figures as a dict: {e}")))
}

/// The hydrostatics as a dict with exactly the fields of [`Hydrostatics`].
pub(crate) fn hydrostatics_dict<'py>(
    py: Python<'py>,
    h: &Hydrostatics,
) -> PyResult<Bound<'py, PyDict>> {
    figures_dict(py, h)
}

/// The flotation asked for (checked by the core when it is used).
pub(crate) fn flotation(draft: f64, trim: f64, heel: f64, density: f64) -> Flotation {
    Flotation {
        draft,
        trim,
        heel_deg: heel,
        density,
    }
}

/// The perpendiculars: FP at `fp` with AP `lpp` aft of it when `fp` is given (then `lpp` must
/// be too); else those the hull implies at `draft` ([`default_datums`]: FP at the waterline's
/// fore end, AP `lpp` aft of it or at the waterline's aft end).
pub(crate) fn datums(
    geom: &dyn HullGeometry,
    draft: f64,
    lpp: Option<f64>,
    fp: Option<f64>,
) -> PyResult<Datums> {
    match (fp, lpp) {
        (Some(fp), Some(lpp)) => {
            let d = Datums {
                x_ap: fp - lpp,
                x_fp: fp,
            };
            d.check().map_err(core_err)?;
            Ok(d)
        }
        (Some(fp), None) => Err(arg_err(format!(
            "fp = {fp} was given without lpp: give the length between perpendiculars too"
        ))),
        (None, lpp) => default_datums(geom, draft, lpp).map_err(core_err),
    }
}

/// The hydrostatics dict of the hull `geom()` gives (called with the GIL released, so making
/// its cells does not hold Python up) at flotation `f`, about the perpendiculars of [`datums`];
/// `what` names the work in an internal error.
pub(crate) fn figures_at<'py, 'g, G: HullGeometry + 'g>(
    py: Python<'py>,
    what: &str,
    geom: impl FnOnce() -> &'g G + Send,
    f: Flotation,
    lpp: Option<f64>,
    fp: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let h = py.detach(|| {
        guard(what, || {
            let geom = geom();
            let d = datums(geom, f.draft, lpp, fp)?;
            hydrostatics(geom, &f, &d).map_err(core_err)
        })
    })?;
    hydrostatics_dict(py, &h)
}

/// `positions` as points: an `(n, 3)` array of numbers.
fn mesh_positions(obj: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    let arr = rows(obj, || "positions".to_owned())?;
    let a = arr.as_array();
    if a.ncols() != 3 {
        return Err(arg_err(format!(
            "positions must have 3 columns (x, y, z), not {} (shape {:?})",
            a.ncols(),
            a.shape()
        )));
    }
    Ok(match a.as_slice() {
        Some(flat) => flat
            .chunks_exact(3)
            .map(|r| DVec3::new(r[0], r[1], r[2]))
            .collect(),
        None => a
            .rows()
            .into_iter()
            .map(|r| DVec3::new(r[0], r[1], r[2]))
            .collect(),
    })
}

/// `triangles` as vertex indices: an `(m, 3)` array of whole numbers from 0 to 2³² − 1 (an
/// array of another kind than integers is refused, never truncated).
fn mesh_triangles(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[u32; 3]>> {
    if let Ok(untyped) = obj.cast::<PyUntypedArray>() {
        let kind = untyped.dtype().kind();
        if kind != b'i' && kind != b'u' {
            return Err(arg_err(format!(
                "triangles must be an array of integers (vertex indices), not of {}",
                untyped.dtype()
            )));
        }
    }
    let arr: PyArrayLike2<'_, i64, AllowTypeChange> = obj.extract().map_err(|e: PyErr| {
        arg_err(format!(
            "triangles must be a 2-D array of vertex indices (one row per triangle): {}",
            e.value(obj.py())
        ))
    })?;
    let a = arr.as_array();
    if a.ncols() != 3 {
        return Err(arg_err(format!(
            "triangles must have 3 columns (vertex indices), not {} (shape {:?})",
            a.ncols(),
            a.shape()
        )));
    }
    let triangle = |k: usize, r: [i64; 3]| {
        let index = |v: i64| {
            u32::try_from(v).map_err(|_| {
                arg_err(format!(
                    "triangle {k} has vertex index {v}: indices run from 0 to 2**32 - 1"
                ))
            })
        };
        Ok([index(r[0])?, index(r[1])?, index(r[2])?])
    };
    match a.as_slice() {
        Some(flat) => flat
            .chunks_exact(3)
            .enumerate()
            .map(|(k, r)| triangle(k, [r[0], r[1], r[2]]))
            .collect(),
        None => a
            .rows()
            .into_iter()
            .enumerate()
            .map(|(k, r)| triangle(k, [r[0], r[1], r[2]]))
            .collect(),
    }
}

/// A triangle mesh built once as a hull (validated, its free edges and half-hull form found),
/// for the hydrostatics at many flotations: `MeshHull(positions, triangles)` with
/// `positions` (n, 3) m and `triangles` (m, 3) vertex indices. A half hull (port side, open
/// along `y = 0`) is mirrored; an inward-wound mesh is reversed.
#[pyclass(frozen, module = "batten_native")]
pub(crate) struct MeshHull {
    inner: TriangleHull,
}

#[pymethods]
impl MeshHull {
    #[new]
    fn py_new(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        triangles: &Bound<'_, PyAny>,
    ) -> PyResult<MeshHull> {
        let points = mesh_positions(positions)?;
        let tris = mesh_triangles(triangles)?;
        let inner = py.detach(|| {
            guard("building a mesh hull", || {
                TriangleHull::try_new(&points, &tris).map_err(core_err)
            })
        })?;
        Ok(MeshHull { inner })
    }

    /// Whether the mesh is a half hull (answered for both sides).
    #[getter]
    fn is_half(&self) -> bool {
        self.inner.is_half()
    }

    /// The number of triangles given.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.inner.triangle_count()
    }

    /// The hydrostatics at `draft` (m at midships), `trim` (m, by the stern positive), `heel`
    /// (degrees, to starboard positive) and `density` (t/m³); the perpendiculars: FP at `fp`
    /// and AP `lpp` aft of it when `fp` is given (`lpp` required then), else FP at the
    /// waterline's fore end and AP `lpp` aft of it (or at the waterline's aft end). Returns a
    /// dict of every figure of the core's `Hydrostatics`. The GIL is released.
    #[pyo3(signature = (draft, *, trim=0.0, heel=0.0, density=SEA_WATER_DENSITY, lpp=None, fp=None))]
    #[allow(clippy::too_many_arguments)]
    fn hydrostatics<'py>(
        &self,
        py: Python<'py>,
        draft: f64,
        trim: f64,
        heel: f64,
        density: f64,
        lpp: Option<f64>,
        fp: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let f = flotation(draft, trim, heel, density);
        figures_at(py, "the hydrostatics of a mesh", || &self.inner, f, lpp, fp)
    }

    /// Sectional areas at `stations` equally spaced stations from AP to FP inclusive (the
    /// flotation and perpendiculars as for [`hydrostatics`](Self::hydrostatics)): returns
    /// `(xs, areas)`, float64 arrays (m, m²). The GIL is released.
    #[pyo3(signature = (draft, stations, *, trim=0.0, heel=0.0, lpp=None, fp=None))]
    #[allow(clippy::too_many_arguments)]
    fn sectional_areas<'py>(
        &self,
        py: Python<'py>,
        draft: f64,
        stations: &Bound<'py, PyAny>,
        trim: f64,
        heel: f64,
        lpp: Option<f64>,
        fp: Option<f64>,
    ) -> PyResult<SectionalAreas<'py>> {
        let n = whole(stations, || "stations".to_owned())?;
        if n < 2 {
            return Err(arg_err(format!(
                "stations = {n}: at least 2 (AP and FP) are needed"
            )));
        }
        let f = flotation(draft, trim, heel, SEA_WATER_DENSITY);
        let geom = &self.inner;
        let (xs, areas) = py.detach(|| {
            guard("the sectional areas of a mesh", || {
                let d = datums(geom, draft, lpp, fp)?;
                let step = d.lpp() / (n - 1) as f64;
                let xs: Vec<f64> = (0..n).map(|k| d.x_ap + step * k as f64).collect();
                let areas = sectional_areas(geom, &f, &d, &xs).map_err(core_err)?;
                Ok((xs, areas))
            })
        })?;
        Ok((PyArray1::from_vec(py, xs), PyArray1::from_vec(py, areas)))
    }
}

/// The hydrostatics of the triangle mesh `positions` (n, 3) m, `triangles` (m, 3) vertex
/// indices, in one call: [`MeshHull`] built and asked once (see
/// [`MeshHull::hydrostatics`] for the arguments and the result).
#[pyfunction]
#[pyo3(signature = (positions, triangles, draft, *, trim=0.0, heel=0.0, density=SEA_WATER_DENSITY, lpp=None, fp=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn mesh_hydrostatics<'py>(
    py: Python<'py>,
    positions: &Bound<'py, PyAny>,
    triangles: &Bound<'py, PyAny>,
    draft: f64,
    trim: f64,
    heel: f64,
    density: f64,
    lpp: Option<f64>,
    fp: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    MeshHull::py_new(py, positions, triangles)?
        .hydrostatics(py, draft, trim, heel, density, lpp, fp)
}

/// Station positions (m) and their immersed areas (m²), float64.
type SectionalAreas<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// Sectional areas of the triangle mesh in one call: [`MeshHull`] built and asked once (see
/// [`MeshHull::sectional_areas`]).
#[pyfunction]
#[pyo3(signature = (positions, triangles, draft, stations, *, trim=0.0, heel=0.0, lpp=None, fp=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn mesh_sectional_areas<'py>(
    py: Python<'py>,
    positions: &Bound<'py, PyAny>,
    triangles: &Bound<'py, PyAny>,
    draft: f64,
    stations: &Bound<'py, PyAny>,
    trim: f64,
    heel: f64,
    lpp: Option<f64>,
    fp: Option<f64>,
) -> PyResult<SectionalAreas<'py>> {
    MeshHull::py_new(py, positions, triangles)?
        .sectional_areas(py, draft, stations, trim, heel, lpp, fp)
}
