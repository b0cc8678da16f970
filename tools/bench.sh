#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Stage benchmark. First every stage and the peak memory of a whole design for the project's own
# model and three real ones; then segmentation and slicing for every model in ../shared/models
# (their target is <= 150 ms together on the default sheet).
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

# The MANIFEST names each real model's up axis; the seedlike shapes are Z-up.
up_of() {
  local up
  up=$(awk -F'\t' -v f="$(basename "$1")" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "up_axis") c = i; next }
                                             $1 == f { print tolower($c) }' "$models/MANIFEST.tsv")
  [[ "$up" == y* ]] && echo y || echo z
}
echo "== segment + slice, every model (ms)"
for model in "$models"/seedlike/*.stl "$models"/*.{obj,stl,off,ply,gz}; do
  [ -f "$model" ] || continue
  build/tools/bench_stages "$model" --up "$(up_of "$model")" --benchmark_filter='segment|slice' \
    --benchmark_format=json 2>/dev/null | sed '/^peak_rss/d' |
    /usr/bin/python3 -c 'import json, sys
t = {b["name"].split("/")[0]: b for b in json.load(sys.stdin)["benchmarks"]}
print("%-28s segment %6.1f  slice %6.1f  total %6.1f ms  (%d segments, %d faces)" % (sys.argv[1],
      t["segment"]["real_time"], t["slice"]["real_time"], t["segment"]["real_time"] + t["slice"]["real_time"],
      t["segment"]["segments"], t["slice"]["faces"]))' "$(basename "$model")"
done
