//! Thickness translucency pass (shaders/thickness.wgsl): the light that crossed thin parts of
//! the mesh from behind, \[BarreBrisebois2011\]'s term ([`crate::local_thickness`]) for every
//! light, added to the skin's diffuse radiance before composition. It runs for materials whose
//! subsurface model is [`crate::scene::SubsurfaceModel::Thickness`]; the G-buffer then carries
//! the local thickness and the material id ([`Target::LocalThickness`]), and the per-material
//! parameters live in this pass's uniform, indexed by that id (the talk's material-id packing).

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::Result;
use crate::local_thickness::TranslucencyParams;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{buf, color_load, float_tex, layout, tex, tex_entry, uniform_buffer, uniform_entry};
use bytemuck::{Pod, Zeroable};
use rouge_model::thickness::Falloff;

/// Translucency material ids the G-buffer's 2-bit alpha can hold (0 is "none").
pub const MATERIAL_IDS: usize = 4;
/// The skin's material id.
pub const SKIN_MATERIAL_ID: usize = 1;

/// The pass's uniform, as in WGSL `ThicknessPass`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ThicknessUniform {
    /// Per material id: distortion, power, scale, ambient (id 0: none, all zero).
    pub materials: [[f32; 4]; MATERIAL_IDS],
    /// The shadow-map source's falloff: rgb rates per mm (exponential) or the exponent in x
    /// (power); w: the cutoff, mm.
    pub falloff: [f32; 4],
    /// x: 1 for the exponential falloff, 0 for the power falloff.
    pub kind: [u32; 4],
}

impl ThicknessUniform {
    /// The uniform for the skin's `params` and the falloff of the shadow-map source.
    pub fn new(skin: TranslucencyParams, falloff: Falloff, cutoff_mm: f32) -> ThicknessUniform {
        let mut materials = [[0.0; 4]; MATERIAL_IDS];
        materials[SKIN_MATERIAL_ID] = skin.to_gpu();
        let (falloff, kind) = match falloff {
            Falloff::Power { exponent } => ([exponent, 0.0, 0.0, cutoff_mm], 0),
            Falloff::Exponential { per_mm } => ([per_mm[0], per_mm[1], per_mm[2], cutoff_mm], 1),
        };
        ThicknessUniform { materials, falloff, kind: [kind, 0, 0, 0] }
    }
}

/// The thickness translucency pass.
#[derive(Debug)]
pub struct ThicknessPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    uniform: wgpu::Buffer,
}

/// The targets the pass reads.
pub fn inputs() -> [Target; 4] {
    [Target::Normal, Target::Albedo, Target::Depth, Target::LocalThickness]
}

impl FramePass for ThicknessPass {
    /// The uniform: the skin's parameters and the local thickness's falloff.
    type Step = ThicknessUniform;
    const SHADER: PassShader =
        pass_shader!(ThicknessPass, "thickness.wgsl", |v| Variant { thickness: v.thickness, ..Variant::BARE });

    fn new(shared: &Shared) -> ThicknessPass {
        let device = &shared.device;
        let layout = layout(
            device,
            "ThicknessPass::layout",
            &[
                float_tex(0, false),
                float_tex(1, false),
                // Depth and shadow maps read as unfilterable floats (textureLoad), as lighting.wgsl.
                float_tex(2, false),
                float_tex(3, false),
                tex_entry(4, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array),
                uniform_entry(5, wgpu::ShaderStages::FRAGMENT),
            ],
        );
        let uniform = uniform_buffer(device, "ThicknessPass::uniform", std::mem::size_of::<ThicknessUniform>());
        ThicknessPass { layout, pipelines: Pipelines::default(), uniform }
    }

    fn name(_: &ThicknessUniform) -> String {
        "thickness".into()
    }

    /// Writes the step's uniform and adds the translucency to [`Target::Diffuse`].
    fn record(&mut self, rec: &mut Recording<'_>, uniform: &ThicknessUniform) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        shared.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(uniform));
        let key = rec.key(&Self::SHADER);
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            shader: &Self::SHADER,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some("fs_thickness"),
            targets: vec![Some(HDR_FORMAT)],
            blend: Some(crate::wgpu_util::ADD_RGB_KEEP_ALPHA),
            depth: None,
        })?;
        let [normal, albedo, depth, local] = inputs().map(|t| targets.view(t));
        let (normal, albedo, depth, local) = (normal?, albedo?, depth?, local?);
        let diffuse = targets.view(Target::Diffuse)?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ThicknessPass::group"),
            layout: &self.layout,
            entries: &[
                tex(0, &normal),
                tex(1, &albedo),
                tex(2, &depth),
                tex(3, &local),
                tex(4, &rec.shadow_maps),
                buf(5, &self.uniform),
            ],
        });
        let mut pass = rec.enc.begin("thickness", &[color_load(&diffuse)], None);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
