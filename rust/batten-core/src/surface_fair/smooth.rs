//! Smoothing along the sections: the stage before the relaxation of Pla et al. (1998, §4).
//!
//! The relaxation filters a section against its neighbours in the family, point by point at
//! corresponding places, which removes noise across the family; noise along a section (each
//! control point off by its own amount, as in the paper's test) passes through it almost whole
//! (the cubic filter's weights −1/6, 2/3, 2/3, −1/6 keep 97 % of it). So every section is first
//! smoothed along itself, all of them together so that the nodes stay where both their curves
//! pass:
//!
//! - Each section's control points move in its plane, along the normal and the tangent at
//!   their Greville abscissae (the tangential moves let a node slide along the line its
//!   planes share wherever the section crosses it), by the moves `x` that minimise
//!   `Σ w_j |ΔP_j|² + μ ∫ κ′² ds / (1 + (κ̄ ℓ)²)`: `w_j` the length of section the control
//!   point stands for (so the first term is `∫ |ΔC|² ds`), the second the curvature variation
//!   the report measures (16-point Gauss–Legendre per knot span), each point's share divided
//!   by `1 + (κ̄ ℓ)²` with `κ̄` the curvature at the scale of the smoothing length `ℓ` (of the
//!   circle through the points `ℓ/2` either side), so that a turn tighter than `ℓ` — a bilge,
//!   a bulb's nose — is kept as form while noise on flat and gently curved stretches goes.
//!   `μ = (ℓ / 2π)⁶`: a wave of length `ℓ` along a section is halved, shorter ones vanish
//!   (`1 / (1 + μ ω⁶)`), longer ones stay. The ends stay, the control points next to them move
//!   only along the end tangents (the section leaves the keel, the profile and the deck as it
//!   did), and the smooth joints stay smooth (the relaxation's joint rows).
//! - The curvature variation is not quadratic in the moves: it is linearised at the sections
//!   as they are (Gauss–Newton), every step anchored where the smoothing started and halved
//!   until the objective falls (the first full step overshoots where a section turns tightly:
//!   KCS's wl_z0.30 round the bulb).
//! - The sections share their nodes by consensus (the alternating direction method of
//!   multipliers, Boyd et al. 2011, §7.1): each section is solved with its nodes pulled toward
//!   the nodes' current places, each free node goes to the mean of where its sections put it
//!   (along the line its planes share; a fixed node stays), and the pull's multipliers gather
//!   the differences, until the sections agree within a hundredth of the tolerance. Then each
//!   section takes the least change from its smoothed moves that passes exactly through its
//!   nodes and keeps its joints (the relaxation's [`least_change`]), so the network is exact.
//! - A control point that would leave its tolerance weighs more (four times, or by the square
//!   of how far over it is) and the sections are solved again; what still is over after a few
//!   such passes is brought back by one factor on every move (the moves are linear, so the
//!   nodes still agree).
//!
//! Sections of a family not faired, and rational or lower-degree ones, only follow their nodes
//! (a quadratic's unfairness is in its curvature's jumps at the knots, which this measure does
//! not see; the relaxation fairs those).

use glam::DVec3;

use crate::curve::{
    ders_basis_funs, smooth_joint_rows, NurbsCurve, GL8, JOINT_ROW_WIDTH, MAX_ORDER,
};
use crate::error::Error;

use super::banded::Banded;
use super::filter::greville;
use super::least_change::{joint_rows, least_change, point_row, Row};
use super::nodes::Freedom;
use super::relax::{in_plane, in_plane_axes, Plan, State};

/// The pull of a section's nodes toward their consensus places (ADMM's ρ), against the unit
/// weight of a control point's own offset.
const NODE_PULL: f64 = 1.0;
/// The weight of the smooth joints' rows while the sections are solved (the final least
/// change keeps them exactly).
const JOINT_WEIGHT: f64 = 1e6;
/// Consensus steps at most per pass.
const MAX_STEPS: usize = 300;
/// The sections agree when every node's places differ by at most this share of the tolerance.
const AGREEMENT: f64 = 1e-2;
/// Linearisations of the curvature variation at most (Gauss–Newton steps, each anchored where
/// the smoothing started, each halved until it lowers the objective).
const LINEARISATIONS: usize = 8;
/// Halvings of a Gauss–Newton step at most.
const MAX_STEP_HALVINGS: usize = 6;
/// The smoothing has converged when a step lowers the objective by less than this share.
const CONVERGED_DECREASE: f64 = 0.02;
/// Passes that weigh control points over their tolerance more.
const REWEIGHT_PASSES: usize = 8;
/// The share of a tolerance the control points may use (as the relaxation's).
const TOLERANCE_SHARE: f64 = 0.99;

/// `μ` of a smoothing length `ℓ` (m): the weight of `∫ κ′² ds` that halves a wave of length `ℓ`.
pub(crate) fn weight_of_length(length: f64) -> f64 {
    (length / std::f64::consts::TAU).powi(6)
}

/// A linear residual `value + coefficients · x[first..]` in a section's unknowns.
struct Residual {
    first: usize,
    coefficients: Vec<f64>,
    value: f64,
}

/// A node row of a section: `coefficients · x[first..]` is how far its point at the node moves
/// along axis `axis`; `dual` is ADMM's scaled multiplier.
struct NodeRow {
    node: usize,
    axis: usize,
    first: usize,
    coefficients: Vec<f64>,
    dual: f64,
}

/// One section's smoothing problem. Its unknowns are two per control point, its moves along
/// the in-plane normal and tangent at the point's Greville abscissa (`x[2j]`, `x[2j + 1]`):
/// the normal moves smooth it, the tangential ones let a node slide along the line its
/// planes share wherever the section crosses it.
struct Section {
    curve: usize,
    /// The curve's degree (a joint's curvature jump couples `2p + 1` control points: the band
    /// of the normal equations).
    degree: usize,
    /// Per control point: the unit in-plane normal and tangent.
    dirs: Vec<[DVec3; 2]>,
    /// `√μ`-scaled curvature-variation residuals (empty for a follower).
    residuals: Vec<Residual>,
    /// Smooth-joint rows.
    joints: Vec<Residual>,
    rows: Vec<NodeRow>,
    /// Data weight per control point.
    weights: Vec<f64>,
    /// Per unknown: how far the control point already is from where the smoothing started,
    /// along the unknown's direction (the data term is `w (x + offset)²`).
    offsets: Vec<f64>,
    factor: Option<Banded>,
    /// The unknowns (the ends' stay zero).
    x: Vec<f64>,
}

/// The control points next to a section's ends (1 and n − 2), which move only along the end
/// tangents, so that the section leaves its ends (on the keel, the profile, the deck) in the
/// direction it did: the surface's tangent plane there comes from these tangents, and a
/// section turned at its end would leave a step in the ribbon of its neighbour along the
/// profile (KCS's bulb: 0.12° where the clean hull has 0.007°).
fn end_tangents(n: usize) -> Vec<usize> {
    match n {
        0..=2 => Vec::new(),
        3 => vec![1],
        _ => vec![1, n - 2],
    }
}

/// The end control point `j` is next to, for `j` in [`end_tangents`].
fn end_neighbour(j: usize, n: usize) -> Option<usize> {
    if n < 3 {
        None
    } else if j == 1 {
        Some(0)
    } else if j == n - 2 {
        Some(n - 1)
    } else {
        None
    }
}

/// The signed curvature `(C′ × C″)·n / |C′|³` and its derivative `dκ/dt`, with their
/// directional derivatives along the changes `(δ1, δ2, δ3)` of `C′, C″, C‴`.
fn curvature_terms(c: [DVec3; 3], delta: [DVec3; 3], n: DVec3) -> ([f64; 2], [f64; 2]) {
    let [c1, c2, c3] = c;
    let [d1, d2, d3] = delta;
    let s = c1.length();
    let ds = c1.dot(d1) / s;
    let (s2, s3) = (s * s, s * s * s);
    let kappa = c1.cross(c2).dot(n) / s3;
    let dkappa = (d1.cross(c2) + c1.cross(d2)).dot(n) / s3 - 3.0 * kappa * ds / s;
    let a = c1.cross(c3).dot(n);
    let b = c1.dot(c2);
    let kp = a / s3 - 3.0 * kappa * b / s2;
    let da = (d1.cross(c3) + c1.cross(d3)).dot(n);
    let db = d1.dot(c2) + c1.dot(d2);
    let dkp = da / s3
        - 3.0 * a * ds / (s3 * s)
        - 3.0 * dkappa * b / s2
        - 3.0 * kappa * (db / s2 - 2.0 * b * ds / s3);
    ([kappa, kp], [dkappa, dkp])
}

/// `C′, C″, C‴` at `t` in knot span `span` of the polynomial `curve` (control points `pts`),
/// and the basis derivatives there.
fn span_derivatives(
    curve: &NurbsCurve,
    pts: &[DVec3],
    span: usize,
    t: f64,
) -> ([DVec3; 3], [[f64; MAX_ORDER]; 4]) {
    let p = curve.degree();
    let mut ders = [[0.0; MAX_ORDER]; 4];
    ders_basis_funs(curve.knots(), span, t, p, 3, &mut ders);
    let mut c = [DVec3::ZERO; 3];
    for (m, cm) in c.iter_mut().enumerate() {
        for k in 0..=p {
            *cm += ders[m + 1][k] * pts[span - p + k];
        }
    }
    (c, ders)
}

/// How a section's curvature variation counts in its smoothing, fixed where the smoothing
/// starts: `μ` and its Gauss–Legendre points (16 per knot span) with their weights.
struct Penalty {
    mu: f64,
    /// `(span, t, w)`: the point's quadrature weight (parameter units) over `1 + (κ ℓ)²`, `κ`
    /// the curvature there at the scale of the smoothing length `ℓ`: a turn tighter than `ℓ`
    /// is form (a bilge, a bulb's nose), smoothed the less the tighter it is, while noise on a
    /// flat or gently curved stretch is smoothed whole.
    points: Vec<(usize, f64, f64)>,
}

impl Penalty {
    /// The penalty of `curve` smoothed at length `length`, or `None` for a curve the smoothing
    /// only carries along: a rational one (its derivatives are not linear in its control
    /// points), or one of degree below 3 (a quadratic's unfairness is in its curvature's jumps
    /// at the knots, which an integral over the spans does not see).
    fn of(curve: &NurbsCurve, length: f64) -> Option<Penalty> {
        let p = curve.degree();
        if length <= 0.0 || p < 3 || curve.is_rational() {
            return None;
        }
        let pts = curve.control_points();
        let knots = curve.knots();
        let (start, end) = curve.domain();
        // The quadrature points: span, parameter, weight, arc length at the point, point.
        let mut quadrature: Vec<(usize, f64, f64, f64, DVec3)> = Vec::new();
        let mut arc = 0.0;
        for span in p..pts.len() {
            let (t0, t1) = (knots[span], knots[span + 1]);
            if !(t1 > t0 && t0 >= start && t1 <= end) {
                continue;
            }
            for (a, b) in [(t0, 0.5 * (t0 + t1)), (0.5 * (t0 + t1), t1)] {
                let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
                for &(x, w) in &GL8 {
                    let t = mid + half * x;
                    let (cs, _) = span_derivatives(curve, &pts, span, t);
                    let speed = cs[0].length();
                    arc += w * half * speed;
                    if speed > 0.0 {
                        quadrature.push((span, t, w * half, arc, curve.point(t)));
                    }
                }
            }
        }
        // The curvature at the scale of the smoothing length: of the circle through the points
        // half a length either side (the ends nearer), which noise of a few millimetres
        // barely moves (by 8δ/ℓ², 0.006 /m for 3 mm at 2 m).
        let at = |s: f64| -> DVec3 {
            let i = quadrature.partition_point(|q| q.3 < s);
            match (i.checked_sub(1).map(|k| quadrature[k]), quadrature.get(i)) {
                (Some(a), Some(b)) if b.3 > a.3 => a.4.lerp(b.4, (s - a.3) / (b.3 - a.3)),
                (Some(a), _) => a.4,
                (None, Some(b)) => b.4,
                (None, None) => DVec3::ZERO,
            }
        };
        let points = quadrature
            .iter()
            .map(|&(span, t, w, s, q)| {
                let (a, b) = (at(s - 0.5 * length), at(s + 0.5 * length));
                let (ab, aq, qb) = (a.distance(b), a.distance(q), q.distance(b));
                let twice_area = (q - a).cross(b - a).length();
                let kappa = if ab * aq * qb > 0.0 {
                    2.0 * twice_area / (ab * aq * qb)
                } else {
                    0.0
                };
                (span, t, w / (1.0 + (kappa * length).powi(2)))
            })
            .collect();
        Some(Penalty {
            mu: weight_of_length(length),
            points,
        })
    }

    /// The penalty's value for `curve` as it is now: `μ Σ w κ′² / |C′|`, its ∫ κ′² ds so
    /// weighted.
    fn value(&self, curve: &NurbsCurve, plane: DVec3) -> f64 {
        let pts = curve.control_points();
        let mut total = 0.0;
        for &(span, t, weight) in &self.points {
            let (cs, _) = span_derivatives(curve, &pts, span, t);
            let speed = cs[0].length();
            if speed > 0.0 {
                let kp = curvature_terms(cs, [DVec3::ZERO; 3], plane).0[1];
                total += weight * kp * kp / speed;
            }
        }
        self.mu * total
    }
}

impl Section {
    /// The problem of `curve` (movable, in the plane normal to `axis`), smoothing by
    /// `penalty` (`None`: it only follows its nodes).
    fn new(
        state: &State,
        curve: usize,
        axis: usize,
        penalty: Option<&Penalty>,
        start: &[DVec3],
        weights: Vec<f64>,
    ) -> Section {
        let c = &state.curves[curve];
        let pts = c.control_points();
        let n = pts.len();
        let p = c.degree();
        let plane = DVec3::AXES[axis];
        let dirs: Vec<[DVec3; 2]> = greville(c)
            .into_iter()
            .enumerate()
            .map(|(j, g)| {
                let mut tangent = c.derivs(g).d1;
                tangent[axis] = 0.0;
                let tangent = match tangent.try_normalize() {
                    Some(t) => t,
                    None => {
                        let mut chord = pts[(j + 1).min(n - 1)] - pts[j.saturating_sub(1)];
                        chord[axis] = 0.0;
                        chord.try_normalize().unwrap_or(in_plane(axis)[0])
                    }
                };
                // Next to an end, along the end's tangent: the control point slides along it,
                // and its move across it is held ([`end_tangents`]).
                let tangent = match end_neighbour(j, n) {
                    Some(e) => {
                        let mut chord = pts[j] - pts[e];
                        chord[axis] = 0.0;
                        chord.try_normalize().unwrap_or(tangent)
                    }
                    None => tangent,
                };
                [plane.cross(tangent), tangent]
            })
            .collect();
        // The coefficients, over the unknowns of control points `first..`, of a functional
        // whose change for a move `d` of control point `first + k` is `along(k, d)`.
        let expand = |count: usize, along: &dyn Fn(usize, DVec3) -> f64, first: usize| {
            (0..count)
                .flat_map(|k| dirs[first + k].map(|d| along(k, d)))
                .collect::<Vec<f64>>()
        };
        let mut residuals = Vec::new();
        if let Some(pen) = penalty {
            let root = pen.mu.sqrt();
            for &(span, t, weight) in &pen.points {
                let (cs, ders) = span_derivatives(c, &pts, span, t);
                let speed = cs[0].length();
                if speed == 0.0 {
                    continue;
                }
                let scale = root * (weight / speed).sqrt();
                let along = |k: usize, d: DVec3| {
                    let delta = [ders[1][k] * d, ders[2][k] * d, ders[3][k] * d];
                    scale * curvature_terms(cs, delta, plane).1[1]
                };
                residuals.push(Residual {
                    first: 2 * (span - p),
                    coefficients: expand(p + 1, &along, span - p),
                    value: scale * curvature_terms(cs, [DVec3::ZERO; 3], plane).0[1],
                });
            }
        }
        let mut joints = Vec::new();
        for j in end_tangents(n) {
            joints.push(Residual {
                first: 2 * j,
                coefficients: vec![1.0],
                value: 0.0,
            });
        }
        for (first, coefficients) in smooth_joint_rows(c) {
            for dir in in_plane(axis) {
                let along = |k: usize, d: DVec3| coefficients[k] * d.dot(dir);
                joints.push(Residual {
                    first: 2 * first,
                    coefficients: expand(JOINT_ROW_WIDTH, &along, first),
                    value: 0.0,
                });
            }
        }
        let mut rows = Vec::new();
        for &(t, node) in &state.nodes.on_curve[curve] {
            let row = point_row(c, t, DVec3::X, 0.0);
            let count = (p + 1).min(n - row.first);
            for a in in_plane_axes(axis) {
                let dir = DVec3::AXES[a];
                let along = |k: usize, d: DVec3| row.coefficients[k] * d.dot(dir);
                rows.push(NodeRow {
                    node,
                    axis: a,
                    first: 2 * row.first,
                    coefficients: expand(count, &along, row.first),
                    dual: 0.0,
                });
            }
        }
        let offsets = dirs
            .iter()
            .zip(pts.iter().zip(start))
            .flat_map(|(d, (p, p0))| d.map(|d| (*p - *p0).dot(d)))
            .collect();
        Section {
            curve,
            degree: p,
            dirs,
            residuals,
            joints,
            rows,
            weights,
            offsets,
            factor: None,
            x: vec![0.0; 2 * n],
        }
    }

    /// The number of control points.
    fn len(&self) -> usize {
        self.dirs.len()
    }

    /// Factor the normal equations (the interior control points' unknowns); `false` when they
    /// are singular.
    fn factor(&mut self) -> bool {
        let n = self.len();
        if n < 3 {
            self.factor = None;
            return true;
        }
        let unknowns = 2 * (n - 2);
        let band = 2 * (2 * self.degree + 1).max(JOINT_ROW_WIDTH) + 1;
        let mut m = Banded::zeros(unknowns, band);
        for j in 1..n - 1 {
            for d in 0..2 {
                m.add(2 * (j - 1) + d, 2 * (j - 1) + d, self.weights[j]);
            }
        }
        let mut add = |first: usize, c: &[f64], w: f64| {
            // The ends' unknowns (0, 1 and the last two) are dropped, the rest shifted by 2.
            let c: Vec<f64> = c
                .iter()
                .enumerate()
                .map(|(k, &v)| {
                    let i = first + k;
                    if i < 2 || i >= 2 * n - 2 {
                        0.0
                    } else {
                        v
                    }
                })
                .collect();
            if first >= 2 {
                m.add_outer(first - 2, &c, w);
            } else {
                m.add_outer(0, &c[2 - first..], w);
            }
        };
        for r in &self.residuals {
            add(r.first, &r.coefficients, 1.0);
        }
        for r in &self.joints {
            add(r.first, &r.coefficients, JOINT_WEIGHT);
        }
        for r in &self.rows {
            add(r.first, &r.coefficients, NODE_PULL);
        }
        self.factor = m.factor();
        self.factor.is_some()
    }

    /// `coefficients · x[first..]`.
    fn dot(&self, first: usize, c: &[f64]) -> f64 {
        c.iter()
            .enumerate()
            .filter_map(|(k, v)| self.x.get(first + k).map(|x| v * x))
            .sum()
    }

    /// Solve for the unknowns with the nodes pulled toward `target(node, axis) − dual`.
    fn solve(&mut self, target: &dyn Fn(usize, usize) -> f64) {
        let n = self.len();
        let Some(factor) = &self.factor else {
            return;
        };
        let mut rhs: Vec<f64> = (0..2 * n)
            .map(|i| -self.weights[i / 2] * self.offsets[i])
            .collect();
        for r in &self.residuals {
            for (k, c) in r.coefficients.iter().enumerate() {
                if let Some(x) = rhs.get_mut(r.first + k) {
                    *x -= c * r.value;
                }
            }
        }
        for r in &self.rows {
            let goal = target(r.node, r.axis) - r.dual;
            for (k, c) in r.coefficients.iter().enumerate() {
                if let Some(x) = rhs.get_mut(r.first + k) {
                    *x += NODE_PULL * c * goal;
                }
            }
        }
        let mut inner: Vec<f64> = rhs[2..2 * n - 2].to_vec();
        factor.solve(&mut inner);
        self.x.fill(0.0);
        self.x[2..2 * n - 2].copy_from_slice(&inner);
    }

    /// The control points' moves.
    fn moves(&self) -> Vec<DVec3> {
        self.dirs
            .iter()
            .enumerate()
            .map(|(j, [nd, td])| self.x[2 * j] * *nd + self.x[2 * j + 1] * *td)
            .collect()
    }
}

/// Smooth every movable section of `state` along itself (module doc): `lengths[c]` is curve
/// `c`'s smoothing length (m; 0 for a section that only follows its nodes, `None` for a curve
/// that does not move). Returns the sections moved.
///
/// Errors: a moved curve f64 cannot hold (naming it).
pub(crate) fn smooth_sections(state: &mut State, lengths: &[Option<f64>]) -> Result<usize, Error> {
    let start: Vec<Vec<DVec3>> = state
        .curves
        .iter()
        .map(NurbsCurve::control_points)
        .collect();
    let penalties: Vec<Option<Penalty>> = lengths
        .iter()
        .enumerate()
        .map(|(c, l)| {
            state.axes[c]?;
            Penalty::of(&state.curves[c], (*l)?)
        })
        .collect();
    let mut weights: Vec<Vec<f64>> = state.curves.iter().map(length_shares).collect();
    let mut moved = vec![false; start.len()];
    // Per curve: its share of the objective, as the curves are now.
    let planes: Vec<Option<DVec3>> = state
        .axes
        .iter()
        .map(|a| a.map(|a| DVec3::AXES[a]))
        .collect();
    let objective = |c: usize, curve: &NurbsCurve, weights: &[f64]| -> f64 {
        let data: f64 = curve
            .control_points()
            .iter()
            .zip(&start[c])
            .zip(weights)
            .map(|((p, p0), w)| w * p.distance_squared(*p0))
            .sum();
        match (&penalties[c], planes[c]) {
            (Some(pen), Some(plane)) => data + pen.value(curve, plane),
            _ => data,
        }
    };
    for _ in 0..LINEARISATIONS {
        let Some(plan) = smooth_step(state, lengths, &penalties, &start, &mut weights) else {
            break;
        };
        let before: f64 = plan
            .iter()
            .map(|(c, _)| objective(*c, &state.curves[*c], &weights[*c]))
            .sum();
        // The longest step within the tolerances, halved until it lowers the objective (the
        // linearisation overshoots where a section turns tightly).
        let mut lambda = state.step_length(&plan);
        let mut taken = None;
        for _ in 0..=MAX_STEP_HALVINGS {
            if lambda <= 0.0 {
                break;
            }
            let mut after = 0.0;
            for (c, change) in &plan {
                let curve = state.moved(*c, change, lambda)?;
                after += objective(*c, &curve, &weights[*c]);
            }
            if after < before {
                taken = Some((lambda, after));
                break;
            }
            lambda *= 0.5;
        }
        let Some((lambda, after)) = taken else {
            break;
        };
        for (c, change) in &plan {
            moved[*c] |= change.iter().any(|d| *d != DVec3::ZERO);
        }
        state.apply(&plan, lambda)?;
        if before - after <= CONVERGED_DECREASE * before {
            break;
        }
    }
    Ok(moved.iter().filter(|m| **m).count())
}

/// The length of section each control point stands for (m): half the distance between its
/// neighbours' Greville points (a quarter of the next at the ends), so that the data term
/// `Σ w_j |ΔP_j|²` is `∫ |ΔC|² ds` and a smoothing length means the same on a section of few
/// control points as on one of many.
fn length_shares(curve: &NurbsCurve) -> Vec<f64> {
    let g: Vec<DVec3> = greville(curve)
        .into_iter()
        .map(|t| curve.point(t))
        .collect();
    let n = g.len();
    let floor = 1e-9;
    (0..n)
        .map(|j| {
            let a = g[j.saturating_sub(1)];
            let b = g[(j + 1).min(n - 1)];
            (0.5 * a.distance(b)).max(floor)
        })
        .collect()
}

/// One linearisation of the smoothing at the sections as they are, anchored at `start` (the
/// control points before the smoothing) with the control points' data `weights` (raised
/// where a point would leave its tolerance): the moves from where the sections are, or `None`
/// when nothing is to be smoothed or the nodes' rows are dependent.
fn smooth_step(
    state: &State,
    lengths: &[Option<f64>],
    penalties: &[Option<Penalty>],
    start: &[Vec<DVec3>],
    weights: &mut [Vec<f64>],
) -> Option<Plan> {
    let mut sections: Vec<Section> = lengths
        .iter()
        .enumerate()
        .filter_map(|(c, l)| {
            l.as_ref()?;
            Some(Section::new(
                state,
                c,
                state.axes[c]?,
                penalties[c].as_ref(),
                &start[c],
                weights[c].clone(),
            ))
        })
        .collect();
    if sections.iter().all(|s| s.residuals.is_empty()) {
        return None;
    }
    // A section whose equations are singular does not move; its nodes stay.
    let mut pinned = vec![false; state.nodes.freedom.len()];
    for s in &mut sections {
        if !s.factor() {
            for r in &s.rows {
                pinned[r.node] = true;
            }
            s.residuals.clear();
            s.rows.clear();
            s.joints.clear();
            s.factor();
        }
    }
    // Nodes no section may move, and those of sections not smoothed at all (a curve with two
    // control points) stay.
    for s in &sections {
        if s.len() < 3 {
            for r in &s.rows {
                pinned[r.node] = true;
            }
        }
    }
    let free = |node: usize, axis: usize, pinned: &[bool]| -> bool {
        !pinned[node] && matches!(state.nodes.freedom[node], Freedom::Along(a) if a[axis])
    };
    let tolerance = state
        .tolerance
        .iter()
        .copied()
        .filter(|t| *t > 0.0)
        .fold(f64::INFINITY, f64::min);
    let agreement = AGREEMENT
        * if tolerance.is_finite() {
            tolerance
        } else {
            1.0
        };
    let nodes = state.nodes.freedom.len();
    let mut place = vec![[0.0f64; 3]; nodes];
    let mut plan: Plan = Vec::new();
    for pass in 0..=REWEIGHT_PASSES {
        for _ in 0..MAX_STEPS {
            for s in &mut sections {
                s.solve(&|node, axis| place[node][axis]);
            }
            // Each free node to the mean of its sections' places.
            let mut sum = vec![[0.0f64; 3]; nodes];
            let mut count = vec![[0usize; 3]; nodes];
            for s in &sections {
                for r in &s.rows {
                    if free(r.node, r.axis, &pinned) {
                        sum[r.node][r.axis] += s.dot(r.first, &r.coefficients) + r.dual;
                        count[r.node][r.axis] += 1;
                    }
                }
            }
            let mut change: f64 = 0.0;
            for v in 0..nodes {
                for a in 0..3 {
                    let new = if count[v][a] > 0 {
                        sum[v][a] / count[v][a] as f64
                    } else {
                        0.0
                    };
                    change = change.max((new - place[v][a]).abs());
                    place[v][a] = new;
                }
            }
            let mut apart: f64 = 0.0;
            for s in &mut sections {
                for i in 0..s.rows.len() {
                    let (first, node, axis) = (s.rows[i].first, s.rows[i].node, s.rows[i].axis);
                    let miss = s.dot(first, &s.rows[i].coefficients) - place[node][axis];
                    s.rows[i].dual += miss;
                    apart = apart.max(miss.abs());
                }
            }
            if apart <= agreement && change <= agreement {
                break;
            }
        }
        // Exactly through the nodes' places, the joints kept.
        plan.clear();
        for s in &sections {
            let curve = &state.curves[s.curve];
            let Some(axis) = state.axes[s.curve] else {
                continue;
            };
            let dirs = in_plane(axis);
            let mut rows: Vec<Row> = joint_rows(curve, &dirs);
            let (start, end) = curve.domain();
            let on = &state.nodes.on_curve[s.curve];
            for t in [start, end] {
                if !on.iter().any(|&(u, _)| u == t) {
                    for dir in dirs {
                        rows.push(point_row(curve, t, dir, 0.0));
                    }
                }
            }
            for &(t, node) in on {
                for a in in_plane_axes(axis) {
                    let by = if free(node, a, &pinned) {
                        place[node][a]
                    } else {
                        0.0
                    };
                    rows.push(point_row(curve, t, DVec3::AXES[a], by));
                }
            }
            let wish = s.moves();
            // The end tangents held; where that is one condition too many next to a node at
            // the end, the node's rows alone.
            let mut held = rows.clone();
            for j in end_tangents(s.len()) {
                let mut coefficients = [0.0; MAX_ORDER];
                coefficients[0] = 1.0;
                held.push(Row {
                    first: j,
                    coefficients,
                    direction: s.dirs[j][0],
                    value: 0.0,
                });
            }
            // The end tangents held unless that is one condition too many (a node next to the
            // end: nearly dependent rows, whose least change departs far from the consensus).
            let departure = |change: &Vec<DVec3>| {
                change
                    .iter()
                    .zip(&wish)
                    .map(|(c, w)| c.distance(*w))
                    .fold(0.0, f64::max)
            };
            let allowance = 0.1 * state.tolerance[s.curve];
            // Dependent rows (nodes too close for the control points between them): the
            // smoothing leaves the hull as it is, and the relaxation has it.
            let change = match (
                least_change(&wish, &held, curve.order()),
                least_change(&wish, &rows, curve.order()),
            ) {
                (Some(h), Some(f)) if departure(&h) <= 2.0 * departure(&f) + allowance => h,
                (_, Some(f)) => f,
                (h, None) => h?,
            };
            plan.push((s.curve, change));
        }
        if pass == REWEIGHT_PASSES {
            break;
        }
        // Control points over their tolerance weigh more.
        let mut over = false;
        for (s, (c, change)) in sections.iter_mut().zip(&plan) {
            let limit = TOLERANCE_SHARE * state.tolerance[*c];
            let points = state.curves[*c].control_points();
            for (j, ((p, p0), d)) in points
                .iter()
                .zip(&state.original[*c])
                .zip(change)
                .enumerate()
            {
                let moved = (*p + *d - *p0).length();
                if moved > limit {
                    over = true;
                    s.weights[j] *= (4.0f64).max(4.0 * (moved / limit).powi(2));
                }
            }
        }
        if !over {
            break;
        }
        for s in &mut sections {
            s.factor();
        }
    }
    for s in &sections {
        weights[s.curve].clone_from(&s.weights);
    }
    Some(plan)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curvature_terms_match_a_circle_and_their_derivatives_match_differences() {
        // A circle of radius 2 run at speed 3: κ = 1/2 (counter-clockwise about z), κ′ = 0.
        let (r, w) = (2.0, 1.5);
        let c = [
            DVec3::new(0.0, r * w, 0.0),
            DVec3::new(-r * w * w, 0.0, 0.0),
            DVec3::new(0.0, -r * w * w * w, 0.0),
        ];
        let ([kappa, kp], _) = curvature_terms(c, [DVec3::ZERO; 3], DVec3::Z);
        assert!(
            (kappa - 0.5).abs() < 1e-12 && kp.abs() < 1e-12,
            "{kappa} {kp}"
        );
        // Directional derivatives against central differences, on a general point.
        let c = [
            DVec3::new(1.0, 0.3, 0.0),
            DVec3::new(-0.2, 0.7, 0.0),
            DVec3::new(0.4, -0.1, 0.0),
        ];
        let delta = [
            DVec3::new(0.1, -0.2, 0.0),
            DVec3::new(0.3, 0.05, 0.0),
            DVec3::new(-0.2, 0.4, 0.0),
        ];
        let (_, d) = curvature_terms(c, delta, DVec3::Z);
        let h = 1e-6;
        let at = |s: f64| {
            let moved = [0, 1, 2].map(|k| c[k] + s * delta[k]);
            curvature_terms(moved, [DVec3::ZERO; 3], DVec3::Z).0
        };
        let (a, b) = (at(h), at(-h));
        for k in 0..2 {
            let fd = (a[k] - b[k]) / (2.0 * h);
            assert!((fd - d[k]).abs() < 1e-7, "term {k}: {} against {fd}", d[k]);
        }
    }

    #[test]
    fn the_smoothing_length_halves_its_own_wave() {
        // 1 / (1 + μ ω⁶) at ω = 2π/ℓ is 1/2.
        let l = 1.7;
        let omega = std::f64::consts::TAU / l;
        let gain = 1.0 / (1.0 + weight_of_length(l) * omega.powi(6));
        assert!((gain - 0.5).abs() < 1e-12, "{gain}");
    }
}
