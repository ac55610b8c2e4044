//! Opening a GPU without a window.
//!
//! [`Gpu::headless`] picks the best adapter wgpu finds (backends from `WGPU_BACKEND`, adapter by
//! `WGPU_ADAPTER_NAME` when set) and falls back to a software adapter (Mesa lavapipe on Linux)
//! when there is no hardware GPU, as on CI. The app passes its own device to the renderer instead.

use crate::error::{RenderError, Result};

/// A device and queue, with what the renderer needs to know about the adapter.
#[derive(Debug)]
pub struct Gpu {
    /// The adapter the device was opened on.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Opens a device with no surface, requesting timestamp queries where the adapter has them.
    ///
    /// # Errors
    /// [`RenderError::Gpu`] when no adapter is found (with a hint to install Mesa's Vulkan
    /// drivers) or the device cannot be opened.
    pub fn headless() -> Result<Gpu> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let request = |force_fallback_adapter| {
            pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter,
                compatible_surface: None,
                apply_limit_buckets: false,
            }))
        };
        let adapter = request(false).or_else(|_| request(true)).map_err(|e| {
            let asked = std::env::var("WGPU_BACKEND").map(|b| format!(" (WGPU_BACKEND={b})")).unwrap_or_default();
            RenderError::Gpu(format!(
                "no GPU adapter found{asked}: {}. Without a GPU driver, install Mesa's software Vulkan \
                 driver (Debian/Ubuntu: apt-get install mesa-vulkan-drivers)",
                e.to_string().replace('\n', " ")
            ))
        })?;
        log::info!("adapter: {}", describe(&adapter.get_info()));
        Self::from_adapter(adapter)
    }

    /// Opens a device on `adapter`.
    ///
    /// # Errors
    /// [`RenderError::Gpu`] when the device cannot be opened.
    pub fn from_adapter(adapter: wgpu::Adapter) -> Result<Gpu> {
        let required_features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        // WebGPU's defaults, lowered where the adapter has less (wgpu's GL backend on Mesa has
        // fewer storage buffers per stage, for instance); the texture sizes of the adapter, and
        // its bytes of colour attachments per pixel (the G-buffer with glitter takes 40, over
        // WebGPU's default 32; Vulkan, GL and DX12 adapters offer more).
        let mut required_limits =
            wgpu::Limits::default().using_resolution(adapter.limits()).or_worse_values_from(&adapter.limits());
        required_limits.max_color_attachment_bytes_per_sample = adapter
            .limits()
            .max_color_attachment_bytes_per_sample
            .max(required_limits.max_color_attachment_bytes_per_sample);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rouge"),
            required_features,
            required_limits,
            ..Default::default()
        }))
        .map_err(|e| RenderError::Gpu(format!("cannot open a device on {}: {e}", adapter.get_info().name)))?;
        Ok(Gpu { adapter, device, queue })
    }

    /// "name (backend, device type)", for reports and benchmark tables.
    pub fn describe(&self) -> String {
        describe(&self.adapter.get_info())
    }

    /// Whether per-pass GPU timestamps can be taken.
    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(wgpu::Features::TIMESTAMP_QUERY)
    }
}

/// "name (backend, device type, driver …)" of an adapter.
pub fn describe(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({:?}, {:?}, driver {} {})", info.name, info.backend, info.device_type, info.driver, info.driver_info)
}
