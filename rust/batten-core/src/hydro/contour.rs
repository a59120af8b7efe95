//! Plane sections of a cell: the curve `g(s, t) = m·P(s, t) − c = 0` of its polynomial, found on
//! a grid by marching squares (each crossing of a grid edge solved on the polynomial), then
//! refined — every piece (an arc: its ends and the curve's point between) halved in parameter space and its middle projected onto the curve by
//! Newton steps along `∇g` — until each chord is within the tolerance of the surface.

use glam::{DVec2, DVec3};

use super::bernstein::{basis, bounds, N};
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

/// Move `x` onto `g = 0` by Newton steps along the gradient, staying in the cell.
fn project(g: &[[f64; N]; N], mut x: DVec2) -> DVec2 {
    for _ in 0..PROJECTION_STEPS {
        let (v, vs, vt) = scalar(g, x.x, x.y);
        let grad = DVec2::new(vs, vt);
        let len2 = grad.length_squared();
        if len2.is_nan() || len2 <= 0.0 || v == 0.0 {
            break;
        }
        x = (x - grad * (v / len2)).clamp(DVec2::ZERO, DVec2::ONE);
    }
    x
}

/// The crossing of `g = 0` on the grid edge from `a` to `b` (parameters), where the signs of
/// `ga` and `gb` differ.
fn edge_root(g: &[[f64; N]; N], a: DVec2, b: DVec2, ga: f64, gb: f64) -> DVec2 {
    let f = |l: f64| {
        let x = a + (b - a) * l;
        scalar(g, x.x, x.y).0
    };
    a + (b - a) * bracketed(f, 0.0, 1.0, ga, gb)
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
        let (p0, p1) = (cell.eval(x0.x, x0.y).0, cell.eval(x1.x, x1.y).0);
        refine(cell, &g, m, (x0, p0), (x1, p1), tolerance, 0, out);
    }
}

/// The pieces of the curve `g = 0` of a cell's scalar net, as pairs of parameter points where
/// it crosses the edges of a [`GRID`] × [`GRID`] grid (marching squares; each crossing solved
/// on the polynomial, a saddle square joined by the sign at its centre); none when the net's
/// bounds keep `g` off zero.
pub(crate) fn grid_pieces(g: &[[f64; N]; N]) -> Vec<(DVec2, DVec2)> {
    let (lo, hi) = bounds(g);
    if lo > 0.0 || hi < 0.0 {
        return Vec::new();
    }
    let h = 1.0 / GRID as f64;
    let mut vals = [[0.0f64; GRID + 1]; GRID + 1];
    for (a, row) in vals.iter_mut().enumerate() {
        for (b, v) in row.iter_mut().enumerate() {
            *v = scalar(g, a as f64 * h, b as f64 * h).0;
        }
    }
    let neg = |v: f64| v < 0.0;
    let mut pieces = Vec::new();
    for a in 0..GRID {
        for b in 0..GRID {
            let corners = [
                (DVec2::new(a as f64 * h, b as f64 * h), vals[a][b]),
                (DVec2::new((a + 1) as f64 * h, b as f64 * h), vals[a + 1][b]),
                (
                    DVec2::new((a + 1) as f64 * h, (b + 1) as f64 * h),
                    vals[a + 1][b + 1],
                ),
                (DVec2::new(a as f64 * h, (b + 1) as f64 * h), vals[a][b + 1]),
            ];
            let mut hits: Vec<(usize, DVec2)> = Vec::with_capacity(4);
            for e in 0..4 {
                let (pa, ga) = corners[e];
                let (pb, gb) = corners[(e + 1) % 4];
                if neg(ga) != neg(gb) {
                    hits.push((e, edge_root(g, pa, pb, ga, gb)));
                }
            }
            match hits.len() {
                2 => pieces.push((hits[0].1, hits[1].1)),
                4 => {
                    // A saddle: join by the sign at the centre.
                    let centre = DVec2::new((a as f64 + 0.5) * h, (b as f64 + 0.5) * h);
                    let gc = scalar(g, centre.x, centre.y).0;
                    if neg(gc) == neg(corners[0].1) {
                        pieces.push((hits[0].1, hits[1].1));
                        pieces.push((hits[2].1, hits[3].1));
                    } else {
                        pieces.push((hits[0].1, hits[3].1));
                        pieces.push((hits[1].1, hits[2].1));
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
#[allow(clippy::too_many_arguments)]
fn refine(
    cell: &Cell,
    g: &[[f64; N]; N],
    m: DVec3,
    (x0, p0): (DVec2, DVec3),
    (x1, p1): (DVec2, DVec3),
    tolerance: f64,
    depth: usize,
    out: &mut Vec<SectionArc>,
) {
    let xm = project(g, 0.5 * (x0 + x1));
    let (pm, ps, pt) = cell.eval(xm.x, xm.y);
    let off = (pm - 0.5 * (p0 + p1)).length();
    if off > tolerance && depth < MAX_REFINE_DEPTH {
        refine(cell, g, m, (x0, p0), (xm, pm), tolerance, depth + 1, out);
        refine(cell, g, m, (xm, pm), (x1, p1), tolerance, depth + 1, out);
        return;
    }
    let n = ps.cross(pt) * cell.sign;
    if (p1 - p0).dot(m.cross(n)) >= 0.0 {
        out.push([p0, pm, p1]);
    } else {
        out.push([p1, pm, p0]);
    }
}
