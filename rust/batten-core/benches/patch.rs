//! Patch evaluation speed: points per second for 3-, 4-, 5- and 6-sided patches (Gregory for
//! 4 sides, Charrot–Gregory otherwise, and Charrot–Gregory on 4 sides), a degenerate sliver
//! face, and the tessellation of 100 patches.

use batten_core::{
    tessellate_patches, FaceBoundary, NurbsCurve, Patch, PatchKind, PatchOptions, Side, SideSegment,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::DVec3;
use std::hint::black_box;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn bezier(pts: &[DVec3]) -> NurbsCurve {
    let p = pts.len() - 1;
    let mut knots = vec![0.0; p + 1];
    knots.extend(vec![1.0; p + 1]);
    NurbsCurve::try_new(p, knots, pts.to_vec(), None).expect("valid Bezier")
}

fn surface(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.3 * (x * x - y * y) + 0.1 * x * y)
}

/// An N-sided face on a saddle: cubic sides through surface points.
fn face(n: usize, shift: f64) -> FaceBoundary {
    let c: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64 + 0.3;
            (1.5 * a.cos() + shift, 1.2 * a.sin())
        })
        .collect();
    FaceBoundary::new(
        (0..n)
            .map(|k| {
                let (a, b) = (c[k], c[(k + 1) % n]);
                let p = |f: f64| surface(a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f);
                Side::single(SideSegment::whole(bezier(&[
                    p(0.0),
                    p(1.0 / 3.0) + DVec3::Z * 0.05,
                    p(2.0 / 3.0),
                    p(1.0),
                ])))
            })
            .collect(),
    )
}

/// The N-gon domain sampled on a fan of rays: `per_side² · N` points.
fn points(p: &Patch, per_side: usize) -> Vec<[f64; 2]> {
    let d = p.domain();
    let c = d.centre();
    let mut xs = Vec::new();
    for i in 0..p.sides() {
        for a in 0..per_side {
            let b = d.side_point(i, a as f64 / per_side as f64);
            for r in 0..per_side {
                let f = (r as f64 + 0.5) / per_side as f64;
                xs.push([c[0] + (b[0] - c[0]) * f, c[1] + (b[1] - c[1]) * f]);
            }
        }
    }
    xs
}

fn bench_eval(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("patch_eval");
    let cases = [
        (3, PatchKind::Auto, "cg3"),
        (4, PatchKind::Auto, "gregory4"),
        (4, PatchKind::CharrotGregory, "cg4"),
        (5, PatchKind::Auto, "cg5"),
        (6, PatchKind::Auto, "cg6"),
    ];
    for (n, kind, name) in cases {
        let opts = PatchOptions {
            kind,
            ..PatchOptions::default()
        };
        let p = Patch::try_new(&face(n, 0.0), &[], &opts).expect("patch");
        let xs = points(&p, 20);
        let mut out = vec![DVec3::ZERO; xs.len()];
        g.throughput(Throughput::Elements(xs.len() as u64));
        g.bench_with_input(BenchmarkId::new(name, xs.len()), &xs, |b, xs| {
            b.iter(|| {
                p.eval_into(black_box(xs), &mut out);
                black_box(&out);
            })
        });
    }
    // Degenerate: a triangle with a 0.5° corner (repaired ribbon).
    let e = 0.5f64.to_radians();
    let sliver = FaceBoundary::new(vec![
        Side::single(SideSegment::whole(bezier(&[DVec3::ZERO, DVec3::X]))),
        Side::single(SideSegment::whole(bezier(&[
            DVec3::X,
            DVec3::new(e.cos(), e.sin(), 0.0),
        ]))),
        Side::single(SideSegment::whole(bezier(&[
            DVec3::new(e.cos(), e.sin(), 0.0),
            DVec3::ZERO,
        ]))),
    ]);
    let p = Patch::try_new(&sliver, &[], &PatchOptions::default()).expect("sliver");
    let xs = points(&p, 20);
    let mut out = vec![DVec3::ZERO; xs.len()];
    g.throughput(Throughput::Elements(xs.len() as u64));
    g.bench_with_input(BenchmarkId::new("sliver3", xs.len()), &xs, |b, xs| {
        b.iter(|| {
            p.eval_into(black_box(xs), &mut out);
            black_box(&out);
        })
    });
    g.finish();
}

fn bench_tessellate(cr: &mut Criterion) {
    let patches: Vec<Patch> = (0..100)
        .map(|k| {
            Patch::try_new(
                &face(3 + k % 4, k as f64 * 0.01),
                &[],
                &PatchOptions::default(),
            )
            .expect("patch")
        })
        .collect();
    let mut g = cr.benchmark_group("patch_tessellate");
    g.bench_function("100_patches_res12", |b| {
        b.iter(|| black_box(tessellate_patches(black_box(&patches), 12).expect("mesh")))
    });
    g.finish();
}

criterion_group!(benches, bench_eval, bench_tessellate);
criterion_main!(benches);
