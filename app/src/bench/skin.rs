//! `rouge bench skin`: the colour the renderer gives skin under a cosmetic layer against the
//! 81-wavelength computation (rouge_render::skin_study: a flat patch, white light from the front,
//! no specular, subsurface off, linear output), in two tables:
//!
//! 1. **Accuracy**: each of the skin model's ten tones under each of the five sample foundations
//!    at 0-60 µm; the renderer composes per channel of its compositing basis
//!    (rouge_measure::compositing::CompositingBasis) and the difference is what three channels
//!    cost (the skin issue's target: ΔE2000 0.5 mean, 1.0 at the 95th percentile). Two ways the
//!    skin gets its colour, a row each: the tone's colour as a uniform albedo (`--skin-tone`), and
//!    the skin maps' albedo texture (uniform maps of the tone through the tone's colour table and
//!    the 8-bit texture: what `--skin-maps` draws).
//! 2. **Coverage on screen against coverage on paper**: a spot (a mole, a hyperpigmented macule,
//!    an acne papule at full strength) on three tones under a foundation at 0-60 µm: the rendered
//!    ΔE2000 between spot and skin against `rouge analyze coverage`'s prediction for the same
//!    spectra (the issue asks for agreement within 1 ΔE). `--plot F` draws it.

use crate::bench::report::{emit_with_json, markdown_table};
use crate::plot_png::{Chart, Marker, Series};
use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_measure::colorimetry::{delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::skin::{skin_tone, skin_tones};
use rouge_model::look::{builtin_preset, builtin_preset_names};
use rouge_model::skin::Condition;
use rouge_render::Gpu;
use rouge_render::skin_study::{SkinColour, SkinPatch, SpotRow, reference_lab, spot_coverage};
use serde::Serialize;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SkinBenchArgs {
    /// Layer thicknesses, µm.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0f64, 5.0, 10.0, 20.0, 40.0, 60.0])]
    pub thickness_um: Vec<f64>,
    /// Only these tones (default: all ten; the coverage table keeps those of its light, tan and
    /// deep skins that are listed).
    #[arg(long, value_delimiter = ',')]
    pub tones: Vec<String>,
    /// Also write the rows as JSON here (both tables: {"accuracy": [...], "coverage": [...]}).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw coverage on screen against coverage on paper as a PNG here.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// One tone's errors over the foundations and thicknesses (or all tones: `tone` "all").
#[derive(Debug, Serialize)]
struct Row {
    tone: String,
    skin: &'static str,
    method: &'static str,
    samples: usize,
    delta_e_mean: f64,
    delta_e_p95: f64,
    delta_e_max: f64,
    worst: String,
    device: String,
}

fn stats(tone: &str, skin: SkinColour, errors: &mut [(f64, String)], device: &str) -> Row {
    errors.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = errors.len();
    Row {
        tone: tone.into(),
        skin: skin.name(),
        method: "compositing basis (3 channels)",
        samples: n,
        delta_e_mean: errors.iter().map(|e| e.0).sum::<f64>() / n as f64,
        delta_e_p95: errors[(n * 95 / 100).min(n - 1)].0,
        delta_e_max: errors[n - 1].0,
        worst: errors[n - 1].1.clone(),
        device: device.into(),
    }
}

/// One spot case of the coverage table.
#[derive(Debug, Serialize)]
struct CoverageCase {
    tone: &'static str,
    spot: &'static str,
    preset: String,
    rows: Vec<SpotRow>,
    /// The largest |screen − paper| over the thicknesses.
    worst_difference: f64,
}

/// Tones, spots and the foundation each wears in the coverage table: a light, a medium and a
/// deep skin, each with the foundation of its own depth.
const COVERAGE_CASES: [(&str, &str); 3] =
    [("light", "foundation_02_ivory"), ("tan", "foundation_03_sand"), ("deep", "foundation_05_espresso")];
const SPOTS: [Condition; 3] = [Condition::Moles, Condition::Hyperpigmentation, Condition::Acne];

pub fn run(args: &SkinBenchArgs) -> Result<()> {
    if args.thickness_um.iter().any(|t| !(0.0..=1000.0).contains(t)) {
        bail!("--thickness-um: each thickness must be 0 to 1000 µm");
    }
    for name in &args.tones {
        skin_tone(name).with_context(|| format!("--tones {name}"))?;
    }
    let wanted = |name: &str| args.tones.is_empty() || args.tones.iter().any(|t| t == name);
    let gpu = Gpu::headless()?;
    let device = gpu.describe();
    let mut patch = SkinPatch::new(&gpu)?;
    // The sample foundations: the built-in presets named foundation_*.
    let foundations: Vec<&str> =
        builtin_preset_names().iter().copied().filter(|n| n.starts_with("foundation_")).collect();
    let mut rows = Vec::new();
    for colour in [SkinColour::Albedo, SkinColour::Maps] {
        let mut all = Vec::new();
        for tone in skin_tones().iter().filter(|t| wanted(&t.name)) {
            let skin = patch.set_skin(&tone.params, colour).with_context(|| format!("tone {}", tone.name))?;
            let mut errors = Vec::new();
            for &name in &foundations {
                let preset = builtin_preset(name).with_context(|| format!("no built-in preset {name}"))?;
                for &um in &args.thickness_um {
                    let rendered = linear_srgb_to_lab(patch.render(&preset, um)?);
                    let e = delta_e_2000_raw(rendered, reference_lab(&preset, um, &skin));
                    errors.push((e, format!("{} {um} µm on {}", preset.name, tone.name)));
                }
            }
            all.extend(errors.iter().cloned());
            rows.push(stats(&tone.name, colour, &mut errors, &device));
        }
        rows.push(stats("all", colour, &mut all, &device));
    }
    let caption = format!(
        "Skin under one foundation layer, rendered (compositing basis) against the 81-wavelength \
         composition: {} foundations × {} thicknesses per tone, {device}",
        foundations.len(),
        args.thickness_um.len()
    );
    let header = ["tone", "skin colour from", "method", "ΔE2000 mean", "p95", "max", "worst"];
    let cells = rows.iter().map(|r| {
        vec![
            r.tone.clone(),
            r.skin.into(),
            r.method.into(),
            format!("{:.2}", r.delta_e_mean),
            format!("{:.2}", r.delta_e_p95),
            format!("{:.2}", r.delta_e_max),
            r.worst.clone(),
        ]
    });
    let accuracy = markdown_table(&caption, &header, 3, cells);

    let mut cases = Vec::new();
    for (tone_name, preset_name) in COVERAGE_CASES.into_iter().filter(|(t, _)| wanted(t)) {
        let tone = skin_tone(tone_name)?;
        let preset = builtin_preset(preset_name).with_context(|| format!("no built-in preset {preset_name}"))?;
        for spot in SPOTS {
            let rows = spot_coverage(&mut patch, &tone.params, spot, &preset, &args.thickness_um, SkinColour::Maps)?;
            let worst_difference = rows.iter().map(|r| (r.screen_delta_e - r.paper_delta_e).abs()).fold(0.0, f64::max);
            cases.push(CoverageCase {
                tone: tone_name,
                spot: spot.key(),
                preset: preset.name.clone(),
                rows,
                worst_difference,
            });
        }
    }
    let caption = format!(
        "Coverage on screen against coverage on paper: ΔE2000 between a spot and the skin around it under a \
         foundation, rendered (skin maps) and as `rouge analyze coverage` predicts it, at {} µm, {device}",
        args.thickness_um.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(", ")
    );
    let header =
        ["tone", "spot", "foundation", "paper ΔE by thickness", "screen ΔE by thickness", "worst |difference|"];
    let list = |v: Vec<f64>| v.iter().map(|x| format!("{x:.2}")).collect::<Vec<_>>().join(" / ");
    let cells = cases.iter().map(|c| {
        vec![
            c.tone.to_string(),
            c.spot.to_string(),
            c.preset.clone(),
            list(c.rows.iter().map(|r| r.paper_delta_e).collect()),
            list(c.rows.iter().map(|r| r.screen_delta_e).collect()),
            format!("{:.2}", c.worst_difference),
        ]
    });
    let coverage = markdown_table(&caption, &header, 3, cells);
    if let Some(path) = &args.plot {
        let png = coverage_plot(&cases, &device)?;
        crate::write_output(path, &png)?;
    }
    emit_with_json(
        &format!("{accuracy}\n\n{coverage}"),
        &serde_json::json!({"accuracy": rows, "coverage": cases}),
        args.json.as_deref(),
    )
}

/// One panel per tone: each spot's ΔE against thickness, on paper (line) and on screen (markers).
fn coverage_plot(cases: &[CoverageCase], device: &str) -> Result<Vec<u8>> {
    let colours = [[31u8, 119, 180], [214, 39, 40], [44, 160, 44]];
    let charts: Vec<Chart> = COVERAGE_CASES
        .iter()
        .map(|(tone, _)| {
            let mut series = Vec::new();
            for (case, rgb) in cases.iter().filter(|c| c.tone == *tone).zip(colours) {
                let points = |f: fn(&SpotRow) -> f64| case.rows.iter().map(|r| (r.thickness_um, f(r), None)).collect();
                series.push(Series {
                    label: format!("{} on paper", case.spot),
                    rgb,
                    points: points(|r| r.paper_delta_e),
                    line: true,
                    marker: Marker::Dot,
                });
                series.push(Series {
                    label: format!("{} on screen", case.spot),
                    rgb: rgb.map(|c| c / 2),
                    points: points(|r| r.screen_delta_e),
                    line: false,
                    marker: Marker::Cross,
                });
            }
            let preset = cases.iter().find(|c| c.tone == *tone).map_or("", |c| c.preset.as_str());
            Chart {
                title: format!("{tone} skin under {preset}"),
                x_label: "foundation thickness, µm".into(),
                y_label: "ΔE2000 spot against skin".into(),
                series,
            }
        })
        .collect();
    crate::plot_png::render(&format!("Coverage on screen against coverage on paper, {device}"), &charts, 3)
}
