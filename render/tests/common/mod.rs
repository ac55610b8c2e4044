//! What the GPU twin tests share: a WGSL compute kernel run once over its cases on a real device
//! (lavapipe on CI), its output read back.

use rouge_render::Gpu;
use wgpu::util::DeviceExt;

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
