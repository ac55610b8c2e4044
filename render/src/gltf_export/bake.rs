//! The look baked into the mesh's UV space: per texel, what the surface shows under white light
//! with no subsurface scattering, as the renderer's lighting pass composes it
//! (render/src/shaders/lighting.wgsl), for exports that carry a look as textures.
//!
//! [`bake_surface`] evaluates, at every texel centre, the same inputs the G-buffer pass samples
//! there (each layer's thickness map × multiplier, the skin's albedo texture or colour) and the
//! same functions the lighting pass runs on them, from their CPU homes:
//! - the diffuse colour: each covering layer's R0 and T from its render table
//!   ([`rouge_measure::layer_table::lookup`]), composed over the skin in the compositing basis
//!   ([`CompositingBasis::reflectance_over_skin`]);
//! - one specular lobe standing for the lighting pass's stack of lobes (the skin's, then each
//!   layer's × its coverage, the lobes below attenuated by T² of the layers above): its F0 is
//!   the sum of the lobes' F0 so weighted, its Beckmann roughness their F0-weighted mean. Where
//!   no layer covers, exactly the skin's lobe; under an opaque layer, exactly the layer's.
//!
//! [`SurfaceMaps`] holds the result as planes of floats; the glTF writer encodes them
//! (`document.rs`). A later part of the surface (a finish's clearcoat or sheen, hair's maps)
//! adds its plane to [`SurfaceMaps`], its value to [`TexelSurface`] and its glTF slot to the
//! writer: the texel loop and the inputs stay as they are.

use crate::error::{RenderError, Result};
use crate::gpu_look::LAYER_FULL_COVERAGE_MM;
use crate::renderer::LayerInput;
use crate::scene::fresnel_f0;
use rouge_measure::colorimetry::srgb_decode;
use rouge_measure::compositing::CompositingBasis;
use rouge_measure::layer_table::{RenderTable, lookup, render_table};
use rouge_model::look::ThicknessMap;

/// Smallest and largest texture side a bake makes, texels.
pub const TEXTURE_PX_RANGE: std::ops::RangeInclusive<u32> = 16..=8192;

/// Rec. 709 luminance weights of linear sRGB: how a coloured transmittance scales a scalar lobe.
const LUMINANCE: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// The skin under the look.
#[derive(Clone, Copy, Debug)]
pub struct SkinSurface<'a> {
    /// The skin's diffuse albedo, linear sRGB, where there is no albedo map.
    pub albedo: [f32; 3],
    /// The skin's albedo texture (RGBA8, sRGB-encoded, row 0 at v = 1, the mesh's UV space), as
    /// the renderer's albedo map (skin maps baked, or `--albedo-map`); replaces `albedo`.
    pub albedo_map: Option<&'a image::RgbaImage>,
    /// Beckmann roughness (RMS slope) of the skin's specular lobe.
    pub beckmann_roughness: f32,
    /// Index of refraction of the skin's surface (Schlick's F0 from it).
    pub ior: f32,
}

/// What one texel of the surface is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelSurface {
    /// Diffuse reflectance under white light, no subsurface scattering, linear sRGB.
    pub base_color: [f32; 3],
    /// Beckmann roughness of the one lobe standing for the stack's lobes.
    pub beckmann_roughness: f32,
    /// Normal-incidence Fresnel reflectance of that lobe.
    pub f0: f32,
}

/// The baked surface: planes of `side_px`² texels, row 0 at v = 1 (like every texture of the
/// mesh's UV space, and like glTF images, whose row 0 is glTF's v = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceMaps {
    /// Side of every plane, texels.
    pub side_px: u32,
    /// [`TexelSurface::base_color`] per texel.
    pub base_color: Vec<[f32; 3]>,
    /// [`TexelSurface::beckmann_roughness`] per texel.
    pub beckmann_roughness: Vec<f32>,
    /// [`TexelSurface::f0`] per texel.
    pub f0: Vec<f32>,
}

impl SurfaceMaps {
    /// The texel at OBJ-convention UV (u right, v up), nearest texel, clamped.
    pub fn texel_at_uv(&self, u: f32, v: f32) -> TexelSurface {
        let n = self.side_px;
        let x = ((u * n as f32) as i64).clamp(0, i64::from(n) - 1) as usize;
        let y = (((1.0 - v) * n as f32) as i64).clamp(0, i64::from(n) - 1) as usize;
        let i = y * n as usize + x;
        TexelSurface { base_color: self.base_color[i], beckmann_roughness: self.beckmann_roughness[i], f0: self.f0[i] }
    }
}

/// The part of a texel a layer `mm` thick covers, as the lighting pass weighs its lobe
/// (full from `LAYER_FULL_COVERAGE_MM`, 2 µm).
pub fn layer_coverage(mm: f32) -> f32 {
    (mm / LAYER_FULL_COVERAGE_MM).clamp(0.0, 1.0)
}

/// Refuses a texture side outside [`TEXTURE_PX_RANGE`].
///
/// # Errors
/// [`RenderError::Invalid`] naming the size and the range.
pub fn check_texture_px(side_px: u32) -> Result<()> {
    if TEXTURE_PX_RANGE.contains(&side_px) {
        return Ok(());
    }
    Err(RenderError::Invalid(format!(
        "texture size {side_px}: must be {} to {} texels",
        TEXTURE_PX_RANGE.start(),
        TEXTURE_PX_RANGE.end()
    )))
}

/// One layer, ready for the texel loop.
struct BakeLayer {
    table: RenderTable,
    /// Thickness × multiplier at the bake's texels, mm.
    mm: Vec<f32>,
    beckmann_roughness: f32,
    f0: f32,
}

/// An sRGB texture decoded to linear values, sampled bilinearly between texel centres with
/// clamp-to-edge: what the renderer's sampler returns from its sRGB albedo texture.
struct LinearTexture {
    width: u32,
    height: u32,
    texels: Vec<[f32; 3]>,
}

impl LinearTexture {
    fn new(img: &image::RgbaImage) -> LinearTexture {
        let lut: Vec<f32> = (0..256).map(|v| srgb_decode(f64::from(v) / 255.0) as f32).collect();
        let texels = img.pixels().map(|p| [lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]]).collect();
        LinearTexture { width: img.width(), height: img.height(), texels }
    }

    /// Bilinear at continuous texel coordinates (texel (x, y)'s centre at (x + 0.5, y + 0.5)).
    fn sample_px(&self, px: f32, py: f32) -> [f32; 3] {
        let (x, y) = (px - 0.5, py - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let clamp = |i: f32, n: u32| (i as i64).clamp(0, i64::from(n) - 1) as usize;
        let (xa, xb) = (clamp(x0, self.width), clamp(x0 + 1.0, self.width));
        let (ya, yb) = (clamp(y0, self.height), clamp(y0 + 1.0, self.height));
        let at = |x: usize, y: usize| self.texels[y * self.width as usize + x];
        let lerp = |a: [f32; 3], b: [f32; 3], t: f32| std::array::from_fn(|c| a[c] + (b[c] - a[c]) * t);
        lerp(lerp(at(xa, ya), at(xb, ya), fx), lerp(at(xa, yb), at(xb, yb), fx), fy)
    }
}

/// Bakes `layers` (bottom to top, as [`crate::Renderer::set_layers`] takes them) over `skin`
/// into [`SurfaceMaps`] of `side_px`² texels: see the module documentation. Rows are shared over
/// the machine's cores.
///
/// # Errors
/// [`RenderError::Invalid`] for a side outside [`TEXTURE_PX_RANGE`], an empty albedo map, a
/// negative or non-finite multiplier, or a non-finite skin.
pub fn bake_surface(skin: &SkinSurface<'_>, layers: &[LayerInput<'_>], side_px: u32) -> Result<SurfaceMaps> {
    check_texture_px(side_px)?;
    if layers.iter().any(|l| !(l.multiplier.is_finite() && l.multiplier >= 0.0)) {
        return Err(RenderError::Invalid("layer thickness multipliers must be finite and ≥ 0".into()));
    }
    let finite = skin.albedo.iter().all(|v| v.is_finite());
    if !(finite && skin.beckmann_roughness.is_finite() && skin.beckmann_roughness > 0.0 && skin.ior.is_finite()) {
        return Err(RenderError::Invalid(format!(
            "skin albedo {:?}, roughness {}, IOR {}: must be finite, roughness above 0",
            skin.albedo, skin.beckmann_roughness, skin.ior
        )));
    }
    let albedo_map = match skin.albedo_map {
        Some(img) if img.width() == 0 || img.height() == 0 => {
            return Err(RenderError::Invalid("skin albedo map: empty image".into()));
        }
        Some(img) => Some(LinearTexture::new(img)),
        None => None,
    };
    let n = side_px as usize;
    let baked: Vec<BakeLayer> = layers
        .iter()
        .map(|l| {
            let map: ThicknessMap = l.map.resized(side_px, side_px);
            BakeLayer {
                table: render_table(l.preset),
                mm: map.mm.iter().map(|v| v * l.multiplier).collect(),
                beckmann_roughness: l.preset.specular.roughness as f32,
                f0: fresnel_f0(l.preset.specular.ior as f32),
            }
        })
        .collect();
    let texel = |x: usize, y: usize| -> TexelSurface {
        let albedo = match &albedo_map {
            Some(t) => {
                let (sx, sy) = (t.width as f32 / side_px as f32, t.height as f32 / side_px as f32);
                t.sample_px((x as f32 + 0.5) * sx, (y as f32 + 0.5) * sy)
            }
            None => skin.albedo,
        };
        texel_surface(skin, albedo, &baked, y * n + x)
    };
    let mut out = SurfaceMaps {
        side_px,
        base_color: vec![[0.0; 3]; n * n],
        beckmann_roughness: vec![0.0; n * n],
        f0: vec![0.0; n * n],
    };
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).clamp(1, 16);
    let rows_per = n.div_ceil(threads).max(1);
    std::thread::scope(|s| {
        let chunks = out
            .base_color
            .chunks_mut(rows_per * n)
            .zip(out.beckmann_roughness.chunks_mut(rows_per * n))
            .zip(out.f0.chunks_mut(rows_per * n));
        for (chunk, ((base, rough), f0)) in chunks.enumerate() {
            let texel = &texel;
            s.spawn(move || {
                for i in 0..base.len() {
                    let t = texel(i % n, chunk * rows_per + i / n);
                    (base[i], rough[i], f0[i]) = (t.base_color, t.beckmann_roughness, t.f0);
                }
            });
        }
    });
    Ok(out)
}

/// One texel: the layers covering texel `i` over a skin of albedo `albedo` (linear sRGB).
fn texel_surface(skin: &SkinSurface<'_>, albedo: [f32; 3], layers: &[BakeLayer], i: usize) -> TexelSurface {
    let mut rt = Vec::with_capacity(layers.len());
    // The lobe stack of lighting.wgsl, bottom to top: lower lobes × T², each layer's × coverage.
    let mut weight = fresnel_f0(skin.ior);
    let mut weighted_roughness = weight * skin.beckmann_roughness;
    for l in layers {
        let x = l.mm[i];
        if x <= 0.0 {
            continue;
        }
        let (r0, t) = (lookup(&l.table.r0, x), lookup(&l.table.t, x));
        rt.push((r0, t));
        let t_lum: f32 = (0..3).map(|c| LUMINANCE[c] * t[c].clamp(0.0, 1.0)).sum();
        let coverage = layer_coverage(x);
        let lobe = coverage * l.f0;
        weight = weight * t_lum * t_lum + lobe;
        weighted_roughness = weighted_roughness * t_lum * t_lum + lobe * l.beckmann_roughness;
    }
    let base = CompositingBasis::get().reflectance_over_skin(&rt, albedo.map(f64::from));
    TexelSurface {
        base_color: base.map(|v| v.clamp(0.0, 1.0) as f32),
        beckmann_roughness: if weight > 0.0 { weighted_roughness / weight } else { skin.beckmann_roughness },
        f0: weight,
    }
}
