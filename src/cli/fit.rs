//! `tabor fit`: measured force curves in, exact Maugis-Dugdale parameters out.

use super::Format;
use crate::error::Named;
use crate::fit::{self, CurveFit, FitOptions, FitStatus, Segments};
use crate::io::output::write_output;
use anyhow::{bail, Context};
use clap::{Args, ValueEnum};
use rayon::prelude::*;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SegmentArg {
    Retract,
    Approach,
    Both,
}

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct FitArgs {
    /// CSV or TSV with a header (segment, height_m, force_n; optionally curve, or x and y of a
    /// force map), or a NumPy .npz with the same array names; `-` is stdin.
    #[arg(long, short)]
    pub input: String,
    /// Tip radius R (m): a sphere's (or give --tip).
    #[arg(long, required_unless_present = "tip", conflicts_with = "tip")]
    pub radius: Option<f64>,
    /// A tip that is not a sphere (docs/PHYSICS.md section 12), in SI units: cone:HALF_ANGLE_DEG,
    /// pyramid:FACES:FACE_ANGLE_DEG (as its equivalent cone), power:N:B (f = B r^N, B in
    /// m^(1-N)), capped-cone:R_M:HALF_ANGLE_DEG, or a scene's tip object as JSON. The closed
    /// forms are then the tip's: Sneddon's punch (hertz) and the JKR-type law (no DMT).
    #[arg(long)]
    pub tip: Option<crate::physics::tip::TipInput>,
    /// Cantilever spring constant (N/m).
    #[arg(long)]
    pub spring_n_m: f64,
    /// The sample's Poisson ratio: also report its Young's modulus E = E* (1 - nu^2) (rigid tip).
    #[arg(long)]
    pub poisson: Option<f64>,
    /// Which segments to fit.
    #[arg(long, value_enum, default_value_t = SegmentArg::Retract)]
    pub segment: SegmentArg,
    /// Fix lambda through the Lennard-Jones range z0 (m) instead of fitting it.
    #[arg(long)]
    pub z0: Option<f64>,
    /// Remove a tilted baseline (force linear in height), not only an offset.
    #[arg(long)]
    pub tilt: bool,
    /// The adequate model: the simplest whose rms force residual is within this fraction of
    /// Maugis-Dugdale's, or whose contact radius is within it at every fitted point in contact.
    #[arg(long, default_value_t = crate::physics::model::DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    #[arg(long, value_parser = super::formats(&["csv", "json"]), default_value_t = Format::Json)]
    pub format: Format,
    /// One curve's data with the Maugis-Dugdale, Hertz, DMT and JKR fits and the residuals
    /// (.png, .svg or .pdf).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
    /// A force map (curves with x and y): PREFIX_NAME.png (with colorbar) and PREFIX_NAME.npy
    /// for E*, w, lambda, pull-off and rms residual, and PREFIX_adequate_model.png/.npy.
    #[arg(long)]
    pub maps: Option<String>,
    /// Every fitted curve on the adhesion map: its lambda and the loads it spans (.png, .svg or
    /// .pdf).
    #[arg(long)]
    pub on_map: Option<std::path::PathBuf>,
    /// The curve drawn by --plot [default: the first].
    #[arg(long)]
    pub curve: Option<String>,
    /// Relative humidity (0..1) of the air the curves were measured in: each fit also reports
    /// the solid's w with the water meniscus taken out of the fitted pull-off.
    #[arg(long, allow_negative_numbers = true)]
    pub relative_humidity: Option<f64>,
    /// Contact angle of water on the surfaces (degrees), with --relative-humidity.
    #[arg(
        long,
        default_value_t = 0.0,
        requires = "relative_humidity",
        allow_negative_numbers = true
    )]
    pub contact_angle_deg: f64,
    /// Surface tension of the liquid (N/m) [default: 0.072, water], with --relative-humidity.
    #[arg(long, requires = "relative_humidity", allow_negative_numbers = true)]
    pub surface_tension_n_m: Option<f64>,
    /// Molar volume of the liquid (m^3/mol) [default: 1.8e-5, water], with
    /// --relative-humidity.
    #[arg(long, requires = "relative_humidity", allow_negative_numbers = true)]
    pub molar_volume_m3_mol: Option<f64>,
    /// Temperature (K) [default: 298.15], with --relative-humidity.
    #[arg(long, requires = "relative_humidity", allow_negative_numbers = true)]
    pub temperature_k: Option<f64>,
    #[command(flatten)]
    pub figure: super::FigureArgs,
}

pub fn run(a: FitArgs) -> anyhow::Result<()> {
    if a.format == Format::Text {
        bail!("--format text is not available for fit: use json or csv (a summary goes to stderr)");
    }
    let opt = options(&a)?;
    if let (Some(_), Some(_)) = (&a.tip, &a.on_map) {
        bail!("--on-map draws the sphere's adhesion map: a tip's lambda is its own (tabor map --tip draws a shape's map); leave out --on-map");
    }
    let figure = a.figure.outputs(a.plot.as_deref(), "--plot")?;
    check_outputs(&a, &figure)?;
    let print = a.figure.print("fit")?;
    let curves = fit::read_curves(&a.input).with_context(|| "--input".to_string())?;
    if a.maps.is_some() {
        fit::map_size(curves.iter().map(|c| (c.x, c.y, c.id.as_str())))
            .map_err(anyhow::Error::msg)
            .context("--maps")?;
    }
    let plotted = match &a.curve {
        Some(id) => Some(
            curves
                .iter()
                .position(|c| &c.id == id)
                .with_context(|| format!("--curve {id}: no such curve in the input"))?,
        ),
        None => (!figure.is_empty()).then_some(0),
    };
    let results = fit_all(&curves, &opt);
    let text = match a.format {
        Format::Json => fits_json(&a, &opt, &results)?,
        _ => csv_rows(&results, opt.humidity.is_some())?,
    };
    write_output(&a.output, text.as_bytes())?;
    let ok = print_summary(&results, &opt);
    if let Some(i) = plotted {
        let (c, r) = (&curves[i], &results[i]);
        if r.status != FitStatus::Ok {
            bail!("--plot: curve {} was not fitted ({})", c.id, r.message);
        }
        crate::render::plots::save(crate::render::Kind::Fit, &print, &figure, &|root| {
            crate::render::plots::fit(root, c, r, &opt)
        })
        .context("drawing the fit")?;
        eprintln!("wrote the figure of curve {}", c.id);
    }
    if let Some(prefix) = &a.maps {
        write_maps(prefix, &results, &print)?;
    }
    if let Some(path) = &a.on_map {
        let d = crate::figure_data::fit_map_data(&results, a.tolerance)?;
        let out =
            crate::render::Outputs::from_path(path).map_err(|e| anyhow::anyhow!("--on-map {e}"))?;
        crate::render::plots::save(crate::render::Kind::Map, &print, &out, &|root| {
            crate::render::plots::fits_on_map(root, &d, &results)
        })
        .context("drawing the curves on the adhesion map")?;
        eprintln!("wrote {}", path.display());
    }
    if ok == 0 {
        bail!(
            "no curve could be fitted ({}): see the status and message of each",
            results
                .first()
                .map_or("no curves".to_string(), |r| r.message.to_string())
        );
    }
    Ok(())
}

/// Every curve fitted, on all cores, with a progress bar on stderr.
fn fit_all(curves: &[fit::Curve], opt: &FitOptions) -> Vec<CurveFit> {
    let progress = std::sync::Mutex::new(crate::progress::Progress::new(
        "fitting",
        curves.len() as u64,
        "curves",
    ));
    let results: Vec<CurveFit> = curves
        .par_iter()
        .map(|c| {
            let r = fit::fit_curve(c, opt);
            if let Ok(mut p) = progress.lock() {
                p.inc(1);
            }
            r
        })
        .collect();
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    results
}

/// The fits as the JSON document of `tabor fit`: the options they were made with, then the
/// curves.
fn fits_json(a: &FitArgs, opt: &FitOptions, results: &[CurveFit]) -> anyhow::Result<String> {
    #[derive(serde::Serialize)]
    struct Out<'a> {
        #[serde(skip_serializing_if = "Option::is_none")]
        radius_m: Option<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        tip: Option<&'a crate::physics::tip::TipInput>,
        spring_n_m: f64,
        segment: Segments,
        tolerance: f64,
        curves: &'a [CurveFit],
    }
    Ok(serde_json::to_string_pretty(&Out {
        radius_m: a.radius,
        tip: a.tip.as_ref(),
        spring_n_m: a.spring_n_m,
        segment: opt.segments,
        tolerance: a.tolerance,
        curves: results,
    })? + "\n")
}

/// The library's options from the flags, checked by the library.
fn options(a: &FitArgs) -> anyhow::Result<FitOptions> {
    let opt = FitOptions {
        radius: a.radius.unwrap_or(f64::NAN),
        tip: a.tip.clone(),
        spring: a.spring_n_m,
        poisson: a.poisson,
        segments: match a.segment {
            SegmentArg::Retract => Segments::Retract,
            SegmentArg::Approach => Segments::Approach,
            SegmentArg::Both => Segments::Both,
        },
        z0: a.z0,
        tilt: a.tilt,
        tolerance: a.tolerance,
        humidity: a
            .relative_humidity
            .map(|rh| crate::scene::humidity::HumidityInput {
                relative_humidity: rh,
                contact_angle_deg: a.contact_angle_deg,
                surface_tension_n_m: a.surface_tension_n_m,
                molar_volume_m3_mol: a.molar_volume_m3_mol,
                temperature_k: a.temperature_k,
            }),
        ..FitOptions::default()
    }
    .sphere_as_radius();
    // One check of the options, the library's, as Python's fit_curves makes it.
    if let Err(e) = opt.validate() {
        bail!("{}", e.named(&super::flags(FIT_FLAGS)));
    }
    Ok(opt)
}

/// The fit's options as flags.
const FIT_FLAGS: &[(&str, &str)] = &[
    ("spring", "--spring-n-m"),
    ("radius", "--radius"),
    ("tip", "--tip"),
    ("poisson", "--poisson"),
    ("z0", "--z0"),
    ("tolerance", "--tolerance"),
    ("relative_humidity", "--relative-humidity"),
    ("contact_angle_deg", "--contact-angle-deg"),
    ("surface_tension_n_m", "--surface-tension-n-m"),
    ("molar_volume_m3_mol", "--molar-volume-m3-mol"),
    ("temperature_k", "--temperature-k"),
];

/// Every output is distinct and can be written: checked before the fits (which can take
/// minutes), a temporary file made beside each and removed again.
fn check_outputs(a: &FitArgs, figure: &crate::render::Outputs) -> anyhow::Result<()> {
    let mut more = vec![("--output".to_string(), std::path::PathBuf::from(&a.output))];
    if let Some(prefix) = &a.maps {
        for n in fit::MAP_QUANTITIES
            .iter()
            .map(|q| q.name)
            .chain(["adequate_model"])
        {
            for ext in ["npy", "png"] {
                more.push(("--maps".to_string(), format!("{prefix}_{n}.{ext}").into()));
            }
        }
    }
    more.extend(a.on_map.clone().map(|p| ("--on-map".to_string(), p)));
    if let (None, Some(id)) = (&a.plot, &a.curve) {
        bail!("--curve {id} chooses the curve that --plot draws: give --plot FILE too, or leave out --curve");
    }
    if a.plot.is_none() && (a.figure.svg.is_some() || a.figure.pdf.is_some()) {
        bail!("--svg and --pdf add formats to --plot's figure of one curve: give --plot too (the --on-map figure takes its format from its own name)");
    }
    let mut every: Vec<(String, std::path::PathBuf)> = more.clone();
    every.extend(
        [&figure.png, &figure.svg, &figure.pdf]
            .into_iter()
            .flatten()
            .map(|p| ("--plot".to_string(), p.clone())),
    );
    a.figure.check_distinct(a.plot.as_deref(), "--plot", more)?;
    for (flag, path) in every.iter().filter(|(_, p)| p.as_os_str() != "-") {
        drop(crate::io::output::Output::create(path).with_context(|| flag.clone())?);
    }
    Ok(())
}

/// The summary on stderr: how many curves were fitted, the failures, and for one curve its
/// values; returns how many were fitted.
fn print_summary(results: &[CurveFit], opt: &FitOptions) -> usize {
    let ok = results.iter().filter(|r| r.status == FitStatus::Ok).count();
    eprintln!("fitted {ok} of {} curves", results.len());
    for r in results.iter().filter(|r| r.status != FitStatus::Ok).take(5) {
        eprintln!("  curve {}: {}", r.curve, r.message);
    }
    if results.len() == 1 && ok == 1 {
        let r = &results[0];
        // Where the data do not bound lambda, its bound is printed, not a point value.
        let lambda = match (r.lambda_determined(), &r.lambda_bound) {
            (false, Some(b)) => b.clone(),
            _ => format!("lambda = {:.4}", r.lambda.unwrap_or(f64::NAN)),
        };
        let range = |i: Option<[Option<f64>; 2]>| match i {
            Some([Some(lo), Some(hi)]) => format!(" (95%: {lo:.4e}..{hi:.4e})"),
            _ => String::new(),
        };
        eprintln!(
            "  E* = {:.4e} Pa{}, w = {:.4e} J/m^2{}, {lambda}, adequate model: {}",
            r.e_star_pa.unwrap_or(f64::NAN),
            range(r.e_star_pa_interval_95),
            r.work_of_adhesion_j_m2.unwrap_or(f64::NAN),
            range(r.work_of_adhesion_j_m2_interval_95),
            r.adequate_model.map_or("-", |m| m.name())
        );
        if let Some(h) = &r.humidity {
            eprintln!("  {}", humidity_line(h));
        }
        if let Some(w) = &r.dwell {
            eprintln!(
                "  dwell (points {}..{}): force {:.4e} -> {:.4e} N, indentation creep {:.4e} m",
                w.first_point, w.last_point, w.force_start_n, w.force_end_n, w.indentation_creep_m
            );
        }
        // The humidity's note is printed above.
        let said = r.humidity.as_ref().map(|h| format!("humidity: {}", h.note));
        for w in r.warnings.iter().filter(|w| Some(*w) != said.as_ref()) {
            eprintln!("  warning: {w}");
        }
    } else if opt.humidity.is_some() {
        let n = results
            .iter()
            .filter(|r| {
                r.humidity
                    .as_ref()
                    .is_some_and(|h| h.solid_work_of_adhesion_j_m2.is_some())
            })
            .count();
        eprintln!("  the solid's w with the meniscus taken out: {n} of {ok} fitted curves (the others have none: see each curve's humidity.note)");
    }
    ok
}

/// The force maps of `--maps PREFIX`: NPY tables and their PNGs.
fn write_maps(
    prefix: &str,
    results: &[CurveFit],
    print: &crate::render::Print,
) -> anyhow::Result<()> {
    let (nx, ny, grid) = fit::map_grid(results)
        .map_err(anyhow::Error::msg)
        .context("--maps")?;
    let names = crate::export::write_fit_npy(prefix, results, nx, ny, &grid)?;
    // PREFIX_<name>.png, drawn by `draw`.
    let png = |name: &str, kind: crate::render::Kind, draw: crate::render::DrawSvg| {
        let path = format!("{prefix}_{name}.png");
        let out = crate::render::Outputs::from_path(std::path::Path::new(&path))
            .map_err(anyhow::Error::msg)?;
        crate::render::plots::save(kind, print, &out, draw)
            .with_context(|| format!("drawing {path}"))
    };
    let fit_at = |i: &Option<usize>| i.map(|i| &results[i]);
    for q in &fit::MAP_QUANTITIES {
        let values: Vec<f64> = grid
            .iter()
            .map(|i| fit_at(i).and_then(|r| q.shown(r)).unwrap_or(f64::NAN))
            .collect();
        let largest = values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let (scale, si) = if q.prefixed {
            crate::render::si_prefix(largest)
        } else {
            (1.0, "")
        };
        let values: Vec<f64> = values.iter().map(|v| v / scale).collect();
        let title = if q.unit.is_empty() {
            q.label.to_string()
        } else {
            format!("{} ({si}{})", q.label, q.unit)
        };
        png(q.name, crate::render::Kind::ForceMap, &|root| {
            crate::render::plots::force_map(root, &values, nx, ny, &title, q.log)
        })?;
    }
    let models: Vec<Option<fit::Model>> = grid
        .iter()
        .map(|i| {
            fit_at(i)
                .filter(|r| r.status == FitStatus::Ok)
                .and_then(|r| r.adequate_model)
        })
        .collect();
    png("adequate_model", crate::render::Kind::ForceMap, &|root| {
        crate::render::plots::model_map(root, &models, nx, ny)
    })?;
    // Per pixel how its fit ended (the index of PIXEL_STATUSES, as its NPY).
    let statuses: Vec<usize> = grid.iter().map(|i| fit::pixel_status(fit_at(i))).collect();
    png("status", crate::render::Kind::ForceMap, &|root| {
        crate::render::plots::status_map(root, &statuses, nx, ny)
    })?;
    // The map at a glance: statuses, models and each quantity's distribution.
    let summary = fit::summarize_map(results, nx, ny, &grid);
    let json = format!("{prefix}_summary.json");
    let mut out = crate::io::Output::create(&json)?;
    serde_json::to_writer_pretty(&mut out, &summary)?;
    out.commit()?;
    png("histograms", crate::render::Kind::MapHistograms, &|root| {
        crate::render::plots::map_histograms(root, &summary)
    })?;
    eprintln!(
        "wrote the {nx} x {ny} force maps: {}, {json} and their PNGs (with {prefix}_histograms.png)",
        names.join(", ")
    );
    Ok(())
}

/// The humidity of a fitted curve in one line: the meniscus and the solid's w.
fn humidity_line(h: &fit::humidity::FitHumidity) -> String {
    let air = format!(
        "RH = {:.1}%, contact angle {} deg",
        100.0 * h.relative_humidity,
        crate::physics::domain::short(h.contact_angle_deg)
    );
    match &h.meniscus {
        Some(m) => format!(
            "humid air ({air}): meniscus Kelvin radius {:.3e} m, Laplace pressure {:.3e} Pa, range {:.3e} m, w = {:.4e} J/m^2; fitted pull-off (load control) {:.4e} N; {}",
            m.kelvin_radius_m,
            m.laplace_pressure_pa,
            m.range_m,
            m.work_of_adhesion_j_m2,
            h.pulloff_force_load_control_n,
            h.note
        ),
        None => format!("humid air ({air}): {}", h.note),
    }
}

/// The humidity columns of the CSV table.
const HUMIDITY_COLUMNS: [&str; 25] = [
    "relative_humidity",
    "contact_angle_deg",
    "kelvin_radius_m",
    "laplace_pressure_pa",
    "meniscus_range_m",
    "meniscus_work_of_adhesion_j_m2",
    "pulloff_force_load_control_n",
    "meniscus_only_pulloff_n",
    "solid_work_of_adhesion_j_m2",
    "solid_lambda",
    "meniscus_share",
    "meniscus_range_over_fitted_range",
    "fair_reading",
    "humidity_note",
    "shape_fit_status",
    "shape_e_star_pa",
    "shape_solid_work_of_adhesion_j_m2",
    "shape_solid_lambda",
    "shape_solid_z0_m",
    "shape_rms_residual_n",
    "shape_lambda_95_low",
    "shape_lambda_95_high",
    "shape_lambda_bounded",
    "shape_solid_w_95_low",
    "shape_solid_w_95_high",
];

/// A fit status as JSON names it.
fn status_name(s: fit::FitStatus) -> String {
    serde_json::to_value(s)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

fn humidity_cells(h: Option<&fit::humidity::FitHumidity>) -> Vec<String> {
    let f = |x: Option<f64>| x.map_or(String::new(), crate::io::fmt17);
    let Some(h) = h else {
        return vec![String::new(); HUMIDITY_COLUMNS.len()];
    };
    let m = h.meniscus.as_ref();
    let mut cells = vec![
        f(Some(h.relative_humidity)),
        f(Some(h.contact_angle_deg)),
        f(m.map(|m| m.kelvin_radius_m)),
        f(m.map(|m| m.laplace_pressure_pa)),
        f(m.map(|m| m.range_m)),
        f(m.map(|m| m.work_of_adhesion_j_m2)),
        f(Some(h.pulloff_force_load_control_n).filter(|v| v.is_finite())),
        f(h.meniscus_only_pulloff_n),
        f(h.solid_work_of_adhesion_j_m2),
        f(h.solid_lambda),
        f(h.meniscus_share),
        f(h.meniscus_range_over_fitted_range),
        h.fair_reading.to_string(),
        h.note.clone(),
    ];
    let sf = h.shape_fit.as_ref();
    let fit = sf.map(|s| &s.fit);
    let end = |k: usize, r: Option<[f64; 2]>| f(r.map(|r| r[k]));
    cells.extend([
        fit.map_or(String::new(), |f| status_name(f.status)),
        f(fit.map(|f| f.e_star_pa)),
        f(fit.map(|f| f.work_of_adhesion_j_m2)),
        f(fit.and_then(|f| f.lambda)),
        f(sf.map(|s| s.z0_m)),
        f(fit.map(|f| f.rms_residual_n)),
        end(0, sf.and_then(|s| s.lambda_95)),
        end(1, sf.and_then(|s| s.lambda_95)),
        sf.and_then(|s| s.lambda_bounded)
            .map_or(String::new(), |b| b.to_string()),
        end(0, sf.and_then(|s| s.solid_w_95)),
        end(1, sf.and_then(|s| s.solid_w_95)),
    ]);
    cells
}

/// The dwell's columns, written where any curve has a dwell between approach and retract.
const DWELL_COLUMNS: [&str; 8] = [
    "dwell_first_point",
    "dwell_last_point",
    "dwell_force_start_n",
    "dwell_force_end_n",
    "dwell_relaxation",
    "dwell_base_advance_m",
    "dwell_indentation_creep_m",
    "dwell_relaxed",
];

fn dwell_cells(w: Option<&fit::DwellReport>) -> Vec<String> {
    let Some(w) = w else {
        return vec![String::new(); DWELL_COLUMNS.len()];
    };
    let f = |x: f64| format!("{x:.10e}");
    vec![
        w.first_point.to_string(),
        w.last_point.to_string(),
        f(w.force_start_n),
        f(w.force_end_n),
        w.relaxation.map_or(String::new(), f),
        f(w.base_advance_m),
        f(w.indentation_creep_m),
        w.relaxed.to_string(),
    ]
}

fn csv_rows(results: &[CurveFit], humid: bool) -> anyhow::Result<String> {
    let dwell = results.iter().any(|r| r.dwell.is_some());
    let mut w = crate::io::csv_writer();
    let mut header = vec![
        "curve",
        "x",
        "y",
        "status",
        "e_star_pa",
        "e_star_pa_stderr",
        "work_of_adhesion_j_m2",
        "work_of_adhesion_j_m2_stderr",
        "lambda",
        "lambda_stderr",
        "e_star_pa_95_low",
        "e_star_pa_95_high",
        "work_of_adhesion_j_m2_95_low",
        "work_of_adhesion_j_m2_95_high",
        "lambda_95_low",
        "lambda_95_high",
        "lambda_determined",
        "tabor_parameter",
        "z0_m",
        "contact_point_m",
        "force_offset_n",
        "rms_residual_n",
        "pulloff_force_measured_n",
        "pulloff_force_model_n",
        "max_load_n",
        "rms_hertz_n",
        "rms_dmt_n",
        "rms_jkr_n",
        "adequate_model",
        "iterations",
        "warnings",
        "message",
    ];
    if humid {
        header.extend(HUMIDITY_COLUMNS);
    }
    if dwell {
        header.extend(DWELL_COLUMNS);
    }
    w.write_record(&header)?;
    let f = |x: Option<f64>| x.map_or(String::new(), crate::io::fmt17);
    for r in results {
        let rms = |m: fit::Model| {
            f(r.models
                .iter()
                .find(|x| x.model == m)
                .map(|x| x.rms_residual_n))
        };
        let mut row = vec![
            r.curve.clone(),
            r.x.map_or(String::new(), |v| v.to_string()),
            r.y.map_or(String::new(), |v| v.to_string()),
            status_name(r.status),
            f(r.e_star_pa),
            f(r.e_star_pa_stderr),
            f(r.work_of_adhesion_j_m2),
            f(r.work_of_adhesion_j_m2_stderr),
            f(r.lambda),
            f(r.lambda_stderr),
            f(r.e_star_pa_interval_95.and_then(|i| i[0])),
            f(r.e_star_pa_interval_95.and_then(|i| i[1])),
            f(r.work_of_adhesion_j_m2_interval_95.and_then(|i| i[0])),
            f(r.work_of_adhesion_j_m2_interval_95.and_then(|i| i[1])),
            f(r.lambda_interval_95.and_then(|i| i[0])),
            f(r.lambda_interval_95.and_then(|i| i[1])),
            r.lambda_determined.map_or(String::new(), |d| d.to_string()),
            f(r.tabor_parameter),
            f(r.z0_m),
            f(r.contact_point_m),
            f(r.force_offset_n),
            f(r.rms_residual_n),
            f(r.pulloff_force_measured_n),
            f(r.pulloff_force_model_n),
            f(r.max_load_n),
            rms(fit::Model::Hertz),
            rms(fit::Model::Dmt),
            rms(fit::Model::Jkr),
            r.adequate_model.map_or("", |m| m.name()).to_string(),
            r.iterations.to_string(),
            r.warnings.join("; "),
            r.message.to_string(),
        ];
        if humid {
            row.extend(humidity_cells(r.humidity.as_ref()));
        }
        if dwell {
            row.extend(dwell_cells(r.dwell.as_ref()));
        }
        w.write_record(&row)?;
    }
    Ok(String::from_utf8(crate::io::csv_finish(w)?)?)
}
