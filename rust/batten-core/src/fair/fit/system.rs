//! Dierckx's least-squares system for one knot vector (the observation matrix triangularised
//! by Givens rotations, Dierckx 1993 ch. 4), updated in place as knots are inserted, with the
//! smoothing and constrained solves on it.

use glam::DVec3;

use super::super::knots::{clamped, jump_rows, Design};
use super::super::lsq::BandedQr;
use super::{Ends, Spline, ZeroCurvature, REL_ACC};

/// The least-squares machinery for one knot vector, updated in place as knots are inserted.
///
/// A datum's observation row has non-zeros in the `k + 1` columns of its knot span only, so
/// the observations of each span are first rotated into a small triangle of their own (a
/// `block`), and the blocks are then rotated into the band triangle in span order (a Givens
/// QR of the same rows, grouped). Inserting a knot changes the observation rows of the `2k − 1`
/// spans around it only: the other blocks are kept (those after it move one column along),
/// and the merge restarts at the first changed span from a saved copy of the `k` triangle rows
/// that later blocks can still change (`checkpoints`, one per span). The triangle is then bit
/// for bit the one [`System::new`] builds on the new knots, at the cost of `2k` spans of
/// data and `n − s` small blocks instead of all the data.
#[derive(Clone)]
pub(crate) struct System {
    pub(super) degree: usize,
    pub(super) knots: Vec<f64>,
    n: usize,
    /// Free coefficients are `first_free..first_free + qr.unknowns()`.
    first_free: usize,
    fixed: Vec<(usize, DVec3)>,
    pub(super) design: Design,
    points: Vec<DVec3>,
    params: Vec<f64>,
    ends: Ends,
    /// One past the last free coefficient.
    last_free: usize,
    pub(super) ls: BandedQr,
    /// Per knot span `l`: the first free column of its block and the block, the observations
    /// of span `l` rotated into a triangle over the span's free columns.
    blocks: Vec<(usize, BandedQr)>,
    /// Per knot span `l`: triangle rows `l − k − first_free .. l − first_free` (those that
    /// exist) and their right-hand sides before block `l` is merged.
    cp_rows: Vec<f64>,
    cp_z: Vec<DVec3>,
    /// `F(0)`, the least-squares polynomial's E, once a search for p has needed it (NaN
    /// before).
    pub(super) f_zero: f64,
}

/// The fixed coefficients for `knots`: end points, and the neighbours fixed by end derivatives.
/// Returns them with the range of free coefficients.
fn fixed_coefficients(
    knots: &[f64],
    degree: usize,
    ends: &Ends,
) -> (Vec<(usize, DVec3)>, usize, usize) {
    let k = degree;
    let n = knots.len() - k - 1;
    let mut fixed = vec![(0, ends.start), (n - 1, ends.end)];
    let mut first_free = 1;
    let mut last_free = n - 1; // exclusive
    if let Some(d) = ends.start_derivative {
        // C'(a) = k (c1 − c0) / (t[k+1] − t[1])  (Piegl & Tiller eq. 3.7)
        fixed.push((1, ends.start + d * (knots[k + 1] - knots[1]) / k as f64));
        first_free = 2;
    }
    if let Some(d) = ends.end_derivative {
        fixed.push((
            n - 2,
            ends.end - d * (knots[n + k - 1] - knots[n - 1]) / k as f64,
        ));
        last_free = n - 2;
    }
    (fixed, first_free, last_free)
}

impl System {
    pub(super) fn new(
        degree: usize,
        knots: Vec<f64>,
        points: &[DVec3],
        params: &[f64],
        ends: &Ends,
    ) -> Self {
        let k = degree;
        let n = knots.len() - k - 1;
        let (fixed, first_free, last_free) = fixed_coefficients(&knots, k, ends);
        let free = last_free.saturating_sub(first_free);
        let design = Design::new(&knots, k, params);
        let mut sys = System {
            degree,
            knots,
            n,
            first_free,
            fixed,
            design,
            points: points.to_vec(),
            params: params.to_vec(),
            ends: *ends,
            last_free,
            ls: BandedQr::new(free, k + 1),
            blocks: Vec::new(),
            cp_rows: Vec::new(),
            cp_z: Vec::new(),
            f_zero: f64::NAN,
        };
        sys.blocks = (0..n).map(|l| sys.block(l)).collect();
        sys.merge_from(0);
        sys
    }

    /// The free columns of knot span `l`: the first, and how many.
    fn span_columns(&self, l: usize) -> (usize, usize) {
        let k = self.degree;
        let lo = l.saturating_sub(k).max(self.first_free);
        let hi = (l + 1).min(self.last_free);
        (lo - self.first_free, hi.saturating_sub(lo))
    }

    /// The observations of knot span `l` rotated into a triangle over its free columns.
    fn block(&self, l: usize) -> (usize, BandedQr) {
        let k = self.degree;
        let (base, width) = self.span_columns(l);
        let mut qr = BandedQr::new(width, k + 1);
        if l < k || width == 0 {
            return (base, qr);
        }
        let span = &self.design.span;
        let from = span.partition_point(|&s| s < l);
        let to = span.partition_point(|&s| s <= l);
        let mut h = [0.0; crate::curve::MAX_ORDER];
        if width == k + 1 {
            // Every coefficient of the span is free (the fixed ones are those outside
            // `first_free..last_free`): the rows are the basis values as they are.
            for i in from..to {
                h[..=k].copy_from_slice(&self.design.basis[i][..=k]);
                qr.add_row(0, &mut h[..=k], self.points[i]);
            }
            return (base, qr);
        }
        for i in from..to {
            let b = &self.design.basis[i];
            let mut rhs = self.points[i];
            let mut len = 0;
            for (j, &bj) in b.iter().enumerate().take(k + 1) {
                let col = l - k + j;
                if let Some(&(_, v)) = self.fixed.iter().find(|(c, _)| *c == col) {
                    rhs -= v * bj;
                } else {
                    h[len] = bj;
                    len += 1;
                }
            }
            if len > 0 {
                qr.add_row(0, &mut h[..len], rhs);
            }
        }
        (base, qr)
    }

    /// Save the rows later blocks may change, for knot span `l` (before block `l` is merged).
    fn checkpoint(&mut self, l: usize) {
        let k = self.degree;
        let band = self.ls.band();
        for q in 0..k {
            let r = (l + q).wrapping_sub(k + self.first_free);
            if r < self.ls.unknowns() {
                let (row, z) = self.ls.row(r);
                let at = (l * k + q) * band;
                self.cp_rows[at..at + band].copy_from_slice(row);
                self.cp_z[l * k + q] = z;
            }
        }
    }

    /// Merge the blocks of spans `from..` into the triangle, saving a checkpoint before each.
    fn merge_from(&mut self, from: usize) {
        let k = self.degree;
        let band = self.ls.band();
        self.cp_rows.resize((self.n + 1) * k * band, 0.0);
        self.cp_z.resize((self.n + 1) * k, DVec3::ZERO);
        let mut h = [0.0; crate::curve::MAX_ORDER];
        for l in from..self.n {
            self.checkpoint(l);
            let (base, block) = &self.blocks[l];
            for q in 0..block.unknowns() {
                let (row, z) = block.row(q);
                let len = block.unknowns() - q;
                h[..len].copy_from_slice(&row[..len]);
                self.ls.add_row(base + q, &mut h[..len], z);
            }
        }
        self.checkpoint(self.n);
    }

    /// Insert the interior knot `t` and update the least-squares triangle (bit for bit the
    /// triangle of [`System::new`] on the new knots).
    pub(super) fn insert(&mut self, t: f64) {
        let k = self.degree;
        // t lies in knot span s: knots[s] < t < knots[s+1]. The basis values on span l use
        // knots l − k + 1 ..= l + k, so the data of spans s − k + 1 ..= s + k − 1 get new rows
        // (they become the new spans s − k + 1 ..= s + k); earlier data keep theirs, later data
        // keep theirs one span (and column) along. (The fixed end derivatives change only for
        // s = k or s = n − 1, where the spans whose rows hold them are among the changed.)
        let s = self.knots.partition_point(|&u| u <= t) - 1;
        self.knots.insert(s + 1, t);
        let old_n = self.n;
        self.n += 1;
        let (fixed, first_free, last_free) = fixed_coefficients(&self.knots, k, &self.ends);
        debug_assert_eq!(first_free, self.first_free, "the same end conditions");
        self.fixed = fixed;
        self.last_free = last_free;
        let free = last_free.saturating_sub(first_free);
        let first = (s + 1).saturating_sub(k);
        let changed_to = (s + k).min(old_n);
        let span = &mut self.design.span;
        let from = span.partition_point(|&l| l < first);
        let to = span.partition_point(|&l| l < changed_to);
        for l in &mut span[to..] {
            *l += 1;
        }
        self.design
            .update_range(&self.knots, &self.params, from, to);
        let old = std::mem::take(&mut self.blocks);
        let mut blocks = Vec::with_capacity(self.n);
        blocks.extend(old[..first].iter().cloned());
        self.blocks = blocks;
        for l in first..=changed_to {
            let b = self.block(l);
            self.blocks.push(b);
        }
        self.blocks.extend(
            old.into_iter()
                .skip(changed_to)
                .map(|(base, b)| (base + 1, b)),
        );
        // Rows before first − k − first_free are final; the next k come from the checkpoint.
        let keep = first.saturating_sub(k).saturating_sub(self.first_free);
        let old_free = self.ls.unknowns();
        self.ls.truncate_resize(free, keep);
        let band = self.ls.band();
        for q in 0..k {
            let r = (first + q).wrapping_sub(k + self.first_free);
            if r < old_free && r < free {
                let at = (first * k + q) * band;
                let z = self.cp_z[first * k + q];
                self.ls.set_row(r, &self.cp_rows[at..at + band], z);
            }
        }
        self.merge_from(first);
    }

    /// The row `g` (over the free coefficients) and the fixed coefficients' part `r0` of the
    /// condition `Σⱼ N″ⱼ(t)·(cⱼ · w) = 0`.
    fn condition(&self, c: &ZeroCurvature) -> (Vec<f64>, f64) {
        let k = self.degree;
        let span = crate::curve::find_span(&self.knots, k, self.n, c.t);
        let mut d = [[0.0; crate::curve::MAX_ORDER]; 4];
        crate::curve::ders_basis_funs(&self.knots, span, c.t, k, 2, &mut d);
        let mut g = vec![0.0; self.ls.unknowns()];
        let mut r0 = 0.0;
        for (j, &b) in d[2].iter().enumerate().take(k + 1) {
            let col = span - k + j;
            if let Some(&(_, v)) = self.fixed.iter().find(|(fc, _)| *fc == col) {
                r0 += b * v.dot(c.w);
            } else {
                g[col - self.first_free] = b;
            }
        }
        (g, r0)
    }

    /// The free coefficients `x` of the least-squares problem with triangle `tri`, corrected
    /// to the minimiser of the same problem under the end conditions `cons` (Lagrange
    /// multipliers: `X = X* − Σᵢ (AᵀA)⁻¹gᵢ λᵢ wᵢᵀ` with `Σⱼ (gᵢᵀ(AᵀA)⁻¹gⱼ)(wᵢ·wⱼ) λⱼ = rᵢ`,
    /// `rᵢ` the condition's value at `X*`; Lawson & Hanson 1974 ch. 20). `None` when the
    /// conditions cannot be imposed (no free coefficient in them, or they are dependent).
    fn constrain(
        &self,
        tri: &BandedQr,
        mut x: Vec<DVec3>,
        cons: &[ZeroCurvature],
    ) -> Option<Vec<DVec3>> {
        if cons.is_empty() {
            return Some(x);
        }
        let rows: Vec<(Vec<f64>, f64)> = cons.iter().map(|c| self.condition(c)).collect();
        let ys: Vec<Vec<f64>> = rows
            .iter()
            .map(|(g, _)| tri.solve_normal(g))
            .collect::<Option<_>>()?;
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
        let r: Vec<f64> = rows
            .iter()
            .zip(cons)
            .map(|((g, r0), c)| {
                g.iter()
                    .zip(&x)
                    .map(|(gj, xj)| gj * xj.dot(c.w))
                    .sum::<f64>()
                    + r0
            })
            .collect();
        let q = cons.len();
        let mut h = vec![0.0; q * q];
        for i in 0..q {
            for j in 0..q {
                h[i * q + j] = dot(&rows[i].0, &ys[j]) * cons[i].w.dot(cons[j].w);
            }
        }
        let lambda = cholesky_solve(&mut h, r)?;
        for ((y, l), c) in ys.iter().zip(&lambda).zip(cons) {
            for (xj, yj) in x.iter_mut().zip(y) {
                *xj -= c.w * (yj * l);
            }
        }
        Some(x)
    }

    /// The system of the same data and end conditions on the knots of a cold start (none, or
    /// the few the end conditions need): the least-squares polynomial, whose E is `F(0)`.
    pub(super) fn polynomial(&self) -> System {
        let params = &self.params;
        let (a, b) = (params[0], params[params.len() - 1]);
        let cold = initial_interior(self.degree, &self.ends, params);
        let knots = clamped(self.degree, a, b, &cold);
        System::new(self.degree, knots, &self.points, params, &self.ends)
    }

    /// `F(0)` as found by the search for p (NaN when there was none).
    pub(crate) fn f_zero(&self) -> f64 {
        self.f_zero
    }

    /// Number of data points.
    pub(crate) fn data_count(&self) -> usize {
        self.points.len()
    }

    /// All coefficients from the free ones.
    fn full(&self, free: &[DVec3]) -> Vec<DVec3> {
        let mut c = vec![DVec3::ZERO; self.n];
        c[self.first_free..self.first_free + free.len()].copy_from_slice(free);
        for &(j, v) in &self.fixed {
            c[j] = v;
        }
        c
    }

    /// Squared residual per data point.
    pub(super) fn residuals2(&self, c: &[DVec3]) -> Vec<f64> {
        self.points
            .iter()
            .enumerate()
            .map(|(i, q)| (self.design.value(i, c) - *q).length_squared())
            .collect()
    }

    /// The least-squares spline (p = ∞).
    pub(super) fn least_squares(&self) -> Option<Vec<DVec3>> {
        self.least_squares_with(&[])
    }

    /// The least-squares spline under the end conditions `cons`.
    pub(super) fn least_squares_with(&self, cons: &[ZeroCurvature]) -> Option<Vec<DVec3>> {
        let x = self.constrain(&self.ls, self.ls.solve()?, cons)?;
        Some(self.full(&x))
    }

    /// The smoothing spline for `p` > 0 under the end conditions `cons` (none: fpcurf part 2).
    pub(super) fn smoothing(&self, p: f64, cons: &[ZeroCurvature]) -> Option<Vec<DVec3>> {
        let g = self.smoothing_triangle(p);
        let x = self.constrain(&g, g.solve()?, cons)?;
        Some(self.full(&x))
    }

    /// The least-squares triangle with the jump rows, scaled by 1/p, rotated in (fpcurf
    /// part 2).
    fn smoothing_triangle(&self, p: f64) -> BandedQr {
        let k = self.degree;
        let pinv = 1.0 / p;
        let mut g = self.ls.widened(k + 2);
        let free = g.unknowns();
        let mut h = [0.0; crate::curve::MAX_ORDER + 1];
        for row in jump_rows(&self.knots, k) {
            let mut rhs = DVec3::ZERO;
            let mut lo = usize::MAX;
            let mut len = 0;
            for j in 0..k + 2 {
                let col = row.first + j;
                let bj = row.b[j] * pinv;
                if let Some(&(_, v)) = self.fixed.iter().find(|(c, _)| *c == col) {
                    rhs -= v * bj;
                } else {
                    if lo == usize::MAX {
                        lo = col;
                    }
                    h[len] = bj;
                    len += 1;
                }
            }
            if len > 0 && free > 0 {
                g.add_row(lo - self.first_free, &mut h[..len], rhs);
            }
        }
        g
    }

    pub(super) fn spline(&self, coefs: Vec<DVec3>, p: f64, fp: f64, s: f64) -> Spline {
        Spline {
            degree: self.degree,
            knots: self.knots.clone(),
            coefs,
            p,
            fp,
            reached: fp <= s * (1.0 + REL_ACC),
        }
    }
}

/// How many fixed coefficients the end conditions take.
fn fixed_count(ends: &Ends) -> usize {
    2 + usize::from(ends.start_derivative.is_some()) + usize::from(ends.end_derivative.is_some())
}

/// Interior knots needed before any free coefficient exists (only when the end conditions fix
/// more coefficients than a polynomial of this degree has).
pub(super) fn initial_interior(degree: usize, ends: &Ends, params: &[f64]) -> Vec<f64> {
    let need = fixed_count(ends).saturating_sub(degree + 1);
    let m = params.len();
    (1..=need)
        .map(|i| params[i * (m - 1) / (need + 1)])
        .collect()
}

/// Solve `H x = b` for a small symmetric positive definite `H` (row-major, overwritten by
/// its Cholesky factor); `None` when `H` is not positive definite to working accuracy (the
/// conditions are dependent).
fn cholesky_solve(h: &mut [f64], mut b: Vec<f64>) -> Option<Vec<f64>> {
    let q = b.len();
    let scale = (0..q).map(|i| h[i * q + i]).fold(0.0, f64::max);
    for j in 0..q {
        let mut d = h[j * q + j];
        for l in 0..j {
            d -= h[j * q + l] * h[j * q + l];
        }
        if d.is_nan() || d <= 1e-12 * scale {
            return None;
        }
        let d = d.sqrt();
        h[j * q + j] = d;
        for i in j + 1..q {
            let mut v = h[i * q + j];
            for l in 0..j {
                v -= h[i * q + l] * h[j * q + l];
            }
            h[i * q + j] = v / d;
        }
    }
    for i in 0..q {
        for l in 0..i {
            b[i] -= h[i * q + l] * b[l];
        }
        b[i] /= h[i * q + i];
    }
    for i in (0..q).rev() {
        for l in i + 1..q {
            b[i] -= h[l * q + i] * b[l];
        }
        b[i] /= h[i * q + i];
    }
    Some(b)
}
