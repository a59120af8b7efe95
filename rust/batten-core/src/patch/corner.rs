//! The corner data of the Gregory and Charrot–Gregory corner interpolants (H-rep paper
//! §3.2.1, eq. 3): at each corner the position, the two ribbons there and their derivatives
//! along the sides, and Gregory's rational twist built from those.

use glam::DVec3;

use super::boundary::PreparedSide;
use super::ribbon::PreparedRibbon;

/// Step in the side parameter for the ribbon derivatives at the corners (the twists of eq. 3),
/// taken by a second-order one-sided difference. The patch's cross derivative along a side is
/// its ribbon only where these twists are the ribbons' own end derivatives: a ribbon turning
/// within 1e-4 of its end (KCS's bilge ribbons, held to the corner's tangent plane there) made
/// a difference at 1e-4 that tilted the bilge 0.53° off the flat of bottom; at 1e-6 it is
/// 6e-4°, and rounding (ε·|R|/h, 2e-8 for a ribbon of 100 m) is still far below it.
const TWIST_STEP: f64 = 1e-6;

/// The data of corner `i` (start of side `i`, end of side `i − 1`) for the corner interpolant
/// of eq. 3: position, `A = R_{i−1}(1)` (the derivative along side `i`), `B = R_i(0)` (along
/// side `i − 1` from the corner) and the two twists `x = −R'_{i−1}(1)`, `y = R'_i(0)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CornerData {
    pub(crate) p: DVec3,
    pub(crate) a: DVec3,
    pub(crate) b: DVec3,
    pub(crate) x: DVec3,
    pub(crate) y: DVec3,
}

impl CornerData {
    /// Gregory's rational twist at local parameters `u` (along side `i`) and `v` (along side
    /// `i − 1` from the corner): `W = (u·x + v·y) / (u + v)`, the mean of the two twists at
    /// the corner itself, so each side keeps its own twist (eq. 3).
    #[inline]
    pub(crate) fn twist(&self, u: f64, v: f64) -> DVec3 {
        let uv = u + v;
        if uv > 0.0 {
            (self.x * u + self.y * v) / uv
        } else {
            (self.x + self.y) * 0.5
        }
    }
}

/// The corner data of every corner of a face, from its prepared sides and ribbons (the
/// ribbons' derivatives by second-order one-sided differences of step [`TWIST_STEP`]).
pub(crate) fn corner_data(sides: &[PreparedSide], ribs: &[PreparedRibbon]) -> Vec<CornerData> {
    let n = sides.len();
    let h = TWIST_STEP;
    let deriv0 = |i: usize| {
        let r = |s: f64| ribs[i].eval(&sides[i], s).1;
        (r(h) * 4.0 - r(0.0) * 3.0 - r(2.0 * h)) / (2.0 * h)
    };
    let deriv1 = |i: usize| {
        let r = |s: f64| ribs[i].eval(&sides[i], s).1;
        (r(1.0) * 3.0 - r(1.0 - h) * 4.0 + r(1.0 - 2.0 * h)) / (2.0 * h)
    };
    (0..n)
        .map(|i| {
            let prev = (i + n - 1) % n;
            CornerData {
                p: sides[i].start(),
                a: ribs[prev].eval(&sides[prev], 1.0).1,
                b: ribs[i].eval(&sides[i], 0.0).1,
                x: -deriv1(prev),
                y: deriv0(i),
            }
        })
        .collect()
}
