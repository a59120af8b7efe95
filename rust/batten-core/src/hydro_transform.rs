//! Hydrostatic transformations (seed 002 §8.1 and §8.3): a hull with a parallel middle body
//! taken to a target displaced volume and LCB by moving the ends of its parallel middle body,
//! through the form topology (the ends, the deck and the midship section keep their shape).
//!
//! - **The model** is Lackenby's (1950), in its general case with a parallel middle body: each
//!   end of the hull (entrance, run) is stretched or squeezed along x between the PMB's end and
//!   the hull's end, so its sectional areas keep their values and move affinely. With `e`, `r`
//!   the entrance and run lengths, `V_E`, `V_R` their volumes and `M_E`, `M_R` their first
//!   moments about the bow and stern ends `X_E`, `X_R`, and `A_m` the PMB's section area:
//!   `∇(e, r) = A_m (X_E − e − X_R − r) + V_E e/e₀ + V_R r/r₀` and
//!   `∇·LCB = A_m (x_f² − x_a²)/2 + X_E V_E e/e₀ + M_E (e/e₀)² + X_R V_R r/r₀ + M_R (r/r₀)²`
//!   with `x_f = X_E − e`, `x_a = X_R + r`. Its Jacobian starts the iteration; it never
//!   decides the answer. (batten's PMB move keeps the flats and the deck where they are, so
//!   its ends do not squeeze affinely as Lackenby's do: on the test barge, whose flat of side
//!   runs far into the ends, the model puts ∂∇/∂e four times too high, and the first
//!   Broyden updates correct it.)
//! - **The iteration** runs on batten's hydrostatics of the transformed and rebuilt hull (each
//!   a *hull evaluation*: both PMB ends moved in one deformation of the original, the patches
//!   integrated on the live cells, about 1e-8 relative; the hull returned is measured again on
//!   the exact cells): quasi-Newton steps (Broyden's update of the model's
//!   Jacobian), kept inside the deformation's limits, until `|δ∇|/∇ ≤ 1e-5` and
//!   `|δLCB| ≤ 1e-5·Lpp` ([`VOLUME_TOLERANCE`], [`LCB_TOLERANCE`]).
//! - **The limits** (§8.3's bracket): the PMB keeps a length and both ends keep theirs
//!   ([`MIN_LENGTH_FRACTION`] of the hull's length each), and every hull evaluated must build
//!   with the faces and warnings of the original (a face that no longer patches, a fold or a
//!   gap is a shape check that fails: the step is halved back towards the last good hull).
//! - **Out of range**: the closest reachable hull (least squares on the scaled misses, on the
//!   limit that stopped it), how far the hulls evaluated went, and which limit it was.
//!
//! A target that is not given is held at the hull's present value.

use crate::error::Error;
use crate::form::{
    form_topology, parametric_moves, transform, FormError, FormOptions, FormTopology,
    ParallelMiddleBody, Plan, Target,
};
use crate::hull::{build_hull, HullOptions, HullSurface};
use crate::hydro::{
    default_datums, hydrostatics, sectional_areas, CellDensity, Datums, Flotation, Hydrostatics,
};
use crate::network::Network;

/// Converged when the volume misses by at most this fraction of the target volume.
pub const VOLUME_TOLERANCE: f64 = 1e-5;
/// Converged when the LCB misses by at most this fraction of Lpp.
pub const LCB_TOLERANCE: f64 = 1e-5;
/// Hull evaluations (transform, rebuild, hydrostatics) at most, the original's included.
pub const MAX_EVALUATIONS: usize = 16;
/// The PMB, the entrance and the run each keep at least this fraction of the hull's length.
pub const MIN_LENGTH_FRACTION: f64 = 0.02;
/// A step at a limit that takes less than this fraction off the (scaled) misses ends the
/// iteration: the targets are out of range and the best hull so far is the closest.
const STALL_REDUCTION: f64 = 0.02;
/// Intervals of the Simpson rule over each end for the model's volumes and moments.
const MODEL_INTERVALS: usize = 40;
/// Halvings of a step whose hull fails a shape check before the limit is taken as found.
const MAX_HALVINGS: usize = 5;

/// The volume target of a hydrostatic transformation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VolumeTarget {
    /// Displaced volume ∇ (m³, both sides).
    Volume(f64),
    /// Displacement Δ (t) at the options' density.
    Displacement(f64),
    /// Block coefficient on Lpp, Bwl and the draft (these do not change when the PMB's ends
    /// move, so ∇ follows Cb in proportion).
    Cb(f64),
    /// Prismatic coefficient on the midship section and Lpp (linked to Cb through Cm, which
    /// does not change either).
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
    /// The target volume and LCB the iteration aimed at.
    pub target_volume: f64,
    /// The target LCB.
    pub target_lcb: f64,
    /// Entrance and run lengths before and after (m).
    pub entrance_length: [f64; 2],
    /// Run lengths before and after (m).
    pub run_length: [f64; 2],
    /// PMB length before and after (m).
    pub pmb_length: [f64; 2],
    /// Hull evaluations spent (the original's included).
    pub evaluations: usize,
    /// Why it stopped.
    pub stop: Stop,
    /// The ∇ and LCB of the hulls evaluated.
    pub explored: Explored,
    /// The perpendiculars used.
    pub datums: Datums,
}

/// One evaluated hull: its network, hydrostatics on the live cells (about 1e-8 relative, far
/// inside the iteration's 1e-5), and its surface for the exact figures of the one returned
/// (`None` for the original, whose figures are exact already).
struct Evaluated {
    network: Network,
    hydro: Hydrostatics,
    surface: Option<HullSurface>,
}

/// The hull's ends and PMB as the model sees them (x from the form topology).
#[derive(Clone, Copy, Debug)]
struct Model {
    x_e: f64,
    x_r: f64,
    e0: f64,
    r0: f64,
    area: f64,
    v_e: f64,
    m_e: f64,
    v_r: f64,
    m_r: f64,
}

impl Model {
    /// Model ∇ and LCB at entrance length `e` and run length `r` (§ module docs).
    fn eval(&self, e: f64, r: f64) -> (f64, f64) {
        let (fe, fr) = (e / self.e0, r / self.r0);
        let (xf, xa) = (self.x_e - e, self.x_r + r);
        let v = self.area * (xf - xa) + self.v_e * fe + self.v_r * fr;
        let m = 0.5 * self.area * (xf * xf - xa * xa)
            + self.x_e * self.v_e * fe
            + self.m_e * fe * fe
            + self.x_r * self.v_r * fr
            + self.m_r * fr * fr;
        (v, m / v)
    }
}

/// Simpson's volume and first moment about `about` of the sectional areas over `[a, b]`.
fn end_integrals(
    surface: &crate::hydro::PatchHydroModel,
    flotation: &Flotation,
    datums: &Datums,
    a: f64,
    b: f64,
    about: f64,
) -> Result<(f64, f64), FormError> {
    let n = MODEL_INTERVALS;
    let xs: Vec<f64> = (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect();
    let areas = sectional_areas(surface, flotation, datums, &xs).map_err(Error::from)?;
    let h = (b - a) / n as f64;
    let (mut v, mut m) = (0.0, 0.0);
    for (k, (&x, &area)) in xs.iter().zip(&areas).enumerate() {
        let w = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        v += w * area;
        m += w * area * (x - about);
    }
    Ok((v * h / 3.0, m * h / 3.0))
}

/// What the PMB mode needs of the form topology: the PMB, the entrance and run lengths and the
/// hull's x extent.
fn pmb_of(form: &FormTopology) -> Result<(ParallelMiddleBody, f64, f64, [f64; 2]), FormError> {
    let p = &form.parameters;
    let (Some(pmb), Some(e), Some(r)) = (&p.pmb, p.entrance_length, p.run_length) else {
        return Err(FormError::NoParallelMiddleBody {
            parameter: "hydrostatic transformation",
            reason: p
                .no_pmb_reason
                .clone()
                .unwrap_or_else(|| "no entrance or run length".into()),
        });
    };
    Ok((pmb.clone(), e, r, p.x_range))
}

/// Take `network` to `targets` by moving the ends of its parallel middle body (module docs:
/// Lackenby's model, quasi-Newton on the exact hydrostatics, inside the deformation's limits).
///
/// Errors: the hull has no parallel middle body ([`FormError::NoParallelMiddleBody`]), a target
/// that is not a finite positive number (LCB: finite; [`FormError::BadTarget`]), the original
/// does not build or float at the draft ([`FormError::Network`]).
pub fn transform_hydrostatic(
    network: &Network,
    targets: HydroTargets,
    options: &HydroTransformOptions,
) -> Result<HydroTransformed, FormError> {
    let form_options = FormOptions {
        tolerance: options.hull.tolerance,
        draft: Some(options.draft),
    };
    let form = form_topology(network, &form_options)?;
    let (pmb, e0, r0, x_range) = pmb_of(&form)?;
    let pmb0 = pmb.length;
    let flotation = Flotation {
        draft: options.draft,
        trim: 0.0,
        heel_deg: 0.0,
        density: options.density,
    };
    let original = build_hull(network, &options.hull)?;
    let faces = original.report.faces;
    let warnings = original.report.warnings.len();
    let cells = original.hydro_model(CellDensity::DEFAULT);
    let datums = match options.datums {
        Some(d) => d,
        None => default_datums(&cells, options.draft, options.lpp).map_err(Error::from)?,
    };
    let before = hydrostatics(&cells, &flotation, &datums).map_err(Error::from)?;
    let lpp = datums.x_fp - datums.x_ap;

    let target_volume = match targets.volume {
        None => before.volume,
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
                VolumeTarget::Volume(v) => v,
                VolumeTarget::Displacement(d) => d / options.density,
                VolumeTarget::Cb(c) => before.volume * c / before.cb,
                VolumeTarget::Cp(c) => before.volume * c / before.cp,
            }
        }
    };
    let target_lcb = match targets.lcb {
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

    // The model, from the original's sectional areas.
    let (x_r, x_e) = (x_range[0], x_range[1]);
    let (v_e, m_e) = end_integrals(&cells, &flotation, &datums, pmb.fwd, x_e, x_e)?;
    let (v_r, m_r) = end_integrals(&cells, &flotation, &datums, x_r, pmb.aft, x_r)?;
    let area =
        sectional_areas(&cells, &flotation, &datums, &[pmb.position]).map_err(Error::from)?[0];
    let model = Model {
        x_e,
        x_r,
        e0,
        r0,
        area,
        v_e,
        m_e,
        v_r,
        m_r,
    };

    // The deformation's limits: e ≥ m, r ≥ m, PMB = e0 + r0 + pmb0 − e − r ≥ m.
    let min_len = MIN_LENGTH_FRACTION * (x_e - x_r);
    let total = e0 + r0 + pmb0;
    let limits = Limits { min_len, total };

    // Scaled misses: volume as a fraction of the target, LCB as a fraction of Lpp.
    let miss = |h: &Hydrostatics| -> [f64; 2] {
        [
            (h.volume - target_volume) / target_volume,
            (h.lcb - target_lcb) / lpp,
        ]
    };
    let mut explored = Explored::of(&before);
    let met = |f: [f64; 2]| f[0].abs() <= VOLUME_TOLERANCE && f[1].abs() <= LCB_TOLERANCE;

    // Model Jacobian of the scaled misses in (e, r), by central differences of the model.
    let mut jac = {
        let h = 1e-4 * (x_e - x_r);
        let col = |de: f64, dr: f64| {
            let (v1, l1) = model.eval(e0 + de, r0 + dr);
            let (v0, l0) = model.eval(e0 - de, r0 - dr);
            [
                (v1 - v0) / (2.0 * h) / target_volume,
                (l1 - l0) / (2.0 * h) / lpp,
            ]
        };
        let (ce, cr) = (col(h, 0.0), col(0.0, h));
        [[ce[0], cr[0]], [ce[1], cr[1]]]
    };

    let mut evaluations = 1;
    let mut x = [e0, r0];
    let mut f = miss(&before);
    let mut best = (
        Evaluated {
            network: network.clone(),
            hydro: before,
            surface: None,
        },
        f,
    );
    let mut blocked: Option<String> = None;
    // A step that met a failing shape check bounds the next steps (a trust radius, m).
    let mut radius = f64::INFINITY;
    let min_radius = 1e-4 * (x_e - x_r);
    let stop = loop {
        if met(f) {
            break Stop::Converged;
        }
        if evaluations >= MAX_EVALUATIONS {
            break Stop::EvaluationsSpent;
        }
        let out_of_range = |blocked: &Option<String>, why: &str| Stop::OutOfRange {
            limit: blocked.clone().unwrap_or_else(|| why.into()),
        };
        let Some((mut dx, limit)) = limits.step(x, newton_step(&jac, f), &jac, f) else {
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
            match evaluate(
                network, &form, trial, &flotation, &datums, options, faces, warnings,
            ) {
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
            best = (ev, nf);
        }
        if stalled && (limit_hit || radius.is_finite()) {
            break out_of_range(&blocked, "no step reduces the misses");
        }
    };
    let best = best.0;
    let after = match &best.surface {
        None => best.hydro,
        Some(hull) => hydrostatics(&hull.hydro_model(CellDensity::DEFAULT), &flotation, &datums)
            .map_err(Error::from)?,
    };
    explored.add(&after);
    let after_form = form_topology(&best.network, &form_options)?;
    let (pmb1, e1, r1, _) = pmb_of(&after_form)?;
    Ok(HydroTransformed {
        network: best.network,
        before,
        after,
        target_volume,
        target_lcb,
        entrance_length: [e0, e1],
        run_length: [r0, r1],
        pmb_length: [pmb0, pmb1.length],
        evaluations,
        stop,
        explored,
        datums,
    })
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

/// The deformation's limits on (entrance, run).
struct Limits {
    min_len: f64,
    total: f64,
}

impl Limits {
    /// How far `x` may go along `d` (a fraction in [0, 1]) and the limit met first.
    fn room(&self, x: [f64; 2], d: [f64; 2]) -> (f64, Option<&'static str>) {
        let mut t = 1.0f64;
        let mut which = None;
        let mut cap = |slack: f64, rate: f64, name: &'static str| {
            if rate < 0.0 && slack + rate * t < 0.0 {
                t = (slack / -rate).max(0.0);
                which = Some(name);
            }
        };
        cap(
            x[0] - self.min_len,
            d[0],
            "the entrance would be shorter than 2 % of the hull",
        );
        cap(
            x[1] - self.min_len,
            d[1],
            "the run would be shorter than 2 % of the hull",
        );
        cap(
            self.total - x[0] - x[1] - self.min_len,
            -(d[0] + d[1]),
            "the parallel middle body would be shorter than 2 % of the hull",
        );
        (t, which)
    }

    /// The step from `x`: the Newton step `newton` cut at the limits; on a limit already, the
    /// least-squares step along it (the other variable free). `None` when no step is left.
    fn step(
        &self,
        x: [f64; 2],
        newton: Option<[f64; 2]>,
        jac: &[[f64; 2]; 2],
        f: [f64; 2],
    ) -> Option<([f64; 2], Option<String>)> {
        let d = newton?;
        let (t, which) = self.room(x, d);
        if t > 1e-9 {
            return Some(([t * d[0], t * d[1]], which.map(str::to_owned)));
        }
        // On a limit: move along it, least squares on the misses.
        let along: [f64; 2] = match which {
            Some(w) if w.contains("parallel") => [1.0, -1.0],
            Some(w) if w.contains("entrance") => [0.0, 1.0],
            _ => [1.0, 0.0],
        };
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
        let (t, other) = self.room(x, d);
        (t > 1e-9).then(|| ([t * d[0], t * d[1]], other.or(which).map(str::to_owned)))
    }
}

/// Transform to entrance `x[0]` and run `x[1]`, rebuild and float: the hull, or why it fails
/// a shape check (the transformation refused, the hull not building with the original's
/// faces, or with more warnings than the original's).
#[allow(clippy::too_many_arguments)]
fn evaluate(
    network: &Network,
    form: &FormTopology,
    x: [f64; 2],
    flotation: &Flotation,
    datums: &Datums,
    options: &HydroTransformOptions,
    faces: usize,
    warnings: usize,
) -> Result<Evaluated, String> {
    // Both PMB ends in one deformation of the original (their moves touch different
    // sections), so the result does not depend on an order of steps.
    let mut moves = Vec::new();
    for target in [Target::EntranceLength(x[0]), Target::RunLength(x[1])] {
        match parametric_moves(network, form, target).map_err(|e| e.to_string())? {
            Plan::Moves(m) => moves.extend(m),
            Plan::TransverseScale(_) => return Err(format!("{} is no PMB move", target.name())),
        }
    }
    let second =
        transform(network, form, &moves, options.hull.tolerance).map_err(|e| e.to_string())?;
    let hull = build_hull(&second.network, &options.hull).map_err(|e| e.to_string())?;
    if hull.report.faces != faces {
        return Err(format!(
            "the hull would build {} faces instead of {faces}",
            hull.report.faces
        ));
    }
    if hull.report.warnings.len() > warnings {
        let new = hull
            .report
            .warnings
            .iter()
            .map(|w| w.message.clone())
            .next_back()
            .unwrap_or_default();
        return Err(format!("the hull would gain a warning ({new})"));
    }
    let cells = hull.hydro_model(CellDensity::LIVE);
    let hydro = hydrostatics(&cells, flotation, datums).map_err(|e| e.to_string())?;
    Ok(Evaluated {
        network: second.network,
        hydro,
        surface: Some(hull),
    })
}
