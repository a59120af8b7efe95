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

use glam::DVec3;

use super::data_nodes::axis_planes;
use crate::network::NetworkCurve;

/// A chain of knuckle points: the curve index and the point, in order along the axis of the
/// family whose sections gave them.
pub(super) type Chain = Vec<(usize, DVec3)>;

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
    let on_a_chain = |p: DVec3| {
        chains
            .iter()
            .any(|(_, ch)| ch.iter().any(|q| q.1.distance(p) <= tolerance))
    };
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
    use crate::network::Network;
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
