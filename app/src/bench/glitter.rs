//! `rouge bench glitter`: Rouge's glitter estimator against explicit flakes on a slowly turning
//! patch (rouge_render::glitter_study): the exact box filter of the flakes (the reference),
//! supersampled 16×16 (the issue's reference, which converges while a sample falls on every
//! flake), 2×2 and 4×4: flicker between frames and the sparkles per frame, each relative to the
//! reference, at a few pixel sizes. The issue's bar: the estimator flickers less than SSAA 2×2
//! and counts the reference's sparkles within 10 %.

use crate::bench::report::{emit_with_json, markdown_table};
use anyhow::{Context as _, Result, bail};
use clap::Args;
use rouge_measure::finish::Glitter;
use rouge_render::glitter_study::{GlitterRow, GlitterStudy, Method, run as run_study};
use serde::Serialize;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct GlitterBenchArgs {
    /// Pixel sizes on the patch, mm (0.083: the close-ups' 12 px/mm, flakes about a pixel;
    /// 0.3: the face at the framing distance; 1 and 3: a face 150 and 50 pixels wide, where the
    /// coarse levels' counts take over).
    #[arg(long, value_delimiter = ',', default_values_t = [0.0833f32, 0.3, 1.0, 3.0])]
    pub pixel_mm: Vec<f32>,
    /// Frames of the turntable.
    #[arg(long, default_value_t = 48)]
    pub frames: u32,
    /// Turn per frame, degrees.
    #[arg(long, default_value_t = 0.25)]
    pub step_deg: f32,
    /// Image side, pixels.
    #[arg(long, default_value_t = 128)]
    pub size: u32,
    /// Flake edge, µm.
    #[arg(long, default_value_t = 100.0)]
    pub size_um: f64,
    /// Flakes per mm².
    #[arg(long, default_value_t = 16.0)]
    pub density: f64,
    /// Flakes' RMS tilt (Beckmann roughness).
    #[arg(long, default_value_t = 0.3)]
    pub spread: f64,
    /// Also time this many frames of the eyelids' close-up (1280×720, the default head) with the
    /// glitter eyeshadow (data/finishes/eyeshadow_03_bronze_gold_glitter.json) and with the same
    /// eyeshadow without its glitter: what glitter costs on the GPU (0: skip).
    #[arg(long, default_value_t = 0)]
    pub gpu_frames: u32,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Also write each method's first frame at each pixel size into this folder (created), as
    /// 16-bit grey PNGs of the lit fraction over the exact frame's brightest pixel, with
    /// `frames.json` naming them: `python/glitter_figure.py` tiles them.
    #[arg(long)]
    pub frames_dir: Option<PathBuf>,
}

/// The methods of the frames written with `--frames-dir`, as their files name them.
const FRAME_METHODS: [(Method, &str); 4] = [
    (Method::Exact, "exact"),
    (Method::Supersampled(16), "ssaa16"),
    (Method::Supersampled(2), "ssaa2"),
    (Method::Estimator, "rouge"),
];

/// Writes the first frame of each of [`FRAME_METHODS`] (as `rows`, the study's, drew them)
/// into `dir`; returns their entries of `frames.json`.
fn write_frames(study: &GlitterStudy, rows: &[GlitterRow], dir: &std::path::Path) -> Result<Vec<serde_json::Value>> {
    let frames = FRAME_METHODS
        .iter()
        .map(|(m, slug)| {
            rows.iter()
                .find(|r| r.drawn_by == *m)
                .map(|r| r.first_frame.as_slice())
                .ok_or_else(|| anyhow::anyhow!("the study drew no {slug} frame"))
        })
        .collect::<Result<Vec<_>>>()?;
    let scale = frames[0].iter().copied().fold(0.0f32, f32::max).max(1e-12);
    let mut entries = Vec::new();
    for ((_, slug), frame) in FRAME_METHODS.iter().zip(&frames) {
        let file = format!("glitter_{}mm_{slug}.png", study.pixel_mm);
        let texels: Vec<u16> = frame.iter().map(|v| ((v / scale).clamp(0.0, 1.0) * 65535.0).round() as u16).collect();
        let image = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(study.size_px, study.size_px, texels)
            .ok_or_else(|| anyhow::anyhow!("frame of {} texels for {}²", frame.len(), study.size_px))?;
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write_to(&mut bytes, image::ImageFormat::Png)?;
        crate::write_output(&dir.join(&file), bytes.get_ref())?;
        entries.push(serde_json::json!({"pixel_mm": study.pixel_mm, "method": slug, "file": file, "scale": scale}));
    }
    Ok(entries)
}

/// The frame times of the eyelids' close-up with the bronze eyeshadow, 15 µm, with and without
/// its gold glitter.
fn gpu_cost(frames: u32) -> Result<String> {
    use rouge_model::look::Look;
    use rouge_render::job::{LookChoice, RenderJob};
    let preset_path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/finishes/eyeshadow_03_bronze_gold_glitter.json");
    let text = format!(
        r#"{{"schema": "rouge-look", "version": 1, "name": "glitter lids",
            "layers": [{{"preset": {:?}, "thickness": {{"region": "eyelids", "thickness_mm": 0.015}}}}]}}"#,
        preset_path.display().to_string()
    );
    let glitter = Look::from_json(&text, std::path::Path::new("glitter.json"))?;
    let mut plain = glitter.clone();
    if let Some(f) = plain.layers[0].preset.finish.as_mut() {
        f.glitter = None;
    }
    let mut out = format!(
        "Eyelids' close-up 1280×720, mean of {frames} frames (ms)\n| look | G-buffer | lighting | GPU sum | wall |\n|---|---:|---:|---:|---:|\n"
    );
    for (label, look) in [("bronze eyeshadow 15 µm", plain), ("the same with gold glitter", glitter)] {
        let job = RenderJob {
            look: LookChoice::Loaded(Box::new(look)),
            width: 1280,
            height: 720,
            skin_detail: true,
            close_up: Some(rouge_model::skin::AnatomyRegion::Eyelids),
            yaw_deg: 15.0,
            pitch_deg: 20.0,
            ..RenderJob::default()
        };
        let mut p = job.prepare()?;
        let t = rouge_render::study::frame_times(&mut p, frames)?;
        let pass =
            |name: &str| t.passes.iter().find(|(n, _)| n == name).map_or("n/a".into(), |(_, ms)| format!("{ms:.2}"));
        out += &format!(
            "| {label} | {} | {} | {} | {:.2} |\n",
            pass("gbuffer"),
            pass("lighting"),
            t.gpu_frame_ms.map_or("n/a".into(), |v| format!("{v:.2}")),
            t.wall_frame_ms
        );
        out = out.replace("(ms)\n", &format!("(ms), {}\n", t.adapter));
    }
    Ok(out)
}

#[derive(Debug, Serialize)]
struct Row {
    pixel_mm: f32,
    #[serde(flatten)]
    row: GlitterRow,
    passes: Option<bool>,
}

pub fn run(args: &GlitterBenchArgs) -> Result<()> {
    let glitter =
        Glitter { size_um: args.size_um, density_per_mm2: args.density, color: [1.0; 3], spread: args.spread };
    glitter.validate().map_err(anyhow::Error::msg)?;
    if args.frames < 2 || !(1..=2048).contains(&args.size) {
        bail!("--frames must be at least 2 and --size 1-2048");
    }
    if args.pixel_mm.iter().any(|p| !(p.is_finite() && *p > 0.0)) || !(args.step_deg.is_finite()) {
        bail!("--pixel-mm must be positive and --step-deg finite");
    }
    if let Some(dir) = &args.frames_dir {
        std::fs::create_dir_all(dir).with_context(|| format!("--frames-dir {}", dir.display()))?;
    }
    let mut rows = Vec::new();
    let mut frames = Vec::new();
    for &pixel_mm in &args.pixel_mm {
        let study = GlitterStudy {
            size_px: args.size,
            frames: args.frames,
            step_deg: args.step_deg,
            glitter,
            ..GlitterStudy::standard(pixel_mm)
        };
        let results = run_study(
            &study,
            &[Method::Supersampled(16), Method::Supersampled(2), Method::Supersampled(4), Method::Estimator],
        );
        if let Some(dir) = &args.frames_dir {
            frames.extend(write_frames(&study, &results, dir)?);
        }
        let ssaa2 = results.iter().find(|r| r.samples_per_pixel == 4).map(|r| r.flicker);
        for row in results {
            let passes = (row.method == Method::Estimator.name())
                .then(|| ssaa2.is_some_and(|f| row.flicker < f) && (row.sparkles_relative - 1.0).abs() < 0.1);
            rows.push(Row { pixel_mm, row, passes });
        }
    }
    let caption = format!(
        "Glitter on a turning patch ({} µm flakes, {}/mm², spread {}; {}² px, {} frames of {}°): \
         flicker = mean |frame(t+1) − frame(t)| of the lit fraction, sparkles = pixels showing over a quarter of a flake, per frame",
        args.size_um, args.density, args.spread, args.size, args.frames, args.step_deg
    );
    let header =
        ["pixel mm", "method", "samples", "flicker", "× ref", "sparkles/frame", "× ref", "RMSE", "CPU ms/frame", "bar"];
    let cells = rows.iter().map(|r| {
        vec![
            format!("{}", r.pixel_mm),
            r.row.method.clone(),
            r.row.samples_per_pixel.to_string(),
            format!("{:.5}", r.row.flicker),
            format!("{:.3}", r.row.flicker_relative),
            format!("{:.1}", r.row.sparkles_per_frame),
            format!("{:.3}", r.row.sparkles_relative),
            format!("{:.4}", r.row.rmse),
            format!("{:.1}", r.row.cpu_ms_per_frame),
            r.passes.map_or(String::new(), |p| if p { "passes".into() } else { "fails".into() }),
        ]
    });
    emit_with_json(&markdown_table(&caption, &header, 2, cells), &rows, args.json.as_deref())?;
    if let Some(dir) = &args.frames_dir {
        crate::write_output(&dir.join("frames.json"), serde_json::to_vec_pretty(&frames)?)?;
    }
    if args.gpu_frames > 0 {
        crate::emit(&gpu_cost(args.gpu_frames)?)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frames_written_are_the_studys_first_frames_scaled_by_the_exact_ones_brightest_pixel() {
        let study = GlitterStudy { size_px: 12, frames: 2, ..GlitterStudy::standard(0.0833) };
        let methods = [Method::Supersampled(16), Method::Supersampled(2), Method::Estimator];
        let rows = run_study(&study, &methods);
        let dir = tempfile::tempdir().expect("tempdir");
        let entries = write_frames(&study, &rows, dir.path()).expect("frames");
        assert_eq!(entries.len(), FRAME_METHODS.len());
        let exact = &rows[0];
        assert_eq!(exact.drawn_by, Method::Exact);
        let scale = exact.first_frame.iter().copied().fold(0.0f32, f32::max);
        assert!(scale > 0.0, "a flake lit in the exact frame");
        for ((method, slug), entry) in FRAME_METHODS.iter().zip(&entries) {
            let file = dir.path().join(entry["file"].as_str().expect("a file name"));
            let png = image::open(&file).expect("a PNG").to_luma16();
            let row = rows.iter().find(|r| r.drawn_by == *method).expect("drawn");
            for (texel, lit) in png.pixels().zip(&row.first_frame) {
                let expected = ((lit / scale).clamp(0.0, 1.0) * 65535.0).round() as u16;
                assert_eq!(texel.0[0], expected, "{slug}");
            }
        }
        // Without a method's rows there is nothing to write, and the error says which.
        let err = write_frames(&study, &rows[..1], dir.path()).expect_err("no ssaa16 row");
        assert!(err.to_string().contains("ssaa16"), "{err}");
    }
}
