//! Adhesion maps (Johnson & Greenwood 1997): a grid over lambda and the load, each point
//! classified into the simplest model whose contact radius is within the tolerance of the exact
//! Maugis-Dugdale one.

use crate::engine::Engine;
use crate::physics::closed::{dmt_radius, hertz_radius, jkr_radius};

use crate::solver::context::{point, x_at_radius};
use crate::solver::{LambdaContext, State, Status};
use rayon::prelude::*;
use serde::Serialize;

/// The load axis of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadAxis {
    /// Pbar on a log axis (positive loads): the classic map.
    Log,
    /// Pbar - Pbar_c on a log axis: the tensile range down to the pull-off.
    AbovePulloff,
    /// Pbar on a linear axis (tensile loads included).
    Linear,
}

#[derive(Clone, Debug, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapSpec {
    pub lambda_min: f64,
    pub lambda_max: f64,
    pub nx: usize,
    pub load_axis: LoadAxis,
    pub load_min: f64,
    pub load_max: f64,
    pub ny: usize,
    pub tolerance: f64,
    /// s0/K ratios for the large-deformation lines a/R = 0.1.
    pub strength_ratios: Vec<f64>,
}

/// The simplest adequate model at a point, in the order they are tried.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum Region {
    NoContact = 0,
    Hertz = 1,
    Rigid = 2,
    Dmt = 3,
    Jkr = 4,
    Md = 5,
    /// The solver could not give a state (not converged, invalid input).
    Failed = 6,
}

impl Region {
    pub const ALL: [Region; 7] = [
        Region::NoContact,
        Region::Hertz,
        Region::Rigid,
        Region::Dmt,
        Region::Jkr,
        Region::Md,
        Region::Failed,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Region::NoContact => "no_contact",
            Region::Hertz => "hertz",
            Region::Rigid => "rigid",
            Region::Dmt => "dmt",
            Region::Jkr => "jkr",
            Region::Md => "md",
            Region::Failed => "failed",
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            Region::NoContact => "no contact",
            Region::Hertz => "Hertz",
            Region::Rigid => "Bradley (rigid)",
            Region::Dmt => "DMT",
            Region::Jkr => "JKR",
            Region::Md => "Maugis-Dugdale",
            Region::Failed => "not computed",
        }
    }
}

/// The criteria of one point: relative errors of the closed-form contact radii (NaN where a
/// model has no answer) and the rigid-body measure (pi lambda / 2) max(A^2, |Dbar|).
#[derive(Clone, Copy, Debug)]
pub struct Criteria {
    pub err_hertz: f64,
    pub err_dmt: f64,
    pub err_jkr: f64,
    pub rigid: f64,
}

pub fn criteria(lambda: f64, load: f64, a: f64, approach: f64) -> Criteria {
    let err = |m: Option<f64>| m.map_or(f64::NAN, |am| (am / a - 1.0).abs());
    Criteria {
        err_hertz: err(hertz_radius(load)),
        err_dmt: err(dmt_radius(load)),
        err_jkr: err(jkr_radius(load)),
        rigid: std::f64::consts::FRAC_PI_2 * lambda * (a * a).max(approach.abs()),
    }
}

/// Hertz, then rigid (Bradley), then DMT, then JKR, else MD; no contact below the pull-off.
pub fn classify(s: &State, tol: f64) -> Region {
    match s.status {
        Status::NoContact => return Region::NoContact,
        Status::Ok => {}
        _ => return Region::Failed,
    }
    // The same tests as `criteria`, on cubes: |A_m / A - 1| <= tol exactly when A_m^3 lies in
    // [(1 - tol)^3 A^3, (1 + tol)^3 A^3], and the closed forms give A_m^3 without a cube root.
    let a3 = s.a * s.a * s.a;
    let (lo, hi) = ((1.0 - tol).powi(3) * a3, (1.0 + tol).powi(3) * a3);
    let within = |m3: f64| m3 >= lo && m3 <= hi;
    let p = s.load;
    if p >= 0.0 && within(p) {
        Region::Hertz
    } else if std::f64::consts::FRAC_PI_2 * s.lambda * (s.a * s.a).max(s.approach.abs()) <= tol {
        Region::Rigid
    } else if within(p + 2.0) {
        Region::Dmt
    } else if p >= -1.5 && within(p + 3.0 + (9.0 + 6.0 * p).max(0.0).sqrt()) {
        Region::Jkr
    } else {
        Region::Md
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct LargeDeformationLine {
    pub strength_ratio: f64,
    /// (lambda, y) where a/R = 0.1; y in the map's load coordinate.
    pub points: Vec<(f64, f64)>,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct Timings {
    pub solve_s: f64,
    pub classify_s: f64,
    pub render_s: f64,
}

pub struct MapData {
    pub spec: MapSpec,
    pub lambdas: Vec<f64>,
    /// The load coordinate of each row: Pbar, or Pbar - Pbar_c for `AbovePulloff`.
    pub rows: Vec<f64>,
    /// Load-controlled pull-off of each column.
    pub pulloff: Vec<f64>,
    /// Row-major, row 0 the lowest load.
    pub states: Vec<State>,
    pub regions: Vec<Region>,
    pub large_deformation: Vec<LargeDeformationLine>,
    pub timings: Timings,
}

pub fn axis(min: f64, max: f64, n: usize, log: bool) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = if n == 1 {
                0.0
            } else {
                i as f64 / (n - 1) as f64
            };
            if log {
                10f64.powf(min.log10() + t * (max.log10() - min.log10()))
            } else {
                min + t * (max - min)
            }
        })
        .collect()
}

#[derive(Debug, thiserror::Error)]
pub enum MapError {
    #[error("{0}")]
    Spec(String),
    #[error(transparent)]
    Engine(#[from] crate::engine::EngineError),
}

/// Most points a map holds (its states stay in memory for classification and rendering).
pub const MAX_MAP_POINTS: usize = 4096 * 4096;
/// Smallest load (or gap above the pull-off) of a log load axis.
pub const LOG_LOAD_MIN: f64 = 1e-15;

impl MapSpec {
    pub fn validate(&self) -> Result<(), MapError> {
        use crate::physics::domain::{check_lambda, short, LOAD_MAX};
        let bad = |m: String| Err(MapError::Spec(m));
        for (flag, l) in [
            ("--lambda-min", self.lambda_min),
            ("--lambda-max", self.lambda_max),
        ] {
            if let Err(e) = check_lambda(l) {
                return bad(format!("{flag}: {e}"));
            }
        }
        if !(self.lambda_max > self.lambda_min) {
            return bad(format!(
                "--lambda-min must be below --lambda-max, got {} and {}",
                short(self.lambda_min),
                short(self.lambda_max)
            ));
        }
        if self.nx < 2 || self.ny < 2 || self.nx > 16384 || self.ny > 16384 {
            return bad(format!(
                "--nx and --ny must be in 2..=16384, got {} and {}",
                self.nx, self.ny
            ));
        }
        if self.nx * self.ny > MAX_MAP_POINTS {
            return bad(format!(
                "--nx {} x --ny {} is {} points, more than the {MAX_MAP_POINTS} (4096 x 4096) a map holds in memory (about 1.5 GB); use fewer points, or split the range into several maps",
                self.nx,
                self.ny,
                self.nx * self.ny
            ));
        }
        if !(self.load_max > self.load_min
            && self.load_min.is_finite()
            && self.load_max.is_finite())
        {
            return bad(format!(
                "--load-min must be below --load-max, got {} and {}",
                short(self.load_min),
                short(self.load_max)
            ));
        }
        let (lo, hi, range) = match self.load_axis {
            LoadAxis::Linear => (-LOAD_MAX, LOAD_MAX, "-1e12..1e12"),
            _ => (LOG_LOAD_MIN, LOAD_MAX, "1e-15..1e12"),
        };
        if self.load_axis != LoadAxis::Linear && self.load_min <= 0.0 {
            return bad(format!("a log load axis needs --load-min > 0 (got {}); use --load-axis linear for tensile loads", short(self.load_min)));
        }
        if !(self.load_min >= lo && self.load_max <= hi) {
            return bad(format!(
                "--load-min {} and --load-max {} must lie within {range} on this load axis (the solver's domain); narrow the range",
                short(self.load_min),
                short(self.load_max)
            ));
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad(format!(
                "--tolerance must be in (0, 1), got {}",
                self.tolerance
            ));
        }
        if self
            .strength_ratios
            .iter()
            .any(|r| !(*r > 0.0 && r.is_finite()))
        {
            return bad("--strength-ratio values must be > 0".into());
        }
        Ok(())
    }
}

/// Solves and classifies a map on the given engine.
pub fn compute(spec: &MapSpec, engine: &Engine) -> Result<MapData, MapError> {
    spec.validate()?;
    let t0 = std::time::Instant::now();
    let lambdas = axis(spec.lambda_min, spec.lambda_max, spec.nx, true);
    let rows = axis(
        spec.load_min,
        spec.load_max,
        spec.ny,
        spec.load_axis != LoadAxis::Linear,
    );
    let ctx = crate::engine::contexts(&lambdas);
    let solve = |rows: &[f64]| match spec.load_axis {
        LoadAxis::AbovePulloff => engine.solve_grid_gaps_with(&ctx, &lambdas, rows),
        _ => engine.solve_grid_with(&ctx, &lambdas, rows, crate::solver::Control::Load),
    };
    let states = if matches!(engine, Engine::Cpu) {
        // On the CPU, blocks of rows with a progress bar (shown on a terminal after 2 s).
        let block = (1 << 18) / spec.nx + 1;
        let mut progress =
            crate::progress::Progress::new("solving", (spec.nx * spec.ny) as u64, "points");
        let mut states = Vec::with_capacity(spec.nx * spec.ny);
        for r in rows.chunks(block) {
            states.extend(solve(r)?);
            progress.inc((r.len() * spec.nx) as u64);
        }
        progress.finish();
        states
    } else {
        solve(&rows)?
    };
    let solve_s = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let pulloff: Vec<f64> = ctx
        .iter()
        .map(|c| c.as_ref().map_or(f64::NAN, |c| c.load_pulloff.load))
        .collect();
    let regions: Vec<Region> = states
        .par_iter()
        .map(|s| classify(s, spec.tolerance))
        .collect();
    let t_regions = t1.elapsed().as_secs_f64();
    let large_deformation = spec
        .strength_ratios
        .iter()
        .map(|&q| LargeDeformationLine {
            strength_ratio: q,
            points: large_deformation_line(spec, &lambdas, &ctx, q),
        })
        .collect();
    let classify_s = t1.elapsed().as_secs_f64();
    if std::env::var("TABOR_PROFILE").is_ok() {
        eprintln!(
            "regions {t_regions:.3} s, lines {:.3} s",
            classify_s - t_regions
        );
    }
    Ok(MapData {
        spec: spec.clone(),
        lambdas,
        rows,
        pulloff,
        states,
        regions,
        large_deformation,
        timings: Timings {
            solve_s,
            classify_s,
            render_s: 0.0,
        },
    })
}

/// a/R = 2 A (s0/K) / lambda = 0.1, i.e. A = 0.05 lambda / (s0/K), on the stable branch.
fn large_deformation_line(
    spec: &MapSpec,
    lambdas: &[f64],
    ctx: &[Option<LambdaContext>],
    ratio: f64,
) -> Vec<(f64, f64)> {
    // Traced at 256 lambdas at most: the line is smooth.
    let step = lambdas.len().div_ceil(256).max(1);
    (0..lambdas.len())
        .into_par_iter()
        .filter(|i| i % step == 0 || *i == lambdas.len() - 1)
        .filter_map(|i| {
            let l = lambdas[i];
            let ctx = ctx[i].as_ref()?;
            let pc = ctx.load_pulloff.load;
            let a = 0.05 * l / ratio;
            if a <= ctx.load_pulloff.a {
                return None;
            }
            let load = point(l, x_at_radius(l, a)).load;
            let y = if spec.load_axis == LoadAxis::AbovePulloff {
                load - pc
            } else {
                load
            };
            (y >= spec.load_min && y <= spec.load_max).then_some((l, y))
        })
        .collect()
}

impl MapData {
    pub fn region_at(&self, ix: usize, iy: usize) -> Region {
        self.regions[iy * self.spec.nx + ix]
    }

    /// For each lambda, the lowest load of the top run of rows where each model is adequate on
    /// its own criterion (`None` where it is not adequate even at the largest load).
    pub fn thresholds(&self) -> Vec<serde_json::Value> {
        let (nx, ny, tol) = (self.spec.nx, self.spec.ny, self.spec.tolerance);
        (0..nx)
            .map(|ix| {
                let mut entry = serde_json::json!({ "lambda": self.lambdas[ix], "pulloff_load": self.pulloff[ix] });
                for (name, k) in [("hertz", 0), ("rigid", 1), ("dmt", 2), ("jkr", 3)] {
                    let ok = |iy: usize| {
                        let s = &self.states[iy * nx + ix];
                        if s.status != Status::Ok {
                            return false;
                        }
                        let c = criteria(s.lambda, s.load, s.a, s.approach);
                        [c.err_hertz, c.rigid, c.err_dmt, c.err_jkr][k] <= tol
                    };
                    let mut iy = ny;
                    while iy > 0 && ok(iy - 1) {
                        iy -= 1;
                    }
                    let v = if iy < ny { serde_json::json!(self.states[iy * nx + ix].load) } else { serde_json::Value::Null };
                    entry[format!("{name}_adequate_above_load")] = v;
                }
                entry
            })
            .collect()
    }

    pub fn region_counts(&self) -> Vec<(Region, usize)> {
        Region::ALL
            .iter()
            .map(|&r| (r, self.regions.iter().filter(|&&x| x == r).count()))
            .filter(|&(_, n)| n > 0)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::LambdaContext;

    #[test]
    fn classification_follows_the_limits() {
        let tol = 0.05;
        // Large load, small lambda: Hertz.
        let s = LambdaContext::new(0.01).unwrap().solve_load(1e3);
        assert_eq!(classify(&s, tol), Region::Hertz);
        // Tiny lambda, tensile load: rigid (no deformation compared to the force range).
        let s = LambdaContext::new(1e-5).unwrap().solve_load(-1.9);
        assert_eq!(classify(&s, tol), Region::Rigid);
        // Large lambda near zero load: JKR.
        let s = LambdaContext::new(1e3).unwrap().solve_load(0.1);
        assert_eq!(classify(&s, tol), Region::Jkr);
        // Transition: MD.
        let s = LambdaContext::new(1.0).unwrap().solve_load(-1.0);
        assert_eq!(classify(&s, tol), Region::Md);
        // Below pull-off.
        let s = LambdaContext::new(1.0).unwrap().solve_load(-1.7);
        assert_eq!(classify(&s, tol), Region::NoContact);
    }
}
