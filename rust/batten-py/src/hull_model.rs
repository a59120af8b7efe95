//! `HullModel`: a built hull's exact patch surface kept for hydrostatics (the core's
//! `PatchHydroModel`, made on first use).

use std::collections::BTreeSet;
use std::sync::{Arc, OnceLock};

use batten_core::{
    float_to, hydrostatics, level_draft, sectional_areas, CellDensity, HullGeometry, HullSurface,
    PatchHydroModel, SectionModel, DEFAULT_CUT_TOLERANCE, SEA_WATER_DENSITY,
};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{core_err, guard};
use crate::hydro::{datums, figures_at, flotation, hydrostatics_dict};
use crate::sections::PySection;

/// A hull's exact surface for hydrostatics, from [`build_hull_model`](crate::hull::build_hull_model).
/// Its cells are made on the first call that needs them (tens of milliseconds for a ship) and
/// kept; the model a `LiveHull` hands out after an incremental rebuild makes only the cells of
/// the faces patched again and keeps the others from the model before (`cells_kept`). Every method releases the GIL and raises `HydrostaticsError` or `InvalidArgumentError`.
#[pyclass(frozen, module = "batten_native")]
pub(crate) struct HullModel {
    surface: Arc<HullSurface>,
    model: Arc<OnceLock<PatchHydroModel>>,
    live: Arc<OnceLock<PatchHydroModel>>,
    sections: OnceLock<SectionModel>,
    /// Where the exact and the Live cells may come from: for a live hull's surface, an earlier
    /// model of the same hull.
    seeds: Seeds,
}

/// An earlier model of the same live hull (its cells, once made) and the topology faces
/// patched again since its surface: the cells of the others are kept.
#[derive(Clone, Debug)]
pub(crate) struct Seed {
    cells: Arc<OnceLock<PatchHydroModel>>,
    changed: Arc<BTreeSet<usize>>,
}

/// The seeds of the exact and the Live cells.
#[derive(Clone, Debug, Default)]
pub(crate) struct Seeds {
    exact: Option<Seed>,
    live: Option<Seed>,
}

impl HullModel {
    /// Keep `surface`.
    pub(crate) fn new(surface: HullSurface) -> HullModel {
        HullModel::seeded(Arc::new(surface), Seeds::default())
    }

    /// Keep `surface`, a live rebuild of an earlier model's (see [`HullModel::successor`]).
    pub(crate) fn seeded(surface: Arc<HullSurface>, seeds: Seeds) -> HullModel {
        HullModel {
            surface,
            model: Arc::new(OnceLock::new()),
            live: Arc::new(OnceLock::new()),
            sections: OnceLock::new(),
            seeds,
        }
    }

    /// The seeds of the model of a surface rebuilt from this one's with only the faces
    /// `rebuilt` patched again (`None`: everything rebuilt, nothing to keep): this model's
    /// cells where they are made, else the ones this model would have kept.
    pub(crate) fn successor(&self, rebuilt: Option<&[usize]>) -> Seeds {
        let Some(rebuilt) = rebuilt else {
            return Seeds::default();
        };
        let next = |lock: &Arc<OnceLock<PatchHydroModel>>, seed: &Option<Seed>| {
            if lock.get().is_some() {
                Some(Seed {
                    cells: lock.clone(),
                    changed: Arc::new(rebuilt.iter().copied().collect()),
                })
            } else {
                seed.as_ref().map(|s| Seed {
                    cells: s.cells.clone(),
                    changed: Arc::new(s.changed.iter().chain(rebuilt).copied().collect()),
                })
            }
        };
        Seeds {
            exact: next(&self.model, &self.seeds.exact),
            live: next(&self.live, &self.seeds.live),
        }
    }

    /// The surface itself (for the CAD exports).
    pub(crate) fn surface(&self) -> &HullSurface {
        &self.surface
    }

    fn geometry(&self, live: bool) -> &PatchHydroModel {
        let (lock, seed, density) = if live {
            (&self.live, &self.seeds.live, CellDensity::LIVE)
        } else {
            (&self.model, &self.seeds.exact, CellDensity::DEFAULT)
        };
        lock.get_or_init(|| {
            let earlier = seed
                .as_ref()
                .and_then(|s| Some((s.cells.get()?, &s.changed)));
            match earlier {
                Some((prev, changed)) if prev.density() == density => self
                    .surface
                    .hydro_model_after(prev, &|f| changed.contains(&f)),
                _ => self.surface.hydro_model(density),
            }
        })
    }

    fn section_model(&self) -> &SectionModel {
        self.sections
            .get_or_init(|| SectionModel::new(&self.surface))
    }
}

#[pymethods]
impl HullModel {
    /// Number of cells of the exact model (made now if not yet).
    #[getter]
    fn cells(&self, py: Python<'_>) -> usize {
        py.detach(|| self.geometry(false).cell_count())
    }

    /// How many of the exact model's cells were kept from the model of the surface before a
    /// live rebuild (the cells of the faces it did not patch again; 0 when all were made).
    #[getter]
    fn cells_kept(&self, py: Python<'_>) -> usize {
        py.detach(|| self.geometry(false).kept_cell_count())
    }

    /// Whether the surface is a half hull (port side) answered for both sides.
    #[getter]
    fn is_half(&self, py: Python<'_>) -> bool {
        py.detach(|| self.geometry(false).is_half())
    }

    /// `(x_ap, x_fp)`: the perpendiculars at `draft` (see `hydrostatics`).
    #[pyo3(signature = (draft, lpp=None, fp=None))]
    fn datums(
        &self,
        py: Python<'_>,
        draft: f64,
        lpp: Option<f64>,
        fp: Option<f64>,
    ) -> PyResult<(f64, f64)> {
        py.detach(|| {
            guard("finding the perpendiculars", || {
                let d = datums(self.geometry(false), draft, lpp, fp)?;
                Ok((d.x_ap, d.x_fp))
            })
        })
    }

    /// The hydrostatics at `draft` (m, at midships), `trim` (m, `T_AP − T_FP`), `heel` (degrees,
    /// to starboard), `density` (t/m³): a dict of floats (volume, displacement, drafts, Lwl,
    /// Bwl, LOS, wetted_area, waterplane_area, midship and largest section, Cb, Cp, Cm, Cwp, Cvp,
    /// LCB, TCB, VCB, LCF, It, Il, BMt, BMl, KMt, KMl, TPC, MTC, transom_area,
    /// entrance_half_angle …). Perpendiculars: `fp` and `lpp` as given, else FP at the fore end
    /// of the level waterline at `draft`, AP `lpp` aft of it (or at its aft end). `live` uses
    /// the coarser cells (about 1e-8 relative) for figures updated while dragging.
    #[pyo3(signature = (draft, trim=0.0, heel=0.0, density=SEA_WATER_DENSITY, lpp=None, fp=None, live=false))]
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
        live: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let f = flotation(draft, trim, heel, density);
        figures_at(
            py,
            "computing hydrostatics",
            || self.geometry(live),
            f,
            lpp,
            fp,
        )
    }

    /// Immersed section areas (m², both sides) at the stations `xs` (m) at `draft`, `trim`,
    /// `heel`; perpendiculars as in `hydrostatics`.
    #[pyo3(signature = (draft, xs, trim=0.0, heel=0.0, lpp=None, fp=None))]
    #[allow(clippy::too_many_arguments)]
    fn sectional_areas<'py>(
        &self,
        py: Python<'py>,
        draft: f64,
        xs: Vec<f64>,
        trim: f64,
        heel: f64,
        lpp: Option<f64>,
        fp: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let areas = py.detach(|| {
            guard("computing sectional areas", || {
                let geom = self.geometry(false);
                let d = datums(geom, draft, lpp, fp)?;
                let f = flotation(draft, trim, heel, SEA_WATER_DENSITY);
                sectional_areas(geom, &f, &d, &xs).map_err(core_err)
            })
        })?;
        Ok(PyArray1::from_vec(py, areas))
    }

    /// The level, upright draft (m) at which the hull displaces `displacement` t.
    #[pyo3(signature = (displacement, density=SEA_WATER_DENSITY))]
    fn level_draft(&self, py: Python<'_>, displacement: f64, density: f64) -> PyResult<f64> {
        py.detach(|| {
            guard("finding the draft", || {
                level_draft(self.geometry(false), displacement, density).map_err(core_err)
            })
        })
    }

    /// The upright flotation with displacement `displacement` (t) and the centre of buoyancy
    /// under `lcg` (m; with `vcg` the true vertical through G, else LCB = LCG): the hydrostatics
    /// dict there (its draft_mid and trim are the answer). Perpendiculars as in `hydrostatics`,
    /// found at the level draft `design_draft` when `fp` is not given.
    #[pyo3(signature = (displacement, lcg, design_draft, vcg=None, density=SEA_WATER_DENSITY, lpp=None, fp=None))]
    #[allow(clippy::too_many_arguments)]
    fn float_to<'py>(
        &self,
        py: Python<'py>,
        displacement: f64,
        lcg: f64,
        design_draft: f64,
        vcg: Option<f64>,
        density: f64,
        lpp: Option<f64>,
        fp: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let h = py.detach(|| {
            guard("floating the hull", || {
                let geom = self.geometry(false);
                let d = datums(geom, design_draft, lpp, fp)?;
                let f = float_to(geom, &d, displacement, lcg, vcg, density).map_err(core_err)?;
                hydrostatics(geom, &f, &d).map_err(core_err)
            })
        })?;
        hydrostatics_dict(py, &h)
    }

    /// The sections of the drawn surface by the planes `normals[k]·p = offsets[k]` (m): per
    /// plane a list of `(points (n, 3), closed, corners, curve)`, the polylines in order along
    /// the section within `tolerance` (m, chordal) of the surface, every point on the patches
    /// and the plane, `corners` the indices where it crosses a knuckle, `curve` its fitted
    /// NURBS named `names[k]` (further pieces of a plane ` (2)`, ` (3)` …). A plane missing
    /// the hull gives an empty list. The GIL is released.
    #[pyo3(signature = (normals, offsets, names, tolerance=DEFAULT_CUT_TOLERANCE))]
    fn sections<'py>(
        &'py self,
        py: Python<'py>,
        normals: Vec<[f64; 3]>,
        offsets: Vec<f64>,
        names: Vec<String>,
        tolerance: f64,
    ) -> PyResult<Vec<Vec<PySection<'py>>>> {
        crate::sections::sections(
            py,
            || self.section_model(),
            normals,
            offsets,
            names,
            tolerance,
        )
    }

    /// The hull's knuckle (chine) lines: `(curve name, points (n, 3))`.
    fn knuckle_lines<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Vec<(String, Bound<'py, PyArray2<f64>>)>> {
        let model = py.detach(|| self.section_model());
        crate::sections::knuckle_lines(py, model)
    }

    /// Gaussian (1/m²) and mean (1/m, positive where the hull bulges outwards) curvature at
    /// every vertex of the surface's mesh, which was built at `resolution`, from the patches
    /// themselves: `(gaussian (n,), mean (n,), defined (n,) bool)`; undefined vertices (no
    /// regular patch there) hold 0. Raises `InvalidArgumentError` when the mesh was built at
    /// another resolution. The GIL is released.
    #[allow(clippy::type_complexity)]
    fn vertex_curvature<'py>(
        &self,
        py: Python<'py>,
        resolution: usize,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
    )> {
        let c = py.detach(|| {
            guard("working out the curvature", || {
                self.surface.vertex_curvature(resolution).map_err(core_err)
            })
        })?;
        Ok((
            PyArray1::from_vec(py, c.gaussian),
            PyArray1::from_vec(py, c.mean),
            PyArray1::from_vec(py, c.defined),
        ))
    }

    /// `((x, y, z) lowest, (x, y, z) highest)`: the box of the drawn surface.
    #[getter]
    fn bounds(&self, py: Python<'_>) -> ([f64; 3], [f64; 3]) {
        let (lo, hi) = py.detach(|| self.section_model().bounds());
        (lo.to_array(), hi.to_array())
    }
}
