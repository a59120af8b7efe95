//! The 4-sided Gregory patch (Gregory 1974/1982; H-rep paper §3.2.1): a bicubically blended
//! Coons patch `P1 + P2 − P12` whose corner twists are replaced by rational combinations of the
//! two ribbons' derivatives along the sides, so incompatible twists at a corner are no obstacle.
//!
//! On the unit square, side 0 is `v = 0` (u increasing), side 1 is `u = 1` (v increasing),
//! side 2 is `v = 1` (u decreasing) and side 3 is `u = 0` (v decreasing): the face's
//! counter-clockwise order. With cubic Hermite functions `H0…H3`,
//!
//! `P1 = H0(u)·L(v) + H1(u)·L_u(v) + H2(u)·R(v) + H3(u)·R_u(v)` (left/right boundaries and
//! their cross derivatives), `P2` the same in `v` for bottom/top, and `P12` the tensor-product
//! Hermite interpolant of the corner positions, first derivatives and the rational twists, e.g.
//! at (0,0): `F_uv = (u·∂L_u/∂v + v·∂B_v/∂u) / (u + v)`. The cross derivatives are the side
//! ribbons `R_i` (see `ribbon`), signed for the square's axes.

use glam::{DVec2, DVec3};

use super::boundary::PreparedSide;
use super::corner::CornerData;
use super::hermite::hermite_basis;
use super::ribbon::PreparedRibbon;

/// A corner of the unit square for the tensor-product Hermite interpolant `P12`: position,
/// derivatives along `u` and `v` and twist `∂²/∂u∂v`, in the square's axes.
#[derive(Clone, Copy, Debug)]
struct CornerJet {
    p: DVec3,
    du: DVec3,
    dv: DVec3,
    twist: DVec3,
}

/// The two ribbons of opposite sides sampled at one parameter of the square: side `i` at `w`
/// and side `i + 2` at `1 − w` (position and cross derivative each). Sides 0 and 2 depend on
/// `u` only, sides 1 and 3 on `v` only, so a tensor grid samples each once per column or row.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RibbonPair {
    near: (DVec3, DVec3),
    far: (DVec3, DVec3),
}

impl RibbonPair {
    /// Sides `i` and `i + 2` (`i` 0 for `u`, 1 for `v`) at parameter `w` of the square.
    #[inline]
    pub(crate) fn at(sides: &[PreparedSide], ribbons: &[PreparedRibbon], i: usize, w: f64) -> Self {
        RibbonPair {
            near: ribbons[i].eval(&sides[i], w),
            far: ribbons[i + 2].eval(&sides[i + 2], 1.0 - w),
        }
    }

    /// The pair sampled by [`RibbonPair::at`] for sides `i` and `i + 2` at `w`, its ribbons as
    /// the patch extrapolates them at `h`, the square's other parameter (side `i` at distance
    /// `h` from it for the bottom side, `1 − h` for the right side; side `i + 2` at the
    /// rest): a knuckle's step spread inside the face (`ribbon::Fan`).
    #[inline]
    fn inside(self, ribbons: &[PreparedRibbon], i: usize, w: f64, h: f64) -> Self {
        let (near, far) = if i == 0 { (h, 1.0 - h) } else { (1.0 - h, h) };
        RibbonPair {
            near: (self.near.0, ribbons[i].inside(self.near.1, w, near)),
            far: (self.far.0, ribbons[i + 2].inside(self.far.1, 1.0 - w, far)),
        }
    }
}

/// Whether any ribbon of the patch spreads a knuckle inside the face (`ribbon::Fan`): its
/// ribbons then depend on both parameters of the square.
#[inline]
pub(crate) fn fanned(ribbons: &[PreparedRibbon]) -> bool {
    ribbons.iter().any(PreparedRibbon::has_fans)
}

/// [`blend`] with the ribbon pairs sampled at `u` and `v` taken as the patch extrapolates them
/// there ([`RibbonPair::inside`]) where the patch has a knuckle inside ([`fanned`]).
#[inline]
pub(crate) fn blend_inside(
    ribbons: &[PreparedRibbon],
    corners: &[CornerData],
    u: f64,
    v: f64,
    along_u: &RibbonPair,
    along_v: &RibbonPair,
) -> DVec3 {
    let along_u = along_u.inside(ribbons, 0, u, v);
    let along_v = along_v.inside(ribbons, 1, v, u);
    blend(corners, u, v, &along_u, &along_v)
}

/// A parameter of the square as the patch takes it: clamped into [0, 1], NaN as ½.
#[inline]
pub(crate) fn square_parameter(w: f64) -> f64 {
    if w.is_nan() {
        0.5
    } else {
        w.clamp(0.0, 1.0)
    }
}

/// Evaluate the Gregory patch at `(u, v)` (clamped into the unit square).
#[inline]
pub(crate) fn eval(
    sides: &[PreparedSide],
    ribbons: &[PreparedRibbon],
    corners: &[CornerData],
    x: DVec2,
) -> DVec3 {
    let (u, v) = (square_parameter(x.x), square_parameter(x.y));
    let along_u = RibbonPair::at(sides, ribbons, 0, u);
    let along_v = RibbonPair::at(sides, ribbons, 1, v);
    blend_sampled(ribbons, corners, fanned(ribbons), u, v, &along_u, &along_v)
}

/// The patch at `(u, v)` from its ribbon pairs sampled there: [`blend_inside`] where its
/// ribbons spread a knuckle inside the face (`fanned`, [`fanned`] of them), else [`blend`].
#[inline]
pub(crate) fn blend_sampled(
    ribbons: &[PreparedRibbon],
    corners: &[CornerData],
    fanned: bool,
    u: f64,
    v: f64,
    along_u: &RibbonPair,
    along_v: &RibbonPair,
) -> DVec3 {
    if fanned {
        blend_inside(ribbons, corners, u, v, along_u, along_v)
    } else {
        blend(corners, u, v, along_u, along_v)
    }
}

/// The Gregory patch at `(u, v)` (in the square) from its ribbons sampled there: `along_u`
/// the bottom and top sides at `u`, `along_v` the right and left sides at `v`
/// ([`RibbonPair::at`]). [`eval`] is this with the ribbons sampled for the one point; a grid
/// samples them once per column and row, with the same result bit for bit.
#[inline]
pub(crate) fn blend(
    corners: &[CornerData],
    u: f64,
    v: f64,
    along_u: &RibbonPair,
    along_v: &RibbonPair,
) -> DVec3 {
    let ((b, bv), (t, t2)) = (along_u.near, along_u.far);
    let ((r, r1), (l, lu)) = (along_v.near, along_v.far);
    let (ru, tv) = (-r1, -t2);
    let hu = hermite_basis(u);
    let hv = hermite_basis(v);
    let p1 = l * hu[0] + lu * hu[1] + r * hu[2] + ru * hu[3];
    let p2 = b * hv[0] + bv * hv[1] + t * hv[2] + tv * hv[3];
    let [c0, c1, c2, c3] = [&corners[0], &corners[1], &corners[2], &corners[3]];
    // Corner data in the square's axes.
    let jet = |p, du, dv, w| CornerJet {
        p,
        du,
        dv,
        twist: w,
    };
    // Corner `i`'s twist takes its local parameters (`u` along side `i`, `v` along side
    // `i − 1` from the corner).
    let k00 = jet(c0.p, c0.a, c0.b, c0.twist(u, v));
    let k10 = jet(c1.p, -c1.b, c1.a, -c1.twist(v, 1.0 - u));
    let k11 = jet(c2.p, -c2.a, -c2.b, c2.twist(1.0 - u, 1.0 - v));
    let k01 = jet(c3.p, c3.b, -c3.a, -c3.twist(1.0 - v, u));
    let term = |k: CornerJet, pu: f64, du: f64, pv: f64, dv: f64| {
        k.p * (pu * pv) + k.du * (du * pv) + k.dv * (pu * dv) + k.twist * (du * dv)
    };
    let p12 = term(k00, hu[0], hu[1], hv[0], hv[1])
        + term(k10, hu[2], hu[3], hv[0], hv[1])
        + term(k11, hu[2], hu[3], hv[2], hv[3])
        + term(k01, hu[0], hu[1], hv[2], hv[3]);
    p1 + p2 - p12
}
