//! The whole H-rep pipeline on the frigate network of the paper (§5.2, Fig. 13; 13 curves,
//! 17 faces): topology, ribbons, patches, tessellation at 12 intervals per edge and the report.
#![allow(missing_docs)]

use batten_core::{build_hull, HullOptions, Network, Tolerance};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// The add-on's allocator (batten-py), so the figures are the add-on's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn frigate() -> Network {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/frigate_network.json");
    let text = std::fs::read_to_string(path).expect("examples/frigate_network.json");
    Network::from_json(&text).expect("a valid network")
}

fn bench_hull(c: &mut Criterion) {
    let net = frigate();
    let options = HullOptions {
        tolerance: Tolerance::DEFAULT,
        resolution: 12,
    };
    c.bench_function("build_hull/frigate/r12", |b| {
        b.iter(|| build_hull(black_box(&net), black_box(&options)).expect("builds"))
    });
}

criterion_group!(benches, bench_hull);
criterion_main!(benches);
