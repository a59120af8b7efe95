//! Curves for the wireframe modules' unit tests.

use glam::DVec3;

use crate::curve::NurbsCurve;
use crate::network::{NetworkCurve, Role};

/// A polyline network curve (degree 1) through `pts`, role free.
pub(super) fn poly(name: &str, pts: &[[f64; 3]]) -> NetworkCurve {
    let n = pts.len();
    let mut knots = vec![0.0, 0.0];
    knots.extend((1..n - 1).map(|i| i as f64));
    knots.extend([(n - 1) as f64; 2]);
    NetworkCurve {
        name: name.to_owned(),
        role: Role::Free,
        curve: NurbsCurve::try_new(
            1,
            knots,
            pts.iter().copied().map(DVec3::from).collect(),
            None,
        )
        .expect("polyline"),
    }
}
