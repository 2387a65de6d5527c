//! `tabor map`: the adhesion map, its figure and its tables.

use super::basic::GpuArgs;
use crate::engine::{cross_check, Backend, Engine};
use crate::io::{json_num, write_atomic};
use crate::map::{compute, LoadAxis, MapData, MapSpec, Region};
use crate::render::map::Quantity;
use crate::solver::{Control, Status};
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args, Debug)]
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
    #[arg(long, value_enum, default_value_t = LoadAxis::Log)]
    pub load_axis: LoadAxis,
    /// Lowest load (default 1e-3 for log, 1e-6 for above-pulloff, -2 for linear).
    #[arg(long, allow_hyphen_values = true)]
    pub load_min: Option<f64>,
    /// Highest load (default 1e3 for the log axes, 10 for linear).
    #[arg(long, allow_hyphen_values = true)]
    pub load_max: Option<f64>,
    /// Relative error of the contact radius a simpler model may have.
    #[arg(long, default_value_t = 0.05)]
    pub tolerance: f64,
    /// s0/K ratios of the large-deformation lines a/R = 0.1.
    #[arg(long, value_delimiter = ',', default_value = "0.001,0.01")]
    pub strength_ratio: Vec<f64>,
    /// Draw this quantity with a colorbar instead of the regions.
    #[arg(long, value_enum)]
    pub quantity: Option<Quantity>,
    /// PNG output.
    #[arg(long, default_value = "map.png")]
    pub out: PathBuf,
    /// SVG output.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// JSON with metadata, axes and per-lambda model thresholds.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Add the per-point arrays to the JSON.
    #[arg(long, requires = "json")]
    pub json_full: bool,
    /// Write PREFIX_lambda.npy, PREFIX_load.npy, PREFIX_region.npy, PREFIX_A.npy, ... .
    #[arg(long)]
    pub npy: Option<String>,
    #[arg(long, value_enum, env = "TABOR_BACKEND", default_value_t = Backend::Auto)]
    pub backend: Backend,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

impl MapArgs {
    pub fn spec(&self) -> MapSpec {
        let (lo, hi) = match self.load_axis {
            LoadAxis::Log => (1e-3, 1e3),
            LoadAxis::AbovePulloff => (1e-6, 1e3),
            LoadAxis::Linear => (-2.0, 10.0),
        };
        MapSpec {
            lambda_min: self.lambda_min,
            lambda_max: self.lambda_max,
            nx: self.nx,
            load_axis: self.load_axis,
            load_min: self.load_min.unwrap_or(lo),
            load_max: self.load_max.unwrap_or(hi),
            ny: self.ny,
            tolerance: self.tolerance,
            strength_ratios: self.strength_ratio.clone(),
        }
    }
}

pub fn run(a: MapArgs) -> anyhow::Result<()> {
    let spec = a.spec();
    spec.validate()?;
    let (mut engine, line) = Engine::select(a.backend, a.gpu.adapter.as_deref())?;
    engine.set_precision(a.gpu.precision)?;
    eprintln!("{line}");
    let mut data = compute(&spec, &engine)?;
    // GPU maps are cross-checked on a sample of points against the f64 solver.
    let check = if let Engine::Gpu(_) = engine {
        let pts: Vec<(f64, f64)> = data.states.iter().map(|s| (s.lambda, s.load)).collect();
        let r = cross_check(
            &pts,
            &data.states,
            Control::Load,
            a.gpu.check.0,
            super::basic::GPU_TOLERANCE,
        );
        eprintln!("{r}");
        Some(r)
    } else {
        None
    };
    let t = Instant::now();
    crate::render::map::write(&data, a.quantity, Some(&a.out), a.svg.as_deref())
        .map_err(|e| anyhow::anyhow!("rendering the figure: {e}"))?;
    data.timings.render_s = t.elapsed().as_secs_f64();
    let tm = &data.timings;
    eprintln!(
        "map {}x{}: solve {:.3} s, classify {:.3} s, render {:.3} s; wrote {}{}",
        spec.nx,
        spec.ny,
        tm.solve_s,
        tm.classify_s,
        tm.render_s,
        a.out.display(),
        a.svg
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default()
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
    if let Some(p) = &a.json {
        let doc = map_json(&data, &engine, check.as_ref(), a.json_full);
        write_atomic(p, (serde_json::to_string_pretty(&doc)? + "\n").as_bytes())?;
    }
    if let Some(prefix) = &a.npy {
        write_npy(&data, prefix)?;
    }
    Ok(())
}

pub fn map_json(
    d: &MapData,
    engine: &Engine,
    check: Option<&crate::engine::CheckReport>,
    full: bool,
) -> serde_json::Value {
    let mut doc = json!({
        "metadata": {
            "tabor_version": env!("CARGO_PKG_VERSION"),
            "backend": engine.name(),
            "adapter": engine.adapter(),
            "precision": engine.precision(),
            "tolerance": d.spec.tolerance,
            "grid": {"nx": d.spec.nx, "ny": d.spec.ny},
            "spec": d.spec,
            "timings_s": d.timings,
            "cross_check": check,
            "criteria": {
                "order": ["hertz", "rigid", "dmt", "jkr", "md"],
                "hertz": "|A_Hertz/A - 1| <= tolerance, A_Hertz = Pbar^(1/3), Pbar >= 0",
                "rigid": "(pi lambda / 2) max(A^2, |Dbar|) <= tolerance",
                "dmt": "|A_DMT/A - 1| <= tolerance, A_DMT = (Pbar + 2)^(1/3)",
                "jkr": "|A_JKR/A - 1| <= tolerance, A_JKR^3 = Pbar + 3 + sqrt(9 + 6 Pbar), Pbar >= -3/2",
                "no_contact": "Pbar below the load-controlled pull-off",
            },
            "region_counts": d.region_counts().iter().map(|(r, n)| (r.name().to_string(), json!(n))).collect::<serde_json::Map<_, _>>(),
        },
        "axes": {
            "lambda": d.lambdas,
            "load": d.rows,
            "load_axis": d.spec.load_axis,
        },
        "thresholds": d.thresholds(),
        "large_deformation": d.large_deformation,
    });
    if full {
        let nx = d.spec.nx;
        let rows = |f: &dyn Fn(usize) -> serde_json::Value| -> Vec<Vec<serde_json::Value>> {
            (0..d.spec.ny)
                .map(|iy| (0..nx).map(|ix| f(iy * nx + ix)).collect())
                .collect()
        };
        doc["points"] = json!({
            "region": rows(&|i| json!(d.regions[i].name())),
            "load": rows(&|i| json_num(d.states[i].load)),
            "A": rows(&|i| json_num(d.states[i].a)),
            "approach": rows(&|i| json_num(d.states[i].approach)),
            "m_minus_1": rows(&|i| json_num(d.states[i].m_minus_1)),
            "status": rows(&|i| json!(d.states[i].status.name())),
        });
    }
    doc
}

fn npy_bytes<T: npyz::AutoSerialize + Copy>(shape: &[u64], data: &[T]) -> anyhow::Result<Vec<u8>> {
    use npyz::WriterBuilder;
    let mut buf = Vec::new();
    {
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(shape)
            .writer(&mut buf)
            .begin_nd()?;
        w.extend(data.iter().copied())?;
        w.finish()?;
    }
    Ok(buf)
}

/// The per-point arrays as NumPy files: NaN where a state could not be computed; region codes
/// as uint8 with their names in PREFIX_region_names.json.
pub fn write_npy(d: &MapData, prefix: &str) -> anyhow::Result<()> {
    let (nx, ny) = (d.spec.nx as u64, d.spec.ny as u64);
    let file = |name: &str| PathBuf::from(format!("{prefix}_{name}"));
    let put = |name: &str, bytes: Vec<u8>| {
        write_atomic(&file(name), &bytes)
            .with_context(|| format!("writing {}", file(name).display()))
    };
    put("lambda.npy", npy_bytes(&[nx], &d.lambdas)?)?;
    put("load_axis.npy", npy_bytes(&[ny], &d.rows)?)?;
    let col =
        |f: &dyn Fn(&crate::solver::State) -> f64| -> Vec<f64> { d.states.iter().map(f).collect() };
    put("load.npy", npy_bytes(&[ny, nx], &col(&|s| s.load))?)?;
    put(
        "A.npy",
        npy_bytes(
            &[ny, nx],
            &col(&|s| {
                if s.status == Status::Ok {
                    s.a
                } else {
                    f64::NAN
                }
            }),
        )?,
    )?;
    put(
        "approach.npy",
        npy_bytes(
            &[ny, nx],
            &col(&|s| {
                if s.status == Status::Ok {
                    s.approach
                } else {
                    f64::NAN
                }
            }),
        )?,
    )?;
    put(
        "m_minus_1.npy",
        npy_bytes(
            &[ny, nx],
            &col(&|s| {
                if s.status == Status::Ok {
                    s.m_minus_1
                } else {
                    f64::NAN
                }
            }),
        )?,
    )?;
    let codes: Vec<u8> = d.regions.iter().map(|&r| r as u8).collect();
    put("region.npy", npy_bytes(&[ny, nx], &codes)?)?;
    let names: serde_json::Map<_, _> = Region::ALL
        .iter()
        .map(|r| ((*r as u8).to_string(), json!(r.name())))
        .collect();
    put(
        "region_names.json",
        (serde_json::to_string_pretty(&names)? + "\n").into_bytes(),
    )?;
    let _ = Path::new(prefix);
    Ok(())
}
