//! The one place where core errors and panics become Python exceptions.

use std::panic::{catch_unwind, AssertUnwindSafe};

use batten_core::{CurveError, Error};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::PyErr;

create_exception!(
    batten_native,
    BattenError,
    PyValueError,
    "A problem with the hull's curves or settings; the message names the curve and the problem."
);

/// A core error as `BattenError`, with the core's message (which names the curve).
pub fn core_err(err: Error) -> PyErr {
    BattenError::new_err(err.to_string())
}

/// A curve error as `BattenError`, naming the curve.
pub fn curve_err(name: &str, err: CurveError) -> PyErr {
    core_err(err.named(name))
}

/// Any displayable error as `BattenError`, naming the curve.
pub fn named_err(name: &str, err: impl std::fmt::Display) -> PyErr {
    BattenError::new_err(format!("curve '{name}': {err}"))
}

/// A plain message as `BattenError` (argument problems found in the binding).
pub fn msg_err(msg: impl Into<String>) -> PyErr {
    BattenError::new_err(msg.into())
}

/// Run core work so that a panic becomes a `BattenError` naming what was being done, never a
/// `PanicException` or a crashed Blender.
pub fn guard<T>(what: &str, f: impl FnOnce() -> Result<T, PyErr>) -> Result<T, PyErr> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(payload) => {
            let detail = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".to_owned());
            Err(msg_err(format!(
                "{what}: internal error in batten's core ({detail}); please report it with the curves that caused it"
            )))
        }
    }
}

/// Panics inside [`guard`], so tests can prove a panic reaches Python as `BattenError`.
#[pyfunction]
pub fn _panic_for_tests(message: &str) -> PyResult<()> {
    guard("panic test", || panic!("{message}"))
}
