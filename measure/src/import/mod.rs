//! Import of cosmetic measurements: R∞ (opaque layer), R (thin layer of known thickness over a
//! background) and Rg (the background), from the formats instruments and people produce, and of
//! any other spectra (skins, white standards, colour tables).
//!
//! * [`input`]: the one entry, [`SpectralInput`]: reads a file (or compiled-in data) once,
//!   recognises its format from its content and gives a [`Measurement`] or named [`Spectra`];
//!   the embedded ColorChecker skins ([`colorchecker_skin`]) are parsed there.
//! * [`rouge_csv`]: Rouge CSV (`wavelength_nm,r_inf,r,rg` with `# key: value` comments).
//! * [`cgats`]: CGATS.17 text as written by X-Rite and i1Profiler (`nm380`, `SPECTRAL_NM380`)
//!   and ArgyllCMS (`.ti3` with `SPEC_380` in percent, `.sp` single spectra).
//! * [`radiance`]: spectroradiometer radiance (a Konica Minolta CS-2000 export): reflectance from
//!   the sample's and the white standard's radiance (\[Huang2013\] eq. 8).
//!
//! Every error names the file, and the line and column where there is one. Nothing is returned
//! unless the whole file is valid. Formats are specified in `docs/FORMATS.md`.

pub mod cgats;
pub mod input;
pub mod radiance;
pub mod rouge_csv;

pub use input::{InputFormat, Spectra, SpectralInput, colorchecker_skin, read_spectra};

use crate::error::LocatedError;
use crate::spectrum::{Extrapolation, ResampleMethod, SampledSpectrum, Spectrum, SpectrumError};
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// Largest reflectance accepted (fluorescent or glossy samples can exceed 1 a little).
pub const MAX_REFLECTANCE: f64 = 1.5;

/// Whether the numbers in a file are fractions (0-1) or percent (0-100), and how that was decided.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Fractions; `declared` says whether the file said so.
    Fraction {
        /// declared by the file (`# unit: fraction`, `SPECTRAL_NORM 1`)
        declared: bool,
    },
    /// Percent; `declared` says whether the file said so.
    Percent {
        /// declared by the file (`# unit: percent`, `SPECTRAL_NORM 100`)
        declared: bool,
    },
}

impl Scale {
    /// Factor that turns file values into fractions.
    pub fn factor(&self) -> f64 {
        match self {
            Scale::Fraction { .. } => 1.0,
            Scale::Percent { .. } => 0.01,
        }
    }
}

impl fmt::Display for Scale {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Scale::Fraction { declared: true } => write!(f, "fractions (declared)"),
            Scale::Fraction { declared: false } => write!(f, "fractions (detected: median value ≤ 1.5)"),
            Scale::Percent { declared: true } => write!(f, "percent (declared)"),
            Scale::Percent { declared: false } => {
                write!(f, "percent (detected: median value above 1.5)")
            }
        }
    }
}

/// A number read from a file, with its position for error messages.
#[derive(Clone, Copy, Debug)]
pub struct Cell {
    /// the number
    pub value: f64,
    /// 1-based line
    pub line: usize,
    /// 1-based column
    pub column: usize,
}

/// Decides fraction or percent from the values (see `docs/FORMATS.md`): percent when the
/// median of all reflectance cells is above 1.5, fractions otherwise. The median, not the
/// maximum, so that one wrong value in a fraction file is reported as out of range instead of
/// silently turning the whole file into percent.
pub(crate) fn detect_scale(cells: &[Cell]) -> Scale {
    let mut v: Vec<f64> = cells.iter().map(|c| c.value).collect();
    v.sort_by(f64::total_cmp);
    let median = if v.is_empty() { 0.0 } else { v[v.len() / 2] };
    if median > MAX_REFLECTANCE { Scale::Percent { declared: false } } else { Scale::Fraction { declared: false } }
}

/// Checks reflectances (already scaled to fractions) lie in [0, 1.5].
pub(crate) fn check_reflectance_range(path: &Path, cells: &[Cell], factor: f64) -> Result<(), LocatedError> {
    for c in cells {
        let v = c.value * factor;
        if !(0.0..=MAX_REFLECTANCE).contains(&v) {
            return Err(LocatedError::at(path, c.line, Some(c.column), format!("reflectance {v} is outside [0, 1.5]")));
        }
    }
    Ok(())
}

/// Parses a number cell; NaN and infinities are errors.
pub(crate) fn parse_number(
    path: &Path,
    text: &str,
    line: usize,
    column: usize,
    what: &str,
) -> Result<f64, LocatedError> {
    let t = text.trim();
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(LocatedError::at(path, line, Some(column), format!("{what} is {v}: not a finite number"))),
        Err(_) if t.is_empty() => Err(LocatedError::at(path, line, Some(column), format!("{what} is empty"))),
        Err(_) => Err(LocatedError::at(path, line, Some(column), format!("{what} `{t}` is not a number"))),
    }
}

/// Checks a wavelength column: strictly increasing, no duplicates, each with its line.
pub(crate) fn check_wavelengths(path: &Path, cells: &[Cell]) -> Result<(), LocatedError> {
    for pair in cells.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b.value == a.value {
            return Err(LocatedError::at(
                path,
                b.line,
                Some(b.column),
                format!("wavelength {} nm appears twice (also on line {})", b.value, a.line),
            ));
        }
        if b.value < a.value {
            return Err(LocatedError::at(
                path,
                b.line,
                Some(b.column),
                format!("wavelengths must increase: {} nm follows {} nm", b.value, a.value),
            ));
        }
    }
    Ok(())
}

/// Kind of cosmetic.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// Foundation.
    Foundation,
    /// Blush.
    Blush,
    /// Eyeshadow.
    Eyeshadow,
    /// Lipstick.
    Lipstick,
    /// Anything else.
    Other,
}

impl Kind {
    /// All kinds.
    pub const ALL: [Kind; 5] = [Kind::Foundation, Kind::Blush, Kind::Eyeshadow, Kind::Lipstick, Kind::Other];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Foundation => "foundation",
            Kind::Blush => "blush",
            Kind::Eyeshadow => "eyeshadow",
            Kind::Lipstick => "lipstick",
            Kind::Other => "other",
        }
    }

    /// Parses a name (case-insensitive).
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name().eq_ignore_ascii_case(s.trim()))
    }
}

/// The three spectra of a KM measurement on the file's own grid, with what the file said.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Where it came from.
    pub source: PathBuf,
    /// The file format, in words (`Rouge CSV`, `CGATS (CGATS.17)`, `CS-2000 radiance`, ...).
    pub format: String,
    /// Name (from the file, or the file stem).
    pub name: String,
    /// Cosmetic kind, if the file says.
    pub kind: Option<Kind>,
    /// Thickness of the thin layer, if the file says.
    pub thickness_mm: Option<f64>,
    /// Instrument, if the file says.
    pub instrument: Option<String>,
    /// Every `key: value` the file carried (Rouge CSV comments, CGATS keywords).
    pub metadata: BTreeMap<String, String>,
    /// How numbers were scaled.
    pub scale: Scale,
    /// Reflectance of the opaque layer.
    pub r_inf: SampledSpectrum,
    /// Reflectance of the thin layer over the background.
    pub r: SampledSpectrum,
    /// Reflectance of the background.
    pub rg: SampledSpectrum,
}

/// A measurement on the working grid, with how it got there.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkingMeasurement {
    /// R∞.
    pub r_inf: Spectrum,
    /// R.
    pub r: Spectrum,
    /// Rg.
    pub rg: Spectrum,
    /// Resampling used (the same for the three spectra, which share a grid).
    pub method: ResampleMethod,
    /// Extrapolated ranges, if any: `(first, last)` nm below and above the measured range.
    pub extrapolated: Vec<(f64, f64)>,
}

impl Measurement {
    /// Resamples the three spectra onto the working grid.
    pub fn to_working_grid(&self, extrapolation: Extrapolation) -> Result<WorkingMeasurement, LocatedError> {
        let conv = |s: &SampledSpectrum, what: &str| {
            s.to_working_grid(extrapolation)
                .map_err(|e: SpectrumError| LocatedError::file(&self.source, format!("{what}: {e}")))
        };
        let a = conv(&self.r_inf, "r_inf")?;
        let b = conv(&self.r, "r")?;
        let c = conv(&self.rg, "rg")?;
        let extrapolated = [a.extrapolated_below_nm, a.extrapolated_above_nm].into_iter().flatten().collect();
        Ok(WorkingMeasurement { r_inf: a.spectrum, r: b.spectrum, rg: c.spectrum, method: a.method, extrapolated })
    }
}

/// Which samples of a multi-sample file (CGATS) hold R∞, R and Rg.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SampleNames {
    /// Name of the opaque-layer sample.
    pub r_inf: String,
    /// Name of the thin-layer-over-background sample.
    pub r: String,
    /// Name of the background sample.
    pub rg: String,
}

impl Default for SampleNames {
    fn default() -> Self {
        SampleNames { r_inf: "R_INF".into(), r: "R".into(), rg: "RG".into() }
    }
}

/// Options of [`read_measurement`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImportOptions {
    /// Sample names in multi-sample files.
    pub samples: SampleNames,
    /// Reflectance of the white standard for radiance files (`None`: flat 0.99, BaSO4).
    pub white_reflectance: Option<SampledSpectrum>,
}

/// Reads a measurement file of any supported format, chosen from its content (not its name):
/// a CGATS-family file has a `BEGIN_DATA_FORMAT` line; a radiance export has a `No.` table with
/// `NNNnm` columns; anything else is read as Rouge CSV. The same as
/// `SpectralInput::read(path)?.measurement(options)` ([`SpectralInput::measurement`]).
///
/// # Examples
///
/// The same product as Rouge CSV and as an X-Rite CGATS export (`data/measurements/`): the
/// format comes from the content, and both give R∞ = 0.398988 at 550 nm.
///
/// ```
/// use rouge_measure::import::{ImportOptions, Kind, read_measurement};
/// use std::path::Path;
///
/// let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/measurements");
/// let csv = read_measurement(&dir.join("foundation_02_ivory.csv"), &ImportOptions::default())?;
/// assert_eq!((csv.format.as_str(), csv.kind, csv.thickness_mm), ("Rouge CSV", Some(Kind::Foundation), Some(0.02)));
/// let xrite = read_measurement(&dir.join("formats/foundation_02_ivory_xrite.txt"), &ImportOptions::default())?;
/// assert_eq!(xrite.format, "CGATS text (CGATS.17)");
/// let at_550 = |m: &rouge_measure::Measurement| {
///     m.r_inf.wavelengths_nm().iter().zip(m.r_inf.values()).find(|(nm, _)| **nm == 550.0).map(|(_, v)| *v)
/// };
/// assert_eq!((at_550(&csv), at_550(&xrite)), (Some(0.398988), Some(0.398988)));
/// # Ok::<(), rouge_measure::LocatedError>(())
/// ```
pub fn read_measurement(path: &Path, options: &ImportOptions) -> Result<Measurement, LocatedError> {
    SpectralInput::read(path)?.measurement(options)
}

/// Reads one spectrum from a single-spectrum CGATS file (an ArgyllCMS `.sp`, or any CGATS file
/// with one sample), returning it with the file's `ROUGE_ROLE` keyword if present
/// ([`SpectralInput::single_spectrum`]).
pub fn read_single_spectrum(path: &Path) -> Result<(SampledSpectrum, Option<String>, Scale), LocatedError> {
    SpectralInput::read(path)?.single_spectrum()
}

/// Builds a measurement from three single-spectrum files (R∞, R, Rg), such as ArgyllCMS `.sp`
/// files. A file whose `ROUGE_ROLE` keyword contradicts the role it is given is refused.
pub fn read_measurement_files(r_inf: &Path, r: &Path, rg: &Path) -> Result<Measurement, LocatedError> {
    let mut spectra = Vec::with_capacity(3);
    for (path, role) in [(r_inf, "R_INF"), (r, "R"), (rg, "RG")] {
        let (spectrum, declared, scale) = read_single_spectrum(path)?;
        if let Some(d) = declared
            && !d.eq_ignore_ascii_case(role)
        {
            {
                return Err(LocatedError::file(
                    path,
                    format!("this file says ROUGE_ROLE {d}, but it was given as {role}"),
                ));
            }
        }
        spectra.push((spectrum, scale));
    }
    let grids: Vec<&[f64]> = spectra.iter().map(|(s, _)| s.wavelengths_nm()).collect();
    if grids[1] != grids[0] || grids[2] != grids[0] {
        return Err(LocatedError::file(r, "R∞, R and Rg must share one wavelength grid"));
    }
    let [a, b, c]: [(SampledSpectrum, Scale); 3] =
        spectra.try_into().map_err(|_| LocatedError::file(r_inf, "internal: three spectra expected"))?;
    Ok(Measurement {
        source: r_inf.to_path_buf(),
        format: "three single-spectrum CGATS files (R∞, R, Rg)".into(),
        name: r_inf.file_stem().map(|s| s.to_string_lossy().trim_end_matches("_r_inf").to_string()).unwrap_or_default(),
        kind: None,
        thickness_mm: None,
        instrument: None,
        metadata: BTreeMap::new(),
        scale: a.1,
        r_inf: a.0,
        r: b.0,
        rg: c.0,
    })
}
