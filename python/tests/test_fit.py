"""The force-curve fitter from Python: the same answers as `tabor fit`, and real measured curves
(the JPK sample files afmformats ships in its source distribution, fetched from PyPI)."""
import json
import os
import pathlib
import subprocess
import sys
import tarfile

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]
TABOR = ROOT / "target" / "release" / "tabor"
CURVE = ROOT / "gallery" / "fit_curve.csv"


def test_arrays_give_what_the_command_line_gives(tmp_path):
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    r = tabor.fit_curve(rows["height_m"], rows["force_n"], rows["segment"],
                        radius_m=20e-9, spring_n_m=40.0, poisson=0.3)
    out = subprocess.run([str(TABOR), "fit", "-i", str(CURVE), "--radius", "20e-9",
                          "--spring-n-m", "40", "--poisson", "0.3"],
                         capture_output=True, check=True)
    cli = json.loads(out.stdout)["curves"][0]
    assert r["status"] == "ok"
    for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "rms_residual_n",
              "contact_point_m", "youngs_modulus_pa"):
        assert r[k] == pytest.approx(cli[k], rel=1e-12), k
    # The synthetic curve was made with E* = 2 GPa (see examples/synthetic_curves.rs).
    assert abs(r["e_star_pa"] - 2e9) < 3 * r["e_star_pa_stderr"]
    # The profile-likelihood intervals, as the command line gives them; an open end is None.
    for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "contact_point_m", "z0_m"):
        for level in ("68", "95"):
            key = f"{k}_interval_{level}"
            assert [a is None for a in r[key]] == [b is None for b in cli[key]], key
            assert [a for a in r[key] if a is not None] == pytest.approx(
                [b for b in cli[key] if b is not None], rel=1e-9), key
            lo, hi = r[key]
            assert (lo is None or lo <= r[k]) and (hi is None or r[k] <= hi), key
    lo, hi = r["e_star_pa_interval_95"]
    assert lo <= 2e9 <= hi
    assert r["lambda_determined"] == (None not in r["lambda_interval_95"])
    assert r["youngs_modulus_pa"] == pytest.approx(r["e_star_pa"] * (1 - 0.09))


def test_many_curves_and_bad_ones_in_one_call():
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    h, f, s = rows["height_m"], rows["force_n"], rows["segment"]
    bad = f.copy()
    bad[5] = np.nan
    out = tabor.fit_curves(np.concatenate([h, h]), np.concatenate([f, bad]),
                           np.concatenate([s, s]), curve=["a"] * len(h) + ["b"] * len(h),
                           radius_m=20e-9, spring_n_m=40.0)
    assert [r["curve"] for r in out] == ["a", "b"]
    assert out[0]["status"] == "ok"
    assert out[1]["status"] == "invalid_input" and "non-finite" in out[1]["message"]
    with pytest.raises(ValueError, match="segment"):
        tabor.fit_curve(h, f, np.array(["up"] * len(h)), radius_m=20e-9, spring_n_m=2.0)


def _afmformats_samples(tmp_path):
    """The JPK sample curves from afmformats' source distribution on PyPI."""
    if os.environ.get("CI"):
        import afmformats  # installed by tests/run_all.sh: a failure, not a skip
    else:
        afmformats = pytest.importorskip("afmformats")
    dl = subprocess.run([sys.executable, "-m", "pip", "download", "--no-binary", ":all:",
                         "--no-deps", "afmformats==0.18.7", "-d", str(tmp_path), "-q"],
                        capture_output=True, text=True)
    if dl.returncode != 0:
        if os.environ.get("CI"):
            pytest.fail(f"cannot fetch the afmformats sdist: {dl.stderr}")
        pytest.skip(f"cannot fetch the afmformats sdist (offline?): {dl.stderr.strip()[:200]}")
    sdist = next(tmp_path.glob("afmformats-*.tar.gz"))
    names = ["fmt-jpk-fd_spot3-0192.jpk-force",
             "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force"]
    with tarfile.open(sdist) as t:
        members = [m for m in t.getmembers() if m.name.split("/")[-1] in names]
        t.extractall(tmp_path, members=members)
    return afmformats, [next(tmp_path.rglob(n)) for n in names]


def test_real_jpk_curves_with_adhesion_are_fitted(tmp_path):
    afmformats, paths = _afmformats_samples(tmp_path)
    for p in paths:
        data = afmformats.load_data(p)
        (r,) = tabor.fit_afmformats(data[:1], radius_m=2.5e-6)
        print(p.name, {k: r[k] for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda",
                                          "rms_residual_n", "pulloff_force_measured_n",
                                          "adequate_model")})
        assert r["status"] == "ok", r["message"]
        # Soft (cell-like) samples with nanonewton adhesion: plausible, not tight, ranges.
        assert 1e2 < r["e_star_pa"] < 1e7
        assert 1e-7 < r["work_of_adhesion_j_m2"] < 1e-2
        assert 0.3e-9 < r["pulloff_force_measured_n"] < 5e-9
        force_range = float(np.ptp(data[0]["force"]))
        assert r["rms_residual_n"] < 0.05 * force_range
        assert r["adequate_model"] in ("hertz", "dmt", "jkr", "md")


def test_an_npz_file_reads_as_the_csv_does(tmp_path):
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    seg = np.where(rows["segment"] == "retract", 1, 0).astype(np.int64)
    npz = tmp_path / "curve.npz"
    np.savez(npz, segment=seg, height_m=rows["height_m"].astype(float),
             force_n=rows["force_n"].astype(float))
    run = lambda path: json.loads(subprocess.run(
        [str(TABOR), "fit", "-i", str(path), "--radius", "20e-9", "--spring-n-m", "40"],
        capture_output=True, check=True).stdout)["curves"][0]
    a, b = run(npz), run(CURVE)
    assert a["status"] == "ok"
    assert a["e_star_pa"] == b["e_star_pa"] and a["lambda"] == b["lambda"]
