//! Small wgpu helpers every pass uses: texture and buffer creation, bind-group layout entries,
//! attachments, and blocking readback of buffers and textures.

use crate::error::{RenderError, Result};

/// A 2D texture (or array of `layers`) with one mip level, also viewable in `view_formats`
/// (which needs `DownlevelFlags::VIEW_FORMATS` unless empty).
pub fn texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    layers: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: layers },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

/// The default view of a texture.
pub fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor::default())
}

/// A 2D-array view of every layer of a texture.
pub fn array_view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

/// A view of one layer of an array texture, as a render attachment.
pub fn layer_view(t: &wgpu::Texture, layer: u32) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_array_layer: layer,
        array_layer_count: Some(1),
        ..Default::default()
    })
}

/// A fragment-stage texture binding.
pub fn tex_entry(
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

/// A fragment-stage 2D float texture binding.
pub fn float_tex(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    tex_entry(binding, wgpu::TextureSampleType::Float { filterable }, wgpu::TextureViewDimension::D2)
}

/// A uniform buffer binding.
pub fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
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

/// A fragment-stage read-only storage buffer binding.
pub fn storage_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A fragment-stage sampler binding.
pub fn sampler_entry(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

/// A write-only storage texture of `format` for a compute pass's output.
pub fn storage_texture_entry(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

/// A bind-group layout from its entries.
pub fn layout(device: &wgpu::Device, label: &str, entries: &[wgpu::BindGroupLayoutEntry]) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries })
}

/// A bind-group entry for a texture view.
pub fn tex(binding: u32, v: &wgpu::TextureView) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) }
}

/// A bind-group entry for a whole buffer.
pub fn buf(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() }
}

/// A bind-group entry for a sampler.
pub fn sampler(binding: u32, s: &wgpu::Sampler) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::Sampler(s) }
}

/// A colour attachment cleared to `clear` and stored.
pub fn color(v: &wgpu::TextureView, clear: wgpu::Color) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
    })
}

/// A colour attachment that keeps what the target holds (for passes that add to it) and stores.
pub fn color_load(v: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
    })
}

/// A blend component that leaves the target's alpha as it is (the passes that blend colour into
/// a target whose alpha carries a flag or coverage).
pub const KEEP_DST_ALPHA: wgpu::BlendComponent = wgpu::BlendComponent {
    src_factor: wgpu::BlendFactor::Zero,
    dst_factor: wgpu::BlendFactor::One,
    operation: wgpu::BlendOperation::Add,
};

/// Adds the colour and keeps the target's alpha (the passes that add radiance to the skin's
/// diffuse target, whose alpha is the skin flag).
pub const ADD_RGB_KEEP_ALPHA: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: KEEP_DST_ALPHA,
};

/// A depth attachment cleared to the far plane and stored.
pub fn depth_clear(v: &wgpu::TextureView) -> Option<wgpu::RenderPassDepthStencilAttachment<'_>> {
    Some(wgpu::RenderPassDepthStencilAttachment {
        view: v,
        depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
        stencil_ops: None,
    })
}

/// A buffer holding `bytes` (at least 16 bytes, padded to 4).
pub fn buffer_init(device: &wgpu::Device, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
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

/// A uniform buffer of `size` bytes written with `queue.write_buffer`.
pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Maps the first `size` bytes of a `MAP_READ` buffer and copies them out, blocking.
///
/// # Errors
/// [`RenderError::Gpu`] if the device is lost or the mapping fails.
pub fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>> {
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

/// Copies a 2D texture (layer 0, `bytes_per_texel`) into tightly packed rows, blocking.
///
/// # Errors
/// [`RenderError::Gpu`] if the device is lost or the mapping fails.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    tex: &wgpu::Texture,
    bytes_per_texel: u32,
) -> Result<Vec<u8>> {
    read_texture_layer(device, queue, tex, 0, bytes_per_texel)
}

/// The texels of layer `layer` of `tex` (mip 0), rows packed, as [`read_texture`].
///
/// # Errors
/// When the GPU copy or the mapping fails.
pub fn read_texture_layer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    tex: &wgpu::Texture,
    layer: u32,
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
        wgpu::TexelCopyTextureInfo {
            texture: tex,
            mip_level: 0,
            origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
            aspect,
        },
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

/// Runs `work` inside wgpu error scopes (validation, internal, out of memory), so that an error
/// becomes a [`RenderError::Gpu`] naming `what` instead of reaching wgpu's default handler,
/// which panics.
///
/// # Errors
/// The error of `work`, or the wgpu error it caused.
pub fn validated<T>(device: &wgpu::Device, what: &str, work: impl FnOnce() -> Result<T>) -> Result<T> {
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let out = work();
    // Scopes pop innermost first.
    let errors = [memory.pop(), internal.pop(), validation.pop()].map(pollster::block_on);
    match (out, errors.into_iter().flatten().next()) {
        (Err(e), _) => Err(e),
        (Ok(_), Some(e)) => Err(RenderError::Gpu(format!("{what}: {e}"))),
        (Ok(v), None) => Ok(v),
    }
}

/// Rgba16Float texels (as read back) to f32.
pub fn halves_to_f32(bytes: &[u8]) -> Vec<[f32; 4]> {
    let halves: Vec<u16> = bytemuck::pod_collect_to_vec(bytes);
    halves.chunks_exact(4).map(|c| std::array::from_fn(|i| half::f16::from_bits(c[i]).to_f32())).collect()
}

/// A vertex buffer of per-instance data (`instances`; one zeroed instance, never drawn, when there
/// are none: a zero-sized vertex buffer cannot be bound), writable for later frames.
pub fn instance_buffer<T: bytemuck::Pod>(device: &wgpu::Device, label: &str, instances: &[T]) -> wgpu::Buffer {
    let zero = [T::zeroed()];
    let data: &[T] = if instances.is_empty() { &zero } else { instances };
    buffer_init(device, label, bytemuck::cast_slice(data), wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST)
}

/// This frame's `instances` in `slot`'s buffer (its capacity in instances beside it): written
/// into the buffer when they fit, else into a new one ([`instance_buffer`]) that replaces it.
pub fn write_instances<'a, T: bytemuck::Pod>(
    (device, queue): (&wgpu::Device, &wgpu::Queue),
    label: &str,
    slot: &'a mut Option<(wgpu::Buffer, usize)>,
    instances: &[T],
) -> &'a wgpu::Buffer {
    match slot {
        Some((buffer, capacity)) if *capacity >= instances.len() => {
            queue.write_buffer(buffer, 0, bytemuck::cast_slice(instances));
        }
        _ => *slot = Some((instance_buffer(device, label, instances), instances.len().max(1))),
    }
    let (buffer, _) = slot.get_or_insert_with(|| (instance_buffer::<T>(device, label, &[]), 1));
    buffer
}
