"""The gallery's real force curves, from afmformats' source distribution on PyPI, read with
afmformats, written as tabor's CSV and fitted with `tabor fit` (tip radius 2.5 um assumed; the
spring constant is the file's):
- fit_jpk: a JPK force curve (fmt-jpk-fd_spot3-0192.jpk-force);
- fit_creep: a JPK creep-compliance curve, whose dwell at constant force is left out;
- fit_igor: an Asylum/Igor curve kept in one segment, split where the base turns.
Approach and retract come from the heights as `tabor.fit_afmformats` takes them
(`tabor::fit::segments`).

    target/py-venv/bin/python gallery/fit_jpk.py      (needs afmformats, tabor and network)
"""
import logging
import pathlib
import subprocess
import sys
import tarfile
import tempfile

import afmformats
import numpy as np

from tabor import _tabor

root = pathlib.Path(__file__).resolve().parents[1]
files = {
    "fit_jpk": "fmt-jpk-fd_spot3-0192.jpk-force",
    "fit_creep": "fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force",
    "fit_igor": "fmt-igor-fd_SiN_FD_plot.ibw",
}
logging.disable(logging.CRITICAL)
with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-binary", ":all:",
                    "--no-deps", "afmformats==0.18.7", "-d", str(tmp)], check=True)
    with tarfile.open(next(tmp.glob("afmformats-*.tar.gz"))) as t:
        t.extractall(tmp, members=[m for m in t.getmembers()
                                   if m.name.split("/")[-1] in files.values()])
    for out, name in files.items():
        d = afmformats.load_data(next(tmp.rglob(name)))[0]
        h = np.asarray(d["height (measured)"], dtype=float)
        code, notes = _tabor.plan_segments(h, np.asarray(d["segment"], dtype=np.int64))
        for n in notes:
            print(f"{name}: {n}")
        csv = tmp / f"{out}.csv"
        with open(csv, "w") as f:
            f.write("segment,height_m,force_n\n")
            for c, hh, force in zip(code, h, d["force"]):
                if c >= 0:
                    f.write(f"{c},{float(hh)!r},{float(force)!r}\n")
        k = d.metadata["spring constant"]
        subprocess.run([str(root / "target/release/tabor"), "fit", "-i", str(csv),
                        "--radius", "2.5e-6", "--spring-n-m", repr(float(k)),
                        "--plot", str(root / f"gallery/{out}.png"),
                        "-o", str(root / f"gallery/{out}.json")], check=True)
