//! `batten_native.Curve`: a named designer curve (NURBS) with its role.

use batten_core::{CurveError, KnotLayout, Network, NetworkCurve, NurbsCurve, Role, TangentPlane};
use glam::DVec3;
use numpy::{
    AllowTypeChange, PyArray1, PyArray2, PyArrayLike1, PyArrayLike2, PyArrayMethods,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::args::{optional_text, optional_whole, role_or_free, rows, text, values, whole};
use crate::errors::{arg_err, core_err, curve_err, guard};

/// The parameters `ts` for evaluating curve `name`: every one finite (a NaN or infinite
/// parameter is a `CurveError` naming the curve; finite ones outside the domain are clamped by
/// the core).
fn finite_parameters<'a>(name: &str, ts: &'a [f64]) -> PyResult<&'a [f64]> {
    match ts.iter().find(|t| !t.is_finite()) {
        Some(&bad) => Err(curve_err(name, CurveError::NonFiniteParameter(bad))),
        None => Ok(ts),
    }
}

/// The parameters of `t` for evaluating curve `name`: contiguous and every one finite.
fn parameters<'a>(
    name: &str,
    t: &'a PyArrayLike1<'_, f64, AllowTypeChange>,
) -> PyResult<&'a [f64]> {
    let ts = t
        .as_slice()
        .map_err(|_| arg_err(format!("curve '{name}': t must be a contiguous 1-D array")))?;
    finite_parameters(name, ts)
}

/// Below this many parameters evaluation stays on one thread (spawning costs more than it saves).
const PARALLEL_MIN: usize = 1 << 15;

/// A designer curve: name, role and NURBS geometry (immutable; edits return new curves).
#[pyclass(module = "batten_native", frozen)]
pub struct Curve {
    pub(crate) inner: NetworkCurve,
}

fn parse_role(name: &str, role: &str) -> PyResult<Role> {
    Role::from_name(role).ok_or_else(|| {
        let all: Vec<_> = Role::ALL.iter().map(|r| r.name()).collect();
        arg_err(format!(
            "curve '{name}': unknown role '{role}' (one of {})",
            all.join(", ")
        ))
    })
}

/// Rows of an (n, k) float array as points (first three columns), naming the curve on error.
fn points_of(
    name: &str,
    what: &str,
    a: &PyArrayLike2<'_, f64, AllowTypeChange>,
    cols: &[usize],
) -> PyResult<Vec<DVec3>> {
    let shape = a.shape();
    if !cols.contains(&shape[1]) {
        return Err(arg_err(format!(
            "curve '{name}': {what} must have shape (n, {}), got ({}, {})",
            cols.iter()
                .map(|c| c.to_string())
                .collect::<Vec<_>>()
                .join(" or "),
            shape[0],
            shape[1]
        )));
    }
    let view = a.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// Two (n, 3) float arrays.
type ArrayPair<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>);

fn to_array2<'py>(
    py: Python<'py>,
    flat: Vec<f64>,
    cols: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = flat.len() / cols;
    PyArray1::from_vec(py, flat).reshape([rows, cols])
}

/// The points as an (n, 3) float array.
pub(crate) fn points_array<'py>(
    py: Python<'py>,
    pts: &[DVec3],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    to_array2(py, pts.iter().flat_map(|p| p.to_array()).collect(), 3)
}

/// The network named `name` of `curves` (names must be non-empty and unique: a
/// `NetworkFileError` otherwise).
pub(crate) fn network_of(name: &str, curves: &[PyRef<'_, Curve>]) -> PyResult<Network> {
    Network::try_new(name, curves.iter().map(|c| c.inner.clone()).collect()).map_err(core_err)
}

/// Tangent planes given as `[nx, ny, nz, offset]` (the plane `n · p = offset`); a zero or
/// non-finite one is a `BattenError` saying so.
pub(crate) fn tangent_planes_of(planes: Option<Vec<[f64; 4]>>) -> PyResult<Vec<TangentPlane>> {
    planes
        .unwrap_or_default()
        .into_iter()
        .map(|[x, y, z, offset]| TangentPlane::try_new(DVec3::new(x, y, z), offset))
        .collect::<Result<Vec<_>, _>>()
        .map_err(core_err)
}

/// The tangent planes of `network` as `[nx, ny, nz, offset]`.
pub(crate) fn planes_of(network: &Network) -> Vec<[f64; 4]> {
    network
        .tangent_planes()
        .iter()
        .map(TangentPlane::to_array)
        .collect()
}

/// The curves of `network`, in order, as Python `Curve`s.
pub(crate) fn curves_of(network: &Network) -> Vec<Curve> {
    network
        .curves()
        .iter()
        .cloned()
        .map(|inner| Curve { inner })
        .collect()
}

impl Curve {
    fn wrap(&self, curve: NurbsCurve) -> Curve {
        Curve {
            inner: NetworkCurve {
                name: self.inner.name.clone(),
                role: self.inner.role,
                curve,
            },
        }
    }

    fn make(
        name: &str,
        role: &str,
        curve: Result<NurbsCurve, batten_core::CurveError>,
    ) -> PyResult<Curve> {
        let role = parse_role(name, role)?;
        let curve = curve.map_err(|e| curve_err(name, e))?;
        Ok(Curve {
            inner: NetworkCurve {
                name: name.to_owned(),
                role,
                curve,
            },
        })
    }

    fn name(&self) -> &str {
        &self.inner.name
    }

    /// A curve from core geometry with a name and role (role validated).
    pub(crate) fn from_parts(name: &str, role: &str, curve: NurbsCurve) -> PyResult<Curve> {
        Curve::make(name, role, Ok(curve))
    }
}

#[pymethods]
impl Curve {
    /// A NURBS curve from its degree, knot vector (n + degree + 1 values), control points (n, 3)
    /// and optional positive weights (n,).
    #[new]
    #[pyo3(signature = (name, degree, knots, points, weights=None, role=None),
        text_signature = "(name, degree, knots, points, weights=None, role=\"free\")")]
    fn py_new(
        name: &Bound<'_, PyAny>,
        degree: &Bound<'_, PyAny>,
        knots: &Bound<'_, PyAny>,
        points: &Bound<'_, PyAny>,
        weights: Option<&Bound<'_, PyAny>>,
        role: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Curve> {
        let name = &text(name, || "the curve name".to_owned())?;
        let role = &role_or_free(name, role)?;
        let degree = whole(degree, || format!("curve '{name}': degree"))?;
        let knots = values(knots, || format!("curve '{name}': knots"))?;
        let points = rows(points, || format!("curve '{name}': points"))?;
        let weights = weights
            .filter(|w| !w.is_none())
            .map(|w| values(w, || format!("curve '{name}': weights")))
            .transpose()?;
        let pts = points_of(name, "points", &points, &[3])?;
        let knots = knots.as_array().to_vec();
        let weights = weights.map(|w| w.as_array().to_vec());
        guard(name, || {
            Curve::make(name, role, NurbsCurve::try_new(degree, knots, pts, weights))
        })
    }

    /// A NURBS spline as Blender stores it: points (n, 4) with the weight in the last column
    /// (or (n, 3) for weight 1), its order and the end-point / Bézier / cyclic flags.
    #[staticmethod]
    #[pyo3(signature = (name, points, order, endpoint=false, bezier=false, cyclic=false, role=None),
        text_signature = "(name, points, order, endpoint=False, bezier=False, cyclic=False, role=\"free\")")]
    fn from_nurbs(
        name: &Bound<'_, PyAny>,
        points: &Bound<'_, PyAny>,
        order: &Bound<'_, PyAny>,
        endpoint: bool,
        bezier: bool,
        cyclic: bool,
        role: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Curve> {
        let name = &text(name, || "the curve name".to_owned())?;
        let role = &role_or_free(name, role)?;
        let points = rows(points, || format!("curve '{name}': points"))?;
        let order = whole(order, || format!("curve '{name}': order"))?;
        let pts = points_of(name, "points", &points, &[3, 4])?;
        let view = points.as_array();
        let weights: Option<Vec<f64>> = (view.ncols() == 4).then(|| view.column(3).to_vec());
        let layout = match (endpoint, bezier) {
            (false, false) => KnotLayout::Uniform,
            (true, false) => KnotLayout::Endpoint,
            (false, true) => KnotLayout::Bezier,
            (true, true) => KnotLayout::EndpointBezier,
        };
        guard(name, || {
            Curve::make(
                name,
                role,
                NurbsCurve::from_layout(&pts, weights.as_deref(), order, layout, cyclic),
            )
        })
    }

    /// A Bézier spline from its points and left/right handles (each (n, 3)); segment i runs on
    /// parameters [i, i+1]. Non-aligned handles stay corners.
    #[staticmethod]
    #[pyo3(signature = (name, co, left, right, cyclic=false, role=None),
        text_signature = "(name, co, left, right, cyclic=False, role=\"free\")")]
    fn from_bezier(
        name: &Bound<'_, PyAny>,
        co: &Bound<'_, PyAny>,
        left: &Bound<'_, PyAny>,
        right: &Bound<'_, PyAny>,
        cyclic: bool,
        role: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Curve> {
        let name = &text(name, || "the curve name".to_owned())?;
        let role = &role_or_free(name, role)?;
        let co = rows(co, || format!("curve '{name}': co"))?;
        let left = rows(left, || format!("curve '{name}': left handles"))?;
        let right = rows(right, || format!("curve '{name}': right handles"))?;
        let co = points_of(name, "co", &co, &[3])?;
        let left = points_of(name, "left handles", &left, &[3])?;
        let right = points_of(name, "right handles", &right, &[3])?;
        if left.len() != co.len() || right.len() != co.len() {
            return Err(arg_err(format!(
                "curve '{name}': {} points but {} left and {} right handles",
                co.len(),
                left.len(),
                right.len()
            )));
        }
        guard(name, || {
            Curve::make(
                name,
                role,
                NurbsCurve::from_bezier(&co, &left, &right, cyclic),
            )
        })
    }

    /// A polyline (points (n, 3), or (n, 4) whose last column is ignored) as a degree-1 curve.
    #[staticmethod]
    #[pyo3(signature = (name, points, cyclic=false, role=None),
        text_signature = "(name, points, cyclic=False, role=\"free\")")]
    fn from_poly(
        name: &Bound<'_, PyAny>,
        points: &Bound<'_, PyAny>,
        cyclic: bool,
        role: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Curve> {
        let name = &text(name, || "the curve name".to_owned())?;
        let role = &role_or_free(name, role)?;
        let points = rows(points, || format!("curve '{name}': points"))?;
        let pts = points_of(name, "points", &points, &[3, 4])?;
        guard(name, || {
            Curve::make(name, role, NurbsCurve::from_polyline(&pts, cyclic))
        })
    }

    /// The curve's name.
    #[getter(name)]
    fn get_name(&self) -> String {
        self.inner.name.clone()
    }

    /// The curve's role ("free", "knuckle", "keel", ...).
    #[getter]
    fn role(&self) -> &'static str {
        self.inner.role.name()
    }

    /// This curve with another name and/or role.
    #[pyo3(signature = (name=None, role=None))]
    fn renamed(
        &self,
        name: Option<&Bound<'_, PyAny>>,
        role: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Curve> {
        let new_name = optional_text(name, || format!("curve '{}': new name", self.name()))?;
        let name = new_name.as_deref().unwrap_or(self.name());
        let role = optional_text(role, || format!("curve '{name}': role"))?;
        let role = match role {
            Some(r) => parse_role(name, &r)?,
            None => self.inner.role,
        };
        Ok(Curve {
            inner: NetworkCurve {
                name: name.to_owned(),
                role,
                curve: self.inner.curve.clone(),
            },
        })
    }

    /// Polynomial degree.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.curve.degree()
    }

    /// Knot vector as a float array.
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.curve.knots())
    }

    /// Cartesian control points, shape (n, 3).
    #[getter]
    fn control_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        points_array(py, &self.inner.curve.control_points())
    }

    /// Weights (n,), or None when the curve is not rational.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner
            .curve
            .weights()
            .map(|w| PyArray1::from_vec(py, w))
    }

    /// The parameter domain (start, end).
    #[getter]
    fn domain(&self) -> (f64, f64) {
        self.inner.curve.domain()
    }

    /// Points at the parameters `t` (1-D array), shape (len(t), 3). Runs without the GIL and,
    /// for large arrays, on all cores.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = values(t, || format!("curve '{}': t", self.name()))?;
        let ts = parameters(self.name(), &t)?;
        let curve = &self.inner.curve;
        let out = py.detach(|| {
            guard(self.name(), || {
                let mut out = vec![0.0; 3 * ts.len()];
                if ts.len() < PARALLEL_MIN {
                    curve.points_into(ts, &mut out);
                } else {
                    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
                    let chunk = ts.len().div_ceil(threads);
                    std::thread::scope(|s| {
                        for (tc, oc) in ts.chunks(chunk).zip(out.chunks_mut(3 * chunk)) {
                            s.spawn(move || curve.points_into(tc, oc));
                        }
                    });
                }
                Ok(out)
            })
        })?;
        to_array2(py, out, 3)
    }

    /// C(t), C'(t), C''(t), C'''(t) as a (4, 3) array (a `CurveError` where they overflow).
    fn derivatives<'py>(&self, py: Python<'py>, t: f64) -> PyResult<Bound<'py, PyArray2<f64>>> {
        finite_parameters(self.name(), &[t])?;
        let d = guard(self.name(), || Ok(self.inner.curve.derivs(t)))?;
        let all = [d.point, d.d1, d.d2, d.d3];
        if !all.iter().all(|v| v.is_finite()) {
            return Err(curve_err(self.name(), CurveError::DerivativeOverflow { t }));
        }
        points_array(py, &all)
    }

    /// Points and curvature vectors (towards the centre of curvature, length κ) at the
    /// parameters `t`: two (len(t), 3) arrays, for curvature combs (a `CurveError` where the
    /// curvature overflows).
    fn curvature<'py>(&self, py: Python<'py>, t: &Bound<'py, PyAny>) -> PyResult<ArrayPair<'py>> {
        let t = values(t, || format!("curve '{}': t", self.name()))?;
        let ts = parameters(self.name(), &t)?;
        let curve = &self.inner.curve;
        let (pts, ks) = py.detach(|| {
            guard(self.name(), || {
                let pts: Vec<DVec3> = ts.iter().map(|&t| curve.point(t)).collect();
                let ks: Vec<DVec3> = ts.iter().map(|&t| curve.curvature_vector(t)).collect();
                if let Some((&t, _)) = ts.iter().zip(&ks).find(|(_, k)| !k.is_finite()) {
                    return Err(curve_err(self.name(), CurveError::DerivativeOverflow { t }));
                }
                Ok((pts, ks))
            })
        })?;
        Ok((points_array(py, &pts)?, points_array(py, &ks)?))
    }

    /// Curve length within `accuracy` metres.
    #[pyo3(signature = (accuracy=1e-9))]
    fn arc_length(&self, py: Python<'_>, accuracy: f64) -> PyResult<f64> {
        py.detach(|| {
            guard(self.name(), || {
                self.inner
                    .curve
                    .arc_length(accuracy)
                    .map_err(|e| curve_err(self.name(), e))
            })
        })
    }

    /// The closest point to `point` (3 floats), global: returns (t, distance, point array).
    #[pyo3(signature = (point, accuracy=1e-9))]
    fn nearest<'py>(
        &self,
        py: Python<'py>,
        point: [f64; 3],
        accuracy: f64,
    ) -> PyResult<(f64, f64, Bound<'py, PyArray1<f64>>)> {
        let q = DVec3::from_array(point);
        let n = py.detach(|| {
            guard(self.name(), || {
                self.inner
                    .curve
                    .nearest(q, accuracy)
                    .map_err(|e| curve_err(self.name(), e))
            })
        })?;
        Ok((
            n.t,
            n.distance,
            PyArray1::from_slice(py, &n.point.to_array()),
        ))
    }

    /// A box (min, max) holding the curve, at most `accuracy` larger than the tightest box.
    #[pyo3(signature = (accuracy=1e-9))]
    fn bounding_box(&self, py: Python<'_>, accuracy: f64) -> PyResult<([f64; 3], [f64; 3])> {
        let b = py.detach(|| {
            guard(self.name(), || {
                self.inner
                    .curve
                    .bounding_box(accuracy)
                    .map_err(|e| curve_err(self.name(), e))
            })
        })?;
        Ok((b.min.to_array(), b.max.to_array()))
    }

    /// The two pieces either side of the interior parameter `t`.
    fn split(&self, t: f64) -> PyResult<(Curve, Curve)> {
        guard(self.name(), || {
            let (a, b) = self
                .inner
                .curve
                .split(t)
                .map_err(|e| curve_err(self.name(), e))?;
            Ok((self.wrap(a), self.wrap(b)))
        })
    }

    /// The same curve with the knot `t` inserted `times` times.
    #[pyo3(signature = (t, times=None), text_signature = "($self, t, times=1)")]
    fn insert_knot(&self, t: f64, times: Option<&Bound<'_, PyAny>>) -> PyResult<Curve> {
        let times =
            optional_whole(times, || format!("curve '{}': times", self.name()))?.unwrap_or(1);
        guard(self.name(), || {
            let c = self
                .inner
                .curve
                .insert_knot(t, times)
                .map_err(|e| curve_err(self.name(), e))?;
            Ok(self.wrap(c))
        })
    }

    /// The curve traversed the other way.
    fn reversed(&self) -> PyResult<Curve> {
        let r = self
            .inner
            .curve
            .try_reversed()
            .map_err(|e| curve_err(self.name(), e))?;
        Ok(self.wrap(r))
    }

    /// Parameters of interior corners where the tangent turns by more than `min_angle_deg`.
    #[pyo3(signature = (min_angle_deg=0.1))]
    fn corners(&self, min_angle_deg: f64) -> Vec<f64> {
        self.inner
            .curve
            .corner_parameters(min_angle_deg.to_radians())
    }

    /// "endpoint" or "uniform" when the knots are that layout (control points usable as they
    /// are in Blender), else None.
    fn matching_layout(&self) -> Option<&'static str> {
        self.inner.curve.matching_layout().map(|l| match l {
            KnotLayout::Endpoint => "endpoint",
            KnotLayout::Uniform => "uniform",
            KnotLayout::Bezier => "bezier",
            KnotLayout::EndpointBezier => "endpoint_bezier",
        })
    }

    /// Control points of the curve's Bézier pieces (joints shared) as (m, 4): x, y, z, weight.
    /// As an end-point + Bézier NURBS spline of the same order they are exactly this shape.
    fn bezier_control_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let flat = self
            .inner
            .curve
            .bezier_control_points()
            .iter()
            .flat_map(|h| {
                let p = h.truncate() / h.w;
                [p.x, p.y, p.z, h.w]
            })
            .collect();
        to_array2(py, flat, 4)
    }

    fn __repr__(&self) -> String {
        format!(
            "Curve('{}', role={}, degree={}, points={})",
            self.inner.name,
            self.inner.role.name(),
            self.inner.curve.degree(),
            self.inner.curve.control_point_count()
        )
    }
}
