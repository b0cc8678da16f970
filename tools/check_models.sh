#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Designs every model in a models folder (MANIFEST.tsv gives the up axis) at the default options and
# checks each plan: it stands (--strict exit 0); only a model named bad_* (a known defective mesh)
# may instead be reported invalid with the reason (exit 3 and a stop reason in the report). The exact
# construction's own checks hold either way, and `origamic validate` reading the DXF back agrees with
# the design's verdict and finds no face outside the card.
# Prints one line per model: faces, supports, removed faces, verdict, time. Exit 77 without models.
# usage: tools/check_models.sh ORIGAMIC_EXE MODELS_DIR
set -uo pipefail
exe=$1 models=$2
[ -f "$models/MANIFEST.tsv" ] || { echo "no models at $models: skipped"; exit 77; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
up_column=$(head -1 "$models/MANIFEST.tsv" | tr '\t' '\n' | grep -n -x 'up_axis\|up' | cut -d: -f1 | head -1)
for file in "$models"/seedlike/*.stl "$models"/*.obj "$models"/*.stl "$models"/*.off "$models"/*.ply "$models"/*.gz; do
  [ -f "$file" ] || continue
  name=$(basename "$file")
  up=z
  if [ -n "$up_column" ]; then
    up=$(awk -F'\t' -v f="$name" -v c="$up_column" '$1==f{print tolower(substr($c, length($c)))}' "$models/MANIFEST.tsv")
    [ "$up" = y ] || [ "$up" = z ] || up=z
  fi
  start=$(date +%s%N)
  "$exe" design "$file" --up "$up" --strict --out "$out/$name" >"$out/$name.log" 2>&1
  status=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  report=$(ls "$out/$name"/*.json 2>/dev/null | head -1)
  dxf=$(ls "$out/$name"/*.dxf 2>/dev/null | head -1)
  validated=2
  [ -n "$dxf" ] && { "$exe" validate --json "$dxf" >"$out/$name.validate" 2>&1; validated=$?; }
  verdict=$(/usr/bin/python3 - "$report" "$status" "$validated" "$name" "$out/$name.validate" <<'PY'
import json, sys
path, status, validated, name, read_back = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
if not path:
    print("FAIL no report"); sys.exit()
r = json.load(open(path))
p, s = r["plan"], r["supports"]
c, x = p["counts"], p["exact_checks"]
problems = [k for k in ("arrangement_valid", "faces_tile_sheet") if not x[k]]
problems += [k for k in ("lost_faces", "unresolved_crossings") if x[k] != 0]
if status == 0 and c["floating"] + c["dangling"] + c["invalid"] != 0: problems.append("exit 0 but invalid faces")
if status == 3 and not s["stop_reason"]: problems.append("invalid without a reason")
if status == 3 and not name.startswith("bad_"): problems.append("invalid: only a bad_* model may be")
if s["cut_out_share"] > 0.25: problems.append("over a quarter of the model cut out")
try:
    outside = sum(p["kind"] == "outside_card" for p in json.load(open(read_back))["problems"])
except (OSError, ValueError, KeyError):
    outside = 0  # validate refused the file: its exit status says so below
if outside: problems.append(f"{outside} faces outside the card, read back")
if status not in (0, 3): problems.append(f"exit {status}")
elif (status == 0) != (validated == 0): problems.append(f"design exit {status} but validate exit {validated}")
head = f'{c["faces"]} faces, {s["added"]} supports, {c["removed"]} removed ({100 * s["cut_out_share"]:.1f}% of the model)'
if problems: print("FAIL " + head + ": " + ", ".join(problems))
elif status == 0: print("VALID " + head)
else: print(f'INVALID {head}: {c["floating"]} floating, {c["dangling"]} dangling, {c["invalid"]} invalid: {s["stop_reason"]}')
PY
)
  printf '%-30s %6d ms  %s\n' "$name" "$ms" "$verdict"
  case $verdict in FAIL*) failures=$((failures + 1)); tail -3 "$out/$name.log"; head -4 "$out/$name.validate" ;; esac
done
exit $(( failures > 0 ))
