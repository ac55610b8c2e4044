//! A curved surface of a medium under light from every side: how much more a convex one returns
//! than the flat half-space of [`crate::dielectric_half_space`], from its mean curvature H (mm⁻¹,
//! positive where convex).
//!
//! **The diffusive part.** Diffusion inside a sphere of radius R lit uniformly has fluence
//! sinh(σ_tr r)/r, whose flux-to-fluence ratio at the surface is σ_tr·coth(σ_tr R) − 1/R instead
//! of the half-space's σ_tr: the surface behaves as a half-space of the smaller transport
//! coefficient, i.e. of the larger reduced albedo α′_eff = 1 − σ_eff²/(3σt′²) (σ_tr² = 3σaσt′).
//! To first order that is σ_tr − H, so the correction is local: [`effective_albedo`] takes
//! σ_eff = σ_tr·coth(σ_tr/H) − H, which goes to 0 with σ_tr (a medium that absorbs nothing returns
//! everything, curved or not). Concave surfaces (H < 0) are left flat: the same argument outside a
//! sphere (fluence e^{−σ_tr r}/r, σ_tr + |H|) loses light to an infinite medium that a closed body
//! returns elsewhere, so that it would darken a non-absorbing body in a furnace, where the path
//! tracer's radiance is exactly uniform; no reference here measures a concave surface.
//!
//! **Single scattering is exempt.** Light scattered once leaves within a mean free path of where it
//! entered, where a surface whose radius is many mean free paths is flat; and at low albedo it is
//! nearly all the light, where mapping σ_tr − H to an albedo would double the reflectance of
//! ketchup's green (0.0089 against the path tracer's 0.0054). The first order of a half-space
//! under a smooth boundary of index η is exactly R₁ = c₁(η)·α′ at normal incidence
//! ([`single_scattering`]: the light refracted in, scattered once at optical depth τ, leaving
//! towards internal cosine ν through e^{−τ/ν} and the boundary), so the curved surface returns
//! R(α′) + [R(α′_eff) − c₁α′_eff] − [R(α′) − c₁α′] ([`reflectance`]): only orders two and up
//! feel the curvature. c₁ agrees with adding-doubling's O(α′) term (R(10⁻³)/10⁻³ at η = 1.3:
//! 0.07447 against 0.07443) and at η = 1 is (1 − ln 2)/2, Chandrasekhar's.
//!
//! **Measured** against Mitsuba 3 spheres under a uniform white sky behind a smooth boundary of
//! η = 1.3 (`data/reference/translucency-dielectric`, the disc within 18° of the view's normal;
//! docs/BENCHMARKS.md): skin1 at 25 mm within 0.3-0.6% per channel and at 100 mm within 0.1-1.1%,
//! where the flat half-space is 4-10% and 1-3% low; ketchup at 25 mm +2.7 / +7 / +6% (absolute
//! 0.005 / 0.0004 / 0.0001) where the flat one is 25% low in red. On spheres rendered after the
//! model was fixed: skin2 at 25 mm within 0.3%, skin1 at 10 mm (a finger's radius) within 2.0%,
//! chicken1 (mean free paths of 2-6 mm) within 3.1%, where the flat one is 4-38% low.
//!
//! Domain: uniform (diffuse) light only: under a light from one direction the light carried
//! around a convex body is another matter (the kernel's and the translucency models'); the mesh's
//! normals (the plan leaves the term out under a normal map or skin detail). Media with
//! σt′ > 0, 1 ≤ η ≤ 3, 0 ≤ H ≤ [`MAX_CURVATURE_PER_MM`] (clamped: radii under 2 mm are beyond the
//! first-order argument for skin; concave surfaces flat).

use crate::dielectric_half_space::reflectance as flat_reflectance;
use crate::diffusion::fresnel_dielectric;
use crate::error::{RenderError, Result};

/// The largest |H| (mm⁻¹) the correction takes; larger curvatures are clamped to it.
pub const MAX_CURVATURE_PER_MM: f64 = 0.5;

/// c₁(η): the single-scattering reflectance of a half-space of unit albedo under a smooth
/// boundary of `eta`, at normal incidence: (1 − F(1, η))·½∫₀¹ ν/(1 + ν)·(1 − F_in(ν)) dν, F_in the
/// Fresnel reflectance from inside (total beyond the critical angle). Midpoint rule on 4096
/// panels, split at the critical cosine (the integrand's kink).
pub fn single_scattering(eta: f64) -> f64 {
    let t_in = 1.0 - fresnel_dielectric(1.0, eta);
    let critical = if eta > 1.0 { (1.0 - 1.0 / (eta * eta)).sqrt() } else { 0.0 };
    let integrand = |nu: f64| nu / (1.0 + nu) * (1.0 - fresnel_dielectric(nu, 1.0 / eta));
    let n = 4096;
    let width = (1.0 - critical) / n as f64;
    let sum: f64 = (0..n).map(|i| integrand(critical + (i as f64 + 0.5) * width)).sum::<f64>() * width;
    t_in * 0.5 * sum
}

/// α′_eff of a surface of mean curvature `h_per_mm` (clamped to [`MAX_CURVATURE_PER_MM`]; concave
/// and NaN read as flat) in a medium of reduced albedo `alpha_prime` and σt′ = `sigma_t_per_mm`
/// (module doc).
pub fn effective_albedo(alpha_prime: f64, sigma_t_per_mm: f64, h_per_mm: f64) -> f64 {
    let alpha = alpha_prime.clamp(0.0, 1.0);
    if h_per_mm.is_nan() || h_per_mm <= 0.0 {
        return alpha;
    }
    let h = h_per_mm.min(MAX_CURVATURE_PER_MM);
    let sigma_tr = sigma_t_per_mm * (3.0 * (1.0 - alpha)).sqrt();
    // σ_tr·coth(σ_tr/H) − H, which falls to 0 with σ_tr (as σ_tr²/(3H)).
    let sigma_eff = if sigma_tr > 0.0 { (sigma_tr / (sigma_tr / h).tanh() - h).max(0.0) } else { 0.0 };
    (1.0 - sigma_eff * sigma_eff / (3.0 * sigma_t_per_mm * sigma_t_per_mm)).clamp(0.0, 1.0)
}

/// The normal-incidence reflectance of a surface of mean curvature `h_per_mm` under uniform
/// light (module doc), for a medium of `alpha_prime`, `sigma_t_per_mm` and boundary `eta`.
///
/// # Errors
/// [`RenderError::Invalid`] naming the value for σt′ not finite and positive, or α′ or η outside
/// [`flat_reflectance`]'s domain.
pub fn reflectance(alpha_prime: f64, sigma_t_per_mm: f64, eta: f64, h_per_mm: f64) -> Result<f64> {
    check(alpha_prime, sigma_t_per_mm, eta)?;
    curved(alpha_prime, sigma_t_per_mm, eta, single_scattering(eta), h_per_mm)
}

/// [`reflectance`]'s domain: σt′ finite and positive, α′ and η as [`flat_reflectance`] takes them
/// (whose error names the value).
fn check(alpha_prime: f64, sigma_t_per_mm: f64, eta: f64) -> Result<()> {
    if !(sigma_t_per_mm.is_finite() && sigma_t_per_mm > 0.0) {
        return Err(RenderError::Invalid(format!(
            "σt′ {sigma_t_per_mm} mm⁻¹: the curvature correction needs a finite, positive σa + σs′"
        )));
    }
    flat_reflectance(alpha_prime, eta).map(|_| ())
}

/// [`reflectance`] in its domain, with c₁ = [`single_scattering`]`(eta)` given: R(α′_eff) −
/// c₁α′_eff + c₁α′, the curved surface's orders two and up and the flat one's first.
fn curved(alpha_prime: f64, sigma_t_per_mm: f64, eta: f64, c1: f64, h_per_mm: f64) -> Result<f64> {
    let curved_alpha = effective_albedo(alpha_prime, sigma_t_per_mm, h_per_mm);
    Ok((flat_reflectance(curved_alpha, eta)?.normal - c1 * (curved_alpha - alpha_prime)).clamp(0.0, 1.0))
}

/// Curvature nodes of the GPU's table, even in H over ±[`MAX_CURVATURE_PER_MM`] (the concave
/// half at ratio 1, so that the shader needs no branch).
pub const GPU_CURVATURE_NODES: usize = 33;

/// The ratio curved / flat per channel at [`GPU_CURVATURE_NODES`] curvatures even in
/// [−[`MAX_CURVATURE_PER_MM`], +[`MAX_CURVATURE_PER_MM`]], channel-major: what the lighting pass
/// multiplies the half-space law's environment term by (`lighting.wgsl`, `half_space_curvature`).
/// A channel that reflects nothing keeps ratio 1.
///
/// # Errors
/// As [`reflectance`].
pub fn gpu_ratios(alpha_prime: [f64; 3], sigma_t_per_mm: [f64; 3], eta: f64) -> Result<Vec<f32>> {
    let c1 = single_scattering(eta);
    let mut out = Vec::with_capacity(3 * GPU_CURVATURE_NODES);
    for c in 0..3 {
        let (alpha, sigma_t) = (alpha_prime[c], sigma_t_per_mm[c]);
        check(alpha, sigma_t, eta)?;
        let flat = curved(alpha, sigma_t, eta, c1, 0.0)?;
        for j in 0..GPU_CURVATURE_NODES {
            let h = MAX_CURVATURE_PER_MM * (2.0 * j as f64 / (GPU_CURVATURE_NODES - 1) as f64 - 1.0);
            let ratio = curved(alpha, sigma_t, eta, c1, h)? / flat;
            out.push(if flat > 0.0 { ratio as f32 } else { 1.0 });
        }
    }
    Ok(out)
}
