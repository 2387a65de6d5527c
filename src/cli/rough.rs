//! `tabor rough`: a rough surface of Maugis-Dugdale summits through an approach and a retract.

use super::Format;
use crate::io::{fmt17, write_output};
use crate::physics::domain::short;
use crate::rough::{Mean, Rough, RoughCycle};
use anyhow::Context;
use clap::Args;
use serde::Serialize;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct RoughArgs {
    /// Maugis parameter of every summit.
    #[arg(long)]
    pub lambda: f64,
    /// Standard deviation of the summit heights, in the summit's approach unit
    /// (pi^2 w^2 R / K^2)^(1/3).
    #[arg(long)]
    pub sigma: f64,
    /// The smallest separation of the flat from the mean summit plane (approach units).
    #[arg(long)]
    pub min_separation: f64,
    /// Where the approach starts and the retract ends [default: where no summit feels the flat].
    #[arg(long)]
    pub max_separation: Option<f64>,
    /// Separations on each half of the cycle.
    #[arg(long, default_value_t = 400)]
    pub points: usize,
    /// json or csv.
    #[arg(long, value_enum, default_value_t = Format::Json)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Load per summit and the fractions of summits on each branch against the separation
    /// (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: crate::cli::FigureArgs,
}

/// The JSON of one half of the cycle: arrays, one entry per separation.
#[derive(Serialize)]
struct Leg {
    separation: Vec<f64>,
    load: Vec<f64>,
    contact_fraction: Vec<f64>,
    noncontact_fraction: Vec<f64>,
}

impl Leg {
    fn of(v: &[Mean]) -> Leg {
        Leg {
            separation: v.iter().map(|m| m.separation).collect(),
            load: v.iter().map(|m| m.load).collect(),
            contact_fraction: v.iter().map(|m| m.contact_fraction).collect(),
            noncontact_fraction: v.iter().map(|m| m.noncontact_fraction).collect(),
        }
    }
}

#[derive(Serialize)]
struct Json<'a> {
    lambda: f64,
    sigma: f64,
    approach: Leg,
    retract: Leg,
    pulloff_load: f64,
    pulloff_separation: f64,
    hysteresis: f64,
    smooth_pulloff: f64,
    fuller_tabor_parameter: f64,
    model: &'a str,
}

const MODEL: &str = "Greenwood-Williamson: identical spherical summits, Gaussian heights, each an exact Maugis-Dugdale sphere under rigid grips with its own history; the summits do not interact (no elastic coupling), which fails when contact spots crowd (a real contact area beyond about 10% of the nominal), when sigma is comparable to the summit radius, or for few summits";

pub fn run(a: RoughArgs) -> anyhow::Result<()> {
    if a.format == Format::Text {
        anyhow::bail!("--format text is not available for a rough cycle: use json or csv");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    let print = a.figure.print(crate::render::DOUBLE_COLUMN_MM)?;
    let rough = Rough::new(a.lambda, a.sigma)?;
    let c = rough
        .cycle(a.min_separation, a.max_separation, a.points)
        .context("the separations (--min-separation, --max-separation, --points)")?;
    let text = match a.format {
        Format::Csv => csv(&c)?,
        _ => {
            let j = Json {
                lambda: c.lambda,
                sigma: c.sigma,
                approach: Leg::of(&c.approach),
                retract: Leg::of(&c.retract),
                pulloff_load: c.pulloff_load,
                pulloff_separation: c.pulloff_separation,
                hysteresis: c.hysteresis,
                smooth_pulloff: c.smooth_pulloff,
                fuller_tabor_parameter: c.fuller_tabor_parameter,
                model: MODEL,
            };
            serde_json::to_string_pretty(&j)? + "\n"
        }
    };
    write_output(&a.output, text.as_bytes())?;
    if !figure.is_empty() {
        crate::render::plots::save(crate::render::Kind::Cycle, &print, &figure, &|r| {
            crate::render::rough::cycle(r, &c)
        })
        .context("drawing the rough cycle")?;
    }
    eprintln!(
        "lambda = {}, sigma = {} (Fuller-Tabor parameter {}): pull-off {} per summit at separation {} (a smooth summit: {}); energy lost {} per summit per cycle",
        short(c.lambda),
        short(c.sigma),
        short(c.fuller_tabor_parameter),
        short(c.pulloff_load),
        short(c.pulloff_separation),
        short(c.smooth_pulloff),
        short(c.hysteresis)
    );
    Ok(())
}

/// One row per separation: `phase,separation,load,contact_fraction,noncontact_fraction`.
fn csv(c: &RoughCycle) -> anyhow::Result<String> {
    let mut w = crate::io::csv_writer();
    w.write_record([
        "phase",
        "separation",
        "load",
        "contact_fraction",
        "noncontact_fraction",
    ])?;
    for (phase, v) in [("approach", &c.approach), ("retract", &c.retract)] {
        for m in v.iter() {
            w.write_record([
                phase.to_string(),
                fmt17(m.separation),
                fmt17(m.load),
                fmt17(m.contact_fraction),
                fmt17(m.noncontact_fraction),
            ])?;
        }
    }
    Ok(String::from_utf8(crate::io::csv_finish(w)?)?)
}
