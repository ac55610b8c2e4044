//! Material presets: a versioned JSON document holding a cosmetic's Kubelka-Munk S and K per
//! wavelength, the measurement they came from, specular parameters, and tables a renderer can
//! use directly (R0 and T in linear sRGB at a table of thicknesses).
//!
//! Schema version 1 (`"schema": "rouge-preset", "version": 1`) is specified field by field on
//! [`Preset`]; version 2 adds the layer's `finish` ([`crate::finish::Finish`]) and nothing else.
//! A preset is written with the lowest version that holds it (1 without a finish), so every
//! preset without a finish still reads in a Rouge that knows only version 1. Loading checks the
//! schema name, the version and every value; anything unknown or out of range is an error naming
//! the field (and the wavelength, for spectra).

use crate::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, srgb_encode};
use crate::error::LocatedError;
use crate::file_set::{read_bounded, write_atomic};
use crate::import::{Kind, Measurement, WorkingMeasurement};
use crate::km::{self, KmCoefficients, KmError, LayerRt, Saunderson};
use crate::layer_table::{TableLayer, layer_rgb_at};
use crate::spectrum::{Spectrum, WORKING_LEN, working_wavelength_nm, working_wavelengths_nm};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The schema name every preset carries.
pub const SCHEMA: &str = "rouge-preset";
/// The newest schema version this build reads and writes (it reads every version from 1).
pub const VERSION: u32 = 2;
/// The version a preset without a finish is written as.
pub const VERSION_WITHOUT_FINISH: u32 = 1;

/// Thicknesses (mm) of the derived tables: 0 to 0.2 mm every 5 µm (41 entries), the range of
/// cosmetic films (foundation 10-40 µm, lipstick 10-30 µm, heavy layers up to ~0.1 mm).
pub fn table_thicknesses_mm() -> Vec<f64> {
    (0..=40).map(|i| i as f64 * 0.005).collect()
}

/// Specular parameters of a layer's Kelemen/Szirmay-Kalos lobe (\[Huang2013\] eq. 5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Specular {
    /// Beckmann roughness (RMS slope), in (0, 1].
    pub roughness: f64,
    /// Index of refraction of the layer's binder, for Schlick's Fresnel, in [1, 3].
    pub ior: f64,
}

impl Specular {
    /// Defaults by kind: glossy lipstick, satin foundation, matte powders.
    pub fn default_for(kind: Kind) -> Self {
        match kind {
            Kind::Lipstick => Specular { roughness: 0.15, ior: 1.50 },
            Kind::Foundation => Specular { roughness: 0.35, ior: 1.45 },
            Kind::Blush | Kind::Eyeshadow => Specular { roughness: 0.55, ior: 1.45 },
            Kind::Other => Specular { roughness: 0.4, ior: 1.45 },
        }
    }
}

/// The measurement a preset was inverted from (on the working grid).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceMeasurement {
    /// File name it was imported from (no directories).
    pub file: String,
    /// Instrument, if known.
    pub instrument: Option<String>,
    /// How the file's numbers were read (fractions or percent, declared or detected).
    pub scale: String,
    /// Saunderson correction applied before inversion, if any.
    pub saunderson: Option<Saunderson>,
    /// Measured R∞.
    pub r_inf: Vec<f64>,
    /// Measured R (thin layer over the background).
    pub r: Vec<f64>,
    /// Measured Rg (background).
    pub rg: Vec<f64>,
}

/// Tables derived from S and K for renderers: linear sRGB (D65, 1931 observer).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Derived {
    /// Viewing of the colours: always `"D65 / CIE 1931"` in version 1.
    pub viewing: String,
    /// Thicknesses of the table rows, mm.
    pub thickness_mm: Vec<f64>,
    /// Layer reflectance over black R0(X) as linear sRGB, one row per thickness.
    pub r0_linear_srgb: Vec<[f64; 3]>,
    /// Layer transmittance T(X) as linear sRGB, one row per thickness.
    pub t_linear_srgb: Vec<[f64; 3]>,
    /// Reflectance of an opaque layer R∞ as linear sRGB.
    pub r_inf_linear_srgb: [f64; 3],
    /// R∞ as an encoded sRGB hex colour (clipped), for swatches.
    pub r_inf_srgb_hex: String,
}

/// A material preset, schema version 1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    /// Always `"rouge-preset"`.
    pub schema: String,
    /// Schema version: 1, or 2 when the preset has a `finish`.
    pub version: u32,
    /// Display name.
    pub name: String,
    /// Cosmetic kind.
    pub kind: Kind,
    /// Thickness of the measured thin layer, mm.
    pub thickness_mm: f64,
    /// Wavelengths of the spectra, nm: the working grid 380-780 nm every 5 nm.
    pub wavelengths_nm: Vec<f64>,
    /// Scattering coefficient S per wavelength, mm⁻¹.
    pub s_per_mm: Vec<f64>,
    /// Absorption coefficient K per wavelength, mm⁻¹.
    pub k_per_mm: Vec<f64>,
    /// The measurement S and K came from (absent for presets made by hand).
    pub measurement: Option<SourceMeasurement>,
    /// Specular lobe parameters.
    pub specular: Specular,
    /// Renderer tables derived from S and K.
    pub derived: Derived,
    /// Standard uncertainties of S and K (optional: presets written before it load unchanged).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<PresetUncertainty>,
    /// The layer's finish (version 2; absent: a clear film that follows the skin's relief,
    /// clarity 1 and levelling 0, as version 1 presets render).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finish: Option<crate::finish::Finish>,
}

/// How certain a preset's S and K are (\[GUM\] linear propagation, `km_uncertainty`), and what
/// was assumed of the measurement to say so.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PresetUncertainty {
    /// Where the readings' uncertainty came from (an instrument class, a flag, the file).
    pub source: String,
    /// Standard uncertainty of each reading (R∞, R, Rg), absolute reflectance, per wavelength.
    pub u_reflectance: Vec<f64>,
    /// Standard uncertainty of the thickness, mm.
    pub u_thickness_mm: f64,
    /// Correlation coefficient between the readings.
    pub reading_correlation: f64,
    /// u(S) per wavelength, mm⁻¹.
    pub u_s_per_mm: Vec<f64>,
    /// u(K) per wavelength, mm⁻¹.
    pub u_k_per_mm: Vec<f64>,
}

/// Errors of building, loading or saving presets.
#[derive(Debug, thiserror::Error)]
pub enum PresetError {
    /// The file cannot be read or written.
    #[error("{path}: {source}")]
    Io {
        /// file
        path: String,
        /// cause
        source: std::io::Error,
    },
    /// Not valid JSON for the schema: the file, serde's 1-based line and column, and what serde
    /// says.
    #[error(transparent)]
    Json(LocatedError),
    /// A field with a bad value.
    #[error("{path}: {message}")]
    Invalid {
        /// file (or `<preset>` when not from a file)
        path: String,
        /// what and where
        message: String,
    },
    /// Inversion failed at a wavelength.
    #[error("{path}: at {wavelength_nm} nm: {error}")]
    Inversion {
        /// the measurement file
        path: String,
        /// wavelength, nm
        wavelength_nm: f64,
        /// why
        error: KmError,
    },
}

fn invalid(path: &str, message: String) -> PresetError {
    PresetError::Invalid { path: path.to_string(), message }
}

/// Per-wavelength S and K inverted from a measurement on the working grid (\[Huang2013\] eq. 6-7).
/// An error names the first wavelength without a solution.
pub fn invert_measurement(
    m: &WorkingMeasurement,
    thickness_mm: f64,
    source: &str,
) -> Result<(Spectrum, Spectrum), PresetError> {
    let mut s = [0.0; WORKING_LEN];
    let mut k = [0.0; WORKING_LEN];
    for i in 0..WORKING_LEN {
        let KmCoefficients { s_per_mm, k_per_mm } =
            km::invert_s_k(m.r_inf.0[i], m.r.0[i], m.rg.0[i], thickness_mm).map_err(|error| {
                PresetError::Inversion { path: source.to_string(), wavelength_nm: working_wavelength_nm(i), error }
            })?;
        s[i] = s_per_mm;
        k[i] = k_per_mm;
    }
    Ok((Spectrum(s), Spectrum(k)))
}

fn hex(rgb_linear: [f64; 3]) -> String {
    let [r, g, b] = rgb_linear.map(|v| (srgb_encode(v).clamp(0.0, 1.0) * 255.0).round() as u8);
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Computes the interchange tables of preset JSON v1 from S and K (the colour conversion lives
/// in [`layer_rgb_at`], shared with the render table).
pub fn derive_tables(s: &Spectrum, k: &Spectrum) -> Derived {
    let c = Colorimeter::get(Viewing::D65_1931);
    let thickness_mm = table_thicknesses_mm();
    let (r0, t) = layer_rgb_at(s, k, &thickness_mm);
    let r_inf = Spectrum(std::array::from_fn(|i| km::r_inf_from_s_k(s.0[i], k.0[i])));
    let r_inf_linear_srgb = c.srgb_linear(&c.xyz(&r_inf));
    Derived {
        viewing: Viewing::D65_1931.to_string(),
        thickness_mm,
        r0_linear_srgb: r0,
        t_linear_srgb: t,
        r_inf_linear_srgb,
        r_inf_srgb_hex: hex(r_inf_linear_srgb),
    }
}

/// A preset's render table ([`crate::layer_table::render_table`]) ends at the R∞ its JSON stores.
impl TableLayer for Preset {
    fn s_k(&self) -> (Spectrum, Spectrum) {
        (self.s(), self.k())
    }

    fn r_inf_linear_srgb(&self) -> [f64; 3] {
        self.derived.r_inf_linear_srgb
    }
}

/// What `rouge import` reports about a preset built from a measurement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ImportReport {
    /// Smallest and largest S, mm⁻¹, with their wavelengths.
    pub s_range_per_mm: [(f64, f64); 2],
    /// Smallest and largest K, mm⁻¹, with their wavelengths.
    pub k_range_per_mm: [(f64, f64); 2],
    /// Largest |R measured − R recomputed from S, K, D and Rg|, and its wavelength.
    pub max_abs_r_error: (f64, f64),
    /// Largest |R∞ measured − R∞ from S and K|, and its wavelength.
    pub max_abs_r_inf_error: (f64, f64),
    /// ΔE2000 (D65, 1931) between measured and recomputed R.
    pub delta_e_2000_r: f64,
    /// ΔE2000 (D65, 1931) between measured and recomputed R∞.
    pub delta_e_2000_r_inf: f64,
    /// sRGB hex of the measured R∞.
    pub r_inf_srgb_hex: String,
}

fn range_with_nm(v: &Spectrum) -> [(f64, f64); 2] {
    let mut lo = (f64::INFINITY, 0.0);
    let mut hi = (f64::NEG_INFINITY, 0.0);
    for (nm, x) in v.iter_nm() {
        if x < lo.0 {
            lo = (x, nm);
        }
        if x > hi.0 {
            hi = (x, nm);
        }
    }
    [lo, hi]
}

impl Preset {
    /// Builds a preset from S and K (mm⁻¹) on the working grid.
    pub fn from_s_k(name: &str, kind: Kind, thickness_mm: f64, s: &Spectrum, k: &Spectrum) -> Self {
        Preset {
            schema: SCHEMA.into(),
            version: VERSION_WITHOUT_FINISH,
            name: name.into(),
            kind,
            thickness_mm,
            wavelengths_nm: working_wavelengths_nm().to_vec(),
            s_per_mm: s.0.to_vec(),
            k_per_mm: k.0.to_vec(),
            measurement: None,
            specular: Specular::default_for(kind),
            derived: derive_tables(s, k),
            uncertainty: None,
            finish: None,
        }
    }

    /// Inverts a measurement into a preset and reports how well S and K reproduce it.
    ///
    /// `saunderson`, if given, converts the measured reflectances to internal ones before the
    /// inversion (see [`Saunderson`]); the report then compares internal reflectances. S and K
    /// come from \[Huang2013\] eq. 6-7 ([`km::invert_s_k`]) at every wavelength.
    ///
    /// # Examples
    ///
    /// Foundation 02 Ivory (`data/measurements/foundation_02_ivory.csv`, 20 µm over a black
    /// card): S and K give back the measured R and R∞ (ΔE2000 below 1e-6), and R over the card
    /// computed forward from them (\[Huang2013\] eq. 1-3) is the measured R at 550 nm.
    ///
    /// ```
    /// use rouge_measure::import::{ImportOptions, Kind, read_measurement};
    /// use rouge_measure::km::reflectance_over_background;
    /// use rouge_measure::{Extrapolation, Preset};
    /// use std::path::Path;
    ///
    /// let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/measurements/foundation_02_ivory.csv");
    /// let m = read_measurement(&path, &ImportOptions::default())?;
    /// let w = m.to_working_grid(Extrapolation::Refuse)?;
    /// let (preset, report) = Preset::from_measurement(&m, &w, "Ivory", Kind::Foundation, 0.02, None)?;
    /// assert!(report.delta_e_2000_r < 1e-6 && report.delta_e_2000_r_inf < 1e-6, "{report:?}");
    /// let i = (550 - 380) / 5;
    /// let r = reflectance_over_background(preset.s_per_mm[i], preset.k_per_mm[i], 0.02, w.rg.0[i])?;
    /// assert!((r - w.r.0[i]).abs() < 1e-12, "{r} vs {}", w.r.0[i]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_measurement(
        measurement: &Measurement,
        working: &WorkingMeasurement,
        name: &str,
        kind: Kind,
        thickness_mm: f64,
        saunderson: Option<Saunderson>,
    ) -> Result<(Preset, ImportReport), PresetError> {
        let source = measurement.source.display().to_string();
        if !(thickness_mm > 0.0 && thickness_mm.is_finite()) {
            return Err(invalid(&source, format!("thickness {thickness_mm} mm must be positive")));
        }
        let internal = match saunderson {
            None => working.clone(),
            Some(c) => WorkingMeasurement {
                r_inf: working.r_inf.map(|v| c.to_internal(v)),
                r: working.r.map(|v| c.to_internal(v)),
                rg: working.rg.map(|v| c.to_internal(v)),
                ..working.clone()
            },
        };
        // Check the KM domain on the measured grid first, so an error names a wavelength that
        // was actually measured; then invert on the working grid, where interpolation between
        // valid measured points can still (rarely) overshoot.
        let to_int = |v: f64| saunderson.map_or(v, |c| c.to_internal(v));
        for (i, &nm) in measurement.r_inf.wavelengths_nm().iter().enumerate() {
            let (a, b, c) = (measurement.r_inf.values()[i], measurement.r.values()[i], measurement.rg.values()[i]);
            km::invert_s_k(to_int(a), to_int(b), to_int(c), thickness_mm).map_err(|error| PresetError::Inversion {
                path: source.clone(),
                wavelength_nm: nm,
                error,
            })?;
        }
        let (s, k) = invert_measurement(&internal, thickness_mm, &source).map_err(|e| match e {
            PresetError::Inversion { path, wavelength_nm, error } => invalid(
                &path,
                format!(
                    "at {wavelength_nm} nm (interpolated between measured wavelengths, which are all valid): {error}; \
                     the measurement grid is too coarse for this spectrum's shape"
                ),
            ),
            other => other,
        })?;
        let mut preset = Preset::from_s_k(name, kind, thickness_mm, &s, &k);
        preset.measurement = Some(SourceMeasurement {
            file: measurement.source.file_name().map_or_else(String::new, |f| f.to_string_lossy().into_owned()),
            instrument: measurement.instrument.clone(),
            scale: measurement.scale.to_string(),
            saunderson,
            r_inf: working.r_inf.0.to_vec(),
            r: working.r.0.to_vec(),
            rg: working.rg.0.to_vec(),
        });
        let mut r_re = [0.0; WORKING_LEN];
        let mut r_inf_re = [0.0; WORKING_LEN];
        for i in 0..WORKING_LEN {
            let layer = km::layer_r_t_unchecked(s.0[i], k.0[i], thickness_mm);
            r_re[i] = km::compose(layer, LayerRt::opaque(internal.rg.0[i])).r;
            r_inf_re[i] = km::r_inf_from_s_k(s.0[i], k.0[i]);
        }
        let max_err = |a: &Spectrum, b: &[f64; WORKING_LEN]| {
            a.iter_nm()
                .zip(b)
                .map(|((nm, x), y)| ((x - y).abs(), nm))
                .fold((0.0, working_wavelength_nm(0)), |acc, e| if e.0 > acc.0 { e } else { acc })
        };
        let c = Colorimeter::get(Viewing::D65_1931);
        let de = |a: &Spectrum, b: &Spectrum| delta_e_2000_raw(c.lab(&c.xyz(a)).lab, c.lab(&c.xyz(b)).lab);
        let report = ImportReport {
            s_range_per_mm: range_with_nm(&s),
            k_range_per_mm: range_with_nm(&k),
            max_abs_r_error: max_err(&internal.r, &r_re),
            max_abs_r_inf_error: max_err(&internal.r_inf, &r_inf_re),
            delta_e_2000_r: de(&internal.r, &Spectrum(r_re)),
            delta_e_2000_r_inf: de(&internal.r_inf, &Spectrum(r_inf_re)),
            r_inf_srgb_hex: hex(c.srgb_linear(&c.xyz(&working.r_inf))),
        };
        Ok((preset, report))
    }

    /// S as a working-grid spectrum.
    pub fn s(&self) -> Spectrum {
        Spectrum::from_slice(&self.s_per_mm).unwrap_or(Spectrum::constant(0.0))
    }

    /// K as a working-grid spectrum.
    pub fn k(&self) -> Spectrum {
        Spectrum::from_slice(&self.k_per_mm).unwrap_or(Spectrum::constant(0.0))
    }

    /// Checks every field; `path` names the file in messages.
    pub fn validate(&self, path: &str) -> Result<(), PresetError> {
        if self.schema != SCHEMA {
            return Err(invalid(path, format!("`schema` is `{}`, expected `{SCHEMA}`", self.schema)));
        }
        if !(VERSION_WITHOUT_FINISH..=VERSION).contains(&self.version) {
            return Err(invalid(
                path,
                format!(
                    "preset schema version {} is not supported: this Rouge reads versions 1 to {VERSION}",
                    self.version
                ),
            ));
        }
        if let Some(finish) = &self.finish {
            if self.version < 2 {
                return Err(invalid(path, "`finish` needs preset schema version 2".into()));
            }
            finish.validate().map_err(|e| invalid(path, e))?;
        }
        if self.name.trim().is_empty() {
            return Err(invalid(path, "`name` is empty".into()));
        }
        if !(self.thickness_mm > 0.0 && self.thickness_mm.is_finite()) {
            return Err(invalid(path, format!("`thickness_mm` = {} must be positive", self.thickness_mm)));
        }
        let grid = working_wavelengths_nm();
        if self.wavelengths_nm.len() != WORKING_LEN
            || self.wavelengths_nm.iter().zip(grid).any(|(a, b)| (a - b).abs() > 1e-9)
        {
            return Err(invalid(path, "`wavelengths_nm` must be 380, 385, ..., 780 (81 values)".into()));
        }
        for (field, values) in [("s_per_mm", &self.s_per_mm), ("k_per_mm", &self.k_per_mm)] {
            if values.len() != WORKING_LEN {
                return Err(invalid(path, format!("`{field}` has {} values, expected {WORKING_LEN}", values.len())));
            }
            if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !(**v >= 0.0 && v.is_finite())) {
                return Err(invalid(
                    path,
                    format!("`{field}` at {} nm is {v}: must be finite and ≥ 0", working_wavelength_nm(i)),
                ));
            }
        }
        let sp = self.specular;
        if !(sp.roughness > 0.0 && sp.roughness <= 1.0) {
            return Err(invalid(path, format!("`specular.roughness` = {} must be in (0, 1]", sp.roughness)));
        }
        if !(1.0..=3.0).contains(&sp.ior) {
            return Err(invalid(path, format!("`specular.ior` = {} must be in [1, 3]", sp.ior)));
        }
        if let Some(m) = &self.measurement {
            for (field, values) in [("r_inf", &m.r_inf), ("r", &m.r), ("rg", &m.rg)] {
                if values.len() != WORKING_LEN {
                    return Err(invalid(
                        path,
                        format!("`measurement.{field}` has {} values, expected {WORKING_LEN}", values.len()),
                    ));
                }
                if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !(0.0..=1.5).contains(*v)) {
                    return Err(invalid(
                        path,
                        format!("`measurement.{field}` at {} nm is {v}: outside [0, 1.5]", working_wavelength_nm(i)),
                    ));
                }
            }
        }
        if let Some(u) = &self.uncertainty {
            for (field, values) in
                [("u_reflectance", &u.u_reflectance), ("u_s_per_mm", &u.u_s_per_mm), ("u_k_per_mm", &u.u_k_per_mm)]
            {
                if values.len() != WORKING_LEN {
                    return Err(invalid(
                        path,
                        format!("`uncertainty.{field}` has {} values, expected {WORKING_LEN}", values.len()),
                    ));
                }
                if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !(**v >= 0.0 && v.is_finite())) {
                    return Err(invalid(
                        path,
                        format!(
                            "`uncertainty.{field}` at {} nm is {v}: must be finite and ≥ 0",
                            working_wavelength_nm(i)
                        ),
                    ));
                }
            }
            if !(u.u_thickness_mm >= 0.0
                && u.u_thickness_mm.is_finite()
                && (0.0..=1.0).contains(&u.reading_correlation))
            {
                return Err(invalid(
                    path,
                    "`uncertainty.u_thickness_mm` must be ≥ 0 and `reading_correlation` in [0, 1]".into(),
                ));
            }
        }
        let d = &self.derived;
        let n = d.thickness_mm.len();
        if n < 2 || d.r0_linear_srgb.len() != n || d.t_linear_srgb.len() != n {
            return Err(invalid(path, "`derived` tables must have one row per thickness (at least 2)".into()));
        }
        if d.thickness_mm.windows(2).any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
            || d.thickness_mm[0] != 0.0
        {
            return Err(invalid(path, "`derived.thickness_mm` must start at 0 and increase".into()));
        }
        for (field, rows) in [("r0_linear_srgb", &d.r0_linear_srgb), ("t_linear_srgb", &d.t_linear_srgb)] {
            if let Some((i, row)) =
                rows.iter().enumerate().find(|(_, r)| r.iter().any(|v| !v.is_finite() || v.abs() > 2.0))
            {
                return Err(invalid(path, format!("`derived.{field}` row {i} = {row:?} is out of range")));
            }
        }
        Ok(())
    }

    /// Reads and validates a preset file.
    pub fn load(path: &Path) -> Result<Preset, PresetError> {
        let p = path.display().to_string();
        let io = |source| PresetError::Io { path: p.clone(), source };
        let bytes = read_bounded(path, MAX_PRESET_FILE_BYTES).map_err(io)?;
        let text = String::from_utf8(bytes)
            .map_err(|e| io(std::io::Error::new(std::io::ErrorKind::InvalidData, format!("not UTF-8: {e}"))))?;
        Self::from_json(&text, &p)
    }

    /// Parses and validates preset JSON; `path` names the source in messages.
    ///
    /// # Examples
    ///
    /// JSON round-trips exactly (`serde_json`'s `float_roundtrip`); a malformed file is refused
    /// with its line and column.
    ///
    /// ```
    /// use rouge_measure::import::Kind;
    /// use rouge_measure::{Preset, Spectrum};
    ///
    /// let (s, k) = (Spectrum::from_fn(|nm| 30.0 - nm / 100.0), Spectrum::constant(4.0));
    /// let p = Preset::from_s_k("sheer red", Kind::Lipstick, 0.02, &s, &k);
    /// assert_eq!(Preset::from_json(&p.to_json(), "red.json")?, p);
    /// let e = Preset::from_json("{\n  \"schema\": 3\n}", "bad.json").unwrap_err();
    /// assert!(e.to_string().starts_with("bad.json:2:"), "{e}");
    /// # Ok::<(), rouge_measure::PresetError>(())
    /// ```
    pub fn from_json(text: &str, path: &str) -> Result<Preset, PresetError> {
        // Check the version before the shape, so a future version gets the right message.
        if let Ok(v) = serde_json::from_str::<serde_json::Value>(text)
            && let Some(ver) = v.get("version").and_then(|x| x.as_u64())
            && !(u64::from(VERSION_WITHOUT_FINISH)..=u64::from(VERSION)).contains(&ver)
        {
            return Err(invalid(
                path,
                format!("preset schema version {ver} is not supported: this Rouge reads versions 1 to {VERSION}"),
            ));
        }
        let preset: Preset = serde_json::from_str(text).map_err(|e| {
            PresetError::Json(LocatedError::at(Path::new(path), e.line(), Some(e.column()), e.to_string()))
        })?;
        preset.validate(path)?;
        Ok(preset)
    }

    /// Gives the preset a finish (and the lobe it comes with), or takes it away: the version
    /// follows (2 with a finish, 1 without).
    pub fn set_finish(&mut self, finish: Option<(Specular, crate::finish::Finish)>) {
        match finish {
            Some((specular, finish)) => {
                self.specular = specular;
                self.finish = Some(finish);
                self.version = VERSION;
            }
            None => {
                self.finish = None;
                self.version = VERSION_WITHOUT_FINISH;
            }
        }
    }

    /// The film's clarity and levelling as the renderer draws them: the finish's, or for a preset
    /// without one a clear film that follows the relief (1, 0), as version 1 presets have always
    /// rendered.
    pub fn clarity_levelling(&self) -> (f64, f64) {
        self.finish.map_or((1.0, 0.0), |f| (f.clarity, f.levelling))
    }

    /// Serialises to pretty JSON (numbers round-trip exactly).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Writes the preset atomically: a temporary file in the same directory, then a rename, so a
    /// failed save never destroys an existing file.
    pub fn save(&self, path: &Path) -> Result<(), PresetError> {
        write_atomic(path, self.to_json().as_bytes())
            .map_err(|source| PresetError::Io { path: path.display().to_string(), source })
    }
}

/// Largest preset file read (bytes); a preset of the 401-wavelength grid is about 40 kB.
pub const MAX_PRESET_FILE_BYTES: u64 = 16 << 20;
