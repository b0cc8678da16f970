#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Designs every model of a models folder at the default options and checks each plan.

MANIFEST.tsv gives each model's up axis. A plan must stand (design --strict --allow-narrow exits 0;
its places narrower than W are counted on its line, and judged by tools/bench_likeness); only a model
named bad_* (a known defective mesh) may instead be reported invalid with the reason (exit 3 and a
stop reason in the report). Either way the exact construction's own checks hold, and `origamic
validate` reading the DXF back agrees with the design's verdict and finds no face outside the card.
Prints a line per model: faces, supports, removed faces, verdict, time. Exits 1 if any model
fails, 77 without models.

  tools/check_models.py ORIGAMIC_EXE MODELS_DIR
  tools/check_models.py --self-test      # the verdict's rules on made-up reports
"""
import csv
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def verdict(report, status, validated, name, read_back):
    """('VALID' | 'INVALID' | 'FAIL', line) for one model: its design's JSON report and exit status,
    and validate's exit status and JSON (None where validate refused the file)."""
    plan, supports = report["plan"], report["supports"]
    counts, checks = plan["counts"], plan["exact_checks"]
    problems = [k for k in ("arrangement_valid", "faces_tile_sheet") if not checks[k]]
    problems += [k for k in ("lost_faces", "unresolved_crossings") if checks[k] != 0]
    if status == 0 and counts["floating"] + counts["dangling"] + counts["invalid"] != 0:
        problems.append("exit 0 but invalid faces")
    if status == 3 and not supports["stop_reason"]:
        problems.append("invalid without a reason")
    if status == 3 and not name.startswith("bad_"):
        problems.append("invalid: only a bad_* model may be")
    if supports["cut_out_share"] > 0.25:
        problems.append("over a quarter of the model cut out")
    outside = sum(p["kind"] == "outside_card" for p in read_back["problems"]) if read_back else 0
    if outside:
        problems.append(f"{outside} faces outside the card, read back")
    if status not in (0, 3):
        problems.append(f"exit {status}")
    elif (status == 0) != (validated == 0):
        problems.append(f"design exit {status} but validate exit {validated}")
    head = (f'{counts["faces"]} faces, {supports["added"]} supports, {counts["removed"]} removed '
            f'({100 * supports["cut_out_share"]:.1f}% of the model), {plan["narrow_strip_count"]} narrow places')
    if problems:
        return "FAIL", f"{head}: " + ", ".join(problems)
    if status == 0:
        return "VALID", head
    return "INVALID", (f'{head}: {counts["floating"]} floating, {counts["dangling"]} dangling, '
                       f'{counts["invalid"]} invalid: {supports["stop_reason"]}')


def up_axes(models):
    """Each model's up axis, y or z, from MANIFEST.tsv (z where it says neither)."""
    with open(models / "MANIFEST.tsv", newline="") as manifest:
        rows = list(csv.DictReader(manifest, delimiter="\t"))
    column = next((c for c in ("up_axis", "up") if rows and c in rows[0]), None)
    axes = {}
    for row in rows:
        axis = (row.get(column) or "").strip().lower()[-1:] if column else ""
        axes[row["file"]] = axis if axis in ("y", "z") else "z"
    return axes


def check(exe, models):
    axes = up_axes(models)
    files = [f for pattern in ("seedlike/*.stl", "*.obj", "*.stl", "*.off", "*.ply", "*.gz")
             for f in sorted(models.glob(pattern))]
    failures = 0
    with tempfile.TemporaryDirectory() as out:
        out = Path(out)
        for file in files:
            name = file.name
            start = time.monotonic()
            design = subprocess.run([str(exe), "design", str(file), "--up", axes.get(name, "z"), "--strict",
                                     "--allow-narrow", "--out", str(out / name)], capture_output=True, text=True)
            ms = (time.monotonic() - start) * 1000
            reports, dxfs = sorted((out / name).glob("*.json")), sorted((out / name).glob("*.dxf"))
            validated, read_back, validate_output = 2, None, ""
            if dxfs:
                validate = subprocess.run([str(exe), "validate", "--json", str(dxfs[0])], capture_output=True, text=True)
                validated, validate_output = validate.returncode, validate.stdout + validate.stderr
                try:
                    read_back = json.loads(validate.stdout)
                except ValueError:
                    read_back = None  # validate refused the file: its exit status says so
            if not reports:
                kind, line = "FAIL", "no report"
            else:
                kind, line = verdict(json.loads(reports[0].read_text()), design.returncode, validated, name, read_back)
            print(f"{name:<30} {ms:6.0f} ms  {kind} {line}", flush=True)
            if kind == "FAIL":
                failures += 1
                print("\n".join((design.stdout + design.stderr).splitlines()[-3:]))
                print("\n".join(validate_output.splitlines()[:4]))
    return 1 if failures else 0


def self_test():
    """The rules on made-up reports: each must hold for the verdict it names."""
    def report(**changes):
        r = {"plan": {"narrow_strip_count": 0,
                      "counts": {"faces": 4, "removed": 0, "floating": 0, "dangling": 0, "invalid": 0},
                      "exact_checks": {"arrangement_valid": True, "faces_tile_sheet": True, "lost_faces": 0,
                                       "unresolved_crossings": 0}},
             "supports": {"added": 2, "cut_out_share": 0.0, "stop_reason": ""}}
        for path, value in changes.items():
            part, key = path.split("__")
            (r["plan"]["counts"] if part == "counts" else r["plan"]["exact_checks"] if part == "checks"
             else r["plan"] if part == "plan" else r["supports"])[key] = value
        return r
    clean = {"problems": []}
    cases = [
        (report(), 0, 0, "box.obj", clean, "VALID", "4 faces, 2 supports"),
        (report(plan__narrow_strip_count=5), 0, 0, "box.obj", clean, "VALID", "5 narrow places"),
        (report(counts__dangling=1), 0, 0, "box.obj", clean, "FAIL", "exit 0 but invalid faces"),
        (report(counts__invalid=1, supports__stop_reason="1 faces invalid"), 3, 3, "bad_x.obj", clean, "INVALID",
         "1 faces invalid"),
        (report(counts__invalid=1), 3, 3, "bad_x.obj", clean, "FAIL", "invalid without a reason"),
        (report(counts__invalid=1, supports__stop_reason="why"), 3, 3, "box.obj", clean, "FAIL",
         "only a bad_* model"),
        (report(checks__lost_faces=2), 0, 0, "box.obj", clean, "FAIL", "lost_faces"),
        (report(checks__faces_tile_sheet=False), 0, 0, "box.obj", clean, "FAIL", "faces_tile_sheet"),
        (report(supports__cut_out_share=0.3), 0, 0, "box.obj", clean, "FAIL", "over a quarter"),
        (report(), 0, 3, "box.obj", {"problems": [{"kind": "outside_card"}]}, "FAIL",
         "1 faces outside the card"),
        (report(), 0, 3, "box.obj", clean, "FAIL", "design exit 0 but validate exit 3"),
        (report(), 2, 2, "box.obj", None, "FAIL", "exit 2"),
    ]
    wrong = 0
    for r, status, validated, name, read_back, kind, words in cases:
        got_kind, line = verdict(r, status, validated, name, read_back)
        if got_kind != kind or words not in line:
            wrong += 1
            print(f"self-test: expected {kind} with '{words}', got {got_kind}: {line}")
    print(f"{len(cases) - wrong} passed, {wrong} failed")
    return 1 if wrong else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    exe, models = Path(sys.argv[1]), Path(sys.argv[2])
    if not (models / "MANIFEST.tsv").is_file():
        print(f"no models at {models}: skipped")
        return 77
    return check(exe, models)


if __name__ == "__main__":
    sys.exit(main())
