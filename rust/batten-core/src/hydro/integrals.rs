//! The surface integrals every hydrostatic figure is made of (divergence theorem on the wet
//! surface, closed by the waterplane): volume and its moments, wetted area, and the waterplane's
//! area, moments and second moments — all as integrals over the wet surface alone.
//!
//! With `ζ` the height above the water and `n` the outward unit normal, the region `Ω` under the
//! water is bounded by the wet surface `S` and the waterplane `W`, on which `ζ = 0` and
//! `n = e3`. For `F = ζ e3`, `div F = 1` and `F = 0` on `W`, so `∇ = ∫_S ζ n_ζ dA`; likewise
//! `∫_Ω ξ dV = ∫_S ξ ζ n_ζ dA`, `∫_Ω ζ dV = ∫_S ½ζ² n_ζ dA`. For `g(ξ, η)`, `∮ g n_ζ = 0`
//! over `∂Ω`, so `∫_W g dA = −∫_S g n_ζ dA`: the waterplane's area and moments need no curve.
//! A half hull's centreplane (normal `∓y`, `n_ζ = 0` when upright) adds nothing to any of them.

use glam::DVec3;

use super::waterplane::Waterplane;

/// Integrals over the wet surface in the earth frame of a [`Waterplane`] (ξ, η, ζ about its
/// origin), summed from quadrature points with [`WetIntegrals::add_point`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WetIntegrals {
    /// `∇ = ∫ ζ n_ζ dA`, m³.
    pub volume: f64,
    /// `∫ ξ dV`, m⁴.
    pub v_xi: f64,
    /// `∫ η dV`, m⁴.
    pub v_eta: f64,
    /// `∫ ζ dV`, m⁴.
    pub v_zeta: f64,
    /// Wetted area `∫ dA`, m².
    pub wetted: f64,
    /// Waterplane area `−∫ n_ζ dA`, m².
    pub wp_area: f64,
    /// `∫_W ξ dA`, m³.
    pub wp_xi: f64,
    /// `∫_W η dA`, m³.
    pub wp_eta: f64,
    /// `∫_W ξ² dA`, m⁴.
    pub wp_xixi: f64,
    /// `∫_W η² dA`, m⁴.
    pub wp_etaeta: f64,
    /// `∫_W ξη dA`, m⁴.
    pub wp_xieta: f64,
}

impl WetIntegrals {
    /// Add one quadrature point: `q = (ξ, η, ζ)` its earth coordinates, `n_zeta` the earth-vertical
    /// component of its weighted outward normal (normal × area element × weight) and `area` its
    /// weighted area element.
    #[inline]
    pub fn add_point(&mut self, q: DVec3, n_zeta: f64, area: f64) {
        let (xi, eta, zeta) = (q.x, q.y, q.z);
        let v = zeta * n_zeta;
        self.volume += v;
        self.v_xi += xi * v;
        self.v_eta += eta * v;
        self.v_zeta += 0.5 * zeta * v;
        self.wetted += area;
        self.wp_area -= n_zeta;
        self.wp_xi -= xi * n_zeta;
        self.wp_eta -= eta * n_zeta;
        self.wp_xixi -= xi * xi * n_zeta;
        self.wp_etaeta -= eta * eta * n_zeta;
        self.wp_xieta -= xi * eta * n_zeta;
    }

    /// Add a ship point `p` with weighted outward normal `n` and area element `area`, taking its
    /// earth coordinates in `plane`.
    #[inline]
    pub fn add_ship_point(&mut self, plane: &Waterplane, p: DVec3, n: DVec3, area: f64) {
        self.add_point(plane.earth(p), plane.e3.dot(n), area);
    }

    /// The integrals of a half hull and its mirror image `y → −y` together, for an upright
    /// waterplane (the image floats the same way: twice each integral, the transverse moments
    /// cancelling).
    pub fn with_mirror_upright(self) -> WetIntegrals {
        WetIntegrals {
            volume: 2.0 * self.volume,
            v_xi: 2.0 * self.v_xi,
            v_eta: 0.0,
            v_zeta: 2.0 * self.v_zeta,
            wetted: 2.0 * self.wetted,
            wp_area: 2.0 * self.wp_area,
            wp_xi: 2.0 * self.wp_xi,
            wp_eta: 0.0,
            wp_xixi: 2.0 * self.wp_xixi,
            wp_etaeta: 2.0 * self.wp_etaeta,
            wp_xieta: 0.0,
        }
    }

    /// Whether every integral is finite.
    pub fn is_finite(&self) -> bool {
        self.as_array().iter().all(|v| v.is_finite())
    }

    fn as_array(&self) -> [f64; 11] {
        [
            self.volume,
            self.v_xi,
            self.v_eta,
            self.v_zeta,
            self.wetted,
            self.wp_area,
            self.wp_xi,
            self.wp_eta,
            self.wp_xixi,
            self.wp_etaeta,
            self.wp_xieta,
        ]
    }
}

impl std::ops::AddAssign for WetIntegrals {
    fn add_assign(&mut self, o: WetIntegrals) {
        self.volume += o.volume;
        self.v_xi += o.v_xi;
        self.v_eta += o.v_eta;
        self.v_zeta += o.v_zeta;
        self.wetted += o.wetted;
        self.wp_area += o.wp_area;
        self.wp_xi += o.wp_xi;
        self.wp_eta += o.wp_eta;
        self.wp_xixi += o.wp_xixi;
        self.wp_etaeta += o.wp_etaeta;
        self.wp_xieta += o.wp_xieta;
    }
}

impl std::ops::Add for WetIntegrals {
    type Output = WetIntegrals;
    fn add(mut self, o: WetIntegrals) -> WetIntegrals {
        self += o;
        self
    }
}

impl std::iter::Sum for WetIntegrals {
    fn sum<I: Iterator<Item = WetIntegrals>>(iter: I) -> WetIntegrals {
        iter.fold(WetIntegrals::default(), |a, b| a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube `[0,1]³` under water to `ζ = 0` at its top: the bottom face alone carries
    /// `n_ζ`, so one midpoint per face gives the exact integrals.
    #[test]
    fn a_cube_below_its_top() {
        let plane = Waterplane::level(1.0);
        let mut w = WetIntegrals::default();
        // Bottom (n = −z) at z = 0: ζ = −1.
        w.add_ship_point(&plane, DVec3::new(0.5, 0.5, 0.0), -DVec3::Z, 1.0);
        // Four sides (n horizontal) add area only.
        for n in [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y] {
            w.add_ship_point(&plane, DVec3::new(0.5, 0.5, 0.5) + n * 0.5, n, 1.0);
        }
        assert!((w.volume - 1.0).abs() < 1e-15, "volume {}", w.volume);
        assert!((w.v_zeta / w.volume + 0.5).abs() < 1e-15, "KB below water");
        assert!((w.wp_area - 1.0).abs() < 1e-15, "Awp {}", w.wp_area);
        assert!((w.wetted - 5.0).abs() < 1e-15, "S {}", w.wetted);
    }
}
