//! `rouge finish PRESET`: a cosmetic's finish (matte, satin, dewy, gloss: its specular lobe and
//! film, `rouge_measure::finish`), shown as the gloss a meter would read, set by name, or fitted
//! to gloss readings (ISO 2813), and written back into the preset (schema version 2).

use anyhow::{Result, bail};
use clap::Args;
use rouge_measure::finish::{FinishKind, Glitter, GlossGeometry, GlossReading, Shimmer, fit_gloss, gloss_units};
use rouge_measure::preset::Specular;
use rouge_model::look::load_preset_ref;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct FinishArgs {
    /// The preset: a file, or `builtin:NAME` (then --out is required).
    pub preset: String,
    /// Give it a named finish: its lobe (roughness, index), clarity and levelling
    /// (matte, satin, dewy, gloss). With --gloss, the roughness comes from the readings.
    #[arg(long, value_parser = parse_kind)]
    pub kind: Option<FinishKind>,
    /// Gloss readings, ANGLE=GU (20, 60 or 85 degrees), e.g. `--gloss 60=12 --gloss 85=30`:
    /// the lobe's roughness is fitted to them (at the preset's index, or --ior).
    #[arg(long, value_parser = parse_reading)]
    pub gloss: Vec<GlossReading>,
    /// Index of refraction of the film's binder for --gloss (default: the preset's).
    #[arg(long)]
    pub ior: Option<f64>,
    /// The part of the shine below the layer that it passes specularly, 0-1 (overrides --kind's).
    #[arg(long)]
    pub clarity: Option<f64>,
    /// How much the film flattens the skin's relief, 0-1 (overrides --kind's).
    #[arg(long)]
    pub levelling: Option<f64>,
    /// Pearlescent shimmer: mica platelets with a rutile TiO₂ film this thick, nm (at normal
    /// incidence about 50 silver, 70 gold, 90 red, 105 violet, 125 blue, 145 green;
    /// docs/FINISHES.md).
    #[arg(long)]
    pub shimmer_nm: Option<f64>,
    /// The shimmer's strength, 0-1 (the platelets' coverage; default 0.5).
    #[arg(long)]
    pub shimmer_strength: Option<f64>,
    /// The shimmer platelets' RMS tilt, a Beckmann roughness in (0, 1] (default 0.25).
    #[arg(long)]
    pub shimmer_spread: Option<f64>,
    /// Take the shimmer out of the finish.
    #[arg(long, conflicts_with_all = ["shimmer_nm", "shimmer_strength", "shimmer_spread"])]
    pub no_shimmer: bool,
    /// Glitter: flat mirror flakes this wide, µm (20-2000; cosmetic glitter 50-1000).
    #[arg(long)]
    pub glitter_size_um: Option<f64>,
    /// The glitter's flakes per mm² of film (at most 1/(2·size)²; default: a quarter of that).
    #[arg(long)]
    pub glitter_density: Option<f64>,
    /// The flakes' reflectance, linear sRGB R,G,B in 0-1 (default 0.9,0.9,0.9: silver).
    #[arg(long, value_parser = parse_rgb)]
    pub glitter_color: Option<[f64; 3]>,
    /// The flakes' RMS tilt, a Beckmann roughness in (0, 1] (default 0.3).
    #[arg(long)]
    pub glitter_spread: Option<f64>,
    /// Take the glitter out of the finish.
    #[arg(long, conflicts_with_all = ["glitter_size_um", "glitter_density", "glitter_color", "glitter_spread"])]
    pub no_glitter: bool,
    /// Remove the finish (the preset goes back to schema version 1).
    #[arg(long, conflicts_with_all = ["kind", "gloss", "clarity", "levelling", "shimmer_nm", "shimmer_strength", "shimmer_spread", "glitter_size_um", "glitter_density", "glitter_color", "glitter_spread"])]
    pub clear: bool,
    /// Where to write the preset (default: over PRESET, atomically). Without a change nothing
    /// is written.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

fn parse_kind(s: &str) -> Result<FinishKind, String> {
    FinishKind::from_name(s).ok_or_else(|| format!("unknown finish {s:?}: use matte, satin, dewy or gloss"))
}

fn parse_rgb(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    let [r, g, b] = parts.as_slice() else {
        return Err(format!("{s:?}: write R,G,B, e.g. 0.9,0.8,0.5"));
    };
    let channel = |c: &str| c.trim().parse::<f64>().map_err(|_| format!("{s:?}: {c:?} is not a number"));
    Ok([channel(r)?, channel(g)?, channel(b)?])
}

fn parse_reading(s: &str) -> Result<GlossReading, String> {
    let (angle, gu) = s.split_once('=').ok_or_else(|| format!("{s:?}: write ANGLE=GU, e.g. 60=12.5"))?;
    let geometry = match angle.trim().trim_end_matches('°') {
        "20" => GlossGeometry::Deg20,
        "60" => GlossGeometry::Deg60,
        "85" => GlossGeometry::Deg85,
        other => return Err(format!("gloss angle {other:?}: a gloss meter reads at 20, 60 or 85 degrees")),
    };
    let gu: f64 = gu.trim().parse().map_err(|_| format!("{s:?}: {gu:?} is not a number of gloss units"))?;
    Ok(GlossReading { geometry, gu })
}

/// The gloss a meter would read of `specular` at 20°, 60°, 85°, in words.
fn gloss_line(specular: Specular) -> String {
    let gu = GlossGeometry::ALL.map(|g| gloss_units(specular, g));
    format!("gloss {:.1} GU at 20°, {:.1} at 60°, {:.1} at 85°", gu[0], gu[1], gu[2])
}

pub fn run(args: &FinishArgs) -> Result<()> {
    let mut preset = load_preset_ref(&args.preset, Path::new("."))?;
    let shimmer_given = args.shimmer_nm.is_some() || args.shimmer_strength.is_some() || args.shimmer_spread.is_some();
    let glitter_given = args.glitter_size_um.is_some()
        || args.glitter_density.is_some()
        || args.glitter_color.is_some()
        || args.glitter_spread.is_some();
    let changes = args.kind.is_some()
        || !args.gloss.is_empty()
        || args.clarity.is_some()
        || args.levelling.is_some()
        || shimmer_given
        || args.no_shimmer
        || glitter_given
        || args.no_glitter
        || args.clear;
    let out = match (&args.out, args.preset.starts_with("builtin:")) {
        (Some(out), _) => out.clone(),
        (None, false) => PathBuf::from(&args.preset),
        (None, true) if changes => bail!("{} is built in: say where to write the preset with --out", args.preset),
        (None, true) => PathBuf::new(),
    };
    if args.clear {
        preset.set_finish(None);
    } else if changes {
        // A named kind starts from its defaults, an edit from the preset's own finish.
        let (mut specular, mut finish) = match (args.kind, preset.finish) {
            (Some(k), _) => k.defaults(),
            (None, Some(f)) => (preset.specular, f),
            (None, None) if !args.gloss.is_empty() || shimmer_given => FinishKind::Satin.defaults(),
            (None, None) if glitter_given => FinishKind::Gloss.defaults(),
            (None, None) => bail!("--clarity/--levelling change a finish: give --kind (matte, satin, dewy, gloss) too"),
        };
        if !args.gloss.is_empty() {
            let ior = args.ior.unwrap_or(preset.specular.ior);
            let fit = fit_gloss(&args.gloss, ior).map_err(|e| anyhow::anyhow!("--gloss: {e}"))?;
            for (g, measured, fitted) in &fit.readings {
                eprintln!("rouge: {}°: read {measured:.1} GU, the fitted lobe {fitted:.1} GU", g.incidence_deg());
            }
            specular = fit.specular;
            if args.kind.is_none() && preset.finish.is_none() {
                finish = fit.nearest_kind.defaults().1;
            }
        }
        finish.clarity = args.clarity.unwrap_or(finish.clarity);
        finish.levelling = args.levelling.unwrap_or(finish.levelling);
        if args.no_shimmer {
            finish.shimmer = None;
        } else if shimmer_given {
            let before = finish.shimmer.or(preset.finish.and_then(|f| f.shimmer));
            let Some(film_nm) = args.shimmer_nm.or(before.map(|s| s.film_nm)) else {
                bail!("--shimmer-strength/--shimmer-spread change a shimmer: give --shimmer-nm too");
            };
            finish.shimmer = Some(Shimmer {
                film_nm,
                strength: args.shimmer_strength.or(before.map(|s| s.strength)).unwrap_or(0.5),
                spread: args.shimmer_spread.or(before.map(|s| s.spread)).unwrap_or(0.25),
            });
        }
        if args.no_glitter {
            finish.glitter = None;
        } else if glitter_given {
            let before = finish.glitter.or(preset.finish.and_then(|f| f.glitter));
            let Some(size_um) = args.glitter_size_um.or(before.map(|g| g.size_um)) else {
                bail!(
                    "--glitter-density/--glitter-color/--glitter-spread change a glitter: give --glitter-size-um too"
                );
            };
            let most = 1.0 / (2.0 * size_um * 1e-3).powi(2);
            finish.glitter = Some(Glitter {
                size_um,
                density_per_mm2: args.glitter_density.or(before.map(|g| g.density_per_mm2)).unwrap_or(0.25 * most),
                color: args.glitter_color.or(before.map(|g| g.color)).unwrap_or([0.9; 3]),
                spread: args.glitter_spread.or(before.map(|g| g.spread)).unwrap_or(0.3),
            });
        }
        finish.validate().map_err(anyhow::Error::msg)?;
        preset.set_finish(Some((specular, finish)));
    }
    let s = preset.specular;
    let film = match preset.finish {
        Some(f) => format!(
            "{} (clarity {:.2}, levelling {:.2}{}{})",
            f.kind.name(),
            f.clarity,
            f.levelling,
            f.shimmer.map_or(String::new(), |s| format!(
                ", shimmer {} nm TiO₂ strength {:.2} spread {:.2}",
                s.film_nm, s.strength, s.spread
            )),
            f.glitter.map_or(String::new(), |g| format!(
                ", glitter {} µm flakes {:.1}/mm² colour {:.2},{:.2},{:.2} spread {:.2}",
                g.size_um, g.density_per_mm2, g.color[0], g.color[1], g.color[2], g.spread
            ))
        ),
        None => "none (schema version 1: a clear film that follows the skin's relief)".into(),
    };
    crate::emit(&format!(
        "{}: finish {film}; lobe roughness {:.3}, index {:.3}; {}",
        preset.name,
        s.roughness,
        s.ior,
        gloss_line(s)
    ))?;
    if changes {
        preset.save(&out)?;
        eprintln!("rouge: wrote {} (preset schema version {})", out.display(), preset.version);
    }
    Ok(())
}
