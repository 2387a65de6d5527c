"""Fits every JPK force curve of afmformats 0.18.7's sample data with tabor, one core, and
prints the time of each and the rate: the measured-curve benchmark of docs/benchmarks.md.

    python bench/jpk_curves.py [DATA_DIR] [--json OUT]

DATA_DIR is the tests/data folder of the afmformats 0.18.7 source distribution; without it the
distribution is fetched with pip. Needs tabor and afmformats. The fits run one after another in
this process with one thread (RAYON_NUM_THREADS=1 is set before tabor is imported).
"""
import os

os.environ["RAYON_NUM_THREADS"] = "1"

import json
import pathlib
import sys
import time

import tabor
from jpk_samples import curves, data_dir

RADIUS_M = 2.5e-6


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    out_json = sys.argv[sys.argv.index("--json") + 1] if "--json" in sys.argv else None
    if out_json in args:
        args.remove(out_json)
    todo = curves(data_dir(args[0] if args else None))
    rows, total = [], 0.0
    print(f"{'s':>7} {'points':>6}  file [curve]: status, adequate model, lambda determined")
    for name, d in todo:
        t = time.perf_counter()
        r = tabor.fit_afmformats(d, radius_m=RADIUS_M)[0]
        dt = time.perf_counter() - t
        total += dt
        n = len(d["force"])
        print(f"{dt:7.3f} {n:6d}  {name} [{d.metadata.get('enum', 0)}]: {r['status']}, "
              f"{r.get('adequate_model')}, {r.get('lambda_determined')}")
        rows.append({"file": name, "enum": int(d.metadata.get("enum", 0)), "points": n,
                     "seconds": dt, **{k: r.get(k) for k in (
                         "status", "adequate_model", "lambda_determined", "e_star_pa",
                         "work_of_adhesion_j_m2", "lambda", "rms_residual_n")}})
    print(f"{len(todo)} curves in {total:.2f} s on one core: {len(todo) / total:.2f} curves/s")
    if out_json:
        pathlib.Path(out_json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
