//! `tabor solve --tip`: states of a tip's law (docs/PHYSICS.md section 12) in its units, one
//! from the flags or a table of (lambda, value) rows, on the f64 CPU path.

use super::basic::{Given, SolveArgs, StreamTable, CHUNK_ROWS};
use super::Format;
use crate::io::{fmt17, write_output, Output};
use crate::law::{tip, Drive, PathPoint, Tip};
use crate::physics::tip::Shape;
use crate::solver::Status;
use anyhow::{bail, Context};
use serde_json::json;
use std::fmt::Write as _;

/// One tip state: the given value, the state (NaN where there is none) and its status.
struct Row {
    lambda: f64,
    value: f64,
    status: Status,
    point: Option<PathPoint>,
}

const HEADER: [&str; 7] = ["lambda", "given", "load", "approach", "A", "C", "status"];

/// The state of `shape` at `lambda` given by `value` of `given` ([`crate::law::tip::solve`]).
fn state(shape: Shape, lambda: f64, given: Given, value: f64) -> Row {
    let (status, point) = tip::solve(shape, lambda, given.into(), value);
    Row {
        lambda,
        value,
        status,
        point,
    }
}

fn values(r: &Row) -> [f64; 4] {
    match r.point {
        Some(p) => [p.load, p.approach, p.a, p.c],
        None => [f64::NAN; 4],
    }
}

fn fields(r: &Row) -> Vec<String> {
    let mut f = vec![fmt17(r.lambda), fmt17(r.value)];
    f.extend(values(r).iter().map(|&x| fmt17(x)));
    f.push(r.status.name().into());
    f
}

fn row_json(r: &Row) -> serde_json::Value {
    let [load, approach, a, c] = values(r).map(crate::io::json_num);
    json!({"lambda": r.lambda, "given": r.value, "load": load, "approach": approach, "A": a,
           "C": c, "status": r.status.name()})
}

/// `tabor solve --tip`: one state from --lambda and --load, --approach or --radius-a, or a
/// CSV of rows (columns `lambda` and `load`, `approach` or `A` by --control).
pub fn solve(a: &SolveArgs, shape: Shape) -> anyhow::Result<()> {
    let meta = |given: Given, rows: Option<usize>| {
        json!({"tabor_version": env!("CARGO_PKG_VERSION"), "backend": "cpu", "precision": "f64",
               "tip": shape.label(), "control": given.name(), "points": rows})
    };
    if let Some(input) = &a.input {
        let given = a.control.unwrap_or(Given::Load);
        let format = match a.format.unwrap_or(Format::Csv) {
            Format::Text => {
                bail!("--format text is for a single state; use csv or json for --input")
            }
            f => f,
        };
        let column = given.column();
        let mut reader = crate::io::PointReader::open(input, column)?;
        let mut table = StreamTable::start(Output::create(&a.output)?, format, &HEADER)?;
        eprintln!("backend: CPU f64 (a tip is solved on the CPU)");
        loop {
            let chunk = reader.next_chunk(CHUNK_ROWS)?;
            if chunk.is_empty() {
                break;
            }
            use rayon::prelude::*;
            let rows: Vec<Row> = chunk
                .par_iter()
                .map(|&(lambda, v)| state(shape, lambda, given, v))
                .collect();
            table.rows(&rows, row_json, |r, buf| {
                let mut w = crate::io::csv_writer();
                if w.write_record(fields(r)).is_ok() {
                    buf.extend(crate::io::csv_finish(w).unwrap_or_default());
                }
            })?;
        }
        return table.finish(|rows| Ok(meta(given, Some(rows))));
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
    if let Some(c) = a.control.filter(|&c| c != given) {
        bail!(
            "--control {} does not match the value given ({}); give {} for {} control",
            c.name(),
            given.flag(),
            c.flag(),
            c.name()
        );
    }
    let tip = Tip::new(shape, lambda).map_err(|e| anyhow::anyhow!("--lambda {lambda}: {e}"))?;
    if !value.is_finite() || (given == Given::Radius && !(value > 0.0)) {
        bail!(
            "{} {value}: give a finite number{}",
            given.flag(),
            if given == Given::Radius {
                " above 0"
            } else {
                ""
            }
        );
    }
    let r = state(shape, lambda, given, value);
    let text = match a.format.unwrap_or(Format::Text) {
        Format::Json => {
            serde_json::to_string_pretty(&json!({"results": [row_json(&r)],
                "metadata": meta(given, None)}))?
                + "\n"
        }
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(HEADER)?;
            w.write_record(fields(&r))?;
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        Format::Text => text(&tip, given, &r),
    };
    write_output(&a.output, text.as_bytes())
}

fn text(tip: &Tip, given: Given, r: &Row) -> String {
    let shown = |x: f64| {
        if x.is_nan() {
            "(not defined: no contact)".to_string()
        } else {
            fmt17(x)
        }
    };
    let [load, approach, a, c] = values(r);
    let mut t = String::new();
    let _ = writeln!(
        t,
        "Maugis-Dugdale on {}, lambda = {} ({} given; units of docs/PHYSICS.md section 12)",
        tip.shape.label(),
        crate::solver::domain::short(r.lambda),
        given.name()
    );
    let _ = writeln!(t, "  status              {}", r.status.name());
    let _ = writeln!(t, "  load   Pbar         {}", shown(load));
    let _ = writeln!(t, "  approach Dbar       {}", shown(approach));
    let _ = writeln!(t, "  contact radius A    {}", shown(a));
    let _ = writeln!(t, "  zone radius C       {}", shown(c));
    if given == Given::Radius {
        let says = |d| {
            if tip.stable_under(d, r.value) {
                "stable"
            } else {
                "unstable"
            }
        };
        let _ = writeln!(
            t,
            "  under load control {}, under displacement control {}",
            says(Drive::DeadLoad),
            says(Drive::RigidGrips)
        );
    }
    for (drive, what) in [
        (Drive::DeadLoad, "pull-off, load control        "),
        (Drive::RigidGrips, "jump-out, displacement control"),
    ] {
        let p = tip.pulloff_state(drive);
        let _ = writeln!(
            t,
            "  {what}  Pbar = {}  at A = {}",
            fmt17(p.load),
            fmt17(p.a)
        );
    }
    if r.status == Status::NoContact {
        let _ = writeln!(t, "  (below the pull-off of this control: no contact)");
    }
    t
}
