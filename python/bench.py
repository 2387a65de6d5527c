"""Speed of tabor.solve against the `adhesion` package's Maugis-Dugdale solver (a benchmark, not
a test): a 1000 x 1000 grid of (lambda, load) through tabor, a subsample of it through adhesion
(a scalar brentq per state, as bench/python_reference.py), in one run; prints the rates and
their ratio. Needs `pip install adhesion scipy`.

    python python/bench.py
"""
import time

import numpy as np
from scipy.optimize import brentq

import tabor

try:
    import Adhesion.ReferenceSolutions.MaugisDugdale as md
except ImportError:
    raise SystemExit("needs the adhesion package: pip install adhesion")

lam = np.logspace(-3, 3, 1000)[None, :]
load = np.logspace(-3, 3, 1000)[:, None]

t = time.perf_counter()
r = tabor.solve(lam, load=load)
t_tabor = time.perf_counter() - t
n = r["A"].size
assert (r["status"] == "ok").all()


def load_of_a(a, lm):
    p, _ = md._load_and_displacement(np.asarray([a]), lm)
    return float(np.asarray(p).ravel()[0])


def solve_adhesion(lm, p, a_c):
    a_hi = max(a_c * 1.5, 1.0)
    while load_of_a(a_hi, lm) <= p:
        a_hi *= 2.0
    return brentq(lambda a: load_of_a(a, lm) - p, a_c, a_hi)


rng = np.random.default_rng(1)
idx = rng.choice(n, 300, replace=False)
lam_b = np.broadcast_to(lam, r["A"].shape).ravel()[idx]
load_b = np.broadcast_to(load, r["A"].shape).ravel()[idx]
a_c = tabor.pulloff(lam_b)["load_control_A"]
t = time.perf_counter()
a_adh = np.array([solve_adhesion(l, p, c) for l, p, c in zip(lam_b, load_b, a_c)])
t_adh = time.perf_counter() - t
err = np.max(np.abs(a_adh / r["A"].ravel()[idx] - 1))

rate_tabor, rate_adh = n / t_tabor, len(idx) / t_adh
print(f"tabor.solve, {n} states (1000 x 1000 grid): {t_tabor:.3f} s, {rate_tabor:.3g} states/s")
print(f"adhesion (brentq per state), {len(idx)} of them: {t_adh:.3f} s, {rate_adh:.3g} states/s")
print(f"ratio: tabor is {rate_tabor / rate_adh:.0f} times faster; "
      f"largest difference of A on the subsample {err:.1e}")
