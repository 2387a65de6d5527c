"""One check, in the library, for both front ends: the same bad value is refused by the command
line (exit 1, one line) and by Python (ValueError) in the same words, up to the names of the
command-line flags."""

import re
import subprocess

import numpy as np
import pytest

import tabor
from test_tabor import tabor_bin

# A small curve for the fit's options (refused before any fit, whatever the curve).
_H = np.linspace(0.0, 1e-8, 40)
_F = np.zeros(40)
_S = np.r_[np.zeros(20), np.ones(20)]
_CURVE = "height_m,force_n,segment\n" + "".join(
    f"{h!r},{f!r},{int(s)}\n" for h, f, s in zip(_H.tolist(), _F.tolist(), _S.tolist()))
_FIT = ["fit", "-i", "-", "--radius", "2e-8", "--spring-n-m"]


def _fit(**kw):
    return lambda: tabor.fit_curves(_H, _F, _S, radius_m=2e-8, **kw)


CASES = [
    (["cycle", "--lambda", "1", "--control", "spring", "--stiffness", "-1"],
     lambda: tabor.cycle(1.0, "spring", -1.0), "spring stiffness"),
    (["cycle", "--lambda", "1", "--max-load", "1e20"],
     lambda: tabor.cycle(1.0, max_load=1e20), "largest load"),
    (["map", "--nx", "0", "--backend", "cpu"],
     lambda: tabor.adhesion_map(nx=0, backend="cpu"), "nx and ny"),
    (["rough", "--lambda", "1", "--sigma", "-1", "--min-separation", "-1"],
     lambda: tabor.rough(1.0, -1.0, -1.0), "sigma"),
    (["rough-map", "--nx", "1"],
     lambda: tabor.rough_map(nx=1), "nx and ny"),
    (["profile", "--lambda", "-1", "--load", "0.5"],
     lambda: tabor.profile(-1.0, load=0.5), "lambda = -1"),
    (["profile", "--lambda", "1", "--load", "0.5", "--points", "1"],
     lambda: tabor.profile(1.0, load=0.5, points=1), "sampling radii"),
    (["profile", "--lambda", "1", "--load", "0.5", "--stress-ratio", "0.3"],
     lambda: tabor.profile(1.0, load=0.5, stress_ratio=0.3), "together"),
    (["pulloff", "--lambda", "1", "--stress-ratio", "-0.2", "--range-ratio", "2"],
     lambda: tabor.pulloff(1.0, stress_ratio=-0.2, range_ratio=2.0), "stress ratio"),
    (["cycle", "--lambda", "1", "--range-ratio", "2"],
     lambda: tabor.cycle(1.0, range_ratio=2.0), "or neither"),
    (["infer", "--pulloff", "1e-8", "--radius", "-1", "--e-star", "1e9"],
     lambda: tabor.infer_pulloff(1e-8, -1.0, 1e9), "radius_m"),
    (["infer", "--pulloff", "1e-8", "--radius", "2e-8", "--e-star", "1e9",
      "--relative-humidity", "1.5"],
     lambda: tabor.infer_pulloff(1e-8, 2e-8, 1e9, relative_humidity=1.5), "relative_humidity"),
    (["rough-pulloff", "--points", "1"],
     lambda: tabor.rough_pulloff(points=1), "roughnesses"),
    ([*_FIT, "2", "--tolerance", "5"], _fit(spring_n_m=2.0, tolerance=5.0), "tolerance"),
    ([*_FIT, "2", "--poisson", "0.9"], _fit(spring_n_m=2.0, poisson=0.9), "Poisson ratio"),
    ([*_FIT, "-2"], _fit(spring_n_m=-2.0), "spring constant -2"),
]


def _plain(msg):
    """A message with its command-line flags written as names: `--nx` -> `nx`."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), msg).strip()


@pytest.mark.parametrize("args, call, what", CASES, ids=[c[2] for c in CASES])
def test_the_same_bad_value_gets_the_same_refusal(args, call, what, tmp_path):
    cli = subprocess.run([tabor_bin(), *args], capture_output=True, text=True, cwd=tmp_path,
                         env={"TABOR_BACKEND": "cpu", "PATH": "/usr/bin:/bin"}, timeout=120,
                         input=_CURVE if "-" in args else None)
    assert cli.returncode == 1, cli.stderr
    lines = cli.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), cli.stderr
    with pytest.raises(ValueError) as e:
        call()
    assert what in str(e.value)
    assert _plain(lines[0][len("error: "):]) == _plain(str(e.value))
    assert list(tmp_path.iterdir()) == []
