//! `tabor rough`: a rough surface of Maugis-Dugdale summits through an approach and a retract.

use super::Format;
use crate::error::Named;
use crate::io::{fmt17, write_output};
use crate::physics::domain::short;
use crate::render::Kind;
use crate::rough::{Mean, RoughCycle};
use anyhow::Context;
use clap::Args;
use serde::Serialize;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct RoughArgs {
    /// Maugis parameter of every summit.
    #[arg(long, required_unless_present_any = ["scene", "preset", "asperities", "topography"])]
    pub lambda: Option<f64>,
    /// Standard deviation of the summit heights, in the summit's approach unit
    /// (pi^2 w^2 R / K^2)^(1/3).
    #[arg(long, required_unless_present_any = ["scene", "preset", "asperities", "topography"])]
    pub sigma: Option<f64>,
    /// The smallest separation of the flat from the mean summit plane (approach units).
    #[arg(long, required_unless_present_any = ["scene", "preset", "asperities", "topography"])]
    pub min_separation: Option<f64>,
    /// A rough scene in SI units (JSON: the materials, summit_radius_m, summit_density_m2,
    /// sigma_m, nominal_area_m2, optional min_separation_m): forces in N, pressures in Pa.
    #[arg(long, conflicts_with_all = ["lambda", "sigma", "min_separation", "max_separation", "preset"])]
    pub scene: Option<std::path::PathBuf>,
    /// An explicit ensemble of summits (CSV with columns height_m, radius_m, or a .npy of shape
    /// (N, 2)), each with its own radius and so its own lambda; the materials and the nominal
    /// area come from --scene or --preset.
    #[arg(long, conflicts_with = "topography")]
    pub asperities: Option<std::path::PathBuf>,
    /// A measured height map (.npy, 2-D, heights in m): its summits are the local maxima, with
    /// radii from the curvature there; needs --pixel-m, and --scene or --preset for the
    /// materials.
    #[arg(long, requires = "pixel_m")]
    pub topography: Option<std::path::PathBuf>,
    /// The height map's pixel spacing (m).
    #[arg(long)]
    pub pixel_m: Option<f64>,
    /// The smallest separation of an ensemble's cycle, in m above the heights' zero [default:
    /// the mean summit height less three standard deviations].
    #[arg(long)]
    pub min_separation_m: Option<f64>,
    /// How an ensemble's summits are solved: `tables` (the contact branch tabulated over the
    /// summits' lambdas, solved exactly next to each fold, error measured and reported) or
    /// `exact` (a root search at every summit state) [default: tables].
    #[arg(long, value_enum)]
    pub summits: Option<SummitsArg>,
    /// Where an ensemble's tables are solved [default: auto, or the environment variable
    /// TABOR_BACKEND]; with tables on a GPU with f64 shaders its summits are stepped there too.
    #[arg(long, value_enum)]
    pub backend: Option<super::BackendArg>,
    /// Use the first adapter whose name contains this text (see `tabor info`).
    #[arg(long)]
    pub adapter: Option<String>,
    /// GPU arithmetic for an ensemble's tables [default: f64 where the adapter has it, else
    /// f32]. The CPU path is f64.
    #[arg(long, value_enum)]
    pub precision: Option<super::PrecisionArg>,
    /// A built-in rough scene: mems-polysilicon, pdms-rough-glass, colloidal-probe-wafer.
    #[arg(long, conflicts_with_all = ["lambda", "sigma", "min_separation", "max_separation"])]
    pub preset: Option<String>,

    /// A water meniscus on every summit (docs/PHYSICS.md section 10.1): its tensile stress over
    /// the solid's (rho = s2/s1); needs --range-ratio. 0: the dry model.
    #[arg(long, conflicts_with_all = ["scene", "preset", "asperities", "topography"])]
    pub stress_ratio: Option<f64>,
    /// The meniscus's range over the solid's Dugdale range (eta = h2/h1); needs --stress-ratio.
    #[arg(long, conflicts_with_all = ["scene", "preset", "asperities", "topography"])]
    pub range_ratio: Option<f64>,

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

/// How an ensemble's summit states are found (`--summits`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SummitsArg {
    /// Tables over the summits' lambdas, with their error measured.
    Tables,
    /// A root search at every summit state.
    Exact,
}

/// The JSON of one half of the cycle: arrays, one entry per separation.
#[derive(Serialize)]
struct Leg {
    separation: Vec<f64>,
    load: Vec<f64>,
    contact_fraction: Vec<f64>,
    noncontact_fraction: Vec<f64>,
    contact_load: Vec<f64>,
    noncontact_load: Vec<f64>,
}

impl Leg {
    fn of(v: &[Mean]) -> Leg {
        Leg {
            separation: v.iter().map(|m| m.separation).collect(),
            load: v.iter().map(|m| m.load).collect(),
            contact_fraction: v.iter().map(|m| m.contact_fraction).collect(),
            noncontact_fraction: v.iter().map(|m| m.noncontact_fraction).collect(),
            contact_load: v.iter().map(|m| m.contact_load).collect(),
            noncontact_load: v.iter().map(|m| m.noncontact_load).collect(),
        }
    }
}

#[derive(Serialize)]
struct Json<'a> {
    lambda: f64,
    sigma: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    stress_ratio: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    range_ratio: Option<f64>,
    approach: Leg,
    retract: Leg,
    pulloff_load: f64,
    pulloff_separation: f64,
    hysteresis: f64,
    smooth_pulloff: f64,
    fuller_tabor_parameter: f64,
    quadrature_error: f64,
    model: &'a str,
    #[serde(skip_serializing_if = "<[String]>::is_empty")]
    warnings: Vec<String>,
}

use crate::rough::scene::MODEL;

const MODEL_WET: &str = "Greenwood-Williamson with a water meniscus on every summit: identical spherical summits, Gaussian heights, each an exact two-zone (solid Dugdale zone plus meniscus) sphere under rigid grips with its own history; loads in pi w R with w the total work of adhesion; the summits and their menisci do not interact, which fails where the meniscus range approaches the summit spacing or sigma (menisci merge), as for the dry model where contact spots crowd; the meniscus is in equilibrium (no film dynamics) and its Kelvin radius small against the summit radius";

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
    let print = a.figure.print("rough")?;
    let scene = scene_of(&a)?;
    if a.asperities.is_some() || a.topography.is_some() {
        let Some(sc) = scene else {
            anyhow::bail!("an ensemble needs the materials: give --scene FILE or --preset NAME with --asperities or --topography");
        };
        if !figure.is_empty() {
            anyhow::bail!("--plot, --svg and --pdf draw the statistical cycle; an explicit ensemble (--asperities, --topography) has no figure yet: drop them (the output has the whole cycle)");
        }
        return run_ensemble(&a, &sc);
    }
    refuse_ensemble_options(&a, scene.is_some())?;
    if let Some(sc) = scene {
        return run_scene(&a, &sc, &figure, &print);
    }
    let (Some(lambda), Some(sigma), Some(d_min)) = (a.lambda, a.sigma, a.min_separation) else {
        anyhow::bail!("give --lambda, --sigma and --min-separation (or --scene/--preset)");
    };
    let wet = super::two_zone_ratios(a.stress_ratio, a.range_ratio)?;
    let law = crate::ContactLaw::with_ratios(lambda, wet);
    let c = crate::rough::wet::WetRough::of_law(law, sigma)
        .map_err(super::zones_error)?
        .cycle(lambda, d_min, a.max_separation, a.points)
        .map_err(|e| super::in_flags(&e, &[("min_separation", "--min-separation")]))
        .context("the separations (--min-separation, --max-separation, --points)")?;
    // The cycle's advice in this command's flags.
    let warnings: Vec<String> = c
        .warnings
        .iter()
        .map(|w| {
            w.named(&super::flags(&[
                ("max_separation", "--max-separation"),
                ("points", "--points"),
            ]))
        })
        .collect();
    let text = match a.format {
        Format::Csv => csv(&c)?,
        _ => {
            let j = Json {
                lambda: c.lambda,
                sigma: c.sigma,
                stress_ratio: wet.map(|w| w.0),
                range_ratio: wet.map(|w| w.1),
                approach: Leg::of(&c.approach),
                retract: Leg::of(&c.retract),
                pulloff_load: c.pulloff_load,
                pulloff_separation: c.pulloff_separation,
                hysteresis: c.hysteresis,
                smooth_pulloff: c.smooth_pulloff,
                fuller_tabor_parameter: c.fuller_tabor_parameter,
                quadrature_error: c.quadrature_error,
                model: if wet.is_some() { MODEL_WET } else { MODEL },
                warnings: warnings.clone(),
            };
            serde_json::to_string_pretty(&j)? + "\n"
        }
    };
    let short = crate::physics::domain::short;
    let title_note = wet.map_or(String::new(), |(rho, eta)| {
        format!(", meniscus ρ = {}, η = {}", short(rho), short(eta))
    });
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Cycle,
        &print,
        &figure,
        &|r| crate::render::rough::cycle(r, &c, &title_note),
    )
    .context("writing the rough cycle")?;
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
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// Refuses the options of an explicit ensemble on a statistical surface, which would ignore
/// them: its cycle is a quadrature over the Gaussian heights, on the CPU, with no summits,
/// tables or height map.
fn refuse_ensemble_options(a: &RoughArgs, scene: bool) -> anyhow::Result<()> {
    let given = [
        ("--min-separation-m", a.min_separation_m.is_some()),
        ("--summits", a.summits.is_some()),
        ("--pixel-m", a.pixel_m.is_some()),
        ("--backend", a.backend.is_some()),
        ("--adapter", a.adapter.is_some()),
        ("--precision", a.precision.is_some()),
    ];
    let Some(&(flag, _)) = given.iter().find(|g| g.1) else {
        return Ok(());
    };
    let instead = match (flag, scene) {
        ("--min-separation-m", true) => " (a scene's smallest separation is its min_separation_m)",
        ("--min-separation-m", false) => " (its smallest separation is --min-separation)",
        _ => "",
    };
    anyhow::bail!(
        "{flag} applies to an explicit ensemble (--asperities, --topography); a statistical rough surface (--lambda and --sigma, --scene, --preset) is a quadrature on the CPU with no summits, tables or height map{instead}: leave out {flag}, or give --asperities or --topography"
    )
}

/// One row per separation and phase: `phase` then the named columns, each half of the cycle
/// given as its columns.
fn phases_csv(columns: &[&str], halves: [(&str, Vec<&[f64]>); 2]) -> anyhow::Result<String> {
    let mut w = crate::io::csv_writer();
    w.write_record(std::iter::once("phase").chain(columns.iter().copied()))?;
    for (phase, cols) in &halves {
        for i in 0..cols.first().map_or(0, |c| c.len()) {
            w.write_record(
                std::iter::once(phase.to_string()).chain(cols.iter().map(|c| fmt17(c[i]))),
            )?;
        }
    }
    Ok(String::from_utf8(crate::io::csv_finish(w)?)?)
}

/// One row per separation: `phase,separation,load,contact_fraction,noncontact_fraction`.
fn csv(c: &RoughCycle) -> anyhow::Result<String> {
    let col = |v: &[Mean], f: fn(&Mean) -> f64| v.iter().map(f).collect::<Vec<f64>>();
    let half = |v: &[Mean]| {
        [
            col(v, |m| m.separation),
            col(v, |m| m.load),
            col(v, |m| m.contact_fraction),
            col(v, |m| m.noncontact_fraction),
            col(v, |m| m.contact_load),
            col(v, |m| m.noncontact_load),
        ]
    };
    let (ap, re) = (half(&c.approach), half(&c.retract));
    phases_csv(
        &[
            "separation",
            "load",
            "contact_fraction",
            "noncontact_fraction",
            "contact_load",
            "noncontact_load",
        ],
        [
            ("approach", ap.iter().map(|v| v.as_slice()).collect()),
            ("retract", re.iter().map(|v| v.as_slice()).collect()),
        ],
    )
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
    let print = a.figure.print("rough-pulloff")?;
    let sweep = crate::rough::PulloffSweep {
        lambdas: a.lambda.clone(),
        sigma_min: a.sigma_min,
        sigma_max: a.sigma_max,
        points: a.points,
        press_sigmas: a.press_sigmas,
    };
    let flags = &[
        ("sigma_min", "--sigma-min"),
        ("sigma_max", "--sigma-max"),
        ("points", "--points"),
        ("press_sigmas", "--press-sigmas"),
        ("lambda_values", "--lambda values"),
    ];
    let curves = sweep.compute().map_err(|e| super::in_flags(&e, flags))?;

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
    let d = -a.press_sigmas;
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Pulloff,
        &print,
        &figure,
        &|r| crate::render::rough::pulloff_curves(r, &curves, d),
    )
    .context("writing the pull-off against roughness")?;
    Ok(())
}

fn scene_of(a: &RoughArgs) -> anyhow::Result<Option<crate::rough::scene::RoughScene>> {
    use crate::rough::scene::{preset, PRESETS};
    if let Some(p) = &a.preset {
        return preset(p).map(Some).with_context(|| {
            format!(
                "--preset {p}: no such rough scene; give one of {}",
                PRESETS.join(", ")
            )
        });
    }
    let Some(path) = &a.scene else {
        return Ok(None);
    };
    let shown = path.display();
    let meta = std::fs::metadata(path).with_context(|| format!("cannot read --scene {shown}"))?;
    if meta.len() > 1 << 20 {
        anyhow::bail!(
            "--scene {shown} is {} bytes: a scene is a small JSON file (at most 1 MiB)",
            meta.len()
        );
    }
    let text = std::fs::read(path).with_context(|| format!("cannot read --scene {shown}"))?;
    let sc = serde_json::from_slice(&text)
        .with_context(|| format!("--scene {shown} is not a rough scene"))?;
    Ok(Some(sc))
}

fn run_scene(
    a: &RoughArgs,
    sc: &crate::rough::scene::RoughScene,
    figure: &crate::render::Outputs,
    print: &crate::render::Print,
) -> anyhow::Result<()> {
    let r = sc.solve(a.points)?;
    let text = match a.format {
        Format::Csv => {
            fn half(l: &crate::rough::scene::SiLeg) -> Vec<&[f64]> {
                vec![
                    l.separation_m.as_slice(),
                    &l.force_n,
                    &l.nominal_pressure_pa,
                    &l.real_contact_area_m2,
                    &l.contact_fraction,
                    &l.noncontact_fraction,
                ]
            }
            phases_csv(
                &[
                    "separation_m",
                    "force_n",
                    "nominal_pressure_pa",
                    "real_contact_area_m2",
                    "contact_fraction",
                    "noncontact_fraction",
                ],
                [
                    ("approach", half(&r.approach)),
                    ("retract", half(&r.retract)),
                ],
            )?
        }
        _ => serde_json::to_string_pretty(&r)? + "\n",
    };
    let c = &r.normalised;
    let note = if r.meniscus.is_some() {
        ", with a meniscus"
    } else {
        ""
    };
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Cycle,
        print,
        figure,
        &|d| crate::render::rough::cycle(d, c, note),
    )
    .context("writing the rough cycle")?;
    eprintln!(
        "{}: {} summits, lambda = {} (Tabor parameter {}), sigma = {} approach units (Fuller-Tabor parameter {})",
        r.name.as_deref().unwrap_or("rough scene"),
        short(r.summits),
        short(r.lambda),
        short(r.tabor_parameter),
        short(r.sigma_normalised),
        short(r.fuller_tabor_parameter)
    );
    eprintln!(
        "  pull-off force {} N (stress {} Pa) at separation {} m; all summits pulling as smooth ones: {} N; energy lost {} J per cycle",
        short(r.pulloff_force_n),
        short(r.pulloff_stress_pa),
        short(r.pulloff_separation_m),
        short(r.smooth_pulloff_force_n),
        short(r.hysteresis_j)
    );
    if let (Some(m), Some(dry)) = (&r.meniscus, r.dry_pulloff_force_n) {
        eprintln!(
            "  with a meniscus on every summit (Kelvin radius {} m, height {} m, Laplace pressure {} Pa); the dry surface after the same press: pull-off {} N",
            short(m.kelvin_radius_m),
            short(m.range_m),
            short(m.laplace_pressure_pa),
            short(dry)
        );
    }
    for w in &r.warnings {
        eprintln!("  warning: {w}");
    }
    if let Some(s) = &r.source {
        eprintln!("  values: {s}");
    }
    Ok(())
}

/// Reads a float64 .npy: its values in C order and its shape.
fn read_npy(path: &std::path::Path, what: &str) -> anyhow::Result<(Vec<f64>, Vec<u64>)> {
    let shown = path.display();
    let f = std::fs::File::open(path).with_context(|| format!("cannot read {what} {shown}"))?;
    let npy = npyz::NpyFile::new(std::io::BufReader::new(f))
        .with_context(|| format!("{what} {shown} is not a .npy file"))?;
    let shape = npy.shape().to_vec();
    let n: u64 = shape.iter().product();
    if n > 4 * crate::rough::ensemble::SUMMITS_MAX as u64 {
        anyhow::bail!(
            "{what} {shown} holds {n} values: at most {} are read",
            4 * crate::rough::ensemble::SUMMITS_MAX
        );
    }
    let fortran = npy.order() == npyz::Order::Fortran;
    let descr = match npy.dtype() {
        npyz::DType::Plain(ts) => ts.to_string(),
        other => other.descr(),
    };
    if descr != "<f8" {
        anyhow::bail!("{what} {shown} has dtype {descr}: give float64 (numpy's default)");
    }
    let v: Vec<f64> = npy
        .into_vec::<f64>()
        .with_context(|| format!("cannot read {what} {shown}"))?;
    // Fortran order (a transposed array): reorder to C order.
    let v = if fortran && shape.len() == 2 {
        let (r, c) = (shape[0] as usize, shape[1] as usize);
        (0..r * c).map(|k| v[(k % c) * r + k / c]).collect()
    } else {
        v
    };
    Ok((v, shape))
}

fn read_asperities(
    path: &std::path::Path,
) -> anyhow::Result<Vec<crate::rough::ensemble::Asperity>> {
    use crate::rough::ensemble::Asperity;
    let shown = path.display();
    let is_npy = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if is_npy {
        let (v, shape) = read_npy(path, "--asperities")?;
        if shape.len() != 2 || shape[1] != 2 {
            anyhow::bail!("--asperities {shown} has shape {shape:?}: give (N, 2), columns height_m and radius_m");
        }
        return Ok(v
            .chunks(2)
            .map(|p| Asperity {
                height_m: p[0],
                radius_m: p[1],
            })
            .collect());
    }
    let mut r = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(path)
        .with_context(|| format!("cannot read --asperities {shown}"))?;
    let head = r.headers()?.clone();
    let col = |name: &str| {
        head.iter().position(|h| h == name).with_context(|| {
            format!(
                "--asperities {shown} has no column {name} (found: {}): give height_m,radius_m",
                head.iter().collect::<Vec<_>>().join(", ")
            )
        })
    };
    let (ih, ir) = (col("height_m")?, col("radius_m")?);
    let mut out = Vec::new();
    for (line, rec) in r.records().enumerate() {
        let rec = rec.with_context(|| format!("--asperities {shown}, row {}", line + 1))?;
        let num = |i: usize| -> anyhow::Result<f64> {
            let t = rec.get(i).unwrap_or("");
            t.parse().with_context(|| {
                format!(
                    "--asperities {shown}, row {}: {t:?} is not a number",
                    line + 1
                )
            })
        };
        out.push(Asperity {
            height_m: num(ih)?,
            radius_m: num(ir)?,
        });
        if out.len() > crate::rough::ensemble::SUMMITS_MAX {
            anyhow::bail!(
                "--asperities {shown} holds more than {} summits",
                crate::rough::ensemble::SUMMITS_MAX
            );
        }
    }
    Ok(out)
}

fn run_ensemble(a: &RoughArgs, sc: &crate::rough::scene::RoughScene) -> anyhow::Result<()> {
    use crate::rough::ensemble::{EnsembleSpec, SummitSolver};
    // Bad summits are refused before an engine is chosen (and says so).
    let asp = ensemble_summits(a)?;
    let spec = EnsembleSpec {
        min_separation_m: a.min_separation_m,
        points: a.points,
        solver: match a.summits.unwrap_or(SummitsArg::Tables) {
            SummitsArg::Tables => SummitSolver::Tables,
            SummitsArg::Exact => SummitSolver::Exact,
        },
    };
    // The flag's name only where the flag was given (else the scene's key is meant).
    let flags = |e: crate::rough::RoughError| match a.min_separation_m {
        Some(_) => super::in_flags(&e, &[("min_separation_m", "--min-separation-m")]),
        None => anyhow::anyhow!(e.to_string()),
    };
    spec.validate(sc).map_err(flags)?;
    let engine = match spec.solver {
        SummitSolver::Exact => crate::engine::Engine::Cpu,
        SummitSolver::Tables => table_engine(a.backend, &a.adapter, a.precision)?,
    };
    let r = spec.run(sc, &asp, &engine).map_err(flags)?;
    write_output(&a.output, ensemble_text(&r, sc, a.format)?.as_bytes())?;
    if let Some(e) = r.table_error {
        eprintln!(
            "summit states from {}: largest measured interpolation error {}",
            r.summit_solver,
            short(e)
        );
    }
    if let Some(c) = &r.table_check {
        eprintln!("tables: {c}");
    }
    eprintln!(
        "{} summits: pull-off force {} N at separation {} m ({} summit-states in {} s: {} per second)",
        r.summits,
        short(r.pulloff_force_n),
        short(r.pulloff_separation_m),
        r.summit_states,
        short(r.seconds),
        short(r.summit_states as f64 / r.seconds.max(1e-9))
    );
    Ok(())
}

/// The summits of `--asperities` or `--topography`, checked by the library.
fn ensemble_summits(a: &RoughArgs) -> anyhow::Result<Vec<crate::rough::ensemble::Asperity>> {
    use crate::rough::ensemble;
    match (&a.asperities, &a.topography) {
        (Some(p), _) => {
            let asp = read_asperities(p)?;
            ensemble::check(&asp)?;
            Ok(asp)
        }
        (None, Some(p)) => {
            let (z, shape) = read_npy(p, "--topography")?;
            if shape.len() != 2 {
                anyhow::bail!(
                    "--topography {} has shape {shape:?}: give a 2-D height map",
                    p.display()
                );
            }
            let nx = shape[1] as usize;
            ensemble::topography_summits(&z, nx, a.pixel_m.unwrap_or(f64::NAN))
                .with_context(|| format!("--topography {}", p.display()))
        }
        _ => unreachable!("run_ensemble is called with an ensemble"),
    }
}

/// The engine of summit tables (ensembles and the rough map): `--backend`, in f64 where the
/// adapter has f64 shaders unless `--precision` says otherwise.
pub(super) fn table_engine(
    backend: Option<super::BackendArg>,
    adapter: &Option<String>,
    precision: Option<super::PrecisionArg>,
) -> anyhow::Result<crate::engine::Engine> {
    let gpu = super::basic::GpuArgs {
        adapter: adapter.clone(),
        check: super::basic::CheckCount(0),
        precision: precision.unwrap_or(super::PrecisionArg::F32),
    };
    let mut e = super::basic::engine_for(backend, super::BackendArg::Auto, &gpu)?;
    if precision.is_none() && e.set_precision(crate::engine::Precision::F64).is_err() {
        eprintln!("the adapter has no f64 shaders: the tables are solved in f32 (--precision f32)");
    }
    Ok(e)
}

/// An ensemble's cycle as CSV (both legs) or JSON.
fn ensemble_text(
    r: &crate::rough::ensemble::EnsembleCycle,
    sc: &crate::rough::scene::RoughScene,
    format: Format,
) -> anyhow::Result<String> {
    if let Format::Csv = format {
        fn half(l: &crate::rough::ensemble::EnsembleLeg) -> Vec<&[f64]> {
            vec![
                l.separation_m.as_slice(),
                &l.force_n,
                &l.real_contact_area_m2,
                &l.contact_fraction,
                &l.noncontact_fraction,
            ]
        }
        let names = [
            "separation_m",
            "force_n",
            "real_contact_area_m2",
            "contact_fraction",
            "noncontact_fraction",
        ];
        let legs = [
            ("approach", half(&r.approach)),
            ("retract", half(&r.retract)),
        ];
        return phases_csv(&names, legs);
    }
    Ok(serde_json::to_string_pretty(&serde_json::json!({
        "summits": r.summits,
        "approach": r.approach,
        "retract": r.retract,
        "pulloff_force_n": r.pulloff_force_n,
        "pulloff_separation_m": r.pulloff_separation_m,
        "nominal_area_m2": sc.nominal_area_m2,
        "pulloff_stress_pa": r.pulloff_force_n / sc.nominal_area_m2,
        "summit_solver": r.summit_solver,
        "table_error": r.table_error,
        "table_check": r.table_check,
        "model": "explicit summits, each an exact Maugis-Dugdale sphere with its own radius and history under the flat's displacement; the summits do not interact (no elastic coupling)",
    }))? + "\n")
}
