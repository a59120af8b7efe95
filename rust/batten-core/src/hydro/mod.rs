//! Hydrostatics on batten's own surface (the H-rep paper's "secondary functions": hydrostatics
//! and the sectional area curve): volume, displacement, centres, waterplane, coefficients,
//! metacentres, TPC, MTC, sectional areas and curves of form, at any draft, trim and heel, and
//! the inverse — the flotation at a displacement and centre of gravity.
//!
//! Every figure is a surface integral over the wet part of the hull ([`WetIntegrals`]: the
//! divergence theorem closes the region by the waterplane, and a half hull's centreplane adds
//! nothing), or a plane section ([`HullGeometry::plane_section`]). The patch surface integrates
//! its patches themselves ([`PatchHydroModel`]); any triangle mesh can be given too, so the
//! numbers can be set beside other tools' on identical input.

mod bernstein;
mod caps;
mod cells;
mod clip;
mod contour;
mod error;
mod float;
mod geometry;
mod hydrostatics;
mod integrals;
mod mesh;
mod patch_model;
mod roots;
mod waterplane;

pub use caps::CAP_FLATNESS_RELATIVE;
pub use cells::CellDensity;
pub use error::HydroError;
pub use float::{float_to, level_draft};
pub use geometry::{
    is_port_half, HullGeometry, OpenChain, SectionArc, SectionSegment, HALF_HULL_SLACK,
};
pub use hydrostatics::{
    default_datums, hydrostatics, immersed_section_area, sectional_areas, Hydrostatics,
    ENTRANCE_FIT_FRACTION, SECTION_TOLERANCE_RELATIVE,
};
pub use integrals::WetIntegrals;
pub use mesh::{TriangleHull, CENTREPLANE_TOLERANCE_RELATIVE};
pub use patch_model::{PatchHydroModel, CENTREPLANE_RELATIVE};
pub use waterplane::{Datums, Flotation, Waterplane, SEA_WATER_DENSITY};

// For the exact plane sections (`crate::sections`): the cells' domain quadrilaterals and
// interpolants, and marching squares on a cell's polynomial.
pub(crate) use bernstein::N as NET_SIZE;
pub(crate) use cells::{boxes, interpolate, quads, Quad};
pub(crate) use contour::{grid_pieces, GRID};
