//! Lighting pass (shaders/lighting.wgsl): per pixel, the cosmetic stack's reflectance and
//! transmittance from the layer tables, the irradiance of each light (with its shadow) and of
//! the environment through the stack, and the specular lobes of skin and layers
//! (\[Huang2013\] section 3, eq. 1-5). Writes the skin's diffuse radiance (to be scattered), the
//! radiance leaving at the surface, and, with layers, the stack's exit transmittance. Under the
//! `half-space` diffuse law it reads that law's table at the skin's η
//! ([`crate::dielectric_brdf::GpuTable`]), made and uploaded when the law changes, and with the
//! skin's medium and an environment, the curvature of the environment term per pixel
//! ([`crate::curved_half_space`]).

use super::{FramePass, Pipelines, Recording, Shared};
use crate::dielectric_brdf::{GpuLaw, GpuTable};
use crate::error::Result;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{
    buffer_init, float_tex, layout, sampler, sampler_entry, storage_entry, storage_texture_entry, tex, tex_entry,
};

/// What the plan gives the lighting pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightingStep {
    /// The half-space law's table when the skin's diffuse law is `half-space` (η checked in
    /// [1, 3] by the plan), else none: the table is then neither made nor uploaded.
    pub half_space: Option<GpuLaw>,
}

/// The lighting pass.
#[derive(Debug)]
pub struct LightingPass {
    /// Without and with the exit transmittance's output.
    layouts: [wgpu::BindGroupLayout; 2],
    pipelines: Pipelines<wgpu::ComputePipeline>,
    /// The half-space law's table and what it is of (none: zeros, for Lambert).
    half_space: (Option<GpuLaw>, wgpu::Buffer),
}

/// The G-buffer targets a variant reads.
pub fn inputs(variant: Variant) -> Vec<Target> {
    let mut t = vec![Target::Normal, Target::Albedo, Target::Depth];
    if variant.layers > 0 {
        t.push(Target::ThicknessA);
    }
    if variant.layers > 4 {
        t.push(Target::ThicknessB);
    }
    if variant.glitter {
        t.push(Target::Glitter);
    }
    t
}

/// The targets a variant writes, in location order.
pub fn outputs(variant: Variant) -> Vec<Target> {
    let mut t = vec![Target::Diffuse, Target::Surface];
    if variant.layers > 0 {
        t.push(Target::ExitT);
    }
    t
}

impl FramePass for LightingPass {
    type Step = LightingStep;
    const SHADER: PassShader = pass_shader!(LightingPass, "lighting.wgsl", |v| Variant {
        layers: v.layers,
        shadows: v.shadows,
        env: v.env,
        dipole: v.dipole,
        atlas: v.atlas,
        glitter: v.glitter,
        ..Variant::BARE
    });

    fn new(shared: &Shared) -> LightingPass {
        let inputs = [
            float_tex(0, false),
            float_tex(1, false),
            // Depth read as unfilterable float (see lighting.wgsl).
            float_tex(2, false),
            float_tex(3, false),
            float_tex(4, false),
            storage_entry(5),
            tex_entry(6, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
            sampler_entry(7, wgpu::SamplerBindingType::Comparison),
            tex_entry(8, wgpu::TextureSampleType::Uint, wgpu::TextureViewDimension::D2),
            storage_entry(12),
        ]
        .map(|e| wgpu::BindGroupLayoutEntry { visibility: wgpu::ShaderStages::COMPUTE, ..e });
        // The outputs: diffuse and surface, and the exit transmittance with layers.
        let layouts = [2, 3].map(|outs: u32| {
            let mut entries = inputs.to_vec();
            entries.extend((0..outs).map(|i| storage_texture_entry(9 + i, HDR_FORMAT)));
            layout(&shared.device, "LightingPass::layout", &entries)
        });
        let none =
            buffer_init(&shared.device, "LightingPass::half_space (none)", &[0u8; 16], wgpu::BufferUsages::STORAGE);
        LightingPass { layouts, pipelines: Pipelines::default(), half_space: (None, none) }
    }

    fn name(_: &LightingStep) -> String {
        "lighting".into()
    }

    /// Records the pass from the G-buffer, the look's tables, the shadow maps and the half-space
    /// law's table.
    fn record(&mut self, rec: &mut Recording<'_>, step: &LightingStep) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        if let Some(law) = step.half_space
            && self.half_space.0 != Some(law)
        {
            let table = GpuTable::new(law)?;
            let bytes = bytemuck::cast_slice(&table.values);
            let buffer = buffer_init(&shared.device, "LightingPass::half_space", bytes, wgpu::BufferUsages::STORAGE);
            self.half_space = (Some(law), buffer);
        }
        let key = rec.key(&Self::SHADER);
        let outs = outputs(key);
        let layout = &self.layouts[outs.len() - 2];
        let pipeline = self.pipelines.get_or_build_compute(shared, (&Self::SHADER, key), layout, "cs_lighting")?;
        let optional = |wanted: bool, t: Target| -> Result<Option<wgpu::TextureView>> {
            if wanted { targets.view(t).map(Some) } else { Ok(None) }
        };
        let (normal, albedo, depth) =
            (targets.view(Target::Normal)?, targets.view(Target::Albedo)?, targets.view(Target::Depth)?);
        let thickness_a = optional(key.layers > 0, Target::ThicknessA)?;
        let thickness_b = optional(key.layers > 4, Target::ThicknessB)?;
        let glitter = optional(key.glitter, Target::Glitter)?;
        let views = outs.iter().map(|&t| targets.view(t)).collect::<Result<Vec<_>>>()?;
        let mut entries = vec![
            tex(0, &normal),
            tex(1, &albedo),
            tex(2, &depth),
            tex(3, thickness_a.as_ref().unwrap_or(&shared.dummy)),
            tex(4, thickness_b.as_ref().unwrap_or(&shared.dummy)),
            wgpu::BindGroupEntry { binding: 5, resource: rec.look.tables.as_entire_binding() },
            tex(6, &rec.shadow_maps),
            sampler(7, &shared.shadow_sampler),
            tex(8, glitter.as_ref().unwrap_or(&shared.dummy_uint)),
            wgpu::BindGroupEntry { binding: 12, resource: self.half_space.1.as_entire_binding() },
        ];
        entries.extend(views.iter().enumerate().map(|(i, v)| tex(9 + i as u32, v)));
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("LightingPass::group"),
            layout,
            entries: &entries,
        });
        // Every pixel is written (zeros and an exit transmittance of 1 where nothing is drawn).
        let (width, height) = targets.size();
        let mut pass = rec.enc.begin_compute("lighting");
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        Ok(())
    }
}
