//! The Maugis-Dugdale curve, parametrised by `mu = sqrt(m^2 - 1)` (docs/PHYSICS.md section 2).
//!
//! Every state on the curve is an explicit function of mu: equation (1) is a quadratic in A whose
//! positive root is taken in the cancellation-free form, and f1, f2 are written as sums of
//! positive terms so that the JKR side (mu -> 0) keeps full precision.

use super::real::Real;

/// Above this lambda the minimum of the approach lies inside the curve; at or below it the
/// displacement-controlled contact shrinks to zero radius (docs/PHYSICS.md section 4).
pub const LAMBDA_D: f64 = 0.937947457210712;

/// One point of the Maugis-Dugdale curve and its slopes with respect to mu.
#[derive(Clone, Copy, Debug, Default)]
pub struct CurvePoint<T> {
    /// `mu = sqrt(m^2 - 1)`, the curve's parameter.
    pub mu: T,
    /// Contact radius A.
    pub a: T,
    /// m - 1 = mu^2 / (1 + m), kept to full relative precision.
    pub m_minus_1: T,
    /// Pbar + 2, written without the cancellation of Pbar = A^3 - lambda A^2 g at small lambda,
    /// where the load hugs the DMT value -2.
    pub load_plus_2: T,
    /// Pbar = A^2 (A - lambda g): the form with the least cancellation on the JKR side.
    pub load: T,
    /// Dbar.
    pub approach: T,
    /// dPbar/dmu along the curve; negative on the load-controlled stable branch.
    pub dload_dmu: T,
    /// dDbar/dmu along the curve; negative on the displacement-controlled stable branch.
    pub dapproach_dmu: T,
    /// dA/dmu along the curve.
    pub da_dmu: T,
}

/// The curve point at `mu > 0` for Maugis parameter `lambda > 0`.
#[inline(always)]
pub fn curve_point<T: Real>(lambda: T, mu: T) -> CurvePoint<T> {
    let one = T::of(1.0);
    let two = T::of(2.0);
    // Constants are formed in T: 4/3 rounded to f64 would perturb the equations by 1e-17,
    // which the pull-off condition amplifies by lambda^-3.
    let four_thirds = T::of(4.0) / T::of(3.0);
    let (at, mu_minus_at) = mu.atan_parts();
    let mu2 = mu * mu;
    let m = (one + mu2).sqrt();
    let m_minus_1 = mu2 / (one + m);
    // f1 = (mu^2 - 1) atan(mu) + mu = mu^2 atan(mu) + (mu - atan(mu)): both terms positive.
    let f1 = mu2 * at + mu_minus_at;
    // f2 = mu atan(mu) - (m - 1); loses at most one bit at small mu.
    let f2 = mu * at - m_minus_1;
    let alpha = T::of(0.5) * lambda * f1;
    let beta = four_thirds * lambda * lambda * f2;
    let a = two / (beta + (beta * beta + T::of(4.0) * alpha).sqrt());
    let g = mu + (one + mu2) * at;
    let load = a * a * (a - lambda * g);
    // lambda A^2 g = 2 - (8/3) lambda^2 f2 A + 2 lambda A^2 atan(mu), by equation (1). The
    // common factor A is taken out by hand: shader compilers may factor `a b + a c` themselves
    // (Mesa's NIR does), and the kernels' CPU mirror must round as the GPU does.
    let load_plus_2 =
        a * (a * a + T::of(8.0) / T::of(3.0) * lambda * lambda * f2) - two * lambda * a * a * at;
    let approach = a * (a - four_thirds * lambda * mu);

    let m2 = one + mu2;
    let df1 = two * mu * at + two * mu2 / m2;
    let df2 = at - mu * mu2 / ((one + m) * m2);
    let dalpha = T::of(0.5) * lambda * df1;
    let dbeta = four_thirds * lambda * lambda * df2;
    let da = -(dalpha * a * a + dbeta * a) / (two * alpha * a + beta);
    let dg = two + two * mu * at;
    let dload_dmu = da * (T::of(3.0) * a * a - two * lambda * a * g) - lambda * a * a * dg;
    let dapproach_dmu = da * (two * a - four_thirds * lambda * mu) - four_thirds * lambda * a;
    CurvePoint {
        mu,
        a,
        m_minus_1,
        load_plus_2,
        load,
        approach,
        dload_dmu,
        dapproach_dmu,
        da_dmu: da,
    }
}

/// The curve point at `x = ln mu`, the parameter the solvers search in.
#[inline]
pub fn point(lambda: f64, x: f64) -> CurvePoint<f64> {
    curve_point(lambda, x.exp())
}

/// The slopes of A, Pbar and Dbar with respect to lambda at fixed mu (the curve point of
/// [`curve_point`] as lambda moves): equation (1), `alpha A^2 + beta A = 1` with
/// `alpha = lambda f1 / 2` and `beta = (4/3) lambda^2 f2`, differentiated at fixed f1, f2.
/// A fit's Jacobian takes lambda's column from them instead of from differences.
pub fn curve_point_dlambda(lambda: f64, mu: f64) -> (f64, f64, f64) {
    let (at, mu_minus_at) = mu.atan_parts();
    let mu2 = mu * mu;
    let m = (1.0 + mu2).sqrt();
    let f1 = mu2 * at + mu_minus_at;
    let f2 = mu * at - mu2 / (1.0 + m);
    let alpha = 0.5 * lambda * f1;
    let beta = 4.0 / 3.0 * lambda * lambda * f2;
    let a = 2.0 / (beta + (beta * beta + 4.0 * alpha).sqrt());
    let g = mu + (1.0 + mu2) * at;
    let da = -(0.5 * f1 * a * a + 8.0 / 3.0 * lambda * f2 * a) / (2.0 * alpha * a + beta);
    let dload = da * (3.0 * a * a - 2.0 * lambda * a * g) - a * a * g;
    let dapproach = da * (2.0 * a - 4.0 / 3.0 * lambda * mu) - 4.0 / 3.0 * a * mu;
    (da, dload, dapproach)
}

/// The end of the curve at A -> 0 (m -> infinity, C = m A finite), where it meets the
/// non-contact branch: `(pi lambda/4) C^2 + (2 (pi-2) lambda^2/3) C = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZeroRadiusEnd {
    /// The Dugdale zone's outer radius C there.
    pub c: f64,
    /// Pbar there.
    pub load: f64,
    /// Dbar there.
    pub approach: f64,
}

/// The A -> 0 end of lambda's curve (the root of its quadratic in C).
pub fn zero_radius_end(lambda: f64) -> ZeroRadiusEnd {
    use std::f64::consts::PI;
    let qa = PI * lambda / 4.0;
    let qb = 2.0 * (PI - 2.0) * lambda * lambda / 3.0;
    let c = 2.0 / (qb + (qb * qb + 4.0 * qa).sqrt());
    ZeroRadiusEnd {
        c,
        load: -(PI * lambda / 2.0) * c * c,
        approach: -(4.0 / 3.0) * lambda * c,
    }
}

/// The non-contact branch (A = 0, cohesive zone of normalised radius C only), for
/// `0 <= C <= zero_radius_end(lambda).c`: returns `(Pbar, Dbar)` (docs/PHYSICS.md section 4).
pub fn non_contact_point(lambda: f64, c: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    let load = -(PI * lambda / 2.0) * c * c;
    let approach = c * c / 2.0 - (8.0 * lambda / (3.0 * PI)) * c - 2.0 / (PI * lambda);
    (load, approach)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::real::{Dd, Real};

    #[test]
    fn atan_parts_agree_between_f64_and_double_double() {
        for i in 0..400 {
            let mu = 10f64.powf(-8.0 + 16.0 * i as f64 / 399.0);
            let (at, d) = mu.atan_parts();
            let (atd, dd) = Dd::of(mu).atan_parts();
            assert!((at / atd.to_f64() - 1.0).abs() < 4e-16, "atan at {mu}");
            assert!((d / dd.to_f64() - 1.0).abs() < 4e-15, "mu-atan at {mu}");
        }
    }

    #[test]
    fn double_double_atan_parts_match_series_identity() {
        // atan(1) = pi/4 to double-double precision.
        let (at, d) = Dd::of(1.0).atan_parts();
        let quarter_pi = Dd {
            hi: std::f64::consts::FRAC_PI_4,
            lo: 3.061616997868383e-17,
        };
        assert!((at - quarter_pi).to_f64().abs() < 1e-31);
        assert!((d + at - Dd::of(1.0)).to_f64().abs() < 1e-31);
    }

    #[test]
    fn lambda_slopes_match_differences_of_the_curve() {
        for &lambda in &[0.05, 0.4, 1.0, 3.0, 20.0] {
            for &mu in &[1e-3, 0.1, 1.0, 4.0, 50.0] {
                let (da, dp, dd) = curve_point_dlambda(lambda, mu);
                let h = 1e-5 * lambda;
                let (p, m) = (curve_point(lambda + h, mu), curve_point(lambda - h, mu));
                let close = |x: f64, fd: f64, what: &str| {
                    assert!(
                        (x - fd).abs() <= 1e-7 * fd.abs().max(1e-3),
                        "{what} at lambda {lambda}, mu {mu}: {x} against {fd}"
                    )
                };
                close(da, (p.a - m.a) / (2.0 * h), "dA");
                close(dp, (p.load - m.load) / (2.0 * h), "dP");
                close(dd, (p.approach - m.approach) / (2.0 * h), "dD");
            }
        }
    }

    #[test]
    fn non_contact_branch_meets_the_curve_end() {
        for &lambda in &[0.01, 0.3, 1.0, 10.0] {
            let end = zero_radius_end(lambda);
            let (p, d) = non_contact_point(lambda, end.c);
            assert!((p - end.load).abs() < 1e-13 * end.load.abs());
            assert!((d - end.approach).abs() < 1e-12 * end.approach.abs().max(1.0));
        }
    }
}
