//! Beyond the certified Maugis-Dugdale domain: the closed-form limits, only where their
//! difference from MD is below a tenth of the f64 contract (docs/PHYSICS.md section 5.1).
//!
//! JKR (lambda above [`LAMBDA_MAX`]): at fixed A, MD differs from JKR by terms in lambda^-2,
//! `Pbar_MD - Pbar_JKR = (3/2 A^2 - (13/8) sqrt(3/2) sqrt(A)) / lambda^2`, the same order in
//! Dbar and in the relative m - 1 (whose leading term, `3 / (4 A lambda^2)`, is reported): at
//! lambda > 1e26 below 1e-51, everywhere on both stable branches.
//!
//! DMT (lambda below [`LAMBDA_MIN`](crate::physics::domain::LAMBDA_MIN) = [`DMT_LIMIT_MAX`]): at fixed A, `Pbar_MD - Pbar_DMT = 1.7175 lambda^1.5 -
//! pi lambda A^2` and `Dbar_MD - Dbar_DMT = -(8 / (3 sqrt(pi))) lambda^0.5`, so the limit holds
//! only away from the pull-off (the MD pull-off is at A ~ 2 pi lambda / 3, not 0): a state whose
//! estimated relative error of A exceeds [`LIMIT_TOL`] is `invalid_input`.

use super::{Control, State, Status};
use crate::physics::closed::{jkr_approach, jkr_load};
use crate::physics::domain::{self, Method, DMT_LIMIT_MAX, LAMBDA_MAX, LIMIT_TOL};
use std::f64::consts::PI;

/// `16 (pi/2 - 1) / (3 sqrt(pi))`: the lambda^1.5 term of Pbar_MD - Pbar_DMT at fixed A.
pub const DMT_LOAD_C15: f64 = 1.717_532_490_160_009_3;
/// `8 / (3 sqrt(pi))`: Dbar_DMT - Dbar_MD at fixed A, over lambda^0.5.
pub const DMT_APPROACH_C05: f64 = 1.504_505_556_127_350_2;

/// The state of a (lambda, value) point by the closed-form limit for `lambda`; `None` where
/// lambda has no limit method (inside the MD domain, or outside every domain).
pub fn solve_limit(lambda: f64, value: f64, control: Control) -> Option<State> {
    let method = domain::method(lambda)?;
    let invalid = || match control {
        Control::Load => State::failed(lambda, value, f64::NAN, Status::InvalidInput),
        Control::Displacement => State::failed(lambda, f64::NAN, value, Status::InvalidInput),
    };
    let in_range = match control {
        Control::Load => domain::check_load(value).is_ok(),
        Control::Displacement => domain::check_approach(value).is_ok(),
    };
    if !in_range {
        return Some(invalid());
    }
    Some(match (method, control) {
        (Method::Md, _) => return None,
        (Method::JkrLimit, Control::Load) => jkr_by_load(lambda, value),
        (Method::JkrLimit, Control::Displacement) => jkr_by_approach(lambda, value),
        (Method::DmtLimit, Control::Load) => dmt_by_load(lambda, value),
        (Method::DmtLimit, Control::Displacement) => dmt_by_approach(lambda, value),
    })
}

fn ok(lambda: f64, load: f64, approach: f64, a: f64, m_minus_1: f64) -> State {
    State {
        lambda,
        load,
        approach,
        a,
        m_minus_1,
        status: Status::Ok,
        iterations: 0,
    }
}

/// JKR's m - 1 as lambda -> infinity: mu = sqrt(3 / (2 A)) / lambda, m - 1 = mu^2 / 2, to a
/// relative O(lambda^-2). Divided in steps: lambda^2 overflows above 1e154.
fn jkr_m_minus_1(lambda: f64, a: f64) -> f64 {
    0.75 / a / lambda / lambda
}

fn jkr_by_load(lambda: f64, load: f64) -> State {
    debug_assert!(lambda > LAMBDA_MAX);
    // The MD pull-off is -3/2 - 0.1637 lambda^-2: -3/2 in f64 beyond the MD domain.
    if load < -1.5 {
        return State::failed(lambda, load, f64::NAN, Status::NoContact);
    }
    // 9 + 6 Pbar written as 6 (Pbar + 3/2): exact near the pull-off, where it vanishes.
    let a = (load + 3.0 + (6.0 * (load + 1.5)).sqrt()).cbrt();
    ok(lambda, load, jkr_approach(a), a, jkr_m_minus_1(lambda, a))
}

fn jkr_by_approach(lambda: f64, approach: f64) -> State {
    // The rigid-grip jump-out: the minimum of Dbar = A^2 - (2/3) sqrt(6 A) at A = 6^(-1/3).
    let a_out = 6f64.powf(-1.0 / 3.0);
    if approach < jkr_approach(a_out) {
        return State::failed(lambda, f64::NAN, approach, Status::NoContact);
    }
    // Dbar rises strictly with A above the jump-out: bisection in f64 to the last bit.
    let (mut lo, mut hi) = (a_out, a_out.max(1.0));
    while jkr_approach(hi) < approach {
        hi *= 2.0;
    }
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if jkr_approach(mid) < approach {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a = if (jkr_approach(hi) - approach).abs() < (jkr_approach(lo) - approach).abs() {
        hi
    } else {
        lo
    };
    ok(lambda, jkr_load(a), approach, a, jkr_m_minus_1(lambda, a))
}

/// DMT's m - 1: mu = 2 / (A sqrt(pi lambda)) to a relative O(lambda A^2, lambda^1.5).
fn dmt_m_minus_1(lambda: f64, a: f64) -> f64 {
    let mu = 2.0 / (a * (PI * lambda).sqrt());
    if mu > 1e8 {
        // sqrt(1 + mu^2) - 1 = mu - 1 + 1/(2 mu) - ...; mu^2 may overflow.
        mu - 1.0 + 0.5 / mu
    } else {
        mu * mu / (1.0 + (1.0 + mu * mu).sqrt())
    }
}

/// The estimated relative error of the DMT contact radius A against MD's at the same load:
/// `(pi lambda A^2 - 1.7175 lambda^1.5) / (3 A^3)` in magnitude, bounded term by term.
pub fn dmt_radius_error(lambda: f64, a: f64) -> f64 {
    PI * lambda / (3.0 * a) + DMT_LOAD_C15 * lambda.powf(1.5) / (3.0 * a * a * a)
}

fn dmt_by_load(lambda: f64, load: f64) -> State {
    debug_assert!(lambda <= DMT_LIMIT_MAX);
    // The MD pull-off is -2 + 1.7175 lambda^1.5 > -2: below -2 there is no contact either way.
    if load < -2.0 {
        return State::failed(lambda, load, f64::NAN, Status::NoContact);
    }
    // Exact for loads near -2 (Sterbenz).
    let a = (load + 2.0).cbrt();
    if !(a > 0.0 && dmt_radius_error(lambda, a) <= LIMIT_TOL) {
        // Too close to the pull-off for the limit: not certified.
        return State::failed(lambda, load, f64::NAN, Status::InvalidInput);
    }
    ok(lambda, load, a * a, a, dmt_m_minus_1(lambda, a))
}

/// The estimated relative error of the DMT contact radius against MD's at the same approach:
/// `(4/(3 sqrt(pi))) lambda^0.5 / A^2` (from the shift of Dbar).
pub fn dmt_radius_error_by_approach(lambda: f64, a: f64) -> f64 {
    0.5 * DMT_APPROACH_C05 * lambda.sqrt() / (a * a)
}

fn dmt_by_approach(lambda: f64, approach: f64) -> State {
    // Below Dbar = 0 DMT has no contact while MD has (down to its A -> 0 end at
    // -1.5045 lambda^0.5): neither is certified there.
    if approach <= 0.0 {
        return State::failed(lambda, f64::NAN, approach, Status::InvalidInput);
    }
    let a = approach.sqrt();
    if dmt_radius_error_by_approach(lambda, a) > LIMIT_TOL {
        return State::failed(lambda, f64::NAN, approach, Status::InvalidInput);
    }
    ok(
        lambda,
        a * a * a - 2.0,
        approach,
        a,
        dmt_m_minus_1(lambda, a),
    )
}

/// Why a state of a limit's lambda is `invalid_input` although its value is in range.
pub fn refusal(lambda: f64, control: Control) -> String {
    match control {
        Control::Load => format!(
            "the DMT limit is not certified this close to its pull-off (the estimated relative error of A, pi lambda / (3 A) + 0.57 lambda^1.5 / A^3, exceeds {}); the exact solver covers lambda >= {}",
            domain::short(LIMIT_TOL),
            domain::short(domain::LAMBDA_MIN)
        ),
        Control::Displacement => format!(
            "the DMT limit is not certified at this approach (its approach differs from MD's by 1.5045 lambda^0.5 = {}, so A needs Dbar >= {}); the exact solver covers lambda >= {}",
            domain::short(DMT_APPROACH_C05 * lambda.sqrt()),
            domain::short(0.5 * DMT_APPROACH_C05 * lambda.sqrt() / LIMIT_TOL),
            domain::short(domain::LAMBDA_MIN)
        ),
    }
}

/// Why a contact radius is not solved for a lambda that only a limit answers (the limits
/// answer a load or an approach; a state by its radius is the exact solver's alone).
pub fn radius_refusal(lambda: f64) -> String {
    let limit = match domain::method(lambda) {
        Some(Method::DmtLimit) => "DMT",
        _ => "JKR",
    };
    format!(
        "a state by its contact radius is solved only for lambda in {}..{} (the exact solver); beyond it the {limit} limit answers a load or an approach, not a radius: give a load or an approach instead, or a lambda in that range",
        domain::short(domain::LAMBDA_MIN),
        domain::short(domain::LAMBDA_MAX)
    )
}
