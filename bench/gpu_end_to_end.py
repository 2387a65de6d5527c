#!/usr/bin/env python3
"""Every GPU workload end to end, GPU against all CPU threads of the same machine, in one run.

    python3 bench/gpu_end_to_end.py [--bin PATH]... [--runs N] [--out DIR] [--big]

Each workload runs `--runs` times (default 2) per binary and backend, alternated, and prints
the wall time and peak memory of each process, the ratio CPU / GPU of the medians, and the
command's own timing line. One more GPU run of each with TABOR_GPU_TRACE=1 keeps the
breakdown (upload, kernels, read-back, host work) in DIR/trace-*.txt. `--big` adds the
16384 x 16384 map (GPU only). Inputs are made here with the standard library (seeded).
"""
import argparse
import math
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time


def make_inputs(d):
    rng = random.Random(1)
    scattered = os.path.join(d, "scattered.csv")
    with open(scattered, "w") as f:
        f.write("lambda,load\n")
        for _ in range(1_000_000):
            f.write(f"{10 ** rng.uniform(-3, 3)!r},{10 ** rng.uniform(-3, 3)!r}\n")
    grid = os.path.join(d, "grid.csv")
    lambdas = [10 ** (-3 + 6 * i / 999) for i in range(1000)]
    loads = [10 ** (-3 + 6 * j / 999) for j in range(1000)]
    with open(grid, "w") as f:
        f.write("lambda,load\n")
        for lam in lambdas:
            for p in loads:
                f.write(f"{lam!r},{p!r}\n")
    asp = os.path.join(d, "asp.csv")
    with open(asp, "w") as f:
        f.write("height_m,radius_m\n")
        for _ in range(1_000_000):
            f.write(f"{rng.gauss(0, 50e-9)!r},{2e-6 * math.exp(rng.gauss(0, 0.5))!r}\n")
    return scattered, grid, asp


def workloads(d, scattered, grid, asp):
    o = lambda name: os.path.join(d, name)  # noqa: E731
    return [
        ("map 4096x4096", ["map", "--nx", "4096", "--ny", "4096", "--out", o("map.png")]),
        ("solve -i, 1e6 rows, 1000 x 1000 grid", ["solve", "-i", grid, "-o", o("grid.out")]),
        ("solve -i, 1e6 rows, own lambdas", ["solve", "-i", scattered, "-o", o("sc.out")]),
        (
            "rough-map 512x512",
            ["rough-map", "--nx", "512", "--ny", "512", "--check", "0", "--out", o("rm.png")],
        ),
        (
            "rough, 1e6 summits x 400",
            ["rough", "--preset", "pdms-rough-glass", "--asperities", asp, "--points", "400",
             "--summits", "tables", "-o", o("ens.json")],
        ),
    ]


def run(cmd, env=None, fail_ok=False):
    t = time.perf_counter()
    # A file, not DEVNULL: builds before 2026-11-29 took a read-write /dev/null for a closed stdout.
    with tempfile.TemporaryFile() as out:
        p = subprocess.Popen(cmd, stdout=out, stderr=subprocess.PIPE, env=env)
        err = p.stderr.read().decode(errors="replace")
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t
    if status != 0:
        if fail_ok:
            return None, None, err
        sys.exit(f"failed ({status}): {' '.join(cmd)}\n{err}")
    return wall, ru.ru_maxrss / 1024, err


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", action="append")
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--out", default=".")
    ap.add_argument("--big", action="store_true")
    ap.add_argument("--only", help="run the workloads whose name contains this")
    a = ap.parse_args()
    bins = a.bin or ["target/release/tabor"]
    os.makedirs(a.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as d:
        t = time.perf_counter()
        # Only the files and the ensemble read inputs.
        needed = a.only is None or "solve" in a.only or "summits" in a.only
        inputs = make_inputs(d) if needed else ("", "", "")
        print(f"inputs made in {time.perf_counter() - t:.1f} s; CPU threads: {os.cpu_count()}")
        rows = []
        for name, args in workloads(d, *inputs):
            if a.only and a.only not in name:
                continue
            walls = {}
            for _ in range(a.runs):
                for b in bins:
                    for backend in ("gpu", "cpu"):
                        w, rss, err = run([b, *args, "--backend", backend], fail_ok=True)
                        if w is None:
                            print(f"    {b} {backend} failed: {err.strip().splitlines()[-1:]}")
                            continue
                        walls.setdefault((b, backend), []).append((w, rss, err))
            for b in bins:
                tag = f"{os.path.basename(os.path.dirname(b)) or b}"
                env = dict(os.environ, TABOR_GPU_TRACE="1")
                _, _, trace = run([b, *args, "--backend", "gpu"], env, fail_ok=True)
                safe = "".join(c if c.isalnum() else "-" for c in name)
                with open(os.path.join(a.out, f"trace-{tag}-{safe}.txt"), "w") as f:
                    f.write(trace)
                if (b, "gpu") not in walls or (b, "cpu") not in walls:
                    continue
                g, c = walls[(b, "gpu")], walls[(b, "cpu")]
                gm = statistics.median(x[0] for x in g)
                cm = statistics.median(x[0] for x in c)
                line = (f"| {name} | {tag} | {min(x[0] for x in g):.2f}-{max(x[0] for x in g):.2f} s,"
                        f" {max(x[1] for x in g):.0f} MB | {min(x[0] for x in c):.2f}-"
                        f"{max(x[0] for x in c):.2f} s, {max(x[1] for x in c):.0f} MB |"
                        f" {cm / gm:.2f} |")
                rows.append(line)
                print(line, flush=True)
                for backend, runs in (("gpu", g), ("cpu", c)):
                    last = [ln for ln in runs[-1][2].splitlines() if ln.strip()][-3:]
                    print(f"    {backend}: " + " / ".join(last), flush=True)
        if a.big:
            for b in bins:
                for backend in ("gpu", "cpu"):
                    args = ["map", "--nx", "16384", "--ny", "16384", "--backend", backend,
                            "--out", os.path.join(d, "big.png")]
                    w, rss, err = run([b, *args], fail_ok=True)
                    last = [ln for ln in err.splitlines() if ln.strip()][-2:]
                    shown = "refused" if w is None else f"{w:.2f} s, {rss:.0f} MB"
                    rows.append(f"| map 16384x16384, {backend} | {b} | {shown} | | |")
                    print(rows[-1], "\n    " + " / ".join(last), flush=True)
        print("\n| workload | binary | GPU wall, peak | CPU wall, peak | CPU / GPU |")
        print("| --- | --- | --- | --- | --- |")
        print("\n".join(rows))


main()
