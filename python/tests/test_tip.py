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


def test_a_measured_profile_is_the_command_lines_and_states_its_error(tmp_path):
    """A measured capped cone (80 points) through ``tabor.Scene``: the command line's report,
    key for key, with the table's error stated and within it of the exact capped cone."""
    theta, big_r = math.radians(20), 20e-9
    r = np.linspace(0.0, 4e-8, 80)
    b = big_r * math.cos(theta)
    z = np.where(r <= b, big_r - np.sqrt(np.maximum(big_r**2 - r**2, 0.0)),
                 big_r - big_r / math.sin(theta) + r / math.tan(theta))
    base = dict(cone_scene(2e-9), loads_n=[0.0, 5e-9])
    measured = dict(base, tip={"shape": "profile", "r_m": r.tolist(), "z_m": z.tolist()})
    exact = dict(base, tip={"shape": "capped_cone", "radius_m": big_r, "half_angle_deg": 20})
    m, e = tabor.Scene(measured).report, tabor.Scene(exact).report
    err = m["profile_error"]
    assert 0 < err < 1e-2
    assert any("gives these results within" in w for w in m["warnings"])
    for key in ("pulloff_force_load_control_N", "pulloff_force_displacement_control_N"):
        assert m[key] == pytest.approx(e[key], rel=err)
    path = tmp_path / "measured.json"
    path.write_text(json.dumps(measured))
    binary = ROOT / "target" / "release" / "tabor"
    if not binary.exists():
        if os.environ.get("CI") == "true":
            pytest.fail("no tabor binary under target/release: run cargo build --release first")
        pytest.skip("SKIPPED: no tabor binary under target/release (cargo build --release)")
    cli = json.loads(subprocess.run([str(binary), "scene", str(path), "--format", "json"],
                                    check=True, capture_output=True, text=True).stdout)
    # The report holds the table as arrays; everything else is the command line's, key for key.
    assert {k: v for k, v in m.items() if k != "tip"} == {k: v for k, v in cli.items() if k != "tip"}
    np.testing.assert_array_equal(m["tip"]["r_m"], cli["tip"]["r_m"])
    bad = dict(base, tip={"shape": "profile", "r_m": [0, 1e-9, 2e-9, 3e-9],
                          "z_m": [0, 1e-10, 5e-11, 2e-10]})
    with pytest.raises(ValueError, match=r"z_m\[2\] = 5e-11"):
        tabor.Scene(bad)


def test_bad_tips_are_refused_in_one_line():
    bad = dict(cone_scene(), tip={"shape": "cone", "half_angle_deg": 95})
    with pytest.raises(ValueError, match="half_angle_deg = 95"):
        tabor.Scene(bad)


def test_tip_states_are_the_spheres_and_the_command_lines():
    """``tabor.solve(..., tip=)``: ``power:2`` is the sphere's Maugis-Dugdale (another code
    path) to 1e-12; a cone's states equal ``tabor solve --tip``'s digits; below the pull-off the
    status is ``no_contact`` with NaN numbers; a bad tip or lambda is refused or flagged."""
    lam = np.array([0.3, 1.0, 5.0])
    for key, value in (("load", 0.5), ("approach", 0.3), ("radius", 0.7)):
        t = tabor.solve(lam, tip="power:2", **{key: value})
        m = tabor.solve(lam, **{key: value})
        assert list(t["status"]) == ["ok"] * 3
        for k in ("A", "load", "approach"):
            np.testing.assert_allclose(t[k], m[k], rtol=1e-12, atol=1e-12)
        assert np.all(t["C"] > t["A"])
    r = tabor.solve([1.0, 1.0, 0.0], load=[0.5, -50.0, 0.5], tip="cone")
    assert list(r["status"]) == ["ok", "no_contact", "invalid_input"]
    assert np.isnan(r["A"][1]) and r["message"][1].startswith("below the pull-off")
    binary = ROOT / "target" / "release" / "tabor"
    if binary.exists():
        out = subprocess.run([str(binary), "solve", "--tip", "cone", "--lambda", "1", "--load",
                              "0.5", "--format", "json"], capture_output=True, text=True,
                             check=True)
        cli = json.loads(out.stdout)["results"][0]
        for k in ("A", "C", "load", "approach"):
            assert r[k][0] == cli[k]
    with pytest.raises(ValueError, match="tip wedge"):
        tabor.solve(1.0, load=0.5, tip="wedge")


def test_a_tips_cycle_leaves_contact_at_its_rigid_grip_fold():
    """``tabor.cycle(lam, tip=...)``: the retract's jump off contact starts at the law's
    rigid-grip fold, which ``solve(..., tip=)`` at that approach confirms as the last stable
    state (a little below it there is no contact)."""
    c = tabor.cycle(1.0, tip="cone")
    jump = [j for j in c.metadata["jumps"]
            if j["phase"] == "retract" and j["from"]["branch"] == "contact"][0]
    d = jump["from"]["approach"]
    above = tabor.solve(1.0, approach=d + 1e-12, tip="cone")
    below = tabor.solve(1.0, approach=d - 1e-6, tip="cone")
    assert above["status"][()] == "ok" and below["status"][()] == "no_contact"
    # The approach is stationary at the fold: the load 1e-12 above it moves like sqrt(1e-12).
    assert above["load"][()] == pytest.approx(jump["from"]["load"], rel=1e-5)
    with pytest.raises(ValueError, match="second zone"):
        tabor.cycle(1.0, tip="cone", stress_ratio=0.5, range_ratio=2.0)


def test_a_tips_profile_closes_at_the_range():
    """``tabor.profile(lam, load=, tip=)``: the gap at the zone's edge is the range (J = w),
    zero inside the contact; the cone's apex pressure is NaN (log-infinite); the same numbers
    as ``tabor profile --tip``."""
    p = tabor.profile(1.0, load=0.5, tip="cone")
    assert p["status"] == "ok"
    assert p["energy_release_rate_over_w"] == pytest.approx(1.0, abs=1e-10)
    inside = p["r"] <= p["a"]
    assert np.all(p["gap"][inside] == 0) and np.all(p["gap"][~inside] > 0)
    assert np.isnan(p["pressure"][0]) and np.all(np.isfinite(p["pressure"][1:]))
    binary = ROOT / "target" / "release" / "tabor"
    if binary.exists():
        out = subprocess.run([str(binary), "profile", "--tip", "cone", "--lambda", "1",
                              "--load", "0.5"], capture_output=True, text=True, check=True)
        cli = json.loads(out.stdout)
        assert cli["gap"] == p["gap"].tolist() and cli["a"] == p["a"]


def test_a_tips_adhesion_map_is_the_command_lines(tmp_path):
    """adhesion_map(tip=...) gives `tabor map --tip`'s regions and contact radii, bit for bit;
    a GPU backend and a bad shape are refused in one line."""
    m = tabor.adhesion_map(nx=24, ny=20, tip="power:4", backend="cpu")
    prefix = tmp_path / "tip"
    subprocess.run([str(ROOT / "target" / "release" / "tabor"), "map", "--tip", "power:4",
                    "--nx", "24", "--ny", "20", "--backend", "cpu", "--out",
                    str(tmp_path / "tip.png"), "--npy", str(prefix)],
                   check=True, capture_output=True)
    region = np.load(f"{prefix}_region.npy")
    assert np.array_equal(m.region, region.reshape(m.region.shape))
    a = np.load(f"{prefix}_A.npy").reshape(m.A.shape)
    assert np.array_equal(np.isnan(a), np.isnan(m.A))
    assert np.array_equal(a[~np.isnan(a)], m.A[~np.isnan(m.A)])
    # A blunt tip's map is not the sphere's.
    assert m.region_counts != tabor.adhesion_map(nx=24, ny=20, backend="cpu").region_counts
    with pytest.raises(ValueError, match="solved on the CPU"):
        tabor.adhesion_map(nx=8, ny=8, tip="cone", backend="gpu")
    with pytest.raises(ValueError, match="tip conee"):
        tabor.adhesion_map(nx=8, ny=8, tip="conee")


def test_a_scenes_tip_in_its_units_is_the_command_lines(tmp_path):
    """A scene (dict) as the ``tip`` of the calls in normalised units takes its tip in the units
    of its E* and w, as ``--tip scene:FILE`` does: a measured profile's map and state, bit for
    bit; a scene without a tip is refused."""
    r = np.linspace(0.0, 3e-8, 60)
    scene = {"e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05, "s0_pa": 5e7,
             "tip": {"shape": "profile", "r_m": r.tolist(), "z_m": (1e15 * r**3).tolist()}}
    path = tmp_path / "cubic.json"
    path.write_text(json.dumps(scene))
    binary = str(ROOT / "target" / "release" / "tabor")
    m = tabor.adhesion_map(nx=6, ny=5, lambda_min=0.1, lambda_max=10, tip=scene, backend="cpu")
    prefix = tmp_path / "cubic"
    subprocess.run([binary, "map", "--tip", f"scene:{path}", "--nx", "6", "--ny", "5",
                    "--lambda-min", "0.1", "--lambda-max", "10", "--out",
                    str(tmp_path / "cubic.png"), "--npy", str(prefix)],
                   check=True, capture_output=True)
    assert np.array_equal(m.region, np.load(f"{prefix}_region.npy").reshape(m.region.shape))
    a = np.load(f"{prefix}_A.npy").reshape(m.A.shape)
    assert np.array_equal(a[~np.isnan(a)], m.A[~np.isnan(m.A)])
    s = tabor.solve(1.0, load=0.5, tip=scene)
    out = subprocess.run([binary, "solve", "--tip", f"scene:{path}", "--lambda", "1", "--load",
                          "0.5", "--format", "json"], check=True, capture_output=True, text=True)
    cli = json.loads(out.stdout)["results"][0]
    assert float(s.A) == cli["A"] and float(s.C) == cli["C"]
    # Within the table's error of the cubic power law itself (the units are the same).
    assert float(s.A) == pytest.approx(float(tabor.solve(1.0, load=0.5, tip="power:3").A),
                                       rel=2e-3)
    # Pull-offs: the table within its error of the cubic law; power:2 is the sphere's.
    p, q = tabor.pulloff(1.0, tip=scene), tabor.pulloff(1.0, tip="power:3")
    assert float(p["load_control_load"]) == pytest.approx(float(q["load_control_load"]), rel=2e-3)
    lam = [0.3, 1.0, 5.0]
    two, sphere = tabor.pulloff(lam, tip="power:2"), tabor.pulloff(lam)
    for k in ("load_control_load", "load_control_A", "displacement_control_load"):
        assert np.allclose(two[k], sphere[k], rtol=0, atol=1e-11), k
    with pytest.raises(ValueError, match='has no "tip"'):
        tabor.solve(1.0, load=0.5, tip={"e_star_pa": 1e9, "work_of_adhesion_j_m2": 0.05,
                                        "s0_pa": 5e7, "radius_m": 1e-8})


def test_a_cones_curve_fits_as_the_command_line_fits_it():
    """fit_curves(tip=...) is `tabor fit --tip`'s fit of the same curve, bit for bit (the tip as
    text or as a scene's dict); a cone's closed forms are Sneddon's punch and the JKR-type law;
    a tip with a radius, a measured profile and a humidity are refused naming the argument."""
    path = ROOT / "tests" / "data" / "cone_curve.csv"
    binary = ROOT / "target" / "release" / "tabor"
    cli = json.loads(subprocess.run([str(binary), "fit", "-i", str(path), "--tip", "cone:65",
                                     "--spring-n-m", "0.5"], check=True, capture_output=True,
                                    text=True).stdout)
    assert cli["tip"] == {"shape": "cone", "half_angle_deg": 65.0} and "radius_m" not in cli
    d = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)
    for tip in ("cone:65", {"shape": "cone", "half_angle_deg": 65}):
        r = tabor.fit_curve(d["height_m"], d["force_n"], d["segment"], tip=tip, spring_n_m=0.5)
        c = cli["curves"][0]
        for k in ("status", "e_star_pa", "work_of_adhesion_j_m2", "lambda", "z0_m",
                  "contact_point_m", "rms_residual_n", "adequate_model", "lambda_bound"):
            assert r[k] == c[k], k
        assert [m["model"] for m in r["models"]] == ["hertz", "jkr"]
        assert r["tabor_parameter"] is None and r["verdict"] is None
    # The curve was made with E* = 1 MPa, w = 0.02 J/m^2 and 1% noise: its 95% intervals hold them.
    lo, hi = r["e_star_pa_interval_95"]
    assert lo < 1e6 < hi
    with pytest.raises(ValueError, match="radius_m and tip"):
        tabor.fit_curves([], [], [], tip="cone:65", radius_m=1e-8, spring_n_m=0.5)
    # A measured profile is fitted (tests/suite/fit_tip.rs); a table too short is refused.
    with pytest.raises(ValueError, match="give at least 4"):
        tabor.fit_curves([], [], [], tip={"shape": "profile", "r_m": [0, 1e-8],
                                          "z_m": [0, 1e-9]}, spring_n_m=0.5)
    with pytest.raises(ValueError, match="relative_humidity"):
        tabor.fit_curves([], [], [], tip="cone:65", spring_n_m=0.5, relative_humidity=0.5)


def test_a_fleet_of_cone_maps_is_fitted_with_the_cone():
    """fit_fleet(..., tip=...) passes the tip to every map: the serial fleet's values are
    fit_curve's, Tabor's parameter (the sphere's) is NaN, and the attrs keep the tip."""
    pytest.importorskip("xarray")
    path = ROOT / "tests" / "data" / "cone_curve.csv"
    d = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)
    seg = np.where(d["segment"] == "approach", 0, 1)
    one = tabor.fit_curve(d["height_m"], d["force_n"], seg, tip="cone:65", spring_n_m=0.5)
    n = len(d)
    m = {"height_m": np.tile(d["height_m"], 2), "force_n": np.tile(d["force_n"], 2),
         "segment": np.tile(seg, 2), "x": np.repeat([0, 1], n), "y": np.zeros(2 * n, int),
         "spring_n_m": 0.5}
    ds = tabor.fit_fleet([m], None, tip="cone:65")
    assert list(ds["status"].values.ravel()) == ["ok", "ok"]
    assert np.all(ds["e_star_pa"].values == one["e_star_pa"])
    assert np.all(np.isnan(ds["tabor_parameter"].values))
    assert json.loads(ds.attrs["options"])["tip"] == "cone:65"
