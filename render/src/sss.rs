//! Skin subsurface scattering: the diffusion profile, the separable screen-space kernel of
//! \[Jimenez2015\] ("Separable Subsurface Scattering"), and the brute-force reference the
//! kernel is measured against.
//!
//! # Profile
//! The diffusion profile R(r) of skin is the sum-of-Gaussians fit of d'Eon, Luebke and Enderton
//! \[dEon2007\]: six Gaussians G(v, r) = exp(−r²/2v) / (2πv) with variances 0.0064 … 7.41 mm² and one
//! weight per RGB channel. The weights of each channel sum to 1, so the profile integrates to 1
//! over the plane: scattering moves light, it neither makes nor absorbs it (the skin's albedo is
//! applied before the blur).
//!
//! # Separable kernel
//! A 2D radial profile is not separable, but each Gaussian is, and \[Jimenez2015\] shows that the
//! rank-1 product of the profile's 1D marginal A(x) = ∫ R(√(x²+y²)) dy with itself,
//! A(x)·A(y), is close to R for skin. For a sum of Gaussians the marginal is exact and cheap:
//! A(x) = Σ w·exp(−x²/2v)/√(2πv). The kernel places N (odd) samples at x_j = ρ·t_j·|t_j|,
//! t_j evenly spaced in [−1, 1] (samples dense near the centre where the profile is peaked, as
//! in \[Jimenez2015\]), with ρ = `range_sigmas` × the widest Gaussian's σ. Each sample's weight is the
//! exact integral of A over its bin (erf), with the outermost bins running to ±∞, so the weights
//! of every channel sum to 1 and the blur conserves energy at any sample count.
//!
//! # Screen space
//! The blur runs twice (horizontal, then vertical) over the skin radiance. A sample at kernel
//! offset x mm lies x·`width`·f/z pixels away, f the focal length in pixels and z the centre's
//! view depth in mm. Depth awareness follows \[Jimenez2015\]: a sample whose depth differs from the
//! centre's by Δz is replaced by the centre value in proportion t = clamp(|Δz| / `follow_mm`, 0, 1),
//! so light does not bleed across silhouettes; samples off the skin (background, eyes) are replaced
//! by the centre value entirely.
//!
//! # Reference
//! [`reference_blur`] applies the exact profile in 2D over its full support: for every pixel,
//! every pixel square around it weighted by the profile's exact integral over that square (each
//! Gaussian is separable, so the integral is a product of erf differences; the outermost ring
//! absorbs the tails), with the same depth and coverage rules. It is the brute-force reference
//! the separable kernel's error is measured against (docs/BENCHMARKS.md).

// RGB triples are indexed by channel throughout; iterator chains over three channels read worse.
#![allow(clippy::needless_range_loop)]

use crate::error::{RenderError, Result};

/// One Gaussian of a sum-of-Gaussians profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gaussian {
    /// Variance v, mm².
    pub variance_mm2: f64,
    /// Weight per linear RGB channel.
    pub weight: [f64; 3],
}

/// A radial diffusion profile as a sum of Gaussians.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffusionProfile {
    /// The Gaussians, narrowest first.
    pub gaussians: Vec<Gaussian>,
}

/// Smallest sample count of a separable kernel.
pub const MIN_SAMPLES: u32 = 3;
/// Largest sample count of a separable kernel (the size of the GPU uniform array).
pub const MAX_SAMPLES: u32 = 33;

impl DiffusionProfile {
    /// Human skin: \[dEon2007\] (d'Eon, Luebke and Enderton, "Efficient rendering of human skin"), the
    /// six-Gaussian fit of the three-layer skin model (variances in mm²).
    pub fn skin() -> Self {
        let g = |v: f64, r: f64, gr: f64, b: f64| Gaussian { variance_mm2: v, weight: [r, gr, b] };
        DiffusionProfile {
            gaussians: vec![
                g(0.0064, 0.233, 0.455, 0.649),
                g(0.0484, 0.100, 0.336, 0.344),
                g(0.187, 0.118, 0.198, 0.0),
                g(0.567, 0.113, 0.007, 0.007),
                g(1.99, 0.358, 0.004, 0.0),
                g(7.41, 0.078, 0.0, 0.0),
            ],
        }
    }

    /// The profile with every distance multiplied by `width` (variances by width²). Width 0
    /// gives a Dirac profile: no scattering.
    pub fn scaled(&self, width: f64) -> Self {
        let gaussians = self
            .gaussians
            .iter()
            .map(|g| Gaussian { variance_mm2: g.variance_mm2 * width * width, weight: g.weight })
            .collect();
        DiffusionProfile { gaussians }
    }

    /// σ of the widest Gaussian, mm.
    pub fn max_sigma_mm(&self) -> f64 {
        self.gaussians.iter().map(|g| g.variance_mm2.sqrt()).fold(0.0, f64::max)
    }

    /// R(r): the radial profile at distance `r_mm`, per mm².
    pub fn radial(&self, r_mm: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        for g in self.gaussians.iter().filter(|g| g.variance_mm2 > 0.0) {
            let v = g.variance_mm2;
            let value = (-r_mm * r_mm / (2.0 * v)).exp() / (2.0 * std::f64::consts::PI * v);
            for c in 0..3 {
                out[c] += g.weight[c] * value;
            }
        }
        out
    }

    /// The 1D marginal A(x) = ∫ R(√(x²+y²)) dy, per mm.
    pub fn marginal(&self, x_mm: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        for g in self.gaussians.iter().filter(|g| g.variance_mm2 > 0.0) {
            let v = g.variance_mm2;
            let value = (-x_mm * x_mm / (2.0 * v)).exp() / (2.0 * std::f64::consts::PI * v).sqrt();
            for c in 0..3 {
                out[c] += g.weight[c] * value;
            }
        }
        out
    }

    /// ∫ A over [a, b] (either end may be infinite). A Gaussian of variance 0 is a Dirac at 0.
    pub fn marginal_integral(&self, a_mm: f64, b_mm: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        for g in &self.gaussians {
            let mass = gaussian_mass(g.variance_mm2, a_mm, b_mm);
            for c in 0..3 {
                out[c] += g.weight[c] * mass;
            }
        }
        out
    }
}

/// Mass of a centred 1D Gaussian of variance `v` over [a, b); a Dirac for v = 0 (its mass counts
/// in the bin whose half-open interval holds 0).
fn gaussian_mass(v: f64, a: f64, b: f64) -> f64 {
    if v <= 0.0 {
        return if a <= 0.0 && 0.0 < b { 1.0 } else { 0.0 };
    }
    let s = (2.0 * v).sqrt();
    0.5 * (erf(b / s) - erf(a / s))
}

/// Error function, accurate to ~1e-15 absolute: a series of positive terms below 3, the continued
/// fraction of erfc above; ±1 at ±∞.
pub fn erf(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    let ax = x.abs();
    let value = if ax < 3.0 {
        // erf(x) = 2/√π · exp(−x²) · Σ 2ⁿ x^(2n+1) / (1·3·…·(2n+1)): positive terms, no cancellation.
        let x2 = ax * ax;
        let mut term = ax;
        let mut sum = ax;
        let mut n = 0.0;
        while term > 1e-17 * sum {
            n += 1.0;
            term *= 2.0 * x2 / (2.0 * n + 1.0);
            sum += term;
        }
        std::f64::consts::FRAC_2_SQRT_PI * (-x2).exp() * sum
    } else if ax < 27.0 {
        // erfc(x) = exp(−x²)/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …)))), evaluated backwards.
        let mut f = ax;
        for k in (1..=60).rev() {
            f = ax + (k as f64 * 0.5) / f;
        }
        1.0 - (-ax * ax).exp() / (std::f64::consts::PI.sqrt() * f)
    } else {
        1.0
    };
    value.copysign(x)
}

/// One sample of a separable kernel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KernelSample {
    /// Offset from the centre, mm (before the width scale).
    pub offset_mm: f32,
    /// Weight per linear RGB channel.
    pub weight: [f32; 3],
}

/// The 1D kernel of the separable blur.
#[derive(Clone, Debug, PartialEq)]
pub struct SeparableKernel {
    /// Samples in increasing offset; the middle one is the centre (offset 0).
    pub samples: Vec<KernelSample>,
}

impl SeparableKernel {
    /// Builds an `n`-sample kernel (odd, [`MIN_SAMPLES`]..=[`MAX_SAMPLES`]) for `profile`, samples
    /// spread over ±`range_sigmas` × the profile's widest σ.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an even or out-of-range `n` or a non-positive range.
    pub fn new(profile: &DiffusionProfile, n: u32, range_sigmas: f64) -> Result<Self> {
        if !(MIN_SAMPLES..=MAX_SAMPLES).contains(&n) || n.is_multiple_of(2) {
            return Err(RenderError::Invalid(format!(
                "SSS sample count {n}: must be odd, {MIN_SAMPLES} to {MAX_SAMPLES} (the kernel is symmetric about its centre sample)"
            )));
        }
        if !(range_sigmas.is_finite() && range_sigmas > 0.0) {
            return Err(RenderError::Invalid(format!("SSS kernel range {range_sigmas} σ: must be positive")));
        }
        let rho = range_sigmas * profile.max_sigma_mm();
        let offsets: Vec<f64> = (0..n)
            .map(|j| {
                let t = -1.0 + 2.0 * j as f64 / (n - 1) as f64;
                rho * t * t.abs()
            })
            .collect();
        let mut samples = Vec::with_capacity(n as usize);
        for j in 0..n as usize {
            let lo = if j == 0 { f64::NEG_INFINITY } else { 0.5 * (offsets[j - 1] + offsets[j]) };
            let hi = if j + 1 == n as usize { f64::INFINITY } else { 0.5 * (offsets[j] + offsets[j + 1]) };
            let w = profile.marginal_integral(lo, hi);
            samples.push(KernelSample { offset_mm: offsets[j] as f32, weight: w.map(|x| x as f32) });
        }
        Ok(SeparableKernel { samples })
    }

    /// Samples packed for the GPU: (offset mm, weight r, g, b), padded with zero samples to
    /// [`MAX_SAMPLES`].
    pub fn to_gpu(&self) -> [[f32; 4]; MAX_SAMPLES as usize] {
        let mut out = [[0.0; 4]; MAX_SAMPLES as usize];
        for (o, s) in out.iter_mut().zip(&self.samples) {
            *o = [s.offset_mm, s.weight[0], s.weight[1], s.weight[2]];
        }
        out
    }
}

/// A screen-space image of skin radiance with what the blur needs to know about each pixel.
#[derive(Clone, Copy, Debug)]
pub struct SkinImage<'a> {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Skin radiance before scattering, row-major, row 0 at the top.
    pub rgb: &'a [[f32; 3]],
    /// Whether the pixel is skin (false for background, eyes).
    pub skin: &'a [bool],
    /// View depth of each pixel, mm.
    pub depth_mm: &'a [f32],
    /// Focal length in pixels: a length of 1 mm at depth z spans `focal_px / z` pixels.
    pub focal_px: f32,
}

/// Depth-aware mix of a sample toward the centre value (the rule of the GPU pass).
fn follow(sample: [f32; 3], centre: [f32; 3], dz: f32, follow_mm: f32) -> [f32; 3] {
    let t = if follow_mm > 0.0 { (dz.abs() / follow_mm).clamp(0.0, 1.0) } else { 1.0 };
    std::array::from_fn(|c| sample[c] + (centre[c] - sample[c]) * t)
}

/// The brute-force reference: the exact 2D profile (scaled by `width`) over its full support at
/// every skin pixel, with the depth and coverage rules of the GPU pass. Non-skin pixels are
/// returned unchanged. Runs on all cores; O(pixels × support²).
pub fn reference_blur(image: &SkinImage<'_>, profile: &DiffusionProfile, width: f32, follow_mm: f32) -> Vec<[f32; 3]> {
    let profile = profile.scaled(width as f64);
    let n = image.width * image.height;
    let mut out = image.rgb[..n].to_vec();
    if width <= 0.0 {
        return out;
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).max(1);
    let rows_per = image.height.div_ceil(threads);
    std::thread::scope(|scope| {
        for (chunk_index, chunk) in out.chunks_mut(rows_per * image.width).enumerate() {
            let profile = &profile;
            scope.spawn(move || {
                let y0 = chunk_index * rows_per;
                for (i, px) in chunk.iter_mut().enumerate() {
                    let (x, y) = (i % image.width, y0 + i / image.width);
                    *px = reference_pixel(image, profile, x, y, follow_mm);
                }
            });
        }
    });
    out
}

fn reference_pixel(image: &SkinImage<'_>, profile: &DiffusionProfile, x: usize, y: usize, follow_mm: f32) -> [f32; 3] {
    let p = y * image.width + x;
    let centre = image.rgb[p];
    if !image.skin[p] {
        return centre;
    }
    let z = image.depth_mm[p].max(1e-3);
    let mm_per_px = (z / image.focal_px) as f64;
    let support_mm = 4.5 * profile.max_sigma_mm();
    let r = ((support_mm / mm_per_px).ceil() as i64).max(1);
    // Per-Gaussian 1D bin masses for offsets −r..=r, outer bins open to infinity.
    let bins = (2 * r + 1) as usize;
    let mut mass = vec![0.0f64; profile.gaussians.len() * bins];
    for (gi, g) in profile.gaussians.iter().enumerate() {
        for k in 0..bins {
            let d = k as i64 - r;
            let lo = if d == -r { f64::NEG_INFINITY } else { (d as f64 - 0.5) * mm_per_px };
            let hi = if d == r { f64::INFINITY } else { (d as f64 + 0.5) * mm_per_px };
            mass[gi * bins + k] = gaussian_mass(g.variance_mm2, lo, hi);
        }
    }
    let mut sum = [0.0f64; 3];
    for ky in 0..bins {
        let qy = y as i64 + ky as i64 - r;
        for kx in 0..bins {
            let qx = x as i64 + kx as i64 - r;
            let mut w = [0.0f64; 3];
            for (gi, g) in profile.gaussians.iter().enumerate() {
                let m = mass[gi * bins + kx] * mass[gi * bins + ky];
                if m == 0.0 {
                    continue;
                }
                for c in 0..3 {
                    w[c] += g.weight[c] * m;
                }
            }
            let inside = qx >= 0 && qy >= 0 && (qx as usize) < image.width && (qy as usize) < image.height;
            let value = if inside {
                let q = qy as usize * image.width + qx as usize;
                if image.skin[q] { follow(image.rgb[q], centre, image.depth_mm[q] - z, follow_mm) } else { centre }
            } else {
                centre
            };
            for c in 0..3 {
                sum[c] += w[c] * value[c] as f64;
            }
        }
    }
    sum.map(|s| s as f32)
}

/// The separable blur on the CPU, with the GPU pass's sampling rules (bilinear fetches,
/// coverage-aware, nearest depth): for tests of the shader and for studying the kernel without a
/// GPU. `horizontal` selects the direction.
pub fn separable_pass_cpu(
    image: &SkinImage<'_>,
    kernel: &SeparableKernel,
    width: f32,
    follow_mm: f32,
    horizontal: bool,
) -> Vec<[f32; 3]> {
    let (w, h) = (image.width, image.height);
    let mut out = image.rgb[..w * h].to_vec();
    for y in 0..h {
        for x in 0..w {
            let p = y * w + x;
            if !image.skin[p] {
                continue;
            }
            let centre = image.rgb[p];
            let z = image.depth_mm[p].max(1e-3);
            let px_per_mm = image.focal_px / z;
            let mut sum = [0.0f32; 3];
            for s in &kernel.samples {
                let o = s.offset_mm * width * px_per_mm;
                let (sx, sy) = if horizontal { (x as f32 + o, y as f32) } else { (x as f32, y as f32 + o) };
                let value = bilinear_skin(image, sx, sy, centre, z, follow_mm);
                for c in 0..3 {
                    sum[c] += value[c] * s.weight[c];
                }
            }
            out[p] = sum;
        }
    }
    out
}

/// Bilinear fetch at pixel coordinates (pixel centres at integers), where missing or non-skin
/// texels count as the centre value and the depth rule uses the nearest texel.
fn bilinear_skin(image: &SkinImage<'_>, sx: f32, sy: f32, centre: [f32; 3], z: f32, follow_mm: f32) -> [f32; 3] {
    let (w, h) = (image.width as i64, image.height as i64);
    let (fx, fy) = (sx.floor(), sy.floor());
    let (tx, ty) = (sx - fx, sy - fy);
    let mut acc = [0.0f32; 3];
    let mut skin_weight = 0.0f32;
    for (dx, dy, wt) in
        [(0, 0, (1.0 - tx) * (1.0 - ty)), (1, 0, tx * (1.0 - ty)), (0, 1, (1.0 - tx) * ty), (1, 1, tx * ty)]
    {
        let (qx, qy) = ((fx as i64 + dx).clamp(0, w - 1), (fy as i64 + dy).clamp(0, h - 1));
        let q = (qy * w + qx) as usize;
        if image.skin[q] && wt > 0.0 {
            for c in 0..3 {
                acc[c] += image.rgb[q][c] * wt;
            }
            skin_weight += wt;
        }
    }
    let sample: [f32; 3] = std::array::from_fn(|c| acc[c] + (1.0 - skin_weight) * centre[c]);
    let (nx, ny) = ((sx.round() as i64).clamp(0, w - 1), (sy.round() as i64).clamp(0, h - 1));
    let nz = image.depth_mm[(ny * w + nx) as usize];
    follow(sample, centre, nz - z, follow_mm)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::excessive_precision)]
    fn erf_matches_known_values() {
        // Values from mpmath at 30 digits (kept as printed).
        for (x, e) in [
            (0.0, 0.0),
            (0.1, 0.1124629160182848922032750717),
            (0.5, 0.5204998778130465376827466538),
            (1.0, 0.8427007929497148693412206350),
            (2.0, 0.9953222650189527341620692563),
            (2.9, 0.9999589021219005411643161325),
            (3.1, 0.9999883513426328004039662938),
            (4.0, 0.9999999845827420997199811478),
        ] {
            assert!((erf(x) - e).abs() < 2e-15, "erf({x}) = {} vs {e}", erf(x));
            assert!((erf(-x) + e).abs() < 2e-15);
        }
        assert_eq!(erf(f64::INFINITY), 1.0);
        assert_eq!(erf(f64::NEG_INFINITY), -1.0);
    }

    #[test]
    fn skin_profile_integrates_to_one_per_channel() {
        let p = DiffusionProfile::skin();
        let total = p.marginal_integral(f64::NEG_INFINITY, f64::INFINITY);
        for c in total {
            assert!((c - 1.0).abs() < 1e-12, "{total:?}");
        }
        // Radial integral by quadrature: ∫ 2πr R(r) dr = 1.
        let (mut s, dr) = ([0.0; 3], 1e-4);
        for i in 0..200_000 {
            let r = (i as f64 + 0.5) * dr;
            let v = p.radial(r);
            for c in 0..3 {
                s[c] += 2.0 * std::f64::consts::PI * r * v[c] * dr;
            }
        }
        for c in s {
            assert!((c - 1.0).abs() < 1e-6, "{s:?}");
        }
    }

    #[test]
    fn kernel_weights_sum_to_one_and_are_symmetric() {
        let p = DiffusionProfile::skin();
        for n in (MIN_SAMPLES..=MAX_SAMPLES).step_by(2) {
            let k = SeparableKernel::new(&p, n, 3.0).expect("kernel");
            assert_eq!(k.samples.len(), n as usize);
            assert_eq!(k.samples[n as usize / 2].offset_mm, 0.0);
            for c in 0..3 {
                let s: f64 = k.samples.iter().map(|s| s.weight[c] as f64).sum();
                assert!((s - 1.0).abs() < 1e-6, "n={n} c={c} sum={s}");
            }
            for j in 0..n as usize {
                let (a, b) = (k.samples[j], k.samples[n as usize - 1 - j]);
                assert_eq!(a.offset_mm, -b.offset_mm);
                assert!((a.weight[0] - b.weight[0]).abs() < 1e-6);
            }
        }
        assert!(SeparableKernel::new(&p, 4, 3.0).is_err());
        assert!(SeparableKernel::new(&p, 35, 3.0).is_err());
        assert!(SeparableKernel::new(&p, 1, 3.0).is_err());
    }

    fn test_image(w: usize, h: usize) -> (Vec<[f32; 3]>, Vec<bool>, Vec<f32>) {
        let mut rgb = vec![[0.0; 3]; w * h];
        let mut skin = vec![false; w * h];
        let depth = vec![500.0; w * h];
        for y in 0..h {
            for x in 0..w {
                let p = y * w + x;
                skin[p] = x > 2 && x < w - 3;
                // A bright stripe on a dim field.
                rgb[p] = if (w / 2..w / 2 + 3).contains(&x) { [1.0, 0.8, 0.6] } else { [0.1, 0.1, 0.1] };
            }
        }
        (rgb, skin, depth)
    }

    #[test]
    fn width_zero_is_identity_for_reference_and_separable() {
        let (w, h) = (40, 8);
        let (rgb, skin, depth) = test_image(w, h);
        let img = SkinImage { width: w, height: h, rgb: &rgb, skin: &skin, depth_mm: &depth, focal_px: 1000.0 };
        assert_eq!(reference_blur(&img, &DiffusionProfile::skin(), 0.0, 2.0), rgb);
        let k = SeparableKernel::new(&DiffusionProfile::skin(), 17, 3.0).expect("kernel");
        let out = separable_pass_cpu(&img, &k, 0.0, 2.0, true);
        for (a, b) in out.iter().zip(&rgb) {
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() <= 1e-6 * b[c].abs().max(1e-3), "{a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn blur_conserves_energy_inside_uniform_skin_and_spreads_red_most() {
        let (w, h) = (121, 121);
        let mut rgb = vec![[0.0f32; 3]; w * h];
        rgb[60 * w + 60] = [1.0, 1.0, 1.0];
        let skin = vec![true; w * h];
        let depth = vec![500.0; w * h];
        // 0.25 mm per pixel.
        let img = SkinImage { width: w, height: h, rgb: &rgb, skin: &skin, depth_mm: &depth, focal_px: 2000.0 };
        let out = reference_blur(&img, &DiffusionProfile::skin(), 1.0, 2.0);
        let total: [f64; 3] = std::array::from_fn(|c| out.iter().map(|p| p[c] as f64).sum());
        // An impulse in the middle spreads into the whole image; the centre pixel still gets the
        // mass of its neighbours' kernels, so totals match to the tail beyond the image.
        for t in total {
            assert!((t - 1.0).abs() < 2e-3, "{total:?}");
        }
        // Red scatters farthest: at 3 mm from the impulse red dominates.
        let far = out[60 * w + 72];
        assert!(far[0] > 10.0 * far[2] && far[0] > far[1], "{far:?}");
        // The separable kernel's rank-1 approximation keeps the same total.
        let k = SeparableKernel::new(&DiffusionProfile::skin(), 33, 3.0).expect("kernel");
        let hpass = separable_pass_cpu(&img, &k, 1.0, 2.0, true);
        let img2 = SkinImage { rgb: &hpass, ..img };
        let sep = separable_pass_cpu(&img2, &k, 1.0, 2.0, false);
        let total_sep: [f64; 3] = std::array::from_fn(|c| sep.iter().map(|p| p[c] as f64).sum());
        for (a, b) in total_sep.iter().zip(total) {
            assert!((a - b).abs() < 5e-3, "{total_sep:?} vs {total:?}");
        }
    }

    #[test]
    fn blur_does_not_cross_depth_discontinuities() {
        let (w, h) = (60, 5);
        let rgb: Vec<[f32; 3]> = (0..w * h).map(|i| if i % w < 30 { [1.0; 3] } else { [0.0; 3] }).collect();
        let skin = vec![true; w * h];
        // Right half 50 mm behind the left.
        let depth: Vec<f32> = (0..w * h).map(|i| if i % w < 30 { 500.0 } else { 550.0 }).collect();
        let img = SkinImage { width: w, height: h, rgb: &rgb, skin: &skin, depth_mm: &depth, focal_px: 2000.0 };
        let out = reference_blur(&img, &DiffusionProfile::skin(), 1.0, 2.0);
        assert_eq!(out[2 * w + 31], [0.0; 3]);
        for c in out[2 * w + 28] {
            assert!((c - 1.0).abs() < 1e-6);
        }
    }
}
