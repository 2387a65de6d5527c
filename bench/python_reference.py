"""The public Python reference (package `adhesion`, module Adhesion.ReferenceSolutions.MaugisDugdale)
on the 300 reference states of data/points.csv, side by side with tabor.

The package has a forward map only (contact radius -> load), solving equation (1) for m with
brentq on a fixed bracket; the load -> state path here is a bracketed brentq on A around that
forward map, from the exact pull-off radius upwards. Errors are against the 50-digit reference.
Not part of CI: run bench/python_reference.sh.
"""
import csv
import subprocess
import sys
import time

import numpy as np
from scipy.optimize import brentq
import Adhesion.ReferenceSolutions.MaugisDugdale as md

rows = list(csv.DictReader(open(sys.argv[1])))
tabor = sys.argv[2]


def load_of_a(a, lam):
    n, _ = md._load_and_displacement(np.asarray([a]), lam)
    return float(np.asarray(n).ravel()[0])


def solve(lam, load, a_c):
    a_hi = max(a_c * 1.5, 1.0)
    for _ in range(60):
        if load_of_a(a_hi, lam) > load:
            break
        a_hi *= 2.0
    return brentq(lambda a: load_of_a(a, lam) - load, a_c, a_hi)


errs, fails = [], 0
t = time.perf_counter()
for r in rows:
    lam, load, a_ref, a_c = float(r["lambda"]), float(r["Pbar"]), float(r["A"]), float(r["A_pulloff_load"])
    try:
        a = solve(lam, load, a_c)
        errs.append(abs(a / a_ref - 1.0))
    except Exception:
        fails += 1
py_s = time.perf_counter() - t

inp = "lambda,load\n" + "".join(f"{r['lambda']},{r['Pbar']}\n" for r in rows)
t = time.perf_counter()
out = subprocess.run([tabor, "solve", "--input", "-", "--backend", "cpu"], input=inp.encode(), capture_output=True, check=True)
tb_s = time.perf_counter() - t
tb = list(csv.DictReader(out.stdout.decode().splitlines()))
tb_errs = [abs(float(x["A"]) / float(r["A"]) - 1.0) for x, r in zip(tb, rows)]

n = len(rows)
print(f"{'':34} {'states/s':>10} {'max err':>10} {'median':>10} {'failed':>7}")
print(f"{'adhesion (Python, brentq on m)':34} {n / py_s:>10.3g} {max(errs):>10.2e} {np.median(errs):>10.2e} {fails:>7}")
print(f"{'tabor solve --backend cpu':34} {n / tb_s:>10.3g} {max(tb_errs):>10.2e} {np.median(tb_errs):>10.2e} {0:>7}")
print("(tabor's figure includes process start and CSV I/O; its in-process rate is in `tabor bench`)")
