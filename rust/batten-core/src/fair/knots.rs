//! Knot vectors of the fitting: the observation rows (B-spline values at the data parameters),
//! the derivative-jump rows of the fairness term (Dierckx `fpdisc`), the Schoenberg–Whitney
//! test, and the choice of the next knot (H-rep paper eq. 12: the parametric middle of the span
//! with the largest error).

use glam::DVec3;

use crate::curve::{basis_funs, find_span, MAX_ORDER};

/// A clamped knot vector `a` (×(k+1)), interior knots, `b` (×(k+1)).
pub(crate) fn clamped(degree: usize, a: f64, b: f64, interior: &[f64]) -> Vec<f64> {
    let mut t = Vec::with_capacity(interior.len() + 2 * degree + 2);
    t.extend(std::iter::repeat_n(a, degree + 1));
    t.extend_from_slice(interior);
    t.extend(std::iter::repeat_n(b, degree + 1));
    t
}

/// The observation matrix in band form: for each data parameter, the knot span `s` and the
/// `k + 1` non-zero basis values `N[s-k..=s]` (Dierckx `fpbspl`).
#[derive(Clone, Debug)]
pub(crate) struct Design {
    pub degree: usize,
    pub span: Vec<usize>,
    pub basis: Vec<[f64; MAX_ORDER]>,
}

impl Design {
    /// Rows for `params` (each inside `[knots[k], knots[n]]`).
    pub(super) fn new(knots: &[f64], degree: usize, params: &[f64]) -> Design {
        let n = knots.len() - degree - 1;
        let mut span = Vec::with_capacity(params.len());
        let mut basis = Vec::with_capacity(params.len());
        for &u in params {
            let s = find_span(knots, degree, n, u);
            let mut b = [0.0; MAX_ORDER];
            basis_funs(knots, s, u, degree, &mut b);
            span.push(s);
            basis.push(b);
        }
        Design {
            degree,
            span,
            basis,
        }
    }

    /// Recompute the rows of `params[from..to]` for new `knots` (after a knot insertion, only
    /// the data near the new knot get new basis values).
    pub(super) fn update_range(&mut self, knots: &[f64], params: &[f64], from: usize, to: usize) {
        let k = self.degree;
        let n = knots.len() - k - 1;
        for (i, &u) in params.iter().enumerate().take(to).skip(from) {
            let s = find_span(knots, k, n, u);
            basis_funs(knots, s, u, k, &mut self.basis[i]);
            self.span[i] = s;
        }
    }

    /// The spline value at data parameter `i` for coefficients `c`.
    #[inline]
    pub(super) fn value(&self, i: usize, c: &[DVec3]) -> DVec3 {
        let (s, k) = (self.span[i], self.degree);
        let b = &self.basis[i];
        let mut acc = DVec3::ZERO;
        for j in 0..=k {
            acc += c[s - k + j] * b[j];
        }
        acc
    }
}

/// The k-th derivatives (constants) of the degree-k B-splines `N[s-k..=s]` on knot span `s`,
/// by differentiating the Cox–de Boor recurrence k times:
/// `N⁽ᵈ⁾[i,d] = d·(N⁽ᵈ⁻¹⁾[i,d−1]/(t[i+d]−t[i]) − N⁽ᵈ⁻¹⁾[i+1,d−1]/(t[i+d+1]−t[i+1]))`.
fn kth_derivatives(knots: &[f64], s: usize, k: usize) -> [f64; MAX_ORDER] {
    let mut cur = [0.0; MAX_ORDER];
    cur[0] = 1.0; // degree 0: N[s,0] = 1 on span s
    for d in 1..=k {
        let mut next = [0.0; MAX_ORDER];
        for (x, out) in next.iter_mut().enumerate().take(d + 1) {
            let i = s + x - d; // next[x] is N[i, d]
            let mut v = 0.0;
            if x >= 1 {
                let den = knots[i + d] - knots[i];
                if den > 0.0 {
                    v += cur[x - 1] / den;
                }
            }
            if x < d {
                let den = knots[i + d + 1] - knots[i + 1];
                if den > 0.0 {
                    v -= cur[x] / den;
                }
            }
            *out = d as f64 * v;
        }
        cur = next;
    }
    cur
}

/// One row of the fairness matrix: the jump of the k-th derivative of the B-splines
/// `N[first..first+k+2]` at one interior knot.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JumpRow {
    pub first: usize,
    pub b: [f64; MAX_ORDER + 1],
}

/// The rows `b` with `Σⱼ b[j]·c[first+j] = s⁽ᵏ⁾(λ+) − s⁽ᵏ⁾(λ−)` for every interior knot λ
/// (Dierckx `fpdisc`, the matrix of the smoothing norm in Dierckx 1993 eq. 5.2), scaled like
/// fpdisc by `h^k`, `h` the mean knot spacing, so that the value of p does not depend on
/// the size of the curve.
pub(crate) fn jump_rows(knots: &[f64], degree: usize) -> Vec<JumpRow> {
    let k = degree;
    let n = knots.len() - k - 1;
    let (a, b) = (knots[k], knots[n]);
    let h = (b - a) / (n - k) as f64;
    let scale = h.powi(k as i32);
    (k + 1..n)
        .map(|l| {
            let left = kth_derivatives(knots, l - 1, k); // N[l-1-k..=l-1]
            let right = kth_derivatives(knots, l, k); // N[l-k..=l]
            let mut row = [0.0; MAX_ORDER + 1];
            for j in 0..=k + 1 {
                let r = if j >= 1 { right[j - 1] } else { 0.0 };
                let lf = if j <= k { left[j] } else { 0.0 };
                row[j] = (r - lf) * scale;
            }
            JumpRow {
                first: l - 1 - k,
                b: row,
            }
        })
        .collect()
}

/// True when the sorted `params` satisfy the Schoenberg–Whitney conditions for the clamped
/// `knots`: some increasing choice of data parameters puts one inside the support of every
/// B-spline, so the least-squares problem has a unique solution (Dierckx 1993 §4.1.1).
pub(crate) fn schoenberg_whitney(knots: &[f64], degree: usize, params: &[f64]) -> bool {
    let k = degree;
    let n = knots.len() - k - 1;
    let (a, b) = (knots[k], knots[n]);
    let mut i = 0;
    for j in 0..n {
        let (lo, hi) = (knots[j], knots[j + k + 1]);
        loop {
            let Some(&u) = params.get(i) else {
                return false;
            };
            i += 1;
            let inside = (lo < u && u < hi) || (j == 0 && u == a) || (j == n - 1 && u == b);
            if inside {
                break;
            }
            if u >= hi && !(j == n - 1 && u == b) {
                return false;
            }
        }
    }
    true
}

/// How many standard deviations of a span's sum of squared residuals under pure noise
/// (`√(2n)·S/M` for `n` data, the χ² spread) its excess over the noise (`n·S/M`) must reach
/// for the span to count as biased in [`next_knots`].
const BIAS_Z: f64 = 3.0;

/// The next `count` interior knots (sorted), chosen one after another as in Dierckx's fpknot:
/// each goes into the span with the largest sum of squared residuals, at its parametric middle
/// (H-rep paper eq. 12) or, where that leaves one side without data (unevenly spaced points),
/// between the span's middle data points (fpknot's choice); a span that cannot take a knot
/// with data on both sides and the Schoenberg–Whitney conditions holding is passed over. The
/// split span's error is shared between its halves in proportion to their data (fpknot), so
/// that the following knots of the batch go where the error is. With `count = 1` this is the
/// single knot of the span with the largest error. Empty when no span can be split.
///
/// "Error" is refined by the noise level `per_point = S/M` (0 for the plain rule): when some
/// span's residuals exceed what noise at that level explains, `n·S/M`, by more than
/// [`BIAS_Z`] of their spread, the error of every span is its excess over `n·S/M`, so the
/// knot goes where the fit is biased; otherwise (noise alone) the plain sum, which spreads
/// knots evenly. Choice: on the KCS benchmark (2,000 points) the plain rule also spread the
/// knots evenly while the bilge was still biased, 32 interior knots and 12 inflections left
/// on the flat bottom after lobe flattening; with the excess 30 and 2 (truth 4). A lower
/// threshold (2σ) split noise clusters in 3 of 40 noisy S-bends, 3σ in 1.
pub(crate) fn next_knots(
    knots: &[f64],
    degree: usize,
    design: &Design,
    residual2: &[f64],
    params: &[f64],
    count: usize,
    per_point: f64,
) -> Vec<f64> {
    let k = degree;
    let n = knots.len() - k - 1;
    // Per knot span: (error, lo, hi, usable).
    let mut spans: Vec<(f64, f64, f64, bool)> = (0..n - k)
        .map(|j| (0.0, knots[j + k], knots[j + k + 1], true))
        .collect();
    let mut data = vec![0usize; n - k];
    for (s, r) in design.span.iter().zip(residual2) {
        spans[s - k].0 += r;
        data[s - k] += 1;
    }
    for (sp, &c) in spans.iter_mut().zip(&data) {
        sp.3 = c >= 2;
    }
    if per_point > 0.0 {
        let significant = spans.iter().zip(&data).any(|(sp, &c)| {
            sp.3 && sp.0 - c as f64 * per_point > BIAS_Z * (2.0 * c as f64).sqrt() * per_point
        });
        if significant {
            for (sp, &c) in spans.iter_mut().zip(&data) {
                sp.0 -= c as f64 * per_point;
            }
        }
    }
    let mut trial = knots.to_vec();
    let mut chosen = Vec::with_capacity(count);
    while chosen.len() < count {
        // The usable span with the largest error (the first of equals).
        let mut pick: Option<usize> = None;
        for (j, sp) in spans.iter().enumerate() {
            if sp.3 && sp.0 > 0.0 && pick.is_none_or(|p| sp.0 > spans[p].0) {
                pick = Some(j);
            }
        }
        let Some(j) = pick else { break };
        let (err, lo, hi, _) = spans[j];
        // Data strictly inside the span (params are sorted).
        let i0 = params.partition_point(|&u| u <= lo);
        let i1 = params.partition_point(|&u| u < hi);
        let inside = &params[i0..i1.max(i0)];
        let mid = 0.5 * (lo + hi);
        let median = (inside.len() >= 2).then(|| {
            let h = inside.len() / 2;
            0.5 * (inside[h - 1] + inside[h])
        });
        let mut placed = None;
        for t in std::iter::once(mid).chain(median) {
            if !(lo < t && t < hi) {
                continue;
            }
            let left = inside.first().is_some_and(|&u| u < t);
            let right = inside.last().is_some_and(|&u| u > t);
            if !(left && right) {
                continue;
            }
            let at = trial.partition_point(|&u| u <= lo);
            trial.insert(at, t);
            if schoenberg_whitney(&trial, k, params) {
                placed = Some(t);
                break;
            }
            trial.remove(at);
        }
        let Some(t) = placed else {
            spans[j].3 = false;
            continue;
        };
        chosen.push(t);
        // Split the span; its error goes to the halves in proportion to their data (fpknot).
        let nl = inside.partition_point(|&u| u < t);
        let nr = inside.len() - nl;
        let total = (nl + nr) as f64;
        spans[j] = (err * nl as f64 / total, lo, t, nl >= 2);
        spans.insert(j + 1, (err * nr as f64 / total, t, hi, nr >= 2));
    }
    chosen.sort_by(f64::total_cmp);
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jump_of_cubic_b_splines_matches_a_spline_with_one_kink_in_d3() {
        // On knots 0,0,0,0,1,2,2,2,2 the spline with coefficients c has s''' jumping at 1 by
        // Σ b[j] c[j]; check against finite third derivatives from the power form.
        let knots = clamped(3, 0.0, 2.0, &[1.0]);
        let rows = jump_rows(&knots, 3);
        assert_eq!(rows.len(), 1, "one interior knot");
        let c = [0.3, -1.0, 2.0, 0.5, 1.5];
        let jump: f64 = (0..5).map(|j| rows[0].b[j] * c[rows[0].first + j]).sum();
        // Third derivative on each span from k-th derivative sums.
        let left = kth_derivatives(&knots, 3, 3);
        let right = kth_derivatives(&knots, 4, 3);
        let dl: f64 = (0..4).map(|j| left[j] * c[j]).sum();
        let dr: f64 = (0..4).map(|j| right[j] * c[1 + j]).sum();
        // Mean spacing is 1, so the scale is 1.
        assert!(
            (jump - (dr - dl)).abs() < 1e-12,
            "jump {jump} vs {}",
            dr - dl
        );
        // Independent check: on a Bézier span [0,1] the third derivative of the cubic with
        // control points P is 6(P3 − 3P2 + 3P1 − P0)/h³; with a single interior knot at 1 the
        // left span's derivatives of the four B-splines are those of the degree-3 B-splines
        // on 0,0,0,0,1,2: N0''' = −1 (from (1−u)³)… so the sum over j of left[j] must be 0.
        let sum: f64 = left[..4].iter().sum();
        assert!(
            sum.abs() < 1e-12,
            "k-th derivatives of a partition of unity sum to 0"
        );
        assert!((left[0] + 6.0).abs() < 1e-12, "N0 = (1-u)^3 has N0''' = -6");
    }

    #[test]
    fn schoenberg_whitney_needs_data_in_every_support() {
        let knots = clamped(3, 0.0, 1.0, &[0.3, 0.6]);
        let good = [0.0, 0.1, 0.35, 0.5, 0.8, 1.0];
        assert!(schoenberg_whitney(&knots, 3, &good), "spread data");
        // Six B-splines but only the end point beyond 0.3: N4 (support (0.3, 1)) has no datum.
        let bad = [0.0, 0.1, 0.2, 0.25, 0.28, 1.0];
        assert!(
            !schoenberg_whitney(&knots, 3, &bad),
            "no data after the first knot but the end"
        );
    }
}
