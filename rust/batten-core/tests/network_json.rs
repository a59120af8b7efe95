//! The network JSON format: exact round trip, version refusal, named errors.

use batten_core::{
    Error, KnotLayout, Network, NetworkCurve, NurbsCurve, Role, TangentPlane, Tolerance,
};
use glam::DVec3;

fn network() -> Network {
    let pts: Vec<DVec3> = (0..6)
        .map(|i| {
            DVec3::new(
                0.1 * i as f64 / 3.0,
                (i as f64).sin() / 7.0,
                1.0 / (1.0 + i as f64),
            )
        })
        .collect();
    let a = NurbsCurve::from_layout(
        &pts,
        Some(&[1.0, 0.3, 2.0, 1.0, 0.7, 1.0]),
        4,
        KnotLayout::Endpoint,
        false,
    )
    .unwrap();
    let b = NurbsCurve::from_polyline(&pts[..3], false).unwrap();
    Network::try_new(
        "test hull",
        vec![
            NetworkCurve {
                name: "stn 1".into(),
                role: Role::Free,
                curve: a,
            },
            NetworkCurve {
                name: "chine".into(),
                role: Role::Knuckle,
                curve: b,
            },
        ],
    )
    .unwrap()
}

#[test]
fn json_round_trip_is_exact() {
    let net = network();
    let text = net.to_json();
    let back = Network::from_json(&text).unwrap();
    assert_eq!(back, net, "bitwise-equal curves after a round trip");
    assert_eq!(back.to_json(), text, "and the same text");
    assert!(text.contains("\"version\": 1"), "versioned");
}

#[test]
fn newer_version_and_foreign_files_are_refused() {
    let text = network()
        .to_json()
        .replace("\"version\": 1", "\"version\": 99");
    match Network::from_json(&text) {
        Err(Error::Format(msg)) => assert!(msg.contains("99"), "{msg}"),
        other => panic!("expected a format error, got {other:?}"),
    }
    assert!(
        matches!(
            Network::from_json("{\"curves\": []}"),
            Err(Error::Format(_))
        ),
        "no format tag"
    );
    assert!(
        matches!(Network::from_json("not json"), Err(Error::Format(_))),
        "not JSON"
    );
}

#[test]
fn bad_curve_in_file_is_named() {
    let text = network()
        .to_json()
        .replacen("\"degree\": 3", "\"degree\": 7", 1);
    let err = Network::from_json(&text).unwrap_err();
    assert!(err.to_string().starts_with("curve 'stn 1':"), "{err}");
}

#[test]
fn duplicate_names_and_zero_length_are_reported() {
    let c = NurbsCurve::from_polyline(&[DVec3::ZERO, DVec3::X], false).unwrap();
    let dup = Network::try_new(
        "n",
        vec![
            NetworkCurve {
                name: "a".into(),
                role: Role::Free,
                curve: c.clone(),
            },
            NetworkCurve {
                name: "a".into(),
                role: Role::Free,
                curve: c,
            },
        ],
    );
    assert_eq!(
        dup.unwrap_err(),
        Error::DuplicateName("a".into()),
        "duplicate name"
    );
    let dot = NurbsCurve::from_polyline(&[DVec3::ONE, DVec3::ONE + 1e-7], false).unwrap();
    let net = Network::try_new(
        "n",
        vec![NetworkCurve {
            name: "dot".into(),
            role: Role::Free,
            curve: dot,
        }],
    )
    .unwrap();
    let err = net.check_lengths(Tolerance::DEFAULT).unwrap_err();
    assert!(
        err.to_string().contains("'dot'") && err.to_string().contains("zero length"),
        "{err}"
    );
}

#[test]
fn roles_have_stable_names() {
    for r in Role::ALL {
        assert_eq!(Role::from_name(r.name()), Some(r), "round trip of {r:?}");
    }
    assert_eq!(
        Role::from_name("KNUCKLE"),
        Some(Role::Knuckle),
        "case-insensitive"
    );
    assert_eq!(Role::from_name("bulb"), None, "unknown");
}

/// The flat of side and of bottom of an imported ship, as `api.import_sections` gives them.
fn with_planes() -> Network {
    network().with_tangent_planes(vec![
        TangentPlane::try_new(DVec3::Y, 16.1003).unwrap(),
        TangentPlane::try_new(DVec3::Y, -16.1003).unwrap(),
        TangentPlane::try_new(DVec3::new(0.0, 0.6, 0.8), 0.1 / 3.0).unwrap(),
    ])
}

#[test]
fn tangent_planes_round_trip_exactly_as_version_2() {
    let net = with_planes();
    let text = net.to_json();
    assert!(
        text.contains("\"version\": 2"),
        "planes need version 2: {text}"
    );
    let back = Network::from_json(&text).unwrap();
    assert_eq!(
        back.tangent_planes(),
        net.tangent_planes(),
        "bitwise-equal planes"
    );
    assert_eq!(back, net, "and curves");
    assert_eq!(back.to_json(), text, "and the same text");
    assert!(
        !network().to_json().contains("tangent_planes"),
        "a network without planes is written as before (version 1)"
    );
}

#[test]
fn tangent_planes_in_a_version_1_file_and_bad_planes_are_refused_by_index() {
    let text = with_planes().to_json();
    let v1 = text.replace("\"version\": 2", "\"version\": 1");
    let err = Network::from_json(&v1).unwrap_err().to_string();
    assert!(
        err.contains("tangent_planes") && err.contains("version 2"),
        "{err}"
    );
    for (bad, what) in [
        (serde_json::json!([0.0, 0.0, 0.0, 1.0]), "non-zero"),
        (serde_json::json!([0.0, 1.0, 0.0]), "[nx, ny, nz, offset]"),
        (serde_json::json!("side"), "[nx, ny, nz, offset]"),
    ] {
        let mut file: serde_json::Value = serde_json::from_str(&text).unwrap();
        file["tangent_planes"][1] = bad.clone();
        let err = Network::from_json(&file.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("tangent plane 1") && err.contains(what),
            "{bad}: {err}"
        );
    }
}
