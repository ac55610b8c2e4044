//! CIE colorimetry for Python on Rouge's working grid (380-780 nm every 5 nm): the
//! `rouge_measure::colorimetry` formulas over numpy arrays. Names and scales follow
//! colour-science: `sd_to_XYZ` gives Y = 100 for the perfect reflector; `XYZ_to_Lab` and
//! `XYZ_to_sRGB` take XYZ scaled to Y = 1 (divide by 100 first, as in colour-science).
#![allow(non_snake_case)]

use crate::arrays::{as_f64_array, broadcast, contiguous, finish, maybe_detach, output};
use crate::errors::spectrum_error;
use numpy::{PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rouge_measure::colorimetry::{Colorimeter, Illuminant, Observer, Viewing, Xyz, delta_e_2000_raw, xyz_to_lab_raw};
use rouge_measure::spectrum::{Extrapolation, SampledSpectrum, WORKING_LEN, working_wavelengths_nm};

/// The viewing named by colour-science's names (`"D65"`, `"CIE 1931 2 Degree Standard
/// Observer"`) or Rouge's short ones (`"1931"`, `"10"`).
pub fn viewing(illuminant: &str, observer: &str) -> PyResult<Viewing> {
    let il = Illuminant::parse(illuminant).ok_or_else(|| {
        let all: Vec<&str> = Illuminant::ALL.iter().map(|i| i.name()).collect();
        PyValueError::new_err(format!("unknown illuminant `{illuminant}` (one of {})", all.join(", ")))
    })?;
    let ob = if observer.contains("1931") {
        Some(Observer::Cie1931)
    } else if observer.contains("1964") {
        Some(Observer::Cie1964)
    } else {
        Observer::parse(observer)
    };
    let ob = ob.ok_or_else(|| {
        PyValueError::new_err(format!(
            "unknown observer `{observer}` (\"CIE 1931 2 Degree Standard Observer\" or \"CIE 1964 10 Degree \
             Standard Observer\", or 1931 / 1964)"
        ))
    })?;
    Ok(Viewing { illuminant: il, observer: ob })
}

fn shape_error(what: &str, shape: &[usize], want: usize) -> PyErr {
    PyValueError::new_err(format!("{what}: the last axis must have {want} entries, the shape is {shape:?}"))
}

/// Values on the working grid, the last axis 81 long: the input itself when it is already
/// there (no `wavelengths`, or exactly 380-780/5 nm), else resampled as `rouge import` does
/// (Sprague for uniform grids, linear otherwise; see `resample_to_working_grid`).
fn on_working_grid<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: Option<&Bound<'py, PyAny>>,
    extrapolate: bool,
) -> PyResult<numpy::PyReadonlyArrayDyn<'py, f64>> {
    let a = as_f64_array("values", values)?;
    let shape = a.shape().to_vec();
    let Some(w) = wavelengths else {
        if shape.last() != Some(&WORKING_LEN) {
            return Err(PyValueError::new_err(format!(
                "the last axis has {} samples: pass `wavelengths=` (nm) for spectra not on 380-780 nm every 5 nm",
                shape.last().copied().unwrap_or(0)
            )));
        }
        return contiguous(a, &shape);
    };
    let resampled = resample(py, w, a.as_any(), extrapolate)?;
    let shape = resampled.shape().to_vec();
    contiguous(resampled, &shape)
}

fn resample<'py>(
    py: Python<'py>,
    wavelengths: &Bound<'py, PyAny>,
    values: &Bound<'py, PyAny>,
    extrapolate: bool,
) -> PyResult<Bound<'py, numpy::PyArrayDyn<f64>>> {
    let w = as_f64_array("wavelengths", wavelengths)?;
    let wl: Vec<f64> = w.readonly().as_array().iter().copied().collect();
    if w.ndim() != 1 {
        return Err(PyValueError::new_err(format!("wavelengths must be 1-D, the shape is {:?}", w.shape())));
    }
    let a = as_f64_array("values", values)?;
    let shape = a.shape().to_vec();
    if shape.last() != Some(&wl.len()) {
        return Err(shape_error("values", &shape, wl.len()));
    }
    let src = contiguous(a, &shape)?;
    let mut out_shape = shape.clone();
    if let Some(l) = out_shape.last_mut() {
        *l = WORKING_LEN;
    }
    let out = output(py, &out_shape);
    let extrapolation = if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
    {
        let mut rw = out.readwrite();
        let dst = rw.as_slice_mut().map_err(|e| PyValueError::new_err(e.to_string()))?;
        let src = src.as_slice().map_err(|e| PyValueError::new_err(e.to_string()))?;
        for (row, (d, s)) in dst.chunks_exact_mut(WORKING_LEN).zip(src.chunks_exact(wl.len())).enumerate() {
            let r = SampledSpectrum::new(wl.clone(), s.to_vec())
                .and_then(|x| x.to_working_grid(extrapolation))
                .map_err(|e| spectrum_error(format!("spectrum {row}: {e}")))?;
            d.copy_from_slice(&r.spectrum.0);
        }
    }
    Ok(out)
}

/// Values sampled at `wavelengths` (nm, strictly increasing, the last axis of `values`) resampled
/// onto Rouge's working grid, 380-780 nm every 5 nm (81 samples), as `rouge import` does:
/// [Sprague1880] interpolation with the [CIE167] end extension for uniform grids, linear for
/// non-uniform ones. A grid not covering 380-780 nm raises `SpectrumError` unless `extrapolate`
/// (the end values held, CIE 15's constant extrapolation).
#[pyfunction]
#[pyo3(name = "resample_to_working_grid", signature = (wavelengths, values, *, extrapolate=false))]
pub fn resample_to_working_grid(
    py: Python<'_>,
    wavelengths: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    extrapolate: bool,
) -> PyResult<Py<PyAny>> {
    finish(resample(py, wavelengths, values, extrapolate)?)
}

/// The working grid, 380-780 nm every 5 nm.
#[pyfunction]
#[pyo3(name = "working_wavelengths")]
pub fn working_wavelengths(py: Python<'_>) -> Bound<'_, numpy::PyArray1<f64>> {
    numpy::PyArray1::from_slice(py, &working_wavelengths_nm())
}

/// CIE XYZ of reflectance (or transmittance) spectra, the last axis over wavelength, by
/// summation on 380-780 nm every 5 nm ([CIE15] §7.1):
///
///     X = k Σ x̄(λ) S(λ) R(λ),   k = 100 / Σ ȳ(λ) S(λ)
///
/// so the perfect reflector has Y = 100, as colour-science's
/// `sd_to_XYZ(sd, cmfs, illuminant, method="Integration", shape=SpectralShape(380, 780, 5))`.
/// Spectra on another grid need `wavelengths=` (resampled first, see `resample_to_working_grid`).
/// Returns an array of shape `(..., 3)`.
#[pyfunction]
#[pyo3(name = "sd_to_XYZ",
       signature = (R, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer", *, wavelengths=None, extrapolate=false))]
pub fn sd_to_xyz(
    py: Python<'_>,
    R: &Bound<'_, PyAny>,
    illuminant: &str,
    observer: &str,
    wavelengths: Option<&Bound<'_, PyAny>>,
    extrapolate: bool,
) -> PyResult<Py<PyAny>> {
    let c = Colorimeter::get(viewing(illuminant, observer)?);
    let values = on_working_grid(py, R, wavelengths, extrapolate)?;
    let mut shape = values.shape().to_vec();
    if let Some(l) = shape.last_mut() {
        *l = 3;
    }
    let out = output(py, &shape);
    {
        let src = values.as_slice().map_err(|e| PyValueError::new_err(e.to_string()))?;
        let (rows, _) = src.as_chunks::<WORKING_LEN>();
        let mut rw = out.readwrite();
        let dst = rw.as_slice_mut().map_err(|e| PyValueError::new_err(e.to_string()))?;
        let (xyz, _) = dst.as_chunks_mut::<3>();
        maybe_detach(py, src.len(), || c.xyz_many_rows(rows, xyz));
    }
    finish(out)
}

/// Applies `f` to every `[f64; 3]` of `x` (last axis 3).
fn map_triples(
    py: Python<'_>,
    name: &str,
    x: &Bound<'_, PyAny>,
    f: impl Fn([f64; 3]) -> [f64; 3] + Send + Sync,
) -> PyResult<Py<PyAny>> {
    let b = broadcast(&[(name, x)])?;
    if b.shape.last() != Some(&3) {
        return Err(shape_error(name, &b.shape, 3));
    }
    let out = output(py, &b.shape);
    {
        let (src, _) = b.slice(0)?.as_chunks::<3>();
        let mut rw = out.readwrite();
        let dst = rw.as_slice_mut().map_err(|e| PyValueError::new_err(e.to_string()))?;
        let (dst, _) = dst.as_chunks_mut::<3>();
        maybe_detach(py, b.len(), || dst.iter_mut().zip(src).for_each(|(d, s)| *d = f(*s)));
    }
    finish(out)
}

/// CIELAB of tristimulus values `XYZ` (scaled so the perfect reflector has Y = 1, i.e.
/// `sd_to_XYZ(...) / 100`) relative to the perfect reflector under the same illuminant and
/// observer ([CIE15] §8.2.1):
///
///     L* = 116 f(Y/Yn) − 16,  a* = 500 [f(X/Xn) − f(Y/Yn)],  b* = 200 [f(Y/Yn) − f(Z/Zn)],
///     f(t) = t^(1/3) for t > (24/116)³, else (841/108) t + 16/116
///
/// = colour-science's `XYZ_to_Lab(XYZ, illuminant=XYZ_to_xy(white))`.
#[pyfunction]
#[pyo3(name = "XYZ_to_Lab", signature = (XYZ, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer"))]
pub fn xyz_to_lab(py: Python<'_>, XYZ: &Bound<'_, PyAny>, illuminant: &str, observer: &str) -> PyResult<Py<PyAny>> {
    let white = Colorimeter::get(viewing(illuminant, observer)?).white().xyz;
    map_triples(py, "XYZ", XYZ, |x| xyz_to_lab_raw(x.map(|v| v * 100.0), white))
}

/// sRGB of tristimulus values `XYZ` (Y = 1 for the perfect reflector) seen under `illuminant`
/// ([IEC61966] matrix on XYZ; for illuminants other than D65, first a Bradford adaptation
/// [Lam1985] from the illuminant's white to D65). With `apply_cctf_encoding`, the sRGB transfer
/// function `1.055 L^(1/2.4) − 0.055` (`12.92 L` below 0.0031308), not clipped: as
/// colour-science's `XYZ_to_sRGB(XYZ, illuminant=xy, chromatic_adaptation_transform="Bradford")`.
#[pyfunction]
#[pyo3(name = "XYZ_to_sRGB",
       signature = (XYZ, illuminant="D65", observer="CIE 1931 2 Degree Standard Observer", apply_cctf_encoding=true))]
pub fn xyz_to_srgb(
    py: Python<'_>,
    XYZ: &Bound<'_, PyAny>,
    illuminant: &str,
    observer: &str,
    apply_cctf_encoding: bool,
) -> PyResult<Py<PyAny>> {
    let v = viewing(illuminant, observer)?;
    let c = Colorimeter::get(v);
    map_triples(py, "XYZ", XYZ, move |x| {
        let xyz = Xyz { xyz: x.map(|t| t * 100.0), viewing: v };
        if apply_cctf_encoding { c.srgb(&xyz) } else { c.srgb_linear(&xyz) }
    })
}

/// CIEDE2000 colour difference of two CIELAB arrays (last axis L*, a*, b*; broadcast)
/// ([CIE142], with the implementation notes of [Sharma2005]); as colour-science's
/// `delta_E(Lab_1, Lab_2, method="CIE 2000")`.
#[pyfunction]
#[pyo3(name = "delta_E_CIE2000")]
pub fn delta_e_cie2000(py: Python<'_>, Lab_1: &Bound<'_, PyAny>, Lab_2: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    let b = broadcast(&[("Lab_1", Lab_1), ("Lab_2", Lab_2)])?;
    if b.shape.last() != Some(&3) {
        return Err(shape_error("Lab_1, Lab_2", &b.shape, 3));
    }
    let out = output(py, &b.shape[..b.shape.len() - 1]);
    {
        let (l1, _) = b.slice(0)?.as_chunks::<3>();
        let (l2, _) = b.slice(1)?.as_chunks::<3>();
        let mut rw = out.readwrite();
        let dst = rw.as_slice_mut().map_err(|e| PyValueError::new_err(e.to_string()))?;
        maybe_detach(py, b.len(), || {
            for ((d, a), c) in dst.iter_mut().zip(l1).zip(l2) {
                *d = delta_e_2000_raw(*a, *c);
            }
        });
    }
    finish(out)
}

/// Registers the functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(resample_to_working_grid, m)?)?;
    m.add_function(wrap_pyfunction!(working_wavelengths, m)?)?;
    m.add_function(wrap_pyfunction!(sd_to_xyz, m)?)?;
    m.add_function(wrap_pyfunction!(xyz_to_lab, m)?)?;
    m.add_function(wrap_pyfunction!(xyz_to_srgb, m)?)?;
    m.add_function(wrap_pyfunction!(delta_e_cie2000, m)?)?;
    Ok(())
}
