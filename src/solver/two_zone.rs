//! States and pull-offs of the two-zone cohesive law (docs/PHYSICS.md section 10): the solid's
//! Dugdale zone plus a second one (a water meniscus), solved exactly as MD.
//!
//! A single zone, or two zones of equal range, is MD itself (with the summed stress) and is
//! solved by [`LambdaContext`]; two ranges are solved along the curve parametrised by
//! `x = ln(mu_L)` of the longer-range zone.

use super::context::LambdaContext;
use super::Status;
use crate::error::Message;
use crate::numeric::golden::{Golden, Ties, Width};
use crate::numeric::root::{bisect_sign, secant_bracketed, Stop};
use crate::physics::domain::short;
use crate::physics::md::LAMBDA_D;
use crate::physics::two_zone::{gap, point, Shape, TwoZonePoint, Zones};
use std::f64::consts::PI;

/// Where the curve is sampled for its minima: from large contact radii (x = ln mu small) to the
/// A -> 0 end (A ~ C e^-X_END, below 1e-15 C).
const X_START: f64 = -25.0;
const X_END: f64 = 36.0;
const X_STEP: f64 = 0.25;
/// The golden-section refinement of a minimum between grid points.
const GOLDEN: Golden = Golden {
    width: Width::Absolute(1e-13),
    ties: Ties::Left,
    max_iter: 90,
};
/// The most negative x searched for large loads and radii.
const X_FAR: f64 = -60.0;

/// Stress numbers and work shares must lie in these bounds (the grid covers the pull-offs of
/// MD for lambda in 1e-4..1e4).
pub const LAMBDA_MIN: f64 = 1e-8;
/// The largest stress number the two-zone solver takes.
pub const LAMBDA_MAX: f64 = 1e6;

/// A bad set of zones: the message names the value and what to do.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct ZonesError(pub Message);

impl From<ZonesError> for Message {
    fn from(e: ZonesError) -> Message {
        e.0
    }
}

impl ZonesError {
    /// A refusal that names no quantity a front end calls otherwise.
    pub fn text(s: impl Into<std::borrow::Cow<'static, str>>) -> ZonesError {
        ZonesError(Message::new().text(s))
    }
}

impl crate::error::Named for ZonesError {
    fn named(&self, names: crate::error::Names) -> String {
        self.0.named(names)
    }
}

impl Zones {
    /// Zones in the total-w units; `(pi/2)(lambda_1 h_1 + lambda_2 h_2)` must be 1 (to 1e-9).
    /// A zone with a zero stress or range is absent.
    pub fn new(lambda: [f64; 2], range: [f64; 2]) -> Result<Zones, ZonesError> {
        for i in 0..2 {
            for (name, v) in [("stress number", lambda[i]), ("range", range[i])] {
                if !v.is_finite() || v < 0.0 {
                    return Err(ZonesError::text(format!(
                        "zone {}'s {name} = {} must be a finite number >= 0",
                        i + 1,
                        short(v)
                    )));
                }
            }
        }
        let z = Zones { lambda, range };
        if !z.present(0) && !z.present(1) {
            return Err(ZonesError::text(
                "neither zone acts: give at least one zone a stress and a range > 0",
            ));
        }
        if (z.total_work() - 1.0).abs() > 1e-9 {
            return Err(ZonesError::text(format!(
                "(pi/2)(lambda_1 h_1 + lambda_2 h_2) = {} must be 1 in the total-w units",
                short(z.total_work())
            )));
        }
        for i in 0..2 {
            if z.present(i) && !(LAMBDA_MIN..=LAMBDA_MAX).contains(&z.lambda[i]) {
                return Err(ZonesError::text(format!(
                    "zone {}'s stress number {} is outside {LAMBDA_MIN:e}..{LAMBDA_MAX:e}",
                    i + 1,
                    short(z.lambda[i])
                )));
            }
        }
        Ok(z)
    }

    /// The zones from the solid's Maugis parameter `lambda_s` (section 1 with the solid's w1)
    /// and the second zone's stress ratio `rho = s2/s1` and range ratio `eta = h2/h1`
    /// (docs/PHYSICS.md section 10). `rho = 0` or `eta = 0` is the solid alone.
    pub fn from_ratios(lambda_s: f64, rho: f64, eta: f64) -> Result<Zones, ZonesError> {
        check_ratios(rho, eta)?;
        if !lambda_s.is_finite() || lambda_s < 0.0 {
            return Err(ZonesError(Message::new().key("lambda").text(format!(
                " = {} must be a finite number >= 0",
                short(lambda_s)
            ))));
        }
        if lambda_s <= 0.0 {
            return Err(ZonesError(
                Message::new()
                    .key("lambda")
                    .text(format!(" = {} must be > 0", short(lambda_s))),
            ));
        }
        let ratio = 1.0 + rho * eta;
        let l1 = lambda_s / ratio.cbrt();
        let h1 = 2.0 / (PI * lambda_s * ratio.powf(2.0 / 3.0));
        check_stress_numbers(lambda_s, rho, eta, l1)?;
        Zones::new([l1, rho * l1], [h1, eta * h1])
    }
}

/// The second zone's stress ratio and range ratio: finite and >= 0 (whatever lambda).
pub fn check_ratios(rho: f64, eta: f64) -> Result<(), ZonesError> {
    for (name, v) in [("stress ratio", rho), ("range ratio", eta)] {
        if !v.is_finite() || v < 0.0 {
            return Err(ZonesError::text(format!(
                "{name} = {} must be a finite number >= 0",
                short(v)
            )));
        }
    }
    Ok(())
}

/// The zones' stress numbers `lambda_1 = lambda_s (1 + rho eta)^(-1/3)` and `lambda_2 = rho
/// lambda_1` in [`LAMBDA_MIN`]..[`LAMBDA_MAX`] (a zone of zero stress or range is absent), in
/// the words of the ratios given: the two-zone solver's grid is built for that span.
fn check_stress_numbers(lambda_s: f64, rho: f64, eta: f64, l1: f64) -> Result<(), ZonesError> {
    let given = Message::new()
        .key("lambda")
        .text(format!(" {}, ", short(lambda_s)))
        .key("stress_ratio")
        .text(format!(" {} (rho), ", short(rho)))
        .key("range_ratio")
        .text(format!(" {} (eta)", short(eta)));
    let span = format!("{LAMBDA_MIN:e}..{LAMBDA_MAX:e}");
    if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&l1) {
        return Err(ZonesError(
            given
                .text(format!(
                    ": the solid zone's stress number lambda_s (1 + rho eta)^(-1/3) = {} is outside {span}, where the two-zone law is solved: give a ",
                    short(l1)
                ))
                .key("lambda")
                .text(" that brings it inside, or no ")
                .key("stress_ratio")
                .text(" and ")
                .key("range_ratio")
                .text(" for the one-zone law, whose ")
                .key("lambda")
                .text(" may be 1e-26..1e26"),
        ));
    }
    let l2 = rho * l1;
    if rho > 0.0 && eta > 0.0 && !(LAMBDA_MIN..=LAMBDA_MAX).contains(&l2) {
        return Err(ZonesError(
            given
                .text(format!(
                    ": the second zone's stress number rho lambda_s (1 + rho eta)^(-1/3) = {} is outside {span}, where the two-zone law is solved: give a ",
                    short(l2)
                ))
                .key("stress_ratio")
                .text(" that brings it inside, or ")
                .key("stress_ratio")
                .text(" 0 for no second zone"),
        ));
    }
    Ok(())
}

/// The scales of a dimensional two-zone problem: total w and the units of section 1 built on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// The total work of adhesion w1 + w2.
    pub w: f64,
    /// The radius unit `(pi w R^2 / K)^(1/3)`.
    pub radius: f64,
    /// The approach unit `(pi^2 w^2 R / K^2)^(1/3)`.
    pub approach: f64,
    /// The load unit `pi w R`.
    pub load: f64,
}

/// The normalised zones and the units of the problem `K, R, (s1, h1), (s2, h2)` (SI or any
/// consistent units): zone i pulls with `s_i` where the gap is below `h_i`.
pub fn dimensional_zones(
    k: f64,
    r: f64,
    s: [f64; 2],
    h: [f64; 2],
) -> Result<(Zones, Units), ZonesError> {
    for (name, v) in [("K", k), ("R", r)] {
        if !v.is_finite() || v <= 0.0 {
            return Err(ZonesError::text(format!(
                "{name} = {} must be a finite number > 0",
                short(v)
            )));
        }
    }
    for i in 0..2 {
        if !s[i].is_finite() || s[i] < 0.0 || !h[i].is_finite() || h[i] < 0.0 {
            return Err(ZonesError::text(format!(
                "zone {}: stress {} and range {} must be finite numbers >= 0",
                i + 1,
                short(s[i]),
                short(h[i])
            )));
        }
    }
    let w = s[0] * h[0] + s[1] * h[1];
    if w <= 0.0 {
        return Err(ZonesError(
            "no adhesion: give at least one zone a stress and a range > 0".into(),
        ));
    }
    let units = Units {
        w,
        radius: (PI * w * r * r / k).cbrt(),
        approach: (PI * PI * w * w * r / (k * k)).cbrt(),
        load: PI * w * r,
    };
    let lam = |si: f64| 2.0 * si * (r / (PI * w * k * k)).cbrt();
    let mut lambda = [lam(s[0]), lam(s[1])];
    let mut range = [h[0] / units.approach, h[1] / units.approach];
    // The conversion rounds; rescale so that the normalised work is 1 to the last bit.
    let tw = 0.5 * PI * (lambda[0] * range[0] + lambda[1] * range[1]);
    for i in 0..2 {
        lambda[i] /= tw.sqrt();
        range[i] /= tw.sqrt();
    }
    Ok((Zones::new(lambda, range)?, units))
}

/// A contact state of the two-zone law. Fields that could not be computed are NaN with a status
/// other than `Ok`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoZoneState {
    /// Contact radius A.
    pub a: f64,
    /// Outer radii C_1 (solid) and C_2 (second zone): where the gap equals each range.
    pub c: [f64; 2],
    /// `C_i / A - 1` to full relative precision (0 for an absent zone): C - A itself, where a
    /// zone is narrow (the JKR end), keeps more digits here than in `c`.
    pub m_minus_1: [f64; 2],
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
    /// Stable under load control.
    pub load_stable: bool,
    /// Stable under displacement control.
    pub displacement_stable: bool,
    /// Whether the state was found.
    pub status: Status,
}

impl TwoZoneState {
    /// No state: every number NaN, with the status that says why.
    pub fn failed(status: Status) -> TwoZoneState {
        TwoZoneState {
            a: f64::NAN,
            c: [f64::NAN; 2],
            m_minus_1: [f64::NAN; 2],
            load: f64::NAN,
            approach: f64::NAN,
            load_stable: false,
            displacement_stable: false,
            status,
        }
    }
}

/// Where a stable branch ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoZonePullOff {
    /// Pbar there.
    pub load: f64,
    /// Contact radius A there.
    pub a: f64,
    /// Dbar there.
    pub approach: f64,
    /// The outer radii there.
    pub c: [f64; 2],
    /// x = ln(mu_L) there; +inf where the contact is lost at zero radius.
    pub x: f64,
}

impl TwoZonePullOff {
    /// The contact is lost at zero radius.
    pub fn at_zero_radius(&self) -> bool {
        self.x == f64::INFINITY
    }
}

/// The curve's parameter `x = ln(mu_L)` at contact radius `a > 0` (two ranges), by bisection
/// (the radius falls as x grows).
pub fn x_at_radius(zones: &Zones, a: f64) -> f64 {
    bisect_sign(
        |x| a - point(zones, x).map_or(f64::NAN, |p| p.a),
        X_FAR,
        X_END,
    )
}

/// The curve of one pair of zones with its pull-offs, for many states.
#[derive(Clone, Debug)]
pub struct TwoZoneContext {
    /// The pair of zones.
    pub zones: Zones,
    md: Option<LambdaContext>,
    /// Load-controlled pull-off: the first minimum of the load from large contact radii.
    pub load_pulloff: TwoZonePullOff,
    /// Displacement-controlled jump-out: the first minimum of the approach (or the A -> 0 end).
    pub disp_pulloff: TwoZonePullOff,
}

fn pulloff_of(p: &TwoZonePoint, x: f64) -> TwoZonePullOff {
    TwoZonePullOff {
        load: p.load,
        a: p.a,
        approach: p.approach,
        c: p.c,
        x,
    }
}

/// The first local minimum of `f` on the grid from X_START, refined by golden section; `None`
/// where `f` falls all the way to X_END (the minimum is the A -> 0 end).
fn first_minimum(f: &dyn Fn(f64) -> f64) -> Result<Option<f64>, Status> {
    let n = ((X_END - X_START) / X_STEP).round() as usize;
    let xs: Vec<f64> = (0..=n).map(|k| X_START + k as f64 * X_STEP).collect();
    let mut prev = f(xs[0]);
    if !prev.is_finite() {
        return Err(Status::NotConverged);
    }
    for k in 1..xs.len() {
        let v = f(xs[k]);
        if !v.is_finite() {
            return Err(Status::NotConverged);
        }
        // A rise within rounding is not a minimum: near the A -> 0 end the curve flattens
        // onto its limit and its last digits are noise.
        if v > prev + 1e-12 * prev.abs().max(1.0) {
            if k == 1 {
                return Err(Status::NotConverged);
            }
            return Ok(Some(GOLDEN.argmin(f, xs[k - 2], xs[k])));
        }
        prev = v;
    }
    Ok(None)
}

impl TwoZoneContext {
    /// Locates both pull-offs; the status says why a pair cannot be solved.
    pub fn new(zones: Zones) -> Result<TwoZoneContext, Status> {
        match zones.shape() {
            Shape::Single { lambda } => {
                let md = LambdaContext::new(lambda).map_err(|_| Status::InvalidInput)?;
                let conv = |p: &super::PullOff| {
                    let c = p.a * (1.0 + p.m_minus_1);
                    let mut cs = [p.a; 2];
                    for (i, ci) in cs.iter_mut().enumerate() {
                        if zones.present(i) {
                            *ci = c;
                        }
                    }
                    TwoZonePullOff {
                        load: p.load,
                        a: p.a,
                        approach: p.approach,
                        c: cs,
                        x: p.x,
                    }
                };
                let mut disp = conv(&md.disp_pulloff());
                if disp.at_zero_radius() {
                    // The MD jump-out at A = 0 carries the zone radius of the curve's end.
                    let end = md.end;
                    for (i, ci) in disp.c.iter_mut().enumerate() {
                        *ci = if zones.present(i) { end.c } else { 0.0 };
                    }
                }
                Ok(TwoZoneContext {
                    zones,
                    load_pulloff: conv(&md.load_pulloff),
                    disp_pulloff: disp,
                    md: Some(md),
                })
            }
            Shape::Two { .. } => {
                let load = |x: f64| point(&zones, x).map_or(f64::NAN, |p| p.load);
                let approach = |x: f64| point(&zones, x).map_or(f64::NAN, |p| p.approach);
                let end = point(&zones, X_END).ok_or(Status::NotConverged)?;
                let at = |x: Option<f64>| -> Result<TwoZonePullOff, Status> {
                    match x {
                        Some(x) => point(&zones, x)
                            .map(|p| pulloff_of(&p, x))
                            .ok_or(Status::NotConverged),
                        None => {
                            let mut p = pulloff_of(&end, f64::INFINITY);
                            p.a = 0.0;
                            Ok(p)
                        }
                    }
                };
                let load_pulloff = at(first_minimum(&load)?)?;
                let disp_pulloff = at(first_minimum(&approach)?)?;
                Ok(TwoZoneContext {
                    zones,
                    md: None,
                    load_pulloff,
                    disp_pulloff,
                })
            }
        }
    }

    fn state_at_x(&self, x: f64) -> TwoZoneState {
        match point(&self.zones, x) {
            Some(p) if p.load.is_finite() && p.approach.is_finite() && p.a > 0.0 => TwoZoneState {
                a: p.a,
                c: p.c,
                m_minus_1: p.mu.map(|m| m * m / (1.0 + (1.0 + m * m).sqrt())),
                load: p.load,
                approach: p.approach,
                load_stable: x <= self.load_pulloff.x,
                displacement_stable: x <= self.disp_pulloff.x,
                status: Status::Ok,
            },
            _ => TwoZoneState::failed(Status::NotConverged),
        }
    }

    fn of_md_state(&self, s: &super::State, a_stable: (bool, bool)) -> TwoZoneState {
        if s.status != Status::Ok {
            return TwoZoneState::failed(s.status);
        }
        let c = s.a * (1.0 + s.m_minus_1);
        let mut cs = [s.a; 2];
        let mut mm = [0.0; 2];
        for i in 0..2 {
            if self.zones.present(i) {
                cs[i] = c;
                mm[i] = s.m_minus_1;
            }
        }
        TwoZoneState {
            a: s.a,
            c: cs,
            m_minus_1: mm,
            load: s.load,
            approach: s.approach,
            load_stable: a_stable.0,
            displacement_stable: a_stable.1,
            status: Status::Ok,
        }
    }

    /// The fold of a spring of normalised stiffness `k` on the contact curve of two ranges:
    /// where the control `Dbar + Pbar / k` stops falling as the contact shrinks, i.e. where
    /// `dPbar/dDbar = -k`, the retract's jump-out under that spring. Searched between the
    /// contact radii `0.8 a_near` and `1.25 a_near` (`a_near` the sampled fold), by bisection
    /// in x on the sign of the control's central difference (step 1e-5 in x: its bias moves the
    /// root by about 1e-11, rounding by less). `None` for one zone (MD's own), or where the
    /// control's slope does not change sign in that range.
    pub fn spring_fold(&self, k: f64, a_near: f64) -> Option<TwoZonePullOff> {
        if self.md.is_some() || !(k > 0.0 && k.is_finite() && a_near > 0.0) {
            return None;
        }
        let x_of = |a: f64| x_at_radius(&self.zones, a);
        let control = |x: f64| point(&self.zones, x).map_or(f64::NAN, |p| p.approach + p.load / k);
        const H: f64 = 1e-5;
        // Negative on the stable side (the control falls as x grows and the contact shrinks).
        let slope = |x: f64| control(x + H) - control(x - H);
        let (lo, hi) = (x_of(1.25 * a_near), x_of(0.8 * a_near));
        if !(slope(lo) < 0.0 && slope(hi) > 0.0) {
            return None;
        }
        let x = bisect_sign(slope, lo, hi);
        let p = point(&self.zones, x)?;
        (p.load.is_finite() && p.approach.is_finite() && p.a > 0.0).then(|| pulloff_of(&p, x))
    }

    /// The state at contact radius `a > 0` (normalised).
    pub fn state_at_radius(&self, a: f64) -> TwoZoneState {
        if !(a.is_finite() && a > 0.0) {
            return TwoZoneState::failed(Status::InvalidInput);
        }
        if let Some(md) = &self.md {
            let r = md.solve_radius(a);
            if r.status != Status::Ok {
                return TwoZoneState::failed(r.status);
            }
            let c = a * (1.0 + r.m_minus_1);
            let mut cs = [a; 2];
            let mut mm = [0.0; 2];
            for i in 0..2 {
                if self.zones.present(i) {
                    cs[i] = c;
                    mm[i] = r.m_minus_1;
                }
            }
            return TwoZoneState {
                a,
                c: cs,
                m_minus_1: mm,
                load: r.load,
                approach: r.approach,
                load_stable: r.load_stable,
                displacement_stable: r.displacement_stable,
                status: Status::Ok,
            };
        }
        let s = self.state_at_x(x_at_radius(&self.zones, a));
        if s.status == Status::Ok && (s.a / a - 1.0).abs() < 1e-10 {
            TwoZoneState { a, ..s }
        } else {
            TwoZoneState::failed(Status::NotConverged)
        }
    }

    /// The stable state under load control at `load` (normalised); `NoContact` below the
    /// pull-off.
    pub fn state_at_load(&self, load: f64) -> TwoZoneState {
        if !load.is_finite() {
            return TwoZoneState::failed(Status::InvalidInput);
        }
        if let Some(md) = &self.md {
            let s = md.solve_load(load);
            let disp_a = if md.lambda <= LAMBDA_D {
                0.0
            } else {
                md.disp_pulloff().a
            };
            return self.of_md_state(&s, (true, s.a >= disp_a));
        }
        self.on_branch(load, self.load_pulloff, |p| p.load)
    }

    /// The stable state under displacement control at `approach` (normalised); `NoContact`
    /// below the jump-out.
    pub fn state_at_approach(&self, approach: f64) -> TwoZoneState {
        if !approach.is_finite() {
            return TwoZoneState::failed(Status::InvalidInput);
        }
        if let Some(md) = &self.md {
            let s = md.solve_approach(approach);
            return self.of_md_state(&s, (s.a >= md.load_pulloff.a, true));
        }
        self.on_branch(approach, self.disp_pulloff, |p| p.approach)
    }

    /// The state on the stable branch from large radii to `end` where `value` equals `target`.
    fn on_branch(
        &self,
        target: f64,
        end: TwoZonePullOff,
        value: impl Fn(&TwoZonePoint) -> f64,
    ) -> TwoZoneState {
        let end_value = value(&TwoZonePoint {
            a: end.a,
            mu: [0.0; 2],
            c: end.c,
            load: end.load,
            approach: end.approach,
        });
        if target < end_value {
            return TwoZoneState::failed(Status::NoContact);
        }
        let hi = if end.at_zero_radius() { X_END } else { end.x };
        if target == end_value {
            return self.state_at_x(hi);
        }
        let f = |x: f64| point(&self.zones, x).map_or(f64::NAN, |p| value(&p) - target);
        let mut lo = hi - 1.0;
        let mut f_lo = f(lo);
        while f_lo.is_finite() && f_lo <= 0.0 && lo > X_FAR {
            lo -= 4.0;
            f_lo = f(lo);
        }
        if !(f_lo > 0.0) {
            return TwoZoneState::failed(Status::NotConverged);
        }
        let f_hi = f(hi);
        if !(f_hi <= 0.0) {
            return TwoZoneState::failed(Status::NotConverged);
        }
        if f_hi == 0.0 {
            return self.state_at_x(hi);
        }
        let r = secant_bracketed(f, (lo, f_lo), (hi, f_hi), 0.5 * (lo + hi), 1e-15, 300);
        let mut s = self.state_at_x(r.x);
        if r.stop != Stop::Converged && s.status == Status::Ok {
            s.status = Status::NotConverged;
        }
        s
    }

    /// The gap at r (normalised) for a contact state of this context.
    pub fn gap(&self, s: &TwoZoneState, r: f64) -> f64 {
        gap(&self.zones, &as_point(s), r)
    }

    /// The pressure at r (normalised, compressive positive) for a contact state.
    pub fn pressure(&self, s: &TwoZoneState, r: f64) -> f64 {
        crate::physics::two_zone::pressure(&self.zones, &as_point(s), r)
    }
}

fn as_point(s: &TwoZoneState) -> TwoZonePoint {
    TwoZonePoint {
        a: s.a,
        mu: [0.0; 2],
        c: s.c,
        load: s.load,
        approach: s.approach,
    }
}

/// A state of the dimensional problem (the units of the inputs): load P (compressive positive),
/// approach delta (Hertz: a^2/R), and the outer radii c1, c2 where the gap equals h1, h2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DimensionalState {
    /// Load P.
    pub load: f64,
    /// Approach delta.
    pub approach: f64,
    /// The solid zone's outer radius.
    pub c1: f64,
    /// The second zone's outer radius.
    pub c2: f64,
    /// Whether the state was found.
    pub status: Status,
}

/// The state at contact radius `a` of a sphere of radius `r` on a half-space of modulus `k`
/// (`K = 4/3 E*`), zone 1 pulling with `s1` where the gap is below `h1` and zone 2 with `s2`
/// below `h2`. A zone without stress still gets its radius (where the gap reaches its range);
/// a zone of zero range has `c = a`.
pub fn state_at_radius_dimensional(
    k: f64,
    r: f64,
    s1: f64,
    h1: f64,
    s2: f64,
    h2: f64,
    a: f64,
) -> Result<DimensionalState, ZonesError> {
    let (zones, u) = dimensional_zones(k, r, [s1, s2], [h1, h2])?;
    if !a.is_finite() || a <= 0.0 {
        return Err(ZonesError::text(format!(
            "a = {a} must be a finite number > 0"
        )));
    }
    let ctx = TwoZoneContext::new(zones).map_err(|st| {
        ZonesError::text(format!("the curve could not be computed ({})", st.name()))
    })?;
    let s = ctx.state_at_radius(a / u.radius);
    if s.status != Status::Ok {
        return Ok(DimensionalState {
            load: f64::NAN,
            approach: f64::NAN,
            c1: f64::NAN,
            c2: f64::NAN,
            status: s.status,
        });
    }
    let h = [h1, h2];
    let mut c = s.c;
    for i in 0..2 {
        if !zones.present(i) {
            c[i] = if h[i] > 0.0 {
                // Where the gap reaches this zone's range: the gap rises monotonically.
                let target = h[i] / u.approach;
                let mut hi = 2.0 * s.a;
                while ctx.gap(&s, hi) < target && hi < 1e12 {
                    hi *= 2.0;
                }
                bisect_sign(|x| ctx.gap(&s, x) - target, s.a, hi)
            } else {
                s.a
            };
        }
    }
    Ok(DimensionalState {
        load: s.load * u.load,
        approach: s.approach * u.approach,
        c1: c[0] * u.radius,
        c2: c[1] * u.radius,
        status: Status::Ok,
    })
}

/// The pull-offs `(load control, displacement control)` of the dimensional problem, as forces
/// (tensile negative).
pub fn pulloffs_dimensional(
    k: f64,
    r: f64,
    s: [f64; 2],
    h: [f64; 2],
) -> Result<(f64, f64), ZonesError> {
    let (zones, u) = dimensional_zones(k, r, s, h)?;
    let ctx = TwoZoneContext::new(zones).map_err(|st| {
        ZonesError::text(format!("the curve could not be computed ({})", st.name()))
    })?;
    Ok((
        ctx.load_pulloff.load * u.load,
        ctx.disp_pulloff.load * u.load,
    ))
}
