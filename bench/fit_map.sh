#!/usr/bin/env bash
# The force-map benchmark of `tabor fit`: a 64 x 64 map of synthetic 1000-point curves (exact
# Maugis-Dugdale under a 40 N/m cantilever, 20 pN noise, lambda 0.3..9.5 across the map), fitted
# on all cores with --maps. Prints the wall time, curves per second and the CPU seconds (the
# figure to compare on a loaded machine). Further binaries (an older build copied aside) are
# timed on the same map after this tree's, with their answers compared.
#   bash bench/fit_map.sh [side] [other tabor binary...]   (default side 64)
set -euo pipefail
cd "$(dirname "$0")/.."
side=${1:-64}
shift || true
cargo build --release --quiet --bin tabor --example synthetic_curves
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
./target/release/examples/synthetic_curves "$dir/map.csv" $((side * side)) 500 40 2e-11
n=0
for bin in ./target/release/tabor "$@"; do
    start=$(date +%s.%N)
    # /usr/bin/time writes the user CPU seconds as the last line of the run's stderr.
    /usr/bin/time -f %U "$bin" fit -i "$dir/map.csv" --radius 20e-9 --spring-n-m 40 \
        --format csv -o "$dir/fit$n.csv" --maps "$dir/fm$n" >/dev/null 2>"$dir/err$n" || true
    end=$(date +%s.%N)
    if [ ! -s "$dir/fit$n.csv" ]; then
        echo "$bin failed:" >&2
        cat "$dir/err$n" >&2
        exit 1
    fi
    cpu=$(tail -n 1 "$dir/err$n")
    python3 - "$start" "$end" "$side" "$dir/fit$n.csv" "$cpu" "$bin" "$dir/fit0.csv" <<'PY'
import csv, sys
start, end, side, path = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
cpu, binary, first = sys.argv[5], sys.argv[6], sys.argv[7]
rows = list(csv.DictReader(open(path)))
ok = sum(r["status"] == "ok" for r in rows)
t = end - start
try:
    cpu_s = f"{float(cpu):.1f} CPU s ({len(rows) / float(cpu):.1f} curves per CPU s)"
except ValueError:
    cpu_s = "CPU time not measured"
print(f"{binary}: {side} x {side} force map, 1000 points a curve: {t:.1f} s wall, "
      f"{len(rows) / t:.1f} curves/s, {cpu_s}, {ok} of {len(rows)} fitted")
if path != first:
    same = sum(a == b for a, b in zip(rows, csv.DictReader(open(first))))
    print(f"  answers identical to this tree's in {same} of {len(rows)} curves")
PY
    n=$((n + 1))
done
