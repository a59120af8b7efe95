//! Topology of hull networks: nodes, edges, half-edges and faces of station × waterline grids
//! drawn on a Wigley-like hull surface (every curve exact on the surface, four Bézier pieces
//! each), from 50 to 800 curves, plus a dense 200-curve grid and a degenerate input (duplicate
//! stations).
#![allow(missing_docs)]

use batten_core::{Network, NetworkCurve, NurbsCurve, Role, Tolerance, Topology};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::DVec3;
use std::hint::black_box;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Bézier ordinates of the surface height `y = 0.6 (1 − u²)(1 − z²)`, `u = (x − 5)/6`, along a
/// straight (x, z) segment: the blossom of a product of four linear factors.
fn ordinates(p: (f64, f64), q: (f64, f64)) -> [f64; 5] {
    let u = |x: f64| (x - 5.0) / 6.0;
    let f = [
        (1.0 - u(p.0), 1.0 - u(q.0)),
        (1.0 + u(p.0), 1.0 + u(q.0)),
        (1.0 - p.1, 1.0 - q.1),
        (1.0 + p.1, 1.0 + q.1),
    ];
    let mut c = [0.0; 5];
    let mut n = [0.0; 5];
    for mask in 0u32..16 {
        let k = mask.count_ones() as usize;
        c[k] += (0..4)
            .map(|i| if mask & (1 << i) != 0 { f[i].1 } else { f[i].0 })
            .product::<f64>();
        n[k] += 1.0;
    }
    c.map(|v| v * 0.6)
        .iter()
        .zip(n)
        .map(|(v, n)| v / n)
        .collect::<Vec<_>>()
        .try_into()
        .unwrap()
}

/// The straight (x, z) segment `a → b` lifted onto the surface, as a degree-4 spline of four
/// Bézier pieces.
fn lifted(name: String, a: (f64, f64), b: (f64, f64)) -> NetworkCurve {
    let pieces = 4;
    let at = |i: usize| {
        let f = i as f64 / pieces as f64;
        (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1))
    };
    let mut points = Vec::new();
    let mut knots = vec![0.0; 5];
    for s in 0..pieces {
        let (p, q) = (at(s), at(s + 1));
        let ys = ordinates(p, q);
        for (k, y) in ys.iter().enumerate().skip(usize::from(s > 0)) {
            let f = k as f64 / 4.0;
            points.push(DVec3::new(p.0 + f * (q.0 - p.0), *y, p.1 + f * (q.1 - p.1)));
        }
        let reps = if s + 1 == pieces { 5 } else { 4 };
        knots.extend(std::iter::repeat_n((s + 1) as f64, reps));
    }
    NetworkCurve {
        name,
        role: Role::Free,
        curve: NurbsCurve::try_new(4, knots, points, None).unwrap(),
    }
}

/// Keel, deck, transom, stem, `m` stations and `n` waterlines: `m + n + 4` curves.
fn grid(m: usize, n: usize) -> Network {
    let mut c = vec![
        lifted("keel".into(), (0.0, -1.0), (10.0, -1.0)),
        lifted("deck".into(), (0.0, 0.0), (10.0, 0.0)),
        lifted("transom".into(), (0.0, -1.0), (0.0, 0.0)),
        lifted("stem".into(), (10.0, -1.0), (10.0, 0.0)),
    ];
    for i in 1..=m {
        let x = 10.0 * i as f64 / (m + 1) as f64;
        c.push(lifted(format!("st{i}"), (x, -1.0), (x, 0.0)));
    }
    for j in 1..=n {
        let z = -1.0 + j as f64 / (n + 1) as f64;
        c.push(lifted(format!("wl{j}"), (0.0, z), (10.0, z)));
    }
    Network::try_new("grid", c).unwrap()
}

fn check(net: &Network, m: usize, n: usize) {
    let t = Topology::build(net, Tolerance::DEFAULT).unwrap();
    assert_eq!(
        t.faces.len(),
        (m + 1) * (n + 1),
        "bench network builds its faces"
    );
}

fn topology(c: &mut Criterion) {
    let mut g = c.benchmark_group("topology");
    g.sample_size(20);
    // Growth: 20 waterlines, more and more stations (nodes grow linearly with curves).
    for total in [50usize, 100, 200, 400, 800] {
        let (m, n) = (total - 24, 20);
        let net = grid(m, n);
        check(&net, m, n);
        g.throughput(Throughput::Elements(total as u64));
        g.bench_with_input(
            BenchmarkId::new("curves_20_waterlines", total),
            &net,
            |b, net| b.iter(|| Topology::build(black_box(net), Tolerance::DEFAULT).unwrap()),
        );
    }
    // The 40 stations × 20 waterlines (64 curves, 800 crossings).
    let net = grid(40, 20);
    check(&net, 40, 20);
    g.bench_function("grid_40x20", |b| {
        b.iter(|| Topology::build(black_box(&net), Tolerance::DEFAULT).unwrap())
    });
    // A dense 200-curve grid: 130 stations × 66 waterlines, 8580 crossings.
    let net = grid(130, 66);
    check(&net, 130, 66);
    g.bench_function("grid_130x66_dense_200_curves", |b| {
        b.iter(|| Topology::build(black_box(&net), Tolerance::DEFAULT).unwrap())
    });
    // Degenerate input: ten stations drawn twice (reported as duplicates and left out).
    let mut curves = grid(40, 20).curves().to_vec();
    for i in 1..=10 {
        let mut dup = curves
            .iter()
            .find(|c| c.name == format!("st{}", 4 * i))
            .unwrap()
            .clone();
        dup.name = format!("dup{i}");
        curves.push(dup);
    }
    let net = Network::try_new("dups", curves).unwrap();
    check(&net, 40, 20);
    g.bench_function("grid_40x20_with_10_duplicates", |b| {
        b.iter(|| Topology::build(black_box(&net), Tolerance::DEFAULT).unwrap())
    });
    g.finish();
}

criterion_group!(benches, topology);
criterion_main!(benches);
