//! Network files: JSON text to and from lists of `Curve`.

use batten_core::{Network, NetworkCurve, Tolerance};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::Curve;
use crate::errors::{core_err, guard};

fn to_network(name: &str, curves: &[PyRef<'_, Curve>]) -> PyResult<Network> {
    let curves = curves.iter().map(|c| c.inner.clone()).collect();
    Network::try_new(name, curves).map_err(core_err)
}

/// The network of `curves` (a list of `Curve`) as batten's versioned JSON text.
#[pyfunction]
#[pyo3(signature = (name, curves))]
pub(crate) fn network_to_json(
    py: Python<'_>,
    name: &str,
    curves: Vec<PyRef<'_, Curve>>,
) -> PyResult<String> {
    let network = to_network(name, &curves)?;
    py.detach(|| guard("writing network", || Ok(network.to_json())))
}

/// Read batten's JSON network text: returns `(name, [Curve, ...])`; a bad curve raises
/// `BattenError` naming it.
#[pyfunction]
pub(crate) fn network_from_json(py: Python<'_>, text: &str) -> PyResult<(String, Vec<Curve>)> {
    let network = py.detach(|| {
        guard("reading network", || {
            Network::from_json(text).map_err(core_err)
        })
    })?;
    let curves = network
        .curves()
        .iter()
        .cloned()
        .map(|inner: NetworkCurve| Curve { inner })
        .collect();
    Ok((network.name.clone(), curves))
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
    let network = to_network("", &curves)?;
    py.detach(|| {
        guard("checking curves", || {
            network.check_lengths(tol).map_err(core_err)
        })
    })
}

/// Move every curve through the nodes the topology finds at the `capture` distance (m), each as
/// little as possible (`batten_core::snap_to_nodes`): returns `([Curve, ...], [report, ...])`,
/// curve for curve in order, each report a dict `curve`, `nodes` (nodes it passes through),
/// `max_move` (m, the largest distance to one of them before the move). The GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, capture))]
pub(crate) fn snap_to_nodes<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    capture: f64,
) -> PyResult<(Vec<Curve>, Vec<Bound<'py, PyDict>>)> {
    let capture = Tolerance::try_new(capture).map_err(core_err)?;
    let network = to_network("", &curves)?;
    let snapped = py.detach(|| {
        guard("snapping curves to their nodes", || {
            batten_core::snap_to_nodes(&network, capture).map_err(core_err)
        })
    })?;
    let reports = snapped
        .snaps
        .iter()
        .map(|s| {
            let d = PyDict::new(py);
            d.set_item("curve", &s.curve)?;
            d.set_item("nodes", s.nodes)?;
            d.set_item("max_move", s.max_move)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let curves = snapped
        .network
        .curves()
        .iter()
        .cloned()
        .map(|inner| Curve { inner })
        .collect();
    Ok((curves, reports))
}
