//! What formulators ask of S and K: how much a layer covers ([`coverage`]), which shade suits
//! which skin ([`matching`]), which mixture of bases reaches a shade ([`mixing`]), which recipe
//! of a colorant library reaches it under limits, costs and several illuminants ([`recipe`]),
//! on skins read from the user's files ([`skin`]). docs/FORMULATION.md shows the answers for
//! the sample products; the Kubelka-Munk model these analyses rest on is judged against
//! adding-doubling there too (`python/km_adding_doubling.py`).
//!
//! Every analysis sees skin (or a contrast chart) as an opaque, diffusely reflecting background
//! under a KM layer (\[Huang2013\] eq. 3 with an opaque second layer): light carried sideways in
//! the skin and the skin's own surface reflection are outside the model.

pub mod correction;
pub mod coverage;
pub mod matching;
pub mod metamerism;
pub mod mixing;
pub mod optimize;
pub mod qc;
pub mod recipe;
pub mod skin;

use crate::colorimetry::Colorimeter;
use crate::km::{self, KmError, LayerRt};
use crate::preset::Preset;
use crate::spectrum::{Spectrum, WORKING_LEN, working_wavelength_nm};

/// Why an analysis cannot run: every message names the input and, where there is one, the
/// wavelength at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AnalysisError {
    /// A coefficient or reflectance with no Kubelka-Munk meaning at one wavelength.
    #[error("{what}: at {wavelength_nm} nm: {error}")]
    Km {
        /// the layer or spectrum
        what: String,
        /// wavelength, nm
        wavelength_nm: f64,
        /// why
        error: KmError,
    },
    /// A parameter outside its domain.
    #[error("{0}")]
    Invalid(String),
}

fn invalid(message: impl Into<String>) -> AnalysisError {
    AnalysisError::Invalid(message.into())
}

/// A cosmetic material: Kubelka-Munk S and K per wavelength of the working grid, mm⁻¹, checked
/// finite and ≥ 0 at every wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Name for reports.
    pub name: String,
    /// Scattering S, mm⁻¹.
    pub s: Spectrum,
    /// Absorption K, mm⁻¹.
    pub k: Spectrum,
}

impl Layer {
    /// Checks S and K; the error names the layer and the first wavelength at fault.
    pub fn new(name: &str, s: Spectrum, k: Spectrum) -> Result<Self, AnalysisError> {
        for i in 0..WORKING_LEN {
            for (label, v) in [("S", s.0[i]), ("K", k.0[i])] {
                if !(v >= 0.0 && v.is_finite()) {
                    return Err(AnalysisError::Km {
                        what: name.to_string(),
                        wavelength_nm: working_wavelength_nm(i),
                        error: KmError::BadCoefficient { name: label, value: v },
                    });
                }
            }
        }
        Ok(Layer { name: name.to_string(), s, k })
    }

    /// The S and K of a preset.
    pub fn from_preset(preset: &Preset) -> Result<Self, AnalysisError> {
        Layer::new(&preset.name, preset.s(), preset.k())
    }

    /// R∞ per wavelength (an opaque layer).
    pub fn r_inf(&self) -> Spectrum {
        Spectrum(std::array::from_fn(|i| km::r_inf_from_s_k(self.s.0[i], self.k.0[i])))
    }

    /// Reflectance of the layer at `thickness_mm` over an opaque diffuse background, per
    /// wavelength: `R = R0 + T² Rb / (1 − R0 Rb)` (\[Huang2013\] eq. 3 corrected, see `km.rs`) with
    /// R0, T from [`km::layer_r_t`]. `thickness_mm = ∞` is the opaque layer (R∞); 0 is the bare
    /// background. The caller checks the thickness ([`check_thickness`]) and the background
    /// ([`check_reflectance`]).
    pub fn reflectance_over(&self, thickness_mm: f64, background: &Spectrum) -> Spectrum {
        Spectrum(std::array::from_fn(|i| {
            let layer = km::layer_r_t(self.s.0[i], self.k.0[i], thickness_mm).unwrap_or(LayerRt::CLEAR);
            km::compose(layer, LayerRt::opaque(background.0[i])).r
        }))
    }
}

/// Checks a thickness: ≥ 0, not NaN (∞ allowed: an opaque layer).
pub fn check_thickness(what: &str, thickness_mm: f64) -> Result<(), AnalysisError> {
    if thickness_mm >= 0.0 {
        Ok(())
    } else {
        Err(invalid(format!("{what} = {thickness_mm} mm: a thickness must be ≥ 0")))
    }
}

/// Checks a background reflectance spectrum lies in [0, 1] at every wavelength.
pub fn check_reflectance(what: &str, r: &Spectrum) -> Result<(), AnalysisError> {
    match r.0.iter().position(|v| !(0.0..=1.0).contains(v)) {
        None => Ok(()),
        Some(i) => Err(AnalysisError::Km {
            what: what.to_string(),
            wavelength_nm: working_wavelength_nm(i),
            error: KmError::ReflectanceOutOfRange { name: "R", value: r.0[i] },
        }),
    }
}

/// CIELAB of a reflectance spectrum under the colorimeter's viewing.
pub fn lab_of(colorimeter: &Colorimeter, r: &Spectrum) -> [f64; 3] {
    colorimeter.lab(&colorimeter.xyz(r)).lab
}

/// A layer with the same S and K at every wavelength, for tests.
#[cfg(test)]
pub(crate) fn grey_layer(s_per_mm: f64, k_per_mm: f64) -> Layer {
    Layer::new("grey", Spectrum::constant(s_per_mm), Spectrum::constant(k_per_mm)).expect("finite, ≥ 0")
}
