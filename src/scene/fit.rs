//! w and E* from measured (load, contact radius) pairs with the exact MD model.

use crate::physics::params::{Contact, ForceRange, ParamError};
use crate::solver::{LambdaContext, Status};
use serde::Serialize;

/// A fit of w and E* to measured (load, contact radius) pairs with the exact MD model.
#[derive(Clone, Debug, Serialize)]
pub struct PairsFit {
    pub work_of_adhesion_j_m2: f64,
    pub e_star_pa: f64,
    pub lambda: f64,
    pub tabor_parameter: f64,
    /// (a_model - a_measured) / a_measured for each pair.
    pub relative_residuals: Vec<f64>,
    pub rms_relative_residual: f64,
}

/// Least squares on the relative contact-radius residuals over (ln w, ln E*): a coarse grid, then
/// a compass search to a step of 1e-9. `pairs` are (load in N, contact radius in m).
pub fn fit_pairs(pairs: &[(f64, f64)], radius: f64, z0: f64) -> Result<PairsFit, ParamError> {
    if pairs.len() < 2 {
        return Err(ParamError::Missing(
            "give at least two (load, contact radius) pairs",
        ));
    }
    for &(p, a) in pairs {
        if !(p.is_finite() && a.is_finite() && a > 0.0) {
            return Err(ParamError::OutOfRange {
                field: "pairs",
                value: if a > 0.0 { p } else { a },
                allowed: "finite loads (N) and positive contact radii (m)",
            });
        }
    }
    // Two parameters need two distinct loads, and an elastic contact grows with the load.
    let mut sorted = pairs.to_vec();
    sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
    sorted.dedup_by(|x, y| x.0 == y.0 && x.1 == y.1);
    if sorted.windows(2).filter(|w| w[1].0 > w[0].0).count() < 1 {
        return Err(ParamError::Missing(
            "the pairs need at least two different loads to determine both w and E*",
        ));
    }
    if let Some(w) = sorted
        .windows(2)
        .find(|w| w[1].0 > w[0].0 && !(w[1].1 > w[0].1))
    {
        return Err(ParamError::OutOfRange {
            field: "contact_radius_m",
            value: w[1].1,
            allowed: "larger at a larger load (the contact radius of an elastic sphere grows with the load); check the columns",
        });
    }
    let residuals = |lw: f64, le: f64| -> Option<Vec<f64>> {
        let c = Contact::new(radius, le.exp(), lw.exp(), ForceRange::LennardJones(z0)).ok()?;
        let ctx = LambdaContext::new(c.lambda()).ok()?;
        let (fs, rs) = (c.force_scale(), c.radius_scale());
        Some(
            pairs
                .iter()
                .map(|&(p, a)| {
                    let s = ctx.solve_load(p / fs);
                    if s.status == Status::Ok {
                        s.a * rs / a - 1.0
                    } else {
                        1.0
                    }
                })
                .collect(),
        )
    };
    let cost = |lw: f64, le: f64| {
        residuals(lw, le).map_or(f64::INFINITY, |r| r.iter().map(|x| x * x).sum::<f64>())
    };
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for i in 0..=24 {
        for j in 0..=24 {
            let (lw, le) = (
                (1e-4f64).ln() + i as f64 * (1e5f64).ln() / 24.0,
                (1e3f64).ln() + j as f64 * (1e9f64).ln() / 24.0,
            );
            let c = cost(lw, le);
            if c < best.0 {
                best = (c, lw, le);
            }
        }
    }
    let (mut f, mut lw, mut le) = best;
    let mut step = 0.5;
    while step > 1e-9 {
        let mut moved = false;
        for (dw, de) in [
            (step, 0.0),
            (-step, 0.0),
            (0.0, step),
            (0.0, -step),
            (step, step),
            (-step, -step),
            (step, -step),
            (-step, step),
        ] {
            let c = cost(lw + dw, le + de);
            if c < f {
                (f, lw, le) = (c, lw + dw, le + de);
                moved = true;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    let r = residuals(lw, le).ok_or(ParamError::Missing("the fit left the valid range"))?;
    // A minimum on the edge of the searched box, or pairs the model leaves out of contact, mean
    // the data do not determine the parameters: no number is better than a wrong one.
    let (lw_lo, lw_hi) = ((1e-4f64).ln(), (1e1f64).ln());
    let (le_lo, le_hi) = ((1e3f64).ln(), (1e12f64).ln());
    if !(lw > lw_lo + 0.5 && lw < lw_hi - 0.5 && le > le_lo + 0.5 && le < le_hi - 0.5) {
        return Err(ParamError::Missing(
            "the pairs do not determine w and E*: the best fit runs to the edge of w in 1e-4..10 J/m^2 and E* in 1e3..1e12 Pa (check the units and that the radii grow with the load)",
        ));
    }
    if r.contains(&1.0) {
        return Err(ParamError::Missing(
            "some loads lie below the fitted model's pull-off: the pairs are not consistent with one Maugis-Dugdale contact",
        ));
    }
    let c = Contact::new(radius, le.exp(), lw.exp(), ForceRange::LennardJones(z0))?;
    let rms = (r.iter().map(|x| x * x).sum::<f64>() / r.len() as f64).sqrt();
    Ok(PairsFit {
        work_of_adhesion_j_m2: c.work,
        e_star_pa: c.e_star,
        lambda: c.lambda(),
        tabor_parameter: c.tabor(),
        relative_residuals: r,
        rms_relative_residual: rms,
    })
}

#[cfg(test)]
mod fit_tests {
    use super::*;

    #[test]
    fn pairs_fit_recovers_w_and_e_star() {
        // Synthetic JKR-like test: PDMS-like sphere, exact MD radii at six loads.
        let (r, e, w, z0) = (2e-3, 2.4e6, 0.044, 0.3e-9);
        let c = Contact::new(r, e, w, ForceRange::LennardJones(z0)).unwrap();
        let ctx = LambdaContext::new(c.lambda()).unwrap();
        let pairs: Vec<(f64, f64)> = [-2e-4, 0.0, 5e-4, 1e-3, 2e-3, 4e-3]
            .iter()
            .map(|&p| (p, ctx.solve_load(p / c.force_scale()).a * c.radius_scale()))
            .collect();
        let fit = fit_pairs(&pairs, r, z0).unwrap();
        assert!(
            (fit.work_of_adhesion_j_m2 / w - 1.0).abs() < 1e-5,
            "{}",
            fit.work_of_adhesion_j_m2
        );
        assert!((fit.e_star_pa / e - 1.0).abs() < 1e-5, "{}", fit.e_star_pa);
        assert!(fit.rms_relative_residual < 1e-6);
    }
}
