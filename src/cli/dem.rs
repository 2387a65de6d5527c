//! `tabor dem-law`: the Maugis-Dugdale force-overlap law for particle (DEM) codes, as tables
//! over lambda and overlap, a pair's SI law, or a pair driven under displacement control.

use super::Format;
use crate::dem::{DemLaw, Eval, History, Pair, DEFAULT_OVERLAP_MAX};
use crate::error::Named;
use crate::io::{fmt17, json_num, write_output};
use crate::law::ContactLaw;
use crate::physics::domain::short;
use clap::Args;
use serde_json::json;
use std::fmt::Write as _;

/// Largest number of overlaps each way.
const POINTS_MAX: usize = 1_000_000;

#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct DemLawArgs {
    /// Maugis parameters, comma separated: the normalised law (loads in pi w R, overlaps in
    /// approach units (pi^2 w^2 R / K^2)^(1/3)).
    #[arg(long, value_delimiter = ',', num_args = 1.., required_unless_present = "scene", conflicts_with = "scene")]
    pub lambda: Vec<f64>,
    /// With --range-ratio: a water meniscus beside the solid's zone, its Dugdale stress over the
    /// solid's (the two-zone law of `tabor cycle`; loads and overlaps in the units of the total w).
    #[arg(long, conflicts_with = "scene")]
    pub stress_ratio: Option<f64>,
    /// With --stress-ratio: the meniscus's range over the solid's.
    #[arg(long, conflicts_with = "scene")]
    pub range_ratio: Option<f64>,
    /// A pair of bodies in SI units: a scene file as `tabor scene` takes it (body1 and body2, or
    /// e_star_pa and radius_m; work_of_adhesion_j_m2; s0_pa, h0_m or z0_m; a humidity for a
    /// water meniscus). Overlaps in m, forces in N.
    #[arg(long)]
    pub scene: Option<String>,
    /// Drive the pair under displacement control from --overlap-min to --overlap-max and back
    /// and write `phase,overlap,force` (CSV) at --points overlaps each way.
    #[arg(long)]
    pub drive: bool,
    /// The smallest overlap (negative: a gap) [default: below where the attraction starts].
    #[arg(long)]
    pub overlap_min: Option<f64>,
    /// The largest overlap, also the table's end [default: 10 approach units].
    #[arg(long)]
    pub overlap_max: Option<f64>,
    /// Overlaps each way.
    #[arg(long, default_value_t = 201)]
    pub points: usize,
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[arg(long, short, default_value = "-")]
    pub output: String,
    /// NumPy arrays PREFIX_lambda.npy (n), PREFIX_overlap.npy, PREFIX_approach_load.npy,
    /// PREFIX_retract_load.npy, PREFIX_approach_stiffness.npy, PREFIX_retract_stiffness.npy
    /// (n x points each).
    #[arg(long)]
    pub npy: Option<String>,
}

/// One law and how its numbers are shown: SI (a pair) or normalised.
struct Shown {
    law: DemLaw,
    /// The pair's force and length scales (N, m); None: normalised.
    pair: Option<(f64, f64)>,
    contact: Option<crate::physics::params::Contact>,
    meniscus: Option<crate::scene::humidity::Meniscus>,
    lambda_given: f64,
}

impl Shown {
    fn length(&self) -> f64 {
        self.pair.map_or(1.0, |p| p.1)
    }
    fn force(&self) -> f64 {
        self.pair.map_or(1.0, |p| p.0)
    }
}

fn pair_of(path: &str, overlap_max_m: Option<f64>) -> anyhow::Result<Shown> {
    let s = super::scene::read_scene(path)?;
    let pair = Pair::from_scene(&s, overlap_max_m).map_err(|e| {
        anyhow::anyhow!(
            "{path}: {}",
            e.named(&super::flags(&[("overlap_max_m", "--overlap-max")]))
        )
    })?;
    Ok(Shown {
        lambda_given: pair.law.lambda,
        pair: Some((pair.force_scale, pair.length_scale)),
        contact: Some(pair.contact),
        meniscus: pair.meniscus,
        law: pair.law,
    })
}

/// The overlaps each way, from `lo` to `hi`.
fn overlaps(lo: f64, hi: f64, points: usize) -> Vec<f64> {
    (0..points)
        .map(|k| lo + (hi - lo) * k as f64 / (points - 1) as f64)
        .collect()
}

/// The law's default smallest overlap: a tenth of the attraction's reach below it.
fn default_min(law: &DemLaw) -> f64 {
    let lo = law.lowest_overlap();
    let reach = -law.attraction_from;
    lo - 0.1 * (reach + (lo - law.attraction_from).abs()).max(0.1)
}

pub fn run(a: DemLawArgs) -> anyhow::Result<()> {
    if !(2..=POINTS_MAX).contains(&a.points) {
        anyhow::bail!(
            "--points {} is outside 2..{POINTS_MAX}: give at least two overlaps each way",
            a.points
        );
    }
    for (flag, v) in [
        ("--overlap-min", a.overlap_min),
        ("--overlap-max", a.overlap_max),
    ] {
        if let Some(v) = v {
            if !v.is_finite() {
                anyhow::bail!("{flag} {v} is not a finite number: give an overlap");
            }
        }
    }
    let ratios = super::two_zone_ratios(a.stress_ratio, a.range_ratio)?;
    let laws: Vec<Shown> = match &a.scene {
        Some(path) => vec![pair_of(path, a.overlap_max)?],
        None => a
            .lambda
            .iter()
            .map(|&l| {
                let max = a.overlap_max.unwrap_or(DEFAULT_OVERLAP_MAX);
                DemLaw::of_law(ContactLaw::with_ratios(l, ratios), max)
                    .map(|law| Shown {
                        law,
                        pair: None,
                        contact: None,
                        meniscus: None,
                        lambda_given: l,
                    })
                    .map_err(|e| {
                        anyhow::anyhow!(
                            "--lambda {l}: {}",
                            e.named(&super::flags(&[
                                ("overlap_max", "--overlap-max"),
                                ("stress_ratio", "--stress-ratio"),
                                ("range_ratio", "--range-ratio")
                            ]))
                        )
                    })
            })
            .collect::<anyhow::Result<_>>()?,
    };
    // The cycle of each law: approach, then retract over the same overlaps.
    let mut cycles = Vec::new();
    for s in &laws {
        let unit = s.length();
        let lo = a.overlap_min.map_or(default_min(&s.law), |m| m / unit);
        let hi = s.law.overlap_max;
        if lo >= hi {
            anyhow::bail!(
                "--overlap-min {} is not below the largest overlap {}: give a smaller --overlap-min",
                short(lo * unit),
                short(hi * unit)
            );
        }
        if a.drive && lo >= s.law.attraction_from {
            eprintln!(
                "warning: --overlap-min {} lies inside the attraction's reach (from {}): the drive starts with the pair already attracted, not from apart",
                short(lo * unit),
                short(s.law.attraction_from * unit)
            );
        }
        let xs = overlaps(lo, hi, a.points);
        let mut h = History::NEW;
        let app: Vec<Eval> = xs.iter().map(|&d| s.law.eval(d, &mut h)).collect();
        let ret: Vec<Eval> = xs.iter().rev().map(|&d| s.law.eval(d, &mut h)).collect();
        cycles.push((xs, app, ret));
    }
    if let Some(prefix) = &a.npy {
        write_npy(prefix, &laws, &cycles)?;
    }
    let text = if a.drive {
        drive_text(&laws, &cycles, a.format)?
    } else {
        table_text(&laws, &cycles, a.format)?
    };
    write_output(&a.output, text.as_bytes())
}

fn drive_text(
    laws: &[Shown],
    cycles: &[(Vec<f64>, Vec<Eval>, Vec<Eval>)],
    format: Format,
) -> anyhow::Result<String> {
    let si = laws[0].pair.is_some();
    let (ox, fx) = if si {
        ("overlap_m", "force_n")
    } else {
        ("overlap", "load")
    };
    match format {
        Format::Json => {
            let list: Vec<_> = laws
                .iter()
                .zip(cycles)
                .map(|(s, (xs, app, ret))| {
                    let col = |e: &[Eval]| e.iter().map(|e| json_num(e.load * s.force())).collect::<Vec<_>>();
                    let back: Vec<f64> = xs.iter().rev().map(|x| x * s.length()).collect();
                    json!({
                        "lambda": json_num(s.law.lambda),
                        "approach": {ox: xs.iter().map(|x| json_num(x * s.length())).collect::<Vec<_>>(), fx: col(app)},
                        "retract": {ox: back.into_iter().map(json_num).collect::<Vec<_>>(), fx: col(ret)},
                    })
                })
                .collect();
            Ok(serde_json::to_string_pretty(&json!({ "cycles": list }))? + "\n")
        }
        _ => {
            let mut w = crate::io::csv_writer();
            let many = laws.len() > 1;
            let mut head = vec!["phase", ox, fx];
            if many {
                head.insert(0, "lambda");
            }
            w.write_record(&head)?;
            for (s, (xs, app, ret)) in laws.iter().zip(cycles) {
                let back: Vec<f64> = xs.iter().rev().copied().collect();
                for (phase, x, e) in [("approach", xs, app), ("retract", &back, ret)] {
                    for (d, e) in x.iter().zip(e) {
                        let mut rec = vec![
                            phase.to_string(),
                            fmt17(d * s.length()),
                            fmt17(e.load * s.force()),
                        ];
                        if many {
                            rec.insert(0, fmt17(s.lambda_given));
                        }
                        w.write_record(&rec)?;
                    }
                }
            }
            Ok(String::from_utf8(w.into_inner()?)?)
        }
    }
}

/// The law's name in the text: Maugis-Dugdale, or with the meniscus's ratios.
fn title(law: &DemLaw) -> String {
    match law.law {
        ContactLaw::SolidAndMeniscus(z) => format!(
            "Maugis-Dugdale with a meniscus (stress ratio {}, range ratio {})",
            short(z.stress_ratio),
            short(z.range_ratio)
        ),
        _ => "Maugis-Dugdale".into(),
    }
}

/// The law's marks: where it jumps and folds, in the shown units.
fn marks(s: &Shown) -> serde_json::Value {
    let (l, f) = (s.length(), s.force());
    let law = &s.law;
    let mut m = json!({
        "lambda": json_num(law.lambda),
        "model": law.law.model().label(),
        "attraction_from": json_num(law.attraction_from * l),
        "jump_in": json_num(law.delta_in * l),
        "jump_out": json_num(law.delta_out * l),
        "jump_out_force": json_num(law.disp_pulloff * f),
        "load_control_pulloff_force": json_num(law.load_pulloff * f),
        "non_contact_end": law.delta_nc.map_or(serde_json::Value::Null, |d| json_num(d * l)),
        "loop_energy": law.loop_area(law.overlap_max).map_or(serde_json::Value::Null, |e| json_num(e * f * l)),
        "table": {
            "nodes": law.nodes,
            "step": json_num(law.step),
            "error": json_num(law.error),
            "error_relative_to": "max(|load-controlled pull-off|, |load|), at every interval's midpoint against exact solves",
            "overlap_max": json_num(law.overlap_max * l),
        },
    });
    if let ContactLaw::SolidAndMeniscus(z) = law.law {
        m["stress_ratio"] = json_num(z.stress_ratio);
        m["range_ratio"] = json_num(z.range_ratio);
    }
    if let Some(men) = &s.meniscus {
        m["meniscus"] = serde_json::to_value(men).unwrap_or_default();
    }
    if let Some((fs, ls)) = s.pair {
        m["force_scale_n"] = json_num(fs);
        m["length_scale_m"] = json_num(ls);
    }
    m
}

fn table_text(
    laws: &[Shown],
    cycles: &[(Vec<f64>, Vec<Eval>, Vec<Eval>)],
    format: Format,
) -> anyhow::Result<String> {
    let si = laws[0].pair.is_some();
    let names = if si {
        ("overlap_m", "force_n", "stiffness_n_m")
    } else {
        ("overlap", "load", "stiffness")
    };
    match format {
        Format::Text => Ok(laws.iter().map(|s| law_text(s, si)).collect()),
        Format::Json => table_json(laws, cycles, names),
        Format::Csv => table_csv(laws, cycles, names),
    }
}

/// One law's lines of the text table: its units, its marks along approach and retract, its
/// pull-off, loop and table.
fn law_text(s: &Shown, si: bool) -> String {
    let mut t = String::new();
    let law = &s.law;
    let (l, f) = (s.length(), s.force());
    let (lu, fu) = if si { (" m", " N") } else { ("", "") };
    let _ = writeln!(
        t,
        "{} force-overlap law, lambda = {}{}",
        title(law),
        short(law.lambda),
        if let Some(c) = &s.contact {
            format!(
                " (R = {} m, E* = {} Pa, w = {} J/m^2, s0 = {} Pa; force unit pi w R = {} N, overlap unit {} m{})",
                short(c.radius),
                short(c.e_star),
                short(c.work),
                short(c.s0),
                short(f),
                short(l),
                if s.meniscus.is_some() { ", w the total" } else { "" }
            )
        } else if law.law.model() == crate::physics::model::ContactModel::SolidAndMeniscus {
            " (loads in pi w R, overlaps in (pi^2 w^2 R / K^2)^(1/3), w the total)".into()
        } else {
            " (loads in pi w R, overlaps in (pi^2 w^2 R / K^2)^(1/3))".into()
        }
    );
    if let Some(m) = &s.meniscus {
        let _ = writeln!(
            t,
            "  meniscus: Kelvin radius {} m, Laplace pressure {} Pa over a height of {} m, w {} J/m^2",
            short(m.kelvin_radius_m),
            short(m.laplace_pressure_pa),
            short(m.range_m),
            short(m.work_of_adhesion_j_m2)
        );
    }
    let _ = writeln!(
        t,
        "  approach: attraction from overlap {}{lu}, into contact at {}{lu}",
        short(law.attraction_from * l),
        short(law.delta_in * l)
    );
    let _ = writeln!(
        t,
        "  retract: out of contact at {}{lu} (force {}{fu}){}",
        short(law.delta_out * l),
        short(law.disp_pulloff * f),
        match law.delta_nc {
            Some(nc) => format!(", then across the gap down to {}{lu}", short(nc * l)),
            None => ", then free".into(),
        }
    );
    let _ = writeln!(
        t,
        "  pull-off under load control {}{fu}",
        short(law.load_pulloff * f)
    );
    if let Some(e) = law.loop_area(law.overlap_max) {
        let _ = writeln!(
            t,
            "  energy lost per slow cycle: {}{}",
            short(e * f * l),
            if si {
                " J"
            } else {
                " (pi w R x approach unit)"
            }
        );
    }
    let _ = writeln!(
        t,
        "  table: {} nodes up to overlap {}{lu}; largest measured error {} of max(|pull-off|, |load|)",
        law.nodes,
        short(law.overlap_max * l),
        short(law.error)
    );
    t
}

/// The laws' samples along approach and retract as JSON, with their marks.
fn table_json(
    laws: &[Shown],
    cycles: &[(Vec<f64>, Vec<Eval>, Vec<Eval>)],
    (ox, fx, kx): (&str, &str, &str),
) -> anyhow::Result<String> {
    let list: Vec<_> = laws
        .iter()
        .zip(cycles)
        .map(|(s, (xs, app, ret))| {
            let back: Vec<f64> = xs.iter().rev().copied().collect();
            let half = |x: &[f64], e: &[Eval]| {
                json!({
                    ox: x.iter().map(|v| json_num(v * s.length())).collect::<Vec<_>>(),
                    fx: e.iter().map(|e| json_num(e.load * s.force())).collect::<Vec<_>>(),
                    kx: e.iter().map(|e| json_num(e.stiffness * s.force() / s.length())).collect::<Vec<_>>(),
                    "branch": e.iter().map(|e| e.branch.name()).collect::<Vec<_>>(),
                })
            };
            let mut m = marks(s);
            m["approach"] = half(xs, app);
            m["retract"] = half(&back, ret);
            m
        })
        .collect();
    Ok(serde_json::to_string_pretty(&json!({ "laws": list }))? + "\n")
}

/// The laws' samples along approach and retract as CSV, a row a sample.
fn table_csv(
    laws: &[Shown],
    cycles: &[(Vec<f64>, Vec<Eval>, Vec<Eval>)],
    (ox, fx, kx): (&str, &str, &str),
) -> anyhow::Result<String> {
    let mut w = crate::io::csv_writer();
    w.write_record(["lambda", "phase", ox, fx, kx, "branch"])?;
    for (s, (xs, app, ret)) in laws.iter().zip(cycles) {
        let back: Vec<f64> = xs.iter().rev().copied().collect();
        for (phase, x, e) in [("approach", xs, app), ("retract", &back, ret)] {
            for (d, e) in x.iter().zip(e) {
                w.write_record([
                    fmt17(s.lambda_given),
                    phase.to_string(),
                    fmt17(d * s.length()),
                    fmt17(e.load * s.force()),
                    fmt17(e.stiffness * s.force() / s.length()),
                    e.branch.name().to_string(),
                ])?;
            }
        }
    }
    Ok(String::from_utf8(w.into_inner()?)?)
}

fn write_npy(
    prefix: &str,
    laws: &[Shown],
    cycles: &[(Vec<f64>, Vec<Eval>, Vec<Eval>)],
) -> anyhow::Result<()> {
    use crate::export::npy_write;
    use crate::io::output::Output;
    let names = [
        "lambda",
        "overlap",
        "approach_load",
        "retract_load",
        "approach_stiffness",
        "retract_stiffness",
    ];
    // Every output opened before any is written, put in place only when all are.
    let mut outs = names
        .iter()
        .map(|n| Output::create(format!("{prefix}_{n}.npy")))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let (n, p) = (laws.len() as u64, cycles[0].0.len() as u64);
    let [lam, ov, al, rl, ak, rk] = &mut outs[..] else {
        unreachable!("six outputs")
    };
    npy_write(lam, &[n], laws.iter().map(|s| s.law.lambda))?;
    let each = |f: &dyn Fn(&Shown, &(Vec<f64>, Vec<Eval>, Vec<Eval>)) -> Vec<f64>| {
        laws.iter()
            .zip(cycles)
            .flat_map(|(s, c)| f(s, c))
            .collect::<Vec<f64>>()
    };
    npy_write(
        ov,
        &[n, p],
        each(&|s, c| c.0.iter().map(|x| x * s.length()).collect()).into_iter(),
    )?;
    // The retract is stored at the same overlaps as the approach (ascending).
    npy_write(
        al,
        &[n, p],
        each(&|s, c| c.1.iter().map(|e| e.load * s.force()).collect()).into_iter(),
    )?;
    npy_write(
        rl,
        &[n, p],
        each(&|s, c| c.2.iter().rev().map(|e| e.load * s.force()).collect()).into_iter(),
    )?;
    let k = |s: &Shown| s.force() / s.length();
    npy_write(
        ak,
        &[n, p],
        each(&|s, c| c.1.iter().map(|e| e.stiffness * k(s)).collect()).into_iter(),
    )?;
    npy_write(
        rk,
        &[n, p],
        each(&|s, c| c.2.iter().rev().map(|e| e.stiffness * k(s)).collect()).into_iter(),
    )?;
    for o in outs {
        o.commit()?;
    }
    Ok(())
}
