//! Cube-atlas gather pass (shaders/atlas_gather.wgsl): per skin pixel, face selection with the
//! self-occlusion test, the local dipole gather and the global term, added to the skin's diffuse
//! radiance ([Benmounah2009] sections 4.2-4.4).

use super::super::skin_gather::SkinGather;
use super::super::{FrameContext, FrameEncoder, Pass};
use super::AtlasResources;
use crate::error::Result;
use crate::wgpu_util::array_view;

/// The gather pass.
#[derive(Debug)]
pub struct AtlasGatherPass(SkinGather);

impl AtlasGatherPass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> AtlasGatherPass {
        AtlasGatherPass(SkinGather::new(device, Pass::AtlasGather, "fs_atlas_gather", 3))
    }

    /// Records the gather into the skin's diffuse radiance (added).
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(&mut self, ctx: FrameContext<'_>, enc: &mut FrameEncoder<'_>, res: &AtlasResources) -> Result<()> {
        let arrays = [array_view(&res.irradiance), array_view(&res.normals), array_view(&res.depths)];
        self.0.record(ctx, enc, "atlas gather", &res.uniform, &arrays)
    }
}
