//! The filtered section F[i] and its bias against C[i] (Pla et al. 1998, §4): at each control
//! point's Greville abscissa the point of C[i] is compared with the filtered section built
//! from the neighbouring sections of its family, and the bias is the normal distance between
//! them, in the section's plane (the paper's distance from the vertices of F[i] to C[i]).
//!
//! The neighbours' points correspond to C[i]'s across the crossing curves: between two nodes
//! of C[i] (where it crosses, say, two waterlines) a point at a share of the parameter interval
//! corresponds to the point at the same share between the neighbour's nodes on the same
//! crossing curves, as a loftsman reads a body plan between waterlines; so a hull whose
//! sections vary as a cubic along the family, at equal shares, is its own filtered section. A
//! point whose neighbour does not cross the same curves takes the neighbour's point where its
//! normal line meets it, moved into the plane of C[i] (from its closest point by Newton's
//! method along the neighbour); a neighbour the normal line does not meet (one that ends short of the point, a
//! bulb beside the stem) is no neighbour there, and without a neighbour on both sides a point
//! has no bias (as the first and last sections, whose filtered section is themselves). Fixed
//! curves in a family's planes (a deck edge among the waterlines, the stem and the transom
//! among the stations) are neighbours too, though they never move.
//!
//! Choice (written down as the seed README asks): [`SectionFilter::Equidistant`] is the paper's
//! filter, the section equidistant from C[i−1] and C[i+1] (between them in proportion to the
//! plane spacing where it is uneven). On a curved hull it is not C[i] even without noise: its
//! bias is the second difference of the shape along the family (0.31 m on the Wigley hull's
//! waterline at a 12.5 m station spacing), so relaxing toward it flattens the hull by all the
//! tolerance allows. [`SectionFilter::Cubic`] (the default) interpolates the normal distances of
//! two neighbours on each side by a cubic in the plane offset (Lagrange), which passes through
//! any shape that varies as a cubic along the family, and so removes noise, not the form.

use glam::DVec3;

use crate::curve::{BezierDecomposition, NurbsCurve};

use super::families::Family;
use super::nodes::Nodes;

/// A neighbour's point counts as on the normal line when its offset along the section's
/// tangent is at most this multiple of its offset along the normal (45°); Newton's method has
/// then failed to reach the line, or the neighbour ends short of it.
const FOOT_SLANT: f64 = 1.0;

/// Newton steps from the closest point toward the normal line (quadratic convergence: a few
/// steps reach f64 resolution from the closest point, which is near for near-parallel
/// sections).
const NORMAL_LINE_STEPS: usize = 8;

/// A neighbour's point counts only if it lies within this many times the planes' distance of
/// the section's point (in the plane): the surface between neighbouring sections may be as
/// steep as 84° to their planes (a flared bow between waterlines), not steeper; a point
/// farther off belongs to another part of the neighbour (its other end, a bulb).
const MAX_SPREAD: f64 = 10.0;

/// Which filtered section the sections are relaxed toward.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SectionFilter {
    /// The paper's: the section equidistant from the two neighbouring sections.
    Equidistant,
    /// A cubic through two neighbouring sections on each side (fewer where the family ends).
    #[default]
    Cubic,
}

impl SectionFilter {
    /// Neighbouring planes the filter takes on each side.
    pub(crate) fn reach(self) -> usize {
        match self {
            SectionFilter::Equidistant => 1,
            SectionFilter::Cubic => 2,
        }
    }
}

/// The bias of one section: per control point, the move that takes its Greville point to the
/// filtered section along the normal, and the section's RMS and largest bias (m).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SectionBias {
    /// Per control point: `(F − C)·n n`, zero at the ends and where the point has no
    /// neighbours.
    pub moves: Vec<DVec3>,
    /// Root mean square of the biases over the points that have one (m).
    pub rms: f64,
    /// The largest bias (m).
    pub max: f64,
}

/// The network as the filter reads it: every curve, its Bézier decomposition, and the nodes.
#[derive(Clone, Copy)]
pub(crate) struct Sections<'a> {
    /// Every curve of the network.
    pub curves: &'a [NurbsCurve],
    /// Their Bézier decompositions (for closest points).
    pub decomps: &'a [BezierDecomposition],
    /// Where they meet.
    pub nodes: &'a Nodes,
}

/// Greville abscissae of `curve`: where each control point pulls hardest.
pub(crate) fn greville(curve: &NurbsCurve) -> Vec<f64> {
    let p = curve.degree();
    let knots = curve.knots();
    (0..curve.control_point_count())
        .map(|j| knots[j + 1..=j + p].iter().sum::<f64>() / p as f64)
        .collect()
}

/// Lagrange weights at `x` of the nodes `xs` (distinct).
fn lagrange(xs: &[f64], x: f64) -> Vec<f64> {
    (0..xs.len())
        .map(|i| {
            (0..xs.len())
                .filter(|&m| m != i)
                .map(|m| (x - xs[m]) / (xs[i] - xs[m]))
                .product()
        })
        .collect()
}

/// The parameter of neighbour `i` that corresponds to parameter `t` of section `k` across
/// their nodes on the same crossing curves (module doc), `None` where they cross no common
/// curves on both sides of `t`.
fn across_nodes(nodes: &Nodes, k: usize, t: f64, i: usize) -> Option<f64> {
    let on_k = &nodes.on_curve[k];
    let b = on_k.iter().position(|&(u, _)| u >= t)?;
    let a = if on_k[b].0 == t { b } else { b.checked_sub(1)? };
    let (ta, na) = on_k[a];
    let (tb, nb) = on_k[b];
    let sa = matching_node(nodes, na, k, i)?;
    let sb = matching_node(nodes, nb, k, i)?;
    if tb <= ta {
        return Some(sa);
    }
    Some(sa + (t - ta) / (tb - ta) * (sb - sa))
}

/// The parameter on curve `i` of its node on a curve (other than `k`) through `node`: of
/// several (a waterline ending twice on the profile, a station crossing a bulb's waterline
/// twice), the one nearest `node`.
fn matching_node(nodes: &Nodes, node: usize, k: usize, i: usize) -> Option<f64> {
    let crossing = || {
        nodes.incidences[node]
            .iter()
            .map(|&(c, _)| c)
            .filter(|&c| c != k)
    };
    let here = nodes.positions[node];
    nodes.on_curve[i]
        .iter()
        .filter(|&&(_, m)| {
            nodes.incidences[m]
                .iter()
                .any(|&(c, _)| c != i && crossing().any(|x| x == c))
        })
        .min_by(|a, b| {
            let (da, db) = (
                nodes.positions[a.1].distance(here),
                nodes.positions[b.1].distance(here),
            );
            da.total_cmp(&db)
        })
        .map(|&(s, _)| s)
}

/// The point of `neighbour` (decomposed as `bez`) on the line through `p` normal to the unit
/// `tangent` (in the plane of its section), by Newton's method on `(Q(u) − p)·tangent = 0`
/// from the parameter `u` of its closest point, kept in its domain.
fn on_normal_line(
    neighbour: &NurbsCurve,
    bez: &BezierDecomposition,
    mut u: f64,
    p: DVec3,
    tangent: DVec3,
    accuracy: f64,
) -> DVec3 {
    let (start, end) = neighbour.domain();
    let mut q = bez.point(u);
    for _ in 0..NORMAL_LINE_STEPS {
        let (point, d1) = bez.point_d1(u);
        q = point;
        let f = (q - p).dot(tangent);
        let slope = d1.dot(tangent);
        if f.abs() <= accuracy || slope == 0.0 {
            break;
        }
        u = (u - f / slope).clamp(start, end);
    }
    q
}

/// The bias of the section `k` (a curve of plane `group` in `family`; module doc) in the
/// `network`; `accuracy` (m) is that of the closest points.
pub(crate) fn section_bias(
    family: &Family,
    group: usize,
    k: usize,
    network: Sections<'_>,
    filter: SectionFilter,
    accuracy: f64,
) -> SectionBias {
    let Sections {
        curves,
        decomps,
        nodes,
    } = network;
    let curve = &curves[k];
    let axis = family.family.axis();
    let normal_axis = DVec3::AXES[axis];
    let offset = family.groups[group].offset;
    let reach = filter.reach();
    let before: Vec<usize> = (group.saturating_sub(reach)..group).rev().collect();
    let after: Vec<usize> = (group + 1..family.groups.len()).take(reach).collect();
    let mut moves = vec![DVec3::ZERO; curve.control_point_count()];
    let (mut sum, mut count, mut max) = (0.0, 0usize, 0.0f64);
    let last = curve.control_point_count() - 1;
    // The end points stay (on the keel, the deck, the stem), so they have no bias.
    for (j, t) in greville(curve).into_iter().enumerate().take(last).skip(1) {
        let d = curve.derivs(t);
        let mut tangent = d.d1;
        tangent[axis] = 0.0;
        let tangent = tangent.normalize_or_zero();
        if tangent == DVec3::ZERO {
            continue;
        }
        let n = normal_axis.cross(tangent);
        // The neighbours' normal distances on each side, nearest plane first, up to the first
        // plane that has no point along the normal.
        let side = |planes: &[usize]| -> Vec<(f64, f64)> {
            let mut found = Vec::new();
            for &g in planes {
                let group = &family.groups[g].curves;
                let mapped = group
                    .iter()
                    .find_map(|&i| across_nodes(nodes, k, t, i).map(|s| curves[i].point(s)));
                let q = match mapped {
                    Some(q) => Some(q),
                    None => group
                        .iter()
                        .filter_map(|&c| decomps[c].nearest(d.point, accuracy).ok().map(|n| (c, n)))
                        .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance))
                        .map(|(c, near)| {
                            on_normal_line(
                                &curves[c],
                                &decomps[c],
                                near.t,
                                d.point,
                                tangent,
                                accuracy,
                            )
                        })
                        .filter(|q| {
                            let mut v = *q - d.point;
                            v[axis] = 0.0;
                            v.dot(tangent).abs() <= FOOT_SLANT * v.dot(n).abs() + accuracy
                        }),
                };
                let Some(mut q) = q else { break };
                let spread = (family.groups[g].offset - offset).abs();
                q[axis] = offset;
                if q.distance(d.point) > MAX_SPREAD * spread + accuracy {
                    break;
                }
                let along = (q - d.point).dot(n);
                found.push((family.groups[g].offset, along));
            }
            found
        };
        let (lo, hi) = (side(&before), side(&after));
        if lo.is_empty() || hi.is_empty() {
            continue;
        }
        let (xs, ds): (Vec<f64>, Vec<f64>) = lo.into_iter().chain(hi).unzip();
        let bias: f64 = lagrange(&xs, offset)
            .iter()
            .zip(&ds)
            .map(|(w, d)| w * d)
            .sum();
        moves[j] = bias * n;
        sum += bias * bias;
        count += 1;
        max = max.max(bias.abs());
    }
    let rms = if count > 0 {
        (sum / count as f64).sqrt()
    } else {
        0.0
    };
    SectionBias { moves, rms, max }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_weights_reproduce_cubics() {
        let xs = [-2.0, -1.0, 1.5, 3.0];
        let w = lagrange(&xs, 0.0);
        let f = |x: f64| 1.0 - 2.0 * x + 0.5 * x * x - 0.25 * x * x * x;
        let at: f64 = xs.iter().zip(&w).map(|(x, w)| w * f(*x)).sum();
        assert!((at - f(0.0)).abs() < 1e-12, "cubic reproduced: {at}");
        let eq = lagrange(&[-1.0, 1.0], 0.0);
        assert_eq!(eq, vec![0.5, 0.5], "the paper's equidistant section");
    }
}
