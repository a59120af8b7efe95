//! Narrow phase of the node search: recursive de Casteljau halving of a candidate pair of
//! pieces until their tangent cones are separated, then Newton's method from the closest points
//! of their chords.

use super::super::approach::{closest_approach, Approach};
use super::{sine_between, Hit, PairHits, Prepared};
use crate::curve::{Aabb, BezierPiece, TangentCone};

/// A segment pair is a leaf (handed to Newton) once their tangent cones are separated by more
/// than this angle (radians, 5°): two pieces whose tangents can never be parallel approach each
/// other at most once. Pieces that could be parallel somewhere are subdivided further.
const CONE_MARGIN: f64 = 0.087;
/// Segments smaller than this fraction of their curve's size are leaves whatever their shape.
const LEAF_SIZE_FRACTION: f64 = 1e-2;
/// A segment whose box is within this many units of rounding of its coordinates is a leaf:
/// halving cannot shrink it (at 1e17 m, where f64 resolves 16 m, boxes never got small and every
/// pair of pieces halved to `MAX_DEPTH`). 64 ulps: a de Casteljau halving rounds each point by
/// a few ulps per level.
const ROUNDING_ULPS: f64 = 64.0;
/// Subdivision depth limit per candidate pair (a guard for overlapping curves).
const MAX_DEPTH: u32 = 48;
/// Leaves examined per curve pair at most (a guard for long overlaps).
const MAX_LEAVES: usize = 512;

/// A piece's control-point box and tangent cone (each piece meets many others in the narrow
/// phase; these are worked out once).
#[derive(Clone, Copy, Debug)]
pub(super) struct PieceBounds {
    /// The box of the control points.
    pub(super) hull: Aabb,
    /// The cone of tangent directions (`None` for a zero chord).
    pub(super) cone: Option<TangentCone>,
}

impl PieceBounds {
    /// The bounds of `piece`.
    pub(super) fn of(piece: &BezierPiece) -> PieceBounds {
        PieceBounds {
            hull: piece.hull_box(),
            cone: piece.tangent_cone(),
        }
    }
}

/// The size below which halving a box at its coordinates is rounding, not refinement.
fn rounding(b: &Aabb) -> f64 {
    ROUNDING_ULPS * f64::EPSILON * b.min.abs().max(b.max.abs()).max_element()
}

/// The narrow phase of one pair of curves: halves candidate piece pairs until they are
/// leaves, and runs Newton on each leaf.
pub(super) struct Narrow<'a, 'h> {
    pub(super) a: &'a Prepared<'a>,
    pub(super) b: &'a Prepared<'a>,
    pub(super) ca: usize,
    pub(super) cb: usize,
    pub(super) near: f64,
    pub(super) accuracy: f64,
    pub(super) leaves: usize,
    pub(super) hits: &'h mut PairHits,
}

impl Narrow<'_, '_> {
    /// Halve the pair until it is a leaf; `kx`, `ky` are the pieces' box and cone when known.
    pub(super) fn recurse(
        &mut self,
        x: &BezierPiece,
        y: &BezierPiece,
        kx: Option<PieceBounds>,
        ky: Option<PieceBounds>,
        depth: u32,
    ) {
        let (bx, by) = (
            kx.map_or_else(|| x.hull_box(), |k| k.hull),
            ky.map_or_else(|| y.hull_box(), |k| k.hull),
        );
        if bx.gap_to(&by) > self.near || self.leaves >= MAX_LEAVES {
            return;
        }
        let (dx, dy) = (bx.diagonal(), by.diagonal());
        let small_x = dx
            <= (LEAF_SIZE_FRACTION * self.a.size)
                .max(self.near)
                .max(rounding(&bx));
        let small_y = dy
            <= (LEAF_SIZE_FRACTION * self.b.size)
                .max(self.near)
                .max(rounding(&by));
        let leaf = (small_x && small_y)
            || depth >= MAX_DEPTH
            || match (
                kx.map_or_else(|| x.tangent_cone(), |k| k.cone),
                ky.map_or_else(|| y.tangent_cone(), |k| k.cone),
            ) {
                (Some(cx), Some(cy)) => {
                    let between = cx.axis.dot(cy.axis).abs().min(1.0).acos();
                    between > cx.half_angle + cy.half_angle + CONE_MARGIN
                }
                _ => false,
            };
        if leaf {
            self.leaf(x, y);
            return;
        }
        if dx >= dy {
            let (l, r) = x.halves();
            self.recurse(&l, y, None, ky, depth + 1);
            self.recurse(&r, y, None, ky, depth + 1);
        } else {
            let (l, r) = y.halves();
            self.recurse(x, &l, kx, None, depth + 1);
            self.recurse(x, &r, kx, None, depth + 1);
        }
    }

    fn leaf(&mut self, x: &BezierPiece, y: &BezierPiece) {
        self.leaves += 1;
        // A join already found inside this pair of pieces is not looked for again.
        if self
            .hits
            .iter()
            .any(|h| h.s >= x.t0 && h.s <= x.t1 && h.t >= y.t0 && h.t <= y.t1)
        {
            return;
        }
        let start = chord_start(x, y);
        let same = self.ca == self.cb;
        // A curve against itself stays inside the two pieces (else it slides to s = t).
        let (sr, tr) = if same {
            ((x.t0, x.t1), (y.t0, y.t1))
        } else {
            (self.a.curve.domain(), self.b.curve.domain())
        };
        let Approach {
            s,
            t,
            gap,
            pa,
            pb,
            ta,
            tb,
        } = closest_approach(
            &self.a.decomposition,
            &self.b.decomposition,
            start,
            sr,
            tr,
            self.accuracy,
        );
        if gap <= self.near {
            self.hits.push(Hit {
                a: self.ca,
                b: self.cb,
                s,
                t,
                gap,
                pa,
                pb,
                sine: sine_between(ta, tb),
            });
        }
    }
}

/// A Newton start for a leaf pair: the closest points of the two chords, mapped linearly to
/// the pieces' parameters (the pieces are nearly straight, so this is close already).
fn chord_start(x: &BezierPiece, y: &BezierPiece) -> (f64, f64) {
    let chord = |piece: &BezierPiece| {
        let (a, b) = piece.ends();
        (a, b - a)
    };
    let (p, u) = chord(x);
    let (q, v) = chord(y);
    let w = p - q;
    let (a, b, c) = (u.dot(u), u.dot(v), v.dot(v));
    let (d, e) = (u.dot(w), v.dot(w));
    let den = a * c - b * b;
    let (fs, ft) = if den > 1e-12 * a * c && den > 0.0 {
        ((b * e - c * d) / den, (a * e - b * d) / den)
    } else {
        (0.5, 0.5)
    };
    let (fs, ft) = (fs.clamp(0.0, 1.0), ft.clamp(0.0, 1.0));
    (x.t0 + fs * (x.t1 - x.t0), y.t0 + ft * (y.t1 - y.t0))
}
