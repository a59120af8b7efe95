//! Network files: JSON text to and from lists of `Curve`.

use batten_core::{Network, NetworkCurve, Tolerance};
use pyo3::prelude::*;

use crate::args::{self, text};
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
    name: &Bound<'_, PyAny>,
    curves: Vec<PyRef<'_, Curve>>,
) -> PyResult<String> {
    let name = text(name, || "the network name".to_owned())?;
    let network = to_network(&name, &curves)?;
    py.detach(|| guard("writing network", || Ok(network.to_json())))
}

/// Read batten's JSON network text: returns `(name, [Curve, ...])`; a bad curve raises
/// `BattenError` naming it.
#[pyfunction]
pub(crate) fn network_from_json(
    py: Python<'_>,
    text: &Bound<'_, PyAny>,
) -> PyResult<(String, Vec<Curve>)> {
    let text = args::text(text, || "the network text".to_owned())?;
    let network = py.detach(|| {
        guard("reading network", || {
            Network::from_json(&text).map_err(core_err)
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
