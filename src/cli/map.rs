//! `tabor map`: the adhesion map, its figure and its tables.

use super::basic::GpuArgs;
use super::{BackendArg, LoadAxisArg, QuantityArg};
use crate::export::{write_map_json, write_npy, NPY_FILES};
use crate::io::Output;
use crate::map::{LoadAxis, MapSpec};
use anyhow::Context;
use clap::Args;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct MapArgs {
    #[arg(long, default_value_t = 1e-3)]
    pub lambda_min: f64,
    #[arg(long, default_value_t = 1e3)]
    pub lambda_max: f64,
    /// Grid columns (lambda).
    #[arg(long, default_value_t = 1024)]
    pub nx: usize,
    /// Grid rows (load).
    #[arg(long, default_value_t = 1024)]
    pub ny: usize,
    /// log: Pbar on a log axis (classic); above-pulloff: Pbar - Pbar_c on a log axis; linear.
    #[arg(long, value_enum, default_value_t = LoadAxisArg::Log)]
    pub load_axis: LoadAxisArg,
    /// Lowest load (default 1e-3 for log, 1e-6 for above-pulloff, -2 for linear).
    #[arg(long)]
    pub load_min: Option<f64>,
    /// Highest load (default 1e3 for the log axes, 10 for linear).
    #[arg(long)]
    pub load_max: Option<f64>,
    /// Relative error of the contact radius a simpler model may have.
    #[arg(long, default_value_t = crate::physics::model::DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    /// s0/K ratios of the large-deformation lines a/R = 0.1.
    #[arg(long, value_delimiter = ',', default_value = "0.001,0.01")]
    pub strength_ratio: Vec<f64>,
    /// Draw this quantity with a colorbar instead of the regions.
    #[arg(long, value_enum)]
    pub quantity: Option<QuantityArg>,
    /// The figure: .png, .svg or .pdf.
    #[arg(long, default_value = "map.png")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figure: super::FigureArgs,
    /// JSON with metadata, axes and per-lambda model thresholds.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Add the per-point arrays to the JSON.
    #[arg(long, requires = "json")]
    pub json_full: bool,
    /// Put the stage timings into the JSON metadata (they differ between runs, so the same
    /// command no longer gives the same bytes).
    #[arg(long)]
    pub timings: bool,
    /// Write PREFIX_lambda.npy, PREFIX_load.npy, PREFIX_region.npy, PREFIX_A.npy, ... .
    #[arg(long)]
    pub npy: Option<String>,
    /// [default: auto, or the environment variable TABOR_BACKEND]
    #[arg(long, value_enum)]
    pub backend: Option<BackendArg>,
    #[command(flatten)]
    pub gpu: GpuArgs,
    /// The map of a tip that is not a sphere (docs/PHYSICS.md section 12), on the CPU: cone,
    /// power:N (f = B r^N; every B has the same map), or capped-cone:R_OVER_L:HALF_ANGLE_DEG
    /// (the cap's radius in the tip's length unit l).
    /// Or scene:FILE, the tip of a scene file in the units of its E* and w (any SI tip, a measured
    /// profile among them).
    #[arg(long)]
    pub tip: Option<String>,
}

impl MapArgs {
    pub fn spec(&self) -> MapSpec {
        let load_axis: LoadAxis = self.load_axis.into();
        let (lo, hi) = load_axis.default_range();
        MapSpec {
            lambda_min: self.lambda_min,
            lambda_max: self.lambda_max,
            nx: self.nx,
            load_axis,
            load_min: self.load_min.unwrap_or(lo),
            load_max: self.load_max.unwrap_or(hi),
            ny: self.ny,
            tolerance: self.tolerance,
            strength_ratios: self.strength_ratio.clone(),
        }
    }
}

/// Refuses an output whose name says another format than the one written.
pub fn check_extension(path: &Path, ext: &str, flag: &str) -> anyhow::Result<()> {
    let got = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    if got != ext {
        anyhow::bail!(
            "{flag} {} writes {}: give a name ending in .{ext}{}",
            path.display(),
            ext.to_uppercase(),
            match ext {
                "png" => " (an SVG goes to --svg FILE.svg)",
                "svg" => " (a PNG goes to --out FILE.png)",
                _ => "",
            }
        );
    }
    Ok(())
}

/// What the map keeps, from the outputs asked for.
fn compute_options(a: &MapArgs) -> crate::map::ComputeOptions {
    // The f64 values are kept only for the exports that write them; GPU maps are cross-checked
    // on a sample of points against the f64 solver as they are solved.
    crate::map::ComputeOptions {
        keep_exact: a.json_full || a.npy.is_some(),
        check: a.gpu.check.0,
        // A sphere's map of regions keeps a byte a point (and is classified on a GPU's
        // device); a map of a quantity colours every point, a tip's keeps them all.
        records: a.quantity.is_some() || a.tip.is_some(),
    }
}

/// A tip's map keeps every point's values: at most [`crate::map::MAX_MAP_POINTS`] points.
fn tip_map_fits(spec: &crate::map::MapSpec) -> anyhow::Result<()> {
    let points = spec.nx * spec.ny;
    if points > crate::map::MAX_MAP_POINTS {
        anyhow::bail!(
            "--nx {} x --ny {} is {points} points, more than the {} (4096 x 4096) a tip's map holds in memory (every point's values are kept); use fewer points, or split the range into several maps",
            spec.nx,
            spec.ny,
            crate::map::MAX_MAP_POINTS
        );
    }
    Ok(())
}

pub fn run(a: MapArgs) -> anyhow::Result<()> {
    if a.timings && a.json.is_none() {
        anyhow::bail!("--timings puts the computing time into the JSON: give --json FILE too, or leave out --timings (the time is always printed on stderr)");
    }
    let t_run = Instant::now();
    let spec = a.spec();
    let opts = compute_options(&a);
    if a.tip.is_some() {
        tip_map_fits(&spec)?;
    }
    spec.validate_with(&opts)
        .map_err(|e| super::in_flags(&e, super::MAP_FLAGS))?;
    let figure = a.figure.outputs(Some(&a.out), "--out")?;
    let print = a.figure.print("map")?;
    let more = super::data_outputs(a.json.as_deref(), a.npy.as_deref(), &NPY_FILES);
    a.figure.check_distinct(Some(&a.out), "--out", more)?;
    // Every output is opened before the work: a bad path fails at once, and none is put in
    // place unless all of them were written.
    let open = |p: &Option<PathBuf>| -> anyhow::Result<Option<Output>> {
        p.as_ref()
            .map(|p| Output::create(p).with_context(|| p.display().to_string()))
            .transpose()
    };
    let mut figure_out = [open(&figure.png)?, open(&figure.svg)?, open(&figure.pdf)?];
    let mut json_out = a
        .json
        .as_ref()
        .map(Output::create)
        .transpose()
        .context("--json")?;
    let mut npy = super::open_npy(a.npy.as_deref(), &NPY_FILES)?;
    let engine = super::basic::engine_for(a.backend, BackendArg::Auto, &a.gpu)?;
    let mut data = match a.tip.as_deref() {
        Some(t) => crate::map::tip::compute_tip(&spec, super::tip_shape(t)?, opts.keep_exact)?,
        None => crate::map::compute_with(&spec, &engine, opts)?,
    };
    let check = data.check.clone();
    if let Some(r) = &check {
        eprintln!("{r}");
    }
    let t = Instant::now();
    let want = crate::render::Formats {
        png: figure.png.is_some(),
        svg: figure.svg.is_some(),
        pdf: figure.pdf.is_some(),
    };
    let fig = crate::render::map::render(&data, a.quantity.map(Into::into), &print, want)
        .map_err(anyhow::Error::from_boxed)
        .context("rendering the figure")?;
    data.timings.render_s = t.elapsed().as_secs_f64();
    let put = |o: &mut Output, bytes: &[u8]| -> anyhow::Result<()> {
        let shown = o.name().display().to_string();
        o.write_all(bytes)
            .with_context(|| format!("cannot write {shown}"))
    };
    let bytes = [
        fig.png.as_deref(),
        fig.svg.as_ref().map(|s| s.as_bytes()),
        fig.pdf.as_deref(),
    ];
    for (o, b) in figure_out.iter_mut().zip(bytes) {
        if let (Some(o), Some(b)) = (o.as_mut(), b) {
            put(o, b)?;
        }
    }
    if let Some(o) = json_out.as_mut() {
        let shown = o.name().display().to_string();
        write_map_json(o, &data, &engine, check.as_ref(), a.json_full, a.timings)
            .with_context(|| format!("cannot write {shown}"))?;
    }
    if !npy.is_empty() {
        write_npy(&data, &mut npy)?;
    }
    for o in figure_out.into_iter().flatten().chain(json_out).chain(npy) {
        o.commit()?;
    }
    report(&a, &spec, &data);
    if crate::gpu::device::trace() {
        // The driver's teardown is part of the command's time too.
        let t = Instant::now();
        drop(engine);
        eprintln!(
            "gpu trace: map command {:.4} s, then the device closed in {:.4} s",
            t_run.elapsed().as_secs_f64() - t.elapsed().as_secs_f64(),
            t.elapsed().as_secs_f64()
        );
    } else if matches!(engine, crate::engine::Engine::Gpu(_)) {
        // The command ends here, every output committed: the process's exit frees the device,
        // and closing it first cost an H200 system 0.057 s of a 0.5 s map (traced).
        std::mem::forget(engine);
    }
    Ok(())
}

/// What a map cost and what it shows, on stderr: the stages' times, the files written and each
/// region's share.
fn report(a: &MapArgs, spec: &crate::map::MapSpec, data: &crate::map::MapData) {
    let tm = &data.timings;
    eprintln!(
        "map {}x{}: solve {:.3} s, classify {:.3} s, render {:.3} s; wrote {}{}",
        spec.nx,
        spec.ny,
        tm.solve_s,
        tm.classify_s,
        tm.render_s,
        a.out.display(),
        [&a.figure.svg, &a.figure.pdf]
            .into_iter()
            .flatten()
            .map(|p| format!(", {}", p.display()))
            .collect::<String>()
    );
    let counts: Vec<String> = data
        .region_counts()
        .iter()
        .map(|(r, n)| {
            format!(
                "{} {:.1}%",
                r.name(),
                100.0 * *n as f64 / data.regions.len() as f64
            )
        })
        .collect();
    eprintln!("regions: {}", counts.join(", "));
}
