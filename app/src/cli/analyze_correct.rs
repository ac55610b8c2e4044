//! `rouge analyze correct`: the corrected amounts of a standard's colorants for a measured
//! production batch (`rouge_measure::analysis::correction`; docs/FORMULATION.md).

use crate::cli::analyze::{CommonArgs, load_layer, skins, viewing, write_json};
use crate::cli::analyze_metamerism::{read_one_spectrum, split_pick};
use anyhow::{Result, anyhow, bail};
use clap::Args;
use rouge_measure::analysis::Layer;
use rouge_measure::analysis::correction::{Presentation, correct_batch};
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::colorimetry::Colorimeter;
use serde_json::json;
use std::path::Path;

#[derive(Debug, Args)]
pub struct CorrectArgs {
    /// The colorants of the recipe (built-in preset names or preset files), comma-separated,
    /// in the order of --recipe.
    #[arg(long, value_delimiter = ',', required = true)]
    pub colorant: Vec<String>,
    /// The amounts the batch was made with (Duncan concentrations), one per colorant.
    #[arg(long, value_delimiter = ',', required = true)]
    pub recipe: Vec<f64>,
    /// The batch's measured reflectance: a spectrum file (CSV table or CGATS; `FILE#NAME` picks one).
    #[arg(long)]
    pub batch: String,
    /// The standard's measured reflectance (default: what --recipe predicts).
    #[arg(long)]
    pub standard: Option<String>,
    /// The product is seen as this thickness, µm, over the skin (--skin's first sample or
    /// --sample), instead of opaque.
    #[arg(long = "thickness-um")]
    pub thickness_um: Option<f64>,
    /// Which sample of --skin.
    #[arg(long)]
    pub sample: Option<String>,
    #[command(flatten)]
    pub common: CommonArgs,
}

fn spectrum_file(spec: &str, what: &str, extrapolate: bool) -> Result<(String, rouge_measure::Spectrum)> {
    let (path, pick) = split_pick(spec);
    if !Path::new(path).is_file() {
        bail!("{what} `{spec}`: no such file (a spectrum file, CSV table or CGATS, `FILE#NAME` for one of several)");
    }
    read_one_spectrum(Path::new(path), pick, extrapolate)
}

pub fn run(args: &CorrectArgs) -> Result<()> {
    let colorants: Vec<Layer> = args.colorant.iter().map(|p| Ok(load_layer(p)?.1)).collect::<Result<_>>()?;
    if args.recipe.len() != colorants.len() {
        bail!("--recipe has {} amounts for {} colorants: give one per --colorant", args.recipe.len(), colorants.len());
    }
    let presentation = match args.thickness_um {
        None => Presentation::Opaque,
        Some(t) if t >= 0.0 && t.is_finite() => {
            let all = skins(&args.common)?;
            let chosen = match &args.sample {
                None => all.into_iter().next(),
                Some(n) => all.into_iter().find(|(name, _)| name == n),
            };
            let (_, r) =
                chosen.ok_or_else(|| anyhow!("--sample: no skin named `{}`", args.sample.as_deref().unwrap_or("")))?;
            Presentation::Over { background: Box::new(r), thickness_mm: t * 1e-3 }
        }
        Some(t) => bail!("--thickness-um = {t} must be finite and ≥ 0"),
    };
    let c = Colorimeter::get(viewing(&args.common));
    let (batch_name, batch) = spectrum_file(&args.batch, "--batch", args.common.extrapolate)?;
    let (standard_name, standard) = match &args.standard {
        Some(s) => spectrum_file(s, "--standard", args.common.extrapolate)?,
        None => (
            "the recipe's prediction".to_string(),
            presentation.reflectance(&duncan_mix("standard", &colorants, &args.recipe)?),
        ),
    };
    let fix = correct_batch(&colorants, &args.recipe, &batch, &standard, &presentation, c)?;
    println!("batch {batch_name} against the standard {standard_name}, {}", c.viewing());
    println!("ΔE2000 of the batch {:.3}; predicted after correction {:.4}", fix.delta_e_before, fix.delta_e_predicted);
    crate::emit(&format!("{:<28} {:>10} {:>10} {:>10}", "colorant", "batch", "corrected", "change"))?;
    for (i, l) in colorants.iter().enumerate() {
        crate::emit(&format!(
            "{:<28} {:>10.5} {:>10.5} {:>+10.5}",
            l.name, args.recipe[i], fix.concentrations[i], fix.change[i]
        ))?;
    }
    let value = json!({
        "viewing": c.viewing().to_string(), "batch": batch_name, "standard": standard_name,
        "presentation": match &presentation { Presentation::Opaque => json!("opaque"),
            Presentation::Over { thickness_mm, .. } => json!({"over_skin_thickness_mm": thickness_mm}) },
        "colorants": colorants.iter().map(|l| l.name.clone()).collect::<Vec<_>>(),
        "recipe": args.recipe, "corrected": fix.concentrations, "change": fix.change,
        "delta_e_before": fix.delta_e_before, "delta_e_predicted": fix.delta_e_predicted,
        "standard_lab": fix.standard_lab, "batch_lab": fix.batch_lab,
        "method": "Allen 1980: the batch's model error carried in K/S (opaque) or reflectance; Gauss-Newton on CIELAB",
    });
    write_json(&args.common.json, &value)
}
