//! The N-sided Charrot–Gregory patch (Charrot & Gregory 1984; H-rep paper §3.2.1, eqs. 1–6).
//!
//! For a domain point X in the regular N-gon with perpendicular side distances `d_i`:
//! side parameters `s_i = d_{i−1}/(d_{i−1}+d_{i+1})` (eq. 1a); at corner `i` (where side `i−1`
//! ends and side `i` starts) the local parameters are `u = s_i` along side `i` and
//! `v = 1 − s_{i−1}` along side `i−1` from the corner (eq. 1b). The corner interpolant is the
//! Boolean sum (eq. 4) of the two side interpolants (eq. 2)
//!
//! `T_a = f_i(u) + v·R_i(u)`, `T_b = f_{i−1}(1 − v) + u·R_{i−1}(1 − v)`
//!
//! minus their tensor product (eq. 3) `T_ab = P + u·A + v·B + u·v·W(u, v)`, where `P` is the
//! corner, `A = R_{i−1}(1)`, `B = R_i(0)` and `W` is Gregory's rational twist
//! `W = (u·(−R'_{i−1}(1)) + v·R'_i(0)) / (u + v)`, which lets each side keep its own twist. The
//! patch is the blend `Σ w_i p_i` (eq. 5) with `w_i = Π_{k∉{i−1,i}} d_k² / Σ_j Π_{k∉{j−1,j}} d_k²`
//! (eq. 6). On side `i` only corners `i` and `i+1` have weight, and both reproduce `f_i` and
//! the ribbon plane there, so the patch interpolates the boundary curves and is tangent to the
//! ribbons (GC¹ to any neighbour built on the same ribbon plane).
//!
//! Implementation note: the side parameter is guarded where eq. 1a is 0/0 (only at the corner
//! opposite a side of a triangle, where that side's corners carry zero weight).

use glam::{DVec2, DVec3};

use super::boundary::PreparedSide;
use super::corner::CornerData;
use super::domain::{Domain, MAX_SIDES};
use super::ribbon::PreparedRibbon;

/// Evaluate the Charrot–Gregory patch at domain point `x` (clamped into the domain).
#[inline]
pub(crate) fn eval(
    domain: &Domain,
    sides: &[PreparedSide],
    ribbons: &[PreparedRibbon],
    corners: &[CornerData],
    x: DVec2,
) -> DVec3 {
    let n = sides.len();
    let x = domain.clamp(x);
    let d = domain.distances(x);
    let mut d2 = [0.0; MAX_SIDES];
    for i in 0..n {
        d2[i] = d[i] * d[i];
    }
    // Eq. 6 numerators: the product of all squared distances except the corner's two sides.
    let mut w = [0.0; MAX_SIDES];
    let mut wsum = 0.0;
    for (i, wi) in w[..n].iter_mut().enumerate() {
        let prev = (i + n - 1) % n;
        let mut p = 1.0;
        for (k, dk) in d2[..n].iter().enumerate() {
            if k != i && k != prev {
                p *= dk;
            }
        }
        *wi = p;
        wsum += p;
    }
    // Eq. 1a side parameters; a side is evaluated only when one of its corners has weight.
    let mut s = [0.0; MAX_SIDES];
    for (i, si) in s[..n].iter_mut().enumerate() {
        *si = domain.side_parameter(&d, i);
    }
    let mut f = [DVec3::ZERO; MAX_SIDES];
    let mut r = [DVec3::ZERO; MAX_SIDES];
    for i in 0..n {
        if w[i] > 0.0 || w[(i + 1) % n] > 0.0 {
            (f[i], r[i]) = ribbons[i].eval(&sides[i], s[i]);
        }
    }
    let mut acc = DVec3::ZERO;
    for i in 0..n {
        if w[i] == 0.0 {
            continue;
        }
        let prev = (i + n - 1) % n;
        let u = s[i];
        let v = 1.0 - s[prev];
        let c = &corners[i];
        // Each ribbon as the patch extrapolates it this far from its side (a knuckle's step
        // spread inside the face, `ribbon::Fan`).
        let ta = f[i] + ribbons[i].inside(r[i], s[i], v) * v;
        let tb = f[prev] + ribbons[prev].inside(r[prev], s[prev], u) * u;
        let tab = c.p + c.a * u + c.b * v + c.twist(u, v) * (u * v);
        acc += (ta + tb - tab) * w[i];
    }
    acc / wsum
}
