//! G-buffer pass: world normals and coverage, albedo with the skin flag, the cosmetic layers'
//! thickness (mm) sampled from their maps, and depth (shaders/gbuffer.wgsl). The thickness
//! targets exist only in variants with layers: 0-3 with any layer, 4-7 with more than four.

use super::{FrameContext, FrameEncoder, Pass, PipelineSpec, Pipelines, Shared, Vertices};
use crate::error::Result;
use crate::gpu_look::{GpuLook, SkinTextures};
use crate::gpu_mesh::GpuMesh;
use crate::shader::Variant;
use crate::targets::Target;
use crate::wgpu_util::{color, depth_clear, float_tex, layout, sampler, sampler_entry, tex, tex_entry};

/// The G-buffer pass.
#[derive(Debug)]
pub struct GbufferPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

/// The colour targets a variant writes, in location order.
pub fn outputs(variant: Variant) -> Vec<Target> {
    let mut t = vec![Target::Normal, Target::Albedo];
    if variant.layers > 0 {
        t.push(Target::ThicknessA);
    }
    if variant.layers > 4 {
        t.push(Target::ThicknessB);
    }
    t
}

impl GbufferPass {
    /// The pass on `shared`'s device.
    pub fn new(shared: &Shared) -> GbufferPass {
        let layout = layout(
            &shared.device,
            "GbufferPass::layout",
            &[
                tex_entry(0, wgpu::TextureSampleType::Float { filterable: true }, wgpu::TextureViewDimension::D2Array),
                sampler_entry(1, wgpu::SamplerBindingType::Filtering),
                float_tex(2, true),
                float_tex(3, true),
            ],
        );
        GbufferPass { layout, pipelines: Pipelines::default() }
    }

    /// Records the pass: `mesh` with `look`'s thickness maps and the skin `textures` into the
    /// targets of [`outputs`] and [`Target::Depth`].
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(
        &mut self,
        ctx: FrameContext<'_>,
        enc: &mut FrameEncoder<'_>,
        mesh: &GpuMesh,
        look: &GpuLook,
        textures: &SkinTextures,
    ) -> Result<()> {
        let (shared, targets) = (ctx.shared, ctx.targets);
        let key = ctx.variant.for_pass(Pass::Gbuffer);
        let outs = outputs(key);
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            pass: Pass::Gbuffer,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::Mesh,
            vs: "vs_gbuffer",
            fs: Some("fs_gbuffer"),
            targets: outs.iter().map(|t| t.format(shared.formats)).collect(),
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("GbufferPass::group"),
            layout: &self.layout,
            entries: &[
                tex(0, &look.maps),
                sampler(1, &shared.linear_sampler),
                tex(2, textures.albedo.as_ref().unwrap_or(&shared.dummy)),
                tex(3, textures.normal.as_ref().unwrap_or(&shared.dummy)),
            ],
        });
        let views = outs.iter().map(|&t| targets.view(t)).collect::<Result<Vec<_>>>()?;
        let depth = targets.view(Target::Depth)?;
        let attachments: Vec<_> = views.iter().map(|v| color(v, wgpu::Color::TRANSPARENT)).collect();
        let mut pass = enc.begin("gbuffer", &attachments, depth_clear(&depth));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        mesh.draw(&mut pass);
        Ok(())
    }
}
