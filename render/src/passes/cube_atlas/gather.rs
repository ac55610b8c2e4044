//! Cube-atlas gather pass (shaders/atlas_gather.wgsl): per skin pixel, face selection with the
//! self-occlusion test, the local dipole gather and the global term, added to the skin's diffuse
//! radiance (\[Benmounah2009\] sections 4.2-4.4).

use super::super::skin_gather::SkinGather;
use super::super::{FramePass, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, bare, pass_shader};
use crate::wgpu_util::array_view;

/// The gather pass.
#[derive(Debug)]
pub struct AtlasGatherPass(SkinGather);

impl FramePass for AtlasGatherPass {
    type Step = ();
    const SHADER: PassShader = pass_shader!(AtlasGatherPass, "atlas_gather.wgsl", bare);

    fn new(shared: &Shared) -> AtlasGatherPass {
        AtlasGatherPass(SkinGather::new(&shared.device, &Self::SHADER, "fs_atlas_gather", 3))
    }

    fn name(_: &()) -> String {
        "atlas gather".into()
    }

    /// Records the gather into the skin's diffuse radiance (added).
    fn record(&mut self, rec: &mut Recording<'_>, _: &()) -> Result<()> {
        let res = &*rec.atlas;
        let arrays = [array_view(&res.irradiance), array_view(&res.normals), array_view(&res.depths)];
        let uniform = res.uniform.clone();
        self.0.record(rec, "atlas gather", &uniform, &arrays)
    }
}
