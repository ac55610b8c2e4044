//! The uniforms every pass sees (WGSL `Frame`, `Light`, `Layer` in shaders/common.wgsl) and how
//! they are built from the scene and the camera: view and projection, lights with their shadow
//! matrices. Keep in sync with common.wgsl; tests/shaders.rs checks the layouts with naga.

use crate::passes::dipole::DipoleUniform;
use crate::passes::sss::SssUniform;
use crate::passes::thickness::ThicknessUniform;
use crate::scene::{Camera, LightKind, Scene};
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
    /// Roughness, F0, full-coverage thickness, unused.
    pub params: [f32; 4],
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
    /// Skin roughness, F0, specular on, unused.
    pub skin: [f32; 4],
    /// SSS width, follow (mm), sample count, unused.
    pub sss: [f32; 4],
    /// Background.
    pub background: [f32; 4],
    /// Lights, layers, table entries, unused.
    pub counts: [u32; 4],
    /// SH irradiance coefficients.
    pub sh: [[f32; 4]; 9],
    /// Lights.
    pub lights: [LightUniform; MAX_LIGHTS],
    /// Layers.
    pub layers: [LayerUniform; MAX_LAYERS],
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
        let radius = 0.5 * bounds.size().length();
        let (near, far) = camera.clip_planes(radius.max(camera.distance * 0.02));
        let aspect = width as f32 / height as f32;
        let view_proj = camera.projection(aspect, near, far) * camera.view();
        FrameView { view_proj, near, far, focal_px: camera.focal_px(height) }
    }
}

impl FrameUniform {
    /// The uniform of one frame: `scene` seen by `camera` at `size`, the mesh's `bounds`, and the
    /// uploaded look's `layers` (count and specular parameters).
    pub fn new(
        scene: &Scene,
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
            projection: [view.focal_px, view.near, view.far, scene.exposure],
            skin: [scene.skin.roughness, scene.skin.f0(), if scene.specular { 1.0 } else { 0.0 }, 0.0],
            sss: [scene.sss.width, scene.sss.follow_mm, scene.sss.samples as f32, 0.0],
            background: [scene.background[0], scene.background[1], scene.background[2], 0.0],
            counts: [scene.lights.len() as u32, layers.0, rouge_measure::layer_table::TABLE_ENTRIES as u32, 0],
            sh: scene.environment.map_or([[0.0; 4]; 9], |sh| sh.to_gpu()),
            lights: light_uniforms(scene, bounds),
            layers: layers.1,
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

/// The lights of `scene` around a mesh with `bounds`; shadowing lights get consecutive shadow
/// map layers in scene order, with an orthographic (directional) or perspective (point) matrix
/// that encloses the mesh's bounding sphere.
pub fn light_uniforms(scene: &Scene, bounds: &Bounds) -> [LightUniform; MAX_LIGHTS] {
    let centre = bounds.center();
    let radius = 0.5 * bounds.size().length();
    let mut lights = [LightUniform::default(); MAX_LIGHTS];
    let mut shadow_layer = 0;
    for (slot, l) in lights.iter_mut().zip(&scene.lights) {
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
    lights
}

/// A uniform struct's WGSL name, size in bytes, and (field, offset) pairs.
pub type UniformLayout = (&'static str, usize, Vec<(&'static str, usize)>);

/// Field offsets of the uniforms, for the layout test against naga's view of the WGSL.
pub fn uniform_layouts() -> Vec<UniformLayout> {
    use crate::passes::cube_atlas::AtlasUniform;
    use std::mem::{offset_of, size_of};
    vec![
        (
            "Frame",
            size_of::<FrameUniform>(),
            vec![
                ("view_proj", offset_of!(FrameUniform, view_proj)),
                ("inv_view_proj", offset_of!(FrameUniform, inv_view_proj)),
                ("view", offset_of!(FrameUniform, view)),
                ("camera_pos", offset_of!(FrameUniform, camera_pos)),
                ("viewport", offset_of!(FrameUniform, viewport)),
                ("projection", offset_of!(FrameUniform, projection)),
                ("skin", offset_of!(FrameUniform, skin)),
                ("sss", offset_of!(FrameUniform, sss)),
                ("background", offset_of!(FrameUniform, background)),
                ("counts", offset_of!(FrameUniform, counts)),
                ("sh", offset_of!(FrameUniform, sh)),
                ("lights", offset_of!(FrameUniform, lights)),
                ("layers", offset_of!(FrameUniform, layers)),
            ],
        ),
        (
            "Light",
            size_of::<LightUniform>(),
            vec![
                ("position", offset_of!(LightUniform, position)),
                ("color", offset_of!(LightUniform, color)),
                ("shadow", offset_of!(LightUniform, shadow)),
                ("translucency", offset_of!(LightUniform, translucency)),
                ("shadow_view_proj", offset_of!(LightUniform, shadow_view_proj)),
            ],
        ),
        ("Layer", size_of::<LayerUniform>(), vec![("params", offset_of!(LayerUniform, params))]),
        (
            "DipolePass",
            size_of::<DipoleUniform>(),
            vec![
                ("channel", offset_of!(DipoleUniform, channel)),
                ("extra", offset_of!(DipoleUniform, extra)),
                ("boundary", offset_of!(DipoleUniform, boundary)),
                ("classic", offset_of!(DipoleUniform, classic)),
                ("sampling", offset_of!(DipoleUniform, sampling)),
                ("fixes", offset_of!(DipoleUniform, fixes)),
                ("counts", offset_of!(DipoleUniform, counts)),
                ("light_view_proj", offset_of!(DipoleUniform, light_view_proj)),
                ("light_inv_view_proj", offset_of!(DipoleUniform, light_inv_view_proj)),
                ("light_info", offset_of!(DipoleUniform, light_info)),
                ("dir_view_proj", offset_of!(DipoleUniform, dir_view_proj)),
                ("dir_axis", offset_of!(DipoleUniform, dir_axis)),
                ("dir_planes", offset_of!(DipoleUniform, dir_planes)),
            ],
        ),
        (
            "AtlasPass",
            size_of::<AtlasUniform>(),
            vec![
                ("view_proj", offset_of!(AtlasUniform, view_proj)),
                ("axis", offset_of!(AtlasUniform, axis)),
                ("right", offset_of!(AtlasUniform, right)),
                ("up", offset_of!(AtlasUniform, up)),
                ("cube", offset_of!(AtlasUniform, cube)),
                ("medium", offset_of!(AtlasUniform, medium)),
                ("params", offset_of!(AtlasUniform, params)),
                ("settings", offset_of!(AtlasUniform, settings)),
                ("kernel", offset_of!(AtlasUniform, kernel)),
                ("sh_fresnel", offset_of!(AtlasUniform, sh_fresnel)),
            ],
        ),
        (
            "ThicknessPass",
            size_of::<ThicknessUniform>(),
            vec![
                ("materials", offset_of!(ThicknessUniform, materials)),
                ("falloff", offset_of!(ThicknessUniform, falloff)),
                ("kind", offset_of!(ThicknessUniform, kind)),
            ],
        ),
        (
            "EdgePass",
            size_of::<crate::passes::edge_overdraw::EdgeUniform>(),
            vec![
                ("params", offset_of!(crate::passes::edge_overdraw::EdgeUniform, params)),
                ("flags", offset_of!(crate::passes::edge_overdraw::EdgeUniform, flags)),
            ],
        ),
        (
            "SssPass",
            size_of::<SssUniform>(),
            vec![
                ("dir", offset_of!(SssUniform, dir)),
                ("count", offset_of!(SssUniform, count)),
                ("samples", offset_of!(SssUniform, samples)),
            ],
        ),
    ]
}
