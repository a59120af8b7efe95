//! Nodes of a curve network: every place where designer curves meet within the model tolerance
//! (end to end, an end on another curve's interior — a T-joint — and interior crossings), found
//! by bounding-volume culling, recursive Bézier subdivision and Newton refinement, and clustered
//! so that three or more curves meeting at one point give one node.

use glam::DVec3;

use super::approach::{closest_approach, Approach};
use super::Network;
use crate::curve::{Aabb, BezierDecomposition, BezierPiece, NurbsCurve, TangentCone};
use crate::diagnostic::Diagnostic;
use crate::error::Error;
use crate::tolerance::Tolerance;

/// A segment pair is a leaf (handed to Newton) once their tangent cones are separated by more
/// than this angle (radians, 5°): two pieces whose tangents can never be parallel approach each
/// other at most once. Pieces that could be parallel somewhere are subdivided further.
const CONE_MARGIN: f64 = 0.087;
/// Segments smaller than this fraction of their curve's size are leaves whatever their shape.
const LEAF_SIZE_FRACTION: f64 = 1e-2;
/// Newton stops at this fraction of the tolerance (distance, or step length).
const NEWTON_ACCURACY: f64 = 1e-4;
/// Subdivision depth limit per candidate pair (a guard for overlapping curves).
const MAX_DEPTH: u32 = 48;
/// Leaves examined per curve pair at most (a guard for long overlaps).
const MAX_LEAVES: usize = 512;
/// A stretch where two curves stay within tolerance is an overlap (not a tangential touch)
/// when longer than this many tolerances…
const OVERLAP_MIN_TOLERANCES: f64 = 100.0;
/// …and longer than this fraction of the shorter curve.
const OVERLAP_MIN_FRACTION: f64 = 0.05;

/// A curve passing through a node: which curve (index in the network) and at which parameter
/// (H-rep paper §3.1: the vertices of the edge–vertex topology lie on the designer's curves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incidence {
    /// Index of the curve in [`Network::curves`].
    pub curve: usize,
    /// Parameter on the curve.
    pub t: f64,
}

/// A node: a point where curves meet (or a free curve end), with every curve through it
/// (H-rep paper §3.1 vertex; §5.2 "let the curves start and end on other curves").
#[derive(Clone, Debug, PartialEq)]
pub struct Junction {
    /// Mean of the curve points that were clustered into this node.
    pub position: DVec3,
    /// The curves through the node, at most one per curve and parameter, sorted by curve.
    pub incidences: Vec<Incidence>,
}

/// The nodes of a network (H-rep paper §3.1: the arrangement of the designer's curves mapped
/// to an edge–vertex topology) with what was found on the way.
#[derive(Clone, Debug, PartialEq)]
pub struct Junctions {
    /// Every node, including free curve ends.
    pub nodes: Vec<Junction>,
    /// For each curve of the network, its nodes as `(parameter, node index)` sorted by
    /// parameter, from its start to its end; empty for curves left out.
    pub splits: Vec<Vec<(f64, usize)>>,
    /// Curves left out of the topology (zero length, or a duplicate of another curve).
    pub excluded: Vec<bool>,
    /// Stretches `(curve, t0, t1)` left out because another curve runs along them (an
    /// overlap): the stretch is kept once, on the curve whose name sorts first.
    pub suppressed: Vec<(usize, f64, f64)>,
    /// Near misses, overlaps, duplicates, self-intersections and zero-length curves.
    pub diagnostics: Vec<Diagnostic>,
}

struct Prepared<'a> {
    curve: &'a NurbsCurve,
    /// Parameters and points of the curve's two ends.
    ends: [(f64, DVec3); 2],
    decomposition: BezierDecomposition,
    /// Per piece: its control-point box and tangent cone (each piece meets many others in the
    /// narrow phase; these are worked out once).
    bounds: Vec<Bounds>,
    size: f64,
}

#[derive(Clone, Copy, Debug)]
struct Hit {
    a: usize,
    b: usize,
    s: f64,
    t: f64,
    gap: f64,
    /// Curve a at `s` and curve b at `t` (kept so later stages need not evaluate again).
    pa: DVec3,
    pb: DVec3,
    /// Sine of the angle between the two curves' tangents there.
    sine: f64,
}

impl Hit {
    /// A join of curve `a` at `s` with curve `b` at `t`, with its points and crossing angle
    /// evaluated.
    fn at(prepared: &[Prepared], a: usize, b: usize, s: f64, t: f64, gap: f64) -> Hit {
        let (ea, eb) = (
            prepared[a].decomposition.derivs(s),
            prepared[b].decomposition.derivs(t),
        );
        Hit {
            a,
            b,
            s,
            t,
            gap,
            pa: ea.point,
            pb: eb.point,
            sine: sine_between(ea.d1, eb.d1),
        }
    }
}

/// Sine of the angle between two tangent vectors (0 when one of them vanishes).
fn sine_between(ta: DVec3, tb: DVec3) -> f64 {
    ta.cross(tb).length() / (ta.length() * tb.length()).max(f64::MIN_POSITIVE)
}

#[derive(Clone, Copy)]
struct Item {
    curve: usize,
    seg: usize,
    bbox: Aabb,
}

impl Network {
    /// Find every node where the curves meet within `tolerance` (H-rep paper §3.1 and §5.2:
    /// curves start and end on other curves; T-joints are allowed).
    ///
    /// Broad phase: sort-and-sweep over the boxes of all Bézier pieces (grown by half the
    /// near-miss distance). Narrow phase: each candidate pair of pieces is halved (de Casteljau)
    /// while their boxes are within the near-miss distance, until their tangent cones are
    /// separated (then they approach each other at most once) or they are tiny; then Newton's
    /// method minimises `|C1(s) − C2(t)|²` from the closest points of the chords. Approaches
    /// within the tolerance join the curves; approaches within 10× tolerance are reported as
    /// near misses and not joined. Joins of curves meeting at a shallow angle are moved to a
    /// curve end or to a join with a third curve on the stretch where the two stay within
    /// tolerance. Curve points of all joins and all curve ends are clustered (union–find, with a
    /// sweep along x for points within the tolerance) into nodes, so the result does not depend
    /// on curve order, direction or sub-tolerance jitter.
    ///
    /// Implementation note: a self-intersection is reported but does not make a node; a
    /// stretch where two curves overlap is reported, its two ends become nodes, and it is kept
    /// on one curve only (see [`Junctions::suppressed`]). A tangential touch longer than
    /// 100 tolerances and 5 % of the shorter curve is reported as an overlap.
    pub fn junctions(&self, tolerance: Tolerance) -> Result<Junctions, Error> {
        let tol = tolerance.get();
        let near = tolerance.near_miss();
        let curves = self.curves();
        let mut diagnostics = Vec::new();
        let mut excluded = vec![false; curves.len()];
        let mut suppressed: Vec<(usize, f64, f64)> = Vec::new();

        for (i, c) in curves.iter().enumerate() {
            let (a, b) = c.curve.domain();
            let (pa, pb) = (c.curve.point(a), c.curve.point(b));
            if (pa - pb).length() < tol
                && super::check_length(&c.curve, tolerance)
                    .map_err(|e| e.named(&c.name))
                    .is_err()
            {
                excluded[i] = true;
                diagnostics.push(Diagnostic::ZeroLength {
                    curve: c.name.clone(),
                    location: pa,
                });
            }
        }

        let prepared: Vec<Prepared> = curves
            .iter()
            .map(|c| {
                let decomposition = c.curve.bezier_decomposition();
                let size = decomposition.hull_box().diagonal();
                let (a, b) = c.curve.domain();
                let bounds = decomposition
                    .pieces
                    .iter()
                    .map(|s| (s.hull_box(), s.tangent_cone()))
                    .collect();
                Prepared {
                    curve: &c.curve,
                    ends: [(a, c.curve.point(a)), (b, c.curve.point(b))],
                    decomposition,
                    bounds,
                    size,
                }
            })
            .collect();

        // Broad phase: sort-and-sweep along the axis of largest spread.
        let mut items: Vec<Item> = Vec::new();
        for (ci, p) in prepared.iter().enumerate() {
            if excluded[ci] {
                continue;
            }
            for (si, s) in p.decomposition.pieces.iter().enumerate() {
                items.push(Item {
                    curve: ci,
                    seg: si,
                    bbox: s.hull_box().expanded(0.5 * near),
                });
            }
        }
        let axis = sweep_axis(&items);
        items.sort_by(|a, b| a.bbox.min[axis].total_cmp(&b.bbox.min[axis]));
        let mut pairs: Vec<(usize, usize, usize, usize)> = Vec::new();
        for i in 0..items.len() {
            let a = items[i];
            for b in &items[i + 1..] {
                if b.bbox.min[axis] > a.bbox.max[axis] {
                    break;
                }
                if !a.bbox.intersects(&b.bbox) {
                    continue;
                }
                let (x, y) = if (a.curve, a.seg) < (b.curve, b.seg) {
                    (a, *b)
                } else {
                    (*b, a)
                };
                if x.curve == y.curve && y.seg <= x.seg + 1 {
                    continue; // the same piece or neighbours: they share an end point
                }
                pairs.push((x.curve, y.curve, x.seg, y.seg));
            }
        }
        pairs.sort_unstable();

        // Narrow phase, one curve pair at a time.
        let mut hits: Vec<Hit> = Vec::with_capacity(pairs.len());
        let mut pair_hits: Vec<Hit> = Vec::new();
        let mut k = 0;
        while k < pairs.len() {
            let (ca, cb) = (pairs[k].0, pairs[k].1);
            let mut group_end = k;
            while group_end < pairs.len() && (pairs[group_end].0, pairs[group_end].1) == (ca, cb) {
                group_end += 1;
            }
            pair_hits.clear();
            let mut narrow = Narrow {
                a: &prepared[ca],
                b: &prepared[cb],
                ca,
                cb,
                near,
                accuracy: tol * NEWTON_ACCURACY,
                leaves: 0,
                hits: &mut pair_hits,
            };
            for &(_, _, sa, sb) in &pairs[k..group_end] {
                let (pa, pb) = (&prepared[ca], &prepared[cb]);
                narrow.recurse(
                    &pa.decomposition.pieces[sa],
                    &pb.decomposition.pieces[sb],
                    Some(pa.bounds[sa]),
                    Some(pb.bounds[sb]),
                    0,
                );
            }
            if ca == cb {
                self_hits(
                    &prepared[ca],
                    &pair_hits,
                    tolerance,
                    &mut diagnostics,
                    &curves[ca].name,
                );
            } else {
                sort_out_pair(
                    &prepared,
                    &pair_hits,
                    tolerance,
                    curves,
                    PairOutcome {
                        diagnostics: &mut diagnostics,
                        excluded: &mut excluded,
                        suppressed: &mut suppressed,
                        joins: &mut hits,
                    },
                );
            }
            k = group_end;
        }
        // A duplicate found late must not keep joins made with it.
        hits.retain(|h| !excluded[h.a] && !excluded[h.b]);
        snap_shallow_joins(&prepared, &mut hits, tol);

        let mut out = cluster(self, &prepared, &hits, &excluded, tol, diagnostics);
        out.suppressed = suppressed;
        Ok(out)
    }
}

fn sweep_axis(items: &[Item]) -> usize {
    let all = items.iter().map(|i| i.bbox).reduce(Aabb::union);
    match all {
        Some(b) => {
            let d = b.max - b.min;
            if d.x >= d.y && d.x >= d.z {
                0
            } else if d.y >= d.z {
                1
            } else {
                2
            }
        }
        None => 0,
    }
}

/// A piece's control-point box and tangent cone.
type Bounds = (Aabb, Option<TangentCone>);

struct Narrow<'a, 'h> {
    a: &'a Prepared<'a>,
    b: &'a Prepared<'a>,
    ca: usize,
    cb: usize,
    near: f64,
    accuracy: f64,
    leaves: usize,
    hits: &'h mut Vec<Hit>,
}

impl Narrow<'_, '_> {
    /// Halve the pair until it is a leaf; `kx`, `ky` are the pieces' box and cone when known.
    fn recurse(
        &mut self,
        x: &BezierPiece,
        y: &BezierPiece,
        kx: Option<Bounds>,
        ky: Option<Bounds>,
        depth: u32,
    ) {
        let (bx, by) = (
            kx.map_or_else(|| x.hull_box(), |k| k.0),
            ky.map_or_else(|| y.hull_box(), |k| k.0),
        );
        if bx.gap_to(&by) > self.near || self.leaves >= MAX_LEAVES {
            return;
        }
        let (dx, dy) = (bx.diagonal(), by.diagonal());
        let small_x = dx <= (LEAF_SIZE_FRACTION * self.a.size).max(self.near);
        let small_y = dy <= (LEAF_SIZE_FRACTION * self.b.size).max(self.near);
        let leaf = (small_x && small_y)
            || depth >= MAX_DEPTH
            || match (
                kx.map_or_else(|| x.tangent_cone(), |k| k.1),
                ky.map_or_else(|| y.tangent_cone(), |k| k.1),
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
            points,
            tangents,
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
                pa: points.0,
                pb: points.1,
                sine: sine_between(tangents.0, tangents.1),
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

/// Report where a curve crosses itself (pieces that are not neighbours along the curve).
fn self_hits(
    p: &Prepared,
    hits: &[Hit],
    tolerance: Tolerance,
    diagnostics: &mut Vec<Diagnostic>,
    name: &str,
) {
    let tol = tolerance.get();
    let mut found: Vec<DVec3> = Vec::new();
    for h in hits {
        if h.gap > tol {
            continue;
        }
        let (lo, hi) = if h.s < h.t { (h.s, h.t) } else { (h.t, h.s) };
        let mut along = p
            .curve
            .arc_length_between(lo, hi, tol * 1e-2)
            .unwrap_or(0.0);
        let (a, b) = p.curve.domain();
        if (p.curve.point(a) - p.curve.point(b)).length() <= tol {
            // A closed curve: its ends are neighbours across the seam.
            let total = p.curve.arc_length(tol * 1e-2).unwrap_or(along);
            along = along.min(total - along);
        }
        if along <= 2.0 * tolerance.near_miss() {
            continue;
        }
        let location = h.pa;
        if found
            .iter()
            .any(|q| (*q - location).length() <= tolerance.near_miss())
        {
            continue;
        }
        found.push(location);
        diagnostics.push(Diagnostic::SelfIntersection {
            curve: name.to_owned(),
            location,
            gap: h.gap,
        });
    }
}

/// Where [`sort_out_pair`] puts what it finds.
struct PairOutcome<'o> {
    diagnostics: &'o mut Vec<Diagnostic>,
    excluded: &'o mut [bool],
    suppressed: &'o mut Vec<(usize, f64, f64)>,
    joins: &'o mut Vec<Hit>,
}

/// Sort the approaches of one pair of curves into joins, tangential touches, overlaps,
/// duplicates and near misses; pushes the joins that make nodes onto `out.joins`.
fn sort_out_pair(
    prepared: &[Prepared],
    pair_hits: &[Hit],
    tolerance: Tolerance,
    curves: &[super::NetworkCurve],
    out: PairOutcome,
) {
    let tol = tolerance.get();
    let near = tolerance.near_miss();
    let Some(first) = pair_hits.first() else {
        return;
    };
    let (ca, cb) = (first.a, first.b);
    let (pa, pb) = (&prepared[ca], &prepared[cb]);
    let names = || {
        let (x, y) = (curves[ca].name.clone(), curves[cb].name.clone());
        if x <= y {
            [x, y]
        } else {
            [y, x]
        }
    };
    if pair_hits.len() == 1 && first.gap <= tol {
        // The usual case, one crossing: only the end snapping applies.
        let mut h = *first;
        snap_to_end(prepared, &mut h, tol, false);
        snap_to_end(prepared, &mut h, tol, true);
        out.joins.push(h);
        return;
    }
    let mut joins: Vec<Hit> = pair_hits.iter().copied().filter(|h| h.gap <= tol).collect();
    // Curves meeting at a shallow angle are within tolerance along a short stretch; where that
    // stretch reaches a curve end, the join is at the end (else jitter moves it along).
    for h in &mut joins {
        snap_to_end(prepared, h, tol, false);
        snap_to_end(prepared, h, tol, true);
    }
    joins.sort_by(|x, y| x.s.total_cmp(&y.s));
    // Merge joins that are the same point of curve a.
    joins.dedup_by(|later, earlier| {
        (later.pa - earlier.pa).length() <= tol && {
            if later.gap < earlier.gap {
                *earlier = *later;
            }
            true
        }
    });

    // Chains of joins connected by a stretch that stays within tolerance.
    let mut kept: Vec<Hit> = Vec::new();
    let mut i = 0;
    while i < joins.len() {
        let mut j = i;
        while j + 1 < joins.len() && stays_close(pa, pb, joins[j].s, joins[j + 1].s, tol) {
            j += 1;
        }
        if j == i {
            kept.push(joins[i]);
        } else {
            let chain = &joins[i..=j];
            let extent: f64 = chain.windows(2).map(|w| (w[1].pa - w[0].pa).length()).sum();
            let shorter = pa.size.min(pb.size);
            if extent > (OVERLAP_MIN_TOLERANCES * tol).max(OVERLAP_MIN_FRACTION * shorter) {
                // The joins sample the shared stretch; find where it really ends.
                let (a0, a1) = pa.curve.domain();
                let s_lo = stretch_end(pa, pb, chain[0].s, a0, tol);
                let s_hi = stretch_end(pa, pb, chain[chain.len() - 1].s, a1, tol);
                let (from, to) = (pa.curve.point(s_lo), pa.curve.point(s_hi));
                let on_b = |p: DVec3| {
                    pb.decomposition
                        .nearest(p, tol * 1e-2)
                        .map_or((pb.curve.domain().0, f64::INFINITY), |n| (n.t, n.distance))
                };
                let ((t_lo, g_lo), (t_hi, g_hi)) = (on_b(from), on_b(to));
                let a_covered = is_end(pa.curve, s_lo, tol)
                    && is_end(pa.curve, s_hi, tol)
                    && (from - to).length() > tol;
                let b_covered = is_end(pb.curve, t_lo, tol)
                    && is_end(pb.curve, t_hi, tol)
                    && (pb.curve.point(t_lo) - pb.curve.point(t_hi)).length() > tol;
                if a_covered && b_covered {
                    let drop = if curves[ca].name <= curves[cb].name {
                        cb
                    } else {
                        ca
                    };
                    out.excluded[drop] = true;
                    out.diagnostics.push(Diagnostic::DuplicateCurve {
                        curves: names(),
                        location: from,
                    });
                    return;
                }
                out.diagnostics.push(Diagnostic::Overlap {
                    curves: names(),
                    from,
                    to,
                });
                if curves[ca].name > curves[cb].name {
                    out.suppressed.push((ca, s_lo.min(s_hi), s_lo.max(s_hi)));
                } else {
                    out.suppressed.push((cb, t_lo.min(t_hi), t_lo.max(t_hi)));
                }
                let (ca_, cb_) = (chain[0].a, chain[0].b);
                kept.push(Hit::at(prepared, ca_, cb_, s_lo, t_lo, g_lo));
                kept.push(Hit::at(prepared, ca_, cb_, s_hi, t_hi, g_hi));
            } else {
                // A tangential touch: one join, at a curve end if there is one there.
                let at_end = chain
                    .iter()
                    .find(|h| is_end(pa.curve, h.s, tol) || is_end(pb.curve, h.t, tol));
                let best = at_end.copied().unwrap_or_else(|| {
                    *chain
                        .iter()
                        .min_by(|x, y| x.gap.total_cmp(&y.gap))
                        .expect("a chain has joins")
                });
                kept.push(best);
            }
        }
        i = j + 1;
    }

    // Near misses: approaches between tol and 10·tol, away from any join of this pair.
    let mut misses: Vec<Hit> = pair_hits
        .iter()
        .copied()
        .filter(|h| h.gap > tol)
        .filter(|h| !kept.iter().any(|k| (k.pa - h.pa).length() <= 2.0 * near))
        .collect();
    misses.sort_by(|x, y| x.s.total_cmp(&y.s));
    let mut reported: Vec<Hit> = Vec::new();
    for m in misses {
        if let Some(r) = reported
            .iter_mut()
            .find(|r| (r.pa - m.pa).length() <= 10.0 * near)
        {
            if m.gap < r.gap {
                *r = m;
            }
        } else {
            reported.push(m);
        }
    }
    for m in reported {
        let location = 0.5 * (m.pa + m.pb);
        out.diagnostics.push(Diagnostic::NearMiss {
            curves: names(),
            location,
            gap: m.gap,
        });
    }
    out.joins.extend(kept);
}

fn is_end(curve: &NurbsCurve, t: f64, tol: f64) -> bool {
    let (a, b) = curve.domain();
    let p = curve.point(t);
    (p - curve.point(a)).length() <= tol || (p - curve.point(b)).length() <= tol
}

/// Where a stretch of curve a that stays within `tol` of curve b ends, going from `inside`
/// (close) towards `bound`: `bound` itself when it is close, else found by bisection.
fn stretch_end(pa: &Prepared, pb: &Prepared, inside: f64, bound: f64, tol: f64) -> f64 {
    // Half the tolerance: the end found is then well within the tolerance of the true end of
    // the shared stretch (where the curves part, or where one of them ends).
    let close = |s: f64| {
        pb.decomposition
            .nearest(pa.curve.point(s), tol * 1e-2)
            .is_ok_and(|n| n.distance <= 0.5 * tol)
    };
    if close(bound) {
        return bound;
    }
    let (mut lo, mut hi) = (inside, bound);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if close(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Curves meeting at an angle with sine below this are "shallow": their join is ill-defined
/// along the stretch where they stay within tolerance (about 30°).
const SHALLOW_SINE: f64 = 0.5;

/// Move joins of curves meeting at a shallow angle onto a join of one of them with a third
/// curve, when that lies on the stretch where the two stay within tolerance: the join of two
/// nearly tangent curves can lie anywhere on that stretch, and would otherwise make a second
/// node beside the one where a third curve crosses them.
fn snap_shallow_joins(prepared: &[Prepared], hits: &mut [Hit], tol: f64) {
    let mut on_curve: Vec<Vec<f64>> = vec![Vec::new(); prepared.len()];
    for h in hits.iter() {
        on_curve[h.a].push(h.s);
        on_curve[h.b].push(h.t);
    }
    for h in hits.iter_mut() {
        if h.sine >= SHALLOW_SINE {
            continue;
        }
        let (pa, pb) = (&prepared[h.a], &prepared[h.b]);
        let mut best: Option<(f64, Hit)> = None;
        for (swapped, p, q, here, at) in [(false, pa, pb, h.s, h.pa), (true, pb, pa, h.t, h.pb)] {
            let list = if swapped {
                &on_curve[h.b]
            } else {
                &on_curve[h.a]
            };
            for &u in list {
                let pu = p.curve.point(u);
                let d = (pu - at).length();
                if u == here || d > OVERLAP_MIN_TOLERANCES * tol {
                    continue;
                }
                let Ok(n) = q.decomposition.nearest(pu, tol * 1e-2) else {
                    continue;
                };
                if n.distance > tol || !stays_close(p, q, here, u, tol) {
                    continue;
                }
                let (s, t) = if swapped { (n.t, u) } else { (u, n.t) };
                let moved = Hit::at(prepared, h.a, h.b, s, t, n.distance);
                let better = best.is_none_or(|(g, b)| {
                    n.distance < g || (n.distance == g && (moved.s, moved.t) < (b.s, b.t))
                });
                if better {
                    best = Some((n.distance, moved));
                }
            }
        }
        if let Some((_, moved)) = best {
            *h = moved;
        }
    }
}

/// Move a join to an end of curve `p` (the join's `s` side, or its `t` side when `swapped`)
/// when that end is within `tol` of curve `q` and the stretch of `p` from the join to the end
/// stays within `tol` of `q`.
fn snap_to_end(prepared: &[Prepared], h: &mut Hit, tol: f64, swapped: bool) {
    let (p, q) = if swapped {
        (&prepared[h.b], &prepared[h.a])
    } else {
        (&prepared[h.a], &prepared[h.b])
    };
    let (s, here) = if swapped { (h.t, h.pb) } else { (h.s, h.pa) };
    for (end, end_point) in p.ends {
        let to_end = (end_point - here).length();
        // Within the tolerance the clustering already puts the join on the end.
        if to_end <= tol || to_end > OVERLAP_MIN_TOLERANCES * tol {
            continue;
        }
        let Ok(n) = q.decomposition.nearest(end_point, tol * 1e-2) else {
            continue;
        };
        if n.distance <= tol && stays_close(p, q, s, end, tol) {
            let (ns, nt) = if swapped { (n.t, end) } else { (end, n.t) };
            *h = Hit::at(prepared, h.a, h.b, ns, nt, n.distance);
            return;
        }
    }
}

/// True when curve a between parameters `s0` and `s1` stays within `tol` of curve b.
fn stays_close(pa: &Prepared, pb: &Prepared, s0: f64, s1: f64, tol: f64) -> bool {
    [0.25, 0.5, 0.75].iter().all(|f| {
        let q = pa.curve.point(s0 + f * (s1 - s0));
        pb.decomposition
            .nearest(q, tol * 1e-2)
            .is_ok_and(|n| n.distance <= tol)
    })
}

struct UnionFind(Vec<usize>);

impl UnionFind {
    fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }
    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb)] = ra.min(rb);
        }
    }
}

/// Cluster curve ends and joins into nodes (union–find: joined pairs, and any two curve points
/// within the tolerance, found by a sweep along x).
fn cluster(
    network: &Network,
    prepared: &[Prepared],
    hits: &[Hit],
    excluded: &[bool],
    tol: f64,
    diagnostics: Vec<Diagnostic>,
) -> Junctions {
    let curves = network.curves();
    let mut incs: Vec<(Incidence, DVec3)> = Vec::new();
    for (ci, p) in prepared.iter().enumerate() {
        if excluded[ci] {
            continue;
        }
        let (a, b) = p.curve.domain();
        for t in [a, b] {
            incs.push((Incidence { curve: ci, t }, p.curve.point(t)));
        }
    }
    let mut uf = UnionFind((0..incs.len() + 2 * hits.len()).collect());
    for h in hits {
        let ia = incs.len();
        incs.push((Incidence { curve: h.a, t: h.s }, h.pa));
        incs.push((Incidence { curve: h.b, t: h.t }, h.pb));
        uf.union(ia, ia + 1);
    }
    // Any two curve points within the tolerance are one node: sweep along x.
    let mut by_x: Vec<(f64, usize)> = incs.iter().map(|(_, p)| p.x).zip(0..).collect();
    by_x.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    for (k, &(x, i)) in by_x.iter().enumerate() {
        let p = incs[i].1;
        for &(qx, j) in &by_x[k + 1..] {
            if qx - x > tol {
                break;
            }
            if (incs[j].1 - p).length() <= tol {
                uf.union(i, j);
            }
        }
    }
    // Groups, in order of their smallest member (curve ends come first, in curve order), as
    // runs of one flat array (counting sort by node).
    let mut node_of_root = vec![usize::MAX; incs.len()];
    let mut node_of = vec![0usize; incs.len()];
    let mut count: Vec<usize> = Vec::new();
    for i in 0..incs.len() {
        let r = uf.find(i);
        if node_of_root[r] == usize::MAX {
            node_of_root[r] = count.len();
            count.push(0);
        }
        node_of[i] = node_of_root[r];
        count[node_of[i]] += 1;
    }
    let mut start = vec![0usize; count.len() + 1];
    for (n, c) in count.iter().enumerate() {
        start[n + 1] = start[n] + c;
    }
    let mut fill = start.clone();
    let mut flat = vec![0usize; incs.len()];
    for (i, &n) in node_of.iter().enumerate() {
        flat[fill[n]] = i;
        fill[n] += 1;
    }
    let mut nodes = Vec::with_capacity(count.len());
    let mut splits: Vec<Vec<(f64, usize)>> = vec![Vec::new(); curves.len()];
    let mut list: Vec<(Incidence, DVec3)> = Vec::new();
    let mut merged: Vec<(Incidence, DVec3)> = Vec::new();
    for node in 0..count.len() {
        let members = &flat[start[node]..start[node + 1]];
        let position = members.iter().map(|&i| incs[i].1).sum::<DVec3>() / members.len() as f64;
        list.clear();
        list.extend(members.iter().map(|&i| incs[i]));
        list.sort_by(|x, y| x.0.curve.cmp(&y.0.curve).then(x.0.t.total_cmp(&y.0.t)));
        // One incidence per curve and place: ends win, otherwise the point nearest the node.
        merged.clear();
        for &(inc, p) in &list {
            let curve = prepared[inc.curve].curve;
            let end_param = {
                let (a, b) = curve.domain();
                (inc.t == a || inc.t == b).then_some(inc.t)
            };
            let (a, b) = curve.domain();
            // The two ends of a closed curve stay two incidences.
            let opposite_ends =
                |m: &Incidence| (m.t == a && inc.t == b) || (m.t == b && inc.t == a);
            match merged.iter_mut().find(|(m, q)| {
                m.curve == inc.curve && (*q - p).length() <= tol && !opposite_ends(m)
            }) {
                Some(m) => {
                    let m_end = m.0.t == a || m.0.t == b;
                    if end_param.is_some() && !m_end
                        || (!m_end
                            && end_param.is_none()
                            && (p - position).length() < (m.1 - position).length())
                    {
                        *m = (inc, p);
                    }
                }
                None => merged.push((inc, p)),
            }
        }
        for (inc, _) in &merged {
            splits[inc.curve].push((inc.t, node));
        }
        nodes.push(Junction {
            position,
            incidences: merged.iter().map(|(i, _)| *i).collect(),
        });
    }
    for s in &mut splits {
        s.sort_by(|x, y| x.0.total_cmp(&y.0));
    }
    Junctions {
        nodes,
        splits,
        excluded: excluded.to_vec(),
        suppressed: Vec::new(),
        diagnostics,
    }
}
