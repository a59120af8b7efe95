//! Runs of consecutive triangles with their bounding boxes, so a plane skips the runs it cannot
//! touch: a station or waterline reads the few runs it crosses, the wet integrals skip the dry
//! runs, and the wet part's extent is found by bounding runs before reading any.
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

/// The bounding box (centre, half extent) of each run of [`RUN`] consecutive triangles.
#[derive(Clone, Debug)]
pub(super) struct Runs {
    boxes: Vec<(DVec3, DVec3)>,
}

impl Runs {
    /// The runs of `triangles` over `positions` (validated: every index in range).
    pub(super) fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Runs {
        let boxes = triangles
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
        Runs { boxes }
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
