//! Rough surfaces (tabor::rough): dicts of NumPy arrays, no JSON in between.

use crate::{arr, run, run_py};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tabor::rough::{Mean, Rough};

fn leg<'py>(py: Python<'py>, v: &[Mean]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item(
        "separation",
        arr(py, v.iter().map(|m| m.separation).collect()),
    )?;
    d.set_item("load", arr(py, v.iter().map(|m| m.load).collect()))?;
    d.set_item(
        "contact_fraction",
        arr(py, v.iter().map(|m| m.contact_fraction).collect()),
    )?;
    d.set_item(
        "noncontact_fraction",
        arr(py, v.iter().map(|m| m.noncontact_fraction).collect()),
    )?;
    d.set_item(
        "contact_load",
        arr(py, v.iter().map(|m| m.contact_load).collect()),
    )?;
    d.set_item(
        "noncontact_load",
        arr(py, v.iter().map(|m| m.noncontact_load).collect()),
    )?;
    Ok(d)
}

/// A rough surface's approach-retract cycle, as `tabor rough` computes it.
#[pyfunction]
#[pyo3(signature = (lam, sigma, min_separation, max_separation, points, stress_ratio=None, range_ratio=None))]
#[allow(clippy::too_many_arguments)]
pub fn rough<'py>(
    py: Python<'py>,
    lam: f64,
    sigma: f64,
    min_separation: f64,
    max_separation: Option<f64>,
    points: usize,
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = run(py, move || {
        let law = tabor::ContactLaw::new(lam, stress_ratio, range_ratio)?;
        Ok(tabor::rough::wet::WetRough::of_law(law, sigma)?.cycle(
            lam,
            min_separation,
            max_separation,
            points,
        )?)
    })?;
    let d = PyDict::new(py);
    d.set_item("lambda", c.lambda)?;
    d.set_item("sigma", c.sigma)?;
    d.set_item("approach", leg(py, &c.approach)?)?;
    d.set_item("retract", leg(py, &c.retract)?)?;
    d.set_item("pulloff_load", c.pulloff_load)?;
    d.set_item("pulloff_separation", c.pulloff_separation)?;
    d.set_item("hysteresis", c.hysteresis)?;
    d.set_item("smooth_pulloff", c.smooth_pulloff)?;
    d.set_item("fuller_tabor_parameter", c.fuller_tabor_parameter)?;
    d.set_item("quadrature_error", c.quadrature_error)?;
    // The library's words name rough()'s own arguments (max_separation, points).
    let warnings: Vec<String> = c.warnings.iter().map(|w| w.to_string()).collect();
    d.set_item("warnings", warnings)?;
    Ok(d)
}

/// The rough adhesion map, as `tabor rough-map` computes it: flat row-major arrays (rows are
/// sigma), reshaped in `tabor/__init__.py`.
#[pyfunction]
#[pyo3(signature = (lambda_min, lambda_max, nx, sigma_min, sigma_max, ny, tolerance, press_sigmas, check))]
#[allow(clippy::too_many_arguments)]
pub fn rough_map<'py>(
    py: Python<'py>,
    lambda_min: f64,
    lambda_max: f64,
    nx: usize,
    sigma_min: f64,
    sigma_max: f64,
    ny: usize,
    tolerance: f64,
    press_sigmas: f64,
    check: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = tabor::rough::map::RoughMapSpec {
        lambda_min,
        lambda_max,
        nx,
        sigma_min,
        sigma_max,
        ny,
        tolerance,
        press_sigmas,
    };
    let m = run(py, move || {
        tabor::rough::map::check_checks(check)?;
        Ok(tabor::rough::map::compute(&spec, check)?)
    })?;
    let d = PyDict::new(py);
    d.set_item("lambda", arr(py, m.lambdas.clone()))?;
    d.set_item("sigma", arr(py, m.sigmas.clone()))?;
    d.set_item("smooth_pulloff", arr(py, m.smooth_pulloff.clone()))?;
    d.set_item("pulloff", arr(py, m.pulloff.clone()))?;
    d.set_item("relative_pulloff", arr(py, m.relative_pulloff.clone()))?;
    d.set_item("pulloff_separation", arr(py, m.pulloff_separation.clone()))?;
    d.set_item(
        "region",
        m.regions.iter().map(|&r| r as u8).collect::<Vec<u8>>(),
    )?;
    d.set_item(
        "region_names",
        tabor::map::Region::ALL
            .iter()
            .map(|r| r.name())
            .collect::<Vec<_>>(),
    )?;
    d.set_item(
        "model_error",
        arr(
            py,
            m.model_error
                .iter()
                .flat_map(|e| e.iter().copied())
                .collect(),
        ),
    )?;
    d.set_item("table_error", m.table_error_max())?;
    d.set_item("check_points", m.check.points)?;
    d.set_item(
        "check_max_relative_difference",
        m.check.max_relative_difference,
    )?;
    Ok(d)
}

/// Loads per summit of explicit ensembles: `heights` (approach units) at each separation of
/// `separations`, on the approach (`min_separation` None) or the retract after it.
#[pyfunction]
#[pyo3(signature = (lam, heights, separations, min_separation))]
pub fn rough_ensemble<'py>(
    py: Python<'py>,
    lam: f64,
    heights: Vec<f64>,
    separations: Vec<f64>,
    min_separation: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let v = run(py, move || {
        if heights.is_empty() || heights.iter().any(|z| !z.is_finite()) {
            anyhow::bail!("the summit heights must be finite, and at least one");
        }
        // The spread only sets the surface's own quadrature, unused here.
        let r = Rough::new(lam, 1.0)?;
        let leg = match min_separation {
            None => tabor::rough::Leg::Approach,
            Some(d_min) => tabor::rough::Leg::Retract { d_min },
        };
        // The library's refusals named as rough_ensemble's arguments.
        separations
            .iter()
            .map(|&d| {
                r.ensemble_mean(leg, &heights, d).map_err(|e| {
                    anyhow::anyhow!(tabor::error::Named::named(&e, &|key| match key {
                        "the smallest separation" => Some("min_separation"),
                        "the separation" => Some("separations"),
                        _ => None,
                    }))
                })
            })
            .collect::<anyhow::Result<Vec<Mean>>>()
    })?;
    leg(py, &v)
}

fn ensemble_leg<'py>(
    py: Python<'py>,
    l: &tabor::rough::ensemble::EnsembleLeg,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("separation_m", arr(py, l.separation_m.clone()))?;
    d.set_item("force_n", arr(py, l.force_n.clone()))?;
    d.set_item(
        "real_contact_area_m2",
        arr(py, l.real_contact_area_m2.clone()),
    )?;
    d.set_item("contact_fraction", arr(py, l.contact_fraction.clone()))?;
    d.set_item(
        "noncontact_fraction",
        arr(py, l.noncontact_fraction.clone()),
    )?;
    Ok(d)
}

/// A rough scene from its JSON text or a preset's name.
fn scene_of(
    scene_json: Option<String>,
    preset: Option<String>,
) -> anyhow::Result<tabor::rough::scene::RoughScene> {
    match (scene_json, preset) {
        (Some(j), None) => {
            serde_json::from_str(&j).map_err(|e| anyhow::anyhow!("not a valid rough scene: {e}"))
        }
        (None, Some(p)) => tabor::rough::scene::preset(&p).ok_or_else(|| {
            anyhow::anyhow!(
                "no rough preset {p:?}; the presets are {}",
                tabor::rough::scene::PRESETS.join(", ")
            )
        }),
        _ => anyhow::bail!("give a rough scene (JSON text) or a preset name, one of them"),
    }
}

/// An ensemble's cycle as a dict of NumPy arrays and numbers.
fn ensemble_dict<'py>(
    py: Python<'py>,
    c: &tabor::rough::ensemble::EnsembleCycle,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("summits", c.summits)?;
    d.set_item("approach", ensemble_leg(py, &c.approach)?)?;
    d.set_item("retract", ensemble_leg(py, &c.retract)?)?;
    d.set_item("pulloff_force_n", c.pulloff_force_n)?;
    d.set_item("pulloff_separation_m", c.pulloff_separation_m)?;
    d.set_item("summit_solver", c.summit_solver.clone())?;
    d.set_item("table_error", c.table_error)?;
    d.set_item("summit_states", c.summit_states)?;
    d.set_item("seconds", c.seconds)?;
    Ok(d)
}

/// The engine of an ensemble's tables and stepping, as `tabor rough --backend` chooses it (f64
/// where the adapter has it).
fn table_engine(backend: tabor::engine::Backend) -> anyhow::Result<tabor::engine::Engine> {
    let (mut e, _) = tabor::engine::Engine::select(backend, None)?;
    let _ = e.set_precision(tabor::engine::Precision::F64);
    Ok(e)
}

/// An explicit ensemble of summits in SI (heights and radii in m) with a rough scene's
/// materials, as `tabor rough --asperities` computes it (tables or exact; on `backend`).
#[pyfunction]
#[pyo3(signature = (heights_m, radii_m, scene_json, preset, min_separation_m, points, summits, backend))]
#[allow(clippy::too_many_arguments)]
pub fn rough_asperities<'py>(
    py: Python<'py>,
    heights_m: Vec<f64>,
    radii_m: Vec<f64>,
    scene_json: Option<String>,
    preset: Option<String>,
    min_separation_m: Option<f64>,
    points: usize,
    summits: String,
    backend: String,
) -> PyResult<Bound<'py, PyDict>> {
    use tabor::rough::ensemble::{asperities, EnsembleSpec};
    let backend = crate::backend_of(&backend)?;
    let c = run(py, move || {
        let scene = scene_of(scene_json, preset)?;
        let asp = asperities(&heights_m, &radii_m)?;
        let spec = EnsembleSpec {
            min_separation_m,
            points,
            solver: summits.parse()?,
        };
        Ok(spec.run(&scene, &asp, &table_engine(backend)?)?)
    })?;
    ensemble_dict(py, &c)
}

/// The summits of a measured height map (rows of `nx` heights in m, `pixel_m` apart) through
/// the cycle, as `tabor rough --topography --pixel-m` computes it.
#[pyfunction]
#[pyo3(signature = (z, nx, pixel_m, scene_json, preset, min_separation_m, points, summits, backend))]
#[allow(clippy::too_many_arguments)]
pub fn rough_topography<'py>(
    py: Python<'py>,
    z: Vec<f64>,
    nx: usize,
    pixel_m: f64,
    scene_json: Option<String>,
    preset: Option<String>,
    min_separation_m: Option<f64>,
    points: usize,
    summits: String,
    backend: String,
) -> PyResult<Bound<'py, PyDict>> {
    use tabor::rough::ensemble::{topography_summits, EnsembleSpec};
    let backend = crate::backend_of(&backend)?;
    let c = run(py, move || {
        let scene = scene_of(scene_json, preset)?;
        let asp = topography_summits(&z, nx, pixel_m)?;
        let spec = EnsembleSpec {
            min_separation_m,
            points,
            solver: summits.parse()?,
        };
        Ok(spec.run(&scene, &asp, &table_engine(backend)?)?)
    })?;
    ensemble_dict(py, &c)
}

/// Fuller and Tabor's sweep, as `tabor rough-pulloff` computes it: one dict per lambda with the
/// pull-off per summit against the roughness (the library checks the options).
#[pyfunction]
#[pyo3(signature = (lambdas, sigma_min, sigma_max, points, press_sigmas))]
pub fn rough_pulloff<'py>(
    py: Python<'py>,
    lambdas: Vec<f64>,
    sigma_min: f64,
    sigma_max: f64,
    points: usize,
    press_sigmas: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let sweep = tabor::rough::PulloffSweep {
        lambdas,
        sigma_min,
        sigma_max,
        points,
        press_sigmas,
    };
    run_py(py, move || Ok(sweep.compute()?))
}

/// A rough scene in SI units (JSON text, or a preset's name) through its cycle, as `tabor rough
/// --scene FILE` or `--preset NAME` computes it (dry, or wet with the scene's humidity): the
/// report `--format json` writes, as Python objects.
#[pyfunction]
#[pyo3(signature = (scene_json, preset, points))]
pub fn rough_scene<'py>(
    py: Python<'py>,
    scene_json: Option<String>,
    preset: Option<String>,
    points: usize,
) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || Ok(scene_of(scene_json, preset)?.solve(points)?))
}
