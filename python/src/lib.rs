//! The Python binding: thin wrappers over tabor's library API on flat float64 arrays (the
//! Python layer in `tabor/__init__.py` broadcasts and reshapes). Every call releases the GIL
//! while it works, turns tabor's errors into ValueError with tabor's own message, a panic into
//! RuntimeError instead of an abort, and a Ctrl-C into KeyboardInterrupt within 50 ms (the
//! library's work stopped through `tabor::interrupt`).

use numpy::{IntoPyArray, PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::panic::AssertUnwindSafe;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use tabor::engine::{Backend, Engine, Precision};
use tabor::solver::{Control, LambdaContext, State, Status};

mod dem;
mod rough;

/// How often a call waiting for its work checks for Ctrl-C.
const SIGNAL_POLL: std::time::Duration = std::time::Duration::from_millis(50);

/// Runs `f` on a worker thread while this one waits without the GIL, checking for Ctrl-C every
/// 50 ms: a Ctrl-C raises KeyboardInterrupt at once (the work is told to stop, and whatever it
/// still returns is dropped). Errors become ValueError, panics RuntimeError.
fn run<T: Send + 'static>(
    py: Python<'_>,
    f: impl FnOnce() -> anyhow::Result<T> + Send + 'static,
) -> PyResult<T> {
    // Work interrupted before is still ending (at its next checkpoint): wait for it, so that its
    // request does not stop this one.
    while tabor::interrupt::requested() {
        py.detach(|| std::thread::sleep(SIGNAL_POLL / 5));
        py.check_signals()?;
    }
    let (tx, rx) = std::sync::mpsc::channel();
    let token = tabor::interrupt::Token::new();
    let worker = token.clone();
    std::thread::Builder::new()
        .name("tabor".into())
        .stack_size(8 << 20) // a main thread's, where the work ran before
        .spawn(move || {
            let r = worker.run(|| std::panic::catch_unwind(AssertUnwindSafe(f)));
            let _ = tx.send(r);
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a thread: {e}")))?;
    // The receiver goes into each wait and back (it is Send, not Sync).
    let wait = |rx: Receiver<_>, t| py.detach(move || (rx.recv_timeout(t), rx));
    let mut rx = rx;
    loop {
        let (r, back) = wait(rx, SIGNAL_POLL);
        rx = back;
        match r {
            Ok(r) => {
                py.check_signals()?;
                return outcome(r);
            }
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    token.interrupt();
                    // Usually ends within milliseconds; a slow end goes on in the background.
                    let _ = wait(rx, 20 * SIGNAL_POLL);
                    return Err(e);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "internal error in tabor (please report): the work ended without a result",
                ))
            }
        }
    }
}

/// As [`run`], on this thread, for work on borrowed data (a chunk of the caller's arrays, a map
/// being saved): a Ctrl-C during it raises KeyboardInterrupt when it ends, before any array is
/// made.
fn run_here<T: Send>(py: Python<'_>, f: impl FnOnce() -> anyhow::Result<T> + Send) -> PyResult<T> {
    let r = py.detach(|| std::panic::catch_unwind(AssertUnwindSafe(f)));
    py.check_signals()?;
    outcome(r)
}

/// A result of the library as Python's: its error a ValueError, a panic a RuntimeError.
fn outcome<T>(r: std::thread::Result<anyhow::Result<T>>) -> PyResult<T> {
    match r {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(PyValueError::new_err(py_text(&e))),
        Err(p) if p.is::<tabor::interrupt::Interrupted>() => Err(PyKeyboardInterrupt::new_err(
            "interrupted (Ctrl-C): the work was stopped and nothing returned",
        )),
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!(
                "internal error in tabor (please report): {msg}"
            )))
        }
    }
}

/// Python's names for the library's keys where they are not the library's own words (the
/// keys are the library's quantities, `lambda_min`, and choices, `load_axis=linear`).
const PY_NAMES: &[(&str, &str)] = &[
    ("load_axis=linear", "load_axis=\"linear\""),
    ("keep_exact", "NPY files or save_json(full=True)"),
    // Python's maps keep every point's values: no map of regions alone.
    ("regions_alone", ""),
    ("precision=f32", "precision=\"f32\""),
    ("backend=cpu", "backend=\"cpu\""),
    ("segment", "fit_segment"),
    // A fit's advice to fit the other segment, with the argument that does.
    (
        "segments=approach",
        "the approach segment instead (fit_segment=\"approach\")",
    ),
    (
        "segments=retract",
        "the retract segment instead (fit_segment=\"retract\")",
    ),
];

/// Python's name for a key of the library's, where it has its own.
fn py_name(key: &str) -> Option<&'static str> {
    PY_NAMES.iter().find(|(k, _)| *k == key).map(|(_, p)| *p)
}

/// A library error as Python's ValueError, with Python's names.
fn py_value_error(e: &impl tabor::error::Named) -> PyErr {
    PyValueError::new_err(e.named(&py_name))
}

/// An error as Python says it: the chain of causes as anyhow's `{:#}` joins them, each typed
/// error of the library rendered with Python's names ([`tabor::error::Named`]).
fn py_text(e: &anyhow::Error) -> String {
    e.chain()
        .map(|c| py_named(c, &py_name).unwrap_or_else(|| c.to_string()))
        .collect::<Vec<_>>()
        .join(": ")
}

/// A library error that names quantities, with `names` for its keys; None for any other error.
fn py_named(c: &(dyn std::error::Error + 'static), names: tabor::error::Names) -> Option<String> {
    use tabor::error::Named;
    macro_rules! named {
        ($($t:ty),* $(,)?) => {
            $(if let Some(e) = c.downcast_ref::<$t>() {
                return Some(e.named(names));
            })*
        };
    }
    named!(
        tabor::error::Message,
        tabor::map::MapError,
        tabor::rough::RoughError,
        tabor::physics::params::ParamError,
        tabor::physics::domain::DomainError,
        tabor::solver::SolveError,
        tabor::solver::two_zone::ZonesError,
        tabor::law::LawError,
        tabor::law::two_zone::ContextError,
        tabor::profile::ProfileError,
        tabor::profile::two_zone::TwoZoneProfileError,
        tabor::profile::tip::TipProfileError,
        tabor::profile::spec::LawProfileError,
        tabor::dem::DemError,
        tabor::gpu::GpuError,
    );
    None
}

pub(crate) fn backend_of(s: &str) -> PyResult<Backend> {
    match s {
        "cpu" => Ok(Backend::Cpu),
        "gpu" => Ok(Backend::Gpu),
        "auto" => Ok(Backend::Auto),
        _ => Err(PyValueError::new_err(format!(
            "backend = {s:?}: give \"cpu\", \"gpu\" or \"auto\""
        ))),
    }
}

fn precision_of(s: &str) -> PyResult<Precision> {
    match s {
        "f32" => Ok(Precision::F32),
        "f64" => Ok(Precision::F64),
        _ => Err(PyValueError::new_err(format!(
            "precision = {s:?}: give \"f32\" or \"f64\""
        ))),
    }
}

fn arr<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    v.into_pyarray(py)
}

/// `run`, its result handed to Python as objects (`to_py`).
fn run_py<'py, T: serde::Serialize + Send + 'static>(
    py: Python<'py>,
    f: impl FnOnce() -> anyhow::Result<T> + Send + 'static,
) -> PyResult<Bound<'py, PyAny>> {
    let r = run(py, f)?;
    to_py(py, &r)
}

/// A library result as Python objects, not JSON text: objects become dicts, arrays of numbers
/// NumPy float64 arrays (a missing number, JSON's null for NaN, becomes NaN), other arrays
/// lists, and the scalars Python's own.
fn to_py<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error in tabor: {e}")))?;
    value_to_py(py, &v)
}

fn value_to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match n.as_i64() {
            Some(i) if !n.is_f64() => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(a)
            if a.iter().any(Value::is_number) && a.iter().all(|x| x.is_number() || x.is_null()) =>
        {
            arr(
                py,
                a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect(),
            )
            .into_any()
        }
        Value::Array(a) => {
            let items = a
                .iter()
                .map(|x| value_to_py(py, x))
                .collect::<PyResult<Vec<_>>>()?;
            pyo3::types::PyList::new(py, items)?.into_any()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, value_to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

/// Points per chunk: between chunks the binding checks for Ctrl-C (a chunk takes well under a
/// second on one core) and the working memory stays one chunk's states, whatever the input size.
const CHUNK: usize = 1 << 18;

/// Solves (lambda, value) pairs; `given` is "load" or "approach". Returns a dict of flat
/// arrays and the status codes with their names, plus metadata. The states go straight into the
/// output arrays chunk by chunk, without the GIL; Ctrl-C between chunks raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (lam, value, given, backend, precision, adapter, check))]
#[allow(clippy::too_many_arguments)]
fn solve_points<'py>(
    py: Python<'py>,
    lam: PyReadonlyArray1<'py, f64>,
    value: PyReadonlyArray1<'py, f64>,
    given: &str,
    backend: &str,
    precision: &str,
    adapter: Option<String>,
    check: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let control = match given {
        "load" => Control::Load,
        "approach" => Control::Displacement,
        _ => {
            return Err(PyValueError::new_err(
                "given must be \"load\" or \"approach\"",
            ))
        }
    };
    let (backend, precision) = (backend_of(backend)?, precision_of(precision)?);
    let (lam, value) = (lam.as_slice()?, value.as_slice()?);
    if lam.len() != value.len() {
        return Err(PyValueError::new_err(
            "lambda and the value arrays differ in length",
        ));
    }
    let n = lam.len();
    let (engine, engine_line) = run(py, move || {
        let (mut engine, line) = Engine::select(backend, adapter.as_deref())?;
        engine.set_precision(precision)?;
        Ok((engine, line))
    })?;
    let out_a = PyArray1::<f64>::zeros(py, n, false);
    let out_load = PyArray1::<f64>::zeros(py, n, false);
    let out_approach = PyArray1::<f64>::zeros(py, n, false);
    let out_m = PyArray1::<f64>::zeros(py, n, false);
    let out_code = PyArray1::<u8>::zeros(py, n, false);
    // SAFETY: the arrays were just created here and no other reference to them exists yet.
    let (sa, sl, sp, sm, sc) = unsafe {
        (
            out_a.as_slice_mut()?,
            out_load.as_slice_mut()?,
            out_approach.as_slice_mut()?,
            out_m.as_slice_mut()?,
            out_code.as_slice_mut()?,
        )
    };
    let gpu = matches!(engine, Engine::Gpu(_));
    let mut check_report = tabor::engine::CheckReport::empty(tabor::engine::GPU_TOLERANCE);
    let mut start = 0;
    while start < n {
        let end = (start + CHUNK).min(n);
        let engine = &engine;
        let (lam, value) = (&lam[start..end], &value[start..end]);
        let (a, l, p, m, c) = (
            &mut sa[start..end],
            &mut sl[start..end],
            &mut sp[start..end],
            &mut sm[start..end],
            &mut sc[start..end],
        );
        let report = run_here(py, move || {
            let points: Vec<(f64, f64)> = lam.iter().copied().zip(value.iter().copied()).collect();
            let (s, report) = engine.solve_points_checked(&points, control, check)?;
            for (i, st) in s.iter().enumerate() {
                (a[i], l[i], p[i], m[i], c[i]) =
                    (st.a, st.load, st.approach, st.m_minus_1, st.status as u8);
            }
            Ok(report)
        })?;
        if let Some(r) = report {
            check_report.merge(r);
        }
        py.check_signals()?;
        start = end;
    }
    let meta = serde_json::json!({
        "backend": engine.name(),
        "adapter": engine.adapter(),
        "precision": engine.precision(),
        "cross_check": gpu.then_some(check_report),
    });
    let d = PyDict::new(py);
    d.set_item("A", out_a)?;
    d.set_item("load", out_load)?;
    d.set_item("approach", out_approach)?;
    d.set_item("m_minus_1", out_m)?;
    d.set_item("status_code", out_code)?;
    d.set_item("engine", engine_line)?;
    d.set_item("metadata", value_to_py(py, &meta)?)?;
    Ok(d)
}

/// The curve points at given contact radii, with stability under both controls: as
/// [`solve_points`], chunk by chunk into the output arrays, Ctrl-C checked between chunks.
#[pyfunction]
fn solve_radius<'py>(
    py: Python<'py>,
    lam: PyReadonlyArray1<'py, f64>,
    a: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (lam, radius) = (lam.as_slice()?, a.as_slice()?);
    if lam.len() != radius.len() {
        return Err(PyValueError::new_err(
            "lambda and the radius arrays differ in length",
        ));
    }
    let n = lam.len();
    let out_a = PyArray1::<f64>::zeros(py, n, false);
    let out_load = PyArray1::<f64>::zeros(py, n, false);
    let out_approach = PyArray1::<f64>::zeros(py, n, false);
    let out_m = PyArray1::<f64>::zeros(py, n, false);
    let out_ls = PyArray1::<bool>::zeros(py, n, false);
    let out_ds = PyArray1::<bool>::zeros(py, n, false);
    let out_code = PyArray1::<u8>::zeros(py, n, false);
    // SAFETY: the arrays were just created here and no other reference to them exists yet.
    let (sa, sl, sp, sm, sls, sds, sc) = unsafe {
        (
            out_a.as_slice_mut()?,
            out_load.as_slice_mut()?,
            out_approach.as_slice_mut()?,
            out_m.as_slice_mut()?,
            out_ls.as_slice_mut()?,
            out_ds.as_slice_mut()?,
            out_code.as_slice_mut()?,
        )
    };
    let mut start = 0;
    while start < n {
        let end = (start + CHUNK).min(n);
        let r = start..end;
        let (lam, radius) = (&lam[r.clone()], &radius[r.clone()]);
        let (a, l, p, m) = (
            &mut sa[r.clone()],
            &mut sl[r.clone()],
            &mut sp[r.clone()],
            &mut sm[r.clone()],
        );
        let (ls, ds, c) = (&mut sls[r.clone()], &mut sds[r.clone()], &mut sc[r]);
        run_here(py, move || {
            let points: Vec<(f64, f64)> = lam.iter().copied().zip(radius.iter().copied()).collect();
            for (i, st) in tabor::solver::solve_radius_points(&points)
                .iter()
                .enumerate()
            {
                (a[i], l[i], p[i], m[i]) = (st.a, st.load, st.approach, st.m_minus_1);
                (ls[i], ds[i], c[i]) = (st.load_stable, st.displacement_stable, st.status as u8);
            }
            Ok(())
        })?;
        py.check_signals()?;
        start = end;
    }
    let d = PyDict::new(py);
    d.set_item("A", out_a)?;
    d.set_item("load", out_load)?;
    d.set_item("approach", out_approach)?;
    d.set_item("m_minus_1", out_m)?;
    d.set_item("load_stable", out_ls)?;
    d.set_item("displacement_stable", out_ds)?;
    d.set_item("status_code", out_code)?;
    Ok(d)
}

/// States of a tip's law (`tabor solve --tip`): per row the state given by the load, the
/// approach or the contact radius, in the tip's units, on all cores chunk by chunk.
#[pyfunction]
fn solve_tip<'py>(
    py: Python<'py>,
    tip: &str,
    lam: PyReadonlyArray1<'py, f64>,
    value: PyReadonlyArray1<'py, f64>,
    given: &str,
) -> PyResult<Bound<'py, PyDict>> {
    use tabor::law::{tip, Given};
    let shape = tabor::scene::tip::shape_of(tip).map_err(|e| py_value_error(&e))?;
    // "approach_in": the approach followed without a jump (`Tip::approach_state`), the
    // nanite models' path.
    let given = match given {
        "load" => Some(Given::Load),
        "approach" => Some(Given::Approach),
        "radius" => Some(Given::Radius),
        "approach_in" => None,
        g => return Err(PyValueError::new_err(format!("given = {g:?}"))),
    };
    let (lam, value) = (lam.as_slice()?, value.as_slice()?);
    let n = lam.len().min(value.len());
    let outs: [Bound<'py, PyArray1<f64>>; 4] =
        std::array::from_fn(|_| PyArray1::<f64>::zeros(py, n, false));
    let out_code = PyArray1::<u8>::zeros(py, n, false);
    // SAFETY: the arrays were just created here and no other reference to them exists yet.
    let (mut cols, sc) = unsafe {
        (
            outs.iter()
                .map(|o| o.as_slice_mut())
                .collect::<Result<Vec<_>, _>>()?,
            out_code.as_slice_mut()?,
        )
    };
    let mut start = 0;
    while start < n {
        let end = (start + CHUNK).min(n);
        let r = start..end;
        let (lam, value) = (&lam[r.clone()], &value[r.clone()]);
        let mut parts: Vec<&mut [f64]> = cols.iter_mut().map(|c| &mut c[r.clone()]).collect();
        let code = &mut sc[r];
        run_here(py, move || {
            use rayon::prelude::*;
            let states: Vec<_> = lam
                .par_iter()
                .zip(value)
                .map(|(&l, &v)| match given {
                    Some(g) => tip::solve(shape, l, g, v),
                    None => tip::approach_in(shape, l, v),
                })
                .collect();
            for (i, (status, p)) in states.into_iter().enumerate() {
                let v = p.map_or([f64::NAN; 4], |p| [p.load, p.approach, p.a, p.c]);
                for (k, part) in parts.iter_mut().enumerate() {
                    part[i] = v[k];
                }
                code[i] = status as u8;
            }
            Ok(())
        })?;
        py.check_signals()?;
        start = end;
    }
    let d = PyDict::new(py);
    for (name, o) in ["load", "approach", "A", "C"].into_iter().zip(outs) {
        d.set_item(name, o)?;
    }
    d.set_item("status_code", out_code)?;
    Ok(d)
}

/// The units of a scene's tip (JSON): `length_m`, `approach_m`, `force_n`, `lambda` and the
/// shape in them (`tabor::scene::tip::units_of`).
#[pyfunction]
fn tip_units<'py>(py: Python<'py>, scene_json: String) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        let s: tabor::scene::SceneInput = serde_json::from_str(&scene_json)
            .map_err(|e| anyhow::anyhow!("not a valid scene: {e}"))?;
        Ok(tabor::scene::tip::units_of(&s)?)
    })
}

/// Per lambda, how `solve` answers a load or an approach (`tabor::physics::domain::method`):
/// 1 the exact solver, 2 the DMT limit, 3 the JKR limit, 0 none.
#[pyfunction]
fn method_codes<'py>(
    py: Python<'py>,
    lam: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<u8>>> {
    use tabor::physics::domain::{method, Method};
    let code = |l: f64| match method(l) {
        Some(Method::Md) => 1,
        Some(Method::DmtLimit) => 2,
        Some(Method::JkrLimit) => 3,
        None => 0,
    };
    Ok(lam
        .as_slice()?
        .iter()
        .map(|&l| code(l))
        .collect::<Vec<u8>>()
        .into_pyarray(py))
}

/// The status names, indexed by code.
#[pyfunction]
fn status_names() -> Vec<&'static str> {
    [
        Status::Ok,
        Status::NoContact,
        Status::NotConverged,
        Status::InvalidInput,
    ]
    .iter()
    .map(|s| s.name())
    .collect()
}

/// Pull-offs under both controls for each lambda; raises for a lambda outside the domain.
#[pyfunction]
fn pulloff<'py>(py: Python<'py>, lam: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyDict>> {
    let lam: Vec<f64> = lam.as_slice()?.to_vec();
    let ctx = run(py, move || {
        lam.iter()
            .map(|&l| LambdaContext::new(l).map_err(anyhow::Error::from))
            .collect::<anyhow::Result<Vec<_>>>()
    })?;
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&LambdaContext) -> f64| arr(py, ctx.iter().map(f).collect());
    d.set_item("load_control_load", col(&|c| c.load_pulloff.load))?;
    d.set_item("load_control_A", col(&|c| c.load_pulloff.a))?;
    d.set_item("load_control_approach", col(&|c| c.load_pulloff.approach))?;
    d.set_item("displacement_control_load", col(&|c| c.disp_pulloff().load))?;
    d.set_item("displacement_control_A", col(&|c| c.disp_pulloff().a))?;
    d.set_item(
        "displacement_control_approach",
        col(&|c| c.disp_pulloff().approach),
    )?;
    d.set_item("zero_radius_end_load", col(&|c| c.end.load))?;
    d.set_item("zero_radius_end_approach", col(&|c| c.end.approach))?;
    Ok(d)
}

/// A tip's pull-offs in its units (`tabor pulloff --tip`): per lambda the states at the folds of
/// its contact piece under a dead load and under rigid grips (or its A -> 0 end).
#[pyfunction]
fn pulloff_tip<'py>(
    py: Python<'py>,
    tip: &str,
    lam: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    use tabor::law::{Drive, Tip};
    let shape = tabor::scene::tip::shape_of(tip).map_err(|e| py_value_error(&e))?;
    let lam: Vec<f64> = lam.as_slice()?.to_vec();
    let states = run(py, move || {
        use rayon::prelude::*;
        lam.par_iter()
            .map(|&l| {
                let t = Tip::new(shape, l).map_err(|e| anyhow::anyhow!("lam = {l}: {e}"))?;
                Ok((
                    t.pulloff_state(Drive::DeadLoad),
                    t.pulloff_state(Drive::RigidGrips),
                ))
            })
            .collect::<anyhow::Result<Vec<_>>>()
    })?;
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&(tabor::law::PathPoint, tabor::law::PathPoint)) -> f64| {
        arr(py, states.iter().map(f).collect())
    };
    d.set_item("load_control_load", col(&|s| s.0.load))?;
    d.set_item("load_control_A", col(&|s| s.0.a))?;
    d.set_item("load_control_approach", col(&|s| s.0.approach))?;
    d.set_item("displacement_control_load", col(&|s| s.1.load))?;
    d.set_item("displacement_control_A", col(&|s| s.1.a))?;
    d.set_item("displacement_control_approach", col(&|s| s.1.approach))?;
    Ok(d)
}

/// A closed form elementwise: `model` hertz|dmt|jkr, `what` radius (A from Pbar) or load (Pbar
/// from A); NaN where the model has no answer.
#[pyfunction]
fn closed_form<'py>(
    py: Python<'py>,
    model: &str,
    what: &str,
    x: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    use tabor::physics::closed::{dmt_radius, hertz_radius, jkr_load, jkr_radius};
    let f: fn(f64) -> f64 = match (model, what) {
        ("hertz", "radius") => |p| hertz_radius(p).unwrap_or(f64::NAN),
        ("dmt", "radius") => |p| dmt_radius(p).unwrap_or(f64::NAN),
        ("jkr", "radius") => |p| jkr_radius(p).unwrap_or(f64::NAN),
        ("hertz", "load") => |a| if a >= 0.0 { a * a * a } else { f64::NAN },
        ("dmt", "load") => |a| if a >= 0.0 { a * a * a - 2.0 } else { f64::NAN },
        ("jkr", "load") => |a| if a >= 0.0 { jkr_load(a) } else { f64::NAN },
        _ => {
            return Err(PyValueError::new_err(format!(
                "no closed form {model:?} for {what:?}"
            )))
        }
    };
    Ok(arr(py, x.as_slice()?.iter().map(|&v| f(v)).collect()))
}

/// The MD curve of one lambda as JSON (`tabor curve`'s columns).
#[pyfunction]
fn curve<'py>(py: Python<'py>, lam: f64, a_max: f64, points: usize) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        let c = tabor::solver::curve::curve(lam, a_max, points)?;
        Ok(c)
    })
}

/// A scene (JSON text, or a preset name) solved: `tabor scene --format json`'s report.
#[pyfunction]
#[pyo3(signature = (scene_json=None, preset=None))]
fn scene<'py>(
    py: Python<'py>,
    scene_json: Option<String>,
    preset: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        Ok(tabor::scene::solve(&scene_input(scene_json, preset)?)?)
    })
}

/// A scene from its JSON text or a preset's name.
fn scene_input(
    scene_json: Option<String>,
    preset: Option<String>,
) -> anyhow::Result<tabor::scene::SceneInput> {
    Ok(match (scene_json, preset) {
        (Some(j), None) => {
            serde_json::from_str(&j).map_err(|e| anyhow::anyhow!("not a valid scene: {e}"))?
        }
        (None, Some(p)) => tabor::scene::preset(&p).ok_or_else(|| {
            anyhow::anyhow!(
                "no preset {p:?}; the presets are {}",
                tabor::scene::preset_names().join(", ")
            )
        })?,
        _ => anyhow::bail!("give a scene or a preset name"),
    })
}

/// `tabor humidity`: the pull-off against relative humidity of a scene (JSON) or a preset.
#[pyfunction]
#[pyo3(signature = (scene_json, preset, rh_min, rh_max, points, contact_angle_deg=None))]
fn humidity<'py>(
    py: Python<'py>,
    scene_json: Option<String>,
    preset: Option<String>,
    rh_min: f64,
    rh_max: f64,
    points: usize,
    contact_angle_deg: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        let input = scene_input(scene_json, preset)?;
        Ok(tabor::scene::humidity::sweep_scene(
            &input,
            contact_angle_deg,
            rh_min,
            rh_max,
            points,
        )?)
    })
}

#[pyfunction]
fn presets() -> Vec<&'static str> {
    tabor::scene::preset_names()
}

#[pyfunction]
fn infer_pulloff<'py>(
    py: Python<'py>,
    force: f64,
    radius: f64,
    e_star: f64,
    z0: f64,
) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        Ok(tabor::scene::infer(force, radius, e_star, z0)?)
    })
}

/// `tabor infer --relative-humidity`: the solid's w with the water meniscus taken out.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn infer_pulloff_wet<'py>(
    py: Python<'py>,
    force: f64,
    radius: f64,
    e_star: f64,
    z0: f64,
    relative_humidity: Option<f64>,
    contact_angle_deg: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    run_py(py, move || {
        // The library's check of the two options, as the command line's flags require.
        tabor::scene::wet_options(relative_humidity, contact_angle_deg)
            .and_then(|h| {
                let h = h.ok_or(tabor::physics::params::ParamError::Missing(
                    "give relative_humidity",
                ))?;
                tabor::scene::infer_wet(force, radius, e_star, z0, &h)
            })
            // Named as infer_pulloff's keywords, where a scene names its keys.
            .map_err(|e| {
                anyhow::anyhow!(tabor::error::Named::named(&e, &|key| match key {
                    "humidity.relative_humidity" => Some("relative_humidity"),
                    "humidity.contact_angle_deg" => Some("contact_angle_deg"),
                    _ => None,
                }))
            })
    })
}

#[pyfunction]
fn fit_pairs<'py>(
    py: Python<'py>,
    loads: PyReadonlyArray1<'py, f64>,
    radii: PyReadonlyArray1<'py, f64>,
    radius: f64,
    z0: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let pairs: Vec<(f64, f64)> = loads
        .as_slice()?
        .iter()
        .copied()
        .zip(radii.as_slice()?.iter().copied())
        .collect();
    run_py(py, move || Ok(tabor::scene::fit_pairs(&pairs, radius, z0)?))
}

/// Approach (0), retract (1) or dwell (-1) for each point of a curve whose file numbers its
/// segments its own way, from the heights (`tabor::fit::segments::plan_segments`), and what
/// was done in words.
#[pyfunction]
fn plan_segments(
    py: Python<'_>,
    height: Vec<f64>,
    segment: Vec<i64>,
) -> PyResult<(Vec<i8>, Vec<String>)> {
    use tabor::fit::Direction;
    let plan = run(py, move || {
        tabor::fit::segments::plan_segments(&height, &segment).map_err(anyhow::Error::msg)
    })?;
    let code = |d: &Option<Direction>| match d {
        Some(Direction::Approach) => 0,
        Some(Direction::Retract) => 1,
        None => -1,
    };
    Ok((plan.direction.iter().map(code).collect(), plan.notes))
}

/// Force curves fitted (`tabor fit`): flat arrays of the points with a curve index, the
/// options as JSON; returns the JSON list of per-curve results.
#[pyfunction]
fn fit_curves<'py>(
    py: Python<'py>,
    curve: PyReadonlyArray1<'py, i64>,
    segment: PyReadonlyArray1<'py, i64>,
    height: PyReadonlyArray1<'py, f64>,
    force: PyReadonlyArray1<'py, f64>,
    options_json: String,
) -> PyResult<Bound<'py, PyAny>> {
    let (c, s, h, f) = (
        curve.as_slice()?.to_vec(),
        segment.as_slice()?.to_vec(),
        height.as_slice()?.to_vec(),
        force.as_slice()?.to_vec(),
    );
    run_py(py, move || {
        use tabor::fit::{Curve, Direction, FitOptions};
        let opt = FitOptions::from_json(&options_json)?;
        // The library's check, as the command line makes it.
        if let Err(e) = opt.validate() {
            // Named as fit_curves' keywords.
            anyhow::bail!(
                "{}",
                tabor::error::Named::named(&e, &|key| match key {
                    "z0" => Some("z0_m"),
                    "spring" => Some("spring_n_m"),
                    "radius" => Some("radius_m"),
                    _ => None,
                })
            );
        }
        let mut curves: Vec<Curve> = Vec::new();
        // Each curve's directions, None for a point of a dwell (-1).
        let mut dirs: Vec<Vec<Option<Direction>>> = Vec::new();
        let mut index = std::collections::HashMap::new();
        for i in 0..h.len() {
            let k = *index.entry(c[i]).or_insert_with(|| {
                curves.push(Curve {
                    id: c[i].to_string(),
                    ..Curve::default()
                });
                dirs.push(Vec::new());
                curves.len() - 1
            });
            dirs[k].push(match s[i] {
                0 => Some(Direction::Approach),
                1 => Some(Direction::Retract),
                -1 => None,
                v => anyhow::bail!(
                    "segment[{i}] = {v}: use 0 for approach, 1 for retract, -1 for a dwell"
                ),
            });
            curves[k].height.push(h[i]);
            curves[k].force.push(f[i]);
        }
        // Dwell points out, the dwell at the turn kept for the fit's report (the library's
        // reading, as the command line's).
        let curves: Vec<Curve> = curves
            .into_iter()
            .zip(dirs)
            .map(|(cv, direction)| {
                cv.with_plan(tabor::fit::segments::SegmentPlan {
                    direction,
                    notes: Vec::new(),
                })
            })
            .collect();
        use rayon::prelude::*;
        let results: Vec<tabor::fit::CurveFit> = curves
            .par_iter()
            .map(|cv| {
                tabor::interrupt::checkpoint();
                let mut r = tabor::fit::fit_curve(cv, &opt);
                // Its message with Python's names (the advice names fit_segment).
                r.message = tabor::error::Named::named(&r.message, &py_name).into();
                r
            })
            .collect();
        Ok(results)
    })
}

/// An approach-retract cycle: drive "grips", "dead_load" or "spring" (with `stiffness`); with
/// `stress_ratio` and `range_ratio`, of the solid plus a second zone (a meniscus).
#[pyfunction]
#[pyo3(signature = (lam, drive, stiffness, max_load, stress_ratio=None, range_ratio=None, tip=None))]
fn cycle<'py>(
    py: Python<'py>,
    lam: f64,
    drive: &str,
    stiffness: Option<f64>,
    max_load: f64,
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
    tip: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    use tabor::cycle::Drive;
    let drive = match (drive, stiffness) {
        ("grips", None) => Drive::RigidGrips,
        ("dead_load", None) => Drive::DeadLoad,
        ("spring", Some(k)) => Drive::Spring(k),
        ("spring", None) => return Err(PyValueError::new_err("drive=\"spring\" needs stiffness")),
        (_, Some(_)) => {
            return Err(PyValueError::new_err(
                "stiffness applies to drive=\"spring\" only",
            ))
        }
        (d, _) => {
            return Err(PyValueError::new_err(format!(
                "drive = {d:?}: give \"grips\", \"dead_load\" or \"spring\""
            )))
        }
    };
    let law = match tip {
        Some(t) => {
            if stress_ratio.is_some() || range_ratio.is_some() {
                return Err(PyValueError::new_err(
                    "tip= has no second zone: leave stress_ratio and range_ratio out",
                ));
            }
            let shape = tabor::scene::tip::shape_of(t).map_err(|e| py_value_error(&e))?;
            tabor::ContactLaw::Tip(
                tabor::law::Tip::new(shape, lam)
                    .map_err(|e| PyValueError::new_err(format!("lam = {lam}: {e}")))?,
            )
        }
        None => tabor::ContactLaw::new(lam, stress_ratio, range_ratio)
            .map_err(|e| py_value_error(&e))?,
    };
    let spec = tabor::cycle::CycleSpec {
        law,
        drive,
        max_load,
    };
    run_py(py, move || Ok(spec.run()?))
}

/// The second zone's ratios paired by the library's check (ValueError where one is missing).
#[pyfunction]
#[pyo3(signature = (stress_ratio, range_ratio))]
fn two_zone_ratios(
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
) -> PyResult<Option<(f64, f64)>> {
    tabor::physics::two_zone::paired_ratios(stress_ratio, range_ratio)
        .map_err(|e| py_value_error(&e))
}

/// A profile's state: `given` load|approach|radius, with its value.
fn given_of(given: &str, value: f64) -> PyResult<tabor::profile::Given> {
    use tabor::profile::Given;
    match given {
        "load" => Ok(Given::Load(value)),
        "approach" => Ok(Given::Approach(value)),
        "radius" => Ok(Given::Radius(value)),
        _ => Err(PyValueError::new_err(
            "given must be load, approach or radius",
        )),
    }
}

/// Pressure and gap profiles: `given` load|approach|radius; with both of the second zone's
/// ratios the two-zone state's (`tabor profile --stress-ratio --range-ratio`).
#[pyfunction]
#[pyo3(signature = (lam, given, value, points, stress_ratio=None, range_ratio=None, tip=None))]
#[allow(clippy::too_many_arguments)]
fn profile<'py>(
    py: Python<'py>,
    lam: f64,
    given: &str,
    value: f64,
    points: usize,
    stress_ratio: Option<f64>,
    range_ratio: Option<f64>,
    tip: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let law = match tip {
        Some(t) => {
            let shape = tabor::scene::tip::shape_of(t).map_err(|e| py_value_error(&e))?;
            tabor::ContactLaw::Tip(
                tabor::law::Tip::new(shape, lam)
                    .map_err(|e| PyValueError::new_err(format!("lam = {lam}: {e}")))?,
            )
        }
        None => tabor::ContactLaw::new(lam, stress_ratio, range_ratio)
            .map_err(|e| py_value_error(&e))?,
    };
    let spec = tabor::profile::spec::ProfileSpec {
        law,
        given: given_of(given, value)?,
        points,
    };
    run_py(py, move || Ok(spec.run()?))
}

/// Both pull-offs of the solid's lambda with a second zone (`tabor pulloff --stress-ratio
/// --range-ratio`), in units built on the total w.
#[pyfunction]
fn pulloff_two_zone<'py>(
    py: Python<'py>,
    lam: f64,
    stress_ratio: f64,
    range_ratio: f64,
) -> PyResult<Bound<'py, PyDict>> {
    use tabor::law::two_zone::ContextError;
    let law = tabor::law::TwoZones {
        lambda: lam,
        stress_ratio,
        range_ratio,
    };
    let ctx = run(py, move || {
        law.context().map_err(|e| match e {
            ContextError::Curve(s) => {
                anyhow::anyhow!("the two-zone pull-offs were not found: {}", s.name())
            }
            e => anyhow::Error::new(e),
        })
    })?;
    let d = PyDict::new(py);
    for (name, p) in [
        ("load_control", &ctx.load_pulloff),
        ("displacement_control", &ctx.disp_pulloff),
    ] {
        d.set_item(format!("{name}_load"), p.load)?;
        d.set_item(format!("{name}_A"), p.a)?;
        d.set_item(format!("{name}_approach"), p.approach)?;
    }
    Ok(d)
}

/// An adhesion map, kept on the Rust side for its arrays, figure, JSON and NPY files.
#[pyclass(module = "tabor._tabor")]
struct AdhesionMap {
    data: tabor::map::MapData,
    engine: Engine,
    check: Option<tabor::engine::CheckReport>,
}

#[pymethods]
impl AdhesionMap {
    #[new]
    #[pyo3(signature = (spec_json, backend, precision, adapter, check, tip=None))]
    fn new(
        py: Python<'_>,
        spec_json: String,
        backend: &str,
        precision: &str,
        adapter: Option<String>,
        check: usize,
        tip: Option<&str>,
    ) -> PyResult<Self> {
        let (mut backend, precision) = (backend_of(backend)?, precision_of(precision)?);
        // A tip's map is solved by the f64 CPU solver only (`tabor map --tip`).
        let shape: Option<tabor::physics::tip::Shape> = match tip {
            Some(t) => {
                if backend == Backend::Gpu {
                    return Err(PyValueError::new_err(
                        "backend = \"gpu\": a tip's map is solved on the CPU; give backend=\"cpu\" or \"auto\"",
                    ));
                }
                backend = Backend::Cpu;
                Some(tabor::scene::tip::shape_of(t).map_err(|e| py_value_error(&e))?)
            }
            None => None,
        };
        run(py, move || {
            let spec = tabor::map::MapSpec::from_json(&spec_json)?;
            spec.validate()?;
            let (mut engine, _) = Engine::select(backend, adapter.as_deref())?;
            engine.set_precision(precision)?;
            let opts = tabor::map::ComputeOptions {
                keep_exact: true,
                check,
                records: true,
            };
            let data = match shape {
                Some(shape) => tabor::map::tip::compute_tip(&spec, shape, opts.keep_exact)?,
                None => tabor::map::compute_with(&spec, &engine, opts)?,
            };
            let check = data.check.clone();
            Ok(AdhesionMap {
                data,
                engine,
                check,
            })
        })
    }

    #[getter]
    fn lam<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr(py, self.data.lambdas.clone())
    }

    #[getter]
    fn load_axis<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr(py, self.data.rows.clone())
    }

    #[getter]
    fn pulloff<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr(py, self.data.pulloff.clone())
    }

    /// Flat per-point arrays (row-major, ny rows of nx): A, load, approach, m_minus_1, region and
    /// status codes.
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s: Vec<State> = (0..self.data.len()).map(|i| self.data.state(i)).collect();
        let ok = |x: f64, st: Status| if st == Status::Ok { x } else { f64::NAN };
        let d = PyDict::new(py);
        d.set_item("A", arr(py, s.iter().map(|s| ok(s.a, s.status)).collect()))?;
        d.set_item("load", arr(py, s.iter().map(|s| s.load).collect()))?;
        d.set_item(
            "approach",
            arr(py, s.iter().map(|s| ok(s.approach, s.status)).collect()),
        )?;
        d.set_item(
            "m_minus_1",
            arr(py, s.iter().map(|s| ok(s.m_minus_1, s.status)).collect()),
        )?;
        let regions: Vec<u8> = self.data.regions.iter().map(|&r| r as u8).collect();
        d.set_item("region", regions.into_pyarray(py))?;
        let codes: Vec<u8> = s.iter().map(|s| s.status as u8).collect();
        d.set_item("status_code", codes.into_pyarray(py))?;
        d.set_item(
            "region_names",
            tabor::map::Region::ALL
                .iter()
                .map(|r| r.name())
                .collect::<Vec<_>>(),
        )?;
        d.set_item("shape", (self.data.spec.ny, self.data.spec.nx))?;
        Ok(d)
    }

    /// Writes the figure (PNG, SVG or PDF by the extension of `path`), with an optional
    /// quantity, `width_mm` wide (85: one column) with a PNG of `dpi`.
    #[pyo3(signature = (path, quantity=None, width_mm=85.0, dpi=300.0))]
    fn save_figure(
        &self,
        py: Python<'_>,
        path: String,
        quantity: Option<String>,
        width_mm: f64,
        dpi: f64,
    ) -> PyResult<()> {
        let q = match quantity.as_deref() {
            None => None,
            Some(name) => Some(
                tabor::render::map::Quantity::from_name(name).ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "quantity = {name:?}: give a, approach, m, err-hertz, err-dmt or err-jkr"
                    ))
                })?,
            ),
        };
        let print = tabor::render::Print::new(width_mm, dpi).map_err(|e| py_value_error(&e))?;
        let out = tabor::render::Outputs::from_path(std::path::Path::new(&path))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let data = &self.data;
        run_here(py, move || tabor::render::map::save(data, q, &print, &out))
    }

    /// Writes the JSON document as `tabor map --json` (with the per-point arrays if `full`).
    fn save_json(&self, py: Python<'_>, path: String, full: bool) -> PyResult<()> {
        let (data, engine, check) = (&self.data, &self.engine, self.check.as_ref());
        run_here(py, move || {
            let mut o = tabor::io::Output::create(&path)?;
            tabor::export::write_map_json(&mut o, data, engine, check, full, false)?;
            o.commit()
        })
    }

    /// Writes PREFIX_lambda.npy, ... as `tabor map --npy PREFIX`.
    fn save_npy(&self, py: Python<'_>, prefix: String) -> PyResult<()> {
        let data = &self.data;
        run_here(py, move || {
            let mut outs = tabor::export::NPY_FILES
                .iter()
                .map(|n| tabor::io::Output::create(format!("{prefix}_{n}")))
                .collect::<anyhow::Result<Vec<_>>>()?;
            tabor::export::write_npy(data, &mut outs)?;
            for o in outs {
                o.commit()?;
            }
            Ok(())
        })
    }

    fn region_counts(&self) -> Vec<(&'static str, usize)> {
        self.data
            .region_counts()
            .into_iter()
            .map(|(r, n)| (r.name(), n))
            .collect()
    }

    #[getter]
    fn backend(&self) -> &'static str {
        self.engine.name()
    }
}

#[pymodule]
fn _tabor(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // NumPy's C API loaded now, not at a call's first array: a Ctrl-C pending then would
    // interrupt that import inside rust-numpy, which panics.
    PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("LAMBDA_MIN", tabor::physics::domain::LAMBDA_MIN)?;
    m.add(
        "DEFAULT_TOLERANCE",
        tabor::physics::model::DEFAULT_TOLERANCE,
    )?;
    m.add("LAMBDA_MAX", tabor::physics::domain::LAMBDA_MAX)?;
    m.add("DMT_LIMIT_MAX", tabor::physics::domain::DMT_LIMIT_MAX)?;
    m.add("LIMIT_LAMBDA_MIN", tabor::physics::domain::LIMIT_LAMBDA_MIN)?;
    m.add("LIMIT_LAMBDA_MAX", tabor::physics::domain::LIMIT_LAMBDA_MAX)?;
    m.add("LAMBDA_D", tabor::physics::md::LAMBDA_D)?;
    m.add("LOAD_MAX", tabor::physics::domain::LOAD_MAX)?;
    m.add("APPROACH_MAX", tabor::physics::domain::APPROACH_MAX)?;
    m.add("RADIUS_MAX", tabor::physics::domain::RADIUS_MAX)?;
    m.add_function(wrap_pyfunction!(method_codes, m)?)?;
    m.add_function(wrap_pyfunction!(dem::dem_law, m)?)?;
    m.add_class::<dem::PyDemLaw>()?;
    m.add_function(wrap_pyfunction!(rough::rough_scene, m)?)?;
    m.add_function(wrap_pyfunction!(solve_points, m)?)?;
    m.add_function(wrap_pyfunction!(solve_radius, m)?)?;
    m.add_function(wrap_pyfunction!(solve_tip, m)?)?;
    m.add_function(wrap_pyfunction!(tip_units, m)?)?;
    m.add_function(wrap_pyfunction!(pulloff_tip, m)?)?;
    m.add_function(wrap_pyfunction!(status_names, m)?)?;
    m.add_function(wrap_pyfunction!(pulloff, m)?)?;
    m.add_function(wrap_pyfunction!(closed_form, m)?)?;
    m.add_function(wrap_pyfunction!(curve, m)?)?;
    m.add_function(wrap_pyfunction!(scene, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(humidity, m)?)?;
    m.add_function(wrap_pyfunction!(infer_pulloff, m)?)?;
    m.add_function(wrap_pyfunction!(fit_curves, m)?)?;
    m.add_function(wrap_pyfunction!(plan_segments, m)?)?;
    m.add_function(wrap_pyfunction!(infer_pulloff_wet, m)?)?;
    m.add_function(wrap_pyfunction!(pulloff_two_zone, m)?)?;
    m.add_function(wrap_pyfunction!(fit_pairs, m)?)?;
    m.add_function(wrap_pyfunction!(cycle, m)?)?;
    m.add_function(wrap_pyfunction!(profile, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough_ensemble, m)?)?;
    m.add_function(wrap_pyfunction!(two_zone_ratios, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough_asperities, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough_topography, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough_map, m)?)?;
    m.add_function(wrap_pyfunction!(rough::rough_pulloff, m)?)?;
    m.add_class::<AdhesionMap>()?;
    Ok(())
}
