//! Dipole combination pass (shaders/dipole_combine.wgsl): per skin pixel, the radiance maps of
//! the directions that see the point, averaged, times the exit Fresnel transmittance, added to
//! the skin's diffuse radiance (\[DirDipoleThesis\] step 3).

use super::super::skin_gather::SkinGather;
use super::super::{FramePass, Recording, Shared};
use crate::error::Result;
use crate::shader::{PassShader, bare, pass_shader};
use crate::wgpu_util::array_view;

/// The combination pass.
#[derive(Debug)]
pub struct DipoleCombinePass(SkinGather);

impl FramePass for DipoleCombinePass {
    type Step = ();
    const SHADER: PassShader = pass_shader!(DipoleCombinePass, "dipole_combine.wgsl", bare);

    fn new(shared: &Shared) -> DipoleCombinePass {
        DipoleCombinePass(SkinGather::new(&shared.device, &Self::SHADER, "fs_dipole_combine", 2))
    }

    fn name(_: &()) -> String {
        "dipole combine".into()
    }

    /// Records the combination into the skin's diffuse radiance (added).
    fn record(&mut self, rec: &mut Recording<'_>, _: &()) -> Result<()> {
        let res = &*rec.dipole;
        let arrays = [array_view(res.current_and_previous().0), array_view(&res.map_depths)];
        let uniform = res.uniform.clone();
        self.0.record(rec, "dipole combine", &uniform, &arrays)
    }
}
