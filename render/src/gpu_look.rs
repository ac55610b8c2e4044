//! The look and the skin's textures on the GPU: the layers' thickness maps (one R16Float array
//! layer each, mm), their R0/T tables (from rouge-measure's [`rouge_measure::layer_table`], in
//! the [`CompositingBasis`] the lighting pass composes in) and specular parameters; the skin
//! albedo and normal maps.

use crate::error::{RenderError, Result};
use crate::scene::fresnel_f0;
use crate::shader::MAX_LAYERS;
use crate::uniforms::LayerUniform;
use crate::wgpu_util::{array_view, buffer_init, texture, view};
use rouge_measure::compositing::CompositingBasis;
use rouge_measure::preset::Preset;
use rouge_model::TexelRect;
use rouge_model::look::ThicknessMap;

/// Thickness (mm) at which a layer's own specular lobe is fully formed; thinner films fade in
/// linearly, so a layer of zero thickness has no lobe and renders exactly as bare skin.
pub const LAYER_FULL_COVERAGE_MM: f32 = 0.002;

/// One cosmetic layer for [`crate::Renderer::set_layers`].
#[derive(Clone, Copy, Debug)]
pub struct LayerInput<'a> {
    /// The material.
    pub preset: &'a Preset,
    /// Thickness in mm over the mesh's UV space.
    pub map: &'a ThicknessMap,
    /// Multiplier applied to the map.
    pub multiplier: f32,
}

/// The uploaded layers of a look.
#[derive(Debug)]
pub struct GpuLook {
    /// Number of layers (0 for a bare look).
    pub layers: u32,
    /// All thickness maps, as a 2D-array view.
    pub maps: wgpu::TextureView,
    texture: wgpu::Texture,
    size: (u32, u32),
    /// R0, T and interference rows of every layer, `TABLE_ENTRIES` RGBA entries each.
    pub tables: wgpu::Buffer,
    /// Specular parameters per layer.
    pub params: [LayerUniform; MAX_LAYERS],
    /// The layers with glitter, bit i for layer i.
    pub glitter: u8,
}

fn half_texels(mm: &[f32], multiplier: f32) -> Vec<u16> {
    mm.iter().map(|&v| half::f16::from_f32(v * multiplier).to_bits()).collect()
}

/// Writes `texels` (half floats, rows of the rectangle) into `rect` of one layer; the rectangle
/// is non-empty.
fn write_layer(queue: &wgpu::Queue, texture: &wgpu::Texture, layer: u32, rect: TexelRect, texels: &[u16]) {
    let (width, height) = (rect.width(), rect.height());
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: rect.x0, y: rect.y0, z: layer },
            aspect: wgpu::TextureAspect::All,
        },
        bytemuck::cast_slice(texels),
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(2 * width), rows_per_image: Some(height) },
        wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
    );
}

impl GpuLook {
    /// No layers; the map array has `min_layers` layers ([`crate::targets::Formats`]).
    pub fn empty(device: &wgpu::Device, min_layers: u32) -> GpuLook {
        let maps = texture(
            device,
            "GpuLook::maps (none)",
            (1, 1),
            crate::targets::array_layers(1, min_layers),
            wgpu::TextureFormat::R16Float,
            wgpu::TextureUsages::TEXTURE_BINDING,
            &[],
        );
        GpuLook {
            layers: 0,
            maps: array_view(&maps),
            texture: maps,
            size: (1, 1),
            tables: buffer_init(device, "GpuLook::tables (none)", &[0u8; 16], wgpu::BufferUsages::STORAGE),
            params: [LayerUniform::default(); MAX_LAYERS],
            glitter: 0,
        }
    }

    /// Uploads `layers` bottom to top; maps of other sizes are resampled to the largest. The map
    /// array has at least `min_layers` layers ([`crate::targets::Formats::min_array_layers`]).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for more than [`MAX_LAYERS`] layers or a negative or non-finite
    /// multiplier.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layers: &[LayerInput<'_>],
        min_layers: u32,
    ) -> Result<GpuLook> {
        if layers.len() > MAX_LAYERS {
            return Err(RenderError::Invalid(format!(
                "the look has {} visible layers; the renderer takes at most {MAX_LAYERS}",
                layers.len()
            )));
        }
        if layers.iter().any(|l| !(l.multiplier.is_finite() && l.multiplier >= 0.0)) {
            return Err(RenderError::Invalid("layer thickness multipliers must be finite and ≥ 0".into()));
        }
        let (w, h) = layers.iter().fold((1, 1), |(w, h), l| (w.max(l.map.width), h.max(l.map.height)));
        let count = crate::targets::array_layers(layers.len() as u32, min_layers);
        let maps = texture(
            device,
            "GpuLook::maps",
            (w, h),
            count,
            wgpu::TextureFormat::R16Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            &[],
        );
        let entries = rouge_measure::layer_table::TABLE_ENTRIES;
        let mut tables: Vec<[f32; 4]> = Vec::with_capacity(layers.len().max(1) * 3 * entries);
        let mut params = [LayerUniform::default(); MAX_LAYERS];
        let whole = TexelRect::whole(w, h);
        let mut glitter_layers = 0u8;
        for (i, layer) in layers.iter().enumerate() {
            let texels = if (layer.map.width, layer.map.height) == (w, h) {
                half_texels(&layer.map.mm, layer.multiplier)
            } else {
                half_texels(&layer.map.resized(w, h).mm, layer.multiplier)
            };
            write_layer(queue, &maps, i as u32, whole, &texels);
            // R0 and T in the compositing basis, where the lighting pass composes the stack.
            let table = rouge_measure::layer_table::render_table(layer.preset);
            let basis = CompositingBasis::get();
            let in_basis = |v: &[f32; 3]| {
                let c = basis.from_linear_srgb(v.map(f64::from));
                [c[0] as f32, c[1] as f32, c[2] as f32, 0.0]
            };
            tables.extend(table.r0.iter().map(in_basis));
            tables.extend(table.t.iter().map(in_basis));
            // The shimmer's interference colour by cos(h, l), linear sRGB (zeros without one).
            let shimmer = layer.preset.finish.and_then(|f| f.shimmer);
            let (clarity, levelling) = layer.preset.clarity_levelling();
            match shimmer {
                Some(s) => tables
                    .extend(s.interference_table(entries).iter().map(|c| [c[0] as f32, c[1] as f32, c[2] as f32, 0.0])),
                None => tables.extend(std::iter::repeat_n([0.0f32; 4], entries)),
            }
            params[i] = LayerUniform {
                params: [
                    layer.preset.specular.roughness as f32,
                    fresnel_f0(layer.preset.specular.ior as f32),
                    LAYER_FULL_COVERAGE_MM,
                    clarity as f32,
                ],
                film: [
                    levelling as f32,
                    shimmer.map_or(0.0, |s| s.strength as f32),
                    shimmer.map_or(1.0, |s| s.spread as f32),
                    0.0,
                ],
                ..LayerUniform::default()
            };
            // The glitter's flake field, seeded by the layer's index (crate::glitter).
            if let Some(g) = layer.preset.finish.and_then(|f| f.glitter) {
                let field = crate::glitter::FlakeField::new(&g, i as u32);
                params[i].glitter = [field.cell_mm, field.size_mm, field.p_flake, field.spread];
                // w: the preset's thickness, at which the glitter has its density.
                params[i].glitter_color =
                    [g.color[0] as f32, g.color[1] as f32, g.color[2] as f32, layer.preset.thickness_mm as f32];
                glitter_layers |= 1 << i;
            }
        }
        if tables.is_empty() {
            tables.push([0.0; 4]);
        }
        Ok(GpuLook {
            layers: layers.len() as u32,
            maps: array_view(&maps),
            texture: maps,
            size: (w, h),
            tables: buffer_init(device, "GpuLook::tables", bytemuck::cast_slice(&tables), wgpu::BufferUsages::STORAGE),
            params,
            glitter: glitter_layers,
        })
    }

    /// Re-uploads the texels `rect` (half-open, clamped to the map) of layer `layer` after
    /// painting; `map` must have the size the layers were uploaded at.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a layer or size that does not match the uploaded look.
    pub fn update(
        &self,
        queue: &wgpu::Queue,
        layer: usize,
        map: &ThicknessMap,
        multiplier: f32,
        rect: TexelRect,
    ) -> Result<()> {
        let (w, h) = self.size;
        if layer >= self.layers as usize || (map.width, map.height) != (w, h) {
            return Err(RenderError::Invalid(format!(
                "thickness update of layer {layer} ({}×{}) does not match the uploaded look ({} layers at {w}×{h})",
                map.width, map.height, self.layers
            )));
        }
        let rect = rect.clamped(w, h);
        if rect.is_empty() {
            return Ok(());
        }
        let mut texels = Vec::with_capacity(rect.area());
        for y in rect.y0..rect.y1 {
            let row = &map.mm[(y * w + rect.x0) as usize..(y * w + rect.x1) as usize];
            texels.extend(half_texels(row, multiplier));
        }
        write_layer(queue, &self.texture, layer as u32, rect, &texels);
        Ok(())
    }
}

/// The skin's optional albedo and normal maps.
#[derive(Debug, Default)]
pub struct SkinTextures {
    /// sRGB albedo in the mesh's UV space.
    pub albedo: Option<wgpu::TextureView>,
    /// Tangent-space normal map (+Y up).
    pub normal: Option<wgpu::TextureView>,
    /// The baked local thickness (Rgba16Float, rgb white = thin), for the thickness model.
    pub local_thickness: Option<wgpu::TextureView>,
    /// The skin's microgeometry ([`rouge_model::skin::detail`]).
    pub detail: Option<SkinDetailTextures>,
    /// The default head's wrinkle map ([`rouge_model::skin::wrinkles`]), drawn with the detail.
    pub wrinkles: Option<WrinkleTexture>,
}

/// The wrinkle map on the device (RGBA8 linear, one family a channel) and where it lies in the
/// mesh's UVs.
#[derive(Debug)]
pub struct WrinkleTexture {
    /// [`rouge_model::skin::WrinkleMap::image`].
    pub view: wgpu::TextureView,
    /// [`rouge_model::skin::WrinkleMap::uv_rect`].
    pub uv_rect: rouge_model::skin::wrinkles::UvRect,
    /// Texels across the map.
    pub side_px: u32,
}

impl WrinkleTexture {
    /// Uploads `map`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty or non-square map.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        map: &rouge_model::skin::WrinkleMap,
    ) -> Result<WrinkleTexture> {
        let (w, h) = map.image.dimensions();
        if w == 0 || w != h {
            return Err(RenderError::Invalid(format!("wrinkle map: {w}×{h} texels, expected a square")));
        }
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let view = upload_2d(device, queue, "WrinkleTexture", (w, h), format, map.image.as_raw(), 4);
        Ok(WrinkleTexture { view, uv_rect: map.uv_rect, side_px: w })
    }
}

/// The skin's microgeometry on the device: the tileable relief with its mip chain, the region
/// map (pore depth, specular scale) in the mesh's UVs, and how many tiles a UV unit holds.
#[derive(Debug)]
pub struct SkinDetailTextures {
    /// [`rouge_model::skin::DetailTile`], RGBA8 linear, every mip level.
    pub tile: wgpu::TextureView,
    /// [`rouge_model::skin::RegionDetail`], RGBA8 linear.
    pub regions: wgpu::TextureView,
    /// Tiles per UV unit ([`rouge_model::skin::detail::tiles_per_uv`]).
    pub tiles_per_uv: f32,
}

impl SkinDetailTextures {
    /// Uploads `tile` (every level) and `regions`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a tile without levels, levels that do not halve, or a scale
    /// that is not finite and positive.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        tile: &rouge_model::skin::DetailTile,
        regions: &rouge_model::skin::RegionDetail,
        tiles_per_uv: f32,
    ) -> Result<SkinDetailTextures> {
        let Some(first) = tile.levels.first() else {
            return Err(RenderError::Invalid("skin detail: a tile without levels".into()));
        };
        if !(tiles_per_uv.is_finite() && tiles_per_uv > 0.0) {
            return Err(RenderError::Invalid(format!("skin detail: {tiles_per_uv} tiles per UV unit")));
        }
        let side = first.width();
        if tile.levels.iter().enumerate().any(|(i, l)| l.width() != (side >> i).max(1) || l.height() != l.width()) {
            return Err(RenderError::Invalid("skin detail: tile levels must be square and halve".into()));
        }
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let levels: Vec<_> = tile.levels.iter().map(|l| (l.dimensions(), l.as_raw().as_slice())).collect();
        let r = &regions.image;
        Ok(SkinDetailTextures {
            tile: upload_mips(device, queue, "SkinDetailTextures::tile", &levels, format, 4),
            regions: upload_2d(device, queue, "SkinDetailTextures::regions", r.dimensions(), format, r.as_raw(), 4),
            tiles_per_uv,
        })
    }
}

impl SkinTextures {
    /// Uploads the maps (RGBA8; the albedo sRGB-encoded, the normal map linear).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty image.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        albedo: Option<&image::RgbaImage>,
        normal: Option<&image::RgbaImage>,
    ) -> Result<SkinTextures> {
        let upload = |img: &image::RgbaImage, format: wgpu::TextureFormat, label: &str| -> Result<wgpu::TextureView> {
            let (w, h) = img.dimensions();
            if w == 0 || h == 0 {
                return Err(RenderError::Invalid(format!("{label}: empty image")));
            }
            Ok(upload_2d(device, queue, &format!("SkinTextures::{label}"), (w, h), format, img.as_raw(), 4))
        };
        Ok(SkinTextures {
            albedo: albedo.map(|a| upload(a, wgpu::TextureFormat::Rgba8UnormSrgb, "albedo map")).transpose()?,
            normal: normal.map(|n| upload(n, wgpu::TextureFormat::Rgba8Unorm, "normal map")).transpose()?,
            local_thickness: None,
            detail: None,
            wrinkles: None,
        })
    }
}

/// Uploads a baked local-thickness map (RGBA f32 texels, row 0 at v = 1) as Rgba16Float.
///
/// # Errors
/// [`RenderError::Invalid`] for an empty map or a texel count other than `width × height`.
pub fn upload_local_thickness(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    width: u32,
    height: u32,
    texels: &[[f32; 4]],
) -> Result<wgpu::TextureView> {
    if width == 0 || height == 0 || texels.len() != width as usize * height as usize {
        return Err(RenderError::Invalid(format!(
            "local-thickness map {width}×{height} with {} texels: need width × height > 0",
            texels.len()
        )));
    }
    let halves: Vec<u16> = texels.iter().flatten().map(|&v| half::f16::from_f32(v).to_bits()).collect();
    let format = crate::targets::HDR_FORMAT;
    Ok(upload_2d(
        device,
        queue,
        "SkinTextures::local thickness",
        (width, height),
        format,
        bytemuck::cast_slice(&halves),
        8,
    ))
}

/// A sampled 2D texture of `size` and `format` holding `bytes` (rows of `bytes_per_texel` ×
/// width, top row first), and its view.
fn upload_2d(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    size: (u32, u32),
    format: wgpu::TextureFormat,
    bytes: &[u8],
    bytes_per_texel: u32,
) -> wgpu::TextureView {
    upload_mips(device, queue, label, &[(size, bytes)], format, bytes_per_texel)
}

/// [`upload_2d`] with a mip chain: `levels` from the full size down, each its size and texels.
fn upload_mips(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    levels: &[((u32, u32), &[u8])],
    format: wgpu::TextureFormat,
    bytes_per_texel: u32,
) -> wgpu::TextureView {
    let (width, height) = levels.first().map_or((1, 1), |l| l.0);
    let t = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: levels.len().max(1) as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (mip_level, &((width, height), bytes)) in levels.iter().enumerate() {
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &t,
                mip_level: mip_level as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(bytes_per_texel * width),
                rows_per_image: Some(height),
            },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
    }
    view(&t)
}
