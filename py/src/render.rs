//! The `render` feature: `rouge.Renderer` (one GPU device for every frame it draws),
//! `rouge.Look` (a look document: load, edit layers, save) and `RenderingError`. The frames are
//! `rouge render`'s: the same job ([`RenderJob`]), the same defaults (the default head at two
//! subdivisions with skin maps of the tone, the studio lights), drawn with the GIL released.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::create_exception;
use pyo3::prelude::*;
use rouge_model::look::Look;
use rouge_model::mesh::targets::FacePose;
use rouge_render::gpu::Gpu;
use rouge_render::job::{LookChoice, RenderJob, skin_of_tone};
use std::path::PathBuf;

create_exception!(
    rouge,
    RenderingError,
    crate::errors::RougeError,
    "A frame that cannot be drawn: no GPU adapter (the message says what to install), a file that \
     cannot be loaded (named), or an option out of range (named)."
);

fn rendering_error(e: impl std::fmt::Display) -> PyErr {
    RenderingError::new_err(e.to_string())
}

/// A look document: its layers bottom to top, each a preset, a thickness and whether it is
/// drawn. Presets, masks and maps are resolved relative to the folder of the file it was read
/// from (the working directory for a new one).
#[pyclass(module = "rouge._rouge", name = "Look")]
#[derive(Debug)]
pub struct PyLook {
    look: Look,
    /// Where relative references resolve: the file it was read from.
    path: PathBuf,
}

impl PyLook {
    /// `edit` applied to the look's JSON, read back (presets and thickness resolved again).
    fn edit(&mut self, edit: impl FnOnce(&mut serde_json::Value) -> PyResult<()>) -> PyResult<()> {
        let mut doc: serde_json::Value = serde_json::from_str(&self.look.to_json()).map_err(rendering_error)?;
        edit(&mut doc)?;
        self.look = Look::from_json(&doc.to_string(), &self.path).map_err(rendering_error)?;
        Ok(())
    }

    fn check_index(&self, index: usize) -> PyResult<()> {
        if index >= self.look.layers.len() {
            return Err(rendering_error(format!(
                "layer {index}: the look has {} layers (0 to {})",
                self.look.layers.len(),
                self.look.layers.len().saturating_sub(1)
            )));
        }
        Ok(())
    }
}

#[pymethods]
impl PyLook {
    /// Reads a look file (`rouge-look` v1 JSON).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Ok(PyLook { look: Look::load(&path).map_err(rendering_error)?, path })
    }

    /// Foundation, blush and lipstick: `rouge render`'s default look.
    #[staticmethod]
    fn default_look() -> Self {
        PyLook { look: Look::default_look(), path: PathBuf::from("look.json") }
    }

    /// No cosmetics.
    #[staticmethod]
    fn bare() -> Self {
        PyLook { look: Look::bare(), path: PathBuf::from("look.json") }
    }

    #[getter]
    fn name(&self) -> String {
        self.look.name.clone()
    }

    #[setter]
    fn set_name(&mut self, name: String) {
        self.look.name = name;
    }

    /// The layers, bottom to top, as dicts: `name`, `preset` (as written), `product` (the
    /// preset's name), `thickness` (the look file's object), `visible`, `locked`.
    #[getter]
    fn layers(&self, py: Python<'_>) -> PyResult<Vec<Py<PyAny>>> {
        let json = py.import("json")?;
        self.look
            .layers
            .iter()
            .map(|l| {
                let thickness = serde_json::to_string(&l.thickness).map_err(rendering_error)?;
                let d = pyo3::types::PyDict::new(py);
                d.set_item("name", &l.name)?;
                d.set_item("preset", &l.preset_ref)?;
                d.set_item("product", &l.preset.name)?;
                d.set_item("thickness", json.call_method1("loads", (thickness,))?)?;
                d.set_item("visible", l.visible)?;
                d.set_item("locked", l.locked)?;
                Ok(d.into_any().unbind())
            })
            .collect()
    }

    /// Shows or hides layer `index`.
    fn set_visible(&mut self, index: usize, visible: bool) -> PyResult<()> {
        self.check_index(index)?;
        self.look.layers[index].visible = visible;
        Ok(())
    }

    /// Replaces layer `index`'s thickness with a look file's thickness object, e.g.
    /// `{"uniform_mm": 0.01}` or `{"region": "lips", "thickness_mm": 0.02}`.
    fn set_thickness(&mut self, index: usize, thickness: &Bound<'_, PyAny>) -> PyResult<()> {
        self.check_index(index)?;
        let text: String = thickness.py().import("json")?.call_method1("dumps", (thickness,))?.extract()?;
        let value: serde_json::Value = serde_json::from_str(&text).map_err(rendering_error)?;
        self.edit(|doc| {
            doc["layers"][index]["thickness"] = value;
            Ok(())
        })
    }

    /// Adds a layer on top: `preset` as a look file writes it (`builtin:lipstick_02_red` or a
    /// path) with a thickness object.
    #[pyo3(signature = (preset, thickness, name=None))]
    fn add_layer(&mut self, preset: String, thickness: &Bound<'_, PyAny>, name: Option<String>) -> PyResult<()> {
        let text: String = thickness.py().import("json")?.call_method1("dumps", (thickness,))?.extract()?;
        let thickness: serde_json::Value = serde_json::from_str(&text).map_err(rendering_error)?;
        self.edit(|doc| {
            let mut layer = serde_json::json!({"preset": preset, "thickness": thickness});
            if let Some(name) = name {
                layer["name"] = name.into();
            }
            doc["layers"].as_array_mut().map(|l| l.push(layer)).ok_or_else(|| rendering_error("no layers"))
        })
    }

    /// Removes layer `index`.
    fn remove_layer(&mut self, index: usize) -> PyResult<()> {
        self.check_index(index)?;
        self.look.layers.remove(index);
        Ok(())
    }

    /// The look as `rouge-look` JSON.
    fn to_json(&self) -> String {
        self.look.to_json()
    }

    /// Writes the look (atomically). Relative references are written as they are, so they must
    /// hold from the new file's folder too.
    fn save(&self, path: PathBuf) -> PyResult<()> {
        self.look.save(&path).map_err(rendering_error)
    }

    fn __len__(&self) -> usize {
        self.look.layers.len()
    }

    fn __repr__(&self) -> String {
        format!("Look({:?}, {} layers)", self.look.name, self.look.layers.len())
    }
}

/// A GPU device opened once and kept: every [`PyRenderer::render`] draws on it.
#[pyclass(module = "rouge._rouge", name = "Renderer")]
#[derive(Debug)]
pub struct PyRenderer {
    gpu: Gpu,
}

#[pymethods]
impl PyRenderer {
    /// Opens the best GPU adapter wgpu finds (a software one, Mesa's lavapipe, where there is no
    /// GPU). Raises RenderingError, saying what to install, where there is none.
    #[new]
    fn new(py: Python<'_>) -> PyResult<Self> {
        let gpu = py.detach(Gpu::headless).map_err(rendering_error)?;
        Ok(PyRenderer { gpu })
    }

    /// The adapter's name, backend and driver.
    #[getter]
    fn adapter(&self) -> String {
        let i = self.gpu.adapter.get_info();
        format!("{} ({:?}, {})", i.name, i.backend, i.driver_info)
    }

    /// Draws a frame as `rouge render` does with the same options and returns it as a numpy
    /// array (height, width, 4): uint8 sRGB (display, tone-mapped) or, with `linear=True`,
    /// float32 linear radiance. `mesh`: a file (.obj, .gltf, .glb, mm) or None for the default
    /// head (painted from skin maps of `skin_tone`); `look`: a Look, "default", "bare" or a look
    /// file; `skin_tone`: a tone name of `rouge skin tones` or an ITA°; `expression`: weights
    /// of the default head's expressions ("smile" or "smile=0.5,blink=1"). Antialiased as
    /// `rouge render`'s default (`--aa edges`: edge overdraw and the hairs' coverage).
    #[pyo3(signature = (*, mesh=None, look=None, skin_tone=None, expression=None, width=640, height=480, linear=false, subdiv=2, yaw=0.0, pitch=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        mesh: Option<PathBuf>,
        look: Option<&Bound<'py, PyAny>>,
        skin_tone: Option<String>,
        expression: Option<String>,
        width: u32,
        height: u32,
        linear: bool,
        subdiv: u32,
        yaw: f32,
        pitch: f32,
    ) -> PyResult<Bound<'py, PyAny>> {
        let check = |name: &str, v: u32, max: u32| {
            if (1..=max).contains(&v) {
                Ok(())
            } else {
                Err(rendering_error(format!("{name}={v}: must be 1 to {max}")))
            }
        };
        check("width", width, 8192)?;
        check("height", height, 8192)?;
        if subdiv > 4 {
            return Err(rendering_error(format!("subdiv={subdiv}: must be 0 to 4")));
        }
        // A Look, or "default", "bare" or a look file.
        let look = match look {
            None => LookChoice::Default,
            Some(l) => match l.cast::<PyLook>() {
                Ok(l) => LookChoice::Loaded(Box::new(l.borrow().look.clone())),
                Err(_) => match l.extract::<PathBuf>()? {
                    p if p.as_os_str() == "default" => LookChoice::Default,
                    p if p.as_os_str() == "bare" => LookChoice::Bare,
                    p => LookChoice::File(p),
                },
            },
        };
        let expression = match &expression {
            Some(spec) => FacePose::parse_weights(spec, "expression").map_err(rendering_error)?,
            None => Default::default(),
        };
        let mut job = RenderJob {
            mesh,
            look,
            width,
            height,
            subdivision: subdiv,
            yaw_deg: yaw,
            pitch_deg: pitch,
            face: FacePose { expression, ..FacePose::default() },
            ..RenderJob::default()
        };
        // As `rouge render`: skin maps of the tone on the default head, its flat colour elsewhere.
        let maps = job.mesh.is_none().then(|| (Default::default(), 1, 1024));
        job.skin_maps = skin_of_tone(&mut job.scene, skin_tone.as_deref(), maps)
            .map_err(|e| rendering_error(format!("skin_tone={}: {e}", skin_tone.as_deref().unwrap_or("light"))))?;
        job.skin_detail = job.skin_maps.is_some();
        let gpu =
            Gpu { adapter: self.gpu.adapter.clone(), device: self.gpu.device.clone(), queue: self.gpu.queue.clone() };
        let (w, h) = (height as usize, width as usize);
        let frame = py.detach(move || -> rouge_render::error::Result<Frame> {
            let loaded = job.load()?;
            let mut prepared = job.prepare_on(&loaded, gpu)?;
            // As `rouge render`'s default.
            let (mode, coverage) = (rouge_render::aa::AaMode::DEFAULT, rouge_render::aa::EdgeCoverage::TwoSided);
            prepared.set_antialiasing(mode, coverage, &loaded.mesh)?;
            Ok(if linear {
                Frame::Linear(prepared.render_linear()?.into_iter().flatten().collect())
            } else {
                Frame::Display(prepared.render_display()?)
            })
        });
        let frame = frame.map_err(rendering_error)?;
        let shape = [w, h, 4];
        Ok(match frame {
            Frame::Linear(v) => PyArray1::from_vec(py, v).reshape(shape)?.into_any(),
            Frame::Display(v) => PyArray1::from_vec(py, v).reshape(shape)?.into_any(),
        })
    }
}

enum Frame {
    Display(Vec<u8>),
    Linear(Vec<f32>),
}

/// Registers `Renderer`, `Look` and `RenderingError`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRenderer>()?;
    m.add_class::<PyLook>()?;
    m.add("RenderingError", m.py().get_type::<RenderingError>())?;
    Ok(())
}
