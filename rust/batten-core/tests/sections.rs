//! Exact plane sections of the patch surface (issue 16): the Wigley hull's stations, waterlines
//! and diagonals against its analytic form, a box barge's sections and chine exactly, fitted
//! curves within the tolerance with their corners, and bad input.

use batten_core::{
    build_hull, Error, HullOptions, HullSurface, Network, SectionModel, SectionPlane,
    SectionPolyline, DEFAULT_CUT_TOLERANCE,
};
use glam::DVec3;

mod common;
use common::box_barge;

const L: f64 = 100.0;
const B: f64 = 10.0;
const T: f64 = 6.25;
const DECK: f64 = 8.75;

fn example(name: &str) -> HullSurface {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let net =
        Network::from_json(&std::fs::read_to_string(path).expect("example")).expect("network");
    build_hull(&net, &HullOptions::default()).expect("builds")
}

/// The Wigley hull's half-breadth `y = B/2·(1 − (2x/L)²)·(1 − ((T − z)/T)²)`, wall-sided above
/// `T` (as the example draws it).
fn wigley_y(x: f64, z: f64) -> f64 {
    let w = ((T - z) / T).max(0.0);
    0.5 * B * (1.0 - (2.0 * x / L).powi(2)) * (1.0 - w * w)
}

/// The port half of a box barge 40 × 8 × 5 m with a chine (knuckle) along the bilge.
fn box_barge_hull() -> HullSurface {
    build_hull(&box_barge(true), &HullOptions::default()).expect("builds")
}

/// The only polyline of a section.
fn single(model: &SectionModel, plane: SectionPlane) -> SectionPolyline {
    let lines = model
        .section(&plane, DEFAULT_CUT_TOLERANCE)
        .expect("section");
    assert_eq!(lines.len(), 1, "one polyline in {plane:?}: {lines:?}");
    lines.into_iter().next().expect("one")
}

#[test]
fn wigley_stations_follow_the_analytic_parabolas_from_keel_to_deck() {
    let model = SectionModel::new(&example("wigley_lines.json"));
    // Drawn stations (every 6.25 m) and stations between them.
    for x in [-40.0, -31.25, -17.3, 0.0, 3.1, 25.0, 44.0] {
        let s = single(&model, SectionPlane::station(x).expect("plane"));
        assert!(!s.closed, "a half hull's station is open");
        let (first, last) = (s.points[0], *s.points.last().expect("points"));
        // Oriented along m × n: from the deck edge round to the keel, or the other way; both
        // ends are the keel (y = 0, z = 0) and the deck edge (z = DECK).
        let (keel, deck) = if first.z < last.z {
            (first, last)
        } else {
            (last, first)
        };
        assert!(
            keel.y.abs() < 1e-6 && keel.z.abs() < 1e-6,
            "x {x}: keel end {keel}"
        );
        assert!((deck.z - DECK).abs() < 1e-6, "x {x}: deck end {deck}");
        let mut worst: f64 = 0.0;
        for p in &s.points {
            assert!((p.x - x).abs() < 1e-9, "x {x}: point {p} off the plane");
            worst = worst.max((p.y - wigley_y(x, p.z)).abs());
        }
        // The patches follow the analytic hull between the drawn curves to a few mm.
        assert!(
            worst < 5e-3,
            "x {x}: half-breadths within {worst} m of the parabola"
        );
        // Chords within the tolerance: every chord's middle near the analytic curve.
        for w in s.points.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            let off = (mid.y - wigley_y(x, mid.z)).abs();
            assert!(
                off < DEFAULT_CUT_TOLERANCE + worst,
                "x {x}: chord off by {off}"
            );
        }
    }
}

#[test]
fn wigley_waterlines_run_from_stern_to_stem_on_their_parabola() {
    let model = SectionModel::new(&example("wigley_lines.json"));
    for z in [0.7, 3.125, 5.0, T, 7.9] {
        let s = single(&model, SectionPlane::waterline(z).expect("plane"));
        let xs: Vec<f64> = s.points.iter().map(|p| p.x).collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::MAX, f64::MIN), |a, &x| (a.0.min(x), a.1.max(x)));
        assert!(
            (lo + L / 2.0).abs() < 1e-6 && (hi - L / 2.0).abs() < 1e-6,
            "z {z}: x {lo}..{hi}"
        );
        for p in &s.points {
            assert!((p.z - z).abs() < 1e-9, "z {z}: point {p} off the plane");
            let want = wigley_y(p.x, z);
            assert!(
                (p.y - want).abs() < 5e-3,
                "z {z}: y {} vs {want} at x {}",
                p.y,
                p.x
            );
        }
        // In order along the hull: x runs one way only.
        let rising = xs.windows(2).all(|w| w[1] >= w[0] - 1e-9);
        let falling = xs.windows(2).all(|w| w[1] <= w[0] + 1e-9);
        assert!(
            rising || falling,
            "z {z}: points in order along the waterline"
        );
    }
}

#[test]
fn wigley_diagonal_points_are_on_their_plane_and_the_hull() {
    let model = SectionModel::new(&example("wigley_lines.json"));
    let plane = SectionPlane::diagonal(0.0, 6.0, -30.0).expect("plane");
    let s = single(&model, plane);
    let (m, c) = (plane.normal(), plane.offset());
    assert!(s.points.len() > 20, "a diagonal has many points");
    for p in &s.points {
        assert!((m.dot(*p) - c).abs() < 1e-9, "point {p} off the diagonal");
        assert!(
            (p.y - wigley_y(p.x, p.z)).abs() < 5e-3,
            "point {p} off the hull"
        );
    }
}

#[test]
fn box_barge_sections_are_exact_with_a_corner_at_the_chine() {
    let hull = box_barge_hull();
    let model = SectionModel::new(&hull);
    let s = single(&model, SectionPlane::station(13.0).expect("plane"));
    assert_eq!(
        s.corners.len(),
        1,
        "the station turns once, at the chine: {:?}",
        s.corners
    );
    let corner = s.points[s.corners[0]];
    assert!(
        (corner - DVec3::new(13.0, 4.0, 0.0)).length() < 1e-9,
        "corner at {corner}"
    );
    for p in &s.points {
        let on_bottom = p.z.abs() < 1e-9 && p.y <= 4.0 + 1e-9;
        let on_side = (p.y - 4.0).abs() < 1e-9 && p.z <= 5.0 + 1e-9;
        assert!(on_bottom || on_side, "point {p} on the box");
    }
    // The fitted curve keeps the corner and stays within the tolerance of the points.
    let curve = s.fit(DEFAULT_CUT_TOLERANCE).expect("fits");
    let through = curve.nearest(corner, 1e-12).expect("nearest").distance;
    assert!(
        through < 1e-6,
        "the fit passes through the chine ({through} m)"
    );
    for p in &s.points {
        let d = curve.nearest(*p, 1e-12).expect("nearest").distance;
        assert!(d <= DEFAULT_CUT_TOLERANCE, "fitted curve {d} m from {p}");
    }
    let wl = single(&model, SectionPlane::waterline(2.5).expect("plane"));
    for p in &wl.points {
        assert!(
            (p.y - 4.0).abs() < 1e-9 && (p.z - 2.5).abs() < 1e-12,
            "waterline point {p}"
        );
    }
    let span = wl
        .points
        .iter()
        .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.x), a.1.max(p.x)));
    assert!(
        span.0.abs() < 1e-9 && (span.1 - 40.0).abs() < 1e-9,
        "waterline x {span:?}"
    );
    let knuckles = model.knuckle_lines();
    assert_eq!(knuckles.len(), 1, "one chine line: {knuckles:?}");
    let k = &knuckles[0];
    assert_eq!(k.curve, "chine");
    let ends = [k.points[0], *k.points.last().expect("points")];
    assert!(
        ends.iter()
            .any(|p| (*p - DVec3::new(0., 4., 0.)).length() < 1e-9)
            && ends
                .iter()
                .any(|p| (*p - DVec3::new(40., 4., 0.)).length() < 1e-9),
        "the chine runs the barge's length: {ends:?}"
    );
}

#[test]
fn a_drawn_station_is_cut_once() {
    // x = 20 holds the drawn midship station, a patch edge: its section is not doubled.
    let model = SectionModel::new(&box_barge_hull());
    let s = single(&model, SectionPlane::station(20.0).expect("plane"));
    let length: f64 = s.points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!(
        (length - 9.0).abs() < 1e-6,
        "the station is 4 + 5 m long: {length}"
    );
}

#[test]
fn planes_missing_the_hull_give_nothing_and_bad_input_is_refused() {
    let model = SectionModel::new(&box_barge_hull());
    for plane in [
        SectionPlane::station(-1.0),
        SectionPlane::station(41.0),
        SectionPlane::waterline(6.0),
        SectionPlane::buttock(5.0),
    ] {
        let lines = model.section(&plane.expect("plane"), DEFAULT_CUT_TOLERANCE);
        assert_eq!(lines.expect("section"), Vec::new(), "nothing cut");
    }
    let nan = SectionPlane::station(f64::NAN).expect_err("NaN offset");
    assert!(
        matches!(&nan, Error::InvalidInput(m) if m.contains("station")),
        "names the family: {nan}"
    );
    let zero = SectionPlane::try_new(DVec3::ZERO, 1.0).expect_err("zero normal");
    assert!(zero.to_string().contains("normal"), "{zero}");
    let diag = SectionPlane::diagonal(0.0, f64::INFINITY, 10.0).expect_err("inf");
    assert!(diag.to_string().contains("z0"), "{diag}");
    let plane = SectionPlane::station(10.0).expect("plane");
    for bad in [0.0, -1.0, f64::NAN] {
        let e = model.section(&plane, bad).expect_err("bad tolerance");
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
}

#[test]
fn the_frigate_s_sections_are_whole_polylines_on_their_planes() {
    // The paper's frigate network: Charrot–Gregory patches, T-joints, a transom. Every
    // station and waterline through the hull is one polyline joined across all its patches.
    let hull = example("frigate_network.json");
    let model = SectionModel::new(&hull);
    let (lo, hi) = model.bounds();
    let mut planes = Vec::new();
    for k in 1..20 {
        let f = k as f64 / 20.0;
        planes.push(SectionPlane::station(lo.x + f * (hi.x - lo.x)).expect("plane"));
    }
    for k in 1..8 {
        let f = k as f64 / 8.0;
        planes.push(SectionPlane::waterline(lo.z + f * (hi.z - lo.z)).expect("plane"));
    }
    let mut pieces = Vec::new();
    for plane in &planes {
        let lines = model
            .section(plane, DEFAULT_CUT_TOLERANCE)
            .expect("section");
        for l in &lines {
            for p in &l.points {
                let r = (plane.normal().dot(*p) - plane.offset()).abs();
                assert!(r < 1e-9, "{plane:?}: point {p} {r} m off the plane");
            }
        }
        pieces.push(lines.len());
    }
    assert!(
        pieces.iter().all(|&n| n == 1),
        "one polyline per plane: {pieces:?}"
    );
}
