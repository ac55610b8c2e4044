//! Dipole light G-buffer pass (shaders/dipole_light.wgsl): the mesh from each directional light,
//! orthographically, into a layer of the light normals and depths ([DirDipoleThesis] step 1).

use super::super::{FrameContext, FrameEncoder, Pass, Pipelines};
use super::{DipoleResources, mesh_pipeline_spec};
use crate::error::Result;
use crate::gpu_mesh::GpuMesh;
use crate::shader::Variant;
use crate::wgpu_util::{buf, layout, uniform_entry};

/// The light G-buffer pass.
#[derive(Debug)]
pub struct DipoleLightPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl DipoleLightPass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> DipoleLightPass {
        let layout =
            layout(device, "DipoleLightPass::layout", &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)]);
        DipoleLightPass { layout, pipelines: Pipelines::default() }
    }

    /// Records `slots` light views of `mesh`.
    ///
    /// # Errors
    /// When the pipeline cannot be built.
    pub fn record(
        &mut self,
        ctx: FrameContext<'_>,
        enc: &mut FrameEncoder<'_>,
        mesh: &GpuMesh,
        res: &DipoleResources,
        slots: u32,
    ) -> Result<()> {
        let shared = ctx.shared;
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || {
            mesh_pipeline_spec(Pass::DipoleLight, &self.layout, "vs_dipole_light", "fs_dipole_light")
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DipoleLightPass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform)],
        });
        let targets = (&[&res.light_normals][..], &res.light_depths);
        enc.draw_mesh_per_layer("dipole light", shared, (pipeline, &group), mesh, targets, slots);
        Ok(())
    }
}
