//! The spectral skin model of `rouge_measure::skin` for Python (docs/SKIN.md): the forward model,
//! the fit, the named tones. Parameters travel as dicts with the field names of `SkinParams`
//! (`melanin_fraction`, `pheomelanin_share`, `blood_fraction`, `oxygen_saturation`,
//! `scattering_500nm_per_mm`, `scattering_power`, `epidermis_thickness_mm`).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rouge_measure::skin::fit::SkinFitter;
use rouge_measure::skin::{FitOptions, SkinError, SkinParams, Specular, skin_tones};
use rouge_measure::spectrum::{Extrapolation, working_wavelength_nm};

fn err(e: SkinError) -> PyErr {
    crate::errors::RougeError::new_err(e.to_string())
}

fn params_dict<'py>(py: Python<'py>, p: &SkinParams) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (v, r) in p.to_array().iter().zip(SkinParams::RANGES) {
        d.set_item(r.name, *v)?;
    }
    Ok(d)
}

/// Reflectance of the skin model (specular included, as a d/8° instrument in SCI mode reads) at
/// `wavelengths` (nm, 380-780; default the working grid 380-780 / 5 nm). Start from the named
/// `tone` (see `skin_tones()`) or the light default; keywords override single parameters.
#[pyfunction]
#[pyo3(signature = (*, tone=None, melanin_fraction=None, pheomelanin_share=None, blood_fraction=None, oxygen_saturation=None, scattering_500nm_per_mm=None, scattering_power=None, epidermis_thickness_mm=None, wavelengths=None))]
#[allow(clippy::too_many_arguments)]
pub fn skin_reflectance(
    tone: Option<&str>,
    melanin_fraction: Option<f64>,
    pheomelanin_share: Option<f64>,
    blood_fraction: Option<f64>,
    oxygen_saturation: Option<f64>,
    scattering_500nm_per_mm: Option<f64>,
    scattering_power: Option<f64>,
    epidermis_thickness_mm: Option<f64>,
    wavelengths: Option<Vec<f64>>,
) -> PyResult<Vec<f64>> {
    let overrides = [
        melanin_fraction,
        pheomelanin_share,
        blood_fraction,
        oxygen_saturation,
        scattering_500nm_per_mm,
        scattering_power,
        epidermis_thickness_mm,
    ];
    let p = SkinParams::from_tone(tone, overrides).map_err(err)?;
    let wl = wavelengths.unwrap_or_else(|| (0..81).map(working_wavelength_nm).collect());
    p.reflectance_at(&wl).map_err(err)
}

/// Fits the skin model to each row of `R` (reflectances as fractions at `wavelengths`, nm).
/// Returns one dict per row: `params` (dict), `fitted_reflectance` (at `wavelengths` inside
/// 380-780 nm), `delta_E` (CIEDE2000, D65, CIE 1931), `rms`, `Lab_measured`, `Lab_fitted`,
/// `at_bounds`. `extrapolate` holds the end values of spectra that stop short of 380/780 nm;
/// `specular` says whether the measurement includes the surface reflection (`included`, SCI) or
/// not (`excluded`, SCE).
#[pyfunction]
#[pyo3(signature = (R, wavelengths, *, epidermis_thickness_mm=0.1, extrapolate=false, specular="included"))]
#[allow(non_snake_case)]
pub fn skin_fit<'py>(
    py: Python<'py>,
    R: Vec<Vec<f64>>,
    wavelengths: Vec<f64>,
    epidermis_thickness_mm: f64,
    extrapolate: bool,
    specular: &str,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let specular = match specular {
        "included" => Specular::Included,
        "excluded" => Specular::Excluded,
        other => {
            return Err(crate::errors::RougeError::new_err(format!(
                "specular=`{other}`: `included` (SCI) or `excluded` (SCE)"
            )));
        }
    };
    let options = FitOptions {
        specular,
        epidermis_thickness_mm,
        extrapolation: if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse },
        ..FitOptions::default()
    };
    let fitter = SkinFitter::new(options).map_err(err)?;
    let inside: Vec<f64> = wavelengths.iter().copied().filter(|w| (380.0..=780.0).contains(w)).collect();
    let mut out = Vec::with_capacity(R.len());
    for (i, row) in R.iter().enumerate() {
        if row.len() != wavelengths.len() {
            return Err(crate::errors::RougeError::new_err(format!(
                "spectrum {i}: {} values for {} wavelengths",
                row.len(),
                wavelengths.len()
            )));
        }
        let f = py
            .detach(|| fitter.fit(&wavelengths, row))
            .map_err(|e| crate::errors::RougeError::new_err(format!("spectrum {i}: {e}")))?;
        let d = PyDict::new(py);
        d.set_item("params", params_dict(py, &f.params)?)?;
        d.set_item("fitted_reflectance", f.params.reflectance_at(&inside).map_err(err)?)?;
        d.set_item("wavelengths", inside.clone())?;
        d.set_item("delta_E", f.delta_e_2000)?;
        d.set_item("rms", f.rms)?;
        d.set_item("Lab_measured", f.lab_measured.to_vec())?;
        d.set_item("Lab_fitted", f.lab_fitted.to_vec())?;
        d.set_item("at_bounds", f.at_bounds.clone())?;
        out.push(d);
    }
    Ok(out)
}

/// The named skin tones, very light to very deep: dicts of `name`, `fitzpatrick`, `params`, `source`.
#[pyfunction]
pub fn skin_tones_list<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    skin_tones()
        .iter()
        .map(|t| {
            let d = PyDict::new(py);
            d.set_item("name", &t.name)?;
            d.set_item("fitzpatrick", &t.fitzpatrick)?;
            d.set_item("params", params_dict(py, &t.params)?)?;
            d.set_item("source", &t.source)?;
            Ok(d)
        })
        .collect()
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(skin_reflectance, m)?)?;
    m.add_function(wrap_pyfunction!(skin_fit, m)?)?;
    m.add_function(wrap_pyfunction!(skin_tones_list, m)?)?;
    Ok(())
}
