//! Shared test helpers: `assert_near!` (prints both sides and the tolerance, as truck's
//! `tolerance.rs`) and a few analytic curves.
#![allow(dead_code)]

pub(crate) mod fuzz;

/// The network of the example file `name` in the repository's `examples/`.
pub(crate) fn example(name: &str) -> Network {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    Network::from_json(&text).expect("example reads")
}

use batten_core::{KnotLayout, Network, NetworkCurve, NurbsCurve, Role};
use glam::DVec3;

/// Assert two f64 or DVec3 values differ by at most `tol` (Euclidean for vectors).
#[macro_export]
macro_rules! assert_near {
    ($a:expr, $b:expr, $tol:expr) => {
        $crate::assert_near!($a, $b, $tol, "")
    };
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let (a, b, tol) = ($a, $b, $tol);
        let d = $crate::common::Distance::distance(&a, &b);
        assert!(d <= tol, "{:?} vs {:?}: distance {:e} > {:e}: {}", a, b, d, tol, format!($($msg)+));
    }};
}

/// Distance between two values of one kind.
pub(crate) trait Distance {
    /// |a − b|.
    fn distance(&self, other: &Self) -> f64;
}
impl Distance for f64 {
    fn distance(&self, other: &Self) -> f64 {
        (self - other).abs()
    }
}
impl Distance for DVec3 {
    fn distance(&self, other: &Self) -> f64 {
        (*self - *other).length()
    }
}

/// A full circle of radius `r` about the origin in the xy plane: rational quadratic with nine
/// control points (Piegl & Tiller Ex. 7.2), exact.
pub(crate) fn circle(r: f64) -> NurbsCurve {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let pts = [
        (1., 0.),
        (1., 1.),
        (0., 1.),
        (-1., 1.),
        (-1., 0.),
        (-1., -1.),
        (0., -1.),
        (1., -1.),
        (1., 0.),
    ]
    .map(|(x, y)| DVec3::new(r * x, r * y, 0.0));
    let w = vec![1., s, 1., s, 1., s, 1., s, 1.];
    let knots = vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.];
    NurbsCurve::try_new(2, knots, pts.to_vec(), Some(w)).unwrap()
}

/// A cubic S-bend: a B-spline whose curvature changes sign twice, a trap for local Newton.
pub(crate) fn s_bend() -> NurbsCurve {
    let pts = [
        (0., 0.),
        (1., 2.),
        (2., 2.),
        (3., -2.),
        (4., -2.),
        (5., 2.),
        (6., 2.),
        (7., 0.),
    ]
    .map(|(x, y)| DVec3::new(x, y, 0.1 * x));
    NurbsCurve::from_layout(&pts, None, 4, KnotLayout::Endpoint, false).unwrap()
}

/// The proptest configuration of every suite: `cases` cases, failures kept beside the suite in
/// `tests/<suite>.proptest-regressions` (committed, replayed first on every run). Said
/// explicitly: proptest's default looks for a `lib.rs` above the file, finds none for an
/// integration test, warns and falls back to the same place. The seed comes from
/// `PROPTEST_RNG_SEED` when set (the Makefile sets it on CI), else it is random.
pub(crate) fn proptest_config(cases: u32) -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        cases,
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..proptest::test_runner::Config::default()
    }
}

/// The straight line from `a` to `b` (degree 1).
pub(crate) fn line(a: [f64; 3], b: [f64; 3]) -> NurbsCurve {
    NurbsCurve::try_new(
        1,
        vec![0., 0., 1., 1.],
        vec![DVec3::from(a), DVec3::from(b)],
        None,
    )
    .expect("line")
}

/// The polyline through `pts` (degree 1, a knot per point).
pub(crate) fn polyline(pts: &[[f64; 3]]) -> NurbsCurve {
    let n = pts.len();
    let mut knots = vec![0.0, 0.0];
    for k in 1..n - 1 {
        knots.push(k as f64);
    }
    knots.extend([(n - 1) as f64, (n - 1) as f64]);
    NurbsCurve::try_new(
        1,
        knots,
        pts.iter().map(|p| DVec3::from(*p)).collect(),
        None,
    )
    .expect("polyline")
}

/// A network curve named `name` with `role`.
pub(crate) fn nc(name: &str, role: Role, curve: NurbsCurve) -> NetworkCurve {
    NetworkCurve {
        name: name.into(),
        role,
        curve,
    }
}

pub(crate) const BL: f64 = 40.0;
pub(crate) const BB: f64 = 8.0;
pub(crate) const BD: f64 = 5.0;

/// The port half of a box barge `BL × BB × BD`, open at both ends (its end stations are the
/// outlines of two flat, open transoms); with `aft_keel` false the keel starts at midships, so
/// the aft half of the bottom is a hole.
pub(crate) fn box_barge(aft_keel: bool) -> Network {
    let b = BB / 2.0;
    let mut c = vec![
        nc("chine", Role::Knuckle, line([0., b, 0.], [BL, b, 0.])),
        nc("deck", Role::Deck, line([0., b, BD], [BL, b, BD])),
        nc(
            "st aft",
            Role::Transom,
            polyline(&[[0., 0., 0.], [0., b, 0.], [0., b, BD]]),
        ),
        nc(
            "st mid",
            Role::Free,
            polyline(&[[BL / 2., 0., 0.], [BL / 2., b, 0.], [BL / 2., b, BD]]),
        ),
        nc(
            "st fwd",
            Role::Free,
            polyline(&[[BL, 0., 0.], [BL, b, 0.], [BL, b, BD]]),
        ),
    ];
    c.push(nc(
        "keel",
        Role::Keel,
        if aft_keel {
            line([0., 0., 0.], [BL, 0., 0.])
        } else {
            line([BL / 2., 0., 0.], [BL, 0., 0.])
        },
    ));
    Network::try_new("box", c).expect("names")
}

/// The main dimensions of the Wigley hull of `examples/wigley.py` (m).
pub(crate) mod wigley_dims {
    /// Length.
    pub(crate) const L: f64 = 100.0;
    /// Beam.
    pub(crate) const B: f64 = 10.0;
    /// Draught.
    pub(crate) const T: f64 = 6.25;
    /// Freeboard.
    pub(crate) const F: f64 = 2.5;
}

/// A NURBS curve of `degree` through the control points `pts` on `knots` (non-rational).
pub(crate) fn poly(degree: usize, knots: Vec<f64>, pts: &[[f64; 3]]) -> NurbsCurve {
    let pts = pts.iter().map(|p| DVec3::from(*p)).collect();
    NurbsCurve::try_new(degree, knots, pts, None).expect("valid curve")
}

/// The Wigley hull of `examples/wigley.py` with `stations` stations (odd) at spacing
/// `L / (stations + 1)` and `waterlines` waterlines at `T·k / waterlines` (the last is the design
/// waterline): exact quadratic stations (wall-sided above `T`) and waterlines.
pub(crate) fn wigley(stations: usize, waterlines: usize) -> Network {
    use wigley_dims::{B, F, L, T};
    let half = |x: f64| 0.5 * B * (1.0 - (2.0 * x / L).powi(2));
    let depth = |z: f64| 1.0 - ((T - z) / T).powi(2);
    let deck = T + F;
    let mut c = Vec::new();
    let m = (stations as i64 - 1) / 2;
    for k in -m..=m {
        let x = L * k as f64 / (stations + 1) as f64;
        let h = half(x);
        c.push(nc(
            &format!("station {x:+.2}"),
            Role::Free,
            poly(
                2,
                vec![0., 0., 0., 1., 1., 2., 2., 2.],
                &[
                    [x, 0., 0.],
                    [x, h, T / 2.],
                    [x, h, T],
                    [x, h, T + F / 2.],
                    [x, h, deck],
                ],
            ),
        ));
    }
    let wl = |z: f64, g: f64| {
        poly(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            &[[-L / 2., 0., z], [0., B * g, z], [L / 2., 0., z]],
        )
    };
    for k in 1..=waterlines {
        let z = T * k as f64 / waterlines as f64;
        c.push(nc(
            &format!("waterline {z:.4}"),
            Role::Free,
            wl(z, depth(z)),
        ));
    }
    c.push(nc("deck edge", Role::Deck, wl(deck, 1.0)));
    c.push(nc(
        "keel",
        Role::Keel,
        line([-L / 2., 0., 0.], [L / 2., 0., 0.]),
    ));
    c.push(nc(
        "stem",
        Role::Stem,
        line([L / 2., 0., 0.], [L / 2., 0., deck]),
    ));
    c.push(nc(
        "stern",
        Role::Transom,
        line([-L / 2., 0., 0.], [-L / 2., 0., deck]),
    ));
    Network::try_new("wigley", c).expect("unique names")
}
