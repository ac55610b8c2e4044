//! The spectral skin model: reflectance 380-780 nm from melanin, blood and the skin's layers,
//! its inversion from measured spectra, the optical properties the renderer takes, and named
//! skin tones. No GPU.
//!
//! **The model** (after \[Donner2006\] and \[Jacques1998\]; every spectrum in [`chromophores`]):
//!
//! * an **epidermis** of thickness d (default 0.1 mm) whose absorption is melanin in a volume
//!   fraction f_mel, a share β of it pheomelanin, and the baseline tissue elsewhere:
//!   μa,epi = f_mel [(1 − β) μa,eu + β μa,pheo] + (1 − f_mel) μa,base;
//! * over a semi-infinite **dermis** whose absorption is blood in a volume fraction f_blood at
//!   oxygen saturation S, and baseline tissue elsewhere:
//!   μa,derm = f_blood [S μa,HbO₂ + (1 − S) μa,Hb] + (1 − f_blood) μa,base;
//! * both layers scatter alike, μs′ = a (λ/500 nm)^−b, with a Henyey-Greenstein g = 0.8 and
//!   refractive index 1.4 under air;
//! * the reflectance is the slab's total (surface Fresnel + scattered) for normal light, solved
//!   by adding-doubling and tabulated ([`transport`]).
//!
//! Six parameters are free in a fit (f_mel, β, f_blood, S, a, b); d is fixed at its default there.
//! Domain: 380-780 nm; f_mel ≤ 0.6, f_blood ≤ 0.3, a in 0.5-10 /mm, b in 0-4, d in 0-0.3 mm,
//! and μs′d ≤ 3 at every wavelength (the table's reach); outside it is an error that says which.

pub mod chromophores;
pub mod color_table;
pub mod fit;
pub mod optics;
pub mod tones;
pub mod transport;

pub use color_table::SkinColorTable;
pub use fit::{FitOptions, SkinFit, SkinFitter, Specular, fit_reflectance};
pub use optics::{LayerOptics, SkinOptics};
pub use tones::{SkinTone, ita_deg, skin_at_ita, skin_tone, skin_tone_or_ita, skin_tones};

use crate::spectrum::{Spectrum, WORKING_LEN};
use chromophores::{MAX_WAVELENGTH_NM, MIN_WAVELENGTH_NM};

/// The parameters of the skin model, with their units in their names.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkinParams {
    /// Volume fraction of melanosomes in the epidermis, 0-0.6.
    pub melanin_fraction: f64,
    /// Share of pheomelanin in the melanin, 0-1 (the rest eumelanin).
    pub pheomelanin_share: f64,
    /// Volume fraction of whole blood in the dermis, 0-0.3.
    pub blood_fraction: f64,
    /// Oxygen saturation of the blood, 0-1.
    pub oxygen_saturation: f64,
    /// Reduced scattering coefficient at 500 nm, per mm (a), 0.5-10.
    pub scattering_500nm_per_mm: f64,
    /// Power of the scattering's fall with wavelength (b), 0-4.
    pub scattering_power: f64,
    /// Thickness of the epidermis, mm, 0-0.3 (0: the dermis alone).
    #[serde(default = "default_epidermis_mm")]
    pub epidermis_thickness_mm: f64,
}

fn default_epidermis_mm() -> f64 {
    SkinParams::DEFAULT_EPIDERMIS_MM
}

/// One parameter's name, unit and physiological range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamRange {
    /// The field's name, as in JSON and on the command line (with `-` for `_`).
    pub name: &'static str,
    /// Lowest value.
    pub min: f64,
    /// Highest value.
    pub max: f64,
}

impl SkinParams {
    /// The epidermis' thickness when none is given, mm (a typical facial epidermis, \[Jacques1998\]).
    pub const DEFAULT_EPIDERMIS_MM: f64 = 0.1;

    /// The ranges, in the order of [`SkinParams::to_array`].
    pub const RANGES: [ParamRange; 7] = [
        ParamRange { name: "melanin_fraction", min: 0.0, max: 0.6 },
        ParamRange { name: "pheomelanin_share", min: 0.0, max: 1.0 },
        ParamRange { name: "blood_fraction", min: 0.0, max: 0.3 },
        ParamRange { name: "oxygen_saturation", min: 0.0, max: 1.0 },
        ParamRange { name: "scattering_500nm_per_mm", min: 0.5, max: 10.0 },
        ParamRange { name: "scattering_power", min: 0.0, max: 4.0 },
        ParamRange { name: "epidermis_thickness_mm", min: 0.0, max: 0.3 },
    ];

    /// The `light` tone of data/skin/tones.json (ITA 50°, Fitzpatrick II): the default skin
    /// (a test keeps the two equal).
    pub const LIGHT: SkinParams = SkinParams {
        melanin_fraction: 0.017425,
        pheomelanin_share: 0.668073,
        blood_fraction: 0.007086,
        oxygen_saturation: 0.735719,
        scattering_500nm_per_mm: 5.381874,
        scattering_power: 3.324154,
        epidermis_thickness_mm: SkinParams::DEFAULT_EPIDERMIS_MM,
    };

    /// The named `tone` (or [`SkinParams::LIGHT`] without one) with each `Some` of `overrides`
    /// (in the order of [`SkinParams::RANGES`]) in place of its value, validated: what `rouge skin
    /// spectrum` and Python's `skin_reflectance` take.
    pub fn from_tone(tone: Option<&str>, overrides: [Option<f64>; 7]) -> Result<SkinParams, SkinError> {
        let base = match tone {
            Some(name) => skin_tone(name)?.params,
            None => SkinParams::LIGHT,
        };
        let mut a = base.to_array();
        for (slot, v) in a.iter_mut().zip(overrides) {
            if let Some(v) = v {
                *slot = v;
            }
        }
        let p = SkinParams::from_array(a);
        p.validate()?;
        Ok(p)
    }

    /// The parameters as an array, in the order of [`SkinParams::RANGES`].
    pub fn to_array(&self) -> [f64; 7] {
        [
            self.melanin_fraction,
            self.pheomelanin_share,
            self.blood_fraction,
            self.oxygen_saturation,
            self.scattering_500nm_per_mm,
            self.scattering_power,
            self.epidermis_thickness_mm,
        ]
    }

    /// The inverse of [`SkinParams::to_array`].
    pub fn from_array(a: [f64; 7]) -> Self {
        SkinParams {
            melanin_fraction: a[0],
            pheomelanin_share: a[1],
            blood_fraction: a[2],
            oxygen_saturation: a[3],
            scattering_500nm_per_mm: a[4],
            scattering_power: a[5],
            epidermis_thickness_mm: a[6],
        }
    }

    /// The thickest epidermis this skin's scattering lets the transport table reach, mm: the
    /// largest d with μs′(380 nm)·d ≤ 3 (the test of [`SkinParams::validate`]; infinite without
    /// scattering). Skin maps and the colour table keep their epidermis below it.
    pub fn max_epidermis_mm(&self) -> f64 {
        let mu = chromophores::reduced_scattering_per_mm(
            MIN_WAVELENGTH_NM,
            self.scattering_500nm_per_mm,
            self.scattering_power,
        );
        if !(mu > 0.0 && mu.is_finite()) {
            return f64::INFINITY;
        }
        // The quotient can round up by an ulp; step down until the product passes the same test.
        let mut d = transport::MAX_TAU_SCATTER_EPI / mu;
        while mu * d > transport::MAX_TAU_SCATTER_EPI {
            d = d.next_down();
        }
        d
    }

    /// Checks every parameter against its range and the transport table's reach.
    pub fn validate(&self) -> Result<(), SkinError> {
        for (v, r) in self.to_array().iter().zip(Self::RANGES) {
            if !(r.min..=r.max).contains(v) {
                return Err(SkinError::Parameter { name: r.name, value: *v, min: r.min, max: r.max });
            }
        }
        // μs′ falls with wavelength (b ≥ 0), so its largest value is at the shortest wavelength.
        let tau = chromophores::reduced_scattering_per_mm(
            MIN_WAVELENGTH_NM,
            self.scattering_500nm_per_mm,
            self.scattering_power,
        ) * self.epidermis_thickness_mm;
        if tau > transport::MAX_TAU_SCATTER_EPI {
            return Err(SkinError::EpidermisTooThick { tau_scatter: tau, wavelength_nm: MIN_WAVELENGTH_NM });
        }
        Ok(())
    }

    /// The slab's reflectance for the layers' optics at one wavelength.
    fn reflectance_of(&self, o: &SkinOptics) -> Result<f64, SkinError> {
        let wavelength_nm = o.wavelength_nm;
        let tau_a = o.epidermis.mu_a_per_mm * self.epidermis_thickness_mm;
        let tau_s = (o.epidermis.mu_s_reduced_per_mm * self.epidermis_thickness_mm).min(transport::MAX_TAU_SCATTER_EPI);
        transport::two_layer_reflectance(tau_a, tau_s, o.dermis.reduced_albedo())
            .map_err(|e| SkinError::Transport { wavelength_nm, message: e.to_string() })
    }

    /// Reflectance (specular included, as a d/8° instrument in SCI mode reads) at each of
    /// `wavelengths_nm`, each in 380-780 nm.
    pub fn reflectance_at(&self, wavelengths_nm: &[f64]) -> Result<Vec<f64>, SkinError> {
        self.validate()?;
        wavelengths_nm
            .iter()
            .map(|&w| {
                if !(MIN_WAVELENGTH_NM..=MAX_WAVELENGTH_NM).contains(&w) {
                    return Err(SkinError::Wavelength { wavelength_nm: w });
                }
                self.reflectance_of(&SkinOptics::at(self, w))
            })
            .collect()
    }

    /// Reflectance on the working grid (380-780 nm every 5 nm).
    pub fn reflectance(&self) -> Result<Spectrum, SkinError> {
        self.validate()?;
        self.reflectance_on_grid_unchecked().map(Spectrum)
    }

    /// [`SkinParams::reflectance`] without validation, for the fit's inner loop: the parameters
    /// must lie inside [`SkinParams::RANGES`] (μs′d past the table is clamped to its edge).
    pub(crate) fn reflectance_on_grid_unchecked(&self) -> Result<[f64; WORKING_LEN], SkinError> {
        let optics = SkinOptics::on_working_grid(self);
        let mut out = [0.0; WORKING_LEN];
        for (o, r) in optics.iter().zip(out.iter_mut()) {
            *r = self.reflectance_of(o)?;
        }
        Ok(out)
    }
}

/// What can go wrong in the skin model, with the parameter or wavelength at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SkinError {
    /// A parameter outside its physiological range.
    #[error("{name} = {value} is outside its range [{min}, {max}]")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Lowest allowed.
        min: f64,
        /// Highest allowed.
        max: f64,
    },
    /// μs′·d past the transport table.
    #[error(
        "the epidermis is {tau_scatter:.2} reduced mean free paths thick at {wavelength_nm} nm, past the model's 3 (thinner epidermis or less scattering)"
    )]
    EpidermisTooThick {
        /// μs′ d at that wavelength.
        tau_scatter: f64,
        /// The wavelength.
        wavelength_nm: f64,
    },
    /// A wavelength outside 380-780 nm.
    #[error("{wavelength_nm} nm is outside the skin model's 380-780 nm")]
    Wavelength {
        /// The wavelength.
        wavelength_nm: f64,
    },
    /// A tone name that is not built in.
    #[error("no skin tone `{name}` (the tones: {known})")]
    UnknownTone {
        /// The name asked for.
        name: String,
        /// The names there are.
        known: String,
    },
    /// An ITA outside the built-in tones' span.
    #[error("ITA {ita_deg}°: the tones span {deepest:.1}° (very deep) to {lightest:.1}° (very light)")]
    ItaOutOfRange {
        /// The angle asked for.
        ita_deg: f64,
        /// The deepest tone's ITA.
        deepest: f64,
        /// The lightest tone's ITA.
        lightest: f64,
    },
    /// A measured spectrum the fit cannot take.
    #[error("{}{message}", wavelength_nm.map(|w| format!("at {w} nm: ")).unwrap_or_default())]
    Measurement {
        /// The wavelength at fault, when one is.
        wavelength_nm: Option<f64>,
        /// Why.
        message: String,
    },
    /// The transport lookup refused its input.
    #[error("at {wavelength_nm} nm: {message}")]
    Transport {
        /// The wavelength.
        wavelength_nm: f64,
        /// Why.
        message: String,
    },
}
