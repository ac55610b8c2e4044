//! One module per pass of the frame ([Huang2013] figure 1). Each pass owns its bind-group
//! layout, its pipelines per [`Variant`] (built on first use), its uniform structs, and one
//! `record` function from named inputs to named outputs. [`crate::frame`] decides which passes
//! run; [`crate::Renderer::render`] walks that plan.
//!
//! Labels name the owner (`"LightingPass::pipeline"`), so validation errors point at the file.

pub mod composite;
pub mod cube_atlas;
pub mod depth_copy;
pub mod dipole;
pub mod edge_overdraw;
pub mod gbuffer;
pub mod lighting;
pub mod shadow;
pub mod skin_gather;
pub mod sss;
pub mod thickness;

use crate::error::Result;
use crate::profiler::Profiler;
use crate::shader::{Variant, shader_source};
use crate::targets::{DEPTH_FORMAT, Formats};
use crate::uniforms::FrameUniform;
use crate::wgpu_util::{layout, texture, uniform_buffer, uniform_entry, view};

/// The passes, for shader sources, pipelines and timings.
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
    /// Thickness translucency ([BarreBrisebois2011]), added to the skin's diffuse radiance.
    Thickness,
    /// Composition and tone mapping.
    Composite,
    /// Depth into a colour target, for readback where depth cannot be copied (GL).
    DepthCopy,
    /// Discontinuity edge overdraw ([Sander2001]) over the composited image.
    EdgeOverdraw,
    /// The dipole models' light G-buffer.
    DipoleLight,
    /// The dipole models' radiance maps.
    DipoleRadiance,
    /// The dipole models' combination.
    DipoleCombine,
    /// The cube atlas's six faces of irradiance ([Benmounah2009]).
    AtlasIrradiance,
    /// The cube atlas's gather, added to the skin's diffuse radiance.
    AtlasGather,
}

impl Pass {
    /// Every pass.
    pub const ALL: [Pass; 13] = [
        Pass::Shadow,
        Pass::Gbuffer,
        Pass::Lighting,
        Pass::Sss,
        Pass::Thickness,
        Pass::Composite,
        Pass::DepthCopy,
        Pass::EdgeOverdraw,
        Pass::DipoleLight,
        Pass::DipoleRadiance,
        Pass::DipoleCombine,
        Pass::AtlasIrradiance,
        Pass::AtlasGather,
    ];

    /// The pass's WGSL file name (for errors).
    pub fn file_name(self) -> &'static str {
        match self {
            Pass::Shadow => "shaders/shadow.wgsl",
            Pass::Gbuffer => "shaders/gbuffer.wgsl",
            Pass::Lighting => "shaders/lighting.wgsl",
            Pass::Sss => "shaders/sss.wgsl",
            Pass::Thickness => "shaders/thickness.wgsl",
            Pass::Composite => "shaders/composite.wgsl",
            Pass::DepthCopy => "shaders/depth_copy.wgsl",
            Pass::DipoleLight => "shaders/dipole_light.wgsl",
            Pass::DipoleRadiance => "shaders/dipole_radiance.wgsl",
            Pass::DipoleCombine => "shaders/dipole_combine.wgsl",
            Pass::EdgeOverdraw => "shaders/edge_overdraw.wgsl",
            Pass::AtlasIrradiance => "shaders/atlas_irradiance.wgsl",
            Pass::AtlasGather => "shaders/atlas_gather.wgsl",
        }
    }

    /// The pass's WGSL source before preprocessing.
    pub fn source(self) -> &'static str {
        match self {
            Pass::Shadow => include_str!("../shaders/shadow.wgsl"),
            Pass::Gbuffer => include_str!("../shaders/gbuffer.wgsl"),
            Pass::Lighting => include_str!("../shaders/lighting.wgsl"),
            Pass::Sss => include_str!("../shaders/sss.wgsl"),
            Pass::Thickness => include_str!("../shaders/thickness.wgsl"),
            Pass::Composite => include_str!("../shaders/composite.wgsl"),
            Pass::DepthCopy => include_str!("../shaders/depth_copy.wgsl"),
            Pass::DipoleLight => include_str!("../shaders/dipole_light.wgsl"),
            Pass::DipoleRadiance => include_str!("../shaders/dipole_radiance.wgsl"),
            Pass::DipoleCombine => include_str!("../shaders/dipole_combine.wgsl"),
            Pass::EdgeOverdraw => include_str!("../shaders/edge_overdraw.wgsl"),
            Pass::AtlasIrradiance => include_str!("../shaders/atlas_irradiance.wgsl"),
            Pass::AtlasGather => include_str!("../shaders/atlas_gather.wgsl"),
        }
    }
}

/// What every pass shares: the device, the frame uniform and its bind group (group 0 of every
/// pipeline), samplers, a 1×1 stand-in texture, and the formats chosen for the adapter.
#[derive(Debug)]
pub struct Shared {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Formats chosen from the adapter's downlevel capabilities.
    pub formats: Formats,
    /// Layout of group 0 (the frame uniform).
    pub frame_layout: wgpu::BindGroupLayout,
    /// The frame uniform buffer.
    pub frame_buffer: wgpu::Buffer,
    /// Group 0.
    pub frame_group: wgpu::BindGroup,
    /// Bilinear, clamped.
    pub linear_sampler: wgpu::Sampler,
    /// Depth comparison for shadow maps.
    pub shadow_sampler: wgpu::Sampler,

    /// A 1×1 Rgba16Float texture bound where a variant reads nothing.
    pub dummy: wgpu::TextureView,
}

impl Shared {
    /// The shared objects on `device`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, formats: Formats) -> Shared {
        let frame_layout = layout(device, "Shared::frame", &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)]);
        let frame_buffer = uniform_buffer(device, "Shared::frame", std::mem::size_of::<FrameUniform>());
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("Shared::frame"),
            layout: &frame_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        let linear_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("Shared::linear_sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("Shared::shadow_sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let dummy = texture(
            device,
            "Shared::dummy",
            (1, 1),
            1,
            crate::targets::HDR_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING,
            &[],
        );
        Shared {
            device: device.clone(),
            queue: queue.clone(),
            formats,
            frame_layout,
            frame_buffer,
            frame_group,
            linear_sampler,
            shadow_sampler,
            dummy: view(&dummy),
        }
    }

    /// Writes this frame's uniform.
    pub fn write_frame(&self, frame: &FrameUniform) {
        self.queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(frame));
    }
}

/// How a pipeline reads vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vertices {
    /// No vertex buffer: one full-screen triangle from the vertex index.
    Fullscreen,
    /// The mesh with every attribute.
    Mesh,
    /// The mesh's positions only.
    MeshPositions,
    /// One discontinuity edge per instance ([`edge_overdraw::instance_layout`]).
    EdgeInstances,
}

/// What differs between the passes' pipelines.
#[derive(Debug)]
pub struct PipelineSpec<'a> {
    /// The pass (shader file and label).
    pub pass: Pass,
    /// The variant, already reduced with [`Variant::for_pass`].
    pub variant: Variant,
    /// Group 1 of the pipeline.
    pub layout: &'a wgpu::BindGroupLayout,
    /// Vertex input.
    pub vertices: Vertices,
    /// Vertex entry point.
    pub vs: &'a str,
    /// Fragment entry point, if any.
    pub fs: Option<&'a str>,
    /// Colour target formats by location (`None`: a location the variant leaves out).
    pub targets: Vec<Option<wgpu::TextureFormat>>,
    /// Blending into the colour targets (`None`: replace).
    pub blend: Option<wgpu::BlendState>,
    /// Depth test and write with this bias, if the pass has a depth buffer.
    pub depth: Option<wgpu::DepthBiasState>,
}

/// Builds the render pipeline of `spec` (shader specialised, group 0 = the frame).
///
/// # Errors
/// [`crate::RenderError::Shader`] when the shader source breaks a preprocessor rule.
pub fn build_pipeline(shared: &Shared, spec: &PipelineSpec<'_>) -> Result<wgpu::RenderPipeline> {
    let device = &shared.device;
    let label = format!("{:?}Pass::pipeline {:?}", spec.pass, spec.variant);
    let source = shader_source(spec.pass, spec.variant, shared.formats.encode_srgb_in_shader)?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&label),
        bind_group_layouts: &[Some(&shared.frame_layout), Some(spec.layout)],
        immediate_size: 0,
    });
    let buffers = match spec.vertices {
        Vertices::Fullscreen => vec![],
        Vertices::Mesh => vec![Some(crate::gpu_mesh::full_layout())],
        Vertices::MeshPositions => vec![Some(crate::gpu_mesh::position_layout())],
        Vertices::EdgeInstances => vec![Some(edge_overdraw::instance_layout())],
    };
    let targets: Vec<Option<wgpu::ColorTargetState>> = spec
        .targets
        .iter()
        .map(|format| {
            format.map(|format| wgpu::ColorTargetState {
                format,
                blend: spec.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })
        })
        .collect();
    Ok(device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(spec.vs),
            compilation_options: Default::default(),
            buffers: &buffers,
        },
        primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
        depth_stencil: spec.depth.map(|bias| wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            // A blended pass (the edge overdraw) tests depth but never writes it.
            depth_write_enabled: Some(spec.blend.is_none()),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias,
        }),
        multisample: Default::default(),
        fragment: spec.fs.map(|entry| wgpu::FragmentState {
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    }))
}

/// What every pass reads while recording a frame: the shared objects, the frame's targets and
/// the frame's shader variant.
#[derive(Clone, Copy, Debug)]
pub struct FrameContext<'a> {
    /// Device, frame uniform, samplers.
    pub shared: &'a Shared,
    /// The targets the plan created.
    pub targets: &'a crate::targets::TargetPool,
    /// The frame's variant (each pass reduces it with [`Variant::for_pass`]).
    pub variant: Variant,
}

/// The command encoder of a frame with its optional profiler: passes begin here.
#[derive(Debug)]
pub struct FrameEncoder<'a> {
    /// The frame's encoder.
    pub encoder: wgpu::CommandEncoder,
    /// Timestamps per pass, when profiling.
    pub profiler: Option<&'a mut Profiler>,
}

impl FrameEncoder<'_> {
    /// Begins a render pass labelled `label` (also its timing label).
    pub fn begin(
        &mut self,
        label: &str,
        color_attachments: &[Option<wgpu::RenderPassColorAttachment<'_>>],
        depth_stencil_attachment: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
    ) -> wgpu::RenderPass<'_> {
        let timestamp_writes = self.profiler.as_mut().and_then(|p| p.timestamp_writes(label));
        self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments,
            depth_stencil_attachment,
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }
}

impl FrameEncoder<'_> {
    /// Draws `mesh` once per layer `0..layers` of the array textures `colours` and `depth`, each
    /// layer cleared (transparent, far) and drawn as instance `layer`, so that the vertex shader
    /// picks the layer's view: the dipoles' light G-buffer and radiance maps, the cube atlas's
    /// faces. Bind group 0 is the frame's, 1 is `group`; `(pipeline, group)` draw it.
    pub fn draw_mesh_per_layer(
        &mut self,
        label: &str,
        shared: &Shared,
        (pipeline, group): (&wgpu::RenderPipeline, &wgpu::BindGroup),
        mesh: &crate::gpu_mesh::GpuMesh,
        (colours, depth): (&[&wgpu::Texture], &wgpu::Texture),
        layers: u32,
    ) {
        use crate::wgpu_util::{color, depth_clear, layer_view};
        for layer in 0..layers {
            let views: Vec<wgpu::TextureView> = colours.iter().map(|t| layer_view(t, layer)).collect();
            let attachments: Vec<_> = views.iter().map(|v| color(v, wgpu::Color::TRANSPARENT)).collect();
            let depth = layer_view(depth, layer);
            let mut pass = self.begin(label, &attachments, depth_clear(&depth));
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &shared.frame_group, &[]);
            pass.set_bind_group(1, group, &[]);
            mesh.draw_instance(&mut pass, layer);
        }
    }
}

/// A pipeline cache keyed by the pass's reduced variant.
#[derive(Debug, Default)]
pub struct Pipelines(std::collections::HashMap<Variant, wgpu::RenderPipeline>);

impl Pipelines {
    /// The pipeline for `variant`, built with `spec` on first use.
    ///
    /// # Errors
    /// As [`build_pipeline`].
    pub fn get_or_build<'s>(
        &mut self,
        shared: &Shared,
        variant: Variant,
        spec: impl FnOnce() -> PipelineSpec<'s>,
    ) -> Result<&wgpu::RenderPipeline> {
        use std::collections::hash_map::Entry;
        match self.0.entry(variant) {
            Entry::Occupied(e) => Ok(e.into_mut()),
            Entry::Vacant(e) => Ok(e.insert(build_pipeline(shared, &spec())?)),
        }
    }
}
