//! Depth copy (shaders/depth_copy.wgsl): the depth buffer's bits into an Rgba8Unorm target, on backends
//! whose depth textures cannot be copied to buffers (wgpu's GL backend), so that picking and
//! frame captures read depth everywhere. Not part of the frame plan: it runs on demand, when
//! the depth of the last frame is read back.

use super::{FrameEncoder, PipelineSpec, Pipelines, Shared, Vertices};
use crate::error::Result;
use crate::shader::{PassShader, Variant, bare, pass_shader};
use crate::wgpu_util::{color, float_tex, layout, tex};

/// Format of the copy: the depth's f32 bits in four unorm bytes (exact: k/255 rounds back to k).
pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The depth copy's shader.
pub const SHADER: PassShader = pass_shader!(DepthCopyPass, "depth_copy.wgsl", bare);

/// The depth copy pass.
#[derive(Debug)]
pub struct DepthCopyPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
}

impl DepthCopyPass {
    /// The pass on `shared`'s device.
    pub fn new(shared: &Shared) -> DepthCopyPass {
        let layout = layout(&shared.device, "DepthCopyPass::layout", &[float_tex(0, false)]);
        DepthCopyPass { layout, pipelines: Pipelines::default() }
    }

    /// Records the copy of `depth` (a Depth32Float view) into `out` (an [`OUTPUT_FORMAT`] view
    /// of the same size).
    ///
    /// # Errors
    /// When the pipeline cannot be built.
    pub fn record(
        &mut self,
        shared: &Shared,
        enc: &mut FrameEncoder<'_>,
        depth: &wgpu::TextureView,
        out: &wgpu::TextureView,
    ) -> Result<()> {
        let pipeline = self.pipelines.get_or_build(shared, Variant::BARE, || PipelineSpec {
            shader: &SHADER,
            variant: Variant::BARE,
            layout: &self.layout,
            vertices: Vertices::Fullscreen,
            vs: "vs_fullscreen",
            fs: Some("fs_depth_copy"),
            targets: vec![Some(OUTPUT_FORMAT)],
            blend: None,
            depth: None,
        })?;
        let group = shared.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("DepthCopyPass::group"),
            layout: &self.layout,
            entries: &[tex(0, depth)],
        });
        let mut pass = enc.begin("depth copy", &[color(out, wgpu::Color::WHITE)], None);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
