//! The hair pass (shaders/hair.wgsl): the mesh's lashes and brows ([`rouge_model::mesh::strands`])
//! drawn as fibres after the skin's passes and before the composite. Each strand's segments are
//! screen-space quads around their centre line, shaded by the fibre model ([`crate::fibre`]:
//! \[Marschner2003\]'s lobes with \[Karis2016\]'s fits, absorption from the hairs' colours by
//! [`crate::fibre::sigma_a_from_color`]) under the scene's lights, shadow maps and environment, depth tested against the
//! G-buffer (which leaves the hair out) and accumulated "over", strands sorted back to front on
//! the CPU, into [`Target::Hair`]: premultiplied radiance and transmittance, which the composite
//! lays over the frame in linear radiance.
//!
//! Antialiased (any `--aa` but `none`), a fragment carries the exact box-filter coverage of its
//! fibre's strip (shaders/coverage.wgsl), so a hair thinner than a pixel is a faint line rather
//! than the dotted one the G-buffer's pixel centres make of it; consecutive segments cut at the
//! bisector of their joint, so no pixel is covered twice by one strand.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::error::{RenderError, Result};
use crate::shader::{PassShader, Variant, pass_shader};
use crate::targets::Target;
use crate::wgpu_util::{buf, color, layout, sampler, sampler_entry, tex, tex_entry, uniform_entry, write_instances};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use rouge_model::mesh::{Part, TriangleMesh};

/// Pixels by which an antialiased fibre's quad is widened on each side: the box filter's reach
/// beyond the strip (half the pixel's diagonal, √2/2) and a margin.
pub const WIDEN_PX: f32 = 0.75;

/// One segment of a strand, as `SegmentIn` in shaders/hair.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct HairSegment {
    prev: [f32; 3],
    p0: [f32; 3],
    p1: [f32; 3],
    next: [f32; 3],
    radii: [f32; 2],
    part: u32,
    pad: u32,
}

/// The per-instance vertex layout of [`HairSegment`].
pub fn instance_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Float32x3, 4 => Float32x2, 5 => Uint32
    ];
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<HairSegment>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &ATTRIBUTES,
    }
}

/// The pass's uniform, as `HairPass` in shaders/hair.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct HairUniform {
    pub(crate) params: [f32; 4],
    pub(crate) lash_sigma_a: [f32; 4],
    pub(crate) lash_albedo: [f32; 4],
    pub(crate) brow_sigma_a: [f32; 4],
    pub(crate) brow_albedo: [f32; 4],
    pub(crate) fibre: [f32; 4],
}

impl HairUniform {
    /// The uniform for hairs of these colours ([`crate::HairAlbedo`], made absorption by
    /// [`crate::fibre::sigma_a_from_color`]), with each fibre's albedo for the environment's
    /// light ([`crate::fibre::albedo`]).
    pub fn new(antialiased: bool, hair: crate::HairAlbedo) -> HairUniform {
        let v4 = |c: [f32; 3]| [c[0], c[1], c[2], 0.0];
        let sigma = |c: [f32; 3]| v4(crate::fibre::sigma_a_from_color(c));
        let colour =
            |c: [f32; 3]| v4(crate::fibre::albedo(crate::fibre::sigma_a_from_color(c), crate::fibre::ROUGHNESS_RAD));
        HairUniform {
            params: [if antialiased { 1.0 } else { 0.0 }, if antialiased { WIDEN_PX } else { 0.0 }, 0.0, 0.0],
            lash_sigma_a: sigma(hair.lash),
            lash_albedo: colour(hair.lash),
            brow_sigma_a: sigma(hair.brow),
            brow_albedo: colour(hair.brow),
            fibre: [crate::fibre::ROUGHNESS_RAD, 0.0, 0.0, 0.0],
        }
    }
}

/// The mesh's strands as segments, grouped by strand, with each strand's centre for sorting.
#[derive(Debug, Default)]
pub struct HairStrands {
    segments: Vec<HairSegment>,
    /// Per strand: its segments' range and its centre (mm).
    strands: Vec<(std::ops::Range<usize>, Vec3)>,
    /// The sorted segments on the GPU, grown as needed.
    buffer: Option<(wgpu::Buffer, usize)>,
    /// The eye they were sorted from: a frame from the same eye draws them as they are (a new
    /// mesh or pose makes new strands, so the positions cannot have changed under it).
    sorted_from: Option<Vec3>,
}

impl HairStrands {
    /// The segments of `mesh`'s strands at its current positions, with `brow_fill` × as many
    /// brow hairs again ([`fill_hairs`]); none without strands.
    pub fn of(mesh: &TriangleMesh, brow_fill: f32) -> HairStrands {
        let mut out = HairStrands::default();
        let Some(strands) = mesh.strands.as_deref() else { return out };
        let hairs: Vec<(Part, Vec<(Vec3, f32)>)> = strands
            .strands
            .iter()
            .map(|s| (s.part, s.stations(&mesh.positions)))
            .filter(|(_, st)| st.len() >= 2 && st.iter().all(|(p, r)| p.is_finite() && r.is_finite()))
            .collect();
        let brows: Vec<&[(Vec3, f32)]> =
            hairs.iter().filter(|(p, _)| *p == Part::Brow).map(|(_, st)| st.as_slice()).collect();
        let fill = fill_hairs(&brows, brow_fill);
        for (part, stations) in hairs.iter().map(|(p, st)| (*p, st)).chain(fill.iter().map(|st| (Part::Brow, st))) {
            out.push(part, stations);
        }
        out
    }

    /// Appends one strand's segments.
    fn push(&mut self, part: Part, stations: &[(Vec3, f32)]) {
        let part = u32::from(part == Part::Brow);
        let start = self.segments.len();
        let at = |i: usize| stations[i.min(stations.len() - 1)].0;
        for i in 0..stations.len() - 1 {
            self.segments.push(HairSegment {
                prev: at(i.saturating_sub(1)).to_array(),
                p0: at(i).to_array(),
                p1: at(i + 1).to_array(),
                next: at(i + 2).to_array(),
                radii: [stations[i].1, stations[i + 1].1],
                part,
                pad: 0,
            });
        }
        let centre = stations.iter().map(|(p, _)| *p).sum::<Vec3>() / stations.len() as f32;
        self.strands.push((start..self.segments.len(), centre));
    }

    /// Whether there is nothing to draw.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.strands.len()
    }

    /// The segments with their strands in back-to-front order from `eye`.
    pub fn sorted(&self, eye: Vec3) -> Vec<HairSegment> {
        let mut order: Vec<usize> = (0..self.strands.len()).collect();
        order.sort_by(|&a, &b| {
            self.strands[b].1.distance_squared(eye).total_cmp(&self.strands[a].1.distance_squared(eye))
        });
        order.iter().flat_map(|&s| self.segments[self.strands[s].0.clone()].iter().copied()).collect()
    }
}

/// A fibre gel's extra brow hairs: for a `fill` fraction of the `hairs` (chosen by a fixed hash
/// of their index, so the same ones in every pose), a hair midway between it and the hair whose
/// root is nearest its own: station k the mean of its k-th and the neighbour's at the same
/// fraction of its length, radius too. Where the brow is sparse the new hairs fill the gaps; where
/// it is dense they lie among the others. Each follows the pose, being made from posed hairs.
pub fn fill_hairs(hairs: &[&[(Vec3, f32)]], fill: f32) -> Vec<Vec<(Vec3, f32)>> {
    if fill.is_nan() || fill <= 0.0 || hairs.len() < 2 {
        return Vec::new();
    }
    let chosen = |i: usize| {
        let h = rouge_measure::file_set::mix64(i as u64 ^ 0x6272_6f77_5f66_696c);
        ((h >> 11) as f64 / (1u64 << 53) as f64) < f64::from(fill)
    };
    let mut out = Vec::new();
    for (i, hair) in hairs.iter().enumerate().filter(|(i, _)| chosen(*i)) {
        let root = hair[0].0;
        let Some(near) = (0..hairs.len())
            .filter(|&j| j != i)
            .min_by(|&a, &b| hairs[a][0].0.distance_squared(root).total_cmp(&hairs[b][0].0.distance_squared(root)))
        else {
            continue;
        };
        let other = hairs[near];
        let last = (hair.len() - 1).max(1) as f32;
        out.push(
            hair.iter()
                .enumerate()
                .map(|(k, &(p, r))| {
                    let (q, s) = other[((k as f32 / last) * (other.len() - 1) as f32).round() as usize];
                    ((p + q) * 0.5, 0.5 * (r + s))
                })
                .collect(),
        );
    }
    out
}

/// What the plan gives the pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HairStep {
    /// Box-filter coverage (antialiasing on), or opaque pixel centres.
    pub antialiased: bool,
}

/// The hair pass.
#[derive(Debug)]
pub struct HairPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    uniform: wgpu::Buffer,
    /// What the uniform buffer holds: the step's coverage and the hairs' colours.
    written: Option<(bool, crate::HairAlbedo)>,
}

impl FramePass for HairPass {
    type Step = HairStep;
    const SHADER: PassShader =
        pass_shader!(HairPass, "hair.wgsl", |v| Variant { shadows: v.shadows, env: v.env, ..Variant::BARE });

    fn new(shared: &Shared) -> HairPass {
        let layout = layout(
            &shared.device,
            "HairPass::layout",
            // The vertex stage shades (lights, shadow maps), the fragment stage covers.
            &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                tex_entry(1, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
                sampler_entry(2, wgpu::SamplerBindingType::Comparison),
            ]
            .map(|e| wgpu::BindGroupLayoutEntry { visibility: wgpu::ShaderStages::VERTEX_FRAGMENT, ..e }),
        );
        let uniform =
            crate::wgpu_util::uniform_buffer(&shared.device, "HairPass::uniform", std::mem::size_of::<HairUniform>());
        HairPass { layout, pipelines: Pipelines::default(), uniform, written: None }
    }

    fn name(step: &HairStep) -> String {
        if step.antialiased { "hair (antialiased)".into() } else { "hair".into() }
    }

    /// Records the strands, sorted back to front from the eye, into [`Target::Hair`] (cleared to
    /// no radiance and full transmittance), depth tested against [`Target::Depth`].
    fn record(&mut self, rec: &mut Recording<'_>, step: &HairStep) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let device = &shared.device;
        let hair = rec
            .hair
            .as_deref_mut()
            .ok_or_else(|| RenderError::Invalid("the hair pass needs the mesh's strands".into()))?;
        let key = rec.variant;
        let key = (Self::SHADER.reduce)(key);
        // Radiance and transmittance both "over": rgb = src + dst·(1 − a), a = dst·(1 − a).
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
        };
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            shader: &Self::SHADER,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::HairSegments,
            vs: "vs_hair",
            fs: Some("fs_hair"),
            targets: vec![Some(Target::Hair.format(shared.formats))],
            blend: Some(blend),
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        // The uniform (with each colour's environment albedo, an integral over the sphere) is
        // made again only when what it depends on changes.
        let inputs = (step.antialiased, rec.hair_albedo);
        if self.written != Some(inputs) {
            let uniform = HairUniform::new(step.antialiased, rec.hair_albedo);
            shared.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
            self.written = Some(inputs);
        }
        if hair.sorted_from != Some(rec.eye) || hair.buffer.is_none() {
            let sorted = hair.sorted(rec.eye);
            write_instances((device, &shared.queue), "HairPass::segments", &mut hair.buffer, &sorted);
            hair.sorted_from = Some(rec.eye);
        }
        let Some((buffer, _)) = hair.buffer.as_ref() else {
            return Err(RenderError::Invalid("the hair segments were not uploaded".into()));
        };
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("HairPass::group"),
            layout: &self.layout,
            entries: &[buf(0, &self.uniform), tex(1, &rec.shadow_maps), sampler(2, &shared.shadow_sampler)],
        });
        let out = targets.view(Target::Hair)?;
        let depth = targets.view(Target::Depth)?;
        let depth_attachment = wgpu::RenderPassDepthStencilAttachment {
            view: &depth,
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        };
        let clear = wgpu::Color { r: 0.0, g: 0.0, b: 0.0, a: 1.0 };
        let mut pass = rec.enc.begin("hair", &[color(&out, clear)], Some(depth_attachment));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..6, 0..hair.segments.len() as u32);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fill_adds_hairs_midway_to_the_nearest_neighbour_and_follows_the_fraction() {
        // Three parallel hairs 1 mm and 3 mm apart.
        let hair = |x: f32, r: f32| -> Vec<(Vec3, f32)> { (0..4).map(|k| (Vec3::new(x, k as f32, 0.0), r)).collect() };
        let (a, b, c) = (hair(0.0, 0.1), hair(1.0, 0.05), hair(4.0, 0.1));
        let hairs = [a.as_slice(), b.as_slice(), c.as_slice()];
        assert!(fill_hairs(&hairs, 0.0).is_empty());
        assert!(fill_hairs(&hairs, f32::NAN).is_empty());
        let full = fill_hairs(&hairs, 1.0);
        assert_eq!(full.len(), 3);
        // a's neighbour is b: midway at x 0.5, radius the mean; c's is b: x 2.5.
        assert!(full[0].iter().all(|(p, r)| (p.x - 0.5).abs() < 1e-6 && (r - 0.075).abs() < 1e-6));
        assert!(full[2].iter().all(|(p, _)| (p.x - 2.5).abs() < 1e-6));
        // A fraction of them, the same ones every time.
        let many: Vec<Vec<(Vec3, f32)>> = (0..400).map(|i| hair(i as f32, 0.1)).collect();
        let refs: Vec<&[(Vec3, f32)]> = many.iter().map(Vec::as_slice).collect();
        let half = fill_hairs(&refs, 0.5);
        assert!((170..230).contains(&half.len()), "{}", half.len());
        assert_eq!(half, fill_hairs(&refs, 0.5));
    }
}
