//! `rouge analyze recipe TARGET --library ...`: the best recipes of k colorants of a library for a
//! target, under limits, fixed pairs and costs, judged under several illuminants
//! (`rouge_measure::analysis::recipe`; docs/FORMULATION.md).

use crate::cli::analyze::{CommonArgs, load_layer, skins, write_json};
use crate::cli::analyze_metamerism::{read_one_spectrum, split_pick};
use crate::cli::color::{parse_illuminant, parse_observer};
use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use rouge_measure::analysis::correction::Presentation;
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::analysis::recipe::{
    Colorant, FixedRatio, RecipeReport, RecipeSearch, WeightedViewing, search_recipes,
};
use rouge_measure::colorimetry::{Illuminant, Observer, Viewing};
use rouge_measure::spectrum::Spectrum;
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct RecipeArgs {
    /// The target: a preset (built-in name or preset file: its R∞, or over the skin at
    /// --thickness-um) or a measured spectrum file (CSV table or CGATS; `FILE#NAME` picks one).
    pub target: String,
    /// The colorant library: preset files, folders of preset files (*.json) or built-in preset
    /// names. A colorant is named by its file stem (or built-in name) in --min/--max/--fixed/--cost.
    #[arg(long, required = true, num_args = 1.., value_delimiter = ',')]
    pub library: Vec<String>,
    /// Colorants per recipe.
    #[arg(long, default_value_t = 3)]
    pub k: usize,
    /// Illuminants of the objective, comma-separated (the first is the reference of the
    /// metamerism indices): D65, D55, D50, A, E, FL2, FL7, FL11 (or F11), LED-B3.
    #[arg(long, value_delimiter = ',', value_parser = parse_illuminant, default_value = "D65,A,FL11")]
    pub illuminants: Vec<Illuminant>,
    /// Weight of each illuminant's ΔE2000 (default 1 each).
    #[arg(long, value_delimiter = ',')]
    pub weights: Vec<f64>,
    /// Observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931", value_parser = parse_observer)]
    pub observer: Observer,
    /// Least amount of a colorant, `NAME=V` (V > 0 makes it required in every recipe).
    #[arg(long, value_delimiter = ',')]
    pub min: Vec<String>,
    /// Largest amount of a colorant, `NAME=V` (0 excludes it).
    #[arg(long, value_delimiter = ',')]
    pub max: Vec<String>,
    /// A fixed ratio `A:B=R`: amount(A) = R × amount(B); the two enter recipes together.
    #[arg(long, value_delimiter = ',')]
    pub fixed: Vec<String>,
    /// Cost per unit amount of a colorant, `NAME=C`.
    #[arg(long, value_delimiter = ',')]
    pub cost: Vec<String>,
    /// Price of cost in the objective, ΔE2000 per unit cost (default 0: cost only reported).
    #[arg(long = "cost-weight", default_value_t = 0.0)]
    pub cost_weight: f64,
    /// How many recipes to list.
    #[arg(long, default_value_t = 10)]
    pub top: usize,
    /// Target and recipes are seen over the skin at this thickness, µm, instead of opaque (the
    /// skin is --skin's first sample, or --sample NAME; default the ColorChecker's dark skin).
    #[arg(long = "thickness-um")]
    pub thickness_um: Option<f64>,
    /// Skin reflectances (CSV table or CGATS), for --thickness-um.
    #[arg(long)]
    pub skin: Option<PathBuf>,
    /// A named skin tone of the skin model instead (`rouge skin tones`).
    #[arg(long = "skin-tone")]
    pub skin_tone: Option<String>,
    /// Which sample of --skin.
    #[arg(long)]
    pub sample: Option<String>,
    /// Hold the end values of spectra that do not cover 380-780 nm.
    #[arg(long)]
    pub extrapolate: bool,
    /// Also write the ranked recipes as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw the target's and the best recipes' reflectances (at most 5) and their ΔE2000 per
    /// light into this PNG.
    #[arg(long)]
    pub png: Option<PathBuf>,
}

/// The library's colorants, named by file stem or built-in name, in the order given (a folder's
/// presets sorted by file name).
pub(crate) fn load_library(items: &[String]) -> Result<Vec<Colorant>> {
    let mut out = Vec::new();
    for item in items {
        let path = Path::new(item);
        let specs: Vec<String> = if path.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(path)
                .with_context(|| format!("--library {item}: cannot read the folder"))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("json")))
                .collect();
            files.sort();
            if files.is_empty() {
                bail!("--library {item}: no preset files (*.json) in the folder");
            }
            files.iter().map(|p| p.to_string_lossy().into_owned()).collect()
        } else {
            vec![item.clone()]
        };
        for spec in specs {
            let (_, mut layer) = load_layer(&spec).with_context(|| format!("--library {spec}"))?;
            let p = Path::new(&spec);
            layer.name = if p.is_file() {
                p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or(spec.clone())
            } else {
                spec.strip_prefix("builtin:").unwrap_or(&spec).to_string()
            };
            out.push(Colorant::new(layer));
        }
    }
    Ok(out)
}

/// `NAME=V` → (index of NAME in the library, V).
fn name_value(flag: &str, text: &str, library: &[Colorant]) -> Result<(usize, f64)> {
    let (name, value) = text.split_once('=').ok_or_else(|| anyhow!("{flag} `{text}`: expected NAME=VALUE"))?;
    let v: f64 = value.trim().parse().map_err(|_| anyhow!("{flag} `{text}`: `{value}` is not a number"))?;
    let i = library.iter().position(|c| c.layer.name == name.trim()).ok_or_else(|| {
        let names: Vec<&str> = library.iter().map(|c| c.layer.name.as_str()).collect();
        anyhow!("{flag} `{text}`: no colorant `{name}` in the library ({})", names.join(", "))
    })?;
    Ok((i, v))
}

fn parse_fixed(text: &str) -> Result<FixedRatio> {
    let err = || anyhow!("--fixed `{text}`: expected A:B=RATIO (amount of A = RATIO × amount of B)");
    let (pair, ratio) = text.split_once('=').ok_or_else(err)?;
    let (a, b) = pair.split_once(':').ok_or_else(err)?;
    let ratio: f64 = ratio.trim().parse().map_err(|_| err())?;
    Ok(FixedRatio { a: a.trim().to_string(), b: b.trim().to_string(), ratio })
}

/// The search the arguments describe (without the target).
fn build_search(args: &RecipeArgs, presentation: Presentation) -> Result<RecipeSearch> {
    let mut colorants = load_library(&args.library)?;
    for text in &args.min {
        let (i, v) = name_value("--min", text, &colorants)?;
        colorants[i].min = v;
    }
    for text in &args.max {
        let (i, v) = name_value("--max", text, &colorants)?;
        colorants[i].max = v;
    }
    for text in &args.cost {
        let (i, v) = name_value("--cost", text, &colorants)?;
        colorants[i].cost_per_unit = v;
    }
    let weights = match args.weights.len() {
        0 => vec![1.0; args.illuminants.len()],
        n if n == args.illuminants.len() => args.weights.clone(),
        n => bail!("--weights has {n} values for {} illuminants: give one per illuminant", args.illuminants.len()),
    };
    let viewings = args
        .illuminants
        .iter()
        .zip(weights)
        .map(|(&illuminant, weight)| WeightedViewing {
            viewing: Viewing { illuminant, observer: args.observer },
            weight,
        })
        .collect();
    Ok(RecipeSearch {
        colorants,
        fixed: args.fixed.iter().map(|t| parse_fixed(t)).collect::<Result<_>>()?,
        k: args.k,
        viewings,
        presentation,
        cost_weight: args.cost_weight,
    })
}

fn presentation(args: &RecipeArgs) -> Result<(Presentation, Option<String>)> {
    let Some(t) = args.thickness_um else { return Ok((Presentation::Opaque, None)) };
    if !(t >= 0.0 && t.is_finite()) {
        bail!("--thickness-um = {t} µm must be finite and ≥ 0");
    }
    let common = CommonArgs {
        skin: args.skin.clone(),
        skin_tone: args.skin_tone.iter().cloned().collect(),
        extrapolate: args.extrapolate,
        illuminant: args.illuminants.first().copied().unwrap_or(Illuminant::D65),
        observer: args.observer,
        json: None,
    };
    let all = skins(&common)?;
    let chosen = match &args.sample {
        None => all.into_iter().next(),
        Some(n) => all.into_iter().find(|(name, _)| name == n),
    };
    let (name, r) =
        chosen.ok_or_else(|| anyhow!("--sample: no skin named `{}`", args.sample.as_deref().unwrap_or("")))?;
    Ok((Presentation::Over { background: Box::new(r), thickness_mm: t * 1e-3 }, Some(name)))
}

/// The target's reflectance as the presentation sees it, and its name.
fn target(spec: &str, presentation: &Presentation, extrapolate: bool) -> Result<(String, Spectrum)> {
    let (path_text, pick) = split_pick(spec);
    let path = Path::new(path_text);
    if !path.is_file() || path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
        let (preset, layer) = load_layer(spec).with_context(|| format!("TARGET {spec}"))?;
        return Ok((preset.name.clone(), presentation.reflectance(&layer)));
    }
    read_one_spectrum(path, pick, extrapolate)
}

/// The ranked recipes as JSON rows.
pub(crate) fn recipes_json(report: &RecipeReport, search: &RecipeSearch) -> serde_json::Value {
    json!(report.recipes.iter().enumerate().map(|(rank, r)| json!({
        "rank": rank + 1,
        "colorants": r.names.iter().zip(&r.amounts).map(|(n, a)| json!({"name": n, "amount": a})).collect::<Vec<_>>(),
        "objective": r.objective, "cost": r.cost,
        "delta_e_2000": search.viewings.iter().zip(&r.delta_e)
            .map(|(v, de)| json!({"viewing": v.viewing.to_string(), "weight": v.weight, "delta_e": de})).collect::<Vec<_>>(),
        "lab": r.lab,
        "metamerism": r.metamerism.iter().map(|m| json!({"reference": m.reference.to_string(), "test": m.test.to_string(),
            "correction": m.correction.name(), "delta_e_2000": m.delta_e_2000, "delta_e_ab": m.delta_e_ab})).collect::<Vec<_>>(),
    })).collect::<Vec<_>>())
}

pub fn run(args: &RecipeArgs) -> Result<()> {
    let (presentation, skin) = presentation(args)?;
    let search = build_search(args, presentation)?;
    let (target_name, target) = target(&args.target, &search.presentation, args.extrapolate)?;
    let start = std::time::Instant::now();
    let report = search_recipes(&search, &target, args.top)?;
    let seconds = start.elapsed().as_secs_f64();
    let seen = match (&skin, args.thickness_um) {
        (Some(name), Some(t)) => format!("{t} µm over {name}"),
        _ => "opaque (R∞)".to_string(),
    };
    println!(
        "target {target_name}, {seen}; {} colorants, k = {}: {} combinations fitted, {} infeasible, {:.2} s",
        search.colorants.len(),
        search.k,
        report.combinations,
        report.infeasible,
        seconds
    );
    let lights: Vec<String> = search.viewings.iter().map(|v| v.viewing.illuminant.name().to_string()).collect();
    let mut header = format!("{:>4} {:>9} {:>8}", "rank", "objective", "cost");
    for l in &lights {
        header += &format!(" {:>9}", format!("ΔE00 {l}"));
    }
    header += &format!(" {:>9}  recipe", "max MI");
    crate::emit(&header)?;
    for (rank, r) in report.recipes.iter().enumerate() {
        let mut line = format!("{:>4} {:>9.4} {:>8.3}", rank + 1, r.objective, r.cost);
        for de in &r.delta_e {
            line += &format!(" {de:>9.3}");
        }
        let mi = r.metamerism.iter().map(|m| m.delta_e_2000).fold(0.0, f64::max);
        let recipe: Vec<String> = r.names.iter().zip(&r.amounts).map(|(n, a)| format!("{n} {a:.4}")).collect();
        line += &format!(" {mi:>9.3}  {}", recipe.join(" + "));
        crate::emit(&line)?;
    }
    if report.recipes.is_empty() {
        println!("no feasible recipe: every combination breaks the limits (maxima summing below 1)");
    }
    let value = json!({
        "target": {"spec": args.target, "name": target_name}, "presentation": seen, "k": search.k,
        "library": search.colorants.iter().map(|c| json!({"name": c.layer.name, "min": c.min, "max": c.max,
            "cost_per_unit": c.cost_per_unit})).collect::<Vec<_>>(),
        "fixed": search.fixed.iter().map(|f| json!({"a": f.a, "b": f.b, "ratio": f.ratio})).collect::<Vec<_>>(),
        "cost_weight": search.cost_weight,
        "combinations": report.combinations, "infeasible": report.infeasible, "seconds": seconds,
        "objective": "weighted RMS of ΔE2000 under the viewings + cost_weight × cost",
        "metamerism": "CIE 15:2018 §9 special index, additive correction, target against recipe, first viewing to each other",
        "recipes": recipes_json(&report, &search),
    });
    write_json(&args.json, &value)?;
    if let Some(path) = &args.png {
        let found = report
            .recipes
            .iter()
            .take(5)
            .map(|r| {
                let layers: Vec<_> = r.indices.iter().map(|&i| search.colorants[i].layer.clone()).collect();
                let mix = duncan_mix("recipe", &layers, &r.amounts)?;
                let label: Vec<String> = r
                    .names
                    .iter()
                    .zip(&r.amounts)
                    .filter(|(_, a)| **a > 1e-7)
                    .map(|(n, a)| format!("{n} {a:.2}"))
                    .collect();
                Ok((label.join(" + "), search.presentation.reflectance(&mix), r.delta_e.clone()))
            })
            .collect::<Result<Vec<_>>>()?;
        let lights: Vec<String> = search.viewings.iter().map(|v| v.viewing.illuminant.name().to_string()).collect();
        let png = crate::cli::analyze_plot::recipes(&target_name, &target, &found, &lights)?;
        crate::write_output(path, png)?;
    }
    Ok(())
}
