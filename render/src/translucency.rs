//! `rouge bench translucency`'s measuring side: a subsurface model's frame against a Mitsuba 3
//! reference of the same scene (data/reference/translucency/, made by
//! python/render_reference.py; docs/TRANSLUCENCY.md).
//!
//! The reference holds the light that went below the surface (medium − absorber), so Rouge's
//! frame is rendered with every specular lobe off and a bare look: its skin radiance is then its
//! whole subsurface estimate. Errors are taken over pixels fully covered in the reference and
//! drawn as skin by Rouge (not the eyes, not the silhouette's partial pixels): RMSE of linear
//! radiance, and ΔE2000 of the tone-mapped (Khronos PBR Neutral, exposure 1) images, mean and
//! 95th percentile.

// RGB channels are indexed by number.
#![allow(clippy::needless_range_loop)]

use crate::error::{RenderError, Result};
use crate::job::Prepared;
use crate::study::{compare, final_image, frame_times};
use serde::Serialize;
use std::path::Path;

/// A reference image: linear RGB subsurface radiance and coverage.
#[derive(Clone, Debug)]
pub struct ReferenceImage {
    /// Width.
    pub width: usize,
    /// Height.
    pub height: usize,
    /// Linear RGB radiance per pixel, row 0 at the top.
    pub rgb: Vec<[f32; 3]>,
    /// Coverage of the object (the film's alpha).
    pub coverage: Vec<f32>,
}

impl ReferenceImage {
    /// Reads the first RGBA layer of an EXR (alpha 1 when absent).
    ///
    /// # Errors
    /// [`RenderError::File`] naming the file when it is not a readable RGB(A) EXR or holds a
    /// non-finite value (the message gives its pixel).
    pub fn load(path: &Path) -> Result<ReferenceImage> {
        use exr::prelude::*;
        let image = read_first_rgba_layer_from_file(
            path,
            |resolution, _| ReferenceImage {
                width: resolution.width(),
                height: resolution.height(),
                rgb: vec![[0.0; 3]; resolution.width() * resolution.height()],
                coverage: vec![1.0; resolution.width() * resolution.height()],
            },
            |img: &mut ReferenceImage, pos, (r, g, b, a): (f32, f32, f32, f32)| {
                let i = pos.y() * img.width + pos.x();
                img.rgb[i] = [r, g, b];
                img.coverage[i] = a;
            },
        )
        .map_err(|e| RenderError::file(path, format!("not a readable RGB(A) EXR reference: {e}")))?;
        let img = image.layer_data.channel_data.pixels;
        if let Some(i) = img.rgb.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
            return Err(RenderError::file(
                path,
                format!("pixel ({}, {}) is not finite: {:?}", i % img.width, i / img.width, img.rgb[i]),
            ));
        }
        Ok(img)
    }
}

/// How far one frame is from the reference.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ErrorFigures {
    /// RMSE of linear radiance over the compared pixels (a white Lambertian facing irradiance π
    /// is 1).
    pub rmse: f64,
    /// Mean ΔE2000 of the tone-mapped images.
    pub delta_e_mean: f64,
    /// 95th percentile ΔE2000.
    pub delta_e_p95: f64,
    /// Pixels compared.
    pub pixels: usize,
}

/// One frame's cost and error.
#[derive(Clone, Debug, Serialize)]
pub struct Measured {
    /// Sum of the passes' GPU times, ms (timestamp queries), if the adapter has them.
    pub gpu_ms: Option<f64>,
    /// Mean wall time of a frame, ms.
    pub wall_ms: f64,
    /// GPU ms per pass (timestamp queries), when the adapter has them.
    pub pass_ms: Vec<(String, f64)>,
    /// Error against the reference.
    pub error: ErrorFigures,
}

/// Renders `p`'s linear frame (the size of `reference`) and returns it with the mask of the
/// pixels compared: drawn as skin by Rouge and fully covered in the reference.
///
/// # Errors
/// The renderer's errors.
pub fn compared_pixels(p: &mut Prepared, reference: &ReferenceImage) -> Result<(Vec<[f32; 3]>, Vec<bool>)> {
    let (w, h) = p.size;
    p.renderer.render(&p.scene, &p.camera, w, h, false)?;
    let cap = p.renderer.capture()?;
    let scattered: Vec<[f32; 3]> = cap.scattered.iter().map(|v| [v[0], v[1], v[2]]).collect();
    let image = final_image(&cap, &scattered);
    let mask = (0..image.len()).map(|i| cap.diffuse[i][3] > 0.5 && reference.coverage[i] > 0.999).collect();
    Ok((image, mask))
}

/// Times `frames` frames of `p` and compares its linear frame with `reference`.
///
/// # Errors
/// A reference whose size differs from the frame's; the renderer's errors.
pub fn measure(p: &mut Prepared, reference: &ReferenceImage, frames: u32) -> Result<Measured> {
    let (w, h) = p.size;
    if (w as usize, h as usize) != (reference.width, reference.height) {
        return Err(RenderError::Invalid(format!(
            "the reference is {}×{} but the frame {w}×{h}",
            reference.width, reference.height
        )));
    }
    let times = frame_times(p, frames)?;
    let (image, mask) = compared_pixels(p, reference)?;
    let (rmse, delta_e_mean, delta_e_p95, _) = compare(&image, &reference.rgb, &mask, 1.0);
    let pixels = mask.iter().filter(|&&m| m).count();
    Ok(Measured {
        gpu_ms: times.gpu_frame_ms,
        wall_ms: times.wall_frame_ms,
        pass_ms: times.passes,
        error: ErrorFigures { rmse, delta_e_mean, delta_e_p95, pixels },
    })
}
