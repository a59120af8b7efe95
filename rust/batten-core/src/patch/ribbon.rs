//! Tangent ribbons: cross-boundary derivatives along each side of a face (H-rep paper §3.2.2).
//!
//! The paper builds the ribbon of a curve `C` from the tangents of the curves `D` crossing it:
//! at each crossing, `T = D' − (D'·C')/(C'·C') C'` (eq. 8, Gram–Schmidt), normalised, and
//! ignored when `D'` is within 15° of `C'`. batten keeps that construction but stores its
//! result as a **surface normal along the edge**, `n = Ĉ' × T̂`, blended between the crossing
//! nodes ([`EdgeNormal`]). Both faces sharing a smooth edge evaluate the same `n(t)` at the same
//! curve parameter and take their cross tangent in the plane perpendicular to it, pointing into
//! their own face; their tangent planes along the edge are therefore the same plane, which is
//! the G1 (GC¹) condition of §3.2.2, along the whole edge and not only at the nodes. A knuckle
//! (G0) edge simply gives each face its own [`EdgeNormal`], built from the crossing tangents on
//! its own side only.
//!
//! The ribbon of side `i` of a face is then
//! `R_i(s) = α(s)·ĉ(s) + β(s)·T̂(s)`, with `ĉ` the unit side tangent, `T̂ = n̂⊥ × ĉ` the unit
//! cross tangent (`n̂⊥` the normal made perpendicular to `ĉ` once more by Gram–Schmidt) and
//! `α`, `β` linear in `s` between the corner values that make `R_i` equal the neighbouring
//! sides' tangents at the two corners (projected into the tangent plane). That corner
//! condition is what the Gregory and Charrot–Gregory corner interpolants (eqs. 2–4) need to
//! reproduce both boundary curves and their cross derivatives.
//!
//! The angle of `R_i` to the side is blended in a frame carried along the side rather than in
//! `ĉ, T̂`, which turn with the side's tangent: a side that turns unevenly or has a corner
//! inside it then keeps its ribbon pointing into the face and continuous ([`Transport`]).
//!
//! A segment without crossing curves gets the face's default ribbon: the normal at each end
//! corner is `ĉ × a` with `a` the neighbouring side's tangent there (the face's own corner),
//! blended linearly and normalised along the side.

use glam::{DVec2, DVec3};

use super::boundary::{PreparedSide, SideSegment, EVEN_SAMPLES};
use super::error::{PatchError, PatchWarning};
use super::field_key::{same_bits, FieldKey};
use super::hermite::hermite_basis;

/// The paper's minimum angle between a side and a crossing curve (§3.2.2): crossing tangents
/// closer than this to the side tangent are ignored, because eq. 8 then amplifies noise.
pub const MIN_CROSSING_ANGLE_DEGREES: f64 = 15.0;

/// Corners sharper than this, or flatter than 180° minus this, are degenerate: the ribbon there
/// is turned to this angle and a [`PatchWarning::CornerAngle`] is recorded.
pub const MIN_CORNER_ANGLE_DEGREES: f64 = 2.0;

/// Corners sharper than this are cusps, though their ribbons need no repair
/// ([`MIN_CORNER_ANGLE_DEGREES`]): their two sides span the corner-based patches' tangent
/// plane only to a few hundredths of their directions' accuracy, so the hull build gives such
/// a face the side-blended patch, and the import takes curves meeting this shallowly as
/// uncertain in where they meet. KVLCC2's station 20 meets the stem at 1.2°, a repaired
/// corner; fitted a little differently (weighted fits, tried and left) it met it at 3.7°, no
/// repair, and the Charrot–Gregory patch between them creased 5.8° against its neighbour
/// across the station.
pub(crate) const CUSP_DEGREES: f64 = 5.0;

/// Below this length (relative to the vectors involved) a cross product or Gram–Schmidt
/// remainder is treated as zero: directions that close are parallel for every purpose here.
const PARALLEL: f64 = 1e-9;

/// Nodes beyond a segment's ends that turn its normal field by up to this from the straight
/// blend of its own nodes shape the field fully (see [`EdgeNormal::from_crossings_along`]).
pub(crate) const BEYOND_TRUSTED_DEGREES: f64 = 3.0;

/// Nodes beyond a segment's ends that would turn its normal field by this or more from the
/// straight blend of its own nodes are left out.
pub(crate) const BEYOND_DROPPED_DEGREES: f64 = 6.0;

/// Samples along a segment at which the turn of the nodes beyond is measured.
const BEYOND_SAMPLES: usize = 16;

/// How far a ribbon node's parameter may lie outside its segment's interval, relative to the
/// interval's length (at least 1): node parameters come from the topology's intersections and
/// may round past the segment's ends.
const NODE_PARAMETER_SLACK: f64 = 1e-9;

/// Samples per side of the boundary polygon whose Newell normal gives a face's overall
/// orientation (used only where local information is degenerate).
const NEWELL_SAMPLES_PER_SIDE: usize = 8;

/// The crossing information at one node on a side segment: the curve parameter of the node on
/// the segment's curve and the tangents of the other curves through it (any orientation, any
/// length; the adjacent sides' tangents at a corner count too).
#[derive(Clone, Debug, PartialEq)]
pub struct RibbonNode {
    /// Parameter of the node on the segment's curve.
    pub t: f64,
    /// Tangents of the crossing curves at the node.
    pub tangents: Vec<DVec3>,
}

/// The cross-boundary tangent of eq. 8 (paper §3.2.2): `cross` made perpendicular to
/// `side_tangent` by Gram–Schmidt and normalised, or `None` when the angle between the two is
/// below `min_angle_degrees` (the 15° rule), or either vector is zero or not finite.
pub fn gram_schmidt_cross_tangent(
    cross: DVec3,
    side_tangent: DVec3,
    min_angle_degrees: f64,
) -> Option<DVec3> {
    if !cross.is_finite() || !side_tangent.is_finite() {
        return None;
    }
    let (lc, ls) = (cross.length(), side_tangent.length());
    if lc <= 0.0 || ls <= 0.0 {
        return None;
    }
    let cos = (cross.dot(side_tangent) / (lc * ls)).abs().min(1.0);
    if cos.acos() < min_angle_degrees.to_radians() {
        return None;
    }
    let t = cross - side_tangent * (cross.dot(side_tangent) / side_tangent.dot(side_tangent));
    let l = t.length();
    (l > PARALLEL * lc).then(|| t / l)
}

/// The surface normal along one side segment (one topological edge), blended between nodes:
/// the shared-plane form of the paper's tangent ribbon (§3.2.2, eq. 8). See the module docs.
///
/// Nodes are keyed by the curve's own parameter, so the two faces sharing the segment (which
/// traverse it in opposite directions) evaluate the same normal at the same point. Between
/// nodes the unit normals are blended by a cubic Hermite (three-point slopes) in a key of the
/// curve parameter that never crowds more than `FieldKey` allows (`t` itself where the curve
/// has no measurable length) and normalised; outside the first and last node the end normals
/// are held. The sign is arbitrary; each face orients it outwards.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeNormal {
    /// The nodes' curve parameters.
    ts: Vec<f64>,
    /// Where the blend runs between them: the key of each node (`FieldKey`), or `ts` again.
    keys: Vec<f64>,
    normals: Vec<DVec3>,
    /// Slopes of the blend per unit of `keys`.
    slopes: Vec<DVec3>,
    /// The key of the curve's parameter, where the curve has a measurable length.
    key: Option<FieldKey>,
}

impl EdgeNormal {
    /// Whether `other` is this field bit for bit (so a patch built on either is the same; `==`
    /// would take −0 for 0 and refuse NaN).
    pub(crate) fn same_bits(&self, other: &EdgeNormal) -> bool {
        let vec_bits = |v: &DVec3| v.to_array().map(f64::to_bits);
        let keyed = match (&self.key, &other.key) {
            (Some(a), Some(b)) => a.same_bits(b),
            (None, None) => true,
            _ => false,
        };
        keyed
            && same_bits(&self.ts, &other.ts)
            && same_bits(&self.keys, &other.keys)
            && self.normals.len() == other.normals.len()
            && self.slopes.len() == other.slopes.len()
            && self
                .normals
                .iter()
                .zip(&other.normals)
                .all(|(a, b)| vec_bits(a) == vec_bits(b))
            && self
                .slopes
                .iter()
                .zip(&other.slopes)
                .all(|(a, b)| vec_bits(a) == vec_bits(b))
    }

    /// Build from the crossing curves at nodes along `segment` (eq. 8 with the 15° rule at each
    /// node; several crossing tangents at one node are averaged). Returns `Ok(None)` when no
    /// crossing tangent survives the angle rule: the face's default ribbon then applies.
    ///
    /// Errors when a node parameter is not finite or outside the segment's interval, or a
    /// tangent is not finite.
    pub fn from_crossings(
        segment: &SideSegment,
        nodes: &[RibbonNode],
        min_angle_degrees: f64,
    ) -> Result<Option<EdgeNormal>, PatchError> {
        EdgeNormal::from_crossings_along(segment, nodes, &[], min_angle_degrees)
    }

    /// [`EdgeNormal::from_crossings`], with nodes beyond the segment on the same curve as
    /// well, each with the curve's tangent there (the segment's curve may be cut to its
    /// interval): they shape the blend's slopes at the segment's ends and are never evaluated
    /// at. `Ok(None)` when no node inside the segment has a crossing tangent.
    pub fn from_crossings_along(
        segment: &SideSegment,
        nodes: &[RibbonNode],
        outer: &[(RibbonNode, DVec3)],
        min_angle_degrees: f64,
    ) -> Result<Option<EdgeNormal>, PatchError> {
        let mut pairs = Vec::with_capacity(nodes.len() + outer.len());
        let inner = nodes.iter().map(|n| (n, None));
        let outer = outer.iter().map(|(n, c)| (n, Some(*c)));
        for (node, tangent) in inner.chain(outer) {
            if tangent.is_none() {
                check_node_t(segment, node.t)?;
            } else if !node.t.is_finite() || !tangent.is_some_and(|c| c.is_finite()) {
                return Err(PatchError::BadRibbonNode {
                    curve: segment_label(segment),
                    t: node.t,
                    reason: "a node beyond the segment is not finite".to_string(),
                });
            }
            if let Some(bad) = node.tangents.iter().find(|v| !v.is_finite()) {
                return Err(PatchError::BadRibbonNode {
                    curve: segment_label(segment),
                    t: node.t,
                    reason: format!("crossing tangent {bad} is not finite"),
                });
            }
            let c = tangent.unwrap_or_else(|| {
                let d = segment.curve.derivs(node.t);
                if d.d1.length() > 0.0 {
                    d.d1
                } else {
                    d.d2
                }
            });
            let Some(c_hat) = c.try_normalize() else {
                continue;
            };
            let mut acc = DVec3::ZERO;
            let mut first: Option<DVec3> = None;
            for &v in &node.tangents {
                if let Some(t_hat) = gram_schmidt_cross_tangent(v, c_hat, min_angle_degrees) {
                    let n = c_hat.cross(t_hat);
                    let n = match first {
                        None => {
                            first = Some(n);
                            n
                        }
                        Some(f) if f.dot(n) < 0.0 => -n,
                        Some(_) => n,
                    };
                    acc += n;
                }
            }
            if let Some(n) = acc.try_normalize() {
                pairs.push((node.t, n, Some(c_hat)));
            }
        }
        let (lo, hi, slack) = node_range(segment);
        let inside = |t: f64| t >= lo - slack && t <= hi + slack;
        // A node beyond an end counts only beside a normal at that end.
        let has_end = |end: f64| pairs.iter().any(|&(t, _, _)| (t - end).abs() <= slack);
        let (at_lo, at_hi) = (has_end(lo), has_end(hi));
        let (inner, outer): (Vec<_>, Vec<_>) = pairs.into_iter().partition(|&(t, _, _)| inside(t));
        let outer: Vec<_> = outer
            .into_iter()
            .filter(|&(t, _, _)| if t < lo { at_lo } else { at_hi })
            .collect();
        if inner.is_empty() {
            return Ok(None);
        }
        let key = FieldKey::new(&segment.curve, lo, hi);
        let near = EdgeNormal::from_pairs(inner.clone(), key.clone());
        if outer.is_empty() || near.ts.len() < 2 {
            return Ok(Some(near));
        }
        let mut all = outer;
        all.extend(inner);
        let far = EdgeNormal::from_pairs(all, key);
        // How far the nodes beyond turn the field from the straight blend of the segment's
        // own nodes. A gentle turn is the surface's curvature along the curve, which the
        // three-node blend follows; past `BEYOND_TRUSTED_DEGREES` the tangent plane turns
        // too fast along the curve (a forefoot, a bilge of few nodes, noisy data) for a
        // parabola through three nodes, and the straight blend is kept, reached smoothly by
        // `BEYOND_DROPPED_DEGREES`.
        let turn = (0..=BEYOND_SAMPLES)
            .map(|j| {
                let t = lo + (hi - lo) * j as f64 / BEYOND_SAMPLES as f64;
                near.normal(t).dot(far.normal(t)).abs().min(1.0).acos()
            })
            .fold(0.0, f64::max)
            .to_degrees();
        let x = ((BEYOND_DROPPED_DEGREES - turn)
            / (BEYOND_DROPPED_DEGREES - BEYOND_TRUSTED_DEGREES))
            .clamp(0.0, 1.0);
        let w = x * x * (3.0 - 2.0 * x);
        if w == 0.0 {
            return Ok(Some(near));
        }
        // Same nodes as `near`; slopes moved towards those the nodes beyond give.
        let mut out = near;
        // The far field's signs follow its own first node; bring them to `out`'s.
        let sign = if far.normal(out.ts[0]).dot(out.normals[0]) < 0.0 {
            -1.0
        } else {
            1.0
        };
        for (t, slope) in out.ts.iter().zip(out.slopes.iter_mut()) {
            // Both fields run in the same keys (the same map), so their slopes compare.
            let i = far.ts.partition_point(|&x| x < *t).min(far.ts.len() - 1);
            *slope = *slope * (1.0 - w) + far.slopes[i] * (sign * w);
        }
        Ok(Some(out))
    }

    /// Build from given unit (or any non-zero) normals at curve parameters along `segment`,
    /// e.g. from a known surface. Zero normals are rejected.
    pub fn from_normals(
        segment: &SideSegment,
        nodes: &[(f64, DVec3)],
    ) -> Result<EdgeNormal, PatchError> {
        let mut pairs = Vec::with_capacity(nodes.len());
        for &(t, n) in nodes {
            check_node_t(segment, t)?;
            let Some(n) = n.is_finite().then(|| n.try_normalize()).flatten() else {
                return Err(PatchError::BadRibbonNode {
                    curve: segment_label(segment),
                    t,
                    reason: format!("normal {n} is zero or not finite"),
                });
            };
            pairs.push((t, n, None));
        }
        if pairs.is_empty() {
            return Err(PatchError::BadRibbonNode {
                curve: segment_label(segment),
                t: segment.t0,
                reason: "no normals given".to_string(),
            });
        }
        let (lo, hi, _) = node_range(segment);
        Ok(EdgeNormal::from_pairs(
            pairs,
            FieldKey::new(&segment.curve, lo, hi),
        ))
    }

    /// From node parameters, unit normals and (where known) the curve's unit tangents there,
    /// blended in the key `key` gives (in the parameter without one).
    fn from_pairs(
        mut pairs: Vec<(f64, DVec3, Option<DVec3>)>,
        key: Option<FieldKey>,
    ) -> EdgeNormal {
        pairs.sort_by(|(ta, _, _), (tb, _, _)| ta.total_cmp(tb));
        // Merge nodes at the same parameter; align signs along the curve.
        let mut ts: Vec<f64> = Vec::with_capacity(pairs.len());
        let mut normals: Vec<DVec3> = Vec::with_capacity(pairs.len());
        let mut last_tangent: Option<DVec3> = None;
        for (t, mut n, tangent) in pairs {
            if let Some(&prev) = normals.last() {
                if aligned_reference(prev, last_tangent, n, tangent).dot(n) < 0.0 {
                    n = -n;
                }
            }
            last_tangent = tangent.or(last_tangent);
            if ts.last() == Some(&t) {
                let last = normals.last_mut().expect("same length as ts");
                *last = (*last + n).try_normalize().unwrap_or(*last);
            } else {
                ts.push(t);
                normals.push(n);
            }
        }
        let keys: Vec<f64> = match &key {
            Some(a) => ts.iter().map(|&t| a.at(t)).collect(),
            None => ts.clone(),
        };
        let slopes = hermite_slopes(&keys, &normals);
        EdgeNormal {
            ts,
            keys,
            normals,
            slopes,
            key,
        }
    }

    /// Where the blend runs at curve parameter `t` (see [`EdgeNormal::keys`]).
    #[inline]
    fn key_at(&self, t: f64) -> f64 {
        match &self.key {
            Some(a) => a.at(t),
            None => t,
        }
    }

    /// The field held at `normal` (either sign: each node's own) over the parameter
    /// intervals `held` (sorted, disjoint): where the edge's curve runs in a plane the surface
    /// is tangent to (the hull's flat of side or bottom, at its greatest breadth or lowest
    /// point: a smooth surface touching such a plane along a curve is tangent to it there).
    /// The nodes inside an interval take the plane's normal, each interval's ends become
    /// nodes too, and all of those have zero slope, so the blend is exactly the plane's normal
    /// over the interval and joins the nodes outside it smoothly.
    pub(crate) fn held(&self, held: &[(f64, f64)], normal: DVec3) -> EdgeNormal {
        let Some(normal) = normal.try_normalize() else {
            return self.clone();
        };
        let inside = |t: f64| held.iter().any(|&(a, b)| a <= t && t <= b);
        let mut keys: Vec<(f64, f64, DVec3, DVec3)> = self
            .ts
            .iter()
            .zip(&self.keys)
            .zip(&self.normals)
            .zip(&self.slopes)
            .map(|(((&t, &k), &n), &d)| (t, k, n, d))
            .collect();
        for &(a, b) in held {
            for t in [a, b] {
                if !keys.iter().any(|k| k.0 == t) {
                    keys.push((t, self.key_at(t), self.normal(t), DVec3::ZERO));
                }
            }
        }
        keys.sort_by(|x, y| x.0.total_cmp(&y.0));
        for key in &mut keys {
            if inside(key.0) {
                key.2 = if key.2.dot(normal) < 0.0 {
                    -normal
                } else {
                    normal
                };
                key.3 = DVec3::ZERO;
            }
        }
        EdgeNormal {
            ts: keys.iter().map(|k| k.0).collect(),
            keys: keys.iter().map(|k| k.1).collect(),
            normals: keys.iter().map(|k| k.2).collect(),
            slopes: keys.iter().map(|k| k.3).collect(),
            key: self.key.clone(),
        }
    }

    /// The unit normal at curve parameter `t` (not yet made perpendicular to the curve): the
    /// node normals blended by a cubic Hermite with three-point slopes, in the field's key.
    #[inline]
    pub fn normal(&self, t: f64) -> DVec3 {
        hermite_unit(&self.keys, &self.normals, &self.slopes, self.key_at(t))
    }

    /// The node parameters.
    pub fn parameters(&self) -> &[f64] {
        &self.ts
    }
}

/// Node normals further apart than this (cosine, 60°) leave the sign of the next one to the
/// curve's turn between them: the previous normal turned with the tangent (by the least
/// rotation taking one tangent to the other) is the reference. Closer normals are their own
/// reference.
const TURNED_SIGN_COS: f64 = 0.5;

/// What node normal `n` (tangent `tangent`) takes its sign from after the node normal `prev`
/// (tangent `prev_tangent`): `prev` itself, or where the two are more than 60° apart and
/// both tangents are known, `prev` turned with the curve (a boss's section turns its normal
/// by 90° between two nodes, and the bare dot product would then pick either sign).
fn aligned_reference(
    prev: DVec3,
    prev_tangent: Option<DVec3>,
    n: DVec3,
    tangent: Option<DVec3>,
) -> DVec3 {
    let (Some(a), Some(b)) = (prev_tangent, tangent) else {
        return prev;
    };
    if prev.dot(n).abs() >= TURNED_SIGN_COS {
        return prev;
    }
    let axis = a.cross(b);
    let (sin, cos) = (axis.length(), a.dot(b));
    let Some(k) = axis.try_normalize() else {
        return prev;
    };
    // Rodrigues: `prev` turned about `k` by the angle from `a` to `b`.
    prev * cos + k.cross(prev) * sin + k * (k.dot(prev) * (1.0 - cos))
}

/// Three-point slopes of `values` at the parameters `ts`: at an inner node the chord slopes of
/// its two intervals weighted by the other interval's length (the derivative of the parabola
/// through the three nodes, so a quadratic is blended exactly), at most three times the
/// gentler of the two chords long; the chord slope at the end nodes; none for a single node
/// (two nodes: the Hermite blend is the straight one).
fn hermite_slopes(ts: &[f64], values: &[DVec3]) -> Vec<DVec3> {
    let k = ts.len();
    let chord = |i: usize| (values[i + 1] - values[i]) / (ts[i + 1] - ts[i]);
    (0..k)
        .map(|i| {
            if k == 1 {
                DVec3::ZERO
            } else if i == 0 {
                chord(0)
            } else if i == k - 1 {
                chord(k - 2)
            } else {
                let (h0, h1) = (ts[i] - ts[i - 1], ts[i + 1] - ts[i]);
                let (d0, d1) = (chord(i - 1), chord(i));
                let m = (d0 * h1 + d1 * h0) / (h0 + h1);
                // Fritsch–Carlson's bound, on the vectors: the slope at most three times the
                // gentler chord, so a short interval's steep chord never swings the long one.
                let cap = 3.0 * d0.length().min(d1.length());
                if m.length() > cap {
                    m * (cap / m.length())
                } else {
                    m
                }
            }
        })
        .collect()
}

/// The cubic Hermite blend of unit vectors `values` (with `slopes`) at `t`, normalised; the end
/// values are held outside the nodes.
#[inline]
fn hermite_unit(ts: &[f64], values: &[DVec3], slopes: &[DVec3], t: f64) -> DVec3 {
    let k = ts.len();
    if k == 1 || t.is_nan() || t <= ts[0] {
        return values[0];
    }
    if t >= ts[k - 1] {
        return values[k - 1];
    }
    let i = ts.partition_point(|&x| x <= t) - 1;
    let (t0, t1) = (ts[i], ts[i + 1]);
    let h = t1 - t0;
    let x = (t - t0) / h;
    let [h00, h10, h01, h11] = hermite_basis(x);
    let v =
        values[i] * h00 + slopes[i] * (h10 * h) + values[i + 1] * h01 + slopes[i + 1] * (h11 * h);
    // Aligned unit vectors never blend to zero unless opposite; fall back to the nearer.
    v.try_normalize()
        .unwrap_or(if x < 0.5 { values[i] } else { values[i + 1] })
}

fn segment_label(segment: &SideSegment) -> String {
    if segment.name.is_empty() {
        "<unnamed>".to_string()
    } else {
        segment.name.clone()
    }
}

/// The segment's parameter interval `(lo, hi)` in increasing order and how far past it a node
/// may round ([`NODE_PARAMETER_SLACK`]).
fn node_range(segment: &SideSegment) -> (f64, f64, f64) {
    let (lo, hi) = (segment.t0.min(segment.t1), segment.t0.max(segment.t1));
    (lo, hi, NODE_PARAMETER_SLACK * (hi - lo).abs().max(1.0))
}

fn check_node_t(segment: &SideSegment, t: f64) -> Result<(), PatchError> {
    let (lo, hi, slack) = node_range(segment);
    if !t.is_finite() || t < lo - slack || t > hi + slack {
        return Err(PatchError::BadRibbonNode {
            curve: segment_label(segment),
            t,
            reason: format!("parameter outside the segment [{lo}, {hi}]"),
        });
    }
    Ok(())
}

/// The ribbon specification of one face side: one optional [`EdgeNormal`] per segment
/// (`None`: that segment uses the face's default ribbon).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SideRibbon {
    /// Per segment of the side, in the side's segment order.
    pub segments: Vec<Option<EdgeNormal>>,
}

impl SideRibbon {
    /// The default ribbon for a side of `segments` segments.
    pub fn default_for(segments: usize) -> SideRibbon {
        SideRibbon {
            segments: vec![None; segments],
        }
    }

    /// A one-segment side with the given normal field.
    pub fn single(normal: EdgeNormal) -> SideRibbon {
        SideRibbon {
            segments: vec![Some(normal)],
        }
    }
}

/// A side ribbon ready for evaluation: oriented normal fields, default end normals and the
/// corner coefficients α, β.
#[derive(Clone, Debug)]
pub(crate) struct PreparedRibbon {
    /// Per segment: the edge normal field and the sign orienting it outwards for this face.
    normals: Vec<Option<(EdgeNormal, f64)>>,
    /// Default (outward) normals at the side's start and end corner.
    n0: DVec3,
    n1: DVec3,
    /// The face's overall normal, last fallback.
    face_normal: DVec3,
    alpha: [f64; 2],
    beta: [f64; 2],
    /// How the side turns, where the ribbon's frame is carried along it ([`Transport`]).
    transport: Option<Transport>,
    /// The ribbon's scale at [`WIDTH_SAMPLES`] + 1 even steps of `s`, with its Hermite slopes
    /// and its smallest value, where a side-blended patch's narrow face shortens it
    /// ([`width_scale`]); `None` where it is 1 throughout (always, for the corner-based
    /// patches).
    scale: Option<WidthScale>,
    /// Where the ribbon still steps at a corner inside its side, what spreads the step over
    /// the side beside it ([`side_mends`]); mostly none.
    mends: Vec<Mend>,
    /// Where it steps at a knuckle no curve follows, what spreads the step inside the face
    /// ([`Fan`]); mostly none.
    fans: Vec<Fan>,
}

/// A side's tangent turning by more than this at one point inside the side (a corner of its
/// curve, or a joint between two of its segments) is a [`Turn`]; the rest of its turning is
/// measured at [`TRANSPORT_SAMPLES`] + 1 even steps. A thousandth of a degree: a corner below
/// it steps the ribbon by less than 2e-5 of its length (a small step at a [`Turn`] is spread
/// along the side, [`side_mends`]); at 0.05° the smaller corners of KCS's bulb station at
/// x = 230 m still stepped its ribbon by up to 0.19 mm, a 0.05 mm crack in the patch beside
/// it.
const MIN_TURN_DEGREES: f64 = 0.001;

/// Even steps of `s` at which a side's smooth turn is measured ([`Transport`]): the steps at
/// which a side's segment keeps its curve's points for the faces along it.
const TRANSPORT_SAMPLES: usize = EVEN_SAMPLES;

/// The carried ribbon keeps at least this angle to the side's tangent, either way (unless the
/// blend of its corner angles already comes closer), so it always points into the face.
const MIN_RIBBON_ANGLE_DEGREES: f64 = 10.0;

/// A corner inside a side, where the side's tangent `ĉ` turns by `angle` in the tangent plane
/// at one point: a waterline curling round a forefoot in section data, a station with a
/// knuckle point that is no node, the joint of two segments of a composite side.
#[derive(Clone, Copy, Debug)]
struct Turn {
    /// Signed angle (radians) from the frame before the corner to the frame after it, about
    /// the surface normal there.
    angle: f64,
    /// The segment holding the corner, or before the joint.
    segment: usize,
    /// The curve parameter of a corner inside `segment`, and whether the segment runs with
    /// increasing parameter; `None` for the joint after `segment`.
    at: Option<(f64, bool)>,
    /// Where it is along the side (its side parameter).
    s: f64,
}

impl Turn {
    /// Whether a sample on segment `k` at curve parameter `t` (the side evaluator's own
    /// segment and parameter) is past the corner: on the side its tangent comes from.
    #[inline]
    fn past(&self, k: usize, t: f64) -> bool {
        k > self.segment
            || (k == self.segment
                && match self.at {
                    None => false,
                    // At the knot the side's evaluator takes the piece after it in t.
                    Some((tc, true)) => t >= tc,
                    Some((tc, false)) => t < tc,
                })
    }
}

/// How far a side's tangent has turned in its tangent plane from `s = 0`: its corners
/// ([`Turn`]) and, between them, its smooth turn (the integral of its geodesic curvature) at
/// even samples, and from the samples either side of `s` to `s` measured on the side's own
/// frame there.
///
/// The ribbon `R = αĉ + βT̂` blends its corner angles linearly in the frame `ĉ, T̂`, which
/// turns with the side's tangent. On a side that turns evenly (an arc) that is the natural
/// blend; but where the side turns unevenly (a waterline curling round a forefoot in 4 cm, a
/// side waving like an S), the frame carries the corners' ribbons round with it: a ribbon
/// leaving one corner nearly along the side still points nearly along the side where the
/// side has turned 90°, out of the face, and the patch folds. A corner in the side turns the
/// frame, and the ribbon with it, at one point. So the blend is made in a frame carried along
/// the side instead, turning by the side's mean rate `τ(1)·s`: the ribbon is turned in the
/// tangent plane by `τ(1)·s − τ(s)`. That is nothing at the face's corners (Gregory's corner
/// conditions hold), nothing anywhere on a side that turns evenly, continuous through corners
/// (the turn's jump cancels the frame's), and leaves the normal, and so G1 with the
/// neighbouring face, unchanged.
///
/// `τ(s)` is exact at every `s`, not only at the samples: the sampled turn up to a sample
/// beside `s`, then the turn from that sample's frame to the frame at `s` (from both samples
/// either side, blended, see [`Transport::turn`]). With the sampled turn alone interpolated
/// between the samples instead (a cubic Hermite, before), a wave of the side shorter than a step
/// was partly missing from `τ` while the frame `ĉ, T̂` still turned with it, so the ribbon
/// swung with the wave and the patch creased beside it: KVLCC2's wl_z5.00 steps 8 mm across
/// 3 cm where it crosses station 20 (its offsets' seam between bulb and hull, fitted within
/// 3.5 mm), and the face aft of the station creased along it (mesh faces at 40°).
#[derive(Clone, Debug)]
struct Transport {
    corners: Vec<Turn>,
    /// The side's frame at the samples.
    frames: Vec<SideSample>,
    /// The turn `τ` at the samples: the smooth turn and the corners before each.
    turned: Vec<f64>,
    /// The whole turn `τ(1)`, corners included.
    total: f64,
}

impl Transport {
    /// The side's turn `τ` at side parameter `s`, where its frame is `f`: measured from each
    /// of the two samples either side of `s` (the sampled turn up to it, then the turn from
    /// its frame to `f`) and blended between them by a smoothstep of `s`'s place in the step.
    /// The two measures differ slightly where the side's tangent plane turns along the step
    /// (the turn about the mean normal of two frames is not additive), so taking the nearest
    /// sample's alone jumped at every step's middle: the ribbon turned by 1.4e-4 rad at one
    /// point and the patch had a 66 µm crack there (KCS's face 75 beside wl_z9.00, which no
    /// B-spline export could follow). The smoothstep leaves `τ` and its slope continuous at
    /// the samples, and a side mirrored (run the other way) still gets the mirrored turn.
    #[inline]
    fn turn(&self, s: f64, f: SideSample) -> f64 {
        let n = self.turned.len() - 1;
        let x = s.clamp(0.0, 1.0) * n as f64;
        // `x` is not negative (or NaN, which casts to 0 either way): the cast is its floor,
        // without a call to libm's `floor` (not an instruction before SSE4.1).
        let j = (x as usize).min(n - 1);
        let from = |j: usize| self.turned[j] + turn_between(self.frames[j], f);
        let w = x - j as f64;
        if w <= 0.0 {
            return from(j);
        }
        if w >= 1.0 {
            return from(j + 1);
        }
        let w = w * w * (3.0 - 2.0 * w);
        (1.0 - w) * from(j) + w * from(j + 1)
    }

    /// How far the ribbon is turned at `s`, where the side's frame is `f` (see the type's
    /// docs).
    #[inline]
    fn angle(&self, s: f64, f: SideSample) -> f64 {
        self.total * s.clamp(0.0, 1.0) - self.turn(s, f)
    }
}

/// The signed angle by which the side's tangent turns from frame `a` to frame `b`, about their
/// mean normal `ĉ × T̂`.
fn turn_between(a: SideSample, b: SideSample) -> f64 {
    let normal = (a.c.cross(a.cross) + b.c.cross(b.cross)).normalize_or_zero();
    normal.dot(a.c.cross(b.c)).atan2(a.c.dot(b.c))
}

/// The [`Transport`] of one side, or `None` where its tangent does not turn in its tangent
/// plane (a straight side) or its frames are not finite.
fn side_transport(rib: &PreparedRibbon, side: &PreparedSide) -> Option<Transport> {
    let corners = side_corners(rib, side);
    let n = TRANSPORT_SAMPLES;
    let samples: Vec<(SideSample, usize, f64)> = (0..=n)
        .map(|j| {
            let s = j as f64 / n as f64;
            let (p, dp, k, t) = side.eval_located_even(j);
            (rib.frame_of(side, s, p, dp, k, t), k, t)
        })
        .collect();
    let mut values = vec![0.0; n + 1];
    for j in 0..n {
        let ((a, ka, ta), (b, kb, tb)) = (samples[j], samples[j + 1]);
        let mut d = turn_between(a, b);
        // A corner between the samples is counted as a corner, not smeared over the step.
        for c in corners.iter().filter(|c| !c.past(ka, ta) && c.past(kb, tb)) {
            d -= c.angle;
        }
        values[j + 1] = values[j] + d;
    }
    if !values.iter().all(|v| v.is_finite()) {
        return None;
    }
    let total = values[n] + corners.iter().map(|c| c.angle).sum::<f64>();
    let straight = values
        .iter()
        .all(|v| v.abs() <= MIN_TURN_DEGREES.to_radians() * 1e-3);
    if straight && corners.is_empty() {
        return None;
    }
    let turned = samples
        .iter()
        .zip(&values)
        .map(|(&(_, k, t), v)| {
            let before: f64 = corners
                .iter()
                .filter(|c| c.past(k, t))
                .map(|c| c.angle)
                .sum();
            v + before
        })
        .collect();
    Some(Transport {
        corners,
        frames: samples.into_iter().map(|(f, _, _)| f).collect(),
        turned,
        total,
    })
}

/// How far a ribbon's step at a corner inside its side is spread along the side, either way
/// (a share of the side's parameter; less where another corner or the side's end is nearer
/// than twice that).
const MEND_SPREAD: f64 = 1.0 / 32.0;

/// The largest step (a share of the ribbon's length) [`side_mends`] spreads along the side:
/// spread, a step tilts the ribbon out of its tangent plane by up to half its angle there,
/// and the faces either side of the curve meet with their normals that far apart; a step of
/// twice [`MEND_G1_DEGREES`] (in radians, 1.745e-3) keeps that within it. A larger step
/// cannot be spread so and stay G1: it is a corner where the hull has a knuckle the network
/// has no curve for, and is left.
const MEND_MOST: f64 = 2.0 * MEND_G1_DEGREES * std::f64::consts::PI / 180.0;

/// The normal jump (degrees) that spreading a step along the side ([`MEND_MOST`]) may leave
/// between the faces either side of the curve: the G1 the real ships are built to.
const MEND_G1_DEGREES: f64 = 0.05;

/// The ribbon's step at one corner inside its side (a [`Turn`]) and how far it is spread
/// ([`side_mends`]).
#[derive(Clone, Copy, Debug)]
struct Mend {
    /// The corner's side parameter.
    at: f64,
    /// The ribbon just before the corner less the ribbon just after it.
    step: DVec3,
    /// How far before and after the corner (side parameter) the step is spread.
    before: f64,
    after: f64,
    /// Whether the side, evaluated at the corner itself, takes the piece before it (at a joint
    /// of two segments, the first one's end): the corner then gets the half taken away.
    at_before: bool,
}

impl Mend {
    /// What the ribbon gains at `s` from this step spread over `before` and `after` of the side
    /// either side of its corner: `share_after` of the step added after the corner and the rest
    /// taken away before it (at the corner itself, on the side of it the side evaluates there),
    /// each share fading to nothing by `fade` across its half of the window.
    #[inline]
    fn spread(
        &self,
        s: f64,
        (before, after): (f64, f64),
        share_after: f64,
        fade: impl Fn(f64) -> f64,
    ) -> DVec3 {
        if (s > self.at || (s == self.at && !self.at_before)) && s < self.at + after {
            self.step * (share_after * fade((s - self.at) / after))
        } else if s <= self.at && s > self.at - before {
            -self.step * ((1.0 - share_after) * fade((self.at - s) / before))
        } else {
            DVec3::ZERO
        }
    }
}

/// What the ribbon gains at `s` from `mends`: half of each step added after its corner and
/// half taken away before it ([`Mend::spread`]), each half fading to nothing by a smoothstep
/// over its spread, so that the ribbon runs on continuously through the corner, and is the
/// middle of its two sides at it.
#[inline]
fn mended(mends: &[Mend], s: f64) -> DVec3 {
    let fade = |x: f64| 1.0 - x * x * (3.0 - 2.0 * x);
    mends
        .iter()
        .map(|m| m.spread(s, (m.before, m.after), 0.5, fade))
        .sum()
}

/// The steps a side's ribbon still takes at the corners inside its side, and their spreads.
///
/// The carried frame turns the ribbon through a corner by the corner's angle about the
/// surface normal ([`Transport`]), which leaves it continuous where the side's two tangents
/// lie in the tangent plane the edge's normal field gives there. Where they do not, the
/// frames either side of the corner lie in different planes, no turn within one of them joins
/// them, and the ribbon steps: the patch beside it cracks along the line from the corner. A
/// small step (up to [`MEND_MOST`] of the ribbon's length: the joints and slight corners of
/// fitted section curves, KCS's bulb station at x = 230 m, whose steps of up to 0.19 mm
/// cracked its patch by 0.05 mm) is spread along the side beside the corner ([`mended`]):
/// the ribbon is continuous, leaves its tangent plane by at most half the step's angle near
/// the corner, and is unchanged elsewhere and at the face's corners. A larger step is a
/// corner where the hull has a knuckle the network has no curve for (KCS's bulb: a 67°
/// corner where wl_z0.30 turns into the stem, 1.1 cm on a 1.7 m ribbon): spreading it along
/// the side would tilt the ribbon, and the surface normal beside the neighbouring face, by
/// degrees, so it is left on the side and spread inside the face instead ([`Fan`]).
///
/// Each knuckle is reported as a [`PatchWarning::KnuckleInSide`] of side `index`. Returns the
/// mends and the fans.
fn side_mends(
    rib: &PreparedRibbon,
    side: &PreparedSide,
    index: usize,
    warnings: &mut Vec<PatchWarning>,
) -> (Vec<Mend>, Vec<Fan>) {
    let Some(transport) = &rib.transport else {
        return (Vec::new(), Vec::new());
    };
    let mut at: Vec<f64> = transport
        .corners
        .iter()
        .map(|c| c.s)
        .filter(|s| *s > 0.0 && *s < 1.0)
        .collect();
    at.sort_by(f64::total_cmp);
    at.dedup();
    // Either side of the corner, close enough that the ribbon's own change is rounding.
    let h = 1e-9;
    let mut out = Vec::with_capacity(at.len());
    let mut fans = Vec::new();
    for (j, &s) in at.iter().enumerate() {
        let prev = if j == 0 { 0.0 } else { 0.5 * (s + at[j - 1]) };
        let next = at.get(j + 1).map_or(1.0, |n| 0.5 * (s + n));
        let (before, after) = ((s - prev).min(MEND_SPREAD), (next - s).min(MEND_SPREAD));
        if before <= h || after <= h {
            continue;
        }
        let (below, above) = (rib.eval(side, s - h).1, rib.eval(side, s + h).1);
        let step = below - above;
        if !step.is_finite() || step.length() == 0.0 {
            continue;
        }
        let itself = rib.eval(side, s).1;
        let at_before = (itself - below).length() < (itself - above).length();
        let r = above.length();
        if step.length() > MEND_MOST * r {
            warnings.push(PatchWarning::KnuckleInSide {
                side: index,
                at: side.point(s).to_array(),
                step: step.length(),
                share: step.length() / r.max(below.length()),
            });
            fans.push(Fan {
                at: s,
                step,
                before: s - prev,
                after: next - s,
                at_before,
            });
            continue;
        }
        out.push(Mend {
            at: s,
            step,
            before,
            after,
            at_before,
        });
    }
    (out, fans)
}

/// How fast a [`Fan`] opens with the distance from its side: its half-widths along the side
/// are `tanh(FAN_OPENING · √h)` of their room, `h` the domain distance from the side (0 on it,
/// 1 across the face). Opening as `√h`, the fan is already wide close to the side, so the
/// step it spreads, `h` times the ribbon's, slopes along the side by a share growing as `√h`
/// only: nothing at the side, where the face meets its neighbour. At 2 the fan has nearly
/// all its room (96 %) across the face.
const FAN_OPENING: f64 = 2.0;

/// A ribbon step at a knuckle inside a side (a corner where the hull has a knuckle no curve of
/// the network follows, larger than [`MEND_MOST`]) spread inside the face, where the patch
/// would otherwise crack along the line from the corner (it extrapolates the side by `h·R`,
/// `h` the distance from the side, so a step of `R` is a step of the surface growing with
/// `h`: KCS's bulb, 3 mm where wl_z0.30 turns into the stem).
///
/// At distance `h` from the side the step is spread over a window of the side around the
/// corner whose half-widths grow from 0 on the side ([`FAN_OPENING`]) to nearly the room
/// there is (half way to the next corner of the side, or the side's end): the ribbon is taken
/// the step back before the corner and forward after it, each share fading by a smootherstep
/// (no jump in the surface's curvature at the window's edges, along which a B-spline export
/// would otherwise have to refine) across its half of the window, the shares in proportion to
/// the half-widths so that both halves slope alike. On the side itself the ribbon is the
/// side's own, so the face meets its neighbour as before (G1 everywhere on the side except the
/// corner point); inside the face the surface is continuous, a knuckle fading out from the
/// corner into the face as a cone does from its apex, and the window never reaches the side's
/// ends, where the other sides' interpolants hold.
///
/// A fan is held as a [`Mend`] whose `before` and `after` are the whole room either side.
type Fan = Mend;

/// What the ribbon gains at `s`, at domain distance `h` from its side, from `fans` ([`Fan`]):
/// nothing on the side (`h ≤ 0`) and outside each window.
#[inline]
fn fanned(fans: &[Fan], s: f64, h: f64) -> DVec3 {
    if h <= 0.0 {
        return DVec3::ZERO;
    }
    let open = (FAN_OPENING * h.sqrt()).tanh();
    // Perlin's smootherstep, whose first and second derivatives vanish at both ends.
    let fade = |x: f64| 1.0 - x * x * x * (10.0 + x * (6.0 * x - 15.0));
    fans.iter()
        .filter_map(|f| {
            let (before, after) = (f.before * open, f.after * open);
            // Shares in proportion to the half-widths: the step taken after is after's share.
            (before > 0.0 && after > 0.0)
                .then(|| f.spread(s, (before, after), after / (before + after), fade))
        })
        .sum()
}

/// The [`Turn`]s of one side: its curves' corners inside its segments and its joints between
/// segments where the ribbon's frame turns by more than [`MIN_TURN_DEGREES`].
fn side_corners(rib: &PreparedRibbon, side: &PreparedSide) -> Vec<Turn> {
    let min = MIN_TURN_DEGREES.to_radians();
    let mut out = Vec::new();
    let m = side.segs.len();
    // One-sided d/ds of segment `k` at curve parameter `t`, from the piece after `t` in t or
    // the one before it.
    let one_sided = |k: usize, t: f64, after_in_t: bool| -> DVec3 {
        let seg = &side.segs[k];
        let du = side.breaks[k + 1] - side.breaks[k];
        let d1 = seg
            .fast()
            .derivs_in(seg.fast().piece_at(t, after_in_t), t)
            .d1;
        (d1 * seg.parameter_slope(t, after_in_t) + (seg.d1 - seg.d0)) / du
    };
    let mut push = |before: SideSample, after: SideSample, segment, at, s| {
        let angle = turn_between(before, after);
        if angle.abs() > min && angle.is_finite() {
            out.push(Turn {
                angle,
                segment,
                at,
                s,
            });
        }
    };
    for (k, seg) in side.segs.iter().enumerate() {
        let up = seg.tb >= seg.ta;
        let (lo, hi) = (seg.ta.min(seg.tb), seg.ta.max(seg.tb));
        let du = side.breaks[k + 1] - side.breaks[k];
        for tc in seg.curve().corner_parameters(min) {
            if tc <= lo || tc >= hi {
                continue;
            }
            let lam = seg.fraction(tc);
            let s = side.breaks[k] + du * lam;
            let p = seg.fast().point(tc) + seg.d0 * (1.0 - lam) + seg.d1 * lam;
            let frame = |after_in_t| rib.frame_of(side, s, p, one_sided(k, tc, after_in_t), k, tc);
            let (before, after) = (frame(!up), frame(up));
            push(before, after, k, Some((tc, up)), s);
        }
        if k + 1 < m {
            let next = &side.segs[k + 1];
            let s = side.breaks[k + 1];
            let p = side.point(s);
            let before = rib.frame_of(side, s, p, one_sided(k, seg.tb, !up), k, seg.tb);
            let next_up = next.tb >= next.ta;
            let dp = one_sided(k + 1, next.ta, next_up);
            let after = rib.frame_of(side, s, p, dp, k + 1, next.ta);
            push(before, after, k, None, s);
        }
    }
    out
}

/// Position, unit tangent and unit inward cross tangent of a side at `s`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SideSample {
    pub(crate) p: DVec3,
    pub(crate) c: DVec3,
    pub(crate) cross: DVec3,
}

impl PreparedRibbon {
    #[inline]
    fn default_normal(&self, s: f64) -> DVec3 {
        (self.n0 * (1.0 - s) + self.n1 * s)
            .try_normalize()
            .unwrap_or(self.face_normal)
    }

    /// The side's frame at `s`: point, unit tangent and unit inward cross tangent.
    #[inline]
    pub(crate) fn frame(&self, side: &PreparedSide, s: f64) -> SideSample {
        let (p, dp, k, t) = side.eval_located(s);
        self.frame_of(side, s, p, dp, k, t)
    }

    /// The frame at `s` from the side's point `p` and derivative `dp` there, on segment `k`
    /// at curve parameter `t` (`dp` one-sided where the side has a corner).
    #[inline]
    fn frame_of(
        &self,
        side: &PreparedSide,
        s: f64,
        p: DVec3,
        dp: DVec3,
        k: usize,
        t: f64,
    ) -> SideSample {
        // A zero derivative (coincident control points) has no direction: use the chord.
        let c = dp
            .try_normalize()
            .unwrap_or_else(|| (side.end - side.start()).normalize_or(DVec3::X));
        let n = match &self.normals[k] {
            Some((en, sign)) => en.normal(t) * *sign,
            None => self.default_normal(s),
        };
        let cross = in_plane_cross(n, c)
            .or_else(|| in_plane_cross(self.default_normal(s), c))
            .or_else(|| in_plane_cross(self.face_normal, c))
            .unwrap_or_else(|| c.any_orthonormal_vector());
        SideSample { p, c, cross }
    }

    /// Position and ribbon vector `R(s) = α(s)ĉ + β(s)T̂` at `s`, turned in the tangent
    /// plane into the frame carried along the side ([`Transport`]).
    #[inline]
    pub(crate) fn eval(&self, side: &PreparedSide, s: f64) -> (DVec3, DVec3) {
        let (p, _, r) = self.eval_along(side, s);
        (p, r)
    }

    /// [`PreparedRibbon::eval`]'s position and ribbon at `s` with the side's derivative d/ds
    /// there (the one the ribbon's frame is made from: one-sided at a corner of the side).
    #[inline]
    pub(crate) fn eval_along(&self, side: &PreparedSide, s: f64) -> (DVec3, DVec3, DVec3) {
        let (p, dp, k, t) = side.eval_located(s);
        let f = self.frame_of(side, s, p, dp, k, t);
        let s = s.clamp(0.0, 1.0);
        let a = self.alpha[0] + (self.alpha[1] - self.alpha[0]) * s;
        let b = self.beta[0] + (self.beta[1] - self.beta[0]) * s;
        let r = f.c * a + f.cross * b;
        let r = match &self.transport {
            None => r,
            Some(tr) => {
                // Turned by the carried frame's angle, kept pointing into the face.
                let psi = b.atan2(a);
                let min = MIN_RIBBON_ANGLE_DEGREES.to_radians();
                let (lo, hi) = (psi.min(min), psi.max(std::f64::consts::PI - min));
                let phi = (psi + tr.angle(s, f)).clamp(lo, hi) - psi;
                // R ⊥ n̂ = ĉ × T̂: Rodrigues' rotation about n̂ in the tangent plane.
                let axis = f.c.cross(f.cross);
                let (sin, cos) = phi.sin_cos();
                r * cos + axis.cross(r) * sin
            }
        };
        let r = match &self.scale {
            None => r,
            Some(w) => r * w.at(s),
        };
        (f.p, dp, r + mended(&self.mends, s))
    }

    /// The ribbon at `s` as the patch extrapolates it at domain distance `h` from the side:
    /// [`PreparedRibbon::eval`]'s ribbon with its knuckles' steps spread inside the face
    /// ([`Fan`]); the same on the side (`h = 0`) and wherever the side has no knuckle.
    #[inline]
    pub(crate) fn inside(&self, r: DVec3, s: f64, h: f64) -> DVec3 {
        if self.fans.is_empty() {
            r
        } else {
            r + fanned(&self.fans, s.clamp(0.0, 1.0), h)
        }
    }

    /// Whether the ribbon has knuckles spread inside the face ([`Fan`]).
    #[inline]
    pub(crate) fn has_fans(&self) -> bool {
        !self.fans.is_empty()
    }

    /// |R(s)| before any width scale: the corner magnitudes' linear blend.
    fn linear_length(&self, s: f64) -> f64 {
        let a = self.alpha[0] + (self.alpha[1] - self.alpha[0]) * s;
        let b = self.beta[0] + (self.beta[1] - self.beta[0]) * s;
        a.hypot(b)
    }
}

/// A ribbon's scale along its side ([`PreparedRibbon::scale`]).
#[derive(Clone, Debug)]
struct WidthScale {
    values: Vec<f64>,
    slopes: Vec<f64>,
    least: f64,
}

impl WidthScale {
    /// The Hermite blend of the samples at `s`, kept within their range (never 0 or less:
    /// the ribbon keeps its direction).
    #[inline]
    fn at(&self, s: f64) -> f64 {
        hermite_scalar(&self.values, &self.slopes, s).clamp(self.least, 1.0)
    }
}

/// Samples along each side at which a face's width is measured for [`width_scale`].
const WIDTH_SAMPLES: usize = 16;

/// Samples per side of the boundary whose distances give the width.
const WIDTH_BOUNDARY_SAMPLES: usize = 32;

/// A ribbon may reach this many times the face's width across from its side before it is
/// shortened ([`width_scale`]).
pub(crate) const RIBBON_WIDTH_RATIO: f64 = 1.0;

/// How much a ribbon of linear length `length` is shortened where the face is `width` wide,
/// for a side-blended patch ([`crate::PatchKind::SideBlend`]): 1 while
/// `length ≤ RIBBON_WIDTH_RATIO·width`; `RIBBON_WIDTH_RATIO·width / length` once the ribbon
/// is three times that long, so it then reaches the face's width; a C¹ cubic between.
///
/// The corner magnitudes (the neighbouring sides' derivatives, which the Gregory and
/// Charrot–Gregory corner interpolants need) are blended linearly along a side (module docs).
/// Where a boundary curve hooks into a corner of a narrow face (a waterline turning into the
/// keel), that blend reaches ten widths across the face, and a patch extrapolating its sides
/// by it crosses its own boundary. A side-blended patch needs no corner conditions, so its
/// ribbons are cut to the width. Scaling a ribbon keeps its direction, so the tangent plane
/// along the edge, and with it G1, is unchanged.
fn width_scale(length: f64, width: f64) -> f64 {
    let (lo, hi) = (1.0 / 3.0, 1.0);
    let r = RIBBON_WIDTH_RATIO * width / length;
    if r.is_nan() || r >= hi {
        1.0
    } else if r <= lo {
        r.max(0.0)
    } else {
        // Hermite from (lo, lo, slope 1) to (hi, 1, slope 0).
        let h = hi - lo;
        let [h00, h10, h01, _] = hermite_basis((r - lo) / h);
        h00 * lo + h10 * h + h01
    }
}

/// The ribbon scales of side `i` of a face (see [`width_scale`]). The face's width at a side
/// point is how far the ray from it along the ribbon runs before it meets the rest of the
/// boundary, all projected on the tangent plane there (no meeting: no limit). Along the ribbon
/// itself, its part along the side included: near a corner whose neighbouring side leaves
/// nearly along this one, the ribbon runs nearly along the side too, and the face is narrow
/// that way however wide it is across.
fn side_scales(sides: &[PreparedSide], i: usize, rib: &PreparedRibbon) -> Option<WidthScale> {
    let n = sides.len();
    // The rest of the boundary as one polyline, from the end of side i round to its start.
    let others: Vec<DVec3> = (1..n)
        .map(|k| &sides[(i + k) % n])
        .flat_map(|side| {
            (0..=WIDTH_BOUNDARY_SAMPLES)
                .map(|j| side.point(j as f64 / WIDTH_BOUNDARY_SAMPLES as f64))
        })
        .collect();
    let mut any = false;
    let values: Vec<f64> = (0..=WIDTH_SAMPLES)
        .map(|j| {
            let s = j as f64 / WIDTH_SAMPLES as f64;
            let f = rib.frame(&sides[i], s);
            // The ray along the ribbon itself (its tangential part included), in the plane.
            let r = rib.eval(&sides[i], s).1;
            let u = DVec2::new(r.dot(f.c), r.dot(f.cross))
                .try_normalize()
                .unwrap_or(DVec2::Y);
            let flat = |q: DVec3| {
                let a = DVec2::new((q - f.p).dot(f.c), (q - f.p).dot(f.cross));
                DVec2::new(a.x * u.y - a.y * u.x, a.x * u.x + a.y * u.y)
            };
            let mut width = f64::INFINITY;
            for w in others.windows(2) {
                let (a, b) = (flat(w[0]), flat(w[1]));
                if (a.x <= 0.0) != (b.x <= 0.0) {
                    let y = a.y + (b.y - a.y) * (a.x / (a.x - b.x));
                    if y > 0.0 {
                        width = width.min(y);
                    }
                }
            }
            let v = width_scale(rib.linear_length(s), width);
            let v = if v.is_finite() && v > 0.0 { v } else { 1.0 };
            any |= v < 1.0;
            v
        })
        .collect();
    if !any {
        return None;
    }
    let slopes = hermite_slopes_even(&values);
    let least = values.iter().copied().fold(1.0, f64::min);
    Some(WidthScale {
        values,
        slopes,
        least,
    })
}

/// [`hermite_slopes`] of scalars at even steps of `[0, 1]` (as [`hermite_scalar`] blends them).
fn hermite_slopes_even(values: &[f64]) -> Vec<f64> {
    let m = values.len() - 1;
    let ts: Vec<f64> = (0..=m).map(|j| j as f64 / m as f64).collect();
    let v: Vec<DVec3> = values.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect();
    hermite_slopes(&ts, &v).into_iter().map(|d| d.x).collect()
}

/// The cubic Hermite blend at `s ∈ [0, 1]` of `values` at even steps with `slopes`.
#[inline]
fn hermite_scalar(values: &[f64], slopes: &[f64], s: f64) -> f64 {
    let m = values.len() - 1;
    let x = s.clamp(0.0, 1.0) * m as f64;
    // Not negative: the cast is the floor (see `Transport::turn`).
    let i = (x as usize).min(m - 1);
    let h = 1.0 / m as f64;
    let [h00, h10, h01, h11] = hermite_basis(x - i as f64);
    h00 * values[i] + h10 * h * slopes[i] + h01 * values[i + 1] + h11 * h * slopes[i + 1]
}

/// `T̂ = n̂⊥ × ĉ`: the unit vector perpendicular to `c` in the plane perpendicular to `n`
/// (Gram–Schmidt of `n` against `c` first), or `None` when `n` is (nearly) parallel to `c`.
#[inline]
fn in_plane_cross(n: DVec3, c: DVec3) -> Option<DVec3> {
    let m = n - c * n.dot(c);
    let l = m.length();
    (l > PARALLEL).then(|| (m / l).cross(c))
}

/// A side's derivatives d/ds at its two ends (s = 0 and s = 1).
#[derive(Clone, Copy, Debug)]
struct SideEnds {
    start: DVec3,
    end: DVec3,
}

/// Build the prepared ribbons of a face from its prepared sides and ribbon specifications;
/// `width_limited` (for a side-blended patch) cuts each to the face's width ([`width_scale`]).
pub(crate) fn prepare_ribbons(
    sides: &[PreparedSide],
    specs: &[SideRibbon],
    width_limited: bool,
    warnings: &mut Vec<PatchWarning>,
) -> Vec<PreparedRibbon> {
    let n = sides.len();
    let ends: Vec<SideEnds> = sides
        .iter()
        .map(|s| {
            let ((_, start), (_, end)) = (s.eval(0.0), s.eval(1.0));
            SideEnds { start, end }
        })
        .collect();
    // Newell normal of the boundary polygon: the face's overall orientation, used only where
    // local information is degenerate.
    let mut poly = Vec::with_capacity(NEWELL_SAMPLES_PER_SIDE * n);
    for s in sides {
        for j in 0..NEWELL_SAMPLES_PER_SIDE {
            poly.push(s.point(j as f64 / NEWELL_SAMPLES_PER_SIDE as f64));
        }
    }
    let mut newell = DVec3::ZERO;
    for (i, a) in poly.iter().enumerate() {
        newell += a.cross(poly[(i + 1) % poly.len()]);
    }
    let face_normal = newell.try_normalize().unwrap_or(DVec3::Z);

    let unit = |v: DVec3| v.try_normalize();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let (prev, next) = ((i + n - 1) % n, (i + 1) % n);
        let SideEnds {
            start: d_start,
            end: d_end,
        } = ends[i];
        // Tangents of the neighbouring sides leaving the two corners, into the face.
        let a0 = -ends[prev].end;
        let a1 = ends[next].start;
        let c0 = unit(d_start).unwrap_or(DVec3::X);
        let c1 = unit(d_end).unwrap_or(c0);
        let corner_normal = |c: DVec3, a: DVec3| -> DVec3 {
            let x = c.cross(a);
            if x.length() > PARALLEL * a.length().max(f64::MIN_POSITIVE) && x.length() > 0.0 {
                x.normalize()
            } else {
                let m = face_normal - c * face_normal.dot(c);
                m.try_normalize().unwrap_or(face_normal)
            }
        };
        let n0 = corner_normal(c0, a0);
        let n1 = corner_normal(c1, a1);
        let mut rib = PreparedRibbon {
            normals: Vec::new(),
            n0,
            n1,
            face_normal,
            alpha: [0.0; 2],
            beta: [0.0; 2],
            transport: None,
            scale: None,
            mends: Vec::new(),
            fans: Vec::new(),
        };
        let side = &sides[i];
        let spec = specs.get(i);
        rib.normals = (0..side.segs.len())
            .map(|k| {
                let en = spec
                    .and_then(|sp| sp.segments.get(k))
                    .and_then(|e| e.clone())?;
                // Orient outwards: agree with the default normal at the segment's middle.
                let seg = &side.segs[k];
                let tm = seg.parameter(0.5).0;
                let sm = 0.5 * (side.breaks[k] + side.breaks[k + 1]);
                let dot = en.normal(tm).dot(rib.default_normal(sm));
                let dot = if dot.abs() > PARALLEL {
                    dot
                } else {
                    en.normal(tm).dot(face_normal)
                };
                Some((en, if dot < 0.0 { -1.0 } else { 1.0 }))
            })
            .collect();
        rib.transport = side_transport(&rib, side);
        // Corner coefficients: R(0) = a0 and R(1) = a1, projected into the tangent plane.
        for (end, (s, a, corner)) in [(0.0, a0, i), (1.0, a1, next)].into_iter().enumerate() {
            let f = rib.frame(side, s);
            let normal = f.c.cross(f.cross);
            let ap = a - normal * a.dot(normal);
            let mut mag = ap.length();
            if mag.is_nan() || mag <= 0.0 {
                mag = a.length();
            }
            if mag.is_nan() || mag <= 0.0 {
                // The neighbouring side has a zero derivative at the corner: use its chord.
                let other = if end == 0 { &sides[prev] } else { &sides[next] };
                mag = (other.end - other.start()).length();
            }
            let mut phi = ap.dot(f.cross).atan2(ap.dot(f.c));
            let lo = MIN_CORNER_ANGLE_DEGREES.to_radians();
            let hi = std::f64::consts::PI - lo;
            if !(phi >= lo && phi <= hi) {
                let used = if phi.is_nan() || phi.abs() < std::f64::consts::FRAC_PI_2 {
                    lo
                } else {
                    hi
                };
                // The corner's interior angle is φ at the start corner and 180° − φ at the end.
                let interior = |x: f64| {
                    if end == 0 {
                        x.to_degrees()
                    } else {
                        180.0 - x.to_degrees()
                    }
                };
                warnings.push(PatchWarning::CornerAngle {
                    corner,
                    degrees: if phi.is_nan() { 0.0 } else { interior(phi) },
                    used_degrees: interior(used),
                });
                phi = used;
            }
            // At the end corner the ribbon's own tangent component is measured along the side's
            // direction at s = 1, same as at the start: R = α ĉ + β T̂ in both cases.
            rib.alpha[end] = mag * phi.cos();
            rib.beta[end] = mag * phi.sin();
        }
        if width_limited {
            rib.scale = side_scales(sides, i, &rib);
        }
        (rib.mends, rib.fans) = side_mends(&rib, side, i, warnings);
        out.push(rib);
    }
    out
}

#[cfg(test)]
mod same_bits_tests {
    use super::*;

    fn field(n: f64) -> EdgeNormal {
        EdgeNormal {
            ts: vec![0.0, 1.0],
            keys: vec![0.0, 1.0],
            normals: vec![DVec3::new(n, 0.0, 1.0), DVec3::Z],
            slopes: vec![DVec3::ZERO, DVec3::ZERO],
            key: None,
        }
    }

    #[test]
    fn same_bits_tells_minus_zero_from_zero_and_takes_a_nan_as_itself() {
        assert!(field(0.5).same_bits(&field(0.5)), "equal");
        assert!(!field(0.5).same_bits(&field(0.5 + 1e-16)), "one ulp apart");
        assert!(field(0.0) == field(-0.0), "== takes -0 for 0");
        assert!(!field(0.0).same_bits(&field(-0.0)), "the bits differ");
        assert!(field(f64::NAN) != field(f64::NAN), "== refuses NaN");
        assert!(
            field(f64::NAN).same_bits(&field(f64::NAN)),
            "the same NaN bits"
        );
    }
}

#[cfg(test)]
mod edge_normal_tests {
    use super::*;
    use crate::patch::field_key::tests::{crowded_line, t_at};

    #[test]
    fn an_edge_normal_does_not_turn_where_its_curves_parameter_crowds() {
        let c = crowded_line();
        let (lo, hi) = c.domain();
        let seg = SideSegment::new(c.clone(), lo, hi);
        let tilt = 40f64.to_radians();
        let n1 = DVec3::new(0.0, -tilt.sin(), tilt.cos());
        let field = EdgeNormal::from_normals(&seg, &[(lo, DVec3::Z), (hi, n1)]).unwrap();
        let at = |x: f64| field.normal(t_at(&c, x));
        let across = at(2.98).angle_between(at(3.06)).to_degrees();
        // 0.38 of the parameter, 8 cm of 6 m: blended in the parameter it turned 15°
        // (measured 3.3° now).
        assert!(
            across < 4.0,
            "the field turns {across}° across the crowded 8 cm"
        );
        assert!(
            (at(6.0).angle_between(n1)).to_degrees() < 1e-9,
            "and reaches its end node"
        );
    }
}
