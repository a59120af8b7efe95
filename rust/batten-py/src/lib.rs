//! `batten_native`: the thin Python binding of batten-core.
//!
//! Arguments are converted first, then the core runs with the GIL released; every core error is
//! mapped in one place ([`errors`]) to a subclass of `batten_native.BattenError` (a
//! `ValueError`) by kind, and a panic never crosses into Python ([`errors::guard`]).
//!
//! Indices and sizes go to Python and Blender converted, never cast: no cast may silently wrap
//! or truncate (kurbo's stricter lints).
#![warn(clippy::cast_possible_wrap, clippy::cast_possible_truncation)]

mod args;
mod curve;
mod errors;
mod export;
mod fair;
mod form;
mod hull;
mod hull_model;
mod hydro;
mod hydro_transform;
mod live;
mod network;
mod progress;
mod sections;
mod surface_fair;
mod topology;

use pyo3::prelude::*;

/// Rust's allocations in the add-on go to mimalloc: the core allocates and frees arrays of a
/// few megabytes on every rebuild, which glibc's malloc returns to the system and faults in
/// again each time (the benches use the same allocator).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The compiled module `batten_native._native`, re-exported by the `batten_native` package.
#[pymodule]
#[pyo3(name = "_native")]
fn batten_native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_TOLERANCE", batten_core::DEFAULT_TOLERANCE)?;
    m.add("DEFAULT_RESOLUTION", batten_core::DEFAULT_RESOLUTION)?;
    m.add("MAX_RESOLUTION", batten_core::MAX_RESOLUTION)?;
    m.add(
        "DEFAULT_FAIR_TOLERANCE",
        batten_core::DEFAULT_FAIR_TOLERANCE,
    )?;
    m.add(
        "DEFAULT_SECTION_TOLERANCE",
        batten_core::DEFAULT_SECTION_TOLERANCE,
    )?;
    m.add(
        "DEFAULT_SECTION_MODEL_TOLERANCE",
        batten_core::DEFAULT_SECTION_MODEL_TOLERANCE,
    )?;
    m.add(
        "DEFAULT_CORNER_ANGLE_DEG",
        batten_core::DEFAULT_CORNER_ANGLE_DEGREES,
    )?;
    m.add("DEFAULT_FAIR_DEGREE", batten_core::DEFAULT_FAIR_DEGREE)?;
    m.add(
        "SECTION_CAPTURE_FACTOR",
        batten_core::SECTION_CAPTURE_FACTOR,
    )?;
    m.add(
        "MAX_TANGENT_TURN_DEGREES",
        batten_core::MAX_TANGENT_TURN_DEGREES,
    )?;
    m.add("ROLES", batten_core::Role::ALL.map(|r| r.name()).to_vec())?;
    m.add_class::<curve::Curve>()?;
    m.add_function(wrap_pyfunction!(network::network_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(network::same_curves, m)?)?;
    m.add_function(wrap_pyfunction!(network::network_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(network::check_lengths, m)?)?;
    m.add_function(wrap_pyfunction!(network::snap_to_nodes, m)?)?;
    m.add_function(wrap_pyfunction!(network::chines_from_knuckles, m)?)?;
    m.add_function(wrap_pyfunction!(network::nodes_from_data, m)?)?;
    #[cfg(feature = "test-hooks")]
    m.add_function(wrap_pyfunction!(errors::_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(fair::fair_points, m)?)?;
    m.add_function(wrap_pyfunction!(fair::fairness, m)?)?;
    m.add_function(wrap_pyfunction!(surface_fair::fair_sections, m)?)?;
    m.add_function(wrap_pyfunction!(surface_fair::section_noise, m)?)?;
    m.add(
        "DEFAULT_SURFACE_FAIR_TOLERANCE",
        batten_core::DEFAULT_SURFACE_FAIR_TOLERANCE,
    )?;
    m.add_function(wrap_pyfunction!(topology::topology, m)?)?;
    m.add_function(wrap_pyfunction!(form::form_topology, m)?)?;
    m.add_function(wrap_pyfunction!(form::transform_network, m)?)?;
    m.add_function(wrap_pyfunction!(hydro_transform::transform_hydrostatic, m)?)?;
    m.add_function(wrap_pyfunction!(hull::build_surface, m)?)?;
    m.add_function(wrap_pyfunction!(hull::build_hull_model, m)?)?;
    m.add_class::<hull_model::HullModel>()?;
    m.add_class::<live::LiveHull>()?;
    m.add("DEFAULT_CUT_TOLERANCE", batten_core::DEFAULT_CUT_TOLERANCE)?;
    m.add(
        "DEFAULT_EXPORT_TOLERANCE",
        batten_core::DEFAULT_EXPORT_TOLERANCE,
    )?;
    m.add_function(wrap_pyfunction!(export::cad_text, m)?)?;
    m.add_function(wrap_pyfunction!(export::cad_faces, m)?)?;
    m.add("SEA_WATER_DENSITY", batten_core::SEA_WATER_DENSITY)?;
    m.add_class::<hydro::MeshHull>()?;
    m.add_function(wrap_pyfunction!(hydro::mesh_hydrostatics, m)?)?;
    m.add_function(wrap_pyfunction!(hydro::mesh_sectional_areas, m)?)?;
    Ok(())
}
