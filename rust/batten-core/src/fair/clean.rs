//! Input checks and clean-up before fitting: non-finite coordinates, duplicate points, points
//! out of order, and corner (knuckle) detection by turning angle.

use glam::DVec3;

use super::error::FairError;

/// How much longer than a nearest-neighbour ordering the given polyline may be before the points
/// count as out of order. An ordered sampling of a curve is about as short as the greedy
/// nearest-neighbour tour (usually shorter: greedy tours leave stragglers); a shuffled one is
/// many times longer.
const ORDER_RATIO: f64 = 2.0;

/// The points after clean-up, with the input index of each.
#[derive(Clone, Debug)]
pub(crate) struct Cleaned {
    pub points: Vec<DVec3>,
    pub index: Vec<usize>,
    pub dropped: usize,
}

/// Reject non-finite coordinates and drop consecutive duplicates: a point within `tolerance` of
/// the last kept point is dropped, except that the last input point replaces the last kept
/// point when they coincide, so both ends of the input are kept exactly.
pub(crate) fn clean(points: &[DVec3], tolerance: f64) -> Result<Cleaned, FairError> {
    for (index, p) in points.iter().enumerate() {
        if let Some(&value) = p.to_array().iter().find(|v| !v.is_finite()) {
            return Err(FairError::NonFinitePoint { index, value });
        }
    }
    let mut kept: Vec<DVec3> = Vec::with_capacity(points.len());
    let mut index = Vec::with_capacity(points.len());
    for (i, &p) in points.iter().enumerate() {
        match kept.last() {
            Some(&last) if (p - last).length() <= tolerance => {
                if i + 1 == points.len() && kept.len() > 1 {
                    *kept.last_mut().expect("non-empty") = p;
                    *index.last_mut().expect("non-empty") = i;
                }
            }
            _ => {
                kept.push(p);
                index.push(i);
            }
        }
    }
    if kept.len() == 1 && points.len() > 1 {
        return Err(FairError::AllPointsIdentical {
            count: points.len(),
            tolerance,
        });
    }
    let dropped = points.len() - kept.len();
    Ok(Cleaned {
        points: kept,
        index,
        dropped,
    })
}

/// Reject points that do not follow a curve in order: the polyline through them is more than
/// [`ORDER_RATIO`] times as long as a greedy nearest-neighbour tour from the first point.
pub(crate) fn check_order(points: &[DVec3]) -> Result<(), FairError> {
    let m = points.len();
    if m < 4 {
        return Ok(());
    }
    let mut path_length = 0.0;
    let (mut jump, mut jump_index) = (0.0, 0);
    for (i, w) in points.windows(2).enumerate() {
        let d = (w[1] - w[0]).length();
        path_length += d;
        if d > jump {
            jump = d;
            jump_index = i;
        }
    }
    let ordered_length = nearest_neighbour_tour(points);
    if path_length > ORDER_RATIO * ordered_length {
        return Err(FairError::OutOfOrder {
            path_length,
            ordered_length,
            jump_index,
        });
    }
    Ok(())
}

/// Length of the greedy nearest-neighbour tour from the first point (O(m²), no allocation per
/// step).
fn nearest_neighbour_tour(points: &[DVec3]) -> f64 {
    let m = points.len();
    let mut visited = vec![false; m];
    let mut current = 0;
    visited[0] = true;
    let mut total = 0.0;
    for _ in 1..m {
        let here = points[current];
        let mut best = (f64::INFINITY, current);
        for (j, p) in points.iter().enumerate() {
            if !visited[j] {
                let d = (*p - here).length_squared();
                if d < best.0 {
                    best = (d, j);
                }
            }
        }
        total += best.0.sqrt();
        current = best.1;
        visited[current] = true;
    }
    total
}

/// Indices of the interior points where the polyline turns by more than `min_angle` radians:
/// the angle between `q[i] − q[i−1]` and `q[i+1] − q[i]` (a knuckle point of a section).
///
/// Implementation note: the turning angle is taken between neighbouring points, so noise that
/// is not small against the point spacing shows up as false corners; pass explicit corners or
/// no angle for noisy data.
pub fn corner_indices(points: &[DVec3], min_angle: f64) -> Vec<usize> {
    (1..points.len().saturating_sub(1))
        .filter(|&i| {
            let a = points[i] - points[i - 1];
            let b = points[i + 1] - points[i];
            a.length_squared() > 0.0 && b.length_squared() > 0.0 && a.angle_between(b) > min_angle
        })
        .collect()
}
