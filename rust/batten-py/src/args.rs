//! Python arguments as batten values, each failure an `InvalidArgumentError` naming the
//! parameter (and its curve), never pyo3's TypeError, OverflowError or UnicodeEncodeError.
//!
//! Parameters that a script may pass in the wrong kind (bytes or a string with a lone
//! surrogate for a name, a ragged or empty list for points, an int beyond 64 bits for a count)
//! are taken as `&Bound<PyAny>` and converted here, after the parameters they are named by.

use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;
use pyo3::types::PyString;

use crate::errors::arg_err;

/// `obj` as text; `what` names the parameter ("curve 'st': role", "the curve name").
pub(crate) fn text(obj: &Bound<'_, PyAny>, what: impl FnOnce() -> String) -> PyResult<String> {
    let Ok(s) = obj.cast::<PyString>() else {
        return Err(arg_err(format!(
            "{} must be text (str), not {}",
            what(),
            type_name(obj)
        )));
    };
    s.to_str().map(str::to_owned).map_err(|_| {
        arg_err(format!(
            "{} {} is not valid Unicode text (it holds a lone surrogate)",
            what(),
            repr(obj)
        ))
    })
}

/// An optional text parameter (`None` stays `None`).
pub(crate) fn optional_text(
    obj: Option<&Bound<'_, PyAny>>,
    what: impl FnOnce() -> String,
) -> PyResult<Option<String>> {
    obj.filter(|o| !o.is_none())
        .map(|o| text(o, what))
        .transpose()
}

/// A curve's `role` parameter as text, `"free"` when not given.
pub(crate) fn role_or_free(name: &str, role: Option<&Bound<'_, PyAny>>) -> PyResult<String> {
    Ok(optional_text(role, || format!("curve '{name}': role"))?
        .unwrap_or_else(|| "free".to_owned()))
}

/// `obj` as a 2-D float array (a list of rows or any array-like numpy converts).
pub(crate) fn rows<'py>(
    obj: &Bound<'py, PyAny>,
    what: impl FnOnce() -> String,
) -> PyResult<PyArrayLike2<'py, f64, AllowTypeChange>> {
    obj.extract().map_err(|e: PyErr| {
        arg_err(format!(
            "{} must be a 2-D array of numbers (one row per point): {}",
            what(),
            e.value(obj.py())
        ))
    })
}

/// `obj` as a 1-D float array.
pub(crate) fn values<'py>(
    obj: &Bound<'py, PyAny>,
    what: impl FnOnce() -> String,
) -> PyResult<PyArrayLike1<'py, f64, AllowTypeChange>> {
    obj.extract().map_err(|e: PyErr| {
        arg_err(format!(
            "{} must be a 1-D array of numbers: {}",
            what(),
            e.value(obj.py())
        ))
    })
}

/// `obj` as a count: a whole number, not negative, within 64 bits.
pub(crate) fn whole(obj: &Bound<'_, PyAny>, what: impl Fn() -> String) -> PyResult<usize> {
    let value: i64 = obj.extract().map_err(|_| {
        arg_err(format!(
            "{} {} must be a whole number below 2**63",
            what(),
            repr(obj)
        ))
    })?;
    count(value, what)
}

/// An optional count (`None` stays `None`).
pub(crate) fn optional_whole(
    obj: Option<&Bound<'_, PyAny>>,
    what: impl Fn() -> String,
) -> PyResult<Option<usize>> {
    obj.filter(|o| !o.is_none())
        .map(|o| whole(o, what))
        .transpose()
}

/// A whole-number argument taken as `i64` (so that a negative one reaches batten rather than
/// failing Python's conversion with OverflowError) as a count; `what` names the argument and
/// its curve in the `InvalidArgumentError`.
fn count(value: i64, what: impl FnOnce() -> String) -> Result<usize, PyErr> {
    usize::try_from(value).map_err(|_| arg_err(format!("{} {value} must not be negative", what())))
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "an unknown type".to_owned(), |n| n.to_string())
}

fn repr(obj: &Bound<'_, PyAny>) -> String {
    obj.repr()
        .map_or_else(|_| "(unprintable)".to_owned(), |r| r.to_string())
}
