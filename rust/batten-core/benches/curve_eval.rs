//! Curve evaluation, closest point and arc length on a 50-point cubic B-spline, plus a
//! degenerate input (all control points equal).
#![allow(missing_docs)]

use batten_core::{KnotLayout, NurbsCurve};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec3;
use std::hint::black_box;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn wavy(n: usize) -> NurbsCurve {
    let pts: Vec<DVec3> = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            DVec3::new(100.0 * t, 5.0 * (7.0 * t).sin(), 2.0 * (3.0 * t).cos())
        })
        .collect();
    NurbsCurve::from_layout(&pts, None, 4, KnotLayout::Endpoint, false).unwrap()
}

fn eval(c: &mut Criterion) {
    let curve = wavy(50);
    let (a, b) = curve.domain();
    let n = 100_000;
    let ts: Vec<f64> = (0..n)
        .map(|i| a + (b - a) * ((i * 7919) % n) as f64 / n as f64)
        .collect();
    let mut out = vec![0.0; 3 * n];
    let mut g = c.benchmark_group("eval");
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("cubic_50pts_100k_params", |bch| {
        bch.iter(|| curve.points_into(black_box(&ts), &mut out))
    });
    let flat =
        NurbsCurve::from_layout(&[DVec3::ONE; 50], None, 4, KnotLayout::Endpoint, false).unwrap();
    g.bench_function("degenerate_all_points_equal", |bch| {
        bch.iter(|| flat.points_into(black_box(&ts), &mut out))
    });
    g.finish();
}

fn nearest_and_length(c: &mut Criterion) {
    let curve = wavy(50);
    let dec = curve.bezier_decomposition();
    c.bench_function("nearest_point_s_curve", |bch| {
        bch.iter(|| {
            dec.nearest(black_box(DVec3::new(40.0, 9.0, 1.0)), 1e-9)
                .unwrap()
        })
    });
    c.bench_function("arc_length_1e-9", |bch| {
        bch.iter(|| black_box(&curve).arc_length(1e-9).unwrap())
    });
}

criterion_group!(benches, eval, nearest_and_length);
criterion_main!(benches);
