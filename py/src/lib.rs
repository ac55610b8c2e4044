//! `rouge._rouge`: the compiled core of the `rouge` Python package, binding `rouge-measure`, and
//! with the `render` feature the renderer (`render.rs`: `Renderer`, `Look`). The public API, its
//! colour-science adapters and stubs live in `py/python/rouge/`.

use pyo3::prelude::*;

mod analysis;
mod arrays;
mod color;
mod errors;
mod finish;
mod formulate;
mod io;
mod km;
#[cfg(feature = "render")]
mod render;
mod skin;

#[pymodule]
fn _rouge(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DETACH_MIN_LEN", arrays::DETACH_MIN_LEN)?;
    errors::register(m)?;
    km::register(m)?;
    color::register(m)?;
    io::register(m)?;
    analysis::register(m)?;
    formulate::register(m)?;
    skin::register(m)?;
    finish::register(m)?;
    #[cfg(feature = "render")]
    render::register(m)?;
    m.add("HAS_RENDER", cfg!(feature = "render"))?;
    Ok(())
}
