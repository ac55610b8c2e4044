//! `rouge qc STANDARD BATCH...`: pass/fail of production batches against a standard in
//! ΔE2000, CMC(l:c) or ΔE*ab, and their 555 shade numbers (`rouge_measure::analysis::qc`), as a
//! table, JSON and a PNG with the tolerance contours.

use crate::cli::analyze::{load_layer, write_json};
use crate::cli::analyze_metamerism::{read_one_spectrum, split_pick};
use crate::cli::analyze_plot::{QcPoint, qc_report};
use crate::cli::color::{parse_illuminant, parse_observer};
use anyhow::{Result, bail};
use clap::Args;
use rouge_measure::analysis::lab_of;
use rouge_measure::analysis::qc::{Metric, judge};
use rouge_measure::colorimetry::{Colorimeter, Illuminant, Observer, Viewing};
use rouge_measure::import::read_spectra;
use rouge_measure::spectrum::{Extrapolation, Spectrum};
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct QcArgs {
    /// The standard: a preset (its R∞) or a spectrum file (`FILE#NAME` for one of several).
    pub standard: String,
    /// The batches: presets or spectrum files (every spectrum of a file without `#NAME`).
    #[arg(required = true, num_args = 1..)]
    pub batches: Vec<String>,
    /// Tolerance formula: de2000, cmc or ab.
    #[arg(long, default_value = "de2000")]
    pub metric: String,
    /// CMC's l:c.
    #[arg(long, default_value = "2:1")]
    pub cmc: String,
    /// The tolerance, in the formula's units.
    #[arg(long, default_value_t = 1.0)]
    pub tolerance: f64,
    /// 555 block widths in L*, a*, b* (`W` or `WL,Wa,Wb`; default: the tolerance).
    #[arg(long, value_delimiter = ',')]
    pub block: Vec<f64>,
    /// Illuminant.
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    pub illuminant: Illuminant,
    /// Observer.
    #[arg(long, default_value = "1931", value_parser = parse_observer)]
    pub observer: Observer,
    /// Hold the end values of spectra that do not cover 380-780 nm.
    #[arg(long)]
    pub extrapolate: bool,
    /// Also write the batch report as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Also draw the batch report as a PNG here: the batches in the a*b* plane and in lightness
    /// and chroma around the standard, with the ΔE2000, CMC(l:c) and ΔE*ab tolerance contours.
    #[arg(long)]
    pub png: Option<PathBuf>,
}

/// The spectra a command-line item names: a preset's R∞, one named spectrum, or all of a file's.
fn spectra(spec: &str, extrapolate: bool) -> Result<Vec<(String, Spectrum)>> {
    let (path, pick) = split_pick(spec);
    let p = Path::new(path);
    if !p.is_file() || p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
        let (preset, layer) = load_layer(spec)?;
        return Ok(vec![(format!("{} (R∞)", preset.name), layer.r_inf())]);
    }
    if pick.is_some() {
        return Ok(vec![read_one_spectrum(p, pick, extrapolate)?]);
    }
    let extrapolation = if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
    Ok(read_spectra(p)?.to_working_grid(extrapolation)?.into_iter().map(|(n, s)| (format!("{path}#{n}"), s)).collect())
}

fn metric(args: &QcArgs) -> Result<Metric> {
    Ok(match args.metric.to_ascii_lowercase().as_str() {
        "de2000" | "2000" => Metric::De2000,
        "ab" | "1976" => Metric::Ab,
        "cmc" => {
            let parse = |s: &str| s.trim().parse::<f64>().ok().filter(|v| *v > 0.0 && v.is_finite());
            match args.cmc.split_once(':').map(|(l, c)| (parse(l), parse(c))) {
                Some((Some(l), Some(c))) => Metric::Cmc { l, c },
                _ => bail!("--cmc `{}`: expected l:c with positive numbers, e.g. 2:1", args.cmc),
            }
        }
        other => bail!("--metric `{other}`: one of de2000, cmc, ab"),
    })
}

pub fn run(args: &QcArgs) -> Result<()> {
    let metric = metric(args)?;
    let block = match args.block.as_slice() {
        [] => [args.tolerance; 3],
        [w] => [*w; 3],
        [l, a, b] => [*l, *a, *b],
        other => bail!("--block: one width or three (L*, a*, b*), got {}", other.len()),
    };
    let c = Colorimeter::get(Viewing { illuminant: args.illuminant, observer: args.observer });
    let standards = spectra(&args.standard, args.extrapolate)?;
    let [(std_name, std)] = standards.as_slice() else {
        bail!("{}: {} spectra; the standard is one (FILE#NAME)", args.standard, standards.len());
    };
    let std_lab = lab_of(c, std);
    println!(
        "standard {std_name}: L*a*b* {:.2}, {:.2}, {:.2}; tolerance {} {}, 555 blocks {:?}, {}",
        std_lab[0],
        std_lab[1],
        std_lab[2],
        metric.name(),
        args.tolerance,
        block,
        c.viewing()
    );
    crate::emit(&format!("{:<40} {:>8} {:>8} {:>8} {:>9} {:>5}  verdict", "batch", "ΔL*", "Δa*", "Δb*", "ΔE", "555"))?;
    let mut rows = Vec::new();
    let mut points = Vec::new();
    for spec in &args.batches {
        for (name, r) in spectra(spec, args.extrapolate)? {
            let j = judge(std_lab, lab_of(c, &r), metric, args.tolerance, block)?;
            crate::emit(&format!(
                "{:<40} {:>+8.2} {:>+8.2} {:>+8.2} {:>9.3} {:>5}  {}",
                name,
                j.delta_lab[0],
                j.delta_lab[1],
                j.delta_lab[2],
                j.delta_e,
                j.shade,
                if j.pass { "pass" } else { "FAIL" }
            ))?;
            // The plot labels a file's spectra by their own names.
            let short = name.rsplit_once('#').map_or(name.as_str(), |(_, n)| n).to_string();
            points.push(QcPoint { name: short, lab: lab_of(c, &r), pass: j.pass });
            rows.push(json!({"batch": name, "lab": lab_of(c, &r), "judgement": j}));
        }
    }
    let failed = rows.iter().filter(|r| r["judgement"]["pass"] == json!(false)).count();
    println!("{} of {} batches pass", rows.len() - failed, rows.len());
    let value = json!({
        "standard": std_name, "standard_lab": std_lab, "viewing": c.viewing().to_string(),
        "metric": metric.name(), "tolerance": args.tolerance, "block_555": block,
        "batches": rows, "passed": rows.len() - failed, "failed": failed,
    });
    write_json(&args.json, &value)?;
    if let Some(path) = &args.png {
        let title = format!(
            "QC: {} of {} batches pass, {} ≤ {} ({})",
            rows.len() - failed,
            rows.len(),
            metric.name(),
            args.tolerance,
            c.viewing()
        );
        let png = qc_report(&title, std_lab, &points, metric, args.tolerance)?;
        crate::write_output(path, png)?;
    }
    Ok(())
}
