//! Explicit ensembles of summits in SI units: each summit its own height and radius, and so its
//! own lambda, stepped through an approach and a retract on its own branch (docs/PHYSICS.md
//! section 9). Summits come from a list (`height_m,radius_m`) or from a measured height map
//! (local maxima, radius from the curvature there, as Greenwood and Williamson did).
//!
//! Memory is the summits (two numbers each) and one accumulator per separation and thread: each
//! summit is taken once, its own context built, and its load at every separation added in.

mod device;

use super::lambda_table::LambdaTables;
use super::{RoughError, Summit, SummitBranch};
use crate::engine::{CheckReport, Engine};
use crate::error::Message;
use crate::physics::domain::{short, DomainError, APPROACH_MAX};
use crate::physics::params::{Contact, ForceRange};
use serde::Serialize;
use std::f64::consts::PI;

/// Most summits an ensemble may hold (16 bytes each).
pub const SUMMITS_MAX: usize = 20_000_000;
/// Most separations of a cycle.
pub const POINTS_MAX: usize = 10_000;

/// One summit: its height above the reference plane and its radius (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Asperity {
    /// Height above the reference plane (m).
    pub height_m: f64,
    /// Radius of curvature (m).
    pub radius_m: f64,
}

/// The materials every summit shares.
#[derive(Clone, Copy, Debug)]
pub struct Materials {
    /// Effective modulus (Pa).
    pub e_star_pa: f64,
    /// Work of adhesion (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// The range of the surface force (z0, s0 or h0).
    pub range: ForceRange,
}

/// One half of an ensemble's cycle, one entry per separation.
#[derive(Clone, Debug, Default, Serialize)]
pub struct EnsembleLeg {
    /// Separation of the flat from the reference plane (m).
    pub separation_m: Vec<f64>,
    /// Total force (N, compressive positive).
    pub force_n: Vec<f64>,
    /// Real contact area, pi a^2 summed over the summits in contact (m^2).
    pub real_contact_area_m2: Vec<f64>,
    /// Fraction of the summits in contact.
    pub contact_fraction: Vec<f64>,
    /// Fraction of the summits with a Dugdale zone only.
    pub noncontact_fraction: Vec<f64>,
}

/// An explicit ensemble's approach-retract cycle.
#[derive(Clone, Debug, Serialize)]
pub struct EnsembleCycle {
    /// The number of summits.
    pub summits: usize,
    /// The approach, from the largest separation down.
    pub approach: EnsembleLeg,
    /// The retract, back up.
    pub retract: EnsembleLeg,
    /// The most tensile retract force (N), searched beyond the reported separations: the
    /// least of them, refined between its neighbours to 1e-13 of the cycle's span.
    pub pulloff_force_n: f64,
    /// The separation of that pull-off (m).
    pub pulloff_separation_m: f64,
    /// Summit states evaluated (summits times separations times two), and the seconds it took.
    pub summit_states: u64,
    /// Seconds the cycle took.
    pub seconds: f64,
    /// How the summits' contact states were found: `exact`, or `tables (BACKEND)`.
    pub summit_solver: String,
    /// With tables: their largest measured interpolation error, relative to max(1, |value|)
    /// per summit (loads in pi w R, contact radii in the summit's radius unit).
    pub table_error: Option<f64>,
    /// With tables solved on a GPU: their states against the CPU f64 solver on a sample.
    pub table_check: Option<CheckReport>,
}

fn bad(name: &'static str, value: f64, range: &'static str, hint: &'static str) -> RoughError {
    DomainError {
        name,
        value,
        range,
        hint,
    }
    .into()
}

/// Checks a list of summits: finite heights, positive finite radii, at least one, at most
/// [`SUMMITS_MAX`].
pub fn check(asp: &[Asperity]) -> Result<(), RoughError> {
    if asp.is_empty() || asp.len() > SUMMITS_MAX {
        return Err(bad(
            "the number of summits",
            asp.len() as f64,
            "1..2e7",
            "give at least one summit, and at most 20 million",
        ));
    }
    for a in asp {
        if !a.height_m.is_finite() {
            return Err(bad(
                "a summit height (m)",
                a.height_m,
                "finite",
                "remove or fix it",
            ));
        }
        if !(a.radius_m.is_finite() && a.radius_m > 0.0) {
            return Err(bad(
                "a summit radius (m)",
                a.radius_m,
                "(0, inf)",
                "every summit needs a positive, finite radius",
            ));
        }
    }
    Ok(())
}

/// The separations of a cycle: from above the highest summit's reach down to `d_min` (m).
fn separations(
    asp: &[Asperity],
    m: &Materials,
    d_min: f64,
    d_max: Option<f64>,
    points: usize,
) -> Result<Vec<f64>, RoughError> {
    check_points(points)?;
    let top = asp
        .iter()
        .map(|a| a.height_m)
        .fold(f64::NEG_INFINITY, f64::max);
    // A summit is free again beyond its reach (the Dugdale range, or its jump-out); three times
    // the largest summit's Dugdale range plus an approach unit is beyond every summit's.
    let r_max = asp.iter().map(|a| a.radius_m).fold(0.0, f64::max);
    let c = Contact::new(r_max, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
        .map_err(|e| RoughError::Scene(e.to_string().into()))?;
    let reach = 3.0 * (c.work / c.s0) + 2.0 * c.approach_scale();
    let d_max = d_max.unwrap_or(top + reach);
    if !(d_min.is_finite() && d_max.is_finite() && d_max > d_min) {
        return Err(bad(
            "min_separation_m",
            d_min,
            "below the largest separation",
            "give a smallest separation below the highest summit's reach",
        ));
    }
    check_depth(asp, m, d_min)?;
    Ok((0..points)
        .map(|i| d_max + (d_min - d_max) * i as f64 / (points - 1) as f64)
        .collect())
}

/// Every summit pressed at most [`APPROACH_MAX`] of its own approach units at `d_min`: the
/// summit solver's domain (a deeper press was a failure at a NaN separation).
fn check_depth(asp: &[Asperity], m: &Materials, d_min: f64) -> Result<(), RoughError> {
    let mut floor = f64::NEG_INFINITY;
    for a in asp {
        let c = Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
            .map_err(|e| RoughError::Scene(e.to_string().into()))?;
        floor = floor.max(a.height_m - APPROACH_MAX * c.approach_scale());
    }
    if d_min >= floor {
        return Ok(());
    }
    Err(RoughError::Scene(
        Message::new()
            .key("min_separation_m")
            .text(format!(
                " = {} m presses a summit more than {APPROACH_MAX:e} of its approach units (pi^2 w^2 R/K^2)^(1/3) deep, beyond what the summit solver takes: give ",
                short(d_min)
            ))
            .key("min_separation_m")
            .text(format!(" of at least {} m", short(floor))),
    ))
}

/// Sums per separation: force, area, contact and non-contact counts, for approach and retract.
#[derive(Clone)]
struct Sums {
    v: Vec<[f64; 8]>,
}

impl Sums {
    fn new(n: usize) -> Sums {
        Sums {
            v: vec![[0.0; 8]; n],
        }
    }
    fn add(mut self, o: Sums) -> Sums {
        for (a, b) in self.v.iter_mut().zip(o.v) {
            for k in 0..8 {
                a[k] += b[k];
            }
        }
        self
    }
}

/// How each summit's contact states are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SummitSolver {
    /// The exact root search at every summit state.
    Exact,
    /// Tables over the ensemble's lambdas ([`LambdaTables`]), solved on an engine, with the
    /// error measured; exact next to each fold.
    Tables,
}

impl std::str::FromStr for SummitSolver {
    type Err = RoughError;
    fn from_str(s: &str) -> Result<Self, RoughError> {
        match s {
            "tables" => Ok(SummitSolver::Tables),
            "exact" => Ok(SummitSolver::Exact),
            _ => Err(RoughError::Scene(
                format!("summits {s:?} is not a summit solver: give tables or exact").into(),
            )),
        }
    }
}

/// Adds one summit's force, contact area and branch counts at every separation, approach and
/// retract.
fn add_summit(
    acc: &mut Sums,
    a: &Asperity,
    m: &Materials,
    seps: &[f64],
    d_min: f64,
    tables: Option<&LambdaTables>,
    retract_only: bool,
) -> Result<(), RoughError> {
    crate::interrupt::checkpoint();
    let c = Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
        .map_err(|e| RoughError::Scene(e.to_string().into()))?;
    let s = Summit::new(c.lambda())?;
    let stencil = tables.map(|t| t.stencil(s.lambda));
    let contact = |delta: f64| match (tables, &stencil) {
        (Some(t), Some(st)) => t.contact(&s, st, delta),
        _ => s.contact(delta),
    };
    let (unit, force, r_unit) = (c.approach_scale(), c.force_scale(), c.radius_scale());
    let delta_max = (a.height_m - d_min) / unit;
    for (k, &d) in seps.iter().enumerate() {
        let delta = (a.height_m - d) / unit;
        let approach = (!retract_only).then(|| (0, s.approach_branch(delta)));
        for (leg, b) in approach
            .into_iter()
            .chain([(4, s.retract_branch(delta, delta_max))])
        {
            let slot = &mut acc.v[k];
            match b {
                SummitBranch::Free => {}
                SummitBranch::NonContact => {
                    slot[leg] += s.non_contact(delta) * force;
                    slot[leg + 3] += 1.0;
                }
                SummitBranch::Contact => {
                    let (p, ar) = contact(delta).ok_or(RoughError::Failed(d, s.lambda))?;
                    slot[leg] += p * force;
                    slot[leg + 1] += PI * (ar * r_unit).powi(2);
                    slot[leg + 2] += 1.0;
                }
            }
        }
    }
    Ok(())
}

/// Every summit's force, area and branch counts summed at each separation (the retract's
/// alone with `retract_only`), on all cores. Fixed chunks summed in order: the same bytes
/// whatever the threads' schedule.
fn sum_summits(
    asp: &[Asperity],
    m: &Materials,
    seps: &[f64],
    d_min: f64,
    tables: Option<&LambdaTables>,
    retract_only: bool,
) -> Result<Sums, RoughError> {
    use rayon::prelude::*;
    let n = seps.len();
    let chunk = (asp.len() / 64).max(1024);
    let parts: Vec<Sums> = asp
        .par_chunks(chunk)
        .map(|part| -> Result<Sums, RoughError> {
            let mut acc = Sums::new(n);
            for a in part {
                add_summit(&mut acc, a, m, seps, d_min, tables, retract_only)?;
            }
            Ok(acc)
        })
        .collect::<Result<_, _>>()?;
    Ok(parts.into_iter().fold(Sums::new(n), Sums::add))
}

/// Separations of each refining pass of an ensemble's pull-off, and the most passes.
const REFINE_POINTS: usize = 65;
const REFINE_PASSES: usize = 6;

/// The most tensile retract force and its separation: the least sample of the retract, then
/// passes of [`REFINE_POINTS`] separations between the neighbours of the least so far, until
/// the bracket is 1e-13 of the cycle's span. The force jumps up wherever a summit jumps out,
/// so the minimum is often the limit just before a jump: the search closes in on it from the
/// side where it is attained.
fn pulloff(
    retract: &EnsembleLeg,
    d_min: f64,
    sum: &dyn Fn(&[f64], bool) -> Result<Sums, RoughError>,
) -> Result<(f64, f64), RoughError> {
    let mut pts: Vec<(f64, f64)> = retract
        .separation_m
        .iter()
        .copied()
        .zip(retract.force_n.iter().copied())
        .collect();
    let span = pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max) - d_min;
    let mut best = (f64::NAN, f64::INFINITY);
    for _ in 0..=REFINE_PASSES {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let Some(i) = (0..pts.len()).min_by(|&a, &b| pts[a].1.total_cmp(&pts[b].1)) else {
            break;
        };
        if pts[i].1 < best.1 {
            best = pts[i];
        }
        let (lo, hi) = (
            pts[i.saturating_sub(1)].0,
            pts[(i + 1).min(pts.len() - 1)].0,
        );
        if !(hi - lo > 1e-13 * span) {
            break;
        }
        let seps: Vec<f64> = (0..REFINE_POINTS)
            .map(|k| lo + (hi - lo) * k as f64 / (REFINE_POINTS - 1) as f64)
            .collect();
        let sums = sum(&seps, true)?;
        pts = seps.into_iter().zip(sums.v.iter().map(|v| v[4])).collect();
    }
    Ok(best)
}

/// The tables an ensemble's summits need: their lambdas' range, and approaches up to the
/// deepest any summit reaches beyond its fold.
fn tables_for(
    asp: &[Asperity],
    m: &Materials,
    d_min: f64,
    engine: &Engine,
) -> Result<LambdaTables, RoughError> {
    let (mut lo, mut hi, mut delta_max) = (f64::INFINITY, 0f64, f64::NEG_INFINITY);
    for a in asp {
        let c = Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
            .map_err(|e| RoughError::Scene(e.to_string().into()))?;
        let l = c.lambda();
        lo = lo.min(l);
        hi = hi.max(l);
        delta_max = delta_max.max((a.height_m - d_min) / c.approach_scale());
    }
    LambdaTables::new(lo, hi, delta_max, engine)
}

/// Steps every summit through the approach from the largest separation down to `d_min` and
/// the retract back; separations in m from the reference plane of the heights. Every summit
/// state is solved exactly, on the CPU.
pub fn cycle(
    asp: &[Asperity],
    m: &Materials,
    d_min: f64,
    d_max: Option<f64>,
    points: usize,
) -> Result<EnsembleCycle, RoughError> {
    cycle_with(
        asp,
        m,
        d_min,
        d_max,
        points,
        SummitSolver::Exact,
        &Engine::Cpu,
    )
}

/// As [`cycle`], each summit's contact states found by `solver`; with
/// [`SummitSolver::Tables`] the tables are solved on `engine` (the summits' stepping is on
/// the CPU, a few cubic evaluations per state).
pub fn cycle_with(
    asp: &[Asperity],
    m: &Materials,
    d_min: f64,
    d_max: Option<f64>,
    points: usize,
    solver: SummitSolver,
    engine: &Engine,
) -> Result<EnsembleCycle, RoughError> {
    check(asp)?;
    let seps = separations(asp, m, d_min, d_max, points)?;
    let t = std::time::Instant::now();
    let tables = match solver {
        SummitSolver::Exact => None,
        SummitSolver::Tables => Some(tables_for(asp, m, d_min, engine)?),
    };
    run_cycle(asp, m, d_min, &seps, tables, engine, t)
}

/// As [`cycle_with`] with tables, these tables (whose exact stretch next to each fold a test may
/// widen); `engine` steps the summits where it is a GPU with f64 shaders.
pub fn cycle_with_tables(
    asp: &[Asperity],
    m: &Materials,
    (d_min, d_max): (f64, Option<f64>),
    points: usize,
    tables: LambdaTables,
    engine: &Engine,
) -> Result<EnsembleCycle, RoughError> {
    check(asp)?;
    let seps = separations(asp, m, d_min, d_max, points)?;
    run_cycle(
        asp,
        m,
        d_min,
        &seps,
        Some(tables),
        engine,
        std::time::Instant::now(),
    )
}

/// The cycle at separations `seps`, with `tables` or exact, from `t`.
fn run_cycle(
    asp: &[Asperity],
    m: &Materials,
    d_min: f64,
    seps: &[f64],
    tables: Option<LambdaTables>,
    engine: &Engine,
    t: std::time::Instant,
) -> Result<EnsembleCycle, RoughError> {
    let n = seps.len();
    // With tables on a GPU with f64 shaders the summits are stepped there.
    let device = match (&tables, engine.gpu_f64()) {
        (Some(t), Some(g)) => device::OnDevice::new(g, asp, m, d_min, t)?,
        _ => None,
    };
    let sum = |seps: &[f64], retract_only| match &device {
        Some(dev) => dev.sums(asp, m, seps, retract_only),
        None => sum_summits(asp, m, seps, d_min, tables.as_ref(), retract_only),
    };
    let sums = sum(seps, false)?;
    let total = asp.len() as f64;
    let leg = |off: usize, order: &mut dyn Iterator<Item = usize>| {
        let mut l = EnsembleLeg::default();
        for k in order {
            let v = &sums.v[k];
            l.separation_m.push(seps[k]);
            l.force_n.push(v[off]);
            l.real_contact_area_m2.push(v[off + 1]);
            l.contact_fraction.push(v[off + 2] / total);
            l.noncontact_fraction.push(v[off + 3] / total);
        }
        l
    };
    let approach = leg(0, &mut (0..n));
    let retract = leg(4, &mut (0..n).rev());
    let (pulloff_separation_m, pulloff_force_n) = pulloff(&retract, d_min, &sum)?;
    Ok(EnsembleCycle {
        summits: asp.len(),
        pulloff_force_n,
        pulloff_separation_m,
        approach,
        retract,
        summit_states: 2 * (asp.len() * n) as u64,
        summit_solver: match (&tables, &device) {
            (None, _) => "exact".to_string(),
            (Some(t), None) => format!("tables ({})", t.backend),
            (Some(t), Some(_)) => format!("tables ({}), stepped on the gpu in f64", t.backend),
        },
        table_error: tables.as_ref().map(|t| t.error),
        table_check: tables.and_then(|t| t.check),
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// Explicit ensembles' summits are dry Maugis-Dugdale spheres: a scene's meniscus silently left
/// out would change the pull-off by orders of magnitude without a word.
fn dry_scene(scene: &super::scene::RoughScene) -> Result<(), RoughError> {
    if scene.humidity.is_some() {
        return Err(RoughError::Scene(
            "the scene's \"humidity\" is not modelled for an explicit ensemble (--asperities, --topography; Python's rough_asperities, rough_topography): its summits are dry. Remove \"humidity\" for the dry ensemble, or drop the ensemble for the statistical model, whose summits carry the meniscus".into()
        ));
    }
    Ok(())
}

/// An ensemble's cycle with a rough scene's materials (its summit radius, density, sigma and
/// nominal area are not used: the summits are given). The smallest separation is
/// `min_separation_m` (from the heights' reference plane) where given, else the scene's
/// `min_separation_m` from the mean summit height (as for a Gaussian scene), else the mean
/// summit height less three standard deviations.
pub fn scene_cycle(
    scene: &super::scene::RoughScene,
    asp: &[Asperity],
    min_separation_m: Option<f64>,
    points: usize,
    solver: SummitSolver,
    engine: &Engine,
) -> Result<EnsembleCycle, RoughError> {
    check(asp)?;
    dry_scene(scene)?;
    let c = scene.summit()?;
    let m = Materials {
        e_star_pa: c.e_star,
        work_of_adhesion_j_m2: c.work,
        range: ForceRange::DugdaleStress(c.s0),
    };
    let n = asp.len() as f64;
    let mean = asp.iter().map(|s| s.height_m).sum::<f64>() / n;
    let sd = (asp.iter().map(|s| (s.height_m - mean).powi(2)).sum::<f64>() / n).sqrt();
    // The scene's own key is measured from the mean summit plane, as for a Gaussian scene; an
    // explicit separation (from the heights' reference plane) overrides it.
    let d_min = match (min_separation_m, scene.min_separation_m) {
        (Some(d), _) => d,
        (None, Some(from_mean)) => {
            return cycle_with(asp, &m, mean + from_mean, None, points, solver, engine).map_err(
                |e| {
                    RoughError::Scene(format!(
                        "{e} (the scene's min_separation_m = {} m, measured from the mean summit height {} m)",
                        short(from_mean),
                        short(mean)
                    ).into())
                },
            )
        }
        (None, None) => mean - 3.0 * sd,
    };
    cycle_with(asp, &m, d_min, None, points, solver, engine)
}

/// An explicit ensemble's cycle with a rough scene's materials: the options of `tabor rough
/// --asperities/--topography` and of Python's `rough_asperities`/`rough_topography`, which
/// only parse them.
#[derive(Clone, Copy, Debug)]
pub struct EnsembleSpec {
    /// The smallest separation (m from the heights' reference plane); None: the scene's
    /// `min_separation_m` from the mean summit height, or without one the mean summit height
    /// less three standard deviations.
    pub min_separation_m: Option<f64>,
    /// Separations each way.
    pub points: usize,
    /// How each summit's states are found.
    pub solver: SummitSolver,
}

impl EnsembleSpec {
    /// Checks the options and the scene, before any engine is chosen: the number of
    /// separations, the smallest separation where one is given, and a dry scene.
    pub fn validate(&self, scene: &super::scene::RoughScene) -> Result<(), RoughError> {
        dry_scene(scene)?;
        check_points(self.points)?;
        match self.min_separation_m {
            Some(d) if !d.is_finite() => Err(bad(
                "min_separation_m",
                d,
                "finite",
                "give a finite separation, or none for three standard deviations below the mean height",
            )),
            _ => Ok(()),
        }
    }

    /// The cycle of `asp` with `scene`'s materials, the tables (if any) solved on `engine`.
    pub fn run(
        &self,
        scene: &super::scene::RoughScene,
        asp: &[Asperity],
        engine: &Engine,
    ) -> Result<EnsembleCycle, RoughError> {
        self.validate(scene)?;
        scene_cycle(
            scene,
            asp,
            self.min_separation_m,
            self.points,
            self.solver,
            engine,
        )
    }
}

/// The number of separations each way: 2..=[`POINTS_MAX`].
fn check_points(points: usize) -> Result<(), RoughError> {
    if !(2..=POINTS_MAX).contains(&points) {
        return Err(bad(
            "the number of separations",
            points as f64,
            "2..10000",
            "give at least 2 points",
        ));
    }
    Ok(())
}

/// Summits from parallel arrays of heights and radii (m), checked ([`check`]).
pub fn asperities(heights_m: &[f64], radii_m: &[f64]) -> Result<Vec<Asperity>, RoughError> {
    if heights_m.len() != radii_m.len() {
        return Err(RoughError::Scene(
            format!(
                "{} heights and {} radii: give one radius per summit",
                heights_m.len(),
                radii_m.len()
            )
            .into(),
        ));
    }
    let asp: Vec<Asperity> = heights_m
        .iter()
        .zip(radii_m)
        .map(|(&height_m, &radius_m)| Asperity { height_m, radius_m })
        .collect();
    check(&asp)?;
    Ok(asp)
}

/// The summits of a measured height map ([`summits_of_topography`]), refusing a map with none.
pub fn topography_summits(z: &[f64], nx: usize, pixel_m: f64) -> Result<Vec<Asperity>, RoughError> {
    let asp = summits_of_topography(z, nx, pixel_m)?;
    if asp.is_empty() {
        return Err(RoughError::Scene(
            "the height map has no summit (no pixel above its eight neighbours with a positive curvature)"
                .into()
        ));
    }
    check(&asp)?;
    Ok(asp)
}

/// Summits of a measured height map (rows of `nx` heights in m, pixel `pixel_m` apart): every
/// pixel higher than its eight neighbours, with the radius from the mean curvature there
/// (`1/R = -(z_xx + z_yy) / 2` by central differences), as Greenwood and Williamson did.
/// Border pixels are not summits; a maximum with no curvature (a plateau) is skipped.
pub fn summits_of_topography(
    z: &[f64],
    nx: usize,
    pixel_m: f64,
) -> Result<Vec<Asperity>, RoughError> {
    if !(pixel_m.is_finite() && pixel_m > 0.0) {
        return Err(bad(
            "the pixel size (m)",
            pixel_m,
            "(0, inf)",
            "give the height map's pixel spacing in m",
        ));
    }
    if nx < 3 || z.len() < 3 * nx || !z.len().is_multiple_of(nx) {
        return Err(bad(
            "the height map's size",
            z.len() as f64,
            "at least 3 x 3 pixels, whole rows",
            "give a 2-D array of heights",
        ));
    }
    if let Some(v) = z.iter().find(|v| !v.is_finite()) {
        return Err(bad(
            "a height of the map (m)",
            *v,
            "finite",
            "fill or crop the missing pixels first",
        ));
    }
    let ny = z.len() / nx;
    let at = |x: usize, y: usize| z[y * nx + x];
    let mut out = Vec::new();
    for y in 1..ny - 1 {
        for x in 1..nx - 1 {
            let h = at(x, y);
            let peak =
                (0..3).all(|j| (0..3).all(|i| (i == 1 && j == 1) || at(x + i - 1, y + j - 1) < h));
            if !peak {
                continue;
            }
            let zxx = (at(x + 1, y) - 2.0 * h + at(x - 1, y)) / (pixel_m * pixel_m);
            let zyy = (at(x, y + 1) - 2.0 * h + at(x, y - 1)) / (pixel_m * pixel_m);
            let kappa = -(zxx + zyy) / 2.0;
            if kappa > 0.0 && kappa.is_finite() {
                out.push(Asperity {
                    height_m: h,
                    radius_m: 1.0 / kappa,
                });
            }
        }
    }
    Ok(out)
}
