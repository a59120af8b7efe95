//! The polynomial B-spline curves and tensor-product surfaces the CAD export writes, and the
//! exact curve operations it builds them with (Piegl & Tiller: knot insertion A5.1, splitting
//! §5.2, linear reparametrisation §6.1).

use glam::DVec3;

use crate::curve::{basis_funs, ders_basis_funs, find_span, NurbsCurve, MAX_ORDER};

/// Degree of every exported curve and surface in both directions (cubic: C² inside a patch,
/// and what every CAD reader takes).
pub const EXPORT_DEGREE: usize = 3;

/// Knots of two boundary curves closer than this (in the unit parameter range) are one knot of
/// the surface: the curve's knot is moved onto the other's, which moves the curve by about
/// this times its parameter speed (1e-12 m on a 1 m edge), and no sliver span is made.
pub const KNOT_MERGE: f64 = 1e-12;

/// The non-zero cubic basis functions of one parameter of a surface and their first
/// derivatives (Piegl & Tiller A2.3): `n[a]` and `dn[a]` belong to control row (or column)
/// `span − degree + a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Basis {
    span: usize,
    n: [f64; EXPORT_DEGREE + 1],
    dn: [f64; EXPORT_DEGREE + 1],
}

impl Basis {
    /// The basis of the clamped `knots` (for `count` control points) at `t` (clamped into
    /// `[0, 1]`).
    fn at(knots: &[f64], count: usize, t: f64) -> Basis {
        let p = EXPORT_DEGREE;
        let t = t.clamp(0.0, 1.0);
        let span = find_span(knots, p, count, t);
        let mut d = [[0.0; MAX_ORDER]; 4];
        ders_basis_funs(knots, span, t, p, 1, &mut d);
        Basis {
            span,
            n: std::array::from_fn(|a| d[0][a]),
            dn: std::array::from_fn(|a| d[1][a]),
        }
    }
}

/// A polynomial tensor-product B-spline surface of [`EXPORT_DEGREE`] in `u` and `v` on
/// `[0, 1]²`: control point `(i, j)` (`i` along `u`) is `control[i * count_v + j]`.
#[derive(Clone, Debug, PartialEq)]
pub struct BsplineSurface {
    /// Clamped knot vector in `u` (`count_u + degree + 1` knots from 0 to 1).
    pub knots_u: Vec<f64>,
    /// Clamped knot vector in `v`.
    pub knots_v: Vec<f64>,
    /// Number of control points along `u`.
    pub count_u: usize,
    /// Number of control points along `v`.
    pub count_v: usize,
    /// The control net, `i` (along `u`) major.
    pub control: Vec<DVec3>,
}

impl BsplineSurface {
    /// The degree in both directions.
    pub fn degree(&self) -> usize {
        EXPORT_DEGREE
    }

    /// Control point `(i, j)`.
    pub fn point_at(&self, i: usize, j: usize) -> DVec3 {
        self.control[i * self.count_v + j]
    }

    /// The surface point at `(u, v)` (clamped into `[0, 1]²`), by the tensor product of the
    /// basis functions (Piegl & Tiller A3.5).
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        let p = EXPORT_DEGREE;
        let (su, nu) = basis(&self.knots_u, self.count_u, u);
        let (sv, nv) = basis(&self.knots_v, self.count_v, v);
        let mut out = DVec3::ZERO;
        for (a, &na) in nu[..=p].iter().enumerate() {
            let row = (su - p + a) * self.count_v + sv - p;
            let acc: DVec3 = self.control[row..=row + p]
                .iter()
                .zip(&nv[..=p])
                .map(|(c, &w)| *c * w)
                .sum();
            out += acc * na;
        }
        out
    }

    /// The surface point and its first partial derivatives `[S, S_u, S_v]` at `(u, v)`
    /// (clamped into `[0, 1]²`), from the basis functions' derivatives (Piegl & Tiller A3.6).
    pub fn eval_derivs(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.eval_derivs_at(&self.basis_u(u), &self.basis_v(v))
    }

    /// The basis functions along `u` at `u` (clamped into `[0, 1]`) and their derivatives: what
    /// [`BsplineSurface::eval_derivs_at`] needs, computed once for every sample on a line
    /// `u = const`.
    pub(crate) fn basis_u(&self, u: f64) -> Basis {
        Basis::at(&self.knots_u, self.count_u, u)
    }

    /// The basis functions along `v` at `v` (see [`BsplineSurface::basis_u`]).
    pub(crate) fn basis_v(&self, v: f64) -> Basis {
        Basis::at(&self.knots_v, self.count_v, v)
    }

    /// [`BsplineSurface::eval_derivs`] from the bases of its two parameters: a grid of samples
    /// takes one basis per row and per column instead of two per sample.
    pub(crate) fn eval_derivs_at(&self, bu: &Basis, bv: &Basis) -> [DVec3; 3] {
        let p = EXPORT_DEGREE;
        let mut out = [DVec3::ZERO; 3];
        for (a, (&n, &dn)) in bu.n.iter().zip(&bu.dn).enumerate() {
            let row = (bu.span - p + a) * self.count_v + bv.span - p;
            let (mut s, mut s_v) = (DVec3::ZERO, DVec3::ZERO);
            for (c, (&m, &dm)) in self.control[row..=row + p]
                .iter()
                .zip(bv.n.iter().zip(&bv.dn))
            {
                s += *c * m;
                s_v += *c * dm;
            }
            out[0] += s * n;
            out[1] += s * dn;
            out[2] += s_v * n;
        }
        out
    }

    /// The same surface with `u` running the other way (its normal `S_u × S_v` flipped).
    pub fn reversed_u(&self) -> BsplineSurface {
        let knots_u = self.knots_u.iter().rev().map(|&k| 1.0 - k).collect();
        let mut control = Vec::with_capacity(self.control.len());
        for i in (0..self.count_u).rev() {
            control.extend_from_slice(&self.control[i * self.count_v..(i + 1) * self.count_v]);
        }
        BsplineSurface {
            knots_u,
            control,
            ..self.clone()
        }
    }

    /// The boundary curves as their control polygons: `v = 0` and `v = 1` (along `u`), `u = 0`
    /// and `u = 1` (along `v`), each from parameter 0 to 1.
    pub fn boundary_rows(&self) -> [Vec<DVec3>; 4] {
        let (nu, nv) = (self.count_u, self.count_v);
        [
            (0..nu).map(|i| self.point_at(i, 0)).collect(),
            (0..nu).map(|i| self.point_at(i, nv - 1)).collect(),
            (0..nv).map(|j| self.point_at(0, j)).collect(),
            (0..nv).map(|j| self.point_at(nu - 1, j)).collect(),
        ]
    }
}

/// The span and the non-zero basis functions of a cubic clamped knot vector at `t`.
#[inline]
pub(crate) fn basis(knots: &[f64], count: usize, t: f64) -> (usize, [f64; MAX_ORDER]) {
    let t = t.clamp(0.0, 1.0);
    let span = find_span(knots, EXPORT_DEGREE, count, t);
    let mut n = [0.0; MAX_ORDER];
    basis_funs(knots, span, t, EXPORT_DEGREE, &mut n);
    (span, n)
}

/// The clamped cubic knot vector on `[0, 1]` with these interior knots (ascending).
pub(crate) fn clamped(interior: &[f64]) -> Vec<f64> {
    let mut k = vec![0.0; EXPORT_DEGREE + 1];
    k.extend_from_slice(interior);
    k.extend(std::iter::repeat_n(1.0, EXPORT_DEGREE + 1));
    k
}

/// The interior knots of a clamped knot vector (with their multiplicities).
pub(crate) fn interior(knots: &[f64]) -> &[f64] {
    &knots[EXPORT_DEGREE + 1..knots.len() - EXPORT_DEGREE - 1]
}

/// A polynomial cubic curve from its knots and control points (the invariants hold by
/// construction in this module; `None` if f64 cannot hold them).
pub(crate) fn curve(knots: Vec<f64>, points: Vec<DVec3>) -> Option<NurbsCurve> {
    NurbsCurve::try_new(EXPORT_DEGREE, knots, points, None).ok()
}

/// `curve` on `[a, b]` (inside its domain), reparametrised linearly onto `[0, 1]`, running
/// from `C(a)` to `C(b)` (reversed when `a > b`).
pub(crate) fn sub_curve(c: &NurbsCurve, a: f64, b: f64) -> Option<NurbsCurve> {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let (start, end) = c.domain();
    let mut piece = c.clone();
    if lo > start {
        piece = piece.split(lo).ok()?.1;
    }
    if hi < end {
        piece = piece.split(hi).ok()?.0;
    }
    let piece = if a > b { piece.reversed() } else { piece };
    let (s, e) = piece.domain();
    let knots = piece
        .knots()
        .iter()
        .map(|&k| ((k - s) / (e - s)).clamp(0.0, 1.0))
        .collect();
    curve(knots, piece.control_points())
}

/// Curves on `[0, 1]` joined end to end into one curve on `[0, 1]`, curve `k` placed on
/// `[breaks[k], breaks[k + 1]]` (`breaks` ascending from 0 to 1): a C0 joint of full
/// multiplicity at every break, the joint's control point the earlier curve's end.
pub(crate) fn join(curves: &[NurbsCurve], breaks: &[f64]) -> Option<NurbsCurve> {
    let p = EXPORT_DEGREE;
    let mut knots = vec![0.0; p + 1];
    let mut points: Vec<DVec3> = Vec::new();
    for (k, c) in curves.iter().enumerate() {
        let (a, b) = (breaks[k], breaks[k + 1]);
        knots.extend(interior(c.knots()).iter().map(|&t| a + (b - a) * t));
        knots.extend(std::iter::repeat_n(b, p));
        let cps = c.control_points();
        let skip = usize::from(k > 0);
        points.extend_from_slice(&cps[skip..]);
    }
    // The last break's copies become the clamped end.
    knots.truncate(knots.len() - p);
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    curve(knots, points)
}

/// The sorted union (with multiplicities, the larger of the two) of two interior knot lists,
/// knots within [`KNOT_MERGE`] taken as one.
pub(crate) fn knot_union(a: &[f64], b: &[f64]) -> Vec<f64> {
    let distinct = |k: &[f64]| -> Vec<(f64, usize)> {
        let mut out: Vec<(f64, usize)> = Vec::new();
        for &t in k {
            match out.last_mut() {
                Some((u, m)) if (t - *u).abs() <= KNOT_MERGE => *m += 1,
                _ => out.push((t, 1)),
            }
        }
        out
    };
    let (da, db) = (distinct(a), distinct(b));
    let mut all: Vec<(f64, usize)> = da.iter().chain(&db).copied().collect();
    all.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut merged: Vec<(f64, usize)> = Vec::new();
    for (t, m) in all {
        match merged.last_mut() {
            Some((u, n)) if (t - *u).abs() <= KNOT_MERGE => *n = (*n).max(m),
            _ => merged.push((t, m)),
        }
    }
    merged
        .into_iter()
        .flat_map(|(t, m)| std::iter::repeat_n(t, m.min(EXPORT_DEGREE)))
        .collect()
}

/// `c` with exactly the interior knots `target` (a superset of its own up to [`KNOT_MERGE`]):
/// its own knots snapped onto the target's, then the missing ones inserted (Boehm, A5.1;
/// the shape does not change). Its control points, one per basis function of `target`.
pub(crate) fn refined_points(c: &NurbsCurve, target: &[f64]) -> Option<Vec<DVec3>> {
    let snapped: Vec<f64> = c
        .knots()
        .iter()
        .map(|&k| {
            target
                .iter()
                .copied()
                .find(|&t| (t - k).abs() <= KNOT_MERGE)
                .unwrap_or(k)
        })
        .collect();
    let mut c = curve(snapped, c.control_points())?;
    let mut i = 0;
    while i < target.len() {
        let t = target[i];
        let want = target[i..].iter().take_while(|&&u| u == t).count();
        let have = interior(c.knots()).iter().filter(|&&u| u == t).count();
        if want > have {
            c = c.insert_knot(t, want - have).ok()?;
        }
        i += want;
    }
    let points = c.control_points();
    (points.len() == target.len() + EXPORT_DEGREE + 1).then_some(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave() -> NurbsCurve {
        let pts = (0..7)
            .map(|i| DVec3::new(i as f64, (i as f64).sin(), 0.1 * i as f64))
            .collect();
        curve(clamped(&[0.25, 0.5, 0.75]), pts).expect("a curve")
    }

    #[test]
    fn sub_curve_and_join_keep_the_shape() {
        let c = wave();
        let (a, b) = (
            sub_curve(&c, 0.0, 0.3).unwrap(),
            sub_curve(&c, 0.3, 1.0).unwrap(),
        );
        let j = join(&[a, b], &[0.0, 0.3, 1.0]).unwrap();
        for k in 0..=50 {
            let t = k as f64 / 50.0;
            let d = (j.point(t) - c.point(t)).length();
            assert!(d < 1e-12, "joined curve off by {d} at {t}");
        }
        let r = sub_curve(&c, 0.8, 0.2).unwrap();
        let d = (r.point(0.0) - c.point(0.8)).length() + (r.point(1.0) - c.point(0.2)).length();
        assert!(d < 1e-12, "reversed piece ends off by {d}");
    }

    #[test]
    fn surface_derivatives_are_the_slopes_of_the_surface() {
        let (nu, nv) = (6, 5);
        let control = (0..nu)
            .flat_map(|i| {
                (0..nv).map(move |j| {
                    let (x, y) = (i as f64, j as f64);
                    DVec3::new(x + 0.3 * y, y - 0.2 * x * x, (x * y).sin())
                })
            })
            .collect();
        let s = BsplineSurface {
            knots_u: clamped(&[0.3, 0.5]),
            knots_v: clamped(&[0.6]),
            count_u: nu,
            count_v: nv,
            control,
        };
        let h = 1e-6;
        for &(u, v) in &[(0.1, 0.2), (0.4, 0.7), (0.55, 0.95), (0.9, 0.6)] {
            let [p, su, sv] = s.eval_derivs(u, v);
            assert!(
                (p - s.eval(u, v)).length() < 1e-12,
                "the point at ({u}, {v})"
            );
            let du = (s.eval(u + h, v) - s.eval(u - h, v)) / (2.0 * h);
            let dv = (s.eval(u, v + h) - s.eval(u, v - h)) / (2.0 * h);
            assert!(
                (su - du).length() < 1e-6 * du.length().max(1.0),
                "S_u {su} vs {du}"
            );
            assert!(
                (sv - dv).length() < 1e-6 * dv.length().max(1.0),
                "S_v {sv} vs {dv}"
            );
        }
    }

    #[test]
    fn refining_to_a_union_keeps_the_curve() {
        let c = wave();
        let u = knot_union(interior(c.knots()), &[0.1, 0.5, 0.5 + 1e-14, 0.9]);
        assert_eq!(
            u,
            vec![0.1, 0.25, 0.5, 0.5, 0.75, 0.9],
            "union: near knots are one, doubled"
        );
        let pts = refined_points(&c, &u).unwrap();
        let r = curve(clamped(&u), pts).unwrap();
        for k in 0..=40 {
            let t = k as f64 / 40.0;
            assert!((r.point(t) - c.point(t)).length() < 1e-12, "refined at {t}");
        }
    }
}
