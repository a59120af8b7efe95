//! A chine that lies in one plane — a transom's edge, joined from the corners of the waterlines
//! that cross the transom — carried on at its ends to the other knuckles in that plane: where
//! the profile turns from the transom onto the counter, and where the deck edge turns onto the
//! transom. Without this the transom's edge below the lowest waterline that crosses it (and
//! above the highest) is in no curve, and one face spans the transom and the hull across their
//! knuckle (H-rep paper §5: every region of the data a face; issue 13's closed regions).
//!
//! The carried-on piece takes its shape from the nearest section parallel to the plane (the
//! station just forward of the transom): that section's run between the points nearest the two
//! ends, moved onto them with a shift that blends from one end's offset to the other's along
//! its length, then laid into the plane.
//!
//! A flat end with no chine at all — a shaft boss cut square, which the profile outlines
//! between two knuckles and no section crosses — gets its edge the same way ([`flat_ends`]):
//! from one knuckle to the other, shaped by the nearest station. Its face would have two sides
//! (the profile and the edge), and the band of boss between the edge and that station turns by
//! half a circle, too much for one patch (KCS: a 154.6° normal jump there); a straight line
//! across the end to the edge's point farthest from the profile, and one on from there to the
//! station, part both.

use glam::DVec3;

use super::data_nodes::axis_planes;
use crate::curve::BezierDecomposition;
use crate::defaults::SECTION_CAPTURE_FACTOR;
use crate::network::NetworkCurve;

/// A chain of knuckle points: the curve index and the point, in order along the axis of the
/// family whose sections gave them.
pub(super) type Chain = Vec<(usize, DVec3)>;

/// The axis along the hull's length (x): a flat end's plane is square to it, never the flat
/// keel's between two knuckles of the profile.
const LENGTH_AXIS: usize = 0;

/// Points the carried-on piece takes from its guiding section, between the two ends.
const GUIDE_SAMPLES: usize = 8;

/// A guiding section may pass this many plane gaps (plus a quarter of the piece's length) from
/// the ends moved into its plane: a hull sloping at up to about 70° to the plane's normal.
const GUIDE_REACH: f64 = 3.0;

/// The pieces that carry each chain of `chains` (found in the family of sections square to
/// axis `chains[c].0`) that lies in one axis plane on to the knuckles in that plane beyond its
/// ends (module doc): per chain, the piece before its first point (from the knuckle reached,
/// in order towards the chain) and the piece after its last (towards the knuckle reached),
/// each empty where there is nothing to reach. `planes[i]` is the axis plane curve `i` lies
/// in, `knuckles[i]` its knuckle points; `tolerance` is the distance within which a point is
/// in a plane or on a chain.
pub(super) fn carried_on_in_plane(
    curves: &[NetworkCurve],
    planes: &[Option<(usize, f64)>],
    knuckles: &[Vec<DVec3>],
    chains: &[(usize, Chain)],
    tolerance: f64,
) -> Vec<(Chain, Chain)> {
    let on_a_chain = |p: DVec3| on_a_chain(chains, p, tolerance);
    chains
        .iter()
        .map(|(family, chain)| {
            let Some((axis, at)) = plane_of_points(chain, tolerance) else {
                return (Vec::new(), Vec::new());
            };
            let family = *family;
            let (first, last) = (chain[0].1, chain[chain.len() - 1].1);
            // The nearest knuckle beyond each end, along the family's axis, in the plane.
            let mut before: Option<(usize, DVec3)> = None;
            let mut after: Option<(usize, DVec3)> = None;
            for (i, ks) in knuckles.iter().enumerate() {
                let in_plane_itself =
                    planes[i].is_some_and(|(a, v)| a == axis && (v - at).abs() <= tolerance);
                if in_plane_itself || chain.iter().any(|q| q.0 == i) {
                    continue;
                }
                for &k in ks {
                    if (k[axis] - at).abs() > tolerance || on_a_chain(k) {
                        continue;
                    }
                    if k[family] < first[family] - tolerance {
                        if before.is_none_or(|b| k.distance(first) < b.1.distance(first)) {
                            before = Some((i, k));
                        }
                    } else if k[family] > last[family] + tolerance
                        && after.is_none_or(|b| k.distance(last) < b.1.distance(last))
                    {
                        after = Some((i, k));
                    }
                }
            }
            let head = before.map_or_else(Vec::new, |(i, k)| {
                let mut piece = vec![(i, k)];
                piece.extend(guided_piece(
                    curves,
                    planes,
                    (axis, at),
                    i,
                    k,
                    first,
                    tolerance,
                ));
                piece
            });
            let tail = after.map_or_else(Vec::new, |(i, k)| {
                let mut piece = guided_piece(curves, planes, (axis, at), i, k, last, tolerance);
                piece.reverse();
                piece.push((i, k));
                piece
            });
            (head, tail)
        })
        .collect()
}

/// A flat end outlined by a curve in an axis plane (the profile) between two of its
/// knuckles: its edge, a knuckle chain from one knuckle to the other, the straight line
/// across it from the edge's point farthest from the outline to the outline (the end, a face
/// of two sides, becomes two of three), and the line on from there to the guiding section.
pub(super) struct FlatEnd {
    /// The family axis (the end's plane is square to it) and the edge's chain.
    pub(super) edge: (usize, Chain),
    /// The line across the end: from the outline curve's point to the edge's.
    pub(super) across: [DVec3; 2],
    /// The outline curve (network index).
    pub(super) outline: usize,
    /// The guiding section (network index) and the straight line from the edge's point
    /// farthest from the outline to that section: it parts the band between the edge and the
    /// section (half a boss's circumference, too much turn for one face) in two.
    pub(super) along: Option<(usize, [DVec3; 2])>,
}

/// The flat ends that a curve lying in an axis plane (the profile) outlines between two of its
/// knuckles, where it runs in a plane square to the length: a shaft boss's end, whose edge
/// no section gives. Each edge runs from one knuckle to the other through the shape of the
/// nearest parallel section ([`guided_piece`]); none where no section guides it, where a
/// knuckle is on a chain already, where a section crosses the end with a knuckle (two or more
/// make a chain, the edge, carried on to the knuckles by [`carried_on_in_plane`]), or where
/// another curve ends within the import's capture distance of one of the two knuckles. Only
/// ends square to the length (x) count.
pub(super) fn flat_ends(
    curves: &[NetworkCurve],
    planes: &[Option<(usize, f64)>],
    knuckles: &[Vec<DVec3>],
    chains: &[(usize, Chain)],
    tolerance: f64,
) -> Vec<FlatEnd> {
    let on_a_chain = |p: DVec3| on_a_chain(chains, p, tolerance);
    let capture = SECTION_CAPTURE_FACTOR * tolerance;
    let curve_ends: Vec<[DVec3; 2]> = curves
        .iter()
        .map(|c| {
            let (lo, hi) = c.curve.domain();
            [c.curve.point(lo), c.curve.point(hi)]
        })
        .collect();
    let mut found = Vec::new();
    for (i, ks) in knuckles.iter().enumerate() {
        // An outline in a plane square to the length has no stretch in another such plane.
        if planes[i].is_none_or(|(own, _)| own == LENGTH_AXIS) {
            continue;
        }
        let dec = curves[i].curve.bezier_decomposition();
        let mut at: Vec<(f64, DVec3)> = ks
            .iter()
            .filter(|&&k| !on_a_chain(k))
            .filter_map(|&k| dec.nearest(k, 1e-3 * tolerance).ok().map(|n| (n.t, k)))
            .collect();
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        // A corner where a section ends already has that section's edges: an added edge would
        // leave it beside them (KVLCC2's lowest waterline ends at its boss's lower corner).
        let ends_at = |p: DVec3| {
            curve_ends
                .iter()
                .enumerate()
                .any(|(j, e)| j != i && e.iter().any(|q| q.distance(p) <= capture))
        };
        for w in at.windows(2) {
            if ends_at(w[0].1) || ends_at(w[1].1) {
                continue;
            }
            found.extend(flat_end(
                curves,
                planes,
                knuckles,
                (i, &dec),
                [w[0], w[1]],
                tolerance,
            ));
        }
    }
    found
}

/// The flat end of outline curve `outline.0` (its Bézier pieces `outline.1`) between its
/// knuckles `ends` (parameter and point), as [`flat_ends`] finds it: `None` where the stretch
/// between them leaves the plane square to the length, a knuckle of another curve lies on the
/// end, or no station guides its edge.
fn flat_end(
    curves: &[NetworkCurve],
    planes: &[Option<(usize, f64)>],
    knuckles: &[Vec<DVec3>],
    outline: (usize, &BezierDecomposition),
    ends: [(f64, DVec3); 2],
    tolerance: f64,
) -> Option<FlatEnd> {
    let (i, dec) = outline;
    let [(ta, a), (tb, b)] = ends;
    let axis = LENGTH_AXIS;
    let curve = &curves[i].curve;
    let c = 0.5 * (a[axis] + b[axis]);
    let flat = (0..=16).all(|j| {
        let p = curve.point(ta + (tb - ta) * j as f64 / 16.0);
        (p[axis] - c).abs() <= tolerance
    });
    if !flat {
        return None;
    }
    let chord = (b - a).normalize_or_zero();
    let span = (b - a).length();
    let crosses = |p: DVec3| {
        let along = (p - a).dot(chord);
        (p[axis] - c).abs() <= tolerance && along > tolerance && along < span - tolerance
    };
    // A section crossing the end has its knuckle on the edge: with two or more, their chine is
    // the edge (carried on to the corners); with one, an edge shaped by the station would pass
    // beside it. Either way none is added.
    if knuckles
        .iter()
        .enumerate()
        .any(|(j, ks)| j != i && ks.iter().any(|&k| crosses(k)))
    {
        return None;
    }
    let piece = guided_piece(curves, planes, (axis, c), i, a, b, tolerance);
    let &(g, _) = piece.first()?;
    // The edge's point farthest from the outline's chord.
    let off = |p: DVec3| (p - a) - chord * (p - a).dot(chord);
    let m = piece
        .iter()
        .map(|q| q.1)
        .max_by(|p, q| off(*p).length().total_cmp(&off(*q).length()))?;
    // Its foot on the outline's chord, where the outline runs straight there (a boss's end),
    // else the outline's nearest point: both put the line across the end square to the
    // outline.
    let on_chord = m - off(m);
    let nearest = dec.nearest(on_chord, 1e-3 * tolerance).ok()?;
    let foot = if nearest.distance <= tolerance {
        on_chord
    } else {
        nearest.point
    };
    let mut q = m;
    q[axis] = planes[g].map_or(c, |(_, w)| w);
    let along = curves[g]
        .curve
        .nearest(q, 1e-3 * tolerance)
        .ok()
        .map(|n| (g, [m, n.point]));
    let mut chain = vec![(i, a)];
    chain.extend(piece);
    chain.push((i, b));
    Some(FlatEnd {
        edge: (axis, chain),
        across: [foot, m],
        outline: i,
        along,
    })
}

/// Whether `p` is within `tolerance` of a point of one of `chains`.
fn on_a_chain(chains: &[(usize, Chain)], p: DVec3, tolerance: f64) -> bool {
    chains
        .iter()
        .any(|(_, ch)| ch.iter().any(|q| q.1.distance(p) <= tolerance))
}

/// The axis plane every point of a chain of two or more lies in, within `tolerance`.
fn plane_of_points(chain: &Chain, tolerance: f64) -> Option<(usize, f64)> {
    if chain.len() < 2 {
        return None;
    }
    axis_planes(chain.iter().map(|q| q.1), tolerance)
        .into_iter()
        .enumerate()
        .find_map(|(axis, v)| v.map(|v| (axis, v)))
}

/// The points strictly between knuckle `k` (of curve `own`) and chain end `end`, in order
/// from `k` to `end`, shaped by the nearest section parallel to `plane` that passes near both
/// (module doc); empty when no section does.
fn guided_piece(
    curves: &[NetworkCurve],
    planes: &[Option<(usize, f64)>],
    plane: (usize, f64),
    own: usize,
    k: DVec3,
    end: DVec3,
    tolerance: f64,
) -> Chain {
    let (axis, at) = plane;
    let gap = k.distance(end);
    let mut guides: Vec<(f64, usize)> = planes
        .iter()
        .enumerate()
        .filter_map(|(g, p)| {
            p.filter(|&(a, w)| a == axis && (w - at).abs() > tolerance && g != own)
                .map(|(_, w)| ((w - at).abs(), g))
        })
        .filter(|&(d, _)| d <= gap)
        .collect();
    guides.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (d, g) in guides {
        let curve = &curves[g].curve;
        let dec = curve.bezier_decomposition();
        let into = |p: DVec3| {
            let mut q = p;
            q[axis] = planes[g].map_or(at, |(_, w)| w);
            dec.nearest(q, 1e-3 * tolerance)
        };
        let (Ok(a), Ok(b)) = (into(k), into(end)) else {
            continue;
        };
        let reach = GUIDE_REACH * d + 0.25 * gap;
        if a.distance > reach || b.distance > reach || a.t == b.t {
            continue;
        }
        let pts: Vec<DVec3> = (0..=GUIDE_SAMPLES + 1)
            .map(|j| curve.point(a.t + (b.t - a.t) * j as f64 / (GUIDE_SAMPLES + 1) as f64))
            .collect();
        let mut run = vec![0.0];
        for w in pts.windows(2) {
            run.push(run[run.len() - 1] + w[0].distance(w[1]));
        }
        let total = run[run.len() - 1];
        if total <= tolerance {
            continue;
        }
        let (shift_k, shift_end) = (k - a.point, end - b.point);
        return pts[1..=GUIDE_SAMPLES]
            .iter()
            .zip(&run[1..=GUIDE_SAMPLES])
            .map(|(&p, &s)| {
                let f = s / total;
                let mut q = p + shift_k * (1.0 - f) + shift_end * f;
                q[axis] = at;
                (g, q)
            })
            .collect();
    }
    Vec::new()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;
    use crate::network::{Network, Role};
    use crate::tolerance::Tolerance;
    use crate::wireframe::chines_from_knuckles;
    use crate::wireframe::test_curves::poly;

    /// A transom at x = 0: three waterlines (z 1.0, 1.5, 2.0) run across it and turn forward at
    /// their knuckles; the profile comes down the transom and turns forward onto the counter at
    /// (0, 0, 0.5); with `station`, a station at x = 0.5 with a flat bottom that turns up.
    fn stern(station: bool) -> (Network, Vec<Vec<DVec3>>) {
        let mut curves = Vec::new();
        let mut knuckles = Vec::new();
        for (z, y) in [(1.0, 1.8), (1.5, 2.0), (2.0, 2.1)] {
            curves.push(poly(
                &format!("wl{z}"),
                &[[0.0, 0.0, z], [0.0, y, z], [3.0, y + 0.2, z]],
            ));
            knuckles.push(vec![DVec3::new(0.0, y, z)]);
        }
        curves.push(poly(
            "profile",
            &[[0.0, 0.0, 2.0], [0.0, 0.0, 0.5], [3.0, 0.0, 0.3]],
        ));
        knuckles.push(vec![DVec3::new(0.0, 0.0, 0.5)]);
        if station {
            curves.push(poly(
                "station",
                &[
                    [0.5, 0.0, 0.45],
                    [0.5, 1.5, 0.5],
                    [0.5, 2.0, 0.95],
                    [0.5, 2.2, 2.0],
                ],
            ));
            knuckles.push(Vec::new());
        }
        (
            Network::try_new("stern", curves).expect("network"),
            knuckles,
        )
    }

    /// Dense samples of a curve.
    fn samples(c: &NurbsCurve) -> Vec<DVec3> {
        let (a, b) = c.domain();
        (0..=400)
            .map(|i| c.point(a + (b - a) * i as f64 / 400.0))
            .collect()
    }

    #[test]
    fn a_transom_edge_is_carried_down_to_the_profile_along_the_station() {
        let (net, knuckles) = stern(true);
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        assert_eq!(chines.len(), 1);
        let c = &chines[0];
        assert_eq!(c.name, "chine1 profile–wl2");
        for k in knuckles.iter().flatten() {
            let d = c.curve.nearest(*k, 1e-12).expect("nearest").distance;
            assert!(d < 1e-9, "through {k}: {d}");
        }
        let pts = samples(&c.curve);
        let off_plane = pts.iter().map(|p| p.x.abs()).fold(0.0, f64::max);
        assert!(off_plane < 1e-9, "in the transom plane: {off_plane}");
        // Half way across, the edge follows the station's flat bottom: not the chord from the
        // profile corner (0, 0, 0.5) to the lowest waterline's knuckle (0, 1.8, 1.0), at z 0.78
        // there, nor the spline through the knuckles alone, at z 0.66.
        let mid = pts
            .iter()
            .min_by(|a, b| (a.y - 0.9).abs().total_cmp(&(b.y - 0.9).abs()))
            .expect("samples");
        assert!(mid.z > 0.5 && mid.z < 0.62, "follows the station: {mid}");
    }

    /// A shaft boss ending flat at x = 0: the profile comes aft along its top, down its end
    /// (x = 0, z 1.5 to 0.5) and forward along its bottom; a station at x = 0.5 is its round
    /// section.
    fn boss(extra: Option<NetworkCurve>) -> (Network, Vec<Vec<DVec3>>) {
        let (a, b) = (DVec3::new(0.0, 0.0, 1.5), DVec3::new(0.0, 0.0, 0.5));
        let mut curves = vec![
            poly(
                "profile",
                &[[3.0, 0.0, 2.0], a.to_array(), b.to_array(), [3.0, 0.0, 0.0]],
            ),
            poly(
                "station",
                &[
                    [0.5, 0.0, 1.5],
                    [0.5, 0.35, 1.35],
                    [0.5, 0.5, 1.0],
                    [0.5, 0.35, 0.65],
                    [0.5, 0.0, 0.5],
                ],
            ),
        ];
        let mut knuckles = vec![vec![a, b], Vec::new()];
        if let Some(c) = extra {
            curves.push(c);
            knuckles.push(Vec::new());
        }
        (Network::try_new("boss", curves).expect("network"), knuckles)
    }

    #[test]
    fn a_boss_end_gets_its_edge_and_the_lines_that_part_it() {
        let (net, knuckles) = boss(None);
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        let names: Vec<&str> = chines.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "chine1 profile–profile",
                "flat end1 profile",
                "flat end1 station"
            ]
        );
        let edge = &chines[0];
        assert_eq!(edge.role, Role::Knuckle);
        for k in &knuckles[0] {
            assert!(edge.curve.nearest(*k, 1e-12).expect("nearest").distance < 1e-9);
        }
        let pts = samples(&edge.curve);
        assert!(pts.iter().all(|p| p.x.abs() < 1e-9), "in the end's plane");
        let widest = pts.iter().map(|p| p.y).fold(0.0, f64::max);
        assert!(
            (widest - 0.5).abs() < 0.05,
            "as wide as the station: {widest}"
        );
        // Across the end from the profile to the edge's widest point, then on to the station.
        let (across, along) = (&chines[1].curve, &chines[2].curve);
        let ends = |c: &NurbsCurve| {
            let (lo, hi) = c.domain();
            (c.point(lo), c.point(hi))
        };
        let (p0, m) = ends(across);
        let (m2, q) = ends(along);
        assert!(
            p0.x.abs() < 1e-9 && p0.y.abs() < 1e-9,
            "starts on the profile: {p0}"
        );
        assert!(
            m.distance(m2) < 1e-12 && (m.y - widest).abs() < 0.05,
            "meets the edge: {m}"
        );
        assert!(
            (q.x - 0.5).abs() < 1e-9 && (q.y - 0.5).abs() < 0.05,
            "ends on the station: {q}"
        );
    }

    /// `chines_from_knuckles` adds no curve to `net` with `knuckles`.
    fn assert_no_chines(net: &Network, knuckles: &[Vec<DVec3>]) {
        let chines = chines_from_knuckles(net, knuckles, Tolerance::DEFAULT).expect("chines");
        let names: Vec<&str> = chines.iter().map(|c| c.name.as_str()).collect();
        assert!(names.is_empty(), "{names:?}");
    }

    #[test]
    fn a_corner_where_a_section_ends_gets_no_flat_end() {
        let (net, knuckles) = boss(Some(poly("waterline", &[[0.0, 0.0, 0.5], [3.0, 1.0, 0.5]])));
        assert_no_chines(&net, &knuckles);
    }

    #[test]
    fn a_lone_waterline_across_the_end_or_a_flat_keel_gets_no_flat_end() {
        // One waterline crosses the boss's end: an edge shaped by the station would pass
        // beside its knuckle.
        let (net, mut knuckles) = boss(None);
        let mut curves = net.curves().to_vec();
        curves.push(poly(
            "wl",
            &[[0.0, 0.0, 0.8], [0.0, 0.45, 0.8], [3.0, 0.45, 0.8]],
        ));
        knuckles.push(vec![DVec3::new(0.0, 0.45, 0.8)]);
        let net = Network::try_new("boss with a waterline", curves).expect("network");
        assert_no_chines(&net, &knuckles);
        // A profile with a knuckle at each end of its flat keel, and a waterline above it: the
        // keel is no end (its plane is not square to the length).
        let profile = poly(
            "profile",
            &[
                [-1.0, 0.0, 1.0],
                [0.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [11.0, 0.0, 1.0],
            ],
        );
        let wl = poly("wl", &[[0.3, 0.0, 0.3], [5.0, 1.0, 0.3], [9.7, 0.0, 0.3]]);
        let net = Network::try_new("keel", vec![profile, wl]).expect("network");
        let knuckles = vec![vec![DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0)], Vec::new()];
        assert_no_chines(&net, &knuckles);
    }

    #[test]
    fn a_boss_end_crossed_by_waterlines_takes_their_chine_as_its_edge() {
        // Two waterlines cross the end to its edge and turn forward along the boss: their
        // knuckles make the chine, carried on to the profile's corners; no second edge.
        let (net, mut knuckles) = boss(None);
        let mut curves = net.curves().to_vec();
        for (z, w) in [(0.8, 0.45), (1.2, 0.45)] {
            curves.push(poly(
                &format!("wl{z}"),
                &[[0.0, 0.0, z], [0.0, w, z], [3.0, w, z]],
            ));
            knuckles.push(vec![DVec3::new(0.0, w, z)]);
        }
        let net = Network::try_new("boss with waterlines", curves).expect("network");
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        let names: Vec<&str> = chines.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["chine1 profile–profile"]);
        for k in [&knuckles[0][..], &knuckles[2], &knuckles[3]].concat() {
            let gap = chines[0].curve.nearest(k, 1e-12).expect("nearest").distance;
            assert!(gap < 1e-9, "through {k}: {gap}");
        }
    }

    #[test]
    fn without_a_station_the_edge_still_reaches_the_profile_and_off_plane_knuckles_stay() {
        let (net, knuckles) = stern(false);
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        assert_eq!(chines.len(), 1);
        let k = DVec3::new(0.0, 0.0, 0.5);
        assert!(chines[0].curve.nearest(k, 1e-12).expect("nearest").distance < 1e-9);
        // The profile's corner 1 cm out of the transom plane is no corner of the transom.
        let mut moved = knuckles.clone();
        moved[3] = vec![DVec3::new(0.01, 0.0, 0.5)];
        let chines = chines_from_knuckles(&net, &moved, Tolerance::DEFAULT).expect("chines");
        assert_eq!(chines[0].name, "chine1 wl1–wl2");
    }
}
