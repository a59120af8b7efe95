//! Whether a fold the mesh shows is the surface's own ([`surface_turn`]).
//!
//! The fold check reads the angles between neighbouring mesh polygons ([`super::folds`]). A
//! mesh follows a smooth but tight turn only as well as its polygons are small, and a side
//! that doubles back within one polygon not at all, so its polygons can meet at angles the
//! surface does not have. KCS's stern counter has a ridge of about 2.5 cm radius beside the
//! 27 mm step of wl_z9.00 (a seam of the surfaces its offsets were cut from), across which the
//! polygons of its face meet at 28–31° whatever the resolution (the face is refined to 32
//! intervals a side at most); widened by 5 %, at 30.2°. The 3.5 cm hook of wl_z0.30 where it
//! turns into the stem makes polygons meet at up to 115° where the surface turns by 7°.
//!
//! So the surface is meshed afresh around the place, ever finer: a fold — a sheet turned over,
//! a crease — keeps its angle however fine the mesh; a turn the mesh was too coarse for does
//! not (the counter's ridge: 22.8°, 17.3°, 12.1° at 16, 32, 64 cells across the place).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use crate::patch::Patch;

/// Samples per axis over the box of a patch's domain in the search for the window around a
/// place ([`window`]).
const SEEK_SAMPLES: usize = 48;

/// How many times [`window`] zooms in on the nearest sample when too few lie in the ball.
const SEEK_ZOOMS: usize = 6;

/// Samples per axis over the window at the coarsest level of [`surface_turn`]; each level
/// doubles them, up to [`PROBE_LAST`].
const PROBE_FIRST: usize = 16;

/// Samples per axis over the window at the finest level: with the ball's radius 1.5 times the
/// polygons' reach, cells some fortieth of a polygon across.
const PROBE_LAST: usize = 128;

/// The domain box `[lo, hi]` of `patch` around the samples within `radius` of `at`, one
/// sample spacing wider: None when the patch comes nowhere near `at` (no sample within
/// `radius` after zooming in on the nearest).
fn window(patch: &Patch, at: DVec3, radius: f64) -> Option<(DVec2, DVec2)> {
    let domain = patch.domain();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for v in domain.vertices() {
        lo = lo.min(DVec2::from(v));
        hi = hi.max(DVec2::from(v));
    }
    let (box_lo, box_hi) = (lo, hi);
    let mut n = SEEK_SAMPLES;
    for _ in 0..=SEEK_ZOOMS {
        let step = (hi - lo) / n as f64;
        let mut nearest = (f64::INFINITY, lo);
        let (mut in_lo, mut in_hi, mut count) = (hi, lo, 0usize);
        for i in 0..=n {
            for j in 0..=n {
                let x = lo + step * DVec2::new(i as f64, j as f64);
                if !domain.contains(x.to_array()) {
                    continue;
                }
                let d = patch.eval_v(x).distance(at);
                if d < nearest.0 {
                    nearest = (d, x);
                }
                if d <= radius {
                    in_lo = in_lo.min(x);
                    in_hi = in_hi.max(x);
                    count += 1;
                }
            }
        }
        if !nearest.0.is_finite() {
            return None;
        }
        if count >= 4 {
            return Some(((in_lo - step).max(box_lo), (in_hi + step).min(box_hi)));
        }
        // Too few samples in the ball: look again at ±2 spacings around the nearest.
        lo = (nearest.1 - 2.0 * step).max(box_lo);
        hi = (nearest.1 + 2.0 * step).min(box_hi);
        n = 16;
    }
    None
}

/// One patch's samples at one level: an `(m + 1)²` grid over its window, and the normal of
/// every cell of it whose corners are all inside the domain and the ball (the cell's own
/// polygon normal: the mesh of the surface at that spacing), with its centre.
struct Samples {
    m: usize,
    cells: Vec<Option<(DVec3, DVec3)>>,
}

impl Samples {
    fn new(patch: &Patch, (lo, hi): (DVec2, DVec2), m: usize, at: DVec3, radius: f64) -> Samples {
        let step = (hi - lo) / m as f64;
        let points: Vec<Option<DVec3>> = (0..=m)
            .flat_map(|i| (0..=m).map(move |j| (i, j)))
            .map(|(i, j)| {
                let x = (lo + step * DVec2::new(i as f64, j as f64)).to_array();
                patch
                    .domain()
                    .contains(x)
                    .then(|| patch.eval(x))
                    .filter(|p| p.distance(at) <= radius)
            })
            .collect();
        let cells = (0..m)
            .flat_map(|i| (0..m).map(move |j| (i, j)))
            .map(|(i, j)| {
                let corner = |a: usize, b: usize| points[a * (m + 1) + b];
                let [a, b, c, d] = [
                    corner(i, j)?,
                    corner(i + 1, j)?,
                    corner(i + 1, j + 1)?,
                    corner(i, j + 1)?,
                ];
                let n = (c - a).cross(d - b).normalize_or_zero();
                (n != DVec3::ZERO).then_some((0.25 * (a + b + c + d), n))
            })
            .collect();
        Samples { m, cells }
    }

    fn cell(&self, i: usize, j: usize) -> Option<(DVec3, DVec3)> {
        self.cells[i * self.m + j]
    }

    /// The largest angle (degrees) between the normals of neighbouring cells, and the
    /// distances between their centres.
    fn turn(&self) -> (f64, Vec<f64>) {
        let (mut worst, mut spacings) = (0.0f64, Vec::new());
        for i in 0..self.m {
            for j in 0..self.m {
                let Some((p, n)) = self.cell(i, j) else {
                    continue;
                };
                for (a, b) in [(i + 1, j), (i, j + 1)] {
                    if a >= self.m || b >= self.m {
                        continue;
                    }
                    if let Some((q, k)) = self.cell(a, b) {
                        worst = worst.max(n.angle_between(k).to_degrees());
                        spacings.push(p.distance(q));
                    }
                }
            }
        }
        (worst, spacings)
    }
}

/// The largest angle (degrees) between the normals of a cell of `a` and a cell of `b` whose
/// centres lie within `near` of each other (found through a hash of `b`'s cells in cubes of
/// side `near`).
fn turn_across(a: &Samples, b: &Samples, near: f64) -> f64 {
    if near <= 0.0 || !near.is_finite() {
        return 0.0;
    }
    let key = |p: DVec3| (p / near).floor().as_i64vec3().to_array();
    let mut cubes: HashMap<[i64; 3], Vec<(DVec3, DVec3)>> = HashMap::new();
    for &(q, k) in b.cells.iter().flatten() {
        cubes.entry(key(q)).or_default().push((q, k));
    }
    let mut worst = 0.0f64;
    for &(p, n) in a.cells.iter().flatten() {
        let [x, y, z] = key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    // Wrapping: far out (a hull of 1e300 m) the cubes' keys saturate, and a
                    // key wrapped round finds no cube or one whose cells the distance refuses.
                    let near_key = [x.wrapping_add(dx), y.wrapping_add(dy), z.wrapping_add(dz)];
                    for (q, k) in cubes.get(&near_key).into_iter().flatten() {
                        if p.distance(*q) <= near {
                            worst = worst.max(n.angle_between(*k).to_degrees());
                        }
                    }
                }
            }
        }
    }
    worst
}

/// The median of `values` (0 for none).
fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    *values.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// How far the surface of `patches` (one, or the two faces of an edge) turns within `radius`
/// of `at`, in degrees: the largest angle between the normals of neighbouring cells of a grid
/// over one patch's domain, or of cells of the two patches whose centres lie as close as
/// neighbours' do, at the finest level meshed. The levels grow from [`PROBE_FIRST`] to
/// [`PROBE_LAST`] cells across the window, and stop early once the angle is at most half of
/// `fold_angle` (a smooth turn only lessens with finer cells): a turn the surface makes
/// smoothly falls under `fold_angle` once the cells are small enough; a fold stays over it.
pub(crate) fn surface_turn(patches: &[&Patch], at: DVec3, radius: f64, fold_angle: f64) -> f64 {
    let windows: Vec<Option<(DVec2, DVec2)>> =
        patches.iter().map(|p| window(p, at, radius)).collect();
    let mut m = PROBE_FIRST;
    let mut worst = 0.0;
    while m <= PROBE_LAST {
        let samples: Vec<Samples> = patches
            .iter()
            .zip(&windows)
            .filter_map(|(p, w)| w.map(|w| Samples::new(p, w, m, at, radius)))
            .collect();
        let turns: Vec<(f64, Vec<f64>)> = samples.iter().map(Samples::turn).collect();
        worst = turns.iter().map(|t| t.0).fold(0.0, f64::max);
        if let [a, b] = &samples[..] {
            let near = 1.5
                * turns
                    .iter()
                    .map(|t| median(t.1.clone()))
                    .fold(0.0, f64::max);
            worst = worst.max(turn_across(a, b, near));
        }
        if worst <= 0.5 * fold_angle {
            break;
        }
        m *= 2;
    }
    worst
}
