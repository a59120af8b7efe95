//! Nodes of a curve network: every place where designer curves meet within the model tolerance
//! (end to end, an end on another curve's interior — a T-joint — and interior crossings), found
//! by bounding-volume culling ([`broad`]), recursive Bézier subdivision and Newton refinement
//! ([`narrow`]), sorted into joins, overlaps and near misses ([`joins`]), and clustered
//! ([`cluster`]) so that three or more curves meeting at one point give one node.

mod broad;
mod cluster;
mod joins;
mod narrow;

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::Network;
use crate::curve::{BezierDecomposition, NurbsCurve};
use crate::diagnostic::Diagnostic;
use crate::error::Error;
use crate::tolerance::Tolerance;

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

/// A curve made ready for the node search: its ends, Bézier pieces and their bounds.
struct Prepared<'a> {
    curve: &'a NurbsCurve,
    /// Parameters and points of the curve's two ends.
    ends: [(f64, DVec3); 2],
    decomposition: BezierDecomposition,
    /// Per piece: its control-point box and tangent cone (each piece meets many others in the
    /// narrow phase; these are worked out once).
    bounds: Vec<narrow::PieceBounds>,
    size: f64,
}

/// An approach of two curves found by the narrow phase (a join when within the tolerance).
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

/// The approaches the narrow phase finds for one pair of curves (most pairs cross once).
type PairHits = SmallVec<[Hit; 2]>;

/// What the narrow phase found for one pair of curves.
enum PairFound {
    /// One crossing, already sorted out ([`joins::single_crossing`]).
    Join(Hit),
    /// Anything else, for [`joins::sort_out_pair`] or [`joins::self_hits`] (on the heap: the
    /// list of all pairs' findings stays the size of one join per pair).
    Approaches(Vec<Hit>),
}

/// Sine of the angle between two tangent vectors (0 when one of them vanishes).
fn sine_between(ta: DVec3, tb: DVec3) -> f64 {
    ta.cross(tb).length() / (ta.length() * tb.length()).max(f64::MIN_POSITIVE)
}

/// Curve pairs handed to one parallel task of the narrow phase at least (a pair of crossing
/// curves takes about a microsecond; fewer per task and the scheduling costs more than it
/// saves).
const NARROW_PAIRS_PER_TASK: usize = 64;

/// The runs of `pairs` (sorted by curves) that share one pair of curves, as `start..end`.
fn pair_groups(pairs: &[broad::CandidatePair]) -> Vec<(usize, usize)> {
    let mut groups = Vec::new();
    let mut k = 0;
    while k < pairs.len() {
        let key = (pairs[k].curve_a, pairs[k].curve_b);
        let mut end = k + 1;
        while end < pairs.len() && (pairs[end].curve_a, pairs[end].curve_b) == key {
            end += 1;
        }
        groups.push((k, end));
        k = end;
    }
    groups
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
    /// sweep along a generic direction for points within the tolerance) into nodes, so the
    /// result does not depend on curve order, direction or sub-tolerance jitter.
    ///
    /// Implementation note: a self-intersection is reported but does not make a node; a
    /// stretch where two curves overlap is reported, its two ends become nodes, and it is kept
    /// on one curve only (see [`Junctions::suppressed`]). A tangential touch longer than
    /// 100 tolerances and 5 % of the shorter curve is reported as an overlap.
    pub fn junctions(&self, tolerance: Tolerance) -> Result<Junctions, Error> {
        self.junctions_and_pieces(tolerance).map(|(j, _)| j)
    }

    /// [`Network::junctions`], with every curve's Bézier decomposition made on the way (the
    /// topology evaluates the curves on them again).
    pub(crate) fn junctions_and_pieces(
        &self,
        tolerance: Tolerance,
    ) -> Result<(Junctions, Vec<BezierDecomposition>), Error> {
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
            .par_iter()
            .map(|c| {
                let decomposition = c.curve.bezier_decomposition();
                let size = decomposition.hull_box().diagonal();
                let (a, b) = c.curve.domain();
                let bounds = decomposition
                    .pieces
                    .iter()
                    .map(narrow::PieceBounds::of)
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
        let pairs = broad::candidate_pairs(&prepared, &excluded, tolerance.sweep_margin());

        // Narrow phase, one curve pair at a time: the pairs are independent, so they run in
        // parallel; what they found is then sorted out in pair order, as one thread would.
        let groups = pair_groups(&pairs);
        let found: Vec<PairFound> = groups
            .par_iter()
            .with_min_len(NARROW_PAIRS_PER_TASK)
            .map(|&(k, end)| {
                let (ca, cb) = (pairs[k].curve_a, pairs[k].curve_b);
                let mut pair_hits = PairHits::new();
                let mut narrow = narrow::Narrow {
                    a: &prepared[ca],
                    b: &prepared[cb],
                    ca,
                    cb,
                    near,
                    accuracy: tolerance.newton_accuracy(),
                    leaves: 0,
                    hits: &mut pair_hits,
                };
                for &broad::CandidatePair {
                    piece_a: sa,
                    piece_b: sb,
                    ..
                } in &pairs[k..end]
                {
                    let (pa, pb) = (&prepared[ca], &prepared[cb]);
                    narrow.recurse(
                        &pa.decomposition.pieces[sa],
                        &pb.decomposition.pieces[sb],
                        Some(pa.bounds[sa]),
                        Some(pb.bounds[sb]),
                        0,
                    );
                }
                match joins::single_crossing(&prepared, &pair_hits, tolerance) {
                    Some(join) => PairFound::Join(join),
                    None => PairFound::Approaches(pair_hits.into_vec()),
                }
            })
            .collect();
        let mut hits: Vec<Hit> = Vec::with_capacity(pairs.len());
        for (&(k, _), found) in groups.iter().zip(found) {
            let (ca, cb) = (pairs[k].curve_a, pairs[k].curve_b);
            let pair_hits = match found {
                PairFound::Join(join) => {
                    hits.push(join);
                    continue;
                }
                PairFound::Approaches(pair_hits) => pair_hits,
            };
            if ca == cb {
                joins::self_hits(
                    &prepared[ca],
                    &pair_hits,
                    tolerance,
                    &mut diagnostics,
                    &curves[ca].name,
                );
            } else {
                joins::sort_out_pair(
                    &prepared,
                    &pair_hits,
                    tolerance,
                    curves,
                    joins::PairOutcome {
                        diagnostics: &mut diagnostics,
                        excluded: &mut excluded,
                        suppressed: &mut suppressed,
                        joins: &mut hits,
                    },
                );
            }
        }
        // A duplicate found late must not keep joins made with it.
        hits.retain(|h| !excluded[h.a] && !excluded[h.b]);
        joins::snap_shallow_joins(&prepared, &mut hits, tolerance);

        let mut out = cluster::cluster(self, &prepared, &hits, &excluded, tol, diagnostics);
        out.suppressed = suppressed;
        Ok((out, prepared.into_iter().map(|p| p.decomposition).collect()))
    }
}
