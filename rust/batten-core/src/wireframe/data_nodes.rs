//! Nodes from the data (the real-ships issue's "nodes from the data"; H-rep paper §3.2.3, Ye &
//! Nowacki 1995): where the point curves of a set of sections or an offsets table cross or end
//! on each other, found on the polylines themselves before any curve is fitted, clustered, and
//! given one point that every curve through the node then takes as one of its data points. So
//! curves that meet in the data are fitted through one common point, and meet after the fit
//! within its tolerance, even where one of them is sampled so sparsely that its fit strays
//! between the samples by more than that (KVLCC2's waterlines: 4 m apart round the forward
//! bilge, the fit 9 cm inside the chord where the station says the surface is).
//!
//! Between two samples a polyline is only as good as its chord: an arc turning by θ over a
//! chord of length L lies up to its sagitta `L·θ/8` off it (`s = L²κ/8`, κ = θ/L), the most at
//! mid-chord, `4u(1−u)` of that at the fraction u along it, nothing at the samples. Two
//! polylines meet where they come within twice the data's tolerance plus those sagittas; the
//! node is the mean of their closest points weighted by the inverse square of each one's
//! uncertainty (tolerance plus sagitta there), so the better-sampled curve places it. Turns
//! sharper than the corner angle are knuckles of the data, not curvature, and give no sagitta.
//! A curve that lies in an axis plane (a station, waterline or buttock: its points within the
//! tolerance of it) keeps its nodes in that plane, so a node of two plane sections is on the
//! line where their planes cross. Where two curves meet at a shallow angle θ, the place along
//! them is uncertain by the capture over sin θ, and another node on one of them within that is
//! the same node (a station at the FP that runs up the stem beside the waterline's end there).

use glam::DVec3;
use rayon::prelude::*;

use crate::curve::Aabb;
use crate::error::Error;
use crate::tolerance::Tolerance;
use crate::union_find::UnionFind;

/// A node found in the data: where two or more point curves meet.
#[derive(Clone, Debug, PartialEq)]
pub struct DataNode {
    /// The node's point, which every curve in `curves` now has among its points.
    pub position: DVec3,
    /// The curves (indices into the input) that meet there, ascending.
    pub curves: Vec<usize>,
    /// The largest distance (m) between two of those polylines there, before the node.
    pub gap: f64,
}

/// The input's point curves with their nodes among their points, and the nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct NodedPoints {
    /// Per input curve, its points in order with the points of its nodes: inserted where a node
    /// falls between two samples, in place of a sample (or an end) it falls on.
    pub points: Vec<Vec<DVec3>>,
    /// Per input curve and point of `points`: the index of the input point it is or replaces,
    /// `None` for a node inserted between samples.
    pub source: Vec<Vec<Option<usize>>>,
    /// The nodes, in the order of their first curve and position along it.
    pub nodes: Vec<DataNode>,
}

/// The point curves `points` with the nodes where they meet (module doc) among their points.
/// `tolerance` (m) is the data's: how far a sample may be from the true curve; `corner_angle`
/// (radians) the turn above which a polyline has a knuckle (None: every turn is curvature);
/// a node within `model_tolerance` of a sample takes the sample's place. A curve with fewer
/// than two points or a non-finite point takes no part (its fit names it).
///
/// Errors: a tolerance that is not positive and finite ([`Error::Tolerance`]).
pub(super) fn nodes_from_data(
    points: &[Vec<DVec3>],
    tolerance: f64,
    corner_angle: Option<f64>,
    model_tolerance: Tolerance,
) -> Result<NodedPoints, Error> {
    let tol = Tolerance::try_new(tolerance)?.get();
    let polylines: Vec<Option<Polyline>> = points
        .iter()
        .map(|p| Polyline::of(p, tol, corner_angle))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..points.len())
        .flat_map(|a| (a + 1..points.len()).map(move |b| (a, b)))
        .collect();
    let meetings: Vec<Meeting> = pairs
        .par_iter()
        .flat_map_iter(|&(a, b)| match (&polylines[a], &polylines[b]) {
            (Some(pa), Some(pb)) => meetings(a, pa, b, pb, tol),
            _ => Vec::new(),
        })
        .collect();
    let planes: Vec<[Option<f64>; 3]> = polylines
        .iter()
        .map(|p| p.as_ref().map_or([None; 3], |p| p.planes))
        .collect();
    let nodes = cluster(&meetings, 2.0 * tol, &planes);
    Ok(insert_nodes(points, &nodes, model_tolerance.get()))
}

/// A polyline with the sagitta of each of its segments and its bounding box grown by the
/// largest distance at which it can meet another.
struct Polyline<'a> {
    points: &'a [DVec3],
    sagitta: Vec<f64>,
    reach: Aabb,
    planes: [Option<f64>; 3],
}

/// Per axis, the value of the axis plane that all `points` lie in within `tolerance` (their
/// range along the axis at most it), at the middle of their range; `None` where they do not.
pub(crate) fn axis_planes(
    points: impl IntoIterator<Item = DVec3>,
    tolerance: f64,
) -> [Option<f64>; 3] {
    let (lo, hi) = points
        .into_iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    std::array::from_fn(|axis| {
        (hi[axis] - lo[axis] <= tolerance).then(|| 0.5 * (lo[axis] + hi[axis]))
    })
}

impl<'a> Polyline<'a> {
    /// `None` for fewer than two points or a non-finite one.
    fn of(points: &'a [DVec3], tol: f64, corner_angle: Option<f64>) -> Option<Polyline<'a>> {
        if points.len() < 2 || points.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let n = points.len();
        // Turning at each point (0 at the ends and at knuckles).
        let mut turn = vec![0.0; n];
        for v in 1..n - 1 {
            let (d0, d1) = (points[v] - points[v - 1], points[v + 1] - points[v]);
            if d0.length_squared() > 0.0 && d1.length_squared() > 0.0 {
                let angle = d0.angle_between(d1);
                turn[v] = if corner_angle.is_some_and(|c| angle > c) {
                    0.0
                } else {
                    angle
                };
            }
        }
        let sagitta: Vec<f64> = (0..n - 1)
            .map(|i| points[i].distance(points[i + 1]) * turn[i].max(turn[i + 1]) / SAGITTA_DIVISOR)
            .collect();
        let lo = points.iter().copied().fold(DVec3::INFINITY, DVec3::min);
        let hi = points.iter().copied().fold(DVec3::NEG_INFINITY, DVec3::max);
        let grow = DVec3::splat(tol + sagitta.iter().copied().fold(0.0, f64::max));
        Some(Polyline {
            points,
            sagitta,
            reach: Aabb {
                min: lo - grow,
                max: hi + grow,
            },
            planes: axis_planes(points.iter().copied(), tol),
        })
    }

    /// How far the true curve may be from the chord at the fraction `u` along segment `i`:
    /// the data's tolerance plus the sagitta's share there.
    fn uncertainty(&self, i: usize, u: f64, tol: f64) -> f64 {
        tol + self.sagitta[i] * 4.0 * u * (1.0 - u)
    }
}

/// The sagitta of a circular arc turning by θ over a chord of length L is L·θ/8 (to first
/// order in θ).
const SAGITTA_DIVISOR: f64 = 8.0;

/// Where two curves meet: each curve's index and parameter along its polyline (segment index
/// plus the fraction along it), the node point and its weight, and the gap.
#[derive(Clone, Copy, Debug)]
struct Meeting {
    at: [(usize, f64); 2],
    position: DVec3,
    weight: f64,
    gap: f64,
    /// |sin| of the angle between the two polylines' segments there (1 where one is a point).
    sin_angle: f64,
}

/// The meetings of polylines `pa` (curve `a`) and `pb` (curve `b`): the local minima of the
/// distance between their segments within the reach of both (module doc).
fn meetings(a: usize, pa: &Polyline<'_>, b: usize, pb: &Polyline<'_>, tol: f64) -> Vec<Meeting> {
    if !overlap(&pa.reach, &pb.reach) {
        return Vec::new();
    }
    let (na, nb) = (pa.sagitta.len(), pb.sagitta.len());
    let mut dist = vec![f64::INFINITY; na * nb];
    let mut closest = vec![(0.0, 0.0); na * nb];
    for i in 0..na {
        let (a0, a1) = (pa.points[i], pa.points[i + 1]);
        let reach = 2.0 * tol + pa.sagitta[i];
        let (alo, ahi) = (a0.min(a1), a0.max(a1));
        for j in 0..nb {
            let (b0, b1) = (pb.points[j], pb.points[j + 1]);
            let grow = DVec3::splat(reach + pb.sagitta[j]);
            if (alo - grow).cmpgt(b0.max(b1)).any() || (ahi + grow).cmplt(b0.min(b1)).any() {
                continue;
            }
            let (s, t) = segment_closest(a0, a1, b0, b1);
            dist[i * nb + j] = a0.lerp(a1, s).distance(b0.lerp(b1, t));
            closest[i * nb + j] = (s, t);
        }
    }
    let mut out = Vec::new();
    for i in 0..na {
        for j in 0..nb {
            let d = dist[i * nb + j];
            if !d.is_finite() || !local_minimum(&dist, na, nb, i, j) {
                continue;
            }
            let (s, t) = closest[i * nb + j];
            let (s, t, d) = at_end(pa, pb, i, j, (s, t, d), tol);
            let (t, s, d) = at_end(pb, pa, j, i, (t, s, d), tol);
            let (sa, sb) = (pa.uncertainty(i, s, tol), pb.uncertainty(j, t, tol));
            if d > sa + sb {
                continue;
            }
            let (wa, wb) = (1.0 / (sa * sa), 1.0 / (sb * sb));
            let p = pa.points[i].lerp(pa.points[i + 1], s);
            let q = pb.points[j].lerp(pb.points[j + 1], t);
            let (da, db) = (
                pa.points[i + 1] - pa.points[i],
                pb.points[j + 1] - pb.points[j],
            );
            let sin_angle = match (da.try_normalize(), db.try_normalize()) {
                (Some(u), Some(v)) => u.cross(v).length().min(1.0),
                _ => 1.0,
            };
            out.push(Meeting {
                at: [(a, i as f64 + s), (b, j as f64 + t)],
                position: in_planes((p * wa + q * wb) / (wa + wb), pa, pb),
                weight: wa + wb,
                gap: d,
                sin_angle,
            });
        }
    }
    out
}

/// A meeting `(s, t, d)` of segment `i` of `pa` and segment `j` of `pb` moved to `pa`'s end
/// when segment `i` is its first or last and that end lies within reach of segment `j`: a
/// curve that ends on another meets it at its end (its closest point may lie a little along
/// it, where the other's chord passes nearer than the true curve does).
fn at_end(
    pa: &Polyline<'_>,
    pb: &Polyline<'_>,
    i: usize,
    j: usize,
    (s, t, d): (f64, f64, f64),
    tol: f64,
) -> (f64, f64, f64) {
    let last = pa.sagitta.len() - 1;
    // On a one-segment polyline, the nearer end.
    let end = if i == 0 && (last > 0 || s < 0.5) {
        0.0
    } else if i == last {
        1.0
    } else {
        return (s, t, d);
    };
    if end == s {
        return (s, t, d);
    }
    let p = pa.points[i].lerp(pa.points[i + 1], end);
    let (b0, b1) = (pb.points[j], pb.points[j + 1]);
    let (_, u) = segment_closest(p, p, b0, b1);
    let gap = p.distance(b0.lerp(b1, u));
    if gap <= pa.uncertainty(i, end, tol) + pb.uncertainty(j, u, tol) {
        (end, u, gap)
    } else {
        (s, t, d)
    }
}

/// `p` moved into the axis planes of `pa` and `pb` (to their mean where both lie in planes
/// square to one axis: two parts of one section).
fn in_planes(mut p: DVec3, pa: &Polyline<'_>, pb: &Polyline<'_>) -> DVec3 {
    for axis in 0..3 {
        p[axis] = match (pa.planes[axis], pb.planes[axis]) {
            (Some(u), Some(v)) => 0.5 * (u + v),
            (Some(u), None) | (None, Some(u)) => u,
            (None, None) => p[axis],
        };
    }
    p
}

/// Whether the boxes overlap.
fn overlap(a: &Aabb, b: &Aabb) -> bool {
    a.min.cmple(b.max).all() && b.min.cmple(a.max).all()
}

/// Whether cell (i, j) of the `na` × `nb` grid `dist` is a local minimum among its eight
/// neighbours: no greater than those after it, less than those before it (row-major), so a
/// minimum shared by neighbouring cells (two segments meeting at the closest sample) counts
/// once.
fn local_minimum(dist: &[f64], na: usize, nb: usize, i: usize, j: usize) -> bool {
    let d = dist[i * nb + j];
    for di in -1i64..=1 {
        for dj in -1i64..=1 {
            let (k, l) = (i as i64 + di, j as i64 + dj);
            if (di, dj) == (0, 0) || k < 0 || l < 0 || k >= na as i64 || l >= nb as i64 {
                continue;
            }
            let e = dist[k as usize * nb + l as usize];
            let before = (di, dj) < (0, 0);
            if e < d || (before && e == d) {
                return false;
            }
        }
    }
    true
}

/// The fractions (s, t) along segments `a0 a1` and `b0 b1` of their closest points (Ericson,
/// *Real-Time Collision Detection* §5.1.9, clamped to both segments; a point-like segment has
/// fraction 0).
fn segment_closest(a0: DVec3, a1: DVec3, b0: DVec3, b1: DVec3) -> (f64, f64) {
    let (d1, d2, r) = (a1 - a0, b1 - b0, a0 - b0);
    let (aa, ee, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    if aa == 0.0 && ee == 0.0 {
        return (0.0, 0.0);
    }
    if aa == 0.0 {
        return (0.0, (f / ee).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if ee == 0.0 {
        return ((-c / aa).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = aa * ee - b * b;
    let mut s = if denom > 0.0 {
        ((b * f - c * ee) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / ee;
    if t < 0.0 {
        t = 0.0;
        s = (-c / aa).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / aa).clamp(0.0, 1.0);
    }
    (s, t)
}

/// The shallowest meeting (degrees) whose place along the curves is taken as uncertain by
/// `capture / sin θ`: shallower ones reach no further. It is the needles' angle (`needles`):
/// an end that meets a curve more shallowly and runs beside it is cut back. Both are the
/// patches' cusp angle: curves meeting more shallowly span no tangent plane a patch can take.
pub(crate) const SHALLOWEST_MEETING_DEGREES: f64 = crate::patch::CUSP_DEGREES;

/// A node being gathered: its curves with their parameters, its point and weight.
struct Gathered {
    at: Vec<(usize, f64)>,
    node: DataNode,
}

/// The meetings closer than `capture` to each other are one node (union–find), at their
/// weighted mean; a curve meeting it more than once takes it at the mean of its parameters.
///
/// Where two curves meet at a shallow angle θ, where along each other they meet is known only
/// to `capture / sin θ` (a curve `capture` off sideways meets `capture / sin θ` further on).
/// Two meetings on one curve within that of each other are one node too, placed in the axis
/// planes of all its curves: KVLCC2's station 20 ends on the stem at 9°, 2.35 cm below where
/// the waterline at 20.8 m ends on it, and the face between got a 2.35 cm side and a 3.5°
/// corner, with an 11.7° crease along the station.
fn cluster(meetings: &[Meeting], capture: f64, planes: &[[Option<f64>; 3]]) -> Vec<Gathered> {
    let shallowest = SHALLOWEST_MEETING_DEGREES.to_radians().sin();
    let slide: Vec<f64> = meetings
        .iter()
        .map(|m| capture / m.sin_angle.max(shallowest))
        .collect();
    let reach = slide.iter().copied().fold(capture, f64::max);
    let mut sets = UnionFind::new(meetings.len());
    let mut slid = vec![false; meetings.len()];
    let mut order: Vec<usize> = (0..meetings.len()).collect();
    order.sort_by(|&i, &j| meetings[i].position.x.total_cmp(&meetings[j].position.x));
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if meetings[j].position.x - meetings[i].position.x > reach {
                break;
            }
            let (a, b) = (&meetings[i], &meetings[j]);
            let d = a.position.distance(b.position);
            if d <= capture {
                sets.union(i, j);
            } else if d <= slide[i].max(slide[j])
                && a.at.iter().any(|p| b.at.iter().any(|q| p.0 == q.0))
            {
                sets.union(i, j);
                slid[i] = true;
                slid[j] = true;
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); meetings.len()];
    for i in 0..meetings.len() {
        groups[sets.find(i)].push(i);
    }
    groups
        .into_iter()
        .filter(|g| !g.is_empty())
        .map(|g| {
            let weight: f64 = g.iter().map(|&i| meetings[i].weight).sum();
            let mut position = g
                .iter()
                .map(|&i| meetings[i].position * meetings[i].weight)
                .sum::<DVec3>()
                / weight;
            if g.iter().any(|&i| slid[i]) {
                for axis in 0..3 {
                    let on: Vec<f64> = g
                        .iter()
                        .flat_map(|&i| meetings[i].at.iter().map(|a| a.0))
                        .filter_map(|c| planes[c][axis])
                        .collect();
                    if !on.is_empty() {
                        position[axis] = on.iter().sum::<f64>() / on.len() as f64;
                    }
                }
            }
            let mut at: Vec<(usize, f64, usize)> = Vec::new();
            for &(c, u) in g.iter().flat_map(|&i| &meetings[i].at) {
                match at.iter_mut().find(|e| e.0 == c) {
                    Some(e) => {
                        e.1 += u;
                        e.2 += 1;
                    }
                    None => at.push((c, u, 1)),
                }
            }
            at.sort_by_key(|e| e.0);
            let at: Vec<(usize, f64)> = at.into_iter().map(|(c, u, n)| (c, u / n as f64)).collect();
            Gathered {
                node: DataNode {
                    position,
                    curves: at.iter().map(|e| e.0).collect(),
                    gap: g.iter().map(|&i| meetings[i].gap).fold(0.0, f64::max),
                },
                at,
            }
        })
        .collect()
}

/// Every curve with its nodes among its points: a node at an end replaces it, a node within
/// `same` of a sample replaces the sample, any other is inserted at its place along the curve.
fn insert_nodes(points: &[Vec<DVec3>], nodes: &[Gathered], same: f64) -> NodedPoints {
    let mut on_curve: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); points.len()];
    for g in nodes {
        for &(c, u) in &g.at {
            on_curve[c].push((u, g.node.position));
        }
    }
    let mut out = NodedPoints {
        points: Vec::with_capacity(points.len()),
        source: Vec::with_capacity(points.len()),
        nodes: Vec::new(),
    };
    for (pts, mut at) in points.iter().zip(on_curve) {
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged: Vec<(DVec3, Option<usize>)> =
            pts.iter().enumerate().map(|(i, &p)| (p, Some(i))).collect();
        let last = pts.len().saturating_sub(1);
        // Inserted nodes go after the samples before them: walk from the end so earlier
        // indices stay valid.
        for &(u, q) in at.iter().rev() {
            let i = (u.floor() as usize).min(last);
            let replace = if u <= 0.0 {
                Some(0)
            } else if u >= last as f64 {
                Some(last)
            } else if pts[i].distance(q) <= same {
                Some(i)
            } else if pts[i + 1].distance(q) <= same {
                Some(i + 1)
            } else {
                None
            };
            match replace {
                Some(k) => merged[k].0 = q,
                None => merged.insert(i + 1, (q, None)),
            }
        }
        out.points.push(merged.iter().map(|m| m.0).collect());
        out.source.push(merged.iter().map(|m| m.1).collect());
    }
    let mut nodes: Vec<&Gathered> = nodes.iter().collect();
    nodes.sort_by(|a, b| {
        a.at[0]
            .0
            .cmp(&b.at[0].0)
            .then(a.at[0].1.total_cmp(&b.at[0].1))
    });
    out.nodes = nodes.into_iter().map(|g| g.node.clone()).collect();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(x: f64, n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let t = std::f64::consts::FRAC_PI_2 * i as f64 / (n - 1) as f64;
                DVec3::new(x, t.sin(), 1.0 - t.cos())
            })
            .collect()
    }

    /// A waterline z = 0.5 of the quarter-circle sections, sampled sparsely along x.
    fn waterline(xs: &[f64]) -> Vec<DVec3> {
        let y = (1.0 - 0.5f64 * 0.5).sqrt();
        xs.iter().map(|&x| DVec3::new(x, y, 0.5)).collect()
    }

    #[test]
    fn crossing_sections_share_one_node_point() {
        // Station x = 1 (8 samples, every 12.9°: 0.5 m high falls between them) and a waterline
        // sampled at x = 0 and 2 only.
        let pts = vec![arc(1.0, 8), waterline(&[0.0, 2.0])];
        let noded = nodes_from_data(&pts, 1e-3, Some(1.0), Tolerance::DEFAULT).expect("nodes");
        assert_eq!(noded.nodes.len(), 1, "{:?}", noded.nodes);
        let node = &noded.nodes[0];
        assert_eq!(node.curves, vec![0, 1]);
        for (c, (points, source)) in noded.points.iter().zip(&noded.source).enumerate() {
            assert!(points.contains(&node.position), "curve {c} has the node");
            assert_eq!(points.len(), pts[c].len() + 1, "inserted in {c}");
            assert_eq!(source.iter().filter(|s| s.is_none()).count(), 1);
        }
        // The true crossing is (1, √0.75, 0.5): the chord of the station misses it by its
        // sagitta (about 4 mm); the waterline is exact there.
        let truth = DVec3::new(1.0, 0.75f64.sqrt(), 0.5);
        assert!(node.position.distance(truth) < 1e-3, "{}", node.position);
    }

    #[test]
    fn an_end_on_a_sparse_curve_is_its_node_and_far_curves_have_none() {
        // A section ending at (1, 0, 0) on a keel line sampled at x = 0 and 3 with a bend at
        // x = 2 (so its chord there is uncertain): the section's end is the node.
        let keel = vec![
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.05),
            DVec3::new(3.0, 0.0, 0.5),
        ];
        let section = vec![DVec3::new(1.0, 0.0, 0.02), DVec3::new(1.0, 1.0, 1.0)];
        let apart = vec![DVec3::new(10.0, 0.0, 0.0), DVec3::new(10.0, 1.0, 1.0)];
        let pts = vec![keel, section.clone(), apart];
        let noded = nodes_from_data(&pts, 1e-3, Some(1.0), Tolerance::DEFAULT).expect("nodes");
        assert_eq!(noded.nodes.len(), 1, "{:?}", noded.nodes);
        assert_eq!(noded.nodes[0].curves, vec![0, 1]);
        assert_eq!(noded.points[2], pts[2], "the far section is unchanged");
        // The end (exact) places the node, and the end stays the section's end.
        assert!(
            noded.nodes[0].position.distance(section[0]) < 1e-3,
            "{:?}",
            noded.nodes
        );
        assert_eq!(noded.points[1][0], noded.nodes[0].position);
        assert_eq!(noded.source[1][0], Some(0));
    }

    /// A vertical stem (x = 0, y = 0), a waterline z = 2 ending on it square, and a station
    /// x = 0 whose last segment runs up to the stem at `end_z` along `(0, −run, 0.475)`.
    fn stem_meetings(end_z: f64, run: f64) -> Vec<Vec<DVec3>> {
        let stem = (0..=6)
            .map(|i| DVec3::new(0.0, 0.0, 0.5 * i as f64))
            .collect();
        let waterline = vec![DVec3::new(-1.0, 1.0, 2.0), DVec3::new(0.0, 0.0, 2.0)];
        let station = vec![
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, run, end_z - 0.475),
            DVec3::new(0.0, 0.0, end_z),
        ];
        vec![stem, waterline, station]
    }

    #[test]
    fn a_shallow_meeting_beside_another_on_one_curve_is_one_node() {
        // The station meets the stem at 9° (run 0.075 over 0.475), 2 cm below the waterline's
        // end: with a capture of 4 mm, where along the stem it meets is known only to
        // 4 mm / sin 9° = 2.6 cm, so the two ends are one node, in all three curves' planes.
        let noded =
            nodes_from_data(&stem_meetings(1.98, 0.075), 2e-3, None, Tolerance::DEFAULT).unwrap();
        assert_eq!(noded.nodes.len(), 1, "{:?}", noded.nodes);
        assert_eq!(noded.nodes[0].curves, vec![0, 1, 2]);
        assert_eq!(noded.nodes[0].position, DVec3::new(0.0, 0.0, 2.0));
        assert_eq!(
            noded.points[2][2],
            DVec3::new(0.0, 0.0, 2.0),
            "the station ends there"
        );
        // Meeting the stem at 45° instead, it is placed to within 4 mm / sin 45° = 5.7 mm: two
        // nodes 2 cm apart.
        let noded =
            nodes_from_data(&stem_meetings(1.98, 0.475), 2e-3, None, Tolerance::DEFAULT).unwrap();
        assert_eq!(noded.nodes.len(), 2, "{:?}", noded.nodes);
        // And at 9° but 3 cm apart, beyond the 2.6 cm.
        let noded =
            nodes_from_data(&stem_meetings(1.97, 0.075), 2e-3, None, Tolerance::DEFAULT).unwrap();
        assert_eq!(noded.nodes.len(), 2, "{:?}", noded.nodes);
    }

    #[test]
    fn bad_tolerance_is_an_error_and_bad_curves_take_no_part() {
        let pts = vec![arc(1.0, 7), waterline(&[0.0, 2.0])];
        assert!(matches!(
            nodes_from_data(&pts, 0.0, None, Tolerance::DEFAULT),
            Err(Error::Tolerance(_))
        ));
        let mut bad = pts.clone();
        bad[0][3].y = f64::NAN;
        bad.push(vec![DVec3::ZERO]);
        let noded = nodes_from_data(&bad, 1e-3, None, Tolerance::DEFAULT).expect("nodes");
        assert!(noded.nodes.is_empty());
        assert_eq!(noded.points.len(), 3);
    }
}
