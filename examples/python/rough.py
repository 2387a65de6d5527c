"""Rough surfaces from Python: a statistical cycle of Maugis-Dugdale summits, a rough scene in
SI units (dry and humid) and a small rough adhesion map.

Run from anywhere: python examples/python/rough.py. Guide: docs/guide/rough.md.
Loads per summit in pi w R; separations and sigma in the summit's approach unit.
"""
import numpy as np

import tabor

# Greenwood-Williamson summits of lambda 2, roughness 0.5, pressed to -1 and retracted.
r = tabor.rough(2.0, 0.5, -1.0, points=100)
print(f"pull-off {r['pulloff_load']:.4f} per summit (a smooth summit: {r['smooth_pulloff']:.4f}), "
      f"energy lost {r['hysteresis']:.4f} per summit per cycle")

# A water meniscus on every summit (stress ratio 0.2, range ratio 5; lambda_s = 1, sigma_s = 1
# in the solid's approach unit, pressed 3 sigma): loads in the units of the total w.
wet = tabor.rough(1.0, 0.6299605249474366, -1.8898815748423097, points=20,
                  stress_ratio=0.2, range_ratio=5.0)
print(f"with a meniscus: pull-off {wet['pulloff_load']:.5f} per summit (total-w units), "
      f"{wet['pulloff_load'] * (1 + 0.2 * 5):.5f} in pi w1 R (w = w1 (1 + rho eta))")

# A MEMS beam on its substrate, in SI units (a scene's "humidity" adds a meniscus per summit).
s = tabor.rough_scene(preset="mems-polysilicon", points=200)
print(f"{s['name']}: pull-off {s['pulloff_force_n'] * 1e6:.2f} uN, {s['summits']:.0f} summits")
scene = {"e_star_pa": 8.4e10, "work_of_adhesion_j_m2": 0.05, "z0_m": 0.3e-9,
         "summit_radius_m": 0.5e-6, "summit_density_m2": 2e12, "sigma_m": 1e-9,
         "nominal_area_m2": 2e-9}
dry = tabor.rough_scene(scene, points=100)
print(f"polysilicon-like scene: pull-off {dry['pulloff_force_n'] * 1e9:.2f} nN")

# The rough adhesion map, small: the pull-off relative to the smooth summit's, and the model.
m = tabor.rough_map(nx=32, ny=32, check=0)
names = m["region_names"]
counts = {n: int((m["region"] == i).sum()) for i, n in enumerate(names) if (m["region"] == i).any()}
print("rough map regions:", counts)
print(f"relative pull-off from {m['relative_pulloff'].max():.3f} to {m['relative_pulloff'].min():.2e}")
