//! Fuzzing the fitter: random point sequences, noisy lines and arcs, duplicated points and
//! extreme magnitudes and offsets, with random options. `fair_points` gives a valid curve with
//! a finite report, or a `FairError`; never a panic, never a hang.

use batten_core::{fair_points, FairOptions, FlatPlane, Smoothing, Tolerance, MAX_FAIR_DEGREE};
use glam::DVec3;
use proptest::prelude::*;

use crate::common::fuzz::{all_finite, fuzz_config, offset3, scale, unit_point, within};

/// Cases of the fitter target in `make test` (a fit of a few hundred points takes
/// milliseconds).
const SHORT_CASES: u32 = 64;

/// The shape the points are sampled from, in the unit box.
#[derive(Clone, Debug)]
enum Shape {
    /// Random points (mostly out of order: the fitter must refuse or cope).
    Random(Vec<DVec3>),
    /// `n` points along a straight line.
    Line(usize),
    /// `n` points along a circular arc turning by `turn` radians.
    Arc(usize, f64),
    /// `n` points along a helix of `turns` turns.
    Helix(usize, f64),
}

/// Points with noise and duplicates.
#[derive(Clone, Debug)]
struct Points {
    shape: Shape,
    /// Noise amplitude relative to the shape's size.
    noise: f64,
    /// Noise directions, cycled over the points.
    shakes: Vec<DVec3>,
    /// Indices (modulo the count) of points repeated right after themselves.
    duplicates: Vec<usize>,
}

fn points() -> impl Strategy<Value = Points> {
    let shape = prop_oneof![
        1 => proptest::collection::vec(unit_point(), 0..12).prop_map(Shape::Random),
        1 => (2usize..60).prop_map(Shape::Line),
        2 => (2usize..400, 0.01f64..6.0).prop_map(|(n, t)| Shape::Arc(n, t)),
        1 => (4usize..200, 0.5f64..4.0).prop_map(|(n, t)| Shape::Helix(n, t)),
    ];
    (
        shape,
        prop_oneof![2 => Just(0.0), 1 => Just(1e-9), 1 => Just(1e-4), 1 => Just(1e-2)],
        proptest::collection::vec(unit_point(), 1..16),
        proptest::collection::vec(any::<usize>(), 0..4),
    )
        .prop_map(|(shape, noise, shakes, duplicates)| Points {
            shape,
            noise,
            shakes,
            duplicates,
        })
}

fn unit_points(p: &Points) -> Vec<DVec3> {
    let along = |n: usize| (0..n).map(move |i| i as f64 / (n - 1).max(1) as f64);
    let mut pts: Vec<DVec3> = match &p.shape {
        Shape::Random(pts) => pts.clone(),
        Shape::Line(n) => along(*n)
            .map(|s| DVec3::new(s, 0.5 * s, -0.2 * s))
            .collect(),
        Shape::Arc(n, turn) => along(*n)
            .map(|s| DVec3::new((s * turn).cos(), (s * turn).sin(), 0.0))
            .collect(),
        Shape::Helix(n, turns) => along(*n)
            .map(|s| {
                let a = s * turns * std::f64::consts::TAU;
                DVec3::new(a.cos(), a.sin(), s)
            })
            .collect(),
    };
    for (i, p_i) in pts.iter_mut().enumerate() {
        *p_i += p.shakes[i % p.shakes.len()] * p.noise;
    }
    for &d in &p.duplicates {
        if !pts.is_empty() {
            let i = d % pts.len();
            pts.insert(i, pts[i]);
        }
    }
    pts
}

/// Options of a fit, from the knobs proptest turns; a negative tolerance exponent is relative
/// to the data's size.
#[derive(Clone, Debug)]
struct Knobs {
    degree: usize,
    smoothing: (u8, f64),
    corner_angle: Option<f64>,
    corners: Vec<usize>,
    start_tangent: Option<DVec3>,
    end_tangent: Option<DVec3>,
    model_tolerance: f64,
    iterations: usize,
    /// A flat plane: its normal, offset and tolerance (the last two times the points' size).
    flat: Option<(DVec3, f64, f64)>,
}

fn knobs() -> impl Strategy<Value = Knobs> {
    let tangent = prop_oneof![3 => Just(None), 1 => unit_point().prop_map(Some)];
    (
        0usize..=MAX_FAIR_DEGREE + 1,
        (
            0u8..3,
            prop_oneof![
                Just(1e-3),
                Just(1e-6),
                Just(1e-12),
                Just(1e-300),
                (-8i32..2).prop_map(|e| 10f64.powi(e))
            ],
        ),
        prop_oneof![2 => Just(None), 2 => (0.01f64..3.2).prop_map(Some)],
        proptest::collection::vec(0usize..500, 0..3),
        tangent.clone(),
        tangent,
        prop_oneof![Just(1e-4), Just(1e-12), Just(1e-300), Just(1.0)],
        0usize..25,
        prop_oneof![
            3 => Just(None),
            1 => (unit_point(), -1.0f64..1.0, prop_oneof![Just(1e-3), Just(0.1), Just(1.0), Just(0.0)])
                .prop_map(Some)
        ],
    )
        .prop_map(
            |(
                degree,
                smoothing,
                corner_angle,
                corners,
                start_tangent,
                end_tangent,
                model_tolerance,
                iterations,
                flat,
            )| Knobs {
                degree,
                smoothing,
                corner_angle,
                corners,
                start_tangent,
                end_tangent,
                model_tolerance,
                iterations,
                flat,
            },
        )
}

fn options(k: &Knobs, size: f64) -> Option<FairOptions> {
    let (kind, value) = k.smoothing;
    let value = value * size;
    let smoothing = match kind {
        0 => Smoothing::MaxDeviation(value),
        1 => Smoothing::Noise(value),
        _ => Smoothing::Factor(value * value),
    };
    Some(FairOptions {
        degree: k.degree,
        smoothing,
        corners: k.corners.clone(),
        corner_angle: k.corner_angle,
        start_tangent: k.start_tangent,
        end_tangent: k.end_tangent,
        model_tolerance: Tolerance::try_new(k.model_tolerance * size.max(1.0)).ok()?,
        max_parameter_iterations: k.iterations,
        flats: k
            .flat
            .map(|(normal, offset, tolerance)| FlatPlane {
                normal,
                offset: offset * size,
                tolerance: tolerance * size,
                noise: tolerance * size,
            })
            .into_iter()
            .collect(),
    })
}

proptest! {
    #![proptest_config(fuzz_config(SHORT_CASES))]

    /// `fair_points`: a curve with finite control points and report, or a `FairError`.
    #[test]
    fn fairing_is_finite_or_an_error(p in points(), size in scale(), shift in offset3(), k in knobs()) {
        let pts: Vec<DVec3> = unit_points(&p).iter().map(|u| shift + *u * size).collect();
        let Some(opts) = options(&k, size) else { return Ok(()) };
        let (input, o) = (pts.clone(), opts.clone());
        let faired = within(
            || format!("fair_points({pts:?}, {opts:?})"),
            move || fair_points(&input, &o),
        );
        if let Ok(f) = faired {
            prop_assert!(all_finite(&f.curve.control_points()), "control points of the fit of {pts:?} with {opts:?}");
            let r = &f.report;
            prop_assert!(
                r.max_deviation.is_finite() && r.rms_deviation.is_finite() && r.smoothing_factor.is_finite(),
                "report {r:?} of the fit of {pts:?} with {opts:?}"
            );
            prop_assert!(
                r.metrics.fairness_energy.is_finite() && r.metrics.max_curvature.is_finite(),
                "fairness {:?} of the fit of {pts:?} with {opts:?}", r.metrics
            );
            // "S is searched downwards … until the fit is within the tolerance" (Smoothing).
            if let Smoothing::MaxDeviation(tol) = opts.smoothing {
                prop_assert!(
                    r.max_deviation <= tol,
                    "max deviation {:e} above the tolerance {tol:e} in the fit of {pts:?} with {opts:?}",
                    r.max_deviation
                );
            }
        }
    }
}
