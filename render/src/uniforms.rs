//! The uniforms every pass sees (WGSL `Frame`, `Light`, `Layer` in shaders/common.wgsl) and how
//! they are built from the scene and the camera: view and projection, lights with their shadow
//! matrices. Keep in sync with common.wgsl; the shader tests (src/shader/tests.rs) check the
//! layouts with naga.

use crate::scene::{Camera, Light, LightKind, Scene};
use crate::shader::MAX_LAYERS;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use rouge_model::mesh::Bounds;

/// Most lights a scene may have.
pub const MAX_LIGHTS: usize = 4;
/// Shadow map size, texels.
pub const SHADOW_MAP_SIZE: u32 = 2048;

/// One light, as in WGSL `Light`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct LightUniform {
    /// Direction toward the light (w 0) or position (w 1).
    pub position: [f32; 4],
    /// Irradiance; w: squared distance to the scene centre for point lights.
    pub color: [f32; 4],
    /// Shadow layer (or −1), bias, normal offset, texel size.
    pub shadow: [f32; 4],
    /// Thickness translucency scale, near and far plane of the shadow projection (mm), 1 for a
    /// perspective projection.
    pub translucency: [f32; 4],
    /// Light's view-projection for its shadow map.
    pub shadow_view_proj: [[f32; 4]; 4],
}

/// One layer's specular parameters, as in WGSL `Layer`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct LayerUniform {
    /// Roughness, F0, full-coverage thickness, clarity of the finish.
    pub params: [f32; 4],
    /// The finish's levelling (how much the film fills the skin's pores), its shimmer's strength
    /// and spread (0 and 1 without a shimmer), unused.
    pub film: [f32; 4],
    /// The glitter's flake field (`crate::glitter::FlakeField`): cell edge (mm; 0 without
    /// glitter), flake edge (mm), probability of a flake in a cell, the flakes' spread.
    pub glitter: [f32; 4],
    /// The flakes' reflectance (linear sRGB), the preset's thickness (mm) at which the flakes
    /// have their density (a thinner film has proportionally fewer).
    pub glitter_color: [f32; 4],
}

/// The per-frame uniform, as in WGSL `Frame` (shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FrameUniform {
    /// World → clip.
    pub view_proj: [[f32; 4]; 4],
    /// Clip → world.
    pub inv_view_proj: [[f32; 4]; 4],
    /// World → view.
    pub view: [[f32; 4]; 4],
    /// Camera position.
    pub camera_pos: [f32; 4],
    /// Width, height, 1/width, 1/height.
    pub viewport: [f32; 4],
    /// Focal length (px), near, far, exposure.
    pub projection: [f32; 4],
    /// Skin roughness, F0, specular on, skin detail tiles per UV unit (0 without detail).
    pub skin: [f32; 4],
    /// SSS width, follow (mm), sample count, the skin's diffuse law (0 Lambert, 1 half-space).
    pub sss: [f32; 4],
    /// Background.
    pub background: [f32; 4],
    /// Lights, layers, table entries, unused.
    pub counts: [u32; 4],
    /// The wrinkle map's UV square (u0, v0, side, 1 / texels across; side 0 without wrinkles),
    /// then each family's depth (mm) on the left and on the right (`rouge_model::skin::wrinkles`).
    pub wrinkles: [[f32; 4]; 3],
    /// SH irradiance coefficients.
    pub sh: [[f32; 4]; 9],
    /// Lights.
    pub lights: [LightUniform; MAX_LIGHTS],
    /// Layers.
    pub layers: [LayerUniform; MAX_LAYERS],
    /// The mesh's mm per UV unit (the glitter's flake field; 0 without glitter), unused ×3.
    pub surface: [f32; 4],
}

/// The camera of one frame, as the passes and the picking need it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameView {
    /// World → clip.
    pub view_proj: Mat4,
    /// Near plane, mm.
    pub near: f32,
    /// Far plane, mm.
    pub far: f32,
    /// Focal length, pixels.
    pub focal_px: f32,
}

impl FrameView {
    /// The view of `camera` at `size` around a mesh with `bounds`.
    pub fn new(camera: &Camera, bounds: &Bounds, (width, height): (u32, u32)) -> FrameView {
        let (near, far) = camera.clip_planes_around(bounds);
        let aspect = width as f32 / height as f32;
        let view_proj = camera.projection(aspect, near, far) * camera.view();
        FrameView { view_proj, near, far, focal_px: camera.focal_px(height) }
    }
}

/// What the frame uniform takes from the scene: the frame plan keeps it, so that recording a
/// frame never goes back to the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneConstants {
    /// The lights.
    pub lights: Vec<Light>,
    /// Exposure of the tone mapping.
    pub exposure: f32,
    /// Skin roughness, F0, specular on, unused.
    pub skin: [f32; 4],
    /// SSS width, follow (mm), sample count, the skin's diffuse law (0 Lambert, 1 half-space).
    pub sss: [f32; 4],
    /// Background.
    pub background: [f32; 4],
    /// SH irradiance coefficients (zero without an environment).
    pub sh: [[f32; 4]; 9],
}

impl SceneConstants {
    /// What the frame uniform takes from `scene`.
    pub fn new(scene: &Scene) -> SceneConstants {
        let [r, g, b] = scene.background;
        SceneConstants {
            lights: scene.lights.clone(),
            exposure: scene.exposure,
            skin: [scene.skin.roughness, scene.skin.f0(), if scene.specular { 1.0 } else { 0.0 }, 0.0],
            sss: [
                scene.sss.width,
                scene.sss.follow_mm,
                scene.sss.samples as f32,
                if scene.skin.diffuse == crate::scene::DiffuseLaw::HalfSpace { 1.0 } else { 0.0 },
            ],
            background: [r, g, b, 0.0],
            sh: scene.environment.map_or([[0.0; 4]; 9], |sh| sh.to_gpu()),
        }
    }
}

impl FrameUniform {
    /// The uniform of one frame: the scene's `constants` seen by `camera` at `size`, the mesh's
    /// `bounds`, and the uploaded look's `layers` (count and specular parameters).
    pub fn new(
        constants: &SceneConstants,
        camera: &Camera,
        view: &FrameView,
        bounds: &Bounds,
        size: (u32, u32),
        layers: (u32, [LayerUniform; MAX_LAYERS]),
    ) -> FrameUniform {
        let (width, height) = (size.0 as f32, size.1 as f32);
        FrameUniform {
            view_proj: view.view_proj.to_cols_array_2d(),
            inv_view_proj: view.view_proj.inverse().to_cols_array_2d(),
            view: camera.view().to_cols_array_2d(),
            camera_pos: camera.position().extend(1.0).to_array(),
            viewport: [width, height, 1.0 / width, 1.0 / height],
            projection: [view.focal_px, view.near, view.far, constants.exposure],
            skin: constants.skin,
            sss: constants.sss,
            background: constants.background,
            counts: [constants.lights.len() as u32, layers.0, rouge_measure::layer_table::TABLE_ENTRIES as u32, 0],
            wrinkles: [[0.0; 4]; 3],
            sh: constants.sh,
            lights: light_uniforms(&constants.lights, bounds),
            layers: layers.1,
            surface: [0.0; 4],
        }
    }
}

/// An orthographic view-projection looking at the sphere (`centre`, `radius`) from the direction
/// `toward` (from the centre toward the eye), enclosing it, with its near and far planes (mm):
/// what the shadow maps of directional lights and the dipole passes' views use.
pub fn orthographic_toward(toward: Vec3, centre: Vec3, radius: f32) -> (Mat4, f32, f32) {
    let t = toward.normalize_or(Vec3::Z);
    let eye = centre + t * 2.5 * radius;
    let up = if t.abs().y > 0.95 { Vec3::Z } else { Vec3::Y };
    let view = glam::camera::rh::view::look_at_mat4(eye, centre, up);
    let (near, far) = (0.5 * radius, 4.5 * radius);
    let proj = glam::camera::rh::proj::directx::orthographic(-radius, radius, -radius, radius, near, far);
    (proj * view, near, far)
}

/// The scene's `lights` around a mesh with `bounds`; shadowing lights get consecutive shadow
/// map layers in scene order, with an orthographic (directional) or perspective (point) matrix
/// that encloses the mesh's bounding sphere.
pub fn light_uniforms(lights: &[Light], bounds: &Bounds) -> [LightUniform; MAX_LIGHTS] {
    let centre = bounds.center();
    let radius = 0.5 * bounds.size().length();
    let mut out = [LightUniform::default(); MAX_LIGHTS];
    let mut shadow_layer = 0;
    for (slot, l) in out.iter_mut().zip(lights) {
        let (position, d2, light_pos, to_centre) = match l.kind {
            LightKind::Directional { toward } => {
                let t = toward.normalize_or_zero();
                ([t.x, t.y, t.z, 0.0], 0.0, centre + t * 2.5 * radius, None)
            }
            LightKind::Point { position } => {
                let d2 = (position - centre).length_squared().max(1e-6);
                ([position.x, position.y, position.z, 1.0], d2, position, Some(d2.sqrt()))
            }
        };
        let mut u = LightUniform {
            position,
            color: [l.irradiance[0], l.irradiance[1], l.irradiance[2], d2],
            shadow: [-1.0, 0.0, 0.0, 0.0],
            translucency: [l.translucency_scale, 0.0, 0.0, 0.0],
            ..Default::default()
        };
        if l.shadows {
            let (view_proj, near, far, perspective) = match to_centre {
                None => {
                    let (view_proj, near, far) = orthographic_toward(light_pos - centre, centre, radius);
                    (view_proj, near, far, 0.0)
                }
                Some(d) => {
                    let up = if (light_pos - centre).normalize_or_zero().abs().y > 0.95 { Vec3::Z } else { Vec3::Y };
                    let light_view = glam::camera::rh::view::look_at_mat4(light_pos, centre, up);
                    let half = (radius / d).clamp(0.05, 0.99).asin() * 1.05;
                    let (near, far) = ((d - radius).max(1.0), d + radius);
                    let proj = glam::camera::rh::proj::directx::perspective(2.0 * half, 1.0, near, far);
                    (proj * light_view, near, far, 1.0)
                }
            };
            u.translucency = [l.translucency_scale, near, far, perspective];
            let texel_mm = 2.0 * radius / SHADOW_MAP_SIZE as f32;
            u.shadow = [shadow_layer as f32, 0.0005, 1.5 * texel_mm, 1.0 / SHADOW_MAP_SIZE as f32];
            u.shadow_view_proj = view_proj.to_cols_array_2d();
            shadow_layer += 1;
        }
        *slot = u;
    }
    out
}
