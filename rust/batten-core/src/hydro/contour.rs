//! Plane sections of a cell: the curve `g(s, t) = m·P(s, t) − c = 0` of its polynomial, found on
//! a grid by marching squares (each crossing of a grid edge solved on the polynomial), then
//! refined — every piece (an arc: its ends and the curve's point between) halved in parameter space and its middle projected onto the curve by
//! Newton steps along `∇g` — until each chord is within the tolerance of the surface.

use glam::{DVec2, DVec3};

use super::bernstein::{basis, bounds, eval1, N};
use super::cells::Cell;
use super::geometry::SectionArc;
use super::roots::bracketed;

/// Grid squares per cell side for marching squares (a cell's polynomial is of degree 7; a plane
/// meets it at most a few times along a grid line, and refinement follows the curve between).
pub(crate) const GRID: usize = 3;
/// Halvings of a piece at most (a piece is then `2⁻¹⁴` of the cell's grid square).
const MAX_REFINE_DEPTH: usize = 14;
/// Newton steps projecting a point onto the curve.
const PROJECTION_STEPS: usize = 4;

/// The value and parameter gradient of the scalar net `g` at `(s, t)`.
#[inline]
fn scalar(g: &[[f64; N]; N], s: f64, t: f64) -> (f64, f64, f64) {
    let (bs, ds) = basis(s);
    let (bt, dt) = basis(t);
    let (mut v, mut vs, mut vt) = (0.0, 0.0, 0.0);
    for i in 0..N {
        let (mut row, mut row_t) = (0.0, 0.0);
        for j in 0..N {
            row += g[i][j] * bt[j];
            row_t += g[i][j] * dt[j];
        }
        v += row * bs[i];
        vs += row * ds[i];
        vt += row_t * bs[i];
    }
    (v, vs, vt)
}

/// A Newton step shorter than this (in the cell's parameters) ends a projection: the next would
/// be of its square's order, below rounding.
const PROJECTION_CONVERGED: f64 = 1e-7;

/// Move `x` onto `g = 0` by Newton steps along the gradient, staying in the cell; with the
/// gradient `(g_s, g_t)` at the last point it was evaluated.
fn project(g: &[[f64; N]; N], mut x: DVec2) -> (DVec2, DVec2) {
    let mut grad = DVec2::ZERO;
    for _ in 0..PROJECTION_STEPS {
        let (v, vs, vt) = scalar(g, x.x, x.y);
        grad = DVec2::new(vs, vt);
        let len2 = grad.length_squared();
        if len2.is_nan() || len2 <= 0.0 || v == 0.0 {
            break;
        }
        let next = (x - grad * (v / len2)).clamp(DVec2::ZERO, DVec2::ONE);
        let step = (next - x).length();
        x = next;
        if step < PROJECTION_CONVERGED {
            break;
        }
    }
    (x, grad)
}

/// The Bernstein basis at the grid's nodes `k / GRID`.
fn grid_basis() -> &'static [[f64; N]; GRID + 1] {
    static TABLE: std::sync::OnceLock<[[f64; N]; GRID + 1]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|k| basis(k as f64 / GRID as f64).0))
}

/// The crossings of `g = 0` on the grid lines, each grid edge solved once on the 1-D polynomial
/// of its line: `along_s[a][b]` on the edge from node `(a, b)` to `(a + 1, b)`, `along_t[a][b]`
/// on the edge from `(a, b)` to `(a, b + 1)` (`None` where the signs at its ends agree).
type EdgeRoots = (
    [[Option<DVec2>; GRID + 1]; GRID],
    [[Option<DVec2>; GRID]; GRID + 1],
);

/// The nets of `g` on the grid's lines: `along_s[k]` on `t = k / GRID` (a polynomial in `s`),
/// `along_t[k]` on `s = k / GRID`.
type GridLines = ([[f64; N]; GRID + 1], [[f64; N]; GRID + 1]);

/// The [`GridLines`] of the net `g` (sum-factorised on the tabled basis).
fn grid_lines(g: &[[f64; N]; N]) -> GridLines {
    let table = grid_basis();
    let along_s = std::array::from_fn(|k| {
        std::array::from_fn(|i| (0..N).map(|j| g[i][j] * table[k][j]).sum())
    });
    let along_t = std::array::from_fn(|k| {
        std::array::from_fn(|j| (0..N).map(|i| g[i][j] * table[k][i]).sum())
    });
    (along_s, along_t)
}

/// The [`EdgeRoots`] of the grid lines `lines`, whose values at the grid nodes are `vals`.
fn edge_roots(lines: &GridLines, vals: &[[f64; GRID + 1]; GRID + 1]) -> EdgeRoots {
    let h = 1.0 / GRID as f64;
    let neg = |v: f64| v < 0.0;
    let mut along_s = [[None; GRID + 1]; GRID];
    let mut along_t = [[None; GRID]; GRID + 1];
    for k in 0..=GRID {
        let (line_s, line_t) = (&lines.0[k], &lines.1[k]);
        for e in 0..GRID {
            let x0 = e as f64 * h;
            let (ga, gb) = (vals[e][k], vals[e + 1][k]);
            if neg(ga) != neg(gb) {
                let l = bracketed(|l| eval1(line_s, x0 + h * l), 0.0, 1.0, ga, gb);
                along_s[e][k] = Some(DVec2::new(x0 + h * l, k as f64 * h));
            }
            let (ga, gb) = (vals[k][e], vals[k][e + 1]);
            if neg(ga) != neg(gb) {
                let l = bracketed(|l| eval1(line_t, x0 + h * l), 0.0, 1.0, ga, gb);
                along_t[k][e] = Some(DVec2::new(k as f64 * h, x0 + h * l));
            }
        }
    }
    (along_s, along_t)
}

/// Add the pieces of the section of `cell` by `{p : m·p = c}` to `out`, oriented along `m × n`
/// (`n` outward), each chord within `tolerance` of the surface.
pub(crate) fn cell_section(
    cell: &Cell,
    m: DVec3,
    c: f64,
    tolerance: f64,
    out: &mut Vec<SectionArc>,
) {
    let g = cell.scalar_net(m, c);
    for (x0, x1) in grid_pieces(&g) {
        let (p0, p1) = (cell.point(x0.x, x0.y), cell.point(x1.x, x1.y));
        refine(cell, &g, (x0, p0), (x1, p1), tolerance, 0, out);
    }
}

/// The pieces of the curve `g = 0` of a cell's scalar net, as pairs of parameter points where
/// it crosses the edges of a [`GRID`] × [`GRID`] grid (marching squares; each grid edge's
/// crossing solved once on its line's polynomial, a saddle square joined by the sign at its
/// centre); none when the net's bounds keep `g` off zero.
pub(crate) fn grid_pieces(g: &[[f64; N]; N]) -> Vec<(DVec2, DVec2)> {
    let (lo, hi) = bounds(g);
    if lo > 0.0 || hi < 0.0 {
        return Vec::new();
    }
    let h = 1.0 / GRID as f64;
    let lines = grid_lines(g);
    let table = grid_basis();
    // g at node (a, b): the line t = b·h at s = a·h.
    let vals: [[f64; GRID + 1]; GRID + 1] = std::array::from_fn(|a| {
        std::array::from_fn(|b| (0..N).map(|i| lines.0[b][i] * table[a][i]).sum())
    });
    let neg = |v: f64| v < 0.0;
    let (along_s, along_t) = edge_roots(&lines, &vals);
    let mut pieces = Vec::new();
    for a in 0..GRID {
        for b in 0..GRID {
            let corner = vals[a][b];
            // The square's edges counter-clockwise from (a, b): bottom, right, top, left.
            let hits: Vec<DVec2> = [
                along_s[a][b],
                along_t[a + 1][b],
                along_s[a][b + 1],
                along_t[a][b],
            ]
            .into_iter()
            .flatten()
            .collect();
            match hits.len() {
                2 => pieces.push((hits[0], hits[1])),
                4 => {
                    // A saddle: join by the sign at the centre.
                    let centre = DVec2::new((a as f64 + 0.5) * h, (b as f64 + 0.5) * h);
                    let gc = scalar(g, centre.x, centre.y).0;
                    if neg(gc) == neg(corner) {
                        pieces.push((hits[0], hits[1]));
                        pieces.push((hits[2], hits[3]));
                    } else {
                        pieces.push((hits[0], hits[3]));
                        pieces.push((hits[1], hits[2]));
                    }
                }
                _ => {}
            }
        }
    }
    pieces
}

/// Emit the piece from `x0` to `x1` (parameters on the curve, surface points `p0`, `p1`), halved
/// while its chord is further than `tolerance` from the curve's point between.
fn refine(
    cell: &Cell,
    g: &[[f64; N]; N],
    (x0, p0): (DVec2, DVec3),
    (x1, p1): (DVec2, DVec3),
    tolerance: f64,
    depth: usize,
    out: &mut Vec<SectionArc>,
) {
    let (xm, grad) = project(g, 0.5 * (x0 + x1));
    let pm = cell.point(xm.x, xm.y);
    let off = (pm - 0.5 * (p0 + p1)).length();
    if off > tolerance && depth < MAX_REFINE_DEPTH {
        refine(cell, g, (x0, p0), (xm, pm), tolerance, depth + 1, out);
        refine(cell, g, (xm, pm), (x1, p1), tolerance, depth + 1, out);
        return;
    }
    // Along m × n: with n = ±P_s × P_t, m × n = ±(P_s g_t − P_t g_s), the image of the
    // parameter direction ±(g_t, −g_s) — so the piece's direction in the parameters tells.
    let along = (x1 - x0).dot(DVec2::new(grad.y, -grad.x)) * cell.sign;
    if along >= 0.0 {
        out.push([p0, pm, p1]);
    } else {
        out.push([p1, pm, p0]);
    }
}
