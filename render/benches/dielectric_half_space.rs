//! The media's albedo under a dielectric boundary: the diffusion profiles' totals
//! (render/src/diffusion.rs) and the adding-doubling table (render/src/dielectric_half_space.rs)
//! against adding-doubling itself (data/reference/dielectric_half_space.json, the points off the
//! table's grid). Prints the errors once, then times one evaluation of each, so that speed and
//! error come from one run (docs/BENCHMARKS.md, "The dielectric half-space").
//!
//! `cargo bench -p rouge-render --bench dielectric_half_space`

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_render::dielectric_half_space::{ReferencePoint, held_out_points, reflectance};
use rouge_render::diffusion::{ChannelProfile, ProfileModel};
use std::hint::black_box;

/// A profile's total at reduced albedo `alpha` (σt′ = 1 mm⁻¹: the total does not depend on it).
fn total(model: ProfileModel, alpha: f64, eta: f64) -> f64 {
    ChannelProfile::new(model, 1.0 - alpha, alpha, eta).total()
}

const MODELS: [(ProfileModel, &str); 3] = [
    (ProfileModel::ClassicDipole, "classic dipole"),
    (ProfileModel::BetterDipole, "better dipole"),
    (ProfileModel::Burley, "Burley"),
];

fn report() {
    let check = held_out_points().expect("the reference");
    eprintln!("| medium channel | α′ | η | adding-doubling | table | classic dipole | better dipole | Burley |");
    eprintln!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for e in check.iter().filter(|e| e.medium.is_some()) {
        let rel = |v: f64| format!("{:+.1}%", 100.0 * (v / e.r_normal - 1.0));
        let table = reflectance(e.albedo, e.eta).expect("in the domain").normal;
        let models: Vec<String> = MODELS.iter().map(|(m, _)| rel(total(*m, e.albedo, e.eta))).collect();
        eprintln!(
            "| {} | {:.4} | {} | {:.4} | {} | {} |",
            e.medium.as_deref().unwrap_or(""),
            e.albedo,
            e.eta,
            e.r_normal,
            rel(table),
            models.join(" | ")
        );
    }
    // Worst relative error over the points off the grid, per η band.
    for (label, lo, hi) in [("η = 1", 1.0, 1.0), ("1 < η ≤ 1.3", 1.0001, 1.3), ("1.3 < η ≤ 1.6", 1.3001, 1.6)] {
        let band: Vec<&ReferencePoint> =
            check.iter().filter(|e| e.eta >= lo && e.eta <= hi && e.r_normal > 1e-3).collect();
        let worst = |f: &dyn Fn(&ReferencePoint) -> f64| {
            band.iter().map(|e| (f(e) / e.r_normal - 1.0).abs()).fold(0.0, f64::max)
        };
        let table = worst(&|e| reflectance(e.albedo, e.eta).expect("in the domain").normal);
        let models: Vec<String> = MODELS
            .iter()
            .map(|(m, name)| format!("{name} {:.1}%", 100.0 * worst(&|e| total(*m, e.albedo, e.eta))))
            .collect();
        eprintln!(
            "{label} ({} points): worst relative error: table {:.3}%, {}",
            band.len(),
            100.0 * table,
            models.join(", ")
        );
    }
}

fn bench(c: &mut Criterion) {
    report();
    let mut group = c.benchmark_group("dielectric_half_space");
    group.bench_function("table", |b| b.iter(|| reflectance(black_box(0.84), black_box(1.37))));
    for (model, name) in MODELS {
        group.bench_function(name, |b| b.iter(|| total(model, black_box(0.84), black_box(1.37))));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
