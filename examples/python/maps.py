"""An adhesion map from Python: which model a contact needs, as arrays and as a figure.

Run from anywhere: python examples/python/maps.py (writes map.png and map_*.npy in the current
folder). Guide: docs/guide/maps.md.
"""
import numpy as np

import tabor

# The classic map, lambda and load 1e-3..1e3, on the exact f64 solver (256 x 256: well under a
# second; tabor map's default is 1024 x 1024).
m = tabor.adhesion_map(nx=256, ny=256, backend="cpu")
total = sum(m.region_counts.values())
print("regions:", ", ".join(f"{k} {100 * v / total:.1f}%" for k, v in m.region_counts.items()))

# Which model is adequate at one state: look it up on the grid.
i = np.argmin(abs(np.log(m.load_axis / 1.0)))  # the row nearest Pbar = 1
j = np.argmin(abs(np.log(m.lam / 0.3)))        # the column nearest lambda = 0.3
print(f"lambda = {m.lam[j]:.3g}, Pbar = {m.load_axis[i]:.3g}: {m.region_names[m.region[i, j]]}")

# The load-controlled pull-off along the lambda axis: -2 (DMT) to -3/2 (JKR).
print(f"pull-off from {m.pulloff[0]:.4f} at lambda {m.lam[0]:g} to {m.pulloff[-1]:.4f} at {m.lam[-1]:g}")

# A figure one journal column wide (85 mm, PNG at 300 dpi) and the NumPy arrays.
m.save("map.png")
m.save("map", npy=True)
print("wrote map.png and map_*.npy")
