//! Shared test helpers: the reference tables (copied from the 50-digit reference, see
//! data/README.md) and the named tolerances of the accuracy contract.
#![allow(dead_code)]

use std::collections::HashMap;

/// Relative error of A and m-1, and error of Dbar relative to max(1, |Dbar|), away from pull-off.
pub const F64_TOL: f64 = 1e-12;
/// Closer than 1e-6 to the pull-off the bound is F64_TOL + F64_NEAR / sqrt(Pbar - Pbar_c).
pub const F64_NEAR: f64 = 1e-15;
/// Pull-off load and A under both controls.
pub const PULLOFF_TOL: f64 = 1e-12;

pub fn bound(load: f64, pulloff: f64) -> f64 {
    let gap = load - pulloff;
    if gap >= 1e-6 {
        F64_TOL
    } else {
        F64_TOL + F64_NEAR / gap.max(1e-300).sqrt()
    }
}

pub type Row = HashMap<String, String>;

pub fn table(name: &str) -> Vec<Row> {
    let path = format!("{}/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let mut rdr = csv::Reader::from_path(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let headers = rdr.headers().unwrap().clone();
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            headers
                .iter()
                .zip(r.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

pub fn num(row: &Row, col: &str) -> f64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("column {col}: {:?}", row[col]))
}

pub fn rel(x: f64, reference: f64) -> f64 {
    if x == reference {
        0.0
    } else {
        ((x - reference) / reference).abs()
    }
}

/// n points log-spaced from 10^a to 10^b.
pub fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
        .collect()
}
