"""Bad input is refused with a clear message, reasons are given per point, files are written
only where asked, Ctrl-C stops a long solve and a large solve's memory stays near its results."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import tabor


# --- bad input ---------------------------------------------------------------------------------

@pytest.mark.parametrize("kw, needle", [
    (dict(lam=-1.0, load=1.0), "lambda = -1 is outside the supported domain 1e-300..1e-26 (DMT limit), 1e-26..1e26 (exact), 1e26..1e150 (JKR limit)"),
    (dict(lam=float("nan"), load=1.0), "lambda = nan"),
    (dict(lam=1.0, load=float("inf")), "load = inf is outside the supported domain"),
    (dict(lam=1.0, approach=-1e9), "approach = -1e+09 is outside the supported domain -1e8..1e8"),
    (dict(lam=1.0, radius=0.0), "radius = 0 is outside the supported domain (0, 1e4]"),
])
def test_a_bad_scalar_raises_instead_of_returning_nan(kw, needle):
    lam = kw.pop("lam")
    with pytest.raises(ValueError) as e:
        tabor.solve(lam, **kw)
    assert needle in str(e.value)


def test_arrays_give_a_reason_per_point():
    s = tabor.solve([1.0, -1.0, 1.0, 1.0], load=[0.5, 1.0, 1e13, -1.7])
    assert list(s["status"]) == ["ok", "invalid_input", "invalid_input", "no_contact"]
    m = s["message"]
    assert m.shape == (4,) and m[0] == ""
    assert m[1] == "lambda = -1 is outside the supported domain 1e-300..1e-26 (DMT limit), 1e-26..1e26 (exact), 1e26..1e150 (JKR limit)"
    assert m[2] == "load = 1e+13 is outside the supported domain -1e12..1e12"
    assert "pull-off" in m[3]
    # Shaped as the broadcast result; the valid point's value is the exact one.
    s = tabor.solve([[1.0], [1e200]], approach=[0.0, 1.0])
    assert s["message"].shape == (2, 2) and (s["message"][1] != "").all()
    assert s["message"][1, 0].startswith("lambda = 1e+200")
    assert (s["message"][0] == "").all()
    assert s["A"][0, 0] == tabor.solve(1.0, approach=0.0)["A"]


@pytest.mark.parametrize("lam, needle", [
    (1.0 + 0.5j, "complex"),
    (np.array([1.0, 2.0], dtype=complex), "complex"),
    (np.datetime64("2020-01-01"), "datetime64"),
    (np.array([1, 2], dtype="timedelta64[s]"), "timedelta64"),
    ("1.0", "strings"),
    (np.array(["1.0"]), "strings"),
    (np.ma.array([1.0, 2.0], mask=[False, True]), "masked"),
    (np.array([1.0, None], dtype=object), "NoneType"),
])
def test_what_is_not_real_numbers_raises_type_error(lam, needle):
    with pytest.raises(TypeError) as e:
        tabor.solve(lam, load=1.0)
    assert needle in str(e.value) and "lam" in str(e.value)
    with pytest.raises(TypeError):
        tabor.solve(1.0, load=lam)


def test_non_finite_si_values_are_named_not_a_json_parse_error():
    scene = {"e_star_pa": 1e9, "radius_m": float("nan"), "work_of_adhesion_j_m2": 0.05,
             "z0_m": 3e-10, "loads_n": [1e-6]}
    with pytest.raises(ValueError) as e:
        tabor.Scene(scene)
    assert "radius_m is not a finite number" in str(e.value) and "line" not in str(e.value)
    with pytest.raises(ValueError) as e:
        tabor.infer_pulloff(1e-6, float("nan"), 1e9)
    assert str(e.value) == "radius_m = nan: give a finite number"
    with pytest.raises(ValueError) as e:
        tabor.fit_pairs([1e-6, 2e-6], [1e-6, 1.2e-6], radius_m=float("inf"))
    assert "radius_m = inf" in str(e.value)
    h = np.linspace(1e-7, -1e-7, 50)
    # A bad option of every curve is refused before any fit, named as the keyword (the library's
    # check, the command line's words).
    with pytest.raises(ValueError) as e:
        tabor.fit_curve(h, h, np.ones(50), radius_m=float("nan"), spring_n_m=1.0)
    assert str(e.value) == "radius_m: tip radius NaN m: give a positive radius in metres"
    with pytest.raises(TypeError):
        tabor.fit_curve(h, h, np.ones(50), radius_m=1e-8 + 1j, spring_n_m=1.0)


@pytest.mark.parametrize("call, message", [
    (lambda: tabor.adhesion_map(nx=1, ny=8, backend="cpu"), "nx and ny must be in 2..=16384"),
    (lambda: tabor.adhesion_map(nx=8, ny=8, lambda_min=10, lambda_max=1, backend="cpu"),
     "lambda_min must be below lambda_max, got 10 and 1"),
    (lambda: tabor.adhesion_map(nx=8, ny=8, load_min=-1.0, backend="cpu"),
     "load_axis=\"linear\""),
    (lambda: tabor.adhesion_map(nx=8, ny=8, tolerance=2.0, backend="cpu"),
     "tolerance must be in (0, 1)"),
    (lambda: tabor.profile(1.0, load=1.0, points=3), "points 3 is out of range"),
])
def test_messages_name_the_python_arguments_not_command_line_flags(call, message):
    with pytest.raises(ValueError) as e:
        call()
    assert message in str(e.value) and "--" not in str(e.value)


def test_figure_options_name_the_python_arguments(tmp_path):
    m = tabor.adhesion_map(nx=8, ny=8, backend="cpu")
    with pytest.raises(ValueError) as e:
        m.save(tmp_path / "m.png", width_mm=10)
    assert str(e.value).startswith("width_mm 10 is outside 40..600")
    assert not (tmp_path / "m.png").exists()


# --- files -------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["m.jpg", "m", "m.npy", "null"])
def test_an_unknown_extension_is_refused_and_writes_nothing(tmp_path, name):
    m = tabor.adhesion_map(nx=8, ny=8, backend="cpu")
    with pytest.raises(ValueError) as e:
        m.save(tmp_path / name)
    assert ".png, .svg, .pdf or .json" in str(e.value) and "npy=True" in str(e.value)
    assert list(tmp_path.iterdir()) == []


def test_a_device_path_is_refused_before_anything_is_written(tmp_path):
    # save("/dev/null") used to write /dev/null_lambda.npy, ...: the same check, on a link to it
    # inside tmp_path so that a regression cannot litter /dev.
    (tmp_path / "null").symlink_to(os.devnull)
    m = tabor.adhesion_map(nx=8, ny=8, backend="cpu")
    with pytest.raises(ValueError):
        m.save(tmp_path / "null")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["null"]


def test_npy_files_only_with_the_explicit_argument(tmp_path):
    m = tabor.adhesion_map(nx=8, ny=6, backend="cpu")
    m.save(tmp_path / "p", npy=True)
    lam = np.load(tmp_path / "p_lambda.npy")
    assert np.array_equal(lam, m.lam)
    assert np.array_equal(np.load(tmp_path / "p_A.npy"), m.A, equal_nan=True)


# --- curve ids ---------------------------------------------------------------------------------

def _curve():
    """A retract curve (contact then a flat line): enough for fit_curves to run."""
    z = np.linspace(20e-9, -5e-9, 200)
    return z, np.where(z > 0, 0.0, -2.0 * z), np.ones(200, dtype=np.int64)


def test_object_curve_ids_of_mixed_types_are_kept_in_order_of_first_appearance():
    h, f, s = _curve()
    ids = np.array(["b"] * 200 + [3] * 200, dtype=object)
    out = tabor.fit_curves(np.concatenate([h, h]), np.concatenate([f, f]),
                           np.concatenate([s, s]), curve=ids, radius_m=20e-9, spring_n_m=2.0)
    assert [r["curve"] for r in out] == ["b", 3]
    unhashable = np.empty(200, dtype=object)
    for i in range(200):
        unhashable[i] = [1]
    with pytest.raises(TypeError) as e:
        tabor.fit_curves(h, f, s, curve=unhashable, radius_m=20e-9, spring_n_m=2.0)
    assert "hashable" in str(e.value)


# --- Ctrl-C and memory -------------------------------------------------------------------------

@pytest.mark.parametrize("given", ["load", "radius"])
def test_ctrl_c_interrupts_a_long_solve_within_a_second_or_two(given):
    code = textwrap.dedent(f"""
        import sys, time, numpy as np, tabor
        x = np.linspace(0.01, 5.0, 30_000_000)
        print("start", flush=True)
        t = time.monotonic()
        try:
            tabor.solve(1.0, {given}=x)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic() - t, flush=True)
            sys.exit(3)
        print("finished", time.monotonic() - t, flush=True)
    """)
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "start"
    time.sleep(1.0)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)
    waited = time.monotonic() - sent
    assert p.returncode == 3, out
    assert waited < 2.5, (waited, out)


@pytest.mark.parametrize("call", [
    "tabor.rough_map(nx=1024, ny=1024, check=0)",
    "tabor.rough(1, .63, -1.89, points=10000)",
    "tabor.rough_ensemble(1.0, np.linspace(-2, 2, 400_000), np.linspace(-1, 3, 2000))",
    "tabor.rough_pulloff(lambdas=[0.01, 0.1, 1.0, 10.0, 100.0, 1000.0], points=400)",
    "tabor.rough_asperities(np.random.default_rng(1).normal(0, 5e-9, 200_000), "
    "np.full(200_000, 2e-6), preset='mems-polysilicon', points=4000, summits='exact')",
])
def test_ctrl_c_interrupts_every_long_call_in_a_fresh_process(call):
    # Once a PanicException out of rust-numpy (the first array of the process made while a
    # Ctrl-C was pending), not caught by `except Exception`; now KeyboardInterrupt at once, and
    # the library's work stops: the next call in the process runs and gives its numbers.
    code = textwrap.dedent(f"""
        import os, signal, sys, threading, time, numpy as np, tabor
        sent = []
        def interrupt():
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)
        threading.Timer(1.0, interrupt).start()
        try:
            {call}
        except KeyboardInterrupt:
            print("interrupted", time.monotonic() - sent[0], flush=True)
            r = tabor.rough(1.0, 0.63, -1.89, points=20)
            print("then", r["pulloff_load"] < 0, flush=True)
            sys.exit(3)
        print("finished", time.monotonic() - sent[0], flush=True)
    """)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert p.returncode == 3, (p.stdout, p.stderr[-2000:])
    lines = p.stdout.split("\n")
    waited = float(lines[0].split()[1])
    assert waited < 2.0, (waited, p.stdout)
    assert lines[1] == "then True", p.stdout
    assert "panicked" not in p.stderr and "Panic" not in p.stderr, p.stderr


def test_chunks_join_without_a_seam():
    # More than one chunk (262144 points), several lambdas: each point as solved alone.
    n = 262144 + 1000
    lam = np.where(np.arange(n) % 3 == 0, 0.3, 3.0)
    load = np.linspace(-0.5, 4.0, n)
    s = tabor.solve(lam, load=load)
    r = tabor.solve(lam, radius=np.linspace(0.1, 3.0, n))
    for i in (0, 262143, 262144, 262145, n - 1):
        one = tabor.solve(lam[i], load=load[i])
        # Equal to the solver tolerance: a large group starts from a dense table, one point not.
        assert s["A"][i] == pytest.approx(one["A"], rel=1e-13)
        assert s["approach"][i] == pytest.approx(one["approach"], rel=1e-13, abs=1e-13)
        one = tabor.solve(lam[i], radius=r["A"][i])
        assert r["load"][i] == one["load"] and r["load_stable"][i] == one["load_stable"]
    assert r["load_stable"].dtype == bool and r["load_stable"].shape == (n,)


@pytest.mark.parametrize("given, n", [("load", 10_000_000), ("radius", 2_000_000)])
def test_a_large_solve_peaks_near_the_size_of_its_results(given, n):
    code = textwrap.dedent(f"""
        import json, resource, numpy as np, tabor
        n = {n}
        x = np.linspace(0.01, 5.0, n)
        tabor.solve(1.0, {given}=[1.0, 2.0])  # the library and the thread pool loaded
        base = int(open("/proc/self/statm").read().split()[1]) * resource.getpagesize()
        r = tabor.solve(1.0, {given}=x)
        # The process's own high-water mark: getrusage's ru_maxrss keeps the forking parent's
        # (Linux carries it across exec), which grows with the test session.
        peak = next(int(l.split()[1]) * 1024 for l in open("/proc/self/status")
                    if l.startswith("VmHWM:"))
        out = sum(v.nbytes for v in r.values())
        print(json.dumps({{"grown": peak - base, "out": out,
                          "ok": int((r["status"] == "ok").sum())}}))
    """)
    r = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                  check=True, timeout=300).stdout)
    assert r["ok"] == n
    assert r["grown"] <= 1.5 * r["out"], r
