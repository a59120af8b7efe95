//! The one place where core errors and panics become Python exceptions.
//!
//! The exception classes are defined in Python (`batten_native/_errors.py`, so that
//! `CurveError` carries a `.curve` attribute and pickles); this module raises them by kind:
//!
//! | core error | Python class |
//! | --- | --- |
//! | [`Error::Curve`], [`Error::DuplicateName`] | `CurveError` (`.curve` set) |
//! | [`Error::Fair`] | `FairError` (a `CurveError`) |
//! | [`Error::Format`] | `NetworkFileError` |
//! | [`Error::NoSurface`], [`Error::Mesh`] | `NoSurfaceError` |
//! | [`Error::Tolerance`], [`Error::Resolution`], [`Error::EmptyName`], [`Error::InvalidInput`], argument checks | `InvalidArgumentError` |
//! | [`Error::Hydro`] (other than [`HydroError::InvalidInput`], an `InvalidArgumentError`) | `HydrostaticsError` |
//! | [`ExportError`](batten_core::ExportError) (its own type: the export sits above the hull, which uses [`Error`]) | `ExportError` (`.faces` set for patches that could not be fitted), `InvalidArgumentError` for a bad tolerance |
//! | a `progress` callback that returned `False` | `Cancelled` |
//! | a caught panic | `InternalError` |

use std::panic::{catch_unwind, AssertUnwindSafe};

use batten_core::{CurveError as CoreCurveError, Error, HydroError};
use pyo3::PyErr;

pyo3::import_exception!(batten_native._errors, BattenError);
pyo3::import_exception!(batten_native._errors, CurveError);
pyo3::import_exception!(batten_native._errors, FairError);
pyo3::import_exception!(batten_native._errors, NetworkFileError);
pyo3::import_exception!(batten_native._errors, NoSurfaceError);
pyo3::import_exception!(batten_native._errors, InvalidArgumentError);
pyo3::import_exception!(batten_native._errors, HydrostaticsError);
pyo3::import_exception!(batten_native._errors, InternalError);
pyo3::import_exception!(batten_native._errors, Cancelled);
pyo3::import_exception!(batten_native._errors, ExportError);

/// A core error as the `BattenError` subclass of its kind, with the core's message (which names
/// the curve).
pub(crate) fn core_err(err: impl Into<Error>) -> PyErr {
    let err = err.into();
    let message = err.to_string();
    match err {
        Error::Curve { curve, .. } | Error::DuplicateName(curve) => {
            CurveError::new_err((message, curve))
        }
        Error::Fair { curve, .. } => FairError::new_err((message, curve)),
        Error::Format(_) => NetworkFileError::new_err(message),
        Error::NoSurface(_) | Error::Mesh(_) => NoSurfaceError::new_err(message),
        Error::Tolerance(_)
        | Error::Resolution { .. }
        | Error::EmptyName(_)
        | Error::InvalidInput(_)
        | Error::Hydro(HydroError::InvalidInput(_)) => InvalidArgumentError::new_err(message),
        Error::Hydro(_) => HydrostaticsError::new_err(message),
    }
}

/// An export error as `ExportError` (`.faces` the topology faces that could not be fitted; a
/// bad tolerance as `InvalidArgumentError`).
pub(crate) fn export_err(err: batten_core::ExportError) -> PyErr {
    let message = format!("export: {err}");
    match err {
        batten_core::ExportError::Tolerance(_) => InvalidArgumentError::new_err(message),
        batten_core::ExportError::NotConverged { faces, .. } => {
            let faces: Vec<usize> = faces.0.iter().map(|u| u.face).collect();
            ExportError::new_err((message, faces))
        }
        batten_core::ExportError::Holes(_) => ExportError::new_err(message),
    }
}

/// A form-topology error: a lost connection as `CurveError` naming its first curve (the
/// message names both), a network error as [`core_err`], everything else (a parameter the hull
/// cannot take, a bad move) as `InvalidArgumentError`.
pub(crate) fn form_err(err: batten_core::FormError) -> PyErr {
    match err {
        batten_core::FormError::Network(e) => core_err(e),
        batten_core::FormError::ConnectionLost { ref curves, .. } => {
            let first = curves.first().cloned().unwrap_or_default();
            CurveError::new_err((format!("transform: {err}"), first))
        }
        e => InvalidArgumentError::new_err(format!("transform: {e}")),
    }
}

/// A curve kernel error as `CurveError`, naming the curve.
pub(crate) fn curve_err(name: &str, err: CoreCurveError) -> PyErr {
    core_err(err.named(name))
}

/// An argument problem found in the binding while converting arguments (a wrong array shape,
/// an unknown role, options that exclude each other) as `InvalidArgumentError`; the message
/// names the curve where there is one.
pub(crate) fn arg_err(msg: impl Into<String>) -> PyErr {
    InvalidArgumentError::new_err(msg.into())
}

/// Run core work so that a panic becomes an `InternalError` naming what was being done, never a
/// `PanicException` or a crashed Blender.
pub(crate) fn guard<T>(what: &str, f: impl FnOnce() -> Result<T, PyErr>) -> Result<T, PyErr> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(payload) => {
            let detail = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".to_owned());
            Err(InternalError::new_err(format!(
                "{what}: internal error in batten's core ({detail}); please report it with the curves that caused it"
            )))
        }
    }
}

/// Panics inside [`guard`], so tests can prove a panic reaches Python as `InternalError`
/// (built only with the `test-hooks` feature, never in a release).
#[cfg(feature = "test-hooks")]
#[pyo3::pyfunction]
pub(crate) fn _panic_for_tests(message: &str) -> pyo3::PyResult<()> {
    guard("panic test", || panic!("{message}"))
}
