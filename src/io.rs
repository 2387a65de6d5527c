//! Input tables and output files: CSV points in, atomic writes out, `-` for stdin/stdout.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum InputError {
    #[error("{source_name}: cannot read: {err}")]
    Read {
        source_name: String,
        err: std::io::Error,
    },
    #[error("{0}: the file is empty; give a header row with the columns `lambda` and `{1}`, then one row per point")]
    Empty(String, &'static str),
    #[error("{source_name}: no column `{column}` in the header (found: {found}); name the columns `lambda` and `{column}`")]
    MissingColumn {
        source_name: String,
        column: &'static str,
        found: String,
    },
    #[error("{source_name}, line {line}: column `{column}`: cannot read {value:?} as a number")]
    Parse {
        source_name: String,
        line: u64,
        column: &'static str,
        value: String,
    },
    #[error("{source_name}, line {line}: column `{column}` is {value}; every value must be a finite number")]
    NotFinite {
        source_name: String,
        line: u64,
        column: &'static str,
        value: f64,
    },
    #[error("{source_name}, line {line}: lambda = {value}; the Maugis parameter must be > 0")]
    Lambda {
        source_name: String,
        line: u64,
        value: f64,
    },
    #[error("{source_name}, line {line}: {err}")]
    Csv {
        source_name: String,
        line: u64,
        err: String,
    },
    #[error("{source_name}: a header row but no data rows")]
    NoRows { source_name: String },
}

/// Reads `(lambda, value)` pairs from CSV with a header row; `value_column` is `load` or
/// `approach`. Other columns are ignored. `-` reads stdin.
pub fn read_points(path: &str, value_column: &'static str) -> Result<Vec<(f64, f64)>, InputError> {
    let source_name = if path == "-" {
        "stdin".to_string()
    } else {
        path.to_string()
    };
    let mut text = String::new();
    let res = if path == "-" {
        std::io::stdin().read_to_string(&mut text)
    } else {
        std::fs::File::open(path).and_then(|mut f| f.read_to_string(&mut text))
    };
    res.map_err(|err| InputError::Read {
        source_name: source_name.clone(),
        err,
    })?;
    parse_points(&text, &source_name, value_column)
}

pub fn parse_points(
    text: &str,
    source_name: &str,
    value_column: &'static str,
) -> Result<Vec<(f64, f64)>, InputError> {
    if text.trim().is_empty() {
        return Err(InputError::Empty(source_name.to_string(), value_column));
    }
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let headers = rdr
        .headers()
        .map_err(|e| InputError::Csv {
            source_name: source_name.into(),
            line: 1,
            err: e.to_string(),
        })?
        .clone();
    let col = |name: &'static str| {
        headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| InputError::MissingColumn {
                source_name: source_name.into(),
                column: name,
                found: headers.iter().collect::<Vec<_>>().join(", "),
            })
    };
    let (il, iv) = (col("lambda")?, col(value_column)?);
    let mut out = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(|e| InputError::Csv {
            source_name: source_name.into(),
            line: e.position().map_or(0, |p| p.line()),
            err: e.to_string(),
        })?;
        let line = rec.position().map_or(0, |p| p.line());
        let get = |i: usize, column: &'static str| -> Result<f64, InputError> {
            let s = rec.get(i).unwrap_or("");
            let v: f64 = s.parse().map_err(|_| InputError::Parse {
                source_name: source_name.into(),
                line,
                column,
                value: s.into(),
            })?;
            if !v.is_finite() {
                return Err(InputError::NotFinite {
                    source_name: source_name.into(),
                    line,
                    column,
                    value: v,
                });
            }
            Ok(v)
        };
        let lambda = get(il, "lambda")?;
        if lambda <= 0.0 {
            return Err(InputError::Lambda {
                source_name: source_name.into(),
                line,
                value: lambda,
            });
        }
        out.push((lambda, get(iv, value_column)?));
    }
    if out.is_empty() {
        return Err(InputError::NoRows {
            source_name: source_name.into(),
        });
    }
    Ok(out)
}

/// A number with 17 significant digits; empty where it could not be computed.
pub fn fmt17(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else if x.is_infinite() {
        if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        }
    } else {
        format!("{x:.16e}")
    }
}

/// A JSON number, or null where it could not be computed.
pub fn json_num(x: f64) -> serde_json::Value {
    if x.is_finite() {
        serde_json::Value::from(x)
    } else {
        serde_json::Value::Null
    }
}

/// Writes the whole output at once: to stdout for `-`, else to a temporary file beside the target
/// that is renamed into place, so a failure never leaves a half-written file.
pub fn write_output(path: &str, bytes: &[u8]) -> anyhow::Result<()> {
    if path == "-" {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes)?;
        out.flush()?;
        return Ok(());
    }
    write_atomic(Path::new(path), bytes)
}

pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    use anyhow::Context;
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path.file_name().context("output path has no file name")?;
    let mut tmp = PathBuf::from(dir);
    tmp.push(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path)
        .with_context(|| format!("cannot move output into place at {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_say_where_and_what() {
        let e = parse_points("lambda,load\n1,0.5\n2,abc\n", "in.csv", "load")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 3") && e.contains("abc"), "{e}");
        let e = parse_points("lambda,x\n1,2\n", "in.csv", "load")
            .unwrap_err()
            .to_string();
        assert!(e.contains("no column `load`"), "{e}");
        let e = parse_points("lambda,load\n-1,2\n", "in.csv", "load")
            .unwrap_err()
            .to_string();
        assert!(e.contains("must be > 0"), "{e}");
        let e = parse_points("lambda,load\n1,NaN\n", "in.csv", "load")
            .unwrap_err()
            .to_string();
        assert!(e.contains("finite"), "{e}");
        assert!(parse_points("", "in.csv", "load").is_err());
        assert!(parse_points("lambda,load\n", "in.csv", "load").is_err());
        let ok = parse_points("id,lambda,load\n7, 1 ,0.5\n", "in.csv", "load").unwrap();
        assert_eq!(ok, vec![(1.0, 0.5)]);
    }

    #[test]
    fn seventeen_digits_round_trip() {
        let x = 0.1 + 0.2;
        assert_eq!(fmt17(x).parse::<f64>().unwrap(), x);
        assert_eq!(fmt17(f64::NAN), "");
    }
}
