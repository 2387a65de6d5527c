"""Maugis-Dugdale states from Python: a broadcast grid, pull-offs, a curve, two zones.

Run from anywhere: python examples/python/states.py. Guide: docs/guide/states.md.
Units (Johnson & Greenwood): load Pbar = P / (pi w R), A = a (K / (pi w R^2))^(1/3), K = 4/3 E*.
"""
import numpy as np

import tabor

# States on a grid: lambda down the rows, loads across, broadcast as NumPy does.
r = tabor.solve([[0.1], [1.0], [10.0]], load=[-1.7, 0.0, 1.0])
print("A =")
print(r["A"].round(6))
print("status:", r["status"].tolist())     # no_contact below each lambda's pull-off
print("backend:", r.metadata["backend"], r.metadata["precision"])

# The same state under displacement control and at a contact radius.
d = tabor.solve(1.0, approach=1.4148143878800299)
print(f"approach 1.41481 -> load {float(d['load']):.6f}")
a = tabor.solve(1.0, radius=1.0)
print(f"A = 1 -> load {float(a['load']):.6f}, load-stable {bool(a['load_stable'])}")

# Pull-offs under both controls; below lambda_D the rigid-grip contact is lost at zero radius.
p = tabor.pulloff([0.1, 1.0, 10.0])
for lam, pc, pd in zip([0.1, 1.0, 10.0], p["load_control_load"], p["displacement_control_load"]):
    print(f"lambda {lam:>4}: Pbar_c = {pc:.6f} (load control), {pd:.6f} (displacement control)")
print(f"lambda_D = {tabor.LAMBDA_D:.6f}")

# The whole curve of one lambda, stable and unstable parts.
c = tabor.curve(1.0, points=5)
print("curve A:", c["A"].tolist(), "load:", c["load"].round(4).tolist())

# The closed forms against MD at one load.
load = 1.0
md = float(tabor.solve(1.0, load=load)["A"])
for name, f in (("hertz", tabor.hertz), ("dmt", tabor.dmt), ("jkr", tabor.jkr)):
    print(f"{name}: A = {float(f(load=load)):.4f} ({100 * (float(f(load=load)) / md - 1):+.1f}% against MD)")

# Two Dugdale zones (solid and a water meniscus): stress ratio 0.5, range ratio 3.
z = tabor.pulloff(1.0, stress_ratio=0.5, range_ratio=3.0)
print(f"two zones: load-controlled pull-off {z['load_control_load']:.6f} (units of the total w)")
assert np.isnan(r["A"][1, 0]) and r["status"][1, 0] == "no_contact"
