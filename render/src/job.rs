//! Whole renders from files: what `rouge render`, `rouge bench render` and the tests run.
//!
//! [`RenderJob`] names a mesh (the embedded default head unless a file is given), a look, an
//! optional environment map, the camera and the image size; [`RenderJob::prepare`] loads and
//! uploads everything, [`Prepared::render_display`] / [`Prepared::render_linear`] draw frames,
//! and [`write_png`] / [`write_exr`] save them atomically (temp file, then rename), so a failed
//! save never destroys an earlier image.

use crate::env::EnvMap;
use crate::error::{RenderError, Result};
use crate::gpu::Gpu;
use crate::renderer::Renderer;
use crate::scene::{Camera, Scene};
use rouge_model::look::Look;
use rouge_model::mesh::Bounds;
pub use rouge_model::mesh::load_mesh;
use std::path::{Path, PathBuf};

/// Which look to render.
#[derive(Clone, Debug, PartialEq)]
pub enum LookChoice {
    /// Foundation, blush and lipstick (the default look on the default head).
    Default,
    /// No cosmetics.
    Bare,
    /// A look document.
    File(PathBuf),
}

/// Everything a render needs, as the command line gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderJob {
    /// Mesh file (.obj, .gltf, .glb); `None` for the embedded default head.
    pub mesh: Option<PathBuf>,
    /// Millimetres per mesh unit.
    pub mesh_scale_mm: f32,
    /// Catmull-Clark levels applied before rendering.
    pub subdivision: u32,
    /// The look.
    pub look: LookChoice,
    /// Equirectangular HDR environment (EXR); `None` for the studio's built-in ambient.
    pub env: Option<PathBuf>,
    /// Skin albedo texture (PNG, sRGB, the mesh's UV space); `None` for the scene's skin colour.
    pub albedo_map: Option<PathBuf>,
    /// Tangent-space normal map (PNG, OpenGL convention, +Y up); tangents are generated.
    pub normal_map: Option<PathBuf>,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Camera yaw, degrees.
    pub yaw_deg: f32,
    /// Camera pitch, degrees.
    pub pitch_deg: f32,
    /// The scene (lights, skin, SSS settings, exposure).
    pub scene: Scene,
}

impl Default for RenderJob {
    fn default() -> Self {
        RenderJob {
            mesh: None,
            mesh_scale_mm: 1.0,
            subdivision: 2,
            look: LookChoice::Default,
            env: None,
            albedo_map: None,
            normal_map: None,
            width: 1280,
            height: 720,
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            scene: Scene::studio(),
        }
    }
}

/// Reads a PNG texture as RGBA8.
///
/// # Errors
/// [`RenderError::File`] naming the file when it is missing or not a readable PNG.
pub fn load_texture(path: &Path) -> Result<image::RgbaImage> {
    let bytes = std::fs::read(path).map_err(|e| RenderError::file(path, format!("cannot read: {e}")))?;
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .map_err(|e| RenderError::file(path, format!("not a readable PNG texture: {e}")))?;
    Ok(img.to_rgba8())
}

/// A job loaded onto the GPU, ready to draw frames.
#[derive(Debug)]
pub struct Prepared {
    /// The device.
    pub gpu: Gpu,
    /// The renderer with mesh and look uploaded.
    pub renderer: Renderer,
    /// The scene, with the environment of the job.
    pub scene: Scene,
    /// The camera framing the mesh.
    pub camera: Camera,
    /// Triangles drawn.
    pub triangles: usize,
    /// Image size.
    pub size: (u32, u32),
}

impl RenderJob {
    /// Loads mesh, look and environment, opens a GPU and uploads them.
    ///
    /// # Errors
    /// Any file that cannot be loaded (named), or no GPU.
    pub fn prepare(&self) -> Result<Prepared> {
        self.prepare_loaded(&self.load()?)
    }

    /// [`RenderJob::prepare`] from a scene already [loaded](RenderJob::load): opens a GPU and
    /// uploads it (the textures are read here).
    ///
    /// # Errors
    /// A texture that cannot be loaded (named), or no GPU.
    pub fn prepare_loaded(&self, loaded: &Loaded) -> Result<Prepared> {
        let Loaded { mesh, look, scene, camera, .. } = loaded;
        let albedo = self.albedo_map.as_deref().map(load_texture).transpose()?;
        let normal = self.normal_map.as_deref().map(load_texture).transpose()?;
        let gpu = Gpu::headless()?;
        let mut renderer = Renderer::new(&gpu.device, &gpu.queue);
        renderer.set_mesh(mesh, scene.skin.albedo)?;
        renderer.set_textures(albedo.as_ref(), normal.as_ref())?;
        renderer.set_look(look)?;
        Ok(Prepared {
            gpu,
            renderer,
            scene: scene.clone(),
            camera: *camera,
            triangles: mesh.triangle_count(),
            size: (self.width, self.height),
        })
    }

    /// Loads mesh, look and environment without a GPU (what `rouge export mitsuba` needs), and
    /// frames the camera on the mesh's bounds as [`RenderJob::prepare`] does.
    ///
    /// # Errors
    /// Any file that cannot be loaded (named); an empty mesh.
    pub fn load(&self) -> Result<Loaded> {
        let look = match &self.look {
            LookChoice::Default => Look::default_look(),
            LookChoice::Bare => Look::bare(),
            LookChoice::File(p) => Look::load(p)?,
        };
        let mut scene = self.scene.clone();
        let env = self.env.as_deref().map(EnvMap::load_exr).transpose()?;
        if let Some(env) = &env {
            scene.environment = Some(env.sh_irradiance());
        }
        let mut mesh = load_mesh(self.mesh.as_deref(), self.mesh_scale_mm, self.subdivision)?;
        if self.normal_map.is_some() {
            mesh.generate_tangents()?;
        }
        let bounds = Bounds::of(&mesh.positions).ok_or_else(|| RenderError::Invalid("empty mesh".into()))?;
        let camera = Camera::framing(&bounds, self.yaw_deg, self.pitch_deg);
        Ok(Loaded { mesh, look, scene, env, camera })
    }
}

/// A job's scene loaded on the CPU.
#[derive(Debug)]
pub struct Loaded {
    /// The triangle mesh, mm, subdivided.
    pub mesh: rouge_model::mesh::TriangleMesh,
    /// The look.
    pub look: Look,
    /// The scene, with the environment of the job.
    pub scene: Scene,
    /// The environment map, when the job names one.
    pub env: Option<EnvMap>,
    /// The camera framing the mesh.
    pub camera: Camera,
}

impl Prepared {
    /// Renders the tone-mapped frame and reads it back as RGBA8.
    ///
    /// # Errors
    /// As [`Renderer::render`].
    pub fn render_display(&mut self) -> Result<Vec<u8>> {
        self.renderer.render(&self.scene, &self.camera, self.size.0, self.size.1, true)?;
        self.renderer.read_display()
    }

    /// Renders linear radiance and reads it back.
    ///
    /// # Errors
    /// As [`Renderer::render`].
    pub fn render_linear(&mut self) -> Result<Vec<[f32; 4]>> {
        self.renderer.render(&self.scene, &self.camera, self.size.0, self.size.1, false)?;
        self.renderer.read_linear()
    }
}

/// Writes RGBA8 pixels as a PNG, atomically.
///
/// # Errors
/// [`RenderError::File`] naming `path`.
pub fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(encoder, rgba, width, height, image::ExtendedColorType::Rgba8)
        .map_err(|e| RenderError::file(path, format!("cannot encode PNG: {e}")))?;
    rouge_measure::preset::write_atomic(path, &bytes).map_err(|e| RenderError::file(path, format!("cannot write: {e}")))
}

/// Writes linear RGB radiance as a 32-bit float EXR, atomically.
///
/// # Errors
/// [`RenderError::File`] naming `path`.
pub fn write_exr(path: &Path, width: u32, height: u32, rgba: &[[f32; 4]]) -> Result<()> {
    let bytes = encode_exr(width, height, rgba).map_err(|e| RenderError::file(path, e))?;
    rouge_measure::preset::write_atomic(path, &bytes).map_err(|e| RenderError::file(path, format!("cannot write: {e}")))
}

/// Encodes linear RGB (alpha ignored) as a 32-bit float EXR in memory.
///
/// # Errors
/// [`RenderError::Invalid`] when the encoder refuses the image.
pub fn encode_exr(width: u32, height: u32, rgba: &[[f32; 4]]) -> Result<Vec<u8>> {
    use exr::prelude::*;
    let (w, h) = (width as usize, height as usize);
    let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let v = rgba[p.y() * w + p.x()];
        (v[0], v[1], v[2])
    });
    let image = Image::from_channels((w, h), channels);
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes).map_err(|e| RenderError::Invalid(format!("cannot encode EXR: {e}")))?;
    Ok(bytes.into_inner())
}

/// Writes the frame to `path` by its extension: .png (tone-mapped) or .exr (linear).
///
/// # Errors
/// An unknown extension, or the writers' errors.
pub fn render_to_file(prepared: &mut Prepared, path: &Path) -> Result<()> {
    let (w, h) = prepared.size;
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => {
            let pixels = prepared.render_display()?;
            write_png(path, w, h, &pixels)
        }
        Some("exr") => {
            let pixels = prepared.render_linear()?;
            write_exr(path, w, h, &pixels)
        }
        _ => {
            Err(RenderError::file(path, "unknown output format: use .png (tone-mapped sRGB) or .exr (linear radiance)"))
        }
    }
}
