//! The options of the dipole subsurface models (`--subsurface directional-dipole|standard-dipole`,
//! \[Frisvad2014\] through the passes of \[DirDipoleThesis\]): samples, directions, map sizes, the
//! three artifact fixes, and how many frames to accumulate before the image is written.

use anyhow::{Result, bail};
use clap::Args;
use rouge_render::SubsurfaceModel;
use rouge_render::{DipoleKind, DipoleSettings};

#[derive(Debug, Clone, Args)]
pub struct DipoleArgs {
    /// Disk samples per radiance-map texel and light (N), 1-256.
    #[arg(long, default_value_t = 16)]
    pub dipole_samples: u32,
    /// Radiance-map directions (K), 1-32, spread evenly on the sphere.
    #[arg(long, default_value_t = 8)]
    pub dipole_directions: u32,
    /// Radiance-map side, texels.
    #[arg(long, default_value_t = 256)]
    pub dipole_map_px: u32,
    /// Light G-buffer side, texels.
    #[arg(long, default_value_t = 512)]
    pub dipole_light_map_px: u32,
    /// Artifact fixes of the thesis's section 4.4 to leave out: shrink (G-buffer lookup inside,
    /// across the light), intrusion (map lookup inside along the normal), bias (visibility in mm).
    #[arg(long, value_delimiter = ',', value_enum)]
    pub dipole_without: Vec<DipoleFix>,
    /// Frames of disk samples accumulated into the radiance maps before the image is written
    /// (progressive convergence; the maps do not depend on the camera).
    #[arg(long, default_value_t = 1)]
    pub dipole_frames: u32,
}

/// `--dipole-without` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DipoleFix {
    /// G-buffer shrink along the light (section 4.4.1).
    Shrink,
    /// Radiance-map intrusion along the normal (section 4.4.2).
    Intrusion,
    /// World-space depth bias (section 4.4.3).
    Bias,
}

impl DipoleArgs {
    /// The skin's dipole model of `kind`.
    pub fn model(&self, kind: DipoleKind) -> Result<SubsurfaceModel> {
        let settings = DipoleSettings {
            samples: self.dipole_samples,
            directions: self.dipole_directions,
            map_px: self.dipole_map_px,
            light_map_px: self.dipole_light_map_px,
            shrink: !self.dipole_without.contains(&DipoleFix::Shrink),
            intrusion: !self.dipole_without.contains(&DipoleFix::Intrusion),
            world_bias: !self.dipole_without.contains(&DipoleFix::Bias),
            progressive: true,
        };
        settings.check().map_err(|e| anyhow::anyhow!("--dipole-*: {e}"))?;
        if !(1..=1000).contains(&self.dipole_frames) {
            bail!("--dipole-frames {}: 1 to 1000", self.dipole_frames);
        }
        Ok(SubsurfaceModel::Dipole { kind, settings })
    }
}
