//! The curvature of a patch at a point of its domain: Gaussian and mean curvature from the first
//! and second fundamental forms (do Carmo, *Differential Geometry of Curves and Surfaces*,
//! §3-3, eqs. (4) and (5)), the second derivatives taken by central differences of the patch
//! itself, so the figures are those of the exact surface the hull is made of (not of its mesh).

use glam::{DVec2, DVec3};

use super::domain::Domain;
use super::face_patch::Patch;

/// Step of the central differences in the unit-size domain. The patches' points are exact to
/// the last bits, so the rounding error of a second difference is about `ε |P| / h²` (2e-8 m
/// for a point 100 m from the origin), against a truncation error of `h² |P⁗| / 12` (1e-7 of
/// the patch's size): both far below what a colour map or a fairness check can show.
const CURVATURE_STEP: f64 = 1e-3;

/// The curvature of a surface at a point ([`Patch::curvature`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceCurvature {
    /// Gaussian curvature `K = κ₁κ₂` (1/m²): positive where the surface is curved the same way
    /// in every direction (a bilge, a bulb), negative on a saddle (the run into a skeg), zero
    /// where it is flat or developable.
    pub gaussian: f64,
    /// Mean curvature `H = (κ₁ + κ₂)/2` (1/m), positive where the surface bends towards the
    /// side its normal `∂P/∂u × ∂P/∂v` points away from (convex seen from that side).
    pub mean: f64,
}

impl Patch {
    /// Gaussian and mean curvature at domain point `x` (do Carmo §3-3: `K = (LN − M²)/(EG − F²)`,
    /// `H = −(EN − 2FM + GL) / (2(EG − F²))` with the sign of [`SurfaceCurvature::mean`]).
    /// Where the nine-point difference stencil would leave the domain (near its boundary), the
    /// figures are taken at the nearest point towards the domain's centre where it fits: a few
    /// thousandths of the patch across, so boundary vertices show the curvature just inside
    /// their patch. `None` where the patch is singular (`∂P/∂u × ∂P/∂v` vanishes, as at a
    /// collapsed corner) or not finite.
    pub fn curvature(&self, x: [f64; 2]) -> Option<SurfaceCurvature> {
        let h = CURVATURE_STEP;
        let domain = self.domain();
        let centre = domain.centre_v();
        let mut at = domain.clamp(DVec2::from(x));
        let mut inward = 2.0 * h;
        while !stencil_fits(domain, at, h) {
            let to_centre = centre - at;
            if to_centre.length() <= inward {
                at = centre;
                break;
            }
            at += to_centre.normalize() * inward;
            inward *= 2.0;
        }
        let [_, pu, pv, puu, puv, pvv] = central_differences(|y| self.eval_v(y), at, h);
        fundamental_forms(pu, pv, puu, puv, pvv)
    }
}

/// Whether the nine-point stencil of [`central_differences`] at `x` with step `h` lies in the
/// (convex) domain: its four corners do.
pub(crate) fn stencil_fits(domain: &Domain, x: DVec2, h: f64) -> bool {
    [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
        .iter()
        .all(|&(a, b)| domain.contains((x + DVec2::new(a, b) * h).to_array()))
}

/// `[S, S_u, S_v, S_uu, S_uv, S_vv]` of the surface `s` at `x` by central differences with
/// step `h` on the nine points `x + (i, j)·h`, `i, j ∈ {−1, 0, 1}`.
pub(crate) fn central_differences(s: impl Fn(DVec2) -> DVec3, x: DVec2, h: f64) -> [DVec3; 6] {
    let p = |du: f64, dv: f64| s(x + DVec2::new(du, dv) * h);
    let p0 = p(0.0, 0.0);
    let (pe, pw, pn, ps) = (p(1.0, 0.0), p(-1.0, 0.0), p(0.0, 1.0), p(0.0, -1.0));
    [
        p0,
        (pe - pw) / (2.0 * h),
        (pn - ps) / (2.0 * h),
        (pe - p0 * 2.0 + pw) / (h * h),
        (p(1.0, 1.0) - p(1.0, -1.0) - p(-1.0, 1.0) + p(-1.0, -1.0)) / (4.0 * h * h),
        (pn - p0 * 2.0 + ps) / (h * h),
    ]
}

/// Gaussian and mean curvature from the first derivatives and the second derivatives of a
/// parametrisation (the normal `pu × pv`); `None` where `pu × pv` vanishes or a figure is not
/// finite.
pub(crate) fn fundamental_forms(
    pu: DVec3,
    pv: DVec3,
    puu: DVec3,
    puv: DVec3,
    pvv: DVec3,
) -> Option<SurfaceCurvature> {
    let cross = pu.cross(pv);
    let (e, f, g) = (pu.dot(pu), pu.dot(pv), pv.dot(pv));
    let det = e * g - f * f;
    // Singular where the parametrisation's area element is below 1e-12 of its scale.
    let regular = cross.length_squared() > 1e-24 * e * g && det > 0.0;
    if !regular {
        return None; // also where a figure is NaN
    }
    let n = cross.normalize();
    let (l, m, nn) = (puu.dot(n), puv.dot(n), pvv.dot(n));
    let gaussian = (l * nn - m * m) / det;
    let mean = -(e * nn - 2.0 * f * m + g * l) / (2.0 * det);
    (gaussian.is_finite() && mean.is_finite()).then_some(SurfaceCurvature { gaussian, mean })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sphere_parametrised_by_longitude_and_latitude_has_k_one_over_r_squared() {
        // P(u, v) = R (cos v cos u, cos v sin u, sin v): outward normal pu × pv for this order?
        // pu = R cos v (−sin u, cos u, 0), pv = R (−sin v cos u, −sin v sin u, cos v):
        // pu × pv = R² cos v (cos v cos u, cos v sin u, sin v), outward. Seen from outside, the
        // sphere is convex, so H = +1/R with the convention of SurfaceCurvature::mean.
        let r = 2.5;
        let (u, v) = (0.3_f64, 0.4_f64);
        let pu = DVec3::new(-v.cos() * u.sin(), v.cos() * u.cos(), 0.0) * r;
        let pv = DVec3::new(-v.sin() * u.cos(), -v.sin() * u.sin(), v.cos()) * r;
        let puu = DVec3::new(-v.cos() * u.cos(), -v.cos() * u.sin(), 0.0) * r;
        let puv = DVec3::new(v.sin() * u.sin(), -v.sin() * u.cos(), 0.0) * r;
        let pvv = DVec3::new(-v.cos() * u.cos(), -v.cos() * u.sin(), -v.sin()) * r;
        let c = fundamental_forms(pu, pv, puu, puv, pvv).expect("regular");
        assert!(
            (c.gaussian - 1.0 / (r * r)).abs() < 1e-12,
            "K {}",
            c.gaussian
        );
        assert!((c.mean - 1.0 / r).abs() < 1e-12, "H {}", c.mean);
        // Seen from inside (the normal turned round by swapping u and v) it is concave.
        let c = fundamental_forms(pv, pu, pvv, puv, puu).expect("regular");
        assert!((c.mean + 1.0 / r).abs() < 1e-12, "H {}", c.mean);
        assert!(
            fundamental_forms(pu, pu, puu, puv, pvv).is_none(),
            "parallel derivatives: singular"
        );
    }
}
