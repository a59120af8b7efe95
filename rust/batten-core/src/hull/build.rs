//! The pipeline of [`build_hull`](super::build_hull): faces of the topology to patch boundaries
//! and ribbons (H-rep paper §3.2), patches, tessellation and orientation.

use std::collections::BTreeSet;

use glam::DVec3;
use rayon::prelude::*;

use super::knuckles::{knuckle_edges, Knuckle};
use super::report::{self, PatchLayout};
use super::ribbons::{one_sided_normal, shared_normal};
use super::{HullOptions, HullSurface};
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::network::Network;
use crate::patch::{
    tessellate_patches, EdgeNormal, FaceBoundary, Patch, PatchKind, PatchOptions, Side, SideParam,
    SideRibbon, SideSegment, SurfaceMesh, MAX_SIDES,
};
use crate::tolerance::Tolerance;
use crate::topo::{TopoFace, Topology};

/// What the hull needs of one edge of the topology that bounds a region.
#[derive(Clone, Debug)]
pub(crate) struct EdgeInfo {
    /// The edge as a side segment along its curve (`t0 → t1`, snapped onto knots whose
    /// points coincide with the node within the tolerance), named, with its node positions.
    /// Its curve is the designer curve cut to `[t0, t1]` (same parameterisation): at a corner
    /// point of the curve at a node, evaluation and derivatives then belong to this edge's
    /// side of the corner, whichever direction a face runs along it.
    pub(crate) segment: SideSegment,
    /// d/dt at `t0` (the one-sided derivative of this edge).
    pub(crate) start_tangent: DVec3,
    /// d/dt at `t1` (the one-sided derivative of this edge).
    pub(crate) end_tangent: DVec3,
}

/// `t` moved onto the nearest knot of `curve` whose point lies within the model tolerance of
/// C(t). A node found by the junction solver a hair beside a knot (at `1 + 2e-16` next to a
/// double knot, or 1e-8 beside a polyline's corner once coordinates went through Blender's
/// float32) would otherwise leave a sliver span at the end of the edge's curve, where the
/// derivatives describe the wrong side of the corner and the patch folds. Points that
/// coincide within the tolerance are the same point, so the knot is the node. The node
/// position itself is kept ([`SideSegment::with_nodes`]).
fn snap_to_knot(curve: &NurbsCurve, t: f64, tolerance: Tolerance) -> f64 {
    let (a, b) = curve.domain();
    let at = curve.point(t);
    curve
        .knots()
        .iter()
        .copied()
        .filter(|&k| k >= a && k <= b && k != t)
        .filter(|&k| (curve.point(k) - at).length() <= tolerance.get())
        .min_by(|x, y| (x - t).abs().total_cmp(&(y - t).abs()))
        .unwrap_or(t)
}

/// The designer curve restricted to `[t0, t1]` (split at interior ends; the parameterisation
/// is kept). Falls back to the whole curve if a split is refused.
fn edge_curve(curve: &NurbsCurve, t0: f64, t1: f64) -> NurbsCurve {
    let (a, b) = curve.domain();
    let mut c = curve.clone();
    if t0 > a && t0 < b {
        if let Ok((_, right)) = c.split(t0) {
            c = right;
        }
    }
    if t1 < b && t1 > c.domain().0 {
        if let Ok((left, _)) = c.split(t1) {
            c = left;
        }
    }
    c
}

/// A non-zero tangent of `curve` at `t` (first derivative, else second, else the chord
/// direction of the whole edge).
fn tangent(curve: &NurbsCurve, t: f64, chord: DVec3) -> DVec3 {
    let d = curve.derivs(t);
    [d.d1, d.d2, chord]
        .into_iter()
        .find(|v| v.is_finite() && v.length() > 0.0)
        .unwrap_or(DVec3::ZERO)
}

fn edge_info(network: &Network, topology: &Topology, k: usize, tolerance: Tolerance) -> EdgeInfo {
    let e = &topology.brep.edges[k];
    let nc = &network.curves()[e.curve];
    let (t0, t1) = (
        snap_to_knot(&nc.curve, e.t0, tolerance),
        snap_to_knot(&nc.curve, e.t1, tolerance),
    );
    let (t0, t1) = if t0 < t1 { (t0, t1) } else { (e.t0, e.t1) };
    let curve = edge_curve(&nc.curve, t0, t1);
    let (p0, p1) = (
        topology.brep.vertices[e.start.index()].position,
        topology.brep.vertices[e.end.index()].position,
    );
    let chord = curve.point(t1) - curve.point(t0);
    let start_tangent = tangent(&curve, t0, chord);
    let end_tangent = tangent(&curve, t1, chord);
    EdgeInfo {
        segment: SideSegment::new(curve, t0, t1)
            .named(nc.name.clone())
            .with_nodes(p0, p1),
        start_tangent,
        end_tangent,
    }
}

/// A face described for the patch module, and where each of its edges went.
struct FacePlan {
    boundary: FaceBoundary,
    ribbons: Vec<SideRibbon>,
    layout: PatchLayout,
}

/// The sides of `face` as patch sides (composite where the topology's side has several
/// edges), oriented along the loop, with ribbons: the shared normal of a smooth edge, the
/// face's own one-sided normal on a knuckle edge, `None` where no crossing curve qualifies.
fn plan_face(
    face: &TopoFace,
    topology: &Topology,
    edges: &[Option<EdgeInfo>],
    knuckle: &[Option<Knuckle>],
    shared: &[Option<EdgeNormal>],
) -> Result<FacePlan, String> {
    let n_sides = face.sides.len();
    if !(3..=MAX_SIDES).contains(&n_sides) {
        return Err(format!(
            "it has {n_sides} sides; a patch needs 3 to {MAX_SIDES} (H-rep §3.2.1)"
        ));
    }
    let n = face.edges.len();
    let first = face.sides[0]
        .edges
        .first()
        .ok_or_else(|| "its first side has no edges".to_string())?;
    let start = face
        .edges
        .iter()
        .position(|e| e == first)
        .ok_or_else(|| "its sides do not follow its loop".to_string())?;
    let mut cursor = 0;
    let mut sides = Vec::with_capacity(n_sides);
    let mut ribbons = Vec::with_capacity(n_sides);
    let mut layout = Vec::with_capacity(n_sides);
    for side in &face.sides {
        let mut segments = Vec::with_capacity(side.edges.len());
        let mut normals = Vec::with_capacity(side.edges.len());
        let mut placed = Vec::with_capacity(side.edges.len());
        for edge in &side.edges {
            let pos = (start + cursor) % n;
            cursor += 1;
            if face.edges[pos] != *edge || cursor > n {
                return Err("its sides do not follow its loop".to_string());
            }
            let k = edge.index();
            let info = edges[k]
                .as_ref()
                .ok_or_else(|| "an edge of it bounds no region".to_string())?;
            let fwd = face.forward[pos];
            segments.push(if fwd {
                info.segment.clone()
            } else {
                info.segment.reversed()
            });
            let normal = if knuckle[k].is_some() {
                one_sided_normal(face, pos, topology, edges).map_err(|e| e.to_string())?
            } else {
                shared[k].clone()
            };
            normals.push(normal);
            placed.push((k, fwd));
        }
        sides.push(Side::new(segments));
        ribbons.push(SideRibbon { segments: normals });
        layout.push(placed);
    }
    if cursor != n {
        return Err("its sides do not cover its loop".to_string());
    }
    Ok(FacePlan {
        boundary: FaceBoundary::new(sides),
        ribbons,
        layout,
    })
}

fn face_label(topology: &Topology, fi: usize, face: &TopoFace) -> String {
    format!(
        "face {fi} (curves '{}')",
        topology.names(&face.curves).join("', '")
    )
}

/// Faces of the mesh touching a non-finite vertex, as patch indices.
fn non_finite_patches(mesh: &SurfaceMesh) -> BTreeSet<usize> {
    let mut bad = BTreeSet::new();
    for (f, vs) in mesh.faces().enumerate() {
        if vs
            .iter()
            .any(|&v| !mesh.positions[v as usize].iter().all(|c| c.is_finite()))
        {
            bad.insert(mesh.face_patch[f] as usize);
        }
    }
    bad
}

/// Reverse every face of the mesh (first vertex kept).
fn flip(mesh: &mut SurfaceMesh) {
    let mut start = 0;
    for &k in &mesh.face_sizes {
        let k = k as usize;
        mesh.face_vertices[start + 1..start + k].reverse();
        start += k;
    }
}

pub(crate) fn build(network: &Network, options: &HullOptions) -> Result<HullSurface, Error> {
    if options.resolution == 0 {
        return Err(Error::NoSurface(
            "tessellation resolution 0 gives no mesh; use at least 1 interval per edge".to_string(),
        ));
    }
    let topology = Topology::build(network, options.tolerance)?;
    let mut warnings: Vec<String> = topology.diagnostics.iter().map(|d| d.to_string()).collect();
    if topology.faces.is_empty() {
        let why = if warnings.is_empty() {
            "the curves enclose no region".to_string()
        } else {
            warnings.join("; ")
        };
        return Err(Error::NoSurface(format!(
            "network '{}' has no faces: {why}",
            network.name
        )));
    }
    let brep = &topology.brep;
    let edges: Vec<Option<EdgeInfo>> = (0..brep.edges.len())
        .into_par_iter()
        .map(|k| {
            brep.edges[k]
                .half_edges
                .is_some()
                .then(|| edge_info(network, &topology, k, options.tolerance))
        })
        .collect();
    let mut at_vertex: Vec<Vec<(usize, bool)>> = vec![Vec::new(); brep.vertices.len()];
    for (k, e) in brep.edges.iter().enumerate() {
        if edges[k].is_some() {
            at_vertex[e.start.index()].push((k, true));
            at_vertex[e.end.index()].push((k, false));
        }
    }
    let near_miss = options.tolerance.near_miss();
    let knuckle = knuckle_edges(network, &topology, &edges, &at_vertex, near_miss);
    let shared_results: Vec<Result<Option<EdgeNormal>, String>> = (0..brep.edges.len())
        .into_par_iter()
        .map(|k| {
            if knuckle[k].is_some() || edges[k].is_none() {
                Ok(None)
            } else {
                shared_normal(k, &topology, &edges, &at_vertex).map_err(|e| e.to_string())
            }
        })
        .collect();
    let shared: Vec<Option<EdgeNormal>> = shared_results
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            r.unwrap_or_else(|msg| {
                warnings.push(format!(
                    "edge {k} of curve '{}': no ribbon from its crossing curves ({msg}); the faces use their default ribbons",
                    topology.curve_names[brep.edges[k].curve]
                ));
                None
            })
        })
        .collect();

    let patch_options = PatchOptions {
        kind: PatchKind::Auto,
        param: SideParam::ArcLength,
        tolerance: options.tolerance,
    };
    let built: Vec<Result<(Patch, PatchLayout), String>> = topology
        .faces
        .par_iter()
        .map(|face| {
            let plan = plan_face(face, &topology, &edges, &knuckle, &shared)?;
            let patch = Patch::try_new(&plan.boundary, &plan.ribbons, &patch_options)
                .map_err(|e| e.to_string())?;
            Ok((patch, plan.layout))
        })
        .collect();
    let mut patches = Vec::new();
    let mut layouts = Vec::new();
    let mut face_of = Vec::new();
    let mut skipped = 0;
    for (fi, r) in built.into_iter().enumerate() {
        let label = face_label(&topology, fi, &topology.faces[fi]);
        match r {
            Ok((patch, layout)) => {
                for w in patch.warnings() {
                    warnings.push(format!("{label}: {w}"));
                }
                patches.push(patch);
                layouts.push(layout);
                face_of.push(fi);
            }
            Err(msg) => {
                skipped += 1;
                warnings.push(format!("{label} is not patched: {msg}"));
            }
        }
    }

    // Tessellate; drop any patch that produced a non-finite point and try again.
    let mut mesh = loop {
        if patches.is_empty() {
            return Err(Error::NoSurface(format!(
                "network '{}': none of its {} faces could be patched: {}",
                network.name,
                topology.faces.len(),
                warnings.join("; ")
            )));
        }
        let mesh = tessellate_patches(&patches, options.resolution)
            .map_err(|e| Error::NoSurface(format!("network '{}': {e}", network.name)))?;
        let bad = non_finite_patches(&mesh);
        if bad.is_empty() {
            break mesh;
        }
        for &p in bad.iter().rev() {
            let fi = face_of[p];
            warnings.push(format!(
                "{} is not patched: its surface has non-finite points",
                face_label(&topology, fi, &topology.faces[fi])
            ));
            skipped += 1;
            patches.remove(p);
            layouts.remove(p);
            face_of.remove(p);
        }
    };
    if report::area_vector(&mesh).y < 0.0 {
        flip(&mut mesh);
    }
    let report = report::report(
        network, &topology, &patches, &layouts, &knuckle, &mesh, skipped, warnings,
    );
    // The mesh names the topology's face of every polygon (skipped faces leave gaps).
    for p in &mut mesh.face_patch {
        *p = face_of[*p as usize] as u32;
    }
    Ok(HullSurface { mesh, report })
}
