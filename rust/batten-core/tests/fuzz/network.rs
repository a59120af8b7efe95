//! Fuzzing the network builder: curve soups (random segments), jittered grids of stations and
//! waterlines with duplicated, near-coincident and zero-length curves, at extreme sizes and
//! offsets. `Topology::build` and `build_hull` give finite figures and diagnostics, or an
//! error; never a panic, never a hang.

use std::sync::Arc;

use batten_core::{
    build_hull, HullOptions, Network, NetworkCurve, NurbsCurve, Role, Tolerance, Topology,
};
use glam::DVec3;
use proptest::prelude::*;

use crate::common::fuzz::{fuzz_config, offset3, scale, unit_point, within};

/// Cases of each network target in `make test` (a hull build of a small grid takes
/// milliseconds in a dev build).
const SHORT_CASES: u32 = 400;

/// The Wigley-like half-breadth `y(x, z)` the grids are drawn on, over x, z in [0, 1].
fn half_breadth(x: f64, z: f64) -> f64 {
    0.3 * (1.0 - (2.0 * x - 1.0).powi(2)) * (1.0 - z * z)
}

/// How the curves through the grid points are drawn.
#[derive(Clone, Copy, Debug)]
enum Drawing {
    /// Polylines through the points.
    Poly,
    /// Cubic Bézier splines through the points (Catmull–Rom handles).
    Cubic,
}

/// A curve soup: how the network is made before mutations.
#[derive(Clone, Debug)]
enum Soup {
    /// Random straight segments in the unit cube.
    Segments(Vec<(DVec3, DVec3)>),
    /// `stations × waterlines` on [`half_breadth`], every grid point jittered by `jitter`
    /// times a unit vector, independently for the two curves through it when `split_jitter`.
    Grid {
        stations: usize,
        waterlines: usize,
        drawing: Drawing,
        jitter: f64,
        split_jitter: bool,
        noise: Vec<DVec3>,
    },
}

/// A mutation of the soup's curve list.
#[derive(Clone, Copy, Debug)]
enum Mutation {
    /// Add an exact copy of curve `i` under another name.
    Duplicate(usize),
    /// Add a copy of curve `i` moved by `d` (relative to the model's size).
    NearCopy(usize, f64),
    /// Add a curve of zero length at the start of curve `i`.
    ZeroLength(usize),
    /// Reverse curve `i`.
    Reverse(usize),
    /// Drop curve `i`.
    Drop(usize),
}

fn soup() -> impl Strategy<Value = Soup> {
    let segments =
        proptest::collection::vec((unit_point(), unit_point()), 1..12).prop_map(Soup::Segments);
    let grid = (2usize..=6, 2usize..=6)
        .prop_flat_map(|(m, k)| {
            (
                Just(m),
                Just(k),
                prop_oneof![Just(Drawing::Poly), Just(Drawing::Cubic)],
                prop_oneof![2 => Just(0.0), 1 => Just(1e-9), 1 => Just(1e-5), 1 => Just(1e-3), 1 => Just(0.05)],
                any::<bool>(),
                proptest::collection::vec(unit_point(), 2 * m * k),
            )
        })
        .prop_map(|(stations, waterlines, drawing, jitter, split_jitter, noise)| Soup::Grid {
            stations,
            waterlines,
            drawing,
            jitter,
            split_jitter,
            noise,
        });
    prop_oneof![1 => segments, 3 => grid]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let i = any::<usize>();
    prop_oneof![
        i.prop_map(Mutation::Duplicate),
        (i, prop_oneof![Just(1e-12), Just(1e-7), Just(1e-4)])
            .prop_map(|(i, d)| Mutation::NearCopy(i, d)),
        i.prop_map(Mutation::ZeroLength),
        i.prop_map(Mutation::Reverse),
        i.prop_map(Mutation::Drop),
    ]
}

/// A curve through `points`: a polyline or a cubic Bézier spline with Catmull–Rom handles.
fn through(points: &[DVec3], drawing: Drawing) -> Option<NurbsCurve> {
    match drawing {
        Drawing::Poly => NurbsCurve::from_polyline(points, false).ok(),
        Drawing::Cubic => {
            let n = points.len();
            let tangent =
                |i: usize| (points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)]) / 6.0;
            let left: Vec<DVec3> = (0..n).map(|i| points[i] - tangent(i)).collect();
            let right: Vec<DVec3> = (0..n).map(|i| points[i] + tangent(i)).collect();
            NurbsCurve::from_bezier(points, &left, &right, false).ok()
        }
    }
}

/// The soup's curves in the unit box (before scaling), curves that cannot be made left out.
fn unit_curves(soup: &Soup) -> Vec<NurbsCurve> {
    match soup {
        Soup::Segments(segs) => segs
            .iter()
            .filter_map(|(a, b)| NurbsCurve::from_polyline(&[*a, *b], false).ok())
            .collect(),
        Soup::Grid {
            stations,
            waterlines,
            drawing,
            jitter,
            split_jitter,
            noise,
        } => {
            let (m, k) = (*stations, *waterlines);
            let at = |i: usize, j: usize, which: usize| {
                let (x, z) = (i as f64 / (m - 1) as f64, j as f64 / (k - 1) as f64);
                let shake = noise[(if *split_jitter { which } else { 0 }) * m * k + i * k + j];
                DVec3::new(x, half_breadth(x, z), z) + shake * *jitter
            };
            let st = (0..m).map(|i| (0..k).map(|j| at(i, j, 0)).collect::<Vec<_>>());
            let wl = (0..k).map(|j| (0..m).map(|i| at(i, j, 1)).collect::<Vec<_>>());
            st.chain(wl)
                .filter_map(|pts| through(&pts, *drawing))
                .collect()
        }
    }
}

/// `c` scaled by `size` about the origin and moved by `shift`.
fn placed(c: &NurbsCurve, size: f64, shift: DVec3) -> Option<NurbsCurve> {
    let pts = c
        .control_points()
        .iter()
        .map(|p| shift + *p * size)
        .collect();
    c.with_control_points(pts).ok()
}

fn apply(curves: &mut Vec<NurbsCurve>, m: Mutation) {
    if curves.is_empty() {
        return;
    }
    let n = curves.len();
    match m {
        Mutation::Duplicate(i) => curves.push(curves[i % n].clone()),
        Mutation::NearCopy(i, d) => {
            if let Some(c) = placed(&curves[i % n], 1.0, DVec3::splat(d)) {
                curves.push(c);
            }
        }
        Mutation::ZeroLength(i) => {
            let p = curves[i % n].point(curves[i % n].domain().0);
            if let Ok(c) = NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p, p], None) {
                curves.push(c);
            }
        }
        Mutation::Reverse(i) => curves[i % n] = curves[i % n].reversed(),
        Mutation::Drop(i) => {
            curves.remove(i % n);
        }
    }
}

/// The network of a soup: mutated, scaled, moved, every curve named `c<i>`; knuckle roles
/// where `knuckles` says.
fn network(
    soup: &Soup,
    mutations: &[Mutation],
    size: f64,
    shift: DVec3,
    knuckles: &[bool],
) -> Option<Network> {
    let mut curves = unit_curves(soup);
    for m in mutations {
        apply(&mut curves, *m);
    }
    let named = curves
        .iter()
        .filter_map(|c| placed(c, size, shift))
        .enumerate()
        .map(|(i, curve)| NetworkCurve {
            name: format!("c{i}"),
            role: if knuckles[i % knuckles.len()] {
                Role::Knuckle
            } else {
                Role::Free
            },
            curve,
        })
        .collect();
    Network::try_new("fuzz", named).ok()
}

/// True when the `Debug` text of a figure holds no NaN or infinity.
fn finite_text(text: &str) -> bool {
    !text
        .split(|c: char| !c.is_alphanumeric())
        .any(|word| word == "NaN" || word == "inf")
}

/// A model tolerance: the default, relative to the model's size, or extreme.
fn tolerance() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => Just(1e-4),
        2 => Just(-4.0),
        1 => Just(-1.0),
        1 => Just(1e-12),
        1 => Just(1e-300),
        1 => Just(10.0),
    ]
}

/// The tolerance `t` for a model of `size`: a negative `t` is the exponent of a tolerance
/// relative to the size.
fn tolerance_for(t: f64, size: f64) -> f64 {
    if t < 0.0 {
        size * 10f64.powf(t)
    } else {
        t
    }
}

proptest! {
    #![proptest_config(fuzz_config(SHORT_CASES))]

    /// The topology of a curve soup: finite node positions and diagnostics, or an error.
    #[test]
    fn topology_is_finite_or_an_error(
        soup in soup(),
        mutations in proptest::collection::vec(mutation(), 0..4),
        size in scale(),
        shift in offset3(),
        tol in tolerance(),
        knuckles in proptest::collection::vec(proptest::bool::weighted(0.2), 1..8),
    ) {
        let Some(net) = network(&soup, &mutations, size, shift, &knuckles) else { return Ok(()) };
        let Ok(tol) = Tolerance::try_new(tolerance_for(tol, size)) else { return Ok(()) };
        let net = Arc::new(net);
        let n = Arc::clone(&net);
        let topo = within(|| format!("Topology::build({net:?}, {tol:?})"), move || Topology::build(&n, tol));
        if let Ok(topo) = topo {
            let positions: Vec<DVec3> = topo.brep.vertices.iter().map(|v| v.position).collect();
            prop_assert!(positions.iter().all(|p| p.is_finite()), "node positions {positions:?} of {net:?}");
            let diagnostics = format!("{:?}", topo.diagnostics);
            prop_assert!(finite_text(&diagnostics), "diagnostics {diagnostics} of {net:?}");
            prop_assert!(topo.node_count() == topo.brep.vertices.len(), "node count of {net:?}");
        }
    }

    /// The hull surface of a curve soup: a finite mesh and report, or an error.
    #[test]
    fn hull_is_finite_or_an_error(
        soup in soup(),
        mutations in proptest::collection::vec(mutation(), 0..3),
        size in scale(),
        shift in offset3(),
        tol in tolerance(),
        resolution in 1usize..=6,
        knuckles in proptest::collection::vec(proptest::bool::weighted(0.2), 1..8),
    ) {
        let Some(net) = network(&soup, &mutations, size, shift, &knuckles) else { return Ok(()) };
        let Ok(options) = HullOptions::try_new(tolerance_for(tol, size), resolution) else { return Ok(()) };
        let net = Arc::new(net);
        let n = Arc::clone(&net);
        let o = options;
        let hull = within(|| format!("build_hull({net:?}, {options:?})"), move || build_hull(&n, &o));
        if let Ok(hull) = hull {
            let r = &hull.report;
            prop_assert!(
                hull.mesh.positions.iter().flatten().all(|v| v.is_finite()),
                "mesh of {net:?} with {options:?}"
            );
            let report = format!("{r:?}");
            prop_assert!(finite_text(&report), "report {report} of {net:?} with {options:?}");
            prop_assert!(r.faces <= r.edges, "{} faces but {} edges", r.faces, r.edges);
        }
    }
}
