//! G-buffer pass: world normals and coverage, albedo with the skin flag, the cosmetic layers'
//! thickness (mm) sampled from their maps, the local thickness and material id of the thickness
//! translucency, and depth (shaders/gbuffer.wgsl). The thickness targets exist only in variants
//! with layers: 0-3 with any layer, 4-7 with more than four; the local thickness only when a
//! material uses the thickness model; the glitter's flake-field coordinates only when a layer has
//! glitter. Each target keeps its location (4 for the local thickness, 5 for the glitter's)
//! whatever the others, so a left-out target leaves its location empty.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::Result;
use crate::shader::{PassShader, ThicknessVariant, Variant, pass_shader};
use crate::targets::Target;
use crate::wgpu_util::{color, depth_clear, float_tex, layout, sampler, sampler_entry, tex, tex_entry};

/// The G-buffer pass.
#[derive(Debug)]
pub struct GbufferPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

/// The colour targets a variant writes, by location (`None` where the variant leaves one out).
pub fn slots(variant: Variant) -> Vec<Option<Target>> {
    let mut t = vec![
        Some(Target::Normal),
        Some(Target::Albedo),
        (variant.layers > 0).then_some(Target::ThicknessA),
        (variant.layers > 4).then_some(Target::ThicknessB),
        (variant.thickness != ThicknessVariant::Off).then_some(Target::LocalThickness),
        variant.glitter.then_some(Target::Glitter),
    ];
    while t.last() == Some(&None) {
        t.pop();
    }
    t
}

/// The bytes per pixel of the colour targets a variant writes, as WebGPU counts them against
/// `maxColorAttachmentBytesPerSample` (each target's render-target byte cost after aligning to
/// its component alignment, in location order).
pub fn bytes_per_sample(variant: Variant) -> u32 {
    let formats = crate::targets::Formats::for_backend(wgpu::Backend::Vulkan);
    outputs(variant).into_iter().fold(0, |total, t| {
        let f = t.format(formats);
        let align = f.target_component_alignment().unwrap_or(1);
        total.div_ceil(align) * align + f.target_pixel_byte_cost().unwrap_or(0)
    })
}

/// The colour targets a variant writes, in location order.
pub fn outputs(variant: Variant) -> Vec<Target> {
    slots(variant).into_iter().flatten().collect()
}

impl FramePass for GbufferPass {
    type Step = ();
    const SHADER: PassShader = pass_shader!(GbufferPass, "gbuffer.wgsl", |v| Variant {
        layers: v.layers,
        albedo_map: v.albedo_map,
        normal_map: v.normal_map,
        skin_detail: v.skin_detail,
        // The G-buffer writes the material id for either shadow-map law alike.
        thickness: match v.thickness {
            ThicknessVariant::Slab => ThicknessVariant::ShadowMap,
            t => t,
        },
        glitter: v.glitter,
        ..Variant::BARE
    });

    fn new(shared: &Shared) -> GbufferPass {
        let layout = layout(
            &shared.device,
            "GbufferPass::layout",
            &[
                tex_entry(0, wgpu::TextureSampleType::Float { filterable: true }, wgpu::TextureViewDimension::D2Array),
                sampler_entry(1, wgpu::SamplerBindingType::Filtering),
                float_tex(2, true),
                float_tex(3, true),
                float_tex(4, true),
                float_tex(5, true),
                float_tex(6, true),
                sampler_entry(7, wgpu::SamplerBindingType::Filtering),
                float_tex(8, true),
            ],
        );
        GbufferPass { layout, pipelines: Pipelines::default() }
    }

    fn name(_: &()) -> String {
        "gbuffer".into()
    }

    /// Records the mesh with the look's thickness maps and the skin textures into the targets of
    /// [`outputs`] and [`Target::Depth`].
    fn record(&mut self, rec: &mut Recording<'_>, _: &()) -> Result<()> {
        let (shared, targets, look, textures) = (rec.shared, rec.targets, rec.look, rec.textures);
        let key = rec.key(&Self::SHADER);
        let slots = slots(key);
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            shader: &Self::SHADER,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::Mesh,
            vs: "vs_gbuffer",
            fs: Some("fs_gbuffer"),
            targets: slots.iter().map(|t| t.map(|t| t.format(shared.formats))).collect(),
            blend: None,
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
                tex(4, textures.local_thickness.as_ref().unwrap_or(&shared.dummy)),
                tex(5, textures.detail.as_ref().map_or(&shared.dummy, |d| &d.tile)),
                tex(6, textures.detail.as_ref().map_or(&shared.dummy, |d| &d.regions)),
                sampler(7, &shared.repeat_sampler),
                tex(8, textures.wrinkles.as_ref().map_or(&shared.dummy, |w| &w.view)),
            ],
        });
        let views = slots.iter().map(|t| t.map(|t| targets.view(t)).transpose()).collect::<Result<Vec<_>>>()?;
        let depth = targets.view(Target::Depth)?;
        let attachments: Vec<_> =
            views.iter().map(|v| v.as_ref().and_then(|v| color(v, wgpu::Color::TRANSPARENT))).collect();
        let mut pass = rec.enc.begin("gbuffer", &attachments, depth_clear(&depth));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        // Hairs drawn as fibres by the hair pass are left out of the G-buffer.
        if rec.variant.hair {
            rec.mesh.draw_without_hair(&mut pass)
        } else {
            rec.mesh.draw(&mut pass)
        }
        Ok(())
    }
}
