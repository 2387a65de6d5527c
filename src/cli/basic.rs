//! `tabor solve`, `tabor pulloff`, `tabor curve`.

use super::{BackendArg, Format, PrecisionArg};
use crate::engine::{Backend, Engine};
use crate::io::{fmt17, json_num, write_output, Output};
use crate::law::two_zone::ContextError;
use crate::physics::md::LAMBDA_D;
use crate::solver::{Control, LambdaContext, State, Status};
use anyhow::{bail, Context};
use clap::Args;
use serde_json::json;
use std::fmt::Write as _;
use std::io::Write as _;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct SolveArgs {
    /// CSV with a header row and the columns `lambda` and `load` (or `approach`); `-` is stdin.
    #[arg(long, short)]
    pub input: Option<String>,
    /// Output file; `-` (the default) is stdout.
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Maugis parameter of a single state.
    #[arg(long, conflicts_with = "input")]
    pub lambda: Option<f64>,
    /// Normalised load Pbar = P / (pi w R) of a single state (load control).
    #[arg(long, conflicts_with = "input")]
    pub load: Option<f64>,
    /// Normalised approach Dbar of a single state (displacement control).
    #[arg(long, conflicts_with_all = ["input", "load"])]
    pub approach: Option<f64>,
    /// What is given: the load (dead load, column `load`), the approach (rigid grips, column
    /// `approach`) or the contact radius (column `A`). Default: load.
    #[arg(long, value_enum)]
    pub control: Option<Given>,
    /// Contact radius A of a single state (the curve point there, with its stability).
    #[arg(long, conflicts_with_all = ["input", "load", "approach"])]
    pub radius_a: Option<f64>,
    /// A second Dugdale zone (e.g. a water meniscus) for a single state: its stress over the
    /// solid's, s2/s1; --lambda is then the solid's, units on the total w (docs/PHYSICS.md
    /// section 10).
    /// With --input, the same second zone for every row (each row's lambda the solid's), solved
    /// on the CPU.
    #[arg(long)]
    pub stress_ratio: Option<f64>,
    /// The second zone's range over the solid's, h2/h1.
    #[arg(long)]
    pub range_ratio: Option<f64>,
    /// A tip that is not a sphere (docs/PHYSICS.md section 12), with --lambda its Maugis
    /// parameter and the load, approach and radii in its units, on the CPU: cone, power:N or
    /// capped-cone:R_OVER_L:HALF_ANGLE_DEG.
    /// Or scene:FILE, the tip of a scene file in the units of its E* and w (any SI tip, a measured
    /// profile among them).
    #[arg(long, conflicts_with_all = ["stress_ratio", "range_ratio"])]
    pub tip: Option<String>,
    /// Output format (default: text for one state, csv for a file).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Where a CSV of points is solved; `auto` takes a hardware GPU if there is one (a software
    /// adapter is slower than the exact CPU solver on the same cores).
    /// [default: cpu, or the environment variable TABOR_BACKEND]
    #[arg(long, value_enum)]
    pub backend: Option<BackendArg>,
    #[command(flatten)]
    pub gpu: GpuArgs,
    /// Put the solve time into the output (JSON metadata) or on stderr; off by default so that
    /// the same command gives the same bytes.
    #[arg(long)]
    pub timings: bool,
}

#[derive(Args, Debug, Clone)]
pub struct GpuArgs {
    /// Use the first adapter whose name contains this text (see `tabor info`) [default: the
    /// environment variable TABOR_ADAPTER].
    #[arg(long)]
    pub adapter: Option<String>,
    /// GPU results: re-solve N evenly spaced points (or `all`) on the CPU in f64 and report the
    /// errors (also written into the JSON metadata).
    #[arg(long, default_value = "1000")]
    pub check: CheckCount,
    /// GPU arithmetic: the f32 kernels, or f64 (their states refined by Newton steps in f64 on
    /// the GPU; needs an adapter with SHADER_F64, see `tabor info`). The CPU path is f64.
    #[arg(long, value_enum, default_value_t = PrecisionArg::F32)]
    pub precision: PrecisionArg,
}

#[derive(Clone, Copy, Debug)]
pub struct CheckCount(pub usize);

impl std::str::FromStr for CheckCount {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s == "all" {
            return Ok(CheckCount(usize::MAX));
        }
        s.parse()
            .map(CheckCount)
            .map_err(|_| format!("expected a number of points or `all`, got {s:?}"))
    }
}

pub use crate::engine::GPU_TOLERANCE;

/// Rows of an input table solved at a time: memory stays bounded (under 100 MB) whatever the
/// size of the input.
pub const CHUNK_ROWS: usize = 1 << 16;

/// Chooses the engine for `--backend` and `--precision`, and says which in one line on stderr.
pub fn engine_for(
    backend: Option<BackendArg>,
    default: BackendArg,
    gpu: &GpuArgs,
) -> anyhow::Result<Engine> {
    let backend = super::backend_choice(backend, default)?;
    let adapter = super::adapter_choice(gpu.adapter.as_deref(), backend)?;
    let (mut engine, line) = Engine::select(backend.into(), adapter.as_deref())?;
    engine.set_precision(gpu.precision.into()).map_err(|e| {
        super::in_flags(
            &e,
            &[
                ("precision=f32", "--precision f32"),
                ("backend=cpu", "--backend cpu"),
            ],
        )
    })?;
    eprintln!("{line}");
    Ok(engine)
}

/// f32 results carry 9 significant digits (what the arithmetic supports); f64 ones 17.
fn digits_of(engine: &Engine) -> usize {
    if engine.precision() == "f32" {
        9
    } else {
        17
    }
}

/// A computed number with `digits` significant digits; empty where it could not be computed.
fn fmt_digits(x: f64, digits: usize) -> String {
    if digits >= 17 || !x.is_finite() {
        fmt17(x)
    } else {
        format!("{x:.prec$e}", prec = digits - 1)
    }
}

fn value_column(control: Control) -> &'static str {
    match control {
        Control::Load => "load",
        Control::Displacement => "approach",
    }
}

/// What `tabor solve` is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Given {
    /// The load Pbar (dead load; column `load`).
    Load,
    /// The approach Dbar (rigid grips; column `approach`).
    Displacement,
    /// The contact radius A (column `A`): the curve point there, stable or not.
    Radius,
}

impl From<Given> for crate::law::Given {
    fn from(g: Given) -> Self {
        match g {
            Given::Load => crate::law::Given::Load,
            Given::Displacement => crate::law::Given::Approach,
            Given::Radius => crate::law::Given::Radius,
        }
    }
}

impl Given {
    /// The input table's column of the value given.
    pub(super) fn column(self) -> &'static str {
        match self {
            Given::Load => "load",
            Given::Displacement => "approach",
            Given::Radius => "A",
        }
    }
    pub(super) fn flag(self) -> &'static str {
        match self {
            Given::Load => "--load",
            Given::Displacement => "--approach",
            Given::Radius => "--radius-a",
        }
    }
    pub(super) fn name(self) -> &'static str {
        match self {
            Given::Load => "load",
            Given::Displacement => "displacement",
            Given::Radius => "radius",
        }
    }
}

/// `tabor solve` for a sphere, one zone or two (a tip's states are [`super::tip::solve`]'s).
pub fn solve(a: SolveArgs) -> anyhow::Result<()> {
    let ratios = super::two_zone_ratios(a.stress_ratio, a.range_ratio)?;
    if let Some(input) = &a.input {
        if let Some((rho, eta)) = ratios {
            return solve_two_zone_file(&a, input, (rho, eta));
        }
        return match a.control {
            Some(Given::Radius) => solve_radius_file(&a, input),
            _ => solve_file(&a, input),
        };
    }
    let lambda = a
        .lambda
        .context("give --input FILE, or --lambda with --load, --approach or --radius-a")?;
    let (given, value) = match (a.load, a.approach, a.radius_a) {
        (Some(l), None, None) => (Given::Load, l),
        (None, Some(d), None) => (Given::Displacement, d),
        (None, None, Some(r)) => (Given::Radius, r),
        _ => bail!("give one of --load, --approach or --radius-a with --lambda"),
    };
    if let Some((rho, eta)) = ratios {
        return solve_two_zone(&a, lambda, (rho, eta), given, value);
    }
    if let Some(c) = a.control.filter(|&c| c != given) {
        bail!(
            "--control {} does not match the value given ({}); give {} for {} control",
            c.name(),
            given.flag(),
            c.flag(),
            c.name()
        );
    }
    if super::backend_choice(a.backend, BackendArg::Cpu)? != BackendArg::Cpu {
        eprintln!("note: a single state is solved by the f64 CPU solver; --backend applies to --input files");
    }
    // Beyond the exact solver's domain a load or an approach is answered by the closed-form
    // limit where it is certified; a radius is not (the limits' curves are not MD's).
    let limit = given != Given::Radius
        && matches!(
            crate::physics::domain::method(lambda),
            Some(
                crate::physics::domain::Method::DmtLimit | crate::physics::domain::Method::JkrLimit
            )
        );
    if given == Given::Radius
        && crate::physics::domain::method(lambda)
            .is_some_and(|m| m != crate::physics::domain::Method::Md)
    {
        bail!(
            "--lambda {} with --radius-a: {}",
            crate::solver::domain::short(lambda),
            crate::solver::limits::radius_refusal(lambda)
        );
    }
    let ctx = if limit {
        None
    } else {
        Some(LambdaContext::new(lambda).context("--lambda")?)
    };
    let format = a.format.unwrap_or(Format::Text);
    let meta = json!({"tabor_version": env!("CARGO_PKG_VERSION"), "backend": "cpu", "precision": "f64", "control": given.name()});
    let text = if given == Given::Radius {
        radius_doc(ctx, value, format, &meta)?
    } else {
        state_doc(ctx.as_ref(), lambda, given, value, format, &meta)?
    };
    write_output(&a.output, text.as_bytes())
}

/// `tabor solve --radius-a`'s one state in its format.
fn radius_doc(
    ctx: Option<LambdaContext>,
    value: f64,
    format: Format,
    meta: &serde_json::Value,
) -> anyhow::Result<String> {
    crate::solver::domain::check_radius(value).context("--radius-a")?;
    let ctx = ctx.context("--lambda")?;
    let s = ctx.solve_radius(value);
    Ok(match format {
        Format::Json => json_doc(&[radius_json(&s)], meta)?,
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(RADIUS_CSV_HEADER)?;
            w.write_record(radius_fields(&s))?;
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        Format::Text => radius_text(&ctx, &s),
    })
}

/// `tabor solve --load` or `--approach`'s one state in its format: the exact solver's, or
/// (`ctx` None) the closed-form limit's where it is certified.
fn state_doc(
    ctx: Option<&LambdaContext>,
    lambda: f64,
    given: Given,
    value: f64,
    format: Format,
    meta: &serde_json::Value,
) -> anyhow::Result<String> {
    let control = if given == Given::Load {
        crate::solver::domain::check_load(value).context("--load")?;
        Control::Load
    } else {
        crate::solver::domain::check_approach(value).context("--approach")?;
        Control::Displacement
    };
    let s = match ctx {
        Some(ctx) => crate::solver::solve_with(ctx, value, control),
        None => crate::solver::solve_one(lambda, value, control),
    };
    if ctx.is_none() && s.status == Status::InvalidInput {
        bail!(
            "--lambda {} with {} {}: {}",
            crate::solver::domain::short(lambda),
            given.flag(),
            crate::solver::domain::short(value),
            crate::solver::limits::refusal(lambda, control)
        );
    }
    Ok(match format {
        Format::Json => json_doc(&[state_json(&s)], meta)?,
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(CSV_HEADER)?;
            w.write_record(state_fields(&s, 17, control))?;
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        Format::Text => state_text(ctx, &s, control),
    })
}

/// One state of the two-zone law (solid's lambda, stress and range ratios) on the CPU: the state
/// at a load, approach or contact radius with both zone edges, or its status.
fn solve_two_zone(
    a: &SolveArgs,
    lambda: f64,
    (rho, eta): (f64, f64),
    given: Given,
    value: f64,
) -> anyhow::Result<()> {
    if super::backend_choice(a.backend, BackendArg::Cpu)? != BackendArg::Cpu {
        eprintln!("note: two zones are solved by the f64 CPU solver only");
    }
    let ctx = two_zone_context(lambda, rho, eta)?;
    if !value.is_finite() || (given == Given::Radius && value <= 0.0) {
        bail!(
            "{} {value}: give a finite number (a contact radius > 0)",
            given.flag()
        );
    }
    let s = crate::law::two_zone::state(&ctx, given.into(), value);
    let vals = two_zone_values(lambda, (rho, eta), given, value, &s);
    let text = match a.format.unwrap_or(Format::Text) {
        Format::Json => serde_json::to_string_pretty(&two_zone_json(&vals, &s, given))? + "\n",
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(TWO_ZONE_HEADER)?;
            w.write_record(two_zone_fields(&vals, &s))?;
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        Format::Text => format!(
            "two zones (stress ratio {rho}, range ratio {eta}; units on w1 + w2): load {}, A {}, approach {}, c1 {}, c2 {}, status {}\n",
            vals[3], vals[4], vals[5], vals[6], vals[7], s.status.name()
        ),
    };
    write_output(&a.output, text.as_bytes())
}

/// The two-zone law of the solid's lambda and the second zone's ratios.
fn two_zones(lambda: f64, rho: f64, eta: f64) -> crate::law::TwoZones {
    crate::law::TwoZones {
        lambda,
        stress_ratio: rho,
        range_ratio: eta,
    }
}

/// The law's curve, its errors in the command's flags.
fn two_zone_context(
    lambda: f64,
    rho: f64,
    eta: f64,
) -> anyhow::Result<crate::solver::two_zone::TwoZoneContext> {
    two_zones(lambda, rho, eta).context().map_err(|e| match e {
        ContextError::Zones(e) => super::zones_error(e),
        e => anyhow::anyhow!("--lambda {lambda}: {e}"),
    })
}

/// The columns of a two-zone state (CSV, and the keys of its JSON object).
const TWO_ZONE_HEADER: [&str; 9] = [
    "lambda",
    "stress_ratio",
    "range_ratio",
    "load",
    "A",
    "approach",
    "c1",
    "c2",
    "status",
];

/// The numbers of a two-zone state, in [`TWO_ZONE_HEADER`]'s order: where no state was found,
/// the value given stays in its column and the rest are NaN (empty in CSV, null in JSON).
fn two_zone_values(
    lambda: f64,
    (rho, eta): (f64, f64),
    given: Given,
    value: f64,
    s: &crate::solver::two_zone::TwoZoneState,
) -> [f64; 8] {
    let mut v = [lambda, rho, eta, s.load, s.a, s.approach, s.c[0], s.c[1]];
    let k = match given {
        Given::Load => 3,
        Given::Radius => 4,
        Given::Displacement => 5,
    };
    if v[k].is_nan() {
        v[k] = value;
    }
    v
}

fn two_zone_fields(vals: &[f64; 8], s: &crate::solver::two_zone::TwoZoneState) -> Vec<String> {
    let mut row: Vec<String> = vals.iter().map(|&v| fmt17(v)).collect();
    row.push(s.status.name().to_string());
    row
}

fn two_zone_json(
    vals: &[f64; 8],
    s: &crate::solver::two_zone::TwoZoneState,
    given: Given,
) -> serde_json::Value {
    let mut m: serde_json::Map<_, _> = TWO_ZONE_HEADER
        .iter()
        .zip(vals)
        .map(|(k, &v)| (k.to_string(), json_num(v)))
        .collect();
    m.insert("load_stable".into(), json!(s.load_stable));
    m.insert("displacement_stable".into(), json!(s.displacement_stable));
    m.insert("status".into(), json!(s.status.name()));
    m.insert("control".into(), json!(given.name()));
    serde_json::Value::Object(m)
}

/// A table of points of the two-zone law (each row's lambda the solid's, the same stress and
/// range ratios for all) on the CPU in f64, streamed in chunks: each distinct lambda's curve is
/// computed once per chunk, and a row that cannot be solved gets its status.
fn solve_two_zone_file(a: &SolveArgs, input: &str, (rho, eta): (f64, f64)) -> anyhow::Result<()> {
    use crate::solver::two_zone::{TwoZoneContext, TwoZoneState};
    use rayon::prelude::*;
    let given = a.control.unwrap_or(Given::Load);
    let format = match a.format.unwrap_or(Format::Csv) {
        Format::Text => bail!("--format text is for a single state; use csv or json for --input"),
        f => f,
    };
    // The ratios are checked once before anything is written; a row whose lambda makes a
    // zone's stress number one the solver does not take is invalid_input.
    crate::solver::two_zone::check_ratios(rho, eta).map_err(super::zones_error)?;
    if super::backend_choice(a.backend, BackendArg::Cpu)? != BackendArg::Cpu {
        eprintln!("note: two zones are solved by the f64 CPU solver only");
    }
    let column = given.column();
    let mut reader = crate::io::PointReader::open(input, column)?;
    let mut table = StreamTable::start(Output::create(&a.output)?, format, &TWO_ZONE_HEADER)?;
    eprintln!("backend: CPU f64 (two zones: stress ratio {rho}, range ratio {eta})");
    let failed = TwoZoneState::failed;
    loop {
        let chunk = reader.next_chunk(CHUNK_ROWS)?;
        if chunk.is_empty() {
            break;
        }
        // Each distinct lambda's curve once.
        let mut lambdas: Vec<f64> = chunk.iter().map(|p| p.0).collect();
        lambdas.sort_by(f64::total_cmp);
        lambdas.dedup_by(|x, y| x.to_bits() == y.to_bits());
        let contexts: Vec<Result<TwoZoneContext, Status>> = lambdas
            .par_iter()
            .map(|&l| {
                two_zones(l, rho, eta).context().map_err(|e| match e {
                    ContextError::Zones(_) => Status::InvalidInput,
                    ContextError::Curve(st) => st,
                })
            })
            .collect();
        let rows: Vec<([f64; 8], TwoZoneState)> = chunk
            .par_iter()
            .map(|&(l, v)| {
                let i = lambdas
                    .binary_search_by(|x| x.total_cmp(&l))
                    .expect("every lambda of the chunk is listed");
                let s = match &contexts[i] {
                    _ if !v.is_finite() || (given == Given::Radius && v <= 0.0) => {
                        failed(Status::InvalidInput)
                    }
                    Ok(ctx) => crate::law::two_zone::state(ctx, given.into(), v),
                    Err(st) => failed(*st),
                };
                (two_zone_values(l, (rho, eta), given, v, &s), s)
            })
            .collect();
        table.rows(
            &rows,
            |(v, s)| two_zone_json(v, s, given),
            |(v, s), buf| {
                let mut w = crate::io::csv_writer();
                if w.write_record(two_zone_fields(v, s)).is_ok() {
                    buf.extend(crate::io::csv_finish(w).unwrap_or_default());
                }
            },
        )?;
    }
    table.finish(|rows| {
        Ok(json!({"tabor_version": env!("CARGO_PKG_VERSION"), "backend": "cpu", "precision": "f64", "control": given.name(), "stress_ratio": rho, "range_ratio": eta, "points": rows}))
    })
}

/// `{"results": [...], "metadata": ...}` as `solve` writes it.
fn json_doc(results: &[serde_json::Value], meta: &serde_json::Value) -> anyhow::Result<String> {
    let mut t = String::from("{\n  \"results\": [\n");
    let rows: Vec<String> = results
        .iter()
        .map(|r| serde_json::to_string_pretty(r).map(|s| indent(&s, 4)))
        .collect::<Result<_, _>>()?;
    t += &rows.join(",\n");
    t += "\n  ],\n  \"metadata\": ";
    t += indent(&serde_json::to_string_pretty(meta)?, 2).trim_start();
    Ok(t + "\n}\n")
}

const RADIUS_CSV_HEADER: [&str; 8] = [
    "lambda",
    "A",
    "load",
    "approach",
    "m_minus_1",
    "load_stable",
    "displacement_stable",
    "status",
];

/// The CSV fields of a state given by its radius.
fn radius_fields(s: &crate::solver::RadiusState) -> [String; 8] {
    let ok = s.status == crate::solver::Status::Ok;
    let flag = |b: bool| {
        if ok {
            (b as u8).to_string()
        } else {
            String::new()
        }
    };
    [
        fmt17(s.lambda),
        fmt17(s.a),
        fmt17(s.load),
        fmt17(s.approach),
        fmt17(s.m_minus_1),
        flag(s.load_stable),
        flag(s.displacement_stable),
        s.status.name().to_string(),
    ]
}

fn radius_json(s: &crate::solver::RadiusState) -> serde_json::Value {
    let ok = s.status == crate::solver::Status::Ok;
    json!({
        "lambda": s.lambda, "A": json_num(s.a), "load": json_num(s.load),
        "approach": json_num(s.approach), "m_minus_1": json_num(s.m_minus_1),
        "load_stable": ok.then_some(s.load_stable), "displacement_stable": ok.then_some(s.displacement_stable),
        "status": s.status.name(),
    })
}

fn radius_text(ctx: &LambdaContext, s: &crate::solver::RadiusState) -> String {
    let mut t = String::new();
    let ok = s.status == crate::solver::Status::Ok;
    let yes = |b: bool| match (ok, b) {
        (false, _) => "not computed",
        (true, true) => "stable",
        (true, false) => "unstable",
    };
    let _ = writeln!(
        t,
        "Maugis-Dugdale state, lambda = {} (contact radius given)",
        crate::solver::domain::short(s.lambda)
    );
    let _ = writeln!(t, "  status            {}", s.status.name());
    let _ = writeln!(t, "  contact radius A  {}", fmt17(s.a));
    let _ = writeln!(t, "  load   Pbar       {}", fmt17(s.load));
    let _ = writeln!(t, "  approach Dbar     {}", fmt17(s.approach));
    let _ = writeln!(t, "  m - 1 (c/a - 1)   {}", fmt17(s.m_minus_1));
    let _ = writeln!(
        t,
        "  under load control {}, under displacement control {}",
        yes(s.load_stable),
        yes(s.displacement_stable)
    );
    let _ = writeln!(
        t,
        "  pull-off, load control          Pbar_c = {}  at A = {}",
        fmt17(ctx.load_pulloff.load),
        fmt17(ctx.load_pulloff.a)
    );
    t
}

/// A CSV or JSON table of results written as it is computed: the header (or the JSON opening),
/// chunks of rows, then the JSON metadata and the commit. Memory stays one chunk.
pub(super) struct StreamTable {
    out: Output,
    shown: String,
    json: bool,
    rows: usize,
}

impl StreamTable {
    pub(super) fn start(
        out: Output,
        format: Format,
        header: &[&str],
    ) -> anyhow::Result<StreamTable> {
        let shown = out.name().display().to_string();
        let mut t = StreamTable {
            out,
            shown,
            json: format == Format::Json,
            rows: 0,
        };
        if t.json {
            t.put(b"{\n  \"results\": [\n")?;
        } else {
            let mut w = crate::io::csv_writer();
            w.write_record(header)?;
            t.put(&crate::io::csv_finish(w)?)?;
        }
        Ok(t)
    }

    fn put(&mut self, bytes: &[u8]) -> anyhow::Result<()> {
        let shown = &self.shown;
        self.out
            .write_all(bytes)
            .with_context(|| format!("cannot write {shown}"))
    }

    /// One chunk of rows: each item as a JSON object or as CSV fields, formatted on all cores
    /// (in slices, joined in order: the same bytes as one writer would give).
    pub(super) fn rows<T: Sync>(
        &mut self,
        items: &[T],
        json: impl Fn(&T) -> serde_json::Value + Sync,
        csv: impl Fn(&T, &mut Vec<u8>) + Sync,
    ) -> anyhow::Result<()> {
        use rayon::prelude::*;
        const SLICE: usize = 2048;
        let first = self.rows == 0;
        let parts: Vec<Vec<u8>> = if self.json {
            items
                .par_chunks(SLICE)
                .enumerate()
                .map(|(j, c)| -> anyhow::Result<Vec<u8>> {
                    let mut buf = String::new();
                    for (k, item) in c.iter().enumerate() {
                        if !(first && j == 0 && k == 0) {
                            buf.push_str(",\n");
                        }
                        buf += &indent(&serde_json::to_string_pretty(&json(item))?, 4);
                    }
                    Ok(buf.into_bytes())
                })
                .collect::<anyhow::Result<_>>()?
        } else {
            items
                .par_chunks(SLICE)
                .map(|c| {
                    let mut buf = Vec::with_capacity(c.len() * 96);
                    for item in c {
                        csv(item, &mut buf);
                    }
                    buf
                })
                .collect()
        };
        self.rows += items.len();
        for p in parts {
            self.put(&p)?;
        }
        Ok(())
    }

    /// Closes the JSON with `metadata` (built from the row count), and puts the output in place.
    pub(super) fn finish(
        mut self,
        metadata: impl FnOnce(usize) -> anyhow::Result<serde_json::Value>,
    ) -> anyhow::Result<()> {
        if self.json {
            let meta = metadata(self.rows)?;
            let tail = format!(
                "\n  ],\n  \"metadata\": {}\n}}\n",
                indent(&serde_json::to_string_pretty(&meta)?, 2).trim_start()
            );
            self.put(tail.as_bytes())?;
        }
        self.out.commit()
    }
}

/// A table of (lambda, A) points: the curve point at each radius, on the CPU (no root search in
/// the load is needed), streamed in chunks.
fn solve_radius_file(a: &SolveArgs, input: &str) -> anyhow::Result<()> {
    let format = match a.format.unwrap_or(Format::Csv) {
        Format::Text => bail!("--format text is for a single state; use csv or json for --input"),
        f => f,
    };
    let mut reader = crate::io::PointReader::open(input, "A")?;
    let mut table = StreamTable::start(Output::create(&a.output)?, format, &RADIUS_CSV_HEADER)?;
    eprintln!("backend: CPU f64 (radius control: each state is the curve point at its radius)");
    loop {
        let chunk = reader.next_chunk(CHUNK_ROWS)?;
        if chunk.is_empty() {
            break;
        }
        let states = crate::solver::solve_radius_points(&chunk);
        table.rows(&states, radius_json, |s, buf| {
            let mut w = crate::io::csv_writer();
            if w.write_record(radius_fields(s)).is_ok() {
                buf.extend(crate::io::csv_finish(w).unwrap_or_default());
            }
        })?;
    }
    table.finish(|rows| {
        Ok(json!({"tabor_version": env!("CARGO_PKG_VERSION"), "backend": "cpu", "precision": "f64", "control": "radius", "points": rows}))
    })
}

/// A CSV or JSON table of points, streamed in chunks of [`CHUNK_ROWS`]: parse, solve, write.
fn solve_file(a: &SolveArgs, input: &str) -> anyhow::Result<()> {
    let control = match a.control {
        Some(Given::Displacement) => Control::Displacement,
        _ => Control::Load,
    };
    let format = match a.format.unwrap_or(Format::Csv) {
        Format::Text => bail!("--format text is for a single state; use csv or json for --input"),
        f => f,
    };
    let mut reader = crate::io::PointReader::open(input, value_column(control))?;
    let mut table = StreamTable::start(Output::create(&a.output)?, format, &CSV_HEADER)?;
    let engine = engine_for(a.backend, BackendArg::Cpu, &a.gpu)?;
    let digits = digits_of(&engine);
    let is_gpu = matches!(engine, Engine::Gpu(_));
    let len = std::fs::metadata(input).map_or(0, |m| m.len());
    let mut progress = crate::progress::Progress::new("solving", len, "bytes");
    let mut check = crate::engine::CheckReport::empty(GPU_TOLERANCE);
    let mut solve_s = 0.0;
    // The next chunk is parsed on its own thread while this one is solved and written; the
    // channel holds two chunks, so memory stays bounded whatever the input size.
    std::thread::scope(|scope| -> anyhow::Result<()> {
        let (tx, rx) = std::sync::mpsc::sync_channel(2);
        scope.spawn(move || loop {
            let next = reader.next_chunk(CHUNK_ROWS);
            let done = !matches!(&next, Ok(c) if !c.is_empty());
            if tx.send(next.map(|c| (c, reader.bytes_read()))).is_err() || done {
                break;
            }
        });
        for next in rx {
            let (chunk, bytes) = next?;
            if chunk.is_empty() {
                break;
            }
            let t = std::time::Instant::now();
            let (states, report) = engine.solve_points_checked(&chunk, control, a.gpu.check.0)?;
            solve_s += t.elapsed().as_secs_f64();
            if let Some(r) = report {
                check.merge(r);
            }
            table.rows(
                &states,
                |s| state_json_digits(s, digits, control),
                |s, buf| state_row(s, digits, control, buf),
            )?;
            progress.set(bytes);
        }
        Ok(())
    })?;
    progress.finish();
    if is_gpu {
        eprintln!("{check}");
    }
    let rows = table.rows;
    table.finish(|rows| {
        let mut meta = json!({
            "tabor_version": env!("CARGO_PKG_VERSION"),
            "backend": engine.name(),
            "adapter": engine.adapter(),
            "precision": engine.precision(),
            "significant_digits": digits,
            "control": control,
            "points": rows,
        });
        if is_gpu {
            meta["cross_check"] = serde_json::to_value(&check)?;
        }
        if a.timings {
            meta["solve_seconds"] = json!(solve_s);
        }
        Ok(meta)
    })?;
    if format != Format::Json && a.timings {
        eprintln!("solved {rows} points in {solve_s:.3} s");
    }
    Ok(())
}

/// Every line of `text` indented by `n` spaces.
fn indent(text: &str, n: usize) -> String {
    let pad = " ".repeat(n);
    text.lines()
        .map(|l| format!("{pad}{l}"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `method`: `md` (the exact solver), `dmt_limit` or `jkr_limit` (beyond its domain, where the
/// closed-form limit is certified; `domain::method`), empty where lambda has none.
const CSV_HEADER: [&str; 7] = [
    "lambda",
    "load",
    "A",
    "approach",
    "m_minus_1",
    "status",
    "method",
];

/// A CSV row of a state, as a CSV writer would write [`state_fields`] (numbers and status
/// names never need quoting), appended without allocating.
fn state_row(s: &State, digits: usize, control: Control, buf: &mut Vec<u8>) {
    use crate::io::fmt_into;
    let (load, approach) = match control {
        Control::Load => (17, digits),
        Control::Displacement => (digits, 17),
    };
    fmt_into(buf, s.lambda, 17);
    buf.push(b',');
    fmt_into(buf, s.load, load);
    buf.push(b',');
    fmt_into(buf, s.a, digits);
    buf.push(b',');
    fmt_into(buf, s.approach, approach);
    buf.push(b',');
    fmt_into(buf, s.m_minus_1, digits);
    buf.push(b',');
    buf.extend_from_slice(s.status.name().as_bytes());
    buf.push(b',');
    buf.extend_from_slice(crate::physics::domain::method_name(s.lambda).as_bytes());
    buf.push(b'\n');
}

/// The CSV fields of a state: what was given with 17 digits, what was computed with `digits`.
fn state_fields(s: &State, digits: usize, control: Control) -> [String; 7] {
    let (load, approach) = match control {
        Control::Load => (fmt17(s.load), fmt_digits(s.approach, digits)),
        Control::Displacement => (fmt_digits(s.load, digits), fmt17(s.approach)),
    };
    [
        fmt17(s.lambda),
        load,
        fmt_digits(s.a, digits),
        approach,
        fmt_digits(s.m_minus_1, digits),
        s.status.name().to_string(),
        crate::physics::domain::method_name(s.lambda).to_string(),
    ]
}

pub fn state_json(s: &State) -> serde_json::Value {
    json!({
        "lambda": s.lambda, "load": json_num(s.load), "A": json_num(s.a),
        "approach": json_num(s.approach), "m_minus_1": json_num(s.m_minus_1),
        "status": s.status.name(), "method": crate::physics::domain::method(s.lambda),
    })
}

/// As [`state_json`], computed numbers rounded to `digits` significant digits.
fn state_json_digits(s: &State, digits: usize, control: Control) -> serde_json::Value {
    if digits >= 17 {
        return state_json(s);
    }
    let r = |x: f64| fmt_digits(x, digits).parse::<f64>().unwrap_or(f64::NAN);
    let mut v = state_json(s);
    v["A"] = json_num(r(s.a));
    v["m_minus_1"] = json_num(r(s.m_minus_1));
    // The computed one of load and approach (the other was given).
    match control {
        Control::Load => v["approach"] = json_num(r(s.approach)),
        Control::Displacement => v["load"] = json_num(r(s.load)),
    }
    v
}

fn shown(x: f64) -> String {
    if x.is_nan() {
        "(not defined: no contact)".into()
    } else {
        fmt17(x)
    }
}

fn state_text(ctx: Option<&LambdaContext>, s: &State, control: Control) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "Maugis-Dugdale state, lambda = {} ({} control)",
        crate::solver::domain::short(s.lambda),
        match control {
            Control::Load => "load",
            Control::Displacement => "displacement",
        }
    );
    let _ = writeln!(t, "  status            {}", s.status.name());
    let _ = writeln!(t, "  load   Pbar       {}", shown(s.load));
    let _ = writeln!(t, "  approach Dbar     {}", shown(s.approach));
    let _ = writeln!(t, "  contact radius A  {}", shown(s.a));
    let _ = writeln!(t, "  m - 1 (c/a - 1)   {}", shown(s.m_minus_1));
    match ctx {
        Some(ctx) => {
            let lp = ctx.load_pulloff;
            let dp = ctx.disp_pulloff();
            let _ = writeln!(
                t,
                "  pull-off, load control          Pbar_c = {}  at A = {}",
                fmt17(lp.load),
                fmt17(lp.a)
            );
            let _ = writeln!(
                t,
                "  jump-out, displacement control  Pbar   = {}  at A = {}",
                fmt17(dp.load),
                fmt17(dp.a)
            );
        }
        None => {
            let method = crate::physics::domain::method(s.lambda);
            let _ = writeln!(
                t,
                "  method            {} (beyond the exact solver's lambda range {}..{}: the closed-form limit, within {} of MD)",
                crate::physics::domain::method_name(s.lambda),
                crate::solver::domain::short(crate::physics::domain::LAMBDA_MIN),
                crate::solver::domain::short(crate::physics::domain::LAMBDA_MAX),
                crate::solver::domain::short(crate::physics::domain::LIMIT_TOL),
            );
            if method == Some(crate::physics::domain::Method::JkrLimit) {
                let _ = writeln!(t, "  pull-off, load control          Pbar_c = -1.5 (JKR)");
                let _ = writeln!(
                    t,
                    "  jump-out, displacement control  Pbar   = -0.83333333333333333 (JKR)"
                );
            } else {
                let _ = writeln!(
                    t,
                    "  pull-off                        Pbar_c = -2 (DMT/Bradley)"
                );
                if s.status == Status::InvalidInput {
                    let _ = writeln!(
                        t,
                        "  (too close to the pull-off for the DMT limit: not certified here)"
                    );
                }
            }
        }
    }
    if s.status == Status::NoContact {
        let _ = writeln!(t, "  (below the pull-off of this control: no contact)");
    }
    t
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct PulloffArgs {
    /// Maugis parameters, comma separated.
    #[arg(long, value_delimiter = ',', required = true, num_args = 1..)]
    pub lambda: Vec<f64>,
    /// A second Dugdale zone (e.g. a water meniscus): its stress over the solid's, s2/s1.
    /// Loads and radii are then in units built on the total w (docs/PHYSICS.md section 10).
    #[arg(long)]
    pub stress_ratio: Option<f64>,
    /// The second zone's range over the solid's, h2/h1.
    #[arg(long)]
    pub range_ratio: Option<f64>,
    /// The pull-offs of a tip that is not a sphere (docs/PHYSICS.md section 12), in its units:
    /// cone, power:N, capped-cone:R_OVER_L:HALF_ANGLE_DEG or scene:FILE (a scene's tip in the
    /// units of its E* and w).
    #[arg(long, conflicts_with_all = ["stress_ratio", "range_ratio"])]
    pub tip: Option<String>,
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
}

/// A pull-off table as `a.format` asks: CSV of `cols`, JSON `results` (one object per row, the
/// keys of `head` beside them), or the text `text` writes.
fn write_pulloffs(
    a: &PulloffArgs,
    cols: &[&str],
    rows: &[Vec<f64>],
    head: &[(&str, serde_json::Value)],
    text: impl FnOnce() -> String,
) -> anyhow::Result<()> {
    let out = match a.format {
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(cols)?;
            for r in rows {
                w.write_record(r.iter().map(|&v| fmt17(v)))?;
            }
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        Format::Json => {
            let res: Vec<_> = rows
                .iter()
                .map(|r| {
                    let m: serde_json::Map<_, _> = cols
                        .iter()
                        .zip(r)
                        .map(|(k, &v)| (k.to_string(), json_num(v)))
                        .collect();
                    serde_json::Value::Object(m)
                })
                .collect();
            let mut doc: serde_json::Map<_, _> = head
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect();
            doc.insert("results".into(), serde_json::Value::Array(res));
            serde_json::to_string_pretty(&doc)? + "\n"
        }
        Format::Text => text(),
    };
    write_output(&a.output, out.as_bytes())
}

/// The two pull-offs' columns, each control's load, radius and approach.
const PULLOFF_COLS: [&str; 6] = [
    "load_control_load",
    "load_control_A",
    "load_control_approach",
    "displacement_control_load",
    "displacement_control_A",
    "displacement_control_approach",
];

/// `head`, the two pull-offs' columns, then `tail`.
fn pulloff_cols(head: &[&'static str], tail: &[&'static str]) -> Vec<&'static str> {
    [head, &PULLOFF_COLS[..], tail].concat()
}

/// The text table's heading line of the two pull-offs.
fn pulloff_heading() -> String {
    format!(
        "{:>12}  {:>20} {:>12}   {:>20} {:>12}\n",
        "lambda", "Pbar_c (load ctl)", "A there", "Pbar (displ. ctl)", "A there"
    )
}

/// One text row: lambda, the load-controlled pull-off's load and radius, the
/// displacement-controlled one's, and a note where the latter is lost at A = 0.
fn pulloff_line(t: &mut String, lambda: f64, load: (f64, f64), disp: (f64, f64), note: &str) {
    let _ = writeln!(
        t,
        "{:>12}  {:>20.15} {:>12.8}   {:>20.15} {:>12.8}{}",
        lambda, load.0, load.1, disp.0, disp.1, note
    );
}

/// Pull-offs of the two-zone law: the solid's lambda with a second zone given by its stress and
/// range ratios.
fn pulloff_two_zone(a: &PulloffArgs, rho: f64, eta: f64) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for &l in &a.lambda {
        rows.push((l, two_zone_context(l, rho, eta)?));
    }
    let cols = pulloff_cols(&["lambda", "stress_ratio", "range_ratio"], &[]);
    let values: Vec<Vec<f64>> = rows
        .iter()
        .map(|(l, c)| {
            vec![
                *l,
                rho,
                eta,
                c.load_pulloff.load,
                c.load_pulloff.a,
                c.load_pulloff.approach,
                c.disp_pulloff.load,
                c.disp_pulloff.a,
                c.disp_pulloff.approach,
            ]
        })
        .collect();
    write_pulloffs(
        a,
        &cols,
        &values,
        &[("units", json!("total w = w1 + w2"))],
        || {
            let mut t = format!(
                "two Dugdale zones, stress ratio {rho}, range ratio {eta}; loads in pi (w1 + w2) R\n{}",
                pulloff_heading()
            );
            for (l, c) in &rows {
                let (lc, dc) = (&c.load_pulloff, &c.disp_pulloff);
                let note = if dc.at_zero_radius() {
                    "  (lost at A = 0)"
                } else {
                    ""
                };
                pulloff_line(&mut t, *l, (lc.load, lc.a), (dc.load, dc.a), note);
            }
            t
        },
    )
}

/// Pull-offs of a tip's law (docs/PHYSICS.md section 12) in its units: the states at the folds
/// of its contact piece under a dead load and under rigid grips (or its A -> 0 end).
fn pulloff_tip(a: &PulloffArgs, shape: crate::physics::tip::Shape) -> anyhow::Result<()> {
    use crate::law::{Drive, Tip};
    let mut rows = Vec::new();
    for &l in &a.lambda {
        let tip = Tip::new(shape, l).context("--lambda")?;
        rows.push((
            l,
            tip.pulloff_state(Drive::DeadLoad),
            tip.pulloff_state(Drive::RigidGrips),
        ));
    }
    let cols = pulloff_cols(&["lambda"], &[]);
    let values: Vec<Vec<f64>> = rows
        .iter()
        .map(|(l, d, g)| vec![*l, d.load, d.a, d.approach, g.load, g.a, g.approach])
        .collect();
    let label = shape.label();
    write_pulloffs(a, &cols, &values, &[("tip", json!(label))], || {
        let mut t = format!(
            "Maugis-Dugdale on {label}; loads in its units (docs/PHYSICS.md section 12)\n{}",
            pulloff_heading()
        );
        for (l, d, g) in &rows {
            let note = if g.a == 0.0 { "  (lost at A = 0)" } else { "" };
            pulloff_line(&mut t, *l, (d.load, d.a), (g.load, g.a), note);
        }
        t
    })
}

pub fn pulloff(a: PulloffArgs) -> anyhow::Result<()> {
    if let Some((rho, eta)) = super::two_zone_ratios(a.stress_ratio, a.range_ratio)? {
        return pulloff_two_zone(&a, rho, eta);
    }
    if let Some(t) = &a.tip {
        return pulloff_tip(&a, super::tip_shape(t)?);
    }
    let mut rows = Vec::new();
    for &l in &a.lambda {
        let ctx = LambdaContext::new(l).context("--lambda")?;
        rows.push(ctx);
    }
    let cols = pulloff_cols(
        &["lambda"],
        &["zero_radius_end_load", "zero_radius_end_approach"],
    );
    let values: Vec<Vec<f64>> = rows
        .iter()
        .map(|c| {
            vec![
                c.lambda,
                c.load_pulloff.load,
                c.load_pulloff.a,
                c.load_pulloff.approach,
                c.disp_pulloff().load,
                c.disp_pulloff().a,
                c.disp_pulloff().approach,
                c.end.load,
                c.end.approach,
            ]
        })
        .collect();
    write_pulloffs(&a, &cols, &values, &[], || {
        let mut t = pulloff_heading();
        for c in &rows {
            let (lc, dc) = (&c.load_pulloff, c.disp_pulloff());
            let note = if dc.at_zero_radius() {
                "  (lost at A = 0: lambda <= lambda_D)"
            } else {
                ""
            };
            pulloff_line(&mut t, c.lambda, (lc.load, lc.a), (dc.load, dc.a), note);
        }
        let _ = writeln!(
            t,
            "lambda_D = {LAMBDA_D}: below it the rigid-grip contact shrinks to zero radius."
        );
        t
    })
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct CurveArgs {
    #[arg(long)]
    pub lambda: f64,
    /// Largest contact radius A on the curve.
    #[arg(long, default_value_t = 4.0)]
    pub a_max: f64,
    /// Number of points (A uniform from a_max down to 0, then the A = 0 end).
    #[arg(long, default_value_t = 200)]
    pub points: usize,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Csv)]
    pub format: Format,
}

pub fn curve(a: CurveArgs) -> anyhow::Result<()> {
    if a.format == Format::Text {
        bail!("--format text is not available for a curve: use csv or json");
    }
    let c = crate::solver::curve::curve(a.lambda, a.a_max, a.points).map_err(|e| {
        let flag = match e {
            crate::solver::curve::CurveError::Solve(_) => "--lambda",
            crate::solver::curve::CurveError::Domain(_) => "--a-max",
            crate::solver::curve::CurveError::Points(_) => "--points",
        };
        anyhow::Error::from(e).context(flag)
    })?;
    let text = match a.format {
        Format::Json => serde_json::to_string_pretty(&c)? + "\n",
        _ => {
            let mut w = crate::io::csv_writer();
            w.write_record(RADIUS_CSV_HEADER[..7].iter())?;
            for r in &c.points {
                w.write_record([
                    fmt17(c.lambda),
                    fmt17(r.a),
                    fmt17(r.load),
                    fmt17(r.approach),
                    fmt17(r.m_minus_1),
                    (r.load_stable as u8).to_string(),
                    (r.displacement_stable as u8).to_string(),
                ])?;
            }
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
    };
    write_output(&a.output, text.as_bytes())
}

pub fn info() -> anyhow::Result<()> {
    let mut t = String::new();
    let adapters = crate::gpu::list_adapters();
    let _ = writeln!(t, "tabor {}", env!("CARGO_PKG_VERSION"));
    if adapters.is_empty() {
        let _ = writeln!(t, "no GPU adapters: the CPU f64 solver is used (install a Vulkan driver, e.g. `apt-get install mesa-vulkan-drivers`, for the GPU kernels)");
    }
    for (i, (a, features, limits)) in adapters.iter().enumerate() {
        let _ = writeln!(t, "adapter {i}: {}", a.name);
        let _ = writeln!(
            t,
            "  backend {}, type {}, driver {} {}",
            a.backend, a.device_type, a.driver, a.driver_info
        );
        let _ = writeln!(
            t,
            "  shader f64: {}",
            features.contains(wgpu::Features::SHADER_F64)
        );
        let _ = writeln!(
            t,
            "  max storage buffer binding {} MiB, max buffer {} MiB, workgroups per dimension {}",
            limits.max_storage_buffer_binding_size >> 20,
            limits.max_buffer_size >> 20,
            limits.max_compute_workgroups_per_dimension
        );
    }
    match Engine::select(
        Backend::Auto,
        std::env::var("TABOR_ADAPTER").ok().as_deref(),
    ) {
        Ok((_, line)) => writeln!(t, "{line}")?,
        Err(e) => writeln!(t, "--backend auto: {e}")?,
    }
    let _ = writeln!(t, "CPU threads: {}", rayon::current_num_threads());
    write_output("-", t.as_bytes())
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PlotKind {
    /// Pull-off load against lambda under both controls.
    Pulloff,
    /// Contact radius against load for several lambda, with Hertz, DMT and JKR.
    Curves,
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct PlotArgs {
    #[arg(value_enum)]
    pub kind: PlotKind,
    /// Maugis parameters of the curves.
    #[arg(long, value_delimiter = ',', default_value = "0.1,1,10")]
    pub lambda: Vec<f64>,
    /// The figure: .png, .svg or .pdf.
    #[arg(long, default_value = "plot.png")]
    pub out: std::path::PathBuf,
    #[command(flatten)]
    pub figure: super::FigureArgs,
}

pub fn plot(a: PlotArgs) -> anyhow::Result<()> {
    use crate::render::plots;
    for &l in &a.lambda {
        crate::solver::domain::check_lambda(l).context("--lambda")?;
    }
    let out = a.figure.outputs(Some(&a.out), "--out")?;
    a.figure.check_distinct(Some(&a.out), "--out", [])?;
    let print = a.figure.print("plot")?;
    use crate::render::Kind;
    let r = match a.kind {
        PlotKind::Pulloff => {
            let d = crate::figure_data::pulloff_data()?;
            plots::save(Kind::Pulloff, &print, &out, &|r| plots::pulloff(r, &d))
        }
        PlotKind::Curves => {
            let d = crate::figure_data::curves_data(&a.lambda)?;
            plots::save(Kind::Curves, &print, &out, &|r| plots::curves(r, &d))
        }
    };
    r.context("drawing the plot")?;
    eprintln!("wrote {}", a.out.display());
    Ok(())
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct BenchArgs {
    /// A small workload (under a minute on 2 cores).
    #[arg(long)]
    pub quick: bool,
    /// Where bench.png, bench.svg, bench.json and bench.txt go.
    #[arg(long, default_value = ".")]
    pub out_dir: std::path::PathBuf,
    /// Skip the GPU variants even if an adapter exists.
    #[arg(long)]
    pub no_gpu: bool,
    /// Redraw bench.png and bench.svg from a saved bench.json instead of measuring (to restyle
    /// the chart of a recorded run).
    #[arg(long)]
    pub replot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

pub fn bench(a: BenchArgs) -> anyhow::Result<()> {
    use crate::bench;
    if let Some(saved) = &a.replot {
        #[derive(serde::Deserialize)]
        struct Saved {
            metadata: serde_json::Value,
            results: Vec<bench::VariantResult>,
        }
        let text = std::fs::read_to_string(saved)
            .with_context(|| format!("--replot {}: cannot read", saved.display()))?;
        let s: Saved = serde_json::from_str(&text).with_context(|| {
            format!(
                "--replot {}: not a bench.json written by tabor bench",
                saved.display()
            )
        })?;
        let machine = s.metadata["machine"].as_str().unwrap_or("unknown machine");
        check_replot(saved, &s.results)?;
        std::fs::create_dir_all(&a.out_dir).with_context(|| {
            format!(
                "--out-dir {}: cannot create the folder",
                a.out_dir.display()
            )
        })?;
        return bench_chart(&a.out_dir, &s.results, machine);
    }
    let (nl, np) = if a.quick { (120, 60) } else { (600, 300) };
    let t = std::time::Instant::now();
    let w = bench::Workload::new(nl, np);
    eprintln!("workload: {} points (lambda 1e-4..1e4 x {np} gaps 1e-6..1e3 above pull-off, and the 300 reference states); reference solved in {:.2} s", w.points.len(), t.elapsed().as_secs_f64());
    let gpu = if a.no_gpu {
        None
    } else {
        let adapter = super::adapter_choice(a.gpu.adapter.as_deref(), BackendArg::Gpu)?;
        match crate::gpu::Gpu::new(adapter.as_deref()) {
            Ok(g) => {
                eprintln!(
                    "GPU variants on {} ({}, {})",
                    g.adapter.name, g.adapter.backend, g.adapter.device_type
                );
                Some(g)
            }
            Err(e) => {
                eprintln!("GPU variants skipped: {e}");
                None
            }
        }
    };
    let mut progress = crate::progress::Progress::spinner("variants");
    let results = bench::run(&w, gpu.as_ref(), &mut |r| {
        progress.println(&format!(
            "  {:<26} {:>10.3e} points/s, max err {:.2e}, {} failed",
            r.name, r.points_per_second, r.max_rel_err, r.failures
        ));
        progress.inc(1);
    });
    progress.finish();
    let front = bench::pareto(&results);
    let text = bench::table(&results);
    write_output("-", text.as_bytes())?;
    std::fs::create_dir_all(&a.out_dir).with_context(|| {
        format!(
            "--out-dir {}: cannot create the folder",
            a.out_dir.display()
        )
    })?;
    let machine = format!(
        "{} CPU threads{}",
        rayon::current_num_threads(),
        gpu.as_ref()
            .map(|g| format!(", GPU: {}", g.adapter.name))
            .unwrap_or_default()
    );
    let doc = json!({
        "metadata": {"tabor_version": env!("CARGO_PKG_VERSION"), "machine": machine, "quick": a.quick, "points": w.points.len(),
                     "adapter": gpu.as_ref().map(|g| g.adapter.clone())},
        "results": results,
        "pareto_front": front.iter().map(|&i| results[i].name.clone()).collect::<Vec<_>>(),
    });
    crate::io::write_atomic(
        &a.out_dir.join("bench.json"),
        (serde_json::to_string_pretty(&doc)? + "\n").as_bytes(),
    )?;
    crate::io::write_atomic(
        &a.out_dir.join("bench.txt"),
        format!("{machine}\n{text}").as_bytes(),
    )?;
    bench_chart(&a.out_dir, &results, &machine)?;
    eprintln!("wrote bench.json, bench.txt");
    Ok(())
}

/// Most solves per second a saved result may claim: the chart's axis is drawn decade by decade,
/// so an absurd speed (1e308) would draw without end.
pub const MAX_SPEED: f64 = 1e15;

/// Refuses a saved bench.json the chart cannot show: no results, or a speed that is not a
/// positive number of solves per second up to [`MAX_SPEED`].
fn check_replot(
    saved: &std::path::Path,
    results: &[crate::bench::VariantResult],
) -> anyhow::Result<()> {
    if results.is_empty() {
        bail!(
            "--replot {}: \"results\" is empty: nothing to draw; give a bench.json of a run of tabor bench",
            saved.display()
        );
    }
    for r in results {
        let v = r.points_per_second;
        if !(v > 0.0 && v <= MAX_SPEED) {
            bail!(
                "--replot {}: variant {:?} has points_per_second = {}; a speed must be above 0 and at most {MAX_SPEED:e} solves per second",
                saved.display(),
                r.name,
                crate::solver::domain::short(v)
            );
        }
    }
    Ok(())
}

/// The speed-accuracy chart of `results`: bench.png and bench.svg in `dir`.
fn bench_chart(
    dir: &std::path::Path,
    results: &[crate::bench::VariantResult],
    machine: &str,
) -> anyhow::Result<()> {
    let front = crate::bench::pareto(results);
    let title = format!("Speed against accuracy ({machine})");
    let (png, svg) = (dir.join("bench.png"), dir.join("bench.svg"));
    // A wide chart: many labelled markers.
    let out = crate::render::Outputs {
        png: Some(png.clone()),
        svg: Some(svg),
        pdf: None,
    };
    crate::render::plots::save(
        crate::render::Kind::Bench,
        &crate::render::Print::double_column(),
        &out,
        &|r| crate::render::plots::bench_chart(r, results, &front, &title),
    )
    .context("drawing the chart")?;
    eprintln!("wrote {}, bench.svg", png.display());
    Ok(())
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct AtlasArgs {
    #[arg(long, default_value = "atlas")]
    pub out_dir: std::path::PathBuf,
    #[arg(long, default_value_t = 240)]
    pub nx: usize,
    #[arg(long, default_value_t = 180)]
    pub ny: usize,
    /// Run the shipped kernel's CPU mirror instead of the GPU.
    #[arg(long)]
    pub no_gpu: bool,
}

pub fn atlas(a: AtlasArgs) -> anyhow::Result<()> {
    if a.nx < 2 || a.ny < 2 || a.nx > 4096 || a.ny > 4096 {
        bail!("--nx and --ny must be in 2..=4096");
    }
    let gpu = if a.no_gpu {
        None
    } else {
        crate::gpu::Gpu::new(None)
            .map_err(|e| eprintln!("GPU skipped: {e}"))
            .ok()
    };
    std::fs::create_dir_all(&a.out_dir).with_context(|| {
        format!(
            "--out-dir {}: cannot create the folder",
            a.out_dir.display()
        )
    })?;
    let progress = crate::progress::Progress::spinner("atlas error maps");
    let (lambdas, gaps, maps) = crate::bench::atlas(a.nx, a.ny, gpu.as_ref())?;
    progress.finish();
    for m in &maps {
        let path = a.out_dir.join(format!("{}.png", m.name));
        let em = crate::render::atlas::ErrorMap {
            title: m.title.clone(),
            lambdas: (lambdas[0], *lambdas.last().unwrap()),
            gaps: (gaps[0], *gaps.last().unwrap()),
            nx: a.nx,
            ny: a.ny,
            err: &m.err,
        };
        let out = crate::render::Outputs {
            png: Some(path.clone()),
            ..Default::default()
        };
        crate::render::atlas::save(&em, &crate::render::Print::double_column(), &out)
            .with_context(|| format!("drawing {}", path.display()))?;
        eprintln!("{}: {}", path.display(), m.title);
    }
    Ok(())
}
