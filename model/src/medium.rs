//! Physical participating media: what is under a material's surface, in the terms a path tracer
//! and the diffusion models share. A [`Medium`] is σa and σs′ per linear RGB channel in mm⁻¹,
//! the phase function's mean cosine g and the boundary's relative index of refraction η.
//!
//! The built-in media are the measurements of Jensen et al. (\[Jensen2001\], the table of measured
//! parameters) in `data/media/*.json` (`rouge-medium` v1, docs/FORMATS.md), embedded. The table
//! gives the reduced scattering σs′ = σs(1 − g) only, so the files carry g = 0 and σs = σs′ (the
//! similarity relation): a diffusion model sees exactly the measured medium, and a path tracer
//! sees its isotropic equivalent.

use crate::error::{ModelError, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A homogeneous participating medium with a dielectric boundary. Unknown fields are refused (a
/// misspelt `sigma_a_per_mm` would otherwise be silently ignored), as looks refuse them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Medium {
    /// Always `"rouge-medium"`.
    pub schema: String,
    /// Format version (1).
    pub version: u32,
    /// Short name (`skin1`, `marble`, ...): what `--medium` takes.
    pub name: String,
    /// What it is, in words.
    #[serde(default)]
    pub description: String,
    /// Absorption coefficient σa per linear RGB channel, mm⁻¹.
    pub sigma_a_per_mm: [f64; 3],
    /// Reduced scattering coefficient σs′ = σs(1 − g) per channel, mm⁻¹.
    pub sigma_s_prime_per_mm: [f64; 3],
    /// Mean cosine of the phase function (Henyey-Greenstein), in (−1, 1).
    pub g: f64,
    /// Relative index of refraction of the boundary (inside over outside).
    pub eta: f64,
    /// Where the values come from (a key of docs/REFERENCES.md and the table or figure).
    #[serde(default)]
    pub source: String,
    /// Independent copies of the source the values were checked against.
    #[serde(default)]
    pub checked_against: Vec<String>,
    /// Anything a user of the values should know (disagreements between copies, choices made).
    #[serde(default)]
    pub notes: String,
    /// The thickness-translucency parameters fitted to the path tracer for this medium, one per
    /// local-thickness source (\[BarreBrisebois2011\]; `rouge bench translucency --fit-thickness`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub translucency: Vec<FittedTranslucency>,
}

/// Parameters of the fast thickness translucency (\[BarreBrisebois2011\]) fitted by least squares
/// to Mitsuba 3 references of a medium (docs/BENCHMARKS.md), with what they were fitted on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FittedTranslucency {
    /// The local-thickness source fitted: `baked` or `shadow-map`.
    pub source: String,
    /// Distortion δ of the light vector by the normal.
    pub distortion: f64,
    /// Power p of the view-dependent back lobe (> 0).
    pub power: f64,
    /// Scale s of the back lobe (≥ 0).
    pub scale: f64,
    /// Ambient translucency a (≥ 0).
    pub ambient: f64,
    /// The reference scenes (data/reference/translucency/) fitted on, and the error.
    #[serde(default)]
    pub fitted_on: String,
}

/// Largest σa or σs′ a medium may have, mm⁻¹.
pub const MAX_COEFFICIENT_PER_MM: f64 = 1e6;

/// A number for an error message: `1e308` rather than its 309 digits.
fn short(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e6).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// The names of the built-in media, in the order of \[Jensen2001\]'s table.
pub const BUILTIN_MEDIA: [&str; 11] = [
    "apple",
    "chicken1",
    "chicken2",
    "cream",
    "ketchup",
    "marble",
    "potato",
    "skimmilk",
    "skin1",
    "skin2",
    "wholemilk",
];

fn builtin_json(name: &str) -> Option<&'static str> {
    Some(match name {
        "apple" => include_str!("../../data/media/apple.json"),
        "chicken1" => include_str!("../../data/media/chicken1.json"),
        "chicken2" => include_str!("../../data/media/chicken2.json"),
        "cream" => include_str!("../../data/media/cream.json"),
        "ketchup" => include_str!("../../data/media/ketchup.json"),
        "marble" => include_str!("../../data/media/marble.json"),
        "potato" => include_str!("../../data/media/potato.json"),
        "skimmilk" => include_str!("../../data/media/skimmilk.json"),
        "skin1" => include_str!("../../data/media/skin1.json"),
        "skin2" => include_str!("../../data/media/skin2.json"),
        "wholemilk" => include_str!("../../data/media/wholemilk.json"),
        _ => return None,
    })
}

impl Medium {
    /// A medium from explicit coefficients (σs′ given, g = 0), checked.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] naming the value out of its domain.
    pub fn from_coefficients(
        name: &str,
        sigma_a_per_mm: [f64; 3],
        sigma_s_prime_per_mm: [f64; 3],
        eta: f64,
    ) -> Result<Medium> {
        let m = Medium {
            schema: "rouge-medium".into(),
            version: 1,
            name: name.into(),
            description: String::new(),
            sigma_a_per_mm,
            sigma_s_prime_per_mm,
            g: 0.0,
            eta,
            source: String::new(),
            checked_against: Vec::new(),
            notes: String::new(),
            translucency: Vec::new(),
        };
        m.validate().map_err(ModelError::Invalid)?;
        Ok(m)
    }

    /// This medium with the boundary's relative index of refraction `eta` instead of its own;
    /// everything else (coefficients, provenance, fitted parameters) kept.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] for η outside [1, 3].
    pub fn with_eta(&self, eta: f64) -> Result<Medium> {
        let m = Medium { eta, ..self.clone() };
        m.validate().map_err(ModelError::Invalid)?;
        Ok(m)
    }

    /// A built-in medium by name ([`BUILTIN_MEDIA`]).
    ///
    /// # Errors
    /// [`ModelError::Invalid`] for an unknown name (the message lists the known ones).
    pub fn builtin(name: &str) -> Result<Medium> {
        let json = builtin_json(name).ok_or_else(|| {
            ModelError::Invalid(format!("no built-in medium {name:?}: use one of {}", BUILTIN_MEDIA.join(", ")))
        })?;
        Self::parse(json, Path::new(&format!("<embedded data/media/{name}.json>")))
    }

    /// A built-in medium by name, or a `rouge-medium` JSON file when `name_or_path` ends in
    /// `.json`.
    ///
    /// # Errors
    /// As [`Medium::builtin`] and [`Medium::load`].
    pub fn resolve(name_or_path: &str) -> Result<Medium> {
        if name_or_path.to_ascii_lowercase().ends_with(".json") {
            Self::load(Path::new(name_or_path))
        } else {
            Self::builtin(name_or_path)
        }
    }

    /// Reads a `rouge-medium` v1 JSON file.
    ///
    /// # Errors
    /// [`ModelError::File`] naming the file and the line and column of a syntax error or the
    /// field out of its domain.
    pub fn load(path: &Path) -> Result<Medium> {
        let text = std::fs::read_to_string(path).map_err(|e| ModelError::file(path, format!("cannot read: {e}")))?;
        Self::parse(&text, path)
    }

    fn parse(text: &str, path: &Path) -> Result<Medium> {
        let m: Medium =
            serde_json::from_str(text).map_err(|e| ModelError::file(path, format!("not a rouge-medium file: {e}")))?;
        m.validate().map_err(|message| ModelError::file(path, message))?;
        Ok(m)
    }

    /// Checks every field's domain; the message names the field and channel.
    fn validate(&self) -> std::result::Result<(), String> {
        if self.schema != "rouge-medium" || self.version != 1 {
            return Err(format!(
                "schema {:?} version {}: expected \"rouge-medium\" version 1",
                self.schema, self.version
            ));
        }
        const CHANNELS: [&str; 3] = ["R", "G", "B"];
        for (c, channel) in CHANNELS.iter().enumerate() {
            let (a, s) = (self.sigma_a_per_mm[c], self.sigma_s_prime_per_mm[c]);
            // Past 1e6 /mm (a mean free path under a nanometre) the profiles' constants overflow
            // into a NaN albedo; no medium needs it.
            if !(a.is_finite() && (0.0..=MAX_COEFFICIENT_PER_MM).contains(&a)) {
                return Err(format!("sigma_a_per_mm[{channel}] = {}: must be finite, 0 to 1e6", short(a)));
            }
            if !(s.is_finite() && (0.0..=MAX_COEFFICIENT_PER_MM).contains(&s)) {
                return Err(format!("sigma_s_prime_per_mm[{channel}] = {}: must be finite, 0 to 1e6", short(s)));
            }
            if a + s <= 0.0 {
                return Err(format!("channel {channel}: σa + σs′ = 0, the medium is vacuum"));
            }
        }
        if !(self.g.is_finite() && self.g > -1.0 && self.g < 1.0) {
            return Err(format!("g = {}: must lie in (−1, 1)", short(self.g)));
        }
        if !(self.eta.is_finite() && (1.0..=3.0).contains(&self.eta)) {
            return Err(format!("eta = {}: must lie in [1, 3] (inside over outside)", short(self.eta)));
        }
        for t in &self.translucency {
            let ok = t.distortion.is_finite()
                && t.power.is_finite()
                && t.power > 0.0
                && t.scale.is_finite()
                && t.scale >= 0.0
                && t.ambient.is_finite()
                && t.ambient >= 0.0;
            if !ok {
                return Err(format!(
                    "translucency {{distortion {}, power {}, scale {}, ambient {}}}: need finite values, power > 0, \
                     scale and ambient ≥ 0",
                    short(t.distortion),
                    short(t.power),
                    short(t.scale),
                    short(t.ambient)
                ));
            }
        }
        Ok(())
    }

    /// Scattering coefficient σs = σs′ / (1 − g) per channel, mm⁻¹ (the similarity relation).
    pub fn sigma_s_per_mm(&self) -> [f64; 3] {
        self.sigma_s_prime_per_mm.map(|s| s / (1.0 - self.g))
    }

    /// Extinction σt = σa + σs per channel, mm⁻¹.
    pub fn sigma_t_per_mm(&self) -> [f64; 3] {
        let s = self.sigma_s_per_mm();
        std::array::from_fn(|c| self.sigma_a_per_mm[c] + s[c])
    }

    /// Single-scattering albedo σs / σt per channel.
    pub fn albedo(&self) -> [f64; 3] {
        let (s, t) = (self.sigma_s_per_mm(), self.sigma_t_per_mm());
        std::array::from_fn(|c| s[c] / t[c])
    }

    /// Reduced extinction σt′ = σa + σs′ per channel, mm⁻¹: the extinction of the isotropic
    /// medium the similarity relation makes of this one (1/σt′ is its transport mean free path).
    pub fn sigma_t_prime_per_mm(&self) -> [f64; 3] {
        std::array::from_fn(|c| self.sigma_a_per_mm[c] + self.sigma_s_prime_per_mm[c])
    }

    /// Reduced albedo α′ = σs′ / σt′ per channel: the single-scattering albedo of the isotropic
    /// medium the similarity relation makes of this one (0 where σt′ = 0, which a validated
    /// medium never has).
    pub fn reduced_albedo(&self) -> [f64; 3] {
        let sigma_t_prime = self.sigma_t_prime_per_mm();
        std::array::from_fn(
            |c| {
                if sigma_t_prime[c] > 0.0 { self.sigma_s_prime_per_mm[c] / sigma_t_prime[c] } else { 0.0 }
            },
        )
    }
}
