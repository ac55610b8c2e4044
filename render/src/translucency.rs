//! `rouge bench translucency`'s measuring side: a subsurface model's frame against a Mitsuba 3
//! reference of the same scene (data/reference/translucency/, made by
//! python/render_reference.py; docs/TRANSLUCENCY.md).
//!
//! The reference holds the light that went below the surface (medium − absorber), so Rouge's
//! frame is rendered with every specular lobe off and a bare look: its skin radiance is then its
//! whole subsurface estimate. Errors are taken over pixels fully covered in the reference and
//! drawn as skin by Rouge (not the eyes, not the silhouette's partial pixels): RMSE of linear
//! radiance, and ΔE2000 of the tone-mapped (Khronos PBR Neutral, exposure 1) images, mean and
//! 95th percentile; and the mean ΔE2000 of both images averaged over blocks of [`BIN_PX`]²
//! pixels ([`binned`]), where a reference's Monte Carlo noise weighs [`BIN_PX`] times less.

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
    /// Mean ΔE2000 of the images averaged over [`BIN_PX`]² blocks whose pixels are all compared
    /// ([`binned`]): the model's error at that scale, where the reference's noise is
    /// [`BIN_PX`] times smaller (less where its pixels' noise is correlated).
    pub delta_e_binned: f64,
}

/// The side of the blocks [`ErrorFigures::delta_e_binned`] averages over, pixels. A 2048-sample
/// wedge reference's own noise scores 3.47 ΔE per pixel against its smoothed self and 0.62 over
/// 4×4 blocks (docs/BENCHMARKS.md, "Scored over 4×4 blocks"); 4 pixels of a 256² frame are 1 mm on
/// the wedges, under the diffusion length of every committed medium's red.
pub const BIN_PX: usize = 4;

/// `image` (`width` pixels a row) averaged over `bin`² blocks, and whether each block is whole:
/// every pixel in `mask`. A partial block at the right or bottom edge is dropped.
pub fn binned(image: &[[f32; 3]], mask: &[bool], width: usize, bin: usize) -> (Vec<[f32; 3]>, Vec<bool>) {
    let height = image.len() / width.max(1);
    let (bw, bh) = (width / bin.max(1), height / bin.max(1));
    let mut out = vec![[0.0f32; 3]; bw * bh];
    let mut whole = vec![true; bw * bh];
    for y in 0..bh * bin {
        for x in 0..bw * bin {
            let (i, b) = (y * width + x, (y / bin) * bw + x / bin);
            whole[b] &= mask[i];
            for c in 0..3 {
                out[b][c] += image[i][c] / (bin * bin) as f32;
            }
        }
    }
    (out, whole)
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
    let (model_blocks, whole) = binned(&image, &mask, reference.width, BIN_PX);
    let (reference_blocks, _) = binned(&reference.rgb, &mask, reference.width, BIN_PX);
    let (_, delta_e_binned, _, _) = compare(&model_blocks, &reference_blocks, &whole, 1.0);
    Ok(Measured {
        gpu_ms: times.gpu_frame_ms,
        wall_ms: times.wall_frame_ms,
        pass_ms: times.passes,
        error: ErrorFigures { rmse, delta_e_mean, delta_e_p95, pixels, delta_e_binned },
    })
}

#[cfg(test)]
mod tests {
    use super::binned;

    #[test]
    fn binned_averages_whole_blocks_and_drops_partial_ones() {
        // 5×5 pixels, value = x + 10 y in red; 2×2 blocks: the fifth column and row are dropped.
        let (w, h) = (5, 5);
        let image: Vec<[f32; 3]> = (0..w * h).map(|i| [(i % w + 10 * (i / w)) as f32, 1.0, 0.0]).collect();
        let mut mask = vec![true; w * h];
        mask[3 * w + 2] = false; // (2, 3): block (1, 1) is not whole.
        let (blocks, whole) = binned(&image, &mask, w, 2);
        assert_eq!((blocks.len(), whole), (4, vec![true, true, true, false]));
        // Block (0, 0): pixels 0, 1, 10, 11 → 5.5; block (1, 0): 2, 3, 12, 13 → 7.5; (0, 1): 25.5.
        assert_eq!(blocks.iter().map(|b| b[0]).collect::<Vec<_>>(), vec![5.5, 7.5, 25.5, 27.5]);
        assert!(blocks.iter().all(|b| b[1] == 1.0 && b[2] == 0.0));
        // Blocks of 1 are the image itself.
        let (same, all) = binned(&image, &mask, w, 1);
        assert_eq!((same, all), (image, mask));
    }
}
