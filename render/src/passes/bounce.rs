//! The bounce pass (shaders/bounce.wgsl): one bounce of the skin's diffuse radiance between
//! parts of the mesh that face each other ([`crate::bounce`]). Two compute dispatches, after the
//! subsurface model's passes and before the blur: `bounce gather`, each skin pixel's irradiance
//! from the screen samples into [`Target::BounceLight`]; `bounce add`, that irradiance averaged
//! over the pixel's neighbours on the same surface (5×5 pixels; the samples' noise is per pixel,
//! the irradiance varies over millimetres) and sent back, added to the diffuse radiance, into
//! [`Target::Bounced`], which the blur (or, without one, the composite) reads.

use super::{FramePass, Pipelines, Recording, Shared};
use crate::bounce::BounceSettings;
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{buf, float_tex, layout, storage_texture_entry, tex, uniform_buffer, uniform_entry};
use bytemuck::{Pod, Zeroable};

/// The pass's uniform, as in WGSL `BouncePass`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct BounceUniform {
    /// Samples, reach (mm), near (mm), the least view cosine of a source.
    pub params: [f32; 4],
}

/// The targets the pass reads (and [`Target::ExitT`] when the look has layers).
pub fn inputs() -> [Target; 4] {
    [Target::Diffuse, Target::Normal, Target::Albedo, Target::Depth]
}

/// The bounce pass.
#[derive(Debug)]
pub struct BouncePass {
    layout: wgpu::BindGroupLayout,
    /// The gather's pipelines and the add's (one entry point each).
    gather: Pipelines<wgpu::ComputePipeline>,
    add: Pipelines<wgpu::ComputePipeline>,
    uniform: wgpu::Buffer,
}

impl FramePass for BouncePass {
    type Step = BounceSettings;
    const SHADER: PassShader = pass_shader!(BouncePass, "bounce.wgsl", bare);

    fn new(shared: &Shared) -> BouncePass {
        let device = &shared.device;
        let mut entries = vec![uniform_entry(0, wgpu::ShaderStages::COMPUTE)];
        let sampled = |b| wgpu::BindGroupLayoutEntry { visibility: wgpu::ShaderStages::COMPUTE, ..float_tex(b, false) };
        entries.extend((1..=5).map(sampled));
        entries.push(storage_texture_entry(6, HDR_FORMAT));
        entries.push(sampled(7));
        let layout = layout(device, "BouncePass::layout", &entries);
        let uniform = uniform_buffer(device, "BouncePass::uniform", std::mem::size_of::<BounceUniform>());
        BouncePass { layout, gather: Pipelines::default(), add: Pipelines::default(), uniform }
    }

    /// `bounce (64 samples to 100 mm)`; its two dispatches are timed as `bounce gather` and
    /// `bounce add`.
    fn name(s: &BounceSettings) -> String {
        format!("bounce ({} samples to {} mm)", s.samples, s.reach_mm)
    }

    /// Writes the uniform and records the two dispatches: every pixel of
    /// [`Target::BounceLight`], then of [`Target::Bounced`], is written.
    fn record(&mut self, rec: &mut Recording<'_>, s: &BounceSettings) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let uniform = BounceUniform { params: [s.samples as f32, s.reach_mm, s.near_mm, s.least_view_cosine] };
        shared.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let [skin, normal, albedo, depth] = inputs().map(|t| targets.view(t));
        let (skin, normal, albedo, depth) = (skin?, normal?, albedo?, depth?);
        let (light, bounced) = (targets.view(Target::BounceLight)?, targets.view(Target::Bounced)?);
        // The shader reads the stack's T only when the frame has layers (`frame.counts.y`).
        let exit_t = if rec.variant.layers > 0 { Some(targets.view(Target::ExitT)?) } else { None };
        let (width, height) = targets.size();
        let steps = [
            ("bounce gather", "cs_bounce_gather", &light, &shared.dummy),
            ("bounce add", "cs_bounce_add", &bounced, &light),
        ];
        for (label, entry, out, gathered) in steps {
            let pipelines = if entry == "cs_bounce_gather" { &mut self.gather } else { &mut self.add };
            let pipeline =
                pipelines.get_or_build_compute(shared, (&Self::SHADER, Variant::BARE), &self.layout, entry)?;
            let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("BouncePass::group"),
                layout: &self.layout,
                entries: &[
                    buf(0, &self.uniform),
                    tex(1, &skin),
                    tex(2, &normal),
                    tex(3, &albedo),
                    tex(4, &depth),
                    tex(5, exit_t.as_ref().unwrap_or(&shared.dummy)),
                    tex(6, out),
                    tex(7, gathered),
                ],
            });
            let mut pass = rec.enc.begin_compute(label);
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &shared.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        }
        Ok(())
    }
}
