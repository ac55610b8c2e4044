//! Spectrum → XYZ for 10^5 spectra on the working grid (D65, CIE 1931). Compare with
//! `python/bench_km.py` (colour-science `msds_to_XYZ` on the whole array, and a numpy matmul).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_measure::spectrum::Spectrum;
use std::hint::black_box;

const N: usize = 100_000;

fn bench(c: &mut Criterion) {
    let spectra: Vec<Spectrum> =
        (0..N).map(|k| Spectrum::from_fn(|nm| 0.5 + 0.45 * ((nm + 7.0 * k as f64) / 53.0).sin())).collect();
    let col = Colorimeter::get(Viewing::D65_1931);
    let mut out = vec![[0.0; 3]; N];
    let mut g = c.benchmark_group("spectrum_to_xyz");
    g.throughput(Throughput::Elements(N as u64)).sample_size(20);
    g.bench_function(BenchmarkId::new("one_at_a_time", N), |b| {
        b.iter(|| {
            for (s, o) in spectra.iter().zip(out.iter_mut()) {
                *o = col.xyz(s).xyz;
            }
            black_box(&out);
        })
    });
    g.bench_function(BenchmarkId::new("xyz_many_simd", N), |b| {
        b.iter(|| {
            col.xyz_many(&spectra, &mut out);
            black_box(&out);
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
