//! Form topology and its transformations (seed 002 §6–§7) as plain Python data.

use batten_core::{
    form_topology as core_form_topology, transform, transform_to, FormOptions, FormParameters,
    FormTopology, Network, Target, Tolerance, VertexMove, DEFAULT_TOLERANCE,
};
use glam::DVec3;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::curve::{curves_of, network_of, Curve};
use crate::errors::{arg_err, core_err, form_err, guard};

fn options(tolerance: f64, draft: Option<f64>) -> PyResult<FormOptions> {
    if draft.is_some_and(|d| !d.is_finite()) {
        return Err(arg_err(
            "form topology: the draft must be a finite number of metres",
        ));
    }
    Ok(FormOptions {
        tolerance: Tolerance::try_new(tolerance).map_err(core_err)?,
        draft,
    })
}

/// The measured parameters as a dict (None where not measurable).
fn parameters_dict<'py>(
    py: Python<'py>,
    network: &Network,
    p: &FormParameters,
) -> PyResult<Bound<'py, PyDict>> {
    let names = network.curves();
    let d = PyDict::new(py);
    d.set_item("length", p.length)?;
    d.set_item("breadth", p.breadth)?;
    d.set_item("depth", p.depth)?;
    d.set_item("draft", p.draft)?;
    d.set_item("waterline_breadth", p.waterline_breadth)?;
    d.set_item("pmb_length", p.pmb.as_ref().map(|m| m.length))?;
    d.set_item("pmb_position", p.pmb.as_ref().map(|m| m.position))?;
    d.set_item("pmb_aft", p.pmb.as_ref().map(|m| m.aft))?;
    d.set_item("pmb_fwd", p.pmb.as_ref().map(|m| m.fwd))?;
    d.set_item("no_pmb_reason", p.no_pmb_reason.clone())?;
    let first = p.bilges.first();
    d.set_item("bilge_radius", first.and_then(|b| b.radius))?;
    d.set_item("rise_of_floor", first.map(|b| b.rise_of_floor))?;
    let bilges = p
        .bilges
        .iter()
        .map(|b| {
            let bd = PyDict::new(py);
            bd.set_item("section", &names[b.section].name)?;
            bd.set_item("radius", b.radius)?;
            bd.set_item("rise_of_floor", b.rise_of_floor)?;
            bd.set_item("fob_vertex", b.fob_vertex)?;
            bd.set_item("fos_vertex", b.fos_vertex)?;
            Ok(bd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("bilges", bilges)?;
    d.set_item("entrance_length", p.entrance_length)?;
    d.set_item("run_length", p.run_length)?;
    Ok(d)
}

/// The form topology as a dict.
fn form_dict<'py>(
    py: Python<'py>,
    network: &Network,
    form: &FormTopology,
) -> PyResult<Bound<'py, PyDict>> {
    let curves = network.curves();
    let name = |c: usize| curves[c].name.clone();
    let d = PyDict::new(py);
    let form_curves: Vec<String> = (0..curves.len())
        .filter(|&c| form.is_form_curve[c])
        .map(name)
        .collect();
    d.set_item("curves", form_curves)?;
    let vertices = form
        .vertices
        .iter()
        .map(|v| {
            let vd = PyDict::new(py);
            vd.set_item("position", v.position.to_array())?;
            vd.set_item(
                "curves",
                v.curves.iter().map(|&c| name(c)).collect::<Vec<_>>(),
            )?;
            vd.set_item("planes", v.planes.clone())?;
            Ok(vd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("vertices", vertices)?;
    let edges = form
        .edges
        .iter()
        .map(|e| {
            let ed = PyDict::new(py);
            ed.set_item("curve", name(e.curve))?;
            ed.set_item("t0", e.t0)?;
            ed.set_item("t1", e.t1)?;
            ed.set_item("start", e.start)?;
            ed.set_item("end", e.end)?;
            ed.set_item("kind", e.kind.name())?;
            Ok(ed)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("edges", edges)?;
    let faces = form
        .faces
        .iter()
        .map(|f| {
            let fd = PyDict::new(py);
            fd.set_item(
                "curves",
                f.curves.iter().map(|&c| name(c)).collect::<Vec<_>>(),
            )?;
            let sides: Vec<Vec<usize>> = f
                .sides
                .iter()
                .map(|s| s.iter().map(|&(e, _)| e).collect())
                .collect();
            fd.set_item("sides", sides)?;
            Ok(fd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("faces", faces)?;
    let planes = form
        .planes
        .iter()
        .map(|p| {
            let pd = PyDict::new(py);
            pd.set_item("kind", p.kind.name())?;
            pd.set_item("normal", p.normal.to_array())?;
            pd.set_item("offset", p.offset)?;
            pd.set_item(
                "curves",
                p.curves.iter().map(|&c| name(c)).collect::<Vec<_>>(),
            )?;
            Ok(pd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("planes", planes)?;
    d.set_item(
        "parameters",
        parameters_dict(py, network, &form.parameters)?,
    )?;
    Ok(d)
}

/// The form topology of the network of `curves` (seed 002 §6): a dict with `curves` (the form
/// curves' names), `vertices` (each `position`, `curves`, `planes` — indices into `planes`),
/// `edges` (each `curve`, `t0`, `t1`, `start`, `end` — vertex indices —, `kind`:
/// `free_form`, `straight` or `blend`), `faces` (each `curves`, `sides` — edge indices per
/// side), `planes` (each `kind`, `normal`, `offset`, `curves`) and `parameters` (§7.2.5:
/// `length`, `breadth`, `depth`, `draft`, `waterline_breadth`, `pmb_length`, `pmb_position`,
/// `pmb_aft`, `pmb_fwd`, `no_pmb_reason`, `bilge_radius`, `rise_of_floor`, `bilges`,
/// `entrance_length`, `run_length`; None where the hull has no such feature). The GIL is
/// released.
#[pyfunction]
#[pyo3(signature = (curves, tolerance=DEFAULT_TOLERANCE, draft=None))]
pub(crate) fn form_topology<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    tolerance: f64,
    draft: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let opts = options(tolerance, draft)?;
    let network = network_of("", &curves)?;
    let form = py.detach(|| {
        guard("finding the form topology", || {
            core_form_topology(&network, &opts).map_err(form_err)
        })
    })?;
    form_dict(py, &network, &form)
}

/// The target of a parameter named as in the Python API.
fn target(name: &str, value: f64) -> PyResult<Target> {
    Ok(match name {
        "breadth" => Target::Breadth(value),
        "depth" => Target::Depth(value),
        "pmb_length" => Target::PmbLength(value),
        "pmb_position" => Target::PmbPosition(value),
        "bilge_radius" => Target::BilgeRadius(value),
        "entrance_length" => Target::EntranceLength(value),
        "run_length" => Target::RunLength(value),
        other => return Err(arg_err(format!("transform: unknown parameter '{other}'"))),
    })
}

/// Transform the network of `curves` through its form topology (seed 002 §7.2): first the
/// explicit `moves` (a list of `(vertex, [dx, dy, dz])`), then each `(parameter, value)` of
/// `targets` in order (`breadth`, `depth`, `pmb_length`, `pmb_position`, `bilge_radius`,
/// `entrance_length`, `run_length`; metres), the form found again before each step.
/// Returns `([Curve, ...], report)`: the new curves in order and a dict `steps` (each `what`,
/// `value`, `reattached` — curves re-attached at their nodes —, `max_move`), `before` and
/// `after` (the parameters). A step that would break a connection raises `CurveError` naming
/// the curves; nothing is returned then. The GIL is released.
#[pyfunction]
#[pyo3(signature = (curves, targets, moves, tolerance=DEFAULT_TOLERANCE, draft=None))]
pub(crate) fn transform_network<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, Curve>>,
    targets: Vec<(String, f64)>,
    moves: Vec<(usize, [f64; 3])>,
    tolerance: f64,
    draft: Option<f64>,
) -> PyResult<(Vec<Curve>, Bound<'py, PyDict>)> {
    let opts = options(tolerance, draft)?;
    let network = network_of("", &curves)?;
    let targets = targets
        .iter()
        .map(|(n, v)| target(n, *v))
        .collect::<PyResult<Vec<_>>>()?;
    let moves: Vec<VertexMove> = moves
        .iter()
        .map(|&(vertex, t)| VertexMove {
            vertex,
            translation: DVec3::from_array(t),
        })
        .collect();
    type Step = (String, Option<f64>, Vec<String>, f64);
    let (before, after, result, steps) = py.detach(|| {
        guard("transforming the network", || {
            let first = core_form_topology(&network, &opts).map_err(form_err)?;
            let before = first.parameters.clone();
            let mut current = network.clone();
            let mut form = first;
            let mut steps: Vec<Step> = Vec::new();
            if !moves.is_empty() {
                let out = transform(&current, &form, &moves, opts.tolerance).map_err(form_err)?;
                steps.push(("moves".into(), None, out.reattached, out.max_move));
                current = out.network;
                form = core_form_topology(&current, &opts).map_err(form_err)?;
            }
            for t in &targets {
                let out = transform_to(&current, &form, *t, opts.tolerance).map_err(form_err)?;
                steps.push((
                    t.name().into(),
                    Some(t.value()),
                    out.reattached,
                    out.max_move,
                ));
                current = out.network;
                form = core_form_topology(&current, &opts).map_err(form_err)?;
            }
            Ok((before, form.parameters, current, steps))
        })
    })?;
    let report = PyDict::new(py);
    let step_dicts = steps
        .into_iter()
        .map(|(what, value, reattached, max_move)| {
            let sd = PyDict::new(py);
            sd.set_item("what", what)?;
            sd.set_item("value", value)?;
            sd.set_item("reattached", reattached)?;
            sd.set_item("max_move", max_move)?;
            Ok(sd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    report.set_item("steps", step_dicts)?;
    report.set_item("before", parameters_dict(py, &network, &before)?)?;
    report.set_item("after", parameters_dict(py, &result, &after)?)?;
    Ok((curves_of(&result), report))
}
