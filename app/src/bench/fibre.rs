//! `rouge bench fibre`: the hair pass's fibre model (`rouge_render::fibre`) against PBRT-v4's
//! `HairBxDF` averaged across the fibre (`data/hair/pbrt_v4_hair.csv`, made by
//! `python/hair_reference.py`): relative RMS difference and scattered energy per σa, the CPU
//! cost of one evaluation, and a plot of both models against the azimuth.

use anyhow::{Context, Result};
use clap::Args;
use rouge_render::fibre::{self, PbrtRow};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct FibreBenchArgs {
    /// PBRT-v4's reference (python/hair_reference.py's CSV).
    #[arg(long, default_value = "data/hair/pbrt_v4_hair.csv")]
    pub reference: PathBuf,
    /// Also write the rows and the summary as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw both models against the azimuth, per σa, for three pairs of angles (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

pub fn run(args: &FibreBenchArgs) -> Result<()> {
    let csv = std::fs::read_to_string(&args.reference)
        .with_context(|| format!("cannot read {} (python/hair_reference.py makes it)", args.reference.display()))?;
    let rows = fibre::compare_with_pbrt(&csv).map_err(|e| anyhow::anyhow!("{}: {e}", args.reference.display()))?;
    let summary = fibre::summarize(&rows);
    // One evaluation's CPU cost (the GPU's is in `rouge bench aa`'s hair pass).
    let (t, l, v) = (glam::Vec3::X, glam::Vec3::new(0.3, 0.2, 0.93).normalize(), glam::Vec3::Z);
    let n = 1_000_000;
    let start = Instant::now();
    let mut sum = 0.0f32;
    for i in 0..n {
        let sigma = (i % 7) as f32 * 0.5;
        sum += fibre::scattering(t, l, v, [sigma; 3], fibre::ROUGHNESS_RAD)[0];
    }
    let ns = start.elapsed().as_secs_f64() * 1e9 / f64::from(n);
    std::hint::black_box(sum);
    println!("Rouge's fibre model (render/src/fibre.rs) against PBRT-v4's HairBxDF averaged across the fibre");
    println!("({} rows of {}; tangent reversed for PBRT's tilt sign)", rows.len(), args.reference.display());
    println!("  {:>6} {:>6} {:>13} {:>12}", "σa", "rows", "relative RMS", "energy ×PBRT");
    for s in &summary {
        println!("  {:>6} {:>6} {:>13.3} {:>12.3}", s.sigma_a, s.rows, s.relative_rms, s.energy_ratio);
    }
    println!("  one RGB evaluation on the CPU: {ns:.0} ns");
    if let Some(path) = &args.json {
        let json =
            serde_json::json!({ "reference": args.reference, "summary": summary, "ns_per_eval": ns, "rows": rows });
        crate::write_output(path, serde_json::to_string_pretty(&json)?.as_bytes())?;
    }
    if let Some(path) = &args.plot {
        crate::write_output(path, &plot(&rows)?)?;
    }
    Ok(())
}

/// Per σa a chart of f against φ for (θi, θo) = (0, 0), (30, −30) and (−60, 60) degrees:
/// PBRT's markers, Rouge's lines.
fn plot(rows: &[PbrtRow]) -> Result<Vec<u8>> {
    use crate::plot_png::{Chart, Marker, Series};
    let pairs = [((0.0, 0.0), [214, 39, 40]), ((30.0, -30.0), [31, 119, 180]), ((-60.0, 60.0), [44, 160, 44])];
    let mut sigmas: Vec<f32> = Vec::new();
    for r in rows {
        if !sigmas.contains(&r.sigma_a) {
            sigmas.push(r.sigma_a);
        }
    }
    let mut charts = Vec::new();
    for sigma in sigmas {
        let mut series = Vec::new();
        for ((ti, to), rgb) in pairs {
            let of: Vec<&PbrtRow> =
                rows.iter().filter(|r| r.sigma_a == sigma && r.theta_i_deg == ti && r.theta_o_deg == to).collect();
            let label = format!("θi {ti}°, θo {to}°");
            series.push(Series {
                label: format!("{label} PBRT-v4"),
                rgb,
                points: of.iter().map(|r| (f64::from(r.phi_deg), f64::from(r.pbrt), None)).collect(),
                line: false,
                marker: Marker::Dot,
            });
            series.push(Series {
                label: format!("{label} Rouge"),
                rgb,
                points: of.iter().map(|r| (f64::from(r.phi_deg), f64::from(r.rouge), None)).collect(),
                line: true,
                marker: Marker::None,
            });
        }
        charts.push(Chart {
            title: format!("σa = {sigma} per radius"),
            x_label: "φ (degrees)".into(),
            y_label: "radiance per irradiance (1/sr)".into(),
            series,
        });
    }
    crate::plot_png::render("Hair fibre: Rouge (lines) against PBRT-v4's HairBxDF (dots)", &charts, 2)
}
