//! A section's flat of bottom (`FairOptions::flats`): the run of points in the base plane at an
//! end of the section becomes a straight piece exactly in the plane, and the rest of the
//! section leaves it with the flat's tangent; without the option the one smooth spline sags on
//! the flat and tilts where it ends.

use batten_core::{fair_points, FairOptions, FlatPlane, Smoothing, MIN_FLAT_RUN};
use glam::DVec3;

/// A midship-like section at x = 10: flat bottom from the keel to y = `w`, a bilge arc of
/// radius `r`, then a vertical side up to z = 8; about 5 cm between points.
fn section(w: f64, r: f64) -> Vec<DVec3> {
    let mut pts = Vec::new();
    let n = (w / 0.05).round() as usize;
    for i in 0..n {
        pts.push(DVec3::new(10.0, w * i as f64 / n as f64, 0.0));
    }
    let arc = ((r * std::f64::consts::FRAC_PI_2) / 0.05).round() as usize;
    for i in 0..arc {
        let a = std::f64::consts::FRAC_PI_2 * i as f64 / arc as f64;
        pts.push(DVec3::new(10.0, w + r * a.sin(), r * (1.0 - a.cos())));
    }
    let side = ((8.0 - r) / 0.05).round() as usize;
    for i in 0..=side {
        pts.push(DVec3::new(
            10.0,
            w + r,
            r + (8.0 - r) * i as f64 / side as f64,
        ));
    }
    pts
}

fn options(flat: Option<FlatPlane>) -> FairOptions {
    FairOptions {
        smoothing: Smoothing::MaxDeviation(0.005),
        flats: flat.into_iter().collect(),
        ..FairOptions::default()
    }
}

const BASE: FlatPlane = FlatPlane {
    normal: DVec3::Z,
    offset: 0.0,
    tolerance: 1e-3,
    noise: 1e-3,
};

/// Largest |f| over `samples + 1` evenly spaced parameters of `curve` from `from` to `to`.
fn largest(
    curve: &batten_core::NurbsCurve,
    (from, to): (f64, f64),
    samples: usize,
    f: impl Fn(DVec3) -> f64,
) -> f64 {
    (0..=samples)
        .map(|i| f(curve.point(from + (to - from) * i as f64 / samples as f64)).abs())
        .fold(0.0, f64::max)
}

/// Largest |z| of the curve from the start of its domain to `upto`, sampled finely.
fn sag(curve: &batten_core::NurbsCurve, upto: f64) -> f64 {
    largest(curve, (curve.domain().0, upto), 400, |p| p.z)
}

#[test]
fn the_flat_is_straight_in_the_plane_and_the_bilge_leaves_it_tangentially() {
    let pts = section(4.0, 2.0);
    let fit = fair_points(&pts, &options(Some(BASE))).unwrap();
    let flat = fit.report.flats.first().copied().expect("a flat run");
    // The run ends at the last point within the plane's tolerance (the arc's first, 0.6 mm up).
    let inner = pts.iter().position(|p| p.z > BASE.tolerance).unwrap() - 1;
    assert_eq!(flat.index, inner);
    assert!(pts[inner].z > 0.0, "it starts the arc");
    assert!((flat.point - DVec3::new(10.0, pts[inner].y, 0.0)).length() < 1e-9);
    assert!(
        fit.report.corners.is_empty() && fit.report.corner_parameters.is_empty(),
        "no knuckle"
    );
    let t = flat.parameter;
    let c = &fit.curve;
    assert!(sag(c, t) < 1e-12, "flat to rounding: {}", sag(c, t));
    // Both sides of the joint point along +y (the knot has multiplicity 3: one-sided
    // derivatives from the neighbouring spans).
    let before = (c.point(t) - c.point(t - 1e-6)).normalize();
    let after = (c.point(t + 1e-6) - c.point(t)).normalize();
    for d in [before, after] {
        assert!(d.angle_between(DVec3::Y) < 1e-4, "tangent {d}");
    }
    assert!(fit.report.max_deviation <= 0.005);

    // The one smooth spline, for comparison: it sags on the flat and tilts where it ends.
    let plain = fair_points(&pts, &options(None)).unwrap();
    assert!(plain.report.flats.is_empty());
    let tp = plain
        .curve
        .nearest(DVec3::new(10.0, 4.0, 0.0), 1e-12)
        .unwrap()
        .t;
    assert!(
        sag(&plain.curve, tp) > 1e-4,
        "without the flat option: {}",
        sag(&plain.curve, tp)
    );
}

#[test]
fn a_run_at_the_end_of_the_points_is_a_flat_too() {
    let mut pts = section(3.0, 1.5);
    pts.reverse();
    let fit = fair_points(&pts, &options(Some(BASE))).unwrap();
    let flat = fit
        .report
        .flats
        .first()
        .copied()
        .expect("a flat run at the end");
    let inner = pts.iter().rposition(|p| p.z > BASE.tolerance).unwrap() + 1;
    assert_eq!(flat.index, inner);
    let (_, b) = fit.curve.domain();
    let (a, _) = fit.curve.domain();
    let worst = largest(&fit.curve, (flat.parameter, b), 200, |p| p.z);
    assert!(worst < 1e-12, "{worst}");
    assert!(a < flat.parameter && flat.parameter < b);
}

#[test]
fn a_noisy_flat_runs_on_over_points_within_the_noise_and_ends_within_the_tolerance() {
    // Offsets read to the nearest 2 mm: the flat's points straddle the base plane, and the
    // second one is 2 mm below it, beyond the 1 mm tolerance.
    let mut pts = section(1.0, 2.0);
    let n = pts.iter().position(|p| p.y >= 1.0).unwrap();
    for (i, p) in pts[..n].iter_mut().enumerate() {
        p.z = [0.0, -0.002, 0.001, -0.0015][i % 4];
    }
    // The tolerance alone: the run stops at the keel point, so there is no flat.
    assert!(fair_points(&pts, &options(Some(BASE)))
        .unwrap()
        .report
        .flats
        .is_empty());
    // With 5 mm of noise the run goes over the straddling points and on up the arc while it
    // stays within 5 mm, but ends at its last point within the 1 mm tolerance: the arc's
    // first point past the flat (0.6 mm up), as without noise.
    let noisy = FlatPlane {
        noise: 0.005,
        ..BASE
    };
    let fit = fair_points(&pts, &options(Some(noisy))).unwrap();
    let flat = fit.report.flats.first().copied().expect("a flat run");
    assert_eq!(flat.index, n + 1, "{:?}", pts[flat.index]);
    assert!(pts[n + 2].z > BASE.tolerance && pts[n + 2].z < noisy.noise);
    assert!(sag(&fit.curve, flat.parameter) < 1e-12);
    assert!(fit.report.max_deviation <= 0.005);
}

#[test]
fn no_flat_where_the_run_is_short_or_the_whole_curve() {
    // Shorter than MIN_FLAT_RUN.
    let short = section(0.5 * MIN_FLAT_RUN, 2.0);
    assert!(fair_points(&short, &options(Some(BASE)))
        .unwrap()
        .report
        .flats
        .is_empty());
    // Wholly in the plane: a straight waterline at the base.
    let line: Vec<DVec3> = (0..50).map(|i| DVec3::new(i as f64, 2.0, 0.0)).collect();
    let fit = fair_points(&line, &options(Some(BASE))).unwrap();
    assert!(fit.report.flats.is_empty());
    // A polyline fit (degree 1) has no tangent to carry off a flat.
    let linear = FairOptions {
        degree: 1,
        ..options(Some(BASE))
    };
    assert!(fair_points(&section(4.0, 2.0), &linear)
        .unwrap()
        .report
        .flats
        .is_empty());
}

#[test]
fn a_bad_flat_plane_is_an_error() {
    let pts = section(4.0, 2.0);
    for (normal, offset, tolerance) in [
        (DVec3::ZERO, 0.0, 1e-3),
        (DVec3::new(f64::NAN, 0.0, 1.0), 0.0, 1e-3),
        (DVec3::Z, f64::INFINITY, 1e-3),
        (DVec3::Z, 0.0, 0.0),
        (DVec3::Z, 0.0, f64::NAN),
    ] {
        let plane = FlatPlane {
            normal,
            offset,
            tolerance,
            noise: tolerance,
        };
        let err = fair_points(&pts, &options(Some(plane))).unwrap_err();
        assert!(
            matches!(err, batten_core::FairError::FlatPlane { .. }),
            "{err}"
        );
    }
    // A normal of any length is the same plane.
    let scaled = FlatPlane {
        normal: DVec3::Z * 4.0,
        offset: 0.0,
        tolerance: 1e-3,
        noise: 1e-3,
    };
    assert!(
        fair_points(&pts, &options(Some(scaled)))
            .unwrap()
            .report
            .flats
            .len()
            == 1
    );
}

/// Half-breadth 6 m through a parallel middle body (x 20..40), a parabola off it to 1 m at the
/// ends, at height `z`; points every 0.5 m.
fn waterline(z: f64) -> Vec<DVec3> {
    (0..=120)
        .map(|i| {
            let x = 0.5 * i as f64;
            let off = ((x - 30.0).abs() - 10.0).max(0.0);
            DVec3::new(x, 6.0 - 0.0125 * off * off, z)
        })
        .collect()
}

const SIDE: FlatPlane = FlatPlane {
    normal: DVec3::Y,
    offset: 6.0,
    tolerance: 1e-3,
    noise: 1e-3,
};

#[test]
fn a_run_between_the_ends_is_straight_and_left_tangentially_at_both_its_ends() {
    let pts = waterline(5.0);
    let fit = fair_points(&pts, &options(Some(SIDE))).unwrap();
    let ends = &fit.report.flats;
    // The points within 1 mm of the side: x 20..40 (19.5 and 40.5 are 3.1 mm off).
    assert_eq!(ends.iter().map(|f| f.index).collect::<Vec<_>>(), [40, 80]);
    assert!(ends.iter().all(|f| f.plane == 0));
    assert!(fit.report.corners.is_empty());
    let c = &fit.curve;
    let (a, b) = (ends[0].parameter, ends[1].parameter);
    let off = largest(c, (a, b), 400, |p| p.y - 6.0);
    assert!(off < 1e-12, "straight in the plane: {off}");
    for t in [a, b] {
        for d in [
            (c.point(t) - c.point(t - 1e-6)).normalize(),
            (c.point(t + 1e-6) - c.point(t)).normalize(),
        ] {
            assert!(d.angle_between(DVec3::X) < 1e-4, "tangent {d} at {t}");
        }
    }
    assert!(fit.report.max_deviation <= 0.005);
    // Fitted as one spline, the flat sags off the side by 2.5 mm.
    let plain = fair_points(&pts, &options(None)).unwrap().curve;
    let (lo, hi) = plain.domain();
    let sag = (0..=2000)
        .map(|i| plain.point(lo + (hi - lo) * i as f64 / 2000.0))
        .filter(|p| p.x > 20.5 && p.x < 39.5)
        .map(|p| (p.y - 6.0).abs())
        .fold(0.0, f64::max);
    assert!(sag > 1e-3, "{sag}");
}

#[test]
fn a_station_runs_flat_on_the_bottom_and_up_the_side() {
    // section(): flat bottom to y = 4, bilge radius 2, side at y = 6 up to z = 8.
    let pts = section(4.0, 2.0);
    let options = FairOptions {
        flats: vec![BASE, SIDE],
        ..options(None)
    };
    let fit = fair_points(&pts, &options).unwrap();
    let ends = &fit.report.flats;
    assert_eq!(
        ends.iter().map(|f| f.plane).collect::<Vec<_>>(),
        [0, 1],
        "{ends:?}"
    );
    let c = &fit.curve;
    let (lo, hi) = c.domain();
    let (a, b) = (ends[0].parameter, ends[1].parameter);
    assert!(
        largest(c, (lo, a), 200, |p| p.z) < 1e-12,
        "the bottom is flat"
    );
    assert!(
        largest(c, (b, hi), 200, |p| p.y - 6.0) < 1e-12,
        "the side is flat"
    );
    // The side's run starts at the arc's first point within 1 mm of y = 6: past 88.2°
    // (z = 2 (1 − cos a) > 1.937 m).
    assert!(
        ends[1].point.z > 1.937 && ends[1].point.z <= 2.0,
        "{}",
        ends[1].point
    );
    assert!(fit.report.corners.is_empty());
}

#[test]
fn a_crossing_is_no_run_and_two_runs_in_a_plane_are_both_kept() {
    // Crossing the side plane: two points within 1 mm (a crossing, 0.35 m apart).
    let cross: Vec<DVec3> = (0..60)
        .map(|i| {
            let z = 0.35 * i as f64;
            DVec3::new(0.0, 6.0 + 0.004 * (z - 10.675), z)
        })
        .collect();
    let close = cross.iter().filter(|p| (p.y - 6.0).abs() <= 1e-3).count();
    assert_eq!(close, 2);
    assert!(fair_points(&cross, &options(Some(SIDE)))
        .unwrap()
        .report
        .flats
        .is_empty());
    // Two flats in one plane with a 2 cm bulge between them: both straight, and the piece
    // between follows the bulge within the tolerance.
    let mut two = waterline(5.0);
    for p in two.iter_mut().filter(|p| p.x > 24.0 && p.x < 27.0) {
        p.y += 0.02 * ((p.x - 24.0) * std::f64::consts::PI / 3.0).sin();
    }
    let fit = fair_points(&two, &options(Some(SIDE))).unwrap();
    let ends: Vec<(f64, f64)> = fit
        .report
        .flats
        .iter()
        .map(|f| (f.point.x, f.parameter))
        .collect();
    assert_eq!(
        ends.iter().map(|e| e.0).collect::<Vec<_>>(),
        [20.0, 24.0, 27.0, 40.0]
    );
    for pair in [(ends[0].1, ends[1].1), (ends[2].1, ends[3].1)] {
        let off = largest(&fit.curve, pair, 100, |p| p.y - 6.0);
        assert!(off < 1e-12, "{off}");
    }
    assert!(fit.report.max_deviation <= 0.005);
}

#[test]
fn a_chine_where_the_flat_of_side_starts_stays_a_knuckle() {
    // A hard-chine station: a deadrise bottom from the keel to the chine at (5, 1), then the
    // side straight up at y = 5; points every 5 cm.
    let mut pts: Vec<DVec3> = (0..100)
        .map(|i| DVec3::new(0.0, 0.05 * i as f64, 0.01 * i as f64))
        .collect();
    let chine = pts.len();
    pts.extend((0..=100).map(|i| DVec3::new(0.0, 5.0, 1.0 + 0.05 * i as f64)));
    let side = FlatPlane {
        offset: 5.0,
        ..SIDE
    };
    let fit = fair_points(&pts, &options(Some(side))).unwrap();
    assert_eq!(fit.report.corners, [chine]);
    assert!(fit.report.flats.is_empty(), "{:?}", fit.report.flats);
    let c = &fit.curve;
    let t = fit.report.corner_parameters[0];
    let (_, hi) = c.domain();
    let off = largest(c, (t, hi), 200, |p| p.y - 5.0);
    assert!(off < 1e-12, "the side is flat: {off}");
    let before = (c.point(t) - c.point(t - 1e-6)).normalize();
    let after = (c.point(t + 1e-6) - c.point(t)).normalize();
    let deadrise = DVec3::new(0.0, 5.0, 1.0).normalize();
    assert!(before.angle_between(deadrise) < 1e-3, "{before}");
    assert!(after.angle_between(DVec3::Z) < 1e-4, "{after}");
}

/// A deck edge along the side y = 6, KVLCC2-like: off the side up to x = 20 (closing on it
/// with y = 6 − 0.0125·(20 − x)²), on it from there, rising with the sheer by 1 m to x = 60
/// (z = 26 − (60 − x)²/1600, level at x = 60), then straight at z = 26 to x = 110, and off
/// it again.
fn sheer_deck_edge() -> Vec<DVec3> {
    (0..=130)
        .map(|i| {
            let x = i as f64;
            let off = (20.0 - x).max(0.0) + (x - 110.0).max(0.0);
            let below = 60.0 - x.clamp(20.0, 60.0);
            DVec3::new(x, 6.0 - 0.0125 * off * off, 26.0 - below * below / 1600.0)
        })
        .collect()
}

#[test]
fn a_stretch_on_the_side_that_curves_in_it_stays_on_it_and_keeps_its_straight_end_straight() {
    let pts = sheer_deck_edge();
    let fit = fair_points(&pts, &options(Some(SIDE))).unwrap();
    // The whole stretch on the side (x 20..110) is no straight run: its straight end is, from
    // where the sheer stops rising (within the noise: x = 59) to x = 110, and the rest of it a
    // run that curves in the plane. The curve leaves the flat at x = 20 and 110 only.
    let ends = &fit.report.flats;
    assert_eq!(ends.iter().map(|f| f.index).collect::<Vec<_>>(), [20, 110]);
    assert!(fit.report.corners.is_empty(), "{:?}", fit.report.corners);
    let c = &fit.curve;
    let (a, b) = (ends[0].parameter, ends[1].parameter);
    assert!(largest(c, (a, b), 4000, |p| p.y - 6.0) < 1e-12);
    // Straight from x = 59, the sheer followed before it, and smooth where the two meet.
    // The curve runs along x here: its parameter at x = 59 by bisection.
    let (mut lo, mut hi) = (a, b);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if c.point(mid).x < pts[59].x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let join = lo;
    assert!(largest(c, (join, b), 400, |p| p.z - 26.0) < 1e-3);
    let sheer = |p: DVec3| 26.0 - (60.0 - p.x.clamp(20.0, 60.0)).powi(2) / 1600.0;
    assert!(largest(c, (a, join), 400, |p| p.z - sheer(p)) <= 0.005);
    let turn = |t: f64| {
        let (before, after) = (c.derivs(t - 1e-7).d1, c.derivs(t + 1e-7).d1);
        before.angle_between(after).to_degrees()
    };
    for t in [a, join, b] {
        assert!(turn(t) < 1e-3, "turns {}° at {t}", turn(t));
    }
    assert!(fit.report.max_deviation <= 0.005);
    // Before, fitted smooth from x = 20 to the straight end, it bowed off the side.
    let plain = fair_points(&pts, &options(None)).unwrap().curve;
    let (lo, hi) = plain.domain();
    let bow = (0..=4000)
        .map(|i| plain.point(lo + (hi - lo) * i as f64 / 4000.0))
        .filter(|p| p.x > 21.0 && p.x < 109.0)
        .map(|p| (p.y - 6.0).abs())
        .fold(0.0, f64::max);
    assert!(bow > 1e-4, "{bow}");
}

#[test]
fn a_quarter_circle_in_the_base_plane_stays_in_it() {
    // In the plane but curved: a quarter circle in z = 0, then up at a knuckle.
    let mut curved: Vec<DVec3> = (0..=40)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 * i as f64 / 40.0;
            DVec3::new(3.0 * a.sin(), 3.0 * (1.0 - a.cos()), 0.0)
        })
        .collect();
    curved.extend((1..40).map(|i| DVec3::new(3.0, 3.0, 0.1 * i as f64)));
    let fit = fair_points(&curved, &options(Some(BASE))).unwrap();
    assert_eq!(fit.report.corners, [40]);
    let knuckle = fit.report.corner_parameters[0];
    let c = &fit.curve;
    assert!(largest(c, (c.domain().0, knuckle), 4000, |p| p.z) < 1e-12);
    assert!(
        largest(c, (c.domain().0, knuckle), 400, |p| p.x.hypot(p.y - 3.0)
            - 3.0)
            <= 0.005
    );
}
