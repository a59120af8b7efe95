//! The rotation system of a curve network on a curved surface: at every node, a surface normal
//! estimated from the incident tangents, oriented consistently over each connected part, and
//! the incident edges sorted counter-clockwise about it (H-rep paper §5.2: "the number of edges
//! bounding a patch … is resolved by the system").

use glam::DVec3;

use crate::curve::BezierDecomposition;

/// Below this sine of the angle between two tangents they are taken as parallel, so they do
/// not define a plane (about 0.06°).
const PARALLEL_SINE: f64 = 1e-3;

/// A curve's derivative at a node counts as vanishing when the distance it predicts over the
/// whole stretch (its length times the parameter length) is below this, relative to the size
/// of the coordinates (`1 + |p|`): near the f64 rounding of the positions.
const VANISHING_DERIVATIVE: f64 = 1e-9;

/// Where the derivative vanishes, the leaving direction is the chord to the point this
/// fraction of the stretch's parameter length along it.
const CHORD_STEP: f64 = 1e-3;

/// Unit direction in which a stretch `[t_from → t_to]` of a curve leaves `t_from`: the
/// one-sided derivative on the stretch's side, or the chord to a nearby point where the
/// derivative vanishes.
pub(crate) fn leaving_direction(
    curve: &BezierDecomposition,
    t_from: f64,
    t_to: f64,
    cache: &mut EvalCache,
) -> DVec3 {
    let forward = t_to > t_from;
    let (p0, d1) = cache.eval(curve, t_from, forward);
    let d = if forward { d1 } else { -d1 };
    let step = (t_to - t_from).abs();
    if d.length() * step > VANISHING_DERIVATIVE * (1.0 + p0.length()) {
        return d.normalize();
    }
    (curve.point(t_from + CHORD_STEP * (t_to - t_from)) - p0).normalize_or_zero()
}

/// The last evaluation of [`leaving_direction`], by curve, parameter and piece: the two
/// half-edges leaving one node along one curve (forward on the edge after it, backward on the
/// edge before it) evaluate the same piece at the same parameter unless the node is at a
/// piece boundary.
#[derive(Default)]
pub(crate) struct EvalCache {
    curve: usize,
    key: Option<(u64, usize)>,
    value: (DVec3, DVec3),
}

impl EvalCache {
    /// Start on curve `curve` (forgets the evaluation of any other curve).
    pub(super) fn on_curve(&mut self, curve: usize) {
        if self.curve != curve {
            self.curve = curve;
            self.key = None;
        }
    }

    fn eval(&mut self, curve: &BezierDecomposition, t: f64, after: bool) -> (DVec3, DVec3) {
        let key = (t.to_bits(), curve.piece_at(t, after));
        if self.key != Some(key) {
            self.value = curve.point_tangent_in(key.1, t);
            self.key = Some(key);
        }
        self.value
    }
}

/// A node's surface normal from its tangents, before orientation
/// ([`orient_normals`](super::orientation::orient_normals)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RawNormal {
    /// The unit normal, either sign ([`raw_normal`]).
    pub normal: DVec3,
    /// How well the tangents define it ([`confidence`]): orientation starts from the most
    /// confident node of each part.
    pub confidence: f64,
}

/// The surface normal at a node from the unit tangents of its edges (unoriented), or `None`
/// when all tangents are parallel.
///
/// With three or more tangents: the normal of the least-squares plane through their tips
/// (the tips of tangents in a tangent plane lie in it; at a cone-like node, such as the corner
/// of a box, the plane through the tips is perpendicular to the cone's axis). The normal is the
/// row of the tips' covariance cofactors with the largest determinant (exact for coplanar
/// tips). With two tangents, or when the tips are collinear: their cross products, each signed
/// to agree with the largest one, summed. `plane` is the tips' plane ([`tip_plane`]), worked
/// out once for this and [`off_plane`].
pub(crate) fn raw_normal(tangents: &[DVec3], plane: Option<DVec3>) -> Option<DVec3> {
    if let Some(n) = plane {
        return Some(n);
    }
    let mut best = DVec3::ZERO;
    for (i, a) in tangents.iter().enumerate() {
        for b in &tangents[i + 1..] {
            let c = a.cross(*b);
            if c.length_squared() > best.length_squared() {
                best = c;
            }
        }
    }
    if best.length() < PARALLEL_SINE {
        return None;
    }
    let mut sum = DVec3::ZERO;
    for (i, a) in tangents.iter().enumerate() {
        for b in &tangents[i + 1..] {
            let c = a.cross(*b);
            sum += if c.dot(best) >= 0.0 { c } else { -c };
        }
    }
    Some(sum.normalize())
}

/// How well a set of tangents defines a plane: the largest sine between two of them (the
/// confidence of a node's [`raw_normal`], which
/// [`orient_normals`](super::orientation::orient_normals) starts from).
pub(crate) fn confidence(tangents: &[DVec3]) -> f64 {
    let mut best: f64 = 0.0;
    for (i, a) in tangents.iter().enumerate() {
        for b in &tangents[i + 1..] {
            best = best.max(a.cross(*b).length());
        }
    }
    best
}

/// Largest distance of a tangent tip from the least-squares plane through the tips (the plane
/// of [`raw_normal`]); 0 for fewer than four tangents, whose tips always fit a plane. Tips of
/// tangents in one smooth surface lie near that plane; a large value means several surface
/// sheets meet at the node. `plane` is the tips' plane ([`tip_plane`]).
pub(crate) fn off_plane(tangents: &[DVec3], plane: Option<DVec3>) -> f64 {
    if tangents.len() < 4 {
        return 0.0;
    }
    let Some(n) = plane else {
        return 0.0;
    };
    let c = tangents.iter().copied().sum::<DVec3>() / tangents.len() as f64;
    tangents
        .iter()
        .map(|t| (*t - c).dot(n).abs())
        .fold(0.0, f64::max)
}

/// The normal of the least-squares plane through the tangents' tips when there are three or
/// more and they are not collinear (what [`raw_normal`] and [`off_plane`] start from).
pub(crate) fn tip_plane(tangents: &[DVec3]) -> Option<DVec3> {
    if tangents.len() >= 3 {
        plane_normal(tangents)
    } else {
        None
    }
}

/// Normal of the least-squares plane through points (here: tangent tips), `None` when they are
/// (nearly) collinear.
fn plane_normal(points: &[DVec3]) -> Option<DVec3> {
    let c = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let (mut xx, mut xy, mut xz, mut yy, mut yz, mut zz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in points {
        let r = *p - c;
        xx += r.x * r.x;
        xy += r.x * r.y;
        xz += r.x * r.z;
        yy += r.y * r.y;
        yz += r.y * r.z;
        zz += r.z * r.z;
    }
    let det_x = yy * zz - yz * yz;
    let det_y = xx * zz - xz * xz;
    let det_z = xx * yy - xy * xy;
    let det_max = det_x.max(det_y).max(det_z);
    let scale = (xx + yy + zz) * (xx + yy + zz);
    if det_max.is_nan() || det_max <= PARALLEL_SINE * PARALLEL_SINE * scale {
        return None;
    }
    let n = if det_max == det_x {
        DVec3::new(det_x, xz * yz - xy * zz, xy * yz - xz * yy)
    } else if det_max == det_y {
        DVec3::new(xz * yz - xy * zz, det_y, xy * xz - yz * xx)
    } else {
        DVec3::new(xy * yz - xz * yy, xy * xz - yz * xx, det_z)
    };
    n.try_normalize()
}

/// Tangent angles (radians) closer than this are a tie, broken further along the edges.
const TANGENT_TIE: f64 = 1e-6;

/// Sort directions counter-clockwise about `normal`; writes the permutation into `idx`.
/// `fallback(i)` gives a second direction for entry `i` (further along the edge) that breaks
/// ties between edges leaving with the same tangent; it is only called for such ties. `keys`
/// is a work buffer.
pub(crate) fn ccw_order(
    normal: DVec3,
    dirs: &[DVec3],
    fallback: &dyn Fn(usize) -> DVec3,
    keys: &mut Vec<f64>,
    idx: &mut Vec<usize>,
) {
    let project = |d: DVec3| d - normal * d.dot(normal);
    let e1 = dirs
        .iter()
        .map(|d| project(*d))
        .find(|p| p.length() > PARALLEL_SINE)
        .map_or_else(|| normal.any_orthonormal_vector(), DVec3::normalize);
    let e2 = normal.cross(e1);
    let angle = |d: DVec3| {
        let p = project(d);
        p.dot(e2).atan2(p.dot(e1))
    };
    keys.clear();
    keys.extend(dirs.iter().map(|d| angle(*d)));
    idx.clear();
    idx.extend(0..dirs.len());
    idx.sort_by(|&a, &b| keys[a].total_cmp(&keys[b]));
    // Runs of (nearly) equal tangent angles are ordered by the direction further along.
    let mut start = 0;
    while start < idx.len() {
        let mut end = start + 1;
        while end < idx.len() && keys[idx[end]] - keys[idx[end - 1]] < TANGENT_TIE {
            end += 1;
        }
        if end - start > 1 {
            let base = keys[idx[start]];
            let rel = |i: usize| {
                let d = angle(fallback(i)) - base;
                (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
            };
            let mut run: Vec<(f64, usize)> = idx[start..end].iter().map(|&i| (rel(i), i)).collect();
            run.sort_by(|(ra, ia), (rb, ib)| ra.total_cmp(rb).then(ia.cmp(ib)));
            for (k, (_, i)) in run.into_iter().enumerate() {
                idx[start + k] = i;
            }
        }
        start = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ccw_order_of_a_plus_sign() {
        let dirs = [DVec3::Y, DVec3::NEG_X, DVec3::X, DVec3::NEG_Y];
        let mut order = Vec::new();
        ccw_order(DVec3::Z, &dirs, &|i| dirs[i], &mut Vec::new(), &mut order);
        // Starting from +Y (the first direction): -X, -Y, +X counter-clockwise about +Z.
        let pos = |i: usize| order.iter().position(|&k| k == i).expect("present");
        let cyc = |a: usize, b: usize| (pos(b) + 4 - pos(a)) % 4;
        assert_eq!(cyc(0, 1), 1, "-X follows +Y");
        assert_eq!(cyc(0, 3), 2, "-Y opposite +Y");
        assert_eq!(cyc(0, 2), 3, "+X last");
    }

    #[test]
    fn equal_tangents_are_ordered_further_along() {
        // Two edges leave along +X; one bends to +Y, the other to -Y. Counter-clockwise about
        // +Z: the one bending to -Y comes first, then the one bending to +Y, then -X.
        let dirs = [DVec3::X, DVec3::NEG_X, DVec3::X];
        let further = [
            DVec3::new(1.0, 0.1, 0.0),
            DVec3::NEG_X,
            DVec3::new(1.0, -0.1, 0.0),
        ];
        let mut order = Vec::new();
        ccw_order(
            DVec3::Z,
            &dirs,
            &|i| further[i],
            &mut Vec::new(),
            &mut order,
        );
        let pos = |i: usize| order.iter().position(|&k| k == i).expect("present");
        assert_eq!(
            (pos(0) + 3 - pos(2)) % 3,
            1,
            "+Y bender right after the -Y bender"
        );
    }

    #[test]
    fn raw_normal_of_a_box_corner_is_its_diagonal() {
        let ts = [DVec3::X, DVec3::Y, DVec3::Z];
        let n = raw_normal(&ts, tip_plane(&ts)).expect("a plane");
        assert!(
            n.cross(DVec3::ONE).length() < 1e-12,
            "normal along (1,1,1), got {n}"
        );
    }

    #[test]
    fn raw_normal_of_a_t_joint_is_the_plane_normal() {
        let ts = [DVec3::X, DVec3::NEG_X, DVec3::Y];
        let n = raw_normal(&ts, tip_plane(&ts)).expect("a plane");
        assert!(
            n.cross(DVec3::Z).length() < 1e-12,
            "normal along z, got {n}"
        );
        assert!(
            raw_normal(&[DVec3::X, DVec3::NEG_X], None).is_none(),
            "collinear: no plane"
        );
    }
}
