//! What the full-screen passes that add a diffusion model's light to the skin share (the dipoles'
//! combination, the cube atlas's gather): the G-buffer they read per pixel (bindings 1-3, with
//! shaders/skin_pixel.wgsl), the model's unfilterable 2D arrays after them, one uniform at
//! binding 0, the cosmetic stack's transmittance at binding 15 (when the look has layers), and
//! the additive draw into [`Target::Diffuse`] that keeps the skin flag in alpha.
//!
//! **Light into the skin through the makeup.** The screen-space path attenuates the skin's light
//! by the stack's T where it enters (the lighting pass) and again where it leaves (the composite).
//! A diffusion model gathers light that entered elsewhere; its entry point's T is taken as the
//! exit pixel's (the stack varies slowly against the diffusion length), so the composite's exit
//! T is not the only one: without it, skin under foundation read 1/T too bright.

use super::{PipelineSpec, Pipelines, Recording, Vertices};
use crate::error::Result;
use crate::shader::{PassShader, Variant};
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{buf, color_load, float_tex, layout, tex, tex_entry, uniform_entry};

/// The frame targets such a pass reads (and [`Target::ExitT`] when the look has layers).
pub fn inputs() -> [Target; 3] {
    [Target::Normal, Target::Albedo, Target::Depth]
}

/// The binding of the stack's transmittance.
const EXIT_T_BINDING: u32 = 15;

/// A pass's bind-group layout and pipelines.
#[derive(Debug)]
pub struct SkinGather {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    shader: &'static PassShader,
    fs: &'static str,
}

impl SkinGather {
    /// The layout of the pass of `shader` (fragment entry `fs`): the uniform, the three G-buffer
    /// targets and `arrays` 2D arrays.
    pub fn new(device: &wgpu::Device, shader: &'static PassShader, fs: &'static str, arrays: u32) -> SkinGather {
        let mut entries = vec![uniform_entry(0, wgpu::ShaderStages::FRAGMENT)];
        entries.extend((1..=3).map(|b| float_tex(b, false)));
        entries.extend((0..arrays).map(|i| {
            tex_entry(4 + i, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array)
        }));
        entries.push(float_tex(EXIT_T_BINDING, false));
        let layout = layout(device, &format!("{}::layout", shader.owner), &entries);
        SkinGather { layout, pipelines: Pipelines::default(), shader, fs }
    }

    /// Records the pass labelled `label` into [`Target::Diffuse`] (added), with `uniform` and the
    /// model's `arrays` (array views, in binding order).
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(
        &mut self,
        rec: &mut Recording<'_>,
        label: &str,
        uniform: &wgpu::Buffer,
        arrays: &[wgpu::TextureView],
    ) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let (shader, fs) = (self.shader, self.fs);
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || PipelineSpec {
            shader,
            variant: Variant::BARE,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some(fs),
            targets: vec![Some(HDR_FORMAT)],
            blend: Some(crate::wgpu_util::ADD_RGB_KEEP_ALPHA),
            depth: None,
        })?;
        let gbuffer = inputs().map(|t| targets.view(t));
        let [normal, albedo, depth] = gbuffer;
        let (normal, albedo, depth) = (normal?, albedo?, depth?);
        let diffuse = targets.view(Target::Diffuse)?;
        // The shader reads the stack's T only when the frame has layers (`frame.counts.y`).
        let exit_t = if rec.variant.layers > 0 { Some(targets.view(Target::ExitT)?) } else { None };
        let mut entries = vec![buf(0, uniform), tex(1, &normal), tex(2, &albedo), tex(3, &depth)];
        entries.extend(arrays.iter().enumerate().map(|(i, v)| tex(4 + i as u32, v)));
        entries.push(tex(EXIT_T_BINDING, exit_t.as_ref().unwrap_or(&shared.dummy)));
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{}::group", shader.owner)),
            layout: &self.layout,
            entries: &entries,
        });
        let mut rp = rec.enc.begin(label, &[color_load(&diffuse)], None);
        rp.set_pipeline(pipeline);
        rp.set_bind_group(0, &shared.frame_group, &[]);
        rp.set_bind_group(1, &group, &[]);
        rp.draw(0..3, 0..1);
        Ok(())
    }
}
