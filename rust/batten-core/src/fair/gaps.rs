//! Between the points: a fit within a tolerance is held within it between its points too.
//!
//! A smoothing spline is measured at its data points only (Dierckx 1993 §5.2; the H-rep paper
//! eq. 9), so where offsets are sparse it may swing between them: the KVLCC2 station 19 runs
//! flat for 2 m on four points at its keel and its fit dipped 24 mm between the first two,
//! within 1 mm of every point; a waterline across the bulb swung 1.4 m between two offsets.
//! A naval architect reads an offsets table as a batten laid through the points, never
//! leaving the neighbourhood of the polygon they make. So after each fit the curve is compared,
//! at [`GAP_FRACTIONS`] of every gap, with the centripetal Catmull–Rom interpolant of the
//! neighbouring four points (Barry & Goldman 1988; centripetal, so it neither overshoots nor
//! loops, Yuksel, Schaefer & Keyser 2011), which is local: it follows a straight run of points
//! exactly and bends only as the points beside a gap do. Where the fit is farther from it than
//! the tolerance plus the interpolant's own bulge from the chord there (the interpolant is
//! only one guess at a curved gap, exact only on a straight one), that interpolant point joins
//! the data and the piece is fitted again, for at most [`GAP_ROUNDS`] rounds.
//!
//! The added points are not data: the fit's report measures the data points only. A refit
//! that cannot meet the tolerance with them (a fixed end tangent the interpolant disagrees
//! with), or that strays farther from the interpolant than the fit before it, gives way to
//! that fit.

use glam::DVec3;

use super::error::FairError;
use super::metrics::distances;
use super::piece::{fit_within, Directions, PieceFit};

/// Where in each gap (fractions of its Catmull–Rom parameter) the fit is compared.
const GAP_FRACTIONS: [f64; 5] = [1.0 / 6.0, 2.0 / 6.0, 0.5, 4.0 / 6.0, 5.0 / 6.0];

/// Most refits with points added between the data.
const GAP_ROUNDS: usize = 4;

/// A point between the data that a fit is held to.
#[derive(Clone, Copy, Debug)]
struct GapPoint {
    /// The gap: between data points `gap` and `gap + 1`.
    gap: usize,
    /// The interpolant's point.
    point: DVec3,
    /// How far the fit may be from it: the tolerance plus its distance from the chord.
    slack: f64,
    /// Whether it has joined the data.
    held: bool,
}

/// [`fit_within`] on `points`, then held within `tol` of the data's local interpolant between
/// the points (see the module docs). The error case is the closest the fit came and the index
/// (into `points`) of the point farthest from it.
pub(crate) fn fit_within_gaps(
    points: &[DVec3],
    degree: usize,
    tol: f64,
    dirs: Directions,
    max_iter: usize,
) -> Result<Result<PieceFit, (f64, usize)>, FairError> {
    let mut gaps: Vec<GapPoint> = (0..points.len().saturating_sub(1))
        .filter(|&i| (points[i + 1] - points[i]).length() > tol)
        .flat_map(|i| {
            GAP_FRACTIONS.map(|f| {
                let point = catmull_rom(points, i, f);
                let chord = points[i].lerp(points[i + 1], f);
                GapPoint {
                    gap: i,
                    point,
                    slack: tol + (point - chord).length(),
                    held: false,
                }
            })
        })
        .filter(|g| g.point.is_finite())
        .collect();
    let mut pts = points.to_vec();
    // For each point of `pts`, the data point it is or follows.
    let mut origin: Vec<usize> = (0..points.len()).collect();
    let probe: Vec<DVec3> = gaps.iter().map(|g| g.point).collect();
    // The fit before, and how far past its slack its worst gap point was.
    let mut last: Option<(PieceFit, f64)> = None;
    let mut round = 0;
    loop {
        let mut fit = match (fit_within(&pts, degree, tol, dirs, max_iter)?, last.take()) {
            (Ok(fit), before) => {
                last = before;
                fit
            }
            (Err(_), Some((met, _))) => return Ok(Ok(met)),
            (Err((achieved, index)), None) => return Ok(Err((achieved, origin[index]))),
        };
        if round > 0 {
            // Measured on the data and the added points together: the report measures again.
            fit.deviation = None;
        }
        let far = distances(&fit.curve, &probe)?;
        let excess = gaps
            .iter()
            .zip(&far)
            .map(|(g, &d)| d - g.slack)
            .fold(f64::NEG_INFINITY, f64::max);
        if let Some((before, worst)) = last.take() {
            // A refit that strays farther between the points than the fit before it (a knot
            // span the added points leave without data) is not taken.
            if excess.partial_cmp(&worst) != Some(std::cmp::Ordering::Less) {
                return Ok(Ok(before));
            }
        }
        if excess <= 0.0 || round >= GAP_ROUNDS {
            return Ok(Ok(fit));
        }
        round += 1;
        for (g, &d) in gaps.iter_mut().zip(&far) {
            if d > g.slack {
                g.held = true;
            }
        }
        last = Some((fit, excess));
        pts.clear();
        origin.clear();
        let mut held = gaps.iter().filter(|g| g.held).peekable();
        for (i, &p) in points.iter().enumerate() {
            pts.push(p);
            origin.push(i);
            while let Some(g) = held.next_if(|g| g.gap == i) {
                pts.push(g.point);
                origin.push(i);
            }
        }
    }
}

/// The centripetal Catmull–Rom point at fraction `f` of the gap between `points[i]` and
/// `points[i + 1]` (Barry & Goldman's pyramid with knot steps `|ΔP|^½`).
fn catmull_rom(points: &[DVec3], i: usize, f: f64) -> DVec3 {
    let n = points.len();
    let p1 = points[i];
    let p2 = points[i + 1];
    // A missing neighbour continues the parabola through the three points nearest the end
    // (the line through two where there are only two).
    let p0 = match i {
        0 if n >= 3 => 3.0 * p1 - 3.0 * p2 + points[2],
        0 => 2.0 * p1 - p2,
        _ => points[i - 1],
    };
    let p3 = match i + 2 {
        j if j < n => points[j],
        _ if i >= 1 => 3.0 * p2 - 3.0 * p1 + points[i - 1],
        _ => 2.0 * p2 - p1,
    };
    let step = |a: DVec3, b: DVec3| (b - a).length().sqrt();
    let t0 = 0.0;
    let t1 = t0 + step(p0, p1);
    let t2 = t1 + step(p1, p2);
    let t3 = t2 + step(p2, p3);
    let t = t1 + f * (t2 - t1);
    let lerp = |a: DVec3, b: DVec3, ta: f64, tb: f64| {
        if tb > ta {
            a * ((tb - t) / (tb - ta)) + b * ((t - ta) / (tb - ta))
        } else {
            a
        }
    };
    let a1 = lerp(p0, p1, t0, t1);
    let a2 = lerp(p1, p2, t1, t2);
    let a3 = lerp(p2, p3, t2, t3);
    let b1 = lerp(a1, a2, t0, t2);
    let b2 = lerp(a2, a3, t1, t3);
    lerp(b1, b2, t1, t2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interpolant_of_a_straight_run_is_the_line() {
        let pts: Vec<DVec3> = [0.0, 0.7, 1.4, 2.0, 2.05]
            .iter()
            .map(|&y| DVec3::new(3.0, y, 0.0))
            .collect();
        for i in 0..pts.len() - 1 {
            for f in GAP_FRACTIONS {
                let p = catmull_rom(&pts, i, f);
                assert!(p.z.abs() < 1e-15 && (p.x - 3.0).abs() < 1e-15, "{p}");
                assert!(p.y > pts[i].y && p.y < pts[i + 1].y, "{p} outside gap {i}");
            }
        }
    }

    #[test]
    fn the_interpolant_passes_near_a_circle_between_its_points() {
        let r = 2.0;
        let pts: Vec<DVec3> = (0..=8)
            .map(|k| {
                let a = f64::from(k) * 0.2;
                DVec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        // Midway between points 3 and 4 lies the circle at angle 0.7.
        let p = catmull_rom(&pts, 3, 0.5);
        assert!((p.length() - r).abs() < 2e-3, "radius {}", p.length());
        assert!(
            (p.y.atan2(p.x) - 0.7).abs() < 1e-3,
            "angle {}",
            p.y.atan2(p.x)
        );
    }
}
