//! The frame's render targets, from one place: [`TargetPool`] creates each [`Target`] on first
//! use at the frame's size in the format [`Formats`] chose for the adapter, and keeps it until the
//! size changes. A target no planned pass writes is never created (a bare look has no thickness
//! targets; a frame without SSS has no scratch or scattered images).
//!
//! Per sample the G-buffer writes 32 bytes at most (WebGPU's default limit):
//! `normal` Rgba16Float (world normal, w = coverage), `albedo` Rgba8UnormSrgb (a = skin flag),
//! `thickness_a`/`thickness_b` Rgba16Float (layers 0-3 / 4-7), `local thickness` Rgb10a2Unorm
//! (with the thickness translucency only), depth Depth32Float.

use crate::error::{RenderError, Result};
use crate::wgpu_util::texture;
use std::collections::HashMap;

/// Format of the world normal target.
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the albedo target.
pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Format of the local-thickness target: 10 bits per colour channel for the thickness, the
/// 2-bit alpha for the translucency material id (0: none), so that the G-buffer stays within
/// WebGPU's 32 bytes per sample with eight layers (\[BarreBrisebois2011\] packs it the same way).
pub const LOCAL_THICKNESS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgb10a2Unorm;
/// The glitter's G-buffer target (gbuffer.wgsl): the UV in mm as f32 bits (x, y), the footprint's
/// half extents log-coded as two snorm16 (z; the sign of the first is the UV frame's
/// handedness), the UV tangent's octahedral code as two snorm16 (w).
pub const GLITTER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
/// Format of radiance and thickness targets.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the display target's texture: plain RGBA8, a storage texture the composite pass
/// writes sRGB-encoded bytes into (sRGB formats cannot be storage textures).
pub const DISPLAY_STORAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Format of depth buffers and shadow maps.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Formats that depend on what the adapter can do (its downlevel capabilities).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formats {
    /// The format the tone-mapped output is drawn through (the edge overdraw pass blends into
    /// it): Rgba8UnormSrgb where an Rgba8Unorm texture can also be viewed as sRGB (so blending
    /// is linear), else Rgba8Unorm. The texture itself is [`DISPLAY_STORAGE_FORMAT`], written by
    /// the composite compute pass, which encodes sRGB (\[IEC61966\]) in the shader; either way it
    /// holds sRGB-encoded bytes, as egui wants them ([`egui_view`]).
    pub display: wgpu::TextureFormat,
    /// Format of the linear output: Rgba32Float, or Rgba16Float on GL, where 32-bit float
    /// textures cannot be render targets (a downlevel restriction); EXRs from GL are half floats.
    pub linear: wgpu::TextureFormat,
    /// Fewest layers of a texture sampled as an array (shadow maps, thickness maps): 1, or 2 on
    /// GL, which creates a one-layer texture as `TEXTURE_2D`, so that an array view of it samples
    /// nothing (every shadow lookup returned 0 before this; wgpu issue 2161). Allocate through
    /// [`array_layers`], which also steers GL clear of cube maps.
    pub min_array_layers: u32,
    /// Whether depth textures can be copied to buffers (`DEPTH_TEXTURE_AND_BUFFER_COPIES`, not
    /// on GL); where not, depth is read back through the depth copy pass.
    pub copy_depth: bool,
}

impl Formats {
    /// Whether the linear output is half floats (the shaders' `HALF_LINEAR` flag).
    pub fn half_linear(self) -> bool {
        self.linear == wgpu::TextureFormat::Rgba16Float
    }

    /// The formats for `device`. wgpu's GL backend is the native backend without
    /// `DownlevelFlags::VIEW_FORMATS` (Vulkan, Metal and DX12 always have it), so it gets the
    /// plain display format and the shader's sRGB encoding.
    pub fn for_device(device: &wgpu::Device) -> Formats {
        Formats::for_backend(device.adapter_info().backend)
    }

    /// The formats for a device on `backend`.
    pub fn for_backend(backend: wgpu::Backend) -> Formats {
        match backend {
            wgpu::Backend::Gl | wgpu::Backend::BrowserWebGpu | wgpu::Backend::Noop => Formats {
                display: wgpu::TextureFormat::Rgba8Unorm,
                linear: wgpu::TextureFormat::Rgba16Float,
                min_array_layers: 2,
                copy_depth: false,
            },
            wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => Formats {
                display: wgpu::TextureFormat::Rgba8UnormSrgb,
                linear: wgpu::TextureFormat::Rgba32Float,
                min_array_layers: 1,
                copy_depth: true,
            },
        }
    }
}

/// Layers to allocate for a texture of `n` layers sampled as an array, on a device whose
/// [`Formats::min_array_layers`] is `min_layers`: at least `min_layers`, and where that is above 1
/// (wgpu's GL backend) never a multiple of 6: GL makes a square texture of 6k layers a cube map
/// (wgpu-hal 30, `gles::Texture::get_info_from_desc`), and an array view of it then samples
/// nothing (the cube atlas's six faces read black on GL before this; a six-layer look would too).
pub fn array_layers(n: u32, min_layers: u32) -> u32 {
    let n = n.max(min_layers).max(1);
    if min_layers > 1 && n.is_multiple_of(6) { n + 1 } else { n }
}

/// A view of a display frame for egui, which wants sRGB-encoded values read as they are
/// (`Rgba8Unorm`), not decoded to linear. Works for both display formats of [`Formats`].
pub fn egui_view(display: &wgpu::Texture) -> wgpu::TextureView {
    display.create_view(&wgpu::TextureViewDescriptor {
        format: Some(wgpu::TextureFormat::Rgba8Unorm),
        ..Default::default()
    })
}

/// The frame's images, named by what they hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Target {
    /// World normal, w = coverage.
    Normal,
    /// Albedo, a = skin flag.
    Albedo,
    /// Thickness (mm) of layers 0-3.
    ThicknessA,
    /// Thickness (mm) of layers 4-7.
    ThicknessB,
    /// Local thickness of the thickness translucency (rgb, white = thin) and its material id (a).
    LocalThickness,
    /// The glitter's flake-field coordinates: UV in mm, footprint, tangent frame (`GLITTER_FORMAT`).
    Glitter,
    /// Depth buffer.
    Depth,
    /// The depth of the nearest back face, where the camera's ray leaves the mesh (the slab law's
    /// single scattering along the view ray).
    BackDepth,
    /// Skin radiance before scattering.
    Diffuse,
    /// The horizontal SSS pass's output.
    SssScratch,
    /// Skin radiance after scattering.
    Scattered,
    /// The irradiance of one bounce between facing parts, per pixel (the bounce pass's gather).
    BounceLight,
    /// Skin radiance with one bounce between facing parts added (the bounce pass's output).
    Bounced,
    /// Radiance that leaves at the surface.
    Surface,
    /// Transmittance of the cosmetic stack toward the viewer.
    ExitT,
    /// Tone-mapped, sRGB-encoded output.
    Display,
    /// Linear radiance output.
    Linear,
    /// The hair pass's premultiplied radiance (rgb) and transmittance (a).
    Hair,
}

impl Target {
    /// The name used in labels and in `rouge render --explain`.
    pub fn name(self) -> &'static str {
        match self {
            Target::Normal => "normal",
            Target::Albedo => "albedo",
            Target::ThicknessA => "thickness 0-3",
            Target::ThicknessB => "thickness 4-7",
            Target::LocalThickness => "local thickness",
            Target::Glitter => "glitter footprint",
            Target::Depth => "depth",
            Target::BackDepth => "back-face depth",
            Target::Diffuse => "diffuse",
            Target::SssScratch => "sss scratch",
            Target::Scattered => "scattered",
            Target::BounceLight => "bounce light",
            Target::Bounced => "bounced",
            Target::Surface => "surface",
            Target::ExitT => "exit T",
            Target::Display => "display",
            Target::Linear => "linear",
            Target::Hair => "hair",
        }
    }

    /// Its format on a device with `formats`, as passes sample it or draw into it (the display
    /// target's texture is [`DISPLAY_STORAGE_FORMAT`], viewed in this format).
    pub fn format(self, formats: Formats) -> wgpu::TextureFormat {
        match self {
            Target::Normal => NORMAL_FORMAT,
            Target::Albedo => ALBEDO_FORMAT,
            Target::LocalThickness => LOCAL_THICKNESS_FORMAT,
            Target::Glitter => GLITTER_FORMAT,
            Target::Depth | Target::BackDepth => DEPTH_FORMAT,
            Target::Display => formats.display,
            Target::Linear => formats.linear,
            _ => HDR_FORMAT,
        }
    }
}

/// The frame's targets, created on first use and kept while the size stays.
#[derive(Debug)]
pub struct TargetPool {
    formats: Formats,
    size: (u32, u32),
    textures: HashMap<Target, wgpu::Texture>,
}

impl TargetPool {
    /// An empty pool for a device with `formats`.
    pub fn new(formats: Formats) -> TargetPool {
        TargetPool { formats, size: (0, 0), textures: HashMap::new() }
    }

    /// Sets the frame size; a change drops every target.
    pub fn resize(&mut self, size: (u32, u32)) {
        if self.size != size {
            self.size = size;
            self.textures.clear();
        }
    }

    /// The frame size.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Creates `targets` that do not exist yet at the current size.
    pub fn ensure(&mut self, device: &wgpu::Device, targets: impl IntoIterator<Item = Target>) {
        use wgpu::TextureUsages as U;
        for target in targets {
            let (size, formats) = (self.size, self.formats);
            self.textures.entry(target).or_insert_with(|| {
                let format = target.format(formats);
                // The compute passes' outputs are also storage textures.
                let storage = matches!(
                    target,
                    Target::SssScratch
                        | Target::Scattered
                        | Target::BounceLight
                        | Target::Bounced
                        | Target::Diffuse
                        | Target::Surface
                        | Target::ExitT
                        | Target::Display
                        | Target::Linear
                );
                let usage = U::RENDER_ATTACHMENT
                    | U::TEXTURE_BINDING
                    | U::COPY_SRC
                    | if storage { U::STORAGE_BINDING } else { U::empty() };
                let label = format!("Target::{}", target.name());
                // The display texture is plain RGBA8 (a storage texture), viewed as sRGB for the
                // edge overdraw's blending where the backend has view formats.
                let (format, views): (_, &[wgpu::TextureFormat]) = match target {
                    Target::Display if format != DISPLAY_STORAGE_FORMAT => (DISPLAY_STORAGE_FORMAT, &[format]),
                    Target::Display => (DISPLAY_STORAGE_FORMAT, &[]),
                    _ => (format, &[]),
                };
                texture(device, &label, size, 1, format, usage, views)
            });
        }
    }

    /// A target created by [`TargetPool::ensure`] at the current size.
    pub fn get(&self, target: Target) -> Option<&wgpu::Texture> {
        self.textures.get(&target)
    }

    /// The default view of a target the frame plan created.
    ///
    /// # Errors
    /// [`RenderError::Gpu`] when it was not created (a planning bug, reported rather than a panic).
    pub fn view(&self, target: Target) -> Result<wgpu::TextureView> {
        let format = target.format(self.formats);
        self.texture(target).map(|t| {
            // A view in another format than the texture's (the display's sRGB view) is drawn
            // into, never stored to: sRGB formats cannot be storage textures.
            let usage = (t.format() != format).then(|| t.usage() - wgpu::TextureUsages::STORAGE_BINDING);
            t.create_view(&wgpu::TextureViewDescriptor { format: Some(format), usage, ..Default::default() })
        })
    }

    /// The view a compute pass writes a target through: the texture's own format (for the
    /// display target, [`DISPLAY_STORAGE_FORMAT`]).
    ///
    /// # Errors
    /// As [`TargetPool::view`].
    pub fn storage_view(&self, target: Target) -> Result<wgpu::TextureView> {
        self.texture(target).map(crate::wgpu_util::view)
    }

    fn texture(&self, target: Target) -> Result<&wgpu::Texture> {
        self.get(target)
            .ok_or_else(|| RenderError::Gpu(format!("target {} was not created by the frame plan", target.name())))
    }
}

#[cfg(test)]
mod tests {
    use super::array_layers;

    #[test]
    fn gl_arrays_never_take_a_cube_maps_layer_count() {
        assert_eq!(array_layers(1, 1), 1);
        assert_eq!(array_layers(6, 1), 6);
        assert_eq!(array_layers(0, 2), 2);
        assert_eq!(array_layers(1, 2), 2);
        assert_eq!(array_layers(6, 2), 7);
        assert_eq!(array_layers(12, 2), 13);
        assert_eq!(array_layers(8, 2), 8);
    }
}
