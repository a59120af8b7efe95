//! Parametric transformations (Bole, seed 002, §7.2.5): a target value of a measured parameter
//! turned into translations of form vertices, then [`transform`]ed.
//!
//! - Breadth, with a PMB: every vertex of the midship sections off the centreplane moves out
//!   by half the change; the flat-of-side and flat-of-bottom vertices also along the bottom
//!   line, so that with rise of floor the bilge keeps its radius (its centre moves along the
//!   bottom line). Without a PMB there are no flat-of-side vertices to move, and the breadth is
//!   changed by scaling every control point transversely (reported as such).
//! - Depth: every vertex on the deck moves up by the change (along a straight stem or transom
//!   ending there, which so keeps its rake).
//! - PMB length: the forward and aft midship sections move apart by half the change each; PMB
//!   position: both move by the change.
//! - Bilge radius: on every midship section the flat-of-bottom and flat-of-side vertices move
//!   along the bottom and side lines so that an arc tangent to both has the new radius.
//! - Entrance (run) length: the forward (aft) midship section moves, the ends stay.

use glam::DVec3;

use super::error::FormError;
use super::identify::FormTopology;
use super::parameters::Bilge;
use super::transform::{transform, Transformed, VertexMove};
use crate::network::{Network, NetworkCurve, Role};
use crate::tolerance::Tolerance;

/// A change of one measured parameter to a target value (metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Largest breadth.
    Breadth(f64),
    /// Depth.
    Depth(f64),
    /// Length of the parallel middle body.
    PmbLength(f64),
    /// x of the centre of the parallel middle body.
    PmbPosition(f64),
    /// Bilge radius of the midship sections.
    BilgeRadius(f64),
    /// Entrance length.
    EntranceLength(f64),
    /// Run length.
    RunLength(f64),
}

impl Target {
    /// The parameter's name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            Target::Breadth(_) => "breadth",
            Target::Depth(_) => "depth",
            Target::PmbLength(_) => "pmb_length",
            Target::PmbPosition(_) => "pmb_position",
            Target::BilgeRadius(_) => "bilge_radius",
            Target::EntranceLength(_) => "entrance_length",
            Target::RunLength(_) => "run_length",
        }
    }

    /// The target value.
    pub fn value(self) -> f64 {
        match self {
            Target::Breadth(v)
            | Target::Depth(v)
            | Target::PmbLength(v)
            | Target::PmbPosition(v)
            | Target::BilgeRadius(v)
            | Target::EntranceLength(v)
            | Target::RunLength(v) => v,
        }
    }
}

/// How a target is reached.
#[derive(Clone, Debug, PartialEq)]
pub enum Plan {
    /// By these vertex moves through the form topology.
    Moves(Vec<VertexMove>),
    /// By scaling every control point's y by this factor (breadth without a PMB).
    TransverseScale(f64),
}

/// The plan that takes `form` (of `network`) to `target` (module docs).
///
/// Errors: a target that is not finite (or not positive where a length must be), a parameter
/// that needs a PMB on a hull without one, a bilge radius on sections without an arc, a PMB
/// or bilge that would not fit.
pub fn parametric_moves(
    network: &Network,
    form: &FormTopology,
    target: Target,
) -> Result<Plan, FormError> {
    let value = target.value();
    let parameter = target.name();
    let bad = |reason: &str| FormError::BadTarget {
        parameter,
        value,
        reason: reason.to_owned(),
    };
    if !value.is_finite() {
        return Err(bad("not a finite number"));
    }
    if value <= 0.0 && !matches!(target, Target::PmbPosition(_)) {
        return Err(bad("must be a positive length"));
    }
    let p = &form.parameters;
    let pmb = || {
        p.pmb
            .clone()
            .ok_or_else(|| FormError::NoParallelMiddleBody {
                parameter,
                reason: p.no_pmb_reason.clone().unwrap_or_default(),
            })
    };
    let curves = network.curves();
    let on_curve =
        |c: usize| (0..form.vertices.len()).filter(move |&v| form.vertices[v].curves.contains(&c));
    let section_moves = |c: usize, t: DVec3| {
        on_curve(c).map(move |v| VertexMove {
            vertex: v,
            translation: t,
        })
    };
    let moves = match target {
        Target::Breadth(b) => {
            if p.pmb.is_none() {
                return Ok(Plan::TransverseScale(b / p.breadth));
            }
            let d = 0.5 * (b - p.breadth);
            let pmb = pmb()?;
            let mut out = Vec::new();
            for s in [pmb.aft_section, pmb.fwd_section] {
                let bilge = p.bilges.iter().find(|g| g.section == s);
                for v in on_curve(s) {
                    let pos = form.vertices[v].position;
                    if pos.y.abs() <= CENTRE_FRACTION * p.breadth {
                        continue;
                    }
                    let t = match bilge {
                        Some(g) if v == g.fob_vertex || v == g.fos_vertex => {
                            outward_along_bottom(g, d)
                        }
                        Some(g) if below_bilge(g, pos) => outward_along_bottom(g, d),
                        _ => DVec3::new(0.0, d, 0.0),
                    };
                    out.push(VertexMove {
                        vertex: v,
                        translation: t,
                    });
                }
            }
            out
        }
        Target::Depth(dv) => {
            let dz = dv - p.depth;
            let decks: Vec<usize> = (0..curves.len())
                .filter(|&c| curves[c].role == Role::Deck)
                .collect();
            if decks.is_empty() {
                return Err(FormError::NotMeasurable {
                    parameter,
                    reason: "no curve has the role 'deck'".into(),
                });
            }
            let mut vs: Vec<usize> = decks.iter().flat_map(|&c| on_curve(c)).collect();
            vs.sort_unstable();
            vs.dedup();
            vs.into_iter()
                .map(|v| VertexMove {
                    vertex: v,
                    translation: up_along_straight(network, form, v, dz),
                })
                .collect()
        }
        Target::PmbLength(l) => {
            let pmb = pmb()?;
            let h = 0.5 * (l - pmb.length);
            check_fits(p, pmb.aft - h, pmb.fwd + h).map_err(|r| bad(&r))?;
            section_moves(pmb.aft_section, DVec3::new(-h, 0.0, 0.0))
                .chain(section_moves(pmb.fwd_section, DVec3::new(h, 0.0, 0.0)))
                .collect()
        }
        Target::PmbPosition(x) => {
            let pmb = pmb()?;
            let dx = x - pmb.position;
            check_fits(p, pmb.aft + dx, pmb.fwd + dx).map_err(|r| bad(&r))?;
            section_moves(pmb.aft_section, DVec3::new(dx, 0.0, 0.0))
                .chain(section_moves(pmb.fwd_section, DVec3::new(dx, 0.0, 0.0)))
                .collect()
        }
        Target::EntranceLength(e) => {
            let pmb = pmb()?;
            let dx = p.entrance_length.unwrap_or(0.0) - e;
            check_fits(p, pmb.aft, pmb.fwd + dx).map_err(|r| bad(&r))?;
            section_moves(pmb.fwd_section, DVec3::new(dx, 0.0, 0.0)).collect()
        }
        Target::RunLength(r) => {
            let pmb = pmb()?;
            let dx = r - p.run_length.unwrap_or(0.0);
            check_fits(p, pmb.aft + dx, pmb.fwd).map_err(|r| bad(&r))?;
            section_moves(pmb.aft_section, DVec3::new(dx, 0.0, 0.0)).collect()
        }
        Target::BilgeRadius(r) => {
            if p.bilges.is_empty() {
                return Err(FormError::NotMeasurable {
                    parameter,
                    reason: "no midship section has flat of bottom and flat of side vertices"
                        .into(),
                });
            }
            let mut out = Vec::new();
            for g in &p.bilges {
                let Some(r0) = g.radius else {
                    return Err(FormError::NotMeasurable {
                        parameter,
                        reason: format!(
                            "the bilge of midship section '{}' is not a circular arc",
                            curves[g.section].name
                        ),
                    });
                };
                let half = 0.5 * g.bottom_direction.angle_between(g.side_direction);
                let dl = (r - r0) / half.tan();
                let pb = form.vertices[g.fob_vertex].position;
                let ps = form.vertices[g.fos_vertex].position;
                if g.corner.distance(pb) + dl <= 0.0 || g.corner.distance(ps) + dl <= 0.0 {
                    return Err(bad("the arc would not fit on the flat of bottom and side"));
                }
                out.push(VertexMove {
                    vertex: g.fob_vertex,
                    translation: g.bottom_direction * dl,
                });
                out.push(VertexMove {
                    vertex: g.fos_vertex,
                    translation: g.side_direction * dl,
                });
            }
            out
        }
    };
    Ok(Plan::Moves(moves))
}

/// The move of deck vertex `v` by `dz` up: along a straight stem or transom ending there (it
/// keeps its rake and its lower end), else straight up.
fn up_along_straight(network: &Network, form: &FormTopology, v: usize, dz: f64) -> DVec3 {
    let curves = network.curves();
    form.edges
        .iter()
        .filter(|e| {
            (e.start == v || e.end == v)
                && e.kind == super::identify::EdgeKind::Straight
                && curves[e.curve].role != Role::Deck
        })
        .find_map(|e| {
            let d = form.vertices[e.end].position - form.vertices[e.start].position;
            (d.z.abs() > RAKE_MIN * d.length()).then(|| d * (dz / d.z))
        })
        .unwrap_or(DVec3::new(0.0, 0.0, dz))
}

/// A straight edge rising less than this fraction of its length is no stem or transom line.
const RAKE_MIN: f64 = 0.1;

/// Vertices within this fraction of the breadth of the centreplane stay there.
const CENTRE_FRACTION: f64 = 1e-6;

/// The move of a bilge vertex when the side moves out by `d`: along the bottom line (so the
/// arc keeps its radius), `d` outwards.
fn outward_along_bottom(g: &Bilge, d: f64) -> DVec3 {
    let b = -g.bottom_direction;
    if b.y.abs() <= f64::EPSILON {
        return DVec3::new(0.0, d, 0.0);
    }
    b * (d / b.y)
}

/// Whether `pos` lies on the bottom below the bilge (between keel and flat-of-bottom vertex).
fn below_bilge(g: &Bilge, pos: DVec3) -> bool {
    (pos - g.corner).dot(g.bottom_direction) > 0.0 && (pos - g.corner).dot(g.side_direction) <= 0.0
}

/// Whether a PMB from `aft` to `fwd` fits inside the hull.
fn check_fits(p: &super::parameters::FormParameters, aft: f64, fwd: f64) -> Result<(), String> {
    if fwd <= aft {
        return Err("the parallel middle body would vanish".into());
    }
    if aft <= p.x_range[0] || fwd >= p.x_range[1] {
        return Err(format!(
            "the parallel middle body ({aft:.3} to {fwd:.3}) would reach the ends of the hull ({:.3} to {:.3})",
            p.x_range[0], p.x_range[1]
        ));
    }
    Ok(())
}

/// Take `network` (with its `form`) to `target`: plan it ([`parametric_moves`]) and carry it
/// out ([`transform`], or for a transverse scale every control point's y scaled and the form
/// vertices reported as moved by it).
///
/// Errors as [`parametric_moves`] and [`transform`].
pub fn transform_to(
    network: &Network,
    form: &FormTopology,
    target: Target,
    tolerance: Tolerance,
) -> Result<Transformed, FormError> {
    match parametric_moves(network, form, target)? {
        Plan::Moves(moves) => transform(network, form, &moves, tolerance),
        Plan::TransverseScale(s) => {
            let scale = DVec3::new(1.0, s, 1.0);
            let curves = network
                .curves()
                .iter()
                .map(|c| {
                    let pts = c
                        .curve
                        .control_points()
                        .into_iter()
                        .map(|p| p * scale)
                        .collect();
                    c.curve
                        .with_control_points(pts)
                        .map(|curve| NetworkCurve {
                            name: c.name.clone(),
                            role: c.role,
                            curve,
                        })
                        .map_err(|e| FormError::from(e.named(&c.name)))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let max_move = network
                .curves()
                .iter()
                .flat_map(|c| c.curve.control_points())
                .map(|p| (p.y * (s - 1.0)).abs())
                .fold(0.0, f64::max);
            Ok(Transformed {
                network: Network::try_new(network.name.clone(), curves)?,
                vertex_translations: form
                    .vertices
                    .iter()
                    .map(|v| DVec3::new(0.0, v.position.y * (s - 1.0), 0.0))
                    .collect(),
                reattached: Vec::new(),
                max_move,
            })
        }
    }
}
