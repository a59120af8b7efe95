//! The CAD export on the example hulls: every patch approximated within the tolerance at
//! points the fit never looked at, neighbouring faces meeting on their shared curves, and the
//! files well formed.

use batten_core::{
    build_hull, cad_surface, cad_surface_with, iges_text, step_text, CadHeader, ExportError,
    ExportOptions, HullOptions, BOUNDARY_SHARE,
};
mod common;
use common::example;

/// Wigley and the frigate: one face per quad, every face within half the tolerance at its
/// check samples (the read-back tests measure the whole tolerance densely), files well formed.
#[test]
fn the_examples_export_within_the_tolerance() {
    for file in ["wigley_lines.json", "frigate_network.json"] {
        let hull = build_hull(&example(file), &HullOptions::default()).expect("builds");
        let t = std::time::Instant::now();
        let cad = cad_surface(&hull, &ExportOptions::default()).expect("exports");
        let quads: usize = hull
            .patches
            .iter()
            .map(|p| if p.sides() == 4 { 1 } else { p.sides() })
            .sum();
        assert_eq!(cad.faces.len(), quads, "{file}: one face per quad");
        assert!(
            cad.max_deviation <= 0.5e-4,
            "{file}: deviation {}",
            cad.max_deviation
        );
        let points: usize = cad.faces.iter().map(|f| f.surface.control.len()).sum();
        eprintln!(
            "{file}: {} patches, {} faces, {points} control points, max deviation {:.2e} m, {:.0} ms",
            cad.patches,
            cad.faces.len(),
            cad.max_deviation,
            t.elapsed().as_secs_f64() * 1e3
        );
        let iges = iges_text(&cad, &CadHeader::default());
        let step = step_text(&cad, &CadHeader::default());
        assert!(iges.lines().all(|l| l.len() == 80), "{file}: IGES records");
        assert_eq!(
            step.matches("ADVANCED_FACE(").count(),
            cad.faces.len(),
            "{file}: STEP faces"
        );
    }
}

#[test]
fn a_bad_tolerance_is_refused() {
    let hull = build_hull(&example("wigley_lines.json"), &HullOptions::default()).expect("builds");
    for tol in [0.0, -1.0, f64::NAN] {
        let options = ExportOptions {
            tolerance: tol,
            allow_holes: false,
        };
        assert!(
            matches!(cad_surface(&hull, &options), Err(ExportError::Tolerance(_))),
            "tolerance {tol} refused"
        );
    }
}

/// A tolerance no cubic edge reaches within the most spans (only straight ones fit): the
/// patches are refused, each by its topology face with what its fits reached, in patch order,
/// and the message says how many of how many.
#[test]
fn the_patches_whose_curves_cannot_be_fitted_are_named() {
    let hull =
        build_hull(&example("frigate_network.json"), &HullOptions::default()).expect("builds");
    let options = ExportOptions {
        tolerance: 1e-13,
        allow_holes: false,
    };
    let Err(err @ ExportError::NotConverged { .. }) = cad_surface(&hull, &options) else {
        panic!("a tolerance of 1e-13 m is refused as not converged");
    };
    let ExportError::NotConverged { faces, patches, .. } = &err else {
        unreachable!("matched above");
    };
    let named: Vec<usize> = faces.0.iter().map(|u| u.face).collect();
    assert!(
        named.len() > hull.patches.len() / 2,
        "most patches: {named:?} of {:?}",
        hull.patch_faces
    );
    assert!(
        named.windows(2).all(|w| w[0] < w[1]) && named.iter().all(|f| hull.patch_faces.contains(f)),
        "patches' faces, in order: {named:?}"
    );
    assert_eq!(*patches, hull.patches.len(), "out of all patches");
    assert!(
        faces.0.iter().all(|u| u.deviation > BOUNDARY_SHARE * 1e-13),
        "each with a deviation above its curves' share of the tolerance: {faces:?}"
    );
    let message = err.to_string();
    assert!(
        message.starts_with(&format!(
            "{} of {} patches",
            named.len(),
            hull.patches.len()
        )),
        "{message}"
    );
}

/// Each fitted face is reported once with the number of faces, and a callback that says stop
/// ends the export early with nothing: no face is started after it.
#[test]
fn the_fitting_reports_each_face_and_stops_when_told() {
    use std::sync::Mutex;
    let hull = build_hull(&example("wigley_lines.json"), &HullOptions::default()).expect("builds");
    let calls = Mutex::new(Vec::new());
    let all = cad_surface_with(&hull, &ExportOptions::default(), &|done, total| {
        calls.lock().expect("calls").push((done, total));
        true
    })
    .expect("exports")
    .expect("not stopped");
    let mut seen = calls.into_inner().expect("calls");
    let n = all.faces.len();
    assert!(seen.iter().all(|&(_, t)| t == n), "the total is the faces");
    seen.sort_unstable();
    assert_eq!(
        seen.iter().map(|&(d, _)| d).collect::<Vec<_>>(),
        (1..=n).collect::<Vec<_>>(),
        "each count once"
    );
    let calls = Mutex::new(0usize);
    let stopped = cad_surface_with(&hull, &ExportOptions::default(), &|_, _| {
        let mut c = calls.lock().expect("calls");
        *c += 1;
        *c < 3
    })
    .expect("no error");
    assert!(stopped.is_none(), "stopped: no surface");
    let calls = calls.into_inner().expect("calls");
    let threads = rayon::current_num_threads();
    assert!(
        (3..3 + threads).contains(&calls) && calls < n,
        "{calls} faces fitted of {n}, with {threads} workers"
    );
}
