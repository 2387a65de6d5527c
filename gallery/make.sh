#!/usr/bin/env bash
# Regenerates every figure of the gallery from scratch. Run from the repository root:
#   bash gallery/make.sh
# Uses the GPU kernels when an adapter exists (the figures are identical within the plotted
# resolution either way; set TABOR_BACKEND=cpu to force the f64 path).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
T=./target/release/tabor
G=gallery

$T map --out $G/map.png --svg $G/map.svg --json $G/map.json
$T map --load-axis above-pulloff --out $G/map_tensile.png --svg $G/map_tensile.svg
$T map --quantity a --out $G/map_A.png
$T map --quantity approach --load-axis above-pulloff --out $G/map_approach.png
$T map --quantity err-jkr --out $G/map_err_jkr.png
$T map --quantity err-dmt --out $G/map_err_dmt.png
$T plot pulloff --out $G/pulloff.png --svg $G/pulloff.svg
$T plot curves --lambda 0.1,1,10 --out $G/curves.png --svg $G/curves.svg
$T bench --out-dir $G
$T atlas --out-dir $G/atlas
$T scene --preset afm-si --plot $G/scene_afm.png > $G/scene_afm.txt
$T scene --preset pdms-glass --plot $G/scene_pdms.png > $G/scene_pdms.txt
for l in 0.1 1 10; do
    $T cycle --lambda $l --plot $G/cycle_grips_$l.png -o $G/cycle_grips_$l.csv
done
$T cycle --lambda 1 --control spring --stiffness 0.5 --plot $G/cycle_spring_0.5.png -o $G/cycle_spring_0.5.csv
$T cycle --lambda 1 --control spring --stiffness 5 --plot $G/cycle_spring_5.png -o $G/cycle_spring_5.csv
for l in 0.1 1 10; do
    $T profile --lambda $l --load 0 --plot $G/profile_$l.png -o $G/profile_$l.json
done
