//! The parameter domain of a patch: a convex polygon with one edge per face side.
//!
//! The Charrot–Gregory construction (H-rep paper §3.2.1, Fig. 7, eq. 1) works on a regular
//! N-gon: for a domain point X, `d_i` is its perpendicular distance to domain side `i` and the
//! side parameter is `s_i = d_{i−1} / (d_{i−1} + d_{i+1})` (eq. 1a; eq. 1b is `1 − s_{i−1}`).
//! batten uses the regular N-gon of circumradius 1 with side 0 at the bottom, and for four
//! sides the unit square `[0, 1]²`, on which `s_0 = u` and `s_1 = v` exactly, so the 4-sided
//! Gregory patch and the 4-sided Charrot–Gregory patch share one domain.

use glam::DVec2;

/// The most sides a face may have: evaluation works in fixed-size stack arrays of this length
/// (no allocation per sample).
pub const MAX_SIDES: usize = 16;

/// A convex, counter-clockwise domain polygon: the unit square for 4 sides, the regular N-gon
/// (circumradius 1, side 0 horizontal at the bottom) otherwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    n: usize,
    vertices: [DVec2; MAX_SIDES],
    /// Inward unit normals of the sides.
    normals: [DVec2; MAX_SIDES],
}

impl Domain {
    /// The domain for an `n`-sided face, `3 <= n <= MAX_SIDES` (clamped into that range).
    pub fn new(n: usize) -> Domain {
        let n = n.clamp(3, MAX_SIDES);
        let mut vertices = [DVec2::ZERO; MAX_SIDES];
        if n == 4 {
            vertices[..4].copy_from_slice(&[
                DVec2::new(0.0, 0.0),
                DVec2::new(1.0, 0.0),
                DVec2::new(1.0, 1.0),
                DVec2::new(0.0, 1.0),
            ]);
        } else {
            let step = std::f64::consts::TAU / n as f64;
            let start = -std::f64::consts::FRAC_PI_2 - 0.5 * step;
            for (k, v) in vertices[..n].iter_mut().enumerate() {
                let a = start + step * k as f64;
                *v = DVec2::new(a.cos(), a.sin());
            }
        }
        let mut normals = [DVec2::ZERO; MAX_SIDES];
        for i in 0..n {
            let e = vertices[(i + 1) % n] - vertices[i];
            normals[i] = e.perp().normalize();
        }
        Domain {
            n,
            vertices,
            normals,
        }
    }

    /// Number of sides.
    pub fn sides(&self) -> usize {
        self.n
    }

    /// The polygon's vertices; vertex `i` is where domain side `i` starts.
    pub fn vertices(&self) -> Vec<[f64; 2]> {
        self.vertices[..self.n]
            .iter()
            .map(|v| v.to_array())
            .collect()
    }

    /// The centroid of the vertices.
    pub fn centre(&self) -> [f64; 2] {
        self.centre_v().to_array()
    }

    pub(crate) fn centre_v(&self) -> DVec2 {
        self.vertices[..self.n].iter().copied().sum::<DVec2>() / self.n as f64
    }

    pub(crate) fn vertex(&self, i: usize) -> DVec2 {
        self.vertices[i % self.n]
    }

    /// The domain point at parameter `s ∈ [0, 1]` along side `i` (from vertex `i` to `i + 1`).
    pub fn side_point(&self, i: usize, s: f64) -> [f64; 2] {
        self.side_point_v(i, s).to_array()
    }

    pub(crate) fn side_point_v(&self, i: usize, s: f64) -> DVec2 {
        let (a, b) = (self.vertex(i), self.vertex(i + 1));
        if s >= 1.0 {
            b
        } else {
            a + (b - a) * s
        }
    }

    /// The inward unit normal of side `i`.
    pub(crate) fn inward(&self, i: usize) -> DVec2 {
        self.normals[i % self.n]
    }

    /// Signed distance of `x` to the line of side `i`, positive inside.
    #[inline]
    pub(crate) fn distance(&self, i: usize, x: DVec2) -> f64 {
        (x - self.vertices[i]).dot(self.normals[i])
    }

    /// The distances of `x` to every side (negative ones taken as 0), in the first
    /// [`Domain::sides`] entries: the `d_i` of eq. 1.
    #[inline]
    pub(crate) fn distances(&self, x: DVec2) -> [f64; MAX_SIDES] {
        let mut d = [0.0; MAX_SIDES];
        for (i, di) in d[..self.n].iter_mut().enumerate() {
            *di = self.distance(i, x).max(0.0);
        }
        d
    }

    /// The side parameter of side `i` from the distances `d` ([`Domain::distances`]): eq. 1a,
    /// `s_i = d_{i−1} / (d_{i−1} + d_{i+1})`, guarded where it is 0/0 (only at the corner
    /// opposite a side of a triangle, where the patches give that side no weight).
    #[inline]
    pub(crate) fn side_parameter(&self, d: &[f64; MAX_SIDES], i: usize) -> f64 {
        let n = self.n;
        let (a, b) = (d[(i + n - 1) % n], d[(i + 1) % n]);
        if a + b > 0.0 {
            (a / (a + b)).clamp(0.0, 1.0)
        } else {
            0.5
        }
    }

    /// Whether `x` lies inside or on the polygon.
    pub fn contains(&self, x: [f64; 2]) -> bool {
        let x = DVec2::from(x);
        (0..self.n).all(|i| self.distance(i, x) >= 0.0)
    }

    /// The unit direction of the side `x` lies on (within 1e-12 of the unit domain), from its
    /// vertex `i` to `i + 1`; None inside the domain or at a corner (on two sides).
    pub(crate) fn side_through(&self, x: DVec2) -> Option<DVec2> {
        let mut on = (0..self.n).filter(|&i| self.distance(i, x).abs() <= 1e-12);
        let i = on.next()?;
        if on.next().is_some() {
            return None;
        }
        (self.vertex(i + 1) - self.vertex(i)).try_normalize()
    }

    /// `x` if inside, else the nearest point of the polygon's boundary (NaN maps to the centre).
    pub(crate) fn clamp(&self, x: DVec2) -> DVec2 {
        if !x.is_finite() {
            return self.centre_v();
        }
        if (0..self.n).all(|i| self.distance(i, x) >= 0.0) {
            return x;
        }
        let mut best = x;
        let mut best_d = f64::INFINITY;
        for i in 0..self.n {
            let (a, b) = (self.vertex(i), self.vertex(i + 1));
            let e = b - a;
            let t = ((x - a).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            let p = a + e * t;
            let d = (x - p).length_squared();
            if d < best_d {
                best_d = d;
                best = p;
            }
        }
        best
    }
}

/// The inside points of `k` rings on the unit square (the tessellation's rings of a 4-sided
/// face) as lattice indices `(i, j)`, the point `(i, j) / (2k)`, in the mesh's vertex order:
/// ring `r`'s corners are `(r, r)` to `(2k − r, 2k − r)` and its `k − r` intervals a side
/// are 2 steps each; then the centre `(k, k)`. Every ring's points share the `2k + 1` columns
/// and rows of the lattice, so a Gregory patch samples its sides' ribbons once per column and
/// row (`Patch::eval_square_rings`).
pub(crate) fn square_rings(k: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::with_capacity(2 * k * k.saturating_sub(1) + 1);
    let top = 2 * k;
    for r in 1..k {
        let m = k - r;
        out.extend((0..m).map(|j| (r + 2 * j, r)));
        out.extend((0..m).map(|j| (top - r, r + 2 * j)));
        out.extend((0..m).map(|j| (top - r - 2 * j, top - r)));
        out.extend((0..m).map(|j| (r, top - r - 2 * j)));
    }
    out.push((k, k));
    out
}

/// The parameter of lattice index `i` of [`square_rings`] for `k` rings: `i / (2k)`.
pub(crate) fn lattice_parameter(k: usize) -> impl Fn(usize) -> f64 {
    let steps = (2 * k) as f64;
    move |i| i as f64 / steps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_side_through_a_point_is_found_on_one_side_only() {
        let d = Domain::new(4);
        let (a, b) = (d.vertex(0), d.vertex(1));
        let mid = (a + b) * 0.5;
        let e = d.side_through(mid).expect("on side 0");
        assert!((e - (b - a).normalize()).length() < 1e-15, "{e}");
        assert!(d.side_through(d.centre_v()).is_none(), "inside");
        assert!(d.side_through(a).is_none(), "a corner is on two sides");
        let five = Domain::new(5);
        let (p, q) = (five.vertex(2), five.vertex(3));
        let e = five.side_through(p + (q - p) * 0.3).expect("on side 2");
        assert!((e - (q - p).normalize()).length() < 1e-12, "{e}");
    }
}
