//! Hydrostatic transformations (seed 002 §8): a hull taken to a target displaced volume and
//! LCB through its form topology, by one of two deformations ([`mode`]): moving the ends of its
//! parallel middle body (§8.1; the ends, the deck and the midship section keep their shape), or
//! bulging / flattening the form faces of its entrance and run (§8.2; for a hull without a
//! PMB, or with `keep_pmb`). §8.3's schedule: the PMB's ends unless the PMB is held, and
//! both when a change is too large for the PMB's ends alone (the ends bulged from the closest
//! hull the PMB's ends reach).
//!
//! - **The start**: for the PMB mode [`lackenby`]'s model (Lackenby 1950, the general case
//!   with a PMB) gives the first Jacobian; for the bulge mode two hull evaluations give it by
//!   differences. (batten's PMB move keeps the flats and the deck where they are, so its ends
//!   do not squeeze affinely as Lackenby's do: on the test barge, whose flat of side runs far
//!   into the ends, the model puts ∂∇/∂e four times too high, and the first Broyden updates
//!   correct it.)
//! - **The iteration** runs on batten's exact hydrostatics of the deformed and rebuilt hull
//!   (each a *hull evaluation*: a deformation of the original, its curves as Blender will hold
//!   them): quasi-Newton steps (Broyden's update of the Jacobian), kept inside the deformation's
//!   limits, until `|δ∇|/∇ ≤ 1e-5` and `|δLCB| ≤ 1e-5·Lpp` ([`VOLUME_TOLERANCE`],
//!   [`LCB_TOLERANCE`]).
//! - **The bracket** (§8.3): the mode's geometric limits, and the [`shape`] checks every hull
//!   evaluated must pass (its faces and warnings as the original's, no station gaining an
//!   inflection): a step to a hull that fails one is halved back towards the last good hull,
//!   and later steps stay within that distance.
//! - **Out of range**: the closest reachable hull (least squares on the scaled misses, along
//!   the limit that stopped it), how far the hulls evaluated went, and which limit it was.
//!
//! A target that is not given is held at the hull's present value.

mod lackenby;
mod mode;
mod shape;

pub use mode::{MAX_BULGE_FRACTION, MIN_LENGTH_FRACTION};

use crate::error::Error;
use crate::form::{form_topology, FormError, FormOptions, FormTopology};
use crate::hull::{build_hull, HullOptions};
use crate::hydro::{default_datums, hydrostatics, CellDensity, Datums, Flotation, Hydrostatics};
use crate::network::Network;
use lackenby::Lackenby;
use mode::{end_faces, Kind, Mode};
use shape::Reference;

/// Converged when the volume misses by at most this fraction of the target volume.
pub const VOLUME_TOLERANCE: f64 = 1e-5;
/// Converged when the LCB misses by at most this fraction of Lpp.
pub const LCB_TOLERANCE: f64 = 1e-5;
/// Hull evaluations (transform, rebuild, hydrostatics) at most per deformation, the original's
/// included.
pub const MAX_EVALUATIONS: usize = 16;
/// A step at a limit that takes less than this fraction off the (scaled) misses ends the
/// iteration: the targets are out of range and the best hull so far is the closest.
const STALL_REDUCTION: f64 = 0.02;
/// Halvings of a step whose hull fails a shape check before the limit is taken as found.
const MAX_HALVINGS: usize = 5;
/// The bulge mode's difference step for its first Jacobian, as a fraction of the largest bulge.
const BULGE_DIFFERENCE: f64 = 0.02;

/// The volume target of a hydrostatic transformation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VolumeTarget {
    /// Displaced volume ∇ (m³, both sides).
    Volume(f64),
    /// Displacement Δ (t) at the options' density.
    Displacement(f64),
    /// Block coefficient on the original's Lpp, Bwl and the draft.
    Cb(f64),
    /// Prismatic coefficient on the original's midship section and Lpp (linked to Cb through
    /// Cm).
    Cp(f64),
}

/// What a hydrostatic transformation aims at: a volume (or Δ, Cb, Cp), an LCB (x, m, in the
/// hull's frame, as [`Hydrostatics::lcb`]), or both; `None` holds the present value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HydroTargets {
    /// The volume target.
    pub volume: Option<VolumeTarget>,
    /// The LCB target (x of the centre of buoyancy, m).
    pub lcb: Option<f64>,
    /// What of the parallel middle body to hold (§8.3): the ends' faces are bulged for what
    /// the PMB may not do.
    pub hold: PmbHold,
}

/// What of the parallel middle body a hydrostatic transformation must keep (§8.3's schedule:
/// the PMB's ends move unless it is held; when it is held in part, the ends' faces are
/// balanced against it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PmbHold {
    /// Nothing: its ends move (and the ends' faces bulge as well when that is not enough).
    #[default]
    Free,
    /// Its length: it shifts along x for the LCB, and the ends bulge alike for the volume.
    Length,
    /// Its position: it lengthens (half at each end) for the volume, and the ends bulge
    /// opposite ways for the LCB.
    Position,
    /// All of it: the ends' faces bulge, each its own way.
    Whole,
}

/// How the hull floats and is built while it is transformed.
#[derive(Clone, Copy, Debug)]
pub struct HydroTransformOptions {
    /// Draft (m above the baseline), upright and level.
    pub draft: f64,
    /// Perpendiculars; `None`: those the original implies at `draft` (FP at the fore end of
    /// its waterline, AP `lpp` aft of it or at the waterline's aft end), held for every hull.
    pub datums: Option<Datums>,
    /// Lpp for the implied perpendiculars (when `datums` is `None`).
    pub lpp: Option<f64>,
    /// Water density (t/m³).
    pub density: f64,
    /// Model tolerance and resolution of the rebuilt hulls.
    pub hull: HullOptions,
}

/// Why the iteration stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// Both targets met within [`VOLUME_TOLERANCE`] and [`LCB_TOLERANCE`].
    Converged,
    /// The targets lie beyond a limit of the deformation: the closest hull is returned.
    OutOfRange {
        /// Which limit stopped it.
        limit: String,
    },
    /// [`MAX_EVALUATIONS`] hull evaluations were spent before the targets were met.
    EvaluationsSpent,
}

/// The ∇ and LCB of the hulls evaluated (the original's included): how far the iteration
/// went each way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Explored {
    /// Smallest and largest ∇ (m³).
    pub volume: [f64; 2],
    /// Smallest and largest LCB (m).
    pub lcb: [f64; 2],
}

impl Explored {
    fn of(h: &Hydrostatics) -> Explored {
        Explored {
            volume: [h.volume; 2],
            lcb: [h.lcb; 2],
        }
    }

    fn merge(&mut self, other: &Explored) {
        self.volume = [
            self.volume[0].min(other.volume[0]),
            self.volume[1].max(other.volume[1]),
        ];
        self.lcb = [self.lcb[0].min(other.lcb[0]), self.lcb[1].max(other.lcb[1])];
    }

    fn add(&mut self, h: &Hydrostatics) {
        self.volume = [self.volume[0].min(h.volume), self.volume[1].max(h.volume)];
        self.lcb = [self.lcb[0].min(h.lcb), self.lcb[1].max(h.lcb)];
    }
}

/// The result of a hydrostatic transformation.
#[derive(Clone, Debug)]
pub struct HydroTransformed {
    /// The transformed network (the original's when nothing had to move).
    pub network: Network,
    /// Hydrostatics of the original and of the result, about the same perpendiculars.
    pub before: Hydrostatics,
    /// Hydrostatics of the result.
    pub after: Hydrostatics,
    /// The volume figure asked for and its value: `"volume"` (m³; a displacement target is
    /// turned into one), `"cb"` or `"cp"`.
    pub target: (&'static str, f64),
    /// The volume the iteration aimed at: Cb and Cp are taken on the original's Lpp, Bwl and
    /// midship section, the design's principal dimensions (a bulge may change the hull's own).
    pub target_volume: f64,
    /// The target LCB.
    pub target_lcb: f64,
    /// The deformation used: `"pmb"` (the PMB's ends moved), `"bulge"` (the ends' faces),
    /// `"pmb+bulge"` (both, for a change too large for the PMB's ends alone),
    /// `"pmb_shift+bulge"` (its length held) or `"pmb_length+bulge"` (its position held).
    pub mode: &'static str,
    /// Entrance length before and after (m), for a hull with a PMB.
    pub entrance_length: Option<[f64; 2]>,
    /// Run length before and after (m), for a hull with a PMB.
    pub run_length: Option<[f64; 2]>,
    /// PMB length before and after (m), for a hull with a PMB.
    pub pmb_length: Option<[f64; 2]>,
    /// The offsets at the middle of the entrance's and the run's faces (m, outward fuller) and
    /// those faces (form-topology face indices), when the ends were bulged.
    pub bulge: Option<([f64; 2], [Vec<usize>; 2])>,
    /// Hull evaluations spent (the original's included).
    pub evaluations: usize,
    /// Why it stopped.
    pub stop: Stop,
    /// The ∇ and LCB of the hulls evaluated.
    pub explored: Explored,
    /// The perpendiculars used.
    pub datums: Datums,
}

/// One evaluated hull: its network and hydrostatics.
struct Evaluated {
    network: Network,
    hydro: Hydrostatics,
}

/// The PMB, entrance and run lengths of `form`, when it has a PMB.
fn pmb_lengths(form: &FormTopology) -> Option<[f64; 3]> {
    let p = &form.parameters;
    Some([p.entrance_length?, p.run_length?, p.pmb.as_ref()?.length])
}

/// Take `network` to `targets` (module docs): by the PMB's ends when it has a PMB and
/// `targets.hold` is [`PmbHold::Free`], else by bulging its ends' faces below the waterline
/// (with the PMB's shift or length for what it may still do). A change
/// too large for the PMB's ends alone is combined (§8.3): from the closest hull they reach,
/// the ends' faces are bulged as well (mode `"pmb+bulge"`; each stage spends at most
/// [`MAX_EVALUATIONS`]).
///
/// Errors: no PMB and no form face of the entrance or the run below the waterline
/// ([`FormError::NotMeasurable`]), a target that is not a finite positive number (LCB: finite;
/// [`FormError::BadTarget`]), the original does not build or float at the draft
/// ([`FormError::Network`]).
pub fn transform_hydrostatic(
    network: &Network,
    targets: HydroTargets,
    options: &HydroTransformOptions,
) -> Result<HydroTransformed, FormError> {
    let first = solve(network, targets, options)?;
    let Stop::OutOfRange { limit } = first.stop.clone() else {
        return Ok(first);
    };
    let lpp = first.datums.x_fp - first.datums.x_ap;
    let misses =
        |h: &Hydrostatics| norm(scaled_misses(h, first.target_volume, first.target_lcb, lpp));
    if first.mode != "pmb" {
        let other = if first.pmb_length.is_some() {
            "; moving the PMB's ends instead (keep_pmb off) may reach it"
        } else {
            ""
        };
        return Ok(HydroTransformed {
            stop: Stop::OutOfRange {
                limit: format!("{limit}{other}"),
            },
            ..first
        });
    }
    let second_targets = HydroTargets {
        volume: Some(VolumeTarget::Volume(first.target_volume)),
        lcb: Some(first.target_lcb),
        hold: PmbHold::Whole,
    };
    let second_options = HydroTransformOptions {
        datums: Some(first.datums),
        ..*options
    };
    match solve(&first.network, second_targets, &second_options) {
        Ok(second) if misses(&second.after) < misses(&first.after) => {
            let mut explored = first.explored;
            explored.merge(&second.explored);
            Ok(HydroTransformed {
                network: second.network,
                after: second.after,
                mode: "pmb+bulge",
                bulge: second.bulge,
                // The second stage's original is the first's result, already evaluated.
                evaluations: first.evaluations + second.evaluations - 1,
                stop: match second.stop {
                    Stop::OutOfRange { limit: then } => Stop::OutOfRange {
                        limit: format!("{limit}; then, bulging the ends: {then}"),
                    },
                    stop => stop,
                },
                explored,
                ..first
            })
        }
        _ => Ok(HydroTransformed {
            stop: Stop::OutOfRange {
                limit: format!("{limit}; bulging the ends as well came no closer"),
            },
            ..first
        }),
    }
}

/// One deformation's solve (module docs): the PMB's ends, or with `targets.hold` or no PMB
/// the bulges (with the PMB's free part).
fn solve(
    network: &Network,
    targets: HydroTargets,
    options: &HydroTransformOptions,
) -> Result<HydroTransformed, FormError> {
    let form_options = FormOptions {
        tolerance: options.hull.tolerance,
        draft: Some(options.draft),
    };
    let tolerance = options.hull.tolerance;
    let form = form_topology(network, &form_options)?;
    let flotation = Flotation {
        draft: options.draft,
        trim: 0.0,
        heel_deg: 0.0,
        density: options.density,
    };
    let original = build_hull(network, &options.hull)?;
    let reference = Reference::of(network, &original, tolerance);
    let cells = original.hydro_model(CellDensity::DEFAULT);
    let datums = match options.datums {
        Some(d) => d,
        None => default_datums(&cells, options.draft, options.lpp).map_err(Error::from)?,
    };
    let before = hydrostatics(&cells, &flotation, &datums).map_err(Error::from)?;
    let lpp = datums.x_fp - datums.x_ap;
    let (target, target_lcb) = target_figures(targets, &before, options.density)?;
    let target_volume = match target.0 {
        "cb" => before.volume * target.1 / before.cb,
        "cp" => before.volume * target.1 / before.cp,
        _ => target.1,
    };

    let miss = |h: &Hydrostatics| scaled_misses(h, target_volume, target_lcb, lpp);
    let met = |f: [f64; 2]| f[0].abs() <= VOLUME_TOLERANCE && f[1].abs() <= LCB_TOLERANCE;
    let mut explored = Explored::of(&before);
    let mut evaluations = 1;
    let evaluate = |x: [f64; 2], mode: &Mode| -> Result<Evaluated, String> {
        let deformed = mode.deform(network, &form, x, tolerance)?;
        let hull = build_hull(&deformed, &options.hull).map_err(|e| e.to_string())?;
        reference.check(&deformed, &hull, tolerance)?;
        // The exact cells: the live ones are 1e-8 relative on smooth hulls but 1e-5 on the
        // frigate's knuckles, as large as the tolerance.
        let cells = hull.hydro_model(CellDensity::DEFAULT);
        let hydro = hydrostatics(&cells, &flotation, &datums).map_err(|e| e.to_string())?;
        Ok(Evaluated {
            network: deformed,
            hydro,
        })
    };

    let p = &form.parameters;
    let lengths = pmb_lengths(&form);
    // Where the iteration starts when not from the original (the bulge mode's trial hulls),
    // and why it cannot start at all.
    let mut start: Option<(Evaluated, [f64; 2], [f64; 2])> = None;
    let mut stuck: Option<String> = None;
    let length = p.x_range[1] - p.x_range[0];
    let (mode, mut jac) = match (&p.pmb, lengths) {
        (Some(pmb), Some([e0, r0, pmb0])) if targets.hold == PmbHold::Free => {
            let model = Lackenby::of(&cells, &flotation, &datums, pmb, p.x_range)?;
            let mode = Mode::new(
                Kind::Pmb,
                Some([e0, r0]),
                pmb0,
                length,
                [vec![], vec![]],
                0.0,
            );
            (mode, model.jacobian(e0, r0, target_volume, lpp))
        }
        _ => {
            let x_mid = before.max_section_x;
            let pmb = p.pmb.as_ref().map(|m| [m.aft, m.fwd]);
            let (entrance, run) = end_faces(network, &form, options.draft, x_mid, pmb, tolerance);
            let missing = match (entrance.is_empty(), run.is_empty()) {
                (true, _) => Some("entrance"),
                (_, true) => Some("run"),
                _ => None,
            };
            if let Some(end) = missing {
                return Err(FormError::NotMeasurable {
                    parameter: "hydrostatic transformation",
                    reason: format!(
                        "no form face of the {end} reaches below the waterline at {} m to bulge{}; \
                         a station with the role 'midship' splits the hull into entrance and run",
                        options.draft,
                        match &p.no_pmb_reason {
                            Some(why) => format!(" (and no parallel middle body: {why})"),
                            None => String::new(),
                        }
                    ),
                });
            }
            let max = MAX_BULGE_FRACTION * 0.5 * p.breadth;
            let kind = match (targets.hold, lengths.is_some()) {
                (PmbHold::Length, true) => Kind::ShiftAndBulge,
                (PmbHold::Position, true) => Kind::LengthAndBulge,
                _ => Kind::Bulge,
            };
            let (ends, pmb0) = match lengths {
                Some([e0, r0, pmb0]) => (Some([e0, r0]), pmb0),
                None => (None, 0.0),
            };
            let mode = Mode::new(kind, ends, pmb0, length, [entrance, run], max);
            // The Jacobian by differences, two hulls per unknown (a step of h and of 2h, fuller
            // or finer as the volume must go): the first bulge already re-attaches the curves
            // inside the face, which inserts knots and so re-parameterises them as Blender
            // holds them, a jump in ∇ (0.1 % on the frigate) that the slope between two steps
            // leaves out. The iteration starts from the best of these hulls.
            let sign = if miss(&before)[0] < 0.0 { 1.0 } else { -1.0 };
            let mut jac = [[0.0; 2]; 2];
            for k in 0..2 {
                let mut h = sign * BULGE_DIFFERENCE * max;
                let mut col = None;
                let mut failed = None;
                for _ in 0..=MAX_HALVINGS {
                    if evaluations + 2 > MAX_EVALUATIONS {
                        break;
                    }
                    let at = |s: f64| {
                        let mut x = [0.0; 2];
                        x[k] = s;
                        x
                    };
                    evaluations += 1;
                    let trial = evaluate(at(h), &mode).and_then(|a| {
                        evaluations += 1;
                        Ok((a, evaluate(at(2.0 * h), &mode)?))
                    });
                    match trial {
                        Ok((a, b)) => {
                            let (fa, fb) = (miss(&a.hydro), miss(&b.hydro));
                            col = Some([(fb[0] - fa[0]) / h, (fb[1] - fa[1]) / h]);
                            for (x, ev, f) in [(at(h), a, fa), (at(2.0 * h), b, fb)] {
                                explored.add(&ev.hydro);
                                if start.as_ref().is_none_or(
                                    |s: &(Evaluated, [f64; 2], [f64; 2])| norm(f) < norm(s.1),
                                ) {
                                    start = Some((ev, f, x));
                                }
                            }
                            break;
                        }
                        Err(why) => {
                            h *= 0.5;
                            failed = Some(why);
                        }
                    }
                }
                let Some(col) = col else {
                    // Not even the smallest trial bulge passes: the original is the closest.
                    stuck = Some(format!(
                        "no bulge of the {} passes the shape checks: {}",
                        ["entrance", "run"][k],
                        failed.unwrap_or_default()
                    ));
                    break;
                };
                jac[0][k] = col[0];
                jac[1][k] = col[1];
            }
            (mode, jac)
        }
    };

    let original = (
        Evaluated {
            network: network.clone(),
            hydro: before,
        },
        miss(&before),
        mode.start(),
    );
    let (mut x, mut f) = start
        .as_ref()
        .map_or((original.2, original.1), |s| (s.2, s.1));
    let mut best = match start {
        Some(s) if norm(s.1) < norm(original.1) => s,
        _ => original,
    };
    let mut blocked: Option<String> = None;
    // A step that met a failing shape check bounds the next steps (a trust radius).
    let mut radius = f64::INFINITY;
    let min_radius = 1e-4 * mode.scale();
    let stop = loop {
        if met(f) {
            break Stop::Converged;
        }
        if let Some(why) = stuck.take() {
            break Stop::OutOfRange { limit: why };
        }
        if evaluations >= MAX_EVALUATIONS {
            break Stop::EvaluationsSpent;
        }
        let out_of_range = |blocked: &Option<String>, why: &str| Stop::OutOfRange {
            limit: blocked.clone().unwrap_or_else(|| why.into()),
        };
        let Some((mut dx, limit)) = limited_step(&mode, x, newton_step(&jac, f), &jac, f) else {
            break out_of_range(&blocked, "no step reduces the misses");
        };
        let limit_hit = limit.is_some();
        if limit_hit {
            blocked = limit;
        }
        let len = norm(dx);
        if len > radius {
            dx = [dx[0] * radius / len, dx[1] * radius / len];
        }
        let mut accepted = None;
        for _ in 0..=MAX_HALVINGS {
            if evaluations >= MAX_EVALUATIONS {
                break;
            }
            let trial = [x[0] + dx[0], x[1] + dx[1]];
            evaluations += 1;
            match evaluate(trial, &mode) {
                Ok(ev) => {
                    explored.add(&ev.hydro);
                    accepted = Some((trial, ev));
                    break;
                }
                Err(why) => {
                    blocked = Some(why);
                    dx = [0.5 * dx[0], 0.5 * dx[1]];
                    radius = norm(dx);
                }
            }
        }
        let Some((trial, ev)) = accepted else {
            break out_of_range(&blocked, "a shape check failed");
        };
        if radius < min_radius {
            break out_of_range(&blocked, "a shape check failed");
        }
        let nf = miss(&ev.hydro);
        // Broyden's update: J += ((Δf − J Δx) Δxᵀ) / (Δxᵀ Δx).
        let d = [trial[0] - x[0], trial[1] - x[1]];
        let dd = d[0] * d[0] + d[1] * d[1];
        for (i, row) in jac.iter_mut().enumerate() {
            let u = (nf[i] - f[i] - (row[0] * d[0] + row[1] * d[1])) / dd;
            row[0] += u * d[0];
            row[1] += u * d[1];
        }
        // Less than 2 % off the misses at a limit (a step cut short by one, or a shape check
        // that failed before): the limit holds the hull back.
        let stalled = norm(nf) > (1.0 - STALL_REDUCTION) * norm(f);
        (x, f) = (trial, nf);
        if norm(nf) < norm(best.1) {
            best = (ev, nf, trial);
        }
        if stalled && (limit_hit || radius.is_finite()) {
            break out_of_range(&blocked, "no step reduces the misses");
        }
    };
    let (best, _, best_x) = best;
    let after = best.hydro;
    let after_lengths = pmb_lengths(&form_topology(&best.network, &form_options)?);
    let pair = |k: usize| lengths.zip(after_lengths).map(|(a, b)| [a[k], b[k]]);
    let mode_name = match mode.kind {
        Kind::Pmb => "pmb",
        Kind::Bulge => "bulge",
        Kind::ShiftAndBulge => "pmb_shift+bulge",
        Kind::LengthAndBulge => "pmb_length+bulge",
    };
    let bulge = (mode.kind != Kind::Pmb).then(|| (mode.bulges(best_x), mode.faces.clone()));
    Ok(HydroTransformed {
        network: best.network,
        before,
        after,
        target,
        target_volume,
        target_lcb,
        mode: mode_name,
        entrance_length: pair(0),
        run_length: pair(1),
        pmb_length: pair(2),
        bulge,
        evaluations,
        stop,
        explored,
        datums,
    })
}

/// The volume figure and value, and the LCB, that `targets` ask for (the original's `before`
/// where not given).
fn target_figures(
    targets: HydroTargets,
    before: &Hydrostatics,
    density: f64,
) -> Result<((&'static str, f64), f64), FormError> {
    let figure = match targets.volume {
        None => ("volume", before.volume),
        Some(t) => {
            let (value, what) = match t {
                VolumeTarget::Volume(v) => (v, "volume"),
                VolumeTarget::Displacement(d) => (d, "displacement"),
                VolumeTarget::Cb(c) => (c, "cb"),
                VolumeTarget::Cp(c) => (c, "cp"),
            };
            if !(value.is_finite() && value > 0.0) {
                return Err(FormError::BadTarget {
                    parameter: what,
                    value,
                    reason: "a target must be a finite positive number".into(),
                });
            }
            match t {
                VolumeTarget::Displacement(d) => ("volume", d / density),
                _ => (what, value),
            }
        }
    };
    let lcb = match targets.lcb {
        None => before.lcb,
        Some(x) if x.is_finite() => x,
        Some(x) => {
            return Err(FormError::BadTarget {
                parameter: "lcb",
                value: x,
                reason: "the LCB target must be a finite number".into(),
            })
        }
    };
    Ok((figure, lcb))
}

/// How far `h` misses the targets, scaled: the volume as a fraction of `volume`, the LCB as a
/// fraction of `lpp`.
fn scaled_misses(h: &Hydrostatics, volume: f64, lcb: f64, lpp: f64) -> [f64; 2] {
    [(h.volume - volume) / volume, (h.lcb - lcb) / lpp]
}

fn norm(f: [f64; 2]) -> f64 {
    (f[0] * f[0] + f[1] * f[1]).sqrt()
}

/// The Newton step `−J⁻¹ f`, or `None` for a singular `J`.
fn newton_step(jac: &[[f64; 2]; 2], f: [f64; 2]) -> Option<[f64; 2]> {
    let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
    let scale = jac.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if det.abs() <= 1e-12 * scale * scale || !det.is_finite() {
        return None;
    }
    Some([
        -(jac[1][1] * f[0] - jac[0][1] * f[1]) / det,
        -(jac[0][0] * f[1] - jac[1][0] * f[0]) / det,
    ])
}

/// The step from `x`: the Newton step `newton` cut at the mode's limits; on a limit already,
/// the least-squares step along it (the other unknown free). `None` when no step is left.
fn limited_step(
    mode: &Mode,
    x: [f64; 2],
    newton: Option<[f64; 2]>,
    jac: &[[f64; 2]; 2],
    f: [f64; 2],
) -> Option<([f64; 2], Option<String>)> {
    let d = newton?;
    let (t, which) = mode.room(x, d);
    if t > 1e-9 {
        return Some(([t * d[0], t * d[1]], which.map(str::to_owned)));
    }
    let along = mode.along(which.unwrap_or(""));
    let jd = [
        jac[0][0] * along[0] + jac[0][1] * along[1],
        jac[1][0] * along[0] + jac[1][1] * along[1],
    ];
    let jj = jd[0] * jd[0] + jd[1] * jd[1];
    if jj <= 0.0 {
        return None;
    }
    let s = -(jd[0] * f[0] + jd[1] * f[1]) / jj;
    let d = [s * along[0], s * along[1]];
    let (t, other) = mode.room(x, d);
    (t > 1e-9).then(|| ([t * d[0], t * d[1]], other.or(which).map(str::to_owned)))
}
