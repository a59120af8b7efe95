//! Network topology as plain Python data: counts, faces, boundary loops, diagnostics.

use batten_core::{Tolerance, Topology, Warning, DEFAULT_TOLERANCE};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::{network_of, Curve};
use crate::errors::{core_err, guard};
use crate::hull::warning_dict;

/// The topology of the network of `curves` at `tolerance` (H-rep paper §3.1, §5.2): a dict
/// with `nodes`, `edges` (counts), `node_positions` (list of [x, y, z]), `node_kinds` (one per
/// node: `crossing`, `end_to_end`, `end_on_curve` — a curve ending on another where every face
/// has a corner —, `t_joint` — a curve ending on another that runs on as one side of a face —
/// or `free_end`), `faces` (each: `curves` (names), `corners`, `sides` (list of curve-name
/// lists, one per side between true corners), `edges` (edge count)), `faces_by_corners`
/// ({corners: count}), `boundary_loops` (each: `curves`, `edges`), and `diagnostics` (each:
/// `kind`, `message`, `curves`, `location` or None, `error` None: the shape of the hull
/// report's warnings).
#[pyfunction]
#[pyo3(signature = (curves, tolerance=DEFAULT_TOLERANCE))]
pub(crate) fn topology<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let tol = Tolerance::try_new(tolerance).map_err(core_err)?;
    let network = network_of("", &curves)?;
    let topo = py.detach(|| {
        guard("building the topology", || {
            Topology::build(&network, tol).map_err(core_err)
        })
    })?;
    let names = |idx: &[usize]| -> Vec<String> {
        idx.iter().map(|&i| topo.curve_names[i].clone()).collect()
    };
    let d = PyDict::new(py);
    d.set_item("nodes", topo.node_count())?;
    d.set_item("edges", topo.edge_count())?;
    let positions: Vec<[f64; 3]> = topo
        .brep
        .vertices
        .iter()
        .map(|v| v.position.to_array())
        .collect();
    d.set_item("node_positions", positions)?;
    let kinds: Vec<&str> = topo.node_kinds().into_iter().map(|k| k.as_str()).collect();
    d.set_item("node_kinds", kinds)?;
    let faces = topo
        .faces
        .iter()
        .map(|f| {
            let fd = PyDict::new(py);
            fd.set_item("curves", names(&f.curves))?;
            fd.set_item("corners", f.corners)?;
            let sides: Vec<Vec<String>> = f.sides.iter().map(|s| names(&s.curves)).collect();
            fd.set_item("sides", sides)?;
            fd.set_item("edges", f.edges.len())?;
            Ok(fd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("faces", faces)?;
    d.set_item("faces_by_corners", topo.faces_by_corners())?;
    let loops = topo
        .boundary_loops
        .iter()
        .map(|l| {
            let ld = PyDict::new(py);
            ld.set_item("curves", names(&l.curves))?;
            ld.set_item("edges", l.edges.len())?;
            Ok(ld)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("boundary_loops", loops)?;
    let diags = topo
        .diagnostics
        .iter()
        .map(|g| warning_dict(py, &Warning::from(g)))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("diagnostics", diags)?;
    Ok(d)
}
