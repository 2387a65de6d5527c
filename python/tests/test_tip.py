"""Tips that are not spheres (docs/PHYSICS.md section 12) through the Python package: the same
report as `tabor scene`, and the JKR cone's pull-off near the JKR end."""

import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]


def cone_scene(h0=3e-10):
    return {"e_star_pa": 1e6, "work_of_adhesion_j_m2": 0.05, "h0_m": h0,
            "tip": {"shape": "cone", "half_angle_deg": 70}, "loads_n": [0.0, 1e-6]}


def test_a_cone_pulls_off_at_the_jkr_cones_force():
    s = tabor.Scene(cone_scene())
    w, e, alpha = 0.05, 1e6, math.radians(70)
    jkr = -54 / math.pi * w * w * math.tan(alpha) ** 3 / e
    assert s.report["pulloff_force_load_control_N"] == pytest.approx(jkr, rel=2e-3)
    assert np.all(s.zone_radius_m > s.contact_radius_m)
    assert list(s.model) == ["jkr", "jkr"]


def test_a_tip_scene_is_the_command_lines(tmp_path):
    scene = dict(cone_scene(2e-9), tip={"shape": "capped_cone", "radius_m": 20e-9,
                                        "half_angle_deg": 20})
    path = tmp_path / "tip.json"
    path.write_text(json.dumps(scene))
    binary = ROOT / "target" / "release" / "tabor"
    if not binary.exists():
        if os.environ.get("CI") == "true":
            pytest.fail("no tabor binary under target/release: run cargo build --release first")
        pytest.skip("SKIPPED: no tabor binary under target/release (cargo build --release)")
    cli = json.loads(subprocess.run([str(binary), "scene", str(path), "--format", "json"],
                                    check=True, capture_output=True, text=True).stdout)
    assert tabor.Scene(scene).report == cli
    assert tabor.Scene(scene).warnings[0] == cli["warnings"]


def test_bad_tips_are_refused_in_one_line():
    bad = dict(cone_scene(), tip={"shape": "cone", "half_angle_deg": 95})
    with pytest.raises(ValueError, match="half_angle_deg = 95"):
        tabor.Scene(bad)
