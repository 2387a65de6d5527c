#!/usr/bin/env bash
# Regenerates every figure of the gallery from scratch. Run from the repository root:
#   bash gallery/make.sh
# Uses the GPU kernels when an adapter exists (the figures are identical within the plotted
# resolution either way; set TABOR_BACKEND=cpu to force the f64 path).
# Figures are one journal column wide (85 mm, PNG at 300 dpi) unless named *_double (175 mm).
# The speed chart is redrawn from the recorded gallery/bench.json (the run the README quotes);
# BENCH=measure runs the benchmark again.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
T=./target/release/tabor
G=gallery

$T map --out $G/map.png --svg $G/map.svg --pdf $G/map.pdf --json $G/map.json
$T map --double-column --out $G/map_double.png --pdf $G/map_double.pdf
$T map --load-axis above-pulloff --out $G/map_tensile.png --svg $G/map_tensile.svg
$T map --quantity a --out $G/map_A.png
$T map --quantity approach --load-axis above-pulloff --out $G/map_approach.png
$T map --quantity err-jkr --out $G/map_err_jkr.png
$T map --quantity err-dmt --out $G/map_err_dmt.png
# Tips: the cone's map (every half-angle) and a capped cone's, beside the sphere's map.png.
$T map --tip cone --nx 192 --ny 144 --out $G/map_cone.png --svg $G/map_cone.svg
$T map --tip capped-cone:1:20 --nx 96 --ny 72 --out $G/map_capped_cone.png
$T plot pulloff --out $G/pulloff.png --svg $G/pulloff.svg --pdf $G/pulloff.pdf
$T plot curves --lambda 0.1,1,10 --out $G/curves.png --svg $G/curves.svg
if [ "${BENCH:-replot}" = measure ]; then
    $T bench --out-dir $G
else
    $T bench --replot $G/bench.json --out-dir $G
fi
# The same chart of a run on an NVIDIA H200 system (16 CPU threads), redrawn from its record.
$T bench --replot $G/h200/bench.json --out-dir $G/h200
$T atlas --out-dir $G/atlas
$T scene --preset afm-si --plot $G/scene_afm.png > $G/scene_afm.txt
$T scene --preset afm-si --double-column --plot $G/scene_afm_double.png > /dev/null
$T scene --preset pdms-glass --plot $G/scene_pdms.png > $G/scene_pdms.txt
$T scene examples/si_tip_40rh.json > $G/scene_afm_40rh.txt
$T humidity --scene examples/si_tip_40rh.json --points 31 --plot $G/humidity_afm.png > $G/humidity_afm.txt
$T humidity --preset pdms-glass --contact-angle-deg 30 --points 31 --plot $G/humidity_pdms.png > $G/humidity_pdms.txt
for l in 0.1 1 10; do
    $T cycle --lambda $l --plot $G/cycle_grips_$l.png -o $G/cycle_grips_$l.csv
done
$T cycle --lambda 1 --control spring --stiffness 0.5 --plot $G/cycle_spring_0.5.png -o $G/cycle_spring_0.5.csv
$T cycle --lambda 1 --control spring --stiffness 5 --plot $G/cycle_spring_5.png -o $G/cycle_spring_5.csv
for l in 0.1 1 10; do
    $T profile --lambda $l --load 0 --plot $G/profile_$l.png -o $G/profile_$l.json
done
# A synthetic AFM curve (exact Maugis-Dugdale under a 40 N/m cantilever, 20 pN noise) and its fit.
cargo run --release --quiet --example synthetic_curves -- $G/fit_curve.csv 1 500 40 2e-11
$T fit -i $G/fit_curve.csv --radius 20e-9 --spring-n-m 40 --plot $G/fit.png -o $G/fit.json
# A curve made on a 65-degree cone (1% noise) fitted with the cone: its closed forms are Sneddon's
# punch and the JKR-type law (docs/guide/fitting.md, "Tips that are not spheres").
$T fit -i tests/data/cone_curve.csv --tip cone:65 --spring-n-m 0.5 --plot $G/fit_cone.png -o $G/fit_cone.json
# A measured curve (JPK sample file from afmformats' sdist on PyPI; needs the test venv).
if [ -x target/py-venv/bin/python ]; then
    target/py-venv/bin/python gallery/fit_jpk.py
fi
# An 8 x 8 synthetic force map: its maps and its curves on the adhesion map.
mkdir -p $G/fitmap
curves=$(mktemp --suffix .csv)
cargo run --release --quiet --example synthetic_curves -- "$curves" 64 500 40 2e-11
$T fit -i "$curves" --radius 20e-9 --spring-n-m 40 --format csv -o $G/fitmap/fits.csv \
    --maps $G/fitmap/map --on-map $G/fit_on_map.png
rm -f "$curves"
# Rough surfaces: an approach-retract cycle of Maugis-Dugdale summits below and above lambda_D,
# and the pull-off against roughness (Fuller and Tabor's figure).
$T rough --lambda 0.2 --sigma 0.3 --min-separation -1 --plot $G/rough_cycle_0.2.png -o $G/rough_cycle_0.2.json
$T rough --lambda 2 --sigma 0.5 --min-separation -1 --plot $G/rough_cycle_2.png -o $G/rough_cycle_2.json
$T rough-pulloff --plot $G/rough_pulloff.png -o $G/rough_pulloff.json
# A meniscus on every summit (rho = 0.2, eta = 5; sigma 1 in the solid's approach unit, pressed 3 sigma).
$T rough --lambda 1 --sigma 0.6299605249474366 --min-separation -1.8898815748423097 --stress-ratio 0.2 --range-ratio 5 --plot $G/rough_cycle_wet.png -o $G/rough_cycle_wet.json
# The rough adhesion map: pull-off relative to the smooth summit's, and the adequate summit model.
$T rough-map --out $G/rough_map.png --json $G/rough_map.json
