//! Input tables and output files: CSV points in, atomic writes out, `-` for stdin/stdout.

pub mod output;

pub use output::{write_output, Output};

use std::io::Read;
use std::path::Path;

/// Why an input table could not be read: one line naming the file, the line and the column.
#[derive(Debug, thiserror::Error)]
#[allow(missing_docs)] // the fields are the message's parts: file, line, column, value
pub enum InputError {
    #[error("{source_name}: cannot read")]
    /// The file could not be read.
    Read {
        source_name: String,
        #[source]
        err: std::io::Error,
    },
    #[error("{0}: the file is empty; give a header row naming the columns (`lambda` and `{1}`), then one row per point")]
    /// The file is empty.
    Empty(String, &'static str),
    #[error("{source_name}: no column `{column}` in the header (the first line is: {found}); the first line must name the columns, e.g. `{expected}`")]
    /// The header lacks a column.
    MissingColumn {
        source_name: String,
        column: &'static str,
        expected: String,
        found: String,
    },
    #[error("{source_name}, line {line}: column `{column}`: cannot read {value:?} as a number")]
    /// A cell is not a number.
    Parse {
        source_name: String,
        line: u64,
        column: &'static str,
        value: String,
    },
    #[error("{source_name}, line {line}: column `{column}` is {value}; every value must be a finite number")]
    /// A cell is not finite.
    NotFinite {
        source_name: String,
        line: u64,
        column: &'static str,
        value: f64,
    },
    #[error("{source_name}, line {line}: lambda = {value}; the Maugis parameter must be > 0")]
    /// A lambda is not positive.
    Lambda {
        source_name: String,
        line: u64,
        value: f64,
    },
    #[error("{source_name}, line {line}: not a CSV table")]
    /// The table is not CSV.
    Csv {
        source_name: String,
        line: u64,
        #[source]
        err: csv::Error,
    },
    #[error("{source_name}: a header row but no data rows")]
    /// A header without data.
    NoRows { source_name: String },
}

/// Longest line accepted in an input table: a longer one is not a CSV table (`/dev/zero`, a
/// binary file) and would otherwise be buffered without bound.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// A reader that fails on a line longer than [`MAX_LINE_BYTES`].
pub struct LineLimit<R> {
    inner: R,
    since_newline: usize,
}

impl<R> LineLimit<R> {
    /// Wraps a reader.
    pub fn new(inner: R) -> LineLimit<R> {
        LineLimit {
            inner,
            since_newline: 0,
        }
    }
}

impl<R: Read> Read for LineLimit<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            if b == b'\n' {
                self.since_newline = 0;
            } else {
                self.since_newline += 1;
                if self.since_newline > MAX_LINE_BYTES {
                    return Err(std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        format!(
                            "a line longer than {} MiB: this is not a CSV table",
                            MAX_LINE_BYTES >> 20
                        ),
                    ));
                }
            }
        }
        Ok(n)
    }
}

/// The one reader of input tables (`solve` and `fit`): CSV, or TSV if the header line has a
/// tab; `#` lines are comments (also before the header, as afmformats writes them); cells are
/// trimmed; a line over [`MAX_LINE_BYTES`] is an error.
pub type Table<R> =
    csv::Reader<std::io::Chain<std::io::Cursor<Vec<u8>>, std::io::BufReader<LineLimit<R>>>>;

/// Opens an input table (see [`Table`]).
pub fn table<R: Read>(r: R) -> std::io::Result<Table<R>> {
    use std::io::BufRead as _;
    let mut input = std::io::BufReader::with_capacity(1 << 16, LineLimit::new(r));
    // The lines up to the header, to see the delimiter; then the rest streamed behind them.
    let mut head = Vec::new();
    let mut delim = b',';
    loop {
        let start = head.len();
        if input.read_until(b'\n', &mut head)? == 0 {
            break;
        }
        let line = &head[start..];
        if line[0] != b'#' && line.iter().any(|b| !b.is_ascii_whitespace()) {
            if line.contains(&b'\t') {
                delim = b'\t';
            }
            break;
        }
    }
    Ok(csv::ReaderBuilder::new()
        .delimiter(delim)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(std::io::Cursor::new(head).chain(input)))
}

/// `(lambda, value)` rows of a CSV table with a header row, read in chunks so that memory stays
/// bounded whatever the size of the input; `value_column` is `load` or `approach`. Other columns
/// are ignored.
pub struct PointReader {
    rdr: Table<Box<dyn Read + Send>>,
    source_name: String,
    names: (&'static str, &'static str),
    columns: (usize, usize),
    rows: u64,
}

impl PointReader {
    /// Opens `path` (`-` is stdin) and reads its header.
    pub fn open(path: &str, value_column: &'static str) -> Result<PointReader, InputError> {
        PointReader::open_columns(path, ("lambda", value_column))
    }

    /// Any two numeric columns (the first must be > 0 if it is `lambda`).
    pub fn open_columns(
        path: &str,
        names: (&'static str, &'static str),
    ) -> Result<PointReader, InputError> {
        let (source_name, r): (String, Box<dyn Read + Send>) = if path == "-" {
            ("stdin".into(), Box::new(std::io::stdin()))
        } else {
            let f = std::fs::File::open(path).map_err(|err| InputError::Read {
                source_name: path.into(),
                err,
            })?;
            (path.into(), Box::new(f))
        };
        PointReader::new(r, &source_name, names)
    }

    /// A reader of (lambda, value) points from `r`, named `source_name` in messages, with the columns `names`.
    pub fn new(
        r: Box<dyn Read + Send>,
        source_name: &str,
        names: (&'static str, &'static str),
    ) -> Result<PointReader, InputError> {
        let value_column = names.1;
        let mut rdr = table(r).map_err(|err| InputError::Read {
            source_name: source_name.into(),
            err,
        })?;
        let csv_err = |e: csv::Error| csv_error(source_name, e);
        let headers = rdr.headers().map_err(csv_err)?.clone();
        if headers.iter().all(|h| h.is_empty()) {
            return Err(InputError::Empty(source_name.into(), value_column));
        }
        let col = |name: &'static str| {
            headers
                .iter()
                .position(|h| h == name)
                .ok_or_else(|| InputError::MissingColumn {
                    source_name: source_name.into(),
                    column: name,
                    expected: format!("{},{}", names.0, names.1),
                    found: headers.iter().collect::<Vec<_>>().join(", "),
                })
        };
        let columns = (col(names.0)?, col(names.1)?);
        Ok(PointReader {
            rdr,
            source_name: source_name.into(),
            names,
            columns,
            rows: 0,
        })
    }

    /// Bytes of the input read so far (for progress).
    pub fn bytes_read(&self) -> u64 {
        self.rdr.position().byte()
    }

    /// The next at most `max` rows; empty at the end of the input. An input without any data
    /// row is an error.
    pub fn next_chunk(&mut self, max: usize) -> Result<Vec<(f64, f64)>, InputError> {
        let mut out = Vec::with_capacity(max.min(1 << 16));
        let mut rec = csv::StringRecord::new();
        let (il, iv) = self.columns;
        let source_name = self.source_name.as_str();
        while out.len() < max {
            if !self
                .rdr
                .read_record(&mut rec)
                .map_err(|e| csv_error(source_name, e))?
            {
                break;
            }
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
            let first = get(il, self.names.0)?;
            if self.names.0 == "lambda" && first <= 0.0 {
                return Err(InputError::Lambda {
                    source_name: source_name.into(),
                    line,
                    value: first,
                });
            }
            out.push((first, get(iv, self.names.1)?));
        }
        self.rows += out.len() as u64;
        if out.is_empty() && self.rows == 0 {
            return Err(InputError::NoRows {
                source_name: source_name.into(),
            });
        }
        Ok(out)
    }
}

fn csv_error(source_name: &str, e: csv::Error) -> InputError {
    let line = e.position().map_or(0, |p| p.line());
    if e.is_io_error() {
        if let csv::ErrorKind::Io(err) = e.into_kind() {
            return InputError::Read {
                source_name: source_name.into(),
                err,
            };
        }
        unreachable!("is_io_error");
    }
    InputError::Csv {
        source_name: source_name.into(),
        line,
        err: e,
    }
}

/// Reads a whole table (for small inputs; see [`PointReader`] for large ones).
pub fn read_points(path: &str, value_column: &'static str) -> Result<Vec<(f64, f64)>, InputError> {
    PointReader::open(path, value_column)?.next_chunk(usize::MAX)
}

/// The (lambda, value) points of a table in `text`.
pub fn parse_points(
    text: &str,
    source_name: &str,
    value_column: &'static str,
) -> Result<Vec<(f64, f64)>, InputError> {
    if text.trim().is_empty() {
        return Err(InputError::Empty(source_name.to_string(), value_column));
    }
    let bytes: Box<dyn Read + Send> = Box::new(std::io::Cursor::new(text.as_bytes().to_vec()));
    PointReader::new(bytes, source_name, ("lambda", value_column))?.next_chunk(usize::MAX)
}

/// A CSV table in memory with the csv crate: fields quoted where they need it, `\n` line
/// ends. Write records, then take the bytes with [`csv_finish`].
pub fn csv_writer() -> csv::Writer<Vec<u8>> {
    csv::WriterBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new())
}

/// The bytes of a [`csv_writer`].
pub fn csv_finish(w: csv::Writer<Vec<u8>>) -> anyhow::Result<Vec<u8>> {
    w.into_inner()
        .map_err(|e| anyhow::anyhow!("CSV output: {}", e.error()))
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

/// Appends `x` as [`fmt17`] writes it, without allocating (files of millions of rows are
/// formatted on all cores, where per-field allocations would contend for the allocator).
pub fn fmt17_into(buf: &mut Vec<u8>, x: f64) {
    fmt_into(buf, x, 17);
}

/// Appends `x` with `digits` significant digits in e-notation ("inf", "-inf"; nothing for NaN).
pub fn fmt_into(buf: &mut Vec<u8>, x: f64, digits: usize) {
    use std::io::Write;
    if x.is_nan() {
    } else if x.is_infinite() {
        buf.extend_from_slice(if x > 0.0 { b"inf" } else { b"-inf" });
    } else {
        let _ = write!(buf, "{x:.prec$e}", prec = digits.clamp(1, 17) - 1);
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

/// Writes the whole output at once (see [`output::Output`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write_output(path, bytes)
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
