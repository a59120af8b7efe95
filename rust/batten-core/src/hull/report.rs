//! The hull report (H-rep paper §3–§5): counts, fit of the patches to the designer's curves,
//! continuity across the edges (with where it is worst), crease angles along knuckles, holes and
//! folds of the surface, and the volume of the half hull.

use std::collections::BTreeMap;

use glam::DVec3;
use rayon::prelude::*;

use serde::Serialize;

use super::folds::{boundary_boxes, fold_findings};
use super::holes::hole_warnings;
use super::knuckles::{knuckle_report, Knuckle, KnuckleEdge};
use super::patched::{LayoutSegment, PatchedFace};
use super::warning::Warning;
use crate::network::Network;
use crate::patch::{FaceMesh, Patch, SurfaceMesh};
use crate::tolerance::Tolerance;
use crate::topo::{NodeKind, Topology};

/// What [`build_hull`] built and how good it is (H-rep paper §3–§5: counts of the topology,
/// continuity across the network's edges, and the designer's first hydrostatic check).
/// Serialises (serde) as a JSON object with these field names.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HullReport {
    /// Nodes of the topology (§3.1 vertices).
    pub nodes: usize,
    /// Edges of the topology (§3.1: curve stretches between nodes), including those bounding no
    /// face.
    pub edges: usize,
    /// Faces that became patches (§3.2.1).
    pub faces: usize,
    /// Patches by number of sides: `{3: …, 4: …, 5: …}` (§3.2.1 three-, four-, N-sided).
    pub faces_by_sides: BTreeMap<usize, usize>,
    /// Faces of the topology that could not be patched (each is named in `warnings`).
    pub skipped_faces: usize,
    /// Edges used by exactly one patch: the open boundary of the surface (keel, stem, deck …).
    pub open_edges: usize,
    /// Largest distance (m) between a network curve and the patch side that should lie on it,
    /// sampled along every side segment (the patches interpolate the curves, §3.2.1).
    pub max_gap: f64,
    /// Largest angle (degrees) between the two patches' normals across a smooth edge, sampled
    /// along every edge shared by two patches (GC¹ of §3.2.2: ideally 0).
    pub max_normal_angle_deg: f64,
    /// Where that largest normal angle is (on the edge), `None` when no edge is shared.
    pub max_normal_angle_at: Option<DVec3>,
    /// The curve of the edge with that largest normal angle.
    pub max_normal_angle_curve: Option<String>,
    /// Largest angle (degrees) between the normals of two neighbouring mesh faces, inside or
    /// across patches, not across a knuckle: the mesh's own check for folds (above
    /// [`FOLD_ANGLE_DEGREES`](super::FOLD_ANGLE_DEGREES) each is a `fold` warning).
    pub max_neighbour_angle_deg: f64,
    /// Where that largest neighbour angle is (the middle of the mesh edge between them).
    pub max_neighbour_angle_at: Option<DVec3>,
    /// Chains of free edges off the hull's boundary (each a `hole` warning).
    pub holes: usize,
    /// Folded patches, folded pairs of patches and patches out of their box (each a `fold`
    /// warning).
    pub folds: usize,
    /// Per knuckle curve: its name and the smallest and largest angle (degrees) between the two
    /// patches' normals along it (the crease the designer drew, §1 "knuckles").
    pub crease_angles_deg: Vec<(String, f64, f64)>,
    /// Every knuckle edge (G0 crease), in the topology's edge order: its curve, whether the
    /// designer's role or batten's corner rule made it a knuckle, its crease angles and a
    /// polyline along it (so a front end can show which creases were found automatically).
    pub knuckle_edges: Vec<KnuckleEdge>,
    /// Volume (m³) between the surface and the centreplane `y = 0`, closed by lids
    /// perpendicular to the centreplane: `|Σ ȳ·n_y·A|` over the mesh triangles (the divergence
    /// theorem with the field `(0, y, 0)`, exact for the mesh); for the drawn half only.
    pub volume: f64,
    /// Position of every node of the topology (§3.1 vertices), in the topology's order.
    pub node_positions: Vec<DVec3>,
    /// What meets at every node (crossing, end to end, T-joint …), as
    /// [`Topology::node_kinds`](crate::Topology::node_kinds).
    pub node_kinds: Vec<NodeKind>,
    /// Every topology diagnostic, every ribbon and patch warning and every skipped face, as data
    /// naming the curves and the place (§5.2: the system tells the designer what it resolved).
    pub warnings: Vec<Warning>,
}

/// Samples per side segment for the gap between patch and curve (ends included).
const GAP_SAMPLES: usize = 16;
/// Samples per shared edge for the normal angle (at the midpoints of 16 equal parameter
/// intervals, so the corners, where a patch's normal comes from one-sided differences of two
/// sides at once, are not sampled).
const NORMAL_SAMPLES: usize = 16;

/// One use of an edge by a patch: which patch, which side and segment of it, and whether the
/// side runs along the edge's curve.
#[derive(Clone, Copy, Debug)]
struct Use {
    patch: usize,
    side: usize,
    segment: usize,
    forward: bool,
}

/// The smallest and largest normal angle (degrees) sampled across one shared edge, and where
/// the largest is.
#[derive(Clone, Copy, Debug)]
struct EdgeAngles {
    edge: usize,
    lo: f64,
    hi: f64,
    hi_at: DVec3,
}

/// `Σ ȳ · (area vector)_y` over the triangles: the volume between the mesh and `y = 0`, closed
/// by lids perpendicular to the centreplane (divergence theorem with the field `(0, y, 0)`:
/// the centreplane has `y = 0` and the lids `n_y = 0`, so only the surface contributes, and
/// `y` is linear on each triangle, so the sum is exact for the triangles).
///
/// A (generally non-planar) quad counts as the mean of its two triangulations, so the result
/// does not depend on which corner the quad starts at (curve directions and order in the
/// network do not change the volume).
pub(crate) fn signed_volume(mesh: &SurfaceMesh) -> f64 {
    polygons_volume(|v| DVec3::from(mesh.positions[v as usize]), mesh.faces())
}

/// One face's mesh's share, before welding, of the two figures a build checks on the welded
/// mesh: the y component of its area vector ([`polygons_area_vector`]), whose sign over all faces tells
/// which way the mesh is turned, and its volume ([`signed_volume`]), which must be finite.
/// Kept per face, so a live rebuild adds up the faces' shares instead of running over the
/// whole mesh; the full build adds up the same shares, so both decide alike, bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct MeshShares {
    /// Σ of the y components of the polygons' area vectors.
    pub(crate) area_y: f64,
    /// The signed volume of the polygons against `y = 0`.
    pub(crate) volume: f64,
}

impl MeshShares {
    /// The shares of one face's mesh.
    pub(crate) fn of(mesh: &FaceMesh) -> MeshShares {
        let p = |v: u32| mesh.positions()[v as usize];
        MeshShares {
            area_y: polygons_area_vector(p, mesh.polygons()).y,
            volume: polygons_volume(p, mesh.polygons()),
        }
    }

    /// The shares of several meshes together, added in order.
    pub(crate) fn total<'a>(shares: impl Iterator<Item = &'a MeshShares>) -> MeshShares {
        shares.fold(MeshShares::default(), |acc, s| MeshShares {
            area_y: acc.area_y + s.area_y,
            volume: acc.volume + s.volume,
        })
    }
}

/// Σ of the area vectors of the polygons `polygons` (vertex indices) over the positions `p`
/// (the polygons fanned into triangles from their first vertex): their mean normal times their
/// area.
fn polygons_area_vector<'a>(
    p: impl Fn(u32) -> DVec3,
    polygons: impl Iterator<Item = &'a [u32]>,
) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for face in polygons {
        let a = p(face[0]);
        for w in face[1..].windows(2) {
            let (b, c) = (p(w[0]), p(w[1]));
            sum += (b - a).cross(c - a) * 0.5;
        }
    }
    sum
}

/// [`signed_volume`] of the polygons `polygons` (vertex indices) over the positions `p`.
fn polygons_volume<'a>(p: impl Fn(u32) -> DVec3, polygons: impl Iterator<Item = &'a [u32]>) -> f64 {
    let tri = |a: DVec3, b: DVec3, c: DVec3| (a.y + b.y + c.y) / 6.0 * (b - a).cross(c - a).y;
    let mut sum = 0.0;
    for face in polygons {
        if let [a, b, c, d] = *face {
            let (a, b, c, d) = (p(a), p(b), p(c), p(d));
            sum += 0.5 * (tri(a, b, c) + tri(a, c, d) + tri(b, c, d) + tri(b, d, a));
        } else {
            let a = p(face[0]);
            for w in face[1..].windows(2) {
                sum += tri(a, p(w[0]), p(w[1]));
            }
        }
    }
    sum
}

/// The normal of `patch` at fraction `lambda` (of the segment's own parameter, from the
/// edge's `t0`) of the edge it uses as segment `seg` of side `side`.
fn edge_normal_at(patch: &Patch, side: usize, seg: usize, forward: bool, lambda: f64) -> DVec3 {
    let local = if forward { lambda } else { 1.0 - lambda };
    let s = patch.segment_side_parameter(side, seg, local);
    patch.boundary_normal(side, s)
}

/// What the build found besides the patches, for [`report`].
pub(crate) struct Findings<'a> {
    /// Why each edge is a knuckle (`None` for a smooth edge), in the topology's edge order.
    pub(crate) knuckle: &'a [Option<Knuckle>],
    /// Faces of the topology that could not be patched.
    pub(crate) skipped_faces: usize,
    /// The warnings gathered on the way.
    pub(crate) warnings: Vec<Warning>,
    /// The model tolerance of the build (the near-miss distance decides what lies in the
    /// centreplane and how far a patch may stand out of its box).
    pub(crate) tolerance: Tolerance,
}

/// Build the report from the built patches and the mesh.
pub(crate) fn report(
    network: &Network,
    topology: &Topology,
    patched: &[PatchedFace],
    mesh: &SurfaceMesh,
    findings: Findings<'_>,
) -> HullReport {
    let brep = &topology.brep;
    let curves = network.curves();
    let knuckle = findings.knuckle;
    let mut faces_by_sides = BTreeMap::new();
    for p in patched {
        *faces_by_sides.entry(p.patch.sides()).or_insert(0) += 1;
    }
    let mut uses: Vec<Vec<Use>> = vec![Vec::new(); brep.edges.len()];
    for (pi, p) in patched.iter().enumerate() {
        for (si, side) in p.layout.iter().enumerate() {
            for (ki, seg) in side.iter().enumerate() {
                uses[seg.edge].push(Use {
                    patch: pi,
                    side: si,
                    segment: ki,
                    forward: seg.forward,
                });
            }
        }
    }
    let free: Vec<usize> = (0..uses.len()).filter(|&k| uses[k].len() == 1).collect();
    let open_edges = free.len();
    let mut warnings = findings.warnings;
    let holes = hole_warnings(network, topology, &free, findings.tolerance);
    let boxes = boundary_boxes(network, topology, patched);
    let folds = fold_findings(topology, patched, mesh, knuckle, &boxes, findings.tolerance);
    let (hole_count, fold_count) = (holes.len(), folds.warnings.len());
    warnings.extend(holes);
    warnings.extend(folds.warnings);

    // Gap between every patch side and its designer curve.
    let max_gap = patched
        .par_iter()
        .map(|PatchedFace { patch, layout, .. }| {
            let mut worst: f64 = 0.0;
            for (si, side) in layout.iter().enumerate() {
                for (ki, &LayoutSegment { edge, .. }) in side.iter().enumerate() {
                    let curve = &curves[brep.edges[edge].curve].curve;
                    for j in 0..=GAP_SAMPLES {
                        let lam = j as f64 / GAP_SAMPLES as f64;
                        let s = patch.segment_side_parameter(si, ki, lam);
                        let t = patch.segment_curve_parameter(si, ki, lam);
                        let gap = (patch.side_point(si, s) - curve.point(t)).length();
                        worst = worst.max(gap);
                    }
                }
            }
            worst
        })
        .reduce(|| 0.0, f64::max);

    // Normal angles across every edge shared by two patches.
    let angles: Vec<EdgeAngles> = uses
        .par_iter()
        .enumerate()
        .filter(|(_, u)| u.len() == 2)
        .filter_map(|(edge, u)| {
            let normal = |u: &Use, lam| {
                edge_normal_at(&patched[u.patch].patch, u.side, u.segment, u.forward, lam)
            };
            let (mut lo, mut hi, mut hi_lam) = (f64::INFINITY, 0.0f64, 0.5);
            for j in 0..NORMAL_SAMPLES {
                let lam = (j as f64 + 0.5) / NORMAL_SAMPLES as f64;
                let na = normal(&u[0], lam);
                let nb = normal(&u[1], lam);
                if na == DVec3::ZERO || nb == DVec3::ZERO {
                    continue;
                }
                let ang = na.angle_between(nb).to_degrees();
                lo = lo.min(ang);
                if ang >= hi {
                    hi = ang;
                    hi_lam = lam;
                }
            }
            let e = &brep.edges[edge];
            let hi_at = curves[e.curve].curve.point(e.t0 + hi_lam * (e.t1 - e.t0));
            (lo <= hi).then_some(EdgeAngles {
                edge,
                lo,
                hi,
                hi_at,
            })
        })
        .collect();
    let mut max_normal_angle_deg: f64 = 0.0;
    let mut max_normal_angle_edge: Option<(usize, DVec3)> = None;
    let mut creases: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    let mut edge_creases: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    for &EdgeAngles {
        edge,
        lo,
        hi,
        hi_at,
    } in &angles
    {
        if knuckle[edge].is_some() {
            edge_creases.insert(edge, (lo, hi));
            let c = creases
                .entry(brep.edges[edge].curve)
                .or_insert((f64::INFINITY, 0.0));
            c.0 = c.0.min(lo);
            c.1 = c.1.max(hi);
        } else if hi >= max_normal_angle_deg {
            max_normal_angle_deg = hi;
            max_normal_angle_edge = Some((edge, hi_at));
        }
    }
    let crease_angles_deg = creases
        .into_iter()
        .map(|(c, (lo, hi))| (curves[c].name.clone(), lo, hi))
        .collect();

    HullReport {
        nodes: topology.node_count(),
        edges: topology.edge_count(),
        faces: patched.len(),
        faces_by_sides,
        skipped_faces: findings.skipped_faces,
        open_edges,
        max_gap,
        max_normal_angle_deg,
        max_normal_angle_at: max_normal_angle_edge.map(|(_, at)| at),
        max_normal_angle_curve: max_normal_angle_edge
            .map(|(edge, _)| curves[brep.edges[edge].curve].name.clone()),
        max_neighbour_angle_deg: folds.max_angle_deg,
        max_neighbour_angle_at: folds.max_angle_at,
        holes: hole_count,
        folds: fold_count,
        crease_angles_deg,
        knuckle_edges: knuckle_report(network, topology, knuckle, &edge_creases),
        volume: signed_volume(mesh).abs(),
        node_positions: brep.vertices.iter().map(|v| v.position).collect(),
        node_kinds: topology.node_kinds(),
        warnings,
    }
}
