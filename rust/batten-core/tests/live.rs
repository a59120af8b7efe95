//! The live rebuild (`LiveHull`): after moving control points, an incremental rebuild gives
//! exactly the mesh, patches and (once settled) report of a full build of the same curves,
//! builds again only the faces the move reaches, falls back to a full build when the
//! connectivity changes, and loses nothing on a failed rebuild.

use std::path::PathBuf;

use batten_core::{
    build_hull, tessellate_patches, HullOptions, LiveHull, Network, NetworkCurve, PatchKind,
    Rebuild, TangentPlane,
};
use glam::DVec3;

fn examples() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn load(name: &str) -> Network {
    let text = std::fs::read_to_string(examples().join(name)).expect("example file");
    Network::from_json(&text).expect("valid network")
}

/// The network with control point `index` of curve `curve` moved by `by`.
fn moved(net: &Network, curve: usize, index: usize, by: DVec3) -> Network {
    let curves: Vec<NetworkCurve> = net
        .curves()
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if i != curve {
                return c.clone();
            }
            let mut points = c.curve.control_points();
            points[index] += by;
            NetworkCurve {
                curve: c.curve.with_control_points(points).expect("a valid curve"),
                ..c.clone()
            }
        })
        .collect();
    Network::try_new(net.name.clone(), curves).expect("a valid network")
}

fn options() -> HullOptions {
    HullOptions::try_new(1e-4, 12).expect("options")
}

/// The index of the curve named `name`.
fn curve(net: &Network, name: &str) -> usize {
    net.curves()
        .iter()
        .position(|c| c.name == name)
        .unwrap_or_else(|| panic!("no curve {name}"))
}

/// The live hull's surface equals a full build of `net`: the mesh and patches at once, the
/// report once settled.
fn assert_same_as_full(live: &mut LiveHull, net: &Network) {
    let full = build_hull(net, live.options()).expect("full build");
    assert!(
        live.surface().mesh == full.mesh,
        "mesh differs from a full build"
    );
    assert_eq!(
        live.surface().patch_faces,
        full.patch_faces,
        "the same faces patched"
    );
    // The patches themselves, sampled where the mesh does not: another resolution.
    let sample = |patches: &[batten_core::Patch]| tessellate_patches(patches, 5).expect("mesh");
    assert!(
        sample(&live.surface().patches) == sample(&full.patches),
        "patches differ"
    );
    let settled = live.settle().expect("settles");
    assert!(
        settled.report == full.report,
        "report differs from a full build"
    );
    assert!(live.is_measured(), "settled");
}

#[test]
fn a_moved_station_point_rebuilds_its_faces_only_and_matches_a_full_build() {
    let net = load("frigate_network.json");
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    assert!(live.is_measured(), "settled");
    assert_eq!(live.last_rebuild(), &Rebuild::Full { reason: None });
    let faces = live.surface().patches.len();
    // Move an interior control point of one station outwards, by less than the model
    // tolerance: its crossings with the waterlines stay nodes (a larger move takes the
    // station off them, which changes the connectivity: the test below).
    let station = curve(&net, "st4");
    let middle = net.curves()[station].curve.control_points().len() / 2;
    let next = moved(&net, station, middle, DVec3::new(0.0, 4e-5, 0.0));
    let did = live.rebuild(&next).expect("rebuilds").clone();
    match did {
        Rebuild::Incremental { faces: rebuilt, of } => {
            assert_eq!(of, faces, "the count of all faces");
            assert!(rebuilt > 0, "a moved station rebuilds its faces");
            assert!(
                rebuilt < faces,
                "only the faces the station reaches are rebuilt: {rebuilt} of {faces}"
            );
        }
        other => panic!("expected an incremental rebuild, got {other:?}"),
    }
    assert!(!live.is_measured(), "the report waits for settle");
    assert_same_as_full(&mut live, &next);
}

#[test]
fn a_sequence_of_drags_ends_where_a_full_build_does() {
    let net = load("frigate_network.json");
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    let mut current = net.clone();
    // A deterministic walk: each step moves one interior control point of a station or a
    // waterline a little (the curves on the centreplane stay there).
    let movable: Vec<usize> = ["st1", "st2", "st4", "st6", "st8", "cwl", "wl_aft"]
        .iter()
        .map(|n| curve(&net, n))
        .collect();
    let mut seed: u64 = 0x5eed;
    let mut next_rand = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) as usize
    };
    let mut incremental = 0;
    for _ in 0..20 {
        let c = movable[next_rand() % movable.len()];
        let n = current.curves()[c].curve.control_points().len();
        if n < 3 {
            continue;
        }
        let i = 1 + next_rand() % (n - 2);
        // Within the model tolerance of the crossings, so the connectivity stays.
        let by = DVec3::new(0.0, 1e-5 * ((next_rand() % 5) as f64 - 2.0), 0.0);
        current = moved(&current, c, i, by);
        if let Rebuild::Incremental { .. } = live.rebuild(&current).expect("rebuilds") {
            incremental += 1;
        }
        assert!(live.surface().mesh == build_hull(&current, &options()).expect("builds").mesh);
    }
    assert!(
        incremental > 10,
        "most small drags are incremental: {incremental} of 20"
    );
    assert_same_as_full(&mut live, &current);
}

#[test]
fn a_connectivity_change_falls_back_to_a_full_build() {
    let net = load("frigate_network.json");
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    // A station moved 2 cm off the waterlines loses its crossings: the rebuild is full.
    let st4 = curve(&net, "st4");
    let middle = net.curves()[st4].curve.control_points().len() / 2;
    let off = moved(&net, st4, middle, DVec3::new(0.0, 0.02, 0.0));
    match live.rebuild(&off).expect("rebuilds") {
        Rebuild::Full { reason: Some(why) } => assert!(why.contains("connectivity"), "{why}"),
        other => panic!("expected a full rebuild, got {other:?}"),
    }
    assert_same_as_full(&mut live, &off);
    // Without one curve the nodes and faces differ too, and the rebuild says why.
    let fewer: Vec<NetworkCurve> = net.curves()[1..].to_vec();
    let fewer = Network::try_new(net.name.clone(), fewer).expect("network");
    match live.rebuild(&fewer) {
        Ok(Rebuild::Full { reason: Some(why) }) => {
            assert!(why.contains("curves"), "{why}");
        }
        Ok(other) => panic!("expected a full rebuild, got {other:?}"),
        Err(e) => panic!("the smaller network builds too: {e}"),
    }
    assert_same_as_full(&mut live, &fewer);
    // And back: the full network again, then an incremental move on it.
    live.rebuild(&net).expect("rebuilds");
    assert_same_as_full(&mut live, &net);
    let deck = curve(&net, &net.curves()[0].name);
    let next = moved(&net, deck, 1, DVec3::new(0.0, 0.01, 0.0));
    live.rebuild(&next).expect("rebuilds");
    assert_same_as_full(&mut live, &next);
}

#[test]
fn a_failed_rebuild_keeps_the_previous_surface() {
    let net = load("frigate_network.json");
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    let before = live.surface().clone();
    // One curve alone encloses nothing.
    let lone = Network::try_new(net.name.clone(), net.curves()[..1].to_vec()).expect("network");
    let err = live.rebuild(&lone).expect_err("no faces");
    assert!(err.to_string().contains("no faces"), "{err}");
    assert!(live.surface() == &before, "the surface is unchanged");
    assert!(live.is_measured(), "and so is its report");
    // The hull still rebuilds incrementally from where it was.
    let next = moved(&net, 0, 1, DVec3::new(0.0, 0.01, 0.0));
    live.rebuild(&next).expect("rebuilds");
    assert_same_as_full(&mut live, &next);
}

/// Hydrostatics follow a drag: the model of each rebuilt surface, made from the one before
/// with the cells of the faces the rebuild did not patch again kept, is the model of a full
/// build — the same figures bit for bit — and keeps most of the cells.
#[test]
fn hydro_cells_kept_across_drags_give_a_full_build_s_figures() {
    use batten_core::{default_datums, hydrostatics, CellDensity, Flotation};
    let net = load("frigate_network.json");
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    assert_eq!(
        live.rebuilt_faces(),
        None,
        "a first build builds everything"
    );
    let mut model = live.surface().hydro_model(CellDensity::DEFAULT);
    assert_eq!(model.kept_cell_count(), 0, "a new model makes every cell");
    let station = curve(&net, "st4");
    let middle = net.curves()[station].curve.control_points().len() / 2;
    let mut current = net;
    for by in [4e-5, -3e-5, 2e-5] {
        current = moved(&current, station, middle, DVec3::new(0.0, by, 0.0));
        live.rebuild(&current).expect("rebuilds");
        let rebuilt = live.rebuilt_faces().expect("incremental").to_vec();
        let of = live.surface().patches.len();
        assert!(
            !rebuilt.is_empty() && rebuilt.len() < of,
            "{rebuilt:?} of {of}"
        );
        model = live
            .surface()
            .hydro_model_after(&model, &|f| rebuilt.contains(&f));
        assert!(
            model.kept_cell_count() > 0 && model.kept_cell_count() < model.cell_count(),
            "kept {} of {}",
            model.kept_cell_count(),
            model.cell_count()
        );
        let full = build_hull(&current, live.options())
            .expect("full build")
            .hydro_model(CellDensity::DEFAULT);
        assert_eq!(full.cell_count(), model.cell_count(), "the same cells");
        let datums = default_datums(&full, 4.0, None).expect("datums");
        let flotation = Flotation::at_draft(4.0);
        let a = hydrostatics(&model, &flotation, &datums).expect("figures");
        let b = hydrostatics(&full, &flotation, &datums).expect("figures");
        assert!(a == b, "kept cells' figures {a:?}\nvs a full build's {b:?}");
    }
}

/// Moving one control point changes a curve on `degree + 1` of its spans only: the faces along
/// the rest of the curve keep their patches (their edges lie where the curve did not change),
/// so fewer faces are built again than when the whole curve moves; both match a full build.
#[test]
fn a_local_move_rebuilds_fewer_faces_than_moving_the_whole_curve() {
    let net = load("frigate_network.json");
    let deck = curve(&net, "deck");
    let rebuilt = |next: &Network| {
        let mut live = LiveHull::new(&net, &options()).expect("builds");
        let faces = match live.rebuild(next).expect("rebuilds").clone() {
            Rebuild::Incremental { faces, .. } => faces,
            other => panic!("expected an incremental rebuild, got {other:?}"),
        };
        assert_same_as_full(&mut live, next);
        faces
    };
    let by = DVec3::new(0.0, 4e-5, 0.0);
    let local = rebuilt(&moved(&net, deck, 1, by));
    let points = net.curves()[deck].curve.control_point_count();
    let mut whole = net.clone();
    for i in 1..points - 1 {
        whole = moved(&whole, deck, i, by);
    }
    let whole = rebuilt(&whole);
    assert!(
        local < whole,
        "a move near the deck's end rebuilds {local} faces, the whole deck's interior {whole}"
    );
}

/// A field computed again that comes out bit for bit as before patches no face again: a move
/// in the middle of frigate station st4 reaches the normal fields at its nodes, but only the
/// faces along the spans the move reached change (measured: 10 faces rebuilt of 17, where
/// every face at a recomputed field was patched again before, 14), and the result is still a
/// full build's.
#[test]
fn recomputed_fields_that_did_not_change_patch_no_face_again() {
    let net = load("frigate_network.json");
    let station = curve(&net, "st4");
    let middle = net.curves()[station].curve.control_point_count() / 2;
    let next = moved(&net, station, middle, DVec3::new(0.0, 4e-5, 0.0));
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    let Rebuild::Incremental { faces, of } = live.rebuild(&next).expect("rebuilds").clone() else {
        panic!("expected an incremental rebuild");
    };
    assert_same_as_full(&mut live, &next);
    println!("{faces} of {of} faces patched again");
    assert!(
        faces > 0 && faces <= 10,
        "{faces} of {of} faces patched again"
    );
}

/// A drag next to side-blended faces (patches that replaced folding corner-based ones) ends
/// in a full build's surface, and the faces it rebuilds choose their patch again as a full
/// build does.
#[test]
fn a_drag_beside_side_blended_faces_matches_a_full_build() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/kcs_faired_apart.json");
    let net = Network::from_json(&std::fs::read_to_string(path).expect("fixture")).expect("reads");
    let options = HullOptions::try_new(0.01, 8).expect("options");
    let mut live = LiveHull::new(&net, &options).expect("builds");
    let blended = |live: &LiveHull| {
        live.surface()
            .patches
            .iter()
            .filter(|p| p.kind() == PatchKind::SideBlend)
            .count()
    };
    assert!(blended(&live) > 0, "the fixture has side-blended faces");
    let station = curve(&net, "st01");
    let middle = net.curves()[station].curve.control_points().len() / 2;
    let next = moved(&net, station, middle, DVec3::new(0.0, 2e-3, 0.0));
    let did = live.rebuild(&next).expect("rebuilds").clone();
    assert!(
        matches!(did, Rebuild::Incremental { .. }),
        "an incremental rebuild: {did:?}"
    );
    assert!(blended(&live) > 0, "still side-blended faces");
    assert_same_as_full(&mut live, &next);
}

/// With a tangent plane (the barge's flat of side: its curves there are exact, so the plane
/// only confirms their normal fields), a drag of a station in the end ends in a full build's
/// surface, and the same curves without the plane rebuild in full, saying why.
#[test]
fn a_hull_with_a_tangent_plane_rebuilds_as_a_full_build_does() {
    let side = vec![TangentPlane::try_new(DVec3::Y, 10.0).expect("a plane")];
    let bare = load("pmb_barge.json");
    let net = bare.clone().with_tangent_planes(side.clone());
    let mut live = LiveHull::new(&net, &options()).expect("builds");
    let st = curve(&net, "st10");
    let next = moved(&net, st, 2, DVec3::new(0.0, 4e-5, 0.0)).with_tangent_planes(side);
    match live.rebuild(&next).expect("rebuilds") {
        Rebuild::Incremental { .. } => {}
        other => panic!("expected an incremental rebuild, got {other:?}"),
    }
    assert_same_as_full(&mut live, &next);
    let no_plane = moved(&bare, st, 2, DVec3::new(0.0, 4e-5, 0.0));
    match live.rebuild(&no_plane).expect("rebuilds") {
        Rebuild::Full { reason: Some(why) } => assert!(why.contains("tangent"), "{why}"),
        other => panic!("expected a full rebuild, got {other:?}"),
    }
    assert_same_as_full(&mut live, &no_plane);
}
