//! Knot spans and B-spline basis functions (Piegl & Tiller A2.1–A2.3).

/// Largest curve degree the kernel supports (order 16). Blender's curves go to order 6 and the
/// fairing module to degree 5; the fixed bound lets the inner loops run on stack arrays.
pub const MAX_DEGREE: usize = 15;
pub(crate) const MAX_ORDER: usize = MAX_DEGREE + 1;

/// Index `i` of the knot span with `knots[i] <= t < knots[i+1]` and `degree <= i < n`
/// (`n` control points), clamping `t` into the domain `[knots[degree], knots[n]]` (A2.1 with a
/// binary search). At the domain end the last non-empty span is returned.
#[inline]
pub(crate) fn find_span(knots: &[f64], degree: usize, n: usize, t: f64) -> usize {
    if t >= knots[n] {
        let end = knots[n];
        let mut i = n - 1;
        while i > degree && knots[i] >= end {
            i -= 1;
        }
        return i;
    }
    let start = knots[degree];
    if t <= start {
        let mut i = degree;
        while knots[i + 1] <= start {
            i += 1;
        }
        return i;
    }
    let (mut lo, mut hi) = (degree, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if t < knots[mid] {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The `degree + 1` non-zero basis functions `N[span-degree+j](t)`, `j = 0..=degree` (A2.2).
#[inline]
pub(crate) fn basis_funs(
    knots: &[f64],
    span: usize,
    t: f64,
    degree: usize,
    n: &mut [f64; MAX_ORDER],
) {
    let mut left = [0.0; MAX_ORDER];
    let mut right = [0.0; MAX_ORDER];
    n[0] = 1.0;
    for j in 1..=degree {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = n[r] / (right[r + 1] + left[j - r]);
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
}

/// Basis functions and their derivatives up to order `nd` (at most 3): `ders[k][j]` is the k-th
/// derivative of `N[span-degree+j]` at `t` (A2.3).
///
/// The loops keep the book's index arithmetic so the code can be checked against it.
#[allow(clippy::needless_range_loop)]
pub(crate) fn ders_basis_funs(
    knots: &[f64],
    span: usize,
    t: f64,
    degree: usize,
    nd: usize,
    ders: &mut [[f64; MAX_ORDER]; 4],
) {
    let p = degree;
    let mut ndu = [[0.0; MAX_ORDER]; MAX_ORDER];
    let mut left = [0.0; MAX_ORDER];
    let mut right = [0.0; MAX_ORDER];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for row in ders.iter_mut() {
        *row = [0.0; MAX_ORDER];
    }
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let nd = nd.min(p).min(3);
    let mut a = [[0.0; MAX_ORDER]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=nd {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for k in 1..=nd {
        for j in 0..=p {
            ders[k][j] *= factor;
        }
        factor *= (p - k) as f64;
    }
}

/// The `degree + 1` non-zero basis functions at `t` (`n0`, as [`basis_funs`]) and their first
/// derivatives (`n1`): [`ders_basis_funs`]'s rows 0 and 1 at `nd = 1`, bit for bit (the same
/// operations in the same order), without its tables. A2.3's triangle of degree `p` is A2.2's
/// steps; its first derivatives need only the last step's knot differences and the degree
/// `p − 1` functions before it, so neither a `(p + 1)²` table nor its zeroing is needed: what
/// a point and tangent cost, which the arc length and the normal fields' keys ask for at every
/// Gauss point.
#[inline]
pub(crate) fn basis_funs_d1(
    knots: &[f64],
    span: usize,
    t: f64,
    degree: usize,
    n0: &mut [f64; MAX_ORDER],
    n1: &mut [f64; MAX_ORDER],
) {
    let p = degree;
    let mut left = [0.0; MAX_ORDER];
    let mut right = [0.0; MAX_ORDER];
    n0[0] = 1.0;
    // The degree p − 1 functions (A2.3's `ndu[r][p − 1]`), then the step to degree p with its
    // knot differences (`ndu[p][r]`) kept.
    let mut below = [0.0; MAX_ORDER];
    let mut diff = [0.0; MAX_ORDER];
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        if j == p {
            below[..p].copy_from_slice(&n0[..p]);
        }
        let mut saved = 0.0;
        for r in 0..j {
            let d = right[r + 1] + left[j - r];
            if j == p {
                diff[r] = d;
            }
            let temp = n0[r] / d;
            n0[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n0[j] = saved;
    }
    *n1 = [0.0; MAX_ORDER];
    if p == 0 {
        return;
    }
    for r in 0..=p {
        let mut d = 0.0;
        if r >= 1 {
            let a = 1.0 / diff[r - 1];
            d = a * below[r - 1];
        }
        if r < p {
            let a = -1.0 / diff[r];
            d += a * below[r];
        }
        n1[r] = d;
    }
    let factor = p as f64;
    for v in &mut n1[..=p] {
        *v *= factor;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`basis_funs_d1`] is [`ders_basis_funs`]'s first two rows bit for bit, for every degree
    /// the kernel takes, on knots with repeats and at the knots themselves.
    #[test]
    fn first_derivatives_alone_are_the_tables_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = 0;
        for p in 0..=MAX_DEGREE {
            for _ in 0..20 {
                let n = p + 1 + (next() * 6.0) as usize;
                // Knots with repeats (whole numbers) and without (any reals).
                let whole = next() < 0.5;
                let mut inner: Vec<f64> = (0..n - p - 1)
                    .map(|_| {
                        if whole {
                            (next() * 8.0).floor()
                        } else {
                            next() * 8.0
                        }
                    })
                    .collect();
                inner.sort_by(f64::total_cmp);
                let mut knots = vec![0.0; p + 1];
                knots.extend(inner);
                knots.extend(vec![8.0; p + 1]);
                for q in 0..=64 {
                    let t = if q % 8 == 0 {
                        q as f64 / 8.0
                    } else {
                        8.0 * next()
                    };
                    let span = find_span(&knots, p, n, t);
                    let mut d = [[0.0; MAX_ORDER]; 4];
                    ders_basis_funs(&knots, span, t, p, 1, &mut d);
                    let (mut n0, mut n1) = ([0.0; MAX_ORDER], [0.0; MAX_ORDER]);
                    basis_funs_d1(&knots, span, t, p, &mut n0, &mut n1);
                    for j in 0..=p {
                        assert_eq!(n0[j].to_bits(), d[0][j].to_bits(), "N p={p} t={t} j={j}");
                        assert_eq!(n1[j].to_bits(), d[1][j].to_bits(), "N' p={p} t={t} j={j}");
                        compared += 1;
                    }
                }
            }
        }
        assert!(compared > 50_000, "{compared} values compared");
    }

    #[test]
    fn partition_of_unity_and_span() {
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        let (p, n) = (3, 7);
        for i in 0..=300 {
            let t = 3.0 * i as f64 / 300.0;
            let span = find_span(&knots, p, n, t);
            assert!(
                knots[span] <= t && (t < knots[span + 1] || t == 3.0),
                "span wrong at {t}"
            );
            let mut b = [0.0; MAX_ORDER];
            basis_funs(&knots, span, t, p, &mut b);
            let sum: f64 = b[..=p].iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-14,
                "partition of unity at {t}: {sum}"
            );
            assert!(
                b[..=p].iter().all(|&v| v >= -1e-15),
                "basis non-negative at {t}"
            );
            let mut d = [[0.0; MAX_ORDER]; 4];
            ders_basis_funs(&knots, span, t, p, 3, &mut d);
            for j in 0..=p {
                assert!((d[0][j] - b[j]).abs() < 1e-14, "A2.3 value matches A2.2");
            }
            let dsum: f64 = d[1][..=p].iter().sum();
            assert!(
                dsum.abs() < 1e-12,
                "derivatives of a partition of unity sum to zero"
            );
        }
    }

    #[test]
    fn span_at_domain_end_of_unclamped_vector() {
        let knots: Vec<f64> = (0..10).map(f64::from).collect();
        // 6 points, order 4: domain [3, 6]
        assert_eq!(find_span(&knots, 3, 6, 6.0), 5, "end uses last span");
        assert_eq!(find_span(&knots, 3, 6, 3.0), 3, "start uses first span");
        assert_eq!(find_span(&knots, 3, 6, -1.0), 3, "clamped below");
        assert_eq!(find_span(&knots, 3, 6, 4.5), 4, "interior");
    }
}
