//! Thickness translucency pass (shaders/thickness.wgsl): the light that crossed thin parts of
//! the mesh from behind, \[BarreBrisebois2011\]'s term ([`crate::local_thickness`]) for every
//! light, added to the skin's diffuse radiance before composition. It runs for materials whose
//! subsurface model is [`crate::scene::SubsurfaceModel::Thickness`]; the G-buffer then carries
//! the local thickness and the material id ([`Target::LocalThickness`]), and the per-material
//! parameters live in this pass's uniform, indexed by that id (the talk's material-id packing).
//! Under the slab law ([`crate::scene::SubsurfaceModel::Slab`]) the same pass lights the skin as a
//! plane slab of the thickness each light crossed ([`crate::slab_transmittance`]), over the
//! share of the slab's plane the light's map holds, drained toward the exit face's edges where
//! the medium ends in a side face the light does not reach ([`crate::slab_extent`],
//! shaders/slab_edge.wgsl), and its light scattered once marched along the view ray to the back
//! faces' depth ([`crate::slab_march`], [`super::back_depth`]); its table is
//! uploaded the first time a frame needs it, and a one-value stand-in is bound otherwise.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::{RenderError, Result};
use crate::local_thickness::TranslucencyParams;
use crate::scene::SlabThrough;
use crate::shader::{PassShader, Variant, pass_shader};
use crate::slab_transmittance;
use crate::targets::{HDR_FORMAT, Target};
use crate::wgpu_util::{
    buf, buffer_init, color_load, float_tex, layout, storage_entry, tex, tex_entry, uniform_buffer, uniform_entry,
};
use bytemuck::{Pod, Zeroable};
use rouge_model::medium::Medium;
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
    /// x: 1 for the exponential falloff, 0 for the power falloff; y (slab law only): 1 for the
    /// transmission gather ([`crate::scene::SlabThrough::gpu_flag`]).
    pub kind: [u32; 4],
    /// The slab law's reduced albedo α′ per channel (zero under the talk's term).
    pub slab_albedo: [f32; 4],
    /// Case's decay rate κ(α′) per channel ([`slab_transmittance::kappa`]).
    pub slab_kappa: [f32; 4],
    /// σt′ = σa + σs′ per channel, mm⁻¹.
    pub slab_sigma_t: [f32; 4],
    /// x the skin's index η (the table is interpolated at it per medium, and the shader's single
    /// scattering refracts by it), then the table's thickness and cosine nodes, ln(1 + τ_max).
    pub slab_axes: [f32; 4],
    /// The hidden-entry gather's classic dipole per channel: α′, σ_tr (mm⁻¹), z_r, z_v (mm)
    /// ([`crate::diffusion::ChannelProfile::classic_constants`]).
    pub gather_medium: [[f32; 4]; 3],
    /// The hidden-entry gather: η, reach (mm), samples (0: off), the radii's sampling rate (mm⁻¹).
    pub gather: [f32; 4],
    /// The screen-space kernel the gather leaves the seen entries' light to: x its reach on the
    /// surface (mm; 0 where no kernel runs), y the depth difference (mm) over which it stops
    /// following a sample ([`crate::scene::SssSettings`]).
    pub screen_kernel: [f32; 4],
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
        ThicknessUniform { materials, falloff, kind: [kind, 0, 0, 0], ..ThicknessUniform::zeroed() }
    }

    /// The uniform of the slab law for a skin of `medium`, with the screen-space kernel's reach
    /// and depth-follow distance (mm) where one runs, and what carries the light that crossed
    /// the mesh (`through`).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] if the compiled-in table is malformed, or the medium's
    /// coefficients give no finite reduced albedo and extinction, or its η is outside the table.
    pub fn slab(medium: &Medium, kernel: Option<(f32, f32)>, through: SlabThrough) -> Result<ThicknessUniform> {
        let axes = slab_transmittance::axes()?;
        let alpha = medium.reduced_albedo();
        let sigma_t = medium.sigma_t_prime_per_mm();
        if let Some(c) = (0..3).find(|&c| !(sigma_t[c].is_finite() && sigma_t[c] > 0.0 && alpha[c].is_finite())) {
            return Err(RenderError::Invalid(format!(
                "the slab law needs a finite, positive σa + σs′: {} has {} mm⁻¹ in channel {c}",
                medium.name, sigma_t[c]
            )));
        }
        if !(1.0..=axes.eta_max).contains(&medium.eta) {
            return Err(RenderError::Invalid(format!(
                "the slab law's table covers η from 1 to {}: {} has η {}",
                axes.eta_max, medium.name, medium.eta
            )));
        }
        let rgb = |v: [f64; 3]| [v[0] as f32, v[1] as f32, v[2] as f32, 0.0];
        let (gather_medium, gather) = slab_transmittance::hidden_entry_constants(medium, through.gather_samples());
        let mut materials = [[0.0; 4]; MATERIAL_IDS];
        materials[SKIN_MATERIAL_ID] = [0.0, 1.0, 0.0, 0.0];
        Ok(ThicknessUniform {
            materials,
            kind: [0, through.gpu_flag(), 0, 0],
            slab_albedo: rgb(alpha),
            slab_kappa: rgb(alpha.map(slab_transmittance::kappa)),
            slab_sigma_t: rgb(sigma_t),
            slab_axes: [medium.eta as f32, axes.taus as f32, axes.mus as f32, axes.tau_max.ln_1p() as f32],
            gather_medium,
            gather,
            screen_kernel: kernel.map_or([0.0; 4], |(reach, follow)| [reach, follow, 0.0, 0.0]),
            ..ThicknessUniform::zeroed()
        })
    }

    /// Whether this is the slab law's uniform.
    pub fn is_slab(&self) -> bool {
        self.slab_axes[0] > 0.0
    }
}

/// The thickness translucency pass.
#[derive(Debug)]
pub struct ThicknessPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    uniform: wgpu::Buffer,
    /// The slab law's table at the albedos and η (the uniform's, as bits) a frame last used it for;
    /// a one-value stand-in binds in its place for the talk's term.
    slab_table: Option<([u32; 4], wgpu::Buffer)>,
    stand_in: wgpu::Buffer,
}

/// The targets the pass reads (the slab law also reads [`Target::BackDepth`]).
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
                storage_entry(6),
                // The back faces' depth (the slab law's), read as the G-buffer's depth is.
                float_tex(7, false),
            ],
        );
        let uniform = uniform_buffer(device, "ThicknessPass::uniform", std::mem::size_of::<ThicknessUniform>());
        let stand_in =
            buffer_init(device, "ThicknessPass::stand_in", bytemuck::bytes_of(&0.0f32), wgpu::BufferUsages::STORAGE);
        ThicknessPass { layout, pipelines: Pipelines::default(), uniform, slab_table: None, stand_in }
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
        // The slab law marches its single scattering to the back faces' depth; the talk's term
        // reads none, and the G-buffer's depth stands in.
        let back = if uniform.is_slab() { targets.view(Target::BackDepth)? } else { depth.clone() };
        let [r, g, b, _] = uniform.slab_albedo;
        let key = [r, g, b, uniform.slab_axes[0]].map(f32::to_bits);
        if uniform.is_slab() && self.slab_table.as_ref().is_none_or(|(k, _)| *k != key) {
            let albedo = std::array::from_fn(|c| f64::from(uniform.slab_albedo[c]));
            // The uniform holds the η the plan checked as an f32: the table's last node, 1.6,
            // comes back as 1.6000000238 (a medium at η 1.6 failed to render before this).
            let eta = f64::from(uniform.slab_axes[0]).min(slab_transmittance::axes()?.eta_max);
            let values = slab_transmittance::medium_values(albedo, eta)?;
            let buffer = buffer_init(
                &shared.device,
                "ThicknessPass::slab_table",
                bytemuck::cast_slice(&values),
                wgpu::BufferUsages::STORAGE,
            );
            self.slab_table = Some((key, buffer));
        }
        let table = match &self.slab_table {
            Some((_, buffer)) if uniform.is_slab() => buffer,
            _ => &self.stand_in,
        };
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
                buf(6, table),
                tex(7, &back),
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
