//! Corner points: places where a curve's tangent direction jumps (a knuckle point).

use glam::DVec3;

use super::nurbs::NurbsCurve;

impl NurbsCurve {
    /// Parameters of the interior corners where the tangent direction turns by more than
    /// `min_angle` radians.
    ///
    /// Only a knot of multiplicity `degree` can carry a corner (elsewhere the curve is at least
    /// C1). There the curve passes through a control point `P`, and the one-sided tangents point
    /// along `P − P_prev` and `P_next − P` (end tangents of the neighbouring Bézier pieces); a
    /// zero-length handle falls back to the next distinct control point on that side.
    pub fn corner_parameters(&self, min_angle: f64) -> Vec<f64> {
        let p = self.degree();
        let knots = self.knots();
        let (start, end) = self.domain();
        let pts = self.control_points();
        let mut corners = Vec::new();
        let mut i = p + 1;
        while i < pts.len() {
            let u = knots[i];
            let mut j = i;
            while knots[j] == u {
                j += 1;
            }
            if u > start && u < end && j - i >= p {
                // Knots i..i+p equal u: C(u) is control point i-1.
                let at = i - 1;
                let before = (0..at).rev().map(|k| pts[at] - pts[k]).find(nonzero);
                let after = (at + 1..pts.len()).map(|k| pts[k] - pts[at]).find(nonzero);
                if let (Some(a), Some(b)) = (before, after) {
                    if a.angle_between(b) > min_angle {
                        corners.push(u);
                    }
                }
            }
            i = j;
        }
        corners
    }
}

fn nonzero(v: &DVec3) -> bool {
    v.length_squared() > 0.0
}
