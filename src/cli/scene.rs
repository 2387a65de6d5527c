//! `tabor scene` and `tabor infer`: real contacts in SI units.

use super::Format;
use crate::io::write_output;
use crate::render::Kind;
use crate::scene::tip::TipSceneResult;
use crate::scene::{infer, preset, preset_names, SceneInput, SceneResult, Solved};
use anyhow::{bail, Context};
use clap::Args;
use std::fmt::Write as _;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct SceneArgs {
    /// Scene file (JSON, SI units; see README); `-` is stdin.
    pub file: Option<String>,
    /// A built-in scene: afm-si, pdms-glass, mica-sfa, graphene-mems, hydrogel-titanium.
    #[arg(long, conflicts_with = "file")]
    pub preset: Option<String>,
    /// Override the scene's loads (N), comma separated.
    #[arg(long, value_delimiter = ',')]
    pub loads: Option<Vec<f64>>,
    #[arg(long)]
    pub tolerance: Option<f64>,
    #[arg(long, value_parser = super::formats(&["text", "json"]), default_value_t = Format::Text)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Draw a(P) for the scene and its place on the adhesion map (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: super::FigureArgs,
}

pub fn scene(a: SceneArgs) -> anyhow::Result<()> {
    let mut input: SceneInput = match (&a.file, &a.preset) {
        (_, Some(p)) => preset_named(p)?,
        (Some(f), None) => read_scene(f)?,
        (None, None) => bail!(
            "give a scene file or --preset ({})",
            preset_names().join(", ")
        ),
    };
    if let Some(l) = &a.loads {
        input.loads_n = Some(l.clone());
        input.load_range_n = None;
    }
    if a.tolerance.is_some() {
        input.tolerance = a.tolerance;
    }
    if a.format == Format::Csv {
        bail!("--format csv is not available for a scene: use text or json");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
    let print = a.figure.print("scene")?;
    let r = match crate::scene::solve(&input)? {
        Solved::Sphere(r) => *r,
        Solved::Tip(r) => {
            if !figure.is_empty() {
                bail!("--plot is not available for a scene with a tip other than a sphere yet: leave it out");
            }
            let text = match a.format {
                Format::Json => serde_json::to_string_pretty(&r)? + "\n",
                _ => tip_scene_text(&r),
            };
            return write_output(&a.output, text.as_bytes()).context("writing the scene");
        }
    };
    let text = match a.format {
        Format::Json => serde_json::to_string_pretty(&r)? + "\n",
        _ => scene_text(&r),
    };
    let fig = if figure.is_empty() {
        None
    } else {
        Some(crate::figure_data::scene_data(&r)?)
    };
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Scene,
        &print,
        &figure,
        &|root| match &fig {
            Some(fig) => crate::render::plots::scene(root, &r, fig),
            None => Ok(()),
        },
    )
    .context("writing the scene")?;
    if fig.is_some() {
        eprintln!("wrote the figure");
    }
    Ok(())
}

/// Largest scene file read (a scene is a few hundred bytes; this keeps `/dev/zero` out).
const MAX_SCENE_BYTES: u64 = 1 << 20;

/// A scene from a JSON file (`-` is stdin).
pub fn read_scene(f: &str) -> anyhow::Result<SceneInput> {
    use std::io::Read;
    let src: Box<dyn Read> = if f == "-" {
        Box::new(std::io::stdin())
    } else {
        Box::new(std::fs::File::open(f).with_context(|| format!("cannot read {f}"))?)
    };
    let mut text = String::new();
    src.take(MAX_SCENE_BYTES + 1)
        .read_to_string(&mut text)
        .with_context(|| format!("cannot read {f}"))?;
    if text.len() as u64 > MAX_SCENE_BYTES {
        bail!("{f}: larger than 1 MiB, not a scene file");
    }
    serde_json::from_str(&text).map_err(|e| {
        // serde names an unknown key but, inside "control", only by its position: say what
        // the control may be.
        let inside_control = text
            .get(..text.len().min(byte_at(&text, e.line(), e.column())))
            .is_some_and(|head| {
                head.rfind("\"control\"")
                    .is_some_and(|i| !head[i..].contains('}'))
            });
        let hint = if inside_control {
            "; control is \"load\", \"displacement\" or {\"cantilever_n_m\": k}"
        } else {
            ""
        };
        anyhow::anyhow!(
            "{f}: not a valid scene ({e}){hint} (JSON with SI keys, e.g. body1.youngs_modulus_pa; see README)"
        )
    })
}

/// The byte offset of a 1-based line and column in `text`.
fn byte_at(text: &str, line: usize, column: usize) -> usize {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    start + column
}

/// A built-in scene by name.
pub fn preset_named(p: &str) -> anyhow::Result<SceneInput> {
    preset(p).with_context(|| {
        format!(
            "no preset {p:?}; the presets are {}",
            preset_names().join(", ")
        )
    })
}

fn si(x: f64, unit: &str) -> String {
    let prefixes = [
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "u"),
        (1e-9, "n"),
        (1e-12, "p"),
        (1e-15, "f"),
        (1e-18, "a"),
        (1e-21, "z"),
    ];
    if x == 0.0 || !x.is_finite() {
        return format!("{x} {unit}");
    }
    match prefixes.iter().find(|(s, _)| x.abs() >= *s * 0.9995) {
        Some((s, p)) => format!("{:.4} {p}{unit}", x / s),
        None => format!("{x:.4e} {unit}"),
    }
}

/// A tip scene as text: the tip and its units, the pull-offs, each load's state.
pub fn tip_scene_text(r: &TipSceneResult) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{}", r.name);
    let tip = serde_json::to_string(&r.tip).unwrap_or_default();
    let _ = writeln!(t, "  tip {tip}");
    if let Some(a) = r.equivalent_cone_half_angle_deg {
        let _ = writeln!(
            t,
            "  solved as the equivalent cone of half-angle {a:.2} deg"
        );
    }
    let _ = writeln!(
        t,
        "  E* = {}, w = {} J/m^2, s0 = {}",
        si(r.e_star_pa, "Pa"),
        r.work_of_adhesion_j_m2,
        si(r.s0_pa, "Pa")
    );
    let _ = writeln!(
        t,
        "  Maugis parameter of the tip lambda = {:.4} (units: radius {}, approach {}, force {})",
        r.lambda,
        si(r.units.length_m, "m"),
        si(r.units.approach_m, "m"),
        si(r.units.force_n, "N")
    );
    for w in &r.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    let _ = writeln!(
        t,
        "  pull-off force: {} (load control, at contact radius {}), {} (displacement control)",
        si(r.pulloff_force_load_control_N, "N"),
        si(r.pulloff_contact_radius_load_control_m, "m"),
        si(r.pulloff_force_displacement_control_N, "N")
    );
    if r.control != "load" {
        let _ = writeln!(
            t,
            "  pull-off (jump-out) force under this scene's control ({}): {}",
            r.control,
            si(r.pulloff_force_under_control_N, "N")
        );
    }
    let _ = writeln!(t, "  recommended model: {}", r.recommended_model);
    let _ = writeln!(
        t,
        "  {:>12} {:>12} {:>12} {:>12} {:>8}  why",
        "load", "radius a", "zone c", "approach", "model"
    );
    for l in &r.loads {
        let f = |x: Option<f64>, u: &str| x.map_or("-".into(), |v| si(v, u));
        let _ = writeln!(
            t,
            "  {:>12} {:>12} {:>12} {:>12} {:>8}  {}",
            si(l.load_n, "N"),
            f(l.contact_radius_m, "m"),
            f(l.zone_radius_m, "m"),
            f(l.approach_m, "m"),
            l.model,
            l.why
        );
    }
    t
}

pub fn scene_text(r: &SceneResult) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{}", r.name);
    let _ = writeln!(
        t,
        "  E* = {}, K = {}, R = {}, w = {} J/m^2, s0 = {}",
        si(r.e_star_pa, "Pa"),
        si(r.k_pa, "Pa"),
        si(r.radius_m, "m"),
        r.work_of_adhesion_j_m2,
        si(r.s0_pa, "Pa")
    );
    let _ = writeln!(
        t,
        "  Maugis parameter lambda = {:.4}, Tabor parameter = {:.4}",
        r.lambda, r.tabor_parameter
    );
    if let Some(m) = &r.meniscus {
        let _ = writeln!(
            t,
            "  water meniscus at RH = {:.1}%: Kelvin radius {}, Laplace pressure {}, height {}, w = {:.4} J/m^2, lambda = {:.4}",
            100.0 * r.relative_humidity.unwrap_or(f64::NAN),
            si(m.kelvin_radius_m, "m"),
            si(m.laplace_pressure_pa, "Pa"),
            si(m.range_m, "m"),
            m.work_of_adhesion_j_m2,
            m.lambda
        );
        let _ = writeln!(
            t,
            "  dry pull-off for comparison: {} (load control), {} (displacement control); below: solid and meniscus",
            si(r.dry_pulloff_force_load_control_N.unwrap_or(f64::NAN), "N"),
            si(r.dry_pulloff_force_displacement_control_N.unwrap_or(f64::NAN), "N")
        );
    } else if let Some(rh) = r.relative_humidity {
        // The reason, unless a warning below gives it.
        let why = match (&r.no_meniscus, r.meniscus_warnings.is_empty()) {
            (Some(w), true) => format!(" ({w})"),
            _ => String::new(),
        };
        let _ = writeln!(t, "  RH = {rh:?}: no meniscus{why}: the dry contact");
    }
    for w in &r.meniscus_warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    let _ = writeln!(
        t,
        "  pull-off force: {} (load control), {} (displacement control); under this scene's control ({}): {}",
        si(r.pulloff_force_load_control_N, "N"),
        si(r.pulloff_force_displacement_control_N, "N"),
        r.control,
        si(r.pulloff_force_under_control_N, "N")
    );
    let _ = writeln!(
        t,
        "  contact radius at zero load: {}",
        si(r.zero_load_contact_radius_m, "m")
    );
    let _ = writeln!(
        t,
        "  recommended model: {} ({})",
        r.recommended_model, r.recommendation
    );
    let _ = writeln!(
        t,
        "  {:>12} {:>12} {:>12} {:>12} {:>8}  why",
        "load", "radius a", "approach", "a/R", "model"
    );
    for l in &r.loads {
        let f = |x: Option<f64>, u: &str| x.map_or("-".into(), |v| si(v, u));
        let _ = writeln!(
            t,
            "  {:>12} {:>12} {:>12} {:>12} {:>8}  {}",
            si(l.load_n, "N"),
            f(l.contact_radius_m, "m"),
            f(l.approach_m, "m"),
            l.a_over_r.map_or("-".into(), |v| format!("{v:.3e}")),
            l.model,
            l.why
        );
        if let Some(fr) = l.friction_n {
            let _ = writeln!(
                t,
                "  {:>12} friction estimate tau0 pi a^2 = {}",
                "",
                si(fr, "N")
            );
        }
        for w in &l.warnings {
            let _ = writeln!(t, "  {:>12} warning: {w}", "");
        }
    }
    if let Some(s) = &r.source {
        let _ = writeln!(t, "  values: {s}");
    }
    t
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct InferArgs {
    /// Measured pull-off force (N).
    #[arg(long, required_unless_present = "pairs")]
    pub pulloff: Option<f64>,
    /// Measured (load, contact radius) pairs: CSV with columns `load_n` and `contact_radius_m`;
    /// w and E* are fitted with the exact MD model.
    #[arg(long, conflicts_with_all = ["pulloff", "e_star"])]
    pub pairs: Option<String>,
    /// Effective radius (m).
    #[arg(long)]
    pub radius: f64,
    /// Reduced modulus E* (Pa); needed with --pulloff.
    #[arg(long, required_unless_present = "pairs")]
    pub e_star: Option<f64>,
    /// Lennard-Jones range z0 (m).
    #[arg(long, default_value_t = 0.3e-9)]
    pub z0: f64,
    /// Relative humidity (0..1) of the air the pull-off was measured in: the solid's w is
    /// reported with the water meniscus taken out (with --pulloff).
    #[arg(long, conflicts_with = "pairs")]
    pub relative_humidity: Option<f64>,
    /// Contact angle of water on the surfaces (degrees), with --relative-humidity.
    #[arg(long, default_value_t = 0.0, requires = "relative_humidity")]
    pub contact_angle_deg: f64,
    #[arg(long, value_parser = super::formats(&["text", "json"]), default_value_t = Format::Text)]
    pub format: Format,
}

/// `infer --pulloff` in humid air: the solid's w with the meniscus taken out.
fn infer_wet_cmd(a: &InferArgs, pulloff: f64, e_star: f64, rh: f64) -> anyhow::Result<()> {
    let h = crate::scene::humidity::HumidityInput::water(rh, a.contact_angle_deg);
    let flags = &[
        ("humidity.relative_humidity", "--relative-humidity"),
        ("humidity.contact_angle_deg", "--contact-angle-deg"),
    ];
    let r = crate::scene::infer_wet(pulloff, a.radius, e_star, a.z0, &h)
        .map_err(|e| super::in_flags(&e, flags))?;
    if a.format == Format::Json {
        return write_output("-", (serde_json::to_string_pretty(&r)? + "\n").as_bytes());
    }
    let mut t = format!(
        "pull-off force {} with R = {}, E* = {}, z0 = {}, in air at RH = {:.1}% (water, contact angle {} deg)\n",
        si(r.pulloff_force_n, "N"),
        si(a.radius, "m"),
        si(e_star, "Pa"),
        si(a.z0, "m"),
        100.0 * rh,
        a.contact_angle_deg,
    );
    if let Some(m) = &r.meniscus {
        let _ = writeln!(
            t,
            "  water meniscus: Kelvin radius {}, height {}, w = {:.4e} J/m^2; alone it pulls off at {}",
            si(m.kelvin_radius_m, "m"),
            si(m.range_m, "m"),
            m.work_of_adhesion_j_m2,
            si(r.meniscus_only_pulloff_n, "N"),
        );
    }
    let _ = writeln!(t, "  {}", r.verdict);
    for w in &r.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    write_output("-", t.as_bytes())
}

pub fn infer_cmd(a: InferArgs) -> anyhow::Result<()> {
    if a.format == Format::Csv {
        bail!("--format csv is not available for infer: use text or json");
    }
    let mut t = String::new();
    if let Some(f) = &a.pairs {
        let pairs = crate::io::PointReader::open_columns(f, ("load_n", "contact_radius_m"))?
            .next_chunk(MAX_PAIRS + 1)?;
        if pairs.len() > MAX_PAIRS {
            bail!("{f}: more than {MAX_PAIRS} pairs; fit a representative subset");
        }
        let fit = crate::scene::fit_pairs(&pairs, a.radius, a.z0).with_context(|| f.to_string())?;
        if a.format == Format::Json {
            return write_output("-", (serde_json::to_string_pretty(&fit)? + "\n").as_bytes());
        }
        let _ = writeln!(
            t,
            "Maugis-Dugdale fit of {} (load, contact radius) pairs with R = {}, z0 = {}:",
            pairs.len(),
            si(a.radius, "m"),
            si(a.z0, "m")
        );
        let _ = writeln!(
            t,
            "  w = {:.5e} J/m^2, E* = {}, lambda = {:.4}, Tabor parameter {:.4}",
            fit.work_of_adhesion_j_m2,
            si(fit.e_star_pa, "Pa"),
            fit.lambda,
            fit.tabor_parameter
        );
        let _ = writeln!(
            t,
            "  relative residuals of the contact radius: rms {:.2e}",
            fit.rms_relative_residual
        );
        for (&(p, r), e) in pairs.iter().zip(&fit.relative_residuals) {
            let _ = writeln!(
                t,
                "    load {:>14}  radius {:>14}  residual {e:+.2e}",
                si(p, "N"),
                si(r, "m")
            );
        }
        return write_output("-", t.as_bytes());
    }
    let (pulloff, e_star) = (
        a.pulloff.context("give --pulloff")?,
        a.e_star.context("give --e-star")?,
    );
    if let Some(rh) = a.relative_humidity {
        return infer_wet_cmd(&a, pulloff, e_star, rh);
    }
    let r = infer(pulloff, a.radius, e_star, a.z0)?;
    if a.format == Format::Json {
        return write_output("-", (serde_json::to_string_pretty(&r)? + "\n").as_bytes());
    }
    let _ = writeln!(
        t,
        "pull-off force {} with R = {}, E* = {}, z0 = {}",
        si(r.pulloff_force_n, "N"),
        si(a.radius, "m"),
        si(e_star, "Pa"),
        si(a.z0, "m")
    );
    let _ = writeln!(
        t,
        "  JKR (Fc = 3/2 pi w R): w = {:.4e} J/m^2, Tabor parameter then {:.3}",
        r.w_jkr_j_m2, r.tabor_if_jkr
    );
    let _ = writeln!(
        t,
        "  DMT (Fc = 2 pi w R):   w = {:.4e} J/m^2, Tabor parameter then {:.3}",
        r.w_dmt_j_m2, r.tabor_if_dmt
    );
    match (r.w_md_j_m2, r.lambda_md) {
        (Some(w), Some(l)) => {
            let _ = writeln!(
                t,
                "  Maugis-Dugdale (w and lambda together): w = {w:.4e} J/m^2, lambda = {l:.4}"
            );
        }
        _ => {
            let _ = writeln!(
                t,
                "  Maugis-Dugdale: no solution between the DMT and JKR values"
            );
        }
    }
    let _ = writeln!(t, "  {}", r.verdict);
    for w in &r.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    write_output("-", t.as_bytes())
}

/// Most (load, contact radius) pairs `infer --pairs` fits.
const MAX_PAIRS: usize = 100_000;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DriveKind {
    /// Rigid grips: displacement control.
    Grips,
    /// Dead load: load control.
    DeadLoad,
    /// A spring in series (an AFM cantilever): --stiffness (normalised) or --spring-n-m.
    Spring,
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct CycleArgs {
    /// Maugis parameter (or take it from --scene/--preset).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// A scene file (SI units): lambda from it, energies in joules.
    #[arg(long)]
    pub scene: Option<String>,
    #[arg(long, conflicts_with = "scene")]
    pub preset: Option<String>,
    #[arg(long, value_enum, default_value_t = DriveKind::Grips)]
    pub control: DriveKind,
    /// Normalised spring stiffness kbar = k (pi^2 w^2 R / K^2)^(1/3) / (pi w R).
    #[arg(long)]
    pub stiffness: Option<f64>,
    /// Spring stiffness in N/m (needs a scene).
    #[arg(long)]
    pub spring_n_m: Option<f64>,
    /// Largest load of the approach (normalised).
    #[arg(long, default_value_t = 2.0)]
    pub max_load: f64,
    /// A second Dugdale zone (a water meniscus): its stress over the solid's, s2/s1 (with
    /// --range-ratio; loads and approaches then in the units of the total w).
    #[arg(long)]
    pub stress_ratio: Option<f64>,
    /// The second zone's range over the solid's, h2/h1 (with --stress-ratio).
    #[arg(long)]
    pub range_ratio: Option<f64>,
    /// A tip that is not a sphere (docs/PHYSICS.md section 12), with --lambda its Maugis
    /// parameter and loads in its units: cone, power:N or capped-cone:R_OVER_L:HALF_ANGLE_DEG.
    /// Or scene:FILE, the tip of a scene file in the units of its E* and w (any SI tip, a measured
    /// profile among them).
    #[arg(long, conflicts_with_all = ["scene", "preset", "stress_ratio", "range_ratio"])]
    pub tip: Option<String>,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Csv)]
    pub format: Format,
    /// Force against displacement and contact radius against load (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: super::FigureArgs,
}

pub fn cycle(a: CycleArgs) -> anyhow::Result<()> {
    use crate::cycle::CycleSpec;
    use crate::law::ContactLaw;
    let scene = match (&a.scene, &a.preset) {
        (Some(f), _) => Some(read_scene(f)?),
        (None, Some(p)) => Some(preset_named(p)?),
        _ => None,
    };
    let contact = scene.as_ref().map(crate::scene::contact_of).transpose()?;
    // A scene with a meniscus: the two-zone cycle, its ratios and total-w units from the scene.
    let wet = match (&scene, &contact) {
        (Some(s), Some(c)) => match s
            .humidity
            .as_ref()
            .map(|h| h.meniscus(c))
            .transpose()?
            .flatten()
        {
            Some(m) => Some(crate::scene::humidity::wet_ratios(c, &m)?),
            None => None,
        },
        _ => None,
    };
    warn_humidity(scene.as_ref(), contact.as_ref());
    if contact.is_some() && a.stress_ratio.is_some() {
        bail!("--stress-ratio and --range-ratio go with --lambda; a scene takes its meniscus from its \"humidity\" key");
    }
    let scale = |c: &crate::physics::params::Contact| match &wet {
        Some((_, _, u)) => (u.load, u.approach),
        None => (c.force_scale(), c.approach_scale()),
    };
    let lambda = match (a.lambda, &contact) {
        (Some(l), None) => l,
        (None, Some(c)) => c.lambda(),
        (Some(_), Some(_)) => bail!("give --lambda or a scene, not both"),
        (None, None) => bail!("give --lambda, --scene FILE or --preset NAME"),
    };
    crate::solver::domain::check_lambda(lambda).context(if a.lambda.is_some() {
        "--lambda"
    } else {
        "the scene's lambda"
    })?;
    if a.format == Format::Text {
        bail!("--format text is not available for a cycle: use csv or json (a summary goes to stderr)");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
    let print = a.figure.print("cycle")?;
    let drive = cycle_drive(
        &a,
        contact.as_ref(),
        wet.as_ref().map(|w| (w.2.load, w.2.approach)),
    )?;
    let ratios = match &wet {
        Some((rho, eta, _)) => Some((*rho, *eta)),
        None => super::two_zone_ratios(a.stress_ratio, a.range_ratio)?,
    };
    let law = match a.tip.as_deref() {
        Some(t) => {
            ContactLaw::Tip(crate::law::Tip::new(super::tip_shape(t)?, lambda).context("--lambda")?)
        }
        None => ContactLaw::with_ratios(lambda, ratios),
    };
    let c = CycleSpec {
        law,
        drive,
        max_load: a.max_load,
    }
    .run()
    .map_err(|e| match contact {
        // --lambda and the ratios given as flags: the library's names are theirs.
        None => super::zones_error(e),
        Some(_) => anyhow::Error::new(e),
    })?;
    let text = cycle_text(&c, a.format)?;
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Cycle,
        &print,
        &figure,
        &|r| crate::render::plots::cycle(r, &c),
    )
    .context("writing the cycle")?;
    cycle_summary(&c, lambda, ratios, contact.as_ref().map(scale));
    if !figure.is_empty() {
        eprintln!("wrote the figure");
    }
    Ok(())
}

/// The drive of `tabor cycle` from its flags: a spring's constant normalised by the scene's
/// units (`wet`: a humid scene's total-w force and approach units).
fn cycle_drive(
    a: &CycleArgs,
    contact: Option<&crate::physics::params::Contact>,
    wet: Option<(f64, f64)>,
) -> anyhow::Result<crate::cycle::Drive> {
    use crate::cycle::{normalised_stiffness, Drive};
    if a.control != DriveKind::Spring && (a.stiffness.is_some() || a.spring_n_m.is_some()) {
        bail!("--stiffness and --spring-n-m set the spring of --control spring; --control {} has none", match a.control {
            DriveKind::Grips => "grips",
            _ => "dead-load",
        });
    }
    Ok(match a.control {
        DriveKind::Grips => Drive::RigidGrips,
        DriveKind::DeadLoad => Drive::DeadLoad,
        DriveKind::Spring => {
            let k = match (a.stiffness, a.spring_n_m, contact) {
                (Some(k), None, _) => k,
                (None, Some(k), Some(c)) => match wet {
                    None => normalised_stiffness(k, c),
                    Some((load, approach)) => k * approach / load,
                },
                (None, Some(_), None) => bail!("--spring-n-m needs a scene (--scene or --preset) to normalise it; or give --stiffness"),
                _ => bail!("--control spring needs --stiffness (normalised) or --spring-n-m with a scene"),
            };
            // The library checks k (and the rest), in the same words as for Python.
            Drive::Spring(k)
        }
    })
}

/// The limits of a scene's meniscus model on stderr, as `tabor scene` reports them.
fn warn_humidity(scene: Option<&SceneInput>, c: Option<&crate::physics::params::Contact>) {
    if let (Some(h), Some(c)) = (scene.and_then(|s| s.humidity.as_ref()), c) {
        for w in h.warnings(c.radius) {
            eprintln!("warning: {w}");
        }
    }
}

/// A cycle as JSON, or as CSV with one row per step.
fn cycle_text(c: &crate::cycle::Cycle, format: Format) -> anyhow::Result<String> {
    Ok(match format {
        Format::Json => serde_json::to_string_pretty(&c)? + "\n",
        _ => {
            let mut w = crate::io::csv_writer();
            w.write_record([
                "phase", "branch", "approach", "load", "A", "C", "control", "jump",
            ])?;
            let e = |x: f64| format!("{x:.16e}");
            for s in &c.steps {
                w.write_record([
                    s.phase.to_string(),
                    s.point.branch.name().to_string(),
                    e(s.point.approach),
                    e(s.point.load),
                    e(s.point.a),
                    e(s.point.c),
                    e(s.control),
                    (s.jump as u8).to_string(),
                ])?;
            }
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
    })
}

/// The summary of a cycle on stderr: its parameters, its jumps, the energy lost (in J for a
/// scene, whose force and approach units are `units`).
fn cycle_summary(
    c: &crate::cycle::Cycle,
    lambda: f64,
    ratios: Option<(f64, f64)>,
    units: Option<(f64, f64)>,
) {
    // A spring's kbar with the w its units are built on, as `tabor scene` says it.
    let drive = match c.drive {
        crate::cycle::Drive::Spring(k) => {
            format!("Spring, {}", crate::cycle::kbar_text(k, ratios.is_some()))
        }
        d => format!("{d:?}"),
    };
    match ratios {
        Some((rho, eta)) => eprintln!(
            "lambda = {lambda:.4} (solid), stress ratio {rho:.4}, range ratio {eta:.4} (units of the total w), {drive}"
        ),
        None => eprintln!("lambda = {lambda:.4}, {drive}"),
    }
    for j in &c.jumps {
        match &j.to {
            Some(to) => eprintln!("  {} jump: from (approach {:.6}, load {:.6}, A {:.6}) to (approach {:.6}, load {:.6}, A {:.6})", j.phase, j.from.approach, j.from.load, j.from.a, to.approach, to.load, to.a),
            None => eprintln!("  {} jump: from (approach {:.6}, load {:.6}, A {:.6}): the surfaces separate", j.phase, j.from.approach, j.from.load, j.from.a),
        }
    }
    match (c.hysteresis, units) {
        (Some(w), Some((force, approach))) => eprintln!(
            "  energy lost per cycle: {w:.6} (normalised) = {}",
            si(w * force * approach, "J")
        ),
        (Some(w), None) => eprintln!(
            "  energy lost per cycle: {w:.6} (in units of pi w R times the approach unit)"
        ),
        (None, _) => eprintln!(
            "  energy lost per cycle: not defined ({} the surfaces separate for good: the loop does not close)",
            match c.drive {
                crate::cycle::Drive::Spring(_) => "the spring is too soft to catch them after the jump-out:",
                _ => "under dead load",
            }
        ),
    }
}

#[derive(Args, Debug)]
pub struct HumidityArgs {
    /// Scene file (JSON, SI units); its "humidity" object, if any, gives the liquid and the
    /// contact angle (its relative_humidity is replaced by the sweep).
    #[arg(long, conflicts_with = "preset")]
    pub scene: Option<String>,
    /// A built-in scene: afm-si, pdms-glass, mica-sfa, graphene-mems, hydrogel-titanium.
    #[arg(long)]
    pub preset: Option<String>,
    #[arg(long, default_value_t = 0.05)]
    pub rh_min: f64,
    #[arg(long, default_value_t = 0.95)]
    pub rh_max: f64,
    #[arg(long, default_value_t = 19)]
    pub points: usize,
    /// Contact angle of water (degrees) [default: the scene's, else 0, a fully wetting surface].
    #[arg(long)]
    pub contact_angle_deg: Option<f64>,
    #[arg(long, value_parser = super::formats(&["text", "csv", "json"]), default_value_t = Format::Text)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Draw the pull-off against RH (solid, meniscus, total) (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: super::FigureArgs,
}

pub fn humidity_cmd(a: HumidityArgs) -> anyhow::Result<()> {
    let input: SceneInput = match (&a.scene, &a.preset) {
        (_, Some(p)) => preset_named(p)?,
        (Some(f), None) => read_scene(f)?,
        (None, None) => bail!(
            "give --scene FILE or --preset ({})",
            preset_names().join(", ")
        ),
    };
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
    let print = a.figure.print("humidity")?;
    let r = crate::scene::humidity::sweep_scene(
        &input,
        a.contact_angle_deg,
        a.rh_min,
        a.rh_max,
        a.points,
    )
    .map_err(|e| super::in_flags(&e, super::HUMIDITY_FLAGS))?;
    let text = match a.format {
        Format::Json => serde_json::to_string_pretty(&r)? + "\n",
        Format::Csv => humidity_csv(&r),
        Format::Text => humidity_text(&r),
    };
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Pulloff,
        &print,
        &figure,
        &|root| crate::render::plots::humidity(root, &r),
    )
    .context("writing the humidity sweep")?;
    // The text carries its warnings; a table or JSON output gets them here too.
    if a.format == Format::Csv {
        for w in &r.warnings {
            eprintln!("warning: {w}");
        }
    }
    if !figure.is_empty() {
        eprintln!("wrote the figure");
    }
    Ok(())
}

fn humidity_csv(r: &crate::scene::humidity::HumiditySweep) -> String {
    let mut t = String::from("relative_humidity,kelvin_radius_m,meniscus_range_m,meniscus_lambda,pulloff_solid_N,pulloff_meniscus_N,pulloff_total_N,meniscus_share\n");
    for p in &r.points {
        let _ = writeln!(
            t,
            "{},{:e},{:e},{},{:e},{:e},{:e},{}",
            p.relative_humidity,
            p.kelvin_radius_m,
            p.meniscus_range_m,
            p.meniscus_lambda.map_or(String::new(), |l| l.to_string()),
            p.pulloff_solid_N,
            p.pulloff_meniscus_N,
            p.pulloff_total_N,
            p.meniscus_share
        );
    }
    t
}

fn humidity_text(r: &crate::scene::humidity::HumiditySweep) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{}", r.name);
    let _ = writeln!(
        t,
        "  solid w = {} J/m^2; water meniscus w = 2 gamma cos(theta) = {:.4} J/m^2 (theta = {} deg)",
        r.work_of_adhesion_solid_j_m2, r.work_of_adhesion_meniscus_j_m2, r.contact_angle_deg
    );
    let _ = writeln!(t, "  {}", r.meniscus_dominates);
    for w in &r.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    let _ = writeln!(
        t,
        "  {:>6} {:>12} {:>12} {:>14} {:>14} {:>14} {:>7}",
        "RH", "r_K", "height", "solid", "meniscus", "total", "share"
    );
    for p in &r.points {
        let _ = writeln!(
            t,
            "  {:>5.1}% {:>12} {:>12} {:>14} {:>14} {:>14} {:>6.1}%",
            100.0 * p.relative_humidity,
            si(p.kelvin_radius_m, "m"),
            si(p.meniscus_range_m, "m"),
            si(p.pulloff_solid_N, "N"),
            si(p.pulloff_meniscus_N, "N"),
            si(p.pulloff_total_N, "N"),
            100.0 * p.meniscus_share
        );
    }
    t
}
