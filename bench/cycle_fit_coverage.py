"""A cantilever's cycle fitted back: how often the 95% intervals hold the truth.

The curve is tabor's own Maugis-Dugdale cycle (lambda 0.3, E* = 2 GPa, w = 0.04 J/m^2,
R = 20 nm, k = 40 N/m), one force per height (a jump's landing shares its fold's height and is
left out), with seeded Gaussian noise on the force. At 0.2% of the pull-off (1e-11 N) the
retract's 1538 points are fitted on bins; the intervals come from the bins' profile and are
moved to the fit finished on the points (`fit::interval::recentre`).

    target/py-venv/bin/python bench/cycle_fit_coverage.py [NOISE_N] [DRAWS]
"""

import sys

import numpy as np

import tabor

E, W, LAM, R, K = 2e9, 0.04, 0.3, 20e-9, 40.0


def main():
    noise = float(sys.argv[1]) if len(sys.argv) > 1 else 1e-11
    draws = int(sys.argv[2]) if len(sys.argv) > 2 else 8
    unit = (np.pi**2 * W**2 * R / (4 / 3 * E) ** 2) ** (1 / 3)
    c = tabor.cycle(LAM, drive="spring", stiffness=K * unit / (np.pi * W * R))
    s = ~c["jump"]
    height = -c["control"][s] * unit
    clean = c["load"][s] * np.pi * W * R
    segment = np.where(c["phase"][s] == "approach", 0, 1)
    print(f"noise {noise:g} N ({noise / -clean.min():.2%} of the pull-off), {draws} draws")
    held = {"e_star_pa": 0, "work_of_adhesion_j_m2": 0, "lambda": 0}
    truth = {"e_star_pa": E, "work_of_adhesion_j_m2": W, "lambda": LAM}
    for seed in range(draws):
        force = clean + np.random.default_rng(seed).normal(0, noise, clean.size)
        f = tabor.fit_curve(height, force, segment, radius_m=R, spring_n_m=K)
        row = []
        for q, t in truth.items():
            lo, hi = f[q + "_interval_95"]
            ok = lo is not None and hi is not None and lo <= t <= hi
            held[q] += ok
            row.append(f"{q} {f[q]:.6g} [{lo:.6g}, {hi:.6g}]{'' if ok else ' MISS'}")
        print(f"draw {seed}: " + "; ".join(row))
    print("95% intervals holding the truth: " + ", ".join(f"{q} {n} of {draws}" for q, n in held.items()))


if __name__ == "__main__":
    main()
