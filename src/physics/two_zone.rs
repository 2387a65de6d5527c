//! Two Dugdale zones sharing one contact radius: the solid's cohesive stress and a second,
//! longer- or shorter-ranged one such as a water meniscus (docs/PHYSICS.md section 10).
//!
//! Units are those of section 1 built on the total work of adhesion `w = w1 + w2`; zone i has the
//! stress number `lambda_i` (its stress is `lambda_i / 2` in the pressure unit) and the range
//! `h_i` in approach units, with `(pi/2)(lambda_1 h_1 + lambda_2 h_2) = 1`.

use super::md::{curve_point, CurvePoint};
use super::real::Real;
use std::f64::consts::PI;

/// Carlson's symmetric integral `RF(x, y, z)` (at most one argument zero), by duplication to a
/// relative error below 1e-16 (the fifth-order series after the arguments agree to 2.5e-3).
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    let (mut xt, mut yt, mut zt) = (x, y, z);
    for _ in 0..200 {
        let (sx, sy, sz) = (xt.sqrt(), yt.sqrt(), zt.sqrt());
        let lam = sx * (sy + sz) + sy * sz;
        xt = 0.25 * (xt + lam);
        yt = 0.25 * (yt + lam);
        zt = 0.25 * (zt + lam);
        let ave = (xt + yt + zt) / 3.0;
        let (dx, dy, dz) = ((ave - xt) / ave, (ave - yt) / ave, (ave - zt) / ave);
        if dx.abs().max(dy.abs()).max(dz.abs()) <= 0.0025 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 + (e2 / 24.0 - 0.1 - 3.0 / 44.0 * e3) * e2 + e3 / 14.0) / ave.sqrt();
        }
    }
    f64::NAN
}

/// Carlson's `RD(x, y, z)` (x, y not both zero, z > 0), relative error below 1e-16.
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    let (mut xt, mut yt, mut zt) = (x, y, z);
    let (mut sum, mut fac) = (0.0, 1.0);
    for _ in 0..200 {
        let (sx, sy, sz) = (xt.sqrt(), yt.sqrt(), zt.sqrt());
        let lam = sx * (sy + sz) + sy * sz;
        sum += fac / (sz * (zt + lam));
        fac *= 0.25;
        xt = 0.25 * (xt + lam);
        yt = 0.25 * (yt + lam);
        zt = 0.25 * (zt + lam);
        let ave = 0.2 * (xt + yt + 3.0 * zt);
        let (dx, dy, dz) = ((ave - xt) / ave, (ave - yt) / ave, (ave - zt) / ave);
        if dx.abs().max(dy.abs()).max(dz.abs()) <= 0.0015 {
            let (c1, c2, c3, c4) = (3.0 / 14.0, 1.0 / 6.0, 9.0 / 22.0, 3.0 / 26.0);
            let (c5, c6) = (0.25 * c3, 1.5 * c4);
            let ea = dx * dy;
            let eb = dz * dz;
            let ec = ea - eb;
            let ed = ea - 6.0 * eb;
            let ee = ed + ec + ec;
            let series = 1.0
                + ed * (-c1 + c5 * ed - c6 * dz * ee)
                + dz * (c2 * ee + dz * (-c3 * ec + dz * c4 * ea));
            return 3.0 * sum + fac * series / (ave * ave.sqrt());
        }
    }
    f64::NAN
}

/// Complete elliptic integrals `(K(k), E(k))` of modulus `0 <= k < 1` (E also at k = 1).
pub fn elliptic_ke(k: f64) -> (f64, f64) {
    let kc2 = (1.0 - k) * (1.0 + k);
    if kc2 <= 0.0 {
        return (f64::INFINITY, 1.0);
    }
    let rf = carlson_rf(0.0, kc2, 1.0);
    let rd = carlson_rd(0.0, kc2, 1.0);
    (rf, rf - k * k / 3.0 * rd)
}

/// `f1(mu) = (mu^2 - 1) atan(mu) + mu` and `f2(mu) = mu atan(mu) - (m - 1)` of section 2,
/// without cancellation at small mu.
fn f1_f2(mu: f64) -> (f64, f64) {
    let (at, d) = mu.atan_parts();
    let mu2 = mu * mu;
    let m_minus_1 = mu2 / (1.0 + (1.0 + mu2).sqrt());
    (mu2 * at + d, mu * at - m_minus_1)
}

/// The band integral `I(r; 1, C) = int_1^min(r,C) acos(s/r) s / sqrt(C^2 - s^2) ds` for a
/// contact radius of 1, given `mu_r = sqrt(r^2 - 1)` and `mu_c = sqrt(C^2 - 1)`: the gap (over
/// `8 lambda / (3 pi)`) that a band of outer radius C opens at radius r (section 10).
pub fn band_gap_unit(mu_r: f64, mu_c: f64) -> f64 {
    if mu_r <= 0.0 || mu_c <= 0.0 {
        return 0.0;
    }
    if mu_r == mu_c {
        return f1_f2(mu_r).1;
    }
    let m_r = (1.0 + mu_r * mu_r).sqrt();
    let m_c = (1.0 + mu_c * mu_c).sqrt();
    // p = |C^2 - r^2| as a product, exact where the two radii are close.
    let p = (mu_c - mu_r).abs() * (mu_c + mu_r);
    let j = if mu_r < mu_c {
        // Inside the band: b = acos(1/r), J = p K0 + r^2 K2.
        let s = mu_r / m_r;
        let x = p / (m_r * m_r);
        let y = mu_c * mu_c;
        let k0 = s * carlson_rf(x, y, p);
        let k2 = s * s * s / 3.0 * p * carlson_rd(x, y, p);
        p * k0 + m_r * m_r * k2
    } else {
        // Outside the band: b = acos(1/C), J = C^2 K2.
        let s = mu_c / m_c;
        let x = p / (m_c * m_c);
        let y = mu_r * mu_r;
        m_c * m_c * (s * s * s / 3.0) * p * carlson_rd(x, y, p)
    };
    mu_c * mu_r.atan() - j
}

/// The gap (over `8 lambda / (3 pi)`) a band of outer radius C and contact radius A opens at r.
pub fn band_gap(r: f64, a: f64, c: f64) -> f64 {
    if r <= a || c <= a {
        return 0.0;
    }
    let mu = |x: f64| ((x - a) * (x + a)).sqrt() / a;
    a * band_gap_unit(mu(r), mu(c))
}

/// The Hertz gap of contact radius A at r >= A, in approach units (section 8).
pub fn hertz_gap(r: f64, a: f64) -> f64 {
    if r <= a {
        return 0.0;
    }
    let t = ((r - a) * (r + a)).sqrt() / a;
    let (at, d) = t.atan_parts();
    a * a / PI * (t * t * at + d)
}

/// The surface displacement (over `8 lambda / (3 pi)`) of a uniform tension on a disc of radius
/// C, at radius r: `C E(r/C)` inside, `r [E(C/r) - (1 - C^2/r^2) K(C/r)]` outside.
pub fn disc_displacement(r: f64, c: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    if r <= c {
        c * elliptic_ke(r / c).1
    } else {
        let k = c / r;
        let (kk, ee) = elliptic_ke(k);
        r * (ee - (1.0 - k) * (1.0 + k) * kk)
    }
}

/// The second zone's two ratios, given together or not at all (the one-zone law): the one
/// check of every front end, in words that name the two quantities.
pub fn paired_ratios(
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
) -> Result<Option<(f64, f64)>, crate::error::Message> {
    match (stress_ratio, range_ratio) {
        (None, None) => Ok(None),
        (Some(rho), Some(eta)) => Ok(Some((rho, eta))),
        _ => Err(crate::error::Message::new()
            .text("give ")
            .key("stress_ratio")
            .text(" and ")
            .key("range_ratio")
            .text(" together (the second zone's stress and range over the solid's), or neither for one zone")),
    }
}

/// The two zones in the total-w units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zones {
    /// Stress numbers (stress = lambda / 2 in the pressure unit).
    pub lambda: [f64; 2],
    /// Ranges in approach units.
    pub range: [f64; 2],
}

/// How the curve is computed for a pair of zones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// One zone acts (the other is absent, or both share the range): MD with this lambda, its
    /// outer radius common to the zones present.
    Single {
        /// The single zone's (or the summed) Maugis parameter.
        lambda: f64,
    },
    /// Two ranges.
    Two {
        /// The index of the zone with the longer range.
        long: usize,
    },
}

impl Zones {
    /// Whether zone i acts at all (a stress over a range).
    pub fn present(&self, i: usize) -> bool {
        self.lambda[i] > 0.0 && self.range[i] > 0.0
    }

    /// The normalised total work `(pi/2)(lambda_1 h_1 + lambda_2 h_2)`: 1 in these units.
    pub fn total_work(&self) -> f64 {
        0.5 * PI * (self.lambda[0] * self.range[0] + self.lambda[1] * self.range[1])
    }

    /// Zone i's share of the work of adhesion.
    pub fn work_share(&self, i: usize) -> f64 {
        if self.present(i) {
            0.5 * PI * self.lambda[i] * self.range[i] / self.total_work()
        } else {
            0.0
        }
    }

    /// Which zones act: one (MD with its lambda) or two (with the longer-range zone's index).
    pub fn shape(&self) -> Shape {
        match (self.present(0), self.present(1)) {
            (true, false) => Shape::Single {
                lambda: self.lambda[0],
            },
            (false, true) => Shape::Single {
                lambda: self.lambda[1],
            },
            _ if self.range[0] == self.range[1] => Shape::Single {
                lambda: self.lambda[0] + self.lambda[1],
            },
            _ => Shape::Two {
                long: if self.range[1] > self.range[0] { 1 } else { 0 },
            },
        }
    }
}

/// One state of the contact curve: contact radius, the zones' outer radii, load and approach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoZonePoint {
    /// Contact radius A.
    pub a: f64,
    /// `mu_i = sqrt(m_i^2 - 1)`, `m_i = C_i / A` (0 for an absent zone: no band).
    pub mu: [f64; 2],
    /// Outer radii C_i (A for an absent zone).
    pub c: [f64; 2],
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
}

fn from_md(p: CurvePoint<f64>, zones: &Zones) -> TwoZonePoint {
    let mut mu = [0.0; 2];
    let mut c = [p.a; 2];
    for i in 0..2 {
        if zones.present(i) {
            mu[i] = p.mu;
            c[i] = p.a * (1.0 + p.m_minus_1);
        }
    }
    TwoZonePoint {
        a: p.a,
        mu,
        c,
        load: p.load,
        approach: p.approach,
    }
}

/// The positive root of condition j, `(f1(mu_j)/pi) A^2 + (8/(3 pi)) sum_i lambda_i I_ij A = h_j`.
fn radius_of_condition(zones: &Zones, j: usize, mu: [f64; 2]) -> f64 {
    let alpha = f1_f2(mu[j]).0 / PI;
    let mut sum = 0.0;
    for (i, &m) in mu.iter().enumerate() {
        if zones.lambda[i] > 0.0 {
            sum += zones.lambda[i] * band_gap_unit(mu[j], m);
        }
    }
    let beta = 8.0 / (3.0 * PI) * sum;
    let h = zones.range[j];
    2.0 * h / (beta + (beta * beta + 4.0 * alpha * h).sqrt())
}

/// The curve point at `x = ln(mu_L)` of the zone with the longer range (or of the single zone).
/// `None` where the inner root for the shorter zone could not be bracketed.
pub fn point(zones: &Zones, x: f64) -> Option<TwoZonePoint> {
    match zones.shape() {
        Shape::Single { lambda } => Some(from_md(curve_point(lambda, x.exp()), zones)),
        Shape::Two { long } => {
            let u = inner_root(zones, long, x)?;
            Some(at_mus(zones, long, x, u))
        }
    }
}

/// [`point`] of two ranges with the slopes of its load, approach and contact radius in x: the
/// inner root `u = ln(mu_S)` moves by `du/dx = -phi_x / phi_u`, so that the slopes are the
/// explicit state's partial derivatives (central differences of explicit functions, relative
/// error about 1e-10) instead of differences of whole root searches. `None` for one zone or
/// where the inner root is not found.
pub fn point_with_slopes(zones: &Zones, x: f64) -> Option<(TwoZonePoint, [f64; 3])> {
    let Shape::Two { long } = zones.shape() else {
        return None;
    };
    let u = inner_root(zones, long, x)?;
    let p = at_mus(zones, long, x, u);
    const H: f64 = 1e-6;
    let phi = |x: f64, u: f64| condition_gap(zones, long, x, u);
    let phi_x = (phi(x + H, u) - phi(x - H, u)) / (2.0 * H);
    let phi_u = (phi(x, u + H) - phi(x, u - H)) / (2.0 * H);
    let du = -phi_x / phi_u;
    let g = |x: f64, u: f64| {
        let q = at_mus(zones, long, x, u);
        [q.load, q.approach, q.a]
    };
    let (gxp, gxm, gup, gum) = (g(x + H, u), g(x - H, u), g(x, u + H), g(x, u - H));
    let slope = |k: usize| ((gxp[k] - gxm[k]) + (gup[k] - gum[k]) * du) / (2.0 * H);
    let slopes = [slope(0), slope(1), slope(2)];
    slopes.iter().all(|v| v.is_finite()).then_some((p, slopes))
}

/// The zones' mu at `x = ln(mu_L)` and `u = ln(mu_S)`.
fn mus_at(long: usize, x: f64, u: f64) -> [f64; 2] {
    let mut mu = [0.0; 2];
    mu[long] = x.exp();
    mu[1 - long] = u.exp();
    mu
}

/// `A_S - A_L`: the contact radii that the two gap conditions give at (x, u), zero on the
/// curve.
fn condition_gap(zones: &Zones, long: usize, x: f64, u: f64) -> f64 {
    let mu = mus_at(long, x, u);
    radius_of_condition(zones, 1 - long, mu) - radius_of_condition(zones, long, mu)
}

/// The shorter zone's `u = ln(mu_S)` at `x = ln(mu_L)`: the root of [`condition_gap`], which is
/// +inf as mu_S -> 0 and negative at mu_S = mu_L (the shorter range there).
fn inner_root(zones: &Zones, long: usize, x: f64) -> Option<f64> {
    let phi = |u: f64| condition_gap(zones, long, x, u);
    let hi = x;
    let f_hi = phi(hi);
    let mut lo = x - 4.0;
    let mut f_lo = phi(lo);
    let mut n = 0;
    while !(f_lo > 0.0) {
        if !f_lo.is_nan() && f_lo <= 0.0 {
            lo -= 8.0;
        } else {
            return None;
        }
        f_lo = phi(lo);
        n += 1;
        if n > 40 {
            return None;
        }
    }
    if !(f_hi < 0.0) {
        return None;
    }
    let r = crate::numeric::root::secant_bracketed(
        phi,
        (lo, f_lo),
        (hi, f_hi),
        0.5 * (lo + hi),
        1e-16,
        300,
    );
    Some(r.x)
}

/// The state at (x, u) with the contact radius of the longer zone's condition: on the curve
/// where u is the inner root.
fn at_mus(zones: &Zones, long: usize, x: f64, u: f64) -> TwoZonePoint {
    let mu = mus_at(long, x, u);
    let a = radius_of_condition(zones, long, mu);
    let g = |m: f64| {
        let (at, _) = m.atan_parts();
        m + (1.0 + m * m) * at
    };
    let adh_load = zones.lambda[0] * g(mu[0]) + zones.lambda[1] * g(mu[1]);
    let adh_app = zones.lambda[0] * mu[0] + zones.lambda[1] * mu[1];
    let load = a * a * (a - adh_load);
    let approach = a * (a - 4.0 / 3.0 * adh_app);
    let c = [
        a * (1.0 + mu[0] * mu[0]).sqrt(),
        a * (1.0 + mu[1] * mu[1]).sqrt(),
    ];
    TwoZonePoint {
        a,
        mu,
        c,
        load,
        approach,
    }
}

/// The gap at r for a contact state (section 10): Hertz plus both bands.
pub fn gap(zones: &Zones, p: &TwoZonePoint, r: f64) -> f64 {
    let mut h = hertz_gap(r, p.a);
    for i in 0..2 {
        if zones.lambda[i] > 0.0 {
            h += 8.0 * zones.lambda[i] / (3.0 * PI) * band_gap(r, p.a, p.c[i]);
        }
    }
    h
}

/// The pressure (compressive positive, in `(pi w K^2 / R)^(1/3)`) at r for a contact state.
pub fn pressure(zones: &Zones, p: &TwoZonePoint, r: f64) -> f64 {
    let a = p.a;
    let mut s = if r < a {
        1.5 / PI * ((a - r) * (a + r)).sqrt()
    } else {
        0.0
    };
    for i in 0..2 {
        let l = zones.lambda[i];
        if l <= 0.0 || p.c[i] <= a {
            continue;
        }
        if r < a {
            let w = ((a - r) * (a + r) / ((p.c[i] - a) * (p.c[i] + a))).sqrt();
            s += -0.5 * l + l / PI * w.atan();
        } else if r <= p.c[i] {
            s -= 0.5 * l;
        }
    }
    s
}

/// A state of the non-contact branch (A = 0): the outer radii of the two discs, load, approach
/// and the gap on the axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonContactPoint {
    /// The zones' outer radii (0 for a zone that has not opened).
    pub c: [f64; 2],
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
    /// The gap at the axis (r = 0).
    pub axis_gap: f64,
}

/// The gap at r on the non-contact branch, given the discs and the approach.
pub fn non_contact_gap(zones: &Zones, c: [f64; 2], approach: f64, r: f64) -> f64 {
    let mut h = -approach + 0.5 * r * r;
    for (&l, &ci) in zones.lambda.iter().zip(&c) {
        if l > 0.0 {
            h -= 8.0 * l / (3.0 * PI) * disc_displacement(r, ci);
        }
    }
    h
}

/// The non-contact state in which only the longer-range zone acts (the single zone for
/// [`Shape::Single`]), its disc of radius `c_long >= 0`: valid while the axis gap is at least the
/// shorter range (and positive).
pub fn non_contact_single(zones: &Zones, c_long: f64) -> NonContactPoint {
    let long = match zones.shape() {
        Shape::Single { .. } => {
            let mut c = [0.0; 2];
            for (i, ci) in c.iter_mut().enumerate() {
                if zones.present(i) {
                    *ci = c_long;
                }
            }
            return nc_from(zones, c, usize::from(!zones.present(0)));
        }
        Shape::Two { long } => long,
    };
    let mut c = [0.0; 2];
    c[long] = c_long;
    nc_from(zones, c, long)
}

/// The non-contact state with both discs, the shorter-range zone's of radius `c_short > 0`
/// (two ranges only): the longer disc's radius is the root of the two gap conditions' approaches,
/// bracketed from `C_L = C_S` (where they differ by the ranges' difference) outwards. `None` for
/// a single shape or where no root was bracketed.
pub fn non_contact_both(zones: &Zones, c_short: f64) -> Option<NonContactPoint> {
    let Shape::Two { long } = zones.shape() else {
        return None;
    };
    let short = 1 - long;
    let approach_of = |cl: f64, j: usize| {
        let mut cc = [0.0; 2];
        cc[long] = cl;
        cc[short] = c_short;
        non_contact_gap(zones, cc, 0.0, cc[j]) - zones.range[j]
    };
    // h_L - h_S > 0 at C_L = C_S; falls like -C_L^2 / 2.
    let diff = |cl: f64| approach_of(cl, short) - approach_of(cl, long);
    let lo = c_short;
    let f_lo = diff(lo);
    let mut hi = 2.0 * c_short + zones.range[long].sqrt();
    let mut f_hi = diff(hi);
    let mut n = 0;
    while f_hi >= 0.0 && n < 60 {
        hi *= 2.0;
        f_hi = diff(hi);
        n += 1;
    }
    if !(f_lo > 0.0 && f_hi < 0.0) {
        return None;
    }
    let r = crate::numeric::root::secant_bracketed(
        diff,
        (lo, f_lo),
        (hi, f_hi),
        0.5 * (lo + hi),
        1e-16,
        300,
    );
    let mut c = [0.0; 2];
    c[long] = r.x;
    c[short] = c_short;
    Some(nc_from(zones, c, long))
}

/// The ends of the non-contact branch's two stretches (two ranges only): the longer zone's disc
/// radius where the axis gap falls to the shorter range, and the shorter zone's disc radius
/// where the axis gap closes (the A -> 0 end of the contact curve). `None` for one zone or
/// where a crossing was not bracketed.
pub fn non_contact_ends(z: &Zones) -> Option<(f64, f64)> {
    let Shape::Two { long } = z.shape() else {
        return None;
    };
    let h_short = z.range[1 - long];
    let scale = z.range[long].sqrt();
    let c1 = crossing(|c| non_contact_single(z, c).axis_gap < h_short, scale)?;
    let both_gap = |c: f64| non_contact_both(z, c).map_or(f64::NAN, |p| p.axis_gap);
    let c2 = crossing(|c| !(both_gap(c) >= 0.0), c1.max(scale))?;
    Some((c1, c2))
}

/// The largest `x` in `[0, hi]` (hi doubled until `below(x)` holds) with `below(x)` false, by
/// bisection: where a monotone quantity crosses its limit.
fn crossing(below: impl Fn(f64) -> bool, start: f64) -> Option<f64> {
    let mut hi = start;
    let mut n = 0;
    while !below(hi) {
        hi *= 2.0;
        n += 1;
        if n > 60 {
            return None;
        }
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if below(m) {
            hi = m;
        } else {
            lo = m;
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    Some(lo)
}

/// The non-contact state with discs `c`, its approach from zone `j`'s gap condition.
fn nc_from(zones: &Zones, c: [f64; 2], j: usize) -> NonContactPoint {
    // h(C_j) = -D + C_j^2/2 - sum u_i(C_j) = h_j.
    let approach = non_contact_gap(zones, c, 0.0, c[j]) - zones.range[j];
    let load = -0.5 * PI * (zones.lambda[0] * c[0] * c[0] + zones.lambda[1] * c[1] * c[1]);
    NonContactPoint {
        c,
        load,
        approach,
        axis_gap: non_contact_gap(zones, c, approach, 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn carlson_matches_known_values() {
        // Carlson (1995) Table: RF(1, 2, 0) = 1.3110287771461, RD(0, 2, 1) = 1.7972103521034.
        assert!((carlson_rf(1.0, 2.0, 0.0) - 1.311_028_777_146_1).abs() < 1e-12);
        assert!((carlson_rd(0.0, 2.0, 1.0) - 1.797_210_352_103_4).abs() < 1e-12);
        // K(1/sqrt 2) = 1.8540746773013719, E(1/sqrt 2) = 1.3506438810476755.
        let (k, e) = elliptic_ke(std::f64::consts::FRAC_1_SQRT_2);
        assert!((k - 1.854_074_677_301_372).abs() < 1e-14);
        assert!((e - 1.350_643_881_047_675_5).abs() < 1e-14);
    }

    /// The band integral by composite Gauss-Legendre quadrature after `s = min(r,C) - (min - 1) v^2`
    /// (which removes the endpoint square roots): independent of the Carlson forms.
    fn band_by_quadrature(r: f64, c: f64) -> f64 {
        let b = r.min(c);
        let n = 4000;
        let (x, w) = gauss5();
        let mut sum = 0.0;
        for k in 0..n {
            let (v0, v1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
            for q in 0..5 {
                let v = 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * x[q];
                let s = b - (b - 1.0) * v * v;
                let ds = 2.0 * (b - 1.0) * v;
                let f = (s / r).min(1.0).acos() * s / ((c - s) * (c + s)).sqrt();
                let f = if f.is_finite() { f } else { 0.0 };
                sum += 0.5 * (v1 - v0) * w[q] * f * ds;
            }
        }
        sum
    }

    fn gauss5() -> ([f64; 5], [f64; 5]) {
        let a = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
        let b = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
        let wa = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
        let wb = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
        ([-b, -a, 0.0, a, b], [wb, wa, 128.0 / 225.0, wa, wb])
    }

    #[test]
    fn band_gap_closed_form_matches_quadrature() {
        for &(mr, mc) in &[
            (0.3, 0.7),
            (0.7, 0.3),
            (2.0, 5.0),
            (5.0, 2.0),
            (1.0, 1.0001),
            (0.05, 3.0),
        ] {
            let r = (1.0f64 + mr * mr).sqrt();
            let c = (1.0f64 + mc * mc).sqrt();
            let closed = band_gap_unit(mr, mc);
            let quad = band_by_quadrature(r, c);
            assert!(
                (closed - quad).abs() < 1e-9 * quad.abs().max(1e-6),
                "mu_r {mr} mu_c {mc}: {closed} vs {quad}"
            );
        }
        // At its own edge the band gap is f2 (equation 1); beside it (p -> 0 in the Carlson
        // forms) the closed form still agrees with the quadrature, from both sides.
        let f2 = f1_f2(0.8).1;
        for (mr, mc) in [(0.8, 0.8 * (1.0 + 1e-6)), (0.8 * (1.0 + 1e-6), 0.8)] {
            let r = (1.0f64 + mr * mr).sqrt();
            let c = (1.0f64 + mc * mc).sqrt();
            let closed = band_gap_unit(mr, mc);
            let quad = band_by_quadrature(r, c);
            assert!(
                (closed - quad).abs() < 1e-9 * quad,
                "{mr} {mc}: {closed} vs {quad}"
            );
            // Continuous: a change of 8e-7 in one radius moves the gap by O(1e-6).
            assert!((closed - f2).abs() < 1e-5, "{closed} vs f2 {f2}");
        }
    }

    #[test]
    fn disc_displacement_matches_abel_sum() {
        // U(r; c) = (pi/2) int_0^c s/sqrt(c^2-s^2) [r < s ? 1 : (2/pi) asin(s/r)] ds; with
        // s = c sin(phi) the integrand is smooth on each side of s = r.
        for &(r, c) in &[(0.0, 1.0), (0.4, 1.0), (1.0, 1.0), (1.7, 1.0), (5.0, 2.0)] {
            let n = 20000;
            let mut sum = 0.0;
            for k in 0..n {
                let phi = (k as f64 + 0.5) / n as f64 * 0.5 * PI;
                let s = c * phi.sin();
                let f = if r < s {
                    1.0
                } else {
                    2.0 / PI * (s / r).min(1.0).asin()
                };
                sum += c * phi.sin() * f * (0.5 * PI / n as f64);
            }
            let abel = 0.5 * PI * sum;
            let closed = disc_displacement(r, c);
            assert!(
                (closed - abel).abs() < 2e-6 * closed,
                "r {r} c {c}: {closed} vs {abel}"
            );
        }
    }
}
