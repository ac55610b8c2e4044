//! Composition (shaders/composite.wgsl, \[Huang2013\] figure 1 step 6): the skin radiance (scattered
//! or not) leaving through the stack (× T), plus the surface radiance, over the background; then
//! linear radiance (EXR) or exposure, Khronos PBR Neutral and sRGB encoding (PNG, the app).

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::Result;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::Target;
use crate::wgpu_util::{color, float_tex, layout, tex};

/// The composite pass.
#[derive(Debug)]
pub struct CompositePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

/// The output target of a variant.
pub fn output(variant: Variant) -> Target {
    if variant.display { Target::Display } else { Target::Linear }
}

impl FramePass for CompositePass {
    /// The skin radiance composed: the diffuse or the scattered one.
    type Step = Target;
    const SHADER: PassShader = pass_shader!(CompositePass, "composite.wgsl", |v| Variant {
        layers: v.layers.min(1),
        display: v.display,
        ..Variant::BARE
    });

    fn new(shared: &Shared) -> CompositePass {
        let layout = layout(
            &shared.device,
            "CompositePass::layout",
            &[float_tex(0, false), float_tex(1, false), float_tex(2, false), float_tex(3, false)],
        );
        CompositePass { layout, pipelines: Pipelines::default() }
    }

    fn name(_: &Target) -> String {
        "composite".into()
    }

    /// Records the pass from `skin` (the diffuse or the scattered radiance) into [`output`].
    fn record(&mut self, rec: &mut Recording<'_>, &skin: &Target) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let key = rec.key(&Self::SHADER);
        let out = output(key);
        let format = out.format(shared.formats);
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            shader: &Self::SHADER,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some("fs_composite"),
            targets: vec![Some(format)],
            blend: None,
            depth: None,
        })?;
        let exit_t = if key.layers > 0 { Some(targets.view(Target::ExitT)?) } else { None };
        let (skin, surface, normal, out) =
            (targets.view(skin)?, targets.view(Target::Surface)?, targets.view(Target::Normal)?, targets.view(out)?);
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("CompositePass::group"),
            layout: &self.layout,
            entries: &[
                tex(0, &skin),
                tex(1, &surface),
                tex(2, exit_t.as_ref().unwrap_or(&shared.dummy)),
                tex(3, &normal),
            ],
        });
        let mut pass = rec.enc.begin("composite", &[color(&out, wgpu::Color::TRANSPARENT)], None);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
