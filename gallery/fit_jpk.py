"""The gallery's real force curve: a JPK sample file from afmformats' source distribution on
PyPI (fmt-jpk-fd_spot3-0192.jpk-force), read with afmformats, written as tabor's CSV and fitted
with `tabor fit` (tip radius 2.5 um assumed; the spring constant is the file's).

    target/py-venv/bin/python gallery/fit_jpk.py      (needs afmformats and network)
"""
import pathlib
import subprocess
import sys
import tarfile
import tempfile

import afmformats

root = pathlib.Path(__file__).resolve().parents[1]
with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-binary", ":all:",
                    "--no-deps", "afmformats==0.18.7", "-d", str(tmp)], check=True)
    name = "fmt-jpk-fd_spot3-0192.jpk-force"
    with tarfile.open(next(tmp.glob("afmformats-*.tar.gz"))) as t:
        t.extractall(tmp, members=[m for m in t.getmembers() if m.name.endswith(name)])
    d = afmformats.load_data(next(tmp.rglob(name)))[0]
    csv = tmp / "spot3.csv"
    with open(csv, "w") as f:
        f.write("segment,height_m,force_n\n")
        for s, h, force in zip(d["segment"], d["height (measured)"], d["force"]):
            f.write(f"{int(s)},{float(h)!r},{float(force)!r}\n")
    k = d.metadata["spring constant"]
    subprocess.run([str(root / "target/release/tabor"), "fit", "-i", str(csv),
                    "--radius", "2.5e-6", "--spring-n-m", repr(float(k)),
                    "--plot", str(root / "gallery/fit_jpk.png"),
                    "-o", str(root / "gallery/fit_jpk.json")], check=True)
