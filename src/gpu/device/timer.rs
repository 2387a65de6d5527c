//! Kernel time by timestamp queries (with `TABOR_GPU_TRACE=1`, on adapters that have them): the
//! time each compute pass took on the device, apart from submission, copies and read-back.

/// Timestamps around `passes` compute passes of one submission.
pub(super) struct Timer {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    passes: u32,
}

impl Timer {
    pub(super) fn new(d: &wgpu::Device, passes: u32) -> Timer {
        let bytes = 16 * passes as u64;
        let buffer = |label, usage| {
            d.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        Timer {
            set: d.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2 * passes,
            }),
            resolve: buffer("timestamps", U::QUERY_RESOLVE | U::COPY_SRC),
            read: buffer("timestamps read", U::MAP_READ | U::COPY_DST),
            passes,
        }
    }

    /// The timestamps of pass `k` (its start and end).
    pub(super) fn writes(&self, k: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(2 * k),
            end_of_pass_write_index: Some(2 * k + 1),
        }
    }

    /// Records the copy of the timestamps, after the passes.
    pub(super) fn resolve(&self, enc: &mut wgpu::CommandEncoder) {
        enc.resolve_query_set(&self.set, 0..2 * self.passes, &self.resolve, 0);
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 16 * self.passes as u64);
    }

    /// Each pass's seconds on the device, once the submission is done (`None` if the
    /// timestamps could not be read).
    pub(super) fn seconds(&self, d: &wgpu::Device, period_ns: f32) -> Option<Vec<f64>> {
        let slice = self.read.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        d.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        rx.recv().ok()?.ok()?;
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&slice.get_mapped_range().ok()?);
        self.read.unmap();
        Some(
            ticks
                .chunks(2)
                .map(|t| t[1].saturating_sub(t[0]) as f64 * period_ns as f64 * 1e-9)
                .collect(),
        )
    }
}

/// The trace's words for the passes' seconds.
pub(super) fn shown(secs: Option<&[f64]>) -> String {
    match secs {
        Some(s) => format!(
            ", kernels {} ms by timestamps",
            s.iter()
                .map(|x| format!("{:.3}", x * 1e3))
                .collect::<Vec<_>>()
                .join(" + ")
        ),
        None => String::new(),
    }
}
