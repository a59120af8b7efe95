//! Hydrostatics on the patch surface (exact cells, [`CellDensity::DEFAULT`]) at the design
//! draft: the whole set of figures, and its parts — the waterline section, the wet surface's
//! integrals, one station's immersed area — for the frigate (examples/) and the real ships.
//!
//! The real ships' networks are made by the section import of the add-on, so they are read from
//! `build/ship_networks/{kcs,kvlcc2}.json`, written by
//! `PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/export_ship_networks.py`
//! (skipped, with a note, when absent); their drafts and perpendiculars come from
//! `../shared/hulls/<ship>/network.json`. KVLCC2's fitted design waterline wavers about `z = T`,
//! the hardest case for the clipping.
#![allow(missing_docs)]

use std::path::{Path, PathBuf};

use batten_core::{
    build_hull, default_datums, hydrostatics, immersed_section_area, CellDensity, Datums,
    Flotation, HullGeometry, HullOptions, Network, PatchHydroModel, Waterplane,
    SECTION_TOLERANCE_RELATIVE,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A hull to time: its model, flotation and perpendiculars.
struct Case {
    name: &'static str,
    model: PatchHydroModel,
    flotation: Flotation,
    datums: Datums,
}

fn model_of(path: &Path) -> Option<PatchHydroModel> {
    let text = std::fs::read_to_string(path).ok()?;
    let net = Network::from_json(&text).expect("a valid network");
    let hull = build_hull(&net, &HullOptions::default()).expect("builds");
    Some(hull.hydro_model(CellDensity::DEFAULT))
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let frigate = model_of(&root().join("examples/frigate_network.json")).expect("frigate");
    let flotation = Flotation::at_draft(4.0);
    let datums = default_datums(&frigate, 4.0, None).expect("datums");
    out.push(Case {
        name: "frigate",
        model: frigate,
        flotation,
        datums,
    });
    for name in ["kcs", "kvlcc2"] {
        let path = root().join(format!("build/ship_networks/{name}.json"));
        let Some(model) = model_of(&path) else {
            eprintln!(
                "{}: not found (blender_scripts/export_ship_networks.py writes it); skipped",
                path.display()
            );
            continue;
        };
        let src = root().join(format!("../shared/hulls/{name}/network.json"));
        let data: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(src).expect("ship data")).expect("json");
        let (lpp, t) = (
            data["Lpp"].as_f64().expect("Lpp"),
            data["T"].as_f64().expect("T"),
        );
        out.push(Case {
            name,
            model,
            flotation: Flotation::at_draft(t),
            datums: Datums {
                x_ap: 0.0,
                x_fp: lpp,
            },
        });
    }
    out
}

fn bench_hydro(c: &mut Criterion) {
    for case in cases() {
        let (model, f, d) = (&case.model, &case.flotation, &case.datums);
        let plane = Waterplane::new(f, d);
        let (lo, hi) = model.bounds();
        let tol = SECTION_TOLERANCE_RELATIVE * (hi - lo).length();
        let level = plane.e3.dot(plane.origin);
        c.bench_function(&format!("hydrostatics/{}", case.name), |b| {
            b.iter(|| hydrostatics(black_box(model), f, d).expect("figures"))
        });
        c.bench_function(&format!("hydro_waterline/{}", case.name), |b| {
            b.iter(|| model.plane_section(black_box(plane.e3), level, tol))
        });
        c.bench_function(&format!("hydro_wet_integrals/{}", case.name), |b| {
            b.iter(|| model.wet_integrals(black_box(&plane)))
        });
        c.bench_function(&format!("hydro_station/{}", case.name), |b| {
            b.iter(|| immersed_section_area(model, &plane, glam::DVec3::X, d.x_mid(), tol))
        });
    }
    // A degenerate input: the frigate with the water below its keel.
    let frigate = &cases()[0];
    c.bench_function("hydrostatics/frigate_below_keel", |b| {
        b.iter(|| {
            hydrostatics(
                &frigate.model,
                &Flotation::at_draft(-1.0),
                black_box(&frigate.datums),
            )
            .expect_err("below the keel")
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bench_hydro
}
criterion_main!(benches);
