//! Adhesion maps (Johnson & Greenwood 1997): a grid over lambda and the load, each point
//! classified into the simplest model whose contact radius is within the tolerance of the exact
//! Maugis-Dugdale one.

use crate::engine::Engine;
use crate::error::Message;
use crate::numeric::grid::axis;
use crate::physics::closed::{dmt_radius, hertz_radius, jkr_radius};
use crate::physics::model::ContactModel;

use crate::physics::md::point;
use crate::solver::context::x_at_radius;
use crate::solver::{LambdaContext, State, Status};
use rayon::prelude::*;
use serde::Serialize;

pub mod tip;

/// The load axis of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadAxis {
    /// Pbar on a log axis (positive loads): the classic map.
    Log,
    /// Pbar - Pbar_c on a log axis: the tensile range down to the pull-off.
    AbovePulloff,
    /// Pbar on a linear axis (tensile loads included).
    Linear,
}

impl LoadAxis {
    /// The axis's load range where none is given: Pbar 1e-3..1e3 (log), a gap of 1e-6..1e3
    /// above the pull-off, Pbar -2..10 (linear: the tensile range and the pull-offs in view).
    pub fn default_range(self) -> (f64, f64) {
        match self {
            LoadAxis::Log => (1e-3, 1e3),
            LoadAxis::AbovePulloff => (1e-6, 1e3),
            LoadAxis::Linear => (-2.0, 10.0),
        }
    }
}

#[derive(Clone, Debug, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
/// An adhesion map's grid and criteria; checked by [`MapSpec::validate`].
pub struct MapSpec {
    /// The smallest lambda (log axis).
    pub lambda_min: f64,
    /// The largest lambda.
    pub lambda_max: f64,
    /// Columns (lambdas).
    pub nx: usize,
    /// The load axis: linear, log, or log above the pull-off.
    pub load_axis: LoadAxis,
    /// The smallest load (or gap above the pull-off) of the axis.
    pub load_min: f64,
    /// The largest.
    pub load_max: f64,
    /// Rows (loads).
    pub ny: usize,
    /// The relative error of A within which a closed form is adequate.
    pub tolerance: f64,
    /// s0/K ratios for the large-deformation lines a/R = 0.1.
    pub strength_ratios: Vec<f64>,
}

/// The simplest adequate model at a point, in the order they are tried.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum Region {
    /// Below the pull-off: no contact.
    NoContact = 0,
    /// Hertz is adequate.
    Hertz = 1,
    /// Bradley's rigid spheres are adequate.
    Rigid = 2,
    /// DMT is adequate.
    Dmt = 3,
    /// JKR is adequate.
    Jkr = 4,
    /// Only Maugis-Dugdale is.
    Md = 5,
    /// The solver could not give a state (not converged, invalid input).
    Failed = 6,
}

impl Region {
    /// Every region, in code order.
    pub const ALL: [Region; 7] = [
        Region::NoContact,
        Region::Hertz,
        Region::Rigid,
        Region::Dmt,
        Region::Jkr,
        Region::Md,
        Region::Failed,
    ];
    /// The region of a code (`self as u8`; bits above 2 ignored, 7 is failed).
    pub fn from_code(c: u8) -> Region {
        Region::ALL[((c & 7) as usize).min(6)]
    }
    /// The contact model of a model's region; None for no contact and failed points.
    pub fn model(self) -> Option<ContactModel> {
        match self {
            Region::Hertz => Some(ContactModel::Hertz),
            Region::Rigid => Some(ContactModel::Rigid),
            Region::Dmt => Some(ContactModel::Dmt),
            Region::Jkr => Some(ContactModel::Jkr),
            Region::Md => Some(ContactModel::Md),
            Region::NoContact | Region::Failed => None,
        }
    }

    /// The name in JSON and NPY legends: the model's name.
    pub fn name(self) -> &'static str {
        match (self, self.model()) {
            (_, Some(m)) => m.name(),
            (Region::NoContact, _) => "no_contact",
            _ => "failed",
        }
    }

    /// The name in figures: the model's label.
    pub fn label(self) -> &'static str {
        match (self, self.model()) {
            (_, Some(m)) => m.label(),
            (Region::NoContact, _) => "no contact",
            _ => "not computed",
        }
    }
}

/// The criteria of one point: relative errors of the closed-form contact radii (NaN where a
/// model has no answer) and the rigid-body measure (pi lambda / 2) max(A^2, |Dbar|).
#[derive(Clone, Copy, Debug)]
pub struct Criteria {
    /// `|A_Hertz/A - 1|`.
    pub err_hertz: f64,
    /// `|A_DMT/A - 1|`.
    pub err_dmt: f64,
    /// `|A_JKR/A - 1|`.
    pub err_jkr: f64,
    /// The rigid-body measure `(pi lambda / 2) max(A^2, |Dbar|)`.
    pub rigid: f64,
}

/// The criteria of a state (lambda, Pbar, A, Dbar).
pub fn criteria(lambda: f64, load: f64, a: f64, approach: f64) -> Criteria {
    let err = |m: Option<f64>| m.map_or(f64::NAN, |am| (am / a - 1.0).abs());
    Criteria {
        err_hertz: err(hertz_radius(load)),
        err_dmt: err(dmt_radius(load)),
        err_jkr: err(jkr_radius(load)),
        rigid: std::f64::consts::FRAC_PI_2 * lambda * (a * a).max(approach.abs()),
    }
}

/// Hertz, then rigid (Bradley), then DMT, then JKR, else MD; no contact below the pull-off.
pub fn classify(s: &State, tol: f64) -> Region {
    match s.status {
        Status::NoContact => return Region::NoContact,
        Status::Ok => {}
        _ => return Region::Failed,
    }
    match adequate(s, tol).trailing_zeros() {
        0 => Region::Hertz,
        1 => Region::Rigid,
        2 => Region::Dmt,
        3 => Region::Jkr,
        _ => Region::Md,
    }
}

/// A state's byte as the device's classification gives it (`shaders/classify.wgsl`): the
/// region in bits 0-2, the adequate models in bits 3-6.
pub fn mark(s: &State, tol: f64) -> u8 {
    classify(s, tol) as u8 | (adequate(s, tol) << 3)
}

/// The models adequate at a solved state, one bit each (0 Hertz, 1 rigid, 2 DMT, 3 JKR); none
/// where the state is not `ok`.
pub fn adequate(s: &State, tol: f64) -> u8 {
    if s.status != Status::Ok {
        return 0;
    }
    // The same tests as `criteria`, on cubes: |A_m / A - 1| <= tol exactly when A_m^3 lies in
    // [(1 - tol)^3 A^3, (1 + tol)^3 A^3], and the closed forms give A_m^3 without a cube root.
    let a3 = s.a * s.a * s.a;
    let (lo, hi) = ((1.0 - tol).powi(3) * a3, (1.0 + tol).powi(3) * a3);
    let within = |m3: f64| m3 >= lo && m3 <= hi;
    let p = s.load;
    let tests = [
        p >= 0.0 && within(p),
        std::f64::consts::FRAC_PI_2 * s.lambda * (s.a * s.a).max(s.approach.abs()) <= tol,
        within(p + 2.0),
        p >= -1.5 && within(p + 3.0 + (9.0 + 6.0 * p).max(0.0).sqrt()),
    ];
    tests
        .iter()
        .enumerate()
        .fold(0, |bits, (m, &t)| bits | ((t as u8) << m))
}

#[derive(Clone, Debug, Serialize)]
/// A line a/R = 0.1 of one strength ratio s0/K: beyond it the small-strain theory is stretched.
pub struct LargeDeformationLine {
    /// s0/K.
    pub strength_ratio: f64,
    /// (lambda, y) where a/R = 0.1; y in the map's load coordinate.
    pub points: Vec<(f64, f64)>,
}

#[derive(Clone, Debug, Default, Serialize)]
/// Where a map's time went (s).
pub struct Timings {
    /// Solving the states.
    pub solve_s: f64,
    /// Classifying and packing them.
    pub classify_s: f64,
    /// Drawing the figure.
    pub render_s: f64,
}

/// A solved and classified adhesion map.
pub struct MapData {
    /// Its grid and criteria.
    pub spec: MapSpec,
    /// The lambda of each column.
    pub lambdas: Vec<f64>,
    /// The load coordinate of each row: Pbar, or Pbar - Pbar_c for `AbovePulloff`.
    pub rows: Vec<f64>,
    /// Load-controlled pull-off of each column.
    pub pulloff: Vec<f64>,
    /// Compact per-point records (row-major, row 0 the lowest load), enough to draw the map:
    /// 13 bytes a point, where whole states took 48.
    pub points: Points,
    /// The simplest adequate model of each point.
    pub regions: Vec<Region>,
    /// A, approach and m - 1 in f64 per point, kept only where asked
    /// ([`ComputeOptions::keep_exact`]: the NPY and full JSON exports, the Python arrays).
    pub exact: Option<Vec<[f64; 3]>>,
    /// Per column and model (Hertz, rigid, DMT, JKR): the lowest row of the top run of rows
    /// where the model is adequate on its own criterion, found from the f64 states.
    pub adequate_from: Vec<[Option<u32>; 4]>,
    /// The GPU's states against the f64 solver on a sample (GPU maps only).
    pub check: Option<crate::engine::CheckReport>,
    /// The a/R = 0.1 lines.
    pub large_deformation: Vec<LargeDeformationLine>,
    /// Where the time went.
    pub timings: Timings,
    /// The tip's shape, for a map of a tip that is not a sphere (`tip::compute_tip`).
    pub tip: Option<crate::physics::tip::Shape>,
}

/// Per-point records for drawing: single precision is ample for colours and contour lines (the
/// regions themselves are classified from the states as solved). Every point's, or where no
/// figure needs them all only those of the contour grid (every `stride`-th row and column,
/// [`trace_stride`]): a map of regions alone then holds a byte a point.
#[derive(Default)]
pub struct Points {
    /// Contact radius A.
    pub a: Vec<f32>,
    /// Dbar.
    pub approach: Vec<f32>,
    /// m - 1.
    pub m_minus_1: Vec<f32>,
    /// [`Status`] codes.
    pub status: Vec<u8>,
    /// Every `stride`-th row and column is kept (1: all).
    pub stride: usize,
    /// Kept columns per row.
    cols: usize,
}

impl Points {
    pub(crate) fn new(nx: usize, ny: usize, stride: usize) -> Points {
        let cols = (nx - 1) / stride + 1;
        let n = cols * ((ny - 1) / stride + 1);
        Points {
            a: Vec::with_capacity(n),
            approach: Vec::with_capacity(n),
            m_minus_1: Vec::with_capacity(n),
            status: Vec::with_capacity(n),
            stride,
            cols,
        }
    }

    /// Whether point (ix, iy) has a record.
    fn keeps(&self, ix: usize, iy: usize) -> bool {
        ix % self.stride == 0 && iy % self.stride == 0
    }

    /// The record of point `i` of a grid of `nx` columns: its own where kept, else the one of
    /// the contour grid's point below and left of it.
    fn slot(&self, i: usize, nx: usize) -> usize {
        (i / nx / self.stride) * self.cols + (i % nx) / self.stride
    }

    fn push(&mut self, s: &State) {
        self.a.push(s.a as f32);
        self.approach.push(s.approach as f32);
        self.m_minus_1.push(s.m_minus_1 as f32);
        self.status.push(s.status as u8);
    }

    /// Appends the records kept of `states`, the points from `first` of a grid of `nx` columns.
    fn extend(&mut self, states: &[State], first: usize, nx: usize) {
        debug_assert_eq!(first % nx, 0);
        for (r, row) in states.chunks(nx).enumerate() {
            if (first / nx + r) % self.stride == 0 {
                row.iter().step_by(self.stride).for_each(|s| self.push(s));
            }
        }
    }
}

/// The stride of the grid on which figures trace their contour lines (about 800 points a
/// side: finer lines would not show).
pub fn trace_stride(nx: usize, ny: usize) -> usize {
    nx.max(ny).div_ceil(800).max(1)
}

/// The top run of adequate rows per column and model, carried row by row from the bottom:
/// `from[ix][m]` is the lowest row of the unbroken run of rows, up to the last one seen, where
/// model m is adequate (None where the last row is not). `marks` are whole rows of [`mark`]
/// bytes starting at row `first_row`; columns are carried in parallel.
fn extend_adequate_runs(from: &mut [[Option<u32>; 4]], marks: &[u8], first_row: usize) {
    let nx = from.len();
    const COLS: usize = 256;
    from.par_chunks_mut(COLS).enumerate().for_each(|(c, cols)| {
        for (k, row) in marks.chunks(nx).enumerate() {
            let iy = (first_row + k) as u32;
            for (j, f) in cols.iter_mut().enumerate() {
                let bits = row[c * COLS + j] >> 3;
                for (m, f) in f.iter_mut().enumerate() {
                    *f = if bits & (1 << m) != 0 {
                        f.or(Some(iy))
                    } else {
                        None
                    };
                }
            }
        }
    });
}

/// What [`compute_with`] keeps besides the compact records.
#[derive(Clone, Copy, Debug)]
pub struct ComputeOptions {
    /// Keep A, approach and m - 1 in f64 (24 bytes a point).
    pub keep_exact: bool,
    /// GPU maps: re-solve this many evenly spread points with the f64 solver.
    pub check: usize,
    /// Keep every point's compact record (maps of a quantity, [`MapData::drawn`] at any
    /// point); else only the contour grid's, and on a GPU the map is classified on the device
    /// (a byte a point read back). Kept anyway with `keep_exact`.
    pub records: bool,
}

impl ComputeOptions {
    /// Whether every point's values are held (the size limit [`MAX_MAP_POINTS`] applies).
    pub fn holds_values(&self) -> bool {
        self.records || self.keep_exact
    }
}

impl Default for ComputeOptions {
    fn default() -> Self {
        ComputeOptions {
            keep_exact: true,
            check: 1000,
            records: true,
        }
    }
}

#[derive(Debug, thiserror::Error)]
/// Why a map was not computed.
#[non_exhaustive]
pub enum MapError {
    #[error("{0}")]
    /// A bad grid or criterion (the message names the quantity).
    Spec(Message),
    #[error(transparent)]
    /// The GPU failed.
    Engine(#[from] crate::engine::EngineError),
}

impl crate::error::Named for MapError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            MapError::Spec(m) => m.named(names),
            MapError::Engine(e) => e.named(names),
        }
    }
}

/// Most points a map holds (its compact records stay in memory for drawing).
pub const MAX_MAP_POINTS: usize = 4096 * 4096;
/// Smallest load (or gap above the pull-off) of a log load axis.
pub const LOG_LOAD_MIN: f64 = 1e-15;

impl MapSpec {
    /// The grid's lambdas (log) and its rows' load coordinates (log but on the linear axis).
    pub fn axes(&self) -> (Vec<f64>, Vec<f64>) {
        (
            axis(self.lambda_min, self.lambda_max, self.nx, true),
            axis(
                self.load_min,
                self.load_max,
                self.ny,
                self.load_axis != LoadAxis::Linear,
            ),
        )
    }

    /// A spec from JSON (the Python binding's), `load_min` and `load_max` taken from the
    /// axis's [`LoadAxis::default_range`] where absent or null; not yet validated.
    pub fn from_json(json: &str) -> Result<MapSpec, MapError> {
        let bad =
            |e: serde_json::Error| MapError::Spec(format!("not a valid map spec: {e}").into());
        let mut v: serde_json::Value = serde_json::from_str(json).map_err(bad)?;
        if let Some(o) = v.as_object_mut() {
            let axis: LoadAxis = o
                .get("load_axis")
                .map(|a| serde_json::from_value(a.clone()))
                .transpose()
                .map_err(bad)?
                .unwrap_or(LoadAxis::Log);
            let (lo, hi) = axis.default_range();
            for (key, default) in [("load_min", lo), ("load_max", hi)] {
                if o.get(key).is_none_or(|x| x.is_null()) {
                    o.insert(key.into(), default.into());
                }
            }
        }
        serde_json::from_value(v).map_err(bad)
    }

    /// One clear line for a bad value, naming the quantity; a map that holds every point's
    /// values (as the default [`ComputeOptions`] do) at most [`MAX_MAP_POINTS`] points.
    pub fn validate(&self) -> Result<(), MapError> {
        self.validate_with(&ComputeOptions::default())
    }

    /// As [`MapSpec::validate`], for a map computed with `opts`: one of regions alone
    /// ([`ComputeOptions::holds_values`] false) takes up to 16384 x 16384 points.
    pub fn validate_with(&self, opts: &ComputeOptions) -> Result<(), MapError> {
        use crate::physics::domain::{check_lambda_range, short, LOAD_MAX};
        let bad = |m: Message| Err(MapError::Spec(m));
        check_lambda_range(self.lambda_min, self.lambda_max).map_err(MapError::Spec)?;
        if self.nx < 2 || self.ny < 2 || self.nx > 16384 || self.ny > 16384 {
            return bad(Message::new()
                .key("nx")
                .text(" and ")
                .key("ny")
                .text(format!(
                    " must be in 2..=16384, got {} and {}",
                    self.nx, self.ny
                )));
        }
        if opts.holds_values() && self.nx * self.ny > MAX_MAP_POINTS {
            return bad(Message::new()
                .key("nx")
                .text(format!(" {} x ", self.nx))
                .key("ny")
                .text(format!(
                    " {} is {} points, more than the {MAX_MAP_POINTS} (4096 x 4096) a map holds in memory (about 300 MB, or 700 MB with ",
                    self.ny,
                    self.nx * self.ny
                ))
                .phrase("keep_exact", "the f64 values kept as NPY files or full JSON")
                .text(")")
                .phrase(
                    "regions_alone",
                    ", a map of regions alone (records and keep_exact off) up to 16384 x 16384",
                )
                .text("; use fewer points, or split the range into several maps"));
        }
        let (load_min, load_max) = (short(self.load_min), short(self.load_max));
        if !(self.load_max > self.load_min
            && self.load_min.is_finite()
            && self.load_max.is_finite())
        {
            return bad(Message::new()
                .key("load_min")
                .text(" must be below ")
                .key("load_max")
                .text(format!(", got {load_min} and {load_max}")));
        }
        let (lo, hi, range) = match self.load_axis {
            LoadAxis::Linear => (-LOAD_MAX, LOAD_MAX, "-1e12..1e12"),
            _ => (LOG_LOAD_MIN, LOAD_MAX, "1e-15..1e12"),
        };
        if self.load_axis != LoadAxis::Linear && self.load_min <= 0.0 {
            return bad(Message::new()
                .text("a log load axis needs ")
                .key("load_min")
                .text(format!(" > 0 (got {load_min}); use "))
                .phrase("load_axis=linear", "the linear load axis")
                .text(" for tensile loads"));
        }
        if !(self.load_min >= lo && self.load_max <= hi) {
            return bad(Message::new()
                .key("load_min")
                .text(format!(" {load_min} and "))
                .key("load_max")
                .text(format!(
                    " {load_max} must lie within {range} on this load axis (the solver's domain); narrow the range"
                )));
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad(Message::new()
                .key("tolerance")
                .text(format!(" must be in (0, 1), got {}", self.tolerance)));
        }
        if self
            .strength_ratios
            .iter()
            .any(|r| !(*r > 0.0 && r.is_finite()))
        {
            return bad(Message::new()
                .key("strength_ratio")
                .text(" values must be > 0"));
        }
        Ok(())
    }
}

/// Per lambda, the load-controlled pull-off; and the large-deformation lines of the spec's
/// strength ratios.
fn per_lambda_lines(
    spec: &MapSpec,
    lambdas: &[f64],
    ctx: &[Option<crate::solver::LambdaContext>],
) -> (Vec<f64>, Vec<LargeDeformationLine>) {
    let pulloff = ctx
        .iter()
        .map(|c| c.as_ref().map_or(f64::NAN, |c| c.load_pulloff.load))
        .collect();
    let lines = spec
        .strength_ratios
        .iter()
        .map(|&q| LargeDeformationLine {
            strength_ratio: q,
            points: large_deformation_line(spec, lambdas, ctx, q),
        })
        .collect();
    (pulloff, lines)
}

/// Solves and classifies a map on the given engine, keeping the f64 values and checking a GPU
/// map on 1000 points (see [`compute_with`]).
pub fn compute(spec: &MapSpec, engine: &Engine) -> Result<MapData, MapError> {
    compute_with(spec, engine, ComputeOptions::default())
}

/// Solves and classifies a map in bands of rows: each band's states are classified (regions,
/// model thresholds, the GPU cross-check sample) and packed into compact records, so memory is
/// the records plus one band, whatever the grid. On a GPU, a map that needs no record of every
/// point is solved and classified on the device, which sends back a byte a point and the
/// states of the contour grid and the cross-check's sample.
pub fn compute_with(
    spec: &MapSpec,
    engine: &Engine,
    opts: ComputeOptions,
) -> Result<MapData, MapError> {
    spec.validate_with(&opts)?;
    let t0 = std::time::Instant::now();
    let (nx, ny) = (spec.nx, spec.ny);
    let (lambdas, rows) = spec.axes();
    let ctx = crate::engine::contexts(&lambdas);
    let n = nx * ny;
    let on_device =
        !opts.holds_values() && spec.load_axis != LoadAxis::AbovePulloff && engine.classifies();
    let is_gpu = !matches!(engine, Engine::Cpu);
    let checks = if is_gpu { opts.check.min(n) } else { 0 };
    let stride = if opts.holds_values() {
        1
    } else {
        trace_stride(nx, ny)
    };
    let mut acc = Bands {
        points: Points::new(nx, ny, stride),
        regions: Vec::with_capacity(n),
        exact: opts.keep_exact.then(|| Vec::with_capacity(n)),
        adequate_from: vec![[None; 4]; nx],
        check_at: (0..checks).map(|k| k * n / checks).collect(),
        sample: Vec::new(),
    };
    let grid = Grid {
        spec,
        engine,
        ctx: &ctx,
        lambdas: &lambdas,
    };
    // Bands of about 2^18 points on the CPU (a progress bar), 2^20 on a GPU (fewer dispatches),
    // 2^24 classified on the device (a byte a point comes back: 16 MB a band).
    let band = match (is_gpu, on_device) {
        (_, true) => 1 << 24,
        (true, false) => 1 << 20,
        (false, _) => 1 << 18,
    } / nx
        + 1;
    let mut progress = crate::progress::Progress::new("solving", n as u64, "points");
    let (mut solve_s, mut classify_s) = (t0.elapsed().as_secs_f64(), 0.0);
    for (b, r) in rows.chunks(band).enumerate() {
        crate::interrupt::checkpoint();
        let first = b * band * nx;
        let (ds, dc) = if on_device {
            grid.band_on_device(r, first, &mut acc)?
        } else {
            grid.band_of_states(r, first, &mut acc)?
        };
        solve_s += ds;
        classify_s += dc;
        progress.inc((r.len() * nx) as u64);
    }
    progress.finish();
    let check = is_gpu.then(|| {
        let (points, states): (Vec<_>, Vec<_>) =
            acc.sample.iter().map(|s| ((s.lambda, s.load), *s)).unzip();
        crate::engine::cross_check(
            &points,
            &states,
            crate::solver::Control::Load,
            points.len(),
            crate::engine::GPU_TOLERANCE,
        )
    });
    let t1 = std::time::Instant::now();
    let (pulloff, large_deformation) = per_lambda_lines(spec, &lambdas, &ctx);
    classify_s += t1.elapsed().as_secs_f64();
    Ok(MapData {
        spec: spec.clone(),
        lambdas,
        rows,
        pulloff,
        points: acc.points,
        regions: acc.regions,
        exact: acc.exact,
        adequate_from: acc.adequate_from,
        check,
        large_deformation,
        timings: Timings {
            solve_s,
            classify_s,
            render_s: 0.0,
        },
        tip: None,
    })
}

/// What a map's bands build up.
struct Bands {
    points: Points,
    regions: Vec<Region>,
    exact: Option<Vec<[f64; 3]>>,
    adequate_from: Vec<[Option<u32>; 4]>,
    /// The points of the GPU's cross-check sample (ascending), and their states as solved.
    check_at: Vec<usize>,
    sample: Vec<State>,
}

impl Bands {
    /// The regions and adequate runs of whole rows of marks from point `first`.
    fn take(&mut self, marks: &[u8], first: usize) {
        let nx = self.adequate_from.len();
        self.regions
            .par_extend(marks.par_iter().map(|&m| Region::from_code(m)));
        extend_adequate_runs(&mut self.adequate_from, marks, first / nx);
    }

    /// The cross-check's points among `first..first + len`.
    fn checks_in(&self, first: usize, len: usize) -> &[usize] {
        let lo = self.check_at.partition_point(|&i| i < first);
        let hi = self.check_at.partition_point(|&i| i < first + len);
        &self.check_at[lo..hi]
    }
}

/// A map's grid and where it is solved.
struct Grid<'a> {
    spec: &'a MapSpec,
    engine: &'a Engine,
    ctx: &'a [Option<LambdaContext>],
    lambdas: &'a [f64],
}

impl Grid<'_> {
    /// One band of rows solved into whole states, classified on the CPU; (solve, classify) s.
    fn band_of_states(
        &self,
        rows: &[f64],
        first: usize,
        acc: &mut Bands,
    ) -> Result<(f64, f64), MapError> {
        let (e, nx) = (self.engine, self.lambdas.len());
        let t = std::time::Instant::now();
        let states = match self.spec.load_axis {
            LoadAxis::AbovePulloff => e.solve_grid_gaps_with(self.ctx, self.lambdas, rows),
            _ => e.solve_grid_with(self.ctx, self.lambdas, rows, crate::solver::Control::Load),
        }?;
        let solve_s = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let tol = self.spec.tolerance;
        let marks: Vec<u8> = states.par_iter().map(|s| mark(s, tol)).collect();
        acc.take(&marks, first);
        acc.points.extend(&states, first, nx);
        if let Some(x) = acc.exact.as_mut() {
            x.extend(states.iter().map(|s| [s.a, s.approach, s.m_minus_1]));
        }
        let sample: Vec<State> = acc
            .checks_in(first, states.len())
            .iter()
            .map(|&i| states[i - first])
            .collect();
        acc.sample.extend(sample);
        Ok((solve_s, t.elapsed().as_secs_f64()))
    }

    /// One band of rows solved and classified on the device: a byte a point, and the states of
    /// the contour grid's points and the cross-check's; (solve, classify) s.
    fn band_on_device(
        &self,
        rows: &[f64],
        first: usize,
        acc: &mut Bands,
    ) -> Result<(f64, f64), MapError> {
        let (nx, len) = (self.lambdas.len(), rows.len() * self.lambdas.len());
        let k = acc.points.stride;
        let first_row = first / nx;
        let mut picks: Vec<usize> = (0..rows.len())
            .filter(|r| (first_row + r) % k == 0)
            .flat_map(|r| (0..nx).step_by(k).map(move |ix| r * nx + ix))
            .chain(acc.checks_in(first, len).iter().map(|&i| i - first))
            .collect();
        picks.sort_unstable();
        picks.dedup();
        let t = std::time::Instant::now();
        let tol = self.spec.tolerance;
        let g = self
            .engine
            .classify_grid(self.ctx, self.lambdas, rows, tol, &picks)?;
        let solve_s = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let mut marks = g.marks;
        for (i, s) in &g.on_cpu {
            marks[*i] = mark(s, tol);
        }
        acc.take(&marks, first);
        for (&p, s) in picks.iter().zip(&g.picked) {
            let i = first + p;
            if acc.points.keeps(i % nx, i / nx) {
                acc.points.push(s);
            }
            if acc.check_at.binary_search(&i).is_ok() {
                acc.sample.push(*s);
            }
        }
        Ok((solve_s, t.elapsed().as_secs_f64()))
    }
}

/// a/R = 2 A (s0/K) / lambda = 0.1, i.e. A = 0.05 lambda / (s0/K), on the stable branch.
fn large_deformation_line(
    spec: &MapSpec,
    lambdas: &[f64],
    ctx: &[Option<LambdaContext>],
    ratio: f64,
) -> Vec<(f64, f64)> {
    // Traced at 256 lambdas at most: the line is smooth.
    let step = lambdas.len().div_ceil(256).max(1);
    (0..lambdas.len())
        .into_par_iter()
        .filter(|i| i % step == 0 || *i == lambdas.len() - 1)
        .filter_map(|i| {
            let l = lambdas[i];
            let ctx = ctx[i].as_ref()?;
            let pc = ctx.load_pulloff.load;
            let a = 0.05 * l / ratio;
            if a <= ctx.load_pulloff.a {
                return None;
            }
            let load = point(l, x_at_radius(l, a)).load;
            let y = if spec.load_axis == LoadAxis::AbovePulloff {
                load - pc
            } else {
                load
            };
            (y >= spec.load_min && y <= spec.load_max).then_some((l, y))
        })
        .collect()
}

impl MapData {
    /// The region at column `ix`, row `iy`.
    pub fn region_at(&self, ix: usize, iy: usize) -> Region {
        self.regions[iy * self.spec.nx + ix]
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.regions.len()
    }

    /// No points.
    pub fn is_empty(&self) -> bool {
        self.regions.is_empty()
    }

    /// Pbar at point `i`: the row's load, or the column's pull-off plus the row's gap.
    pub fn load(&self, i: usize) -> f64 {
        let (ix, iy) = (i % self.spec.nx, i / self.spec.nx);
        match self.spec.load_axis {
            LoadAxis::AbovePulloff => self.pulloff[ix] + self.rows[iy],
            _ => self.rows[iy],
        }
    }

    /// The state at point `i`: f64 where the map kept them, else from the compact records
    /// (single precision).
    pub fn state(&self, i: usize) -> State {
        match &self.exact {
            Some(e) => State {
                a: e[i][0],
                approach: e[i][1],
                m_minus_1: e[i][2],
                ..self.drawn(i)
            },
            None => self.drawn(i),
        }
    }

    /// The state at point `i` from the compact records, as figures draw it (the same figure
    /// whether or not the f64 values were kept). A map that kept the contour grid's records
    /// alone (`points.stride > 1`) has them only at its points: elsewhere this is the state of
    /// the grid point below and left of `i`, labelled with `i`'s lambda and load.
    pub fn drawn(&self, i: usize) -> State {
        let j = self.points.slot(i, self.spec.nx);
        let (a, approach, m_minus_1) = (
            self.points.a[j] as f64,
            self.points.approach[j] as f64,
            self.points.m_minus_1[j] as f64,
        );
        State {
            lambda: self.lambdas[i % self.spec.nx],
            load: self.load(i),
            approach,
            a,
            m_minus_1,
            status: Status::from_code(self.points.status[j] as u32),
            iterations: 0,
        }
    }

    /// For each lambda, the lowest load of the top run of rows where each model is adequate on
    /// its own criterion (`None` where it is not adequate even at the largest load).
    pub fn thresholds(&self) -> Vec<serde_json::Value> {
        let nx = self.spec.nx;
        (0..nx)
            .map(|ix| {
                let mut entry = serde_json::json!({ "lambda": self.lambdas[ix], "pulloff_load": self.pulloff[ix] });
                for (k, name) in crate::physics::model::ContactModel::CLOSED_FORMS.map(|m| m.name()).iter().enumerate() {
                    let v = match self.adequate_from[ix][k] {
                        Some(iy) => serde_json::json!(self.load(iy as usize * nx + ix)),
                        None => serde_json::Value::Null,
                    };
                    entry[format!("{name}_adequate_above_load")] = v;
                }
                entry
            })
            .collect()
    }

    /// Each region present and its number of points.
    pub fn region_counts(&self) -> Vec<(Region, usize)> {
        Region::ALL
            .iter()
            .map(|&r| (r, self.regions.iter().filter(|&&x| x == r).count()))
            .filter(|&(_, n)| n > 0)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_json_spec_takes_its_axis_default_loads() {
        let base = r#""lambda_min":0.01,"lambda_max":100,"nx":4,"ny":4,"tolerance":0.05,"strength_ratios":[]"#;
        for (axis, lo, hi) in [
            ("log", 1e-3, 1e3),
            ("above-pulloff", 1e-6, 1e3),
            ("linear", -2.0, 10.0),
        ] {
            let s = MapSpec::from_json(&format!(
                r#"{{{base},"load_axis":"{axis}","load_min":null}}"#
            ))
            .unwrap();
            assert_eq!((s.load_min, s.load_max), (lo, hi), "{axis}");
            assert_eq!(s.load_axis.default_range(), (lo, hi));
        }
        let s = MapSpec::from_json(&format!(
            r#"{{{base},"load_axis":"linear","load_min":-1.5}}"#
        ))
        .unwrap();
        assert_eq!((s.load_min, s.load_max), (-1.5, 10.0));
        let e = MapSpec::from_json(&format!(r#"{{{base},"load_axis":"sideways"}}"#)).unwrap_err();
        assert!(e.to_string().contains("sideways"), "{e}");
    }

    use crate::solver::LambdaContext;

    #[test]
    fn classification_follows_the_limits() {
        let tol = 0.05;
        // Large load, small lambda: Hertz.
        let s = LambdaContext::new(0.01).unwrap().solve_load(1e3);
        assert_eq!(classify(&s, tol), Region::Hertz);
        // Tiny lambda, tensile load: rigid (no deformation compared to the force range).
        let s = LambdaContext::new(1e-5).unwrap().solve_load(-1.9);
        assert_eq!(classify(&s, tol), Region::Rigid);
        // Large lambda near zero load: JKR.
        let s = LambdaContext::new(1e3).unwrap().solve_load(0.1);
        assert_eq!(classify(&s, tol), Region::Jkr);
        // Transition: MD.
        let s = LambdaContext::new(1.0).unwrap().solve_load(-1.0);
        assert_eq!(classify(&s, tol), Region::Md);
        // Below pull-off.
        let s = LambdaContext::new(1.0).unwrap().solve_load(-1.7);
        assert_eq!(classify(&s, tol), Region::NoContact);
    }
}
