//! The cube-atlas subsurface model's passes (\[Benmounah2009\], geometry and derivations in
//! [`crate::cube_atlas`]): `irradiance` draws the mesh onto the six faces of its bounding cube
//! every frame (irradiance entering the medium, n·p, normal, depth), `gather` adds, per skin
//! pixel, the local dipole gather on the face that sees the point and the global term through
//! thin parts. Both run every frame, so a deforming mesh is never seen through stale data.

pub mod gather;
pub mod irradiance;

use crate::cube_atlas::{AtlasFrame, AtlasSettings, MIN_AREA_COSINE, face_axes};
use crate::diffusion::{ProfileModel, medium_profiles};
use crate::env::fresnel_band_kernels;
use bytemuck::{Pod, Zeroable};
use rouge_model::medium::Medium;
use rouge_model::mesh::Bounds;
use std::f64::consts::PI;

/// The cube-atlas passes' uniform, as WGSL `AtlasPass` (shaders/atlas_common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct AtlasUniform {
    /// Per face: world → clip.
    pub view_proj: [[[f32; 4]; 4]; 6],
    /// Per face: outward axis.
    pub axis: [[f32; 4]; 6],
    /// Per face: image right.
    pub right: [[f32; 4]; 6],
    /// Per face: image up.
    pub up: [[f32; 4]; 6],
    /// Centre (mm), half side (mm).
    pub cube: [f32; 4],
    /// Per channel: α′, σ_tr (mm⁻¹), z_r, z_v (mm).
    pub medium: [[f32; 4]; 3],
    /// η, texel (mm), face side (texels), smallest area cosine.
    pub params: [f32; 4],
    /// Kernel half side (taps), adaptive, self-occlusion test, global term (0 off, 1 real
    /// source, 2 slab).
    pub settings: [u32; 4],
    /// Kernel radius at sp = 1 (mm), unused ×3.
    pub kernel: [f32; 4],
    /// Fresnel scale of the SH bands 0, 1, 2.
    pub sh_fresnel: [f32; 4],
}

impl AtlasUniform {
    /// The uniform for `medium` around a mesh with `bounds`.
    pub fn new(medium: &Medium, settings: &AtlasSettings, bounds: &Bounds) -> AtlasUniform {
        let frame = AtlasFrame::new(bounds, settings.atlas_px);
        let mut u = AtlasUniform::zeroed();
        for f in 0..6 {
            let (a, r, v) = face_axes(f);
            u.view_proj[f] = frame.view_proj(f).to_cols_array_2d();
            u.axis[f] = a.extend(0.0).to_array();
            u.right[f] = r.extend(0.0).to_array();
            u.up[f] = v.extend(0.0).to_array();
        }
        u.cube = frame.centre.extend(frame.half_mm).to_array();
        let profiles = medium_profiles(medium, ProfileModel::ClassicDipole);
        for (c, p) in profiles.iter().enumerate() {
            u.medium[c] = p.classic_constants().map(|v| v as f32);
        }
        u.kernel = [settings.kernel_radius_mm(1.0, &profiles), 0.0, 0.0, 0.0];
        u.params = [medium.eta as f32, frame.texel_mm(), settings.atlas_px as f32, MIN_AREA_COSINE];
        u.settings = [
            (settings.kernel_max - 1) / 2,
            u32::from(settings.adaptive),
            settings.occlusion.code(),
            settings.global as u32,
        ];
        let k = fresnel_band_kernels(medium.eta);
        u.sh_fresnel = [(k[0] / PI) as f32, (k[1] / (2.0 * PI / 3.0)) as f32, (k[2] / (PI / 4.0)) as f32, 0.0];
        u
    }
}

/// What the cube-atlas passes need of the scene, planned once a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct AtlasStep {
    /// The atlas's settings (checked).
    pub settings: AtlasSettings,
    /// The skin's medium.
    pub medium: Medium,
}

/// The atlas: six layers of irradiance (+ n·p), normals (+ medium flag) and depth, and the
/// uniform. Resized when the settings change; the contents are redrawn every frame.
#[derive(Debug)]
pub struct AtlasResources {
    /// The `AtlasPass` uniform.
    pub uniform: wgpu::Buffer,
    /// Irradiance entering the medium (rgb) and n·p (a), Rgba16Float, six layers.
    pub irradiance: wgpu::Texture,
    /// Normal (xyz) and medium flag (w), Rgba16Float, six layers.
    pub normals: wgpu::Texture,
    /// Depth, six layers.
    pub depths: wgpu::Texture,
    /// The cube the atlas was last drawn for.
    pub frame: Option<AtlasFrame>,
    min_layers: u32,
    /// What the uniform holds: σa, σs′, η, the settings and the mesh's bounds.
    written: Option<UniformInputs>,
}

/// What [`AtlasUniform::new`] is made from.
type UniformInputs = ([f64; 3], [f64; 3], f64, AtlasSettings, Bounds);

impl AtlasResources {
    /// Stand-ins of 1×1 until a frame needs the atlas, on a device whose
    /// [`crate::targets::Formats::min_array_layers`] is `min_layers`.
    pub fn new(device: &wgpu::Device, min_layers: u32) -> AtlasResources {
        let uniform = crate::wgpu_util::uniform_buffer(device, "Atlas::uniform", std::mem::size_of::<AtlasUniform>());
        let (irradiance, normals, depths) = Self::textures(device, 1, min_layers);
        AtlasResources { uniform, irradiance, normals, depths, frame: None, min_layers, written: None }
    }

    /// Six faces (seven layers on GL: [`crate::targets::array_layers`]).
    fn textures(device: &wgpu::Device, px: u32, min_layers: u32) -> (wgpu::Texture, wgpu::Texture, wgpu::Texture) {
        let layers = crate::targets::array_layers(6, min_layers);
        use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};
        use wgpu::TextureUsages as U;
        let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        let t = |label, format| crate::wgpu_util::texture(device, label, (px, px), layers, format, usage, &[]);
        (t("Atlas::irradiance", HDR_FORMAT), t("Atlas::normals", HDR_FORMAT), t("Atlas::depths", DEPTH_FORMAT))
    }

    /// Sizes the atlas for `settings`.
    pub fn ensure(&mut self, device: &wgpu::Device, settings: &AtlasSettings) {
        if self.irradiance.width() != settings.atlas_px {
            (self.irradiance, self.normals, self.depths) = Self::textures(device, settings.atlas_px, self.min_layers);
        }
    }

    /// Writes the uniform for `medium` and `settings` around a mesh with `bounds`, unless it
    /// holds them already: a still mesh redoes neither the profiles nor the Fresnel bands'
    /// integrals every frame; a deforming one (new bounds) does.
    pub fn update(&mut self, queue: &wgpu::Queue, medium: &Medium, settings: &AtlasSettings, bounds: &Bounds) {
        let inputs = (medium.sigma_a_per_mm, medium.sigma_s_prime_per_mm, medium.eta, *settings, *bounds);
        if self.written.as_ref() == Some(&inputs) {
            return;
        }
        let u = AtlasUniform::new(medium, settings, bounds);
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&u));
        self.frame = Some(AtlasFrame::new(bounds, settings.atlas_px));
        self.written = Some(inputs);
    }

    /// The atlas as last drawn.
    ///
    /// # Errors
    /// [`crate::RenderError::Invalid`] before any frame drew it; GPU failures.
    pub fn read(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> crate::Result<crate::cube_atlas::AtlasImage> {
        use crate::wgpu_util::{halves_to_f32, read_texture_layer};
        let frame =
            self.frame.ok_or_else(|| crate::RenderError::Invalid("no frame has drawn the cube atlas yet".into()))?;
        let mut image =
            crate::cube_atlas::AtlasImage { frame, irradiance: Vec::new(), normals: Vec::new(), depths: Vec::new() };
        for f in 0..6 {
            image.irradiance.push(halves_to_f32(&read_texture_layer(device, queue, &self.irradiance, f, 8)?));
            image.normals.push(halves_to_f32(&read_texture_layer(device, queue, &self.normals, f, 8)?));
            image.depths.push(bytemuck::pod_collect_to_vec(&read_texture_layer(device, queue, &self.depths, f, 4)?));
        }
        Ok(image)
    }
}
