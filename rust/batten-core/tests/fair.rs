//! Curve fairing (Dierckx smoothing spline): known curves with noise, real hull sections, bad
//! input. Figures are printed with `cargo test --test fair -- --nocapture`.
mod common;

use batten_core::{
    corner_indices, fair_points, fairness_metrics, FairError, FairOptions, KnotLayout, NurbsCurve,
    Smoothing, Tolerance,
};
use glam::DVec3;
use proptest::prelude::*;

/// SplitMix64 with Box–Muller: a tiny deterministic Gaussian source.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn gauss(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// Quarter circle of radius `r` in the xy plane (exact rational quadratic).
fn arc(r: f64) -> NurbsCurve {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let pts = vec![
        DVec3::new(r, 0., 0.),
        DVec3::new(r, r, 0.),
        DVec3::new(0., r, 0.),
    ];
    NurbsCurve::try_new(2, vec![0., 0., 0., 1., 1., 1.], pts, Some(vec![1., w, 1.])).unwrap()
}

/// Wigley section y = B/2·(1 − ((T − z)/T)²) in the station plane x = x0, keel to waterline:
/// exactly the quadratic Bézier (x0, 0, 0), (x0, B/2, T/2), (x0, B/2, T).
fn wigley(b: f64, t: f64, x0: f64) -> NurbsCurve {
    let pts = vec![
        DVec3::new(x0, 0., 0.),
        DVec3::new(x0, b / 2., t / 2.),
        DVec3::new(x0, b / 2., t),
    ];
    NurbsCurve::try_new(2, vec![0., 0., 0., 1., 1., 1.], pts, None).unwrap()
}

/// A planar cubic B-spline S-bend with one inflection and curved ends.
fn sbend() -> NurbsCurve {
    let pts = [
        (0., 0.),
        (1.5, 3.),
        (4.5, 4.),
        (7., 0.),
        (9.5, -4.),
        (12.5, -3.),
        (14., 0.),
    ]
    .map(|(x, y)| DVec3::new(x, y, 0.0));
    NurbsCurve::from_layout(&pts, None, 4, KnotLayout::Endpoint, false).unwrap()
}

/// `m` points of `truth`, uniform in its parameter, with Gaussian noise σ in the plane with
/// normal `normal` on the interior points (the end points lie on the neighbouring curves of a
/// network and are exact; the fit interpolates them).
fn sample(truth: &NurbsCurve, m: usize, sigma: f64, normal: DVec3, seed: u64) -> Vec<DVec3> {
    let (a, b) = truth.domain();
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    let mut rng = Rng(seed);
    (0..m)
        .map(|i| {
            let t = a + (b - a) * i as f64 / (m - 1) as f64;
            let e = (u * rng.gauss() + w * rng.gauss()) * sigma;
            truth.point(t) + if i == 0 || i == m - 1 { DVec3::ZERO } else { e }
        })
        .collect()
}

/// Largest distance from 2001 samples of `fit` to the true curve (global closest points).
fn distance_to_truth(fit: &NurbsCurve, truth: &NurbsCurve) -> f64 {
    let bez = truth.bezier_decomposition();
    let (a, b) = fit.domain();
    (0..=2000)
        .map(|i| {
            let p = fit.point(a + (b - a) * i as f64 / 2000.0);
            bez.nearest(p, 1e-10).unwrap().distance
        })
        .fold(0.0, f64::max)
}

fn options(smoothing: Smoothing) -> FairOptions {
    FairOptions {
        smoothing,
        corner_angle: None,
        ..FairOptions::default()
    }
}

const SEEDS: std::ops::RangeInclusive<u64> = 1..=8;
const M: usize = 200;

fn cases() -> [(&'static str, NurbsCurve, DVec3, f64); 3] {
    [
        ("arc R10", arc(10.0), DVec3::Z, 0.02),
        ("wigley B16 T6", wigley(16.0, 6.0, 25.0), DVec3::X, 0.01),
        ("s-bend", sbend(), DVec3::Z, 0.02),
    ]
}

#[test]
fn noisy_fits_stay_within_three_sigma_of_the_true_curve() {
    for (name, truth, normal, sigma) in cases() {
        for seed in SEEDS {
            let noisy = sample(&truth, M, sigma, normal, seed);
            let fit = fair_points(&noisy, &options(Smoothing::Noise(sigma))).unwrap();
            let d = distance_to_truth(&fit.curve, &truth);
            println!(
                "{name} seed {seed}: {} control points, {:.3}σ from truth, max dev {:.4} m, \
                 rms {:.4} m, p {:.1}",
                fit.report.control_points,
                d / sigma,
                fit.report.max_deviation,
                fit.report.rms_deviation,
                fit.report.pieces[0].p
            );
            assert!(
                d <= 3.0 * sigma,
                "{name} seed {seed}: {d} > 3σ = {}",
                3.0 * sigma
            );
            // RMS distance of the points from the fit is the noise level (S = Mσ²): within
            // 20% (the sample RMS of 200 normal deviates scatters by about 5%).
            let rms = fit.report.rms_deviation;
            assert!(
                (rms - sigma).abs() <= 0.2 * sigma,
                "{name} seed {seed}: rms {rms} vs σ {sigma}"
            );
        }
    }
}

#[test]
fn noisy_arc_and_wigley_fits_add_no_inflection() {
    for (name, truth, normal, sigma) in cases().into_iter().take(2) {
        let truth_inflections = fairness_metrics(&truth).inflections;
        assert_eq!(truth_inflections, 0, "{name}: a convex truth");
        for seed in SEEDS {
            let noisy = sample(&truth, M, sigma, normal, seed);
            let fit = fair_points(&noisy, &options(Smoothing::Noise(sigma))).unwrap();
            let got = fit.report.metrics.inflections;
            assert!(
                got <= truth_inflections,
                "{name} seed {seed}: {got} inflections, truth {truth_inflections}"
            );
        }
    }
}

/// The S-bend's true end curvature (0.066 /m, an eighth of its largest) is within the scatter
/// of a free end span's curvature at this noise, so without lobe flattening 3 of these 8
/// seeds bent the wrong way in the last percent of the curve.
#[test]
fn noisy_s_bend_fit_adds_no_inflection() {
    let (_, truth, normal, sigma) = cases().into_iter().nth(2).unwrap();
    let truth_inflections = fairness_metrics(&truth).inflections;
    assert_eq!(truth_inflections, 1, "one inflection in the truth");
    for seed in SEEDS {
        let noisy = sample(&truth, M, sigma, normal, seed);
        let fit = fair_points(&noisy, &options(Smoothing::Noise(sigma))).unwrap();
        let got = fit.report.metrics.inflections;
        assert!(got <= truth_inflections, "seed {seed}: {got} inflections");
    }
}

/// Over 40 seeds the S-bend fits bend the wrong way in at most one: a wiggle about the true
/// inflection or a hook at an end, flattened where the data allow it (before lobe flattening
/// 9 of these 40 had extra inflections; the one left, seed 13, is a knot cluster on a noise
/// cluster that the data then do support).
#[test]
fn noisy_s_bend_extra_inflections_are_rare() {
    let (_, truth, normal, sigma) = cases().into_iter().nth(2).unwrap();
    let extra: Vec<u64> = (1..=40)
        .filter(|&seed| {
            let noisy = sample(&truth, M, sigma, normal, seed);
            let fit = fair_points(&noisy, &options(Smoothing::Noise(sigma))).unwrap();
            fit.report.metrics.inflections > 1
        })
        .collect();
    println!("seeds with extra inflections: {extra:?}");
    assert!(extra.len() <= 1, "seeds {extra:?}");
}

/// An inflection the data demand is kept: the S-bend from just before its inflection (7 % of
/// the length in, end curvature a tenth of the largest), so the true sign change lies in the
/// first knot span of the fit, an end lobe flattening tries; at σ = 2 mm the data reject
/// zero end curvature. (At σ = 5 mm they do not, and the fit may lose it: 4 of these seeds.)
#[test]
fn an_inflection_next_to_an_end_is_kept() {
    let full = sbend();
    let (a, b) = full.domain();
    let t0 = a + 0.46 * (b - a);
    let truth_pts: Vec<DVec3> = (0..=400)
        .map(|i| full.point(t0 + (b - t0) * f64::from(i) / 400.0))
        .collect();
    let truth = fair_points(&truth_pts, &options(Smoothing::MaxDeviation(1e-6)))
        .unwrap()
        .curve;
    assert_eq!(
        fairness_metrics(&truth).inflections,
        1,
        "the truth bends once"
    );
    for seed in SEEDS {
        let sigma = 0.002;
        let noisy = sample(&truth, M, sigma, DVec3::Z, seed);
        let fit = fair_points(&noisy, &options(Smoothing::Noise(sigma))).unwrap();
        let kn = &fit.report.knots;
        let first = kn.iter().copied().find(|&t| t > 0.0).unwrap();
        let (fa, fb) = fit.curve.domain();
        println!(
            "seed {seed}: {} inflections, first knot at {:.3} of the curve",
            fit.report.metrics.inflections,
            (first - fa) / (fb - fa)
        );
        assert_eq!(fit.report.metrics.inflections, 1, "seed {seed}");
        assert!(
            distance_to_truth(&fit.curve, &truth) <= 3.0 * sigma,
            "seed {seed}"
        );
    }
}

#[test]
fn noisy_fits_use_no_more_knots_than_the_noise_free_data_needs() {
    for (name, truth, normal, sigma) in cases() {
        // What the truth needs: the noise-free samples fitted to a quarter of the noise level.
        let clean = sample(&truth, M, 0.0, normal, 0);
        let needed = fair_points(&clean, &options(Smoothing::MaxDeviation(sigma / 4.0)))
            .unwrap()
            .report
            .control_points;
        let mut counts: Vec<usize> = SEEDS
            .map(|seed| {
                let noisy = sample(&truth, M, sigma, normal, seed);
                fair_points(&noisy, &options(Smoothing::Noise(sigma)))
                    .unwrap()
                    .report
                    .control_points
            })
            .collect();
        println!("{name}: noise-free needs {needed} control points; noisy fits {counts:?}");
        counts.sort_unstable();
        let median = counts[counts.len() / 2];
        assert!(
            median <= needed,
            "{name}: median {median} control points, noise-free data needs {needed}"
        );
        assert!(
            counts[counts.len() - 1] <= 2 * needed,
            "{name}: worst seed {} control points, noise-free {needed}",
            counts[counts.len() - 1]
        );
    }
}

#[test]
fn tolerance_mode_meets_the_tolerance_and_tighter_needs_more_knots() {
    let truth = sbend();
    let clean = sample(&truth, 120, 0.0, DVec3::Z, 0);
    let mut last = 0;
    for tol in [1e-2, 1e-3, 1e-4] {
        let fit = fair_points(&clean, &options(Smoothing::MaxDeviation(tol))).unwrap();
        let r = &fit.report;
        // Independent check of the reported deviation by global closest points.
        let bez = fit.curve.bezier_decomposition();
        let worst = clean
            .iter()
            .map(|q| bez.nearest(*q, 1e-12).unwrap().distance)
            .fold(0.0, f64::max);
        println!(
            "s-bend tol {tol:e}: {} control points, max dev {:.3e}",
            r.control_points, worst
        );
        assert!(worst <= tol, "tol {tol}: deviation {worst}");
        assert!((worst - r.max_deviation).abs() < 1e-9, "reported deviation");
        assert!(
            r.control_points >= last,
            "tighter tolerance, no fewer knots"
        );
        last = r.control_points;
        assert_eq!(
            fit.curve.point(fit.curve.domain().0),
            clean[0],
            "start kept"
        );
        assert_eq!(
            fit.curve.point(fit.curve.domain().1),
            clean[119],
            "end kept"
        );
    }
}

#[test]
fn a_chine_stays_sharp_and_is_found_by_corner_parameters() {
    // A hard-chine section: bottom deadrise line, chine at index 20, curved topside.
    let mut pts: Vec<DVec3> = (0..=20)
        .map(|i| {
            let s = f64::from(i) / 20.0;
            DVec3::new(10.0, 3.0 * s, 0.6 * s)
        })
        .collect();
    pts.extend((1..=30).map(|i| {
        let s = f64::from(i) / 30.0;
        DVec3::new(10.0, 3.0 + 0.8 * s - 0.5 * s * s, 0.6 + 4.0 * s)
    }));
    assert_eq!(
        corner_indices(&pts, 30f64.to_radians(), 1e-4),
        vec![20],
        "detected"
    );
    for opts in [
        FairOptions {
            corners: vec![20],
            corner_angle: None,
            smoothing: Smoothing::MaxDeviation(1e-4),
            ..FairOptions::default()
        },
        FairOptions {
            smoothing: Smoothing::MaxDeviation(1e-4),
            ..FairOptions::default()
        },
    ] {
        let fit = fair_points(&pts, &opts).unwrap();
        let r = &fit.report;
        assert_eq!(r.corners, vec![20], "corner kept");
        assert_eq!(r.pieces.len(), 2, "two pieces");
        let t = r.corner_parameters[0];
        let found = fit.curve.corner_parameters(10f64.to_radians());
        assert_eq!(found, vec![t], "the knuckle is a knot of multiplicity 3");
        assert!(
            (fit.curve.point(t) - pts[20]).length() < 1e-12,
            "through it"
        );
        // The bottom is straight: the first piece is a line (its points are collinear).
        let mid = fit.curve.point(0.5 * t);
        let dist_to_line = (mid - pts[0])
            .cross((pts[20] - pts[0]).normalize())
            .length();
        assert!(dist_to_line < 1e-9, "bottom straight: {dist_to_line}");
        assert!(r.max_deviation <= 1e-4, "within tolerance");
        assert_eq!(r.metrics.inflections, 0, "no inflection in a chine section");
    }
}

/// `m` points along a 2 m quarter arc (radius 4/π) in the xy plane with Gaussian noise of
/// `sigma` in the radius (the end points exact).
fn noisy_quarter_arc(m: usize, sigma: f64, seed: u64) -> Vec<DVec3> {
    let mut rng = Rng(seed);
    let radius = 2.0 / std::f64::consts::FRAC_PI_2;
    (0..m)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 * i as f64 / (m - 1) as f64;
            let noise = if i == 0 || i + 1 == m {
                0.0
            } else {
                sigma * rng.gauss()
            };
            DVec3::new(a.cos(), a.sin(), 0.0) * (radius + noise)
        })
        .collect()
}

#[test]
fn noise_does_not_make_corners() {
    // Issue 21: 1 mm noise on a 2 m arc at the default 45° corner angle and 5 mm tolerance gave
    // 212 corners at 500 points and ~8,852 at 10,000 (the turn between neighbours is noise).
    for m in [500, 10_000, 30_000] {
        let pts = noisy_quarter_arc(m, 1e-3, 21);
        let o = FairOptions {
            smoothing: Smoothing::MaxDeviation(5e-3),
            ..FairOptions::default()
        };
        let fit = fair_points(&pts, &o).unwrap();
        let r = &fit.report;
        assert_eq!(r.corners, Vec::<usize>::new(), "{m} points: no corner");
        assert!(
            r.control_points <= 12,
            "{m} points: {} control points",
            r.control_points
        );
        assert!(r.max_deviation <= 5e-3, "{m} points: within tolerance");
    }
}

#[test]
fn a_noisy_knuckle_is_one_corner() {
    // An L-shaped section (two 1 m legs meeting at 90° at index 2000), 0.25 mm spacing, 1 mm
    // noise across the legs: exactly one corner, at a point within two tolerances of the
    // knuckle (noise moves the apex along the legs); the fit keeps it sharp and stays within
    // the tolerance.
    let mut rng = Rng(5);
    let n = 4000;
    let knuckle = n / 2;
    let pts: Vec<DVec3> = (0..=n)
        .map(|i| {
            let s = i as f64 / knuckle as f64;
            let noise = if i == 0 || i == n || i == knuckle {
                0.0
            } else {
                1e-3 * rng.gauss()
            };
            if i <= knuckle {
                DVec3::new(s, noise, 0.0)
            } else {
                DVec3::new(1.0 + noise, s - 1.0, 0.0)
            }
        })
        .collect();
    let o = FairOptions {
        smoothing: Smoothing::MaxDeviation(5e-3),
        ..FairOptions::default()
    };
    let fit = fair_points(&pts, &o).unwrap();
    let r = &fit.report;
    assert_eq!(r.corners.len(), 1, "one corner: {:?}", r.corners);
    let at = pts[r.corners[0]];
    assert!(
        (at - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-2,
        "at the knuckle: {at}"
    );
    assert_eq!(
        fit.curve.corner_parameters(10f64.to_radians()),
        r.corner_parameters,
        "sharp"
    );
    assert!(r.max_deviation <= 5e-3, "within tolerance");
    assert!(r.control_points < 40, "{} control points", r.control_points);
}

/// 4,001 points evenly spread in parameter along `fit`, ends included.
fn samples(fit: &NurbsCurve) -> Vec<DVec3> {
    let (a, b) = fit.domain();
    (0..=4000)
        .map(|i| fit.point(a + (b - a) * f64::from(i) / 4000.0))
        .collect()
}

/// The fit of a noisy midship section's points `pts` (`distance` from the true section),
/// checked within 3 `sigma` of the truth with at most 30 control points, its figures printed
/// under `label`.
fn midship_fit(
    pts: &[DVec3],
    distance: impl Fn(DVec3) -> f64,
    o: &FairOptions,
    sigma: f64,
    label: &str,
) -> batten_core::FairedCurve {
    let fit = fair_points(pts, o).unwrap();
    let r = &fit.report;
    let off = samples(&fit.curve)
        .iter()
        .map(|&p| distance(p))
        .fold(0.0, f64::max);
    println!(
        "{label}: {} control points, {:.2} mm from the truth, {} inflections",
        r.control_points,
        off * 1e3,
        r.metrics.inflections
    );
    assert!(off <= 3.0 * sigma, "{label}: {off} m from the section");
    assert!(r.control_points <= 30, "{label}: {}", r.control_points);
    fit
}

/// `m` points along a midship-like section in the plane x = 0 (flat bottom 0.6 m, bilge
/// radius 0.4 m, flat side 0.6 m) with Gaussian noise of `sigma` along the normal (the end
/// points exact), and the distance of a point from that section.
fn noisy_midship(m: usize, sigma: f64, seed: u64) -> (Vec<DVec3>, impl Fn(DVec3) -> f64) {
    noisy_midship_of(1.0, 0.4, m, sigma, seed)
}

/// [`noisy_midship`] of half breadth `half` and bilge radius `r` (flat bottom and flat side
/// each `half − r` long).
fn noisy_midship_of(
    half: f64,
    r: f64,
    m: usize,
    sigma: f64,
    seed: u64,
) -> (Vec<DVec3>, impl Fn(DVec3) -> f64) {
    let flat = half - r;
    let quarter = std::f64::consts::FRAC_PI_2 * r;
    let at = move |s: f64| -> (DVec3, DVec3) {
        if s <= flat {
            (DVec3::new(0.0, s, 0.0), DVec3::NEG_Z)
        } else if s <= flat + quarter {
            let a = (s - flat) / r;
            let n = DVec3::new(0.0, a.sin(), -a.cos());
            (DVec3::new(0.0, flat, r) + n * r, n)
        } else {
            (DVec3::new(0.0, half, r + s - flat - quarter), DVec3::Y)
        }
    };
    let length = 2.0 * flat + quarter;
    let mut rng = Rng(seed);
    let pts = (0..m)
        .map(|i| {
            let (p, n) = at(length * i as f64 / (m - 1) as f64);
            let e = if i == 0 || i + 1 == m {
                0.0
            } else {
                sigma * rng.gauss()
            };
            p + n * e
        })
        .collect();
    // Near the section (within millimetres), the piece a point is closest to is the one whose
    // strip it lies in: the bottom left of the bilge, the side above it, the arc between.
    let distance = move |p: DVec3| -> f64 {
        let (y, z) = (p.y, p.z);
        if y <= flat {
            z.hypot(y.min(0.0))
        } else if z <= r {
            ((y - flat).hypot(z - r) - r).abs()
        } else {
            (y - half).hypot((z - r - flat).max(0.0))
        }
    };
    (pts, distance)
}

#[test]
fn noise_mode_on_a_dense_scan_fits_the_curve_not_the_noise() {
    // Issue 21: 10,000 points with 1 mm noise (0.2 mm apart) gave 7-141 control points and up
    // to 80 inflections on a convex arc, 30,000 points 214-546 and a curve metres off; the
    // noise's sum of squares was fitted with knots. Now: the curve within 3σ of the truth
    // with few control points, and the arc without inflections.
    let sigma = 1e-3;
    let o = options(Smoothing::Noise(sigma));
    let radius = 2.0 / std::f64::consts::FRAC_PI_2;
    for seed in [21, 1] {
        let fit = fair_points(&noisy_quarter_arc(10_000, sigma, seed), &o).unwrap();
        let r = &fit.report;
        let off = samples(&fit.curve)
            .iter()
            .map(|p| (p.length() - radius).abs())
            .fold(0.0, f64::max);
        println!(
            "arc seed {seed}: {} control points, {:.3} mm from the truth, {} inflections",
            r.control_points,
            off * 1e3,
            r.metrics.inflections
        );
        assert!(off <= 3.0 * sigma, "arc seed {seed}: {off} m from the arc");
        assert!(
            r.control_points <= 12,
            "arc seed {seed}: {}",
            r.control_points
        );
        assert_eq!(r.metrics.inflections, 0, "arc seed {seed}: convex");
        assert_eq!(r.corners, Vec::<usize>::new(), "arc seed {seed}: no corner");
    }
    for seed in [21, 1] {
        let (pts, distance) = noisy_midship(10_000, sigma, seed);
        let fit = midship_fit(&pts, distance, &o, sigma, &format!("midship seed {seed}"));
        let r = &fit.report;
        assert_eq!(
            r.corners,
            Vec::<usize>::new(),
            "midship seed {seed}: no corner"
        );
    }
}

#[test]
fn noise_denser_than_its_size_is_not_disorder() {
    // Issue 21: 30,000 and 100,000 points with 1 mm noise (0.07 and 0.02 mm apart) were
    // refused as out of order (at 100,000 the polyline 113 m long, a nearest-neighbour tour
    // 31 m); at the tolerance's scale they follow the arc. Shuffled points are still refused.
    let pts = noisy_quarter_arc(30_000, 1e-3, 3);
    let o = FairOptions {
        smoothing: Smoothing::MaxDeviation(5e-3),
        ..FairOptions::default()
    };
    let fit = fair_points(&pts, &o).unwrap();
    assert!(fit.report.max_deviation <= 5e-3, "within tolerance");
    assert_eq!(fit.report.corners, Vec::<usize>::new(), "no corner");
    let mut rng = Rng(8);
    let mut shuffled = pts[..2000].to_vec();
    for i in (1..shuffled.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        shuffled.swap(i, j);
    }
    let err = fair_points(&shuffled, &o).unwrap_err();
    assert!(matches!(err, FairError::OutOfOrder { .. }), "{err}");
}

#[test]
fn a_shifted_curve_fits_the_same() {
    // Found by the property test `tolerance_mode_is_met_and_translation_invariant` (issue 21):
    // this cubic shifted by 83.28 m along x fitted with 22 control points instead of 20 and a
    // gap of 2.70 mm between the fits at tolerance 1 mm (the chord lengths, and so the knot
    // search, rounded differently). In the data's own frame the two fits are one.
    let truth = planar_cubic(&[-1.9597, 1.6655, -2.2278, -1.7757, -2.2521, 0.4825]);
    let pts = sample(&truth, 60, 0.0, DVec3::Z, 0);
    let o = options(Smoothing::MaxDeviation(1e-3));
    let a = fair_points(&pts, &o).unwrap();
    let d = DVec3::new(-83.28, 0.0, 0.0);
    let moved: Vec<DVec3> = pts.iter().map(|p| *p + d).collect();
    let b = fair_points(&moved, &o).unwrap();
    assert_eq!(
        a.report.control_points, b.report.control_points,
        "same size"
    );
    assert_eq!(
        b.curve.point(b.curve.domain().0),
        moved[0],
        "start kept exactly"
    );
    assert_eq!(
        b.curve.point(b.curve.domain().1),
        moved[59],
        "end kept exactly"
    );
    for (p, q) in a
        .curve
        .control_points()
        .iter()
        .zip(b.curve.control_points())
    {
        assert!(
            (q - d - *p).length() < 1e-6,
            "same control points: {p} vs {}",
            q - d
        );
    }
    assert!(b.report.max_deviation <= 1e-3, "within tolerance");
}

#[test]
fn the_reported_deviation_is_the_largest_true_distance() {
    // Issue 21: a 48-point helix 10⁷ m from the origin with a start tangent hung; and the
    // report understated the deviation (1.37e-4 at point 20, the true 1.53e-4 at point 16).
    // Measured here by the global closest point on the fit moved back to the origin.
    let offset = DVec3::new(1e7, 0.0, 0.0);
    let mut rng = Rng(16);
    for (sigma, tol) in [(0.0, 1e-4), (2e-5, 2e-4), (1e-4, 1e-3)] {
        let pitch = 0.4;
        let pts: Vec<DVec3> = (0..48)
            .map(|i| {
                let a = std::f64::consts::TAU * 1.5 * f64::from(i) / 47.0;
                let e = DVec3::new(rng.gauss(), rng.gauss(), rng.gauss()) * sigma;
                DVec3::new(a.cos(), a.sin(), pitch * a / std::f64::consts::TAU) + e
            })
            .collect();
        let far: Vec<DVec3> = pts.iter().map(|p| *p + offset).collect();
        let o = FairOptions {
            start_tangent: Some(DVec3::new(0.0, 1.0, pitch / std::f64::consts::TAU)),
            ..options(Smoothing::MaxDeviation(tol))
        };
        let start = std::time::Instant::now();
        let fit = fair_points(&far, &o).unwrap();
        assert!(start.elapsed().as_secs_f64() < 1.0, "well under a second");
        let back = NurbsCurve::try_new(
            fit.curve.degree(),
            fit.curve.knots().to_vec(),
            fit.curve
                .control_points()
                .iter()
                .map(|p| *p - offset)
                .collect(),
            None,
        )
        .unwrap();
        let (index, truth) = pts
            .iter()
            .map(|&p| back.nearest(p, 1e-12).unwrap().distance)
            .enumerate()
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        let r = &fit.report;
        assert!(
            (r.max_deviation - truth).abs() <= 1e-8,
            "sigma {sigma}: reported {} at {}, true {truth} at {index}",
            r.max_deviation,
            r.max_deviation_index
        );
        assert_eq!(
            r.max_deviation_index, index,
            "sigma {sigma}: at the worst point"
        );
        assert!(truth <= tol, "within tolerance");
    }
}

#[test]
fn a_fixed_tangent_on_noisy_data_gives_no_nan() {
    // Issue 21: noisy points with a start tangent the data turn away from (here +x on a sine
    // that leaves at 63°) and corners detected ended in "control point 2 has a non-finite
    // coordinate": nearly interpolating least-squares systems overflowed in back substitution
    // and were taken as solved; and the end derivative's speed, taken from the fit's own length,
    // fed a loop at the fixed tangent until the length was beyond f64 (seed 590). (Found with
    // a 64-bit LCG; these are its failing cases.)
    struct Lcg(u64);
    impl Lcg {
        fn u(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn g(&mut self) -> f64 {
            let (a, b) = (self.u().max(f64::MIN_POSITIVE), self.u());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        }
    }
    for seed in [590u64, 925, 1250, 1585, 1789, 1850] {
        let mut r = Lcg(seed * 7 + 3);
        let m = 5 + (r.u() * 300.0) as usize;
        let sigma = [1e-4, 1e-3, 1e-2, 0.1][(seed % 4) as usize];
        let pts: Vec<DVec3> = (0..m)
            .map(|i| {
                let a = 2.0 * i as f64 / (m - 1) as f64;
                let e = DVec3::new(r.g(), r.g(), r.g() * 0.1) * sigma;
                DVec3::new(a, (a * 2.0).sin(), 0.0) + e
            })
            .collect();
        let tol = sigma * (1.0 + 3.0 * r.u());
        let o = FairOptions {
            degree: 1 + (seed / 12 % 5) as usize,
            smoothing: Smoothing::MaxDeviation(tol),
            corner_angle: Some(0.05 + 3.0 * r.u()),
            start_tangent: Some(DVec3::X),
            ..FairOptions::default()
        };
        match fair_points(&pts, &o) {
            Ok(fit) => {
                assert!(
                    fit.curve.control_points().iter().all(|p| p.is_finite()),
                    "seed {seed}: finite"
                );
                assert!(
                    fit.report.max_deviation <= tol,
                    "seed {seed}: within tolerance"
                );
            }
            Err(e) => {
                assert!(
                    matches!(e, FairError::ToleranceNotReached { achieved, .. } if achieved.is_finite()),
                    "seed {seed}: {e}"
                );
            }
        }
    }
}

#[test]
fn fixed_end_tangents_are_met() {
    let truth = arc(5.0);
    let pts = sample(&truth, 40, 0.0, DVec3::Z, 0);
    // The true tangents (+y at the start, −x at the end) with a tight tolerance, and tangents a
    // few degrees off with a tolerance loose enough to bend into them.
    for (start, end, tol) in [
        (DVec3::Y, -DVec3::X, 1e-4),
        (
            DVec3::new(-0.05, 1.0, 0.0),
            DVec3::new(-1.0, -0.08, 0.0),
            3e-3,
        ),
    ] {
        let opts = FairOptions {
            smoothing: Smoothing::MaxDeviation(tol),
            corner_angle: None,
            start_tangent: Some(start),
            end_tangent: Some(end),
            ..FairOptions::default()
        };
        let fit = fair_points(&pts, &opts).unwrap();
        let (a, b) = fit.curve.domain();
        let d0 = fit.curve.derivs(a).d1.normalize();
        let d1 = fit.curve.derivs(b).d1.normalize();
        assert!(
            d0.angle_between(start.normalize()) < 1e-9,
            "start tangent {d0}"
        );
        assert!(d1.angle_between(end.normalize()) < 1e-9, "end tangent {d1}");
        assert!(fit.report.max_deviation <= tol, "still within tolerance");
    }
}

#[test]
fn duplicates_are_dropped_and_counted() {
    let truth = wigley(16.0, 6.0, 0.0);
    let mut pts = sample(&truth, 50, 0.0, DVec3::X, 0);
    pts.insert(10, pts[10]); // exact
    pts.insert(20, pts[20] + DVec3::new(0.0, 3e-5, 0.0)); // within the 1e-4 tolerance
    pts.push(pts[pts.len() - 1]); // a duplicate end
    let fit = fair_points(&pts, &options(Smoothing::MaxDeviation(1e-3))).unwrap();
    assert_eq!(fit.report.dropped_duplicates, 3, "three duplicates");
    assert!(fit.report.max_deviation <= 1e-3, "fit unaffected");
}

#[test]
fn bad_input_gives_typed_errors() {
    let good: Vec<DVec3> = (0..10)
        .map(|i| DVec3::new(f64::from(i), (f64::from(i) * 0.3).sin(), 0.0))
        .collect();
    let fit = |pts: &[DVec3], o: FairOptions| fair_points(pts, &o).unwrap_err();
    let d = FairOptions::default;

    assert!(matches!(
        fit(&good[..3], d()),
        FairError::TooFewPoints {
            count: 3,
            needed: 4,
            ..
        }
    ));
    let mut dup = vec![good[0]; 3];
    dup.push(good[1]);
    assert!(matches!(
        fit(&dup, d()),
        FairError::TooFewPoints {
            count: 2,
            dropped: 2,
            ..
        }
    ));
    assert!(matches!(
        fit(&[DVec3::ONE; 7], d()),
        FairError::AllPointsIdentical { count: 7, .. }
    ));
    let mut nan = good.clone();
    nan[4].y = f64::NAN;
    assert!(matches!(
        fit(&nan, d()),
        FairError::NonFinitePoint { index: 4, .. }
    ));
    let mut inf = good.clone();
    inf[7].z = f64::INFINITY;
    assert!(matches!(
        fit(&inf, d()),
        FairError::NonFinitePoint { index: 7, .. }
    ));
    for bad in [0.0, -1e-3, f64::NAN] {
        let o = FairOptions {
            smoothing: Smoothing::MaxDeviation(bad),
            ..d()
        };
        assert!(matches!(fit(&good, o), FairError::Tolerance(_)), "{bad}");
        let o = FairOptions {
            smoothing: Smoothing::Noise(bad),
            ..d()
        };
        assert!(matches!(fit(&good, o), FairError::Noise(_)), "{bad}");
        let o = FairOptions {
            smoothing: Smoothing::Factor(bad),
            ..d()
        };
        assert!(
            matches!(fit(&good, o), FairError::SmoothingFactor(_)),
            "{bad}"
        );
    }
    for degree in [0, 6] {
        let o = FairOptions { degree, ..d() };
        assert!(
            matches!(fit(&good, o), FairError::Degree { .. }),
            "{degree}"
        );
    }
    let o = FairOptions {
        corners: vec![9],
        ..d()
    };
    assert!(matches!(
        fit(&good, o),
        FairError::CornerIndex { index: 9, .. }
    ));
    let o = FairOptions {
        start_tangent: Some(DVec3::ZERO),
        ..d()
    };
    assert!(matches!(
        fit(&good, o),
        FairError::Tangent { end: "start", .. }
    ));
    let o = FairOptions {
        degree: 2,
        start_tangent: Some(DVec3::X),
        end_tangent: Some(DVec3::X),
        ..d()
    };
    assert!(matches!(
        fit(&good, o),
        FairError::TangentDegree { needed: 3, .. }
    ));
    // Messages name the evidence.
    let msg = fit(&nan, d()).to_string();
    assert!(msg.contains("point 4"), "{msg}");
}

#[test]
fn shuffled_points_are_rejected() {
    let truth = sbend();
    let pts = sample(&truth, 100, 0.0, DVec3::Z, 0);
    let mut rng = Rng(42);
    let mut shuffled = pts.clone();
    for i in (1..shuffled.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        shuffled.swap(i, j);
    }
    let err = fair_points(&shuffled, &FairOptions::default()).unwrap_err();
    assert!(matches!(err, FairError::OutOfOrder { .. }), "{err}");
    // The same points in order fit fine.
    fair_points(&pts, &options(Smoothing::MaxDeviation(1e-3))).unwrap();
}

/// One curve of a hull network file.
struct HullCurve {
    name: String,
    points: Vec<DVec3>,
}

fn hull(name: &str) -> Vec<HullCurve> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/hulls")
        .join(name)
        .join("network.json");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("hull file {} must exist (CI has it): {e}", path.display()));
    let json: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    json["curves"]
        .as_array()
        .expect("curves")
        .iter()
        .map(|c| HullCurve {
            name: c["name"].as_str().expect("name").to_owned(),
            points: points_of(&c["points"]),
        })
        .collect()
}

/// The points of a JSON array of `[x, y, z]` arrays.
fn points_of(json: &serde_json::Value) -> Vec<DVec3> {
    json.as_array()
        .expect("points")
        .iter()
        .map(|p| {
            let v: Vec<f64> = p
                .as_array()
                .expect("xyz")
                .iter()
                .map(|x| x.as_f64().expect("number"))
                .collect();
            DVec3::new(v[0], v[1], v[2])
        })
        .collect()
}

fn fit_hull(name: &str) {
    let curves = hull(name);
    assert!(curves.len() > 40, "{name}: the whole network");
    let tol = 0.005;
    let opts = FairOptions {
        smoothing: Smoothing::MaxDeviation(tol),
        // Coordinates are given to 0.1 mm: points within 1 mm of each other are one point
        // (the KVLCC2 profile repeats a point 13 times with 0.1 mm jitter).
        model_tolerance: Tolerance::try_new(1e-3).unwrap(),
        ..FairOptions::default()
    };
    let (mut total_cp, mut total_pts, mut worst, mut worst_run) = (0, 0, 0.0f64, 0.0f64);
    for c in &curves {
        let fit =
            fair_points(&c.points, &opts).unwrap_or_else(|e| panic!("{name} {}: {e}", c.name));
        let r = &fit.report;
        println!(
            "{name} {:<22} {:>4} points -> {:>3} control points, max dev {:.2} mm, rms {:.2} mm, \
             corners {:?}, inflections {}, dropped {}",
            c.name,
            c.points.len(),
            r.control_points,
            r.max_deviation * 1e3,
            r.rms_deviation * 1e3,
            r.corners,
            r.metrics.inflections,
            r.dropped_duplicates
        );
        assert!(
            r.max_deviation <= tol,
            "{name} {}: {} m",
            c.name,
            r.max_deviation
        );
        // Measured, not reported: every input point (the dropped duplicates too) lies within
        // the tolerance of the fitted curve, by a global closest-point search.
        let measured = c
            .points
            .iter()
            .map(|&p| fit.curve.nearest(p, 1e-9).expect("nearest").distance)
            .fold(0.0, f64::max);
        assert!(
            measured <= tol,
            "{name} {}: an input point is {measured} m from the curve",
            c.name
        );
        // Corners kept: the curve passes through each knuckle point, with a knot of
        // multiplicity 3 there that corner_parameters finds.
        let found = fit.curve.corner_parameters(1f64.to_radians());
        for (&i, &t) in r.corners.iter().zip(&r.corner_parameters) {
            assert!(
                (fit.curve.point(t) - c.points[i]).length() < 1e-9,
                "{name} {}: through corner {i}",
                c.name
            );
            assert!(
                found.contains(&t),
                "{name} {}: corner {i} at {t} is sharp",
                c.name
            );
        }
        // Between the points too: where four consecutive points lie on a line (a flat of
        // bottom or side), the curve between the middle two does not swing away from it. (It
        // may ring by about the tolerance next to the turn of a bilge: 7.0 mm on KVLCC2 st19,
        // where it swung 43 mm before fits were held between their points.)
        let off = straight_run_departure(&fit.curve, &c.points);
        assert!(
            off <= 1.5 * tol,
            "{name} {}: the curve leaves a straight run of points by {:.1} mm",
            c.name,
            off * 1e3
        );
        worst_run = worst_run.max(off);
        total_cp += r.control_points;
        total_pts += c.points.len();
        worst = worst.max(r.max_deviation);
    }
    println!(
        "{name}: {} curves, {total_pts} points -> {total_cp} control points, worst {:.2} mm, \
         {:.2} mm off a straight run of points",
        curves.len(),
        worst * 1e3,
        worst_run * 1e3
    );
}

/// How far `curve` strays, between the middle two of any four consecutive `points` that lie on
/// one line (within 0.1 mm), from that line: sampled at 20 parameters between the two points'
/// feet on the curve.
fn straight_run_departure(curve: &NurbsCurve, points: &[DVec3]) -> f64 {
    let on_line = |a: DVec3, b: DVec3, p: DVec3| {
        let d = (b - a).normalize();
        ((p - a) - d * (p - a).dot(d)).length() <= 1e-4
    };
    let mut worst = 0.0f64;
    for w in points.windows(4) {
        let (a, b) = (w[0], w[3]);
        if (b - a).length() < 1e-3 || !(on_line(a, b, w[1]) && on_line(a, b, w[2])) {
            continue;
        }
        let d = (b - a).normalize();
        let t1 = curve.nearest(w[1], 1e-10).expect("nearest").t;
        let t2 = curve.nearest(w[2], 1e-10).expect("nearest").t;
        for j in 0..=20 {
            let p = curve.point(t1 + (t2 - t1) * f64::from(j) / 20.0);
            worst = worst.max(((p - a) - d * (p - a).dot(d)).length());
        }
    }
    worst
}

#[test]
fn kcs_sections_fit_within_5_mm() {
    fit_hull("kcs");
}

#[test]
fn kvlcc2_sections_fit_within_5_mm() {
    fit_hull("kvlcc2");
}

/// The planar cubic B-spline with control points `(2i, ys[i], 0)`, the random curves of the
/// property tests.
fn planar_cubic(ys: &[f64]) -> NurbsCurve {
    let ctrl: Vec<DVec3> = ys
        .iter()
        .enumerate()
        .map(|(i, &y)| DVec3::new(2.0 * i as f64, y, 0.0))
        .collect();
    NurbsCurve::from_layout(&ctrl, None, 4, KnotLayout::Endpoint, false).unwrap()
}

proptest! {
    #![proptest_config(common::proptest_config(24))]

    /// For random planar cubic curves with noise, in every degree: the noise-mode fit keeps
    /// its sum of squares within Dierckx's range (lobe flattening included) and interpolates
    /// the end points. (Not asserted: closeness to the truth. S = Mσ² lets a fit trade the
    /// noise its coefficients absorb for bias at a tight bend; a quadratic fit of one such
    /// curve came 5σ from it in places, with or without lobe flattening.)
    #[test]
    fn noise_mode_keeps_the_smoothing_contract(
        ys in prop::collection::vec(-3.0f64..3.0, 6),
        degree in 2usize..=5,
        seed in 1u64..1000,
    ) {
        let truth = planar_cubic(&ys);
        let sigma = 0.01;
        let m = 150;
        let pts = sample(&truth, m, sigma, DVec3::Z, seed);
        let o = FairOptions { degree, ..options(Smoothing::Noise(sigma)) };
        let fit = fair_points(&pts, &o).unwrap();
        let mf = m as f64;
        let accept = (mf + (2.0 * mf).sqrt()) * sigma * sigma;
        let e = fit.report.pieces[0].residual;
        prop_assert!(e <= accept * 1.001, "E {} above {}", e, accept);
        prop_assert_eq!(fit.curve.point(fit.curve.domain().0), pts[0]);
        prop_assert_eq!(fit.curve.point(fit.curve.domain().1), pts[m - 1]);
    }

    /// For random planar cubic curves, tolerance mode meets the tolerance, keeps both end
    /// points, and the fit does not depend on where the points are (translation invariance).
    #[test]
    fn tolerance_mode_is_met_and_translation_invariant(
        ys in prop::collection::vec(-3.0f64..3.0, 6),
        tol in 1e-3f64..1e-2,
        shift in prop::array::uniform3(-100.0f64..100.0),
    ) {
        let truth = planar_cubic(&ys);
        let pts = sample(&truth, 60, 0.0, DVec3::Z, 0);
        let o = options(Smoothing::MaxDeviation(tol));
        let a = fair_points(&pts, &o).unwrap();
        prop_assert!(a.report.max_deviation <= tol, "deviation {}", a.report.max_deviation);
        prop_assert_eq!(a.curve.point(a.curve.domain().0), pts[0]);
        prop_assert_eq!(a.curve.point(a.curve.domain().1), pts[59]);
        let d = DVec3::from_array(shift);
        let moved: Vec<DVec3> = pts.iter().map(|p| *p + d).collect();
        let b = fair_points(&moved, &o).unwrap();
        prop_assert!(b.report.max_deviation <= tol, "moved deviation {}", b.report.max_deviation);
        // Same shape: every sample of the moved fit, moved back, lies within 2·tol of the
        // first fit (each is within tol of the same points; the parameterisations may differ).
        // Measured by the global closest point: dense sampling of the first fit (4000 samples,
        // a few mm apart on these curves) overstated a gap by up to half that spacing (found
        // by PROPTEST_RNG_SEED=12: 2.01 mm measured for tol 1 mm; kept in the regressions).
        let (lo, hi) = b.curve.domain();
        for i in 0..=50 {
            let p = b.curve.point(lo + (hi - lo) * f64::from(i) / 50.0) - d;
            let gap = a.curve.nearest(p, 1e-9).unwrap().distance;
            prop_assert!(gap <= 2.0 * tol, "gap {}", gap);
        }
    }
}

/// The real-ships issue: a midship section (flat bottom, bilge radius, flat side) with
/// σ = 2 mm of noise comes back within 3σ of the truth and without the inflections a smoothing
/// spline rings with past the bilge's jumps in curvature (`fair::convex`). KCS's section at
/// full scale: half breadth 16.1 m, bilge radius 2 m. Measured before `convex`: 8 inflections
/// in the five 400-point fits (every one had 1 or 2), 2 in the five 2,000-point fits (seeds 1
/// and 2); after: none at 400 points, and the same 2 at 2,000 (their lobes are not rejected
/// by the likelihood-ratio test on the refined knots; an open point of the issue).
#[test]
fn a_noisy_midship_section_keeps_its_convexity() {
    let sigma = 2e-3;
    let o = options(Smoothing::Noise(sigma));
    let mut inflected = Vec::new();
    for m in [400, 2000] {
        for seed in 1..=5 {
            let (pts, distance) = noisy_midship_of(16.1, 2.0, m, sigma, seed);
            let label = format!("{m} points, seed {seed}");
            let r = midship_fit(&pts, distance, &o, sigma, &label).report;
            if r.metrics.inflections > 0 {
                inflected.push((m, seed, r.metrics.inflections));
            }
        }
    }
    assert!(
        inflected.iter().all(|&(m, _, _)| m == 2000) && inflected.len() <= 2,
        "inflections left: {inflected:?}"
    );
}

/// A dense waterline cut from a built KCS (4,548 points, 5 mm apart) once fitted into a curve
/// that swung 8.5 km out between two of its points and came back within the tolerance of every
/// point: a parameter correction let the points of one knot span jump past a loop the fit made
/// there, and the next least-squares fit, free in that span, grew the loop. Each foot point now
/// stays between its neighbours' parameters: the fit stays within the points' box.
#[test]
fn a_dense_waterline_fits_without_a_loop_between_its_points() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/kcs_round_trip_waterline.json");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("test data")).expect("JSON");
    let points = points_of(&json["points"]);
    let opts = FairOptions {
        smoothing: Smoothing::MaxDeviation(0.005),
        model_tolerance: Tolerance::try_new(1e-3).unwrap(),
        ..FairOptions::default()
    };
    let fit = fair_points(&points, &opts).unwrap();
    assert!(
        fit.report.max_deviation <= 0.005,
        "{}",
        fit.report.max_deviation
    );
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let (a, b) = fit.curve.domain();
    let mut out = 0.0f64;
    for i in 0..=100_000 {
        let p = fit.curve.point(a + (b - a) * f64::from(i) / 100_000.0);
        out = out.max((lo - p).max_element()).max((p - hi).max_element());
    }
    println!("the fit leaves the points' box by {:.2} mm", out * 1e3);
    assert!(out <= 0.005, "the fit leaves the points' box by {out} m");
}
