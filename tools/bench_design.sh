#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Whole-design benchmark: model file to written plan files (`origamic design`, default options), the
# best and the median of N runs (default 5) of each seedlike shape, the dragon and the city block,
# one at a time. Targets (issue 22, on the median): <= 1 s for each seedlike shape, <= 3 s for the
# dragon and the city block.
# Usage: bash tools/bench_design.sh [runs]   (after tools/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
models=../shared/models
[ -x build/origamic ] || { echo "bench_design: build/origamic missing: run tools/build.sh first" >&2; exit 2; }
[ -d "$models" ] || { echo "bench_design: $models not found" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

bench() {  # model, up axis, target in ms
  local model=$1 up=$2 target=$3 times=() t start
  for ((i = 0; i < runs; ++i)); do
    start=$(date +%s%N)
    build/origamic design "$model" --up "$up" --out "$out" >/dev/null
    times+=($(( ($(date +%s%N) - start) / 1000000 )))
  done
  mapfile -t times < <(printf '%s\n' "${times[@]}" | sort -n)
  t=${times[$((runs / 2))]}
  printf '%-28s best %5d ms  median %5d ms  target %5d ms  %s\n' "$(basename "$model")" "${times[0]}" \
    "$t" "$target" "$([ "$t" -le "$target" ] && echo met || echo MISSED)"
}
for model in "$models"/seedlike/*.stl; do bench "$model" z 1000; done
bench "$models/res_dragon_full.ply.gz" y 3000
bench "$models/arch_city_block.obj" z 3000
