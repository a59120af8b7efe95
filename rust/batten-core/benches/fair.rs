//! Curve fairing (Dierckx smoothing spline) of a noisy midship section: flat bottom, bilge
//! radius, vertical side; 200 and 2000 points, and a degenerate input (collinear points).

use batten_core::{fair_points, FairOptions, Smoothing};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::DVec3;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// SplitMix64 + Box–Muller, deterministic.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (((z ^ (z >> 31)) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn gauss(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// A midship section at x = 100 m (half breadth 16 m, bilge radius 3 m, side to z = 15 m),
/// sampled by arc length, with Gaussian noise σ in the section plane.
fn section(m: usize, sigma: f64) -> Vec<DVec3> {
    let (b, r, d) = (16.0, 3.0, 15.0);
    let (l1, l2, l3) = (b - r, 0.5 * std::f64::consts::PI * r, d - r);
    let total = l1 + l2 + l3;
    let mut rng = Rng(7);
    (0..m)
        .map(|i| {
            let s = total * i as f64 / (m - 1) as f64;
            let (y, z) = if s < l1 {
                (s, 0.0)
            } else if s < l1 + l2 {
                let a = (s - l1) / r;
                (b - r + r * a.sin(), r - r * a.cos())
            } else {
                (b, r + (s - l1 - l2))
            };
            let noise = if i == 0 || i == m - 1 { 0.0 } else { sigma };
            DVec3::new(100.0, y + noise * rng.gauss(), z + noise * rng.gauss())
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let sigma = 0.002;
    let opts = FairOptions {
        smoothing: Smoothing::Noise(sigma),
        corner_angle: None,
        ..FairOptions::default()
    };
    let mut group = c.benchmark_group("fair_section");
    for m in [200, 2000] {
        let pts = section(m, sigma);
        group.bench_with_input(BenchmarkId::new("noise", m), &pts, |bch, pts| {
            bch.iter(|| fair_points(pts, &opts).expect("fits"))
        });
    }
    let tol = FairOptions {
        smoothing: Smoothing::MaxDeviation(0.005),
        corner_angle: None,
        ..FairOptions::default()
    };
    let pts = section(200, 0.0);
    group.bench_with_input(BenchmarkId::new("tolerance_5mm", 200), &pts, |bch, pts| {
        bch.iter(|| fair_points(pts, &tol).expect("fits"))
    });
    let line: Vec<DVec3> = (0..200)
        .map(|i| DVec3::new(0.0, f64::from(i) * 0.1, 0.0))
        .collect();
    group.bench_with_input(BenchmarkId::new("collinear", 200), &line, |bch, pts| {
        bch.iter(|| fair_points(pts, &tol).expect("fits"))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
