//! Antialiasing modes of a frame (`--aa none|edges|edges-sorted|msaa4|ssaa2|ssaa4`) and what
//! measures them: supersampling by a box filter (the reference, and the `ssaaN` modes), the
//! pixels near discontinuities, and the spatial and temporal errors of `rouge bench aa`.
//!
//! Edge overdraw (\[Sander2001\]) is a pass of the frame (`passes::edge_overdraw`);
//! supersampling renders k× larger and averages k×k pixels in linear light.

use crate::error::{RenderError, Result};
use rouge_measure::colorimetry::{delta_e_2000_raw, linear_srgb_to_lab, srgb_decode, srgb_encode};

/// How the overdraw pass covers a pixel next to an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum EdgeCoverage {
    /// The paper's antialiased line of width 1 (section 3.4): the drawn face is bloated by half a
    /// pixel, one side only, sharp edges blended by β′ with the double draw (section 3.3).
    Line,
    /// Exact box-filter coverage on both sides: each side's colour is drawn over the other
    /// side's pixels (the "antialiased double line" section 5 asks for, possible here because the
    /// composited image holds both sides, the background beyond a silhouette included).
    TwoSided,
}

/// The frame's edge overdraw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeAa {
    /// No overdraw pass.
    Off,
    /// Overdraw, edges unsorted (the GPU classifies every edge: brute force in the vertex stage).
    Unsorted(EdgeCoverage),
    /// Overdraw, silhouettes and near-silhouette sharp edges sorted back to front on the CPU.
    Sorted(EdgeCoverage),
}

/// An antialiasing mode of `rouge render --aa` and the app.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AaMode {
    /// Aliased.
    None,
    /// Edge overdraw, unsorted.
    Edges,
    /// Edge overdraw, sorted.
    EdgesSorted,
    /// Multisampling, 4 samples.
    Msaa4,
    /// Supersampling k×k (k = 2 or 4; the bench's reference uses more).
    Ssaa(u32),
}

impl AaMode {
    /// The mode of `rouge render` and `rouge.render` when none is asked for: two-sided edge
    /// overdraw and the hairs' coverage, about 3 % of a 1280×720 frame (docs/BENCHMARKS.md).
    pub const DEFAULT: AaMode = AaMode::Edges;

    /// The modes, as the command line names them.
    pub const ALL: [AaMode; 6] =
        [AaMode::None, AaMode::Edges, AaMode::EdgesSorted, AaMode::Msaa4, AaMode::Ssaa(2), AaMode::Ssaa(4)];

    /// The command-line name.
    pub fn name(self) -> String {
        match self {
            AaMode::None => "none".into(),
            AaMode::Edges => "edges".into(),
            AaMode::EdgesSorted => "edges-sorted".into(),
            AaMode::Msaa4 => "msaa4".into(),
            AaMode::Ssaa(k) => format!("ssaa{k}"),
        }
    }

    /// Parses a command-line name.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] listing the modes.
    pub fn parse(s: &str) -> Result<AaMode> {
        AaMode::ALL.into_iter().find(|m| m.name() == s).ok_or_else(|| {
            RenderError::Invalid(format!(
                "unknown antialiasing mode {s:?}: use one of {}",
                AaMode::ALL.map(|m| m.name()).join(", ")
            ))
        })
    }

    /// The edge overdraw of this mode with `coverage`, and the supersampling factor.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for `msaa4`: the deferred frame's G-buffer has no multisampled
    /// path (lighting per sample over 8 G-buffer layers), so it is refused rather than faked.
    pub fn frame(self, coverage: EdgeCoverage) -> Result<(EdgeAa, u32)> {
        match self {
            AaMode::None => Ok((EdgeAa::Off, 1)),
            AaMode::Edges => Ok((EdgeAa::Unsorted(coverage), 1)),
            AaMode::EdgesSorted => Ok((EdgeAa::Sorted(coverage), 1)),
            AaMode::Msaa4 => Err(RenderError::Invalid(
                "--aa msaa4: the deferred frame has no multisampled G-buffer (lighting would run per sample over \
                 8 layers); use edges, edges-sorted, ssaa2 or ssaa4"
                    .into(),
            )),
            AaMode::Ssaa(k) if (1..=16).contains(&k) => Ok((EdgeAa::Off, k)),
            AaMode::Ssaa(k) => Err(RenderError::Invalid(format!("supersampling {k}×{k}: use 1 to 16"))),
        }
    }
}

/// Linear sRGB of an sRGB-encoded RGBA8 image.
pub fn decode_srgb8(rgba: &[u8]) -> Vec<[f32; 3]> {
    rgba.chunks_exact(4).map(|p| std::array::from_fn(|c| srgb_decode(f64::from(p[c]) / 255.0) as f32)).collect()
}

/// A linear value (clamped to 0..=1) sRGB-encoded, in levels of 255, unrounded.
fn encoded_255(v: f32) -> f64 {
    srgb_encode(f64::from(v.clamp(0.0, 1.0))) * 255.0
}

/// An sRGB-encoded RGBA8 image (alpha 255) from linear sRGB.
pub fn encode_srgb8(linear: &[[f32; 3]]) -> Vec<u8> {
    linear
        .iter()
        .flat_map(|p| {
            let e = |v: f32| encoded_255(v).round() as u8;
            [e(p[0]), e(p[1]), e(p[2]), 255]
        })
        .collect()
}

/// Box-filters a linear image of `(k·w) × (k·h)` pixels to `w × h`: each output pixel the mean
/// of its k×k samples (the supersampling resolve, in linear light).
///
/// # Errors
/// [`RenderError::Invalid`] when the image is not `k·w × k·h` pixels or k is 0.
pub fn box_downsample(linear: &[[f32; 3]], (w, h): (usize, usize), k: usize) -> Result<Vec<[f32; 3]>> {
    if k == 0 || linear.len() != w * h * k * k {
        return Err(RenderError::Invalid(format!("cannot box-filter {} pixels to {w}×{h} by {k}×{k}", linear.len())));
    }
    let big_w = w * k;
    let norm = 1.0 / (k * k) as f32;
    let mut out = vec![[0.0f32; 3]; w * h];
    for (y, row) in out.chunks_exact_mut(w).enumerate() {
        for (x, px) in row.iter_mut().enumerate() {
            let mut sum = [0.0f32; 3];
            for sy in 0..k {
                for sample in &linear[(y * k + sy) * big_w + x * k..][..k] {
                    for c in 0..3 {
                        sum[c] += sample[c];
                    }
                }
            }
            *px = sum.map(|s| s * norm);
        }
    }
    Ok(out)
}

/// Marks the pixels of a `w × h` image within `radius` pixels of any of `segments` (pixel
/// coordinates, y down, pixel centres at +0.5): the pixels near a discontinuity.
pub fn mask_near_segments(segments: &[([f32; 2], [f32; 2])], (w, h): (usize, usize), radius: f32) -> Vec<bool> {
    let mut mask = vec![false; w * h];
    for &(a, b) in segments {
        let lo = [a[0].min(b[0]) - radius, a[1].min(b[1]) - radius];
        let hi = [a[0].max(b[0]) + radius, a[1].max(b[1]) + radius];
        let (x0, y0) = (lo[0].floor().max(0.0) as usize, lo[1].floor().max(0.0) as usize);
        let (x1, y1) = ((hi[0].ceil().max(0.0) as usize).min(w), (hi[1].ceil().max(0.0) as usize).min(h));
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        for y in y0..y1 {
            for x in x0..x1 {
                let p = [x as f32 + 0.5 - a[0], y as f32 + 0.5 - a[1]];
                let t = if len2 > 0.0 { ((p[0] * d[0] + p[1] * d[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let q = [p[0] - t * d[0], p[1] - t * d[1]];
                if q[0] * q[0] + q[1] * q[1] <= radius * radius {
                    mask[y * w + x] = true;
                }
            }
        }
    }
    mask
}

/// Marks the pixels where the reference differs from its own 1-pixel blur (a 3×3 box, edges
/// clamped) by more than `threshold` levels of 255 in some sRGB-encoded channel: every
/// discontinuity a viewer sees (silhouettes, the eyes' outlines, the lash line, hairs, specular
/// edges), whether or not it lies on a mesh edge. Issue 27's measure of edge antialiasing.
pub fn detail_mask(reference: &[[f32; 3]], (w, h): (usize, usize), threshold: f32) -> Vec<bool> {
    let encoded: Vec<[f32; 3]> = reference.iter().map(|p| p.map(|v| encoded_255(v) as f32)).collect();
    let at =
        |x: isize, y: isize| encoded[y.clamp(0, h as isize - 1) as usize * w + x.clamp(0, w as isize - 1) as usize];
    let mut mask = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let mut blur = [0.0f32; 3];
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let p = at(x as isize + dx, y as isize + dy);
                    (0..3).for_each(|c| blur[c] += p[c] / 9.0);
                }
            }
            let p = encoded[y * w + x];
            mask[y * w + x] = (0..3).any(|c| (p[c] - blur[c]).abs() > threshold);
        }
    }
    mask
}

/// Errors of an image against its reference on the masked pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct EdgeError {
    /// Root mean square of the linear sRGB differences (all channels).
    pub rmse: f64,
    /// The same of the sRGB-encoded values, in levels of 255 (as an 8-bit image differs).
    pub rmse_srgb8: f64,
    /// Mean CIEDE2000 (D65).
    pub delta_e_mean: f64,
    /// Pixels measured.
    pub pixels: usize,
}

/// RMSE and mean ΔE2000 of `image` against `reference` (linear sRGB) over the `mask`ed pixels.
pub fn edge_error(image: &[[f32; 3]], reference: &[[f32; 3]], mask: &[bool]) -> EdgeError {
    let (mut sq, mut sq8, mut de, mut n) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for ((a, b), &m) in image.iter().zip(reference).zip(mask) {
        if !m {
            continue;
        }
        n += 1;
        for c in 0..3 {
            sq += f64::from(a[c] - b[c]).powi(2);
            sq8 += (encoded_255(a[c]) - encoded_255(b[c])).powi(2);
        }
        let lab = |p: &[f32; 3]| linear_srgb_to_lab(p.map(f64::from));
        de += delta_e_2000_raw(lab(a), lab(b));
    }
    if n == 0 {
        return EdgeError::default();
    }
    let rms = |s: f64| (s / (3 * n) as f64).sqrt();
    EdgeError { rmse: rms(sq), rmse_srgb8: rms(sq8), delta_e_mean: de / n as f64, pixels: n }
}

/// Crawl between two consecutive frames: the RMS over the masked pixels of the difference
/// between the image's frame-to-frame change and the reference's, (I₁ − I₀) − (R₁ − R₀). A
/// jaggy that jumps a whole pixel while the reference moves smoothly scores high; an image that
/// changes as the reference does scores 0.
pub fn crawl(image: [&[[f32; 3]]; 2], reference: [&[[f32; 3]]; 2], mask: &[bool]) -> f64 {
    let (mut sq, mut n) = (0.0f64, 0usize);
    for (i, &m) in mask.iter().enumerate() {
        if !m {
            continue;
        }
        n += 1;
        for c in 0..3 {
            let di = image[1][i][c] - image[0][i][c];
            let dr = reference[1][i][c] - reference[0][i][c];
            sq += f64::from(di - dr).powi(2);
        }
    }
    if n == 0 { 0.0 } else { (sq / (3 * n) as f64).sqrt() }
}
