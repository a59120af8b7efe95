//! The hull report's warnings are data (H-rep paper §5.2): kind, message, curves, place and the
//! underlying error, for topology findings and for the hull's own warnings alike.

use batten_core::{
    build_hull, FaceError, HullOptions, Network, NetworkCurve, NurbsCurve, PatchError, Role,
    WarningKind,
};
use glam::DVec3;

fn line(name: &str, a: [f64; 3], b: [f64; 3]) -> NetworkCurve {
    NetworkCurve {
        name: name.to_owned(),
        role: Role::Free,
        curve: NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![DVec3::from(a), DVec3::from(b)],
            None,
        )
        .expect("line"),
    }
}

/// A triangle whose corner at the origin is `deg` degrees wide.
fn sliver(deg: f64) -> Network {
    let a = deg.to_radians();
    let tip = [10.0 * a.cos(), 10.0 * a.sin(), 0.0];
    Network::try_new(
        "sliver",
        vec![
            line("base", [0.0; 3], [10.0, 0.0, 0.0]),
            line("slant", [0.0; 3], tip),
            line("end", [10.0, 0.0, 0.0], tip),
        ],
    )
    .expect("network")
}

#[test]
fn degenerate_corner_is_a_typed_warning_at_its_face() {
    let r = build_hull(&sliver(0.5), &HullOptions::default())
        .expect("the sliver is built")
        .report;
    let w = r
        .warnings
        .iter()
        .find(|w| w.kind == WarningKind::DegenerateCorner)
        .expect("the 0.5° corner is reported");
    assert_eq!(w.kind.as_str(), "degenerate_corner", "its tag");
    let mut curves = w.curves.clone();
    curves.sort();
    assert_eq!(
        curves,
        ["base", "end", "slant"],
        "the face's curves by name"
    );
    let at = w.location.expect("a face warning has a place");
    let a = 0.5f64.to_radians();
    let centre = DVec3::new(10.0 + 10.0 * a.cos(), 10.0 * a.sin(), 0.0) / 3.0;
    assert!(
        (at - centre).length() < 1e-9,
        "the place is the mean of the face's three nodes: {at}"
    );
    assert!(w.error.is_none(), "a repair, not a failure");
    assert!(
        w.message.contains("0.50°"),
        "the sentence says the angle: {}",
        w.message
    );
    // An 8° corner is not degenerate: no warning (the test can fail both ways) but the hole
    // its rim off the centreplane is (the sliver is no half hull).
    let ok = build_hull(&sliver(8.0), &HullOptions::default()).expect("built");
    let kinds: Vec<WarningKind> = ok.report.warnings.iter().map(|w| w.kind).collect();
    assert_eq!(kinds, [WarningKind::Hole], "{:?}", ok.report.warnings);
}

#[test]
fn a_cusp_corner_gets_the_side_blended_patch_and_says_so() {
    // At a 0.5° corner a corner-based patch has no tangent plane to interpolate; the
    // side-blended patch has no corner interpolants, and is used where it folds no more.
    let r = build_hull(&sliver(0.5), &HullOptions::default())
        .expect("built")
        .report;
    let blended: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.kind == WarningKind::SideBlended)
        .collect();
    assert_eq!(blended.len(), 1, "{:?}", r.warnings);
    let message = &blended[0].message;
    assert!(
        message.contains("cusp") && message.contains("0.50°"),
        "{message}"
    );
    // A 3° corner needs no repair of its ribbons, and is still a cusp: the two sides' 3° span
    // the corner-based patch's tangent plane there to a few hundredths of their directions'
    // accuracy (KVLCC2's station 20 meeting the stem at 3.5° creased 5.8°).
    let narrow = build_hull(&sliver(3.0), &HullOptions::default())
        .expect("built")
        .report;
    let kinds: Vec<WarningKind> = narrow.warnings.iter().map(|w| w.kind).collect();
    assert_eq!(
        kinds,
        [WarningKind::SideBlended, WarningKind::Hole],
        "{:?}",
        narrow.warnings
    );
    assert!(narrow.warnings[0].message.contains("3.00°"));
    // An 8° corner keeps the corner-based patch.
    let ok = build_hull(&sliver(8.0), &HullOptions::default()).expect("built");
    assert!(
        ok.report
            .warnings
            .iter()
            .all(|w| w.kind != WarningKind::SideBlended),
        "{:?}",
        ok.report.warnings
    );
}

#[test]
fn warnings_serialise_with_kind_place_and_error() {
    let r = build_hull(&sliver(0.5), &HullOptions::default())
        .expect("built")
        .report;
    let json = serde_json::to_value(&r).expect("report serialises");
    let w = &json["warnings"][0];
    assert_eq!(w["kind"], "degenerate_corner", "{w}");
    assert_eq!(w["curves"].as_array().map(Vec::len), Some(3), "{w}");
    assert_eq!(w["location"].as_array().map(Vec::len), Some(3), "{w}");
    assert!(w["error"].is_null(), "{w}");
    assert_eq!(
        json["node_positions"].as_array().map(Vec::len),
        Some(3),
        "three nodes"
    );
    assert_eq!(
        json["node_kinds"][0], "end_to_end",
        "{}",
        json["node_kinds"]
    );
}

#[test]
fn face_error_tags_name_the_patch_error() {
    let e = FaceError::from(PatchError::RibbonCount {
        expected: 4,
        got: 3,
    });
    assert_eq!(
        e.kind(),
        "ribbon_count",
        "the patch error's tag passes through"
    );
    assert_eq!(
        e.to_string(),
        "3 side ribbons given for 4 sides",
        "and its message"
    );
    assert_eq!(
        FaceError::SideCount { sides: 17 }.kind(),
        "side_count",
        "own tag"
    );
}
