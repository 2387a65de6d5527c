"""Fixtures shared by the test files."""
import os
import subprocess
import sys
import tarfile

import pytest


@pytest.fixture(scope="session")
def afmformats_data(tmp_path_factory):
    """The tests/data folder of afmformats 0.18.7's source distribution on PyPI, fetched once for
    the session. afmformats missing or the download failing: a failure under CI (which
    installs it and is online), a skip elsewhere."""
    if os.environ.get("CI"):
        import afmformats  # noqa: F401 (installed by tests/run_all.sh: a failure, not a skip)
    else:
        pytest.importorskip("afmformats")
    tmp = tmp_path_factory.mktemp("afmformats")
    dl = subprocess.run([sys.executable, "-m", "pip", "download", "--no-binary", ":all:",
                         "--no-deps", "afmformats==0.18.7", "-d", str(tmp), "-q"],
                        capture_output=True, text=True)
    if dl.returncode != 0:
        if os.environ.get("CI"):
            pytest.fail(f"cannot fetch the afmformats sdist: {dl.stderr}")
        pytest.skip(f"cannot fetch the afmformats sdist (offline?): {dl.stderr.strip()[:200]}")
    with tarfile.open(next(tmp.glob("afmformats-*.tar.gz"))) as t:
        t.extractall(tmp, members=[m for m in t.getmembers()
                                   if "/tests/data/" in m.name and m.isfile()])
    return next(tmp.rglob("tests/data"))
