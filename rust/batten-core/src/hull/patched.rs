//! The faces that became patches, each with its patch and where its edges went, in one value
//! (so the patch, its layout and its face index cannot drift apart).

use std::borrow::Borrow;

use crate::patch::Patch;

/// One segment of a patch side: the topology edge it is and whether the side runs along the
/// edge's curve (`t0 → t1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LayoutSegment {
    /// Index of the edge in the topology.
    pub(crate) edge: usize,
    /// True when the side runs along the curve.
    pub(crate) forward: bool,
}

/// Where the edges of one patch went: per side, per segment.
pub(crate) type PatchLayout = Vec<Vec<LayoutSegment>>;

/// A face of the topology built as a patch.
#[derive(Clone, Debug)]
pub(crate) struct PatchedFace {
    /// Index of the face in [`Topology::faces`](crate::Topology::faces).
    pub(crate) face: usize,
    /// Its patch.
    pub(crate) patch: Patch,
    /// Where the face's edges went among the patch's sides and segments.
    pub(crate) layout: PatchLayout,
}

impl Borrow<Patch> for PatchedFace {
    /// The patch, so a slice of faces tessellates as a slice of patches.
    fn borrow(&self) -> &Patch {
        &self.patch
    }
}
