//! Any triangle mesh as a hull for hydrostatics ([`TriangleHull`]): each triangle clipped exactly
//! by the waterplane and integrated exactly, so a mesh's figures are those of the polyhedron it
//! is, and can be set beside other tools' on identical input.

/// Free-edge chains and the half-hull test, shared with the patch model's mesh.
pub(in crate::hydro) mod boundary;
mod clip;
mod runs;

use glam::DVec3;
use rayon::prelude::*;

use super::error::HydroError;
use super::geometry::{HullGeometry, OpenChain, SectionSegment};
use super::integrals::WetIntegrals;
use super::waterplane::Waterplane;
use clip::{add_wet_triangle, coplanar_flux, section_segment, widen_wet_range};
use runs::{Runs, RUN};

/// How far from `y = 0` (relative to the mesh's size, the diagonal of its box) a vertex may be
/// and still lie on the centreplane: a mesh stored in single precision (Blender's) rounds to
/// about 1.2e-7 of its size.
pub const CENTREPLANE_TOLERANCE_RELATIVE: f64 = 2e-7;

/// Triangles per parallel task: large enough that the split costs nothing beside the work.
const TRIANGLES_PER_TASK: usize = 8192;

/// A run of triangles (see [`Runs`]) and whether it is taken mirrored.
type RunKey = (usize, bool);

/// A triangle mesh as a hull: positions in the ship's axes (m) and triangles of vertex indices,
/// wound counter-clockwise about the outward normal.
///
/// Orientation: the signed volume of the closed mesh (its mirror image included for a half
/// hull; an open top or centreplane adds nothing, measured as the flux of `y e2`) decides.
/// When it is negative the triangles are taken as wound inward and every one is reversed, so a
/// mesh of either winding gives the same figures.
///
/// A half hull (no vertex to starboard and free edges along `y = 0`, see
/// [`CENTREPLANE_TOLERANCE_RELATIVE`]) answers for the whole ship: upright, its mirror image
/// doubles the integrals; heeled, the image is integrated explicitly.
#[derive(Clone, Debug)]
pub struct TriangleHull {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    half: bool,
    reversed: bool,
    bounds: (DVec3, DVec3),
    open: Vec<OpenChain>,
    runs: Runs,
}

impl TriangleHull {
    /// A hull from `positions` (m) and `triangles` (indices into `positions`).
    ///
    /// Errors ([`HydroError::InvalidInput`]): no triangles, a coordinate that is not finite
    /// (naming the vertex), an index out of range (naming the triangle and the index).
    pub fn try_new(
        positions: &[DVec3],
        triangles: &[[u32; 3]],
    ) -> Result<TriangleHull, HydroError> {
        if triangles.is_empty() {
            return Err(HydroError::InvalidInput(
                "the mesh has no triangles: a hull needs at least one".into(),
            ));
        }
        if u32::try_from(triangles.len()).is_err() {
            return Err(HydroError::InvalidInput(format!(
                "the mesh has {} triangles, more than the 2³² a mesh may have",
                triangles.len()
            )));
        }
        if let Some((k, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(HydroError::InvalidInput(format!(
                "mesh vertex {k} at ({}, {}, {}) is not a finite point",
                p.x, p.y, p.z
            )));
        }
        let n = positions.len();
        if let Some((k, t)) = triangles
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&i| i as usize >= n))
        {
            let bad = t
                .iter()
                .find(|&&i| i as usize >= n)
                .copied()
                .unwrap_or(t[0]);
            return Err(HydroError::InvalidInput(format!(
                "mesh triangle {k} refers to vertex {bad}, but the mesh has {n} vertices"
            )));
        }
        let (mut lo, mut hi) = positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(a, b), p| (a.min(*p), b.max(*p)),
        );
        let size = (hi - lo).length();
        let tol = CENTREPLANE_TOLERANCE_RELATIVE * size;
        let found = boundary::boundary(positions, triangles, tol);
        if found.half {
            lo.y = lo.y.min(-hi.y);
            hi.y = hi.y.max(-lo.y);
        }
        let mut triangles = triangles.to_vec();
        let reversed = signed_volume_flux(positions, &triangles) < 0.0;
        if reversed {
            triangles.par_iter_mut().for_each(|t| t.swap(1, 2));
        }
        let runs = Runs::new(positions, &triangles);
        Ok(TriangleHull {
            positions: positions.to_vec(),
            triangles,
            half: found.half,
            reversed,
            bounds: (lo, hi),
            open: found.open,
            runs,
        })
    }

    /// Whether the triangles were wound inward and have been reversed.
    pub fn was_reversed(&self) -> bool {
        self.reversed
    }

    /// The number of triangles (of the half given, for a half hull).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The corners of triangle `t` in the ship's axes, wound outward; of its mirror image
    /// (`y → −y`, the winding reversed so the normal stays outward) when `mirror`.
    #[inline]
    fn corners(&self, t: &[u32; 3], mirror: bool) -> [DVec3; 3] {
        let p = |i: u32| self.positions[i as usize];
        if mirror {
            let m = |i: u32| {
                let v = p(i);
                DVec3::new(v.x, -v.y, v.z)
            };
            [m(t[0]), m(t[2]), m(t[1])]
        } else {
            [p(t[0]), p(t[1]), p(t[2])]
        }
    }

    /// The halves to go over: the mesh, and its mirror image for a half hull unless `symmetric`
    /// (the quantity asked for is the same on both).
    fn halves(&self, symmetric: bool) -> &'static [bool] {
        if self.half && !symmetric {
            &[false, true]
        } else {
            &[false]
        }
    }

    /// The triangles of run `k`.
    #[inline]
    fn run(&self, k: usize) -> &[[u32; 3]] {
        &self.triangles[k * RUN..((k + 1) * RUN).min(self.triangles.len())]
    }

    /// The runs (of the halves to go over, see [`halves`](Self::halves)) whose box reaches
    /// `m·p = c` (`at_or_below`: reaches down to it or below; else: straddles it); a station
    /// (`m = ±x`) looks only at the runs of its slab.
    fn runs_reaching(&self, m: DVec3, c: f64, symmetric: bool, at_or_below: bool) -> Vec<RunKey> {
        let station = m.y == 0.0 && m.z == 0.0 && m.x != 0.0;
        let all: Vec<u32>;
        let candidates: &[u32] = if station {
            self.runs.at_station(c / m.x)
        } else {
            all = (0..self.runs.len() as u32).collect();
            &all
        };
        self.halves(symmetric)
            .iter()
            .flat_map(|&mirror| {
                candidates.iter().filter_map(move |&k| {
                    let (lo, hi) = self.runs.span(k as usize, m, mirror);
                    (lo <= c && (at_or_below || hi >= c)).then_some((k as usize, mirror))
                })
            })
            .collect()
    }

    /// The wet integrals of one half (the mesh, or its mirror image): the runs wholly above the
    /// water are skipped.
    fn wet_half(&self, plane: &Waterplane, mirror: bool) -> WetIntegrals {
        let level = plane.e3.dot(plane.origin);
        (0..self.runs.len())
            .into_par_iter()
            .filter(|&k| self.runs.span(k, plane.e3, mirror).0 <= level)
            .map(|k| {
                let mut w = WetIntegrals::default();
                for t in self.run(k) {
                    add_wet_triangle(&mut w, plane, self.corners(t, mirror));
                }
                w
            })
            .reduce(WetIntegrals::default, |a, b| a + b)
    }

    /// The range of `dir·p` over the wet part of run `key`.
    fn run_wet_range(&self, plane: &Waterplane, dir: DVec3, key: RunKey) -> (f64, f64) {
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        for t in self.run(key.0) {
            widen_wet_range(&mut r, plane, dir, self.corners(t, key.1));
        }
        r
    }
}

/// The signed volume of the closed mesh as the flux of `F = y e2` (`div F = 1`), exact on each
/// flat triangle (its integrand is linear): `Σ Ay · ȳ`. An opening in a plane `y = 0`, `z =
/// const` or `x = const` (the centreplane of a half hull, a deck or transom left open) has no
/// flux, so the sign says the winding of an open hull too.
fn signed_volume_flux(positions: &[DVec3], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .par_chunks(TRIANGLES_PER_TASK)
        .map(|chunk| {
            chunk
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| positions[i as usize]);
                    let area_y = 0.5 * (b - a).cross(c - a).y;
                    area_y * (a.y + b.y + c.y) / 3.0
                })
                .sum::<f64>()
        })
        .sum()
}

impl HullGeometry for TriangleHull {
    fn wet_integrals(&self, plane: &Waterplane) -> WetIntegrals {
        let w = self.wet_half(plane, false);
        if !self.half {
            w
        } else if plane.is_upright() {
            w.with_mirror_upright()
        } else {
            w + self.wet_half(plane, true)
        }
    }

    /// Exact for a mesh (`tolerance` is not needed): one segment per triangle the plane cuts,
    /// read from the runs whose box the plane crosses. A plane lying in faces of the mesh (a
    /// flat transom or end, a flat bottom) is taken from the solid's side of them, so a box's
    /// station at its very end has the end's area.
    fn plane_section(&self, m: DVec3, c: f64, _tolerance: f64) -> Vec<SectionSegment> {
        let keys = self.runs_reaching(m, c, false, false);
        // The segments with on-plane corners counted above, and the flux of the faces lying in
        // the plane (of the half given).
        let (segments, flux) = keys
            .par_iter()
            .fold(
                || (Vec::new(), 0.0),
                |(mut out, mut flux), &(k, mirror)| {
                    for t in self.run(k) {
                        let p = self.corners(t, mirror);
                        out.extend(section_segment(m, c, p, true));
                        if !mirror {
                            flux += coplanar_flux(m, c, p);
                        }
                    }
                    (out, flux)
                },
            )
            .reduce(
                || (Vec::new(), 0.0),
                |(mut a, fa), (b, fb)| {
                    a.extend(b);
                    (a, fa + fb)
                },
            );
        if flux >= 0.0 {
            return segments;
        }
        // Faces in the plane with the solid ahead (along m): move the plane into the solid
        // (rare: only a plane exactly in faces, such as a box's aft end).
        keys.par_iter()
            .flat_map_iter(|&(k, mirror)| {
                self.run(k)
                    .iter()
                    .filter_map(move |t| section_segment(m, c, self.corners(t, mirror), false))
            })
            .collect()
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

    /// Exact, by bounds: the runs that reach below the water are ordered by how far their box
    /// reaches along `dir`, and read only while their box could still widen the range.
    fn wet_range(
        &self,
        plane: &Waterplane,
        dir: DVec3,
        _waterline: &[SectionSegment],
    ) -> Option<(f64, f64)> {
        // Upright, the mirror image has the same wet part mirrored: the same range along a
        // direction without a transverse part.
        let symmetric = plane.is_upright() && dir.y == 0.0;
        let level = plane.e3.dot(plane.origin);
        let mut keys: Vec<(RunKey, (f64, f64))> = self
            .runs_reaching(plane.e3, level, symmetric, true)
            .into_iter()
            .map(|key| (key, self.runs.span(key.0, dir, key.1)))
            .collect();
        let mut range = (f64::INFINITY, f64::NEG_INFINITY);
        let widen = |range: &mut (f64, f64), r: (f64, f64)| {
            range.0 = range.0.min(r.0);
            range.1 = range.1.max(r.1);
        };
        keys.sort_by(|a, b| b.1 .1.total_cmp(&a.1 .1));
        for &(key, (_, hi)) in &keys {
            if hi < range.1 {
                break;
            }
            widen(&mut range, self.run_wet_range(plane, dir, key));
        }
        keys.sort_by(|a, b| a.1 .0.total_cmp(&b.1 .0));
        for &(key, (lo, _)) in &keys {
            if lo > range.0 {
                break;
            }
            widen(&mut range, self.run_wet_range(plane, dir, key));
        }
        (range.0 <= range.1).then_some(range)
    }
}
