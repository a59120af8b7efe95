//! Chines from the knuckles of the sections (H-rep paper §5: "the chines, connecting the
//! knuckles in each cross section"): sections of one family (plane cuts square to one axis)
//! are ordered along that axis, each knuckle point is joined to the nearest knuckle of the next
//! section when they are each other's nearest, and every chain of two or more knuckles becomes
//! a knuckle curve through them.

use glam::DVec3;

use super::data_nodes::axis_planes;
use super::transom::{self, Chain};
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::network::{Network, NetworkCurve, Role};
use crate::tolerance::Tolerance;

/// Knuckles of consecutive sections are joined only when closer than this many times the gap
/// between the sections' planes (a chine sloping at up to about 70° to the axis).
const MAX_RISE: f64 = 3.0;

/// The axis-aligned plane a curve lies in (within the tolerance), as `(axis, value)`.
fn plane_of(curve: &NurbsCurve, tolerance: f64) -> Option<(usize, f64)> {
    axis_planes(curve.control_points().iter().copied(), tolerance)
        .into_iter()
        .enumerate()
        .find_map(|(axis, v)| v.map(|v| (axis, v)))
}

/// The knuckle curves joining the knuckles of consecutive sections of `network` (module doc).
/// `knuckles[i]` are the knuckle points of curve `i` (its interior corners); a curve lies in an
/// axis plane when its control points do within `tolerance` (curves in one plane are one
/// section); curves in no axis plane take part in no chine. A chain lying in one axis plane
/// (a transom's edge) is carried on in that plane to the knuckles beyond its ends
/// (module `transom`). Each chine is named `chine<k> <first>–<last>` (k from 1) after the curves it
/// starts and ends on, and passes through its knuckle points. A flat end that a curve in an
/// axis plane (the profile) outlines between two of its knuckles (a shaft boss's) gets its
/// edge, a chine shaped like the nearest parallel section, and two straight lines of role
/// [`Role::Free`] after the chines: `flat end<k> <outline>` across the end to the edge's point
/// farthest from the outline, and `flat end<k> <section>` on from there to that section.
///
/// Errors: knuckles given for a different number of curves ([`Error::InvalidInput`]), and a
/// chine the curve kernel refuses (named).
pub fn chines_from_knuckles(
    network: &Network,
    knuckles: &[Vec<DVec3>],
    tolerance: Tolerance,
) -> Result<Vec<NetworkCurve>, Error> {
    let curves = network.curves();
    if knuckles.len() != curves.len() {
        return Err(Error::InvalidInput(format!(
            "chines: knuckles for {} curves, the network has {}",
            knuckles.len(),
            curves.len()
        )));
    }
    let planes: Vec<Option<(usize, f64)>> = curves
        .iter()
        .map(|c| plane_of(&c.curve, tolerance.get()))
        .collect();
    let mut chains: Vec<(usize, Chain)> = Vec::new();
    for axis in 0..3 {
        let mut family: Vec<(f64, usize)> = planes
            .iter()
            .enumerate()
            .filter_map(|(i, p)| p.filter(|p| p.0 == axis).map(|p| (p.1, i)))
            .collect();
        family.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Curves in one plane (a section cut in parts) are one section.
        let mut sections: Vec<Section> = Vec::new();
        for (z, i) in family {
            let points = knuckles[i].iter().map(|&p| (i, p));
            match sections.last_mut() {
                Some(s) if z - s.at <= tolerance.get() => s.knuckles.extend(points),
                _ => sections.push(Section {
                    at: z,
                    knuckles: points.collect(),
                }),
            }
        }
        chains.extend(chains_of(&sections).into_iter().map(|c| (axis, c)));
    }
    let ends = transom::flat_ends(curves, &planes, knuckles, &chains, tolerance.get());
    let mut lines: Vec<(String, [DVec3; 2])> = Vec::new();
    for (k, e) in ends.iter().enumerate() {
        lines.push((
            format!("flat end{} {}", k + 1, curves[e.outline].name),
            e.across,
        ));
        if let Some((g, along)) = e.along {
            lines.push((format!("flat end{} {}", k + 1, curves[g].name), along));
        }
    }
    chains.extend(ends.into_iter().map(|e| e.edge));
    let carried = transom::carried_on_in_plane(curves, &planes, knuckles, &chains, tolerance.get());
    let mut out = chains
        .iter()
        .zip(&carried)
        .enumerate()
        .map(|(k, ((_, chain), (head, tail)))| chine_curve(network, chain, head, tail, k + 1))
        .collect::<Result<Vec<_>, Error>>()?;
    for (name, ends) in lines {
        let curve = through_points(&ends).map_err(|e| e.named(&name))?;
        out.push(NetworkCurve {
            name,
            role: Role::Free,
            curve,
        });
    }
    Ok(out)
}

/// One section of a family: its plane's value along the axis, and its knuckles (curve index,
/// point) from every curve in that plane.
struct Section {
    at: f64,
    knuckles: Vec<(usize, DVec3)>,
}

/// The chains of mutually nearest knuckles of consecutive sections of one family (sorted by
/// plane value), each of two or more points.
fn chains_of(sections: &[Section]) -> Vec<Chain> {
    let mut open: Vec<Chain> = Vec::new();
    let mut done: Vec<Chain> = Vec::new();
    for pair in sections.windows(2) {
        let (a, b) = (&pair[0].knuckles, &pair[1].knuckles);
        let reach = MAX_RISE * (pair[1].at - pair[0].at);
        let nearest = |p: DVec3, among: &[(usize, DVec3)]| {
            among
                .iter()
                .enumerate()
                .min_by(|x, y| x.1 .1.distance(p).total_cmp(&y.1 .1.distance(p)))
                .map(|(i, q)| (i, q.1.distance(p)))
        };
        let mut next_open = Vec::new();
        for (j, &q) in b.iter().enumerate() {
            let link = nearest(q.1, a)
                .filter(|&(i, d)| d <= reach && nearest(a[i].1, b).map(|n| n.0) == Some(j));
            let mut chain = match link {
                Some((i, _)) => match open.iter().position(|c| c.last() == Some(&a[i])) {
                    Some(k) => open.swap_remove(k),
                    None => vec![a[i]],
                },
                None => Vec::new(),
            };
            chain.push(q);
            next_open.push(chain);
        }
        done.extend(open.drain(..).filter(|c| c.len() >= 2));
        open = next_open;
    }
    done.extend(open.into_iter().filter(|c| c.len() >= 2));
    done
}

/// The `number`-th knuckle curve, through a chain's points ([`through_points`]); where the
/// chain is carried on at its ends (`head` before its first point, `tail` after its last, from
/// [`transom::carried_on_in_plane`]), through those pieces' points and through dense samples
/// of the chain's own curve, so that it keeps its shape between its knuckles.
fn chine_curve(
    network: &Network,
    chain: &Chain,
    head: &Chain,
    tail: &Chain,
    number: usize,
) -> Result<NetworkCurve, Error> {
    let curves = network.curves();
    let first = head.first().unwrap_or(&chain[0]).0;
    let last = tail.last().unwrap_or(&chain[chain.len() - 1]).0;
    let name = format!("chine{number} {}–{}", curves[first].name, curves[last].name);
    let named = |e: crate::curve::CurveError| e.named(&name);
    let pts: Vec<DVec3> = chain.iter().map(|c| c.1).collect();
    let mut curve = through_points(&pts).map_err(named)?;
    if !(head.is_empty() && tail.is_empty()) {
        // Every knuckle itself, and samples between, at the parameters it was fitted at.
        let params = chord_parameters(&pts);
        let mut all: Vec<DVec3> = head.iter().map(|c| c.1).collect();
        all.push(pts[0]);
        for (w, span) in params.windows(2).zip(pts.windows(2)) {
            all.extend((1..CORE_SAMPLES_PER_SPAN).map(|j| {
                let f = j as f64 / CORE_SAMPLES_PER_SPAN as f64;
                curve.point(w[0] + (w[1] - w[0]) * f)
            }));
            all.push(span[1]);
        }
        all.extend(tail.iter().map(|c| c.1));
        curve = through_points(&all).map_err(named)?;
    }
    Ok(NetworkCurve {
        name,
        role: Role::Knuckle,
        curve,
    })
}

/// Chord-length parameters of points, from 0 to 1.
fn chord_parameters(pts: &[DVec3]) -> Vec<f64> {
    let mut s = vec![0.0];
    for w in pts.windows(2) {
        s.push(s[s.len() - 1] + w[0].distance(w[1]));
    }
    let total = s[s.len() - 1];
    s.iter().map(|d| d / total).collect()
}

/// Samples per span between knuckles of a chain's own curve that a chine carried on at its
/// ends passes through.
const CORE_SAMPLES_PER_SPAN: usize = 8;

/// A line through two points, else the clamped B-spline of degree up to 3 on the points as
/// control polygon, moved through them at their chord-length parameters
/// ([`NurbsCurve::through`]).
fn through_points(pts: &[DVec3]) -> Result<NurbsCurve, crate::curve::CurveError> {
    let n = pts.len();
    let degree = (n - 1).min(3);
    let params = chord_parameters(pts);
    let mut knots = vec![0.0; degree + 1];
    // Averaged knots (Piegl & Tiller eq. 9.8) on the chord-length parameters.
    for j in 1..n - degree {
        knots.push(params[j..j + degree].iter().sum::<f64>() / degree as f64);
    }
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    let polygon = NurbsCurve::try_new(degree, knots, pts.to_vec(), None)?;
    let targets: Vec<(f64, DVec3)> = params.iter().copied().zip(pts.iter().copied()).collect();
    polygon.through(&targets)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wireframe::test_curves::poly;

    /// Three stations of a hard-chine hull (x = 0, 2, 4), the chine rising from z 0.5 to 0.7.
    fn stations() -> (Network, Vec<Vec<DVec3>>) {
        let mut curves = Vec::new();
        let mut knuckles = Vec::new();
        for (i, x) in [0.0, 2.0, 4.0].into_iter().enumerate() {
            let z = 0.5 + 0.1 * i as f64;
            curves.push(poly(
                &format!("st{i}"),
                &[[x, 0.0, 0.0], [x, 1.0, z], [x, 1.2, 1.5]],
            ));
            knuckles.push(vec![DVec3::new(x, 1.0, z)]);
        }
        (
            Network::try_new("chine", curves).expect("network"),
            knuckles,
        )
    }

    #[test]
    fn consecutive_stations_give_one_chine_through_their_knuckles() {
        let (net, knuckles) = stations();
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        assert_eq!(chines.len(), 1);
        let c = &chines[0];
        assert_eq!((c.name.as_str(), c.role), ("chine1 st0–st2", Role::Knuckle));
        for k in knuckles.iter().flatten() {
            let d = c.curve.nearest(*k, 1e-12).expect("nearest").distance;
            assert!(d < 1e-9, "through {k}: {d}");
        }
    }

    #[test]
    fn far_or_lone_knuckles_make_no_chine() {
        let (net, mut knuckles) = stations();
        // The middle station's knuckle 7 m away: beyond three plane gaps (6 m) of both.
        knuckles[1] = vec![DVec3::new(2.0, 7.0, 0.6)];
        let chines = chines_from_knuckles(&net, &knuckles, Tolerance::DEFAULT).expect("chines");
        assert!(
            chines.is_empty(),
            "{:?}",
            chines.iter().map(|c| &c.name).collect::<Vec<_>>()
        );
        assert!(matches!(
            chines_from_knuckles(&net, &knuckles[..2], Tolerance::DEFAULT),
            Err(Error::InvalidInput(_))
        ));
    }
}
