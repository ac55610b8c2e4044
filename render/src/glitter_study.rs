//! `rouge bench glitter`'s measuring side: a flat patch of glitter ([`crate::glitter`]'s flake
//! field) turning slowly on a turntable under one light, seen by an orthographic camera, drawn
//! several ways on the CPU:
//! - the **reference**: the explicit flakes, each lit flake's square intersected with the
//!   pixel's footprint exactly (the box filter every supersampled render converges to);
//! - **SSAA k×k** of the same explicit flakes (k = 16: the reference, which converges
//!   while a sample falls on every flake, pixels up to 16 flake edges; k = 2, 4: what
//!   supersampling buys at 4 and 16 samples);
//! - **Rouge's estimator** ([`crate::glitter::pixel_sparkle`], the shader's CPU twin), one
//!   evaluation per pixel from the UVs' footprint.
//!
//! Each frame is the lit fraction of each pixel (what multiplies the light's radiance × the
//! flakes' colour), so the figures are independent of the light's strength. Per method:
//! **flicker**, the mean over pixels and consecutive frames of |frame(t+1) − frame(t)|, and the
//! **sparkle count**, the pixels that show more than a quarter of a flake per frame, each also
//! relative to the
//! reference's; and the RMSE against the reference frame by frame.
//!
//! Geometry: the patch lies in the plane through the origin whose normal is turned `φ` about
//! the vertical axis from the camera's axis; the camera looks down −z, so a pixel at (X, Y) mm
//! sees the patch at u = X / cos φ, v = Y (plus an offset, so that the image does not start on
//! a cell corner), and the footprint is exactly a UV box of pixel/cos φ × pixel.

use crate::glitter::{FlakeField, footprint_half_mm, pixel_sparkle};
use glam::{Vec2, Vec3};
use rouge_measure::finish::Glitter;
use std::time::Instant;

/// What to measure.
#[derive(Clone, Debug)]
pub struct GlitterStudy {
    /// Image side, pixels.
    pub size_px: u32,
    /// Pixel side on the camera's image plane, mm.
    pub pixel_mm: f32,
    /// Frames of the turntable.
    pub frames: u32,
    /// Turn of the patch at the first frame, degrees.
    pub start_deg: f32,
    /// Turn per frame, degrees.
    pub step_deg: f32,
    /// The glitter.
    pub glitter: Glitter,
    /// Direction toward the light, world (normalised when used).
    pub light: Vec3,
    /// A pixel sparkles when it shows more than this part of one flake (its lit fraction exceeds
    /// this × min(1, flake area / pixel footprint): the count means the same at every distance).
    pub threshold: f32,
    /// The reference the others are measured against.
    pub reference: Method,
    /// Samples per pixel side of the supersampled rival.
    pub ssaa_k: u32,
}

impl GlitterStudy {
    /// The study of the docs' figures: 128² pixels, 48 frames of 0.25° from 20°, 100 µm flakes
    /// at 16 per mm², spread 0.3, a light 5° across seen near the mirror direction.
    pub fn standard(pixel_mm: f32) -> GlitterStudy {
        GlitterStudy {
            size_px: 128,
            pixel_mm,
            frames: 48,
            start_deg: 20.0,
            step_deg: 0.25,
            glitter: Glitter { size_um: 100.0, density_per_mm2: 16.0, color: [1.0; 3], spread: 0.3 },
            light: Vec3::new(0.68, 0.15, 0.71),
            threshold: 0.25,
            reference: Method::Exact,
            ssaa_k: 2,
        }
    }
}

/// A way to draw a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Explicit flakes, the lit area of each inside the footprint, exactly.
    Exact,
    /// Explicit flakes, k×k point samples per pixel.
    Supersampled(u32),
    /// [`pixel_sparkle`] once per pixel.
    Estimator,
}

impl Method {
    /// The method's name in tables.
    pub fn name(self) -> String {
        match self {
            Method::Exact => "explicit, exact area".into(),
            Method::Supersampled(k) => format!("explicit {k}×{k}"),
            Method::Estimator => "rouge estimator".into(),
        }
    }
}

/// UV offset of the image's centre, mm.
const UV_OFFSET_MM: Vec2 = Vec2::new(37.31, 11.87);

/// Frame `t` of the turntable drawn by `method`: the lit fraction per pixel, row-major.
pub fn frame(study: &GlitterStudy, method: Method, t: u32) -> Vec<f32> {
    let field = FlakeField::new(&study.glitter, 1);
    let phi = (study.start_deg + t as f32 * study.step_deg).to_radians();
    let (s, c) = phi.sin_cos();
    let (u_axis, normal) = (Vec3::new(c, 0.0, -s), Vec3::new(s, 0.0, c));
    let l = study.light.normalize();
    let l_t = Vec3::new(l.dot(u_axis), l.y, l.dot(normal));
    let v_t = Vec3::new(-s, 0.0, c);
    let h = (l_t + v_t).normalize();
    let n = study.size_px;
    let uv_at = |x: f32, y: f32| {
        let (px, py) = ((x - 0.5 * n as f32) * study.pixel_mm, (0.5 * n as f32 - y) * study.pixel_mm);
        Vec2::new(px / c, py) + UV_OFFSET_MM
    };
    let half = footprint_half_mm(Vec2::new(study.pixel_mm / c, 0.0), Vec2::new(0.0, -study.pixel_mm));
    let pixel = |x: u32, y: u32| -> f32 {
        match method {
            Method::Estimator => pixel_sparkle(&field, uv_at(x as f32 + 0.5, y as f32 + 0.5), half, h),
            Method::Exact => field.lit_area(uv_at(x as f32 + 0.5, y as f32 + 0.5), half, h) / (4.0 * half.x * half.y),
            Method::Supersampled(k) => {
                let mut lit = 0u32;
                for j in 0..k {
                    for i in 0..k {
                        let (sx, sy) = ((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                        lit += u32::from(field.point_sparkle(uv_at(x as f32 + sx, y as f32 + sy), h));
                    }
                }
                lit as f32 / (k * k) as f32
            }
        }
    };
    let rows: Vec<Vec<f32>> = std::thread::scope(|scope| {
        let threads = std::thread::available_parallelism().map_or(2, |p| p.get()).min(16) as u32;
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let pixel = &pixel;
                scope.spawn(move || {
                    (k..n).step_by(threads as usize).map(|y| (0..n).map(|x| pixel(x, y)).collect()).collect::<Vec<_>>()
                })
            })
            .collect();
        let parts: Vec<Vec<Vec<f32>>> = handles.into_iter().map(|h| h.join().unwrap_or_default()).collect();
        (0..n).map(|y| parts[(y % threads) as usize].get((y / threads) as usize).cloned().unwrap_or_default()).collect()
    });
    rows.concat()
}

/// One method's figures over the turntable.
#[derive(Clone, Debug, serde::Serialize)]
pub struct GlitterRow {
    /// The method.
    pub method: String,
    /// Point samples (or estimator evaluations) per pixel.
    pub samples_per_pixel: u32,
    /// Mean |frame(t+1) − frame(t)| over pixels and frames (lit fraction).
    pub flicker: f64,
    /// `flicker` over the reference's.
    pub flicker_relative: f64,
    /// Mean pixels above the threshold per frame.
    pub sparkles_per_frame: f64,
    /// `sparkles_per_frame` over the reference's.
    pub sparkles_relative: f64,
    /// RMSE of the lit fraction against the reference, over pixels and frames.
    pub rmse: f64,
    /// CPU milliseconds per frame (all threads; the estimator as the shader's twin, not the
    /// shader).
    pub cpu_ms_per_frame: f64,
    /// The method drawn.
    #[serde(skip)]
    pub drawn_by: Method,
    /// Its first frame ([`frame`] at `t` = 0), for figures.
    #[serde(skip)]
    pub first_frame: Vec<f32>,
}

/// The lit fraction above which a pixel of `study` sparkles (at its first frame's footprint).
pub fn sparkle_threshold(study: &GlitterStudy) -> f32 {
    let footprint_mm2 = study.pixel_mm * study.pixel_mm / study.start_deg.to_radians().cos();
    let flake_mm2 = (study.glitter.size_um as f32 * 1e-3).powi(2);
    study.threshold * (flake_mm2 / footprint_mm2).min(1.0)
}

/// The figures of `methods` (the first row is the reference, `study.reference`).
pub fn run(study: &GlitterStudy, methods: &[Method]) -> Vec<GlitterRow> {
    let threshold = sparkle_threshold(study);
    let reference_method = study.reference;
    let mut all = vec![reference_method];
    all.extend(methods.iter().copied().filter(|m| *m != reference_method));
    let mut frames_of = Vec::new();
    let mut times = Vec::new();
    for &m in &all {
        let start = Instant::now();
        frames_of.push((0..study.frames).map(|t| frame(study, m, t)).collect::<Vec<_>>());
        times.push(start.elapsed().as_secs_f64() * 1e3 / study.frames.max(1) as f64);
    }
    let stats = |frames: &Vec<Vec<f32>>| {
        let pairs = frames.windows(2);
        let count = pairs.len().max(1) * frames[0].len().max(1);
        let flicker: f64 =
            frames.windows(2).flat_map(|w| w[0].iter().zip(&w[1]).map(|(a, b)| (a - b).abs() as f64)).sum::<f64>()
                / count as f64;
        let sparkles = frames.iter().map(|f| f.iter().filter(|v| **v > threshold).count() as f64).sum::<f64>()
            / frames.len().max(1) as f64;
        (flicker, sparkles)
    };
    let (ref_flicker, ref_sparkles) = stats(&frames_of[0]);
    all.iter()
        .zip(&frames_of)
        .zip(&times)
        .map(|((m, frames), ms)| {
            let (flicker, sparkles) = stats(frames);
            let mut se = 0.0;
            let mut n = 0usize;
            for (f, r) in frames.iter().zip(&frames_of[0]) {
                for (a, b) in f.iter().zip(r) {
                    se += ((a - b) as f64).powi(2);
                    n += 1;
                }
            }
            GlitterRow {
                method: m.name(),
                samples_per_pixel: match m {
                    Method::Supersampled(k) => k * k,
                    Method::Estimator | Method::Exact => 1,
                },
                flicker,
                flicker_relative: flicker / ref_flicker.max(1e-12),
                sparkles_per_frame: sparkles,
                sparkles_relative: sparkles / ref_sparkles.max(1e-12),
                rmse: (se / n.max(1) as f64).sqrt(),
                cpu_ms_per_frame: *ms,
                drawn_by: *m,
                first_frame: frames.first().cloned().unwrap_or_default(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimator_flickers_less_than_ssaa_2x2_and_counts_the_sparkles() {
        // Small, short turntables (the bench's are 128² × 48 frames): the close-up, where the
        // flakes are about a pixel, and 1 and 3 mm a pixel, where the coarse levels' counts
        // take over (spread over their cells, the counts lit 1.6 times the pixels at 1 mm; with
        // one draw per cell, they flickered a quarter as much as the flakes).
        for (pixel_mm, size_px) in [(0.0833, 48), (1.0, 32), (3.0, 24)] {
            let study = GlitterStudy { size_px, frames: 8, ..GlitterStudy::standard(pixel_mm) };
            let rows = run(&study, &[Method::Supersampled(2), Method::Estimator]);
            let (reference, ssaa, estimator) = (&rows[0], &rows[1], &rows[2]);
            assert!(reference.sparkles_per_frame > 5.0, "{pixel_mm} mm: {reference:?}");
            assert!(estimator.flicker < ssaa.flicker, "{pixel_mm} mm: {estimator:?} against {ssaa:?}");
            assert!(estimator.flicker > 0.5 * reference.flicker, "{pixel_mm} mm: {estimator:?}");
            assert!((estimator.sparkles_relative - 1.0).abs() < 0.1, "{pixel_mm} mm: {estimator:?}");
            assert!(estimator.rmse < ssaa.rmse, "{pixel_mm} mm: {estimator:?} against {ssaa:?}");
        }
    }

    #[test]
    fn sixteen_samples_a_side_converge_to_the_exact_area_only_on_flakes_a_sample_apart() {
        // The 16×16 reference against the exact box filter: within a few percent at
        // 1 mm a pixel (a sample every 62 µm on 100 µm flakes), a quarter of the sparkles
        // missed at 4 mm (a sample every 250 µm).
        let count = |pixel_mm: f32| {
            let study = GlitterStudy { size_px: 16, frames: 2, ..GlitterStudy::standard(pixel_mm) };
            run(&study, &[Method::Supersampled(16)])[1].sparkles_relative
        };
        assert!((count(1.0) - 1.0).abs() < 0.1, "{}", count(1.0));
        assert!(count(4.0) < 0.8, "{}", count(4.0));
    }
}
