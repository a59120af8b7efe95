//! The fuzz suite's budget, watchdog and number strategies (issue 21): every call of a fuzz
//! case runs under [`within`], so a hang fails the case naming the call and its input instead
//! of freezing the run.

use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::Duration;

use glam::DVec3;
use proptest::prelude::*;

/// The environment variable that sets the number of cases of every fuzz target (`make fuzz`
/// sets it high; `make test` leaves it unset and runs each target's short budget).
pub(crate) const CASES_VAR: &str = "BATTEN_FUZZ_CASES";

/// The environment variable that sets the per-call time limit in seconds.
pub(crate) const CASE_SECONDS_VAR: &str = "BATTEN_FUZZ_CASE_SECONDS";

/// A call of the core that takes longer than this is a hang. Generous for a dev build on a
/// shared two-core machine: the slowest ordinary case (a hull of a 6 × 6 grid) takes ~0.1 s.
const DEFAULT_CASE_SECONDS: f64 = 2.0;

/// Proptest stops shrinking a failure after this long: a hang costs the limit per attempt, and
/// the first failing input (printed as well) is already a reproducer.
const MAX_SHRINK_MS: u32 = 60_000;

/// The proptest configuration of a fuzz target: `short` cases unless [`CASES_VAR`] says how
/// many, failures persisted beside the suite like every other proptest suite.
pub(crate) fn fuzz_config(short: u32) -> proptest::test_runner::Config {
    let cases = std::env::var(CASES_VAR)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(short);
    proptest::test_runner::Config {
        max_shrink_time: MAX_SHRINK_MS,
        ..super::proptest_config(cases)
    }
}

fn case_limit() -> Duration {
    let seconds = std::env::var(CASE_SECONDS_VAR)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASE_SECONDS);
    Duration::from_secs_f64(seconds)
}

/// Run `f` on a watchdog thread: its result, or a panic saying `what` hung (took longer than
/// the case limit) or panicked. `what` should carry the input, so the failure is its own
/// reproducer.
pub(crate) fn within<T: Send + 'static>(
    what: impl Fn() -> String,
    f: impl FnOnce() -> T + Send + 'static,
) -> T {
    let limit = case_limit();
    let (tx, rx) = channel();
    let worker = std::thread::spawn(move || {
        // The receiver is gone only after a timeout, which has already failed the case.
        let _ = tx.send(f());
    });
    match rx.recv_timeout(limit) {
        Ok(value) => {
            worker.join().expect("the worker sent its result and ended");
            value
        }
        Err(RecvTimeoutError::Timeout) => panic!("hang: {} took more than {limit:?}", what()),
        Err(RecvTimeoutError::Disconnected) => {
            let payload = worker
                .join()
                .expect_err("a worker that sent nothing panicked");
            let detail = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            panic!("panic in {}: {detail}", what())
        }
    }
}

/// A length scale from subnormal to 1e200 metres, weighted towards ordinary sizes.
pub(crate) fn scale() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => Just(1.0),
        4 => (-3i32..=3).prop_map(|e| 10f64.powi(e)),
        4 => (-300i32..=200).prop_map(|e| 10f64.powi(e)),
        1 => Just(f64::MIN_POSITIVE),
        1 => Just(5e-324),
    ]
}

/// An offset of the data from the origin: none, georeferenced (1e7 m), or beyond f64's
/// resolution of ordinary sizes (1e17).
pub(crate) fn offset() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => Just(0.0),
        2 => -1e3f64..1e3,
        1 => Just(1e7),
        1 => Just(-1e7),
        1 => Just(1e17),
    ]
}

/// A 3D offset with each coordinate from [`offset`].
pub(crate) fn offset3() -> impl Strategy<Value = DVec3> {
    (offset(), offset(), offset()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A point of the unit cube about the origin, sometimes exactly on an axis plane (repeated
/// coordinates make coincident and collinear control points).
pub(crate) fn unit_point() -> impl Strategy<Value = DVec3> {
    let c = || prop_oneof![6 => -1.0f64..1.0, 1 => Just(0.0), 1 => Just(1.0)];
    (c(), c(), c()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// True when every coordinate of every point is finite.
pub(crate) fn all_finite(points: &[DVec3]) -> bool {
    points.iter().all(|p| p.is_finite())
}
