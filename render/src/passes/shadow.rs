//! Shadow pass: the depth of the mesh seen from one shadowing light, into one layer of the
//! shadow-map array (shaders/shadow.wgsl). The light's matrix is in the frame uniform
//! ([`crate::uniforms::light_uniforms`]); this pass's uniform says which light.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::targets::DEPTH_FORMAT;
use crate::uniforms::{LightUniform, MAX_LIGHTS, SHADOW_MAP_SIZE};
use crate::wgpu_util::{buf, buffer_init, depth_clear, layout, texture, uniform_entry};

/// The shadow pass: its layout, pipeline, one uniform per light slot and the shadow-map array.
#[derive(Debug)]
pub struct ShadowPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    /// `ShadowPass` uniforms (WGSL: `index: vec4<u32>`), one per light slot.
    light_indices: Vec<wgpu::BindGroup>,
    maps: wgpu::Texture,
    /// What each layer of `maps` holds ([`ShadowKey`]), `None` where nothing drawn is current.
    drawn: [Option<ShadowKey>; MAX_LIGHTS],
}

/// What a shadow map's depths depend on: the mesh's positions (the renderer's count of mesh
/// uploads and moves) and the light's view-projection (its direction or position, and the
/// mesh's bounds, which frame it). A map drawn under the same key holds the same depths, so a
/// frame whose key matches keeps it instead of drawing it again: a still face, or a brush stroke,
/// draws no shadow pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowKey {
    /// The renderer's mesh generation.
    pub mesh_generation: u64,
    /// The light's shadow view-projection, column-major.
    pub view_proj: [[f32; 4]; 4],
}

/// The key of each shadow-map layer the scene's `lights` draw, by layer (only the scene's
/// lights: the frame uniform's unused slots are zeros, which would read as layer 0).
pub fn shadow_keys(lights: &[LightUniform], mesh_generation: u64) -> [Option<ShadowKey>; MAX_LIGHTS] {
    let mut keys = [None; MAX_LIGHTS];
    for l in lights {
        // `LightUniform::shadow[0]` is the light's layer, −1 for a light without a shadow map.
        if l.shadow[0] >= 0.0 && (l.shadow[0] as usize) < MAX_LIGHTS {
            keys[l.shadow[0] as usize] = Some(ShadowKey { mesh_generation, view_proj: l.shadow_view_proj });
        }
    }
    keys
}

/// One shadow map: the light (its index in the scene) and its layer of the shadow-map array.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadowStep {
    /// The light's index in the scene.
    pub light: usize,
    /// Its layer of the shadow-map array.
    pub layer: u32,
}

impl FramePass for ShadowPass {
    type Step = ShadowStep;
    const SHADER: PassShader = pass_shader!(ShadowPass, "shadow.wgsl", bare);

    /// The pass on `shared`'s device, with a 1×1 stand-in map until a shadowing light comes.
    fn new(shared: &Shared) -> ShadowPass {
        let device = &shared.device;
        let layout = layout(device, "ShadowPass::layout", &[uniform_entry(0, wgpu::ShaderStages::VERTEX)]);
        let light_indices = (0..MAX_LIGHTS as u32)
            .map(|i| {
                let buffer = buffer_init(
                    device,
                    "ShadowPass::light_index",
                    bytemuck::bytes_of(&[i, 0, 0, 0]),
                    wgpu::BufferUsages::UNIFORM,
                );
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("ShadowPass::group"),
                    layout: &layout,
                    entries: &[buf(0, &buffer)],
                })
            })
            .collect();
        let maps = Self::create_maps(device, (1, 1), shared.formats.min_array_layers, "ShadowPass::maps (none)");
        ShadowPass { layout, pipelines: Pipelines::default(), light_indices, maps, drawn: [None; MAX_LIGHTS] }
    }

    fn name(step: &ShadowStep) -> String {
        format!("shadow {}", step.layer)
    }

    /// Records the depth of the mesh from the step's light into its layer.
    fn record(&mut self, rec: &mut Recording<'_>, step: &ShadowStep) -> Result<()> {
        let shared = rec.shared;
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || {
            let bias = wgpu::DepthBiasState { constant: 2, slope_scale: 2.0, clamp: 0.0 };
            PipelineSpec::mesh_depth(&Self::SHADER, &self.layout, "vs_shadow", None, bias)
        })?;
        let target = self.maps.create_view(&wgpu::TextureViewDescriptor {
            label: Some("ShadowPass::map"),
            dimension: Some(wgpu::TextureViewDimension::D2),
            base_array_layer: step.layer,
            array_layer_count: Some(1),
            ..Default::default()
        });
        let mut pass = rec.enc.begin(&Self::name(step), &[], depth_clear(&target));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &self.light_indices[step.light], &[]);
        rec.mesh.draw_positions(&mut pass);
        Ok(())
    }
}

impl ShadowPass {
    fn create_maps(device: &wgpu::Device, size: (u32, u32), layers: u32, label: &str) -> wgpu::Texture {
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
        texture(device, label, size, layers, DEPTH_FORMAT, usage, &[])
    }

    /// Makes room for `count` shadow maps of [`SHADOW_MAP_SIZE`]² (kept while large enough).
    pub fn ensure_maps(&mut self, shared: &Shared, count: u32) {
        if !self.must_reallocate(count) {
            return;
        }
        let layers = crate::targets::array_layers(count, shared.formats.min_array_layers);
        self.maps = Self::create_maps(&shared.device, (SHADOW_MAP_SIZE, SHADOW_MAP_SIZE), layers, "ShadowPass::maps");
        self.drawn = [None; MAX_LIGHTS];
    }

    /// Whether `count` maps need a new array (none yet, too few layers).
    fn must_reallocate(&self, count: u32) -> bool {
        count > 0 && (self.maps.depth_or_array_layers() < count || self.maps.width() != SHADOW_MAP_SIZE)
    }

    /// The layers (bit i: layer i) whose map is current for `keys`: drawn under the same key, and
    /// the array kept for as many maps as `keys` has.
    pub fn current_layers(&self, keys: &[Option<ShadowKey>; MAX_LIGHTS]) -> u8 {
        let count = keys.iter().flatten().count() as u32;
        if self.must_reallocate(count) {
            return 0;
        }
        let mut bits = 0u8;
        for (layer, (key, drawn)) in keys.iter().zip(&self.drawn).enumerate() {
            if key.is_some() && key == drawn {
                bits |= 1 << layer;
            }
        }
        bits
    }

    /// Notes that `layer` now holds the depths of `key` (after a frame that drew it was
    /// submitted), or nothing current (`None`).
    pub fn set_drawn(&mut self, layer: u32, key: Option<ShadowKey>) {
        if let Some(slot) = self.drawn.get_mut(layer as usize) {
            *slot = key;
        }
    }

    /// Forgets what every layer holds, so the next frame draws every shadow map.
    pub fn forget(&mut self) {
        self.drawn = [None; MAX_LIGHTS];
    }

    /// The shadow-map array as the lighting pass samples it.
    pub fn maps_view(&self) -> wgpu::TextureView {
        crate::wgpu_util::array_view(&self.maps)
    }
}
