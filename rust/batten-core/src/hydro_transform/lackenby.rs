//! Lackenby's model of the PMB mode (Lackenby 1950, the general case with a parallel middle
//! body): each end of the hull is stretched or squeezed along x between the PMB's end and the
//! hull's end, its sectional areas keeping their values and moving affinely.
//!
//! With `e`, `r` the entrance and run lengths, `V_E`, `V_R` their volumes and `M_E`, `M_R`
//! their first moments about the bow and stern ends `X_E`, `X_R`, and `A_m` the PMB's section
//! area: `∇(e, r) = A_m (X_E − e − X_R − r) + V_E e/e₀ + V_R r/r₀` and
//! `∇·LCB = A_m (x_f² − x_a²)/2 + X_E V_E e/e₀ + M_E (e/e₀)² + X_R V_R r/r₀ + M_R (r/r₀)²`
//! with `x_f = X_E − e`, `x_a = X_R + r`.

use crate::error::Error;
use crate::form::{FormError, ParallelMiddleBody};
use crate::hydro::{sectional_areas, Datums, Flotation, PatchHydroModel};

/// Intervals of the Simpson rule over each end for the model's volumes and moments.
const MODEL_INTERVALS: usize = 40;

/// The hull's ends and PMB as the model sees them.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lackenby {
    x_e: f64,
    x_r: f64,
    e0: f64,
    r0: f64,
    area: f64,
    v_e: f64,
    m_e: f64,
    v_r: f64,
    m_r: f64,
}

impl Lackenby {
    /// The model of the hull `cells` floating at `flotation`: the ends from `x_range` to the
    /// PMB's ends, integrated on the exact sectional areas.
    pub(super) fn of(
        cells: &PatchHydroModel,
        flotation: &Flotation,
        datums: &Datums,
        pmb: &ParallelMiddleBody,
        x_range: [f64; 2],
    ) -> Result<Lackenby, FormError> {
        let (x_r, x_e) = (x_range[0], x_range[1]);
        let (v_e, m_e) = end_integrals(cells, flotation, datums, pmb.fwd, x_e, x_e)?;
        let (v_r, m_r) = end_integrals(cells, flotation, datums, x_r, pmb.aft, x_r)?;
        let area =
            sectional_areas(cells, flotation, datums, &[pmb.position]).map_err(Error::from)?[0];
        Ok(Lackenby {
            x_e,
            x_r,
            e0: x_e - pmb.fwd,
            r0: pmb.aft - x_r,
            area,
            v_e,
            m_e,
            v_r,
            m_r,
        })
    }

    /// Model ∇ and LCB at entrance length `e` and run length `r`.
    pub(super) fn eval(&self, e: f64, r: f64) -> (f64, f64) {
        let (fe, fr) = (e / self.e0, r / self.r0);
        let (xf, xa) = (self.x_e - e, self.x_r + r);
        let v = self.area * (xf - xa) + self.v_e * fe + self.v_r * fr;
        let m = 0.5 * self.area * (xf * xf - xa * xa)
            + self.x_e * self.v_e * fe
            + self.m_e * fe * fe
            + self.x_r * self.v_r * fr
            + self.m_r * fr * fr;
        (v, m / v)
    }

    /// The model's Jacobian of `(∇/volume, LCB/lpp)` in `(e, r)` at `(e, r)`, by central
    /// differences of the model.
    pub(super) fn jacobian(&self, e: f64, r: f64, volume: f64, lpp: f64) -> [[f64; 2]; 2] {
        let h = 1e-4 * (self.x_e - self.x_r);
        let col = |de: f64, dr: f64| {
            let (v1, l1) = self.eval(e + de, r + dr);
            let (v0, l0) = self.eval(e - de, r - dr);
            [(v1 - v0) / (2.0 * h) / volume, (l1 - l0) / (2.0 * h) / lpp]
        };
        let (ce, cr) = (col(h, 0.0), col(0.0, h));
        [[ce[0], cr[0]], [ce[1], cr[1]]]
    }
}

/// Simpson's volume and first moment about `about` of the sectional areas over `[a, b]`.
fn end_integrals(
    cells: &PatchHydroModel,
    flotation: &Flotation,
    datums: &Datums,
    a: f64,
    b: f64,
    about: f64,
) -> Result<(f64, f64), FormError> {
    let n = MODEL_INTERVALS;
    let xs: Vec<f64> = (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect();
    let areas = sectional_areas(cells, flotation, datums, &xs).map_err(Error::from)?;
    let h = (b - a) / n as f64;
    let (mut v, mut m) = (0.0, 0.0);
    for (k, (&x, &area)) in xs.iter().zip(&areas).enumerate() {
        let w = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        v += w * area;
        m += w * area * (x - about);
    }
    Ok((v * h / 3.0, m * h / 3.0))
}
