//! Dipole radiance-map pass (shaders/dipole_radiance.wgsl): the mesh from each of K directions,
//! orthographically, each texel gathering the BSSRDF over a disk of the light G-buffer
//! (\[DirDipoleThesis\] step 2); after n frames of one state each texel holds the mean of its n
//! frames (the shader mixes in the previous frame's map of the ping-pong pair).

use super::super::{FramePass, Pipelines, Recording, Shared};
use super::mesh_pipeline_spec;
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::wgpu_util::{array_view, buf, layout, tex, tex_entry, uniform_entry};

/// The radiance-map pass.
#[derive(Debug)]
pub struct DipoleRadiancePass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl FramePass for DipoleRadiancePass {
    /// The radiance-map directions K.
    type Step = u32;
    const SHADER: PassShader = pass_shader!(DipoleRadiancePass, "dipole_radiance.wgsl", bare);

    fn new(shared: &Shared) -> DipoleRadiancePass {
        let device = &shared.device;
        let array =
            |b| tex_entry(b, wgpu::TextureSampleType::Float { filterable: false }, wgpu::TextureViewDimension::D2Array);
        let layout = layout(
            device,
            "DipoleRadiancePass::layout",
            &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT), array(1), array(2), array(3)],
        );
        DipoleRadiancePass { layout, pipelines: Pipelines::default() }
    }

    fn name(_: &u32) -> String {
        "dipole radiance".into()
    }

    /// Records this frame's maps, one per direction.
    fn record(&mut self, rec: &mut Recording<'_>, &directions: &u32) -> Result<()> {
        let (shared, res) = (rec.shared, &*rec.dipole);
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || {
            mesh_pipeline_spec(&Self::SHADER, &self.layout, "vs_layer", "fs_dipole_radiance")
        })?;
        let (normals, depths) = (array_view(&res.light_normals), array_view(&res.light_depths));
        let (current, previous) = res.current_and_previous();
        let previous = array_view(previous);
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DipoleRadiancePass::group"),
            layout: &self.layout,
            entries: &[buf(0, &res.uniform), tex(1, &normals), tex(2, &depths), tex(3, &previous)],
        });
        let targets = (&[current][..], &res.map_depths);
        rec.enc.draw_mesh_per_layer("dipole radiance", shared, (pipeline, &group), rec.mesh, targets, directions);
        Ok(())
    }
}
