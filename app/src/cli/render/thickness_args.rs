//! The options of the thickness translucency (`--subsurface thickness`, \[BarreBrisebois2011\]):
//! where the local thickness comes from, the bake's rays and cutoff, and the term's parameters.
//! `rouge render` and `rouge bench translucency` share them.

use anyhow::{Result, bail};
use clap::Args;
use rouge_model::medium::Medium;
use rouge_render::SubsurfaceModel;
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};
use rouge_render::sss::DiffusionProfile;

#[derive(Debug, Clone, Args)]
pub struct ThicknessArgs {
    /// Local thickness of --subsurface thickness: baked (inverted-normal ambient occlusion per
    /// vertex, cached by mesh) or shadow-map (per light and per frame, the distance the light
    /// travelled inside the mesh; follows deformation, needs lights that cast shadows).
    #[arg(long, value_enum, default_value_t = ThicknessSourceArg::Baked)]
    pub thickness_source: ThicknessSourceArg,
    /// Rays per vertex of the local-thickness bake.
    #[arg(long, default_value_t = 64)]
    pub thickness_rays: u32,
    /// Longest chord (mm) that counts as "inside" for the local thickness: beyond it the mesh is
    /// opaque. Falloff: the medium's exp(−σ_tr·d) per channel with --medium, else linear.
    #[arg(long, default_value_t = 30.0)]
    pub thickness_cutoff_mm: f32,
    /// The term's parameters DISTORTION,POWER,SCALE,AMBIENT; default: those fitted to the path
    /// tracer for the --medium (docs/BENCHMARKS.md), else three.js's 0.1,2,10,0.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub translucency: Option<Vec<f32>>,
    /// Bake the local thickness on the mesh as drawn (current) or before --morph (rest: a map
    /// baked once, which the talk says breaks when the mesh deforms).
    #[arg(long, value_enum, default_value_t = BakePose::Current)]
    pub thickness_bake: BakePose,
}

/// `--thickness-source` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ThicknessSourceArg {
    /// Inverted-normal ambient occlusion, baked per vertex.
    Baked,
    /// Each light's shadow map, every frame.
    ShadowMap,
}

/// `--thickness-bake` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BakePose {
    /// The mesh as drawn.
    Current,
    /// The mesh before --morph.
    Rest,
}

impl ThicknessArgs {
    /// The skin's thickness model for a material of `medium` (if any), under the screen-space
    /// `kernel` of a profile if given (`--subsurface screen-space-thickness`).
    pub fn model(&self, medium: Option<&Medium>, kernel: Option<DiffusionProfile>) -> Result<SubsurfaceModel> {
        let params = match &self.translucency {
            Some(v) => {
                let &[distortion, power, scale, ambient] = v.as_slice() else {
                    bail!("--translucency: give DISTORTION,POWER,SCALE,AMBIENT");
                };
                let p = TranslucencyParams { distortion, power, scale, ambient };
                p.check().map_err(|e| anyhow::anyhow!("--translucency: {e}"))?;
                p
            }
            None => {
                let source = if self.thickness_source == ThicknessSourceArg::Baked { "baked" } else { "shadow-map" };
                TranslucencyParams::fitted(medium, source, kernel.is_some()).0
            }
        };
        let baked = self.thickness_source == ThicknessSourceArg::Baked;
        if !(self.thickness_cutoff_mm.is_finite() && self.thickness_cutoff_mm > 0.0) {
            bail!("--thickness-cutoff-mm {}: must be positive", self.thickness_cutoff_mm);
        }
        if self.thickness_rays == 0 {
            bail!("--thickness-rays 0: at least one ray per vertex");
        }
        let source = ThicknessSource::for_medium(baked, medium, self.thickness_rays, self.thickness_cutoff_mm);
        Ok(SubsurfaceModel::Thickness { params, source, kernel })
    }
}
