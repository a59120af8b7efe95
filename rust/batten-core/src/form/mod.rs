//! Form topology and curve-network transformations (Bole, *Interactive hull form
//! transformations using curve network deformation*, seed 002, §6–§7).
//!
//! [`form_topology`] finds the curves that carry the form (roles, and the curves those end
//! on), their vertices, edges (free-form, straight, blend), faces and planes, and measures the
//! parameters of §7.2.5. [`transform`] moves form vertices and passes the moves through the
//! network in the paper's order (§7.2); [`parametric_moves`] turns target values (breadth,
//! depth, PMB length and position, bilge radius, entrance and run) into vertex moves.

mod error;
mod identify;
mod measure;
mod parameters;
mod parametric;
mod planes;
mod transform;

pub use error::FormError;
pub use identify::{
    EdgeKind, FormEdge, FormFace, FormOptions, FormTopology, FormVertex, BLEND_TANGENT_DEGREES,
};
pub use parameters::{Bilge, FormParameters, ParallelMiddleBody};
pub use parametric::{parametric_moves, transform_to, Plan, Target};
pub(crate) use planes::curve_planes;
pub use planes::{FormPlane, PlaneKind};
pub use transform::{transform, transform_bulged, FaceBulge, Transformed, VertexMove};

/// The form topology of `network` (Bole, seed 002, §6: form curves, vertices, edges, faces,
/// planes) with its parameters measured (§7.2.5).
///
/// Errors only when a curve cannot be evaluated (naming it).
pub fn form_topology(
    network: &crate::network::Network,
    options: &FormOptions,
) -> Result<FormTopology, FormError> {
    let mut form = identify::identify(network, options)?;
    form.parameters = measure::measure(network, &form, options)?;
    Ok(form)
}
