//! Dipole light G-buffer pass (shaders/dipole_light.wgsl): the mesh from each directional light,
//! orthographically, into a layer of the light normals and depths (\[DirDipoleThesis\] step 1).
//! As the first of the dipole passes of a frame, it also sizes their maps and writes their
//! uniform ([`DipoleStep`]), starting the radiance maps afresh when what they depend on changed.

use super::super::{FramePass, Pipelines, Recording, Shared};
use super::{DipoleStep, DipoleUniform, mesh_pipeline_spec};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::wgpu_util::{buf, layout, uniform_entry};

/// The light G-buffer pass.
#[derive(Debug)]
pub struct DipoleLightPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl FramePass for DipoleLightPass {
    type Step = DipoleStep;
    const SHADER: PassShader = pass_shader!(DipoleLightPass, "dipole_light.wgsl", bare);

    fn new(shared: &Shared) -> DipoleLightPass {
        let layout =
            layout(&shared.device, "DipoleLightPass::layout", &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)]);
        DipoleLightPass { layout, pipelines: Pipelines::default() }
    }

    fn name(_: &DipoleStep) -> String {
        "dipole light".into()
    }

    /// Sizes the dipole maps, writes the passes' uniform and records one light view per slot.
    fn record(&mut self, rec: &mut Recording<'_>, step: &DipoleStep) -> Result<()> {
        let shared = rec.shared;
        let res = &mut *rec.dipole;
        res.ensure(&shared.device, &step.settings, step.slots(), shared.formats.min_array_layers);
        let frame_index = res.next_frame(step.state_key(rec.mesh_generation), step.settings.progressive);
        let uniform = DipoleUniform::new(step, &rec.mesh.bounds, frame_index);
        shared.queue.write_buffer(&res.uniform, 0, bytemuck::bytes_of(&uniform));
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || {
            mesh_pipeline_spec(&Self::SHADER, &self.layout, "vs_layer", "fs_dipole_light")
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DipoleLightPass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform)],
        });
        let targets = (&[&res.light_normals][..], &res.light_depths);
        rec.enc.draw_mesh_per_layer("dipole light", shared, (pipeline, &group), rec.mesh, targets, step.slots());
        Ok(())
    }
}
