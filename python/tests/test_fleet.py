"""fit_fleet: a fleet of force maps fitted serially and on a two-worker Dask cluster gives one
Dataset, the same both ways and the same as fit_curves / fit_afmformats on each map; it goes to
Zarr and NetCDF and back unchanged; the serial path needs no Dask; a map that cannot be read is
its own status and message, a bad argument one ValueError before any work."""
import functools
import importlib
import importlib.util
import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import tabor

R, K = 20e-9, 40.0
# E* (Pa), w (J/m^2), lambda of the four curves the synthetic maps are made of
TRUTH = [(2e9, 0.04, 0.3), (1e9, 0.05, 1.0), (3e9, 0.03, 3.0), (0.5e9, 0.06, 0.5)]
NOISE_N = 2e-12


def _need(name):
    if os.environ.get("CI"):
        return importlib.import_module(name)  # installed in CI: missing is a failure
    return pytest.importorskip(name)


@functools.lru_cache(maxsize=None)
def _curve(j):
    """A noise-free approach-retract curve under a 40 N/m cantilever (every 6th point of
    tabor.cycle's): heights (m), forces (N), segments."""
    E, w, lam = TRUTH[j]
    unit = (np.pi**2 * w**2 * R / (4 / 3 * E)**2) ** (1 / 3)
    c = tabor.cycle(lam, drive="spring", stiffness=K * unit / (np.pi * w * R))
    keep = slice(None, None, 6)
    return (-c["control"][keep] * unit, c["load"][keep] * np.pi * w * R,
            np.where(c["phase"][keep] == "approach", 0, 1))


def _truth(i, x, y):
    return (i + 2 * y + x) % 4


def _map(i, nx=2, ny=2):
    """Map i: an nx x ny map of the four curves, with 2 pN of noise seeded by i."""
    rng = np.random.default_rng(i)
    h, f, s, xs, ys = [], [], [], [], []
    for y in range(ny):
        for x in range(nx):
            hh, ff, ss = _curve(_truth(i, x, y))
            h.append(hh)
            f.append(ff + rng.normal(0, NOISE_N, len(ff)))
            s.append(ss)
            xs.append(np.full(len(hh), x))
            ys.append(np.full(len(hh), y))
    return {"height_m": np.concatenate(h), "force_n": np.concatenate(f),
            "segment": np.concatenate(s), "x": np.concatenate(xs), "y": np.concatenate(ys)}


@pytest.fixture(scope="module")
def fleet():
    """16 2 x 2 maps and a 3 x 1 one (the others padded to x = 3)."""
    maps = {f"m{i:02d}": _map(i) for i in range(16)}
    maps["wide"] = _map(16, nx=3, ny=1)
    return maps


@pytest.fixture(scope="module")
def client():
    _need("dask")
    distributed = _need("distributed")
    # distributed sets variables in this process's environment (MALLOC_TRIM_THRESHOLD_,
    # OMP_NUM_THREADS, ...) that the later tests' subprocesses would inherit: put them back.
    environ = dict(os.environ)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()
    os.environ.clear()
    os.environ.update(environ)
    cluster.close()


@pytest.fixture(scope="module")
def serial(fleet):
    _need("xarray")
    return tabor.fit_fleet(fleet, radius_m=R, spring_n_m=K, poisson=0.3)


def test_serial_and_dask_fits_are_identical(fleet, serial, client):
    xr = _need("xarray")
    on_dask = tabor.fit_fleet(fleet, radius_m=R, spring_n_m=K, poisson=0.3, client=client)
    xr.testing.assert_identical(serial, on_dask)
    assert dict(serial.sizes) == {"map": 17, "y": 2, "x": 3}
    assert serial["map"].values.tolist() == list(fleet)


def test_values_are_those_of_fit_curves_and_near_the_truth(fleet, serial):
    assert (serial["status"].drop_sel(map="wide").sel(x=[0, 1]).values == "ok").all()
    # The padded pixels: no curve, no numbers.
    assert (serial["status"].sel(x=2).drop_sel(map="wide").values == "no_curve").all()
    assert np.isnan(serial["e_star_pa"].sel(x=2).drop_sel(map="wide").values).all()
    assert (serial["status"].sel(map="wide", y=1).values == "no_curve").all()
    assert serial["nx"].sel(map="wide").item() == 3 and serial["ny"].sel(map="wide").item() == 1
    for name in ("m00", "m05", "wide"):
        m = fleet[name]
        nx = int(m["x"].max()) + 1
        direct = tabor.fit_curves(m["height_m"], m["force_n"], m["segment"],
                                  m["y"] * nx + m["x"], radius_m=R, spring_n_m=K, poisson=0.3)
        assert len(direct) == serial["nx"].sel(map=name).item() * serial["ny"].sel(map=name).item()
        i = int(np.flatnonzero(serial["map"].values == name)[0])
        for r in direct:
            y, x = divmod(int(r["curve"]), nx)
            px = serial.isel(map=i, y=y, x=x)
            assert px["status"].item() == r["status"] == "ok"
            for k in ("e_star_pa", "youngs_modulus_pa", "work_of_adhesion_j_m2", "lambda",
                      "z0_m", "rms_residual_n", "e_star_pa_stderr", "lambda_stderr"):
                assert px[k].item() == r[k], (name, k)
            for k in ("e_star_pa", "work_of_adhesion_j_m2", "lambda", "z0_m"):
                for level in ("68", "95"):  # an open end NaN
                    ends = [np.nan if e is None else e for e in r[f"{k}_interval_{level}"]]
                    np.testing.assert_equal([px[f"{k}_lo{level}"].item(),
                                             px[f"{k}_hi{level}"].item()], ends)
            assert px["adequate_model"].item() == (r["adequate_model"] or "")
            assert px["lambda_determined"].item() == bool(r["lambda_determined"])
            assert px["points_fitted"].item() == r["points_fitted"]
            E, w, lam = TRUTH[_truth(int(name[1:]) if name != "wide" else 16, x, y)]
            assert px["e_star_pa"].item() == pytest.approx(E, rel=0.03)
            assert px["work_of_adhesion_j_m2"].item() == pytest.approx(w, rel=0.03)
    assert serial["spring_n_m"].values.tolist() == [K] * 17
    assert (serial["message"].values == "").all() and (serial["source"].values == "").all()
    assert serial["e_star_pa"].attrs["units"] == "Pa"
    assert serial.attrs["radius_m"] == R and serial.attrs["tabor_version"] == tabor.__version__
    assert '"poisson": 0.3' in serial.attrs["options"]


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_zarr_and_netcdf_round_trips_are_identical(serial, tmp_path):
    xr = _need("xarray")
    _need("zarr")
    serial.to_zarr(tmp_path / "fleet.zarr")
    with xr.open_zarr(tmp_path / "fleet.zarr") as back:
        xr.testing.assert_identical(serial, back.load())
    if not any(importlib.util.find_spec(m) for m in ("netCDF4", "h5netcdf")):
        _need("h5netcdf")
    serial.to_netcdf(tmp_path / "fleet.nc")
    with xr.open_dataset(tmp_path / "fleet.nc") as back:
        xr.testing.assert_identical(serial, back.load())


@pytest.mark.filterwarnings("error::UserWarning")
def test_a_store_is_written_map_by_map_and_reads_back_as_the_dataset(fleet, serial, client,
                                                                       tmp_path):
    """store=: the maps written to Zarr one by one as they are fitted, serially and on Dask,
    read back identical to the Dataset held in memory; a map that cannot be read is padded as
    there; nothing is left beside the store, and an existing store is never overwritten."""
    xr = _need("xarray")
    _need("zarr")
    for name, c in (("serial.zarr", None), ("dask.zarr", client)):
        ds = tabor.fit_fleet(fleet, radius_m=R, spring_n_m=K, poisson=0.3, client=c,
                             store=tmp_path / name)
        xr.testing.assert_identical(serial, ds.load())
    maps = {"lost": "no/such/map.jpk-force-map", "good": fleet["wide"]}
    ds = tabor.fit_fleet(maps, radius_m=R, spring_n_m=K, store=str(tmp_path / "lost.zarr"))
    xr.testing.assert_identical(tabor.fit_fleet(maps, radius_m=R, spring_n_m=K), ds.load())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dask.zarr", "lost.zarr",
                                                          "serial.zarr"]
    before = sorted(str(p) for p in (tmp_path / "lost.zarr").rglob("*"))
    with pytest.raises(FileExistsError, match="exists already"):
        tabor.fit_fleet(maps, radius_m=R, spring_n_m=K, store=tmp_path / "lost.zarr")
    assert sorted(str(p) for p in (tmp_path / "lost.zarr").rglob("*")) == before


def test_the_serial_path_needs_no_dask(fleet, tmp_path):
    """In a fresh interpreter where Dask cannot be imported (xarray itself imports dask.array
    when it is installed), the serial fit runs; and where it can, the serial path loads no
    dask.distributed."""
    _need("xarray")
    np.savez(tmp_path / "m.npz", **fleet["m00"])
    code = textwrap.dedent(f"""
        import sys
        if sys.argv[1] == "blocked":
            for m in ("dask", "distributed"):
                sys.modules[m] = None  # any import of them fails
        import numpy as np, tabor
        m = dict(np.load({str(tmp_path / "m.npz")!r}))
        ds = tabor.fit_fleet([m], radius_m={R!r}, spring_n_m={K!r})
        assert (ds["status"].values == "ok").all()
        print(sorted(k for k in sys.modules
                     if k.split(".")[0] == "distributed" and sys.modules[k] is not None))
    """)
    for mode in ("blocked", "installed"):
        r = subprocess.run([sys.executable, "-c", code, mode], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() == "[]", (mode, r.stdout)


def test_a_missing_file_is_its_maps_status_and_bad_arguments_raise(fleet, client):
    xr = _need("xarray")
    _need("afmformats")
    maps = {"good": fleet["m01"], "lost": "no/such/map.jpk-force-map"}
    ds = tabor.fit_fleet(maps, radius_m=R, spring_n_m=K)
    xr.testing.assert_identical(ds, tabor.fit_fleet(maps, radius_m=R, spring_n_m=K,
                                                    client=client))
    assert (ds["status"].sel(map="good").values == "ok").all()
    assert (ds["status"].sel(map="lost").values == "invalid_input").all()
    assert "no such file" in ds["message"].sel(map="lost").item()
    assert ds["source"].sel(map="lost").item() == "no/such/map.jpk-force-map"
    assert ds["message"].sel(map="good").item() == ""
    with pytest.raises(ValueError, match="radius_m"):
        tabor.fit_fleet(maps, radius_m=-1.0, spring_n_m=K, client=client)
    with pytest.raises(ValueError, match="'poison'"):
        tabor.fit_fleet(maps, radius_m=R, spring_n_m=K, poison=0.3)
    with pytest.raises(ValueError, match="spring_n_m"):
        tabor.fit_fleet([fleet["m01"]], radius_m=R)
    with pytest.raises(ValueError, match="missing"):
        tabor.fit_fleet([{"height_m": [], "force_n": []}], radius_m=R, spring_n_m=K)


@pytest.fixture(scope="module")
def samples(afmformats_data, tmp_path_factory):
    """Two force maps of afmformats 0.18.7's source distribution (conftest.py), in a folder with a
    file afmformats does not read."""
    folder = tmp_path_factory.mktemp("maps")
    for n in ["fmt-jpk-fd_map2x2_extracted.jpk-force-map",
              "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"]:
        shutil.copy(afmformats_data / n, folder / n)
    (folder / "notes.txt").write_text("not a force map\n")
    return folder


def test_real_force_maps_fit_the_same_both_ways(samples, client):
    xr = _need("xarray")
    import afmformats

    ds = tabor.fit_fleet(samples, radius_m=2.5e-6)
    xr.testing.assert_identical(ds, tabor.fit_fleet(str(samples), radius_m=2.5e-6,
                                                    client=client))
    assert ds["map"].values.tolist() == ["fmt-jpk-fd_2020.02.07-16.29.05.036",
                                         "fmt-jpk-fd_map2x2_extracted"]
    # The instruments' grids: 128 x 128 and 10 x 10, the curves at their grid positions.
    assert dict(ds.sizes) == {"map": 2, "y": 128, "x": 128}
    assert ds["nx"].values.tolist() == [128, 10] and ds["ny"].values.tolist() == [128, 10]
    for i, path in enumerate(ds["source"].values):
        data = afmformats.load_data(path)
        fits = tabor.fit_afmformats(data, radius_m=2.5e-6)
        assert ds["spring_n_m"].values[i] == data[0].metadata["spring constant"]
        assert (ds["status"].values[i] != "no_curve").sum() == len(fits)
        for d, r in zip(data, fits):
            px = ds.isel(map=i, x=d.metadata["grid index x"], y=d.metadata["grid index y"])
            assert px["status"].item() == r["status"] == "ok"
            assert px["enum"].item() == r["enum"]
            assert px["e_star_pa"].item() == r["e_star_pa"]
            assert px["work_of_adhesion_j_m2"].item() == r["work_of_adhesion_j_m2"]
