//! The command line: parsing builds the work, the library does it.

mod argv;
mod basic;
mod dem;
mod fit;
mod map;
mod profile;
mod rough;
mod rough_map;
pub(crate) mod scene;
mod tip;

use crate::error::Named;
use clap::{Parser, Subcommand, ValueEnum};

#[derive(Parser, Debug)]
#[command(name = "tabor", version, about = "Adhesion maps for elastic spheres: exact Maugis-Dugdale solutions on the GPU and CPU", long_about = None)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Solve Maugis-Dugdale states: one (--lambda, --load) or a CSV of points (--input).
    Solve(basic::SolveArgs),
    /// Pull-off (jump-out) under load and displacement control for one or more lambda.
    Pulloff(basic::PulloffArgs),
    /// The whole Maugis-Dugdale curve for one lambda, with stability under both controls.
    Curve(basic::CurveArgs),
    /// Render an adhesion map (PNG/SVG) with JSON and NPY tables: the main job.
    Map(Box<map::MapArgs>),
    /// Line plots: pull-off against lambda, or A(P) curves with the closed forms.
    Plot(basic::PlotArgs),
    /// Speed against accuracy of every solver variant: a table, JSON and a chart.
    Bench(basic::BenchArgs),
    /// The failure atlas: error maps of each method over lambda 1e-6..1e6 and loads from 1e-8
    /// above pull-off to 1e6.
    Atlas(basic::AtlasArgs),
    /// A real contact in SI units: which model it needs, radii, pull-off forces, warnings.
    Scene(scene::SceneArgs),
    /// Work of adhesion from a measured pull-off force under JKR, DMT and exact MD.
    Infer(scene::InferArgs),
    /// Approach-retract force curves: jump-in, jump-out and the energy lost per cycle.
    Cycle(scene::CycleArgs),
    /// Pull-off against relative humidity: solid adhesion and the water meniscus together (two
    /// Dugdale zones), the meniscus' share and where it dominates.
    Humidity(scene::HumidityArgs),
    /// Pressure and surface gap inside and around the contact (MD, Hertz, DMT, JKR), stress
    /// intensity and energy release rate at the contact edge.
    Profile(profile::ProfileArgs),
    /// Fit exact Maugis-Dugdale (and Hertz, DMT, JKR) to measured AFM force curves: one curve,
    /// many, or a force map.
    Fit(Box<fit::FitArgs>),
    /// A rough surface (Greenwood-Williamson) of exact Maugis-Dugdale summits through an
    /// approach and a retract: load per summit, contact fractions, pull-off, energy lost.
    Rough(rough::RoughArgs),
    /// Pull-off of a rough surface against its roughness for several lambda (Fuller and Tabor's
    /// figure), after pressing to a given separation.
    RoughPulloff(rough::RoughPulloffArgs),
    /// The rough adhesion map over lambda and sigma: pull-off per summit relative to the smooth
    /// summit's, and the simplest adequate summit model (Hertz, Bradley, DMT, JKR, MD).
    RoughMap(rough_map::RoughMapArgs),
    /// The Maugis-Dugdale force-overlap law for particle (DEM) codes: its branches, jumps and
    /// hysteresis as tables over lambda and overlap, a pair's law in SI units, or a pair driven
    /// under displacement control.
    DemLaw(dem::DemLawArgs),
    /// GPU adapters, backends, features and limits; and which one `--backend auto` takes.
    Info,
}

/// Where the work runs (`--backend`); the library's [`crate::engine::Backend`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum BackendArg {
    /// A hardware GPU, else the CPU (exact, and faster than a software adapter on the same
    /// cores; `gpu` uses one).
    Auto,
    /// The WGSL kernels (f32) on a GPU adapter; an error if there is none.
    Gpu,
    /// The f64 reference solver on all CPU cores.
    Cpu,
}

impl From<BackendArg> for crate::engine::Backend {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Auto => Self::Auto,
            BackendArg::Gpu => Self::Gpu,
            BackendArg::Cpu => Self::Cpu,
        }
    }
}

/// A setting from the environment: unset and empty are the same (an empty `VAR=` is how
/// scripts clear one).
fn env_setting(var: &str) -> anyhow::Result<Option<String>> {
    match std::env::var(var) {
        Ok(v) if v.trim().is_empty() => Ok(None),
        Ok(v) => Ok(Some(v.trim().to_string())),
        Err(std::env::VarError::NotPresent) => Ok(None),
        Err(std::env::VarError::NotUnicode(v)) => anyhow::bail!(
            "the environment variable {var}={v:?} is not valid text: set it to a plain value or unset it"
        ),
    }
}

/// Where the work runs: `--backend`, else the environment variable TABOR_BACKEND (named in the
/// message when its value is wrong), else `default`.
pub(crate) fn backend_choice(
    flag: Option<BackendArg>,
    default: BackendArg,
) -> anyhow::Result<BackendArg> {
    if let Some(b) = flag {
        return Ok(b);
    }
    match env_setting("TABOR_BACKEND")? {
        None => Ok(default),
        Some(v) => BackendArg::from_str(&v, true).map_err(|_| {
            anyhow::anyhow!(
                "the environment variable TABOR_BACKEND={v:?} is not a backend: set it to auto, gpu or cpu, or unset it"
            )
        }),
    }
}

/// The GPU adapter to use: `--adapter`, else the environment variable TABOR_ADAPTER. The CPU
/// backend has none: an `--adapter` with it is refused (it would be silently ignored), a
/// TABOR_ADAPTER is not used.
pub(crate) fn adapter_choice(
    flag: Option<&str>,
    backend: BackendArg,
) -> anyhow::Result<Option<String>> {
    if backend == BackendArg::Cpu {
        if let Some(a) = flag {
            anyhow::bail!(
                "--adapter {a:?} with --backend cpu: the CPU solver uses no GPU adapter; give --backend gpu (or auto) to use it, or leave out --adapter"
            );
        }
        return Ok(None);
    }
    match flag {
        Some(a) => Ok(Some(a.to_string())),
        None => env_setting("TABOR_ADAPTER"),
    }
}

/// The GPU's arithmetic (`--precision`); the library's [`crate::engine::Precision`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum PrecisionArg {
    F32,
    F64,
}

impl From<PrecisionArg> for crate::engine::Precision {
    fn from(p: PrecisionArg) -> Self {
        match p {
            PrecisionArg::F32 => Self::F32,
            PrecisionArg::F64 => Self::F64,
        }
    }
}

/// A map's load axis (`--load-axis`); the library's [`crate::map::LoadAxis`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum LoadAxisArg {
    /// Pbar on a log axis (positive loads): the classic map.
    Log,
    /// Pbar - Pbar_c on a log axis: the tensile range down to the pull-off.
    AbovePulloff,
    /// Pbar on a linear axis (tensile loads included).
    Linear,
}

impl From<LoadAxisArg> for crate::map::LoadAxis {
    fn from(a: LoadAxisArg) -> Self {
        match a {
            LoadAxisArg::Log => Self::Log,
            LoadAxisArg::AbovePulloff => Self::AbovePulloff,
            LoadAxisArg::Linear => Self::Linear,
        }
    }
}

/// A quantity drawn with a colorbar (`--quantity`); the library's
/// [`crate::render::map::Quantity`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum QuantityArg {
    /// Contact radius A (log scale).
    A,
    /// Approach Dbar.
    Approach,
    /// c/a - 1 (log scale).
    M,
    /// |A_Hertz / A - 1| (log scale).
    ErrHertz,
    /// |A_DMT / A - 1| (log scale).
    ErrDmt,
    /// |A_JKR / A - 1| (log scale).
    ErrJkr,
}

impl From<QuantityArg> for crate::render::map::Quantity {
    fn from(q: QuantityArg) -> Self {
        match q {
            QuantityArg::A => Self::A,
            QuantityArg::Approach => Self::Approach,
            QuantityArg::M => Self::M,
            QuantityArg::ErrHertz => Self::ErrHertz,
            QuantityArg::ErrDmt => Self::ErrDmt,
            QuantityArg::ErrJkr => Self::ErrJkr,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    Text,
    Csv,
    Json,
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Format::Text => "text",
            Format::Csv => "csv",
            Format::Json => "json",
        })
    }
}

/// A `--format` that accepts only `accepted` (which `--help` lists), for a command that does
/// not write every [`Format`].
pub(crate) fn formats(
    accepted: &'static [&'static str],
) -> impl clap::builder::TypedValueParser<Value = Format> {
    use clap::builder::TypedValueParser as _;
    clap::builder::PossibleValuesParser::new(accepted.to_vec())
        .map(|s| <Format as ValueEnum>::from_str(&s, false).expect("a format name"))
}

/// Parses the process's arguments and runs the command: the whole of the `tabor` binary. A
/// command line that cannot be parsed exits the process with code 1 (`--help` and `--version`
/// print to stdout and exit with 0); any other failure is returned.
pub fn run() -> anyhow::Result<()> {
    // A command line that cannot be parsed is bad input like any other: exit code 1 (clap's
    // own is 2); --help and --version go to stdout with 0.
    use clap::FromArgMatches as _;
    let mut cmd = argv::command();
    let args = argv::join_negative_values(&cmd, std::env::args_os().collect());
    let parsed = match cmd.try_get_matches_from_mut(args) {
        Ok(m) => Cli::from_arg_matches(&m).map_err(|e| e.format(&mut cmd)),
        Err(e) => Err(e),
    };
    let cli = match parsed {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            let _ = e.print();
            std::process::exit(1)
        }
        Err(e) => e.exit(),
    };
    match cli.command {
        Command::Solve(a) => match &a.tip {
            Some(t) => {
                two_zone_ratios(a.stress_ratio, a.range_ratio)?;
                tip::solve(&a, tip_shape(t)?)
            }
            None => basic::solve(a),
        },
        Command::Pulloff(a) => basic::pulloff(a),
        Command::Curve(a) => basic::curve(a),
        Command::Info => basic::info(),
        Command::Map(a) => map::run(*a),
        Command::Plot(a) => basic::plot(a),
        Command::Bench(a) => basic::bench(a),
        Command::Atlas(a) => basic::atlas(a),
        Command::Scene(a) => scene::scene(a),
        Command::Infer(a) => scene::infer_cmd(a),
        Command::Cycle(a) => scene::cycle(a),
        Command::Humidity(a) => scene::humidity_cmd(a),
        Command::Profile(a) => profile::run(a),
        Command::Fit(a) => fit::run(*a),
        Command::Rough(a) => rough::run(a),
        Command::RoughPulloff(a) => rough::pulloff(a),
        Command::RoughMap(a) => rough_map::run(a),
        Command::DemLaw(a) => dem::run(a),
    }
}

/// How a figure is written: its files (the format of each by its extension) and its printed
/// size.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct FigureArgs {
    /// The same figure as SVG (vector; text as text).
    #[arg(long)]
    pub svg: Option<std::path::PathBuf>,
    /// The same figure as a vector PDF.
    #[arg(long)]
    pub pdf: Option<std::path::PathBuf>,
    /// Printed width in millimetres (the help names each command's default, from
    /// `argv::figure_width_mm`).
    #[arg(long, conflicts_with = "double_column")]
    pub width_mm: Option<f64>,
    /// Two journal columns wide (175 mm).
    #[arg(long)]
    pub double_column: bool,
    /// PNG resolution at the printed width (85 mm at 300 dpi is 1004 pixels wide).
    #[arg(long, default_value_t = crate::render::DEFAULT_DPI)]
    pub dpi: f64,
}

/// The data outputs of a map-like command (`--json`, and `--npy PREFIX` as PREFIX_NAME for
/// each of `files`), named by their options for `FigureArgs::check_distinct`.
pub(crate) fn data_outputs(
    json: Option<&std::path::Path>,
    npy: Option<&str>,
    files: &[&str],
) -> Vec<(String, std::path::PathBuf)> {
    let json = json.map(|p| ("--json".to_string(), p.to_path_buf()));
    let npy = npy.into_iter().flat_map(|prefix| {
        files
            .iter()
            .map(move |n| ("--npy".to_string(), format!("{prefix}_{n}").into()))
    });
    json.into_iter().chain(npy).collect()
}

/// Opens PREFIX_NAME for each of `files` (none without `--npy`).
pub(crate) fn open_npy(
    prefix: Option<&str>,
    files: &[&str],
) -> anyhow::Result<Vec<crate::io::Output>> {
    use anyhow::Context;
    prefix
        .map_or(&[][..], |_| files)
        .iter()
        .map(|n| crate::io::Output::create(format!("{}_{n}", prefix.unwrap_or_default())))
        .collect::<anyhow::Result<_>>()
        .context("--npy")
}

/// The library names quantities by keys (`lambda_min`, `width_mm`, ...), never flags; the command
/// line renders its errors ([`Named`]) with the flags of a table of (key, flag).
pub(crate) fn flags(
    table: &'static [(&'static str, &'static str)],
) -> impl Fn(&str) -> Option<&'static str> {
    move |key| table.iter().find(|(k, _)| *k == key).map(|(_, f)| *f)
}

/// A library error in the flags of `table`.
pub(crate) fn in_flags(
    e: &impl Named,
    table: &'static [(&'static str, &'static str)],
) -> anyhow::Error {
    anyhow::anyhow!(e.named(&flags(table)))
}

/// The second zone's ratios, paired by the library's check, its message in flags.
pub(crate) fn two_zone_ratios(
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
) -> anyhow::Result<Option<(f64, f64)>> {
    crate::physics::two_zone::paired_ratios(stress_ratio, range_ratio)
        .map_err(|m| in_flags(&m, ZONES_FLAGS))
}

/// The two-zone law's quantities (the solid's lambda and the second zone's ratios) as flags.
pub(crate) const ZONES_FLAGS: &[(&str, &str)] = &[
    ("lambda", "--lambda"),
    ("stress_ratio", "--stress-ratio"),
    ("range_ratio", "--range-ratio"),
];

/// A two-zone refusal (the solid's lambda and the second zone's ratios) in flags.
pub(crate) fn zones_error(e: impl Named) -> anyhow::Error {
    in_flags(&e, ZONES_FLAGS)
}

/// The rough adhesion map's quantities as flags.
pub(crate) const ROUGH_MAP_FLAGS: &[(&str, &str)] = &[
    ("lambda_min", "--lambda-min"),
    ("lambda_max", "--lambda-max"),
    ("sigma_min", "--sigma-min"),
    ("sigma_max", "--sigma-max"),
    ("press_sigmas", "--press-sigmas"),
    ("nx", "--nx"),
    ("ny", "--ny"),
    ("tolerance", "--tolerance"),
];

/// The humidity sweep's quantities as flags.
pub(crate) const HUMIDITY_FLAGS: &[(&str, &str)] = &[
    ("rh_min", "--rh-min"),
    ("rh_max", "--rh-max"),
    ("points", "--points"),
];

/// A tip as a flag.
pub(crate) const TIP_FLAGS: &[(&str, &str)] = &[("tip", "--tip")];

/// The map's quantities as flags.
pub(crate) const MAP_FLAGS: &[(&str, &str)] = &[
    ("lambda_min", "--lambda-min"),
    ("lambda_max", "--lambda-max"),
    ("load_min", "--load-min"),
    ("load_max", "--load-max"),
    ("nx", "--nx"),
    ("ny", "--ny"),
    ("tolerance", "--tolerance"),
    ("strength_ratio", "--strength-ratio"),
    ("load_axis=linear", "--load-axis linear"),
    ("keep_exact", "--npy or --json-full"),
    (
        "regions_alone",
        ", a map of regions alone (without --quantity, --npy or --json-full) up to 16384 x 16384",
    ),
];

/// A figure's size as flags.
pub(crate) const FIGURE_FLAGS: &[(&str, &str)] = &[("width_mm", "--width-mm"), ("dpi", "--dpi")];

impl FigureArgs {
    /// The printed size of `command`'s figure; its default width where none is given.
    pub fn print(&self, command: &str) -> anyhow::Result<crate::render::Print> {
        let default_mm = argv::figure_width_mm(command);
        let mm = match (self.width_mm, self.double_column) {
            (Some(w), _) => w,
            (None, true) => crate::render::DOUBLE_COLUMN_MM,
            (None, false) => default_mm,
        };
        crate::render::Print::new(mm, self.dpi).map_err(|e| in_flags(&e, FIGURE_FLAGS))
    }

    /// The figure's files with the options that name them (`main` given by `flag`), for
    /// [`crate::io::output::check_distinct`].
    pub fn named(
        &self,
        main: Option<&std::path::Path>,
        flag: &str,
    ) -> Vec<(String, std::path::PathBuf)> {
        let mut v: Vec<(String, std::path::PathBuf)> = main
            .map(|p| (flag.to_string(), p.to_path_buf()))
            .into_iter()
            .collect();
        v.extend(self.svg.clone().map(|p| ("--svg".to_string(), p)));
        v.extend(self.pdf.clone().map(|p| ("--pdf".to_string(), p)));
        v
    }

    /// Refuses two of these outputs (the figure's, and `more`) that would write one file.
    pub fn check_distinct(
        &self,
        main: Option<&std::path::Path>,
        flag: &str,
        more: impl IntoIterator<Item = (String, std::path::PathBuf)>,
    ) -> anyhow::Result<()> {
        let mut v = self.named(main, flag);
        v.extend(more);
        crate::io::output::check_distinct(v)
    }

    /// The files: `main` (given by `flag`, any of .png, .svg, .pdf) with --svg and --pdf.
    pub fn outputs(
        &self,
        main: Option<&std::path::Path>,
        flag: &str,
    ) -> anyhow::Result<crate::render::Outputs> {
        let mut o = crate::render::Outputs::default();
        if let Some(p) = main {
            o.add(p).map_err(|e| anyhow::anyhow!("{flag} {e}"))?;
        }
        for (p, ext, f) in [(&self.svg, "svg", "--svg"), (&self.pdf, "pdf", "--pdf")] {
            if let Some(p) = p {
                map::check_extension(p, ext, f)?;
                o.add(p).map_err(|e| anyhow::anyhow!("{f} {e}"))?;
            }
        }
        Ok(o)
    }
}

/// Writes the data (`-o`) and the figure (`--plot`, `--svg`, `--pdf`) together: every file is
/// opened and the figure drawn before any is written, and none is put in place unless all were.
/// A bad figure path or a failed drawing leaves no data file behind, and a bad data path no
/// figure. With no figure asked for, only the data.
pub(crate) fn write_with_figure(
    output: &str,
    data: &[u8],
    kind: crate::render::Kind,
    print: &crate::render::Print,
    figure: &crate::render::Outputs,
    draw: crate::render::DrawSvg,
) -> anyhow::Result<()> {
    use anyhow::Context;
    use std::io::Write;
    let open = |p: &std::path::Path| crate::io::Output::create(p);
    let mut files = vec![(
        open(std::path::Path::new(output))?,
        std::borrow::Cow::Borrowed(data),
    )];
    if !figure.is_empty() {
        let opened =
            [&figure.png, &figure.svg, &figure.pdf].map(|p| p.as_deref().map(open).transpose());
        let mut outs = Vec::with_capacity(3);
        for o in opened {
            outs.push(o?);
        }
        let r = crate::render::draw_figure(kind, print, figure.formats(), draw)
            .map_err(anyhow::Error::from_boxed)?;
        let bytes = [r.png, r.svg.map(String::into_bytes), r.pdf];
        for (o, b) in outs.into_iter().zip(bytes) {
            if let (Some(o), Some(b)) = (o, b) {
                files.push((o, std::borrow::Cow::Owned(b)));
            }
        }
    }
    for (o, b) in files.iter_mut() {
        let shown = o.name().display().to_string();
        o.write_all(b)
            .with_context(|| format!("cannot write {shown}"))?;
    }
    for (o, _) in files {
        o.commit()?;
    }
    Ok(())
}

/// A `--tip` value as a shape in its normalised units ([`Shape`]'s parser, its message named
/// as the flag), or `scene:FILE`: the tip of a scene file in the units of its E* and w
/// ([`units_of`]; a measured profile's shape in the units depends on them).
///
/// [`Shape`]: crate::physics::tip::Shape
/// [`units_of`]: crate::scene::tip::units_of
pub fn tip_shape(s: &str) -> anyhow::Result<crate::physics::tip::Shape> {
    match s.strip_prefix("scene:") {
        Some(f) => {
            let u = crate::scene::tip::units_of(&scene::read_scene(f)?)
                .map_err(|e| anyhow::anyhow!("--tip {s}: {e}"))?;
            eprintln!(
                "the tip of {f} in the units of its E* and w: {} (l = {} m, d = {} m; the scene's own lambda is {:.6})",
                u.shape.label(),
                crate::physics::domain::short(u.length_m),
                crate::physics::domain::short(u.approach_m),
                u.lambda
            );
            Ok(u.shape)
        }
        None => s.parse().map_err(|e: crate::error::Message| {
            anyhow::anyhow!(
                "{} (or scene:FILE, a scene's tip)",
                e.named(&flags(TIP_FLAGS))
            )
        }),
    }
}
