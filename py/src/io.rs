//! Measurements and presets for Python: every format `rouge import` reads, and the preset JSON
//! schema (`rouge-preset` v1) read and written by the same code as the CLI.

use crate::arrays::as_f64_array;
use crate::errors::{import_error, preset_error};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rouge_measure::import::{self, ImportOptions, Kind, Measurement, SampleNames};
use rouge_measure::km::Saunderson;
use rouge_measure::km_uncertainty::{DEFAULT_U_THICKNESS_MM, InstrumentClass};
use rouge_measure::preset::{Preset, PresetError};
use rouge_measure::spectrum::{Extrapolation, SampledSpectrum, Spectrum, WORKING_LEN};
use std::path::{Path, PathBuf};

fn json_to_py<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

fn array<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// R∞, R and Rg of a cosmetic on the file's own wavelength grid, as fractions, with what the
/// file said about it (`read_measurement`).
#[pyclass(name = "Measurement", module = "rouge", frozen)]
#[derive(Debug)]
pub struct PyMeasurement {
    inner: Measurement,
}

#[pymethods]
impl PyMeasurement {
    /// The file it was read from.
    #[getter]
    fn path(&self) -> String {
        self.inner.source.display().to_string()
    }
    /// The file format, in words (`Rouge CSV`, `CGATS (CGATS.17)`, `CS-2000 radiance`, ...).
    #[getter]
    fn format(&self) -> &str {
        &self.inner.format
    }
    /// The name (from the file, or its stem).
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }
    /// The cosmetic kind the file gives (`foundation`, `blush`, ...), or None.
    #[getter]
    fn kind(&self) -> Option<&'static str> {
        self.inner.kind.map(Kind::name)
    }
    /// Thickness of the thin layer R was measured on, mm, if the file gives it.
    #[getter]
    fn thickness_mm(&self) -> Option<f64> {
        self.inner.thickness_mm
    }
    /// The instrument, if the file names it.
    #[getter]
    fn instrument(&self) -> Option<&str> {
        self.inner.instrument.as_deref()
    }
    /// Every `key: value` the file carried (Rouge CSV comments, CGATS keywords).
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in &self.inner.metadata {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
    /// How the file's numbers were read (fractions or percent, declared or detected).
    #[getter]
    fn scale(&self) -> String {
        self.inner.scale.to_string()
    }
    /// Wavelengths, nm.
    #[getter]
    fn wavelengths<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.inner.r_inf.wavelengths_nm())
    }
    /// Reflectance of the opaque layer R∞ (fractions).
    #[getter]
    #[allow(non_snake_case)]
    fn R_inf<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.inner.r_inf.values())
    }
    /// Reflectance R of the thin layer over the background (fractions).
    #[getter]
    #[allow(non_snake_case)]
    fn R<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.inner.r.values())
    }
    /// Reflectance Rg of the background (fractions).
    #[getter]
    #[allow(non_snake_case)]
    fn R_g<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.inner.rg.values())
    }

    /// The same measurement resampled onto 380-780 nm every 5 nm, as `rouge import` does before
    /// inverting (Sprague for uniform grids, linear otherwise; `extrapolate` holds the end
    /// values where the file does not cover the range).
    #[pyo3(signature = (extrapolate=false))]
    fn to_working_grid(&self, py: Python<'_>, extrapolate: bool) -> PyResult<PyMeasurement> {
        let w = self.inner.to_working_grid(extrapolation(extrapolate)).map_err(|e| import_error(py, e))?;
        let grid = rouge_measure::spectrum::working_wavelengths_nm().to_vec();
        let s = |x: &Spectrum| SampledSpectrum::new(grid.clone(), x.0.to_vec());
        let spectra = (s(&w.r_inf), s(&w.r), s(&w.rg));
        let (Ok(r_inf), Ok(r), Ok(rg)) = spectra else {
            return Err(PyValueError::new_err("internal: the working grid is not a valid grid"));
        };
        Ok(PyMeasurement { inner: Measurement { r_inf, r, rg, ..self.inner.clone() } })
    }

    fn __repr__(&self) -> String {
        let w = self.inner.r_inf.wavelengths_nm();
        let t = self.inner.thickness_mm.map_or_else(|| "None".to_string(), |t| t.to_string());
        format!(
            "Measurement(name={:?}, format={:?}, {}-{} nm, {} samples, thickness_mm={t})",
            self.inner.name,
            self.inner.format,
            w[0],
            w[w.len() - 1],
            w.len(),
        )
    }
}

fn extrapolation(extrapolate: bool) -> Extrapolation {
    if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse }
}

/// Reads a measurement file of any format `rouge import` reads, recognised from its content:
/// Rouge CSV, CGATS / X-Rite / i1Profiler / ArgyllCMS .ti3, or a CS-2000 radiance export
/// (reflectance from the sample's and the white standard's radiance, [Huang2013] eq. 8).
///
/// `samples`: the names of R∞, R and Rg in multi-sample files (default `("R_INF", "R", "RG")`).
/// `white_reflectance`: the white standard's reflectance for radiance files, a number in (0, 1]
/// or a pair `(wavelengths_nm, values)` (default: the file's, else 0.99, BaSO4).
/// Raises `MeasurementImportError` naming the file, line and column.
#[pyfunction]
#[pyo3(signature = (path, *, samples=None, white_reflectance=None))]
pub fn read_measurement(
    py: Python<'_>,
    path: PathBuf,
    samples: Option<(String, String, String)>,
    white_reflectance: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyMeasurement> {
    let samples = samples.map_or_else(SampleNames::default, |(r_inf, r, rg)| SampleNames { r_inf, r, rg });
    let white_reflectance = match white_reflectance {
        None => None,
        Some(w) => Some(white(w)?),
    };
    let options = ImportOptions { samples, white_reflectance };
    let inner = py.detach(|| import::read_measurement(&path, &options)).map_err(|e| import_error(py, e))?;
    Ok(PyMeasurement { inner })
}

fn white(w: &Bound<'_, PyAny>) -> PyResult<SampledSpectrum> {
    let bad = |m: String| PyValueError::new_err(format!("white_reflectance: {m}"));
    let (wl, v) = if let Ok(rho) = w.extract::<f64>() {
        (vec![380.0, 780.0], vec![rho, rho])
    } else {
        let (a, b): (Bound<'_, PyAny>, Bound<'_, PyAny>) = w.extract()?;
        let vec = |x: &Bound<'_, PyAny>, n: &str| -> PyResult<Vec<f64>> {
            Ok(as_f64_array(n, x)?.readonly().as_array().iter().copied().collect())
        };
        (vec(&a, "wavelengths")?, vec(&b, "values")?)
    };
    if let Some((nm, x)) = import::radiance::white_out_of_range(&wl, &v) {
        return Err(bad(format!("{x} at {nm} nm must be in (0, 1]")));
    }
    SampledSpectrum::new(wl, v).map_err(|e| bad(e.to_string()))
}

/// A measurement from three single-spectrum files (R∞, R, Rg), such as ArgyllCMS `.sp` files
/// (as `rouge import --r-inf A --r B --rg C`).
#[pyfunction]
#[pyo3(signature = (R_inf, R, R_g))]
#[allow(non_snake_case)]
pub fn read_measurement_files(py: Python<'_>, R_inf: PathBuf, R: PathBuf, R_g: PathBuf) -> PyResult<PyMeasurement> {
    let inner = import::read_measurement_files(&R_inf, &R, &R_g).map_err(|e| import_error(py, e))?;
    Ok(PyMeasurement { inner })
}

/// Wavelengths, values (samples × wavelengths) and sample names.
type SpectraTable<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>, Vec<String>);

/// A table of spectra or a CGATS file (what `rouge color` reads): a table in either layout
/// colour-science uses, a `wavelength_nm` or `wavelength` column and one column per sample, or
/// one spectrum per row with the wavelengths in the header (`wavelength,380,385,...`), commas
/// or tabs; or CGATS text (X-Rite, i1Profiler, ArgyllCMS), one spectrum per sample. Returns
/// `(wavelengths, values, names)` with `values` of shape `(samples, wavelengths)` as fractions.
#[pyfunction]
pub fn read_spectra<'py>(py: Python<'py>, path: PathBuf) -> PyResult<SpectraTable<'py>> {
    let spectra = py.detach(|| import::read_spectra(&path)).map_err(|e| import_error(py, e))?.samples;
    let wl = spectra.first().map_or(&[][..], |(_, s)| s.wavelengths_nm());
    let rows: Vec<Vec<f64>> = spectra.iter().map(|(_, s)| s.values().to_vec()).collect();
    let values = PyArray2::from_vec2(py, &rows).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((array(py, wl), values, spectra.iter().map(|(n, _)| n.clone()).collect()))
}

/// A material preset (`rouge-preset` JSON v1, the file `rouge import --out` writes): S and K per
/// wavelength on 380-780 nm / 5 nm, the measurement they came from, specular parameters and
/// the renderer's R0(X)/T(X) tables.
#[pyclass(name = "Preset", module = "rouge", frozen)]
#[derive(Debug)]
pub struct PyPreset {
    inner: Preset,
}

fn spectrum(py: Python<'_>, name: &str, x: &Bound<'_, PyAny>) -> PyResult<Spectrum> {
    let v: Vec<f64> = as_f64_array(name, x)?.readonly().as_array().iter().copied().collect();
    let grid = rouge_measure::spectrum::working_wavelengths_nm();
    if v.len() != WORKING_LEN {
        return Err(PyValueError::new_err(format!(
            "{name} has {} values; a preset holds {WORKING_LEN}, 380-780 nm every 5 nm",
            v.len()
        )));
    }
    if let Some((nm, x)) = grid.iter().zip(&v).find(|(_, x)| !(x.is_finite() && **x >= 0.0)) {
        let message = format!("{name} = {x} at {nm} nm must be finite and ≥ 0");
        return Err(preset_error(py, PresetError::Invalid { path: "<preset>".into(), message }));
    }
    Ok(Spectrum(std::array::from_fn(|i| v[i])))
}

fn kind(name: Option<&str>) -> PyResult<Option<Kind>> {
    name.map(|k| {
        Kind::parse(k).ok_or_else(|| {
            PyValueError::new_err(format!("unknown kind `{k}` (foundation, blush, eyeshadow, lipstick, other)"))
        })
    })
    .transpose()
}

#[pymethods]
impl PyPreset {
    /// Reads a preset file; errors name the file, line and column (JSON) or the field and
    /// wavelength (values), as the CLI's.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyPreset> {
        Preset::load(&path).map(|inner| PyPreset { inner }).map_err(|e| preset_error(py, e))
    }

    /// Parses preset JSON text (`path` names it in errors).
    #[staticmethod]
    #[pyo3(signature = (text, path="<preset>"))]
    fn from_json(py: Python<'_>, text: &str, path: &str) -> PyResult<PyPreset> {
        Preset::from_json(text, path).map(|inner| PyPreset { inner }).map_err(|e| preset_error(py, e))
    }

    /// A preset from S and K (mm⁻¹, 81 values on 380-780 nm / 5 nm) and the thickness of the
    /// layer they describe; derived tables computed as `rouge import` computes them.
    #[staticmethod]
    #[pyo3(name = "from_SK", signature = (S, K, thickness_mm, name, kind="other"))]
    #[allow(non_snake_case)]
    fn from_sk(
        py: Python<'_>,
        S: &Bound<'_, PyAny>,
        K: &Bound<'_, PyAny>,
        thickness_mm: f64,
        name: &str,
        kind: &str,
    ) -> PyResult<PyPreset> {
        let (s, k) = (spectrum(py, "S", S)?, spectrum(py, "K", K)?);
        let kind = self::kind(Some(kind))?.unwrap_or(Kind::Other);
        let inner = Preset::from_s_k(name, kind, thickness_mm, &s, &k);
        inner.validate("<preset>").map_err(|e| preset_error(py, e))?;
        Ok(PyPreset { inner })
    }

    /// Inverts a measurement into a preset exactly as `rouge import` does and returns
    /// `(preset, report)`; the report (a dict) gives S and K ranges, the largest reconstruction
    /// errors and ΔE2000. `thickness_mm`, `name`, `kind` default to the file's; `saunderson`
    /// (a dict `{"n": 1.5, "K2": 0.6, "specular_included": True}`) corrects the surface first.
    /// The preset keeps the uncertainty of S and K as `rouge import` computes it: readings to
    /// `u_reflectance` (default the benchtop class's 0.001), thickness to `u_thickness_mm`.
    #[staticmethod]
    #[pyo3(signature = (measurement, *, thickness_mm=None, name=None, kind=None, saunderson=None, extrapolate=false,
        u_reflectance=None, u_thickness_mm=DEFAULT_U_THICKNESS_MM))]
    #[allow(clippy::too_many_arguments)]
    fn from_measurement<'py>(
        py: Python<'py>,
        measurement: &PyMeasurement,
        thickness_mm: Option<f64>,
        name: Option<&str>,
        kind: Option<&str>,
        saunderson: Option<&Bound<'py, PyDict>>,
        extrapolate: bool,
        u_reflectance: Option<f64>,
        u_thickness_mm: f64,
    ) -> PyResult<(PyPreset, Bound<'py, PyAny>)> {
        let m = &measurement.inner;
        let working = m.to_working_grid(extrapolation(extrapolate)).map_err(|e| import_error(py, e))?;
        let thickness_mm = thickness_mm.or(m.thickness_mm).ok_or_else(|| {
            let message = "the file gives no thickness: pass thickness_mm (the thickness of the thin layer R was \
                           measured on)";
            preset_error(py, PresetError::Invalid { path: m.source.display().to_string(), message: message.into() })
        })?;
        let kind = self::kind(kind)?.or(m.kind).unwrap_or(Kind::Other);
        let name = name.map_or_else(|| m.name.clone(), str::to_string);
        let saunderson = match saunderson {
            None => None,
            Some(d) => {
                let get = |k: &str| d.get_item(k);
                let n: f64 = get("n")?.map_or(Ok(1.5), |v| v.extract())?;
                let k2: f64 = get("K2")?.map_or(Ok(0.6), |v| v.extract())?;
                let spec: bool = get("specular_included")?.map_or(Ok(true), |v| v.extract())?;
                let c = Saunderson::from_refractive_index(n, k2, spec)
                    .map_err(|e| crate::errors::KubelkaMunkError::new_err(e.to_string()))?;
                Some(c)
            }
        };
        let (mut inner, report) = py
            .detach(|| Preset::from_measurement(m, &working, &name, kind, thickness_mm, saunderson))
            .map_err(|e| preset_error(py, e))?;
        let (u, source) = match u_reflectance {
            None => (InstrumentClass::Benchtop.u_reflectance(), InstrumentClass::Benchtop.source_text()),
            Some(u) => (u, format!("± {u} (u_reflectance)")),
        };
        inner
            .estimate_uncertainty(&source, &Spectrum::constant(u), u_thickness_mm, 0.0)
            .map_err(|e| preset_error(py, e))?;
        Ok((PyPreset { inner }, json_to_py(py, &report)?))
    }

    /// Writes the preset (atomically: a temporary file, then a rename), as `rouge import --out`.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        self.inner.save(Path::new(&path)).map_err(|e| preset_error(py, e))
    }

    /// The JSON text `save` writes.
    fn to_json(&self) -> String {
        self.inner.to_json()
    }

    /// The whole preset as a dict (the JSON document).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.inner)
    }

    /// Display name.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }
    /// Cosmetic kind.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind.name()
    }
    /// Thickness of the measured layer, mm.
    #[getter]
    fn thickness_mm(&self) -> f64 {
        self.inner.thickness_mm
    }
    /// Wavelengths, nm (380-780 every 5).
    #[getter]
    fn wavelengths<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.inner.wavelengths_nm)
    }
    /// Scattering S, mm⁻¹.
    #[getter]
    #[allow(non_snake_case)]
    fn S<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.inner.s_per_mm)
    }
    /// Absorption K, mm⁻¹.
    #[getter]
    #[allow(non_snake_case)]
    fn K<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.inner.k_per_mm)
    }
    /// Specular lobe parameters `{"roughness": ..., "ior": ...}`.
    #[getter]
    fn specular<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.inner.specular)
    }
    /// The source measurement (dict) or None.
    #[getter]
    fn measurement<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.inner.measurement)
    }
    /// Renderer tables derived from S and K (dict).
    #[getter]
    fn derived<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.inner.derived)
    }

    fn __eq__(&self, other: &PyPreset) -> bool {
        self.inner == other.inner
    }

    fn __repr__(&self) -> String {
        format!(
            "Preset(name={:?}, kind={:?}, thickness_mm={})",
            self.inner.name,
            self.inner.kind.name(),
            self.inner.thickness_mm
        )
    }
}

/// Registers the classes and functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMeasurement>()?;
    m.add_class::<PyPreset>()?;
    m.add_function(wrap_pyfunction!(read_measurement, m)?)?;
    m.add_function(wrap_pyfunction!(read_measurement_files, m)?)?;
    m.add_function(wrap_pyfunction!(read_spectra, m)?)?;
    Ok(())
}
