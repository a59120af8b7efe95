//! Network files: JSON text to and from lists of `Curve`.

use batten_core::{Network, SnapData, Tolerance};
use glam::DVec3;
use numpy::{PyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{self, text};
use crate::curve::{curves_of, network_of, planes_of, points_array, tangent_planes_of, Curve};
use crate::errors::{arg_err, core_err, guard};

/// The network of `curves` (a list of `Curve`) and its `tangent_planes` (each
/// `[nx, ny, nz, offset]`) as batten's versioned JSON text.
#[pyfunction]
#[pyo3(signature = (name, curves, tangent_planes=None))]
pub(crate) fn network_to_json(
    py: Python<'_>,
    name: &Bound<'_, PyAny>,
    curves: Vec<PyRef<'_, Curve>>,
    tangent_planes: Option<Vec<[f64; 4]>>,
) -> PyResult<String> {
    let name = text(name, || "the network name".to_owned())?;
    let network =
        network_of(&name, &curves)?.with_tangent_planes(tangent_planes_of(tangent_planes)?);
    py.detach(|| guard("writing network", || Ok(network.to_json())))
}

/// Whether the curve lists `a` and `b` are the same curves: names, roles, degrees, knots,
/// control points and weights equal, in order (what a network's JSON would say, without
/// writing it: the check a kept surface makes on every hydrostatics call).
#[pyfunction]
pub(crate) fn same_curves(a: Vec<PyRef<'_, Curve>>, b: Vec<PyRef<'_, Curve>>) -> bool {
    a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| x.inner == y.inner)
}

/// Read batten's JSON network text: returns `(name, [Curve, ...], tangent_planes)`, each plane
/// `[nx, ny, nz, offset]`; a bad curve or plane raises `BattenError` naming it.
#[pyfunction]
pub(crate) fn network_from_json(
    py: Python<'_>,
    text: &Bound<'_, PyAny>,
) -> PyResult<(String, Vec<Curve>, Vec<[f64; 4]>)> {
    let text = args::text(text, || "the network text".to_owned())?;
    let network = py.detach(|| {
        guard("reading network", || {
            Network::from_json(&text).map_err(core_err)
        })
    })?;
    Ok((
        network.name.clone(),
        curves_of(&network),
        planes_of(&network),
    ))
}

/// Check names are unique and no curve is shorter than `tolerance` (a zero-length curve);
/// raises `BattenError` naming the first offending curve.
#[pyfunction]
#[pyo3(signature = (curves, tolerance))]
pub(crate) fn check_lengths(
    py: Python<'_>,
    curves: Vec<PyRef<'_, Curve>>,
    tolerance: f64,
) -> PyResult<()> {
    let tol = Tolerance::try_new(tolerance).map_err(core_err)?;
    let network = network_of("", &curves)?;
    py.detach(|| {
        guard("checking curves", || {
            network.check_lengths(tol).map_err(core_err)
        })
    })
}

/// Move every curve through the nodes the topology finds at the `capture` distance (m), each as
/// little as possible (`batten_core::snap_to_nodes`). With `points` (per curve, the (n, 3) points
/// it was fitted to) and `tolerance`, a curve leaves out the nodes that would take one of its
/// points farther than `tolerance`. Returns `([Curve, ...], [report, ...])`, curve for curve in
/// order, each report a dict `curve`, `nodes` (nodes it passes through), `skipped` (nodes left
/// out), `max_move` (m, the largest distance to a node before the move), `tangent_nodes`
/// (smooth nodes at which its tangent was turned into the plane of every curve's tangent
/// there), `max_tangent_turn` (degrees, the largest such turn) and, with points,
/// `max_deviation` (m) and `max_deviation_index`. The GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, capture, points=None, tolerance=None))]
pub(crate) fn snap_to_nodes<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    capture: f64,
    points: Option<Vec<Bound<'py, PyAny>>>,
    tolerance: Option<f64>,
) -> PyResult<(Vec<Curve>, Vec<Bound<'py, PyDict>>)> {
    let capture = Tolerance::try_new(capture).map_err(core_err)?;
    let network = network_of("", &curves)?;
    let data: Option<Vec<Vec<DVec3>>> = points
        .map(|all| {
            all.iter()
                .zip(&curves)
                .map(|(p, c)| points3(p, &c.inner.name, "points"))
                .collect::<PyResult<Vec<_>>>()
        })
        .transpose()?;
    let tol = match (&data, tolerance) {
        (Some(_), Some(t)) => t,
        (Some(_), None) => return Err(arg_err("snap_to_nodes: points need a tolerance")),
        (None, Some(_)) => return Err(arg_err("snap_to_nodes: a tolerance needs points")),
        (None, None) => 0.0,
    };
    let snapped = py.detach(|| {
        guard("snapping curves to their nodes", || {
            let data = data.as_deref().map(|points| SnapData {
                points,
                tolerance: tol,
            });
            batten_core::snap_to_nodes(&network, capture, data).map_err(core_err)
        })
    })?;
    let reports = snapped
        .snaps
        .iter()
        .map(|s| {
            let d = PyDict::new(py);
            d.set_item("curve", &s.curve)?;
            d.set_item("nodes", s.nodes)?;
            d.set_item("skipped", s.skipped)?;
            d.set_item("max_move", s.max_move)?;
            if let Some((dev, i)) = s.max_deviation {
                d.set_item("max_deviation", dev)?;
                d.set_item("max_deviation_index", i)?;
            }
            d.set_item("tangent_nodes", s.tangent_nodes)?;
            d.set_item("max_tangent_turn", s.max_tangent_turn)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((curves_of(&snapped.network), reports))
}

/// `obj` as points: an (n, 3) array-like, or an empty sequence for none; anything else is an
/// InvalidArgumentError naming the curve and the argument.
fn points3(obj: &Bound<'_, PyAny>, name: &str, what: &str) -> PyResult<Vec<DVec3>> {
    if obj.len().is_ok_and(|n| n == 0) {
        return Ok(Vec::new());
    }
    let arr = args::rows(obj, || format!("curve '{name}': {what}"))?;
    if arr.shape()[1] != 3 {
        return Err(arg_err(format!(
            "curve '{name}': {what} must have shape (n, 3)"
        )));
    }
    Ok(arr
        .as_array()
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// The knuckle curves (chines) joining the knuckles of consecutive sections
/// (`batten_core::chines_from_knuckles`): `knuckles[i]` are the knuckle points ((k, 3), k ≥ 0)
/// of curve `i`, sections are the curves lying in an axis plane within `tolerance` (m).
/// Returns the new curves: chines, role `knuckle`, then the straight lines that part a flat
/// end (a shaft boss's), role `free`. The GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, knuckles, tolerance))]
pub(crate) fn chines_from_knuckles<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    knuckles: Vec<Bound<'py, PyAny>>,
    tolerance: f64,
) -> PyResult<Vec<Curve>> {
    let tol = Tolerance::try_new(tolerance).map_err(core_err)?;
    let network = network_of("", &curves)?;
    let knuckles = knuckles
        .iter()
        .zip(&curves)
        .map(|(k, c)| points3(k, &c.inner.name, "knuckles"))
        .collect::<PyResult<Vec<_>>>()?;
    let chines = py.detach(|| {
        guard("joining knuckles into chines", || {
            batten_core::chines_from_knuckles(&network, &knuckles, tol).map_err(core_err)
        })
    })?;
    Ok(chines.into_iter().map(|inner| Curve { inner }).collect())
}

/// Nodes from the data (`batten_core::nodes_from_data`): where the point curves `points` (per
/// curve an (n, 3) array-like; `names` name them in errors) cross or end on each other, one
/// point per node, put among the points of every curve through it. `tolerance` (m) is the
/// data's, `corner_angle_deg` the turn above which a polyline has a knuckle (None: none),
/// `model_tolerance` (m) how close a node must be to a sample to take its place. Returns
/// `(points, sources, nodes)`: per curve its new (m, 3) points and, per point, the index of
/// the input point it is or replaces (None for an inserted node); each node a dict `position`,
/// `curves` (indices) and `gap` (m). The GIL is released.
#[pyfunction]
#[pyo3(signature = (names, points, tolerance, corner_angle_deg, model_tolerance))]
pub(crate) fn nodes_from_data<'py>(
    py: Python<'py>,
    names: Vec<String>,
    points: Vec<Bound<'py, PyAny>>,
    tolerance: f64,
    corner_angle_deg: Option<f64>,
    model_tolerance: f64,
) -> PyResult<NodesFromData<'py>> {
    if names.len() != points.len() {
        return Err(arg_err(format!(
            "nodes_from_data: {} names for {} curves",
            names.len(),
            points.len()
        )));
    }
    let model = Tolerance::try_new(model_tolerance).map_err(core_err)?;
    let data = points
        .iter()
        .zip(&names)
        .map(|(p, n)| points3(p, n, "points"))
        .collect::<PyResult<Vec<_>>>()?;
    let corner = corner_angle_deg.map(f64::to_radians);
    let noded = py.detach(|| {
        guard("finding the nodes of the data", || {
            batten_core::nodes_from_data(&data, tolerance, corner, model).map_err(core_err)
        })
    })?;
    let arrays = noded
        .points
        .iter()
        .map(|pts| points_array(py, pts))
        .collect::<PyResult<Vec<_>>>()?;
    let nodes = noded
        .nodes
        .iter()
        .map(|n| {
            let d = PyDict::new(py);
            d.set_item("position", n.position.to_array())?;
            d.set_item("curves", &n.curves)?;
            d.set_item("gap", n.gap)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((arrays, noded.source, nodes))
}

/// What [`nodes_from_data`] returns: per curve its points and their sources, and the nodes.
type NodesFromData<'py> = (
    Vec<Bound<'py, PyArray2<f64>>>,
    Vec<Vec<Option<usize>>>,
    Vec<Bound<'py, PyDict>>,
);
