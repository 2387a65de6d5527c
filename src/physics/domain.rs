//! The domain where every quantity is computed to its accuracy contract. Outside it the solver
//! returns `invalid_input` and the command line refuses with a message that names the limit; it
//! never extrapolates a number it cannot certify.
//!
//! The exact Maugis-Dugdale solver is certified for lambda in [`LAMBDA_MIN`]..[`LAMBDA_MAX`]
//! against a 50-digit oracle (`tests/reference/md_oracle.py`, `tests/data/md_extended.csv`,
//! `examples/domain_probe.rs` measures it: within 0.41 of the contract's bound over
//! 1e-26..1e26, and the pull-offs within 1.4e-14). Beyond it a state is answered by the
//! closed-form limit (`crate::solver::limits`) only where the limit's difference from MD is
//! below [`LIMIT_TOL`]: JKR above [`LAMBDA_MAX`] (to [`LIMIT_LAMBDA_MAX`]), DMT below
//! [`LAMBDA_MIN`] (from [`LIMIT_LAMBDA_MIN`]); [`method`] says which.

use crate::error::Message;
use serde::Serialize;

/// Smallest Maugis parameter of the exact solver.
pub const LAMBDA_MIN: f64 = 1e-26;
/// Largest Maugis parameter of the exact solver.
pub const LAMBDA_MAX: f64 = 1e26;
/// The DMT limit answers lambda below this (and below [`LAMBDA_MIN`]): its approach differs
/// from MD's by 1.5045 lambda^0.5, 1.5e-13 here (docs/PHYSICS.md section 5.1).
pub const DMT_LIMIT_MAX: f64 = 1e-26;
/// Smallest lambda answered by the DMT limit (a normal double's square root stays normal).
pub const LIMIT_LAMBDA_MIN: f64 = 1e-300;
/// Largest lambda answered by the JKR limit: its m - 1, 3/(4 A lambda^2), stays a normal
/// double up to A = 1e4.
pub const LIMIT_LAMBDA_MAX: f64 = 1e150;
/// A limit answers only where its estimated difference from MD is below this: a tenth of the
/// f64 contract (1e-12).
pub const LIMIT_TOL: f64 = 1e-13;
/// Largest |Pbar| (the normalised load).
pub const LOAD_MAX: f64 = 1e12;
/// Largest |Dbar| (the normalised approach): Dbar ~ Pbar^(2/3) at the largest load.
pub const APPROACH_MAX: f64 = 1e8;
/// Largest contact radius A: A ~ Pbar^(1/3) at the largest load.
pub const RADIUS_MAX: f64 = 1e4;

/// How a state is computed: the exact Maugis-Dugdale solver or a closed-form limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The exact Maugis-Dugdale solver (lambda in its certified domain).
    Md,
    /// DMT's closed form, certified below the exact domain.
    DmtLimit,
    /// JKR's closed form, certified above the exact domain.
    JkrLimit,
}

impl Method {
    /// The name in JSON (`method` fields).
    pub fn name(self) -> &'static str {
        match self {
            Method::Md => "md",
            Method::DmtLimit => "dmt_limit",
            Method::JkrLimit => "jkr_limit",
        }
    }
}

/// The method that answers `lambda`; None outside every domain (NaN, <= 0, or beyond the
/// limits).
pub fn method(lambda: f64) -> Option<Method> {
    if within(lambda, LAMBDA_MIN, LAMBDA_MAX) {
        Some(Method::Md)
    } else if within(lambda, LIMIT_LAMBDA_MIN, DMT_LIMIT_MAX.min(LAMBDA_MIN)) {
        Some(Method::DmtLimit)
    } else if lambda > LAMBDA_MAX && lambda <= LIMIT_LAMBDA_MAX {
        Some(Method::JkrLimit)
    } else {
        None
    }
}

/// The method's name for an output column ("" where lambda has none).
pub fn method_name(lambda: f64) -> &'static str {
    method(lambda).map_or("", Method::name)
}

/// A value outside the domain: what it is, its value and the allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{name} = {} is outside the supported domain {range}: {hint}", short(*.value))]
pub struct DomainError {
    /// The quantity, as the library names it (`lambda`, `load`, ...).
    pub name: &'static str,
    /// The value given.
    pub value: f64,
    /// The allowed range, in words.
    pub range: &'static str,
    /// What to do, or why the range is what it is.
    pub hint: &'static str,
}

pub use crate::error::short;

fn within(x: f64, lo: f64, hi: f64) -> bool {
    x.is_finite() && x >= lo && x <= hi
}

impl DomainError {
    /// The message, naming the quantity by its key.
    pub fn message(&self) -> Message {
        Message::new().key(self.name).text(format!(
            " = {} is outside the supported domain {}: {}",
            short(self.value),
            self.range,
            self.hint
        ))
    }
}

impl crate::error::Named for DomainError {
    fn named(&self, names: crate::error::Names) -> String {
        self.message().named(names)
    }
}

/// The Maugis parameter lambda must lie in [`LAMBDA_MIN`], [`LAMBDA_MAX`] (the exact solver's
/// domain: pull-offs, curves, profiles, cycles, maps and fits need it).
pub fn check_lambda(lambda: f64) -> Result<f64, DomainError> {
    if within(lambda, LAMBDA_MIN, LAMBDA_MAX) {
        Ok(lambda)
    } else {
        Err(DomainError {
            name: "lambda",
            value: lambda,
            range: "1e-26..1e26",
            hint: "outside it the exact solver cannot certify its answer; single states (solve) are answered by the DMT limit for lambda in 1e-300..1e-26 and by the JKR limit for lambda in 1e26..1e150 (method field), where each is within 1e-13 of MD",
        })
    }
}

/// A lambda axis (`lambda_min..lambda_max`, as a map spans it): both ends in the exact
/// solver's domain ([`check_lambda`]) and in order. The message names the end at fault.
pub fn check_lambda_range(lambda_min: f64, lambda_max: f64) -> Result<(), Message> {
    for (name, l) in [("lambda_min", lambda_min), ("lambda_max", lambda_max)] {
        check_lambda(l).map_err(|e| Message::new().key(name).text(format!(": {e}")))?;
    }
    if !(lambda_max > lambda_min) {
        return Err(Message::new()
            .key("lambda_min")
            .text(" must be below ")
            .key("lambda_max")
            .text(format!(
                ", got {} and {}",
                short(lambda_min),
                short(lambda_max)
            )));
    }
    Ok(())
}

/// lambda must have a method ([`method`]): the exact solver's domain or a limit's.
pub fn check_lambda_any(lambda: f64) -> Result<f64, DomainError> {
    match method(lambda) {
        Some(_) => Ok(lambda),
        None => Err(DomainError {
            name: "lambda",
            value: lambda,
            range: "1e-300..1e-26 (DMT limit), 1e-26..1e26 (exact), 1e26..1e150 (JKR limit)",
            hint: "give a finite lambda > 0 in that range",
        }),
    }
}

/// |Pbar| must be at most [`LOAD_MAX`].
pub fn check_load(load: f64) -> Result<f64, DomainError> {
    if within(load, -LOAD_MAX, LOAD_MAX) {
        Ok(load)
    } else {
        Err(DomainError {
            name: "load Pbar",
            value: load,
            range: "-1e12..1e12",
            hint: "give a finite normalised load P / (pi w R) of at most 1e12 in magnitude",
        })
    }
}

/// |Dbar| must be at most [`APPROACH_MAX`].
pub fn check_approach(approach: f64) -> Result<f64, DomainError> {
    if within(approach, -APPROACH_MAX, APPROACH_MAX) {
        Ok(approach)
    } else {
        Err(DomainError {
            name: "approach Dbar",
            value: approach,
            range: "-1e8..1e8",
            hint: "give a finite normalised approach of at most 1e8 in magnitude",
        })
    }
}

/// The contact radius A must lie in (0, [`RADIUS_MAX`]].
pub fn check_radius(a: f64) -> Result<f64, DomainError> {
    if a.is_finite() && a > 0.0 && a <= RADIUS_MAX {
        Ok(a)
    } else {
        Err(DomainError {
            name: "contact radius A",
            value: a,
            range: "(0, 1e4]",
            hint: "give a positive normalised contact radius of at most 1e4",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_inclusive_and_messages_are_short() {
        assert!(check_lambda(1e-26).is_ok() && check_lambda(1e26).is_ok());
        let e = check_lambda(1e-30).unwrap_err().to_string();
        assert!(
            e.contains("lambda = 1e-30") && e.contains("1e-26..1e26"),
            "{e}"
        );
        assert_eq!(method(1e-26), Some(Method::Md));
        assert_eq!(method(1.0000001e26), Some(Method::JkrLimit));
        assert_eq!(method(0.9999999e-26), Some(Method::DmtLimit));
        assert_eq!(method(1e-301), None);
        assert_eq!(method(1e151), None);
        assert_eq!(method(f64::NAN), None);
        assert!(check_lambda_any(1e151)
            .unwrap_err()
            .to_string()
            .contains("1e150"));
        let e = check_lambda(1e300).unwrap_err().to_string();
        assert!(e.contains("lambda = 1e300"), "{e}");
        assert!(check_lambda(f64::NAN).is_err() && check_lambda(-1.0).is_err());
        assert!(check_load(-1e12).is_ok() && check_load(1.0000001e12).is_err());
        assert!(check_approach(f64::INFINITY).is_err());
        assert!(check_radius(0.0).is_err() && check_radius(1e4).is_ok());
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(1.4e21), "1.4e21");
        assert_eq!(short(1.23456789e-30), "1.23457e-30");
        assert_eq!(short(1.3361811461), "1.33618");
        assert_eq!(short(-1234.56789012), "-1234.57");
    }
}
