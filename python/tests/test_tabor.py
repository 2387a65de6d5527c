"""tabor's Python package against the reference tables, the command line and its own limits."""

import csv
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "data"
IN_CI = os.environ.get("CI") == "true"

# The f64 contract, as tests/common/mod.rs: relative error of A and m-1 within 1e-12, within
# 1e-12 + 1e-15/sqrt(Pbar - Pbar_c) closer than 1e-6 to the pull-off.
F64_TOL, F64_NEAR = 1e-12, 1e-15


def bound(load, pulloff):
    gap = load - pulloff
    return F64_TOL if gap >= 1e-6 else F64_TOL + F64_NEAR / np.sqrt(max(gap, 1e-300))


def rows(name):
    with open(DATA / name) as f:
        return list(csv.DictReader(f))


def tabor_bin():
    """The command-line binary built by `cargo build --release` (the README's test command
    builds it before pytest runs)."""
    for p in (ROOT / "target" / "release" / "tabor", ROOT / "target" / "debug" / "tabor"):
        if p.exists():
            return str(p)
    if IN_CI:
        pytest.fail("no tabor binary under target/: run cargo build --release first")
    pytest.skip("SKIPPED: no tabor binary under target/ (cargo build --release)")


def test_version_matches_the_crate():
    cargo = (ROOT / "Cargo.toml").read_text()
    version = next(l.split('"')[1] for l in cargo.splitlines() if l.startswith("version"))
    assert tabor.__version__ == version


def test_reference_states_meet_the_f64_contract():
    r = rows("points.csv")
    lam = np.array([float(x["lambda"]) for x in r])
    load = np.array([float(x["Pbar"]) for x in r])
    s = tabor.solve(lam, load=load)
    assert (s["status"] == "ok").all()
    worst = 0.0
    for i, x in enumerate(r):
        b = bound(load[i], float(x["Pbar_pulloff_load"]))
        e = max(abs(s["A"][i] / float(x["A"]) - 1.0),
                abs(s["m_minus_1"][i] / float(x["m_minus_1"]) - 1.0),
                abs(s["approach"][i] - float(x["Dbar"])) / max(1.0, abs(float(x["Dbar"]))))
        assert e <= b, (x, e)
        worst = max(worst, e / b)
    print(f"300 reference states: worst error {worst:.2f} of its bound")


def test_solve_equals_the_command_line_bit_for_bit(tmp_path):
    r = rows("points.csv")
    inp = tmp_path / "in.csv"
    inp.write_text("lambda,load\n" + "".join(f"{x['lambda']},{x['Pbar']}\n" for x in r))
    out = subprocess.run([tabor_bin(), "solve", "-i", str(inp), "--backend", "cpu"],
                         capture_output=True, text=True, check=True).stdout
    cli = list(csv.DictReader(out.splitlines()))
    s = tabor.solve([float(x["lambda"]) for x in r], load=[float(x["Pbar"]) for x in r])
    for i, c in enumerate(cli):
        for key, col in (("A", "A"), ("approach", "approach"), ("m_minus_1", "m_minus_1")):
            assert float(c[col]) == s[key][i], (i, key)
        assert c["status"] == s["status"][i]


def test_broadcasting_and_shapes():
    lam = np.array([0.1, 1.0, 10.0])[:, None]
    load = np.linspace(-1.0, 5.0, 7)
    s = tabor.solve(lam, load=load)
    assert s["A"].shape == (3, 7) and s["status"].shape == (3, 7)
    # Each element is the scalar solve of its pair.
    for i in range(3):
        for j in range(7):
            one = tabor.solve(float(lam[i, 0]), load=float(load[j]))
            assert one["A"].shape == ()
            assert one["A"] == s["A"][i, j] or (np.isnan(one["A"]) and np.isnan(s["A"][i, j]))
    assert tabor.solve(1.0, approach=np.zeros((2, 2)))["A"].shape == (2, 2)
    p = tabor.pulloff([[0.1, 1.0]])
    assert p["load_control_load"].shape == (1, 2)


def test_values_and_failures_are_marked():
    s = tabor.solve(1.0, load=[0.5, -1.7, 1e13])
    assert list(s["status"]) == ["ok", "no_contact", "invalid_input"]
    assert s["A"][0] == pytest.approx(1.7289400402050878, rel=1e-15)
    assert np.isnan(s["A"][1:]).all()
    s = tabor.solve([1e-305, 1e200], load=1.0)
    assert (s["status"] == "invalid_input").all() and np.isnan(s["A"]).all()


def test_radius_control_matches_the_reference_curves():
    r = [x for x in rows("curves.csv") if float(x["A"]) > 0]
    s = tabor.solve([float(x["lambda"]) for x in r], radius=[float(x["A"]) for x in r])
    for i, x in enumerate(r):
        assert abs(s["load"][i] - float(x["Pbar"])) <= 1e-12 * max(1.0, abs(float(x["Pbar"])))
        assert s["load_stable"][i] == (x["load_stable"] == "1")
        assert s["displacement_stable"][i] == (x["disp_stable"] == "1")


def test_pulloffs_and_closed_forms():
    for x in rows("pulloff.csv")[::10]:
        p = tabor.pulloff(float(x["lambda"]))
        assert p["load_control_load"] == pytest.approx(float(x["Pbar_load"]), rel=1e-12)
        assert p["displacement_control_load"] == pytest.approx(float(x["Pbar_disp"]), rel=1e-12)
    assert tabor.jkr(load=0.0) == pytest.approx(6 ** (1 / 3))
    assert tabor.dmt(load=-2.0) == 0.0 and np.isnan(tabor.dmt(load=-2.5))
    assert tabor.hertz(A=2.0) == 8.0
    assert tabor.jkr(A=1.5 ** (1 / 3)) == pytest.approx(-1.5, abs=1e-14)
    assert tabor.bradley() == -2.0
    c = tabor.curve(1.0, a_max=4.0, points=5)
    assert c["A"][-1] == 0.0 and np.isinf(c["m_minus_1"][-1])
    assert c["load"][3] == pytest.approx(-1.5796270206018335, rel=1e-15)


@pytest.mark.parametrize("call, needle", [
    (lambda: tabor.solve(1.0), "exactly one of"),
    (lambda: tabor.solve(1.0, load=1.0, approach=1.0), "exactly one of"),
    (lambda: tabor.solve([1.0, 2.0], load=[1.0, 2.0, 3.0]), "broadcast"),
    (lambda: tabor.solve(1.0, load=1.0, backend="tpu"), "backend"),
    (lambda: tabor.solve(1.0, load=1.0, check=-1), "check"),
    (lambda: tabor.pulloff(1e300), "1e-26..1e26"),
    (lambda: tabor.curve(1.0, a_max=1e300), "contact radius A = 1e300"),
    (lambda: tabor.adhesion_map(nx=8, ny=8, lambda_min=1e-30, backend="cpu"), "lambda = 1e-30"),
    (lambda: tabor.adhesion_map(nx=8, ny=8, load_axis="sideways"), "load_axis"),
    (lambda: tabor.Scene.preset("nosuch"), "no preset"),
    (lambda: tabor.Scene({"e_star_pa": 1e9}), "missing"),
    (lambda: tabor.infer_pulloff(-1e300, 1e-8, 1e11), "pulloff_force_n"),
    (lambda: tabor.fit_pairs([1e-6, 1e-6], [1e-6, 1e-6], 1e-3), "two different loads"),
    (lambda: tabor.cycle(1.0, drive="grips", stiffness=1.0), "stiffness"),
    (lambda: tabor.cycle(1e-300), "1e-26..1e26"),
    (lambda: tabor.profile(1.0, load=-1.7), "no_contact"),
])
def test_bad_input_raises_with_tabors_message(call, needle):
    with pytest.raises((ValueError, TypeError)) as e:
        call()
    assert needle in str(e.value)


def test_a_map_as_arrays_and_files_as_the_command_line_writes_them(tmp_path):
    m = tabor.adhesion_map(nx=48, ny=32, backend="cpu")
    assert m.A.shape == (32, 48) and m.lam.shape == (48,) and m.load_axis.shape == (32,)
    names = m.region_names
    assert names[m.region[-1, 0]] == "hertz"  # largest load, smallest lambda
    assert sum(m.region_counts.values()) == 48 * 32
    for ext in ("png", "svg", "pdf", "json"):
        m.save(tmp_path / f"py.{ext}")
    m.save(tmp_path / "py", npy=True)  # a prefix only when asked for: see test_reliability
    subprocess.run([tabor_bin(), "map", "--nx", "48", "--ny", "32", "--backend", "cpu",
                    "--out", str(tmp_path / "cli.png"), "--svg", str(tmp_path / "cli.svg"),
                    "--pdf", str(tmp_path / "cli.pdf"),
                    "--json", str(tmp_path / "cli.json"), "--npy", str(tmp_path / "cli")],
                   check=True, capture_output=True)
    # Two journal columns at 300 dpi: 175 mm is 2067 pixels (the PNG header holds the width).
    m.save(tmp_path / "wide.png", width_mm=175)
    assert int.from_bytes((tmp_path / "wide.png").read_bytes()[16:20], "big") == 2067
    for ext in ("png", "svg", "pdf", "json"):
        assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / f"cli.{ext}").read_bytes(), ext
    for n in ("lambda", "A", "region"):
        assert (tmp_path / f"py_{n}.npy").read_bytes() == (tmp_path / f"cli_{n}.npy").read_bytes()


def test_scenes_infer_fit_cycle_profile():
    s = tabor.Scene.preset("afm-si")
    assert 0.05 < s.lam < 0.2 and s.recommended_model in ("md", "dmt", "rigid")
    assert s.contact_radius_m.shape == s.load_n.shape
    same = tabor.Scene(s.report and {"e_star_pa": 1e9, "radius_m": 1e-6,
                                     "work_of_adhesion_j_m2": 0.05, "z0_m": 3e-10})
    assert same.lam > 0
    inf = tabor.infer_pulloff(1e-8, 1e-8, 1e11)
    assert inf["w_jkr_j_m2"] == pytest.approx(1e-8 / (1.5 * np.pi * 1e-8))
    c = tabor.cycle(1.0)
    assert c.metadata["hysteresis"] == pytest.approx(0.4963, abs=2e-3)
    p = tabor.profile(1.0, load=0.0)
    md = p["models"][0]
    assert md["energy_release_rate_over_w"] == pytest.approx(1.0, abs=1e-12)
    assert md["pressure"].shape == md["r"].shape


def gpu_or_skip():
    try:
        return tabor.solve(1.0, load=0.5, backend="gpu")
    except ValueError as e:
        if os.environ.get("TABOR_REQUIRE_GPU") == "1":
            pytest.fail(f"TABOR_REQUIRE_GPU=1 but no GPU adapter: {e}")
        pytest.skip(f"SKIPPED: no GPU adapter ({e}); set TABOR_REQUIRE_GPU=1 to make this a failure")


def test_gpu_results_follow_the_f32_contract():
    gpu_or_skip()
    r = rows("points.csv")
    lam = np.array([float(x["lambda"]) for x in r])
    load = np.array([float(x["Pbar"]) for x in r])
    s = tabor.solve(lam, load=load, backend="gpu", check=300)
    assert s.metadata["backend"] == "gpu" and s.metadata["precision"] == "f32"
    cc = s.metadata["cross_check"]
    assert cc["status_mismatches"] == 0 and cc["over_tolerance"] == 0
    far = np.array([load[i] - float(x["Pbar_pulloff_load"]) >= 1e-4 * abs(float(x["Pbar_pulloff_load"]))
                    for i, x in enumerate(r)])
    ref = np.array([float(x["A"]) for x in r])
    assert np.max(np.abs(s["A"][far] / ref[far] - 1)) <= 1e-5


def _nanite_fit(nanite, key, x, f, spring, params):
    """nanite's fit of the model `key` to the force `f` at the tip positions `x` (the same
    curve as approach and retract, under a cantilever of `spring` N/m): the fitted parameters."""
    n = len(x)
    data = {"force": np.concatenate([f, f[::-1]]),
            "height (measured)": np.concatenate([x, x[::-1]]),
            "tip position": np.concatenate([x, x[::-1]]),
            "segment": np.concatenate([np.zeros(n, bool), np.ones(n, bool)]),
            "time": np.linspace(0, 1, 2 * n)}
    meta = {"spring constant": spring, "imaging mode": "force-distance", "sensitivity": 1e-8,
            "duration": 1.0, "point count": 2 * n, "format": "synthetic",
            "path": "synthetic", "enum": 0}
    idnt = nanite.Indentation(data=data, metadata=meta)
    idnt.fit_model(model_key=key, params_initial=params, x_axis="tip position",
                   y_axis="force", segment="approach", weight_cp=False, range_x=(0, 0),
                   range_type="absolute")
    return idnt.fit_properties["params_fitted"]


def test_nanite_fits_a_synthetic_md_curve():
    """nanite's own fitting API with tabor's model recovers the parameters of a curve made
    with them."""
    try:
        import nanite
    except ImportError:
        if IN_CI:
            pytest.fail("nanite is not installed (.ci/run installs it)")
        pytest.skip("SKIPPED: nanite is not installed (pip install nanite)")
    import tabor.nanite_model as tm
    nanite.model.register_model(tm)
    try:
        truth = dict(E=1e9, w=0.05, z0=0.3e-9, R=20e-9, nu=0.5, contact_point=1e-9, baseline=0.0)
        lam, force_unit, _ = tm.scales(1e9, 0.05, 0.3e-9, 20e-9, 0.5)
        assert 0.5 < lam < 2.0  # the transition: neither JKR nor DMT
        x = np.linspace(4e-9, -2e-9, 600)
        f = tm.md_force(x, **truth)
        assert f.min() < -force_unit  # the adhesive well is in the curve
        p = tm.get_parameter_defaults()
        p["E"].set(3e8)
        p["w"].set(0.02)
        p["R"].set(20e-9)
        p["contact_point"].set(0.5e-9)
        fitted = _nanite_fit(nanite, "tabor_md", x, f, 40.0, p)
        for k in ("E", "w", "contact_point"):
            assert fitted[k].value == pytest.approx(truth[k], rel=1e-6), k
    finally:
        nanite.model.deregister_model(tm)


def test_the_nanite_tip_models_follow_the_tips_path():
    """The tip models (tabor_md_cone, pyramids, for_tip): a paraboloid given as a tip is the
    sphere model's force to rounding (below lambda_D: at 0.59, where the zone alone leads into
    contact, and at 0.8, where the zone's end lies beyond the range and both jump in); a cone's
    zone-alone branch is the closed form `P = -(pi lambda/2) C^2`, `D = (2/pi) C - 8 lambda C /
    (3 pi) - 2/(pi lambda)` (section 12, k_1 = pi/2); nanite fits a cone's curve back to 1e-6."""
    import tabor.nanite_model as tm
    import tabor._tabor as raw
    r_tip = 20e-9
    para = tm.for_tip({"shape": "power", "exponent": 2, "coefficient": 0.5 / r_tip}, "para")
    x = np.linspace(4e-9, -2e-9, 61)
    for z0, (lo, hi) in ((0.6e-9, (0.3, 0.655)), (0.44e-9, (0.655, 0.9))):
        truth = dict(E=1e9, w=0.05, z0=z0, nu=0.5, contact_point=1e-9, baseline=0.0)
        lam = tm.scales(1e9, 0.05, z0, r_tip, 0.5)[0]
        assert lo < lam < hi, lam
        sphere = tm.md_force(x, R=r_tip, **truth)
        tip = para.model_func(x, **truth)
        assert np.count_nonzero(sphere) > 30 and np.count_nonzero(sphere < 0) > 8
        assert np.max(np.abs(tip - sphere)) <= 1e-12 * np.max(np.abs(sphere)), lam
    # The cone's zone alone, against its closed form.
    scene = {"e_star_pa": 1e6, "work_of_adhesion_j_m2": 0.02, "s0_pa": 2e5,
             "tip": {"shape": "cone", "half_angle_deg": 70}}
    u = raw.tip_units(json.dumps(scene))
    c = np.linspace(0.05, 0.6, 12) * u["lambda"] ** -1
    d = 2 / np.pi * c - 8 * u["lambda"] * c / (3 * np.pi) - 2 / (np.pi * u["lambda"])
    r = raw.solve_tip(json.dumps(scene), np.full(12, u["lambda"]), d, "approach_in")
    zone = np.isnan(r["A"]) | (r["A"] == 0)
    assert zone.sum() >= 4, r
    assert np.allclose(r["C"][zone], c[zone], rtol=1e-12)
    assert np.allclose(r["load"][zone], -np.pi * u["lambda"] / 2 * c[zone] ** 2, rtol=1e-12)
    try:
        import nanite
    except ImportError:
        if IN_CI:
            pytest.fail("nanite is not installed (.ci/run installs it)")
        pytest.skip("SKIPPED: nanite is not installed (pip install nanite)")
    nanite.model.register_model(tm.cone)
    try:
        truth = dict(E=1e6, w=0.02, z0=2e-9, alpha=70.0, nu=0.5, contact_point=2e-7,
                     baseline=0.0)
        x = np.linspace(3e-7, -8e-7, 300)
        f = tm.cone.model_func(x, **truth)
        assert f.min() < 0 < f.max()
        p = tm.cone.get_parameter_defaults()
        p["E"].set(5e5)
        p["w"].set(0.01)
        p["z0"].set(2e-9)
        p["alpha"].set(70.0)
        p["contact_point"].set(1.9e-7)
        fitted = _nanite_fit(nanite, "tabor_md_cone", x, f, 1.0, p)
        for k in ("E", "w", "contact_point"):
            assert fitted[k].value == pytest.approx(truth[k], rel=1e-6), k
    finally:
        nanite.model.deregister_model(tm.cone)


def test_extended_domain_and_the_limits_method():
    # lambda = 1e-12 (the Python peer's DMT-limit case) is inside the exact solver's domain:
    # A within 1e-10 of DMT's at Pbar = 0 (MD differs by pi lambda A^2 in the load), method "md".
    s = tabor.solve([1e-12, 1e-30, 1e30, 1e-301], load=0.0)
    assert list(s["method"]) == ["md", "dmt_limit", "jkr_limit", ""]
    assert list(s["status"]) == ["ok", "ok", "ok", "invalid_input"]
    assert s["A"][0] == pytest.approx(2 ** (1 / 3), rel=1e-10)
    assert s["A"][1] == pytest.approx(2 ** (1 / 3), rel=1e-15)
    assert s["A"][2] == pytest.approx(6 ** (1 / 3), rel=1e-15)
    assert "1e-300..1e-26 (DMT limit)" in s["message"][3]
    # Too close to the DMT pull-off for the limit: not certified, with its reason.
    s = tabor.solve(1e-30, load=[-2.0, -1.0])
    assert list(s["status"]) == ["invalid_input", "ok"]
    assert "DMT limit" in s["message"][0]
    with pytest.raises(ValueError):
        tabor.solve(1e-301, load=0.0)
