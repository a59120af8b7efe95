//! Progress callbacks from the long core calls (surface fairing, CAD exports) to Python:
//! `progress(done, total)` is called holding the GIL again, from whichever thread the core
//! reports on; returning `False` stops the work, and an exception it raises stops it too and is
//! raised in its place.

use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::PyBool;

use crate::errors::Cancelled;

/// A Python progress callback (or none) and the first error it raised.
pub(crate) struct Progress {
    callback: Option<Py<PyAny>>,
    error: Mutex<Option<PyErr>>,
}

impl Progress {
    /// The callback `callback` (None: the work always goes on).
    pub(crate) fn new(callback: Option<Py<PyAny>>) -> Self {
        Progress {
            callback,
            error: Mutex::new(None),
        }
    }

    /// Whether the work goes on after `done` of `total`: the callback's answer, anything but
    /// `False` going on (so a callback that only shows progress and returns None goes on); an
    /// exception it raises is kept for [`Progress::stopped`] and stops the work.
    pub(crate) fn goes_on(&self, done: usize, total: usize) -> bool {
        let Some(callback) = &self.callback else {
            return true;
        };
        Python::attach(|py| {
            let answer = callback
                .call1(py, (done, total))
                .map(|a| !a.bind(py).is(&*PyBool::new(py, false)));
            answer.unwrap_or_else(|err| {
                let mut slot = self.error.lock().unwrap_or_else(|e| e.into_inner());
                slot.get_or_insert(err);
                false
            })
        })
    }

    /// The error for work the callback stopped: the exception it raised, or `Cancelled` with
    /// `message`.
    pub(crate) fn stopped(self, message: &str) -> PyErr {
        let error = self.error.into_inner().unwrap_or_else(|e| e.into_inner());
        error.unwrap_or_else(|| Cancelled::new_err(message.to_owned()))
    }
}
