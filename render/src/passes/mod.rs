//! One module per pass of the frame (\[Huang2013\] figure 1). Each pass module declares, in one
//! place, its shader ([`PassShader`]: WGSL file and variant reduction), what the plan gives each
//! of its steps ([`FramePass::Step`]), its name in timings and `--explain`, the targets it reads
//! and writes, and one `record` from those to its outputs; it owns its bind-group layout,
//! pipelines per reduced [`Variant`] (built on first use) and uniform structs.
//!
//! [`frame_passes!`] below registers every pass once: it makes the frame's [`Step`] (one variant
//! per pass, holding the pass's step), the renderer's set of passes, the dispatch from a step to
//! its pass, and the list of shaders the tests validate. [`crate::frame`] decides which steps run;
//! [`crate::Renderer::render`] records them in order through [`Passes::record`], and never looks
//! at the scene again. Labels name the owner (`"LightingPass::pipeline"`), so validation errors
//! point at the file.
//!
//! How to add a pass: docs/ARCHITECTURE.md, "How to add a pass".

pub mod back_depth;
pub mod bounce;
pub mod composite;
pub mod cube_atlas;
pub mod depth_copy;
pub mod dipole;
pub mod edge_overdraw;
pub mod gbuffer;
pub mod hair;
pub mod lighting;
pub mod shadow;
pub mod skin_gather;
pub mod sss;
pub mod thickness;

use crate::error::Result;
use crate::gpu_look::{GpuLook, SkinTextures};
use crate::gpu_mesh::GpuMesh;
use crate::profiler::Profiler;
use crate::shader::{PassShader, Variant, shader_source};
use crate::silhouettes::FrameEdgeStats;
use crate::targets::{DEPTH_FORMAT, Formats, TargetPool};
use crate::uniforms::FrameUniform;
use crate::wgpu_util::{layout, texture, uniform_buffer, uniform_entry, view};

/// A pass of the frame, as the registry ([`frame_passes!`]) takes it.
pub trait FramePass: Sized {
    /// What the plan gives each step of this pass (its slots, directions, uniforms' contents).
    type Step: Clone + std::fmt::Debug + PartialEq;
    /// The pass's shader.
    const SHADER: PassShader;
    /// The pass on `shared`'s device.
    fn new(shared: &Shared) -> Self;
    /// The step's name, as in timings and `--explain`.
    fn name(step: &Self::Step) -> String;
    /// Records `step` into the frame.
    ///
    /// # Errors
    /// When a pipeline cannot be built or a target is missing.
    fn record(&mut self, rec: &mut Recording<'_>, step: &Self::Step) -> Result<()>;
}

/// Registers the frame's passes: `Step variant => field: pass type`, in no particular order (the
/// plan orders the steps). Adding a pass adds one line here.
macro_rules! frame_passes {
    ($($(#[$doc:meta])* $step:ident => $field:ident: $pass:ty),* $(,)?) => {
        /// One step of the frame: a pass, with what the plan gives it.
        #[derive(Clone, Debug, PartialEq)]
        #[allow(clippy::large_enum_variant, reason = "a frame has a dozen steps; the SSS kernel's samples travel by value")]
        pub enum Step {
            $($(#[$doc])* $step(<$pass as FramePass>::Step),)*
        }

        impl Step {
            /// The step's name, as in timings and `--explain`.
            pub fn name(&self) -> String {
                match self {
                    $(Step::$step(s) => <$pass>::name(s),)*
                }
            }
        }

        /// Every pass of the frame.
        #[derive(Debug)]
        pub(crate) struct Passes {
            $(pub(crate) $field: $pass,)*
        }

        impl Passes {
            /// Every pass on `shared`'s device.
            pub(crate) fn new(shared: &Shared) -> Passes {
                Passes { $($field: <$pass>::new(shared),)* }
            }

            /// Records `step` with its pass.
            pub(crate) fn record(&mut self, rec: &mut Recording<'_>, step: &Step) -> Result<()> {
                match step {
                    $(Step::$step(s) => self.$field.record(rec, s),)*
                }
            }
        }

        /// The shaders of every pass, the frame's and the depth copy (which runs on demand).
        #[cfg(test)]
        pub(crate) const SHADERS: &[&PassShader] = &[$(&<$pass as FramePass>::SHADER,)* &depth_copy::SHADER];
    };
}

frame_passes! {
    /// Depth of the mesh from one light into its layer of the shadow maps.
    Shadow => shadow: shadow::ShadowPass,
    /// The G-buffer.
    Gbuffer => gbuffer: gbuffer::GbufferPass,
    /// Lighting through the cosmetic stack.
    Lighting => lighting: lighting::LightingPass,
    /// The depth of the mesh's back faces, where the camera's ray leaves it (the slab law's).
    BackDepth => back_depth: back_depth::BackDepthPass,
    /// Thickness translucency added to the skin's diffuse radiance.
    Thickness => thickness: thickness::ThicknessPass,
    /// The dipole models' light G-buffer, one view per directional light.
    DipoleLight => dipole_light: dipole::light::DipoleLightPass,
    /// The dipole models' K radiance maps.
    DipoleRadiance => dipole_radiance: dipole::radiance::DipoleRadiancePass,
    /// The dipole models' combination, added to the skin's diffuse radiance.
    DipoleCombine => dipole_combine: dipole::combine::DipoleCombinePass,
    /// The cube atlas's six faces of irradiance, drawn from the current mesh.
    AtlasIrradiance => atlas_irradiance: cube_atlas::irradiance::AtlasIrradiancePass,
    /// The cube atlas's gather, added to the skin's diffuse radiance.
    AtlasGather => atlas_gather: cube_atlas::gather::AtlasGatherPass,
    /// One direction of the screen-space scattering blur.
    Sss => sss: sss::SssPass,
    /// One bounce of the skin's glow between parts that face each other.
    Bounce => bounce: bounce::BouncePass,
    /// The lashes and brows as fibres, into the hair target the composite lays over the frame.
    Hair => hair: hair::HairPass,
    /// Composition of the skin radiance (diffuse or scattered) with the surface radiance.
    Composite => composite: composite::CompositePass,
    /// Discontinuity edges drawn over the display image (\[Sander2001\]).
    EdgeOverdraw => edge_overdraw: edge_overdraw::EdgeOverdrawPass,
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
    /// Trilinear, repeating: the skin's tiled detail.
    pub repeat_sampler: wgpu::Sampler,

    /// A 1×1 Rgba16Float texture bound where a variant reads nothing.
    pub dummy: wgpu::TextureView,
    /// A 1×1 texture of the glitter target's (unsigned integer) format, for the same.
    pub dummy_uint: wgpu::TextureView,
}

impl Shared {
    /// The shared objects on `device`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, formats: Formats) -> Shared {
        let frame_layout = layout(
            device,
            "Shared::frame",
            &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE)],
        );
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
        let repeat_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("Shared::repeat_sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let dummy_of =
            |label, format| texture(device, label, (1, 1), 1, format, wgpu::TextureUsages::TEXTURE_BINDING, &[]);
        let dummy = dummy_of("Shared::dummy", crate::targets::HDR_FORMAT);
        let dummy_uint = dummy_of("Shared::dummy_uint", crate::targets::GLITTER_FORMAT);
        Shared {
            device: device.clone(),
            queue: queue.clone(),
            formats,
            frame_layout,
            frame_buffer,
            frame_group,
            linear_sampler,
            shadow_sampler,
            repeat_sampler,
            dummy: view(&dummy),
            dummy_uint: view(&dummy_uint),
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
    HairSegments,
}

/// What differs between the passes' pipelines.
#[derive(Debug)]
pub struct PipelineSpec<'a> {
    /// The pass's shader (file and label).
    pub shader: &'static PassShader,
    /// The variant, already reduced with the shader's [`PassShader::reduce`].
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

impl<'a> PipelineSpec<'a> {
    /// A depth-only pipeline of the mesh's positions in the bare variant, with no colour target
    /// (the shadow and back-face depth passes'): `fs`, if any, only discards.
    pub fn mesh_depth(
        shader: &'static PassShader,
        layout: &'a wgpu::BindGroupLayout,
        vs: &'a str,
        fs: Option<&'a str>,
        bias: wgpu::DepthBiasState,
    ) -> PipelineSpec<'a> {
        PipelineSpec {
            shader,
            variant: Variant::BARE,
            layout,
            vertices: Vertices::MeshPositions,
            vs,
            fs,
            targets: vec![],
            blend: None,
            depth: Some(bias),
        }
    }
}

/// Builds the render pipeline of `spec` (shader specialised, group 0 = the frame).
///
/// # Errors
/// [`crate::RenderError::Shader`] when the shader source breaks a preprocessor rule.
pub fn build_pipeline(shared: &Shared, spec: &PipelineSpec<'_>) -> Result<wgpu::RenderPipeline> {
    let device = &shared.device;
    let label = format!("{}::pipeline {:?}", spec.shader.owner, spec.variant);
    let source = shader_source(spec.shader, spec.variant, shared.formats.half_linear())?;
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
        Vertices::Mesh => crate::gpu_mesh::full_layouts().map(Some).to_vec(),
        Vertices::MeshPositions => vec![Some(crate::gpu_mesh::position_layout())],
        Vertices::EdgeInstances => vec![Some(edge_overdraw::instance_layout())],
        Vertices::HairSegments => vec![Some(hair::instance_layout())],
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

/// What the passes record a frame with: the shared objects, the frame's targets and variant,
/// the encoder, and what is uploaded (mesh, look, skin textures, the subsurface models' resources,
/// the edges). Made by [`crate::Renderer`] for one frame; the steps carry the rest.
#[derive(Debug)]
pub struct Recording<'a> {
    /// Device, frame uniform, samplers.
    pub shared: &'a Shared,
    /// The targets the plan created.
    pub targets: &'a TargetPool,
    /// The frame's variant (each pass reduces it with its [`PassShader::reduce`]).
    pub variant: Variant,
    /// The frame's encoder.
    pub enc: FrameEncoder<'a>,
    /// The mesh.
    pub mesh: &'a GpuMesh,
    /// Counts mesh uploads (the dipole maps depend on the mesh).
    pub mesh_generation: u64,
    /// The look's tables and thickness maps.
    pub look: &'a GpuLook,
    /// The skin's albedo, normal and local-thickness textures.
    pub textures: &'a SkinTextures,
    /// The shadow-map array (a stand-in when no light casts shadows).
    pub shadow_maps: wgpu::TextureView,
    /// The dipole models' maps and their accumulation.
    pub dipole: &'a mut dipole::DipoleResources,
    /// The cube atlas.
    pub atlas: &'a mut cube_atlas::AtlasResources,
    /// The mesh's discontinuity edges, when prepared.
    pub edges: Option<&'a mut edge_overdraw::GpuEdges>,
    /// Whether unsorted edge overdraw has the GPU classify every edge.
    pub edge_gpu_classify: bool,
    /// The camera's position, mm (the edges' classification and sort).
    pub eye: glam::Vec3,
    /// Edge counts of this frame's edge list, when the CPU made one (set by the pass).
    pub edge_stats: Option<FrameEdgeStats>,
    /// The mesh's strands, when the hair pass runs.
    pub hair: Option<&'a mut hair::HairStrands>,
    /// The hairs' colours.
    pub hair_albedo: crate::HairAlbedo,
}

impl Recording<'_> {
    /// The frame's variant reduced for `shader`.
    pub fn key(&self, shader: &PassShader) -> Variant {
        (shader.reduce)(self.variant)
    }
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
    /// Begins a compute pass named `label` (timed like [`FrameEncoder::begin`]'s).
    pub fn begin_compute(&mut self, label: &str) -> wgpu::ComputePass<'_> {
        let timestamp_writes = self.profiler.as_mut().and_then(|p| p.compute_timestamp_writes(label));
        self.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes })
    }

    /// Draws `mesh` once per layer `0..layers` of the array textures `colours` and `depth`, each
    /// layer cleared (transparent, far) and drawn as instance `layer`, so that the vertex shader
    /// (`vs_layer`, shaders/layered_mesh.wgsl) picks the layer's view: the dipoles' light
    /// G-buffer and radiance maps, the cube atlas's faces. Bind group 0 is the frame's, 1 is `group`; `(pipeline, group)` draw it.
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

/// A pipeline cache keyed by the pass's reduced variant (render pipelines, or compute ones).
#[derive(Debug)]
pub struct Pipelines<P = wgpu::RenderPipeline>(std::collections::HashMap<Variant, P>);

impl<P> Default for Pipelines<P> {
    fn default() -> Self {
        Pipelines(Default::default())
    }
}

impl<P> Pipelines<P> {
    /// The pipeline for `variant`, built by `build` on first use.
    fn get_or_insert(&mut self, variant: Variant, build: impl FnOnce() -> Result<P>) -> Result<&P> {
        use std::collections::hash_map::Entry;
        match self.0.entry(variant) {
            Entry::Occupied(e) => Ok(e.into_mut()),
            Entry::Vacant(e) => Ok(e.insert(build()?)),
        }
    }
}

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
        self.get_or_insert(variant, || build_pipeline(shared, &spec()))
    }
}

impl Pipelines<wgpu::ComputePipeline> {
    /// The compute pipeline of entry point `entry` of `shader` for `variant` (group 0 the
    /// frame's, group 1 `layout`), built on first use.
    ///
    /// # Errors
    /// [`crate::RenderError::Shader`] when the shader source breaks a preprocessor rule.
    pub fn get_or_build_compute(
        &mut self,
        shared: &Shared,
        (shader, variant): (&PassShader, Variant),
        layout: &wgpu::BindGroupLayout,
        entry: &str,
    ) -> Result<&wgpu::ComputePipeline> {
        self.get_or_insert(variant, || {
            let device = &shared.device;
            let label = format!("{}::compute {variant:?}", shader.owner);
            let source = shader_source(shader, variant, shared.formats.half_linear())?;
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&label),
                bind_group_layouts: &[Some(&shared.frame_layout), Some(layout)],
                immediate_size: 0,
            });
            Ok(device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&label),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            }))
        })
    }
}
