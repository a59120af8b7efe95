//! The side-blended patch: Kato's N-sided interpolant (Kato 1991) of the sides' ribbon
//! surfaces, the fallback for a face whose Charrot–Gregory or Gregory patch folds.
//!
//! For a domain point with perpendicular distances `d_i` to the domain's sides, side `i`
//! contributes its ribbon surface `f_i(s_i) + h_i·R_i(s_i)`, with the side parameter `s_i` of
//! the Charrot–Gregory patch (eq. 1a, `d_{i−1}/(d_{i−1}+d_{i+1})`) and `h_i = d_i / H_i` the
//! distance from the side scaled by the domain's depth `H_i` behind it ([`depths`]); the
//! contributions are blended with weights `Π_{j≠i} d_j²` (normalised). On side `i` every
//! other weight and its first derivative across the side vanish, so the patch interpolates
//! the side curve and its cross derivative lies in the plane of the side tangent and the
//! ribbon: the ribbon planes, and with them G1 to the neighbouring faces, are those of the
//! corner-based patches.
//!
//! What it gives up is the corner interpolants: a corner-based patch sums the displacements of
//! the two sides at each corner, which overshoots where a side curve hooks into a corner of a
//! narrow face (a waterline turning into the keel); here each side is extrapolated only by its
//! own ribbon, and the ribbons of such a patch are limited by the face's width across from
//! them (`ribbon::width_scale`), so the surface stays inside its boundary. Its corners are
//! where it is weakest: the blend of two ribbon surfaces that need not agree to first order
//! there is continuous but not smooth in the parameters, which a B-spline export must follow
//! with many spans.

use glam::{DVec2, DVec3};

use super::boundary::PreparedSide;
use super::domain::Domain;
use super::ribbon::PreparedRibbon;

/// The depth of the domain behind each side: the largest distance of a domain vertex from it
/// (for a triangle its height, for the square 1), so that `h_i` runs from 0 on the side to 1
/// at the far corner.
pub(crate) fn depths(domain: &Domain) -> Vec<f64> {
    let n = domain.sides();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|k| domain.distance(i, domain.vertex(k)))
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Evaluate the side-blended patch at domain point `x` (clamped into the domain).
#[inline]
pub(crate) fn eval(
    domain: &Domain,
    depth: &[f64],
    sides: &[PreparedSide],
    ribbons: &[PreparedRibbon],
    x: DVec2,
) -> DVec3 {
    let n = sides.len();
    let x = domain.clamp(x);
    let d = domain.distances(x);
    let mut acc = DVec3::ZERO;
    let mut wsum = 0.0;
    for i in 0..n {
        let mut w = 1.0;
        for (k, dk) in d[..n].iter().enumerate() {
            if k != i {
                w *= dk * dk;
            }
        }
        if w == 0.0 {
            continue;
        }
        let si = domain.side_parameter(&d, i);
        let (f, r) = ribbons[i].eval(&sides[i], si);
        let h = d[i] / depth[i];
        acc += (f + ribbons[i].inside(r, si, h) * h) * w;
        wsum += w;
    }
    if wsum > 0.0 {
        return acc / wsum;
    }
    // A corner (two distances zero): the corner point.
    let i = (0..n)
        .find(|&i| d[i] == 0.0 && d[(i + n - 1) % n] == 0.0)
        .unwrap_or(0);
    sides[i].point(0.0)
}
