//! `rouge analyze coverage|match|mix|metamerism|correct|recipe`: what formulators ask of S and K (docs/FORMULATION.md).
//! The analyses live in `rouge_measure::analysis`; this module reads the inputs, prints the
//! tables for people, writes `--json` for machines and `--plot` PNGs (`analyze_plot.rs`).

use crate::cli::color::{parse_illuminant, parse_observer};
use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, Subcommand};
use rouge_measure::analysis::coverage::{self, ContrastChart, HIDING_CONTRAST_RATIO};
use rouge_measure::analysis::matching::{self, Target};
use rouge_measure::analysis::mixing::{self, MixTarget};
use rouge_measure::analysis::skin::read_skins;
use rouge_measure::analysis::{Layer, lab_of};
use rouge_measure::colorimetry::{Colorimeter, Illuminant, Observer, Viewing};
use rouge_measure::import::colorchecker_skin;
use rouge_measure::spectrum::{Extrapolation, Spectrum};
use rouge_measure::{Preset, delta_e_2000};
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(Debug, Subcommand)]
pub enum AnalyzeCommand {
    /// How much a preset covers: contrast ratio (Y over black / Y over white) and ΔE2000 on skin
    /// against thickness, and the hiding thickness (contrast ratio 0.98).
    Coverage(CoverageArgs),
    /// Which shade suits which skin: the preset and thickness closest to a target (the bare skin,
    /// or --target), per skin; with many skins, where the product line leaves gaps.
    Match(MatchArgs),
    /// Which mixture of 2-4 base presets reaches a target colour (Duncan's rule, least squares
    /// in ΔE2000 over concentrations ≥ 0 summing to 1).
    Mix(MixArgs),
    /// How far a match under one light comes apart under others: the special metamerism index
    /// (CIE 15:2018 §9, ISO 18314-4) per test illuminant and for a change of observer, with the
    /// additive and multiplicative corrections, as ΔE*ab and ΔE2000.
    Metamerism(crate::cli::analyze_metamerism::MetamerismArgs),
    /// Batch correction: the amounts of the recipe's colorants that bring a measured production
    /// batch back to the standard (the batch's model error carried, Gauss-Newton on CIELAB).
    Correct(crate::cli::analyze_correct::CorrectArgs),
    /// Recipe search: the best recipes of k colorants of a library (presets or folders of them)
    /// for a target, with per-colorant limits, fixed ratios and costs, ranked by the weighted
    /// ΔE2000 under several illuminants; ΔE per illuminant, metamerism index and cost.
    Recipe(crate::cli::analyze_recipe::RecipeArgs),
}

/// Options every analysis shares.
#[derive(Debug, Args)]
pub struct CommonArgs {
    /// Skin reflectances: a CSV with `wavelength_nm` and one column per skin, or a CGATS file (one
    /// sample per skin). Default: the ColorChecker's "dark skin" and "light skin" patches.
    #[arg(long)]
    pub skin: Option<PathBuf>,
    /// Skins from the spectral skin model's named tones instead (`rouge skin tones` lists them;
    /// comma-separated, or `all`), beside or instead of --skin.
    #[arg(long = "skin-tone", value_delimiter = ',')]
    pub skin_tone: Vec<String>,
    /// Hold the end values of --skin spectra that do not cover 380-780 nm (e.g. 360-740 nm data).
    #[arg(long)]
    pub extrapolate: bool,
    /// Illuminant: D65, D55, D50, A, E, FL2, FL7, FL11 (or F11) or LED-B3.
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    pub illuminant: Illuminant,
    /// Observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931", value_parser = parse_observer)]
    pub observer: Observer,
    /// Also write the results as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct CoverageArgs {
    /// Preset: a built-in name (`foundation_02_ivory`, or `builtin:...`) or a preset JSON file.
    pub preset: String,
    #[command(flatten)]
    pub common: CommonArgs,
    /// Reflectance of the contrast chart's black (spectrally flat).
    #[arg(long, default_value_t = 0.01)]
    pub black: f64,
    /// Reflectance of the contrast chart's white (ISO 6504-3: Y = 80).
    #[arg(long, default_value_t = 0.80)]
    pub white: f64,
    /// Thicknesses of the table, µm.
    #[arg(long = "thickness-um", value_delimiter = ',', default_values_t = [0.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 60.0, 80.0, 100.0, 150.0, 200.0])]
    pub thickness_um: Vec<f64>,
    /// Draw contrast ratio and ΔE2000 against thickness into this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct MatchArgs {
    /// The shades (built-in names or preset files), e.g. the five sample foundations.
    #[arg(required = true, num_args = 1..)]
    pub presets: Vec<String>,
    #[command(flatten)]
    pub common: CommonArgs,
    /// Target colour as CIELAB `L,a,b` (default: each bare skin itself, "your shade").
    #[arg(long, value_name = "L,a,b", value_parser = parse_lab)]
    pub target: Option<[f64; 3]>,
    /// Thickness range searched, µm, `MIN:MAX` (default: 0:100 with --target; the wear
    /// thickness --wear-um for "your shade", where less product is always closer to bare skin).
    #[arg(long = "thickness-um", value_name = "MIN:MAX")]
    pub thickness_um: Option<String>,
    /// Thickness the product is worn at, µm, for "your shade" matching.
    #[arg(long = "wear-um", default_value_t = 20.0)]
    pub wear_um: f64,
    /// A skin whose best shade is farther than this ΔE2000 falls in a gap of the line.
    #[arg(long = "gap-de", default_value_t = 2.0)]
    pub gap_de: f64,
    /// Plot the skins (L* against b*), each marked with its best shade, gaps crossed, into this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct MixArgs {
    /// 2-4 base presets (built-in names or preset files).
    #[arg(required = true, num_args = 2..=4)]
    pub bases: Vec<String>,
    #[command(flatten)]
    pub common: CommonArgs,
    /// Target colour as CIELAB `L,a,b`.
    #[arg(long, value_name = "L,a,b", value_parser = parse_lab, required_unless_present = "target_preset",
          conflicts_with = "target_preset")]
    pub target: Option<[f64; 3]>,
    /// Target: the colour of this preset (R∞, or over the skin at --thickness-um).
    #[arg(long = "target-preset")]
    pub target_preset: Option<String>,
    /// Match the colour of the skin covered by this thickness, µm, instead of R∞ (the skin is
    /// --skin's first sample, or --sample NAME).
    #[arg(long = "thickness-um")]
    pub thickness_um: Option<f64>,
    /// Which sample of --skin to use.
    #[arg(long)]
    pub sample: Option<String>,
}

/// `L,a,b` → three finite numbers.
fn parse_lab(text: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>().map_err(|_| format!("`{p}` is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [l, a, b] if v.iter().all(|x| x.is_finite()) => Ok([*l, *a, *b]),
        _ => Err(format!("`{text}`: expected three finite numbers L,a,b")),
    }
}

/// The ColorChecker's two skin patches (N. Ohta's measurements, `data/skin/colorchecker_skin.csv`,
/// parsed by [`colorchecker_skin`]), the default skins of the analyses and of `rouge bench
/// compositing`.
pub fn embedded_skins() -> Result<Vec<(String, Spectrum)>> {
    Ok(colorchecker_skin()?)
}

pub fn run(cmd: &AnalyzeCommand) -> Result<()> {
    match cmd {
        AnalyzeCommand::Coverage(args) => run_coverage(args),
        AnalyzeCommand::Match(args) => run_match(args),
        AnalyzeCommand::Mix(args) => run_mix(args),
        AnalyzeCommand::Metamerism(args) => crate::cli::analyze_metamerism::run(args),
        AnalyzeCommand::Correct(args) => crate::cli::analyze_correct::run(args),
        AnalyzeCommand::Recipe(args) => crate::cli::analyze_recipe::run(args),
    }
}

/// A preset by built-in name (with or without `builtin:`) or by file.
pub(crate) fn load_layer(spec: &str) -> Result<(Preset, Layer)> {
    let name = spec.strip_prefix("builtin:").unwrap_or(spec);
    let preset = match rouge_model::look::builtin_preset(name) {
        Some(p) if !Path::new(spec).exists() => p,
        _ => Preset::load(Path::new(spec)).map_err(|e| {
            anyhow!(
                "{e} (PRESET is a preset file or a built-in: {})",
                rouge_model::look::builtin_preset_names().join(", ")
            )
        })?,
    };
    let layer = Layer::from_preset(&preset).with_context(|| format!("preset {spec}"))?;
    Ok((preset, layer))
}

pub(crate) fn skins(common: &CommonArgs) -> Result<Vec<(String, Spectrum)>> {
    let mut skins = match &common.skin {
        None if !common.skin_tone.is_empty() => vec![],
        None => embedded_skins()?,
        Some(path) => {
            let extrapolation = if common.extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
            let skins = read_skins(path, extrapolation)?;
            if skins.is_empty() {
                bail!("{}: no skin spectra", path.display());
            }
            skins
        }
    };
    let all = common.skin_tone.iter().any(|n| n == "all");
    let tones: Vec<&rouge_measure::skin::SkinTone> = if all {
        rouge_measure::skin::skin_tones().iter().collect()
    } else {
        common.skin_tone.iter().map(|n| rouge_measure::skin::skin_tone(n)).collect::<Result<_, _>>()?
    };
    for t in tones {
        skins.push((format!("tone {}", t.name), t.params.reflectance()?));
    }
    Ok(skins)
}

pub(crate) fn viewing(common: &CommonArgs) -> Viewing {
    Viewing { illuminant: common.illuminant, observer: common.observer }
}

pub(crate) fn write_json(path: &Option<PathBuf>, value: &serde_json::Value) -> Result<()> {
    if let Some(p) = path {
        crate::write_output(p, format!("{value:#}\n"))?;
    }
    Ok(())
}

fn write_png(path: &Path, bytes: &[u8]) -> Result<()> {
    crate::write_output(path, bytes)
}

fn um(mm: f64) -> String {
    format!("{:.2}", mm * 1e3)
}

fn lab_text(lab: [f64; 3]) -> String {
    format!("{:.1}, {:.1}, {:.1}", lab[0], lab[1], lab[2])
}

fn check_um(what: &str, v: f64) -> Result<f64> {
    if v >= 0.0 && v.is_finite() { Ok(v * 1e-3) } else { bail!("{what} = {v} µm must be finite and ≥ 0") }
}

fn run_coverage(args: &CoverageArgs) -> Result<()> {
    let (preset, layer) = load_layer(&args.preset)?;
    let skins = skins(&args.common)?;
    let c = Colorimeter::get(viewing(&args.common));
    let chart = ContrastChart::new(args.black, args.white)?;
    let xs = args.thickness_um.iter().map(|&v| check_um("--thickness-um", v)).collect::<Result<Vec<f64>>>()?;
    let rows = coverage::coverage_table(&layer, &xs, chart, &skins, c)?;
    let hiding = coverage::hiding_thickness_mm(&layer, chart, c, HIDING_CONTRAST_RATIO)?;
    println!("{}: coverage under {} (chart black {}, white {})", preset.name, c.viewing(), chart.black, chart.white);
    match hiding {
        Some(x) => println!("hiding thickness (contrast ratio {HIDING_CONTRAST_RATIO}): {} µm", um(x)),
        None => println!("hiding thickness: never (the film does not scatter enough to hide a black/white chart)"),
    }
    let mut header = format!("{:>9} {:>8} {:>8} {:>8}", "µm", "Y black", "Y white", "CR");
    for (name, _) in &skins {
        header += &format!(" {:>16}", format!("ΔE00 {name}"));
    }
    crate::emit(&header)?;
    for r in &rows {
        let mut line = format!(
            "{:>9} {:>8.3} {:>8.3} {:>8.4}",
            um(r.thickness_mm),
            r.contrast.y_black,
            r.contrast.y_white,
            r.contrast.contrast_ratio
        );
        for de in &r.delta_e_on_skin {
            line += &format!(" {de:>16.2}");
        }
        crate::emit(&line)?;
    }
    let value = json!({
        "preset": preset.name, "viewing": c.viewing().to_string(),
        "chart": {"black": chart.black, "white": chart.white},
        "hiding_thickness_mm": hiding, "hiding_contrast_ratio": HIDING_CONTRAST_RATIO,
        "skins": skins.iter().map(|(n, r)| json!({"name": n, "lab": lab_of(c, r)})).collect::<Vec<_>>(),
        "rows": rows.iter().map(|r| json!({
            "thickness_mm": r.thickness_mm, "y_black": r.contrast.y_black, "y_white": r.contrast.y_white,
            "contrast_ratio": r.contrast.contrast_ratio, "lab_on_skin": r.lab_on_skin, "delta_e_on_skin": r.delta_e_on_skin,
        })).collect::<Vec<_>>(),
    });
    write_json(&args.common.json, &value)?;
    if let Some(p) = &args.plot {
        let curve = coverage::coverage_table(&layer, &crate::cli::analyze_plot::curve_mm(&xs), chart, &skins, c)?;
        write_png(p, &crate::cli::analyze_plot::coverage(&preset.name, &curve, hiding, &skins, c)?)?;
    }
    Ok(())
}

fn parse_range_um(text: &str) -> Result<(f64, f64)> {
    let (a, b) = text.split_once(':').ok_or_else(|| anyhow!("--thickness-um `{text}`: expected MIN:MAX in µm"))?;
    let parse =
        |s: &str| s.trim().parse::<f64>().map_err(|_| anyhow!("--thickness-um `{text}`: `{s}` is not a number"));
    let (lo, hi) = (check_um("--thickness-um minimum", parse(a)?)?, check_um("--thickness-um maximum", parse(b)?)?);
    if hi < lo {
        bail!("--thickness-um `{text}`: the maximum is below the minimum");
    }
    Ok((lo, hi))
}

fn run_match(args: &MatchArgs) -> Result<()> {
    let loaded = args.presets.iter().map(|p| load_layer(p)).collect::<Result<Vec<_>>>()?;
    let shades: Vec<Layer> = loaded.iter().map(|(_, l)| l.clone()).collect();
    let skins = skins(&args.common)?;
    let c = Colorimeter::get(viewing(&args.common));
    let target = match &args.target {
        Some(lab) => Target::Lab(*lab),
        None => Target::BareSkin,
    };
    let range = match (&args.thickness_um, target) {
        (Some(t), _) => parse_range_um(t)?,
        (None, Target::Lab(_)) => (0.0, 0.1),
        (None, Target::BareSkin) => {
            let w = check_um("--wear-um", args.wear_um)?;
            (w, w)
        }
    };
    let cover = matching::product_line_coverage(&shades, &skins, target, range, args.gap_de, c)?;
    let target_text = match target {
        Target::BareSkin => "the bare skin (your shade)".to_string(),
        Target::Lab(l) => format!("L*a*b* {}", lab_text(l)),
    };
    println!(
        "{} shades, {} skins, target {target_text}, {}-{} µm, {}",
        shades.len(),
        skins.len(),
        um(range.0),
        um(range.1),
        c.viewing()
    );
    crate::emit(&format!("{:<24} {:>20} {:<28} {:>8} {:>7}  ", "skin", "L*, a*, b*", "best shade", "µm", "ΔE00"))?;
    for sc in &cover {
        crate::emit(&format!(
            "{:<24} {:>20} {:<28} {:>8} {:>7.2}{}",
            skins[sc.skin].0,
            lab_text(sc.skin_lab),
            shades[sc.best.shade].name,
            um(sc.best.thickness_mm),
            sc.best.delta_e,
            if sc.gap { "  gap" } else { "" }
        ))?;
    }
    let gaps = cover.iter().filter(|s| s.gap).count();
    println!("{gaps} of {} skins in gaps (best ΔE2000 > {})", cover.len(), args.gap_de);
    for (i, s) in shades.iter().enumerate() {
        let n = cover.iter().filter(|sc| sc.best.shade == i).count();
        println!("  {:<28} best for {n} skins", s.name);
    }
    let value = json!({
        "viewing": c.viewing().to_string(), "range_mm": [range.0, range.1], "gap_delta_e": args.gap_de,
        "target": match target { Target::BareSkin => json!("bare skin"), Target::Lab(l) => json!(l) },
        "shades": shades.iter().map(|s| json!({"name": s.name, "r_inf_lab": lab_of(c, &s.r_inf())})).collect::<Vec<_>>(),
        "skins": cover.iter().map(|sc| json!({
            "name": skins[sc.skin].0, "lab": sc.skin_lab, "best_shade": shades[sc.best.shade].name,
            "thickness_mm": sc.best.thickness_mm, "delta_e": sc.best.delta_e, "covered_lab": sc.best.lab, "gap": sc.gap,
        })).collect::<Vec<_>>(),
    });
    write_json(&args.common.json, &value)?;
    if let Some(p) = &args.plot {
        write_png(p, &crate::cli::analyze_plot::shade_map(&shades, &skins, &cover, args.gap_de, &target_text, c)?)?;
    }
    Ok(())
}

fn run_mix(args: &MixArgs) -> Result<()> {
    let loaded = args.bases.iter().map(|p| load_layer(p)).collect::<Result<Vec<_>>>()?;
    let bases: Vec<Layer> = loaded.iter().map(|(_, l)| l.clone()).collect();
    let c = Colorimeter::get(viewing(&args.common));
    let skin = match args.thickness_um {
        None => None,
        Some(t) => {
            let all = skins(&args.common)?;
            let chosen = match &args.sample {
                None => all.into_iter().next(),
                Some(name) => all.into_iter().find(|(n, _)| n == name),
            };
            let (name, r) =
                chosen.ok_or_else(|| anyhow!("no skin sample named `{}`", args.sample.as_deref().unwrap_or("")))?;
            Some((name, r, check_um("--thickness-um", t)?))
        }
    };
    let colour_under = |cm: &Colorimeter, l: &Layer| match &skin {
        None => lab_of(cm, &l.r_inf()),
        Some((_, r, x)) => lab_of(cm, &l.reflectance_over(*x, r)),
    };
    let (target_lab, target_name, target_layer) = match (&args.target, &args.target_preset) {
        (Some(lab), _) => (*lab, format!("L*a*b* {}", lab_text(*lab)), None),
        (None, Some(p)) => {
            let (preset, layer) = load_layer(p)?;
            (colour_under(c, &layer), preset.name, Some(layer))
        }
        (None, None) => bail!("give --target L,a,b or --target-preset PRESET"),
    };
    let target = match &skin {
        None => MixTarget::RInf(target_lab),
        Some((_, r, x)) => MixTarget::Covered { skin: Box::new(*r), thickness_mm: *x, lab: target_lab },
    };
    let fit = mixing::fit_mix(&bases, &target, c)?;
    let what = match &skin {
        None => "R∞ (opaque layer)".to_string(),
        Some((name, _, x)) => format!("skin `{name}` under {} µm", um(*x)),
    };
    println!("mixing {} bases to reach {target_name} as {what}, {}", bases.len(), c.viewing());
    for (b, x) in bases.iter().zip(&fit.concentrations) {
        crate::emit(&format!("  {:<28} {:>8.4}", b.name, x))?;
    }
    crate::emit(&format!("target {}  mixture {}  ΔE2000 {:.3}", lab_text(target_lab), lab_text(fit.lab), fit.delta_e))?;
    // With a target spectrum, the match under illuminant A says whether it holds when the
    // light changes (a metameric match does not).
    let metamerism = match &target_layer {
        None => None,
        Some(t) => {
            let a = Colorimeter::get(Viewing { illuminant: Illuminant::A, observer: args.common.observer });
            let lab = |l: &Layer| rouge_measure::Lab { lab: colour_under(a, l), viewing: a.viewing() };
            let de = delta_e_2000(&lab(&fit.mixture), &lab(t))?;
            crate::emit(&format!("under illuminant A: ΔE2000 {de:.3} (metamerism of the match)"))?;
            Some(de)
        }
    };
    let value = json!({
        "viewing": c.viewing().to_string(), "target_lab": target_lab, "target": target_name, "as": what,
        "bases": bases.iter().map(|b| b.name.clone()).collect::<Vec<_>>(),
        "concentrations": fit.concentrations, "mixture_lab": fit.lab, "delta_e": fit.delta_e,
        "delta_e_illuminant_a": metamerism,
    });
    write_json(&args.common.json, &value)
}
