"""A fleet of AFM force maps fitted into one xarray Dataset, serially or on a Dask cluster.

Each map is fitted by :func:`tabor.fit_afmformats` (a file, read where it is fitted) or
:func:`tabor.fit_curves` (arrays with a pixel per point), one task per map, and its curves'
numbers are written into arrays of dims ``(map, y, x)`` as each map's fit arrives. The serial
path (``client=None``) imports no Dask; xarray is needed for the Dataset either way.
"""

import importlib.util
import json
import os
import pathlib
import uuid

import numpy as np

import tabor

__all__ = ["fit_fleet"]

#: The options passed on to fit_afmformats / fit_curves (``spring_n_m`` is an argument).
OPTIONS = ("poisson", "fit_segment", "z0_m", "tilt", "tolerance", "relative_humidity",
           "contact_angle_deg", "surface_tension_n_m", "molar_volume_m3_mol", "temperature_k",
           "tip")

#: The fitting modes tabor fits (afmformats' ``imaging mode``): the files of a folder kept.
MODALITIES = ("force-distance", "creep-compliance", "stress-relaxation")

#: The largest map side in pixels (as ``tabor map``'s grids): a larger map is its own error.
MAX_SIDE = 4096

#: The keys of an array map, and the optional one.
ARRAY_KEYS = ("height_m", "force_n", "segment", "x", "y")
ARRAY_OPTIONAL = ("spring_n_m",)

# name, units, description: the per-pixel numbers (float64, NaN where absent). Where the fit
# gives them, each quantity also has ``_stderr`` and its interval ends.
QUANTITIES = (
    ("e_star_pa", "Pa", "effective modulus E* of the Maugis-Dugdale (MD) fit"),
    ("youngs_modulus_pa", "Pa", "Young's modulus E* (1 - poisson^2), with the poisson option"),
    ("work_of_adhesion_j_m2", "J/m^2", "work of adhesion w of the MD fit"),
    ("lambda", "1", "Maugis parameter lambda of the MD fit"),
    ("tabor_parameter", "1", "Tabor parameter of the MD fit"),
    ("z0_m", "m", "Lennard-Jones range z0 of the MD fit"),
    ("contact_point_m", "m", "contact point of the MD fit"),
    ("force_offset_n", "N", "force offset of the fitted baseline"),
    ("rms_residual_n", "N", "rms residual of the MD fit"),
    ("noise_from_residual_n", "N", "noise level read from the residual"),
    ("pulloff_force_measured_n", "N", "pull-off force measured on the curve"),
    ("pulloff_force_model_n", "N", "pull-off force of the fitted MD model"),
    ("max_load_n", "N", "largest load on the fitted segment"),
    ("max_contact_radius_m", "m", "largest contact radius of the fitted MD model"),
    ("rms_hertz_n", "N", "rms residual of the Hertz fit"),
    ("rms_dmt_n", "N", "rms residual of the DMT fit"),
    ("rms_jkr_n", "N", "rms residual of the JKR fit"),
)
STDERR = ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "tabor_parameter", "z0_m",
          "contact_point_m")
INTERVALS = ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "contact_point_m", "z0_m")
# name, dtype, fill (padded pixels), description
STRINGS = (
    ("status", "no_curve", "how the pixel's fit ended: ok, invalid_input, no_contact, "
     "not_converged, or no_curve (no curve at that pixel)"),
    ("adequate_model", "", "the simplest model not significantly worse than MD: hertz, dmt, "
     "jkr, md; empty where none"),
    ("curve_message", "", "the curve's message: why its fit ended so"),
    ("warnings", "", "the curve's warnings, one a line"),
)
INTEGERS = (
    ("points_fitted", 0, "points fitted"),
    ("points_in_contact", 0, "fitted points in contact"),
    ("iterations", 0, "iterations of the MD fit"),
    ("enum", -1, "the curve's index in its file (afmformats' enum); -1 for an array map or "
     "no curve"),
)
BOOLS = (("lambda_determined", "whether lambda is determined (its 95% set one bounded "
          "interval, and no second basin of its profile below the 99% level)"),)


def _float_names():
    names = [q[0] for q in QUANTITIES]
    names += [f"{q}_stderr" for q in STDERR]
    names += [f"{q}_{end}{level}" for q in INTERVALS for level in ("68", "95")
              for end in ("lo", "hi")]
    return names


def _number(v):
    """A result's number as float (NaN for None, text or what is not a number)."""
    if v is None or isinstance(v, (bool, str, np.bool_)):
        return np.nan
    try:
        return float(v)
    except (TypeError, ValueError):
        return np.nan


def _row(r):
    """One curve's fit (a dict of fit_curves) as the Dataset's per-pixel values."""
    row = {}
    for name, _, _ in QUANTITIES:
        row[name] = _number(r.get(name))
    for m in r.get("models") or []:
        if isinstance(m, dict) and m.get("model") in ("hertz", "dmt", "jkr"):
            row[f"rms_{m['model']}_n"] = _number(m.get("rms_residual_n"))
    for q in STDERR:
        row[f"{q}_stderr"] = _number(r.get(f"{q}_stderr"))
    for q in INTERVALS:
        for level in ("68", "95"):
            iv = r.get(f"{q}_interval_{level}") or (None, None)
            row[f"{q}_lo{level}"] = _number(iv[0])
            row[f"{q}_hi{level}"] = _number(iv[1])
    row["status"] = str(r.get("status") or "invalid_input")
    row["adequate_model"] = str(r.get("adequate_model") or "")
    row["curve_message"] = str(r.get("message") or "")
    row["warnings"] = "\n".join(str(w) for w in r.get("warnings") or [])
    for name, fill, _ in INTEGERS:
        v = r.get(name)
        row[name] = fill if v is None else int(v)
    row["lambda_determined"] = bool(r.get("lambda_determined") or False)
    return row


def _columns(rows, iy, ix):
    """The rows as columns (one array per variable) with their pixels."""
    out = {"iy": np.asarray(iy, dtype=np.int64), "ix": np.asarray(ix, dtype=np.int64)}
    for name in _float_names():
        out[name] = np.array([r.get(name, np.nan) for r in rows], dtype=np.float64)
    for name, _, _ in STRINGS:
        out[name] = np.array([r[name] for r in rows] or [], dtype=object)
    for name, _, _ in INTEGERS:
        out[name] = np.array([r[name] for r in rows], dtype=np.int64)
    for name, _ in BOOLS:
        out[name] = np.array([r[name] for r in rows], dtype=bool)
    return out


def _caught():
    """What a map's failure may raise: any Exception, and afmformats' own errors (which derive
    from BaseException)."""
    kinds = [Exception]
    try:
        from afmformats import errors
        kinds += [errors.AFMFileFormatError, errors.MissingMetaDataError]
    except ImportError:
        pass
    return tuple(kinds)


def _fit_file(path, radius_m, spring_n_m, options):
    import afmformats

    path = pathlib.Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    data = afmformats.load_data(path)
    if not data:
        raise ValueError(f"{path}: afmformats reads no curve from it")
    grid = [(d.metadata.get("grid index x"), d.metadata.get("grid index y")) for d in data]
    if all(x is not None and y is not None for x, y in grid):
        ix, iy = [int(x) for x, _ in grid], [int(y) for _, y in grid]
    elif all(x is None and y is None for x, y in grid):  # no grid: the curves along x
        ix, iy = list(range(len(data))), [0] * len(data)
    else:
        raise ValueError(f"{path}: some curves have a grid position and others not")
    meta = data[0].metadata
    nx = max([int(meta.get("grid shape x") or 0)] + [x + 1 for x in ix])
    ny = max([int(meta.get("grid shape y") or 0)] + [y + 1 for y in iy])
    _size(nx, ny)
    fits = tabor.fit_afmformats(data, radius_m, spring_n_m, **options)
    if spring_n_m is not None:
        spring = float(spring_n_m)
    else:
        ks = {float(d.metadata.get("spring constant")) for d in data}
        spring = ks.pop() if len(ks) == 1 else np.nan
    return fits, iy, ix, ny, nx, spring


def _size(nx, ny):
    if nx > MAX_SIDE or ny > MAX_SIDE:
        raise ValueError(f"a map of {nx} x {ny} pixels: at most {MAX_SIDE} x {MAX_SIDE}")


def _fit_arrays(m, radius_m, spring_n_m, options):
    x = np.asarray(m["x"]).ravel()
    y = np.asarray(m["y"]).ravel()
    for name, v in (("x", x), ("y", y)):
        if v.dtype.kind not in "iuf" or not np.all(np.isfinite(v)) or np.any(v < 0) \
                or np.any(v != np.round(v)):
            raise ValueError(f"{name}: pixel indices must be integers >= 0")
    x, y = x.astype(np.int64), y.astype(np.int64)
    if len(x) != len(y):
        raise ValueError("x and y must have the same length")
    nx = int(x.max()) + 1 if len(x) else 0
    ny = int(y.max()) + 1 if len(y) else 0
    _size(nx, ny)
    k = m.get("spring_n_m") if spring_n_m is None else spring_n_m
    fits = tabor.fit_curves(m["height_m"], m["force_n"], m["segment"], y * nx + x,
                            radius_m=radius_m, spring_n_m=k, **options)
    pixel = [divmod(int(r["curve"]), nx) if nx else (0, 0) for r in fits]
    return fits, [p[0] for p in pixel], [p[1] for p in pixel], ny, nx, float(k)


def _fit_map(spec, radius_m, spring_n_m, options):
    """One map's fit (a task): its per-pixel columns, size, spring constant and the map's
    error message ("" where it was fitted). What goes wrong with the map is its message."""
    kind, what = spec
    try:
        if kind == "path":
            fits, iy, ix, ny, nx, spring = _fit_file(what, radius_m, spring_n_m, options)
        else:
            fits, iy, ix, ny, nx, spring = _fit_arrays(what, radius_m, spring_n_m, options)
        if len(set(zip(iy, ix))) != len(fits):
            raise ValueError("two curves at one pixel")
        columns = _columns([_row(r) for r in fits], iy, ix)
        return {"ny": ny, "nx": nx, "spring_n_m": spring, "message": "", "columns": columns}
    except _caught() as e:
        why = str(e) or type(e).__name__
        return {"ny": 0, "nx": 0, "spring_n_m": np.nan, "message": why, "columns": None}


class _Grid:
    """The Dataset's arrays, grown (padded) to the largest map as the maps' fits arrive."""

    def __init__(self, count):
        self.count, self.ny, self.nx = count, 0, 0
        self.arrays, self.fill = {}, {}
        for name in _float_names():
            self._add(name, np.float64, np.nan)
        for name, fill, _ in STRINGS:
            self._add(name, object, fill)
        for name, fill, _ in INTEGERS:
            self._add(name, np.int64, fill)
        for name, _ in BOOLS:
            self._add(name, bool, False)
        self.failed = []
        self.per_map = {"nx": np.zeros(count, np.int64), "ny": np.zeros(count, np.int64),
                        "spring_n_m": np.full(count, np.nan),
                        "message": np.full(count, "", dtype=object)}

    def _add(self, name, dtype, fill):
        self.arrays[name] = np.full((self.count, 0, 0), fill, dtype=dtype)
        self.fill[name] = fill

    def _grow(self, ny, nx):
        if ny <= self.ny and nx <= self.nx:
            return
        ny, nx = max(ny, self.ny), max(nx, self.nx)
        for name, a in self.arrays.items():
            b = np.full((self.count, ny, nx), self.fill[name], dtype=a.dtype)
            b[:, :self.ny, :self.nx] = a
            self.arrays[name] = b
        self.ny, self.nx = ny, nx

    def put(self, i, res):
        for k in ("nx", "ny", "spring_n_m", "message"):
            self.per_map[k][i] = res[k]
        if res["columns"] is None:
            self.failed.append(i)
            return
        self._grow(res["ny"], res["nx"])
        c = res["columns"]
        for name, a in self.arrays.items():
            a[i, c["iy"], c["ix"]] = c[name]

    def finish(self):
        if self.failed:  # at least one pixel to say so, where every map failed
            self._grow(1, 1)
        for i in self.failed:  # a map not read or not fitted: all its pixels invalid_input
            self.arrays["status"][i] = "invalid_input"


def _expand(maps):
    """(name, source, spec) of every map, in order; a folder gives its files, sorted."""
    if isinstance(maps, (str, os.PathLike)):
        maps = [maps]
    if isinstance(maps, dict):
        if set(ARRAY_KEYS) <= set(maps):
            raise ValueError("maps: pass a list of maps or a dict of name -> map, not one map "
                             "(put it in a list)")
        items = [(str(k), v) for k, v in maps.items()]
    else:
        try:
            items = [(None, v) for v in maps]
        except TypeError:
            raise TypeError(f"maps: give a sequence of paths or dicts of arrays, or a dict of "
                            f"them, not {type(maps).__name__}") from None
    out = []
    for i, (name, m) in enumerate(items):
        if isinstance(m, (str, os.PathLike)):
            p = pathlib.Path(m)
            files = _folder(p) if p.is_dir() else [p]
            for f in files:
                out.append((name if name is not None and not p.is_dir() else None,
                            str(f), ("path", str(f))))
        elif isinstance(m, dict):
            missing = [k for k in ARRAY_KEYS if k not in m]
            unknown = [k for k in m if k not in ARRAY_KEYS + ARRAY_OPTIONAL]
            where = f"map {name if name is not None else i}"
            if missing or unknown:
                raise ValueError(f"{where}: an array map has the keys {', '.join(ARRAY_KEYS)} "
                                 f"(and optionally spring_n_m); missing {missing}, unknown "
                                 f"{unknown}")
            out.append((name if name is not None else str(i), "", ("arrays", m)))
        else:
            raise TypeError(f"map {name if name is not None else i}: give a file path, a folder "
                            f"or a dict of arrays, not {type(m).__name__}")
    if not out:
        raise ValueError("maps: no map to fit (an empty list, or a folder without force "
                         "curve files afmformats reads)")
    # A file's name is its stem, or its whole file name where two stems are the same.
    stems = [pathlib.Path(src).stem if name is None else name for name, src, _ in out]
    names = [pathlib.Path(src).name if name is None and stems.count(stem) > 1 else stem
             for (name, src, _), stem in zip(out, stems)]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ValueError(f"maps: two maps named {twice[0]!r} (each map's name must be unique: "
                         "pass a dict of name -> map)")
    return [(n, src, spec) for n, (_, src, spec) in zip(names, out)]


def _folder(p):
    """The force-curve files directly in folder p that afmformats has a recipe for, sorted."""
    if importlib.util.find_spec("afmformats") is None:
        raise ImportError("reading a folder of force maps needs afmformats "
                          "(pip install afmformats)")
    from afmformats import errors
    from afmformats.formats import get_recipe
    files = []
    for f in sorted(p.iterdir()):
        if not f.is_file():
            continue
        try:
            recipe = get_recipe(f)
        except errors.FileFormatNotSupportedError:
            continue
        if any(m in MODALITIES for m in recipe.modalities):
            files.append(f)
    return files


def _check(radius_m, spring_n_m, options):
    unknown = sorted(k for k in options if k not in OPTIONS)
    if unknown:
        raise ValueError(f"unknown option {unknown[0]!r}: fit_fleet passes on "
                         f"{', '.join(OPTIONS)}")
    # Every option checked once, on no data (a stand-in spring where each map has its own),
    # as fit_afmformats does: what is wrong for every curve raises before any map is read.
    tabor.fit_curves([], [], [], radius_m=radius_m,
                     spring_n_m=1.0 if spring_n_m is None else spring_n_m, **options)


def _json(options):
    def plain(v):
        return v.item() if hasattr(v, "item") else str(v)
    return json.dumps(options, sort_keys=True, default=plain)


def fit_fleet(maps, radius_m, spring_n_m=None, *, client=None, store=None, **options):
    """Fits a fleet of AFM force maps, each map one task, serially or on a Dask cluster, into one
    xarray Dataset of dims ``(map, y, x)``.

    Parameters
    ----------
    maps : sequence or dict
        The maps (a dict: name -> map). A map is a force-curve file (str or os.PathLike), read
        where it is fitted, by ``afmformats.load_data`` then :func:`fit_afmformats` (each
        curve at its ``grid index x``/``y``, the grid as large as the file's ``grid shape``; the
        curves of a file without a grid along x); a folder, all the files in it that
        afmformats has a force-curve recipe for, sorted by name; or a dict of arrays, one value
        a point: ``height_m``, ``force_n``, ``segment`` and the pixel ``x``, ``y`` (integers >=
        0), optionally ``spring_n_m``, fitted by :func:`fit_curves` with a curve per pixel.
        A single path (a folder) may be passed alone.
    radius_m : float or None
        Tip radius in m, for every map (None where ``tip=`` is among the options).
    spring_n_m : float, optional
        Spring constant in N/m for every map, instead of each file's (or array map's) own.
    client : distributed.Client, optional
        Fit on this Dask cluster, one task per map (the default: serially, here, without
        importing Dask). A worker holds one map's curves at a time per thread; the maps' fits
        are written into the Dataset's arrays as they arrive.
    store : str or os.PathLike, optional
        A Zarr store (a folder that must not exist yet) to write the Dataset to, map by map:
        each map's fit goes to a temporary file beside it as it arrives, and the maps are then
        written in order, padded to the largest, so that this process holds one map's numbers
        at a time (without ``store`` the whole Dataset is held: about 0.4 kB a pixel). The
        store appears only when complete (written under a temporary name, then renamed). The
        Dataset returned is then the store's, opened lazily.
    **options
        Passed on to :func:`fit_afmformats` / :func:`fit_curves`: ``poisson``,
        ``fit_segment``, ``z0_m``, ``tilt``, ``tolerance``, ``relative_humidity``,
        ``contact_angle_deg``, ``surface_tension_n_m``, ``molar_volume_m3_mol``,
        ``temperature_k``, ``tip``.

    Returns
    -------
    xarray.Dataset
        Coordinates ``map`` (each file's stem, or its file name where two stems are the same,
        or the dict key, or an array map's position), ``y``, ``x`` (pixels; maps smaller than
        the largest are padded, their pixels ``no_curve``). Per pixel: float64 numbers (NaN
        where absent) ``e_star_pa``, ``youngs_modulus_pa``, ``work_of_adhesion_j_m2``,
        ``lambda``, ``tabor_parameter``, ``z0_m``, ``contact_point_m``, ``force_offset_n``,
        ``rms_residual_n``, ``noise_from_residual_n``, ``pulloff_force_measured_n``,
        ``pulloff_force_model_n``, ``max_load_n``, ``max_contact_radius_m``, ``rms_hertz_n``,
        ``rms_dmt_n``, ``rms_jkr_n``; ``<q>_stderr`` for E*, w, lambda, the Tabor parameter,
        z0 and the contact point; ``<q>_lo68``, ``<q>_hi68``, ``<q>_lo95``, ``<q>_hi95`` (the
        profile-likelihood intervals' ends, NaN where open) for E*, w, lambda, the contact
        point and z0; strings ``status`` (``ok``, ``invalid_input``, ``no_contact``,
        ``not_converged``, ``no_curve``), ``adequate_model`` ("" where none),
        ``curve_message``, ``warnings`` (one a line); bool ``lambda_determined``; int64
        ``points_fitted``, ``points_in_contact``, ``iterations``, ``enum``. Per map:
        ``source`` (the path, "" for arrays), ``spring_n_m`` (NaN where a file's curves
        differ), ``nx``, ``ny`` (the map's own size) and ``message`` ("", or why the map could
        not be read or fitted: then all its pixels are ``invalid_input``). Each variable's
        ``attrs`` hold ``units`` and ``description``; the Dataset's ``tabor_version``,
        ``radius_m`` and ``options`` (JSON text, with ``spring_n_m``). Strings are Python
        strings (object dtype), which Zarr and NetCDF store as variable-length strings.

    Raises
    ------
    ValueError
        before any map is fitted: an option wrong for every curve (``radius_m`` <= 0, ...) or
        unknown, named; an array map without a key, or without a spring constant where
        ``spring_n_m`` is not given; two maps of one name; no map. What is wrong with one map
        (a file missing or unreadable, arrays of different lengths, two curves at one pixel, a
        side over 4096 pixels) is that map's ``message``.
    TypeError
        a map that is neither a path nor a dict; values that are not numbers.
    ImportError
        xarray missing; afmformats missing where a map is a file or a folder; zarr missing
        where ``store`` is given.
    FileExistsError
        ``store`` exists already (it is never overwritten), checked before any map is fitted.
    FileNotFoundError
        ``store``'s folder does not exist (before any map is fitted).

    Examples
    --------
    Two 2 x 1 maps of noise-free curves (E* = 2 GPa, w = 0.04 J/m^2, lambda = 0.3) and a map
    whose file is missing, fitted serially:

    >>> import numpy as np, tabor
    >>> E, w, lam, R, k = 2e9, 0.04, 0.3, 20e-9, 40.0
    >>> unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)
    >>> c = tabor.cycle(lam, drive="spring", stiffness=k * unit / (np.pi * w * R))
    >>> h, f = -c["control"][::4] * unit, c["load"][::4] * np.pi * w * R
    >>> s = np.where(c["phase"][::4] == "approach", 0, 1)
    >>> n = len(h)
    >>> m = {"height_m": np.tile(h, 2), "force_n": np.tile(f, 2), "segment": np.tile(s, 2),
    ...      "x": np.repeat([0, 1], n), "y": np.zeros(2 * n, dtype=int)}
    >>> ds = tabor.fit_fleet({"a": m, "b": m, "c": "missing.jpk-force"}, radius_m=R,
    ...                      spring_n_m=k)
    >>> dict(ds.sizes)
    {'map': 3, 'y': 1, 'x': 2}
    >>> ds["status"].values.tolist()
    [[['ok', 'ok']], [['ok', 'ok']], [['invalid_input', 'invalid_input']]]
    >>> (ds["e_star_pa"].sel(map="a") / 1e9).round(4).values.tolist()
    [[2.0, 2.0]]
    >>> print(ds["message"].sel(map="c").item())
    no such file: missing.jpk-force
    >>> ds["e_star_pa"].attrs["units"]
    'Pa'
    """
    if importlib.util.find_spec("xarray") is None:
        raise ImportError("fit_fleet returns an xarray Dataset: pip install xarray "
                          "(or tabor[dask])")
    _check(radius_m, spring_n_m, options)
    fleet = _expand(maps)
    if spring_n_m is None:
        for name, _, (kind, m) in fleet:
            if kind == "arrays" and m.get("spring_n_m") is None:
                raise ValueError(f"map {name!r}: no spring constant: pass spring_n_m= (N/m) "
                                 "or give the map a spring_n_m")
    if any(kind == "path" for _, _, (kind, _) in fleet) \
            and importlib.util.find_spec("afmformats") is None:
        raise ImportError("fitting force-map files needs afmformats (pip install afmformats)")
    specs = [spec for _, _, spec in fleet]
    if store is not None:
        return _to_store(store, fleet, specs, client, radius_m, spring_n_m, options)
    grid = _Grid(len(fleet))
    _fit_all(specs, client, radius_m, spring_n_m, options, grid.put)
    grid.finish()
    return _dataset(fleet, grid, radius_m, spring_n_m, options)


def _fit_all(specs, client, radius_m, spring_n_m, options, put):
    """Every map's fit, serially or on the client, each handed to put(i, result) as it
    arrives."""
    if client is None:
        for i, spec in enumerate(specs):
            put(i, _fit_map(spec, radius_m, spring_n_m, options))
    else:
        _on_dask(client, specs, radius_m, spring_n_m, options, put)


def _to_store(store, fleet, specs, client, radius_m, spring_n_m, options):
    """The fleet's Dataset written to the Zarr store map by map (see fit_fleet's ``store``)."""
    import pickle
    import tempfile

    import xarray as xr

    if importlib.util.find_spec("zarr") is None:
        raise ImportError("store= writes Zarr: pip install zarr (or tabor[dask])")
    store = pathlib.Path(store)
    if store.exists():
        raise FileExistsError(f"store: {store} exists already; give a new path (it is never "
                              "overwritten)")
    with tempfile.TemporaryDirectory(dir=store.parent, prefix=f".{store.name}.") as tmp:
        tmp = pathlib.Path(tmp)
        size = {"ny": 0, "nx": 0, "failed": False}

        def put(i, res):
            size["ny"], size["nx"] = max(size["ny"], res["ny"]), max(size["nx"], res["nx"])
            size["failed"] |= res["columns"] is None
            with open(tmp / f"{i}.pickle", "wb") as f:
                pickle.dump(res, f, protocol=pickle.HIGHEST_PROTOCOL)

        _fit_all(specs, client, radius_m, spring_n_m, options, put)
        ny, nx = size["ny"], size["nx"]
        if size["failed"]:  # at least one pixel to say so, as the Dataset in memory has
            ny, nx = max(ny, 1), max(nx, 1)
        partial = tmp / "store.zarr"
        for i in range(len(fleet)):
            with open(tmp / f"{i}.pickle", "rb") as f:
                res = pickle.load(f)
            grid = _Grid(1)
            grid.put(0, res)
            grid._grow(ny, nx)
            grid.finish()
            one = _dataset(fleet[i:i + 1], grid, radius_m, spring_n_m, options)
            if i == 0:
                # (Zarr 3 has no consolidated metadata in its specification.)
                one.to_zarr(partial, mode="w-", consolidated=False)
            else:
                one.to_zarr(partial, append_dim="map", consolidated=False)
            (tmp / f"{i}.pickle").unlink()
        if store.exists():  # made while the maps were fitted: never overwritten
            raise FileExistsError(f"store: {store} appeared while the maps were fitted; the "
                                  "results are not written (give a new path)")
        os.rename(partial, store)
    return xr.open_dataset(store, engine="zarr", chunks=None, consolidated=False)


def _on_dask(client, specs, radius_m, spring_n_m, options, put):
    from distributed import as_completed

    run = uuid.uuid4().hex
    keys = [f"tabor-fit_fleet-{run}-{i}" for i in range(len(specs))]
    index = {k: i for i, k in enumerate(keys)}
    futures = client.map(_fit_map, specs, radius_m=radius_m, spring_n_m=spring_n_m,
                         options=options, key=keys)
    done = as_completed(futures, with_results=True, raise_errors=False)
    del futures  # each future dropped once its result is written: the worker frees it
    for future, result in done:
        i = index[future.key]
        if future.status != "finished":  # a worker lost (memory, a crash) or the task cancelled
            exc = result[1] if isinstance(result, tuple) and len(result) == 3 else result
            result = {"ny": 0, "nx": 0, "spring_n_m": np.nan, "columns": None,
                      "message": f"the task failed: {type(exc).__name__}: {exc}"}
        put(i, result)
        del future, result


def _reference_attrs():
    attrs = {}
    for name, units, text in QUANTITIES:
        attrs[name] = {"units": units, "description": text}
    for q in STDERR:
        attrs[f"{q}_stderr"] = {"units": attrs[q]["units"],
                                "description": f"standard error of {q}"}
    for q in INTERVALS:
        for level, pct in (("68", "68%"), ("95", "95%")):
            for end, word in (("lo", "low"), ("hi", "high")):
                attrs[f"{q}_{end}{level}"] = {
                    "units": attrs[q]["units"],
                    "description": f"{word} end of the {pct} profile-likelihood interval of "
                                   f"{q}; NaN where the data leave it open"}
    for name, _, text in STRINGS:
        attrs[name] = {"units": "", "description": text}
    for name, _, text in INTEGERS:
        attrs[name] = {"units": "", "description": text}
    for name, text in BOOLS:
        attrs[name] = {"units": "", "description": text}
    return attrs


def _dataset(fleet, grid, radius_m, spring_n_m, options):
    import xarray as xr

    attrs = _reference_attrs()
    dims = ("map", "y", "x")
    data = {name: (dims, a, attrs[name]) for name, a in grid.arrays.items()}
    per_map = {
        "source": (np.array([src for _, src, _ in fleet], dtype=object),
                   "", "the map's file, \"\" for arrays"),
        "spring_n_m": (grid.per_map["spring_n_m"], "N/m",
                       "the map's spring constant; NaN where its curves' differ or it was "
                       "not read"),
        "nx": (grid.per_map["nx"], "", "the map's own width in pixels (0 where not read)"),
        "ny": (grid.per_map["ny"], "", "the map's own height in pixels (0 where not read)"),
        "message": (grid.per_map["message"], "",
                    "\"\", or why the map could not be read or fitted"),
    }
    for name, (a, units, text) in per_map.items():
        data[name] = (("map",), a, {"units": units, "description": text})
    coords = {
        "map": ("map", np.array([n for n, _, _ in fleet], dtype=object),
                {"description": "the map's name: its file's stem or its key"}),
        "y": ("y", np.arange(grid.ny, dtype=np.int64), {"units": "pixel"}),
        "x": ("x", np.arange(grid.nx, dtype=np.int64), {"units": "pixel"}),
    }
    return xr.Dataset(data, coords=coords, attrs={
        "title": "tabor fit_fleet: Maugis-Dugdale fits of AFM force maps",
        "tabor_version": tabor.__version__,
        # NaN for a tip that is not a sphere (its description is in the options).
        "radius_m": float("nan") if radius_m is None else float(radius_m),
        "options": _json(dict(options, spring_n_m=spring_n_m)),
    })
