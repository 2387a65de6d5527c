#!/usr/bin/env bash
# The force-map benchmark of `tabor fit`: a 64 x 64 map of synthetic 1000-point curves (exact
# Maugis-Dugdale under a 40 N/m cantilever, 20 pN noise, lambda 0.3..9.5 across the map), fitted
# on all cores with --maps. Prints the wall time and curves per second.
#   bash bench/fit_map.sh [side]   (default 64)
set -euo pipefail
cd "$(dirname "$0")/.."
side=${1:-64}
cargo build --release --quiet --bin tabor --example synthetic_curves
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
./target/release/examples/synthetic_curves "$dir/map.csv" $((side * side)) 500 40 2e-11
start=$(date +%s.%N)
./target/release/tabor fit -i "$dir/map.csv" --radius 20e-9 --spring-n-m 40 --format csv \
    -o "$dir/fit.csv" --maps "$dir/fm"
end=$(date +%s.%N)
python3 - "$start" "$end" "$side" "$dir/fit.csv" <<'PY'
import csv, sys
start, end, side, path = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
rows = list(csv.DictReader(open(path)))
ok = sum(r["status"] == "ok" for r in rows)
t = end - start
print(f"{side} x {side} force map, 1000 points a curve: {t:.1f} s wall, "
      f"{len(rows) / t:.1f} curves/s, {ok} of {len(rows)} fitted")
PY
