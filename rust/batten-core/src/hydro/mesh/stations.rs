//! Which triangles a station plane `x = const` can cut: the mesh's length split into equal
//! slabs, each listing the triangles whose `x` extent overlaps it, so a sectional area or the
//! search for the largest section reads a few thousand triangles, not the whole mesh.

use glam::DVec3;

/// About this many triangles per slab (a station reads one slab).
const TRIANGLES_PER_SLAB: usize = 64;

/// At most this many slabs.
const MAX_SLABS: usize = 1 << 16;

/// The slab lists may hold at most this many entries per triangle: a mesh of long triangles
/// (a box barge's sides) gets fewer, wider slabs rather than quadratic memory.
const MAX_ENTRIES_PER_TRIANGLE: usize = 8;

/// Triangles by the slab of `x` they overlap (compressed rows: slab `s` holds
/// `items[starts[s]..starts[s + 1]]`).
#[derive(Clone, Debug)]
pub(super) struct StationIndex {
    x0: f64,
    inv_width: f64,
    slabs: usize,
    starts: Vec<usize>,
    items: Vec<u32>,
}

impl StationIndex {
    /// The index of `triangles` over `positions` (validated: every index in range).
    pub(super) fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> StationIndex {
        let (x0, x1) = positions
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.x), b.max(p.x))
            });
        let extent = |t: &[u32; 3]| {
            let xs = t.map(|i| positions[i as usize].x);
            (xs[0].min(xs[1]).min(xs[2]), xs[0].max(xs[1]).max(xs[2]))
        };
        let mut slabs = (triangles.len() / TRIANGLES_PER_SLAB).clamp(1, MAX_SLABS);
        loop {
            let index = StationIndex {
                x0,
                inv_width: if x1 > x0 {
                    slabs as f64 / (x1 - x0)
                } else {
                    0.0
                },
                slabs,
                starts: Vec::new(),
                items: Vec::new(),
            };
            let mut counts = vec![0isize; slabs + 1];
            let mut total = 0usize;
            for t in triangles {
                let (lo, hi) = extent(t);
                let (s0, s1) = (index.slab(lo), index.slab(hi));
                counts[s0] += 1;
                counts[s1 + 1] -= 1;
                total += s1 - s0 + 1;
            }
            if slabs > 1 && total > MAX_ENTRIES_PER_TRIANGLE * triangles.len() {
                slabs /= 2;
                continue;
            }
            return index.filled(triangles, &counts, total, extent);
        }
    }

    /// Fill the lists from the difference array `counts` (+1 at a triangle's first slab, −1
    /// after its last).
    fn filled(
        mut self,
        triangles: &[[u32; 3]],
        counts: &[isize],
        total: usize,
        extent: impl Fn(&[u32; 3]) -> (f64, f64),
    ) -> StationIndex {
        let mut starts = Vec::with_capacity(self.slabs + 1);
        let (mut running, mut at) = (0isize, 0usize);
        for c in &counts[..self.slabs] {
            running += c;
            starts.push(at);
            at += running.unsigned_abs();
        }
        starts.push(at);
        debug_assert_eq!(at, total, "slab lists hold every overlap");
        let mut fill = starts.clone();
        let mut items = vec![0u32; total];
        for (k, t) in triangles.iter().enumerate() {
            let (lo, hi) = extent(t);
            for s in self.slab(lo)..=self.slab(hi) {
                items[fill[s]] = k as u32;
                fill[s] += 1;
            }
        }
        self.starts = starts;
        self.items = items;
        self
    }

    /// The slab holding `x` (clamped to the mesh's length).
    #[inline]
    fn slab(&self, x: f64) -> usize {
        let s = ((x - self.x0) * self.inv_width).floor();
        if s > 0.0 {
            (s as usize).min(self.slabs - 1)
        } else {
            0
        }
    }

    /// The triangles a station at `x` may cut (every one it cuts is among them).
    pub(super) fn candidates(&self, x: f64) -> &[u32] {
        let s = self.slab(x);
        &self.items[self.starts[s]..self.starts[s + 1]]
    }
}
