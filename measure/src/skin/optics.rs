//! The skin's optical properties: per layer and wavelength, and as the one homogeneous RGB medium
//! the renderer's subsurface models take.

use super::chromophores::{
    baseline_mu_a_per_mm, blood_mu_a_per_mm, eumelanin_mu_a_per_mm, pheomelanin_mu_a_per_mm,
    reduced_scattering_from_ln_ratio,
};
use super::transport::{TISSUE_INDEX, two_layer_reflectance};
use super::{SkinError, SkinParams};
use crate::colorimetry::{Colorimeter, Viewing};
use crate::spectrum::{WORKING_LEN, working_wavelength_nm};
use std::sync::OnceLock;

/// Absorption and reduced scattering of one layer at one wavelength, per mm.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LayerOptics {
    /// Absorption coefficient μa, mm⁻¹.
    pub mu_a_per_mm: f64,
    /// Reduced scattering coefficient μs′ = μs(1 − g), mm⁻¹.
    pub mu_s_reduced_per_mm: f64,
}

impl LayerOptics {
    /// μs′/(μs′ + μa); 0 for a layer that neither scatters nor absorbs.
    pub fn reduced_albedo(&self) -> f64 {
        let t = self.mu_s_reduced_per_mm + self.mu_a_per_mm;
        if t > 0.0 { self.mu_s_reduced_per_mm / t } else { 0.0 }
    }
}

/// Both layers at one wavelength.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SkinOptics {
    /// The wavelength, nm.
    pub wavelength_nm: f64,
    /// The epidermis.
    pub epidermis: LayerOptics,
    /// The dermis.
    pub dermis: LayerOptics,
}

/// The chromophores' spectra at one wavelength: what the mixing rules combine.
#[derive(Clone, Copy, Debug)]
struct Chromophores {
    wavelength_nm: f64,
    eumelanin: f64,
    pheomelanin: f64,
    oxy: f64,
    deoxy: f64,
    baseline: f64,
    /// ln(λ/500 nm), for the scattering power law.
    ln_over_500: f64,
}

impl Chromophores {
    fn at(wavelength_nm: f64) -> Self {
        let (oxy, deoxy) = blood_mu_a_per_mm(wavelength_nm);
        Chromophores {
            wavelength_nm,
            eumelanin: eumelanin_mu_a_per_mm(wavelength_nm),
            pheomelanin: pheomelanin_mu_a_per_mm(wavelength_nm),
            oxy,
            deoxy,
            baseline: baseline_mu_a_per_mm(wavelength_nm),
            ln_over_500: (wavelength_nm / 500.0).ln(),
        }
    }

    /// The working grid's, computed once.
    fn working_grid() -> &'static [Chromophores; WORKING_LEN] {
        static GRID: OnceLock<[Chromophores; WORKING_LEN]> = OnceLock::new();
        GRID.get_or_init(|| std::array::from_fn(|i| Chromophores::at(working_wavelength_nm(i))))
    }

    /// The mixing rules of the module documentation of [`crate::skin`]: the one place they live.
    fn mix(&self, p: &SkinParams) -> SkinOptics {
        let melanin = (1.0 - p.pheomelanin_share) * self.eumelanin + p.pheomelanin_share * self.pheomelanin;
        let blood = p.oxygen_saturation * self.oxy + (1.0 - p.oxygen_saturation) * self.deoxy;
        let mu_s = reduced_scattering_from_ln_ratio(self.ln_over_500, p.scattering_500nm_per_mm, p.scattering_power);
        SkinOptics {
            wavelength_nm: self.wavelength_nm,
            epidermis: LayerOptics {
                mu_a_per_mm: p.melanin_fraction * melanin + (1.0 - p.melanin_fraction) * self.baseline,
                mu_s_reduced_per_mm: mu_s,
            },
            dermis: LayerOptics {
                mu_a_per_mm: p.blood_fraction * blood + (1.0 - p.blood_fraction) * self.baseline,
                mu_s_reduced_per_mm: mu_s,
            },
        }
    }
}

impl SkinOptics {
    /// The layers' μa and μs′ at `wavelength_nm` (380-780 nm) by the mixing rules of the module
    /// documentation of [`crate::skin`].
    pub fn at(p: &SkinParams, wavelength_nm: f64) -> SkinOptics {
        Chromophores::at(wavelength_nm).mix(p)
    }

    /// The same at every wavelength of the working grid, with the chromophores' spectra computed
    /// once per process (the fit's inner loop).
    pub fn on_working_grid(p: &SkinParams) -> [SkinOptics; WORKING_LEN] {
        let grid = Chromophores::working_grid();
        std::array::from_fn(|i| grid[i].mix(p))
    }
}

/// The skin as one homogeneous medium per linear sRGB channel, for the renderer's subsurface
/// models (a `rouge-medium`: σa and σs′ in mm⁻¹, isotropic equivalent g = 0, η = 1.4).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RgbMedium {
    /// The skin's colour: linear sRGB (D65) of its reflectance spectrum, specular included.
    pub albedo_linear_srgb: [f64; 3],
    /// Absorption per channel, mm⁻¹.
    pub sigma_a_per_mm: [f64; 3],
    /// Reduced scattering per channel, mm⁻¹.
    pub sigma_s_prime_per_mm: [f64; 3],
    /// Relative index of the surface.
    pub eta: f64,
}

/// Lowest reduced albedo [`rgb_medium`] gives a channel.
pub const MIN_REDUCED_ALBEDO: f64 = 1e-3;

/// The homogeneous medium that looks like the layered skin: per linear sRGB channel, σs′ is the
/// dermis' μs′ averaged with the channel's spectral weight (x̄ȳz̄ under D65 through the sRGB
/// matrix, clipped at 0), and σa is chosen so that a semi-infinite slab of that medium under the
/// same surface has the channel's reflectance (the same adding-doubling table with no epidermis,
/// inverted by bisection on the reduced albedo). A tone on screen and its diffusion profile
/// then come from the same skin: that medium's total reflectance by transport is the tone's
/// colour (the renderer's diffusion profiles return 0.02-0.03 less, docs/SKIN.md).
pub fn rgb_medium(p: &SkinParams) -> Result<RgbMedium, SkinError> {
    let reflectance = p.reflectance()?;
    let colorimeter = Colorimeter::get(Viewing::D65_1931);
    let albedo = colorimeter.srgb_linear(&colorimeter.xyz(&reflectance));
    // The channels' spectral weights: the sRGB matrix applied to the colorimeter's x̄ȳz̄ weights.
    let w = colorimeter.weights();
    let (mut num, mut den) = ([0.0; 3], [0.0; 3]);
    for (i, o) in SkinOptics::on_working_grid(p).iter().enumerate() {
        let xyz = crate::colorimetry::Xyz { xyz: [w[0][i], w[1][i], w[2][i]], viewing: Viewing::D65_1931 };
        for (c, weight) in colorimeter.srgb_linear(&xyz).into_iter().enumerate() {
            num[c] += weight.max(0.0) * o.dermis.mu_s_reduced_per_mm;
            den[c] += weight.max(0.0);
        }
    }
    let sigma_s: [f64; 3] = std::array::from_fn(|c| num[c] / den[c]);
    let mut sigma_a = [0.0; 3];
    for c in 0..3 {
        let target = albedo[c].clamp(0.0, 1.0);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let r = two_layer_reflectance(0.0, 0.0, mid)
                .map_err(|e| SkinError::Transport { wavelength_nm: 0.0, message: e.to_string() })?;
            if r < target { lo = mid } else { hi = mid }
        }
        // A channel at or below the bare surface's reflection (only the deepest skins' blue comes
        // near) is given the floor a′ = 1e-3: an absorption 1000× the scattering.
        let a = (0.5 * (lo + hi)).max(MIN_REDUCED_ALBEDO);
        sigma_a[c] = sigma_s[c] * (1.0 - a) / a;
    }
    Ok(RgbMedium {
        albedo_linear_srgb: albedo,
        sigma_a_per_mm: sigma_a,
        sigma_s_prime_per_mm: sigma_s,
        eta: TISSUE_INDEX,
    })
}
