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

/// What the two unknowns of a [`Mode`] move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// (entrance length, run length): the PMB's ends.
    Pmb,
    /// (entrance bulge, run bulge), m.
    Bulge,
    /// The PMB's length held: (the PMB's shift forward, m; both ends' bulge, m). The shift
    /// moves the LCB, the bulge the volume.
    ShiftAndBulge,
    /// The PMB's position held: (the PMB's lengthening, m, half at each end; the entrance's
    /// bulge, m, the run's the opposite). The length moves the volume, the opposite bulges the
    /// LCB.
    LengthAndBulge,
}

/// A deformation with its two unknowns and its limits.
#[derive(Clone, Debug)]
pub(super) struct Mode {
    pub(super) kind: Kind,
    /// The original's entrance and run lengths (m), when it has a PMB.
    lengths: Option<[f64; 2]>,
    /// Shortest PMB, entrance and run (m).
    min_len: f64,
    /// Entrance + PMB + run (m): what the two ends share.
    total: f64,
    /// Form faces of the entrance and of the run below the waterline.
    pub(super) faces: [Vec<usize>; 2],
    /// Largest bulge either way (m).
    max: f64,
}

/// A limit of a mode, linear in its unknowns: `a·x + c ≥ 0`.
struct Limit {
    a: [f64; 2],
    c: f64,
    name: &'static str,
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
    /// A mode of `kind`: the original's entrance and run lengths when it has a PMB (`lengths`,
    /// with the PMB's length `pmb`, over a hull `length` long), and the ends' faces with the
    /// largest bulge `max`.
    pub(super) fn new(
        kind: Kind,
        lengths: Option<[f64; 2]>,
        pmb: f64,
        length: f64,
        faces: [Vec<usize>; 2],
        max: f64,
    ) -> Mode {
        let total = lengths.map_or(0.0, |[e, r]| e + r + pmb);
        Mode {
            kind,
            lengths,
            min_len: MIN_LENGTH_FRACTION * length,
            total,
            faces,
            max,
        }
    }

    /// The unknowns of the original.
    pub(super) fn start(&self) -> [f64; 2] {
        match (self.kind, self.lengths) {
            (Kind::Pmb, Some(l)) => l,
            _ => [0.0, 0.0],
        }
    }

    /// A length for "no step left" (m).
    pub(super) fn scale(&self) -> f64 {
        if self.kind == Kind::Bulge {
            self.max
        } else {
            self.total
        }
    }

    /// The entrance and run lengths (m; the original's when they do not move) and the
    /// entrance's and run's bulges (m) at the unknowns `x`.
    fn map(&self, x: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let [e0, r0] = self.lengths.unwrap_or([0.0; 2]);
        match self.kind {
            Kind::Pmb => (x, [0.0; 2]),
            Kind::Bulge => ([e0, r0], x),
            Kind::ShiftAndBulge => ([e0 - x[0], r0 + x[0]], [x[1]; 2]),
            Kind::LengthAndBulge => ([e0 - 0.5 * x[0], r0 - 0.5 * x[0]], [x[1], -x[1]]),
        }
    }

    /// The mode's limits, each linear in the unknowns (read off [`Mode::map`], which is
    /// affine); a quantity the mode does not move has none.
    fn limits(&self) -> Vec<Limit> {
        let flat = |x: [f64; 2]| {
            let (l, b) = self.map(x);
            [l[0], l[1], b[0], b[1]]
        };
        let c0 = flat([0.0; 2]);
        let (c1, c2) = (flat([1.0, 0.0]), flat([0.0, 1.0]));
        let linear = |k: usize, sign: f64, offset: f64| Limit {
            a: [sign * (c1[k] - c0[k]), sign * (c2[k] - c0[k])],
            c: sign * c0[k] + offset,
            name: "",
        };
        let mut out = Vec::new();
        let mut add = |l: Limit, name: &'static str| {
            if l.a != [0.0, 0.0] {
                out.push(Limit { name, ..l });
            }
        };
        if self.lengths.is_some() {
            add(
                linear(0, 1.0, -self.min_len),
                "the entrance would be shorter than 2 % of the hull",
            );
            add(
                linear(1, 1.0, -self.min_len),
                "the run would be shorter than 2 % of the hull",
            );
            let (e, r) = (linear(0, -1.0, 0.0), linear(1, -1.0, 0.0));
            add(
                Limit {
                    a: [e.a[0] + r.a[0], e.a[1] + r.a[1]],
                    c: self.total + e.c + r.c - self.min_len,
                    name: "",
                },
                "the parallel middle body would be shorter than 2 % of the hull",
            );
        }
        const ENTRANCE: &str = "the entrance's bulge would exceed a quarter of the half breadth";
        const RUN: &str = "the run's bulge would exceed a quarter of the half breadth";
        add(linear(2, -1.0, self.max), ENTRANCE);
        add(linear(2, 1.0, self.max), ENTRANCE);
        add(linear(3, -1.0, self.max), RUN);
        add(linear(3, 1.0, self.max), RUN);
        out
    }

    /// How far `x` may go along `d` (a fraction in [0, 1]) and the limit met first.
    pub(super) fn room(&self, x: [f64; 2], d: [f64; 2]) -> (f64, Option<&'static str>) {
        let mut t = 1.0f64;
        let mut which = None;
        for l in self.limits() {
            let slack = l.a[0] * x[0] + l.a[1] * x[1] + l.c;
            let rate = l.a[0] * d[0] + l.a[1] * d[1];
            if rate < 0.0 && slack + rate * t < 0.0 {
                t = (slack / -rate).max(0.0);
                which = Some(l.name);
            }
        }
        (t, which)
    }

    /// The entrance's and run's bulges (m) at the unknowns `x`.
    pub(super) fn bulges(&self, x: [f64; 2]) -> [f64; 2] {
        self.map(x).1
    }

    /// The direction along the limit `which` (as [`Mode::room`] names it).
    pub(super) fn along(&self, which: &str) -> [f64; 2] {
        self.limits()
            .into_iter()
            .find(|l| l.name == which)
            .map_or([1.0, 0.0], |l| [l.a[1], -l.a[0]])
    }

    /// `network` (of form topology `form`) deformed to the unknowns `x`, or why not.
    pub(super) fn deform(
        &self,
        network: &Network,
        form: &FormTopology,
        x: [f64; 2],
        tolerance: Tolerance,
    ) -> Result<Network, String> {
        let ([e, r], [b_e, b_r]) = self.map(x);
        // Both PMB ends in one deformation of the original (their moves touch different
        // sections), so the result does not depend on an order of steps.
        let mut moves = Vec::new();
        if self.lengths.is_some() && self.kind != Kind::Bulge {
            for target in [Target::EntranceLength(e), Target::RunLength(r)] {
                match parametric_moves(network, form, target).map_err(|e| e.to_string())? {
                    Plan::Moves(m) => moves.extend(m),
                    Plan::TransverseScale(_) => {
                        return Err(format!("{} is no PMB move", target.name()))
                    }
                }
            }
        }
        let mut bulges = Vec::new();
        if self.kind != Kind::Pmb {
            for (faces, amount) in self.faces.iter().zip([b_e, b_r]) {
                bulges.extend(faces.iter().map(|&face| FaceBulge { face, amount }));
            }
        }
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
        // The flats' tangent planes stay where they were: the PMB's ends move along them, and
        // a bulge leaves the form curves (the flats among them) where they are.
        Network::try_new(deformed.name.clone(), held)
            .map(|n| n.with_tangent_planes(network.tangent_planes().to_vec()))
            .map_err(|e| e.to_string())
    }
}
