//! `rouge bench shading`: the same per-pixel work as a full-screen render pass (a fragment
//! shader writing a colour target, as every full-screen pass of Rouge's frame is) and as a
//! compute pass (a storage-texture write), on this device. It tells whether the frame's
//! full-screen passes are slow for their work or for the graphics pipeline of the device they
//! run on (docs/BENCHMARKS.md, "Renderer: frame time per pass": on the lent H200 each pass took
//! about ten times what the GPU's rates predict).
//!
//! Two kinds of work, on a 1280×720 RGBA16F image of pseudo-random values (never zeros):
//! - `blur 11 taps`: 11 texel loads along a row, weighted (the SSS passes' shape);
//! - `alu 64 steps`: 64 dependent steps of a multiply-add, a `fract` and a `sin` per channel.

use anyhow::{Context, Result};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct ShadingBenchArgs {
    /// Image width.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Passes timed per row, submitted together (after as many untimed ones).
    #[arg(long, default_value_t = 200)]
    pub passes: u32,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// One kind of work on one kind of pass.
#[derive(Debug, Serialize)]
struct Row {
    work: &'static str,
    pass: &'static str,
    ms_per_pass: f64,
    /// Texel bytes read and written per pass over the time (each tap counted), GB/s.
    gb_per_s: f64,
    device: String,
}

/// The work per pixel, spliced into the shader at `WORK`.
const WORKS: [(&str, &str, u32); 2] = [
    (
        "blur 11 taps",
        "var s = vec4<f32>(0.0);
         for (var k = -5; k <= 5; k++) {
             let q = clamp(p + vec2<i32>(2 * k, 0), vec2<i32>(0), size - 1);
             s += textureLoad(src, q, 0) * (1.0 / 11.0);
         }
         return s;",
        12,
    ),
    (
        "alu 64 steps",
        "var v = textureLoad(src, p, 0);
         for (var k = 0; k < 64; k++) { v = fract(v * 1.618034 + sin(v.yzwx)); }
         return v;",
        2,
    ),
];

const SHADER: &str = "
@group(0) @binding(0) var src: texture_2d<f32>;
@group(0) @binding(1) var dst: texture_storage_2d<rgba16float, write>;

fn work(p: vec2<i32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(src));
    WORK
}

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    return work(vec2<i32>(pos.xy));
}

@compute @workgroup_size(8, 8)
fn cs(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(src);
    if (id.x >= size.x || id.y >= size.y) { return; }
    textureStore(dst, vec2<i32>(id.xy), work(vec2<i32>(id.xy)));
}
";

pub fn run(args: &ShadingBenchArgs) -> Result<()> {
    if args.width == 0 || args.height == 0 || args.passes == 0 {
        anyhow::bail!("--width, --height and --passes must be positive");
    }
    let gpu = rouge_render::gpu::Gpu::headless()?;
    let (device, queue) = (&gpu.device, &gpu.queue);
    let size = wgpu::Extent3d { width: args.width, height: args.height, depth_or_array_layers: 1 };
    let texture = |label, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage,
            view_formats: &[],
        })
    };
    let src = texture("shading bench src", wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST);
    let dst =
        texture("shading bench dst", wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::STORAGE_BINDING);
    // Half floats in [0, 1) from a hash of the index: exponents 0-14, any mantissa.
    let texels: Vec<u8> = (0..size.width * size.height * 4)
        .flat_map(|i| ((i.wrapping_mul(2_654_435_761) >> 16) as u16 & 0x3bff).to_le_bytes())
        .collect();
    queue.write_texture(
        src.as_image_copy(),
        &texels,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(8 * size.width), rows_per_image: None },
        size,
    );
    let (src_view, dst_view) = (src.create_view(&Default::default()), dst.create_view(&Default::default()));
    let mut rows = Vec::new();
    for (work, body, texel_accesses) in WORKS {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(work),
            source: wgpu::ShaderSource::Wgsl(SHADER.replace("WORK", body).into()),
        });
        let render = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(work),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::TextureFormat::Rgba16Float.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let compute = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(work),
            layout: None,
            module: &module,
            entry_point: Some("cs"),
            compilation_options: Default::default(),
            cache: None,
        });
        let group = |layout: wgpu::BindGroupLayout, with_dst: bool| {
            let mut entries =
                vec![wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src_view) }];
            if with_dst {
                entries
                    .push(wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&dst_view) });
            }
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(work),
                layout: &layout,
                entries: &entries,
            })
        };
        let (render_group, compute_group) =
            (group(render.get_bind_group_layout(0), false), group(compute.get_bind_group_layout(0), true));
        for pass in ["fragment", "compute"] {
            let encode = |n: u32| {
                let mut encoder = device.create_command_encoder(&Default::default());
                for _ in 0..n {
                    if pass == "fragment" {
                        let mut rp = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                            label: Some(work),
                            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                                view: &dst_view,
                                depth_slice: None,
                                resolve_target: None,
                                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                            })],
                            ..Default::default()
                        });
                        rp.set_pipeline(&render);
                        rp.set_bind_group(0, &render_group, &[]);
                        rp.draw(0..3, 0..1);
                    } else {
                        let mut cp = encoder.begin_compute_pass(&Default::default());
                        cp.set_pipeline(&compute);
                        cp.set_bind_group(0, &compute_group, &[]);
                        cp.dispatch_workgroups(size.width.div_ceil(8), size.height.div_ceil(8), 1);
                    }
                }
                encoder.finish()
            };
            let wait = || device.poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).context("waiting for the GPU");
            queue.submit([encode(args.passes)]);
            wait()?;
            let t = Instant::now();
            queue.submit([encode(args.passes)]);
            wait()?;
            let ms_per_pass = t.elapsed().as_secs_f64() * 1e3 / f64::from(args.passes);
            let bytes = f64::from(size.width * size.height) * 8.0 * f64::from(texel_accesses);
            rows.push(Row { work, pass, ms_per_pass, gb_per_s: bytes / (ms_per_pass * 1e6), device: gpu.describe() });
        }
    }
    let caption = format!(
        "The same work per pixel as a full-screen render pass and as a compute pass, {}×{} RGBA16F, {} passes in one submission (wall clock); {}",
        args.width,
        args.height,
        args.passes,
        gpu.describe()
    );
    let cells = rows.iter().map(|r| {
        vec![r.work.to_string(), r.pass.to_string(), format!("{:.4}", r.ms_per_pass), format!("{:.0}", r.gb_per_s)]
    });
    let table = crate::bench::report::markdown_table(&caption, &["work", "pass", "ms a pass", "texel GB/s"], 2, cells);
    crate::bench::report::emit_with_json(&table, &rows, args.json.as_deref())
}
