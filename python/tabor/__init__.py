"""tabor: adhesive contact of elastic spheres, on NumPy arrays.

Exact Maugis-Dugdale (MD) states, pull-offs, curves, adhesion maps, scenes in SI units,
approach-retract cycles and the pressure and gap inside the contact, computed by tabor's Rust
library (the f64 solver on all cores, or the f32 GPU kernels with a cross-check).

Normalisation (Johnson & Greenwood 1997), with K = 4/3 E*:

- ``lam``: the Maugis parameter lambda = 2 s0 (R / (pi w K^2))^(1/3), in 1e-26 .. 1e26
  (``solve`` answers loads and approaches by the DMT and JKR limits beyond it, see ``solve``)
- ``load``: Pbar = P / (pi w R), tensile negative, |Pbar| <= 1e12
- ``approach``: Dbar = delta (K^2 / (pi^2 w^2 R))^(1/3), |Dbar| <= 1e8
- ``A``: contact radius a (K / (pi w R^2))^(1/3), in (0, 1e4]
- ``m_minus_1``: c/a - 1 (c the outer radius of the Dugdale zone)

Closed forms in the same units: Hertz Pbar = A^3, DMT Pbar = A^3 - 2, JKR Pbar = A^3 - sqrt(6 A^3),
Bradley (rigid) pull-off -2.

Results that could not be computed are NaN, and the ``status`` array says why: ``ok``,
``no_contact`` (below the pull-off), ``not_converged``, ``invalid_input`` (outside the domain);
``message`` gives the reason per point. A single value outside the domain (a scalar ``lam`` or
``load``) raises ``ValueError`` with tabor's own message; what is not real numbers (complex,
dates, strings, masked arrays) raises ``TypeError``. Ctrl-C interrupts any long call.
"""

import json
import os

import numpy as np

from . import _tabor

__version__ = _tabor.__version__
LAMBDA_MIN = _tabor.LAMBDA_MIN
LAMBDA_MAX = _tabor.LAMBDA_MAX
#: Beyond the exact solver's lambda range, ``solve`` answers loads and approaches by the DMT
#: limit for lambda in LIMIT_LAMBDA_MIN..DMT_LIMIT_MAX and by the JKR limit above LAMBDA_MAX up
#: to LIMIT_LAMBDA_MAX, where each is within 1e-13 of MD (the ``method`` array says which).
DMT_LIMIT_MAX = _tabor.DMT_LIMIT_MAX
LIMIT_LAMBDA_MIN = _tabor.LIMIT_LAMBDA_MIN
LIMIT_LAMBDA_MAX = _tabor.LIMIT_LAMBDA_MAX
#: Below this lambda the contact under rigid grips shrinks to zero radius.
LAMBDA_D = _tabor.LAMBDA_D
STATUS_NAMES = tuple(_tabor.status_names())

__all__ = [
    "solve", "pulloff", "curve", "hertz", "dmt", "jkr", "bradley", "adhesion_map",
    "AdhesionMap", "Scene", "humidity", "infer_pulloff", "fit_pairs", "fit_curves", "fit_curve",
    "fit_afmformats", "fit_fleet", "cycle", "profile", "presets", "rough", "rough_asperities",
    "rough_ensemble", "rough_map", "rough_pulloff", "rough_scene", "rough_topography", "dem_law",
]


class Result(dict):
    """A mapping of NumPy arrays (``A``, ``load``, ``approach``, ``m_minus_1``, ``status``,
    ...) with the run's ``metadata`` (backend, adapter, precision, GPU cross-check)."""

    def __init__(self, arrays, metadata):
        super().__init__(arrays)
        self.metadata = metadata

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None


def _numbers(a, name):
    """``a`` as a float64 array; TypeError for what is not plain real numbers (complex values
    would lose their imaginary part, dates and strings would be read as numbers, a masked
    array would lose its mask)."""
    if isinstance(a, np.ma.MaskedArray):
        raise TypeError(f"{name}: masked arrays are not supported (the mask would be lost); "
                        "pass a.filled(np.nan) or the unmasked values")
    x = np.asarray(a)
    kind = x.dtype.kind
    if kind == "c":
        raise TypeError(f"{name}: complex values are not supported (the imaginary part would "
                        "be dropped); pass real numbers")
    if kind in "mM":
        raise TypeError(f"{name}: {x.dtype} values are not numbers; pass float values")
    if kind in "USV":
        raise TypeError(f"{name}: strings are not numbers; pass float values")
    if kind == "O":
        try:
            for v in x.flat:
                if not isinstance(v, (int, float, np.integer, np.floating)) or isinstance(v, bool):
                    raise TypeError(type(v).__name__)
        except TypeError as e:
            raise TypeError(f"{name}: an element of type {e} is not a real number; pass float "
                            "values") from None
    return np.asarray(x, dtype=np.float64)


def _c(x, dtype=None):
    """A C-contiguous, aligned array (the extension reads nothing else): np.ascontiguousarray
    passes a misaligned array through, as unpickled (Dask, multiprocessing) buffers can be."""
    return np.require(x, dtype=dtype, requirements="CA")


def _flat(*arrays, names=None):
    """Broadcasts float64 inputs; returns the flat contiguous copies and the common shape."""
    names = names or [f"argument {i + 1}" for i in range(len(arrays))]
    f = [_numbers(a, n) for a, n in zip(arrays, names)]
    try:
        b = np.broadcast_arrays(*f)
    except ValueError as e:
        raise ValueError(f"the inputs do not broadcast to a common shape: {e}") from None
    shape = b[0].shape
    return [_c(x.ravel()) for x in b], shape


def _real(x, name):
    """A float for a scalar argument (tabor checks its range); TypeError for what is not one
    real number."""
    if isinstance(x, np.ma.MaskedArray) or np.ndim(x) != 0:
        raise TypeError(f"{name} = {x!r}: give one number")
    return float(_numbers(x, name))


def _optional(x, name):
    """None, or a float for a scalar argument."""
    return None if x is None else _real(x, name)


def _finite(x, name):
    """A finite float for a scalar argument, or ValueError naming it."""
    v = _real(x, name)
    if not np.isfinite(v):
        raise ValueError(f"{name} = {v}: give a finite number")
    return v


#: The largest |load|, |approach| and contact radius the solver takes (the library's limits).
LOAD_MAX = _tabor.LOAD_MAX
APPROACH_MAX = _tabor.APPROACH_MAX
RADIUS_MAX = _tabor.RADIUS_MAX


def _e(x):
    """A power of ten as tabor writes it in messages: 1e12, 1e-26."""
    m, e = f"{x:.0e}".split("e")
    return f"{m}e{int(e)}"


#: The solver's domain per input: (name in messages, the test of a valid value, the range).
_DOMAIN = {
    "lam": ("lambda", lambda x: (x >= LAMBDA_MIN) & (x <= LAMBDA_MAX),
            f"{_e(LAMBDA_MIN)}..{_e(LAMBDA_MAX)}"),
    # Loads and approaches: the exact solver's range and the closed-form limits' beyond it.
    "lam_any": ("lambda", lambda x: _method_code(x) != 0,
                f"{_e(LIMIT_LAMBDA_MIN)}..{_e(DMT_LIMIT_MAX)} (DMT limit), "
                f"{_e(LAMBDA_MIN)}..{_e(LAMBDA_MAX)} (exact), "
                f"{_e(LAMBDA_MAX)}..{_e(LIMIT_LAMBDA_MAX)} (JKR limit)"),
    "load": ("load", lambda x: np.abs(x) <= LOAD_MAX, f"-{_e(LOAD_MAX)}..{_e(LOAD_MAX)}"),
    "approach": ("approach", lambda x: np.abs(x) <= APPROACH_MAX,
                 f"-{_e(APPROACH_MAX)}..{_e(APPROACH_MAX)}"),
    "radius": ("radius", lambda x: (x > 0) & (x <= RADIUS_MAX), f"(0, {_e(RADIUS_MAX)}]"),
}


def _method_code(lam):
    """Per lambda, how ``solve`` answers a load or an approach, as a small code: 1 the exact
    solver, 2 the DMT limit, 3 the JKR limit (beyond the exact solver's range), 0 none (the
    library's ``physics::domain::method``)."""
    lam = np.asarray(lam, dtype=float)
    return _tabor.method_codes(_c(lam.ravel())).reshape(lam.shape)


#: The names of the codes of ``_method_code``.
_METHODS = np.array(["", "md", "dmt_limit", "jkr_limit"], dtype="<U9")


def _method(lam):
    """Per lambda: "md" (the exact solver), "dmt_limit" or "jkr_limit" (the closed-form
    limits, beyond the exact solver's range), "" where none is certified."""
    return _METHODS[_method_code(lam)]


def _bad(key, x):
    """The mask of the values of ``x`` outside the domain of input ``key`` (NaN included)."""
    with np.errstate(invalid="ignore"):
        return ~_DOMAIN[key][1](x)


def _why(key, v):
    name, _, rng = _DOMAIN[key]
    return f"{name} = {v:.6g} is outside the supported domain {rng}"


def _check_scalar(key, x, flat):
    """Raises ValueError for a single (0-d) input outside its domain: the whole input is bad."""
    if np.ndim(x) == 0 and flat.size and _bad(key, flat[:1])[0]:
        raise ValueError(_why(key, flat[0]))


#: Why a point has each status other than ok.
_STATUS_WHY = {
    "no_contact": "below the pull-off: no contact on the stable branch",
    "not_converged": "the solver did not converge at this point",
}


def _messages(status, keys, flats, shape):
    """The per-point reasons (an object array: '' where ok), naming the value outside the
    domain where the status is invalid_input."""
    msg = np.full(shape, "", dtype=object)
    flat = msg.reshape(-1)
    st = status.reshape(-1)
    for name, why in _STATUS_WHY.items():
        flat[st == name] = why
    bad = np.flatnonzero(st == "invalid_input")
    for i in bad:
        reasons = [_why(k, f[i]) for k, f in zip(keys, flats) if _bad(k, f[i:i + 1])[0]]
        flat[i] = "; ".join(reasons) or (
            "not certified by the DMT limit here (too close to its pull-off, or an approach "
            "below its bound); the exact solver covers lambda >= 1e-26"
            if keys[0] == "lam_any" else "outside the supported domain")
    return msg


def _status(codes, shape):
    # Indexing a string array as wide as the longest status present (2 characters where all are
    # "ok"): no per-point object array on the way, and no wider than needed.
    present = np.bincount(codes.ravel(), minlength=len(STATUS_NAMES)) > 0
    width = max([len(n) for n, p in zip(STATUS_NAMES, present) if p], default=1)
    return np.array(STATUS_NAMES, dtype=f"<U{width}")[codes].reshape(shape)


def solve(lam, load=None, approach=None, radius=None, *, backend="cpu", precision="f32",
          check=1000, adapter=None, tip=None):
    """Maugis-Dugdale states, broadcast over ``lam`` and exactly one of ``load``,
    ``approach`` or ``radius`` (``tabor solve``).

    Units (Johnson & Greenwood 1997, K = 4/3 E*): load Pbar = P / (pi w R), approach
    Dbar = delta (K^2 / (pi^2 w^2 R))^(1/3), contact radius A = a (K / (pi w R^2))^(1/3),
    lam = 2 s0 (R / (pi w K^2))^(1/3). Domain: lam in 1e-26..1e26 (the exact solver),
    |load| <= 1e12, |approach| <= 1e8, 0 < radius <= 1e4; outside it the status is
    ``invalid_input``. Beyond the exact solver's lambda range a load or an approach is answered
    by the closed-form limit where it is within 1e-13 of MD: DMT for lam in 1e-300..1e-26
    (away from its pull-off), JKR for lam in 1e26..1e150; ``method`` says which.

    Parameters
    ----------
    lam : array_like
        Maugis parameter lambda (dimensionless; 1e-26 .. 1e26, the limits beyond, see above).
    load : array_like, optional
        Normalised load Pbar (in pi w R, tensile negative): the state on the stable branch
        under load control.
    approach : array_like, optional
        Normalised approach Dbar (in (pi^2 w^2 R / K^2)^(1/3)): the state on the stable branch
        under displacement control.
    radius : array_like, optional
        Contact radius A (in (pi w R^2 / K)^(1/3)): the curve point there (stable or not); adds
        ``load_stable`` and ``displacement_stable``.
    backend : {"cpu", "gpu", "auto"}
        ``cpu``: the exact f64 solver. ``gpu``: the f32 WGSL kernels (error if no adapter);
        ``auto``: a GPU if there is one. Radius control always runs on the CPU.
    precision : {"f32", "f64"}
        GPU arithmetic; ``f64`` refines every f32 state by Newton steps in f64 on the GPU.
    check : int
        GPU results: re-solve this many evenly spaced points per chunk on the CPU and report the
        errors in ``metadata["cross_check"]``.
    adapter : str, optional
        Use the first GPU adapter whose name contains this text.
    tip : str or dict, optional
        A tip that is not a sphere (``tabor solve --tip``, docs/PHYSICS.md section 12):
        ``"cone"``, ``"power:N"`` or ``"capped-cone:R_OVER_L:HALF_ANGLE_DEG"``, with ``lam`` its
        Maugis parameter (1e-3 .. 1e3) and the values in its units; on the CPU in f64. The
        result then has ``A``, ``load``, ``approach``, ``C`` (the zone's outer radius),
        ``status`` and ``message``. A scene (a dict with a ``"tip"``, ``e_star_pa``
        and ``work_of_adhesion_j_m2``) gives its tip in the units of its E* and w: any tip in SI
        units, a measured profile among them (``--tip scene:FILE``).

    Returns
    -------
    Result
        float64 arrays ``A``, ``load``, ``approach``, ``m_minus_1`` (c/a - 1), a string array
        ``status`` (``ok``, ``no_contact``, ``not_converged``, ``invalid_input``), an object
        array ``message`` (why, where ``status`` is not ``ok``; '' elsewhere) and a string array
        ``method`` ("md", "dmt_limit", "jkr_limit", or '' where lambda has none), all of the
        broadcast shape; NaN only where ``status`` is not ``ok``. ``metadata`` holds the
        backend, precision and a GPU run's cross-check.

    Raises
    ------
    ValueError
        a scalar ``lam`` or value outside the domain (the whole input is bad), or not exactly
        one of ``load``, ``approach``, ``radius``.
    TypeError
        complex, date, string or masked-array input.
    KeyboardInterrupt
        on Ctrl-C, checked between chunks of 262144 points.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.solve(1.0, load=[0.5, -1.7])
    >>> r["A"].round(6).tolist()
    [1.72894, nan]
    >>> r["status"].tolist()
    ['ok', 'no_contact']
    >>> r.metadata["backend"], r.metadata["precision"]
    ('cpu', 'f64')
    """
    given = [k for k, v in (("load", load), ("approach", approach), ("radius", radius))
             if v is not None]
    if len(given) != 1:
        raise ValueError("give exactly one of load=, approach= or radius= "
                         f"(got {', '.join(given) or 'none'})")
    value = {"load": load, "approach": approach, "radius": radius}[given[0]]
    (lam_f, val_f), shape = _flat(lam, value, names=["lam", given[0]])
    if tip is not None:
        return _solve_tip(tip, lam_f, val_f, given[0], shape)
    lam_key = "lam" if given[0] == "radius" else "lam_any"
    _check_scalar(lam_key, lam, lam_f)
    _check_scalar(given[0], value, val_f)
    if isinstance(check, bool) or not isinstance(check, (int, np.integer)) or check < 0:
        raise ValueError(f"check = {check!r}: give a number of points >= 0")
    if given[0] == "radius":
        r = _tabor.solve_radius(lam_f, val_f)
        meta = {"backend": "cpu", "precision": "f64", "control": "radius"}
        out = {k: np.asarray(r[k]).reshape(shape)
               for k in ("A", "load", "approach", "m_minus_1")}
        out["load_stable"] = np.asarray(r["load_stable"], dtype=bool).reshape(shape)
        out["displacement_stable"] = np.asarray(
            r["displacement_stable"], dtype=bool).reshape(shape)
    else:
        r = _tabor.solve_points(lam_f, val_f, given[0], backend, precision, adapter, int(check))
        meta = dict(r["metadata"])
        meta["control"] = "load" if given[0] == "load" else "displacement"
        meta["engine"] = r["engine"]
        out = {k: np.asarray(r[k]).reshape(shape)
               for k in ("A", "load", "approach", "m_minus_1")}
    out["status"] = _status(np.asarray(r["status_code"]), shape)
    out["message"] = _messages(out["status"], (lam_key, given[0]), (lam_f, val_f), shape)
    code = _method_code(lam_f)
    if given[0] == "radius":  # radius control has no closed-form stand-in
        code[code != 1] = 0
    out["method"] = _METHODS[code].reshape(shape)
    return Result(out, meta)


def _tip_text(tip):
    """A normalised-unit call's ``tip``: a shape's text, or a scene (dict) as its JSON, whose
    tip the library takes in the units of the scene's E* and w (NumPy arrays as lists)."""
    if tip is None or isinstance(tip, str):
        return tip
    if not isinstance(tip, dict):
        raise TypeError(f"tip = {tip!r}: give a shape string such as \"cone\" or \"power:3\", "
                        "or a scene (dict) with a \"tip\"")
    if "shape" in tip and "tip" not in tip:
        raise ValueError(f"tip = {{\"shape\": {tip['shape']!r}, ...}} is a tip in SI units, which "
                         "has no normalised shape without its materials: give the scene, "
                         "{\"e_star_pa\": ..., \"work_of_adhesion_j_m2\": ..., \"s0_pa\": ..., "
                         "\"tip\": {...}}")

    def plain(o):
        if isinstance(o, (np.ndarray, np.generic)):
            return o.tolist()
        raise TypeError(f"{type(o).__name__} is not a number, string, list or dict")

    try:
        return json.dumps(tip, allow_nan=False, default=plain)
    except ValueError:
        raise ValueError("tip: the scene holds a value that is not a finite number; give "
                         "finite values") from None


def _solve_tip(tip, lam_f, val_f, given, shape):
    """``solve(..., tip=...)``: the tip's states (``tabor solve --tip``)."""
    r = _tabor.solve_tip(_tip_text(tip), lam_f, val_f,
                         "approach" if given == "approach" else given)
    out = {k: np.asarray(r[k]).reshape(shape) for k in ("A", "load", "approach", "C")}
    out["status"] = _status(np.asarray(r["status_code"]), shape)
    why = {"ok": "", "no_contact": "below the pull-off of this control: no contact",
           "invalid_input": f"lam outside 1e-3..1e3 for a tip, or {given} not a finite "
                            f"number{' above 0' if given == 'radius' else ''}"}
    out["message"] = np.array([why.get(s, s) for s in out["status"].ravel()],
                              dtype=object).reshape(shape)
    control = {"load": "load", "approach": "displacement", "radius": "radius"}[given]
    return Result(out, {"backend": "cpu", "precision": "f64", "control": control, "tip": tip})


def pulloff(lam, stress_ratio=None, range_ratio=None, *, tip=None):
    """Pull-off (jump-out) under load and displacement control, as ``tabor pulloff``.

    Parameters
    ----------
    lam : array_like
        Maugis parameter lambda (1e-26 .. 1e26). With ``stress_ratio`` and ``range_ratio``, the
        solid's own lambda, one number.
    stress_ratio, range_ratio : float, optional
        A second Dugdale zone, such as a water meniscus: its stress and range relative to the
        solid's (both or neither; docs/PHYSICS.md section 10).
    tip : str or dict, optional
        A tip that is not a sphere (``tabor pulloff --tip``): ``"cone"``, ``"power:N"``,
        ``"capped-cone:R_OVER_L:HALF_ANGLE_DEG"`` or a scene (dict) whose tip is taken in the
        units of its E* and w; ``lam`` its Maugis parameter (1e-3 .. 1e3), the loads in its
        units (docs/PHYSICS.md section 12). The same keys, without the zero-radius end's.

    Returns
    -------
    Result or dict
        Arrays of the shape of ``lam``, normalised (loads in pi w R): ``load_control_load``
        (Pbar_c), ``load_control_A``, ``load_control_approach``, ``displacement_control_load``,
        ``displacement_control_A`` (0 for lambda <= LAMBDA_D: the contact is lost at zero
        radius), ``displacement_control_approach``, ``zero_radius_end_load``,
        ``zero_radius_end_approach``. With two zones, a dict of the two pull-offs' ``*_load``,
        ``*_A`` and ``*_approach`` in units built on the total work of adhesion.

    Raises
    ------
    ValueError
        a lambda outside 1e-26 .. 1e26 (a tip's: 1e-3 .. 1e3), one ratio without the other, or
        a tip with a ratio.

    Examples
    --------
    >>> import tabor
    >>> p = tabor.pulloff([0.1, 1.0, 10.0])
    >>> p["load_control_load"].round(6).tolist()
    [-1.950595, -1.600735, -1.501625]
    >>> p["displacement_control_A"].round(6).tolist()
    [0.0, 0.084681, 0.544932]
    >>> round(tabor.pulloff(1.0, stress_ratio=0.5, range_ratio=3.0)["load_control_load"], 6)
    -1.617368
    """
    if tip is not None:
        if stress_ratio is not None or range_ratio is not None:
            raise ValueError("tip= has no second zone: leave stress_ratio and range_ratio out")
        (lam_f,), shape = _flat(lam, names=["lam"])
        r = _tabor.pulloff_tip(_tip_text(tip), lam_f)
        return Result({k: np.asarray(v).reshape(shape) for k, v in r.items()}, {"tip": tip})
    if _tabor.two_zone_ratios(_optional(stress_ratio, "stress_ratio"),
                              _optional(range_ratio, "range_ratio")) is not None:
        return _tabor.pulloff_two_zone(_real(lam, "lam"), _real(stress_ratio, "stress_ratio"),
                                       _real(range_ratio, "range_ratio"))
    (lam_f,), shape = _flat(lam, names=["lam"])
    r = _tabor.pulloff(lam_f)
    return Result({k: np.asarray(v).reshape(shape) for k, v in r.items()}, {})


def _closed(model, load=None, A=None):
    if (load is None) == (A is None):
        raise ValueError("give exactly one of load= (returns A) or A= (returns the load)")
    what, x = ("radius", load) if load is not None else ("load", A)
    (x_f,), shape = _flat(x, names=["load" if load is not None else "A"])
    return np.asarray(_tabor.closed_form(model, what, x_f)).reshape(shape)


def hertz(load=None, A=None):
    """Hertz: A = Pbar^(1/3) from ``load``, or Pbar = A^3 from ``A`` (normalised units).

    Parameters
    ----------
    load : array_like, optional
        Normalised load Pbar (in pi w R); gives A (NaN for Pbar < 0).
    A : array_like, optional
        Normalised contact radius; gives Pbar. Exactly one of ``load`` and ``A``.

    Returns
    -------
    numpy.ndarray
        float64, of the input's shape.

    Raises
    ------
    ValueError
        neither or both of ``load`` and ``A``.

    Examples
    --------
    >>> import tabor
    >>> float(tabor.hertz(load=8.0)), float(tabor.hertz(A=2.0))
    (2.0, 8.0)
    """
    return _closed("hertz", load, A)


def dmt(load=None, A=None):
    """DMT: A = (Pbar + 2)^(1/3) from ``load``, or Pbar = A^3 - 2 from ``A`` (normalised units).

    Parameters
    ----------
    load : array_like, optional
        Normalised load Pbar (in pi w R); gives A (NaN below the pull-off -2).
    A : array_like, optional
        Normalised contact radius; gives Pbar. Exactly one of ``load`` and ``A``.

    Returns
    -------
    numpy.ndarray
        float64, of the input's shape.

    Raises
    ------
    ValueError
        neither or both of ``load`` and ``A``.

    Examples
    --------
    >>> import tabor
    >>> float(tabor.dmt(load=6.0)), float(tabor.dmt(A=1.0))
    (2.0, -1.0)
    """
    return _closed("dmt", load, A)


def jkr(load=None, A=None):
    """JKR: A^3 = Pbar + 3 + sqrt(9 + 6 Pbar) from ``load``, or Pbar = A^3 - sqrt(6 A^3) from
    ``A`` (normalised units).

    Parameters
    ----------
    load : array_like, optional
        Normalised load Pbar (in pi w R); gives A (NaN below the pull-off -3/2).
    A : array_like, optional
        Normalised contact radius; gives Pbar. Exactly one of ``load`` and ``A``.

    Returns
    -------
    numpy.ndarray
        float64, of the input's shape.

    Raises
    ------
    ValueError
        neither or both of ``load`` and ``A``.

    Examples
    --------
    >>> import tabor
    >>> round(float(tabor.jkr(load=-1.5)), 6), round(float(tabor.jkr(A=1.0)), 6)
    (1.144714, -1.44949)
    """
    return _closed("jkr", load, A)


def bradley():
    """Bradley (rigid spheres): the pull-off load -2 (no deformation, no contact radius).

    Returns
    -------
    float
        The normalised pull-off load, -2 (in pi w R).

    Examples
    --------
    >>> import tabor
    >>> tabor.bradley()
    -2.0
    """
    return -2.0


def curve(lam, a_max=4.0, points=200):
    """The whole MD curve of one lambda, stable and unstable parts, as ``tabor curve``.

    Parameters
    ----------
    lam : float
        Maugis parameter lambda (1e-26 .. 1e26).
    a_max : float
        The largest normalised contact radius; A runs uniformly from it down to 0.
    points : int
        Number of points, at most 1,000,000.

    Returns
    -------
    Result
        Arrays ``A``, ``load`` (Pbar), ``approach`` (Dbar), ``m_minus_1`` (inf at the A = 0
        end), ``load_stable`` (dPbar/dA > 0) and ``displacement_stable`` (dDbar/dA > 0);
        ``metadata["lambda"]``.

    Raises
    ------
    ValueError
        a lambda outside the domain, a bad ``a_max`` or ``points``.

    Examples
    --------
    >>> import tabor
    >>> c = tabor.curve(1.0, a_max=4.0, points=5)
    >>> c["A"].tolist()
    [4.0, 3.0, 2.0, 1.0, 0.0]
    >>> c["load"].round(4).tolist()
    [50.7884, 17.8608, 2.4562, -1.5796, -0.8683]
    >>> c["load_stable"].tolist()
    [True, True, True, True, False]
    """
    c = _tabor.curve(_real(lam, "lam"), _real(a_max, "a_max"), int(points))
    pts = c["points"]
    out = {k: np.array([p[k] if p[k] is not None else np.inf for p in pts], dtype=float)
           for k in ("A", "load", "approach", "m_minus_1")}
    for k in ("load_stable", "displacement_stable"):
        out[k] = np.array([p[k] for p in pts], dtype=bool)
    return Result(out, {"lambda": c["lambda"]})


class AdhesionMap:
    """An adhesion map (Johnson & Greenwood 1997), as ``tabor map`` computes it; made by
    :func:`adhesion_map`.

    Attributes
    ----------
    lam : numpy.ndarray
        The nx lambdas.
    load_axis : numpy.ndarray
        The ny loads: Pbar (in pi w R), or Pbar - Pbar_c for ``load_axis="above-pulloff"``.
    pulloff : numpy.ndarray
        The load-controlled pull-off Pbar_c of each lambda (nx).
    A, load, approach, m_minus_1 : numpy.ndarray
        (ny, nx) float64 states in normalised units, NaN where not computed.
    region : numpy.ndarray
        (ny, nx) uint8 codes; ``region_names`` gives the names.
    status : numpy.ndarray
        (ny, nx) strings: ``ok``, ``no_contact``, ``not_converged``, ``invalid_input``.
    region_counts : dict
        Region name to point count.
    backend : str
        Where the states were solved.

    Examples
    --------
    >>> import tabor
    >>> m = tabor.adhesion_map(nx=64, ny=64, backend="cpu")
    >>> m.A.shape, m.backend
    ((64, 64), 'cpu')
    >>> m.region_names[:6]
    ('no_contact', 'hertz', 'rigid', 'dmt', 'jkr', 'md')
    """

    def __init__(self, inner):
        self._inner = inner
        a = inner.arrays()
        shape = tuple(a["shape"])
        self.lam = np.asarray(inner.lam)
        self.load_axis = np.asarray(inner.load_axis)
        self.pulloff = np.asarray(inner.pulloff)
        for k in ("A", "load", "approach", "m_minus_1"):
            setattr(self, k, np.asarray(a[k]).reshape(shape))
        self.region = np.asarray(a["region"]).reshape(shape)
        self.region_names = tuple(a["region_names"])
        self.status = _status(np.asarray(a["status_code"]), shape)
        self.region_counts = dict(inner.region_counts())
        self.backend = inner.backend

    def save(self, path, quantity=None, width_mm=85.0, dpi=300.0, *, npy=False):
        """Writes the figure or the JSON document, exactly as ``tabor map`` does.

        Parameters
        ----------
        path : str or os.PathLike
            A file ending in ``.png``, ``.svg`` or ``.pdf`` (the figure; ``--out``, ``--svg``,
            ``--pdf``) or ``.json`` (``--json``); with ``npy=True`` a prefix.
        quantity : str, optional
            Draw a quantity with a colorbar instead of the regions: ``a``, ``approach``, ``m``,
            ``err-hertz``, ``err-dmt``, ``err-jkr`` (``--quantity``).
        width_mm : float
            Printed width in mm: 85 for one journal column, 175 for two (40..600).
        dpi : float
            Resolution of the PNG.
        npy : bool
            Write the NumPy files ``PATH_lambda.npy``, ``PATH_load_axis.npy``, ``PATH_load.npy``,
            ``PATH_A.npy``, ``PATH_approach.npy``, ``PATH_m_minus_1.npy``, ``PATH_region.npy``
            and ``PATH_region_names.json`` (``--npy``).

        Raises
        ------
        ValueError
            another extension (it is refused rather than taken for a prefix), or ``quantity``
            with ``npy=True``.
        OSError
            a file that cannot be written.

        Examples
        --------
        >>> import os, tempfile, tabor
        >>> m = tabor.adhesion_map(nx=64, ny=64, backend="cpu")
        >>> d = tempfile.mkdtemp()
        >>> m.save(os.path.join(d, "map.svg"), width_mm=175)
        >>> m.save(os.path.join(d, "map"), npy=True)
        >>> sorted(os.listdir(d))[:3]
        ['map.svg', 'map_A.npy', 'map_approach.npy']
        """
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower()
        if npy:
            if quantity is not None:
                raise ValueError("quantity applies to a figure, not to NPY files")
            self._inner.save_npy(path)
        elif ext in (".png", ".svg", ".pdf"):
            self._inner.save_figure(path, quantity, float(width_mm), float(dpi))
        elif ext == ".json":
            self._inner.save_json(path, False)
        else:
            raise ValueError(f"path = {path!r}: give a file ending in .png, .svg, .pdf or .json, "
                             "or save(prefix, npy=True) for the NumPy files PREFIX_lambda.npy, ...")

    def save_json(self, path, full=False):
        """Writes the JSON document (``tabor map --json``); ``full`` adds the per-point arrays
        (``--json-full``).

        Parameters
        ----------
        path : str or os.PathLike
            The JSON file.
        full : bool
            Add the arrays ``region``, ``load``, ``A``, ``approach``, ``m_minus_1``, ``status``
            (ny rows of nx).

        Examples
        --------
        >>> import json, os, tempfile, tabor
        >>> m = tabor.adhesion_map(nx=64, ny=64, backend="cpu")
        >>> path = os.path.join(tempfile.mkdtemp(), "map.json")
        >>> m.save_json(path)
        >>> sorted(json.load(open(path)))
        ['axes', 'large_deformation', 'metadata', 'thresholds']
        """
        self._inner.save_json(os.fspath(path), bool(full))


def adhesion_map(lambda_min=1e-3, lambda_max=1e3, nx=1024, ny=1024, load_axis="log",
                 load_min=None, load_max=None, tolerance=_tabor.DEFAULT_TOLERANCE, strength_ratio=(0.001, 0.01),
                 *, backend="auto", precision="f32", check=1000, adapter=None, tip=None):
    """Computes an adhesion map with the options of ``tabor map``.

    Each point is classified into the first of Hertz, Bradley (rigid), DMT, JKR whose contact
    radius is within ``tolerance`` of the exact MD one, else MD; below the pull-off: no contact.

    Parameters
    ----------
    lambda_min, lambda_max : float
        The lambda axis (log), default 1e-3..1e3.
    nx, ny : int
        Grid size (at most 4096 x 4096).
    load_axis : {"log", "above-pulloff", "linear"}
        ``"log"`` (Pbar, default 1e-3..1e3), ``"above-pulloff"`` (Pbar - Pbar_c, default
        1e-6..1e3) or ``"linear"`` (default -2..10); loads in pi w R.
    load_min, load_max : float, optional
        The load axis' range, if not the default.
    tolerance : float
        The relative error of the contact radius a closed form may have (default 0.05).
    strength_ratio : sequence of float
        s0/K of the large-deformation lines a/R = 0.1 on the figure.
    backend : {"auto", "cpu", "gpu"}
        ``auto`` takes a hardware GPU, else the CPU; ``cpu`` the exact f64 solver.
    precision : {"f32", "f64"}
        GPU arithmetic.
    check : int
        GPU points re-solved on the CPU for the cross-check.
    adapter : str, optional
        The GPU adapter whose name contains this text.
    tip : str or dict, optional
        The map of a tip that is not a sphere (``tabor map --tip``; docs/PHYSICS.md section 12):
        ``"cone"``, ``"power:N"`` (f = B r^N; every B has the same map) or
        ``"capped-cone:R_OVER_L:HALF_ANGLE_DEG"``, in the tip's normalised units; solved by the
        f64 CPU solver (``backend`` ``"cpu"`` or ``"auto"``), lambda within the tip law's range. A scene (a dict with a ``"tip"``, ``e_star_pa``
        and ``work_of_adhesion_j_m2``) gives its tip in the units of its E* and w: any tip in SI
        units, a measured profile among them (``--tip scene:FILE``).

    Returns
    -------
    AdhesionMap

    Raises
    ------
    ValueError
        a bad range, count, axis or tolerance (the library's message).
    KeyboardInterrupt
        on Ctrl-C.

    Examples
    --------
    >>> import tabor
    >>> m = tabor.adhesion_map(nx=64, ny=64, backend="cpu")
    >>> m.region_counts
    {'hertz': 822, 'rigid': 566, 'dmt': 419, 'jkr': 1691, 'md': 598}
    """
    if load_axis not in ("log", "above-pulloff", "linear"):
        raise ValueError(f"load_axis = {load_axis!r}: give 'log', 'above-pulloff' or 'linear'")
    # The axis's load range where none is given is the library's (map::LoadAxis::default_range).
    spec = {
        "lambda_min": _finite(lambda_min, "lambda_min"),
        "lambda_max": _finite(lambda_max, "lambda_max"),
        "nx": int(nx), "ny": int(ny), "load_axis": load_axis,
        "load_min": None if load_min is None else _finite(load_min, "load_min"),
        "load_max": None if load_max is None else _finite(load_max, "load_max"),
        "tolerance": _finite(tolerance, "tolerance"),
        "strength_ratios": [_finite(s, "strength_ratio") for s in strength_ratio],
    }
    inner = _tabor.AdhesionMap(json.dumps(spec), backend, precision, adapter, int(check),
                               _tip_text(tip))
    return AdhesionMap(inner)


def presets():
    """Names of the built-in scenes (``tabor scene --preset NAME``).

    Returns
    -------
    list of str

    Examples
    --------
    >>> import tabor
    >>> tabor.presets()
    ['afm-si', 'pdms-glass', 'mica-sfa', 'graphene-mems', 'hydrogel-titanium']
    """
    return list(_tabor.presets())


def _leaves(d, prefix=""):
    """(dotted key, value) for every leaf of nested dicts and lists."""
    items = d.items() if isinstance(d, dict) else enumerate(d)
    for k, v in items:
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, (dict, list, tuple)):
            yield from _leaves(v, key)
        else:
            yield key, v


def _scene_text(scene):
    """A scene dict as JSON text; ValueError naming non-finite values."""
    try:
        return json.dumps(scene, allow_nan=False)
    except ValueError:
        bad = [k for k, v in _leaves(scene) if isinstance(v, float) and not np.isfinite(v)]
        raise ValueError(f"scene: {', '.join(bad)} is not a finite number; give "
                         "finite values") from None
    except TypeError as e:
        raise TypeError(f"scene: {e}; give numbers, strings, lists and dicts") from None


class Scene:
    """A real contact in SI units, solved as ``tabor scene`` does.

    Parameters
    ----------
    scene : dict
        The scene JSON keys: ``body1``/``body2`` (``youngs_modulus_pa``, ``poisson_ratio``,
        ``radius_m``) or ``e_star_pa`` (Pa) and ``radius_m`` (m); ``work_of_adhesion_j_m2``
        (J/m^2) or ``surface_energies_j_m2``; the range as ``z0_m`` (m), ``s0_pa`` (Pa) or
        ``h0_m`` (m); ``loads_n`` (N) or ``load_range_n``; optional ``tolerance``,
        ``atomic_spacing_m``, ``shear_strength_pa``, ``control`` and ``humidity``. A tip other
        than a sphere replaces ``radius_m``: ``"tip": {"shape": "cone", "half_angle_deg": a}``,
        ``{"shape": "pyramid", "faces": 3, "face_angle_deg": 65.27}`` (as its equivalent cone),
        ``{"shape": "power", "exponent": n, "coefficient": B}`` (B in m^(1-n)) or
        ``{"shape": "capped_cone", "radius_m": R, "half_angle_deg": a}`` (docs/PHYSICS.md
        section 12). Or use :meth:`from_file` or :meth:`preset`.

    Attributes
    ----------
    report : dict
        The whole report, the keys of ``tabor scene --format json``.
    lam : float
        The Maugis parameter.
    recommended_model : str
        The simplest model adequate at every load in contact.
    load_n, contact_radius_m, approach_m : numpy.ndarray
        Per load, in N and m (NaN where no contact).
    zone_radius_m : numpy.ndarray
        Per load, the Dugdale zone's outer radius in m (a tip's scene; NaN for a sphere's).
    model : numpy.ndarray
        Per load, the adequate model.
    warnings : list of list of str
        Per load.

    Raises
    ------
    TypeError
        a scene that is not a dict.
    ValueError
        a missing or bad key (the library's message), a value that is not a finite number.

    Examples
    --------
    >>> import tabor
    >>> s = tabor.Scene({"e_star_pa": 1e9, "radius_m": 1e-6, "work_of_adhesion_j_m2": 0.05,
    ...                  "z0_m": 0.3e-9, "loads_n": [0.0, 1e-6]})
    >>> s
    Scene('scene', lambda=5.234, recommended model 'jkr')
    >>> (s.contact_radius_m * 1e9).round(2).tolist()
    [88.31, 123.34]
    """

    def __init__(self, scene=None, *, _report=None):
        if _report is None:
            if not isinstance(scene, dict):
                raise TypeError("Scene(...) takes a dict; use Scene.from_file or Scene.preset")
            _report = _tabor.scene(_scene_text(scene), None)
        self.report = _report
        self.lam = _report["lambda"]
        self.recommended_model = _report["recommended_model"]
        loads = _report["loads"]
        nan = float("nan")
        self.load_n = np.array([l["load_n"] for l in loads])
        self.contact_radius_m = np.array(
            [l["contact_radius_m"] if l["contact_radius_m"] is not None else nan for l in loads])
        self.approach_m = np.array(
            [l["approach_m"] if l["approach_m"] is not None else nan for l in loads])
        self.zone_radius_m = np.array(
            [l["zone_radius_m"] if l.get("zone_radius_m") is not None else nan for l in loads])
        self.model = np.array([l["model"] for l in loads])
        # A tip's warnings are the scene's, the same at every load.
        self.warnings = [l.get("warnings", _report.get("warnings", [])) for l in loads]

    @classmethod
    def from_file(cls, path):
        """A scene from a JSON file (``tabor scene FILE``).

        Parameters
        ----------
        path : str or os.PathLike
            The scene file (the keys of :class:`Scene`).

        Returns
        -------
        Scene

        Examples
        --------
        >>> import json, os, tempfile, tabor
        >>> path = os.path.join(tempfile.mkdtemp(), "scene.json")
        >>> json.dump({"e_star_pa": 1e9, "radius_m": 1e-6, "work_of_adhesion_j_m2": 0.05,
        ...            "z0_m": 0.3e-9, "loads_n": [0.0]}, open(path, "w"))
        >>> tabor.Scene.from_file(path).recommended_model
        'jkr'
        """
        with open(path) as f:
            return cls(json.load(f))

    @classmethod
    def preset(cls, name):
        """A built-in scene by name (``tabor scene --preset NAME``; see :func:`presets`).

        Parameters
        ----------
        name : str
            ``afm-si``, ``pdms-glass``, ``mica-sfa``, ``graphene-mems`` or ``hydrogel-titanium``.

        Returns
        -------
        Scene

        Raises
        ------
        ValueError
            an unknown name.

        Examples
        --------
        >>> import tabor
        >>> s = tabor.Scene.preset("pdms-glass")
        >>> s.recommended_model, round(s.lam, 1)
        ('jkr', 3378.5)
        """
        return cls(_report=_tabor.scene(None, name))

    def __repr__(self):
        return (f"Scene({self.report.get('name')!r}, lambda={self.lam:.4g}, "
                f"recommended model {self.recommended_model!r})")


def humidity(scene=None, preset=None, rh_min=0.05, rh_max=0.95, points=19,
             contact_angle_deg=None):
    """The pull-off against relative humidity (``tabor humidity``): the solid's adhesion and
    the water meniscus together (two Dugdale zones).

    Parameters
    ----------
    scene : dict, optional
        A scene as :class:`Scene` takes it; or
    preset : str, optional
        a preset name (one of the two).
    rh_min, rh_max : float
        The relative humidity's range (fractions, in (0, 1)).
    points : int
        Number of humidities (2..10000).
    contact_angle_deg : float, optional
        The liquid's contact angle in degrees, replacing the scene's (water at 0 degrees where
        the scene has no ``"humidity"``).

    Returns
    -------
    dict
        The dict of ``tabor humidity --format json``: ``points`` (per RH ``relative_humidity``,
        ``kelvin_radius_m``, ``meniscus_range_m`` (m), ``meniscus_lambda`` (None where no
        meniscus is counted), ``pulloff_solid_N``, ``pulloff_meniscus_N``, ``pulloff_total_N``
        (N, load control), ``meniscus_share``), ``meniscus_dominates_above_rh`` and
        ``warnings`` (where the meniscus model does not hold: a Kelvin radius below one
        molecule, where no meniscus is counted, or a meniscus height above a tenth of R).

    Raises
    ------
    ValueError
        neither or both of ``scene`` and ``preset``, a bad range or count.
    TypeError
        a scene that is not a dict.

    Examples
    --------
    >>> import tabor
    >>> h = tabor.humidity(preset="afm-si", points=3)
    >>> [(round(p["relative_humidity"], 2), round(p["pulloff_total_N"] * 1e9, 2))
    ...  for p in h["points"]]
    [(0.05, -12.21), (0.5, -30.0), (0.95, -30.28)]
    """
    if (scene is None) == (preset is None):
        raise ValueError("give scene (a dict) or preset (a name), one of them")
    if scene is not None and not isinstance(scene, dict):
        raise TypeError("scene: give a dict (the scene JSON keys); or preset=NAME")
    if int(points) < 0:
        raise ValueError(f"points = {points}: give a count in 2..10000")
    return _tabor.humidity(None if scene is None else _scene_text(scene),
                           None if preset is None else str(preset),
                           _real(rh_min, "rh_min"), _real(rh_max, "rh_max"), int(points),
                           _optional(contact_angle_deg, "contact_angle_deg"))


def infer_pulloff(force_n, radius_m, e_star_pa, z0_m=0.3e-9, relative_humidity=None,
                  contact_angle_deg=None):
    """The work of adhesion from a measured pull-off force under JKR, DMT and exact MD, with
    the Tabor self-consistency verdict (``tabor infer``).

    Parameters
    ----------
    force_n : float
        The measured pull-off force in N (its sign is ignored).
    radius_m : float
        The tip (sphere) radius in m.
    e_star_pa : float
        The combined modulus E* in Pa.
    z0_m : float
        The Lennard-Jones range in m (default 0.3 nm).
    relative_humidity : float, optional
        The force measured in air at this relative humidity (in (0, 1)): the water meniscus is
        taken out of it.
    contact_angle_deg : float, optional
        The water's contact angle in degrees (default 0); only with ``relative_humidity``.

    Returns
    -------
    dict
        Dry: ``pulloff_force_n``, ``w_jkr_j_m2``, ``tabor_if_jkr``, ``w_dmt_j_m2``,
        ``tabor_if_dmt``, ``w_md_j_m2`` (J/m^2), ``lambda_md``, ``verdict``, ``warnings``. With
        ``relative_humidity``, ``tabor infer --relative-humidity``'s:
        ``solid_work_of_adhesion_j_m2`` with the meniscus taken out (None where the meniscus
        alone pulls off harder), ``solid_lambda``, ``meniscus``, ``meniscus_only_pulloff_n``,
        ``dry_md_work_of_adhesion_j_m2``, ``verdict`` and ``warnings`` (below one molecule's
        Kelvin radius no meniscus is counted and the solid's w is the dry one).

    Raises
    ------
    ValueError
        a value that is not a finite number or outside its range; a contact angle without a
        humidity.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.infer_pulloff(-12.2073e-9, 20e-9, 91.1444e9)
    >>> round(r["w_md_j_m2"], 4), round(r["w_dmt_j_m2"], 5)
    (0.1, 0.09714)
    >>> r = tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, relative_humidity=0.4,
    ...                         contact_angle_deg=20)
    >>> round(r["solid_work_of_adhesion_j_m2"], 4)
    0.1
    """
    if relative_humidity is not None or contact_angle_deg is not None:
        return _tabor.infer_pulloff_wet(_finite(force_n, "force_n"), _finite(radius_m, "radius_m"),
                                        _finite(e_star_pa, "e_star_pa"), _finite(z0_m, "z0_m"),
                                        _optional(relative_humidity, "relative_humidity"),
                                        _optional(contact_angle_deg, "contact_angle_deg"))
    return _tabor.infer_pulloff(_finite(force_n, "force_n"),
                                           _finite(radius_m, "radius_m"),
                                           _finite(e_star_pa, "e_star_pa"), _finite(z0_m, "z0_m"))


def fit_pairs(loads_n, radii_m, radius_m, z0_m=0.3e-9):
    """Fits w and E* to measured (load, contact radius) pairs with the exact MD model
    (``tabor infer --pairs``), as in a JKR test.

    Parameters
    ----------
    loads_n : array_like
        Loads in N (at most 100,000 pairs).
    radii_m : array_like
        The contact radius at each load, in m.
    radius_m : float
        The sphere's radius R in m.
    z0_m : float
        The Lennard-Jones range in m (default 0.3 nm).

    Returns
    -------
    dict
        ``work_of_adhesion_j_m2`` (J/m^2), ``e_star_pa`` (Pa), ``lambda``, ``tabor_parameter``,
        ``relative_residuals`` (of the contact radius, per pair) and ``rms_relative_residual``.

    Raises
    ------
    ValueError
        arrays of different lengths, values that are not finite or out of range.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.fit_pairs([0, 5e-4, 1e-3, 1.5e-3],
    ...                     [1.012106e-4, 1.169795e-4, 1.280752e-4, 1.369721e-4], 2e-3)
    >>> round(r["work_of_adhesion_j_m2"], 5), round(r["e_star_pa"] / 1e6, 4)
    (0.044, 2.3999)
    """
    (p, a), _ = _flat(loads_n, radii_m, names=["loads_n", "radii_m"])
    return _tabor.fit_pairs(p, a, _finite(radius_m, "radius_m"), _finite(z0_m, "z0_m"))


def fit_curves(height_m, force_n, segment, curve=None, *, radius_m=None, spring_n_m, poisson=None,
               fit_segment="retract", z0_m=None, tilt=False, tolerance=_tabor.DEFAULT_TOLERANCE,
               relative_humidity=None, contact_angle_deg=0.0, surface_tension_n_m=None,
               molar_volume_m3_mol=None, temperature_k=None, tip=None):
    """Fits exact Maugis-Dugdale, and Hertz, DMT and JKR beside it, to AFM force curves
    (``tabor fit``).

    Parameters
    ----------
    height_m : array_like
        Piezo height of the cantilever base in m (larger is farther from the sample).
    force_n : array_like
        Force on the tip in N, positive when repulsive. The tip sits at
        ``height_m + force_n / spring_n_m``.
    segment : array_like
        Per point: 0 approach, 1 retract, -1 a dwell between them, left out of the fit (or the
        strings "approach", "retract", "dwell").
    curve : array_like, optional
        An id per point (numbers or strings) where the arrays hold many curves; each result's
        ``curve`` is its id (None without ``curve``).
    radius_m : float
        Tip radius in m (plausible: 1e-10..1e-3), for a sphere; or give ``tip``.
    spring_n_m : float
        Cantilever spring constant in N/m (plausible: 1e-4..1e4).
    poisson : float, optional
        The sample's Poisson ratio in (-1, 0.5]: adds ``youngs_modulus_pa``.
    tip : dict or str, optional
        A tip that is not a sphere, as a scene's ``"tip"`` (``{"shape": "cone",
        "half_angle_deg": 20}``, ``"pyramid"`` with ``faces`` and ``face_angle_deg``,
        ``"power"`` with ``exponent`` and ``coefficient``, ``"capped_cone"`` with ``radius_m``
        and ``half_angle_deg``) or as ``tabor fit --tip`` writes it (``"cone:20"``). The closed
        forms are then the tip's (Sneddon's punch as ``hertz``, the JKR-type law as ``jkr``; no
        DMT) and lambda is the tip's own; no ``tabor_parameter`` or ``verdict``.
    fit_segment : {"retract", "approach", "both"}
        The segment fitted.
    z0_m : float, optional
        Hold the Lennard-Jones range (m, 1e-12..1e-6) instead of fitting lambda.
    tilt : bool
        Fit a tilted baseline.
    tolerance : float
        For noise-free curves: the relative tolerance of the adequate model, in (0, 1).
    relative_humidity : float, optional
        The curves measured in humid air (in (0, 1)): each fitted curve gets a ``humidity``
        dict with the solid's w, the meniscus taken out.
    contact_angle_deg : float
        The liquid's contact angle in degrees (0..180), with ``relative_humidity``.
    surface_tension_n_m, molar_volume_m3_mol, temperature_k : float, optional
        The liquid (default water: 0.072 N/m, 1.8e-5 m^3/mol, 298.15 K).

    Returns
    -------
    list of dict
        One per curve, in order of first appearance, with the keys of ``tabor fit --format
        json`` (SI units): ``status`` (``ok``, ``invalid_input``, ``no_contact``,
        ``not_converged``) and ``message``; ``e_star_pa``, ``work_of_adhesion_j_m2``,
        ``lambda``, ``tabor_parameter``, ``z0_m``, ``contact_point_m``, each with ``_stderr``;
        the 95% and 68% profile-likelihood intervals ``*_interval_95`` and ``*_interval_68``
        (tuples, None for an end the data leave open); ``lambda_determined``,
        ``lambda_bound``, ``lambda_set_95`` (lambda's 95% set, one interval or several) and
        ``lambda_basins`` (second basins of lambda's profile up to the 99% level); ``rms_residual_n``, ``pulloff_force_measured_n``,
        ``pulloff_force_model_n``; ``models`` (Hertz, DMT, JKR); ``adequate_model`` and
        ``why``; ``verdict``; ``warnings``; ``dwell`` for a curve with one. With
        ``relative_humidity``, ``humidity``: the ``meniscus``, the fitted model's load-controlled
        pull-off and ``solid_work_of_adhesion_j_m2`` (None, with the reason in ``note``, where
        the meniscus alone pulls off harder); where that reading is doubtful (``fair_reading``
        False), ``shape_fit`` is the two-zone law fitted to the curve's shape (``fit``,
        ``z0_m``, ``lambda_profile``, ``lambda_95``, ``lambda_bounded``, ``solid_w_95``).

    Raises
    ------
    ValueError
        an option wrong for every curve (a NaN ``radius_m``, a relative humidity of 0, a
        negative ``spring_n_m``), named, before any curve is fitted; arrays of different
        lengths; a segment value other than 0, 1, -1. What is wrong with one curve's data is
        that curve's ``invalid_input`` status.
    TypeError
        complex heights or forces, unhashable curve ids.
    KeyboardInterrupt
        on Ctrl-C.

    Examples
    --------
    A noise-free curve made with :func:`cycle` under a 40 N/m cantilever (E* = 2 GPa,
    w = 0.04 J/m^2, lambda = 0.3, R = 20 nm), fitted back:

    >>> import numpy as np, tabor
    >>> E, w, lam, R, k = 2e9, 0.04, 0.3, 20e-9, 40.0
    >>> unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)   # the approach unit, m
    >>> c = tabor.cycle(lam, drive="spring", stiffness=k * unit / (np.pi * w * R))
    >>> height = -c["control"] * unit                # the base, from the normalised Delta
    >>> force = c["load"] * np.pi * w * R
    >>> segment = np.where(c["phase"] == "approach", 0, 1)
    >>> f = tabor.fit_curves(height, force, segment, radius_m=R, spring_n_m=k)[0]
    >>> f["status"], f["adequate_model"]
    ('ok', 'md')
    >>> print(f"{f['e_star_pa']:.3g} {f['work_of_adhesion_j_m2']:.3g} {f['lambda']:.3g}")
    2e+09 0.04 0.3
    """
    h = _c(_numbers(height_m, "height_m").ravel())
    f = _c(_numbers(force_n, "force_n").ravel())
    seg = np.asarray(segment).ravel()
    if seg.dtype.kind in "cmMO":  # complex, dates and objects refused as the others are
        seg = _numbers(seg, "segment")
    if seg.dtype.kind in "US":
        names = {"approach": 0, "retract": 1, "dwell": -1}
        try:
            seg = np.array([names[str(v)] for v in seg])
        except KeyError as e:
            raise ValueError(f"segment {e}: use approach/retract/dwell or 0/1/-1") from None
    # 0, 1 or -1 exactly: a cast to integers would read 0.5 as approach and 1.5 as retract.
    bad = ~np.isin(seg, (0, 1, -1))
    if bad.any():
        raise ValueError(f"segment value {seg[np.argmax(bad)]!r} at index {int(np.argmax(bad))}: "
                         "use 0 (or \"approach\"), 1 (or \"retract\") and -1 (or \"dwell\")")
    seg = _c(seg, np.int64)
    if curve is None:
        ids = np.zeros(len(h), dtype=np.int64)
        labels = None
    else:
        labels, ids = _curve_ids(curve)
    if not (len(h) == len(f) == len(seg) == len(ids)):
        raise ValueError("height_m, force_n, segment (and curve) must have the same length")
    # JSON has no NaN or infinity: those go as text, and the library's check names them.
    def num(x, name):
        v = _real(x, name)
        return v if np.isfinite(v) else repr(v)
    if tip is not None and radius_m is not None:
        raise ValueError("radius_m and tip: give one (a sphere's radius, or the tip)")
    options = {"spring": num(spring_n_m, "spring_n_m"),
               "segment": fit_segment, "tilt": bool(tilt), "tolerance": num(tolerance, "tolerance")}
    if tip is None:
        options["radius"] = num(radius_m if radius_m is not None else float("nan"), "radius_m")
    elif isinstance(tip, (str, dict)):
        options["tip"] = tip
    else:
        raise TypeError(f"tip: give a dict like a scene's tip or a string like 'cone:20', not {type(tip).__name__}")
    if poisson is not None:
        options["poisson"] = num(poisson, "poisson")
    if z0_m is not None:
        options["z0"] = num(z0_m, "z0_m")
    if relative_humidity is not None:
        options["relative_humidity"] = num(relative_humidity, "relative_humidity")
        options["contact_angle_deg"] = num(contact_angle_deg, "contact_angle_deg")
        for k, v in (("surface_tension_n_m", surface_tension_n_m),
                     ("molar_volume_m3_mol", molar_volume_m3_mol), ("temperature_k", temperature_k)):
            if v is not None:
                options[k] = num(v, k)
    out = _tabor.fit_curves(ids, seg, h, f, json.dumps(options))
    for r in out:
        # Each interval a (low, high) tuple, None for an end the data leave open (as JSON's
        # null), whether one end is open or both.
        for k, v in r.items():
            if k.endswith(("_interval_68", "_interval_95")) and v is not None:
                r[k] = tuple(None if e is None or np.isnan(e) else float(e) for e in v)
    for r in out:  # each curve's own id as given (None where no curve= was given)
        label = None if labels is None else labels[int(r["curve"])]
        r["curve"] = label.item() if isinstance(label, np.generic) else label
    return out


def _curve_ids(curve):
    """(labels, int64 index of each point's label) for curve ids of any hashable type: sorted
    labels where they compare, else in order of first appearance."""
    c = np.asarray(curve).ravel()
    if c.dtype.kind != "O":
        labels, ids = np.unique(c, return_inverse=True)
        return labels, _c(ids, np.int64)
    index, labels = {}, []
    try:
        ids = np.fromiter((index.setdefault(v, len(index)) for v in c), dtype=np.int64,
                          count=len(c))
    except TypeError as e:
        raise TypeError(f"curve: each id must be hashable (a number or a string): {e}") from None
    labels = np.empty(len(index), dtype=object)
    for v, i in index.items():
        labels[i] = v
    return labels, ids


def fit_curve(height_m, force_n, segment, **options):
    """One force curve: :func:`fit_curves` for a single curve, its dict.

    Parameters
    ----------
    height_m, force_n, segment : array_like
        As :func:`fit_curves` (m, N, 0/1/-1 per point).
    **options
        The keyword options of :func:`fit_curves` (``radius_m`` and ``spring_n_m`` needed).

    Returns
    -------
    dict
        The curve's fit, the keys of :func:`fit_curves`.

    Raises
    ------
    ValueError, TypeError
        As :func:`fit_curves`.

    Examples
    --------
    >>> import numpy as np, tabor
    >>> E, w, lam, R, k = 2e9, 0.04, 0.3, 20e-9, 40.0
    >>> unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)
    >>> c = tabor.cycle(lam, drive="spring", stiffness=k * unit / (np.pi * w * R))
    >>> s = ~c["jump"]  # one force per height: a jump's landing shares its fold's
    >>> noise = np.random.default_rng(0).normal(0, 5e-11, s.sum())  # 1.1% of the pull-off
    >>> f = tabor.fit_curve(-c["control"][s] * unit, c["load"][s] * np.pi * w * R + noise,
    ...                     np.where(c["phase"][s] == "approach", 0, 1), radius_m=R, spring_n_m=k)
    >>> lo, hi = f["work_of_adhesion_j_m2_interval_95"]
    >>> bool(lo < 0.04 < hi)
    True
    """
    return fit_curves(height_m, force_n, segment, **options)[0]


def fit_afmformats(data, radius_m=None, spring_n_m=None, *, poisson=None, fit_segment="retract",
                   z0_m=None, tilt=False, tolerance=_tabor.DEFAULT_TOLERANCE,
                   relative_humidity=None, contact_angle_deg=0.0, surface_tension_n_m=None,
                   molar_volume_m3_mol=None, temperature_k=None, tip=None):
    """Fits curves read by afmformats (``afmformats.load_data(path)``: JPK, Asylum/Igor,
    NT-MDT, AFM Workshop, ...), each with the spring constant of its file.

    Uses ``height (measured)`` where present, else ``height (piezo)``. Approach and retract are
    taken from the heights, whatever the file's segment numbers: a pause or a dwell (stress
    relaxation, creep) is left out, and a curve kept in one segment is split where the base
    turns (each said in ``warnings``); a curve without a clear turn, or whose file gives a
    spring constant out of range, gets the status ``invalid_input``. A dwell between approach
    and retract is reported in ``dwell`` (its forces, relaxation and creep); where the force
    relaxed during it, the retract is no loading curve and the approach is fitted instead (said
    in ``message``).

    Parameters
    ----------
    data : afmformats.AFMForceDistance or list of them
        What ``afmformats.load_data`` returns (a file without a sensitivity is loaded with
        ``afmformats.load_data(path, meta_override={"sensitivity": ...})``).
    radius_m : float
        Tip radius in m, for a sphere; or give ``tip``.
    spring_n_m : float, optional
        Spring constant in N/m for every curve, instead of each file's own (needed where a file
        has none).
    poisson, fit_segment, z0_m, tilt, tolerance, relative_humidity, contact_angle_deg,
    surface_tension_n_m, molar_volume_m3_mol, temperature_k, tip
        As :func:`fit_curves` (``fit_segment="approach"`` fits the approach; ``tip`` a cone, a
        pyramid, a power law or a capped cone).

    Returns
    -------
    list of dict
        As :func:`fit_curves`, each with ``path`` and ``enum`` from the data.

    Raises
    ------
    ValueError
        a bad option, named, before any curve is fitted, as :func:`fit_curves` does; a file
        without a spring constant where ``spring_n_m`` is not given.

    Examples
    --------
    >>> import afmformats, numpy as np, tabor
    >>> E, w, lam, R, k = 2e9, 0.04, 0.3, 20e-9, 40.0
    >>> unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)
    >>> c = tabor.cycle(lam, drive="spring", stiffness=k * unit / (np.pi * w * R))
    >>> data = {"height (measured)": -c["control"] * unit, "force": c["load"] * np.pi * w * R,
    ...         "segment": np.where(c["phase"] == "approach", 0, 1)}
    >>> meta = {"spring constant": k, "path": "synthetic", "enum": 0}
    >>> fd = afmformats.AFMForceDistance(data, meta, diskcache=False)
    >>> r = tabor.fit_afmformats(fd, radius_m=R)[0]
    >>> r["status"], r["path"], round(r["work_of_adhesion_j_m2"], 4)
    ('ok', 'synthetic', 0.04)
    """
    options = dict(radius_m=radius_m, poisson=poisson, fit_segment=fit_segment, z0_m=z0_m,
                   tilt=tilt, tolerance=tolerance, relative_humidity=relative_humidity,
                   contact_angle_deg=contact_angle_deg,
                   surface_tension_n_m=surface_tension_n_m,
                   molar_volume_m3_mol=molar_volume_m3_mol, temperature_k=temperature_k, tip=tip)
    # The options checked once, on no data (with a valid stand-in for a spring read per file):
    # options wrong for every curve raise, a file's own bad spring constant is its curve's status.
    fit_curves([], [], [], spring_n_m=1.0 if spring_n_m is None else spring_n_m, **options)
    items = [data] if hasattr(data, "columns") else list(data)
    springs = []
    for d in items:  # every curve's spring first: a missing one stops before any fit
        # .get, not [...]: afmformats' metadata raises a BaseException for a missing key.
        k = d.metadata.get("spring constant") if spring_n_m is None else spring_n_m
        if k is None:
            raise ValueError(f"{d.metadata.get('path', 'a curve')}: the file gives no spring "
                             "constant: pass spring_n_m= (N/m)")
        springs.append(_real(k, "spring_n_m"))
    out = []
    for d, k in zip(items, springs):
        col = "height (measured)" if "height (measured)" in d.columns else "height (piezo)"
        h = np.asarray(d[col], dtype=float)
        f = np.asarray(d["force"], dtype=float)
        try:
            code, notes = _tabor.plan_segments(h, np.asarray(d["segment"], dtype=np.int64))
            # -1 (a pause, a dwell) left out by the fit, which reports the dwell at the turn.
            r = fit_curve(h, f, np.asarray(code), spring_n_m=k, **options)
            r["warnings"] = list(notes) + list(r.get("warnings", []))
        except ValueError as e:  # the file's segments or its own spring constant
            why = str(e)
            r = _refused(f"the file's spring constant: {why}" if why.startswith("spring_n_m")
                         else why)
        r["path"] = str(d.metadata.get("path", ""))
        r["enum"] = int(d.metadata.get("enum", 0))
        out.append(r)
    return out


def _refused(message):
    """A curve that could not be fitted at all: the keys of a fit, its numbers None."""
    keys = ["e_star_pa", "work_of_adhesion_j_m2", "lambda", "contact_point_m",
            "rms_residual_n", "pulloff_force_measured_n", "adequate_model"]
    r = {k: None for k in keys}
    r.update(status="invalid_input", message=message, warnings=[], why="")
    return r


def cycle(lam, drive="grips", stiffness=None, max_load=2.0, stress_ratio=None,
          range_ratio=None, tip=None):
    """An approach-retract cycle (``tabor cycle``): the equilibrium path followed under rigid
    grips, dead load or a spring, its jumps and the energy lost per cycle.

    Parameters
    ----------
    lam : float
        Maugis parameter lambda (with two zones, the solid's).
    drive : {"grips", "dead_load", "spring"}
        The control.
    stiffness : float, optional
        The spring's normalised stiffness kbar = k (pi^2 w^2 R / K^2)^(1/3) / (pi w R), with
        ``drive="spring"``.
    max_load : float
        The largest normalised load (in pi w R) of the approach.
    stress_ratio, range_ratio : float, optional
        A second Dugdale zone (a water meniscus: its stress and range over the solid's; both or
        neither): the cycle of both zones, in the units of the total w.
    tip : str or dict, optional
        A tip that is not a sphere (``tabor cycle --tip``): ``"cone"``, ``"power:N"`` or
        ``"capped-cone:R_OVER_L:HALF_ANGLE_DEG"``, with ``lam`` its Maugis parameter and the
        loads in its units (docs/PHYSICS.md section 12). A scene (a dict with a ``"tip"``, ``e_star_pa``
        and ``work_of_adhesion_j_m2``) gives its tip in the units of its E* and w: any tip in SI
        units, a measured profile among them (``--tip scene:FILE``).

    Returns
    -------
    Result
        Arrays of the followed path: ``phase`` (approach, retract), ``branch`` (free,
        non_contact, contact), ``approach`` (Dbar), ``load`` (Pbar), ``A``, ``C`` (the cohesive
        zone's radius), ``control`` (the controlled variable: Dbar, Pbar, or the base
        displacement Delta = Dbar + Pbar/kbar), ``jump`` (True at the first point after a
        jump); ``metadata``: ``hysteresis`` (energy lost per cycle in pi w R times the approach
        unit; None under dead load), ``jumps``, ``drive``.

    Raises
    ------
    ValueError
        a bad lambda, drive, stiffness or ratio.

    Examples
    --------
    >>> import tabor
    >>> c = tabor.cycle(1.0)
    >>> round(c.metadata["hysteresis"], 6)
    0.496319
    >>> [round(j["from"]["load"], 6) for j in c.metadata["jumps"]]
    [0.0, -0.891741]
    """
    opt = lambda v, n: None if v is None else _real(v, n)
    c = _tabor.cycle(_real(lam, "lam"), drive, opt(stiffness, "stiffness"),
                     _real(max_load, "max_load"), opt(stress_ratio, "stress_ratio"),
                     opt(range_ratio, "range_ratio"), _tip_text(tip))
    steps = c["steps"]
    out = {
        "phase": np.array([s["phase"] for s in steps]),
        "branch": np.array([s["point"]["branch"] for s in steps]),
        "approach": np.array([s["point"]["approach"] for s in steps]),
        "load": np.array([s["point"]["load"] for s in steps]),
        "A": np.array([s["point"]["a"] for s in steps]),
        "C": np.array([s["point"]["c"] for s in steps]),
        "control": np.array([s["control"] for s in steps]),
        "jump": np.array([s["jump"] for s in steps], dtype=bool),
    }
    return Result(out, {"hysteresis": c["hysteresis"], "jumps": c["jumps"],
                        "drive": c["drive"]})


def profile(lam, load=None, approach=None, radius=None, points=400, stress_ratio=None,
            range_ratio=None, tip=None):
    """Pressure and gap inside and around the contact (``tabor profile``) for the MD state
    given by exactly one of ``load``, ``approach``, ``radius``, and Hertz, DMT and JKR at the
    same load.

    Parameters
    ----------
    lam : float
        Maugis parameter lambda (with two zones, the solid's).
    load, approach, radius : float, optional
        The state: normalised load Pbar, approach Dbar or contact radius A (one of them).
    points : int
        Radii sampled (at most 100,000), uniformly plus clusters at every a and c.
    stress_ratio, range_ratio : float, optional
        A second Dugdale zone: the two-zone profile (model ``two_zone`` first, with both zone
        edges), then Hertz, DMT and JKR of the total w.
    tip : str or dict, optional
        A tip that is not a sphere (``tabor profile --tip``): ``"cone"``, ``"power:N"`` or
        ``"capped-cone:R_OVER_L:HALF_ANGLE_DEG"``, with ``lam`` its Maugis parameter and the
        values in its units. A scene (a dict with a ``"tip"``, ``e_star_pa``
        and ``work_of_adhesion_j_m2``) gives its tip in the units of its E* and w: any tip in SI
        units, a measured profile among them (``--tip scene:FILE``). The result is then the one state's ``r``, ``pressure`` (NaN at a
        cone's apex), ``gap``, ``a``, ``c``, ``load``, ``approach``, ``status`` and
        ``energy_release_rate_over_w``.

    Returns
    -------
    dict
        ``models``: one dict per model with arrays ``r`` (in (pi w R^2 / K)^(1/3)),
        ``pressure`` (in (pi w K^2 / R)^(1/3), compressive positive; NaN where singular) and
        ``gap`` (in the approach unit), and ``a``, ``c``, ``load``, ``max_tension``,
        ``max_tension_at``, ``stress_intensity``, ``energy_release_rate_over_w``, ``notes``.

    Raises
    ------
    ValueError
        not exactly one of ``load``, ``approach``, ``radius``; a value outside the domain.

    Examples
    --------
    >>> import tabor
    >>> p = tabor.profile(1.0, load=0.0)
    >>> [m["model"] for m in p["models"]]
    ['md', 'hertz', 'dmt', 'jkr']
    >>> round(p["models"][0]["a"], 5), round(p["models"][0]["c"], 5)
    (1.63609, 2.00569)
    """
    given = [(k, v) for k, v in (("load", load), ("approach", approach), ("radius", radius))
             if v is not None]
    if len(given) != 1:
        raise ValueError("give exactly one of load=, approach= or radius=")
    # With both ratios the two-zone state (``tabor profile --stress-ratio --range-ratio``):
    # its model "two_zone" first, with both zone edges, then Hertz, DMT and JKR of the total w.
    p = _tabor.profile(_real(lam, "lam"), given[0][0], _real(given[0][1], given[0][0]),
                       int(points), _optional(stress_ratio, "stress_ratio"),
                       _optional(range_ratio, "range_ratio"), _tip_text(tip))
    if tip is not None:
        # A tip's profile (``tabor profile --tip``): one state, its arrays at the top level.
        p["r"] = np.array(p["r"], dtype=float)
        p["pressure"] = np.array([np.nan if q is None else q for q in p["pressure"]],
                                 dtype=float)
        p["gap"] = np.array(p["gap"], dtype=float)
        return p
    for m in p["models"]:
        m["r"] = np.array(m["r"], dtype=float)
        m["pressure"] = np.array([np.nan if q is None else q for q in m["pressure"]],
                                 dtype=float)
        m["gap"] = np.array(m["gap"], dtype=float)
    return p


def rough(lam, sigma, min_separation, max_separation=None, points=400, stress_ratio=None,
          range_ratio=None):
    """A rough surface of Maugis-Dugdale summits (Greenwood-Williamson, Gaussian heights)
    through an approach and a retract, as ``tabor rough`` computes it.

    Parameters
    ----------
    lam : float
        The summits' Maugis parameter.
    sigma : float
        Standard deviation of the summit heights, in the summit's approach unit
        (pi^2 w^2 R / K^2)^(1/3).
    min_separation : float
        The deepest separation of the flat from the mean summit plane (approach units).
    max_separation : float, optional
        Where the approach starts (default: where no summit feels the flat).
    points : int
        Separations each way (2..10000).
    stress_ratio, range_ratio : float, optional
        A water meniscus on every summit (both): the two-zone law, units built on the total w.

    Returns
    -------
    dict
        ``approach`` and ``retract`` (arrays ``separation``, ``load`` per summit in pi w R,
        ``contact_fraction``, ``noncontact_fraction``, and the load's parts ``contact_load``
        and ``noncontact_load``), ``pulloff_load``, ``pulloff_separation``, ``hysteresis``
        (energy lost per summit per cycle), ``smooth_pulloff``, ``fuller_tabor_parameter``,
        ``quadrature_error`` (the largest error estimate of the quadrature over the loads
        given), ``warnings`` (what the range or the sampling cannot show), ``lambda``,
        ``sigma``.

    Raises
    ------
    ValueError
        a bad sigma, separation, count or ratio.
    KeyboardInterrupt
        on Ctrl-C.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.rough(2.0, 0.5, -1.0, points=50)
    >>> round(r["pulloff_load"], 4), round(r["hysteresis"], 4)
    (-1.2081, 0.8805)
    """
    rho = None if stress_ratio is None else float(stress_ratio)
    eta = None if range_ratio is None else float(range_ratio)
    return _tabor.rough(float(lam), float(sigma), float(min_separation),
                        None if max_separation is None else float(max_separation), int(points),
                        rho, eta)


def rough_ensemble(lam, heights, separations, min_separation=None):
    """Load per summit and branch fractions of an explicit ensemble of summit heights, all of
    one Maugis parameter.

    Parameters
    ----------
    lam : float
        The summits' Maugis parameter.
    heights : array_like
        Summit heights in the approach unit (pi^2 w^2 R / K^2)^(1/3).
    separations : array_like
        Separations of the flat from the mean plane (approach units); each a finite number.
    min_separation : float, optional
        Without it, the states on the approach; with it, on the retract after pressing to it.

    Returns
    -------
    dict
        NumPy arrays ``separation``, ``load`` (per summit, in pi w R), ``contact_fraction``,
        ``noncontact_fraction``, ``contact_load``, ``noncontact_load``.

    Raises
    ------
    ValueError
        a separation that is not a finite number, a bad lambda.

    Examples
    --------
    >>> import numpy as np, tabor
    >>> h = np.random.default_rng(1).normal(0.0, 0.5, 2000)
    >>> e = tabor.rough_ensemble(2.0, h, [0.5, 0.0, -0.5])
    >>> e["contact_fraction"].round(4).tolist()
    [0.352, 0.7345, 0.9515]
    """
    h = _numbers(heights, "heights").ravel()
    d = _numbers(separations, "separations").ravel()
    d_min = _optional(min_separation, "min_separation")  # the library checks both
    # Each separation's state depends only on it and min_separation: solved in chunks of about
    # 2e6 summit-states (a fraction of a second each).
    step = max(1, 2_000_000 // max(1, len(h)))
    hl = h.tolist()
    parts = [_tabor.rough_ensemble(_real(lam, "lam"), hl, d[i:i + step].tolist(), d_min)
             for i in range(0, max(1, len(d)), step)]
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def _rough_scene(scene, preset):
    """A rough scene as JSON text (or None with a preset), checked as the command line reads it."""
    if (scene is None) == (preset is None):
        raise ValueError("give a rough scene (a dict) or a preset name, one of them")
    if scene is None:
        return None
    if not isinstance(scene, dict):
        raise TypeError("scene: give a dict (as tabor rough --scene reads)")
    try:
        return json.dumps(scene, allow_nan=False)
    except ValueError:
        raise ValueError("scene: a value is not a finite number; give finite values") from None


def rough_scene(scene=None, preset=None, points=400):
    """A rough scene in SI units through an approach and a retract, as ``tabor rough --scene
    FILE`` or ``tabor rough --preset NAME`` computes it (dry, or with the scene's ``humidity``
    a water meniscus on every summit).

    Parameters
    ----------
    scene : dict or str or os.PathLike, optional
        A dict or the path of a JSON file: the materials of a scene (``e_star_pa`` or two
        bodies, ``work_of_adhesion_j_m2``, one of ``z0_m``, ``s0_pa``, ``h0_m``) with
        ``summit_radius_m`` (m), ``summit_density_m2`` (1/m^2), ``sigma_m`` (m),
        ``nominal_area_m2`` (m^2), optional ``min_separation_m`` and ``humidity``; or
    preset : str, optional
        ``mems-polysilicon``, ``pdms-rough-glass`` or ``colloidal-probe-wafer``.
    points : int
        Separations each way (2..10000).

    Returns
    -------
    dict
        The dict ``tabor rough --scene --format json`` writes, the same numbers to the last
        bit: ``approach`` and ``retract`` (arrays ``separation_m``, ``force_n``,
        ``nominal_pressure_pa``, ``real_contact_area_m2``, ``contact_fraction``,
        ``noncontact_fraction``), ``pulloff_force_n``, ``pulloff_stress_pa``,
        ``pulloff_separation_m``, ``hysteresis_j``, ``lambda``, ``summits``, ``warnings``, ...
        and, with a humidity, ``meniscus`` and ``dry_pulloff_force_n``.

    Raises
    ------
    ValueError
        neither or both of ``scene`` and ``preset``; a bad key or value.
    TypeError
        a scene that is not a dict or a path.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.rough_scene(preset="mems-polysilicon", points=50)
    >>> print(f"{r['pulloff_force_n']:.3g} N")
    -2.09e-05 N
    """
    if isinstance(scene, (str, os.PathLike)) and preset is None:
        with open(scene) as f:
            text = f.read()
    else:
        text = _rough_scene(scene, preset)
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or points < 0:
        raise ValueError(f"points = {points!r}: give a count >= 2")
    return _tabor.rough_scene(text, None if preset is None else str(preset), int(points))


def rough_asperities(heights_m, radii_m, scene=None, preset=None, min_separation_m=None,
                     points=400, summits="tables", backend="cpu"):
    """An explicit ensemble of summits in SI units, as ``tabor rough --asperities`` computes
    it: each summit its own radius, lambda and history.

    Parameters
    ----------
    heights_m : array_like
        Summit heights in m.
    radii_m : array_like
        Summit radii in m, one per height.
    scene : dict, optional
        A rough scene (as ``tabor rough --scene`` reads) for the materials; or
    preset : str, optional
        a rough preset name.
    min_separation_m : float, optional
        The deepest separation in m (default: the mean height less three standard
        deviations).
    points : int
        Separations each way.
    summits : {"tables", "exact"}
        ``tables`` (default) takes the contact states from tables over the summits' lambdas
        with their error measured (``table_error``); ``exact`` solves every state.
    backend : {"cpu", "gpu", "auto"}
        Where the tables are solved and, on a GPU with f64 shaders, the summits stepped
        (``tabor rough --backend``); ``cpu`` (default) is the f64 solver on all cores.

    Returns
    -------
    dict
        ``summits``, ``approach`` and ``retract`` (arrays ``separation_m``, ``force_n``,
        ``real_contact_area_m2``, ``contact_fraction``, ``noncontact_fraction``),
        ``pulloff_force_n``, ``pulloff_separation_m``, ``summit_solver``, ``table_error``,
        ``summit_states``, ``seconds``.

    Raises
    ------
    ValueError
        bad summits (the library's message), neither or both of ``scene`` and ``preset``, a
        humid scene (explicit summits are dry).

    Examples
    --------
    >>> import numpy as np, tabor
    >>> h = np.random.default_rng(0).normal(0.0, 0.6e-9, 500)
    >>> r = tabor.rough_asperities(h, np.full(500, 0.5e-6), preset="mems-polysilicon", points=50)
    >>> r["summits"], r["summit_solver"]
    (500, 'tables (cpu f64)')
    """
    h = _numbers(heights_m, "heights_m").ravel()
    r = _numbers(radii_m, "radii_m").ravel()
    text = _rough_scene(scene, preset)
    d_min = None if min_separation_m is None else _finite(min_separation_m, "min_separation_m")
    if int(points) < 0:
        raise ValueError(f"points = {points}: give a count >= 2")
    return _tabor.rough_asperities(h.tolist(), r.tolist(), text,
                                   None if preset is None else str(preset), d_min, int(points),
                                   str(summits), str(backend))


def rough_topography(heights_m, pixel_m, scene=None, preset=None, min_separation_m=None,
                     points=400, summits="tables", backend="cpu"):
    """A measured height map as ``tabor rough --topography --pixel-m`` takes it: its summits are
    the pixels above their eight neighbours, with the radius from the mean curvature there (as
    Greenwood and Williamson did), then the cycle of :func:`rough_asperities`.

    Parameters
    ----------
    heights_m : array_like
        A 2-D height map in m.
    pixel_m : float
        The pixel spacing in m.
    scene, preset, min_separation_m, points, summits, backend
        As :func:`rough_asperities`.

    Returns
    -------
    dict
        As :func:`rough_asperities`.

    Raises
    ------
    ValueError
        a map that is not 2-D, bad values (the library's message).

    Examples
    --------
    >>> import numpy as np, tabor
    >>> x = np.arange(64) * 10e-9
    >>> z = 2e-9 * np.outer(np.sin(2 * np.pi * x / 160e-9), np.sin(2 * np.pi * x / 160e-9))
    >>> tabor.rough_topography(z, 10e-9, preset="mems-polysilicon", points=50)["summits"]
    32
    """
    z = _numbers(heights_m, "heights_m")
    if z.ndim != 2:
        raise ValueError(f"heights_m has shape {z.shape}: give a 2-D height map")
    text = _rough_scene(scene, preset)
    d_min = None if min_separation_m is None else _finite(min_separation_m, "min_separation_m")
    if int(points) < 0:
        raise ValueError(f"points = {points}: give a count >= 2")
    return _tabor.rough_topography(np.ascontiguousarray(z).ravel().tolist(), int(z.shape[1]),
                                   _real(pixel_m, "pixel_m"), text,
                                   None if preset is None else str(preset), d_min, int(points),
                                   str(summits), str(backend))


def rough_pulloff(lambdas=(0.01, 0.1, 1.0, 1000.0), sigma_min=0.01, sigma_max=10.0, points=24,
                  press_sigmas=3.0):
    """Fuller and Tabor's figure, as ``tabor rough-pulloff`` computes it: for each summit lambda,
    the pull-off per summit after pressing the flat below the mean summit plane, over a range
    of roughness.

    Parameters
    ----------
    lambdas : sequence of float
        The summits' Maugis parameters.
    sigma_min, sigma_max : float
        The roughness range (approach units), log-spaced.
    points : int
        Roughnesses per lambda.
    press_sigmas : float
        How deep the flat is pressed, in sigma (at most 6 either way).

    Returns
    -------
    list of dict
        One per lambda: ``lambda``, ``smooth_pulloff``, and NumPy arrays ``sigma``,
        ``fuller_tabor_parameter``, ``pulloff`` (per summit, pi w R), ``relative_pulloff``.

    Raises
    ------
    ValueError
        a bad range, count or press depth.

    Examples
    --------
    >>> import tabor
    >>> r = tabor.rough_pulloff([1.0], points=3)
    >>> r[0]["relative_pulloff"].round(4).tolist()
    [0.9999, 0.9163, 0.0]
    """
    if int(points) < 0:
        raise ValueError(f"points = {points}: give a count >= 0")
    lams = [float(v) for v in np.atleast_1d(_numbers(lambdas, "lambdas")).ravel()]
    return _tabor.rough_pulloff(lams, _real(sigma_min, "sigma_min"), _real(sigma_max, "sigma_max"),
                                int(points), _real(press_sigmas, "press_sigmas"))


def rough_map(lambda_min=1e-2, lambda_max=1e3, nx=256, sigma_min=1e-2, sigma_max=1e2, ny=256,
              tolerance=_tabor.DEFAULT_TOLERANCE, press_sigmas=3.0, check=64):
    """The rough adhesion map, as ``tabor rough-map`` computes it: over lambda and the
    roughness sigma, the pull-off per summit after pressing to ``-press_sigmas * sigma`` and
    retracting, relative to the smooth summit's, and the simplest adequate summit model.

    Parameters
    ----------
    lambda_min, lambda_max : float
        The summits' Maugis parameter axis (log).
    nx : int
        Lambdas.
    sigma_min, sigma_max : float
        The roughness axis (log, approach units).
    ny : int
        Roughnesses.
    tolerance : float
        The region test's tolerance (default 0.05).
    press_sigmas : float
        Press depth in sigma (at most 6).
    check : int
        Points re-solved by the adaptive quadrature.

    Returns
    -------
    dict
        NumPy arrays: ``lambda`` (nx), ``sigma`` (ny), ``smooth_pulloff`` (nx); ``pulloff``,
        ``relative_pulloff``, ``pulloff_separation`` and ``region`` (uint8 codes named by
        ``region_names``), each (ny, nx); ``model_error`` (ny, nx, 4: Hertz, Bradley, DMT,
        JKR); ``table_error`` and the check of ``check`` points against the adaptive quadrature
        (``check_points``, ``check_max_relative_difference``).

    Raises
    ------
    ValueError
        a bad range, count, tolerance or press depth.
    KeyboardInterrupt
        on Ctrl-C.

    Examples
    --------
    >>> import tabor
    >>> m = tabor.rough_map(nx=8, ny=8, check=0)
    >>> m["region"].shape, m["region_names"][:6]
    ((8, 8), ['no_contact', 'hertz', 'rigid', 'dmt', 'jkr', 'md'])
    """
    for name, v in [("nx", nx), ("ny", ny), ("check", check)]:
        if int(v) < 0:
            raise ValueError(f"{name} = {v}: give a count >= 0")
    d = _tabor.rough_map(_real(lambda_min, "lambda_min"), _real(lambda_max, "lambda_max"),
                         int(nx), _real(sigma_min, "sigma_min"), _real(sigma_max, "sigma_max"),
                         int(ny), _real(tolerance, "tolerance"),
                         _real(press_sigmas, "press_sigmas"), int(check))
    shape = (len(d["sigma"]), len(d["lambda"]))
    for k in ["pulloff", "relative_pulloff", "pulloff_separation"]:
        d[k] = d[k].reshape(shape)
    d["region"] = np.frombuffer(bytes(d["region"]), dtype=np.uint8).reshape(shape).copy()
    d["model_error"] = d["model_error"].reshape(shape + (4,))
    return d


def dem_law(lam=None, scene=None, overlap_max=None, stress_ratio=None, range_ratio=None):
    """The Maugis-Dugdale force-overlap law for particle (DEM) codes, dry or with a water
    meniscus, as ``tabor dem-law`` and the C library ``libtabor_dem`` evaluate it: the approach
    (attraction across the gap, the jump into contact) and the retract (the contact branch down
    to its fold under rigid grips, the jump out, the meniscus's bridge across the gap), each
    contact carrying the stretch of the law's path it is on as a history code.

    Parameters
    ----------
    lam : float, optional
        The (solid's) Maugis parameter of a normalised law: forces in ``pi w R``, overlaps in
        ``(pi^2 w^2 R / K^2)^(1/3)`` (positive interpenetrating). Or:
    scene : dict or str or os.PathLike, optional
        A pair in SI units, a dict or the path of a JSON file with ``tabor scene``'s keys
        (``body1`` and ``body2``, or ``e_star_pa`` and ``radius_m``; ``work_of_adhesion_j_m2``;
        ``s0_pa``, ``h0_m`` or ``z0_m``; ``humidity`` for a water meniscus): overlaps in m,
        forces in N.
    overlap_max : float, optional
        The largest overlap the table covers (approach units, or m for a scene) [default: 10
        approach units]; beyond it an evaluation extrapolates the last cubic.
    stress_ratio, range_ratio : float, optional
        With ``lam``, both or neither: a meniscus beside the solid's zone, its stress and range
        over the solid's (the two-zone law of :func:`cycle`; loads and overlaps in the units of
        the total w).

    Returns
    -------
    DemLaw
        ``law.info`` (a dict: ``model``, ``lambda``, ``stress_ratio`` and ``range_ratio`` or
        ``meniscus`` where there is one, ``histories`` (every history code is below it),
        ``attraction_from``, ``jump_in``, ``jump_out``, ``jump_out_force``, ``non_contact_end``
        (where the retract comes free after crossing the gap; None where it comes free at the
        jump out), ``pulloff_force``, ``loop_energy`` (the energy lost per slow cycle),
        ``table_error`` (the table's largest measured error relative to max(|pull-off|,
        |force|)), ``table_nodes``, ``overlap_max``, ``force_scale``, ``length_scale``,
        ``units``); ``law.eval(overlap, history)`` (float64 and uint8 arrays of one length: the
        forces and stiffnesses dF/d(overlap), the history codes updated in place: 0 for a new
        contact, apart); ``law.branches(history)`` (each code's branch: 0 free, 1 non-contact,
        2 contact); ``law.drive(overlap_min, overlap_max, points)`` (the pair driven out and
        back under displacement control: ``{"approach": {"overlap", "force"}, "retract":
        {...}}``); ``law.loop_energy(overlap_max)``.

    Raises
    ------
    ValueError
        neither or both of ``lam`` and ``scene``; a lambda, ratio or overlap outside the
        domain; one ratio without the other, or ratios with a scene; a scene key the law under
        displacement control does not use (``loads_n``, ``control``, ...).
    TypeError
        a scene that is not a dict or a path.

    Examples
    --------
    >>> import numpy as np, tabor
    >>> law = tabor.dem_law(10.0)
    >>> round(law.info["jump_out_force"], 4), round(law.info["loop_energy"], 4)
    (-0.8337, 1.1918)
    >>> history = np.zeros(3, dtype=np.uint8)          # three new contacts, apart
    >>> f, k = law.eval(np.array([-1.0, 0.0, 1.0]), history)
    >>> law.branches(history).tolist(), f.round(4).tolist()
    ([0, 2, 2], [0.0, -1.3345, -0.1621])
    >>> f, k = law.eval(np.array([-0.5, -0.5, -0.5]), history)   # pulled back: the contacts hold
    >>> law.branches(history).tolist(), f.round(4).tolist()
    ([0, 2, 2], [0.0, -1.4971, -1.4971])
    >>> wet = tabor.dem_law(1.0, stress_ratio=0.5, range_ratio=3.0)   # with a meniscus
    >>> round(wet.info["non_contact_end"], 4), round(wet.info["loop_energy"], 4)
    (-1.0857, 0.1297)
    """
    if (lam is None) == (scene is None):
        raise ValueError("give lam (a normalised law) or scene (a pair in SI units), one of them")
    text = None
    if scene is not None:
        if isinstance(scene, (str, os.PathLike)):
            with open(scene) as f:
                text = f.read()
        elif isinstance(scene, dict):
            text = _scene_text(scene)
        else:
            raise TypeError(f"scene = {scene!r}: give a dict or the path of a JSON file")
    return _tabor.dem_law(
        _optional(lam, "lam"),
        text,
        _optional(overlap_max, "overlap_max"),
        _optional(stress_ratio, "stress_ratio"),
        _optional(range_ratio, "range_ratio"),
    )


from .fleet import fit_fleet  # noqa: E402 (a fleet of force maps, serially or on Dask)
