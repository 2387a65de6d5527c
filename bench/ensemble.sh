#!/usr/bin/env bash
# The explicit-ensemble benchmark of `tabor rough --asperities`: N summits (heights N(0, 50 nm),
# radii log-normal about 2 um, sd 0.5 in ln R: lambda over a factor ~3) on the PDMS preset, 400
# separations each way. Runs the summit tables (`--summits tables`, on --backend cpu and, where
# an adapter exists, gpu) and the exact root search on the same summits, prints each one's
# summit-states per second as the command reports it, and the largest difference of the forces
# and contact areas between tables and exact (relative to each curve's largest).
#   bash bench/ensemble.sh [N] [points]   (default 100000 400)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-100000}
points=${2:-400}
cargo build --release --quiet --bin tabor
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 - "$n" "$dir/asp.csv" <<'PY'
import math, random, sys
n, path = int(sys.argv[1]), sys.argv[2]
rng = random.Random(1)
with open(path, "w") as f:
    f.write("height_m,radius_m\n")
    for _ in range(n):
        f.write(f"{rng.gauss(0, 50e-9)!r},{2e-6 * math.exp(rng.gauss(0, 0.5))!r}\n")
PY
run() {
    local name=$1
    shift
    ./target/release/tabor rough --preset pdms-rough-glass --asperities "$dir/asp.csv" \
        --points "$points" -o "$dir/$name.json" "$@" 2>"$dir/$name.err" || {
        cat "$dir/$name.err" >&2
        return 1
    }
    echo "$name: $(tail -n 1 "$dir/$name.err")"
}
run tables_cpu --summits tables --backend cpu
if ./target/release/tabor info 2>/dev/null | grep -qi "adapter"; then
    run tables_gpu --summits tables --backend gpu || echo "tables_gpu: no usable adapter"
fi
run exact --summits exact
python3 - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]
exact = json.load(open(os.path.join(d, "exact.json")))
for name in ("tables_cpu", "tables_gpu"):
    p = os.path.join(d, name + ".json")
    if not os.path.exists(p):
        continue
    t = json.load(open(p))
    worst = {}
    for leg in ("approach", "retract"):
        for key in ("force_n", "real_contact_area_m2"):
            a, b = exact[leg][key], t[leg][key]
            top = max(abs(x) for x in a) or 1.0
            worst[key] = max(worst.get(key, 0.0), max(abs(x - y) for x, y in zip(a, b)) / top)
    print(f"{name} against exact: forces within {worst['force_n']:.2e}, contact areas within "
          f"{worst['real_contact_area_m2']:.2e} of the curve's largest; measured table error "
          f"{t['table_error']:.2e}")
PY
