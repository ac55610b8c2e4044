//! Speed-against-error studies of the renderer (`rouge bench render`, docs/BENCHMARKS.md):
//! per-pass GPU times of a frame, the SSS sample count against a brute-force reference, and the
//! layer tables' interpolation error.

// RGB channels are indexed by number.
#![allow(clippy::needless_range_loop)]

use crate::error::Result;
use crate::job::Prepared;
use crate::renderer::FrameCapture;
use crate::sss::{SkinImage, reference_blur};
use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::layer_table::layer_spectra;
use rouge_measure::layer_table::{TABLE_ENTRIES, TABLE_X0_MM, lookup, render_table};
use rouge_measure::preset::Preset;
use serde::Serialize;
use std::time::Instant;

/// Khronos PBR Neutral tone mapping (\[KhronosNeutral\]), the composite shader's, on the CPU.
pub fn pbr_neutral(c: [f32; 3]) -> [f32; 3] {
    let (start, desat) = (0.76f32, 0.15f32);
    let x = c[0].min(c[1]).min(c[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let mut c = c.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    if peak < start {
        return c;
    }
    let d = 1.0 - start;
    let new_peak = 1.0 - d * d / (peak + d - start);
    c = c.map(|v| v * new_peak / peak);
    let g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0);
    c.map(|v| v + (new_peak - v) * g)
}

/// Mean GPU time of each pass and the whole frame.
#[derive(Clone, Debug, Serialize)]
pub struct FrameTimes {
    /// Adapter description.
    pub adapter: String,
    /// Image size.
    pub width: u32,
    /// Image size.
    pub height: u32,
    /// Cosmetic layers.
    pub layers: u32,
    /// SSS samples per direction.
    pub sss_samples: u32,
    /// Frames averaged.
    pub frames: u32,
    /// (pass, mean ms) from timestamp queries; empty when the adapter has none.
    pub passes: Vec<(String, f64)>,
    /// Sum of the pass times, ms (timestamps only).
    pub gpu_frame_ms: Option<f64>,
    /// Mean wall time from submission to completion of a frame, ms.
    pub wall_frame_ms: f64,
    /// Fastest wall time, ms.
    pub wall_frame_min_ms: f64,
}

/// Renders `frames` frames (after two warm-up frames) and averages their times.
///
/// # Errors
/// As [`crate::Renderer::render`].
pub fn frame_times(p: &mut Prepared, frames: u32) -> Result<FrameTimes> {
    let (w, h) = p.size;
    p.renderer.set_profiling(true);
    for _ in 0..2 {
        p.renderer.render(&p.scene, &p.camera, w, h, true)?;
        p.renderer.wait()?;
    }
    let mut sums: Vec<(String, f64)> = Vec::new();
    let (mut wall, mut wall_min) = (0.0f64, f64::INFINITY);
    for _ in 0..frames.max(1) {
        let t = Instant::now();
        p.renderer.render(&p.scene, &p.camera, w, h, true)?;
        p.renderer.wait()?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        wall += ms;
        wall_min = wall_min.min(ms);
        // By name: a pass that runs in some frames only (a shadow map kept) counts in those.
        for t in p.renderer.timings() {
            match sums.iter_mut().find(|(name, _)| *name == t.pass) {
                Some(sum) => sum.1 += t.ms,
                None => sums.push((t.pass.clone(), t.ms)),
            }
        }
    }
    let n = frames.max(1) as f64;
    let passes: Vec<(String, f64)> = sums.into_iter().map(|(k, v)| (k, v / n)).collect();
    let gpu_frame_ms = (!passes.is_empty()).then(|| passes.iter().map(|(_, v)| v).sum());
    p.renderer.set_profiling(false);
    Ok(FrameTimes {
        adapter: p.gpu.describe(),
        width: w,
        height: h,
        layers: p.renderer.layer_count(),
        sss_samples: p.scene.sss.samples,
        frames: frames.max(1),
        passes,
        gpu_frame_ms,
        wall_frame_ms: wall / n,
        wall_frame_min_ms: wall_min,
    })
}

/// One row of the SSS study.
#[derive(Clone, Debug, Serialize)]
pub struct SssRow {
    /// Samples per direction.
    pub samples: u32,
    /// GPU time of the two blur passes, ms (timestamps), if available.
    pub sss_ms: Option<f64>,
    /// Wall time of the whole frame, ms.
    pub frame_ms: f64,
    /// RMSE of the final linear radiance over skin pixels (same units as the image: a white
    /// Lambertian facing a light of irradiance π is 1).
    pub rmse: f64,
    /// Mean ΔE2000 over skin pixels of the displayed (tone-mapped) image.
    pub mean_de: f64,
    /// 95th percentile ΔE2000.
    pub p95_de: f64,
    /// Largest ΔE2000.
    pub max_de: f64,
}

/// The SSS study: result and reference.
#[derive(Clone, Debug, Serialize)]
pub struct SssStudy {
    /// Image size.
    pub width: u32,
    /// Image size.
    pub height: u32,
    /// Skin pixels compared.
    pub skin_pixels: usize,
    /// Seconds the CPU reference took.
    pub reference_seconds: f64,
    /// No scattering at all against the reference (what SSS buys).
    pub no_sss: SssRow,
    /// One row per sample count.
    pub rows: Vec<SssRow>,
}

pub(crate) fn final_image(cap: &FrameCapture, scattered: &[[f32; 3]]) -> Vec<[f32; 3]> {
    (0..cap.width * cap.height)
        .map(|i| std::array::from_fn(|c| scattered[i][c] * cap.exit_t[i][c] + cap.surface[i][c]))
        .collect()
}

pub(crate) fn compare(a: &[[f32; 3]], b: &[[f32; 3]], skin: &[bool], exposure: f32) -> (f64, f64, f64, f64) {
    let mut sq = 0.0f64;
    let mut des = Vec::new();
    for i in 0..a.len() {
        if !skin[i] {
            continue;
        }
        for c in 0..3 {
            sq += ((a[i][c] - b[i][c]) as f64).powi(2);
        }
        let lab = |p: [f32; 3]| {
            let t = pbr_neutral(p.map(|v| (v * exposure).max(0.0)));
            // Display-referred: the 8-bit target clamps to [0, 1]; ΔE on what the viewer sees.
            linear_srgb_to_lab(t.map(|v| v.clamp(0.0, 1.0) as f64))
        };
        des.push(delta_e_2000_raw(lab(a[i]), lab(b[i])));
    }
    des.sort_by(f64::total_cmp);
    let n = des.len().max(1);
    let rmse = (sq / (3 * n) as f64).sqrt();
    let mean = des.iter().sum::<f64>() / n as f64;
    let p95 = des.get(des.len() * 95 / 100).copied().unwrap_or(0.0);
    let max = des.last().copied().unwrap_or(0.0);
    (rmse, mean, p95, max)
}

/// Renders the frame once per sample count and compares each with the brute-force reference
/// (the exact profile over its full support, on the CPU, from the same skin radiance).
///
/// # Errors
/// As [`crate::Renderer::render`].
pub fn sss_study(p: &mut Prepared, sample_counts: &[u32], progress: &mut dyn FnMut(&str)) -> Result<SssStudy> {
    let (w, h) = p.size;
    let saved = p.scene.sss;
    let profile =
        p.scene.skin.subsurface.profile().cloned().ok_or_else(|| {
            crate::RenderError::Invalid("the SSS study needs the screen-space subsurface model".into())
        })?;
    p.renderer.render(&p.scene, &p.camera, w, h, false)?;
    let cap = p.renderer.capture()?;
    let rgb: Vec<[f32; 3]> = cap.diffuse.iter().map(|v| [v[0], v[1], v[2]]).collect();
    let skin: Vec<bool> = cap.diffuse.iter().map(|v| v[3] > 0.5).collect();
    let img = SkinImage {
        width: cap.width,
        height: cap.height,
        rgb: &rgb,
        skin: &skin,
        depth_mm: &cap.depth_mm,
        focal_px: cap.focal_px,
    };
    progress("brute-force reference on the CPU");
    let t = Instant::now();
    let reference = reference_blur(&img, &profile, saved.width, saved.follow_mm);
    let reference_seconds = t.elapsed().as_secs_f64();
    let ref_final = final_image(&cap, &reference);
    let exposure = p.scene.exposure;
    let row = |samples, sss_ms, frame_ms, img: &[[f32; 3]]| {
        let (rmse, mean_de, p95_de, max_de) = compare(&final_image(&cap, img), &ref_final, &skin, exposure);
        SssRow { samples, sss_ms, frame_ms, rmse, mean_de, p95_de, max_de }
    };
    let no_sss = row(0, None, 0.0, &rgb);
    let mut rows = Vec::new();
    p.renderer.set_profiling(true);
    for &n in sample_counts {
        progress(&format!("{n} samples"));
        p.scene.sss.samples = n;
        // Warm-up (pipeline and kernel upload), then a timed frame.
        p.renderer.render(&p.scene, &p.camera, w, h, false)?;
        p.renderer.wait()?;
        let t = Instant::now();
        p.renderer.render(&p.scene, &p.camera, w, h, false)?;
        p.renderer.wait()?;
        let frame_ms = t.elapsed().as_secs_f64() * 1e3;
        let timings = p.renderer.timings();
        let sss_ms = (!timings.is_empty())
            .then(|| timings.iter().filter(|t| t.pass.starts_with("sss")).map(|t| t.ms).sum::<f64>());
        let c = p.renderer.capture()?;
        let scattered: Vec<[f32; 3]> = c.scattered.iter().map(|v| [v[0], v[1], v[2]]).collect();
        rows.push(row(n, sss_ms, frame_ms, &scattered));
    }
    p.renderer.set_profiling(false);
    p.scene.sss = saved;
    Ok(SssStudy {
        width: w,
        height: h,
        skin_pixels: skin.iter().filter(|&&s| s).count(),
        reference_seconds,
        no_sss,
        rows,
    })
}

/// Interpolation error of the layer tables against exact spectral R0 and T.
#[derive(Clone, Debug, Serialize)]
pub struct TableStudy {
    /// Entries per row.
    pub entries: usize,
    /// X0 of the parameterisation, mm.
    pub x0_mm: f64,
    /// Thicknesses tested per preset.
    pub thicknesses: usize,
    /// Mean ΔE2000 of R0 (over black) between table lookup and exact linear RGB.
    pub mean_de_r0: f64,
    /// Largest ΔE2000 of R0.
    pub max_de_r0: f64,
    /// Largest absolute error of T (linear RGB).
    pub max_abs_t: f64,
}

/// Compares table lookups with exact values at thicknesses between table entries, log-spaced
/// from 0.1 µm to 2 mm, for every preset.
pub fn table_study(presets: &[Preset]) -> TableStudy {
    let c = Colorimeter::get(Viewing::D65_1931);
    let xs: Vec<f64> = (0..200).map(|i| 1e-4 * (2e4f64).powf(i as f64 / 199.0)).collect();
    let (mut sum, mut n, mut max_de, mut max_t) = (0.0, 0usize, 0.0f64, 0.0f64);
    for preset in presets {
        let table = render_table(preset);
        let (r_row, t_row) = (table.r0, table.t);
        let (s, k) = (preset.s(), preset.k());
        for &x in &xs {
            let (rs, ts) = layer_spectra(&s, &k, x);
            let exact_r = c.srgb_linear(&c.xyz(&rs));
            let exact_t = c.srgb_linear(&c.xyz(&ts));
            let r = lookup(&r_row, x as f32).map(f64::from);
            let t = lookup(&t_row, x as f32).map(f64::from);
            let de = delta_e_2000_raw(linear_srgb_to_lab(r), linear_srgb_to_lab(exact_r));
            sum += de;
            n += 1;
            max_de = max_de.max(de);
            for ch in 0..3 {
                max_t = max_t.max((t[ch] - exact_t[ch]).abs());
            }
        }
    }
    TableStudy {
        entries: TABLE_ENTRIES,
        x0_mm: TABLE_X0_MM,
        thicknesses: xs.len(),
        mean_de_r0: sum / n.max(1) as f64,
        max_de_r0: max_de,
        max_abs_t: max_t,
    }
}

/// Brush dab to updated frame, end to end.
#[derive(Clone, Debug, Serialize)]
pub struct DabTimes {
    /// Adapter description.
    pub adapter: String,
    /// Frame size.
    pub width: u32,
    /// Frame size.
    pub height: u32,
    /// Thickness map size (square).
    pub map_size: u32,
    /// Brush radius, mm.
    pub radius_mm: f32,
    /// Dabs timed.
    pub dabs: usize,
    /// Building the surface map of the mesh (once per mesh), ms.
    pub surface_build_ms: f64,
    /// CPU time to apply one dab to the map, ms (mean).
    pub dab_cpu_ms: f64,
    /// Uploading the changed rectangle, ms (mean; the GPU copy itself runs with the frame).
    pub upload_ms: f64,
    /// Rendering and waiting for the frame, ms (mean).
    pub frame_ms: f64,
    /// Dab to finished frame, ms (mean).
    pub total_ms: f64,
    /// Slowest dab to frame, ms.
    pub total_max_ms: f64,
}

/// Paints `dabs` dabs along a line across the face's right cheek of the default head on the
/// default project's foundation layer (2048² maps) and times each from dab to finished frame.
///
/// # Errors
/// As [`crate::Renderer::render`].
pub fn dab_to_frame(p: &mut Prepared, mesh: &rouge_model::mesh::TriangleMesh, dabs: usize) -> Result<DabTimes> {
    use crate::renderer::LayerInput;
    use rouge_model::document::{Document, MAP_SIZE};
    use rouge_model::paint::{Brush, SurfaceMap, apply_dab};
    let (w, h) = p.size;
    let t = Instant::now();
    let surface = SurfaceMap::build(mesh, MAP_SIZE, MAP_SIZE);
    let surface_build_ms = t.elapsed().as_secs_f64() * 1e3;
    let mut doc = Document::default_project();
    {
        let inputs: Vec<LayerInput<'_>> = doc
            .layers
            .iter()
            .map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: l.multiplier })
            .collect();
        p.renderer.set_layers(&inputs)?;
    }
    p.renderer.render(&p.scene, &p.camera, w, h, true)?;
    p.renderer.wait()?;
    let brush = Brush { mirror: false, ..Brush::default() };
    // Centres: pick the frame at points across the right cheek (image left of centre).
    let mut centres = Vec::new();
    for i in 0..dabs {
        let f = i as f32 / dabs.max(1) as f32;
        let (x, y) = ((w as f32 * (0.42 + 0.05 * f)) as u32, (h as f32 * (0.58 + 0.04 * f)) as u32);
        if let Some(c) = p.renderer.pick(x, y)? {
            centres.push(c);
        }
    }
    let (mut cpu, mut up, mut frame, mut total, mut worst) = (0.0, 0.0, 0.0, 0.0, 0.0f64);
    let _ = doc.begin_stroke(0);
    for &c in &centres {
        let t0 = Instant::now();
        let rect = match doc.stroke_map(0) {
            Some(map) => apply_dab(map, &surface, &brush, c),
            None => break,
        };
        let t1 = Instant::now();
        let layer = &doc.layers[0];
        p.renderer.update_thickness(0, &layer.map, layer.multiplier, rect)?;
        let t2 = Instant::now();
        p.renderer.render(&p.scene, &p.camera, w, h, true)?;
        p.renderer.wait()?;
        let t3 = Instant::now();
        cpu += (t1 - t0).as_secs_f64() * 1e3;
        up += (t2 - t1).as_secs_f64() * 1e3;
        frame += (t3 - t2).as_secs_f64() * 1e3;
        let all = (t3 - t0).as_secs_f64() * 1e3;
        total += all;
        worst = worst.max(all);
    }
    let n = centres.len().max(1) as f64;
    Ok(DabTimes {
        adapter: p.gpu.describe(),
        width: w,
        height: h,
        map_size: MAP_SIZE,
        radius_mm: brush.radius_mm,
        dabs: centres.len(),
        surface_build_ms,
        dab_cpu_ms: cpu / n,
        upload_ms: up / n,
        frame_ms: frame / n,
        total_ms: total / n,
        total_max_ms: worst,
    })
}
