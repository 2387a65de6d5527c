"""Every script in examples/python/ runs and prints what it should: each in a scratch folder
(cwd), with this interpreter, so that the examples keep working as the package changes."""
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "python"

# What each script must print (lines or fragments of its output), checked in order of appearance.
EXPECTED = {
    "maps.py": [
        "regions: hertz 19.6%, rigid 13.6%, dmt 10.6%, jkr 41.4%, md 14.9%",
        "pull-off from -1.9999 at lambda 0.001 to -1.5000 at 1000",
        "wrote map.png and map_*.npy",
    ],
    "states.py": [
        "status: [['ok', 'ok', 'ok'], ['no_contact', 'ok', 'ok'], ['no_contact', 'ok', 'ok']]",
        "approach 1.41481 -> load 0.500000",
        "lambda  1.0: Pbar_c = -1.600735 (load control), -0.891741 (displacement control)",
        "lambda_D = 0.937947",
        "two zones: load-controlled pull-off -1.617368",
    ],
    "scene_humidity.py": [
        "pull-off -12.2073 nN (load control)",
        "w (exact MD) = 1.0000e-01 J/m^2, lambda = 0.1114",
        "solid w with the meniscus taken out: 1.0000e-01 J/m^2; a dry reading: 2.4405e-01 J/m^2",
        "RH 0.40: pull-off -28.8155 nN",
    ],
    "fit.py": [
        "status ok, adequate model md",
        "e_star_pa = 2.0001e+09 Pa (95%: 1.9991e+09..2.0012e+09)",
        "lambda = 0.2999, determined: True",
        "pixel 0: lambda 0.3000",
        "pixel 2: lambda 3.0000",
        "cone: E* = 9.974e+05 Pa (95%: 9.789e+05..1.015e+06), adequate model jkr",
    ],
    "rough.py": [
        "pull-off -1.2081 per summit (a smooth summit: -1.5346)",
        "with a meniscus: pull-off -1.24299 per summit (total-w units), -2.48597 in pi w1 R",
        "pull-off -20.91 uN, 4000 summits",
        "polysilicon-like scene: pull-off -0.25 nN",
        "rough map regions:",
    ],
}


def test_every_example_is_checked():
    assert sorted(p.name for p in EXAMPLES.glob("*.py")) == sorted(EXPECTED)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_example_runs(name, tmp_path):
    run = subprocess.run([sys.executable, str(EXAMPLES / name)], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    out = run.stdout
    at = 0
    for fragment in EXPECTED[name]:
        i = out.find(fragment, at)
        assert i >= 0, f"{name}: {fragment!r} not printed (after position {at}):\n{out}"
        at = i + len(fragment)
    if name == "maps.py":
        assert (tmp_path / "map.png").stat().st_size > 0
        assert (tmp_path / "map_region.npy").exists()
