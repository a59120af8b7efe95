//! Fuzzing the curve kernel: random NURBS of degree 1–5 with repeated knots, tiny and huge
//! spans, weights and extreme magnitudes and offsets; every operation is `Ok` with finite
//! results or an error, never a panic, never a hang.

use std::sync::Arc;

use batten_core::{KnotLayout, NurbsCurve};
use glam::DVec3;
use proptest::prelude::*;

use crate::common::fuzz::{all_finite, fuzz_config, offset, offset3, scale, unit_point, within};

/// Cases of each curve target in `make test` (each case is a dozen calls of microseconds).
const SHORT_CASES: u32 = 2000;

/// Degrees of the random curves: those of ship lines (Blender offers orders up to 6).
const FUZZ_MAX_DEGREE: usize = 5;

/// The raw input of [`NurbsCurve::try_new`].
#[derive(Clone, Debug)]
struct CurveInput {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
}

/// A knot span's width relative to the curve's span scale: ordinary, or nearly zero or huge
/// beside its neighbours.
fn span_factor() -> impl Strategy<Value = f64> {
    prop_oneof![8 => 0.01f64..100.0, 1 => Just(1e-15), 1 => Just(1e15)]
}

/// A knot vector for `n` control points of degree `p`: clamped or not, starting at an
/// [`offset`], spans of one [`scale`] times [`span_factor`], interior knots repeated at random
/// (sometimes more often than the degree allows, which must be refused).
fn knots(p: usize, n: usize) -> impl Strategy<Value = Vec<f64>> {
    let len = n + p + 1;
    (
        any::<bool>(),
        offset(),
        scale(),
        proptest::collection::vec(span_factor(), len),
        proptest::collection::vec(proptest::bool::weighted(0.2), len),
    )
        .prop_map(move |(clamped, start, span, factors, repeats)| {
            let mut knots = Vec::with_capacity(len);
            knots.push(start);
            for i in 1..len {
                let end_run = clamped && (i <= p || i > n);
                let step = if end_run || (repeats[i] && !(clamped && i == n)) {
                    0.0
                } else {
                    span * factors[i]
                };
                knots.push(knots[i - 1] + step);
            }
            knots
        })
}

/// A weight: ordinary, or at the edges of what f64 carries.
fn weight() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.1f64..10.0,
        1 => Just(1e-200),
        1 => Just(1e200),
        1 => Just(f64::MIN_POSITIVE),
    ]
}

fn curve_input() -> impl Strategy<Value = CurveInput> {
    (1..=FUZZ_MAX_DEGREE)
        .prop_flat_map(|p| (Just(p), (p + 1)..=(p + 8)))
        .prop_flat_map(|(p, n)| {
            (
                Just(p),
                knots(p, n),
                scale(),
                offset3(),
                proptest::collection::vec(unit_point(), n),
                prop_oneof![
                    2 => Just(None),
                    1 => proptest::collection::vec(weight(), n).prop_map(Some),
                ],
            )
        })
        .prop_map(|(degree, knots, size, at, unit, weights)| CurveInput {
            degree,
            knots,
            points: unit.iter().map(|u| at + *u * size).collect(),
            weights,
        })
}

/// Where on (or off) the domain an operation is asked at.
#[derive(Clone, Copy, Debug)]
enum Param {
    /// `a + f·(b − a)`; f outside [0, 1] is outside the domain.
    Fraction(f64),
    /// The knot of this index (modulo the knot count).
    Knot(usize),
    /// The first f64 after the domain's start.
    AfterStart,
    /// The last f64 before the domain's end.
    BeforeEnd,
}

fn param() -> impl Strategy<Value = Param> {
    prop_oneof![
        4 => (-0.5f64..1.5).prop_map(Param::Fraction),
        2 => any::<usize>().prop_map(Param::Knot),
        1 => Just(Param::AfterStart),
        1 => Just(Param::BeforeEnd),
    ]
}

fn resolve(c: &NurbsCurve, p: Param) -> f64 {
    let (a, b) = c.domain();
    match p {
        Param::Fraction(f) => a + f * (b - a),
        Param::Knot(i) => c.knots()[i % c.knots().len()],
        Param::AfterStart => next_up(a),
        Param::BeforeEnd => -next_up(-b),
    }
}

/// The least f64 above the finite `x` (`f64::next_up` is newer than the crate's MSRV).
fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() + 1)
    } else {
        f64::from_bits(x.to_bits() - 1)
    }
}

/// An accuracy asked of an approximating routine: relative to the curve's size, absolute, or
/// far below what f64 resolves.
fn accuracy() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1e-9),
        Just(1e-3),
        Just(1.0),
        Just(1e-300),
        (-320i32..=200).prop_map(|e| 10f64.powi(e)),
    ]
}

/// Every point of `c` the other checks rely on: the ends and a few interior parameters.
fn finite_everywhere(c: &NurbsCurve) -> bool {
    let (a, b) = c.domain();
    (0..=8).all(|i| c.point(a + (b - a) * f64::from(i) / 8.0).is_finite())
        && all_finite(&c.control_points())
}

proptest! {
    #![proptest_config(fuzz_config(SHORT_CASES))]

    /// Construction, evaluation, derivatives and curvature: a valid curve evaluates to finite
    /// points everywhere in and outside its domain (parameters are clamped).
    #[test]
    fn evaluation_is_finite(input in curve_input(), ts in proptest::collection::vec(param(), 1..6)) {
        let i = input.clone();
        let made = within(
            || format!("try_new({input:?})"),
            move || NurbsCurve::try_new(i.degree, i.knots, i.points, i.weights),
        );
        let Ok(c) = made else { return Ok(()) };
        let c = Arc::new(c);
        for p in ts {
            let t = resolve(&c, p);
            let cc = Arc::clone(&c);
            let (point, derivs, kappa) = within(
                || format!("evaluating {c:?} at {t:e}"),
                move || (cc.point(t), cc.derivs(t), cc.curvature_vector(t)),
            );
            prop_assert!(point.is_finite(), "C({t:e}) = {point} on {c:?}");
            prop_assert!(derivs.point == point, "derivs and point disagree at {t:e} on {c:?}");
            // Derivatives and curvature may overflow (spans of 1e-300 under points of 1e200,
            // neighbouring weights 1e-200 and 1, a speed near zero); the binding refuses
            // those. Finite derivatives never give a NaN curvature.
            let finite = derivs.d1.is_finite() && derivs.d2.is_finite();
            prop_assert!(!finite || !kappa.is_nan(), "curvature {kappa} at {t:e} on {c:?}");
        }
        let cc = Arc::clone(&c);
        let mut out = vec![0.0; 3 * 9];
        let (a, b) = c.domain();
        let ts: Vec<f64> = (0..9).map(|i| a + (b - a) * f64::from(i) / 8.0).collect();
        let out = within(|| format!("points_into on {c:?}"), move || {
            cc.points_into(&ts, &mut out);
            out
        });
        prop_assert!(out.iter().all(|v| v.is_finite()), "points_into gave {out:?} on {c:?}");
    }

    /// Arc length, bounding box and the closest point: `Ok` with finite figures or an error.
    #[test]
    fn measures_are_finite_or_errors(
        input in curve_input(),
        acc in accuracy(),
        query_on in param(),
        query_off in unit_point(),
        query_scale in scale(),
        t0 in param(),
        t1 in param(),
    ) {
        let Ok(c) = NurbsCurve::try_new(input.degree, input.knots, input.points, input.weights)
        else { return Ok(()) };
        let c = Arc::new(c);
        let cc = Arc::clone(&c);
        if let Ok(len) = within(|| format!("arc_length({acc:e}) of {c:?}"), move || cc.arc_length(acc)) {
            prop_assert!(len.is_finite() && len >= 0.0, "arc length {len} of {c:?}");
        }
        let (t0, t1) = (resolve(&c, t0), resolve(&c, t1));
        let cc = Arc::clone(&c);
        let between = within(
            || format!("arc_length_between({t0:e}, {t1:e}, {acc:e}) of {c:?}"),
            move || cc.arc_length_between(t0, t1, acc),
        );
        if let Ok(len) = between {
            prop_assert!(len.is_finite(), "arc length {len} between {t0:e} and {t1:e} of {c:?}");
        }
        let cc = Arc::clone(&c);
        if let Ok(b) = within(|| format!("bounding_box({acc:e}) of {c:?}"), move || cc.bounding_box(acc)) {
            prop_assert!(b.min.is_finite() && b.max.is_finite(), "box {b:?} of {c:?}");
        }
        let q = c.point(resolve(&c, query_on)) + query_off * query_scale;
        let cc = Arc::clone(&c);
        if let Ok(n) = within(|| format!("nearest({q}, {acc:e}) on {c:?}"), move || cc.nearest(q, acc)) {
            prop_assert!(
                n.t.is_finite() && n.point.is_finite() && n.distance.is_finite(),
                "nearest {n:?} to {q} on {c:?}"
            );
            let (a, b) = c.domain();
            prop_assert!((a..=b).contains(&n.t), "nearest t {} outside {a}..{b}", n.t);
        }
    }

    /// Edits (split, knot insertion, reversal): every curve they make is valid, so it
    /// evaluates to finite points; or the edit is refused.
    #[test]
    fn edits_make_valid_curves_or_errors(
        input in curve_input(),
        at in param(),
        times in 1usize..=6,
        min_angle in 0.0f64..3.2,
    ) {
        let Ok(c) = NurbsCurve::try_new(input.degree, input.knots, input.points, input.weights)
        else { return Ok(()) };
        let c = Arc::new(c);
        let t = resolve(&c, at);
        let cc = Arc::clone(&c);
        if let Ok((l, r)) = within(|| format!("split({t:e}) of {c:?}"), move || cc.split(t)) {
            prop_assert!(finite_everywhere(&l) && finite_everywhere(&r), "split at {t:e} of {c:?}: {l:?} {r:?}");
        }
        let cc = Arc::clone(&c);
        let inserted = within(
            || format!("insert_knot({t:e}, {times}) of {c:?}"),
            move || cc.insert_knot(t, times),
        );
        if let Ok(k) = inserted {
            prop_assert!(finite_everywhere(&k), "insert_knot({t:e}, {times}) of {c:?}: {k:?}");
        }
        let cc = Arc::clone(&c);
        if let Ok(r) = within(|| format!("try_reversed of {c:?}"), move || cc.try_reversed()) {
            prop_assert!(finite_everywhere(&r), "reversal of {c:?}: {r:?}");
        }
        let cc = Arc::clone(&c);
        let corners = within(
            || format!("corner_parameters({min_angle}) of {c:?}"),
            move || cc.corner_parameters(min_angle),
        );
        prop_assert!(corners.iter().all(|t| t.is_finite()), "corners {corners:?} of {c:?}");
        let cc = Arc::clone(&c);
        let bez = within(|| format!("bezier_control_points of {c:?}"), move || cc.bezier_control_points());
        prop_assert!(bez.iter().all(|h| h.is_finite()), "Bézier points {bez:?} of {c:?}");
    }

    /// The constructors from Blender's spline data: polylines, NURBS layouts and Bézier
    /// splines from random points (coincident, collinear, huge, offset).
    #[test]
    fn constructors_from_points_are_valid_or_errors(
        unit in proptest::collection::vec(unit_point(), 0..10),
        size in scale(),
        at in offset3(),
        order in 1usize..=7,
        layout in prop_oneof![
            Just(KnotLayout::Uniform),
            Just(KnotLayout::Endpoint),
            Just(KnotLayout::Bezier),
            Just(KnotLayout::EndpointBezier),
        ],
        cyclic in any::<bool>(),
        weights in proptest::collection::vec(weight(), 10),
    ) {
        let pts: Vec<DVec3> = unit.iter().map(|u| at + *u * size).collect();
        let p = pts.clone();
        let poly = within(
            || format!("from_polyline({pts:?}, {cyclic})"),
            move || NurbsCurve::from_polyline(&p, cyclic),
        );
        if let Ok(c) = poly {
            prop_assert!(finite_everywhere(&c), "polyline {c:?}");
        }
        let p = pts.clone();
        let w = weights[..pts.len()].to_vec();
        let nurbs = within(
            || format!("from_layout({pts:?}, {w:?}, {order}, {layout:?}, {cyclic})", w = &weights[..pts.len()]),
            move || NurbsCurve::from_layout(&p, Some(&w), order, layout, cyclic),
        );
        if let Ok(c) = nurbs {
            prop_assert!(finite_everywhere(&c), "NURBS {c:?}");
        }
        let (left, right): (Vec<DVec3>, Vec<DVec3>) = pts
            .iter()
            .zip(pts.iter().cycle().skip(1))
            .map(|(a, b)| (*a + (*a - *b) / 3.0, *a + (*b - *a) / 3.0))
            .unzip();
        let (co, l, r) = (pts.clone(), left.clone(), right.clone());
        let bezier = within(
            || format!("from_bezier({pts:?}, {left:?}, {right:?}, {cyclic})"),
            move || NurbsCurve::from_bezier(&co, &l, &r, cyclic),
        );
        if let Ok(c) = bezier {
            prop_assert!(finite_everywhere(&c), "Bézier {c:?}");
        }
    }
}
