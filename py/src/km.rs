//! Kubelka-Munk for Python: the formulas of `rouge_measure::km` (scalar) and `km_batch` (SIMD),
//! over broadcast numpy arrays. Names follow colour-science: `X_to_Y_Method`.
#![allow(non_snake_case)]

use crate::arrays::{AtIndex, as_f64_array, broadcast, contiguous, map_arrays, map_broadcast, wavelengths_vec};
use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rouge_measure::km::{self, KmCoefficients, KmError, LayerRt, Saunderson};
use rouge_measure::km_batch::{self, BatchError};

fn batch_error(e: BatchError) -> AtIndex<KmError> {
    match e {
        BatchError::Sample { index, error } => (index, error),
        // The slices are built with one length; a mismatch cannot reach Python.
        BatchError::LengthMismatch(_) => (0, KmError::BadCoefficient { name: "length", value: f64::NAN }),
    }
}

/// Kubelka-Munk S and K (mm⁻¹) from the reflectance `R_inf` of an opaque layer, the reflectance
/// `R` of a layer `thickness_mm` thick over a background, and the background's reflectance `R_g`
/// (reflectances as fractions). Arrays broadcast; returns `(S, K)`.
///
/// [Huang2013] eq. 6-7 ([Kubelka1948]), rewritten so it holds on both sides of R∞:
///
///     S·D = R∞ · ln(1 + z)/z · (Rg − R) / ((1 − Rg·R∞)(R − R∞)),
///     z   = (Rg − R)(1 − R∞²) / ((1 − Rg·R∞)(R − R∞)),
///     K   = S (1 − R∞)² / (2 R∞)
///
/// (the printed `S = [coth⁻¹((a−R)/b) − coth⁻¹((a−Rg)/b)]/(bD)` with `a = (1/R∞ + R∞)/2`,
/// `b = (1/R∞ − R∞)/2` is undefined for a background lighter than the layer and cancels for thin
/// layers; see `measure/src/km.rs`). Domain: `0 < R∞ ≤ 1`, R between Rg and R∞, `D > 0`.
/// `wavelengths` (nm), if given, label the last axis so errors name the wavelength.
///
/// Raises `KubelkaMunkError` (a `ValueError`) at the first element without a solution.
#[pyfunction]
#[pyo3(name = "R_to_SK_KubelkaMunk", signature = (R_inf, R, R_g, thickness_mm, *, wavelengths=None))]
pub fn r_to_sk(
    py: Python<'_>,
    R_inf: &Bound<'_, PyAny>,
    R: &Bound<'_, PyAny>,
    R_g: &Bound<'_, PyAny>,
    thickness_mm: &Bound<'_, PyAny>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let inputs = [("R_inf", R_inf), ("R", R), ("R_g", R_g), ("thickness_mm", thickness_mm)];
    let [s, k] = map_arrays(py, &inputs, wavelengths, |i, o| {
        let [s_out, k_out] = o else { unreachable!() };
        km_batch::invert_batch(i[0], i[1], i[2], i[3], s_out, k_out).map_err(batch_error)
    })?;
    Ok((s, k))
}

/// Reflectance over black `R0` and transmittance `T` of a layer with scattering `S` and
/// absorption `K` (mm⁻¹), `thickness_mm` thick. Returns `(R0, T)`.
///
/// [Huang2013] eq. 1-2 ([Kubelka1948]), divided through by cosh so nothing overflows:
/// with `β = √(K(K + 2S))`, `q = tanh(βX)/β` (→ X as β → 0), `w = (S + K) q`:
///
///     R0 = S q / (1 + w),     T = sech(βX) / (1 + w)
///
/// Domain: S, K ≥ 0 and finite, X ≥ 0 (X = inf gives the opaque layer: R0 = R∞, T = 0).
#[pyfunction]
#[pyo3(name = "SK_to_R0T_KubelkaMunk", signature = (S, K, thickness_mm, *, wavelengths=None))]
pub fn sk_to_r0t(
    py: Python<'_>,
    S: &Bound<'_, PyAny>,
    K: &Bound<'_, PyAny>,
    thickness_mm: &Bound<'_, PyAny>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let [r0, t] = map_arrays(py, &[("S", S), ("K", K), ("thickness_mm", thickness_mm)], wavelengths, |i, o| {
        let [r_out, t_out] = o else { unreachable!() };
        km_batch::layer_batch(i[0], i[1], i[2], r_out, t_out).map_err(batch_error)
    })?;
    Ok((r0, t))
}

/// Reflectance `R` of a layer (S, K in mm⁻¹, `thickness_mm`) over an opaque background of
/// reflectance `R_g`: the layer's R0 and T ([Huang2013] eq. 1-2) composed with the background
/// ([Huang2013] eq. 3, corrected numerator, [Kubelka1954]):
///
///     R = R0 + T² Rg / (1 − R0 Rg)
#[pyfunction]
#[pyo3(name = "SK_to_R_KubelkaMunk", signature = (S, K, thickness_mm, R_g, *, wavelengths=None))]
pub fn sk_to_r(
    py: Python<'_>,
    S: &Bound<'_, PyAny>,
    K: &Bound<'_, PyAny>,
    thickness_mm: &Bound<'_, PyAny>,
    R_g: &Bound<'_, PyAny>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    let inputs = [("S", S), ("K", K), ("thickness_mm", thickness_mm), ("R_g", R_g)];
    let [r] = map_arrays(py, &inputs, wavelengths, |i, o| {
        let [r_out] = o else { unreachable!() };
        let mut t = vec![0.0; r_out.len()];
        km_batch::layer_batch(i[0], i[1], i[2], r_out, &mut t).map_err(batch_error)?;
        for (j, (r, &rg)) in r_out.iter_mut().zip(i[3]).enumerate() {
            if !(0.0..=1.0).contains(&rg) {
                return Err((j, KmError::ReflectanceOutOfRange { name: "Rg", value: rg }));
            }
            *r = km::compose(LayerRt { r: *r, t: t[j] }, LayerRt::opaque(rg)).r;
        }
        Ok(())
    })?;
    Ok(r)
}

/// Reflectance of an opaque layer from its S and K (mm⁻¹) ([Kubelka1948]):
///
///     R∞ = 1 + K/S − √((K/S)² + 2K/S) = S / (S + K + √(K(K + 2S)))
///
/// (the second form, used here, does not cancel). S = K = 0 gives 0.
#[pyfunction]
#[pyo3(name = "SK_to_Rinf_KubelkaMunk", signature = (S, K, *, wavelengths=None))]
pub fn sk_to_rinf(
    py: Python<'_>,
    S: &Bound<'_, PyAny>,
    K: &Bound<'_, PyAny>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    let [r] = map_arrays(py, &[("S", S), ("K", K)], wavelengths, |i, o| {
        let [r_out] = o else { unreachable!() };
        for (j, ((r, &s), &k)) in r_out.iter_mut().zip(i[0]).zip(i[1]).enumerate() {
            // The same checks as every other entry point: S, K finite and ≥ 0.
            let c = km::duncan_mix([(1.0, KmCoefficients { s_per_mm: s, k_per_mm: k })]).map_err(|e| (j, e))?;
            *r = km::r_inf_from_s_k(c.s_per_mm, c.k_per_mm);
        }
        Ok(())
    })?;
    Ok(r)
}

/// R and T of a stack of layers given by their `R0` and `T`, the **first axis** running over
/// the layers from the top down; with `R_g`, over an opaque background of that reflectance
/// (then T = 0). Folded from the bottom up with [Huang2013] eq. 3-4 ([Kubelka1954]), numerator
/// corrected (the light reaching layer 2 is reflected by R₂, not R₁):
///
///     R₁₂ = R₁ + T₁² R₂ / (1 − R₁R₂),     T₁₂ = T₁ T₂ / (1 − R₁R₂)
///
/// Each layer must have R0, T in [0, 1] and R0 + T ≤ 1. Returns `(R, T)`.
#[pyfunction]
#[pyo3(name = "RT_stack_KubelkaMunk", signature = (R0, T, R_g=None, *, wavelengths=None))]
pub fn rt_stack(
    py: Python<'_>,
    R0: &Bound<'_, PyAny>,
    T: &Bound<'_, PyAny>,
    R_g: Option<&Bound<'_, PyAny>>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let mut b = broadcast(&[("R0", R0), ("T", T)])?;
    let Some((&layers, rest)) = b.shape.split_first() else {
        return Err(PyValueError::new_err("R0 and T need a first axis over the layers"));
    };
    let rest = rest.to_vec();
    let m: usize = rest.iter().product();
    let has_bg = R_g.is_some();
    if let Some(rg) = R_g {
        b.arrays.push(contiguous(as_f64_array("R_g", rg)?, &rest)?);
    }
    if has_bg {
        let rg = b.slice(2)?;
        if let Some(j) = rg.iter().position(|v| !(0.0..=1.0).contains(v)) {
            let error = KmError::ReflectanceOutOfRange { name: "Rg", value: rg[j] };
            let wl = wavelengths_vec(wavelengths)?;
            return Err(crate::errors::km_error(py, error, &crate::arrays::unravel(j, &rest), wl.as_deref()));
        }
    }
    let [r, t] = map_broadcast(py, &b, &rest, wavelengths, |i, o| {
        let [r_out, t_out] = o else { unreachable!() };
        let mut stack = Vec::with_capacity(layers + 1);
        for j in 0..m {
            stack.clear();
            for l in 0..layers {
                let layer = km::check_layer(LayerRt { r: i[0][l * m + j], t: i[1][l * m + j] });
                stack.push(layer.map_err(|e| (l * m + j, e))?);
            }
            if has_bg {
                stack.push(LayerRt::opaque(i[2][j]));
            }
            let LayerRt { r, t } = km::stack(&stack);
            r_out[j] = r;
            t_out[j] = t;
        }
        Ok(())
    })?;
    Ok((r, t))
}

fn saunderson(n: f64, K2: f64, specular_included: bool, K1: Option<f64>) -> PyResult<Saunderson> {
    let to_py = |e: KmError| crate::errors::KubelkaMunkError::new_err(e.to_string());
    let c = Saunderson::from_refractive_index(n, K2, specular_included).map_err(to_py)?;
    match K1 {
        None => Ok(c),
        Some(k1) if (0.0..1.0).contains(&k1) => Ok(Saunderson { k1, ..c }),
        Some(k1) => Err(to_py(KmError::BadCoefficient { name: "K1", value: k1 })),
    }
}

fn saunderson_map(
    py: Python<'_>,
    R: &Bound<'_, PyAny>,
    c: Saunderson,
    wavelengths: Option<&Bound<'_, PyAny>>,
    to_internal: bool,
) -> PyResult<Py<PyAny>> {
    let [out] = map_arrays(py, &[("R", R)], wavelengths, |i, o| {
        let [out] = o else { unreachable!() };
        for (j, (y, &x)) in out.iter_mut().zip(i[0]).enumerate() {
            km::check_layer(LayerRt { r: x, t: 0.0 }).map_err(|e| (j, e))?;
            *y = if to_internal { c.to_internal(x) } else { c.to_measured(x) };
        }
        Ok(())
    })?;
    Ok(out)
}

/// Measured reflectance → the internal reflectance Kubelka-Munk describes ([Saunderson1942]):
///
///     R_i = (R_m − f K1) / ((1 − K1)(1 − K2) + K2 (R_m − f K1))      (clamped to [0, 1])
///
/// `K1 = ((n − 1)/(n + 1))²` (Fresnel at normal incidence, or give `K1`), `K2` the internal
/// diffuse reflectance (0.6 classic for n = 1.5), `f = 1` when the instrument included the
/// specular component (SCI), 0 when it excluded it (SCE, 45/0).
#[pyfunction]
#[pyo3(name = "R_measured_to_internal_Saunderson",
       signature = (R, n=1.5, K2=0.6, specular_included=true, *, K1=None, wavelengths=None))]
pub fn saunderson_to_internal(
    py: Python<'_>,
    R: &Bound<'_, PyAny>,
    n: f64,
    K2: f64,
    specular_included: bool,
    K1: Option<f64>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    saunderson_map(py, R, saunderson(n, K2, specular_included, K1)?, wavelengths, true)
}

/// Internal reflectance → what an instrument measures ([Saunderson1942]), the inverse of
/// `R_measured_to_internal_Saunderson`:
///
///     R_m = f K1 + (1 − K1)(1 − K2) R_i / (1 − K2 R_i)
#[pyfunction]
#[pyo3(name = "R_internal_to_measured_Saunderson",
       signature = (R, n=1.5, K2=0.6, specular_included=true, *, K1=None, wavelengths=None))]
pub fn saunderson_to_measured(
    py: Python<'_>,
    R: &Bound<'_, PyAny>,
    n: f64,
    K2: f64,
    specular_included: bool,
    K1: Option<f64>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    saunderson_map(py, R, saunderson(n, K2, specular_included, K1)?, wavelengths, false)
}

/// S and K (mm⁻¹) of a mixture by Duncan's rule ([Duncan1940]), the concentration-weighted sums
/// of the components':
///
///     S = Σᵢ cᵢ Sᵢ,     K = Σᵢ cᵢ Kᵢ
///
/// The **first axis** of `S` and `K` runs over the components; `concentrations` (volume
/// fractions, ≥ 0; they need not sum to 1, a clear binder takes the rest) has one entry per
/// component, or any shape that broadcasts with the component axis first. Returns `(S, K)`.
#[pyfunction]
#[pyo3(name = "SK_mix_Duncan", signature = (S, K, concentrations, *, wavelengths=None))]
pub fn sk_mix_duncan(
    py: Python<'_>,
    S: &Bound<'_, PyAny>,
    K: &Bound<'_, PyAny>,
    concentrations: &Bound<'_, PyAny>,
    wavelengths: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let b = broadcast(&[("S", S), ("K", K)])?;
    let mut c = as_f64_array("concentrations", concentrations)?;
    if c.ndim() == 1 && b.shape.len() > 1 {
        // One concentration per component: put it on the component axis.
        let mut shape = vec![1usize; b.shape.len()];
        shape[0] = c.len();
        c = c.call_method1("reshape", (shape,))?.cast_into()?;
    }
    let c_shape = c.shape().to_vec();
    let b = broadcast(&[("S", S), ("K", K), ("concentrations", c.as_any())]).map_err(|e| {
        PyValueError::new_err(format!("{e} (concentrations {c_shape:?}; the first axis runs over the components)"))
    })?;
    let Some((&n, rest)) = b.shape.split_first() else {
        return Err(PyValueError::new_err("S and K need a first axis over the components"));
    };
    let rest = rest.to_vec();
    let m: usize = rest.iter().product();
    let [s, k] = map_broadcast(py, &b, &rest, wavelengths, |i, o| {
        let [s_out, k_out] = o else { unreachable!() };
        for j in 0..m {
            let parts = (0..n).map(|l| {
                let at = l * m + j;
                (i[2][at], KmCoefficients { s_per_mm: i[0][at], k_per_mm: i[1][at] })
            });
            let mix = km::duncan_mix(parts.clone()).map_err(|e| {
                // Name the first component that fails alone (the sum can also overflow: then the first).
                let bad = parts.clone().position(|p| km::duncan_mix([p]).is_err()).unwrap_or(0);
                (bad * m + j, e)
            })?;
            s_out[j] = mix.s_per_mm;
            k_out[j] = mix.k_per_mm;
        }
        Ok(())
    })?;
    Ok((s, k))
}

/// Registers the functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(r_to_sk, m)?)?;
    m.add_function(wrap_pyfunction!(sk_to_r0t, m)?)?;
    m.add_function(wrap_pyfunction!(sk_to_r, m)?)?;
    m.add_function(wrap_pyfunction!(sk_to_rinf, m)?)?;
    m.add_function(wrap_pyfunction!(rt_stack, m)?)?;
    m.add_function(wrap_pyfunction!(saunderson_to_internal, m)?)?;
    m.add_function(wrap_pyfunction!(saunderson_to_measured, m)?)?;
    m.add_function(wrap_pyfunction!(sk_mix_duncan, m)?)?;
    Ok(())
}
