//! The dipole subsurface models' passes (\[DirDipoleThesis\] section 4.2, after \[Frisvad2014\]):
//! `light` renders a light G-buffer per directional light (normals; positions from depth),
//! `radiance` renders K orthographic radiance maps in which each texel gathers the BSSRDF over a
//! disk of the light G-buffer, and `combine` averages, per pixel, the maps of the directions that
//! see the point. The BSSRDF is the directional dipole or, for comparison, the standard dipole
//! ([`crate::directional_dipole`]); [`DipoleUniform`] carries both. The radiance maps do not
//! depend on the camera: while the lights, the mesh and the settings stay, new disk samples are
//! blended in frame after frame ([`DipoleSettings::progressive`]).

pub mod combine;
pub mod light;
pub mod radiance;

use crate::diffusion::{ChannelProfile, ProfileModel, medium_profiles};
use crate::directional_dipole::{
    DipoleKind, DipoleSettings, DipoleSource, DirectionalDipole, MAX_DIRECTIONS, direction,
};
use crate::scene::{LightKind, Scene};
use crate::uniforms::{MAX_LIGHTS, orthographic_toward};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use rouge_model::medium::Medium;
use rouge_model::mesh::Bounds;

/// The dipole passes' uniform, as WGSL `DipolePass` (shaders/dipole_common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct DipoleUniform {
    /// Per channel: D, σ_tr, d_e, A.
    pub channel: [[f32; 4]; 3],
    /// Per channel: (3σ′_t)⁻², α′, classic z_r, classic z_v.
    pub extra: [[f32; 4]; 3],
    /// C_φ(η), C_E(η), 1/(4C_φ(1/η)), η.
    pub boundary: [f32; 4],
    /// Classic σ_tr per channel; w 0 standard, 1 directional as published, 2 directional with
    /// the mean-free-path source.
    pub classic: [f32; 4],
    /// Sampling σ, N, frame index, largest radius (mm).
    pub sampling: [f32; 4],
    /// ε_g, ε_c, ε_b (mm), fix bits.
    pub fixes: [f32; 4],
    /// K, light slots, light map side, radiance map side.
    pub counts: [u32; 4],
    /// Per light slot: world → clip.
    pub light_view_proj: [[[f32; 4]; 4]; MAX_LIGHTS],
    /// Per light slot: clip → world.
    pub light_inv_view_proj: [[[f32; 4]; 4]; MAX_LIGHTS],
    /// Per light slot: scene light index, near, far, mm per light G-buffer texel.
    pub light_info: [[f32; 4]; MAX_LIGHTS],
    /// Per direction: world → clip.
    pub dir_view_proj: [[[f32; 4]; 4]; MAX_DIRECTIONS],
    /// Per direction: toward the viewer.
    pub dir_axis: [[f32; 4]; MAX_DIRECTIONS],
    /// Per direction: near, far (mm).
    pub dir_planes: [[f32; 4]; MAX_DIRECTIONS],
}

/// A directional light of the scene as the dipole passes take it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Its index in the scene (its irradiance and shadow are in the frame uniform's lights).
    pub index: usize,
    /// Toward the light.
    pub toward: Vec3,
    /// Irradiance, linear RGB.
    pub irradiance: [f32; 3],
}

/// What the dipole passes need of the scene, planned once a frame: the model, the medium, the
/// settings and the directional lights (point lights get no subsurface light from them).
#[derive(Clone, Debug, PartialEq)]
pub struct DipoleStep {
    /// Which BSSRDF.
    pub kind: DipoleKind,
    /// The skin's medium.
    pub medium: Medium,
    /// The passes' settings.
    pub settings: DipoleSettings,
    /// The light views, at most [`MAX_LIGHTS`].
    pub lights: Vec<DirectionalLight>,
}

impl DipoleStep {
    /// The step for `medium` under the directional lights of `scene`.
    pub fn new(kind: DipoleKind, medium: &Medium, settings: DipoleSettings, scene: &Scene) -> DipoleStep {
        let lights = scene
            .lights
            .iter()
            .enumerate()
            .filter_map(|(index, l)| match l.kind {
                LightKind::Directional { toward } => Some(DirectionalLight { index, toward, irradiance: l.irradiance }),
                LightKind::Point { .. } => None,
            })
            .take(MAX_LIGHTS)
            .collect();
        DipoleStep { kind, medium: medium.clone(), settings, lights }
    }

    /// The light views.
    pub fn slots(&self) -> u32 {
        self.lights.len() as u32
    }

    /// A hash of what the radiance maps depend on: the medium, the kind, the settings, the lights
    /// and the mesh's identity (its upload generation). Not the camera: the maps are
    /// view-independent.
    pub fn state_key(&self, mesh_generation: u64) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.kind.hash(&mut h);
        mesh_generation.hash(&mut h);
        let m = &self.medium;
        for v in m.sigma_a_per_mm.iter().chain(&m.sigma_s_prime_per_mm).chain([&m.eta]) {
            v.to_bits().hash(&mut h);
        }
        let s = &self.settings;
        (s.samples, s.directions, s.map_px, s.light_map_px, s.shrink, s.intrusion, s.world_bias).hash(&mut h);
        for l in &self.lights {
            l.toward.to_array().map(f32::to_bits).hash(&mut h);
            l.irradiance.map(f32::to_bits).hash(&mut h);
        }
        h.finish()
    }
}

impl DipoleUniform {
    /// The uniform of `step` around a mesh with `bounds`, for the samples of frame `frame_index`.
    pub fn new(step: &DipoleStep, bounds: &Bounds, frame_index: u32) -> DipoleUniform {
        let (kind, medium, settings) = (step.kind, &step.medium, &step.settings);
        let dipole = DirectionalDipole::with_source(medium, kind.source().unwrap_or_default());
        let classic: [ChannelProfile; 3] = medium_profiles(medium, ProfileModel::ClassicDipole);
        let centre = bounds.center();
        let radius = (0.5 * bounds.size().length()).max(1e-3);
        let mut u = DipoleUniform::zeroed();
        for (c, (ch, p)) in dipole.channels.iter().zip(&classic).enumerate() {
            u.channel[c] = [ch.d as f32, ch.sigma_tr as f32, ch.de as f32, ch.a as f32];
            let [alpha, sigma_tr, z_r, z_v] = p.classic_constants();
            u.extra[c] = [ch.backlit_sq as f32, alpha as f32, z_r as f32, z_v as f32];
            u.classic[c] = sigma_tr as f32;
        }
        let ch0 = dipole.channels[0];
        u.boundary = [ch0.c_phi as f32, ch0.c_e as f32, dipole.exit_norm as f32, medium.eta as f32];
        u.classic[3] = match kind.source() {
            None => 0.0,
            Some(DipoleSource::Published) => 1.0,
            Some(DipoleSource::MeanFreePath) => 2.0,
        };
        // Sample by the slowest decay (the widest channel); reach 8 of its lengths.
        let sigma = dipole.channels.iter().map(|c| c.sigma_tr).fold(f64::INFINITY, f64::min).max(0.02) as f32;
        u.sampling = [sigma, settings.samples as f32, frame_index as f32, 8.0 / sigma];
        let texel_mm = 2.0 * radius / settings.light_map_px as f32;
        let bits =
            u32::from(settings.shrink) | u32::from(settings.intrusion) << 1 | u32::from(settings.world_bias) << 2;
        u.fixes = [
            1.5 * texel_mm,
            1.5 * 2.0 * radius / settings.map_px as f32,
            2.0 * 2.0 * radius / settings.map_px as f32,
            bits as f32,
        ];
        u.counts = [settings.directions, step.slots(), settings.light_map_px, settings.map_px];
        for (slot, l) in step.lights.iter().enumerate() {
            let (vp, near, far) = orthographic_toward(l.toward, centre, radius);
            u.light_view_proj[slot] = vp.to_cols_array_2d();
            u.light_inv_view_proj[slot] = vp.inverse().to_cols_array_2d();
            u.light_info[slot] = [l.index as f32, near, far, texel_mm];
        }
        for k in 0..settings.directions.min(MAX_DIRECTIONS as u32) {
            let d = direction(k, settings.directions);
            let (vp, near, far): (Mat4, f32, f32) = orthographic_toward(d, centre, radius);
            u.dir_view_proj[k as usize] = vp.to_cols_array_2d();
            u.dir_axis[k as usize] = [d.x, d.y, d.z, 0.0];
            u.dir_planes[k as usize] = [near, far, 0.0, 0.0];
        }
        u
    }
}

/// The pipeline of a dipole pass that draws the mesh into an Rgba16Float target with depth
/// (the light G-buffer and the radiance maps).
pub fn mesh_pipeline_spec<'a>(
    shader: &'static crate::shader::PassShader,
    layout: &'a wgpu::BindGroupLayout,
    vs: &'a str,
    fs: &'a str,
) -> super::PipelineSpec<'a> {
    super::PipelineSpec {
        shader,
        variant: crate::shader::Variant::BARE,
        layout,
        vertices: super::Vertices::Mesh,
        vs,
        fs: Some(fs),
        targets: vec![Some(crate::targets::HDR_FORMAT)],
        blend: None,
        depth: Some(wgpu::DepthBiasState::default()),
    }
}

/// What the three dipole passes share: the uniform, the light G-buffer and the radiance maps
/// (sized by the settings, kept while they fit), and the progressive accumulation's state.
#[derive(Debug)]
pub struct DipoleResources {
    /// The `DipolePass` uniform.
    pub uniform: wgpu::Buffer,
    /// Light G-buffer normals (Rgba16Float array, a layer per light slot).
    pub light_normals: wgpu::Texture,
    /// Light G-buffer depths.
    pub light_depths: wgpu::Texture,
    /// Radiance maps (Rgba16Float array, a layer per direction), a ping-pong pair: one holds the
    /// running mean up to the last frame, the other receives this frame's.
    pub maps: [wgpu::Texture; 2],
    /// Their depths.
    pub map_depths: wgpu::Texture,
    /// What the maps hold: the key of the state they were made for, and how many frames of
    /// samples are blended in.
    progress: Option<(u64, u32)>,
}

impl DipoleResources {
    /// Stand-ins of 1×1 until a frame needs more.
    pub fn new(device: &wgpu::Device, min_layers: u32) -> DipoleResources {
        let uniform = crate::wgpu_util::uniform_buffer(device, "Dipole::uniform", std::mem::size_of::<DipoleUniform>());
        let (ln, ld, m, md) = Self::textures(device, (1, min_layers), (1, min_layers));
        DipoleResources { uniform, light_normals: ln, light_depths: ld, maps: m, map_depths: md, progress: None }
    }

    fn textures(
        device: &wgpu::Device,
        (light_px, light_layers): (u32, u32),
        (map_px, map_layers): (u32, u32),
    ) -> (wgpu::Texture, wgpu::Texture, [wgpu::Texture; 2], wgpu::Texture) {
        use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};
        use wgpu::TextureUsages as U;
        let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING;
        let t =
            |label, px, layers, format| crate::wgpu_util::texture(device, label, (px, px), layers, format, usage, &[]);
        (
            t("Dipole::light normals", light_px, light_layers, HDR_FORMAT),
            t("Dipole::light depths", light_px, light_layers, DEPTH_FORMAT),
            [
                t("Dipole::radiance maps 0", map_px, map_layers, HDR_FORMAT),
                t("Dipole::radiance maps 1", map_px, map_layers, HDR_FORMAT),
            ],
            t("Dipole::radiance map depths", map_px, map_layers, DEPTH_FORMAT),
        )
    }

    /// Sizes the textures for `settings` and `light_slots` (at least `min_layers` layers each).
    pub fn ensure(&mut self, device: &wgpu::Device, settings: &DipoleSettings, light_slots: u32, min_layers: u32) {
        let layers = |n| crate::targets::array_layers(n, min_layers);
        let light = (settings.light_map_px, layers(light_slots));
        let maps = (settings.map_px, layers(settings.directions));
        let fits = self.light_normals.width() == light.0
            && self.light_normals.depth_or_array_layers() >= light.1
            && self.maps[0].width() == maps.0
            && self.maps[0].depth_or_array_layers() >= maps.1;
        if !fits {
            let (ln, ld, m, md) = Self::textures(device, light, maps);
            (self.light_normals, self.light_depths, self.maps, self.map_depths) = (ln, ld, m, md);
            self.progress = None;
        }
    }

    /// The index of this frame's samples: 0 (the maps start afresh) when the state `key` changed
    /// or accumulation is off, n after n frames of the same state.
    pub fn next_frame(&mut self, key: u64, progressive: bool) -> u32 {
        let n = match self.progress {
            Some((k, n)) if k == key && progressive => n,
            _ => 0,
        };
        self.progress = Some((key, n + 1));
        n
    }

    /// The maps this frame writes (`written`) and the ones holding the mean so far.
    pub fn current_and_previous(&self) -> (&wgpu::Texture, &wgpu::Texture) {
        let n = self.frames_accumulated();
        // Frame n (1-based) writes maps[n % 2] and reads maps[(n + 1) % 2].
        (&self.maps[(n % 2) as usize], &self.maps[((n + 1) % 2) as usize])
    }

    /// Frames of samples blended into the maps so far.
    pub fn frames_accumulated(&self) -> u32 {
        self.progress.map_or(0, |(_, n)| n)
    }
}
