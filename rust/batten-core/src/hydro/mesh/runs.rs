//! Runs of consecutive triangles with their bounding boxes, so a plane skips the runs it cannot
//! touch: a station or waterline reads the few runs it crosses (a station finds them in an
//! index of the runs by slabs of `x`), the wet integrals skip the dry runs, and the wet part's
//! extent is found by bounding runs before reading any.
//!
//! Implementation note: the runs follow the mesh's own triangle order, which is spatially
//! coherent for a tessellated surface, a Blender mesh or an STL export (neighbours are stored
//! near each other); a mesh in random order still gives exact results, only without the
//! savings.

use glam::DVec3;
use rayon::prelude::*;

/// Triangles per run: small enough that a plane's runs hold few triangles it misses (a
/// column of a hull's grid is some hundreds), large enough that the boxes of a
/// million-triangle mesh (about 16,000) are read in a blink.
pub(super) const RUN: usize = 64;

/// Runs per slab of the station index: a station reads the runs of one slab.
const RUNS_PER_SLAB: usize = 4;

/// The bounding box (centre, half extent) of each run of [`RUN`] consecutive triangles, and
/// the runs by the slab of `x` their box overlaps (compressed rows: slab `s` holds
/// `by_slab[slab_starts[s]..slab_starts[s + 1]]`), so a station finds its runs at once.
#[derive(Clone, Debug)]
pub(super) struct Runs {
    boxes: Vec<(DVec3, DVec3)>,
    x0: f64,
    slabs_per_metre: f64,
    slab_starts: Vec<usize>,
    by_slab: Vec<u32>,
}

impl Runs {
    /// The runs of `triangles` over `positions` (validated: every index in range).
    pub(super) fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Runs {
        let boxes: Vec<(DVec3, DVec3)> = triangles
            .par_chunks(RUN)
            .map(|run| {
                let (lo, hi) = run.iter().flatten().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), &i| {
                        let p = positions[i as usize];
                        (lo.min(p), hi.max(p))
                    },
                );
                (0.5 * (lo + hi), 0.5 * (hi - lo))
            })
            .collect();
        let (x0, x1) = boxes
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, h)| {
                (a.min(c.x - h.x), b.max(c.x + h.x))
            });
        let slabs = (boxes.len() / RUNS_PER_SLAB).max(1);
        let mut runs = Runs {
            boxes,
            x0,
            slabs_per_metre: if x1 > x0 {
                slabs as f64 / (x1 - x0)
            } else {
                0.0
            },
            slab_starts: vec![0; slabs + 1],
            by_slab: Vec::new(),
        };
        let extent = |r: &Runs, k: usize| {
            let (c, h) = r.boxes[k];
            (r.slab(c.x - h.x, slabs), r.slab(c.x + h.x, slabs))
        };
        for k in 0..runs.boxes.len() {
            let (s0, s1) = extent(&runs, k);
            for s in s0..=s1 {
                runs.slab_starts[s + 1] += 1;
            }
        }
        for s in 0..slabs {
            runs.slab_starts[s + 1] += runs.slab_starts[s];
        }
        let mut fill = runs.slab_starts.clone();
        let mut by_slab = vec![0u32; runs.slab_starts[slabs]];
        for k in 0..runs.boxes.len() {
            let (s0, s1) = extent(&runs, k);
            for s in s0..=s1 {
                by_slab[fill[s]] = k as u32;
                fill[s] += 1;
            }
        }
        runs.by_slab = by_slab;
        runs
    }

    /// The slab of `x` among `slabs` (clamped to the mesh's length).
    #[inline]
    fn slab(&self, x: f64, slabs: usize) -> usize {
        let s = ((x - self.x0) * self.slabs_per_metre).floor();
        if s > 0.0 {
            (s as usize).min(slabs - 1)
        } else {
            0
        }
    }

    /// The runs whose box may hold points with `x` = `x` (every such run is among them).
    pub(super) fn at_station(&self, x: f64) -> &[u32] {
        let s = self.slab(x, self.slab_starts.len() - 1);
        &self.by_slab[self.slab_starts[s]..self.slab_starts[s + 1]]
    }

    /// The number of runs.
    pub(super) fn len(&self) -> usize {
        self.boxes.len()
    }

    /// The range of `m·p` over the box of run `k` (of its mirror image `y → −y` when
    /// `mirror`), widened by a rounding margin so that it holds every corner's value as
    /// computed.
    #[inline]
    pub(super) fn span(&self, k: usize, m: DVec3, mirror: bool) -> (f64, f64) {
        let (mut c, h) = self.boxes[k];
        if mirror {
            c.y = -c.y;
        }
        let mid = m.dot(c);
        let half = m.abs().dot(h);
        let margin = RUN_ROUNDING * (m.abs().dot(c.abs()) + half);
        (mid - half - margin, mid + half + margin)
    }
}

/// Relative rounding margin of a run's span: the box's centre-and-half form and the dot
/// products round at a few ulps of the coordinates.
const RUN_ROUNDING: f64 = 1e-14;
