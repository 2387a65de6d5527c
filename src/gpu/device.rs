//! The wgpu context: adapter choice, device, pipelines and reusable buffers, and the chunked
//! dispatch with streamed readback.

use crate::kernel::layout::{
    control_code, GpuLambda, KernelFlags, Lambda64, Out, Out64, Params, Point64,
};
use crate::kernel::start::Starts;
use crate::solver::Control;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use wgpu::util::DeviceExt;

mod classify;
mod ensemble;
mod timer;

pub use ensemble::{EnsembleSums, SummitBuffers};

#[derive(Debug, thiserror::Error)]
/// Why the GPU path could not run; the caller falls back to the CPU or says so.
#[non_exhaustive]
pub enum GpuError {
    #[error("no GPU adapter was found (is a Vulkan driver installed? `apt-get install mesa-vulkan-drivers` gives a software one)")]
    /// No adapter at all.
    NoAdapter,
    #[error("no adapter name contains {wanted:?}; available: {available}")]
    /// No adapter's name contains the one asked for.
    NoMatch {
        /// The name asked for.
        wanted: String,
        /// The adapters there are.
        available: String,
    },
    #[error("could not open a device on {adapter}")]
    /// The adapter would not open a device.
    Device {
        /// The adapter's name.
        adapter: String,
        /// wgpu's error.
        #[source]
        err: wgpu::RequestDeviceError,
    },
    #[error("the GPU reported an error: {0}")]
    /// An error reported by the device while running.
    Runtime(String),
    #[error("{0}")]
    /// A problem too large for the device's buffers.
    TooLarge(String),
    #[error("the adapter {0} has no f64 shaders (SHADER_F64); use f32 precision, or the cpu backend for f64")]
    /// f64 precision asked of an adapter without f64 shaders.
    NoF64(String),
}

impl crate::error::Named for GpuError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            GpuError::NoF64(adapter) => format!(
                "the adapter {adapter} has no f64 shaders (SHADER_F64); use {}, or {} for f64",
                names("precision=f32").unwrap_or("f32 precision"),
                names("backend=cpu").unwrap_or("the cpu backend")
            ),
            e => e.to_string(),
        }
    }
}

/// A short description of an adapter, for `tabor info` and result metadata.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AdapterSummary {
    /// The adapter's name.
    pub name: String,
    /// Its graphics API (Vulkan, Metal, ...).
    pub backend: String,
    /// Discrete, integrated, virtual or CPU.
    pub device_type: String,
    /// The driver's name.
    pub driver: String,
    /// The driver's version text.
    pub driver_info: String,
    /// A software adapter (lavapipe, llvmpipe, SwiftShader), no faster than the CPU path.
    pub software: bool,
}

impl AdapterSummary {
    fn of(info: &wgpu::AdapterInfo) -> Self {
        AdapterSummary {
            name: info.name.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: info.driver.clone(),
            driver_info: info.driver_info.clone(),
            software: info.device_type == wgpu::DeviceType::Cpu,
        }
    }
}

/// Mesa's Vulkan loader probes Wayland and prints "XDG_RUNTIME_DIR is invalid or not set" on
/// every run where the variable is unset (ssh shells, containers, CI): that is not an error of
/// ours, so point it at a private folder before the first instance is made.
fn quiet_driver_probe() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
            // One private folder per user (the owner of /proc/self), reused across runs.
            #[cfg(unix)]
            let user = {
                use std::os::unix::fs::MetadataExt;
                std::fs::metadata("/proc/self").map_or(0, |m| m.uid())
            };
            #[cfg(not(unix))]
            let user = 0;
            let dir = std::env::temp_dir().join(format!("tabor-runtime-{user}"));
            let made = std::fs::create_dir_all(&dir).is_ok();
            #[cfg(unix)]
            if made {
                use std::os::unix::fs::PermissionsExt;
                let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
            }
            if made {
                std::env::set_var("XDG_RUNTIME_DIR", &dir);
            }
        }
    });
}

fn instance() -> wgpu::Instance {
    quiet_driver_probe();
    wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
}

/// Every adapter wgpu can see, with its features and limits.
pub fn list_adapters() -> Vec<(AdapterSummary, wgpu::Features, wgpu::Limits)> {
    let adapters = pollster::block_on(instance().enumerate_adapters(wgpu::Backends::all()));
    adapters
        .iter()
        .map(|a| (AdapterSummary::of(&a.get_info()), a.features(), a.limits()))
        .collect()
}

/// Picks an adapter: the first whose name contains `wanted` (case-insensitive), else a hardware
/// GPU, else a software one. Only adapters that can run compute shaders (Vulkan, Metal, DX12)
/// are considered.
fn choose_adapter(wanted: Option<&str>) -> Result<wgpu::Adapter, GpuError> {
    let mut adapters = pollster::block_on(instance().enumerate_adapters(wgpu::Backends::all()));
    adapters.retain(|a| {
        a.get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
    });
    if adapters.is_empty() {
        return Err(GpuError::NoAdapter);
    }
    if let Some(w) = wanted.filter(|w| !w.is_empty()) {
        let wl = w.to_lowercase();
        let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
        return adapters
            .into_iter()
            .find(|a| a.get_info().name.to_lowercase().contains(&wl))
            .ok_or(GpuError::NoMatch {
                wanted: w.into(),
                available: names.join(", "),
            });
    }
    let rank = |a: &wgpu::Adapter| match a.get_info().device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu | wgpu::DeviceType::Other => 2,
        wgpu::DeviceType::Cpu => 3,
    };
    adapters.sort_by_key(rank);
    Ok(adapters.remove(0))
}

/// What [`Gpu::new`] would run on, without making a device or compiling a shader: for
/// choosing a backend.
pub fn choose_summary(wanted: Option<&str>) -> Result<AdapterSummary, GpuError> {
    choose_adapter(wanted).map(|a| AdapterSummary::of(&a.get_info()))
}

/// The kernels' entry points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Entry {
    /// A lambda x load grid (`shaders/solve.wgsl`).
    Grid,
    /// A list of points.
    Points,
    /// The kernels' own functions at given arguments.
    Probe,
    /// The f64 refinement (`shaders/polish64.wgsl`, its own module).
    Polish,
}

impl Entry {
    fn name(self) -> &'static str {
        match self {
            Entry::Grid => "grid",
            Entry::Points => "points",
            Entry::Probe => "probe",
            Entry::Polish => "polish",
        }
    }
}

/// One kernel variant: the entry point and the values of its pipeline overrides.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Variant {
    entry: Entry,
    control: Control,
    rows_are_gaps: bool,
    naive: bool,
}

impl Variant {
    /// The WGSL `override` constants (names as in `shaders/md.wgsl` and `polish64.wgsl`).
    fn overrides(&self) -> Vec<(&'static str, f64)> {
        let mut v = vec![
            ("CONTROL", control_code(self.control) as f64),
            ("ROWS_ARE_GAPS", self.rows_are_gaps as u32 as f64),
        ];
        // The f64 module has no NAIVE override.
        if self.entry != Entry::Polish {
            v.push(("NAIVE", self.naive as u32 as f64));
        }
        v
    }
}

/// Device, queue, the shader module and its pipelines (compiled on first use, then reused).
pub struct Gpu {
    /// The adapter in use.
    pub adapter: AdapterSummary,
    device: wgpu::Device,
    queue: wgpu::Queue,
    layout: wgpu::BindGroupLayout,
    module: wgpu::ShaderModule,
    /// The f64 refinement's module, built on first use.
    polish_module: std::sync::OnceLock<wgpu::ShaderModule>,
    pipeline_layout: wgpu::PipelineLayout,
    pipelines: Mutex<HashMap<Variant, wgpu::ComputePipeline>>,
    /// At most this many points per dispatch (0: as the limits allow); see `limit_dispatch`.
    max_dispatch: std::sync::atomic::AtomicUsize,
    /// Points per dispatch by the workgroup count limit (65,535 workgroups).
    by_workgroups: usize,
    /// The adapter runs f64 shaders (SHADER_F64): the f64 refinement is available.
    pub f64: bool,
    /// Refine every result in f64 (set through `Engine::set_precision`).
    pub refine_f64: bool,
    max_binding: u64,
    max_buffer: u64,
    error: Arc<Mutex<Option<String>>>,
    /// The lambdas (their bits) of the last grid and the kernel's preparation of each: a map's
    /// bands share them, and preparing is a pull-off search and tables per lambda.
    prepared: Mutex<Option<Prepared>>,
    /// The map's classification (`shaders/classify.wgsl`): its bindings and pipeline, built on
    /// first use.
    classify: std::sync::OnceLock<(wgpu::BindGroupLayout, wgpu::ComputePipeline)>,
    /// The device runs the map's classification: f64 shaders, five storage buffers.
    pub classifies: bool,
    /// Traced runs time their passes by timestamp queries (the adapter has them).
    timestamps: bool,
    /// An ensemble's stepping (`shaders/ensemble64.wgsl`): bindings and pipelines, built on
    /// first use.
    ensemble: std::sync::OnceLock<(
        wgpu::BindGroupLayout,
        wgpu::ComputePipeline,
        wgpu::ComputePipeline,
    )>,
    /// Storage buffers a shader stage may bind on this device.
    storage_buffers: u32,
}

/// A band of a map from the device: a byte a point (`shaders/classify.wgsl`) and the whole
/// results of the points asked for.
pub struct Classified {
    /// Region (bits 0-2) and adequate models (bits 3-6) of each point.
    pub marks: Vec<u8>,
    /// The kernel's results at the picked points, in the order asked.
    pub picked: Vec<Out>,
}

/// A grid's lambdas (their bits) and the kernel's preparation of each.
type Prepared = (Vec<u64>, Arc<Vec<GpuLambda>>);

/// The kernels' bindings: the parameters (uniform), the lambdas and the input (read-only) and
/// the output.
fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("md"),
        entries: &[
            uniform(0),
            storage(1, true),
            storage(2, true),
            storage(3, false),
        ],
    })
}

/// The grid kernel's lambdas and input: each row's load as a hi/lo pair, then the lambdas'
/// dense starts (each lambda told where its block begins).
fn grid_input(
    lambdas: &[GpuLambda],
    starts: &Starts,
    rows: &[(f32, f32)],
) -> (Vec<GpuLambda>, Vec<u32>) {
    let mut words: Vec<u32> = rows
        .iter()
        .flat_map(|&(h, l)| [h.to_bits(), l.to_bits()])
        .collect();
    let lambdas = starts.placed(lambdas, words.len());
    words.extend_from_slice(&starts.words);
    (lambdas, words)
}

/// A compute shader's uniform binding.
fn uniform(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A compute shader's storage binding.
fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

const WORKGROUP: usize = crate::kernel::prelude::WORKGROUP_SIZE;
/// Dispatches over an input bound in slices hold a multiple of this many points.
const SLICE_POINTS: usize = 256;

/// With `TABOR_GPU_TRACE=1` each GPU run prints where its time went (pipeline, upload, each
/// dispatch's wait and read-back) on stderr: the way to see a host-side bottleneck on an
/// adapter at hand. "Upload" is the host's staging of the buffers: wgpu copies them to the
/// device at the first submit, so that copy shows in the first dispatch's "compute and copy".
pub(crate) fn trace() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var("TABOR_GPU_TRACE").is_ok_and(|v| v == "1"))
}

impl Gpu {
    /// Opens the first hardware adapter, or the one whose name contains `adapter_name`.
    pub fn new(adapter_name: Option<&str>) -> Result<Gpu, GpuError> {
        let t0 = std::time::Instant::now();
        let adapter = choose_adapter(adapter_name)?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let f64_ok = adapter.features().contains(wgpu::Features::SHADER_F64);
        // Kernel time by timestamps only when traced: queries are not free.
        let timestamps = trace() && adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("tabor"),
            required_features: {
                let mut f = wgpu::Features::empty();
                f.set(wgpu::Features::SHADER_F64, f64_ok);
                f.set(wgpu::Features::TIMESTAMP_QUERY, timestamps);
                f
            },
            required_limits: wgpu::Limits {
                max_storage_buffer_binding_size: limits.max_storage_buffer_binding_size,
                max_buffer_size: limits.max_buffer_size,
                // The map's classification binds five storage buffers.
                max_storage_buffers_per_shader_stage:
                    limits.max_storage_buffers_per_shader_stage.clamp(4, 8),
                ..wgpu::Limits::downlevel_defaults()
            },
            ..Default::default()
        }))
        .map_err(|err| GpuError::Device {
            adapter: info.name.clone(),
            err,
        })?;
        // Errors are collected, never panicked on: they become GpuError::Runtime.
        let error = Arc::new(Mutex::new(None::<String>));
        let e2 = error.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            e2.lock().unwrap().get_or_insert(e.to_string());
        }));
        let e3 = error.clone();
        device.set_device_lost_callback(move |reason, msg| {
            e3.lock()
                .unwrap()
                .get_or_insert(format!("device lost ({reason:?}): {msg}"));
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("md"),
            source: wgpu::ShaderSource::Wgsl(crate::kernel::shader_source().into()),
        });
        let layout = bind_group_layout(&device);
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("md"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let max_binding = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        let max_buffer = limits.max_buffer_size;
        // The device's limit, not the adapter's: the device was asked for the defaults.
        let by_workgroups =
            device.limits().max_compute_workgroups_per_dimension as usize * WORKGROUP;
        let device_limits_storage = device.limits().max_storage_buffers_per_shader_stage;
        let gpu = Gpu {
            adapter: AdapterSummary::of(&info),
            device,
            queue,
            layout,
            module,
            polish_module: std::sync::OnceLock::new(),
            pipeline_layout: pl,
            pipelines: Mutex::new(HashMap::new()),
            max_dispatch: std::sync::atomic::AtomicUsize::new(0),
            by_workgroups,
            f64: f64_ok,
            refine_f64: false,
            max_binding,
            max_buffer,
            error,
            prepared: Mutex::new(None),
            classify: std::sync::OnceLock::new(),
            classifies: device_limits_storage >= 5 && f64_ok,
            timestamps,
            ensemble: std::sync::OnceLock::new(),
            storage_buffers: device_limits_storage,
        };
        gpu.check()?;
        if trace() {
            eprintln!(
                "gpu trace: adapter, device and shader module in {:.4} s",
                t0.elapsed().as_secs_f64()
            );
        }
        Ok(gpu)
    }

    /// A bind group of whole buffers, binding k the k-th of `bufs`.
    fn bind_whole(
        &self,
        label: &'static str,
        layout: &wgpu::BindGroupLayout,
        bufs: &[&wgpu::Buffer],
    ) -> wgpu::BindGroup {
        let entries: Vec<_> = bufs
            .iter()
            .enumerate()
            .map(|(i, buf)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: buf.as_entire_binding(),
            })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        })
    }

    /// A uniform buffer holding `bytes`.
    fn uniform_buffer(&self, bytes: &[u8]) -> wgpu::Buffer {
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("params"),
                contents: bytes,
                usage: wgpu::BufferUsages::UNIFORM,
            })
    }

    /// A module of its own (`source`, labelled `label`) with the bindings `entries`: its
    /// bind group layout and a pipeline for each of `entry_points`.
    fn own_pipelines(
        &self,
        label: &'static str,
        source: String,
        entries: &[wgpu::BindGroupLayoutEntry],
        entry_points: &[&'static str],
    ) -> (wgpu::BindGroupLayout, Vec<wgpu::ComputePipeline>) {
        let d = &self.device;
        let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        });
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipelines = entry_points
            .iter()
            .map(|&entry| {
                d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(&pl),
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
            })
            .collect();
        (layout, pipelines)
    }

    /// The pipeline of a variant, compiled on first use: a software adapter spends tens of
    /// milliseconds on each, so only what a run needs is built.
    fn pipeline(&self, v: Variant) -> Result<wgpu::ComputePipeline, GpuError> {
        let mut cache = self.pipelines.lock().unwrap();
        if let Some(p) = cache.get(&v) {
            return Ok(p.clone());
        }
        let constants = v.overrides();
        // The f64 module is its own (the f32 one must build where f64 does not exist).
        let module = match v.entry {
            Entry::Polish => self.f64_module(
                &self.polish_module,
                "polish64",
                crate::kernel::polish64_source,
            ),
            _ => &self.module,
        };
        let p = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(v.entry.name()),
                layout: Some(&self.pipeline_layout),
                module,
                entry_point: Some(v.entry.name()),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            });
        self.check()?;
        cache.insert(v, p.clone());
        Ok(p)
    }

    /// An f64 module, built on first use.
    fn f64_module<'a>(
        &'a self,
        cell: &'a std::sync::OnceLock<wgpu::ShaderModule>,
        label: &'static str,
        source: fn() -> String,
    ) -> &'a wgpu::ShaderModule {
        cell.get_or_init(|| {
            self.device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source().into()),
                })
        })
    }

    /// Splits every run into dispatches of at most `n` points (0: as the adapter's limits
    /// allow; runs whose input is bound in slices round `n` down to a multiple of 256 points,
    /// and up to 256). Results do not depend on it; tests use it to exercise the chunked path that
    /// only huge inputs reach otherwise.
    pub fn limit_dispatch(&self, n: usize) {
        self.max_dispatch
            .store(n, std::sync::atomic::Ordering::Relaxed);
    }

    /// The kernel's preparation of `lambdas`: the last one where the lambdas are the same
    /// (bit for bit), else `make()`, kept for the next call. Preparing depends on the lambda
    /// alone, so a kept one is what `make` would give.
    pub(crate) fn prepared_for(
        &self,
        lambdas: &[f64],
        make: impl FnOnce() -> Vec<GpuLambda>,
    ) -> Arc<Vec<GpuLambda>> {
        let bits: Vec<u64> = lambdas.iter().map(|l| l.to_bits()).collect();
        if let Some((b, p)) = self.prepared.lock().unwrap().as_ref() {
            if *b == bits {
                return p.clone();
            }
        }
        let p = Arc::new(make());
        *self.prepared.lock().unwrap() = Some((bits, p.clone()));
        p
    }

    fn check(&self) -> Result<(), GpuError> {
        match self.error.lock().unwrap().take() {
            Some(e) => Err(GpuError::Runtime(e)),
            None => Ok(()),
        }
    }

    /// Solves the grid `lambdas x rows` (row-major, one row per load): `rows` are the loads (or
    /// the distances above the branch end, with `rows_are_gaps`) as hi/lo pairs.
    pub fn grid(
        &self,
        lambdas: &[GpuLambda],
        rows: &[(f32, f32)],
        control: Control,
        rows_are_gaps: bool,
        flags: KernelFlags,
    ) -> Result<Vec<Out>, GpuError> {
        let none = Starts::default();
        self.grid_started(lambdas, &none, rows, control, rows_are_gaps, flags)
    }

    /// As [`Gpu::grid`], with the lambdas' dense starts (load control): their blocks follow the
    /// rows in the kernel's input.
    pub fn grid_started(
        &self,
        lambdas: &[GpuLambda],
        starts: &Starts,
        rows: &[(f32, f32)],
        control: Control,
        rows_are_gaps: bool,
        flags: KernelFlags,
    ) -> Result<Vec<Out>, GpuError> {
        let (lambdas, words) = grid_input(lambdas, starts, rows);
        let lambdas = &lambdas[..];
        let total = lambdas.len() * rows.len();
        let v = Variant {
            entry: Entry::Grid,
            control,
            rows_are_gaps,
            naive: flags.naive,
        };
        self.run(
            v,
            lambdas,
            &words,
            0,
            total,
            lambdas.len() as u32,
            flags.max_iter,
        )
    }

    /// Solves a list of points `(lambda index, hi, lo)`.
    pub fn points(
        &self,
        lambdas: &[GpuLambda],
        points: &[(u32, f32, f32)],
        control: Control,
        flags: KernelFlags,
    ) -> Result<Vec<Out>, GpuError> {
        let words: Vec<u32> = points
            .iter()
            .flat_map(|&(c, h, l)| [c, h.to_bits(), l.to_bits(), 0])
            .collect();
        let v = Variant {
            entry: Entry::Points,
            control,
            rows_are_gaps: false,
            naive: flags.naive,
        };
        self.run(v, lambdas, &words, 16, points.len(), 0, flags.max_iter)
    }

    /// Refines f32 results in f64 (adapters with SHADER_F64): `points` are (lambda index, value)
    /// and `start` the f32 kernel's results for them; with `gaps` the values are distances above
    /// the branch end. `max_steps` caps the Newton steps (0: the default, 8).
    #[allow(clippy::too_many_arguments)]
    pub fn polish_f64(
        &self,
        lambdas: &[Lambda64],
        points: &[(u32, f64)],
        start: &[Out],
        control: Control,
        gaps: bool,
        max_steps: u32,
    ) -> Result<Vec<Out64>, GpuError> {
        if !self.f64 {
            return Err(GpuError::NoF64(self.adapter.name.clone()));
        }
        let input: Vec<Point64> = points
            .iter()
            .zip(start)
            .map(|(&(ci, value), o)| crate::kernel::cpu::polish64::point64(ci, value, o))
            .collect();
        let v = Variant {
            entry: Entry::Polish,
            control,
            rows_are_gaps: gaps,
            naive: false,
        };
        let words: &[u32] = bytemuck::cast_slice(&input);
        self.run(
            v,
            lambdas,
            words,
            std::mem::size_of::<Point64>(),
            points.len(),
            0,
            max_steps,
        )
    }

    /// Evaluates the kernels' own atan, mu - atan and exp, and the built-in atan, at `xs`:
    /// returns (atan, mu - atan, exp(-x/4), built-in atan) per argument.
    pub fn probe(&self, xs: &[f32]) -> Result<Vec<[f32; 4]>, GpuError> {
        let words: Vec<u32> = xs.iter().map(|x| x.to_bits()).collect();
        let v = Variant {
            entry: Entry::Probe,
            control: Control::Load,
            rows_are_gaps: false,
            naive: false,
        };
        let out: Vec<Out> = self.run(
            v,
            &[<GpuLambda as bytemuck::Zeroable>::zeroed()],
            &words,
            4,
            xs.len(),
            0,
            0,
        )?;
        Ok(out
            .iter()
            .map(|o| [o.a, o.other, o.m_minus_1, f32::from_bits(o.code)])
            .collect())
    }

    #[allow(clippy::too_many_arguments)]
    fn run<L: bytemuck::Pod, T: bytemuck::Pod>(
        &self,
        variant: Variant,
        lambdas: &[L],
        input: &[u32],
        input_stride: usize,
        total: usize,
        nx: u32,
        max_iter: u32,
    ) -> Result<Vec<T>, GpuError> {
        let out_bytes = std::mem::size_of::<T>();
        if total == 0 {
            return Ok(Vec::new());
        }
        self.fits(lambdas, input.len() * 4, total)?;
        let t0 = std::time::Instant::now();
        let pipeline = self.pipeline(variant)?;
        let t_pipeline = t0.elapsed().as_secs_f64();
        let d = &self.device;
        let lam_buf = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lambdas"),
            contents: bytemuck::cast_slice(lambdas),
            usage: wgpu::BufferUsages::STORAGE,
        });
        // A buffer cannot be empty: one word stands in for no input (not a copy of the input,
        // which can be hundreds of megabytes).
        let in_words: &[u32] = if input.is_empty() { &[0] } else { input };
        let in_buf = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("input"),
            contents: bytemuck::cast_slice(in_words),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let chunk = self.chunk_points(total, out_bytes, input_stride);
        let out_size = (chunk * out_bytes) as u64;
        let out_buf = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("out"),
            size: out_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("staging"),
            size: out_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.check()?;
        let mut result: Vec<T> = Vec::with_capacity(total);
        let mut start = 0usize;
        let bufs = Buffers {
            lambdas: &lam_buf,
            input: &in_buf,
            out: &out_buf,
            staging: &staging,
        };
        let t_upload = t0.elapsed().as_secs_f64() - t_pipeline;
        while start < total {
            let n = chunk.min(total - start);
            let p = Params {
                nx,
                offset: start as u32,
                count: n as u32,
                max_iter,
            };
            self.dispatch(&pipeline, &bufs, p, input_stride, &mut result)?;
            start += n;
        }
        if trace() {
            eprintln!(
                "gpu trace: {} {total} points in {} dispatches: pipeline {t_pipeline:.4} s, upload {t_upload:.4} s, total {:.4} s",
                variant.entry.name(),
                total.div_ceil(chunk),
                t0.elapsed().as_secs_f64()
            );
        }
        Ok(result)
    }

    /// Checked before a run (wgpu would otherwise fail inside buffer creation): the lambdas fit
    /// one binding, the input one buffer.
    fn fits<L>(&self, lambdas: &[L], in_bytes: usize, total: usize) -> Result<(), GpuError> {
        let lam_bytes = std::mem::size_of_val(lambdas);
        if lam_bytes as u64 > self.max_binding {
            return Err(GpuError::TooLarge(format!(
                "{} distinct lambda values need {lam_bytes} bytes, more than this adapter binds ({}); split the input",
                lambdas.len(),
                self.max_binding
            )));
        }
        if in_bytes as u64 > self.max_buffer {
            return Err(GpuError::TooLarge(format!(
                "{total} points need {in_bytes} bytes of input, more than this adapter's largest buffer ({}); split the input into smaller files",
                self.max_buffer
            )));
        }
        Ok(())
    }

    /// Points per dispatch of a run of `total`: within the workgroup limit, the binding size of
    /// the output (and of the per-point input) and `limit_dispatch`'s.
    fn chunk_points(&self, total: usize, out_bytes: usize, input_stride: usize) -> usize {
        let limit = self.max_dispatch.load(std::sync::atomic::Ordering::Relaxed);
        let chunk = self
            .by_workgroups
            .min(self.max_binding as usize / out_bytes.max(input_stride))
            .min(if limit > 0 { limit } else { usize::MAX })
            .min(total);
        // An input bound in slices starts each at `offset * stride` bytes, which must be a
        // multiple of the storage offset alignment (at most 256 bytes): chunks of whole
        // multiples of 256 points are, whatever the stride.
        if input_stride > 0 && chunk < total {
            (chunk / SLICE_POINTS).max(1) * SLICE_POINTS
        } else {
            chunk
        }
    }

    /// One dispatch of `p.count` points from `p.offset`, its results appended to `result`.
    fn dispatch<T: bytemuck::Pod>(
        &self,
        pipeline: &wgpu::ComputePipeline,
        bufs: &Buffers,
        p: Params,
        input_stride: usize,
        result: &mut Vec<T>,
    ) -> Result<(), GpuError> {
        let d = &self.device;
        let out_bytes = std::mem::size_of::<T>();
        // A buffer per dispatch, not one shared by the Gpu: threads sharing a Gpu would
        // otherwise overwrite each other's parameters between write and submit.
        let params = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("params"),
            contents: bytemuck::bytes_of(&p),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        // The point kernel sees only this chunk's input; the grid kernel reads its rows whole.
        let input_binding = if input_stride > 0 {
            wgpu::BufferBinding {
                buffer: bufs.input,
                offset: (p.offset as usize * input_stride) as u64,
                size: wgpu::BufferSize::new((p.count as usize * input_stride) as u64),
            }
        } else {
            wgpu::BufferBinding {
                buffer: bufs.input,
                offset: 0,
                size: None,
            }
        };
        let bind = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("md"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: bufs.lambdas.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Buffer(input_binding),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: bufs.out.as_entire_binding(),
                },
            ],
        });
        let mut enc =
            d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("md") });
        let timer = self.timestamps.then(|| timer::Timer::new(d, 1));
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("md"),
                timestamp_writes: timer.as_ref().map(|t| t.writes(0)),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups((p.count as usize).div_ceil(WORKGROUP) as u32, 1, 1);
        }
        if let Some(t) = &timer {
            t.resolve(&mut enc);
        }
        let bytes = (p.count as usize * out_bytes) as u64;
        enc.copy_buffer_to_buffer(bufs.out, 0, bufs.staging, 0, bytes);
        let t0 = std::time::Instant::now();
        self.queue.submit([enc.finish()]);
        let t_wait = self.read_back(bufs.staging, bytes, t0, result)?;
        bufs.staging.unmap();
        if trace() {
            let secs = timer.and_then(|t| t.seconds(d, self.queue.get_timestamp_period()));
            eprintln!(
                "gpu trace:   dispatch of {}: compute and copy {t_wait:.4} s, read back {:.4} s{}",
                p.count,
                t0.elapsed().as_secs_f64() - t_wait,
                timer::shown(secs.as_deref())
            );
        }
        self.check()
    }

    /// Maps the first `bytes` of `staging` once the queue is done and appends them to `result`;
    /// returns the seconds from `t0` to the queue's end (for the trace).
    fn read_back<T: bytemuck::Pod>(
        &self,
        staging: &wgpu::Buffer,
        bytes: u64,
        t0: std::time::Instant,
        result: &mut Vec<T>,
    ) -> Result<f64, GpuError> {
        let d = &self.device;
        let slice = staging.slice(..bytes);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        d.poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Runtime(e.to_string()))?;
        let t_wait = t0.elapsed().as_secs_f64();
        match rx.recv() {
            Ok(Ok(())) => {}
            Ok(Err(e)) => return Err(GpuError::Runtime(format!("reading results back: {e}"))),
            Err(_) => {
                return Err(GpuError::Runtime(
                    "reading results back: no answer from the device".into(),
                ))
            }
        }
        {
            let view = slice
                .get_mapped_range()
                .map_err(|e| GpuError::Runtime(format!("reading results back: {e}")))?;
            result.extend_from_slice(bytemuck::cast_slice(&view));
        }
        Ok(t_wait)
    }
}

/// The buffers of one run: the lambdas, the input, the output and its staging copy.
struct Buffers<'a> {
    lambdas: &'a wgpu::Buffer,
    input: &'a wgpu::Buffer,
    out: &'a wgpu::Buffer,
    staging: &'a wgpu::Buffer,
}
