//! The live rebuild: a hull kept between edits and rebuilt incrementally (the core's
//! `LiveHull`), for Blender's Live mode.

use batten_core::{LiveHull as CoreLiveHull, Rebuild, DEFAULT_TOLERANCE};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::{network_of, Curve};
use crate::errors::{core_err, guard};
use crate::hull::{network_and_options, surface_outputs, MeshArrays};
use crate::hull_model::{HullModel, Seeds};

/// A hull surface kept with everything its build computed: `rebuild(curves)` after the
/// curves moved builds again only the faces they reach (when the network's connectivity is
/// unchanged; else everything), with exactly the mesh of a full build; the report's quality
/// figures are measured again by `settle()`.
#[pyclass(module = "batten_native", name = "LiveHull")]
pub(crate) struct LiveHull {
    inner: CoreLiveHull,
    /// The last model handed out, whose cells (once made) the next one keeps for the faces a
    /// rebuild did not patch again.
    last: Option<Py<HullModel>>,
}

/// The report dict of `hull` with how it was built: `measured` (False while the quality
/// figures — gaps, normal jumps, creases, holes, folds, warnings — are those of the last
/// settled build) and `rebuild` (`kind` "full" or "incremental", `faces` rebuilt, `of` all
/// faces, `reason` a full rebuild was needed, or None).
fn outputs<'py>(
    py: Python<'py>,
    hull: &CoreLiveHull,
    seeds: Seeds,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, Py<HullModel>)> {
    let surface = hull.surface();
    let (arrays, report) = surface_outputs(py, surface)?;
    report.set_item("measured", hull.is_measured())?;
    let rebuild = PyDict::new(py);
    match hull.last_rebuild() {
        Rebuild::Full { reason } => {
            rebuild.set_item("kind", "full")?;
            rebuild.set_item("faces", surface.patches.len())?;
            rebuild.set_item("of", surface.patches.len())?;
            rebuild.set_item("reason", reason.as_deref())?;
        }
        Rebuild::Incremental { faces, of } => {
            rebuild.set_item("kind", "incremental")?;
            rebuild.set_item("faces", *faces)?;
            rebuild.set_item("of", *of)?;
            rebuild.set_item("reason", None::<&str>)?;
        }
    }
    report.set_item("rebuild", rebuild)?;
    let model = Py::new(py, HullModel::seeded(hull.shared_surface(), seeds))?;
    Ok((arrays, report, model))
}

impl LiveHull {
    /// The outputs of the current surface, its model seeded from the last one handed out
    /// (`rebuilt`: the faces patched again since, `None` for everything), and kept as the last.
    fn handed_out<'py>(
        &mut self,
        py: Python<'py>,
        rebuilt: Option<&[usize]>,
    ) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, Py<HullModel>)> {
        let seeds = self
            .last
            .as_ref()
            .map(|m| m.get().successor(rebuilt))
            .unwrap_or_default();
        let out = outputs(py, &self.inner, seeds)?;
        self.last = Some(out.2.clone_ref(py));
        Ok(out)
    }
}

#[pymethods]
impl LiveHull {
    /// Build `curves` in full (as `build_hull_model`, whose errors it raises).
    #[new]
    #[pyo3(signature = (curves, tolerance=DEFAULT_TOLERANCE, resolution=None, name=None, tangent_planes=None))]
    fn new(
        py: Python<'_>,
        curves: Vec<PyRef<'_, Curve>>,
        tolerance: f64,
        resolution: Option<&Bound<'_, PyAny>>,
        name: Option<&Bound<'_, PyAny>>,
        tangent_planes: Option<Vec<[f64; 4]>>,
    ) -> PyResult<LiveHull> {
        let (network, options) =
            network_and_options(&curves, tolerance, resolution, name, tangent_planes)?;
        let inner = py.detach(|| {
            guard("building the hull surface", || {
                CoreLiveHull::new(&network, &options).map_err(core_err)
            })
        })?;
        Ok(LiveHull { inner, last: None })
    }

    /// `(arrays, report, model)` of the current surface, as `build_hull_model` gives them,
    /// the report with `measured` and `rebuild`.
    fn result<'py>(
        &mut self,
        py: Python<'py>,
    ) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, Py<HullModel>)> {
        // The same surface as the last model's: all its cells kept.
        self.handed_out(py, Some(&[]))
    }

    /// Rebuild for `curves` (the same curves, moved; names and order as built; the tangent
    /// planes those it was built with) and return `result()`. On an error nothing changes.
    /// The GIL is released.
    fn rebuild<'py>(
        &mut self,
        py: Python<'py>,
        curves: Vec<PyRef<'py, Curve>>,
    ) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, Py<HullModel>)> {
        let built = self.inner.network();
        let network =
            network_of(&built.name, &curves)?.with_tangent_planes(built.tangent_planes().to_vec());
        let inner = &mut self.inner;
        py.detach(|| {
            guard("rebuilding the hull surface", || {
                inner.rebuild(&network).map(|_| ()).map_err(core_err)
            })
        })?;
        let rebuilt = self.inner.rebuilt_faces().map(<[usize]>::to_vec);
        self.handed_out(py, rebuilt.as_deref())
    }

    /// Measure the report's quality figures on the current surface if a rebuild left them
    /// unmeasured, and return `result()`. The GIL is released.
    fn settle<'py>(
        &mut self,
        py: Python<'py>,
    ) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>, Py<HullModel>)> {
        let inner = &mut self.inner;
        py.detach(|| {
            guard("measuring the hull surface", || {
                inner.settle().map(|_| ()).map_err(core_err)
            })
        })?;
        // Settling measures the report; the patches stay.
        self.handed_out(py, Some(&[]))
    }

    /// True when the report's quality figures were measured on the current surface.
    #[getter]
    fn measured(&self) -> bool {
        self.inner.is_measured()
    }

    /// The model tolerance (m) the hull is built with.
    #[getter]
    fn tolerance(&self) -> f64 {
        self.inner.options().tolerance.get()
    }

    /// Tessellation intervals per side segment.
    #[getter]
    fn resolution(&self) -> usize {
        self.inner.options().resolution
    }
}
