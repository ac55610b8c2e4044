//! `rouge bench ...`: speed-against-error studies whose figures go in docs/BENCHMARKS.md.

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use rouge_measure::compositing::{ErrorStats, Method, compositing_error};
use rouge_measure::import::rouge_csv::parse_spectra_table;
use rouge_measure::km::{self, LayerRt};
use rouge_measure::preset::Preset;
use rouge_measure::spectrum::{Extrapolation, Spectrum};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Compositing cosmetic layers in linear RGB or a few bands against spectral compositing:
    /// ΔE2000 over all ordered pairs of presets, thicknesses 0-0.2 mm, both ColorChecker skins.
    Compositing(CompositingArgs),
}

#[derive(Debug, Args)]
pub struct CompositingArgs {
    /// Directory of material presets (*.json).
    #[arg(long, default_value = "data/presets")]
    pub presets: PathBuf,
    /// Layer thicknesses to combine, mm.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2])]
    pub thicknesses_mm: Vec<f64>,
    /// Band counts to compare besides linear RGB.
    #[arg(long, value_delimiter = ',', default_values_t = [3usize, 4, 6, 8, 16])]
    pub bands: Vec<usize>,
    /// Also write the table as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

const SKIN_CSV: &str = include_str!("../../data/skin/colorchecker_skin.csv");

pub fn run(cmd: &BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Compositing(args) => compositing(args),
    }
}

fn load_presets(dir: &Path) -> Result<Vec<Preset>> {
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read the preset directory {} (use --presets DIR)", dir.display()))?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    let presets = paths.iter().map(|p| Preset::load(p)).collect::<Result<Vec<_>, _>>()?;
    if presets.len() < 2 {
        bail!("{}: {} presets; the study needs at least 2", dir.display(), presets.len());
    }
    Ok(presets)
}

/// CPU time of composing two layers over skin per pixel with `channels` channels (the layer
/// R and T looked up per channel, as a renderer would after its table fetch).
fn ns_per_pixel(channels: usize) -> f64 {
    let pixels = 200_000usize;
    let layer = |i: usize, c: usize| {
        let r = 0.05 + 0.4 * (((i * 7 + c * 13) % 97) as f64 / 97.0);
        LayerRt { r, t: 0.9 * (1.0 - r) }
    };
    let mut acc = 0.0;
    let start = Instant::now();
    for i in 0..pixels {
        for c in 0..channels {
            let s = km::stack(&[layer(i, c), layer(i + 1, c), LayerRt::opaque(0.4)]);
            acc += s.r;
        }
    }
    black_box(acc);
    start.elapsed().as_secs_f64() * 1e9 / pixels as f64
}

fn compositing(args: &CompositingArgs) -> Result<()> {
    let presets = load_presets(&args.presets)?;
    let (skins, _) = parse_spectra_table(Path::new("<embedded>/data/skin/colorchecker_skin.csv"), SKIN_CSV)?;
    let skins: Vec<(String, Spectrum)> = skins
        .into_iter()
        .map(|(n, s)| Ok((n, s.to_working_grid(Extrapolation::Refuse)?.spectrum)))
        .collect::<Result<_>>()?;
    if let Some(bad) = args.thicknesses_mm.iter().find(|x| !(**x >= 0.0 && x.is_finite())) {
        bail!("thickness {bad} mm must be finite and ≥ 0");
    }
    if let Some(bad) = args.bands.iter().find(|&&n| n == 0 || n > 81) {
        bail!("{bad} bands: use 1 to 81");
    }
    let mut methods = vec![Method::LinearRgb];
    methods.extend(args.bands.iter().map(|&n| Method::Bands(n)));
    let stats = compositing_error(&presets, &skins, &args.thicknesses_mm, &methods);
    let timing: Vec<f64> = stats.iter().map(|s| ns_per_pixel(s.channels)).collect();
    let spectral_ns = ns_per_pixel(81);
    let mut out = String::new();
    out.push_str(&format!(
        "Compositing 2 layers over skin: {} presets ({} ordered pairs) x {} x {} thicknesses x {} skins = {} stacks\n",
        presets.len(),
        presets.len() * (presets.len() - 1),
        args.thicknesses_mm.len(),
        args.thicknesses_mm.len(),
        skins.len(),
        stats.first().map_or(0, |s| s.cases)
    ));
    out.push_str("| method | channels | CPU ns/pixel | mean ΔE2000 | p95 ΔE2000 | max ΔE2000 | worst case |\n");
    out.push_str("|---|---:|---:|---:|---:|---:|---|\n");
    out.push_str(&format!("| spectral (reference) | 81 | {spectral_ns:.0} | 0 | 0 | 0 | |\n"));
    for (s, ns) in stats.iter().zip(&timing) {
        out.push_str(&format!(
            "| {} | {} | {ns:.0} | {:.3} | {:.3} | {:.3} | {} |\n",
            s.method, s.channels, s.mean, s.p95, s.max, s.worst_case
        ));
    }
    crate::emit(out.trim_end())?;
    if let Some(path) = &args.json {
        let rows: Vec<serde_json::Value> = stats
            .iter()
            .zip(&timing)
            .map(|(s, ns): (&ErrorStats, &f64)| serde_json::json!({"stats": s, "cpu_ns_per_pixel": ns}))
            .collect();
        let text = serde_json::to_string_pretty(&serde_json::json!({
            "thicknesses_mm": args.thicknesses_mm,
            "spectral_cpu_ns_per_pixel": spectral_ns,
            "methods": rows,
        }))?;
        rouge_measure::preset::write_atomic(path, text.as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}
