//! Input checks and clean-up before fitting: non-finite coordinates, duplicate points, points
//! out of order, and corner (knuckle) detection by turning angle at the fit's resolution.

use glam::DVec3;

use super::error::FairError;
use super::NOISE_REACH;

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

/// The order check looks at the points this many times the data's reach apart: a step of
/// length `h` between points each within `scale` of the curve is at most `√(1 + (2/4)²)`
/// ≈ 1.12 times as long as the curve between them, far below [`ORDER_RATIO`].
pub(crate) const ORDER_STEP: f64 = 4.0;

/// The points at the resolution `step`: the first, each next one at least `step` from the one
/// kept before, and the last.
pub(crate) fn resolved(points: &[DVec3], step: f64) -> Vec<DVec3> {
    resolved_indices(points, step)
        .into_iter()
        .map(|i| points[i])
        .collect()
}

/// The indices of [`resolved`]`(points, step)`.
pub(crate) fn resolved_indices(points: &[DVec3], step: f64) -> Vec<usize> {
    let m = points.len();
    let mut kept = vec![0];
    let mut last = points[0];
    for (i, &p) in points.iter().enumerate().take(m.saturating_sub(1)).skip(1) {
        if (p - last).length() >= step {
            kept.push(i);
            last = p;
        }
    }
    if m > 1 {
        kept.push(m - 1);
    }
    kept
}

/// Length of the polyline through `points`.
pub(crate) fn polyline_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

/// Reject points that do not follow a curve in order: the polyline through them is more than
/// [`ORDER_RATIO`] times as long as a greedy nearest-neighbour tour from the first point, both
/// measured at the data's resolution: on the points [`ORDER_STEP`]` · scale` apart along the
/// polyline (`scale` is how far the data may stray from the curve), so noise larger than the
/// point spacing does not count as disorder.
pub(crate) fn check_order(points: &[DVec3], scale: f64) -> Result<(), FairError> {
    let m = points.len();
    if m < 4 {
        return Ok(());
    }
    let mut jump_index = 0;
    let mut jump = 0.0;
    for (i, w) in points.windows(2).enumerate() {
        let d = (w[1] - w[0]).length();
        if d > jump {
            jump = d;
            jump_index = i;
        }
    }
    let coarse = resolved(points, ORDER_STEP * scale);
    let path_length = polyline_length(&coarse);
    // Any tour from the first point reaches the point farthest from it, so it is at least that
    // far: when the polyline is within the ratio of that, it is within the ratio of the tour
    // too (the usual case, a curve that does not turn back on itself, decided in O(m)).
    let reach = coarse
        .iter()
        .map(|p| (*p - coarse[0]).length())
        .fold(0.0, f64::max);
    if path_length <= ORDER_RATIO * reach || coarse.len() < 4 {
        return Ok(());
    }
    let ordered_length = nearest_neighbour_tour(&coarse);
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
    let length = polyline_length(points);
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

/// The turn that noise can fake stays below the corner angle on chords of length
/// `w = CORNER_WINDOW · reach / angle`: points off the curve by at most `reach` turn the two
/// chords of length `w` at a point by at most `4·reach / w`, i.e. by half the corner angle (by
/// three quarters when one chord is the half-length chord to an end point, see
/// [`corner_indices`]). The same window keeps smooth bends apart from corners at that
/// resolution: a bend turns its chords by more than the angle only where its radius `R` is
/// below `w / angle`, and such an arc lies within `R·angle²/8 ≤ reach` of the corner of its
/// tangents.
const CORNER_WINDOW: f64 = 8.0;

/// The points of a corner's window that turn (over the window) within this fraction of the
/// corner angle of its sharpest are all candidates for its apex.
const APEX_MARGIN: f64 = 0.125;

/// The median of `|a − (b + c)/2|` for independent Gaussian `a, b, c` of deviation σ, in units
/// of σ: `Φ⁻¹(3/4) · √(3/2)`.
const MEDIAN_CHORD_OFFSET: f64 = 0.6745 * 1.224_744_871;

/// The noise is estimated on chords this many times the data's reach long: long against the
/// noise (at most about a quarter of the reach), so that the offset of a point from a chord is
/// its noise and not the scatter of a cloud of points closer together than the noise.
const NOISE_CHORD: f64 = 2.0;

/// For each point `i`, the nearest points before and after it at least `w` away (`l`, `r`),
/// or the end point where that is at least `end · w` away; `None` where neither exists.
/// Each search starts from the previous point's result, so both are found in one pass.
fn chord_ends(points: &[DVec3], w: f64, end: f64) -> Vec<Option<(usize, usize)>> {
    let m = points.len();
    let dist = |i: usize, j: usize| (points[j] - points[i]).length();
    let mut right: Vec<Option<usize>> = vec![None; m];
    let mut j = 1;
    for (i, r) in right.iter_mut().enumerate().take(m - 1) {
        j = j.max(i + 1);
        while j < m - 1 && dist(i, j) < w {
            j += 1;
        }
        if j == m - 1 && dist(i, j) < end * w {
            break;
        }
        *r = Some(j);
    }
    let mut left: Vec<Option<usize>> = vec![None; m];
    let mut j = m - 2;
    for i in (1..m).rev() {
        j = j.min(i - 1);
        while j > 0 && dist(i, j) < w {
            j -= 1;
        }
        if j == 0 && dist(i, j) < end * w {
            break;
        }
        left[i] = Some(j);
    }
    left.into_iter()
        .zip(right)
        .map(|(l, r)| Some((l?, r?)))
        .collect()
}

/// The noise level σ of points along a curve, `reach` being the most it can be: the median
/// distance of a point from the chord between the points [`NOISE_CHORD`]` · reach` before and
/// after it, over [`MEDIAN_CHORD_OFFSET`] (a robust estimate: corners and the curvature of a
/// few bends do not move a median). For clean points it is what curvature and rounding put
/// there, a small fraction of the spacing.
pub(crate) fn noise_estimate(points: &[DVec3], reach: f64) -> f64 {
    if points.len() < 3 {
        return 0.0;
    }
    let mut offsets: Vec<f64> = chord_ends(points, NOISE_CHORD * reach, 1.0)
        .into_iter()
        .enumerate()
        .filter_map(|(i, ends)| {
            let (l, r) = ends?;
            let chord = points[r] - points[l];
            let len = chord.length();
            Some(if len > 0.0 {
                (points[i] - points[l]).cross(chord).length() / len
            } else {
                (points[i] - points[l]).length()
            })
        })
        .collect();
    if offsets.is_empty() {
        return 0.0;
    }
    let mid = offsets.len() / 2;
    let (_, median, _) = offsets.select_nth_unstable_by(mid, f64::total_cmp);
    *median / MEDIAN_CHORD_OFFSET
}

/// Indices of the interior points where the polyline turns by more than `min_angle` radians
/// over a length that noise cannot bend by that much (a knuckle point of a section). `reach`
/// is the most the data may stray from the curve (the fit's tolerance or noise reach); the
/// noise is taken as the smaller of it and the noise level the points show
/// ([`noise_estimate`], times [`NOISE_REACH`]).
///
/// The turn at point `i` is the angle between the chords `q[i] − q[l]` and `q[r] − q[i]`, with
/// `l` and `r` the nearest points (before and after `i`) at least `w = 8·noise/min_angle` from
/// it (see [`CORNER_WINDOW`]), or the end point where that is at least `w/2` away: where the
/// points are sparser than `w`, the neighbours, so clean data keep their exact knuckle points;
/// where they are dense against the noise, chords long enough that the noise cannot turn them
/// by the corner angle. Points without such chords on both sides are not corners. Of the
/// points that turn by more than `min_angle`, the sharpest marks a corner and no other inside
/// its window does (the others see the same knuckle from beside it); the corner is the point
/// of the window farthest from the chord `q[r] − q[l]`, the apex.
///
/// Implementation note: a chord can be longer than `w` where the curve turns back on itself
/// within a window (the searches run one way, see `chord_ends`).
pub fn corner_indices(points: &[DVec3], min_angle: f64, reach: f64) -> Vec<usize> {
    if points.len() < 3 {
        return Vec::new();
    }
    let noise = reach.min(NOISE_REACH * noise_estimate(points, reach));
    let w = CORNER_WINDOW * noise / min_angle;
    let mut turns: Vec<(f64, usize, usize, usize)> = chord_ends(points, w, 0.5)
        .into_iter()
        .enumerate()
        .filter_map(|(i, ends)| {
            let (l, r) = ends?;
            let a = points[i] - points[l];
            let b = points[r] - points[i];
            if a.length_squared() == 0.0 || b.length_squared() == 0.0 {
                return None;
            }
            let turn = a.angle_between(b);
            (turn > min_angle).then_some((turn, i, l, r))
        })
        .collect();
    // Sharpest first; the lower index among equals.
    turns.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut kept: std::collections::BTreeMap<usize, (usize, usize)> = Default::default();
    for &(_, i, l, r) in &turns {
        // Neither of two corners lies strictly inside the other's window.
        let before = kept.range(..i).next_back();
        let after = kept.range(i + 1..).next();
        let clear = before.is_none_or(|(&a, &(_, ar))| a <= l && ar <= i)
            && after.is_none_or(|(&a, &(al, _))| a >= r && al >= i);
        if clear {
            kept.insert(i, (l, r));
        }
    }
    // The knuckle point: of the window's points that turn by nearly as much (within
    // [`APEX_MARGIN`] of the corner angle), the one whose neighbours turn most, i.e. the apex
    // of clean data; noise moves it no farther than those points reach.
    let turn_of: std::collections::HashMap<usize, f64> =
        turns.iter().map(|&(t, i, _, _)| (i, t)).collect();
    let margin = APEX_MARGIN * min_angle;
    kept.into_iter()
        .map(|(i, (l, r))| {
            let best = turn_of[&i];
            let near = |j: &usize| turn_of.get(j).is_some_and(|&t| t >= best - margin);
            let bend =
                |j: usize| (points[j] - points[j - 1]).angle_between(points[j + 1] - points[j]);
            (l + 1..r)
                .filter(near)
                .fold(i, |at, j| if bend(j) > bend(at) { j } else { at })
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
            assert!(check_order(&pts, 1e-4).is_ok(), "{sweep}° in order");
            let mut shuffled = pts.clone();
            for i in 1..shuffled.len() {
                shuffled.swap(i, (i * 7919) % pts.len());
            }
            assert!(
                matches!(
                    check_order(&shuffled, 1e-4),
                    Err(FairError::OutOfOrder { .. })
                ),
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
