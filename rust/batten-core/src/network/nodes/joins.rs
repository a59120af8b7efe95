//! Sorting the approaches of a pair of curves into joins, tangential touches, overlaps,
//! duplicates, near misses and self-intersections, and moving ill-defined joins of nearly
//! tangent curves to a curve end or a third curve's join.

use glam::DVec3;

use super::super::{NetworkCurve, Role};
use super::{Hit, Prepared};
use crate::curve::NurbsCurve;
use crate::diagnostic::Diagnostic;
use crate::tolerance::Tolerance;

/// A stretch where two curves stay within tolerance is an overlap (not a tangential touch)
/// when longer than [`Tolerance::overlap_min_length`] and this fraction of the shorter curve.
const OVERLAP_MIN_FRACTION: f64 = 0.05;

/// Report where a curve crosses itself (pieces that are not neighbours along the curve).
pub(super) fn self_hits(
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
            .arc_length_between(lo, hi, tolerance.search_accuracy())
            .unwrap_or(0.0);
        let (a, b) = p.curve.domain();
        if (p.curve.point(a) - p.curve.point(b)).length() <= tol {
            // A closed curve: its ends are neighbours across the seam.
            let total = p
                .curve
                .arc_length(tolerance.search_accuracy())
                .unwrap_or(along);
            along = along.min(total - along);
        }
        if along <= tolerance.self_crossing_min_arc() {
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

/// Of two duplicate curves, whether `a` is kept rather than `b`: a curve with a role (a
/// transom, a keel, a chine) over a free one drawn along it (a station cut in the transom's
/// plane), else the first by name.
fn keeps_over(a: &NetworkCurve, b: &NetworkCurve) -> bool {
    match (a.role == Role::Free, b.role == Role::Free) {
        (false, true) => true,
        (true, false) => false,
        _ => a.name <= b.name,
    }
}

/// Where [`sort_out_pair`] puts what it finds.
pub(super) struct PairOutcome<'o> {
    pub(super) diagnostics: &'o mut Vec<Diagnostic>,
    pub(super) excluded: &'o mut [bool],
    pub(super) suppressed: &'o mut Vec<(usize, f64, f64)>,
    pub(super) joins: &'o mut Vec<Hit>,
}

/// The usual outcome for a pair of curves, one crossing within the tolerance: its join, moved
/// to a curve end where the two stay within the tolerance up to it ([`snap_to_end`]). `None`
/// for anything else, which [`sort_out_pair`] sorts out. It reads nothing but the two curves,
/// so the narrow phase works it out in parallel.
pub(super) fn single_crossing(
    prepared: &[Prepared],
    pair_hits: &[Hit],
    tolerance: Tolerance,
) -> Option<Hit> {
    match pair_hits {
        [h] if h.gap <= tolerance.get() && h.a != h.b => {
            let mut h = *h;
            snap_to_end(prepared, &mut h, tolerance, false);
            snap_to_end(prepared, &mut h, tolerance, true);
            Some(h)
        }
        _ => None,
    }
}

/// Sort the approaches of one pair of curves into joins, tangential touches, overlaps,
/// duplicates and near misses; pushes the joins that make nodes onto `out.joins`.
pub(super) fn sort_out_pair(
    prepared: &[Prepared],
    pair_hits: &[Hit],
    tolerance: Tolerance,
    curves: &[NetworkCurve],
    out: PairOutcome,
) {
    let tol = tolerance.get();
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
    if let Some(h) = single_crossing(prepared, pair_hits, tolerance) {
        out.joins.push(h);
        return;
    }
    let mut joins: Vec<Hit> = pair_hits.iter().copied().filter(|h| h.gap <= tol).collect();
    // Curves meeting at a shallow angle are within tolerance along a short stretch; where that
    // stretch reaches a curve end, the join is at the end (else jitter moves it along).
    for h in &mut joins {
        snap_to_end(prepared, h, tolerance, false);
        snap_to_end(prepared, h, tolerance, true);
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
        while j + 1 < joins.len() && stays_close(pa, pb, joins[j].s, joins[j + 1].s, tolerance) {
            j += 1;
        }
        if j == i {
            kept.push(joins[i]);
        } else {
            let chain = &joins[i..=j];
            let extent: f64 = chain.windows(2).map(|w| (w[1].pa - w[0].pa).length()).sum();
            let shorter = pa.size.min(pb.size);
            if extent > (tolerance.overlap_min_length()).max(OVERLAP_MIN_FRACTION * shorter) {
                // The joins sample the shared stretch; find where it really ends.
                let (a0, a1) = pa.curve.domain();
                let s_lo = stretch_end(pa, pb, chain[0].s, a0, tolerance);
                let s_hi = stretch_end(pa, pb, chain[chain.len() - 1].s, a1, tolerance);
                let (from, to) = (pa.curve.point(s_lo), pa.curve.point(s_hi));
                let on_b = |p: DVec3| {
                    pb.decomposition
                        .nearest(p, tolerance.search_accuracy())
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
                    let (keep, drop) = if keeps_over(&curves[ca], &curves[cb]) {
                        (ca, cb)
                    } else {
                        (cb, ca)
                    };
                    out.excluded[drop] = true;
                    out.diagnostics.push(Diagnostic::DuplicateCurve {
                        curves: [curves[keep].name.clone(), curves[drop].name.clone()],
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
        .filter(|h| {
            !kept
                .iter()
                .any(|k| (k.pa - h.pa).length() <= tolerance.near_miss_clearance())
        })
        .collect();
    misses.sort_by(|x, y| x.s.total_cmp(&y.s));
    let mut reported: Vec<Hit> = Vec::new();
    for m in misses {
        if let Some(r) = reported
            .iter_mut()
            .find(|r| (r.pa - m.pa).length() <= tolerance.near_miss_merge())
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
fn stretch_end(pa: &Prepared, pb: &Prepared, inside: f64, bound: f64, tolerance: Tolerance) -> f64 {
    // Half the tolerance: the end found is then well within the tolerance of the true end of
    // the shared stretch (where the curves part, or where one of them ends).
    let close = |s: f64| {
        pb.decomposition
            .nearest(pa.curve.point(s), tolerance.search_accuracy())
            .is_ok_and(|n| n.distance <= tolerance.shared_stretch())
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
pub(super) fn snap_shallow_joins(prepared: &[Prepared], hits: &mut [Hit], tolerance: Tolerance) {
    let tol = tolerance.get();
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
                if u == here || d > tolerance.overlap_min_length() {
                    continue;
                }
                let Ok(n) = q.decomposition.nearest(pu, tolerance.search_accuracy()) else {
                    continue;
                };
                if n.distance > tol || !stays_close(p, q, here, u, tolerance) {
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
fn snap_to_end(prepared: &[Prepared], h: &mut Hit, tolerance: Tolerance, swapped: bool) {
    let tol = tolerance.get();
    let (p, q) = if swapped {
        (&prepared[h.b], &prepared[h.a])
    } else {
        (&prepared[h.a], &prepared[h.b])
    };
    let (s, here) = if swapped { (h.t, h.pb) } else { (h.s, h.pa) };
    for (end, end_point) in p.ends {
        let to_end = (end_point - here).length();
        // Within the tolerance the clustering already puts the join on the end.
        if to_end <= tol || to_end > tolerance.overlap_min_length() {
            continue;
        }
        let Ok(n) = q
            .decomposition
            .nearest(end_point, tolerance.search_accuracy())
        else {
            continue;
        };
        if n.distance <= tol && stays_close(p, q, s, end, tolerance) {
            let (ns, nt) = if swapped { (n.t, end) } else { (end, n.t) };
            *h = Hit::at(prepared, h.a, h.b, ns, nt, n.distance);
            return;
        }
    }
}

/// True when curve a between parameters `s0` and `s1` stays within `tol` of curve b.
fn stays_close(pa: &Prepared, pb: &Prepared, s0: f64, s1: f64, tolerance: Tolerance) -> bool {
    let tol = tolerance.get();
    [0.25, 0.5, 0.75].iter().all(|f| {
        let q = pa.curve.point(s0 + f * (s1 - s0));
        pb.decomposition
            .nearest(q, tolerance.search_accuracy())
            .is_ok_and(|n| n.distance <= tol)
    })
}
