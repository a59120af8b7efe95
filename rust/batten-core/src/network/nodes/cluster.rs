//! Clustering the curve ends and joins into nodes: union–find over joined pairs and over any
//! two curve points within the tolerance.

use glam::DVec3;

use super::{Hit, Incidence, Junction, Junctions, Prepared};
use crate::curve::NurbsCurve;
use crate::diagnostic::Diagnostic;
use crate::network::Network;
use crate::union_find::UnionFind;

/// A tangent jump (radians) above which a curve's knot is a corner that a node within the
/// tolerance of it sits at (about 0.06°, where two tangents stop being parallel for the
/// rotation system).
const NODE_CORNER_ANGLE: f64 = 1e-3;

/// A corner of a hull boundary curve ([`Role::bounds_hull`](crate::network::Role::bounds_hull):
/// keel, stem, transom, deck) where
/// its tangent turns by more than this (15°, the H-rep paper's minimum angle between tangents,
/// §3.2.2, as [`CORNER_ANGLE_DEGREES`](crate::topo::CORNER_ANGLE_DEGREES) for a face's corners)
/// is a node even where no other curve meets it: the surface lies on one side of such a curve
/// only, so its knuckle is a true corner of the face there (the profile round the aft end of a
/// shaft boss, whose knuckles are the corners of the boss's end face). A knuckle of a curve
/// inside the surface may be a crease across it rather than a corner of the faces on either
/// side, and stays inside their sides.
pub(crate) const KNUCKLE_NODE_DEGREES: f64 = 15.0;

/// Put an incidence within the tolerance of one of its curve's corners at the corner: the
/// node is at the knuckle, and the edges on either side leave it along the one-sided tangents
/// of their own sides. (Found a little off the corner, the parameter would give both edges the
/// tangent of one side, and the faces around the node would be traced wrong.)
fn at_corner(c: &mut CurvePoint, curve: &NurbsCurve, corners: &[f64], tol: f64) {
    if corners.is_empty() {
        return; // most curves are smooth: nothing to evaluate
    }
    let here = curve.point(c.incidence.t);
    if let Some(&t) = corners
        .iter()
        .filter(|&&t| curve.point(t).distance(here) <= tol)
        .min_by(|a, b| {
            let (pa, pb) = (curve.point(**a), curve.point(**b));
            pa.distance(here).total_cmp(&pb.distance(here))
        })
    {
        c.incidence.t = t;
        c.point = curve.point(t);
    }
}

/// A curve through a place (a curve end or one side of a join) and its point there.
#[derive(Clone, Copy, Debug)]
struct CurvePoint {
    incidence: Incidence,
    point: DVec3,
}

/// The direction of the sweep in [`pairs_within`]: generic (components in the ratios of the
/// plastic number's powers), so that no family of a hull's curves lies across it — a sweep
/// along x compared every pair of points on one station, all of whose crossings share its x,
/// which made a dense grid's clustering quadratic in its waterlines.
const SWEEP: DVec3 = DVec3::new(0.7296, 0.5507, 0.4158);

/// `x`'s bits as an unsigned integer ordered as `f64::total_cmp` orders the floats (negative
/// numbers' bits reversed, the sign bit flipped).
fn total_order_bits(x: f64) -> u64 {
    let b = x.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | (1 << 63)
    }
}

/// Pairs `(i, j)` of curve points within `tol` of each other, enough to join every group of
/// points that has a member within `tol` of another group's: the points from `first_pair` on
/// come in pairs already joined (the two sides of a crossing), and each such pair, like each
/// point before `first_pair`, is one group. A sweep along [`SWEEP`] over one point per group:
/// points within `tol` are within `tol` along any unit direction, so two groups with members
/// within `tol` have first points within `tol` plus both groups' spreads along it, and each
/// group is compared only with those after it until the sweep has moved past that (half the
/// points to sort as comparing every point).
fn pairs_within(points: &[CurvePoint], first_pair: usize, tol: f64) -> Vec<(usize, usize)> {
    let along = SWEEP.normalize();
    let groups = first_pair + (points.len() - first_pair) / 2;
    // Group `g`: the index of its first point, and its points.
    let group = |g: usize| {
        let i = if g < first_pair {
            g
        } else {
            first_pair + 2 * (g - first_pair)
        };
        (i, &points[i..i + usize::from(g >= first_pair) + 1])
    };
    let spread = points[first_pair..]
        .chunks_exact(2)
        .map(|p| p[0].point.distance(p[1].point))
        .fold(0.0, f64::max);
    let reach = tol + 2.0 * spread;
    let key: Vec<f64> = (0..groups)
        .map(|g| points[group(g).0].point.dot(along))
        .collect();
    // Sorted by the keys' total order (as `f64::total_cmp`), then by index: as integers, which
    // sort faster than floats compared through a closure.
    let mut order: Vec<(u64, usize)> = key.iter().map(|&s| total_order_bits(s)).zip(0..).collect();
    order.sort_unstable();
    let mut pairs = Vec::new();
    for (k, &(_, g)) in order.iter().enumerate() {
        for &(_, h) in &order[k + 1..] {
            if key[h] - key[g] > reach {
                break;
            }
            // The first pair of members within the tolerance, if any, joins the two groups.
            let ((i, gs), (j, hs)) = (group(g), group(h));
            let close = (0..gs.len())
                .flat_map(|x| (0..hs.len()).map(move |y| (x, y)))
                .find(|&(x, y)| gs[x].point.distance(hs[y].point) <= tol);
            if let Some((x, y)) = close {
                pairs.push((i + x, j + y));
            }
        }
    }
    pairs
}

/// Cluster curve ends and joins into nodes (union–find: joined pairs, and any two curve points
/// within the tolerance, [`pairs_within`]).
pub(super) fn cluster(
    network: &Network,
    prepared: &[Prepared],
    hits: &[Hit],
    excluded: &[bool],
    tol: f64,
    diagnostics: Vec<Diagnostic>,
) -> Junctions {
    let curves = network.curves();
    let corners: Vec<Vec<f64>> = prepared
        .iter()
        .map(|p| p.curve.corner_parameters(NODE_CORNER_ANGLE))
        .collect();
    let mut incs: Vec<CurvePoint> = Vec::new();
    for (ci, p) in prepared.iter().enumerate() {
        if excluded[ci] {
            continue;
        }
        let (a, b) = p.curve.domain();
        for t in [a, b] {
            incs.push(CurvePoint {
                incidence: Incidence { curve: ci, t },
                point: p.curve.point(t),
            });
        }
    }
    // Knuckles of the boundary, after all the ends (ends keep the first node numbers).
    for (ci, p) in prepared.iter().enumerate() {
        if excluded[ci] || !curves[ci].role.bounds_hull() {
            continue;
        }
        for t in p.curve.corner_parameters(KNUCKLE_NODE_DEGREES.to_radians()) {
            incs.push(CurvePoint {
                incidence: Incidence { curve: ci, t },
                point: p.curve.point(t),
            });
        }
    }
    let mut uf = UnionFind::new(incs.len() + 2 * hits.len());
    let first_pair = incs.len();
    for h in hits {
        let ia = incs.len();
        incs.push(CurvePoint {
            incidence: Incidence { curve: h.a, t: h.s },
            point: h.pa,
        });
        incs.push(CurvePoint {
            incidence: Incidence { curve: h.b, t: h.t },
            point: h.pb,
        });
        uf.union(ia, ia + 1);
    }
    // Any two curve points within the tolerance are one node.
    for (i, j) in pairs_within(&incs, first_pair, tol) {
        uf.union(i, j);
    }
    // Groups, in order of their smallest member (curve ends come first, in curve order), as
    // runs of one flat array (counting sort by node).
    let mut node_of_root = vec![usize::MAX; incs.len()];
    let mut node_of = vec![0usize; incs.len()];
    let mut count: Vec<usize> = Vec::new();
    for i in 0..incs.len() {
        let r = uf.find(i);
        if node_of_root[r] == usize::MAX {
            node_of_root[r] = count.len();
            count.push(0);
        }
        node_of[i] = node_of_root[r];
        count[node_of[i]] += 1;
    }
    let mut start = vec![0usize; count.len() + 1];
    for (n, c) in count.iter().enumerate() {
        start[n + 1] = start[n] + c;
    }
    let mut fill = start.clone();
    let mut flat = vec![0usize; incs.len()];
    for (i, &n) in node_of.iter().enumerate() {
        flat[fill[n]] = i;
        fill[n] += 1;
    }
    let mut nodes = Vec::with_capacity(count.len());
    let mut splits: Vec<Vec<(f64, usize)>> = vec![Vec::new(); curves.len()];
    let mut list: Vec<CurvePoint> = Vec::new();
    let mut merged: Vec<CurvePoint> = Vec::new();
    for node in 0..count.len() {
        let members = &flat[start[node]..start[node + 1]];
        let position = members.iter().map(|&i| incs[i].point).sum::<DVec3>() / members.len() as f64;
        list.clear();
        list.extend(members.iter().map(|&i| incs[i]));
        list.sort_by(|x, y| {
            let (x, y) = (x.incidence, y.incidence);
            x.curve.cmp(&y.curve).then(x.t.total_cmp(&y.t))
        });
        // One incidence per curve and place: ends win, otherwise the point nearest the node.
        merged.clear();
        for &CurvePoint {
            incidence: inc,
            point: p,
        } in &list
        {
            let curve = prepared[inc.curve].curve;
            let end_param = {
                let (a, b) = curve.domain();
                (inc.t == a || inc.t == b).then_some(inc.t)
            };
            let (a, b) = curve.domain();
            // The two ends of a closed curve stay two incidences.
            let opposite_ends =
                |m: &Incidence| (m.t == a && inc.t == b) || (m.t == b && inc.t == a);
            match merged.iter_mut().find(|m| {
                m.incidence.curve == inc.curve
                    && (m.point - p).length() <= tol
                    && !opposite_ends(&m.incidence)
            }) {
                Some(m) => {
                    let m_end = m.incidence.t == a || m.incidence.t == b;
                    if end_param.is_some() && !m_end
                        || (!m_end
                            && end_param.is_none()
                            && (p - position).length() < (m.point - position).length())
                    {
                        *m = CurvePoint {
                            incidence: inc,
                            point: p,
                        };
                    }
                }
                None => merged.push(CurvePoint {
                    incidence: inc,
                    point: p,
                }),
            }
        }
        for c in &mut merged {
            at_corner(
                c,
                prepared[c.incidence.curve].curve,
                &corners[c.incidence.curve],
                tol,
            );
            splits[c.incidence.curve].push((c.incidence.t, node));
        }
        nodes.push(Junction {
            position,
            incidences: merged.iter().map(|c| c.incidence).collect(),
        });
    }
    for s in &mut splits {
        s.sort_by(|x, y| x.0.total_cmp(&y.0));
    }
    Junctions {
        nodes,
        splits,
        excluded: excluded.to_vec(),
        suppressed: Vec::new(),
        diagnostics,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_order_bits_order_as_total_cmp() {
        let xs = [
            f64::NEG_INFINITY,
            -1e300,
            -2.5,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            1.0,
            3e10,
            f64::INFINITY,
        ];
        for a in xs {
            for b in xs {
                assert_eq!(
                    total_order_bits(a).cmp(&total_order_bits(b)),
                    a.total_cmp(&b),
                    "{a} vs {b}"
                );
            }
        }
    }

    /// The groups `pairs` join among `n` points whose points from `first_pair` on are joined
    /// in pairs, each group by its smallest member.
    fn groups(n: usize, first_pair: usize, pairs: &[(usize, usize)]) -> Vec<usize> {
        let mut uf = UnionFind::new(n);
        for i in (first_pair..n).step_by(2) {
            uf.union(i, i + 1);
        }
        for &(i, j) in pairs {
            uf.union(i, j);
        }
        let mut smallest = vec![usize::MAX; n];
        for i in 0..n {
            let r = uf.find(i);
            smallest[r] = smallest[r].min(i);
        }
        (0..n).map(|i| smallest[uf.find(i)]).collect()
    }

    #[test]
    fn the_sweep_joins_what_comparing_every_two_points_joins() {
        // Points on a 0.5 mm lattice with jitter (many within the 1 mm tolerance of each
        // other, many not); from point 40 on, crossings: pairs up to the tolerance apart.
        let tol = 1e-3;
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut unit = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut points = Vec::new();
        let at = |p: DVec3| CurvePoint {
            incidence: Incidence { curve: 0, t: 0.0 },
            point: p,
        };
        // A crossing whose second side is near a curve end its first side is not: along the
        // sweep, the end lies 1.9 tolerances past the crossing's first point.
        let sweep = SWEEP.normalize();
        let crossing = DVec3::splat(0.5);
        points.push(at(crossing + sweep * 1.9 * tol));
        for _ in 0..40 {
            let p = DVec3::new(unit(), unit(), unit()) * 5e-3;
            points.push(at(p));
        }
        let first_pair = points.len();
        points.push(at(crossing));
        points.push(at(crossing + sweep * 0.95 * tol));
        for _ in 0..60 {
            let p = DVec3::new(unit(), unit(), unit()) * 5e-3;
            let d = DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5).normalize() * tol * unit();
            points.push(at(p));
            points.push(at(p + d));
        }
        let n = points.len();
        let every: Vec<(usize, usize)> = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .filter(|&(i, j)| points[i].point.distance(points[j].point) <= tol)
            .collect();
        let swept = pairs_within(&points, first_pair, tol);
        let expected = groups(n, first_pair, &every);
        assert_eq!(
            expected[first_pair], 0,
            "the crossing joins the end its second side is near"
        );
        assert_eq!(groups(n, first_pair, &swept), expected, "the same groups");
        let count = |g: &[usize]| (0..n).filter(|&i| g[i] == i).count();
        assert!(
            count(&expected) > 5 && count(&expected) < n / 2,
            "a test with groups of several points: {} groups",
            count(&expected)
        );
    }

    #[test]
    fn an_incidence_a_hair_off_a_corner_goes_to_the_corner() {
        // An L-shaped polyline, corner at t = 1 (the point (1, 0, 0)).
        let l = NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 2.0, 2.0],
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)],
            None,
        )
        .expect("polyline");
        let corners = l.corner_parameters(NODE_CORNER_ANGLE);
        assert_eq!(corners, [1.0]);
        let near = |t: f64| CurvePoint {
            incidence: Incidence { curve: 0, t },
            point: l.point(t),
        };
        let mut c = near(1.0 - 1e-9);
        at_corner(&mut c, &l, &corners, 1e-4);
        assert_eq!((c.incidence.t, c.point), (1.0, DVec3::X));
        // Farther than the tolerance from the corner: left where it is.
        let mut c = near(0.5);
        at_corner(&mut c, &l, &corners, 1e-4);
        assert_eq!(c.incidence.t, 0.5);
    }
}
