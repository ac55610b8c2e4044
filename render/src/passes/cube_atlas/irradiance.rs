//! Cube-atlas irradiance pass (shaders/atlas_irradiance.wgsl): the mesh onto the six faces of its
//! bounding cube, one orthographic view each ([Benmounah2009] sections 4.1-4.2).

use super::super::{FrameContext, FrameEncoder, Pass, PipelineSpec, Pipelines, Vertices};
use super::AtlasResources;
use crate::error::Result;
use crate::gpu_mesh::GpuMesh;
use crate::targets::HDR_FORMAT;
use crate::wgpu_util::{buf, layout, sampler, sampler_entry, tex, tex_entry, uniform_entry};

/// The irradiance pass.
#[derive(Debug)]
pub struct AtlasIrradiancePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl AtlasIrradiancePass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> AtlasIrradiancePass {
        let layout = layout(
            device,
            "AtlasIrradiancePass::layout",
            &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                tex_entry(1, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
                sampler_entry(2, wgpu::SamplerBindingType::Comparison),
            ],
        );
        AtlasIrradiancePass { layout, pipelines: Pipelines::default() }
    }

    /// Records the six faces of `mesh` into `res`.
    ///
    /// # Errors
    /// When the pipeline cannot be built.
    pub fn record(
        &mut self,
        ctx: FrameContext<'_>,
        enc: &mut FrameEncoder<'_>,
        mesh: &GpuMesh,
        res: &AtlasResources,
        shadow_maps: &wgpu::TextureView,
    ) -> Result<()> {
        let shared = ctx.shared;
        let variant = ctx.variant.for_pass(Pass::AtlasIrradiance);
        let pipeline = self.pipelines.get_or_build(shared, variant, || PipelineSpec {
            pass: Pass::AtlasIrradiance,
            variant,
            layout: &self.layout,
            vertices: Vertices::Mesh,
            vs: "vs_atlas_irradiance",
            fs: Some("fs_atlas_irradiance"),
            targets: vec![Some(HDR_FORMAT), Some(HDR_FORMAT)],
            blend: None,
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("AtlasIrradiancePass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform), tex(1, shadow_maps), sampler(2, &shared.shadow_sampler)],
        });
        let targets = (&[&res.irradiance, &res.normals][..], &res.depths);
        enc.draw_mesh_per_layer("atlas irradiance", shared, (pipeline, &group), mesh, targets, 6);
        Ok(())
    }
}
