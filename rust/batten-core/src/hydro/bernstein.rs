//! Tensor-product Bernstein polynomials of one fixed degree on `[0, 1]²`, the form in which
//! [`cells`](super::cells) holds a patch: values and derivatives by the basis, the convex-hull
//! bound of a net, de Casteljau halving, interpolation at Chebyshev–Lobatto nodes, and
//! Gauss–Legendre rules (Farin, *Curves and Surfaces for CAGD*, ch. 5 and 15).

use std::sync::OnceLock;

/// The degree of a cell's polynomial in each parameter (8 × 8 coefficients): with cells a
/// quarter of a patch or smaller, it follows a Gregory patch to about 1e-9 of its size.
pub(crate) const DEGREE: usize = 7;
/// Coefficients per parameter.
pub(crate) const N: usize = DEGREE + 1;
/// Gauss–Legendre points per parameter: twice the degree, so a product of two of a cell's
/// coordinates with its normal (degree `4·DEGREE − 1`) integrates exactly.
pub(crate) const GAUSS: usize = 2 * DEGREE;

/// The Bernstein basis of degree [`DEGREE`] and its derivative at `s`.
#[inline]
pub(crate) fn basis(s: f64) -> ([f64; N], [f64; N]) {
    // Degree DEGREE−1 basis first (its differences are the derivative), by the triangle.
    let r = 1.0 - s;
    let mut b = [0.0f64; N];
    b[0] = 1.0;
    for k in 1..DEGREE {
        let mut prev = 0.0;
        for bi in b.iter_mut().take(k + 1) {
            let cur = *bi;
            *bi = r * cur + s * prev;
            prev = cur;
        }
    }
    let mut d = [0.0f64; N];
    for i in 0..N {
        let left = if i > 0 { b[i - 1] } else { 0.0 };
        let right = if i < DEGREE { b[i] } else { 0.0 };
        d[i] = DEGREE as f64 * (left - right);
    }
    // Raise to degree DEGREE.
    let mut full = [0.0f64; N];
    let mut prev = 0.0;
    for i in 0..N {
        let cur = if i < DEGREE { b[i] } else { 0.0 };
        full[i] = r * cur + s * prev;
        prev = cur;
    }
    (full, d)
}

/// The value at `s` of the 1-D Bernstein polynomial with coefficients `c` (de Casteljau).
#[inline]
pub(crate) fn eval1(c: &[f64; N], s: f64) -> f64 {
    let mut w = *c;
    let r = 1.0 - s;
    for k in (1..N).rev() {
        for i in 0..k {
            w[i] = r * w[i] + s * w[i + 1];
        }
    }
    w[0]
}

/// The smallest and largest coefficient: bounds of the polynomial on its square (convex hull).
#[inline]
pub(crate) fn bounds(c: &[[f64; N]; N]) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in c.iter().flatten() {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    (lo, hi)
}

/// Split the 1-D coefficients `c` at `s`: the coefficients of `[0, s]` and of `[s, 1]`
/// (de Casteljau).
#[inline]
pub(crate) fn split1<T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>>(
    c: &[T; N],
    s: f64,
) -> ([T; N], [T; N]) {
    let mut w = *c;
    let mut left = *c;
    let mut right = *c;
    let r = 1.0 - s;
    left[0] = w[0];
    right[DEGREE] = w[DEGREE];
    for k in 1..N {
        for i in 0..N - k {
            w[i] = w[i] * r + w[i + 1] * s;
        }
        left[k] = w[0];
        right[DEGREE - k] = w[N - k - 1];
    }
    (left, right)
}

/// Chebyshev–Lobatto nodes on `[0, 1]` (ends included, symmetric about ½): a cell's
/// interpolation points, shared along the edges of neighbouring cells.
pub(crate) fn lobatto_nodes() -> &'static [f64; N] {
    static NODES: OnceLock<[f64; N]> = OnceLock::new();
    NODES.get_or_init(|| {
        let mut x = [0.0; N];
        for (i, xi) in x.iter_mut().enumerate() {
            *xi = 0.5 * (1.0 - (std::f64::consts::PI * i as f64 / DEGREE as f64).cos());
        }
        x[0] = 0.0;
        x[DEGREE] = 1.0;
        x
    })
}

/// The inverse of the collocation matrix `M[i][k] = B_k(node_i)`: Bernstein coefficients of the
/// interpolant are `M⁻¹ · values` (Gauss–Jordan with partial pivoting, once).
pub(crate) fn interpolation_matrix() -> &'static [[f64; N]; N] {
    static INV: OnceLock<[[f64; N]; N]> = OnceLock::new();
    INV.get_or_init(|| {
        let nodes = lobatto_nodes();
        let mut a = [[0.0f64; N]; N];
        for (i, row) in a.iter_mut().enumerate() {
            *row = basis(nodes[i]).0;
        }
        let mut inv = [[0.0f64; N]; N];
        for (i, row) in inv.iter_mut().enumerate() {
            row[i] = 1.0;
        }
        for col in 0..N {
            let piv = (col..N)
                .max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))
                .unwrap_or(col);
            a.swap(col, piv);
            inv.swap(col, piv);
            let d = a[col][col];
            for k in 0..N {
                a[col][k] /= d;
                inv[col][k] /= d;
            }
            for r in 0..N {
                if r != col {
                    let f = a[r][col];
                    if f != 0.0 {
                        for k in 0..N {
                            a[r][k] -= f * a[col][k];
                            inv[r][k] -= f * inv[col][k];
                        }
                    }
                }
            }
        }
        inv
    })
}

/// A Gauss–Legendre rule of [`GAUSS`] points on `[0, 1]`: nodes and weights (Newton on the
/// Legendre polynomial from Chebyshev guesses, once).
pub(crate) fn gauss() -> &'static ([f64; GAUSS], [f64; GAUSS]) {
    static RULE: OnceLock<([f64; GAUSS], [f64; GAUSS])> = OnceLock::new();
    RULE.get_or_init(gauss_rule::<GAUSS>)
}

/// The `K`-point Gauss–Legendre rule on `[0, 1]`.
pub(crate) fn gauss_rule<const K: usize>() -> ([f64; K], [f64; K]) {
    let mut x = [0.0; K];
    let mut w = [0.0; K];
    let n = K as f64;
    for i in 0..K {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0f64, z);
            for k in 2..=K {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[K - 1 - i] = 0.5 * (1.0 + z);
        w[K - 1 - i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_sums_to_one_and_interpolates() {
        let (b, d) = basis(0.3);
        assert!(
            (b.iter().sum::<f64>() - 1.0).abs() < 1e-15,
            "partition of unity"
        );
        assert!(d.iter().sum::<f64>().abs() < 1e-13, "derivative of 1 is 0");
        // Interpolate s⁵ at the nodes and evaluate elsewhere.
        let m = interpolation_matrix();
        let nodes = lobatto_nodes();
        let vals: Vec<f64> = nodes.iter().map(|s| s.powi(5)).collect();
        let mut c = [0.0; N];
        for i in 0..N {
            c[i] = (0..N).map(|k| m[i][k] * vals[k]).sum();
        }
        assert!(
            (eval1(&c, 0.37) - 0.37f64.powi(5)).abs() < 1e-14,
            "s^5 reproduced"
        );
        let (l, r) = split1(&c, 0.5);
        assert!(
            (eval1(&l, 0.5) - 0.25f64.powi(5)).abs() < 1e-14,
            "left half"
        );
        assert!(
            (eval1(&r, 0.5) - 0.75f64.powi(5)).abs() < 1e-14,
            "right half"
        );
    }

    #[test]
    fn gauss_integrates_degree_27() {
        let (x, w) = gauss();
        let s: f64 = x.iter().zip(w).map(|(x, w)| w * x.powi(27)).sum();
        assert!((s - 1.0 / 28.0).abs() < 1e-15, "∫ s^27 = {s}");
    }
}
