//! A map's bands solved and classified on the device: the grid kernel's pass, then
//! `shaders/classify.wgsl` over its results in the same submission. A byte a point comes back
//! (16 for a whole result), and the whole results of the few points the host asks for.

use super::{storage, timer, trace, uniform, Classified, Entry, Gpu, GpuError, Variant, WORKGROUP};
use crate::kernel::layout::{ClassifyParams, GpuLambda, Out, Params};
use crate::kernel::start::Starts;
use crate::solver::Control;
use wgpu::util::DeviceExt;

/// A dispatch's buffers: the solver's (lambdas, rows, results), the f64 lambdas and loads, the
/// picks' indices, and the marks with the picked results, and their staging copy.
struct Bufs {
    lambdas: wgpu::Buffer,
    rows: wgpu::Buffer,
    lambdas64: wgpu::Buffer,
    loads64: wgpu::Buffer,
    states: wgpu::Buffer,
    pick: wgpu::Buffer,
    out: wgpu::Buffer,
    staging: wgpu::Buffer,
}

impl Gpu {
    /// The classification's bindings and pipeline, built on first use.
    fn classify_pipeline(&self) -> &(wgpu::BindGroupLayout, wgpu::ComputePipeline) {
        self.classify.get_or_init(|| {
            let entries = [
                uniform(0),
                storage(1, true),
                storage(2, true),
                storage(3, true),
                storage(4, true),
                storage(5, false),
            ];
            let source = crate::kernel::classify_source();
            let (layout, mut p) = self.own_pipelines("classify", source, &entries, &["classify"]);
            (layout, p.remove(0))
        })
    }

    /// Solves the grid `lambdas x rows` (row-major, one row per load; load control) and
    /// classifies each point on the device with tolerance `tol`, on the f64 lambdas and loads
    /// `grid64` (needs f64 shaders): returns a byte a point and the kernel's results at `picks`
    /// (point indices, ascending).
    pub fn grid_classified(
        &self,
        lambdas: &[GpuLambda],
        starts: &Starts,
        rows: &[(f32, f32)],
        grid64: (&[f64], &[f64]),
        tol: f64,
        picks: &[usize],
    ) -> Result<Classified, GpuError> {
        if !self.classifies {
            return Err(GpuError::NoF64(self.adapter.name.clone()));
        }
        let t0 = std::time::Instant::now();
        let (lambdas, words) = super::grid_input(lambdas, starts, rows);
        let (nx, total) = (lambdas.len(), lambdas.len() * rows.len());
        let mut res = Classified {
            marks: Vec::with_capacity(total),
            picked: Vec::with_capacity(picks.len()),
        };
        if total == 0 {
            return Ok(res);
        }
        self.fits(&lambdas, words.len() * 4, total)?;
        let solve = self.pipeline(Variant {
            entry: Entry::Grid,
            control: Control::Load,
            rows_are_gaps: false,
            naive: false,
        })?;
        let classify = self.classify_pipeline();
        self.check()?;
        // Whole words of marks in every dispatch but the last.
        let mut chunk = self.chunk_points(total, std::mem::size_of::<Out>(), 0);
        if chunk < total {
            chunk = (chunk / 4).max(1) * 4;
        }
        let b = self.classify_buffers(&lambdas, &words, grid64, chunk, picks.len().min(chunk));
        let base = ClassifyParams {
            nx: nx as u32,
            ..crate::kernel::cpu::classify::params(tol)
        };
        let (mut start, mut next_pick) = (0usize, 0usize);
        while start < total {
            let n = chunk.min(total - start);
            let end = next_pick + picks[next_pick..].partition_point(|&i| i < start + n);
            let local: Vec<u32> = picks[next_pick..end]
                .iter()
                .map(|&i| (i - start) as u32)
                .collect();
            next_pick = end;
            let p = ClassifyParams {
                offset: start as u32,
                count: n as u32,
                picks: local.len() as u32,
                marks_words: n.div_ceil(4) as u32,
                ..base
            };
            self.classify_dispatch(&solve, classify, &b, p, &local, &mut res)?;
            start += n;
        }
        if trace() {
            eprintln!(
                "gpu trace: grid classified on the device, {total} points in {} dispatches: {:.4} s",
                total.div_ceil(chunk),
                t0.elapsed().as_secs_f64()
            );
        }
        Ok(res)
    }

    /// The buffers of a classified grid: dispatches of `chunk` points, at most `picks` picked.
    fn classify_buffers(
        &self,
        lambdas: &[GpuLambda],
        rows: &[u32],
        (lambdas64, loads64): (&[f64], &[f64]),
        chunk: usize,
        picks: usize,
    ) -> Bufs {
        let d = &self.device;
        let init = |label, contents: &[u8]| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let buffer = |label, size: usize, usage| {
            d.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let out_bytes = (chunk.div_ceil(4) + 4 * picks) * 4;
        Bufs {
            lambdas: init("lambdas", bytemuck::cast_slice(lambdas)),
            rows: init("rows", bytemuck::cast_slice(rows)),
            lambdas64: init("lambdas64", bytemuck::cast_slice(lambdas64)),
            loads64: init("loads64", bytemuck::cast_slice(loads64)),
            states: buffer("states", chunk * std::mem::size_of::<Out>(), U::STORAGE),
            pick: buffer("picks", picks.max(1) * 4, U::STORAGE | U::COPY_DST),
            out: buffer("marks", out_bytes, U::STORAGE | U::COPY_SRC),
            staging: buffer("staging", out_bytes, U::MAP_READ | U::COPY_DST),
        }
    }

    /// One dispatch: the grid kernel's pass, the classification's, one copy back.
    fn classify_dispatch(
        &self,
        solve: &wgpu::ComputePipeline,
        (layout, classify): &(wgpu::BindGroupLayout, wgpu::ComputePipeline),
        b: &Bufs,
        p: ClassifyParams,
        local: &[u32],
        res: &mut Classified,
    ) -> Result<(), GpuError> {
        let d = &self.device;
        let sp = Params {
            nx: p.nx,
            offset: p.offset,
            count: p.count,
            max_iter: 0,
        };
        let sparams = self.uniform_buffer(bytemuck::bytes_of(&sp));
        let cparams = self.uniform_buffer(bytemuck::bytes_of(&p));
        let group = |layout, bufs: &[&wgpu::Buffer]| self.bind_whole("classify", layout, bufs);
        let solve_group = group(&self.layout, &[&sparams, &b.lambdas, &b.rows, &b.states]);
        let classify_group = group(
            layout,
            &[
                &cparams,
                &b.lambdas64,
                &b.loads64,
                &b.states,
                &b.pick,
                &b.out,
            ],
        );
        if !local.is_empty() {
            self.queue
                .write_buffer(&b.pick, 0, bytemuck::cast_slice(local));
        }
        let n = p.count as usize;
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("classify"),
        });
        let timer = self.timestamps.then(|| timer::Timer::new(d, 2));
        let desc = |k| wgpu::ComputePassDescriptor {
            label: Some("classify"),
            timestamp_writes: timer.as_ref().map(|t| t.writes(k)),
        };
        {
            let mut pass = enc.begin_compute_pass(&desc(0));
            pass.set_pipeline(solve);
            pass.set_bind_group(0, &solve_group, &[]);
            pass.dispatch_workgroups(n.div_ceil(WORKGROUP) as u32, 1, 1);
        }
        {
            let mut pass = enc.begin_compute_pass(&desc(1));
            pass.set_pipeline(classify);
            pass.set_bind_group(0, &classify_group, &[]);
            let threads = n.div_ceil(4).max(local.len());
            pass.dispatch_workgroups(threads.div_ceil(WORKGROUP) as u32, 1, 1);
        }
        if let Some(t) = &timer {
            t.resolve(&mut enc);
        }
        let marks_bytes = p.marks_words as usize * 4;
        let bytes = (marks_bytes + 16 * local.len()) as u64;
        enc.copy_buffer_to_buffer(&b.out, 0, &b.staging, 0, bytes);
        let t0 = std::time::Instant::now();
        self.queue.submit([enc.finish()]);
        let mut raw: Vec<u8> = Vec::with_capacity(bytes as usize);
        let t_wait = self.read_back(&b.staging, bytes, t0, &mut raw)?;
        b.staging.unmap();
        res.marks.extend_from_slice(&raw[..n]);
        res.picked
            .extend(bytemuck::pod_collect_to_vec::<u8, Out>(&raw[marks_bytes..]));
        if trace() {
            let secs = timer.and_then(|t| t.seconds(d, self.queue.get_timestamp_period()));
            eprintln!(
                "gpu trace:   classified dispatch of {n}: compute and copy {t_wait:.4} s, read back {:.4} s ({bytes} bytes){}",
                t0.elapsed().as_secs_f64() - t_wait,
                timer::shown(secs.as_deref())
            );
        }
        self.check()
    }
}
