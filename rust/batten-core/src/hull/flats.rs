//! Where the hull's curves run in a plane its surface is tangent to (the flat of side or
//! bottom, [`TangentPlane`]): there the normal field of the edge is the plane's normal, so
//! the faces on both sides of the edge take the plane as their tangent plane along the run,
//! not the blend of the tangent planes at its end nodes. KCS's station 6 runs up the flat of
//! side from z = 7.1 m, between nodes at 7 m and 9 m; blended from the 0.8° the waterline at
//! 7 m crosses the side at, the surface beside it stood 1.35 mm off the flat at z = 8.4 m.

use crate::fair::MIN_FLAT_RUN;
use crate::network::TangentPlane;
use crate::patch::{EdgeNormal, SideSegment};

/// The parameter intervals of `segment` over which its curve lies within `tol` of `plane`:
/// unions of knot spans whose control points all do (so the curve does, by the convex hull
/// property), each at least [`MIN_FLAT_RUN`] between its ends. A curve that crosses or
/// touches the plane has no such interval; a fitted run on a flat is its own piece of the
/// curve (its ends are knots), so its interval is exactly the run.
pub(crate) fn runs_in(segment: &SideSegment, plane: &TangentPlane, tol: f64) -> Vec<(f64, f64)> {
    let curve = &segment.curve;
    let (k, knots, points) = (curve.degree(), curve.knots(), curve.control_points());
    let (lo, hi) = (segment.t0.min(segment.t1), segment.t0.max(segment.t1));
    let mut runs: Vec<(f64, f64)> = Vec::new();
    for i in k..points.len() {
        let (a, b) = (knots[i].max(lo), knots[i + 1].min(hi));
        if a >= b
            || points[i - k..=i]
                .iter()
                .any(|p| plane.distance(*p).abs() > tol)
        {
            continue;
        }
        match runs.last_mut() {
            Some(last) if last.1 == a => last.1 = b,
            _ => runs.push((a, b)),
        }
    }
    runs.retain(|&(a, b)| curve.point(a).distance(curve.point(b)) >= MIN_FLAT_RUN);
    runs
}

/// `normal` (the edge's field) held at each plane's normal where the edge's curve runs in it
/// ([`runs_in`], within `tol`).
pub(crate) fn held_on_planes(
    normal: EdgeNormal,
    segment: &SideSegment,
    planes: &[TangentPlane],
    tol: f64,
) -> EdgeNormal {
    planes.iter().fold(normal, |n, plane| {
        let runs = runs_in(segment, plane, tol);
        if runs.is_empty() {
            n
        } else {
            n.held(&runs, plane.normal)
        }
    })
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::curve::NurbsCurve;

    /// A cubic through the side y = 6 on knot span [2, 3] only (its control points 2..=5 on
    /// it), leaving it on both sides; `lift` moves control point 4 off the side.
    fn segment(lift: f64) -> SideSegment {
        let ys = [5.0, 5.5, 6.0, 6.0, 6.0 - lift, 6.0, 5.5];
        let points = ys
            .iter()
            .enumerate()
            .map(|(i, &y)| DVec3::new(i as f64, y, 0.0))
            .collect();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0];
        SideSegment {
            curve: NurbsCurve::try_new(3, knots, points, None).unwrap(),
            t0: 0.0,
            t1: 4.0,
            name: "wl".to_string(),
            start: None,
            end: None,
            measure: Default::default(),
        }
    }

    const SIDE: TangentPlane = TangentPlane {
        normal: DVec3::Y,
        offset: 6.0,
    };

    #[test]
    fn a_run_on_the_plane_is_the_knot_spans_whose_control_points_are_on_it() {
        assert_eq!(runs_in(&segment(0.0), &SIDE, 1e-4), [(2.0, 3.0)]);
        // Off by more than the tolerance: no run; within it: the run.
        assert!(runs_in(&segment(1e-3), &SIDE, 1e-4).is_empty());
        assert_eq!(runs_in(&segment(5e-5), &SIDE, 1e-4), [(2.0, 3.0)]);
        // Cut to the edge [2.5, 4]: the run is cut too, and too short past 0.3 m it is none.
        let mut cut = segment(0.0);
        cut.t0 = 2.5;
        assert_eq!(runs_in(&cut, &SIDE, 1e-4), [(2.5, 3.0)]);
        cut.t0 = 2.8;
        assert!(runs_in(&cut, &SIDE, 1e-4).is_empty());
        // A plane the curve only crosses.
        let crossed = TangentPlane::try_new(DVec3::Y, 5.8).unwrap();
        assert!(runs_in(&segment(0.0), &crossed, 1e-4).is_empty());
    }

    #[test]
    fn the_field_is_the_planes_normal_along_the_run_and_as_it_was_beyond() {
        let seg = segment(0.0);
        // Normals tilted off the side's, opposite ways, at the ends.
        let (n0, n1) = (
            DVec3::new(0.3, 1.0, 0.1).normalize(),
            DVec3::new(-0.2, -1.0, 0.3).normalize(),
        );
        let field = EdgeNormal::from_normals(&seg, &[(0.0, n0), (4.0, n1)]).unwrap();
        let held = held_on_planes(field.clone(), &seg, &[SIDE], 1e-4);
        for i in 0..=10 {
            let t = 2.0 + 0.1 * f64::from(i);
            let n = held.normal(t);
            assert!(n.cross(DVec3::Y).length() < 1e-15, "at {t}: {n}");
        }
        // Each node keeps its own normal (with the sign the field gave it, aligned along the
        // curve); the field is smooth into the run.
        assert!(held.normal(0.0).distance(n0) < 1e-15);
        assert!(held.normal(4.0).distance(field.normal(4.0)) < 1e-15);
        assert!(held.normal(4.0).cross(n1).length() < 1e-15);
        assert!(held.normal(1.0).dot(field.normal(1.0)) > 0.0);
        let step = |t: f64| held.normal(t).angle_between(held.normal(t + 1e-6));
        assert!(step(2.0 - 1e-6) < 1e-9 && step(3.0) < 1e-9);
        // Without a tangent plane, or with one the curve never runs in, nothing changes.
        let crossed = TangentPlane::try_new(DVec3::Y, 5.8).unwrap();
        assert_eq!(held_on_planes(field.clone(), &seg, &[crossed], 1e-4), field);
    }

    #[test]
    fn a_bad_tangent_plane_is_an_error() {
        for (normal, offset) in [
            (DVec3::ZERO, 1.0),
            (DVec3::new(f64::NAN, 1.0, 0.0), 1.0),
            (DVec3::Y, f64::INFINITY),
        ] {
            assert!(TangentPlane::try_new(normal, offset).is_err());
        }
        let p = TangentPlane::try_new(DVec3::new(0.0, 2.0, 0.0), 12.0).unwrap();
        assert_eq!((p.normal, p.offset), (DVec3::Y, 6.0));
    }
}
