//! The formulator's bench: metamerism indices (three test illuminants × three corrections, a
//! pair of spectra), the uncertainty of S and K over a whole spectrum (81 Jacobians and
//! propagations), the best thin-layer thickness, and one batch correction of three colorants.
//! docs/BENCHMARKS.md, "The formulator's bench".

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_measure::analysis::Layer;
use rouge_measure::analysis::correction::{Presentation, correct_batch};
use rouge_measure::analysis::metamerism::{Correction, illuminant_metamerism};
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::km_uncertainty::{optimal_thickness_mm, propagate_spectrum};
use rouge_measure::{Colorimeter, Illuminant, Preset, Spectrum, Viewing};
use std::hint::black_box;
use std::path::PathBuf;

fn preset(name: &str) -> Preset {
    Preset::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../data/presets/{name}.json")))
        .expect("sample preset")
}

fn bench(c: &mut Criterion) {
    let ivory = preset("foundation_02_ivory");
    let m = ivory.measurement.clone().expect("measurement");
    let spec = |v: &[f64]| Spectrum::from_slice(v).expect("81 values");
    let (r_inf, r, rg) = (spec(&m.r_inf), spec(&m.r), spec(&m.rg));
    let u = Spectrum::constant(0.001);
    let sand = Layer::from_preset(&preset("foundation_03_sand")).expect("valid").r_inf();
    let ivory_r = Layer::from_preset(&ivory).expect("valid").r_inf();
    let tests = [Illuminant::A, Illuminant::Fl11, Illuminant::LedB3];
    let mut g = c.benchmark_group("formulate");
    g.sample_size(30);
    g.bench_function("metamerism_3_illuminants_3_corrections", |b| {
        b.iter(|| black_box(illuminant_metamerism(&sand, &ivory_r, Viewing::D65_1931, &tests, &Correction::ALL)))
    });
    g.bench_function("uncertainty_spectrum_81", |b| {
        b.iter(|| black_box(propagate_spectrum(&r_inf, &r, &rg, 0.02, &u, 0.0005, 0.0)))
    });
    g.bench_function("optimal_thickness", |b| {
        b.iter(|| black_box(optimal_thickness_mm(&ivory.s(), &ivory.k(), &rg, &u, 0.0005, 0.001, 1.0)))
    });
    let lib: Vec<Layer> = ["foundation_01_porcelain", "foundation_04_caramel", "lipstick_02_red"]
        .map(|n| Layer::from_preset(&preset(n)).expect("valid"))
        .to_vec();
    let recipe = [0.5, 0.35, 0.15];
    let col = Colorimeter::get(Viewing::D65_1931);
    let standard = duncan_mix("std", &lib, &recipe).expect("mix").r_inf();
    let weak: Vec<Layer> = lib
        .iter()
        .zip([0.9, 1.0, 1.1])
        .map(|(l, f)| Layer::new(&l.name, Spectrum(l.s.0.map(|v| v * f)), Spectrum(l.k.0.map(|v| v * f))).expect("ok"))
        .collect();
    let batch = duncan_mix("batch", &weak, &recipe).expect("mix").r_inf();
    g.bench_function("batch_correction_3_colorants", |b| {
        b.iter(|| black_box(correct_batch(&lib, &recipe, &batch, &standard, &Presentation::Opaque, col)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
