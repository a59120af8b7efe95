//! The pipeline of [`build_hull`](super::build_hull): faces of the topology to patch boundaries
//! and ribbons (H-rep paper §3.2), patches, tessellation and orientation.

use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;

use super::edges::FaceEdges;
use super::flats::held_on_planes;
use super::folds::{face_folds, face_mesh_folds, in_plane_folds, MeshFolds, FOLD_ANGLE_DEGREES};
use super::knuckles::{corner_points, curve_corner_points, knuckle_edges, Knuckle};
use super::patched::{LayoutSegment, PatchLayout, PatchedFace};
use super::report::{self, Findings, MeshShares};
use super::ribbons::{beyond, one_sided_normal, shared_normal};
use super::warning::{FaceError, Warning, WarningKind};
use super::{HullOptions, HullReport, HullSurface};
use crate::error::Error;
use crate::network::Network;
use crate::patch::{
    weld_face_meshes_with, EdgeNormal, FaceBoundary, FaceMesh, Patch, PatchError, PatchKind,
    PatchOptions, PatchWarning, Side, SideParam, SideRibbon, SurfaceMesh, Weld, CUSP_DEGREES,
    MAX_SIDES,
};
use crate::tolerance::Tolerance;
use crate::topo::{TopoFace, Topology};

/// A face described for the patch module, and where each of its edges went.
struct FacePlan {
    boundary: FaceBoundary,
    ribbons: Vec<SideRibbon>,
    layout: PatchLayout,
    /// Per side: whether every edge of it is a smooth edge shared with another face, whose
    /// patch takes the same tangent plane along it ([`face_folds`]).
    smooth: Vec<bool>,
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
    inner: &[bool],
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
    let mut smooth = Vec::with_capacity(n_sides);
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
        smooth.push(
            side.edges
                .iter()
                .all(|e| knuckle[e.index()].is_none() && inner[e.index()]),
        );
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
        smooth,
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
        PatchWarning::KnuckleInSide { .. } => WarningKind::KnuckleInFace,
        PatchWarning::SideBlended { .. }
        | PatchWarning::FlatSideBlended { .. }
        | PatchWarning::CuspSideBlended { .. } => WarningKind::SideBlended,
    };
    face_warning(topology, fi, kind, format!("{label}: {w}"), None)
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

/// What one face of the topology became.
#[derive(Clone, Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "always held in an Arc (Stages::faces): the small variants waste no memory per face"
)]
pub(crate) enum FaceOutcome {
    /// A patch, where its edges went, and the patch's own mesh (before welding).
    Built {
        patch: Patch,
        layout: PatchLayout,
        mesh: FaceMesh,
        /// The mesh's share of the checks on the welded mesh.
        shares: MeshShares,
        /// How finely the face's own mesh needs to be made ([`refinement`]).
        need: Need,
        /// The intervals `mesh` has on each side segment (all sides' segments in order).
        counts: Vec<usize>,
        /// The largest angle between neighbouring polygons of the mesh with `counts` of the
        /// patch [`unfolded`] chose (degrees): `mesh`'s, unless `patch` replaced that one.
        worst: f64,
        /// The patch [`unfolded`] chose, where its mesh with `counts` folded and `patch` is the
        /// side-blended patch taken instead ([`refolded`]): what a mesh with other counts
        /// starts from again, so a live rebuild meets the full build's choice.
        unfolded: Option<Patch>,
    },
    /// No patch: why.
    Failed(FaceError),
    /// A patch whose surface has non-finite points: dropped.
    NonFinite,
}

/// Everything a build computes on its way to the mesh, per edge and per face: what
/// [`LiveHull`](super::LiveHull) keeps so that a rebuild computes again only what a moved
/// curve reaches.
#[derive(Clone, Debug)]
pub(crate) struct Stages {
    pub(crate) topology: Topology,
    pub(crate) edges: FaceEdges,
    /// The corner points of every curve.
    pub(crate) corners: Vec<Vec<DVec3>>,
    pub(crate) knuckle: Vec<Option<Knuckle>>,
    /// Per edge: whether it bounds two faces ([`inner_edges`]).
    pub(crate) inner: Vec<bool>,
    /// The shared normal field of every smooth edge.
    pub(crate) shared: Vec<Option<EdgeNormal>>,
    /// Per edge: the warning that its crossing curves gave no ribbon.
    pub(crate) edge_warnings: Vec<Option<Warning>>,
    /// Per topology face (shared with the stages it was kept from).
    pub(crate) faces: Vec<Arc<FaceOutcome>>,
}

/// The topology of `network`, refused with [`Error::NoSurface`] when it has no faces.
fn faced_topology(network: &Network, options: &HullOptions) -> Result<Topology, Error> {
    let topology = Topology::build(network, options.tolerance)?;
    if topology.faces.is_empty() {
        let warnings: Vec<Warning> = topology.diagnostics.iter().map(Warning::from).collect();
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
    Ok(topology)
}

/// Per edge of `topology`: whether it bounds two faces (an inner edge, not the surface's
/// boundary). One pass over the faces' edges, each face counted once per edge.
fn inner_edges(topology: &Topology) -> Vec<bool> {
    let n = topology.brep.edges.len();
    let (mut count, mut last_face) = (vec![0usize; n], vec![usize::MAX; n]);
    for (fi, face) in topology.faces.iter().enumerate() {
        for e in &face.edges {
            let k = e.index();
            if last_face[k] != fi {
                last_face[k] = fi;
                count[k] += 1;
            }
        }
    }
    count.into_iter().map(|c| c == 2).collect()
}

/// The normal field of edge `k` (none for a knuckle or a region-less edge), or the warning
/// that its crossing curves gave none. An inner edge's field (`inner`: it bounds two faces)
/// is held at the normal of each of the network's tangent planes where its curve runs in it
/// (`flats`); a boundary edge's is not, as a surface that ends on a plane need not be tangent
/// to it (a V-bottom's keel).
fn edge_normal(
    k: usize,
    network: &Network,
    tolerance: Tolerance,
    inner: bool,
    topology: &Topology,
    edges: &FaceEdges,
    knuckle: &[Option<Knuckle>],
) -> (Option<EdgeNormal>, Option<Warning>) {
    if knuckle[k].is_some() || edges.info[k].is_none() {
        return (None, None);
    }
    match shared_normal(k, topology, edges, knuckle) {
        Ok(normal) => {
            let planes = network.tangent_planes();
            let held = normal.map(|n| match &edges.info[k] {
                Some(info) if inner && !planes.is_empty() => {
                    held_on_planes(n, &info.segment, planes, tolerance.get())
                }
                _ => n,
            });
            (held, None)
        }
        Err(error) => (
            None,
            Some(no_ribbon_warning(network, topology, k, error.into())),
        ),
    }
}

/// The options every patch of a hull is built with.
fn patch_options(options: &HullOptions) -> PatchOptions {
    PatchOptions {
        kind: PatchKind::Auto,
        param: SideParam::ArcLength,
        tolerance: options.tolerance,
    }
}

/// Faces of more mesh vertices than this are not meshed to look for folds before the whole
/// mesh is known to be indexable (see [`face_outcomes`]).
const FOLD_CHECK_VERTICES: usize = 1 << 20;

/// A side-blended patch replaces a folded corner-based one when its folds
/// ([`MeshFolds::excess`](super::folds::MeshFolds)) are at most this fraction of the other's:
/// where both fold about as badly, the paper's patch stays.
const FALLBACK_GAIN: f64 = 0.5;

/// A face's patch, its mesh at `resolution` when it was made to look for folds, and how many
/// times `resolution` its mesh needs ([`refinement`]): the corner-based patch, or — where its
/// mesh folds ([`face_mesh_folds`]) and the side-blended patch of the same boundary and
/// ribbons folds clearly less ([`FALLBACK_GAIN`]) — that one ([`PatchKind::SideBlend`]). Both
/// are judged on meshes fine enough for the tighter of their turns, so a patch whose coarse
/// mesh only cuts a tight turn short is kept, and a fallback whose coarse mesh steps over a
/// fold of its own is not taken for that. A flat face whose mesh shows no fold is also looked
/// at within its plane ([`flat_unfolded`]). Also the chosen patch's finer mesh, where its
/// need is finer than `resolution` and [`refinement`] made it.
fn unfolded(
    plan: &FacePlan,
    patch: Patch,
    opts: &PatchOptions,
    resolution: usize,
) -> (Patch, Option<FaceMesh>, Need, Option<Made>) {
    if patch.mesh_vertex_count(resolution) > FOLD_CHECK_VERTICES {
        return (patch, None, Need::NONE, None);
    }
    let mesh = patch.face_mesh(resolution);
    if !mesh.is_finite() {
        return (patch, Some(mesh), Need::NONE, None);
    }
    let (need, finer) = refinement(&patch, &mesh, resolution, &plan.smooth);
    if let Some((blended, mesh, (need, finer))) =
        cusp_unfolded(plan, &patch, opts, resolution, &need)
    {
        return (blended, Some(mesh), need, finer);
    }
    if need.folds.pairs == 0 {
        return match flat_unfolded(plan, &patch, opts, resolution) {
            Some((blended, mesh, (need, finer))) => (blended, Some(mesh), need, finer),
            None => (patch, Some(mesh), need, finer),
        };
    }
    let Some((blended, other, (other_need, other_finer))) =
        side_blended_mesh(plan, opts, resolution)
    else {
        return (patch, Some(mesh), need, finer);
    };
    // Both judged at the finer of their levels: a patch's own level's folds are at hand.
    let level = need.times.max(other_need.times);
    let folds_at = |p: &Patch, n: &Need| {
        if n.times == level {
            n.folds
        } else {
            face_folds(p, &p.face_mesh(level * resolution), &plan.smooth)
        }
    };
    let (folds, other_folds) = (folds_at(&patch, &need), folds_at(&blended, &other_need));
    match fallback(&patch, &folds, blended, &other_folds) {
        Some(blended) => (blended, Some(other), other_need, other_finer),
        None => (patch, Some(mesh), need, finer),
    }
}

/// For a face with a cusp (two sides meeting at a corner angle near 0°: repaired by its
/// ribbons, [`PatchWarning::CornerAngle`], or under [`CUSP_DEGREES`] without a repair,
/// [`sharpest_cusp`]), the side-blended patch of the same boundary and
/// ribbons, its mesh and need, where its mesh folds no more than `patch`'s (`need`): a
/// corner-based patch interpolates the tangent plane its two sides span at each corner, and
/// at a cusp they span none (KVLCC2's station 20 runs up the stem and meets it at 1°: the
/// Charrot–Gregory patch there creased 0.79° against its neighbour). None otherwise.
fn cusp_unfolded(
    plan: &FacePlan,
    patch: &Patch,
    opts: &PatchOptions,
    resolution: usize,
    need: &Need,
) -> Option<(Patch, FaceMesh, (Need, Option<Made>))> {
    let (corner, degrees) = patch
        .warnings()
        .iter()
        .find_map(|w| match *w {
            PatchWarning::CornerAngle {
                corner, degrees, ..
            } if degrees.abs() < 90.0 => Some((corner, degrees)),
            _ => None,
        })
        .or_else(|| sharpest_cusp(patch))?;
    let (blended, mesh, other) = side_blended_mesh(plan, opts, resolution)?;
    (other.0.folds.pairs <= need.folds.pairs).then(|| {
        let blended = blended.with_warning(PatchWarning::CuspSideBlended {
            replaced: patch.kind(),
            corner,
            degrees,
        });
        (blended, mesh, other)
    })
}

/// The side parameter step over which [`sharpest_cusp`] takes a side's direction at a corner.
const CUSP_STEP: f64 = 1e-4;

/// The sharpest corner of `patch` under [`CUSP_DEGREES`]: its index and interior angle in
/// degrees, between the directions of its two sides there.
fn sharpest_cusp(patch: &Patch) -> Option<(usize, f64)> {
    let n = patch.sides();
    (0..n)
        .filter_map(|i| {
            let prev = (i + n - 1) % n;
            let p = patch.side_point(i, 0.0);
            let along = patch.side_point(i, CUSP_STEP) - p;
            let back = patch.side_point(prev, 1.0 - CUSP_STEP) - p;
            let degrees = along.angle_between(back).to_degrees();
            (degrees < CUSP_DEGREES).then_some((i, degrees))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// For a flat face whose patch folds within its plane ([`in_plane_folds`]; its mesh shows
/// nothing), the side-blended patch of the same boundary and ribbons, its mesh and need, where
/// that one neither folds within the plane nor on its mesh; None otherwise (nothing to replace,
/// or nothing better).
fn flat_unfolded(
    plan: &FacePlan,
    patch: &Patch,
    opts: &PatchOptions,
    resolution: usize,
) -> Option<(Patch, FaceMesh, (Need, Option<Made>))> {
    let cells = in_plane_folds(patch, opts.tolerance);
    if cells == 0 {
        return None;
    }
    let (blended, mesh, need) = side_blended_mesh(plan, opts, resolution)?;
    (need.0.folds.pairs == 0 && in_plane_folds(&blended, opts.tolerance) == 0).then(|| {
        let blended = blended.with_warning(PatchWarning::FlatSideBlended {
            replaced: patch.kind(),
            cells,
        });
        (blended, mesh, need)
    })
}

/// The side-blended patch of `plan` ([`side_blend`]) with its mesh at `resolution` and the
/// refinement that mesh needs (with the finer mesh [`refinement`] made); None where the
/// patch cannot be made or its mesh is not finite.
fn side_blended_mesh(
    plan: &FacePlan,
    opts: &PatchOptions,
    resolution: usize,
) -> Option<(Patch, FaceMesh, (Need, Option<Made>))> {
    let blended = side_blend(plan, opts)?;
    let mesh = blended.face_mesh(resolution);
    if !mesh.is_finite() {
        return None;
    }
    let need = refinement(&blended, &mesh, resolution, &plan.smooth);
    Some((blended, mesh, need))
}

/// The side-blended patch ([`PatchKind::SideBlend`]) of `plan`'s boundary and ribbons, None
/// where it cannot be made.
fn side_blend(plan: &FacePlan, opts: &PatchOptions) -> Option<Patch> {
    let blend_opts = PatchOptions {
        kind: PatchKind::SideBlend,
        ..*opts
    };
    Patch::try_new(&plan.boundary, &plan.ribbons, &blend_opts).ok()
}

/// `blended`, noted as replacing `patch`, where its mesh folds clearly less than `patch`'s
/// ([`FALLBACK_GAIN`]; `folds` and `other` measured on meshes alike); None otherwise.
fn fallback(patch: &Patch, folds: &MeshFolds, blended: Patch, other: &MeshFolds) -> Option<Patch> {
    (other.excess <= FALLBACK_GAIN * folds.excess).then(|| {
        blended.with_warning(PatchWarning::SideBlended {
            replaced: patch.kind(),
            replaced_pairs: folds.pairs,
            replaced_degrees: folds.worst,
            pairs: other.pairs,
            degrees: other.worst,
        })
    })
}

/// The outcomes of the faces flagged in `dirty` (in parallel), the others taken from `kept`
/// (all faces when `kept` is `None`): patch, then — once the whole mesh is known to be
/// indexable ([`PatchError::MeshTooLarge`](crate::PatchError::MeshTooLarge) otherwise) —
/// the patch's own mesh, checked finite; then every face's mesh made as finely as it and its
/// neighbours need ([`refined`]).
fn face_outcomes(
    stages: &Stages,
    kept: Option<&[Arc<FaceOutcome>]>,
    dirty: &[bool],
    options: &HullOptions,
) -> Result<Vec<Arc<FaceOutcome>>, Error> {
    let opts = patch_options(options);
    type Built = (Patch, PatchLayout, Option<FaceMesh>, Need, Option<Made>);
    let built: Vec<Option<Result<Built, FaceError>>> = stages
        .topology
        .faces
        .par_iter()
        .enumerate()
        .map(|(fi, face)| {
            (dirty[fi] || kept.is_none()).then(|| {
                let plan = plan_face(
                    face,
                    &stages.topology,
                    &stages.edges,
                    &stages.knuckle,
                    &stages.shared,
                    &stages.inner,
                )?;
                let patch = Patch::try_new(&plan.boundary, &plan.ribbons, &opts)?;
                let (patch, mesh, need, finer) = unfolded(&plan, patch, &opts, options.resolution);
                Ok((patch, plan.layout, mesh, need, finer))
            })
        })
        .collect();
    // Counted before anything is meshed: a mesh too large to index is refused up front.
    let total = built.iter().enumerate().fold(0usize, |acc, (fi, b)| {
        let n = match (b, kept) {
            (Some(Ok((patch, ..))), _) => patch.mesh_vertex_count(options.resolution),
            (None, Some(kept)) => match kept[fi].as_ref() {
                FaceOutcome::Built { mesh, .. } => mesh.vertex_count(),
                _ => 0,
            },
            _ => 0,
        };
        acc.saturating_add(n)
    });
    if total >= u32::MAX as usize {
        return Err(PatchError::MeshTooLarge(total).into());
    }
    let (outcomes, made): (Vec<_>, Vec<_>) = built
        .into_par_iter()
        .enumerate()
        .map(|(fi, b)| match b {
            None => (
                Arc::clone(&kept.expect("kept outcomes for the clean faces")[fi]),
                None,
            ),
            Some(Err(error)) => (Arc::new(FaceOutcome::Failed(error)), None),
            Some(Ok((patch, layout, mesh, need, finer))) => {
                let mesh = mesh.unwrap_or_else(|| patch.face_mesh(options.resolution));
                let outcome = Arc::new(if mesh.is_finite() {
                    FaceOutcome::Built {
                        unfolded: None,
                        worst: if need.times == 1 {
                            need.folds.worst
                        } else {
                            face_mesh_folds(&mesh).worst
                        },
                        need,
                        counts: vec![options.resolution; patch.segment_count()],
                        patch,
                        layout,
                        shares: MeshShares::of(&mesh),
                        mesh,
                    }
                } else {
                    FaceOutcome::NonFinite
                });
                (outcome, finer)
            }
        })
        .unzip();
    refined(outcomes, made, stages, options)
}

/// Neighbouring polygons of a face's own mesh more than this apart (degrees) ask for a finer
/// mesh ([`refinement`]): where the surface turns tightly (a stem or a forefoot with a small
/// radius, a bulb's crown), the resolution's polygons are too coarse to follow it, and their
/// angles — which the fold check reads — are the mesh's, not the surface's.
const REFINE_DEGREES: f64 = 20.0;

/// [`refinement`] makes a face's mesh at most this many times finer than the resolution...
const REFINE_MAX_TIMES: usize = 4;

/// ...and gives its side segments at most this many intervals (never fewer than the
/// resolution): what the meshes of the few faces that turn tightly may add is bounded.
const REFINE_MAX_INTERVALS: usize = 32;

/// How many times `resolution` the face of `patch` (whose mesh at `resolution` is `mesh`)
/// needs on its sides: 1 when its neighbouring polygons are within [`REFINE_DEGREES`];
/// otherwise the least doubling (up to [`REFINE_MAX_TIMES`], and [`REFINE_MAX_INTERVALS`]
/// intervals per segment) after which they are, or failing that the doubling with the
/// smallest largest angle if it is at most half the first (a tight turn the finer mesh
/// follows). A fold keeps its angle however fine the mesh: its face is not refined, and the
/// fold check reports it. Also the face's finer mesh at that need, where it is finer than
/// `resolution`: [`refined`] takes it where the face's sides get those intervals.
fn refinement(
    patch: &Patch,
    mesh: &FaceMesh,
    resolution: usize,
    smooth: &[bool],
) -> (Need, Option<Made>) {
    let first = Need {
        times: 1,
        folds: face_folds(patch, mesh, smooth),
    };
    if first.folds.worst <= REFINE_DEGREES {
        return (first, None);
    }
    let mut best = (first, None);
    let mut m = 2;
    while m <= REFINE_MAX_TIMES
        && m * resolution <= REFINE_MAX_INTERVALS
        && patch.mesh_vertex_count(m * resolution) <= FOLD_CHECK_VERTICES
    {
        let counts = vec![m * resolution; patch.segment_count()];
        let finer = patch.face_mesh_with(&counts);
        let folds = face_folds(patch, &finer, smooth);
        let made = Made {
            counts,
            mesh: finer,
            worst: None,
        };
        if folds.worst <= REFINE_DEGREES {
            return (Need { times: m, folds }, Some(made));
        }
        if folds.worst < best.0.folds.worst {
            best = (Need { times: m, folds }, Some(made));
        }
        m *= 2;
    }
    if best.0.folds.worst <= 0.5 * first.folds.worst {
        best
    } else {
        (first, None)
    }
}

/// A face's mesh made on the way to its final one ([`refinement`], or [`refined`] looking at
/// mixed intervals), with the intervals it has on its side segments and, once measured, the
/// largest angle between its neighbouring polygons ([`face_mesh_folds`]): where the face's
/// final intervals are these, it is its mesh, not made again.
pub(crate) struct Made {
    counts: Vec<usize>,
    mesh: FaceMesh,
    worst: Option<f64>,
}

/// How finely a face's own mesh needs to be made ([`refinement`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Need {
    /// How many times the resolution its sides need.
    pub(crate) times: usize,
    /// How its mesh made so folds (`worst`: the largest angle between neighbouring polygons).
    pub(crate) folds: MeshFolds,
}

impl Need {
    /// What a face whose mesh was not looked at needs: the resolution.
    const NONE: Need = Need {
        times: 1,
        folds: MeshFolds {
            pairs: 0,
            worst: 0.0,
            excess: 0.0,
        },
    };
}

/// The faces' outcomes with every face's mesh made with the intervals its segments need:
/// each edge takes the largest need of the faces along it (so the two faces of an edge sample
/// it alike and weld), a face's segment `resolution` times that. A face's need is its
/// [`refinement`], raised to its finest edge's where its mesh with those mixed intervals has
/// neighbouring polygons more than [`REFINE_DEGREES`] apart, until no need rises. A face
/// whose counts are already those keeps its outcome (the same `Arc`); a face whose mesh with
/// those counts was made on the way (`made`, per face: [`refinement`]'s finer mesh, or one
/// looked at here) takes it. Errors: [`PatchError::MeshTooLarge`] when the refined meshes
/// could not be indexed.
fn refined(
    outcomes: Vec<Arc<FaceOutcome>>,
    mut made: Vec<Option<Made>>,
    stages: &Stages,
    options: &HullOptions,
) -> Result<Vec<Arc<FaceOutcome>>, Error> {
    let (edges, resolution) = (stages.topology.brep.edges.len(), options.resolution);
    let mut needs: Vec<usize> = outcomes
        .iter()
        .map(|o| match o.as_ref() {
            FaceOutcome::Built { need, .. } => need.times,
            _ => 1,
        })
        .collect();
    let wanted = |needs: &[usize]| -> Vec<Option<Vec<usize>>> {
        let mut times = vec![1usize; edges];
        for (outcome, &need) in outcomes.iter().zip(needs) {
            if let FaceOutcome::Built { layout, .. } = outcome.as_ref() {
                for seg in layout.iter().flatten() {
                    times[seg.edge] = times[seg.edge].max(need);
                }
            }
        }
        outcomes
            .iter()
            .map(|o| match o.as_ref() {
                FaceOutcome::Built { layout, .. } => Some(
                    layout
                        .iter()
                        .flatten()
                        .map(|seg| resolution * times[seg.edge])
                        .collect(),
                ),
                _ => None,
            })
            .collect()
    };
    // A face with finer sides than its own need, zipped to its coarser inside, may turn too
    // sharply between its long thin triangles: it takes its finest side's need. Not a face
    // that folds at its own need (no finer mesh mends a fold).
    let mixed = |counts: &[usize]| counts.iter().any(|&c| c != counts[0]);
    let mut want = wanted(&needs);
    loop {
        // Per face looked at: whether its need rises to its finest edge's, and the mesh it
        // was looked at with where that was made now (kept for the next round and the end).
        let looked: Vec<(usize, Option<usize>, Option<Made>)> = outcomes
            .par_iter()
            .zip(&want)
            .zip(&made)
            .enumerate()
            .filter_map(|(fi, ((outcome, want), made))| {
                let (
                    FaceOutcome::Built {
                        patch,
                        need,
                        counts,
                        worst,
                        unfolded,
                        ..
                    },
                    Some(want),
                ) = (outcome.as_ref(), want)
                else {
                    return None;
                };
                let patch = unfolded.as_ref().unwrap_or(patch);
                let finest = want.iter().copied().max()? / resolution;
                if !mixed(want) || finest <= needs[fi] || need.folds.worst > FOLD_ANGLE_DEGREES {
                    return None;
                }
                // A kept face's mesh may already have these intervals, or one made before.
                let (mixed_worst, new) = match made {
                    _ if want == counts => (*worst, None),
                    Some(Made {
                        counts,
                        worst: Some(worst),
                        ..
                    }) if counts == want => (*worst, None),
                    _ => {
                        let mesh = patch.face_mesh_with(want);
                        let worst = face_mesh_folds(&mesh).worst;
                        let made = Made {
                            counts: want.clone(),
                            mesh,
                            worst: Some(worst),
                        };
                        (worst, Some(made))
                    }
                };
                let raise = (mixed_worst > REFINE_DEGREES).then_some(finest);
                (raise.is_some() || new.is_some()).then_some((fi, raise, new))
            })
            .collect();
        let mut raised = false;
        for (fi, raise, new) in looked {
            if let Some(finest) = raise {
                needs[fi] = finest;
                raised = true;
            }
            if new.is_some() {
                made[fi] = new;
            }
        }
        if !raised {
            break;
        }
        want = wanted(&needs);
    }
    let total =
        outcomes
            .iter()
            .zip(&want)
            .fold(0usize, |acc, (o, want)| match (o.as_ref(), want) {
                (FaceOutcome::Built { patch, .. }, Some(want)) => {
                    acc.saturating_add(patch.mesh_vertex_count_with(want))
                }
                _ => acc,
            });
    if total >= u32::MAX as usize {
        return Err(PatchError::MeshTooLarge(total).into());
    }
    Ok(outcomes
        .into_par_iter()
        .zip(want)
        .zip(made)
        .enumerate()
        .map(
            |(fi, ((outcome, want), made))| match (outcome.as_ref(), want) {
                (
                    FaceOutcome::Built {
                        patch,
                        layout,
                        need,
                        counts,
                        unfolded,
                        ..
                    },
                    Some(want),
                ) => {
                    if want == *counts {
                        return outcome;
                    }
                    let base = unfolded.as_ref().unwrap_or(patch);
                    let (mesh, measured) = match made {
                        Some(made) if made.counts == want => (made.mesh, made.worst),
                        _ => (base.face_mesh_with(&want), None),
                    };
                    // At the resolution itself, `unfolded` has chosen; only a finer mesh may
                    // show what it could not.
                    let (patch, mesh, worst) = if want.iter().all(|&c| c == resolution) {
                        let worst = measured.unwrap_or_else(|| face_mesh_folds(&mesh).worst);
                        (base.clone(), mesh, worst)
                    } else {
                        refolded(stages, fi, options, base, mesh, &want)
                    };
                    let unfolded = (patch.kind() != base.kind()).then(|| base.clone());
                    Arc::new(if mesh.is_finite() {
                        FaceOutcome::Built {
                            patch,
                            layout: layout.clone(),
                            shares: MeshShares::of(&mesh),
                            mesh,
                            need: *need,
                            counts: want,
                            worst,
                            unfolded,
                        }
                    } else {
                        FaceOutcome::NonFinite
                    })
                }
                _ => outcome,
            },
        )
        .collect())
}

/// The patch of face `fi`, its mesh with the finer intervals `counts` ([`refined`]), and the
/// largest angle between neighbouring polygons of `mesh` (`patch`'s with `counts`). `patch`
/// and `mesh` as they are; or, where that finer mesh shows the corner-based patch folding
/// where its mesh at the resolution stepped over it, the side-blended patch on
/// [`unfolded`]'s terms, judged on meshes with these intervals.
fn refolded(
    stages: &Stages,
    fi: usize,
    options: &HullOptions,
    patch: &Patch,
    mesh: FaceMesh,
    counts: &[usize],
) -> (Patch, FaceMesh, f64) {
    let folds = face_mesh_folds(&mesh);
    if folds.pairs == 0 || patch.kind() == PatchKind::SideBlend || !mesh.is_finite() {
        return (patch.clone(), mesh, folds.worst);
    }
    let Ok(plan) = plan_face(
        &stages.topology.faces[fi],
        &stages.topology,
        &stages.edges,
        &stages.knuckle,
        &stages.shared,
        &stages.inner,
    ) else {
        return (patch.clone(), mesh, folds.worst);
    };
    let Some(blended) = side_blend(&plan, &patch_options(options)) else {
        return (patch.clone(), mesh, folds.worst);
    };
    let other = blended.face_mesh_with(counts);
    if !other.is_finite() {
        return (patch.clone(), mesh, folds.worst);
    }
    match fallback(patch, &folds, blended, &face_mesh_folds(&other)) {
        Some(blended) => (blended, other, folds.worst),
        None => (patch.clone(), mesh, folds.worst),
    }
}

impl Stages {
    /// Every stage of `network` computed from scratch (steps 1–5 of
    /// [`build_hull`](super::build_hull), before the welding).
    pub(crate) fn full(network: &Network, options: &HullOptions) -> Result<Stages, Error> {
        options.check()?;
        let topology = faced_topology(network, options)?;
        let edges = FaceEdges::new(network, &topology, options.tolerance);
        let corners = corner_points(network);
        let near_miss = options.tolerance.near_miss();
        let knuckle = knuckle_edges(network, &topology, &edges, &corners, near_miss);
        let inner = inner_edges(&topology);
        let (shared, edge_warnings): (Vec<_>, Vec<_>) = (0..topology.brep.edges.len())
            .into_par_iter()
            .map(|k| {
                let tol = options.tolerance;
                edge_normal(k, network, tol, inner[k], &topology, &edges, &knuckle)
            })
            .unzip();
        let mut stages = Stages {
            topology,
            edges,
            corners,
            knuckle,
            inner,
            shared,
            edge_warnings,
            faces: Vec::new(),
        };
        let dirty = vec![true; stages.topology.faces.len()];
        stages.faces = face_outcomes(&stages, None, &dirty, options)?;
        Ok(stages)
    }

    /// The stages of `network` from these (made for `before`, with the same `options`),
    /// computing again only what the curves that changed reach: the edges whose curve or end
    /// nodes moved, the normal fields of edges at a node with such an edge, the faces with
    /// any of those (and any edge whose knuckle status changed). The result is the same as
    /// [`Stages::full`] bit for bit. `Ok(Err(why))` when that cannot be done because the
    /// network's connectivity changed (curves added, removed, renamed or given another role,
    /// nodes or faces appearing or disappearing): then build it in full.
    pub(crate) fn updated(
        &self,
        before: &Network,
        network: &Network,
        options: &HullOptions,
    ) -> Result<Result<(Stages, usize), String>, Error> {
        let (old, new) = (before.curves(), network.curves());
        if before.tangent_planes() != network.tangent_planes() {
            return Ok(Err(
                "the planes the surface is tangent to changed".to_string()
            ));
        }
        if old.len() != new.len()
            || old
                .iter()
                .zip(new)
                .any(|(a, b)| a.name != b.name || a.role != b.role)
        {
            return Ok(Err(
                "curves were added, removed, renamed or given another role".to_string(),
            ));
        }
        let topology = faced_topology(network, options)?;
        if let Err(why) = same_connectivity(&self.topology, &topology) {
            return Ok(Err(why));
        }
        let moved: Vec<bool> = old.iter().zip(new).map(|(a, b)| a != b).collect();
        let (brep, old_brep) = (&topology.brep, &self.topology.brep);
        // Per edge: whether its parameters and end nodes are bit for bit as before.
        let at = |b: &crate::topo::Brep, v: crate::topo::VertexId| {
            b.vertices[v.index()].position.to_array().map(f64::to_bits)
        };
        let same_ends: Vec<bool> = brep
            .edges
            .iter()
            .zip(&old_brep.edges)
            .map(|(e, o)| {
                e.t0.to_bits() == o.t0.to_bits()
                    && e.t1.to_bits() == o.t1.to_bits()
                    && at(brep, e.start) == at(old_brep, o.start)
                    && at(brep, e.end) == at(old_brep, o.end)
            })
            .collect();
        let dirty_info: Vec<bool> = brep
            .edges
            .iter()
            .zip(&same_ends)
            .map(|(e, &same)| moved[e.curve] || !same)
            .collect();
        // Of those, the edges whose curve changed where the edge lies: a moved control point
        // reaches only `degree + 1` spans of its curve, and the edges beyond them (their
        // nodes, parameters and curve bits there unchanged) give their faces the same patch.
        let changed: Vec<bool> = brep
            .edges
            .iter()
            .zip(&same_ends)
            .map(|(e, &same)| {
                !same
                    || (moved[e.curve]
                        && !new[e.curve].curve.same_on(&old[e.curve].curve, e.t0, e.t1))
            })
            .collect();
        let edges = self
            .edges
            .updated(network, &topology, options.tolerance, &dirty_info);
        let corners: Vec<Vec<DVec3>> = new
            .iter()
            .zip(&self.corners)
            .zip(&moved)
            .map(|((c, kept), &m)| {
                if m {
                    curve_corner_points(c)
                } else {
                    kept.clone()
                }
            })
            .collect();
        let near_miss = options.tolerance.near_miss();
        let knuckle = knuckle_edges(network, &topology, &edges, &corners, near_miss);
        let inner = inner_edges(&topology);
        let knuckle_changed: Vec<bool> = knuckle
            .iter()
            .zip(&self.knuckle)
            .map(|(a, b)| a != b)
            .collect();
        let dirty_normal: Vec<bool> = brep
            .edges
            .iter()
            .enumerate()
            .map(|(k, e)| {
                // The nodes whose crossing tangents shape the field: the ends and the nodes
                // beyond them along the curve (`ribbons::beyond`).
                let outer = [true, false].into_iter().filter_map(|at_start| {
                    beyond(k, at_start, &topology, &edges, &knuckle).map(|(v, ..)| v)
                });
                changed[k]
                    || knuckle_changed[k]
                    || [e.start, e.end].into_iter().chain(outer).any(|v| {
                        edges.at_vertex[v.index()]
                            .iter()
                            .any(|end| changed[end.edge] || knuckle_changed[end.edge])
                    })
            })
            .collect();
        let (shared, edge_warnings): (Vec<_>, Vec<_>) = (0..brep.edges.len())
            .into_par_iter()
            .map(|k| {
                if dirty_normal[k] {
                    let tol = options.tolerance;
                    edge_normal(k, network, tol, inner[k], &topology, &edges, &knuckle)
                } else {
                    (self.shared[k].clone(), self.edge_warnings[k].clone())
                }
            })
            .unzip();
        // A field computed again that came out bit for bit as it was changes no patch.
        let normal_changed: Vec<bool> = (0..brep.edges.len())
            .map(|k| {
                let same = match (&shared[k], &self.shared[k]) {
                    (Some(a), Some(b)) => a.same_bits(b),
                    (None, None) => true,
                    _ => false,
                };
                dirty_normal[k] && (changed[k] || !same)
            })
            .collect();
        let dirty_faces: Vec<bool> = topology
            .faces
            .iter()
            .map(|f| {
                // A composite side's breaks come from its segments' arc lengths, which are
                // measured on the whole curve (centred on its control points): a face with
                // one is patched again whenever any of its edges' curves moved.
                let composite = f.sides.len() < f.edges.len();
                f.edges.iter().any(|e| {
                    let k = e.index();
                    normal_changed[k] || knuckle_changed[k] || (composite && dirty_info[k])
                })
            })
            .collect();
        let mut stages = Stages {
            topology,
            edges,
            corners,
            knuckle,
            inner,
            shared,
            edge_warnings,
            faces: Vec::new(),
        };
        stages.faces = face_outcomes(&stages, Some(&self.faces), &dirty_faces, options)?;
        let rebuilt = dirty_faces.iter().filter(|&&d| d).count();
        Ok(Ok((stages, rebuilt)))
    }

    /// The warnings of the stages in the build's order — the topology's findings, the edges
    /// without ribbon, then face by face the patch's own repairs or why it has none — and the
    /// number of faces without a patch.
    fn warnings(&self) -> (Vec<Warning>, usize) {
        let topology = &self.topology;
        let mut warnings: Vec<Warning> = topology.diagnostics.iter().map(Warning::from).collect();
        warnings.extend(self.edge_warnings.iter().flatten().cloned());
        let mut skipped = 0;
        for (fi, outcome) in self.faces.iter().enumerate() {
            let label = face_label(topology, fi, &topology.faces[fi]);
            match outcome.as_ref() {
                FaceOutcome::Built { patch, .. } => {
                    for w in patch.warnings() {
                        warnings.push(patch_warning(topology, fi, &label, w));
                    }
                }
                FaceOutcome::Failed(error) => {
                    skipped += 1;
                    warnings.push(face_warning(
                        topology,
                        fi,
                        WarningKind::FaceNotPatched,
                        format!("{label} is not patched: {error}"),
                        Some(error.clone()),
                    ));
                }
                FaceOutcome::NonFinite => {
                    skipped += 1;
                    warnings.push(face_warning(
                        topology,
                        fi,
                        WarningKind::NonFiniteSurface,
                        format!("{label} is not patched: its surface has non-finite points"),
                        None,
                    ));
                }
            }
        }
        (warnings, skipped)
    }
}

/// `Ok` when `b` has the connectivity of `a` — the same nodes, edges (curve, end nodes,
/// whether they bound a region) and faces (edges, directions, corners, sides) in the same
/// order — else what differs.
fn same_connectivity(a: &Topology, b: &Topology) -> Result<(), String> {
    let (ba, bb) = (&a.brep, &b.brep);
    if ba.vertices.len() != bb.vertices.len()
        || ba.edges.len() != bb.edges.len()
        || a.faces.len() != b.faces.len()
    {
        return Err(format!(
            "the connectivity changed: {} nodes, {} edges, {} faces became {}, {}, {}",
            ba.vertices.len(),
            ba.edges.len(),
            a.faces.len(),
            bb.vertices.len(),
            bb.edges.len(),
            b.faces.len()
        ));
    }
    let edges_same = ba.edges.iter().zip(&bb.edges).all(|(x, y)| {
        x.curve == y.curve
            && x.start == y.start
            && x.end == y.end
            && x.half_edges.is_some() == y.half_edges.is_some()
    });
    let faces_same = a.faces.iter().zip(&b.faces).all(|(x, y)| {
        x.edges == y.edges && x.forward == y.forward && x.corners == y.corners && x.sides == y.sides
    });
    if edges_same && faces_same {
        Ok(())
    } else {
        Err("the connectivity changed: edges or faces run between other nodes".to_string())
    }
}

/// The patched faces of `stages` in topology face order, and their meshes.
fn built(stages: &Stages) -> (Vec<PatchedFace>, Vec<&FaceMesh>) {
    let mut patched = Vec::new();
    let mut meshes = Vec::new();
    for (fi, outcome) in stages.faces.iter().enumerate() {
        if let FaceOutcome::Built {
            patch,
            layout,
            mesh,
            ..
        } = outcome.as_ref()
        {
            patched.push(PatchedFace {
                face: fi,
                patch: patch.clone(),
                layout: layout.clone(),
            });
            meshes.push(mesh);
        }
    }
    (patched, meshes)
}

/// The intervals of each built face's mesh on its side segments, in face order (what
/// [`HullSurface::mesh_counts`] holds).
pub(crate) fn mesh_counts(stages: &Stages) -> Vec<Vec<usize>> {
    stages
        .faces
        .iter()
        .filter_map(|f| match f.as_ref() {
            FaceOutcome::Built { counts, .. } => Some(counts.clone()),
            _ => None,
        })
        .collect()
}

/// The shares of the built faces' meshes, added in face order: the welded mesh's area vector
/// (y) and volume before it is turned outward.
fn total_shares(stages: &Stages) -> MeshShares {
    MeshShares::total(stages.faces.iter().filter_map(|f| match f.as_ref() {
        FaceOutcome::Built { shares, .. } => Some(shares),
        _ => None,
    }))
}

/// The built faces of the stages as patches (in topology face order), welded into one mesh
/// oriented outwards (`face_patch`: index into the patches), whether the patches' own
/// orientation was outward, and how the faces' meshes were welded (what [`reassemble`] starts
/// from). [`Error::NoSurface`] when no face has a patch, or when the mesh's volume overflows.
pub(crate) fn assemble_welded(
    network: &Network,
    stages: &Stages,
) -> Result<(Vec<PatchedFace>, SurfaceMesh, bool, Weld), Error> {
    let (patched, meshes) = built(stages);
    if patched.is_empty() {
        let (warnings, _) = stages.warnings();
        return Err(Error::NoSurface(format!(
            "network '{}': none of its {} faces could be patched: {}",
            network.name,
            stages.topology.faces.len(),
            join(&warnings)
        )));
    }
    let (mut mesh, weld) = weld_face_meshes_with(&meshes);
    let shares = total_shares(stages);
    let outward = shares.area_y >= 0.0;
    if !outward {
        flip(&mut mesh);
    }
    if !shares.volume.is_finite() {
        return Err(overflow(network, f64::INFINITY, f64::NAN));
    }
    Ok((patched, mesh, outward, weld))
}

/// The surface of `stages`, a live rebuild of `before` (whose surface, report aside, is
/// `surface`, welded as `weld`) that patched some faces again and kept the others' outcomes
/// (the same `Arc`): `surface`'s mesh with only the vertices of the faces patched again
/// rewritten ([`Weld::rewrite`]), which is bit for bit the mesh [`assemble_welded`] gives, with
/// `weld` updated to it. `None` where that cannot be shown — other faces patched, a face's
/// mesh of another shape, vertices welded otherwise, the mesh turned the other way, figures
/// that overflow — and the stages must be assembled afresh; `weld` is then unchanged. The
/// report is `surface`'s.
pub(crate) fn reassemble(
    stages: &Stages,
    before: &Stages,
    surface: &HullSurface,
    weld: &mut Weld,
) -> Option<HullSurface> {
    if stages.faces.len() != before.faces.len() {
        return None;
    }
    // Assembled afresh, the mesh would be turned the way `surface`'s is when the faces'
    // shares decide alike (the same shares, added in the same order, as `assemble_welded`).
    let shares = total_shares(stages);
    if (shares.area_y >= 0.0) != surface.patches_outward || !shares.volume.is_finite() {
        return None;
    }
    let mut changed = Vec::new();
    let mut k = 0;
    for (now, then) in stages.faces.iter().zip(&before.faces) {
        match (now.as_ref(), then.as_ref()) {
            (FaceOutcome::Built { mesh: new, .. }, FaceOutcome::Built { mesh: old, .. }) => {
                if !Arc::ptr_eq(now, then) {
                    changed.push((k, old, new));
                }
                k += 1;
            }
            (FaceOutcome::Built { .. }, _) | (_, FaceOutcome::Built { .. }) => return None,
            _ => {}
        }
    }
    let mut mesh = surface.mesh.clone();
    if !weld.rewrite(&mut mesh.positions, &changed) {
        return None;
    }
    let (patched, _) = built(stages);
    let patch_faces = patched.iter().map(|p| p.face).collect();
    let (patches, layouts) = patched.into_iter().map(|p| (p.patch, p.layout)).unzip();
    Some(HullSurface {
        mesh,
        report: surface.report.clone(),
        patches,
        patch_faces,
        layouts,
        patches_outward: surface.patches_outward,
        mesh_counts: mesh_counts(stages),
        mesh_resolution: surface.mesh_resolution,
    })
}

/// The report of assembled stages ([`assemble_welded`]), refused with [`Error::NoSurface`]
/// when its figures overflow.
pub(crate) fn measure(
    network: &Network,
    options: &HullOptions,
    stages: &Stages,
    patched: &[PatchedFace],
    mesh: &SurfaceMesh,
) -> Result<HullReport, Error> {
    let (warnings, skipped_faces) = stages.warnings();
    let findings = Findings {
        knuckle: &stages.knuckle,
        skipped_faces,
        warnings,
        tolerance: options.tolerance,
    };
    let report = report::report(network, &stages.topology, patched, mesh, findings);
    let figures = [report.volume, report.max_gap, report.max_normal_angle_deg];
    if !figures.iter().all(|f| f.is_finite()) {
        return Err(overflow(network, report.volume, report.max_gap));
    }
    Ok(report)
}

/// The error of a surface whose figures overflow f64.
fn overflow(network: &Network, volume: f64, max_gap: f64) -> Error {
    Error::NoSurface(format!(
        "network '{}': the surface's figures overflow f64 (volume {volume}, max gap {max_gap}); its coordinates are too large",
        network.name
    ))
}

/// The hull surface of assembled stages with its report: the mesh's `face_patch` renamed to
/// the topology's face of every polygon (skipped faces leave gaps).
pub(crate) fn into_surface(
    patched: Vec<PatchedFace>,
    mut mesh: SurfaceMesh,
    patches_outward: bool,
    report: HullReport,
    stages: &Stages,
    resolution: usize,
) -> HullSurface {
    for p in &mut mesh.face_patch {
        *p = patched[*p as usize].face as u32;
    }
    let patch_faces = patched.iter().map(|p| p.face).collect();
    let (patches, layouts) = patched.into_iter().map(|p| (p.patch, p.layout)).unzip();
    HullSurface {
        mesh,
        report,
        patches,
        patch_faces,
        layouts,
        patches_outward,
        mesh_counts: mesh_counts(stages),
        mesh_resolution: resolution,
    }
}

/// The pipeline of [`build_hull`](super::build_hull), step by step (see there).
pub(crate) fn build(network: &Network, options: &HullOptions) -> Result<HullSurface, Error> {
    built_in_full(network, options).map(|(_, surface, _)| surface)
}

/// A build of `network` in full, report included: its stages, its surface, and how its faces'
/// meshes were welded (what a [`LiveHull`](super::LiveHull) keeps to rebuild from).
pub(crate) fn built_in_full(
    network: &Network,
    options: &HullOptions,
) -> Result<(Stages, HullSurface, Weld), Error> {
    let stages = Stages::full(network, options)?;
    let (patched, mesh, outward, weld) = assemble_welded(network, &stages)?;
    let report = measure(network, options, &stages, &patched, &mesh)?;
    let surface = into_surface(patched, mesh, outward, report, &stages, options.resolution);
    Ok((stages, surface, weld))
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
