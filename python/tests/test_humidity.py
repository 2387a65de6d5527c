"""Scenes in humid air through Python: the same numbers as `tabor scene`, and the limits that
make the meniscus vanish."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import tabor
from test_tabor import tabor_bin

ROOT = pathlib.Path(__file__).resolve().parents[2]
WET = ROOT / "examples" / "si_tip_40rh.json"


def test_wet_scene_matches_the_command_line():
    r = tabor.Scene.from_file(WET).report
    cli = json.loads(subprocess.run([tabor_bin(), "scene", str(WET), "--format", "json"],
                                    capture_output=True, text=True, check=True).stdout)
    for k in ("pulloff_force_load_control_N", "pulloff_force_displacement_control_N",
              "dry_pulloff_force_load_control_N"):
        assert r[k] == cli[k], k
    assert r["meniscus"] == cli["meniscus"]
    # The meniscus' work is 2 gamma cos(theta) (water, 20 degrees), whatever the humidity.
    assert r["meniscus"]["work_of_adhesion_j_m2"] == pytest.approx(
        2 * 0.072 * np.cos(np.radians(20.0)), rel=1e-12)
    assert abs(r["pulloff_force_load_control_N"]) > abs(r["dry_pulloff_force_load_control_N"])


@pytest.mark.parametrize("humidity", [{"relative_humidity": 0.4, "contact_angle_deg": 95.0},
                                      {"relative_humidity": 0.0, "contact_angle_deg": 20.0}])
def test_no_meniscus_is_the_dry_scene(humidity):
    scene = json.loads(WET.read_text())
    dry = dict(scene)
    del dry["humidity"]
    scene["humidity"] = humidity
    wet, ref = tabor.Scene(scene).report, tabor.Scene(dry).report
    assert wet["pulloff_force_load_control_N"] == ref["pulloff_force_load_control_N"]
    assert wet.get("meniscus") is None


def test_bad_humidity_is_one_value_error():
    scene = json.loads(WET.read_text())
    scene["humidity"] = {"relative_humidity": 1.5, "contact_angle_deg": 20.0}
    with pytest.raises(ValueError, match="relative_humidity"):
        tabor.Scene(scene)
