//! `tabor rough-map`: the rough adhesion map, its figure and its tables.

use crate::io::Output;
use crate::rough::map::{RoughMap, RoughMapSpec};
use anyhow::Context;
use clap::Args;
use std::io::Write as _;
use std::path::PathBuf;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct RoughMapArgs {
    #[arg(long, default_value_t = 1e-2)]
    pub lambda_min: f64,
    #[arg(long, default_value_t = 1e3)]
    pub lambda_max: f64,
    /// Grid columns (lambda, log-spaced).
    #[arg(long, default_value_t = 256)]
    pub nx: usize,
    /// The smallest roughness sigma (approach units).
    #[arg(long, default_value_t = 1e-2)]
    pub sigma_min: f64,
    /// The largest roughness sigma.
    #[arg(long, default_value_t = 1e2)]
    pub sigma_max: f64,
    /// Grid rows (sigma, log-spaced).
    #[arg(long, default_value_t = 256)]
    pub ny: usize,
    /// Largest error a simpler summit model may have: its rough pull-off relative to the smooth
    /// summit's, and its retract curve relative to the curve's largest |load|.
    #[arg(long, default_value_t = crate::physics::model::DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    /// How far the flat was pressed before the retract, in sigma below the mean summit plane.
    #[arg(long, default_value_t = 3.0)]
    pub press_sigmas: f64,
    /// Points re-solved by the adaptive quadrature of `tabor rough` to check the map.
    #[arg(long, default_value_t = 64)]
    pub check: usize,
    /// The figure: .png, .svg or .pdf.
    #[arg(long, default_value = "rough-map.png")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figure: super::FigureArgs,
    /// JSON with metadata, axes, per-lambda table errors and the check.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Add the per-point arrays to the JSON.
    #[arg(long, requires = "json")]
    pub json_full: bool,
    /// Put the computing time into the JSON (it differs between runs).
    #[arg(long)]
    pub timings: bool,
    /// Write PREFIX_lambda.npy, PREFIX_sigma.npy, PREFIX_relative_pulloff.npy, ... .
    #[arg(long)]
    pub npy: Option<String>,
    /// Where the summits' tables are solved [default: auto, or the environment variable
    /// TABOR_BACKEND]; the quadrature runs on the CPU.
    #[arg(long, value_enum)]
    pub backend: Option<super::BackendArg>,
    /// Use the first adapter whose name contains this text (see `tabor info`) [default: the
    /// environment variable TABOR_ADAPTER].
    #[arg(long)]
    pub adapter: Option<String>,
    /// GPU arithmetic for the tables: the f32 kernels, or f64 (refined by Newton steps in f64 on
    /// the GPU; needs SHADER_F64) [default: f64 where the adapter has it, else f32: f32 nodes
    /// miss the table's 1e-6 near the fold, where the quadrature then solves exactly on the
    /// CPU]. The CPU path is f64.
    #[arg(long, value_enum)]
    pub precision: Option<super::PrecisionArg>,
}

/// The NPY files of `--npy PREFIX`, each `PREFIX_<name>`.
pub const NPY_FILES: [&str; 7] = [
    "lambda.npy",
    "sigma.npy",
    "pulloff.npy",
    "relative_pulloff.npy",
    "pulloff_separation.npy",
    "region.npy",
    "model_error.npy",
];

impl RoughMapArgs {
    pub fn spec(&self) -> RoughMapSpec {
        RoughMapSpec {
            lambda_min: self.lambda_min,
            lambda_max: self.lambda_max,
            nx: self.nx,
            sigma_min: self.sigma_min,
            sigma_max: self.sigma_max,
            ny: self.ny,
            tolerance: self.tolerance,
            press_sigmas: self.press_sigmas,
        }
    }
}

/// How a region is decided, for the JSON and the figure.
pub const REGION_RULE: &str = "each point takes the first of Hertz (no adhesion), Bradley (rigid summits: Dugdale attraction -2(1 + delta/h0) at a gap, -2 in contact), DMT (delta^(3/2) - 2 in contact, the same attraction at a gap), JKR (Fuller and Tabor: in at delta = 0, out at JKR's rigid-grip jump-out) whose rough pull-off differs from the exact MD summits' by at most the tolerance times the smooth summit's pull-off, and whose retract curve (at 20 separations from the smallest to where the summits are free, and, where those are more than half a sigma apart, every half sigma within 4 sigma of where either model's touched summits jump out, d = -delta_out) differs by at most the tolerance times the MD curve's largest |load| (its pull-off included); else MD";

/// The map's metadata as JSON (everything but the per-point arrays).
pub fn json(m: &RoughMap, timings: bool) -> serde_json::Value {
    use crate::io::json_num;
    let nums = |v: &[f64]| -> Vec<serde_json::Value> { v.iter().map(|&x| json_num(x)).collect() };
    let mut j = serde_json::json!({
        "spec": m.spec,
        "model": "Greenwood-Williamson: identical spherical summits, Gaussian heights, each an exact Maugis-Dugdale sphere under rigid grips with its own history; the summits do not interact (no elastic coupling), which fails when contact spots crowd, when sigma is comparable to the summit radius, or for few summits",
        "quantity": "relative_pulloff: the most tensile retract load per summit after pressing to -press_sigmas*sigma, over the smooth summit's load-controlled pull-off Pbar_c",
        "region_rule": REGION_RULE,
        "regions": m.region_counts().iter().map(|(r, n)| (r.name().to_string(), serde_json::json!(n))).collect::<serde_json::Map<_, _>>(),
        "contours": crate::rough::map::CONTOURS,
        "axes": {
            "lambda": nums(&m.lambdas),
            "sigma": nums(&m.sigmas),
            "fuller_tabor_parameter": m.sigmas.iter().map(|s| json_num(0.75 * std::f64::consts::PI * s.powf(1.5))).collect::<Vec<_>>(),
        },
        "smooth_pulloff": nums(&m.smooth_pulloff),
        "table_error": json_num(m.table_error_max()),
        "table_error_per_lambda": nums(&m.table_error),
        "quadrature_check": m.check,
        "table_backend": m.table_backend,
    });
    if let Some(c) = &m.table_check {
        j["table_check"] = serde_json::json!(c);
    }
    if timings {
        j["seconds"] = json_num(m.seconds);
    }
    j
}

/// Writes the JSON document; with `full`, the per-point arrays (row-major, rows = sigma)
/// follow the metadata, streamed a row a line: a 4096 x 4096 map's arrays never exist as JSON
/// values or one string (as `tabor map --json-full`).
pub fn write_json(
    out: &mut dyn std::io::Write,
    m: &RoughMap,
    full: bool,
    timings: bool,
) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(&json(m, timings))?;
    if !full {
        out.write_all(text.as_bytes())?;
        out.write_all(b"\n")?;
        return Ok(());
    }
    // Reopen the document's closing brace and append the arrays.
    let body = text
        .trim_end()
        .strip_suffix('}')
        .unwrap_or(&text)
        .trim_end();
    out.write_all(body.as_bytes())?;
    let value = |x: f64| crate::io::json_num(x).to_string();
    let errors = crate::rough::map::MODEL_REGIONS.map(|r| format!("{}_error", r.name()));
    let mut fields: Vec<(&str, Box<dyn Fn(usize) -> String + '_>)> = vec![
        ("pulloff", Box::new(|i| value(m.pulloff[i]))),
        (
            "relative_pulloff",
            Box::new(|i| value(m.relative_pulloff[i])),
        ),
        (
            "pulloff_separation",
            Box::new(|i| value(m.pulloff_separation[i])),
        ),
        (
            "region",
            Box::new(|i| format!("\"{}\"", m.regions[i].name())),
        ),
    ];
    for (k, name) in errors.iter().enumerate() {
        fields.push((name, Box::new(move |i| value(m.model_error[i][k]))));
    }
    let nx = m.spec.nx;
    let mut line = String::new();
    for (name, f) in &fields {
        write!(out, ",\n  \"{name}\": [")?;
        for iy in 0..m.spec.ny {
            line.clear();
            line.push_str(if iy > 0 { ",\n    " } else { "\n    " });
            for ix in 0..nx {
                if ix > 0 {
                    line.push(',');
                }
                line.push_str(&f(iy * nx + ix));
            }
            out.write_all(line.as_bytes())?;
        }
        out.write_all(b"\n  ]")?;
    }
    out.write_all(b"\n}\n")?;
    Ok(())
}

pub fn write_npy(m: &RoughMap, outs: &mut [Output]) -> anyhow::Result<()> {
    use crate::export::npy_write;
    let [lam, sig, pc, rel, sep, region, err] = outs else {
        anyhow::bail!("write_npy needs the {} outputs", NPY_FILES.len());
    };
    let (nx, ny) = (m.spec.nx as u64, m.spec.ny as u64);
    npy_write(lam, &[nx], m.lambdas.iter().copied())?;
    npy_write(sig, &[ny], m.sigmas.iter().copied())?;
    npy_write(pc, &[ny, nx], m.pulloff.iter().copied())?;
    npy_write(rel, &[ny, nx], m.relative_pulloff.iter().copied())?;
    npy_write(sep, &[ny, nx], m.pulloff_separation.iter().copied())?;
    npy_write(region, &[ny, nx], m.regions.iter().map(|&r| r as u8))?;
    npy_write(
        err,
        &[ny, nx, 4],
        m.model_error.iter().flat_map(|e| e.iter().copied()),
    )?;
    Ok(())
}

pub fn run(a: RoughMapArgs) -> anyhow::Result<()> {
    if a.timings && a.json.is_none() {
        anyhow::bail!("--timings puts the computing time into the JSON: give --json FILE too, or leave out --timings (the time is always printed on stderr)");
    }
    let spec = a.spec();
    spec.validate()
        .map_err(|e| super::in_flags(&e, super::ROUGH_MAP_FLAGS))?;
    crate::rough::map::check_checks(a.check)
        .map_err(|e| super::in_flags(&e, &[("check", "--check")]))?;
    let figure = a.figure.outputs(Some(&a.out), "--out")?;
    let print = a.figure.print("rough-map")?;
    let more = super::data_outputs(a.json.as_deref(), a.npy.as_deref(), &NPY_FILES);
    a.figure.check_distinct(Some(&a.out), "--out", more)?;
    // Every output is opened before the work; none is put in place unless all were written.
    let open = |p: &Option<PathBuf>| -> anyhow::Result<Option<Output>> {
        p.as_ref()
            .map(|p| Output::create(p).with_context(|| p.display().to_string()))
            .transpose()
    };
    let mut figure_out = [open(&figure.png)?, open(&figure.svg)?, open(&figure.pdf)?];
    let mut json_out = open(&a.json).context("--json")?;
    let mut npy = super::open_npy(a.npy.as_deref(), &NPY_FILES)?;
    let engine = super::rough::table_engine(a.backend, &a.adapter, a.precision)?;
    let m = crate::rough::map::compute_with(&spec, a.check, &engine)?;
    let want = crate::render::Formats {
        png: figure.png.is_some(),
        svg: figure.svg.is_some(),
        pdf: figure.pdf.is_some(),
    };
    let fig = crate::render::draw_figure(crate::render::Kind::Map, &print, want, &|r| {
        crate::render::rough::map(r, &m)
    })
    .map_err(anyhow::Error::from_boxed)
    .context("rendering the figure")?;
    let bytes = [
        fig.png.as_deref(),
        fig.svg.as_ref().map(|s| s.as_bytes()),
        fig.pdf.as_deref(),
    ];
    let put = |o: &mut Output, bytes: &[u8]| -> anyhow::Result<()> {
        let shown = o.name().display().to_string();
        o.write_all(bytes)
            .with_context(|| format!("cannot write {shown}"))
    };
    for (o, b) in figure_out.iter_mut().zip(bytes) {
        if let (Some(o), Some(b)) = (o.as_mut(), b) {
            put(o, b)?;
        }
    }
    if let Some(o) = json_out.as_mut() {
        let shown = o.name().display().to_string();
        write_json(o, &m, a.json_full, a.timings)
            .with_context(|| format!("cannot write {shown}"))?;
    }
    if !npy.is_empty() {
        write_npy(&m, &mut npy)?;
    }
    for o in figure_out.into_iter().flatten().chain(json_out).chain(npy) {
        o.commit()?;
    }
    let counts: Vec<String> = m
        .region_counts()
        .iter()
        .map(|(r, n)| {
            format!(
                "{} {:.1}%",
                r.name(),
                100.0 * *n as f64 / m.regions.len() as f64
            )
        })
        .collect();
    eprintln!(
        "rough map {}x{}: {:.3} s; table error {:.1e}; check on {} points: largest relative difference {:.1e}; wrote {}",
        spec.nx,
        spec.ny,
        m.seconds,
        m.table_error_max(),
        m.check.points,
        m.check.max_relative_difference,
        a.out.display()
    );
    if let Some(c) = &m.table_check {
        eprintln!("tables on {}: {c}", m.table_backend);
    }
    eprintln!("regions: {}", counts.join(", "));
    Ok(())
}
