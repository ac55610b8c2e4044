//! `rouge bench recipe`: how fast the recipe search (`rouge_measure::analysis::recipe`) runs on
//! the sample presets, and whether it finds the recipe of a synthetic target again.
//!
//! The library is every preset of `--presets` (the 13 samples); the target is Duncan's mixture
//! of three of them (ivory, coral blush, bronze eyeshadow at 0.6 : 0.25 : 0.15) seen opaque, with
//! ±0.3 % uniform reflectance noise (a spectrophotometer's repeatability); the objective weighs
//! D65, A and FL11 equally. For each k the table gives the combinations fitted per second (the
//! figure in docs/BENCHMARKS.md), model evaluations per second, the best recipe's objective and
//! whether it is the generating recipe (k = 3) or contains it (k > 3).

use crate::bench::report::{emit_with_json, markdown_table};
use crate::cli::analyze_recipe::load_library;
use anyhow::{Result, bail};
use clap::Args;
use rouge_measure::analysis::Layer;
use rouge_measure::analysis::correction::Presentation;
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::analysis::recipe::{RecipeSearch, WeightedViewing, search_recipes};
use rouge_measure::colorimetry::{Illuminant, Observer, Viewing};
use rouge_measure::spectrum::Spectrum;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct RecipeBenchArgs {
    /// Folder of colorant presets (*.json).
    #[arg(long, default_value = "data/presets")]
    pub presets: PathBuf,
    /// Colorants per recipe to time.
    #[arg(long, value_delimiter = ',', default_values_t = [2usize, 3, 4])]
    pub k: Vec<usize>,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// The generating recipe: preset file stems and amounts.
const TRUTH: [(&str, f64); 3] = [("foundation_02_ivory", 0.6), ("blush_02_coral", 0.25), ("eyeshadow_03_bronze", 0.15)];

#[derive(Debug, Serialize)]
struct Row {
    library: usize,
    k: usize,
    combinations: usize,
    seconds: f64,
    recipes_per_second: f64,
    evaluations_per_second: f64,
    best: String,
    best_objective: f64,
    recovered: bool,
    largest_amount_error: Option<f64>,
    device: String,
}

/// Uniform noise of ±`amplitude`, from a fixed seed (a 64-bit LCG), held in [0, 1].
fn noisy(r: &Spectrum, amplitude: f64) -> Spectrum {
    let mut state = 7u64;
    Spectrum(std::array::from_fn(|i| {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let u = (state >> 11) as f64 / (1u64 << 53) as f64;
        (r.0[i] + amplitude * (2.0 * u - 1.0)).clamp(0.0, 1.0)
    }))
}

/// The CPU the search ran on: cores, architecture and the model name `/proc/cpuinfo` gives.
fn cpu_description() -> String {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, m)| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown model".into());
    format!("{cores}-core {} CPU ({model}), one thread", std::env::consts::ARCH)
}

pub fn run(args: &RecipeBenchArgs) -> Result<()> {
    let library = load_library(&[args.presets.to_string_lossy().into_owned()])?;
    let mut chosen: Vec<Layer> = Vec::new();
    for (name, _) in TRUTH {
        match library.iter().find(|c| c.layer.name == name) {
            Some(c) => chosen.push(c.layer.clone()),
            None => bail!("{}: no preset {name}.json (the bench's target is made from it)", args.presets.display()),
        }
    }
    let amounts: Vec<f64> = TRUTH.iter().map(|t| t.1).collect();
    let target = noisy(&duncan_mix("target", &chosen, &amounts)?.r_inf(), 0.003);
    let viewings = [Illuminant::D65, Illuminant::A, Illuminant::Fl11]
        .map(|illuminant| WeightedViewing { viewing: Viewing { illuminant, observer: Observer::Cie1931 }, weight: 1.0 })
        .to_vec();
    let device = cpu_description();
    let mut rows = Vec::new();
    for &k in &args.k {
        let search = RecipeSearch {
            colorants: library.clone(),
            fixed: vec![],
            k,
            viewings: viewings.clone(),
            presentation: Presentation::Opaque,
            cost_weight: 0.0,
        };
        let start = Instant::now();
        let report = search_recipes(&search, &target, 1)?;
        let seconds = start.elapsed().as_secs_f64();
        let Some(best) = report.recipes.first() else { bail!("k = {k}: no feasible recipe") };
        let amount_of = |name: &str| best.names.iter().position(|n| n == name).map(|j| best.amounts[j]);
        let recovered = TRUTH.iter().all(|(n, _)| amount_of(n).is_some());
        let largest_amount_error =
            recovered.then(|| TRUTH.iter().map(|(n, a)| (amount_of(n).unwrap_or(0.0) - a).abs()).fold(0.0, f64::max));
        rows.push(Row {
            library: library.len(),
            k,
            combinations: report.combinations,
            seconds,
            recipes_per_second: report.combinations as f64 / seconds,
            evaluations_per_second: report.evaluations as f64 / seconds,
            best: best
                .names
                .iter()
                .zip(&best.amounts)
                .map(|(n, a)| format!("{n} {a:.3}"))
                .collect::<Vec<_>>()
                .join(" + "),
            best_objective: best.objective,
            recovered,
            largest_amount_error,
            device: device.clone(),
        });
    }
    let table = markdown_table(
        "Recipe search on the sample presets (target: a noisy mixture of three; D65, A, FL11 weighted 1, 1, 1)",
        &[
            "k",
            "combinations",
            "s",
            "recipes/s",
            "evaluations/s",
            "best objective (ΔE00)",
            "generating recipe found",
            "largest amount error",
        ],
        0,
        rows.iter().map(|r| {
            vec![
                r.k.to_string(),
                r.combinations.to_string(),
                format!("{:.3}", r.seconds),
                format!("{:.0}", r.recipes_per_second),
                format!("{:.0}", r.evaluations_per_second),
                format!("{:.3}", r.best_objective),
                if r.recovered { "yes".into() } else { format!("no: {}", r.best) },
                r.largest_amount_error.map_or("-".into(), |e| format!("{e:.4}")),
            ]
        }),
    );
    emit_with_json(&format!("{table}\ndevice: {device}"), &rows, args.json.as_deref())
}
