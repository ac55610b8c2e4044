//! The formulator's bench for Python (docs/FORMULATION.md): metamerism indices
//! (`rouge_measure::analysis::metamerism`), recipe search (`analysis::recipe`), batch correction
//! (`analysis::correction`), QC tolerances (`analysis::qc`) and the uncertainty of S and K
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
use rouge_measure::analysis::qc::{AB_PLANE, Metric, judge, lightness_chroma_plane, tolerance_contour};
use rouge_measure::analysis::recipe::{Colorant, FixedRatio, RecipeSearch, WeightedViewing, search_recipes};
use rouge_measure::colorimetry::Colorimeter;
use rouge_measure::km_uncertainty::{ILL_CONDITIONED, InputUncertainty, optimal_thickness_mm, propagate_s_k};
use rouge_measure::spectrum::{Spectrum, WORKING_LEN};
use std::collections::HashMap;

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

fn rouge_err(e: impl std::fmt::Display) -> PyErr {
    crate::errors::RougeError::new_err(e.to_string())
}

/// Recipe search: the best recipes of `k` of `colorants` (a list of `(S, K)`, 81 values each,
/// named by `names`, default `"0"`, `"1"`, ...) for a `target` reflectance (81 values), opaque
/// or as a layer of `thickness_mm` over `skin`; per-colorant limits `min` / `max` and `cost` as
/// dicts by name, `fixed` pairs `(a, b, ratio)` with amount(a) = ratio × amount(b); ranked by
/// the weighted RMS of CIEDE2000 under `illuminants` (with `weights`) plus `cost_weight` × cost.
/// Returns a list (best first) of dicts: `names`, `amounts`, `objective`, `delta_E` (one per
/// illuminant), `metamerism_index` (CIEDE2000, additive correction, first illuminant to each
/// other, or to A), `cost`.
#[pyfunction]
#[pyo3(name = "recipe_search_KubelkaMunk", signature = (colorants, target, k, *, names=None, min=None, max=None,
    fixed=None, cost=None, illuminants=vec!["D65".to_string(), "A".to_string(), "FL11".to_string()], weights=None,
    observer="CIE 1931 2 Degree Standard Observer", skin=None, thickness_mm=None, cost_weight=0.0, top=10))]
#[allow(clippy::too_many_arguments)]
pub fn recipe_search_kubelka_munk<'py>(
    py: Python<'py>,
    colorants: Vec<(Vec<f64>, Vec<f64>)>,
    target: Vec<f64>,
    k: usize,
    names: Option<Vec<String>>,
    min: Option<HashMap<String, f64>>,
    max: Option<HashMap<String, f64>>,
    fixed: Option<Vec<(String, String, f64)>>,
    cost: Option<HashMap<String, f64>>,
    illuminants: Vec<String>,
    weights: Option<Vec<f64>>,
    observer: &str,
    skin: Option<Vec<f64>>,
    thickness_mm: Option<f64>,
    cost_weight: f64,
    top: usize,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let names = names.unwrap_or_else(|| (0..colorants.len()).map(|i| i.to_string()).collect());
    if names.len() != colorants.len() {
        return Err(PyValueError::new_err(format!("{} names for {} colorants", names.len(), colorants.len())));
    }
    let mut library = colorants
        .into_iter()
        .zip(&names)
        .map(|((s, k), name)| {
            let layer = Layer::new(
                name,
                spectrum(&format!("colorant `{name}` S"), s)?,
                spectrum(&format!("colorant `{name}` K"), k)?,
            )
            .map_err(rouge_err)?;
            Ok(Colorant::new(layer))
        })
        .collect::<PyResult<Vec<_>>>()?;
    for (what, map) in [("min", &min), ("max", &max), ("cost", &cost)] {
        for (name, v) in map.iter().flatten() {
            let c = library
                .iter_mut()
                .find(|c| &c.layer.name == name)
                .ok_or_else(|| PyValueError::new_err(format!("{what}: no colorant named `{name}`")))?;
            match what {
                "min" => c.min = *v,
                "max" => c.max = *v,
                _ => c.cost_per_unit = *v,
            }
        }
    }
    let weights = weights.unwrap_or_else(|| vec![1.0; illuminants.len()]);
    if weights.len() != illuminants.len() {
        return Err(PyValueError::new_err(format!("{} weights for {} illuminants", weights.len(), illuminants.len())));
    }
    let viewings = illuminants
        .iter()
        .zip(weights)
        .map(|(il, weight)| Ok(WeightedViewing { viewing: viewing(il, observer)?, weight }))
        .collect::<PyResult<Vec<_>>>()?;
    let presentation = match (skin, thickness_mm) {
        (None, None) => Presentation::Opaque,
        (Some(r), Some(x)) => Presentation::Over { background: Box::new(spectrum("skin", r)?), thickness_mm: x },
        _ => return Err(PyValueError::new_err("give both skin and thickness_mm, or neither (opaque)")),
    };
    let search = RecipeSearch {
        colorants: library,
        fixed: fixed.unwrap_or_default().into_iter().map(|(a, b, ratio)| FixedRatio { a, b, ratio }).collect(),
        k,
        viewings,
        presentation,
        cost_weight,
    };
    let report = search_recipes(&search, &spectrum("target", target)?, top).map_err(rouge_err)?;
    report
        .recipes
        .iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("names", r.names.clone())?;
            d.set_item("amounts", r.amounts.clone())?;
            d.set_item("objective", r.objective)?;
            d.set_item("delta_E", r.delta_e.clone())?;
            d.set_item("metamerism_index", r.metamerism.iter().map(|m| m.delta_e_2000).collect::<Vec<_>>())?;
            d.set_item("cost", r.cost)?;
            Ok(d)
        })
        .collect()
}

/// The colour-difference formula named as colour-science's `delta_E` methods: `"CIE 2000"`,
/// `"CMC"` (with `l`, `c`) or `"CIE 1976"`.
fn metric(method: &str, l: f64, c: f64) -> PyResult<Metric> {
    match method {
        "CIE 2000" => Ok(Metric::De2000),
        "CMC" => Ok(Metric::Cmc { l, c }),
        "CIE 1976" => Ok(Metric::Ab),
        other => Err(PyValueError::new_err(format!("method `{other}`: one of \"CIE 2000\", \"CMC\", \"CIE 1976\""))),
    }
}

fn lab3(what: &str, v: Vec<f64>) -> PyResult<[f64; 3]> {
    <[f64; 3]>::try_from(v.as_slice())
        .map_err(|_| PyValueError::new_err(format!("{what}: {} values, expected L*, a*, b*", v.len())))
}

/// Pass/fail of `Lab_sample` against `Lab_standard` at `tolerance` in `method` (colour-science's
/// `delta_E` names: `"CIE 2000"`, `"CMC"` with `l:c`, `"CIE 1976"`), and the 555 shade number
/// with blocks `block` (ΔL*, Δa*, Δb*; default the tolerance). Returns a dict: `delta_E`,
/// `pass`, `delta_Lab`, `shade_555`.
#[pyfunction]
#[pyo3(signature = (Lab_standard, Lab_sample, tolerance, *, method="CIE 2000", l=2.0, c=1.0, block=None))]
#[allow(clippy::too_many_arguments)]
pub fn qc_pass_fail<'py>(
    py: Python<'py>,
    Lab_standard: Vec<f64>,
    Lab_sample: Vec<f64>,
    tolerance: f64,
    method: &str,
    l: f64,
    c: f64,
    block: Option<(f64, f64, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let block = block.map_or([tolerance; 3], |(a, b, d)| [a, b, d]);
    let j = judge(
        lab3("Lab_standard", Lab_standard)?,
        lab3("Lab_sample", Lab_sample)?,
        metric(method, l, c)?,
        tolerance,
        block,
    )
    .map_err(rouge_err)?;
    let d = PyDict::new(py);
    d.set_item("delta_E", j.delta_e)?;
    d.set_item("pass", j.pass)?;
    d.set_item("delta_Lab", j.delta_lab.to_vec())?;
    d.set_item("shade_555", j.shade)?;
    Ok(d)
}

/// The tolerance contour of `method` at `tolerance` around `Lab_standard`: `points` CIELAB
/// colours where the difference equals the tolerance, in the a*b* plane through the standard
/// (`plane="ab"`) or its lightness-chroma plane (`plane="LC"`), traced numerically per angle
/// (`rouge qc --png` draws them). Returns a list of `[L*, a*, b*]`.
#[pyfunction]
#[pyo3(signature = (Lab_standard, tolerance, *, method="CIE 2000", l=2.0, c=1.0, plane="ab", points=72))]
#[allow(clippy::too_many_arguments)]
pub fn qc_tolerance_contour(
    Lab_standard: Vec<f64>,
    tolerance: f64,
    method: &str,
    l: f64,
    c: f64,
    plane: &str,
    points: usize,
) -> PyResult<Vec<[f64; 3]>> {
    let std = lab3("Lab_standard", Lab_standard)?;
    let plane = match plane {
        "ab" => AB_PLANE,
        "LC" => lightness_chroma_plane(std),
        other => return Err(PyValueError::new_err(format!("plane `{other}`: \"ab\" or \"LC\""))),
    };
    tolerance_contour(metric(method, l, c)?, std, tolerance, plane, points).map_err(rouge_err)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(correct_batch_kubelka_munk, m)?)?;
    m.add("ILL_CONDITIONED_ABOVE", ILL_CONDITIONED)?;
    m.add_function(wrap_pyfunction!(metamerism_index_special, m)?)?;
    m.add_function(wrap_pyfunction!(sk_uncertainty, m)?)?;
    m.add_function(wrap_pyfunction!(sk_thickness_optimal, m)?)?;
    m.add_function(wrap_pyfunction!(recipe_search_kubelka_munk, m)?)?;
    m.add_function(wrap_pyfunction!(qc_pass_fail, m)?)?;
    m.add_function(wrap_pyfunction!(qc_tolerance_contour, m)?)?;
    Ok(())
}
