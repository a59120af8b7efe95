//! The fuzz suite of the core (issue 21): property-based fuzzing of the curve kernel, the
//! network builder and the fitter, every call under a time limit (`common::fuzz::within`).
//!
//! `make test` runs each target's short budget; `make fuzz` sets `BATTEN_FUZZ_CASES` high and
//! repeats with fresh seeds for as long as asked. Failures persist beside each target
//! (`tests/fuzz/<target>.proptest-regressions`) and are replayed first on every run.

#[path = "../common/mod.rs"]
mod common;

mod curve;
mod fit;
mod network;
