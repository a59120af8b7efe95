//! Folds in the surface, found on the mesh (the real-ships issue: "the report tells the truth
//! about the surface"): two neighbouring mesh polygons whose normals differ by more than
//! [`FOLD_ANGLE_DEGREES`] — inside one patch, or across two patches that do not meet along a
//! knuckle — where the surface meshed afresh around them turns by that much too
//! ([`super::fold_probe`]), and patches that leave the box of their own boundary by more than
//! their size allows (a fin, a ridge, a lid bulging past the transom).

use std::collections::BTreeMap;

use glam::DVec3;
use rayon::prelude::*;

use super::fold_probe::surface_turn;
use super::knuckles::Knuckle;
use super::patched::PatchedFace;
use super::warning::{Warning, WarningKind};
use crate::patch::{FaceMesh, Patch, SurfaceMesh};
use crate::tolerance::Tolerance;
use crate::topo::Topology;

/// Neighbouring mesh polygons whose normals differ by more than this (degrees) are a fold,
/// except across a knuckle: at the default resolution a smooth hull turns by a few degrees
/// between neighbours, a fold by tens (a sheet doubling back turns by up to 180°).
pub const FOLD_ANGLE_DEGREES: f64 = 30.0;

/// How far (as a fraction of the diagonal of its boundary's box) a patch may stand out of that
/// box before it is a fold: a smooth patch bulges by a fraction of its size over its boundary
/// (a quarter of a circle's chord for a semicircular bulge of the chord's span), never by more.
pub const BOX_SLACK: f64 = 0.25;

/// Samples per boundary edge for the box of a patch's boundary (ends included).
const BOX_SAMPLES: usize = 8;

/// The unit normal of a polygon (Newell's method) with vertex positions from `at`, zero for a
/// degenerate one.
fn polygon_normal(at: impl Fn(u32) -> DVec3, face: &[u32]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, &v) in face.iter().enumerate() {
        n += at(v).cross(at(face[(i + 1) % face.len()]));
    }
    n.normalize_or_zero()
}

/// Every mesh side that exactly two polygons share, as (lower vertex, upper vertex, polygon,
/// other polygon), in the order of (lower vertex, upper vertex, polygons): the pairs of
/// neighbouring polygons. The sides are bucketed by their lower vertex (`vertices` of them)
/// and each bucket — a vertex's few sides — sorted alone, in the order a sort of all sides
/// would give, which took a tenth of a rebuild.
fn shared_sides(faces: &[&[u32]], vertices: usize) -> Vec<(u32, u32, usize, usize)> {
    let side = |f: &[u32], i: usize| {
        let (a, b) = (f[i], f[(i + 1) % f.len()]);
        (a.min(b), a.max(b))
    };
    let mut start = vec![0usize; vertices + 1];
    for f in faces {
        for i in 0..f.len() {
            start[side(f, i).0 as usize + 1] += 1;
        }
    }
    for v in 0..vertices {
        start[v + 1] += start[v];
    }
    let mut next = start.clone();
    let mut slots = vec![(0u32, 0usize); start[vertices]];
    for (fi, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            let (lo, hi) = side(f, i);
            slots[next[lo as usize]] = (hi, fi);
            next[lo as usize] += 1;
        }
    }
    let mut out = Vec::with_capacity(slots.len() / 2);
    for lo in 0..vertices {
        let bucket = &mut slots[start[lo]..start[lo + 1]];
        if bucket.len() < 2 {
            continue;
        }
        sort_sides(bucket);
        let mut i = 0;
        while i < bucket.len() {
            let hi = bucket[i].0;
            let mut j = i + 1;
            while j < bucket.len() && bucket[j].0 == hi {
                j += 1;
            }
            if j - i == 2 {
                out.push((lo as u32, hi, bucket[i].1, bucket[i + 1].1));
            }
            i = j;
        }
    }
    out
}

/// Buckets up to this long are sorted by [`sort_sides`]'s insertion sort, longer ones (a
/// vertex many polygons meet at, a fan's hub) by the slice sort.
const SMALL_BUCKET: usize = 16;

/// Sort one vertex's sides: in place by insertion where there are few (a bucket mostly holds
/// two to eight, where a call to the slice sort cost more than the sorting), else by the
/// slice sort, so a vertex with thousands of sides does not take their square.
#[inline]
fn sort_sides(bucket: &mut [(u32, usize)]) {
    if bucket.len() > SMALL_BUCKET {
        bucket.sort_unstable();
        return;
    }
    for i in 1..bucket.len() {
        let mut j = i;
        while j > 0 && bucket[j - 1] > bucket[j] {
            bucket.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// How badly a patch's own mesh folds ([`MeshFolds`]): between its neighbouring polygons
/// ([`face_mesh_folds`]), and between each polygon along a side that `smooth` marks (a
/// smooth edge shared with another face) and the surface's tangent plane there, which the
/// patch's ribbons give and the neighbouring face shares ([`boundary_folds`]).
pub(crate) fn face_folds(patch: &Patch, mesh: &FaceMesh, smooth: &[bool]) -> MeshFolds {
    let inside = face_mesh_folds(mesh);
    let edge = boundary_folds(patch, mesh, smooth);
    MeshFolds {
        pairs: inside.pairs + edge.pairs,
        worst: inside.worst.max(edge.worst),
        excess: inside.excess + edge.excess,
    }
}

/// The polygons of a patch's mesh along its boundary that stand more than
/// [`FOLD_ANGLE_DEGREES`] off the surface's tangent plane at their boundary side (its normal
/// `ĉ × R`, side tangent and ribbon): the inside of the patch turning away within the first
/// row of its mesh. The neighbouring face across the edge has that tangent plane too, so such
/// a polygon folds against it where they meet, which the polygons of one patch alone do not
/// show (KCS's five-sided face aft of station 1.5 against the face above it along
/// wl_z1.50: 35.7°).
pub(crate) fn boundary_folds(patch: &Patch, mesh: &FaceMesh, smooth: &[bool]) -> MeshFolds {
    let positions = mesh.positions();
    let polys: Vec<&[u32]> = mesh.polygons().collect();
    tally(
        mesh.boundary_sides()
            .into_iter()
            .filter(|&(_, side, _)| smooth.get(side).copied().unwrap_or(false))
            .filter_map(|(f, side, s)| {
                let np = polygon_normal(|v| positions[v as usize], polys[f]);
                let ne = patch.side_plane_normal(side, s);
                // Either orientation: a polygon turned right over is the inside check's to
                // find.
                (np != DVec3::ZERO && ne != DVec3::ZERO).then(|| np.dot(ne).abs().min(1.0))
            }),
    )
}

/// The [`MeshFolds`] of pairs with these cosines between their normals.
fn tally(cosines: impl Iterator<Item = f64>) -> MeshFolds {
    let fold_cos = FOLD_ANGLE_DEGREES.to_radians().cos();
    let (mut out, mut least_cos) = (MeshFolds::default(), 1.0f64);
    for cos in cosines {
        least_cos = least_cos.min(cos);
        if cos < fold_cos {
            out.pairs += 1;
            out.excess += cos.acos().to_degrees() - FOLD_ANGLE_DEGREES;
        }
    }
    out.worst = least_cos.acos().to_degrees();
    out
}

/// How badly a patch's own mesh folds ([`MeshFolds`]), measured between its neighbouring
/// polygons as [`fold_findings`] measures the welded mesh (one arc cosine per folded pair: the
/// build measures every face it makes).
pub(crate) fn face_mesh_folds(mesh: &FaceMesh) -> MeshFolds {
    let positions = mesh.positions();
    let faces: Vec<&[u32]> = mesh.polygons().collect();
    let normals: Vec<DVec3> = faces
        .iter()
        .map(|f| polygon_normal(|v| positions[v as usize], f))
        .collect();
    tally(
        shared_sides(&faces, positions.len())
            .into_iter()
            .filter_map(|(_, _, f, g)| {
                let (nf, ng) = (normals[f], normals[g]);
                (nf != DVec3::ZERO && ng != DVec3::ZERO).then(|| nf.dot(ng).clamp(-1.0, 1.0))
            }),
    )
}

/// Cells along each axis of the grid [`in_plane_folds`] lays over a patch's domain: fine
/// enough to see the thin turned-over strips of KCS's shaft-boss end and KVLCC2's transom (3
/// and 17 cells at 96, none at 48), about 2 ms a face.
pub(crate) const IN_PLANE_GRID: usize = 128;

/// Boundary samples per side for the plane of [`in_plane_folds`] (from its start; its end is
/// the next side's start).
const PLANE_SAMPLES: usize = 8;

/// How many cells of a fine grid over the domain of a flat patch of other than 4 sides turn
/// over in its plane (0 for a patch that is not flat within `tolerance`, or has 4 sides).
///
/// A flat face (a transom, a shaft boss's end) gets a flat patch, but its interpolant can
/// still fold within the plane: a thin strip of the domain maps onto the surface turned over,
/// and the fold search's mesh steps over it. The grid's cells ([`IN_PLANE_GRID`] across the
/// domain's square) are triangles of evaluated points; one whose signed area in the plane has
/// the minority's sign has turned over. Only patches of 3, 5 or more sides are looked at:
/// those are the Charrot–Gregory patches whose corners fold so, and the check costs up to
/// (`IN_PLANE_GRID` + 1)² evaluations (those inside the domain).
pub(crate) fn in_plane_folds(patch: &Patch, tolerance: Tolerance) -> usize {
    let n = patch.sides();
    if n == 4 {
        return 0;
    }
    let boundary: Vec<DVec3> = (0..n)
        .flat_map(|i| {
            (0..PLANE_SAMPLES).map(move |k| patch.side_point(i, k as f64 / PLANE_SAMPLES as f64))
        })
        .collect();
    let normal = polygon_normal(
        |v| boundary[v as usize],
        &(0..boundary.len() as u32).collect::<Vec<_>>(),
    );
    let centre = boundary.iter().sum::<DVec3>() / boundary.len() as f64;
    if normal == DVec3::ZERO
        || boundary
            .iter()
            .any(|&b| (b - centre).dot(normal).abs() > tolerance.get())
    {
        return 0;
    }
    let domain = patch.domain();
    let m = IN_PLANE_GRID;
    let at = |i: usize, j: usize| {
        [
            -1.0 + 2.0 * i as f64 / m as f64,
            -1.0 + 2.0 * j as f64 / m as f64,
        ]
    };
    let grid: Vec<Option<DVec3>> = (0..=m)
        .flat_map(|i| (0..=m).map(move |j| (i, j)))
        .map(|(i, j)| {
            let x = at(i, j);
            domain.contains(x).then(|| patch.eval(x))
        })
        .collect();
    let (mut ahead, mut behind) = (0usize, 0usize);
    for i in 0..m {
        for j in 0..m {
            let cell = (
                grid[i * (m + 1) + j],
                grid[(i + 1) * (m + 1) + j],
                grid[i * (m + 1) + j + 1],
            );
            if let (Some(a), Some(b), Some(c)) = cell {
                let area = (b - a).cross(c - a).dot(normal);
                if area > 0.0 {
                    ahead += 1;
                } else if area < 0.0 {
                    behind += 1;
                }
            }
        }
    }
    ahead.min(behind)
}

/// How badly one patch's mesh folds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct MeshFolds {
    /// Pairs of neighbouring polygons whose normals differ by more than
    /// [`FOLD_ANGLE_DEGREES`].
    pub(crate) pairs: usize,
    /// The largest angle between neighbouring polygons, degrees.
    pub(crate) worst: f64,
    /// The sum over those pairs of their angle beyond [`FOLD_ANGLE_DEGREES`]: what the build
    /// compares when it weighs a fallback patch (a sheet doubling back over a few polygons
    /// outweighs a crease along many).
    pub(crate) excess: f64,
}

/// The worst fold found for one patch (inside) or one pair of patches (across).
#[derive(Clone, Copy, Debug)]
struct Worst {
    angle: f64,
    at: DVec3,
    count: usize,
    /// How far the surface itself turns around `at` ([`surface_turn`]), where it was looked at.
    surface: Option<f64>,
}

/// A pair of neighbouring mesh polygons more than [`FOLD_ANGLE_DEGREES`] apart: their angle,
/// the middle of their common side, and the radius around it that [`surface_turn`] samples
/// (their reach from there, times [`PROBE_REACH`]).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    angle: f64,
    at: DVec3,
    radius: f64,
}

/// The ball [`surface_turn`] samples around a pair of polygons: this many times the farthest
/// of their vertices from the middle of their common side.
const PROBE_REACH: f64 = 1.5;

/// The places of one patch (or one pair of patches) that [`surface_turn`] looks at, the
/// largest angles first: a pair within half a ball of a place looked at takes its verdict;
/// pairs beyond these are taken as folds without a look.
const PROBES_PER_FOLD: usize = 8;

/// How many folded patches, and how many folded pairs of patches, are looked at
/// ([`PROBES_PER_FOLD`] places each); the others' pairs are taken as folds without a look, so
/// that a network that folds everywhere builds in about its usual time.
const PROBED_FOLDS: usize = 32;

/// The worst of `candidates` (pairs of polygons of `patches`) where the surface turns by more
/// than [`FOLD_ANGLE_DEGREES`] too ([`surface_turn`], when `probe`; all of them otherwise):
/// None when the surface turns by less at every one, which is then a turn the mesh was too
/// coarse to follow, not a fold.
fn confirmed(patches: &[&Patch], candidates: &[Candidate], probe: bool) -> Option<Worst> {
    let mut order: Vec<&Candidate> = candidates.iter().collect();
    order.sort_by(|a, b| b.angle.total_cmp(&a.angle));
    let mut looked: Vec<(Candidate, f64)> = Vec::new();
    let mut worst: Option<Worst> = None;
    for c in order {
        let seen = looked
            .iter()
            .find(|(l, _)| l.at.distance(c.at) <= 0.5 * l.radius)
            .map(|(_, turn)| *turn);
        let verdict = seen.or_else(|| {
            (probe && looked.len() < PROBES_PER_FOLD).then(|| {
                let turn = surface_turn(patches, c.at, c.radius, FOLD_ANGLE_DEGREES);
                looked.push((*c, turn));
                turn
            })
        });
        if verdict.is_some_and(|turn| turn <= FOLD_ANGLE_DEGREES) {
            continue;
        }
        match &mut worst {
            Some(w) => {
                w.count += 1;
                if c.angle > w.angle {
                    (w.angle, w.at, w.surface) = (c.angle, c.at, verdict);
                }
            }
            None => {
                worst = Some(Worst {
                    angle: c.angle,
                    at: c.at,
                    count: 1,
                    surface: verdict,
                })
            }
        }
    }
    worst
}

/// The position of mesh vertex `v`.
fn at(mesh: &SurfaceMesh, v: u32) -> DVec3 {
    DVec3::from(mesh.positions[v as usize])
}

/// What a fold warning adds about the surface itself ([`Worst::surface`]).
fn surface_note(w: &Worst) -> String {
    w.surface
        .map(|turn| format!("; the surface itself turns by {turn:.1}° there"))
        .unwrap_or_default()
}

/// What the fold search found: the warnings, and the largest angle between neighbouring mesh
/// polygons anywhere off the knuckles (degrees) with where it is.
pub(crate) struct FoldFindings {
    /// One warning per folded patch, per folded pair of patches, per patch out of its box.
    pub(crate) warnings: Vec<Warning>,
    /// The largest angle between neighbouring polygons, not across a knuckle.
    pub(crate) max_angle_deg: f64,
    /// Where that angle is (midpoint of the mesh edge between them).
    pub(crate) max_angle_at: Option<DVec3>,
}

/// Search the mesh for folds: neighbouring polygons more than [`FOLD_ANGLE_DEGREES`] apart
/// where the surface itself turns by more too ([`confirmed`]), and patches out of their box.
/// `mesh.face_patch` indexes `patched` (before the build renumbers it to topology faces);
/// `knuckle` says which topology edges are knuckles.
pub(crate) fn fold_findings(
    topology: &Topology,
    patched: &[PatchedFace],
    mesh: &SurfaceMesh,
    knuckle: &[Option<Knuckle>],
    boxes: &[(DVec3, DVec3)],
    tolerance: Tolerance,
) -> FoldFindings {
    let faces: Vec<&[u32]> = mesh.faces().collect();
    let at = |v: u32| self::at(mesh, v);
    let normals: Vec<DVec3> = faces.par_iter().map(|f| polygon_normal(at, f)).collect();
    let pairs = shared_sides(&faces, mesh.positions.len());
    let edge_sets: Vec<Vec<usize>> = patched
        .iter()
        .map(|p| p.layout.iter().flatten().map(|s| s.edge).collect())
        .collect();
    let knuckle_between = |a: usize, b: usize| {
        edge_sets[a]
            .iter()
            .any(|e| knuckle[*e].is_some() && edge_sets[b].contains(e))
    };
    let mut inside: BTreeMap<usize, Vec<Candidate>> = BTreeMap::new();
    let mut across: BTreeMap<(usize, usize), Vec<Candidate>> = BTreeMap::new();
    let (mut max_angle_deg, mut max_angle_at) = (0.0f64, None);
    for (a, b, f, g) in pairs {
        let (nf, ng) = (normals[f], normals[g]);
        if nf == DVec3::ZERO || ng == DVec3::ZERO {
            continue;
        }
        let (pf, pg) = (mesh.face_patch[f] as usize, mesh.face_patch[g] as usize);
        if pf != pg && knuckle_between(pf, pg) {
            continue;
        }
        let angle = nf.angle_between(ng).to_degrees();
        let at = 0.5 * (at(a) + at(b));
        if angle > max_angle_deg {
            max_angle_deg = angle;
            max_angle_at = Some(at);
        }
        if angle > FOLD_ANGLE_DEGREES {
            let reach = faces[f]
                .iter()
                .chain(faces[g])
                .map(|&v| at.distance(self::at(mesh, v)))
                .fold(0.0, f64::max);
            let candidate = Candidate {
                angle,
                at,
                radius: PROBE_REACH * reach,
            };
            if pf == pg {
                inside.entry(pf).or_default().push(candidate);
            } else {
                across
                    .entry((pf.min(pg), pf.max(pg)))
                    .or_default()
                    .push(candidate);
            }
        }
    }
    let probed = |patches: &[usize], candidates: &[Candidate], rank: usize| {
        let patches: Vec<&Patch> = patches.iter().map(|&p| &patched[p].patch).collect();
        confirmed(&patches, candidates, rank < PROBED_FOLDS)
    };
    let inside: Vec<(usize, Option<Worst>)> = Vec::from_iter(inside)
        .into_par_iter()
        .enumerate()
        .map(|(rank, (p, c))| (p, probed(&[p], &c, rank)))
        .collect();
    let across: Vec<((usize, usize), Option<Worst>)> = Vec::from_iter(across)
        .into_par_iter()
        .enumerate()
        .map(|(rank, ((p, q), c))| ((p, q), probed(&[p, q], &c, rank)))
        .collect();
    let label = |p: usize| {
        let fi = patched[p].face;
        (fi, topology.names(&topology.faces[fi].curves).join("', '"))
    };
    let mut warnings = Vec::new();
    for (p, w) in inside {
        let Some(w) = w else { continue };
        let (fi, names) = label(p);
        warnings.push(fold_warning(
            topology,
            &[p],
            patched,
            format!(
                "face {fi} (curves '{names}') folds: {} pair(s) of neighbouring mesh faces inside its patch meet at up to {:.1}° (more than {FOLD_ANGLE_DEGREES}°) near ({:.3}, {:.3}, {:.3}){}",
                w.count, w.angle, w.at.x, w.at.y, w.at.z, surface_note(&w)
            ),
            w.at,
        ));
    }
    for ((p, q), w) in across {
        let Some(w) = w else { continue };
        let ((fa, _), (fb, _)) = (label(p), label(q));
        warnings.push(fold_warning(
            topology,
            &[p, q],
            patched,
            format!(
                "faces {fa} and {fb} fold where they meet: their mesh faces meet at up to {:.1}° (more than {FOLD_ANGLE_DEGREES}°, and the edge is no knuckle) near ({:.3}, {:.3}, {:.3}){}",
                w.angle, w.at.x, w.at.y, w.at.z, surface_note(&w)
            ),
            w.at,
        ));
    }
    warnings.extend(box_warnings(topology, patched, mesh, boxes, tolerance));
    FoldFindings {
        warnings,
        max_angle_deg,
        max_angle_at,
    }
}

/// A fold warning about the faces of `patches`, naming their curves.
fn fold_warning(
    topology: &Topology,
    patches: &[usize],
    patched: &[PatchedFace],
    message: String,
    at: DVec3,
) -> Warning {
    let mut curves: Vec<String> = patches
        .iter()
        .flat_map(|&p| topology.names(&topology.faces[patched[p].face].curves))
        .map(str::to_owned)
        .collect();
    curves.sort();
    curves.dedup();
    Warning {
        kind: WarningKind::Fold,
        message,
        curves,
        location: Some(at),
        error: None,
    }
}

/// The box of every patch's boundary, sampled along its network edges.
pub(crate) fn boundary_boxes(
    network: &crate::network::Network,
    topology: &Topology,
    patched: &[PatchedFace],
) -> Vec<(DVec3, DVec3)> {
    let curves = network.curves();
    patched
        .iter()
        .map(|p| {
            let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for seg in p.layout.iter().flatten() {
                let e = &topology.brep.edges[seg.edge];
                for j in 0..=BOX_SAMPLES {
                    let t = e.t0 + (e.t1 - e.t0) * j as f64 / BOX_SAMPLES as f64;
                    let x = curves[e.curve].curve.point(t);
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
            (lo, hi)
        })
        .collect()
}

/// One warning per patch whose mesh stands out of its boundary's box by more than
/// [`BOX_SLACK`] of the box's diagonal (plus the near-miss distance).
fn box_warnings(
    topology: &Topology,
    patched: &[PatchedFace],
    mesh: &SurfaceMesh,
    boxes: &[(DVec3, DVec3)],
    tolerance: Tolerance,
) -> Vec<Warning> {
    let mut worst: Vec<(f64, DVec3)> = vec![(0.0, DVec3::ZERO); patched.len()];
    for (f, face) in mesh.faces().enumerate() {
        let p = mesh.face_patch[f] as usize;
        let (lo, hi) = boxes[p];
        for &v in face {
            let x = DVec3::from(mesh.positions[v as usize]);
            let out = (lo - x).max(x - hi).max(DVec3::ZERO).length();
            if out > worst[p].0 {
                worst[p] = (out, x);
            }
        }
    }
    let mut warnings = Vec::new();
    for (p, &(out, at)) in worst.iter().enumerate() {
        let (lo, hi) = boxes[p];
        let allowed = BOX_SLACK * (hi - lo).length() + tolerance.near_miss();
        if out <= allowed {
            continue;
        }
        let fi = patched[p].face;
        let names = topology.names(&topology.faces[fi].curves).join("', '");
        warnings.push(fold_warning(
            topology,
            &[p],
            patched,
            format!(
                "face {fi} (curves '{names}') stands {out:.3} m out of the box of its boundary curves (more than the {allowed:.3} m its size allows) at ({:.3}, {:.3}, {:.3}): the patch bulges or folds away from its curves",
                at.x, at.y, at.z
            ),
            at,
        ));
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;
    use crate::patch::{FaceBoundary, PatchKind, PatchOptions, Side, SideSegment};

    /// `shared_sides` gives what sorting every polygon side at once gives: the sides exactly
    /// two polygons have, in order, on meshes of random triangles and quads over few vertices
    /// (sides had by one, two, three or more polygons, polygons with a side twice, and a fan
    /// whose hub has more sides than the insertion sort takes).
    #[test]
    fn shared_sides_are_the_sides_two_polygons_have_in_order() {
        use rand_core::{Rng, SeedableRng};
        let mut rng = rand_xorshift::XorShiftRng::seed_from_u64(0x9e37_79b9_7f4a_7c15);
        let mut next = |n: u32| (rng.next_u64() % u64::from(n)) as u32;
        let mut found = 0;
        for vertices in [3u32, 5, 12, 40] {
            let mut polygons: Vec<Vec<u32>> = (0..60)
                .map(|_| {
                    let n = 3 + next(2) as usize;
                    (0..n).map(|_| next(vertices)).collect()
                })
                .collect();
            // A fan round vertex 0: a bucket longer than `SMALL_BUCKET`.
            polygons.extend((1..vertices).map(|v| vec![0, v, 1 + v % (vertices - 1)]));
            let faces: Vec<&[u32]> = polygons.iter().map(Vec::as_slice).collect();
            let mut all: Vec<(u32, u32, usize)> = Vec::new();
            for (fi, f) in faces.iter().enumerate() {
                for i in 0..f.len() {
                    let (a, b) = (f[i], f[(i + 1) % f.len()]);
                    all.push((a.min(b), a.max(b), fi));
                }
            }
            all.sort_unstable();
            let expected: Vec<(u32, u32, usize, usize)> = all
                .chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
                .filter_map(|run| match run {
                    [(lo, hi, f), (_, _, g)] => Some((*lo, *hi, *f, *g)),
                    _ => None,
                })
                .collect();
            found += expected.len();
            assert_eq!(
                shared_sides(&faces, vertices as usize),
                expected,
                "{vertices} vertices"
            );
        }
        assert!(found > 0, "some sides shared by two polygons");
    }

    /// The patch (`kind`) of the triangle `(0, 0)`, `(1, 0)`, `(0.05, 0.2)` whose first side
    /// waves by `wave` across its line (a cubic with its inner control points `±wave` off it),
    /// lifted by `lift(x, y)` in z.
    fn triangle(wave: f64, lift: impl Fn(f64, f64) -> f64, kind: PatchKind) -> Patch {
        let at = |x: f64, y: f64| DVec3::new(x, y, lift(x, y));
        let cubic = |pts: [(f64, f64); 4]| {
            let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
            NurbsCurve::try_new(3, knots, pts.map(|(x, y)| at(x, y)).to_vec(), None)
                .expect("a cubic")
        };
        let line = |(x0, y0): (f64, f64), (x1, y1): (f64, f64)| {
            cubic(
                [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].map(|t| (x0 + t * (x1 - x0), y0 + t * (y1 - y0))),
            )
        };
        let (a, b, c) = ((0.0, 0.0), (1.0, 0.0), (0.05, 0.2));
        let sides = [
            cubic([a, (0.3, wave), (0.6, -wave), b]),
            line(b, c),
            line(c, a),
        ]
        .into_iter()
        .map(|curve| Side::single(SideSegment::whole(curve)))
        .collect();
        let options = PatchOptions {
            kind,
            ..PatchOptions::default()
        };
        Patch::try_new(&FaceBoundary::new(sides), &[], &options).expect("a patch")
    }

    #[test]
    fn a_side_waving_like_an_s_keeps_the_charrot_gregory_patch_from_turning_over() {
        // With the ribbon's angle blended in the frame of the side's tangent, the ribbon
        // leaving the corners turned with the S and pointed out of the face: cells of
        // this patch turned over (more than 100). Carried along the side, it does not.
        let flat = |_: f64, _: f64| 0.0;
        let folds = in_plane_folds(&triangle(0.15, flat, PatchKind::Auto), Tolerance::DEFAULT);
        assert!(folds <= 1, "{folds} cells turned over");
    }

    #[test]
    fn a_flat_patch_turned_over_in_its_plane_is_found() {
        let flat = |_: f64, _: f64| 0.0;
        let tol = Tolerance::DEFAULT;
        assert_eq!(
            in_plane_folds(&triangle(0.0, flat, PatchKind::Auto), tol),
            0,
            "a plain triangle"
        );
        let folds = in_plane_folds(&triangle(0.2, flat, PatchKind::Auto), tol);
        assert!(
            folds > 100,
            "a waving side folds the Charrot–Gregory patch: {folds} cells"
        );
        let blended = in_plane_folds(&triangle(0.2, flat, PatchKind::SideBlend), tol);
        assert_eq!(blended, 0, "the side-blended patch does not fold");
        // Out of the plane by more than the tolerance: not looked at.
        let bent = |x: f64, y: f64| 0.05 * x * y;
        assert_eq!(
            in_plane_folds(&triangle(0.2, bent, PatchKind::Auto), tol),
            0
        );
    }

    /// A cubic B-spline with its pieces joined C¹ at `knots` (each thrice).
    fn pieces(points: &[[f64; 3]], joints: &[f64]) -> NurbsCurve {
        let mut knots = vec![0.0; 4];
        for &k in joints {
            knots.extend([k; 3]);
        }
        knots.extend([1.0; 4]);
        NurbsCurve::try_new(
            3,
            knots,
            points.iter().map(|&p| DVec3::from(p)).collect(),
            None,
        )
        .expect("a cubic")
    }

    /// The line from `a` to `b` as a cubic.
    fn line(a: [f64; 3], b: [f64; 3]) -> NurbsCurve {
        let (a, b) = (DVec3::from(a), DVec3::from(b));
        let points = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].map(|t| (a + (b - a) * t).to_array());
        pieces(&points, &[])
    }

    /// The quad over `[0, 1]²` in x and y that steps up by `rise` in z across the band
    /// `0.5 ± half` of x (a smooth S, flat either side): a ridge far narrower than the
    /// polygons of its mesh at resolution 8.
    fn step(rise: f64, half: f64) -> Patch {
        let (a, b) = (0.5 - half, 0.5 + half);
        let at = |x: f64, y: f64, z: f64| [x, y, z];
        let s = |y: f64| {
            pieces(
                &[
                    at(0.0, y, 0.0),
                    at(a / 3.0, y, 0.0),
                    at(2.0 * a / 3.0, y, 0.0),
                    at(a, y, 0.0),
                    at(a + half / 1.5, y, 0.0),
                    at(b - half / 1.5, y, rise),
                    at(b, y, rise),
                    at(b + (1.0 - b) / 3.0, y, rise),
                    at(b + 2.0 * (1.0 - b) / 3.0, y, rise),
                    at(1.0, y, rise),
                ],
                &[a, b],
            )
        };
        let reversed = |c: NurbsCurve| c.reversed();
        let sides = [
            s(0.0),
            line(at(1.0, 0.0, rise), at(1.0, 1.0, rise)),
            reversed(s(1.0)),
            line(at(0.0, 1.0, 0.0), at(0.0, 0.0, 0.0)),
        ]
        .into_iter()
        .map(|curve| Side::single(SideSegment::whole(curve)))
        .collect();
        Patch::try_new(&FaceBoundary::new(sides), &[], &PatchOptions::default()).expect("a patch")
    }

    #[test]
    fn a_ridge_narrower_than_the_mesh_is_a_smooth_turn_not_a_fold() {
        let patch = step(0.1, 0.01);
        let folds = face_mesh_folds(&patch.face_mesh(8));
        assert!(
            folds.worst > FOLD_ANGLE_DEGREES,
            "the mesh's polygons meet at {}°",
            folds.worst
        );
        let at = patch.eval([0.5, 0.5]);
        let turn = surface_turn(&[&patch], at, 0.3, FOLD_ANGLE_DEGREES);
        // 40.5° between polygons; 14.1° between the cells the probe stops at.
        assert!(
            turn < FOLD_ANGLE_DEGREES,
            "the surface turns by {turn}° between fine cells"
        );
        // The same ridge made a cliff (no band to turn in) stays a fold however fine: 75.9°.
        let crease = step(0.1, 1e-9);
        let turn = surface_turn(&[&crease], at, 0.3, FOLD_ANGLE_DEGREES);
        assert!(turn > FOLD_ANGLE_DEGREES, "the crease turns by {turn}°");
    }

    /// The flat quad through `corners` (in order, its sides straight).
    fn quad(corners: [[f64; 3]; 4]) -> Patch {
        let sides = (0..4)
            .map(|i| Side::single(SideSegment::whole(line(corners[i], corners[(i + 1) % 4]))))
            .collect();
        Patch::try_new(&FaceBoundary::new(sides), &[], &PatchOptions::default()).expect("a patch")
    }

    #[test]
    fn the_two_faces_of_an_edge_are_looked_at_across_it() {
        // Two squares side by side in z = 0, both facing up: one flat surface across x = 1.
        let left = quad([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        let right = quad([
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ]);
        let at = DVec3::new(1.0, 0.5, 0.0);
        let turn = surface_turn(&[&left, &right], at, 0.3, FOLD_ANGLE_DEGREES);
        assert!(turn < 1e-6, "{turn}°");
        // The right one facing down: neither folds alone, but they meet turned over.
        let over = quad([
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
        ]);
        assert!(surface_turn(&[&over], at, 0.3, FOLD_ANGLE_DEGREES) < 1e-6);
        let turn = surface_turn(&[&left, &over], at, 0.3, FOLD_ANGLE_DEGREES);
        assert!(turn > 179.0, "{turn}°");
    }

    #[test]
    fn a_place_the_patch_comes_nowhere_near_is_not_looked_at() {
        let patch = step(0.1, 0.01);
        assert_eq!(
            surface_turn(
                &[&patch],
                DVec3::new(5.0, 5.0, 5.0),
                0.1,
                FOLD_ANGLE_DEGREES
            ),
            0.0
        );
    }
}
