//! The adhesion map of a tip that is not a sphere (docs/PHYSICS.md section 12): over the tip's
//! lambda and its normalised load, the simplest of the shape's own closed forms (Sneddon's
//! punch, the rigid tip, the DMT-type and the JKR-type) whose contact radius is within the
//! tolerance of the exact Maugis-Dugdale one. Solved on the CPU in f64, column by column (a
//! power law's map holds for every B: its units absorb it).

use super::{extend_adequate_runs, LoadAxis, MapData, MapError, MapSpec, Points, Region};
use crate::law::{Drive, Law, Piece, Tip};
use crate::physics::tip::Shape;
use crate::solver::Status;
use rayon::prelude::*;
use std::f64::consts::PI;

/// One solved point: its state in the compact records' terms, its region and adequate models.
struct TipPoint {
    a: f64,
    approach: f64,
    m_minus_1: f64,
    status: Status,
    region: Region,
    bits: u8,
}

/// The models adequate at an exact state (A, Dbar) at load `p`, one bit each (0 Sneddon, 1
/// rigid, 2 DMT-type, 3 JKR-type), as `map::adequate` for the sphere: a closed form's radius
/// within `tol` of A; rigid where the deformation is within `tol` of the range,
/// `(pi lambda/2) max(Fbar(A), |Dbar|) <= tol`.
fn adequate(shape: &Shape, lambda: f64, f0: f64, p: f64, a: f64, approach: f64, tol: f64) -> u8 {
    let radii = shape.closed_radii(p, f0);
    let within = |x: f64| x.is_finite() && (x / a - 1.0).abs() <= tol;
    let rigid = PI / 2.0 * lambda * shape.abel(a).0.max(approach.abs()) <= tol;
    [within(radii[0]), rigid, within(radii[1]), within(radii[2])]
        .iter()
        .enumerate()
        .fold(0, |bits, (m, &t)| bits | ((t as u8) << m))
}

/// The column at `lambda`: its load-controlled pull-off and its points at the rows.
fn column(shape: Shape, lambda: f64, spec: &MapSpec, rows: &[f64]) -> (f64, Vec<TipPoint>) {
    let Ok(law) = Tip::new(shape, lambda) else {
        return (f64::NAN, Vec::new());
    };
    let t0 = law.stable_from(Drive::DeadLoad);
    let pulloff = law.state(Piece::Contact, t0).load;
    let f0 = shape.rigid_force(lambda);
    let points = rows
        .iter()
        .map(|&y| {
            let p = if spec.load_axis == LoadAxis::AbovePulloff {
                pulloff + y
            } else {
                y
            };
            match law.at_load_above(t0, p) {
                None => TipPoint {
                    a: f64::NAN,
                    approach: f64::NAN,
                    m_minus_1: f64::NAN,
                    status: Status::NoContact,
                    region: Region::NoContact,
                    bits: 0,
                },
                Some(s) => {
                    let bits = adequate(&shape, lambda, f0, p, s.a, s.approach, spec.tolerance);
                    TipPoint {
                        a: s.a,
                        approach: s.approach,
                        m_minus_1: s.c / s.a - 1.0,
                        status: Status::Ok,
                        region: match bits.trailing_zeros() {
                            0 => Region::Hertz,
                            1 => Region::Rigid,
                            2 => Region::Dmt,
                            3 => Region::Jkr,
                            _ => Region::Md,
                        },
                        bits,
                    }
                }
            }
        })
        .collect();
    (pulloff, points)
}

/// The adhesion map of `shape` over `spec`'s grid (lambda within the tip's 1e-3..1e3).
pub fn compute_tip(spec: &MapSpec, shape: Shape, keep_exact: bool) -> Result<MapData, MapError> {
    spec.validate()?;
    let (lo, hi) = crate::law::tip::LAMBDA_RANGE;
    if spec.lambda_min < lo || spec.lambda_max > hi {
        return Err(MapError::Spec(
            format!(
                "a tip's map spans lambda from {lo:e} to {hi:e}: got {:e} to {:e}; narrow the lambda range",
                spec.lambda_min, spec.lambda_max
            )
            .into(),
        ));
    }
    let t0 = std::time::Instant::now();
    let (nx, ny) = (spec.nx, spec.ny);
    let (lambdas, rows) = spec.axes();
    let mut progress = crate::progress::Progress::new("solving", nx as u64, "columns");
    let mut columns: Vec<(f64, Vec<TipPoint>)> = Vec::with_capacity(nx);
    for chunk in lambdas.chunks(16) {
        crate::interrupt::checkpoint();
        columns.par_extend(chunk.par_iter().map(|&l| column(shape, l, spec, &rows)));
        progress.inc(chunk.len() as u64);
    }
    progress.finish();
    let solve_s = t0.elapsed().as_secs_f64();
    // Row-major, row 0 the lowest load, as the sphere's map.
    let n = nx * ny;
    let mut points = Points::new(nx, ny, 1);
    let mut regions = Vec::with_capacity(n);
    let mut exact = keep_exact.then(|| Vec::with_capacity(n));
    let mut marks = Vec::with_capacity(n);
    for iy in 0..ny {
        for (_, col) in &columns {
            let q = col.get(iy).unwrap_or(&TipPoint {
                a: f64::NAN,
                approach: f64::NAN,
                m_minus_1: f64::NAN,
                status: Status::InvalidInput,
                region: Region::Failed,
                bits: 0,
            });
            points.a.push(q.a as f32);
            points.approach.push(q.approach as f32);
            points.m_minus_1.push(q.m_minus_1 as f32);
            points.status.push(q.status as u8);
            regions.push(q.region);
            marks.push(q.region as u8 | (q.bits << 3));
            if let Some(e) = exact.as_mut() {
                e.push([q.a, q.approach, q.m_minus_1]);
            }
        }
    }
    let mut adequate_from = vec![[None; 4]; nx];
    extend_adequate_runs(&mut adequate_from, &marks, 0);
    Ok(MapData {
        spec: spec.clone(),
        lambdas,
        rows,
        pulloff: columns.iter().map(|c| c.0).collect(),
        points,
        regions,
        exact,
        adequate_from,
        check: None,
        large_deformation: Vec::new(),
        timings: super::Timings {
            solve_s,
            classify_s: t0.elapsed().as_secs_f64() - solve_s,
            render_s: 0.0,
        },
        tip: Some(shape),
    })
}
