//! The frame of paper 003, figure 1, on wgpu: shadow maps → G-buffer → lighting (cosmetic stack,
//! irradiance through it, specular lobes) → separable SSS (two passes) → composition.
//!
//! Only what the scene uses runs or is compiled: shaders are specialised per [`Variant`] (layer
//! count, shadows, environment), so a bare look has no thickness targets, no table lookups and
//! no layer lobes; there is no shadow pass without a shadowing light, no SH evaluation without an
//! environment, and no SSS pass at width 0.
//!
//! Targets (per sample: 32 bytes at most, the WebGPU default):
//! - `normal` Rgba16Float: world normal, w = coverage;
//! - `albedo` Rgba8UnormSrgb: albedo, a = skin flag;
//! - `thickness_a`/`thickness_b` Rgba16Float: layers 0-3 / 4-7, only when present;
//! - depth Depth32Float, read back as view depth for the depth-aware blur;
//! - `diffuse` (skin radiance before/after scattering), `surface`, `exit_t`: Rgba16Float;
//! - output: Rgba8UnormSrgb (tone-mapped, for PNG and the app) or Rgba32Float (linear radiance).

use crate::error::{RenderError, Result};
use crate::look::Look;
use crate::mesh::{Bounds, TriangleMesh};
use crate::scene::{Camera, LightKind, Scene, fresnel_f0};
use crate::sss::{MAX_SAMPLES, SeparableKernel};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_measure::preset::{Preset, layer_spectra};
use std::collections::HashMap;

/// Most cosmetic layers a look may have (two RGBA16F thickness targets).
pub const MAX_LAYERS: usize = 8;
/// Most lights a scene may have.
pub const MAX_LIGHTS: usize = 4;
/// Entries per layer table row.
pub const TABLE_ENTRIES: usize = 64;
/// X0 of the table parameterisation X = X0·u/(1−u): half the entries cover 0..X0.
pub const TABLE_X0_MM: f64 = 0.02;
/// Thickness (mm) at which a layer's own specular lobe is fully formed; thinner films fade in
/// linearly, so a layer of zero thickness has no lobe and renders exactly as bare skin.
pub const LAYER_FULL_COVERAGE_MM: f32 = 0.002;
/// Shadow map size, texels.
pub const SHADOW_MAP_SIZE: u32 = 2048;

const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Format of the tone-mapped output.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// A view of a display frame for egui, which wants sRGB-encoded values read as they are
/// (`Rgba8Unorm`), not decoded to linear.
pub fn egui_view(display: &wgpu::Texture) -> wgpu::TextureView {
    display.create_view(&wgpu::TextureViewDescriptor {
        format: Some(wgpu::TextureFormat::Rgba8Unorm),
        ..Default::default()
    })
}

/// Format of the linear output.
pub const LINEAR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// One light, as in WGSL `Light`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct LightUniform {
    /// Direction toward the light (w 0) or position (w 1).
    pub position: [f32; 4],
    /// Irradiance; w: squared distance to the scene centre for point lights.
    pub color: [f32; 4],
    /// Shadow layer (or −1), bias, normal offset, texel size.
    pub shadow: [f32; 4],
    /// Light's view-projection for its shadow map.
    pub shadow_view_proj: [[f32; 4]; 4],
}

/// One layer's specular parameters, as in WGSL `Layer`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct LayerUniform {
    /// Roughness, F0, full-coverage thickness, unused.
    pub params: [f32; 4],
}

/// The per-frame uniform, as in WGSL `Frame` (shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FrameUniform {
    /// World → clip.
    pub view_proj: [[f32; 4]; 4],
    /// Clip → world.
    pub inv_view_proj: [[f32; 4]; 4],
    /// World → view.
    pub view: [[f32; 4]; 4],
    /// Camera position.
    pub camera_pos: [f32; 4],
    /// Width, height, 1/width, 1/height.
    pub viewport: [f32; 4],
    /// Focal length (px), near, far, exposure.
    pub projection: [f32; 4],
    /// Skin roughness, F0, specular on, unused.
    pub skin: [f32; 4],
    /// SSS width, follow (mm), sample count, unused.
    pub sss: [f32; 4],
    /// Background.
    pub background: [f32; 4],
    /// Lights, layers, table entries, unused.
    pub counts: [u32; 4],
    /// SH irradiance coefficients.
    pub sh: [[f32; 4]; 9],
    /// Lights.
    pub lights: [LightUniform; MAX_LIGHTS],
    /// Layers.
    pub layers: [LayerUniform; MAX_LAYERS],
}

/// One SSS pass's uniform, as in WGSL `SssPass`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct SssUniform {
    /// Direction (px), width, follow (mm).
    pub dir: [f32; 4],
    /// Sample count.
    pub count: [u32; 4],
    /// Offset (mm) and weights.
    pub samples: [[f32; 4]; MAX_SAMPLES as usize],
}

/// A uniform struct's WGSL name, size in bytes, and (field, offset) pairs.
pub type UniformLayout = (&'static str, usize, Vec<(&'static str, usize)>);

/// Field offsets of the uniforms, for the layout test against naga's view of the WGSL.
pub fn uniform_layouts() -> Vec<UniformLayout> {
    use std::mem::{offset_of, size_of};
    vec![
        (
            "Frame",
            size_of::<FrameUniform>(),
            vec![
                ("view_proj", offset_of!(FrameUniform, view_proj)),
                ("inv_view_proj", offset_of!(FrameUniform, inv_view_proj)),
                ("view", offset_of!(FrameUniform, view)),
                ("camera_pos", offset_of!(FrameUniform, camera_pos)),
                ("viewport", offset_of!(FrameUniform, viewport)),
                ("projection", offset_of!(FrameUniform, projection)),
                ("skin", offset_of!(FrameUniform, skin)),
                ("sss", offset_of!(FrameUniform, sss)),
                ("background", offset_of!(FrameUniform, background)),
                ("counts", offset_of!(FrameUniform, counts)),
                ("sh", offset_of!(FrameUniform, sh)),
                ("lights", offset_of!(FrameUniform, lights)),
                ("layers", offset_of!(FrameUniform, layers)),
            ],
        ),
        (
            "Light",
            size_of::<LightUniform>(),
            vec![
                ("position", offset_of!(LightUniform, position)),
                ("color", offset_of!(LightUniform, color)),
                ("shadow", offset_of!(LightUniform, shadow)),
                ("shadow_view_proj", offset_of!(LightUniform, shadow_view_proj)),
            ],
        ),
        ("Layer", size_of::<LayerUniform>(), vec![("params", offset_of!(LayerUniform, params))]),
        (
            "SssPass",
            size_of::<SssUniform>(),
            vec![
                ("dir", offset_of!(SssUniform, dir)),
                ("count", offset_of!(SssUniform, count)),
                ("samples", offset_of!(SssUniform, samples)),
            ],
        ),
    ]
}

/// The passes, for shader sources and timings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pass {
    /// Depth from a light.
    Shadow,
    /// Normals, albedo, layer thickness.
    Gbuffer,
    /// Stack, irradiance, specular.
    Lighting,
    /// One direction of the separable blur.
    Sss,
    /// Composition and tone mapping.
    Composite,
}

impl Pass {
    /// Every pass.
    pub const ALL: [Pass; 5] = [Pass::Shadow, Pass::Gbuffer, Pass::Lighting, Pass::Sss, Pass::Composite];

    fn file(self) -> &'static str {
        match self {
            Pass::Shadow => include_str!("shaders/shadow.wgsl"),
            Pass::Gbuffer => include_str!("shaders/gbuffer.wgsl"),
            Pass::Lighting => include_str!("shaders/lighting.wgsl"),
            Pass::Sss => include_str!("shaders/sss.wgsl"),
            Pass::Composite => include_str!("shaders/composite.wgsl"),
        }
    }
}

/// What a scene and look need compiled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Variant {
    /// Number of cosmetic layers, 0..=[`MAX_LAYERS`].
    pub layers: u32,
    /// Some light casts shadows.
    pub shadows: bool,
    /// An environment lights the scene.
    pub env: bool,
    /// Tone-mapped sRGB output (else linear radiance).
    pub display: bool,
    /// The skin albedo comes from a texture.
    pub albedo_map: bool,
    /// A tangent-space normal map perturbs the normals.
    pub normal_map: bool,
}

impl Variant {
    /// Every variant, for validating all shader sources.
    pub fn all() -> impl Iterator<Item = Variant> {
        (0..=MAX_LAYERS as u32).flat_map(|layers| {
            (0..32u32).map(move |bits| Variant {
                layers,
                shadows: bits & 1 != 0,
                env: bits & 2 != 0,
                display: bits & 4 != 0,
                albedo_map: bits & 8 != 0,
                normal_map: bits & 16 != 0,
            })
        })
    }

    /// The part of the variant a pass depends on (passes share pipelines across the rest).
    pub fn for_pass(self, pass: Pass) -> Variant {
        let none =
            Variant { layers: 0, shadows: false, env: false, display: false, albedo_map: false, normal_map: false };
        match pass {
            Pass::Shadow | Pass::Sss => none,
            Pass::Gbuffer => {
                Variant { layers: self.layers, albedo_map: self.albedo_map, normal_map: self.normal_map, ..none }
            }
            Pass::Lighting => Variant { layers: self.layers, shadows: self.shadows, env: self.env, ..none },
            Pass::Composite => Variant { layers: self.layers.min(1), display: self.display, ..none },
        }
    }
}

/// The WGSL source of `pass` specialised for `variant`: common declarations, constants, and the
/// pass file with its `//#if FLAG … //#else … //#endif` blocks resolved.
pub fn shader_source(pass: Pass, variant: Variant) -> String {
    let flags = [
        ("LAYERS_A", variant.layers > 0),
        ("LAYERS_B", variant.layers > 4),
        ("SHADOWS", variant.shadows),
        ("ENV", variant.env),
        ("DISPLAY", variant.display),
        ("ALBEDO_MAP", variant.albedo_map),
        ("NORMAL_MAP", variant.normal_map),
    ];
    let mut out = format!("const LAYERS: u32 = {}u;\n", variant.layers);
    out.push_str(include_str!("shaders/common.wgsl"));
    let mut keep = true;
    for line in pass.file().lines() {
        let t = line.trim();
        if let Some(flag) = t.strip_prefix("//#if ") {
            keep = flags.iter().any(|(name, on)| *name == flag.trim() && *on);
        } else if t == "//#else" {
            keep = !keep;
        } else if t == "//#endif" {
            keep = true;
        } else if keep {
            if t == "SH_EVAL" {
                out.push_str(crate::env::WGSL_SH_EVAL);
            } else {
                out.push_str(line);
            }
            out.push('\n');
        }
    }
    out
}

/// GPU time of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass label ("shadow 0", "gbuffer", …).
    pub pass: String,
    /// Milliseconds.
    pub ms: f64,
}

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

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
    albedo: [f32; 4],
    tangent: [f32; 4],
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    bounds: Bounds,
    has_tangents: bool,
}

/// One cosmetic layer for [`Renderer::set_layers`].
#[derive(Clone, Copy, Debug)]
pub struct LayerInput<'a> {
    /// The material.
    pub preset: &'a Preset,
    /// Thickness in mm over the mesh's UV space.
    pub map: &'a crate::look::ThicknessMap,
    /// Multiplier applied to the map.
    pub multiplier: f32,
}

struct GpuLook {
    layers: u32,
    maps: wgpu::TextureView,
    texture: wgpu::Texture,
    size: (u32, u32),
    tables: wgpu::Buffer,
    params: [LayerUniform; MAX_LAYERS],
}

struct Targets {
    width: u32,
    height: u32,
    normal: wgpu::Texture,
    albedo: wgpu::Texture,
    thickness_a: wgpu::Texture,
    thickness_b: wgpu::Texture,
    depth: wgpu::Texture,
    diffuse: wgpu::Texture,
    scratch: wgpu::Texture,
    scattered: wgpu::Texture,
    surface: wgpu::Texture,
    exit_t: wgpu::Texture,
    display: wgpu::Texture,
    linear: wgpu::Texture,
}

struct Profiler {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
}

const MAX_TIMED_PASSES: u32 = MAX_LIGHTS as u32 + 4;

/// The renderer: owns pipelines, the uploaded mesh and look, and the frame's targets.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    frame_buffer: wgpu::Buffer,
    frame_layout: wgpu::BindGroupLayout,
    frame_group: wgpu::BindGroup,
    layouts: HashMap<Pass, wgpu::BindGroupLayout>,
    pipelines: HashMap<(Pass, Variant), wgpu::RenderPipeline>,
    linear_sampler: wgpu::Sampler,
    shadow_sampler: wgpu::Sampler,
    sss_buffers: [wgpu::Buffer; 2],
    shadow_buffers: Vec<wgpu::Buffer>,
    shadow_maps: wgpu::Texture,
    dummy_2d: wgpu::Texture,
    mesh: Option<GpuMesh>,
    albedo_map: Option<wgpu::TextureView>,
    normal_map: Option<wgpu::TextureView>,
    look: GpuLook,
    targets: Option<Targets>,
    profiler: Option<Profiler>,
    profiling: bool,
    timings: Vec<PassTiming>,
    last_variant: Option<Variant>,
    last_sss_ran: bool,
    last_focal_px: f32,
    last_view_proj: glam::Mat4,
    depth_cache: std::sync::Mutex<Option<Vec<f32>>>,
    last_near: f32,
    last_far: f32,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer").field("layers", &self.look.layers).field("mesh", &self.mesh.is_some()).finish()
    }
}

fn texture(
    device: &wgpu::Device,
    label: &str,
    w: u32,
    h: u32,
    layers: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: layers },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        // The display target is also viewable as plain RGBA8 (the sRGB-encoded bytes as they
        // are), which is what egui expects of the textures it shows.
        view_formats: if format == DISPLAY_FORMAT { &[wgpu::TextureFormat::Rgba8Unorm] } else { &[] },
    })
}

fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor::default())
}

fn array_view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

fn tex_entry(
    binding: u32,
    sample_type: wgpu::TextureSampleType,
    dim: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture { sample_type, view_dimension: dim, multisampled: false },
        count: None,
    }
}

fn float_tex(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    tex_entry(binding, wgpu::TextureSampleType::Float { filterable }, wgpu::TextureViewDimension::D2)
}

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn sampler_entry(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

fn buffer_init(device: &wgpu::Device, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (bytes.len() as u64).max(16).next_multiple_of(4),
        usage,
        mapped_at_creation: true,
    });
    if let Ok(mut range) = buffer.get_mapped_range_mut(..bytes.len() as u64) {
        range.copy_from_slice(bytes);
    }
    buffer.unmap();
    buffer
}

/// Row-major R0 and T tables of one preset: `TABLE_ENTRIES` rows of linear sRGB each, at
/// thickness X = X0·u/(1−u), u = i/(n−1); the last entry is the opaque limit (R∞, T = 0).
pub fn layer_tables(preset: &Preset) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let c = Colorimeter::get(Viewing::D65_1931);
    let (s, k) = (preset.s(), preset.k());
    let mut r0 = Vec::with_capacity(TABLE_ENTRIES);
    let mut t = Vec::with_capacity(TABLE_ENTRIES);
    for i in 0..TABLE_ENTRIES {
        if i + 1 == TABLE_ENTRIES {
            r0.push(preset.derived.r_inf_linear_srgb.map(|v| v as f32));
            t.push([0.0; 3]);
            continue;
        }
        let u = i as f64 / (TABLE_ENTRIES - 1) as f64;
        let x = TABLE_X0_MM * u / (1.0 - u);
        let (rs, ts) = layer_spectra(&s, &k, x);
        let (r_rgb, t_rgb) =
            if i == 0 { ([0.0; 3], [1.0; 3]) } else { (c.srgb_linear(&c.xyz(&rs)), c.srgb_linear(&c.xyz(&ts))) };
        r0.push(r_rgb.map(|v| v as f32));
        t.push(t_rgb.map(|v| v as f32));
    }
    (r0, t)
}

/// The table lookup of the lighting shader, on the CPU (for its error study and tests).
pub fn table_lookup(row: &[[f32; 3]], x_mm: f32) -> [f32; 3] {
    let n = row.len();
    let u = x_mm / (x_mm + TABLE_X0_MM as f32);
    let f = u * (n - 1) as f32;
    let i = (f as usize).min(n - 2);
    let w = f - i as f32;
    std::array::from_fn(|c| row[i][c] + (row[i + 1][c] - row[i][c]) * w)
}

/// Albedo and material per vertex: skin everywhere but groups named like eyes, which get a
/// sclera, iris and pupil by angle from the eye's forward axis (+Z) and do not scatter.
fn vertex_albedo(mesh: &TriangleMesh, skin: [f32; 3]) -> Vec<[f32; 4]> {
    let mut albedo = vec![[skin[0], skin[1], skin[2], 1.0]; mesh.positions.len()];
    for g in &mesh.groups {
        if !g.name.to_ascii_lowercase().contains("eye") {
            continue;
        }
        let mut verts: Vec<u32> = mesh.indices[g.triangles.start * 3..g.triangles.end * 3].to_vec();
        verts.sort_unstable();
        verts.dedup();
        if verts.is_empty() {
            continue;
        }
        let centre = verts.iter().map(|&v| mesh.positions[v as usize]).sum::<Vec3>() / verts.len() as f32;
        for &v in &verts {
            let d = (mesh.positions[v as usize] - centre).normalize_or_zero();
            let cos = d.z;
            albedo[v as usize] = if cos > 0.985 {
                [0.01, 0.01, 0.01, 0.0]
            } else if cos > 0.93 {
                [0.10, 0.05, 0.025, 0.0]
            } else {
                [0.62, 0.58, 0.55, 0.0]
            };
        }
    }
    albedo
}

impl Renderer {
    /// A renderer on `device` (the app's, or [`crate::gpu::Gpu::headless`]'s).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Renderer {
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)],
        });
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame"),
            size: std::mem::size_of::<FrameUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &frame_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        let unfilterable = |b| float_tex(b, false);
        let mut layouts = HashMap::new();
        let mk = |label: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries })
        };
        layouts.insert(Pass::Shadow, mk("shadow", &[uniform_entry(0, wgpu::ShaderStages::VERTEX)]));
        layouts.insert(
            Pass::Gbuffer,
            mk(
                "gbuffer",
                &[
                    tex_entry(
                        0,
                        wgpu::TextureSampleType::Float { filterable: true },
                        wgpu::TextureViewDimension::D2Array,
                    ),
                    sampler_entry(1, wgpu::SamplerBindingType::Filtering),
                    float_tex(2, true),
                    float_tex(3, true),
                ],
            ),
        );
        layouts.insert(
            Pass::Lighting,
            mk(
                "lighting",
                &[
                    unfilterable(0),
                    unfilterable(1),
                    tex_entry(2, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2),
                    unfilterable(3),
                    unfilterable(4),
                    wgpu::BindGroupLayoutEntry {
                        binding: 5,
                        visibility: wgpu::ShaderStages::FRAGMENT,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Storage { read_only: true },
                            has_dynamic_offset: false,
                            min_binding_size: None,
                        },
                        count: None,
                    },
                    tex_entry(6, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
                    sampler_entry(7, wgpu::SamplerBindingType::Comparison),
                ],
            ),
        );
        layouts.insert(
            Pass::Sss,
            mk(
                "sss",
                &[
                    uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                    float_tex(1, true),
                    tex_entry(2, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2),
                    sampler_entry(3, wgpu::SamplerBindingType::Filtering),
                ],
            ),
        );
        layouts.insert(
            Pass::Composite,
            mk("composite", &[unfilterable(0), unfilterable(1), unfilterable(2), unfilterable(3)]),
        );

        let linear_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let sss_size = std::mem::size_of::<SssUniform>() as u64;
        let sss_buffers = [0, 1].map(|i| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(if i == 0 { "sss horizontal" } else { "sss vertical" }),
                size: sss_size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        });
        let shadow_buffers = (0..MAX_LIGHTS as u32)
            .map(|i| buffer_init(device, "shadow pass", bytemuck::bytes_of(&[i, 0, 0, 0]), wgpu::BufferUsages::UNIFORM))
            .collect();
        let shadow_maps = texture(
            device,
            "shadow maps (none)",
            1,
            1,
            1,
            DEPTH_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let dummy_2d = texture(device, "dummy", 1, 1, 1, HDR_FORMAT, wgpu::TextureUsages::TEXTURE_BINDING);
        let look = empty_look(device);
        let profiler = device.features().contains(wgpu::Features::TIMESTAMP_QUERY).then(|| {
            let count = MAX_TIMED_PASSES * 2;
            Profiler {
                queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                    label: Some("pass times"),
                    ty: wgpu::QueryType::Timestamp,
                    count,
                }),
                resolve: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamps"),
                    size: count as u64 * 8,
                    usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                }),
                readback: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamps readback"),
                    size: count as u64 * 8,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                period_ns: queue.get_timestamp_period(),
            }
        });
        Renderer {
            device: device.clone(),
            queue: queue.clone(),
            frame_buffer,
            frame_layout,
            frame_group,
            layouts,
            pipelines: HashMap::new(),
            linear_sampler,
            shadow_sampler,
            sss_buffers,
            shadow_buffers,
            shadow_maps,
            dummy_2d,
            mesh: None,
            albedo_map: None,
            normal_map: None,
            look,
            targets: None,
            profiler,
            profiling: false,
            timings: Vec::new(),
            last_variant: None,
            last_sss_ran: false,
            last_focal_px: 1.0,
            last_view_proj: glam::Mat4::IDENTITY,
            depth_cache: std::sync::Mutex::new(None),
            last_near: 1.0,
            last_far: 1.0,
        }
    }

    /// Uploads a triangle mesh (mm) with the skin albedo per vertex.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty mesh.
    pub fn set_mesh(&mut self, mesh: &TriangleMesh, skin_albedo: [f32; 3]) -> Result<()> {
        let bounds =
            Bounds::of(&mesh.positions).ok_or_else(|| RenderError::Invalid("the mesh has no vertices".into()))?;
        if mesh.indices.is_empty() {
            return Err(RenderError::Invalid("the mesh has no triangles".into()));
        }
        let albedo = vertex_albedo(mesh, skin_albedo);
        let vertices: Vec<Vertex> = (0..mesh.positions.len())
            .map(|i| Vertex {
                position: mesh.positions[i].to_array(),
                normal: mesh.normals.get(i).copied().unwrap_or(Vec3::Z).to_array(),
                uv: mesh.uvs.get(i).map_or([0.0; 2], |uv| uv.to_array()),
                albedo: albedo[i],
                tangent: mesh.tangents.as_ref().and_then(|t| t.get(i)).map_or([0.0; 4], |t| t.to_array()),
            })
            .collect();
        self.mesh = Some(GpuMesh {
            vertices: buffer_init(
                &self.device,
                "vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer_init(
                &self.device,
                "indices",
                bytemuck::cast_slice(&mesh.indices),
                wgpu::BufferUsages::INDEX,
            ),
            index_count: mesh.indices.len() as u32,
            bounds,
            has_tangents: mesh.tangents.is_some(),
        });
        Ok(())
    }

    /// Sets or clears the skin albedo texture (sRGB-encoded RGBA8, in the mesh's UV space, row 0
    /// at v = 1) and the tangent-space normal map (RGBA8, +Y up, OpenGL convention). A normal map
    /// needs a mesh uploaded with tangents ([`TriangleMesh::generate_tangents`]).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a normal map on a mesh without tangents, or an empty image.
    pub fn set_textures(&mut self, albedo: Option<&image::RgbaImage>, normal: Option<&image::RgbaImage>) -> Result<()> {
        if normal.is_some() && !self.mesh.as_ref().is_some_and(|m| m.has_tangents) {
            return Err(RenderError::Invalid("a normal map needs a mesh with tangents (generate them first)".into()));
        }
        let upload = |img: &image::RgbaImage, format: wgpu::TextureFormat, label: &str| -> Result<wgpu::TextureView> {
            let (w, h) = img.dimensions();
            if w == 0 || h == 0 {
                return Err(RenderError::Invalid(format!("{label}: empty image")));
            }
            let t = texture(
                &self.device,
                label,
                w,
                h,
                1,
                format,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            );
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &t,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                img.as_raw(),
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * w), rows_per_image: Some(h) },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
            Ok(view(&t))
        };
        self.albedo_map = albedo.map(|a| upload(a, wgpu::TextureFormat::Rgba8UnormSrgb, "albedo map")).transpose()?;
        self.normal_map = normal.map(|n| upload(n, wgpu::TextureFormat::Rgba8Unorm, "normal map")).transpose()?;
        Ok(())
    }

    /// Bounds of the uploaded mesh.
    pub fn mesh_bounds(&self) -> Option<Bounds> {
        self.mesh.as_ref().map(|m| m.bounds)
    }

    /// Uploads a look: its visible layers' tables and thickness maps.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for more than [`MAX_LAYERS`] visible layers.
    pub fn set_look(&mut self, look: &Look) -> Result<()> {
        let layers: Vec<_> =
            look.visible_layers().map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: 1.0 }).collect();
        self.set_layers(&layers)
    }

    /// Uploads cosmetic layers bottom to top (the painting app's path: its maps carry a
    /// multiplier).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for more than [`MAX_LAYERS`] layers.
    pub fn set_layers(&mut self, layers: &[LayerInput<'_>]) -> Result<()> {
        self.look = Self::upload_look_layers(&self.device, &self.queue, layers)?;
        Ok(())
    }

    /// Re-uploads the texels `rect` = (x0, y0, x1, y1) (half-open) of layer `layer`'s thickness
    /// map after painting; `map` must have the size the layers were uploaded at.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a layer or size that does not match the uploaded look.
    pub fn update_thickness(
        &mut self,
        layer: usize,
        map: &crate::look::ThicknessMap,
        multiplier: f32,
        rect: (u32, u32, u32, u32),
    ) -> Result<()> {
        let (w, h) = self.look.size;
        if layer >= self.look.layers as usize || (map.width, map.height) != (w, h) {
            return Err(RenderError::Invalid(format!(
                "thickness update of layer {layer} ({}×{}) does not match the uploaded look ({} layers at {w}×{h})",
                map.width, map.height, self.look.layers
            )));
        }
        let (x0, y0) = (rect.0.min(w), rect.1.min(h));
        let (x1, y1) = (rect.2.min(w), rect.3.min(h));
        if x0 >= x1 || y0 >= y1 {
            return Ok(());
        }
        let mut texels = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
        for y in y0..y1 {
            let row = &map.mm[(y * w + x0) as usize..(y * w + x1) as usize];
            texels.extend(row.iter().map(|&v| half::f16::from_f32(v * multiplier).to_bits()));
        }
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &self.look.texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x: x0, y: y0, z: layer as u32 },
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(2 * (x1 - x0)),
                rows_per_image: Some(y1 - y0),
            },
            wgpu::Extent3d { width: x1 - x0, height: y1 - y0, depth_or_array_layers: 1 },
        );
        Ok(())
    }

    /// The surface point under pixel (`x`, `y`) of the last frame, read from the GPU depth
    /// buffer; `None` over the background.
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn pick(&self, x: u32, y: u32) -> Result<Option<Vec3>> {
        let t = self.targets.as_ref().ok_or_else(|| RenderError::Invalid("no frame rendered yet".into()))?;
        if x >= t.width || y >= t.height {
            return Ok(None);
        }
        // Depth textures cannot be copied in part: read the whole depth buffer once per frame
        // (3.7 MB at 1280×720) and answer every pick of that frame from the copy.
        let mut cache = self.depth_cache.lock().map_err(|_| RenderError::Gpu("depth cache poisoned".into()))?;
        if cache.is_none() {
            let bytes = read_texture(&self.device, &self.queue, &t.depth, 4)?;
            *cache = Some(bytemuck::pod_collect_to_vec(&bytes));
        }
        let depth = cache.as_ref().and_then(|d| d.get((y * t.width + x) as usize).copied()).unwrap_or(1.0);
        if depth >= 1.0 {
            return Ok(None);
        }
        let ndc = glam::Vec4::new(
            (x as f32 + 0.5) / t.width as f32 * 2.0 - 1.0,
            1.0 - (y as f32 + 0.5) / t.height as f32 * 2.0,
            depth,
            1.0,
        );
        let world = self.last_view_proj.inverse() * ndc;
        Ok((world.w != 0.0).then(|| world.truncate() / world.w))
    }

    /// Pixel coordinates of a world point in the last frame (for tests and overlays).
    pub fn project(&self, world: Vec3) -> Option<(f32, f32)> {
        let t = self.targets.as_ref()?;
        let clip = self.last_view_proj * world.extend(1.0);
        if clip.w <= 0.0 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(((ndc.x + 1.0) * 0.5 * t.width as f32, (1.0 - ndc.y) * 0.5 * t.height as f32))
    }

    fn upload_look_layers(device: &wgpu::Device, queue: &wgpu::Queue, layers: &[LayerInput<'_>]) -> Result<GpuLook> {
        if layers.len() > MAX_LAYERS {
            return Err(RenderError::Invalid(format!(
                "the look has {} visible layers; the renderer takes at most {MAX_LAYERS}",
                layers.len()
            )));
        }
        let (w, h) = layers.iter().fold((1, 1), |(w, h), l| (w.max(l.map.width), h.max(l.map.height)));
        if layers.iter().any(|l| !(l.multiplier.is_finite() && l.multiplier >= 0.0)) {
            return Err(RenderError::Invalid("layer thickness multipliers must be finite and ≥ 0".into()));
        }
        let count = layers.len().max(1) as u32;
        let maps = texture(
            device,
            "thickness maps",
            w,
            h,
            count,
            wgpu::TextureFormat::R16Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        let mut tables: Vec<[f32; 4]> = Vec::with_capacity(layers.len().max(1) * 2 * TABLE_ENTRIES);
        let mut params = [LayerUniform::default(); MAX_LAYERS];
        for (i, layer) in layers.iter().enumerate() {
            let map =
                if (layer.map.width, layer.map.height) == (w, h) { layer.map.clone() } else { layer.map.resized(w, h) };
            let m = layer.multiplier;
            let texels: Vec<u16> = map.mm.iter().map(|&v| half::f16::from_f32(v * m).to_bits()).collect();
            queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &maps,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: i as u32 },
                    aspect: wgpu::TextureAspect::All,
                },
                bytemuck::cast_slice(&texels),
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(2 * w), rows_per_image: Some(h) },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
            let (r0, t) = layer_tables(layer.preset);
            tables.extend(r0.iter().map(|v| [v[0], v[1], v[2], 0.0]));
            tables.extend(t.iter().map(|v| [v[0], v[1], v[2], 0.0]));
            params[i] = LayerUniform {
                params: [
                    layer.preset.specular.roughness as f32,
                    fresnel_f0(layer.preset.specular.ior as f32),
                    LAYER_FULL_COVERAGE_MM,
                    0.0,
                ],
            };
        }
        if tables.is_empty() {
            tables.push([0.0; 4]);
        }
        Ok(GpuLook {
            layers: layers.len() as u32,
            maps: array_view(&maps),
            texture: maps,
            size: (w, h),
            tables: buffer_init(device, "layer tables", bytemuck::cast_slice(&tables), wgpu::BufferUsages::STORAGE),
            params,
        })
    }

    /// Number of layers of the uploaded look.
    pub fn layer_count(&self) -> u32 {
        self.look.layers
    }

    /// Collect per-pass GPU times of the following frames (when the adapter has timestamps).
    pub fn set_profiling(&mut self, on: bool) {
        self.profiling = on && self.profiler.is_some();
    }

    /// Per-pass GPU times of the last frame rendered with profiling on.
    pub fn timings(&self) -> &[PassTiming] {
        &self.timings
    }

    /// The variant of the last frame.
    pub fn last_variant(&self) -> Option<Variant> {
        self.last_variant
    }

    fn pipeline(&mut self, pass: Pass, variant: Variant) -> &wgpu::RenderPipeline {
        // Passes that do not depend on a flag share one pipeline.
        let key_variant = variant.for_pass(pass);
        let device = &self.device;
        let frame_layout = &self.frame_layout;
        let pass_layout = &self.layouts[&pass];
        self.pipelines.entry((pass, key_variant)).or_insert_with(|| {
            let source = shader_source(pass, key_variant);
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&format!("{pass:?}")),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&format!("{pass:?}")),
                bind_group_layouts: &[Some(frame_layout), Some(pass_layout)],
                immediate_size: 0,
            });
            let vertex_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4, 4 => Float32x4];
            let mesh_buffers = [Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &vertex_attrs,
            })];
            let hdr = |f| Some(wgpu::ColorTargetState { format: f, blend: None, write_mask: wgpu::ColorWrites::ALL });
            let (vs, buffers, fs, targets, depth): (
                _,
                &[Option<wgpu::VertexBufferLayout>],
                _,
                Vec<Option<wgpu::ColorTargetState>>,
                _,
            ) = match pass {
                Pass::Shadow => ("vs_shadow", &mesh_buffers[..], None, vec![], true),
                Pass::Gbuffer => {
                    let mut t = vec![hdr(NORMAL_FORMAT), hdr(ALBEDO_FORMAT)];
                    if key_variant.layers > 0 {
                        t.push(hdr(HDR_FORMAT));
                    }
                    if key_variant.layers > 4 {
                        t.push(hdr(HDR_FORMAT));
                    }
                    ("vs_gbuffer", &mesh_buffers[..], Some("fs_gbuffer"), t, true)
                }
                Pass::Lighting => {
                    let mut t = vec![hdr(HDR_FORMAT), hdr(HDR_FORMAT)];
                    if key_variant.layers > 0 {
                        t.push(hdr(HDR_FORMAT));
                    }
                    ("vs_fullscreen", &[][..], Some("fs_lighting"), t, false)
                }
                Pass::Sss => ("vs_fullscreen", &[][..], Some("fs_sss"), vec![hdr(HDR_FORMAT)], false),
                Pass::Composite => {
                    let f = if key_variant.display { DISPLAY_FORMAT } else { LINEAR_FORMAT };
                    ("vs_fullscreen", &[][..], Some("fs_composite"), vec![hdr(f)], false)
                }
            };
            // The shadow pass uses a vertex buffer layout with position only (same stride).
            let shadow_attrs = wgpu::vertex_attr_array![0 => Float32x3];
            let shadow_buffers = [Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &shadow_attrs,
            })];
            let buffers = if pass == Pass::Shadow { &shadow_buffers[..] } else { buffers };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&format!("{pass:?}")),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: depth.then(|| wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: if pass == Pass::Shadow {
                        wgpu::DepthBiasState { constant: 2, slope_scale: 2.0, clamp: 0.0 }
                    } else {
                        Default::default()
                    },
                }),
                multisample: Default::default(),
                fragment: fs.map(|entry| wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }

    fn ensure_targets(&mut self, width: u32, height: u32) {
        if self.targets.as_ref().is_some_and(|t| t.width == width && t.height == height) {
            return;
        }
        let d = &self.device;
        use wgpu::TextureUsages as U;
        let rt = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        self.targets = Some(Targets {
            width,
            height,
            normal: texture(d, "normal", width, height, 1, NORMAL_FORMAT, rt),
            albedo: texture(d, "albedo", width, height, 1, ALBEDO_FORMAT, rt),
            thickness_a: texture(d, "thickness 0-3", width, height, 1, HDR_FORMAT, rt),
            thickness_b: texture(d, "thickness 4-7", width, height, 1, HDR_FORMAT, rt),
            depth: texture(d, "depth", width, height, 1, DEPTH_FORMAT, rt),
            diffuse: texture(d, "diffuse", width, height, 1, HDR_FORMAT, rt),
            scratch: texture(d, "sss scratch", width, height, 1, HDR_FORMAT, rt),
            scattered: texture(d, "scattered", width, height, 1, HDR_FORMAT, rt),
            surface: texture(d, "surface", width, height, 1, HDR_FORMAT, rt),
            exit_t: texture(d, "exit T", width, height, 1, HDR_FORMAT, rt),
            display: texture(d, "display", width, height, 1, DISPLAY_FORMAT, rt),
            linear: texture(d, "linear", width, height, 1, LINEAR_FORMAT, rt),
        });
    }

    fn ensure_shadow_maps(&mut self, count: u32) {
        if count == 0
            || self.shadow_maps.depth_or_array_layers() >= count && self.shadow_maps.width() == SHADOW_MAP_SIZE
        {
            return;
        }
        self.shadow_maps = texture(
            &self.device,
            "shadow maps",
            SHADOW_MAP_SIZE,
            SHADOW_MAP_SIZE,
            count,
            DEPTH_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
    }

    /// Renders one frame of `scene` seen by `camera` at `width` × `height` into the renderer's
    /// targets: the tone-mapped output when `display`, else linear radiance. Returns the output
    /// texture (Rgba8UnormSrgb or Rgba32Float), which stays valid until the next frame at another
    /// size.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] without a mesh, for a zero size, too many lights or a bad SSS
    /// sample count.
    pub fn render(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        width: u32,
        height: u32,
        display: bool,
    ) -> Result<wgpu::Texture> {
        let max_dim = self.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max_dim || height > max_dim {
            return Err(RenderError::Invalid(format!("image size {width}×{height}: each side must be 1 to {max_dim}")));
        }
        if scene.lights.len() > MAX_LIGHTS {
            return Err(RenderError::Invalid(format!(
                "{} lights: the renderer takes at most {MAX_LIGHTS}",
                scene.lights.len()
            )));
        }
        let Some(bounds) = self.mesh.as_ref().map(|m| m.bounds) else {
            return Err(RenderError::Invalid("no mesh to render: call set_mesh first".into()));
        };
        let kernel = SeparableKernel::new(&scene.skin.profile, scene.sss.samples, scene.sss.range_sigmas as f64)?;
        let run_sss = scene.sss.width > 0.0 || scene.sss.run_at_zero_width;
        if !(scene.sss.width.is_finite() && scene.sss.width >= 0.0) {
            return Err(RenderError::Invalid(format!("SSS width {}: must be ≥ 0", scene.sss.width)));
        }
        self.ensure_targets(width, height);
        let shadow_count = scene.lights.iter().filter(|l| l.shadows).count() as u32;
        self.ensure_shadow_maps(shadow_count);
        let variant = Variant {
            layers: self.look.layers,
            shadows: shadow_count > 0,
            env: scene.environment.is_some(),
            display,
            albedo_map: self.albedo_map.is_some(),
            normal_map: self.normal_map.is_some(),
        };

        // Frame uniform.
        let centre = bounds.center();
        let radius = 0.5 * bounds.size().length();
        let (near, far) = camera.clip_planes(radius.max(camera.distance * 0.02));
        let aspect = width as f32 / height as f32;
        let view_m = camera.view();
        let view_proj = camera.projection(aspect, near, far) * view_m;
        let mut lights = [LightUniform::default(); MAX_LIGHTS];
        let mut shadow_layer = 0;
        for (i, l) in scene.lights.iter().enumerate() {
            let (position, d2, light_pos, to_centre) = match l.kind {
                LightKind::Directional { toward } => {
                    let t = toward.normalize_or_zero();
                    ([t.x, t.y, t.z, 0.0], 0.0, centre + t * 2.5 * radius, None)
                }
                LightKind::Point { position } => {
                    let d2 = (position - centre).length_squared().max(1e-6);
                    ([position.x, position.y, position.z, 1.0], d2, position, Some(d2.sqrt()))
                }
            };
            let mut u = LightUniform {
                position,
                color: [l.irradiance[0], l.irradiance[1], l.irradiance[2], d2],
                shadow: [-1.0, 0.0, 0.0, 0.0],
                ..Default::default()
            };
            if l.shadows {
                let up = if (light_pos - centre).normalize_or_zero().abs().y > 0.95 { Vec3::Z } else { Vec3::Y };
                let light_view = glam::camera::rh::view::look_at_mat4(light_pos, centre, up);
                let proj = match to_centre {
                    None => glam::camera::rh::proj::directx::orthographic(
                        -radius,
                        radius,
                        -radius,
                        radius,
                        0.5 * radius,
                        4.5 * radius,
                    ),
                    Some(d) => {
                        let half = (radius / d).clamp(0.05, 0.99).asin() * 1.05;
                        glam::camera::rh::proj::directx::perspective(2.0 * half, 1.0, (d - radius).max(1.0), d + radius)
                    }
                };
                let texel_mm = 2.0 * radius / SHADOW_MAP_SIZE as f32;
                u.shadow = [shadow_layer as f32, 0.0005, 1.5 * texel_mm, 1.0 / SHADOW_MAP_SIZE as f32];
                u.shadow_view_proj = (proj * light_view).to_cols_array_2d();
                shadow_layer += 1;
            }
            lights[i] = u;
        }
        let focal_px = camera.focal_px(height);
        let frame = FrameUniform {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            view: view_m.to_cols_array_2d(),
            camera_pos: camera.position().extend(1.0).to_array(),
            viewport: [width as f32, height as f32, 1.0 / width as f32, 1.0 / height as f32],
            projection: [focal_px, near, far, scene.exposure],
            skin: [scene.skin.roughness, scene.skin.f0(), if scene.specular { 1.0 } else { 0.0 }, 0.0],
            sss: [scene.sss.width, scene.sss.follow_mm, scene.sss.samples as f32, 0.0],
            background: [scene.background[0], scene.background[1], scene.background[2], 0.0],
            counts: [scene.lights.len() as u32, self.look.layers, TABLE_ENTRIES as u32, 0],
            sh: scene.environment.map_or([[0.0; 4]; 9], |sh| sh.to_gpu()),
            lights,
            layers: self.look.params,
        };
        self.queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        let samples = kernel.to_gpu();
        for (i, dir) in [[1.0, 0.0], [0.0, 1.0]].iter().enumerate() {
            let u = SssUniform {
                dir: [dir[0], dir[1], scene.sss.width, scene.sss.follow_mm],
                count: [scene.sss.samples, 0, 0, 0],
                samples,
            };
            self.queue.write_buffer(&self.sss_buffers[i], 0, bytemuck::bytes_of(&u));
        }

        // Pipelines first (they borrow self mutably).
        for pass in Pass::ALL {
            self.pipeline(pass, variant);
        }
        let key = |pass: Pass| variant.for_pass(pass);
        let Some(t) = self.targets.as_ref() else {
            return Err(RenderError::Gpu("render targets were not created".into()));
        };
        let Some(mesh) = self.mesh.as_ref() else {
            return Err(RenderError::Invalid("no mesh to render".into()));
        };
        let d = &self.device;
        let views = |tex: &wgpu::Texture| view(tex);
        let (normal_v, albedo_v, ta_v, tb_v, depth_v) =
            (views(&t.normal), views(&t.albedo), views(&t.thickness_a), views(&t.thickness_b), views(&t.depth));
        let (diffuse_v, scratch_v, scattered_v, surface_v, exit_v) =
            (views(&t.diffuse), views(&t.scratch), views(&t.scattered), views(&t.surface), views(&t.exit_t));
        let out_tex = if display { t.display.clone() } else { t.linear.clone() };
        let out_v = view(&out_tex);
        let dummy_v = view(&self.dummy_2d);
        let shadow_array_v = array_view(&self.shadow_maps);

        let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame") });
        let profiler = if self.profiling { self.profiler.as_ref() } else { None };
        let mut labels: Vec<String> = Vec::new();
        let mut timestamp = |label: String| -> Option<wgpu::RenderPassTimestampWrites<'_>> {
            let p = profiler?;
            let i = labels.len() as u32;
            labels.push(label);
            Some(wgpu::RenderPassTimestampWrites {
                query_set: &p.queries,
                beginning_of_pass_write_index: Some(2 * i),
                end_of_pass_write_index: Some(2 * i + 1),
            })
        };
        let zero = wgpu::Color::TRANSPARENT;

        // 0. Shadow maps.
        let mut layer = 0u32;
        for (i, l) in scene.lights.iter().enumerate() {
            if !l.shadows {
                continue;
            }
            let sv = self.shadow_maps.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: layer,
                array_layer_count: Some(1),
                ..Default::default()
            });
            let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("shadow"),
                layout: &self.layouts[&Pass::Shadow],
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: self.shadow_buffers[i].as_entire_binding() }],
            });
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &sv,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: timestamp(format!("shadow {layer}")),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines[&(Pass::Shadow, key(Pass::Shadow))]);
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            layer += 1;
        }

        // 1. G-buffer.
        {
            let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("gbuffer"),
                layout: &self.layouts[&Pass::Gbuffer],
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&self.look.maps) },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&self.linear_sampler) },
                    tex(2, self.albedo_map.as_ref().unwrap_or(&dummy_v)),
                    tex(3, self.normal_map.as_ref().unwrap_or(&dummy_v)),
                ],
            });
            let mut attachments = vec![color(&normal_v, zero), color(&albedo_v, zero)];
            if variant.layers > 0 {
                attachments.push(color(&ta_v, zero));
            }
            if variant.layers > 4 {
                attachments.push(color(&tb_v, zero));
            }
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("gbuffer"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_v,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: timestamp("gbuffer".into()),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines[&(Pass::Gbuffer, key(Pass::Gbuffer))]);
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, 0..1);
        }

        // 2-3, 5. Lighting.
        {
            let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("lighting"),
                layout: &self.layouts[&Pass::Lighting],
                entries: &[
                    tex(0, &normal_v),
                    tex(1, &albedo_v),
                    tex(2, &depth_v),
                    tex(3, if variant.layers > 0 { &ta_v } else { &dummy_v }),
                    tex(4, if variant.layers > 4 { &tb_v } else { &dummy_v }),
                    wgpu::BindGroupEntry { binding: 5, resource: self.look.tables.as_entire_binding() },
                    tex(6, &shadow_array_v),
                    wgpu::BindGroupEntry { binding: 7, resource: wgpu::BindingResource::Sampler(&self.shadow_sampler) },
                ],
            });
            let mut attachments = vec![color(&diffuse_v, zero), color(&surface_v, zero)];
            if variant.layers > 0 {
                attachments.push(color(&exit_v, wgpu::Color::WHITE));
            }
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("lighting"),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: timestamp("lighting".into()),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines[&(Pass::Lighting, key(Pass::Lighting))]);
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.draw(0..3, 0..1);
        }

        // 4. SSS, horizontal then vertical.
        if run_sss {
            for (i, (src, dst, label)) in
                [(&diffuse_v, &scratch_v, "sss horizontal"), (&scratch_v, &scattered_v, "sss vertical")]
                    .into_iter()
                    .enumerate()
            {
                let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(label),
                    layout: &self.layouts[&Pass::Sss],
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: self.sss_buffers[i].as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(src) },
                        wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&depth_v) },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: wgpu::BindingResource::Sampler(&self.linear_sampler),
                        },
                    ],
                });
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(label),
                    color_attachments: &[color(dst, zero)],
                    depth_stencil_attachment: None,
                    timestamp_writes: timestamp(label.into()),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(&self.pipelines[&(Pass::Sss, key(Pass::Sss))]);
                pass.set_bind_group(0, &self.frame_group, &[]);
                pass.set_bind_group(1, &group, &[]);
                pass.draw(0..3, 0..1);
            }
        }

        // 6. Composite.
        {
            let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("composite"),
                layout: &self.layouts[&Pass::Composite],
                entries: &[
                    tex(0, if run_sss { &scattered_v } else { &diffuse_v }),
                    tex(1, &surface_v),
                    tex(2, if variant.layers > 0 { &exit_v } else { &dummy_v }),
                    tex(3, &normal_v),
                ],
            });
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("composite"),
                color_attachments: &[color(&out_v, zero)],
                depth_stencil_attachment: None,
                timestamp_writes: timestamp("composite".into()),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines[&(Pass::Composite, key(Pass::Composite))]);
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.draw(0..3, 0..1);
        }

        let timed = labels.len() as u32;
        if let Some(p) = profiler.filter(|_| timed > 0) {
            encoder.resolve_query_set(&p.queries, 0..2 * timed, &p.resolve, 0);
            encoder.copy_buffer_to_buffer(&p.resolve, 0, &p.readback, 0, 16 * timed as u64);
        }
        self.queue.submit([encoder.finish()]);
        self.last_variant = Some(variant);
        self.last_sss_ran = run_sss;
        self.last_focal_px = focal_px;
        self.last_near = near;
        self.last_view_proj = view_proj;
        if let Ok(mut cache) = self.depth_cache.lock() {
            *cache = None;
        }
        self.last_far = far;
        self.timings.clear();
        if let Some(p) = profiler.filter(|_| timed > 0) {
            let bytes = read_buffer(d, &p.readback, 16 * timed as u64)?;
            let stamps: &[u64] = bytemuck::cast_slice(&bytes);
            let period = p.period_ns as f64;
            self.timings = labels
                .into_iter()
                .enumerate()
                .map(|(i, pass)| {
                    let ticks = stamps[2 * i + 1].saturating_sub(stamps[2 * i]);
                    PassTiming { pass, ms: ticks as f64 * period * 1e-6 }
                })
                .collect();
        }
        Ok(out_tex)
    }

    /// Waits for the GPU to finish the submitted work.
    ///
    /// # Errors
    /// [`RenderError::Gpu`] if the device is lost.
    pub fn wait(&self) -> Result<()> {
        self.device.poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).map_err(|e| RenderError::Gpu(e.to_string()))
    }

    /// Reads back the tone-mapped output of the last display frame as RGBA8 (sRGB-encoded).
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn read_display(&self) -> Result<Vec<u8>> {
        let t = self.targets.as_ref().ok_or_else(|| RenderError::Invalid("no frame rendered yet".into()))?;
        read_texture(&self.device, &self.queue, &t.display, 4)
    }

    /// Reads back the linear output of the last linear frame (RGBA f32).
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn read_linear(&self) -> Result<Vec<[f32; 4]>> {
        let t = self.targets.as_ref().ok_or_else(|| RenderError::Invalid("no frame rendered yet".into()))?;
        let bytes = read_texture(&self.device, &self.queue, &t.linear, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Reads back the intermediate images of the last frame.
    ///
    /// # Errors
    /// Without a frame, or if the GPU fails.
    pub fn capture(&self) -> Result<FrameCapture> {
        let t = self.targets.as_ref().ok_or_else(|| RenderError::Invalid("no frame rendered yet".into()))?;
        let half4 = |tex: &wgpu::Texture| -> Result<Vec<[f32; 4]>> {
            let bytes = read_texture(&self.device, &self.queue, tex, 8)?;
            let halves: Vec<u16> = bytemuck::pod_collect_to_vec(&bytes);
            Ok(halves.chunks_exact(4).map(|c| std::array::from_fn(|i| half::f16::from_bits(c[i]).to_f32())).collect())
        };
        let diffuse = half4(&t.diffuse)?;
        let scattered = if self.last_sss_ran { half4(&t.scattered)? } else { diffuse.clone() };
        let layers = self.last_variant.map_or(0, |v| v.layers);
        let exit_t = if layers > 0 { half4(&t.exit_t)? } else { vec![[1.0; 4]; diffuse.len()] };
        let thickness = if layers > 0 { half4(&t.thickness_a)? } else { vec![[0.0; 4]; diffuse.len()] };
        let depth_bytes = read_texture(&self.device, &self.queue, &t.depth, 4)?;
        let depth: Vec<f32> = bytemuck::pod_collect_to_vec(&depth_bytes);
        let (n, f) = (self.last_near, self.last_far);
        let depth_mm = depth.iter().map(|&d| n * f / (f - d * (f - n))).collect();
        Ok(FrameCapture {
            width: t.width as usize,
            height: t.height as usize,
            diffuse,
            scattered,
            surface: half4(&t.surface)?,
            exit_t,
            thickness,
            depth_mm,
            focal_px: self.last_focal_px,
        })
    }
}

fn color(v: &wgpu::TextureView, clear: wgpu::Color) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
    })
}

fn tex(binding: u32, v: &wgpu::TextureView) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) }
}

fn empty_look(device: &wgpu::Device) -> GpuLook {
    let maps =
        texture(device, "thickness maps", 1, 1, 1, wgpu::TextureFormat::R16Float, wgpu::TextureUsages::TEXTURE_BINDING);
    GpuLook {
        layers: 0,
        maps: array_view(&maps),
        texture: maps.clone(),
        size: (1, 1),
        tables: buffer_init(device, "layer tables", &[0u8; 16], wgpu::BufferUsages::STORAGE),
        params: [LayerUniform::default(); MAX_LAYERS],
    }
}

fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>> {
    let slice = buffer.slice(..size);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Gpu(e.to_string()))?;
    rx.recv()
        .map_err(|e| RenderError::Gpu(format!("buffer mapping was dropped: {e}")))?
        .map_err(|e| RenderError::Gpu(format!("buffer mapping failed: {e}")))?;
    let data = slice.get_mapped_range().map_err(|e| RenderError::Gpu(format!("mapped range: {e:?}")))?.to_vec();
    buffer.unmap();
    Ok(data)
}

/// Copies a 2D texture (one layer, `bytes_per_texel`) into tightly packed rows.
fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    tex: &wgpu::Texture,
    bytes_per_texel: u32,
) -> Result<Vec<u8>> {
    let (w, h) = (tex.width(), tex.height());
    let row = w * bytes_per_texel;
    let padded = row.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded as u64 * h as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    let aspect =
        if tex.format().is_depth_stencil_format() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture: tex, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(padded), rows_per_image: Some(h) },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let data = read_buffer(device, &buffer, padded as u64 * h as u64)?;
    let mut out = Vec::with_capacity((row * h) as usize);
    for y in 0..h as usize {
        out.extend_from_slice(&data[y * padded as usize..y * padded as usize + row as usize]);
    }
    Ok(out)
}
