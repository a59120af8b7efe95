//! Surface fairing through families of plane sections, as loftsmen faired a hull (Pla, Vinacua,
//! Vivó, Brunet, Rodríguez 1998, *Surface fairing for ship hull design*, §4): in a family of
//! sections (stations, waterlines, buttocks) the filtered section F[i] is built from the
//! neighbours C[i−1], C[i+1] (ends fixed), the section of largest bias ‖F[k] − C[k]‖ is moved by
//! λ ≤ 1 toward F[k] with λ as large as every constraint allows, and again; the families take
//! turns.
//!
//! Before the relaxation every section is smoothed along itself ([`smooth`]): the filter
//! compares a section with its neighbours and so cannot see noise along the section itself
//! (each control point off by its own amount, as in the paper's test). On KCS with noise of
//! 30 % of a 10 mm tolerance the relaxation alone left ∫κ′² ds where the noise put it, 84
//! times the clean hull's; smoothed first, it ends below the clean hull's. And a relaxation move
//! must leave its curves fairer ([`relax`]'s guard): the cubic filter is not the section of a
//! real hull even without noise, and unguarded moves toward it spent the tolerance making
//! the clean KCS less fair (55 inflections to 90).
//!
//! In batten the sections are the network's own curves, and the network is the surface: it is
//! rebuilt from the faired curves, so the paper's least-squares `SurfaceModification` is the
//! hull build itself. A node moved on a station moves on the waterline through it too (the
//! waterline takes the least change that carries it along and keeps its other nodes), so the
//! network stays exact; such a node may only move along the line both planes share.
//!
//! Constraints: every control point stays within the tolerance (global, or per curve) of where
//! it started, and so every point of every curve does; fixed curves (by role: keel, stem,
//! transom, deck, midship, flat of side and bottom, and the knuckle lines, so a chine stays
//! where and what it is; or by name) are not touched (bitwise); the nodes on them, every curve's
//! ends (so the perpendiculars, the DWL's ends and the outline stay) and given fixed positions
//! stay; sections stay in their planes (AP, FP and DWL positions); smooth joints stay smooth and
//! corners (knuckle points) corners.
//!
//! Implementation note: the sections' points are their control points' Greville points (the
//! paper's polygonal sections); the filter is in [`filter`], the moves in [`relax`]. Knots are
//! inserted once at the nodes so that each node has a control point of its own to move; they
//! stay for the rest of the fairing.

mod banded;
mod families;
mod filter;
mod least_change;
mod nodes;
mod relax;
mod report;
mod smooth;

use std::collections::HashSet;

use glam::DVec3;
use rand_core::{Rng, SeedableRng};
use rand_xorshift::XorShiftRng;

pub use families::SectionFamily;
pub use filter::SectionFilter;
pub use report::{HullFairness, SectionFairness, SectionReport, SurfaceFairReport};

use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::network::{Network, NetworkCurve, Role};
use crate::tolerance::Tolerance;
use families::{group_families, plane_of, Family};
use filter::{greville, SectionBias};
use nodes::{nodes, refined};
use relax::State;
use smooth::smooth_sections;

/// Default tolerance (m) of the fairing: 10 mm, the accuracy a yard fairs a full-scale hull to.
pub const DEFAULT_SURFACE_FAIR_TOLERANCE: f64 = 1e-2;
/// Default number of rounds (each round one family, in turn).
pub const DEFAULT_SURFACE_FAIR_ROUNDS: usize = 12;
/// Default bias (as a share of the tolerance) below which a family counts as fair: 1 %.
pub const DEFAULT_BIAS_SHARE: f64 = 0.01;
/// Default smoothing length along the sections, as a multiple of the tolerance: 200, so a
/// fairing to 10 mm smooths out the waves along a section shorter than about 2 m and keeps
/// the longer ones (the form), and a model-scale hull faired to a scaled tolerance is smoothed
/// alike (see [`fair_sections`]).
pub const DEFAULT_SMOOTHING_PER_TOLERANCE: f64 = 200.0;
/// The paper's MaxIter per round, as a multiple of the family's sections: each may be picked
/// this many times on average before the family's turn ends.
const PICKS_PER_SECTION: usize = 4;

/// The roles whose curves the fairing keeps as they are unless told otherwise.
pub const DEFAULT_FIXED_ROLES: [Role; 8] = [
    Role::Keel,
    Role::Stem,
    Role::Transom,
    Role::Deck,
    Role::Midship,
    Role::Fos,
    Role::Fob,
    Role::Knuckle,
];

/// Options of [`fair_sections`].
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceFairOptions {
    /// Largest distance (m) any point may move from where it started.
    pub tolerance: f64,
    /// Per curve (by name), a tolerance of its own (m).
    pub curve_tolerances: Vec<(String, f64)>,
    /// The families to fair, in the order they take turns.
    pub families: Vec<SectionFamily>,
    /// Curves of these roles stay as they are.
    pub fixed_roles: Vec<Role>,
    /// Curves of these names stay as they are.
    pub fixed_curves: Vec<String>,
    /// Nodes within the model tolerance of these points stay where they are.
    pub fixed_points: Vec<DVec3>,
    /// The filtered section the sections are relaxed toward.
    pub filter: SectionFilter,
    /// Most rounds (one family per round).
    pub max_rounds: usize,
    /// A family is fair when no section's RMS bias exceeds this (m); default 1 % of the
    /// tolerance.
    pub bias_target: Option<f64>,
    /// Points closer than this are one point (nodes, planes).
    pub model_tolerance: Tolerance,
    /// The smoothing length along the sections (m) before the relaxation;
    /// `None`: [`DEFAULT_SMOOTHING_PER_TOLERANCE`] times the tolerance; `Some(0.0)`: no
    /// smoothing along the sections (the paper's relaxation alone).
    pub smoothing_length: Option<f64>,
}

impl Default for SurfaceFairOptions {
    fn default() -> Self {
        SurfaceFairOptions {
            tolerance: DEFAULT_SURFACE_FAIR_TOLERANCE,
            curve_tolerances: Vec::new(),
            families: vec![SectionFamily::Stations, SectionFamily::Waterlines],
            fixed_roles: DEFAULT_FIXED_ROLES.to_vec(),
            fixed_curves: Vec::new(),
            fixed_points: Vec::new(),
            filter: SectionFilter::default(),
            max_rounds: DEFAULT_SURFACE_FAIR_ROUNDS,
            bias_target: None,
            model_tolerance: Tolerance::DEFAULT,
            smoothing_length: None,
        }
    }
}

/// A faired network and its report.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceFairing {
    /// The network, curve for curve in the input's order: fixed and unmoved curves exactly as
    /// given, moved ones with a knot at each of their nodes.
    pub network: Network,
    /// What was done, and the figures before and after.
    pub report: SurfaceFairReport,
}

fn positive(value: f64, what: impl FnOnce() -> String) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidInput(format!(
            "{} {value} must be a positive finite number of metres",
            what()
        )))
    }
}

/// The fairing's set-up: the sections, their families and nodes, ready to move.
struct Setup {
    state: State,
    families: Vec<Family>,
    /// Per curve: its family (index into `families`) and plane (group index).
    place: Vec<Option<(usize, usize)>>,
}

fn setup(network: &Network, options: &SurfaceFairOptions) -> Result<Setup, Error> {
    let tol = positive(options.tolerance, || "tolerance".to_owned())?;
    if options.families.is_empty() {
        return Err(Error::InvalidInput(
            "families: give at least one of stations, waterlines, buttocks".to_owned(),
        ));
    }
    let curves = network.curves();
    let index = |name: &str, what: &str| {
        curves.iter().position(|c| c.name == name).ok_or_else(|| {
            Error::InvalidInput(format!("{what}: the network has no curve '{name}'"))
        })
    };
    let mut fixed: HashSet<usize> = HashSet::new();
    for name in &options.fixed_curves {
        fixed.insert(index(name, "fixed")?);
    }
    let mut tolerance = vec![tol; curves.len()];
    for (name, t) in &options.curve_tolerances {
        let i = index(name, "curve tolerances")?;
        tolerance[i] = positive(*t, || format!("curve '{name}': tolerance"))?;
    }
    if let Some(p) = options.fixed_points.iter().find(|p| !p.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "fixed points: {p} is not a finite point"
        )));
    }
    let model = options.model_tolerance.get();
    // Every curve in a family's plane is a neighbour in the filter; only the movable ones move.
    // Sections of the families not faired are carried along where a faired one moves a node.
    // A section is in its plane to within the tolerance: an imported section moved through its
    // nodes may leave the plane by a little of it (and keeps that, moving only in the plane).
    let planes: Vec<Option<(SectionFamily, f64)>> = curves
        .iter()
        .map(|c| plane_of(&c.curve, &SectionFamily::ALL, tol))
        .collect();
    let movable: Vec<bool> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| !fixed.contains(&i) && !options.fixed_roles.contains(&c.role))
        .collect();
    let families = group_families(&planes, &options.families, tol);
    let mut place = vec![None; curves.len()];
    for (f, family) in families.iter().enumerate() {
        for (g, group) in family.groups.iter().enumerate() {
            for &c in group.curves.iter().filter(|&&c| movable[c]) {
                place[c] = Some((f, g));
            }
        }
    }
    let axes: Vec<Option<usize>> = planes
        .iter()
        .zip(&movable)
        .map(|(p, &m)| p.filter(|_| m).map(|(f, _)| f.axis()))
        .collect();
    let junctions = network.junctions(options.model_tolerance)?;
    let originals: Vec<NurbsCurve> = curves.iter().map(|c| c.curve.clone()).collect();
    let found = nodes(&junctions, &originals, &axes, &options.fixed_points, model);
    let refined_curves = curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if axes[i].is_none() {
                return Ok(c.curve.clone());
            }
            let at: Vec<f64> = found.on_curve[i].iter().map(|&(t, _)| t).collect();
            refined(&c.curve, &at).map_err(|e| e.named(&c.name))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    // The node parameters are the same on the refined curves (knot insertion keeps them).
    for (i, t) in tolerance.iter_mut().enumerate() {
        if axes[i].is_none() {
            *t = 0.0;
        }
    }
    let state = State {
        names: curves.iter().map(|c| c.name.clone()).collect(),
        decomps: refined_curves
            .iter()
            .map(NurbsCurve::bezier_decomposition)
            .collect(),
        original: refined_curves
            .iter()
            .map(NurbsCurve::control_points)
            .collect(),
        curves: refined_curves,
        tolerance,
        axes,
        nodes: found,
        moves: vec![0; curves.len()],
        model_tolerance: model,
    };
    Ok(Setup {
        state,
        families,
        place,
    })
}

/// The biases of every section of every family.
fn all_biases(setup: &Setup, filter: SectionFilter) -> Vec<Option<SectionBias>> {
    setup
        .place
        .iter()
        .enumerate()
        .map(|(c, p)| p.map(|(f, g)| setup.state.bias(&setup.families[f], g, c, filter)))
        .collect()
}

/// Fair the sections of `network` (module doc; Pla et al. 1998 §4) within the tolerance and
/// constraints of `options`: each section smoothed along itself first, every section's waves
/// shorter than the smoothing length taken out and its form and tight turns kept, the nodes
/// shared by consensus; then the relaxation's rounds.
///
/// Errors: a tolerance or per-curve tolerance or smoothing length that is not positive and
/// finite, no family, a
/// fixed or toleranced curve name the network does not have, a fixed point that is not finite
/// ([`Error::InvalidInput`]); the node search's own errors. Sections that cannot move within
/// their constraints are no error: they stay, and the report says how far the fairing got.
pub fn fair_sections(
    network: &Network,
    options: &SurfaceFairOptions,
) -> Result<SurfaceFairing, Error> {
    let faired = fair_sections_with(network, options, &mut |_, _| true)?;
    faired.ok_or_else(|| Error::InvalidInput("surface fairing stopped".to_owned()))
}

/// [`fair_sections`], calling `round_done(rounds done, max rounds)` after each round (one
/// family's turn, Pla et al. 1998 §4); when it returns `false` the fairing stops there and
/// gives `Ok(None)`: nothing of the network is changed (the caller keeps its curves). So a
/// front end shows progress and lets the designer cancel between rounds.
///
/// Errors: as [`fair_sections`].
pub fn fair_sections_with(
    network: &Network,
    options: &SurfaceFairOptions,
    round_done: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<Option<SurfaceFairing>, Error> {
    let mut setup = setup(network, options)?;
    let filter = options.filter;
    let target = match options.bias_target {
        Some(b) => positive(b, || "bias target".to_owned())?,
        None => DEFAULT_BIAS_SHARE * options.tolerance,
    };
    let before = all_biases(&setup, filter);
    let smoothing_length = match options.smoothing_length {
        Some(0.0) => 0.0,
        Some(l) => positive(l, || "smoothing length".to_owned())?,
        None => DEFAULT_SMOOTHING_PER_TOLERANCE * options.tolerance,
    };
    let smoothed = if smoothing_length > 0.0 {
        let lengths: Vec<Option<f64>> = (0..network.curves().len())
            .map(|c| {
                setup.state.axes[c].map(|_| {
                    if setup.place[c].is_some() {
                        smoothing_length
                    } else {
                        0.0
                    }
                })
            })
            .collect();
        smooth_sections(&mut setup.state, &lengths)?
    } else {
        0
    };
    let mut rounds = 0;
    let mut total_moves = 0;
    let mut idle_rounds = 0;
    let mut converged = false;
    for round in 0..options.max_rounds {
        if setup.families.is_empty() {
            converged = true;
            break;
        }
        rounds = round + 1;
        let f = round % setup.families.len();
        let moved = relax_family(&mut setup, f, filter, target)?;
        total_moves += moved.moves;
        if !round_done(rounds, options.max_rounds) {
            return Ok(None);
        }
        idle_rounds = if moved.moves == 0 { idle_rounds + 1 } else { 0 };
        if idle_rounds >= setup.families.len() {
            converged = moved.fair;
            break;
        }
    }
    let after = all_biases(&setup, filter);
    if !converged {
        converged = after.iter().flatten().all(|b| b.rms <= target);
    }
    let report = report::report(
        network,
        &setup.state,
        &setup.place,
        &setup.families,
        &before,
        &after,
        report::Totals {
            rounds,
            moves: total_moves,
            converged,
            bias_target: target,
            smoothing_length,
            smoothed,
        },
    );
    Ok(Some(SurfaceFairing {
        network: moved_network(network, &setup.state)?,
        report,
    }))
}

/// What one family's turn came to.
struct Turn {
    moves: usize,
    /// No section is biased beyond the target any more.
    fair: bool,
}

/// One round: the family's sections of largest bias moved, one at a time, until none is biased
/// beyond `target`, none can move, or the paper's MaxIter is reached.
fn relax_family(
    setup: &mut Setup,
    f: usize,
    filter: SectionFilter,
    target: f64,
) -> Result<Turn, Error> {
    let family = setup.families[f].clone();
    let last = family.groups.len().saturating_sub(1);
    // Inner sections only: the first and last are their own filtered sections.
    let members: Vec<(usize, usize)> = family
        .groups
        .iter()
        .enumerate()
        .filter(|&(g, _)| g > 0 && g < last)
        .flat_map(|(g, group)| group.curves.iter().map(move |&c| (g, c)))
        .filter(|&(_, c)| setup.place[c].is_some())
        .collect();
    let mut biases: Vec<Option<SectionBias>> = vec![None; members.len()];
    let mut stuck = vec![false; members.len()];
    let mut moves = 0;
    for _ in 0..PICKS_PER_SECTION * members.len() {
        for (m, &(g, c)) in members.iter().enumerate() {
            if biases[m].is_none() {
                biases[m] = Some(setup.state.bias(&family, g, c, filter));
            }
        }
        let pick = (0..members.len())
            .filter(|&m| !stuck[m])
            .map(|m| (m, biases[m].as_ref().map_or(0.0, |b| b.rms)))
            .filter(|&(_, rms)| rms > target)
            .max_by(|a, b| a.1.total_cmp(&b.1));
        let Some((m, _)) = pick else { break };
        let c = members[m].1;
        let wish = biases[m]
            .as_ref()
            .map(|b| b.moves.clone())
            .unwrap_or_default();
        let planned = setup.state.plan(c, &wish);
        let Some(plan) = planned else {
            stuck[m] = true;
            continue;
        };
        let lambda = setup.state.step_length(&plan);
        if !setup.state.moves_visibly(&plan, lambda) || !setup.state.fairer(&plan, lambda) {
            stuck[m] = true;
            continue;
        }
        setup.state.apply(&plan, lambda)?;
        moves += 1;
        // The sections whose filter sees the moved one (and any moved section of this family
        // carried along) have a new bias.
        let touched: Vec<usize> = plan.iter().map(|(c, _)| *c).collect();
        for (n, &(gn, cn)) in members.iter().enumerate() {
            let near = touched.iter().any(|&t| {
                t == cn
                    || setup.place[t]
                        .is_some_and(|(ft, gt)| ft == f && gt.abs_diff(gn) <= filter.reach())
            });
            if near {
                biases[n] = None;
                stuck[n] = false;
            }
        }
    }
    for (m, &(g, c)) in members.iter().enumerate() {
        if biases[m].is_none() {
            biases[m] = Some(setup.state.bias(&family, g, c, filter));
        }
    }
    let fair = biases.iter().flatten().all(|b| b.rms <= target);
    Ok(Turn { moves, fair })
}

/// The paper's test input (Pla et al. 1998, §5: "the original surface has been perturbed with
/// random noise below the tolerance"): every movable section of `options.families` moved along
/// its normal at each control point by a random amount, uniform in ±`amplitude` (m), from the
/// generator seeded with `seed`, each move kept to what its nodes allow and carried along the
/// crossing sections (as a fairing move is), so the network stays exact. Fixed curves stay.
///
/// Errors: as [`fair_sections`]; an amplitude that is not positive and finite.
pub fn section_noise(
    network: &Network,
    amplitude: f64,
    seed: u64,
    options: &SurfaceFairOptions,
) -> Result<Network, Error> {
    let amplitude = positive(amplitude, || "noise amplitude".to_owned())?;
    let mut setup = setup(network, options)?;
    let mut rng = XorShiftRng::seed_from_u64(seed);
    for c in 0..network.curves().len() {
        let Some(axis) = setup.state.axes[c] else {
            continue;
        };
        let curve = &setup.state.curves[c];
        let wish: Vec<DVec3> = greville(curve)
            .into_iter()
            .map(|t| {
                let mut tangent = curve.derivs(t).d1;
                tangent[axis] = 0.0;
                let n = DVec3::AXES[axis].cross(tangent.normalize_or_zero());
                // A uniform number in [−1, 1) from the top 53 bits.
                let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                (2.0 * u - 1.0) * amplitude * n
            })
            .collect();
        if let Some(plan) = setup.state.plan(c, &wish) {
            setup.state.apply(&plan, 1.0)?;
        }
    }
    moved_network(network, &setup.state)
}

/// `network` with the curves that moved in `state` as they are now (the others exactly as
/// given: a curve that never moved keeps its own knots).
fn moved_network(network: &Network, state: &State) -> Result<Network, Error> {
    let curves = network
        .curves()
        .iter()
        .enumerate()
        .map(|(i, c)| NetworkCurve {
            name: c.name.clone(),
            role: c.role,
            curve: if state.moves[i] > 0 {
                state.curves[i].clone()
            } else {
                c.curve.clone()
            },
        })
        .collect();
    Network::try_new(network.name.clone(), curves)
}
