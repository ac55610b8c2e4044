//! Data-parallel Kubelka-Munk over many wavelength samples: the same formulas as [`crate::km`],
//! written so the compiler vectorises them (AVX-512 or AVX2+FMA chosen at run time, portable code
//! otherwise).
//!
//! # How the fast path stays exact where it matters
//! The loops contain no branches and no library calls: `ln` and `exp` are replaced by the
//! polynomial kernels [`fast_ln`] and [`fast_exp_neg`] (relative error ≈ 1e-16, see their docs),
//! and every special case is a select. Lanes outside the fast path's domain (invalid inputs,
//! `R − R∞` so small that `z` overflows, optical thickness `βX > 700` where `sech` underflows,
//! `w` overflowing, results below 1e-290 where subnormal rounding would cost relative
//! accuracy) are marked with NaN and counted; a second, scalar pass recomputes exactly
//! those with [`crate::km`] and reports the first invalid sample as an error. Results therefore
//! never contain NaN and match the scalar path to ~1e-15 relative (measured in
//! `docs/BENCHMARKS.md`, checked by `tests/km_reference.rs`).

use crate::km::{self, KmError, LayerRt};

/// An error at one sample of a batch.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum BatchError {
    /// The input and output slices differ in length.
    #[error("batch slices differ in length: {0}")]
    LengthMismatch(&'static str),
    /// Sample `index` has no solution.
    #[error("sample {index}: {error}")]
    Sample {
        /// index of the first failing sample
        index: usize,
        /// why it fails
        error: KmError,
    },
}

/// ln 2 split in two (fdlibm): the high part has trailing zero bits, so `n·LN2_HI` is exact.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
const SQRT2: f64 = std::f64::consts::SQRT_2;

/// `a·b + c`: fused on the SIMD paths (compiled with FMA), plain on the portable one, where
/// `mul_add` would be a slow library call.
#[inline(always)]
fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA { a.mul_add(b, c) } else { a * b + c }
}

/// `Σ c[i] xⁱ` by Estrin's scheme: pairs combined with x, x², x⁴, … so the dependency chain
/// is log₂(N) multiply-adds deep instead of N (Horner), which lets the SIMD loops overlap
/// iterations. Fully unrolled for constant `N`.
#[inline(always)]
fn estrin<const FMA: bool, const N: usize>(x: f64, c: [f64; N]) -> f64 {
    let mut v = c;
    let mut n = N;
    let mut xp = x;
    while n > 1 {
        let half = n.div_ceil(2);
        for i in 0..half {
            v[i] = if 2 * i + 1 < n { madd::<FMA>(v[2 * i + 1], xp, v[2 * i]) } else { v[2 * i] };
        }
        n = half;
        xp *= xp;
    }
    v[0]
}

/// Natural logarithm of a positive, finite, normal `x`, branch-free.
///
/// `x = 2^e m` with `m ∈ [√½, √2)`; `ln m = 2 atanh(s)`, `s = (m−1)/(m+1)`, `|s| ≤ 0.1716`,
/// `atanh(s)/s` by a near-minimax polynomial in `s²` (below 5e-18 relative). The exponent is read from the bits without
/// integer→float conversion so that AVX2 vectorises it. Result undefined (not UB) outside the domain.
#[inline(always)]
pub fn fast_ln(x: f64) -> f64 {
    fast_ln_impl::<false>(x)
}

#[inline(always)]
fn fast_ln_impl<const FMA: bool>(x: f64) -> f64 {
    let bits = x.to_bits();
    // Exponent as a float: put the 11 exponent bits into the mantissa of 2^52, subtract 2^52.
    let e_biased = f64::from_bits(0x4330_0000_0000_0000 | (bits >> 52)) - 4_503_599_627_370_496.0;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let big = m > SQRT2;
    let m = if big { 0.5 * m } else { m };
    let e = e_biased - 1023.0 + if big { 1.0 } else { 0.0 };
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let s2 = s * s;
    // p = Σ_{k≥1} s2^k/(2k+1) = s2·q(s2); q is a degree-6 near-minimax polynomial (Chebyshev
    // interpolation on [0, 0.02944], error 1.6e-16 on q ≈ 1/3, i.e. below 5e-18 of ln m).
    let p = s2
        * estrin::<FMA, 7>(
            s2,
            [
                0.333_333_333_333_333_5,
                0.199_999_999_999_497_52,
                0.142_857_143_129_877_43,
                0.111_111_055_673_975_4,
                0.090_914_445_626_308_61,
                0.076_658_608_002_780_21,
                0.073_082_248_425_217_02,
            ],
        );
    // ln m = 2s(1 + p)
    let two_s = 2.0 * s;
    let ln_m = madd::<FMA>(two_s, p, two_s);
    madd::<FMA>(e, LN2_HI, madd::<FMA>(e, LN2_LO, ln_m))
}

/// `e^{−y}` for `0 ≤ y ≤ 700`, branch-free.
///
/// `−y = n ln2 + r`, `|r| ≤ ln2/2`, `e^r` by a degree-11 polynomial (4e-18 relative), scaled by `2^n` through the exponent bits. Result undefined outside the domain.
#[inline(always)]
pub fn fast_exp_neg(y: f64) -> f64 {
    fast_exp_neg_impl::<false>(y)
}

#[inline(always)]
fn fast_exp_neg_impl<const FMA: bool>(y: f64) -> f64 {
    let x = -y;
    const SHIFT: f64 = 6_755_399_441_055_744.0; // 1.5·2^52: adding it rounds to an integer
    let t = madd::<FMA>(x, std::f64::consts::LOG2_E, SHIFT);
    let n = t - SHIFT;
    let r = madd::<FMA>(-n, LN2_LO, madd::<FMA>(-n, LN2_HI, x));
    // e^r by a degree-11 near-minimax polynomial on |r| ≤ ln2/2 (Chebyshev interpolation,
    // relative error 4.2e-18; the Taylor series needed degree 13).
    let p = estrin::<FMA, 12>(
        r,
        [
            1.0,
            1.0,
            0.500_000_000_000_001_9,
            0.166_666_666_666_666_8,
            0.041_666_666_666_488_1,
            0.008_333_333_333_319_601,
            0.001_388_888_895_231_477_5,
            0.000_198_412_698_900_471_13,
            2.480_148_548_232_849_4e-5,
            2.755_724_091_857_897e-6,
            2.763_263_963_904_103e-7,
            2.511_003_760_596_377_7e-8,
        ],
    );
    // t's low bits hold n in two's complement: 2^n has exponent field n + 1023.
    let n_bits = t.to_bits().wrapping_sub(SHIFT.to_bits());
    let scale = f64::from_bits(n_bits.wrapping_add(1023) << 52);
    p * scale
}

/// Fast-path inversion of one sample; NaN in both outputs marks a lane for the scalar pass.
///
/// The formula of [`km::invert_s_k`] rearranged to three divisions:
/// `ratio = (Rg − R)/((1 − Rg R∞)(R − R∞))`, `z = ratio (1 − R∞²)`, `u = 1 + z`,
/// `g = ratio · ln(u)/((u − 1) D)` (Kahan's `ln1p` trick: the rounding of `u` cancels),
/// `S = R∞ g`, `K = g (1 − R∞)²/2` (the `R∞` of `K = S(1−R∞)²/(2R∞)` cancels).
#[inline(always)]
#[allow(clippy::manual_range_contains)] // `&` of comparisons, not `&&`: keeps the loop branch-free
fn invert_lane<const FMA: bool>(r_inf: f64, r: f64, rg: f64, d: f64) -> (f64, f64) {
    let dr = r - r_inf;
    let one_minus = 1.0 - r_inf;
    let ratio = (rg - r) / (madd::<FMA>(-rg, r_inf, 1.0) * dr);
    let z = ratio * (one_minus * (1.0 + r_inf));
    let u = 1.0 + z;
    let at_one = u == 1.0;
    let ln_u = if at_one { 1.0 } else { fast_ln_impl::<FMA>(u) };
    let u_minus = if at_one { 1.0 } else { u - 1.0 };
    let g = ratio * ln_u / (u_minus * d);
    // `+ 0.0` turns the −0 of R = Rg with R < R∞ into the +0 the scalar path returns.
    let s = r_inf * g + 0.0;
    let k = g * (0.5 * one_minus * one_minus) + 0.0;
    // The domain of km::invert_s_k in nine comparisons: with R∞ ∈ (0, 1] and Rg ∈ [0, 1],
    // `ratio ≥ 0` (NaN fails) holds exactly when R lies between Rg and R∞ with R ≠ R∞
    // ((Rg − R)/(R − R∞) = (Rg − R∞)/(R − R∞) − 1 ≥ 0), which also puts R in [0, 1]; R = R∞
    // makes `ratio` infinite or NaN, caught by `z < 1e300`.
    let ok = (r_inf > 0.0)
        & (r_inf <= 1.0)
        & (rg >= 0.0)
        & (rg <= 1.0)
        & (d > 0.0)
        & (d < f64::INFINITY)
        & (ratio >= 0.0)
        & (z < 1e300)
        & (s < f64::INFINITY);
    if ok { (s, k) } else { (f64::NAN, f64::NAN) }
}

/// Fast-path layer R0, T of one sample; NaN marks a lane for the scalar pass.
///
/// The formula of [`km::layer_r_t`] rearranged to two divisions: with `m = e^{−y}`,
/// `tanh y = (1 − m²)/(1 + m²)` and `sech y = 2m/(1 + m²)` share one reciprocal; then
/// `R0 = S·num/(den + (S+K)·num)`, `T = sech·den/(den + (S+K)·num)` with `(num, den) =
/// (tanh y, β)` for `y ≥ 1/16` and `(X·tanh(y)/y, 1)` below, where `1 − m²` would cancel.
#[inline(always)]
fn layer_lane<const FMA: bool>(s: f64, k: f64, x: f64) -> (f64, f64) {
    let sk = s + k;
    // One square root, as km::beta: K(K + 2S) overflows only past 1e154 (then y = ∞ sends the
    // lane to the scalar pass) and underflows only where y is far inside the series branch.
    let beta = (k * (k + 2.0 * s)).sqrt();
    let y = beta * x;
    let y2 = y * y;
    // tanh(y)/y to y¹⁰ (first omitted term < 3e-17 for y < 1/16).
    let p = estrin::<FMA, 6>(y2, [1.0, -1.0 / 3.0, 2.0 / 15.0, -17.0 / 315.0, 62.0 / 2835.0, -1382.0 / 155_925.0]);
    let m = fast_exp_neg_impl::<FMA>(y);
    let m2 = m * m;
    let inv = 1.0 / (1.0 + m2);
    let tanh = (1.0 - m2) * inv;
    let sech = 2.0 * m * inv;
    let small = y < 0.0625;
    let num = if small { x * p } else { tanh };
    let den = if small { 1.0 } else { beta };
    let total = madd::<FMA>(sk, num, den);
    let inv_total = 1.0 / total;
    let r = s * num * inv_total;
    let t = sech * den * inv_total;
    // Results near the subnormal range lose relative precision in the extra roundings of this
    // path: the scalar pass recomputes them (T < 1e-290 only past βX ≈ 660).
    let ok = (s >= 0.0)
        & (k >= 0.0)
        & (x >= 0.0)
        & (y <= 700.0)
        & (total <= 1e300)
        & (t > 1e-290)
        & ((r == 0.0) | (r > 1e-290));
    if ok { (r, t) } else { (f64::NAN, f64::NAN) }
}

#[inline(always)]
fn invert_loop<const FMA: bool>(
    r_inf: &[f64],
    r: &[f64],
    rg: &[f64],
    d: &[f64],
    s: &mut [f64],
    k: &mut [f64],
) -> usize {
    let mut bad = 0usize;
    for (((((ri, rr), rgg), dd), so), ko) in r_inf.iter().zip(r).zip(rg).zip(d).zip(s.iter_mut()).zip(k.iter_mut()) {
        let (sv, kv) = invert_lane::<FMA>(*ri, *rr, *rgg, *dd);
        bad += usize::from(sv.is_nan());
        *so = sv;
        *ko = kv;
    }
    bad
}

#[inline(always)]
fn layer_loop<const FMA: bool>(s: &[f64], k: &[f64], x: &[f64], r: &mut [f64], t: &mut [f64]) -> usize {
    let mut bad = 0usize;
    for ((((ss, kk), xx), ro), to) in s.iter().zip(k).zip(x).zip(r.iter_mut()).zip(t.iter_mut()) {
        let (rv, tv) = layer_lane::<FMA>(*ss, *kk, *xx);
        bad += usize::from(rv.is_nan());
        *ro = rv;
        *to = tv;
    }
    bad
}

fn invert_generic(a: &[f64], b: &[f64], c: &[f64], d: &[f64], s: &mut [f64], k: &mut [f64]) -> usize {
    invert_loop::<false>(a, b, c, d, s, k)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn invert_avx2(a: &[f64], b: &[f64], c: &[f64], d: &[f64], s: &mut [f64], k: &mut [f64]) -> usize {
    invert_loop::<true>(a, b, c, d, s, k)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,fma")]
fn invert_avx512(a: &[f64], b: &[f64], c: &[f64], d: &[f64], s: &mut [f64], k: &mut [f64]) -> usize {
    invert_loop::<true>(a, b, c, d, s, k)
}
fn layer_generic(s: &[f64], k: &[f64], x: &[f64], r: &mut [f64], t: &mut [f64]) -> usize {
    layer_loop::<false>(s, k, x, r, t)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn layer_avx2(s: &[f64], k: &[f64], x: &[f64], r: &mut [f64], t: &mut [f64]) -> usize {
    layer_loop::<true>(s, k, x, r, t)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,fma")]
fn layer_avx512(s: &[f64], k: &[f64], x: &[f64], r: &mut [f64], t: &mut [f64]) -> usize {
    layer_loop::<true>(s, k, x, r, t)
}

/// Inverts S and K for every sample (see [`km::invert_s_k`] for the formula and domain).
/// `thickness_mm` holds one thickness per sample. On error, outputs before the failing index
/// are valid and the error names the index.
pub fn invert_batch(
    r_inf: &[f64],
    r: &[f64],
    rg: &[f64],
    thickness_mm: &[f64],
    s_out: &mut [f64],
    k_out: &mut [f64],
) -> Result<(), BatchError> {
    let n = r_inf.len();
    if [r.len(), rg.len(), thickness_mm.len(), s_out.len(), k_out.len()].iter().any(|&l| l != n) {
        return Err(BatchError::LengthMismatch("r_inf, r, rg, thickness_mm, s_out, k_out"));
    }
    let bad = dispatch!(invert_generic, invert_avx2, invert_avx512, (r_inf, r, rg, thickness_mm, s_out, k_out));
    if bad > 0 {
        for i in 0..n {
            if s_out[i].is_nan() {
                let c = km::invert_s_k(r_inf[i], r[i], rg[i], thickness_mm[i])
                    .map_err(|error| BatchError::Sample { index: i, error })?;
                s_out[i] = c.s_per_mm;
                k_out[i] = c.k_per_mm;
            }
        }
    }
    Ok(())
}

/// R0 and T of a layer for every sample (see [`km::layer_r_t`] for the formula and domain).
pub fn layer_batch(
    s_per_mm: &[f64],
    k_per_mm: &[f64],
    thickness_mm: &[f64],
    r_out: &mut [f64],
    t_out: &mut [f64],
) -> Result<(), BatchError> {
    let n = s_per_mm.len();
    if [k_per_mm.len(), thickness_mm.len(), r_out.len(), t_out.len()].iter().any(|&l| l != n) {
        return Err(BatchError::LengthMismatch("s, k, thickness_mm, r_out, t_out"));
    }
    let bad = dispatch!(layer_generic, layer_avx2, layer_avx512, (s_per_mm, k_per_mm, thickness_mm, r_out, t_out));
    if bad > 0 {
        for i in 0..n {
            if r_out[i].is_nan() {
                let LayerRt { r, t } = km::layer_r_t(s_per_mm[i], k_per_mm[i], thickness_mm[i])
                    .map_err(|error| BatchError::Sample { index: i, error })?;
                r_out[i] = r;
                t_out[i] = t;
            }
        }
    }
    Ok(())
}

/// The portable (no SIMD dispatch) variants, for benchmarks that compare them.
pub mod portable {
    use super::*;

    /// [`super::invert_batch`] compiled for the baseline target only; returns the number of
    /// lanes left for the scalar pass (their outputs are NaN).
    pub fn invert_fast_only(a: &[f64], b: &[f64], c: &[f64], d: &[f64], s: &mut [f64], k: &mut [f64]) -> usize {
        invert_generic(a, b, c, d, s, k)
    }

    /// [`super::layer_batch`] compiled for the baseline target only (see [`invert_fast_only`]).
    pub fn layer_fast_only(s: &[f64], k: &[f64], x: &[f64], r: &mut [f64], t: &mut [f64]) -> usize {
        layer_generic(s, k, x, r, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_ln_matches_std() {
        let mut worst = 0.0f64;
        let mut x = 1e-300;
        while x < 1e300 {
            for m in [1.0, 1.1, 1.3, 1.414, 1.4143, 1.7, 1.99] {
                let v = x * m;
                let e = (fast_ln(v) - v.ln()).abs() / v.ln().abs().max(1.0);
                worst = worst.max(e);
            }
            x *= 7.3;
        }
        assert!(worst < 4e-16, "worst {worst}");
        for v in [1.0 + 1e-15, 1.0 - 1e-15, 0.999, 1.001] {
            let e = ((fast_ln(v) - v.ln()) / v.ln()).abs();
            assert!(e < 1e-15, "{v}: {e}");
        }
    }

    #[test]
    fn fast_exp_matches_std() {
        let mut worst = 0.0f64;
        let mut y = 0.0;
        while y <= 700.0 {
            let e = (fast_exp_neg(y) / (-y).exp() - 1.0).abs();
            worst = worst.max(e);
            y += 0.0137;
        }
        assert!(worst < 1e-15, "worst {worst}");
        assert_eq!(fast_exp_neg(0.0), 1.0);
    }

    #[test]
    fn batch_reports_the_failing_index_and_fixes_hard_lanes() {
        // Lane 3: R − R∞ is subnormal, so z overflows and the scalar pass takes over.
        let r_inf = [0.5, 0.5, 1.0, 1e-300];
        let r = [0.3, 0.3, 0.4, 1e-300 * (1.0 + f64::EPSILON)];
        let rg = [0.1, 0.1, 0.1, 0.1];
        let d = [0.1; 4];
        let (mut s, mut k) = ([0.0; 4], [0.0; 4]);
        invert_batch(&r_inf, &r, &rg, &d, &mut s, &mut k).unwrap();
        for i in 0..4 {
            let c = km::invert_s_k(r_inf[i], r[i], rg[i], d[i]).unwrap();
            assert!((s[i] / c.s_per_mm - 1.0).abs() < 1e-14, "{i}");
            assert!(s[i].is_finite() && k[i].is_finite());
        }
        let bad_r = [0.3, 0.3, 1.0, 0.3]; // lane 2: R = R∞ = 1 over Rg = 0.1
        let err = invert_batch(&r_inf, &bad_r, &rg, &d, &mut s, &mut k).unwrap_err();
        assert!(matches!(err, BatchError::Sample { index: 2, .. }), "{err}");
        let err = invert_batch(&r_inf, &r[..3], &rg, &d, &mut s, &mut k).unwrap_err();
        assert!(matches!(err, BatchError::LengthMismatch(_)));
    }

    #[test]
    fn layer_batch_handles_edges() {
        let s = [0.0, 2.0, 0.0, 1e6, 5.0, 3.0];
        let k = [0.0, 0.0, 3.0, 1e6, 0.5, 1.0];
        let x = [1.0, 0.5, 0.5, 1.0, 1e-9, 1e3];
        let (mut r, mut t) = ([0.0; 6], [0.0; 6]);
        layer_batch(&s, &k, &x, &mut r, &mut t).unwrap();
        for i in 0..6 {
            let l = km::layer_r_t(s[i], k[i], x[i]).unwrap();
            assert!((r[i] - l.r).abs() <= 1e-14 * l.r.abs(), "{i}: {} {}", r[i], l.r);
            assert!((t[i] - l.t).abs() <= 1e-14 * l.t.abs(), "{i}: {} {}", t[i], l.t);
        }
    }
}
