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
use crate::local_thickness::ThicknessSource;
use crate::renderer::Renderer;
use crate::scene::{Camera, Scene, SubsurfaceModel};
use rouge_measure::skin::SkinColorTable;
use rouge_model::look::Look;
use rouge_model::mesh::Bounds;
use rouge_model::mesh::TriangleMesh;
use rouge_model::mesh::default_head;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::lashes::{LashRig, Mascara};
pub use rouge_model::mesh::load_mesh;
pub use rouge_model::mesh::targets::FacePose;
use rouge_model::mesh::targets::{TargetError, TargetSet};
use rouge_model::skin::SkinRecipe;
use rouge_model::thickness::{
    BakeSettings, CacheUse, UvMap, bake_local_thickness_cached, default_cache_dir, morph_to_bounding_sphere,
    thickness_uv_map,
};
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
    /// A look already loaded (and perhaps edited): the Python package's `rouge.Look`.
    Loaded(Box<Look>),
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
    /// Skin maps to generate from a tone, the default head's anatomy and skin conditions
    /// ([`rouge_model::skin`]); their colour through the spectral skin model becomes the skin's
    /// albedo texture. Exclusive with `albedo_map`.
    pub skin_maps: Option<SkinRecipe>,
    /// Whether the skin has its microgeometry ([`rouge_model::skin::detail`]: pores, fine lines,
    /// the T-zone's shine), tiled at the mesh's scale with the default head's region map, and on
    /// the default head its expression wrinkles and lip furrows ([`rouge_model::skin::wrinkles`],
    /// as deep as `face` makes them).
    pub skin_detail: bool,
    /// Whether the skin maps' blood follows the face's expression
    /// ([`rouge_model::skin::SkinMaps::with_blood_flow`]: a smile flushes the cheeks, pressed lips
    /// blanch).
    pub blood_flow: bool,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Camera yaw, degrees.
    pub yaw_deg: f32,
    /// Camera pitch, degrees.
    pub pitch_deg: f32,
    /// A close-up of a region of the default head instead of the whole face
    /// ([`Camera::close_up`]).
    pub close_up: Option<rouge_model::skin::AnatomyRegion>,
    /// The scene (lights, skin, SSS settings, exposure).
    pub scene: Scene,
    /// Morph of the mesh toward its bounding sphere, 0 (none) to 1: a deformation for testing
    /// what depends on the rest pose ([`rouge_model::thickness::morph_to_bounding_sphere`]).
    pub morph: f32,
    /// Bake the thickness model's local thickness on the undeformed mesh (a map baked once, as
    /// shipped) rather than on the mesh as drawn.
    pub thickness_bake_rest_pose: bool,
    /// Expression and face shape of the default head (its morph targets), applied before
    /// subdivision; the neutral, unshaped head is then the rest mesh.
    pub face: FacePose,
    /// A mascara on the default head's lashes, over the look's own (`"mascara"`), if any.
    pub mascara: Option<Mascara>,
    /// A tinted brow gel on the default head's brows, over the look's own (`"brow_gel"`), if any.
    pub brow_gel: Option<rouge_model::mesh::brow_gel::BrowGel>,
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
            skin_maps: None,
            skin_detail: false,
            blood_flow: true,
            width: 1280,
            height: 720,
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            close_up: None,
            scene: Scene::studio(),
            morph: 0.0,
            thickness_bake_rest_pose: false,
            face: FacePose::default(),
            mascara: None,
            brow_gel: None,
        }
    }
}

/// The albedo texture of the skin maps `recipe` makes, their blood moved by `face`'s expression
/// when given: the maps, the tone's colour table, the bake
/// ([`rouge_model::skin::SkinMaps::albedo_image`]).
fn skin_albedo(recipe: &SkinRecipe, face: Option<&FacePose>) -> Result<image::RgbaImage> {
    let mut maps = recipe.generate()?;
    if let Some(face) = face.filter(|f| !f.is_neutral()) {
        let invalid = |e: TargetError| RenderError::Invalid(e.to_string());
        let (units, _) = TargetSet::default_head().map_err(invalid)?.resolve(face).map_err(invalid)?;
        maps = maps.with_blood_flow(&units);
    }
    let table = skin_color_table(maps.base())?;
    Ok(bake_skin_albedo(&maps, &table))
}

/// The skin colour table of skin maps whose base is `base` (`SkinColorTable::new`; about a
/// second on two cores), kept between runs in the cache directory
/// ([`rouge_model::skin::table_cache`]): build it once per tone and keep it.
///
/// # Errors
/// [`RenderError::Invalid`] when the table cannot be built for `base`.
pub fn skin_color_table(base: &rouge_measure::skin::SkinParams) -> Result<SkinColorTable> {
    use rouge_model::skin::table_cache::{color_table_cached, default_table_dir};
    color_table_cached(base, default_table_dir().as_deref())
        .map(|(table, _)| table)
        .map_err(|e| RenderError::Invalid(format!("skin maps: {e}")))
}

/// The skin's albedo texture baked from `maps` through `table` (made for the maps' base by
/// [`skin_color_table`]): the one bake of skin maps that `rouge render` and the painting app
/// both call ([`rouge_model::skin::SkinMaps::albedo_image`]).
pub fn bake_skin_albedo(maps: &rouge_model::skin::SkinMaps, table: &SkinColorTable) -> image::RgbaImage {
    maps.albedo_image(table)
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
    /// The local-thickness bake, when the skin's model is `thickness` with the baked source.
    pub thickness_bake: Option<BakeReport>,
}

/// How a local-thickness bake went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeReport {
    /// Vertices baked.
    pub vertices: usize,
    /// Seconds the bake took (for a cache hit: the bake that wrote the cache).
    pub seconds: f64,
    /// Whether it came from the cache.
    pub cache: CacheUse,
}

/// Side of the baked local-thickness map in the mesh's UV space, texels.
pub const LOCAL_THICKNESS_MAP_SIDE: u32 = 1024;

/// Bakes (or reads from the cache, [`default_cache_dir`]) the local thickness of `mesh` with
/// `settings` and rasterises it into a UV map of [`LOCAL_THICKNESS_MAP_SIDE`]².
///
/// # Errors
/// [`RenderError::Invalid`] with the baker's message.
pub fn bake_thickness_map(mesh: &TriangleMesh, settings: &BakeSettings) -> Result<(UvMap, BakeReport)> {
    let fail = |e: rouge_model::thickness::ThicknessError| RenderError::Invalid(e.to_string());
    let cache = default_cache_dir();
    // Only the tissue's surface (skin and mouth bag): an eye, the teeth, the tongue or a lash is
    // not the skin's medium, and light does not cross an eye toward the lids, so a ray into the
    // interior that would meet an eyeball goes on through the socket instead (and usually
    // leaves the cutoff, reading as thick).
    let skin = mesh.only(|g| g.is_tissue());
    let mesh = &skin;
    // A cache that cannot be written costs a bake, not the frame.
    let (bake, cache_use) = match bake_local_thickness_cached(mesh, settings, cache.as_deref()) {
        Err(rouge_model::thickness::ThicknessError::Cache { path, source }) => {
            log::warn!("local thickness cache {}: {source}; baking without it", path.display());
            bake_local_thickness_cached(mesh, settings, None).map_err(fail)?
        }
        other => other.map_err(fail)?,
    };
    let side = LOCAL_THICKNESS_MAP_SIDE;
    let map = thickness_uv_map(mesh, &bake.value, side, side).map_err(fail)?;
    Ok((map, BakeReport { vertices: mesh.vertex_count(), seconds: bake.bake_seconds, cache: cache_use }))
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
        self.prepare_on(loaded, Gpu::headless()?)
    }

    /// How deep the default head's wrinkles are in the job's face ([`rouge_model::skin::wrinkles`]):
    /// `None` without skin detail or on another mesh (the wrinkle map lies in the default head's
    /// UVs).
    ///
    /// # Errors
    /// Unknown Face Units or weights out of range, naming `--expression`.
    pub fn wrinkle_weights(&self) -> Result<Option<rouge_model::skin::WrinkleWeights>> {
        if !self.skin_detail || self.mesh.as_deref().is_some_and(|p| p.to_str() != Some("builtin:head")) {
            return Ok(None);
        }
        let invalid = |e: TargetError| RenderError::Invalid(e.to_string());
        let (units, _) = TargetSet::default_head().map_err(invalid)?.resolve(&self.face).map_err(invalid)?;
        Ok(Some(rouge_model::skin::WrinkleWeights::of(&units)))
    }

    /// [`RenderJob::prepare_loaded`] on a device already open (a long-lived renderer's: the
    /// Python package draws every frame on one).
    ///
    /// # Errors
    /// A texture that cannot be loaded (named), or what the renderer refuses.
    pub fn prepare_on(&self, loaded: &Loaded, gpu: Gpu) -> Result<Prepared> {
        let Loaded { mesh, look, scene, camera, rest_mesh, .. } = loaded;
        let SkinTextureImages { albedo, normal } = self.skin_textures()?;
        let mut renderer = Renderer::new(&gpu.device, &gpu.queue);
        renderer
            .set_hair_albedo(crate::gpu_mesh::HairAlbedo::with_products(look.mascara.as_ref(), look.brow_gel.as_ref()));
        renderer.set_mesh(mesh, scene.skin.albedo)?;
        renderer.set_textures(albedo.as_ref(), normal.as_ref())?;
        renderer.set_look(look)?;
        if self.skin_detail {
            let scale = rouge_model::skin::detail::tiles_per_uv(mesh)
                .ok_or_else(|| RenderError::Invalid("skin detail: the mesh has no UV area".into()))?;
            let (tile, regions) = default_skin_detail();
            renderer.set_skin_detail(Some((tile, regions, scale)))?;
            if let Some(weights) = self.wrinkle_weights()? {
                renderer.set_wrinkle_map(Some(rouge_model::skin::WrinkleMap::default_head()))?;
                renderer.set_wrinkle_weights(weights);
            }
        }
        let mut thickness_bake = None;
        if let SubsurfaceModel::Thickness { source: ThicknessSource::Baked(settings), .. } = &scene.skin.subsurface {
            let bake_mesh = if self.thickness_bake_rest_pose { rest_mesh.as_ref().unwrap_or(mesh) } else { mesh };
            let (map, report) = bake_thickness_map(bake_mesh, settings)?;
            renderer.set_local_thickness(Some((map.width, map.height, &map.texels)))?;
            thickness_bake = Some(report);
        }
        Ok(Prepared {
            gpu,
            renderer,
            scene: scene.clone(),
            camera: *camera,
            triangles: mesh.triangle_count(),
            size: (self.width, self.height),
            thickness_bake,
        })
    }

    /// The skin's textures the job names: the albedo (an `--albedo-map` file, or the skin maps
    /// baked with the blood following the face's expression) and the normal map; what
    /// [`RenderJob::prepare_loaded`] uploads and the glTF export bakes.
    ///
    /// # Errors
    /// Both an albedo map and skin maps; a texture that cannot be loaded (named); skin maps
    /// that cannot be made.
    pub fn skin_textures(&self) -> Result<SkinTextureImages> {
        let albedo = match (&self.albedo_map, &self.skin_maps) {
            (Some(_), Some(_)) => {
                return Err(RenderError::Invalid(
                    "an albedo map and skin maps both set the skin's colour: give one".into(),
                ));
            }
            (Some(path), None) => Some(load_texture(path)?),
            (None, Some(recipe)) => Some(skin_albedo(recipe, self.blood_flow.then_some(&self.face))?),
            (None, None) => None,
        };
        let normal = self.normal_map.as_deref().map(load_texture).transpose()?;
        Ok(SkinTextureImages { albedo, normal })
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
            LookChoice::Loaded(look) => (**look).clone(),
        };
        let mut scene = self.scene.clone();
        let env = self.env.as_deref().map(EnvMap::load_exr).transpose()?;
        if let Some(env) = &env {
            scene.environment = Some(env.sh_irradiance());
        }
        let mascara = self.mascara.or(look.mascara).filter(|m| !m.is_none());
        let (mut mesh, mut rest_mesh) = if self.face.is_neutral() && mascara.is_none() {
            (load_mesh(self.mesh.as_deref(), self.mesh_scale_mm, self.subdivision)?, None)
        } else {
            let (rest, posed) =
                posed_default_head(self.mesh.as_deref(), &self.face, mascara.as_ref(), self.subdivision)?;
            (posed, Some(rest))
        };
        if self.morph != 0.0 {
            let morphed = morph_to_bounding_sphere(&mesh, self.morph)
                .map_err(|e| RenderError::Invalid(format!("--morph {}: {e}", self.morph)))?;
            let before = std::mem::replace(&mut mesh, morphed);
            rest_mesh.get_or_insert(before);
        }
        if self.normal_map.is_some() {
            mesh.generate_tangents()?;
        }
        let bounds = Bounds::of(&mesh.positions).ok_or_else(|| RenderError::Invalid("empty mesh".into()))?;
        let camera = match self.close_up {
            None => Camera::framing(&bounds, self.yaw_deg, self.pitch_deg),
            Some(region) => Camera::close_up(&mesh, region, self.yaw_deg, self.pitch_deg).ok_or_else(|| {
                RenderError::Invalid(format!(
                    "close-up of the {}: the mesh has no vertex in that region (close-ups use the default head's UVs)",
                    region.name()
                ))
            })?,
        };
        // The mascara and brow gel drawn (the job's over the look's) are the look's from here
        // on: their colours go to the hairs' albedo and to exports.
        let brow_gel = self.brow_gel.or(look.brow_gel);
        let look = Look { mascara, brow_gel, ..look };
        Ok(Loaded { mesh, look, scene, env, camera, rest_mesh })
    }
}

/// The skin detail every render uses: the relief tile of seed 1 and the default head's region
/// map, made once per process.
pub fn default_skin_detail() -> (&'static rouge_model::skin::DetailTile, &'static rouge_model::skin::RegionDetail) {
    static DETAIL: std::sync::OnceLock<(rouge_model::skin::DetailTile, rouge_model::skin::RegionDetail)> =
        std::sync::OnceLock::new();
    let (tile, regions) = DETAIL
        .get_or_init(|| (rouge_model::skin::DetailTile::generate(1), rouge_model::skin::RegionDetail::default_head()));
    (tile, regions)
}

/// The default head subdivided `levels` times at rest (neutral, unshaped) and in `face`'s pose
/// with `mascara` on its lashes ([`LashRig`]), sharing triangles and UVs. `mesh` must be absent or `builtin:head`: the targets are the
/// default head's.
///
/// # Errors
/// Another mesh; unknown target names or weights out of range (naming `--expression`/`--shape`).
pub fn posed_default_head(
    mesh: Option<&Path>,
    face: &FacePose,
    mascara: Option<&Mascara>,
    levels: u32,
) -> Result<(TriangleMesh, TriangleMesh)> {
    if let Some(p) = mesh.filter(|p| p.to_str() != Some("builtin:head")) {
        return Err(RenderError::Invalid(format!(
            "--expression/--shape/--mascara move the default head's vertices; {} is another mesh (leave out --mesh)",
            p.display()
        )));
    }
    let invalid = |e: TargetError| RenderError::Invalid(e.to_string());
    let base = default_head().map_err(rouge_model::ModelError::from)?;
    let mut positions = base.positions.clone();
    TargetSet::default_head().map_err(invalid)?.apply(face, &mut positions).map_err(invalid)?;
    if let Some(m) = mascara {
        m.validate()?;
        LashRig::of(&base).apply(m, &mut positions);
    }
    let plan = SubdivisionPlan::new(&base, levels);
    let posed = plan.mesh(&positions);
    Ok((plan.rest().clone(), posed))
}

/// The skin's textures of a job ([`RenderJob::skin_textures`]), RGBA8, row 0 at v = 1.
#[derive(Clone, Debug, Default)]
pub struct SkinTextureImages {
    /// The albedo, sRGB-encoded.
    pub albedo: Option<image::RgbaImage>,
    /// The tangent-space normal map (OpenGL convention, +Y up).
    pub normal: Option<image::RgbaImage>,
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
    /// The mesh before the morph and the face's targets (the neutral, unshaped head), when the
    /// job deforms it.
    pub rest_mesh: Option<rouge_model::mesh::TriangleMesh>,
}

impl Prepared {
    /// Sets the antialiasing of the frames as `rouge render --aa` does: the mode's edge overdraw
    /// (with `mesh`'s edges, prepared here when it draws them) and the hairs' coverage; returns
    /// the mode's supersampling factor.
    ///
    /// # Errors
    /// As [`crate::aa::AaMode::frame`].
    pub fn set_antialiasing(
        &mut self,
        mode: crate::aa::AaMode,
        coverage: crate::aa::EdgeCoverage,
        mesh: &TriangleMesh,
    ) -> Result<u32> {
        let k = self.renderer.set_aa_mode(mode, coverage)?;
        if mode != crate::aa::AaMode::None && k == 1 {
            self.renderer.prepare_edges(mesh);
        }
        Ok(k)
    }

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

/// The skin of a tone, as `rouge render --skin-tone` gives it: `tone` a named tone of the spectral
/// skin model or an ITA° (`None`: light), painted from skin maps when `maps` gives their
/// conditions, seed and side (texels). Sets the scene's skin colour from the tone's spectrum
/// (where a tone is named or maps are made) and returns the maps' recipe.
///
/// # Errors
/// An unknown tone, an ITA outside the tones' span, a spectrum that cannot be made.
pub fn skin_of_tone(
    scene: &mut Scene,
    tone: Option<&str>,
    maps: Option<(rouge_model::skin::SkinConditions, u64, u32)>,
) -> Result<Option<SkinRecipe>> {
    use rouge_measure::skin::{SkinParams, skin_tone_or_ita};
    let invalid = |e: &dyn std::fmt::Display| RenderError::Invalid(e.to_string());
    let params = tone.map(skin_tone_or_ita).transpose().map_err(|e| invalid(&e))?;
    // The recipe keeps a tone's name; an ITA is kept as its parameters only.
    let tone_name = match tone {
        None => Some("light".to_string()),
        Some(spec) if spec.trim().parse::<f64>().is_err() => Some(spec.to_string()),
        Some(_) => None,
    };
    let recipe = maps.map(|(conditions, seed, size_px)| SkinRecipe {
        tone: tone_name,
        base: params.unwrap_or(SkinParams::LIGHT),
        conditions,
        seed,
        size_px,
    });
    if let Some(params) = recipe.as_ref().map(|r| r.base).or(params) {
        let spectrum = params.reflectance().map_err(|e| invalid(&e))?;
        scene.skin = crate::scene::Skin {
            subsurface: scene.skin.subsurface.clone(),
            diffuse: scene.skin.diffuse,
            ..crate::scene::Skin::from_spectrum(&spectrum)
        };
    }
    Ok(recipe)
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
    rouge_measure::file_set::write_atomic(path, &bytes)
        .map_err(|e| RenderError::file(path, format!("cannot write: {e}")))
}

/// Writes linear RGB radiance as a 32-bit float EXR, atomically.
///
/// # Errors
/// [`RenderError::File`] naming `path`.
pub fn write_exr(path: &Path, width: u32, height: u32, rgba: &[[f32; 4]]) -> Result<()> {
    let bytes = encode_exr(width, height, rgba).map_err(|e| RenderError::file(path, e))?;
    rouge_measure::file_set::write_atomic(path, &bytes)
        .map_err(|e| RenderError::file(path, format!("cannot write: {e}")))
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
