//! One surface patch over a face (H-rep paper §3.2.1–3.2.2): its options, construction from
//! the face's boundary and ribbons, and evaluation by the Gregory (4 sides) or Charrot–Gregory
//! (N sides) scheme, or by the side-blended fallback for a face where those fold.

use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::boundary::{prepare_boundary, FaceBoundary, PreparedSide, SideParam};
use super::charrot_gregory;
use super::corner::{corner_data, CornerData};
use super::domain::{lattice_parameter, square_rings, Domain, MAX_SIDES};
use super::error::{PatchError, PatchWarning};
use super::gregory4;
use super::ribbon::{prepare_ribbons, PreparedRibbon, SideRibbon};
use super::side_blend;
use crate::tolerance::Tolerance;

/// Which surface scheme interpolates a face.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PatchKind {
    /// Gregory for 4 sides, Charrot–Gregory otherwise (the paper's choice, §3.2.1).
    #[default]
    Auto,
    /// The 4-sided Gregory patch with rational twists.
    Gregory,
    /// The N-sided Charrot–Gregory patch (also for 4 sides).
    CharrotGregory,
    /// Kato's side-blended patch with ribbons limited by the face's width: the fallback for a
    /// face whose corner-based patch folds (see the `side_blend` module).
    SideBlend,
}

/// Options of [`Patch::try_new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchOptions {
    /// The surface scheme.
    pub kind: PatchKind,
    /// How composite sides divide their parameter among segments.
    pub param: SideParam,
    /// The model tolerance: shorter sides are refused, gaps up to 10× it are closed.
    pub tolerance: Tolerance,
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            kind: PatchKind::Auto,
            param: SideParam::ArcLength,
            tolerance: Tolerance::DEFAULT,
        }
    }
}

/// Step in domain units for [`Patch::derivatives`] (the domain has unit size).
const DERIV_STEP: f64 = 1e-6;

/// One surface patch over a face: the Gregory (4 sides) or Charrot–Gregory (N sides) interpolant
/// of the face's boundary curves and tangent ribbons (H-rep paper §3.2.1–3.2.2).
///
/// Evaluation allocates nothing and is `Sync`: patches of a network can be evaluated in
/// parallel. A clone shares the patch's data (the live rebuild keeps the patches of faces
/// that did not move).
#[derive(Clone, Debug)]
pub struct Patch {
    kind: PatchKind,
    domain: Domain,
    /// The domain's depth behind each side (side-blended patches only).
    depth: Arc<[f64]>,
    sides: Arc<[PreparedSide]>,
    ribbons: Arc<[PreparedRibbon]>,
    corners: Arc<[CornerData]>,
    warnings: Arc<[PatchWarning]>,
}

impl Patch {
    /// Build the patch of a face from its boundary and one ribbon per side (`ribbons` empty:
    /// default ribbons everywhere).
    ///
    /// Errors: fewer than 3 or more than [`MAX_SIDES`] sides, an empty or zero-length side, a
    /// parameter outside its curve, a gap at a corner or T-joint wider than 10× the tolerance,
    /// a ribbon list of the wrong shape, or [`PatchKind::Gregory`] on a face without 4 sides.
    pub fn try_new(
        boundary: &FaceBoundary,
        ribbons: &[SideRibbon],
        options: &PatchOptions,
    ) -> Result<Patch, PatchError> {
        let sides = prepare_boundary(boundary, options.param, options.tolerance, MAX_SIDES)?;
        let n = sides.len();
        let kind = match (options.kind, n) {
            (PatchKind::Auto, 4) | (PatchKind::Gregory, 4) => PatchKind::Gregory,
            (PatchKind::Gregory, _) => return Err(PatchError::GregoryNeedsFourSides { sides: n }),
            (PatchKind::SideBlend, _) => PatchKind::SideBlend,
            _ => PatchKind::CharrotGregory,
        };
        if !ribbons.is_empty() && ribbons.len() != n {
            return Err(PatchError::RibbonCount {
                expected: n,
                got: ribbons.len(),
            });
        }
        for (i, (r, s)) in ribbons.iter().zip(&boundary.sides).enumerate() {
            if r.segments.len() != s.segments.len() {
                return Err(PatchError::RibbonSegments {
                    side: i,
                    expected: s.segments.len(),
                    got: r.segments.len(),
                });
            }
        }
        let mut warnings = Vec::new();
        let blend = kind == PatchKind::SideBlend;
        let ribs = prepare_ribbons(&sides, ribbons, blend, &mut warnings);
        let corners = corner_data(&sides, &ribs);
        let domain = Domain::new(n);
        Ok(Patch {
            kind,
            depth: if blend {
                side_blend::depths(&domain).into()
            } else {
                Arc::from([])
            },
            domain,
            sides: sides.into(),
            ribbons: ribs.into(),
            corners: corners.into(),
            warnings: warnings.into(),
        })
    }

    /// Number of sides.
    pub fn sides(&self) -> usize {
        self.sides.len()
    }

    /// The validated sides, for the tessellation.
    pub(super) fn prepared_sides(&self) -> &[PreparedSide] {
        &self.sides
    }

    /// The scheme in use ([`PatchKind::Gregory`], [`PatchKind::CharrotGregory`] or
    /// [`PatchKind::SideBlend`]).
    pub fn kind(&self) -> PatchKind {
        self.kind
    }

    /// The parameter domain (unit square for 4 sides, regular N-gon otherwise).
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// What was repaired while building the patch.
    pub fn warnings(&self) -> &[PatchWarning] {
        &self.warnings
    }

    /// The same patch with one more warning.
    pub(crate) fn with_warning(mut self, warning: PatchWarning) -> Patch {
        let mut all = self.warnings.to_vec();
        all.push(warning);
        self.warnings = all.into();
        self
    }

    /// The surface point at domain point `x` (points outside the domain are clamped onto it).
    #[inline]
    pub fn eval(&self, x: [f64; 2]) -> DVec3 {
        self.eval_v(DVec2::from(x))
    }

    #[inline]
    pub(crate) fn eval_v(&self, x: DVec2) -> DVec3 {
        match self.kind {
            PatchKind::Gregory => gregory4::eval(&self.sides, &self.ribbons, &self.corners, x),
            PatchKind::SideBlend => {
                side_blend::eval(&self.domain, &self.depth, &self.sides, &self.ribbons, x)
            }
            _ => charrot_gregory::eval(&self.domain, &self.sides, &self.ribbons, &self.corners, x),
        }
    }

    /// The interior points of a tensor grid on the unit square of a Gregory patch, rows of
    /// `v` (outer) by columns of `u`, appended to `out`: each point is exactly
    /// `eval_v((u, v))`, with each side's ribbon sampled once per column or row instead of
    /// once per point (the sides' ribbons depend on one of the two parameters only). False
    /// (and nothing appended) for a patch of another kind.
    pub(crate) fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut Vec<DVec3>) -> bool {
        if self.kind != PatchKind::Gregory {
            return false;
        }
        let (along_u, along_v) = (self.ribbon_pairs(0, us), self.ribbon_pairs(1, vs));
        let fanned = gregory4::fanned(&self.ribbons);
        out.reserve(us.len() * vs.len());
        for pv in &along_v {
            out.extend(along_u.iter().map(|pu| self.blend_pairs(fanned, pu, pv)));
        }
        true
    }

    /// The inside points of a Gregory patch meshed on `k` rings (the tessellation's lattice of
    /// the unit square, [`square_rings`]), appended to `out` in the mesh's vertex order: each
    /// point is exactly `eval_v` there, with each side's ribbon sampled once per lattice column
    /// or row instead of once per point. False (and nothing appended) for a patch of another
    /// kind.
    pub(crate) fn eval_square_rings(&self, k: usize, out: &mut Vec<DVec3>) -> bool {
        if self.kind != PatchKind::Gregory {
            return false;
        }
        let lattice: Vec<f64> = (0..=2 * k).map(lattice_parameter(k)).collect();
        let (along_u, along_v) = (
            self.ribbon_pairs(0, &lattice),
            self.ribbon_pairs(1, &lattice),
        );
        let fanned = gregory4::fanned(&self.ribbons);
        out.extend(
            square_rings(k)
                .into_iter()
                .map(|(i, j)| self.blend_pairs(fanned, &along_u[i], &along_v[j])),
        );
        true
    }

    /// A Gregory patch's two opposite sides across `axis` (0: the sides along `u`, 1: along
    /// `v`) sampled at each of `ws`, with the parameter as the patch takes it.
    fn ribbon_pairs(&self, axis: usize, ws: &[f64]) -> Vec<(f64, gregory4::RibbonPair)> {
        ws.iter()
            .map(|&w| {
                let w = gregory4::square_parameter(w);
                (
                    w,
                    gregory4::RibbonPair::at(&self.sides, &self.ribbons, axis, w),
                )
            })
            .collect()
    }

    /// A Gregory patch's point from its ribbon pairs sampled at `u` ([`Patch::ribbon_pairs`]
    /// across axis 0) and at `v` (across axis 1), `fanned` its ribbons' [`gregory4::fanned`]:
    /// `eval_v((u, v))` exactly.
    #[inline]
    fn blend_pairs(
        &self,
        fanned: bool,
        (u, along_u): &(f64, gregory4::RibbonPair),
        (v, along_v): &(f64, gregory4::RibbonPair),
    ) -> DVec3 {
        gregory4::blend_sampled(
            &self.ribbons,
            &self.corners,
            fanned,
            *u,
            *v,
            along_u,
            along_v,
        )
    }

    /// Evaluate many domain points into `out` (same length); allocates nothing.
    pub fn eval_into(&self, xs: &[[f64; 2]], out: &mut [DVec3]) {
        for (x, o) in xs.iter().zip(out.iter_mut()) {
            *o = self.eval(*x);
        }
    }

    /// The surface point and its first derivatives along the domain axes at `x`.
    ///
    /// Implementation note: the derivatives are finite differences (step 1e-6 in the unit-size
    /// domain; central inside, one-sided and second-order at the domain boundary, always
    /// sampling inside the domain), accurate to about 1e-6 relative.
    pub fn derivatives(&self, x: [f64; 2]) -> (DVec3, DVec3, DVec3) {
        let x = self.domain.clamp(DVec2::from(x));
        let p = self.eval_v(x);
        let h = DERIV_STEP;
        let axis = |e: DVec2| -> DVec3 {
            let (fwd, bwd) = (x + e * h, x - e * h);
            let inside = |y: DVec2| self.domain.contains(y.to_array());
            match (inside(fwd), inside(bwd)) {
                (true, true) => (self.eval_v(fwd) - self.eval_v(bwd)) / (2.0 * h),
                (true, false) => {
                    (self.eval_v(fwd) * 4.0 - p * 3.0 - self.eval_v(x + e * (2.0 * h))) / (2.0 * h)
                }
                (false, true) => {
                    (p * 3.0 - self.eval_v(bwd) * 4.0 + self.eval_v(x - e * (2.0 * h))) / (2.0 * h)
                }
                (false, false) => DVec3::ZERO,
            }
        };
        (p, axis(DVec2::X), axis(DVec2::Y))
    }

    /// The unit surface normal at domain point `x` (outward for a counter-clockwise face), or
    /// zero where the patch is singular.
    pub fn normal(&self, x: [f64; 2]) -> DVec3 {
        let (_, du, dv) = self.derivatives(x);
        du.cross(dv).normalize_or_zero()
    }

    /// The unit surface normal on side `i` at side parameter `s` (as [`Patch::normal`] at that
    /// boundary point): the side curve's tangent crossed with the patch's derivative into the
    /// domain. The tangent is the side's own (central differences of [`Patch::side_point`],
    /// one-sided at its ends: the patch interpolates its sides), the cross derivative a
    /// second-order one-sided difference along the side's inward normal: three patch
    /// evaluations where [`Patch::normal`] takes five. Zero where the patch is singular.
    pub fn boundary_normal(&self, i: usize, s: f64) -> DVec3 {
        let i = i % self.domain.sides();
        let s = s.clamp(0.0, 1.0);
        let x = self.domain.side_point_v(i, s);
        let inward = self.domain.inward(i);
        let h = DERIV_STEP;
        let p = self.eval_v(x);
        let across =
            (self.eval_v(x + inward * h) * 4.0 - p * 3.0 - self.eval_v(x + inward * (2.0 * h)))
                / (2.0 * h);
        self.side_tangent(i, s).cross(across).normalize_or_zero()
    }

    /// The unit normal of the surface's tangent plane on side `i` at side parameter `s`: the
    /// side's derivative there crossed with its ribbon (the plane the patch takes along its
    /// side, and its neighbour across a smooth edge too), or zero where they are parallel.
    /// One-sided at a corner inside the side, as the ribbon's own frame is.
    pub(crate) fn side_plane_normal(&self, i: usize, s: f64) -> DVec3 {
        let i = i % self.sides.len();
        let (_, along, ribbon) = self.ribbons[i].eval_along(&self.sides[i], s);
        along.cross(ribbon).normalize_or_zero()
    }

    /// d/ds of side `i` at `s`: central differences of [`Patch::side_point`], one-sided at the
    /// side's ends.
    pub(crate) fn side_tangent(&self, i: usize, s: f64) -> DVec3 {
        let h = DERIV_STEP;
        let (lo, hi) = ((s - h).max(0.0), (s + h).min(1.0));
        (self.side_point(i, hi) - self.side_point(i, lo)) / (hi - lo)
    }

    /// The boundary curve of side `i` at side parameter `s ∈ [0, 1]` (the designer curve, with
    /// the corner corrections that close gaps below the tolerance).
    pub fn side_point(&self, i: usize, s: f64) -> DVec3 {
        self.sides[i % self.sides.len()].point(s)
    }

    /// The side parameter `s ∈ [0, 1]` of the point at fraction `lambda` of segment `segment`
    /// of side `side` (the segment's own parameter, which runs at nearly uniform speed along
    /// its curve; [`Patch::segment_curve_parameter`] gives the curve's parameter there): lets
    /// the hull report (H-rep §3.2.2, G1 across shared edges) evaluate both faces of an edge at
    /// the same curve point when the edge is one segment of a composite side. Two faces sharing
    /// a segment map its fractions to the same curve points, `lambda` on one and `1 − lambda`
    /// on the other.
    pub(crate) fn segment_side_parameter(&self, side: usize, segment: usize, lambda: f64) -> f64 {
        let side = &self.sides[side % self.sides.len()];
        let k = segment.min(side.segs.len() - 1);
        let (a, b) = (side.breaks[k], side.breaks[k + 1]);
        a + (b - a) * lambda.clamp(0.0, 1.0)
    }

    /// The curve parameter at fraction `lambda` of segment `segment` of side `side` (as in
    /// [`Patch::segment_side_parameter`]).
    pub(crate) fn segment_curve_parameter(&self, side: usize, segment: usize, lambda: f64) -> f64 {
        let side = &self.sides[side % self.sides.len()];
        side.segs[segment.min(side.segs.len() - 1)]
            .parameter(lambda)
            .0
    }

    /// The ribbon (cross-boundary derivative pointing into the face, with respect to the cross
    /// parameter running from 0 on the side to 1 across the domain) of side `i` at `s`.
    pub fn ribbon(&self, i: usize, s: f64) -> DVec3 {
        let i = i % self.sides.len();
        self.ribbons[i].eval(&self.sides[i], s).1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::NurbsCurve;
    use crate::patch::{Side, SideSegment};

    /// A cubic Bézier through `p`, its inner control points lifted by `lift` along z.
    fn cubic(a: DVec3, b: DVec3, lift: f64) -> NurbsCurve {
        let (m1, m2) = (a.lerp(b, 1.0 / 3.0), a.lerp(b, 2.0 / 3.0));
        let up = DVec3::Z * lift;
        NurbsCurve::try_new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![a, m1 + up, m2 - up, b],
            None,
        )
        .expect("a cubic")
    }

    fn patch(lift: f64, n: usize) -> Patch {
        let corners: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64 + 0.2;
                DVec3::new(2.0 * a.cos(), 1.3 * a.sin(), 0.0)
            })
            .collect();
        let sides = (0..n)
            .map(|k| {
                let (a, b) = (corners[k], corners[(k + 1) % n]);
                Side::single(SideSegment::whole(cubic(a, b, lift * (k % 2) as f64)))
            })
            .collect();
        Patch::try_new(&FaceBoundary::new(sides), &[], &PatchOptions::default()).expect("patch")
    }

    #[test]
    fn the_side_plane_normal_is_the_patch_normal_on_its_side() {
        // Flat: the plane's normal, to rounding.
        for n in [3, 4, 5] {
            let p = patch(0.0, n);
            for i in 0..n {
                for s in [0.0, 0.1, 0.5, 0.93, 1.0] {
                    let normal = p.side_plane_normal(i, s);
                    assert!(
                        normal.cross(DVec3::Z).length() < 1e-12,
                        "{n} sides, side {i} at {s}: {normal}"
                    );
                }
            }
        }
        // Curved: the patch's own normal there (finite differences, 1e-6 relative).
        for n in [3, 4, 5] {
            let p = patch(0.4, n);
            for i in 0..n {
                for s in [0.1, 0.5, 0.93] {
                    let (a, b) = (p.side_plane_normal(i, s), p.boundary_normal(i, s));
                    assert!(
                        a.cross(b).length() < 1e-5 && a.dot(b) > 0.0,
                        "{n} sides, side {i} at {s}: {a} against {b}"
                    );
                }
            }
        }
    }
}
