"""tabor.dem_law: the force-overlap law for particle codes from Python, the same numbers as the
command line's `tabor dem-law`, and its refusals."""

import csv
import io
import json
import pathlib
import subprocess

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]
TABOR = ROOT / "target" / "release" / "tabor"
PAIR = {"body1": {"youngs_modulus_pa": 3e9, "poisson_ratio": 0.35, "radius_m": 10e-6},
        "body2": {"youngs_modulus_pa": 3e9, "poisson_ratio": 0.35, "radius_m": 10e-6},
        "work_of_adhesion_j_m2": 0.1, "z0_m": 0.3e-9}


def test_the_drive_is_the_command_lines_to_the_last_bit(tmp_path):
    if not TABOR.exists():
        pytest.skip("the tabor binary is not built (cargo build --release)")
    path = tmp_path / "pair.json"
    path.write_text(json.dumps(PAIR))
    out = subprocess.run(
        [str(TABOR), "dem-law", "--scene", str(path), "--drive", "--overlap-min", "-8e-9",
         "--overlap-max", "2e-8", "--points", "300", "--format", "csv"],
        capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    law = tabor.dem_law(scene=path, overlap_max=2e-8)
    cycle = law.drive(-8e-9, 2e-8, 300)
    for phase in ("approach", "retract"):
        cli = [r for r in rows if r["phase"] == phase]
        assert [float(r["overlap_m"]) for r in cli] == cycle[phase]["overlap"].tolist()
        assert [float(r["force_n"]) for r in cli] == cycle[phase]["force"].tolist()


def test_eval_carries_each_contacts_history():
    law = tabor.dem_law(scene=PAIR, overlap_max=2e-6)
    info = law.info
    assert info["units"].startswith("SI")
    # Approach to 10 nm, then back to a gap between the jump-in and the jump-out: in contact
    # on the way out only.
    history = np.zeros(2, dtype=np.uint8)
    d = 0.5 * (info["jump_in"] + info["jump_out"])
    law.eval(np.array([1e-8, d]), history)
    assert law.branches(history).tolist() == [2, 0]
    f, k = law.eval(np.array([d, d]), history)
    assert law.branches(history).tolist() == [2, 0] and f[0] < 0 and f[1] == 0.0
    # Below the jump-out both are free.
    f, _ = law.eval(np.array([2 * info["jump_out"]] * 2), history)
    assert history.tolist() == [0, 0] and f.tolist() == [0.0, 0.0]
    # The loop energy equals the area between the drive's two branches (trapezoids).
    c = law.drive(3 * info["jump_out"], 1e-8, 20001)
    area = np.trapezoid if hasattr(np, "trapezoid") else np.trapz
    lost = area(c["approach"]["force"], c["approach"]["overlap"]) - \
        area(c["retract"]["force"][::-1], c["retract"]["overlap"][::-1])
    assert abs(lost - info["loop_energy"]) <= 2e-3 * info["loop_energy"]


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="one of them"):
        tabor.dem_law()
    with pytest.raises(ValueError, match="one of them"):
        tabor.dem_law(1.0, scene=PAIR)
    with pytest.raises(ValueError, match="loads_n"):
        tabor.dem_law(scene={**PAIR, "loads_n": [1e-6]})
    with pytest.raises(ValueError, match="range_ratio"):
        tabor.dem_law(1.0, stress_ratio=0.5)
    with pytest.raises(ValueError, match="humidity"):
        tabor.dem_law(scene=PAIR, stress_ratio=0.5, range_ratio=3.0)
    with pytest.raises(ValueError, match="relative_humidity"):
        tabor.dem_law(scene={**PAIR, "humidity": {"relative_humidity": 1.5, "contact_angle_deg": 20}})
    with pytest.raises(ValueError, match="overlap_max"):
        tabor.dem_law(1.0, overlap_max=1e9)
    law = tabor.dem_law(1.0)
    with pytest.raises(ValueError, match="history"):
        law.eval(np.zeros(2), np.zeros(3, dtype=np.uint8))
    with pytest.raises(ValueError, match=r"history\[1\] = 7"):
        law.eval(np.zeros(2), np.array([0, 7], dtype=np.uint8))
    with pytest.raises(ValueError, match=r"history\[0\] = 9"):
        law.branches(np.array([9], dtype=np.uint8))
    with pytest.raises(ValueError, match="points"):
        law.drive(-1.0, 1.0, 1)


HUMID = {**PAIR, "humidity": {"relative_humidity": 0.5, "contact_angle_deg": 20}}


@pytest.mark.parametrize("how", ["scene", "ratios"])
def test_a_wet_law_is_the_command_lines_to_the_last_bit(tmp_path, how):
    if not TABOR.exists():
        pytest.skip("the tabor binary is not built (cargo build --release)")
    if how == "scene":
        path = tmp_path / "pair.json"
        path.write_text(json.dumps(HUMID))
        args = ["--scene", str(path), "--overlap-min", "-4e-9", "--overlap-max", "2e-8"]
        law = tabor.dem_law(scene=path, overlap_max=2e-8)
        lo, hi, ox, fx = -4e-9, 2e-8, "overlap_m", "force_n"
    else:
        args = ["--lambda", "1", "--stress-ratio", "0.5", "--range-ratio", "3",
                "--overlap-min", "-1.5", "--overlap-max", "3"]
        law = tabor.dem_law(1.0, overlap_max=3.0, stress_ratio=0.5, range_ratio=3.0)
        lo, hi, ox, fx = -1.5, 3.0, "overlap", "load"
    out = subprocess.run([str(TABOR), "dem-law", *args, "--drive", "--points", "300",
                          "--format", "csv"], capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    cycle = law.drive(lo, hi, 300)
    for phase in ("approach", "retract"):
        cli = [r for r in rows if r["phase"] == phase]
        assert [float(r[ox]) for r in cli] == cycle[phase]["overlap"].tolist()
        assert [float(r[fx]) for r in cli] == cycle[phase]["force"].tolist()
    info = law.info
    assert info["model"] == "solid_and_meniscus" and info["histories"] >= 3
    if how == "ratios":
        # The meniscus holds the pair across the gap after the jump out of contact.
        assert info["non_contact_end"] < info["jump_out"] < info["jump_in"]
    else:
        # Stiff spheres: the meniscus pulls them into contact from its reach, and the retract
        # comes free at the jump out.
        assert info["jump_in"] == info["attraction_from"] and info["non_contact_end"] is None
        m = info["meniscus"]
        dry = tabor.dem_law(scene=PAIR, overlap_max=2e-8).info
        assert m["range_m"] > 0 and info["attraction_from"] == pytest.approx(-m["range_m"], rel=1e-14)
        assert info["loop_energy"] > dry["loop_energy"]
        assert info["force_scale"] == pytest.approx(
            np.pi * (0.1 + m["work_of_adhesion_j_m2"]) * 5e-6, rel=1e-14)
