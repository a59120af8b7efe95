//! Surface fairing through families of sections (seed 003, Pla et al. 1998 §4–5): the paper's
//! test — noise below the tolerance added to a hull, then faired — and the constraints.

mod common;

use batten_core::{
    curvature_variation, fair_sections, fair_sections_with, section_noise, Error, Network,
    NurbsCurve, Role, SectionFamily, SectionFilter, SurfaceFairOptions,
};
use common::{poly, wigley};
use glam::DVec3;

const TOL: f64 = 0.01;

/// The largest distance between two networks' curves at equal parameters (same domains).
fn apart(a: &Network, b: &Network) -> f64 {
    a.curves()
        .iter()
        .zip(b.curves())
        .flat_map(|(a, b)| {
            let (s, e) = a.curve.domain();
            (0..=400).map(move |i| {
                let t = s + (e - s) * i as f64 / 400.0;
                a.curve.point(t).distance(b.curve.point(t))
            })
        })
        .fold(0.0, f64::max)
}

fn options() -> SurfaceFairOptions {
    SurfaceFairOptions {
        tolerance: TOL,
        ..Default::default()
    }
}

/// Every curve still passes through every node it passed before (the network stays exact):
/// the nodes of both networks at the model tolerance, curve by curve.
fn nodes_per_curve(net: &Network) -> Vec<usize> {
    let j = net.junctions(Default::default()).expect("nodes");
    j.splits.iter().map(Vec::len).collect()
}

#[test]
fn noise_below_the_tolerance_is_faired_out_of_the_wigley_hull() {
    let clean = wigley(21, 8);
    let noisy = section_noise(&clean, 0.3 * TOL, 3, &options()).expect("noise");
    let noise = apart(&clean, &noisy);
    assert!(
        noise > 0.2 * TOL && noise < TOL,
        "noise below the tolerance: {noise}"
    );
    assert_eq!(
        nodes_per_curve(&noisy),
        nodes_per_curve(&clean),
        "noise keeps the nodes"
    );
    let faired = fair_sections(&noisy, &options()).expect("fairing");
    let r = &faired.report;
    assert!(r.moves > 50, "sections moved: {}", r.moves);
    // Within the tolerance of the (noisy) original everywhere, and nearer the clean hull.
    assert!(
        r.max_deviation <= TOL,
        "within the tolerance: {}",
        r.max_deviation
    );
    assert!(apart(&noisy, &faired.network) <= TOL, "sampled");
    let left = apart(&clean, &faired.network);
    assert!(
        left < 0.6 * noise,
        "nearer the clean hull: {left} vs noise {noise}"
    );
    assert!(
        r.after.curvature_variation < r.before.curvature_variation,
        "fairer: {:?} → {:?}",
        r.before,
        r.after
    );
    assert_eq!(
        nodes_per_curve(&faired.network),
        nodes_per_curve(&clean),
        "still exact"
    );
}

#[test]
fn fixed_curves_stay_bitwise_and_sections_stay_in_their_planes() {
    let clean = wigley(21, 8);
    let noisy = section_noise(&clean, 0.3 * TOL, 7, &options()).expect("noise");
    let opts = SurfaceFairOptions {
        fixed_curves: vec!["station +0.00".to_owned()],
        ..options()
    };
    let faired = fair_sections(&noisy, &opts).expect("fairing");
    let moved = faired.report.moves;
    assert!(moved > 0, "something moved");
    for (a, b) in noisy.curves().iter().zip(faired.network.curves()) {
        let fixed = a.role != Role::Free || a.name == "station +0.00";
        if fixed {
            assert_eq!(a.curve, b.curve, "{} is fixed: bitwise the same", a.name);
        }
        let axis = if a.name.starts_with("station") { 0 } else { 2 };
        if a.role == Role::Free {
            // Exactly but for the rounding of the knot insertion at the nodes.
            let plane = a.curve.control_points()[0][axis];
            assert!(
                b.curve
                    .control_points()
                    .iter()
                    .all(|p| (p[axis] - plane).abs() < 1e-12),
                "{} stays in its plane",
                a.name
            );
            // The curve's ends stay (on the keel, the deck, the stem and stern).
            let (s, e) = a.curve.domain();
            for t in [s, e] {
                assert_eq!(
                    a.curve.point(t),
                    b.curve.point(t),
                    "{}: its ends stay",
                    a.name
                );
            }
        }
    }
}

#[test]
fn a_clean_hull_moves_less_than_a_noisy_one_and_the_paper_filter_more() {
    let clean = wigley(21, 8);
    let own = fair_sections(&clean, &options()).expect("clean");
    let noisy = section_noise(&clean, 0.3 * TOL, 3, &options()).expect("noise");
    let faired = fair_sections(&noisy, &options()).expect("noisy");
    assert!(
        own.report.moves < faired.report.moves / 4,
        "{} vs {}",
        own.report.moves,
        faired.report.moves
    );
    // The paper's equidistant filter flattens the form by all the tolerance allows.
    let paper = SurfaceFairOptions {
        filter: SectionFilter::Equidistant,
        ..options()
    };
    let flat = fair_sections(&clean, &paper).expect("paper filter");
    assert!(
        flat.report.moves > 4 * own.report.moves.max(1),
        "{}",
        flat.report.moves
    );
    assert!(
        flat.report.max_deviation > 0.9 * TOL,
        "{}",
        flat.report.max_deviation
    );
}

#[test]
fn one_family_moves_only_its_sections_and_carries_the_nodes() {
    let clean = wigley(21, 8);
    let noisy = section_noise(&clean, 0.3 * TOL, 5, &options()).expect("noise");
    let opts = SurfaceFairOptions {
        families: vec![SectionFamily::Stations],
        ..options()
    };
    let faired = fair_sections(&noisy, &opts).expect("stations");
    let r = &faired.report;
    assert_eq!(r.sections, vec![(SectionFamily::Stations, 21)]);
    assert!(r
        .curves
        .iter()
        .all(|c| c.family != Some(SectionFamily::Waterlines)));
    // The waterlines are not faired but carry the stations' nodes along.
    let wl = r
        .curves
        .iter()
        .find(|c| c.curve == "waterline 3.1250")
        .expect("a waterline");
    assert!(wl.moves > 0 && wl.family.is_none(), "{wl:?}");
    assert_eq!(nodes_per_curve(&faired.network), nodes_per_curve(&clean));
}

#[test]
fn bad_options_are_errors_naming_them() {
    let net = wigley(7, 3);
    let e = fair_sections(
        &net,
        &SurfaceFairOptions {
            tolerance: -1.0,
            ..options()
        },
    )
    .expect_err("negative tolerance");
    assert!(
        matches!(&e, Error::InvalidInput(m) if m.contains("tolerance")),
        "{e}"
    );
    let e = fair_sections(
        &net,
        &SurfaceFairOptions {
            fixed_curves: vec!["nope".into()],
            ..options()
        },
    )
    .expect_err("unknown curve");
    assert!(e.to_string().contains("'nope'"), "{e}");
    let e = fair_sections(
        &net,
        &SurfaceFairOptions {
            families: vec![],
            ..options()
        },
    )
    .expect_err("no family");
    assert!(e.to_string().contains("families"), "{e}");
    let e = fair_sections(
        &net,
        &SurfaceFairOptions {
            tolerance: f64::NAN,
            ..options()
        },
    )
    .expect_err("NaN");
    assert!(e.to_string().contains("NaN"), "{e}");
    for bad in [-2.0, f64::NAN, f64::INFINITY] {
        let e = fair_sections(
            &net,
            &SurfaceFairOptions {
                smoothing_length: Some(bad),
                ..options()
            },
        )
        .expect_err("bad smoothing length");
        assert!(e.to_string().contains("smoothing length"), "{e}");
    }
    assert!(
        section_noise(&net, 0.0, 1, &options()).is_err(),
        "zero noise amplitude"
    );
}

#[test]
fn curvature_variation_is_zero_on_a_circle_and_matches_quadrature_on_a_cubic() {
    let circle = common::circle(3.0);
    assert!(
        curvature_variation(&circle) < 1e-18,
        "{}",
        curvature_variation(&circle)
    );
    // y = x³ on [0, 1] as a Bézier cubic: κ = 6x / (1 + 9x⁴)^{3/2}.
    let cubic: NurbsCurve = poly(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        &[
            [0., 0., 0.],
            [1. / 3., 0., 0.],
            [2. / 3., 0., 0.],
            [1., 1., 0.],
        ],
    );
    let kappa = |x: f64| 6.0 * x / (1.0 + 9.0 * x.powi(4)).powf(1.5);
    let n = 20_000;
    let mut reference = 0.0;
    for i in 0..n {
        let (a, b) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
        let x = 0.5 * (a + b);
        let ds = (1.0 + 9.0 * x.powi(4)).sqrt() * (b - a);
        let dk = (kappa(b) - kappa(a)) / ((1.0 + 9.0 * x.powi(4)).sqrt() * (b - a));
        reference += dk * dk * ds;
    }
    let got = curvature_variation(&cubic);
    assert!(
        (got - reference).abs() < 1e-4 * reference,
        "{got} vs {reference}"
    );
    let _ = DVec3::ZERO;
}

#[test]
fn the_round_callback_sees_every_round_and_stops_the_fairing() {
    let noisy = section_noise(&wigley(21, 8), 0.3 * TOL, 3, &options()).expect("noise");
    let opts = options();
    let mut seen = Vec::new();
    let whole = fair_sections_with(&noisy, &opts, &mut |done, total| {
        seen.push((done, total));
        true
    })
    .expect("fairing")
    .expect("not stopped");
    let rounds = whole.report.rounds;
    assert!(rounds >= 3, "rounds: {rounds}");
    let expected: Vec<_> = (1..=rounds).map(|k| (k, opts.max_rounds)).collect();
    assert_eq!(seen, expected, "one call per round, in order");
    let plain = fair_sections(&noisy, &opts).expect("fairing");
    assert_eq!(
        apart(&plain.network, &whole.network),
        0.0,
        "the callback changes nothing"
    );
    let mut calls = 0;
    let stopped = fair_sections_with(&noisy, &opts, &mut |_, _| {
        calls += 1;
        calls < 2
    })
    .expect("no error");
    assert!(stopped.is_none(), "stopped: no network");
    assert_eq!(calls, 2, "no round after the stop");
}

/// KCS's sections as an earlier import drew them (47 cubic sections of 7–240 control points):
/// noise of 30 % of the tolerance at every control point of every station and waterline, the
/// seed 003 test. The smoothing along the sections takes the curvature variation below the
/// clean hull's (the relaxation alone left it where the noise put it, 10⁴ times the clean
/// hull's), keeps every control point within the tolerance of the noisy input, the network
/// exact and the fixed curves bitwise, and gives back most of the inflections the noise made.
#[test]
fn noise_along_the_sections_of_kcs_is_smoothed_out_within_the_tolerance() {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/kcs_faired_apart.json");
    let clean =
        Network::from_json(&std::fs::read_to_string(path).expect("fixture")).expect("reads");
    let noisy = section_noise(&clean, 0.3 * TOL, 2, &options()).expect("noise");
    let figures = |net: &Network, smoothing: f64| {
        let opts = SurfaceFairOptions {
            max_rounds: 0,
            smoothing_length: Some(smoothing),
            ..options()
        };
        fair_sections(net, &opts).expect("figures").report
    };
    let clean_figures = figures(&clean, 0.0).before;
    let alone = fair_sections(
        &noisy,
        &SurfaceFairOptions {
            smoothing_length: Some(0.0),
            ..options()
        },
    )
    .expect("relaxation alone")
    .report;
    let faired = fair_sections(&noisy, &options()).expect("fairing");
    let r = &faired.report;
    assert!(
        (r.smoothing_length - 200.0 * TOL).abs() < 1e-12,
        "the default: 200 tolerances"
    );
    assert!(r.smoothed >= 40, "sections smoothed: {}", r.smoothed);
    let (noisy_kv, faired_kv) = (r.before.curvature_variation, r.after.curvature_variation);
    assert!(
        faired_kv < 0.01 * noisy_kv && faired_kv < clean_figures.curvature_variation,
        "∫κ′² ds: clean {}, noisy {noisy_kv}, faired {faired_kv}",
        clean_figures.curvature_variation
    );
    assert!(
        alone.after.curvature_variation > 1000.0 * clean_figures.curvature_variation,
        "the relaxation alone keeps the noise: {}",
        alone.after.curvature_variation
    );
    assert!(
        r.after.inflections < r.before.inflections
            && r.after.inflections + 20 > clean_figures.inflections,
        "inflections: clean {}, noisy {}, faired {}",
        clean_figures.inflections,
        r.before.inflections,
        r.after.inflections
    );
    assert!(
        r.max_deviation <= TOL,
        "within the tolerance: {}",
        r.max_deviation
    );
    assert!(apart(&noisy, &faired.network) <= TOL, "sampled");
    // Every node stays where both its curves pass (this import's sections were faired one by
    // one and miss some of their crossings by more than the model tolerance, so a section
    // smoothed onto its neighbour may gain a node; none loses one).
    let (before, after) = (nodes_per_curve(&noisy), nodes_per_curve(&faired.network));
    assert!(
        before.iter().zip(&after).all(|(b, a)| a >= b),
        "still exact: {before:?} → {after:?}"
    );
    for (a, b) in noisy.curves().iter().zip(faired.network.curves()) {
        if a.role != Role::Free {
            assert_eq!(a.curve, b.curve, "{} is fixed: bitwise the same", a.name);
        }
    }
}
