//! Per-pass GPU times from timestamp queries (where the adapter has them: Vulkan and lavapipe
//! do, wgpu's GL backend does not).

use crate::error::{RenderError, Result};
use crate::wgpu_util::read_buffer;

/// Most passes timed in one frame.
const MAX_TIMED_PASSES: u32 = 32;

/// GPU time of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass label ("shadow 0", "gbuffer", …).
    pub pass: String,
    /// Milliseconds.
    pub ms: f64,
}

/// Timestamp queries around each render pass of a frame.
#[derive(Debug)]
pub struct Profiler {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
    labels: Vec<String>,
}

impl Profiler {
    /// A profiler on `device`, or `None` when it has no timestamp queries.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Profiler> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let count = MAX_TIMED_PASSES * 2;
        let bytes = count as u64 * 8;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Profiler {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("Profiler::queries"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer("Profiler::resolve", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            readback: buffer("Profiler::readback", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            period_ns: queue.get_timestamp_period(),
            labels: Vec::new(),
        })
    }

    /// Starts a frame: forgets the previous frame's labels.
    pub fn begin_frame(&mut self) {
        self.labels.clear();
    }

    /// Timestamp writes for the next pass, labelled `label`; `None` once the frame has
    /// [`MAX_TIMED_PASSES`] passes.
    pub fn timestamp_writes(&mut self, label: &str) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let (begin, end) = self.next_pair(label)?;
        Some(wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(begin),
            end_of_pass_write_index: Some(end),
        })
    }

    /// [`Profiler::timestamp_writes`] for a compute pass.
    pub fn compute_timestamp_writes(&mut self, label: &str) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let (begin, end) = self.next_pair(label)?;
        Some(wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(begin),
            end_of_pass_write_index: Some(end),
        })
    }

    /// The query indices of the next timed pass, named `label` (none past the last).
    fn next_pair(&mut self, label: &str) -> Option<(u32, u32)> {
        let i = self.labels.len() as u32;
        if i >= MAX_TIMED_PASSES {
            return None;
        }
        self.labels.push(label.to_string());
        Some((2 * i, 2 * i + 1))
    }

    /// Records the copy of this frame's timestamps into the readback buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let timed = self.labels.len() as u32;
        if timed > 0 {
            encoder.resolve_query_set(&self.queries, 0..2 * timed, &self.resolve, 0);
            encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, 16 * timed as u64);
        }
    }

    /// The times of the submitted frame (blocks until the GPU is done).
    ///
    /// # Errors
    /// [`RenderError::Gpu`] if the readback fails.
    pub fn read(&mut self, device: &wgpu::Device) -> Result<Vec<PassTiming>> {
        let timed = self.labels.len();
        if timed == 0 {
            return Ok(Vec::new());
        }
        let bytes = read_buffer(device, &self.readback, 16 * timed as u64)?;
        let stamps: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        if stamps.len() < 2 * timed {
            return Err(RenderError::Gpu("short timestamp readback".into()));
        }
        let period = self.period_ns as f64;
        Ok(self
            .labels
            .drain(..)
            .enumerate()
            .map(|(i, pass)| {
                let ticks = stamps[2 * i + 1].saturating_sub(stamps[2 * i]);
                PassTiming { pass, ms: ticks as f64 * period * 1e-6 }
            })
            .collect())
    }
}
