//! The spectral skin model: one spectrum of the forward model on the working grid (81 lookups of
//! the tabulated adding-doubling), one two-layer transport lookup, and one fit of a measured-like
//! spectrum (Xiao's 380-740 nm / 10 nm grid); the skin colour table: building it for a tone and
//! one lookup, against the exact colour of one texel. Figures in docs/SKIN.md and
//! docs/BENCHMARKS.md.

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_measure::skin::fit::SkinFitter;
use rouge_measure::skin::transport::two_layer_reflectance;
use rouge_measure::skin::{FitOptions, SkinColorTable, SkinParams, skin_tone};
use rouge_measure::spectrum::Extrapolation;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("skin");
    g.bench_function("transport_lookup", |b| {
        b.iter(|| black_box(two_layer_reflectance(black_box(0.31), black_box(0.42), black_box(0.97))))
    });
    let p = SkinParams::LIGHT;
    g.bench_function("forward_working_grid_81", |b| b.iter(|| black_box(black_box(&p).reflectance())));
    let wl: Vec<f64> = (0..37).map(|i| 380.0 + 10.0 * f64::from(i)).collect();
    let fitter = SkinFitter::new(FitOptions { extrapolation: Extrapolation::Constant, ..FitOptions::default() });
    let fitter = fitter.expect("the default options build a fitter");
    for name in ["light", "brown", "very-deep"] {
        let tone = skin_tone(name).expect("a built-in tone");
        // The tone, perturbed a little so the fit starts away from a seed.
        let measured: Vec<f64> = tone
            .params
            .reflectance_at(&wl)
            .expect("a tone is in range")
            .iter()
            .enumerate()
            .map(|(i, r)| r * (1.0 + 0.02 * (i as f64 * 0.7).sin()))
            .collect();
        g.bench_function(format!("fit_{name}"), |b| b.iter(|| black_box(fitter.fit(&wl, black_box(&measured)))));
    }
    let colorimeter = Colorimeter::get(Viewing::D65_1931);
    let texel = SkinParams { melanin_fraction: 0.031, blood_fraction: 0.021, ..p };
    g.bench_function("texel_colour_exact", |b| {
        b.iter(|| {
            let r = black_box(&texel).reflectance().expect("in range");
            black_box(colorimeter.srgb_linear(&colorimeter.xyz(&r)))
        })
    });
    let table = SkinColorTable::new(&p).expect("the light tone is in range");
    g.bench_function("texel_colour_table", |b| b.iter(|| black_box(table.linear_srgb(black_box(&texel)))));
    g.sample_size(10);
    g.bench_function("colour_table_build", |b| b.iter(|| black_box(SkinColorTable::new(black_box(&p)))));
    // The cache on disk (rouge_model::skin::table_cache): the bytes written, and read back with
    // their 8 probe nodes recomputed by the exact model (a hit, less the file read).
    let bytes = table.to_bytes();
    g.bench_function("colour_table_to_bytes", |b| b.iter(|| black_box(table.to_bytes())));
    g.bench_function("colour_table_from_bytes", |b| {
        b.iter(|| black_box(SkinColorTable::from_bytes(black_box(&p), black_box(&bytes))))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
