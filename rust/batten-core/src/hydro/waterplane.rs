//! Where the hull floats: the draft, trim and heel of [`Flotation`], the perpendiculars of
//! [`Datums`], and the [`Waterplane`] they make, with its earth frame (ξ forward along the
//! water surface, η across it, ζ up from it).
//!
//! Conventions (ITTC symbols, SI units, batten's ship axes: x forward, y to port, z up from the
//! baseline): `draft` is the draft at the midpoint of the perpendiculars; `trim = T_AP − T_FP`,
//! positive by the stern; `heel` positive to starboard (the starboard side, `y < 0`, goes down).
//! The water surface in the ship's axes is the plane
//! `z = T − (x − x_mid)·tan θ − y·tan φ`, with `tan θ = trim / Lpp`, `tan φ = tan heel`.

use glam::DVec3;

use super::error::HydroError;

/// The default density of sea water, t/m³ (ITTC 2011 fresh-water/sea-water tables at 15 °C
/// round to 1.025).
pub const SEA_WATER_DENSITY: f64 = 1.025;

/// How the hull floats: draft at the midpoint of the perpendiculars (m), trim (m, `T_AP − T_FP`,
/// by the stern positive), heel (degrees, to starboard positive) and the water density (t/m³).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flotation {
    /// Draft at the midpoint of the perpendiculars, m above the baseline `z = 0`.
    pub draft: f64,
    /// `T_AP − T_FP`, m; positive by the stern.
    pub trim: f64,
    /// Heel, degrees; positive to starboard.
    pub heel_deg: f64,
    /// Water density, t/m³.
    pub density: f64,
}

impl Flotation {
    /// Upright, level, in sea water at `draft`.
    pub fn at_draft(draft: f64) -> Flotation {
        Flotation {
            draft,
            trim: 0.0,
            heel_deg: 0.0,
            density: SEA_WATER_DENSITY,
        }
    }

    /// Refuse non-finite values, a density that is not positive, and heel of 90° or more.
    pub fn check(&self) -> Result<(), HydroError> {
        for (what, v) in [
            ("draft", self.draft),
            ("trim", self.trim),
            ("heel", self.heel_deg),
            ("density", self.density),
        ] {
            if !v.is_finite() {
                return Err(HydroError::InvalidInput(format!(
                    "{what} {v} must be a finite number"
                )));
            }
        }
        if self.density <= 0.0 {
            return Err(HydroError::InvalidInput(format!(
                "density {} t/m³ must be positive",
                self.density
            )));
        }
        if self.heel_deg.abs() >= 90.0 {
            return Err(HydroError::InvalidInput(format!(
                "heel {}° must be less than 90° either way",
                self.heel_deg
            )));
        }
        Ok(())
    }
}

/// The perpendiculars: `x` of the aft (AP) and forward (FP) perpendiculars; `Lpp = x_fp − x_ap`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Datums {
    /// `x` of the aft perpendicular, m.
    pub x_ap: f64,
    /// `x` of the forward perpendicular, m.
    pub x_fp: f64,
}

impl Datums {
    /// Length between perpendiculars.
    pub fn lpp(&self) -> f64 {
        self.x_fp - self.x_ap
    }

    /// `x` of midships, halfway between the perpendiculars.
    pub fn x_mid(&self) -> f64 {
        0.5 * (self.x_ap + self.x_fp)
    }

    /// Refuse non-finite perpendiculars and an `Lpp` that is not positive.
    pub fn check(&self) -> Result<(), HydroError> {
        if !(self.x_ap.is_finite() && self.x_fp.is_finite()) || self.lpp() <= 0.0 {
            return Err(HydroError::InvalidInput(format!(
                "the perpendiculars (AP at x = {}, FP at x = {}) must be finite with FP forward of AP",
                self.x_ap, self.x_fp
            )));
        }
        Ok(())
    }
}

/// The water surface as a plane in the ship's axes with an orthonormal earth frame:
/// `e3` its upward unit normal, `e1` the ship's x axis projected on it (forward), `e2 = e3 × e1`
/// (to port when upright), `origin` the point of the plane above midships on the centreline.
/// Earth coordinates of a ship point `p`: `ξ = e1·(p − origin)`, `η = e2·(p − origin)`,
/// `ζ = e3·(p − origin)` (negative below the water).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Waterplane {
    /// Upward unit normal.
    pub e3: DVec3,
    /// Forward unit vector in the plane.
    pub e1: DVec3,
    /// Transverse unit vector in the plane (`e3 × e1`).
    pub e2: DVec3,
    /// `(x_mid, 0, draft)`.
    pub origin: DVec3,
}

impl Waterplane {
    /// The water surface of `flotation` about the perpendiculars `datums`.
    pub fn new(flotation: &Flotation, datums: &Datums) -> Waterplane {
        let tan_trim = flotation.trim / datums.lpp();
        let tan_heel = flotation.heel_deg.to_radians().tan();
        let e3 = DVec3::new(tan_trim, tan_heel, 1.0).normalize();
        let e1 = (DVec3::X - e3 * e3.x).normalize();
        let e2 = e3.cross(e1);
        Waterplane {
            e3,
            e1,
            e2,
            origin: DVec3::new(datums.x_mid(), 0.0, flotation.draft),
        }
    }

    /// A level, upright water surface at height `z` (used for the waterlines of a body plan).
    pub fn level(z: f64) -> Waterplane {
        Waterplane {
            e3: DVec3::Z,
            e1: DVec3::X,
            e2: DVec3::Y,
            origin: DVec3::new(0.0, 0.0, z),
        }
    }

    /// The frame in which a half hull, integrated, gives the integrals of its mirror image
    /// `y → −y` in this plane: every vector and the origin mirrored (a left-handed frame; the
    /// integrals use only its dot products).
    pub fn mirrored(&self) -> Waterplane {
        let m = |v: DVec3| DVec3::new(v.x, -v.y, v.z);
        Waterplane {
            e1: m(self.e1),
            e2: m(self.e2),
            e3: m(self.e3),
            origin: m(self.origin),
        }
    }

    /// Whether the plane is the ship's own `z = const` (no trim, no heel): a half hull's mirror
    /// image then contributes exactly what the half does, its transverse moments cancelling.
    pub fn is_level(&self) -> bool {
        self.e3 == DVec3::Z
    }

    /// Whether `e3` has no transverse component (upright, any trim): the mirror image of a half
    /// hull then floats the same way and its transverse moments cancel.
    pub fn is_upright(&self) -> bool {
        self.e3.y == 0.0
    }

    /// Height of `p` above the water (negative below).
    #[inline]
    pub fn zeta(&self, p: DVec3) -> f64 {
        self.e3.dot(p - self.origin)
    }

    /// Earth coordinates `(ξ, η, ζ)` of ship point `p`.
    #[inline]
    pub fn earth(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(self.e1.dot(d), self.e2.dot(d), self.e3.dot(d))
    }

    /// The ship point with earth coordinates `q = (ξ, η, ζ)`.
    #[inline]
    pub fn ship(&self, q: DVec3) -> DVec3 {
        self.origin + self.e1 * q.x + self.e2 * q.y + self.e3 * q.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trim_by_the_stern_raises_the_water_at_the_ap() {
        let f = Flotation {
            draft: 5.0,
            trim: 2.0,
            heel_deg: 0.0,
            density: 1.0,
        };
        let d = Datums {
            x_ap: 0.0,
            x_fp: 100.0,
        };
        let w = Waterplane::new(&f, &d);
        // The water surface at AP is at T + trim/2, at FP at T − trim/2.
        let at = |x: f64, z: f64| w.zeta(DVec3::new(x, 0.0, z));
        assert!(at(0.0, 6.0).abs() < 1e-12, "AP draft {}", at(0.0, 6.0));
        assert!(at(100.0, 4.0).abs() < 1e-12, "FP draft {}", at(100.0, 4.0));
        let q = DVec3::new(3.0, -2.0, 1.5);
        assert!(
            (w.earth(w.ship(q)) - q).length() < 1e-12,
            "frame round trip"
        );
    }

    #[test]
    fn heel_to_starboard_puts_the_starboard_side_under() {
        let mut f = Flotation::at_draft(5.0);
        f.heel_deg = 10.0;
        let w = Waterplane::new(
            &f,
            &Datums {
                x_ap: 0.0,
                x_fp: 10.0,
            },
        );
        assert!(w.zeta(DVec3::new(5.0, -3.0, 5.0)) < 0.0, "starboard under");
        assert!(w.zeta(DVec3::new(5.0, 3.0, 5.0)) > 0.0, "port out");
        assert!(
            Flotation { density: 0.0, ..f }.check().is_err(),
            "density 0"
        );
    }
}
