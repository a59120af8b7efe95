//! The hull's patches as B-spline faces for CAD: every shared edge fitted once, every patch
//! side joined from its edges' curves, every quad of every patch fitted inside its sides.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec2;
use rayon::prelude::*;

use super::bspline::{join, sub_curve, BsplineSurface};
use super::error::{ExportError, UnfittedFace, UnfittedFaces};
use super::fit::{fit_curve, fit_surface, FitFailed, QuadBoundary};
use super::quads::{quads, side_midpoint, Quad, QuadSide};
use crate::curve::NurbsCurve;
use crate::hull::{HullSurface, LayoutSegment, WarningKind};
use crate::patch::Patch;

/// The largest deviation (m) of an exported face from batten's surface by default: 0.1 mm,
/// the model tolerance (a yard's CAD works to it; the faces of neighbouring patches then meet
/// well within it).
pub const DEFAULT_EXPORT_TOLERANCE: f64 = 1e-4;

/// Share of the export tolerance a boundary curve (a shared edge or an N-sided patch's spoke)
/// may deviate from the surface: the rest is the face's interior, so a face whose boundary is
/// this close stays within the whole tolerance.
pub const BOUNDARY_SHARE: f64 = 0.25;

/// Share of the export tolerance a face may deviate at its check samples: the other half is the
/// margin for the points between them (a reader's denser check, OpenCASCADE's projection).
pub const FACE_SHARE: f64 = 0.5;

/// What [`cad_surface`] needs besides the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExportOptions {
    /// The largest deviation (m) of a face from batten's surface.
    pub tolerance: f64,
    /// Export a surface whose build found holes (what exists is written).
    pub allow_holes: bool,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            tolerance: DEFAULT_EXPORT_TOLERANCE,
            allow_holes: false,
        }
    }
}

/// One exported face: a bicubic B-spline piece of one patch, its normal `S_u × S_v` pointing
/// out of the hull.
#[derive(Clone, Debug, PartialEq)]
pub struct CadFace {
    /// Index of its patch in [`HullSurface::patches`].
    pub patch: usize,
    /// Its patch's face in the topology.
    pub face: usize,
    /// Which quad of the patch it is (0 for a 4-sided patch; `i` at corner `i` of an N-sided
    /// one).
    pub quad: usize,
    /// The surface.
    pub surface: BsplineSurface,
    /// Its largest distance from the patch at the check samples (m): from each sample point of
    /// the patch to the face (see the `fit` module's `deviation_at`).
    pub deviation: f64,
}

/// The hull surface as B-spline faces (see [`cad_surface`]).
#[derive(Clone, Debug, PartialEq)]
pub struct CadSurface {
    /// The faces, patch by patch.
    pub faces: Vec<CadFace>,
    /// The tolerance they were fitted to (m).
    pub tolerance: f64,
    /// The largest deviation of any face (m).
    pub max_deviation: f64,
    /// Number of patches exported.
    pub patches: usize,
}

/// The warnings of a build that mean the surface has a hole: free edges off its boundary, a
/// face not patched or dropped, curves that nearly meet.
fn hole_messages(surface: &HullSurface) -> Vec<String> {
    surface
        .report
        .warnings
        .iter()
        .filter(|w| {
            matches!(
                w.kind,
                WarningKind::Hole
                    | WarningKind::FaceNotPatched
                    | WarningKind::NonFiniteSurface
                    | WarningKind::Network("near_miss")
            )
        })
        .map(|w| w.message.clone())
        .collect()
}

/// The first use of every topology edge: (patch, side, segment, forward).
fn edge_owners(surface: &HullSurface) -> Vec<Option<(usize, usize, usize, bool)>> {
    let edges = surface
        .layouts
        .iter()
        .flatten()
        .flatten()
        .map(|s| s.edge + 1)
        .max()
        .unwrap_or(0);
    let mut owner = vec![None; edges];
    for (p, layout) in surface.layouts.iter().enumerate() {
        for (si, side) in layout.iter().enumerate() {
            for (k, &LayoutSegment { edge, forward }) in side.iter().enumerate() {
                owner[edge].get_or_insert((p, si, k, forward));
            }
        }
    }
    owner
}

/// The edge's curve on `[0, 1]` (the segments' own parameter, from the edge's `t0` end to its
/// `t1` end), fitted once from the side of its first patch.
fn fit_edge(
    patches: &[Patch],
    (p, side, seg, forward): (usize, usize, usize, bool),
    tol: f64,
) -> Result<NurbsCurve, FitFailed> {
    let patch = &patches[p];
    let f = |lam: f64| {
        let local = if forward { lam } else { 1.0 - lam };
        patch.side_point(side, patch.segment_side_parameter(side, seg, local))
    };
    fit_curve(f, &[], tol).map(|(c, _)| c)
}

/// The side's curve on its side parameter `[0, 1]`: its edges' curves joined, each placed on
/// its segment's interval and turned to run along the side; else the deviation an edge's fit
/// reached (infinite where the curves could not be joined).
fn side_curve(
    patch: &Patch,
    side: usize,
    layout: &[LayoutSegment],
    edges: &[Option<Fitted<NurbsCurve>>],
) -> Fitted<NurbsCurve> {
    let mut curves = Vec::with_capacity(layout.len());
    let mut breaks = vec![0.0];
    for (k, s) in layout.iter().enumerate() {
        let c = edges[s.edge]
            .as_ref()
            .ok_or(FitFailed::NOTHING)?
            .as_ref()
            .map_err(|&e| e)?;
        curves.push(if s.forward { c.clone() } else { c.reversed() });
        breaks.push(if k + 1 == layout.len() {
            1.0
        } else {
            patch.segment_side_parameter(side, k, 1.0)
        });
    }
    join(&curves, &breaks).ok_or(FitFailed::NOTHING)
}

/// The spokes of an N-sided patch: from the fitted side's midpoint to the centre, through the
/// patch along the straight domain line between them.
fn spokes(patch: &Patch, sides: &[NurbsCurve], tol: f64) -> Result<Vec<NurbsCurve>, FitFailed> {
    let domain = patch.domain();
    if domain.sides() == 4 {
        return Ok(Vec::new());
    }
    let centre = DVec2::from(domain.centre());
    (0..domain.sides())
        .map(|i| {
            let mid = side_midpoint(domain, i);
            let start = sides[i].point(0.5);
            let f = |t: f64| {
                if t <= 0.0 {
                    start
                } else {
                    patch.eval_v(mid.lerp(centre, t))
                }
            };
            fit_curve(f, &[], tol).map(|(c, _)| c)
        })
        .collect()
}

/// The boundary curves of `quad` from its patch's side curves and spokes.
fn quad_boundary(quad: &Quad, sides: &[NurbsCurve], spokes: &[NurbsCurve]) -> Option<QuadBoundary> {
    let get = |s: QuadSide| match s {
        QuadSide::Patch { side, from, to } => sub_curve(&sides[side], from, to),
        QuadSide::Spoke(i) => Some(spokes[i].clone()),
    };
    Some(QuadBoundary {
        bottom: get(quad.sides[0])?,
        right: get(quad.sides[1])?,
        top: get(quad.sides[2])?,
        left: get(quad.sides[3])?,
    })
}

/// A fitted curve or face, or what its fits reached ([`FitFailed::NOTHING`] where there was
/// nothing to fit, e.g. a boundary curve f64 could not represent).
type Fitted<T> = Result<T, FitFailed>;

/// What one patch needs before its quads are fitted: each quad with its boundary curves (from
/// the patch's side curves and spokes).
type QuadBoundaries = Vec<(Quad, QuadBoundary)>;

/// Approximate each patch of `surface` by bicubic B-spline faces within `options.tolerance`
/// (a 4-sided patch by one face, an N-sided one by N quads, see the `quads` module), so that
/// neighbouring faces meet on the same curve.
///
/// 1. Every topology edge is fitted once, as a cubic B-spline through its end nodes, from the
///    side of the first patch that uses it, to [`BOUNDARY_SHARE`] of the tolerance.
/// 2. Every patch side is its edges' curves joined (C0 at the T-joints), so the two patches of
///    an edge hold the same curve there, whatever the rest of their sides.
/// 3. Every quad is fitted inside its four side curves ([`fit_surface`]) to [`FACE_SHARE`] of
///    the tolerance (the whole tolerance where refining cannot get there, e.g. at a repaired
///    degenerate corner), measured as the distance from the patch's points to the face (its
///    parameters may run otherwise than the patch's; it may not fold): its boundary rows are
///    the side curves' control points after exact knot insertion, and neighbours therefore
///    meet exactly (to rounding) on the shared curve.
///
/// Edges, patches and quads are fitted in parallel. Errors: holes in the build (unless
/// `allow_holes`), a tolerance that is not a positive finite number, patches that could not
/// be fitted within [`MAX_SURFACE_SPANS`](super::fit::MAX_SURFACE_SPANS) spans a side or
/// [`MAX_SURFACE_CELLS`](super::fit::MAX_SURFACE_CELLS) cells or whose fits refining no
/// longer brought closer, with what each fit reached:
/// every patch whose boundary curves could not be fitted (a patch whose shared edge could not
/// be fitted fails with it; no face is fitted then), else the faces that failed before the
/// first failing face stopped the rest.
pub fn cad_surface(
    surface: &HullSurface,
    options: &ExportOptions,
) -> Result<CadSurface, ExportError> {
    let cad = cad_surface_with(surface, options, &|_, _| true)?;
    Ok(cad.expect("a progress callback that always goes on never stops the export"))
}

/// [`cad_surface`], calling `face_done(faces fitted, faces)` each time a face (a quad of a
/// patch) has been fitted, from whichever worker fitted it (so the count may reach the callback
/// out of order); when it returns `false` no further face is started and the export gives
/// `Ok(None)`. So a front end shows the fitting's progress and lets the designer cancel it.
///
/// Errors: as [`cad_surface`].
pub fn cad_surface_with(
    surface: &HullSurface,
    options: &ExportOptions,
    face_done: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Result<Option<CadSurface>, ExportError> {
    let tol = options.tolerance;
    if !(tol.is_finite() && tol > 0.0) {
        return Err(ExportError::Tolerance(tol));
    }
    let holes = hole_messages(surface);
    if !holes.is_empty() && !options.allow_holes {
        return Err(ExportError::Holes(holes.join("; ")));
    }
    let patches = &surface.patches;
    let boundary_tol = BOUNDARY_SHARE * tol;
    let edges: Vec<Option<Fitted<NurbsCurve>>> = edge_owners(surface)
        .into_par_iter()
        .map(|owner| owner.map(|o| fit_edge(patches, o, boundary_tol)))
        .collect();
    let boundaries: Vec<Fitted<QuadBoundaries>> = patches
        .par_iter()
        .zip(&surface.layouts)
        .map(|(patch, layout)| {
            let sides = (0..patch.sides())
                .map(|si| side_curve(patch, si, &layout[si], &edges))
                .collect::<Fitted<Vec<_>>>()?;
            let spokes = spokes(patch, &sides, boundary_tol)?;
            quads(patch.domain())
                .into_iter()
                .map(|q| {
                    let boundary = quad_boundary(&q, &sides, &spokes).ok_or(FitFailed::NOTHING)?;
                    Ok((q, boundary))
                })
                .collect()
        })
        .collect();
    let jobs: Vec<(usize, usize, &Quad, &QuadBoundary)> = boundaries
        .iter()
        .enumerate()
        .filter_map(|(p, b)| b.as_ref().ok().map(|b| (p, b)))
        .flat_map(|(p, b)| b.iter().enumerate().map(move |(k, (q, b))| (p, k, q, b)))
        .collect();
    // A face that cannot be fitted refines to its most cells (seconds each): once one has
    // failed (or a patch's boundary curves already have), the quads not yet started are left
    // and those being fitted stop, so a failing export ends soon; so do they once the caller
    // asked to stop. A stopped fit is neither a face nor a failure.
    let failed = AtomicBool::new(boundaries.iter().any(Result::is_err));
    let stopped = AtomicBool::new(false);
    let go_on = || !failed.load(Ordering::Relaxed) && !stopped.load(Ordering::Relaxed);
    let done = AtomicUsize::new(0);
    let total = jobs.len();
    let fitted: Vec<(usize, Fitted<CadFace>)> = jobs
        .into_par_iter()
        .filter(|_| go_on())
        .filter_map(|(p, k, quad, boundary)| {
            let fit = || -> Fitted<Option<CadFace>> {
                let patch = &patches[p];
                let target = |u: f64, v: f64| patch.eval_v(quad.domain_point(u, v));
                let Some((fitted, deviation)) =
                    fit_surface(target, boundary, FACE_SHARE * tol, tol, &go_on)?
                else {
                    return Ok(None);
                };
                Ok(Some(CadFace {
                    patch: p,
                    face: surface.patch_faces[p],
                    quad: k,
                    surface: if surface.patches_outward {
                        fitted
                    } else {
                        fitted.reversed_u()
                    },
                    deviation,
                }))
            };
            let result = match fit() {
                Ok(None) => return None,
                Ok(Some(face)) => Ok(face),
                Err(e) => {
                    failed.store(true, Ordering::Relaxed);
                    Err(e)
                }
            };
            if !face_done(done.fetch_add(1, Ordering::Relaxed) + 1, total) {
                stopped.store(true, Ordering::Relaxed);
            }
            Some((p, result))
        })
        .collect();
    if stopped.load(Ordering::Relaxed) {
        return Ok(None);
    }
    let mut unfitted: Vec<Option<FitFailed>> = boundaries
        .iter()
        .map(|b| b.as_ref().err().copied())
        .collect();
    let mut faces = Vec::with_capacity(fitted.len());
    for (p, f) in fitted {
        match f {
            Ok(face) => faces.push(face),
            Err(e) => unfitted[p] = Some(unfitted[p].map_or(e, |u| u.worse(e))),
        }
    }
    let unfitted: Vec<UnfittedFace> = unfitted
        .into_iter()
        .enumerate()
        .filter_map(|(p, e)| {
            e.map(|e| UnfittedFace {
                face: surface.patch_faces[p],
                deviation: e.deviation,
                turned: e.turned,
            })
        })
        .collect();
    if !unfitted.is_empty() {
        return Err(ExportError::NotConverged {
            faces: UnfittedFaces(unfitted),
            patches: patches.len(),
            tolerance: tol,
        });
    }
    let max_deviation = faces.iter().map(|f| f.deviation).fold(0.0, f64::max);
    Ok(Some(CadSurface {
        faces,
        tolerance: tol,
        max_deviation,
        patches: patches.len(),
    }))
}
