//! Finishes for Python (`rouge_measure::finish`, docs/FINISHES.md): the specular lobe, gloss
//! units at the ISO 2813 geometries, roughness from gloss readings, and the thin-film
//! reflectance of pearlescent pigments (`rouge_measure::thin_film`).

use pyo3::prelude::*;
use rouge_measure::finish::{GlossGeometry, GlossReading, fit_gloss, gloss_units};
use rouge_measure::preset::Specular;
use rouge_measure::specular::{fresnel_f0, kelemen};

fn value_err(message: String) -> PyErr {
    pyo3::exceptions::PyValueError::new_err(message)
}

fn geometry(angle_deg: f64) -> PyResult<GlossGeometry> {
    GlossGeometry::ALL
        .into_iter()
        .find(|g| g.incidence_deg() == angle_deg)
        .ok_or_else(|| value_err(format!("gloss angle {angle_deg}: a gloss meter reads at 20, 60 or 85 degrees")))
}

fn lobe(roughness: f64, ior: f64) -> PyResult<Specular> {
    if !(roughness > 0.0 && roughness <= 1.0 && (1.0..=3.0).contains(&ior)) {
        return Err(value_err(format!("roughness {roughness} must be in (0, 1] and ior {ior} in [1, 3]")));
    }
    Ok(Specular { roughness, ior })
}

/// The Kelemen/Szirmay-Kalos BRDF f_r (1/sr) of a surface of Beckmann `roughness` and index `ior`
/// for light from `wi` seen from `wo` (unit vectors in the surface's frame, z the normal): the lobe
/// of every Rouge layer and of the skin (`rouge_measure::specular::kelemen`).
#[pyfunction]
#[pyo3(name = "specular_BRDF_Kelemen")]
pub fn specular_brdf_kelemen(wi: [f64; 3], wo: [f64; 3], roughness: f64, ior: f64) -> PyResult<f64> {
    let s = lobe(roughness, ior)?;
    let (l, v) = (glam::DVec3::from(wi), glam::DVec3::from(wo));
    if !(l.is_finite() && v.is_finite()) || (l.length() - 1.0).abs() > 1e-6 || (v.length() - 1.0).abs() > 1e-6 {
        return Err(value_err("wi and wo must be finite unit vectors".into()));
    }
    Ok(kelemen(glam::DVec3::Z, l, v, s.roughness, fresnel_f0(s.ior)))
}

/// The gloss units a meter reads at `angle` (20, 60 or 85 degrees, ISO 2813) of a surface with
/// Rouge's lobe of `roughness` and `ior`.
#[pyfunction]
#[pyo3(name = "gloss_units_ISO2813")]
pub fn gloss_units_iso2813(roughness: f64, ior: f64, angle: f64) -> PyResult<f64> {
    Ok(gloss_units(lobe(roughness, ior)?, geometry(angle)?))
}

/// The roughness of Rouge's lobe fitted to gloss `readings` ({angle: GU}) at index `ior`: a dict
/// with `roughness`, `nearest_finish` and `fitted` ({angle: GU of the fitted lobe}).
#[pyfunction]
#[pyo3(name = "fit_gloss_ISO2813")]
pub fn fit_gloss_iso2813(
    py: Python<'_>,
    readings: std::collections::BTreeMap<i64, f64>,
    ior: f64,
) -> PyResult<Py<pyo3::types::PyDict>> {
    let readings: Vec<GlossReading> = readings
        .into_iter()
        .map(|(angle, gu)| Ok(GlossReading { geometry: geometry(angle as f64)?, gu }))
        .collect::<PyResult<_>>()?;
    let fit = fit_gloss(&readings, ior).map_err(value_err)?;
    let d = pyo3::types::PyDict::new(py);
    d.set_item("roughness", fit.specular.roughness)?;
    d.set_item("nearest_finish", fit.nearest_kind.name())?;
    let fitted = pyo3::types::PyDict::new(py);
    for (g, _, gu) in &fit.readings {
        fitted.set_item(g.incidence_deg() as i64, *gu)?;
    }
    d.set_item("fitted", fitted)?;
    Ok(d.unbind())
}

/// Unpolarised reflectance of a mica platelet coated with `film_nm` of rutile TiO₂ in a binder,
/// for light at `theta_deg` from the platelet's normal in the binder, at `wavelengths` (nm; default
/// the working grid 380-780 / 5 nm): `rouge_measure::thin_film` (Airy's formula; rutile after
/// DeVore 1951, `binder_index` and `core_index` constant).
#[pyfunction]
#[pyo3(name = "reflectance_thin_film_TiO2", signature = (film_nm, theta_deg, *, wavelengths=None, binder_index=1.5, core_index=1.58))]
pub fn reflectance_thin_film_tio2(
    film_nm: f64,
    theta_deg: f64,
    wavelengths: Option<Vec<f64>>,
    binder_index: f64,
    core_index: f64,
) -> PyResult<Vec<f64>> {
    if !(film_nm.is_finite() && film_nm >= 0.0 && (0.0..=90.0).contains(&theta_deg)) {
        return Err(value_err(format!("film_nm {film_nm} must be ≥ 0 and theta_deg {theta_deg} in [0, 90]")));
    }
    if !(binder_index >= 1.0 && core_index >= 1.0 && binder_index.is_finite() && core_index.is_finite()) {
        return Err(value_err("indices must be finite and ≥ 1".into()));
    }
    let wl = wavelengths.unwrap_or_else(|| (0..81).map(rouge_measure::spectrum::working_wavelength_nm).collect());
    if let Some(bad) = wl.iter().find(|w| !(**w >= 300.0 && **w <= 2000.0)) {
        return Err(value_err(format!("wavelength {bad} nm: outside 300-2000 nm")));
    }
    let p = rouge_measure::thin_film::CoatedPlatelet { film_nm, binder_index, core_index };
    Ok(wl.iter().map(|&nm| p.reflectance(nm, theta_deg.to_radians())).collect())
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(reflectance_thin_film_tio2, m)?)?;
    m.add_function(wrap_pyfunction!(specular_brdf_kelemen, m)?)?;
    m.add_function(wrap_pyfunction!(gloss_units_iso2813, m)?)?;
    m.add_function(wrap_pyfunction!(fit_gloss_iso2813, m)?)?;
    Ok(())
}
