//! Back-face depth pass (shaders/back_depth.wgsl): the depth of the nearest face turned from the
//! camera at each pixel into [`Target::BackDepth`], where the camera's ray leaves the mesh. The
//! slab law ([`crate::scene::SubsurfaceModel::Slab`]) marches the light scattered once along
//! the view ray to it ([`crate::slab_march`]); no other model reads it, and the frame plan runs
//! it only under the slab law.

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::targets::Target;
use crate::wgpu_util::{depth_clear, layout};

/// The back-face depth pass.
#[derive(Debug)]
pub struct BackDepthPass {
    layout: wgpu::BindGroupLayout,
    group: wgpu::BindGroup,
    pipelines: Pipelines,
}

impl FramePass for BackDepthPass {
    type Step = ();
    const SHADER: PassShader = pass_shader!(BackDepthPass, "back_depth.wgsl", bare);

    fn new(shared: &Shared) -> BackDepthPass {
        let layout = layout(&shared.device, "BackDepthPass::layout", &[]);
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("BackDepthPass::group"),
            layout: &layout,
            entries: &[],
        });
        BackDepthPass { layout, group, pipelines: Pipelines::default() }
    }

    fn name(_: &()) -> String {
        "back depth".into()
    }

    /// Records the mesh's back faces' depth into [`Target::BackDepth`].
    fn record(&mut self, rec: &mut Recording<'_>, _: &()) -> Result<()> {
        let shared = rec.shared;
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || {
            let bias = wgpu::DepthBiasState::default();
            PipelineSpec::mesh_depth(&Self::SHADER, &self.layout, "vs_back_depth", Some("fs_back_depth"), bias)
        })?;
        let depth = rec.targets.view(Target::BackDepth)?;
        let mut pass = rec.enc.begin("back depth", &[], depth_clear(&depth));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &self.group, &[]);
        // What the G-buffer draws: not the hairs the hair pass draws as fibres (they are not
        // the medium, and in front of the skin their back faces would cut the ray short).
        rec.mesh.draw_positions_of(&mut pass, rec.variant.hair);
        Ok(())
    }
}
