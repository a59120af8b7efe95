//! The least change of a curve's control points that meets linear constraints: minimise
//! `Σ |ΔP_j − W_j|²` (a wished move `W`, or none) subject to rows
//! `Σ_c a_c · (d · ΔP_{first+c}) = value` — a point of the curve moving by a given amount along
//! a direction (Fowler & Bartels 1993, as in `NurbsCurve::through`, but on the given knots:
//! fairing keeps its knots between rounds), or a smooth joint keeping its ratio.
//!
//! The solution is `ΔP = W + Σ_a y_a a_a d_a` with `G y = value − A W`, `G_ab = Σ a_a a_b (d_a·d_b)`
//! over the control points the two rows share (Lagrange multipliers), solved by Cholesky.

use glam::DVec3;

use crate::curve::JOINT_ROW_WIDTH;
use crate::curve::{cholesky_solve, rational_basis, smooth_joint_rows, NurbsCurve, MAX_ORDER};

/// One linear constraint on the change of a curve's control points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Row {
    /// Index of the first control point the row involves.
    pub first: usize,
    /// Coefficients of the control points from `first` on (zeros past the row's width).
    pub coefficients: [f64; MAX_ORDER],
    /// The direction (unit vector) along which the combination is constrained.
    pub direction: DVec3,
    /// The required value of the combination along `direction` (m).
    pub value: f64,
}

/// A row asking the curve's point at `t` to move by `value` along `direction`.
pub(crate) fn point_row(curve: &NurbsCurve, t: f64, direction: DVec3, value: f64) -> Row {
    let (first, coefficients) = rational_basis(curve, t);
    Row {
        first,
        coefficients,
        direction,
        value,
    }
}

/// The rows keeping every smooth joint of multiplicity `degree` smooth (see
/// `NurbsCurve::through`), one per direction of `directions` (the curve's plane).
pub(crate) fn joint_rows(curve: &NurbsCurve, directions: &[DVec3]) -> Vec<Row> {
    smooth_joint_rows(curve)
        .into_iter()
        .flat_map(|(first, coefficients)| {
            directions.iter().map(move |&direction| Row {
                first,
                coefficients,
                direction,
                value: 0.0,
            })
        })
        .collect()
}

/// The change of `wish.len()` control points nearest to `wish` that meets every row, or `None`
/// when the rows cannot all be met (they are dependent: more constraints on a stretch than it
/// has control points, or two rows asking the same thing).
pub(crate) fn least_change(wish: &[DVec3], rows: &[Row], order: usize) -> Option<Vec<DVec3>> {
    let n = wish.len();
    let m = rows.len();
    if m == 0 {
        return Some(wish.to_vec());
    }
    let width = order.clamp(JOINT_ROW_WIDTH, MAX_ORDER);
    let window = |first: usize| first..(first + width).min(n);
    let mut gram = vec![0.0; m * m];
    let mut rhs = Vec::with_capacity(m);
    for (i, a) in rows.iter().enumerate() {
        let wa = window(a.first);
        for (j, b) in rows.iter().enumerate().skip(i) {
            let wb = window(b.first);
            let (lo, hi) = (wa.start.max(wb.start), wa.end.min(wb.end));
            let dot = a.direction.dot(b.direction);
            let g: f64 = (lo..hi)
                .map(|c| a.coefficients[c - a.first] * b.coefficients[c - b.first])
                .sum::<f64>()
                * dot;
            gram[i * m + j] = g;
            gram[j * m + i] = g;
        }
        let moved: f64 = wa
            .map(|c| a.coefficients[c - a.first] * a.direction.dot(wish[c]))
            .sum();
        // The Cholesky solver takes vector right-hand sides; this one is scalar (in x).
        rhs.push(DVec3::new(a.value - moved, 0.0, 0.0));
    }
    let y = cholesky_solve(gram, m, rhs)?;
    let mut change = wish.to_vec();
    for (row, y) in rows.iter().zip(&y) {
        for c in window(row.first) {
            change[c] += y.x * row.coefficients[c - row.first] * row.direction;
        }
    }
    change.iter().all(|d| d.is_finite()).then_some(change)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> NurbsCurve {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let pts = (0..5).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        NurbsCurve::try_new(3, knots, pts, None).expect("valid cubic")
    }

    #[test]
    fn rows_are_met_and_the_rest_follows_the_wish() {
        let c = cubic();
        let wish = vec![DVec3::Y * 0.1; 5];
        let rows = [
            point_row(&c, 0.0, DVec3::Y, 0.0),
            point_row(&c, 1.0, DVec3::Y, 0.0),
            point_row(&c, 0.3, DVec3::Y, 0.05),
        ];
        let change = least_change(&wish, &rows, c.order()).expect("independent rows");
        for row in &rows {
            let moved: f64 = (0..c.order())
                .filter(|k| row.first + k < 5)
                .map(|k| row.coefficients[k] * row.direction.dot(change[row.first + k]))
                .sum();
            assert!(
                (moved - row.value).abs() < 1e-12,
                "row met: {moved} vs {}",
                row.value
            );
        }
        assert!(
            change.iter().all(|d| d.x == 0.0 && d.z == 0.0),
            "only along y: {change:?}"
        );
    }

    #[test]
    fn dependent_rows_are_refused() {
        let c = cubic();
        let rows: Vec<Row> = (0..7)
            .map(|i| point_row(&c, i as f64 / 6.0, DVec3::Y, 0.01))
            .collect();
        assert!(
            least_change(&[DVec3::ZERO; 5], &rows, c.order()).is_none(),
            "7 rows, 5 points"
        );
    }
}
