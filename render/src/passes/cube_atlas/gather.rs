//! Cube-atlas gather pass (shaders/atlas_gather.wgsl): per skin pixel, face selection with the
//! self-occlusion test, the local dipole gather and the global term, added to the skin's diffuse
//! radiance ([Benmounah2009] sections 4.2-4.4).

use super::super::{FrameContext, FrameEncoder, Pass, PipelineSpec, Pipelines, Vertices};
use super::AtlasResources;
use crate::error::Result;
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{array_view, buf, color_load, float_tex, layout, tex, tex_entry, uniform_entry};

/// The gather pass.
#[derive(Debug)]
pub struct AtlasGatherPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

/// The frame targets the pass reads.
pub fn inputs() -> [Target; 3] {
    [Target::Normal, Target::Albedo, Target::Depth]
}

impl AtlasGatherPass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> AtlasGatherPass {
        let array =
            |b| tex_entry(b, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array);
        let layout = layout(
            device,
            "AtlasGatherPass::layout",
            &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                float_tex(1, false),
                float_tex(2, false),
                float_tex(3, false),
                array(4),
                array(5),
                array(6),
            ],
        );
        AtlasGatherPass { layout, pipelines: Pipelines::default() }
    }

    /// Records the gather into [`Target::Diffuse`] (added).
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(&mut self, ctx: FrameContext<'_>, enc: &mut FrameEncoder<'_>, res: &AtlasResources) -> Result<()> {
        let (shared, targets) = (ctx.shared, ctx.targets);
        let variant = ctx.variant.for_pass(Pass::AtlasGather);
        let pipeline = self.pipelines.get_or_build(shared, variant, || PipelineSpec {
            pass: Pass::AtlasGather,
            variant,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some("fs_atlas_gather"),
            targets: vec![Some(HDR_FORMAT)],
            blend: Some(crate::wgpu_util::ADD_RGB_KEEP_ALPHA),
            depth: None,
        })?;
        let [normal, albedo, depth] = inputs().map(|t| targets.view(t));
        let (normal, albedo, depth) = (normal?, albedo?, depth?);
        let (irradiance, normals, depths) =
            (array_view(&res.irradiance), array_view(&res.normals), array_view(&res.depths));
        let diffuse = targets.view(Target::Diffuse)?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("AtlasGatherPass::group"),
            layout: &self.layout,
            entries: &[
                buf(0, &res.uniform),
                tex(1, &normal),
                tex(2, &albedo),
                tex(3, &depth),
                tex(4, &irradiance),
                tex(5, &normals),
                tex(6, &depths),
            ],
        });
        let mut pass = enc.begin("atlas gather", &[color_load(&diffuse)], None);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
