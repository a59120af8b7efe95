//! Input checks and clean-up before fitting: non-finite coordinates, duplicate points, points
//! out of order, and corner (knuckle) detection by turning angle.

use glam::DVec3;

use super::error::FairError;

/// How much longer than a nearest-neighbour ordering the given polyline may be before the points
/// count as out of order. An ordered sampling of a curve is about as short as the greedy
/// nearest-neighbour tour (usually shorter: greedy tours leave stragglers); a shuffled one is
/// many times longer.
const ORDER_RATIO: f64 = 2.0;

/// From this many points on, the nearest-neighbour tour uses a grid rather than an O(m²) scan.
const GRID_POINTS: usize = 400;

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
    // Any tour from the first point reaches the point farthest from it, so it is at least that
    // far: when the polyline is within the ratio of that, it is within the ratio of the tour
    // too (the usual case, a curve that does not turn back on itself, decided in O(m)).
    let reach = points
        .iter()
        .map(|p| (*p - points[0]).length())
        .fold(0.0, f64::max);
    if path_length <= ORDER_RATIO * reach {
        return Ok(());
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

/// Length of the greedy nearest-neighbour tour from the first point (each step to the closest
/// unvisited point, the lowest index among equals).
///
/// Implementation note: the closest unvisited point is found in a uniform grid of cell size
/// `h` (the mean spacing of the points along the polyline), searching cube shells of cells
/// outwards until the best distance found is below the nearest any unsearched cell can be
/// (`r·h` after shell `r`); when the shells would hold more cells than there are unvisited
/// points, by a plain scan of them. The tour is the same as the O(m²) scan's, in near-linear
/// time for points that follow a curve. Below [`GRID_POINTS`] points the plain scan is faster.
fn nearest_neighbour_tour(points: &[DVec3]) -> f64 {
    use rustc_hash::FxHashMap as HashMap;
    let m = points.len();
    let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let h = length / (m - 1) as f64;
    if m < GRID_POINTS || !(h.is_finite() && h > 0.0) {
        return nearest_neighbour_tour_scan(points);
    }
    let cell_of = |p: DVec3| -> [i64; 3] {
        let c = (p / h).floor();
        [c.x as i64, c.y as i64, c.z as i64]
    };
    let mut grid: HashMap<[i64; 3], Vec<usize>> =
        HashMap::with_capacity_and_hasher(m, Default::default());
    for (j, p) in points.iter().enumerate().skip(1) {
        grid.entry(cell_of(*p)).or_default().push(j);
    }
    let mut visited = vec![false; m];
    visited[0] = true;
    let mut unvisited = m - 1;
    let mut current = 0;
    let mut total = 0.0;
    let better = |d: f64, j: usize, best: (f64, usize)| d < best.0 || (d == best.0 && j < best.1);
    for _ in 1..m {
        let here = points[current];
        let centre = cell_of(here);
        let mut best = (f64::INFINITY, usize::MAX);
        let mut r: i64 = 0;
        loop {
            let side = (2 * r + 1) as usize;
            if side * side * side > 8 * unvisited + 27 {
                // The shells have outgrown the unvisited points: scan them instead.
                for (j, p) in points.iter().enumerate() {
                    if !visited[j] {
                        let d = (*p - here).length_squared();
                        if better(d, j, best) {
                            best = (d, j);
                        }
                    }
                }
                break;
            }
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        let key = [centre[0] + dx, centre[1] + dy, centre[2] + dz];
                        if let Some(cell) = grid.get(&key) {
                            for &j in cell {
                                let d = (points[j] - here).length_squared();
                                if better(d, j, best) {
                                    best = (d, j);
                                }
                            }
                        }
                    }
                }
            }
            // Cells outside shell r are at least r·h from `here` (it lies in the centre cell).
            let reach = r as f64 * h;
            if best.0 < reach * reach {
                break;
            }
            r += 1;
        }
        total += best.0.sqrt();
        current = best.1;
        visited[current] = true;
        unvisited -= 1;
        let key = cell_of(points[current]);
        if let Some(cell) = grid.get_mut(&key) {
            cell.retain(|&j| j != current);
            if cell.is_empty() {
                grid.remove(&key);
            }
        }
    }
    total
}

/// The greedy nearest-neighbour tour by plain O(m²) scanning (few points, degenerate spacing).
fn nearest_neighbour_tour_scan(points: &[DVec3]) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_check_accepts_curves_that_turn_back_and_rejects_shuffles() {
        // 200 points round 330° of a circle: the polyline is 2.9 times as long as the farthest
        // point is from the first, so the tour itself decides (and accepts); an open quarter
        // circle is decided by the farthest point alone; both shuffled are rejected.
        for sweep in [330f64, 90.0] {
            let pts: Vec<DVec3> = (0..200)
                .map(|i| {
                    let a = (sweep * f64::from(i) / 199.0).to_radians();
                    DVec3::new(a.cos(), a.sin(), 0.0) * 10.0
                })
                .collect();
            assert!(check_order(&pts).is_ok(), "{sweep}° in order");
            let mut shuffled = pts.clone();
            for i in 1..shuffled.len() {
                shuffled.swap(i, (i * 7919) % pts.len());
            }
            assert!(
                matches!(check_order(&shuffled), Err(FairError::OutOfOrder { .. })),
                "{sweep}° shuffled"
            );
        }
    }

    #[test]
    fn grid_tour_is_the_scanned_tour() {
        // A noisy helix in order, the same shuffled, and one with a far straggler and ties.
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let helix: Vec<DVec3> = (0..900)
            .map(|i| {
                let a = f64::from(i) * 0.02;
                DVec3::new(a.cos() * 5.0, a.sin() * 5.0, 0.1 * a)
                    + DVec3::new(next(), next(), next()) * 0.05
            })
            .collect();
        let mut shuffled = helix.clone();
        for i in (1..shuffled.len()).rev() {
            let j = ((next() + 0.5) * i as f64) as usize;
            shuffled.swap(i, j.min(i));
        }
        let mut grid: Vec<DVec3> = (0..600)
            .map(|i| DVec3::new(f64::from(i % 30), f64::from(i / 30), 0.0))
            .collect();
        grid.push(DVec3::new(1e3, -50.0, 7.0));
        for pts in [&helix, &shuffled, &grid] {
            assert_eq!(
                nearest_neighbour_tour(pts),
                nearest_neighbour_tour_scan(pts),
                "same tour, same length"
            );
        }
    }
}
