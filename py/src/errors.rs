//! Python exceptions: every one a `ValueError` subclass carrying the Rust error's message, with
//! the wavelength, index, file, line and column as attributes where the error has them.

use pyo3::IntoPyObjectExt;
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rouge_measure::{KmError, LocatedError, PresetError as RustPresetError};

create_exception!(rouge, RougeError, PyValueError, "Base class of Rouge's errors (a ValueError).");
create_exception!(
    rouge,
    KubelkaMunkError,
    RougeError,
    "Inputs without a Kubelka-Munk solution. Attributes: `index` (tuple, the first failing element \
     of the broadcast arrays, or None), `wavelength` (nm, or None when no wavelengths were given)."
);
create_exception!(
    rouge,
    MeasurementImportError,
    RougeError,
    "A measurement or spectra file that cannot be read. Attributes: `path`, `line`, `column` \
     (1-based; None where the error has none)."
);
create_exception!(
    rouge,
    PresetError,
    RougeError,
    "A preset that cannot be built, read or written. Attributes: `path`, `wavelength` (nm or None), \
     `line`, `column` (JSON errors)."
);
create_exception!(rouge, SpectrumError, RougeError, "A spectrum on an unusable wavelength grid.");

fn with_attrs(err: PyErr, py: Python<'_>, attrs: &[(&str, Py<PyAny>)]) -> PyErr {
    let value = err.value(py);
    for (name, v) in attrs {
        // Setting an attribute on a fresh exception instance cannot fail.
        let _ = value.setattr(*name, v);
    }
    err
}

fn opt<'py, T: IntoPyObjectExt<'py>>(py: Python<'py>, v: Option<T>) -> Py<PyAny> {
    match v.map(|x| x.into_py_any(py)) {
        Some(Ok(o)) => o,
        _ => py.None(),
    }
}

/// A Kubelka-Munk error at `index` of the arrays (empty for scalars; [`crate::arrays::unravel`]
/// makes it from a flat position); `wavelengths` (if given) label the last axis, so the message
/// names the wavelength as `rouge import` does.
pub fn km_error(py: Python<'_>, error: KmError, index: &[usize], wavelengths: Option<&[f64]>) -> PyErr {
    let nm = wavelengths.and_then(|w| index.last().and_then(|&i| w.get(i).copied()));
    let at = match (nm, index.is_empty()) {
        (Some(nm), _) => format!("at {nm} nm (index {}): ", fmt_index(index)),
        (None, false) => format!("at index {}: ", fmt_index(index)),
        (None, true) => String::new(),
    };
    let index_py = match PyTuple::new(py, index) {
        Ok(t) if !index.is_empty() => t.into_any().unbind(),
        _ => py.None(),
    };
    with_attrs(
        KubelkaMunkError::new_err(format!("{at}{error}")),
        py,
        &[("index", index_py), ("wavelength", opt(py, nm))],
    )
}

fn fmt_index(index: &[usize]) -> String {
    match index {
        [i] => format!("({i},)"),
        _ => format!("({})", index.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")),
    }
}

/// An import error, message as `rouge import` prints it (`file:line:column: why`).
pub fn import_error(py: Python<'_>, e: LocatedError) -> PyErr {
    let attrs = [
        ("path", opt(py, Some(e.path.display().to_string()))),
        ("line", opt(py, e.line)),
        ("column", opt(py, e.column)),
    ];
    with_attrs(MeasurementImportError::new_err(e.to_string()), py, &attrs)
}

/// A preset error, message as the CLI prints it.
pub fn preset_error(py: Python<'_>, e: RustPresetError) -> PyErr {
    let (path, nm, line, column) = match &e {
        RustPresetError::Io { path, .. } | RustPresetError::Invalid { path, .. } => (path.clone(), None, None, None),
        RustPresetError::Json(e) => (e.path.display().to_string(), None, e.line, e.column),
        RustPresetError::Inversion { path, wavelength_nm, .. } => (path.clone(), Some(*wavelength_nm), None, None),
    };
    let attrs = [
        ("path", opt(py, Some(path))),
        ("wavelength", opt(py, nm)),
        ("line", opt(py, line)),
        ("column", opt(py, column)),
    ];
    with_attrs(PresetError::new_err(e.to_string()), py, &attrs)
}

/// A spectrum (grid) error.
pub fn spectrum_error(message: impl std::fmt::Display) -> PyErr {
    SpectrumError::new_err(message.to_string())
}

/// Registers the exception classes on the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("RougeError", py.get_type::<RougeError>())?;
    m.add("KubelkaMunkError", py.get_type::<KubelkaMunkError>())?;
    m.add("MeasurementImportError", py.get_type::<MeasurementImportError>())?;
    m.add("PresetError", py.get_type::<PresetError>())?;
    m.add("SpectrumError", py.get_type::<SpectrumError>())?;
    Ok(())
}
