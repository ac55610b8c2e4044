//! Composition (shaders/composite.wgsl, \[Huang2013\] figure 1 step 6): the skin radiance (scattered
//! or not) leaving through the stack (× T), plus the surface radiance, over the background; then
//! linear radiance (EXR) or exposure, Khronos PBR Neutral and sRGB encoding (PNG, the app).

use super::{FramePass, Pipelines, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::{DISPLAY_STORAGE_FORMAT, Target};
use crate::wgpu_util::{float_tex, layout, storage_texture_entry, tex};

/// The composite pass: a compute pass (on GPUs whose graphics pipeline runs on a few of their
/// cores, a full-screen fragment pass costs several times more: docs/BENCHMARKS.md, "Renderer:
/// frame time per pass").
#[derive(Debug)]
pub struct CompositePass {
    /// Writing the display target, and the linear one.
    layouts: [wgpu::BindGroupLayout; 2],
    pipelines: Pipelines<wgpu::ComputePipeline>,
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
        hair: v.hair,
        ..Variant::BARE
    });

    fn new(shared: &Shared) -> CompositePass {
        let inputs =
            [float_tex(0, false), float_tex(1, false), float_tex(2, false), float_tex(3, false), float_tex(5, false)]
                .map(|e| wgpu::BindGroupLayoutEntry { visibility: wgpu::ShaderStages::COMPUTE, ..e });
        let layouts = [DISPLAY_STORAGE_FORMAT, shared.formats.linear].map(|format| {
            let mut entries = inputs.to_vec();
            entries.push(storage_texture_entry(4, format));
            layout(&shared.device, "CompositePass::layout", &entries)
        });
        CompositePass { layouts, pipelines: Pipelines::default() }
    }

    fn name(_: &Target) -> String {
        "composite".into()
    }

    /// Records the pass from `skin` (the diffuse or the scattered radiance) into [`output`]:
    /// every pixel is written.
    fn record(&mut self, rec: &mut Recording<'_>, &skin: &Target) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let key = rec.key(&Self::SHADER);
        let layout = &self.layouts[usize::from(!key.display)];
        let pipeline = self.pipelines.get_or_build_compute(shared, (&Self::SHADER, key), layout, "cs_composite")?;
        let exit_t = if key.layers > 0 { Some(targets.view(Target::ExitT)?) } else { None };
        let hair = if key.hair { Some(targets.view(Target::Hair)?) } else { None };
        let (skin, surface, normal, out) = (
            targets.view(skin)?,
            targets.view(Target::Surface)?,
            targets.view(Target::Normal)?,
            targets.storage_view(output(key))?,
        );
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("CompositePass::group"),
            layout,
            entries: &[
                tex(0, &skin),
                tex(1, &surface),
                tex(2, exit_t.as_ref().unwrap_or(&shared.dummy)),
                tex(3, &normal),
                tex(4, &out),
                tex(5, hair.as_ref().unwrap_or(&shared.dummy)),
            ],
        });
        let (width, height) = targets.size();
        let mut pass = rec.enc.begin_compute("composite");
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        Ok(())
    }
}
