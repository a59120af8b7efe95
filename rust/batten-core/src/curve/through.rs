//! The least change of a curve that makes it pass through given points at given parameters:
//! the constrained modification of Fowler & Bartels (1993, "Constraint-based curve
//! manipulation") as in Piegl & Tiller §11.5 — the control points move by the smallest sum of
//! squares that meets the constraints, so the curve keeps its knots, continuity and weights.
//!
//! A knot is inserted first at every interior target parameter that is not yet a knot (Boehm,
//! no change of shape; in the middle of the span instead when the target is near a knot),
//! which gives each target a control point of its own, so the change stays local to the spans
//! around its target. Where the knots put mid-span leave the targets dependent (more of them
//! in a few spans than control points there), a knot halfway between any two neighbouring
//! targets that no knot separates gives each one a span of its own.
//!
//! Continuity at a knot follows from its multiplicity whatever the control points, except at a
//! knot of multiplicity `degree`, where the curve is only C0 by its knots and smooth (G1) only
//! because its three control points there are collinear in a fixed ratio. At each such smooth
//! joint one more linear constraint keeps that ratio (`P₊ − P = r (P − P₋)`, right-hand side
//! zero), so the change keeps the curve smooth there; a corner (a real tangent jump) stays free.

use glam::DVec3;

use super::basis::{basis_funs, ders_basis_funs, find_span, MAX_ORDER};
use super::error::CurveError;
use super::nurbs::NurbsCurve;

/// Targets whose parameters differ by less than this fraction of the domain are one target.
const SAME_PARAMETER: f64 = 1e-12;

/// A target closer to a knot than this share of its span gets its knot in the middle of the
/// span instead: a sliver of a span would make a Bézier piece so short that single-precision
/// control points (Blender's) bend it.
const NEAR_KNOT: f64 = 0.25;

/// A joint of multiplicity `degree` whose two tangent directions differ by less than this
/// (radians, 1°) is smooth, and is kept so: its row keeps the kink vector `P₊ − P − r (P − P₋)`
/// as it is, zero for an exact G1 joint, and the rounding of a joint that went through single
/// precision (about 1e-6 rad) for one that came from Blender. A real corner turns by more.
const SMOOTH_JOINT: f64 = 0.017_453_292_519_943_295;

/// A pivot of the constraint system smaller than this fraction of its diagonal means the
/// targets are not independent (a target the others already fix).
const DEPENDENT_PIVOT: f64 = 1e-12;

/// The `(first index, values)` of the rational basis `R_i(t) = N_i(t)·w_i / Σ N_j(t)·w_j`
/// that is non-zero at `t`: how a change of the Cartesian control points moves `C(t)`.
pub(crate) fn rational_basis(curve: &NurbsCurve, t: f64) -> (usize, [f64; MAX_ORDER]) {
    let p = curve.degree();
    let cw = curve.homogeneous_points();
    let span = find_span(curve.knots(), p, cw.len(), t);
    let mut n = [0.0; MAX_ORDER];
    basis_funs(curve.knots(), span, t, p, &mut n);
    let first = span - p;
    let w: f64 = (0..=p).map(|j| n[j] * cw[first + j].w).sum();
    for j in 0..=p {
        n[j] *= cw[first + j].w / w;
    }
    (first, n)
}

/// Solve `M x = b` for a symmetric positive definite `M` (row-major `m × m`) by Cholesky,
/// three right-hand sides at once; `None` when a pivot shows the rows dependent.
pub(crate) fn cholesky_solve(mut m: Vec<f64>, n: usize, mut b: Vec<DVec3>) -> Option<Vec<DVec3>> {
    for j in 0..n {
        let diag = m[j * n + j] - (0..j).map(|k| m[j * n + k] * m[j * n + k]).sum::<f64>();
        // Also refuses a NaN pivot.
        if diag.is_nan() || diag <= DEPENDENT_PIVOT * m[j * n + j].abs() {
            return None;
        }
        let d = diag.sqrt();
        m[j * n + j] = d;
        for i in j + 1..n {
            let s = m[i * n + j] - (0..j).map(|k| m[i * n + k] * m[j * n + k]).sum::<f64>();
            m[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let s: DVec3 = (0..i).map(|k| m[i * n + k] * b[k]).sum();
        b[i] = (b[i] - s) / m[i * n + i];
    }
    for i in (0..n).rev() {
        let s: DVec3 = (i + 1..n).map(|k| m[k * n + i] * b[k]).sum();
        b[i] = (b[i] - s) / m[i * n + i];
    }
    Some(b)
}

/// Coefficients in a smooth-joint row (the control points before, at and after the joint).
pub(crate) const JOINT_ROW_WIDTH: usize = 3;

/// One constraint row per smooth joint of multiplicity `degree` (module doc): with `P` the
/// control point on the curve at the joint and `r = |P₊ − P| / |P − P₋|`, the row
/// `r·ΔP₋ − (1 + r)·ΔP + ΔP₊ = 0` keeps `P₊ − P = r (P − P₋)`. For a rational curve the
/// Cartesian points keep the ratio while the weights stay, which keeps the tangent direction
/// but not exactly G1 of the homogeneous curve; the fits this serves are polynomial.
pub(crate) fn smooth_joint_rows(curve: &NurbsCurve) -> Vec<(usize, [f64; MAX_ORDER])> {
    let p = curve.degree();
    let knots = curve.knots();
    let pts = curve.control_points();
    let n = pts.len();
    let mut rows = Vec::new();
    let mut i = p + 1;
    while i < n {
        let u = knots[i];
        let mult = knots[i..].iter().take_while(|&&k| k == u).count();
        if mult == p {
            let j = i - 1;
            let (left, right) = (pts[j] - pts[j - 1], pts[j + 1] - pts[j]);
            let (ll, lr) = (left.length(), right.length());
            // The ratio r of the lengths keeps the kink vector right − r·left unchanged.
            if ll > 0.0 && lr > 0.0 && left.angle_between(right) < SMOOTH_JOINT {
                let r = lr / ll;
                let mut row = [0.0; MAX_ORDER];
                row[..JOINT_ROW_WIDTH].copy_from_slice(&[r, -(1.0 + r), 1.0]);
                rows.push((j - 1, row));
            }
        }
        i += mult;
    }
    rows
}

impl NurbsCurve {
    /// The curve changed as little as possible (smallest sum of squared control-point moves,
    /// weights kept) so that `C(t) = q` for every target `(t, q)`: Fowler & Bartels' constrained
    /// modification (Piegl & Tiller §11.5), after inserting a knot at every interior target
    /// parameter that is not yet one.
    ///
    /// Errors: a non-finite parameter or point, a parameter outside the domain, two targets at
    /// one parameter asking for different points ([`CurveError::TargetsConflict`]), targets
    /// the control points cannot all meet ([`CurveError::TargetsDependent`]), a result that
    /// f64 cannot hold.
    pub fn through(&self, targets: &[(f64, DVec3)]) -> Result<NurbsCurve, CurveError> {
        self.through_with_tangents(targets, &[])
    }

    /// [`NurbsCurve::through`] that also gives the curve the first derivative `C'(t) = d` at
    /// each of `tangents` `(t, d)` (each at the parameter of a target, where the target's knot
    /// gives it control points to move): Fowler & Bartels' derivative constraints, in the same
    /// least move. The wireframe import turns the tangents of the curves through a smooth node
    /// into one plane with them (H-rep §3.2.3, Ye & Nowacki 1995). A polynomial curve only:
    /// a rational one's derivative is not linear in its control points.
    ///
    /// Errors: as [`NurbsCurve::through`]; a tangent at a parameter that is not a target's, or
    /// on a rational curve, is [`CurveError::TargetsDependent`]; a non-finite one as a point.
    pub fn through_with_tangents(
        &self,
        targets: &[(f64, DVec3)],
        tangents: &[(f64, DVec3)],
    ) -> Result<NurbsCurve, CurveError> {
        let (start, end) = self.domain();
        for &(t, d) in tangents {
            if !t.is_finite() {
                return Err(CurveError::NonFiniteParameter(t));
            }
            if !d.is_finite() {
                return Err(CurveError::NonFiniteQuery);
            }
            if self.is_rational() || !targets.iter().any(|&(u, _)| u == t) {
                return Err(CurveError::TargetsDependent);
            }
        }
        let mut sorted: Vec<(f64, DVec3)> = Vec::with_capacity(targets.len());
        for &(t, q) in targets {
            if !t.is_finite() {
                return Err(CurveError::NonFiniteParameter(t));
            }
            if !q.is_finite() {
                return Err(CurveError::NonFiniteQuery);
            }
            if !(start..=end).contains(&t) {
                return Err(CurveError::ParameterOutOfDomain { t, start, end });
            }
            sorted.push((t, q));
        }
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let same = SAME_PARAMETER * (end - start);
        let mut unique: Vec<(f64, DVec3)> = Vec::with_capacity(sorted.len());
        for (t, q) in sorted {
            match unique.last() {
                Some(&(u, p)) if t - u <= same => {
                    if p != q {
                        return Err(CurveError::TargetsConflict { t });
                    }
                }
                _ => unique.push((t, q)),
            }
        }
        if unique.is_empty() {
            return Ok(self.clone());
        }
        let mut curve = self.clone();
        for &(t, _) in &unique {
            if t > start && t < end && curve.multiplicity(t) == 0 {
                let knots = curve.knots();
                let right = knots.partition_point(|&u| u <= t);
                let (a, b) = (knots[right - 1], knots[right]);
                let at = if (t - a).min(b - t) > NEAR_KNOT * (b - a) {
                    t
                } else {
                    0.5 * (a + b)
                };
                curve = curve.insert_knot(at, 1)?;
            }
        }
        match constrained_move(&curve, &unique, tangents) {
            // A knot put mid-span can leave two targets in one span, and then more targets near
            // there than control points to meet them: a knot halfway between any two
            // neighbours with none between them gives every target a span of its own.
            Err(CurveError::TargetsDependent) => {
                constrained_move(&separated(curve, &unique)?, &unique, tangents)
            }
            moved => moved,
        }
    }
}

/// `curve` with a knot halfway between any two neighbouring `targets` (sorted) that no knot
/// separates.
fn separated(mut curve: NurbsCurve, targets: &[(f64, DVec3)]) -> Result<NurbsCurve, CurveError> {
    for pair in targets.windows(2) {
        let (t, u) = (pair[0].0, pair[1].0);
        let knots = curve.knots();
        if knots.partition_point(|&k| k <= t) == knots.partition_point(|&k| k < u) {
            curve = curve.insert_knot(0.5 * (t + u), 1)?;
        }
    }
    Ok(curve)
}

/// The `(first index, values)` of the derivative basis `N_i'(t)` of a polynomial curve that is
/// non-zero at `t` (Piegl & Tiller A2.3; at a knot, the span that starts there): how a change of
/// the control points moves `C'(t)`.
fn derivative_basis(curve: &NurbsCurve, t: f64) -> (usize, [f64; MAX_ORDER]) {
    let p = curve.degree();
    let n = curve.control_point_count();
    let span = find_span(curve.knots(), p, n, t);
    let mut ders = [[0.0; MAX_ORDER]; 4];
    ders_basis_funs(curve.knots(), span, t, p, 1, &mut ders);
    (span - p, ders[1])
}

/// Fowler & Bartels' least move of the control points of `curve` (its knots as they are) that
/// meets the sorted, distinct `targets` and the first derivatives `tangents` (a polynomial
/// curve's), keeping its smooth joints smooth.
fn constrained_move(
    curve: &NurbsCurve,
    unique: &[(f64, DVec3)],
    tangents: &[(f64, DVec3)],
) -> Result<NurbsCurve, CurveError> {
    let mut rows: Vec<(usize, [f64; MAX_ORDER])> = unique
        .iter()
        .map(|&(t, _)| rational_basis(curve, t))
        .collect();
    let mut residual: Vec<DVec3> = unique.iter().map(|&(t, q)| q - curve.point(t)).collect();
    for &(t, d) in tangents {
        rows.push(derivative_basis(curve, t));
        residual.push(d - curve.derivs(t).d1);
    }
    for row in smooth_joint_rows(curve) {
        rows.push(row);
        residual.push(DVec3::ZERO);
    }
    let m = rows.len();
    let n = curve.control_point_count();
    // Every row is a window of `width` coefficients from its first control point.
    let width = curve.order().max(JOINT_ROW_WIDTH);
    let window = |first: usize| first..(first + width).min(n);
    let mut gram = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..m {
            let (fi, ri) = &rows[i];
            let (fj, rj) = &rows[j];
            let (a, b) = (window(*fi), window(*fj));
            let (lo, hi) = (a.start.max(b.start), a.end.min(b.end));
            gram[i * m + j] = (lo..hi).map(|c| ri[c - fi] * rj[c - fj]).sum();
        }
    }
    let lambda = cholesky_solve(gram, m, residual).ok_or(CurveError::TargetsDependent)?;
    let mut points = curve.control_points();
    for ((first, r), l) in rows.iter().zip(&lambda) {
        for c in window(*first) {
            points[c] += r[c - first] * *l;
        }
    }
    NurbsCurve::try_new(
        curve.degree(),
        curve.knots().to_vec(),
        points,
        curve.weights(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> NurbsCurve {
        let pts = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 2.0, 1.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(6.0, -1.0, 0.0),
        ];
        NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            pts.to_vec(),
            None,
        )
        .expect("cubic")
    }

    #[test]
    fn it_meets_every_target_and_moves_the_rest_a_little() {
        let c = cubic();
        let targets = [
            (0.0, c.point(0.0) + DVec3::new(0.0, 0.01, 0.0)),
            (0.3, c.point(0.3) + DVec3::new(0.0, 0.0, -0.02)),
            (0.7, c.point(0.7) + DVec3::new(0.01, 0.0, 0.0)),
        ];
        let d = c.through(&targets).expect("through");
        for (t, q) in targets {
            assert!((d.point(t) - q).length() < 1e-12, "at {t}");
        }
        // The change is bounded by the largest correction (2 cm) everywhere.
        let most = (0..=100)
            .map(|i| (d.point(i as f64 / 100.0) - c.point(i as f64 / 100.0)).length())
            .fold(0.0, f64::max);
        assert!((0.02..0.03).contains(&most), "largest change {most}");
        // A target already met changes nothing.
        let same = c.through(&[(0.4, c.point(0.4))]).expect("through");
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            assert!((same.point(t) - c.point(t)).length() < 1e-12);
        }
    }

    #[test]
    fn weights_stay_and_a_rational_curve_meets_its_targets() {
        let c = cubic();
        let w = vec![1.0, 2.0, 0.5, 1.0, 3.0];
        let r = NurbsCurve::try_new(3, c.knots().to_vec(), c.control_points(), Some(w))
            .expect("rational");
        let q = r.point(0.6) + DVec3::new(0.0, 0.05, 0.0);
        let d = r.through(&[(0.6, q)]).expect("through");
        assert!((d.point(0.6) - q).length() < 1e-12);
        assert!(d.is_rational());
    }

    #[test]
    fn a_smooth_joint_of_multiplicity_degree_stays_smooth_and_a_corner_stays_a_corner() {
        // Two cubic pieces joined at u = 1 (knot of multiplicity 3): smooth at P3 (P2, P3, P4
        // collinear), and a second curve with a corner there.
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
        let smooth = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.5, 0.0),
            DVec3::new(3.0, 1.5, 0.0),
            DVec3::new(5.0, 1.5, 0.0),
            DVec3::new(6.0, 1.0, 0.0),
            DVec3::new(7.0, 0.0, 0.0),
        ];
        let c = NurbsCurve::try_new(3, knots.clone(), smooth.to_vec(), None).expect("smooth");
        let q = c.point(0.5) + DVec3::new(0.0, 0.1, 0.05);
        let d = c.through(&[(0.5, q)]).expect("through");
        assert!((d.point(0.5) - q).length() < 1e-12);
        let (l, r) = (d.derivs(1.0 - 1e-9).d1, d.derivs(1.0 + 1e-9).d1);
        assert!(
            l.angle_between(r) < 1e-6,
            "still smooth: {}",
            l.angle_between(r)
        );
        let mut bent = smooth;
        bent[4].y = 2.5;
        let c = NurbsCurve::try_new(3, knots, bent.to_vec(), None).expect("corner");
        let before = c.derivs(0.999).d1.angle_between(c.derivs(1.001).d1);
        let d = c
            .through(&[(0.5, c.point(0.5) + DVec3::Y * 0.1)])
            .expect("through");
        let after = d.derivs(0.999).d1.angle_between(d.derivs(1.001).d1);
        assert!(
            before > 0.1 && after > 0.1,
            "the corner stays: {before} → {after}"
        );
    }

    #[test]
    fn many_targets_on_one_span_are_all_met() {
        // The frigate's keel fitted as one cubic Bézier span (a straight line), moved through
        // the ends of 39 stations 3.08 m apart and the stem at 114 m: the knots inserted near
        // other knots once left two targets in one span and the targets dependent.
        let line = NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 114.0, 114.0, 114.0, 114.0],
            (0..4)
                .map(|i| DVec3::new(38.0 * i as f64, 0.0, 0.0))
                .collect(),
            None,
        )
        .expect("line");
        let step = 114.0 / 37.05;
        let mut targets: Vec<(f64, DVec3)> = (0..38)
            .map(|k| {
                let x = step * k as f64;
                (x, DVec3::new(x, 0.0, 1e-4 * (k % 3) as f64))
            })
            .collect();
        targets.push((114.0, DVec3::new(114.0, 0.0, 0.0)));
        let moved = line.through(&targets).expect("every target met");
        for (t, q) in targets {
            assert!(moved.point(t).distance(q) < 1e-12, "target at {t} missed");
        }
    }

    #[test]
    fn bad_targets_are_errors() {
        let c = cubic();
        let p = c.point(0.5);
        assert!(matches!(
            c.through(&[(0.5, p), (0.5, p + DVec3::X)]),
            Err(CurveError::TargetsConflict { .. })
        ));
        assert!(matches!(
            c.through(&[(f64::NAN, p)]),
            Err(CurveError::NonFiniteParameter(_))
        ));
        assert!(matches!(
            c.through(&[(2.0, p)]),
            Err(CurveError::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            c.through(&[(0.5, DVec3::splat(f64::INFINITY))]),
            Err(CurveError::NonFiniteQuery)
        ));
        // The same target twice is one target.
        assert!(c.through(&[(0.5, p), (0.5, p)]).is_ok());
    }
    #[test]
    fn a_tangent_target_turns_the_derivative_and_keeps_the_point() {
        let c = cubic();
        let (t, end) = (0.3, 1.0);
        let q = c.point(t);
        // Turn the derivative by 0.5° about the z axis at an interior target and at the end.
        let turn = glam::DQuat::from_rotation_z(0.5f64.to_radians());
        let (d, e) = (turn * c.derivs(t).d1, turn * c.derivs(end).d1);
        let moved = c
            .through_with_tangents(&[(t, q), (end, c.point(end))], &[(t, d), (end, e)])
            .expect("through with tangents");
        assert!(moved.point(t).distance(q) < 1e-12);
        assert!(moved.point(end).distance(c.point(end)) < 1e-12);
        assert!((moved.derivs(t).d1 - d).length() < 1e-9 * d.length());
        assert!((moved.derivs(end).d1 - e).length() < 1e-9 * e.length());
        // The turn is a small change: the curve moves by a fraction of its span's tangent turn.
        let most = (0..=100)
            .map(|i| {
                moved
                    .point(i as f64 / 100.0)
                    .distance(c.point(i as f64 / 100.0))
            })
            .fold(0.0, f64::max);
        assert!(most > 1e-4 && most < 0.02, "largest change {most}");
        // Positions alone leave the derivative as it was.
        let plain = c.through(&[(t, q)]).expect("through");
        assert!((plain.derivs(t).d1 - c.derivs(t).d1).length() < 1e-9);
    }

    #[test]
    fn a_tangent_needs_a_target_there_and_a_polynomial_curve() {
        let c = cubic();
        let q = c.point(0.3);
        let d = c.derivs(0.3).d1;
        assert!(matches!(
            c.through_with_tangents(&[(0.3, q)], &[(0.4, d)]),
            Err(CurveError::TargetsDependent)
        ));
        assert!(matches!(
            c.through_with_tangents(&[(0.3, q)], &[(0.3, DVec3::splat(f64::NAN))]),
            Err(CurveError::NonFiniteQuery)
        ));
        let rational = NurbsCurve::try_new(
            3,
            c.knots().to_vec(),
            c.control_points(),
            Some(vec![1.0, 2.0, 1.0, 1.0, 1.0]),
        )
        .expect("rational");
        assert!(matches!(
            rational.through_with_tangents(&[(0.3, rational.point(0.3))], &[(0.3, d)]),
            Err(CurveError::TargetsDependent)
        ));
    }
}
