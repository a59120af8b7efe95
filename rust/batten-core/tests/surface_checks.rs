//! The report tells the truth about the surface (real-ships issue): holes — free edges off the
//! profile, deck and transom — and folds — neighbouring mesh faces at more than
//! `FOLD_ANGLE_DEGREES` off the knuckles, or a patch out of its boundary's box — are warnings
//! naming the curves, with a place; the clean example hulls have none.

use batten_core::{
    build_hull, HullOptions, HullReport, Network, NetworkCurve, NurbsCurve, Role, Warning,
    WarningKind, FOLD_ANGLE_DEGREES,
};
use glam::DVec3;
mod common;
use common::example;

fn line(name: &str, role: Role, a: [f64; 3], b: [f64; 3]) -> NetworkCurve {
    NetworkCurve {
        name: name.to_owned(),
        role,
        curve: NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![DVec3::from(a), DVec3::from(b)],
            None,
        )
        .expect("line"),
    }
}

/// A flat side panel 10 m × 3 m in the plane `y = y0`, split by a station at x = 5: its rim
/// curves get `rim` as role.
fn panel(y0: f64, rim: [Role; 4]) -> Network {
    let p = |x: f64, z: f64| [x, y0, z];
    Network::try_new(
        "panel",
        vec![
            line("keel", rim[0], p(0.0, 0.0), p(10.0, 0.0)),
            line("deck", rim[1], p(0.0, 3.0), p(10.0, 3.0)),
            line("aft", rim[2], p(0.0, 0.0), p(0.0, 3.0)),
            line("stem", rim[3], p(10.0, 0.0), p(10.0, 3.0)),
            line("st5", Role::Free, p(5.0, 0.0), p(5.0, 3.0)),
        ],
    )
    .expect("network")
}

fn report(net: &Network, tolerance: f64, resolution: usize) -> HullReport {
    let options = HullOptions::try_new(tolerance, resolution).expect("options");
    build_hull(net, &options).expect("hull builds").report
}

fn of_kind(r: &HullReport, kind: WarningKind) -> Vec<&Warning> {
    r.warnings.iter().filter(|w| w.kind == kind).collect()
}

#[test]
fn a_rim_without_boundary_roles_is_one_hole_naming_its_curves() {
    let r = report(&panel(1.0, [Role::Free; 4]), 1e-4, 8);
    let holes = of_kind(&r, WarningKind::Hole);
    assert_eq!((r.holes, holes.len()), (1, 1), "{:?}", r.warnings);
    assert_eq!(holes[0].curves, ["aft", "deck", "keel", "stem"]);
    let at = holes[0].location.expect("a hole has a place");
    assert!((at.y - 1.0).abs() < 1e-12, "on the panel's rim: {at}");
    assert!(
        holes[0].message.contains("6 free edge(s)"),
        "{}",
        holes[0].message
    );
}

#[test]
fn the_profile_deck_transom_and_stem_are_the_hulls_own_rim() {
    let roles = [Role::Keel, Role::Deck, Role::Transom, Role::Stem];
    assert_eq!(report(&panel(1.0, roles), 1e-4, 8).holes, 0);
    // In the centreplane, the rim is the profile whatever its role.
    let r = report(&panel(0.0, [Role::Free; 4]), 1e-4, 8);
    assert_eq!((r.holes, r.open_edges), (0, 6), "{:?}", r.warnings);
    // Only the keel without its role: a hole along the keel alone.
    let r = report(
        &panel(1.0, [Role::Free, roles[1], roles[2], roles[3]]),
        1e-4,
        8,
    );
    let holes = of_kind(&r, WarningKind::Hole);
    assert_eq!(holes.len(), 1);
    assert_eq!(holes[0].curves, ["keel"]);
}

#[test]
fn the_example_hulls_have_no_holes_and_no_folds() {
    for file in ["wigley.json", "frigate_network.json", "hard_chine.json"] {
        let net = example(file);
        for resolution in [4, 8, 16] {
            let r = report(&net, 1e-4, resolution);
            assert_eq!(
                (r.holes, r.folds),
                (0, 0),
                "{file} at {resolution}: {:?}",
                r.warnings
            );
            assert!(
                r.max_neighbour_angle_deg > 0.5 && r.max_neighbour_angle_deg < FOLD_ANGLE_DEGREES,
                "{file} at {resolution}: neighbouring faces turn by {}°",
                r.max_neighbour_angle_deg
            );
            assert!(r.max_neighbour_angle_at.is_some());
        }
        // Finer meshes turn less between neighbours: the figure measures the mesh, not noise.
        let (coarse, fine) = (report(&net, 1e-4, 8), report(&net, 1e-4, 16));
        assert!(
            fine.max_neighbour_angle_deg < 0.7 * coarse.max_neighbour_angle_deg,
            "{file}: {} → {}",
            coarse.max_neighbour_angle_deg,
            fine.max_neighbour_angle_deg
        );
    }
}

#[test]
fn the_largest_normal_jump_says_where_it_is() {
    let net = example("frigate_network.json");
    let r = report(&net, 1e-4, 8);
    let at = r.max_normal_angle_at.expect("the frigate has shared edges");
    let curve = r.max_normal_angle_curve.as_deref().expect("a curve");
    let c = net
        .curves()
        .iter()
        .find(|c| c.name == curve)
        .expect("a network curve");
    let distance = c.curve.nearest(at, 1e-9).expect("nearest").distance;
    assert!(
        distance < 1e-9,
        "the place lies on curve '{curve}' ({distance} m off)"
    );
}

/// KCS as the import made it before the real-ships issue: every section faired on its own
/// within 5 mm (`tests/data/kcs_faired_apart.json`, written by `api.export_network`), built at
/// 1 cm. Rendered, it showed what the issue lists; the report must name each of them (its
/// holes are closed since).
#[test]
fn the_faired_apart_kcs_reports_its_holes_and_folds_where_they_are() {
    let path = format!(
        "{}/tests/data/kcs_faired_apart.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let net = Network::from_json(&std::fs::read_to_string(path).expect("fixture")).expect("reads");
    let r = report(&net, 0.01, 8);
    let folds = of_kind(&r, WarningKind::Fold);
    let holes = of_kind(&r, WarningKind::Hole);
    assert_eq!((r.folds, r.holes), (folds.len(), holes.len()));
    let near = |ws: &[&Warning], test: &dyn Fn(DVec3) -> bool| {
        ws.iter().any(|w| w.location.is_some_and(test))
    };
    // The 2 m fin out of the aft keel near x 14 and the ridge 11 cm proud of the side near
    // x 76 were corner-based patches folding; side-blended patches replaced them. Since the
    // patches run their sides at arc length and turning, not at the curves' own parameters
    // (one unit per Bézier piece), the corner-based patches there fold no more and stay.
    let blended = of_kind(&r, WarningKind::SideBlended);
    let aft_keel = |p: DVec3| (12.0..16.0).contains(&p.x) && p.z < 1.0;
    let side_ridge = |p: DVec3| (70.0..80.0).contains(&p.x) && p.y > 15.0;
    for (what, place) in [
        ("aft keel", &aft_keel as &dyn Fn(DVec3) -> bool),
        ("ridge", &side_ridge),
    ] {
        assert!(!near(&blended, place), "{what}: {blended:?}");
        assert!(!near(&folds, place), "{what}: {folds:?}");
    }
    // The surface that stood 0.7 m aft of the transom (x = -6) no longer does. It was
    // side-blended while the ribbons' angles were blended in the frames of their sides'
    // tangents, and is not since they are blended in frames carried along the sides; it still
    // folds, at the transom, and the report says so.
    let transom = |p: DVec3| p.x < -5.5;
    assert!(near(&folds, &transom), "{folds:?}");
    assert!(!near(&folds, &|p| p.x < -6.3), "{folds:?}");
    // The bow between st19.50 and the bulb, and the skeg ahead of the boss, had no faces
    // (267 faces, holes naming st19.50 and near x 8–11 under z 6) while node normals were
    // oriented by the sign of their dot product, which is chance where neighbouring normals
    // turn by a right angle or more; oriented by parallel transport along the edges, both
    // regions are faces (286) and no hole is left to report.
    assert!(holes.is_empty(), "{holes:?}");
    assert!(r.faces >= 286, "{} faces", r.faces);
    // The normal jump names its place: the boss's end section, whose two nodes (on the
    // profile) have normals half a turn apart, so no blend between them follows the boss
    // round. (It was the forefoot, 90.4°, until the signs of an edge's node normals followed
    // the turn of its curve; now 88.3° at the boss.)
    assert!(r.max_normal_angle_deg > 10.0);
    assert!(
        r.max_normal_angle_at
            .is_some_and(|p| (5.5..6.0).contains(&p.x) && p.y > 0.5)
            && r.max_normal_angle_curve.as_deref() == Some("st0.50_part1of2"),
        "{} at {:?} on {:?}",
        r.max_normal_angle_deg,
        r.max_normal_angle_at,
        r.max_normal_angle_curve
    );
    for w in folds.iter().chain(&holes) {
        assert!(!w.curves.is_empty() && w.location.is_some(), "{w:?}");
    }
}

/// KCS's flat-of-bottom bay as the import made it while the flat of bottom passed up to
/// 0.55 mm off the stations' flat ends: the profile, the flat of bottom, wl_z0.30 and
/// wl_z1.50 between st11 and st14, and those stations up to wl_z1.50, each cut at its
/// crossings (`tests/data/kcs_flat_of_bottom_bay.json`, written with `Curve.split` from
/// `api.import_sections` of `shared/hulls/kcs`). The bilge patches' sides end in a short flat
/// stretch there, and still meet the planar faces of the flat smoothly: the Gregory patches'
/// twists are their ribbons' own end derivatives. (With the twists taken over 1e-4 of a side,
/// the ribbon turning within that of its end tilted the bilge 0.53° off the flat.)
#[test]
fn the_kcs_bilge_meets_its_flat_of_bottom_tangentially() {
    let path = format!(
        "{}/tests/data/kcs_flat_of_bottom_bay.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let net = Network::from_json(&std::fs::read_to_string(path).expect("fixture")).expect("reads");
    let r = report(&net, 1e-4, 8);
    assert_eq!(r.faces, 9, "three bays of flat, bilge and side");
    // The cut curves are its rim (one hole, named); nothing else is found.
    let kinds: Vec<WarningKind> = r.warnings.iter().map(|w| w.kind).collect();
    assert_eq!(kinds, [WarningKind::Hole], "{:?}", r.warnings);
    assert!(
        r.max_normal_angle_deg < 1e-3,
        "{}° at {:?} on {:?}",
        r.max_normal_angle_deg,
        r.max_normal_angle_at,
        r.max_normal_angle_curve
    );
}
