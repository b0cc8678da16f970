#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs the stage benchmark on the named real models (../shared/models) and one of the project's own.
# Peak memory is measured in a separate process per model (the whole design for it: load, BVH, raster).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
models=../shared/models
run() { echo "== $1"; build/tools/bench_stages "$@"; /usr/bin/time -f "design peak_rss_MB %M KB" build/origamic design "$1" ${2:+$2} ${3:+$3} >/dev/null; }
run fixtures/house.obj
[ -d "$models" ] || { echo "bench: $models not found; only the project's own model was run"; exit 0; }
run "$models/seedlike/capitol.stl" --up z
run "$models/res_bunny.obj"
run "$models/res_dragon_full.ply.gz"
