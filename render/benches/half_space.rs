//! The half-space laws: the exact H-function's Nyström solve (render/src/half_space.rs, η = 1)
//! and the `half-space` diffuse law's table at any η (render/src/dielectric_brdf.rs): making the
//! GPU's per-frame table, and one lookup of its CPU twin, the shader's arithmetic. Prints the
//! twin's error against adding-doubling off every grid and against the H-function at η = 1 once,
//! so that speed and error come from one run (docs/BENCHMARKS.md, "The half-space law under a
//! dielectric boundary").
//!
//! `cargo bench -p rouge-render --bench half_space`

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_render::dielectric_brdf::{GpuLaw, GpuTable, held_out_points};
use rouge_render::half_space::HalfSpace;
use std::hint::black_box;

fn quantiles(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.95), at(1.0))
}

fn report_errors() {
    let points = held_out_points().expect("the reference");
    let mut tables: Vec<(f64, GpuTable)> = Vec::new();
    let (mut f_err, mut r_err) = (vec![], vec![]);
    for p in &points {
        if !tables.iter().any(|(e, _)| *e == p.eta) {
            tables.push((p.eta, GpuTable::new(GpuLaw { eta: p.eta, curvature: None }).expect("in the domain")));
        }
        let t = &tables.iter().find(|(e, _)| *e == p.eta).expect("made above").1;
        f_err.push((t.pi_brdf(p.r_normal, p.mu, p.mu0) / p.pi_f - 1.0).abs());
        r_err.push((t.reflectance(p.r_normal, p.mu0) / p.r - 1.0).abs());
    }
    let (fm, f95, fw) = quantiles(f_err);
    let (rm, r95, rw) = quantiles(r_err);
    eprintln!(
        "GPU twin against adding-doubling, {} points off every grid: πf median {fm:.1e}, p95 {f95:.1e}, worst {fw:.1e}; \
         R median {rm:.1e}, p95 {r95:.1e}, worst {rw:.1e}",
        points.len()
    );
    let table = GpuTable::new(GpuLaw { eta: 1.0, curvature: None }).expect("η = 1");
    let mut worst: f64 = 0.0;
    for i in 1..=20 {
        let hs = HalfSpace::new(1.0 - (f64::from(i) / 20.0).powi(3));
        let rn = hs.directional_reflectance(1.0);
        for j in 1..=20 {
            for k in 1..=20 {
                let (mu, mu0) = (f64::from(j) / 20.0, f64::from(k) / 20.0);
                worst = worst.max((table.pi_brdf(rn, mu, mu0) / hs.pi_brdf(mu, mu0) - 1.0).abs());
            }
        }
    }
    eprintln!("GPU twin at η = 1 against the H-function (μ, μ₀ ≥ 0.05, 20 albedos): worst relative error {worst:.1e}");
}

fn bench_half_space(c: &mut Criterion) {
    report_errors();
    let mut group = c.benchmark_group("half_space");
    group.bench_function("solve H (80 nodes)", |b| b.iter(|| HalfSpace::new(black_box(0.84))));
    let hs = HalfSpace::new(0.84);
    group.bench_function("exact pi f, solved", |b| b.iter(|| hs.pi_brdf(black_box(0.37), black_box(0.8))));
    group.bench_function("GPU table at eta 1.3 (made per eta)", |b| {
        b.iter(|| GpuTable::new(GpuLaw { eta: black_box(1.3), curvature: None }))
    });
    let table = GpuTable::new(GpuLaw { eta: 1.3, curvature: None }).expect("η = 1.3");
    group.bench_function("GPU twin pi f, one channel", |b| {
        b.iter(|| table.pi_brdf(black_box(0.31), black_box(0.37), black_box(0.8)))
    });
    group.finish();
}

criterion_group!(benches, bench_half_space);
criterion_main!(benches);
