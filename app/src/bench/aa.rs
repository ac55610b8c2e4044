//! `rouge bench aa`: edge antialiasing (\[Sander2001\]) against supersampling on turning meshes:
//! the error near discontinuities and the crawl against a k×k supersampled reference, ms per
//! frame, and the edge counts of the paper's table 1 over 100 viewpoints
//! (`rouge_render::aa_study`).

use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_model::mesh::TriangleMesh;
use rouge_render::aa::{AaMode, EdgeCoverage};
use rouge_render::aa_study::{self, AaRow, AaStudy, EdgeTable};
use rouge_render::{Gpu, Renderer, Scene};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct AaBenchArgs {
    /// Image width.
    #[arg(long, default_value_t = 320)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 240)]
    pub height: u32,
    /// Frames of the turning sequence.
    #[arg(long, default_value_t = 12)]
    pub frames: u32,
    /// Yaw step between frames, degrees (small: the edges move by a fraction of a pixel).
    #[arg(long, default_value_t = 0.25)]
    pub yaw_step: f32,
    /// Supersampling of the reference, k×k samples per pixel.
    #[arg(long, default_value_t = 8)]
    pub reference: u32,
    /// Meshes: head (the default head, subdivided once), cube (flat-shaded, the paper's
    /// textured cube without its texture), wedge (builtin:wedge, a box with a slanted back),
    /// face (the default head as `rouge render` draws it: two levels, its skin, look and
    /// lights, turned from yaw 35°; issue 27's scene, best with --width 320 --height 180
    /// --reference 16 --mask detail).
    #[arg(long, value_delimiter = ',', default_values_t = ["head".to_string(), "cube".to_string(), "wedge".to_string()])]
    pub meshes: Vec<String>,
    /// Pixels measured: edges (within 2 px of a mesh edge drawn from the view) or detail
    /// (where the reference differs from its 1-px blur by more than --threshold levels of 255:
    /// every discontinuity a viewer sees, hairs and eye outlines included).
    #[arg(long, value_enum, default_value_t = MaskArg::Edges)]
    pub mask: MaskArg,
    /// Levels of 255 of the detail mask.
    #[arg(long, default_value_t = 4.0)]
    pub threshold: f32,
    /// Frames timed per mode (median reported).
    #[arg(long, default_value_t = 9)]
    pub timed_frames: u32,
    /// Also write the rows and tables as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw error and crawl against ms per frame (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// `--mask` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MaskArg {
    /// Within 2 px of a mesh edge.
    Edges,
    /// Where the reference differs from its 1-px blur.
    Detail,
}

/// The default head as `rouge render --width W --height H` draws it (its look, skin and
/// lights), ready to render, with its mesh.
fn face(width: u32, height: u32) -> Result<(rouge_render::job::Prepared, TriangleMesh)> {
    #[derive(clap::Parser)]
    struct Defaults {
        #[command(flatten)]
        scene: crate::cli::render::scene_args::SceneArgs,
    }
    use clap::Parser;
    let (w, h) = (width.to_string(), height.to_string());
    let defaults = Defaults::try_parse_from(["rouge", "--width", w.as_str(), "--height", h.as_str()])?;
    let (job, _) = defaults.scene.render_job()?;
    let loaded = job.load()?;
    let prepared = job.prepare_loaded(&loaded)?;
    Ok((prepared, loaded.mesh))
}

/// One mesh's results.
#[derive(Debug, serde::Serialize)]
struct MeshResult {
    mesh: String,
    /// CPU ms of the edge preprocess (welding, classification, orientation, clusters).
    preprocess_ms: f64,
    table: EdgeTable,
    rows: Vec<AaRow>,
}

fn mesh(name: &str) -> Result<(TriangleMesh, f32, f32)> {
    use rouge_model::mesh::{load_mesh, shapes::builtin_shape};
    // (mesh, yaw of the sequence's first frame, pitch): three-quarter views, silhouettes
    // crossing sharp edges.
    Ok(match name {
        "head" => (load_mesh(None, 1.0, 1)?, 30.0, 5.0),
        // The app's head (two subdivision levels): for the preprocess cost.
        "head2" => (load_mesh(None, 1.0, 2)?, 30.0, 5.0),
        "cube" => (rouge_render::edges::cube(40.0).triangulate(), 20.0, 25.0),
        "wedge" => (builtin_shape("wedge").context("builtin:wedge")?.triangulate(), 35.0, 20.0),
        other => bail!("unknown mesh {other:?} for bench aa: use head, face, cube or wedge"),
    })
}

pub fn run(args: &AaBenchArgs) -> Result<()> {
    if args.frames < 2 || args.reference < 2 || args.width == 0 || args.height == 0 {
        bail!("bench aa needs at least 2 frames, a reference of at least 2×2 and a non-empty image");
    }
    if !(args.yaw_step.is_finite() && args.yaw_step > 0.0) {
        bail!("--yaw-step {}: must be positive", args.yaw_step);
    }
    let gpu = Gpu::headless()?;
    let device = gpu.describe();
    let mut results = Vec::new();
    let modes = vec![
        (AaMode::None, EdgeCoverage::TwoSided),
        (AaMode::Edges, EdgeCoverage::TwoSided),
        (AaMode::EdgesSorted, EdgeCoverage::TwoSided),
        (AaMode::Edges, EdgeCoverage::Line),
        (AaMode::EdgesSorted, EdgeCoverage::Line),
        (AaMode::Ssaa(2), EdgeCoverage::TwoSided),
        (AaMode::Ssaa(4), EdgeCoverage::TwoSided),
    ];
    println!(
        "Edge antialiasing on {device}: {}×{}, {} frames turning by {}°, reference {}×{} supersampled",
        args.width, args.height, args.frames, args.yaw_step, args.reference, args.reference
    );
    println!("msaa4: not measured (the deferred frame has no multisampled G-buffer)");
    for name in &args.meshes {
        let (mut r, scene, mesh, yaw0, pitch) = if name == "face" {
            let (prepared, mesh) = face(args.width, args.height)?;
            (prepared.renderer, prepared.scene, mesh, 35.0, 0.0)
        } else {
            let (mesh, yaw0, pitch) = mesh(name)?;
            let mut scene = Scene::studio();
            if name != "head" {
                scene.skin.subsurface = rouge_render::SubsurfaceModel::None;
            }
            let mut r = Renderer::new(&gpu.device, &gpu.queue);
            r.set_mesh(&mesh, scene.skin.albedo)?;
            r.set_look(&rouge_model::look::Look::default_look())?;
            (r, scene, mesh, yaw0, pitch)
        };
        let study = AaStudy {
            size: (args.width, args.height),
            yaws_deg: (0..args.frames).map(|i| yaw0 + args.yaw_step * i as f32).collect(),
            pitch_deg: pitch,
            reference_k: args.reference,
            modes: modes.clone(),
            timed_frames: args.timed_frames,
            gpu_classify: name != "face",
            mask: match args.mask {
                MaskArg::Edges => aa_study::Mask::NearEdges,
                MaskArg::Detail => aa_study::Mask::Detail(args.threshold),
            },
        };
        let start = std::time::Instant::now();
        r.prepare_edges(&mesh);
        let preprocess_ms = start.elapsed().as_secs_f64() * 1e3;
        let rows = aa_study::run(&mut r, &scene, &mesh, &study)?;
        let views: Vec<f32> = (0..100).map(|i| i as f32 * 3.6).collect();
        let table = aa_study::edge_table(&r, &views, pitch)?;
        let c = table.counts;
        println!(
            "\n{name}: {} faces, {} edges, {} sharp, {} boundary, {} concave/flat dropped, {} searched; \
             preprocess {preprocess_ms:.1} ms",
            c.faces, c.edges, c.sharp, c.boundary, c.concave, c.candidates
        );
        println!(
            "  over 100 viewpoints: {:.0} extracted silhouettes, {:.0} rendered, {:.0} sorted, {:.1} blended; \
             CPU search {:.0} µs brute force, {:.0} µs skipping clusters; sorted list {:.0} µs",
            table.extracted_silhouettes,
            table.rendered,
            table.sorted,
            table.blended,
            table.search_brute_us,
            table.search_skipping_us,
            table.sorted_list_us
        );
        let none = rows.iter().find(|r| r.mode == "none");
        println!(
            "  {:.0} pixels measured a frame; RMSE in linear sRGB and in levels of 255, × none's; GPU: the passes' \
             timestamps; AA cost: the GPU time it adds to none's frame (AaRow::aa_ms); wall: render and wait",
            rows.first().map_or(0.0, |r| r.pixels)
        );
        println!(
            "  {:<13} {:<10} {:>8} {:>8} {:>6} {:>7} {:>8} {:>8} {:>8} {:>8}",
            "mode", "coverage", "RMSE", "RMSE/255", "× none", "ΔE", "crawl", "wall ms", "GPU ms", "AA cost"
        );
        for row in &rows {
            let coverage = row.coverage.map_or("-".to_string(), |c| format!("{c:?}"));
            let (ratio, cost) = none.map_or((f64::NAN, f64::NAN), |n| (row.rmse_srgb8 / n.rmse_srgb8, row.aa_ms(n)));
            println!(
                "  {:<13} {:<10} {:>8.4} {:>8.2} {:>6.2} {:>7.2} {:>8.4} {:>8.2} {:>8.2} {:>8.2}",
                row.mode,
                coverage,
                row.rmse,
                row.rmse_srgb8,
                ratio,
                row.delta_e_mean,
                row.crawl,
                row.frame_ms,
                row.gpu_ms(),
                cost
            );
        }
        for row in rows.iter().filter(|r| r.mode == "none" || r.mode == "edges") {
            let passes: Vec<String> = row.pass_ms.iter().map(|(p, ms)| format!("{p} {ms:.2}")).collect();
            println!("  {} {:?} passes (GPU ms): {}", row.mode, row.coverage, passes.join(", "));
        }
        results.push(MeshResult { mesh: name.clone(), preprocess_ms, table, rows });
    }
    if let Some(path) = &args.json {
        let json = serde_json::json!({
            "device": device,
            "size": [args.width, args.height],
            "frames": args.frames,
            "yaw_step_deg": args.yaw_step,
            "reference_k": args.reference,
            "mask": format!("{:?}", args.mask),
            "threshold": args.threshold,
            "meshes": results,
        });
        crate::write_output(path, serde_json::to_string_pretty(&json)?.as_bytes())?;
    }
    if let Some(path) = &args.plot {
        let png = plot(&results, &device)?;
        crate::write_output(path, &png)?;
    }
    Ok(())
}

/// Two charts per mesh: edge RMSE and crawl against ms per frame, one marker per mode.
fn plot(results: &[MeshResult], device: &str) -> Result<Vec<u8>> {
    use crate::plot_png::{Chart, Marker, Series};
    let style = |row: &AaRow| -> (String, [u8; 3], Marker) {
        match (row.mode.as_str(), row.coverage) {
            ("none", _) => ("none".into(), [0, 0, 0], Marker::Cross),
            (m, Some(EdgeCoverage::TwoSided)) => (format!("{m} two-sided"), [214, 39, 40], Marker::Diamond),
            (m, Some(EdgeCoverage::Line)) => (format!("{m} line (paper)"), [31, 119, 180], Marker::Square),
            (m, None) => (m.to_string(), [44, 160, 44], Marker::Dot),
        }
    };
    let mut charts = Vec::new();
    for result in results {
        for (what, value) in [("edge RMSE", 0usize), ("crawl", 1)] {
            let mut series: Vec<Series> = Vec::new();
            for row in &result.rows {
                let (label, rgb, marker) = style(row);
                let y = if value == 0 { row.rmse } else { row.crawl };
                let sorted = row.mode.ends_with("sorted");
                let rgb = if sorted { rgb.map(|c| c / 2) } else { rgb };
                series.push(Series { label, rgb, points: vec![(row.frame_ms, y, None)], line: false, marker });
            }
            charts.push(Chart {
                title: format!("{}: {what}", result.mesh),
                x_label: "ms per frame".into(),
                y_label: format!("{what} against the reference"),
                series,
            });
        }
    }
    crate::plot_png::render(&format!("Edge antialiasing against supersampling, {device}"), &charts, 2)
}
