//! Dipole radiance-map pass (shaders/dipole_radiance.wgsl): the mesh from each of K directions,
//! orthographically, each texel gathering the BSSRDF over a disk of the light G-buffer
//! ([DirDipoleThesis] step 2), blended into the maps with weight 1/(n + 1) after n frames.

use super::super::{FrameContext, FrameEncoder, Pass, PipelineSpec, Pipelines, Vertices};
use super::{DipoleResources, layer_view};
use crate::error::Result;
use crate::gpu_mesh::GpuMesh;
use crate::shader::Variant;
use crate::targets::HDR_FORMAT;
use crate::wgpu_util::{array_view, buf, depth_clear, layout, tex, tex_entry, uniform_entry};

/// The radiance-map pass.
#[derive(Debug)]
pub struct DipoleRadiancePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl DipoleRadiancePass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> DipoleRadiancePass {
        let array =
            |b| tex_entry(b, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array);
        let layout = layout(
            device,
            "DipoleRadiancePass::layout",
            &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT), array(1), array(2)],
        );
        DipoleRadiancePass { layout, pipelines: Pipelines::default() }
    }

    /// Records the `directions` maps; this frame's samples weigh `blend` (1 replaces).
    ///
    /// # Errors
    /// When the pipeline cannot be built.
    pub fn record(
        &mut self,
        ctx: FrameContext<'_>,
        enc: &mut FrameEncoder<'_>,
        mesh: &GpuMesh,
        res: &DipoleResources,
        directions: u32,
        blend: f64,
    ) -> Result<()> {
        let shared = ctx.shared;
        // new = old·(1 − w) + sample·w, w the blend constant.
        let mix = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Constant,
            dst_factor: wgpu::BlendFactor::OneMinusConstant,
            operation: wgpu::BlendOperation::Add,
        };
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || PipelineSpec {
            pass: Pass::DipoleRadiance,
            variant: Variant::BARE,
            layout: &self.layout,
            vertices: Vertices::Mesh,
            vs: "vs_dipole_radiance",
            fs: Some("fs_dipole_radiance"),
            targets: vec![Some(HDR_FORMAT)],
            blend: Some(wgpu::BlendState { color: mix, alpha: mix }),
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        let (normals, depths) = (array_view(&res.light_normals), array_view(&res.light_depths));
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DipoleRadiancePass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform), tex(1, &normals), tex(2, &depths)],
        });
        for k in 0..directions {
            let (map, depth) = (layer_view(&res.maps, k), layer_view(&res.map_depths, k));
            // The first frame clears (its weight is 1); later ones keep what the map holds.
            let load = if blend >= 1.0 { wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT) } else { wgpu::LoadOp::Load };
            let attachment = wgpu::RenderPassColorAttachment {
                view: &map,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
            };
            let mut pass = enc.begin("dipole radiance", &[Some(attachment)], depth_clear(&depth));
            pass.set_pipeline(pipeline);
            pass.set_blend_constant(wgpu::Color { r: blend, g: blend, b: blend, a: blend });
            pass.set_bind_group(0, &shared.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            mesh.draw_instance(&mut pass, k);
        }
        Ok(())
    }
}
