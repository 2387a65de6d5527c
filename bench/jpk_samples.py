"""The JPK force curves of afmformats 0.18.7's sample data, which bench/jpk_curves.py and
bench/nanite_agreement.py fit."""
import logging
import pathlib
import subprocess
import sys
import tarfile
import tempfile

#: The imaging modes fitted (afmformats' "imaging mode").
MODES = ("force-distance", "creep-compliance", "stress-relaxation")


def data_dir(arg):
    """The tests/data folder of afmformats 0.18.7's source distribution (fetched with pip
    without arg)."""
    if arg:
        return pathlib.Path(arg)
    tmp = pathlib.Path(tempfile.mkdtemp())
    subprocess.run([sys.executable, "-m", "pip", "download", "--no-binary", ":all:", "--no-deps",
                    "afmformats==0.18.7", "-d", str(tmp), "-q"], check=True)
    with tarfile.open(next(tmp.glob("afmformats-*.tar.gz"))) as t:
        t.extractall(tmp, members=[m for m in t.getmembers()
                                   if "/tests/data/" in m.name and m.isfile()])
    return next(tmp.rglob("tests/data"))


def curves(folder):
    """(file name, curve) of every JPK curve afmformats reads with an indentation mode (the
    files without a spring constant or sensitivity raise MissingMetaDataError: left out).
    Creep-compliance and stress-relaxation curves are kept."""
    import afmformats
    logging.disable(logging.CRITICAL)
    out = []
    try:
        for p in sorted(pathlib.Path(folder).glob("fmt-jpk-*")):
            try:
                ds = afmformats.load_data(p)
            except (Exception, afmformats.errors.MissingMetaDataError):
                continue
            out += [(p.name, d) for d in ds if d.metadata.get("imaging mode") in MODES]
    finally:
        logging.disable(logging.NOTSET)
    return out
