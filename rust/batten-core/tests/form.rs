//! Form topology and its transformations (Bole, seed 002, §6–§7) on the frigate network of the
//! examples (no parallel middle body) and on a box-like barge with a parallel middle body,
//! flat of side and bottom, rise of floor and a circular bilge.

mod common;

use batten_core::{
    build_hull, fairness_metrics, form_topology, hydrostatics, transform, transform_hydrostatic,
    transform_to, CellDensity, EdgeKind, Flotation, FormError, FormOptions, FormTopology,
    HullOptions, HydroTargets, HydroTransformOptions, HydroTransformed, Network, NurbsCurve,
    PmbHold, Role, Stop, TangentPlane, Target, Tolerance, VertexMove, VolumeTarget, LCB_TOLERANCE,
    SEA_WATER_DENSITY, VOLUME_TOLERANCE,
};
use common::nc;
use glam::DVec3;

/// Half breadth, depth and draft of the barge.
const HB: f64 = 10.0;
const D: f64 = 12.0;
const T: f64 = 8.0;

fn examples() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn frigate() -> Network {
    let text =
        std::fs::read_to_string(examples().join("frigate_network.json")).expect("frigate file");
    Network::from_json(&text).expect("valid network")
}

/// A degree-2 curve of Bézier pieces (knots doubled between pieces), optional weights.
fn pieces(pts: &[DVec3], weights: Option<Vec<f64>>) -> NurbsCurve {
    let n = (pts.len() - 1) / 2;
    let mut knots = vec![0.0; 3];
    for k in 1..n {
        knots.extend([k as f64, k as f64]);
    }
    knots.extend([n as f64; 3]);
    NurbsCurve::try_new(2, knots, pts.to_vec(), weights).expect("valid curve")
}

/// The x where a curve reaches `x` (bisection on a curve whose x is monotone).
fn at_x(c: &NurbsCurve, x: f64) -> DVec3 {
    let (mut a, mut b) = c.domain();
    let up = c.point(b).x > c.point(a).x;
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (c.point(m).x < x) == up {
            a = m;
        } else {
            b = m;
        }
    }
    c.point(0.5 * (a + b))
}

/// The bilge corner, its tangent points and the corner weight for radius `r` and rise of floor
/// `rise` at half breadth.
fn bilge(r: f64, rise: f64) -> (DVec3, DVec3, DVec3, f64) {
    let k = DVec3::new(0.0, HB, rise);
    let ub = DVec3::new(0.0, -HB, -rise).normalize();
    let us = DVec3::Z;
    let phi = 0.5 * ub.angle_between(us);
    let l = r / phi.tan();
    (k, k + ub * l, k + us * l, phi.sin())
}

/// The barge: PMB from x = 40 to 60, flat of side and bottom curves running into the ends,
/// stations at x = 10 and 90, raked stem and stern profiles.
fn barge(r: f64, rise: f64) -> Network {
    let (k, fob, fos, w) = bilge(r, rise);
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let section = |x: f64| {
        let at = |q: DVec3| p(x, q.y, q.z);
        let keel = p(x, 0.0, 0.0);
        let deck = p(x, HB, D);
        pieces(
            &[
                keel,
                (keel + at(fob)) * 0.5,
                at(fob),
                at(k),
                at(fos),
                (at(fos) + deck) * 0.5,
                deck,
            ],
            Some(vec![1.0, 1.0, 1.0, w, 1.0, 1.0, 1.0]),
        )
    };
    let (yb, zb, zs) = (fob.y, fob.z, fos.z);
    let deck = pieces(
        &[
            p(0.0, 0.0, D),
            p(8.0, HB, D),
            p(15.0, HB, D),
            p(27.5, HB, D),
            p(40.0, HB, D),
            p(50.0, HB, D),
            p(60.0, HB, D),
            p(72.5, HB, D),
            p(85.0, HB, D),
            p(92.0, HB, D),
            p(100.0, 0.0, D),
        ],
        None,
    );
    let station = |x: f64| {
        let top = at_x(&deck, x);
        let yd = top.y;
        NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            vec![
                p(x, 0.0, 0.0),
                p(x, 0.7 * yd, 0.6),
                p(x, 1.2 * yd, 0.45 * D),
                p(x, 0.8 * yd, 0.75 * D),
                top,
            ],
            None,
        )
        .expect("station")
    };
    let keel = NurbsCurve::try_new(
        1,
        vec![0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 5.0],
        [5.0, 20.0, 40.0, 60.0, 80.0, 95.0]
            .map(|x| p(x, 0.0, 0.0))
            .to_vec(),
        None,
    )
    .expect("keel");
    let fos_curve = pieces(
        &[
            p(15.0, HB, D),
            p(28.0, HB, zs),
            p(40.0, HB, zs),
            p(50.0, HB, zs),
            p(60.0, HB, zs),
            p(72.0, HB, zs),
            p(85.0, HB, D),
        ],
        None,
    );
    let fob_curve = pieces(
        &[
            p(20.0, 0.0, 0.0),
            p(30.0, yb, zb),
            p(40.0, yb, zb),
            p(50.0, yb, zb),
            p(60.0, yb, zb),
            p(70.0, yb, zb),
            p(80.0, 0.0, 0.0),
        ],
        None,
    );
    let stern = pieces(&[p(5.0, 0.0, 0.0), p(0.0, 0.0, 2.0), p(0.0, 0.0, D)], None);
    let stem = pieces(
        &[p(95.0, 0.0, 0.0), p(100.0, 0.0, 2.0), p(100.0, 0.0, D)],
        None,
    );
    let st10 = station(10.0);
    let st90 = station(90.0);
    Network::try_new(
        "barge",
        vec![
            nc("keel", Role::Keel, keel),
            nc("stern", Role::Transom, stern),
            nc("stem", Role::Stem, stem),
            nc("deck", Role::Deck, deck),
            nc("ms_aft", Role::Midship, section(40.0)),
            nc("ms_fwd", Role::Midship, section(60.0)),
            nc("fos", Role::Fos, fos_curve),
            nc("fob", Role::Fob, fob_curve),
            nc("st10", Role::Free, st10),
            nc("st90", Role::Free, st90),
        ],
    )
    .expect("barge network")
}

fn options(draft: f64) -> FormOptions {
    FormOptions {
        tolerance: Tolerance::DEFAULT,
        draft: Some(draft),
    }
}

fn curve<'a>(n: &'a Network, name: &str) -> &'a NurbsCurve {
    &n.curves()
        .iter()
        .find(|c| c.name == name)
        .expect("curve")
        .curve
}

fn index(n: &Network, name: &str) -> usize {
    n.curves()
        .iter()
        .position(|c| c.name == name)
        .expect("curve")
}

/// Warning kinds of the built surface, counted, and their messages.
fn warnings(n: &Network) -> (std::collections::BTreeMap<String, usize>, Vec<String>) {
    let hull = build_hull(n, &HullOptions::try_new(1e-4, 8).unwrap()).expect("hull builds");
    let mut out = std::collections::BTreeMap::new();
    for w in &hull.report.warnings {
        *out.entry(format!("{:?}", w.kind)).or_insert(0) += 1;
    }
    (
        out,
        hull.report
            .warnings
            .iter()
            .map(|w| w.message.clone())
            .collect(),
    )
}

fn no_new_warnings(before: &Network, after: &Network, what: &str) {
    let ((a, _), (b, messages)) = (warnings(before), warnings(after));
    for (k, n) in &b {
        assert!(
            a.get(k).copied().unwrap_or(0) >= *n,
            "{what}: new warning {k}: before {a:?}, after {b:?}: {messages:#?}"
        );
    }
}

fn max_point_distance(a: &Network, b: &Network) -> f64 {
    a.curves()
        .iter()
        .zip(b.curves())
        .flat_map(|(p, q)| {
            assert_eq!(
                p.curve.knots(),
                q.curve.knots(),
                "curve '{}' kept its knots",
                p.name
            );
            p.curve
                .control_points()
                .into_iter()
                .zip(q.curve.control_points())
                .map(|(x, y)| x.distance(y))
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max)
}

#[test]
fn frigate_has_no_parallel_middle_body() {
    let n = frigate();
    let form = form_topology(&n, &options(4.8)).unwrap();
    let p = &form.parameters;
    assert!(p.pmb.is_none(), "{p:?}");
    assert!(
        p.no_pmb_reason.as_deref().unwrap().contains("midship"),
        "{:?}",
        p.no_pmb_reason
    );
    assert!(p.entrance_length.is_none() && p.run_length.is_none() && p.bilges.is_empty());
    assert_near!(p.length, 120.0, 1e-9);
    assert_near!(p.depth, 9.6, 1e-9);
    // The knuckle ends on station st6, which so becomes a form curve; the cwl does not.
    assert!(
        form.is_form_curve[index(&n, "st6")],
        "st6 carries the knuckle's end"
    );
    assert!(!form.is_form_curve[index(&n, "cwl")], "cwl is a free curve");
    assert!(
        form.faces.len() >= 3,
        "aft of st6, below and above the knuckle: {}",
        form.faces.len()
    );
    // The cwl lies in the waterplane z = 4.8: the waterline breadth is twice its largest y.
    let cwl = curve(&n, "cwl");
    let half = (0..=20_000)
        .map(|j| cwl.point(j as f64 / 20_000.0).y)
        .fold(0.0, f64::max);
    assert_near!(p.waterline_breadth.unwrap(), 2.0 * half, 1e-6);
    assert!(p.waterline_breadth.unwrap() < p.breadth, "{p:?}");
}

#[test]
fn barge_form_is_identified_and_measured() {
    let n = barge(2.0, 0.2);
    let form = form_topology(&n, &options(T)).unwrap();
    let p = &form.parameters;
    let pmb = p.pmb.as_ref().expect("a PMB");
    assert_near!(pmb.length, 20.0, 1e-12);
    assert_near!(pmb.position, 50.0, 1e-12);
    assert_near!(p.entrance_length.unwrap(), 40.0, 1e-9);
    assert_near!(p.run_length.unwrap(), 40.0, 1e-9);
    assert_near!(p.breadth, 2.0 * HB, 1e-9);
    assert_near!(p.waterline_breadth.unwrap(), 2.0 * HB, 1e-9);
    assert_eq!(p.bilges.len(), 2, "both midship sections have a bilge");
    for b in &p.bilges {
        assert_near!(b.radius.unwrap(), 2.0, 1e-9);
        assert_near!(b.rise_of_floor, 0.2, 1e-9);
    }
    let kinds = |c: &str| -> Vec<EdgeKind> {
        let i = index(&n, c);
        form.edges
            .iter()
            .filter(|e| e.curve == i)
            .map(|e| e.kind)
            .collect()
    };
    assert_eq!(
        kinds("ms_aft"),
        vec![EdgeKind::Straight, EdgeKind::Blend, EdgeKind::Straight]
    );
    assert!(kinds("keel").iter().all(|k| *k == EdgeKind::Straight));
    assert_eq!(
        kinds("fos"),
        vec![EdgeKind::FreeForm, EdgeKind::Straight, EdgeKind::FreeForm]
    );
    assert!(!form.is_form_curve[index(&n, "st10")]);
}

fn bwl(n: &Network) -> f64 {
    form_topology(n, &options(T))
        .unwrap()
        .parameters
        .waterline_breadth
        .unwrap()
}

#[test]
fn barge_breadth_plus_five_percent_keeps_the_bilge() {
    let n = barge(2.0, 0.2);
    let form = form_topology(&n, &options(T)).unwrap();
    let b0 = form.parameters.breadth;
    let out = transform_to(&n, &form, Target::Breadth(1.05 * b0), Tolerance::DEFAULT).unwrap();
    let after = form_topology(&out.network, &options(T)).unwrap();
    assert_near!(after.parameters.breadth, 1.05 * b0, 1e-3);
    assert_near!(bwl(&out.network), 1.05 * bwl(&n), 1e-3);
    for b in &after.parameters.bilges {
        assert_near!(b.radius.unwrap(), 2.0, 1e-6, "bilge radius unchanged");
    }
    for st in ["st10", "st90"] {
        assert_eq!(
            fairness_metrics(curve(&out.network, st)).inflections,
            fairness_metrics(curve(&n, st)).inflections,
            "{st} keeps its inflections"
        );
    }
    no_new_warnings(&n, &out.network, "barge");
    // The inverse returns the network.
    let back = transform_to(
        &out.network,
        &after,
        Target::Breadth(b0),
        Tolerance::DEFAULT,
    )
    .unwrap();
    let d = max_point_distance(&n, &back.network);
    assert!(
        d <= 1e-9,
        "breadth and back: {d:e} (re-attached {:?})",
        back.reattached
    );
}

#[test]
fn barge_pmb_length_plus_ten_metres_keeps_the_planes() {
    let n = barge(2.0, 0.2);
    let form = form_topology(&n, &options(T)).unwrap();
    let out = transform_to(&n, &form, Target::PmbLength(30.0), Tolerance::DEFAULT).unwrap();
    let after = form_topology(&out.network, &options(T)).unwrap();
    let pmb = after.parameters.pmb.as_ref().unwrap();
    assert_near!(pmb.length, 30.0, 1e-9);
    assert_near!(pmb.position, 50.0, 1e-9);
    assert_near!(after.parameters.length, 100.0, 1e-9, "the ends stay");
    for p in curve(&out.network, "deck").control_points() {
        assert_near!(p.z, D, 1e-12, "deck stays in its plane");
    }
    for p in curve(&out.network, "fos").control_points() {
        assert_near!(p.y, HB, 1e-12, "flat of side curve stays in its plane");
    }
    for p in curve(&out.network, "fob").control_points() {
        assert_near!(
            p.z,
            0.02 * p.y,
            1e-12,
            "flat of bottom curve stays in its plane"
        );
    }
    no_new_warnings(&n, &out.network, "barge");
    let back = transform_to(
        &out.network,
        &after,
        Target::PmbLength(20.0),
        Tolerance::DEFAULT,
    )
    .unwrap();
    let d = max_point_distance(&n, &back.network);
    assert!(
        d <= 1e-9,
        "PMB +10 m and back: {d:e} (re-attached {:?})",
        back.reattached
    );
}

#[test]
fn barge_bilge_radius_two_to_two_and_a_half() {
    let n = barge(2.0, 0.2);
    let form = form_topology(&n, &options(T)).unwrap();
    let out = transform_to(&n, &form, Target::BilgeRadius(2.5), Tolerance::DEFAULT).unwrap();
    let after = form_topology(&out.network, &options(T)).unwrap();
    assert_eq!(after.parameters.bilges.len(), 2);
    for (b0, b1) in form.parameters.bilges.iter().zip(&after.parameters.bilges) {
        assert_near!(b1.radius.unwrap(), 2.5, 1e-3);
        assert_near!(b1.rise_of_floor, 0.2, 1e-9, "rise of floor kept");
        let (fob0, fob1) = (
            form.vertices[b0.fob_vertex].position,
            after.vertices[b1.fob_vertex].position,
        );
        let (fos0, fos1) = (
            form.vertices[b0.fos_vertex].position,
            after.vertices[b1.fos_vertex].position,
        );
        assert_near!(
            fob1.z,
            0.02 * fob1.y,
            1e-9,
            "FOB vertex on the bottom plane"
        );
        assert_near!(fos1.y, HB, 1e-9, "FOS vertex on the side plane");
        assert!(
            fob1.y < fob0.y && fos1.z > fos0.z,
            "both arc ends moved away from the corner"
        );
    }
    // The flat of side and bottom curves followed the arc's ends and stayed in their planes.
    for p in curve(&out.network, "fos").control_points() {
        assert_near!(p.y, HB, 1e-12);
    }
    for p in curve(&out.network, "fob").control_points() {
        assert_near!(p.z, 0.02 * p.y, 1e-12);
    }
    no_new_warnings(&n, &out.network, "barge");
    let back = transform_to(
        &out.network,
        &after,
        Target::BilgeRadius(2.0),
        Tolerance::DEFAULT,
    )
    .unwrap();
    let d = max_point_distance(&n, &back.network);
    assert!(d <= 1e-9, "bilge 2.5 and back: {d:e}");
}

#[test]
fn a_move_that_breaks_a_connection_is_refused_naming_the_curves() {
    let n = barge(2.0, 0.2);
    let form = form_topology(&n, &options(T)).unwrap();
    let ms_fwd = index(&n, "ms_fwd");
    let keel = index(&n, "keel");
    let v = form
        .vertices
        .iter()
        .position(|v| v.curves.contains(&ms_fwd) && v.curves.contains(&keel))
        .unwrap();
    // The forward midship section pushed behind the aft one.
    let err = transform(
        &n,
        &form,
        &[VertexMove {
            vertex: v,
            translation: DVec3::new(-30.0, 0.0, 0.0),
        }],
        Tolerance::DEFAULT,
    )
    .unwrap_err();
    match &err {
        FormError::ConnectionLost { curves, .. } => {
            assert_eq!(curves.len(), 2, "{err}");
            assert!(
                curves
                    .iter()
                    .all(|c| n.curves().iter().any(|k| &k.name == c)),
                "{err}"
            );
        }
        e => panic!("expected a lost connection, got {e}"),
    }
    let bad = transform(
        &n,
        &form,
        &[VertexMove {
            vertex: form.vertices.len(),
            translation: DVec3::X,
        }],
        Tolerance::DEFAULT,
    );
    assert!(matches!(bad, Err(FormError::BadMove { .. })), "{bad:?}");
}

#[test]
fn frigate_breadth_depth_and_a_vertex_drag() {
    let n = frigate();
    let form: FormTopology = form_topology(&n, &options(4.8)).unwrap();
    let p = form.parameters.clone();
    let out = transform_to(
        &n,
        &form,
        Target::Breadth(1.05 * p.breadth),
        Tolerance::DEFAULT,
    )
    .unwrap();
    let after = form_topology(&out.network, &options(4.8)).unwrap();
    assert_near!(
        after.parameters.waterline_breadth.unwrap(),
        1.05 * p.waterline_breadth.unwrap(),
        1e-3
    );
    for c in n.curves().iter().filter(|c| c.name.starts_with("st")) {
        assert_eq!(
            fairness_metrics(curve(&out.network, &c.name)).inflections,
            fairness_metrics(&c.curve).inflections,
            "{} keeps its inflections",
            c.name
        );
    }
    no_new_warnings(&n, &out.network, "breadth");
    let deeper = transform_to(&n, &form, Target::Depth(p.depth + 1.0), Tolerance::DEFAULT).unwrap();
    let d = form_topology(&deeper.network, &options(4.8)).unwrap();
    assert_near!(d.parameters.depth, p.depth + 1.0, 1e-6);
    // Implementation note: the rebuilt frigate loses the faces by the stem 'rounding' after a
    // depth change (an unclosed region there); depth is checked by its measure only.
    assert!(matches!(
        transform_to(&n, &form, Target::PmbLength(30.0), Tolerance::DEFAULT),
        Err(FormError::NoParallelMiddleBody { .. })
    ));
    // Drag the deck's aft corner outwards by 0.3 m.
    let corner = form
        .vertices
        .iter()
        .position(|v| {
            v.curves.contains(&index(&n, "deck")) && v.curves.contains(&index(&n, "transom"))
        })
        .unwrap();
    let dragged = transform(
        &n,
        &form,
        &[VertexMove {
            vertex: corner,
            translation: DVec3::new(0.0, 0.3, 0.0),
        }],
        Tolerance::DEFAULT,
    )
    .unwrap();
    let moved = form_topology(&dragged.network, &options(4.8)).unwrap();
    assert_near!(
        moved.vertices[corner].position,
        form.vertices[corner].position + DVec3::new(0.0, 0.3, 0.0),
        1e-9
    );
    no_new_warnings(&n, &dragged.network, "drag");
}

// Hydrostatic transformations (seed 002 §8): the barge's PMB ends moved to hit ∇ and LCB.

fn hydro_options() -> HydroTransformOptions {
    HydroTransformOptions {
        draft: T,
        datums: None,
        lpp: None,
        density: SEA_WATER_DENSITY,
        hull: HullOptions::try_new(Tolerance::DEFAULT.get(), 8).unwrap(),
    }
}

/// The result's hydrostatics recomputed from its network alone (not the solver's figures).
fn recheck(out: &HydroTransformed) -> batten_core::Hydrostatics {
    recheck_at(out, T)
}

/// [`recheck`] floating at `draft`.
fn recheck_at(out: &HydroTransformed, draft: f64) -> batten_core::Hydrostatics {
    let o = hydro_options();
    let hull = build_hull(&out.network, &o.hull).unwrap();
    let cells = hull.hydro_model(CellDensity::DEFAULT);
    let f = Flotation {
        draft,
        trim: 0.0,
        heel_deg: 0.0,
        density: SEA_WATER_DENSITY,
    };
    hydrostatics(&cells, &f, &out.datums).unwrap()
}

/// Converged within the tolerances, in at most 12 hull evaluations, confirmed by a fresh
/// build; the midship sections only moved along x, the deck stayed in its plane.
fn assert_hit(n: &Network, out: &HydroTransformed, what: &str) {
    assert_eq!(out.stop, Stop::Converged, "{what}: {:?}", out.stop);
    assert!(
        out.evaluations <= 12,
        "{what}: {} evaluations",
        out.evaluations
    );
    let h = recheck(out);
    let lpp = out.datums.x_fp - out.datums.x_ap;
    let dv = (h.volume / out.target_volume - 1.0).abs();
    let dl = (h.lcb - out.target_lcb).abs() / lpp;
    assert!(dv <= VOLUME_TOLERANCE, "{what}: volume misses by {dv:e}");
    assert!(dl <= LCB_TOLERANCE, "{what}: LCB misses by {dl:e} Lpp");
    for name in ["ms_aft", "ms_fwd"] {
        let (a, b) = (curve(n, name), curve(&out.network, name));
        let dx = b.control_points()[0].x - a.control_points()[0].x;
        for (p, q) in a.control_points().iter().zip(b.control_points()) {
            assert_near!(
                q.x - p.x,
                dx,
                1e-9,
                "{what}: {name} moves along x as a whole"
            );
            assert_near!(q.y, p.y, 1e-9, "{what}: {name} keeps its shape");
            assert_near!(q.z, p.z, 1e-9, "{what}: {name} keeps its shape");
        }
    }
    for p in curve(&out.network, "deck").control_points() {
        assert_near!(p.z, D, 1e-12, "{what}: the deck stays in its plane");
    }
    for p in curve(&out.network, "fos").control_points() {
        assert_near!(
            p.y,
            HB,
            1e-12,
            "{what}: the flat of side stays in its plane"
        );
    }
    no_new_warnings(n, &out.network, what);
}

#[test]
fn barge_cb_plus_one_hundredth_with_lcb_held() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let before = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    assert_eq!(
        before.evaluations, 1,
        "nothing asked: the original is the answer"
    );
    let cb = before.before.cb + 0.01;
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(cb)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    assert_hit(&n, &out, "Cb + 0.01");
    assert_near!(recheck(&out).cb, cb, 1e-5 * cb, "Cb reached");
    assert_near!(out.target_lcb, out.before.lcb, 0.0, "LCB held at its value");
    assert!(
        out.pmb_length.unwrap()[1] > out.pmb_length.unwrap()[0] + 10.0,
        "a fuller hull has a longer PMB: {:?}",
        out.pmb_length.unwrap()
    );
}

#[test]
fn a_hydrostatic_transformation_measures_its_hulls_with_their_tangent_planes() {
    // The flat of side and bottom as the import holds them (KCS, KVLCC2): every hull the
    // solver evaluates, and the one it returns, is built with them, as the designer's build is.
    let planes = vec![
        TangentPlane::try_new(DVec3::Y, HB).unwrap(),
        TangentPlane::try_new(DVec3::Z, 0.0).unwrap(),
    ];
    let n = barge(2.0, 0.2).with_tangent_planes(planes.clone());
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb + 0.01)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    assert_hit(&n, &out, "Cb + 0.01 with tangent planes");
    assert_eq!(
        out.network.tangent_planes(),
        &planes[..],
        "the planes go with the hull"
    );
    let again = recheck(&out);
    assert_eq!(
        again.volume, out.after.volume,
        "the hull returned is the hull measured"
    );
}

#[test]
fn barge_lcb_forward_and_aft_with_volume_held_mirror_each_other() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let lpp = base.datums.x_fp - base.datums.x_ap;
    let mut runs = Vec::new();
    for sign in [1.0, -1.0] {
        let targets = HydroTargets {
            volume: None,
            lcb: Some(base.before.lcb + sign * 0.0025 * lpp),
            hold: PmbHold::Free,
        };
        let out = transform_hydrostatic(&n, targets, &o).unwrap();
        assert_hit(&n, &out, "LCB ± 0.25 % Lpp");
        runs.push(out);
    }
    // The barge is symmetric fore and aft: LCB forward is LCB aft mirrored.
    assert_near!(
        runs[0].entrance_length.unwrap()[1],
        runs[1].run_length.unwrap()[1],
        1e-6
    );
    assert_near!(
        runs[0].run_length.unwrap()[1],
        runs[1].entrance_length.unwrap()[1],
        1e-6
    );
    assert!(
        runs[0].entrance_length.unwrap()[1] < 40.0,
        "LCB forward: the PMB moves forward"
    );
}

#[test]
fn barge_volume_and_lcb_together() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let lpp = base.datums.x_fp - base.datums.x_ap;
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Volume(base.before.volume * 1.005)),
        lcb: Some(base.before.lcb - 0.001 * lpp),
        hold: PmbHold::Free,
    };
    assert_hit(
        &n,
        &transform_hydrostatic(&n, targets, &o).unwrap(),
        "∇ +0.5 %, LCB aft",
    );
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Displacement(base.before.displacement * 1.01)),
        lcb: None,
        hold: PmbHold::Free,
    };
    assert_hit(
        &n,
        &transform_hydrostatic(&n, targets, &o).unwrap(),
        "Δ + 1 %",
    );
}

#[test]
fn barge_target_out_of_range_gives_the_closest_hull_and_the_limit() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    // Cb + 0.2 asks for a box; the ends cannot squeeze that far.
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb + 0.2)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    let Stop::OutOfRange { limit } = &out.stop else {
        panic!("out of range expected, got {:?}", out.stop)
    };
    assert!(!limit.is_empty());
    // Too large for the PMB's ends alone: the ends bulged as well, from where they stopped.
    assert_eq!(out.mode, "pmb+bulge", "{limit}");
    assert!(out.bulge.as_ref().unwrap().0.iter().all(|&b| b > 0.0));
    assert!(out.evaluations < 2 * batten_core::MAX_EVALUATIONS);
    let h = recheck(&out);
    assert!(
        h.volume > base.before.volume * 1.02,
        "the closest hull went towards the target: {} → {}",
        base.before.volume,
        h.volume
    );
    assert_near!(
        h.volume,
        out.after.volume,
        1e-9 * h.volume,
        "the result is the hull reported"
    );
    assert!(out.explored.volume[1] >= h.volume);
    no_new_warnings(&n, &out.network, "closest hull");
    // Smaller than the PMB allows: stopped by the PMB's minimum length, then by the bulges'
    // largest flattening, each said.
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Volume(base.before.volume * 0.9)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    match &out.stop {
        Stop::OutOfRange { limit } => {
            assert!(limit.contains("parallel middle body"), "{limit}");
            assert!(
                limit.contains("then, bulging the ends"),
                "and the bulges' limit: {limit}"
            );
        }
        s => panic!("out of range expected, got {s:?}"),
    }
    assert!(
        out.pmb_length.unwrap()[1] < 3.0,
        "PMB squeezed to its limit: {:?}",
        out.pmb_length.unwrap()
    );
}

#[test]
fn hydrostatic_transformation_refuses_what_it_cannot_do() {
    let n = barge(2.0, 0.2);
    for bad in [
        HydroTargets {
            volume: Some(VolumeTarget::Volume(f64::NAN)),
            lcb: None,
            hold: PmbHold::Free,
        },
        HydroTargets {
            volume: Some(VolumeTarget::Cb(-0.5)),
            lcb: None,
            hold: PmbHold::Free,
        },
        HydroTargets {
            volume: None,
            lcb: Some(f64::INFINITY),
            hold: PmbHold::Free,
        },
    ] {
        assert!(
            matches!(
                transform_hydrostatic(&n, bad, &hydro_options()),
                Err(FormError::BadTarget { .. })
            ),
            "{bad:?}"
        );
    }
}

/// Stations' inflections (curves in a plane x = constant), by name.
fn station_inflections(n: &Network) -> Vec<(String, usize)> {
    n.curves()
        .iter()
        .filter(|c| {
            let p = c.curve.control_points();
            c.curve.degree() >= 2 && p.iter().all(|q| (q.x - p[0].x).abs() < 1e-9)
        })
        .map(|c| (c.name.clone(), fairness_metrics(&c.curve).inflections))
        .collect()
}

#[test]
fn frigate_without_a_pmb_is_made_finer_by_flattening_its_ends() {
    let n = frigate();
    let o = HydroTransformOptions {
        draft: 4.8,
        ..hydro_options()
    };
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb - 0.005)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    assert_eq!(out.mode, "bulge");
    assert_eq!(out.stop, Stop::Converged, "{:?}", out.stop);
    assert!(out.evaluations <= 12, "{} evaluations", out.evaluations);
    assert!(out.pmb_length.is_none());
    let (offsets, [entrance, run]) = out.bulge.clone().unwrap();
    assert!(!entrance.is_empty() && !run.is_empty());
    assert!(
        offsets[0] < 0.0 && offsets[1] < 0.0,
        "finer: both ends flattened {offsets:?}"
    );
    // Re-measured on the exact cells from the network alone.
    let h = recheck_at(&out, 4.8);
    let lpp = out.datums.x_fp - out.datums.x_ap;
    assert_eq!(out.target, ("cb", base.before.cb - 0.005));
    assert_near!(
        out.target_volume,
        base.before.volume * (1.0 - 0.005 / base.before.cb),
        1e-9 * out.target_volume,
        "Cb on the original's dimensions"
    );
    assert!(
        (h.volume / out.target_volume - 1.0).abs() <= VOLUME_TOLERANCE,
        "rebuilt {} reported {} target {} ({:?}, {} evaluations)",
        h.volume,
        out.after.volume,
        out.target_volume,
        out.stop,
        out.evaluations
    );
    assert!((h.lcb - base.before.lcb).abs() <= LCB_TOLERANCE * lpp);
    // The form curves stay where they are (re-attachment may insert knots, not move them);
    // no station gains an inflection.
    let form = form_topology(&n, &options(4.8)).unwrap();
    for (i, c) in n.curves().iter().enumerate() {
        if form.is_form_curve[i] {
            let new = &out.network.curves()[i].curve;
            let (a, b) = c.curve.domain();
            for k in 0..=50 {
                let t = a + (b - a) * k as f64 / 50.0;
                let d = c.curve.point(t).distance(new.point(t));
                assert!(d <= 1e-9, "form curve '{}' moved {d:e} at t = {t}", c.name);
            }
        }
    }
    for ((name, a), (_, b)) in station_inflections(&n)
        .iter()
        .zip(station_inflections(&out.network))
    {
        assert!(b <= *a, "station '{name}': inflections {a} → {b}");
    }
    no_new_warnings(&n, &out.network, "frigate bulged");
    // Much fuller than its stations can take: the closest hull, and the check that stopped it.
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb + 0.05)),
        lcb: None,
        hold: PmbHold::Free,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    let Stop::OutOfRange { limit } = &out.stop else {
        panic!("out of range expected, got {:?}", out.stop)
    };
    assert!(
        limit.contains("inflection") || limit.contains("bulge"),
        "{limit}"
    );
    assert!(out.after.volume >= base.before.volume * (1.0 - 1e-9));
}

#[test]
fn barge_with_its_pmb_held_bulges_its_ends_alike_fore_and_aft() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let mut offsets = Vec::new();
    for dcb in [0.005, -0.005] {
        let targets = HydroTargets {
            volume: Some(VolumeTarget::Cb(base.before.cb + dcb)),
            lcb: None,
            hold: PmbHold::Whole,
        };
        let out = transform_hydrostatic(&n, targets, &o).unwrap();
        assert_eq!((out.mode, &out.stop), ("bulge", &Stop::Converged));
        let lengths = out.pmb_length.unwrap();
        assert_near!(lengths[1], lengths[0], 1e-9, "the PMB is held");
        let (x, [entrance, run]) = out.bulge.unwrap();
        assert_eq!(
            entrance.len(),
            run.len(),
            "the barge is symmetric: {entrance:?} {run:?}"
        );
        // Alike to what the solve stops at (|δLCB| ≤ 1e-5·Lpp, about 4e-3 in the bulge
        // here), not bit for bit: one end bulged alone would be 0.4 apart.
        assert_near!(
            x[0],
            x[1],
            1e-3 * x[0].abs(),
            "LCB held on a symmetric hull: both ends alike"
        );
        offsets.push(x[0]);
    }
    assert!(
        offsets[0] > 0.0 && offsets[1] < 0.0,
        "fuller out, finer in: {offsets:?}"
    );
}

#[test]
fn barge_with_its_pmb_held_in_part_balances_the_ends() {
    let n = barge(2.0, 0.2);
    let o = hydro_options();
    let base = transform_hydrostatic(&n, HydroTargets::default(), &o).unwrap();
    let lpp = base.datums.x_fp - base.datums.x_ap;
    let position = |net: &Network| {
        let p = form_topology(net, &options(T)).unwrap().parameters;
        let pmb = p.pmb.unwrap();
        (pmb.length, pmb.position)
    };
    let (l0, x0) = position(&n);
    // Length held: the PMB shifts forward for the LCB, the ends bulge alike for the volume.
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb + 0.005)),
        lcb: Some(base.before.lcb + 0.002 * lpp),
        hold: PmbHold::Length,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    assert_eq!((out.mode, &out.stop), ("pmb_shift+bulge", &Stop::Converged));
    assert!(out.evaluations <= 12, "{} evaluations", out.evaluations);
    let (l, x) = position(&out.network);
    assert_near!(l, l0, 1e-9, "the PMB's length is held");
    assert!(x > x0, "the PMB moved forward: {x0} → {x}");
    let (b, _) = out.bulge.clone().unwrap();
    assert_near!(b[0], b[1], 1e-12, "both ends bulge alike");
    assert!(b[0] > 0.0);
    no_new_warnings(&n, &out.network, "length held");
    // Position held: the PMB lengthens for the volume, the ends bulge opposite ways for the LCB.
    let targets = HydroTargets {
        volume: Some(VolumeTarget::Cb(base.before.cb + 0.01)),
        lcb: Some(base.before.lcb + 0.001 * lpp),
        hold: PmbHold::Position,
    };
    let out = transform_hydrostatic(&n, targets, &o).unwrap();
    assert_eq!(
        (out.mode, &out.stop),
        ("pmb_length+bulge", &Stop::Converged)
    );
    assert!(out.evaluations <= 12, "{} evaluations", out.evaluations);
    let (l, x) = position(&out.network);
    assert_near!(x, x0, 1e-9, "the PMB's position is held");
    assert!(l > l0 + 5.0, "the PMB lengthened: {l0} → {l}");
    let (b, _) = out.bulge.unwrap();
    assert_near!(b[0], -b[1], 1e-12, "the ends bulge opposite ways");
    assert!(
        b[0] > 0.0,
        "LCB forward: the entrance fuller, the run finer"
    );
    no_new_warnings(&n, &out.network, "position held");
}
