//! Topology of curve networks (H-rep paper §3.1, §5.2): node, edge and face counts of hull
//! networks drawn on a Wigley-like hull surface, corner counts with T-joints, the frigate-like
//! network of the paper, invariance under curve order, direction and jitter, and bad input.
//!
//! Every network here lies exactly on a polynomial hull surface `y(x, z)`, a sum of products of
//! factors linear in (x, z): a curve that is straight in the (x, z) plane lifts to a polynomial
//! curve whose degree is the number of factors, written exactly as a Bézier spline by its
//! blossom. So curves that cross in the (x, z) plane meet exactly in 3D, and the networks are
//! genuinely curved. The test networks use the Wigley-like surface `y = B/2 (1 − u²)(1 − w²)`
//! with `u = (x − 5)/6`, `w = z/T` (x from 0 to 10, keel at z = −1, deck at z = 0); the frigate
//! has a full-scale surface of its own (see [`frigate_surface`]).

mod common;

use std::collections::BTreeMap;

use batten_core::{Diagnostic, Network, NetworkCurve, NurbsCurve, Role, Tolerance, Topology};
use glam::DVec3;
use proptest::prelude::*;

const HALF_BEAM: f64 = 0.6;
const DRAFT: f64 = 1.0;

/// A function `c + cx·x + cz·z` on the (x, z) plane.
#[derive(Clone, Copy, Debug)]
struct Linear {
    c: f64,
    cx: f64,
    cz: f64,
}

impl Linear {
    const ONE: Linear = Linear {
        c: 1.0,
        cx: 0.0,
        cz: 0.0,
    };

    fn new(c: f64, cx: f64, cz: f64) -> Self {
        Linear { c, cx, cz }
    }

    /// The value at (x, z). `c + cz·z` first: a factor `x_s(z) − x` with `x_s(z) = c + cz·z`
    /// is exactly zero at points computed as `(x_s(z), z)`.
    fn at(self, x: f64, z: f64) -> f64 {
        (self.c + self.cz * z) + self.cx * x
    }
}

/// A hull surface `y(x, z) = Σ a_i Π_j ℓ_ij(x, z)`: terms of linear factors, padded with ones
/// to `degree` factors each.
#[derive(Clone, Debug)]
struct Surface {
    degree: usize,
    terms: Vec<(f64, Vec<Linear>)>,
}

impl Surface {
    fn new(terms: Vec<(f64, Vec<Linear>)>) -> Self {
        let degree = terms.iter().map(|t| t.1.len()).max().unwrap_or(0);
        let terms = terms
            .into_iter()
            .map(|(a, mut f)| {
                f.resize(degree, Linear::ONE);
                (a, f)
            })
            .collect();
        Surface { degree, terms }
    }

    /// The height of the surface at (x, z).
    fn y(&self, x: f64, z: f64) -> f64 {
        self.terms
            .iter()
            .map(|(a, f)| a * f.iter().map(|l| l.at(x, z)).product::<f64>())
            .sum()
    }

    /// Bézier ordinates of `y` along the straight segment from `p` to `q`: `c_k` is the blossom
    /// at k ones and `degree − k` zeros, per term the mean over the ways to pick which k factors
    /// take their value at `q`.
    fn ordinates(&self, p: (f64, f64), q: (f64, f64)) -> Vec<f64> {
        let n = self.degree;
        let mut c = vec![0.0; n + 1];
        let mut count = vec![0usize; n + 1];
        for mask in 0u32..(1 << n) {
            count[mask.count_ones() as usize] += 1;
        }
        for (a, f) in &self.terms {
            let ends: Vec<(f64, f64)> =
                f.iter().map(|l| (l.at(p.0, p.1), l.at(q.0, q.1))).collect();
            for mask in 0u32..(1 << n) {
                let prod: f64 = (0..n)
                    .map(|i| {
                        if mask & (1 << i) != 0 {
                            ends[i].1
                        } else {
                            ends[i].0
                        }
                    })
                    .product();
                let k = mask.count_ones() as usize;
                c[k] += a * prod / count[k] as f64;
            }
        }
        c
    }
}

/// The Wigley-like surface of the test networks, `y = B/2 (1 − u²)(1 − w²)`.
fn hull_surface() -> Surface {
    Surface::new(vec![(
        HALF_BEAM,
        vec![
            Linear::new(11.0 / 6.0, -1.0 / 6.0, 0.0),
            Linear::new(1.0 / 6.0, 1.0 / 6.0, 0.0),
            Linear::new(1.0, 0.0, -1.0 / DRAFT),
            Linear::new(1.0, 0.0, 1.0 / DRAFT),
        ],
    )])
}

/// The height of the test networks' hull surface at (x, z).
fn surface_y(x: f64, z: f64) -> f64 {
    hull_surface().y(x, z)
}

/// A designer curve that is the (x, z) polyline `pts` lifted onto the surface `on(p, q)` of
/// each segment: a B-spline of the surfaces' degree, one Bézier piece per segment, exact.
fn lifted_on<'s>(
    name: &str,
    role: Role,
    pts: &[(f64, f64)],
    on: impl Fn((f64, f64), (f64, f64)) -> &'s Surface,
) -> NetworkCurve {
    let mut points = Vec::new();
    let degree = on(pts[0], pts[1]).degree;
    let mut knots = vec![0.0; degree + 1];
    for (s, w) in pts.windows(2).enumerate() {
        let (p, q) = (w[0], w[1]);
        let surface = on(p, q);
        assert_eq!(surface.degree, degree, "one degree along a curve");
        let ys = surface.ordinates(p, q);
        let first = if s == 0 { 0 } else { 1 };
        for (k, y) in ys.iter().enumerate().skip(first) {
            let f = k as f64 / degree as f64;
            points.push(DVec3::new(p.0 + f * (q.0 - p.0), *y, p.1 + f * (q.1 - p.1)));
        }
        let reps = if s + 2 == pts.len() {
            degree + 1
        } else {
            degree
        };
        knots.extend(std::iter::repeat_n((s + 1) as f64, reps));
    }
    let curve = NurbsCurve::try_new(degree, knots, points, None).expect("a valid lifted curve");
    NetworkCurve {
        name: name.to_owned(),
        role,
        curve,
    }
}

/// A designer curve that is the (x, z) polyline `pts` lifted onto the test networks' surface: a
/// degree-4 B-spline, one Bézier piece per polyline segment, exact.
fn lifted(name: &str, role: Role, pts: &[(f64, f64)]) -> NetworkCurve {
    let surface = hull_surface();
    lifted_on(name, role, pts, |_, _| &surface)
}

fn network(curves: Vec<NetworkCurve>) -> Network {
    Network::try_new("test", curves).expect("unique names")
}

fn build(net: &Network) -> Topology {
    Topology::build(net, Tolerance::DEFAULT).expect("topology builds")
}

/// Keel, deck, transom (x = 0), a vertical stem (x = 10), `m` stations and `n` waterlines.
fn grid_curves(m: usize, n: usize) -> Vec<NetworkCurve> {
    let (xa, xb) = (0.0, 10.0);
    let mut c = vec![
        lifted("keel", Role::Keel, &[(xa, -DRAFT), (xb, -DRAFT)]),
        lifted("deck", Role::Deck, &[(xa, 0.0), (xb, 0.0)]),
        lifted("transom", Role::Transom, &[(xa, -DRAFT), (xa, 0.0)]),
        lifted("stem", Role::Stem, &[(xb, -DRAFT), (xb, 0.0)]),
    ];
    for i in 1..=m {
        let x = xa + (xb - xa) * i as f64 / (m + 1) as f64;
        c.push(lifted(
            &format!("st{i}"),
            Role::Free,
            &[(x, -DRAFT), (x, 0.0)],
        ));
    }
    for j in 1..=n {
        let z = -DRAFT + DRAFT * j as f64 / (n + 1) as f64;
        c.push(lifted(&format!("wl{j}"), Role::Free, &[(xa, z), (xb, z)]));
    }
    c
}

fn corner_histogram(t: &Topology) -> BTreeMap<usize, usize> {
    t.faces_by_corners()
}

/// Each face as (corners, sorted curve names), sorted: the face list up to numbering.
fn face_list(t: &Topology) -> Vec<(usize, Vec<String>)> {
    let mut v: Vec<(usize, Vec<String>)> = t
        .faces
        .iter()
        .map(|f| (f.corners, sorted_names(t, &f.curves)))
        .collect();
    v.sort();
    v
}

/// The sorted names of curves given by index.
fn sorted_names(t: &Topology, curves: &[usize]) -> Vec<String> {
    let mut v: Vec<String> = t.names(curves).into_iter().map(str::to_owned).collect();
    v.sort();
    v
}

fn face(corners: usize, names: &[&str]) -> (usize, Vec<String>) {
    let mut n: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    n.sort();
    (corners, n)
}

#[test]
fn lifted_curves_lie_on_the_hull_surface() {
    let c = lifted("d", Role::Free, &[(1.0, -0.9), (7.0, -0.1), (9.0, -0.6)]);
    let (a, b) = c.curve.domain();
    for i in 0..=50 {
        let p = c.curve.point(a + (b - a) * i as f64 / 50.0);
        assert_near!(p.y, surface_y(p.x, p.z), 1e-12, "on the surface at {p}");
    }
}

#[test]
fn grids_have_the_counted_nodes_edges_and_faces() {
    // m stations × n waterlines inside keel, deck, transom and stem:
    // V = mn (crossings) + 2m (stations on keel and deck) + 2n (waterlines on transom and
    // stem) + 4 (corners); E = m(n+1) + n(m+1) + 2(m+1) + 2(n+1); F = (m+1)(n+1) quads;
    // V − E + F = 1 (a disk: one boundary loop).
    for (m, n) in [(0, 0), (1, 1), (3, 2), (7, 4), (12, 6)] {
        let t = build(&network(grid_curves(m, n)));
        assert_eq!(
            t.node_count(),
            m * n + 2 * m + 2 * n + 4,
            "nodes of {m}x{n}"
        );
        assert_eq!(
            t.edge_count(),
            2 * m * n + 3 * m + 3 * n + 4,
            "edges of {m}x{n}"
        );
        let mut expected = BTreeMap::new();
        expected.insert(4, (m + 1) * (n + 1));
        assert_eq!(corner_histogram(&t), expected, "faces of {m}x{n}");
        assert_eq!(t.boundary_loops.len(), 1, "one boundary loop for {m}x{n}");
        let outer = sorted_names(&t, &t.boundary_loops[0].curves);
        assert_eq!(
            outer,
            ["deck", "keel", "stem", "transom"],
            "outer boundary of {m}x{n}"
        );
        assert!(t.diagnostics.is_empty(), "{m}x{n}: {:?}", t.diagnostics);
        assert_eq!(t.brep.validate(), vec![], "valid B-rep for {m}x{n}");
    }
}

#[test]
fn grid_faces_name_their_four_curves() {
    let t = build(&network(grid_curves(1, 1)));
    let faces = face_list(&t);
    assert_eq!(
        faces,
        vec![
            face(4, &["deck", "st1", "stem", "wl1"]),
            face(4, &["deck", "st1", "transom", "wl1"]),
            face(4, &["keel", "st1", "stem", "wl1"]),
            face(4, &["keel", "st1", "transom", "wl1"]),
        ]
    );
    for f in &t.faces {
        assert_eq!(f.sides.len(), 4, "four sides");
        assert!(
            f.sides.iter().all(|s| s.curves.len() == 1),
            "one curve per side"
        );
    }
}

/// A 1 × 1 grid with a diagonal from the keel–transom corner through the station–waterline
/// crossing to the deck–stem corner: three curves meet at three nodes.
fn diagonal_curves() -> Vec<NetworkCurve> {
    let mut c = grid_curves(1, 1);
    c.push(lifted("diag", Role::Free, &[(0.0, -DRAFT), (10.0, 0.0)]));
    c
}

#[test]
fn three_curves_through_one_point_make_one_node() {
    let t = build(&network(diagonal_curves()));
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(t.node_count(), 9, "the diagonal adds no node");
    assert_eq!(t.edge_count(), 14, "12 grid edges and 2 diagonal edges");
    let centre = t
        .brep
        .vertices
        .iter()
        .find(|v| v.curves.len() == 3 && t.names(&v.curves).contains(&"st1"))
        .expect("the centre node");
    assert_eq!(
        t.names(&centre.curves),
        ["st1", "wl1", "diag"],
        "curves through the centre"
    );
    assert_eq!(
        face_list(&t),
        vec![
            face(3, &["deck", "diag", "st1"]),
            face(3, &["diag", "keel", "st1"]),
            face(3, &["diag", "stem", "wl1"]),
            face(3, &["diag", "transom", "wl1"]),
            face(4, &["deck", "st1", "transom", "wl1"]),
            face(4, &["keel", "st1", "stem", "wl1"]),
        ]
    );
}

/// A bow whose keel drags (runs deeper forward, to the forefoot at x = 8), a raked stem, and a
/// waterline that starts on the keel: below the waterline keel, stem and waterline bound a
/// triangle. Above it, the waterline runs on into the keel within 15°, so waterline and keel
/// make one side of a 4-cornered face.
fn bow_curves() -> Vec<NetworkCurve> {
    vec![
        lifted("keel", Role::Keel, &[(0.0, -0.8), (8.0, -1.2)]),
        lifted("stem", Role::Stem, &[(8.0, -1.2), (10.0, 0.0)]),
        lifted("deck", Role::Deck, &[(0.0, 0.0), (10.0, 0.0)]),
        lifted("transom", Role::Transom, &[(0.0, -0.8), (0.0, 0.0)]),
        lifted("st1", Role::Free, &[(1.0, -0.85), (1.0, 0.0)]),
        lifted("wl1", Role::Free, &[(2.0, -0.9), (8.5, -0.9)]),
    ]
}

#[test]
fn bow_keel_stem_and_waterline_make_a_triangle() {
    let t = build(&network(bow_curves()));
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(t.node_count(), 8, "nodes");
    assert_eq!(t.edge_count(), 10, "edges");
    assert_eq!(
        face_list(&t),
        vec![
            face(3, &["keel", "stem", "wl1"]),
            face(4, &["deck", "keel", "st1", "stem", "wl1"]),
            face(4, &["deck", "keel", "st1", "transom"]),
        ]
    );
    let big = t
        .faces
        .iter()
        .find(|f| f.curves.len() == 5)
        .expect("the face above the waterline");
    assert_eq!(big.edges.len(), 5, "five edges");
    let composite: Vec<Vec<String>> = big
        .sides
        .iter()
        .filter(|s| s.curves.len() > 1)
        .map(|s| sorted_names(&t, &s.curves))
        .collect();
    assert_eq!(
        composite,
        [["keel", "wl1"]],
        "the waterline runs on into the keel"
    );
}

/// A grid with a partial station from the deck down to the waterline: a T-joint.
fn t_joint_curves() -> Vec<NetworkCurve> {
    let mut c = vec![
        lifted("keel", Role::Keel, &[(0.0, -DRAFT), (10.0, -DRAFT)]),
        lifted("deck", Role::Deck, &[(0.0, 0.0), (10.0, 0.0)]),
        lifted("transom", Role::Transom, &[(0.0, -DRAFT), (0.0, 0.0)]),
        lifted("stem", Role::Stem, &[(10.0, -DRAFT), (10.0, 0.0)]),
        lifted("wl", Role::Free, &[(0.0, -0.5), (10.0, -0.5)]),
        lifted("st5", Role::Free, &[(5.0, -DRAFT), (5.0, 0.0)]),
    ];
    c.push(lifted("partial", Role::Free, &[(2.5, -0.5), (2.5, 0.0)]));
    c
}

#[test]
fn a_t_joint_side_is_one_side_of_two_edges() {
    let t = build(&network(t_joint_curves()));
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(
        t.node_count(),
        4 + 2 + 2 + 1 + 2,
        "corners, wl ends, st5 ends, crossing, partial"
    );
    assert_eq!(
        face_list(&t),
        vec![
            face(4, &["deck", "partial", "st5", "wl"]),
            face(4, &["deck", "partial", "transom", "wl"]),
            face(4, &["deck", "st5", "stem", "wl"]),
            face(4, &["keel", "st5", "stem", "wl"]),
            face(4, &["keel", "st5", "transom", "wl"]),
        ]
    );
    let under = t
        .faces
        .iter()
        .find(|f| sorted_names(&t, &f.curves) == ["keel", "st5", "transom", "wl"])
        .expect("the face under the T-joint");
    assert_eq!(under.edges.len(), 5, "the waterline side has two edges");
    assert_eq!(under.corners, 4, "the T-joint is no corner");
    let wl_side = under
        .sides
        .iter()
        .find(|s| t.names(&s.curves) == ["wl"])
        .expect("a waterline side");
    assert_eq!(wl_side.edges.len(), 2, "composite side");
}

/// Angles (degrees, about the x axis from +y towards +z) of the longitudinals of the tube
/// network: the first two 95° apart, so the surface normals of those neighbouring nodes along a
/// station point more than a right angle apart (like a shaft boss or a bulb between two
/// waterlines).
const TUBE_ANGLES: [f64; 3] = [-90.0, 5.0, 85.0];

/// A station of the tube: the unit circle about the x axis at `x`, from the first to the last
/// of [`TUBE_ANGLES`], exactly, as a rational quadratic B-spline of one arc per gap.
fn tube_station(name: &str, x: f64) -> NetworkCurve {
    let at = |deg: f64, r: f64| {
        let a = deg.to_radians();
        DVec3::new(x, r * a.cos(), r * a.sin())
    };
    let (mut points, mut weights, mut knots) =
        (vec![at(TUBE_ANGLES[0], 1.0)], vec![1.0], vec![0.0; 3]);
    for (k, w) in TUBE_ANGLES.windows(2).enumerate() {
        let half = 0.5 * (w[1] - w[0]);
        let c = half.to_radians().cos();
        points.extend([at(w[0] + half, 1.0 / c), at(w[1], 1.0)]);
        weights.extend([c, 1.0]);
        let reps = if k + 2 == TUBE_ANGLES.len() { 3 } else { 2 };
        knots.extend(std::iter::repeat_n((k + 1) as f64, reps));
    }
    let curve = NurbsCurve::try_new(2, knots, points, Some(weights)).expect("a valid arc");
    NetworkCurve {
        name: name.to_owned(),
        role: Role::Free,
        curve,
    }
}

/// A tube round 175° of the unit circle about the x axis, from x = 0 to 3: four stations and
/// three straight longitudinals at [`TUBE_ANGLES`].
fn tube_curves() -> Vec<NetworkCurve> {
    let mut c: Vec<NetworkCurve> = (0..4)
        .map(|i| tube_station(&format!("st{i}"), i as f64))
        .collect();
    for (j, deg) in TUBE_ANGLES.iter().enumerate() {
        let a = deg.to_radians();
        let p = |x: f64| DVec3::new(x, a.cos(), a.sin());
        let curve = NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p(0.0), p(3.0)], None)
            .expect("a valid line");
        c.push(NetworkCurve {
            name: format!("long{j}"),
            role: Role::Free,
            curve,
        });
    }
    c
}

#[test]
fn a_tube_turning_by_more_than_a_right_angle_between_nodes_has_all_its_faces() {
    // Neighbouring normals along a station point 95° apart: their dot product has the wrong
    // sign, and orienting by it alone turned the strip of faces between them inside out.
    let t = build(&network(tube_curves()));
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(t.node_count(), 12, "4 stations × 3 longitudinals");
    let mut want = Vec::new();
    for i in 0..3 {
        for j in 0..TUBE_ANGLES.len() - 1 {
            let names = [
                format!("st{i}"),
                format!("st{}", i + 1),
                format!("long{j}"),
                format!("long{}", j + 1),
            ];
            want.push(face(
                4,
                &names.iter().map(String::as_str).collect::<Vec<_>>(),
            ));
        }
    }
    want.sort();
    assert_eq!(face_list(&t), want);
}

// The frigate, at full scale in metres: x forward from the transom (x = 0), z up from the keel
// (z = 0), y to port.

/// Transom to stem head, along the deck.
const FRIGATE_LENGTH: f64 = 120.0;
/// Keel to deck.
const FRIGATE_DEPTH: f64 = 9.6;
/// Keel to design waterline (the CWL).
const FRIGATE_DRAFT: f64 = 4.8;
/// Largest half-breadth of the design waterline.
const FRIGATE_HALF_BEAM: f64 = 7.25;
/// Where the raked stem leaves the keel.
const FRIGATE_FOREFOOT: f64 = 114.0;
/// Stem rake: run forward per metre of height.
const FRIGATE_RAKE: f64 = (FRIGATE_LENGTH - FRIGATE_FOREFOOT) / FRIGATE_DEPTH;
/// The waterlines are parabolas through the stem and this far aft of the transom, so the
/// transom keeps a real width.
const FRIGATE_STERN_ROOT: f64 = 30.0;
/// Height where the sections' round-bilge cubic `S(z) = 1 − (1 − z/z₀)³` stands vertical (a
/// stationary inflection): bilge below, flare above.
const FRIGATE_BILGE: f64 = 7.2;
/// The knuckle runs from the ordinate at this x (`st6`) to the stem …
const FRIGATE_KNUCKLE_X: f64 = 72.0;
/// … at this height.
const FRIGATE_KNUCKLE_Z: f64 = 7.2;
/// Largest jump of the section slope dy/dz across the knuckle (the flare above it).
const FRIGATE_KNUCKLE_FLARE: f64 = 0.3;

/// Where the stem is at height z (a straight raked stem).
fn frigate_stem_x(z: f64) -> f64 {
    FRIGATE_FOREFOOT + FRIGATE_RAKE * z
}

/// The frigate's hull surface below the knuckle, and above it forward of `st6`:
///
/// `y = C (x + a) (x_s(z) − x) S(z)`, `S(z) = 1 − (1 − ζ)³ = 3ζ(1 − ζ) + ζ³`, `ζ = z/z₀`,
///
/// which is zero on the keel (z = 0) and on the stem (`x = x_s(z)`), exactly: every term has
/// both factors. Above the knuckle and forward of `st6` the flare term
/// `K (z − z_k)(x − x_k)² (x_s(z) − x)` is added: zero on the knuckle (a crease, G0, dying out
/// at both ends) and on the stem, and tangent to zero at `st6` (G1 there). Both are of degree 5,
/// so every straight (x, z) segment lifts to a quintic. `C` makes the CWL's largest
/// half-breadth `FRIGATE_HALF_BEAM` (at `x = (x_s(T) − a)/2`); `K` makes the largest slope jump
/// at the knuckle (at two thirds of its length) `FRIGATE_KNUCKLE_FLARE`.
fn frigate_surfaces() -> (Surface, Surface) {
    let (a, z0) = (FRIGATE_STERN_ROOT, FRIGATE_BILGE);
    let (xk, zk) = (FRIGATE_KNUCKLE_X, FRIGATE_KNUCKLE_Z);
    let bilge = |z: f64| 1.0 - (1.0 - z / z0).powi(3);
    let widest = 0.5 * (frigate_stem_x(FRIGATE_DRAFT) + a);
    let c = FRIGATE_HALF_BEAM / (widest * widest * bilge(FRIGATE_DRAFT));
    let k = FRIGATE_KNUCKLE_FLARE / (4.0 / 27.0 * (frigate_stem_x(zk) - xk).powi(3));
    let stem = Linear::new(FRIGATE_FOREFOOT, -1.0, FRIGATE_RAKE);
    let stern = Linear::new(a, 1.0, 0.0);
    let zeta = Linear::new(0.0, 0.0, 1.0 / z0);
    let lower = vec![
        (
            3.0 * c,
            vec![zeta, Linear::new(1.0, 0.0, -1.0 / z0), stern, stem],
        ),
        (c, vec![zeta, zeta, zeta, stern, stem]),
    ];
    let mut upper = lower.clone();
    let aft = Linear::new(-xk, 1.0, 0.0);
    upper.push((k, vec![Linear::new(-zk, 0.0, 1.0), aft, aft, stem]));
    (Surface::new(lower), Surface::new(upper))
}

/// Is (x, z) on the frigate's upper surface (above the knuckle, forward of `st6`)?
fn frigate_upper(p: (f64, f64)) -> bool {
    p.0 > FRIGATE_KNUCKLE_X && p.1 > FRIGATE_KNUCKLE_Z
}

/// The height of the frigate's hull surface at (x, z).
fn frigate_y(x: f64, z: f64) -> f64 {
    let (lower, upper) = frigate_surfaces();
    if frigate_upper((x, z)) {
        upper.y(x, z)
    } else {
        lower.y(x, z)
    }
}

/// The (x, z) polyline `pts` lifted onto the frigate's surface; every segment lies on one side
/// of the knuckle and of `st6`.
fn frigate_lifted(name: &str, role: Role, pts: &[(f64, f64)]) -> NetworkCurve {
    let (lower, upper) = frigate_surfaces();
    let on_or_above = |p: (f64, f64)| p.0 >= FRIGATE_KNUCKLE_X && p.1 >= FRIGATE_KNUCKLE_Z;
    lifted_on(name, role, pts, |p, q| {
        let mid = (0.5 * (p.0 + q.0), 0.5 * (p.1 + q.1));
        if frigate_upper(mid) {
            assert!(on_or_above(p) && on_or_above(q), "{name}: {p:?}–{q:?}");
            &upper
        } else {
            assert!(
                !frigate_upper(p) && !frigate_upper(q),
                "{name}: {p:?}–{q:?}"
            );
            &lower
        }
    })
}

/// The frigate-like network of the H-rep paper (§5.2, Fig. 13), at full scale (120 m from
/// transom to stem head, 14.5 m beam on a 4.8 m design waterline, 9.6 m deep): 13 curves with
/// a fore-ship knuckle ending on an ordinate (T-joint), an aft partial waterline ending on an
/// ordinate (T-joint), and a stem-rounding transition curve from the CWL to the stem between
/// CWL and knuckle, which makes a five-sided face (CWL, stem, rounding, knuckle, foremost
/// ordinate). The ordinates keep the paper's names (`st1` … `st8`, at 12 m per unit).
fn frigate() -> Network {
    let (d, t) = (FRIGATE_DEPTH, FRIGATE_DRAFT);
    let (xk, zk) = (FRIGATE_KNUCKLE_X, FRIGATE_KNUCKLE_Z);
    let xs = frigate_stem_x;
    let rounding_z = 6.6;
    let mut c = vec![
        frigate_lifted("keel", Role::Keel, &[(0.0, 0.0), (xs(0.0), 0.0)]),
        frigate_lifted(
            "stem",
            Role::Stem,
            &[(xs(0.0), 0.0), (xs(zk), zk), (xs(d), d)],
        ),
        frigate_lifted("deck", Role::Deck, &[(0.0, d), (xk, d), (xs(d), d)]),
        frigate_lifted("transom", Role::Transom, &[(0.0, 0.0), (0.0, d)]),
        frigate_lifted("cwl", Role::Free, &[(0.0, t), (xs(t), t)]),
        frigate_lifted("knuckle", Role::Knuckle, &[(xk, zk), (xs(zk), zk)]),
        frigate_lifted("wl_aft", Role::Free, &[(0.0, 2.4), (24.0, 2.4)]),
        frigate_lifted(
            "rounding",
            Role::Free,
            &[(xs(t) - 2.0, t), (xs(rounding_z), rounding_z)],
        ),
    ];
    for (name, x) in [
        ("st1", 12.0),
        ("st2", 24.0),
        ("st4", 48.0),
        ("st6", xk),
        ("st8", 96.0),
    ] {
        let pts: &[(f64, f64)] = if x > xk {
            &[(x, 0.0), (x, zk), (x, d)]
        } else {
            &[(x, 0.0), (x, d)]
        };
        c.push(frigate_lifted(name, Role::Free, pts));
    }
    Network::try_new("frigate", c).expect("unique names")
}

fn frigate_faces() -> Vec<(usize, Vec<String>)> {
    let mut v = vec![
        face(4, &["keel", "st1", "transom", "wl_aft"]),
        face(4, &["cwl", "st1", "transom", "wl_aft"]),
        face(4, &["cwl", "deck", "st1", "transom"]),
        face(4, &["keel", "st1", "st2", "wl_aft"]),
        face(4, &["cwl", "st1", "st2", "wl_aft"]),
        face(4, &["cwl", "deck", "st1", "st2"]),
        face(4, &["cwl", "keel", "st2", "st4"]),
        face(4, &["cwl", "deck", "st2", "st4"]),
        face(4, &["cwl", "keel", "st4", "st6"]),
        face(4, &["cwl", "deck", "st4", "st6"]),
        face(4, &["cwl", "keel", "st6", "st8"]),
        face(4, &["cwl", "knuckle", "st6", "st8"]),
        face(4, &["deck", "knuckle", "st6", "st8"]),
        face(4, &["cwl", "keel", "st8", "stem"]),
        face(3, &["cwl", "rounding", "stem"]),
        face(5, &["cwl", "knuckle", "rounding", "st8", "stem"]),
        face(4, &["deck", "knuckle", "st8", "stem"]),
    ];
    v.sort();
    v
}

#[test]
fn frigate_is_a_full_scale_hull_with_a_stem_and_a_transom() {
    let net = frigate();
    let curve = |name: &str| {
        &net.curves()
            .iter()
            .find(|c| c.name == name)
            .expect("a frigate curve")
            .curve
    };
    let samples = |name: &str| {
        let c = curve(name);
        let (a, b) = c.domain();
        (0..=200)
            .map(|i| c.point(a + (b - a) * i as f64 / 200.0))
            .collect::<Vec<DVec3>>()
    };
    for c in net.curves() {
        for p in samples(&c.name) {
            assert_near!(
                p.y,
                frigate_y(p.x, p.z),
                1e-9,
                "{} on the surface at {p}",
                c.name
            );
        }
    }
    // Keel and raked stem on the centreplane, exactly: the bow is a stem, not a slab.
    for name in ["keel", "stem"] {
        assert!(
            curve(name).control_points().iter().all(|p| p.y == 0.0),
            "{name} on y = 0"
        );
    }
    let stem = samples("stem");
    let (foot, head) = (stem[0], stem[stem.len() - 1]);
    assert_eq!((foot.z, head.z), (0.0, FRIGATE_DEPTH), "keel to deck");
    assert!(head.x - foot.x > 0.3 * FRIGATE_DEPTH, "a raked stem");
    assert_eq!(head.x, FRIGATE_LENGTH, "the stem head is the bow");
    // Proportions on the design waterline: a frigate's L/B ≈ 8 and B/T ≈ 3.
    let cwl = samples("cwl");
    let lwl = cwl.iter().map(|p| p.x).fold(0.0, f64::max);
    let beam = 2.0 * cwl.iter().map(|p| p.y).fold(0.0, f64::max);
    assert_near!(beam, 2.0 * FRIGATE_HALF_BEAM, 1e-3, "design beam");
    assert!((7.5..8.5).contains(&(lwl / beam)), "L/B {}", lwl / beam);
    assert!(
        (2.8..3.3).contains(&(beam / FRIGATE_DRAFT)),
        "B/T {}",
        beam / FRIGATE_DRAFT
    );
    // A transom with a real width, and flare: the deck is wider than the waterline amidships,
    // and the bow sections flare out more above the knuckle than below it.
    assert!(
        cwl[0].y > 0.5 * FRIGATE_HALF_BEAM,
        "transom at the CWL {}",
        cwl[0].y
    );
    let mid = 0.5 * (frigate_stem_x(FRIGATE_DRAFT) - FRIGATE_STERN_ROOT);
    assert!(
        frigate_y(mid, FRIGATE_DEPTH) > FRIGATE_HALF_BEAM,
        "flare amidships"
    );
    let (x, z, h) = (103.0, FRIGATE_KNUCKLE_Z, 1e-6);
    let below = (frigate_y(x, z) - frigate_y(x, z - h)) / h;
    let above = (frigate_y(x, z + h) - frigate_y(x, z)) / h;
    assert!(
        above > below + 0.25,
        "knuckle flare: slope {below} below, {above} above"
    );
}

#[test]
fn frigate_network_has_the_paper_faces() {
    let net = frigate();
    assert_eq!(net.curves().len(), 13, "13 curves as in Fig. 13");
    let t = build(&net);
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(t.node_count(), 29, "nodes");
    assert_eq!(t.edge_count(), 45, "edges");
    assert_eq!(face_list(&t), frigate_faces(), "face list");
    assert_eq!(t.boundary_loops.len(), 1, "one boundary");
    assert_eq!(t.brep.shells.len(), 1, "one shell");
    assert_eq!(t.brep.shells[0].genus, 0, "a disk");
    // T-joints: the faces beside the ordinates where wl_aft and the knuckle end have five
    // edges but four corners.
    for names in [["cwl", "keel", "st2", "st4"], ["cwl", "deck", "st4", "st6"]] {
        let f = t
            .faces
            .iter()
            .find(|f| sorted_names(&t, &f.curves) == names)
            .expect("face beside a T-joint");
        assert_eq!((f.edges.len(), f.corners), (5, 4), "T-joint face {names:?}");
    }
    let five = t
        .faces
        .iter()
        .find(|f| f.corners == 5)
        .expect("five-sided face");
    let mut sides: Vec<String> = five
        .sides
        .iter()
        .map(|s| t.names(&s.curves).join("+"))
        .collect();
    sides.sort();
    assert_eq!(
        sides,
        ["cwl", "knuckle", "rounding", "st8", "stem"],
        "one curve per side"
    );
}

#[test]
fn frigate_faces_do_not_depend_on_the_tolerance() {
    let net = frigate();
    for tol in [1e-6, 1e-5, 1e-3] {
        let t = Topology::build(&net, Tolerance::try_new(tol).expect("valid")).expect("builds");
        assert!(
            t.diagnostics.is_empty(),
            "tolerance {tol}: {:?}",
            t.diagnostics
        );
        assert_eq!(face_list(&t), frigate_faces(), "tolerance {tol}");
    }
}

#[test]
fn frigate_example_file_matches_the_network() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/frigate_network.json"
    );
    let json = frigate().to_json();
    if std::env::var_os("BATTEN_WRITE_EXAMPLES").is_some() {
        std::fs::write(path, &json).expect("write the example");
    }
    let text = std::fs::read_to_string(path)
        .expect("examples/frigate_network.json exists (BATTEN_WRITE_EXAMPLES=1 writes it)");
    assert_eq!(text, json, "the example file is the frigate network");
    let read = Network::from_json(&text).expect("the example reads");
    assert_eq!(
        face_list(&build(&read)),
        frigate_faces(),
        "faces of the file"
    );
}

// ---------------------------------------------------------------------------------------
// Invariance

/// Nodes, edges, face list, boundary loops, diagnostics.
type Summary = (usize, usize, Vec<(usize, Vec<String>)>, usize, usize);

/// A summary that must not change with curve order, direction or sub-tolerance jitter.
fn summary(t: &Topology) -> Summary {
    (
        t.node_count(),
        t.edge_count(),
        face_list(t),
        t.boundary_loops.len(),
        t.diagnostics.len(),
    )
}

fn perturbed(net: &Network, order: &[usize], flips: &[bool], jitter: &[f64]) -> Network {
    let tol = Tolerance::DEFAULT.get();
    let mut j = jitter.iter().cycle();
    let curves = order
        .iter()
        .map(|&i| {
            let c = &net.curves()[i];
            let mut curve = if flips[i] {
                c.curve.reversed()
            } else {
                c.curve.clone()
            };
            let pts: Vec<DVec3> = curve
                .control_points()
                .iter()
                .map(|p| {
                    let d = DVec3::new(
                        *j.next().expect("cycle"),
                        *j.next().expect("cycle"),
                        *j.next().expect("cycle"),
                    );
                    *p + d * (0.2 * tol)
                })
                .collect();
            curve = NurbsCurve::try_new(curve.degree(), curve.knots().to_vec(), pts, None)
                .expect("jittered curve");
            NetworkCurve {
                name: c.name.clone(),
                role: c.role,
                curve,
            }
        })
        .collect();
    Network::try_new("perturbed", curves).expect("unique names")
}

fn invariance_case(
    net: Network,
) -> impl Strategy<Value = (Network, Vec<usize>, Vec<bool>, Vec<f64>)> {
    let n = net.curves().len();
    (
        Just((0..n).collect::<Vec<usize>>()).prop_shuffle(),
        proptest::collection::vec(any::<bool>(), n),
        proptest::collection::vec(-1.0f64..1.0, 1..64),
    )
        .prop_map(move |(o, f, j)| (net.clone(), o, f, j))
}

proptest! {
    #![proptest_config(common::proptest_config(24))]

    #[test]
    fn frigate_topology_is_invariant((net, order, flips, jitter) in invariance_case(frigate())) {
        let reference = summary(&build(&net));
        let t = build(&perturbed(&net, &order, &flips, &jitter));
        prop_assert_eq!(summary(&t), reference, "{:?}", t.diagnostics);
    }

    #[test]
    fn diagonal_topology_is_invariant(
        (net, order, flips, jitter) in invariance_case(network(diagonal_curves()))
    ) {
        let reference = summary(&build(&net));
        let t = build(&perturbed(&net, &order, &flips, &jitter));
        prop_assert_eq!(summary(&t), reference, "{:?}", t.diagnostics);
    }

    #[test]
    fn grid_topology_is_invariant(
        (net, order, flips, jitter) in invariance_case(network(grid_curves(5, 3)))
    ) {
        let reference = summary(&build(&net));
        let t = build(&perturbed(&net, &order, &flips, &jitter));
        prop_assert_eq!(summary(&t), reference, "{:?}", t.diagnostics);
    }
}

// ---------------------------------------------------------------------------------------
// Bad input: clear diagnostics, no panic.

fn grid_line(i: usize, a: (u8, u8), b: (u8, u8)) -> NetworkCurve {
    let p = |q: (u8, u8)| DVec3::new(f64::from(q.0), f64::from(q.1), 0.0);
    let curve =
        NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p(a), p(b)], None).expect("line");
    NetworkCurve {
        name: format!("line{i}"),
        role: Role::Free,
        curve,
    }
}

/// Found by `random_segment_networks_give_valid_breps`: a segment lying along part of another
/// once gave two coincident edges and a twisted rotation (genus 1). The shared stretch is now
/// kept once, on the curve whose name sorts first.
#[test]
fn a_segment_along_part_of_another_is_kept_once() {
    let segs = [
        ((3, 1), (0, 4)),
        ((2, 4), (0, 4)),
        ((2, 4), (1, 4)),
        ((0, 0), (2, 4)),
    ];
    let curves = segs
        .iter()
        .enumerate()
        .map(|(i, &(a, b))| grid_line(i, a, b))
        .collect();
    let t = build(&network(curves));
    assert_eq!(t.brep.validate(), vec![], "valid B-rep");
    assert_eq!(
        face_list(&t),
        vec![face(3, &["line0", "line1", "line3"])],
        "one triangle"
    );
    let overlaps = t.diagnostics_of("overlap");
    assert_eq!(overlaps.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(overlaps[0].curves(), ["line1", "line2"], "both named");
    assert!(t.diagnostics_of("genus").is_empty(), "{:?}", t.diagnostics);
    assert!(
        t.brep
            .edges
            .iter()
            .all(|e| t.curve_names[e.curve] != "line2"),
        "line2 left out"
    );
}

proptest! {
    #![proptest_config(common::proptest_config(200))]

    /// Random segments between points of a 5 × 5 grid: crossings, T-joints, shared ends,
    /// collinear overlaps, duplicates and zero-length segments in every mix. The builder never
    /// panics and its B-rep always passes every check.
    #[test]
    fn random_segment_networks_give_valid_breps(
        segs in proptest::collection::vec(((0u8..5, 0u8..5), (0u8..5, 0u8..5)), 1..12)
    ) {
        let curves = segs.iter().enumerate().map(|(i, &(a, b))| grid_line(i, a, b)).collect();
        let t = build(&network(curves));
        prop_assert_eq!(t.brep.validate(), vec![]);
        prop_assert!(t.diagnostics_of("invalid_topology").is_empty(), "{:?}", t.diagnostics);
        prop_assert!(t.diagnostics_of("genus").is_empty(), "{:?}", t.diagnostics);
    }

    /// The same on the curved hull surface: segments between points of a 5 × 5 grid in the
    /// (x, z) plane, lifted onto the surface.
    #[test]
    fn random_curved_networks_give_valid_breps(
        segs in proptest::collection::vec(((0u8..5, 0u8..5), (0u8..5, 0u8..5)), 1..12)
    ) {
        let at = |q: (u8, u8)| (2.5 * f64::from(q.0), -0.25 * f64::from(q.1));
        let curves = segs
            .iter()
            .enumerate()
            .map(|(i, &(a, b))| lifted(&format!("c{i}"), Role::Free, &[at(a), at(b)]))
            .collect();
        let t = build(&network(curves));
        prop_assert_eq!(t.brep.validate(), vec![]);
        prop_assert!(t.diagnostics_of("invalid_topology").is_empty(), "{:?}", t.diagnostics);
        prop_assert!(t.diagnostics_of("genus").is_empty(), "{:?}", t.diagnostics);
    }
}

fn with(mut base: Vec<NetworkCurve>, extra: Vec<NetworkCurve>) -> Network {
    base.extend(extra);
    network(base)
}

#[test]
fn a_near_miss_is_reported_and_not_joined() {
    let tol = Tolerance::DEFAULT.get();
    let mut curves = grid_curves(2, 1);
    // wl1 stops 5 tolerances short of the stem.
    let gap = 5.0 * tol;
    let z = -0.5;
    let i = curves.iter().position(|c| c.name == "wl1").expect("wl1");
    curves[i] = lifted("wl1", Role::Free, &[(0.0, z), (10.0 - gap, z)]);
    let t = build(&network(curves));
    let misses = t.diagnostics_of("near_miss");
    assert_eq!(misses.len(), 1, "{:?}", t.diagnostics);
    let Diagnostic::NearMiss {
        curves,
        location,
        gap: found,
    } = misses[0]
    else {
        unreachable!("kind is near_miss")
    };
    assert_eq!(curves, &["stem".to_owned(), "wl1".to_owned()], "both names");
    // The closest approach from the end is a little under the x-gap (the stem is curved).
    assert!(*found > tol && *found <= gap * 1.01, "gap {found}");
    assert_near!(location.x, 10.0, gap, "at the stem");
    assert_near!(location.z, z, gap, "at the waterline");
    let dangling = t.diagnostics_of("dangling_end");
    assert_eq!(
        dangling.len(),
        1,
        "the short end dangles: {:?}",
        t.diagnostics
    );
    assert_eq!(dangling[0].curves(), ["wl1"], "named");
    // Not joined: the last stretch of wl1 bounds no face, so the two faces next to the stem
    // merge into one.
    assert_eq!(t.faces.len(), 5, "faces: {:?}", face_list(&t));
}

#[test]
fn a_curve_ending_in_the_air_dangles() {
    let net = with(
        grid_curves(1, 1),
        vec![lifted("stub", Role::Free, &[(7.0, 0.0), (7.0, -0.3)])],
    );
    let t = build(&net);
    let d = t.diagnostics_of("dangling_end");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves(), ["stub"], "named");
    assert_near!(
        d[0].location().expect("located").z,
        -0.3,
        1e-9,
        "at the free end"
    );
    assert_eq!(
        t.diagnostics_of("unused_edges").len(),
        1,
        "its edge bounds no face"
    );
    assert_eq!(t.faces.len(), 4, "faces unchanged");
}

#[test]
fn a_curve_meeting_nothing_is_isolated() {
    let net = with(
        grid_curves(1, 1),
        vec![lifted("lost", Role::Free, &[(20.0, -0.5), (22.0, -0.5)])],
    );
    let t = build(&net);
    let d = t.diagnostics_of("isolated_curve");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves(), ["lost"], "named");
    assert_eq!(t.faces.len(), 4, "faces unchanged");
}

#[test]
fn a_free_curve_along_a_transom_is_the_one_left_out() {
    // A station cut in the transom's plane (a sections file's station at the AP) duplicates
    // the transom: the transom keeps its role, whatever the names' order.
    let station = lifted("a station", Role::Free, &[(0.0, -DRAFT), (0.0, 0.0)]);
    let t = build(&with(grid_curves(1, 1), vec![station]));
    let d = t.diagnostics_of("duplicate_curve");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(
        d[0].curves(),
        ["transom", "a station"],
        "kept, then left out"
    );
    assert_eq!(
        summary(&t).2,
        summary(&build(&network(grid_curves(1, 1)))).2,
        "faces"
    );
}

#[test]
fn a_duplicate_curve_is_reported_and_left_out() {
    let mut dup = lifted("st1_copy", Role::Free, &[(5.0, 0.0), (5.0, -DRAFT)]);
    dup.curve = dup.curve.reversed();
    let net = with(grid_curves(1, 1), vec![dup]);
    let t = build(&net);
    let d = t.diagnostics_of("duplicate_curve");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves(), ["st1", "st1_copy"], "both named");
    assert_eq!(
        summary(&t).2,
        summary(&build(&network(grid_curves(1, 1)))).2,
        "faces"
    );
}

#[test]
fn an_overlapping_curve_is_reported() {
    let net = with(
        grid_curves(1, 1),
        vec![lifted(
            "batten",
            Role::Free,
            &[(1.0, -DRAFT), (3.0, -DRAFT), (3.0, -0.2)],
        )],
    );
    let t = build(&net);
    let d = t.diagnostics_of("overlap");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves(), ["batten", "keel"], "both named");
    let Diagnostic::Overlap { from, to, .. } = d[0] else {
        unreachable!("kind is overlap")
    };
    let (lo, hi) = if from.x < to.x {
        (from, to)
    } else {
        (to, from)
    };
    assert_near!(lo.x, 1.0, 1e-3, "stretch starts at x = 1");
    assert_near!(hi.x, 3.0, 1e-3, "stretch ends at x = 3");
}

#[test]
fn a_self_intersecting_curve_is_reported() {
    let net = with(
        grid_curves(1, 1),
        vec![lifted(
            "bow_tie",
            Role::Free,
            &[(1.0, -0.2), (3.0, -0.4), (3.0, -0.2), (1.0, -0.4)],
        )],
    );
    let t = build(&net);
    let d = t.diagnostics_of("self_intersection");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves(), ["bow_tie"], "named");
    let p = d[0].location().expect("located");
    assert_near!(
        DVec3::new(p.x, 0.0, p.z),
        DVec3::new(2.0, 0.0, -0.3),
        1e-6,
        "crossing"
    );
    assert_near!(p.y, surface_y(2.0, -0.3), 1e-6, "on the surface");
}

#[test]
fn a_zero_length_curve_is_reported_and_left_out() {
    let p = DVec3::new(3.0, surface_y(3.0, -0.5), -0.5);
    let dot = NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![p, p], None).expect("valid");
    let net = with(
        grid_curves(1, 1),
        vec![NetworkCurve {
            name: "dot".into(),
            role: Role::Free,
            curve: dot,
        }],
    );
    let t = build(&net);
    assert_eq!(t.diagnostics.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(
        t.diagnostics_of("zero_length")[0].curves(),
        ["dot"],
        "named"
    );
    assert_eq!(
        summary(&t).2,
        summary(&build(&network(grid_curves(1, 1)))).2,
        "faces"
    );
}

#[test]
fn a_lone_closed_curve_bounds_one_face_without_corners() {
    // A circle upright in the xz plane: its one node has two parallel tangents, so the normal
    // comes from the loop itself.
    let c = common::circle(0.5);
    let pts: Vec<DVec3> = c
        .control_points()
        .iter()
        .map(|p| DVec3::new(p.x + 3.0, 0.2, p.y - 0.5))
        .collect();
    let curve = NurbsCurve::try_new(2, c.knots().to_vec(), pts, c.weights()).expect("circle");
    let net = network(vec![NetworkCurve {
        name: "porthole".into(),
        role: Role::Free,
        curve,
    }]);
    let t = build(&net);
    assert_eq!(
        (t.node_count(), t.edge_count()),
        (1, 1),
        "one node, one edge"
    );
    assert_eq!(
        face_list(&t),
        vec![face(0, &["porthole"])],
        "one face, no corners"
    );
    assert_eq!(t.boundary_loops.len(), 1, "and its outside");
    let kinds: Vec<&str> = t.diagnostics.iter().map(Diagnostic::kind).collect();
    assert_eq!(
        kinds,
        ["isolated_curve", "unusual_face"],
        "{:?}",
        t.diagnostics
    );
}

#[test]
fn a_closed_box_network_has_six_faces_and_no_boundary() {
    // The twelve edges of a box as separate straight curves: a closed surface (V − E + F = 2).
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 != 0 { 4.0 } else { 0.0 },
            if i & 2 != 0 { 2.0 } else { 0.0 },
            if i & 4 != 0 { 1.0 } else { 0.0 },
        )
    };
    let mut curves = Vec::new();
    for i in 0..8usize {
        for bit in [1usize, 2, 4] {
            if i & bit == 0 {
                let (a, b) = (corner(i), corner(i | bit));
                let curve = NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b], None)
                    .expect("a line");
                curves.push(NetworkCurve {
                    name: format!("e{i}_{}", i | bit),
                    role: Role::Free,
                    curve,
                });
            }
        }
    }
    let t = build(&network(curves));
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    assert_eq!(
        (t.node_count(), t.edge_count()),
        (8, 12),
        "box nodes and edges"
    );
    assert_eq!(t.faces_by_corners(), BTreeMap::from([(4, 6)]), "six quads");
    assert!(t.boundary_loops.is_empty(), "closed");
    assert_eq!(t.brep.shells[0].genus, 0, "a sphere");
}

/// Sheets round a spine from x 0 to 2, one per direction in `dirs` (each a rectangle: ribs at
/// both spine ends, a far edge, and a line from the spine's middle node across the sheet),
/// the spine with `role`.
fn sheets_round_a_spine(dirs: &[DVec3], role: Role) -> Vec<NetworkCurve> {
    let line = |name: String, a: DVec3, b: DVec3| NetworkCurve {
        name,
        role: Role::Free,
        curve: NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b], None).expect("line"),
    };
    let (p0, pm, p1) = (DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
    let mut spine = line("spine".into(), p0, p1);
    spine.role = role;
    let mut curves = vec![spine];
    for (k, &d) in dirs.iter().enumerate() {
        curves.push(line(format!("rib{k}a"), p0, p0 + d));
        curves.push(line(format!("rib{k}b"), p1, p1 + d));
        curves.push(line(format!("fin{k}"), p0 + d, p1 + d));
        curves.push(line(format!("across{k}"), pm, pm + d));
    }
    curves
}

#[test]
fn two_faces_creased_along_a_knuckle_are_one_surface_where_lines_cross_it() {
    // A boss's flat end meeting its side: along the crease, a line across the end and a line
    // along the side meet it at one node, whose four tangents lie in no one plane.
    let creased = [DVec3::Y, DVec3::Z];
    let t = build(&network(sheets_round_a_spine(&creased, Role::Knuckle)));
    assert!(
        t.diagnostics_of("non_manifold_node").is_empty(),
        "{:?}",
        t.diagnostics
    );
    assert_eq!(t.faces.len(), 4, "two faces each side of the middle line");
    // The same tangents without the crease are taken for a branching…
    let t = build(&network(sheets_round_a_spine(&creased, Role::Free)));
    assert_eq!(
        t.diagnostics_of("non_manifold_node").len(),
        1,
        "{:?}",
        t.diagnostics
    );
    // …and a third sheet off a knuckle still is one.
    let third = DVec3::new(0.0, -1.0, -1.0).normalize();
    let t = build(&network(sheets_round_a_spine(
        &[DVec3::Y, DVec3::Z, third],
        Role::Knuckle,
    )));
    assert!(
        !t.diagnostics_of("non_manifold_node").is_empty(),
        "three sheets: {:?}",
        t.diagnostics
    );
}

#[test]
fn three_sheets_branching_off_one_curve_are_reported() {
    // A spine along x with three fins at 120° round it (like a bulkhead meeting the hull):
    // at both spine ends four tangents leave, one far out of the best plane of the others.
    let line = |name: String, a: DVec3, b: DVec3| NetworkCurve {
        name,
        role: Role::Free,
        curve: NurbsCurve::try_new(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b], None).expect("line"),
    };
    let (p0, p1) = (DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
    let mut curves = vec![line("spine".into(), p0, p1)];
    for k in 0..3 {
        let phi = std::f64::consts::TAU * k as f64 / 3.0;
        let d = DVec3::new(0.0, phi.cos(), phi.sin());
        curves.push(line(format!("rib{k}a"), p0, p0 + d));
        curves.push(line(format!("rib{k}b"), p1, p1 + d));
        curves.push(line(format!("fin{k}"), p0 + d, p1 + d));
    }
    let t = build(&network(curves));
    let d = t.diagnostics_of("non_manifold_node");
    assert_eq!(d.len(), 2, "both spine ends: {:?}", t.diagnostics);
    for n in d {
        assert_eq!(n.curves().len(), 4, "spine and three ribs named: {n}");
        assert!(n.curves().contains(&"spine"), "the spine is named: {n}");
    }
    assert_eq!(t.brep.validate(), vec![], "still a consistent B-rep");
}

#[test]
fn an_empty_network_builds_an_empty_topology() {
    let t = build(&network(Vec::new()));
    assert_eq!(
        (t.node_count(), t.edge_count(), t.faces.len()),
        (0, 0, 0),
        "empty"
    );
    assert!(t.diagnostics.is_empty(), "nothing to report");
}

#[test]
fn a_face_with_many_corners_is_flagged() {
    // A zig-zag top side drawn as eight separate curves: its nine nodes are all corners, so
    // with the two bottom corners the face has 11.
    let zig: Vec<(f64, f64)> = (0..=8)
        .map(|i| (1.0 + i as f64, if i % 2 == 0 { -0.2 } else { -0.4 }))
        .collect();
    let mut curves = vec![
        lifted("bottom", Role::Keel, &[(1.0, -0.8), (9.0, -0.8)]),
        lifted("aft", Role::Free, &[(1.0, -0.8), (1.0, -0.2)]),
        lifted("fore", Role::Free, &[(9.0, -0.8), (9.0, -0.2)]),
    ];
    for (i, w) in zig.windows(2).enumerate() {
        curves.push(lifted(&format!("zig{i}"), Role::Free, w));
    }
    let t = build(&network(curves));
    assert_eq!(t.faces.len(), 1, "one face");
    assert_eq!(
        t.faces[0].corners, 11,
        "corners: 2 below, 9 along the zig-zag"
    );
    let d = t.diagnostics_of("unusual_face");
    assert_eq!(d.len(), 1, "{:?}", t.diagnostics);
    assert_eq!(d[0].curves().len(), 11, "names every curve of the face");
}

#[test]
fn node_kinds_tell_t_joints_from_stations_landing_on_the_keel() {
    use batten_core::NodeKind;
    let count =
        |t: &Topology, kind: NodeKind| t.node_kinds().iter().filter(|&&k| k == kind).count();
    // The T-joint grid: the partial station ends on the waterline, which runs on through it.
    let t = build(&network(t_joint_curves()));
    assert_eq!(count(&t, NodeKind::TJoint), 1, "the partial station's foot");
    assert_eq!(count(&t, NodeKind::Crossing), 1, "st5 × wl");
    assert_eq!(count(&t, NodeKind::EndToEnd), 4, "the four corners");
    assert_eq!(count(&t, NodeKind::FreeEnd), 0, "no dangling end");
    // st5 and wl end on the boundary curves where every face has a corner, and the partial
    // station's head ends on the deck the same way.
    assert_eq!(count(&t, NodeKind::EndOnCurve), 5, "ends on the boundary");
    // The frigate: the knuckle ends on st6, wl_aft on st2 and the rounding on the cwl.
    let f = build(&frigate());
    let kinds = f.node_kinds();
    assert_eq!(kinds.len(), f.node_count(), "one kind per node");
    assert_eq!(count(&f, NodeKind::TJoint), 3, "three T-joints");
    assert_eq!(count(&f, NodeKind::Crossing), 7, "crossings");
    assert_eq!(count(&f, NodeKind::EndToEnd), 4, "corners of the network");
    assert_eq!(
        count(&f, NodeKind::EndOnCurve),
        15,
        "curve ends on the boundary curves"
    );
}

#[test]
fn a_ring_joined_to_its_hole_by_one_curve_is_an_unclosed_region() {
    // An outer square, a square hole in it and one curve joining the two: the region between
    // them is bounded by a loop that runs along the joining curve on both sides (a cut, not
    // a disk), so no face is made of it and the diagnostic names its curves. The hole is a
    // face of its own.
    let square = |p: &str, (x0, z0): (f64, f64), (x1, z1): (f64, f64)| {
        vec![
            lifted(&format!("{p} bottom"), Role::Free, &[(x0, z0), (x1, z0)]),
            lifted(&format!("{p} fore"), Role::Free, &[(x1, z0), (x1, z1)]),
            lifted(&format!("{p} top"), Role::Free, &[(x1, z1), (x0, z1)]),
            lifted(&format!("{p} aft"), Role::Free, &[(x0, z1), (x0, z0)]),
        ]
    };
    let mut curves = square("outer", (1.0, -0.9), (9.0, -0.1));
    curves.extend(square("hole", (4.0, -0.6), (6.0, -0.4)));
    curves.push(lifted("cut", Role::Free, &[(6.0, -0.5), (9.0, -0.5)]));
    let t = build(&network(curves));
    let d = t.diagnostics_of("unclosed_region");
    assert_eq!(d.len(), 1, "one unclosed region: {:?}", t.diagnostics);
    let names = d[0].curves();
    for c in [
        "cut",
        "outer bottom",
        "outer top",
        "hole bottom",
        "hole top",
    ] {
        assert!(names.contains(&c), "{c} named: {}", d[0]);
    }
    let loc = d[0].location().expect("located");
    assert!(
        (1.0 - 1e-9..=9.0 + 1e-9).contains(&loc.x) && (-0.9 - 1e-9..=-0.1 + 1e-9).contains(&loc.z),
        "on the ring: {loc}"
    );
    assert_eq!(t.faces.len(), 1, "the hole is the only face");
    assert_eq!(t.faces[0].corners, 4, "a quad");
    assert!(
        t.diagnostics_of("non_manifold_edge").is_empty(),
        "a cut is not a branching"
    );
    assert_eq!(t.brep.validate(), vec![], "still a consistent B-rep");
}
