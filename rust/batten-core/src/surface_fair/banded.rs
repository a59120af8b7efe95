//! Symmetric positive definite banded systems, solved by Cholesky's factorisation within the
//! band (Golub & Van Loan, *Matrix Computations*, §4.3.5): the normal equations of a section's
//! smoothing couple only control points a few apart, so an `n`-point section costs `O(n·b²)`
//! for a band of half-width `b`, not the `O(n³)` of a dense solve.

/// A symmetric `n × n` matrix with nonzero entries only within `band` of the diagonal, its
/// lower band stored row by row (`a[i][band + j − i]` for `i − band ≤ j ≤ i`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Banded {
    n: usize,
    band: usize,
    a: Vec<f64>,
}

/// A pivot at most this share of its diagonal entry before elimination marks the matrix as not
/// positive definite (dependent rows).
const DEPENDENT_PIVOT: f64 = 1e-13;

impl Banded {
    /// The zero matrix of size `n` and half-width `band`.
    pub(crate) fn zeros(n: usize, band: usize) -> Banded {
        Banded {
            n,
            band,
            a: vec![0.0; n * (band + 1)],
        }
    }

    fn at(&self, i: usize, j: usize) -> usize {
        i * (self.band + 1) + self.band + j - i
    }

    /// Add `v` to the entries `(i, j)` and `(j, i)` (once on the diagonal). Panics outside the
    /// band (a caller's indexing error).
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        assert!(i - j <= self.band && i < self.n, "entry outside the band");
        let k = self.at(i, j);
        self.a[k] += v;
    }

    /// Add `w · c cᵀ` for the vector `c` whose entries start at index `first` (entries past the
    /// matrix are dropped).
    pub(crate) fn add_outer(&mut self, first: usize, c: &[f64], w: f64) {
        for (p, &cp) in c.iter().enumerate() {
            let i = first + p;
            if i >= self.n || cp == 0.0 {
                continue;
            }
            for (q, &cq) in c.iter().enumerate().take(p + 1) {
                if cq != 0.0 {
                    self.add(i, first + q, w * cp * cq);
                }
            }
        }
    }

    /// The Cholesky factor `L` (`A = L Lᵀ`, in the same band), or `None` when the matrix is
    /// not positive definite.
    pub(crate) fn factor(mut self) -> Option<Banded> {
        let (n, b) = (self.n, self.band);
        for i in 0..n {
            let lo = i.saturating_sub(b);
            for j in lo..=i {
                let mut sum = self.a[self.at(i, j)];
                for k in lo.max(j.saturating_sub(b))..j {
                    sum -= self.a[self.at(i, k)] * self.a[self.at(j, k)];
                }
                if i == j {
                    let diag = self.a[self.at(i, i)];
                    // Also refuses a NaN pivot.
                    if sum.is_nan() || sum <= DEPENDENT_PIVOT * diag.abs() {
                        return None;
                    }
                    let k = self.at(i, i);
                    self.a[k] = sum.sqrt();
                } else {
                    let k = self.at(i, j);
                    self.a[k] = sum / self.a[self.at(j, j)];
                }
            }
        }
        Some(self)
    }

    /// Solve `L Lᵀ x = b` in place, `self` being a factor from [`Banded::factor`].
    pub(crate) fn solve(&self, x: &mut [f64]) {
        let (n, b) = (self.n, self.band);
        for i in 0..n {
            let lo = i.saturating_sub(b);
            let sum: f64 = (lo..i).map(|k| self.a[self.at(i, k)] * x[k]).sum();
            x[i] = (x[i] - sum) / self.a[self.at(i, i)];
        }
        for i in (0..n).rev() {
            let hi = (i + b + 1).min(n);
            let sum: f64 = (i + 1..hi).map(|k| self.a[self.at(k, i)] * x[k]).sum();
            x[i] = (x[i] - sum) / self.a[self.at(i, i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_banded_solve_is_the_dense_solution() {
        // A pentadiagonal SPD matrix (second differences squared plus the identity) and a
        // right-hand side; the residual of the banded solution in the dense product.
        let n = 9;
        let mut m = Banded::zeros(n, 2);
        let mut dense = vec![vec![0.0; n]; n];
        for (i, row) in dense.iter_mut().enumerate() {
            m.add(i, i, 1.0);
            row[i] += 1.0;
        }
        for i in 0..n - 2 {
            let c = [1.0, -2.0, 1.0];
            m.add_outer(i, &c, 0.7);
            for p in 0..3 {
                for q in 0..3 {
                    dense[i + p][i + q] += 0.7 * c[p] * c[q];
                }
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut x = b.clone();
        m.factor().expect("positive definite").solve(&mut x);
        for i in 0..n {
            let ax: f64 = (0..n).map(|j| dense[i][j] * x[j]).sum();
            assert!((ax - b[i]).abs() < 1e-12, "row {i}: {ax} against {}", b[i]);
        }
    }

    #[test]
    fn a_singular_matrix_has_no_factor() {
        let mut m = Banded::zeros(3, 1);
        m.add_outer(0, &[1.0, -1.0], 1.0);
        m.add_outer(1, &[1.0, -1.0], 1.0);
        assert!(
            m.factor().is_none(),
            "the constant vector is in its null space"
        );
    }
}
