//! The transformation of a curve network through its form topology (Bole, seed 002, §7.2), in
//! the paper's order: 1. translate the selected vertices; 2. move the planes they lie in;
//! 3. distribute the translation breadth first with the three edge rules, each vertex kept on
//! its planes; 4. move the free control points of every form edge (Fig. 6); 5. move the
//! control points of the curves inside each form face by the change of a Gregory surface over
//! the face (§7.2.3); 6. re-attach the curves at their nodes, in hierarchy order (form curves
//! first); then check every connection (§7.2.4) and refuse the result if one was lost.
//!
//! Choices the paper leaves open, made so that a transformation and its inverse cancel:
//! - Fig. 6's distance `t` of a free control point between the edge's ends is its Greville
//!   abscissa, normalised over the edge (the chord parameter of the curve), which no move
//!   changes; on a straight edge it is the point's position along the chord.
//! - A blend (the bilge arc) is mapped by the affine map taking its end points and the meeting
//!   point of its end tangents to their new places: an arc between lines stays an arc.
//! - A face point moves by the surface's change at the foot of the midpoint of its old and
//!   new place on the mean of the two surfaces (the paper's projection, made symmetric): the
//!   reverse change moves it back. A free curve lying in an axis plane (a station) keeps
//!   lying in a parallel plane (§5's surface attribute), its ends sliding along the curves
//!   they end on.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::error::FormError;
use super::identify::{EdgeKind, FormEdge, FormTopology};
use super::measure::line_meeting;
use super::planes::{constrain, curve_planes};
use crate::curve::NurbsCurve;
use crate::hull::edge_curve;
use crate::network::{Network, NetworkCurve};
use crate::patch::{
    central_differences, stencil_fits, Domain, FaceBoundary, Patch, PatchOptions, Side, SideSegment,
};
use crate::tolerance::Tolerance;

/// A translation of one form vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexMove {
    /// The vertex (index into [`FormTopology::vertices`]).
    pub vertex: usize,
    /// Its translation.
    pub translation: DVec3,
}

/// The transformed network and what the transformation did.
#[derive(Clone, Debug, PartialEq)]
pub struct Transformed {
    /// The new network (same curves, names and roles).
    pub network: Network,
    /// The translation each form vertex received.
    pub vertex_translations: Vec<DVec3>,
    /// The curves re-attached at their nodes afterwards (step 6).
    pub reattached: Vec<String>,
    /// The largest control-point move by steps 4–5 (before re-attachment, which may insert
    /// knots).
    pub max_move: f64,
}

/// Domain grid per axis for the first guess of a point's foot on a face surface.
const FOOT_GRID: usize = 24;
/// Gauss–Newton steps for a foot point (quadratic convergence: far more than needed).
const FOOT_STEPS: usize = 30;
/// A foot step shorter than this (domain units) has converged: far below what moves a point
/// by 1e-12 m on a hull-sized face.
const FOOT_CONVERGED: f64 = 1e-13;
/// Foot steps shorter than this (domain units) that no longer halve are the noise of the
/// finite-difference derivatives ([`Patch::derivatives`]: 1e-6 relative), not convergence.
const FOOT_NOISE: f64 = 1e-9;
/// A node whose curves lie farther apart than this fraction of the tolerance is re-attached.
const REATTACH_FRACTION: f64 = 0.25;

/// A bulge of one form face (seed 002 §8.2): the curves inside the face move along the
/// face's surface normal, outward by `amount` (m) at the middle of the face and by nothing at
/// its edges (inward, flattening the face, for a negative amount); the form curves stay.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceBulge {
    /// The face (index into [`FormTopology::faces`]).
    pub face: usize,
    /// The offset at the middle of the face (m), outward from the hull.
    pub amount: f64,
}

/// Transform `network` by moving form vertices (Bole, seed 002, §7.2; see the module docs).
///
/// Errors: a move of a vertex that does not exist or is not finite ([`FormError::BadMove`]), a
/// result in which curves no longer meet as they did ([`FormError::ConnectionLost`], naming
/// them), a face whose surface cannot be built (naming its curves).
pub fn transform(
    network: &Network,
    form: &FormTopology,
    moves: &[VertexMove],
    tolerance: Tolerance,
) -> Result<Transformed, FormError> {
    transform_bulged(network, form, moves, &[], tolerance)
}

/// [`transform`], with the faces of `bulges` bulged as well (seed 002 §8.2): each such face's
/// surface after the change is the moved boundary's Gregory surface plus the bulge's offset
/// `amount · b(x) · n(x)` along the unit normal `n` of the surface before, outward (away from
/// the hull's centre line at mid-depth), where `b` is 1 at the middle of the face's domain and
/// falls to 0 at its sides with a level tangent (the product of the squared distances to the
/// domain's sides, normalised at its centre), so the face still meets its neighbours
/// tangentially. The curves inside the face follow by step 5, stations and waterlines in their
/// planes.
///
/// Errors: as [`transform`]; [`FormError::BadMove`] for a bulge of a face that does not exist
/// or whose amount is not finite.
pub fn transform_bulged(
    network: &Network,
    form: &FormTopology,
    moves: &[VertexMove],
    bulges: &[FaceBulge],
    tolerance: Tolerance,
) -> Result<Transformed, FormError> {
    for b in bulges {
        if b.face >= form.faces.len() || !b.amount.is_finite() {
            return Err(FormError::BadMove {
                vertex: b.face,
                reason: format!(
                    "a bulge of face {} by {} m: the form has {} faces and the amount must be finite",
                    b.face,
                    b.amount,
                    form.faces.len()
                ),
            });
        }
    }
    for m in moves {
        if m.vertex >= form.vertices.len() {
            return Err(FormError::BadMove {
                vertex: m.vertex,
                reason: format!("the form has {} vertices", form.vertices.len()),
            });
        }
        if !m.translation.is_finite() {
            return Err(FormError::BadMove {
                vertex: m.vertex,
                reason: "the translation is not finite".into(),
            });
        }
    }
    let tv = distribute(form, moves);
    let given = network;
    let refined = with_vertex_points(network, form)?;
    let network = &refined;
    let curves = network.curves();
    // 4. Form edges.
    let mut points: Vec<Vec<DVec3>> = curves.iter().map(|c| c.curve.control_points()).collect();
    for (ci, c) in curves
        .iter()
        .enumerate()
        .filter(|(i, _)| form.is_form_curve[*i])
    {
        points[ci] = moved_edge_points(&c.curve, ci, form, &tv);
    }
    let with_points = |ci: usize, pts: &[DVec3]| -> Result<NurbsCurve, FormError> {
        curves[ci]
            .curve
            .with_control_points(pts.to_vec())
            .map_err(|e| FormError::from(e.named(&curves[ci].name)))
    };
    let new_form_curves: Vec<Option<NurbsCurve>> = (0..curves.len())
        .map(|ci| {
            form.is_form_curve[ci]
                .then(|| with_points(ci, &points[ci]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    // 5. Face interiors.
    let mut faces = face_surfaces(network, form, &new_form_curves, tolerance)?;
    add_bulges(network, &mut faces, bulges);
    if !faces.is_empty() {
        points
            .par_iter_mut()
            .enumerate()
            .filter(|(ci, _)| !form.is_form_curve[*ci])
            .for_each(|(ci, pts)| curve_moved(&faces, &curves[ci].curve, pts, tolerance.get()));
    }
    let max_move = curves
        .iter()
        .zip(&points)
        .flat_map(|(c, pts)| {
            c.curve
                .control_points()
                .into_iter()
                .zip(pts.iter())
                .map(|(p, q)| p.distance(*q))
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max);
    let mut new_curves: Vec<NetworkCurve> = Vec::with_capacity(curves.len());
    for (ci, c) in curves.iter().enumerate() {
        // A form curve none of whose points moved is the curve given, without the knots its
        // vertices had inserted (a modeller holding the curve by knot layouts would otherwise
        // re-parameterise it, and the patches along it would change with nothing moved).
        let unmoved = form.is_form_curve[ci] && c.curve.control_points() == points[ci];
        new_curves.push(NetworkCurve {
            name: c.name.clone(),
            role: c.role,
            curve: if unmoved {
                given.curves()[ci].curve.clone()
            } else {
                with_points(ci, &points[ci])?
            },
        });
    }
    // 6. Re-attach, form curves first.
    let reattached = reattach(network, form, &tv, &mut new_curves, tolerance)?;
    let new_network = Network::try_new(network.name.clone(), new_curves)?;
    check_connections(network, &new_network, tolerance)?;
    Ok(Transformed {
        network: new_network,
        vertex_translations: tv,
        reattached,
        max_move,
    })
}

/// The network with a control point on every form vertex of its form curves ("the position
/// of a vertex corresponds to a control point on a curve", §7.2.1): knots inserted at interior
/// vertex parameters up to the degree (the shape is unchanged; curves whose vertices already
/// sit on control points are returned as they are).
fn with_vertex_points(network: &Network, form: &FormTopology) -> Result<Network, FormError> {
    let mut curves = network.curves().to_vec();
    for (ci, c) in curves
        .iter_mut()
        .enumerate()
        .filter(|(i, _)| form.is_form_curve[*i])
    {
        let (a, b) = c.curve.domain();
        let mut ts: Vec<f64> = form
            .edges
            .iter()
            .filter(|e| e.curve == ci)
            .flat_map(|e| [e.t0, e.t1])
            .filter(|&t| t > a && t < b)
            .collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup();
        for t in ts {
            let have = c.curve.knots().iter().filter(|&&k| k == t).count();
            let degree = c.curve.degree();
            if have < degree {
                c.curve = c
                    .curve
                    .insert_knot(t, degree - have)
                    .map_err(|e| e.named(&c.name))?;
            }
        }
    }
    Ok(Network::try_new(network.name.clone(), curves)?)
}

/// Steps 1–3 (§7.2.1): the selected translations, the planes they move, and the breadth-first
/// distribution with the edge rules (free-form stops, straight passes the part normal to the
/// line, blend passes it whole), contributions averaged and kept on the vertex's planes.
fn distribute(form: &FormTopology, moves: &[VertexMove]) -> Vec<DVec3> {
    let nv = form.vertices.len();
    let mut tv = vec![DVec3::ZERO; nv];
    let mut done = vec![false; nv];
    let mut selected: BTreeMap<usize, Vec<DVec3>> = BTreeMap::new();
    for m in moves {
        selected.entry(m.vertex).or_default().push(m.translation);
    }
    for (&v, ts) in &selected {
        tv[v] = ts.iter().copied().sum::<DVec3>() / ts.len() as f64;
        done[v] = true;
    }
    // 2. Each plane through a selected vertex moves by the mean normal part of their moves.
    let mut shift: Vec<Option<(f64, usize)>> = vec![None; form.planes.len()];
    for &v in selected.keys() {
        for &p in &form.vertices[v].planes {
            let s = tv[v].dot(form.planes[p].normal);
            let e = shift[p].get_or_insert((0.0, 0));
            e.0 += s;
            e.1 += 1;
        }
    }
    let plane_of = |p: usize| {
        let pl = &form.planes[p];
        let s = shift[p].map_or(0.0, |(s, n)| s / n as f64);
        (pl.normal, pl.offset + s)
    };
    let constrained = |v: usize, t: DVec3| {
        let vx = &form.vertices[v];
        let planes: Vec<(DVec3, f64)> = vx.planes.iter().map(|&p| plane_of(p)).collect();
        constrain(vx.position + t, &planes) - vx.position
    };
    // 3. Breadth first.
    let mut frontier: Vec<usize> = selected.keys().copied().collect();
    while !frontier.is_empty() {
        let mut received: BTreeMap<usize, Vec<DVec3>> = BTreeMap::new();
        for &v in &frontier {
            for e in form.edges.iter().filter(|e| e.start == v || e.end == v) {
                let w = if e.start == v { e.end } else { e.start };
                if done[w] {
                    continue;
                }
                if let Some(t) = passed_on(form, e, tv[v]) {
                    received.entry(w).or_default().push(t);
                }
            }
        }
        for (&w, ts) in &received {
            let mean = ts.iter().copied().sum::<DVec3>() / ts.len() as f64;
            tv[w] = constrained(w, mean);
            done[w] = true;
        }
        frontier = received.into_keys().collect();
    }
    // Vertices no translation reached still keep to their planes if those moved.
    for v in 0..nv {
        if !done[v] && form.vertices[v].planes.iter().any(|&p| shift[p].is_some()) {
            tv[v] = constrained(v, DVec3::ZERO);
        }
    }
    tv
}

/// The translation edge `e` passes on from one end (§7.2.1 edge rules).
fn passed_on(form: &FormTopology, e: &FormEdge, t: DVec3) -> Option<DVec3> {
    match e.kind {
        EdgeKind::FreeForm => None,
        EdgeKind::Blend => Some(t),
        EdgeKind::Straight => {
            let d = form.vertices[e.end].position - form.vertices[e.start].position;
            d.try_normalize().map(|d| t - d * t.dot(d))
        }
    }
}

/// The Greville abscissae of a curve's control points.
fn greville(c: &NurbsCurve) -> Vec<f64> {
    let p = c.degree();
    let k = c.knots();
    (0..c.control_point_count())
        .map(|i| k[i + 1..=i + p].iter().sum::<f64>() / p as f64)
        .collect()
}

/// Step 4 (Fig. 6): the control points of form curve `ci` moved with its edges: a point at a
/// vertex moves with it; a free point between an edge's ends by `(1 − t)·T0 + t·T1`; a blend
/// by the affine map of its end tangents' triangle (module docs).
fn moved_edge_points(c: &NurbsCurve, ci: usize, form: &FormTopology, tv: &[DVec3]) -> Vec<DVec3> {
    let pts = c.control_points();
    let g = greville(c);
    let edges: Vec<&FormEdge> = form.edges.iter().filter(|e| e.curve == ci).collect();
    let mut out = pts.clone();
    for (i, (&p, &xi)) in pts.iter().zip(&g).enumerate() {
        let Some(e) = edges.iter().find(|e| xi >= e.t0 && xi <= e.t1).or_else(|| {
            edges
                .iter()
                .min_by(|a, b| gap(a, xi).total_cmp(&gap(b, xi)))
        }) else {
            continue;
        };
        let (t0, t1) = (tv[e.start], tv[e.end]);
        out[i] = match e.kind {
            EdgeKind::Blend => {
                blend_map(c, e, form, tv).map_or(p + lerp(t0, t1, along(e, xi)), |m| m(p))
            }
            EdgeKind::Straight => {
                let (a, b) = (
                    form.vertices[e.start].position,
                    form.vertices[e.end].position,
                );
                let s = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                p + lerp(t0, t1, s)
            }
            EdgeKind::FreeForm => p + lerp(t0, t1, along(e, xi)),
        };
    }
    out
}

/// How far parameter `xi` lies outside edge `e`.
fn gap(e: &FormEdge, xi: f64) -> f64 {
    (e.t0 - xi).max(xi - e.t1).max(0.0)
}

/// The normalised position of parameter `xi` along edge `e`, in `[0, 1]`.
fn along(e: &FormEdge, xi: f64) -> f64 {
    ((xi - e.t0) / (e.t1 - e.t0)).clamp(0.0, 1.0)
}

/// `(1 − s)·a + s·b`.
fn lerp(a: DVec3, b: DVec3, s: f64) -> DVec3 {
    a * (1.0 - s) + b * s
}

/// The affine map of a blend edge: its ends and the meeting point of its end tangents to
/// their new places (the tangent directions kept), the normal of their plane kept. `None` when
/// the end tangents are parallel.
fn blend_map(
    c: &NurbsCurve,
    e: &FormEdge,
    form: &FormTopology,
    tv: &[DVec3],
) -> Option<impl Fn(DVec3) -> DVec3> {
    let (p0, p1) = (
        form.vertices[e.start].position,
        form.vertices[e.end].position,
    );
    let (d0, d1) = (c.derivs(e.t0).d1, c.derivs(e.t1).d1);
    let k = line_meeting(p0, d0, p1, d1)?;
    let (q0, q1) = (p0 + tv[e.start], p1 + tv[e.end]);
    let k2 = line_meeting(q0, d0, q1, d1)?;
    let (a, b) = (p0 - k, p1 - k);
    let n = a.cross(b).try_normalize()?;
    let (a2, b2) = (q0 - k2, q1 - k2);
    let m = glam::DMat3::from_cols(a, b, n);
    let inv = m.inverse();
    let m2 = glam::DMat3::from_cols(a2, b2, n);
    inv.is_finite()
        .then_some(move |p: DVec3| k2 + m2 * (inv * (p - k)))
}

/// The Gregory surface of one form face before and after the edges moved, with a grid of
/// their mean's points for the first guess of a foot point, and the face's bulge (§8.2).
struct FaceSurfaces {
    before: Patch,
    after: Patch,
    grid: Vec<(DVec2, DVec3)>,
    bulge: Option<Bulge>,
}

/// A face's bulge: the offset at the middle along the outward normal (m, signed), and the
/// product of the squared distances to the domain's sides at its centre (what normalises the
/// bump to 1 there).
#[derive(Clone, Copy, Debug)]
struct Bulge {
    amount: f64,
    centre_product: f64,
}

/// The bulge's offset at domain point `x` of face `f` (zero without a bulge).
fn bulge_offset(f: &FaceSurfaces, x: DVec2) -> DVec3 {
    let Some(b) = f.bulge else {
        return DVec3::ZERO;
    };
    let domain = f.before.domain();
    let product: f64 = (0..domain.sides())
        .map(|i| domain.distance(i, x).max(0.0).powi(2))
        .product();
    f.before.normal(x.to_array()) * (b.amount * product / b.centre_product)
}

/// Give the faces of `bulges` their bulge, its sign turned so that a positive amount moves
/// the face away from the hull's centre line (y = 0 at the middle of the network's height).
fn add_bulges(network: &Network, faces: &mut [FaceSurfaces], bulges: &[FaceBulge]) {
    if bulges.is_empty() {
        return;
    }
    let (lo, hi) =
        network
            .curves()
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                c.curve
                    .control_points()
                    .iter()
                    .fold((lo, hi), |(lo, hi), p| (lo.min(p.z), hi.max(p.z)))
            });
    let mid = 0.5 * (lo + hi);
    for b in bulges {
        let f = &mut faces[b.face];
        let domain = f.before.domain();
        let c = domain.centre_v();
        let centre_product: f64 = (0..domain.sides())
            .map(|i| domain.distance(i, c).powi(2))
            .product();
        let p = f.before.eval(c.to_array());
        let n = f.before.normal(c.to_array());
        let away = DVec3::new(0.0, p.y, p.z - mid);
        let sign = if n.dot(away) >= 0.0 { 1.0 } else { -1.0 };
        f.bulge = Some(Bulge {
            amount: sign * b.amount,
            centre_product,
        });
    }
}

/// Step 5's surfaces: for every form face, the Gregory / Charrot–Gregory patch of its boundary
/// (default ribbons: a surface of the boundary only, Gregory's multi-sided Coons patch), before
/// and after the form curves moved.
fn face_surfaces(
    network: &Network,
    form: &FormTopology,
    moved: &[Option<NurbsCurve>],
    tolerance: Tolerance,
) -> Result<Vec<FaceSurfaces>, FormError> {
    let curves = network.curves();
    let options = PatchOptions {
        tolerance,
        ..PatchOptions::default()
    };
    let boundary = |face: &super::identify::FormFace, after: bool| {
        let sides = face
            .sides
            .iter()
            .map(|side| {
                side.iter()
                    .map(|&(ei, fwd)| {
                        let e = &form.edges[ei];
                        let c = if after {
                            moved[e.curve]
                                .clone()
                                .unwrap_or_else(|| curves[e.curve].curve.clone())
                        } else {
                            curves[e.curve].curve.clone()
                        };
                        // The stretch cut out, so that derivatives at a knot where the
                        // moved curve kinks belong to this edge's side.
                        let s = SideSegment::new(edge_curve(&c, e.t0, e.t1), e.t0, e.t1)
                            .named(curves[e.curve].name.clone());
                        if fwd {
                            s
                        } else {
                            s.reversed()
                        }
                    })
                    .collect()
            })
            .collect();
        FaceBoundary::new(
            at_least_three_sides(sides)
                .into_iter()
                .map(Side::new)
                .collect(),
        )
    };
    let mut out = Vec::with_capacity(form.faces.len());
    for face in &form.faces {
        let names = || {
            face.curves
                .iter()
                .map(|&c| curves[c].name.as_str())
                .collect::<Vec<_>>()
                .join("', '")
        };
        let build = |after: bool| {
            Patch::try_new(&boundary(face, after), &[], &options).map_err(|e| {
                FormError::NotMeasurable {
                    parameter: "face surface",
                    reason: format!("the form face of curves '{}': {e}", names()),
                }
            })
        };
        let (before, after) = (build(false)?, build(true)?);
        let grid = domain_grid(before.domain())
            .into_iter()
            .map(|x| {
                (
                    x,
                    (before.eval(x.to_array()) + after.eval(x.to_array())) * 0.5,
                )
            })
            .collect();
        out.push(FaceSurfaces {
            before,
            after,
            grid,
            bulge: None,
        });
    }
    Ok(out)
}

/// The sides of a form face split until there are at least three, as a Gregory surface needs
/// (a face bounded by two curves between the same two vertices, such as the flat end of a
/// shaft boss between its knuckle and the profile, or by one closed curve): a side of several
/// edges is split at the vertex in its middle, else the longest single-edge side at the middle
/// of its parameter. The new corner is flat (180°), which the patch construction repairs with
/// its documented fallback ([`crate::PatchWarning::CornerAngle`]); the surface serves only as
/// the face's field of displacement, and the boundary it spans is unchanged.
fn at_least_three_sides(mut sides: Vec<Vec<SideSegment>>) -> Vec<Vec<SideSegment>> {
    while (1..3).contains(&sides.len()) {
        let length = |side: &[SideSegment]| -> f64 {
            side.iter()
                .map(|s| {
                    (0..8)
                        .map(|k| {
                            let at =
                                |j: usize| s.curve.point(s.t0 + (s.t1 - s.t0) * j as f64 / 8.0);
                            at(k).distance(at(k + 1))
                        })
                        .sum::<f64>()
                })
                .sum()
        };
        let i = (0..sides.len())
            .max_by(|&a, &b| {
                (sides[a].len(), length(&sides[a]))
                    .partial_cmp(&(sides[b].len(), length(&sides[b])))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(0);
        let tail = if sides[i].len() >= 2 {
            let half = sides[i].len() / 2;
            sides[i].split_off(half)
        } else {
            let Some(seg) = sides[i].pop() else {
                break;
            };
            let mid = 0.5 * (seg.t0 + seg.t1);
            let first = SideSegment {
                t1: mid,
                end: None,
                ..seg.clone()
            };
            sides[i].push(first);
            vec![SideSegment {
                t0: mid,
                start: None,
                ..seg
            }]
        };
        sides.insert(i + 1, tail);
    }
    sides
}

/// Points of a `FOOT_GRID`² grid over the domain's box that lie inside the domain.
fn domain_grid(domain: &Domain) -> Vec<DVec2> {
    let vs = domain.vertices();
    let (lo, hi) = vs.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(DVec2::from(*v)), hi.max(DVec2::from(*v))),
    );
    let mut out = Vec::new();
    for i in 0..=FOOT_GRID {
        for j in 0..=FOOT_GRID {
            let x = lo + (hi - lo) * DVec2::new(i as f64, j as f64) / FOOT_GRID as f64;
            if domain.contains(x.to_array()) {
                out.push(x);
            }
        }
    }
    out
}

/// The mean of the surfaces before and after at domain point `x`, with its derivatives.
fn mean_surface(f: &FaceSurfaces, x: DVec2) -> (DVec3, DVec3, DVec3) {
    let (a, au, av) = f.before.derivatives(x.to_array());
    let (b, bu, bv) = f.after.derivatives(x.to_array());
    // (A bulge is no part of the mean: the midpoint of a point's old and new place is found
    // on the surfaces of the boundary alone, so the opposite bulge finds the same foot and
    // moves the point back.)
    ((a + b) * 0.5, (au + bu) * 0.5, (av + bv) * 0.5)
}

/// The surfaces before and after at domain point `x` (inside the domain): the points of
/// [`mean_surface`] without its derivatives.
fn points_at(f: &FaceSurfaces, x: DVec2) -> (DVec3, DVec3) {
    (
        f.before.eval(x.to_array()),
        f.after.eval(x.to_array()) + bulge_offset(f, x),
    )
}

/// Step of the central differences for the mean surface's second derivatives (domain units):
/// they only shape the Newton steps of [`foot`], not where it converges.
const SECOND_DERIV_STEP: f64 = 1e-3;

/// The second derivatives `(S_uu, S_uv, S_vv)` of the mean surface at `x` by central
/// differences, or None where the stencil would leave the domain.
fn mean_second_derivatives(f: &FaceSurfaces, x: DVec2) -> Option<(DVec3, DVec3, DVec3)> {
    let h = SECOND_DERIV_STEP;
    if !stencil_fits(f.before.domain(), x, h) {
        return None;
    }
    let mean = |y: DVec2| (f.before.eval(y.to_array()) + f.after.eval(y.to_array())) * 0.5;
    let [_, _, _, suu, suv, svv] = central_differences(mean, x, h);
    Some((suu, suv, svv))
}

/// The foot of `p` on the mean surface: the stationary point of `½|p − S(x)|²` in the domain
/// (clamped) from `x`, by Newton's method with the second derivatives taken once at the start
/// (a control point off a curved face makes Gauss–Newton converge only linearly, by the
/// distance over the radius of curvature each step: some 25 steps to 1e-13 at the bilge);
/// Gauss–Newton where that Hessian is not positive definite or cannot be taken. Returns the
/// foot, its distance from `p`, and the surfaces before and after there ([`points_at`]).
fn foot(f: &FaceSurfaces, p: DVec3, mut x: DVec2) -> (DVec2, f64, (DVec3, DVec3)) {
    let second = mean_second_derivatives(f, x);
    let mut last = f64::INFINITY;
    for _ in 0..FOOT_STEPS {
        let (s, du, dv) = mean_surface(f, x);
        let r = p - s;
        let (mut a, mut b, mut c) = (du.dot(du), du.dot(dv), dv.dot(dv));
        if let Some((suu, suv, svv)) = second {
            let (na, nb, nc) = (a - r.dot(suu), b - r.dot(suv), c - r.dot(svv));
            if na > 0.0 && nc > 0.0 && na * nc - nb * nb > 0.0 {
                (a, b, c) = (na, nb, nc);
            }
        }
        let den = a * c - b * b;
        if den <= 0.0 || !den.is_finite() {
            break;
        }
        let (g0, g1) = (du.dot(r), dv.dot(r));
        let mut step = DVec2::new(c * g0 - b * g1, a * g1 - b * g0) / den;
        let domain = f.before.domain();
        if !domain.contains((x + step).to_array()) {
            // On a side with the step leading out: the (Gauss–)Newton step along the side
            // instead, so the foot slides to the constrained minimum (the step clamped back
            // onto the side moves along it by the step's share only, a few per cent per step).
            if let Some(e) = domain.side_through(x) {
                let along = a * e.x * e.x + 2.0 * b * e.x * e.y + c * e.y * e.y;
                if along > 0.0 {
                    step = e * ((e.x * g0 + e.y * g1) / along);
                }
            }
        }
        let next = domain.clamp(x + step);
        let moved = (next - x).length();
        x = next;
        // Converged, or down to the noise of the difference derivatives (the steps no longer
        // shrink: a point a metre off the face has its steps wander by 1e-10, far below what
        // moves it measurably).
        if moved <= FOOT_CONVERGED || (moved < FOOT_NOISE && moved > 0.5 * last) {
            break;
        }
        last = moved;
    }
    let (a, b) = points_at(f, x);
    (x, ((a + b) * 0.5).distance(p), (a, b))
}

/// The move of `p` by face `f` (§7.2.3): the change `S′(x) − S(x)` of the face's surface at
/// the foot `x` of the midpoint of `p` and its new place on the mean surface (solved by fixed
/// point iteration), with the distance of that midpoint from the mean surface. The rule is
/// the paper's to first order, and symmetric: the reverse change moves the point back.
fn face_move(f: &FaceSurfaces, p: DVec3, keep: &[(DVec3, f64)]) -> (DVec3, f64) {
    let (mut x, _) = grid_nearest(f, p);
    // The surface change at the points (before, after), along `keep`'s normals as given.
    let change = |(before, after): (DVec3, DVec3)| {
        let d = after - before;
        keep.iter()
            .fold(d, |d, &(n, shift)| d + n * (shift - n.dot(d)))
    };
    let mut delta = change(points_at(f, x));
    let mut dist = 0.0;
    for _ in 0..MIDPOINT_STEPS {
        let (xm, d, at) = foot(f, p + delta * 0.5, x);
        x = xm;
        dist = d;
        let next = change(at);
        let change = (next - delta).length();
        delta = next;
        if change <= MIDPOINT_CONVERGED {
            break;
        }
    }
    (delta, dist)
}

/// Fixed-point steps of the midpoint rule (each contracts by the surface change's slope).
const MIDPOINT_STEPS: usize = 60;
/// Change of a move (m) below which the midpoint rule has converged: a thousandth of the
/// 1e-9 m to which a transformation and its inverse cancel.
const MIDPOINT_CONVERGED: f64 = 1e-12;

/// The grid point of face `f` nearest to `p`, with its squared distance.
fn grid_nearest(f: &FaceSurfaces, p: DVec3) -> (DVec2, f64) {
    f.grid
        .iter()
        .map(|&(x, q)| (x, q.distance_squared(p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((DVec2::from(f.before.domain().centre()), f64::INFINITY))
}

/// How many faces, nearest by their grids, are tried for a point.
const CANDIDATE_FACES: usize = 2;

/// Step 5 (§7.2.3): `p` moved by the nearest face (its midpoint nearest the mean surface; the
/// faces tried are the nearest few by their grids), its move along each normal of `keep` set
/// to the shift given there.
fn face_moved(faces: &[FaceSurfaces], p: DVec3, keep: &[(DVec3, f64)]) -> DVec3 {
    let mut order: Vec<(usize, f64)> = faces
        .iter()
        .enumerate()
        .map(|(i, f)| (i, grid_nearest(f, p).1))
        .collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    order
        .iter()
        .take(CANDIDATE_FACES)
        .map(|&(i, _)| face_move(&faces[i], p, keep))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(p, |(d, _)| p + d)
}

/// Step 5 for one free curve: every control point moved by the faces; a curve lying in axis
/// planes (a station: §5's surface attribute) keeps lying in parallel planes, moved along
/// their normals as its first control point is (its end on a form curve, which so stays on
/// it).
fn curve_moved(faces: &[FaceSurfaces], curve: &NurbsCurve, pts: &mut [DVec3], tol: f64) {
    let normals: Vec<DVec3> = curve_planes(curve, tol)
        .into_iter()
        .filter(|(k, _, _)| *k != super::planes::PlaneKind::Inclined)
        .map(|(_, n, _)| n)
        .collect();
    let Some(&first) = pts.first() else {
        return;
    };
    let moved_first = face_moved(faces, first, &[]);
    let keep: Vec<(DVec3, f64)> = normals
        .iter()
        .map(|&n| (n, n.dot(moved_first - first)))
        .collect();
    for p in pts.iter_mut() {
        *p = face_moved(faces, *p, &keep);
    }
}

/// Step 6 (with the reconnection of §7.2.4): every node of the original network whose curves
/// no longer meet (a free curve's point off its form curve, or points farther apart than a
/// fraction of the tolerance; every form vertex) is restored, form curves
/// first in the hierarchy. The node goes to the moved form vertex; else, with a form curve
/// through it, to that curve's point — slid along it into the plane of a free curve lying in
/// an axis plane (a station keeps its plane and its end slides along the keel); else to the
/// mean of the curves' points kept in their planes. Each curve is then changed as little as
/// possible to pass its nodes ([`NurbsCurve::through`]). Returns the names of the curves
/// changed.
fn reattach(
    network: &Network,
    form: &FormTopology,
    tv: &[DVec3],
    curves: &mut [NetworkCurve],
    tolerance: Tolerance,
) -> Result<Vec<String>, FormError> {
    let tol = tolerance.get();
    let junctions = network.junctions(tolerance)?;
    let limit = REATTACH_FRACTION * tol;
    let planes: Vec<Vec<(DVec3, f64)>> = curves
        .iter()
        .enumerate()
        .map(|(ci, c)| {
            if form.is_form_curve[ci] {
                return Vec::new();
            }
            curve_planes(&c.curve, tol)
                .into_iter()
                .filter(|(k, _, _)| *k != super::planes::PlaneKind::Inclined)
                .map(|(_, n, d)| (n, d))
                .collect()
        })
        .collect();
    let mut targets: Vec<Vec<(f64, DVec3)>> = vec![Vec::new(); curves.len()];
    let mut needs = vec![false; curves.len()];
    for node in &junctions.nodes {
        if node.incidences.len() < 2 {
            continue;
        }
        let child_planes: Vec<(DVec3, f64)> = node
            .incidences
            .iter()
            .flat_map(|i| planes[i.curve].iter().copied())
            .collect();
        let vertex = form
            .vertices
            .iter()
            .position(|v| v.position.distance(node.position) <= tol);
        let parent = node.incidences.iter().find(|i| form.is_form_curve[i.curve]);
        let mut slid: Option<usize> = None;
        let target = match (vertex, parent) {
            (Some(v), _) => form.vertices[v].position + tv[v],
            (None, Some(i)) => {
                let c = &curves[i.curve].curve;
                let t = child_planes
                    .first()
                    .and_then(|&(n, d)| into_plane(c, i.t, n, d))
                    .unwrap_or(i.t);
                slid = Some(i.curve);
                c.point(t)
            }
            (None, None) => {
                let mean = node
                    .incidences
                    .iter()
                    .map(|i| curves[i.curve].curve.point(i.t))
                    .sum::<DVec3>()
                    / node.incidences.len() as f64;
                constrain(mean, &child_planes)
            }
        };
        // A node the move kept (a free curve's end still on its form curve) is left alone.
        let still_meet = vertex.is_none()
            && match parent {
                Some(pi) => node.incidences.iter().all(|i| {
                    i.curve == pi.curve
                        || on_curve(
                            &curves[pi.curve].curve,
                            curves[i.curve].curve.point(i.t),
                            limit,
                        )
                }),
                None => {
                    let p0 = curves[node.incidences[0].curve]
                        .curve
                        .point(node.incidences[0].t);
                    node.incidences
                        .iter()
                        .all(|i| curves[i.curve].curve.point(i.t).distance(p0) <= limit)
                }
            };
        for i in &node.incidences {
            if slid == Some(i.curve) {
                // The parent keeps its shape; the node slid along it.
                continue;
            }
            let here = curves[i.curve].curve.point(i.t);
            if still_meet {
                targets[i.curve].push((i.t, here));
                continue;
            }
            targets[i.curve].push((i.t, target));
            if here.distance(target) > limit {
                needs[i.curve] = true;
            }
        }
    }
    let mut changed = Vec::new();
    for (ci, c) in curves.iter_mut().enumerate() {
        if needs[ci] {
            c.curve = c
                .curve
                .through(&targets[ci])
                .map_err(|e| e.named(&c.name))?;
            changed.push(c.name.clone());
        }
    }
    Ok(changed)
}

/// Whether `p` lies within `limit` of `curve`.
fn on_curve(curve: &NurbsCurve, p: DVec3, limit: f64) -> bool {
    curve
        .nearest(p, limit * NEAREST_ACCURACY)
        .is_ok_and(|n| n.distance <= limit)
}

/// Accuracy of a nearest-point search, as a fraction of the distance it decides.
const NEAREST_ACCURACY: f64 = 1e-3;

/// The parameter near `t` where `curve` crosses the plane `n · p = d` (Newton), `None` when
/// it does not converge inside the domain.
fn into_plane(curve: &NurbsCurve, t: f64, n: DVec3, d: f64) -> Option<f64> {
    let (a, b) = curve.domain();
    let mut t = t;
    for _ in 0..PLANE_STEPS {
        let e = curve.derivs(t);
        let f = n.dot(e.point) - d;
        if f.abs() <= PLANE_RESIDUAL {
            return Some(t);
        }
        let g = n.dot(e.d1);
        if g == 0.0 || !g.is_finite() {
            return None;
        }
        t = (t - f / g).clamp(a, b);
    }
    None
}

/// Newton steps for a curve's crossing with a plane.
const PLANE_STEPS: usize = 50;
/// A crossing within this distance (m) of the plane is exact for every purpose here.
const PLANE_RESIDUAL: f64 = 1e-12;

/// §7.2.4: every pair of curves that met in `before` meets as often in `after`, and no others;
/// otherwise the curves are named.
fn check_connections(
    before: &Network,
    after: &Network,
    tolerance: Tolerance,
) -> Result<(), FormError> {
    let pairs = |n: &Network| -> Result<BTreeMap<(usize, usize), usize>, FormError> {
        let j = n.junctions(tolerance)?;
        let mut out = BTreeMap::new();
        for node in &j.nodes {
            let mut cs: Vec<usize> = node.incidences.iter().map(|i| i.curve).collect();
            cs.sort_unstable();
            cs.dedup();
            for (k, &a) in cs.iter().enumerate() {
                for &b in &cs[k + 1..] {
                    *out.entry((a, b)).or_insert(0) += 1;
                }
            }
        }
        Ok(out)
    };
    let (old, new) = (pairs(before)?, pairs(after)?);
    let names = |&(a, b): &(usize, usize)| {
        vec![
            before.curves()[a].name.clone(),
            before.curves()[b].name.clone(),
        ]
    };
    let count =
        |m: &BTreeMap<(usize, usize), usize>, k: &(usize, usize)| m.get(k).copied().unwrap_or(0);
    let changed = old
        .keys()
        .chain(new.keys())
        .find(|k| count(&old, k) != count(&new, k));
    if let Some(k) = changed {
        return Err(FormError::ConnectionLost {
            curves: names(k),
            detail: format!(
                "they met {} time(s) and now meet {} time(s)",
                count(&old, k),
                count(&new, k)
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quadratic Bézier curve through `a`, pulled toward `b`, to `c`.
    fn quadratic(a: DVec3, b: DVec3, c: DVec3) -> NurbsCurve {
        NurbsCurve::try_new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![a, b, c], None).unwrap()
    }

    /// The flat end of a shaft boss: a knuckle arc and the straight profile between the same
    /// two vertices, in the plane y = 0.
    fn lens() -> Vec<Vec<SideSegment>> {
        let (a, c) = (DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
        let chord = quadratic(a, DVec3::new(1.0, 0.0, 0.0), c);
        let arc = quadratic(a, DVec3::new(1.0, 0.0, 1.5), c);
        vec![
            vec![SideSegment::new(chord, 0.0, 1.0)],
            vec![SideSegment::new(arc, 1.0, 0.0)],
        ]
    }

    #[test]
    fn a_two_sided_form_face_gets_a_surface_on_its_own_boundary() {
        let sides = lens();
        let split = at_least_three_sides(sides.clone());
        assert_eq!(split.len(), 3);
        let patch = Patch::try_new(
            &FaceBoundary::new(split.into_iter().map(Side::new).collect()),
            &[],
            &PatchOptions::default(),
        )
        .expect("three sides make a patch");
        // The boundary is the lens's: points of the sides lie on the arc or on the chord.
        let on_boundary = |p: DVec3| {
            let chord = p.z.abs();
            let arc = (0..=2000)
                .map(|k| sides[1][0].curve.point(k as f64 / 2000.0).distance(p))
                .fold(f64::INFINITY, f64::min);
            chord.min(arc)
        };
        for i in 0..3 {
            for k in 0..=10 {
                let p = patch.side_point(i, k as f64 / 10.0);
                assert!(
                    on_boundary(p) < 2e-3,
                    "side {i} at {k}/10: {p} is off the lens"
                );
            }
        }
        // A flat face gets a flat surface: the whole domain stays in y = 0.
        let d = patch.domain();
        for x in domain_grid(d) {
            let p = patch.eval(x.to_array());
            assert!(
                p.y.abs() < 1e-9 && p.is_finite(),
                "{p} leaves the face's plane"
            );
        }
        // Without the split, the same face is refused.
        let whole = FaceBoundary::new(sides.into_iter().map(Side::new).collect());
        assert!(Patch::try_new(&whole, &[], &PatchOptions::default()).is_err());
    }

    #[test]
    fn one_closed_side_splits_into_three_and_three_sides_stay_as_they_are() {
        let (a, b) = (DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
        let loop_ = NurbsCurve::try_new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0],
            vec![a, DVec3::new(0.0, 0.0, 2.0), DVec3::new(2.0, 0.0, 2.0), a],
            None,
        )
        .unwrap();
        let split = at_least_three_sides(vec![vec![SideSegment::new(loop_, 0.0, 2.0)]]);
        assert_eq!(split.len(), 3);
        // Each piece starts where the one before it ends.
        for i in 0..3 {
            let (s, n) = (&split[i][0], &split[(i + 1) % 3][0]);
            assert_eq!(s.t1, n.t0 + if i == 2 { 2.0 } else { 0.0 });
        }
        let three = vec![
            vec![SideSegment::new(quadratic(a, DVec3::X, b), 0.0, 1.0)],
            vec![SideSegment::new(
                quadratic(b, DVec3::Z, DVec3::Z * 2.0),
                0.0,
                1.0,
            )],
            vec![SideSegment::new(
                quadratic(DVec3::Z * 2.0, DVec3::Z, a),
                0.0,
                1.0,
            )],
        ];
        assert_eq!(at_least_three_sides(three.clone()), three);
    }
}
