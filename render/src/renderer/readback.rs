//! Reading the last frame back: the display and linear images, depth and picking, the
//! intermediate targets ([`FrameCapture`]), the layers' rendered thickness, the cube atlas.

use super::{LastFrame, Renderer};
use crate::error::{RenderError, Result};
use crate::passes::FrameEncoder;
use crate::passes::depth_copy;
use crate::targets::Target;
use crate::wgpu_util::{self, read_texture, texture, validated};
use glam::Vec3;

/// Intermediate images of the last frame, read back for analysis (SSS study, tests).
#[derive(Clone, Debug)]
pub struct FrameCapture {
    /// Width.
    pub width: usize,
    /// Height.
    pub height: usize,
    /// Skin radiance before scattering.
    pub diffuse: Vec<[f32; 4]>,
    /// Skin radiance after scattering (equal to `diffuse` when the blur did not run).
    pub scattered: Vec<[f32; 4]>,
    /// Skin radiance with the bounce between facing parts added, when the bounce pass ran
    /// ([`crate::bounce`]).
    pub bounced: Option<Vec<[f32; 4]>>,
    /// World normal (w: coverage).
    pub normal: Vec<[f32; 4]>,
    /// Surface radiance.
    pub surface: Vec<[f32; 4]>,
    /// Stack transmittance (1 without layers).
    pub exit_t: Vec<[f32; 4]>,
    /// Thickness (mm) of layers 0-3 as the G-buffer read it (0 without layers).
    pub thickness: Vec<[f32; 4]>,
    /// View depth, mm (far plane for the background).
    pub depth_mm: Vec<f32>,
    /// Focal length in pixels.
    pub focal_px: f32,
}

/// A frame's depth buffer ([0, 1] NDC depth, row 0 at the top) and the matrix that made it.
#[derive(Clone, Debug)]
pub struct FrameDepth {
    /// World → clip of the frame.
    pub view_proj: glam::Mat4,
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// The depths.
    pub depth: std::sync::Arc<Vec<f32>>,
}

/// The rendered thickness of layers 0-3 of a frame ([`Renderer::thickness_image`]).
#[derive(Clone, Debug)]
pub struct ThicknessImage {
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// Per pixel, row-major: layers 0-3's thickness × multiplier, mm.
    pub texels: Vec<[f32; 4]>,
}

impl Renderer {
    /// The cube atlas as the last frame that used it drew it (tests, inspection).
    ///
    /// # Errors
    /// Before any frame used the cube-atlas model; GPU failures.
    pub fn atlas_image(&self) -> Result<crate::cube_atlas::AtlasImage> {
        if !self.shared.formats.copy_depth {
            return Err(RenderError::Invalid(
                "reading the cube atlas back copies its depth, which this backend (GL) cannot".into(),
            ));
        }
        let device = &self.shared.device;
        validated(device, "atlas readback", || self.atlas.read(device, &self.shared.queue))
    }

    pub(super) fn last_frame(&self) -> Result<&LastFrame> {
        self.last.as_ref().ok_or_else(|| RenderError::Invalid("no frame rendered yet".into()))
    }

    /// The depth buffer of the last frame (values in [0, 1]); through the depth copy pass where
    /// depth textures cannot be copied to buffers (GL).
    fn read_depth(&self) -> Result<Vec<f32>> {
        if self.shared.formats.copy_depth {
            return Ok(bytemuck::pod_collect_to_vec(&self.read(Target::Depth, 4)?));
        }
        let depth = self.targets.view(Target::Depth)?;
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        let mut pass = self.depth_copy.lock().map_err(|_| RenderError::Gpu("depth copy pass poisoned".into()))?;
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let copy = validated(device, "depth copy", || {
            let (size, format) = (self.targets.size(), depth_copy::OUTPUT_FORMAT);
            let copy = texture(device, "DepthCopyPass::out", size, 1, format, usage, &[]);
            let label = Some("DepthCopyPass");
            let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label });
            let mut enc = FrameEncoder { encoder, profiler: None };
            pass.record(&self.shared, &mut enc, &depth, &wgpu_util::view(&copy))?;
            queue.submit([enc.encoder.finish()]);
            Ok(copy)
        })?;
        let bytes = validated(device, "readback", || read_texture(device, queue, &copy, 4))?;
        // Each texel holds the f32's bytes, least significant first.
        Ok(bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect())
    }

    fn read(&self, target: Target, bytes_per_texel: u32) -> Result<Vec<u8>> {
        let texture = self
            .targets
            .get(target)
            .ok_or_else(|| RenderError::Invalid(format!("the last frame has no {} image", target.name())))?;
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        // GL without DEPTH_TEXTURE_AND_BUFFER_COPIES cannot copy depth: an error, not a panic.
        validated(device, "readback", || read_texture(device, queue, texture, bytes_per_texel))
    }

    /// Reads back the tone-mapped output of the last display frame as RGBA8 (sRGB-encoded).
    ///
    /// # Errors
    /// Without a display frame, or if the GPU fails.
    pub fn read_display(&self) -> Result<Vec<u8>> {
        self.last_frame()?;
        self.read(Target::Display, 4)
    }

    /// Reads back the linear output of the last linear frame (RGBA f32).
    ///
    /// # Errors
    /// Without a linear frame, or if the GPU fails.
    pub fn read_linear(&self) -> Result<Vec<[f32; 4]>> {
        self.last_frame()?;
        if self.shared.formats.linear == wgpu::TextureFormat::Rgba16Float {
            return Ok(crate::wgpu_util::halves_to_f32(&self.read(Target::Linear, 8)?));
        }
        Ok(bytemuck::pod_collect_to_vec(&self.read(Target::Linear, 16)?))
    }

    /// The surface point under pixel (`x`, `y`) of the last frame, read from the GPU depth
    /// buffer; `None` over the background.
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn pick(&self, x: u32, y: u32) -> Result<Option<Vec3>> {
        let last = self.last_frame()?;
        let (w, h) = self.targets.size();
        if x >= w || y >= h {
            return Ok(None);
        }
        let depth = self.frame_depth()?.get((y * w + x) as usize).copied().unwrap_or(1.0);
        if depth >= 1.0 {
            return Ok(None);
        }
        let ndc = glam::Vec4::new(
            (x as f32 + 0.5) / w as f32 * 2.0 - 1.0,
            1.0 - (y as f32 + 0.5) / h as f32 * 2.0,
            depth,
            1.0,
        );
        let world = last.view.view_proj.inverse() * ndc;
        Ok((world.w != 0.0).then(|| world.truncate() / world.w))
    }

    /// The last frame's depth buffer ([0, 1], row 0 at the top), read once per frame: depth
    /// textures cannot be copied in part, so the whole buffer (3.7 MB at 1280×720) is read on the
    /// first request and every pick of that frame is answered from the copy.
    fn frame_depth(&self) -> Result<std::sync::Arc<Vec<f32>>> {
        let last = self.last_frame()?;
        let mut cache = last.depth.lock().map_err(|_| RenderError::Gpu("depth cache poisoned".into()))?;
        if cache.is_none() {
            *cache = Some(std::sync::Arc::new(self.read_depth()?));
        }
        cache.clone().ok_or_else(|| RenderError::Gpu("depth cache empty".into()))
    }

    /// The last frame's depth buffer with its view-projection and size, for tests of what the
    /// viewer sees (the brush's occlusion test).
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn depth_image(&self) -> Result<FrameDepth> {
        let view_proj = self.last_frame()?.view.view_proj;
        Ok(FrameDepth { view_proj, size: self.targets.size(), depth: self.frame_depth()? })
    }

    /// Pixel coordinates of a world point in the last frame (for tests and overlays).
    pub fn project(&self, world: Vec3) -> Option<(f32, f32)> {
        let last = self.last.as_ref()?;
        let (w, h) = self.targets.size();
        let clip = last.view.view_proj * world.extend(1.0);
        if clip.w <= 0.0 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(((ndc.x + 1.0) * 0.5 * w as f32, (1.0 - ndc.y) * 0.5 * h as f32))
    }

    /// The rendered thickness (mm) of layers 0-3 at every pixel of the last frame (the
    /// G-buffer's first thickness target, map × multiplier; zeros for a bare look), row-major,
    /// with the frame's size: one target read back, where [`Renderer::capture`] reads them all.
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn thickness_image(&self) -> Result<ThicknessImage> {
        let last = self.last_frame()?;
        let size = self.targets.size();
        let texels = if last.variant.layers == 0 {
            vec![[0.0; 4]; (size.0 * size.1) as usize]
        } else {
            crate::wgpu_util::halves_to_f32(&self.read(Target::ThicknessA, 8)?)
        };
        Ok(ThicknessImage { size, texels })
    }

    /// Reads back the intermediate images of the last frame.
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn capture(&self) -> Result<FrameCapture> {
        let last = self.last_frame()?;
        let half4 =
            |target: Target| -> Result<Vec<[f32; 4]>> { Ok(crate::wgpu_util::halves_to_f32(&self.read(target, 8)?)) };
        let diffuse = half4(Target::Diffuse)?;
        let scattered = if last.sss_ran { half4(Target::Scattered)? } else { diffuse.clone() };
        let bounced = if last.bounce_ran { Some(half4(Target::Bounced)?) } else { None };
        let layers = last.variant.layers;
        let exit_t = if layers > 0 { half4(Target::ExitT)? } else { vec![[1.0; 4]; diffuse.len()] };
        let thickness = if layers > 0 { half4(Target::ThicknessA)? } else { vec![[0.0; 4]; diffuse.len()] };
        let depth = self.read_depth()?;
        let (n, f) = (last.view.near, last.view.far);
        let depth_mm = depth.iter().map(|&d| n * f / (f - d * (f - n))).collect();
        let (w, h) = self.targets.size();
        Ok(FrameCapture {
            width: w as usize,
            height: h as usize,
            diffuse,
            scattered,
            bounced,
            normal: half4(Target::Normal)?,
            surface: half4(Target::Surface)?,
            exit_t,
            thickness,
            depth_mm,
            focal_px: last.view.focal_px,
        })
    }
}
