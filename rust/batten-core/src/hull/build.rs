//! The pipeline of [`build_hull`](super::build_hull): faces of the topology to patch boundaries
//! and ribbons (H-rep paper §3.2), patches, tessellation and orientation.

use std::collections::BTreeSet;

use glam::DVec3;
use rayon::prelude::*;

use super::edges::FaceEdges;
use super::knuckles::{knuckle_edges, Knuckle};
use super::patched::{LayoutSegment, PatchLayout, PatchedFace};
use super::report::{self, Findings};
use super::ribbons::{one_sided_normal, shared_normal};
use super::warning::{FaceError, Warning, WarningKind};
use super::{HullOptions, HullSurface};
use crate::error::Error;
use crate::network::Network;
use crate::patch::{
    tessellate_patches, EdgeNormal, FaceBoundary, Patch, PatchKind, PatchOptions, PatchWarning,
    Side, SideParam, SideRibbon, SurfaceMesh, MAX_SIDES,
};
use crate::topo::{TopoFace, Topology};

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
    edges: &FaceEdges,
    knuckle: &[Option<Knuckle>],
    shared: &[Option<EdgeNormal>],
) -> Result<FacePlan, FaceError> {
    let n_sides = face.sides.len();
    if !(3..=MAX_SIDES).contains(&n_sides) {
        return Err(FaceError::SideCount { sides: n_sides });
    }
    let n = face.edges.len();
    let first = face.sides[0]
        .edges
        .first()
        .ok_or(FaceError::EmptyFirstSide)?;
    let start = face
        .edges
        .iter()
        .position(|e| e == first)
        .ok_or(FaceError::SidesOffLoop)?;
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
                return Err(FaceError::SidesOffLoop);
            }
            let k = edge.index();
            let info = edges.info[k].as_ref().ok_or(FaceError::EdgeOutsideRegion)?;
            let fwd = face.forward[pos];
            segments.push(if fwd {
                info.segment.clone()
            } else {
                info.segment.reversed()
            });
            let normal = if knuckle[k].is_some() {
                one_sided_normal(face, pos, topology, &edges.info)?
            } else {
                shared[k].clone()
            };
            normals.push(normal);
            placed.push(LayoutSegment {
                edge: k,
                forward: fwd,
            });
        }
        sides.push(Side::new(segments));
        ribbons.push(SideRibbon { segments: normals });
        layout.push(placed);
    }
    if cursor != n {
        return Err(FaceError::SidesShortOfLoop);
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

/// A warning about face `fi`: its curves, and as its place the mean of its nodes.
fn face_warning(
    topology: &Topology,
    fi: usize,
    kind: WarningKind,
    message: String,
    error: Option<FaceError>,
) -> Warning {
    let face = &topology.faces[fi];
    let brep = &topology.brep;
    let sum: DVec3 = face
        .edges
        .iter()
        .zip(&face.forward)
        .map(|(e, &fwd)| {
            let e = &brep.edges[e.index()];
            brep.vertices[if fwd { e.start } else { e.end }.index()].position
        })
        .sum();
    Warning {
        kind,
        message,
        curves: topology
            .names(&face.curves)
            .into_iter()
            .map(str::to_owned)
            .collect(),
        location: Some(sum / face.edges.len().max(1) as f64),
        error,
    }
}

/// The warning for a patch's own repair of face `fi`.
fn patch_warning(topology: &Topology, fi: usize, label: &str, w: &PatchWarning) -> Warning {
    let kind = match w {
        PatchWarning::CornerAngle { .. } => WarningKind::DegenerateCorner,
    };
    face_warning(topology, fi, kind, format!("{label}: {w}"), None)
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

/// The pipeline of [`build_hull`](super::build_hull), step by step (see there).
pub(crate) fn build(network: &Network, options: &HullOptions) -> Result<HullSurface, Error> {
    options.check()?;
    let topology = Topology::build(network, options.tolerance)?;
    let mut warnings: Vec<Warning> = topology.diagnostics.iter().map(Warning::from).collect();
    if topology.faces.is_empty() {
        let why = if warnings.is_empty() {
            "the curves enclose no region".to_string()
        } else {
            join(&warnings)
        };
        return Err(Error::NoSurface(format!(
            "network '{}' has no faces: {why}",
            network.name
        )));
    }
    let brep = &topology.brep;
    let edges = FaceEdges::new(network, &topology, options.tolerance);
    let near_miss = options.tolerance.near_miss();
    let knuckle = knuckle_edges(network, &topology, &edges, near_miss);
    let shared_results: Vec<Result<Option<EdgeNormal>, FaceError>> = (0..brep.edges.len())
        .into_par_iter()
        .map(|k| {
            if knuckle[k].is_some() || edges.info[k].is_none() {
                Ok(None)
            } else {
                Ok(shared_normal(k, &topology, &edges)?)
            }
        })
        .collect();
    let shared: Vec<Option<EdgeNormal>> = shared_results
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            r.unwrap_or_else(|error| {
                warnings.push(no_ribbon_warning(network, &topology, k, error));
                None
            })
        })
        .collect();

    let patch_options = PatchOptions {
        kind: PatchKind::Auto,
        param: SideParam::ArcLength,
        tolerance: options.tolerance,
    };
    let built: Vec<Result<(Patch, PatchLayout), FaceError>> = topology
        .faces
        .par_iter()
        .map(|face| {
            let plan = plan_face(face, &topology, &edges, &knuckle, &shared)?;
            let patch = Patch::try_new(&plan.boundary, &plan.ribbons, &patch_options)?;
            Ok((patch, plan.layout))
        })
        .collect();
    let mut patched: Vec<PatchedFace> = Vec::new();
    let mut skipped = 0;
    for (fi, r) in built.into_iter().enumerate() {
        let label = face_label(&topology, fi, &topology.faces[fi]);
        match r {
            Ok((patch, layout)) => {
                for w in patch.warnings() {
                    warnings.push(patch_warning(&topology, fi, &label, w));
                }
                patched.push(PatchedFace {
                    face: fi,
                    patch,
                    layout,
                });
            }
            Err(error) => {
                skipped += 1;
                warnings.push(face_warning(
                    &topology,
                    fi,
                    WarningKind::FaceNotPatched,
                    format!("{label} is not patched: {error}"),
                    Some(error),
                ));
            }
        }
    }

    // Tessellate; drop any patch that produced a non-finite point and try again.
    let mut mesh = loop {
        if patched.is_empty() {
            return Err(Error::NoSurface(format!(
                "network '{}': none of its {} faces could be patched: {}",
                network.name,
                topology.faces.len(),
                join(&warnings)
            )));
        }
        let mesh = tessellate_patches(&patched, options.resolution)?;
        let bad = non_finite_patches(&mesh);
        if bad.is_empty() {
            break mesh;
        }
        for &p in bad.iter().rev() {
            let fi = patched.remove(p).face;
            let label = face_label(&topology, fi, &topology.faces[fi]);
            warnings.push(face_warning(
                &topology,
                fi,
                WarningKind::NonFiniteSurface,
                format!("{label} is not patched: its surface has non-finite points"),
                None,
            ));
            skipped += 1;
        }
    };
    let patches_outward = report::area_vector(&mesh).y >= 0.0;
    if !patches_outward {
        flip(&mut mesh);
    }
    let findings = Findings {
        knuckle: &knuckle,
        skipped_faces: skipped,
        warnings,
        tolerance: options.tolerance,
    };
    let report = report::report(network, &topology, &patched, &mesh, findings);
    let figures = [report.volume, report.max_gap, report.max_normal_angle_deg];
    if !figures.iter().all(|f| f.is_finite()) {
        return Err(Error::NoSurface(format!(
            "network '{}': the surface's figures overflow f64 (volume {}, max gap {}); its coordinates are too large",
            network.name, report.volume, report.max_gap
        )));
    }
    // The mesh names the topology's face of every polygon (skipped faces leave gaps).
    for p in &mut mesh.face_patch {
        *p = patched[*p as usize].face as u32;
    }
    let patch_faces = patched.iter().map(|p| p.face).collect();
    let (patches, layouts) = patched.into_iter().map(|p| (p.patch, p.layout)).unzip();
    Ok(HullSurface {
        mesh,
        report,
        patches,
        patch_faces,
        layouts,
        patches_outward,
    })
}

/// The warnings' messages, joined for an error message.
fn join(warnings: &[Warning]) -> String {
    warnings
        .iter()
        .map(|w| w.message.as_str())
        .collect::<Vec<_>>()
        .join("; ")
}

/// The warning for smooth edge `k`, whose crossing curves gave no ribbon.
fn no_ribbon_warning(
    network: &Network,
    topology: &Topology,
    k: usize,
    error: FaceError,
) -> Warning {
    let e = &topology.brep.edges[k];
    let name = &topology.curve_names[e.curve];
    Warning {
        kind: WarningKind::NoRibbon,
        message: format!(
            "edge {k} of curve '{name}': no ribbon from its crossing curves ({error}); the faces use their default ribbons"
        ),
        curves: vec![name.clone()],
        location: Some(network.curves()[e.curve].curve.point(0.5 * (e.t0 + e.t1))),
        error: Some(error),
    }
}
