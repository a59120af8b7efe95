//! Section ends that run into a needle along another curve (the real-ships issue's "closed
//! regions"): a waterline whose plane the sheer crosses at a grazing angle runs beside the
//! sheer for metres before it meets it (KVLCC2's wl_z25.50 meets its deck edge at 1.8° and
//! 1.1°, 16 m and 6 m past its last station). The face between them is a needle whose
//! corner at the meeting is degenerate, and whose patch folds or breaks there, while the
//! waterline's last stretch says nothing about the surface that the other curve and the
//! stations do not (it lies within a few centimetres of the other curve per metre).
//!
//! Such an end is cut back to the curve's last node before it: the stretch is dropped from
//! the curve's points, and the curve is taken off the node where it ended. The end qualifies
//! when it meets the other curve at less than [`NEEDLE_DEGREES`] and its whole stretch from
//! that last node lies within `sin(NEEDLE_DEGREES)` of its length from the other curve — a
//! needle, not a curve that only turns onto the other at its very end (KVLCC2's st20 meets
//! the stem at 9°, but 3 m away from it at its last node). A stretch that lies on the other
//! curve (within the capture distance all along, or through a node with it) is no needle but
//! an overlap, which the topology names.

use glam::DVec3;

use super::data_nodes::NodedPoints;
use crate::curve::segment_distance;

/// The largest angle (degrees) at which a section end meeting another curve, and the stretch
/// before it, make a needle ([module doc](self)).
pub(crate) const NEEDLE_DEGREES: f64 = super::data_nodes::SHALLOWEST_MEETING_DEGREES;

/// `noded` with every section end that runs into a needle cut back to the curve's last node
/// before it ([module doc](self)); `capture` (m) is the distance within which two curves meet.
/// Curves with fewer than three points are left alone.
pub(crate) fn without_needle_ends(mut noded: NodedPoints, capture: f64) -> NodedPoints {
    let limit = NEEDLE_DEGREES.to_radians().sin();
    for i in 0..noded.points.len() {
        for at_start in [false, true] {
            let Some(cut) = needle_cut(&noded, i, at_start, limit, capture) else {
                continue;
            };
            let pts = &noded.points[i];
            let end = if at_start { pts[0] } else { pts[pts.len() - 1] };
            let (points, source) = (&mut noded.points[i], &mut noded.source[i]);
            if at_start {
                points.drain(..cut);
                source.drain(..cut);
            } else {
                points.truncate(cut + 1);
                source.truncate(cut + 1);
            }
            for node in noded.nodes.iter_mut().filter(|n| n.position == end) {
                node.curves.retain(|&c| c != i);
            }
            noded.nodes.retain(|n| n.curves.len() >= 2);
        }
    }
    noded
}

/// Where curve `i` is cut at its start (`at_start`) or end: the index of its last node before
/// that end, when the end runs into a needle along another curve through its end node.
fn needle_cut(
    noded: &NodedPoints,
    i: usize,
    at_start: bool,
    limit: f64,
    capture: f64,
) -> Option<usize> {
    let pts = &noded.points[i];
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let (end, before) = if at_start {
        (pts[0], pts[1])
    } else {
        (pts[n - 1], pts[n - 2])
    };
    let node = noded
        .nodes
        .iter()
        .find(|node| node.position == end && node.curves.contains(&i))?;
    // The curve this end meets at the smallest angle.
    let dir = (end - before).normalize_or_zero();
    let (other, sine) = node
        .curves
        .iter()
        .filter(|&&c| c != i)
        .filter_map(|&c| Some((c, sine_at(&noded.points[c], end, dir)?)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    if sine >= limit {
        return None;
    }
    // The last node along the curve before this end; none shared with the other curve.
    let node_at = |p: DVec3| {
        noded
            .nodes
            .iter()
            .find(|m| m.position == p && m.curves.contains(&i))
    };
    let cut = if at_start {
        (1..n - 1).find(|&k| node_at(pts[k]).is_some())?
    } else {
        (1..n - 1).rev().find(|&k| node_at(pts[k]).is_some())?
    };
    if node_at(pts[cut])?.curves.contains(&other) {
        return None;
    }
    let stretch = if at_start { &pts[..=cut] } else { &pts[cut..] };
    let length: f64 = stretch.windows(2).map(|w| w[0].distance(w[1])).sum();
    let width = stretch
        .iter()
        .map(|&p| distance_to_polyline(&noded.points[other], p))
        .fold(0.0, f64::max);
    (width > capture && width <= limit * length).then_some(cut)
}

/// The sine of the angle between `dir` and the polyline `pts` where it passes through `at`
/// (one of its points): the smaller over the segments on either side.
fn sine_at(pts: &[DVec3], at: DVec3, dir: DVec3) -> Option<f64> {
    let k = pts.iter().position(|&p| p == at)?;
    [k.checked_sub(1), (k + 1 < pts.len()).then_some(k + 1)]
        .into_iter()
        .flatten()
        .map(|j| dir.cross((pts[j] - at).normalize_or_zero()).length())
        .min_by(f64::total_cmp)
}

/// The distance from `p` to the polyline `pts`.
fn distance_to_polyline(pts: &[DVec3], p: DVec3) -> f64 {
    pts.windows(2)
        .map(|w| segment_distance(p, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use crate::tolerance::Tolerance;
    use crate::wireframe::nodes_from_data;

    use glam::DVec3;

    /// A sheer falling `drop` over 20 m from z 1 at x 0, a waterline z = 0.5 ending on it, and
    /// stations at x 4 and 8 from the keel (z 0) up to the sheer, all at y 1.
    fn sheer_and_waterline(drop: f64) -> Vec<Vec<DVec3>> {
        let sheer_z = |x: f64| 1.0 - drop * x / 20.0;
        let meet = 0.5 * 20.0 / drop;
        let sheer = (0..=20)
            .map(|k| DVec3::new(k as f64, 1.0, sheer_z(k as f64)))
            .collect();
        let waterline = (0..=10)
            .map(|k| DVec3::new(meet * k as f64 / 10.0, 1.0, 0.5))
            .collect();
        let station = |x: f64| {
            (0..=10)
                .map(|k| DVec3::new(x, 1.0, sheer_z(x) * k as f64 / 10.0))
                .collect()
        };
        vec![sheer, waterline, station(4.0), station(8.0)]
    }

    #[test]
    fn a_waterline_running_into_a_needle_along_the_sheer_ends_at_its_last_station() {
        // The sheer falls 1 m over 20 m (2.9°): the waterline meets it at x 10, 2 m past the
        // station at x 8, where it is 10 cm below it.
        let noded =
            nodes_from_data(&sheer_and_waterline(1.0), 1e-3, None, Tolerance::DEFAULT).expect("ok");
        let waterline = &noded.points[1];
        let last = *waterline.last().expect("points");
        assert!(last.distance(DVec3::new(8.0, 1.0, 0.5)) < 1e-9, "{last}");
        assert!(waterline.iter().all(|p| p.x <= 8.0 + 1e-9));
        assert_eq!(noded.source[1].len(), waterline.len());
        // Nothing else moved, and no node lists the waterline at the sheer any more.
        for node in &noded.nodes {
            assert!(node.curves.len() >= 2, "{node:?}");
            if node.curves.contains(&1) {
                assert!(node.position.x <= 8.0 + 1e-9, "{node:?}");
            }
        }
        assert!(noded.nodes.iter().any(|n| n.curves == vec![0, 3]));
        assert_eq!(noded.points[0].len(), 21, "the sheer keeps its points");
    }

    #[test]
    fn a_duplicate_waterline_is_an_overlap_not_a_needle() {
        // Two copies of the waterline meet at 0° all along: neither end is cut (the topology
        // names the duplicate).
        let mut pts = sheer_and_waterline(1.0);
        pts.push(pts[1].clone());
        let noded = nodes_from_data(&pts, 1e-3, None, Tolerance::DEFAULT).expect("ok");
        for c in [1, 4] {
            assert!(
                noded.points[c].last().expect("end").x > 9.9,
                "curve {c} keeps its end"
            );
        }
    }

    #[test]
    fn a_waterline_meeting_the_sheer_at_an_angle_keeps_its_end() {
        // The sheer falls 8 m over 20 m (22°): the waterline meets it at x 1.25, before any
        // station.
        let noded =
            nodes_from_data(&sheer_and_waterline(8.0), 1e-3, None, Tolerance::DEFAULT).expect("ok");
        assert_eq!(noded.points[1].len(), 11);
        // At 3° but with no station before its end, it has no node to end at: kept.
        let mut pts = sheer_and_waterline(1.0);
        pts.truncate(2);
        let noded = nodes_from_data(&pts, 1e-3, None, Tolerance::DEFAULT).expect("ok");
        assert!(noded.points[1].last().expect("end").x > 9.9);
    }
}
