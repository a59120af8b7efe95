//! Tessellation of patches into one welded mesh of quads and triangles.
//!
//! Every side is sampled from its designer curve itself: segment `k` of a side gets
//! `resolution` intervals — or its own count (`Patch::face_mesh_with`; the hull build gives
//! a segment more where a face along it turns tightly) — at the curve parameters of evenly
//! spaced fractions of the segment's own parameter (its speed map, always computed in the
//! curve's increasing parameter and reversed when the face traverses the segment backwards),
//! and its ends are the resolved node positions. Two faces sharing a segment with the same
//! count therefore emit bitwise identical boundary vertices whichever direction they see it in,
//! and [`tessellate_patches`] welds them by exact equality, never by a distance.
//!
//! Interiors: a 4-sided face whose opposite sides have equal sample counts is a grid of quads
//! (domain points by a discrete Coons interpolation of the boundary samples); any other face is
//! triangulated on concentric rings of its domain polygon (ring `r` has `K − r` intervals per
//! side, `K` the mean boundary count; a zipper joins the boundary to the first ring), which has
//! no slivers for regular counts. Faces are counter-clockwise in the domain, so their normals
//! point outwards for a counter-clockwise (seen from outside) face.

use rustc_hash::FxHashMap;
use std::borrow::Borrow;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::domain::{lattice_parameter, square_rings};
use super::error::PatchError;
use super::face_patch::Patch;

/// A polygon mesh in plain arrays, as the Blender bridge wants it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceMesh {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Vertex indices of all faces, face after face (3 or 4 per face).
    pub face_vertices: Vec<u32>,
    /// Number of vertices of each face (3 or 4).
    pub face_sizes: Vec<u8>,
    /// Index of the patch each face belongs to (its position in the input slice).
    pub face_patch: Vec<u32>,
}

impl SurfaceMesh {
    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_sizes.len()
    }

    /// The vertex indices of every face, as slices (in face order).
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        polygons(&self.face_vertices, &self.face_sizes)
    }
}

/// The boundary samples of one face, counter-clockwise from corner 0, each corner once.
struct BoundaryRing {
    /// The surface points.
    points: Vec<DVec3>,
    /// Their domain points.
    domain: Vec<DVec2>,
    /// Index of the first sample of each side, and the sample count at the end.
    starts: Vec<usize>,
    /// Each sample's side parameter `s ∈ [0, 1)` along its side.
    side_parameters: Vec<f64>,
}

/// A vertex of a polyline the triangulation joins ([`fan`], [`zipper`]): its index and its
/// relative position along the strip (0 at the start, 1 at the end).
#[derive(Clone, Copy, Debug)]
struct RingPoint {
    vertex: u32,
    along: f64,
}

/// How the inside of a face is meshed: a structured grid of `nu × nv` quads for a 4-sided face
/// whose opposite sides have equal sample counts, else `k` rings of triangles towards the
/// centre of the domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Interior {
    Grid { nu: usize, nv: usize },
    Rings { k: usize },
}

impl Interior {
    /// The layout for a face with `counts[i]` boundary samples on side `i`.
    fn of(counts: &[usize]) -> Interior {
        let n = counts.len();
        if n == 4 && counts[0] == counts[2] && counts[1] == counts[3] {
            Interior::Grid {
                nu: counts[0],
                nv: counts[1],
            }
        } else {
            let total: usize = counts.iter().sum();
            Interior::Rings {
                k: ((total as f64 / n as f64).round() as usize).max(1),
            }
        }
    }

    /// Vertices inside the face (saturating, so a count too large for any mesh stays large):
    /// `(nu − 1)(nv − 1)` for a grid; `n·(k − 1) + … + n·1` ring points and the centre for rings.
    fn vertices(self, n: usize) -> usize {
        match self {
            Interior::Grid { nu, nv } => nu.saturating_sub(1).saturating_mul(nv.saturating_sub(1)),
            Interior::Rings { k } => n
                .saturating_mul(k.saturating_mul(k - 1) / 2)
                .saturating_add(1),
        }
    }
}

/// One face's mesh before welding: the first `boundary` vertices lie on the face boundary.
/// Kept per face by the hull's live rebuild, which meshes again only the faces that moved.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FaceMesh {
    positions: Vec<DVec3>,
    boundary: usize,
    /// The side and side parameter `s` of each boundary vertex (empty where not known).
    ring: Vec<(usize, f64)>,
    faces: Vec<u32>,
    sizes: Vec<u8>,
}

impl Patch {
    /// Tessellate this patch alone with `resolution` intervals per side segment.
    pub fn tessellate(&self, resolution: usize) -> Result<SurfaceMesh, PatchError> {
        tessellate_patches(std::slice::from_ref(self), resolution)
    }

    /// The number of side segments, over all sides in order: the length of the per-segment
    /// interval counts [`Patch::face_mesh_with`] takes.
    pub(crate) fn segment_count(&self) -> usize {
        self.prepared_sides()
            .iter()
            .map(|side| side.segs.len())
            .sum()
    }

    /// Boundary samples per side with `counts` intervals per segment (all sides' segments in
    /// order).
    fn side_counts(&self, counts: &[usize]) -> Vec<usize> {
        let mut next = counts.iter();
        self.prepared_sides()
            .iter()
            .map(|side| {
                side.segs
                    .iter()
                    .fold(0usize, |a, _| a.saturating_add(*next.next().unwrap_or(&1)))
            })
            .collect()
    }

    /// The vertices [`Patch::face_mesh`] makes at resolution `r`, counted without meshing.
    pub(crate) fn mesh_vertex_count(&self, r: usize) -> usize {
        self.mesh_vertex_count_with(&vec![r; self.segment_count()])
    }

    /// The vertices [`Patch::face_mesh_with`] makes with `counts`, counted without meshing.
    pub(crate) fn mesh_vertex_count_with(&self, counts: &[usize]) -> usize {
        let counts = self.side_counts(counts);
        let boundary = counts.iter().fold(0usize, |a, &c| a.saturating_add(c));
        boundary.saturating_add(Interior::of(&counts).vertices(counts.len()))
    }

    /// The boundary samples of the face in counter-clockwise order starting at corner 0 (each
    /// corner once), with their domain points: `counts[j]` intervals on segment `j` (all
    /// sides' segments in order).
    fn boundary_ring(&self, counts: &[usize]) -> BoundaryRing {
        let n = self.sides();
        let mut pts = Vec::new();
        let mut dom = Vec::new();
        let mut starts = Vec::with_capacity(n + 1);
        let mut lambdas = Vec::new();
        let mut next = counts.iter();
        for (i, side) in self.prepared_sides().iter().enumerate() {
            starts.push(pts.len());
            for (k, seg) in side.segs.iter().enumerate() {
                let r = *next.next().unwrap_or(&1);
                let (u0, u1) = (side.breaks[k], side.breaks[k + 1]);
                pts.push(seg.p0);
                dom.push(self.domain().side_point_v(i, u0));
                lambdas.push(u0);
                for q in 1..r {
                    let j = if seg.ta <= seg.tb { q } else { r - q };
                    let t = seg.canonical_sample(r, j);
                    let s = u0 + (u1 - u0) * (q as f64 / r as f64);
                    pts.push(seg.curve().point(t));
                    dom.push(self.domain().side_point_v(i, s));
                    lambdas.push(s);
                }
            }
        }
        starts.push(pts.len());
        BoundaryRing {
            points: pts,
            domain: dom,
            starts,
            side_parameters: lambdas,
        }
    }

    /// The domain points of the inside of a face meshed on `k` rings ([`Interior::Rings`]), in
    /// the order of [`Patch::face_mesh`]'s vertices: ring 1 to ring `k − 1` (ring `r` scaled
    /// by `1 − r/k` about the centre, `k − r` intervals per side), then the centre. On the
    /// unit square those points lie on the lattice of step `1/(2k)` ([`square_rings`]) and
    /// are taken there exactly.
    fn ring_domain(&self, k: usize) -> Vec<DVec2> {
        let n = self.sides();
        if n == 4 {
            let at = lattice_parameter(k);
            return square_rings(k)
                .into_iter()
                .map(|(i, j)| DVec2::new(at(i), at(j)))
                .collect();
        }
        let centre = self.domain().centre_v();
        let mut out = Vec::with_capacity(Interior::Rings { k }.vertices(n));
        for rr in 1..k {
            let scale = 1.0 - rr as f64 / k as f64;
            let m = k - rr;
            for i in 0..n {
                let a = centre + (self.domain().vertex(i) - centre) * scale;
                let c = centre + (self.domain().vertex(i + 1) - centre) * scale;
                out.extend((0..m).map(|j| a + (c - a) * (j as f64 / m as f64)));
            }
        }
        out.push(centre);
        out
    }

    /// The domain point of every vertex of [`Patch::face_mesh_with`] with `counts`, in its
    /// vertex order: where the surface point of each vertex was evaluated (for figures taken
    /// at the vertices, such as the curvature).
    pub(crate) fn mesh_domain_with(&self, counts: &[usize]) -> Vec<DVec2> {
        let ring = self.boundary_ring(counts);
        let counts: Vec<usize> = ring.starts.windows(2).map(|w| w[1] - w[0]).collect();
        let inside = match Interior::of(&counts) {
            Interior::Grid { nu, nv } => grid_domain(&ring.domain, nu, nv),
            Interior::Rings { k } => self.ring_domain(k),
        };
        let mut out = ring.domain;
        out.extend(inside);
        out
    }

    /// This patch's own mesh at resolution `r`, before welding ([`weld_face_meshes`]): `r`
    /// intervals on every side segment.
    pub(crate) fn face_mesh(&self, r: usize) -> FaceMesh {
        self.face_mesh_with(&vec![r; self.segment_count()])
    }

    /// This patch's own mesh with `counts[j]` intervals on side segment `j` (all sides'
    /// segments in order; two faces sharing a segment sample it alike when they give it the
    /// same count), before welding.
    pub(crate) fn face_mesh_with(&self, counts: &[usize]) -> FaceMesh {
        let n = self.sides();
        let BoundaryRing {
            points: mut positions,
            domain: dom,
            starts,
            side_parameters: lambdas,
        } = self.boundary_ring(counts);
        let b = positions.len();
        let counts: Vec<usize> = (0..n).map(|i| starts[i + 1] - starts[i]).collect();
        let mut faces = Vec::new();
        let mut sizes = Vec::new();
        let wrap = |q: usize| (q % b) as u32;
        match Interior::of(&counts) {
            Interior::Grid { nu, nv } => {
                let bidx = |a: usize, c: usize| -> Option<usize> {
                    if c == 0 {
                        Some(a)
                    } else if a == nu {
                        Some(nu + c)
                    } else if c == nv {
                        Some(nu + nv + (nu - a))
                    } else if a == 0 {
                        Some((2 * nu + nv + (nv - c)) % b)
                    } else {
                        None
                    }
                };
                let idx = |a: usize, c: usize| -> u32 {
                    bidx(a, c)
                        .map_or_else(|| (b + (c - 1) * (nu - 1) + (a - 1)) as u32, |q| q as u32)
                };
                positions.reserve((nu - 1) * (nv - 1));
                // Sides of one segment each sample the square evenly, so the inside is the
                // tensor grid of those parameters (what the blend below gives, up to
                // rounding), evaluated a column and a row at a time.
                let even = self.prepared_sides().iter().all(|s| s.segs.len() == 1);
                let grid = |n: usize| (1..n).map(|k| k as f64 / n as f64).collect::<Vec<_>>();
                let gridded = even && self.eval_grid(&grid(nu), &grid(nv), &mut positions);
                if !gridded {
                    let inside = grid_domain(&dom, nu, nv);
                    positions.extend(inside.into_iter().map(|x| self.eval_v(x)));
                }
                for c in 0..nv {
                    for a in 0..nu {
                        faces.extend([idx(a, c), idx(a + 1, c), idx(a + 1, c + 1), idx(a, c + 1)]);
                        sizes.push(4);
                    }
                }
            }
            Interior::Rings { k } => {
                // Ring r ≥ 1: (k − r) intervals per side, starting index base[r]; then the
                // centre.
                let mut base = vec![0usize; k];
                let mut next = b;
                for (rr, bs) in base.iter_mut().enumerate().skip(1) {
                    *bs = next;
                    next += n * (k - rr);
                }
                let centre_idx = next as u32;
                if !self.eval_square_rings(k, &mut positions) {
                    let inside = self.ring_domain(k);
                    positions.extend(inside.into_iter().map(|x| self.eval_v(x)));
                }
                let ring_side = |rr: usize, i: usize| -> Vec<RingPoint> {
                    let m = k - rr;
                    (0..=m)
                        .map(|j| {
                            let (ii, jj) = if j == m { ((i + 1) % n, 0) } else { (i, j) };
                            RingPoint {
                                vertex: (base[rr] + ii * m + jj) as u32,
                                along: j as f64 / m as f64,
                            }
                        })
                        .collect()
                };
                for i in 0..n {
                    let outer: Vec<RingPoint> = (starts[i]..=starts[i + 1])
                        .map(|q| RingPoint {
                            vertex: wrap(q),
                            along: if q == starts[i + 1] { 1.0 } else { lambdas[q] },
                        })
                        .collect();
                    if k == 1 {
                        fan(&outer, centre_idx, &mut faces, &mut sizes);
                    } else {
                        zipper(&outer, &ring_side(1, i), &mut faces, &mut sizes);
                    }
                    for rr in 1..k {
                        let o = ring_side(rr, i);
                        if rr + 1 < k {
                            zipper(&o, &ring_side(rr + 1, i), &mut faces, &mut sizes);
                        } else {
                            fan(&o, centre_idx, &mut faces, &mut sizes);
                        }
                    }
                }
            }
        }
        let ring = (0..n)
            .flat_map(|i| (starts[i]..starts[i + 1]).map(move |q| (i, q)))
            .map(|(i, q)| (i, lambdas[q]))
            .collect();
        FaceMesh {
            positions,
            boundary: b,
            ring,
            faces,
            sizes,
        }
    }
}

/// The inside domain points of a 4-sided face meshed as an `nu × nv` grid
/// ([`Interior::Grid`]), row after row, from the domain points `dom` of its boundary ring
/// (counter-clockwise from corner 0): the discrete Coons interpolation of the boundary.
fn grid_domain(dom: &[DVec2], nu: usize, nv: usize) -> Vec<DVec2> {
    let b = dom.len();
    let bd = |a: usize, c: usize| -> DVec2 {
        dom[if c == 0 {
            a
        } else if a == nu {
            nu + c
        } else if c == nv {
            nu + nv + (nu - a)
        } else {
            (2 * nu + nv + (nv - c)) % b
        }]
    };
    let (p00, p10, p11, p01) = (bd(0, 0), bd(nu, 0), bd(nu, nv), bd(0, nv));
    let mut out = Vec::with_capacity((nu - 1) * (nv - 1));
    for c in 1..nv {
        let v = c as f64 / nv as f64;
        for a in 1..nu {
            let u = a as f64 / nu as f64;
            out.push(
                bd(a, 0) * (1.0 - v) + bd(a, nv) * v + bd(0, c) * (1.0 - u) + bd(nu, c) * u
                    - (p00 * ((1.0 - u) * (1.0 - v))
                        + p10 * (u * (1.0 - v))
                        + p11 * (u * v)
                        + p01 * ((1.0 - u) * v)),
            );
        }
    }
    out
}

/// Triangles from a polyline to one point (counter-clockwise when the point lies to the left).
fn fan(outer: &[RingPoint], c: u32, faces: &mut Vec<u32>, sizes: &mut Vec<u8>) {
    for w in outer.windows(2) {
        faces.extend([w[0].vertex, w[1].vertex, c]);
        sizes.push(3);
    }
}

/// Triangulate the strip between two polylines running the same way (`inner` to the left),
/// each point carrying its relative position along the strip; advance the side whose next
/// interval has the smaller midpoint.
fn zipper(outer: &[RingPoint], inner: &[RingPoint], faces: &mut Vec<u32>, sizes: &mut Vec<u8>) {
    let (mut a, mut b) = (0, 0);
    while a + 1 < outer.len() || b + 1 < inner.len() {
        let take_outer = if a + 1 >= outer.len() {
            false
        } else if b + 1 >= inner.len() {
            true
        } else {
            outer[a].along + outer[a + 1].along <= inner[b].along + inner[b + 1].along
        };
        if take_outer {
            faces.extend([outer[a].vertex, outer[a + 1].vertex, inner[b].vertex]);
            a += 1;
        } else {
            faces.extend([outer[a].vertex, inner[b + 1].vertex, inner[b].vertex]);
            b += 1;
        }
        sizes.push(3);
    }
}

/// Tessellate several patches (in parallel) into one mesh, `resolution` intervals per side
/// segment, welding boundary vertices that are bitwise identical (shared segments and shared
/// node positions). `face_patch` holds each face's index into `patches`. Takes anything that
/// borrows as a [`Patch`] (patches, or values that carry one).
pub fn tessellate_patches<P: Borrow<Patch> + Sync>(
    patches: &[P],
    resolution: usize,
) -> Result<SurfaceMesh, PatchError> {
    if resolution == 0 {
        return Err(PatchError::Resolution(resolution));
    }
    // Counted before anything is allocated: a mesh too large to index is refused up front.
    let total = patches.iter().fold(0usize, |a, p| {
        a.saturating_add(p.borrow().mesh_vertex_count(resolution))
    });
    if total >= u32::MAX as usize {
        return Err(PatchError::MeshTooLarge(total));
    }
    let meshes: Vec<FaceMesh> = patches
        .par_iter()
        .map(|p| p.borrow().face_mesh(resolution))
        .collect();
    debug_assert_eq!(
        meshes.iter().map(|m| m.positions.len()).sum::<usize>(),
        total,
        "the vertex count is the meshes' own"
    );
    Ok(weld_face_meshes(&meshes))
}

impl FaceMesh {
    /// True when every vertex of the mesh is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.positions.iter().all(|p| p.is_finite())
    }

    /// Its number of vertices (before welding).
    pub(crate) fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Its vertex positions (the first `boundary` of them on the face boundary).
    pub(crate) fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The vertex indices of each of its polygons, in order.
    pub(crate) fn polygons(&self) -> impl Iterator<Item = &[u32]> + '_ {
        polygons(&self.faces, &self.sizes)
    }

    /// Where each polygon side that lies on the face's boundary is, as its polygon's index and
    /// the side of the face and the side parameter `s` at the side's middle.
    pub(crate) fn boundary_sides(&self) -> Vec<(usize, usize, f64)> {
        let b = self.boundary;
        if self.ring.len() != b || b < 2 {
            return Vec::new();
        }
        let mut out = Vec::new();
        for (f, poly) in self.polygons().enumerate() {
            for (k, &v) in poly.iter().enumerate() {
                let w = poly[(k + 1) % poly.len()];
                let (v, w) = (v as usize, w as usize);
                if v >= b || w >= b {
                    continue;
                }
                // Consecutive ring vertices, either way round.
                let (first, next) = if (v + 1) % b == w {
                    (v, w)
                } else if (w + 1) % b == v {
                    (w, v)
                } else {
                    continue;
                };
                let (side, s0) = self.ring[first];
                let (next_side, s1) = self.ring[next];
                let s1 = if next_side == side { s1 } else { 1.0 };
                out.push((f, side, 0.5 * (s0 + s1)));
            }
        }
        out
    }
}

/// The polygons of `vertices` (their indices, polygon after polygon) with `sizes` vertices
/// each, as slices.
fn polygons<'a>(vertices: &'a [u32], sizes: &'a [u8]) -> impl Iterator<Item = &'a [u32]> + 'a {
    let mut start = 0;
    sizes.iter().map(move |&k| {
        let f = &vertices[start..start + k as usize];
        start += k as usize;
        f
    })
}

/// The faces' meshes welded into one, in order (face `k` of the result's `face_patch` is the
/// index of its mesh in `meshes`): boundary vertices that are bitwise identical (shared
/// segments and shared node positions) become one vertex.
pub(crate) fn weld_face_meshes<M: Borrow<FaceMesh>>(meshes: &[M]) -> SurfaceMesh {
    weld_face_meshes_with(meshes).0
}

/// How [`weld_face_meshes_with`] welded its meshes: where every vertex of each mesh went, which
/// welded vertex each boundary position became, and how many mesh vertices each welded vertex
/// stands for. A live rebuild keeps it and rewrites only the vertices of the faces it patched
/// again ([`Weld::rewrite`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Weld {
    /// Per mesh (in weld order), the welded vertex of each of its vertices.
    maps: Vec<Vec<u32>>,
    /// The bit pattern of every welded boundary position → its welded vertex.
    boundary: FxHashMap<[u64; 3], u32>,
    /// Per welded vertex, how many mesh vertices it stands for.
    uses: Vec<u32>,
}

/// The bit pattern of a position: the weld's key (exact equality, never a distance).
fn bits(p: [f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// [`weld_face_meshes`], with how it welded them.
pub(crate) fn weld_face_meshes_with<M: Borrow<FaceMesh>>(meshes: &[M]) -> (SurfaceMesh, Weld) {
    let total = meshes.iter().map(|m| m.borrow().positions.len()).sum();
    let mut out = SurfaceMesh::default();
    out.positions.reserve(total);
    let mut weld = Weld {
        maps: Vec::with_capacity(meshes.len()),
        boundary: FxHashMap::default(),
        uses: Vec::with_capacity(total),
    };
    for (pid, m) in meshes.iter().enumerate() {
        let m = m.borrow();
        let mut local = Vec::with_capacity(m.positions.len());
        for (q, p) in m.positions.iter().enumerate() {
            let p = p.to_array();
            let fresh = |out: &mut SurfaceMesh, uses: &mut Vec<u32>| {
                out.positions.push(p);
                uses.push(0);
                (out.positions.len() - 1) as u32
            };
            let idx = if q < m.boundary {
                match weld.boundary.get(&bits(p)) {
                    Some(&idx) => idx,
                    None => {
                        let idx = fresh(&mut out, &mut weld.uses);
                        weld.boundary.insert(bits(p), idx);
                        idx
                    }
                }
            } else {
                fresh(&mut out, &mut weld.uses)
            };
            weld.uses[idx as usize] += 1;
            local.push(idx);
        }
        out.face_vertices
            .extend(m.faces.iter().map(|&v| local[v as usize]));
        out.face_sizes.extend_from_slice(&m.sizes);
        out.face_patch
            .extend(std::iter::repeat_n(pid as u32, m.sizes.len()));
        weld.maps.push(local);
    }
    (out, weld)
}

impl Weld {
    /// Rewrite `positions` (those of the mesh this weld made, vertices in its order) for the
    /// meshes in `changed` — `(index in weld order, its mesh before, its mesh now)` — when
    /// welding every mesh again would give the same welded vertices and polygons: each changed
    /// mesh has the shape it had (vertex, polygon and boundary counts), the vertices that were one
    /// are still bitwise equal (those shared with an unchanged mesh where they were), and no new
    /// boundary position equals another vertex's. Then the positions are exactly those of a new
    /// weld, the weld is updated, and the answer is true; otherwise nothing changes (false).
    pub(crate) fn rewrite(
        &mut self,
        positions: &mut [[f64; 3]],
        changed: &[(usize, &FaceMesh, &FaceMesh)],
    ) -> bool {
        let same_shape = |a: &FaceMesh, b: &FaceMesh| {
            a.positions.len() == b.positions.len()
                && a.boundary == b.boundary
                && a.faces == b.faces
                && a.sizes == b.sizes
        };
        if changed
            .iter()
            .any(|&(k, old, new)| k >= self.maps.len() || !same_shape(old, new))
        {
            return false;
        }
        // The new bit pattern of every welded boundary vertex a changed mesh writes, and how
        // many of its mesh vertices write it.
        let mut written: FxHashMap<u32, ([u64; 3], u32)> = FxHashMap::default();
        for &(k, _, new) in changed {
            for (q, p) in new.positions[..new.boundary].iter().enumerate() {
                let key = bits(p.to_array());
                let entry = written.entry(self.maps[k][q]).or_insert((key, 0));
                if entry.0 != key {
                    return false;
                }
                entry.1 += 1;
            }
        }
        let mut taken: FxHashMap<[u64; 3], u32> =
            FxHashMap::with_capacity_and_hasher(written.len(), Default::default());
        for (&g, &(key, count)) in &written {
            let kept_elsewhere = count < self.uses[g as usize];
            let moved = bits(positions[g as usize]) != key;
            let held = self.boundary.get(&key).is_some_and(|&h| h != g);
            let twice = taken.insert(key, g).is_some_and(|h| h != g);
            if (kept_elsewhere && moved) || held || twice {
                return false;
            }
        }
        for &g in written.keys() {
            let old = bits(positions[g as usize]);
            if self.boundary.get(&old) == Some(&g) {
                self.boundary.remove(&old);
            }
        }
        self.boundary.extend(taken);
        for &(k, _, new) in changed {
            for (&g, p) in self.maps[k].iter().zip(&new.positions) {
                positions[g as usize] = p.to_array();
            }
        }
        true
    }
}

#[cfg(test)]
mod weld_tests {
    use super::*;

    /// A fan of three triangles: corners `a`, `b`, `c` on the boundary, `m` inside.
    fn fan(a: [f64; 3], b: [f64; 3], c: [f64; 3], m: [f64; 3]) -> FaceMesh {
        FaceMesh {
            positions: [a, b, c, m].map(DVec3::from).to_vec(),
            boundary: 3,
            ring: Vec::new(),
            faces: vec![0, 1, 3, 1, 2, 3, 2, 0, 3],
            sizes: vec![3, 3, 3],
        }
    }

    /// Two fans sharing the edge (1,0,0)–(0,1,0); the second's corner and centre as given.
    fn pair(shared: [f64; 3], corner: [f64; 3], centre: [f64; 3]) -> [FaceMesh; 2] {
        let x = [1.0, 0.0, 0.0];
        [
            fan([0.0, 0.0, 0.0], x, shared, [0.3, 0.3, 0.1]),
            fan(x, corner, shared, centre),
        ]
    }

    /// Rewrite the weld of `before` for the meshes `now` (all of them changed); the positions
    /// when accepted.
    fn rewritten(before: &[FaceMesh; 2], now: &[FaceMesh; 2]) -> Option<Vec<[f64; 3]>> {
        let (mesh, mut weld) = weld_face_meshes_with(before);
        let mut positions = mesh.positions.clone();
        let changed: Vec<_> = (0..2).map(|k| (k, &before[k], &now[k])).collect();
        weld.rewrite(&mut positions, &changed).then_some(positions)
    }

    #[test]
    fn a_rewrite_is_a_fresh_weld_or_refused() {
        let y = [0.0, 1.0, 0.0];
        let before = pair(y, [1.0, 1.0, 0.0], [0.7, 0.7, 0.1]);
        assert_eq!(
            weld_face_meshes_with(&before).0.positions.len(),
            6,
            "two vertices shared"
        );
        // The second fan's corner and centre moved: the same as welding afresh.
        let now = pair(y, [1.0, 1.2, 0.0], [0.7, 0.8, 0.2]);
        let fresh = weld_face_meshes(&now);
        assert_eq!(
            rewritten(&before, &now),
            Some(fresh.positions),
            "corner and centre"
        );
        // The shared vertex moved in both fans: still one vertex, as a fresh weld has it.
        let moved = [0.0, 1.1, 0.0];
        let both = [
            fan([0.0; 3], [1.0, 0.0, 0.0], moved, [0.3, 0.3, 0.1]),
            pair(moved, [1.0, 1.0, 0.0], [0.7, 0.7, 0.1])[1].clone(),
        ];
        let fresh = weld_face_meshes(&both);
        assert_eq!(fresh.positions.len(), 6, "still shared");
        assert_eq!(
            rewritten(&before, &both),
            Some(fresh.positions),
            "shared vertex moved"
        );
        // Moved in one fan only: the fans no longer share it; refused.
        let one = [
            before[0].clone(),
            pair(moved, [1.0, 1.0, 0.0], [0.7, 0.7, 0.1])[1].clone(),
        ];
        assert_eq!(rewritten(&before, &one), None, "split");
        // A corner moved onto the first fan's own corner: a fresh weld would join them.
        let onto = pair(y, [0.0, 0.0, 0.0], [0.7, 0.7, 0.1]);
        assert_eq!(weld_face_meshes(&onto).positions.len(), 5, "joined afresh");
        assert_eq!(rewritten(&before, &onto), None, "joined");
        // Another shape: refused.
        let mut other = now.clone();
        other[1].sizes = vec![3, 3];
        other[1].faces.truncate(6);
        assert_eq!(rewritten(&before, &other), None, "another shape");
    }
}
