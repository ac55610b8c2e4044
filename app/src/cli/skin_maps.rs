//! `rouge skin maps`: the skin maps of the default head as files, the same maps `rouge render
//! --skin-maps` draws and a project saves: the parameters as a multi-channel OpenEXR (the
//! project's format, docs/FORMATS.md), their colour as the albedo texture, and where the
//! conditions are as a mask a concealer layer can use as its thickness map.

use anyhow::{Context, Result};
use clap::Args;
use rouge_measure::skin::skin_tone_or_ita;
use rouge_model::skin::generate::conditions_mask;
use rouge_model::skin::{SkinConditions, SkinMaps};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct MapsArgs {
    /// The maps' tone: a named tone (`rouge skin tones`) or an ITA in degrees.
    #[arg(long, default_value = "light")]
    pub tone: String,
    /// Skin conditions, NAME=AMOUNT,... with amounts 0 to 1: freckles, moles, redness, acne,
    /// hyperpigmentation, under_eye, veins.
    #[arg(long, default_value = "none")]
    pub conditions: SkinConditions,
    /// Seed of the conditions' placement (`rouge render --skin-seed`).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Side of the maps, texels (16 to 4096).
    #[arg(long, default_value_t = 1024)]
    pub size_px: u32,
    /// Write the maps here: OpenEXR, one 32-bit float channel per parameter (melanin_fraction,
    /// pheomelanin_share, blood_fraction, oxygen_saturation, epidermis_thickness_mm).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write their colour here: the skin's albedo texture (8-bit sRGB PNG, the renderer's).
    #[arg(long)]
    pub albedo: Option<PathBuf>,
    /// Write where the conditions are here: a 16-bit greyscale PNG, 1 (white) at a spot's centre
    /// or where a condition's region is full. In a look, `{"map": "mask.png", "scale_mm": 0.03}`
    /// puts 30 µm of concealer on the spots and redness and nothing elsewhere.
    #[arg(long)]
    pub conditions_mask: Option<PathBuf>,
}

/// Encodes `image` as PNG and writes it atomically (a failed write leaves the old file).
fn write_png(path: &Path, image: image::DynamicImage) -> Result<()> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write_to(&mut bytes, image::ImageFormat::Png).with_context(|| format!("cannot encode {}", path.display()))?;
    crate::write_output(path, bytes.get_ref())
}

pub fn run(args: &MapsArgs) -> Result<()> {
    if args.out.is_none() && args.albedo.is_none() && args.conditions_mask.is_none() {
        anyhow::bail!("nothing to write: give --out, --albedo or --conditions-mask");
    }
    let base = skin_tone_or_ita(&args.tone).with_context(|| format!("--tone {}", args.tone))?;
    if args.out.is_some() || args.albedo.is_some() {
        let maps = SkinMaps::generate(&base, &args.conditions, args.seed, args.size_px)?;
        if let Some(path) = &args.out {
            let bytes = maps.to_exr_bytes().map_err(anyhow::Error::msg).context("skin maps")?;
            crate::write_output(path, &bytes)?;
            eprintln!("rouge: skin maps {0}×{0} → {1}", args.size_px, path.display());
        }
        if let Some(path) = &args.albedo {
            let table = rouge_render::job::skin_color_table(maps.base())?;
            write_png(path, rouge_render::job::bake_skin_albedo(&maps, &table).into())?;
            eprintln!("rouge: their albedo → {}", path.display());
        }
    }
    if let Some(path) = &args.conditions_mask {
        let mask = conditions_mask(&args.conditions, args.seed, args.size_px)?;
        let pixels = mask.mm.iter().map(|&w| (f64::from(w).clamp(0.0, 1.0) * 65535.0).round() as u16).collect();
        let image = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(mask.width, mask.height, pixels)
            .context("conditions mask size")?;
        write_png(path, image.into())?;
        eprintln!("rouge: where the conditions are → {}", path.display());
    }
    Ok(())
}
