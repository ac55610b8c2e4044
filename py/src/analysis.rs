//! The formulation analyses of `rouge_measure::analysis` for Python (docs/FORMULATION.md):
//! coverage (contrast ratio, hiding thickness, ΔE2000 on skin), shade matching over skins, and
//! mixing bases by Duncan's rule. Spectra are on the working grid (81 values, 380-780 nm / 5 nm;
//! `resample_to_working_grid` puts others there); thickness in mm; results as dicts of floats.

use crate::color::viewing;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rouge_measure::analysis::coverage::{self, ContrastChart, HIDING_CONTRAST_RATIO};
use rouge_measure::analysis::matching::{self, Target};
use rouge_measure::analysis::mixing::{self, MixTarget};
use rouge_measure::analysis::{AnalysisError, Layer};
use rouge_measure::colorimetry::Colorimeter;
use rouge_measure::spectrum::{Spectrum, WORKING_LEN};

fn err(e: AnalysisError) -> PyErr {
    crate::errors::RougeError::new_err(e.to_string())
}

fn spectrum(what: &str, values: Vec<f64>) -> PyResult<Spectrum> {
    Spectrum::from_slice(&values).map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: {} values; give the {WORKING_LEN} of the working grid 380-780 nm / 5 nm (resample_to_working_grid)",
            values.len()
        ))
    })
}

fn layer(what: &str, s: Vec<f64>, k: Vec<f64>) -> PyResult<Layer> {
    Layer::new(what, spectrum(&format!("{what} S"), s)?, spectrum(&format!("{what} K"), k)?).map_err(err)
}

fn skins(values: Option<Vec<Vec<f64>>>) -> PyResult<Vec<(String, Spectrum)>> {
    values
        .unwrap_or_default()
        .into_iter()
        .enumerate()
        .map(|(i, r)| Ok((format!("skin {i}"), spectrum(&format!("skin {i}"), r)?)))
        .collect()
}

/// Coverage of a layer of scattering `S` and absorption `K` (mm⁻¹, 81 values each) at each of
/// `thickness_mm`: the contrast ratio Y over black / Y over white on a chart of reflectances
/// `black`, `white` ([ISO6504-3]), and the CIEDE2000 between each bare skin of `skins` (rows of
/// 81 reflectances) and the same skin under the layer. Returns a dict: `thickness_mm`,
/// `contrast_ratio`, `Y_black`, `Y_white` (lists), `delta_E_skin` (per thickness, per skin),
/// `hiding_thickness_mm` (contrast ratio 0.98, None if never reached).
#[pyfunction]
#[pyo3(name = "SK_to_coverage", signature = (S, K, thickness_mm, *, skins=None, black=0.01, white=0.80, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer"))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn sk_to_coverage<'py>(
    py: Python<'py>,
    S: Vec<f64>,
    K: Vec<f64>,
    thickness_mm: Vec<f64>,
    skins: Option<Vec<Vec<f64>>>,
    black: f64,
    white: f64,
    illuminant: &str,
    observer: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let l = layer("layer", S, K)?;
    let skins = self::skins(skins)?;
    let c = Colorimeter::get(viewing(illuminant, observer)?);
    let chart = ContrastChart::new(black, white).map_err(err)?;
    let rows = coverage::coverage_table(&l, &thickness_mm, chart, &skins, c).map_err(err)?;
    let hiding = coverage::hiding_thickness_mm(&l, chart, c, HIDING_CONTRAST_RATIO).map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("thickness_mm", thickness_mm)?;
    d.set_item("contrast_ratio", rows.iter().map(|r| r.contrast.contrast_ratio).collect::<Vec<_>>())?;
    d.set_item("Y_black", rows.iter().map(|r| r.contrast.y_black).collect::<Vec<_>>())?;
    d.set_item("Y_white", rows.iter().map(|r| r.contrast.y_white).collect::<Vec<_>>())?;
    d.set_item("delta_E_skin", rows.iter().map(|r| r.delta_e_on_skin.clone()).collect::<Vec<_>>())?;
    d.set_item("hiding_thickness_mm", hiding)?;
    Ok(d)
}

/// For each skin of `skins` (rows of 81 reflectances), the shade of `shades` (a list of `(S, K)`)
/// and thickness in `thickness_mm = (min, max)` whose covered skin is closest in CIEDE2000 to
/// `target_Lab` (None: the bare skin itself, "your shade"). A skin whose best ΔE2000 exceeds
/// `gap_delta_E` is in a gap of the line. Returns one dict per skin: `shade` (index),
/// `thickness_mm`, `delta_E`, `Lab` (covered), `skin_Lab`, `gap`.
#[pyfunction]
#[pyo3(name = "match_shades", signature = (shades, skins, thickness_mm, *, target_Lab=None, gap_delta_E=2.0, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer"))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn match_shades<'py>(
    py: Python<'py>,
    shades: Vec<(Vec<f64>, Vec<f64>)>,
    skins: Vec<Vec<f64>>,
    thickness_mm: (f64, f64),
    target_Lab: Option<[f64; 3]>,
    gap_delta_E: f64,
    illuminant: &str,
    observer: &str,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let shades = shades
        .into_iter()
        .enumerate()
        .map(|(i, (s, k))| layer(&format!("shade {i}"), s, k))
        .collect::<PyResult<Vec<_>>>()?;
    let skins = self::skins(Some(skins))?;
    let c = Colorimeter::get(viewing(illuminant, observer)?);
    let target = target_Lab.map_or(Target::BareSkin, Target::Lab);
    let cover = matching::product_line_coverage(&shades, &skins, target, thickness_mm, gap_delta_E, c).map_err(err)?;
    cover
        .iter()
        .map(|sc| {
            let d = PyDict::new(py);
            d.set_item("shade", sc.best.shade)?;
            d.set_item("thickness_mm", sc.best.thickness_mm)?;
            d.set_item("delta_E", sc.best.delta_e)?;
            d.set_item("Lab", sc.best.lab)?;
            d.set_item("skin_Lab", sc.skin_lab)?;
            d.set_item("gap", sc.gap)?;
            Ok(d)
        })
        .collect()
}

/// Concentrations (≥ 0, summing to 1) of 2-4 `bases` (a list of `(S, K)`) whose Duncan mixture
/// ([Duncan1940]) comes closest in CIEDE2000 to `target_Lab`: as R∞ (an opaque layer), or, with
/// `skin` (81 reflectances) and `thickness_mm`, as that skin under the mixture. Returns a dict:
/// `concentrations`, `delta_E`, `Lab` (the mixture's), `S`, `K` (the mixture's).
#[pyfunction]
#[pyo3(name = "fit_mix_Duncan", signature = (bases, target_Lab, *, skin=None, thickness_mm=None, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer"))]
#[allow(non_snake_case)]
pub fn fit_mix_duncan<'py>(
    py: Python<'py>,
    bases: Vec<(Vec<f64>, Vec<f64>)>,
    target_Lab: [f64; 3],
    skin: Option<Vec<f64>>,
    thickness_mm: Option<f64>,
    illuminant: &str,
    observer: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let bases = bases
        .into_iter()
        .enumerate()
        .map(|(i, (s, k))| layer(&format!("base {i}"), s, k))
        .collect::<PyResult<Vec<_>>>()?;
    let c = Colorimeter::get(viewing(illuminant, observer)?);
    let target = match (skin, thickness_mm) {
        (None, None) => MixTarget::RInf(target_Lab),
        (Some(r), Some(x)) => {
            MixTarget::Covered { skin: Box::new(spectrum("skin", r)?), thickness_mm: x, lab: target_Lab }
        }
        _ => return Err(PyValueError::new_err("give both skin and thickness_mm, or neither (match R∞)")),
    };
    let fit = mixing::fit_mix(&bases, &target, c).map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("concentrations", fit.concentrations)?;
    d.set_item("delta_E", fit.delta_e)?;
    d.set_item("Lab", fit.lab)?;
    d.set_item("S", fit.mixture.s.0.to_vec())?;
    d.set_item("K", fit.mixture.k.0.to_vec())?;
    Ok(d)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sk_to_coverage, m)?)?;
    m.add_function(wrap_pyfunction!(match_shades, m)?)?;
    m.add_function(wrap_pyfunction!(fit_mix_duncan, m)?)?;
    Ok(())
}
