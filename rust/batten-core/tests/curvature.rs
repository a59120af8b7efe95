//! The hull's curvature at its mesh vertices ([`HullSurface::vertex_curvature`]) against the
//! analytic Wigley hull, and its errors.

use batten_core::{build_hull, Error, HullOptions};
mod common;
use common::example;

const L: f64 = 100.0;
const B: f64 = 10.0;
const T: f64 = 6.25;

/// Gaussian and mean curvature (mean positive where convex seen from outside) of the Wigley
/// hull `y = f(x, z) = B/2 (1 − ξ²)(1 − w²)`, `ξ = 2x/L`, `w = (T − z)/T`, as a graph over
/// (x, z) with its normal towards +y (outwards for the port half).
fn wigley_curvature(x: f64, z: f64) -> (f64, f64) {
    let (xi, w) = (2.0 * x / L, (T - z) / T);
    let (a, b) = (1.0 - xi * xi, 1.0 - w * w);
    let fx = 0.5 * B * (-2.0 * xi * 2.0 / L) * b;
    let fz = 0.5 * B * a * (2.0 * w / T);
    let fxx = 0.5 * B * (-8.0 / (L * L)) * b;
    let fzz = 0.5 * B * a * (-2.0 / (T * T));
    let fxz = 0.5 * B * (-4.0 * xi / L) * (2.0 * w / T);
    let g = 1.0 + fx * fx + fz * fz;
    let k = (fxx * fzz - fxz * fxz) / (g * g);
    let h = -((1.0 + fz * fz) * fxx - 2.0 * fx * fz * fxz + (1.0 + fx * fx) * fzz)
        / (2.0 * g.powf(1.5));
    (k, h)
}

#[test]
fn the_wigley_hulls_curvature_at_its_vertices_is_the_analytic_one() {
    let hull = build_hull(&example("wigley_lines.json"), &HullOptions::default()).expect("builds");
    let c = hull
        .vertex_curvature(HullOptions::default().resolution)
        .expect("curvature");
    assert_eq!(c.gaussian.len(), hull.mesh.positions.len());
    let (mut worst_k, mut worst_h, mut n) = (0.0f64, 0.0f64, 0);
    let (mut k_scale, mut h_scale) = (0.0f64, 0.0f64);
    for (i, p) in hull.mesh.positions.iter().enumerate() {
        let [x, _, z] = *p;
        // Inside the hull below the design waterline (the surface is only C1 at z = T, where
        // it turns wall-sided), away from the ends.
        if !(0.3..=T - 0.3).contains(&z) || x.abs() > 0.4 * L {
            continue;
        }
        assert!(c.defined[i], "curvature defined at {p:?}");
        let (k, h) = wigley_curvature(x, z);
        k_scale = k_scale.max(k.abs());
        h_scale = h_scale.max(h.abs());
        worst_k = worst_k.max((c.gaussian[i] - k).abs());
        worst_h = worst_h.max((c.mean[i] - h).abs());
        n += 1;
    }
    println!(
        "{n} vertices: worst |ΔK| {worst_k:.3e} (scale {k_scale:.3e}), worst |ΔH| {worst_h:.3e} \
         (scale {h_scale:.3e})"
    );
    assert!(n > 500, "enough vertices compared: {n}");
    // Measured: 3.0 % of the largest |K| and 1.6 % of the largest H. What is left is the
    // patches' own error against the Wigley surface between its 15 × 6 curves (smooth and of
    // one sign across each patch), not the differences: a wrong sign or a vertex taking another
    // patch's point would be off by the whole scale.
    assert!(worst_k < 0.05 * k_scale, "K off by {worst_k:.3e}");
    assert!(worst_h < 0.025 * h_scale, "H off by {worst_h:.3e}");
}

#[test]
fn curvature_at_another_resolution_than_the_mesh_is_refused() {
    let hull = build_hull(&example("wigley.json"), &HullOptions::default()).expect("builds");
    let r = HullOptions::default().resolution;
    let err = hull.vertex_curvature(r + 1).expect_err("mismatch");
    assert!(
        matches!(&err, Error::InvalidInput(m) if m.contains("resolution")),
        "{err}"
    );
}
