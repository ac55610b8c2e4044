//! Dipole combination pass (shaders/dipole_combine.wgsl): per skin pixel, the radiance maps of
//! the directions that see the point, averaged, times the exit Fresnel transmittance, added to
//! the skin's diffuse radiance ([DirDipoleThesis] step 3).

use super::super::skin_gather::SkinGather;
use super::super::{FrameContext, FrameEncoder, Pass};
use super::DipoleResources;
use crate::error::Result;
use crate::wgpu_util::array_view;

/// The combination pass.
#[derive(Debug)]
pub struct DipoleCombinePass(SkinGather);

impl DipoleCombinePass {
    /// The pass on `device`.
    pub fn new(device: &wgpu::Device) -> DipoleCombinePass {
        DipoleCombinePass(SkinGather::new(device, Pass::DipoleCombine, "fs_dipole_combine", 2))
    }

    /// Records the combination into the skin's diffuse radiance (added).
    ///
    /// # Errors
    /// When the pipeline cannot be built or a target is missing.
    pub fn record(&mut self, ctx: FrameContext<'_>, enc: &mut FrameEncoder<'_>, res: &DipoleResources) -> Result<()> {
        let arrays = [array_view(res.current_and_previous().0), array_view(&res.map_depths)];
        self.0.record(ctx, enc, "dipole combine", &res.uniform, &arrays)
    }
}
