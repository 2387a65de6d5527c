#!/usr/bin/env bash
# Installs the public Python reference (`adhesion`) in a virtual environment and compares it
# with tabor on the 300 reference states. Not part of CI. Run from the repository root.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${VENV:-target/adhesion-venv}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q adhesion scipy numpy
cargo build --release --quiet
"$venv/bin/python" bench/python_reference.py data/points.csv target/release/tabor
