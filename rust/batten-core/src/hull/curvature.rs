//! The curvature of the hull surface at the vertices of its mesh, from the patches themselves
//! ([`Patch::curvature`]): what a curvature colour map shows (Gaussian curvature for the shape
//! of the shell plating, mean curvature for bumps and hollows).

use rayon::prelude::*;

use super::HullSurface;
use crate::error::Error;
use crate::patch::SurfaceCurvature;

/// One patch vertex's welded vertex and the patch's curvature there.
type AtVertex = (u32, Option<SurfaceCurvature>);

/// Gaussian and mean curvature at every vertex of a hull's mesh
/// ([`HullSurface::vertex_curvature`]), in vertex order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VertexCurvature {
    /// Gaussian curvature `K` (1/m²); 0 where `defined` is false.
    pub gaussian: Vec<f64>,
    /// Mean curvature `H` (1/m), positive where the hull bulges outwards (convex seen from
    /// outside, as at the bilge), negative where it is hollow; 0 where `defined` is false.
    pub mean: Vec<f64>,
    /// False where no patch through the vertex is regular there.
    pub defined: Vec<bool>,
}

impl HullSurface {
    /// Gaussian and mean curvature at every vertex of [`HullSurface::mesh`], which must have
    /// been made at `resolution` (the [`HullOptions::resolution`](super::HullOptions) of the
    /// build). Each vertex takes the curvature of the patch whose mesh made it
    /// ([`Patch::curvature`](crate::Patch::curvature) at the vertex's domain point); a vertex on
    /// an edge or at a node, shared by several patches, takes their mean — so across an edge
    /// where the surface is only G1 the colours step, as they should.
    ///
    /// Errors: [`Error::InvalidInput`] when the mesh was not made at `resolution` (its polygons
    /// do not match the patches' meshes).
    pub fn vertex_curvature(&self, resolution: usize) -> Result<VertexCurvature, Error> {
        let nv = self.mesh.positions.len();
        // Each polygon's start in `face_vertices`, and the polygons of each face, in order.
        let mut starts = Vec::with_capacity(self.mesh.face_sizes.len());
        let mut at = 0usize;
        for &k in &self.mesh.face_sizes {
            starts.push(at);
            at += k as usize;
        }
        let faces = self.patch_faces.iter().copied().max().map_or(0, |m| m + 1);
        let mut polygons_of: Vec<Vec<usize>> = vec![Vec::new(); faces];
        for (q, &f) in self.mesh.face_patch.iter().enumerate() {
            if let Some(list) = polygons_of.get_mut(f as usize) {
                list.push(q);
            }
        }
        let mismatch = || {
            Error::InvalidInput(format!(
                "the hull's mesh was not made at resolution {resolution}: build it at that \
                 resolution, or ask for the curvature at the resolution it was built at"
            ))
        };
        // Per patch: (welded vertex, curvature) for each of its mesh's vertices.
        let per_patch: Vec<Option<Vec<AtVertex>>> = self
            .patches
            .par_iter()
            .zip(&self.patch_faces)
            .enumerate()
            .map(|(k, (patch, &face))| {
                // The mesh's own intervals where it was made at `resolution` (finer where the
                // surface turns tightly), else that resolution's.
                let counts = match self.mesh_counts.get(k) {
                    Some(c) if self.mesh_resolution == resolution => c.clone(),
                    _ => vec![resolution; patch.segment_count()],
                };
                let mesh = patch.face_mesh_with(&counts);
                let domain = patch.mesh_domain_with(&counts);
                let polygons = &polygons_of[face];
                if domain.len() != mesh.vertex_count() || polygons.len() != mesh.polygons().count()
                {
                    return None;
                }
                // The welded vertex of each of the patch's own vertices: the vertex of its
                // polygon with the same position, bit for bit (the weld copies positions; a
                // flipped mesh has its polygons' corners in the other order).
                let mut welded = vec![u32::MAX; mesh.vertex_count()];
                for (local, &q) in mesh.polygons().zip(polygons) {
                    let k = self.mesh.face_sizes[q] as usize;
                    let corners = &self.mesh.face_vertices[starts[q]..starts[q] + k];
                    if local.len() != k {
                        return None;
                    }
                    for &lv in local {
                        let p = mesh.positions()[lv as usize].to_array();
                        let w = corners
                            .iter()
                            .find(|&&w| self.mesh.positions[w as usize] == p)?;
                        welded[lv as usize] = *w;
                    }
                }
                Some(
                    welded
                        .iter()
                        .zip(&domain)
                        .filter(|(w, _)| **w != u32::MAX)
                        .map(|(&w, x)| (w, patch.curvature(x.to_array())))
                        .collect(),
                )
            })
            .collect();
        let sign = if self.patches_outward { 1.0 } else { -1.0 };
        let (mut gaussian, mut mean) = (vec![0.0; nv], vec![0.0; nv]);
        let mut count = vec![0u32; nv];
        for list in per_patch {
            for (w, c) in list.ok_or_else(mismatch)? {
                if let Some(c) = c {
                    let w = w as usize;
                    gaussian[w] += c.gaussian;
                    mean[w] += sign * c.mean;
                    count[w] += 1;
                }
            }
        }
        for ((g, h), &c) in gaussian.iter_mut().zip(&mut mean).zip(&count) {
            if c > 0 {
                *g /= f64::from(c);
                *h /= f64::from(c);
            }
        }
        Ok(VertexCurvature {
            gaussian,
            mean,
            defined: count.iter().map(|&c| c > 0).collect(),
        })
    }
}
