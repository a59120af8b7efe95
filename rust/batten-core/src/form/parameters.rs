//! The parameters measured from a form topology (Bole, seed 002, §7.2.5), as plain data; how
//! they are measured is [`measure`](super::measure).

use glam::DVec3;

/// The parallel middle body: between two midship sections.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParallelMiddleBody {
    /// x of its aft end.
    pub aft: f64,
    /// x of its forward end.
    pub fwd: f64,
    /// `fwd − aft`.
    pub length: f64,
    /// x of its centre.
    pub position: f64,
    /// The midship section at its aft end (network index).
    pub aft_section: usize,
    /// The midship section at its forward end.
    pub fwd_section: usize,
}

/// The bilge of one midship section: the arc between the flat of bottom and flat of side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bilge {
    /// The midship section (network index).
    pub section: usize,
    /// The vertex where the flat of bottom ends (index into the form's vertices).
    pub fob_vertex: usize,
    /// The vertex where the flat of side begins.
    pub fos_vertex: usize,
    /// The arc's radius, `None` when the stretch is not a circular arc.
    pub radius: Option<f64>,
    /// Height of the bottom line at half breadth above the keel.
    pub rise_of_floor: f64,
    /// Where the bottom and side lines meet (the bilge corner, in the section plane).
    pub corner: DVec3,
    /// Unit direction of the bottom line from the corner towards the keel.
    pub bottom_direction: DVec3,
    /// Unit direction of the side line from the corner towards the deck.
    pub side_direction: DVec3,
}

/// The measured parameters of a form (§7.2.5).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FormParameters {
    /// Overall length (x extent).
    pub length: f64,
    /// Largest breadth (twice the largest y).
    pub breadth: f64,
    /// Depth (z extent).
    pub depth: f64,
    /// The design draft given.
    pub draft: Option<f64>,
    /// Breadth at the design waterline (with a draft).
    pub waterline_breadth: Option<f64>,
    /// x extent `[min, max]` of the curves.
    pub x_range: [f64; 2],
    /// The parallel middle body, if there is one.
    pub pmb: Option<ParallelMiddleBody>,
    /// Why there is none (when `pmb` is `None`).
    pub no_pmb_reason: Option<String>,
    /// The bilge of each midship section with flat of bottom and side, aft first.
    pub bilges: Vec<Bilge>,
    /// From the PMB's forward end to the bow.
    pub entrance_length: Option<f64>,
    /// From the stern to the PMB's aft end.
    pub run_length: Option<f64>,
}
