//! Screen-space subsurface scattering (shaders/sss.wgsl): the separable, depth-aware blur of
//! \[Jimenez2015\] with the kernel of [`crate::sss::SeparableKernel`], horizontal then vertical.
//! It runs for materials whose subsurface model is
//! [`crate::scene::SubsurfaceModel::ScreenSpace`].

use super::{FramePass, Pipelines, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::sss::{MAX_SAMPLES, SeparableKernel};
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{
    buf, float_tex, layout, sampler, sampler_entry, storage_texture_entry, tex, uniform_buffer, uniform_entry,
};
use bytemuck::{Pod, Zeroable};

/// One SSS pass's uniform, as in WGSL `SssPass`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SssUniform {
    /// Direction (px), width, follow (mm).
    pub dir: [f32; 4],
    /// Sample count.
    pub count: [u32; 4],
    /// Offset (mm) and weights.
    pub samples: [[f32; 4]; MAX_SAMPLES as usize],
}

/// The blur's direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// Along x: the skin radiance (diffuse or bounced) → scratch.
    Horizontal,
    /// Along y: scratch → scattered.
    Vertical,
}

impl Direction {
    fn index(self) -> usize {
        match self {
            Direction::Horizontal => 0,
            Direction::Vertical => 1,
        }
    }

    /// Input and output targets, the horizontal pass reading `skin` (the diffuse radiance, or
    /// the bounced one when the bounce ran).
    pub fn targets(self, skin: Target) -> (Target, Target) {
        match self {
            Direction::Horizontal => (skin, Target::SssScratch),
            Direction::Vertical => (Target::SssScratch, Target::Scattered),
        }
    }

    /// The pass label.
    pub fn label(self) -> &'static str {
        match self {
            Direction::Horizontal => "sss horizontal",
            Direction::Vertical => "sss vertical",
        }
    }
}

/// The two SSS passes.
#[derive(Debug)]
pub struct SssPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines<wgpu::ComputePipeline>,
    uniforms: [wgpu::Buffer; 2],
}

/// One direction of the blur, with its uniform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SssStep {
    /// The direction.
    pub direction: Direction,
    /// The skin radiance the blur starts from ([`Direction::targets`]).
    pub skin: Target,
    /// Its uniform: the kernel's samples, the width and the depth following.
    pub uniform: SssUniform,
}

impl SssStep {
    /// The step of `direction` from the skin radiance `skin`: `kernel` scaled by `width`,
    /// `follow_mm` of depth, `count` samples.
    pub fn new(
        (direction, skin): (Direction, Target),
        kernel: &SeparableKernel,
        width: f32,
        follow_mm: f32,
        count: u32,
    ) -> SssStep {
        let [x, y] = match direction {
            Direction::Horizontal => [1.0, 0.0],
            Direction::Vertical => [0.0, 1.0],
        };
        let uniform = SssUniform { dir: [x, y, width, follow_mm], count: [count, 0, 0, 0], samples: kernel.to_gpu() };
        SssStep { direction, skin, uniform }
    }
}

impl FramePass for SssPass {
    type Step = SssStep;
    const SHADER: PassShader = pass_shader!(SssPass, "sss.wgsl", bare);

    /// The passes on `shared`'s device.
    fn new(shared: &Shared) -> SssPass {
        let device = &shared.device;
        let compute =
            |e: wgpu::BindGroupLayoutEntry| wgpu::BindGroupLayoutEntry { visibility: wgpu::ShaderStages::COMPUTE, ..e };
        let layout = layout(
            device,
            "SssPass::layout",
            &[
                uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                compute(float_tex(1, true)),
                // Depth read as unfilterable float (see sss.wgsl).
                compute(float_tex(2, false)),
                compute(sampler_entry(3, wgpu::SamplerBindingType::Filtering)),
                storage_texture_entry(4, HDR_FORMAT),
            ],
        );
        let size = std::mem::size_of::<SssUniform>();
        let uniforms =
            [uniform_buffer(device, "SssPass::horizontal", size), uniform_buffer(device, "SssPass::vertical", size)];
        SssPass { layout, pipelines: Pipelines::default(), uniforms }
    }

    fn name(step: &SssStep) -> String {
        step.direction.label().into()
    }

    /// Writes the direction's uniform (each direction has its own buffer) and records it.
    fn record(&mut self, rec: &mut Recording<'_>, step: &SssStep) -> Result<()> {
        let (shared, targets, direction) = (rec.shared, rec.targets, step.direction);
        let buffer = &self.uniforms[direction.index()];
        shared.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&step.uniform));
        let pipeline =
            self.pipelines.get_or_build_compute(shared, (&Self::SHADER, Variant::BARE), &self.layout, "cs_sss")?;
        let (src, dst) = direction.targets(step.skin);
        let (src, dst, depth) = (targets.view(src)?, targets.view(dst)?, targets.view(Target::Depth)?);
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("SssPass::group"),
            layout: &self.layout,
            entries: &[
                buf(0, &self.uniforms[direction.index()]),
                tex(1, &src),
                tex(2, &depth),
                sampler(3, &shared.linear_sampler),
                tex(4, &dst),
            ],
        });
        let (width, height) = targets.size();
        let mut pass = rec.enc.begin_compute(direction.label());
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        Ok(())
    }
}
