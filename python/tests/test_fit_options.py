"""fit_curves makes the option checks `tabor fit` makes (one check, in the library), refuses
segment values other than 0, 1 and -1 (a dwell), and gives a curve that once panicked its own status."""
import pathlib

import numpy as np
import pytest

import tabor

ROOT = pathlib.Path(__file__).resolve().parents[2]
CURVE = ROOT / "gallery" / "fit_curve.csv"


def rows():
    r = np.genfromtxt(CURVE, delimiter=",", names=True, dtype=None, encoding="utf-8")
    return r["height_m"], r["force_n"], r["segment"]


@pytest.mark.parametrize("option, value, says", [
    ("poisson", 5.0, "poisson: Poisson ratio 5 must be in (-1, 0.5]"),
    ("poisson", -1.0, "poisson: Poisson ratio -1 must be"),
    ("tolerance", 5.0, "tolerance: adequate-model tolerance 5 must be"),
    ("tolerance", -1.0, "tolerance: adequate-model tolerance -1 must be"),
    ("tolerance", float("nan"), "tolerance: adequate-model tolerance NaN must be"),
    ("z0_m", 1.0, "z0_m: Lennard-Jones range z0 1 m must be between 1e-12 and 1e-6 m"),
    ("z0_m", 1e-30, "z0_m: Lennard-Jones range z0 1e-30 m must be between"),
    ("fit_segment", "bogus", 'fit_segment="bogus": use "retract", "approach" or "both"'),
])
def test_options_out_of_range_are_refused_as_the_command_line_refuses_them(option, value, says):
    h, f, s = rows()
    with pytest.raises(ValueError) as e:
        tabor.fit_curves(h, f, s, radius_m=20e-9, spring_n_m=40.0, **{option: value})
    assert says in str(e.value)
    assert "--" not in str(e.value)


@pytest.mark.parametrize("value", [0.5, 1.5, 2, -2])  # -1 marks a dwell
def test_segment_values_other_than_0_1_and_dwell_are_refused(value):
    h, f, s = rows()
    seg = np.where(np.asarray(s) == "retract", 1.0, 0.0)
    seg[3] = value
    with pytest.raises(ValueError) as e:
        tabor.fit_curves(h, f, seg, radius_m=20e-9, spring_n_m=40.0)
    assert "segment value" in str(e.value) and "index 3" in str(e.value)


def test_a_curve_of_huge_forces_gets_its_status_and_the_other_is_fitted():
    h, f, s = rows()
    bad = f.copy()
    bad[len(bad) // 2::3] = 1e200
    bad[len(bad) // 2 + 1::3] = -1e200
    out = tabor.fit_curves(np.concatenate([h, h]), np.concatenate([f, bad]),
                           np.concatenate([s, s]),
                           curve=np.repeat(["good", "bad"], len(h)),
                           radius_m=20e-9, spring_n_m=40.0)
    by = {r["curve"]: r for r in out}
    assert by["good"]["status"] == "ok"
    assert by["bad"]["status"] != "ok" and by["bad"]["e_star_pa"] is None
