//! Skin reflectance spectra from the user's files, in the formats `rouge import` and `rouge
//! color` read: a spectra table (Rouge CSV with a `wavelength_nm` column and one column per
//! skin) or a CGATS file (X-Rite, i1Profiler, ArgyllCMS `.ti3`/`.sp`; one sample per skin),
//! chosen by content, through the one entry for spectral inputs ([`read_spectra`]). Rouge ships
//! no real skin data: measured skins, such as the Xiao et al. database (\[Xiao2016\]) read by
//! `python/skin_gamut.py`, come in as such files.

use crate::error::LocatedError;
use crate::import::read_spectra;
use crate::spectrum::{Extrapolation, SampledSpectrum, Spectrum, working_wavelength_nm};
use std::path::Path;

/// Reads every skin of `path` as measured, on its own wavelengths (the skin model's fit works
/// there). Errors name the file and the line and column of a bad cell.
pub fn read_sampled_skins(path: &Path) -> Result<Vec<(String, SampledSpectrum)>, LocatedError> {
    Ok(read_spectra(path)?.samples)
}

/// Reads every skin of `path` onto the working grid. Errors name the file and the line and
/// column (a bad cell), or the sample and wavelength (a grid that does not cover 380-780 nm
/// without `Extrapolation::Constant`, a reflectance outside [0, 1] after resampling).
pub fn read_skins(path: &Path, extrapolation: Extrapolation) -> Result<Vec<(String, Spectrum)>, LocatedError> {
    let sampled = read_sampled_skins(path)?;
    sampled
        .into_iter()
        .map(|(name, s)| {
            let w = s.to_working_grid(extrapolation).map_err(|e| {
                LocatedError::file(path, format!("skin `{name}`: {e} (--extrapolate holds the end values)"))
            })?;
            if let Some(i) = w.spectrum.0.iter().position(|v| !(0.0..=1.0).contains(v)) {
                return Err(LocatedError::file(
                    path,
                    format!(
                        "skin `{name}`: reflectance {} at {} nm is outside [0, 1]",
                        w.spectrum.0[i],
                        working_wavelength_nm(i)
                    ),
                ));
            }
            Ok((name, w.spectrum))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_tables_and_names_the_fault() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("skins.csv");
        let rows: String = (0..=40).map(|i| format!("{},0.3,0.5\n", 380 + 10 * i)).collect();
        std::fs::write(&p, format!("wavelength_nm,a,b\n{rows}")).unwrap();
        let skins = read_skins(&p, Extrapolation::Refuse).unwrap();
        assert_eq!(skins.len(), 2);
        assert_eq!(skins[1].0, "b");
        assert!((skins[1].1.0[7] - 0.5).abs() < 1e-12);
        // 360-740 nm needs --extrapolate.
        let rows: String = (0..=38).map(|i| format!("{},0.3\n", 360 + 10 * i)).collect();
        std::fs::write(&p, format!("wavelength_nm,a\n{rows}")).unwrap();
        let e = read_skins(&p, Extrapolation::Refuse).unwrap_err().to_string();
        assert!(e.contains("skin `a`") && e.contains("--extrapolate"), "{e}");
        assert!(read_skins(&p, Extrapolation::Constant).is_ok());
        std::fs::write(&p, "wavelength_nm,a\n380,0.3\n390,x\n").unwrap();
        let e = read_skins(&p, Extrapolation::Refuse).unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), Some(2)));
    }
}
