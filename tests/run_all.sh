#!/usr/bin/env bash
# Every test: the Rust suite, then the Python package built from this checkout into a virtual
# environment (target/py-venv) and its pytest suite (with nanite for the client test).
# Run from anywhere: bash tests/run_all.sh
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's start, with the seconds spent so far (where a slow run spends its time).
stage() { echo "== $1 (at $SECONDS s)" >&2; }
stage "the Rust tests"
cargo test --release
# The C library for particle codes (libtabor_dem, sharing the compiled tabor above), its tests
# and the C example compiled and run against it; the committed header is the generated one.
stage "the C library"
cargo build --release -p tabor-capi
cargo test --release -p tabor-capi
cargo test --release -p tabor-capi-header
# The library's documentation builds without a warning (broken links included).
stage "the documentation"
# In release mode: it reads the release build's dependencies instead of checking them all again.
RUSTDOCFLAGS="-D warnings" cargo doc --release --no-deps --lib --quiet
# The Python tests compare with the command line: target/release/tabor, built by `cargo test`
# above (a separate `cargo build` would compile tabor again without the tests' features).
stage "the Python package"
venv=${TABOR_VENV:-target/py-venv}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q --upgrade pip
"$venv/bin/python" -m pip install -q pytest nanite afmformats "dask[distributed]>=2024.1" \
    "xarray>=2023.1" "zarr>=2.16" "h5netcdf>=1.1"
"$venv/bin/python" -m pip install -q ./python
stage "the Python tests"
"$venv/bin/python" -m pytest -q python/tests
stage "done"
