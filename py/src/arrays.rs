//! numpy in, numpy out: conversion to float64, numpy's broadcasting rules, and the GIL released
//! around the work on large arrays.
//!
//! Inputs that already are C-contiguous float64 arrays of the broadcast shape are read in place
//! (no copy). Anything else (another dtype, a list, a non-contiguous view, a smaller operand that
//! broadcasts) is first made into a contiguous float64 numpy array of the broadcast shape, so
//! the formulas always run over plain slices.

use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Arrays at least this long are processed with the GIL released.
pub const DETACH_MIN_LEN: usize = 4096;

/// Runs `f` with the GIL released when the arrays are large, holding it for small ones (where
/// releasing costs more than it saves).
pub fn maybe_detach<T: Send>(py: Python<'_>, len: usize, f: impl FnOnce() -> T + Send) -> T {
    if len >= DETACH_MIN_LEN { py.detach(f) } else { f() }
}

/// Any array-like as a float64 numpy array: float64 arrays as they are, the rest through
/// `numpy.asarray(x, dtype=float64)`.
pub fn as_f64_array<'py>(name: &str, obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        return Ok(a.clone());
    }
    let py = obj.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", "float64")?;
    let converted = py
        .import("numpy")?
        .call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| PyValueError::new_err(format!("{name}: cannot be read as float64 numbers: {e}")))?;
    Ok(converted.cast_into::<PyArrayDyn<f64>>()?)
}

/// numpy's broadcast shape of `shapes` (right-aligned; each dimension equal or 1).
pub fn broadcast_shape(named: &[(&str, &[usize])]) -> PyResult<Vec<usize>> {
    let ndim = named.iter().map(|(_, s)| s.len()).max().unwrap_or(0);
    let mut out = vec![1usize; ndim];
    for (_, shape) in named {
        for (i, &d) in shape.iter().enumerate() {
            let slot = &mut out[ndim - shape.len() + i];
            if *slot == 1 {
                *slot = d;
            } else if d != 1 && d != *slot {
                let shapes: Vec<String> = named.iter().map(|(n, s)| format!("{n} {s:?}")).collect();
                return Err(PyValueError::new_err(format!("shapes do not broadcast together: {}", shapes.join(", "))));
            }
        }
    }
    Ok(out)
}

/// `arrays` broadcast to one shape, each a C-contiguous float64 array of that shape (the input
/// itself where it already is one).
#[derive(Debug)]
pub struct Broadcast<'py> {
    /// The common shape.
    pub shape: Vec<usize>,
    /// The inputs, in order, read-only.
    pub arrays: Vec<PyReadonlyArrayDyn<'py, f64>>,
}

impl Broadcast<'_> {
    /// Number of elements of the common shape.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }

    /// Input `i` as a slice (always contiguous by construction).
    pub fn slice(&self, i: usize) -> PyResult<&[f64]> {
        self.arrays[i].as_slice().map_err(|e| PyValueError::new_err(e.to_string()))
    }
}

/// Converts and broadcasts named array-likes (see the module documentation).
pub fn broadcast<'py>(inputs: &[(&str, &Bound<'py, PyAny>)]) -> PyResult<Broadcast<'py>> {
    let arrays: Vec<Bound<'py, PyArrayDyn<f64>>> =
        inputs.iter().map(|(n, o)| as_f64_array(n, o)).collect::<PyResult<_>>()?;
    let shapes: Vec<Vec<usize>> = arrays.iter().map(|a| a.shape().to_vec()).collect();
    let named: Vec<(&str, &[usize])> = inputs.iter().zip(&shapes).map(|((n, _), s)| (*n, s.as_slice())).collect();
    let shape = broadcast_shape(&named)?;
    let arrays = arrays.into_iter().map(|a| contiguous(a, &shape)).collect::<PyResult<_>>()?;
    Ok(Broadcast { shape, arrays })
}

/// `a` as a C-contiguous array of `shape`: itself if it is one, else a numpy copy.
pub fn contiguous<'py>(a: Bound<'py, PyArrayDyn<f64>>, shape: &[usize]) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    if a.shape() == shape && a.is_c_contiguous() {
        return Ok(a.readonly());
    }
    let copy = PyArrayDyn::<f64>::zeros(a.py(), IxDyn(shape), false);
    {
        let src = a.readonly();
        let view = src.as_array();
        let view = view
            .broadcast(IxDyn(shape))
            .ok_or_else(|| PyValueError::new_err(format!("shape {:?} does not broadcast to {shape:?}", a.shape())))?;
        copy.readwrite().as_array_mut().assign(&view);
    }
    Ok(copy.readonly())
}

/// A new float64 array of `shape`, to be filled.
pub fn output<'py>(py: Python<'py>, shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    PyArrayDyn::<f64>::zeros(py, IxDyn(shape), false)
}

/// The multi-index of flat (C-order) position `flat` in `shape`.
pub fn unravel(mut flat: usize, shape: &[usize]) -> Vec<usize> {
    let mut index = vec![0; shape.len()];
    for (slot, &d) in index.iter_mut().zip(shape).rev() {
        if d > 0 {
            *slot = flat % d;
            flat /= d;
        }
    }
    index
}

/// A failure at one flat position of the broadcast arrays.
pub type AtIndex<E> = (usize, E);

/// Broadcasts `inputs`, allocates `O` outputs of the common shape, and runs `f` over the flat
/// slices (GIL released for large arrays). A failure at a position becomes a
/// `KubelkaMunkError` naming that position and, with `wavelengths` labelling the last axis, its
/// wavelength. 0-d results come back as Python floats.
pub fn map_arrays<const O: usize>(
    py: Python<'_>,
    inputs: &[(&str, &Bound<'_, PyAny>)],
    wavelengths: Option<&Bound<'_, PyAny>>,
    f: impl FnOnce(&[&[f64]], &mut [&mut [f64]]) -> Result<(), AtIndex<rouge_measure::KmError>> + Send,
) -> PyResult<[Py<PyAny>; O]> {
    let b = broadcast(inputs)?;
    map_broadcast(py, &b, &b.shape, wavelengths, f)
}

/// [`map_arrays`] over arrays already broadcast, with outputs of `out_shape`.
pub fn map_broadcast<const O: usize>(
    py: Python<'_>,
    b: &Broadcast<'_>,
    out_shape: &[usize],
    wavelengths: Option<&Bound<'_, PyAny>>,
    f: impl FnOnce(&[&[f64]], &mut [&mut [f64]]) -> Result<(), AtIndex<rouge_measure::KmError>> + Send,
) -> PyResult<[Py<PyAny>; O]> {
    let ins: Vec<&[f64]> = (0..b.arrays.len()).map(|i| b.slice(i)).collect::<PyResult<_>>()?;
    let outs: [Bound<'_, PyArrayDyn<f64>>; O] = std::array::from_fn(|_| output(py, out_shape));
    let result = {
        let mut rw: Vec<_> = outs.iter().map(|o| o.readwrite()).collect();
        let mut slices: Vec<&mut [f64]> = rw
            .iter_mut()
            .map(|r| r.as_slice_mut().map_err(|e| PyValueError::new_err(e.to_string())))
            .collect::<PyResult<_>>()?;
        maybe_detach(py, b.len(), || f(&ins, &mut slices))
    };
    if let Err((flat, error)) = result {
        let wl = wavelengths_vec(wavelengths)?;
        return Err(crate::errors::km_error(py, error, &unravel(flat, &b.shape), wl.as_deref()));
    }
    outs.into_iter()
        .map(finish)
        .collect::<PyResult<Vec<_>>>()?
        .try_into()
        .map_err(|_| PyValueError::new_err("internal: output count"))
}

/// An output array as Python returns it: a float for a 0-d result, the array otherwise.
pub fn finish(a: Bound<'_, PyArrayDyn<f64>>) -> PyResult<Py<PyAny>> {
    if a.ndim() == 0 { Ok(a.call_method0("item")?.unbind()) } else { Ok(a.into_any().unbind()) }
}

/// The optional `wavelengths` argument as numbers (only read when an error needs it).
pub fn wavelengths_vec(wavelengths: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<f64>>> {
    match wavelengths {
        Some(w) => {
            let a = as_f64_array("wavelengths", w)?;
            let v = a.readonly().as_array().iter().copied().collect();
            Ok(Some(v))
        }
        None => Ok(None),
    }
}
