//! The relaxation of Pla et al. (1998, §4, figure 2): the section of largest bias is moved by
//! λ ≤ 1 toward its filtered section, λ as large as every tolerance allows, its nodes carried
//! along the crossing sections, and again, family after family.

use glam::DVec3;

use crate::curve::{BezierDecomposition, NurbsCurve};
use crate::error::Error;
use crate::fair::{curvature_variation, fairness_metrics};

use super::families::Family;
use super::filter::{section_bias, SectionBias, SectionFilter, Sections};
use super::least_change::{joint_rows, least_change, point_row, Row};
use super::nodes::{Freedom, Nodes};

/// The share of a tolerance the control points may use: the curves go to Blender in single
/// precision, which rounds a coordinate of 250 m by up to 8 µm (as `import_sections` keeps).
const TOLERANCE_SHARE: f64 = 0.99;

/// A move must lower the curvature variation of the curves it moves by at least this share
/// ([`State::fairer`]).
const FAIRER_BY: f64 = 0.1;

/// A move whose largest control-point change is below this share of the model tolerance moves
/// nothing a designer could see: the section is stuck (until its neighbours move).
const NEGLIGIBLE_MOVE: f64 = 1e-3;

/// The sections as they are being faired.
pub(crate) struct State {
    /// Every curve's name, for messages.
    pub names: Vec<String>,
    /// Every curve of the network, movable ones with a knot at each node.
    pub curves: Vec<NurbsCurve>,
    /// Their Bézier decompositions (for the neighbours' closest points).
    pub decomps: Vec<BezierDecomposition>,
    /// The control points the fairing started from (the tolerance is measured from them).
    pub original: Vec<Vec<DVec3>>,
    /// Per curve: its tolerance (m); 0 for a fixed curve.
    pub tolerance: Vec<f64>,
    /// Per curve: the axis normal to its plane for a movable section.
    pub axes: Vec<Option<usize>>,
    /// The nodes and how they may move.
    pub nodes: Nodes,
    /// Per curve: the moves it took part in (as the section moved or carried along).
    pub moves: Vec<usize>,
    /// The model tolerance (m).
    pub model_tolerance: f64,
}

/// The indices of the in-plane axes of a section whose plane is normal to `axis`.
pub(crate) fn in_plane_axes(axis: usize) -> [usize; 2] {
    match axis {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// The in-plane axes of a section whose plane is normal to `axis`.
pub(crate) fn in_plane(axis: usize) -> [DVec3; 2] {
    in_plane_axes(axis).map(|a| DVec3::AXES[a])
}

/// A planned move: per curve taking part, its control-point changes at λ = 1.
pub(crate) type Plan = Vec<(usize, Vec<DVec3>)>;

impl State {
    /// The bias of the section `curve` in plane `group` of `family`.
    pub(crate) fn bias(
        &self,
        family: &Family,
        group: usize,
        curve: usize,
        filter: SectionFilter,
    ) -> SectionBias {
        section_bias(
            family,
            group,
            curve,
            Sections {
                curves: &self.curves,
                decomps: &self.decomps,
                nodes: &self.nodes,
            },
            filter,
            self.model_tolerance,
        )
    }

    /// The move of section `k` toward `wish` (per control point, at λ = 1), kept to what its
    /// nodes allow, and the moves of the sections crossing it that carry its nodes along (each
    /// the least change that moves its point at the node by as much and keeps its other nodes).
    /// `None` when some curve cannot make its share (its constraints are dependent).
    pub(crate) fn plan(&self, k: usize, wish: &[DVec3]) -> Option<Plan> {
        let axis = self.axes[k]?;
        let dirs = in_plane(axis);
        let curve = &self.curves[k];
        let mut rows: Vec<Row> = joint_rows(curve, &dirs);
        for &(t, node) in &self.nodes.on_curve[k] {
            for a in in_plane_axes(axis) {
                let free = match self.nodes.freedom[node] {
                    Freedom::Fixed => false,
                    Freedom::Along(along) => along[a],
                };
                if !free {
                    rows.push(point_row(curve, t, DVec3::AXES[a], 0.0));
                }
            }
        }
        let change = least_change(wish, &rows, curve.order())?;
        let mut plan: Plan = vec![(k, change)];
        // The nodes moved, by how much.
        let moved: Vec<(usize, DVec3)> = self.nodes.on_curve[k]
            .iter()
            .filter(|&&(_, node)| self.nodes.freedom[node] != Freedom::Fixed)
            .map(|&(t, node)| (node, displacement(curve, &plan[0].1, t)))
            .filter(|(_, d)| *d != DVec3::ZERO)
            .collect();
        let mut followers: Vec<usize> = moved
            .iter()
            .flat_map(|&(node, _)| self.nodes.incidences[node].iter().map(|&(c, _)| c))
            .filter(|&c| c != k)
            .collect();
        followers.sort_unstable();
        followers.dedup();
        for c in followers {
            let curve = &self.curves[c];
            let dirs = in_plane(self.axes[c]?);
            let mut rows = joint_rows(curve, &dirs);
            for &(t, node) in &self.nodes.on_curve[c] {
                let by = moved
                    .iter()
                    .find(|(m, _)| *m == node)
                    .map_or(DVec3::ZERO, |(_, d)| *d);
                for dir in dirs {
                    rows.push(point_row(curve, t, dir, by.dot(dir)));
                }
            }
            let wish = vec![DVec3::ZERO; curve.control_point_count()];
            plan.push((c, least_change(&wish, &rows, curve.order())?));
        }
        Some(plan)
    }

    /// The largest λ in [0, 1] for which every control point of `plan` stays within its
    /// curve's tolerance (times [`TOLERANCE_SHARE`]) of where it started: then every point of
    /// every curve does (a B-spline point is a convex combination of its control points).
    pub(crate) fn step_length(&self, plan: &Plan) -> f64 {
        let mut lambda: f64 = 1.0;
        for (c, change) in plan {
            let tol = TOLERANCE_SHARE * self.tolerance[*c];
            let points = self.curves[*c].control_points();
            for ((p, p0), d) in points.iter().zip(&self.original[*c]).zip(change) {
                let e = *p - *p0;
                let dd = d.length_squared();
                if dd == 0.0 {
                    continue;
                }
                // |e + λ d| ≤ tol: the larger root of dd λ² + 2 e·d λ + |e|² − tol² = 0.
                let ed = e.dot(*d);
                let disc = ed * ed - dd * (e.length_squared() - tol * tol);
                let root = if disc > 0.0 {
                    ((-ed + disc.sqrt()) / dd).max(0.0)
                } else {
                    0.0
                };
                lambda = lambda.min(root);
            }
        }
        lambda
    }

    /// Whether `plan` at `lambda` moves any control point by a visible amount.
    pub(crate) fn moves_visibly(&self, plan: &Plan, lambda: f64) -> bool {
        let largest = plan
            .iter()
            .flat_map(|(_, change)| change.iter().map(|d| d.length()))
            .fold(0.0, f64::max);
        lambda * largest > NEGLIGIBLE_MOVE * self.model_tolerance
    }

    /// Whether `plan` at `lambda` leaves the curves it moves fairer: the summed curvature
    /// variation ∫κ′² ds of those of degree 3 or more lower by [`FAIRER_BY`] at least (a
    /// quadratic's unfairness is in its curvature's jumps at the knots, which the integral
    /// over the spans does not see; a plan of quadratics only has this test met), and no more
    /// inflections among them all.
    /// A move toward the filtered section that does not is the filter's error, not the
    /// section's: on a real hull the cubic filter is not the section even without noise (KCS:
    /// the clean hull relaxed unguarded goes from 55 inflections to 90 and ∫κ′² ds up 14 %,
    /// points moving 9.9 mm; guarded to any decrease, 7 moves still spend 9.8 mm of the
    /// tolerance for 3 % off ∫κ′² ds; guarded to 10 %, it stays as it is).
    pub(crate) fn fairer(&self, plan: &Plan, lambda: f64) -> bool {
        let (mut before, mut after) = (0.0, 0.0);
        let (mut inflections_before, mut inflections_after) = (0usize, 0usize);
        for (c, change) in plan {
            let old = &self.curves[*c];
            let Ok(new) = self.moved(*c, change, lambda) else {
                return false;
            };
            if old.degree() >= 3 {
                before += curvature_variation(old);
                after += curvature_variation(&new);
            }
            inflections_before += fairness_metrics(old).inflections;
            inflections_after += fairness_metrics(&new).inflections;
        }
        after <= (1.0 - FAIRER_BY) * before && inflections_after <= inflections_before
    }

    /// Curve `c` with its control points changed by `lambda · change` (not applied).
    pub(crate) fn moved(
        &self,
        c: usize,
        change: &[DVec3],
        lambda: f64,
    ) -> Result<NurbsCurve, Error> {
        let points = self.curves[c]
            .control_points()
            .iter()
            .zip(change)
            .map(|(p, d)| *p + lambda * *d)
            .collect();
        self.curves[c]
            .with_control_points(points)
            .map_err(|e| e.named(&self.names[c]))
    }

    /// Apply `plan` at `lambda`.
    pub(crate) fn apply(&mut self, plan: &Plan, lambda: f64) -> Result<(), Error> {
        for (c, change) in plan {
            let curve = self.moved(*c, change, lambda)?;
            self.decomps[*c] = curve.bezier_decomposition();
            self.curves[*c] = curve;
            self.moves[*c] += 1;
        }
        Ok(())
    }
}

/// How far the point at `t` of `curve` moves when its control points change by `change`.
fn displacement(curve: &NurbsCurve, change: &[DVec3], t: f64) -> DVec3 {
    let row = point_row(curve, t, DVec3::X, 0.0);
    row.coefficients
        .iter()
        .enumerate()
        .filter(|(i, _)| row.first + i < change.len())
        .map(|(i, w)| *w * change[row.first + i])
        .sum()
}
