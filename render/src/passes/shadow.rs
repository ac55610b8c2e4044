//! Shadow pass: the depth of the mesh seen from one shadowing light, into one layer of the
//! shadow-map array (shaders/shadow.wgsl). The light's matrix is in the frame uniform
//! ([`crate::uniforms::light_uniforms`]); this pass's uniform says which light.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::targets::DEPTH_FORMAT;
use crate::uniforms::{MAX_LIGHTS, SHADOW_MAP_SIZE};
use crate::wgpu_util::{buf, buffer_init, depth_clear, layout, texture, uniform_entry};

/// The shadow pass: its layout, pipeline, one uniform per light slot and the shadow-map array.
#[derive(Debug)]
pub struct ShadowPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    /// `ShadowPass` uniforms (WGSL: `index: vec4<u32>`), one per light slot.
    light_indices: Vec<wgpu::BindGroup>,
    maps: wgpu::Texture,
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
        ShadowPass { layout, pipelines: Pipelines::default(), light_indices, maps }
    }

    fn name(step: &ShadowStep) -> String {
        format!("shadow {}", step.layer)
    }

    /// Records the depth of the mesh from the step's light into its layer.
    fn record(&mut self, rec: &mut Recording<'_>, step: &ShadowStep) -> Result<()> {
        let shared = rec.shared;
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || PipelineSpec {
            shader: &Self::SHADER,
            variant: Variant::BARE,
            layout: &self.layout,
            vertices: Vertices::MeshPositions,
            vs: "vs_shadow",
            fs: None,
            targets: vec![],
            blend: None,
            depth: Some(wgpu::DepthBiasState { constant: 2, slope_scale: 2.0, clamp: 0.0 }),
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
        if count == 0 || self.maps.depth_or_array_layers() >= count && self.maps.width() == SHADOW_MAP_SIZE {
            return;
        }
        let layers = crate::targets::array_layers(count, shared.formats.min_array_layers);
        self.maps = Self::create_maps(&shared.device, (SHADOW_MAP_SIZE, SHADOW_MAP_SIZE), layers, "ShadowPass::maps");
    }

    /// The shadow-map array as the lighting pass samples it.
    pub fn maps_view(&self) -> wgpu::TextureView {
        crate::wgpu_util::array_view(&self.maps)
    }
}
