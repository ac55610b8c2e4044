//! Environment lighting: HDR equirectangular maps and their spherical-harmonics irradiance.
//!
//! \[Benmounah2009\] section 4.1.2 (eq. 4-8) with the closed form of \[Ramamoorthi2001\], "An
//! efficient representation for irradiance environment maps" (sections 2-3). Irradiance on a
//! surface with normal `n` lit by distant radiance `L(ω)` (\[Benmounah2009\] eq. 4 without the
//! Fresnel factor) is
//!
//! ```text
//! E(n) = ∫ L(ω) max(0, n·ω) dω  ≈  Σ_{l≤2} Σ_m Â_l L_lm Y_lm(n),   L_lm = ∫ L(ω) Y_lm(ω) dω
//! Â_0 = π,  Â_1 = 2π/3,  Â_2 = π/4
//! ```
//!
//! The Â_l are the Legendre coefficients of the clamped cosine (Funk-Hecke theorem), so the
//! convolution is exact for the first nine terms; what is lost is the l > 2 part of the cosine,
//! which bounds the error for any smooth environment to a few percent (measured in
//! `tests/env.rs`). [`ShIrradiance`] stores `c_i = Â_l L_lm`, so evaluation is `E(n) = Σ c_i Y_i(n)`.
//!
//! **Corrections to \[Benmounah2009\].** Eq. 8 multiplies the coefficients of L, Ft and the cosine G
//! index by index. The SH coefficients of a product are not the products of the coefficients;
//! the form is right only when Ft and G are zonal (functions of `n·ω`), and then the kernel to use
//! is the Legendre expansion of the product `Ft(μ)·μ`, not `F_l G_l`. We fold only the clamped
//! cosine (the Â_l above); the renderer applies the Fresnel transmittance, which for skin
//! (η ≈ 1.4) is nearly constant over the hemisphere. Eq. 6 weights each texel by its solid angle;
//! here each texel is taken as constant radiance over its cell and the basis is integrated over
//! the cell in closed form, so a constant map projects exactly at any resolution.
//!
//! # Conventions
//! World frame: right-handed, +Y up, the face looks toward +Z (the camera sits on +Z).
//! An equirectangular map of `width × height` texels is row-major, row 0 at the top (+Y).
//! For continuous texel coordinates `(x, y)` with `x ∈ [0, width]`, `y ∈ [0, height]`:
//!
//! ```text
//! u = x / width,  v = y / height,  φ = 2π u − π,  θ = π v        (θ polar angle from +Y)
//! d(x, y) = (sin φ sin θ,  cos θ,  −cos φ sin θ)
//! ```
//!
//! Texel `(i, j)` covers `[i, i+1] × [j, j+1]`; its centre is `(i + 0.5, j + 0.5)`. So the image
//! centre (u = 0.5) is −Z, what the camera sees behind the head; u = 0.75 is +X (to the right
//! when looking down −Z, so the map is not mirrored); the left and right edges (u = 0, 1) are +Z,
//! the light that falls on the face. The inverse is [`direction_to_uv`].
//!
//! Real SH basis in the same world (x, y, z) frame, coefficients in this order (the shader's):
//!
//! | i | Y        | function                 | i | Y        | function                  |
//! |---|----------|--------------------------|---|----------|---------------------------|
//! | 0 | Y_0^0    | 0.282095                 | 5 | Y_2^-1   | 1.092548 · y z            |
//! | 1 | Y_1^-1   | 0.488603 · y             | 6 | Y_2^0    | 0.315392 · (3 z² − 1)     |
//! | 2 | Y_1^0    | 0.488603 · z             | 7 | Y_2^1    | 1.092548 · x z            |
//! | 3 | Y_1^1    | 0.488603 · x             | 8 | Y_2^2    | 0.546274 · (x² − y²)      |
//! | 4 | Y_2^-2   | 1.092548 · x y           |   |          |                           |
//!
//! (The polar axis of this basis is world Z, not up; any orthonormal frame spans the same
//! l ≤ 2 space, the only requirement is that projection and evaluation agree, which they do.)

use std::f64::consts::PI;
use std::path::Path;

use glam::{Vec2, Vec3};

use crate::error::{RenderError, Result};

/// Normalisation constants of the real SH basis: `1/(2√π)`, `√(3/4π)`, `√(15/4π)`, `√(5/16π)`,
/// `√(15/16π)`.
const K0: f64 = 0.282_094_791_773_878_14;
const K1: f64 = 0.488_602_511_902_919_9;
const K2: f64 = 1.092_548_430_592_079_2;
const K20: f64 = 0.315_391_565_252_520_05;
const K22: f64 = 0.546_274_215_296_039_6;
/// Clamped-cosine convolution factors Â_l (R&H 2001) for l = 0, 1, 2.
const A0: f64 = PI;
const A1: f64 = 2.0 * PI / 3.0;
const A2: f64 = PI / 4.0;
/// Band l of coefficient i.
const BAND_FACTOR: [f64; 9] = [A0, A1, A1, A1, A2, A2, A2, A2, A2];

/// WGSL for [`ShIrradiance::eval`]: the same formula, constants and clamp. Paste it into shaders
/// and upload [`ShIrradiance::to_gpu`] as a `array<vec4<f32>, 9>` uniform.
pub const WGSL_SH_EVAL: &str = r"
// Irradiance from 9 SH coefficients (rgb in .xyz), already convolved with the clamped cosine.
// Keep in sync with rouge_render::env::ShIrradiance::eval (same basis order and constants).
fn sh_irradiance(c: array<vec4<f32>, 9>, n: vec3<f32>) -> vec3<f32> {
    let e = c[0].xyz * 0.2820948
        + c[1].xyz * (0.48860252 * n.y)
        + c[2].xyz * (0.48860252 * n.z)
        + c[3].xyz * (0.48860252 * n.x)
        + c[4].xyz * (1.0925485 * (n.x * n.y))
        + c[5].xyz * (1.0925485 * (n.y * n.z))
        + c[6].xyz * (0.31539157 * (3.0 * n.z * n.z - 1.0))
        + c[7].xyz * (1.0925485 * (n.x * n.z))
        + c[8].xyz * (0.54627424 * (n.x * n.x - n.y * n.y));
    return max(e, vec3<f32>(0.0));
}
";

/// An HDR environment: linear RGB radiance on an equirectangular grid (conventions in the module
/// doc). Row-major, row 0 = top (+Y).
#[derive(Clone, Debug)]
pub struct EnvMap {
    /// Texels per row (azimuth).
    pub width: usize,
    /// Rows (polar angle).
    pub height: usize,
    /// `width * height` radiances, finite and non-negative.
    pub texels: Vec<[f32; 3]>,
}

/// Irradiance `E(n) = Σ_i c_i Y_i(n)`, already convolved with the clamped cosine; linear RGB,
/// W/m² for radiance in W/(m² sr). Coefficient order and basis in the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShIrradiance {
    /// `c_i = Â_l L_lm`, RGB.
    pub coeffs: [[f32; 3]; 9],
}

/// The direction of the equirectangular coordinates `(u, v) ∈ [0, 1]²` (module doc).
fn uv_direction(u: f64, v: f64) -> [f64; 3] {
    let (sin_p, cos_p) = (2.0 * PI * u - PI).sin_cos();
    let (sin_t, cos_t) = (PI * v).sin_cos();
    [sin_p * sin_t, cos_t, -cos_p * sin_t]
}

/// The equirectangular `(u, v) ∈ [0, 1]²` of direction `d` (need not be unit length), the inverse
/// of [`EnvMap::direction`] divided by the size: `u = (atan2(x, −z) + π) / 2π`, `v = acos(y/|d|)/π`.
/// The zero vector gives `(0.5, 0.5)`.
pub fn direction_to_uv(d: Vec3) -> Vec2 {
    let d = d.normalize_or(Vec3::NEG_Z);
    let phi = d.x.atan2(-d.z);
    Vec2::new((phi + std::f32::consts::PI) / std::f32::consts::TAU, d.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI)
}

/// Radiance of the default studio dome toward unit direction `d`: a smooth gradient brighter above,
/// `L(d) = (0.1 + 0.1 y + 0.05 y²) · (1.0, 0.96, 0.90)`, i.e. 0.25 at the zenith, 0.1 at the
/// horizon and 0.05 at the nadir (relative units; scale with [`ShIrradiance::scaled`]). Being a
/// quadratic in `y` it lies in the l ≤ 2 SH space, so [`ShIrradiance::studio`] is exact.
pub fn studio_radiance(d: Vec3) -> [f32; 3] {
    let s = 0.1 + 0.1 * d.y + 0.05 * d.y * d.y;
    STUDIO_TINT.map(|t| s * t)
}

const STUDIO_TINT: [f32; 3] = [1.0, 0.96, 0.90];

/// Widest and tallest environment map read (texels), checked in the file's header: 16384 × 8192
/// is the largest equirectangular HDRI commonly published (Poly Haven's 16K).
pub const MAX_ENV_SIDE_PX: usize = 16384;
/// Largest environment file read (bytes), checked before reading: a 16K map of RGB f32,
/// uncompressed, is 1.6 GB.
pub const MAX_ENV_FILE_BYTES: u64 = 2 << 30;

impl EnvMap {
    /// Loads the first layer with R, G and B channels of an OpenEXR file (scan lines or tiles,
    /// f16, f32 or u32 samples; alpha and other channels are ignored; the largest mip level).
    ///
    /// # Errors
    /// [`RenderError::File`] naming the file and saying why: it cannot be read, it is not an
    /// OpenEXR file, it is not a regular file or larger than [`MAX_ENV_FILE_BYTES`], its header
    /// claims more than [`MAX_ENV_SIDE_PX`] texels on a side, no layer has R, G and B channels,
    /// the image is empty, or a texel is
    /// non-finite or negative (the message gives its `(x, y)`, row 0 at the top, and its value).
    pub fn load_exr(path: impl AsRef<Path>) -> Result<EnvMap> {
        let path = path.as_ref();
        let fail = |m: String| RenderError::file(path, m);
        // A regular file of bounded size (not a pipe or a device), and a size in its header
        // that fits, before any texel is decoded: a header of a few bytes can claim any size.
        let bytes = rouge_measure::file_set::read_bounded(path, MAX_ENV_FILE_BYTES)
            .map_err(|e| fail(format!("cannot read: {e}")))?;
        let (width, height, texels) = rouge_model::hdr::decode_rgb_exr(&bytes, MAX_ENV_SIDE_PX).map_err(fail)?;
        if let Some(i) = texels.iter().position(|t| t.iter().any(|c| !c.is_finite() || *c < 0.0)) {
            let t = texels[i];
            let what = if t.iter().all(|c| c.is_finite()) { "negative" } else { "non-finite" };
            return Err(fail(format!(
                "{what} radiance at texel (x {}, y {}) (row 0 = top): RGB = ({}, {}, {})",
                i % width,
                i / width,
                t[0],
                t[1],
                t[2]
            )));
        }
        Ok(EnvMap { width, height, texels })
    }

    /// A map whose texel `(i, j)` is `f` of the unit direction of its centre `(i + ½, j + ½)`.
    pub fn from_fn(width: usize, height: usize, f: impl Fn(Vec3) -> [f32; 3]) -> EnvMap {
        let mut texels = Vec::with_capacity(width * height);
        for j in 0..height {
            for i in 0..width {
                texels.push(f(Self::grid_direction(i as f64 + 0.5, j as f64 + 0.5, width, height)));
            }
        }
        EnvMap { width, height, texels }
    }

    fn grid_direction(x: f64, y: f64, width: usize, height: usize) -> Vec3 {
        let d = uv_direction(x / width as f64, y / height as f64);
        Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32)
    }

    /// Unit direction of continuous texel coordinates `(x, y)` (module doc): `x ∈ [0, width]`,
    /// `y ∈ [0, height]`, texel `(i, j)` has its centre at `(i + 0.5, j + 0.5)`.
    pub fn direction(&self, x: f32, y: f32) -> Vec3 {
        Self::grid_direction(f64::from(x), f64::from(y), self.width, self.height)
    }

    /// Projects the map on the nine SH basis functions and convolves with the clamped cosine.
    ///
    /// `L_i = Σ_texels L_texel ∫_cell Y_i(ω) sin θ dθ dφ` with the cell integral in closed form
    /// (it separates into a θ part and a φ part for every basis function), then `c_i = Â_l L_i`.
    /// Sums in f64. An empty map gives [`ShIrradiance::zero`].
    pub fn sh_irradiance(&self) -> ShIrradiance {
        let mut proj = [[0.0f64; 3]; 9];
        let (w, h) = (self.width, self.height);
        if w == 0 || h == 0 || self.texels.len() != w * h {
            return ShIrradiance::zero();
        }
        let cols: Vec<[f64; 6]> = (0..w).map(|i| phi_integrals(i, w)).collect();
        for (j, row) in self.texels.chunks_exact(w).enumerate() {
            let [t1, tc, ts, tsc, tsss, tcc] = theta_integrals(j, h);
            // s[k][ch] = Σ_i L_ij · (φ integral k over column i).
            let mut s = [[0.0f64; 3]; 6];
            for (l, p) in row.iter().zip(&cols) {
                for (sk, pk) in s.iter_mut().zip(p) {
                    for ch in 0..3 {
                        sk[ch] += f64::from(l[ch]) * pk;
                    }
                }
            }
            let [p1, psin, pcos, psc, pss, pcc] = s;
            for ch in 0..3 {
                proj[0][ch] += K0 * t1 * p1[ch];
                proj[1][ch] += K1 * tc * p1[ch];
                proj[2][ch] -= K1 * ts * pcos[ch];
                proj[3][ch] += K1 * ts * psin[ch];
                proj[4][ch] += K2 * tsc * psin[ch];
                proj[5][ch] -= K2 * tsc * pcos[ch];
                proj[6][ch] += K20 * (3.0 * tsss * pcc[ch] - t1 * p1[ch]);
                proj[7][ch] -= K2 * tsss * psc[ch];
                proj[8][ch] += K22 * (tsss * pss[ch] - tcc * p1[ch]);
            }
        }
        let mut coeffs = [[0.0f32; 3]; 9];
        for ((c, p), a) in coeffs.iter_mut().zip(&proj).zip(BAND_FACTOR) {
            *c = p.map(|v| (a * v) as f32);
        }
        ShIrradiance { coeffs }
    }

    /// Reference irradiance `∫ L(ω) max(0, n·ω) dω` summed over every texel: radiance times the
    /// clamped cosine at the texel centre times the texel's exact solid angle
    /// `Δφ (cos θ_j − cos θ_{j+1})`. f64; `normal` is normalised (zero gives zero). O(width·height).
    pub fn irradiance_brute_force(&self, normal: Vec3) -> [f64; 3] {
        let (w, h) = (self.width, self.height);
        let n = normal.normalize_or_zero().as_dvec3();
        let mut e = [0.0f64; 3];
        if w == 0 || h == 0 || self.texels.len() != w * h {
            return e;
        }
        let dphi = 2.0 * PI / w as f64;
        let cols: Vec<(f64, f64)> = (0..w).map(|i| (dphi * (i as f64 + 0.5) - PI).sin_cos()).collect();
        for (j, row) in self.texels.chunks_exact(w).enumerate() {
            let (sin_t, cos_t) = (PI * (j as f64 + 0.5) / h as f64).sin_cos();
            let d_omega = theta_integrals(j, h)[0] * dphi;
            for (l, &(sin_p, cos_p)) in row.iter().zip(&cols) {
                let cos = n.x * sin_p * sin_t + n.y * cos_t - n.z * cos_p * sin_t;
                if cos > 0.0 {
                    for ch in 0..3 {
                        e[ch] += f64::from(l[ch]) * cos * d_omega;
                    }
                }
            }
        }
        e
    }
}

/// `∫ g(θ) sin θ dθ` over row `j` of `h` (θ from πj/h to π(j+1)/h) for
/// g = 1, cos θ, sin θ, sin θ cos θ, sin² θ, cos² θ, in that order.
fn theta_integrals(j: usize, h: usize) -> [f64; 6] {
    let (a, b) = (PI * j as f64 / h as f64, PI * (j as f64 + 1.0) / h as f64);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    // cos a − cos b without cancellation near the poles.
    let t1 = 2.0 * (0.5 * (a + b)).sin() * (0.5 * (b - a)).sin();
    let tcc = (ca * ca * ca - cb * cb * cb) / 3.0;
    [
        t1,
        0.5 * (sb * sb - sa * sa),
        0.5 * (b - a) - 0.25 * ((2.0 * b).sin() - (2.0 * a).sin()),
        (sb * sb * sb - sa * sa * sa) / 3.0,
        t1 - tcc,
        tcc,
    ]
}

/// `∫ g(φ) dφ` over column `i` of `w` (φ from 2πi/w − π to 2π(i+1)/w − π) for
/// g = 1, sin φ, cos φ, sin φ cos φ, sin² φ, cos² φ, in that order.
fn phi_integrals(i: usize, w: usize) -> [f64; 6] {
    let (a, b) = (2.0 * PI * i as f64 / w as f64 - PI, 2.0 * PI * (i as f64 + 1.0) / w as f64 - PI);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let half = 0.5 * (b - a);
    let sin2 = 0.25 * ((2.0 * b).sin() - (2.0 * a).sin());
    [b - a, ca - cb, sb - sa, 0.5 * (sb * sb - sa * sa), half - sin2, half + sin2]
}

impl ShIrradiance {
    /// No light.
    pub fn zero() -> Self {
        ShIrradiance { coeffs: [[0.0; 3]; 9] }
    }

    /// A uniform environment of `radiance`: `E(n) = π L` for every normal
    /// (`c_0 = Â_0 · 4π Y_0 L = π L / Y_0`).
    pub fn constant(radiance: [f32; 3]) -> Self {
        let mut s = Self::zero();
        s.coeffs[0] = radiance.map(|l| (A0 * f64::from(l) / K0) as f32);
        s
    }

    /// The default ambient of the default scene: the studio dome [`studio_radiance`],
    /// `L = (a + b y + c y²)·tint` with a = 0.1, b = 0.1, c = 0.05, projected analytically:
    /// `y² = 1/3 − (3z² − 1)/6 − (x² − y²)/2`, so `L_0 = (a + c/3)/Y_0`, `L_1 = b/Y_1`,
    /// `L_6 = −(c/6)/K_20`, `L_8 = −(c/2)/K_22`, each times Â_l. Hence
    /// `E(n) = π(a + c/3) + (2π/3) b n_y + (π/4) c (n_y² − 1/3)`, times the tint: 0.602 facing up,
    /// 0.353 facing the horizon, 0.183 facing down.
    pub fn studio() -> Self {
        let (a, b, c) = (0.1, 0.1, 0.05);
        let mut s = Self::zero();
        let scalar =
            [(0, A0 * (a + c / 3.0) / K0), (1, A1 * b / K1), (6, -A2 * (c / 6.0) / K20), (8, -A2 * (c / 2.0) / K22)];
        for (i, v) in scalar {
            s.coeffs[i] = STUDIO_TINT.map(|t| (v * f64::from(t)) as f32);
        }
        s
    }

    /// Irradiance for normal `n` (unit length): `max(0, Σ_i c_i Y_i(n))` per channel, f32, the same
    /// formula as [`WGSL_SH_EVAL`]. The clamp removes the negative ringing that nine terms give
    /// behind a strong, small light.
    pub fn eval(&self, n: Vec3) -> [f32; 3] {
        let basis = basis_f32(n);
        let mut e = [0.0f32; 3];
        for (c, y) in self.coeffs.iter().zip(basis) {
            for ch in 0..3 {
                e[ch] += c[ch] * y;
            }
        }
        e.map(|v| v.max(0.0))
    }

    /// Every coefficient times `s` (an intensity scale).
    pub fn scaled(&self, s: f32) -> Self {
        ShIrradiance { coeffs: self.coeffs.map(|c| c.map(|v| v * s)) }
    }

    /// The environment's irradiance as it enters a dielectric of relative index `eta`:
    /// `E_t(n) = ∫ L(ω) T(n·ω) max(0, n·ω) dω` with T = 1 − F the Fresnel transmittance
    /// (\[Benmounah2009\] eq. 4, done right: see the module doc). The kernel T(μ)μ is zonal, so by
    /// Funk-Hecke each band l is scaled by `Â_l^T / Â_l` with `Â_l^T = 2π ∫₀¹ T(μ) μ P_l(μ) dμ`
    /// ([`fresnel_band_kernels`]).
    pub fn fresnel_transmitted(&self, eta: f64) -> Self {
        let kt = fresnel_band_kernels(eta);
        let ratio = [kt[0] / A0, kt[1] / A1, kt[2] / A2];
        let band = |i: usize| {
            if i == 0 {
                0
            } else if i < 4 {
                1
            } else {
                2
            }
        };
        let mut out = *self;
        for (i, c) in out.coeffs.iter_mut().enumerate() {
            *c = c.map(|v| (f64::from(v) * ratio[band(i)]) as f32);
        }
        out
    }

    /// Coefficients padded to `vec4` (w = 0) for a WGSL uniform `array<vec4<f32>, 9>`.
    pub fn to_gpu(&self) -> [[f32; 4]; 9] {
        self.coeffs.map(|[r, g, b]| [r, g, b, 0.0])
    }
}

/// `Â_l^T = 2π ∫₀¹ T(μ) μ P_l(μ) dμ` for l = 0, 1, 2 with T(μ) = 1 − F(μ, η) the unpolarised
/// Fresnel transmittance from outside ([`crate::diffusion::fresnel_dielectric`]): the Legendre
/// coefficients of the transmitted clamped cosine. Composite Simpson on 4096 panels (T is smooth
/// on [0, 1] for η ≥ 1). At η = 1 (T = 1) they are π, 2π/3, π/4, the plain cosine's.
pub fn fresnel_band_kernels(eta: f64) -> [f64; 3] {
    let legendre = [|_: f64| 1.0, |m: f64| m, |m: f64| 0.5 * (3.0 * m * m - 1.0)];
    legendre.map(|p| {
        let f = |m: f64| (1.0 - crate::diffusion::fresnel_dielectric(m, eta)) * m * p(m);
        let n = 4096;
        let h = 1.0 / n as f64;
        let mut s = f(0.0) + f(1.0);
        for k in 1..n {
            s += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        2.0 * PI * s * h / 3.0
    })
}

/// The nine basis functions at `n`, in coefficient order, in f32 as the shader computes them.
fn basis_f32(n: Vec3) -> [f32; 9] {
    let (k0, k1, k2, k20, k22) = (K0 as f32, K1 as f32, K2 as f32, K20 as f32, K22 as f32);
    [
        k0,
        k1 * n.y,
        k1 * n.z,
        k1 * n.x,
        k2 * (n.x * n.y),
        k2 * (n.y * n.z),
        k20 * (3.0 * n.z * n.z - 1.0),
        k2 * (n.x * n.z),
        k22 * (n.x * n.x - n.y * n.y),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The basis at `d` in f64 (for the midpoint reference).
    fn basis_f64(d: [f64; 3]) -> [f64; 9] {
        let [x, y, z] = d;
        [
            K0,
            K1 * y,
            K1 * z,
            K1 * x,
            K2 * x * y,
            K2 * y * z,
            K20 * (3.0 * z * z - 1.0),
            K2 * x * z,
            K22 * (x * x - y * y),
        ]
    }

    /// The closed-form cell integrals agree with a fine midpoint rule inside each texel.
    #[test]
    fn env_closed_form_projection_matches_midpoint_rule() {
        let (w, h, sub) = (24, 12, 32);
        let env = EnvMap::from_fn(w, h, |d| [1.0 + d.x + 0.5 * d.y * d.z, (2.0 * d.y).exp(), (1.0 - d.z).powi(3)]);
        let exact = env.sh_irradiance();
        let mut proj = [[0.0f64; 3]; 9];
        for j in 0..h {
            for i in 0..w {
                let l = env.texels[j * w + i];
                for sj in 0..sub {
                    for si in 0..sub {
                        let u = (i as f64 + (si as f64 + 0.5) / sub as f64) / w as f64;
                        let v = (j as f64 + (sj as f64 + 0.5) / sub as f64) / h as f64;
                        let d_omega = (PI * v).sin() * (2.0 * PI / (w * sub) as f64) * (PI / (h * sub) as f64);
                        for (p, y) in proj.iter_mut().zip(basis_f64(uv_direction(u, v))) {
                            for ch in 0..3 {
                                p[ch] += f64::from(l[ch]) * y * d_omega;
                            }
                        }
                    }
                }
            }
        }
        for (k, (c, p)) in exact.coeffs.iter().zip(&proj).enumerate() {
            for ch in 0..3 {
                let want = BAND_FACTOR[k] * p[ch];
                assert!((f64::from(c[ch]) - want).abs() < 2e-4, "c{k}[{ch}] = {} vs midpoint {want}", c[ch]);
            }
        }
    }

    /// The analytic studio coefficients equal the projection of the sampled studio dome.
    #[test]
    fn env_studio_is_projection_of_studio_radiance() {
        let numeric = EnvMap::from_fn(256, 128, studio_radiance).sh_irradiance();
        let analytic = ShIrradiance::studio();
        for (k, (a, b)) in analytic.coeffs.iter().zip(&numeric.coeffs).enumerate() {
            for ch in 0..3 {
                assert!((a[ch] - b[ch]).abs() < 1e-4, "c{k}[{ch}]: analytic {} vs projected {}", a[ch], b[ch]);
            }
        }
        for (n, want) in [(Vec3::Y, 0.602_139), (Vec3::X, 0.353_429), (Vec3::NEG_Y, 0.183_259)] {
            let e = analytic.eval(n);
            for ch in 0..3 {
                assert!((e[ch] - want * STUDIO_TINT[ch]).abs() < 1e-5, "E({n}) = {e:?}, want {want} × tint");
            }
        }
    }

    /// The WGSL snippet uses exactly the constants of `eval` (f32 shortest representation).
    #[test]
    fn env_wgsl_uses_eval_constants() {
        for k in [K0, K1, K2, K20, K22] {
            let lit = format!("{}", k as f32);
            assert!(WGSL_SH_EVAL.contains(&lit), "WGSL_SH_EVAL lacks {lit}");
        }
    }
}
