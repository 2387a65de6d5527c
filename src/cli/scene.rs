//! `tabor scene` and `tabor infer`: real contacts in SI units.

use super::Format;
use crate::io::write_output;
use crate::scene::{infer, preset, solve_scene, SceneInput, SceneResult, PRESETS};
use anyhow::{bail, Context};
use clap::Args;
use std::fmt::Write as _;

#[derive(Args, Debug)]
pub struct SceneArgs {
    /// Scene file (JSON, SI units; see README); `-` is stdin.
    pub file: Option<String>,
    /// A built-in scene: afm-si, pdms-glass, mica-sfa, graphene-mems, hydrogel-titanium.
    #[arg(long, conflicts_with = "file")]
    pub preset: Option<String>,
    /// Override the scene's loads (N), comma separated.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub loads: Option<Vec<f64>>,
    #[arg(long)]
    pub tolerance: Option<f64>,
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// Draw a(P) for the scene and its place on the adhesion map (PNG).
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
}

pub fn scene(a: SceneArgs) -> anyhow::Result<()> {
    let mut input: SceneInput = match (&a.file, &a.preset) {
        (_, Some(p)) => preset(p)
            .with_context(|| format!("no preset {p:?}; the presets are {}", PRESETS.join(", ")))?,
        (Some(f), None) => {
            let text = if f == "-" {
                std::io::read_to_string(std::io::stdin())?
            } else {
                std::fs::read_to_string(f).with_context(|| format!("cannot read {f}"))?
            };
            serde_json::from_str(&text).with_context(|| format!("{f}: not a valid scene (JSON with SI keys, e.g. body1.youngs_modulus_pa; see README)"))?
        }
        (None, None) => bail!("give a scene file or --preset ({})", PRESETS.join(", ")),
    };
    if let Some(l) = &a.loads {
        input.loads_n = Some(l.clone());
        input.load_range_n = None;
    }
    if a.tolerance.is_some() {
        input.tolerance = a.tolerance;
    }
    let r = solve_scene(&input)?;
    let text = match a.format {
        Format::Json => serde_json::to_string_pretty(&r)? + "\n",
        _ => scene_text(&r),
    };
    write_output(&a.output, text.as_bytes())?;
    if let Some(p) = &a.plot {
        crate::render::plots::save(
            Some(p),
            None,
            &|root| crate::render::plots::scene(root, &r),
            &|root| crate::render::plots::scene(root, &r),
        )
        .map_err(|e| anyhow::anyhow!("drawing the scene: {e}"))?;
        eprintln!("wrote {}", p.display());
    }
    Ok(())
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
    ];
    if x == 0.0 || !x.is_finite() {
        return format!("{x} {unit}");
    }
    let (s, p) = prefixes
        .iter()
        .find(|(s, _)| x.abs() >= *s * 0.9995)
        .copied()
        .unwrap_or((1e-12, "p"));
    format!("{:.4} {p}{unit}", x / s)
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
    let _ = writeln!(
        t,
        "  pull-off force: {} (load control), {} (displacement control)",
        si(r.pulloff_force_load_control_N, "N"),
        si(r.pulloff_force_displacement_control_N, "N")
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
pub struct InferArgs {
    /// Measured pull-off force (N).
    #[arg(long, allow_hyphen_values = true)]
    pub pulloff: f64,
    /// Effective radius (m).
    #[arg(long)]
    pub radius: f64,
    /// Reduced modulus E* (Pa).
    #[arg(long)]
    pub e_star: f64,
    /// Lennard-Jones range z0 (m).
    #[arg(long, default_value_t = 0.3e-9)]
    pub z0: f64,
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

pub fn infer_cmd(a: InferArgs) -> anyhow::Result<()> {
    let r = infer(a.pulloff, a.radius, a.e_star, a.z0)?;
    if a.format == Format::Json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!(
        "pull-off force {} with R = {}, E* = {}, z0 = {}",
        si(r.pulloff_force_n, "N"),
        si(a.radius, "m"),
        si(a.e_star, "Pa"),
        si(a.z0, "m")
    );
    println!(
        "  JKR (Fc = 3/2 pi w R): w = {:.4e} J/m^2, Tabor parameter then {:.3}",
        r.w_jkr_j_m2, r.tabor_if_jkr
    );
    println!(
        "  DMT (Fc = 2 pi w R):   w = {:.4e} J/m^2, Tabor parameter then {:.3}",
        r.w_dmt_j_m2, r.tabor_if_dmt
    );
    match (r.w_md_j_m2, r.lambda_md) {
        (Some(w), Some(l)) => {
            println!("  Maugis-Dugdale (w and lambda together): w = {w:.4e} J/m^2, lambda = {l:.4}")
        }
        _ => println!("  Maugis-Dugdale: no solution between the DMT and JKR values"),
    }
    println!("  {}", r.verdict);
    Ok(())
}
