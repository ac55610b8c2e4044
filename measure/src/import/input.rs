//! One entry for spectral inputs: [`SpectralInput`]. Every spectrum Rouge reads passes through
//! it: a measurement for `rouge import` (R∞, R and Rg), the spectra of a table or a CGATS file
//! (`rouge color`, the skins of `rouge analyze`, the white standard of a radiance import, the
//! `rouge` Python package), and the data compiled into Rouge (the ColorChecker's skin patches
//! that the renderer and the analyses take as default skins, the demo measurement).
//!
//! The input's text is read once; its format is decided from its content, never its name: a
//! CGATS-family file has a `BEGIN_DATA_FORMAT` line, a radiance export a `No.` table with
//! `NNNnm` columns, anything else is a Rouge CSV measurement or a table of spectra. Every error
//! is a [`LocatedError`] naming the file (`<embedded>/...` for compiled-in data), and the line
//! and column where there is one.

use super::{ImportOptions, LocatedError, Measurement, Scale, cgats, radiance, rouge_csv};
use crate::spectrum::{Extrapolation, SampledSpectrum, Spectrum};
use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// The ColorChecker's "dark skin" and "light skin" patches (N. Ohta's measurements, written by
/// `python/gen_skin.py` from colour-science), 380-780 nm every 5 nm, as fractions.
const COLORCHECKER_SKIN_CSV: &str = include_str!("../../../data/skin/colorchecker_skin.csv");

/// The format of a spectral input, recognised from its content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputFormat {
    /// CGATS.17 text (X-Rite, i1Profiler, ArgyllCMS `.ti3` and `.sp`): a `BEGIN_DATA_FORMAT` line.
    Cgats,
    /// A spectroradiometer radiance export (CS-2000): a `No.` table with `NNNnm` columns.
    Radiance,
    /// Comma- or tab-separated text: a Rouge CSV measurement or a table of spectra.
    Csv,
}

/// A spectral input: its name for messages and its whole text, read once.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralInput {
    path: PathBuf,
    text: Cow<'static, str>,
}

/// Named spectra on the input's own grid, as fractions: the columns (or rows) of a table of
/// spectra, or the samples of a CGATS file, in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectra {
    /// The input.
    pub path: PathBuf,
    /// How the numbers were read (fractions or percent, declared or detected).
    pub scale: Scale,
    /// Every spectrum with its name (column header, row label or CGATS sample name).
    pub samples: Vec<(String, SampledSpectrum)>,
}

impl SpectralInput {
    /// Reads a file. Errors: it cannot be read, is not UTF-8 text (the byte where it stops
    /// being so), or holds nothing but white space.
    pub fn read(path: &Path) -> Result<SpectralInput, LocatedError> {
        let bytes = std::fs::read(path).map_err(|e| LocatedError::file(path, format!("cannot read: {e}")))?;
        let text = String::from_utf8(bytes)
            .map_err(|e| LocatedError::file(path, format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to())))?;
        if text.trim().is_empty() {
            return Err(LocatedError::file(path, "the file is empty"));
        }
        Ok(SpectralInput { path: path.to_path_buf(), text: Cow::Owned(text) })
    }

    /// Data compiled into Rouge, named `path` in messages (by convention `<embedded>/FILE`).
    pub fn embedded(path: impl Into<PathBuf>, text: &'static str) -> SpectralInput {
        SpectralInput { path: path.into(), text: Cow::Borrowed(text) }
    }

    /// The ColorChecker's two skin patches, `dark_skin` and `light_skin` (N. Ohta's
    /// measurements, `data/skin/colorchecker_skin.csv`), compiled in.
    pub fn colorchecker_skin() -> SpectralInput {
        SpectralInput::embedded("<embedded>/data/skin/colorchecker_skin.csv", COLORCHECKER_SKIN_CSV)
    }

    /// The name errors give.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The format, from the content.
    pub fn format(&self) -> InputFormat {
        if cgats::looks_like_cgats(&self.text) {
            InputFormat::Cgats
        } else if radiance::looks_like_radiance(&self.text) {
            InputFormat::Radiance
        } else {
            InputFormat::Csv
        }
    }

    /// A measurement: R∞, R and Rg from a CGATS file's named samples, a radiance export
    /// (\[Huang2013\] eq. 8, with `options`' white standard) or a Rouge CSV measurement.
    pub fn measurement(&self, options: &ImportOptions) -> Result<Measurement, LocatedError> {
        match self.format() {
            InputFormat::Cgats => cgats::parse(&self.path, &self.text)?.measurement(&options.samples),
            InputFormat::Radiance => {
                radiance::parse(&self.path, &self.text, &options.samples, options.white_reflectance.as_ref())
            }
            InputFormat::Csv => rouge_csv::parse(&self.path, &self.text),
        }
    }

    /// Every spectrum of the input: a CGATS file's samples, or a table of spectra's columns (or
    /// rows) in either layout colour-science uses ([`rouge_csv::parse_spectra_table`]).
    pub fn spectra(&self) -> Result<Spectra, LocatedError> {
        let (samples, scale) = match self.format() {
            InputFormat::Cgats => {
                let file = cgats::parse(&self.path, &self.text)?;
                (file.samples.into_iter().map(|s| (s.name, s.spectrum)).collect(), file.scale)
            }
            InputFormat::Radiance | InputFormat::Csv => rouge_csv::parse_spectra_table(&self.path, &self.text)?,
        };
        Ok(Spectra { path: self.path.clone(), scale, samples })
    }

    /// The one spectrum of a single-spectrum CGATS file (an ArgyllCMS `.sp`, or any CGATS file
    /// with one sample), with the file's `ROUGE_ROLE` keyword if present.
    pub fn single_spectrum(&self) -> Result<(SampledSpectrum, Option<String>, Scale), LocatedError> {
        if self.format() != InputFormat::Cgats {
            return Err(LocatedError::file(&self.path, "not a CGATS / ArgyllCMS .sp file (no BEGIN_DATA_FORMAT)"));
        }
        let file = cgats::parse(&self.path, &self.text)?;
        match file.samples.as_slice() {
            [one] => Ok((one.spectrum.clone(), file.keywords.get("ROUGE_ROLE").cloned(), file.scale)),
            many => Err(LocatedError::file(
                &self.path,
                format!(
                    "{} spectra in a file given as a single spectrum; name the samples with --samples instead",
                    many.len()
                ),
            )),
        }
    }
}

impl Spectra {
    /// Every spectrum resampled onto the working grid (Sprague on uniform grids, linear
    /// otherwise; see [`SampledSpectrum::to_working_grid`]). An error names the input and the
    /// sample: a grid that does not cover 380-780 nm without [`Extrapolation::Constant`].
    pub fn to_working_grid(&self, extrapolation: Extrapolation) -> Result<Vec<(String, Spectrum)>, LocatedError> {
        self.samples
            .iter()
            .map(|(name, s)| {
                let w = s
                    .to_working_grid(extrapolation)
                    .map_err(|e| LocatedError::file(&self.path, format!("sample `{name}`: {e}")))?;
                Ok((name.clone(), w.spectrum))
            })
            .collect()
    }
}

/// Every spectrum of a table of spectra or a CGATS file, as measured:
/// `SpectralInput::read(path)?.spectra()`.
///
/// # Examples
///
/// The ColorChecker's skins as a user's table, one column per skin:
///
/// ```
/// use rouge_measure::import::read_spectra;
///
/// let dir = std::env::temp_dir().join(format!("rouge-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let path = dir.join("skins.csv");
/// std::fs::write(&path, "wavelength_nm,a,b\n380,30,50\n780,40,60\n")?;
/// let spectra = read_spectra(&path)?;
/// // Percent, detected (the median value is above 1.5), read as fractions.
/// assert_eq!(spectra.samples[1].0, "b");
/// assert_eq!(spectra.samples[1].1.values(), &[0.5, 0.6]);
/// std::fs::write(&path, "wavelength_nm,a\n380,0.3\n390,x\n")?;
/// let e = read_spectra(&path).unwrap_err();
/// assert_eq!(e.to_string(), format!("{}:3:2: a `x` is not a number", path.display()));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_spectra(path: &Path) -> Result<Spectra, LocatedError> {
    SpectralInput::read(path)?.spectra()
}

/// The ColorChecker's `dark_skin` and `light_skin` patches (N. Ohta's measurements) on the
/// working grid: the default skins of the renderer and the analyses, parsed here only.
///
/// # Examples
///
/// ```
/// use rouge_measure::import::colorchecker_skin;
/// use rouge_measure::{Colorimeter, Viewing};
///
/// let skins = colorchecker_skin()?;
/// assert_eq!(skins.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), ["dark_skin", "light_skin"]);
/// // colour-science 0.4.7 (`sd_to_XYZ` by integration on 380-780/5 nm, D65, CIE 1931, Lab
/// // against the perfect reflector) gives light skin L*a*b* = 66.2002, 14.4668, 17.7397.
/// let c = Colorimeter::get(Viewing::D65_1931);
/// let lab = c.lab(&c.xyz(&skins[1].1)).lab;
/// for (got, want) in lab.iter().zip([66.200_19, 14.466_85, 17.739_68]) {
///     assert!((got - want).abs() < 1e-4, "{lab:?}");
/// }
/// # Ok::<(), rouge_measure::LocatedError>(())
/// ```
pub fn colorchecker_skin() -> Result<Vec<(String, Spectrum)>, LocatedError> {
    SpectralInput::colorchecker_skin().spectra()?.to_working_grid(Extrapolation::Refuse)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_format_comes_from_the_content() {
        let csv = SpectralInput::embedded("a.txt", "wavelength_nm,a\n380,0.1\n780,0.2\n");
        assert_eq!(csv.format(), InputFormat::Csv);
        let cgats = SpectralInput::embedded(
            "b.csv",
            "CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_NAME nm380 nm780\nEND_DATA_FORMAT\nBEGIN_DATA\nA 0.1 0.2\nEND_DATA\n",
        );
        assert_eq!(cgats.format(), InputFormat::Cgats);
        let s = cgats.spectra().unwrap();
        assert_eq!((s.samples.len(), s.samples[0].0.as_str()), (1, "A"));
        assert_eq!(cgats.single_spectrum().unwrap().0.values(), &[0.1, 0.2]);
        let e = csv.single_spectrum().unwrap_err().to_string();
        assert_eq!(e, "a.txt: not a CGATS / ArgyllCMS .sp file (no BEGIN_DATA_FORMAT)");
    }

    #[test]
    fn working_grid_errors_name_the_input_and_the_sample() {
        let short = SpectralInput::embedded("s.csv", "wavelength_nm,a\n400,0.1\n780,0.2\n");
        let e = short.spectra().unwrap().to_working_grid(Extrapolation::Refuse).unwrap_err();
        assert!(e.to_string().starts_with("s.csv: sample `a`: "), "{e}");
        assert!(short.spectra().unwrap().to_working_grid(Extrapolation::Constant).is_ok());
    }

    #[test]
    fn missing_and_empty_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("none.csv");
        assert!(SpectralInput::read(&p).unwrap_err().message.starts_with("cannot read: "));
        std::fs::write(&p, " \n").unwrap();
        assert_eq!(SpectralInput::read(&p).unwrap_err().message, "the file is empty");
        std::fs::write(&p, b"wavelength_nm,a\n\xff").unwrap();
        assert_eq!(SpectralInput::read(&p).unwrap_err().message, "not UTF-8 text (byte 16)");
    }
}
