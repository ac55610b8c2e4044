//! The half-space's H-function (render/src/half_space.rs): the exact Nyström solve and one
//! evaluation against \[Hapke2002\]'s closed form, the GPU's. Prints the closed form's worst
//! relative error against the exact H (ϖ on a cubic grid towards 1, μ on [0, 1]) once, so that
//! speed and error come from one run (docs/BENCHMARKS.md, "The exact half-space").
//!
//! `cargo bench -p rouge-render --bench half_space`

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_render::half_space::{HalfSpace, h_hapke};
use std::hint::black_box;

fn bench_h(c: &mut Criterion) {
    let mut worst = (0.0f64, 0.0, 0.0);
    for i in 0..=100 {
        let w = 1.0 - (f64::from(i) / 100.0).powi(3);
        let hs = HalfSpace::new(w);
        for j in 0..=100 {
            let mu = f64::from(j) / 100.0;
            let e = (h_hapke(w, mu) / hs.h(mu) - 1.0).abs();
            if e > worst.0 {
                worst = (e, w, mu);
            }
        }
    }
    eprintln!(
        "Hapke's H against the exact H: worst relative error {:.4} at ϖ = {:.4}, μ = {:.2}",
        worst.0, worst.1, worst.2
    );
    let mut group = c.benchmark_group("half_space");
    group.bench_function("solve H (80 nodes)", |b| b.iter(|| HalfSpace::new(black_box(0.84))));
    let hs = HalfSpace::new(0.84);
    group.bench_function("exact H(mu), solved", |b| b.iter(|| hs.h(black_box(0.37))));
    group.bench_function("Hapke H(mu)", |b| b.iter(|| h_hapke(black_box(0.84), black_box(0.37))));
    group.finish();
}

criterion_group!(benches, bench_h);
criterion_main!(benches);
