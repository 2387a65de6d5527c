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
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Json)]
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
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
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

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct RoughPulloffArgs {
    /// Maugis parameters of the summits, comma-separated (one line each).
    #[arg(long, value_delimiter = ',', default_value = "0.01,0.1,1,1000")]
    pub lambda: Vec<f64>,
    /// The smallest roughness sigma (approach units).
    #[arg(long, default_value_t = 0.01)]
    pub sigma_min: f64,
    /// The largest roughness sigma.
    #[arg(long, default_value_t = 10.0)]
    pub sigma_max: f64,
    /// Roughnesses, log-spaced.
    #[arg(long, default_value_t = 24)]
    pub points: usize,
    /// How far the flat was pressed before the retract, in sigma below the mean summit plane
    /// (3: 99.9% of the summits touched; the pull-off of a lightly pressed surface is lower).
    #[arg(long, default_value_t = 3.0)]
    pub press_sigmas: f64,
    /// json or csv.
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Json)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Pull-off relative to the smooth summit's against Fuller and Tabor's adhesion parameter.
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: crate::cli::FigureArgs,
}

pub fn pulloff(a: RoughPulloffArgs) -> anyhow::Result<()> {
    if a.format == Format::Text {
        anyhow::bail!("--format text is not available here: use json or csv");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
    let print = a.figure.print(crate::render::SINGLE_COLUMN_MM)?;
    if !(a.sigma_min > 0.0 && a.sigma_max > a.sigma_min && a.sigma_max <= 1e4) {
        anyhow::bail!(
            "the roughness range {}..{} is not valid: give 0 < --sigma-min < --sigma-max <= 1e4",
            short(a.sigma_min),
            short(a.sigma_max)
        );
    }
    if !(2..=1000).contains(&a.points) || a.lambda.is_empty() || a.lambda.len() > 20 {
        anyhow::bail!(
            "give 2..1000 roughnesses (--points, got {}) and 1..20 lambda values (got {})",
            a.points,
            a.lambda.len()
        );
    }
    let sigmas = crate::map::axis(a.sigma_min, a.sigma_max, a.points, true);
    if !(a.press_sigmas.is_finite() && a.press_sigmas.abs() <= 12.0) {
        anyhow::bail!(
            "--press-sigmas {} is not valid: give how many sigma below the mean summit plane the flat was pressed, -12..12",
            short(a.press_sigmas)
        );
    }
    let curves = crate::rough::pulloff_against_roughness(&a.lambda, &sigmas, -a.press_sigmas)?;
    let text = match a.format {
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record([
                "lambda",
                "sigma",
                "fuller_tabor_parameter",
                "pulloff",
                "relative_pulloff",
            ])?;
            for c in &curves {
                for i in 0..c.sigma.len() {
                    w.write_record([
                        fmt17(c.lambda),
                        fmt17(c.sigma[i]),
                        fmt17(c.fuller_tabor_parameter[i]),
                        fmt17(c.pulloff[i]),
                        fmt17(c.relative_pulloff[i]),
                    ])?;
                }
            }
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        _ => {
            serde_json::to_string_pretty(&serde_json::json!({
                "min_separation_in_sigma": -a.press_sigmas,
                "curves": curves,
                "model": MODEL,
            }))? + "\n"
        }
    };
    write_output(&a.output, text.as_bytes())?;
    if !figure.is_empty() {
        let d = -a.press_sigmas;
        crate::render::plots::save(crate::render::Kind::Pulloff, &print, &figure, &|r| {
            crate::render::rough::pulloff_curves(r, &curves, d)
        })
        .context("drawing the pull-off against roughness")?;
    }
    Ok(())
}
