"""One check, in the library, for both front ends: the same bad value is refused by the command
line (exit 1, one line) and by Python (ValueError) in the same words, up to the names of the
command-line flags."""

import re
import subprocess

import pytest

import tabor
from test_tabor import tabor_bin

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
]


def _plain(msg):
    """A message with its command-line flags written as names: `--nx` -> `nx`."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), msg).strip()


@pytest.mark.parametrize("args, call, what", CASES, ids=[c[2] for c in CASES])
def test_the_same_bad_value_gets_the_same_refusal(args, call, what, tmp_path):
    cli = subprocess.run([tabor_bin(), *args], capture_output=True, text=True, cwd=tmp_path,
                         env={"TABOR_BACKEND": "cpu", "PATH": "/usr/bin:/bin"}, timeout=120)
    assert cli.returncode == 1, cli.stderr
    lines = cli.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), cli.stderr
    with pytest.raises(ValueError) as e:
        call()
    assert what in str(e.value)
    assert _plain(lines[0][len("error: "):]) == _plain(str(e.value))
    assert list(tmp_path.iterdir()) == []
