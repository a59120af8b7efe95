//! The hull's knuckle (chine) lines for drawing: the knuckle edges of the build report joined,
//! curve by curve, end to end into polylines.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::hull::KnuckleEdge;

/// One knuckle line: the name of its curve and its points in order.
#[derive(Clone, Debug, PartialEq)]
pub struct KnuckleLine {
    /// The network curve the knuckle runs along.
    pub curve: String,
    /// Points along it (m).
    pub points: Vec<DVec3>,
}

/// The knuckle edges joined into lines: the edges of one curve chained where an end lies within
/// `join` (m) of another's end (either way round); a curve whose edges do not all meet gives
/// several lines. In the order of the curves' names.
pub fn knuckle_lines(edges: &[KnuckleEdge], join: f64) -> Vec<KnuckleLine> {
    let mut by_curve: BTreeMap<&str, Vec<Vec<DVec3>>> = BTreeMap::new();
    for e in edges {
        let pts: Vec<DVec3> = e.points.iter().map(|p| DVec3::from(*p)).collect();
        if pts.len() >= 2 {
            by_curve.entry(e.curve.as_str()).or_default().push(pts);
        }
    }
    let mut out = Vec::new();
    for (curve, mut rest) in by_curve {
        while let Some(mut line) = rest.pop() {
            // Grow the line at either end while some edge meets it.
            loop {
                let (first, last) = (line[0], *line.last().expect("two points"));
                let found = rest.iter().enumerate().find_map(|(k, e)| {
                    let (a, b) = (e[0], *e.last().expect("two points"));
                    [
                        ((a - last).length() <= join).then_some((k, false, false)),
                        ((b - last).length() <= join).then_some((k, false, true)),
                        ((b - first).length() <= join).then_some((k, true, false)),
                        ((a - first).length() <= join).then_some((k, true, true)),
                    ]
                    .into_iter()
                    .flatten()
                    .next()
                });
                let Some((k, at_front, reverse)) = found else {
                    break;
                };
                let mut e = rest.swap_remove(k);
                if reverse {
                    e.reverse();
                }
                if at_front {
                    e.pop();
                    e.extend_from_slice(&line);
                    line = e;
                } else {
                    line.extend_from_slice(&e[1..]);
                }
            }
            out.push(KnuckleLine {
                curve: curve.to_owned(),
                points: line,
            });
        }
    }
    out
}
