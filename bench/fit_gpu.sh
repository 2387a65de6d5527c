#!/usr/bin/env bash
# One evaluation round of the force-map benchmark's curves (bench/fit_map.sh's map at its true
# parameters), every retract point's state on its path: on the CPU's cores, and batched on a GPU
# with f64 shaders (the host follows the paths and brackets the points; shaders/fit_states.wgsl
# takes the Newton steps). Prints each stage's time, the GPU's agreement with the CPU, and the
# ratio of the two rounds. TABOR_GPU_TRACE=1 splits the GPU's time into upload, compute and
# read-back.
#   bash bench/fit_gpu.sh [side: 64] [repeats: 5] [adapter name]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --example fit_states_gpu
./target/release/examples/fit_states_gpu "$@"
