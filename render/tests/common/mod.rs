//! What the GPU twin tests share: a WGSL compute kernel run once over its cases on a real device
//! (lavapipe on CI), its output read back; and a frame of the builtin sphere seen from the front.
//! (Each test crate uses part of it.)
#![allow(dead_code)]

pub mod wedge;

use rouge_model::look::Look;
use rouge_model::mesh::load_mesh;
use rouge_render::renderer::FrameCapture;
use rouge_render::{Camera, Gpu, LightRig, Renderer, Scene, Skin};
use std::path::Path;
use wgpu::util::DeviceExt;

/// A frame of the builtin sphere (radius 25 mm) and how it was seen.
pub struct SphereFrame {
    /// The frame's buffers (`diffuse`: the skin's radiance before scattering).
    pub capture: FrameCapture,
    /// The camera, framing the sphere from the front.
    pub camera: Camera,
    /// The sphere's bounds (mm).
    pub bounds: rouge_model::mesh::Bounds,
    /// Width and height (pixels).
    pub size: usize,
}

/// The bare builtin sphere of `skin` at 96², without specular, seen from the front under the
/// front rig as `light` changes it (its lights and environment).
pub fn front_sphere(skin: Skin, light: impl FnOnce(&mut Scene)) -> SphereFrame {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let mesh = load_mesh(Some(Path::new("builtin:sphere")), 1.0, 0).expect("sphere");
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&mesh, skin.albedo).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    let mut scene = Scene::rig(LightRig::Front);
    light(&mut scene);
    scene.specular = false;
    scene.skin = skin;
    let bounds = r.mesh_bounds().expect("bounds");
    let camera = Camera::framing(&bounds, 0.0, 0.0);
    let size = 96;
    r.render(&scene, &camera, size as u32, size as u32, false).expect("render");
    SphereFrame { capture: r.capture().expect("capture"), camera, bounds, size }
}

/// Runs the entry point `main` of `source` (workgroup size 64) over `invocations` with the
/// `inputs` bound in group 0 (binding, bytes, usage: storage or uniform) and a storage output of
/// `output_bytes` at `output_binding`, and returns the output's bytes.
pub fn run_kernel(
    gpu: &Gpu,
    label: &str,
    source: &str,
    inputs: &[(u32, &[u8], wgpu::BufferUsages)],
    (output_binding, output_bytes): (u32, u64),
    invocations: u32,
) -> Vec<u8> {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let buffers: Vec<(u32, wgpu::Buffer)> = inputs
        .iter()
        .map(|&(binding, contents, usage)| {
            let init = wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage };
            (binding, device.create_buffer_init(&init))
        })
        .collect();
    let buffer = |usage| {
        let desc = wgpu::BufferDescriptor { label: Some(label), size: output_bytes, usage, mapped_at_creation: false };
        device.create_buffer(&desc)
    };
    let output = buffer(wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC);
    let readback = buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST);
    let mut entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .map(|(binding, b)| wgpu::BindGroupEntry { binding: *binding, resource: b.as_entire_binding() })
        .collect();
    entries.push(wgpu::BindGroupEntry { binding: output_binding, resource: output.as_entire_binding() });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
    {
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: None });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(invocations.div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, output_bytes);
    gpu.queue.submit([encoder.finish()]);
    let slice = readback.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    rx.recv().expect("mapping callback").expect("mapping");
    slice.get_mapped_range().expect("mapped range").to_vec()
}
