//! The wet part of a cell: integrals over `{ζ(s, t) ≤ 0}` of a cell's polynomial, by Saye's
//! high-order quadrature on implicitly defined domains (R. Saye, SIAM J. Sci. Comput. 37(2),
//! 2015, §3, in two dimensions): where `ζ` is monotone in one parameter (its derivative net has
//! one sign), the wet part is, over each interval of the other parameter between the crossings
//! of the box's edges, a region under a graph; a Gauss rule along the interval and one along
//! each column up to the graph (its root) integrate it to the rule's order. Elsewhere the box is
//! halved until `ζ` is monotone.

use glam::DVec3;

use super::bernstein::{basis, bounds, eval1, gauss, gauss_rule, split1, GAUSS, N};
use super::cells::{Cell, CellMoments};
use super::integrals::WetIntegrals;
use super::roots::{bracketed, sign_changes};
use super::waterplane::Waterplane;

/// Halvings of a box before giving up on monotony (the box is then `2⁻¹²` of the cell: its
/// tensor rule with the wet indicator errs by far less than rounding of the whole).
const MAX_DEPTH: usize = 12;

/// Gauss–Legendre points along the outer parameter of a graph (the integrand there, through
/// the graph's root, is smooth but not a polynomial; along the height see [`INNER_GAUSS`]).
/// Seven points give the Wigley hull's and the frigate's wet integrals within 2e-14 relative of
/// ten points' (three: 6e-9), at 30 % less work per cut cell.
const OUTER_GAUSS: usize = 7;

/// The [`OUTER_GAUSS`]-point rule on `[0, 1]`.
fn outer_gauss() -> &'static ([f64; OUTER_GAUSS], [f64; OUTER_GAUSS]) {
    static RULE: std::sync::OnceLock<([f64; OUTER_GAUSS], [f64; OUTER_GAUSS])> =
        std::sync::OnceLock::new();
    RULE.get_or_init(gauss_rule::<OUTER_GAUSS>)
}

/// Gauss–Legendre points along the height parameter of a graph, from the box's edge up to the
/// graph (the whole-box rules keep [`GAUSS`]). Ten points integrate degree 19 exactly; the
/// integrands are of degree up to 27 along a cell's parameter, but a cell's polynomial is a
/// smooth surface's, whose high-degree part is small: on the Wigley hull, the frigate, KCS and
/// KVLCC2 at their drafts the polynomial integrals agree with [`GAUSS`] points' to 3e-12
/// relative (most to 1e-15), the wetted area (not a polynomial) to 2e-8, for 30 % less work
/// per cut cell.
const INNER_GAUSS: usize = 10;

/// The [`INNER_GAUSS`]-point rule on `[0, 1]`.
fn inner_gauss() -> &'static ([f64; INNER_GAUSS], [f64; INNER_GAUSS]) {
    static RULE: std::sync::OnceLock<([f64; INNER_GAUSS], [f64; INNER_GAUSS])> =
        std::sync::OnceLock::new();
    RULE.get_or_init(gauss_rule::<INNER_GAUSS>)
}

/// Halvings below which a box's quarters are integrated in parallel (the first two levels).
const PARALLEL_DEPTH: usize = 2;

/// How a cell lies relative to the water.
pub(crate) enum CellWetness {
    /// Entirely above.
    Dry,
    /// Entirely below: its whole-cell moments apply.
    Wet,
    /// Cut by the water surface: the integrals of its wet part.
    Cut(WetIntegrals),
}

/// Split a scalar net at `½` along `s` (first index).
fn split_s(z: &[[f64; N]; N]) -> ([[f64; N]; N], [[f64; N]; N]) {
    let mut l = [[0.0; N]; N];
    let mut r = [[0.0; N]; N];
    for j in 0..N {
        let col: [f64; N] = std::array::from_fn(|i| z[i][j]);
        let (a, b) = split1(&col, 0.5);
        for i in 0..N {
            l[i][j] = a[i];
            r[i][j] = b[i];
        }
    }
    (l, r)
}

/// Split a scalar net at `½` along `t` (second index).
fn split_t(z: &[[f64; N]; N]) -> ([[f64; N]; N], [[f64; N]; N]) {
    let mut l = [[0.0; N]; N];
    let mut r = [[0.0; N]; N];
    for i in 0..N {
        let (a, b) = split1(&z[i], 0.5);
        l[i] = a;
        r[i] = b;
    }
    (l, r)
}

/// The sign of the net's derivative along `t` (`Some(true)` increasing) if it has one.
fn monotone_t(z: &[[f64; N]; N]) -> Option<(bool, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for row in z {
        for j in 0..N - 1 {
            let d = row[j + 1] - row[j];
            lo = lo.min(d);
            hi = hi.max(d);
        }
    }
    if lo > 0.0 {
        Some((true, lo / hi))
    } else if hi < 0.0 {
        Some((false, hi / lo))
    } else {
        None
    }
}

fn transpose(z: &[[f64; N]; N]) -> [[f64; N]; N] {
    std::array::from_fn(|i| std::array::from_fn(|j| z[j][i]))
}

/// Where and how the cell meets the water surface of `plane`. A cell within `slack` of the
/// water on its dry (wet) side counts as dry (wet): a waterplane along a network curve leaves
/// the cells on either side of it whole, not cut by rounding.
pub(crate) fn wetness(cell: &Cell, plane: &Waterplane, slack: f64) -> CellWetness {
    let z = cell.scalar_net(plane.e3, plane.e3.dot(plane.origin));
    let (lo, hi) = bounds(&z);
    if lo >= -slack {
        return CellWetness::Dry;
    }
    if hi <= slack {
        return CellWetness::Wet;
    }
    // The quadrature reads the cell in the plane's earth frame: the net's image is the
    // surface's (a Bernstein net is affine invariant), and normals turn with the frame — a
    // rotation, or for a half hull's mirrored plane a reflection, which turns them round too.
    let handedness = plane.e1.cross(plane.e2).dot(plane.e3).signum();
    let earth = Cell {
        net: cell.net.map(|row| row.map(|p| plane.earth(p))),
        sign: cell.sign * handedness,
        moments: CellMoments::default(),
    };
    let mut out = WetIntegrals::default();
    clip(&earth, &z, [0.0, 1.0, 0.0, 1.0], 0, &mut out);
    CellWetness::Cut(out)
}

/// Add the integrals over the wet part of box `bx = [s0, s1, t0, t1]` of `cell` (in earth
/// coordinates), whose `ζ` net over the box is `z`.
fn clip(cell: &Cell, z: &[[f64; N]; N], bx: [f64; 4], depth: usize, out: &mut WetIntegrals) {
    let (lo, hi) = bounds(z);
    if lo >= 0.0 {
        return;
    }
    if hi <= 0.0 {
        full_box(cell, bx, out);
        return;
    }
    let along_t = monotone_t(z);
    let along_s = monotone_t(&transpose(z));
    let pick_t = match (along_t, along_s) {
        (Some((_, qt)), Some((_, qs))) => Some(qt >= qs),
        (Some(_), None) => Some(true),
        (None, Some(_)) => Some(false),
        (None, None) => None,
    };
    match pick_t {
        Some(true) => graph(cell, z, bx, false, out),
        Some(false) => graph(cell, &transpose(z), bx, true, out),
        None if depth < MAX_DEPTH => {
            let [s0, s1, t0, t1] = bx;
            let (sm, tm) = (0.5 * (s0 + s1), 0.5 * (t0 + t1));
            let (l, r) = split_s(z);
            let (ll, lr) = split_t(&l);
            let (rl, rr) = split_t(&r);
            let quarters = [
                (ll, [s0, sm, t0, tm]),
                (lr, [s0, sm, tm, t1]),
                (rl, [sm, s1, t0, tm]),
                (rr, [sm, s1, tm, t1]),
            ];
            let part = |q: &[([[f64; N]; N], [f64; 4])]| {
                let mut w = WetIntegrals::default();
                for (z, bx) in q {
                    clip(cell, z, *bx, depth + 1, &mut w);
                }
                w
            };
            if depth < PARALLEL_DEPTH {
                // A cell that needs halving may need thousands of boxes (a waterline wavering
                // about the water): its first quarters go to other threads.
                let (a, b) = rayon::join(|| part(&quarters[..2]), || part(&quarters[2..]));
                *out += a + b;
            } else {
                *out += part(&quarters);
            }
        }
        None => indicator_box(cell, bx, out),
    }
}

/// Add one quadrature point of `cell` (in earth coordinates): `p` and its derivatives `ps`,
/// `pt`, with weight `w`.
#[inline]
fn add(cell: &Cell, p: DVec3, ps: DVec3, pt: DVec3, w: f64, out: &mut WetIntegrals) {
    let n = ps.cross(pt) * (cell.sign * w);
    out.add_point(p, n.z, n.length());
}

/// A box wholly under water: the tensor Gauss rule.
fn full_box(cell: &Cell, bx: [f64; 4], out: &mut WetIntegrals) {
    tensor_box(cell, bx, false, out);
}

/// The last resort for a box where `ζ` is monotone in neither parameter after
/// [`MAX_DEPTH`] halvings: the tensor rule counting the points under water.
fn indicator_box(cell: &Cell, bx: [f64; 4], out: &mut WetIntegrals) {
    tensor_box(cell, bx, true, out);
}

/// The tensor Gauss rule over box `bx`, with `only_wet` counting only the points under water.
fn tensor_box(cell: &Cell, bx: [f64; 4], only_wet: bool, out: &mut WetIntegrals) {
    let (x, w) = gauss();
    let [s0, s1, t0, t1] = bx;
    let area = (s1 - s0) * (t1 - t0);
    for a in 0..GAUSS {
        let s = s0 + (s1 - s0) * x[a];
        let (c, cs) = cell.column(s);
        for b in 0..GAUSS {
            let t = t0 + (t1 - t0) * x[b];
            let (p, ps, pt) = along_column(&c, &cs, t);
            if !only_wet || p.z <= 0.0 {
                add(cell, p, ps, pt, w[a] * w[b] * area, out);
            }
        }
    }
}

/// `P`, `P_s`, `P_t` at `t` from the column nets of [`Cell::column`].
#[inline]
fn along_column(c: &[DVec3; N], cs: &[DVec3; N], t: f64) -> (DVec3, DVec3, DVec3) {
    let (b, d) = basis(t);
    let mut p = DVec3::ZERO;
    let mut ps = DVec3::ZERO;
    let mut pt = DVec3::ZERO;
    for j in 0..N {
        p += c[j] * b[j];
        pt += c[j] * d[j];
        ps += cs[j] * b[j];
    }
    (p, ps, pt)
}

/// `P`, `P_s`, `P_t` at `s` from the row nets of `Cell::row` (the roles of the parameters
/// exchanged).
#[inline]
fn along_row(r: &[DVec3; N], rt: &[DVec3; N], s: f64) -> (DVec3, DVec3, DVec3) {
    let (b, d) = basis(s);
    let mut p = DVec3::ZERO;
    let mut ps = DVec3::ZERO;
    let mut pt = DVec3::ZERO;
    for i in 0..N {
        p += r[i] * b[i];
        ps += r[i] * d[i];
        pt += rt[i] * b[i];
    }
    (p, ps, pt)
}

/// The wet part of a box where `ζ` is monotone along the height parameter: `z[u][h]` is the
/// net with `u` the outer parameter and `h` the height one (`swapped`: `u = t`, `h = s`).
fn graph(cell: &Cell, z: &[[f64; N]; N], bx: [f64; 4], swapped: bool, out: &mut WetIntegrals) {
    let [s0, s1, t0, t1] = bx;
    let (u0, u1, h0, h1) = if swapped {
        (t0, t1, s0, s1)
    } else {
        (s0, s1, t0, t1)
    };
    // Break the outer interval where the graph meets the box's bottom or top edge.
    let bottom: [f64; N] = std::array::from_fn(|i| z[i][0]);
    let top: [f64; N] = std::array::from_fn(|i| z[i][N - 1]);
    let mut cuts = vec![0.0];
    sign_changes(&bottom, &mut cuts);
    sign_changes(&top, &mut cuts);
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    let (x, w) = inner_gauss();
    let (xo, wo) = outer_gauss();
    for win in cuts.windows(2) {
        let (a, b) = (win[0], win[1]);
        if b - a <= 0.0 {
            continue;
        }
        for q in 0..OUTER_GAUSS {
            let lu = a + (b - a) * xo[q];
            let (bu, _) = basis(lu);
            let col: [f64; N] = std::array::from_fn(|j| (0..N).map(|i| z[i][j] * bu[i]).sum());
            let (lo_h, hi_h) = match (col[0] <= 0.0, col[N - 1] <= 0.0) {
                (true, true) => (0.0, 1.0),
                (false, false) => continue,
                (below_at_0, _) => {
                    let f = |h: f64| eval1(&col, h);
                    let r = bracketed(f, 0.0, 1.0, col[0], col[N - 1]);
                    if below_at_0 {
                        (0.0, r)
                    } else {
                        (r, 1.0)
                    }
                }
            };
            if hi_h <= lo_h {
                continue;
            }
            let u = u0 + (u1 - u0) * lu;
            let wu = wo[q] * (b - a) * (u1 - u0);
            let (c, cd) = if swapped { cell.row(u) } else { cell.column(u) };
            for r in 0..INNER_GAUSS {
                let lh = lo_h + (hi_h - lo_h) * x[r];
                let h = h0 + (h1 - h0) * lh;
                let wh = w[r] * (hi_h - lo_h) * (h1 - h0);
                let (p, ps, pt) = if swapped {
                    along_row(&c, &cd, h)
                } else {
                    along_column(&c, &cd, h)
                };
                add(cell, p, ps, pt, wu * wh, out);
            }
        }
    }
}
