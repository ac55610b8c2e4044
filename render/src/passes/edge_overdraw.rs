//! Discontinuity edge overdraw (\[Sander2001\], shaders/edge_overdraw.wgsl) after composition:
//! the display image is copied, and each discontinuity edge is drawn over it as a screen-space
//! quad with the analytic box-filter coverage of its face's side, shaded with that face's lit
//! colour read from the copy one pixel into the face's side, "over" blended, depth tested
//! against the G-buffer's depth and not written (chains of edges get no gaps, section 3.4).
//!
//! Two feeds of the same shader: the CPU's list of the edges to draw, in their order
//! ([`crate::silhouettes::EdgeFrames::frame`]; the default, measured faster), or every edge of
//! the mesh, uploaded once, with the vertex stage classifying each instance and collapsing the
//! hidden ones (brute force on the GPU, no CPU work per frame;
//! [`crate::Renderer::set_edge_gpu_classify`]).

use super::{FramePass, PipelineSpec, Pipelines, Recording, Shared, Vertices};
use crate::aa::EdgeCoverage;
use crate::error::{RenderError, Result};
use crate::shader::{PassShader, bare, pass_shader};
use crate::silhouettes::{EdgeFrames, EdgeInstance};
use crate::targets::Target;
use crate::wgpu_util::{
    buf, color_load, float_tex, instance_buffer, layout, tex, texture, uniform_entry, view, write_instances,
};
use bytemuck::{Pod, Zeroable};

/// Fraction of its distance from the eye by which an edge is pulled toward the eye for the depth
/// test, so that it wins against its own faces (whose depth near a silhouette changes fast) and
/// loses against surfaces a few percent nearer: the paper's polygon offset (section 4), applied
/// to the edges instead of the mesh so that the G-buffer pass is untouched.
pub const DEPTH_PULL: f32 = 0.01;

/// The pass's uniform, as `EdgePass` in shaders/edge_overdraw.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct EdgeUniform {
    /// x: bloat (pixels), y: depth pull, z: τ, w: unused.
    pub params: [f32; 4],
    /// x: 1 for two-sided coverage, y: 1 for a closed mesh.
    pub flags: [u32; 4],
}

impl EdgeUniform {
    /// The uniform for `coverage` on a mesh that is `closed` or not.
    pub fn new(coverage: EdgeCoverage, closed: bool) -> EdgeUniform {
        let (bloat, two_sided) = match coverage {
            EdgeCoverage::Line => (0.5, 0),
            EdgeCoverage::TwoSided => (0.0, 1),
        };
        EdgeUniform {
            params: [bloat, DEPTH_PULL, crate::edges::BLEND_THRESHOLD, 0.0],
            flags: [two_sided, u32::from(closed), 0, 0],
        }
    }
}

/// The per-instance vertex layout of [`EdgeInstance`].
pub fn instance_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTRIBUTES: [wgpu::VertexAttribute; 5] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Uint32, 2 => Float32x3, 3 => Float32x3, 4 => Float32x3
    ];
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<EdgeInstance>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &ATTRIBUTES,
    }
}

/// Vertices per instance: two quads (the double draw), six vertices each.
const VERTICES: u32 = 12;

/// The mesh's edges on the GPU.
#[derive(Debug)]
pub struct GpuEdges {
    /// The CPU side: preprocessed edges and the per-frame search.
    pub frames: EdgeFrames,
    /// Every edge that may be drawn (the brute-force feed), uploaded on first use.
    all: Option<wgpu::Buffer>,
}

impl GpuEdges {
    /// The edges of `frames`, for the GPU.
    pub fn new(frames: EdgeFrames) -> GpuEdges {
        GpuEdges { frames, all: None }
    }

    /// Moves the edges to a posed copy of their mesh; false for another mesh
    /// ([`EdgeFrames::reposition`]).
    pub fn reposition(&mut self, mesh: &rouge_model::mesh::TriangleMesh) -> bool {
        self.all = None;
        self.frames.reposition(mesh)
    }
}

/// The edge overdraw pass.
#[derive(Debug)]
pub struct EdgeOverdrawPass {
    layout: wgpu::BindGroupLayout,
    pipelines: Pipelines,
    uniform: wgpu::Buffer,
    /// The copy of the composited image the shader reads.
    copy: Option<wgpu::Texture>,
    /// This frame's sorted instances, grown as needed.
    sorted: Option<(wgpu::Buffer, usize)>,
}

/// The edge overdraw of a frame: the order of the edges and their coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeStep {
    /// Silhouettes and near-silhouette sharp edges sorted back to front on the CPU.
    pub sorted: bool,
    /// The coverage drawn.
    pub coverage: EdgeCoverage,
}

impl FramePass for EdgeOverdrawPass {
    type Step = EdgeStep;
    const SHADER: PassShader = pass_shader!(EdgeOverdrawPass, "edge_overdraw.wgsl", bare);

    fn new(shared: &Shared) -> EdgeOverdrawPass {
        let device = &shared.device;
        let layout = layout(
            device,
            "EdgeOverdrawPass::layout",
            &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT), float_tex(1, false)],
        );
        let uniform =
            crate::wgpu_util::uniform_buffer(device, "EdgeOverdrawPass::uniform", std::mem::size_of::<EdgeUniform>());
        EdgeOverdrawPass { layout, pipelines: Pipelines::default(), uniform, copy: None, sorted: None }
    }

    fn name(_: &EdgeStep) -> String {
        "edge overdraw".into()
    }

    /// Records the pass over [`Target::Display`]: the CPU's list of this frame's edges
    /// ([`EdgeFrames::frame`], sorted when the step says so) in its order, or, when the GPU is to
    /// classify them ([`Recording::edge_gpu_classify`], unsorted only), every edge of the mesh.
    fn record(&mut self, rec: &mut Recording<'_>, step: &EdgeStep) -> Result<()> {
        let (shared, targets) = (rec.shared, rec.targets);
        let device = &shared.device;
        let edges = rec.edges.as_deref_mut().ok_or_else(|| {
            RenderError::Invalid("edge antialiasing needs the mesh's edges: call prepare_edges".into())
        })?;
        // The CPU's list (search, classification, sort when asked) unless the GPU is to classify
        // every edge: `rouge bench aa` measured the list faster (the vertex stage over every edge
        // of the head costs more than the CPU's search).
        let sorted = (step.sorted || !rec.edge_gpu_classify).then(|| {
            let (list, stats) = edges.frames.frame(rec.eye, step.sorted);
            rec.edge_stats = Some(stats);
            list
        });
        let key = (Self::SHADER.reduce)(rec.variant);
        let format = Target::Display.format(shared.formats);
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::SrcAlpha,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: crate::wgpu_util::KEEP_DST_ALPHA,
        };
        let pipeline = self.pipelines.get_or_build(shared, key, || PipelineSpec {
            shader: &Self::SHADER,
            variant: key,
            layout: &self.layout,
            vertices: Vertices::EdgeInstances,
            vs: "vs_edge",
            fs: Some("fs_edge"),
            targets: vec![Some(format)],
            blend: Some(blend),
            depth: Some(wgpu::DepthBiasState::default()),
        })?;
        let display = targets
            .get(Target::Display)
            .ok_or_else(|| RenderError::Gpu("the display target was not created".into()))?;
        let size = (display.width(), display.height());
        if self.copy.as_ref().is_none_or(|c| (c.width(), c.height()) != size || c.format() != format) {
            let usage = wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING;
            self.copy = Some(texture(device, "EdgeOverdrawPass::copy", size, 1, format, usage, &[]));
        }
        let copy = self.copy.as_ref().ok_or_else(|| RenderError::Gpu("no copy texture".into()))?;
        rec.enc.encoder.copy_texture_to_texture(
            display.as_image_copy(),
            copy.as_image_copy(),
            wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
        );
        shared.queue.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&EdgeUniform::new(step.coverage, edges.frames.set.closed)),
        );
        let (buffer, count) = match sorted.as_deref() {
            None => {
                let all = edges.all.get_or_insert_with(|| {
                    instance_buffer(device, "EdgeOverdrawPass::instances", &edges.frames.all_instances())
                });
                (&*all, edges.frames.set.edges.len())
            }
            Some(list) => {
                let gpu = (device, &shared.queue);
                (write_instances(gpu, "EdgeOverdrawPass::instances", &mut self.sorted, list), list.len())
            }
        };
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("EdgeOverdrawPass::group"),
            layout: &self.layout,
            entries: &[buf(0, &self.uniform), tex(1, &view(copy))],
        });
        let out = targets.view(Target::Display)?;
        let depth = targets.view(Target::Depth)?;
        let depth_attachment = wgpu::RenderPassDepthStencilAttachment {
            view: &depth,
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        };
        let mut pass = rec.enc.begin("edge overdraw", &[color_load(&out)], Some(depth_attachment));
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &shared.frame_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..VERTICES, 0..count as u32);
        Ok(())
    }
}
