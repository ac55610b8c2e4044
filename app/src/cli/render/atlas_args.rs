//! The options of the cube-atlas subsurface model (`--subsurface cube-atlas`, \[Benmounah2009\]):
//! atlas size, largest kernel, adaptive kernel, self-occlusion test and global term.

use anyhow::Result;
use clap::Args;
use rouge_render::SubsurfaceModel;
use rouge_render::cube_atlas::{AtlasSettings, GlobalTerm, OcclusionTest, Reach};

#[derive(Debug, Clone, Args)]
pub struct AtlasArgs {
    /// Side of each of the atlas's six faces, texels (16-4096).
    #[arg(long, default_value_t = 512)]
    pub atlas_px: u32,
    /// Taps per side of the gather kernel, odd (1-63); the paper settles on 5.
    #[arg(long, default_value_t = 5)]
    pub atlas_kernel: u32,
    /// The kernel's radius: 'support' (three decay lengths 1/σ_tr of the medium's dipole, at
    /// most 40 mean free paths) or a number of mean free paths 1/σ′_t (the paper's: 1).
    #[arg(long, default_value = "support")]
    pub atlas_reach: String,
    /// Use the full radius everywhere instead of shrinking it by the normal's scalar product
    /// with the face (section 4.3.2).
    #[arg(long)]
    pub atlas_fixed_kernel: bool,
    /// How a point is found on a face: tangent-plane (the stored point against the pixel's
    /// tangent plane), plane-offset (the paper's stored n·p) or off (the best face, always).
    #[arg(long, default_value = "tangent-plane")]
    pub atlas_occlusion: String,
    /// The global term (light through thin parts, section 4.4): slab (a slab's diffusion
    /// transmittance over the local thickness), real-source (the paper's eq. 9), or off.
    #[arg(long, default_value = "slab")]
    pub atlas_global: String,
}

impl AtlasArgs {
    /// The skin's cube-atlas model.
    pub fn model(&self) -> Result<SubsurfaceModel> {
        let settings = AtlasSettings {
            atlas_px: self.atlas_px,
            kernel_max: self.atlas_kernel,
            reach: Reach::parse(&self.atlas_reach).map_err(|e| anyhow::anyhow!("--atlas-reach: {e}"))?,
            adaptive: !self.atlas_fixed_kernel,
            occlusion: OcclusionTest::parse(&self.atlas_occlusion)
                .map_err(|e| anyhow::anyhow!("--atlas-occlusion: {e}"))?,
            global: GlobalTerm::parse(&self.atlas_global).map_err(|e| anyhow::anyhow!("--atlas-global: {e}"))?,
        };
        settings.check().map_err(|e| anyhow::anyhow!("--atlas-*: {e}"))?;
        Ok(SubsurfaceModel::CubeAtlas { settings })
    }
}
