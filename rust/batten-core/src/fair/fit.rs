//! The smoothing spline of one smooth piece for fixed data parameters: Dierckx's `fpcurf`
//! (Dierckx 1993 ch. 5, routines curfit/parcur) with the H-rep paper's one-knot-at-a-time rule.
//!
//! Part 1 adds knots until the least-squares spline `s∞` satisfies `F(∞) = E(s∞) ≤ S`; part 2
//! finds `p` with `F(p) = S` for the spline minimising `E + J/p²` (Dierckx's scaling of the
//! paper's `J + p·E`), by Dierckx's rational interpolation (`fprati`). The end points are
//! interpolated by fixing the end control points; fixed end derivatives fix the next control
//! point too (as Dierckx's concur does with end derivatives).
//!
//! Implementation note: where fpcurf refactorises the whole observation matrix after each knot
//! step, the triangle here is updated in place at each insertion (see `System`): only the data
//! of the spans around the new knot are rotated again, and the per-span triangles after it are
//! merged again from a saved state, which is the same least-squares problem solved by the same
//! Givens rotations, grouped by span. Dierckx's fpcurf also adds several knots per step once it
//! can estimate how many are needed (its `nplus`); that changes the knots chosen and gave a less
//! fair curve on the KCS section benchmark (2,000 noisy points: 77 instead of 48 interior knots
//! and 46 instead of 25 inflections), so knots are still added one at a time.

use glam::DVec3;

use super::knots::{clamped, jump_rows, next_knots, schoenberg_whitney, Design};
use super::lsq::BandedQr;

/// Dierckx's relative tolerance on `F(p) = S` (curfit's `tol = 0.001`).
const REL_ACC: f64 = 1e-3;
/// Dierckx's maximum number of iterations for p (curfit's `maxit = 20`).
const MAX_P_ITER: usize = 20;
/// Step factors of fpcurf when the bracket on p is not yet found (`con1`, `con4`, `con9`).
const CON1: f64 = 0.1;
const CON4: f64 = 0.04;
const CON9: f64 = 0.9;

/// Constraints at the ends of a piece: the end points, and optionally the end derivatives
/// `C'(a)`, `C'(b)` (with respect to the fitting parameter).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ends {
    pub start: DVec3,
    pub end: DVec3,
    pub start_derivative: Option<DVec3>,
    pub end_derivative: Option<DVec3>,
}

/// A linear condition on the fit: `w · C″(t) = 0`, which makes the curvature at `t` zero in
/// the plane with in-plane normal `w` (for `w ⊥ C′(t)`). The condition is linear in the
/// coefficients, so the constrained fit is a least-squares problem with equality
/// constraints, solved by a Lagrange correction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ZeroCurvature {
    /// The parameter (inside the piece's domain).
    pub t: f64,
    /// The direction `w` whose component of `C″(t)` is held at zero.
    pub w: DVec3,
}

/// The smoothing factor S, and the value of `F(∞)` at which knot insertion may stop (`≥ s`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Target {
    pub s: f64,
    pub accept: f64,
}

impl Target {
    /// Knots are added until `F(∞) ≤ s` (Dierckx's rule).
    pub fn exact(s: f64) -> Self {
        Target { s, accept: s }
    }
}

/// A fitted piece: a clamped B-spline on `[params[0], params[m-1]]`.
#[derive(Clone, Debug)]
pub(crate) struct Spline {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub coefs: Vec<DVec3>,
    /// The smoothing parameter: 0 for the least-squares polynomial, ∞ for the least-squares
    /// spline, otherwise the root of `F(p) = S` (Dierckx's scaling).
    pub p: f64,
    /// `E`, the sum of squared residuals at the data parameters.
    pub fp: f64,
    /// True when `E ≤ S` within Dierckx's tolerance.
    pub reached: bool,
}

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
pub(crate) struct System {
    degree: usize,
    knots: Vec<f64>,
    n: usize,
    /// Free coefficients are `first_free..first_free + qr.unknowns()`.
    first_free: usize,
    fixed: Vec<(usize, DVec3)>,
    design: Design,
    points: Vec<DVec3>,
    params: Vec<f64>,
    ends: Ends,
    /// One past the last free coefficient.
    last_free: usize,
    ls: BandedQr,
    /// Per knot span `l`: the first free column of its block and the block, the observations
    /// of span `l` rotated into a triangle over the span's free columns.
    blocks: Vec<(usize, BandedQr)>,
    /// Per knot span `l`: triangle rows `l − k − first_free .. l − first_free` (those that
    /// exist) and their right-hand sides before block `l` is merged.
    cp_rows: Vec<f64>,
    cp_z: Vec<DVec3>,
    /// `F(0)`, the least-squares polynomial's E, once a search for p has needed it (NaN
    /// before).
    f_zero: f64,
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
    fn new(degree: usize, knots: Vec<f64>, points: &[DVec3], params: &[f64], ends: &Ends) -> Self {
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
    fn insert(&mut self, t: f64) {
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
    fn polynomial(&self) -> System {
        let params = &self.params;
        let (a, b) = (params[0], params[params.len() - 1]);
        let cold = initial_interior(self.degree, &self.ends, params);
        let knots = clamped(self.degree, a, b, &cold);
        System::new(self.degree, knots, &self.points, params, &self.ends)
    }

    /// `F(0)` as found by the search for p (NaN when there was none).
    pub fn f_zero(&self) -> f64 {
        self.f_zero
    }

    /// Number of data points.
    pub fn data_count(&self) -> usize {
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
    fn residuals2(&self, c: &[DVec3]) -> Vec<f64> {
        self.points
            .iter()
            .enumerate()
            .map(|(i, q)| (self.design.value(i, c) - *q).length_squared())
            .collect()
    }

    /// The least-squares spline (p = ∞).
    fn least_squares(&self) -> Option<Vec<DVec3>> {
        self.least_squares_with(&[])
    }

    /// The least-squares spline under the end conditions `cons`.
    fn least_squares_with(&self, cons: &[ZeroCurvature]) -> Option<Vec<DVec3>> {
        let x = self.constrain(&self.ls, self.ls.solve()?, cons)?;
        Some(self.full(&x))
    }

    /// The smoothing spline for `p` > 0 under the end conditions `cons` (none: fpcurf part 2).
    fn smoothing(&self, p: f64, cons: &[ZeroCurvature]) -> Option<Vec<DVec3>> {
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

    fn spline(&self, coefs: Vec<DVec3>, p: f64, fp: f64, s: f64) -> Spline {
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
fn initial_interior(degree: usize, ends: &Ends, params: &[f64]) -> Vec<f64> {
    let need = fixed_count(ends).saturating_sub(degree + 1);
    let m = params.len();
    (1..=need)
        .map(|i| params[i * (m - 1) / (need + 1)])
        .collect()
}

/// The smoothing spline of degree `degree` through `points` at sorted `params` with
/// `E ≤ S` (Dierckx fpcurf with single knot insertion, H-rep paper §4); knot insertion stops
/// at `F(∞) ≤ target.accept`, and when that is above S the least-squares spline is returned.
///
/// Requires at least `degree + 1` points with distinct end parameters; `None` when the
/// parameters cannot determine even the polynomial (Schoenberg–Whitney fails).
pub(crate) fn smoothing_spline(
    points: &[DVec3],
    params: &[f64],
    degree: usize,
    target: Target,
    ends: &Ends,
) -> Option<Spline> {
    fit_with_system(points, params, degree, target, ends, &[], Some(None), None).map(|(sp, _)| sp)
}

/// [`smoothing_spline`] starting from the interior knots `warm` instead of none (they are
/// kept; knots are only added), returning with it the least-squares system of its knots (for
/// a refit under conditions on the same knots and data, [`constrained_fit`]; `None` only when
/// the spline is the last good one before a numerically singular step).
///
/// `search_p`: `None` stops at the least-squares spline once `F(∞)` is within the target
/// (part 1 only); `Some(start)` searches p from `start` (the p of a previous fit to nearly
/// the same data) or, when that is `None`, from fpcurf's first guess. `f_zero`: `F(0)` of a
/// previous fit to nearly the same data, to start that search without fitting the
/// polynomial again.
///
/// `warm` is used only when the Schoenberg–Whitney conditions hold for it at `params`
/// (parameters moved by a correction can leave a span without data); otherwise the search
/// starts from no knots.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_with_system(
    points: &[DVec3],
    params: &[f64],
    degree: usize,
    target: Target,
    ends: &Ends,
    warm: &[f64],
    search_p: Option<Option<f64>>,
    f_zero: Option<f64>,
) -> Option<(Spline, Option<System>)> {
    let k = degree;
    let s = target.s;
    let m = points.len();
    let (a, b) = (params[0], params[m - 1]);
    let acc = REL_ACC * s;
    let cold = initial_interior(k, ends, params);
    let warm_started = warm.len() > cold.len()
        && warm.iter().all(|&t| a < t && t < b)
        && schoenberg_whitney(&clamped(k, a, b, warm), k, params);
    let mut interior = if warm_started {
        warm.to_vec()
    } else {
        cold.clone()
    };

    // Part 1: knots until F(∞) ≤ S, one at a time, each updating the triangle in place.
    let mut fp0: Option<f64> = None;
    let mut previous: Option<Spline> = None;
    let mut system = System::new(k, clamped(k, a, b, &interior), points, params, ends);
    let (mut system, ls_coefs, fp_inf) = loop {
        // Knots are only added where Schoenberg–Whitney holds, so this fails only when
        // rounding makes the system numerically singular: keep the last good spline then.
        let Some(coefs) = system.least_squares() else {
            return previous.map(|sp| (sp, None));
        };
        let r2 = system.residuals2(&coefs);
        let fp: f64 = r2.iter().sum();
        if fp0.is_none() {
            fp0 = Some(fp);
            if fp <= s && !warm_started {
                // The least-squares polynomial is smooth enough (fpcurf ier = -2).
                let sp = system.spline(coefs, 0.0, fp, s);
                return Some((sp, Some(system)));
            }
        }
        if (fp - s).abs() < acc || fp < s {
            break (system, coefs, fp);
        }
        if fp <= target.accept {
            // Within the accepted range above S: the least-squares spline.
            let sp = system.spline(coefs, f64::INFINITY, fp, target.accept);
            return Some((sp, Some(system)));
        }
        // One knot at a time (the paper's rule; see the module note on fpcurf's nplus).
        let ts = next_knots(
            &system.knots,
            k,
            &system.design,
            &r2,
            params,
            1,
            s / m as f64,
        );
        if ts.is_empty() {
            // No span can take a knot: the least-squares spline is the closest we get.
            let sp = system.spline(coefs, f64::INFINITY, fp, s);
            return Some((sp, Some(system)));
        }
        for &t in &ts {
            let pos = interior.partition_point(|&u| u < t);
            interior.insert(pos, t);
        }
        previous = Some(system.spline(coefs, f64::INFINITY, fp, s));
        for &t in &ts {
            system.insert(t);
        }
    };
    let Some(p_start) = search_p else {
        let sp = system.spline(ls_coefs, f64::INFINITY, fp_inf, s);
        return Some((sp, Some(system)));
    };
    if (fp_inf - s).abs() < acc || interior.is_empty() {
        let sp = system.spline(ls_coefs, f64::INFINITY, fp_inf, s);
        return Some((sp, Some(system)));
    }

    // Part 2: p with F(p) = S by rational interpolation (fpcurf, fprati).
    // F(0): the least-squares polynomial's E (the first pass of a cold start).
    let fp0 = match (warm_started, f_zero) {
        (true, Some(f)) if f.is_finite() => f,
        (true, _) => {
            let poly = system.polynomial();
            let c = poly.least_squares()?;
            poly.residuals2(&c).iter().sum()
        }
        (false, _) => fp0.expect("set on the first pass"),
    };
    system.f_zero = fp0;
    let sp = find_p(&system, s, fp0, (ls_coefs, fp_inf), p_start, &[])?;
    Some((sp, Some(system)))
}

/// The smoothing spline of `system` with `F(p) = S` under the end conditions `cons` (fpcurf
/// part 2): p by Dierckx's rational interpolation (`fprati`) between `F(0) = fp0` and the
/// least-squares spline `(coefs, F(∞))`, starting from `p_start` or fpcurf's first guess.
/// Returns the feasible result (`E ≤ S` within tolerance) with the smallest p found, the
/// least-squares spline if no other is.
fn find_p(
    system: &System,
    s: f64,
    fp0: f64,
    (ls_coefs, fp_inf): (Vec<DVec3>, f64),
    p_start: Option<f64>,
    cons: &[ZeroCurvature],
) -> Option<Spline> {
    let acc = REL_ACC * s;
    let eval = |p: f64| -> Option<(Vec<DVec3>, f64)> {
        let c = system.smoothing(p, cons)?;
        let fp = system.residuals2(&c).iter().sum();
        Some((c, fp))
    };
    // Best feasible result (E ≤ S) with the smallest p, starting from the LS spline.
    let mut best = (f64::INFINITY, ls_coefs, fp_inf);
    let (mut p1, mut f1) = (0.0, fp0 - s);
    let (mut p3, mut f3) = (-1.0, fp_inf - s);
    let rn = system.ls.unknowns().max(1) as f64;
    let diag = system.ls.diagonal_sum();
    let mut p = match p_start {
        Some(p) if p.is_finite() && p > 0.0 => p,
        _ if diag > 0.0 => rn / diag,
        _ => 1.0,
    };
    let (mut ich1, mut ich3) = (false, false);
    for _ in 0..MAX_P_ITER {
        let Some((c, fp)) = eval(p) else { break };
        let fpms = fp - s;
        if fpms <= acc && p < best.0 {
            best = (p, c, fp);
        }
        if fpms.abs() < acc {
            break;
        }
        let (p2, f2) = (p, fpms);
        if !ich3 {
            if f2 - f3 <= acc {
                // Initial p too large.
                p3 = p2;
                f3 = f2;
                p *= CON4;
                if p <= p1 {
                    p = p1 * CON9 + p2 * CON1;
                }
                continue;
            }
            if f2 < 0.0 {
                ich3 = true;
            }
        }
        if !ich1 {
            if f1 - f2 <= acc {
                // Initial p too small.
                p1 = p2;
                f1 = f2;
                p /= CON4;
                if p3 >= 0.0 && p >= p3 {
                    p = p2 * CON1 + p3 * CON9;
                }
                continue;
            }
            if f2 > 0.0 {
                ich1 = true;
            }
        }
        if f2 >= f1 || f2 <= f3 {
            // Not monotone as theory says (fpcurf ier = 2): keep the best feasible result.
            break;
        }
        p = fprati(&mut p1, &mut f1, p2, f2, &mut p3, &mut f3);
    }
    let (p, coefs, fp) = best;
    Some(system.spline(coefs, p, fp, s))
}

/// The smoothing spline of `system` (its knots and data; no knot is added) under the
/// conditions `cons`, with `E ≤ target.s` when the constrained least-squares spline can reach
/// it (p searched from `p_start`), otherwise that least-squares spline when its E is within
/// `target.accept`. `None` when neither is possible, when the conditions cannot be imposed, or
/// when they raise the least-squares E by more than `max_increase` (the data reject them).
pub(crate) fn constrained_fit(
    system: &System,
    target: Target,
    cons: &[ZeroCurvature],
    p_start: Option<f64>,
    max_increase: f64,
) -> Option<Spline> {
    let s = target.s;
    let free = system.least_squares()?;
    let coefs = system.least_squares_with(cons)?;
    let fp_inf: f64 = system.residuals2(&coefs).iter().sum();
    if fp_inf - system.residuals2(&free).iter().sum::<f64>() > max_increase {
        return None;
    }
    let k = system.degree;
    let interior = system.knots.len() - 2 * (k + 1);
    if fp_inf > s * (1.0 + REL_ACC) || (fp_inf - s).abs() < REL_ACC * s || interior == 0 {
        return (fp_inf <= target.accept * (1.0 + REL_ACC))
            .then(|| system.spline(coefs, f64::INFINITY, fp_inf, target.accept));
    }
    // F(0) only starts the bracket on p: the free polynomial's of the fit, if it had one (the
    // constrained polynomial's is no smaller), else the constrained polynomial's (or, if the
    // conditions fix it completely or cannot be imposed on it, the free one's).
    if system.f_zero.is_finite() {
        let f0 = system.f_zero.max(fp_inf);
        return find_p(system, s, f0, (coefs, fp_inf), p_start, cons);
    }
    let poly = system.polynomial();
    let c0 = poly
        .least_squares_with(cons)
        .or_else(|| poly.least_squares())?;
    let fp0: f64 = poly.residuals2(&c0).iter().sum();
    find_p(system, s, fp0.max(fp_inf), (coefs, fp_inf), p_start, cons)
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

/// Dierckx's `fprati`: the zero of the rational function `R(p) = (u·p + v)/(p + w)` through
/// `(p1, f1)`, `(p2, f2)`, `(p3, f3)` (`p3 < 0` meaning ∞), then narrowing the bracket so that
/// `f1 > 0 > f3`.
fn fprati(p1: &mut f64, f1: &mut f64, p2: f64, f2: f64, p3: &mut f64, f3: &mut f64) -> f64 {
    let p = if *p3 > 0.0 {
        let h1 = *f1 * (f2 - *f3);
        let h2 = f2 * (*f3 - *f1);
        let h3 = *f3 * (*f1 - f2);
        -(*p1 * p2 * h3 + p2 * *p3 * h1 + *p3 * *p1 * h2) / (*p1 * h1 + p2 * h2 + *p3 * h3)
    } else {
        (*p1 * (*f1 - *f3) * f2 - p2 * (f2 - *f3) * *f1) / ((*f1 - f2) * *f3)
    };
    if f2 < 0.0 {
        *p3 = p2;
        *f3 = f2;
    } else {
        *p1 = p2;
        *f1 = f2;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;

    fn ends(points: &[DVec3]) -> Ends {
        Ends {
            start: points[0],
            end: points[points.len() - 1],
            start_derivative: None,
            end_derivative: None,
        }
    }

    #[test]
    fn a_cubic_is_reproduced_by_the_polynomial_stage() {
        let params: Vec<f64> = (0..20).map(|i| f64::from(i) / 19.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .map(|&u| DVec3::new(u, u * u * u - u, 0.5 * u * u))
            .collect();
        let sp = smoothing_spline(&points, &params, 3, Target::exact(1e-12), &ends(&points))
            .expect("fits");
        assert_eq!(sp.knots.len(), 8, "no interior knot for a cubic");
        assert!(sp.fp < 1e-20, "exact: {}", sp.fp);
        assert_eq!(sp.p, 0.0, "polynomial stage");
    }

    #[test]
    fn inserting_knots_updates_the_triangle_exactly() {
        // The in-place update from the checkpoints gives bit for bit the triangle of a rebuild,
        // with and without fixed end derivatives, for knots anywhere (near the ends included).
        let params: Vec<f64> = (0..80).map(|i| (f64::from(i) / 79.0).powf(1.3)).collect();
        let points: Vec<DVec3> = params
            .iter()
            .map(|&u| DVec3::new(u, (5.0 * u).sin(), 0.3 * (3.0 * u).cos()))
            .collect();
        let mut with_tangents = ends(&points);
        with_tangents.start_derivative = Some(DVec3::new(1.0, 5.0, 0.0));
        with_tangents.end_derivative = Some(DVec3::new(1.0, 1.4, -0.4));
        for (e, degrees) in [(ends(&points), [1, 2, 3, 5]), (with_tangents, [3, 4, 5, 5])] {
            for k in degrees {
                let mut interior: Vec<f64> = Vec::new();
                let mut sys = System::new(k, clamped(k, 0.0, 1.0, &interior), &points, &params, &e);
                for t in [0.5, 0.8, 0.9, 0.03, 0.65, 0.97, 0.3, 0.72, 0.77] {
                    sys.insert(t);
                    interior.push(t);
                    interior.sort_by(f64::total_cmp);
                    let fresh =
                        System::new(k, clamped(k, 0.0, 1.0, &interior), &points, &params, &e);
                    assert_eq!(sys.knots, fresh.knots, "knots");
                    assert_eq!(sys.design.span, fresh.design.span, "spans");
                    let n = fresh.ls.unknowns();
                    assert_eq!(sys.ls.unknowns(), n, "unknowns");
                    for i in 0..n {
                        assert_eq!(sys.ls.row(i), fresh.ls.row(i), "k {k} t {t}: row {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn end_curvature_conditions_are_met_by_the_closest_fit() {
        // Noisy data on a bent curve; the fit with zero end curvature along w at both ends must
        // meet the conditions (checked on the curve itself), and every feasible change of its
        // coefficients must raise E (it is the constrained minimiser).
        let params: Vec<f64> = (0..90).map(|i| f64::from(i) / 89.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .enumerate()
            .map(|(i, &u)| {
                let wobble = 0.01 * ((i * 7 % 5) as f64 - 2.0);
                DVec3::new(3.0 * u, (2.5 * u).sin() + wobble, 0.4 * u * u)
            })
            .collect();
        let e = ends(&points);
        let interior = [0.2, 0.45, 0.7, 0.85];
        let sys = System::new(3, clamped(3, 0.0, 1.0, &interior), &points, &params, &e);
        let cons = [
            ZeroCurvature {
                t: 0.0,
                w: DVec3::new(0.0, 1.0, 0.2).normalize(),
            },
            ZeroCurvature {
                t: 1.0,
                w: DVec3::new(-0.3, 1.0, 0.0).normalize(),
            },
        ];
        let energy = |c: &[DVec3]| -> f64 { sys.residuals2(c).iter().sum() };
        for p in [f64::INFINITY, 30.0] {
            let c = if p.is_infinite() {
                sys.least_squares_with(&cons)
            } else {
                sys.smoothing(p, &cons)
            }
            .expect("fits");
            let curve = NurbsCurve::try_new(3, sys.knots.clone(), c.clone(), None).unwrap();
            for (con, t) in cons.iter().zip([0.0, 1.0]) {
                let d2 = curve.derivs(t).d2;
                assert!(
                    d2.dot(con.w).abs() < 1e-9 * d2.length().max(1.0),
                    "p {p}: w·C'' = {} at {t}",
                    d2.dot(con.w)
                );
            }
            if p.is_finite() {
                continue;
            }
            // Feasible perturbations: along a direction orthogonal to both w, or along w on a
            // coefficient the conditions do not involve (the middle ones).
            let base = energy(&c);
            let across = cons[0].w.cross(cons[1].w).normalize();
            for j in 1..c.len() - 1 {
                let mut dirs = vec![across];
                if (3..c.len() - 3).contains(&j) {
                    dirs.extend([cons[0].w, cons[1].w]);
                }
                for d in dirs {
                    for eps in [1e-3, -1e-3] {
                        let mut moved = c.clone();
                        moved[j] += d * eps;
                        assert!(energy(&moved) > base, "coefficient {j} moved lowers E");
                    }
                }
            }
            let free = sys.least_squares().expect("fits");
            assert!(energy(&free) < base, "the conditions cost something here");
        }
    }

    #[test]
    fn smoothing_hits_the_smoothing_factor() {
        let params: Vec<f64> = (0..60).map(|i| f64::from(i) / 59.0).collect();
        let points: Vec<DVec3> = params
            .iter()
            .enumerate()
            .map(|(i, &u)| {
                let wobble = if i % 2 == 0 { 0.01 } else { -0.01 };
                DVec3::new(u, (6.0 * u).sin() + wobble, 0.0)
            })
            .collect();
        let s = 60.0 * 0.012f64.powi(2);
        let sp =
            smoothing_spline(&points, &params, 3, Target::exact(s), &ends(&points)).expect("fits");
        assert!(sp.reached, "E {} vs S {s}", sp.fp);
        assert!(
            (sp.fp - s).abs() <= 2.0 * REL_ACC * s || sp.p.is_infinite(),
            "F(p) = S: {} vs {s} (p = {})",
            sp.fp,
            sp.p
        );
    }
}
