//! Kubelka-Munk over 10^6 wavelength samples: scalar reference vs the data-parallel fast path.
//! Compare with `python/bench_km.py` (vectorised numpy), run in the same session; figures and
//! accuracy in docs/BENCHMARKS.md.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rouge_measure::km::{self, r_inf_from_s_k, reflectance_over_background};
use rouge_measure::km_batch;
use std::hint::black_box;

const N: usize = 1_000_000;

/// Deterministic xorshift, so runs compare.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Valid inversion inputs from random layers (S 5-60 /mm, K 0.1-40 /mm, D 10-40 µm) over black
/// or white backgrounds: the data cosmetics produce.
/// R∞, R, Rg, D, S, K.
type Inputs = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

fn inputs() -> Inputs {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut ri, mut r, mut rg, mut d, mut s, mut k) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    for i in 0..N {
        let (si, ki, di) = (5.0 + 55.0 * rng.next(), 0.1 + 40.0 * rng.next(), 0.01 + 0.03 * rng.next());
        let g = if i % 2 == 0 { 0.04 } else { 0.88 };
        ri.push(r_inf_from_s_k(si, ki));
        r.push(reflectance_over_background(si, ki, di, g).unwrap_or(g));
        rg.push(g);
        d.push(di);
        s.push(si);
        k.push(ki);
    }
    (ri, r, rg, d, s, k)
}

fn bench(c: &mut Criterion) {
    let (ri, r, rg, d, s, k) = inputs();
    let mut o1 = vec![0.0; N];
    let mut o2 = vec![0.0; N];
    let mut g = c.benchmark_group("km_invert");
    g.throughput(Throughput::Elements(N as u64)).sample_size(10);
    g.bench_function(BenchmarkId::new("scalar", N), |b| {
        b.iter(|| {
            for i in 0..N {
                let c = km::invert_s_k(ri[i], r[i], rg[i], d[i])
                    .unwrap_or(km::KmCoefficients { s_per_mm: 0.0, k_per_mm: 0.0 });
                o1[i] = c.s_per_mm;
                o2[i] = c.k_per_mm;
            }
            black_box(&o1);
        })
    });
    g.bench_function(BenchmarkId::new("batch_simd", N), |b| {
        b.iter(|| black_box(km_batch::invert_batch(&ri, &r, &rg, &d, &mut o1, &mut o2).is_ok()))
    });
    g.bench_function(BenchmarkId::new("batch_portable", N), |b| {
        b.iter(|| black_box(km_batch::portable::invert_fast_only(&ri, &r, &rg, &d, &mut o1, &mut o2)))
    });
    g.finish();

    let mut g = c.benchmark_group("km_forward");
    g.throughput(Throughput::Elements(N as u64)).sample_size(10);
    g.bench_function(BenchmarkId::new("scalar", N), |b| {
        b.iter(|| {
            for i in 0..N {
                let l = km::layer_r_t(s[i], k[i], d[i]).unwrap_or(km::LayerRt::CLEAR);
                o1[i] = l.r;
                o2[i] = l.t;
            }
            black_box(&o1);
        })
    });
    g.bench_function(BenchmarkId::new("batch_simd", N), |b| {
        b.iter(|| black_box(km_batch::layer_batch(&s, &k, &d, &mut o1, &mut o2).is_ok()))
    });
    g.bench_function(BenchmarkId::new("batch_portable", N), |b| {
        b.iter(|| black_box(km_batch::portable::layer_fast_only(&s, &k, &d, &mut o1, &mut o2)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
