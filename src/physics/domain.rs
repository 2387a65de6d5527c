//! The domain where every quantity is computed to its accuracy contract. Outside it the solver
//! returns `invalid_input` and the command line refuses with a message that names the limit; it
//! never extrapolates a number it cannot certify.
//!
//! The limits come from the f64 solver: its bracket reaches loads of 1e12 at every lambda in
//! 1e-8..1e8 (`tests/properties.rs` checks the residuals over and beyond these limits), and at
//! 1e-22 or 1e160 the pull-off search meets underflow and overflow.

/// Smallest Maugis parameter.
pub const LAMBDA_MIN: f64 = 1e-8;
/// Largest Maugis parameter.
pub const LAMBDA_MAX: f64 = 1e8;
/// Largest |Pbar| (the normalised load).
pub const LOAD_MAX: f64 = 1e12;
/// Largest |Dbar| (the normalised approach): Dbar ~ Pbar^(2/3) at the largest load.
pub const APPROACH_MAX: f64 = 1e8;
/// Largest contact radius A: A ~ Pbar^(1/3) at the largest load.
pub const RADIUS_MAX: f64 = 1e4;

/// A value outside the domain: what it is, its value and the allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{name} = {} is outside the supported domain {range}: {hint}", short(*.value))]
pub struct DomainError {
    pub name: &'static str,
    pub value: f64,
    pub range: &'static str,
    pub hint: &'static str,
}

/// A number for a message: plain where short, else in e-notation with at most 6 digits (never a
/// 301-digit decimal).
pub fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let trim = |m: &str| -> String {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m.to_string()
        }
    };
    if (1e-4..1e7).contains(&x.abs()) {
        // Six significant digits, plain.
        let decimals = (5 - x.abs().log10().floor() as i32).max(0) as usize;
        return trim(&format!("{x:.decimals$}"));
    }
    let e = format!("{x:.5e}");
    match e.split_once('e') {
        Some((m, p)) => format!("{}e{p}", trim(m)),
        None => e,
    }
}

fn within(x: f64, lo: f64, hi: f64) -> bool {
    x.is_finite() && x >= lo && x <= hi
}

/// The Maugis parameter lambda must lie in [`LAMBDA_MIN`], [`LAMBDA_MAX`].
pub fn check_lambda(lambda: f64) -> Result<f64, DomainError> {
    if within(lambda, LAMBDA_MIN, LAMBDA_MAX) {
        Ok(lambda)
    } else {
        Err(DomainError {
            name: "lambda",
            value: lambda,
            range: "1e-8..1e8",
            hint: "outside it the solver cannot certify its answer; MD tends to DMT/Bradley as lambda -> 0 and to JKR as lambda -> inf, so use those closed forms there",
        })
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
        assert!(check_lambda(1e-8).is_ok() && check_lambda(1e8).is_ok());
        let e = check_lambda(1e-22).unwrap_err().to_string();
        assert!(
            e.contains("lambda = 1e-22") && e.contains("1e-8..1e8"),
            "{e}"
        );
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
