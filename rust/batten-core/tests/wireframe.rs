//! Wireframe import: curves fitted one by one meet exactly after `snap_to_nodes`, so the
//! network builds at the model tolerance without near misses (real-ships issue, H-rep §3.2.3).

use batten_core::{
    build_hull, snap_to_nodes, Error, HullOptions, Network, NetworkCurve, NurbsCurve, Role,
    SnapData, Tolerance, Topology, WarningKind,
};
use glam::DVec3;

fn cubic(name: &str, pts: [[f64; 3]; 4]) -> NetworkCurve {
    NetworkCurve {
        name: name.to_owned(),
        role: Role::Free,
        curve: NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            pts.iter().copied().map(DVec3::from).collect(),
            None,
        )
        .expect("cubic"),
    }
}

/// A station in the plane x = 0, from the keel (origin) up to (0, 2, 2); at parameter 0.5 it
/// passes (0, 0.925, 1.075).
fn station() -> NetworkCurve {
    cubic(
        "st",
        [
            [0.0, 0.0, 0.0],
            [0.0, 0.5, 0.7],
            [0.0, 1.3, 1.5],
            [0.0, 2.0, 2.0],
        ],
    )
}

fn near_misses(t: &Topology) -> usize {
    t.diagnostics
        .iter()
        .filter(|d| d.kind() == "near_miss")
        .count()
}

#[test]
fn two_curves_that_miss_by_half_a_millimetre_meet_exactly_after_snapping() {
    // A station and a waterline crossing at (0, 0.925, 1.075) (both at parameter 0.5); the
    // waterline is then moved 0.5 mm along their common normal there: a near miss at the
    // default 0.1 mm.
    let station = station();
    let mut wl = cubic(
        "wl",
        [
            [-2.0, 0.775, 1.075],
            [-1.0, 0.975, 1.075],
            [1.0, 0.975, 1.075],
            [2.0, 0.775, 1.075],
        ],
    );
    assert!(station.curve.point(0.5).distance(wl.curve.point(0.5)) < 1e-12);
    let normal = station
        .curve
        .derivs(0.5)
        .d1
        .cross(wl.curve.derivs(0.5).d1)
        .normalize();
    let pts: Vec<DVec3> = wl
        .curve
        .control_points()
        .iter()
        .map(|p| *p + normal * 5e-4)
        .collect();
    wl.curve = NurbsCurve::try_new(3, wl.curve.knots().to_vec(), pts, None).expect("moved");
    let net = Network::try_new("cross", vec![station, wl]).expect("network");
    let fine = Tolerance::DEFAULT;
    assert_eq!(
        near_misses(&Topology::build(&net, fine).expect("topology")),
        1
    );
    let snapped =
        snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    let t = Topology::build(&snapped.network, fine).expect("topology");
    assert_eq!(near_misses(&t), 0, "{:?}", t.diagnostics);
    // The crossing is one node both curves pass through, to rounding.
    let crossing = t
        .brep
        .vertices
        .iter()
        .find(|v| v.curves.len() == 2)
        .expect("a crossing node");
    for c in snapped.network.curves() {
        let d = c
            .curve
            .nearest(crossing.position, 1e-12)
            .expect("nearest")
            .distance;
        assert!(d < 1e-9, "'{}' is {d} m off the node", c.name);
    }
    // Each curve moved by about half the miss at the node, and by no more anywhere.
    for (s, c) in snapped.snaps.iter().zip(net.curves()) {
        assert!(
            (s.max_move - 2.5e-4).abs() < 5e-5,
            "{}: moved {}",
            s.curve,
            s.max_move
        );
        let new = &snapped
            .network
            .curves()
            .iter()
            .find(|n| n.name == c.name)
            .expect("kept")
            .curve;
        let most = (0..=50)
            .map(|i| {
                let t = i as f64 / 50.0;
                new.point(t).distance(c.curve.point(t))
            })
            .fold(0.0, f64::max);
        assert!(most <= 1.01 * s.max_move, "{}: changed by {most} m", c.name);
    }
}

/// KCS faired section by section (`tests/data/kcs_faired_apart.json`): 144 near misses at the
/// default tolerance; snapped at 1 cm it builds there with none, and each curve stays smooth
/// where it was (its Bézier joints keep their tangents).
#[test]
fn faired_apart_kcs_builds_at_the_default_tolerance_once_snapped() {
    let path = format!(
        "{}/tests/data/kcs_faired_apart.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let net = Network::from_json(&std::fs::read_to_string(path).expect("fixture")).expect("reads");
    let before = Topology::build(&net, Tolerance::DEFAULT).expect("topology");
    assert!(near_misses(&before) > 100, "{}", near_misses(&before));
    let snapped =
        snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    let most = snapped.snaps.iter().map(|s| s.max_move).fold(0.0, f64::max);
    assert!(most < 0.01, "largest move {most} m");
    let hull = build_hull(&snapped.network, &HullOptions::default()).expect("builds");
    let r = &hull.report;
    let misses = r
        .warnings
        .iter()
        .filter(|w| w.kind == WarningKind::Network("near_miss"))
        .count();
    assert_eq!(misses, 0, "{:?}", r.warnings);
    assert!(r.faces >= 270, "{} faces", r.faces);
    for (old, new) in net.curves().iter().zip(snapped.network.curves()) {
        let (a, b) = (
            old.curve.corner_parameters(1f64.to_radians()),
            new.curve.corner_parameters(1f64.to_radians()),
        );
        assert_eq!(
            a.len(),
            b.len(),
            "'{}' keeps its corners and no more",
            old.name
        );
    }
}

#[test]
fn a_curve_leaves_out_the_node_its_data_forbid() {
    let station = station();
    let wl = cubic(
        "wl",
        [
            [-2.0, 0.775, 1.075],
            [-1.0, 0.975, 1.076],
            [1.0, 0.975, 1.076],
            [2.0, 0.775, 1.075],
        ],
    );
    // The waterline passes about 0.5 mm above the station; each curve's data are its own
    // points. Their nodes: the two ends of each and the crossing.
    let net = Network::try_new("cross", vec![station, wl]).expect("network");
    let samples = |c: &NetworkCurve| -> Vec<DVec3> {
        (0..=40).map(|i| c.curve.point(i as f64 / 40.0)).collect()
    };
    let data: Vec<Vec<DVec3>> = net.curves().iter().map(samples).collect();
    let capture = Tolerance::try_new(0.01).expect("capture");
    // Within 1 mm both move (by about half the miss each) and meet.
    let loose = SnapData {
        points: &data,
        tolerance: 1e-3,
    };
    let s = snap_to_nodes(&net, capture, Some(loose)).expect("snap");
    assert!(
        s.snaps.iter().all(|c| c.skipped == 0 && c.nodes == 3),
        "{:?}",
        s.snaps
    );
    // Within 0.2 mm neither may move 0.27 mm: both leave the crossing out and keep their data.
    let tight = SnapData {
        points: &data,
        tolerance: 2e-4,
    };
    let s = snap_to_nodes(&net, capture, Some(tight)).expect("snap");
    for c in &s.snaps {
        assert_eq!((c.nodes, c.skipped), (2, 1), "{c:?}");
        let (dev, _) = c.max_deviation.expect("measured");
        assert!(dev < 1e-9, "{}: {dev}", c.curve);
    }
    // Bad data are errors, not guesses.
    let short = SnapData {
        points: &data[..1],
        tolerance: 1e-3,
    };
    assert!(matches!(
        snap_to_nodes(&net, capture, Some(short)),
        Err(Error::InvalidInput(_))
    ));
    let mut nan = data.clone();
    nan[1][3].x = f64::NAN;
    let bad = SnapData {
        points: &nan,
        tolerance: 1e-3,
    };
    let err = snap_to_nodes(&net, capture, Some(bad)).expect_err("NaN");
    assert!(err.to_string().contains("'wl'"), "{err}");
    let zero = SnapData {
        points: &data,
        tolerance: 0.0,
    };
    assert!(matches!(
        snap_to_nodes(&net, capture, Some(zero)),
        Err(Error::Tolerance(_))
    ));
}

#[test]
fn a_duplicate_follows_the_curve_it_duplicates() {
    let station = station();
    let mut copy = station.clone();
    copy.name = "st copy".to_owned();
    copy.curve = copy.curve.try_reversed().expect("reversed");
    let wl = cubic(
        "wl",
        [
            [-2.0, 0.775, 1.0755],
            [-1.0, 0.975, 1.0755],
            [1.0, 0.975, 1.0755],
            [2.0, 0.775, 1.0755],
        ],
    );
    let net = Network::try_new("dup", vec![station, copy, wl]).expect("network");
    let s = snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    let (a, b) = (&s.network.curves()[0].curve, &s.network.curves()[1].curve);
    assert!(
        s.snaps[0].max_move > 1e-4,
        "the station moved: {:?}",
        s.snaps[0]
    );
    for i in 0..=20 {
        let p = a.point(i as f64 / 20.0);
        let d = b.nearest(p, 1e-12).expect("nearest").distance;
        assert!(d < 1e-9, "the copy follows: {d}");
    }
    // Run its own way still (it was reversed).
    assert!(b.point(b.domain().0).distance(a.point(a.domain().1)) < 1e-12);
    let t = Topology::build(&s.network, Tolerance::DEFAULT).expect("topology");
    let kinds: Vec<&str> = t.diagnostics.iter().map(|d| d.kind()).collect();
    assert!(
        kinds.contains(&"duplicate_curve") && !kinds.contains(&"near_miss"),
        "{kinds:?}"
    );
}

/// A fine stem: the profile in the centreplane raked 30°, a station in the plane x = 0 leaving
/// the stem with a slope of 1/20 off the centreplane, and a waterline in z = 0 leaving it at
/// 4° (with the profile and the station, three curves at one node, as at KCS's stem where
/// st20 and the design waterline meet the profile). Returns them with the station's slope off
/// the plane of the other two, in degrees.
fn stem(slope: f64, role: Role) -> (Vec<NetworkCurve>, f64) {
    stem_at(slope, role, 0.0)
}

/// [`stem`] moved by `dy` across the centreplane (off it, its profile is a free curve like
/// the others).
fn stem_at(slope: f64, role: Role, dy: f64) -> (Vec<NetworkCurve>, f64) {
    let (curves, off) = stem_in_centreplane(slope, role);
    let moved = curves
        .into_iter()
        .map(|c| {
            let pts: Vec<[f64; 3]> = c
                .curve
                .control_points()
                .iter()
                .map(|p| [p.x, p.y + dy, p.z])
                .collect();
            let mut m = cubic(&c.name, [pts[0], pts[1], pts[2], pts[3]]);
            m.role = c.role;
            m
        })
        .collect();
    (moved, off)
}

fn stem_in_centreplane(slope: f64, role: Role) -> (Vec<NetworkCurve>, f64) {
    let (rake, entrance) = (30f64.to_radians(), 4f64.to_radians());
    let p = DVec3::new(rake.sin(), 0.0, rake.cos());
    let mut profile = cubic(
        "profile",
        [
            (-p).to_array(),
            (-p / 3.0).to_array(),
            (p / 3.0).to_array(),
            p.to_array(),
        ],
    );
    profile.role = role;
    let s = DVec3::new(0.0, slope, 1.0).normalize();
    let station = cubic(
        "st20",
        [
            [0.0, 0.0, 0.0],
            (s / 3.0).to_array(),
            [0.0, 0.2, 0.66],
            [0.0, 0.4, 1.0],
        ],
    );
    let w = DVec3::new(-entrance.cos(), entrance.sin(), 0.0);
    let wl = cubic(
        "wl",
        [
            [0.0, 0.0, 0.0],
            (w / 3.0).to_array(),
            [-0.66, 0.15, 0.0],
            [-1.0, 0.3, 0.0],
        ],
    );
    let off = s.dot(p.cross(w).normalize()).abs().asin().to_degrees();
    (vec![profile, station, wl], off)
}

fn unit_tangent(c: &NetworkCurve, at: DVec3) -> DVec3 {
    let n = c.curve.nearest(at, 1e-12).expect("nearest");
    assert!(n.distance < 1e-9, "{} passes the node", c.name);
    c.curve.derivs(n.t).d1.normalize()
}

/// The tangents of the network's three curves at `node` lie in one plane.
fn assert_coplanar(network: &Network, node: DVec3) {
    let t: Vec<DVec3> = network
        .curves()
        .iter()
        .map(|c| unit_tangent(c, node))
        .collect();
    let triple = t[0].dot(t[1].cross(t[2])).abs();
    assert!(triple < 1e-9, "tangents {triple:e} off one plane");
}

#[test]
fn the_tangents_at_a_smooth_node_are_turned_into_one_plane() {
    let (curves, off) = stem(0.05, Role::Free);
    assert!(
        (0.2..1.0).contains(&off),
        "the station is {off}° off the plane"
    );
    let net = Network::try_new("stem", curves).expect("network");
    let s = snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    let node = DVec3::ZERO;
    assert_coplanar(&s.network, node);
    assert_eq!(s.smooth_nodes.len(), 1);
    let report = &s.smooth_nodes[0];
    assert!(report.position.length() < 1e-12);
    assert_eq!(report.curves.len(), 3);
    // The least-squares plane turns each tangent by less than the station's whole slope.
    assert!(report.turn_degrees > 0.05 * off && report.turn_degrees < off);
    for (idx, (snap, c)) in s.snaps.iter().zip(net.curves()).enumerate() {
        assert_eq!(snap.tangent_nodes, 1, "{}", c.name);
        assert!((snap.max_tangent_turn - report.turn_degrees).abs() < 1e-12);
        // Each turned by at most the node's turn, and moved little away from the node.
        let before = unit_tangent(c, node);
        let after = unit_tangent(&s.network.curves()[idx], node);
        assert!(before.angle_between(after).to_degrees() <= report.turn_degrees + 1e-9);
    }
    // The change is local: the station's far end stays.
    let far = s.network.curves()[1].curve.point(1.0);
    assert!(
        far.distance(net.curves()[1].curve.point(1.0)) < 1e-12,
        "the far end stays"
    );
}

#[test]
fn a_knuckle_node_or_one_far_off_a_plane_is_left_as_it_is() {
    // A chine through the node: its two sides have their own tangent planes.
    let (curves, _) = stem(0.05, Role::Knuckle);
    let net = Network::try_new("chine", curves).expect("network");
    let s = snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    assert!(s.smooth_nodes.is_empty());
    assert!(s.snaps.iter().all(|c| c.tangent_nodes == 0));
    // A station whose data allow it no turn: it keeps its shape, and the node is not reported
    // (the other two may still turn, towards it).
    let (curves, _) = stem(0.05, Role::Free);
    let points: Vec<Vec<DVec3>> = curves
        .iter()
        .map(|c| (0..=20).map(|i| c.curve.point(i as f64 / 20.0)).collect())
        .collect();
    let net = Network::try_new("held", curves).expect("network");
    let tight = SnapData {
        points: &points,
        tolerance: 1e-9,
    };
    let s = snap_to_nodes(
        &net,
        Tolerance::try_new(0.01).expect("capture"),
        Some(tight),
    )
    .expect("snap");
    assert_eq!(
        s.snaps[1].tangent_nodes, 0,
        "the station is held by its data"
    );
    assert!(s.snaps[1].max_deviation.expect("data").0 <= 1e-9);
    assert!(s.smooth_nodes.is_empty());
    // A station leaving the stem 5° off the others' plane: a crease in the data, not noise.
    let (curves, off) = stem(0.15, Role::Free);
    assert!(off > batten_core::MAX_TANGENT_TURN_DEGREES * 1.5, "{off}");
    let net = Network::try_new("crease", curves).expect("network");
    let s = snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    assert!(s.smooth_nodes.is_empty());
    for (a, b) in s.network.curves().iter().zip(net.curves()) {
        // Already through the node: the same shape (a knot inserted there at most).
        let moved = (0..=20)
            .map(|i| {
                a.curve
                    .point(i as f64 / 20.0)
                    .distance(b.curve.point(i as f64 / 20.0))
            })
            .fold(0.0, f64::max);
        assert!(moved < 1e-12, "{} moved {moved:e}", a.name);
    }
}

#[test]
fn a_curve_held_by_its_data_keeps_its_tangent_and_the_others_turn_into_a_plane_through_it() {
    // The station's data allow it no move; the profile's and the waterline's are only their
    // far ends, which a turn at the node leaves where they are. (Off the centreplane: a
    // profile in it turns only within it, and the plane is then fixed by both.)
    let (curves, off) = stem_at(0.05, Role::Free, 1.0);
    let points: Vec<Vec<DVec3>> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| match i {
            1 => (0..=20).map(|k| c.curve.point(k as f64 / 20.0)).collect(),
            0 => vec![c.curve.point(0.0), c.curve.point(1.0)],
            _ => vec![c.curve.point(1.0)],
        })
        .collect();
    let net = Network::try_new("held", curves).expect("network");
    let data = SnapData {
        points: &points,
        tolerance: 1e-9,
    };
    let capture = Tolerance::try_new(0.01).expect("capture");
    let s = snap_to_nodes(&net, capture, Some(data)).expect("snap");
    let node = DVec3::Y;
    assert_eq!(s.snaps[1].tangent_nodes, 0, "the station is held");
    assert_eq!((s.snaps[0].tangent_nodes, s.snaps[2].tangent_nodes), (1, 1));
    let given = unit_tangent(&net.curves()[1], node);
    let kept = unit_tangent(&s.network.curves()[1], node);
    assert!(
        given.angle_between(kept) < 1e-9,
        "the station keeps its tangent"
    );
    assert_coplanar(&s.network, node);
    // The plane is the one through the station's tangent: the others turn by the station's
    // whole slope off their plane between them (the least-squares plane of all three, as
    // before, would have turned each by less and left the station out of it by `off`/3).
    assert_eq!(s.smooth_nodes.len(), 1);
    let report = &s.smooth_nodes[0];
    assert!(report.normal.dot(kept).abs() < 1e-9);
    assert!(
        report.turn_degrees > 0.3 * off && report.turn_degrees <= off + 1e-9,
        "{off} {report:?}"
    );
}

#[test]
fn a_profile_in_the_centreplane_turns_only_within_it() {
    // The stem's three curves, the profile in the centreplane: the least-squares plane of the
    // three tangents would turn the profile's out of the centreplane, and the profile would
    // leave it between its ends (KCS's stem, 0.63 mm). It turns within the plane, and the
    // others into a plane through it.
    let (curves, off) = stem(0.05, Role::Free);
    let net = Network::try_new("stem", curves).expect("network");
    let s = snap_to_nodes(&net, Tolerance::try_new(0.01).expect("capture"), None).expect("snap");
    let node = DVec3::ZERO;
    assert_coplanar(&s.network, node);
    let profile = &s.network.curves()[0].curve;
    let off_plane = profile
        .control_points()
        .iter()
        .map(|p| p.y.abs())
        .fold(0.0, f64::max);
    assert!(
        off_plane < 1e-12,
        "the profile leaves the centreplane by {off_plane:e}"
    );
    let report = &s.smooth_nodes[0];
    assert!(
        report.turn_degrees > 0.0 && report.turn_degrees <= off + 1e-9,
        "{off} {report:?}"
    );
    assert_eq!(
        s.snaps[0].tangent_nodes, 1,
        "the profile is turned, within its plane"
    );
}
