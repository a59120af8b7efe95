//! A patch surface as cells of Bernstein polynomials, for exact-to-rounding integration.
//!
//! Each patch's domain is cut into quadrilaterals — the unit square of a 4-sided patch, or the N
//! kites (vertex, side midpoint, centre, side midpoint) of an N-gon — and each into cells
//! (a `k × k` grid, halved [`CellDensity::corner_levels`] more times towards the patch's corners, where the
//! Gregory and Charrot–Gregory blends are least smooth). On every cell the surface is
//! interpolated at Chebyshev–Lobatto nodes by a tensor polynomial of degree
//! [`DEGREE`](super::bernstein::DEGREE), held as a Bernstein net: its values follow the patch
//! to near rounding, its bounds are the net's (convex hull), its normals are exact derivatives,
//! and neighbouring cells share their edge nodes, so the cells are as watertight as the patches.
//!
//! A cell keeps the integrals over its whole square of `N`, `P_j N` and `P_j P_k N` (`N` the
//! outward area normal) and of `|N|`: any wet-surface integral of a cell entirely under water
//! is a linear combination of them, whatever the waterplane.

use glam::{DVec2, DVec3};

use super::bernstein::{basis, gauss, interpolation_matrix, lobatto_nodes, GAUSS, N};
use super::integrals::WetIntegrals;
use super::waterplane::Waterplane;
use crate::patch::{Domain, Patch};

/// How finely the patches are cut into cells: `per_quad × per_quad` cells per domain
/// quadrilateral, the cell at a patch corner halved `corner_levels` more times.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellDensity {
    /// Cells per quadrilateral side.
    pub per_quad: usize,
    /// Halvings of the cells at the patches' corners.
    pub corner_levels: usize,
}

impl CellDensity {
    /// The density batten uses: on the Wigley hull and the frigate its volume, waterplane and
    /// wetted area agree with those of `{4, 5}` (8,512 cells on the Wigley) to 4e-10 relative
    /// (see the hydrostatics tests).
    pub const DEFAULT: CellDensity = CellDensity {
        per_quad: 2,
        corner_levels: 2,
    };

    /// A coarser density for figures updated while a control point is dragged: about 10× fewer
    /// cells, within about 1e-8 relative of [`CellDensity::DEFAULT`] on the example hulls.
    pub const LIVE: CellDensity = CellDensity {
        per_quad: 1,
        corner_levels: 1,
    };
}

/// Integrals over a cell's whole square (ship axes): `∫ N`, `∫ P_j N`, `∫ P_j P_k N` (`j ≤ k`,
/// in the order xx, xy, xz, yy, yz, zz) and `∫ |N|`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct CellMoments {
    /// `∫ N dA`.
    pub(crate) m0: DVec3,
    /// `∫ P_j N dA`, `j` = x, y, z.
    pub(crate) m1: [DVec3; 3],
    /// `∫ P_j P_k N dA`.
    pub(crate) m2: [DVec3; 6],
    /// `∫ |N| dA`.
    pub(crate) area: f64,
}

/// The index of `(j, k)` in [`CellMoments::m2`].
const fn pair(j: usize, k: usize) -> usize {
    let (a, b) = if j <= k { (j, k) } else { (k, j) };
    match (a, b) {
        (0, 0) => 0,
        (0, 1) => 1,
        (0, 2) => 2,
        (1, 1) => 3,
        (1, 2) => 4,
        _ => 5,
    }
}

impl CellMoments {
    pub(crate) fn add(&mut self, o: &CellMoments) {
        self.m0 += o.m0;
        for j in 0..3 {
            self.m1[j] += o.m1[j];
        }
        for j in 0..6 {
            self.m2[j] += o.m2[j];
        }
        self.area += o.area;
    }

    /// The wet-surface integrals in `plane`'s frame of the surface these moments cover (all of
    /// it under water): each integrand is `a(P)·b(P)·(e3·N)` with `a`, `b` affine in `P`.
    pub(crate) fn in_frame(&self, plane: &Waterplane) -> WetIntegrals {
        let e3 = plane.e3;
        let (m0, m1, m2) = (
            e3.dot(self.m0),
            [e3.dot(self.m1[0]), e3.dot(self.m1[1]), e3.dot(self.m1[2])],
            self.m2.map(|v| e3.dot(v)),
        );
        // ∫ a b n_ζ for a = α·P + α0, b = β·P + β0.
        let quad = |al: DVec3, a0: f64, be: DVec3, b0: f64| -> f64 {
            let (al, be) = (al.to_array(), be.to_array());
            let mut s = a0 * b0 * m0;
            for j in 0..3 {
                s += (al[j] * b0 + be[j] * a0) * m1[j];
                for k in 0..3 {
                    s += al[j] * be[k] * m2[pair(j, k)];
                }
            }
            s
        };
        let o = plane.origin;
        let (x, x0) = (plane.e1, -plane.e1.dot(o));
        let (y, y0) = (plane.e2, -plane.e2.dot(o));
        let (z, z0) = (plane.e3, -plane.e3.dot(o));
        let one = (DVec3::ZERO, 1.0);
        WetIntegrals {
            volume: quad(z, z0, one.0, one.1),
            v_xi: quad(x, x0, z, z0),
            v_eta: quad(y, y0, z, z0),
            v_zeta: 0.5 * quad(z, z0, z, z0),
            wetted: self.area,
            wp_area: -m0,
            wp_xi: -quad(x, x0, one.0, one.1),
            wp_eta: -quad(y, y0, one.0, one.1),
            wp_xixi: -quad(x, x0, x, x0),
            wp_etaeta: -quad(y, y0, y, y0),
            wp_xieta: -quad(x, x0, y, y0),
        }
    }
}

/// One cell: the Bernstein net of the surface over it (`net[i][j]`, `i` along `s`, `j` along
/// `t`), the sign making `P_s × P_t` outward, and its moments.
#[derive(Clone, Debug)]
pub(crate) struct Cell {
    /// Bernstein coefficients of `P(s, t)` on `[0, 1]²`.
    pub(crate) net: [[DVec3; N]; N],
    /// `+1` when `P_s × P_t` points out of the hull, else `−1`.
    pub(crate) sign: f64,
    /// Integrals over the whole cell.
    pub(crate) moments: CellMoments,
}

impl Cell {
    /// The point at `(s, t)` (no derivatives).
    #[inline]
    pub(crate) fn point(&self, s: f64, t: f64) -> DVec3 {
        let (bs, _) = basis(s);
        let (bt, _) = basis(t);
        self.net
            .iter()
            .zip(bs)
            .map(|(row, b)| row.iter().zip(bt).map(|(q, c)| *q * c).sum::<DVec3>() * b)
            .sum()
    }

    /// Call `f` with the points of the grid `(s_a, t_b)` whose Bernstein bases are
    /// `bases[a]` and `bases[b]`, in order of `a`, then `b` (sum-factorised: a column per `s_a`).
    pub(crate) fn grid_points(&self, bases: &[[f64; N]], mut f: impl FnMut(DVec3)) {
        for bs in bases {
            let mut col = [DVec3::ZERO; N];
            for (i, row) in self.net.iter().enumerate() {
                for (c, p) in col.iter_mut().zip(row) {
                    *c += *p * bs[i];
                }
            }
            for bt in bases {
                f(col.iter().zip(bt).map(|(c, b)| *c * *b).sum());
            }
        }
    }

    /// The 1-D nets along `t` at fixed `s`: of `P(s, ·)` and of `P_s(s, ·)`.
    #[inline]
    pub(crate) fn column(&self, s: f64) -> ([DVec3; N], [DVec3; N]) {
        let (bs, ds) = basis(s);
        let mut c = [DVec3::ZERO; N];
        let mut cs = [DVec3::ZERO; N];
        for i in 0..N {
            for j in 0..N {
                c[j] += self.net[i][j] * bs[i];
                cs[j] += self.net[i][j] * ds[i];
            }
        }
        (c, cs)
    }

    /// The 1-D nets along `s` at fixed `t`: of `P(·, t)` and of `P_t(·, t)`.
    #[inline]
    pub(crate) fn row(&self, t: f64) -> ([DVec3; N], [DVec3; N]) {
        let (bt, dt) = basis(t);
        let mut r = [DVec3::ZERO; N];
        let mut rt = [DVec3::ZERO; N];
        for i in 0..N {
            for j in 0..N {
                r[i] += self.net[i][j] * bt[j];
                rt[i] += self.net[i][j] * dt[j];
            }
        }
        (r, rt)
    }

    /// The net of the affine function `m·P − c` over the cell.
    #[inline]
    pub(crate) fn scalar_net(&self, m: DVec3, c: f64) -> [[f64; N]; N] {
        self.net.map(|row| row.map(|p| m.dot(p) - c))
    }
}

/// A domain quadrilateral: corners in the patch's domain (counter-clockwise) and which of them
/// are corners of the patch.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quad {
    c: [DVec2; 4],
    patch_corner: [bool; 4],
}

impl Quad {
    /// The domain point at quad parameters `(s, t)` (bilinear).
    pub(crate) fn at(&self, s: f64, t: f64) -> DVec2 {
        let c = &self.c;
        c[0] * ((1.0 - s) * (1.0 - t))
            + c[1] * (s * (1.0 - t))
            + c[2] * (s * t)
            + c[3] * ((1.0 - s) * t)
    }
}

/// The quadrilaterals of a domain: the square itself, or the N-gon's kites.
pub(crate) fn quads(domain: &Domain) -> Vec<Quad> {
    let v: Vec<DVec2> = domain.vertices().into_iter().map(DVec2::from).collect();
    let n = v.len();
    if n == 4 {
        return vec![Quad {
            c: [v[0], v[1], v[2], v[3]],
            patch_corner: [true; 4],
        }];
    }
    let centre = DVec2::from(domain.centre());
    (0..n)
        .map(|k| {
            let mid_next = 0.5 * (v[k] + v[(k + 1) % n]);
            let mid_prev = 0.5 * (v[k] + v[(k + n - 1) % n]);
            Quad {
                c: [v[k], mid_next, centre, mid_prev],
                patch_corner: [true, false, false, false],
            }
        })
        .collect()
}

/// The cells of a quad as parameter boxes `(s0, s1, t0, t1)`: a `k × k` grid, the boxes at the
/// patch's corners halved `levels` more times towards them.
pub(crate) fn boxes(q: &Quad, k: usize, levels: usize) -> Vec<[f64; 4]> {
    let mut out = Vec::new();
    let h = 1.0 / k as f64;
    for a in 0..k {
        for b in 0..k {
            let bx = [
                a as f64 * h,
                (a + 1) as f64 * h,
                b as f64 * h,
                (b + 1) as f64 * h,
            ];
            // Which quad corner (if any, and a patch corner) this box touches.
            let touch = [
                a == 0 && b == 0,
                a == k - 1 && b == 0,
                a == k - 1 && b == k - 1,
                a == 0 && b == k - 1,
            ];
            match (0..4).find(|&c| touch[c] && q.patch_corner[c]) {
                Some(c) => graded(bx, c, levels, &mut out),
                None => out.push(bx),
            }
        }
    }
    out
}

/// Halve `bx` into four `levels` times, each time again at its corner `corner` (0: `(s0,t0)`,
/// 1: `(s1,t0)`, 2: `(s1,t1)`, 3: `(s0,t1)`).
fn graded(bx: [f64; 4], corner: usize, levels: usize, out: &mut Vec<[f64; 4]>) {
    if levels == 0 {
        out.push(bx);
        return;
    }
    let [s0, s1, t0, t1] = bx;
    let (sm, tm) = (0.5 * (s0 + s1), 0.5 * (t0 + t1));
    let kids = [
        [s0, sm, t0, tm],
        [sm, s1, t0, tm],
        [sm, s1, tm, t1],
        [s0, sm, tm, t1],
    ];
    for (i, kid) in kids.into_iter().enumerate() {
        if i == corner {
            graded(kid, corner, levels - 1, out);
        } else {
            out.push(kid);
        }
    }
}

/// The Bernstein net interpolating `patch` over parameter box `bx` of quad `q`.
pub(crate) fn interpolate(patch: &Patch, q: &Quad, bx: [f64; 4]) -> [[DVec3; N]; N] {
    let nodes = lobatto_nodes();
    let m = interpolation_matrix();
    let [s0, s1, t0, t1] = bx;
    let mut vals = [[DVec3::ZERO; N]; N];
    for (i, row) in vals.iter_mut().enumerate() {
        let s = s0 + (s1 - s0) * nodes[i];
        for (j, v) in row.iter_mut().enumerate() {
            let t = t0 + (t1 - t0) * nodes[j];
            *v = patch.eval(q.at(s, t).to_array());
        }
    }
    // net = M⁻¹ · vals · M⁻ᵀ.
    let mut tmp = [[DVec3::ZERO; N]; N];
    for i in 0..N {
        for j in 0..N {
            tmp[i][j] = (0..N).map(|k| vals[k][j] * m[i][k]).sum();
        }
    }
    let mut net = [[DVec3::ZERO; N]; N];
    for i in 0..N {
        for j in 0..N {
            net[i][j] = (0..N).map(|k| tmp[i][k] * m[j][k]).sum();
        }
    }
    net
}

/// The integrals of a net over its whole square by the [`GAUSS`]-point tensor rule
/// (sum-factorised), `sign` orienting the normal.
fn moments(net: &[[DVec3; N]; N], sign: f64) -> CellMoments {
    let (x, w) = gauss();
    let basis_at: Vec<([f64; N], [f64; N])> = x.iter().map(|&s| basis(s)).collect();
    // Partial sums along t: T[i][q] = Σ_j net[i][j] B_j(t_q), TD likewise with B'_j.
    let mut tb = [[DVec3::ZERO; GAUSS]; N];
    let mut td = [[DVec3::ZERO; GAUSS]; N];
    for i in 0..N {
        for q in 0..GAUSS {
            let (b, d) = &basis_at[q];
            for j in 0..N {
                tb[i][q] += net[i][j] * b[j];
                td[i][q] += net[i][j] * d[j];
            }
        }
    }
    let mut out = CellMoments::default();
    for qa in 0..GAUSS {
        let (b, d) = &basis_at[qa];
        for qb in 0..GAUSS {
            let mut p = DVec3::ZERO;
            let mut ps = DVec3::ZERO;
            let mut pt = DVec3::ZERO;
            for i in 0..N {
                p += tb[i][qb] * b[i];
                ps += tb[i][qb] * d[i];
                pt += td[i][qb] * b[i];
            }
            let n = ps.cross(pt) * (sign * w[qa] * w[qb]);
            let pa = p.to_array();
            out.m0 += n;
            for j in 0..3 {
                out.m1[j] += n * pa[j];
                for k in j..3 {
                    out.m2[pair(j, k)] += n * (pa[j] * pa[k]);
                }
            }
            out.area += n.length();
        }
    }
    out
}

/// The cells of one patch, `outward` saying whether the patches' `P_u × P_v` points out of the
/// hull.
pub(crate) fn patch_cells(patch: &Patch, outward: bool, density: CellDensity) -> Vec<Cell> {
    let sign = if outward { 1.0 } else { -1.0 };
    let mut cells = Vec::new();
    for q in &quads(patch.domain()) {
        for bx in boxes(q, density.per_quad.max(1), density.corner_levels) {
            let net = interpolate(patch, q, bx);
            let moments = moments(&net, sign);
            cells.push(Cell { net, sign, moments });
        }
    }
    cells
}

#[cfg(test)]
pub(crate) fn moments_of(cell: &Cell) -> CellMoments {
    moments(&cell.net, cell.sign)
}
