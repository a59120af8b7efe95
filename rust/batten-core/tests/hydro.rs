//! Hydrostatics on the patch surface, against analytic values: the Wigley hull (drawn as a lines
//! plan) at T and T/2, a box barge with open ends (closed by their planes) upright, trimmed and
//! heeled, the inverse (floating at a displacement), the convergence of the integration, and the
//! errors.

use batten_core::{
    build_hull, default_datums, float_to, hydrostatics, sectional_areas, CellDensity, Datums,
    Flotation, HullGeometry, HullOptions, HydroError, Hydrostatics, Network, PatchHydroModel,
};
mod common;
use common::{box_barge, example, BB, BD, BL};

const L: f64 = 100.0;
const B: f64 = 10.0;
const T: f64 = 6.25;

fn model_of(net: &Network, density: CellDensity) -> PatchHydroModel {
    let hull = build_hull(net, &HullOptions::default()).expect("builds");
    hull.hydro_model(density)
}

fn figures(geom: &dyn HullGeometry, f: Flotation) -> Hydrostatics {
    let d = default_datums(geom, f.draft, None).expect("datums");
    hydrostatics(geom, &f, &d).expect("hydrostatics")
}

fn close(what: &str, got: f64, want: f64, rel: f64) {
    let err = (got - want).abs() / want.abs().max(1e-300);
    assert!(
        err <= rel,
        "{what}: {got} vs {want} (relative error {err:.2e} > {rel:.0e})"
    );
}

/// The Wigley hull's analytic figures at draft `d` (both sides; the hull y = B/2·(1−ξ²)(1−w²),
/// ξ = 2x/L, w = (T−z)/T): with `k = 1 − ((T−d)/T)²` the waterline's breadth factor,
/// Awp = 2/3·L·B·k, It = 4/105·(kB)³·L, Il = kB·L³/30, ∇ = 2/3·L·B·T·∫_{w_d}^1 (1−w²) dw,
/// KB from ∫ z·Awp(z) dz, Am = B·T·∫_{w_d}^1 (1−w²) dw.
struct Wigley {
    volume: f64,
    kb: f64,
    awp: f64,
    it: f64,
    il: f64,
    am: f64,
    bwl: f64,
}

fn wigley_at(d: f64) -> Wigley {
    let w0 = (T - d) / T;
    let k = 1.0 - w0 * w0;
    let i1 = |w: f64| w - w.powi(3) / 3.0; // ∫(1−w²)
    let i2 = |w: f64| w - w * w / 2.0 - w.powi(3) / 3.0 + w.powi(4) / 4.0; // ∫(1−w)(1−w²)
    let area_int = i1(1.0) - i1(w0);
    let volume = 2.0 / 3.0 * L * B * T * area_int;
    let kb = T * (i2(1.0) - i2(w0)) / area_int;
    Wigley {
        volume,
        kb,
        awp: 2.0 / 3.0 * L * B * k,
        it: 4.0 / 105.0 * (k * B).powi(3) * L,
        il: k * B * L.powi(3) / 30.0,
        am: B * T * area_int,
        bwl: k * B,
    }
}

/// The Wigley hull drawn light (`wigley.json`: 7 stations, 3 waterlines; its ribbons must carry
/// the flare between the stations, measured −0.011 % ∇ at T, −0.032 % at T/2) and as a lines
/// plan (`wigley_lines.json`: 15 × 6, −0.0004 %, −0.001 %), each against the analytic hull.
/// (Its curves' own parameters run with x, the best pairing of points across a face; the
/// patches run the sides at arc length and turning instead, which cost the light drawing
/// −0.008 % → −0.011 % at T and −0.024 % → −0.032 % at T/2.)
#[test]
fn wigley_drawings_match_the_analytic_hull_at_t_and_half_t() {
    for file in ["wigley.json", "wigley_lines.json"] {
        wigley_matches_the_analytic_hull(file);
    }
}

fn wigley_matches_the_analytic_hull(file: &str) {
    let geom = model_of(&example(file), CellDensity::DEFAULT);
    assert!(geom.is_half(), "the Wigley network is a port half");
    for d in [T, 0.5 * T] {
        let h = figures(&geom, Flotation::at_draft(d));
        let w = wigley_at(d);
        let rel = 5e-4; // the 0.05 %
        close("volume", h.volume, w.volume, rel);
        close("KB", h.vcb, w.kb, rel);
        close("Awp", h.waterplane_area, w.awp, rel);
        close("BMt", h.bmt, w.it / w.volume, rel);
        close("BMl", h.bml, w.il / w.volume, rel);
        close("Am", h.midship_area, w.am, rel);
        close("Bwl", h.bwl, w.bwl, rel);
        close("Lwl", h.lwl, L, rel);
        close("Cm", h.cm, w.am / (w.bwl * d), rel);
        close("Cwp", h.cwp, 2.0 / 3.0, rel);
        close("Cp", h.cp, w.volume / (w.am * L), rel);
        close("Cb", h.cb, w.volume / (L * w.bwl * d), rel);
        assert!(h.lcb.abs() < 5e-4 * L, "LCB {} at midships", h.lcb);
        assert!(h.lcf.abs() < 5e-4 * L, "LCF {} at midships", h.lcf);
        assert!(h.tcb.abs() < 1e-12, "TCB {} on the centreline", h.tcb);
        // The waterline y = kB/2·(1 − ξ²) meets the centreline at atan(2kB/L).
        close(
            "entrance",
            h.entrance_half_angle,
            (2.0 * w.bwl / L).atan().to_degrees(),
            2e-3, // 0.0120° off at T/2 of the light drawing, between its waterlines
        );
        close("Δ", h.displacement, 1.025 * h.volume, 1e-15);
        close("TPC", h.tpc, 1.025 * h.waterplane_area / 100.0, 1e-15);
        assert!(
            h.transom_area < 1e-3,
            "a pointed stern has no transom: {}",
            h.transom_area
        );
    }
}

#[test]
fn integration_converges_to_1e_9_on_the_wigley_hull_and_the_frigate() {
    // Measured (coarse against fine): the lines plan 1e-11 at every draft; the light 7 × 3
    // drawing, whose patches are four times the size (same cells per patch), 1e-11 at T and
    // T/2 and 2.6e-9 for Il at 0.37 T, a waterline just above a drawn one, through the cells
    // at the patches' corners at the stem and stern. The frigate's composite sides leave
    // parameter lines where its patches are only C0 in parameter speed: 1.4e-9 for It at 4 m.
    for (file, drafts) in [
        (
            "wigley_lines.json",
            [(T, 1e-9), (0.5 * T, 1e-9), (0.37 * T, 1e-9)],
        ),
        (
            "wigley.json",
            [(T, 1e-9), (0.5 * T, 1e-9), (0.37 * T, 1e-8)],
        ),
        (
            "frigate_network.json",
            [(4.0, 1e-8), (3.1, 1e-8), (5.3, 1e-8)],
        ),
    ] {
        let net = example(file);
        let coarse = model_of(&net, CellDensity::DEFAULT);
        let fine = model_of(
            &net,
            CellDensity {
                per_quad: 4,
                corner_levels: 5,
            },
        );
        let d = default_datums(&coarse, drafts[0].0, None).expect("datums");
        for (t, rel) in drafts {
            let plane = batten_core::Waterplane::new(&Flotation::at_draft(t), &d);
            let (a, b) = (coarse.wet_integrals(&plane), fine.wet_integrals(&plane));
            for (what, x, y) in [
                ("volume", a.volume, b.volume),
                ("∫ζ dV", a.v_zeta, b.v_zeta),
                ("Awp", a.wp_area, b.wp_area),
                ("Il", a.wp_xixi, b.wp_xixi),
                ("It", a.wp_etaeta, b.wp_etaeta),
                ("S", a.wetted, b.wetted),
            ] {
                close(&format!("{file} at {t}: {what}"), x, y, rel);
            }
        }
    }
}

fn box_datums() -> Datums {
    Datums {
        x_ap: 0.0,
        x_fp: BL,
    }
}

#[test]
fn box_barge_with_open_ends_is_exact() {
    let geom = model_of(&box_barge(true), CellDensity::DEFAULT);
    let t = 2.0;
    let h = hydrostatics(&geom, &Flotation::at_draft(t), &box_datums()).expect("floats");
    let v = BL * BB * t;
    let rel = 1e-9;
    close("∇", h.volume, v, rel);
    close("KB", h.vcb, t / 2.0, rel);
    close("BMt", h.bmt, BB * BB / (12.0 * t), rel);
    close("BMl", h.bml, BL * BL / (12.0 * t), rel);
    close("Awp", h.waterplane_area, BL * BB, rel);
    close("LCB", h.lcb, BL / 2.0, rel);
    close("LCF", h.lcf, BL / 2.0, rel);
    close("S", h.wetted_area, BL * BB + 2.0 * BL * t, rel);
    close("Am", h.midship_area, BB * t, rel);
    close("Cb", h.cb, 1.0, rel);
    close("transom", h.transom_area, BB * t, 1e-6);
    close("MTC", h.mtc, h.displacement * h.bml / (100.0 * BL), 1e-15);
    let xs = [1.0, 10.0, 20.0, 39.0];
    let f = Flotation::at_draft(t);
    for (x, a) in xs
        .iter()
        .zip(sectional_areas(&geom, &f, &box_datums(), &xs).expect("SAC"))
    {
        close(&format!("A({x})"), a, BB * t, rel);
    }
}

#[test]
fn box_barge_trimmed_and_heeled_keeps_its_volume_where_the_analysis_says() {
    let geom = model_of(&box_barge(true), CellDensity::DEFAULT);
    // Trim 1 m by the stern about midships: the wedges cancel, ∇ and Awp stay, the centre
    // moves aft by L²·tanθ/(12·T) along the water.
    let t = 2.0;
    let f = Flotation {
        trim: 1.0,
        ..Flotation::at_draft(t)
    };
    let h = hydrostatics(&geom, &f, &box_datums()).expect("trimmed");
    close("∇ trimmed", h.volume, BL * BB * t, 1e-9);
    close("T_AP", h.draft_ap, t + 0.5, 1e-12);
    close("T_FP", h.draft_fp, t - 0.5, 1e-12);
    let tan = 1.0 / BL;
    let shift = BL * BL * tan / (12.0 * t);
    assert!(
        (h.lcb - (BL / 2.0 - shift)).abs() < 2e-3 * shift,
        "LCB {} vs {}",
        h.lcb,
        BL / 2.0 - shift
    );
    // Heel 10° (a wall-sided box, the deck edge dry): ∇ stays, TCB = (B²/12T)·tanφ to starboard.
    let phi = 10f64.to_radians();
    let f = Flotation {
        heel_deg: 10.0,
        ..Flotation::at_draft(t)
    };
    let h = hydrostatics(&geom, &f, &box_datums()).expect("heeled");
    close("∇ heeled", h.volume, BL * BB * t, 1e-9);
    let tcb = -(BB * BB / (12.0 * t)) * phi.tan();
    assert!((h.tcb - tcb).abs() < 1e-9 * BB, "TCB {} vs {tcb}", h.tcb);
}

#[test]
fn float_to_finds_the_draft_and_trim_of_a_box() {
    let geom = model_of(&box_barge(true), CellDensity::DEFAULT);
    let disp = 1.025 * BL * BB * 2.5;
    let f = float_to(&geom, &box_datums(), disp, BL / 2.0, None, 1.025).expect("floats level");
    close("draft", f.draft, 2.5, 1e-9);
    assert!(f.trim.abs() < 1e-9, "level: trim {}", f.trim);
    // G 1 m aft of midships: trimmed by the stern until LCB is under G.
    let f =
        float_to(&geom, &box_datums(), disp, BL / 2.0 - 1.0, None, 1.025).expect("floats trimmed");
    assert!(f.trim > 0.0, "by the stern: {}", f.trim);
    let h = hydrostatics(&geom, &f, &box_datums()).expect("there");
    close("Δ", h.displacement, disp, 1e-9);
    assert!(
        (h.lcb - (BL / 2.0 - 1.0)).abs() < 1e-8,
        "LCB {} under G",
        h.lcb
    );
    assert!(
        matches!(
            float_to(&geom, &box_datums(), 1e9, BL / 2.0, None, 1.025),
            Err(HydroError::InvalidInput(_))
        ),
        "more than it holds"
    );
}

#[test]
fn bad_flotations_are_refused_by_name() {
    let geom = model_of(&box_barge(true), CellDensity::DEFAULT);
    let d = box_datums();
    let err = |f: Flotation| hydrostatics(&geom, &f, &d).expect_err("refused");
    assert!(matches!(
        err(Flotation::at_draft(-1.0)),
        HydroError::DraftBelowKeel { .. }
    ));
    assert!(matches!(
        err(Flotation::at_draft(f64::NAN)),
        HydroError::InvalidInput(_)
    ));
    assert!(matches!(
        err(Flotation {
            density: 0.0,
            ..Flotation::at_draft(2.0)
        }),
        HydroError::InvalidInput(_)
    ));
    assert!(matches!(
        err(Flotation {
            heel_deg: 90.0,
            ..Flotation::at_draft(2.0)
        }),
        HydroError::InvalidInput(_)
    ));
    let over = err(Flotation::at_draft(BD + 1.0));
    assert!(matches!(over, HydroError::DraftAboveTop { .. }), "{over}");
    assert!(
        hydrostatics(
            &geom,
            &Flotation::at_draft(2.0),
            &Datums {
                x_ap: 5.0,
                x_fp: 5.0
            }
        )
        .is_err(),
        "Lpp 0"
    );
}

#[test]
fn a_hole_under_water_is_an_error_naming_where() {
    let geom = model_of(&box_barge(false), CellDensity::DEFAULT);
    let e = hydrostatics(&geom, &Flotation::at_draft(2.0), &box_datums()).expect_err("a hole");
    match &e {
        HydroError::HoleBelowWater { x, z, .. } => {
            assert!(
                *x <= BL / 2.0 + 1e-9 && z.abs() < 1e-9,
                "on the aft half of the bottom: {e}"
            );
        }
        other => panic!("expected a hole, got {other}"),
    }
    assert!(e.to_string().contains("hole below the waterline"), "{e}");
}

#[test]
fn the_frigate_floats_with_its_open_transom_closed_and_a_fine_entrance() {
    let geom = model_of(&example("frigate_network.json"), CellDensity::DEFAULT);
    let h = figures(&geom, Flotation::at_draft(4.0));
    // Its transom (x = 0) is open: the cap closes it, and the section just forward of it is the
    // immersed transom.
    assert!(h.transom_area > 1.0, "immersed transom {}", h.transom_area);
    assert!(
        (5.0..30.0).contains(&h.entrance_half_angle),
        "half angle of entrance {}°",
        h.entrance_half_angle
    );
    assert!(
        h.cb > 0.3 && h.cb < 0.7 && h.cp > h.cb,
        "Cb {} Cp {}",
        h.cb,
        h.cp
    );
}
