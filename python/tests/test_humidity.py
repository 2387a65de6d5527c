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


def test_wet_cycle_matches_the_command_line_and_its_md_limit():
    args = ["cycle", "--lambda", "2", "--stress-ratio", "0.3", "--range-ratio", "3",
            "--format", "json"]
    cli = json.loads(subprocess.run([tabor_bin(), *args], capture_output=True, text=True,
                                    check=True).stdout)
    c = tabor.cycle(2.0, stress_ratio=0.3, range_ratio=3.0)
    assert c.metadata["hysteresis"] == cli["hysteresis"]
    assert list(c["load"]) == [s["point"]["load"] for s in cli["steps"]]
    # No meniscus (stress ratio 0): the dry cycle, number for number.
    dry, md = tabor.cycle(2.0, stress_ratio=0.0, range_ratio=3.0), tabor.cycle(2.0)
    assert np.array_equal(dry["load"], md["load"]) and dry.metadata["hysteresis"] == md.metadata["hysteresis"]


@pytest.mark.parametrize("kw", [{"stress_ratio": -0.1, "range_ratio": 2.0},
                                {"stress_ratio": 0.1},
                                {"stress_ratio": 0.1, "range_ratio": float("nan")}])
def test_bad_wet_cycle_is_one_value_error(kw):
    with pytest.raises(ValueError) as e:
        tabor.cycle(1.0, **kw)
    assert "\n" not in str(e.value) and ("ratio" in str(e.value))


def test_two_zone_pulloff_and_profile_from_python_equal_the_command_line():
    cli = lambda *a: json.loads(subprocess.run([tabor_bin(), *a, "--format", "json"],
                                               capture_output=True, text=True, check=True).stdout)
    p = tabor.pulloff(0.5, stress_ratio=0.3, range_ratio=3.0)
    want = cli("pulloff", "--lambda", "0.5", "--stress-ratio", "0.3", "--range-ratio", "3")
    for k in ("load_control_load", "load_control_A", "displacement_control_load"):
        assert p[k] == want["results"][0][k], k
    # A vanishing second zone is MD itself.
    md = tabor.pulloff(0.5)
    dry = tabor.pulloff(0.5, stress_ratio=0.0, range_ratio=3.0)
    assert abs(dry["load_control_load"] - md["load_control_load"]) < 1e-12
    prof = tabor.profile(0.5, load=0.2, stress_ratio=0.3, range_ratio=3.0, points=64)
    want = cli("profile", "--lambda", "0.5", "--load", "0.2", "--stress-ratio", "0.3",
               "--range-ratio", "3", "--points", "64")
    got_m, want_m = prof["models"][0], want["models"][0]
    assert got_m["model"] == want_m["model"]
    np.testing.assert_array_equal(got_m["r"], np.array(want_m["r"], dtype=float))
    np.testing.assert_array_equal(got_m["gap"], np.array(want_m["gap"], dtype=float))
    with pytest.raises(ValueError, match="range_ratio"):
        tabor.profile(0.5, load=0.2, stress_ratio=0.3)
    with pytest.raises(ValueError):
        tabor.pulloff(0.5, stress_ratio=-1.0, range_ratio=3.0)


def test_infer_in_humid_air_equals_the_command_line():
    r = tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, relative_humidity=0.4,
                            contact_angle_deg=20)
    cli = json.loads(subprocess.run(
        [tabor_bin(), "infer", "--pulloff", "-28.8155e-9", "--radius", "20e-9", "--e-star",
         "91.1444e9", "--relative-humidity", "0.4", "--contact-angle-deg", "20",
         "--format", "json"], capture_output=True, text=True, check=True).stdout)
    assert r["solid_work_of_adhesion_j_m2"] == cli["solid_work_of_adhesion_j_m2"]
    assert abs(r["solid_work_of_adhesion_j_m2"] - 0.1) < 1e-6
    assert r["dry_md_work_of_adhesion_j_m2"] > 0.2
    with pytest.raises(ValueError, match="relative_humidity"):
        tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, relative_humidity=1.5)


def _cli_json(*args):
    return json.loads(subprocess.run([tabor_bin(), *args], capture_output=True, text=True,
                                     check=True).stdout)


@pytest.mark.parametrize("kw,args", [
    ({"preset": "afm-si"}, ["--preset", "afm-si"]),
    ({"preset": "pdms-glass", "contact_angle_deg": 30.0, "points": 31},
     ["--preset", "pdms-glass", "--contact-angle-deg", "30", "--points", "31"]),
    ({"scene": json.loads(WET.read_text()), "rh_min": 0.1, "rh_max": 0.99, "points": 7},
     ["--scene", str(WET), "--rh-min", "0.1", "--rh-max", "0.99", "--points", "7"]),
])
def test_humidity_sweep_equals_the_command_line_to_the_last_bit(kw, args):
    r = tabor.humidity(**kw)
    cli = _cli_json("humidity", *args, "--format", "json")
    assert r == cli
    # The CSV table carries the same numbers (17 significant digits round-trip).
    csv = subprocess.run([tabor_bin(), "humidity", *args, "--format", "csv"],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    for row, p in zip(csv[1:], r["points"]):
        v = row.split(",")
        assert float(v[0]) == p["relative_humidity"]
        assert float(v[6]) == p["pulloff_total_N"]
        assert (v[3] == "") == (p["meniscus_lambda"] is None)


def test_humidity_sweep_refuses_as_the_command_line():
    with pytest.raises(ValueError, match="rh_max"):
        tabor.humidity(preset="afm-si", rh_max=1.0)
    with pytest.raises(ValueError, match="points"):
        tabor.humidity(preset="afm-si", points=-3)
    with pytest.raises(ValueError, match="scene"):
        tabor.humidity()


def test_below_one_molecule_python_warns_and_gives_the_dry_answer():
    """RH = 1e-10: a Kelvin radius of 23 pm, below one molecule: no meniscus is counted, and
    the warning is the command line's."""
    r = tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, relative_humidity=1e-10,
                            contact_angle_deg=20)
    dry = tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9)
    cli = _cli_json("infer", "--pulloff", "-28.8155e-9", "--radius", "20e-9", "--e-star",
                    "91.1444e9", "--relative-humidity", "1e-10", "--contact-angle-deg", "20",
                    "--format", "json")
    assert r["solid_work_of_adhesion_j_m2"] == dry["w_md_j_m2"]
    assert r["meniscus"] is None
    assert r["warnings"] == cli["warnings"]
    assert "below one molecule of the liquid (0.310 nm" in r["warnings"][0]
    scene = json.loads(WET.read_text())
    scene["humidity"]["relative_humidity"] = 1e-10
    rep = tabor.Scene(scene).report
    assert rep["meniscus_warnings"][0].startswith("the Kelvin radius 0.023 nm at RH = 1e-10")
    assert "meniscus" not in rep


def test_contact_angle_without_humidity_is_refused():
    with pytest.raises(ValueError, match="contact_angle_deg is given without relative_humidity"):
        tabor.infer_pulloff(-28.8155e-9, 20e-9, 91.1444e9, contact_angle_deg=20)


CURVE = ROOT / "gallery" / "fit_curve.csv"  # E* = 2 GPa, w = 0.04 J/m^2, lambda = 0.3, R = 20 nm


def _fit_cli(*extra):
    out = subprocess.run([tabor_bin(), "fit", "-i", str(CURVE), "--radius", "20e-9",
                          "--spring-n-m", "40", *extra], capture_output=True, text=True)
    return out


def test_fit_in_humid_air_gives_the_solid_w_of_infer_on_the_fitted_pulloff():
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    args = (rows["height_m"], rows["force_n"], rows["segment"])
    r = tabor.fit_curve(*args, radius_m=20e-9, spring_n_m=40.0, relative_humidity=0.4,
                        contact_angle_deg=80)
    assert r["status"] == "ok"
    assert abs(r["work_of_adhesion_j_m2"] / 0.04 - 1) < 0.1
    h = r["humidity"]
    # The same object as the command line's.
    cli = json.loads(_fit_cli("--relative-humidity", "0.4", "--contact-angle-deg", "80").stdout)
    want = cli["curves"][0]["humidity"]
    for k in ("pulloff_force_load_control_n", "z0_m", "solid_work_of_adhesion_j_m2",
              "solid_lambda", "meniscus_share", "meniscus_only_pulloff_n"):
        assert h[k] == pytest.approx(want[k], rel=1e-12), k
    assert h["meniscus"] == pytest.approx(want["meniscus"], rel=1e-12)
    # The force: the fitted model's load-controlled pull-off, Pbar_c(lambda) pi w R.
    pbar = tabor.pulloff(r["lambda"])["load_control_load"]
    assert h["pulloff_force_load_control_n"] == pytest.approx(
        -pbar * np.pi * r["work_of_adhesion_j_m2"] * 20e-9, rel=1e-12)
    # The solid's w: `infer --relative-humidity` on that force with the fitted E* and z0.
    inf = tabor.infer_pulloff(h["pulloff_force_load_control_n"], 20e-9, r["e_star_pa"],
                              z0_m=h["z0_m"], relative_humidity=0.4, contact_angle_deg=80)
    ws = h["solid_work_of_adhesion_j_m2"]
    assert abs(ws / inf["solid_work_of_adhesion_j_m2"] - 1) < 1e-9
    assert 0 < ws < r["work_of_adhesion_j_m2"]
    assert h["meniscus"]["work_of_adhesion_j_m2"] == pytest.approx(
        2 * 0.072 * np.cos(np.radians(80)), rel=1e-12)
    # No meniscus at 90 degrees or more: the fitted w itself.
    dry = tabor.fit_curve(*args, radius_m=20e-9, spring_n_m=40.0, relative_humidity=0.4,
                          contact_angle_deg=95)["humidity"]
    assert dry["meniscus"] is None and dry["meniscus_share"] == 0.0
    assert dry["solid_work_of_adhesion_j_m2"] == r["work_of_adhesion_j_m2"]


# Two zones (examples/wet_curve.rs): E* 1.5 GPa, solid w 0.03 J/m^2, lambda 0.5, RH 0.7, 10 deg.
WET_CURVE = ROOT / "tests" / "data" / "wet_curve.csv"


def test_a_curve_beyond_one_zone_is_fitted_with_two_zones_as_on_the_command_line():
    rows = np.genfromtxt(WET_CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    r = tabor.fit_curve(rows["height_m"], rows["force_n"], rows["segment"], radius_m=20e-9,
                        spring_n_m=2.0, relative_humidity=0.7, contact_angle_deg=10)
    h = r["humidity"]
    assert h["fair_reading"] is False
    s = h["shape_fit"]
    f = s["fit"]
    assert f["model"] == "solid_and_meniscus"
    assert f["e_star_pa"] == pytest.approx(1.5e9, rel=1e-6)
    assert f["work_of_adhesion_j_m2"] == pytest.approx(0.03, rel=1e-6)
    assert f["lambda"] == pytest.approx(0.5, rel=1e-5)
    assert s["lambda_bounded"] is True
    out = subprocess.run([tabor_bin(), "fit", "-i", str(WET_CURVE), "--radius", "20e-9", "--spring-n-m",
                          "2", "--relative-humidity", "0.7", "--contact-angle-deg", "10"],
                         capture_output=True, text=True)
    cli = json.loads(out.stdout)["curves"][0]["humidity"]["shape_fit"]
    for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "rms_residual_n"):
        assert f[k] == pytest.approx(cli["fit"][k], rel=1e-12), k
    assert s["lambda_95"] == pytest.approx(cli["lambda_95"], rel=1e-12)


@pytest.mark.parametrize("kw,flags", [
    ({"relative_humidity": 1.5}, ["--relative-humidity", "1.5"]),
    ({"relative_humidity": -0.1}, ["--relative-humidity", "-0.1"]),
    ({"relative_humidity": 0.0}, ["--relative-humidity", "0"]),
    ({"relative_humidity": float("nan")}, ["--relative-humidity", "NaN"]),
    ({"relative_humidity": 0.4, "contact_angle_deg": 200.0},
     ["--relative-humidity", "0.4", "--contact-angle-deg", "200"]),
    ({"relative_humidity": 0.4, "contact_angle_deg": -5.0},
     ["--relative-humidity", "0.4", "--contact-angle-deg", "-5"]),
    ({"relative_humidity": 0.4, "surface_tension_n_m": -0.07},
     ["--relative-humidity", "0.4", "--surface-tension-n-m", "-0.07"]),
    ({"relative_humidity": 0.4, "temperature_k": 0.0},
     ["--relative-humidity", "0.4", "--temperature-k", "0"]),
])
def test_bad_humidity_in_a_fit_is_refused_with_the_command_lines_words(kw, flags, tmp_path):
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    with pytest.raises(ValueError) as e:
        tabor.fit_curve(rows["height_m"], rows["force_n"], rows["segment"], radius_m=20e-9,
                        spring_n_m=40.0, **kw)
    out = tmp_path / "fit.json"
    cli = _fit_cli(*flags, "-o", str(out))
    assert cli.returncode == 1 and not out.exists()
    line = cli.stderr.strip()
    assert "\n" not in line and "\n" not in str(e.value)
    flag = flags[-2]
    # "error: --flag: words" against "keyword: words", the keyword the flag's.
    words = line.split(f"{flag}: ", 1)[1]
    key = flag[2:].replace("-", "_")
    assert str(e.value) == f"{key}: {words}"
    if kw["relative_humidity"] == 0.0:
        assert "no meniscus" in words
