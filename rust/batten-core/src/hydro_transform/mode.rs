//! The two deformations a hydrostatic transformation steers (seed 002 §8), each with two
//! unknowns and its limits:
//!
//! - **PMB** (§8.1): the entrance and run lengths, the PMB's ends moved through the form
//!   topology (the midship sections translate; the ends, deck and flats keep their shape). The
//!   PMB, the entrance and the run each keep at least [`MIN_LENGTH_FRACTION`] of the length.
//! - **Bulge** (§8.2): the offsets (m) at the middle of the entrance's and the run's form faces
//!   below the waterline, along their normals, zero on their edges (so the face meets its
//!   neighbours as before); outward is fuller. Each at most [`MAX_BULGE_FRACTION`] of the
//!   half breadth.

use glam::DVec3;

use crate::form::{parametric_moves, transform_bulged, FaceBulge, FormTopology, Plan, Target};
use crate::network::{Network, NetworkCurve};
use crate::tolerance::Tolerance;

/// The PMB, the entrance and the run each keep at least this fraction of the hull's length.
pub const MIN_LENGTH_FRACTION: f64 = 0.02;
/// A face's bulge is at most this fraction of the hull's half breadth, either way.
pub const MAX_BULGE_FRACTION: f64 = 0.25;
/// Points per form edge for the place of a face (its centre in x, its lowest point).
const EDGE_SAMPLES: usize = 9;

/// Which deformation, and its limits.
#[derive(Clone, Debug)]
pub(super) enum Mode {
    /// The PMB's ends: unknowns (entrance length, run length).
    Pmb {
        /// The entrance and run lengths of the original.
        start: [f64; 2],
        /// Shortest PMB, entrance and run (m).
        min_len: f64,
        /// Entrance + PMB + run (m): what the two ends share.
        total: f64,
    },
    /// Bulges of the entrance's and the run's faces below the waterline: unknowns (entrance
    /// offset, run offset), m.
    Bulge {
        /// Form faces of the entrance.
        entrance: Vec<usize>,
        /// Form faces of the run.
        run: Vec<usize>,
        /// Largest offset either way (m).
        max: f64,
    },
}

/// The entrance's and the run's form faces below the waterline at `draft`: faces reaching below
/// it, forward (aft) of `x_mid` by the middle of their edges' points; the faces of the
/// parallel middle body `pmb` (x from, to: every point within it) are no end's.
pub(super) fn end_faces(
    network: &Network,
    form: &FormTopology,
    draft: f64,
    x_mid: f64,
    pmb: Option<[f64; 2]>,
    tolerance: Tolerance,
) -> (Vec<usize>, Vec<usize>) {
    let curves = network.curves();
    let (mut entrance, mut run) = (Vec::new(), Vec::new());
    for (i, face) in form.faces.iter().enumerate() {
        let points: Vec<DVec3> = face
            .sides
            .iter()
            .flatten()
            .flat_map(|&(e, _)| {
                let edge = &form.edges[e];
                let c = &curves[edge.curve].curve;
                (0..EDGE_SAMPLES).map(move |k| {
                    let t = edge.t0 + (edge.t1 - edge.t0) * k as f64 / (EDGE_SAMPLES - 1) as f64;
                    c.point(t)
                })
            })
            .collect();
        if points.is_empty() || points.iter().all(|p| p.z >= draft) {
            continue;
        }
        let tol = tolerance.get();
        if pmb.is_some_and(|[a, b]| points.iter().all(|p| p.x >= a - tol && p.x <= b + tol)) {
            continue;
        }
        let x = points.iter().map(|p| p.x).sum::<f64>() / points.len() as f64;
        if x > x_mid {
            entrance.push(i);
        } else {
            run.push(i);
        }
    }
    (entrance, run)
}

impl Mode {
    /// The unknowns of the original.
    pub(super) fn start(&self) -> [f64; 2] {
        match self {
            Mode::Pmb { start, .. } => *start,
            Mode::Bulge { .. } => [0.0, 0.0],
        }
    }

    /// A length for "no step left" (m).
    pub(super) fn scale(&self) -> f64 {
        match self {
            Mode::Pmb { total, .. } => *total,
            Mode::Bulge { max, .. } => *max,
        }
    }

    /// How far `x` may go along `d` (a fraction in [0, 1]) and the limit met first.
    pub(super) fn room(&self, x: [f64; 2], d: [f64; 2]) -> (f64, Option<&'static str>) {
        let mut t = 1.0f64;
        let mut which = None;
        let mut cap = |slack: f64, rate: f64, name: &'static str| {
            if rate < 0.0 && slack + rate * t < 0.0 {
                t = (slack / -rate).max(0.0);
                which = Some(name);
            }
        };
        match self {
            Mode::Pmb { min_len, total, .. } => {
                cap(
                    x[0] - min_len,
                    d[0],
                    "the entrance would be shorter than 2 % of the hull",
                );
                cap(
                    x[1] - min_len,
                    d[1],
                    "the run would be shorter than 2 % of the hull",
                );
                cap(
                    total - x[0] - x[1] - min_len,
                    -(d[0] + d[1]),
                    "the parallel middle body would be shorter than 2 % of the hull",
                );
            }
            Mode::Bulge { max, .. } => {
                const ENTRANCE: &str =
                    "the entrance's bulge would exceed a quarter of the half breadth";
                const RUN: &str = "the run's bulge would exceed a quarter of the half breadth";
                cap(max - x[0], -d[0], ENTRANCE);
                cap(max + x[0], d[0], ENTRANCE);
                cap(max - x[1], -d[1], RUN);
                cap(max + x[1], d[1], RUN);
            }
        }
        (t, which)
    }

    /// The direction along the limit `which` (as [`Mode::room`] names it).
    pub(super) fn along(&self, which: &str) -> [f64; 2] {
        if which.contains("parallel") {
            [1.0, -1.0]
        } else if which.contains("entrance") {
            [0.0, 1.0]
        } else {
            [1.0, 0.0]
        }
    }

    /// `network` (of form topology `form`) deformed to the unknowns `x`, or why not.
    pub(super) fn deform(
        &self,
        network: &Network,
        form: &FormTopology,
        x: [f64; 2],
        tolerance: Tolerance,
    ) -> Result<Network, String> {
        let (moves, bulges) = match self {
            // Both PMB ends in one deformation of the original (their moves touch different
            // sections), so the result does not depend on an order of steps.
            Mode::Pmb { .. } => {
                let mut moves = Vec::new();
                for target in [Target::EntranceLength(x[0]), Target::RunLength(x[1])] {
                    match parametric_moves(network, form, target).map_err(|e| e.to_string())? {
                        Plan::Moves(m) => moves.extend(m),
                        Plan::TransverseScale(_) => {
                            return Err(format!("{} is no PMB move", target.name()))
                        }
                    }
                }
                (moves, Vec::new())
            }
            Mode::Bulge { entrance, run, .. } => {
                let bulge = |faces: &[usize], amount: f64| {
                    faces
                        .iter()
                        .map(move |&face| FaceBulge { face, amount })
                        .collect::<Vec<_>>()
                };
                let mut bulges = bulge(entrance, x[0]);
                bulges.extend(bulge(run, x[1]));
                (Vec::new(), bulges)
            }
        };
        let deformed = transform_bulged(network, form, &moves, &bulges, tolerance)
            .map_err(|e| e.to_string())?
            .network;
        // As the modeller will hold it (re-attachment inserts knots that Blender's layouts
        // cannot hold; its Bézier pieces then take a unit of parameter each, and the patches
        // follow the parameters), so the hull measured is the hull the designer gets.
        let held = deformed
            .curves()
            .iter()
            .map(|c| NetworkCurve {
                curve: c.curve.as_layouts_hold(),
                ..c.clone()
            })
            .collect();
        Network::try_new(deformed.name.clone(), held).map_err(|e| e.to_string())
    }
}
