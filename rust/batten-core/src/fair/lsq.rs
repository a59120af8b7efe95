//! Banded least squares by Givens rotations, as in Dierckx (1993) §4.1.2 and the FITPACK
//! routines `fpgivs`, `fprota` and `fpback`.
//!
//! Observation rows are rotated one at a time into an upper-triangular band matrix `R` (each row
//! of `R` stores its diagonal and the `band − 1` entries to its right) together with the rotated
//! right-hand sides, one per coordinate. The normal equations are never formed, which keeps the
//! condition number that of the observation matrix, not its square (the reason the H-rep paper
//! chose orthogonalisation).

use glam::DVec3;

/// An upper-triangular band matrix with three right-hand sides, built row by row.
#[derive(Clone, Debug)]
pub(crate) struct BandedQr {
    n: usize,
    band: usize,
    r: Vec<f64>,
    z: Vec<DVec3>,
}

/// Givens rotation annihilating `piv` against the diagonal `diag` (Dierckx `fpgivs`): returns
/// `(cos, sin, new diagonal)`.
///
/// `√(piv² + diag²)` directly rather than `hypot` (several times slower in libm): the entries
/// are B-spline values and rotated sums of them (at most a few times √m), far from overflow.
#[inline]
fn givens(piv: f64, diag: f64) -> (f64, f64, f64) {
    let dd = (piv * piv + diag * diag).sqrt();
    (diag / dd, piv / dd, dd)
}

impl BandedQr {
    /// An empty (all-zero) system of `n` unknowns and bandwidth `band`.
    pub(crate) fn new(n: usize, band: usize) -> Self {
        BandedQr {
            n,
            band,
            r: vec![0.0; n * band],
            z: vec![DVec3::ZERO; n],
        }
    }

    /// Number of unknowns.
    pub(super) fn unknowns(&self) -> usize {
        self.n
    }

    /// Bandwidth.
    pub(super) fn band(&self) -> usize {
        self.band
    }

    /// Row `i` of the triangle (diagonal first) and its rotated right-hand side.
    pub(super) fn row(&self, i: usize) -> (&[f64], DVec3) {
        (&self.r[i * self.band..(i + 1) * self.band], self.z[i])
    }

    /// Overwrite row `i` and its right-hand side.
    pub(super) fn set_row(&mut self, i: usize, row: &[f64], z: DVec3) {
        self.r[i * self.band..(i + 1) * self.band].copy_from_slice(row);
        self.z[i] = z;
    }

    /// Resize to `n` unknowns keeping rows `..keep` and zeroing the rest (for rebuilding the
    /// triangle from the first observation a knot insertion changes).
    pub(super) fn truncate_resize(&mut self, n: usize, keep: usize) {
        let keep = keep.min(self.n).min(n);
        self.n = n;
        self.r.truncate(keep * self.band);
        self.r.resize(n * self.band, 0.0);
        self.z.truncate(keep);
        self.z.resize(n, DVec3::ZERO);
    }

    /// The same triangle in a wider band (the extra columns zero), so that rows with more
    /// non-zeros (the derivative-jump rows of the smoothing term) can be rotated in.
    pub(super) fn widened(&self, band: usize) -> Self {
        debug_assert!(band >= self.band, "widening only");
        let mut out = BandedQr::new(self.n, band);
        for i in 0..self.n {
            out.r[i * band..i * band + self.band]
                .copy_from_slice(&self.r[i * self.band..(i + 1) * self.band]);
        }
        out.z.copy_from_slice(&self.z);
        out
    }

    /// Rotate the row with entries `h` in columns `first..first + h.len()` and right-hand side
    /// `rhs` into the triangle (Dierckx `fpgivs` + `fprota`). `h` is used as scratch space.
    /// Entries at columns `>= n` must be zero. As in Dierckx's ordered processing, the
    /// triangle rows the row meets must have no entries beyond its last column (true when rows
    /// come with non-decreasing last columns, as observations in span order do).
    pub(crate) fn add_row(&mut self, first: usize, h: &mut [f64], rhs: DVec3) {
        // The common widths pass through an array, so that the inlined loop has a constant
        // length and unrolls.
        match h.len() {
            3 => self.rotate_in(
                first,
                &mut <&mut [f64; 3]>::try_from(h).expect("3")[..],
                rhs,
            ),
            4 => self.rotate_in(
                first,
                &mut <&mut [f64; 4]>::try_from(h).expect("4")[..],
                rhs,
            ),
            5 => self.rotate_in(
                first,
                &mut <&mut [f64; 5]>::try_from(h).expect("5")[..],
                rhs,
            ),
            _ => self.rotate_in(first, h, rhs),
        }
    }

    #[inline(always)]
    fn rotate_in(&mut self, first: usize, h: &mut [f64], rhs: DVec3) {
        let len = h.len();
        debug_assert!(len <= self.band, "row wider than the band");
        let mut y = rhs;
        for i in 0..len {
            let j = first + i;
            if j >= self.n {
                break;
            }
            let piv = h[i];
            if piv == 0.0 {
                continue;
            }
            let row = &mut self.r[j * self.band..(j + 1) * self.band];
            let (c, s, d) = givens(piv, row[0]);
            row[0] = d;
            let zj = self.z[j];
            self.z[j] = zj * c + y * s;
            y = y * c - zj * s;
            for l in i + 1..len {
                let (a, b) = (h[l], row[l - i]);
                row[l - i] = c * b + s * a;
                h[l] = c * a - s * b;
            }
        }
    }

    /// Back substitution (Dierckx `fpback`); `None` when a diagonal entry is negligible, i.e.
    /// the observations do not determine every unknown (Schoenberg–Whitney violated), or when
    /// the solution overflows: pivots above the threshold can still be small enough, one after
    /// another, for back substitution to multiply rounding up to infinity (a nearly
    /// interpolating spline with a fixed end tangent on noisy data did), and such a system is
    /// numerically singular just the same.
    pub(crate) fn solve(&self) -> Option<Vec<DVec3>> {
        let n = self.n;
        let b = self.band;
        let scale = (0..n).map(|i| self.r[i * b].abs()).fold(0.0, f64::max);
        // Relative rank threshold: a pivot this far below the largest means the unknown is
        // fixed by rounding noise, not by the data.
        let tiny = scale * 1e-13;
        let mut c = vec![DVec3::ZERO; n];
        for i in (0..n).rev() {
            let row = &self.r[i * b..(i + 1) * b];
            if row[0].abs() <= tiny || row[0].is_nan() {
                return None;
            }
            let mut acc = self.z[i];
            for l in 1..b.min(n - i) {
                acc -= c[i + l] * row[l];
            }
            c[i] = acc / row[0];
            if !c[i].is_finite() {
                return None;
            }
        }
        Some(c)
    }

    /// `(RᵀR)⁻¹ g`, i.e. `(AᵀA)⁻¹ g` for the rows `A` rotated in so far: a forward
    /// substitution with `Rᵀ` and a back substitution with `R` (for the Lagrange correction of
    /// a linearly constrained fit, Lawson & Hanson 1974 ch. 20). `None` on a negligible pivot
    /// or an overflowing solution, as [`BandedQr::solve`].
    pub(super) fn solve_normal(&self, g: &[f64]) -> Option<Vec<f64>> {
        let n = self.n;
        let b = self.band;
        debug_assert_eq!(g.len(), n, "one entry per unknown");
        let scale = (0..n).map(|i| self.r[i * b].abs()).fold(0.0, f64::max);
        let tiny = scale * 1e-13;
        // Rᵀ v = g: column j of R holds R[i][j] = r[i·b + (j − i)] for j − b < i ≤ j.
        let mut v = vec![0.0; n];
        for j in 0..n {
            let d = self.r[j * b];
            if d.abs() <= tiny || d.is_nan() {
                return None;
            }
            let mut acc = g[j];
            let lo = j.saturating_sub(b - 1);
            for (i, vi) in v.iter().enumerate().take(j).skip(lo) {
                acc -= self.r[i * b + (j - i)] * vi;
            }
            v[j] = acc / d;
        }
        // R y = v.
        let mut y = vec![0.0; n];
        for i in (0..n).rev() {
            let row = &self.r[i * b..(i + 1) * b];
            let mut acc = v[i];
            for l in 1..b.min(n - i) {
                acc -= y[i + l] * row[l];
            }
            y[i] = acc / row[0];
            if !y[i].is_finite() {
                return None;
            }
        }
        Some(y)
    }

    /// Sum of the diagonal entries (Dierckx's initial value for p is `n / Σ diag`).
    pub(super) fn diagonal_sum(&self) -> f64 {
        (0..self.n).map(|i| self.r[i * self.band]).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_an_overdetermined_banded_system() {
        // Fit y = a + b x on x = 0..5 as a "band" of width 2 with rows (1, x) in columns 0, 1.
        let mut qr = BandedQr::new(2, 2);
        for x in 0..6 {
            let x = f64::from(x);
            let y = 2.0 + 3.0 * x + if x as i32 % 2 == 0 { 0.1 } else { -0.1 };
            qr.add_row(0, &mut [1.0, x], DVec3::splat(y));
        }
        let c = qr.solve().expect("full rank");
        // Normal equations by hand: the symmetric ±0.1 pattern shifts the LS line slightly.
        let (sx, sxx, n) = (15.0, 55.0, 6.0);
        let ys: Vec<f64> = (0..6)
            .map(|i| 2.0 + 3.0 * f64::from(i) + if i % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let sy: f64 = ys.iter().sum();
        let sxy: f64 = ys.iter().enumerate().map(|(i, y)| i as f64 * y).sum();
        let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let a = (sy - b * sx) / n;
        assert!((c[0].x - a).abs() < 1e-12, "intercept {} vs {a}", c[0].x);
        assert!((c[1].x - b).abs() < 1e-12, "slope {} vs {b}", c[1].x);
    }

    #[test]
    fn solve_normal_inverts_the_normal_matrix() {
        // Rows of a banded 5-unknown problem (in column order, as `add_row` needs); check
        // (AᵀA) y = g with AᵀA formed by hand.
        let rows: Vec<(usize, [f64; 3])> = (0..12)
            .map(|i| {
                let x = f64::from(i) * 0.37;
                (
                    (i as usize) / 4,
                    [1.0 + x.sin(), 0.5 * x.cos(), 0.2 + 0.1 * x],
                )
            })
            .collect();
        let mut qr = BandedQr::new(5, 3);
        let mut ata = [[0.0; 5]; 5];
        for (first, h) in &rows {
            for (a, &ha) in h.iter().enumerate() {
                for (b, &hb) in h.iter().enumerate() {
                    ata[first + a][first + b] += ha * hb;
                }
            }
            qr.add_row(*first, &mut h.clone(), DVec3::ZERO);
        }
        let g = [0.3, -1.0, 2.0, 0.0, 0.7];
        let y = qr.solve_normal(&g).expect("full rank");
        for (i, row) in ata.iter().enumerate() {
            let back: f64 = row.iter().zip(&y).map(|(a, y)| a * y).sum();
            assert!((back - g[i]).abs() < 1e-11, "row {i}: {back} vs {}", g[i]);
        }
    }

    #[test]
    fn rank_deficiency_is_reported() {
        let mut qr = BandedQr::new(2, 2);
        qr.add_row(0, &mut [1.0, 0.0], DVec3::ONE);
        assert!(qr.solve().is_none(), "second unknown undetermined");
    }
}
