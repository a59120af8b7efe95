//! Hydrostatics of triangle meshes ([`TriangleHull`]): a box barge exact (upright, heeled,
//! trimmed; half and full; either winding), a sphere within its mesh error, and bad input,
//! holes and drafts out of range as errors.

mod common;

use std::collections::HashMap;
use std::f64::consts::PI;

use batten_core::{
    default_datums, hydrostatics, sectional_areas, Datums, Flotation, HullGeometry, HydroError,
    Hydrostatics, TriangleHull,
};
use glam::DVec3;

/// A mesh welded on an integer lattice (vertices shared where faces meet), scaled to metres.
struct Lattice {
    scale: DVec3,
    index: HashMap<[i64; 3], u32>,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl Lattice {
    fn new(scale: DVec3) -> Lattice {
        Lattice {
            scale,
            index: HashMap::new(),
            positions: Vec::new(),
            triangles: Vec::new(),
        }
    }

    fn vertex(&mut self, k: [i64; 3]) -> u32 {
        let next = self.positions.len() as u32;
        let scale = self.scale;
        *self.index.entry(k).or_insert_with(|| {
            self.positions
                .push(DVec3::new(k[0] as f64, k[1] as f64, k[2] as f64) * scale);
            next
        })
    }

    /// The rectangle `o + i u + j v` (`0 ≤ i ≤ nu`, `0 ≤ j ≤ nv`), outward along `u × v`.
    fn face(&mut self, o: [i64; 3], u: [i64; 3], nu: i64, v: [i64; 3], nv: i64) {
        let at = |i: i64, j: i64| [0, 1, 2].map(|c| o[c] + i * u[c] + j * v[c]);
        for i in 0..nu {
            for j in 0..nv {
                let p00 = self.vertex(at(i, j));
                let p10 = self.vertex(at(i + 1, j));
                let p11 = self.vertex(at(i + 1, j + 1));
                let p01 = self.vertex(at(i, j + 1));
                self.triangles.push([p00, p10, p11]);
                self.triangles.push([p00, p11, p01]);
            }
        }
    }
}

const L: f64 = 20.0;
const B: f64 = 6.0;
const D: f64 = 4.0;
const T: f64 = 1.3;
const NX: i64 = 10;
const NY: i64 = 3;
const NZ: i64 = 8;

/// A box barge `0 ≤ x ≤ L`, `|y| ≤ B/2`, `0 ≤ z ≤ D`: the port half only (open along the
/// centreplane) when `half`, without its deck when `open_top`.
fn box_mesh(half: bool, open_top: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut m = Lattice::new(DVec3::new(
        L / NX as f64,
        0.5 * B / NY as f64,
        D / NZ as f64,
    ));
    let (y0, ny) = if half { (0, NY) } else { (-NY, 2 * NY) };
    let (x, y, z) = ([1, 0, 0], [0, 1, 0], [0, 0, 1]);
    m.face([0, y0, 0], y, ny, x, NX); // bottom, −z
    if !open_top {
        m.face([0, y0, NZ], x, NX, y, ny); // deck, +z
    }
    m.face([0, NY, 0], z, NZ, x, NX); // port side, +y
    if !half {
        m.face([0, -NY, 0], x, NX, z, NZ); // starboard side, −y
    }
    m.face([NX, y0, 0], y, ny, z, NZ); // fore end, +x
    m.face([0, y0, 0], z, NZ, y, ny); // aft end, −x
    (m.positions, m.triangles)
}

fn hull(mesh: &(Vec<DVec3>, Vec<[u32; 3]>)) -> TriangleHull {
    TriangleHull::try_new(&mesh.0, &mesh.1).expect("a valid mesh")
}

const PERPENDICULARS: Datums = Datums { x_ap: 0.0, x_fp: L };

fn at(geom: &TriangleHull, flotation: Flotation) -> Result<Hydrostatics, HydroError> {
    hydrostatics(geom, &flotation, &PERPENDICULARS)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Assert `a` is `b` to `tol` relative (absolute when `b` is 0).
fn assert_rel(a: f64, b: f64, tol: f64, what: &str) {
    let d = if b == 0.0 { a.abs() } else { rel(a, b) };
    assert!(d <= tol, "{what}: {a} vs {b} ({d:e} > {tol:e})");
}

const EXACT: f64 = 1e-12;

#[test]
fn an_upright_box_barge_is_exact() {
    let geom = hull(&box_mesh(false, false));
    assert!(
        !geom.is_half() && !geom.was_reversed(),
        "a closed, outward box"
    );
    let h = at(&geom, Flotation::at_draft(T)).expect("the box floats");
    assert_rel(h.volume, L * B * T, EXACT, "volume");
    assert_rel(h.displacement, 1.025 * L * B * T, EXACT, "displacement");
    assert_rel(h.vcb, T / 2.0, EXACT, "KB");
    assert_rel(h.bmt, B * B / (12.0 * T), EXACT, "BMt");
    assert_rel(h.bml, L * L / (12.0 * T), EXACT, "BMl");
    assert_rel(h.waterplane_area, L * B, EXACT, "Awp");
    assert_rel(h.lcf, L / 2.0, EXACT, "LCF");
    assert_rel(h.lcb, L / 2.0, EXACT, "LCB");
    assert!(h.tcb.abs() < EXACT * B, "TCB {}", h.tcb);
    assert_rel(
        h.wetted_area,
        L * B + 2.0 * L * T + 2.0 * B * T,
        EXACT,
        "wetted area",
    );
    assert_rel(h.midship_area, B * T, EXACT, "Am");
    assert_rel(h.max_section_area, B * T, EXACT, "Ax");
    assert_rel(h.transom_area, B * T, EXACT, "transom");
    assert_rel(h.lwl, L, EXACT, "Lwl");
    assert_rel(h.bwl, B, EXACT, "Bwl");
    assert_rel(h.los, L, EXACT, "LOS");
    for (c, what) in [(h.cb, "Cb"), (h.cm, "Cm"), (h.cp, "Cp"), (h.cwp, "Cwp")] {
        assert_rel(c, 1.0, EXACT, what);
    }
    assert_rel(h.tpc, 1.025 * L * B / 100.0, EXACT, "TPC");
}

#[test]
fn half_and_full_boxes_give_the_same_figures_upright_and_heeled() {
    let full = hull(&box_mesh(false, false));
    let half = hull(&box_mesh(true, true));
    assert!(half.is_half(), "open along y = 0: a half hull");
    let (lo, hi) = half.bounds();
    assert_rel(
        lo.y,
        -B / 2.0,
        EXACT,
        "the half's bounds include its mirror",
    );
    assert_rel(hi.y, B / 2.0, EXACT, "bounds");
    for heel_deg in [0.0, 5.0, -7.0] {
        let f = Flotation {
            heel_deg,
            ..Flotation::at_draft(T)
        };
        let (a, b) = (at(&full, f).expect("full"), at(&half, f).expect("half"));
        let pairs = [
            (a.volume, b.volume, "volume"),
            (a.lcb, b.lcb, "LCB"),
            (a.vcb, b.vcb, "VCB"),
            (a.bmt, b.bmt, "BMt"),
            (a.bml, b.bml, "BMl"),
            (a.waterplane_area, b.waterplane_area, "Awp"),
            (a.wetted_area, b.wetted_area, "S"),
            (a.midship_area, b.midship_area, "Am"),
        ];
        for (x, y, what) in pairs {
            assert_rel(x, y, 1e-11, &format!("{what} at heel {heel_deg}°"));
        }
        assert!(
            (a.tcb - b.tcb).abs() < 1e-11 * B,
            "TCB at heel {heel_deg}°: {} vs {}",
            a.tcb,
            b.tcb
        );
    }
}

#[test]
fn a_heeled_box_keeps_its_volume_and_moves_its_centre_of_buoyancy() {
    // Heel to starboard by φ: the immersed section is a trapezoid of depth T − y·tan φ, so
    // ∇ = LBT, TCB = −tan φ·B²/(12T), KB = T/2 + tan²φ·B²/(24T).
    for geom in [hull(&box_mesh(false, false)), hull(&box_mesh(true, true))] {
        let heel_deg: f64 = 6.0;
        let t = heel_deg.to_radians().tan();
        let h = at(
            &geom,
            Flotation {
                heel_deg,
                ..Flotation::at_draft(T)
            },
        )
        .expect("heeled");
        assert_rel(h.volume, L * B * T, EXACT, "volume conserved");
        assert_rel(h.tcb, -t * B * B / (12.0 * T), 1e-11, "TCB");
        assert_rel(h.vcb, T / 2.0 + t * t * B * B / (24.0 * T), 1e-11, "KB");
        // The waterplane: the box's section by the inclined plane, B/cos φ wide.
        assert_rel(
            h.waterplane_area,
            L * B / heel_deg.to_radians().cos(),
            1e-11,
            "Awp",
        );
    }
}

#[test]
fn a_trimmed_box_keeps_its_volume_and_moves_its_centre_aft() {
    // Trim by the stern t over Lpp = L: depth T + (L/2 − x)·t/L, so ∇ = LBT and
    // LCB = L/2 − t·L/(12T).
    let trim = 0.8;
    let geom = hull(&box_mesh(true, true));
    let h = at(
        &geom,
        Flotation {
            trim,
            ..Flotation::at_draft(T)
        },
    )
    .expect("trimmed");
    assert_rel(h.volume, L * B * T, EXACT, "volume conserved");
    assert_rel(h.lcb, L / 2.0 - trim * L / (12.0 * T), EXACT, "LCB");
    assert_rel(h.draft_ap, T + trim / 2.0, EXACT, "T_AP");
    assert_rel(h.draft_fp, T - trim / 2.0, EXACT, "T_FP");
    assert_rel(
        h.wetted_area,
        L * B + 2.0 * L * T + 2.0 * B * T,
        EXACT,
        "S (the ends' extra and missing depth cancel)",
    );
    let areas = sectional_areas(
        &geom,
        &Flotation {
            trim,
            ..Flotation::at_draft(T)
        },
        &PERPENDICULARS,
        &[0.25 * L, 0.5 * L, 0.0, L],
    )
    .expect("stations");
    assert_rel(areas[0], B * (T + 0.25 * trim), EXACT, "A at L/4");
    assert_rel(areas[1], B * T, EXACT, "A at midships");
    // Stations in the box's end faces are taken from the inside: the ends' areas.
    assert_rel(areas[2], B * (T + 0.5 * trim), EXACT, "A at the aft end");
    assert_rel(areas[3], B * (T - 0.5 * trim), EXACT, "A at the fore end");
}

#[test]
fn a_reversed_box_gives_the_same_figures() {
    let (p, mut t) = box_mesh(false, false);
    for tri in &mut t {
        tri.swap(0, 1);
    }
    let geom = TriangleHull::try_new(&p, &t).expect("valid");
    assert!(geom.was_reversed(), "an inward mesh is reversed");
    let h = at(&geom, Flotation::at_draft(T)).expect("floats");
    assert_rel(h.volume, L * B * T, EXACT, "volume");
    assert_rel(h.bmt, B * B / (12.0 * T), EXACT, "BMt");
}

#[test]
fn the_default_perpendiculars_are_the_waterline_ends() {
    let geom = hull(&box_mesh(true, true));
    let d = default_datums(&geom, T, None).expect("datums");
    assert_rel(d.x_fp, L, EXACT, "FP at the stem");
    assert!(d.x_ap.abs() < EXACT * L, "AP at the stern: {}", d.x_ap);
    let d = default_datums(&geom, T, Some(15.0)).expect("datums");
    assert_rel(d.x_ap, L - 15.0, EXACT, "AP Lpp aft of FP");
}

/// A UV sphere of radius `r` about `(0, 0, r)`: `lon` segments round, `lat` rings from pole to
/// pole (an even number, so the equator is a ring of vertices).
fn sphere(r: f64, lon: u32, lat: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = vec![DVec3::new(0.0, 0.0, 0.0)];
    for i in 1..lat {
        let th = PI * i as f64 / lat as f64;
        for j in 0..lon {
            let ph = 2.0 * PI * j as f64 / lon as f64;
            p.push(DVec3::new(
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r - r * th.cos(),
            ));
        }
    }
    p.push(DVec3::new(0.0, 0.0, 2.0 * r));
    let top = p.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * lon + j % lon;
    let mut t = Vec::new();
    for j in 0..lon {
        // Bottom cap (outward is −z there) and top cap.
        t.push([0, ring(1, j + 1), ring(1, j)]);
        t.push([top, ring(lat - 1, j), ring(lat - 1, j + 1)]);
    }
    for i in 1..lat - 1 {
        for j in 0..lon {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j + 1),
                ring(i + 1, j),
            );
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (p, t)
}

#[test]
fn a_fine_sphere_floats_within_its_mesh_error() {
    let (r, lon, lat) = (2.0, 256, 128);
    let geom = hull(&sphere(r, lon, lat));
    assert!(!geom.was_reversed(), "outward");
    let datums = Datums { x_ap: -r, x_fp: r };
    let h = hydrostatics(&geom, &Flotation::at_draft(r), &datums).expect("floats");
    // The waterplane at the equator is the inscribed polygon: exact.
    let n = lon as f64;
    assert_rel(
        h.waterplane_area,
        0.5 * n * r * r * (2.0 * PI / n).sin(),
        EXACT,
        "Awp, the inscribed polygon",
    );
    // The rest within the mesh error, (2π/n)² ≈ 6e-4.
    let mesh_error = 1e-3;
    assert_rel(h.volume, 2.0 / 3.0 * PI * r.powi(3), mesh_error, "volume");
    assert_rel(h.vcb, 5.0 * r / 8.0, mesh_error, "KB");
    assert_rel(h.bmt, 3.0 * r / 8.0, mesh_error, "BMt");
    assert_rel(h.wetted_area, 2.0 * PI * r * r, mesh_error, "S");
    // A cap of depth 0.7r: ∇ = π h² (3r − h)/3.
    let d = 0.7 * r;
    let h = hydrostatics(&geom, &Flotation::at_draft(d), &datums).expect("floats");
    assert_rel(
        h.volume,
        PI * d * d * (3.0 * r - d) / 3.0,
        mesh_error,
        "cap volume",
    );
}

#[test]
fn bad_meshes_are_refused_naming_the_fault() {
    let (mut p, t) = box_mesh(false, false);
    let err = |p: &[DVec3], t: &[[u32; 3]]| match TriangleHull::try_new(p, t) {
        Err(HydroError::InvalidInput(m)) => m,
        other => panic!("expected InvalidInput, got {other:?}"),
    };
    assert!(err(&p, &[]).contains("no triangles"), "empty");
    let mut bad = t.clone();
    bad[5][1] = 9999;
    let m = err(&p, &bad);
    assert!(
        m.contains("triangle 5") && m.contains("9999"),
        "out of range: {m}"
    );
    p[3].y = f64::NAN;
    assert!(err(&p, &t).contains("vertex 3"), "NaN: {}", err(&p, &t));
}

#[test]
fn a_hole_below_the_water_is_named() {
    for (half, open_top) in [(false, false), (true, true), (false, true)] {
        let (p, mut t) = box_mesh(half, open_top);
        // The bottom's first triangle: near x = 1, y = −3 (full) or 0 (half), z = 0.
        let gone = t.remove(0);
        let geom = TriangleHull::try_new(&p, &t).expect("valid");
        match at(&geom, Flotation::at_draft(T)) {
            Err(HydroError::HoleBelowWater { x, y, z, .. }) => {
                let q = DVec3::new(x, y, z);
                let near = gone
                    .iter()
                    .map(|&i| (p[i as usize] - q).length())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    near <= 2.5,
                    "the hole at {q} is by the missing triangle (half {half})"
                );
                assert!(z.abs() < 1e-12, "on the bottom: {q}");
            }
            other => panic!("expected a hole (half {half}, open top {open_top}): {other:?}"),
        }
    }
}

#[test]
fn drafts_below_the_keel_and_over_the_top_are_errors() {
    for geom in [hull(&box_mesh(false, false)), hull(&box_mesh(true, true))] {
        assert!(
            matches!(
                at(&geom, Flotation::at_draft(-0.5)),
                Err(HydroError::DraftBelowKeel { keel, .. }) if keel == 0.0
            ),
            "below the keel"
        );
        assert!(
            matches!(
                at(&geom, Flotation::at_draft(D + 0.5)),
                Err(HydroError::DraftAboveTop { .. })
            ),
            "over the top (half {}): {:?}",
            geom.is_half(),
            at(&geom, Flotation::at_draft(D + 0.5))
        );
    }
}

#[test]
fn a_plane_section_of_a_closed_mesh_is_closed_and_oriented() {
    let geom = hull(&box_mesh(true, true));
    // The station at midships, both halves: its segments' directed area is +B·D (counter-
    // clockwise about +x) and every end is some segment's start.
    let segs = geom.plane_section(DVec3::X, 0.5 * L, 0.0);
    let area: f64 = segs
        .iter()
        .map(|[a, b]| 0.5 * (a.y * b.z - b.y * a.z))
        .sum();
    // The open top leaves the section open along z = D: close it for the area.
    let top: f64 = 0.5 * (B / 2.0 * D - (-B / 2.0) * D);
    assert_rel(area + top, B * D, EXACT, "station area");
}

#[test]
fn the_triangle_order_does_not_change_the_figures() {
    // The runs of consecutive triangles only skip work: a mesh in scrambled order (a fixed
    // permutation, so the runs' boxes span the whole sphere) gives the same figures.
    let (p, t) = sphere(2.0, 96, 48);
    let n = t.len();
    let scrambled: Vec<[u32; 3]> = (0..n).map(|k| t[(k * 7919) % n]).collect();
    assert!(
        n % 7919 != 0,
        "7919 is prime and n not its multiple: a permutation"
    );
    let datums = Datums {
        x_ap: -2.0,
        x_fp: 2.0,
    };
    for heel_deg in [0.0, 20.0] {
        let f = Flotation {
            heel_deg,
            ..Flotation::at_draft(1.3)
        };
        let a = hydrostatics(&hull(&(p.clone(), t.clone())), &f, &datums).expect("in order");
        let b =
            hydrostatics(&hull(&(p.clone(), scrambled.clone())), &f, &datums).expect("scrambled");
        for (x, y, what) in [
            (a.volume, b.volume, "volume"),
            (a.vcb, b.vcb, "KB"),
            (a.bmt, b.bmt, "BMt"),
            (a.waterplane_area, b.waterplane_area, "Awp"),
            (a.midship_area, b.midship_area, "Am"),
            (a.lwl, b.lwl, "Lwl"),
            (a.los, b.los, "LOS"),
        ] {
            assert_rel(x, y, 1e-12, &format!("{what} at heel {heel_deg}°"));
        }
    }
}
