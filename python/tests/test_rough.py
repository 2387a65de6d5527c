"""Rough surfaces from Python: the same numbers as the command line, and explicit ensembles."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]
TABOR = ROOT / "target" / "release" / "tabor"


def test_rough_equals_the_command_line():
    got = tabor.rough(2.0, 0.5, -1.0, points=60)
    out = subprocess.run([str(TABOR), "rough", "--lambda", "2", "--sigma", "0.5",
                          "--min-separation", "-1", "--points", "60"],
                         capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    for k in ["pulloff_load", "pulloff_separation", "hysteresis", "smooth_pulloff",
              "fuller_tabor_parameter"]:
        assert got[k] == want[k], k
    for leg in ["approach", "retract"]:
        for k in ["separation", "load", "contact_fraction", "noncontact_fraction",
                  "contact_load", "noncontact_load"]:
            assert isinstance(got[leg][k], np.ndarray)
            np.testing.assert_array_equal(got[leg][k], np.array(want[leg][k]))


def test_ensembles_approach_the_statistical_mean():
    rng = np.random.default_rng(3)
    sigma, seps = 0.6, np.array([-0.8, 0.5])
    stat = tabor.rough(1.0, sigma, -0.8, points=2, max_separation=0.5)
    z = rng.normal(0.0, sigma, 200_000)
    e = tabor.rough_ensemble(1.0, z, seps, min_separation=-0.8)
    # The retract of the statistical cycle at d = -0.8 .. 0.5 has the two separations as ends.
    want = stat["retract"]["load"][[0, -1]]
    assert np.all(np.abs(e["load"] - want) < 0.01), (e["load"], want)


def test_bad_roughness_raises():
    with pytest.raises(ValueError, match="sigma"):
        tabor.rough(1.0, -1.0, 0.0)
    with pytest.raises(ValueError, match="heights"):
        tabor.rough_ensemble(1.0, [np.nan], [0.0])


def test_rough_map_equals_the_command_line(tmp_path):
    got = tabor.rough_map(lambda_min=0.1, lambda_max=100, nx=5, sigma_min=0.05, sigma_max=5,
                          ny=4, check=3)
    prefix = str(tmp_path / "m")
    subprocess.run([str(TABOR), "rough-map", "--lambda-min", "0.1", "--lambda-max", "100",
                    "--nx", "5", "--sigma-min", "0.05", "--sigma-max", "5", "--ny", "4",
                    "--check", "3", "--out", str(tmp_path / "m.png"), "--npy", prefix],
                   capture_output=True, text=True, check=True)
    for k in ["lambda", "sigma", "pulloff", "relative_pulloff", "pulloff_separation", "region",
              "model_error"]:
        want = np.load(f"{prefix}_{k}.npy")
        assert isinstance(got[k], np.ndarray)
        assert got[k].shape == want.shape, k
        np.testing.assert_array_equal(got[k], want)
    # The ratio is the pull-off over the smooth summit's, at most 1 (the grips path's minimum).
    np.testing.assert_allclose(got["relative_pulloff"],
                               got["pulloff"] / got["smooth_pulloff"][None, :], rtol=1e-15)
    assert np.all(got["relative_pulloff"] <= 1 + 1e-9)
    assert got["table_error"] < 1e-6 and got["check_max_relative_difference"] < 1e-6
    names = got["region_names"]
    assert set(names[r] for r in got["region"].ravel()) <= {"hertz", "rigid", "dmt", "jkr", "md"}


def test_rough_map_refuses_bad_input():
    with pytest.raises(ValueError, match="sigma_min"):
        tabor.rough_map(sigma_min=-1.0, nx=4, ny=4)
    with pytest.raises(ValueError, match="tolerance"):
        tabor.rough_map(tolerance=2.0, nx=4, ny=4)
    with pytest.raises(ValueError, match="nx"):
        tabor.rough_map(nx=-3)


def test_ensemble_in_chunks_equals_one_call():
    # 3e5 summits: chunks of 6 separations, so 40 separations cross six chunk seams.
    h = np.random.default_rng(1).normal(0.0, 1.0, 300_000)
    d = np.linspace(-3.0, 3.0, 40)
    a = tabor.rough_ensemble(1.0, h, d, min_separation=-3.0)
    b = tabor._tabor.rough_ensemble(1.0, h.tolist(), d.tolist(), -3.0)
    for k in ("separation", "load", "contact_fraction", "noncontact_fraction"):
        assert a[k].shape == (40,) and np.array_equal(a[k], b[k]), k


def test_rough_pulloff_equals_the_command_line_and_refuses_as_it_does():
    got = tabor.rough_pulloff([0.1, 10.0], sigma_min=0.05, sigma_max=2.0, points=7)
    out = subprocess.run([str(TABOR), "rough-pulloff", "--lambda", "0.1,10", "--sigma-min", "0.05",
                          "--sigma-max", "2", "--points", "7"],
                         capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    want = want["curves"] if isinstance(want, dict) else want
    assert [c["lambda"] for c in got] == [0.1, 10.0]
    for g, w in zip(got, want):
        assert g["smooth_pulloff"] == w["smooth_pulloff"]
        for k in ["sigma", "fuller_tabor_parameter", "pulloff", "relative_pulloff"]:
            assert isinstance(g[k], np.ndarray)
            np.testing.assert_array_equal(g[k], np.array(w[k]))
    # Rough enough, the pull-off falls below the smooth summit's (Fuller and Tabor).
    assert got[1]["relative_pulloff"][-1] < 0.5 * got[1]["relative_pulloff"][0]
    with pytest.raises(ValueError, match="sigma_min 0 and sigma_max 10"):
        tabor.rough_pulloff(sigma_min=0.0)
    cli = subprocess.run([str(TABOR), "rough-pulloff", "--sigma-min", "0"],
                         capture_output=True, text=True)
    assert cli.returncode == 1 and "--sigma-min 0 and --sigma-max 10" in cli.stderr


def test_wet_rough_equals_the_command_line_and_refuses_as_it_does():
    args = ["--lambda", "1", "--sigma", "0.6299605249474366", "--min-separation",
            "-1.8898815748423097", "--stress-ratio", "0.2", "--range-ratio", "5",
            "--points", "40"]
    got = tabor.rough(1.0, 0.6299605249474366, -1.8898815748423097, points=40,
                      stress_ratio=0.2, range_ratio=5.0)
    out = subprocess.run([str(TABOR), "rough", *args], capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    for k in ["pulloff_load", "pulloff_separation", "hysteresis", "smooth_pulloff",
              "fuller_tabor_parameter"]:
        assert got[k] == want[k], k
    for leg in ["approach", "retract"]:
        for k in ["separation", "load", "contact_fraction", "noncontact_fraction",
                  "contact_load", "noncontact_load"]:
            np.testing.assert_array_equal(got[leg][k], np.array(want[leg][k]))
    # rho = 0 is the dry surface.
    dry = tabor.rough(1.0, 0.5, -1.0, points=20)
    zero = tabor.rough(1.0, 0.5, -1.0, points=20, stress_ratio=0.0, range_ratio=3.0)
    np.testing.assert_array_equal(dry["retract"]["load"], zero["retract"]["load"])
    with pytest.raises(ValueError, match="range_ratio"):
        tabor.rough(1.0, 0.5, -1.0, stress_ratio=0.2)
    with pytest.raises(ValueError, match="stress ratio"):
        tabor.rough(1.0, 0.5, -1.0, stress_ratio=-0.2, range_ratio=2.0)


def test_asperities_equal_the_command_line_and_refuse_as_it_does(tmp_path):
    rng = np.random.default_rng(3)
    h = rng.normal(0.0, 50e-9, 400)
    r = 2e-6 * np.exp(rng.normal(0.0, 0.5, 400))
    path = tmp_path / "asp.csv"
    rows = "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(h, r))
    path.write_text("height_m,radius_m\n" + rows)
    for summits in ["tables", "exact"]:
        got = tabor.rough_asperities(h, r, preset="pdms-rough-glass", points=50, summits=summits)
        out = subprocess.run([str(TABOR), "rough", "--preset", "pdms-rough-glass",
                              "--asperities", str(path), "--points", "50", "--summits", summits,
                              "--backend", "cpu"],
                             capture_output=True, text=True, check=True)
        want = json.loads(out.stdout)
        assert got["summits"] == want["summits"] == 400
        assert got["pulloff_force_n"] == want["pulloff_force_n"]
        assert got["summit_solver"] == want["summit_solver"]
        assert got["table_error"] == want["table_error"]
        for leg in ["approach", "retract"]:
            for k in ["separation_m", "force_n", "real_contact_area_m2", "contact_fraction",
                      "noncontact_fraction"]:
                assert isinstance(got[leg][k], np.ndarray)
                np.testing.assert_array_equal(got[leg][k], np.array(want[leg][k]))
        if summits == "tables":
            tables = got
    # The two solvers agree within the tables' measured error (forces relative to the largest).
    exact = got
    top = np.abs(exact["retract"]["force_n"]).max()
    assert np.abs(tables["retract"]["force_n"] - exact["retract"]["force_n"]).max() < 1e-6 * top
    with pytest.raises(ValueError, match="radius"):
        tabor.rough_asperities([0.0], [-1e-6], preset="pdms-rough-glass")
    with pytest.raises(ValueError, match="one radius per summit"):
        tabor.rough_asperities([0.0, 1e-9], [1e-6], preset="pdms-rough-glass")
    with pytest.raises(ValueError, match="tables or exact"):
        tabor.rough_asperities(h, r, preset="pdms-rough-glass", summits="fast")
    with pytest.raises(ValueError, match="presets are"):
        tabor.rough_asperities(h, r, preset="granite")


def test_topography_equals_the_command_line(tmp_path):
    # Three paraboloid bumps of known radius on a flat (as tests/suite/rough.rs makes them).
    ny, nx, px = 40, 60, 1e-8
    y, x = np.mgrid[0:ny, 0:nx] * px
    z = np.zeros((ny, nx))
    for bx, by, h, r in [(10, 10, 30e-9, 1e-7), (30, 20, 50e-9, 1.5e-7), (50, 30, 20e-9, 8e-8)]:
        z = np.maximum(z, h - ((x - bx * px) ** 2 + (y - by * px) ** 2) / (2 * r))
    path = tmp_path / "z.npy"
    np.save(path, z)
    got = tabor.rough_topography(z, px, preset="pdms-rough-glass", points=30)
    out = subprocess.run([str(TABOR), "rough", "--preset", "pdms-rough-glass", "--topography",
                          str(path), "--pixel-m", str(px), "--points", "30", "--backend", "cpu"],
                         capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    assert got["summits"] == want["summits"] == 3
    assert got["pulloff_force_n"] == want["pulloff_force_n"] < 0
    for leg in ["approach", "retract"]:
        np.testing.assert_array_equal(got[leg]["force_n"], np.array(want[leg]["force_n"]))
    # Fortran order is the same map.
    same = tabor.rough_topography(np.asfortranarray(z), px, preset="pdms-rough-glass", points=30)
    np.testing.assert_array_equal(same["retract"]["force_n"], got["retract"]["force_n"])
    with pytest.raises(ValueError, match="2-D"):
        tabor.rough_topography(z.ravel(), px, preset="pdms-rough-glass")
    with pytest.raises(ValueError, match="pixel size"):
        tabor.rough_topography(z, -1.0, preset="pdms-rough-glass")
    with pytest.raises(ValueError, match="no summit") as refused:
        tabor.rough_topography(np.zeros((5, 5)), px, preset="pdms-rough-glass")
    # The command line refuses a flat map in the library's words, naming its file.
    flat = tmp_path / "flat.npy"
    np.save(flat, np.zeros((5, 5)))
    out = subprocess.run([str(TABOR), "rough", "--preset", "pdms-rough-glass", "--topography",
                          str(flat), "--pixel-m", str(px), "--backend", "cpu"],
                         capture_output=True, text=True)
    assert out.returncode == 1
    assert str(refused.value) in out.stderr and str(flat) in out.stderr


def _same(got, want, path="report"):
    """The CLI's JSON (parsed) and Python's objects, equal to the last bit: numbers exactly,
    NaN (JSON's null in a number array) as NaN."""
    if isinstance(want, dict):
        assert isinstance(got, dict) and set(got) == set(want), (path, set(got) ^ set(want))
        for k in want:
            _same(got[k], want[k], f"{path}.{k}")
    elif isinstance(got, np.ndarray):
        w = np.array([np.nan if v is None else v for v in want], dtype=float)
        assert got.dtype == np.float64 and got.shape == w.shape, path
        assert np.array_equal(got, w, equal_nan=True), path
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), path
        for i, (g, w) in enumerate(zip(got, want)):
            _same(g, w, f"{path}[{i}]")
    else:
        assert type(got) is type(want) and got == want, (path, got, want)


_SI_SCENE = {"e_star_pa": 8.4e10, "work_of_adhesion_j_m2": 0.05, "z0_m": 0.3e-9,
             "summit_radius_m": 0.5e-6, "summit_density_m2": 2e12, "sigma_m": 1e-9,
             "nominal_area_m2": 2e-9}


@pytest.mark.parametrize("how", ["preset", "dry dict", "wet dict", "wet file"])
def test_rough_scenes_equal_the_command_line_to_the_last_bit(how, tmp_path):
    wet = dict(_SI_SCENE, humidity={"relative_humidity": 0.6, "contact_angle_deg": 20.0})
    scene = {"preset": None, "dry dict": _SI_SCENE, "wet dict": wet, "wet file": wet}[how]
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    args = ["--preset", "mems-polysilicon"] if scene is None else ["--scene", str(path)]
    out = subprocess.run([str(TABOR), "rough", *args, "--points", "40"],
                         capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    if scene is None:
        got = tabor.rough_scene(preset="mems-polysilicon", points=40)
    else:
        got = tabor.rough_scene(str(path) if how == "wet file" else scene, points=40)
    _same(got, want)
    assert ("meniscus" in got) == how.startswith("wet")
    assert isinstance(got["approach"]["force_n"], np.ndarray)


def test_rough_scenes_refuse_as_the_command_line_does():
    with pytest.raises(ValueError, match="one of them"):
        tabor.rough_scene()
    with pytest.raises(ValueError, match="one of them"):
        tabor.rough_scene(_SI_SCENE, preset="mems-polysilicon")
    with pytest.raises(ValueError, match="presets are mems-polysilicon"):
        tabor.rough_scene(preset="granite")
    bad = dict(_SI_SCENE, humidity={"relative_humidity": 1.5, "contact_angle_deg": 20.0})
    with pytest.raises(ValueError, match="relative_humidity"):
        tabor.rough_scene(bad)


@pytest.mark.parametrize("kw, says", [
    (dict(separations=[0.0, float("nan")]), "separations = NaN is outside the supported domain"),
    (dict(separations=[float("inf")]), "separations = inf is outside the supported domain"),
    (dict(separations=[0.0], min_separation=float("nan")),
     "min_separation = NaN is outside the supported domain"),
])
def test_an_ensemble_refuses_a_separation_that_is_not_a_number(kw, says):
    # A NaN separation left every summit free: a load of 0 instead of a refusal.
    with pytest.raises(ValueError) as e:
        tabor.rough_ensemble(1.0, [0.0, 0.5], **kw)
    assert says in str(e.value)


def test_rough_warns_as_the_command_line_does():
    """A retract that ends inside the force range is a partial cycle; the wet loss is exact
    whatever the number of separations, and so is the pull-off."""
    full = tabor.rough(1.0, 0.63, -1.89, points=40, stress_ratio=0.2, range_ratio=5)
    assert full["warnings"] == []
    cut = tabor.rough(1.0, 0.63, -1.89, max_separation=0.0, points=40)
    assert any("inside the summits' force range" in w for w in cut["warnings"]), cut["warnings"]
    few = tabor.rough(1.0, 0.63, -1.89, points=2, stress_ratio=0.2, range_ratio=5)
    assert abs(few["hysteresis"] - full["hysteresis"]) <= 1e-9 * full["hysteresis"]
    assert abs(few["pulloff_load"] - full["pulloff_load"]) <= 1e-9 * abs(full["pulloff_load"])
    assert any("miss the pull-off" in w for w in few["warnings"]), few["warnings"]


def test_a_rough_cycles_advice_names_its_own_arguments():
    # The library's warnings name keys; the command line says --max-separation and --points.
    r = tabor.rough(1.0, 0.63, -1.9, max_separation=0.5, points=5)
    assert len(r["warnings"]) == 2
    assert "give a larger max_separation, or none" in r["warnings"][0]
    assert "give more points to draw it" in r["warnings"][1]
    assert not any("--" in w for w in r["warnings"])


def test_asperities_stepped_on_the_gpu_are_the_cpu_ensemble():
    # The summits stepped on the device (f64 shaders) give the CPU's cycle within 1e-12 of the
    # largest force; without an adapter this skips (fails under TABOR_REQUIRE_GPU=1).
    try:
        tabor.solve(1.0, load=0.5, backend="gpu")
    except ValueError as e:
        if os.environ.get("TABOR_REQUIRE_GPU") == "1":
            pytest.fail(f"TABOR_REQUIRE_GPU=1 but no GPU adapter: {e}")
        pytest.skip(f"SKIPPED: no GPU adapter ({e}); set TABOR_REQUIRE_GPU=1 to make this a failure")
    rng = np.random.default_rng(5)
    h = rng.normal(0.0, 50e-9, 300)
    r = 2e-6 * np.exp(rng.normal(0.0, 0.5, 300))
    cpu = tabor.rough_asperities(h, r, preset="pdms-rough-glass", points=40)
    gpu = tabor.rough_asperities(h, r, preset="pdms-rough-glass", points=40, backend="gpu")
    assert "stepped on the gpu" in gpu["summit_solver"], gpu["summit_solver"]
    top = np.abs(cpu["retract"]["force_n"]).max()
    for leg in ["approach", "retract"]:
        np.testing.assert_array_equal(gpu[leg]["contact_fraction"], cpu[leg]["contact_fraction"])
        np.testing.assert_allclose(gpu[leg]["force_n"], cpu[leg]["force_n"], rtol=0,
                                   atol=1e-12 * top)
    assert gpu["pulloff_force_n"] == pytest.approx(cpu["pulloff_force_n"], rel=1e-12)
    with pytest.raises(ValueError, match="backend"):
        tabor.rough_asperities(h, r, preset="pdms-rough-glass", points=40, backend="tpu")
