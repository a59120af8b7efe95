//! Identifying the form topology in a curve network (Bole, seed 002, §6 and §7.2): the curves
//! that carry the form (every curve with a role, and the curves those end on), their vertices,
//! their edges classified as free-form, straight or blend, the faces they enclose, and the
//! planes the form curves lie in.

use glam::DVec3;

use super::error::FormError;
use super::parameters::FormParameters;
use super::planes::{curve_planes, FormPlane};
use crate::hull::KnotPoints;
use crate::network::{Network, NetworkCurve, Role};
use crate::tolerance::Tolerance;
use crate::topo::Topology;

/// How an edge of the form topology passes a translation on (§7.2.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// The curve has free control points: a translation stops here.
    FreeForm,
    /// A straight line: only the part of a translation normal to it is passed on.
    Straight,
    /// A blend between two straight edges it is tangent to (the bilge radius): a translation
    /// is passed on whole.
    Blend,
}

impl EdgeKind {
    /// The lowercase name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            EdgeKind::FreeForm => "free_form",
            EdgeKind::Straight => "straight",
            EdgeKind::Blend => "blend",
        }
    }
}

/// A vertex of the form topology: where form curves meet or end (§7.2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct FormVertex {
    /// Its position.
    pub position: DVec3,
    /// The form curves through it (indices into the network), sorted.
    pub curves: Vec<usize>,
    /// The planes it lies in (indices into [`FormTopology::planes`]).
    pub planes: Vec<usize>,
}

/// An edge of the form topology: the stretch `[t0, t1]` of one form curve between two of its
/// vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct FormEdge {
    /// The curve (index into the network).
    pub curve: usize,
    /// Start parameter.
    pub t0: f64,
    /// End parameter.
    pub t1: f64,
    /// The vertex at `t0` (index into [`FormTopology::vertices`]).
    pub start: usize,
    /// The vertex at `t1`.
    pub end: usize,
    /// How it passes translations on.
    pub kind: EdgeKind,
}

/// A face of the form topology: a region the form curves enclose (the flat of side, the
/// bilge, the entrance …), its boundary as sides of edges between its corners.
#[derive(Clone, Debug, PartialEq)]
pub struct FormFace {
    /// Per side, its edges in loop order with `true` where the loop runs along the curve.
    pub sides: Vec<Vec<(usize, bool)>>,
    /// The curves of its boundary (indices into the network), sorted, without repeats.
    pub curves: Vec<usize>,
}

/// The form topology of a hull network (§6), with the parameters measured from it (§7.2.5).
#[derive(Clone, Debug, PartialEq)]
pub struct FormTopology {
    /// For each network curve, whether it is a form curve.
    pub is_form_curve: Vec<bool>,
    /// The vertices.
    pub vertices: Vec<FormVertex>,
    /// The edges.
    pub edges: Vec<FormEdge>,
    /// The faces.
    pub faces: Vec<FormFace>,
    /// The planes form curves lie in.
    pub planes: Vec<FormPlane>,
    /// The measured parameters.
    pub parameters: FormParameters,
}

/// Options of [`form_topology`](super::form_topology).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FormOptions {
    /// The model tolerance: when points coincide and curves lie in planes.
    pub tolerance: Tolerance,
    /// The design draft (z of the design waterline), for the waterline breadth.
    pub draft: Option<f64>,
}

impl Default for FormOptions {
    fn default() -> Self {
        FormOptions {
            tolerance: Tolerance::DEFAULT,
            draft: None,
        }
    }
}

/// Samples per Bézier span when an edge is tested for straightness.
const STRAIGHT_SAMPLES_PER_SPAN: usize = 16;

/// Largest angle (degrees) between the tangents of a blend and of the straight edge next to it
/// at their common vertex: the blend enters the straight edges tangentially.
pub const BLEND_TANGENT_DEGREES: f64 = 1.0;

/// The form topology of `network` (Bole, seed 002, §6): the form curves are every curve with a
/// role (keel, stem, transom, deck, midship, flat of side and bottom, knuckle) and, so that
/// the form closes, every curve a form curve ends on (a station the knuckle ends on); their
/// nodes are its vertices, their stretches between nodes its edges, the regions they enclose
/// its faces. The parameters are left at their defaults ([`form_topology`](super::form_topology)
/// measures them).
///
/// Errors only when a curve cannot be evaluated (naming it).
pub(crate) fn identify(
    network: &Network,
    options: &FormOptions,
) -> Result<FormTopology, FormError> {
    let tol = options.tolerance;
    let curves = network.curves();
    let is_form_curve = form_curves(network, tol)?;
    let index: Vec<usize> = (0..curves.len()).filter(|&i| is_form_curve[i]).collect();
    let sub = Network::try_new(
        network.name.clone(),
        index
            .iter()
            .map(|&i| curves[i].clone())
            .collect::<Vec<NetworkCurve>>(),
    )?;
    let topology = Topology::build(&sub, tol)?;
    let planes = merged_planes(curves, &index, tol.get());
    let brep = &topology.brep;
    let vertices: Vec<FormVertex> = brep
        .vertices
        .iter()
        .map(|v| {
            let mut cs: Vec<usize> = v.curves.iter().map(|&c| index[c]).collect();
            cs.sort_unstable();
            cs.dedup();
            let planes = (0..planes.len())
                .filter(|&p| planes[p].curves.iter().any(|c| cs.contains(c)))
                .collect();
            FormVertex {
                position: v.position,
                curves: cs,
                planes,
            }
        })
        .collect();
    // Each curve's knot points once, for the ends of all its edges.
    let knots: Vec<KnotPoints> = index
        .iter()
        .map(|&i| KnotPoints::of(&curves[i].curve))
        .collect();
    let snap = |c: usize, t: f64| knots[c].snap(&curves[index[c]].curve, t, tol);
    let mut edges: Vec<FormEdge> = brep
        .edges
        .iter()
        .map(|e| FormEdge {
            curve: index[e.curve],
            t0: snap(e.curve, e.t0),
            t1: snap(e.curve, e.t1),
            start: e.start.index(),
            end: e.end.index(),
            kind: EdgeKind::FreeForm,
        })
        .collect();
    classify_edges(network, &mut edges, tol.get());
    let faces = topology
        .faces
        .iter()
        .map(|f| {
            let mut k = 0;
            let start = f
                .sides
                .first()
                .and_then(|s| s.edges.first())
                .and_then(|e0| f.edges.iter().position(|e| e == e0))
                .unwrap_or(0);
            let sides = f
                .sides
                .iter()
                .map(|s| {
                    s.edges
                        .iter()
                        .map(|e| {
                            let pos = (start + k) % f.edges.len();
                            k += 1;
                            (e.index(), f.forward[pos])
                        })
                        .collect()
                })
                .collect();
            FormFace {
                sides,
                curves: f.curves.iter().map(|&c| index[c]).collect(),
            }
        })
        .collect();
    Ok(FormTopology {
        is_form_curve,
        vertices,
        edges,
        faces,
        planes,
        parameters: FormParameters::default(),
    })
}

/// Which curves carry the form: those with a role, then (until nothing changes) every curve a
/// form curve ends on in its interior (§7.2: a curve important to the form without an
/// attribute, such as the station a knuckle ends on).
fn form_curves(network: &Network, tol: Tolerance) -> Result<Vec<bool>, FormError> {
    let curves = network.curves();
    let mut form: Vec<bool> = curves.iter().map(|c| c.role != Role::Free).collect();
    let junctions = network.junctions(tol)?;
    let at_end = |c: usize, t: f64| {
        let (a, b) = curves[c].curve.domain();
        (t - a).abs() <= f64::EPSILON * a.abs().max(1.0) * END_SLACK
            || (t - b).abs() <= f64::EPSILON * b.abs().max(1.0) * END_SLACK
            || curves[c].curve.point(t).distance(curves[c].curve.point(a)) <= tol.get()
            || curves[c].curve.point(t).distance(curves[c].curve.point(b)) <= tol.get()
    };
    loop {
        let mut changed = false;
        for node in &junctions.nodes {
            let form_end = node
                .incidences
                .iter()
                .any(|i| form[i.curve] && at_end(i.curve, i.t));
            if !form_end {
                continue;
            }
            for i in &node.incidences {
                if !form[i.curve] && !at_end(i.curve, i.t) {
                    form[i.curve] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            return Ok(form);
        }
    }
}

/// Parameters within this many ulps of a domain end count as the end.
const END_SLACK: f64 = 64.0;

/// The planes of the form curves `index`, one [`FormPlane`] for planes that coincide.
fn merged_planes(curves: &[NetworkCurve], index: &[usize], tol: f64) -> Vec<FormPlane> {
    let mut planes: Vec<FormPlane> = Vec::new();
    for &c in index {
        for (kind, normal, offset) in curve_planes(&curves[c].curve, tol) {
            let same = planes.iter_mut().find(|p| {
                let dot = p.normal.dot(normal);
                (1.0 - dot.abs()) <= PLANE_SAME_COS
                    && (p.offset - offset * dot.signum()).abs() <= tol
            });
            match same {
                Some(p) => p.curves.push(c),
                None => planes.push(FormPlane {
                    kind,
                    normal,
                    offset,
                    curves: vec![c],
                }),
            }
        }
    }
    planes
}

/// Two planes with normals this close (1 − |cos|) and offsets within the tolerance coincide.
const PLANE_SAME_COS: f64 = 1e-9;

/// Mark each edge straight, blend or free-form (§7.2.1).
fn classify_edges(network: &Network, edges: &mut [FormEdge], tol: f64) {
    let curves = network.curves();
    for e in edges.iter_mut() {
        if is_straight(&curves[e.curve].curve, e.t0, e.t1, tol) {
            e.kind = EdgeKind::Straight;
        }
    }
    let snapshot = edges.to_vec();
    for e in edges.iter_mut().filter(|e| e.kind == EdgeKind::FreeForm) {
        let curve = &curves[e.curve].curve;
        let neighbour = |t: f64, at_start: bool| {
            snapshot.iter().find(|o| {
                o.curve == e.curve
                    && o.kind == EdgeKind::Straight
                    && if at_start { o.t1 == t } else { o.t0 == t }
            })
        };
        let (before, after) = (neighbour(e.t0, true), neighbour(e.t1, false));
        if let (Some(b), Some(a)) = (before, after) {
            let c = |o: &FormEdge| curve.point(o.t1) - curve.point(o.t0);
            let (d0, d1) = (curve.derivs(e.t0).d1, curve.derivs(e.t1).d1);
            let ok0 = d0.angle_between(c(b)).to_degrees() <= BLEND_TANGENT_DEGREES;
            let ok1 = d1.angle_between(c(a)).to_degrees() <= BLEND_TANGENT_DEGREES;
            if ok0 && ok1 {
                e.kind = EdgeKind::Blend;
            }
        }
    }
}

/// Whether the stretch `[t0, t1]` of `curve` is a straight line within `tol`.
fn is_straight(curve: &crate::curve::NurbsCurve, t0: f64, t1: f64, tol: f64) -> bool {
    let (a, b) = (curve.point(t0), curve.point(t1));
    let Some(dir) = (b - a).try_normalize() else {
        return false;
    };
    let spans = curve
        .knots()
        .windows(2)
        .filter(|w| w[0] < w[1] && w[1] > t0 && w[0] < t1)
        .count();
    let n = STRAIGHT_SAMPLES_PER_SPAN * spans.max(1);
    (1..n).all(|j| {
        let t = t0 + (t1 - t0) * j as f64 / n as f64;
        (curve.point(t) - a).reject_from_normalized(dir).length() <= tol
    })
}
