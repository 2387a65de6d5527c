//! The numbers behind the line figures, computed apart from the drawing code: `render` draws
//! what these return and solves nothing itself.

use crate::map::{compute, LoadAxis, MapData, MapError, MapSpec};
use crate::physics::md::curve_point;
use crate::scene::SceneResult;
use crate::solver::context::x_at_radius;
use crate::solver::{LambdaContext, SolveError};

/// The pull-off figure: lambda 1e-4..1e4 (401 points) and each one's pull-offs.
pub struct PulloffData {
    /// The lambdas, log-spaced.
    pub lambdas: Vec<f64>,
    /// Each lambda's solver, with both pull-offs.
    pub contexts: Vec<LambdaContext>,
}

/// The pull-offs of 401 lambdas from 1e-4 to 1e4.
pub fn pulloff_data() -> Result<PulloffData, SolveError> {
    let lambdas: Vec<f64> = (0..=400)
        .map(|i| 10f64.powf(-4.0 + 8.0 * i as f64 / 400.0))
        .collect();
    let contexts = lambdas
        .iter()
        .map(|&l| LambdaContext::new(l))
        .collect::<Result<_, _>>()?;
    Ok(PulloffData { lambdas, contexts })
}

/// One MD curve of the A(P) figure: (Pbar, A, stable under load control) for A up to 2.6 and
/// Pbar up to 4, and the load-controlled pull-off (Pbar_c, A_c).
pub struct CurveSeries {
    /// The Maugis parameter.
    pub lambda: f64,
    /// (Pbar, A, stable under load control).
    pub points: Vec<(f64, f64, bool)>,
    /// The load-controlled pull-off (Pbar_c, A_c).
    pub pulloff: (f64, f64),
}

/// The A(P) curves of the given lambdas.
pub fn curves_data(lambdas: &[f64]) -> Result<Vec<CurveSeries>, SolveError> {
    lambdas
        .iter()
        .map(|&l| {
            let c = LambdaContext::new(l)?;
            let points = (1..=400)
                .map(|i| {
                    let a = 2.6 * i as f64 / 400.0;
                    let p = curve_point(l, x_at_radius(l, a).exp());
                    (p.load, p.a, p.dload_dmu < 0.0)
                })
                .filter(|p| p.0 <= 4.0)
                .collect();
            Ok(CurveSeries {
                lambda: l,
                points,
                pulloff: (c.load_pulloff.load, c.load_pulloff.a),
            })
        })
        .collect()
}

/// The scene figure: its MD a(P) in SI units (from the pull-off to 1.1 times the largest load
/// or twice the pull-off force), in a wet scene also that of solid and meniscus, and the
/// adhesion map it is placed on.
pub struct SceneFigure {
    /// The MD contact radius against the load (N, m): the dry contact's in a wet scene.
    pub md: Vec<(f64, f64)>,
    /// In a wet scene, the contact radius of solid and meniscus together (the two-zone law)
    /// against the load (N, m).
    pub wet: Option<Vec<(f64, f64)>>,
    /// The adhesion map the scene is placed on.
    pub map: MapData,
    /// The force unit pi w R (N) and the radius unit (m) of the scene.
    pub force_scale: f64,
    /// The radius unit `(pi w R^2 / K)^(1/3)` (m).
    pub radius_scale: f64,
    /// The load range drawn: from the pull-off force to the largest load (N).
    pub loads: (f64, f64),
}

#[derive(Debug, thiserror::Error)]
/// Why a figure's data could not be computed.
pub enum FigureError {
    #[error(transparent)]
    /// A state was not found.
    Solve(#[from] SolveError),
    #[error(transparent)]
    /// The map failed.
    Map(#[from] MapError),
    #[error(transparent)]
    /// The scene's contact could not be rebuilt (a wet scene's two zones).
    Param(#[from] crate::physics::params::ParamError),
}

/// The scene figure's data.
pub fn scene_data(r: &SceneResult) -> Result<SceneFigure, FigureError> {
    let fs = std::f64::consts::PI * r.work_of_adhesion_j_m2 * r.radius_m;
    let rs =
        (std::f64::consts::PI * r.work_of_adhesion_j_m2 * r.radius_m * r.radius_m / r.k_pa).cbrt();
    // The load range from the pull-off (of solid and meniscus, in a wet scene) to the largest.
    let pc = r.pulloff_force_load_control_N;
    let pmax = r
        .loads
        .iter()
        .map(|l| l.load_n)
        .fold(pc.abs() * 2.0, f64::max)
        * 1.1;
    // A curve from its own pull-off `p0` to pmax, dense near the pull-off.
    let from = |p0: f64, a_of: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        (0..=300)
            .map(|i| {
                let p = p0 + (pmax - p0) * (i as f64 / 300.0).powi(2);
                (p, a_of(p))
            })
            .filter(|q| q.1.is_finite())
            .collect()
    };
    let ctx = LambdaContext::new(r.lambda)?;
    // The MD curve: the dry contact's, from its own pull-off.
    let dry_pc = r.dry_pulloff_force_load_control_N.unwrap_or(pc);
    let md = from(dry_pc, &|p| ctx.solve_load(p / fs).a * rs);
    let wet = match &r.meniscus {
        None => None,
        Some(m) => {
            let c = crate::physics::params::Contact::new(
                r.radius_m,
                r.e_star_pa,
                r.work_of_adhesion_j_m2,
                crate::physics::params::ForceRange::DugdaleStress(r.s0_pa),
            )?;
            let (two, u) = crate::scene::humidity::wet_context(&c, m)?;
            Some(from(pc, &|p| two.state_at_load(p / u.load).a * u.radius))
        }
    };
    let spec = MapSpec {
        lambda_min: 1e-3,
        lambda_max: 1e3,
        nx: 400,
        load_axis: LoadAxis::Linear,
        load_min: -2.0,
        load_max: 10.0,
        ny: 400,
        tolerance: r.tolerance,
        strength_ratios: vec![],
    };
    let map = compute(&spec, &crate::engine::Engine::Cpu)?;
    Ok(SceneFigure {
        md,
        wet,
        map,
        force_scale: fs,
        radius_scale: rs,
        loads: (pc, pmax),
    })
}

/// The adhesion map under fitted force curves (`tabor fit --on-map`): lambda over the curves'
/// values, loads on a linear axis over the normalised loads they span.
pub fn fit_map_data(
    results: &[crate::fit::CurveFit],
    tolerance: f64,
) -> Result<MapData, FigureError> {
    let fitted: Vec<&crate::fit::CurveFit> = results
        .iter()
        .filter(|r| r.status == crate::fit::FitStatus::Ok && r.lambda.is_some())
        .collect();
    let (mut lo, mut hi) = (1e-2f64, 1e2f64);
    let (mut pmin, mut pmax) = (-2.1f64, 2.0f64);
    // The lambda axis spans the curves whose lambda the data determine.
    for r in fitted.iter().filter(|r| r.lambda_determined()) {
        let l = r.lambda.unwrap().clamp(1e-3, 1e3);
        lo = lo.min(l / 3.0);
        hi = hi.max(l * 3.0);
    }
    for r in &fitted {
        if let Some([a, b]) = r.load_range_normalised {
            pmin = pmin.min(a * 1.05);
            pmax = pmax.max(b * 1.05);
        }
    }
    let spec = MapSpec {
        lambda_min: lo.max(1e-4),
        lambda_max: hi.min(1e4),
        nx: 400,
        load_axis: LoadAxis::Linear,
        load_min: pmin.max(-2.1),
        load_max: pmax.min(1e3),
        ny: 400,
        tolerance,
        strength_ratios: vec![],
    };
    Ok(compute(&spec, &crate::engine::Engine::Cpu)?)
}
