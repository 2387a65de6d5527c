//! Measured force curves in, as CSV/TSV with a header or as a NumPy `.npz`: columns `segment`
//! (`approach`/`retract`, or 0/1 as afmformats writes it), `height_m` (piezo height of the
//! cantilever base, larger is farther from the sample), `force_n` (positive when repulsive), and
//! optionally `curve` (any id) or `x` and `y` (pixel indices of a force map) to hold many curves.

use crate::law::follow::Direction;
use std::collections::HashMap;

/// One approach-retract curve, points in the order measured.
#[derive(Clone, Debug, Default)]
pub struct Curve {
    /// The curve's id: the `curve` column, else `x,y` of a force map, else `0`.
    pub id: String,
    /// The pixel column in a force map (the `x` column), if given.
    pub x: Option<i64>,
    /// The pixel row in a force map (the `y` column), if given.
    pub y: Option<i64>,
    /// Each point's segment: approach or retract.
    pub segment: Vec<Direction>,
    /// Piezo height of the cantilever base at each point (m), larger farther from the sample.
    pub height: Vec<f64>,
    /// Force at each point (N), positive when repulsive.
    pub force: Vec<f64>,
    /// What reading did to the curve (a dwell left out, one segment split): fit warnings.
    pub notes: Vec<String>,
    /// Why the curve cannot be fitted as read (approach and retract not separated), if so:
    /// it gets the status invalid_input and the others go on.
    pub refused: Option<super::CurveError>,
    /// The dwell between approach and retract, left out of the points (stress relaxation,
    /// creep), if the curve had one: the fit reports it, and fits the approach where the force
    /// relaxed during it.
    pub dwell: Option<super::segments::Dwell>,
}

impl Curve {
    /// The number of points.
    pub fn len(&self) -> usize {
        self.height.len()
    }
    /// Whether the curve has no points.
    pub fn is_empty(&self) -> bool {
        self.height.is_empty()
    }

    /// The curve with the directions of a plan ([`super::segments::plan_segments`]): the
    /// points of pauses and dwells left out, the dwell at the turn kept as [`Curve::dwell`],
    /// the plan's notes as the curve's. `height` and `force` are every point's, as read.
    pub fn with_plan(mut self, plan: super::segments::SegmentPlan) -> Curve {
        self.dwell = super::segments::dwell_at_turn(&plan.direction, &self.height, &self.force);
        let keep: Vec<bool> = plan.direction.iter().map(Option::is_some).collect();
        let pick = |v: &[f64]| -> Vec<f64> {
            v.iter()
                .zip(&keep)
                .filter(|(_, &k)| k)
                .map(|(x, _)| *x)
                .collect()
        };
        self.height = pick(&self.height);
        self.force = pick(&self.force);
        self.segment = plan.direction.into_iter().flatten().collect();
        self.notes = plan.notes;
        self
    }
}

/// The curves of one input, in order of first appearance.
pub type CurveSet = Vec<Curve>;

/// Why an input of force curves could not be read. `path` is the input's name as given.
#[derive(Debug, thiserror::Error)]
pub enum DataError {
    /// The file could not be opened or read.
    #[error("cannot read {path}")]
    Io {
        /// The input.
        path: String,
        /// The error of the read.
        #[source]
        source: std::io::Error,
    },
    /// The CSV/TSV is malformed.
    #[error("{path}")]
    Csv {
        /// The input.
        path: String,
        /// The parser's error.
        #[source]
        source: csv::Error,
    },
    /// A required column is absent.
    #[error("{path}: no column `{column}` (columns: {found}); a force curve needs segment, height_m and force_n")]
    MissingColumn {
        /// The input.
        path: String,
        /// The missing column.
        column: &'static str,
        /// The columns the header has, comma-separated.
        found: String,
    },
    /// A cell is not a valid value of its column.
    #[error("{path}, line {line}: {column} = `{value}` {what}")]
    Value {
        /// The input.
        path: String,
        /// The line of the cell (1 is the header).
        line: u64,
        /// The cell's column.
        column: &'static str,
        /// The cell as read.
        value: String,
        /// What is wrong with it.
        what: &'static str,
    },
    /// The `.npz` archive or one of its arrays is not usable.
    #[error("{path}: {what}")]
    Npz {
        /// The input.
        path: String,
        /// What is wrong.
        what: String,
    },
    /// The input has a header but no data rows.
    #[error("{path}: no data rows")]
    Empty {
        /// The input.
        path: String,
    },
    /// The input exceeds [`POINTS_PER_CURVE_MAX`] or [`POINTS_MAX`].
    #[error("{path}: {what}")]
    TooLarge {
        /// The input.
        path: String,
        /// Which limit was passed.
        what: String,
    },
}

/// Most points of one curve (an AFM curve has 1e3..1e5) and of one input: beyond them the
/// input is refused, so that memory stays bounded (17 bytes a point).
pub const POINTS_PER_CURVE_MAX: usize = 10_000_000;
/// Most points of one input, all its curves together (see [`POINTS_PER_CURVE_MAX`]).
pub const POINTS_MAX: usize = 50_000_000;

trait ReadSeek: std::io::Read + std::io::Seek {}
impl<T: std::io::Read + std::io::Seek> ReadSeek for T {}

/// The zip local-file header: an NPZ, whatever its name.
const ZIP_MAGIC: &[u8; 4] = b"PK\x03\x04";

/// A segment cell as an id: 0 approach, 1 retract (or their names), or the instrument's own
/// number (a pause, a dwell: resolved from the heights, see [`super::segments`]).
fn segment_of(s: &str) -> Option<i64> {
    match s.trim().to_ascii_lowercase().as_str() {
        "approach" | "extend" | "trace" => Some(0),
        "retract" | "retrace" => Some(1),
        v => v.parse::<i64>().ok().filter(|&i| (0..=1000).contains(&i)),
    }
}

/// Directions from the segment ids: 0 and 1 as they are; a curve with any other id has its
/// approach and retract taken from its heights (dwells left out, with a note), or is refused
/// with the reason where they cannot be told apart.
fn resolve_segments(mut c: Curve, ids: &[i64]) -> Curve {
    if ids.iter().all(|&i| i == 0 || i == 1) {
        c.segment = ids
            .iter()
            .map(|&i| {
                if i == 0 {
                    Direction::Approach
                } else {
                    Direction::Retract
                }
            })
            .collect();
        return c;
    }
    match super::segments::plan_segments(&c.height, ids) {
        Err(m) => {
            c.segment = vec![Direction::Approach; ids.len()];
            c.refused = Some(m);
            c
        }
        Ok(plan) => c.with_plan(plan),
    }
}

/// Groups rows into curves by id, in order of first appearance.
#[derive(Default)]
struct Grouper {
    curves: Vec<Curve>,
    /// Each curve's segment ids, resolved into directions by `finish`.
    ids: Vec<Vec<i64>>,
    index: HashMap<String, usize>,
    points: usize,
}

impl Grouper {
    fn push(
        &mut self,
        id: String,
        x: Option<i64>,
        y: Option<i64>,
        seg: i64,
        h: f64,
        f: f64,
    ) -> Result<(), String> {
        self.points += 1;
        if self.points > POINTS_MAX {
            return Err(format!(
                "more than {POINTS_MAX} points: split the input into several files"
            ));
        }
        let k = match self.index.get(&id) {
            Some(&k) => k,
            None => {
                self.curves.push(Curve {
                    id: id.clone(),
                    x,
                    y,
                    ..Default::default()
                });
                self.ids.push(Vec::new());
                self.index.insert(id, self.curves.len() - 1);
                self.curves.len() - 1
            }
        };
        let c = &mut self.curves[k];
        if c.height.len() >= POINTS_PER_CURVE_MAX {
            return Err(format!(
                "curve {} has more than {POINTS_PER_CURVE_MAX} points: is the curve column (or x, y) right?",
                c.id
            ));
        }
        self.ids[k].push(seg);
        c.height.push(h);
        c.force.push(f);
        Ok(())
    }

    /// The curves, each with its directions.
    fn finish(self) -> Vec<Curve> {
        self.curves
            .into_iter()
            .zip(&self.ids)
            .map(|(c, ids)| resolve_segments(c, ids))
            .collect()
    }
}

fn curve_id(curve: Option<&str>, x: Option<i64>, y: Option<i64>) -> String {
    match (curve, x, y) {
        (Some(c), _, _) => c.to_string(),
        (None, Some(x), Some(y)) => format!("{x},{y}"),
        _ => "0".to_string(),
    }
}

/// Reads the curves of a CSV/TSV (`-` is stdin) or `.npz` file.
pub fn read_curves(path: &str) -> Result<CurveSet, DataError> {
    use std::io::BufRead as _;
    let io = |source| DataError::Io {
        path: path.to_string(),
        source,
    };
    // Streamed: only the curves are held, not the file's text; a line over 1 MiB (/dev/zero, a
    // binary file) ends the read.
    let raw: Box<dyn std::io::Read> = if path == "-" {
        Box::new(std::io::stdin())
    } else {
        Box::new(std::fs::File::open(path).map_err(io)?)
    };
    let mut reader = std::io::BufReader::with_capacity(1 << 16, raw);
    // An NPZ by its zip magic, whatever its name (.NPZ, stdin).
    let is_npz = reader.fill_buf().map_err(io)?.starts_with(ZIP_MAGIC);
    if is_npz {
        return read_npz(path, reader);
    }
    parse_csv_reader(path, reader)
}

/// Parses CSV or TSV text held in memory.
pub fn parse_csv(path: &str, text: &[u8]) -> Result<CurveSet, DataError> {
    parse_csv_reader(path, text)
}

/// Parses CSV or TSV from a reader (the delimiter is a tab if the header line has one); `#`
/// lines are comments.
fn parse_csv_reader(path: &str, input: impl std::io::Read) -> Result<CurveSet, DataError> {
    let mut rdr = crate::io::table(input).map_err(|source| DataError::Io {
        path: path.to_string(),
        source,
    })?;
    let csv_err = |source| DataError::Csv {
        path: path.to_string(),
        source,
    };
    let headers = rdr.headers().map_err(csv_err)?.clone();
    for (i, h) in headers.iter().enumerate() {
        if headers.iter().take(i).any(|g| g.eq_ignore_ascii_case(h)) {
            return Err(DataError::Npz {
                path: path.to_string(),
                what: format!(
                    "the column name `{h}` appears twice in the header: rename or remove one"
                ),
            });
        }
    }
    let col = |name: &str| headers.iter().position(|h| h.eq_ignore_ascii_case(name));
    let need = |name: &'static str| {
        col(name).ok_or_else(|| DataError::MissingColumn {
            path: path.to_string(),
            column: name,
            found: headers.iter().collect::<Vec<_>>().join(", "),
        })
    };
    let (cs, ch, cf) = (need("segment")?, need("height_m")?, need("force_n")?);
    let (cc, cx, cy) = (col("curve"), col("x"), col("y"));
    let mut g = Grouper::default();
    for rec in rdr.records() {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map_or(0, |p| p.line());
        let value = |c: usize| rec.get(c).unwrap_or("");
        let err = |column: &'static str, c: usize, what: &'static str| DataError::Value {
            path: path.to_string(),
            line,
            column,
            value: value(c).to_string(),
            what,
        };
        let seg = segment_of(value(cs)).ok_or_else(|| {
            err(
                "segment",
                cs,
                "is not approach/retract, 0/1, or an instrument's segment number (0..1000)",
            )
        })?;
        // Non-finite numbers are kept: the curve gets a status, the others go on.
        let num = |column, c| {
            let v = value(c);
            if v.is_empty() {
                return Ok(f64::NAN);
            }
            v.parse::<f64>()
                .map_err(|_| err(column, c, "is not a number"))
        };
        let h = num("height_m", ch)?;
        let f = num("force_n", cf)?;
        let int = |column, c: Option<usize>| -> Result<Option<i64>, DataError> {
            c.map(|c| {
                value(c)
                    .parse::<i64>()
                    .map_err(|_| err(column, c, "is not an integer pixel index"))
            })
            .transpose()
        };
        let (x, y) = (int("x", cx)?, int("y", cy)?);
        g.push(curve_id(cc.map(value), x, y), x, y, seg, h, f)
            .map_err(|what| DataError::TooLarge {
                path: path.to_string(),
                what,
            })?;
    }
    if g.curves.is_empty() {
        return Err(DataError::Empty {
            path: path.to_string(),
        });
    }
    Ok(g.finish())
}

/// One column of an NPZ file, `name.npy`, as f64 (None where the file has no such member):
/// its declared and read sizes bounded, its CRC checked, 1-D (or a vector stored as 2-D).
fn npz_column(
    ar: &mut zip::ZipArchive<Box<dyn ReadSeek>>,
    path: &str,
    name: &str,
) -> Result<Option<Vec<f64>>, DataError> {
    use std::io::Read as _;
    let npz_err = |what: String| DataError::Npz {
        path: path.to_string(),
        what,
    };
    let mut member = match ar.by_name(&format!("{name}.npy")) {
        Ok(m) => m,
        Err(zip::result::ZipError::FileNotFound) => return Ok(None),
        Err(e) => return Err(npz_err(format!("array {name}: {e}"))),
    };
    // The declared size first (a zip bomb declares its size), then at most that much read:
    // reading to the end checks the member's CRC.
    let cap = 8 * POINTS_MAX as u64 + 4096;
    if member.size() > cap {
        return Err(DataError::TooLarge {
            path: path.to_string(),
            what: format!(
                "array {name} unpacks to {} bytes: at most {POINTS_MAX} points are read",
                member.size()
            ),
        });
    }
    let mut bytes = Vec::new();
    (&mut member)
        .take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| {
            npz_err(format!(
                "array {name} is damaged ({e}): the file is corrupt"
            ))
        })?;
    if bytes.len() as u64 > cap {
        return Err(DataError::TooLarge {
            path: path.to_string(),
            what: format!("array {name} unpacks to more than {cap} bytes"),
        });
    }
    let arr = npyz::NpyFile::new(&bytes[..]).map_err(|e| npz_err(format!("array {name}: {e}")))?;
    // One column of values: 1-D, or a vector stored as 2-D; any order reads the same then.
    let shape = arr.shape().to_vec();
    if shape.iter().filter(|&&d| d > 1).count() > 1 {
        return Err(npz_err(format!(
            "array {name} has shape {shape:?}: give each column as a 1-D array"
        )));
    }
    let dtype = arr.dtype();
    let descr = match &dtype {
        npyz::DType::Plain(ts) => ts.to_string(),
        other => other.descr(),
    };
    let v: Result<Vec<f64>, std::io::Error> = match descr.as_str() {
        "<f8" => arr.into_vec::<f64>(),
        "<f4" => arr.into_vec::<f32>().map(|v| v.into_iter().map(f64::from).collect()),
        "<i8" => arr.into_vec::<i64>().map(|v| v.into_iter().map(|x| x as f64).collect()),
        "<i4" => arr.into_vec::<i32>().map(|v| v.into_iter().map(f64::from).collect()),
        "|u1" => arr.into_vec::<u8>().map(|v| v.into_iter().map(f64::from).collect()),
        "|b1" => arr
            .into_vec::<bool>()
            .map(|v| v.into_iter().map(|b| f64::from(u8::from(b))).collect()),
        d => {
            return Err(npz_err(format!(
                "array {name} has dtype {d}: use float64, float32, int64, int32 or bool (segment: 0 approach, 1 retract)"
            )))
        }
    };
    v.map(Some)
        .map_err(|e| npz_err(format!("array {name}: {e}")))
}

fn read_npz(path: &str, mut input: impl std::io::Read) -> Result<CurveSet, DataError> {
    use std::io::Read as _;
    let npz_err = |what: String| DataError::Npz {
        path: path.to_string(),
        what,
    };
    // A zip needs seeking: the file itself, or stdin read into memory (at most 1 GiB).
    let seekable: Box<dyn ReadSeek> = if path == "-" {
        let mut bytes = Vec::new();
        (&mut input)
            .take(1 << 30)
            .read_to_end(&mut bytes)
            .map_err(|source| DataError::Io {
                path: path.to_string(),
                source,
            })?;
        Box::new(std::io::Cursor::new(bytes))
    } else {
        Box::new(std::fs::File::open(path).map_err(|source| DataError::Io {
            path: path.to_string(),
            source,
        })?)
    };
    let mut ar = zip::ZipArchive::new(seekable)
        .map_err(|e| npz_err(format!("not a readable NPZ (zip) file: {e}")))?;
    let names: Vec<String> = ar
        .file_names()
        .map(|n| n.trim_end_matches(".npy").to_string())
        .collect();
    let mut get = |name: &'static str| npz_column(&mut ar, path, name);
    let need = |v: Option<Vec<f64>>, name: &'static str| {
        v.ok_or_else(|| DataError::MissingColumn {
            path: path.to_string(),
            column: name,
            found: names.join(", "),
        })
    };
    let seg = need(get("segment")?, "segment")?;
    let h = need(get("height_m")?, "height_m")?;
    let f = need(get("force_n")?, "force_n")?;
    let (c, x, y) = (get("curve")?, get("x")?, get("y")?);
    let n = h.len();
    for (name, len) in [
        ("segment", Some(seg.len())),
        ("force_n", Some(f.len())),
        ("curve", c.as_ref().map(Vec::len)),
        ("x", x.as_ref().map(Vec::len)),
        ("y", y.as_ref().map(Vec::len)),
    ] {
        if let Some(len) = len {
            if len != n {
                return Err(npz_err(format!(
                    "array {name} has {len} values and height_m {n}: they must be the same length"
                )));
            }
        }
    }
    let mut g = Grouper::default();
    for i in 0..n {
        let s = match seg[i] {
            v if v.fract() == 0.0 && (0.0..=1000.0).contains(&v) => v as i64,
            v => {
                return Err(npz_err(format!(
                    "segment[{i}] = {v}: use 0 for approach and 1 for retract (or the instrument's segment numbers, 0..1000)"
                )))
            }
        };
        let xi = x.as_ref().map(|v| v[i] as i64);
        let yi = y.as_ref().map(|v| v[i] as i64);
        let id = c.as_ref().map(|v| format!("{}", v[i]));
        g.push(curve_id(id.as_deref(), xi, yi), xi, yi, s, h[i], f[i])
            .map_err(|what| DataError::TooLarge {
                path: path.to_string(),
                what,
            })?;
    }
    if g.curves.is_empty() {
        return Err(DataError::Empty {
            path: path.to_string(),
        });
    }
    Ok(g.finish())
}
