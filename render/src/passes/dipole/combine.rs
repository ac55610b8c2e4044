//! Dipole combination pass (shaders/dipole_combine.wgsl): per skin pixel, the radiance maps of
//! the directions that see the point, averaged, times the exit Fresnel transmittance, added to
//! the skin's diffuse radiance ([DirDipoleThesis] step 3).

use super::super::{FrameContext, FrameEncoder, Pass, PipelineSpec, Pipelines, Vertices};
use super::DipoleResources;
use crate::error::Result;
use crate::shader::Variant;
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{array_view, buf, color_load, float_tex, layout, tex, tex_entry, uniform_entry};

/// The combination pass.
#[derive(Debug)]
pub struct DipoleCombinePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

/// The frame targets the pass reads.
pub fn inputs() -> [Target; 3] {
    [Target::Normal, Target::Albedo, Target::Depth]
}

impl DipoleCombinePass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> DipoleCombinePass {
        let array =
            |b| tex_entry(b, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array);
        let layout = layout(
            device,
            "DipoleCombinePass::layout",
            &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                float_tex(1, false),
                float_tex(2, false),
                float_tex(3, false),
                array(4),
                array(5),
            ],
        );
        DipoleCombinePass { layout, pipelines: Pipelines::default() }
    }

    /// Records the combination into [`Target::Diffuse`] (added).
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(&mut self, ctx: FrameContext<'_>, enc: &mut FrameEncoder<'_>, res: &DipoleResources) -> Result<()> {
        let (shared, targets) = (ctx.shared, ctx.targets);
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || PipelineSpec {
            pass: Pass::DipoleCombine,
            variant: Variant::BARE,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some("fs_dipole_combine"),
            targets: vec![Some(HDR_FORMAT)],
            blend: Some(crate::wgpu_util::ADD_RGB_KEEP_ALPHA),
            depth: None,
        })?;
        let [normal, albedo, depth] = inputs().map(|t| targets.view(t));
        let (normal, albedo, depth) = (normal?, albedo?, depth?);
        let (maps, map_depths) = (array_view(res.current_and_previous().0), array_view(&res.map_depths));
        let diffuse = targets.view(Target::Diffuse)?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DipoleCombinePass::group"),
            layout: &self.layout,
            entries: &[
                buf(0, &res.uniform),
                tex(1, &normal),
                tex(2, &albedo),
                tex(3, &depth),
                tex(4, &maps),
                tex(5, &map_depths),
            ],
        });
        let mut pass = enc.begin("dipole combine", &[color_load(&diffuse)], None);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
