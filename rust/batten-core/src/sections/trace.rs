//! The pieces of a plane section on each patch: the patch's domain cut into the cells of the
//! hydrostatics ([`crate::hydro`]: Bernstein interpolants of degree 7 at Chebyshev–Lobatto
//! nodes), the curve `m·P − c = 0` found on each cell's polynomial by marching squares, then
//! every point moved onto the patch itself by Newton steps in its domain (the minimum-norm step
//! along the domain gradient of `m·P(x) − c`), and each piece halved in the domain, its middle
//! polished the same way, until every chord is within the tolerance of the surface.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::curve::segment_distance;
use crate::hydro::{boxes, grid_pieces, interpolate, quads, CellDensity, Quad, GRID, NET_SIZE};
use crate::patch::{Domain, Patch};

/// Newton steps at most when moving a point onto patch ∩ plane (it converges from the cell
/// polynomial's root to the patch's rounding in two or three).
const POLISH_STEPS: usize = 8;

/// A curve crossing a patch's side at a smaller angle than this (its sine) is taken to run
/// along it (a plane holding a drawn curve): about 3°.
const ALONG_SIDE_SINE: f64 = 0.05;

/// A hit on a cell's grid line stays on that line when getting onto the curve along it moves
/// it at most this many times as far as the shortest way does (a crossing at 15° or steeper).
const LINE_SLIDE_FACTOR: f64 = 4.0;

/// Halvings of a piece at most (the piece is then `2⁻¹⁶` of a cell's grid square).
const MAX_REFINE_DEPTH: usize = 16;

/// One cell of a patch's domain: where it is (patch, quadrilateral, parameter box), the
/// Bernstein net of the surface over it and the net's box (which holds the polynomial).
pub(crate) struct DomainCell {
    patch: usize,
    quad: Quad,
    bx: [f64; 4],
    net: [[DVec3; NET_SIZE]; NET_SIZE],
    lo: DVec3,
    hi: DVec3,
}

impl DomainCell {
    /// The patch-domain point at cell parameters `x = (s, t)`.
    fn domain_point(&self, x: DVec2) -> DVec2 {
        let [s0, s1, t0, t1] = self.bx;
        self.quad.at(s0 + (s1 - s0) * x.x, t0 + (t1 - t0) * x.y)
    }

    /// Whether the net's box reaches the plane `m·p = c`.
    fn reaches(&self, m: DVec3, c: f64) -> bool {
        let lo = DVec3::select(m.cmpge(DVec3::ZERO), self.lo, self.hi);
        let hi = self.lo + self.hi - lo;
        m.dot(lo) <= c && m.dot(hi) >= c
    }
}

/// The cells of every patch at `density` (in parallel).
pub(crate) fn domain_cells(patches: &[Patch], density: CellDensity) -> Vec<DomainCell> {
    patches
        .par_iter()
        .enumerate()
        .flat_map_iter(|(patch, p)| {
            let mut out = Vec::new();
            for quad in quads(p.domain()) {
                for bx in boxes(&quad, density.per_quad.max(1), density.corner_levels) {
                    let net = interpolate(p, &quad, bx);
                    let mut lo = DVec3::splat(f64::INFINITY);
                    let mut hi = DVec3::splat(f64::NEG_INFINITY);
                    for q in net.iter().flatten() {
                        lo = lo.min(*q);
                        hi = hi.max(*q);
                    }
                    out.push(DomainCell {
                        patch,
                        quad,
                        bx,
                        net,
                        lo,
                        hi,
                    });
                }
            }
            out
        })
        .collect()
}

/// One piece of a section on one patch: its points in order along `m × n` (`n` outward),
/// each on the patch and the plane, and the domain points of its ends.
#[derive(Clone, Debug)]
pub(crate) struct Piece {
    /// Index of the patch.
    pub(crate) patch: usize,
    /// The points, first to last.
    pub(crate) points: Vec<DVec3>,
    /// Domain point of the first point.
    pub(crate) start: DVec2,
    /// Domain point of the last point.
    pub(crate) end: DVec2,
}

/// The plane a section is traced on and what it asks of the points.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cut {
    /// Unit normal `m`.
    pub(crate) m: DVec3,
    /// The plane's offset `c` (`m·p = c`): where the points are polished to.
    pub(crate) c: f64,
    /// The offset the cells are cut at: `c` moved a little off, so a plane holding a patch
    /// edge cuts the patches on one side of it only.
    pub(crate) c_cells: f64,
    /// Chordal tolerance (m).
    pub(crate) tolerance: f64,
    /// A point is on the plane when `|m·P − c|` is below this (m).
    pub(crate) close: f64,
    /// `+1` when the patches' `P_u × P_v` points out of the hull, else `−1`.
    pub(crate) sign: f64,
}

/// Newton steps on `g(x) = m·P(x) − c` from the domain point `x`, each the next point that
/// `step(x, ∇g, g)` gives (`None`: stop), until `|g|` is within [`Cut::close`]; the best
/// point met and its surface point.
fn newton(
    patch: &Patch,
    cut: &Cut,
    mut x: DVec2,
    step: impl Fn(DVec2, DVec2, f64) -> Option<DVec2>,
) -> (DVec2, DVec3) {
    let mut best = (x, patch.eval_v(x), f64::INFINITY);
    for _ in 0..POLISH_STEPS {
        let (p, pu, pv) = patch.derivatives(x.to_array());
        let g = cut.m.dot(p) - cut.c;
        if g.abs() < best.2 {
            best = (x, p, g.abs());
        }
        if g.abs() <= cut.close {
            break;
        }
        match step(x, DVec2::new(cut.m.dot(pu), cut.m.dot(pv)), g) {
            Some(next) => x = next,
            None => break,
        }
    }
    (best.0, best.1)
}

/// The minimum-norm Newton step from `x` (along `∇g`), kept in the domain: where it would
/// leave it (the curve crosses the patch's side there), along the side nearest `x` instead,
/// to the side's own crossing of the plane.
fn free_step(domain: &Domain, x: DVec2, grad: DVec2, g: f64) -> Option<DVec2> {
    let len2 = grad.length_squared();
    if !(len2 > 0.0 && len2.is_finite()) {
        return None;
    }
    let step = x - grad * (g / len2);
    Some(if domain.contains(step.to_array()) {
        step
    } else {
        domain.clamp(along_side(domain, x, grad, g).unwrap_or(step))
    })
}

/// Move the domain point `x` onto `m·P(x) = c` on `patch` by minimum-norm Newton steps
/// ([`free_step`]).
fn polish(patch: &Patch, cut: &Cut, x: DVec2) -> (DVec2, DVec3) {
    let domain = patch.domain();
    newton(patch, cut, x, |x, grad, g| free_step(domain, x, grad, g))
}

/// Move the domain point `x` onto `m·P(x) = c` along the domain line through it in direction
/// `d` (Newton on the line), so points found on a cell's edge stay on it and the pieces of
/// neighbouring cells (and patches, whose shared side is one curve) meet at one point; where
/// the curve runs along the line (within [`ALONG_SIDE_SINE`]), by minimum-norm steps.
fn polish_on_line(patch: &Patch, cut: &Cut, x: DVec2, d: DVec2) -> (DVec2, DVec3) {
    let domain = patch.domain();
    newton(patch, cut, x, |x, grad, g| {
        let gd = grad.dot(d);
        if gd.abs() > ALONG_SIDE_SINE * grad.length() * d.length() && gd.is_finite() {
            Some(domain.clamp(x - d * (g / gd)))
        } else {
            free_step(domain, x, grad, g)
        }
    })
}

/// A marching-squares hit (cell parameters `h`, on a grid line of the cell: one coordinate a
/// multiple of `1/GRID`) moved onto the patch ∩ plane along that grid line.
fn polish_hit(cell: &DomainCell, patch: &Patch, cut: &Cut, h: DVec2) -> (DVec2, DVec3) {
    let step = 1.0 / GRID as f64;
    let on_grid = |v: f64| (v * GRID as f64).round() * step == v;
    let (a, b) = if on_grid(h.x) {
        (DVec2::new(h.x, 0.0), DVec2::new(h.x, 1.0))
    } else if on_grid(h.y) {
        (DVec2::new(0.0, h.y), DVec2::new(1.0, h.y))
    } else {
        return polish(patch, cut, cell.domain_point(h));
    };
    let x = cell.domain_point(h);
    let d = cell.domain_point(b) - cell.domain_point(a);
    let start = patch.eval_v(x);
    let along = polish_on_line(patch, cut, x, d);
    let free = polish(patch, cut, x);
    // Where the grid line meets the curve at a shallow angle, the cell polynomial's small
    // error becomes a long slide along the line, past the pieces of the neighbouring cells:
    // then the shortest move onto the curve is the point (the pieces' ends then meet within
    // the tolerance, where they are joined).
    if (along.1 - start).length() <= LINE_SLIDE_FACTOR * (free.1 - start).length() + cut.close {
        along
    } else {
        free
    }
}

/// The Newton step from `x` along the domain side nearest it: `x − d·g/(∇g·d)`, `d` the
/// side's direction; `None` when the curve runs along the side (within [`ALONG_SIDE_SINE`]):
/// the clamped step then lands on the side, which is on the curve.
fn along_side(domain: &Domain, x: DVec2, grad: DVec2, g: f64) -> Option<DVec2> {
    let side = (0..domain.sides()).min_by(|&a, &b| {
        domain
            .distance(a, x)
            .abs()
            .total_cmp(&domain.distance(b, x).abs())
    })?;
    let d = (domain.vertex(side + 1) - domain.vertex(side)).normalize();
    let gd = grad.dot(d);
    (gd.abs() > ALONG_SIDE_SINE * grad.length() && gd.is_finite()).then(|| x - d * (g / gd))
}

/// Push the points after `p0` up to `p1` (both on the curve, at domain points `x0`, `x1`):
/// the piece's middle (polished), halving while a chord is further than the tolerance from it.
fn refine(
    patch: &Patch,
    cut: &Cut,
    (x0, p0): (DVec2, DVec3),
    (x1, p1): (DVec2, DVec3),
    depth: usize,
    out: &mut Vec<DVec3>,
) {
    let (xm, pm) = polish(patch, cut, 0.5 * (x0 + x1));
    if (pm - 0.5 * (p0 + p1)).length() > cut.tolerance && depth < MAX_REFINE_DEPTH {
        refine(patch, cut, (x0, p0), (xm, pm), depth + 1, out);
        refine(patch, cut, (xm, pm), (x1, p1), depth + 1, out);
    } else {
        out.push(pm);
        out.push(p1);
    }
}

/// Keep the points the polish brought onto the plane; move those it left within the tolerance
/// of it onto it (where the plane runs along a drawn curve that is not quite plane, the
/// section weaves across the patch's side and the patch holds no exact point); drop the rest
/// (a degenerate patch corner where the cell's polynomial strays from the patch).
fn on_plane(points: &mut Vec<DVec3>, cut: &Cut) {
    points.retain_mut(|p| {
        let r = cut.m.dot(*p) - cut.c;
        if r.abs() > cut.tolerance {
            return false;
        }
        if r.abs() > cut.close {
            *p -= cut.m * r;
        }
        true
    });
}

/// The pieces of the section of one cell, oriented along `m × n`.
fn cell_pieces(cell: &DomainCell, patch: &Patch, cut: &Cut) -> Vec<Piece> {
    let g = cell.net.map(|row| row.map(|p| cut.m.dot(p) - cut.c_cells));
    grid_pieces(&g)
        .into_iter()
        .map(|(a, b)| {
            let (x0, p0) = polish_hit(cell, patch, cut, a);
            let (x1, p1) = polish_hit(cell, patch, cut, b);
            let mut points = vec![p0];
            refine(patch, cut, (x0, p0), (x1, p1), 0, &mut points);
            on_plane(&mut points, cut);
            let mid = 0.5 * (x0 + x1);
            let n = patch.normal(mid.to_array()) * cut.sign;
            let mut piece = Piece {
                patch: cell.patch,
                points,
                start: x0,
                end: x1,
            };
            if (p1 - p0).dot(cut.m.cross(n)) < 0.0 {
                piece.points.reverse();
                std::mem::swap(&mut piece.start, &mut piece.end);
            }
            piece
        })
        .filter(|piece| piece.points.len() >= 2)
        .collect()
}

/// The pieces of the section by `cut` of every cell whose box reaches it (in parallel).
pub(crate) fn section_pieces(cells: &[DomainCell], patches: &[Patch], cut: &Cut) -> Vec<Piece> {
    cells
        .par_iter()
        .filter(|cell| cell.reaches(cut.m, cut.c_cells))
        .flat_map_iter(|cell| cell_pieces(cell, &patches[cell.patch], cut))
        .collect()
}

/// A piece's end this far (in domain units) inside its patch's domain is an inner end: the
/// section of a patch never ends there.
const INNER_END: f64 = 1e-7;

/// A bridge over a gap between inner ends may be at most this many times as long as the gap's
/// chord (else the polish has jumped to another branch of the section).
const BRIDGE_LENGTH_FACTOR: f64 = 2.0;

/// Whether domain point `x` of `piece`'s patch lies inside the domain ([`INNER_END`]).
fn inner_end(patches: &[Patch], piece: &Piece, x: DVec2) -> bool {
    let domain = patches[piece.patch].domain();
    (0..domain.sides()).all(|i| domain.distance(i, x) > INNER_END)
}

/// Whether an end of a piece other than `pieces[i]` lies within `within` of `q`.
fn end_met(pieces: &[Piece], i: usize, q: DVec3, within: f64) -> bool {
    pieces.iter().enumerate().any(|(j, p)| {
        j != i
            && ((p.points[0] - q).length() <= within
                || (p.points[p.points.len() - 1] - q).length() <= within)
    })
}

/// Close the gaps a section can leave inside a patch, where it runs along the shared edge of
/// two cells: each cell's polynomial interpolates the patch only to about 1e-9 of its size, so
/// where the section strays across the edge by less than that, one cell has it leave across the
/// edge and the other never has it enter (the frigate's waterline at 7/8 of its depth ran along
/// a cell edge of a side patch for 0.7 m). A piece's end inside its patch's domain that no
/// other piece meets within `join` is such a gap; it is bridged to the nearest such start on
/// the same patch by the exact section between them (the points polished onto the plane on the
/// patch itself, halved as [`refine`] does), kept only if no longer than
/// [`BRIDGE_LENGTH_FACTOR`] times the gap's chord.
fn bridge_inner_gaps(pieces: &mut Vec<Piece>, patches: &[Patch], cut: &Cut, join: f64) {
    let ends: Vec<(DVec3, DVec3)> = pieces
        .iter()
        .map(|p| (p.points[0], p.points[p.points.len() - 1]))
        .collect();
    // Dangling inner ends (exits) and starts (entries).
    let exits: Vec<usize> = (0..pieces.len())
        .filter(|&i| {
            inner_end(patches, &pieces[i], pieces[i].end) && !end_met(pieces, i, ends[i].1, join)
        })
        .collect();
    let mut entries: Vec<usize> = (0..pieces.len())
        .filter(|&i| {
            inner_end(patches, &pieces[i], pieces[i].start) && !end_met(pieces, i, ends[i].0, join)
        })
        .collect();
    let mut bridges = Vec::new();
    for i in exits {
        let (patch, x0, p0) = (pieces[i].patch, pieces[i].end, ends[i].1);
        let Some((k, &j)) = entries
            .iter()
            .enumerate()
            .filter(|&(_, &j)| j != i && pieces[j].patch == patch)
            .min_by(|a, b| {
                (pieces[*a.1].start - x0)
                    .length()
                    .total_cmp(&(pieces[*b.1].start - x0).length())
            })
        else {
            continue;
        };
        let (x1, p1) = (pieces[j].start, ends[j].0);
        let mut points = vec![p0];
        refine(&patches[patch], cut, (x0, p0), (x1, p1), 0, &mut points);
        on_plane(&mut points, cut);
        let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
        if points.len() >= 2 && length <= BRIDGE_LENGTH_FACTOR * (p1 - p0).length() + join {
            entries.swap_remove(k);
            bridges.push(Piece {
                patch,
                points,
                start: x0,
                end: x1,
            });
        }
    }
    pieces.extend(bridges);
}

/// Mend what a section's pieces lose or double where it runs along the shared edge of two
/// cells: [`bridge_inner_gaps`] (within `join`), then [`drop_covered_fragments`].
pub(crate) fn mend_cell_edges(pieces: &mut Vec<Piece>, patches: &[Patch], cut: &Cut, join: f64) {
    bridge_inner_gaps(pieces, patches, cut, join);
    drop_covered_fragments(pieces, patches, cut.tolerance);
}

/// The other side of [`bridge_inner_gaps`]: where the section strays across a cell edge the
/// other way, both cells have it, and the one that has it only for a stretch leaves a fragment
/// with an inner end that nothing meets, lying on a piece of the other cell. Such a piece (every
/// point within twice the chordal `tolerance` of another piece's chords) is dropped, and so on
/// along the fragment.
fn drop_covered_fragments(pieces: &mut Vec<Piece>, patches: &[Patch], tolerance: f64) {
    let near = 2.0 * tolerance;
    loop {
        let covered = |i: usize| {
            pieces[i].points.iter().all(|&q| {
                pieces.iter().enumerate().any(|(j, p)| {
                    j != i
                        && p.patch == pieces[i].patch
                        && p.points
                            .windows(2)
                            .any(|w| segment_distance(q, w[0], w[1]) <= near)
                })
            })
        };
        let fragment = (0..pieces.len()).find(|&i| {
            let p = &pieces[i];
            let dangling = (inner_end(patches, p, p.start)
                && !end_met(pieces, i, p.points[0], near))
                || (inner_end(patches, p, p.end)
                    && !end_met(pieces, i, p.points[p.points.len() - 1], near));
            dangling && covered(i)
        });
        match fragment {
            Some(i) => {
                pieces.swap_remove(i);
            }
            None => break,
        }
    }
}
