"""Fitting AFM force curves from Python: one measured-like curve with its intervals, a small
force map of several curves told apart by their ids, and a cone's curve fitted with the cone.

Run from anywhere: python examples/python/fit.py. Guide: docs/guide/fitting.md.
"""
from pathlib import Path

import numpy as np

import tabor

# The gallery's synthetic curve (exact MD under a 40 N/m cantilever, E* = 2 GPa,
# w = 0.04 J/m^2, lambda = 0.3, R = 20 nm, 20 pN noise): columns x, y, segment, height_m, force_n.
path = Path(__file__).resolve().parents[2] / "gallery" / "fit_curve.csv"
c = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
f = tabor.fit_curve(c["height_m"], c["force_n"], c["segment"], radius_m=20e-9, spring_n_m=40)
print(f"status {f['status']}, adequate model {f['adequate_model']}")
for key, unit in (("e_star_pa", "Pa"), ("work_of_adhesion_j_m2", "J/m^2")):
    lo, hi = f[key + "_interval_95"]
    print(f"{key} = {f[key]:.5g} {unit} (95%: {lo:.5g}..{hi:.5g})")
print(f"lambda = {f['lambda']:.4f}, determined: {f['lambda_determined']}")
print(f"rms residual {f['rms_residual_n'] * 1e12:.1f} pN; Hertz, DMT, JKR:",
      ", ".join(f"{m['model']} {m['rms_residual_n'] * 1e12:.0f} pN" for m in f["models"]))
for w in f["warnings"]:
    print("warning:", w)

# A small force map: three noise-free curves made with tabor.cycle at three lambdas (the base
# height from the normalised base displacement Delta), in one set of arrays with curve ids.
E, w, R, k = 2e9, 0.04, 20e-9, 40.0
unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)     # the approach unit, m
heights, forces, segments, ids = [], [], [], []
for i, lam in enumerate([0.3, 1.0, 3.0]):
    cy = tabor.cycle(lam, drive="spring", stiffness=k * unit / (np.pi * w * R))
    heights.append(-cy["control"] * unit)
    forces.append(cy["load"] * np.pi * w * R)
    segments.append(np.where(cy["phase"] == "approach", 0, 1))
    ids.append(np.full(len(cy["load"]), f"pixel {i}"))
fits = tabor.fit_curves(np.concatenate(heights), np.concatenate(forces),
                        np.concatenate(segments), np.concatenate(ids), radius_m=R, spring_n_m=k)
for r in fits:
    print(f"{r['curve']}: lambda {r['lambda']:.4f}, w {r['work_of_adhesion_j_m2']:.4g} J/m^2, "
          f"adequate model {r['adequate_model']}")

# A curve made on a 65-degree cone (E* = 1 MPa, w = 0.02 J/m^2, lambda = 1, 1% noise), fitted
# with the cone: its closed forms are Sneddon's punch ("hertz") and the JKR-type law ("jkr").
path = Path(__file__).resolve().parents[2] / "tests" / "data" / "cone_curve.csv"
c = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
f = tabor.fit_curve(c["height_m"], c["force_n"], c["segment"], tip="cone:65", spring_n_m=0.5)
lo, hi = f["e_star_pa_interval_95"]
print(f"cone: E* = {f['e_star_pa']:.4g} Pa (95%: {lo:.4g}..{hi:.4g}), "
      f"adequate model {f['adequate_model']}")
