//! The slab law's transmission (render/src/slab_transmittance.rs) against adding-doubling's own
//! values off the table's grid (data/reference/slab_transmittance.json), and its speed: prints
//! the errors once, then times one evaluation, so that speed and error come from one run
//! (docs/BENCHMARKS.md, "The slab law"). Single scattering alone, the closed-form part, is the
//! cheaper approximation beside it.
//!
//! `cargo bench -p rouge-render --bench slab_transmittance`

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_render::slab_transmittance::{SlabPoint, held_out_points, single_scattering, transmittance};
use std::hint::black_box;

/// Median and worst of μ_l·|T − T_ref| (radiance per unit E/π) and the median relative error where
/// T_ref > 10⁻³, of `f` over `points`.
fn errors(points: &[SlabPoint], f: &dyn Fn(&SlabPoint) -> f64) -> (f64, f64, f64) {
    let mut radiance: Vec<f64> = points.iter().map(|p| p.mu_l * (f(p) - p.t).abs()).collect();
    let mut relative: Vec<f64> = points.iter().filter(|p| p.t > 1e-3).map(|p| (f(p) - p.t).abs() / p.t).collect();
    radiance.sort_by(f64::total_cmp);
    relative.sort_by(f64::total_cmp);
    (radiance[radiance.len() / 2], radiance[radiance.len() - 1], relative[relative.len() / 2])
}

fn bench(c: &mut Criterion) {
    let points = held_out_points().expect("the reference");
    let table = |p: &SlabPoint| transmittance(p.albedo, p.eta, p.tau, p.mu_v, p.mu_l).expect("in the domain");
    let single = |p: &SlabPoint| single_scattering(p.albedo, p.eta, p.tau, p.mu_v, p.mu_l);
    // The index-matched law where the faces are dielectric: what the boundary is worth.
    let matched = |p: &SlabPoint| transmittance(p.albedo, 1.0, p.tau, p.mu_v, p.mu_l).expect("in the domain");
    let dielectric: Vec<SlabPoint> = points.iter().filter(|p| p.eta >= 1.3).cloned().collect();
    for (name, f) in [("table, η ≥ 1.3", &table as &dyn Fn(&SlabPoint) -> f64), ("the η = 1 table, η ≥ 1.3", &matched)]
    {
        let (median, worst, rel) = errors(&dielectric, f);
        eprintln!(
            "{name}: μ_l·|ΔT| median {median:.2e}, worst {worst:.2e}; relative (T > 10⁻³) median {:.2}% over {} points",
            100.0 * rel,
            dielectric.len()
        );
    }
    for (name, f) in [("table", &table as &dyn Fn(&SlabPoint) -> f64), ("single scattering alone", &single)] {
        let (median, worst, rel) = errors(&points, f);
        eprintln!(
            "{name}: μ_l·|ΔT| median {median:.2e}, worst {worst:.2e}; relative (T > 10⁻³) median {:.2}% over {} points",
            100.0 * rel,
            points.len()
        );
    }
    for (name, eta) in [("η 1", 1.0), ("η 1.33", 1.33)] {
        let p = points.iter().find(|p| p.tau > 2.0 && p.albedo > 0.9 && p.eta == eta).expect("a thick, bright point");
        let p = p.clone();
        c.bench_function(&format!("slab transmittance, table, {name}"), |b| {
            b.iter(|| {
                transmittance(
                    black_box(p.albedo),
                    black_box(p.eta),
                    black_box(p.tau),
                    black_box(p.mu_v),
                    black_box(p.mu_l),
                )
            })
        });
        c.bench_function(&format!("slab transmittance, single scattering alone, {name}"), |b| {
            b.iter(|| {
                single_scattering(
                    black_box(p.albedo),
                    black_box(p.eta),
                    black_box(p.tau),
                    black_box(p.mu_v),
                    black_box(p.mu_l),
                )
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
