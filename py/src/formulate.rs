//! The formulator's bench for Python (docs/FORMULATION.md): metamerism indices
//! (`rouge_measure::analysis::metamerism`), batch correction (`analysis::correction`) and the uncertainty of S and K
//! (`rouge_measure::km_uncertainty`). Spectra on the working grid (81 values); colour-difference
//! keys are colour-science's `delta_E` method names (`"CIE 1976"`, `"CIE 2000"`).
#![allow(non_snake_case)]

use crate::color::viewing;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rouge_measure::analysis::Layer;
use rouge_measure::analysis::correction::{Presentation, correct_batch};
use rouge_measure::analysis::metamerism::{Correction, metamerism_index};
use rouge_measure::colorimetry::Colorimeter;
use rouge_measure::km_uncertainty::{ILL_CONDITIONED, InputUncertainty, optimal_thickness_mm, propagate_s_k};
use rouge_measure::spectrum::{Spectrum, WORKING_LEN};

fn spectrum(what: &str, values: Vec<f64>) -> PyResult<Spectrum> {
    Spectrum::from_slice(&values).map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: {} values; give the {WORKING_LEN} of the working grid 380-780 nm / 5 nm (resample_to_working_grid)",
            values.len()
        ))
    })
}

/// The special metamerism index of `sd_standard` and `sd_sample` (81 reflectances each) for a
/// change from the reference viewing (`illuminant_reference`, `cmfs_reference`) to the test
/// viewing (`illuminant_test`, `cmfs_test`, the reference observer when None), after the
/// `correction` ("multiplicative", "additive" or "none"; CIE 15:2018 §9, ISO 18314-4).
/// Returns a dict: `"CIE 1976"` (ΔE*ab), `"CIE 2000"` (ΔE2000), `Lab_standard`,
/// `Lab_sample_corrected` (under the test viewing).
#[pyfunction]
#[pyo3(signature = (sd_standard, sd_sample, *, illuminant_reference="D65", illuminant_test="A",
    cmfs_reference="CIE 1931 2 Degree Standard Observer", cmfs_test=None, correction="multiplicative"))]
#[allow(clippy::too_many_arguments)]
pub fn metamerism_index_special<'py>(
    py: Python<'py>,
    sd_standard: Vec<f64>,
    sd_sample: Vec<f64>,
    illuminant_reference: &str,
    illuminant_test: &str,
    cmfs_reference: &str,
    cmfs_test: Option<&str>,
    correction: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let reference = viewing(illuminant_reference, cmfs_reference)?;
    let test = viewing(illuminant_test, cmfs_test.unwrap_or(cmfs_reference))?;
    let c = Correction::parse(correction).ok_or_else(|| {
        PyValueError::new_err(format!("correction `{correction}`: one of multiplicative, additive, none"))
    })?;
    let m = metamerism_index(
        &spectrum("sd_standard", sd_standard)?,
        &spectrum("sd_sample", sd_sample)?,
        reference,
        test,
        c,
    )
    .map_err(|e| crate::errors::RougeError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("CIE 1976", m.delta_e_ab)?;
    d.set_item("CIE 2000", m.delta_e_2000)?;
    d.set_item("Lab_standard", m.standard_lab.to_vec())?;
    d.set_item("Lab_sample_corrected", m.sample_lab_corrected.to_vec())?;
    Ok(d)
}

fn per_wavelength(what: &str, v: Vec<f64>, n: usize) -> PyResult<Vec<f64>> {
    match v.len() {
        1 => Ok(vec![v[0]; n]),
        m if m == n => Ok(v),
        m => Err(PyValueError::new_err(format!("{what}: {m} values for {n} wavelengths (give 1 or {n})"))),
    }
}

/// Standard uncertainties of Kubelka-Munk S and K inverted from `R_inf`, `R` over `Rg` at
/// `thickness_mm` (equal-length sequences, one value per wavelength), by linear propagation
/// (GUM) of the readings' standard uncertainty `u_R` (one value, or one per wavelength) and
/// `u_thickness_mm`, with `reading_correlation` between readings. Returns a dict of lists: `S`,
/// `K`, `u_S`, `u_K`, `correlation_SK`, `condition` (None where S or K is 0) and
/// `ill_conditioned` (bool: condition above `ILL_CONDITIONED_ABOVE`).
#[pyfunction]
#[pyo3(name = "SK_uncertainty", signature = (R_inf, R, Rg, thickness_mm, u_R, *, u_thickness_mm=0.0, reading_correlation=0.0))]
#[allow(clippy::too_many_arguments)]
pub fn sk_uncertainty<'py>(
    py: Python<'py>,
    R_inf: Vec<f64>,
    R: Vec<f64>,
    Rg: Vec<f64>,
    thickness_mm: f64,
    u_R: Vec<f64>,
    u_thickness_mm: f64,
    reading_correlation: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let n = R_inf.len();
    let (R, Rg) = (per_wavelength("R", R, n)?, per_wavelength("Rg", Rg, n)?);
    let u_R = per_wavelength("u_R", u_R, n)?;
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        let u = InputUncertainty { reading_correlation, ..InputUncertainty::readings(u_R[i], u_thickness_mm) };
        let v = propagate_s_k(R_inf[i], R[i], Rg[i], thickness_mm, &u)
            .map_err(|e| crate::errors::RougeError::new_err(format!("at index {i}: {e}")))?;
        rows.push(v);
    }
    let d = PyDict::new(py);
    d.set_item("S", rows.iter().map(|r| r.s_per_mm).collect::<Vec<_>>())?;
    d.set_item("K", rows.iter().map(|r| r.k_per_mm).collect::<Vec<_>>())?;
    d.set_item("u_S", rows.iter().map(|r| r.u_s_per_mm).collect::<Vec<_>>())?;
    d.set_item("u_K", rows.iter().map(|r| r.u_k_per_mm).collect::<Vec<_>>())?;
    d.set_item("correlation_SK", rows.iter().map(|r| r.correlation_sk).collect::<Vec<_>>())?;
    d.set_item("condition", rows.iter().map(|r| r.condition).collect::<Vec<_>>())?;
    d.set_item(
        "ill_conditioned",
        rows.iter().map(|r| r.condition.is_none_or(|c| c > ILL_CONDITIONED)).collect::<Vec<_>>(),
    )?;
    Ok(d)
}

/// The thin-layer thickness (mm, within `bounds_mm`) at which measuring a product of `S`, `K`
/// (81 values each) over a background `Rg` with readings of standard uncertainty `u_R` and a
/// thickness known to `u_thickness_mm` gives the most certain S and K (RMS over wavelengths of
/// the relative standard uncertainties). Returns a dict: `thickness_mm`,
/// `relative_uncertainty`; None when no thickness of the range gives a solution.
#[pyfunction]
#[pyo3(name = "SK_thickness_optimal", signature = (S, K, Rg, u_R, *, u_thickness_mm=0.0, bounds_mm=(0.001, 1.0)))]
pub fn sk_thickness_optimal<'py>(
    py: Python<'py>,
    S: Vec<f64>,
    K: Vec<f64>,
    Rg: Vec<f64>,
    u_R: Vec<f64>,
    u_thickness_mm: f64,
    bounds_mm: (f64, f64),
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let u = per_wavelength("u_R", u_R, WORKING_LEN)?;
    let rg = per_wavelength("Rg", Rg, WORKING_LEN)?;
    let best = optimal_thickness_mm(
        &spectrum("S", S)?,
        &spectrum("K", K)?,
        &spectrum("Rg", rg)?,
        &spectrum("u_R", u)?,
        u_thickness_mm,
        bounds_mm.0,
        bounds_mm.1,
    );
    best.map(|b| {
        let d = PyDict::new(py);
        d.set_item("thickness_mm", b.thickness_mm)?;
        d.set_item("relative_uncertainty", b.relative_uncertainty)?;
        Ok(d)
    })
    .transpose()
}

/// Batch correction: the amounts of `colorants` (a list of `(S, K)`, 81 values each) that bring
/// a batch made to `recipe` and measured as `batch` (81 reflectances) back to `standard`; opaque,
/// or as a layer of `thickness_mm` over `skin` when both are given. Returns a dict:
/// `concentrations`, `change`, `delta_E_before`, `delta_E_predicted` (CIEDE2000).
#[pyfunction]
#[pyo3(name = "correct_batch_KubelkaMunk", signature = (colorants, recipe, batch, standard, *, skin=None, thickness_mm=None,
    illuminant="D65", observer="CIE 1931 2 Degree Standard Observer"))]
#[allow(clippy::too_many_arguments)]
pub fn correct_batch_kubelka_munk<'py>(
    py: Python<'py>,
    colorants: Vec<(Vec<f64>, Vec<f64>)>,
    recipe: Vec<f64>,
    batch: Vec<f64>,
    standard: Vec<f64>,
    skin: Option<Vec<f64>>,
    thickness_mm: Option<f64>,
    illuminant: &str,
    observer: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let layers = colorants
        .into_iter()
        .enumerate()
        .map(|(i, (s, k))| {
            let what = format!("colorant {i}");
            Layer::new(&what, spectrum(&format!("{what} S"), s)?, spectrum(&format!("{what} K"), k)?)
                .map_err(|e| crate::errors::RougeError::new_err(e.to_string()))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let presentation = match (skin, thickness_mm) {
        (None, None) => Presentation::Opaque,
        (Some(r), Some(x)) => Presentation::Over { background: Box::new(spectrum("skin", r)?), thickness_mm: x },
        _ => return Err(PyValueError::new_err("give both skin and thickness_mm, or neither (opaque)")),
    };
    let c = Colorimeter::get(viewing(illuminant, observer)?);
    let fix =
        correct_batch(&layers, &recipe, &spectrum("batch", batch)?, &spectrum("standard", standard)?, &presentation, c)
            .map_err(|e| crate::errors::RougeError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("concentrations", fix.concentrations)?;
    d.set_item("change", fix.change)?;
    d.set_item("delta_E_before", fix.delta_e_before)?;
    d.set_item("delta_E_predicted", fix.delta_e_predicted)?;
    Ok(d)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(correct_batch_kubelka_munk, m)?)?;
    m.add("ILL_CONDITIONED_ABOVE", ILL_CONDITIONED)?;
    m.add_function(wrap_pyfunction!(metamerism_index_special, m)?)?;
    m.add_function(wrap_pyfunction!(sk_uncertainty, m)?)?;
    m.add_function(wrap_pyfunction!(sk_thickness_optimal, m)?)?;
    Ok(())
}
