//! The dipole subsurface models' passes ([DirDipoleThesis] section 4.2, after [Frisvad2014]):
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
use crate::directional_dipole::DirectionalDipole;
use crate::error::{RenderError, Result};
use crate::scene::{LightKind, Scene};
use crate::uniforms::{MAX_LIGHTS, orthographic_toward};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use rouge_model::medium::Medium;
use rouge_model::mesh::Bounds;

/// Most radiance-map directions.
pub const MAX_DIRECTIONS: usize = 32;

/// Which BSSRDF the dipole passes gather.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DipoleKind {
    /// [Frisvad2014]'s directional dipole.
    Directional,
    /// [Jensen2001]'s standard (classic) dipole.
    Standard,
}

impl DipoleKind {
    /// The `--subsurface` name.
    pub fn name(self) -> &'static str {
        match self {
            DipoleKind::Directional => "directional-dipole",
            DipoleKind::Standard => "standard-dipole",
        }
    }
}

/// The settings of the dipole passes ([DirDipoleThesis] sections 4.2 and 4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DipoleSettings {
    /// Disk samples N per radiance-map texel and light (1 to 256).
    pub samples: u32,
    /// Radiance-map directions K (1 to [`MAX_DIRECTIONS`]), spread on the sphere.
    pub directions: u32,
    /// Radiance-map side, texels.
    pub map_px: u32,
    /// Light G-buffer side, texels.
    pub light_map_px: u32,
    /// Fix 1 (section 4.4.1): the exit point looked up ε_g inside, across the light.
    pub shrink: bool,
    /// Fix 2 (section 4.4.2): the pixel looked up ε_c inside along its normal.
    pub intrusion: bool,
    /// Fix 3 (section 4.4.3): visibility compared in mm with a bias ε_b.
    pub world_bias: bool,
    /// Keep blending new samples into the maps while lights, mesh and settings stay.
    pub progressive: bool,
}

impl Default for DipoleSettings {
    fn default() -> Self {
        DipoleSettings {
            samples: 16,
            directions: 8,
            map_px: 256,
            light_map_px: 512,
            shrink: true,
            intrusion: true,
            world_bias: true,
            progressive: true,
        }
    }
}

impl DipoleSettings {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the setting.
    pub fn check(&self) -> Result<()> {
        let bad = |what: &str, v: u32, range: &str| Err(RenderError::Invalid(format!("dipole {what} {v}: {range}")));
        if !(1..=256).contains(&self.samples) {
            return bad("samples", self.samples, "1 to 256");
        }
        if !(1..=MAX_DIRECTIONS as u32).contains(&self.directions) {
            return bad("directions", self.directions, "1 to 32");
        }
        if !(16..=4096).contains(&self.map_px) {
            return bad("radiance map size", self.map_px, "16 to 4096 texels");
        }
        if !(16..=4096).contains(&self.light_map_px) {
            return bad("light map size", self.light_map_px, "16 to 4096 texels");
        }
        Ok(())
    }
}

/// `k` of `count` directions spread evenly on the unit sphere (the Fibonacci lattice through both
/// poles; a single direction is +Z, the default camera's).
pub fn direction(k: u32, count: u32) -> Vec3 {
    if count <= 1 {
        return Vec3::Z;
    }
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let y = 1.0 - 2.0 * k as f32 / (count - 1) as f32;
    let r = (1.0 - y * y).max(0.0).sqrt();
    let phi = golden * k as f32;
    Vec3::new(r * phi.cos(), y, r * phi.sin())
}

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
    /// Classic σ_tr per channel; w 1 directional, 0 standard.
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

/// The scene lights the dipole passes take (directional ones, up to [`MAX_LIGHTS`]), by index.
pub fn dipole_lights(scene: &Scene) -> Vec<usize> {
    scene
        .lights
        .iter()
        .enumerate()
        .filter(|(_, l)| matches!(l.kind, LightKind::Directional { .. }))
        .map(|(i, _)| i)
        .collect()
}

impl DipoleUniform {
    /// The uniform for `medium` seen by the scene's directional lights around `bounds`.
    pub fn new(
        kind: DipoleKind,
        medium: &Medium,
        settings: &DipoleSettings,
        scene: &Scene,
        bounds: &Bounds,
        frame_index: u32,
    ) -> DipoleUniform {
        let dipole = DirectionalDipole::new(medium);
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
        u.classic[3] = if kind == DipoleKind::Directional { 1.0 } else { 0.0 };
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
        let lights = dipole_lights(scene);
        let slots = lights.len().min(MAX_LIGHTS);
        u.counts = [settings.directions, slots as u32, settings.light_map_px, settings.map_px];
        for (slot, &li) in lights.iter().take(MAX_LIGHTS).enumerate() {
            let LightKind::Directional { toward } = scene.lights[li].kind else { continue };
            let (vp, near, far) = orthographic_toward(toward, centre, radius);
            u.light_view_proj[slot] = vp.to_cols_array_2d();
            u.light_inv_view_proj[slot] = vp.inverse().to_cols_array_2d();
            u.light_info[slot] = [li as f32, near, far, texel_mm];
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_cover_the_sphere_evenly() {
        for k in [1u32, 4, 8, 16, 32] {
            let ds: Vec<Vec3> = (0..k).map(|i| direction(i, k)).collect();
            assert!(ds.iter().all(|d| (d.length() - 1.0).abs() < 1e-5));
            if k >= 8 {
                // Every direction of the sphere is within 60° of one of them.
                for i in 0..200 {
                    let probe = direction(i, 200);
                    let best = ds.iter().map(|d| d.dot(probe)).fold(-1.0f32, f32::max);
                    assert!(best > 0.5, "{k} directions leave {probe} uncovered");
                }
            }
        }
    }

    #[test]
    fn settings_out_of_range_are_errors() {
        assert!(DipoleSettings::default().check().is_ok());
        for bad in [
            DipoleSettings { samples: 0, ..Default::default() },
            DipoleSettings { directions: 33, ..Default::default() },
            DipoleSettings { map_px: 8, ..Default::default() },
        ] {
            assert!(bad.check().is_err());
        }
    }
}

/// The pipeline of a dipole pass that draws the mesh into an Rgba16Float target with depth
/// (the light G-buffer and the radiance maps).
pub fn mesh_pipeline_spec<'a>(
    pass: super::Pass,
    layout: &'a wgpu::BindGroupLayout,
    vs: &'a str,
    fs: &'a str,
) -> super::PipelineSpec<'a> {
    super::PipelineSpec {
        pass,
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

/// A hash of what the radiance maps depend on: the medium, the kind, the settings, the lights and
/// the mesh's identity (its upload generation). Not the camera: the maps are view-independent.
pub fn state_key(
    kind: DipoleKind,
    medium: &Medium,
    settings: &DipoleSettings,
    scene: &Scene,
    mesh_generation: u64,
) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    kind.hash(&mut h);
    mesh_generation.hash(&mut h);
    for v in medium.sigma_a_per_mm.iter().chain(&medium.sigma_s_prime_per_mm).chain([&medium.eta]) {
        v.to_bits().hash(&mut h);
    }
    let s = settings;
    (s.samples, s.directions, s.map_px, s.light_map_px, s.shrink, s.intrusion, s.world_bias).hash(&mut h);
    for l in &scene.lights {
        if let LightKind::Directional { toward } = l.kind {
            toward.to_array().map(f32::to_bits).hash(&mut h);
            l.irradiance.map(f32::to_bits).hash(&mut h);
        }
    }
    h.finish()
}
