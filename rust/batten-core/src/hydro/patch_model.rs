//! batten's own patch surface as a [`HullGeometry`]: its patches as cells of Bernstein
//! polynomials ([`cells`](super::cells)), integrated exactly below the water
//! ([`clip`](super::clip)) and cut by planes ([`contour`](super::contour)); its free edges from
//! the welded mesh.

use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;

use super::bernstein::{basis, N};
use super::cells::{patch_cells, Cell, CellDensity, CellMoments};
use super::clip::{wetness, CellWetness};
use super::contour::cell_section;
use super::geometry::{HullGeometry, OpenChain, SectionArc, SectionSegment};
use super::integrals::WetIntegrals;
use super::mesh::boundary::boundary;
use super::waterplane::Waterplane;
use crate::patch::{Patch, SurfaceMesh};

/// How near the water (relative to the hull's size) a cell may reach and still count as wholly
/// wet or dry: the rounding of a waterplane along a network curve.
const WETNESS_SLACK_RELATIVE: f64 = 1e-11;

/// How far (relative to the hull's size) a section's plane is moved off the one asked for, so a
/// plane along a network curve — a station where a station was drawn — cuts the cells on one
/// side of it, not both (its pieces would count twice); the areas move by as little.
const SECTION_NUDGE_RELATIVE: f64 = 1e-10;

/// How close to the centreplane (relative to the hull's size) a free edge must lie to be a half
/// hull's profile, closed by its mirror image.
pub const CENTREPLANE_RELATIVE: f64 = 1e-5;

/// Samples per cell side when looking for the extent of the wet surface (about a centimetre on a
/// ship, where a cell is a few metres).
const RANGE_SAMPLES: usize = 8;

/// The mirror image `y → −y`.
#[inline]
fn mirror(p: DVec3) -> DVec3 {
    DVec3::new(p.x, -p.y, p.z)
}

/// A hull's patch surface ready for hydrostatics: its cells with their boxes, whether it is a
/// half hull, and its free edges off the centreplane.
///
/// The cells are held patch by patch (shared, so a model of the same hull after an edit,
/// [`PatchHydroModel::updated`], keeps those of the patches the edit did not reach) and read in
/// the order of their boxes' lowest `x`.
#[derive(Clone, Debug)]
pub struct PatchHydroModel {
    /// Per patch: its topology face and its cells, in patch order.
    patches: Vec<(usize, Arc<FaceCells>)>,
    /// `(patch, cell)` of each cell, in order of their boxes' lowest `x` (a stable sort of the
    /// patch order, so a model made in any way from the same cells reads them alike).
    order: Vec<(u32, u32)>,
    boxes: Vec<(DVec3, DVec3)>,
    /// The largest extent in `x` of a cell's box (the cells are in order of their boxes' lowest
    /// `x`, so a station reads only the cells within this of it).
    max_dx: f64,
    half: bool,
    open: Vec<OpenChain>,
    bounds: (DVec3, DVec3),
    outward: bool,
    density: CellDensity,
    /// How many of the cells were kept from an earlier model ([`PatchHydroModel::updated`]).
    kept: usize,
}

/// Cells folded one after another per chunk of the box order, the chunks' sums added in order:
/// the wet integrals are the same bit for bit whatever the threads do.
const FOLD_CHUNK: usize = 256;

/// The cells of one patch and their boxes (in the same order).
#[derive(Debug)]
struct FaceCells {
    cells: Vec<Cell>,
    boxes: Vec<Aabb>,
}

impl FaceCells {
    fn new(cells: Vec<Cell>) -> FaceCells {
        let boxes = cells.iter().map(net_box).collect();
        FaceCells { cells, boxes }
    }
}

/// `(patch, cell)`: where a cell is held.
type CellKey = (u32, u32);
/// A box `(lowest, highest)`.
type Aabb = (DVec3, DVec3);

/// The box of a cell's net (it holds the polynomial).
fn net_box(cell: &Cell) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in cell.net.iter().flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (lo, hi)
}

/// The range of `m·p` over a box.
#[inline]
fn box_range(b: &(DVec3, DVec3), m: DVec3) -> (f64, f64) {
    let lo = DVec3::new(
        if m.x >= 0.0 { b.0.x } else { b.1.x },
        if m.y >= 0.0 { b.0.y } else { b.1.y },
        if m.z >= 0.0 { b.0.z } else { b.1.z },
    );
    let hi = b.0 + b.1 - lo;
    (m.dot(lo), m.dot(hi))
}

impl PatchHydroModel {
    /// The model of a hull surface from its patches (`outward`: whether their `∂P/∂u × ∂P/∂v`
    /// points out of the hull) and its welded mesh (for the free edges), with cells of
    /// `density`, built in parallel. [`HullSurface::hydro_model`](crate::HullSurface::hydro_model)
    /// gives it for a built hull.
    pub fn new(
        patches: &[Patch],
        outward: bool,
        mesh: &SurfaceMesh,
        density: CellDensity,
    ) -> PatchHydroModel {
        let faces: Vec<usize> = (0..patches.len()).collect();
        PatchHydroModel::of_faces(patches, &faces, outward, mesh, density, None)
    }

    /// The model of `patches` (`faces[k]` the topology face of `patches[k]`), as
    /// [`PatchHydroModel::new`], keeping from `previous` — a model of the same hull before an
    /// edit — the cells of every face that `changed` does not name (when it was made with the
    /// same density and orientation): the result is the model `new` makes, bit for bit, at the
    /// cost of the changed faces' cells. [`HullSurface::hydro_model_after`](crate::HullSurface::hydro_model_after)
    /// gives it for a live rebuild.
    pub fn updated(
        previous: &PatchHydroModel,
        patches: &[Patch],
        faces: &[usize],
        changed: &(dyn Fn(usize) -> bool + Sync),
        outward: bool,
        mesh: &SurfaceMesh,
    ) -> PatchHydroModel {
        let keep = (previous.outward == outward).then_some((previous, changed));
        PatchHydroModel::of_faces(patches, faces, outward, mesh, previous.density, keep)
    }

    /// [`PatchHydroModel::updated`] from `previous`, or a new model of `patches` (of topology
    /// `faces`) at `density`.
    pub(crate) fn updated_or_new(
        previous: Option<(&PatchHydroModel, &(dyn Fn(usize) -> bool + Sync))>,
        patches: &[Patch],
        faces: &[usize],
        outward: bool,
        mesh: &SurfaceMesh,
        density: CellDensity,
    ) -> PatchHydroModel {
        match previous {
            Some((prev, changed)) => {
                PatchHydroModel::updated(prev, patches, faces, changed, outward, mesh)
            }
            None => PatchHydroModel::of_faces(patches, faces, outward, mesh, density, None),
        }
    }

    /// The model of `patches` of topology `faces`, reusing the cells of the unchanged faces of
    /// `keep`'s model.
    fn of_faces(
        patches: &[Patch],
        faces: &[usize],
        outward: bool,
        mesh: &SurfaceMesh,
        density: CellDensity,
        keep: Option<(&PatchHydroModel, &(dyn Fn(usize) -> bool + Sync))>,
    ) -> PatchHydroModel {
        let kept = |face: usize| -> Option<Arc<FaceCells>> {
            let (prev, changed) = keep?;
            if changed(face) {
                return None;
            }
            let k = prev.patches.binary_search_by_key(&face, |p| p.0).ok()?;
            Some(prev.patches[k].1.clone())
        };
        let per_patch: Vec<(usize, Arc<FaceCells>, bool)> = patches
            .par_iter()
            .zip(faces)
            .map(|(patch, &face)| match kept(face) {
                Some(cells) => (face, cells, true),
                None => (
                    face,
                    Arc::new(FaceCells::new(patch_cells(patch, outward, density))),
                    false,
                ),
            })
            .collect();
        let kept_cells = per_patch
            .iter()
            .filter(|p| p.2)
            .map(|p| p.1.cells.len())
            .sum();
        let per_patch: Vec<(usize, Arc<FaceCells>)> =
            per_patch.into_iter().map(|(f, c, _)| (f, c)).collect();
        // Kept patches bring their boxes: only the sort is done again.
        let mut keyed: Vec<(CellKey, Aabb)> = Vec::new();
        for (p, (_, face)) in per_patch.iter().enumerate() {
            for (c, b) in face.boxes.iter().enumerate() {
                keyed.push(((p as u32, c as u32), *b));
            }
        }
        keyed.sort_by(|a, b| a.1 .0.x.total_cmp(&b.1 .0.x));
        let (order, boxes): (Vec<CellKey>, Vec<Aabb>) = keyed.into_iter().unzip();
        let max_dx = boxes.iter().map(|b| b.1.x - b.0.x).fold(0.0, f64::max);
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for b in &boxes {
            lo = lo.min(b.0);
            hi = hi.max(b.1);
        }
        let size = (hi - lo).length();
        let near = CENTREPLANE_RELATIVE * size;
        // The free edges and the half-hull test from the welded mesh (its points lie on the
        // surface, where a cell's net may reach beyond a folded patch), fanned into triangles.
        let positions: Vec<DVec3> = mesh.positions.iter().map(|p| DVec3::from(*p)).collect();
        let triangles: Vec<[u32; 3]> = mesh
            .faces()
            .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
            .collect();
        let found = boundary(&positions, &triangles, near);
        let (half, open) = (found.half, found.open);
        if half {
            lo.y = lo.y.min(-hi.y);
        }
        PatchHydroModel {
            patches: per_patch,
            order,
            boxes,
            max_dx,
            half,
            open,
            bounds: (lo, hi),
            outward,
            density,
            kept: kept_cells,
        }
    }

    /// The `k`-th cell in box order.
    #[inline]
    fn cell(&self, k: usize) -> &Cell {
        let (p, c) = self.order[k];
        &self.patches[p as usize].1.cells[c as usize]
    }

    /// The diagonal of the surface's box.
    fn size(&self) -> f64 {
        (self.bounds.1 - self.bounds.0).length()
    }

    /// Number of cells (for benchmarks and reports).
    pub fn cell_count(&self) -> usize {
        self.order.len()
    }

    /// How many cells were kept from the earlier model [`PatchHydroModel::updated`] was given
    /// (0 for a new model).
    pub fn kept_cell_count(&self) -> usize {
        self.kept
    }

    /// The density of the cells.
    pub fn density(&self) -> CellDensity {
        self.density
    }

    /// The integrals of the drawn half (or whole) in `plane`.
    fn own_integrals(&self, plane: &Waterplane) -> WetIntegrals {
        let c = plane.e3.dot(plane.origin);
        let slack = WETNESS_SLACK_RELATIVE * self.size();
        let parts: Vec<(CellMoments, WetIntegrals)> = (0..self.order.len())
            .step_by(FOLD_CHUNK)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|start| {
                let (mut m, mut w) = (CellMoments::default(), WetIntegrals::default());
                for k in start..(start + FOLD_CHUNK).min(self.order.len()) {
                    let (lo, hi) = box_range(&self.boxes[k], plane.e3);
                    if lo - c >= -slack {
                        continue;
                    }
                    let cell = self.cell(k);
                    if hi - c <= slack {
                        m.add(&cell.moments);
                        continue;
                    }
                    match wetness(cell, plane, slack) {
                        CellWetness::Dry => {}
                        CellWetness::Wet => m.add(&cell.moments),
                        CellWetness::Cut(x) => w += x,
                    }
                }
                (m, w)
            })
            .collect();
        let (mut moments, mut cut) = (CellMoments::default(), WetIntegrals::default());
        for (m, w) in &parts {
            moments.add(m);
            cut += *w;
        }
        moments.in_frame(plane) + cut
    }

    /// The section of the drawn half by `m·p = c`, from the cells whose boxes `keep` passes.
    fn own_section(
        &self,
        m: DVec3,
        c: f64,
        tolerance: f64,
        keep: &(dyn Fn(&(DVec3, DVec3)) -> bool + Sync),
    ) -> Vec<SectionArc> {
        let c = c + SECTION_NUDGE_RELATIVE * self.size();
        // A station (m = x) reads only the cells whose boxes can reach it.
        let (first, last) = if m == DVec3::X {
            (
                self.boxes.partition_point(|b| b.0.x < c - self.max_dx),
                self.boxes.partition_point(|b| b.0.x <= c),
            )
        } else {
            (0, self.order.len())
        };
        // The box test is cheap: done in one go, so the parallel work is the cells cut.
        let cut: Vec<usize> = (first..last)
            .filter(|&k| {
                let b = &self.boxes[k];
                let (lo, hi) = box_range(b, m);
                lo <= c && hi >= c && keep(b)
            })
            .collect();
        cut.par_iter()
            .flat_map_iter(|&k| {
                let mut out = Vec::new();
                cell_section(self.cell(k), m, c, tolerance, &mut out);
                out
            })
            .collect()
    }

    /// The section of both halves by `m·p = c` (see [`HullGeometry::section_arcs`]), from the
    /// cells whose boxes `keep` passes.
    fn arcs_of(
        &self,
        m: DVec3,
        c: f64,
        tolerance: f64,
        keep: &(dyn Fn(&(DVec3, DVec3)) -> bool + Sync),
    ) -> Vec<SectionArc> {
        let mut out = self.own_section(m, c, tolerance, keep);
        if self.half {
            // The image's section is the mirrored section of the half by the mirrored plane,
            // its direction reversed (a reflection turns m × n round).
            // A plane square to the centreplane (a station, an upright waterplane) is its own
            // image: the half's pieces, mirrored, are the image's.
            let image = if m.y == 0.0 {
                out.clone()
            } else {
                self.own_section(mirror(m), c, tolerance, keep)
            };
            out.extend(
                image
                    .into_iter()
                    .map(|[a, p, b]| [mirror(b), mirror(p), mirror(a)]),
            );
        }
        out
    }

    /// The range of `dir·p` over the wet part of the drawn half: the ends of the waterline's
    /// pieces, then samples of the cells under water whose boxes reach beyond that range.
    fn own_range(
        &self,
        plane: &Waterplane,
        dir: DVec3,
        waterline: &[SectionSegment],
    ) -> Option<(f64, f64)> {
        let c = plane.e3.dot(plane.origin);
        let mut range = waterline
            .iter()
            .flatten()
            .map(|p| Some((dir.dot(*p), dir.dot(*p))))
            .fold(None, merge);
        // Cells under water whose box pokes out of the range so far, furthest first.
        let mut candidates: Vec<(f64, usize)> = self
            .boxes
            .iter()
            .enumerate()
            .filter(|(_, b)| box_range(b, plane.e3).0 < c)
            .filter_map(|(k, b)| {
                let (lo, hi) = box_range(b, dir);
                let reach = match range {
                    Some((a, z)) => (a - lo).max(hi - z),
                    None => f64::INFINITY,
                };
                (reach > 0.0).then_some((reach, k))
            })
            .collect();
        candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
        let samples: [[f64; N]; RANGE_SAMPLES + 1] =
            std::array::from_fn(|k| basis(k as f64 / RANGE_SAMPLES as f64).0);
        for (_, k) in candidates {
            let (lo, hi) = box_range(&self.boxes[k], dir);
            if let Some((a, z)) = range {
                if lo >= a && hi <= z {
                    continue;
                }
            }
            self.cell(k).grid_points(&samples, |p| {
                if plane.zeta(p) <= 0.0 {
                    let v = dir.dot(p);
                    range = merge(range, Some((v, v)));
                }
            });
        }
        range
    }
}

fn merge(a: Option<(f64, f64)>, b: Option<(f64, f64)>) -> Option<(f64, f64)> {
    match (a, b) {
        (Some(x), Some(y)) => Some((x.0.min(y.0), x.1.max(y.1))),
        (x, None) => x,
        (None, y) => y,
    }
}

impl HullGeometry for PatchHydroModel {
    fn wet_integrals(&self, plane: &Waterplane) -> WetIntegrals {
        let own = self.own_integrals(plane);
        if !self.half {
            own
        } else if plane.is_upright() {
            own.with_mirror_upright()
        } else {
            own + self.own_integrals(&plane.mirrored())
        }
    }

    fn plane_section(&self, m: DVec3, c: f64, tolerance: f64) -> Vec<SectionSegment> {
        self.section_arcs(m, c, tolerance)
            .into_iter()
            .map(|[a, _, b]| [a, b])
            .collect()
    }

    fn section_arcs(&self, m: DVec3, c: f64, tolerance: f64) -> Vec<SectionArc> {
        self.arcs_of(m, c, tolerance, &|_| true)
    }

    fn section_arcs_below(
        &self,
        m: DVec3,
        c: f64,
        tolerance: f64,
        plane: &Waterplane,
    ) -> Vec<SectionArc> {
        // A cell whose box is above the water surface (of the half's plane, or for a half hull
        // of its image's) adds nothing below it: its pieces are left out.
        let image = plane.mirrored();
        let level = |p: &Waterplane| p.e3.dot(p.origin);
        let (own, mirrored) = (level(plane), level(&image));
        let below = |b: &(DVec3, DVec3)| {
            box_range(b, plane.e3).0 <= own || (self.half && box_range(b, image.e3).0 <= mirrored)
        };
        self.arcs_of(m, c, tolerance, &below)
    }

    fn bounds(&self) -> (DVec3, DVec3) {
        self.bounds
    }

    fn open_chains(&self) -> &[OpenChain] {
        &self.open
    }

    fn is_half(&self) -> bool {
        self.half
    }

    fn wet_range(
        &self,
        plane: &Waterplane,
        dir: DVec3,
        waterline: &[SectionSegment],
    ) -> Option<(f64, f64)> {
        // The waterline holds both halves, so its ends bound the image's range too.
        let own = self.own_range(plane, dir, waterline);
        // Upright, the image's range along a direction in the centreplane is the half's own.
        if self.half && !(plane.is_upright() && dir.y == 0.0) {
            merge(own, self.own_range(&plane.mirrored(), mirror(dir), &[]))
        } else {
            own
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hydro::bernstein::split1;
    use crate::hydro::cells::moments_of;
    use crate::{build_hull, HullOptions, Network};

    /// The four quarter nets of `net` (exact de Casteljau halving in both parameters).
    fn quarters(net: &[[DVec3; N]; N]) -> [[[DVec3; N]; N]; 4] {
        let mut l = [[DVec3::ZERO; N]; N];
        let mut r = [[DVec3::ZERO; N]; N];
        for j in 0..N {
            let col: [DVec3; N] = std::array::from_fn(|i| net[i][j]);
            let (a, b) = split1(&col, 0.5);
            for i in 0..N {
                l[i][j] = a[i];
                r[i][j] = b[i];
            }
        }
        let split_t = |z: &[[DVec3; N]; N]| {
            let mut a = [[DVec3::ZERO; N]; N];
            let mut b = [[DVec3::ZERO; N]; N];
            for i in 0..N {
                (a[i], b[i]) = split1(&z[i], 0.5);
            }
            (a, b)
        };
        let (ll, lr) = split_t(&l);
        let (rl, rr) = split_t(&r);
        [ll, lr, rl, rr]
    }

    /// Every cell the water cuts integrates as its four quarters do: the clipping (Saye's
    /// graphs, their roots and breaks) is exact for the polynomial, whatever way it goes.
    #[test]
    fn cut_cells_integrate_as_their_quarters() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/wigley_lines.json"
        );
        let net =
            Network::from_json(&std::fs::read_to_string(path).expect("example")).expect("network");
        let hull = build_hull(&net, &HullOptions::default()).expect("builds");
        let model = hull.hydro_model(CellDensity::DEFAULT);
        let mut cut = 0;
        for z in [3.1, 4.0, 5.9] {
            let plane = Waterplane::level(z);
            for cell in (0..model.cell_count()).map(|k| model.cell(k)) {
                let CellWetness::Cut(whole) = wetness(cell, &plane, 0.0) else {
                    continue;
                };
                cut += 1;
                let mut sum = WetIntegrals::default();
                for net in quarters(&cell.net) {
                    let mut kid = Cell {
                        net,
                        sign: cell.sign,
                        moments: CellMoments::default(),
                    };
                    kid.moments = moments_of(&kid);
                    match wetness(&kid, &plane, 0.0) {
                        CellWetness::Cut(w) => sum += w,
                        CellWetness::Wet => sum += kid.moments.in_frame(&plane),
                        CellWetness::Dry => {}
                    }
                }
                let scale = cell.moments.area;
                for (what, a, b) in [
                    ("area", whole.wetted, sum.wetted),
                    ("volume", whole.volume, sum.volume),
                    ("waterplane", whole.wp_area, sum.wp_area),
                ] {
                    assert!(
                        (a - b).abs() <= 1e-11 * scale.max(scale * z),
                        "{what} at z {z}: {a} vs quarters {b}"
                    );
                }
            }
        }
        assert!(cut > 50, "the water cuts many cells ({cut})");
    }
}
