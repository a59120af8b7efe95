//! The four-sided pieces a patch is exported as: a 4-sided (Gregory) patch is one piece, its
//! unit-square domain as it is; an N-sided (Charrot–Gregory) patch is cut into N quads from the
//! centre of its regular-polygon domain to the midpoints of its sides (the usual split of an
//! N-sided patch into quads, Gregory & Zhou 1994), each mapped bilinearly from `[0, 1]²`.
//!
//! Quads rather than a B-spline with a collapsed edge: a collapsed edge puts a singular point
//! (no normal, a fan of isoparametric lines) on the surface, where OpenCASCADE's projection
//! and sewing are least reliable, and a triangle fitted that way needs many more control
//! points near the collapse; the quads' edges are ordinary curves shared by two faces.

use glam::DVec2;

use crate::patch::Domain;

/// Where one side of a quad lies on its patch, running with the quad's own parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum QuadSide {
    /// Side `side` of the patch from side parameter `from` to `to`.
    Patch {
        /// The patch side.
        side: usize,
        /// Side parameter at the quad's parameter 0.
        from: f64,
        /// Side parameter at the quad's parameter 1.
        to: f64,
    },
    /// Spoke `spoke` of an N-sided patch: from the midpoint of side `spoke` to the centre.
    Spoke(usize),
}

/// One exported piece of a patch: its domain corners (at `(0,0)`, `(1,0)`, `(1,1)`, `(0,1)`
/// of the quad, counter-clockwise as the domain) and its sides `[bottom, right, top, left]`,
/// bottom and top running along `u`, left and right along `v`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Quad {
    /// Domain points of the quad's corners.
    pub(crate) corners: [DVec2; 4],
    /// `v = 0`, `u = 1`, `v = 1`, `u = 0`.
    pub(crate) sides: [QuadSide; 4],
}

impl Quad {
    /// The domain point at quad parameter `(u, v)` (bilinear in the corners).
    #[inline]
    pub(crate) fn domain_point(&self, u: f64, v: f64) -> DVec2 {
        let [a, b, c, d] = self.corners;
        a * ((1.0 - u) * (1.0 - v)) + b * (u * (1.0 - v)) + c * (u * v) + d * ((1.0 - u) * v)
    }
}

/// The domain midpoint of side `i`.
pub(crate) fn side_midpoint(domain: &Domain, i: usize) -> DVec2 {
    domain.side_point_v(i, 0.5)
}

/// The quads of a patch with `domain`.
pub(crate) fn quads(domain: &Domain) -> Vec<Quad> {
    let n = domain.sides();
    if n == 4 {
        let side = |side, from, to| QuadSide::Patch { side, from, to };
        return vec![Quad {
            corners: [
                domain.vertex(0),
                domain.vertex(1),
                domain.vertex(2),
                domain.vertex(3),
            ],
            sides: [
                side(0, 0.0, 1.0),
                side(1, 0.0, 1.0),
                side(2, 1.0, 0.0),
                side(3, 1.0, 0.0),
            ],
        }];
    }
    let centre = domain.centre_v();
    (0..n)
        .map(|i| {
            let prev = (i + n - 1) % n;
            Quad {
                corners: [
                    domain.vertex(i),
                    side_midpoint(domain, i),
                    centre,
                    side_midpoint(domain, prev),
                ],
                sides: [
                    QuadSide::Patch {
                        side: i,
                        from: 0.0,
                        to: 0.5,
                    },
                    QuadSide::Spoke(i),
                    QuadSide::Spoke(prev),
                    QuadSide::Patch {
                        side: prev,
                        from: 1.0,
                        to: 0.5,
                    },
                ],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_cover_the_domain_counter_clockwise_and_follow_their_sides() {
        for n in [3, 4, 5, 6] {
            let d = Domain::new(n);
            let qs = quads(&d);
            assert_eq!(qs.len(), if n == 4 { 1 } else { n }, "quads of {n} sides");
            let area: f64 = qs
                .iter()
                .map(|q| {
                    let [a, b, c, e] = q.corners;
                    0.5 * ((b - a).perp_dot(c - a) + (c - a).perp_dot(e - a))
                })
                .sum();
            let v = d.vertices();
            let poly: f64 = (0..n)
                .map(|i| {
                    let (p, q) = (DVec2::from(v[i]), DVec2::from(v[(i + 1) % n]));
                    0.5 * p.perp_dot(q)
                })
                .sum();
            assert!(
                (area - poly).abs() < 1e-12,
                "{n}: quads cover {area} of {poly}"
            );
            for q in &qs {
                if let QuadSide::Patch { side, from, to } = q.sides[0] {
                    let at = d.side_point_v(side, from + 0.3 * (to - from));
                    assert!(
                        (q.domain_point(0.3, 0.0) - at).length() < 1e-12,
                        "bottom side"
                    );
                }
            }
        }
    }
}
