//! `tabor profile`: pressure and gap inside and around the contact.

use super::Format;
use crate::io::fmt17;
use crate::profile::{profile, Given, Profile};
use crate::render::Kind;
use anyhow::{bail, Context};
use clap::Args;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct ProfileArgs {
    /// Maugis parameter (or take it from --scene/--preset).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Normalised load Pbar (the stable branch under load control).
    #[arg(long, conflicts_with_all = ["approach", "radius_a", "load_n"])]
    pub load: Option<f64>,
    /// Normalised approach Dbar (the stable branch under displacement control).
    #[arg(long, conflicts_with_all = ["radius_a", "load_n"])]
    pub approach: Option<f64>,
    /// Contact radius A (any point of the curve).
    #[arg(long, conflicts_with = "load_n")]
    pub radius_a: Option<f64>,
    /// A scene file (SI units): lambda from it and the output in m, Pa and N.
    #[arg(long, conflicts_with = "lambda")]
    pub scene: Option<String>,
    #[arg(long, conflicts_with_all = ["scene", "lambda"])]
    pub preset: Option<String>,
    /// The load in N, with a scene.
    #[arg(long)]
    pub load_n: Option<f64>,
    /// A second Dugdale zone (e.g. a water meniscus): its stress over the solid's, s2/s1; then
    /// --lambda is the solid's and units are built on the total w (docs/PHYSICS.md section 10).
    #[arg(long, conflicts_with_all = ["scene", "preset"])]
    pub stress_ratio: Option<f64>,
    /// The second zone's range over the solid's, h2/h1.
    #[arg(long)]
    pub range_ratio: Option<f64>,
    /// A tip that is not a sphere (docs/PHYSICS.md section 12), with --lambda its Maugis
    /// parameter and the values in its units: cone, power:N or
    /// capped-cone:R_OVER_L:HALF_ANGLE_DEG.
    /// Or scene:FILE, the tip of a scene file in the units of its E* and w (any SI tip, a measured
    /// profile among them).
    #[arg(long, conflicts_with_all = ["scene", "preset", "stress_ratio", "range_ratio", "plot"])]
    pub tip: Option<String>,
    /// Sampling points on the uniform part of the r grid (more are added near a and c).
    #[arg(long, default_value_t = 400)]
    pub points: usize,
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Json)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Pressure and gap against r for the four models (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub figure: crate::cli::FigureArgs,
}

pub fn run(a: ProfileArgs) -> anyhow::Result<()> {
    if a.format == Format::Text {
        bail!("--format text is not available for a profile: use json or csv");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    a.figure.check_distinct(
        a.plot.as_deref(),
        "--plot",
        std::iter::once(("--output".to_string(), std::path::PathBuf::from(&a.output))),
    )?;
    let print = a.figure.print("profile")?;
    if let Some(t) = &a.tip {
        return run_tip(&a, super::tip_shape(t)?);
    }
    if let Some((rho, eta)) = super::two_zone_ratios(a.stress_ratio, a.range_ratio)? {
        return run_two_zone(&a, rho, eta, &figure, &print);
    }
    let scene = match (&a.scene, &a.preset) {
        (Some(f), _) => Some(crate::cli::scene::read_scene(f)?),
        (None, Some(p)) => Some(crate::cli::scene::preset_named(p)?),
        _ => None,
    };
    let contact = scene.as_ref().map(crate::scene::contact_of).transpose()?;
    let (lambda, given) = match &contact {
        Some(c) => {
            let f = a
                .load_n
                .context("with a scene, give the load in N: --load-n")?;
            if a.load.is_some() || a.approach.is_some() || a.radius_a.is_some() {
                bail!("with a scene, give the load in N (--load-n), not a normalised value");
            }
            (c.lambda(), Given::Load(f / c.force_scale()))
        }
        None => {
            let l = a
                .lambda
                .context("give --lambda (or a scene: --scene FILE or --preset NAME)")?;
            let g = match (a.load, a.approach, a.radius_a) {
                (Some(p), None, None) => Given::Load(p),
                (None, Some(d), None) => Given::Approach(d),
                (None, None, Some(r)) => Given::Radius(r),
                _ => bail!("give one of --load, --approach or --radius-a"),
            };
            if a.load_n.is_some() {
                bail!("--load-n needs a scene (--scene or --preset)");
            }
            (l, g)
        }
    };
    let mut humid_warnings = Vec::new();
    if let (Some(s), Some(c)) = (&scene, &contact) {
        if let Some(h) = &s.humidity {
            humid_warnings = h.warnings(c.radius);
            if let Some(m) = h.meniscus(c)? {
                return run_wet(&a, c, h, &m, given, &figure, &print);
            }
        }
    }
    let p = profile(lambda, given, a.points);
    if let Err(e @ crate::profile::ProfileError::Points(_)) = &p {
        return Err(super::in_flags(e, &[("points", "--points")]));
    }
    // The library's message names the quantity, as Python's profile() shows it.
    let mut p = p?;
    if let Some(c) = &contact {
        p = p.to_si(c);
    }
    p.warnings.extend(humid_warnings);
    let text = match a.format {
        Format::Csv => profile_csv(&p)?,
        _ => serde_json::to_string_pretty(&p)? + "\n",
    };
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Profile,
        &print,
        &figure,
        &|r| crate::render::plots::profile(r, &p),
    )
    .context("writing the profile")?;
    for w in &p.warnings {
        eprintln!("warning: {w}");
    }
    let md = &p.models[0];
    eprintln!(
        "lambda = {}, load {}: MD contact radius a = {}, cohesive zone to c = {}, J/w = {:.12}",
        crate::solver::domain::short(p.lambda),
        crate::solver::domain::short(md.load),
        md.a.map_or("-".into(), crate::solver::domain::short),
        md.c.map_or("-".into(), crate::solver::domain::short),
        md.energy_release_rate_over_w.unwrap_or(f64::NAN)
    );
    Ok(())
}

/// The normalised state (--load, --approach or --radius-a) of the solid's lambda and a second
/// zone: the same outputs as the MD profile.
fn run_two_zone(
    a: &ProfileArgs,
    rho: f64,
    eta: f64,
    figure: &crate::render::Outputs,
    print: &crate::render::Print,
) -> anyhow::Result<()> {
    use crate::profile::two_zone::{two_zone_profile, TwoZoneProfileError};
    let l = a
        .lambda
        .context("give --lambda (the solid's Maugis parameter)")?;
    if a.load_n.is_some() {
        bail!("--load-n needs a scene (--scene or --preset)");
    }
    let (given, flag) = match (a.load, a.approach, a.radius_a) {
        (Some(p), None, None) => (Given::Load(p), "--load"),
        (None, Some(d), None) => (Given::Approach(d), "--approach"),
        (None, None, Some(r)) => (Given::Radius(r), "--radius-a"),
        _ => bail!("give one of --load, --approach or --radius-a"),
    };
    let p = match two_zone_profile(l, rho, eta, given, a.points) {
        Ok(p) => p,
        Err(e @ TwoZoneProfileError::Points(_)) => {
            return Err(super::in_flags(&e, &[("points", "--points")]))
        }
        Err(e @ TwoZoneProfileError::Zones(_)) => return Err(super::zones_error(e)),
        Err(e) => bail!("{flag}: {e}"),
    };
    write_two_zone(a, &p, figure, print)?;
    let m = &p.models[0];
    eprintln!(
        "lambda = {l} (solid), stress ratio {rho}, range ratio {eta}, load {}: a = {}, zone edges c1 = {}, c2 = {}, J/(w1 + w2) = {:.12}",
        crate::solver::domain::short(m.load),
        m.a.map_or("-".into(), crate::solver::domain::short),
        crate::solver::domain::short(p.zone_edges[0]),
        crate::solver::domain::short(p.zone_edges[1]),
        p.energy_release_rate_over_w
    );
    Ok(())
}

/// A scene with a meniscus: the two-zone profile of solid and meniscus in SI units.
fn run_wet(
    a: &ProfileArgs,
    c: &crate::physics::params::Contact,
    h: &crate::scene::humidity::HumidityInput,
    m: &crate::scene::humidity::Meniscus,
    given: Given,
    figure: &crate::render::Outputs,
    print: &crate::render::Print,
) -> anyhow::Result<()> {
    let (rho, eta, u) = crate::scene::humidity::wet_ratios(c, m)?;
    // The load in the units of the total w.
    let given = match given {
        Given::Load(f) => Given::Load(f * c.force_scale() / u.load),
        g => g,
    };
    let p = crate::profile::two_zone::two_zone_profile(c.lambda(), rho, eta, given, a.points)
        .context("--load-n")?;
    let mut p = p.to_si(&u);
    p.warnings.extend(h.warnings(c.radius));
    write_two_zone(a, &p, figure, print)?;
    // The summary line of a dry scene's profile, for solid and meniscus together.
    let s = &p.models[0];
    let si = crate::solver::domain::short;
    eprintln!(
        "lambda = {} (solid), meniscus lambda = {}, load {} N: contact radius a = {} m, zone edges c1 = {} m (solid), c2 = {} m (meniscus), J/(w1 + w2) = {:.12}",
        si(c.lambda()),
        si(m.lambda),
        si(s.load),
        s.a.map_or("-".into(), si),
        si(p.zone_edges[0]),
        si(p.zone_edges[1]),
        p.energy_release_rate_over_w
    );
    Ok(())
}

/// JSON or CSV, and the plot, of a two-zone profile.
fn write_two_zone(
    a: &ProfileArgs,
    p: &crate::profile::two_zone::TwoZoneProfile,
    figure: &crate::render::Outputs,
    print: &crate::render::Print,
) -> anyhow::Result<()> {
    // The plot and CSV take the models as an MD profile's.
    let as_md = Profile {
        lambda: p.lambda,
        units: p.units,
        dugdale_range: p.zone_range[0],
        dugdale_stress: p.zone_stress[0] + p.zone_stress[1],
        models: p.models.clone(),
        warnings: p.warnings.clone(),
    };
    let text = match a.format {
        Format::Csv => profile_csv(&as_md)?,
        _ => serde_json::to_string_pretty(p)? + "\n",
    };
    super::write_with_figure(
        &a.output,
        text.as_bytes(),
        Kind::Profile,
        print,
        figure,
        &|r| crate::render::plots::profile(r, &as_md),
    )
    .context("writing the profile")?;
    for w in &p.warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// `tabor profile --tip`: a tip state's pressure and gap in its units (JSON, or CSV
/// `r,pressure,gap`).
fn run_tip(a: &ProfileArgs, shape: crate::physics::tip::Shape) -> anyhow::Result<()> {
    use crate::profile::spec::{LawProfile, ProfileSpec};
    let lambda = a.lambda.context("give --lambda with --tip")?;
    let given = match (a.load, a.approach, a.radius_a) {
        (Some(p), None, None) => Given::Load(p),
        (None, Some(d), None) => Given::Approach(d),
        (None, None, Some(r)) => Given::Radius(r),
        _ => bail!("give one of --load, --approach or --radius-a"),
    };
    if a.load_n.is_some() {
        bail!("--load-n needs a scene (--scene or --preset); with --tip give --load");
    }
    let law = crate::law::Tip::new(shape, lambda).context("--lambda")?;
    let spec = ProfileSpec {
        law: crate::law::ContactLaw::Tip(law),
        given,
        points: a.points,
    };
    let p = match spec.run() {
        Ok(LawProfile::Tip(p)) => p,
        Ok(_) => unreachable!("a tip's law gives a tip's profile"),
        Err(e) => return Err(super::in_flags(&e, &[("points", "--points")])),
    };
    let text = match a.format {
        Format::Csv => {
            let mut w = crate::io::csv_writer();
            w.write_record(["r", "pressure", "gap"])?;
            for ((r, q), g) in p.r.iter().zip(&p.pressure).zip(&p.gap) {
                w.write_record([fmt17(*r), q.map_or(String::new(), fmt17), fmt17(*g)])?;
            }
            String::from_utf8(crate::io::csv_finish(w)?)?
        }
        _ => serde_json::to_string_pretty(&p)? + "\n",
    };
    crate::io::write_output(&a.output, text.as_bytes())?;
    match (p.a, p.c, p.energy_release_rate_over_w) {
        (Some(ra), Some(rc), Some(j)) => eprintln!(
            "{}, lambda = {}: contact radius A = {}, Dugdale zone to C = {}, J/w = {j:.12}",
            p.tip,
            crate::solver::domain::short(lambda),
            crate::solver::domain::short(ra),
            crate::solver::domain::short(rc)
        ),
        _ => eprintln!("no contact: the value given is below the pull-off of its control"),
    }
    Ok(())
}

/// One row per model and radius: `model,r,pressure,gap` (pressure empty where singular).
pub fn profile_csv(p: &Profile) -> anyhow::Result<String> {
    let mut w = crate::io::csv_writer();
    w.write_record(["model", "r", "pressure", "gap"])?;
    for m in &p.models {
        for ((r, q), g) in m.r.iter().zip(&m.pressure).zip(&m.gap) {
            w.write_record([
                m.model_name().to_string(),
                fmt17(*r),
                q.map_or(String::new(), fmt17),
                fmt17(*g),
            ])?;
        }
    }
    Ok(String::from_utf8(crate::io::csv_finish(w)?)?)
}
