//! Cube-atlas irradiance pass (shaders/atlas_irradiance.wgsl): the mesh onto the six faces of its
//! bounding cube, one orthographic view each (\[Benmounah2009\] sections 4.1-4.2). As the first of
//! the atlas passes of a frame, it also sizes the atlas and writes its uniform ([`AtlasStep`]).

use super::super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use super::AtlasStep;
use crate::error::Result;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::HDR_FORMAT;
use crate::wgpu_util::{buf, layout, sampler, sampler_entry, tex, tex_entry, uniform_entry};

/// The irradiance pass.
#[derive(Debug)]
pub struct AtlasIrradiancePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl FramePass for AtlasIrradiancePass {
    type Step = AtlasStep;
    const SHADER: PassShader = pass_shader!(AtlasIrradiancePass, "atlas_irradiance.wgsl", |v| Variant {
        shadows: v.shadows,
        env: v.env,
        ..Variant::BARE
    });

    fn new(shared: &Shared) -> AtlasIrradiancePass {
        let layout = layout(
            &shared.device,
            "AtlasIrradiancePass::layout",
            &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                tex_entry(1, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
                sampler_entry(2, wgpu::SamplerBindingType::Comparison),
            ],
        );
        AtlasIrradiancePass { layout, pipelines: Pipelines::default() }
    }

    fn name(_: &AtlasStep) -> String {
        "atlas irradiance".into()
    }

    /// Sizes the atlas, writes its uniform and records the six faces of the mesh into it.
    fn record(&mut self, rec: &mut Recording<'_>, step: &AtlasStep) -> Result<()> {
        let shared = rec.shared;
        let variant = rec.key(&Self::SHADER);
        let res = &mut *rec.atlas;
        res.ensure(&shared.device, &step.settings);
        res.update(&shared.queue, &step.medium, &step.settings, &rec.mesh.bounds);
        let pipeline = self.pipelines.get_or_build(shared, variant, || PipelineSpec {
            shader: &Self::SHADER,
            variant,
            layout: &self.layout,
            vertices: Vertices::Mesh,
            vs: "vs_layer",
            fs: Some("fs_atlas_irradiance"),
            targets: vec![Some(HDR_FORMAT), Some(HDR_FORMAT)],
            blend: None,
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("AtlasIrradiancePass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform), tex(1, &rec.shadow_maps), sampler(2, &shared.shadow_sampler)],
        });
        let targets = (&[&res.irradiance, &res.normals][..], &res.depths);
        rec.enc.draw_mesh_per_layer("atlas irradiance", shared, (pipeline, &group), rec.mesh, targets, 6);
        Ok(())
    }
}
