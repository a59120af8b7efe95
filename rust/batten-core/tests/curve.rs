//! Curve kernel: analytic values and identities (derivatives vs differences, knot insertion and
//! splitting keep the shape, reversal, arc length of a circle, global closest points).

mod common;

use std::f64::consts::PI;

use batten_core::{CurveError, KnotLayout, NurbsCurve};
use common::{circle, s_bend};
use glam::DVec3;
use proptest::prelude::*;

fn sample(curve: &NurbsCurve, n: usize) -> Vec<(f64, DVec3)> {
    let (a, b) = curve.domain();
    (0..=n)
        .map(|i| {
            let t = a + (b - a) * i as f64 / n as f64;
            (t, curve.point(t))
        })
        .collect()
}

#[test]
fn circle_points_lie_on_the_circle() {
    let c = circle(2.5);
    for (_, p) in sample(&c, 997) {
        assert_near!(p.length(), 2.5, 1e-13, "rational quadratic circle is exact");
    }
}

#[test]
fn circle_arc_length_meets_every_accuracy() {
    let c = circle(3.0);
    for acc in [1e-3, 1e-6, 1e-9, 1e-12] {
        let len = c.arc_length(acc).unwrap();
        assert_near!(
            len,
            6.0 * PI,
            acc.max(1e-13),
            "circumference at accuracy {acc}"
        );
    }
    let (a, _) = c.domain();
    let quarter = c.arc_length_between(a, a + 1.0, 1e-12).unwrap();
    assert_near!(quarter, 1.5 * PI, 1e-12, "one quadrant");
}

#[test]
fn derivatives_of_the_circle_are_analytic() {
    // On a circle, C' is perpendicular to C and |C'|^2 + C·C'' = 0 (from C·C = r^2).
    let c = circle(1.7);
    for (t, _) in sample(&c, 301) {
        let d = c.derivs(t);
        assert_near!(d.point.dot(d.d1), 0.0, 1e-12, "C·C' = 0 at {t}");
        assert_near!(
            d.d1.length_squared() + d.point.dot(d.d2),
            0.0,
            1e-10,
            "at {t}"
        );
        // Differentiate C·C'' + C'·C' = 0 once more: 3 C'·C'' + C·C''' = 0.
        assert_near!(
            3.0 * d.d1.dot(d.d2) + d.point.dot(d.d3),
            0.0,
            1e-8,
            "at {t}"
        );
    }
}

#[test]
fn curvature_of_a_circle_points_to_its_centre() {
    let c = circle(2.5);
    for (t, p) in sample(&c, 101) {
        let k = c.curvature_vector(t);
        assert_near!(k.length(), 0.4, 1e-12, "kappa = 1/r at {t}");
        assert_near!(
            k.normalize(),
            -p.normalize(),
            1e-12,
            "towards the centre at {t}"
        );
    }
}

#[test]
fn closest_point_on_circle_is_radial() {
    let c = circle(2.0);
    for k in 0..40 {
        let ang = 0.37 + k as f64 * 0.157;
        let q = DVec3::new(3.1 * ang.cos(), 3.1 * ang.sin(), 0.4);
        let near = c.nearest(q, 1e-12).unwrap();
        let expected = (1.1f64 * 1.1 + 0.16).sqrt();
        assert_near!(
            near.distance,
            expected,
            1e-10,
            "distance to circle at angle {ang}"
        );
        assert_near!(
            near.point,
            DVec3::new(2.0 * ang.cos(), 2.0 * ang.sin(), 0.0),
            1e-8
        );
    }
}

#[test]
fn closest_point_on_s_bend_is_global() {
    // Dense sampling gives an upper bound of the true distance; the search must match it
    // (within the sampling error) everywhere, including points between the lobes where
    // Newton from a poor start lands on a local minimum.
    let c = s_bend();
    let dense = sample(&c, 200_000);
    for i in 0..30 {
        for j in 0..12 {
            let q = DVec3::new(
                -1.0 + 9.0 * i as f64 / 29.0,
                -3.0 + 6.0 * j as f64 / 11.0,
                0.3,
            );
            let near = c.nearest(q, 1e-10).unwrap();
            let brute = dense
                .iter()
                .map(|(_, p)| (*p - q).length())
                .fold(f64::INFINITY, f64::min);
            assert!(
                near.distance <= brute + 1e-10,
                "{q}: {} > dense {brute}",
                near.distance
            );
            assert!(
                near.distance >= brute - 1e-6,
                "{q}: {} far below dense {brute}",
                near.distance
            );
            assert_near!(
                c.point(near.t),
                near.point,
                1e-12,
                "point matches parameter"
            );
        }
    }
}

#[test]
fn bounding_box_of_circle_is_tight() {
    // The circle turned 45° about z: its box is still [−r, r]², but its control polygon (a
    // square turned 45°) reaches r·√2 along x and y, so a box read off the control points
    // (or not tightened far enough) is off by r·(√2 − 1) ≈ 0.62.
    let r = 1.5;
    let c = circle(r);
    let turn = glam::DQuat::from_rotation_z(PI / 4.0);
    let turned = NurbsCurve::try_new(
        c.degree(),
        c.knots().to_vec(),
        c.control_points().into_iter().map(|p| turn * p).collect(),
        c.weights(),
    )
    .unwrap();
    let hull = turned.bezier_decomposition().hull_box();
    assert_near!(
        hull.max,
        DVec3::new(r * 2f64.sqrt(), r * 2f64.sqrt(), 0.0),
        1e-12,
        "the control polygon's box is loose"
    );
    for acc in [1e-2, 1e-5, 1e-9] {
        let b = turned.bounding_box(acc).unwrap();
        assert_near!(
            b.min,
            DVec3::new(-r, -r, 0.0),
            acc * 3f64.sqrt() + 1e-12,
            "min at {acc}"
        );
        assert_near!(
            b.max,
            DVec3::new(r, r, 0.0),
            acc * 3f64.sqrt() + 1e-12,
            "max at {acc}"
        );
    }
}

#[test]
fn s_bend_bounding_box_holds_every_point() {
    let c = s_bend();
    let b = c.bounding_box(1e-9).unwrap();
    let pts: Vec<_> = sample(&c, 20_000).into_iter().map(|(_, p)| p).collect();
    let tight = batten_core::Aabb::from_points(pts.iter().copied()).unwrap();
    assert!(
        b.expanded(1e-12).contains_box(&tight),
        "box holds the curve"
    );
    assert_near!(b.min, tight.min, 1e-6, "min close to sampled extreme");
    assert_near!(b.max, tight.max, 1e-6, "max close to sampled extreme");
}

#[test]
fn bezier_corners_are_found_and_aligned_handles_are_not_corners() {
    let co = [
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(2.0, 1.0, 0.0),
    ];
    let left = [
        DVec3::new(-0.3, 0.0, 0.0),
        DVec3::new(0.7, 0.0, 0.0),
        DVec3::new(1.7, 0.7, 0.0),
    ];
    // Point 1: aligned handles (collinear through the point), different lengths.
    let right_smooth = [
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::new(1.5, 0.0, 0.0),
        DVec3::new(2.3, 1.3, 0.0),
    ];
    let smooth = NurbsCurve::from_bezier(&co, &left, &right_smooth, false).unwrap();
    assert!(
        smooth.corner_parameters(1e-3).is_empty(),
        "aligned handles are smooth"
    );
    // Point 1: the right handle turns 45 degrees.
    let right_kink = [
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::new(1.3, 0.3, 0.0),
        DVec3::new(2.3, 1.3, 0.0),
    ];
    let kink = NurbsCurve::from_bezier(&co, &left, &right_kink, false).unwrap();
    assert_eq!(
        kink.corner_parameters(1e-3),
        vec![1.0],
        "one corner at the middle point"
    );
    assert_eq!(kink.degree(), 3, "cubic");
    assert_near!(kink.point(1.0), co[1], 1e-15, "passes through the point");
}

#[test]
fn polyline_corners_and_closure() {
    let pts = [
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 2.0, 0.0),
    ];
    let c = NurbsCurve::from_polyline(&pts, false).unwrap();
    assert_eq!(c.degree(), 1, "degree 1");
    assert_eq!(
        c.corner_parameters(1e-3),
        vec![1.0, 2.0],
        "both inner vertices turn"
    );
    let closed = NurbsCurve::from_polyline(&pts, true).unwrap();
    let (a, b) = closed.domain();
    assert_near!(closed.point(a), closed.point(b), 0.0, "closed");
    assert_near!(
        closed.arc_length(1e-12).unwrap(),
        1.0 + 1.0 + 2f64.sqrt() + 8f64.sqrt(),
        1e-12
    );
}

#[test]
fn cyclic_layouts_close_smoothly() {
    let pts: Vec<DVec3> = (0..7)
        .map(|i| {
            let a = i as f64 * 2.0 * PI / 7.0;
            DVec3::new(a.cos(), a.sin(), 0.1 * (3.0 * a).sin())
        })
        .collect();
    for layout in [KnotLayout::Uniform, KnotLayout::Endpoint] {
        for order in 2..=6 {
            let c = NurbsCurve::from_layout(&pts, None, order, layout, true).unwrap();
            let (a, b) = c.domain();
            assert_near!(
                c.point(a),
                c.point(b),
                1e-12,
                "{layout:?} order {order} closes"
            );
            if layout == KnotLayout::Uniform && order > 2 {
                assert_near!(
                    c.derivs(a).d1,
                    c.derivs(b).d1,
                    1e-10,
                    "tangent continuous at seam"
                );
            }
        }
    }
}

#[test]
fn validation_errors_carry_evidence() {
    let pts = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
    let knots = vec![0., 0., 0., 0., 1., 1., 1., 1.];
    let ok = NurbsCurve::try_new(3, knots.clone(), pts.clone(), None);
    assert!(ok.is_ok(), "valid cubic");
    let mut nan = pts.clone();
    nan[2].y = f64::NAN;
    assert!(
        matches!(
            NurbsCurve::try_new(3, knots.clone(), nan, None),
            Err(CurveError::NonFinitePoint { index: 2, .. })
        ),
        "NaN point"
    );
    let mut inf = pts.clone();
    inf[1].z = f64::INFINITY;
    assert!(
        matches!(
            NurbsCurve::try_new(3, knots.clone(), inf, None),
            Err(CurveError::NonFinitePoint { index: 1, .. })
        ),
        "infinite point"
    );
    assert_eq!(
        NurbsCurve::try_new(3, vec![0., 0., 0., 0., 1., 1., 1.], pts[..3].to_vec(), None),
        Err(CurveError::TooFewPoints { count: 3, order: 4 }),
        "too few points"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(3, vec![0., 0., 0., 1., 0.5, 1., 1., 1.], pts.clone(), None),
            Err(CurveError::DecreasingKnots { index: 4, .. })
        ),
        "decreasing knots"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(3, knots.clone(), pts.clone(), Some(vec![1., 0., 1., 1.])),
            Err(CurveError::BadWeight { index: 1, .. })
        ),
        "zero weight"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(3, knots.clone(), pts.clone(), Some(vec![1., 1., -2., 1.])),
            Err(CurveError::BadWeight { index: 2, .. })
        ),
        "negative weight"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(3, vec![0.; 8], pts.clone(), None),
            Err(CurveError::EmptyDomain { .. }) | Err(CurveError::KnotMultiplicity { .. })
        ),
        "all-equal knots"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(
                1,
                vec![0., 0., 1., 1., 1., 2., 2.],
                vec![DVec3::ZERO; 5],
                None
            ),
            Err(CurveError::KnotMultiplicity { .. }) | Err(CurveError::KnotCount { .. })
        ),
        "broken curve"
    );
    assert!(
        matches!(
            NurbsCurve::try_new(0, vec![], vec![], None),
            Err(CurveError::Degree { .. })
        ),
        "degree 0"
    );
}

#[test]
fn split_rejects_domain_ends() {
    let c = s_bend();
    let (a, b) = c.domain();
    for t in [a, b, a - 1.0, f64::NAN] {
        assert!(c.split(t).is_err(), "split at {t} must fail");
    }
}

fn arb_curve() -> impl Strategy<Value = NurbsCurve> {
    (1usize..=5, 0usize..6, any::<bool>()).prop_flat_map(|(degree, extra, rational)| {
        let n = degree + 1 + extra;
        (
            prop::collection::vec(prop::array::uniform3(-10.0f64..10.0), n),
            prop::collection::vec(0.2f64..5.0, n),
            prop::collection::vec(0.05f64..1.0, n - degree),
            Just((degree, rational)),
        )
            .prop_map(|(pts, w, gaps, (degree, rational))| {
                let mut knots = vec![0.0; degree + 1];
                let mut u = 0.0;
                for g in &gaps[..gaps.len() - 1] {
                    u += g;
                    knots.push(u);
                }
                u += gaps[gaps.len() - 1];
                knots.extend(std::iter::repeat_n(u, degree + 1));
                let pts = pts.into_iter().map(DVec3::from_array).collect();
                NurbsCurve::try_new(degree, knots, pts, rational.then_some(w)).unwrap()
            })
    })
}

proptest! {
    #![proptest_config(common::proptest_config(256))]

    #[test]
    fn derivatives_match_central_differences(c in arb_curve(), s in 0.05f64..0.95) {
        let (a, b) = c.domain();
        let t = a + s * (b - a);
        // Stay inside one polynomial piece: differences across a knot are meaningless.
        let k = c.knots();
        prop_assume!(k.iter().all(|&u| (u - t).abs() > 2e-3));
        let h = 1e-5;
        let d = c.derivs(t);
        let (m, p) = (c.derivs(t - h), c.derivs(t + h));
        let scale = 1.0 + d.d1.length() + d.d2.length() + d.d3.length();
        prop_assert!(((p.point - m.point) / (2.0 * h) - d.d1).length() <= 1e-5 * scale);
        prop_assert!(((p.d1 - m.d1) / (2.0 * h) - d.d2).length() <= 1e-4 * scale);
        prop_assert!(((p.d2 - m.d2) / (2.0 * h) - d.d3).length() <= 1e-3 * scale);
        prop_assert!((d.point - c.point(t)).length() <= 1e-12 * (1.0 + d.point.length()));
    }

    #[test]
    fn knot_insertion_keeps_the_shape(c in arb_curve(), s in 0.0f64..=1.0, times in 1usize..4) {
        let (a, b) = c.domain();
        let t = a + s * (b - a);
        let room = c.degree().saturating_sub(c.knots().iter().filter(|&&u| u == t).count());
        let times = times.min(room);
        prop_assume!(times > 0);
        let d = c.insert_knot(t, times).unwrap();
        prop_assert_eq!(d.control_point_count(), c.control_point_count() + times);
        for i in 0..=50 {
            let u = a + (b - a) * i as f64 / 50.0;
            prop_assert!((c.point(u) - d.point(u)).length() <= 1e-10 * (1.0 + c.point(u).length()));
        }
    }

    #[test]
    fn split_pieces_reproduce_the_curve(c in arb_curve(), s in 0.01f64..0.99) {
        let (a, b) = c.domain();
        let t = a + s * (b - a);
        let (l, r) = c.split(t).unwrap();
        prop_assert_eq!(l.domain(), (a, t));
        prop_assert_eq!(r.domain(), (t, b));
        prop_assert!((l.point(t) - r.point(t)).length() <= 1e-12 * (1.0 + c.point(t).length()));
        for i in 0..=40 {
            let u = a + (t - a) * i as f64 / 40.0;
            prop_assert!((l.point(u) - c.point(u)).length() <= 1e-10 * (1.0 + c.point(u).length()));
            let v = t + (b - t) * i as f64 / 40.0;
            prop_assert!((r.point(v) - c.point(v)).length() <= 1e-10 * (1.0 + c.point(v).length()));
        }
        let total = c.arc_length(1e-9).unwrap();
        let parts = l.arc_length(1e-9).unwrap() + r.arc_length(1e-9).unwrap();
        prop_assert!((total - parts).abs() <= 1e-8 * (1.0 + total));
    }

    #[test]
    fn reversal_keeps_points_and_length(c in arb_curve(), s in 0.0f64..=1.0) {
        let r = c.reversed();
        let (a, b) = c.domain();
        let (ra, rb) = r.domain();
        let t = a + s * (b - a);
        let u = rb - s * (rb - ra);
        prop_assert!((c.point(t) - r.point(u)).length() <= 1e-10 * (1.0 + c.point(t).length()));
        let (l1, l2) = (c.arc_length(1e-9).unwrap(), r.arc_length(1e-9).unwrap());
        prop_assert!((l1 - l2).abs() <= 1e-8 * (1.0 + l1));
    }

    #[test]
    fn nearest_never_worse_than_sampling(c in arb_curve(), q in prop::array::uniform3(-12.0f64..12.0)) {
        let q = DVec3::from_array(q);
        let near = c.nearest(q, 1e-9).unwrap();
        let (a, b) = c.domain();
        let brute = (0..=4000)
            .map(|i| (c.point(a + (b - a) * i as f64 / 4000.0) - q).length())
            .fold(f64::INFINITY, f64::min);
        prop_assert!(near.distance <= brute + 1e-9, "{} > sampled {}", near.distance, brute);
        prop_assert!((c.point(near.t) - near.point).length() <= 1e-9 * (1.0 + near.point.length()));
    }

    #[test]
    fn nearest_is_global_with_very_unequal_spans(
        gaps in prop::collection::vec(prop_oneof![0.001f64..0.03, 1.0f64..3.4], 30..60),
        seed in prop::array::uniform3(-1.0f64..1.0),
        s in 0.0f64..1.0,
        off in prop::array::uniform3(-0.05f64..0.05),
    ) {
        // A long waterline-like curve whose knot spans range from 1 mm to 3.4 m (the shape of
        // fitted hull curves), queried near a curve point: the answer is never worse than
        // dense sampling, and near the true distance.
        let n = gaps.len() + 3;
        let mut knots = vec![0.0; 4];
        let mut u = 0.0;
        for g in &gaps[..gaps.len() - 1] {
            u += g;
            knots.push(u);
        }
        u += gaps[gaps.len() - 1];
        knots.extend([u; 4]);
        let mut x = 0.0;
        let pts: Vec<DVec3> = (0..n)
            .map(|i| {
                x += if i % 7 == 3 { 0.02 } else { 4.0 };
                DVec3::new(x, 15.0 + 3.0 * (x * 0.05 + seed[0]).sin(), 0.3 * seed[1] * (x * 0.2).cos())
            })
            .collect();
        let c = NurbsCurve::try_new(3, knots, pts, None).unwrap();
        let (a, b) = c.domain();
        let q = c.point(a + s * (b - a)) + DVec3::from_array(off);
        let near = c.nearest(q, 1e-9).unwrap();
        let brute = (0..=200_000)
            .map(|i| (c.point(a + (b - a) * i as f64 / 200_000.0) - q).length())
            .fold(f64::INFINITY, f64::min);
        prop_assert!(near.distance <= brute + 1e-9, "{} > sampled {}", near.distance, brute);
    }

    #[test]
    fn bounding_box_holds_the_curve(c in arb_curve()) {
        let b = c.bounding_box(1e-6).unwrap().expanded(1e-9);
        let (a, e) = c.domain();
        for i in 0..=500 {
            let p = c.point(a + (e - a) * i as f64 / 500.0);
            prop_assert!(b.contains_box(&batten_core::Aabb::from_point(p)), "{p} outside");
        }
    }
}
