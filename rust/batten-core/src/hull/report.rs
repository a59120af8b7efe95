//! The hull report (H-rep paper §3–§5): counts, fit of the patches to the designer's curves,
//! continuity across the edges, crease angles along knuckles, and the volume of the half hull.

use std::collections::BTreeMap;

use glam::DVec3;
use rayon::prelude::*;

use super::knuckles::{knuckle_report, Knuckle};
use super::HullReport;
use crate::network::Network;
use crate::patch::{Patch, SurfaceMesh};
use crate::topo::Topology;

/// Where the edges of one patch went: per side, per segment, `(edge index, runs along the
/// curve)`.
pub(crate) type PatchLayout = Vec<Vec<(usize, bool)>>;

/// Samples per side segment for the gap between patch and curve (ends included).
const GAP_SAMPLES: usize = 16;
/// Samples per shared edge for the normal angle (at the midpoints of 16 equal parameter
/// intervals, so the corners, where a patch's normal comes from one-sided differences of two
/// sides at once, are not sampled).
const NORMAL_SAMPLES: usize = 16;

/// One use of an edge by a patch: patch, side, segment, runs along the curve.
type Use = (usize, usize, usize, bool);

/// Σ over the mesh polygons of their area vectors: the surface's mean normal times its area.
pub(crate) fn area_vector(mesh: &SurfaceMesh) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for_each_triangle(mesh, |a, b, c| sum += (b - a).cross(c - a) * 0.5);
    sum
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
    let p = |v: u32| DVec3::from(mesh.positions[v as usize]);
    let tri = |a: DVec3, b: DVec3, c: DVec3| (a.y + b.y + c.y) / 6.0 * (b - a).cross(c - a).y;
    let mut sum = 0.0;
    for face in mesh.faces() {
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

/// Call `f` on the triangles of a fan triangulation of every mesh polygon.
fn for_each_triangle(mesh: &SurfaceMesh, mut f: impl FnMut(DVec3, DVec3, DVec3)) {
    let p = |v: u32| DVec3::from(mesh.positions[v as usize]);
    for face in mesh.faces() {
        let a = p(face[0]);
        for w in face[1..].windows(2) {
            f(a, p(w[0]), p(w[1]));
        }
    }
}

/// The normal of `patch` at fraction `lambda` (of the curve's parameter interval, from `t0`)
/// of the edge it uses as segment `seg` of side `side`.
fn edge_normal_at(patch: &Patch, side: usize, seg: usize, forward: bool, lambda: f64) -> DVec3 {
    let local = if forward { lambda } else { 1.0 - lambda };
    let s = patch.segment_side_parameter(side, seg, local);
    patch.normal(patch.domain().side_point(side, s))
}

/// Build the report from the built patches.
#[allow(clippy::too_many_arguments)]
pub(crate) fn report(
    network: &Network,
    topology: &Topology,
    patches: &[Patch],
    layouts: &[PatchLayout],
    knuckle: &[Option<Knuckle>],
    mesh: &SurfaceMesh,
    skipped_faces: usize,
    warnings: Vec<String>,
) -> HullReport {
    let brep = &topology.brep;
    let curves = network.curves();
    let mut faces_by_sides = BTreeMap::new();
    for p in patches {
        *faces_by_sides.entry(p.sides()).or_insert(0) += 1;
    }
    let mut uses: Vec<Vec<Use>> = vec![Vec::new(); brep.edges.len()];
    for (pi, layout) in layouts.iter().enumerate() {
        for (si, side) in layout.iter().enumerate() {
            for (ki, &(edge, fwd)) in side.iter().enumerate() {
                uses[edge].push((pi, si, ki, fwd));
            }
        }
    }
    let open_edges = uses.iter().filter(|u| u.len() == 1).count();

    // Gap between every patch side and its designer curve.
    let max_gap = patches
        .par_iter()
        .zip(layouts.par_iter())
        .map(|(patch, layout)| {
            let mut worst: f64 = 0.0;
            for (si, side) in layout.iter().enumerate() {
                for (ki, &(edge, fwd)) in side.iter().enumerate() {
                    let e = &brep.edges[edge];
                    let curve = &curves[e.curve].curve;
                    let (ta, tb) = if fwd { (e.t0, e.t1) } else { (e.t1, e.t0) };
                    for j in 0..=GAP_SAMPLES {
                        let lam = j as f64 / GAP_SAMPLES as f64;
                        let s = patch.segment_side_parameter(si, ki, lam);
                        let t = ta + lam * (tb - ta);
                        let gap = (patch.side_point(si, s) - curve.point(t)).length();
                        worst = worst.max(gap);
                    }
                }
            }
            worst
        })
        .reduce(|| 0.0, f64::max);

    // Normal angles across every edge shared by two patches: (edge, min, max).
    let angles: Vec<(usize, f64, f64)> = uses
        .par_iter()
        .enumerate()
        .filter(|(_, u)| u.len() == 2)
        .filter_map(|(edge, u)| {
            let ((pa, sa, ka, fa), (pb, sb, kb, fb)) = (u[0], u[1]);
            let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
            for j in 0..NORMAL_SAMPLES {
                let lam = (j as f64 + 0.5) / NORMAL_SAMPLES as f64;
                let na = edge_normal_at(&patches[pa], sa, ka, fa, lam);
                let nb = edge_normal_at(&patches[pb], sb, kb, fb, lam);
                if na == DVec3::ZERO || nb == DVec3::ZERO {
                    continue;
                }
                let ang = na.angle_between(nb).to_degrees();
                lo = lo.min(ang);
                hi = hi.max(ang);
            }
            (lo <= hi).then_some((edge, lo, hi))
        })
        .collect();
    let mut max_normal_angle_deg: f64 = 0.0;
    let mut creases: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    let mut edge_creases: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    for &(edge, lo, hi) in &angles {
        if knuckle[edge].is_some() {
            edge_creases.insert(edge, (lo, hi));
            let c = creases
                .entry(brep.edges[edge].curve)
                .or_insert((f64::INFINITY, 0.0));
            c.0 = c.0.min(lo);
            c.1 = c.1.max(hi);
        } else {
            max_normal_angle_deg = max_normal_angle_deg.max(hi);
        }
    }
    let crease_angles_deg = creases
        .into_iter()
        .map(|(c, (lo, hi))| (curves[c].name.clone(), lo, hi))
        .collect();

    HullReport {
        nodes: topology.node_count(),
        edges: topology.edge_count(),
        faces: patches.len(),
        faces_by_sides,
        skipped_faces,
        open_edges,
        max_gap,
        max_normal_angle_deg,
        crease_angles_deg,
        knuckle_edges: knuckle_report(network, topology, knuckle, &edge_creases),
        volume: signed_volume(mesh).abs(),
        warnings,
    }
}
