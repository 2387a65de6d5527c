"""tabor's Hertz fit of the approach against nanite's `hertz_para` fit of the same curves: every
JPK force curve of afmformats 0.18.7's sample data (docs/benchmarks.md, "tabor and nanite on
the approach"; python/tests/test_nanite_agreement.py asserts the same comparison).

    python bench/nanite_agreement.py [DATA_DIR] [--synthetic] [--cone=HALF_ANGLE_DEG]

DATA_DIR is the tests/data folder of the afmformats 0.18.7 source distribution; without it the
distribution is fetched with pip. Needs tabor, afmformats and nanite (with lmfit).

Both tools fit the same model: a paraboloid of R = 2.5 um on an incompressible sample
(nu = 0.5, which both accept: nanite bounds nu to [0, 0.5]), F = 4/3 E/(1-nu^2) sqrt(R)
delta^1.5, with E, the contact point and a force offset free. tabor:
`fit_afmformats(curve, radius_m=2.5e-6, poisson=0.5, fit_segment="approach")`, its `models`
entry `hertz` (E = E* (1 - nu^2)). nanite is made to fit what tabor fits:

- the same points: tabor's approach (its segment plan, which leaves a pause or a dwell out),
  not nanite's `correct_split_approach_retract`, which splits at the lowest tip position (the
  creep of a creep-compliance curve, the pause before a stress-relaxation approach and a few
  points of the retract's start would join the approach); the whole approach, baseline
  included, in both;
- unweighted residuals (`weight_cp=0`): nanite's default (1e-6) scales the residuals within
  1 um of the contact point down, all of the contact on a 50 nm indentation;
- the same baseline model: a constant force offset fitted with the rest (tabor removes the
  mean of the approach's far 30% first and fits an offset on top, nanite subtracts its own
  estimate and fits `baseline`: the same least-squares minimum);
- the same data: `height (measured)`, afmformats' force and the file's spring constant.

What stays different is where the residual is taken. tabor's is the force at the measured base
height, the tip following through the spring (indentation z_c - height - F/k); nanite's is the
force at the tip position computed from the measured force (height + F/k). A force misfit d at
a base height is a misfit d (1 + S/k) at the tip position, S the secant contact stiffness
(about 2 E/(1-nu^2) sqrt(R delta)): nanite weighs the deep points up to (1 + S_max/k)^2 times
more. On a curve the model describes, the two minima coincide (`--synthetic`: each curve's own
fitted Hertz curve plus white noise of its baseline's rms); on a curve it does not, they differ
unless S_max/k is small. A curve with S_max/k < STIFF is listed as comparable and must agree
within TOLERANCE; on every curve, nanite's model refitted with its residuals at the base
height (`nanite_base_axis`) checks that the axis is the whole difference (it gives tabor's E).

`--cone=DEG` makes the same comparison with a cone of that half-angle (axis to flank) in both
tools: tabor's `tip="cone:DEG"` (Sneddon's punch, its `hertz` entry) against nanite's
`hertz_cone`, F = (2/pi) E/(1-nu^2) tan(alpha) delta^2 (the curves were measured with a sphere:
this compares the tools, not the tip).

Exit status 1 if a comparable curve's E differs by more than TOLERANCE.
"""
import sys
import time
import warnings

import numpy as np

from jpk_samples import curves, data_dir

RADIUS_M = 2.5e-6
POISSON = 0.5


class Paraboloid:
    """The paraboloid of R = 2.5 um: tabor's sphere, nanite's `hertz_para`."""
    label = "paraboloid, R = 2.5 um"
    nanite_key = "hertz_para"
    tabor = {"radius_m": RADIUS_M}

    def set_nanite(self, p):
        p["R"].set(value=RADIUS_M)

    def force(self, e_star, delta):
        """F = 4/3 E* sqrt(R) delta^1.5."""
        return 4 / 3 * e_star * np.sqrt(RADIUS_M) * delta ** 1.5

    def stiffness(self, e_star, delta):
        """dF/ddelta = 2 E* sqrt(R delta)."""
        return 2 * e_star * np.sqrt(RADIUS_M * delta)


class Cone:
    """A cone of half-angle `deg` (axis to flank): tabor's `tip="cone:DEG"` (Sneddon's punch
    as its `hertz`), nanite's `hertz_cone`, both F = (2/pi) E* tan(alpha) delta^2."""
    nanite_key = "hertz_cone"

    def __init__(self, deg):
        self.deg = deg
        self.label = f"cone, half-angle {deg} degrees"
        self.tabor = {"tip": f"cone:{deg}"}

    def set_nanite(self, p):
        p["alpha"].set(value=self.deg)

    def force(self, e_star, delta):
        return 2 / np.pi * e_star * np.tan(np.radians(self.deg)) * delta ** 2

    def stiffness(self, e_star, delta):
        return 4 / np.pi * e_star * np.tan(np.radians(self.deg)) * delta


PARABOLOID = Paraboloid()
TOLERANCE = 0.02   # |E_tabor / E_nanite - 1| on a comparable curve
STIFF = 0.3        # S_max/k below which the two residual axes weigh the points alike


def approach_points(fd):
    """The points tabor fits as the approach: its own segment plan of the curve (a pause or a
    dwell left out), as `fit_afmformats` makes it."""
    import tabor
    h = np.asarray(fd["height (measured)"], dtype=float)
    code, _ = tabor._tabor.plan_segments(h, np.asarray(fd["segment"], dtype=np.int64))
    return np.asarray(code) == 0


def baseline_noise(fd, approach):
    """The rms of the approach's far 30% (by height) about its mean: the force noise."""
    h = np.asarray(fd["height (measured)"], dtype=float)[approach]
    f = np.asarray(fd["force"], dtype=float)[approach]
    return float(np.std(f[np.argsort(-h)[: int(np.ceil(0.3 * len(h)))]]))


def tabor_hertz(fd, shape=PARABOLOID):
    """tabor's Hertz fit of the approach: E (Pa), the contact point (a base height, m), the
    points fitted, the rms residual (N)."""
    import tabor
    r = tabor.fit_afmformats(fd, poisson=POISSON, fit_segment="approach", **shape.tabor)[0]
    hz = [m for m in r.get("models") or [] if m.get("model") == "hertz"]
    if not hz or hz[0].get("status") != "ok":
        return {"status": r["status"], "message": r.get("message")}
    return {"status": "ok", "E": hz[0]["e_star_pa"] * (1 - POISSON**2),
            "cp": hz[0]["contact_point_m"], "points": r["points_fitted"],
            "rms": hz[0]["rms_residual_n"], "curve_status": r["status"],
            "rms_models": {m["model"]: m["rms_residual_n"] for m in r["models"]
                           if m["status"] == "ok"},
            "stops": {m["model"]: m["stop"] for m in r["models"]}}


def _indentation(fd, columns=None):
    import nanite
    if columns is None:
        data, meta = {c: np.array(fd[c]) for c in fd.columns}, dict(fd.metadata)
    else:  # arrays other than the file's: of its metadata only the spring constant
        data = columns
        meta = {"spring constant": fd.metadata["spring constant"], "path": "synthetic",
                "enum": 0}
    return nanite.Indentation(data=data, metadata=meta, diskcache=False)


def nanite_hertz(fd, approach=None, columns=None, shape=PARABOLOID):
    """nanite's fit of the approach with the shape's model (hertz_para, hertz_cone).

    approach None: nanite's usual workflow (its own split of approach and retract, its default
    contact-point weighting); a mask: those points, unweighted (what tabor fits). Returns E,
    the contact point as a base height (tabor's convention), the points, the fitted arrays
    (tip position, force) and parameters, the spring constant; None where the fit failed.
    """
    idnt = _indentation(fd, columns)
    k = float(idnt.metadata["spring constant"])
    h = np.asarray(idnt["height (measured)"], dtype=float)
    f_raw = np.asarray(idnt["force"], dtype=float)
    steps = ["compute_tip_position", "correct_force_offset", "correct_tip_offset"]
    if approach is None:
        steps.append("correct_split_approach_retract")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        idnt.apply_preprocessing(steps)
        # The shifts the preprocessing made, to put nanite's contact point back on the base
        # height: the tip touches where height = tip - (force there) / k.
        tip_shift = (h[0] + f_raw[0] / k) - idnt["tip position"][0]
        force_shift = f_raw[0] - idnt["force"][0]
        fp = {"model_key": shape.nanite_key, "segment": 0, "range_type": "absolute",
              "range_x": [0, 0], "x_axis": "tip position", "y_axis": "force"}
        if approach is not None:
            idnt["segment"] = np.where(approach, 0, 1).astype(np.uint8)
            fp["weight_cp"] = 0
        idnt.fit_properties["model_key"] = shape.nanite_key
        p = idnt.get_initial_fit_parameters()
        shape.set_nanite(p)
        p["nu"].set(value=POISSON)
        idnt.fit_model(params_initial=p, **fp)
    res = idnt.fit_properties
    if not res.get("success"):
        return None
    pf = res["params_fitted"]
    fit = np.asarray(idnt["fit range"], dtype=bool)
    offset = force_shift + pf["baseline"].value
    return {"E": pf["E"].value, "cp": pf["contact_point"].value + tip_shift - offset / k,
            "points": int(fit.sum()), "x": np.asarray(idnt["tip position"])[fit],
            "y": np.asarray(idnt["force"])[fit], "params": pf, "k": k, "shape": shape}


def stiffness_ratio(n):
    """S_max/k of a nanite fit: the contact stiffness (the paraboloid's 2 E/(1-nu^2)
    sqrt(R delta)) at its deepest point over the spring constant."""
    depth = max(n["params"]["contact_point"].value - n["x"].min(), 0.0)
    return n["shape"].stiffness(n["E"] / (1 - POISSON**2), depth) / n["k"]


def nanite_base_axis(n):
    """nanite's fit redone with the residual taken at the base height, as tabor takes it:
    nanite's own model function g and parameters, lmfit, the same points. Each point's model
    force F solves F = g(base + F/k), the tip following through the spring (bisection: g falls
    as the tip rises). E (Pa)."""
    import lmfit
    import nanite.model
    g = nanite.model.models_available[n["shape"].nanite_key].model
    x, y, k = n["x"], n["y"], n["k"]
    base = x - y / k  # the measured base height, shifted as nanite shifted the tip

    def model_force(q):
        b = q["baseline"].value
        lo = np.zeros_like(base)
        hi = np.maximum(q["contact_point"].value - base, 0.0) * k  # all push in the spring
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            up = g(q, base + (mid + b) / k) - b > mid
            lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
        return 0.5 * (lo + hi) + b

    fit = lmfit.minimize(lambda q: y - model_force(q), n["params"].copy(), method="leastsq")
    return fit.params["E"].value


def hertz_under_spring(height, e_star, zc, k, shape=PARABOLOID):
    """The Hertz force at each base height under a spring k: F = F_shape(zc - height - F/k)
    (bisection)."""
    push = np.asarray(zc - height, dtype=float)
    lo, hi = np.zeros_like(push), np.maximum(push, 0.0) * k
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        up = shape.force(e_star, np.maximum(push - mid / k, 0.0)) > mid
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    return 0.5 * (lo + hi)


def synthetic_ratio(fd, t, approach, noise, seed=0, shape=PARABOLOID):
    """E_tabor / E_nanite on the curve's own fitted Hertz curve (tabor's fit, on its approach
    heights) plus white noise of its baseline's rms: both tools on a curve the model describes,
    with this curve's points, spring and stiffness."""
    import tabor
    h = np.asarray(fd["height (measured)"], dtype=float)[approach]
    k = float(fd.metadata["spring constant"])
    force = (hertz_under_spring(h, t["E"] / (1 - POISSON**2), t["cp"], k, shape)
             + np.random.default_rng(seed).normal(0.0, noise, len(h)))
    seg = np.zeros(len(h), dtype=np.uint8)
    r = tabor.fit_curve(h, force, seg.astype(int), spring_n_m=k, poisson=POISSON,
                        fit_segment="approach", **shape.tabor)
    hz = [m for m in r["models"] if m["model"] == "hertz"][0]
    n = nanite_hertz(fd, approach=seg == 0,
                     columns={"height (measured)": h, "force": force, "segment": seg},
                     shape=shape)
    return hz["e_star_pa"] * (1 - POISSON**2) / n["E"]


def compare(name, fd, synthetic=False, default=True, shape=PARABOLOID):
    """One curve's row: both fits, their ratio, and what makes a difference.

    Keys: file, enum, tabor (its fit), points (tabor's, nanite's), e_tabor, e_nanite, ratio,
    cp_tabor, cp_nanite (base heights, m), misfit (tabor's Hertz rms over the baseline's
    noise), s_over_k, comparable, e_base_axis (nanite_base_axis), ratio_default (against
    nanite's usual workflow), synthetic_ratio, verdict, and the seconds each part took."""
    row = {"file": name, "enum": int(fd.metadata.get("enum", 0))}
    approach = approach_points(fd)
    t0 = time.perf_counter()
    t = tabor_hertz(fd, shape)
    row["tabor_s"] = time.perf_counter() - t0
    row["tabor"] = t
    if t["status"] != "ok":
        row["verdict"] = f"tabor's Hertz fit: {t['status']}"
        return row
    t0 = time.perf_counter()
    n = nanite_hertz(fd, approach, shape=shape)
    row["nanite_s"] = time.perf_counter() - t0
    if n is None:
        row["verdict"] = "nanite's fit failed"
        return row
    noise = baseline_noise(fd, approach)
    row.update(points=(t["points"], n["points"]), e_tabor=t["E"], e_nanite=n["E"],
               ratio=t["E"] / n["E"], cp_tabor=t["cp"], cp_nanite=n["cp"],
               misfit=t["rms"] / noise, s_over_k=stiffness_ratio(n))
    row["comparable"] = row["s_over_k"] < STIFF
    t0 = time.perf_counter()
    row["e_base_axis"] = nanite_base_axis(n)
    row["base_axis_s"] = time.perf_counter() - t0
    if default:
        d = nanite_hertz(fd, shape=shape)
        row["ratio_default"] = t["E"] / d["E"] if d else float("nan")
    if synthetic:
        row["synthetic_ratio"] = synthetic_ratio(fd, t, approach, noise, shape=shape)
    if row["comparable"]:
        row["verdict"] = "agree" if abs(row["ratio"] - 1) <= TOLERANCE else "DIFFER"
    else:
        row["verdict"] = "axis"
    return row


def table(rows):
    synthetic = any("synthetic_ratio" in r for r in rows)
    lines = [f"{'curve':<46} {'points':>11} {'E_tabor':>9} {'E_nanite':>9} {'ratio':>6} "
             f"{'cp_tabor':>9} {'cp_nanite':>9} {'dcp':>5} {'misfit':>6} {'S/k':>5} "
             f"{'base':>6} {'default':>7}" + (f" {'synth':>6}" if synthetic else "")
             + " verdict"]
    for r in rows:
        label = f"{r['file'][8:]} [{r['enum']}]"[-46:]
        if "ratio" not in r:
            lines.append(f"{label:<46} {r['verdict']}")
            continue
        lines.append(
            f"{label:<46} {r['points'][0]:>5}/{r['points'][1]:<5} {r['e_tabor']:9.4g} "
            f"{r['e_nanite']:9.4g} {r['ratio']:6.4f} {r['cp_tabor'] * 1e6:9.4f} "
            f"{r['cp_nanite'] * 1e6:9.4f} {(r['cp_tabor'] - r['cp_nanite']) * 1e9:5.1f} "
            f"{r['misfit']:6.2f} {r['s_over_k']:5.2f} {r['e_tabor'] / r['e_base_axis']:6.4f} "
            f"{r.get('ratio_default', float('nan')):7.3g}"
            + (f" {r['synthetic_ratio']:6.4f}" if synthetic else "") + f" {r['verdict']}")
    return "\n".join(lines)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    synthetic = "--synthetic" in sys.argv
    cone = [a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--cone=")]
    shape = Cone(float(cone[0])) if cone else PARABOLOID
    todo = curves(data_dir(args[0] if args else None))
    t0 = time.perf_counter()
    rows = [compare(name, fd, synthetic, shape=shape) for name, fd in todo]
    wall = time.perf_counter() - t0
    print(table(rows))
    print(f"E in Pa (E = E* (1 - nu^2), nu = 0.5, {shape.label}); points: tabor's/nanite's; "
          "ratio: E_tabor/E_nanite on the same points; cp: contact points as base heights (um), "
          "dcp their difference (nm); misfit: tabor's Hertz rms residual over the baseline's "
          "noise; S/k: nanite's deepest contact stiffness over the spring constant; base: "
          "E_tabor over nanite's E with its residuals at the base height; default: "
          "E_tabor/E_nanite with nanite's own split and contact-point weighting"
          + ("; synth: E_tabor/E_nanite on the curve's fitted Hertz curve plus noise"
             if synthetic else ""))
    fitted = [r for r in rows if "ratio" in r]
    comparable = [r for r in fitted if r["comparable"]]
    other = [r for r in fitted if not r["comparable"]]
    bad = [r for r in comparable if abs(r["ratio"] - 1) > TOLERANCE]
    print(f"{len(rows)} curves, {len(fitted)} fitted by both, {len(comparable)} comparable "
          f"(S_max/k < {STIFF}); seconds: tabor {sum(r['tabor_s'] for r in rows):.1f}, nanite "
          f"{sum(r.get('nanite_s', 0.0) for r in rows):.1f}, nanite at the base height "
          f"{sum(r.get('base_axis_s', 0.0) for r in rows):.1f}; all {wall:.1f}")
    for what, group in (("on a comparable curve", comparable), ("where the axis matters", other)):
        if group:
            w = max(group, key=lambda r: abs(r["ratio"] - 1))
            print(f"largest difference {what}: {100 * (w['ratio'] - 1):+.2f}% "
                  f"({w['file']} [{w['enum']}], S_max/k {w['s_over_k']:.2f})")
    if fitted:
        w = max(fitted, key=lambda r: abs(r["e_tabor"] / r["e_base_axis"] - 1))
        print(f"nanite with its residuals at the base height against tabor, largest difference: "
              f"{100 * (w['e_tabor'] / w['e_base_axis'] - 1):+.3f}% ({w['file']} [{w['enum']}])")
    if bad:
        print(f"{len(bad)} comparable curve(s) outside {TOLERANCE:.1%}")
        sys.exit(1)


if __name__ == "__main__":
    main()
