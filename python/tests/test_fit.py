"""The force-curve fitter from Python: the same answers as `tabor fit`, and real measured curves
(the JPK sample files afmformats ships in its source distribution, fetched from PyPI)."""
import json
import os
import pathlib
import subprocess

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


def _misaligned(a):
    """a's values in a C-contiguous array whose buffer starts one byte off its alignment, as a
    pickled array can come back (Dask's workers)."""
    a = np.asarray(a)
    raw = np.zeros(a.nbytes + 1, dtype=np.uint8)[1:]
    out = raw.view(a.dtype).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned and out.flags.c_contiguous
    return out


def test_misaligned_arrays_fit_as_aligned_ones():
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    h, f = np.asarray(rows["height_m"], float), np.asarray(rows["force_n"], float)
    seg = (rows["segment"] == "retract").astype(np.int64)
    kw = dict(radius_m=20e-9, spring_n_m=40.0)
    want = tabor.fit_curve(h, f, seg, **kw)
    got = tabor.fit_curve(_misaligned(h), _misaligned(f), _misaligned(seg), **kw)
    assert got["status"] == want["status"] == "ok"
    assert got["e_star_pa"] == want["e_star_pa"]
    assert got["lambda"] == want["lambda"]
    # Without curve= a result has no id (not the library's internal "0").
    assert want["curve"] is None


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


def test_advice_to_fit_the_other_segment_names_the_argument():
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    h, f, s = rows["height_m"], rows["force_n"], rows["segment"]
    approach = s == "approach"
    r = tabor.fit_curve(h[approach], f[approach], np.zeros(approach.sum(), np.int64),
                        radius_m=20e-9, spring_n_m=40.0)
    assert r["status"] == "invalid_input"
    assert r["message"] == ('no retract segment: fit the approach segment instead '
                            '(fit_segment="approach"), or check the segment column '
                            '(approach/retract or 0/1)')
    r = tabor.fit_curve(h[~approach], f[~approach], np.ones((~approach).sum(), np.int64),
                        radius_m=20e-9, spring_n_m=40.0, fit_segment="approach")
    assert r["message"] == ('no approach segment: fit the retract segment instead '
                            '(fit_segment="retract"), or check the segment column')


def _afmformats_samples(data):
    """The JPK sample curves from afmformats' source distribution on PyPI (`data`: the
    afmformats_data fixture)."""
    import afmformats
    names = ["fmt-jpk-fd_spot3-0192.jpk-force",
             "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force"]
    return afmformats, [data / n for n in names]


def _load(afmformats, path):
    """afmformats' curves of a file, or None where afmformats cannot load it (its errors derive
    from BaseException, and it logs a traceback)."""
    import logging
    logging.disable(logging.CRITICAL)
    try:
        return afmformats.load_data(path)
    except (Exception, afmformats.errors.MissingMetaDataError):
        return None
    finally:
        logging.disable(logging.NOTSET)


def test_every_afmformats_sample_fits_or_gets_its_own_status(afmformats_data):
    """Every sample force curve afmformats 0.18.7 ships: a dwell (stress relaxation, creep) is
    left out, a one-segment file is split at its turn, a missing spring constant is one error
    naming spring_n_m, and no file stops the call; each fit is sane."""
    import afmformats
    data = afmformats_data
    fitted, statuses, last = 0, {}, {}
    for p in sorted(data.iterdir()):
        ds = _load(afmformats, p)
        if not ds or ds[0].metadata.get("imaging mode") not in (
                "force-distance", "creep-compliance", "stress-relaxation"):
            continue
        ds = ds[:4]
        spring = None
        if ds[0].metadata.get("spring constant") is None:
            with pytest.raises(ValueError, match="spring_n_m="):
                tabor.fit_afmformats(ds, radius_m=2.5e-6)
            spring = 0.1
        for r in tabor.fit_afmformats(ds, radius_m=2.5e-6, spring_n_m=spring):
            statuses[p.name], last[p.name] = r["status"], r
            assert r["status"] in ("ok", "no_contact", "not_converged", "invalid_input"), r
            # No contact only where no segment of the curve shows any.
            if r["status"] == "no_contact":
                assert "no segment of the curve" in r["message"], (p.name, r["message"])
            assert r["message"]
            if r["status"] != "ok":
                continue
            fitted += 1
            for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda"):
                v = r[k]
                assert np.isfinite(v) and v > 0, (p.name, k, v)
                # An open end is None.
                assert all(e is None or np.isfinite(e) for e in r[f"{k}_interval_95"])
                lo68, hi68 = (np.nan if e is None else e for e in r[f"{k}_interval_68"])
                lo95, hi95 = (np.nan if e is None else e for e in r[f"{k}_interval_95"])
                # The estimate inside its intervals, the 95% one holding the 68% one.
                assert (np.isnan(lo95) or lo95 <= v) and (np.isnan(hi95) or v <= hi95), (p.name, k)
                assert np.isnan(lo95) or np.isnan(lo68) or lo95 <= lo68, (p.name, k)
                assert np.isnan(hi95) or np.isnan(hi68) or hi68 <= hi95, (p.name, k)
            assert 10 <= r["e_star_pa"] <= 1e12 and r["work_of_adhesion_j_m2"] <= 10
    print(statuses)
    # The files that once raised: a dwell and a single segment now fit, with a warning.
    assert statuses["fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force"] == "ok"
    assert statuses["fmt-igor-fd_SiN_FD_plot.ibw"] == "ok"
    _assert_dwells_reported(last)
    assert fitted >= 15
    (r,) = tabor.fit_afmformats(afmformats.load_data(data / "fmt-igor-fd_U3_3_p10004.ibw"),
                                radius_m=2.5e-6)
    assert any("split at the lowest height" in w for w in r["warnings"]), r["warnings"]
    (r,) = tabor.fit_afmformats(
        afmformats.load_data(data / "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force"),
        radius_m=2.5e-6)
    assert any("a dwell, left out" in w for w in r["warnings"]), r["warnings"]
    # A soft cell-like sample that leaves the tip gradually (tethers): the Maugis-Dugdale path
    # follows the tail along a long Dugdale zone, lambda small and determined, and the warning
    # says the zone is no surface force.
    (r,) = tabor.fit_afmformats(afmformats.load_data(data / "fmt-jpk-fd_spot3-0192.jpk-force"),
                                radius_m=2.5e-6)
    lo, hi = r["lambda_interval_95"]
    assert r["lambda_determined"] is True and hi < 0.1, r["lambda_interval_95"]
    assert r["z0_m"] > 1e-8
    assert any("beyond the range of surface forces" in w for w in r["warnings"]), r["warnings"]
    # A soft tissue, and the relaxed cell's approach, whose misfit falls as a Dugdale zone longer
    # than the curve and the force offset grow together (the zone's pull trading against the
    # offset): the offset stops at the largest force measured, and w, z0 and lambda are not
    # determined.
    for name in ("fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force", "fmt-jpk-sr_cell1-0008.jpk-force"):
        r = last[name]
        assert r["lambda_determined"] is False, (name, r["lambda_bound"])
        assert any("force offset as large as the largest force" in w for w in r["warnings"]), (name, r)
        assert r["work_of_adhesion_j_m2_interval_95"][1] is None, name


def _assert_dwells_reported(last):
    """The dwell files' results: stress relaxation fits its approach (the retract after the
    relaxed force is no loading curve), creep its retract; each reports its dwell."""
    r = last["fmt-jpk-sr_cell1-0008.jpk-force"]
    assert r["status"] == "ok", r["message"]
    assert r["message"].startswith(
        "ok: the approach was fitted, not the retract: the retract follows a dwell "
        "(points 2304..9983) in which the force relaxed from "), r["message"]
    assert r["message"][len("ok: "):] in r["warnings"]
    d = r["dwell"]
    assert d["relaxed"] is True and (d["first_point"], d["last_point"]) == (2304, 9983)
    # 288 nN above the baseline relaxing to 82 nN (71%) at a held base (it moves by 9 nm):
    # the tip advances by the cantilever's unbending, (start - end) / k with k = 1.0677 N/m.
    assert d["force_start_n"] == pytest.approx(2.88e-7, rel=0.05)
    assert 0.6 < d["relaxation"] < 0.8
    assert d["relaxation"] == pytest.approx(1 - d["force_end_n"] / d["force_start_n"])
    assert abs(d["base_advance_m"]) < 0.1 * d["indentation_creep_m"]
    assert d["indentation_creep_m"] == pytest.approx(
        d["base_advance_m"] + (d["force_start_n"] - d["force_end_n"]) / 1.0677, rel=1e-9)
    assert 1e2 < r["e_star_pa"] < 1e5
    # Creep compliance: the force held (relaxing by under 2%), the base advancing as the
    # indentation creeps; the retract fitted as asked.
    for name, creep in (("fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force", 1.57e-6),
                        ("fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", 2.36e-7)):
        r = last[name]
        assert r["status"] == "ok" and r["message"] == "ok", (name, r["message"])
        d = r["dwell"]
        assert d["relaxed"] is False and d["relaxation"] < 0.02, (name, d)
        assert d["indentation_creep_m"] == pytest.approx(creep, rel=0.05), (name, d)
        assert d["indentation_creep_m"] == pytest.approx(d["base_advance_m"], rel=0.02), (name, d)
        assert any("a dwell, left out" in w for w in r["warnings"]), r["warnings"]
    # Files without a dwell report none.
    assert "dwell" not in last["fmt-jpk-fd_spot3-0192.jpk-force"]


def test_a_dwell_marked_in_arrays_is_reported_and_a_relaxed_one_fits_the_approach():
    """Segment -1 (or "dwell") marks a dwell's points: the base held at the turn while the force
    relaxes to 40% of its start; the approach is fitted, as fit_segment="approach" fits it."""
    rows = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    h, f = rows["height_m"].astype(float), rows["force_n"].astype(float)
    s = np.where(rows["segment"] == "retract", 1, 0)
    turn = int(np.argmax(s == 1))
    fd = f[turn - 1] * np.r_[np.ones(5), np.linspace(1.0, 0.4, 40), np.full(5, 0.4)]
    hh = np.r_[h[:turn], np.full(50, h[turn - 1]), h[turn:]]
    ff = np.r_[f[:turn], fd, f[turn:]]
    ss = np.r_[s[:turn], np.full(50, -1), s[turn:]]
    opts = dict(radius_m=20e-9, spring_n_m=40.0)
    r = tabor.fit_curve(hh, ff, ss, **opts)
    a = tabor.fit_curve(h, f, s, fit_segment="approach", **opts)
    assert r["status"] == "ok" and r["message"].startswith("ok: the approach was fitted"), r
    assert r["e_star_pa"] == pytest.approx(a["e_star_pa"], rel=1e-10)
    d = r["dwell"]
    assert (d["first_point"], d["last_point"], d["relaxed"]) == (turn, turn + 49, True)
    # The baseline's offset (a few pN against nN) aside, 60% relaxed.
    assert d["relaxation"] == pytest.approx(0.6, rel=1e-2)
    names = np.where(ss == -1, "dwell", np.where(ss == 1, "retract", "approach"))
    assert tabor.fit_curve(hh, ff, names, **opts)["dwell"] == d
    assert "dwell" not in tabor.fit_curve(h, f, s, **opts)


def test_real_jpk_curves_with_adhesion_are_fitted(afmformats_data):
    afmformats, paths = _afmformats_samples(afmformats_data)
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
