"""Rough surfaces from Python: the same numbers as the command line, and explicit ensembles."""

import json
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
        for k in ["separation", "load", "contact_fraction", "noncontact_fraction"]:
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
