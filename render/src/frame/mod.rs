//! The frame plan: from the scene, what the renderer has uploaded (the look's layers, the skin's
//! maps) and the frame settings, which passes run, in which order, reading and writing which
//! resources, and what is skipped and why. The plan carries everything the frame needs of the
//! scene (each [`Step`] holds its pass's slots, directions and uniforms' contents, and
//! [`FramePlan::constants`] the frame uniform's), so [`crate::Renderer::render`] only walks it;
//! `rouge render --explain` prints it ([`FramePlan::explain`]).
//!
//! Only what the scene uses runs or is allocated: no shadow pass for a light that casts no
//! shadow; no SSS passes (nor their targets) when the skin's subsurface model is `none` or the
//! width is 0; no thickness targets, table lookups or layer lobes for a bare look; no SH code
//! without an environment. Shaders are specialised per [`Variant`] accordingly.
//!
//! [`FramePlan::new`] reads like the frame: validation, then one stage per part of it
//! (`stages.rs`): shadows, the subsurface model's settings, the variant, the G-buffer, lighting,
//! the subsurface model's passes, the bounce between facing parts, the blur, the hair,
//! composition, edge overdraw. The render targets are the ones
//! the passes read or write.

mod explain;
mod stages;

use crate::aa::EdgeAa;
use crate::error::{RenderError, Result};
use crate::scene::Scene;
use crate::shader::Variant;
use crate::sss::SeparableKernel;
use crate::targets::Target;
use crate::uniforms::{MAX_LIGHTS, SceneConstants};

pub use crate::passes::Step;
pub use crate::passes::cube_atlas::AtlasStep;
pub use crate::passes::dipole::{DipoleStep, DirectionalLight};
pub use crate::passes::edge_overdraw::EdgeStep;
pub use crate::passes::shadow::ShadowStep;
pub use crate::passes::sss::{Direction, SssStep};

/// What the renderer has uploaded that the plan depends on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Uploaded {
    /// Layers of the look (0 = bare).
    pub layers: u32,
    /// A skin albedo texture is bound.
    pub albedo_map: bool,
    /// A normal map is bound.
    pub normal_map: bool,
    /// A baked local-thickness map is bound ([`crate::Renderer::set_local_thickness`]).
    pub local_thickness_map: bool,
    /// The skin's microgeometry is bound ([`crate::Renderer::set_skin_detail`]).
    pub skin_detail: bool,
    /// The layers with glitter, one bit per layer index (`crate::gpu_look::GpuLook::glitter`).
    pub glitter: u8,
    /// The shadow maps kept from an earlier frame and current for this one (bit i: layer i):
    /// neither the mesh nor the light has moved since they were drawn
    /// (`crate::passes::shadow::ShadowKey`).
    pub shadow_maps_kept: u8,
    /// The mesh's hair strands drawn as fibres (0: no hair pass).
    pub hair_strands: u32,
}

/// The output of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameSettings {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Tone-mapped sRGB (true) or linear radiance (false).
    pub display: bool,
    /// The largest texture side the device takes.
    pub max_side: u32,
    /// The most bytes of colour attachments per pixel the device takes (WebGPU's default: 32).
    pub max_color_bytes: u32,
    /// Discontinuity edge overdraw (\[Sander2001\]).
    pub aa: EdgeAa,
    /// The hairs drawn with their box-filter coverage (any antialiasing but none).
    pub hair_aa: bool,
}

/// What a pass reads or writes: a render target of the frame, or data uploaded or made by other
/// passes (which the passes own and size themselves).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resource {
    /// A render target of the frame (allocated because a pass uses it).
    Target(Target),
    /// The mesh.
    Mesh,
    /// The mesh as posed this frame (its current positions).
    PosedMesh,
    /// A light of the scene, by index, and its kind.
    Light {
        /// Its index in the scene.
        index: usize,
        /// `directional` or `point`.
        kind: &'static str,
    },
    /// The directional lights the dipole passes take.
    DirectionalLights(u32),
    /// One layer of the shadow-map array.
    ShadowMap(u32),
    /// The shadow-map array.
    ShadowMaps,
    /// The look's thickness maps.
    ThicknessMaps(u32),
    /// The look's layer tables.
    LayerTables,
    /// The skin's albedo texture.
    AlbedoMap,
    /// The normal map.
    NormalMap,
    /// The baked local-thickness map.
    LocalThicknessMap,
    /// The skin's microgeometry: relief tile, region map and (on the default head) wrinkle map.
    SkinDetail,
    /// The glitter of the layers in the mask (bit i: layer i), as flake fields.
    Glitter(u8),
    /// The environment's spherical-harmonics irradiance.
    Environment,
    /// The dipole models' light G-buffer: light views and side, texels.
    LightGbuffer {
        /// Light views.
        slots: u32,
        /// Side, texels.
        px: u32,
    },
    /// The dipole models' radiance maps.
    RadianceMaps {
        /// Directions K.
        directions: u32,
        /// Side, texels.
        px: u32,
        /// Disk samples a texel.
        samples: u32,
        /// The BSSRDF's name.
        kind: &'static str,
        /// Accumulated over frames.
        progressive: bool,
    },
    /// The cube atlas, six faces of this side, texels.
    CubeAtlas(u32),
    /// The mesh's discontinuity edges, sorted back to front or classified on the GPU.
    MeshEdges {
        /// Sorted on the CPU.
        sorted: bool,
    },
    /// A copy of the display image.
    DisplayCopy,
    /// The mesh's hair strands, sorted back to front.
    Strands(u32),
}

/// How a pass writes a resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Replaced.
    Replace,
    /// Added to.
    Add,
    /// Blended over, depth tested.
    Blend,
}

/// A planned pass with what it reads and writes.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedPass {
    /// The step: the pass and what it is given.
    pub step: Step,
    /// What it reads.
    pub reads: Vec<Resource>,
    /// What it writes, and how.
    pub writes: Vec<(Resource, Access)>,
}

/// A pass, target or piece of shader code left out, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// What is left out.
    pub what: String,
    /// Why.
    pub why: String,
}

/// The plan of one frame.
#[derive(Clone, Debug)]
pub struct FramePlan {
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// The shader variant.
    pub variant: Variant,
    /// The passes, in order.
    pub passes: Vec<PlannedPass>,
    /// What is left out, and why.
    pub skipped: Vec<Skipped>,
    /// Shadow maps needed.
    pub shadow_maps: u32,
    /// The separable kernel, when the SSS passes run.
    pub kernel: Option<SeparableKernel>,
    /// The render targets the passes read or write, sorted.
    pub targets: Vec<Target>,
    /// What the frame uniform takes from the scene.
    pub constants: SceneConstants,
    /// The skin material in words: its medium, albedo and subsurface model.
    pub material: String,
}

impl FramePlan {
    /// Plans a frame of `scene` with the `uploaded` look and maps at `settings`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a zero or oversized image, too many lights, a negative or
    /// non-finite SSS width, an SSS sample count or range the kernel refuses, or bounce settings
    /// out of range.
    pub fn new(scene: &Scene, uploaded: Uploaded, settings: FrameSettings) -> Result<FramePlan> {
        validate(scene, settings)?;
        let mut plan = stages::Planner::default();
        let shadow_maps = plan.shadows(scene, uploaded.shadow_maps_kept);
        let models = plan.subsurface_models(scene, uploaded, shadow_maps)?;
        let variant = Variant {
            layers: uploaded.layers,
            shadows: shadow_maps > 0,
            env: scene.environment.is_some(),
            display: settings.display,
            albedo_map: uploaded.albedo_map,
            normal_map: uploaded.normal_map,
            skin_detail: uploaded.skin_detail,
            thickness: models.thickness_variant(),
            dipole: models.dipole.is_some() || models.atlas.is_some(),
            atlas: models.atlas.is_some(),
            glitter: uploaded.glitter != 0 && uploaded.layers > 0 && scene.specular,
            hair: uploaded.hair_strands > 0,
        };
        let mut variant = variant;
        let glitter_bytes = crate::passes::gbuffer::bytes_per_sample(variant);
        if variant.glitter && glitter_bytes > settings.max_color_bytes {
            variant.glitter = false;
            plan.skip(
                "glitter",
                format!(
                    "its G-buffer would take {glitter_bytes} bytes a pixel, the device takes {}",
                    settings.max_color_bytes
                ),
            );
        }
        plan.gbuffer(variant);
        plan.glitter(uploaded.glitter, scene.specular);
        let half_space = plan.half_space_law(scene, variant.normal_map || variant.skin_detail)?;
        plan.lighting(variant, uploaded.glitter, half_space);
        plan.subsurface_passes(variant, models);
        let skin = plan.bounce(scene, variant)?;
        let kernel = plan.screen_space(scene, skin)?;
        let skin = if kernel.is_some() { Target::Scattered } else { skin };
        plan.hair(variant, uploaded.hair_strands, settings.hair_aa);
        plan.composite(variant, skin);
        plan.edge_overdraw(settings.aa, variant.display);
        let targets = plan.targets();
        Ok(FramePlan {
            size: (settings.width, settings.height),
            variant,
            passes: plan.passes,
            skipped: plan.skipped,
            shadow_maps,
            kernel,
            targets,
            constants: SceneConstants::new(scene),
            material: explain::material(&scene.skin, half_space.is_some_and(|l| l.curvature.is_some())),
        })
    }
}

/// The requests no frame can take: a zero or oversized image, too many lights, a bad SSS width.
fn validate(scene: &Scene, settings: FrameSettings) -> Result<()> {
    let (width, height, max) = (settings.width, settings.height, settings.max_side);
    if width == 0 || height == 0 || width > max || height > max {
        return Err(RenderError::Invalid(format!("image size {width}×{height}: each side must be 1 to {max}")));
    }
    if scene.lights.len() > MAX_LIGHTS {
        return Err(RenderError::Invalid(format!(
            "{} lights: the renderer takes at most {MAX_LIGHTS}",
            scene.lights.len()
        )));
    }
    if !(scene.sss.width.is_finite() && scene.sss.width >= 0.0) {
        return Err(RenderError::Invalid(format!("SSS width {}: must be ≥ 0", scene.sss.width)));
    }
    Ok(())
}

#[cfg(test)]
mod tests;
