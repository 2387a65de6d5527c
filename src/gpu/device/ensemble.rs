//! An explicit ensemble's stepping on the device (`shaders/ensemble64.wgsl`, f64): the summits
//! and the node tables are uploaded once, then each set of separations is summed in one
//! submission (a partial sum per chunk of summits and separation, then the chunks added in
//! order); the contact states next to a fold come back flagged, for the host's exact solve.

use super::{storage, timer, trace, uniform, Gpu, GpuError, WORKGROUP};
use crate::kernel::layout::{EnsembleParams, SummitRec};
use wgpu::util::DeviceExt;

/// An ensemble's summits and node tables on the device.
pub struct SummitBuffers {
    summits: wgpu::Buffer,
    coefs: wgpu::Buffer,
    nodes: wgpu::Buffer,
    n: usize,
    params: EnsembleParams,
}

/// The sums of one set of separations.
pub struct EnsembleSums {
    /// Per separation: approach force, area, contacts, non-contacts; then the retract's.
    pub sums: Vec<[f64; 8]>,
    /// The contact states left to the host: (summit, separation | leg << 31), leg 1 the
    /// retract, in no particular order.
    pub flagged: Vec<[u32; 2]>,
    /// The parameters the kernel ran with (its chunks: the mirror's order of summation).
    pub params: EnsembleParams,
}

/// Partial sums held at most (8 f64 each): 256 MB.
const PARTIALS_MAX: usize = 1 << 22;

impl Gpu {
    /// The stepping's bindings and its two pipelines, built on first use.
    fn ensemble_pipelines(
        &self,
    ) -> &(
        wgpu::BindGroupLayout,
        wgpu::ComputePipeline,
        wgpu::ComputePipeline,
    ) {
        self.ensemble.get_or_init(|| {
            let mut entries = vec![uniform(0)];
            entries.extend((1..5).map(|b| storage(b, true)));
            entries.extend((5..8).map(|b| storage(b, false)));
            let source = crate::kernel::ensemble64_source();
            let (layout, mut p) =
                self.own_pipelines("ensemble64", source, &entries, &["sum_chunks", "reduce"]);
            let reduce = p.remove(1);
            (layout, p.remove(0), reduce)
        })
    }

    /// Whether `summits` summits fit one binding (checked before their records are built).
    pub fn holds_summits(&self, summits: usize) -> bool {
        self.f64
            && self.storage_buffers >= 8
            && (summits * std::mem::size_of::<SummitRec>()) as u64 <= self.max_binding
    }

    /// Uploads an ensemble: its summits, and per node table (load, then area) its cubic
    /// coefficients, `nodes` giving each node's (first, intervals) of its load and area tables.
    /// `exact_below`, `inv_h` and `two_over_us` as in [`EnsembleParams`]. Needs f64 shaders and
    /// the summits within one binding.
    pub fn summit_buffers(
        &self,
        summits: &[SummitRec],
        coefs: &[[f64; 4]],
        nodes: &[[u32; 4]],
        (exact_below, inv_h, two_over_us): (f64, f64, f64),
    ) -> Result<SummitBuffers, GpuError> {
        if !self.f64 || self.storage_buffers < 8 {
            return Err(GpuError::NoF64(self.adapter.name.clone()));
        }
        let bytes = std::mem::size_of_val(summits).max(std::mem::size_of_val(coefs)) as u64;
        if bytes > self.max_binding || summits.is_empty() {
            return Err(GpuError::TooLarge(format!(
                "{} summits need {bytes} bytes, more than this adapter binds ({})",
                summits.len(),
                self.max_binding
            )));
        }
        let d = &self.device;
        let init = |label, contents: &[u8]| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        Ok(SummitBuffers {
            summits: init("summits", bytemuck::cast_slice(summits)),
            coefs: init("coefs", bytemuck::cast_slice(coefs)),
            nodes: init("nodes", bytemuck::cast_slice(nodes)),
            n: summits.len(),
            params: EnsembleParams {
                exact_below,
                inv_h,
                two_over_us,
                summits: summits.len() as u32,
                seps: 0,
                chunk: 0,
                chunks: 0,
                retract_only: 0,
                flag_cap: 0,
            },
        })
    }

    /// Every summit's states at the separations `seps` (m), summed; the retract's alone with
    /// `retract_only` (the approach's sums are then zero).
    pub fn summit_sums(
        &self,
        b: &SummitBuffers,
        seps: &[f64],
        retract_only: bool,
    ) -> Result<EnsembleSums, GpuError> {
        let t0 = std::time::Instant::now();
        let p = self.ensemble_params(b, seps, retract_only)?;
        let (ns, chunks, cap) = (seps.len().max(1), p.chunks as usize, p.flag_cap as usize);
        let (layout, sum_chunks, reduce) = self.ensemble_pipelines();
        self.check()?;
        let d = &self.device;
        use wgpu::BufferUsages as U;
        let buffer = |label, size: usize, usage| {
            d.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(8) as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        let params = self.uniform_buffer(bytemuck::bytes_of(&p));
        let seps_buf = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("separations"),
            contents: bytemuck::cast_slice(if seps.is_empty() { &[0.0] } else { seps }),
            usage: U::STORAGE,
        });
        let partials = buffer("partials", chunks * ns * 64, U::STORAGE);
        let flags = buffer("flags", 8 + cap * 8, U::STORAGE | U::COPY_SRC);
        let sums = buffer("sums", ns * 64, U::STORAGE | U::COPY_SRC);
        let staging = buffer("staging", ns * 64 + 8, U::MAP_READ | U::COPY_DST);
        let bufs = [
            &params, &b.summits, &b.coefs, &b.nodes, &seps_buf, &partials, &flags, &sums,
        ];
        let group = self.bind_whole("ensemble64", layout, &bufs);
        let mut enc = d.create_command_encoder(&Default::default());
        let timer = self.timestamps.then(|| timer::Timer::new(d, 2));
        for (k, (pipeline, threads)) in
            [(sum_chunks, chunks * seps.len()), (reduce, 8 * seps.len())]
                .into_iter()
                .enumerate()
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ensemble64"),
                timestamp_writes: timer.as_ref().map(|t| t.writes(k as u32)),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(threads.div_ceil(WORKGROUP).max(1) as u32, 1, 1);
        }
        if let Some(t) = &timer {
            t.resolve(&mut enc);
        }
        let sum_bytes = (seps.len() * 64) as u64;
        enc.copy_buffer_to_buffer(&sums, 0, &staging, 0, sum_bytes);
        enc.copy_buffer_to_buffer(&flags, 0, &staging, sum_bytes, 8);
        self.queue.submit([enc.finish()]);
        let mut raw: Vec<u8> = Vec::new();
        self.read_back(&staging, sum_bytes + 8, t0, &mut raw)?;
        staging.unmap();
        let out: Vec<f64> = bytemuck::pod_collect_to_vec(&raw[..sum_bytes as usize]);
        let word = |k: usize| {
            u32::from_le_bytes(raw[sum_bytes as usize + 4 * k..][..4].try_into().unwrap())
        };
        let (count, over) = (word(0) as usize, word(1));
        if over != 0 || count > cap {
            return Err(GpuError::TooLarge(format!(
                "{count} summit states next to their folds, more than the {cap} the device keeps"
            )));
        }
        let flagged = self.read_flags(&flags, count)?;
        if trace() {
            let secs = timer.and_then(|t| t.seconds(d, self.queue.get_timestamp_period()));
            eprintln!(
                "gpu trace: ensemble of {} summits at {} separations: {:.4} s, {count} states flagged{}",
                b.n,
                seps.len(),
                t0.elapsed().as_secs_f64(),
                timer::shown(secs.as_deref())
            );
        }
        self.check()?;
        Ok(EnsembleSums {
            sums: out.chunks_exact(8).map(|c| c.try_into().unwrap()).collect(),
            flagged,
            params: p,
        })
    }

    /// A run's parameters: chunks of summits (their partial sums bounded by [`PARTIALS_MAX`]) and
    /// room for flagged states; TooLarge where those would not fit one binding.
    fn ensemble_params(
        &self,
        b: &SummitBuffers,
        seps: &[f64],
        retract_only: bool,
    ) -> Result<EnsembleParams, GpuError> {
        let ns = seps.len().max(1);
        let chunks = b.n.div_ceil(1024).min((PARTIALS_MAX / ns).max(1));
        let cap = (4 * b.n).clamp(1 << 16, 1 << 24);
        let largest = (chunks * ns * 64).max(8 + cap * 8) as u64;
        if largest > self.max_binding {
            return Err(GpuError::TooLarge(format!(
                "an ensemble's sums need {largest} bytes, more than this adapter binds ({})",
                self.max_binding
            )));
        }
        Ok(EnsembleParams {
            seps: seps.len() as u32,
            chunk: b.n.div_ceil(chunks) as u32,
            chunks: chunks as u32,
            retract_only: retract_only as u32,
            flag_cap: cap as u32,
            ..b.params
        })
    }

    /// The first `count` flagged states of `flags` (after its 8-byte header).
    fn read_flags(&self, flags: &wgpu::Buffer, count: usize) -> Result<Vec<[u32; 2]>, GpuError> {
        if count == 0 {
            return Ok(Vec::new());
        }
        let bytes = (count * 8) as u64;
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("flags staging"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(flags, 8, &staging, 0, bytes);
        self.queue.submit([enc.finish()]);
        let mut out: Vec<[u32; 2]> = Vec::with_capacity(count);
        self.read_back(&staging, bytes, std::time::Instant::now(), &mut out)?;
        staging.unmap();
        Ok(out)
    }
}
