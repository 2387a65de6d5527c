"""Real contacts in SI units from Python: a scene, the work of adhesion from a pull-off force,
and the pull-off against relative humidity (the water meniscus).

Run from anywhere: python examples/python/scene_humidity.py. Guide: docs/guide/scenes.md.
"""
import json
from pathlib import Path

import tabor

# A silicon AFM tip on silicon (a preset of representative handbook values).
s = tabor.Scene.preset("afm-si")
print(s)
print(f"pull-off {s.report['pulloff_force_load_control_N'] * 1e9:.4f} nN (load control)")
for load, a, model in zip(s.load_n, s.contact_radius_m, s.model):
    print(f"  load {load * 1e9:6.2f} nN: contact radius {a * 1e9:.4f} nm, model {model}")

# Your own materials: a dict with the scene JSON keys.
own = tabor.Scene({"e_star_pa": 1e9, "radius_m": 1e-6, "work_of_adhesion_j_m2": 0.05,
                   "z0_m": 0.3e-9, "loads_n": [0.0, 1e-6]})
print(own, "radii (nm):", (own.contact_radius_m * 1e9).round(2).tolist())

# The work of adhesion from a measured pull-off force (dry), with the Tabor verdict.
r = tabor.infer_pulloff(-12.2073e-9, 20e-9, 91.1444e9, z0_m=0.3e-9)
print(f"w (exact MD) = {r['w_md_j_m2']:.4e} J/m^2, lambda = {r['lambda_md']:.4f}")
print("verdict:", r["verdict"])

# The same tip in air at 40% RH: the meniscus taken out of the measured force.
wet = tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, relative_humidity=0.4,
                          contact_angle_deg=20)
print(f"solid w with the meniscus taken out: {wet['solid_work_of_adhesion_j_m2']:.4e} J/m^2; "
      f"a dry reading: {wet['dry_md_work_of_adhesion_j_m2']:.4e} J/m^2")

# The pull-off against relative humidity, from the scene file examples/si_tip_40rh.json.
scene = json.loads((Path(__file__).resolve().parent.parent / "si_tip_40rh.json").read_text())
h = tabor.humidity(scene, rh_min=0.2, rh_max=0.8, points=4)
for p in h["points"]:
    print(f"  RH {p['relative_humidity']:.2f}: pull-off {p['pulloff_total_N'] * 1e9:.4f} nN, "
          f"meniscus share {p['meniscus_share']:.3f}")
print(f"the meniscus adds more than half above RH = {h['meniscus_dominates_above_rh']:.3f}")
for w in h["warnings"]:
    print("  warning:", w)
