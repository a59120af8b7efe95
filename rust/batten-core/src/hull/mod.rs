//! The H-rep pipeline of the paper end to end: curve network → topology (§3.1, §5.2) → one
//! surface patch per face (§3.2.1) with tangent ribbons from the crossing curves (§3.2.2, eq. 8
//! and the 15° rule) and knuckles (G0 creases) where the designer drew them → one welded mesh,
//! with a report of what was built and how well it fits the curves.
//!
//! - [`edges`]: the region-bounding edges as side segments, and the edges at every node.
//! - [`ribbons`]: one shared [`EdgeNormal`](crate::EdgeNormal) per smooth edge (G1 across it),
//!   one per face on knuckle edges (G0).
//! - [`knuckles`]: which edges are knuckles (role, or corner points of crossing curves), and
//!   the report's [`KnuckleEdge`]s.
//! - [`patched`]: a face built as a patch, with where its edges went.
//! - [`build`]: the face boundaries, the patches, the tessellation and its orientation.
//! - [`report`]: gaps, normal jumps, crease angles, volume, nodes and warnings.
//! - [`holes`]: free edges off the hull's boundary (profile, deck, transom), as warnings.
//! - [`folds`]: neighbouring mesh faces at a steep angle off the knuckles, and patches
//!   standing out of their boundary's box, as warnings.
//! - [`warning`]: warnings as data (kind, message, curves, place, underlying error).
//! - [`live`]: [`LiveHull`], the hull kept with its stages and rebuilt incrementally.
//!
//! The modules depend on each other one way: `live` → `build`, `build` → `report` → `knuckles` → `edges`,
//! `report` → `holes`, `report` → `folds` → `knuckles`,
//! `build` → `ribbons` → `edges`, and `warning`, `patched` at the bottom.

mod build;
mod curvature;
mod edges;
mod flats;
mod fold_probe;
mod folds;
mod holes;
mod knuckles;
mod live;
mod patched;
mod report;
mod ribbons;
mod warning;

use crate::defaults::{DEFAULT_RESOLUTION, MAX_RESOLUTION};
use crate::error::Error;
use crate::hydro::{CellDensity, PatchHydroModel};
use crate::network::Network;
use crate::patch::{Patch, SurfaceMesh};
use crate::tolerance::Tolerance;

pub use curvature::VertexCurvature;
pub use folds::{BOX_SLACK, FOLD_ANGLE_DEGREES};
// The CAD export fits each shared edge once from the patches' layouts.
pub(crate) use edges::{edge_curve, KnotPoints};
pub use knuckles::{KnuckleEdge, KnuckleSource, KNUCKLE_EDGE_SAMPLES, KNUCKLE_POINT_ANGLE_DEGREES};
pub use live::{LiveHull, Rebuild};
pub(crate) use patched::{LayoutSegment, PatchLayout};
pub use report::HullReport;
pub use warning::{FaceError, Warning, WarningKind};

/// Options of [`build_hull`] (H-rep paper §3: the model tolerance of the topology and the
/// patches, and the density of the display mesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullOptions {
    /// The model tolerance: nodes closer than it are one node (§3.1), gaps between a face's
    /// sides up to 10× it are closed by the patches (§3.2.1).
    pub tolerance: Tolerance,
    /// Tessellation intervals per side segment (per topological edge) of every patch;
    /// 1 to [`MAX_RESOLUTION`].
    pub resolution: usize,
}

impl HullOptions {
    /// Validated options: the tolerance a positive finite number of metres, the resolution
    /// 1 to [`MAX_RESOLUTION`] ([`Error::Tolerance`], [`Error::Resolution`] otherwise).
    pub fn try_new(tolerance: f64, resolution: usize) -> Result<HullOptions, Error> {
        let options = HullOptions {
            tolerance: Tolerance::try_new(tolerance)?,
            resolution,
        };
        options.check()?;
        Ok(options)
    }

    /// Check the fields set directly: the resolution must be 1 to [`MAX_RESOLUTION`].
    pub fn check(&self) -> Result<(), Error> {
        if (1..=MAX_RESOLUTION).contains(&self.resolution) {
            Ok(())
        } else {
            Err(Error::Resolution {
                resolution: self.resolution,
                max: MAX_RESOLUTION,
            })
        }
    }
}

impl Default for HullOptions {
    /// The default tolerance (0.1 mm) and [`DEFAULT_RESOLUTION`] (8) intervals per edge.
    fn default() -> Self {
        HullOptions {
            tolerance: Tolerance::DEFAULT,
            resolution: DEFAULT_RESOLUTION,
        }
    }
}

/// The hull surface: the welded mesh of all patches and its report (H-rep paper §3).
///
/// Two surfaces compare equal when their meshes and reports do (the patches are what made
/// them).
#[derive(Clone, Debug)]
pub struct HullSurface {
    /// One welded mesh; `face_patch` holds, for every polygon, the index of its face in the
    /// topology (`Topology::faces`, §3.1; a skipped face has no polygons). Consistently
    /// oriented, normals pointing away from the centreplane for a port half.
    pub mesh: SurfaceMesh,
    /// What was built and how well.
    pub report: HullReport,
    /// The patches themselves, one per face that was patched, in topology face order
    /// (`patch_faces[k]` is the face of `patches[k]`): the exact surface the mesh samples, for
    /// hydrostatics and sections.
    pub patches: Vec<Patch>,
    /// The topology face of each patch.
    pub patch_faces: Vec<usize>,
    /// Where the topology's edges went among each patch's sides and segments (in patch
    /// order): which edges two patches share, for the CAD export.
    pub(crate) layouts: Vec<PatchLayout>,
    /// Whether `∂P/∂u × ∂P/∂v` of the patches points out of the hull (false when the mesh was
    /// flipped to face away from the centreplane).
    pub patches_outward: bool,
    /// The intervals of each patch's mesh on its side segments (in patch order): the
    /// resolution, or a multiple of it where the surface turns too tightly for it.
    pub(crate) mesh_counts: Vec<Vec<usize>>,
    /// The resolution the mesh was made at.
    pub(crate) mesh_resolution: usize,
}

impl HullSurface {
    /// The surface's patches as cells for hydrostatics and sections (see
    /// [`PatchHydroModel`]), cut at `density` ([`CellDensity::DEFAULT`] for the figures,
    /// [`CellDensity::LIVE`] while dragging).
    pub fn hydro_model(&self, density: CellDensity) -> PatchHydroModel {
        PatchHydroModel::updated_or_new(
            None,
            &self.patches,
            &self.patch_faces,
            self.patches_outward,
            &self.mesh,
            density,
        )
    }

    /// The model of this surface, a live rebuild of the surface `previous` was made of in which
    /// only the faces `changed` names were patched again: `previous`'s cells of the other faces
    /// are kept, and the result is [`HullSurface::hydro_model`] at `previous`'s density, bit
    /// for bit ([`PatchHydroModel::updated`]).
    pub fn hydro_model_after(
        &self,
        previous: &PatchHydroModel,
        changed: &(dyn Fn(usize) -> bool + Sync),
    ) -> PatchHydroModel {
        PatchHydroModel::updated(
            previous,
            &self.patches,
            &self.patch_faces,
            changed,
            self.patches_outward,
            &self.mesh,
        )
    }
}

impl PartialEq for HullSurface {
    fn eq(&self, other: &HullSurface) -> bool {
        self.mesh == other.mesh && self.report == other.report
    }
}

/// Build the hull surface of a curve network (the H-rep paper's pipeline, §3 and §5.2).
///
/// 1. [`Topology::build`](crate::Topology::build): nodes, edges, faces with their true corners.
/// 2. Knuckle edges: curves with role `Knuckle`, and edges whose end node is a
///    corner point (tangent jump above [`KNUCKLE_POINT_ANGLE_DEGREES`]) of a crossing curve —
///    the paper's chines "connecting the knuckles in each cross section" (§5).
/// 3. Ribbons (§3.2.2): every smooth edge gets ONE surface normal field from the tangents of
///    all curves crossing it at its end nodes (eq. 8, crossings within 15° of the edge
///    ignored), given to both its faces, which makes them GC¹ along the whole edge; a knuckle
///    edge gives each face its own field from the crossing tangents on that face's side (the
///    loop neighbours of the edge in that face), so the surface is G0 there.
/// 4. Patches (§3.2.1): each face with 3..=[`MAX_SIDES`](crate::MAX_SIDES) sides becomes a
///    Gregory (4 sides) or Charrot–Gregory patch; sides are the topology's sides, composite
///    where a T-joint splits them; every segment carries the exact node positions, so faces
///    weld bitwise. A face that fails is skipped, named in the warnings (with its
///    [`FaceError`]) and counted.
/// 5. Tessellation (in parallel), a finiteness check (a patch producing a non-finite point is
///    dropped), and orientation: the topology's faces are counter-clockwise about normals
///    propagated over the network, so the shell is consistent; if the mesh's area-weighted
///    mean normal has a negative `y` component the whole mesh is flipped, so a port half
///    (`y ≥ 0`) has outward normals.
///
/// Errors: the topology's own errors (curve kernel), a network without faces or with no face
/// that could be patched ([`Error::NoSurface`], naming the diagnostics), a resolution outside
/// 1..=[`MAX_RESOLUTION`] ([`Error::Resolution`]), a mesh too large to index
/// ([`Error::Mesh`]).
pub fn build_hull(network: &Network, options: &HullOptions) -> Result<HullSurface, Error> {
    build::build(network, options)
}
